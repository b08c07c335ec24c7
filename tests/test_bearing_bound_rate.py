"""A property bound λ re-reads a series bearing's µ(v) by the reader's rules (Bearing.with_friction_factor).

Session 14 made the bound re-check the slope at rest λ a (µ_fast − µ_slow) against MIN_RATE_SLOPE_S_PER_M; two
things were left (note14, "Noticed, left alone"): the refusal's hint was the reader's "(give 'mu' = mu_slow)", which
does not fit a design that reads at λ = 1, and the re-check took every surface with a rate as µ(v), so a flat law
(mu_slow = mu_fast, which the reader reads as constant friction) was refused at every bound, λ = 1 included.
"""

from __future__ import annotations

import math

import pytest

from isolator.bearing import MIN_RATE_SLOPE_S_PER_M, parse_bearing
from isolator.errors import DesignError

#: Fenz & Constantinou's triple pendulum with µ(v) of slope a (µ_fast − µ_slow) = 1.1 × 1e-3 per m/s on every
#: surface (tests/test_hostile_s14.py's edge law)
EDGE = [(2.1, 0.059, 0.06, 0.4), (0.3, 0.019, 0.02, 0.05), (0.3, 0.019, 0.02, 0.05), (2.1, 0.099, 0.10, 0.4)]


def _triple(surfaces, rate=1.1):
    return parse_bearing({"type": "triple", "surface": [
        dict(radius_m=r, mu_slow=slow, mu_fast=fast, rate_s_per_m=rate, displacement_capacity_m=d)
        for r, slow, fast, d in surfaces]}, DesignError)


def test_a_bound_below_the_slope_floor_says_which_bound_keeps_the_law():
    bearing = _triple(EDGE)
    with pytest.raises(DesignError) as refused:
        bearing.with_friction_factor(0.85)
    message = str(refused.value)
    assert "= 0.000935 per m/s at rest, below 0.001" in message
    # the smallest λ that keeps 1.1e-3 λ ≥ 1e-3 is 1/1.1 = 0.90909…, printed rounded up so that it reads
    assert "(the design's own slope 0.0011 stays above 0.001 for λ >= 0.91: give a lower bound" in message
    assert "give 'mu' = mu_slow" not in message
    assert math.ceil(MIN_RATE_SLOPE_S_PER_M / 1.1e-3 * 1e3) / 1e3 == 0.91
    scaled = bearing.with_friction_factor(0.91)  # the λ the line gives reads
    assert [s.rate_s_per_m * (s.mu_fast - s.mu_slow) for s in scaled.surfaces] == pytest.approx([1.001e-3] * 4)
    with pytest.raises(DesignError, match="below 0.001"):
        bearing.with_friction_factor(0.909)


def test_the_design_as_read_keeps_the_readers_hint():
    flat = [(r, fast - 0.9e-3, fast, d) for r, _, fast, d in EDGE]  # slope 0.99e-3
    with pytest.raises(DesignError, match=r"cannot invert it \(give 'mu' = mu_slow\)$"):
        _triple(flat)


def test_a_flat_law_read_as_constant_friction_stays_so_at_every_bound():
    """mu_slow = mu_fast with a rate: the reader reads it (constant friction); main refused it at λ = 0.9, 1, 1.2
    ("µ(v) rises by … = 0 per m/s at rest")."""
    flat = [(r, fast, fast, d) for r, _, fast, d in EDGE]
    bearing = _triple(flat, rate=50.0)
    for factor in (0.9, 1.0, 1.2):
        scaled = bearing.with_friction_factor(factor)
        assert [s.mu_kinetic for s in scaled.surfaces] == pytest.approx([factor * f for _, _, f, _ in flat])
        assert all(s.mu_slow == s.mu_fast for s in scaled.surfaces)
