"""Session 25's hostile sweep (h228): session 24's leftovers (a story stiffness or a bearing's capacity in another
unit, a triple's capacity beyond its sphere, a huge TOML's parse) and record headers that disagree with their data
(docs/security.md, "Session 25 sweep").
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from _records import assert_one_line_exit_2
from typer.testing import CliRunner

from isolator.cli import app
from isolator.design import Design
from isolator.errors import DesignError, RecordFormatError, TimeStepConflictError

RUNNER = CliRunner()
DATA = Path(__file__).resolve().parents[1] / "data"
BASE = {"name": "B", "mass_kg": 2.0e6, "radius_m": 2.5, "mu_static": 0.06}


def _building(floors, **extra):
    return Design.from_mapping({**BASE, "superstructure": {"damping_ratio": 0.05, "floor": floors}, **extra})


# ---- 1. a story stiffness in kN/m: the fixed-base period beyond any building's

def test_a_story_stiffness_in_kn_per_m_is_refused_by_the_fixed_base_period():
    """c765efa read the example building with its stiffnesses in kN/m (T_1 = 15.5 s instead of 0.49 s) and with one
    story in kN/m (top: 5.9 s); now T_1 above 4 C_u T_a (ASCE 7-22 Eq. 12.8-7, steel moment frame) is refused."""
    from isolator.design import load_toml

    mapping = load_toml(DATA / "example_building.toml", "design file", DesignError)
    Design.from_mapping(mapping)  # the example: T_1 = 0.49 s, read
    for stories in ([0, 1, 2, 3, 4], [4]):
        floors = [dict(f) for f in mapping["superstructure"]["floor"]]
        for i in stories:
            floors[i]["stiffness_x_N_per_m"] /= 1000.0  # kN/m typed as N/m
        with pytest.raises(DesignError, match=rf"fixed-base period along x is .* s, longer than any building of h_n = "
                                              rf"18.4 m .* a story stiffness in kN/m\? .* floor {stories[0] + 1} from"):
            Design.from_mapping({**mapping, "superstructure": {**mapping["superstructure"], "floor": floors}})


def test_the_period_bound_is_four_cu_ta_of_a_steel_moment_frame_by_hand():
    """One story (m, k, h): T = 2π √(m/k), the bound 4 × 1.4 × 0.0724 h^0.8 written here from ASCE 7-22 Tables
    12.8-1/12.8-2; a stiffness 1 % stiffer than the bound's reads, 1 % softer is refused (c765efa read both)."""
    m, h = 1.0e6, 4.0
    bound_s = 4 * 1.4 * 0.0724 * h ** 0.8
    k_at_bound = m * (2 * math.pi / bound_s) ** 2  # 2.6e7 N/m
    floor = {"mass_kg": m, "story_height_m": h}
    _building([{**floor, "stiffness_x_N_per_m": 1.01 * k_at_bound}])
    with pytest.raises(DesignError, match=rf"along x is {2 * math.pi * math.sqrt(m / (0.99 * k_at_bound)):.3g} s, .* "
                                          rf"\(above 4 C_u T_a = {bound_s:.3g} s"):
        _building([{**floor, "stiffness_x_N_per_m": 0.99 * k_at_bound}])
    with pytest.raises(DesignError, match=r"along y .*\(stiffness_y_N_per_m is in N/m"):  # y alone in kN/m
        _building([{**floor, "stiffness_x_N_per_m": 1e9, "stiffness_y_N_per_m": 0.99 * k_at_bound}])


# ---- 2. a bearing's axial capacity: a range and its gravity load

@pytest.mark.parametrize("capacity, words", [
    (1.2e4, "= 12000 N is below 0.1 of the bearing's gravity load (4.903e+06 N): a capacity in kN?"),
    (1e-300, "= 1e-300 N is below 0.1 of the bearing's gravity load"),
    (1e300, "= 1e+300 N is above 1e+09 N"),
])
def test_an_axial_capacity_in_another_unit_is_refused(capacity, words):
    """c765efa read 1.2e4 N (kN typed as N) for a bearing carrying 4.9 MN, 1e-300 and 1e300 N; a capacity half the
    load (a failing design, the review's 17.2.4.6 row) still reads."""
    positions = [{"x_m": x, "y_m": y} for x in (-5.0, 5.0) for y in (-5.0, 5.0)]  # W/4 = 4.903e6 N each
    share = BASE["mass_kg"] * 9.80665 / 4
    Design.from_mapping({**BASE, "bearing_position": [{**p, "axial_capacity_N": 0.5 * share} for p in positions]})
    with pytest.raises(DesignError, match=r"bearing_position 1: key 'axial_capacity_N' " + _escaped(words)):
        Design.from_mapping({**BASE, "bearing_position": [{**p, "axial_capacity_N": capacity} for p in positions]})


def _escaped(text: str) -> str:
    import re

    return re.escape(text)


# ---- 4. a huge TOML is refused before its parse

def test_a_design_file_past_4_mib_is_refused_unparsed_while_a_designs_file_keeps_64(tmp_path):
    """c765efa parsed up to 64 MiB of any TOML: a 10 MB array took 100 s to refuse (load 9); now a design file stops
    at 4 MiB (MAX_ONE_TOML_BYTES; the 10,000-bearing building is 0.5 MiB), a batch's designs file keeps 64 MiB."""
    from isolator.batch.plan import load_design_mappings
    from isolator.errors import BatchError

    big = tmp_path / "big.toml"
    with open(big, "wb") as stream:
        stream.truncate(4 * 2**20 + 1)  # sparse NULs: no disk used
    with pytest.raises(DesignError, match=r"big.toml: is 4.0 MiB, larger than any design file \(isolator reads a "
                                          r"design file up to 4 MiB"):
        Design.from_toml(big)
    with pytest.raises(BatchError) as caught:  # read past the size check: the NULs are not TOML
        load_design_mappings(big)
    assert "not valid TOML" in str(caught.value), caught.value


# ---- 5. a text record's time step stated twice, or against its time column or --dt

SINE = [0.1 * math.sin(2 * math.pi * i * 0.01) for i in range(200)]


def _read(path, **options):
    from isolator.io.text import _read_text

    return _read_text(str(path), **options)[0]


def test_a_stated_step_that_disagrees_with_the_time_column_is_refused(tmp_path):
    """c765efa read `# dt_s: 0.02` above a time column of 0.01 s as 0.01 s without a word; a note that is not a number
    (`# dt: 0.01 s`) is still a note, and a line that agrees reads."""
    body = "".join(f"{i * 0.01:.2f} {v:.6f}\n" for i, v in enumerate(SINE))
    path = tmp_path / "x.txt"
    path.write_text("# dt_s: 0.02\n" + body)
    with pytest.raises(RecordFormatError, match=r"'# dt_s: 0.02' disagrees with the time column's step of 0.01 s"):
        _read(path)
    for note in ("# dt: 0.01 s\n", "# dt_s: 0.010\n"):
        path.write_text(note + body)
        assert _read(path).stats.delta == 0.01


def test_two_stated_steps_or_dt_against_the_file_are_refused(tmp_path):
    """c765efa took the last of `# dt_s: 0.02` / `# dt_s: 0.01` (0.01 s), and `info --dt 0.02` over `# dt_s: 0.01`
    (0.02 s), without a word; `--units` against `# units:` was already refused."""
    body = "".join(f"{v:.6f}\n" for v in SINE)
    path = tmp_path / "x.txt"
    path.write_text("# dt_s: 0.02\n# units: g\n# dt_s: 0.01\n" + body)
    with pytest.raises(RecordFormatError, match=r"states its time step 2 times, differently \('# dt_s: 0.02', "
                                                r"'# dt_s: 0.01'\)"):
        _read(path)
    path.write_text("# dt_s: 0.01\n# units: g\n" + body)
    with pytest.raises(TimeStepConflictError):
        _read(path, dt_s=0.02)
    assert _read(path, dt_s=0.01).stats.delta == 0.01  # the same step given twice reads
    line = assert_one_line_exit_2(RUNNER.invoke(app, ["info", str(path), "--dt", "0.02"]))
    assert line == (f"error: {path}: plain text: the file states '# dt_s: 0.01' but the time step given is 0.02 s; "
                    "--dt says 0.02 s: drop it to use the file's time step"), line


def test_a_v2_block_whose_step_disagrees_with_its_channel_header_is_refused(tmp_path, records_dir):
    """c765efa read an accel block of 0.020 s under the channel's 'equally-spaced intervals of 0.010 sec' as 0.02 s
    (the record twice as long, its spectrum shifted an octave) without a word."""
    from isolator.io.v2 import _read_v2

    text = (records_dir / "other" / "ce89486SampleInput.v2").read_text()
    block = " 10100 points of accel data equally spaced at 0.010 sec"
    assert text.count(block) == 3  # one per channel
    path = tmp_path / "x.v2"
    path.write_text(text.replace(block, block.replace("0.010", "0.020"), 1))
    with pytest.raises(RecordFormatError, match=r"DT=0.02 s on line 46 disagrees with the channel's header "
                                                r"\('equally-spaced intervals of 0.010 sec'\)"):
        _read_v2(str(path))
    assert [trace.stats.delta for trace in _read_v2(str(records_dir / "other" / "ce89486SampleInput.v2"))] == [0.01] * 3


def test_a_knet_file_cut_short_or_scaled_against_its_header_is_refused(tmp_path, records_dir):
    """c765efa read the first 900 lines of a K-NET file (7064 of 13800 samples) as a 70.6 s record under its header's
    'Duration Time(s) 138', and a 'Max. Acc. (gal)' 100 times the samples' peak, without a word.  The shared records'
    seven K-NET components agree with their headers (span = duration, peak within 5e-4 gal) and read."""
    from isolator.errors import RecordError
    from isolator.motion import read_ground_motion

    text = (records_dir / "other" / "AOM0081801241951.EW").read_text()
    assert read_ground_motion(records_dir / "other" / "AOM0081801241951.EW").npts == 13800
    cut, scaled = tmp_path / "cut.EW", tmp_path / "scaled.EW"
    cut.write_text("\n".join(text.splitlines()[:900]) + "\n")
    scaled.write_text(text.replace("Max. Acc. (gal)   30.248", "Max. Acc. (gal)   3024.8"))
    with pytest.raises(RecordError, match=r"cut.EW: K-NET header states 'Duration Time\(s\) 138' but the file holds "
                                          r"7064 samples at 0.01 s \(70.64 s\): truncated"):
        read_ground_motion(cut)
    with pytest.raises(RecordError, match=r"'Max. Acc. \(gal\) 3024.8' but the samples × its 'Scale Factor' peak at "
                                          r"30.248 gal"):
        read_ground_motion(scaled)
