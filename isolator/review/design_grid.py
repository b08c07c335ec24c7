"""The design space of ``isolator design``: what may vary, the candidates, the objectives and the recommendation.

This module holds the keys of a design file that ``--vary`` may replace (:data:`VARY_KEYS`), the friction
coefficients that follow a varied µk (:data:`FRICTION_FOLLOWERS`), the keys no analysis reads
(:data:`CHECK_ONLY_KEYS`), the objectives (:data:`OBJECTIVES`) and the bound on a search
(:data:`MAX_CANDIDATES`); the parsing of a range (:func:`parse_vary`), the product of the ranges
(:func:`candidate_mappings`, :class:`Candidate`) and the choice of the recommended candidate among those
that pass every check (:func:`recommend`).  The search itself is :mod:`isolator.review.design_space`.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from isolator.design import CANDIDATE_WORDS
from isolator.errors import ReviewError, key_hint

#: numbers of a design file that ``vary`` may replace
VARY_KEYS = ("radius_m", "mu_kinetic", "mu_static", "displacement_capacity_m", "mass_kg", "stiffness_N_per_m",
             "damping_ratio", "damping_Ns_per_m", "mu_slow", "mu_fast", "rate_s_per_m", "lambda_max", "lambda_min",
             "mu_upper", "mu_lower", "lambda_ae_max", "lambda_ae_min", "lambda_test_max", "lambda_test_min",
             "lambda_spec_max", "lambda_spec_min")

#: friction coefficients that follow a varied µk by their ratio to µk in the design file
FRICTION_FOLLOWERS = ("mu_static", "mu_slow", "mu_fast", "mu_upper", "mu_lower")

#: keys that change no analysis, only the checks (candidates differing only in these share their analyses).
#: Empty: the displacement capacity was one until the rim (a single pendulum whose motion reaches its capacity
#: is run again with its rim, in 1-D and 2-D: the capacity changes the analysis).
CHECK_ONLY_KEYS: tuple[str, ...] = ()

#: objective → (column minimised, what it is)
OBJECTIVES = {
    "base_shear": ("base_shear_coefficient", "design base-shear coefficient V_b/W (response history, larger bound)"),
    "displacement": ("design_total_displacement_m", "design total displacement D_TM (torsion and ELF floor)"),
    "residual": ("residual_displacement_m", "suite residual displacement (larger bound)"),
}

#: largest number of candidates of one search (a bound on the loop; split larger searches)
MAX_CANDIDATES = 20_000

# ---- the design space ----------------------------------------------------------------------

def vary_key_problem(key: str) -> str:
    """Why ``key`` cannot vary, in words, naming the keys that can (``--vary``'s and the search's message).

    A key of a design file's table (``bearing.surface.radius_m``, ``superstructure.…``) was told "is not a number of
    a design file that can vary" with the whole list, as a typo was (session 21 sweep): the search varies the
    design file's top-level numbers only; each candidate keeps the file's [bearing] surfaces and tables.
    """
    table = key.split(".", 1)[0].strip().lower()
    can_vary = f"Keys that can vary: {', '.join(VARY_KEYS)}"
    if table in ("bearing", "surface"):
        from isolator.bearing import REPLACED_DESIGN_KEYS

        kept = ", ".join(k for k in VARY_KEYS if k not in REPLACED_DESIGN_KEYS)
        return (f"{key!r} cannot vary: the search varies a design file's top-level numbers, never its [bearing] keys "
                "(its [[bearing.surface]] entries): every candidate keeps the file's surfaces (to compare other "
                f"surfaces, write a design file per geometry). {can_vary}; of these a design with [bearing] keeps "
                f"{kept}")
    if table in ("superstructure", "plan", "bearing_position", "floor"):
        return (f"{key!r} cannot vary: the search varies a design file's top-level numbers, never its [{table}] "
                f"keys: every candidate keeps the file's tables. {can_vary}")
    if key.strip().lower() in ("name", "description"):
        return f"{key!r} is text, not a number: the search names each candidate by its values. {can_vary}"
    return f"{key!r} is not a number of a design file that can vary{key_hint(key, VARY_KEYS, 'one of')}"


def parse_vary(spec: str) -> tuple[str, list[float]]:
    """``KEY=START:STOP:COUNT`` (COUNT values, both ends included) or ``KEY=V1,V2,…`` → (key, values).

    Parameters
    ----------
    spec : str
        e.g. ``"radius_m=1.5:4.5:13"`` or ``"mu_kinetic=0.04,0.06"`` [-].

    Raises
    ------
    ReviewError
        Unknown key, unparsable or non-finite numbers, COUNT < 1, COUNT = 1 with START ≠ STOP, repeated values.
    """
    def fail(message: str):
        return ReviewError(f"{spec!r}: {message}", parameter="vary")

    if "=" not in spec:
        raise fail("expected KEY=START:STOP:COUNT or KEY=V1,V2,…, e.g. radius_m=1.5:4.5:13")
    key, _, text = (part.strip() for part in spec.partition("="))
    if key not in VARY_KEYS:
        raise fail(vary_key_problem(key))
    if ":" in text:
        parts = text.split(":")
        if len(parts) != 3:
            raise fail(f"expected {key}=START:STOP:COUNT")
        try:
            start, stop = float(parts[0]), float(parts[1])
        except ValueError:
            raise fail("START and STOP must be numbers") from None
        try:
            count = int(parts[2])
        except ValueError:
            raise fail(f"COUNT must be a whole number, got {parts[2]!r}") from None
        if not (math.isfinite(start) and math.isfinite(stop)):
            raise fail("START and STOP must be finite")
        if count < 1:
            raise fail(f"COUNT must be >= 1, got {count}")
        if count == 1 and start != stop:
            raise fail("COUNT = 1 needs START = STOP")
        if count > MAX_CANDIDATES:
            raise fail(f"COUNT = {count} exceeds {MAX_CANDIDATES} candidates")
        values = [float(v) for v in np.linspace(start, stop, count)]
        if len(set(values)) != len(values):
            raise fail("START = STOP with COUNT > 1 gives the same value twice")
        return key, values
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise fail("the list must hold numbers separated by commas") from None
    if not values or not all(math.isfinite(v) for v in values):
        raise fail("the values must be finite numbers")
    if len(set(values)) != len(values):
        raise fail("a value is repeated")
    return key, values


def candidate_mappings(base: dict, base_mu_kinetic: float, vary: list[tuple[str, list[float]]]) -> list[dict]:
    """The design mappings of the product of the ranges (first key slowest), in order.

    Parameters
    ----------
    base : dict
        The design file's content (its TOML table).
    base_mu_kinetic : float
        µk of the design file (µs when the file gives no µk) [-].
    vary : list of (key, values)
        The ranges, as :func:`parse_vary` returns them.

    Raises
    ------
    ReviewError
        A key varied twice, a key the design's form excludes (``radius_m`` of a spring design …),
        or more than :data:`MAX_CANDIDATES` candidates.
    """
    keys = [key for key, _ in vary]
    if not keys:
        raise ReviewError("nothing varies: give at least one range", parameter="vary")
    if len(set(keys)) != len(keys):
        twice = next(k for k in keys if keys.count(k) > 1)
        raise ReviewError(f"{twice!r} is varied twice", parameter="vary")
    exclusive = (("radius_m", "stiffness_N_per_m"), ("damping_ratio", "damping_Ns_per_m"))
    for a, b in exclusive:
        for key, other in ((a, b), (b, a)):
            if key in keys and other in base:
                raise ReviewError(f"{key!r} cannot vary: the design gives {other!r} (one or the other)",
                                        parameter="vary")
    n = math.prod(len(values) for _, values in vary)
    if n > MAX_CANDIDATES:
        raise ReviewError(f"{n} candidates exceed {MAX_CANDIDATES}: split the search", parameter="vary")
    out = []
    for combination in itertools.product(*(values for _, values in vary)):
        mapping = dict(base)
        chosen = dict(zip(keys, combination, strict=True))
        if "mu_kinetic" in chosen and base_mu_kinetic > 0:
            ratio = chosen["mu_kinetic"] / base_mu_kinetic
            for follower in FRICTION_FOLLOWERS:
                if follower in base and follower not in chosen:
                    mapping[follower] = base[follower] * ratio
        mapping.update(chosen)
        out.append(mapping)
    return out


def candidate_name(base: dict, mapping: dict, values: dict) -> str:
    """The name of a candidate: "[radius_m=4.5, mu_kinetic=0.09, mu_static=0.105] varied from the base design: NAME".

    The varied values and every friction coefficient that followed µk (:data:`FRICTION_FOLLOWERS`) come first: the
    base name ("FPS R = 4.0 m, mu_s = 0.07 …") says the base's numbers, which were printed as the candidate's on
    every page of the recommended review (h227's audit).  Not an identifier: candidates are keyed by their content.
    """
    followed = {k: mapping[k] for k in FRICTION_FOLLOWERS
                if k not in values and k in mapping and mapping[k] != base.get(k)}
    said = ", ".join(f"{k}={v:.6g}" for k, v in {**values, **followed}.items())
    return f"[{said}]{CANDIDATE_WORDS}{base['name']}"


@dataclass
class Candidate:
    """One point of the design space: its index, the varied values and the design mapping."""

    index: int
    values: dict  #: varied key → value
    mapping: dict  #: the complete design table
    key: str = ""  #: content key of the row (inputs and code version)
    group: str = ""  #: candidates of one group share every analysis



# ---- the recommendation ---------------------------------------------------------------------

def recommend(rows: list[dict], objective: str) -> dict | None:
    """The passing row with the smallest objective column (ties: the other objectives, then candidate order).

    Raises
    ------
    ReviewError
        An unknown objective.
    """
    if objective not in OBJECTIVES:
        raise ReviewError(f"objective {objective!r}: choose one of {', '.join(OBJECTIVES)}",
                                parameter="objective")
    order = [OBJECTIVES[objective][0], *(c for name, (c, _) in OBJECTIVES.items() if name != objective)]

    def value(row, column):
        v = row.get(column)
        return v if isinstance(v, (int, float)) and math.isfinite(v) else math.inf

    passing = [r for r in rows if r.get("passes") and r.get("error") is None
               and math.isfinite(value(r, order[0]))]
    if not passing:
        return None
    return min(passing, key=lambda r: (*(value(r, c) for c in order), r["candidate"]))
