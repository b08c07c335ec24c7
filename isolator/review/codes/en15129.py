r"""EN 15129 / EN 1998-1 §10 / EN 1998-2 §7: the clauses where they differ from ASCE 7 (REVIEW_RULES §2, all [U]).

* Reliability factor on displacements: each isolator is designed for γ_x · d (EN 1998-1 10.3(2)).
* Restoring capability (EN 1998-2 7.7.1, EN 15129): d_Ed / d_r ≥ δ with d_r = F₀/K_r, which for a
  curved-surface slider (F₀ = µN, K_r = N/R) is d_r = µR.
* Records: the mean 5 %-damped spectrum of the *components* ≥ 90 % of the elastic spectrum over
  0.2 T – 2 T (no maximum-direction spectrum), T the effective isolated period.
* Bounds: the plain product of the λ factors (:func:`isolator.review.bounds.combine_lambda`).
"""

from __future__ import annotations

import math

CLAUSE = {"gamma_x": "EN 1998-1 10.3(2)", "restoring": "EN 1998-2 7.7.1 / EN 15129",
          "records": "EN 1998-1 3.2.3.1.2(4)", "mean": "EN 1998-1 4.3.3.4.3(3)"}


def static_residual_m(design, mu: float) -> float:
    """d_r = F₀/K_r [m]: µR for a friction pendulum, µ W / K for a spring (∞ without restoring stiffness)."""
    if design.stiffness_N_per_m == 0.0:
        return math.inf
    return mu * design.weight_N / design.stiffness_N_per_m


def restoring_capability_ratio(design, mu: float, displacement_m: float) -> float:
    """d_Ed / d_r [-] (EN 1998-2 7.7.1): ≥ δ is required."""
    d_r = static_residual_m(design, mu)
    return 0.0 if math.isinf(d_r) else displacement_m / d_r


def damping_divisor(beta: float) -> float:
    """1/η with η = sqrt(10/(5 + ξ)) ≥ 0.55, ξ in % (EN 1998-1 3.2.2.2(3)) [-]: divides the 5 % spectrum."""
    eta = max(math.sqrt(0.10 / (0.05 + max(beta, 0.0))), 0.55)
    return 1.0 / eta
