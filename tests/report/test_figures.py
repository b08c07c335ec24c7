"""isolator.report.figures: each drawing shows what was computed, checked against independent numbers."""

from __future__ import annotations

import numpy as np
import pytest
from matplotlib.figure import Figure
from scipy.ndimage import distance_transform_edt

from isolator.maps import regime_map
from isolator.metrics import slip_intervals
from isolator.motion import GroundMotion
from isolator.report import figures
from isolator.solver.record import simulate_record
from isolator.units import STANDARD_GRAVITY


@pytest.fixture(scope="module")
def pendulum_response():
    """A pendulum (T = 2.84 s, µs = 0.06, µk = 0.05, 5 % damper) under 20 s of a 1.5 Hz sine of 0.09 g."""
    dt = 0.01
    t = np.arange(2001) * dt
    acc = 0.09 * STANDARD_GRAVITY * np.sin(2 * np.pi * 1.5 * t) * np.minimum(1.0, t / 3.0)
    kappa = STANDARD_GRAVITY / 2.0
    response = simulate_record(acc, dt, mu_static=0.06, mu_kinetic=0.05, stiffness_per_mass=kappa,
                               damping_per_mass=2 * 0.05 * np.sqrt(kappa))
    return acc, dt, response


def test_distance_to_edge_is_the_euclidean_distance_transform():
    rng = np.random.default_rng(12)
    for shape, fill in (((10, 10), 0.5), ((42, 42), 0.9), ((30, 57), 0.97), ((3, 80), 0.8)):
        mask = np.pad(rng.random(shape) < fill, 1)
        np.testing.assert_array_equal(figures.distance_to_edge(mask), distance_transform_edt(mask))
    # closed form: one False cell, the distance is the Euclidean distance to it
    mask = np.ones((9, 13), bool)
    mask[4, 6] = False
    rows, cols = np.indices(mask.shape)
    np.testing.assert_allclose(figures.distance_to_edge(mask), np.hypot(rows - 4, cols - 6), rtol=0, atol=1e-12)


def test_new_figure_is_outside_pyplot_and_in_the_report_style():
    import sys

    import matplotlib

    pyplot = sys.modules.get("matplotlib.pyplot")  # another test may have imported it
    before = pyplot.get_fignums() if pyplot else []
    fig = figures.new_figure(figsize=(4.0, 3.0))
    assert isinstance(fig, Figure) and tuple(fig.get_size_inches()) == (4.0, 3.0)
    assert matplotlib.rcParams["pdf.fonttype"] == 3 and matplotlib.rcParams["font.size"] == 8.5
    assert (pyplot.get_fignums() if pyplot else []) == before  # nothing registered, nothing to close


def test_slip_shading_covers_exactly_the_slip_intervals(pendulum_response):
    _, _, response = pendulum_response
    intervals = slip_intervals(response)
    assert 5 < intervals.shape[0] < 100  # stick-slip: several separate slips
    fig = figures.new_figure(figsize=(8.0, 3.0))
    ax = fig.add_subplot()
    ax.plot(response.time_s, response.displacement_m)
    figures.shade_intervals(ax, intervals, span_s=float(response.time_s[-1]))
    shading = [c for c in ax.collections if c.get_label() == "sliding"]
    assert len(shading) == 1  # one artist for all the slips
    extents = []
    for path in shading[0].get_paths():
        x = path.vertices[:, 0]
        y = path.vertices[:, 1]
        extents.append((x.min(), x.max()))
        assert y.min() == pytest.approx(0.0) and y.max() == pytest.approx(1.0)  # full height, axes units
    # merged only where the gap is below one pixel of a 20 s axis: the bars' union is the slip time
    covered = sum(end - start for start, end in extents)
    assert covered == pytest.approx(response.slip_time_s, rel=0, abs=len(intervals) * 20.0 / figures.PIXELS_PER_AXIS)
    assert extents[0][0] == pytest.approx(intervals[0, 0]) and extents[-1][1] == pytest.approx(intervals[-1, 1])
    assert "sliding" in [t.get_text() for t in ax.legend().get_texts()]


def test_record_page_marks_the_true_peaks_and_draws_the_given_spectrum(pendulum_response):
    acc, dt, _ = pendulum_response
    motion = GroundMotion.from_array(acc, dt, units_source="test")
    periods = np.geomspace(0.05, 6.0, 30)
    psa = np.linspace(1.0, 3.0, 30)  # any values: the page draws what it is given
    fig = figures.new_figure(figsize=(8.27, 11.69))
    axes = figures.record_page(fig, motion, (3.0, 17.0), periods, psa, 2.84, 2.5)
    assert len(axes) == 4
    # the acceleration peak label: max |a| / g, by numpy on the input
    labels = [t.get_text() for t in axes[0].get_legend().get_texts()]
    assert f"peak {np.abs(acc).max() / STANDARD_GRAVITY:.3g}" in " ".join(labels)
    # the velocity peak: an independent trapezoidal sum from rest
    velocity = np.concatenate(([0.0], np.cumsum(0.5 * dt * (acc[1:] + acc[:-1]))))
    labels = [t.get_text() for t in axes[1].get_legend().get_texts()]
    assert f"peak {np.abs(velocity).max():.3g}" in " ".join(labels)
    spectrum = axes[3].get_lines()[0]
    np.testing.assert_allclose(spectrum.get_ydata(), psa / STANDARD_GRAVITY)
    assert axes[3].get_xscale() == "log"
    legend = " ".join(t.get_text() for t in axes[3].get_legend().get_texts())
    assert "isolated period T = 2.84 s" in legend and "effective period T_eff = 2.5 s" in legend


def test_response_page_energies_balance(pendulum_response):
    """Input = kinetic + potential + friction + viscous at every sample (the solver's exact energies)."""
    _, _, response = pendulum_response
    mass_kg = 1000.0
    fig = figures.new_figure(figsize=(8.27, 11.69))
    energies = figures.response_page(fig, response, mass_kg, slip_intervals(response))
    stored = energies["kinetic + potential"]
    residual = energies["input"] - energies["friction"] - energies["viscous"] - stored
    assert np.abs(residual).max() <= 1e-9 * energies["input"].max()
    assert energies["friction"][-1] > 0 and energies["viscous"][-1] > 0
    # the hysteresis loop is the isolator force -M a_abs against X
    loop = fig.axes[3].get_lines()[0]
    force_kN = -mass_kg * response.absolute_acceleration_m_s2 / 1e3
    assert np.abs(loop.get_ydata()).max() == pytest.approx(np.abs(force_kN).max())
    assert fig.axes[3].get_title() == "Force-displacement loop"


def test_regime_labels_sit_inside_their_regions(tmp_path, monkeypatch):
    monkeypatch.setenv("ISOLATOR_CACHE_DIR", str(tmp_path))
    rmap = regime_map(0.5, 0.25, k_range=(0.0, 2.0), alpha_range=(0.0, 6.0), n_k=12, n_alpha=12, workers=1)
    fig = figures.new_figure(figsize=(9.0, 5.6))
    ax = fig.add_subplot()
    handles = figures.draw_regime_map(ax, rmap, design_point=(0.5, 3.0, "design"), triple=(2.417, 0.389))
    names = [h.get_label() for h in handles]
    assert "ST | SS boundary (α = 1)" in names and "design" in names and any("triple point" in n for n in names)
    labels = [t for t in ax.texts if t.get_text() in ("ST", "SS", "SL")]
    assert {t.get_text() for t in labels} == {name for code, name in enumerate(("ST", "SS", "SL"))
                                              if (rmap.regime == code).any()}
    for text in labels:  # each regime's name is placed on a grid point of that regime
        k, alpha = text.get_position()
        assert rmap.regime_at(alpha, k) == text.get_text()


def test_amplitude_curve_caps_the_axis_and_marks_what_it_cuts():
    alphas = np.linspace(1.1, 6.0, 50)
    amplitudes = np.full(50, 0.8)
    amplitudes[10] = 500.0  # one near-resonant point
    steady = np.ones(50, bool)
    steady[20] = False  # one point of unbounded growth
    regimes = np.where(alphas < 2.0, 1, 2)
    fig = figures.new_figure(figsize=(6.0, 4.0))
    ax = fig.add_subplot()
    figures.draw_amplitude_curve(ax, alphas, amplitudes, regimes, steady=steady, alpha_record=3.0,
                                 amplitude_record=1.4, k=0.1, eta=0.0)
    top = ax.get_ylim()[1]
    assert 1.4 < top < 500.0  # the record's A is visible, the outlier is not allowed to squash the curve
    labels = {line.get_label(): line for line in ax.get_lines()}
    assert labels["A above the axis"].get_xdata()[0] == alphas[10]
    assert labels["resonant growth (unbounded A)"].get_xdata()[0] == alphas[20]
    assert "record A = 1.4" in labels
