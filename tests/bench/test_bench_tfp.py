"""The triple friction pendulum cases of the bench (isolator.bench.tfp): ours against OpenSees' element.

The argument mapping and the tables run everywhere; the comparisons skip without
``../shared`` (the record) or openseespy.
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.bench import tfp as tfp_bench
from isolator.bench.opensees import opensees_available
from isolator.bench.opensees_tfp import tfp_arguments

OPENSEES_OK, OPENSEES_WHY = opensees_available()
needs_opensees = pytest.mark.skipif(not OPENSEES_OK, reason=f"OpenSees baseline: {OPENSEES_WHY}")


def _case(records_dir, seconds, scale):
    from isolator.motion import read_ground_motion

    motion = read_ground_motion(records_dir / tfp_bench.TFP_RECORD[1])
    acc = scale * motion.acceleration_m_s2[:round(seconds / motion.dt_s) + 1]
    return tfp_bench.TfpCase(f"test x{scale:g}", acc, motion.dt_s, tfp_bench.tfp_bearing())


def test_opensees_arguments_follow_the_element_numbering():
    # pendulum 1 = the inner surfaces, 2 = the outer one of lower friction, 3 = the other
    mus, lengths, capacities = tfp_arguments(tfp_bench.tfp_bearing())
    assert mus == (0.02, 0.06, 0.10) and lengths == (0.3, 2.1, 2.1) and capacities == (0.05, 0.4, 0.4)
    from dataclasses import replace

    b = tfp_bench.tfp_bearing()
    swapped = replace(b, surfaces=(b.surfaces[3], b.surfaces[1], b.surfaces[2], b.surfaces[0]))
    assert tfp_arguments(swapped)[0] == (0.02, 0.06, 0.10)
    uneven = replace(b, surfaces=(b.surfaces[0], b.surfaces[1], replace(b.surfaces[2], mu_kinetic=0.03), b.surfaces[3]))
    with pytest.raises(ValueError, match="identical inner surfaces"):
        tfp_arguments(uneven)
    with pytest.raises(ValueError, match="triple"):
        tfp_arguments(replace(b, kind="double", surfaces=b.surfaces[:2]))


def test_errors_and_summary_without_opensees():
    truth = np.sin(np.linspace(0, 3, 31))
    e = tfp_bench.trajectory_errors(truth + 0.01, truth)
    assert e["error_trajectory"] == pytest.approx(0.01 / np.max(np.abs(truth)))
    result = {"case": "c", "regimes": ["I", "II"], "ours": {"seconds": 1e-3, "runs": 5},
              "opensees": {"seconds": None, "note": "openseespy not installed"}, "time_ratio": None,
              "error_ratio": None}
    (line,) = tfp_bench.tfp_summary([result])
    assert "regimes I-II" in line and "not measured (openseespy not installed)" in line


def test_no_record_no_case(tmp_path):
    assert tfp_bench.tfp_cases(True, tmp_path) == []


@needs_opensees
def test_opensees_tfp_agrees_with_ours_through_regimes_I_to_V(records_dir):
    # NWH360 x2, 10 s: ours goes through regimes I-V (outer rims) below the ultimate; OpenSees at the
    # record's dt within its known error (elastic stick branch uy = 0.5 mm): measured 0.7 % on the peak,
    # 2 % on the trajectory (20 s)
    case = _case(records_dir, 10.0, 2.0)
    ours = tfp_bench.ours_tfp(case)
    assert list(ours.regimes) == ["I", "II", "III", "IV", "V"] and not ours.ultimate_displacement_reached
    theirs = tfp_bench.opensees_tfp_solver(case)
    e = tfp_bench.trajectory_errors(theirs, ours.displacement_m)
    assert e["error_peak"] < 0.02 and e["error_trajectory"] < 0.05, e
    # and not a coincidence: OpenSees' answer is far from a single pendulum's of the outer radius
    assert np.max(np.abs(theirs)) > 0.75  # past the inner capacity (regime IV starts at 0.752 m)


@needs_opensees
def test_run_tfp_case_with_a_reference(records_dir):
    case = _case(records_dir, 4.0, 1.0)
    ref = tfp_bench.ours_tfp(case).displacement_m.copy()
    result = tfp_bench.run_tfp_case(case, rounds=1, ours_per_round=2, reference=lambda c: ref)
    assert result["ours"]["error_trajectory"] == 0.0 and result["opensees"]["runs"] == 1
    assert result["time_ratio"] == pytest.approx(result["opensees"]["seconds"] / result["ours"]["seconds"])
    assert "faster than OpenSees' TripleFrictionPendulum" in tfp_bench.tfp_summary([result])[0]


def test_run_tfp_case_without_opensees(records_dir, monkeypatch):
    import isolator.bench.opensees as opensees_module

    monkeypatch.setattr(opensees_module, "opensees_available", lambda: (False, "openseespy not installed"))
    result = tfp_bench.run_tfp_case(_case(records_dir, 2.0, 1.0), rounds=1, ours_per_round=1)
    assert result["time_ratio"] is None and result["opensees"]["note"] == "openseespy not installed"


def _pair_case(records_dir, seconds):
    from isolator.motion import read_ground_motion

    _, folder, fx, fy = tfp_bench.TFP_PAIR
    mx, my = (read_ground_motion(records_dir / folder / f) for f in (fx, fy))
    keep = round(seconds / mx.dt_s) + 1
    return tfp_bench.TfpCase("test pair", mx.acceleration_m_s2[:keep], mx.dt_s, tfp_bench.tfp_bearing(),
                             acceleration_y_m_s2=my.acceleration_m_s2[:keep])


@needs_opensees
def test_opensees_tfp_in_2d_with_a_zero_second_component_is_its_1d_answer(records_dir):
    case = _case(records_dir, 6.0, 2.0)
    one = tfp_bench.opensees_tfp_solver(case)
    two = tfp_bench.opensees_tfp_solver(tfp_bench.TfpCase("zero y", case.acceleration_m_s2, case.dt_s, case.bearing,
                                                          acceleration_y_m_s2=np.zeros_like(case.acceleration_m_s2)))
    assert two.shape == (one.size, 2) and float(np.max(np.abs(two[:, 1]))) == 0.0
    np.testing.assert_allclose(two[:, 0], one, rtol=0, atol=1e-12 * float(np.max(np.abs(one))))
    assert float(np.max(np.abs(one))) > 0.1


def test_2d_case_without_our_engine(records_dir, monkeypatch):
    # the 2-D TFP case on a branch without the 2d-multisurface model: ours is a note, OpenSees (when it
    # runs) is measured against the reference given, no ratio is claimed
    monkeypatch.setattr(tfp_bench, "planar_tfp_available", lambda: (False, "not here"))
    case = _pair_case(records_dir, 2.0)
    truth = np.zeros((case.acceleration_m_s2.size, 2))
    truth[:, 0] = 1.0  # a stand-in reference: OpenSees' error against it is |x − (1, 0)| / 1
    result = tfp_bench.run_tfp_case(case, rounds=1, reference=lambda c: truth)
    assert result["planar"] and result["ours"]["seconds"] is None and result["time_ratio"] is None
    (line,) = tfp_bench.tfp_summary([result])
    assert "ours not run (not here)" in line
    if OPENSEES_OK:
        x = tfp_bench.opensees_tfp_solver(case)
        assert result["opensees"]["errors_against"] == "the reference"
        assert result["opensees"]["error_trajectory"] == pytest.approx(float(np.max(np.hypot(x[:, 0] - 1.0, x[:, 1]))))


def test_both_sides_see_the_same_pair(monkeypatch):
    # ours (through the registry's Scene, with the bench's bearing) and OpenSees receive the case's components
    import isolator.bench.opensees_tfp as opensees_tfp_module
    import isolator.solver.models as models

    t = np.arange(40) * 0.01
    case = tfp_bench.TfpCase("same", np.sin(4 * t), 0.01, tfp_bench.tfp_bearing(), acceleration_y_m_s2=np.cos(2 * t))
    seen = {}

    def fake_opensees(dt_s, ax, ay=None, **kwargs):
        seen["opensees"] = (dt_s, ax, ay, kwargs["bearing"])
        raise RuntimeError("stop")

    def fake_simulate(scene):
        seen["ours"] = (scene.dt_s, scene.ax_m_s2, scene.ay_m_s2, scene.design.bearing)
        raise RuntimeError("stop")

    monkeypatch.setattr(opensees_tfp_module, "opensees_tfp", fake_opensees)
    monkeypatch.setattr(models, "simulate", fake_simulate)
    for run in (tfp_bench.opensees_tfp_solver, tfp_bench.ours_tfp):
        with pytest.raises(RuntimeError, match="stop"):
            run(case)
    for dt_s, ax, ay, bearing in seen.values():
        assert dt_s == case.dt_s and ax is case.acceleration_m_s2 and ay is case.acceleration_y_m_s2
        assert bearing is case.bearing
    assert set(seen) == {"opensees", "ours"}


def test_2d_errors_are_vector_differences():
    truth = np.column_stack([np.sin(np.linspace(0, 3, 31)), np.cos(np.linspace(0, 3, 31))])
    e = tfp_bench.trajectory_errors(truth + [0.03, 0.04], truth)
    assert e["error_trajectory"] == pytest.approx(0.05 / float(np.max(np.hypot(*truth.T))), rel=1e-12)


@needs_opensees
def test_the_2d_pair_has_a_second_row_at_the_loose_rtol_with_its_own_error_and_ratios(records_dir):
    # h171: ours at TFP_LOOSE_RTOL beside the default, each row with its own measured error and ratios
    case = _pair_case(records_dir, 4.0)
    tight = tfp_bench.ours_tfp(case, rtol=1e-13).displacement_m.copy()
    result = tfp_bench.run_tfp_case(case, rounds=1, ours_per_round=1, reference=lambda c: tight)
    loose = result["ours_loose"]
    assert loose["rtol"] == tfp_bench.TFP_LOOSE_RTOL and loose["errors_against"] == "the reference"
    assert loose["error_trajectory"] > result["ours"]["error_trajectory"] and loose["error_trajectory"] < 1e-8
    assert loose["time_ratio"] == pytest.approx(loose["opensees_seconds"] / loose["seconds"]) and loose["runs"] == 1
    assert loose["default_time_ratio"] == pytest.approx(loose["opensees_seconds"] / loose["default_seconds"])
    assert loose["error_ratio"] == pytest.approx(result["opensees"]["error_trajectory"] / loose["error_trajectory"])
    lines = tfp_bench.tfp_summary([result])
    assert len(lines) == 2 and f"at rtol {tfp_bench.TFP_LOOSE_RTOL:g}" in lines[1]
