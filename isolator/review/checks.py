"""The review's checks: one row each, {id, clause, status, value, limit, note}.

Status is ``pass``, ``fail`` or ``not checked`` (with the reason in ``note``).  Every function
here is pure: numbers in, one row out; :mod:`isolator.review.run` gathers the numbers.
"""

from __future__ import annotations

import math

import numpy as np

PASS, FAIL, NOT_CHECKED = "pass", "fail", "not checked"


def check(id_: str, clause: str, status: str, value=None, limit=None, note: str = "", unit: str = "") -> dict:
    """One row of the checks table."""
    if status not in (PASS, FAIL, NOT_CHECKED):
        raise ValueError(f"status {status!r}")
    return {"id": id_, "clause": clause, "status": status, "value": _finite_or_none(value),
            "limit": _finite_or_none(limit), "unit": unit, "note": note}


def _finite_or_none(value):
    return None if isinstance(value, float) and not math.isfinite(value) else value


def _missing(number) -> bool:
    return number is None or (isinstance(number, float) and math.isnan(number))


def at_most(id_, clause, value, limit, note="", unit="") -> dict:
    """value ≤ limit passes (no limit or no value — None or NaN: not checked)."""
    if _missing(limit) or _missing(value):
        return check(id_, clause, NOT_CHECKED, value, limit, note, unit)
    return check(id_, clause, PASS if value <= limit else FAIL, value, limit, note, unit)


def at_least(id_, clause, value, limit, note="", unit="") -> dict:
    """value ≥ limit passes (no limit or no value — None or NaN: not checked)."""
    if _missing(limit) or _missing(value):
        return check(id_, clause, NOT_CHECKED, value, limit, note, unit)
    return check(id_, clause, PASS if value >= limit else FAIL, value, limit, note, unit)


def suite_value(values, n_for_mean: int = 7) -> dict:
    """The design value of a quantity over a suite: the mean of ≥ ``n_for_mean`` analyses, else the maximum.

    (ASCE 7-22 17.6.3.4 [U]; EN 1998-1 4.3.3.4.3(3).)

    Returns
    -------
    dict
        ``value``, ``rule`` (``"mean"`` or ``"max"``), ``n``.
    """
    values = np.asarray([v for v in values if v is not None and math.isfinite(v)], dtype=np.float64)
    n = int(values.size)
    if n == 0:
        return {"value": math.nan, "rule": "none", "n": 0}
    if n >= n_for_mean:
        return {"value": float(values.mean()), "rule": "mean", "n": n}
    return {"value": float(values.max()), "rule": "max", "n": n}


def restoring_force(ratio: float, minimum: float = 0.025, *, displacement_m=None, radius_m=None,
                    clause: str = "ASCE 7-22 17.2.4.4") -> dict:
    """(F(D) − F(D/2))/W ≥ ``minimum`` (for a single friction pendulum: D ≥ 2 minimum R = 0.05 R)."""
    note = "F(D) − F(D/2) per unit weight at the design displacement of each bound (the smaller is shown)"
    if radius_m is not None and displacement_m is not None:
        note += f"; FPS: D = {displacement_m:.4g} m vs {2 * minimum:g} R = {2 * minimum * radius_m:.4g} m"
    return at_least("restoring_force", clause, ratio, minimum, note, "×W")


def usable_band(pairs: list, range_hi_s: float, factor: float = 1.25) -> dict:
    """Records whose usable band (from the high-pass corner f_hp: up to 1/(factor f_hp)) reaches the range.

    ``pass`` only when every pair states its corner and every one reaches the range; ``fail`` when a
    stated corner falls short; otherwise ``not checked``, saying for how many pairs the corner is unknown.

    Parameters
    ----------
    pairs : list of (name, high_pass_hz or None)
    range_hi_s : float
        Upper end of the scaling period range [s].
    factor : float
        Lowest usable frequency = factor × f_hp (NGA-West2 practice) [-].
    """
    known = [(name, 1.0 / (factor * hz)) for name, hz in pairs if hz]
    unknown = [name for name, hz in pairs if not hz]
    short = [(name, t) for name, t in known if t < range_hi_s]
    note = (f"usable to 1/({factor:g} f_hp); " + (", ".join(f"{n} to {t:.3g} s" for n, t in short) + " fall short; "
                                                  if short else "")
            + (f"corner unknown for {len(unknown)} of {len(pairs)} pair(s): {', '.join(unknown)}" if unknown
               else "all corners known"))
    clause = "record processing (practice)"
    if not known:
        return check("usable_band", clause, NOT_CHECKED, None, range_hi_s,
                     "no record states its high-pass corner; " + note, "s")
    shortest = min(t for _, t in known)
    if short:
        return check("usable_band", clause, FAIL, shortest, range_hi_s, note, "s")
    if unknown:
        return check("usable_band", clause, NOT_CHECKED, shortest, range_hi_s,
                     f"checked for {len(known)} pair(s) only (all reach the range); " + note, "s")
    return check("usable_band", clause, PASS, shortest, range_hi_s, note, "s")


def uplift(n_vertical_exceedances: int, n_pairs_with_vertical: int, min_axial_load_N: float | None = None, *,
           detail: str = "", n_verticals_not_analysed: int = 0, clause: str = "ASCE 7-22 17.2.4.7 [U]",
           basis: str | None = None) -> dict:
    """Bearing uplift (ASCE 7-22 17.2.4.7 [U]): from overturning, so from the bearings' axial loads.

    Parameters
    ----------
    n_vertical_exceedances : int
        Episodes in which g + a_z ≤ 0 (the vertical ground acceleration reached −1 g), summed over the
        analyses: shown as what it is, not as uplift [-].
    n_pairs_with_vertical : int
        Pairs of the suite that have a vertical component [-].
    min_axial_load_N : float, optional
        Smallest bearing axial compression over every analysis [N] — the hook for a superstructure and
        bearing layout model (positive: compression).  Without it the row is ``not checked``.
    detail : str
        What the value is (suite rule, bearing, bound) and how many analyses lifted a bearing.
    n_verticals_not_analysed : int
        Pairs whose vertical the review left out (parameter ``horizontal_only``) [-].
    clause : str
        The clause printed (EN reviews: a sliding bearing carries no tension, no EN clause in the rules).
    basis : str, optional
        How the loads were factored (the 2.3.6 combination, 17.2.4.7); without it the loads are unfactored and the
        note says so.
    """
    vertical = (f"the isolated mass's normal force M (g + a_z) vanished in {n_vertical_exceedances} episode(s) over "
                f"{n_pairs_with_vertical} pair(s) with a vertical (vertical ground acceleration ≤ −1 g: a ground "
                "quantity, not bearing uplift)"
                if n_pairs_with_vertical else
                f"the verticals of {n_verticals_not_analysed} pair(s) not analysed (horizontal_only)"
                if n_verticals_not_analysed else "no vertical components in the suite")
    if min_axial_load_N is None:
        return check("uplift", clause, NOT_CHECKED, None, 0.0,
                     "uplift comes from overturning: needs the bearings' axial loads (a superstructure and bearing "
                     "layout); " + vertical, "N")
    return at_least("uplift", clause, float(min_axial_load_N), 0.0,
                    "smallest bearing axial compression (uplift if < 0; 17.2.4.7 permits local uplift only where "
                    "the resulting deflections cause no overstress or instability; "
                    + (basis or "unfactored gravity share, the minimum-load combination of 2.3.6 — 0.9D − E_v — not "
                       "applied [U]") + ")"
                    + (f": {detail}" if detail else "") + "; " + vertical, "N")


def superstructure_shear(v_s_elf_over_w: float, f_above: float, rha_over_w: float | None = None,
                         clause: str = "ASCE 7-22 17.6.4.2", *, limits: dict | None = None, r_i: float = 1.0,
                         note: str = "", missing: str = "", not_computed: str = "") -> dict:
    """RHA superstructure design shear ≥ ``f_above`` × ELF V_s and ≥ the 17.5.4.3 limits (17.6.4.2).

    The value is the response-history superstructure shear / W reduced by R_I (the elastic first-story shear of
    the suite, divided by R_I as for the ELF V_s = V_st / R_I [U]) — never the ELF V_s itself; without it the
    row is ``not checked``.

    Parameters
    ----------
    v_s_elf_over_w : float
        ELF V_s / W (Eq. 17.5-6), the larger bound [-].
    f_above : float
        17.6.4.2's fraction of V_s for response-history analysis (0.6 regular, 0.8 irregular) [-].
    rha_over_w : float, optional
        The suite's elastic superstructure shear / W (design value, larger bound) [-].
    limits : dict, optional
        The 17.5.4.3 limits that the review computes, name → V/W [-]: the limit is the largest of these
        and ``f_above`` × V_s, and the note names which governs.
    r_i : float
        R_I of 17.5.4.2 [-].
    note : str
        What the value is made of (suite rule, bound).
    missing : str
        Why there is no value (``rha_over_w`` None): said first in the row's note.
    not_computed : str
        The limits that could not be computed, and why (said in the note with or without a value).
    """
    candidates = {}
    if v_s_elf_over_w is not None and math.isfinite(v_s_elf_over_w):
        candidates[f"17.6.4.2 {f_above:g} × ELF V_s/W = {f_above:g} × {v_s_elf_over_w:.4g} = "
                   f"{f_above * v_s_elf_over_w:.4g}"] = f_above * v_s_elf_over_w
    for name, value in (limits or {}).items():
        if value is not None and math.isfinite(value):
            candidates[name] = value
    limit, governs = (max(candidates.values()), max(candidates, key=candidates.get)) if candidates else (None, "")
    if rha_over_w is None or not math.isfinite(rha_over_w):
        # it said "limit <the governing one>" alone, whatever else was computed and whether or not the design had a
        # superstructure (session 19 sweep): now why no value, every limit computed and what was not
        why = missing or ("needs the superstructure shear of the response histories (a design with a "
                          "[superstructure] analysed by the building model)")
        said = ("the limit computed: the largest of " + "; ".join(candidates) + f" — {governs} governs"
                if candidates else "no limit computed (no ELF V_s)")
        return check("superstructure_shear", clause, NOT_CHECKED, None, limit,
                     f"{why}; {said}" + (f"; {not_computed}" if not_computed else ""), "V/W")
    value = rha_over_w / r_i
    return at_least("superstructure_shear", clause, value, limit,
                    f"RHA superstructure shear / W ÷ R_I = {rha_over_w:.4g} / {r_i:g} [U: RHA forces reduced by R_I]"
                    + (f" ({note})" if note else "") + " ≥ the largest of 17.6.4.2 and the 17.5.4.3 limits: "
                    + "; ".join(candidates) + f" — {governs} governs" + (f"; {not_computed}" if not_computed else ""),
                    "V/W")


def story_drift(drift_ratio: float | None, limit: float | None, note: str = "",
                clause: str = "ASCE 7-22 17.6.4.4 [U]") -> dict:
    """Largest story drift / story height of the suite ≤ ``limit`` (0.020 with RHA; 17.6.4.4 [U])."""
    if drift_ratio is None or not math.isfinite(drift_ratio):
        return check("story_drift", clause, NOT_CHECKED, None, limit,
                     "needs the superstructure's story drifts (a design with a [superstructure] analysed by the "
                     "building model)", "h_sx")
    return at_most("story_drift", clause, drift_ratio, limit, note, "h_sx")


def floor_acceleration(peak_m_s2: float | None, note: str = "",
                       clause: str = "ASCE 7-22 13.3.1 (nonstructural components; reported) [U]", *,
                       why: str = "reported, not a Chapter 17 check (the input of Chapter 13's nonstructural "
                                  "forces): ") -> dict:
    """The suite's largest absolute floor acceleration: reported for the nonstructural components (no limit in the
    code's rules: ``why`` says so), so always ``not checked``, with the value when the building model gave it."""
    if peak_m_s2 is None or not math.isfinite(peak_m_s2):
        return check("floor_acceleration", clause, NOT_CHECKED, None, None,
                     "needs the floors' accelerations (a design with a [superstructure])", "m/s²")
    return check("floor_acceleration", clause, NOT_CHECKED, peak_m_s2, None, why + note, "m/s²")


def vertical_load_stability(max_load_N: list | None, capacities_N: list | None, note: str = "",
                            clause: str = "ASCE 7-22 17.2.4.6", basis: str | None = None) -> dict:
    """Each bearing's largest axial compression (suite value) ≤ its vertical load capacity at the total displacement.

    The value is the largest demand ratio P_max / capacity over the bearings; ``not checked`` without the loads
    (a superstructure and ``[[bearing_position]]``) or the capacities (``axial_capacity_N``).  ``basis`` says how
    the loads were factored (the 2.3.6 combination); without it they are unfactored and the note says so.
    """
    if max_load_N is None:
        return check("vertical_load_stability", clause, NOT_CHECKED,
                     note="needs each bearing's maximum vertical load (dead, live, seismic overturning) at the total "
                          "displacement: a [superstructure] and [[bearing_position]] analysed by the building model")
    if capacities_N is None:
        return check("vertical_load_stability", clause, NOT_CHECKED, max(max_load_N), None,
                     "bearing axial loads are known (largest shown) but the design gives no axial_capacity_N in "
                     "[[bearing_position]] (the bearings' vertical load capacity at the total displacement)", "N")
    ratios = [p / c for p, c in zip(max_load_N, capacities_N, strict=True)]
    k = int(np.argmax(ratios))
    return at_most("vertical_load_stability", clause, ratios[k], 1.0,
                   f"bearing {k + 1}: P_max {max_load_N[k]:.4g} N / capacity {capacities_N[k]:.4g} N ("
                   + (basis or "unfactored: the bearing's gravity share of W = g × mass_kg + the overturning of the "
                      "floors' inertia forces; "
                      + ("the factored combination of 2.3.6 that 17.2.4.6 names — dead-load factor, E_v, live load — "
                         "is not applied [U]" if clause.startswith("ASCE") else "no load combination applied [U]"))
                   + ")" + (f"; {note}" if note else ""), "×capacity")


def record_capacity(analyses: dict, capacity_m: float | None, clause: str = "ASCE 7-22 17.2.4.5 / 17.6.3.4 [U]",
                    *, mass_kg: float | None = None, torsion_factor: float | None = None,
                    reliability_factor: float | None = None) -> list[dict]:
    """One ``fail`` row per analysis (pair × bound) whose peak displacement exceeds the capacity, or that reached
    the bearing's ultimate displacement (a double or triple pendulum's rims: ``ultimate_displacement_reached``).

    When none does, one ``pass`` row with the largest single displacement; ``not checked`` without a
    capacity.  Beyond the capacity the analysed motion is not physical: no restrainer is modelled.  At the
    ultimate displacement the bearing's rims stop the motion (plastic impact): its peak equals the capacity,
    so it never passes.

    Parameters
    ----------
    analyses : dict
        bound → pair → result (``peak_displacement_m``; ``ultimate_displacement_reached`` and
        ``impact_impulse_m_s`` for a bearing with rims; failed analyses carry ``error``).
    capacity_m : float or None
        Displacement capacity of the bearing [m] (a double or triple pendulum's ultimate Σ d*).
    mass_kg : float, optional
        The isolated mass M [kg], for the impulse M Σ|V| in the note.
    torsion_factor : float, optional
        D_TM/D_M of Eq. 17.5-3 (review parameter ``capacity_at_corner`` [U], REVIEW_RULES 1.10): each analysis's
        centre-of-mass displacement times it is the corner bearing's, the value compared (the row's
        ``centre_of_mass_m`` keeps the analysis's own).  An analysis held at a single pendulum's rim has its centre
        of mass at the capacity, so its corner reads factor × capacity > capacity: it fails either way.
    reliability_factor : float, optional
        γ_x of EN 1998-1 10.3(2) [U] (review parameter ``gamma_x``): each isolator is designed for γ_x times its
        displacement, so each analysis's (corner) displacement times it is the value compared, as the suite's
        ``displacement_capacity`` row does.  None (ASCE 7): no reliability factor.
    """
    rows = []
    largest, where = -math.inf, ""
    gamma = 1.0 if reliability_factor is None else float(reliability_factor)
    factor = (1.0 if torsion_factor is None else float(torsion_factor)) * gamma
    corner = ("" if reliability_factor is None else f"γ_x {gamma:g} (EN 1998-1 10.3(2)) × ") + (
        "" if torsion_factor is None else f"corner bearing {float(torsion_factor):.4g} × ")
    for bound, results in analyses.items():
        for name, r in results.items():
            d_cm = r.get("peak_displacement_m")
            if "error" in r or d_cm is None or not math.isfinite(d_cm):
                continue
            d = factor * d_cm
            extra = {"pair": name, "bound": bound} | (
                {} if torsion_factor is None else {"centre_of_mass_m": d_cm, "torsion_factor": float(torsion_factor)}
            ) | ({} if reliability_factor is None else {"centre_of_mass_m": d_cm, "reliability_factor": gamma})
            said_d = f"D = {corner}{d_cm:.4g} m = {d:.4g} m" if corner else f"D = {d:.4g} m"
            if d > largest:
                largest, where = d, f"{name}, {bound} bound" + (f" ({said_d})" if corner else "")
            if r.get("ultimate_displacement_reached") and r.get("rim_modelled", True):  # held at a modelled rim
                impulse = r.get("impact_impulse_m_s")
                said = "" if impulse is None else (f"; impulse {impulse * mass_kg:.4g} N·s" if mass_kg
                                                   else f"; impulse {impulse:.4g} m/s per unit mass")
                at_corner = (f"; the centre of mass is held at the rim, so the {corner}{d_cm:.4g} m = {d:.4g} m "
                             "exceeds the capacity" + (" (with torsion the corner bearings reach their rims first)"
                                                       if torsion_factor is not None else "")
                             if corner and d > d_cm else "")
                rows.append(check("record_capacity", clause, FAIL, d, capacity_m,
                                  f"{name}, {bound} bound: the bearing REACHED its ultimate displacement (every slider "
                                  f"on its rim; plastic impact{said}): the demand is at least the capacity{at_corner}",
                                  "m") | extra)
            elif capacity_m is not None and d > capacity_m:
                rows.append(check("record_capacity", clause, FAIL, d, capacity_m,
                                  f"{name}, {bound} bound: {said_d} > capacity {capacity_m:.4g} m"
                                  + ((" (the centre of mass within it: the corner bearing is not)" if torsion_factor
                                      is not None and reliability_factor is None else
                                      " (the centre of mass within it: the factored demand is not)")
                                     if d_cm <= capacity_m else "; the result assumes no restrainer (none is "
                                     "modelled) and is not physical beyond the capacity"),
                                  "m") | extra)
    if rows:
        return rows
    if not math.isfinite(largest):
        return [check("record_capacity", clause, NOT_CHECKED, None, capacity_m, "no analysis succeeded", "m")]
    if capacity_m is None:
        return [check("record_capacity", clause, NOT_CHECKED, largest, None,
                      f"no displacement_capacity_m in the design; largest single analysis {where}", "m")]
    return [check("record_capacity", clause, PASS, largest, capacity_m,
                  f"every analysis within the capacity{' at the corner bearing' if torsion_factor is not None else ''}"
                  f"{' with γ_x' if reliability_factor is not None else ''}; largest {where}",
                  "m")]


def ultimate_reached(analyses: dict) -> list[str]:
    """"pair (bound)" of every analysis that reached the bearing's ultimate displacement."""
    return [f"{name} ({bound})" for bound, results in analyses.items() for name, r in results.items()
            if "error" not in r and r.get("ultimate_displacement_reached") and r.get("rim_modelled", True)]


def never_pass_at_ultimate(row: dict, reached: list[str]) -> dict:
    """A capacity row that cannot pass when an analysis reached the ultimate displacement (its peak is held at the
    rim, so the suite value understates the demand): ``fail``, naming the analyses."""
    if not reached or row["status"] == FAIL:
        return row
    return {**row, "status": FAIL,
            "note": row["note"] + f"; {len(reached)} analysis(es) reached the bearing's ultimate displacement "
                                  f"({', '.join(reached[:4])}{' …' if len(reached) > 4 else ''}): their peaks are "
                                  "held at the rims, so the suite value understates the demand"}


#: Relative amount by which a surface's peak may pass its own displacement capacity before the review says so (the
#: rims hold the outer surfaces to rounding: 0.4000000000000002 m against 0.4 m measured).
SURFACE_RIM_TOLERANCE = 1e-9


def surface_rims_passed(analyses: dict, capacities_m: list[float] | None) -> list[str]:
    """"pair (bound): surface i d m > d_i m" of every analysis whose peak displacement on a surface of a double or
    triple bearing passed that surface's own capacity (``surface_peak_displacement_m`` against ``capacities_m``, both
    on the surface, file order).

    The planar series model holds its elements within their rims, which are the surfaces' rims for a double and for a
    triple's outer surfaces but not for a triple's inner ones in a planar motion (docs/multisurface.md, "What the rims
    are in the plane — a limit"): there an inner slider can pass its rim, which the real bearing's rim would stop.
    """
    if not capacities_m:
        return []
    out = []
    for bound, results in analyses.items():
        for name, r in results.items():
            peaks = r.get("surface_peak_displacement_m")
            if "error" in r or not peaks:
                continue
            over = [(i, d, c) for i, (d, c) in enumerate(zip(peaks, capacities_m, strict=True), 1)
                    if d > c * (1.0 + SURFACE_RIM_TOLERANCE)]
            if over:
                out.append(f"{name} ({bound}): " + ", ".join(f"surface {i} {d:.4g} m > its {c:.4g} m"
                                                             for i, d, c in over))
    return out


def within_surface_rims(rows: list, passed: list[str]) -> list:
    """The capacity rows of analyses in which a surface passed its own rim (``passed``: :func:`surface_rims_passed`):
    the model let an inner slider past its rim, so the bearing's capacity is not checked by that analysis —
    ``record_capacity`` cannot pass (``not checked``, naming them), a failure stands with them named;
    ``D_over_R`` (read from the same surface peaks) says so."""
    if not passed:
        return rows
    said = (f"in {len(passed)} analysis(es) a surface passed its own displacement capacity ({'; '.join(passed[:3])}"
            f"{' …' if len(passed) > 3 else ''}): the planar model's element rims are not a triple's inner rims "
            "(docs/multisurface.md), the real rim would have stopped the slider")
    out = []
    for row in rows:
        if row["id"] == "record_capacity" and row["status"] == PASS:
            out.append({**row, "status": NOT_CHECKED, "note": row["note"] + f"; would pass, but {said}"})
        elif row["id"] in ("record_capacity", "D_over_R"):
            out.append({**row, "note": row["note"] + f"; {said}"})
        else:
            out.append(row)
    return out


#: The models that integrate by implicit steps under a relative local-error tolerance (not exact; their errors are
#: measured in docs/multisurface.md and docs/building.md), by the name before any ``+vertical``.
IMPLICIT_STEP_MODELS = ("2d-multisurface", "2d-building-multisurface")


def implicit_step_limit(analyses: dict) -> str:
    """What a row computed from the analyses must say when some of them ran an implicit-step model (else ''): the
    tolerance they ran at and, for a building on a double or triple, that its base shear while the slab slides is
    the peak of each step's parabola (not located exactly, docs/building.md h153: a floor row that passes on it
    stands, one that fails may be the sampling; a limit row may understate)."""
    models = sorted({r.get("model", "") for results in analyses.values() for r in results.values()
                     if "error" not in r and r.get("model", "").split("+")[0] in IMPLICIT_STEP_MODELS})
    if not models:
        return ""
    from isolator.solver.planar_multisurface import DEFAULT_STEP_TOL  # the tolerance the analyses ran at

    building = any(m.startswith("2d-building-multisurface") for m in models)
    return (f"model {', '.join(models)}: implicit steps at step_tol {DEFAULT_STEP_TOL:g} (relative local error; not "
            "exact, measured in docs/multisurface.md and docs/building.md)"
            + ("; the base shear while the slab slides is the peak of each step's parabola through its start, half and "
               "end (not located exactly: it may understate the true peak)"
               if building else ""))


def spread(values) -> dict:
    """Spread of a design quantity over the suite: ``n``, ``mean``, ``std`` (sample, ddof = 1), ``cv`` = std/mean,
    ``max``, ``max_over_mean`` (NaN where undefined)."""
    v = np.asarray([x for x in values if x is not None and math.isfinite(x)], dtype=np.float64)
    if v.size == 0:
        return {"n": 0, "mean": math.nan, "std": math.nan, "cv": math.nan, "max": math.nan, "max_over_mean": math.nan}
    mean = float(v.mean())
    std = float(v.std(ddof=1)) if v.size > 1 else 0.0
    return {"n": int(v.size), "mean": mean, "std": std, "cv": std / mean if mean > 0 else math.nan,
            "max": float(v.max()), "max_over_mean": float(v.max()) / mean if mean > 0 else math.nan}


def status_counts(checks: list) -> dict:
    """How many checks pass, fail, or were not checked."""
    out = {PASS: 0, FAIL: 0, NOT_CHECKED: 0}
    for row in checks:
        out[row["status"]] += 1
    return out
