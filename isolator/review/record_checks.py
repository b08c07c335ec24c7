"""The review checks that apply to one record (the single-record ``isolator report``).

Capacity, D/R, restoring force (ASCE 7-22 17.2.4.4), transmitted acceleration / PGA, the record's
scale factor and its usable band — the same rows (and parameters) as :mod:`isolator.review.assess`,
for a design under one (optionally scaled) record and nominal properties.
"""

from __future__ import annotations

import math

from isolator.review import checks as C
from isolator.review.codes import asce7_22
from isolator.review.parameters import resolve


def record_checks(design, motion, engineering: dict, parameters: dict | None = None) -> list[dict]:
    """Check rows for a design under one record.

    Parameters
    ----------
    design : isolator.design.Design
    motion : isolator.motion.GroundMotion
        The record as analysed (its ``processing`` names any scaling; an AT2 header its filter corners).
    engineering : dict
        :func:`isolator.adapter.engineering_quantities` of the response (``peak_displacement_m``,
        ``peak_transmitted_force_N``, ``effective_period_s``).
    parameters : dict, optional
        Overrides of the review parameters.

    Returns
    -------
    list of dict
        {id, clause, status, value, limit, unit, note}.
    """
    from isolator.review.suite_components import high_pass_corner_hz

    p = resolve("asce7-22", parameters)
    d = float(engineering["peak_displacement_m"])
    rows = [C.at_most("displacement_capacity", "capacity (ASCE 7-22 17.6.3.4, one record)", d,
                      design.displacement_capacity_m,
                      "peak displacement under this record, nominal properties"
                      + ("" if design.displacement_capacity_m else "; no displacement_capacity_m in the design"), "m")]
    if design.is_pendulum:
        rows.append(C.at_most("D_over_R", "small-angle pendulum (practice)", d / design.radius_m, p["D_over_R_max"],
                              f"R = {design.radius_m:g} m", "-"))
        rows.append(C.restoring_force(asce7_22.restoring_force_ratio(design, d), p["restoring_min"],
                                      displacement_m=d, radius_m=design.radius_m))
    pga = motion.pga_m_s2
    transmitted = engineering["peak_transmitted_force_N"] / design.mass_kg
    rows.append(C.at_most("transmitted_over_pga", "isolation effectiveness (practice)", transmitted / pga if pga else None,
                          p["transmitted_over_pga_max"], "peak transmitted acceleration / PGA of the record as analysed",
                          "-"))
    factor = 1.0
    for step in motion.processing:
        if "factor" in step:
            factor *= float(step["factor"])
    outside = not p["sf_flag_low"] <= factor <= p["sf_flag_high"]
    rows.append(C.check("scale_factor", "reviewer practice, not code", C.FAIL if outside else C.PASS, factor,
                        p["sf_flag_high"], f"flagged outside {p['sf_flag_low']:g}–{p['sf_flag_high']:g}", "×"))
    period = engineering.get("effective_period_s")
    period = period if period is not None and math.isfinite(period) and period > 0 else design.isolated_period_s
    rows.append(C.usable_band([(motion.component or "record", high_pass_corner_hz(motion))],
                              p["range_hi_factor"] * period, p["usable_band_factor"]))
    rows[-1]["note"] = f"needs {p['range_hi_factor']:g} × T_eff = {p['range_hi_factor'] * period:.3g} s; " + rows[-1]["note"]
    return rows


def with_record_checks(analysis, parameters: dict | None = None):
    """The analysis with the checks of :func:`record_checks` added (a new object; the caller adds them).

    Parameters
    ----------
    analysis : isolator.analysis.Analysis
        One component (a planar analysis is returned as it is: a pair's checks are the review's,
        over a suite, and its ``checks`` key says so in ``not_applicable``).
    parameters : dict, optional
        Overrides of the review parameters.
    """
    r = analysis.response
    at_rim = getattr(r, "ultimate_displacement_reached", False) and getattr(r, "bearing_type", "") == "single"
    if not analysis.paper_applies and not at_rim:  # a single pendulum rerun with its rim keeps its checks
        return analysis
    rows = record_checks(analysis.design, analysis.motion, analysis.engineering, parameters)
    if at_rim:  # its peak is the capacity because the rim stopped it (solver.multisurface): not a demand within it
        rows[0].update(status=C.FAIL, note=f"the bearing REACHED its displacement capacity (rim, plastic impact(s), "
                                             f"impulse {analysis.design.mass_kg * r.impact_impulse_m_s:.4g} N·s); "
                                             f"{r.model_reason}")
    return analysis.with_checks(rows)

