"""The rigid block's implicit steps at a tight tolerance, and the building's anisotropic steps leaving the ultimate (``2d-multisurface`` with method "steps", ``2d-building-multisurface`` with
floors that differ along x and y); docs/multisurface.md and docs/building.md, h225's sections.

The truth: the exact 1-D models (``1d-multisurface``, ``1d-building-multisurface``: event-driven closed forms) on the
same record along x, the second component zero.  IELC's double [(2.5, 0.04, 0.3), (1.5, 0.07, 0.3)] (h174's case).
"""

from __future__ import annotations

import numpy as np

from isolator.motion.pair import read_ground_motion_pair
from isolator.solver.building_multisurface import simulate_building_bearing
from isolator.solver.multisurface import simulate_bearing
from isolator.solver.planar_building_multisurface import simulate_building_bearing_pair
from isolator.solver.planar_multisurface import simulate_bearing_pair
from isolator.superstructure import Floor, Superstructure
from tests.solver.test_building_multisurface import bearing

G = 9.80665
DOUBLE = [(2.5, 0.04, 0.3), (1.5, 0.07, 0.3)]
DAMPING = 5e4 / 6e5  # IELC's dashpot per unit of the total mass [1/s]


def _push_hold_ease(push_g, push_s, hold_g, end_s):
    """The ground at −push_g g for push_s s, then −hold_g g, easing at 0.4 g/s from push_s + 1 s (0.005 s samples)."""
    dt = 0.005
    t = np.arange(0.0, end_s + dt / 2, dt)
    return np.where(t < push_s, -push_g * G, -hold_g * G + 0.4 * G * np.clip(t - push_s - 1.0, 0.0, None)), dt


def test_a_tight_step_tol_takes_no_floor_steps_on_a_small_slide(records_dir):
    # N. California 89146 ×1.5, 8 s from 1 s before its peak (a 2 mm slide): at step_tol 3e-10 the displacement's
    # error scale step_tol × the floor fell below the rounding of the groups' slips before the first slides, and
    # 141,017 steps were accepted at the floor (1,130,359 steps on c765efa; 377,862 here, none at the floor)
    pair = read_ground_motion_pair(records_dir / "pairs" / "ncalifornia2012_89146" / "CE89146.V2", trim=True)
    a = np.asarray(pair.x.acceleration_m_s2, dtype=float)
    i0 = int(np.argmax(np.abs(a))) - int(round(1.0 / pair.dt_s))
    acc = 1.5 * a[i0:i0 + int(round(8.0 / pair.dt_s)) + 1]
    b = bearing("double", DOUBLE)
    exact = simulate_bearing(acc, pair.dt_s, bearing=b, damping_per_mass=DAMPING)
    plane = simulate_bearing_pair(acc, 0.0 * acc, pair.dt_s, bearing=b, damping_per_mass=DAMPING, method="steps",
                                  step_tol=3e-10)
    peak = exact.peak_displacement_m
    # measured 3.66 × step_tol (3.67 on c765efa)
    assert np.max(np.abs(plane.displacement_m[:, 0] - exact.displacement_m)) <= 6.0 * 3e-10 * peak
    assert plane.n_steps_at_floor == 0
    assert plane.n_steps <= 600_000


def _anisotropic(push_g, push_s, hold_g, end_s):
    """IELC's one-story building on the double, pushed along x by :func:`_push_hold_ease`: the exact 1-D building with
    the x stiffness (the truth) and the 2-D building whose story is half as stiff along y (step_tol 1e-8)."""
    acc, dt = _push_hold_ease(push_g, push_s, hold_g, end_s)
    b = bearing("double", DOUBLE)
    one = Superstructure(floors=(Floor(4e5, 3.5, 3e8, 3e8),), damping_ratio=0.05, gravity_m_s2=G)
    two = Superstructure(floors=(Floor(4e5, 3.5, 3e8, 1.5e8),), damping_ratio=0.05, gravity_m_s2=G)
    exact = simulate_building_bearing(acc, dt, superstructure=one, bearing=b, total_mass_kg=6e5, damping_Ns_per_m=5e4)
    plane = simulate_building_bearing_pair(acc, 0.0 * acc, dt, superstructure=two, bearing=b, total_mass_kg=6e5,
                                           damping_Ns_per_m=5e4, step_tol=1e-8)
    return exact, plane, [exact.EVENT_NAMES[k] for k in exact.event_kind], exact.peak_displacement_m


def test_an_anisotropic_building_leaves_the_ultimate_inward_as_the_exact_1d_building():
    # h220's second case (IELC's one-story building pushed to the double's ultimate, left inward from rest at 0.898 s)
    # with the story's stiffness along y half that along x: the anisotropic steps, whose velocity was turned onto the
    # ultimate circle's tangent in every step while the groups' slips were below their rims' rounding; on c765efa the
    # work bound at 0.898132 s.  The truth along x: the exact 1-D building with the x stiffness
    exact, plane, kinds, peak = _anisotropic(0.3, 0.5, 0.16, 1.2)
    assert "ultimate" in kinds and kinds[kinds.index("ultimate") + 1] == "breakaway"
    # measured 8.5e-9 of the peak (the isotropic building's: the same)
    assert np.max(np.abs(plane.displacement_m[:, 0] - exact.displacement_m)) <= 2e-8 * peak
    assert np.max(np.abs(plane.displacement_m[:, 1])) <= 1e-12 * peak


def test_an_anisotropic_building_leaves_a_rim_inward_as_the_exact_1d_building():
    # h220's first case (the first group held on its rim from 1.459 s, its force leaving the friction circle inward at
    # 1.494 s: it leaves the rim from rest) with the story's stiffness along y half that along x: the anisotropic steps
    # ran without be_step's ``block`` (its step without slip took V = h A for unit masses only), so the first slips,
    # below the rim test's rounding, were turned back onto the rim's tangent in every step; on int25 (de0a704) the work
    # bound at 1.49439 s.  The truth along x: the exact 1-D building with the x stiffness
    exact, plane, kinds, peak = _anisotropic(0.2, 0.3, 0.1, 1.8)
    assert kinds[-2:] == ["stick", "breakaway"] and 1.45 < exact.event_time_s[-1] < 1.5
    assert exact.displacement_m[-1] < peak - 0.04  # it went back inward
    # measured 1.66e-9 of the peak
    assert np.max(np.abs(plane.displacement_m[:, 0] - exact.displacement_m)) <= 5e-9 * peak
    assert np.max(np.abs(plane.displacement_m[:, 1])) <= 1e-12 * peak
