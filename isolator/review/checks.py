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
    return at_least("restoring_force", clause, ratio, minimum, note, "W")


def usable_band(pairs: list, range_hi_s: float, factor: float = 1.25) -> dict:
    """Records whose usable band (from the high-pass corner f_hp: up to 1/(factor f_hp)) reaches the range.

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
            + (f"corner unknown for {len(unknown)} pair(s): {', '.join(unknown)}" if unknown else "all corners known"))
    if not known:
        return check("usable_band", "record processing (practice)", NOT_CHECKED, None, range_hi_s,
                     "no record states its high-pass corner; " + note, "s")
    shortest = min(t for _, t in known)
    return check("usable_band", "record processing (practice)", FAIL if short else PASS, shortest, range_hi_s,
                 note, "s")


def status_counts(checks: list) -> dict:
    """How many checks pass, fail, or were not checked."""
    out = {PASS: 0, FAIL: 0, NOT_CHECKED: 0}
    for row in checks:
        out[row["status"]] += 1
    return out
