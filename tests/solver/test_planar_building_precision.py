"""The 2-D building's accuracy parameters as knobs (docs/building.md, h172): the fast sub-steps' friction truncation
``planar_building.FAST_TRUNC_EPS`` refused outside its measured range, and a looser value's answer within its
measured bound of the default's on a real pair (the end check FAST_CHECK = 1e-12 µk N bounds the sub-steps' friction
whatever the truncation: on the bench's PTS 0-20 s, 1e-10 ... 1e-2 moved the answer by 6e-14 ... 6.3e-13 of its
scale, and every looser value was slower — more sub-steps refused by that check)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.bench.building import FIXED_BASE_PERIOD_Y_S, building_case
from isolator.solver import planar_building

from .test_planar_building_fast_eps import _assert_within
from .test_planar_building_stops import _run_bench_pair, bench_pair  # noqa: F401 (fixture)


@pytest.mark.parametrize("value", (0.0, -1e-12, math.nan, math.inf, 1e-1, 1e-17))
def test_a_truncation_outside_the_measured_range_is_refused(monkeypatch, value):
    """≤ 0 or NaN the kernel would silently replace by its default; above 1e-2 or below 1e-16 it is not measured."""
    t = np.arange(200) * 0.01
    case = building_case("sine", 3.0 * np.sin(2 * np.pi * t), 0.01, acceleration_y_m_s2=2.0 * np.cos(3 * t),
                         period_y_s=FIXED_BASE_PERIOD_Y_S)
    monkeypatch.setattr(planar_building, "FAST_TRUNC_EPS", value)
    with pytest.raises(ValueError, match=r"FAST_TRUNC_EPS = .* is outside \(1e-16, 0\.01\)"):
        _run_bench_pair(case)


@pytest.mark.parametrize("value", (1e-8, 1e-2))
def test_a_looser_truncation_stays_within_its_measured_bound_of_the_default(bench_pair, monkeypatch, value):  # noqa: F811
    """PTS 0-4 s: the same events, histories, peaks and energies to 1e-12 of their scale (measured on 0-20 s: 1.0e-13
    at 1e-8, 2.1e-13 at 1e-2), and more sub-steps refused by the end check than at the default (why it is slower)."""
    base = _run_bench_pair(bench_pair)
    monkeypatch.setattr(planar_building, "FAST_TRUNC_EPS", value)
    loose = _run_bench_pair(bench_pair)
    _assert_within(loose, base, 1e-12)
    assert loose.n_fast_refused[1] > base.n_fast_refused[1]
