"""Figures of a long record draw a bounded number of artists and vertices, and keep every peak."""

from __future__ import annotations

import time

import numpy as np
import pytest

from isolator.metrics import slip_intervals
from isolator.report import figures
from isolator.solver.record import simulate_record


def test_extreme_indices_keep_the_envelope_of_every_bucket():
    rng = np.random.default_rng(3)
    y = rng.standard_normal(1_000_003)
    index = figures.extreme_indices(500, y)
    assert index.size <= 2 * 500 + 4
    assert y[index].max() == y.max() and y[index].min() == y.min()
    length = y.size // 500
    for b in (0, 137, 499):  # each column spans the same range as the full data
        block = slice(b * length, (b + 1) * length)
        kept = index[(index >= b * length) & (index < (b + 1) * length)]
        assert y[kept].max() == y[block].max() and y[kept].min() == y[block].min()
    assert np.array_equal(figures.extreme_indices(500, y[:1000]), np.arange(1000))  # short: whole


def test_merge_intervals_closes_only_gaps_below_the_threshold():
    merged = figures.merge_intervals([[0, 1], [1.05, 2], [3, 4], [4.2, 5]], 0.1)
    np.testing.assert_array_equal(merged, [[0, 2], [3, 4], [4.2, 5]])
    assert figures.merge_intervals(np.zeros((0, 2)), 1.0).shape == (0, 2)


@pytest.mark.filterwarnings("error")
def test_response_page_of_a_long_record_with_many_slips_is_bounded():
    # 1.2 million samples of a ground motion that makes the block slip ~100,000 times
    n, dt = 1_200_000, 0.005
    t = np.arange(n) * dt
    acc = 1.3 * np.sin(2 * np.pi * 5.0 * t)  # just above µs g: two short slips per cycle
    response = simulate_record(acc, dt, mu_static=0.1, stiffness_per_mass=4.0)
    intervals = slip_intervals(response)
    assert intervals.shape[0] > 50_000
    fig = figures.new_figure(figsize=(8.27, 11.69))
    start = time.perf_counter()
    figures.response_page(fig, response, 1000.0, intervals)
    fig.savefig(__import__("io").BytesIO(), format="pdf")
    seconds = time.perf_counter() - start
    artists = sum(len(ax.get_children()) for ax in fig.axes)
    vertices = sum(line.get_xydata().shape[0] for ax in fig.axes for line in ax.get_lines())
    bars = sum(len(c.get_paths()) for ax in fig.axes for c in ax.collections)
    assert artists < 300 and vertices < 12 * (2 * figures.PIXELS_PER_AXIS + 4) and bars <= 3 * figures.PIXELS_PER_AXIS
    assert seconds < 30, seconds  # one axvspan per slip took minutes
    # the drawn displacement still reaches the exact peak
    assert max(abs(line.get_ydata()).max() for line in fig.axes[0].get_lines()) == pytest.approx(
        np.abs(response.displacement_m).max())
