r"""The compiled record loop of a double or triple friction pendulum with µ(v) on its surfaces (1-D).

Per surface i (physical displacement u_i on the surface, effective geometry; x = Σ u_i),
in units of the weight, the one force r = F/W through the massless sliders obeys

.. math::

    r = b_i(u) + \mu_i(|\dot u_i|)\,\mathrm{sign}(\dot u_i) \quad (\text{sliding}),\qquad
    |r - b_i(u)| \le \mu_{slow,i} \quad (\text{stuck}),\qquad
    \mu_i(v) = \mu_{fast,i} - (\mu_{fast,i} - \mu_{slow,i})\,e^{-a_i v},

with the back-force b = B u of the series model (B = diag(1/R̄) T⁻¹: b_i = u_i/R_eff,i for a single
or double; for a triple b_2 = u_1/R_eff,1 + u_2/R_eff,2 and b_3 = u_3/R_eff,3 + u_4/R_eff,4, the
rotated slide plates of Fenz & Constantinou), and the mass X'' = −g r − c X' − a_g(t).

With µ_i increasing in |v| each sliding surface's slide rate is a monotone function of its
friction excess, v_i = φ_i(r − b_i) = ± ln((µ_fast − µ_slow)/(µ_fast − |r − b_i|))/a_i, so
Σ φ_i(r − b_i) = X' fixes r from the state (an index-1 DAE; :func:`solve_force`).  The force is computed from a *pivot*
surface k (the one farthest into saturation), whose rate is the rest of the velocity and whose friction comes
from the forward law µ_k(v_k): at a·v ≳ 36 µ_fast − µ(v) is below the rounding of r and φ is not resolvable
(the first rim of a µ(v) TFP: one surface left to carry 2.6 m/s, a·v = 53).  With two or more surfaces saturated together
(a·v ≳ 30 on each: NWH360 ×3 at 4.92 s, surfaces 1 and 4 at X' = −3.4 m/s) no φ but one is resolvable: the
velocity is then shared on the set's slow manifold, its back-forces moving together ((B u̇)_ℓ = (B u̇)_k, the
friction of each within (µ_fast − µ_slow) e^(−26) ≈ 5e-12 (µ_fast − µ_slow) of µ_fast; :func:`set_split`, :func:`update_lock`), and
the friction work is taken from the stage derivatives the collocation took (:func:`radau_step`).  The split of
the velocity between sliding surfaces relaxes at the rate φ'_i/R_eff,i = e^{a v}/(a (µ_fast −
µ_slow) R_eff), 10⁵–10⁹ s⁻¹ at real slide speeds: the system is stiff, so it is integrated with the
L-stable 3-stage Radau IIA collocation (order 5), Newton's method on the stage equations with the
analytic Jacobian (simplified: one Jacobian per step, factored once for h and once for h/2; full Newton where that
does not contract, :func:`radau_step`), every step taken twice (h, then two halves) and the difference held below the
tolerance; the halves are kept.  Inside a *mode* (each surface sliding +, sliding −, stuck, or held on
a rim) the right-hand side is analytic (the sliding branches are continued through the onset), and
the mode changes are events located on re-stepped collocation steps (Illinois secant):

* a sliding surface stops (v_i = 0), a stuck one starts (|r − b_i| = µ_slow,i);
* a surface reaches its rim |u_i| = d_i* (the force then jumps so the others take its velocity;
  the slide rates are continuous in r, so the mass does not stop), or leaves it (r − b_i past the
  opposite static level);
* the mass stops (X' = 0 with every sliding surface moving the same way): then it sticks while
  −a_g/g lies in the window [max(b_i − µ_slow,i), min(b_i + µ_slow,i)] (rims make a side infinite),
  which with a piecewise-linear record is linear in time, so the break-away is exact;
* every surface on its rim the way the mass moves: the ultimate displacement, a plastic impact
  (X' → 0; impulse |X'| and energy ½X'² reported), as in :mod:`isolator.solver.multisurface_kernel`.

Energies per unit mass: input −∫a_g X' dt, viscous c∫X'², and the bearing's friction g Σ∫(r − b_i)
dū_i on the series elements ū = T⁻¹u (the accounting of :mod:`isolator.solver.multisurface_kernel`,
whose stored energy is g Σ ū_i²/(2R̄_i)), all by the collocation's own quadrature (order 5), the slide rates
in the friction power being the collocation's stage derivatives A⁻¹Z/h.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.dense import lu_factor, lu_solve, solve_or_refuse
from isolator.solver.events import BREAKAWAY, REVERSAL, STICK, record_event
from isolator.solver.jit import njit
from isolator.solver.multisurface_kernel import (  # noqa: F401 (the summary layout, re-exported)
    S_E_FRICTION,
    S_E_IMPACT,
    S_E_INPUT,
    S_E_VISCOUS,
    S_FIRST_ULTIMATE_T,
    S_IMPULSE,
    S_MAX_IMPACT_V,
    S_N_EVENTS,
    S_N_RIM_CONTACTS,
    S_N_ULTIMATE,
    S_PEAK_A,
    S_PEAK_R,
    S_PEAK_V,
    S_PEAK_X,
    S_SLIP_TIME,
    S_STATUS,
)

REGIME = 3  #: the sliding set changed (a surface started, stopped, reached or left its rim)
RIM_REACHED = 4  #: a surface reached its rim; the others took its velocity (no impact)
ULTIMATE = 5  #: plastic impact at the ultimate displacement (every slider on its rim)
EVENT_NAMES = ("breakaway", "stick", "reversal", "regime", "rim reached", "ultimate")

MAX_EVENTS_PER_INTERVAL = 1000  #: chatter guard
MAX_STEPS_PER_INTERVAL = 200000  #: bound on the steps of one sample interval
LEVEL_TIE = 1e-13  #: friction levels closer than this in F/W start together
#: the default (join, leave) levels of :func:`update_lock`: a sliding surface at a_i s_i v_i ≥ 28 joins the saturated
#: set of :func:`set_split` (its friction µ_fast − δ, δ = (µ_fast − µ_slow) e^-28 ≈ 7e-13 (µ_fast − µ_slow), ~1e3 ulp
#: of r: its φ still resolved to ~1e-3, its rate to ~5e-5 m/s), and leaves it at 26
LOCK_LEVELS = np.array([28.0, 26.0])

STATUS_OK = 0
STATUS_CHATTER = 1
STATUS_EVENTS_TRUNCATED = 2
STATUS_STEP_FAILED = 4  #: the step size fell below 1e-13 of the interval (the run stops there)

# layout of the summary vector: slots 0-15 are the constant-µ kernel's (one layout: the drivers read both through
# isolator.solver.multisurface.response_fields), then this kernel's own
S_N_STEPS = 16  #: accepted collocation steps (each one step of h and two of h/2)
S_FAIL_T = 17  #: time [s] where a step failed (-1: none)
S_N_NEWTON = 18  #: Newton iterations of every collocation step tried (the work, independent of the machine's load)
SUMMARY_SIZE = 19

# Radau IIA, 3 stages (Hairer & Wanner, Solving ODEs II, Table IV.5.6)
_SQ6 = math.sqrt(6.0)
RADAU_C = np.array([(4.0 - _SQ6) / 10.0, (4.0 + _SQ6) / 10.0, 1.0])
RADAU_A = np.array([[(88.0 - 7.0 * _SQ6) / 360.0, (296.0 - 169.0 * _SQ6) / 1800.0, (-2.0 + 3.0 * _SQ6) / 225.0],
                    [(296.0 + 169.0 * _SQ6) / 1800.0, (88.0 + 7.0 * _SQ6) / 360.0, (-2.0 - 3.0 * _SQ6) / 225.0],
                    [(16.0 - _SQ6) / 36.0, (16.0 + _SQ6) / 36.0, 1.0 / 9.0]])
#: A⁻¹: the stage derivatives implied by the stage increments, F_j = Σ_k (A⁻¹)_jk Z_k / h
RADAU_A_INV = np.linalg.inv(RADAU_A)


def _lagrange(tau):
    """ℓ_k(τ), k = 1..3, of the collocation polynomial on the nodes (0, c_1, c_2, c_3 = 1) [-]."""
    nodes = np.concatenate(([0.0], RADAU_C))
    return np.array([np.prod([(tau - nodes[i]) / (nodes[k] - nodes[i]) for i in range(4) if i != k])
                     for k in range(1, 4)])


#: Newton's first guess for the two half steps of :func:`double_step`: the stage increments of the full step's
#: collocation polynomial at the half steps' stages (Z_half,j = Σ_k GUESS[j, k] Z_full,k; the second half
#: relative to the polynomial at h/2).  A better start, the same converged stages.
GUESS_FIRST_HALF = np.array([_lagrange(0.5 * cj) for cj in RADAU_C])
GUESS_SECOND_HALF = np.array([_lagrange(0.5 + 0.5 * cj) - _lagrange(0.5) for cj in RADAU_C])


@njit(cache=True)
def slide_rate(f, s, mu_s, mu_f, a):
    """Slide velocity v [m/s] and dv/df of a surface sliding in direction s at friction excess f = r − b.

    The inverse of µ(v) continued through the onset (v changes sign at s f = µ_slow);
    ±inf where s f ≥ µ_fast (no finite speed gives that friction).
    """
    gap = mu_f - s * f
    if not gap > 0.0:
        return s * math.inf, math.inf
    return s * math.log((mu_f - mu_s) / gap) / a, 1.0 / (a * gap)


@njit(cache=True)
def friction_at_rate(v, s, mu_s, mu_f, a):
    """Friction excess f = r − b [-] and df/dv of a surface sliding in direction s at slide velocity v [m/s].

    The forward law s µ(s v), continued through the onset like :func:`slide_rate`; well conditioned at
    every speed (at a·|v| ≳ 36 it is µ_fast to rounding, where :func:`slide_rate` is not resolvable).
    """
    decay = math.exp(-a * s * v)
    return s * (mu_s - (mu_f - mu_s) * math.expm1(-a * s * v)), a * (mu_f - mu_s) * decay


@njit(cache=True)
def _sliding(md):
    return md == 1 or md == -1


@njit(cache=True)
def set_split(mode, pivot, lock, bmat, gmap):
    """The split of the velocity for a step: the pivot surface (returned) and the map ``gmap`` [n × n+1].

    Row ℓ of ``gmap`` gives the rate of the pivot and of every *locked* surface ℓ (``lock[ℓ] = 1``) as
    v_ℓ = gmap[ℓ, 0] X' + Σ_{i∈U} gmap[ℓ, 1+i] v_i, U the other sliding surfaces (v_i = φ_i(r − b_i)).
    Without locked surfaces that is the series constraint v_k = X' − Σ_U v_i.  The locked set L (two or more
    sliding surfaces saturated together, :func:`update_lock`, pivot included) shares its velocity so that the
    back-forces of L move together, (B v)_ℓ = (B v)_k for ℓ ∈ L: the slow manifold of
    r = b_ℓ + s_ℓ (µ_fast,ℓ − δ_ℓ) = b_k + s_k (µ_fast,k − δ_k), δ_i = (µ_fast,i − µ_slow,i) e^{−a_i v_i},
    with d(δ_ℓ − δ_k)/dt neglected (docs/multisurface.md: the error is ≤ R̄ max δ on the positions and ≤ max δ
    on the force; δ ≤ (µ_fast − µ_slow) e^{−lock_out}).  An invalid pivot becomes the first sliding surface;
    a locked set that does not contain the pivot, has fewer than two members or a singular system is cleared.
    """
    n = mode.shape[0]
    k = pivot
    if not (0 <= k < n) or not _sliding(mode[k]):
        k = -1
        for i in range(n):
            if _sliding(mode[i]):
                k = i
                break
    members = 0
    for i in range(n):
        if not _sliding(mode[i]):
            lock[i] = 0
        members += lock[i]
        for q in range(n + 1):
            gmap[i, q] = 0.0
    if k < 0:
        for i in range(n):
            lock[i] = 0
        return k
    if lock[k] == 0 or members < 2:
        for i in range(n):
            lock[i] = 0
        members = 0
    if members >= 2:
        # rows: (B_ℓ − B_k)·v = 0 for ℓ ∈ L∖{k}, Σ_L v = X' − Σ_U v_i; unknowns v_L in index order
        idx = np.empty(members, dtype=np.int64)
        m = 0
        for i in range(n):
            if lock[i] == 1:
                idx[m] = i
                m += 1
        mat = np.zeros((members, members))
        right = np.zeros((members, n + 1))
        row = 0
        for ell in idx:
            if ell == k:
                continue
            for col in range(members):
                mat[row, col] = bmat[ell, idx[col]] - bmat[k, idx[col]]
            for i in range(n):
                if _sliding(mode[i]) and lock[i] == 0:
                    right[row, 1 + i] = -(bmat[ell, i] - bmat[k, i])
            row += 1
        for col in range(members):
            mat[members - 1, col] = 1.0
        right[members - 1, 0] = 1.0
        for i in range(n):
            if _sliding(mode[i]) and lock[i] == 0:
                right[members - 1, 1 + i] = -1.0
        scale = 0.0
        for p in range(members):
            for q in range(members):
                scale = max(scale, abs(mat[p, q]))
        if abs(np.linalg.det(mat)) > 1e-12 * scale ** members:
            sol = np.linalg.solve(mat, right)
            ok = True
            for p in range(members):
                for q in range(n + 1):
                    if not math.isfinite(sol[p, q]):
                        ok = False
            if ok:
                for p in range(members):
                    for q in range(n + 1):
                        gmap[idx[p], q] = sol[p, q]
                return k
        for i in range(n):
            lock[i] = 0
    gmap[k, 0] = 1.0
    for i in range(n):
        if i != k and _sliding(mode[i]):
            gmap[k, 1 + i] = -1.0
    return k


@njit(cache=True)
def solve_force(vel, b, mode, mu_s, mu_f, a, pivot, gmap, lock):
    """F/W [-] at which the sliding surfaces' rates (mode ±1) sum to the bearing's velocity ``vel`` [m/s].

    The *pivot* surface k takes the rest of the velocity, v_k = vel − Σ_{j≠k} φ_j(r − b_j) (in general
    v_k = gmap[k, 0] vel + Σ_U gmap[k, 1+j] φ_j(r − b_j), with the locked surfaces of :func:`set_split`
    sharing it), and its friction from it by the forward law; r is the root of g(r) = r − b_k − s_k µ_k(|v_k|),
    with g' = 1 − µ_k'(v_k) Σ_U gmap[k, 1+j] φ'_j ≥ 1 (gmap[k, 1+j] ≤ 0: increasing, well conditioned).  This is
    the same root as Σ_i φ_i(r − b_i) = vel, but it never inverts the pivot's law: a surface sliding so fast that
    µ_fast − µ(v) is below the rounding of r (a·v ≳ 36, e.g. one surface carrying the mass at 2.6 m/s
    after another reached its rim) has no resolvable φ, and must be the pivot (:func:`pick_pivot`).
    Safeguarded Newton to rounding; NaN when no surface slides (or the pivot does not).
    """
    n = b.shape[0]
    k = pivot
    if not (0 <= k < n) or not _sliding(mode[k]):
        return math.nan
    sk = float(mode[k])
    c0 = gmap[k, 0]
    # the bracket: where an unlocked non-pivot surface's rate becomes infinite (r past b_j ± µ_fast,j)
    lo = -math.inf
    hi = math.inf
    others = 0
    for j in range(n):
        if j != k and _sliding(mode[j]) and lock[j] == 0:
            others += 1
            if mode[j] == 1:
                hi = min(hi, b[j] + mu_f[j])
            else:
                lo = max(lo, b[j] - mu_f[j])
    if others == 0:
        f0, _ = friction_at_rate(c0 * vel, sk, mu_s[k], mu_f[k], a[k])
        return b[k] + f0
    f0, _ = friction_at_rate(c0 * vel / (others + 1), sk, mu_s[k], mu_f[k], a[k])
    r = b[k] + f0
    if not (lo < r < hi):
        r = 0.5 * (lo + hi) if math.isfinite(lo) and math.isfinite(hi) else (
            hi - 1e-3 if math.isfinite(hi) else lo + 1e-3)
    for _ in range(200):
        rest = c0 * vel
        dsum = 0.0
        finite = True
        for j in range(n):
            if j != k and _sliding(mode[j]) and lock[j] == 0:
                v, dv = slide_rate(r - b[j], float(mode[j]), mu_s[j], mu_f[j], a[j])
                if not math.isfinite(v):
                    finite = False
                    break
                rest += gmap[k, 1 + j] * v
                dsum -= gmap[k, 1 + j] * dv
        if not finite:  # past a non-pivot surface's infinite rate: inside the bracket again
            if mode[j] == 1:
                hi = min(hi, r)
            else:
                lo = max(lo, r)
            r = 0.5 * (lo + hi) if math.isfinite(lo) and math.isfinite(hi) else (
                hi - 1e-3 if math.isfinite(hi) else lo + 1e-3)
            continue
        fk, dfk = friction_at_rate(rest, sk, mu_s[k], mu_f[k], a[k])
        gval = r - b[k] - fk
        if gval == 0.0:
            return r
        if gval > 0.0:
            hi = r
        else:
            lo = r
        step = gval / (1.0 + dfk * dsum)
        if abs(step) <= 4e-16 * abs(r) + 1e-300:
            return r - step  # Newton's step at rounding: converged (quadratically) to the last bits
        r_new = r - step
        if not (lo < r_new < hi):
            if math.isfinite(lo) and math.isfinite(hi):
                r_new = 0.5 * (lo + hi)
            elif math.isfinite(hi):
                r_new = hi - 2.0 * abs(hi - r) - 1e-12
            else:
                r_new = lo + 2.0 * abs(r - lo) + 1e-12
        if math.isfinite(lo) and math.isfinite(hi) and hi - lo <= 2e-16 * max(abs(lo), abs(hi)):
            return 0.5 * (lo + hi)
        r = r_new
    return r


@njit(cache=True)
def surface_rates(vel, r, b, mode, mu_s, mu_f, a, pivot, gmap, lock, out_v, out_dv):
    """Slide rates [m/s] at the force r (the pivot's and the locked surfaces' from ``gmap``) and φ'_j (0 for those)."""
    n = b.shape[0]
    for i in range(n):
        out_v[i] = 0.0
        out_dv[i] = 0.0
    if not (0 <= pivot < n) or not _sliding(mode[pivot]):
        return -1
    for i in range(n):
        if i != pivot and _sliding(mode[i]) and lock[i] == 0:
            v, dv = slide_rate(r - b[i], float(mode[i]), mu_s[i], mu_f[i], a[i])
            out_v[i] = v
            out_dv[i] = dv
    for ell in range(n):
        if ell == pivot or lock[ell] == 1:
            total = gmap[ell, 0] * vel
            for i in range(n):
                if out_dv[i] != 0.0:
                    total += gmap[ell, 1 + i] * out_v[i]
            out_v[ell] = total
    if vel == 0.0:
        # at rest (a start from rest: every sliding surface at its onset, r = b_i ± µ_slow,i) the rates are 0;
        # φ_j((b_k + µ_slow) − b_j) alone would leave a rounding residue of either sign (−1e-17 m/s), which
        # the stop events would take for a surface already past its stop
        for i in range(n):
            out_v[i] = 0.0
    return pivot


@njit(cache=True)
def pick_pivot(dy, mode, a):
    """The sliding surface farthest into saturation (largest a_i s_i v_i): the pivot of :func:`solve_force`."""
    best = -1
    worst = -math.inf
    for i in range(mode.shape[0]):
        if _sliding(mode[i]):
            w = a[i] * float(mode[i]) * dy[1 + i]
            if w > worst or best < 0:
                worst = w
                best = i
    return best


@njit(cache=True)
def update_lock(dy, mode, a, lock, lock_in, lock_out):
    """The saturated set for the next step, from the rates at its start (hysteresis LOCK_IN / LOCK_OUT).

    A sliding surface joins when a_i s_i v_i ≥ ``lock_in`` (+inf: φ unresolvable), a member leaves when it
    falls to ``lock_out`` (:data:`LOCK_LEVELS`).  A rate of −inf is no saturation: a pivot left to absorb an unresolvable one (the
    pivot of the step before, after an event).  Returns the pivot (:func:`pick_pivot`), made a member when
    the set is not empty; :func:`set_split` clears a set of fewer than two.
    """
    n = mode.shape[0]
    any_member = False
    for i in range(n):
        if _sliding(mode[i]):
            w = a[i] * float(mode[i]) * dy[1 + i]
            if w >= lock_in or (lock[i] == 1 and w > lock_out):
                lock[i] = 1
                any_member = True
            else:
                lock[i] = 0
        else:
            lock[i] = 0
    k = pick_pivot(dy, mode, a)
    if any_member and k >= 0:
        lock[k] = 1
    return k


@njit(cache=True)
def back_force(u, bmat, out_b):
    for i in range(u.shape[0]):
        total = 0.0
        for k in range(u.shape[0]):
            total += bmat[i, k] * u[k]
        out_b[i] = total


@njit(cache=True)
def rhs(y, ag, g, c, bmat, mode, mu_s, mu_f, a, smat, wb, out_dy, out_jac, want_jac, pivot, gmap, lock):
    """dy/dt of y = (X', u_1..u_n) in a fixed mode; returns (r, friction power per unit mass).

    ``out_jac`` [m+1 × m+1] is filled with ∂(dy/dt)/∂y when ``want_jac``.  The friction power
    is g Σ (r − b_i) dū_i/dt on the series elements ū = smat u.  ``pivot``, ``gmap``, ``lock``: the surface whose
    rate comes from the series constraint (:func:`solve_force`) and the locked set (:func:`set_split`).
    """
    n = bmat.shape[0]
    vel = y[0]
    u = y[1:]
    back_force(u, bmat, wb)
    r = solve_force(vel, wb, mode, mu_s, mu_f, a, pivot, gmap, lock)
    out_dy[0] = -g * r - c * vel - ag
    rates = np.empty(n)
    dphi = np.empty(n)
    k = surface_rates(vel, r, wb, mode, mu_s, mu_f, a, pivot, gmap, lock, rates, dphi)
    for i in range(n):
        out_dy[1 + i] = rates[i]
    power = 0.0
    for i in range(n):
        ubar_dot = 0.0
        for q in range(n):
            ubar_dot += smat[i, q] * out_dy[1 + q]
        power += (r - wb[i]) * ubar_dot
    if want_jac:
        for p in range(n + 1):
            for q in range(n + 1):
                out_jac[p, q] = 0.0
        if k >= 0:
            # r from g(r) = r − b_k − s µ_k(v_k), v_k = G_k0 X' + Σ_U G_kj φ_j(r − b_j):
            # dr = (µ'_k G_k0 dX' + (B_k − µ'_k Σ_U G_kj φ'_j B_j) du) / (1 − µ'_k Σ_U G_kj φ'_j)
            _, dmu = friction_at_rate(rates[k], float(mode[k]), mu_s[k], mu_f[k], a[k])
            dsum = 0.0
            for j in range(n):
                dsum -= gmap[k, 1 + j] * dphi[j]
            den = 1.0 + dmu * dsum
            dr_dv = dmu * gmap[k, 0] / den
            out_jac[0, 0] = -g * dr_dv - c
            for q in range(n):
                total = bmat[k, q]
                for j in range(n):
                    total -= dmu * gmap[k, 1 + j] * dphi[j] * bmat[j, q]
                out_jac[0, 1 + q] = -g * total / den
            # the unlocked non-pivot rates v_j = φ_j(r − b_j); the pivot's and the locked ones by gmap
            for j in range(n):
                if dphi[j] != 0.0:
                    out_jac[1 + j, 0] = dphi[j] * dr_dv
                    for q in range(n):
                        out_jac[1 + j, 1 + q] = dphi[j] * (-out_jac[0, 1 + q] / g - bmat[j, q])
            for ell in range(n):
                if ell == k or lock[ell] == 1:
                    out_jac[1 + ell, 0] = gmap[ell, 0]
                    for j in range(n):
                        if dphi[j] != 0.0:
                            out_jac[1 + ell, 0] += gmap[ell, 1 + j] * out_jac[1 + j, 0]
                            for q in range(n):
                                out_jac[1 + ell, 1 + q] += gmap[ell, 1 + j] * out_jac[1 + j, 1 + q]
        else:
            out_jac[0, 0] = -c
    return r, g * power


@njit(cache=True)
def stage_matrix(h, jac0, out):
    """I − h (A ⊗ J) [3m × 3m], the Newton matrix of the collocation with one Jacobian J for the three stages."""
    m = jac0.shape[0]
    for j in range(3):
        for p in range(m):
            for k in range(3):
                for q in range(m):
                    out[j * m + p, k * m + q] = (1.0 if (j == k and p == q) else 0.0) - h * RADAU_A[j, k] * jac0[p, q]


@njit(cache=True)
def radau_step(y0, h, a_start, slope, g, c, bmat, mode, mu_s, mu_f, a, smat, scale, y1, quad, pivot, gmap, lock,
               z_full, guess, lu, piv, use_lu):
    """One Radau IIA step of length h from y0 (ground acceleration a_start + slope τ); Newton's iterations, or −1
    if Newton fails.

    ``y1`` is filled with the end state; ``quad`` with the step's (−∫a_g X', c∫X'², friction work) [J/kg].
    ``guess`` [3 × 3]: Newton starts from the stage increments Σ_k guess[j, k] z_full[k] (a half step of
    :func:`double_step`), or, when ``guess`` is empty, from 0 and then ``z_full`` receives this step's increments.
    ``use_lu``: *simplified* Newton first, its matrix I − h A⊗J(y0) factored once by the caller (``lu``, ``piv``);
    when it does not contract (θ ≥ 1, or 10 iterations) full Newton (a Jacobian per stage and iteration) takes over
    from the same start.  Both end at their rounding floor.
    """
    m = y0.shape[0]
    n = m - 1
    z = np.zeros((3, m))
    if guess.shape[0] == 3:
        for j in range(3):
            for p in range(m):
                total = 0.0
                for k in range(3):
                    total += guess[j, k] * z_full[k, p]
                z[j, p] = total
    fz = np.empty((3, m))
    jac = np.empty((3, m, m))
    big = np.empty((3 * m, 3 * m))
    res = np.empty(3 * m)
    delta = np.empty(3 * m)
    ys = np.empty(m)
    dy = np.empty(m)
    wb = np.empty(n)
    rs = np.empty(3)
    power = np.empty(3)
    z_start = z.copy()
    simplified = use_lu
    prev = math.inf
    converged = False
    it = 0
    n_it = 0
    while n_it < 40:
        n_it += 1
        fall_back = False
        for j in range(3):
            for p in range(m):
                ys[p] = y0[p] + z[j, p]
            ag = a_start + slope * RADAU_C[j] * h
            rs[j], power[j] = rhs(ys, ag, g, c, bmat, mode, mu_s, mu_f, a, smat, wb, dy, jac[j], not simplified,
                                  pivot, gmap, lock)
            for p in range(m):
                fz[j, p] = dy[p]
        ok = True
        for j in range(3):
            if not math.isfinite(rs[j]):
                ok = False
        for j in range(3):
            for p in range(m):
                total = z[j, p]
                for k in range(3):
                    total -= h * RADAU_A[j, k] * fz[k, p]
                res[j * m + p] = -total
                if not math.isfinite(res[j * m + p]):
                    ok = False
        if not ok:
            if not simplified:
                return -1
            fall_back = True
        elif simplified:
            for p in range(3 * m):
                delta[p] = res[p]
            lu_solve(lu, piv, delta)
        else:
            for j in range(3):
                for p in range(m):
                    for k in range(3):
                        for q in range(m):
                            big[j * m + p, k * m + q] = (1.0 if (j == k and p == q) else 0.0) - h * RADAU_A[j, k] * jac[k, p, q]
            for p in range(3 * m):
                for q in range(3 * m):
                    if not math.isfinite(big[p, q]):
                        return -1  # a stage left the slide law's domain: the caller shortens the step
            if not solve_or_refuse(big, res, delta):
                return -1  # a singular stage matrix: the caller shortens the step
        if not fall_back:
            size = 0.0
            for j in range(3):
                for p in range(m):
                    z[j, p] += delta[j * m + p]
                    size = max(size, abs(delta[j * m + p]) / scale[p])
            if not math.isfinite(size):
                if not simplified:
                    return -1
                fall_back = True
            elif not simplified:
                if size <= 1e-15 or (it >= 2 and size >= 0.5 * prev and size <= 1e-11):
                    converged = True
                    break
            else:
                # linear contraction θ: the error left after this iteration is ≤ θ/(1 − θ) of its size
                theta = size / prev if it >= 1 else 0.0
                if size <= 1e-15 or (it >= 1 and theta < 0.9 and theta * size <= 1e-16 * (1.0 - theta)):
                    converged = True
                    break
                if (it >= 1 and theta >= 1.0) or it >= 10:
                    fall_back = True
        if fall_back:
            simplified = False
            for j in range(3):
                for p in range(m):
                    z[j, p] = z_start[j, p]
            prev = math.inf
            it = 0
            continue
        prev = size
        it += 1
    if not converged:
        return -1
    if guess.shape[0] != 3:
        for j in range(3):
            for p in range(m):
                z_full[j, p] = z[j, p]
    # the quadratures of the step's energies.  The slide rates in the friction power are the stage derivatives
    # the collocation itself took, F_j = Σ_k (A⁻¹)_jk Z_k / h (so that Σ_j b_j F_j = Z_3 / h, the step's own
    # displacement of every surface), not the right-hand side re-evaluated at the stages: with two surfaces
    # saturated (a·v ≳ 30 on both, regime III of a µ(v) TFP at 3 m/s) the split of the velocity between them is
    # φ(r − b) at µ_fast − µ(v) ~ 1e-15, so f(Y_j) carries the rounding of r amplified 1e13 times: positions
    # right to 1e-13, re-evaluated rates off by 1e-3 m/s, and the friction work of one step off by 1.6e-4 J/kg
    # (NWH360 x2.5 at 4.99 s; measured per step, docs/multisurface.md)
    q_in = 0.0
    q_visc = 0.0
    q_fric = 0.0
    inv_h = 1.0 / h
    for j in range(3):
        for p in range(m):
            ys[p] = y0[p] + z[j, p]
        ag = a_start + slope * RADAU_C[j] * h
        rs[j], power[j] = rhs(ys, ag, g, c, bmat, mode, mu_s, mu_f, a, smat, wb, dy, jac[j], False, pivot, gmap, lock)
        for p in range(1, m):
            total = 0.0
            for k in range(3):
                total += RADAU_A_INV[j, k] * z[k, p]
            dy[p] = total * inv_h
        stage_power = 0.0
        for i in range(n):
            ubar_dot = 0.0
            for q in range(n):
                ubar_dot += smat[i, q] * dy[1 + q]
            stage_power += (rs[j] - wb[i]) * ubar_dot
        w = h * RADAU_A[2, j]
        q_in -= w * ag * ys[0]
        q_visc += w * c * ys[0] * ys[0]
        q_fric += w * g * stage_power
    for p in range(m):
        y1[p] = y0[p] + z[2, p]
    quad[0] = q_in
    quad[1] = q_visc
    quad[2] = q_fric
    return n_it


@njit(cache=True)
def double_step(y0, h, a_start, slope, g, c, bmat, mode, mu_s, mu_f, a, smat, scale, y1, quad, pivot, gmap, lock,
                simplified):
    """Two Radau steps of h/2 (kept) and one of h (the estimate); returns the scaled difference (inf: failed).

    ``quad`` [4]: the halves' (−∫a_g X', c∫X'², friction work) [J/kg] and the Newton iterations of the three steps.
    The halves' Newton starts from the full step's collocation polynomial (:data:`GUESS_FIRST_HALF`).
    ``simplified``: the three steps' Newton uses one Jacobian, at y0, in two factored matrices (h and h/2;
    :func:`radau_step`), instead of a Jacobian per stage and iteration and a 3m × 3m solve each time.
    """
    m = y0.shape[0]
    jac0 = np.empty((m, m))
    lu_full = np.empty((3 * m, 3 * m))
    lu_half = np.empty((3 * m, 3 * m))
    piv_full = np.zeros(3 * m, dtype=np.int64)
    piv_half = np.zeros(3 * m, dtype=np.int64)
    use_full = False
    use_half = False
    if simplified:
        dy0 = np.empty(m)
        wb0 = np.empty(m - 1)
        r0, _ = rhs(y0, a_start, g, c, bmat, mode, mu_s, mu_f, a, smat, wb0, dy0, jac0, True, pivot, gmap, lock)
        if math.isfinite(r0):
            stage_matrix(h, jac0, lu_full)
            use_full = lu_factor(lu_full, piv_full)
            stage_matrix(0.5 * h, jac0, lu_half)
            use_half = lu_factor(lu_half, piv_half)
    y_full = np.empty(m)
    y_mid = np.empty(m)
    q_full = np.empty(3)
    q1 = np.empty(3)
    q2 = np.empty(3)
    z_full = np.empty((3, m))
    no_guess = np.empty((0, 3))
    quad[3] = 0.0
    it0 = radau_step(y0, h, a_start, slope, g, c, bmat, mode, mu_s, mu_f, a, smat, scale, y_full, q_full, pivot, gmap, lock,
                     z_full, no_guess, lu_full, piv_full, use_full)
    if it0 < 0:
        return math.inf
    quad[3] = it0
    half = 0.5 * h
    it1 = radau_step(y0, half, a_start, slope, g, c, bmat, mode, mu_s, mu_f, a, smat, scale, y_mid, q1, pivot, gmap, lock,
                     z_full, GUESS_FIRST_HALF, lu_half, piv_half, use_half)
    if it1 < 0:
        return math.inf
    quad[3] += it1
    it2 = radau_step(y_mid, half, a_start + slope * half, slope, g, c, bmat, mode, mu_s, mu_f, a, smat, scale,
                     y1, q2, pivot, gmap, lock, z_full, GUESS_SECOND_HALF, lu_half, piv_half,
                     use_half)
    if it2 < 0:
        return math.inf
    err = 0.0
    for p in range(m):
        err = max(err, abs(y1[p] - y_full[p]) / scale[p])
    for k in range(3):
        quad[k] = q1[k] + q2[k]
    quad[3] += it2
    return err


@njit(cache=True)
def event_values(y, r, dy, mode, pivot, mu_s, cap, bmat, wb, out_e):
    """The event functions at a state (≥ 0: no event); slots 2i (stop/start/leave), 2i+1 (rim), 2n (mass stop).

    The pivot's stop slot is off (+inf), as in the 2-D kernel: its rate is the rest of the velocity, re-chosen at
    every step's start as the fastest surface, so it stops only with the mass (slot 2n) or after another surface
    became the pivot.  Left on, the rest of the velocity after a non-pivot rate at its resolution floor (two equal
    surfaces whose split had relaxed to rounding, a·v ≈ 24–32) crossed 0 for one 6.5e-12 s step: a stop and a restart
    at one instant (the rim pulse of tests/solver/test_planar_multisurface_rate_rim.py at 0.7173546 s, h177).
    """
    n = mode.shape[0]
    back_force(y[1:], bmat, wb)
    same = 0
    mixed = False
    for i in range(n):
        md = mode[i]
        f = r - wb[i]
        out_e[2 * i + 1] = math.inf
        if md == 1 or md == -1:
            s = float(md)
            out_e[2 * i] = math.inf if i == pivot else s * dy[1 + i]
            if math.isfinite(cap[i]):
                out_e[2 * i + 1] = cap[i] - s * y[1 + i]
            if same == 0:
                same = md
            elif same != md:
                mixed = True
        elif md == 0:
            out_e[2 * i] = mu_s[i] - abs(f)
        else:
            s = 1.0 if md > 0 else -1.0
            out_e[2 * i] = s * f + mu_s[i]
    out_e[2 * n] = math.inf
    if same != 0 and not mixed:
        out_e[2 * n] = float(same) * y[0]


@njit(cache=True)
def window(u, bmat, mode, mu_s, wb):
    """(lo, hi) of F/W the stuck bearing holds; a surface held on its rim removes that side's limit."""
    back_force(u, bmat, wb)
    lo = -math.inf
    hi = math.inf
    for i in range(u.shape[0]):
        if mode[i] != 2:
            hi = min(hi, wb[i] + mu_s[i])
        if mode[i] != -2:
            lo = max(lo, wb[i] - mu_s[i])
    return lo, hi


@njit(cache=True)
def start_from_rest(s, u, bmat, mode, mu_s, wb):
    """The surfaces at the window's edge in direction s begin to slide (mode s); the others stay."""
    lo, hi = window(u, bmat, mode, mu_s, wb)
    for i in range(u.shape[0]):
        if s > 0.0 and mode[i] != 2 and wb[i] + mu_s[i] <= hi + LEVEL_TIE:
            mode[i] = 1
        elif s < 0.0 and mode[i] != -2 and wb[i] - mu_s[i] >= lo - LEVEL_TIE:
            mode[i] = -1


@njit(cache=True)
def consistent_mode(vel, u, bmat, mode, mu_s, mu_f, a, wb):
    """Set the sliding surfaces for a moving bearing (vel ≠ 0) from the true slide law (bisection on r).

    Each surface not held on a rim that way slides when |r − b_i| > µ_slow,i; r solves
    Σ v_i(r) = vel with v_i = 0 inside the static band.
    """
    n = u.shape[0]
    back_force(u, bmat, wb)
    lo = -math.inf
    hi = math.inf
    for i in range(n):
        if mode[i] != 2:
            hi = min(hi, wb[i] + mu_f[i])
        if mode[i] != -2:
            lo = max(lo, wb[i] - mu_f[i])
    if not lo < hi:
        return
    for _ in range(400):
        r = 0.5 * (lo + hi)
        if r <= lo or r >= hi:
            break
        total = -vel
        for i in range(n):
            f = r - wb[i]
            if f > mu_s[i] and mode[i] != 2:
                total += slide_rate(f, 1.0, mu_s[i], mu_f[i], a[i])[0]
            elif f < -mu_s[i] and mode[i] != -2:
                total += slide_rate(f, -1.0, mu_s[i], mu_f[i], a[i])[0]
        if total > 0.0:
            hi = r
        else:
            lo = r
    r = 0.5 * (lo + hi)
    for i in range(n):
        f = r - wb[i]
        if f > mu_s[i] + LEVEL_TIE and mode[i] != 2:
            mode[i] = 1
        elif f < -mu_s[i] - LEVEL_TIE and mode[i] != -2:
            mode[i] = -1
        elif mode[i] == 1 or mode[i] == -1:
            mode[i] = 0


@njit(cache=True)
def _masks(mode):
    sliding = 0
    rimmed = 0
    for i in range(mode.shape[0]):
        if mode[i] == 1 or mode[i] == -1:
            sliding |= 1 << i
        elif mode[i] == 2 or mode[i] == -2:
            rimmed |= 1 << i
    return sliding, rimmed


@njit(cache=True)
def rate_kernel(acc, times, g, c, bmat, smat, mu_s, mu_f, a, cap, tol, h_first, lock_levels, simplified_newton,
                out_x, out_v, out_a, out_r, out_energy, ev_time, ev_kind, ev_x,
                summary, surf_peak, state_first_time, u):
    """Response of a mass on a multi-surface bearing with µ(v) surfaces to a sampled record.

    Parameters
    ----------
    acc : float64[n]
        Ground acceleration [m/s²], linear between samples.
    times : float64[n]
        Sample times from the first [s].
    g, c : float
        Gravity [m/s²] and damping per unit mass [1/s].
    bmat, smat : float64[ns, ns]
        Back-force matrix B (b = B u) [1/m] and the element map ū = S u [-].
    mu_s, mu_f, a : float64[ns]
        µ_slow, µ_fast [-] and the rate [s/m] of each surface (µ_slow < µ_fast).
    cap : float64[ns]
        d_i* [m] (inf: no rim).
    tol : float
        Largest scaled difference of a step from its two halves (scales: the running peaks).
    h_first : float
        First trial step [s].
    lock_levels : float64[2]
        (join, leave) levels of a_i s_i v_i of the saturated set (:func:`update_lock`, :data:`LOCK_LEVELS`) [-].
    simplified_newton : bool
        The collocation's Newton with one Jacobian per step (:func:`double_step`); False: full Newton.
    out_x, out_v, out_a, out_r, out_energy, ev_time, ev_kind, ev_x, summary, surf_peak, state_first_time
        Filled as in :func:`isolator.solver.multisurface_kernel.multisurface_kernel`.
    u : float64[ns]
        In: initial surface displacements (zeros); out: the final ones [m].
    """
    n_samples = acc.shape[0]
    ns = u.shape[0]
    m = ns + 1
    mode = np.zeros(ns, dtype=np.int64)
    before = np.zeros(ns, dtype=np.int64)
    fresh = np.zeros(ns, dtype=np.int64)
    y = np.zeros(m)
    y_try = np.empty(m)
    y_ev = np.empty(m)
    dy = np.empty(m)
    jac = np.empty((m, m))
    quad = np.empty(4)
    quad_ev = np.empty(4)
    wb = np.empty(ns)
    e0 = np.empty(2 * ns + 1)
    e1 = np.empty(2 * ns + 1)
    e_end = np.empty(2 * ns + 1)  # e1 at the step's end, kept while the secant overwrites e1 (and dy)
    scale = np.empty(m)
    for i in range(ns):
        y[1 + i] = u[i]
    n_masks = 1 << ns
    for j in range(state_first_time.shape[0]):
        state_first_time[j] = -1.0
    stuck = True
    n_ev = 0
    status = 0
    peak_x = 0.0
    peak_v = 0.0
    peak_a = abs(acc[0])
    peak_r = 0.0
    slip_time = 0.0
    e_in = 0.0
    e_f = 0.0
    e_v = 0.0
    e_imp = 0.0
    n_rim = 0
    n_ult = 0
    impulse = 0.0
    max_imp_v = 0.0
    first_ult = -1.0
    n_steps = 0
    n_newton = 0.0
    fail_t = -1.0
    h = h_first
    pivot = -1
    lock = np.zeros(ns, dtype=np.int64)
    gmap = np.zeros((ns, ns + 1))
    r_now = -acc[0] / g
    x_floor = 1e-4
    v_floor = 1e-3
    out_x[0] = 0.0
    out_v[0] = 0.0
    out_a[0] = acc[0]
    out_r[0] = r_now
    for row in range(4):
        out_energy[row, 0] = 0.0
    for idx in range(n_samples - 1):
        t_i = times[idx]
        dt_i = times[idx + 1] - t_i
        a0 = acc[idx]
        slope = (acc[idx + 1] - a0) / dt_i
        tau = 0.0
        events_here = 0
        steps_here = 0
        while tau < dt_i and status & STATUS_STEP_FAILED == 0:
            if stuck:
                lo, hi = window(y[1:], bmat, mode, mu_s, wb)
                need_now = -(a0 + slope * tau) / g
                need_end = -(a0 + slope * dt_i) / g
                if lo <= need_now <= hi:
                    if lo <= need_end <= hi:
                        break  # stuck to the end of the interval (need is linear in between)
                    s = 1.0 if need_end > hi else -1.0
                    level = hi if s > 0.0 else lo
                    tb = (-g * level - a0) / slope if slope != 0.0 else tau
                    tb = min(max(tb, tau), dt_i)
                else:
                    s = 1.0 if need_now > hi else -1.0
                    tb = tau
                if tb >= dt_i:
                    break
                tau = tb
                stuck = False
                start_from_rest(s, y[1:], bmat, mode, mu_s, wb)
                n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_i + tau, np.int64(BREAKAWAY), y[1:].sum())
                sliding, rimmed = _masks(mode)
                code = sliding + n_masks * rimmed
                if state_first_time[code] < 0.0:
                    state_first_time[code] = t_i + tau
            # ---- one step (or the part up to an event) ----
            steps_here += 1
            if steps_here > MAX_STEPS_PER_INTERVAL:
                status |= STATUS_STEP_FAILED
                fail_t = t_i + tau
                break
            h = min(h, dt_i - tau)
            scale[0] = max(peak_v, v_floor)
            for p in range(1, m):
                scale[p] = max(peak_x, x_floor)
            # the pivot (the surface whose rate comes from the series constraint) is the one farthest into
            # saturation at the step's start; held for the step and its event search (the same equations)
            # the saturated set (:func:`set_split`) likewise, from the rates at the step's start
            pivot = set_split(mode, pivot, lock, bmat, gmap)
            rhs(y, a0 + slope * tau, g, c, bmat, mode, mu_s, mu_f, a, smat, wb, dy, jac, False, pivot, gmap, lock)
            pivot = update_lock(dy, mode, a, lock, lock_levels[0], lock_levels[1])
            pivot = set_split(mode, pivot, lock, bmat, gmap)
            err = double_step(y, h, a0 + slope * tau, slope, g, c, bmat, mode, mu_s, mu_f, a, smat, scale,
                              y_try, quad, pivot, gmap, lock, simplified_newton)
            n_newton += quad[3]
            if not err <= tol:
                if h <= 1e-13 * dt_i:
                    status |= STATUS_STEP_FAILED
                    fail_t = t_i + tau
                    break
                if math.isfinite(err):
                    h = h * max(0.1, 0.9 * (tol / err) ** (1.0 / 6.0))
                else:
                    h = 0.25 * h
                continue
            # events between y and y_try
            r0, _ = rhs(y, a0 + slope * tau, g, c, bmat, mode, mu_s, mu_f, a, smat, wb, dy, jac, False, pivot, gmap, lock)
            event_values(y, r0, dy, mode, pivot, mu_s, cap, bmat, wb, e0)
            r1, _ = rhs(y_try, a0 + slope * (tau + h), g, c, bmat, mode, mu_s, mu_f, a, smat, wb, dy, jac, False, pivot, gmap,
                         lock)
            event_values(y_try, r1, dy, mode, pivot, mu_s, cap, bmat, wb, e1)
            for slot in range(2 * ns + 1):
                e_end[slot] = e1[slot]
            first_slot = -1
            first_t = math.inf
            for slot in range(2 * ns + 1):
                # an armed event already past at the step's start is taken at once: the mode is no longer
                # consistent (an event located a hair past another one, e.g. the second of two equal
                # surfaces stopping with the mass, or the mass stopping a hair after its last surface);
                # left alone the sliding branch would run on through its onset, against the slide law
                if slot < 2 * ns and slot % 2 == 0 and fresh[slot // 2] == 1 and e0[slot] < 0.0:
                    # a surface that has just started is at its onset, rate 0: a residue of rounding
                    # (−1e-17 m/s) is not a stop already past; only its rate at the step's end tells
                    e0[slot] = 0.0
                # a stop slot at 0 where the motion starts (the mass from rest, a surface just started) is the
                # start, not a stop: its event, if any, lies inside the step (the velocity turns back in it)
                starting = e0[slot] == 0.0 and (
                    (slot == 2 * ns and y[0] == 0.0) or (slot < 2 * ns and slot % 2 == 0 and (
                        y[0] == 0.0 or fresh[slot // 2] == 1) and (mode[slot // 2] == 1 or mode[slot // 2] == -1)))
                if e0[slot] < 0.0 or (e1[slot] < 0.0 and e0[slot] >= 0.0):
                    if e0[slot] <= 0.0 and not starting:  # at the event already (a rim reached with another)
                        t_root = 0.0
                    else:
                        # Illinois secant on the re-stepped collocation
                        ta = 0.0
                        fa = e0[slot]
                        tb_ = h
                        fb = e1[slot]
                        side = 0
                        t_root = h
                        for _ in range(100):
                            tm = (ta * fb - tb_ * fa) / (fb - fa)
                            if not (ta < tm < tb_):
                                tm = 0.5 * (ta + tb_)
                            double_step(y, tm, a0 + slope * tau, slope, g, c, bmat, mode, mu_s, mu_f, a, smat,
                                        scale, y_ev, quad_ev, pivot, gmap, lock, simplified_newton)
                            n_newton += quad_ev[3]
                            rm, _ = rhs(y_ev, a0 + slope * (tau + tm), g, c, bmat, mode, mu_s, mu_f, a, smat, wb,
                                        dy, jac, False, pivot, gmap, lock)
                            event_values(y_ev, rm, dy, mode, pivot, mu_s, cap, bmat, wb, e1)
                            fm = e1[slot]
                            if fm == 0.0:  # on the event: the root is tm (not the bracket's far end)
                                tb_ = tm
                                break
                            if fm < 0.0:
                                tb_ = tm
                                fb = fm
                                if side == -1:
                                    fa *= 0.5
                                side = -1
                            else:
                                ta = tm
                                fa = fm
                                if side == 1:
                                    fb *= 0.5
                                side = 1
                            if tb_ - ta <= 1e-13 * dt_i:  # ≤ 1e-13 of the interval
                                break
                        t_root = tb_
                        # restore the end values for the other slots (a copy: re-evaluated here they took the
                        # rates dy of the secant's last point, not the step end's; h177)
                        for q in range(2 * ns + 1):
                            e1[q] = e_end[q]
                    if t_root < first_t or (t_root == first_t and slot == 2 * ns):
                        first_t = t_root
                        first_slot = slot
            if first_slot < 0:
                # no event: accept the step
                for i in range(ns):
                    fresh[i] = 0
                for p in range(m):
                    y[p] = y_try[p]
                e_in += quad[0]
                e_v += quad[1]
                e_f += quad[2]
                tau += h
                slip_time += h
                n_steps += 1
                r_now = r1
                peak_x = max(peak_x, abs(y[1:].sum()))
                peak_v = max(peak_v, abs(y[0]))
                peak_r = max(peak_r, abs(r_now))
                peak_a = max(peak_a, abs(g * r_now + c * y[0]))
                for i in range(ns):
                    surf_peak[i] = max(surf_peak[i], abs(y[1 + i]))
                err_next = max(err, 1e-3 * tol)
                h = h * min(4.0, 0.9 * (tol / err_next) ** (1.0 / 6.0))
                continue
            # ---- the event: advance to it ----
            if first_t > 0.0:
                double_step(y, first_t, a0 + slope * tau, slope, g, c, bmat, mode, mu_s, mu_f, a, smat, scale,
                            y_ev, quad_ev, pivot, gmap, lock, simplified_newton)
                n_newton += quad_ev[3]
                for p in range(m):
                    y[p] = y_ev[p]
                e_in += quad_ev[0]
                e_v += quad_ev[1]
                e_f += quad_ev[2]
                tau += first_t
                slip_time += first_t
                n_steps += 1
            t_now = t_i + tau
            for i in range(ns):
                surf_peak[i] = max(surf_peak[i], abs(y[1 + i]))
            events_here += 1
            if events_here > MAX_EVENTS_PER_INTERVAL:
                status |= STATUS_CHATTER
                y[0] = 0.0
                for i in range(ns):
                    if mode[i] == 1 or mode[i] == -1:
                        mode[i] = 0
                stuck = True
                break
            ag_now = a0 + slope * tau
            for i in range(ns):
                before[i] = mode[i]
            if first_slot < 2 * ns and first_slot % 2 == 0 and e0[2 * ns] < math.inf and (
                    mode[first_slot // 2] == 1 or mode[first_slot // 2] == -1) and abs(y[0]) <= 1e-9 * scale[0]:
                # a surface stops with the mass (every slider moving one way, X' at rounding): the mass stop,
                # located a hair later; taken here, or the others would run on through X' = 0
                first_slot = 2 * ns
            if first_slot == 2 * ns:
                # the mass stops
                y[0] = 0.0
                for i in range(ns):
                    if mode[i] == 1 or mode[i] == -1:
                        mode[i] = 0
                lo, hi = window(y[1:], bmat, mode, mu_s, wb)
                need = -ag_now / g
                if lo <= need <= hi:
                    stuck = True
                    n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_now, np.int64(STICK), y[1:].sum())
                    r_now = need
                else:
                    s = 1.0 if need > hi else -1.0
                    start_from_rest(s, y[1:], bmat, mode, mu_s, wb)
                    n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_now, np.int64(REVERSAL), y[1:].sum())
            else:
                i = first_slot // 2
                if first_slot % 2 == 1:
                    # a rim: hold the surface there
                    s = 1.0 if mode[i] > 0 else -1.0
                    y[1 + i] = s * cap[i]
                    mode[i] = 2 if s > 0.0 else -2
                    n_rim += 1
                    movable = False
                    sv = 1.0 if y[0] > 0.0 else -1.0
                    for k in range(ns):
                        if not (mode[k] == 2 and sv > 0.0) and not (mode[k] == -2 and sv < 0.0):
                            movable = True
                    if not movable:
                        # the ultimate displacement: plastic impact
                        vimp = abs(y[0])
                        impulse += vimp
                        max_imp_v = max(max_imp_v, vimp)
                        e_imp += 0.5 * vimp * vimp
                        y[0] = 0.0
                        n_ult += 1
                        if first_ult < 0.0:
                            first_ult = t_now
                        n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_now, np.int64(ULTIMATE), y[1:].sum())
                        lo, hi = window(y[1:], bmat, mode, mu_s, wb)
                        need = -ag_now / g
                        if lo <= need <= hi:
                            stuck = True
                            r_now = need
                        else:
                            s2 = 1.0 if need > hi else -1.0
                            start_from_rest(s2, y[1:], bmat, mode, mu_s, wb)
                    else:
                        consistent_mode(y[0], y[1:], bmat, mode, mu_s, mu_f, a, wb)
                        n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_now, np.int64(RIM_REACHED), y[1:].sum())
                else:
                    md = mode[i]
                    back_force(y[1:], bmat, wb)
                    if md == 1 or md == -1:
                        mode[i] = 0  # a surface stops while the mass moves on
                    elif md == 0:
                        mode[i] = 1 if r1_sign(y, ag_now, g, c, bmat, mode, mu_s, mu_f, a, smat, wb, dy, jac,
                                                i, pivot, gmap, lock) > 0.0 else -1
                    else:
                        mode[i] = -1 if md > 0 else 1  # leaves its rim inward
                    n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t_now, np.int64(REGIME), y[1:].sum())
            for i in range(ns):
                if (mode[i] == 1 or mode[i] == -1) and mode[i] != before[i]:
                    fresh[i] = 1
                # the saturated set is the old mode's: chosen again from the rates at the next step's start
                lock[i] = 0
            if not stuck:
                sliding, rimmed = _masks(mode)
                code = sliding + n_masks * rimmed
                if state_first_time[code] < 0.0:
                    state_first_time[code] = t_now
                if sliding == 0:
                    # nothing slides but the mass moves: only after rounding at a stop; stop it
                    y[0] = 0.0
                    stuck = True
            peak_x = max(peak_x, abs(y[1:].sum()))
        if status & STATUS_STEP_FAILED:
            # leave the remaining samples at the last state
            for j in range(idx + 1, n_samples):
                out_x[j] = y[1:].sum()
                out_v[j] = y[0]
                out_a[j] = acc[j]
                out_r[j] = r_now
                out_energy[0, j] = e_in
                out_energy[1, j] = e_f
                out_energy[2, j] = e_v
                out_energy[3, j] = e_imp
            break
        j = idx + 1
        out_x[j] = y[1:].sum()
        out_v[j] = y[0]
        if stuck:
            out_a[j] = acc[j]
            out_r[j] = -acc[j] / g
        else:
            pivot = set_split(mode, pivot, lock, bmat, gmap)
            r_now, _ = rhs(y, acc[j], g, c, bmat, mode, mu_s, mu_f, a, smat, wb, dy, jac, False, pivot, gmap, lock)
            out_r[j] = r_now
            out_a[j] = -(g * r_now + c * y[0])
            peak_r = max(peak_r, abs(r_now))
        peak_a = max(peak_a, abs(out_a[j]))
        peak_x = max(peak_x, abs(out_x[j]))
        peak_v = max(peak_v, abs(y[0]))
        out_energy[0, j] = e_in
        out_energy[1, j] = e_f
        out_energy[2, j] = e_v
        out_energy[3, j] = e_imp
    for i in range(ns):
        u[i] = y[1 + i]
        surf_peak[i] = max(surf_peak[i], abs(y[1 + i]))
    if n_ev > ev_time.shape[0]:
        status |= STATUS_EVENTS_TRUNCATED
    summary[S_PEAK_X] = peak_x
    summary[S_PEAK_V] = peak_v
    summary[S_PEAK_A] = peak_a
    summary[S_SLIP_TIME] = slip_time
    summary[S_E_INPUT] = e_in
    summary[S_E_FRICTION] = e_f
    summary[S_E_VISCOUS] = e_v
    summary[S_E_IMPACT] = e_imp
    summary[S_N_EVENTS] = n_ev
    summary[S_STATUS] = status
    summary[S_N_RIM_CONTACTS] = n_rim
    summary[S_N_ULTIMATE] = n_ult
    summary[S_IMPULSE] = impulse
    summary[S_MAX_IMPACT_V] = max_imp_v
    summary[S_FIRST_ULTIMATE_T] = first_ult
    summary[S_PEAK_R] = peak_r
    summary[S_N_STEPS] = n_steps
    summary[S_FAIL_T] = fail_t
    summary[S_N_NEWTON] = n_newton


@njit(cache=True)
def r1_sign(y, ag, g, c, bmat, mode, mu_s, mu_f, a, smat, wb, dy, jac, i, pivot, gmap, lock):
    """The sign of the friction excess r − b_i of surface i at the state (which way it starts)."""
    r, _ = rhs(y, ag, g, c, bmat, mode, mu_s, mu_f, a, smat, wb, dy, jac, False, pivot, gmap, lock)
    back_force(y[1:], bmat, wb)
    return r - wb[i]


__all__ = ["rate_kernel", "solve_force", "slide_rate", "EVENT_NAMES", "SUMMARY_SIZE"]
