"""Record selection: the same motion refused (rotated, scaled, shifted, resampled copies), weak and sinusoidal
records flagged, metadata against the controlling ranges, the fault-normal rotation, the engineer's own factors."""

from __future__ import annotations

import math
import shutil

import numpy as np
import pytest

from isolator.errors import SuiteError
from isolator.review.selection import (
    SAME_MOTION_TOLERANCE,
    closest_motions,
    motion_signature,
    selection_rows,
    signature_distance,
    spectral_bandwidth,
)
from isolator.review.suite import Pair, load_suite
from isolator.review.suite_components import component_azimuth_deg, rotate_to_fault
from tests.review.conftest import EXAMPLE, SHORT

G = 9.80665


def write_at2(path, acceleration_g, dt_s, component="0"):
    """A PEER AT2 file of the samples [g] (the component name closes the title line)."""
    values = np.asarray(acceleration_g, dtype=np.float64)
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD", f"copy, 1/1/2000, test, {component}",
             "ACCELERATION TIME SERIES IN UNITS OF G", f"NPTS= {values.size}, DT= {dt_s:.6f} SEC"]
    lines += ["".join(f"{v:15.7E}" for v in values[i:i + 5]) for i in range(0, values.size, 5)]
    path.write_text("\n".join(lines) + "\n")


def _suite_toml(folder, pairs):
    body = ""
    for name, x, y, extra in pairs:
        body += f'[[pair]]\nname = "{name}"\nx = "{x}"\ny = "{y}"\n{extra}\n'
    path = folder / "suite.toml"
    path.write_text(body)
    return path


@pytest.mark.parametrize("change", ["rotated 30°", "scaled 1.7", "shifted 3 s"])
def test_a_rotated_scaled_or_shifted_copy_is_refused_naming_both(tmp_path, change):
    folder, x, y, _ = SHORT[0]
    original = load_suite(_suite_toml(tmp_path, [("YER", EXAMPLE / folder / x, EXAMPLE / folder / y, "")])).pairs[0]
    ax, ay, dt = original.ax_m_s2 / G, original.ay_m_s2 / G, original.dt_s
    if change.startswith("rotated"):
        c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
        ax, ay = c * ax - s * ay, s * ax + c * ay
    elif change.startswith("scaled"):
        ax, ay = 1.7 * ax, 1.7 * ay
    else:
        zeros = np.zeros(int(round(3.0 / dt)))
        ax, ay = np.concatenate([zeros, ax]), np.concatenate([zeros, ay])
    write_at2(tmp_path / "cx.AT2", ax, dt)
    write_at2(tmp_path / "cy.AT2", ay, dt)
    other = SHORT[1]
    path = _suite_toml(tmp_path, [("YER", EXAMPLE / folder / x, EXAMPLE / folder / y, ""),
                                  ("ABY", EXAMPLE / other[0] / other[1], EXAMPLE / other[0] / other[2], ""),
                                  ("copy", tmp_path / "cx.AT2", tmp_path / "cy.AT2", "")])
    with pytest.raises(SuiteError) as info:
        load_suite(path)
    message = str(info.value)
    assert "same motion" in message and "\n" not in message
    assert x in message and "cx.AT2" in message and "'copy'" in message and "'YER'" in message


def test_resampled_copies_stay_close_and_real_pairs_stay_apart():
    suite = load_suite(EXAMPLE / "suite.toml")
    closest = closest_motions(suite.pairs)
    assert closest["distance"] > 4 * SAME_MOTION_TOLERANCE  # 8 real pairs of 8 earthquakes are far apart
    p = suite.pairs[0]
    base = motion_signature(p.ax_m_s2, p.ay_m_s2, p.dt_s)
    t = np.arange(p.npts) * p.dt_s
    for factor in (0.5, 2.0):  # linear resampling to dt/2 and 2 dt
        t2 = np.arange(0.0, t[-1], p.dt_s * factor)
        copy = motion_signature(np.interp(t2, t, p.ax_m_s2), np.interp(t2, t, p.ay_m_s2), p.dt_s * factor)
        assert signature_distance(base, copy) < SAME_MOTION_TOLERANCE / 2
    # the exact invariances
    c, s = math.cos(1.0), math.sin(1.0)
    rotated = motion_signature(c * p.ax_m_s2 - s * p.ay_m_s2, s * p.ax_m_s2 + c * p.ay_m_s2, p.dt_s)
    assert signature_distance(base, rotated) < 1e-9


def _pair(name, ax, ay, dt, **metadata):
    return Pair(name=name, ax_m_s2=np.asarray(ax, float), ay_m_s2=np.asarray(ay, float), az_m_s2=None, dt_s=dt,
                files={"x": f"{name}x", "y": f"{name}y"}, component_names={}, metadata=metadata)


def test_sinusoid_and_weak_records_are_flagged_and_metadata_checked():
    from isolator.review.parameters import resolve

    t = np.arange(0.0, 20.0, 0.01)
    sine = _pair("circle", 3.0 * np.sin(2 * np.pi * t), 3.0 * np.cos(2 * np.pi * t), 0.01, magnitude=7.0,
                 distance_km=10.0)
    assert spectral_bandwidth(sine.ax_m_s2, 0.01) < 0.15
    suite = load_suite(EXAMPLE / "suite.toml")
    real = suite.pairs[1]
    real.metadata = {"magnitude": 7.3, "distance_km": 45.0}
    params = resolve("asce7-22")
    rows = {r["id"]: r for r in selection_rows(
        [sine, real], [1.0, 0.01], mu_lower=0.04, gravity_m_s2=G,
        controlling={"magnitude_range": [6.5, 7.5], "distance_km_range": [0.0, 30.0]}, params=params,
        closest=closest_motions([sine, real]))}
    assert rows["record_nature"]["status"] == "fail" and "circle x" in rows["record_nature"]["note"]
    weak = 0.01 * float(np.max(np.hypot(real.ax_m_s2, real.ay_m_s2))) / G
    assert weak < 0.1 * 0.04  # the scaled real pair is below a tenth of the sliding acceleration
    assert rows["record_strength"]["status"] == "fail" and rows["record_strength"]["value"] == pytest.approx(weak)
    assert real.name in rows["record_strength"]["note"]
    assert rows["record_selection"]["status"] == "fail" and "distance_km 45" in rows["record_selection"]["note"]
    # mechanism and V_s30 against the target's: the circle says strike-slip, the real pair says nothing
    sine.metadata.update(mechanism="Strike-Slip", vs30_m_s=400.0)
    real.metadata.update(distance_km=20.0)
    both = {"magnitude_range": [6.5, 7.5], "distance_km_range": [0.0, 30.0], "vs30_m_s_range": [300.0, 500.0],
            "mechanisms": ["strike-slip"]}
    row = selection_rows([sine, real], [1.0, 1.0], mu_lower=0.04, gravity_m_s2=G, controlling=both, params=params,
                         closest=None)[0]
    assert row["status"] == "not checked" and "unknown for 2 of 2" in row["note"]  # real: mechanism, V_s30
    real.metadata.update(mechanism="reverse", vs30_m_s=350.0)
    row = selection_rows([sine, real], [1.0, 1.0], mu_lower=0.04, gravity_m_s2=G, controlling=both, params=params,
                         closest=None)[0]
    assert row["status"] == "fail" and "mechanism reverse" in row["note"] and "circle" not in row["note"]
    real.metadata.update(mechanism="strike-slip")
    row = selection_rows([sine, real], [1.0, 1.0], mu_lower=0.04, gravity_m_s2=G, controlling=both, params=params,
                         closest=None)[0]
    assert row["status"] == "pass" and "pulse" not in row["note"]
    assert rows["distinct_motions"]["status"] == "pass"
    none = {r["id"]: r for r in selection_rows([real], [1.0], mu_lower=0.04, gravity_m_s2=G, controlling={},
                                               params=params, closest=None)}
    assert none["record_selection"]["status"] == "not checked" and none["distinct_motions"]["status"] == "not checked"
    assert none["record_strength"]["status"] == none["record_nature"]["status"] == "pass"


@pytest.mark.parametrize("name, azimuth", [("270", 270.0), ("HN1 (90)", 90.0), ("YER360", 0.0), ("N55W", 305.0),
                                           ("S01W", 181.0), ("S35E", 145.0), ("EW", 90.0), ("N", 0.0), ("HN1", None)])
def test_component_azimuths_from_names(name, azimuth):
    assert component_azimuth_deg(name) == azimuth


def test_rotation_to_fault_normal_both_components_recorded(tmp_path):
    folder, x, y, _ = SHORT[0]  # Landers YER: x = 270, y = 360
    plain = load_suite(_suite_toml(tmp_path, [("YER", EXAMPLE / folder / x, EXAMPLE / folder / y, "")])).pairs[0]
    rotated = load_suite(_suite_toml(tmp_path, [("YER", EXAMPLE / folder / x, EXAMPLE / folder / y,
                                                 "rotate_to_fault_normal_deg = 30.0")])).pairs[0]
    step = rotated.processing[-1]
    assert step["strike_deg"] == 30.0 and step["azimuth_x_deg"] == 270.0 and step["azimuth_y_deg"] == 0.0
    # by hand: east = −a_270, north = a_360; FN azimuth 120°: (sin 120, cos 120) · (east, north)
    east, north = -plain.ax_m_s2, plain.ay_m_s2
    fn = math.sin(math.radians(120)) * east + math.cos(math.radians(120)) * north
    fp = math.sin(math.radians(30)) * east + math.cos(math.radians(30)) * north
    assert np.allclose(rotated.ax_m_s2, fn, atol=1e-12) and np.allclose(rotated.ay_m_s2, fp, atol=1e-12)
    assert np.allclose(np.hypot(rotated.ax_m_s2, rotated.ay_m_s2), np.hypot(plain.ax_m_s2, plain.ay_m_s2))
    a, b = rotate_to_fault(np.array([1.0]), np.array([0.0]), 90.0, 0.0, 0.0)  # east motion, strike north
    assert a[0] == pytest.approx(1.0) and b[0] == pytest.approx(0.0, abs=1e-15)


def test_suite_keys_checked_and_a_mixed_matched_suite_refused(tmp_path):
    (a, ax, ay, _), (b, bx, by, _) = SHORT[0], SHORT[1]
    base = [("A", EXAMPLE / a / ax, EXAMPLE / a / ay, "matched = true"), ("B", EXAMPLE / b / bx, EXAMPLE / b / by, "")]
    with pytest.raises(SuiteError, match="spectrally matched and pair 'B' is not"):
        load_suite(_suite_toml(tmp_path, base))
    for extra, words in (("scale_factor = -1.0", "'scale_factor' must be a number > 0"),
                         ("magnitude = 12.0", "'magnitude' must be a number in"),
                         ("pulse = 1", "'pulse' must be true or false"),
                         ("azimuth_x_deg = 10.0", "serve rotate_to_fault_normal_deg")):
        with pytest.raises(SuiteError, match=words):
            load_suite(_suite_toml(tmp_path, [("A", EXAMPLE / a / ax, EXAMPLE / a / ay, extra)]))
    shutil.copy(EXAMPLE / a / ax, tmp_path / "x.AT2")
    write_at2(tmp_path / "y.AT2", np.linspace(0.0, 0.1, 10), 0.02, component="UNK")
    with pytest.raises(SuiteError, match="not in its name; give azimuth_y_deg"):
        load_suite(_suite_toml(tmp_path, [("A", tmp_path / "x.AT2", tmp_path / "y.AT2",
                                           "trim = true\nrotate_to_fault_normal_deg = 10.0")]))


# ---------------------------------------------------------------- issue 26: one answer per piecewise-linear signal
def _broadband(n=1200, dt=0.01, seed=3):
    rng = np.random.default_rng(seed)
    t = np.arange(n) * dt
    return np.convolve(rng.normal(size=n + 9), np.ones(10) / 10, "valid")[:n] * np.exp(-((t - 4.0) / 2.5) ** 2) + 0.2


def _refined(a):
    """The same piecewise-linear signal at dt/2: a collinear midpoint in every interval."""
    out = np.empty(2 * a.size - 1)
    out[0::2], out[1::2] = a, 0.5 * (a[:-1] + a[1:])
    return out


def test_bandwidth_is_the_piecewise_linear_signals_own_against_a_segment_by_segment_transform():
    """δ from an independent transform (each linear segment integrated in closed form, no DFT, no sinc) on the
    same frequency grid and band, and δ of the same signal sampled at dt/2, equal the function's δ."""
    from isolator.review.selection import BANDWIDTH_BAND_HZ

    a, dt = _broadband(), 0.01
    n = 1 << int(math.ceil(math.log2(2 * a.size)))
    f = np.arange(int(BANDWIDTH_BAND_HZ * n * dt) + 1) / (n * dt)
    u = 2.0 * np.pi * f[1:, None]
    t0 = np.arange(a.size - 1) * dt
    slope = np.diff(a) / dt
    e = np.exp(-1j * u * dt)
    i0 = (e - 1.0) / (-1j * u)
    i1 = dt * e / (-1j * u) - (e - 1.0) / (-1j * u) ** 2
    spectrum = np.concatenate([[np.sum(dt * (a[:-1] + a[1:]) / 2.0)],
                               np.sum(np.exp(-1j * u * t0) * (a[:-1] * i0 + slope * i1), axis=1)])
    power = np.abs(spectrum) ** 2
    l0, l1, l2 = (np.sum(power * f ** k) for k in (0, 1, 2))
    reference = math.sqrt(1.0 - l1 * l1 / (l0 * l2))
    assert spectral_bandwidth(a, dt) == pytest.approx(reference, rel=1e-10)
    assert spectral_bandwidth(_refined(a), dt / 2) == pytest.approx(reference, rel=1e-10)


def test_resultant_arias_window_and_orbit_are_exact_for_the_piecewise_linear_pair():
    """A ramp a = t on [0, 1] s has ∫a² = t³/3: the fraction p is reached at t = p^(1/3) exactly (the trapezoidal
    rule on two samples would put 5 % at 0.05 s); a pair and its dt/2 refinement share the window and the orbit."""
    from isolator.motion.measures import arias_window_s, energy_window_s
    from isolator.review.selection import resultant_arias_window

    start, end = arias_window_s(np.array([0.0, 1.0]), 1.0)
    assert (start, end) == (pytest.approx(0.05 ** (1 / 3), rel=1e-14), pytest.approx(0.95 ** (1 / 3), rel=1e-14))
    assert energy_window_s([np.array([0.0, 3.0]), np.array([0.0, 4.0])], 2.0, (0.5,))[0] == pytest.approx(
        2.0 * 0.5 ** (1 / 3), rel=1e-14)  # resultant 5t/2 on [0, 2] s
    ax, ay, dt = _broadband(seed=4), _broadband(seed=5), 0.01
    coarse = resultant_arias_window(ax, ay, dt)
    fine = resultant_arias_window(_refined(ax), _refined(ay), dt / 2)
    assert fine == (pytest.approx(coarse[0], rel=1e-12), pytest.approx(coarse[1], rel=1e-12))
    a, b = motion_signature(ax, ay, dt), motion_signature(_refined(ax), _refined(ay), dt / 2)
    assert b["eigen_ratio"] == pytest.approx(a["eigen_ratio"], rel=1e-12)
    assert b["duration_s"] == pytest.approx(a["duration_s"], rel=1e-12)
