"""A shear building on a double or triple friction pendulum under a pair and a vertical
(``2d-building-multisurface+vertical``).

Every surface carries N = M n(t), n = g + a_z (the floors and the slab move with the ground vertically; the floors
are horizontal shear springs the vertical does not load); the implicit steps take n at each step's mean and book
the vertical's work; the bearings' axial loads take the vertical's share P_k,g a_z/g.  Truths: a_z ≡ 0 (bitwise the
run without a vertical), a constant a_z = c (exactly the run with g' = g + c, the bearings' loads shifted by
P_k,g c/g), the exact 2-D building on one pendulum of the summed radius with the same vertical (``2d-building``: a
double of equal friction), the energy balance with the vertical's work, the lift-off refused, the CLI.  The Loma
Prieta APEEL2 pair and its vertical are bundled with the example suite.
"""

from __future__ import annotations

import functools
import json

import numpy as np
import pytest

from isolator.errors import SolverError
from isolator.solver.planar_building import simulate_planar_building
from isolator.solver.planar_building_multisurface import simulate_building_bearing_pair
from isolator.superstructure import BearingLayout
from tests.solver.test_building import make_superstructure
from tests.solver.test_building_multisurface import bearing
from tests.solver.test_planar_building_multisurface import DESIGN as BUILDING_ON_SMALL_TFP
from tests.solver.test_planar_multisurface_vertical import TFP, apeel2

G = 9.80665
FLOORS = make_superstructure([3e5, 2.5e5, 2e5], [6e8, 4.5e8, 3e8], 0.05)
MASS = 1.0e6
LAYOUT = BearingLayout(x_m=(-6.0, 6.0, 6.0, -6.0), y_m=(-4.0, -4.0, 4.0, 4.0), gravity_loads_N=(MASS * G / 4,) * 4)


@functools.cache
def segment(start_s=2.0, end_s=12.0):
    """(ax, ay, az, dt) of APEEL2's strong part (its peak horizontal at 6.9 s, |a_z| up to 0.85 m/s²)."""
    ax, ay, az, dt = apeel2(until_s=end_s)
    i0 = int(round(start_s / dt))
    return ax[i0:], ay[i0:], az[i0:], dt


def run(bearing_, az=None, end_s=12.0, **kw):
    ax, ay, _, dt = segment(end_s=end_s)
    kw.setdefault("step_tol", 1e-7)
    return simulate_building_bearing_pair(ax, ay, dt, superstructure=FLOORS, bearing=bearing_, total_mass_kg=MASS,
                                          az_m_s2=az, **kw)


def _rel(a, b):
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b))) / np.max(np.abs(b)))


#: the identities below hold sample by sample, so they are checked on 2–8 s of APEEL2: the flat run reaches regimes
#: I–III (III at 7.25 s) and its peak (0.1644 m, the same as on 2–12 s) there, at 0.69 of the CPU (docs/performance.md,
#: h223)
IDENTITY_END_S = 8.0


def test_a_zero_vertical_is_bitwise_no_vertical_and_a_constant_one_is_a_run_with_g_plus_it():
    end = IDENTITY_END_S
    flat = run(TFP, bearing_layout=LAYOUT, end_s=end)
    zero = run(TFP, np.zeros_like(segment(end_s=end)[0]), bearing_layout=LAYOUT, end_s=end)
    assert flat.model == "2d-building-multisurface" and zero.model == "2d-building-multisurface+vertical"
    assert list(flat.regimes) == ["I", "II", "III"]  # the window holds the regimes of the whole 2–12 s
    for key in ("displacement_m", "velocity_m_s", "floor_displacement_m", "force_per_weight", "isolator_force_N",
                "energy_history_J_per_kg", "peak_resultants", "signed_max", "signed_min"):
        assert np.array_equal(getattr(flat, key), getattr(zero, key)), key
    assert zero.energy_balance_error_J_per_kg == flat.energy_balance_error_J_per_kg
    # n = g + c throughout: the run with g' = g + c (g is a parameter of the model), the bearings' loads shifted by
    # the vertical's share P_k,g c/g at every instant (so their extremes too)
    c = 0.7
    up = run(TFP, np.full_like(segment(end_s=end)[0], c), bearing_layout=LAYOUT, end_s=end)
    heavier = run(TFP, gravity_m_s2=G + c, bearing_layout=LAYOUT, end_s=end)
    assert up.model == "2d-building-multisurface+vertical"
    for key in ("displacement_m", "velocity_m_s", "floor_displacement_m", "force_per_weight", "isolator_force_N",
                "energy_history_J_per_kg", "peak_resultants"):
        assert np.array_equal(getattr(up, key), getattr(heavier, key)), key
    assert up.energy_balance_error_J_per_kg == heavier.energy_balance_error_J_per_kg
    share = MASS * G / 4 * c / G
    assert np.allclose(up.signed_max[2:], heavier.signed_max[2:] + share, rtol=1e-12, atol=0.0)
    assert np.allclose(up.signed_min[2:], heavier.signed_min[2:] + share, rtol=1e-12, atol=0.0)
    assert np.array_equal(up.signed_max[:2], heavier.signed_max[:2])  # the moments carry none of it
    # and the vertical matters: a TFP heavier by c is another answer
    assert _rel(up.displacement_m, flat.displacement_m) > 1e-3


def test_an_equal_friction_double_under_a_vertical_is_the_2d_building_on_one_pendulum_of_the_summed_radius():
    ax, ay, az, dt = segment()
    dbl = bearing("double", [(1.5, 0.05, 2.0), (1.0, 0.05, 2.0)])
    ref = simulate_planar_building(ax, ay, dt, superstructure=FLOORS, total_mass_kg=MASS,
                                   stiffness_N_per_m=MASS * G / 2.5, mu_static=0.05, mu_kinetic=0.05, pendulum=True,
                                   az_m_s2=az, bearing_layout=LAYOUT)
    assert ref.model == "2d-building"
    peak = ref.peak_displacement_m
    for tol, bound in ((1e-7, 1e-6), (1e-8, 1e-7)):
        ours = run(dbl, az, step_tol=tol, bearing_layout=LAYOUT)
        assert ours.model == "2d-building-multisurface+vertical" and "vertical" in ours.model_reason
        # measured (2–12 s of APEEL2, peak 0.175 m): at step_tol 1e-7 / 1e-8 the slab's history 1.9e-7 / 1.2e-8 of
        # its peak, the floors' 2.5e-6 / 2.7e-7, the drifts 4.4e-6 / 3.0e-8, the balance 1.8e-7 / 1.9e-8 of the input
        assert _rel(ours.displacement_m, ref.displacement_m) <= bound
        assert _rel(ours.floor_displacement_m, ref.floor_displacement_m) <= 10 * bound
        assert ours.peak_displacement_m == pytest.approx(peak, rel=bound)
        assert ours.story_drift_m == pytest.approx(ref.story_drift_m, rel=50 * bound)
        assert ours.base_shear_coefficient == pytest.approx(ref.base_shear_coefficient, rel=bound)
        assert ours.energy_input_J_per_kg == pytest.approx(ref.energy_input_J_per_kg, rel=bound)
        # the balance with the vertical's work in the input (the steps' own dissipation, ∝ step_tol)
        assert abs(ours.energy_balance_error_J_per_kg) <= 5 * tol * ours.energy_input_J_per_kg
        # the bearings' axial loads with the vertical's share, as the 2-D building's (its extremes located exactly,
        # ours at the steps' ends and the watch points): measured 8.1e-8 / 8.7e-9 (the vertical's share 53 kN of 2.5 MN)
        mine, theirs = ours.bearing_loads(), ref.bearing_loads()
        for key in ("bearing_axial_load_max_N", "bearing_axial_load_min_N"):
            assert mine[key] == pytest.approx(theirs[key], rel=bound), key
    # without the vertical the answer is another
    flat = run(dbl, step_tol=1e-7)
    assert _rel(flat.displacement_m, ref.displacement_m) > 1e-3


def test_the_bearing_lifting_off_is_refused_in_one_line():
    ax, _, _, dt = segment()
    az = np.zeros_like(ax)
    az[100] = -1.2 * G
    with pytest.raises(SolverError, match=r"lifts off at t = 0\.5 s .*not modelled") as err:
        run(TFP, az)
    assert "\n" not in str(err.value)


def test_the_registry_chooses_it_for_a_pair_and_a_vertical_and_says_so(tmp_path):
    from isolator.adapter import motion_keywords
    from isolator.design import Design
    from isolator.solver.models import Scene, select_model, simulate

    path = tmp_path / "tfp_building.toml"
    path.write_text(DESIGN)
    design = Design.from_toml(path)
    ax, ay, az, dt = segment(2.0, 5.0)
    scene = Scene(ax_m_s2=ax, ay_m_s2=ay, az_m_s2=az, dt_s=dt, isolator=motion_keywords(design), design=design)
    name, reason = select_model(scene)
    assert name == "2d-building-multisurface+vertical" and "a vertical (n = g + a_z" in reason
    out = simulate(scene)
    assert (out.model, out.model_reason) == (name, reason)
    # the scene's vertical reaches the steps (and the bearings' loads): the direct call with it, and not without it
    kw = dict(superstructure=design.superstructure, bearing=design.bearing, total_mass_kg=design.mass_kg,
              gravity_m_s2=design.gravity_m_s2, bearing_layout=design.bearing_layout)
    direct = simulate_building_bearing_pair(ax, ay, dt, az_m_s2=az, **kw)
    assert np.array_equal(out.displacement_m, direct.displacement_m)
    for key in ("bearing_axial_load_max_N", "bearing_axial_load_min_N"):
        assert out.bearing_loads()[key] == direct.bearing_loads()[key]
    flat = simulate_building_bearing_pair(ax, ay, dt, **kw)
    assert not np.array_equal(out.displacement_m, flat.displacement_m)
    assert out.bearing_loads()["bearing_axial_load_max_N"] != flat.bearing_loads()["bearing_axial_load_max_N"]


def _write(path, values, dt):
    np.savetxt(path, np.column_stack((dt * np.arange(values.size), values)))
    return str(path)


#: the 2-story building on a TFP of test_planar_building_multisurface.py, its outer plates 0.4 m (as TFP here)
DESIGN = BUILDING_ON_SMALL_TFP.replace("displacement_capacity_m = 0.15", "displacement_capacity_m = 0.4")


def test_cli_simulate_a_pair_and_a_vertical_with_a_building_on_a_tfp(tmp_path):
    from typer.testing import CliRunner

    from isolator.cli import app

    ax, ay, az, dt = segment(2.0, 8.0)
    design = tmp_path / "tfp_building.toml"
    design.write_text(DESIGN)
    files = [_write(tmp_path / f"{name}.txt", values, dt) for name, values in (("x", ax), ("y", ay), ("z", az))]

    def simulate(*extra):
        result = CliRunner().invoke(app, ["simulate", files[0], "--pair", files[1], *extra, "--design", str(design),
                                          "--units", "m/s2", "--json"])
        assert result.exit_code == 0, result.output
        return json.loads(result.output)

    out = simulate("--vertical", files[2])
    flat = simulate()
    assert out["model"] == "2d-building-multisurface+vertical" and "vertical" in out["model_reason"]
    assert flat["model"] == "2d-building-multisurface"
    assert abs(out["energy_balance_error_J_per_kg"]) <= 1e-5 * out["energy_input_J_per_kg"]
    assert out["peak_displacement_m"] != flat["peak_displacement_m"]
    # the vertical's share of the bearings' loads: the extremes move by up to P_k,g max|a_z|/g
    share = 1.0e6 * G / 4.0
    bound = share * float(np.max(np.abs(az))) / G
    high, low = out["bearing_axial_load_max_N"], out["bearing_axial_load_min_N"]
    assert len(high) == 4 and all(lo < share < hi for lo, hi in zip(low, high, strict=True))
    moved = [abs(a - b) for a, b in zip(high, flat["bearing_axial_load_max_N"], strict=True)]
    assert 0.0 < max(moved) <= 1.5 * bound
