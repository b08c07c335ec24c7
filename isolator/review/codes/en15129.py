r"""EN 15129 / EN 1998-1 §10 / EN 1998-2 §7: the clauses where they differ from ASCE 7 (REVIEW_RULES §2, all [U]).

* Reliability factor on displacements: each isolator is designed for γ_x · d (EN 1998-1 10.3(2)).
* Restoring capability (EN 1998-2 7.7.1, EN 15129): d_Ed / d_r ≥ δ with d_r = F₀/K_r, which for a
  curved-surface slider (F₀ = µN, K_r = N/R) is d_r = µR.
* Records: the mean 5 %-damped spectrum of the *components* ≥ 90 % of the elastic spectrum over
  0.2 T – 2 T (no maximum-direction spectrum), T the effective isolated period.
* Bounds: the plain product of the λ factors (:func:`isolator.review.bounds.combine_lambda`).
* Torsion: each isolator's displacement d_bi,d (EN 1998-1 10.3(2), "torsion included") is the centre of mass's
  times δ_i = 1 + e_tot y_i / r² (EN 1998-1 10.9.6, the simplified analysis's torsion amplification [U]: not
  quoted in REVIEW_RULES §2), e_tot the actual eccentricity plus the accidental 0.05 L (EN 1998-1 4.3.2(1),
  parameter ``en_accidental_e`` [U]).  No floor on it: ASCE 7's 1.15 D_M of Eq. 17.5-3 and its P_T ≥ 1 are not
  EN rules (:func:`torsion_factors`).
"""

from __future__ import annotations

import math

import numpy as np

CLAUSE = {"gamma_x": "EN 1998-1 10.3(2)", "restoring": "EN 1998-2 7.7.1 / EN 15129",
          "records": "EN 1998-1 3.2.3.1.2(4)", "mean": "EN 1998-1 4.3.3.4.3(3)",
          "torsion": "EN 1998-1 10.9.6 [U]", "accidental": "EN 1998-1 4.3.2(1) [U]"}


def torsion_amplification(distance_m: float, eccentricity_m: float, r_squared_m2: float) -> float:
    """δ = 1 + e_tot · y / r² (EN 1998-1 10.9.6 [U]) [-].

    Parameters
    ----------
    distance_m : float
        The isolator's distance from the centre of stiffness, perpendicular to the loading [m].
    eccentricity_m : float
        e_tot, actual + accidental eccentricity [m].
    r_squared_m2 : float
        r², the isolation system's torsional radius squared [m²] (> 0): Σ(x_i² + y_i²)/N for identical isolators.
    """
    return 1.0 + eccentricity_m * distance_m / r_squared_m2


def torsion_factors(plan: dict | None, accidental_e: float, x_m=None, y_m=None) -> dict:
    """Each isolator's displacement / the centre of mass's, EN 1998-1 10.9.6 [U], the larger of the two loading
    directions; no floor.

    Loading along x: distance |y_i|, e_tot = ``eccentricity_m`` + ``accidental_e`` × d (the plan dimension along y);
    along y: |x_i| and ``accidental_e`` × b.  r² = Σ(x_i² + y_i²)/N of the bearing layout (identical isolators);
    without one, r² = P_T² (b² + d²)/12 with the plan's ``P_T`` (the same ratio of torsional to translational
    stiffness radius), else (b² + d²)/12 — the isolators spread like the mass (assumed) — and the distance the plan's
    ``y_m``, else half the plan dimension (a corner isolator, assumed).

    Parameters
    ----------
    plan : dict or None
        The design's ``[plan]`` (``b_m``, ``d_m``, ``eccentricity_m``, ``y_m``, ``P_T``).
    accidental_e : float
        Accidental eccentricity / the plan dimension ⟂ the loading (``en_accidental_e``) [-].
    x_m, y_m : sequence of float, optional
        The bearing layout's positions from the centre of the plan [m].

    Returns
    -------
    dict
        ``factor`` (the largest δ) [-], ``bearing_factors`` (one per bearing, with a layout) [-], ``r_m`` [m],
        ``basis`` (one sentence), ``assumed`` (True when r or y was not given).  Without a plan: factor 1 (no
        torsion can be computed), ``assumed`` True, and the basis says so.
    """
    if plan is None:
        return {"factor": 1.0, "basis": "no [plan] in the design: no torsion amplification computed (δ = 1; "
                                        f"{CLAUSE['torsion']} needs the plan and eccentricity)", "assumed": True,
                "code": "en15129"}
    b, d = float(plan["b_m"]), float(plan["d_m"])
    e0 = float(plan.get("eccentricity_m", 0.0))
    e_x, e_y = e0 + accidental_e * d, e0 + accidental_e * b  # loading x: e along y (⟂ x), and conversely
    out = {"code": "en15129", "e_x_m": e_x, "e_y_m": e_y}
    if x_m is not None and len(x_m) > 0:
        x, y = np.abs(np.asarray(x_m, dtype=np.float64)), np.abs(np.asarray(y_m, dtype=np.float64))
        r2 = float(np.mean(x * x + y * y))
        if not r2 > 0:
            raise ValueError("the bearing layout has every bearing at the centre: no torsional radius")
        factors = [max(torsion_amplification(yi, e_x, r2), torsion_amplification(xi, e_y, r2))
                   for xi, yi in zip(x, y, strict=True)]
        k = int(np.argmax(factors))
        out.update(factor=factors[k], bearing_factors=factors, r_m=math.sqrt(r2), assumed=False,
                   basis=f"δ_i = 1 + e_tot y_i / r² ({CLAUSE['torsion']}) at each of the {len(factors)} bearings, "
                         f"r = {math.sqrt(r2):.4g} m from the bearing layout, e_tot = {e0:g} + {accidental_e:g} L = "
                         f"{e_x:.4g} m (loading x) / {e_y:.4g} m (loading y) ({CLAUSE['accidental']}); largest "
                         f"{factors[k]:.4g} at ({x_m[k]:g}, {y_m[k]:g}) m; no floor")
        return out
    p_t = plan.get("P_T")
    r2 = (1.0 if p_t is None else float(p_t) ** 2) * (b * b + d * d) / 12.0
    dist = {"x": plan.get("y_m", 0.5 * d), "y": plan.get("y_m", 0.5 * b)}
    factor = max(torsion_amplification(dist["x"], e_x, r2), torsion_amplification(dist["y"], e_y, r2))
    out.update(factor=factor, r_m=math.sqrt(r2), assumed=p_t is None or "y_m" not in plan,
               basis=f"δ = 1 + e_tot y / r² ({CLAUSE['torsion']}), r = {math.sqrt(r2):.4g} m "
                     + ("(√((b² + d²)/12): the isolators spread like the mass, assumed)" if p_t is None else
                        f"(P_T = {float(p_t):g} × √((b² + d²)/12), the plan's P_T)")
                     + (f", y = {plan['y_m']:g} m (given)" if "y_m" in plan else
                        ", y = half the plan dimension (a corner isolator, assumed)")
                     + f", e_tot = {e0:g} + {accidental_e:g} L = {e_x:.4g} m (loading x) / {e_y:.4g} m (loading y) "
                       f"({CLAUSE['accidental']}); no floor")
    return out


def static_residual_m(design, mu: float) -> float:
    """d_r = F₀/K_r [m]: µR for a friction pendulum, µ W / K for a spring (∞ without restoring stiffness)."""
    if design.stiffness_N_per_m == 0.0:
        return math.inf
    return mu * design.weight_N / design.stiffness_N_per_m


def restoring_capability_ratio(design, mu: float, displacement_m: float) -> float:
    """d_Ed / d_r [-] (EN 1998-2 7.7.1): ≥ δ is required."""
    d_r = static_residual_m(design, mu)
    return 0.0 if math.isinf(d_r) else displacement_m / d_r


def damping_divisor(beta: float, eta_min: float = 0.55) -> float:
    """1/η with η = sqrt(10/(5 + ξ)) ≥ η_min, ξ in % (EN 1998-1 3.2.2.2(3); η_min 0.55 [U], the review parameter
    ``eta_min``) [-]: divides the 5 % spectrum."""
    eta = max(math.sqrt(0.10 / (0.05 + max(beta, 0.0))), eta_min)
    return 1.0 / eta
