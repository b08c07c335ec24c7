"""Design values over the suite (per bound, then the envelope) and the checks of a review.

:func:`assess` returns them (with the ELF values completed by D_TM); :func:`isolator.review.run.run_review`
builds the :class:`~isolator.review.run.Review` from its inputs and these, once.  The response-history
design displacement is ``D_M_rha_m``; the ELF's is ``elf[bound]["D_M_m"]`` (ASCE 7-22 17.5.3).
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from isolator.review import checks as C
from isolator.review.codes import asce7_22, en15129
from isolator.review.selection import selection_rows
from isolator.review.target import design_values
from isolator.superstructure import review_inputs

BOUNDS = ("lower", "upper")


def _per_bound(results: dict, n_for_mean: int, factoring: dict | None = None) -> dict:
    ok = [r for r in results.values() if "error" not in r]
    d = C.suite_value([r["peak_displacement_m"] for r in ok], n_for_mean)
    return {**_structure_values(results, n_for_mean, factoring), **{
        "D_M_rha_m": d["value"], "rule": d["rule"], "n": d["n"],
        "residual_displacement_m": C.suite_value([abs(r["residual_displacement_m"]) for r in ok
                                                  if r["residual_displacement_m"] is not None], n_for_mean)["value"],
        "base_shear_coefficient": C.suite_value([r["base_shear_coefficient"] for r in ok], n_for_mean)["value"],
        "transmitted_over_pga": C.suite_value([r["transmitted_over_pga"] for r in ok], n_for_mean)["value"],
        "transmitted_over_pga_max": max((r["transmitted_over_pga"] for r in ok), default=math.nan),
        "peak_displacement_max_m": max((r["peak_displacement_m"] for r in ok), default=math.nan),
        "n_uplifts": int(sum(r.get("n_uplifts", 0) for r in ok)),
        "models": sorted({r.get("model", "") for r in ok}),
        "spread": {key: C.spread([r[key] for r in ok]) for key in ("peak_displacement_m", "base_shear_coefficient")},
    }}


def _per_item(ok: list, key: str, n_for_mean: int, *, smallest: bool = False) -> list[float]:
    """The suite value of each entry of a per-story / per-floor / per-bearing list (mean of ≥ n, else the most
    unfavourable: the maximum, or the minimum when ``smallest``)."""
    size = len(ok[0][key])
    sign = -1.0 if smallest else 1.0
    return [sign * C.suite_value([sign * r[key][i] for r in ok], n_for_mean)["value"] for i in range(size)]


def _structure_values(results: dict, n_for_mean: int, factoring: dict | None = None) -> dict:
    """A building's suite values per bound (story drift ratios, floor accelerations, superstructure shear, bearing
    loads) from the analyses' rows; empty when the analyses carry none (a rigid block).  With ``factoring``
    (:func:`_load_factoring`) also the factored bearing loads of 17.2.4.6 / 17.2.4.7."""
    ok = {name: r for name, r in results.items() if "error" not in r and r.get("story_drift_ratio") is not None}
    if not ok:
        return {}
    rows = list(ok.values())
    out = {"story_drift_ratio": _per_item(rows, "story_drift_ratio", n_for_mean),
           "floor_peak_acceleration_m_s2": _per_item(rows, "floor_peak_acceleration_m_s2", n_for_mean),
           "superstructure_shear_coefficient": C.suite_value([r["superstructure_shear_coefficient"] for r in rows],
                                                             n_for_mean)["value"]}
    if all(r.get("bearing_axial_load_min_N") is not None for r in rows):
        out["bearing_axial_load_min_N"] = _per_item(rows, "bearing_axial_load_min_N", n_for_mean, smallest=True)
        out["bearing_axial_load_max_N"] = _per_item(rows, "bearing_axial_load_max_N", n_for_mean)
        lifted = [name for name, r in ok.items() if r.get("n_bearings_uplifted")]
        single = min(((min(r["bearing_axial_load_min_N"]), name) for name, r in ok.items()))
        out["uplift_analyses"] = lifted
        out["bearing_axial_load_min_single_N"] = {"value": single[0], "pair": single[1]}
        if factoring is not None:
            out["factored_bearing_loads"] = _factored_loads(ok, n_for_mean, factoring)
    return out


def _factored_loads(ok: dict, n_for_mean: int, factoring: dict) -> dict:
    """Each analysis's bearing loads under the 2.3.6 combinations, then their suite values (17.2.4.6 / 17.2.4.7).

    The gravity share g_k is constant in time, so the extremes of f g_k + (overturning + vertical) are those of the
    history shifted: max_f = P_max + (f_max − 1) g_k and min_f = P_min + (f_min − 1) g_k, with each analysis's
    factors (E_v only where its vertical was not analysed).
    """
    gravity = np.asarray(factoring["gravity_N"])
    rows, lifted, single = [], [], (math.inf, "")
    for name, r in ok.items():
        f_max, f_min = factoring["per_pair"].get(name, factoring["without_vertical"])
        low = np.asarray(r["bearing_axial_load_min_N"]) + (f_min - 1.0) * gravity
        high = np.asarray(r["bearing_axial_load_max_N"]) + (f_max - 1.0) * gravity
        rows.append({"min": low.tolist(), "max": high.tolist()})
        lifted += [name] if np.any(low < 0.0) else []
        single = min(single, (float(low.min()), name))
    return {"max_N": _per_item(rows, "max", n_for_mean), "min_N": _per_item(rows, "min", n_for_mean, smallest=True),
            "lifted": lifted, "min_single_N": {"value": single[0], "pair": single[1]}}


def _load_factoring(review) -> dict | None:
    """The factors of the 2.3.6 combinations on each bearing's gravity share (ASCE 7-22 17.2.4.6 / 17.2.4.7 [U]).

    f_max = ``dead_load_factor_max`` + c S_MS and f_min = ``dead_load_factor_min`` − c S_MS (E_v = c S_MS D,
    c = ``vertical_Ev_coefficient``, 12.4.2.2 with S_MS for the MCE_R) for an analysis without its vertical; the
    dead-load factors alone for one whose vertical component was analysed (its loads carry the vertical already:
    not counted twice).  ``None`` for a code without them (EN) or a design without a bearing layout.
    """
    p, layout = review.parameters, review.design.bearing_layout
    if "dead_load_factor_max" not in p or layout is None:
        return None
    target = review.target
    if target.kind == "asce7-two-period":
        s_ms, where = float(target.parameters["S_MS"]), "S_MS of the two-period target"
    else:  # a tabulated target: its short-period ordinate stands for S_MS [U]
        s_ms, where = float(target.sa_g(0.2, clip=True)[0]), "the target's S_a(0.2 s) taken as S_MS [U]"
    e_v = p["vertical_Ev_coefficient"] * s_ms
    without = asce7_22.vertical_load_factors(s_ms, p, vertical_analysed=False)
    with_vertical = asce7_22.vertical_load_factors(s_ms, p, vertical_analysed=True)
    analysed = {pair.name: pair.az_m_s2 is not None and not p.get("horizontal_only") for pair in review.suite.pairs}
    n_vertical = sum(analysed.values())
    basis = (f"factored (2.3.6 [U]): max {without[0]:.4g} D + E_h, min {without[1]:.4g} D − E_h on each bearing's "
             f"gravity share D (dead_load_factor_max {p['dead_load_factor_max']:g} / dead_load_factor_min "
             f"{p['dead_load_factor_min']:g} ± E_v, E_v = {p['vertical_Ev_coefficient']:g} × S_MS D = "
             f"{e_v:.4g} D with S_MS = {s_ms:.4g} g, {where}), E_h the overturning of the response history "
             "(its peak MCE_R response, ρ = 1); "
             + (f"{n_vertical} pair(s) with their vertical analysed: {with_vertical[0]:g} D / {with_vertical[1]:g} D "
                "+ the analysed vertical (E_v not added twice)" if n_vertical else
                "no vertical analysed, so E_v is applied")
             + "; no separate live load (the design's mass is the seismic weight)")
    return {"gravity_N": list(layout.gravity_loads_N), "without_vertical": without,
            "per_pair": {name: with_vertical if v else without for name, v in analysed.items()},
            "S_MS": s_ms, "factor_max": without[0], "factor_min": without[1], "basis": basis}


def _governing(values: dict, key: str) -> tuple[float, str]:
    finite = {b: v[key] for b, v in values.items() if math.isfinite(v[key])}
    if not finite:
        return math.nan, "none"
    bound = max(finite, key=finite.get)
    return finite[bound], bound


def assess(basis: dict, designs: dict, *, min_ratio_required: float) -> dict:
    """The design values and checks of a review from its inputs and analyses (nothing is changed in place).

    Parameters
    ----------
    basis : dict
        The :class:`~isolator.review.run.Review` fields other than ``design_values`` and ``checks``
        (``parameters``, ``code``, ``design``, ``suite``, ``elf``, ``analyses`` …).
    designs : dict
        Bound → the design at that bound.
    min_ratio_required : float
        The suite spectrum's minimum ratio to the target that the code asks [-].

    Returns
    -------
    dict
        ``design_values`` (per bound: ``D_M_rha_m``, rule, n, suite values; ``envelope``; ``torsion``;
        ``elf_D_TM_m``), ``elf`` (the ELF values with ``D_TM_m``) and ``checks`` (rows with their clauses).
    """
    review = SimpleNamespace(**basis, min_ratio_required=min_ratio_required)
    p, code = review.parameters, review.code
    factoring = _load_factoring(review)
    values = {b: _per_bound(review.analyses[b], p["n_for_mean"], factoring) for b in review.analyses}
    bounded = {b: values[b] for b in values}
    d_m, d_bound = _governing(bounded, "D_M_rha_m")
    v_b, v_bound = _governing(bounded, "base_shear_coefficient")
    residual, _ = _governing(bounded, "residual_displacement_m")
    torsion = _torsion(review)
    elf = {b: {**review.elf[b], "D_TM_m": review.elf[b]["D_M_m"] * torsion["factor"]} for b in review.elf}
    for b in elf:  # a flexible superstructure: D'_M of Eq. 17.6-1 may replace D_M in the 17.6.4.1 floor
        if "D_M_prime_m" in elf[b]:
            elf[b]["D_TM_prime_m"] = elf[b]["D_M_prime_m"] * torsion["factor"]
    elf_d_tm = max((elf[b]["D_TM_m"] for b in BOUNDS if math.isfinite(elf[b]["D_TM_m"])), default=math.nan)
    floor_key = "D_TM_prime_m" if all("D_TM_prime_m" in elf[b] for b in BOUNDS) else "D_TM_m"
    elf_floor_basis = max((elf[b][floor_key] for b in BOUNDS if math.isfinite(elf[b][floor_key])), default=math.nan)
    rha_d_tm = d_m * torsion["factor"]
    floor = p.get("f_disp", 0.0) * elf_floor_basis if code == "asce7-22" else 0.0
    d_tm_value = max(rha_d_tm, floor) if math.isfinite(floor) else rha_d_tm
    rule = values[d_bound]["rule"] if d_bound in values else "none"
    n = values[d_bound]["n"] if d_bound in values else 0
    design_values = {**values, "torsion": torsion, "elf_D_TM_m": elf_d_tm, "elf_floor_basis": {
        "key": floor_key, "value_m": elf_floor_basis}, "structure": _structure_envelope(values, factoring), "envelope": {
        "D_M_rha_m": d_m, "D_M_bound": d_bound, "rule": rule, "n": n, "V_b_over_W": v_b, "V_b_bound": v_bound,
        "residual_displacement_m": residual,
        "D_TM": {"value": d_tm_value, "rha_m": rha_d_tm, "elf_floor_m": floor,
                 "governs": "ELF floor" if floor > rha_d_tm else "response history"}}}
    design_values["spread"] = {b: values[b]["spread"] for b in values}
    view = SimpleNamespace(**{**vars(review), "elf": elf, "design_values": design_values})
    checks = (_asce_checks if code == "asce7-22" else _en_checks)(view, values, designs)
    checks = no_pass_past_ultimate(checks, C.ultimate_reached(review.analyses))
    checks = no_stability_pass_beyond_capacity(checks)
    checks = no_stability_pass_past_uplift(checks, design_values["structure"].get("uplift_analyses", []))
    limit = C.implicit_step_limit(review.analyses)
    checks = [{**row, "note": row["note"] + f"; {limit}"} if limit and row["id"] in SAMPLED_ROWS else row
              for row in checks]
    surfaces = review.design.bearing.surfaces if asce7_22.is_multisurface(review.design) else ()
    checks = C.within_surface_rims(checks, C.surface_rims_passed(review.analyses,
                                                                 [s.displacement_capacity_m for s in surfaces]))
    return {"design_values": design_values, "elf": elf, "checks": no_pass_on_part(checks, incomplete_analyses(
        review.analyses))}


#: The rows computed from the analyses' results (suite values, each analysis, their envelope); the others come from
#: the suite's spectra, the ELF or the design alone.
FROM_ANALYSES = frozenset({
    "D_M_capacity", "record_capacity", "D_TM_capacity", "D_TM_elf_floor", "restoring_force", "base_shear_elf_floor",
    "superstructure_shear", "vertical_load_stability", "story_drift", "floor_acceleration", "uplift",
    "displacement_capacity", "restoring_capability", "D_over_R", "residual_displacement", "transmitted_over_pga"})


def incomplete_analyses(analyses: dict) -> list[str]:
    """"pair (bound): why" of every analysis whose numbers the rows cannot stand on: it failed (``error``), or its
    solver flagged it (``solver_status`` other than ``ok``: the chatter guard, an unfinished interval …)."""
    out = []
    for bound, results in analyses.items():
        for name, r in results.items():
            if "error" in r:
                out.append(f"{name} ({bound}): failed")
            elif r.get("solver_status", "ok") != "ok":
                out.append(f"{name} ({bound}): its solver says {r['solver_status']}")
    return out


def no_pass_on_part(rows: list, incomplete: list[str]) -> list:
    """A row computed from the analyses cannot pass when some analyses failed or were flagged by their solver (its
    suite value, or 'every analysis within', is then over part of the suite): ``not checked``, naming them.  A
    failure stands, said the same way."""
    if not incomplete:
        return rows
    said = f"{len(incomplete)} analysis(es) not usable: {'; '.join(incomplete[:3])}{' …' if len(incomplete) > 3 else ''}"
    out = []
    for row in rows:
        if row["id"] not in FROM_ANALYSES or row["status"] == C.NOT_CHECKED:
            out.append(row)
        elif row["status"] == C.PASS:
            out.append({**row, "status": C.NOT_CHECKED,
                        "note": row["note"] + f"; would pass over the analyses that ran, but {said}"})
        else:
            out.append({**row, "note": row["note"] + f"; {said}"})
    return out


#: The rows whose value is a peak force or displacement of the analyses: where an implicit-step model ran they say its
#: tolerance and, for the base shear, that it is sampled (:func:`isolator.review.checks.implicit_step_limit`).
SAMPLED_ROWS = frozenset({"base_shear_elf_floor", "transmitted_over_pga", "superstructure_shear", "D_M_capacity",
                          "record_capacity", "D_TM_capacity", "displacement_capacity"})

#: The rows computed from the analyses whose pass does not stand when an analysis reached the bearing's ultimate
#: displacement (or a single pendulum's rim): after the impact its response is the model's plastic impact of the
#: slab (or the mass) on the rims — an idealisation of the restraint, whose forces, drifts, bearing loads and
#: accelerations inflate the suite values (a floor 'RHA ≥ f × ELF' then passes on them) — and its displacements are
#: held at the rims (understated).  Not here: the capacity rows (they fail: :func:`isolator.review.checks.
#: never_pass_at_ultimate`) and ``D_TM_elf_floor`` (an understated displacement that reaches the floor stands).
PAST_ULTIMATE = FROM_ANALYSES - {"D_M_capacity", "record_capacity", "D_TM_capacity", "displacement_capacity",
                                 "D_TM_elf_floor"}


def no_pass_past_ultimate(rows: list, reached: list[str]) -> list:
    """No row passes on analyses that reached the ultimate displacement (``reached``: "pair (bound)" of each,
    :func:`isolator.review.checks.ultimate_reached`): a :data:`PAST_ULTIMATE` row that would pass is ``not checked``,
    naming them; EN's suite ``displacement_capacity`` fails as ASCE's ``D_M_capacity`` does (the suite value
    understates the demand); a failure stands."""
    if not reached:
        return rows
    said = (f"{len(reached)} analysis(es) reached the bearing's ultimate displacement ({', '.join(reached[:4])}"
            f"{' …' if len(reached) > 4 else ''}): after the impact their response is the model's plastic impact on "
            "the rims (an idealisation of the restraint) and their displacements are held there, so the suite value "
            "does not stand")
    out = []
    for row in rows:
        if row["id"] == "displacement_capacity":
            out.append(C.never_pass_at_ultimate(row, reached))
        elif row["id"] in PAST_ULTIMATE and row["status"] == C.PASS:
            out.append({**row, "status": C.NOT_CHECKED, "note": row["note"] + f"; would pass, but {said}"})
        else:
            out.append(row)
    return out


def no_stability_pass_beyond_capacity(rows: list) -> list:
    """The bearings' stability under vertical load (``vertical_load_stability``: ASCE 7-22 17.2.4.6, EN 15129) is
    checked against capacities stated at the total displacement; where an analysis takes a bearing beyond its
    displacement capacity (a failing ``record_capacity`` row) that capacity says nothing, so a passing row becomes
    ``not checked``, naming how many analyses (h218 found it passing at 0.694 × capacity beside corner bearings at
    1.47–1.56 m of a 1.4 m capacity).  A failure stands."""
    beyond = [row for row in rows if row["id"] == "record_capacity" and row["status"] == C.FAIL]
    if not beyond:
        return rows
    return _stability_would_pass(rows, f"{len(beyond)} analysis(es) take a bearing beyond its displacement capacity "
                                       "(record_capacity), where the axial capacity, stated at the total displacement, "
                                       "does not apply")


def no_stability_pass_past_uplift(rows: list, lifted: list) -> list:
    """17.2.4.6 cannot pass on the bearing loads of an analysis whose history put a bearing in tension (``lifted``:
    "pair (bound)" of each, the unfactored loads): the rigid-slab statics is linear and does not release a bearing
    in tension (docs/building.md), so while it pulls, the others' loads — the P_max the row compares — are
    understated.  A passing row becomes ``not checked`` naming them; a failure stands (session 25: the narrow-base
    building, 18 of 24 analyses with a bearing in tension)."""
    if not lifted:
        return rows
    return _stability_would_pass(rows, f"{len(lifted)} analysis(es) put a bearing in tension ({', '.join(lifted[:3])}"
                                       f"{' …' if len(lifted) > 3 else ''}), which the linear rigid-slab statics does "
                                       "not release: the other bearings' loads are understated there")


def _stability_would_pass(rows: list, said: str) -> list:
    """A passing ``vertical_load_stability`` row made ``not checked``, saying why; every other row as it is."""
    return [{**row, "status": C.NOT_CHECKED, "note": row["note"] + f"; would pass, but {said}"}
            if row["id"] == "vertical_load_stability" and row["status"] == C.PASS else row for row in rows]


def _structure_envelope(values: dict, factoring: dict | None = None) -> dict:
    """The building's design values over the bounds: the larger (smaller for the bearings' least load) of each
    story, floor and bearing, and the bound that governs the largest."""
    built = {b: v for b, v in values.items() if "story_drift_ratio" in v}
    if not built:
        return {}

    def envelope(key, pick=max):
        per = list(zip(*(built[b][key] for b in built), strict=True))
        return [pick(items) for items in per]

    out = {"story_drift_ratio": envelope("story_drift_ratio"),
           "floor_peak_acceleration_m_s2": envelope("floor_peak_acceleration_m_s2")}
    drift_bound = max(built, key=lambda b: max(built[b]["story_drift_ratio"]))
    out["story_drift_bound"] = drift_bound
    shear_bound = max(built, key=lambda b: built[b]["superstructure_shear_coefficient"])
    out["superstructure_shear_coefficient"] = built[shear_bound]["superstructure_shear_coefficient"]
    out["superstructure_shear_bound"] = shear_bound
    if all("bearing_axial_load_min_N" in v for v in built.values()):
        out["bearing_axial_load_min_N"] = envelope("bearing_axial_load_min_N", min)
        out["bearing_axial_load_max_N"] = envelope("bearing_axial_load_max_N")
        out["uplift_analyses"] = [f"{name} ({b})" for b, v in built.items() for name in v["uplift_analyses"]]
        single = min(((v["bearing_axial_load_min_single_N"]["value"], v["bearing_axial_load_min_single_N"]["pair"], b)
                      for b, v in built.items()))
        out["bearing_axial_load_min_single_N"] = {"value": single[0], "pair": single[1], "bound": single[2]}
    if factoring is not None and all("factored_bearing_loads" in v for v in built.values()):
        per = {b: v["factored_bearing_loads"] for b, v in built.items()}
        single = min((f["min_single_N"]["value"], f["min_single_N"]["pair"], b) for b, f in per.items())
        out["factored_bearing_loads"] = {
            "max_N": [max(items) for items in zip(*(f["max_N"] for f in per.values()), strict=True)],
            "min_N": [min(items) for items in zip(*(f["min_N"] for f in per.values()), strict=True)],
            "lifted": [f"{name} ({b})" for b, f in per.items() for name in f["lifted"]],
            "min_single_N": {"value": single[0], "pair": single[1], "bound": single[2]},
            "factor_max": factoring["factor_max"], "factor_min": factoring["factor_min"],
            "S_MS": factoring["S_MS"], "basis": factoring["basis"]}
    return out


def _torsion(review) -> dict:
    """The code's torsion factor of the review, with its basis.

    ASCE 7-22: D_TM/D_M of Eq. 17.5-3 with its 1.15 floor (:func:`asce7_22.torsion_factor`).  EN 15129 /
    EN 1998-1: each isolator's δ_i = 1 + e_tot y_i / r² of EN 1998-1 10.9.6 [U] with the EN accidental eccentricity
    (``en_accidental_e``), no floor (:func:`en15129.torsion_factors`) — an EN review applies no ASCE rule here.
    """
    design, p = review.design, review.parameters
    layout = design.bearing_layout
    if review.code == "en15129":
        x, y = (None, None) if layout is None else (layout.x_m, layout.y_m)
        return en15129.torsion_factors(design.plan, p["en_accidental_e"], x, y)
    return asce7_22.torsion_factor(design.plan, p, review_inputs(design))


def _common_front(review, n_min: int, clause_size: str, clause_spectrum: str, basis: str) -> list:
    p = review.parameters
    n = len(review.suite.pairs)
    ratio = float(np.min(review.suite_ratio))
    t_min = float(review.grid_s[int(np.argmin(review.suite_ratio))])
    lo, hi = review.period_range_s
    unusable = {name for results in review.analyses.values() for name, r in results.items()
                if "error" in r or r.get("solver_status", "ok") != "ok"}
    rows = [C.at_least("suite_size", clause_size, n - len(unusable), n_min, f"{n} pairs read"
                       + (f", {len(review.suite.failed)} failed to read" if review.suite.failed else "")
                       + (f"; {len(unusable)} not analysed at every bound (failed or flagged by the solver): "
                          f"{', '.join(sorted(unusable))}" if unusable else "; every pair analysed at every bound"),
                       "pairs"),
            C.at_least("suite_spectrum", clause_spectrum, ratio, review.min_ratio_required,
                       f"min over {review.grid_s.size} log-spaced periods {lo:.3g}–{hi:.3g} s of the average scaled "
                       f"{basis} / target, at T = {t_min:.3g} s; " + _scaling_words(review), "×target")]
    if review.code == "asce7-22" and p.get("mean_ratio_min"):
        rows.append(C.at_least("suite_spectrum_mean", "ASCE 7-22 16.2.3.2 (interpretation)",
                               float(np.mean(review.suite_ratio)), p["mean_ratio_min"],
                               "mean over the range of the ratio ('generally matches or exceeds')", "×target"))
    factors = list(review.factors.values())
    outside = [name for name, f in review.factors.items() if not p["sf_flag_low"] <= f <= p["sf_flag_high"]]
    rows.append(C.check("scale_factors", "reviewer practice, not code", C.FAIL if outside else C.PASS,
                        max(factors), p["sf_flag_high"],
                        f"factors {min(factors):.3g}–{max(factors):.3g}; flagged outside "
                        f"{p['sf_flag_low']:g}–{p['sf_flag_high']:g}" + (f": {', '.join(outside)}" if outside else ""),
                        "×"))
    rows.append(C.usable_band([(pair.name, pair.high_pass_hz) for pair in review.suite.pairs], hi,
                              p["usable_band_factor"]))
    # a record moves the isolator once its force passes the breakaway at rest — µs, not µk (a double's or triple's
    # equivalent µ never ran: its smallest µ_i does) — at the lower bound, where the bearing slides most easily
    multi = asce7_22.is_multisurface(review.design)
    rows += selection_rows(review.suite.pairs, list(review.factors.values()),
                           mu_lower=review.bounds.lambda_min * asce7_22.breakaway_force_per_weight(review.design),
                           mu_lower_said=("the lower bound's breakaway force / W (the bearing at rest: its smallest "
                                          "µ_i)" if multi else "the lower bound's breakaway µs (λ_min × µs)"),
                           gravity_m_s2=review.design.gravity_m_s2, controlling=review.target.controlling, params=p,
                           closest=review.suite.closest, code=review.code)
    return rows


def _scaling_words(review) -> str:
    basis = review.trace.get("run", {}).get("scaling_basis", review.scaling)
    return {"common": "scaling 'common': holds by construction (the factor is the smallest that passes)",
            "fit": "scaling 'fit': the common factor on the fitted shapes makes it hold",
            "given": "the engineer's factors, not rescaled: a real check of the suite",
            "matched": "spectrally matched records, not rescaled (16.2.3.3)"}.get(basis, f"scaling '{basis}'")


def _common_back(review, values: dict, d_tm_design: float, what: str = "design total displacement") -> list:
    p, design = review.parameters, review.design
    env = review.design_values["envelope"]
    rows = []
    if asce7_22.is_multisurface(design):
        rows.append(surface_d_over_r(review, p["D_over_R_max"]))
    elif design.is_pendulum:
        rows.append(C.at_most("D_over_R", "small-angle pendulum (practice)", d_tm_design / design.radius_m,
                              p["D_over_R_max"], f"{what} / R = {design.radius_m:g} m", "-"))
    else:
        rows.append(C.check("D_over_R", "small-angle pendulum (practice)", C.NOT_CHECKED,
                            note="not a friction pendulum (no radius)"))
    rows.append(C.at_most("residual_displacement", "no code clause (practice)", env["residual_displacement_m"],
                          p["residual_max_m"], "suite value of |residual| (resultant), larger bound"
                          + ("" if p["residual_max_m"] is not None else "; no limit set (residual_max_m)"), "m"))
    ratio = max(v["transmitted_over_pga_max"] for v in values.values())
    rows.append(C.at_most("transmitted_over_pga", "isolation effectiveness (practice)", ratio,
                          p["transmitted_over_pga_max"],
                          "largest peak transmitted acceleration / resultant PGA of the scaled pair, any bound"
                          + _largest_transmitted(review.analyses), "-"))
    rows.append(_uplift_row(review, values))
    return rows


def _largest_transmitted(analyses: dict) -> str:
    """Which analysis gives the largest transmitted / PGA, and — when it reached the ultimate (its peak is the force
    of the plastic impact on the rims, an idealisation) — the largest of the analyses below the ultimate."""
    reached = set(C.ultimate_reached(analyses))
    ratios = sorted(((r["transmitted_over_pga"], f"{name} ({bound})") for bound, results in analyses.items()
                     for name, r in results.items() if "error" not in r and r.get("transmitted_over_pga") is not None),
                    reverse=True)
    if not ratios:
        return ""
    top = ratios[0][1]
    if top not in reached:
        return f": {top}"
    below = next(((value, name) for value, name in ratios if name not in reached), None)
    return (f": {top}, which reached the bearing's ultimate displacement (its peak is the plastic impact on the rims, "
            "an idealisation of the restraint); " + ("every analysis reached it" if below is None else
                                                    f"below the ultimate the largest is {below[0]:.4g} ({below[1]})"))


#: The uplift row's clause in an EN review: REVIEW_RULES §2 gives no EN clause, a slider carries no tension.
EN_UPLIFT_CLAUSE = "no tension in a sliding bearing (practice; no EN clause in the rules)"


def _uplift_row(review, values: dict) -> dict:
    """17.2.4.7 from the bearings' axial loads (a building with [[bearing_position]]), else not checked."""
    s = review.design_values.get("structure", {})
    n_vertical = sum(v["n_uplifts"] for v in values.values())
    with_vertical = sum(pair.az_m_s2 is not None for pair in review.suite.pairs)
    dropped = with_vertical if review.parameters.get("horizontal_only") else 0
    n_pairs = with_vertical - dropped
    clause = EN_UPLIFT_CLAUSE if review.code == "en15129" else "ASCE 7-22 17.2.4.7 [U]"
    if "bearing_axial_load_min_N" not in s:
        return C.uplift(n_vertical, n_pairs, n_verticals_not_analysed=dropped, clause=clause)
    factored = s.get("factored_bearing_loads")
    loads = factored["min_N"] if factored else s["bearing_axial_load_min_N"]
    k = int(np.argmin(loads))
    env = review.design_values["envelope"]
    single = factored["min_single_N"] if factored else s["bearing_axial_load_min_single_N"]
    lifted = factored["lifted"] if factored else s["uplift_analyses"]
    # a least load's suite value: the mean of ≥ n_for_mean analyses, else the least of them (the most unfavourable:
    # the suite rule's 'max' of a demand is the minimum of a load that must stay ≥ 0)
    rule = "mean" if env["rule"] == "mean" else "the least"
    detail = (f"bearing {k + 1}'s least load, {rule} of {env['n']} analyses per bound, the smaller bound; "
              f"{len(lifted)} analysis(es) lift a bearing"
              + (f" ({', '.join(lifted[:4])}{' …' if len(lifted) > 4 else ''})" if lifted else "")
              + f"; least single analysis {single['value']:.4g} N ({single['pair']}, {single['bound']} bound)"
              + (f"; unfactored least load {min(s['bearing_axial_load_min_N']):.4g} N" if factored else ""))
    return C.uplift(n_vertical, n_pairs, loads[k], detail=detail, n_verticals_not_analysed=dropped, clause=clause,
                    basis=factored["basis"] if factored else None)


def surface_d_over_r(review, limit: float) -> dict:
    """D/R of a double or triple pendulum, surface by surface: the largest d_i/R_i over the analyses (each surface's
    peak displacement on its own radius)."""
    radii = [surface.radius_m for surface in review.design.bearing.surfaces]
    # a surface held on its rim reads its capacity: its peak passes it by rounding only (0.5000000000000001 m on a
    # 0.5 m rim measured), which is not a D/R beyond the rim's (0.25 vs 0.25 said 'fail' before)
    rims = [surface.displacement_capacity_m for surface in review.design.bearing.surfaces]
    worst, where = math.nan, ""
    for bound, results in review.analyses.items():
        for name, r in results.items():
            peaks = r.get("surface_peak_displacement_m")
            if "error" in r or not peaks:
                continue
            ratios = [(c if c < d <= c * (1.0 + C.SURFACE_RIM_TOLERANCE) else d) / radius
                      for d, radius, c in zip(peaks, radii, rims, strict=True)]
            i = int(np.argmax(ratios))
            if not ratios[i] <= worst:
                worst, where = ratios[i], f"surface {i + 1}, {name}, {bound} bound"
    return C.at_most("D_over_R", "small-angle pendulum (practice)", worst, limit,
                     f"largest peak displacement on a surface / its radius over the analyses ({where})"
                     if where else "no analysis gave the surfaces' peak displacements", "-")


def _asce_checks(review, values: dict, designs: dict) -> list:
    p, design, elf = review.parameters, review.design, review.elf
    env = review.design_values["envelope"]
    d_tm = env["D_TM"]
    cap = design.displacement_capacity_m
    # a matched suite is held to 16.2.3.3's 110 % (spectral_matching_min): the row cited 16.2.3.2's scaling clause
    matched = review.trace.get("run", {}).get("scaling_basis") == "matched"
    rows = _common_front(review, p["n_pairs_min"], "ASCE 7-22 17.3.2",
                         "ASCE 7-22 17.3.3 / 16.2.3.3" if matched else "ASCE 7-22 17.3.3 / 16.2.3.2", "RotD100")
    capacity_note = "" if cap is not None else "no displacement_capacity_m in the design"
    factor = _corner_factor(review)
    largest = max(v["peak_displacement_max_m"] for v in values.values()) * (factor or 1.0)
    where = (f"the corner bearing: torsion factor {factor:.4g} ({_torsion_said(review)}; capacity_at_corner [U]) × "
             f"the centre of mass's D_M {env['D_M_rha_m']:.4g} m" if factor else
             "the centre of mass (capacity_at_corner false)")
    rows.append(C.at_most("D_M_capacity", "ASCE 7-22 17.6.3.4, capacity [U]", env["D_M_rha_m"] * (factor or 1.0), cap,
                          f"{where}; {env['rule']} of {env['n']} pairs, {env['D_M_bound']} bound governs; largest "
                          f"single analysis {largest:.3g} m" + ("; " + capacity_note if capacity_note else ""), "m"))
    reached = C.ultimate_reached(review.analyses)
    rows[-1] = C.never_pass_at_ultimate(rows[-1], reached)
    rows += C.record_capacity(review.analyses, cap, mass_kg=design.mass_kg, torsion_factor=_corner_factor(review))
    # the floor is f_disp × D'_TM (Eq. 17.6-1) with a superstructure: it said "0.8 D_TM ELF" whichever it was
    floor_said = ("D'_TM ELF (Eq. 17.6-1)" if review.design_values["elf_floor_basis"]["key"] == "D_TM_prime_m"
                  else "D_TM ELF")
    d_tm_row = C.never_pass_at_ultimate(
        C.at_most("D_TM_capacity", "ASCE 7-22 17.5.3.3 / 17.6.4.1", d_tm["value"], cap,
                  f"max(RHA D_M × {review.design_values['torsion']['factor']:.4g} (torsion: "
                  f"{_torsion_said(review)}) = {d_tm['rha_m']:.4g} m, {p['f_disp']:g} {floor_said} = "
                  f"{d_tm['elf_floor_m']:.4g} m); {d_tm['governs']} governs", "m"), reached)
    beyond = [b for b in ("lower", "upper") if elf[b].get("beyond_ultimate")]
    if beyond and d_tm_row["status"] != C.FAIL:
        d_tm_row = {**d_tm_row, "status": C.FAIL, "note": d_tm_row["note"] + f"; the ELF demand of the "
                    f"{' and '.join(beyond)} bound exceeds the bearing's ultimate displacement"}
    rows.append(d_tm_row)
    basis = review.design_values["elf_floor_basis"]
    prime = basis["key"] == "D_TM_prime_m"
    rows.append(C.at_least("D_TM_elf_floor", "ASCE 7-22 17.6.4.1" + (" (Eq. 17.6-1)" if prime else ""), d_tm["rha_m"],
                           d_tm["elf_floor_m"],
                           f"RHA total displacement ≥ {p['f_disp']:g} × "
                           + (f"D'_TM (ELF, D'_M = D_M/√(1 + (T/T_M)²), T = {review.structure['T_fixed_s']:.4g} s "
                              f"the superstructure's fixed-base period) = {p['f_disp']:g} × {basis['value_m']:.4g} m"
                              if prime else f"D_TM (ELF) = {p['f_disp']:g} × {review.design_values['elf_D_TM_m']:.4g} m")
                           + "; below it the floor is used", "m"))
    ratios = {b: asce7_22.restoring_force_ratio(designs[b], values[b]["D_M_rha_m"]) for b in ("lower", "upper")}
    b_min = min(ratios, key=lambda b: ratios[b] if math.isfinite(ratios[b]) else math.inf)
    rows.append(C.restoring_force(ratios[b_min], p["restoring_min"], displacement_m=values[b_min]["D_M_rha_m"],
                                  radius_m=None if asce7_22.is_multisurface(design) else design.radius_m))
    elf_vb = max(elf[b]["V_b_over_W"] for b in ("lower", "upper"))
    rows.append(C.at_least("base_shear_elf_floor", "ASCE 7-22 17.6.4.2", env["V_b_over_W"], p["f_below"] * elf_vb,
                           f"RHA isolation-system shear / W ({env['V_b_bound']} bound) ≥ {p['f_below']:g} V_b/W (ELF "
                           f"{elf_vb:.4g})", "V/W"))
    v_s = max(elf[b].get("V_s_over_W", math.nan) for b in ("lower", "upper"))
    mode = p.get("multisurface_activation", "outer")
    activation = {b: asce7_22.activation_force_per_weight(designs[b], mode) for b in ("lower", "upper")}
    activation["nominal"] = asce7_22.activation_force_per_weight(design, mode)  # analysed or not: the design's own
    r_fixed = design.superstructure.response_modification_R if design.superstructure is not None else None
    fixed_base = asce7_22.fixed_base_limits(elf, design_values(review.target), r_fixed, p)
    rows.append(_superstructure_shear_row(review, v_s, activation, fixed_base))
    s = review.design_values.get("structure", {})
    drift = s.get("story_drift_ratio")
    story = int(np.argmax(drift)) if drift else 0
    layout = design.bearing_layout
    factored = s.get("factored_bearing_loads")
    loads = None if "bearing_axial_load_max_N" not in s else {
        "max": factored["max_N"] if factored else s["bearing_axial_load_max_N"],
        "capacity": None if layout is None or layout.axial_capacities_N is None else list(layout.axial_capacities_N),
        "note": f"{env['rule']} of {env['n']} analyses per bound, the larger bound"
                + (f"; unfactored {max(s['bearing_axial_load_max_N']):.4g} N" if factored else ""),
        "basis": factored["basis"] if factored else None}
    rows += asce7_22.requirement_rows(
        elf, p, mu_static_lower=asce7_22.breakaway_force_per_weight(designs["lower"]),
        mu_static_upper=activation["upper"], mu_static_nominal=activation["nominal"],
        story_drift_ratio=drift[story] if drift else None,
        story_drift_note=(f"story {story + 1} of {len(drift)} (from the bottom), {env['rule']} of {env['n']} analyses "
                          f"per bound, {s.get('story_drift_bound')} bound; limit drift_limit_rha [U]") if drift else "",
        bearing_axial_loads_N=loads, fixed_base=fixed_base, multisurface=asce7_22.is_multisurface(design),
        activation_mode=mode, activation_regime=asce7_22.activation_regime(design))
    accel = s.get("floor_peak_acceleration_m_s2")
    rows.append(C.floor_acceleration(
        max(accel) if accel else None,
        ("per floor, bottom to top: " + ", ".join(f"{a:.3g}" for a in accel)
         + f" m/s² ({env['rule']} of {env['n']} per bound, the larger bound)") if accel else ""))
    rows.append(C.check("separation", "ASCE 7-22 17.2.5.2 [U]", C.NOT_CHECKED, None, d_tm["value"],
                        "the moat (separation to retaining walls) must be ≥ the design total displacement; not an "
                        "input of the review", "m"))
    rows.append(C.check("prototype_tests", "ASCE 7-22 17.8 [U]", C.NOT_CHECKED, None, d_tm["value"],
                        f"prototype tests must reach the total displacement and confirm λ_min "
                        f"{review.bounds.lambda_min:.3g} / λ_max {review.bounds.lambda_max:.3g}; reviewer's list",
                        "m"))
    return rows + _common_back(review, values, d_tm["value"])


def _torsion_said(review) -> str:
    """The torsion factor's basis, marked [U] where the design did not give what it needs (y, P_T, or the plan)."""
    torsion = review.design_values["torsion"]
    return torsion["basis"] + ("; assumed where not given [U]" if torsion.get("assumed") else "")


def _corner_factor(review) -> float | None:
    """The torsion factor the capacity rows apply to each analysis (``capacity_at_corner`` [U]), else None: ASCE's
    D_TM/D_M (Eq. 17.5-3, its floor without a plan), EN's largest δ_i (none without a plan: the centre of mass)."""
    torsion = review.design_values["torsion"]
    if not review.parameters.get("capacity_at_corner") or (torsion.get("code") == "en15129" and "e_x_m" not in torsion):
        return None
    return torsion["factor"]


def _superstructure_shear_row(review, v_s: float, activation: dict, fixed_base: dict) -> dict:
    """17.6.4.2: the suite's superstructure shear / R_I against f_above V_s and the 17.5.4.3 limits it computes."""
    p, elf = review.parameters, review.elf
    limits = {}
    per = fixed_base["per_bound"]
    if per:
        b = max(per, key=lambda k: per[k]["V_over_W"])
        limits[f"17.5.4.3(1) fixed-base C_s W_s/W = {per[b]['C_s']:.4g} × {p['Ws_over_W']:.4g} = "
               f"{per[b]['V_over_W']:.4g} (T_M {per[b]['T_M_s']:.4g} s, {b} bound, R = "
               f"{review.design.superstructure.response_modification_R:g}, I_e = {p['importance_factor_Ie']:g})"] = \
            per[b]["V_over_W"]
    v_act = asce7_22.activation_shear_over_w(activation["upper"], activation["nominal"], p["activation_nominal_factor"])
    act = [asce7_22.activation_superstructure_shear_over_w(v_act, elf[b]["beta_M"], p)
           for b in ("lower", "upper") if math.isfinite(elf[b].get("beta_M", math.nan))]
    if act:
        limits[f"17.5.4.3(3) activation V_st/W = {max(act):.4g}"] = max(act)
    if p.get("wind_shear_over_W") is not None:
        limits[f"17.5.4.3(2) wind V/W = {p['wind_shear_over_W']:.4g}"] = p["wind_shear_over_W"]
    s = review.design_values.get("structure", {})
    coefficient = s.get("superstructure_shear_coefficient")
    ws = p.get("Ws_over_W", 1.0)
    rha = None if coefficient is None else coefficient * ws
    env = review.design_values["envelope"]
    note = (f"first-story shear / W_s {coefficient:.4g} × W_s/W {ws:.4g}, {env['rule']} of {env['n']} analyses per "
            f"bound, {s.get('superstructure_shear_bound')} bound; f_above_rha = {p['f_above_rha']:g} (regular; 0.8 "
            "irregular)") if rha is not None else ""
    not_computed = "; ".join(([] if per else [f"17.5.4.3(1) not computed: {fixed_base['missing']}"])
                             + ([] if p.get("wind_shear_over_W") is not None
                                else ["17.5.4.3(2) not computed: needs wind_shear_over_W"]))
    if review.design.superstructure is None:
        missing = ("no value: the design has no [superstructure], so its analyses (the isolated mass as one rigid "
                   "block) give no superstructure shear; give the floors in [superstructure] for the building model")
    else:
        missing = (f"no value: the design's {review.design.superstructure.n_floors}-floor [superstructure] was not "
                   "analysed by the building model, so no first-story shear came out of the analyses")
    return C.superstructure_shear(v_s, p["f_above_rha"], rha, limits=limits, r_i=p["R_I"], note=note,
                                  missing=missing, not_computed=not_computed)


def _en_checks(review, values: dict, designs: dict) -> list:
    """The EN 15129 / EN 1998-1 rows (REVIEW_RULES §2): each cites an EN clause and applies only EN's rules."""
    p, design = review.parameters, review.design
    env = review.design_values["envelope"]
    torsion = review.design_values["torsion"]
    cap = design.displacement_capacity_m
    rows = _common_front(review, p["n_records_min_en"], "EN 1998-1 3.2.3.1.2", "EN 1998-1 3.2.3.1.2(4)",
                         "component spectra")
    rows.insert(2, _en_zero_period_row(review))
    d_bi = env["D_TM"]["rha_m"]  # the suite's centre-of-mass displacement × the largest δ_i (no floor)
    capacity_rows = C.record_capacity(review.analyses, cap, clause="EN 1998-1 10.3(2) / EN 15129 (capacity, each "
                                                                   "analysis)", torsion_factor=_corner_factor(review),
                                    reliability_factor=p["gamma_x"])
    rows += [_unless_torsion_known(row, torsion) for row in capacity_rows]
    per_bearing = _en_bearing_displacements(review, env["D_M_rha_m"], p["gamma_x"])
    tail = f"; {env['rule']} of {env['n']} pairs (EN 1998-1 4.3.3.4.3(3))" + (
        "" if cap is not None else "; no displacement_capacity_m in the design")
    if per_bearing is None:
        row = C.at_most("displacement_capacity", "EN 1998-1 10.3(2) / EN 15129", p["gamma_x"] * d_bi, cap,
                        f"γ_x = {p['gamma_x']:g} (EN 1998-1 10.3(2)) × the isolator's design displacement "
                        f"{d_bi:.4g} m = δ {torsion['factor']:.4g} × the centre of mass's {env['D_M_rha_m']:.4g} m "
                        f"({torsion['basis']})" + tail, "m")
    else:
        row = C.at_most("displacement_capacity", "EN 1998-1 10.3(2) / EN 15129", per_bearing["largest"], cap,
                        per_bearing["note"] + tail, "m")
    rows.append(_unless_torsion_known(row, torsion))
    if asce7_22.is_multisurface(design):  # d_r = F₀/K_r is the bilinear CSS model's; a double/triple has none
        rows.append(C.check("restoring_capability", "EN 1998-2 7.7.1 / EN 15129", C.NOT_CHECKED, None, p["delta"],
                            "d_r = F₀/K_r is defined for the bilinear curved-surface slider (EN 15129); the rules give "
                            "no d_r of a double or triple pendulum's multi-linear loop", "-"))
    else:
        rows.append(_en_restoring_row(review, values, designs))
    rows += _en_building_rows(review)
    return rows + _common_back(review, values, p["gamma_x"] * d_bi,
                               f"γ_x {p['gamma_x']:g} × the isolator's design displacement (δ {torsion['factor']:.4g})")


def _en_restoring_row(review, values: dict, designs: dict) -> dict:
    """EN 1998-2 7.7.1(2) / EN 15129 [U]: d_cd / d_r ≥ δ at each bound, d_r = F₀/K_r = µR (REVIEW_RULES §2), with
    d_cd the design displacement of the stiffness centre: the bound's centre-of-mass suite value (friction
    pendulums: the stiffness centre is the centre of mass).  The isolators' reliability factor γ_x and the torsion
    factors δ_i of EN 1998-1 10.3(2) / 10.9.6 enlarge each isolator's displacement *capacity* requirement, not the
    restoring check's d_cd; applying them here would make the check easier to pass, so they are not applied (the
    note says so)."""
    p = review.parameters
    d_cd = {b: values[b]["D_M_rha_m"] for b in ("lower", "upper")}
    ratios = {b: en15129.restoring_capability_ratio(designs[b], designs[b].mu_kinetic, d_cd[b]) for b in d_cd}
    b_min = min(ratios, key=ratios.get)
    return C.at_least("restoring_capability", "EN 1998-2 7.7.1(2) / EN 15129", ratios[b_min], p["delta"],
                      f"d_cd / d_r, d_cd = the {b_min} bound's centre-of-mass (stiffness-centre) design displacement "
                      f"{d_cd[b_min]:.4g} m, without γ_x or δ_i (they apply to the isolators' capacity, EN 1998-1 "
                      f"10.3(2)); d_r = µR (µ = {designs[b_min].mu_kinetic:.4g})", "-")


def _en_zero_period_row(review) -> dict:
    """EN 1998-1 3.2.3.1.2(4) [U]: the mean zero-period spectral acceleration of the scaled records — the mean of
    their components' PGA (the records are linear between samples, so the peak is at a sample) — not below the
    target's S_a(0) (a_g·S for the EN elastic spectrum)."""
    clause = "EN 1998-1 3.2.3.1.2(4) [U] (zero-period ordinate)"
    target = review.target
    if target.kind == "table" and target.periods_s[0] > 0:
        return C.check("suite_zero_period", clause, C.NOT_CHECKED, None, None,
                       f"the tabulated target starts at T = {target.periods_s[0]:g} s: no zero-period ordinate", "g")
    s0 = float(target.sa_g(0.0)[0])
    g = review.design.gravity_m_s2
    pgas = [review.factors[pair.name] * float(np.max(np.abs(a))) / g for pair in review.suite.pairs
            for a in (pair.ax_m_s2, pair.ay_m_s2)]
    return C.at_least("suite_zero_period", clause, float(np.mean(pgas)), s0,
                      f"mean over the {len(pgas)} scaled components of their PGA (S_a at T = 0) ≥ the target's "
                      f"S_a(0) = {s0:.4g} g" + (" = a_g·S" if target.kind == "en1998-elastic" else ""), "g")


def _unless_torsion_known(row: dict, torsion: dict) -> dict:
    """An EN displacement row that passes without a plan: ``not checked`` (EN 1998-1 10.3(2) asks each isolator's
    displacement with torsion, which needs the plan); a failure stands (δ ≥ 1 only adds to it)."""
    if row["status"] != C.PASS or "e_x_m" in torsion:  # e_x_m: the plan was there, δ computed
        return row
    return {**row, "status": C.NOT_CHECKED,
            "note": row["note"] + "; passes without torsion only: EN 1998-1 10.3(2) asks each isolator's displacement "
                                  "with torsion, which needs the design's [plan]"}


def _en_bearing_displacements(review, d_m: float, gamma_x: float) -> dict | None:
    """EN 1998-1 10.3(2): γ_x × each bearing's design displacement, torsion included (δ_i of EN 1998-1 10.9.6 at
    each bearing of the layout: ``torsion["bearing_factors"]``); None without ``[[bearing_position]]`` and
    ``[plan]`` (the row then uses the plan's corner isolator)."""
    torsion = review.design_values["torsion"]
    factors = torsion.get("bearing_factors")
    if not factors or not math.isfinite(d_m):
        return None
    layout = review.design.bearing_layout
    values = [gamma_x * f * d_m for f in factors]
    k = int(np.argmax(values))
    note = (f"γ_x = {gamma_x:g} (EN 1998-1 10.3(2)) × each bearing's displacement, torsion included: the suite's "
            f"centre-of-mass D = {d_m:.4g} m × δ_i; bearing {k + 1} at ({layout.x_m[k]:g}, {layout.y_m[k]:g}) m "
            f"governs, δ = {factors[k]:.4g} (δ from {min(factors):.4g} to {max(factors):.4g} over the "
            f"{len(factors)} bearings); {torsion['basis']}")
    return {"largest": values[k], "note": note}


def _en_building_rows(review) -> list:
    """A building under EN 15129 / EN 1998-1: what REVIEW_RULES §2 supports, else reported with no limit.

    The suite values are the mean of ≥ ``n_for_mean`` analyses, else the most unfavourable (EN 1998-1
    4.3.3.4.3(3)), the larger bound.  The rules give no EN limit on story drift, superstructure shear or floor
    acceleration: those rows are ``not checked`` with their values.  The bearings' axial capacity (given in
    ``axial_capacity_N``) is checked against the largest load.
    """
    s = review.design_values.get("structure", {})
    if "story_drift_ratio" not in s:
        return []
    env = review.design_values["envelope"]
    rule = f"{env['rule']} of {env['n']} analyses per bound (EN 1998-1 4.3.3.4.3(3)), the larger bound"
    none = "reported, no EN limit in the rules"
    drift = s["story_drift_ratio"]
    story = int(np.argmax(drift))
    ws = review.structure.get("Ws_over_W", math.nan)
    rows = [C.check("story_drift", f"EN 1998-1 4.3.3.4.3(3) (suite value); {none}", C.NOT_CHECKED, drift[story],
                    None, f"{none} (REVIEW_RULES §2 gives no EN drift limit): story {story + 1} of {len(drift)} "
                          f"(from the bottom), {rule}; every story: " + ", ".join(f"{d:.3g}" for d in drift),
                    "h_sx"),
            C.check("superstructure_shear", f"EN 1998-1 4.3.3.4.3(3) (suite value); {none}", C.NOT_CHECKED,
                    s["superstructure_shear_coefficient"] * ws, None,
                    f"{none}: first-story shear / W_s {s['superstructure_shear_coefficient']:.4g} × W_s/W {ws:.4g} "
                    f"(elastic, not reduced), {rule}", "V/W"),
            C.floor_acceleration(max(s["floor_peak_acceleration_m_s2"]),
                                 "per floor, bottom to top: " + ", ".join(
                                     f"{a:.3g}" for a in s["floor_peak_acceleration_m_s2"]) + f" m/s² ({rule})",
                                 clause=f"EN 1998-1 4.3.3.4.3(3) (suite value); {none}", why=f"{none}: ")]
    if "bearing_axial_load_max_N" in s:
        layout = review.design.bearing_layout
        rows.append(C.vertical_load_stability(
            s["bearing_axial_load_max_N"], None if layout.axial_capacities_N is None
            else list(layout.axial_capacities_N), rule, clause="EN 15129 (the bearing's vertical load capacity, "
                                                               "axial_capacity_N as given) [U]"))
    return rows

