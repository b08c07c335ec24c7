"""The analysis of a design under a pair of components (and a vertical), on the model the scene needs.

``analyse_pair(design, motions)`` (reached through :func:`isolator.analysis.analyse` for
a pair, a vertical or µ(v)) runs :func:`isolator.solver.planar.simulate_motion`
on the components of a :class:`~isolator.motion.MotionPair` (or one
:class:`~isolator.motion.GroundMotion`) with the design's isolator
(:func:`isolator.adapter.motion_keywords`) and returns a :class:`PairAnalysis`, whose
:meth:`~PairAnalysis.to_dict` is the one schema of :mod:`isolator.analysis` for a 2-D
response: the model that ran and why first, then the results under the same names as
a 1-D analysis (units in the names, energies per unit mass), plus the pair's own
(``residual_displacement_x_m``/``_y_m``, ``uplift_time_s``, the displacement demand).
"""

from __future__ import annotations

import datetime as _dt
from dataclasses import dataclass, field


def response_summary(result) -> dict:
    """The scalar results of a 1-D or 2-D response under one set of keys, the model first.

    Both summaries carry the same keys (a 1-D response moves along X: its resultant
    peak is its peak, ``residual_displacement_x_m`` its signed residual, Y zero, no
    uplift); this puts the model and why first.

    Parameters
    ----------
    result : Response or PairResponse
        From :func:`isolator.solver.planar.simulate_motion`.

    Returns
    -------
    dict
        ``model``, ``model_reason``, ``peak_displacement_m`` (resultant),
        ``residual_displacement_m`` (resultant; signed for 1-D), ``residual_displacement_x_m``,
        ``residual_displacement_y_m``, ``peak_velocity_m_s``,
        ``peak_transmitted_acceleration_m_s2``, ``slip_time_s``, ``uplift_time_s``,
        ``n_uplifts``, ``n_events``, energies [J/kg] (``energy_input_J_per_kg`` …),
        ``solver_seconds``, ``configuration``, ``solver_status``.
    """
    summary = dict(result.summary())
    first = {"model": summary.pop("model", getattr(result, "model", "1d-exact")),
             "model_reason": summary.pop("model_reason", getattr(result, "model_reason", ""))}
    return {**first, **summary}


@dataclass
class PairAnalysis:
    """A design under a pair (or one component with µ(v) or a vertical): the response and what it means.

    Attributes
    ----------
    design : Design
    motions : MotionPair or GroundMotion
    response : PairResponse or Response
    engineering : dict
        :func:`isolator.adapter.engineering_quantities` at the resultant peak displacement.
    record_label : str
    scaling_note : str
    """

    design: object
    motions: object
    response: object
    engineering: dict = field(default_factory=dict)
    record_label: str = ""
    scaling_note: str = ""
    created_utc: str = ""

    @property
    def components(self) -> dict:
        """The ground motions analysed, by axis name (``x``, ``y``, ``z``)."""
        parts = getattr(self.motions, "components", None)
        return parts if isinstance(parts, dict) else {"x": self.motions}

    @property
    def displacement_demand_ratio(self) -> float | None:
        """Peak resultant displacement / the design's displacement capacity (None without one) [-]."""
        capacity = getattr(self.design, "displacement_capacity_m", None)
        return None if capacity is None else self.response.peak_displacement_m / capacity

    def verdicts(self) -> list[str]:
        """Plain sentences on the demand, the residual and the uplift."""
        r, out = self.response, []
        ratio = self.displacement_demand_ratio
        if ratio is not None:
            word = "within" if ratio <= 1.0 else "EXCEEDS"
            out.append(f"Peak resultant displacement {r.peak_displacement_m:.4g} m {word} the displacement "
                       f"capacity {self.design.displacement_capacity_m:.4g} m (ratio {ratio:.3g}).")
        if getattr(r, "ultimate_displacement_reached", False):  # a bearing with rims (isolator.solver.multisurface)
            out.append(f"The bearing REACHED its ultimate displacement {r.ultimate_displacement_m:.4g} m (every slider "
                       f"on its rim): plastic impact(s), impulse {self.design.mass_kg * r.impact_impulse_m_s:.4g} N·s "
                       "in all; the motion is held there, not continued past it.")
        summary = response_summary(r)
        if summary["uplift_time_s"] > 0:
            out.append(f"The bearing lifts off {summary['n_uplifts']} time(s), {summary['uplift_time_s']:.3g} s "
                       "in all (n = g + a_z <= 0: no friction, no restoring force).")
        out.append(f"Residual displacement {summary['residual_displacement_m']:.3g} m "
                   f"(x {summary['residual_displacement_x_m']:.3g} m, y {summary['residual_displacement_y_m']:.3g} m).")
        return out

    def to_dict(self) -> dict:
        """The numbers of the analysis in the one schema of :meth:`isolator.analysis.Analysis.to_dict`.

        Returns
        -------
        dict
            ``schema_version``, ``model``, ``model_reason``, ``configuration``; the response
            keys (``peak_displacement_m`` resultant, ``residual_displacement_m`` resultant,
            ``residual_displacement_x_m``/``_y_m``, ``peak_velocity_m_s``, ``slip_time_s``,
            ``uplift_time_s``, ``n_uplifts``, ``n_events``, energies in J/kg,
            ``solver_status``, ``solver_seconds``); ``displacement_capacity_m`` and
            ``displacement_demand_ratio``; ``engineering``; ``design``; ``record`` (label,
            each component's path, label, units source, PGA, processing; the set's
            processing, npts, dt_s, duration_s, uniform_sampling, scaling); ``verdicts``;
            ``software``; ``created_utc``.  JSON-safe.
        """
        from isolator import __version__
        from isolator.analysis import SCHEMA_VERSION
        from isolator.serialize import json_safe

        components = {axis: {"path": m.provenance.get("path", ""), "component": m.component,
                             "units_source": m.units_source, "pga_m_s2": m.pga_m_s2,
                             "processing": list(m.processing)}
                      for axis, m in self.components.items()}
        first = next(iter(self.components.values()))
        out = {"schema_version": SCHEMA_VERSION, **response_summary(self.response)}
        out["displacement_capacity_m"] = getattr(self.design, "displacement_capacity_m", None)
        out["displacement_demand_ratio"] = self.displacement_demand_ratio
        out["engineering"] = dict(self.engineering)
        out["design"] = self.design.as_dict() if hasattr(self.design, "as_dict") else {}
        out["record"] = {"label": self.record_label, "components": components,
                         "processing": list(getattr(self.motions, "processing", [])),
                         "npts": first.npts, "dt_s": first.dt_s, "duration_s": first.duration_s,
                         "uniform_sampling": first.sample_times_s is None, "scaling": self.scaling_note}
        out["verdicts"] = self.verdicts()
        out["software"] = {"name": "isolator", "version": __version__}
        out["created_utc"] = self.created_utc
        return json_safe(out)

    def row(self) -> dict:
        """The batch's slice of :meth:`to_dict` (:data:`ROW_KEYS` and the engineering keys of a 1-D row), flat."""
        from isolator.analysis import schema_row

        return schema_row(self.to_dict(), ROW_KEYS)


#: Keys of a batch row of a pair analysis (the harmonic columns of a 1-D row stay empty).
ROW_KEYS = ("model", "model_reason", "configuration", "peak_displacement_m", "residual_displacement_m",
            "residual_displacement_x_m", "residual_displacement_y_m", "peak_velocity_m_s",
            "peak_transmitted_acceleration_m_s2", "slip_time_s", "uplift_time_s", "n_uplifts", "n_events",
            "energy_input_J_per_kg", "energy_friction_J_per_kg", "energy_viscous_J_per_kg",
            "energy_balance_error_J_per_kg", "solver_status", "solver_seconds", "displacement_capacity_m",
            "displacement_demand_ratio")


def analyse_pair(design, motions, *, record_label: str = "", scaling_note: str = "") -> PairAnalysis:
    """Analyse a design under a pair (and a vertical) or one component, on the model the scene needs.

    Parameters
    ----------
    design : Design
        The isolator (µ(v) and the displacement capacity are used when given).
    motions : MotionPair or GroundMotion
        The components, on one time base.
    record_label, scaling_note : str
        How the record is named and was scaled, for the outputs.

    Returns
    -------
    PairAnalysis
    """
    from isolator.adapter import engineering_quantities, motion_keywords
    from isolator.solver.models import Scene, simulate

    response = simulate(Scene.of(motions, motion_keywords(design), design))
    return PairAnalysis(design=design, motions=motions, response=response,
                        engineering=engineering_quantities(design, response), record_label=record_label,
                        scaling_note=scaling_note,
                        created_utc=_dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC"))
