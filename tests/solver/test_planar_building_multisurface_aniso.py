"""Floors whose stiffness differs along x and y on a multi-surface bearing under a pair (``2d-building-multisurface``).

The slab's effective mass then differs per direction and the implicit step's dual Ψ has a diagonal metric
(planar_building_multisurface_kernel, planar_multisurface_stepper.be_step's m_x, m_y).  The references are
independent of it: the exact 1-D building on the series model (``1d-building-multisurface``) along x with the x
stiffness and along y with the y stiffness; the exact 2-D building on one pendulum of the summed radius
(``2d-building``, floors differing along x and y) for an equal-friction double under a real pair; the isotropic
step (g/µ_h, no metric) for floors that differ by 1e-12.  Bounds: measured (docs/building.md) with a margin.
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.solver.building_multisurface import simulate_building_bearing
from isolator.solver.planar_building import simulate_planar_building
from isolator.solver.planar_building_multisurface import simulate_building_bearing_pair
from isolator.superstructure import Floor, Superstructure
from tests.solver.test_building import real_segment
from tests.solver.test_building_multisurface import TFP_SMALL, bearing
from tests.solver.test_planar_building_multisurface import _pair_segment

G = 9.80665
MASSES = [3e5, 2e5]
K_X = [4e8, 3e8]
K_Y = [1.5e8, 0.8e8]


#: measured at step_tol 1e-8 (Superstition Hills PTS 7-12 s): the equal-friction double vs the 2-D building, history
#: 6.7e-9 of the peak, floors 5.5e-8, drifts 5.8e-8, base shear 3.5e-9, balance 5.0e-9 of the input
BOUNDS_2D = dict(history=1e-7, floors=1e-6)
#: the quarter turn (the TFP ×2 through its rims to the ultimate, step_tol 1e-7): history 1.6e-13, floors 3.0e-13,
#: drifts 3.4e-13, balance 1.5e-7 (at 1e-8: 8.4e-12, 6.4e-11, 1.9e-11).  With the steps' local error at HISTORY_SHARE
#: (0.5) of step_tol the turned run's steps part from the original's at 2.03 s (131 359 against 131 349 steps: a
#: decision at rounding taken the other way, not traced): history 2.4e-9, floors 7.1e-9, drifts 4.2e-9 — below the
#: steps' own error at 1e-7 (2e-7); main's constants at a local 5e-8 alone part too (1.1e-9 at 4.97 s; /tmp/h153/turn.py).
#: With the error norm on each plane difference's length (docs/building.md, "The error norm turned with the pair") the
#: two runs take the same 137 136 steps again: history 1.8e-13, floors 2.8e-13, drifts 1.2e-13 (the norm is symmetric
#: under the turn as the larger component was; the rounding-level decision at 2.03 s is not met on this step sequence)
BOUNDS_TURN = dict(history=1e-9, floors=1e-9)
#: k_y = k_x (1 + 1e-12) vs k_y = k_x (step_tol 1e-7): history 2.1e-13, floors 3.2e-13 (at 1e-8: 5.2e-11, 1.8e-10)
BOUNDS_NEAR = 1e-8


def _building(k_x, k_y, masses=MASSES):
    return Superstructure(floors=tuple(Floor(m, 3.5, a, b) for m, a, b in zip(masses, k_x, k_y, strict=True)),
                          damping_ratio=0.05, gravity_m_s2=G)


def _rel(a, b):
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b))) / np.max(np.abs(b)))


def test_a_record_along_x_or_y_is_the_1d_building_with_that_directions_stiffness(records_dir):
    # NWH360 2-6 s on a double with an intermediate rim (3 rim contacts); measured at step_tol 1e-8: history
    # 3.3e-6 / 2.9e-6 of the peak, floors 4.0e-5 / 2.5e-5, balance 4.2e-8 / 2.8e-8 of the input (along x / y)
    acc, dt = real_segment(records_dir, "RSN1044_NORTHR_NWH360.AT2", 2.0, 4.0, 1.0)
    b = bearing("double", [(2.0, 0.03, 0.03), (2.0, 0.07, 0.3)])
    s = _building(K_X, K_Y)
    zero = np.zeros_like(acc)
    for d, k in ((0, K_X), (1, K_Y)):
        ref = simulate_building_bearing(acc, dt, superstructure=_building(k, k), bearing=b, total_mass_kg=7e5)
        pair = (acc, zero) if d == 0 else (zero, acc)
        ours = simulate_building_bearing_pair(*pair, dt, superstructure=s, bearing=b, total_mass_kg=7e5,
                                              step_tol=1e-8)
        assert np.max(np.abs(ours.displacement_m[:, 1 - d])) == 0.0
        assert _rel(ours.displacement_m[:, d], ref.displacement_m) <= 2e-5
        assert _rel(ours.floor_displacement_m[:, :, d], ref.floor_displacement_m) <= 2e-4
        assert ours.story_drift_m == pytest.approx(ref.story_drift_m, rel=5e-4)
        assert ours.n_rim_contacts == ref.n_rim_contacts > 0
        assert abs(ours.energy_balance_error_J_per_kg) <= 1e-6 * ours.energy_input_J_per_kg
    # the two directions' answers differ (the floors do): the test above is not the same run twice
    assert not np.allclose(simulate_building_bearing(acc, dt, superstructure=_building(K_X, K_X), bearing=b,
                                                     total_mass_kg=7e5).story_drift_m, ref.story_drift_m, rtol=0.1)


@pytest.fixture(scope="module")
def pts(records_dir):
    ax, ay, dt = _pair_segment(records_dir)
    return ax, ay, dt


def test_an_equal_friction_double_is_the_2d_building_with_floors_differing_along_x_and_y(pts):
    ax, ay, dt = pts
    s = _building(K_X, K_Y)
    b = bearing("double", [(1.5, 0.05, 2.0), (1.0, 0.05, 2.0)])
    ours = simulate_building_bearing_pair(ax, ay, dt, superstructure=s, bearing=b, total_mass_kg=7e5, step_tol=1e-8)
    ref = simulate_planar_building(ax, ay, dt, superstructure=s, total_mass_kg=7e5, stiffness_N_per_m=7e5 * G / 2.5,
                                   mu_static=0.05, mu_kinetic=0.05, pendulum=True)
    # measured at step_tol 1e-8: see BOUNDS_2D
    assert _rel(ours.displacement_m, ref.displacement_m) <= BOUNDS_2D["history"]
    assert _rel(ours.floor_displacement_m, ref.floor_displacement_m) <= BOUNDS_2D["floors"]
    assert ours.story_drift_m == pytest.approx(ref.story_drift_m, rel=BOUNDS_2D["floors"])
    assert ours.base_shear_coefficient == pytest.approx(ref.base_shear_coefficient, rel=BOUNDS_2D["floors"])
    assert ours.energy_input_J_per_kg == pytest.approx(ref.energy_input_J_per_kg, rel=BOUNDS_2D["floors"])
    assert abs(ours.energy_balance_error_J_per_kg) <= 1e-6 * ours.energy_input_J_per_kg


def _on_tfp(pts, k_x, k_y, quarter=False):
    # the pair ×2 on the small TFP (through its rims to the ultimate), turned by a quarter if asked
    ax, ay, dt = pts
    x, y = (2.0 * ay, -2.0 * ax) if quarter else (2.0 * ax, 2.0 * ay)
    return simulate_building_bearing_pair(x, y, dt, superstructure=_building(k_x, k_y),
                                          bearing=bearing("triple", TFP_SMALL), total_mass_kg=7e5, step_tol=1e-7)


def test_a_quarter_turn_swaps_the_directions(pts):
    # the building turned by 90° (x' = y, y' = −x: the stiffnesses swap) under the pair turned with it
    one = _on_tfp(pts, K_X, K_Y)
    turned = _on_tfp(pts, K_Y, K_X, quarter=True)
    back = np.column_stack((-turned.displacement_m[:, 1], turned.displacement_m[:, 0]))
    assert one.ultimate_displacement_reached and one.n_rim_contacts > 0
    assert _rel(back, one.displacement_m) <= BOUNDS_TURN["history"]
    floors = np.stack((-turned.floor_displacement_m[:, :, 1], turned.floor_displacement_m[:, :, 0]), axis=2)
    assert _rel(floors, one.floor_displacement_m) <= BOUNDS_TURN["floors"]
    assert turned.story_drift_m == pytest.approx(one.story_drift_m, rel=BOUNDS_TURN["floors"])
    for out in (one, turned):
        assert abs(out.energy_balance_error_J_per_kg) <= 1e-6 * out.energy_input_J_per_kg


def test_floors_nearly_the_same_along_x_and_y_give_the_isotropic_step(pts):
    # k_y = k_x (1 + 1e-12) takes the metric's Newton, k_y = k_x the closed isotropic step: the same answer
    iso = _on_tfp(pts, K_X, K_X)
    near = _on_tfp(pts, K_X, [k * (1 + 1e-12) for k in K_X])
    assert iso.ultimate_displacement_reached
    assert _rel(near.displacement_m, iso.displacement_m) <= BOUNDS_NEAR
    assert _rel(near.floor_displacement_m, iso.floor_displacement_m) <= BOUNDS_NEAR
