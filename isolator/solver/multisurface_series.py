r"""The series model of a multi-surface friction pendulum: elements, rims, one excursion.

A bearing with n concave surfaces and massless sliders is modelled, after Fenz &
Constantinou (2008), as n rigid–plastic elements with linear (kinematic) hardening in
series, all carrying the one horizontal force F.  Element i has a radius
:math:`\bar R_i` [m], a friction coefficient :math:`\mu_i` [-] and a rim
:math:`\bar c_i` [m] on its displacement :math:`\bar u_i`; in units of the weight,
r = F/W:

.. math::

    \text{sliding } (s = \pm 1):\quad r = \bar u_i/\bar R_i + s\,\mu_i, \qquad
    \text{stuck:}\quad |r - \bar u_i/\bar R_i| \le \mu_i, \qquad |\bar u_i| \le \bar c_i .

An element at its rim holds any force that pushes it outward (rigid rim) and leaves it
when the force falls to the opposite friction level.  The bearing's displacement is
:math:`x = \sum_i \bar u_i`.

Why a whole excursion is known in advance.  While the mass moves one way (s fixed,
between two stops) the force only grows in that direction: an element joins the
sliding set when r reaches its friction level :math:`y_i = \bar u_i/\bar R_i + s\mu_i`
and leaves it when it reaches its rim, at :math:`z_i = \bar c_i/\bar R_i + s\mu_i`.
So along the excursion r(x) is a known piecewise-linear function: a list of regimes,
each with its start (x_k, r_k) and its compliance :math:`\sum_{\text{sliding}} \bar R_i`
(:func:`excursion`).  A regime with zero compliance is rigid: every element that has
slid is at its rim.  Before the last regime (an *intermediate* rim: the next element's
friction level lies above the rim level, e.g. a double with µ2 > µ1 + d1*/R̄1) it has
zero length in x: the next element is rigid–plastic, so a mass arriving moving goes on
with the force jumped to that level and its velocity continuous (no impulse; massless
sliders).  The last one of an excursion, when every element is at its rim, is the
bearing's ultimate displacement: a *plastic impact* when the mass reaches it moving.  Between breakpoints the mass obeys a linear equation, so the solver
uses the same closed forms as the single pendulum (:mod:`isolator.solver.segments`).

The elements of each bearing type (:func:`series_elements`):

* single: one element, :math:`\bar R = R_{eff}`, rim :math:`d^*`;
* double: two elements in series, :math:`\bar R_i = R_{eff,i}`, rims :math:`d_i^*`;
* triple (Fenz & Constantinou 2008, Earthquake Spectra 24(4), the series model): the
  inner slide plates rotate, so the outer elements are
  :math:`\bar R_1 = R_{eff,1} - R_{eff,2}`, :math:`\bar R_4 = R_{eff,4} - R_{eff,3}`,
  the inner ones :math:`\bar R_{2,3} = R_{eff,2,3}`, and the displacement on each real
  surface is (:func:`surface_matrix`)
  :math:`u_1 = \bar u_1 R_{eff,1}/\bar R_1`, :math:`u_2 = \bar u_2 - \bar u_1 R_{eff,2}/\bar R_1`
  (and the mirror for 3, 4).  Real surface 2 therefore moves only while element 2
  slides and element 1 does not (regimes I, IV, V): it stops when surface 1 starts, as
  in their theory.  Its rim :math:`|u_2| = d_2^*` can only be reached while element 1
  rests on its rim (when :math:`d_2^* \ge (\mu_1 - \mu_2) R_{eff,2}`, which the design
  checks), so it is the fixed rim :math:`\bar c_2 = d_2^* + d_1^* R_{eff,2}/R_{eff,1}` on
  :math:`\bar u_2`; the outer rims are :math:`\bar c_1 = d_1^* \bar R_1/R_{eff,1}`.
  The ultimate displacement is :math:`\sum \bar c_i = \sum d_i^*`.

All functions are compiled (numba) and take plain arrays.

References
----------
D. M. Fenz, M. C. Constantinou (2008), Spherical sliding isolation bearings with adaptive
behavior: Theory, Earthquake Engng Struct. Dyn. 37, 163–183 (regimes I–V).
D. M. Fenz, M. C. Constantinou (2008), Modeling triple friction pendulum bearings for
response-history analysis, Earthquake Spectra 24(4), 1011–1028 (the series model).
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.jit import njit

#: Two friction or rim levels closer than this (in F/W) are one event: the elements start
#: or stop together (equal inner surfaces), without a spurious regime of rounding length.
LEVEL_TIE = 1e-13

#: Why static friction above kinetic is refused on a double or triple bearing (one clause): the
#: excursion below assumes that the force only grows while the mass moves one way.
STATIC_FRICTION_REASON = (
    "its sliders are massless, so the drop from static to kinetic friction when this surface breaks away is "
    "an instant drop of the one force through the bearing, below the level at which the other surfaces were "
    "sliding: they stop (or slide back), must break away again, and the force is no longer a known function of "
    "the displacement along an excursion, which the exact series solution needs (the answer would depend on "
    "the slider masses the model leaves out)")

#: Why µ falling with speed (mu_slow > mu_fast) is refused on a double or triple (one clause).
DECREASING_RATE_REASON = (
    "with µ falling with speed the slide rate of a surface is not a function of the force through it (at one "
    "force it may slide fast or stay stuck), so the split of the bearing's velocity between surfaces in series "
    "is not unique (two equal surfaces can share it or one can take it all) and would depend on the slider "
    "masses the model leaves out")

#: Largest number of regimes in one excursion: each element starts once and stops once.
def max_regimes(n_elements: int) -> int:
    """Room for the regimes of one excursion of ``n_elements`` elements (2n + 1)."""
    return 2 * n_elements + 1


def series_elements(kind: str, effective_radius_m, mu, effective_capacity_m):
    """The series elements of a bearing: (R̄ [m], µ [-], rim c̄ [m]) arrays.

    Parameters
    ----------
    kind : {"single", "double", "triple"}
        The bearing type.
    effective_radius_m, mu, effective_capacity_m : sequence of float
        Per real surface, in file order (1, 2, 3, 4 of Fenz & Constantinou): R_eff,i,
        µ_i and d_i* (``inf`` for no rim).

    Returns
    -------
    tuple of numpy.ndarray
        ``(rbar_m, mu, rim_m)``, one entry per element (element i ↔ surface i).
    """
    r_eff = np.asarray(effective_radius_m, dtype=np.float64)
    mu = np.asarray(mu, dtype=np.float64).copy()
    d = np.asarray(effective_capacity_m, dtype=np.float64)
    if kind in ("single", "double"):
        return r_eff.copy(), mu, d.copy()
    if kind != "triple":
        raise ValueError(f"unknown bearing type {kind!r}")
    r1, r2, r3, r4 = r_eff
    rbar = np.array([r1 - r2, r2, r3, r4 - r3])
    rim = np.array([d[0] * (r1 - r2) / r1, d[1] + d[0] * r2 / r1,
                    d[2] + d[3] * r3 / r4, d[3] * (r4 - r3) / r4])
    return rbar, mu, rim


def surface_matrix(kind: str, effective_radius_m) -> np.ndarray:
    """T with u = T ū: displacement on each real surface (effective geometry) from the elements' [-].

    Parameters
    ----------
    kind : {"single", "double", "triple"}
    effective_radius_m : sequence of float
        R_eff,i per surface [m].
    """
    r_eff = np.asarray(effective_radius_m, dtype=np.float64)
    n = r_eff.size
    if kind != "triple":
        return np.eye(n)
    r1, r2, r3, r4 = r_eff
    t = np.zeros((4, 4))
    t[0, 0] = r1 / (r1 - r2)
    t[1, 1] = 1.0
    t[1, 0] = -r2 / (r1 - r2)
    t[2, 2] = 1.0
    t[2, 3] = -r3 / (r4 - r3)
    t[3, 3] = r4 / (r4 - r3)
    return t


@njit(cache=True)
def stick_window(u, rbar, mu, rim):
    """The range of F/W the stuck bearing holds: (r_lo, r_hi) [-].

    Each element holds ``ū/R̄ − µ ≤ r ≤ ū/R̄ + µ``; an element on its rim holds any
    force pushing it outward (that side is infinite).

    Parameters
    ----------
    u, rbar, mu, rim : float64[n]
        Element displacements [m], radii [m], friction [-] and rims [m].
    """
    lo = -math.inf
    hi = math.inf
    for i in range(u.shape[0]):
        centre = u[i] / rbar[i]
        if u[i] < rim[i]:
            hi = min(hi, centre + mu[i])
        if u[i] > -rim[i]:
            lo = max(lo, centre - mu[i])
    return lo, hi


@njit(cache=True)
def excursion(s, u, rbar, mu, rim, x0, reg_x, reg_r, reg_rsum, reg_mask):
    """The piecewise-linear force of one excursion in direction s, regime by regime.

    Parameters
    ----------
    s : float
        +1 (x increasing) or −1.
    u, rbar, mu, rim : float64[n]
        Element state and properties (see :func:`stick_window`).
    x0 : float
        Bearing displacement at the start, Σ ū [m].
    reg_x, reg_r, reg_rsum : float64[2n+1]
        Filled with each regime's start displacement [m], its start force r = F/W [-]
        and its compliance Σ R̄ of the sliding elements [m] (0: rigid).
    reg_mask : int64[2n+1]
        Filled with the sliding elements of each regime (bit i = element i).

    Returns
    -------
    int
        The number of regimes.  Regime k spans x from ``reg_x[k]`` to ``reg_x[k+1]``
        (the last one to ±inf when its compliance is > 0).  A last regime of zero
        compliance is the ultimate displacement (every element on its rim in
        direction s); a rigid regime before the last is an intermediate rim.
    """
    n = u.shape[0]
    # mirror to s = +1: positions s·ū, levels s·r; element sets as bit masks (no allocation:
    # this runs at every reversal of the record loop)
    started = 0
    active = 0
    rimmed = 0
    for i in range(n):
        if s * u[i] >= rim[i]:
            rimmed |= 1 << i
    r = math.inf
    for i in range(n):
        if not rimmed >> i & 1:
            r = min(r, s * u[i] / rbar[i] + mu[i])
    x = s * x0
    if r == math.inf:
        # every element on its rim: rigid from the start
        r_hold = -math.inf
        for i in range(n):
            r_hold = max(r_hold, rim[i] / rbar[i] + mu[i])
        reg_x[0] = s * x
        reg_r[0] = s * r_hold
        reg_rsum[0] = 0.0
        reg_mask[0] = 0
        return 1
    n_reg = 0
    for _ in range(2 * n + 1):
        # elements that start or reach the rim at level r
        for i in range(n):
            bit = 1 << i
            if not (rimmed | started) & bit and s * u[i] / rbar[i] + mu[i] <= r + LEVEL_TIE:
                started |= bit
                active |= bit
            if active & bit and rim[i] / rbar[i] + mu[i] <= r + LEVEL_TIE:
                active &= ~bit
                rimmed |= bit
        rsum = 0.0
        for i in range(n):
            if active >> i & 1:
                rsum += rbar[i]
        reg_x[n_reg] = s * x
        reg_r[n_reg] = s * r
        reg_rsum[n_reg] = rsum
        reg_mask[n_reg] = active
        n_reg += 1
        # next level: an element starts or an active one reaches its rim
        r_next = math.inf
        for i in range(n):
            bit = 1 << i
            if not (rimmed | started) & bit:
                r_next = min(r_next, s * u[i] / rbar[i] + mu[i])
            if active & bit:
                r_next = min(r_next, rim[i] / rbar[i] + mu[i])
        if r_next == math.inf:
            if rsum == 0.0 and rimmed == (1 << n) - 1:
                # the ultimate displacement: every element on its rim, x = s Σ c̄ exactly (not the
                # rounded sum of the regimes' travels), so a peak there equals the capacity
                total = 0.0
                for i in range(n):
                    total += rim[i]
                reg_x[n_reg - 1] = s * total
            return n_reg  # open (no rim ahead) or the ultimate displacement (rigid)
        x = x + rsum * (r_next - r)
        r = r_next
    return n_reg


@njit(cache=True)
def settle(s, u, rbar, mu, rim, r_end):
    """Move the elements to the end of an excursion in direction s at force r_end = F/W (in place).

    Every element whose friction level lies below ``s·r_end`` has slid to
    ``ū = R̄ (r_end − s µ)``, or to its rim if that is closer.
    """
    for i in range(u.shape[0]):
        target = s * r_end - mu[i]  # s·ū/R̄ of an element sliding at this force
        if s * u[i] / rbar[i] < target:
            ui = rbar[i] * target
            if ui >= rim[i] - rbar[i] * LEVEL_TIE:
                ui = rim[i]  # on the rim (a level within the tie of the rim level is the rim)
            if ui > s * u[i]:
                u[i] = s * ui


@njit(cache=True)
def regime_force(k, x, reg_x, reg_r, reg_rsum):
    """F/W [-] at displacement x [m] inside regime k of an excursion."""
    if reg_rsum[k] == 0.0:
        return reg_r[k]
    return reg_r[k] + (x - reg_x[k]) / reg_rsum[k]
