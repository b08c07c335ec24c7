"""The analysis behind a report and the JSON of its numbers.

One call, :func:`analyse`, runs the record through the design (exact solver), maps it
onto the paper's dimensionless point, solves the harmonic problem at that point and
classifies both responses by the same rules (:mod:`isolator.metrics`).
"""

from __future__ import annotations

import datetime as _dt
from dataclasses import dataclass, field


from isolator.adapter import Adaptation, adapt, engineering_quantities
from isolator.design import Design
from isolator.serialize import json_safe
from isolator.motion.examples import EXAMPLE_RECORDS, resolve_record  # noqa: F401 - re-exported
from isolator.metrics import REGIME_WORDS, Classification, classify_harmonic, classify_record, compare


@dataclass
class Analysis:
    """Everything a report shows (SI units)."""

    design: Design
    motion: object  #: isolator.motion.GroundMotion
    adaptation: Adaptation
    response: object  #: isolator.solver.record.Response
    harmonic: object  #: isolator.solver.harmonic.HarmonicResponse at the equivalent point
    record_class: Classification
    harmonic_class: Classification
    engineering: dict
    disagreements: list
    record_label: str = ""
    scaling_note: str = ""
    created_utc: str = ""
    extra: dict = field(default_factory=dict)


def analyse(design: Design, motion, *, record_label: str = "", scaling_note: str = "") -> Analysis:
    """Simulate, adapt and classify a design under a ground motion.

    Parameters
    ----------
    design : Design
        The isolator.
    motion : isolator.motion.GroundMotion
        The ground acceleration [m/s²] (already scaled if asked).
    record_label : str
        How the record was named on the command line.
    scaling_note : str
        A sentence on scaling, shown on the summary page.

    Returns
    -------
    Analysis
    """
    from isolator.solver.harmonic import harmonic_response
    from isolator.solver.record import simulate_record

    adaptation = adapt(design, motion)
    response = simulate_record(motion.acceleration_m_s2, motion.dt_s, system=adaptation.system)
    p = adaptation.point
    harmonic = harmonic_response(p.alpha, p.k, p.eta, p.mu_s, p.mu_k)
    record_class = classify_record(response, p, design)
    harmonic_class = classify_harmonic(harmonic)
    return Analysis(design=design, motion=motion, adaptation=adaptation, response=response, harmonic=harmonic,
                    record_class=record_class, harmonic_class=harmonic_class,
                    engineering=engineering_quantities(design, response),
                    disagreements=compare(record_class, harmonic_class), record_label=record_label,
                    scaling_note=scaling_note,
                    created_utc=_dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"))


def verdicts(analysis: Analysis) -> list[str]:
    """Plain sentences for the summary page."""
    rc, hc = analysis.record_class, analysis.harmonic_class
    eng = analysis.engineering
    p = analysis.adaptation.point
    if rc.regime == "ST":
        out = [f"Regime under the record: ST - the isolator never slides (alpha = PGA/(mu_s g) = {p.alpha:.3g}"
               f"{' <= 1' if p.alpha <= 1 else ''}): the superstructure moves with the ground, not isolated; "
               f"harmonic prediction: {hc.regime} ({REGIME_WORDS[hc.regime]})."]
    else:
        out = [f"Regime under the record: {rc.regime} ({REGIME_WORDS[rc.regime]}), slip-time ratio over D5-95 "
               f"zeta = {rc.zeta:.3f}; harmonic prediction: {hc.regime} ({REGIME_WORDS[hc.regime]})."]
    if rc.amplified:
        out.append(f"The isolator AMPLIFIES the ground motion: A = {rc.amplitude:.3g} > 1.")
    else:
        out.append(f"Ground motion not amplified: A = {rc.amplitude:.3g} <= 1.")
    out.append(f"Dominant force: {rc.dominant_force} (force peaks); harmonic prediction: {hc.dominant_force}.")
    if eng["peak_displacement_m"] > 0:
        ratio = abs(eng["residual_displacement_m"]) / eng["peak_displacement_m"]
        out.append(f"Residual displacement {eng['residual_displacement_m'] * 1e3:.3g} mm "
                   f"= {100 * ratio:.3g} % of the peak.")
    out.extend(f"Disagreement - {note}." for note in analysis.disagreements)
    if not analysis.disagreements:
        out.append("Record and harmonic map agree on regime, amplification and dominant force.")
    return out


def summary_dict(analysis: Analysis) -> dict:
    """The JSON written beside the PDF (SI units; energies per unit mass in J/kg)."""
    from isolator import __version__

    a = analysis
    p = a.adaptation.point
    r = a.response
    motion = a.motion
    im = a.adaptation.intensity
    out = {
        "regime_record": a.record_class.regime,
        "regime_harmonic": a.harmonic_class.regime,
        "amplified_record": a.record_class.amplified,
        "amplified_harmonic": a.harmonic_class.amplified,
        "dominant_force_record": a.record_class.dominant_force,
        "dominant_force_harmonic": a.harmonic_class.dominant_force,
        "amplitude_record": a.record_class.amplitude,
        "amplitude_harmonic": a.harmonic_class.amplitude,
        "zeta_record": a.record_class.zeta,
        "zeta_harmonic": a.harmonic_class.zeta,
        "k": p.k,
        "alpha": p.alpha,
        "eta": p.eta,
        "mu_s": p.mu_s,
        "mu_k": p.mu_k,
        "a0_m": p.a0_m,
        "omega_rad_s": p.omega_rad_s,
        "peak_displacement_m": r.peak_displacement_m,
        "residual_displacement_m": r.residual_displacement_m,
        "peak_velocity_m_s": r.peak_velocity_m_s,
        "peak_transmitted_acceleration_m_s2": r.peak_transmitted_acceleration_m_s2,
        "slip_time_s": r.slip_time_s,
        "n_events": r.n_events,
        "energy_input_J_per_kg": r.energy_input_J_per_kg,
        "energy_friction_J_per_kg": r.energy_friction_J_per_kg,
        "energy_viscous_J_per_kg": r.energy_viscous_J_per_kg,
        "energy_balance_error_J_per_kg": r.energy_balance_error_J_per_kg,
        "engineering": a.engineering,
        "classification_record": a.record_class.as_dict(),
        "classification_harmonic": a.harmonic_class.as_dict(),
        "harmonic_steady": a.harmonic.steady,
        "harmonic_status": a.harmonic.status,
        "disagreements": a.disagreements,
        "verdicts": verdicts(a),
        "design": a.design.as_dict(),
        "system": a.adaptation.dimensional_dict(),
        "record": {
            "label": a.record_label,
            "component": motion.component,
            "units_source": motion.units_source,
            "npts": motion.npts,
            "dt_s": motion.dt_s,
            "duration_s": motion.duration_s,
            "provenance": motion.provenance,
            "processing": list(motion.processing),
            "scaling": a.scaling_note,
            "intensity_measures": im.as_dict(),
        },
        "solver_status": r.message,
        "software": {"name": "isolator", "version": __version__},
        "created_utc": a.created_utc,
    }
    return json_safe(out)
