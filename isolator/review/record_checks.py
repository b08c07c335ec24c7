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


def capacity_reading(design, parameters: dict | None = None) -> dict:
    """Where the single-record report reads the displacement it compares with the capacity, as the review does.

    With ``capacity_at_corner`` (default [U], REVIEW_RULES 1.10) and a design ``[plan]``: the corner bearing, the
    centre-of-mass displacement × the torsion factor D_TM/D_M of ASCE 7-22 Eq. 17.5-3 — from the bearing layout
    (``[[bearing_position]]``: P_T of Eq. 17.5-4 and the farthest bearing) when there is one, else from the plan —
    the factor the review applies (:func:`isolator.review.codes.asce7_22.torsion_factor`).  Otherwise the centre
    of mass, and ``where`` says why.

    Returns
    -------
    dict
        ``factor`` [-] (1 at the centre of mass), ``at_corner`` (bool), ``where`` (one phrase for the rows),
        ``basis`` (the torsion factor's basis, or why the centre of mass).
    """
    from isolator.superstructure import review_inputs

    p = resolve("asce7-22", parameters, other_codes=True)
    if not p["capacity_at_corner"]:
        return {"factor": 1.0, "at_corner": False, "where": "the centre of mass (capacity_at_corner false)",
                "basis": "capacity_at_corner false"}
    if design.plan is None:
        return {"factor": 1.0, "at_corner": False,
                "where": "the centre of mass: the design has no [plan] (nor [[bearing_position]]), so no corner "
                         "bearing's displacement (a review would take D_TM = 1.15 D_M, the floor of Eq. 17.5-3)",
                "basis": "no [plan]"}
    torsion = asce7_22.torsion_factor(design.plan, p, review_inputs(design))
    return {"factor": torsion["factor"], "at_corner": True, "basis": torsion["basis"],
            "where": f"the corner bearing: torsion factor {torsion['factor']:.4g} (D_TM/D_M, {torsion['basis']}; "
                     "capacity_at_corner [U], as the review) × the centre-of-mass displacement"}


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

    p = resolve("asce7-22", parameters, other_codes=True)
    d = float(engineering["peak_displacement_m"])
    reading = capacity_reading(design, parameters)
    d_read = reading["factor"] * d
    said = f"{reading['factor']:.4g} × {d:.4g} m" if reading["at_corner"] else f"{d:.4g} m"
    rows = [C.at_most("displacement_capacity", "capacity (ASCE 7-22 17.6.3.4, one record)", d_read,
                      design.displacement_capacity_m,
                      f"peak displacement under this record, nominal properties, at {reading['where']}: {said}"
                      + ("" if design.displacement_capacity_m else "; no displacement_capacity_m in the design"), "m")]
    rows[0].update(centre_of_mass_m=d, torsion_factor=reading["factor"] if reading["at_corner"] else None)
    if design.is_pendulum:
        rows.append(C.at_most("D_over_R", "small-angle pendulum (practice)", d_read / design.radius_m,
                              p["D_over_R_max"], f"R = {design.radius_m:g} m; D at "
                              + ("the corner bearing (× the torsion factor)" if reading["at_corner"]
                                 else "the centre of mass"), "-"))
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
                                             f"{r.model_reason}; {rows[0]['note']}")
    return analysis.with_checks(rows)

