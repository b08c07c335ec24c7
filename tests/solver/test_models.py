"""The solver model registry: one choice of model per scene, one result type, one set of summary keys."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from isolator.solver import models
from isolator.solver.base import SUMMARY_KEYS, Scene, SolverResult
from isolator.solver.models import MODELS, Model, select_model, simulate, simulate_motion
from isolator.solver.planar import PairResponse
from isolator.solver.record import Response, simulate_record
from tests.solver.test_planar import synthetic_pair


def _rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def _scene(*, has_y, has_z, velocity_dependent):
    """A scene with just the features the choice looks at."""
    a = np.zeros(3)
    isolator = {"mu_static": 0.05}
    if velocity_dependent:
        isolator.update(mu_slow=0.03, mu_fast=0.05, rate_s_per_m=10.0)
    return Scene(ax_m_s2=a, ay_m_s2=a if has_y else None, az_m_s2=a if has_z else None, dt_s=0.01,
                 isolator=isolator)


def test_select_model_and_simulate_motion_dispatch():
    assert select_model(_scene(has_y=False, has_z=False, velocity_dependent=False))[0] == "1d-exact"
    assert select_model(_scene(has_y=True, has_z=False, velocity_dependent=False))[0] == "2d"
    assert select_model(_scene(has_y=True, has_z=True, velocity_dependent=True))[0] == "2d+vertical+mu(v)"
    name, reason = select_model(_scene(has_y=False, has_z=False, velocity_dependent=True))
    assert name == "2d+mu(v)" and "zero" in reason
    t, ax, ay = synthetic_pair(n=300)
    dt = t[1] - t[0]
    one = simulate_motion(ax, dt_s=dt, mu_static=0.06, radius_m=2.0)
    assert isinstance(one, Response) and one.model == "1d-exact" and one.summary()["model"] == "1d-exact"
    two = simulate_motion(ax, ay, dt_s=dt, mu_static=0.06, radius_m=2.0)
    assert isinstance(two, PairResponse) and two.model == "2d" and two.summary()["model_reason"]
    # a single component on a non-uniform grid stays on the exact 1-D kernel (unequal steps are exact there)
    t2 = np.sort(np.concatenate((t, t[:-1] + 0.3 * dt)))
    nonuniform = simulate_motion(np.interp(t2, t, ax), time_s=t2, mu_static=0.06, radius_m=2.0)
    assert isinstance(nonuniform, Response) and nonuniform.model == "1d-exact"
    assert _rel(nonuniform.peak_displacement_m, one.peak_displacement_m) <= 1e-12
    mu_v = simulate_motion(ax, dt_s=dt, mu_static=0.06, mu_slow=0.04, mu_fast=0.08, rate_s_per_m=10.0)
    assert mu_v.model == "2d+mu(v)"
    keys = set(one.summary()) - {"configuration"}
    assert keys <= set(two.summary())


def test_every_model_returns_the_one_result_type_with_the_declared_summary_keys():
    t, ax, ay = synthetic_pair(n=300)
    dt = t[1] - t[0]
    one = simulate(Scene(ax_m_s2=ax, dt_s=dt, isolator={"mu_static": 0.06, "radius_m": 2.0}))
    two = simulate(Scene(ax_m_s2=ax, ay_m_s2=ay, dt_s=dt, isolator={"mu_static": 0.06, "radius_m": 2.0}))
    for result in (one, two):
        assert isinstance(result, SolverResult)
        assert tuple(result.summary()) == SUMMARY_KEYS
    # the 1-D block moves along X: its x residual is its signed residual, nothing across, no uplift
    s = one.summary()
    assert s["residual_displacement_x_m"] == s["residual_displacement_m"] and s["residual_displacement_y_m"] == 0.0
    assert s["uplift_time_s"] == 0.0 and s["n_uplifts"] == 0 and s["solver_status"] == one.message == "ok"
    # the registry's 1-D run is the kernel's: a pendulum of R = 2 m is K/M = g/R
    direct = simulate_record(ax, dt, mu_static=0.06, stiffness_per_mass=9.80665 / 2.0)
    assert one.peak_displacement_m == direct.peak_displacement_m
    assert np.array_equal(one.displacement_m, direct.displacement_m)


def test_a_registered_model_is_chosen_in_its_place_and_reports_its_name(monkeypatch):
    """Adding a model is a registry line: the first model that answers runs, and the result says so."""
    calls = []

    def needs(scene):
        return ("1d-test", "a scene with a design flagged for the test model") if scene.design == "flagged" else None

    def run(scene):
        calls.append(scene)
        return MODELS["1d-exact"].run(scene)

    registry = {"1d-test": Model("1d-test", needs, run, "test model"), **MODELS}
    monkeypatch.setattr(models, "MODELS", registry)
    t, ax, _ = synthetic_pair(n=200)
    plain = Scene(ax_m_s2=ax, dt_s=0.01, isolator={"mu_static": 0.06, "radius_m": 2.0})
    flagged = dataclasses.replace(plain, design="flagged")
    assert select_model(plain)[0] == "1d-exact" and simulate(plain).model == "1d-exact" and not calls
    result = simulate(flagged)
    assert len(calls) == 1 and result.model == "1d-test" and "flagged" in result.model_reason


@pytest.mark.parametrize("isolator, word", [
    ({"mu_static": 0.05, "radius_m": -1.0}, "radius_m"),
    ({"mu_static": 0.05, "radius_m": 2.0, "stiffness_per_mass": 3.0}, "not both"),
    ({"mu_static": -0.05, "radius_m": 2.0}, "mu_static"),
])
def test_the_1d_model_refuses_an_invalid_isolator(isolator, word):
    from isolator.solver.system import InvalidSystemError

    with pytest.raises(InvalidSystemError, match=word):
        simulate(Scene(ax_m_s2=np.array([0.0, 1.0, 0.0]), dt_s=0.01, isolator=isolator))


def test_the_registry_warms_every_kernel_the_tests_warmed_before_each_once():
    """:data:`models.WARM_UP_ORDER` names one model per distinct warm-up, and together they are exactly the ten
    engine warm-ups tests/conftest.py called by their private names up to e9efb0c, in the same order (the costliest
    first): nothing compiles twice, nothing less than before.  Also: an unknown name is refused by name."""
    before = [("planar_multisurface_rate", "_warm_up"), ("planar_building_multisurface", "_warm_up"),
              ("planar_multisurface", "_warm_up"), ("planar_building", "_warm_up"), ("planar", "_warm_up"),
              ("building_multisurface", "_warm_up"), ("multisurface_rate", "_warm_up"), ("building", "_warm_up"),
              ("multisurface", "_warm_up"), ("record", "_warm_up_kernel")]
    functions = [MODELS[name].warm_up for name in models.WARM_UP_ORDER]
    assert [(f.__module__.removeprefix("isolator.solver."), f.__name__) for f in functions] == before
    assert {model.warm_up for model in MODELS.values()} == set(functions)  # every model's warm-up is in the order
    with pytest.raises(KeyError, match="no solver model 'nope'.*1d-exact"):
        models.warm_up("1d-exact", "nope")
