"""A building's bearing at its displacement capacity is never run past silently (issue 23, with issue 22).

1-D: a building on a single pendulum whose peak reaches its capacity is run again with the rim
(``1d-building`` first, then ``1d-building-multisurface`` with the single surface, ``rerun`` true),
checked against the independent solve_ivp reference of ``test_building_multisurface`` (the series
bearing with its rim and the static friction of the stuck bearing).  2-D: the 2-D building has no
rim; past the capacity its result says so (``ultimate_displacement_reached``, the first time, a
notice in ``solver_status``), and the review's capacity rows fail on the peak without claiming a rim.
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from typer.testing import CliRunner

from isolator.adapter import motion_keywords
from isolator.bearing import Bearing, Surface
from isolator.cli import app
from isolator.design import Design
from isolator.solver import building
from isolator.solver.building import simulate_building
from isolator.solver.building_multisurface import simulate_building_bearing
from isolator.solver.models import Scene, select_model, simulate
from tests.solver.test_building import make_superstructure, real_segment
from tests.solver.test_building_multisurface import BuildingOnSeries, _rel
from tests.solver.test_building_registry import BASE, BEARINGS, FLOORS, TOML

G = 9.80665
MASSES = [f["mass_kg"] for f in FLOORS]
STIFFNESSES = [f["stiffness_x_N_per_m"] for f in FLOORS]
#: Northridge NWH360 from 2 s: the 3-story building of test_building_registry (R 2.5 m, µs 0.06, µk 0.045,
#: a dashpot) reaches 0.318 m on an unbounded plate, near 4.3 s
SEGMENT = ("RSN1044_NORTHR_NWH360.AT2", 2.0, 6.0)


def design(capacity_m):
    return Design.from_mapping({**BASE, "displacement_capacity_m": capacity_m,
                                "superstructure": {"damping_ratio": 0.05, "floor": FLOORS},
                                "bearing_position": BEARINGS})


def scene_of(d, acc, dt, ay=None):
    return Scene(ax_m_s2=acc, ay_m_s2=ay, dt_s=dt, isolator=motion_keywords(d), design=d)


def single(capacity_m):
    return Bearing(kind="single", surfaces=(Surface(radius_m=BASE["radius_m"], height_m=0.0,
                                                    mu_kinetic=BASE["mu_kinetic"], mu_static=BASE["mu_static"],
                                                    displacement_capacity_m=capacity_m),))


def test_a_single_surface_with_static_friction_is_the_1d_building_below_its_rim(records_dir):
    """µs > µk on one surface: the stuck bearing holds to µs W, slides at µk W (the 1-D building's friction)."""
    acc, dt = real_segment(records_dir, *SEGMENT)
    s = make_superstructure(MASSES, STIFFNESSES, 0.05)
    mass, c = BASE["mass_kg"], BASE["damping_Ns_per_m"]
    ours = simulate_building_bearing(acc, dt, superstructure=s, bearing=single(1.0), total_mass_kg=mass,
                                     damping_Ns_per_m=c)
    free = simulate_building(acc, dt, superstructure=s, total_mass_kg=mass, stiffness_N_per_m=mass * G / 2.5,
                             mu_static=0.06, mu_kinetic=0.045, damping_Ns_per_m=c)
    assert free.n_events > 10 and ours.event_names == free.event_names
    assert np.max(np.abs(ours.event_time_s - free.event_time_s)) <= 1e-12
    for attr in ("displacement_m", "velocity_m_s", "floor_displacement_m", "floor_absolute_acceleration_m_s2",
                 "isolator_force_N"):
        assert _rel(getattr(ours, attr), getattr(free, attr)) <= 1e-12, attr
    for key in ("peak_displacement_m", "peak_transmitted_acceleration_m_s2", "energy_input_J_per_kg",
                "energy_friction_J_per_kg"):
        assert getattr(ours, key) == pytest.approx(getattr(free, key), rel=1e-12), key
    # the first break-away is at the static level: the bearing's force reaches µs W there
    assert abs(free.isolator_force_N).max() / (mass * G) >= 0.06 * (1 - 1e-9)


def test_a_building_past_its_capacity_is_run_again_with_the_rim(records_dir):
    acc, dt = real_segment(records_dir, *SEGMENT)
    d = design(0.25)
    sc = scene_of(d, acc, dt)
    assert select_model(sc)[0] == "1d-building" and "redone with the rim" in select_model(sc)[1]
    r = simulate(sc)
    assert r.model == "1d-building-multisurface" and r.rerun
    assert "reached its displacement capacity 0.25 m" in r.model_reason and "its peak was 0.3179 m" in r.model_reason
    summary = r.summary()
    assert summary["ultimate_displacement_reached"] is True and summary["solver_status"] == "ok"
    assert summary["bearing_type"] == "single" and summary["peak_displacement_m"] == pytest.approx(0.25, rel=1e-12)
    assert summary["impact_impulse_N_s"] > 0.0 and r.n_rim_contacts == 2
    # the independent reference: solve_ivp on the building with the series bearing, its rim and µs > µk
    ref = BuildingOnSeries(MASSES, STIFFNESSES, 0.05, BASE["mass_kg"], single(0.25), BASE["damping_Ns_per_m"]
                           ).run(acc, dt)
    assert [kind for _, kind in ref["events"]] == r.event_names and r.event_names.count("ultimate") == 2
    assert np.max(np.abs(np.array([t for t, _ in ref["events"]]) - r.event_time_s)) <= 1e-9
    assert r.ultimate_first_time_s == pytest.approx(ref["impacts"][0][0], abs=1e-9)
    assert r.impact_impulse_m_s == pytest.approx(sum(v for _, v in ref["impacts"]), rel=1e-9)
    for ours, theirs in ((r.displacement_m, ref["x_b"]), (r.velocity_m_s, ref["v_b"]),
                         (r.floor_displacement_m, ref["u"])):
        assert _rel(ours, theirs) <= 1e-9
    mass = BASE["mass_kg"]
    assert np.array([r.energy_input_J_per_kg, r.energy_friction_J_per_kg, r.energy_viscous_J_per_kg,
                     r.energy_impact_J_per_kg]) * mass == pytest.approx(ref["energy"], rel=1e-9)
    assert abs(r.energy_balance_error_J_per_kg) <= 1e-9 * r.energy_input_J_per_kg


def test_a_building_below_its_capacity_is_unchanged(records_dir):
    acc, dt = real_segment(records_dir, *SEGMENT)
    d = design(0.5)
    r = simulate(scene_of(d, acc, dt))
    plain = building.simulate_scene(scene_of(d, acc, dt))
    assert r.model == "1d-building" and not getattr(r, "rerun", False) and r.peak_displacement_m < 0.5
    assert np.array_equal(r.displacement_m, plain.displacement_m)
    assert np.array_equal(r.floor_displacement_m, plain.floor_displacement_m)
    summary = r.summary()
    assert summary["ultimate_displacement_reached"] is False and summary["ultimate_first_time_s"] is None
    assert summary["solver_status"] == "ok"


def test_cli_simulate_says_the_rim_was_reached(records_dir, tmp_path):
    """``isolator simulate`` on the whole record: the peak is the capacity, the impulse is m_b Σ|v_b|."""
    path = tmp_path / "b.toml"
    path.write_text(TOML.replace("damping_Ns_per_m", "displacement_capacity_m = 0.25\ndamping_Ns_per_m", 1))
    out = CliRunner().invoke(app, ["simulate", str(records_dir / "at2" / SEGMENT[0]), "--design", str(path),
                                   "--json"])
    assert out.exit_code == 0, out.output
    r = json.loads(out.stdout)
    assert r["model"] == "1d-building-multisurface" and r["ultimate_displacement_reached"] is True
    assert r["peak_displacement_m"] == pytest.approx(0.25, rel=1e-12) and r["n_rim_contacts"] >= 1
    slab = BASE["mass_kg"] - sum(MASSES)
    assert r["impact_impulse_N_s"] == pytest.approx(slab * r["impact_impulse_m_s"], rel=1e-12)
    assert r["impact_impulse_m_s"] >= r["max_impact_velocity_m_s"] > 0.0


def _pair(records_dir):
    from isolator.motion import read_ground_motion

    folder = records_dir / "pairs" / "superstitionhills1987_PTS"
    x = read_ground_motion(folder / "RSN723_SUPER.B_B-PTS225.AT2")
    y = read_ground_motion(folder / "RSN723_SUPER.B_B-PTS315.AT2")
    n = min(x.npts, y.npts, int(round(20.0 / x.dt_s)))
    assert x.dt_s == y.dt_s
    return x.acceleration_m_s2[:n], y.acceleration_m_s2[:n], x.dt_s


@pytest.mark.parametrize("capacity", [0.3, 2.0])
def test_the_2d_building_says_when_it_passes_its_capacity(records_dir, capacity):
    """No rim in the 2-D building: the result is the unbounded plate's, unchanged, and says from when."""
    ax, ay, dt = _pair(records_dir)
    # with a vertical (zero here): under a pair alone a run past the capacity is redone with the rim
    # (2d-building-multisurface, tests/solver/test_planar_building_multisurface.py)
    az = np.zeros_like(ax)
    r = simulate(dataclasses.replace(scene_of(design(capacity), ax, ay=ay, dt=dt), az_m_s2=az))
    plain = simulate(dataclasses.replace(scene_of(Design.from_mapping(
        {**BASE, "superstructure": {"damping_ratio": 0.05, "floor": FLOORS}, "bearing_position": BEARINGS}), ax,
        ay=ay, dt=dt), az_m_s2=az))
    assert r.model == plain.model == "2d-building"
    assert np.array_equal(r.displacement_m, plain.displacement_m) and r.n_events == plain.n_events
    summary = r.summary()
    size = np.hypot(r.displacement_m[:, 0], r.displacement_m[:, 1])
    assert summary["rim_modelled"] is False and summary["ultimate_displacement_m"] == capacity
    if capacity > r.peak_displacement_m:
        assert summary["ultimate_displacement_reached"] is False and summary["ultimate_first_time_s"] is None
        assert summary["solver_status"] == "ok"
        return
    assert summary["ultimate_displacement_reached"] is True
    k = int(np.flatnonzero(size >= capacity)[0])
    assert k > 0 and size[k - 1] < capacity <= size[k] and summary["ultimate_first_time_s"] == r.time_s[k]
    assert summary["solver_status"] == (
        f"the bearing reached its displacement capacity 0.3 m by t = {r.time_s[k]:.4g} s (peak "
        f"{r.peak_displacement_m:.4g} m): 2d-building has no rim, so the response after that time is that of an "
        "unbounded plate, not modelled")
    assert plain.summary()["solver_status"] == "ok" and "ultimate_displacement_reached" not in plain.summary()


def test_the_review_reruns_a_2d_building_past_its_capacity_with_the_rim(tmp_path):
    """Three real pairs through the 2-D building with a 0.3 m capacity (floors that differ along x and y, µs 0.06 >
    µk 0.05): Superstition Hills passes it at both bounds on the unbounded plate, so it is run again with the rim
    (2d-building-multisurface, static friction modelled); its record_capacity rows fail as the rim's (REACHED)."""
    from isolator.review.run import run_review
    from isolator.review.suite import load_suite
    from isolator.review.target import two_period_target
    from tests.review.conftest import EXAMPLE, SHORT
    from tests.review.test_structure_review import SMALL_BUILDING

    body = "".join(f'[[pair]]\nname = "{name}"\nx = "{EXAMPLE / name / x}"\ny = "{EXAMPLE / name / y}"\n{extra}\n'
                   for name, x, y, extra in SHORT)
    (tmp_path / "suite.toml").write_text(body)
    r = run_review(Design.from_mapping({**SMALL_BUILDING, "displacement_capacity_m": 0.3}),
                   two_period_target(1.5, 0.9, 8.0), load_suite(tmp_path / "suite.toml"), jobs=1, nominal=False,
                   parameters={"n_for_mean": 3})
    reached = {(b, n) for b in r.analyses for n, a in r.analyses[b].items() if a.get("ultimate_displacement_reached")}
    assert reached == {("lower", "superstitionhills1987_PTS"), ("upper", "superstitionhills1987_PTS")}
    rows = [row for row in r.checks if row["id"] == "record_capacity"]
    assert {(row["bound"], row["pair"]) for row in rows} == reached
    for row in rows:
        analysis = r.analyses[row["bound"]][row["pair"]]
        assert analysis["model"] == "2d-building-multisurface"
        assert analysis["peak_displacement_m"] == pytest.approx(0.3, rel=1e-12)
        assert row["status"] == "fail" and row["clause"] == "ASCE 7-22 17.2.4.5 / 17.6.3.4 [U]"
        assert row["value"] == pytest.approx(row["torsion_factor"] * 0.3) and row["value"] > 0.3
        assert "REACHED its ultimate displacement" in row["note"] and "unbounded plate" not in row["note"]
    assert next(row for row in r.checks if row["id"] == "D_M_capacity")["status"] == "fail"
    assert not any("unbounded plate, not modelled" in note for note in r.notes)
    assert all(a["impact_impulse_N_s"] > 0.0 for b in r.analyses for a in r.analyses[b].values()
               if a.get("ultimate_displacement_reached"))
