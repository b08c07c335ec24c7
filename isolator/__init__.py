"""isolator: exact event-driven analysis of friction isolators under ground motion.

The physics is M. Nicolas (2017), *A comprehensive study on the behavior of a rigid
block on an oscillating ground with friction, elastic and viscous forces*
(hal-01432172), generalised from harmonic to recorded ground acceleration.

Public API (imported lazily, so that ``import isolator`` and ``isolator --help``
stay instant)::

    simulate_record(acceleration_m_s2, dt_s, mu_static=..., ...) -> Response
    simulate_pair(ax_m_s2, ay_m_s2, dt_s, mu_static=..., az_m_s2=None, radius_m=None, ...) -> PairResponse
    simulate(Scene(ax_m_s2, ay_m_s2=None, az_m_s2=None, dt_s=..., isolator={...})) -> SolverResult
        (the model registry, isolator.solver.models: select_model(scene) once, then that model;
        simulate_motion(ax, ay=None, az=None, dt_s, **isolator) is the same on arrays)
    harmonic_response(alpha, k, eta, mu_s, mu_k=None) -> HarmonicResponse
    harmonic_thresholds(k, eta, mu_s, mu_k=None, alpha_max=6) -> RegimeThresholds
    System(mu_static, mu_kinetic, stiffness_per_mass, damping_per_mass, gravity_m_s2)
    read_ground_motion(path, component=None, units=None, ...) -> GroundMotion
    read_motion(path, RecordOptions(component=..., pair=..., vertical=..., units=..., defaults=...))
        -> GroundMotion or MotionPair;  motion.scaled_to_pga(pga_m_s2) (a pair: its larger horizontal)
    Design.from_toml(path) -> Design;  adapt(design, motion) -> Adaptation (System, (α, k, η))
    analyse(design, motion | pair) -> Analysis (one type; .to_dict() is the schema, docs/schema.md)
    classify_record(response, point) / classify_harmonic(harmonic_response) -> Classification
    regime_map(eta, mu_s, mu_k, k_range=..., alpha_range=...) -> RegimeMap (cached)
    design_search(design, target, suite, ["radius_m=1.5:4.5:13", ...]) -> DesignSearch (every candidate reviewed)
"""

from __future__ import annotations

_EXPORTS = {
    "simulate_record": "isolator.solver.record",
    "Response": "isolator.solver.record",
    "simulate_pair": "isolator.solver.planar",
    "PairResponse": "isolator.solver.planar",
    "simulate_motion": "isolator.solver.models",
    "simulate": "isolator.solver.models",
    "select_model": "isolator.solver.models",
    "Scene": "isolator.solver.models",
    "SolverResult": "isolator.solver.models",
    "harmonic_response": "isolator.solver.harmonic",
    "HarmonicResponse": "isolator.solver.harmonic",
    "harmonic_thresholds": "isolator.solver.thresholds",
    "System": "isolator.solver.system",
    "pseudo_acceleration_spectrum": "isolator.solver.linear",
    "read_ground_motion": "isolator.motion",
    "read_motion": "isolator.motion",
    "RecordOptions": "isolator.motion",
    "GroundMotion": "isolator.motion",
    "MotionPair": "isolator.motion",
    "Design": "isolator.design",
    "adapt": "isolator.adapter",
    "classify_record": "isolator.metrics",
    "classify_harmonic": "isolator.metrics",
    "regime_map": "isolator.maps",
    "design_search": "isolator.review.design_space",
    "analyse": "isolator.analysis",
    "Analysis": "isolator.analysis",
    "IsolatorError": "isolator.errors",
    "RecordError": "isolator.errors",
    "MotionError": "isolator.errors",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str):
    if name == "__version__":
        # the installed distribution's version (pyproject.toml), looked up on first use only:
        # importlib.metadata costs ~0.1-0.3 s to import, which `import isolator` must not pay
        from importlib.metadata import PackageNotFoundError, version

        try:
            found = version("isolator")
        except PackageNotFoundError:  # a source tree run without being installed
            found = "0+unknown"
        globals()["__version__"] = found
        return found
    if name in _EXPORTS:
        import importlib

        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'isolator' has no attribute {name!r}")
