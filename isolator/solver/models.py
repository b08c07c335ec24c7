"""The solver model registry: which model a scene needs, chosen once, and the run of it.

In the manner of ``scipy.integrate._ivp`` (``METHODS`` and one ``OdeResult``): every
caller — ``isolator simulate``, the analysis, the report, the batch, the review — builds a
:class:`~isolator.solver.base.Scene` and calls :func:`simulate`; none of them chooses a
model.  Every model returns a :class:`~isolator.solver.base.SolverResult` (one set of
summary keys, :data:`~isolator.solver.base.SUMMARY_KEYS`) whose ``model`` and
``model_reason`` say which model ran and why.

How to add a model
------------------
1. Write a module under ``isolator/solver/`` with two functions::

       def scene_needs(scene: Scene) -> tuple[str, str] | None:
           '''(model name, reason) when this model is the one the scene needs, else None.'''

       def simulate_scene(scene: Scene) -> MyResult:   # MyResult subclasses SolverResult
           ...

   ``MyResult`` is a ``@dataclass(kw_only=True)`` subclass of
   :class:`~isolator.solver.base.SolverResult`; scalars beyond the common ones go in its
   ``EXTRA_SUMMARY_KEYS`` (and in ``docs/schema.md``).  What the model needs beyond the
   equivalent single bearing (floors, bearing surfaces) it reads from ``scene.design``;
   import nothing from this module (the registry imports the models, not the reverse).
2. Add one line to :data:`MODELS` **above** the models it specialises: :func:`select_model`
   asks the models in this order and takes the first that answers (``2d``, the general
   rigid-block engine, is last).

One choice depends on a result: a single pendulum with a ``displacement_capacity_m`` under one
component is ``1d-exact`` (its reason says so), and when that run's peak reaches the capacity
the multi-surface module runs the scene again with the rim; that result has ``rerun`` true and
keeps its own ``model`` (``1d-multisurface``) and ``model_reason`` (:func:`simulate`).  The same holds in the
plane: a single pendulum with a capacity that needs the 2-D engine runs ``2d`` (its reason says so), and when
its peak reaches the capacity :mod:`isolator.solver.planar_rim` runs it again with the rim (``2d+rim``,
``rerun`` true).  A building on a single pendulum with a capacity under one component runs ``1d-building``,
and past the capacity :mod:`isolator.solver.building_multisurface` runs it again with the rim
(``1d-building-multisurface``, ``rerun`` true); under a pair it runs ``2d-building``, and past the capacity
:mod:`isolator.solver.planar_building_multisurface` runs it again with the rim (``2d-building-multisurface``,
``rerun`` true).  With a vertical or µ(v) the 2-D building has no rim: past the capacity its result says so
(:func:`isolator.solver.building_multisurface.say_if_capacity_passed`, a notice in ``solver_status``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from isolator.solver import (
    building,
    building_multisurface,
    multisurface,
    multisurface_rate,
    planar,
    planar_building,
    planar_building_multisurface,
    planar_multisurface,
    planar_multisurface_rate,
    planar_rim,
    record,
)
from isolator.solver.base import SUMMARY_KEYS, Scene, SolverResult


@dataclass(frozen=True)
class Model:
    """One entry of the registry.

    Attributes
    ----------
    name : str
        Registry key, and the first part of the ``model`` a result reports (``"2d"`` runs as
        ``"2d+vertical+mu(v)"`` …).
    needs : callable
        ``needs(scene) -> (model, reason)`` when the scene needs this model, else None.
    run : callable
        ``run(scene) -> SolverResult``.
    description : str
        One line for the documentation.
    warm_up : callable
        ``warm_up()``: load (on a cold cache: compile) the model's numba kernels on a tiny problem, once per process
        (later calls return at once); a model without compiled kernels leaves the default, which does nothing.
        :func:`warm_up` calls it by the model's name.
    """

    name: str
    needs: Callable
    run: Callable
    description: str
    warm_up: Callable = lambda: None


#: The models, most specific first: :func:`select_model` takes the first whose ``needs`` answers.
MODELS: dict[str, Model] = {model.name: model for model in (
    Model(multisurface_rate.MODEL_NAME, multisurface_rate.scene_needs, multisurface_rate.simulate_scene,
          "mass on a double or triple friction pendulum with µ(v) surfaces, one component: Radau IIA with events",
          warm_up=multisurface_rate._warm_up),
    Model(planar_multisurface_rate.MODEL_NAME, planar_multisurface_rate.scene_needs,
          planar_multisurface_rate.simulate_scene, "mass on a double or triple friction pendulum with µ(v) surfaces "
          "under a pair: Radau IIA with events, coupled friction, no rims",
          warm_up=planar_multisurface_rate._warm_up),
    Model(planar_building_multisurface.MODEL_NAME, planar_building_multisurface.scene_needs,
          planar_building_multisurface.simulate_scene, "shear building on a double or triple friction pendulum under a "
          "pair (and its vertical): implicit steps with rims, the floors exact within each step",
          warm_up=planar_building_multisurface._warm_up),
    Model(planar_multisurface.MODEL_NAME, planar_multisurface.scene_needs, planar_multisurface.simulate_scene,
          "mass on a double or triple friction pendulum in the plane (series model, coupled friction): DOP853",
          warm_up=planar_multisurface._warm_up),
    Model(building_multisurface.MODEL_NAME, building_multisurface.scene_needs, building_multisurface.simulate_scene,
          "shear building on a double or triple friction pendulum, one component: exact between events, rims",
          warm_up=building_multisurface._warm_up),
    Model(multisurface.MODEL_NAME, multisurface.scene_needs, multisurface.simulate_scene,
          "mass on a double or triple friction pendulum (series model, rims), one component: closed forms",
          warm_up=multisurface._warm_up),
    Model(planar_building.MODEL_NAME, planar_building.scene_needs, planar_building.simulate_scene,
          "shear building on the isolation plane under a pair: friction coupled in the plane, Taylor series pieces",
          warm_up=planar_building._warm_up),
    Model(building.MODEL_NAME, building.scene_needs, building.simulate_scene,
          "shear building on the isolation plane under one component: exact linear propagation between events",
          warm_up=building._warm_up),
    Model(record.MODEL_NAME, record.scene_needs, record.simulate_scene,
          "rigid block on one surface under one component, constant friction: closed forms between events",
          warm_up=record._warm_up_kernel),
    Model(planar_rim.MODEL_NAME, planar_rim.scene_needs, planar_rim.simulate_scene,
          "single pendulum with a displacement capacity under a pair (or a vertical, µ(v)): the 2-D engine, rerun "
          "with the rim (plastic impact, sliding along it) when the peak reaches the capacity",
          warm_up=planar._warm_up),
    Model(planar.MODEL_NAME, planar.scene_needs, planar.simulate_scene,
          "rigid block on one surface in the plane: coupled friction, µ(v), n(t) = g + a_z (DOP853 between events)",
          warm_up=planar._warm_up),
)}


#: One model per distinct warm-up (``2d+rim`` is warmed by ``2d``, its engine), the costliest to compile cold first (on
#: a 2-core machine the 2-D multi-surface ones take 1.5-10 min of CPU each): the order in which a warm-up of several
#: processes starts them (tests/conftest.py), and :func:`warm_up`'s order when no name is given.
WARM_UP_ORDER: tuple[str, ...] = (
    planar_multisurface_rate.MODEL_NAME, planar_building_multisurface.MODEL_NAME, planar_multisurface.MODEL_NAME,
    planar_building.MODEL_NAME, planar.MODEL_NAME, building_multisurface.MODEL_NAME, multisurface_rate.MODEL_NAME,
    building.MODEL_NAME, multisurface.MODEL_NAME, record.MODEL_NAME,
)


def warm_up(*names: str) -> None:
    """Load (on a cold cache: compile) the numba kernels of the models ``names`` (all models when none is given).

    Each model's warm-up runs its engine once on a tiny problem and is cached in the process: a second call, or a
    model sharing an engine with one already warmed (``2d+rim`` and ``2d``), returns at once.  Used by
    :func:`isolator.parallel.warm_up` (before a pool forks), the bench (before it times) and the tests' warm-up.

    Raises
    ------
    KeyError
        A name not in :data:`MODELS` (the message lists the names).
    """
    unknown = [name for name in names if name not in MODELS]
    if unknown:
        raise KeyError(f"no solver model {', '.join(map(repr, unknown))}; the models: {', '.join(MODELS)}")
    done: set = set()
    for name in names or WARM_UP_ORDER:
        function = MODELS[name].warm_up
        if function not in done:  # bounded: one call per distinct warm-up
            done.add(function)
            function()


def _choose(scene: Scene) -> tuple[Model, str, str]:
    for model in MODELS.values():
        answer = model.needs(scene)
        if answer is not None:
            return model, answer[0], answer[1]
    raise LookupError("no solver model takes this scene")  # pragma: no cover - "2d" takes every scene


def select_model(scene: Scene) -> tuple[str, str]:
    """The model a scene needs, and why (issue 10, "model only what the scene needs").

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    tuple of str
        ``(model, reason)``, e.g. ``("1d-exact", "one horizontal component, …")`` or
        ``("2d+vertical", "the 2-D engine, for …")``.
    """
    _, name, reason = _choose(scene)
    return name, reason


def simulate(scene: Scene) -> SolverResult:
    """Run the model the scene needs (:func:`select_model`) and say which ran and why.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    SolverResult
        The model's result; ``model`` and ``model_reason`` as :func:`select_model` gives them.

    Raises
    ------
    isolator.solver.system.InvalidSystemError
        An invalid isolator.
    isolator.errors.RecordInputError
        A motion the model cannot take.
    """
    _check_rtol(scene.isolator.get("rtol") if hasattr(scene.isolator, "get") else None)
    model, name, reason = _choose(scene)
    result = model.run(scene)
    if not getattr(result, "rerun", False):  # a model that ran the scene again on another names that one itself
        result.model, result.model_reason = name, reason
    building_multisurface.say_if_capacity_passed(scene, result)  # a building run past its capacity without a rim
    return result


def _check_rtol(rtol) -> None:
    """The scene's ``rtol`` is a positive finite number or absent, whichever model runs: the exact 1-D models and the
    buildings do not use it, and took ``"x"``, NaN or -1 without a word (session 19 sweep); the models that use it
    check their own range (``planar.RTOL_RANGE``, ``planar_multisurface.RTOL_RANGE``)."""
    import math
    from numbers import Real

    from isolator.errors import InvalidSystemError

    if rtol is None:
        return
    if isinstance(rtol, bool) or not isinstance(rtol, Real) or not (math.isfinite(rtol) and rtol > 0):
        raise InvalidSystemError(f"rtol must be a finite number > 0 (a relative tolerance, or absent for the "
                                 f"default), got {rtol!r}")


def simulate_motion(ax_m_s2, ay_m_s2=None, az_m_s2=None, dt_s=None, *, time_s=None, design=None,
                    **isolator) -> SolverResult:
    """:func:`simulate` on arrays: one component, a pair, or a pair and a vertical.

    Parameters
    ----------
    ax_m_s2, ay_m_s2, az_m_s2 : array_like
        Ground acceleration [m/s²]; ``ay``/``az`` optional.
    dt_s : float, optional
        Sample interval [s]; or give ``time_s`` [s].
    design : Design, optional
        For models that need more than the isolator keywords.
    **isolator
        The keywords of :func:`isolator.solver.planar.simulate_pair` (mu_static, mu_kinetic, radius_m, …).
    """
    return simulate(Scene(ax_m_s2=ax_m_s2, ay_m_s2=ay_m_s2, az_m_s2=az_m_s2, dt_s=dt_s, time_s=time_s,
                          isolator=isolator, design=design))


__all__ = ["MODELS", "SUMMARY_KEYS", "WARM_UP_ORDER", "Model", "Scene", "SolverResult", "select_model", "simulate",
           "simulate_motion", "warm_up"]
