"""A building on a double or triple pendulum whose groups turn on their rims (``2d-building-multisurface``), h112.

A group held on its rim by the normal force and at its friction limit along the rim slides along it by a slip that
the step's Newton iteration must see as a smooth function of the force: for a short slip the closed form of the
element's problem on the circle (its tangential balance to first order in the turn) is the reference.  The scene
that the short slips stopped ("found no force") must answer, and balance.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.solver.planar_building_multisurface import simulate_building_bearing_pair
from isolator.solver.planar_multisurface_stepper import element_return
from tests.solver.test_building import make_superstructure, real_segment
from tests.solver.test_building_multisurface import bearing


@pytest.mark.parametrize("angle", [0.3, 2.0, -2.9])
def test_a_short_slip_along_the_rim_is_the_closed_form_of_its_tangential_balance(angle):
    # a group on its rim (ū = c̄ e), pushed outward (the rim holds it) and along the rim past its friction by x:
    # it turns by θ with r·t(θ) = µ q·t, t' = −e, q·t = 1 − O(θ²): c̄θ = c̄ x / (r·e) to first order in θ.
    # Before the chord's direction was taken from c̄ e(θ) − ū itself, rounded to ~ulp(c̄)/|δ| in its normal part,
    # the slip was 0.9-16 times this for slips of 1e-13 m, and it moved when r moved along e (the rim's reaction)
    rb, mu, rim = 2.0, 0.03, 0.03
    e = np.array([math.cos(angle), math.sin(angle)])
    t = np.array([-e[1], e[0]])
    u = rim * e
    push = 0.0557
    for excess in (2e-13, 5e-13, 1e-12, 1e-11, 1e-10, 1e-9):
        slips = []
        for normal in (0.0, 3e-13, -7e-13, 1.1e-12):
            r = (rim / rb + push + normal) * e + (mu + excess) * t
            d1, d2, *_, state = element_return(r[0], r[1], u[0], u[1], rb, mu, rim)
            assert state == 2
            w = u + np.array([d1, d2])
            assert abs(math.hypot(*w) - rim) <= 4e-17
            exact = rim * excess / (r @ e)
            slips.append(np.array([d1, d2]) @ t)
            assert slips[-1] == pytest.approx(exact, rel=2e-3, abs=3e-17)
        # the normal force is the rim's: it does not move the slip
        assert max(slips) - min(slips) <= 1e-3 * max(slips) + 3e-17


def test_a_double_with_an_intermediate_rim_answers_where_a_short_slip_on_its_rim_stopped_it(records_dir):
    # NWH360 2-8 s along x and the same reversed ×0.6 along y (its first 4 s), 2 stories on a double whose inner
    # surface has a 0.03 m rim: the slab slows to a near stop at 0.917 s with the inner group held on its rim at its
    # friction limit along it; refused before ("found no force at t = 0.917209 s")
    acc, dt = real_segment(records_dir, "RSN1044_NORTHR_NWH360.AT2", 2.0, 6.0, 1.0)
    ax = acc[:200].copy()
    ay = 0.6 * acc[::-1][:200].copy()
    s = make_superstructure([3e5, 2e5], [4e8, 3e8], 0.05)
    b = bearing("double", [(2.0, 0.03, 0.03), (2.0, 0.07, 0.3)])
    out = simulate_building_bearing_pair(ax, ay, dt, superstructure=s, bearing=b, total_mass_kg=7e5)
    assert np.all(np.isfinite(out.displacement_m))
    assert out.n_rim_contacts >= 1
    assert out.surface_peak_displacement_m[0] <= 0.03 * (1.0 + 1e-9)
    assert abs(out.energy_balance_error_J_per_kg) <= 1e-6 * out.energy_input_J_per_kg
    # the mirror y → −y mirrors the answer
    mirror = simulate_building_bearing_pair(ax, -ay, dt, superstructure=s, bearing=b, total_mass_kg=7e5)
    assert np.max(np.abs(mirror.displacement_m * [1.0, -1.0] - out.displacement_m)) <= 1e-9 * out.peak_displacement_m
