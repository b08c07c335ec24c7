"""Review suites under hostile use (issue 26): unequal sampling, components that start at different
times, one motion twice in a pair, a vertical labelled horizontal, names that collide.

The records are written here as text files with a time column, so that each case is exactly the
signal it claims to be; a piecewise-linear signal sampled two ways must give the same suite (and,
in test_hostile_review.py, the same review).
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.errors import SuiteError
from isolator.motion import pseudo_acceleration_spectrum
from isolator.review.suite import load_suite

DT = 0.01


def _signal(n=1500, seed=3, phase=0.0):
    """A record-like acceleration [g]: a decaying sum of sines with random phases."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) * DT
    envelope = np.minimum(1.0, t / 2.0) * np.exp(-np.maximum(t - 6.0, 0.0) / 3.0)
    a = sum(rng.uniform(0.03, 0.1) * np.sin(2 * np.pi * f * t + rng.uniform(0, 6.3) + phase)
            for f in rng.uniform(0.3, 6.0, 12))
    return t, envelope * a


def _write(path, t, a, *, units="g", component="000", station=None):
    header = f"# units: {units}\n# component: {component}\n" + (f"# station: {station}\n" if station else "")
    path.write_text(header + "".join(f"{x:.6f},{y:.9e}\n" for x, y in zip(t, a, strict=True)))
    return path


def _suite_toml(folder, x, y, z=None, name="p", trim=False, extra=""):
    text = f'[[pair]]\nname = "{name}"\nx = "{x}"\ny = "{y}"\n' + (f'z = "{z}"\n' if z else "")
    text += "trim = true\n" if trim else ""
    (folder / "suite.toml").write_text(text + extra)
    return folder / "suite.toml"


def _with_midpoints(t, a, intervals):
    """The same piecewise-linear signal with a collinear midpoint in each of the first intervals."""
    mid_t = 0.5 * (t[:intervals] + t[1:intervals + 1])
    mid_a = 0.5 * (a[:intervals] + a[1:intervals + 1])
    times = np.concatenate([np.ravel(np.column_stack([t[:intervals], mid_t])), t[intervals:]])
    values = np.concatenate([np.ravel(np.column_stack([a[:intervals], mid_a])), a[intervals:]])
    return times, values


def test_unequal_sampling_of_one_signal_gives_the_same_pair(tmp_path):
    t, ax = _signal(seed=1)
    _, ay = _signal(seed=2)
    _write(tmp_path / "x.csv", t, ax, component="000")
    _write(tmp_path / "y.csv", t, ay, component="090")
    tm, axm = _with_midpoints(t, ax, 1000)  # the attack: midpoints in the first 1000 intervals
    tn, aym = _with_midpoints(t, ay, 1000)
    _write(tmp_path / "xm.csv", tm, axm, component="000")
    _write(tmp_path / "ym.csv", tn, aym, component="090")
    plain = load_suite(str(_suite_toml(tmp_path, "x.csv", "y.csv"))).pairs[0]
    (tmp_path / "m").mkdir()
    refined = load_suite(str(_suite_toml(tmp_path / "m", "../xm.csv", "../ym.csv"))).pairs[0]
    assert refined.dt_s == pytest.approx(DT / 2, rel=1e-12) and refined.npts == 2 * plain.npts - 1
    np.testing.assert_array_equal(refined.ax_m_s2[::2], plain.ax_m_s2)  # every sample kept
    assert any(step.get("step") == "uniform_grid" for step in refined.processing)
    assert refined.pga_m_s2 == plain.pga_m_s2
    periods = np.array([0.5, 1.0, 2.5, 4.0])
    for a, b in ((plain.ax_m_s2, refined.ax_m_s2), (plain.ay_m_s2, refined.ay_m_s2)):
        sa_plain = pseudo_acceleration_spectrum(a, plain.dt_s, periods)
        sa_refined = pseudo_acceleration_spectrum(b, refined.dt_s, periods)
        np.testing.assert_allclose(sa_refined, sa_plain, rtol=1e-9)  # exact for piecewise-linear input


def test_sample_times_that_share_no_grid_are_refused(tmp_path):
    t, a = _signal(400)
    jitter = t + np.random.default_rng(0).uniform(0, 0.003, t.size) * (np.arange(t.size) % 2)
    _write(tmp_path / "x.csv", jitter, a, component="000")
    _write(tmp_path / "y.csv", t, a[::-1].copy(), component="090")
    with pytest.raises(SuiteError, match=r"pair 'p' x .*x\.csv\): sampled at unequal steps .* share no common grid"):
        load_suite(str(_suite_toml(tmp_path, "x.csv", "y.csv")))


def test_components_that_start_at_different_times_are_aligned_or_refused(tmp_path):
    t, ax = _signal(seed=4)
    _, ay = _signal(seed=5)
    _write(tmp_path / "x.csv", t, ax, component="000")
    _write(tmp_path / "y.csv", t[100:], ay[100:], component="090")  # starts 1 s later: its own clock
    with pytest.raises(SuiteError, match=r"pair 'p': the components have different start times .* not paired "
                                         "sample by sample: set trim = true"):
        load_suite(str(_suite_toml(tmp_path, "x.csv", "y.csv")))
    pair = load_suite(str(_suite_toml(tmp_path, "x.csv", "y.csv", trim=True))).pairs[0]
    np.testing.assert_allclose(pair.ax_m_s2, ax[100:] * 9.80665)  # x cut to y's start: same instants
    np.testing.assert_allclose(pair.ay_m_s2, ay[100:] * 9.80665)
    assert any(step.get("step") == "trim_to_common_window" for step in pair.processing)


@pytest.mark.parametrize("case, words", [
    ("vertical_is_x", "the same samples twice"),
    ("g_and_gal", "are one motion (equal to 1e-06 of the PGA in m/s²; one file twice, or one record in two units)"),
    ("z_labelled_090", "z (" ),
    ("x_labelled_up", "a vertical component; give it as z"),
])
def test_one_motion_twice_or_a_component_in_the_wrong_place_is_refused(tmp_path, case, words):
    t, ax = _signal(seed=6)
    _, ay = _signal(seed=7)
    _, az = _signal(seed=8)
    _write(tmp_path / "x.csv", t, ax, component="000")
    _write(tmp_path / "y.csv", t, ay, component="090")
    _write(tmp_path / "z.csv", t, 0.5 * az, component="UP")
    x, y, z = "x.csv", "y.csv", "z.csv"
    if case == "vertical_is_x":
        _write(tmp_path / "zx.csv", t, ax, component="UP")  # the vertical file holds x's samples
        z = "zx.csv"
    elif case == "g_and_gal":
        _write(tmp_path / "y.csv", t, ax * 980.665, units="gal", component="090")
    elif case == "z_labelled_090":
        _write(tmp_path / "z.csv", t, 0.5 * az, component="090")
        words = "z (" + str(tmp_path / "z.csv") + ") is labelled '090', a horizontal component; give the vertical as z"
    elif case == "x_labelled_up":
        _write(tmp_path / "x.csv", t, ax, component="UP")
    with pytest.raises(SuiteError) as info:
        load_suite(str(_suite_toml(tmp_path, x, y, z)))
    assert words in str(info.value) and "pair 'p'" in str(info.value)


def test_pair_names_that_differ_by_spaces_or_case_are_refused(tmp_path):
    t, ax = _signal(seed=9)
    _, ay = _signal(seed=10)
    _, bx = _signal(seed=11)
    _, by = _signal(seed=12)
    for name, a in (("ax", ax), ("ay", ay), ("bx", bx), ("by", by)):
        _write(tmp_path / f"{name}.csv", t, a, component="000" if name.endswith("x") else "090")
    text = '[[pair]]\nname = "a"\nx = "ax.csv"\ny = "ay.csv"\n[[pair]]\nname = " A"\nx = "bx.csv"\ny = "by.csv"\n'
    (tmp_path / "suite.toml").write_text(text)
    with pytest.raises(SuiteError, match="pair 2: name ' A' is used twice"):
        load_suite(str(tmp_path / "suite.toml"))


def test_one_station_in_two_earthquakes_keeps_both_pairs(tmp_path):
    for quake, seed in (("kobe", 20), ("chichi", 30)):
        folder = tmp_path / quake / "STA"
        folder.mkdir(parents=True)
        t, ax = _signal(seed=seed)
        _, ay = _signal(seed=seed + 1)
        _write(folder / "x.csv", t, ax, component="000")
        _write(folder / "y.csv", t, ay, component="090")
    suite = load_suite([str(tmp_path / "kobe" / "STA"), str(tmp_path / "chichi" / "STA")])
    assert sorted(suite.names) == ["STA (chichi/STA)", "STA (kobe/STA)"]
    assert len({pair.content_key() for pair in suite.pairs}) == 2
