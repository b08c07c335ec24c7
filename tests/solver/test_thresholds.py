"""The one bisection of regime boundaries (isolator.solver.thresholds.bisect_change)."""

from __future__ import annotations

import math

import pytest

from isolator.solver.thresholds import MAX_BISECTIONS, bisect_change


def test_bisect_to_a_relative_tolerance():
    lo, hi = bisect_change(lambda x: x * x < 2.0, 1.0, 2.0, rel_tol=1e-12)
    assert lo < math.sqrt(2.0) <= hi and hi - lo <= 1e-12 * hi


def test_bisect_a_fixed_number_of_times():
    calls = []
    lo, hi = bisect_change(lambda x: calls.append(x) or x < 0.3, 0.0, 1.0, iterations=10)
    assert len(calls) == 10 and hi - lo == pytest.approx(2.0 ** -10) and lo < 0.3 <= hi


def test_bisect_is_bounded_and_needs_a_stopping_rule():
    calls = []
    bisect_change(lambda x: calls.append(x) or True, 0.0, 1.0, rel_tol=-1.0)  # a tolerance never met
    assert len(calls) == MAX_BISECTIONS
    with pytest.raises(ValueError):
        bisect_change(lambda x: True, 0.0, 1.0)
