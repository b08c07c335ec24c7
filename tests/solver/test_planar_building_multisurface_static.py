"""Static friction of a single pendulum under a building in the plane (``2d-building-multisurface``'s rim rerun).

The reference is independent of the implicit steps: the exact 1-D building on the single surface with its rim
(``1d-building-multisurface``, µs at rest and after every stop, µk sliding; itself checked against solve_ivp), for a
record along one line in the plane.  The bounds are those measured (docs/building.md, "Static friction in the
rerun") with a margin, at step_tol 1e-8.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.bearing import Bearing, Surface
from isolator.solver.building_multisurface import simulate_building_bearing
from isolator.solver.planar_building_multisurface import simulate_building_bearing_pair
from tests.solver.test_building import make_superstructure, real_segment

TOTAL = 7e5


def _single(mu_s, mu_k, capacity):
    return Bearing(kind="single", surfaces=(Surface(radius_m=2.5, height_m=0.0, mu_kinetic=mu_k, mu_static=mu_s,
                                                    displacement_capacity_m=capacity),))


def _rel(a, b):
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b))) / np.max(np.abs(b)))


def _runs(records_dir, scale, bearing, degrees, plane_bearing=None):
    acc, dt = real_segment(records_dir, "RSN1044_NORTHR_NWH360.AT2", 2.0, 6.0, scale)
    s = make_superstructure([3e5, 2e5], [4e8, 3e8], 0.05)
    ref = simulate_building_bearing(acc, dt, superstructure=s, bearing=bearing, total_mass_kg=TOTAL)
    c, sn = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    ours = simulate_building_bearing_pair(c * acc, sn * acc, dt, superstructure=s, total_mass_kg=TOTAL,
                                          bearing=bearing if plane_bearing is None else plane_bearing, step_tol=1e-8)
    return ref, ours, ours.displacement_m @ [c, sn], ours.displacement_m @ [-sn, c]


#: scale, µs, µk, capacity, degrees, history bound (measured 3.1e-8 / 2.0e-7 / 3.2e-5 of the peak at step_tol 1e-8)
CASES = {
    "µs 0.10 > µk 0.05, off the rim": (0.3, 0.10, 0.05, 0.5, 35.0, 1e-6),
    "µs 0.10 > µk 0.05, held at the capacity 4 times": (1.0, 0.10, 0.05, 0.15, 0.0, 2e-6),
    "µs = µk, held at the capacity 4 times": (1.0, 0.05, 0.05, 0.15, 0.0, 2e-4),
}


@pytest.mark.parametrize("name", list(CASES))
def test_a_record_along_one_line_is_the_exact_1d_building_with_static_friction(records_dir, name):
    scale, mu_s, mu_k, capacity, degrees, bound = CASES[name]
    ref, ours, along, across = _runs(records_dir, scale, _single(mu_s, mu_k, capacity), degrees)
    peak = ref.peak_displacement_m
    assert np.max(np.abs(across)) <= 1e-9 * peak
    assert _rel(along, ref.displacement_m) <= bound
    assert ours.residual_displacement_m == pytest.approx(abs(ref.residual_displacement_m), rel=100 * bound)
    assert ours.slip_time_s == pytest.approx(ref.slip_time_s, rel=1e-3)
    assert ours.ultimate_displacement_reached is ref.ultimate_displacement_reached is (capacity < 0.2)
    assert abs(ours.energy_balance_error_J_per_kg) <= 1e-7 * ours.energy_input_J_per_kg
    assert ours.energy_friction_J_per_kg == pytest.approx(ref.energy_friction_J_per_kg, rel=100 * bound)


def test_ignoring_static_friction_would_change_the_answer(records_dir):
    # the same scene run with µk only (what the rerun did before): off the 1-D building by far more than the bound
    bearing = _single(0.10, 0.05, 0.5)
    ref, ours, along, _ = _runs(records_dir, 0.3, bearing, 0.0)
    _, kinetic, along_k, _ = _runs(records_dir, 0.3, bearing, 0.0, plane_bearing=_single(0.05, 0.05, 0.5))
    assert _rel(along, ref.displacement_m) <= 1e-6
    assert _rel(along_k, ref.displacement_m) >= 1e-2  # measured 9.0e-2 of the peak
    assert abs(kinetic.residual_displacement_m - ours.residual_displacement_m) >= 1e-3  # 7.73 vs 4.28 mm
    assert kinetic.slip_time_s > 1.2 * ours.slip_time_s  # 2.97 vs 2.08 s


def test_the_registry_reruns_a_single_pendulum_with_its_static_friction(records_dir, tmp_path):
    # a design of µs 0.06 > µk 0.05 past its capacity: the pair's rerun (a zero second component) is the 1-D rerun
    from isolator.adapter import motion_keywords
    from isolator.design import Design
    from isolator.solver.models import Scene, simulate
    from tests.solver.test_planar_building_multisurface import SINGLE

    path = tmp_path / "single.toml"
    path.write_text(SINGLE.replace("mu_static = 0.05", "mu_static = 0.06"))
    design = Design.from_toml(path)
    assert design.mu_static == 0.06 and design.mu_kinetic == 0.05
    acc, dt = real_segment(records_dir, "RSN1044_NORTHR_NWH360.AT2", 2.0, 6.0, 1.0)
    kw = motion_keywords(design)
    one = simulate(Scene(ax_m_s2=acc, ay_m_s2=None, dt_s=dt, isolator=kw, design=design))
    two = simulate(Scene(ax_m_s2=acc, ay_m_s2=np.zeros_like(acc), dt_s=dt, isolator=kw, design=design))
    assert one.rerun and one.model == "1d-building-multisurface" and one.ultimate_displacement_reached
    assert two.rerun and two.model == "2d-building-multisurface" and "static friction at rest" in two.model_reason
    # at the registry's step_tol 1e-7: measured 2.8e-4 of the peak (4.5e-4 with µs = µk)
    assert _rel(two.displacement_m[:, 0], one.displacement_m) <= 1e-3
    assert two.peak_displacement_m == pytest.approx(one.peak_displacement_m, rel=1e-9)
