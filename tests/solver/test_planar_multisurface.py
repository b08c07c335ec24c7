"""The 2-D multi-surface model (double and triple friction pendulums in the plane).

Truths: the exact 1-D model ``1d-multisurface`` (a pair whose second component is zero, and a
collinear pair rotated), the planar single pendulum ``simulate_pair`` (a double with equal
friction is one pendulum of radius R1 + R2), rotation invariance, the energy balance.
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.bearing import parse_bearing
from isolator.errors import DesignError, SolverError
from isolator.solver.multisurface import simulate_bearing
from isolator.solver.planar import simulate_pair
from isolator.solver.planar_multisurface import element_groups, simulate_bearing_pair

G = 9.80665


def bearing(kind, surfaces):
    return parse_bearing({"type": kind, "surface": [
        {"radius_m": r, "mu": m, "displacement_capacity_m": d} for r, m, d in surfaces]}, DesignError)


TFP = bearing("triple", [(2.1, 0.06, 0.4), (0.3, 0.02, 0.05), (0.3, 0.02, 0.05), (2.1, 0.10, 0.4)])
#: a triple whose four surfaces have four frictions (no groups: every join is a corner of two circles)
TFP4 = bearing("triple", [(2.1, 0.07, 0.4), (0.3, 0.02, 0.05), (0.35, 0.03, 0.06), (2.1, 0.10, 0.4)])


def pulse_pair(ax_g=0.25, ay_g=0.2, dt=0.01, duration=10.0, until=4.0):
    t = np.arange(0.0, duration, dt)
    on = t < until
    return 0.0 + ax_g * G * np.sin(2 * np.pi * t / 2.0) * on, ay_g * G * np.cos(2 * np.pi * t / 1.7) * on, dt


def rotate(a, b, theta):
    c, s = np.cos(theta), np.sin(theta)
    return c * a - s * b, s * a + c * b


def test_groups_of_equal_friction():
    rb, mu, rim, members = element_groups(TFP)
    np.testing.assert_allclose(rb, [1.8, 0.6, 1.8])
    np.testing.assert_allclose(mu, [0.06, 0.02, 0.10])
    assert [int(g) for g in members[:, 0]] == [0, 1, 1, 2]


@pytest.mark.parametrize("b", [TFP, TFP4], ids=["tfp", "tfp-4-frictions"])
def test_zero_second_component_is_the_1d_model(b):
    t = np.arange(0.0, 12.0, 0.01)
    acc = 0.25 * G * np.sin(2 * np.pi * t / 2.0) * (t < 3.0)
    one = simulate_bearing(acc, 0.01, bearing=b)
    two = simulate_bearing_pair(acc, np.zeros_like(acc), 0.01, bearing=b)
    peak = one.peak_displacement_m
    assert set(one.regimes) >= {"I", "II", "III"}
    assert abs(two.peak_displacement_m - peak) <= 1e-9 * peak
    assert np.max(np.abs(two.displacement_m[:, 0] - one.displacement_m)) <= 1e-9 * peak
    assert np.all(two.displacement_m[:, 1] == 0.0)
    assert list(two.regimes) == list(one.regimes)
    for name in one.regimes:
        assert abs(two.regimes[name] - one.regimes[name]) <= 1e-9
    np.testing.assert_allclose(two.surface_peak_displacement_m, one.surface_peak_displacement_m, rtol=0, atol=1e-9)
    assert abs(two.energy_balance_error_J_per_kg) <= 1e-9 * two.energy_input_J_per_kg
    # the same collinear record along other azimuths: the tangent circles are found through rounding
    for degrees in (35.0, 123.0):
        theta = np.radians(degrees)
        rot = simulate_bearing_pair(np.cos(theta) * acc, np.sin(theta) * acc, 0.01, bearing=b)
        assert abs(rot.peak_displacement_m - peak) <= 1e-9 * peak
        along = rot.displacement_m[:, 0] * np.cos(theta) + rot.displacement_m[:, 1] * np.sin(theta)
        assert np.max(np.abs(along - one.displacement_m)) <= 1e-9 * peak
        assert list(rot.regimes) == list(one.regimes)


@pytest.mark.parametrize("b", [TFP, TFP4], ids=["tfp", "tfp-4-frictions"])
def test_rotation_invariance_and_energy_balance_in_the_plane(b):
    ax, ay, dt = pulse_pair()
    res = simulate_bearing_pair(ax, ay, dt, bearing=b)
    assert set(res.regimes) >= {"I", "II", "III"}  # the corners of two and three circles are reached
    assert abs(res.energy_balance_error_J_per_kg) <= 1e-9 * res.energy_input_J_per_kg
    theta = 0.7
    rx, ry = rotate(ax, ay, theta)
    rot = simulate_bearing_pair(rx, ry, dt, bearing=b)
    x = np.column_stack(rotate(res.displacement_m[:, 0], res.displacement_m[:, 1], theta))
    peak = res.peak_displacement_m
    assert np.max(np.abs(x - rot.displacement_m)) <= 1e-9 * peak
    assert abs(rot.peak_displacement_m - peak) <= 1e-9 * peak
    # mirror y -> -y
    mir = simulate_bearing_pair(ax, -ay, dt, bearing=b)
    assert np.max(np.abs(mir.displacement_m[:, 1] + res.displacement_m[:, 1])) <= 1e-9 * peak


def test_double_with_equal_friction_is_the_single_pendulum_of_summed_radius():
    dbl = bearing("double", [(1.5, 0.05, 0.5), (2.5, 0.05, 0.5)])
    ax, ay, dt = pulse_pair()
    res = simulate_bearing_pair(ax, ay, dt, bearing=dbl)
    ref = simulate_pair(ax, ay, dt, mu_static=0.05, radius_m=4.0)
    peak = ref.peak_displacement_m
    assert abs(res.peak_displacement_m - peak) <= 1e-9 * peak
    assert np.max(np.abs(res.displacement_m - ref.displacement_m)) <= 1e-9 * peak
    assert abs(res.peak_velocity_m_s - ref.peak_velocity_m_s) <= 1e-9 * ref.peak_velocity_m_s
    # each surface carries its share R_i / (R1 + R2) of the displacement
    assert res.surface_peak_displacement_m[0] / res.surface_peak_displacement_m[1] == pytest.approx(1.5 / 2.5,
                                                                                                   rel=1e-9)


def test_a_rim_contact_is_refused_with_its_time():
    ax, ay, dt = pulse_pair(0.6, 0.5)
    with pytest.raises(SolverError, match=r"reaches a rim at t = [0-9.]+ s"):
        simulate_bearing_pair(ax, ay, dt, bearing=TFP)


def test_registry_runs_the_2d_model_for_a_pair_and_refuses_a_vertical():
    from isolator.errors import RecordInputError
    from isolator.solver.models import Scene, select_model, simulate

    class _Design:
        bearing = TFP
        superstructure = None
        source = "tfp.toml"

    ax, ay, dt = pulse_pair(duration=6.0)
    scene = Scene(ax_m_s2=ax, ay_m_s2=ay, dt_s=dt, isolator={"mu_static": 0.06, "radius_m": 4.2}, design=_Design())
    name, reason = select_model(scene)
    assert name == "2d-multisurface" and "triple" in reason
    res = simulate(scene)
    direct = simulate_bearing_pair(ax, ay, dt, bearing=TFP)
    np.testing.assert_array_equal(res.displacement_m, direct.displacement_m)
    summary = res.summary()
    for key in ("surface_peak_displacement_m", "regimes", "n_rim_contacts", "ultimate_displacement_reached",
                "peak_displacement_m", "peak_transmitted_acceleration_m_s2"):
        assert key in summary
    vertical = Scene(ax_m_s2=ax, ay_m_s2=ay, az_m_s2=0.1 * ax, dt_s=dt, isolator={}, design=_Design())
    assert select_model(vertical)[0] == "2d-multisurface+vertical"
    with pytest.raises(RecordInputError, match="vertical component is not modelled"):
        simulate(vertical)
