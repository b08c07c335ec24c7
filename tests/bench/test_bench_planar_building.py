"""The 2-D building case of the bench: the independent 2-D reference, OpenSees' 3-D model, the harness.

The reference is checked against the 1-D reference on a collinear pair (another formulation,
the full mass matrix) and for rotation invariance on a real pair; OpenSees' 3-D model against
its own 1-D model (a zero second component) and, with stiff stories, against the rigid block
on one ``singleFPBearing`` (``isolator.bench.opensees.opensees_pair``).  Real records skip
without ``../shared``, OpenSees without openseespy.
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.bench import building as building_bench
from isolator.bench.building_reference import building_reference
from isolator.bench.opensees import opensees_available
from isolator.bench.planar_building_reference import planar_building_reference

OPENSEES_OK, OPENSEES_WHY = opensees_available()
needs_opensees = pytest.mark.skipif(not OPENSEES_OK, reason=f"OpenSees baseline: {OPENSEES_WHY}")


def _pair(records_dir, start: int, stop: int, scale: float = 1.0):
    from isolator.motion import read_ground_motion

    _, folder, fx, fy = building_bench.BUILDING_PAIR
    mx, my = (read_ground_motion(records_dir / folder / f) for f in (fx, fy))
    return scale * mx.acceleration_m_s2[start:stop], scale * my.acceleration_m_s2[start:stop], mx.dt_s


def _reference(case, ax, ay):
    s = case.superstructure
    return planar_building_reference(
        ax, ay, case.dt_s, masses_kg=s.masses_kg, stiffness_matrices=(s.stiffness_matrix("x"), s.stiffness_matrix("y")),
        damping_matrices=(s.damping_matrix("x"), s.damping_matrix("y")), total_mass_kg=case.total_mass_kg,
        isolator_stiffness_N_per_m=case.isolator_stiffness_N_per_m, mu_static=case.mu, mu_kinetic=case.mu,
        gravity_m_s2=case.gravity_m_s2)


def _relative(a, b) -> float:
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b)))) / float(np.max(np.abs(b)))


def test_reference_on_a_collinear_pair_equals_the_1d_reference(records_dir):
    # the record along an axis at 30°: the 2-D reference projected on that axis equals the 1-D reference
    # (written with the full mass matrix, a different formulation), nothing moves across it
    from isolator.motion import read_ground_motion

    acc = read_ground_motion(records_dir / building_bench.BUILDING_RECORD[1]).acceleration_m_s2[:301]
    case = building_bench.building_case("collinear", acc, 0.02)
    s = case.superstructure
    one = building_reference(acc, case.dt_s, masses_kg=s.masses_kg, stiffness_matrix=s.stiffness_matrix(),
                             damping_matrix=s.damping_matrix(), total_mass_kg=case.total_mass_kg,
                             isolator_stiffness_N_per_m=case.isolator_stiffness_N_per_m, mu_static=case.mu,
                             mu_kinetic=case.mu, gravity_m_s2=case.gravity_m_s2)
    axis = np.array([np.cos(np.pi / 6), np.sin(np.pi / 6)])
    two = _reference(case, axis[0] * acc, axis[1] * acc)
    assert two["n_starts"] >= 3 and two["n_stops"] >= 3
    assert float(np.max(np.abs(one["slab_displacement_m"]))) > 0.01  # it slid
    for key in ("slab_displacement_m", "floor_displacement_m", "floor_absolute_acceleration_m_s2"):
        assert _relative(two[key] @ axis, one[key]) < 1e-9, key
    across = two["slab_displacement_m"] @ np.array([-axis[1], axis[0]])
    assert float(np.max(np.abs(across))) < 1e-12 * float(np.max(np.abs(one["slab_displacement_m"])))


def test_reference_is_rotation_invariant_on_a_real_pair(records_dir):
    # an isotropic building (equal stories both ways) under the first 3 s of the PTS pair ×2, turned by 40°:
    # the answer turns with it (the friction is coupled: starts and stops in the plane)
    ax, ay, dt = _pair(records_dir, 0, 301, 2.0)
    case = building_bench.building_case("rotation", ax, dt, acceleration_y_m_s2=ay)
    angle = np.deg2rad(40.0)
    turn = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    ground = np.column_stack([ax, ay]) @ turn.T
    base = _reference(case, ax, ay)
    turned = _reference(case, ground[:, 0], ground[:, 1])
    assert base["n_starts"] >= 3
    for key in ("slab_displacement_m", "floor_displacement_m", "floor_absolute_acceleration_m_s2"):
        assert _relative(turned[key], base[key] @ turn.T) < 1e-9, key


@needs_opensees
def test_opensees_3d_building_with_a_zero_second_component_is_its_1d_model(records_dir):
    ax, _, dt = _pair(records_dir, 0, 401)
    case = building_bench.building_case("zero y", ax, dt)
    one = building_bench.opensees_building_solver(case)
    two = building_bench.opensees_building_solver(building_bench.building_case(
        "zero y", ax, dt, acceleration_y_m_s2=np.zeros_like(ax)))
    for key in ("slab", "drift", "floor_acc"):
        np.testing.assert_allclose(two[key][..., 0], one[key], rtol=0, atol=1e-12 * float(np.max(np.abs(one[key]))))
        assert float(np.max(np.abs(two[key][..., 1]))) == 0.0
    assert float(np.max(np.abs(one["slab"]))) > 1e-3


@needs_opensees
def test_opensees_3d_building_with_stiff_stories_is_the_rigid_block(records_dir):
    # stiff stories (T1 0.01 s, then 0.002 s): the slab of OpenSees' building converges to OpenSees' rigid
    # block on one singleFPBearing (isolator.bench.opensees.opensees_pair, per unit mass) under the same pair
    from isolator.bench.opensees import opensees_pair

    ax, ay, dt = _pair(records_dir, 0, 801)
    rigid = opensees_pair(dt, ax, ay, mu=building_bench.MU, radius_m=building_bench.RADIUS_M)
    errors = []
    for period in (0.01, 0.002):
        case = building_bench.building_case("stiff", ax, dt, acceleration_y_m_s2=ay, period_s=period,
                                            period_y_s=0.8 * period)
        slab = building_bench.opensees_building_solver(case)["slab"]
        errors.append(float(np.max(np.hypot(*(slab - rigid).T))) / float(np.max(np.hypot(*rigid.T))))
    assert float(np.max(np.hypot(*rigid.T))) > 0.05
    assert errors[0] < 1e-3 and errors[1] < errors[0] / 10, errors


@needs_opensees
def test_opensees_3d_building_agrees_with_the_reference_within_its_error(records_dir):
    # the bench's 2-D building (T1 0.5 s along x, 0.4 s along y) on the first 4 s of the pair ×2 (a 40 mm
    # slide): OpenSees at the record's dt within its known error (stick branch, Newmark): peak isolator
    # displacement within 5 %, drift peaks within 20 % (measured 3.1 % and 5 %)
    ax, ay, dt = _pair(records_dir, 0, 401, 2.0)
    case = building_bench.building_case("2-D", ax, dt, acceleration_y_m_s2=ay,
                                        period_y_s=building_bench.FIXED_BASE_PERIOD_Y_S)
    truth = building_bench.reference_building(case)
    theirs = building_bench.opensees_building_solver(case)
    e = building_bench.building_errors(theirs, truth)
    assert building_bench.is_planar(truth) and theirs["slab"].shape == (401, 2) and theirs["drift"].shape == (401, 5, 2)
    assert float(np.max(np.hypot(*truth["slab"].T))) > 0.03
    assert e["error_peak_slab"] < 0.05 and e["error_peak_drift"] < 0.2, e


def test_both_sides_see_the_same_record(monkeypatch):
    # ours (through the registry's Scene), the reference and OpenSees receive the case's two components as
    # they are, on the same dt
    import isolator.bench.opensees_building as opensees_building_module
    import isolator.bench.planar_building_reference as reference_module
    import isolator.solver.models as models

    t = np.arange(50) * 0.01
    case = building_bench.building_case("same", np.sin(5 * t), 0.01, acceleration_y_m_s2=np.cos(3 * t)[:45])
    assert case.acceleration_m_s2.size == case.acceleration_y_m_s2.size == 45  # trimmed to the shorter
    seen = {}

    def fake_opensees(dt_s, ax, ay=None, **kwargs):
        seen["opensees"] = (dt_s, ax, ay)
        raise RuntimeError("stop")

    def fake_reference(ax, ay, dt_s, **kwargs):
        seen["reference"] = (dt_s, ax, ay)
        raise RuntimeError("stop")

    def fake_simulate(scene):
        seen["ours"] = (scene.dt_s, scene.ax_m_s2, scene.ay_m_s2)
        raise RuntimeError("stop")

    monkeypatch.setattr(opensees_building_module, "opensees_building", fake_opensees)
    monkeypatch.setattr(reference_module, "planar_building_reference", fake_reference)
    monkeypatch.setattr(models, "simulate", fake_simulate)
    for run in (building_bench.opensees_building_solver, building_bench.reference_building,
                building_bench.ours_building):
        with pytest.raises(RuntimeError, match="stop"):
            run(case)
    for dt_s, ax, ay in seen.values():
        assert dt_s == case.dt_s and ax is case.acceleration_m_s2 and ay is case.acceleration_y_m_s2
    assert set(seen) == {"opensees", "reference", "ours"}


def test_planar_errors_are_vector_differences():
    t = np.linspace(0.0, 1.0, 11)
    slab = np.column_stack([np.sin(t), np.cos(t)])
    floors = np.stack([slab, 2 * slab], axis=1)
    truth = building_bench._histories(slab, floors, floors)
    assert building_bench.is_planar(truth) and truth["drift"].shape == (11, 2, 2)
    shifted = building_bench._histories(slab + [0.03, 0.04], floors, floors)
    e = building_bench.building_errors(shifted, truth)
    assert e["error_slab"] == pytest.approx(0.05 / float(np.max(np.hypot(*slab.T))), rel=1e-12)  # |(0.03, 0.04)|
    assert e["error_drift"] == 0.0 and e["error_floor_acc"] == 0.0
    peaks = building_bench.sampled_peaks(truth)
    assert peaks["slab"] == pytest.approx(1.0) and peaks["drift"] == pytest.approx([1.0, 1.0])


def test_run_building_case_2d_without_our_engine_measures_opensees_against_the_reference(records_dir, monkeypatch):
    # the 2-D building case on a branch without the 2d-building model: ours is a note, OpenSees (when it
    # runs) is measured against the independent reference, no ratio is claimed
    monkeypatch.setattr(building_bench, "planar_building_available", lambda: (False, "not here"))
    ax, ay, dt = _pair(records_dir, 0, 151, 2.0)
    case = building_bench.building_case("2-D", ax, dt, acceleration_y_m_s2=ay, period_y_s=0.4)
    result = building_bench.run_building_case(case, rounds=1)
    assert result["planar"] and result["ours"]["seconds"] is None and result["ours"]["note"] == "not here"
    assert result["time_ratio"] is None and result["error_ratio"] is None
    line = building_bench.building_summary([result])[0]
    assert "ours not run (not here)" in line
    if OPENSEES_OK:
        assert result["opensees"]["errors_against"] == "the reference" and result["opensees"]["error_max"] > 0
        assert "vs the reference" in line
    assert "| — |" in building_bench.building_markdown([result])


PLANAR_OK, PLANAR_WHY = building_bench.planar_building_available()


@pytest.mark.skipif(not PLANAR_OK, reason=f"our 2-D building: {PLANAR_WHY}")
def test_ours_in_2d_agrees_with_the_reference_and_the_harness_reports_both_ratios(records_dir):
    # the bench's 2-D building on the first 3 s of the pair ×2: ours (the registry's 2d-building) within 1e-9 of
    # the independent reference on every history; with OpenSees, the run reports both ratios
    ax, ay, dt = _pair(records_dir, 0, 301, 2.0)
    case = building_bench.building_case("2-D", ax, dt, acceleration_y_m_s2=ay,
                                        period_y_s=building_bench.FIXED_BASE_PERIOD_Y_S)
    result = building_bench.run_building_case(case, rounds=1, ours_per_round=2)
    ours = result["ours"]
    assert ours["method"] == building_bench.BUILDING_OURS_2D and ours["runs"] == 2
    assert ours["error_max"] < 1e-9, ours
    assert ours["peaks"]["slab"] >= ours["sampled_peaks"]["slab"] > 0.01  # exact peak ≥ the sampled one
    if OPENSEES_OK:
        assert result["opensees"]["errors_against"] == "ours"
        assert result["time_ratio"] == pytest.approx(result["opensees"]["seconds"] / ours["seconds"])
        assert result["error_ratio"] > 1e3
        assert "faster than OpenSees" in building_bench.building_summary([result])[0]
        # h184: the second row at the looser end check, with its own measured errors and ratios from one alternation
        loose = result["ours_loose"]
        assert loose["check"] == building_bench.BUILDING_LOOSE_CHECK and loose["runs"] == 2
        assert loose["errors_against"] == "the reference" and loose["error_max"] < 1e-9, loose
        assert loose["time_ratio"] == pytest.approx(loose["opensees_seconds"] / loose["seconds"])
        assert loose["default_time_ratio"] == pytest.approx(loose["opensees_seconds"] / loose["default_seconds"])
        assert loose["error_ratio"] == pytest.approx(result["opensees"]["error_max"] / loose["error_max"])
        lines = building_bench.building_summary([result])
        assert len(lines) == 2 and f"at end check {building_bench.BUILDING_LOOSE_CHECK:g}" in lines[1]
