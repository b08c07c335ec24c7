"""Inputs a hostile or careless user gives the review and the readers (issue 26): units stated twice
and differently, review parameters outside their range, target files that are not tables.

Each is refused with one typed error naming the file or the parameter and the reason, at once.
"""

from __future__ import annotations

import os
import time

import numpy as np
import pytest

from isolator.errors import IsolatorError, RecordError, ReviewError, TargetError
from isolator.motion import read_ground_motion
from isolator.review import parameters as P
from isolator.review.target import load_target


def _text_record(header: str) -> str:
    t = np.arange(300) * 0.01
    return header + "".join(f"{x:.2f},{0.3 * np.sin(2 * np.pi * x):.6f}\n" for x in t)


# ---------------------------------------------------------------- units stated in a text record
def test_two_different_units_lines_are_refused_as_ambiguous(tmp_path):
    path = tmp_path / "two.csv"
    path.write_text(_text_record("# units: g\n# units: cm/s2\n"))
    with pytest.raises(RecordError, match=r"states its units 2 times, differently \('# units: g', "
                                          r"'# units: cm/s2'\): ambiguous") as info:
        read_ground_motion(path)
    assert str(path) in str(info.value)
    # the order does not matter, nor whether the first one is a unit isolator knows
    path.write_text(_text_record("# units: mm\n# units: g\n"))
    with pytest.raises(RecordError, match="ambiguous"):
        read_ground_motion(path)


def test_the_same_units_twice_are_one_statement(tmp_path):
    once, twice = tmp_path / "once.csv", tmp_path / "twice.csv"
    once.write_text(_text_record("# units: cm/s2\n"))
    twice.write_text(_text_record("# units: cm/s2\n# units: CM/S2\n"))
    a, b = read_ground_motion(once), read_ground_motion(twice)
    np.testing.assert_array_equal(a.acceleration_m_s2, b.acceleration_m_s2)
    assert a.pga_m_s2 == pytest.approx(0.3 * 0.01)  # cm/s² → m/s², not g


@pytest.mark.parametrize("column", ["acc_mm", "a (m/s)", "disp [cm]"])
def test_a_column_named_in_a_length_or_velocity_unit_is_refused(tmp_path, column):
    path = tmp_path / "r.csv"
    path.write_text(_text_record(f"time_s,{column}\n"))
    with pytest.raises(RecordError, match="not of acceleration"):
        read_ground_motion(path, units="g")  # even when the user states units: the file says otherwise


# ---------------------------------------------------------------- review parameters
def test_every_review_parameter_has_a_range_holding_its_default():
    numeric = {name for name, p in P.PARAMETERS.items() if not isinstance(p.default, (bool, str))}
    assert numeric <= set(P.RANGES), sorted(numeric - set(P.RANGES))  # text and switches have their own values
    for name, parameter in P.PARAMETERS.items():
        if isinstance(parameter.default, (int, float)) and not isinstance(parameter.default, bool):
            P._check_range(name, parameter.default)  # the defaults pass their own ranges


@pytest.mark.parametrize("name, value, words", [
    ("usable_band_factor", "0", "'usable_band_factor' = 0 is outside [1, 10]"),
    ("min_ratio", "1e300", "'min_ratio' = 1e+300 is outside [0.5, 2]"),
    ("min_ratio", "0", "'min_ratio' = 0 is outside"),
    ("grid_points", "1e7", "'grid_points' = 1e+07 is outside [10, 10000]"),
    ("grid_points", "1", "'grid_points' = 1 is outside"),
    ("range_lo_factor", "1e-6", "'range_lo_factor' = 1e-06 is outside [0.1, 1]"),
    ("f_ae", "1e6", "'f_ae' = 1e+06 is outside [0, 1]"),
    ("sf_flag_low", "0", "'sf_flag_low' = 0 is outside (0, 1]"),
    ("R_I", "3", "1 ≤ R_I ≤ 2"),
])
def test_review_parameters_outside_their_range_are_refused_with_the_reason(name, value, words):
    with pytest.raises(ReviewError) as info:
        P.resolve("asce7-22" if name in P.resolve("asce7-22") else "en15129", {name: value})
    assert words in str(info.value) and ":" in str(info.value) and "\n" not in str(info.value)
    assert isinstance(info.value, IsolatorError)


def test_ordered_parameters_must_stay_ordered():
    with pytest.raises(ReviewError, match="'sf_flag_low' = 1 and 'sf_flag_high' = 1: the first must be below"):
        P.resolve("asce7-22", {"sf_flag_low": 1.0, "sf_flag_high": 1.0})
    with pytest.raises(ReviewError, match="range_lo_factor"):
        P.resolve("asce7-22", {"range_lo_factor": 1.0, "range_hi_factor": 1.0})
    assert P.resolve("asce7-22", {"sf_flag_low": 0.5, "sf_flag_high": 2})["sf_flag_high"] == 2.0


# ---------------------------------------------------------------- target files
@pytest.mark.parametrize("special", ["/dev/zero", "/dev/urandom", "fifo"])
def test_a_target_table_that_is_not_a_regular_file_is_refused_at_once(tmp_path, special):
    if special == "fifo":
        special = str(tmp_path / "table.csv")
        os.mkfifo(special)  # reading it would block for ever
    (tmp_path / "t.toml").write_text(f'spectrum_csv = "{special}"\n')
    start = time.perf_counter()
    with pytest.raises(TargetError, match="not a regular file") as info:
        load_target(tmp_path / "t.toml")
    assert time.perf_counter() - start < 2.0 and str(tmp_path / "t.toml") in str(info.value)


def test_a_target_table_with_two_header_lines_is_refused(tmp_path):
    (tmp_path / "s.csv").write_text("MCE_R spectrum, site B\nperiod_s,sa_g\n0.1,1.0\n1.0,0.5\n")
    (tmp_path / "t.toml").write_text('spectrum_csv = "s.csv"\n')
    with pytest.raises(TargetError, match="line 2: a second header line"):
        load_target(tmp_path / "t.toml")
    (tmp_path / "s.csv").write_text("period_s,sa_g\n0.1,1.0\n1.0,0.5\n")  # one header line: read
    assert load_target(tmp_path / "t.toml").sa_g([1.0])[0] == pytest.approx(0.5)


def test_a_target_table_larger_than_a_spectrum_is_refused(tmp_path):
    (tmp_path / "s.csv").write_bytes(b"0.1,1.0\n" * 1_300_000)
    (tmp_path / "t.toml").write_text('spectrum_csv = "s.csv"\n')
    with pytest.raises(TargetError, match="more than a spectrum table holds"):
        load_target(tmp_path / "t.toml")


@pytest.mark.parametrize("text, words", [
    ("S_MS = 1e-308\nS_M1 = 0.9\nT_L = 8\n", "'S_MS' = 1e-308 is outside [0.0001, 10], a spectral acceleration"),
    ("S_MS = 1.5\nS_M1 = 1e300\nT_L = 8\n", "'S_M1' = 1e+300 is outside"),
    ("S_MS = 1.5\nS_M1 = 0.9\nT_L = 1e300\n", "'T_L' = 1e+300 is outside [0.001, 100], a period"),
    ("a_g_g = 0.3\nS = 100\nT_B = 0.15\nT_C = 0.5\nT_D = 2.0\n", "'S' = 100 is outside"),
])
def test_absurd_target_values_are_refused(tmp_path, text, words):
    (tmp_path / "t.toml").write_text(text)
    with pytest.raises(TargetError) as info:
        load_target(tmp_path / "t.toml")
    assert words in str(info.value)
