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


def at_most(id_, clause, value, limit, note="", unit="") -> dict:
    """value ≤ limit passes (no limit or no value: not checked)."""
    if limit is None or value is None or (isinstance(value, float) and math.isnan(value)):
        return check(id_, clause, NOT_CHECKED, value, limit, note, unit)
    return check(id_, clause, PASS if value <= limit else FAIL, value, limit, note, unit)


def at_least(id_, clause, value, limit, note="", unit="") -> dict:
    """value ≥ limit passes (no limit or no value: not checked)."""
    if limit is None or value is None or (isinstance(value, float) and math.isnan(value)):
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


def uplift(n_vertical_exceedances: int, n_pairs_with_vertical: int, min_axial_load_N: float | None = None) -> dict:
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
    """
    clause = "ASCE 7-22 17.2.4.7 [U]"
    vertical = (f"the rigid block's normal force g + a_z vanished in {n_vertical_exceedances} episode(s) over "
                f"{n_pairs_with_vertical} pair(s) with a vertical (vertical ground acceleration ≤ −1 g: a ground "
                "quantity, not bearing uplift)"
                if n_pairs_with_vertical else "no vertical components in the suite")
    if min_axial_load_N is None:
        return check("uplift", clause, NOT_CHECKED, None, 0.0,
                     "uplift comes from overturning: needs the bearings' axial loads (a superstructure and bearing "
                     "layout); " + vertical, "N")
    return at_least("uplift", clause, float(min_axial_load_N), 0.0,
                    "smallest bearing axial compression over the analyses (uplift if < 0); " + vertical, "N")


def superstructure_shear(v_s_elf_over_w: float, f_above: float, rha_over_w: float | None = None,
                         clause: str = "ASCE 7-22 17.6.4.2") -> dict:
    """RHA superstructure shear ≥ ``f_above`` × ELF V_s (17.6.4.2); not checked without an RHA superstructure.

    The limit is ``f_above`` × the ELF V_s/W; the value is the response-history superstructure shear /W
    — never the ELF V_s itself.
    """
    limit = f_above * v_s_elf_over_w if v_s_elf_over_w is not None and math.isfinite(v_s_elf_over_w) else None
    if rha_over_w is None:
        return check("superstructure_shear", clause, NOT_CHECKED, None, limit,
                     f"needs the superstructure shear of the response histories (a superstructure model); limit "
                     f"{f_above:g} × ELF V_s/W = {f_above:g} × {v_s_elf_over_w:.4g}", "V/W")
    return at_least("superstructure_shear", clause, rha_over_w, limit,
                    f"RHA superstructure shear / W ≥ {f_above:g} × ELF V_s/W", "V/W")


def record_capacity(analyses: dict, capacity_m: float | None, clause: str = "ASCE 7-22 17.2.4.5 / 17.6.3.4 [U]"
                    ) -> list[dict]:
    """One ``fail`` row per analysis (pair × bound) whose peak displacement exceeds the capacity.

    When none does, one ``pass`` row with the largest single displacement; ``not checked`` without a
    capacity.  Beyond the capacity the analysed motion is not physical: no restrainer is modelled.

    Parameters
    ----------
    analyses : dict
        bound → pair → result (``peak_displacement_m``; failed analyses carry ``error``).
    capacity_m : float or None
        Displacement capacity of the bearing [m].
    """
    rows = []
    largest, where = -math.inf, ""
    for bound, results in analyses.items():
        for name, r in results.items():
            d = r.get("peak_displacement_m")
            if "error" in r or d is None or not math.isfinite(d):
                continue
            if d > largest:
                largest, where = d, f"{name}, {bound} bound"
            if capacity_m is not None and d > capacity_m:
                rows.append(check("record_capacity", clause, FAIL, d, capacity_m,
                                  f"{name}, {bound} bound: D = {d:.4g} m > capacity {capacity_m:.4g} m; the result "
                                  "assumes no restrainer (none is modelled) and is not physical beyond the capacity",
                                  "m") | {"pair": name, "bound": bound})
    if rows:
        return rows
    if not math.isfinite(largest):
        return [check("record_capacity", clause, NOT_CHECKED, None, capacity_m, "no analysis succeeded", "m")]
    if capacity_m is None:
        return [check("record_capacity", clause, NOT_CHECKED, largest, None,
                      f"no displacement_capacity_m in the design; largest single analysis {where}", "m")]
    return [check("record_capacity", clause, PASS, largest, capacity_m,
                  f"every analysis within the capacity; largest {where}", "m")]


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
