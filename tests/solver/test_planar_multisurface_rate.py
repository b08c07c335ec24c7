"""Double and triple pendulums with µ(v) surfaces in the plane (2d-multisurface+mu(v)) against independent truths.

Truths: the 1-D µ(v) model ``1d-multisurface+mu(v)`` (a pair whose second component is zero, and that record
along another azimuth), the single-surface engine ``2d+mu(v)`` (an equal double: each surface slides at V/2, so
it is one pendulum of radius 2R̄ with the rate a/2), rotation and mirror invariance, the energy balance, the
constant-µ model (µ_slow = µ_fast runs ``2d-multisurface``); on a real pair, the equal double against the planar
engine; through saturation (two surfaces in the 1-D model's saturated set) the equal double and the 1-D model along
a line.  Not here yet: a reference of the equations alone on a real pair (scipy's Radau stalled at the first start
from rest, docs/multisurface.md), two saturated surfaces whose directions part.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from isolator.bearing import parse_bearing
from isolator.errors import DesignError, RecordInputError, SolverError
from isolator.solver.multisurface_rate import simulate_bearing_rate
from isolator.solver.planar import simulate_pair
from isolator.solver.planar_multisurface_rate import simulate_bearing_pair_rate

G = 9.80665
GEOMETRY = [(2.1, 0.4), (0.3, 0.05), (0.3, 0.05), (2.1, 0.4)]  # Fenz & Constantinou's TFP (R [m], d [m])
MU_SLOW = [0.03, 0.01, 0.01, 0.05]
MU_FAST = [0.06, 0.02, 0.02, 0.10]
PTS = ("superstitionhills1987_PTS", "RSN723_SUPER.B_B-PTS225.AT2", "RSN723_SUPER.B_B-PTS315.AT2")


def rate_bearing(kind, geometry, mu_slow, mu_fast, rate):
    return parse_bearing({"type": kind, "surface": [
        {"radius_m": r, "mu_slow": s, "mu_fast": f, "rate_s_per_m": rate, "displacement_capacity_m": d}
        for (r, d), s, f in zip(geometry, mu_slow, mu_fast, strict=True)]}, DesignError)


TFP = rate_bearing("triple", GEOMETRY, MU_SLOW, MU_FAST, 20.0)


def pulse_pair(ax_g=0.2, ay_g=0.15, dt=0.01, duration=4.0, until=2.0):
    t = np.arange(0.0, duration, dt)
    on = t < until
    return ax_g * G * np.sin(2 * np.pi * t / 2.0) * on, ay_g * G * np.cos(2 * np.pi * t / 1.7) * on, dt


def rotate(a, b, theta):
    c, s = np.cos(theta), np.sin(theta)
    return c * a - s * b, s * a + c * b


def read_pair(records_dir, seconds):
    from isolator.motion import read_ground_motion

    folder, fx, fy = PTS
    mx, my = (read_ground_motion(records_dir / "pairs" / folder / name) for name in (fx, fy))
    n = min(mx.npts, my.npts, int(round(seconds / mx.dt_s)) + 1)
    return mx.acceleration_m_s2[:n], my.acceleration_m_s2[:n], mx.dt_s


def test_zero_second_component_is_the_1d_model():
    """The 1-D model's TFP pulse (regimes I–III) as a pair with ay = 0, and along two other azimuths."""
    t = np.arange(0.0, 1.0, 0.02)
    acc = 0.25 * G * np.sin(2 * np.pi * t / 2.0)
    one = simulate_bearing_rate(acc, 0.02, bearing=TFP)
    two = simulate_bearing_pair_rate(acc, np.zeros_like(acc), 0.02, bearing=TFP)
    peak = one.peak_displacement_m
    print("zero component:", two.model_reason, np.max(np.abs(two.displacement_m[:, 0] - one.displacement_m)) / peak)
    assert [name for name in one.regimes if "(one inner)" not in name] == ["I", "II", "III"] and list(two.regimes) == list(one.regimes)
    assert np.max(np.abs(two.displacement_m[:, 0] - one.displacement_m)) <= 1e-9 * peak
    assert np.all(two.displacement_m[:, 1] == 0.0)
    assert abs(two.peak_displacement_m - peak) <= 1e-9 * peak
    for name in one.regimes:
        assert abs(two.regimes[name] - one.regimes[name]) <= 1e-9
    np.testing.assert_allclose(two.surface_peak_displacement_m, one.surface_peak_displacement_m, rtol=0, atol=1e-9 * peak)
    assert abs(two.energy_balance_error_J_per_kg) <= 1e-9 * two.energy_input_J_per_kg
    assert abs(two.energy_input_J_per_kg - one.energy_input_J_per_kg) <= 1e-9 * one.energy_input_J_per_kg
    theta = np.radians(35.0)
    rot = simulate_bearing_pair_rate(np.cos(theta) * acc, np.sin(theta) * acc, 0.02, bearing=TFP)
    along = rot.displacement_m[:, 0] * np.cos(theta) + rot.displacement_m[:, 1] * np.sin(theta)
    assert np.max(np.abs(along - one.displacement_m)) <= 1e-9 * peak


def test_rotation_mirror_and_energy_in_the_plane():
    ax, ay, dt = pulse_pair()
    res = simulate_bearing_pair_rate(ax, ay, dt, bearing=TFP)
    peak = res.peak_displacement_m
    print("pulse pair:", res.model_reason, res.regimes, "balance", res.energy_balance_error_J_per_kg)
    assert set(res.regimes) >= {"I", "II", "III"}
    assert abs(res.energy_balance_error_J_per_kg) <= 1e-9 * res.energy_input_J_per_kg
    theta = 0.7
    rot = simulate_bearing_pair_rate(*rotate(ax, ay, theta), dt, bearing=TFP)
    x = np.column_stack(rotate(res.displacement_m[:, 0], res.displacement_m[:, 1], theta))
    assert np.max(np.abs(x - rot.displacement_m)) <= 1e-9 * peak
    mir = simulate_bearing_pair_rate(ax, -ay, dt, bearing=TFP)
    assert np.max(np.abs(mir.displacement_m[:, 1] + res.displacement_m[:, 1])) <= 1e-9 * peak
    assert np.max(np.abs(mir.displacement_m[:, 0] - res.displacement_m[:, 0])) <= 1e-9 * peak


def test_equal_double_is_the_single_pendulum_of_summed_radius_and_half_rate():
    """Equal surfaces (R̄, µ_slow, µ_fast, a) share the velocity: each slides at V/2 with the one force, so
    r = u/R̄ + µ(|V|/2) V̂ = X/(2R̄) + (µ_fast − Δµ e^(−(a/2)|V|)) V̂: the single pendulum of radius 2R̄ and rate
    a/2 (break-away at µ_slow), run by the planar engine (another integrator, its own events)."""
    dbl = rate_bearing("double", [(1.5, 1.5), (1.5, 1.5)], [0.04, 0.04], [0.08, 0.08], 10.0)
    rbar, _, _ = dbl.elements()
    ax, ay, dt = pulse_pair(0.3, 0.25)
    res = simulate_bearing_pair_rate(ax, ay, dt, bearing=dbl)
    ref = simulate_pair(ax, ay, dt, mu_static=0.04, radius_m=float(rbar.sum()), mu_slow=0.04, mu_fast=0.08,
                        rate_s_per_m=5.0)
    peak = ref.peak_displacement_m
    dist = np.max(np.hypot(*(res.displacement_m - ref.displacement_m).T)) / peak
    print("equal double vs 2d+mu(v):", dist, "peak", peak)
    assert dist <= 1e-9
    assert abs(res.energy_balance_error_J_per_kg) <= 1e-9 * res.energy_input_J_per_kg


def test_a_constant_law_runs_the_constant_model_and_the_registry_says_which():
    from isolator.adapter import motion_keywords
    from isolator.design import Design
    from isolator.solver.models import Scene, select_model, simulate
    from isolator.solver.planar_multisurface import simulate_bearing_pair

    def design(mu_fast):
        return Design.from_mapping({"name": "TFP", "mass_kg": 1.0e5, "bearing": {"type": "triple", "surface": [
            {"radius_m": r, "mu_slow": s, "mu_fast": s if mu_fast is None else f, "rate_s_per_m": 20.0,
             "displacement_capacity_m": d} for (r, d), s, f in zip(GEOMETRY, MU_SLOW, MU_FAST, strict=True)]}},
            source="tfp_muv.toml")

    ax, ay, dt = pulse_pair(duration=3.0)
    rate = design(True)
    pair = Scene(ax_m_s2=ax, ay_m_s2=ay, dt_s=dt, isolator=motion_keywords(rate), design=rate)
    assert select_model(pair)[0] == "2d-multisurface+mu(v)"
    one = Scene(ax_m_s2=ax, dt_s=dt, isolator=motion_keywords(rate), design=rate)
    assert select_model(one)[0] == "1d-multisurface+mu(v)"  # one component keeps the 1-D model
    vertical = Scene(ax_m_s2=ax, ay_m_s2=ay, az_m_s2=0.1 * ax, dt_s=dt, isolator=motion_keywords(rate), design=rate)
    with pytest.raises(RecordInputError, match="vertical component is not modelled"):
        simulate(vertical)
    flat = design(None)  # µ_slow = µ_fast: constant friction, the constant-µ model
    scene = Scene(ax_m_s2=ax, ay_m_s2=ay, dt_s=dt, isolator=motion_keywords(flat), design=flat)
    res = simulate(scene)
    assert res.model == "2d-multisurface"
    constant = parse_bearing({"type": "triple", "surface": [
        {"radius_m": r, "mu": s, "displacement_capacity_m": d} for (r, d), s in zip(GEOMETRY, MU_SLOW, strict=True)]},
        DesignError)
    direct = simulate_bearing_pair(ax, ay, dt, bearing=constant)
    np.testing.assert_array_equal(res.displacement_m, direct.displacement_m)


def test_equal_double_through_saturation_is_the_single_pendulum():
    """The equal double at a = 30 s/m reaches 2.2 m/s (a·v ≈ 30–33 on both surfaces from 1.76 s): the two surfaces
    saturate together and the non-pivot one's slide law µ_fast − µ(v) ≈ 1e-15 cannot be inverted from the state.
    They now share the velocity on their slow manifold (the 1-D model's saturated set, set_split/update_lock, on each
    component: b_1 = b_2 moves together, each slides at V/2), exact here: against the planar engine's single pendulum
    of radius 2R̄ and rate a/2, measured 4.4e-12 of the peak (balance 1.9e-12 of the input).  Without the set (levels
    (inf, inf)) the run is refused in one line at the time the two saturate (the window covers the failure)."""
    dbl = rate_bearing("double", [(1.5, 1.5), (1.5, 1.5)], [0.04, 0.04], [0.08, 0.08], 30.0)
    rbar, _, _ = dbl.elements()
    ax, ay, dt = pulse_pair(0.3, 0.25)
    res = simulate_bearing_pair_rate(ax, ay, dt, bearing=dbl)
    ref = simulate_pair(ax, ay, dt, mu_static=0.04, radius_m=float(rbar.sum()), mu_slow=0.04, mu_fast=0.08,
                        rate_s_per_m=15.0)
    peak = ref.peak_displacement_m
    dist = np.max(np.hypot(*(res.displacement_m - ref.displacement_m).T)) / peak
    print("equal double through saturation vs 2d+mu(v):", dist, "peak speed", res.peak_velocity_m_s)
    assert 30.0 * res.peak_velocity_m_s / 2 >= 32.0  # each surface well past the set's join level (28)
    assert dist <= 1e-9
    assert abs(res.energy_balance_error_J_per_kg) <= 1e-9 * res.energy_input_J_per_kg
    with pytest.raises(SolverError, match=r"at t = 1\.7\d* s \(.*two surfaces saturated together") as info:
        simulate_bearing_pair_rate(ax, ay, dt, bearing=dbl, saturation_levels=(np.inf, np.inf))
    assert "\n" not in str(info.value)


#: F&C's TFP radii with plates large enough to stay off the rims, a = 40 s/m: surfaces 1 and 4 saturate together
#: (a·v ≥ 28 on both) under :func:`saturating_pulse`
BIG_TFP = rate_bearing("triple", [(2.1, 1.5), (0.3, 0.1), (0.3, 0.1), (2.1, 1.5)], MU_SLOW, MU_FAST, 40.0)


def saturating_pulse(dt=0.01):
    """A half-sine of 0.5 g and 1 s, then 0.4 s free: the mass reaches 2.0 m/s, surfaces 1 and 4 ~1 m/s each.  (At
    1.437 s the mass stops and starts back on surfaces 1 and 3 from rest, where the plane's start from rest fails:
    docs/multisurface.md, h122; the window ends before.)"""
    t = np.arange(0.0, 1.405, dt)
    return 0.5 * G * np.sin(np.pi * t) * (t < 1.0), dt


def test_saturated_pair_with_a_zero_second_component_is_the_1d_model():
    """Surfaces 1 and 4 of a TFP saturated together (a·v up to 40 each): a pair with ay = 0 is the 1-D model (its
    saturated set, set_split) — the plane's set is the same map on each component — and the record along 35° is
    that history rotated (the run without the set is refused here too, after ~2 min on the work bound: left to the
    equal double's test, which shows the same refusal at once).  Measured
    (h122): 4.4e-16 of the peak along x, 8.8e-15 along 35° (2.0e-15 across), balance 4e-14 of the input."""
    acc, dt = saturating_pulse()
    one = simulate_bearing_rate(acc, dt, bearing=BIG_TFP)
    two = simulate_bearing_pair_rate(acc, np.zeros_like(acc), dt, bearing=BIG_TFP)
    peak = one.peak_displacement_m
    dist = np.max(np.abs(two.displacement_m[:, 0] - one.displacement_m)) / peak
    print("saturated, zero component:", dist, "peak", peak, "speed", one.peak_velocity_m_s, two.model_reason)
    assert one.status == 0 and one.n_rim_contacts == 0
    assert 40.0 * one.peak_velocity_m_s / 2 >= 38.0
    assert dist <= 1e-9
    assert np.all(two.displacement_m[:, 1] == 0.0)
    assert list(two.regimes) == list(one.regimes)
    assert abs(two.energy_balance_error_J_per_kg) <= 1e-9 * two.energy_input_J_per_kg
    theta = np.radians(35.0)
    rot = simulate_bearing_pair_rate(np.cos(theta) * acc, np.sin(theta) * acc, dt, bearing=BIG_TFP)
    back_x, back_y = rotate(*rot.displacement_m.T, -theta)
    along = np.max(np.abs(back_x - one.displacement_m)) / peak
    across = np.max(np.abs(back_y)) / peak
    print("saturated, along 35°:", along, across)
    assert along <= 1e-9 and across <= 1e-9
    assert abs(rot.energy_balance_error_J_per_kg) <= 1e-9 * rot.energy_input_J_per_kg


def review_tfp():
    """The µ(v) TFP of the review's scene (0.4 m plates, a = 20 s/m; µ_slow 0.04/0.01/0.01/0.07, µ_fast
    0.06/0.02/0.02/0.10): the lower bound's PTS runs of this file and of test_planar_multisurface_rate_corner.py."""
    return parse_bearing({"type": "triple", "surface": [
        {"radius_m": r, "mu_slow": s, "mu_fast": f, "rate_s_per_m": 20.0, "displacement_capacity_m": d}
        for (r, d), s, f in zip(GEOMETRY, [0.04, 0.01, 0.01, 0.07], [0.06, 0.02, 0.02, 0.10], strict=True)]},
        DesignError)

def test_pts_lower_bound_of_the_review_runs_past_its_old_stop(records_dir):
    """The review's scene that stopped it (h113): last session's µ(v) TFP (0.4 m plates, a = 20 s/m) under PTS
    ×1.512437746473765, which took more than 20 000 collocation steps in one sample interval at 11.8755 s.  Not a
    saturated pair (a·v ≈ 15.8 on surfaces 1 and 4): each stage's force was sought from the force of the step's
    start, outside the circle |r − b_1| = µ_fast,1 that had moved with b_1 by 40 times its gap, and the force's
    Newton stalled.  From the force predicted along dr/dy it answers; its first 12.0 s here (the rim of surface 1
    follows at 12.18 s, refused in one line), balance ≤ 1e-9 of the input."""
    bearing = review_tfp()
    ax, ay, dt = read_pair(records_dir, 12.0)
    factor = 1.512437746473765
    res = simulate_bearing_pair_rate(factor * ax, factor * ay, dt, bearing=bearing)
    print("PTS lower bound, 12 s:", res.model_reason, res.regimes, "balance",
          res.energy_balance_error_J_per_kg / res.energy_input_J_per_kg)
    assert res.status == 0 and res.time_s[-1] >= 12.0 - 1e-9
    assert abs(res.energy_balance_error_J_per_kg) <= 1e-9 * res.energy_input_J_per_kg


def test_equal_double_on_a_real_pair_is_the_single_pendulum(records_dir):
    """Superstition Hills PTS (26 events: starts from rest, stops, turns in the plane) on the equal double against
    the planar engine's single pendulum of radius 2R̄ and rate a/2: measured 1.8e-11 of the peak."""
    ax, ay, dt = read_pair(records_dir, 1e9)
    dbl = rate_bearing("double", [(1.5, 1.5), (1.5, 1.5)], [0.04, 0.04], [0.08, 0.08], 10.0)
    rbar, _, _ = dbl.elements()
    res = simulate_bearing_pair_rate(ax, ay, dt, bearing=dbl)
    ref = simulate_pair(ax, ay, dt, mu_static=0.04, radius_m=float(rbar.sum()), mu_slow=0.04, mu_fast=0.08,
                        rate_s_per_m=5.0)
    assert res.n_events >= 10
    assert np.max(np.hypot(*(res.displacement_m - ref.displacement_m).T)) <= 1e-9 * ref.peak_displacement_m
    assert abs(res.energy_balance_error_J_per_kg) <= 1e-9 * res.energy_input_J_per_kg


def test_real_pair_energy_balance(records_dir):
    ax, ay, dt = read_pair(records_dir, 1e9)
    res = simulate_bearing_pair_rate(ax, ay, dt, bearing=TFP)
    print("PTS whole:", res.model_reason, res.regimes, "balance", res.energy_balance_error_J_per_kg, "of",
          res.energy_input_J_per_kg)
    assert [name for name in res.regimes if "(one inner)" not in name] == ["I", "II", "III"]
    assert abs(res.energy_balance_error_J_per_kg) <= 1e-9 * res.energy_input_J_per_kg
    hist = res.energy_history_J_per_kg
    assert np.all(np.diff(hist[1]) >= -1e-12 * res.energy_input_J_per_kg)  # friction work never decreases


#: the µ(v) TFP of these tests as a design file, with the review's bounds and plan
TFP_MUV_TOML = """name = "TFP with mu(v) (review)"
mass_kg = 2.0e6
lambda_max = 1.2
lambda_min = 0.9
[plan]
b_m = 40.0
d_m = 25.0
eccentricity_m = 0.5
y_m = 20.0
[bearing]
type = "triple"
surface = [
  {radius_m = 2.1, mu_slow = 0.03, mu_fast = 0.06, rate_s_per_m = 20.0, displacement_capacity_m = 0.4},
  {radius_m = 0.3, mu_slow = 0.01, mu_fast = 0.02, rate_s_per_m = 20.0, displacement_capacity_m = 0.05},
  {radius_m = 0.3, mu_slow = 0.01, mu_fast = 0.02, rate_s_per_m = 20.0, displacement_capacity_m = 0.05},
  {radius_m = 2.1, mu_slow = 0.05, mu_fast = 0.10, rate_s_per_m = 20.0, displacement_capacity_m = 0.4},
]
"""


def test_cli_simulate_json_on_a_pair(tmp_path, records_dir):
    design = tmp_path / "tfp_muv.toml"
    design.write_text(TFP_MUV_TOML)
    folder = records_dir / "pairs" / PTS[0]
    exe = str(Path(sys.executable).with_name("isolator"))
    run = subprocess.run([exe, "simulate", str(folder / PTS[1]), "--pair", str(folder / PTS[2]), "--design",
                          str(design), "--trim", "--json"], capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    out = json.dumps(json.loads(run.stdout))
    assert "2d-multisurface+mu(v)" in out and "Radau IIA" in out and "regimes" in out
