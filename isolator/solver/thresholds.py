"""Regime thresholds of the harmonic response along α, and the one bisection they use.

:func:`bisect_change` is the bisection of every regime boundary in isolator (the α
scan of :func:`harmonic_thresholds`, the refined regime maps and the triple point of
:mod:`isolator.maps`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from isolator.errors import InvalidSystemError
from isolator.solver.harmonic import (
    MAX_DIMENSIONLESS,
    MAX_PERIODS_DEFAULT,
    harmonic_response,
    validate_harmonic_parameters,
)

#: Largest grid of an α scan (each point a harmonic response, ~0.5 ms: about 10 s).
MAX_THRESHOLD_GRID = 20_000
#: bound on the halvings of one bisection (2⁻²⁰⁰ is far below any float spacing)
MAX_BISECTIONS = 200


def bisect_change(on_low_side: Callable[[float], bool], lo: float, hi: float, *, rel_tol: float | None = None,
                  iterations: int | None = None) -> tuple[float, float]:
    """Shrink [lo, hi] around the point where ``on_low_side`` turns from True to False.

    Parameters
    ----------
    on_low_side : callable
        ``on_low_side(x)`` is True on the side of ``lo`` (same regime as ``lo``, or a
        negative excess) [-].
    lo, hi : float
        A bracket: ``on_low_side(lo)`` True, ``on_low_side(hi)`` False [-].
    rel_tol : float, optional
        Stop when ``hi - lo <= rel_tol * hi``.
    iterations : int, optional
        Halve exactly this many times instead (the error is (hi - lo) / 2^iterations).

    Returns
    -------
    (float, float)
        The final bracket; its midpoint is the estimate.  At most
        :data:`MAX_BISECTIONS` halvings whatever the tolerance.
    """
    if rel_tol is None and iterations is None:
        raise ValueError("give rel_tol or iterations")
    count = 0
    limit = MAX_BISECTIONS if iterations is None else min(int(iterations), MAX_BISECTIONS)
    while count < limit and (iterations is not None or hi - lo > rel_tol * hi):
        mid = 0.5 * (lo + hi)
        if on_low_side(mid):
            lo = mid
        else:
            hi = mid
        count += 1
    return lo, hi


@dataclass
class RegimeThresholds:
    """Regime transitions of the harmonic response along α at fixed (k, η, µs, µk).

    ``alpha_ss`` = 1 (the block cannot move for α ≤ 1, whatever k and η);
    ``alpha_sl`` is the lowest α above which the motion stays permanent slip up to
    ``alpha_max`` (``None`` if it is not SL at ``alpha_max``); ``transitions`` lists
    every change of regime found, in order, so an SS/SL/SS/SL sequence (Fig. 5a,
    4.1 < k < 5.3) shows as three transitions above α = 1.
    """

    k: float
    eta: float
    mu_s: float
    mu_k: float
    alpha_max: float
    alpha_ss: float
    alpha_sl: float | None
    transitions: list

    def summary(self) -> dict:
        return {"alpha_ss": self.alpha_ss, "alpha_sl": self.alpha_sl, "transitions": self.transitions,
                "k": self.k, "eta": self.eta, "mu_s": self.mu_s, "mu_k": self.mu_k,
                "alpha_max": self.alpha_max}


def harmonic_regime(alpha: float, k: float, eta: float, mu_s: float, mu_k: float | None = None,
                    max_periods: int = MAX_PERIODS_DEFAULT) -> str:
    """Regime (ST, SS or SL) of the steady harmonic response; see :func:`harmonic_response`."""
    if alpha <= 1.0:
        return "ST"  # |ω² cos| ≤ µs: the block never breaks away
    return harmonic_response(alpha, k, eta, mu_s, mu_k, max_periods=max_periods, samples_per_period=2).regime


def harmonic_thresholds(k: float, eta: float, mu_s: float, mu_k: float | None = None, *,
                        alpha_max: float = 6.0, n_grid: int = 120,
                        rel_tol: float = 1e-9) -> RegimeThresholds:
    """Every regime transition in α ∈ (1, alpha_max] at fixed k, η, µs, µk.

    Scans a grid of ``n_grid`` values of α, plus the values where the natural
    frequency is a multiple or a fraction of the forcing one (where the narrow
    SS windows of Fig. 5a open), then bisects every change of regime between
    neighbours to ``rel_tol``.  A window narrower than the grid step elsewhere can
    be missed; raise ``n_grid`` to look closer.

    Parameters
    ----------
    k, eta : float
        Dimensionless stiffness and damping (Eq. 6).
    mu_s, mu_k : float
        Friction coefficients; µk defaults to µs.
    alpha_max : float
        Upper end of the scan [-].
    n_grid : int
        Grid points on (1, alpha_max].
    rel_tol : float
        Relative accuracy of each transition in α.

    Returns
    -------
    RegimeThresholds
    """
    mu_k = mu_s if mu_k is None else mu_k
    if not alpha_max > 1.0:
        raise InvalidSystemError(f"alpha_max must be > 1, got {alpha_max!r}")
    if not alpha_max <= MAX_DIMENSIONLESS:
        raise InvalidSystemError(f"alpha_max = {alpha_max:g} exceeds {MAX_DIMENSIONLESS:g} (the largest α the "
                                 "harmonic solver accepts)")
    if not 4 <= n_grid <= MAX_THRESHOLD_GRID:
        raise InvalidSystemError(f"the α grid must have 4 to {MAX_THRESHOLD_GRID} points (each is a harmonic "
                                 f"response, ~0.5 ms), got {n_grid}")
    validate_harmonic_parameters(1.0, float(k), float(eta), float(mu_s), float(mu_k))
    # the first grid point sits just above 1 so that the ST → moving step is at α_SS = 1;
    # narrow windows open at the sub- and super-harmonic resonances √k = n ω and
    # ω = n √k (ω² = α µs), so those values of α join the grid
    resonant = [k * n * n / mu_s for n in range(1, 7)] + [k / (n * n * mu_s) for n in range(2, 7)]
    resonant = [a for a in resonant if 1.0 < a < alpha_max]
    alphas = np.unique(np.concatenate(([1.0 + 1e-6], np.linspace(1.0, alpha_max, n_grid + 1)[1:], resonant)))
    regimes = [harmonic_regime(a, k, eta, mu_s, mu_k) for a in alphas]
    transitions = [{"alpha": 1.0, "from": "ST", "to": regimes[0]}]
    for a_lo, a_hi, r_lo, r_hi in zip(alphas[:-1], alphas[1:], regimes[:-1], regimes[1:], strict=True):
        if r_lo == r_hi:
            continue
        lo, hi = bisect_change(lambda a, r_lo=r_lo: harmonic_regime(a, k, eta, mu_s, mu_k) == r_lo, a_lo, a_hi,
                               rel_tol=rel_tol)
        transitions.append({"alpha": 0.5 * (lo + hi), "from": r_lo, "to": r_hi})
    alpha_sl = None
    if regimes[-1] == "SL":
        alpha_sl = 1.0
        for tr in transitions:
            if tr["to"] == "SL":
                alpha_sl = tr["alpha"]
    return RegimeThresholds(k=float(k), eta=float(eta), mu_s=float(mu_s), mu_k=float(mu_k),
                            alpha_max=float(alpha_max), alpha_ss=1.0, alpha_sl=alpha_sl,
                            transitions=transitions)


