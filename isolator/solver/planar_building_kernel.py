r"""The compiled loop of the 2-D building: Taylor series of the exact solution, piece by piece.

Pure arrays in, arrays out (numba, cached on disk).  Per horizontal direction d the state is

    z_d = [x_b, v_b, u_1..u_n, u̇_1..u̇_n]

(slab displacement and velocity relative to the ground, floor displacements and velocities
relative to the slab) and, in each phase, z_d' = A z_d + g a_d(t) + p F_d(t), with a_d linear
between samples and F the friction force on the slab (its direction couples x and y):

* ``STUCK``: the slab holds (x_b fixed, v_b = 0); A is the fixed-base floors' matrix, F absent;
* ``START``: leaving rest (|V| < r_sw): F = µk N D/|D|, with D the force on the slab other
  than friction (the velocity of a block leaving rest turns onto D within a time ∝ |V|: its
  slow manifold; the lag it neglects is ∝ |V| and is measured in the tests);
* ``SLIDE``: F = µk N V/|V|;
* ``FINISH``: the last ~1e-10 v_ref of a stop, F frozen in the direction of V (linear).

In every phase the solution is the Taylor series z(τ) = Σ Z_k τ^k whose coefficients follow
from the recurrence Z_{k+1} = (A Z_k + g a_k + p F_k)/(k + 1), where F_k comes from the series
of |V| = sqrt(V·V) and V/|V| (the classical recurrences of a square root and a quotient).  In
the linear phases (stuck, finish, a collinear slide) the series is that of the exact solution;
in every phase a piece is only as long as the series reaches rounding (the last two terms
below ~1e-16 of the state, the Jorba–Zou rule) and at most THETA / ρ(A), ρ the largest |eigenvalue|.  Events
(break-away |D| = µs N, stop, the hand-overs between phases) and the interior extremes of the
watched quantities are roots of these polynomials, found by safeguarded Newton (events) or
Illinois (extremes); energies over a piece are exact integrals of the series' products.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.jit import njit

#: Taylor order of a piece (z uses Z_0..Z_N; ż and z̈ use Z up to N + 2); THETA^N / N! = 3e-19.  The kernel takes
#: it as an argument (``n_order``; its series arrays hold N + 3 coefficients), the driver passes this value.
N_ORDER = 18
#: Longest piece, as ρ(A) h [-] (the angle the fastest mode turns).
THETA = 0.75
#: truncation tolerance of a piece, relative to the state's size
TRUNC_EPS = 1e-16
MAX_EVENTS_PER_INTERVAL = 1000
MAX_PIECES_PER_INTERVAL = 200000

#: the piece's vertical and µ(v), ``vz``: 1 when either is present (else the constant-µ, no-vertical code runs,
#: bit for bit as without them), ν = N/W = 1 + a_z/g at the series' origin and its rate [1/s], the stiffness
#: that follows the normal force (W/R of a pendulum, 0 for a spring) [N/m], (µ_fast − µ_slow) W [N], a [s/m]
V_VARYING = 0
V_NU0 = 1
V_NU1 = 2
V_K_VERT = 3
V_DMU_N = 4
V_RATE = 5
VZ_SIZE = 6

STUCK = 0
START = 1
SLIDE = 2
FINISH = 3
#: a slide slowing to a stop, by series in λ = ln(s0/s) (:func:`_series_log`), down to the finish's speed
APPROACH = 4
#: the approach is entered in SLIDE below this speed, as a fraction of v_ref, when slowing and when a piece in time
#: is shorter than APPROACH_ENTRY × the time to the stop s/|ṡ| (the stop's singularity limits it); after an
#: approach that found the slab not stopping, only below half the speed it left at
APPROACH_SPEED = 1e-2
APPROACH_ENTRY = 1.0
#: an approach piece shorter than this in λ: ṡ is near zero, the slab is not stopping: back to SLIDE
APPROACH_MIN = 0.02

#: a departure from rest at a break-away with µs N = µk N (``DEPART``: the slow manifold's series from the break-away,
#: :func:`_series_depart`) is taken when |D| at the break-away is within this fraction of µk N (else: ``START``)
DEPART_EXCESS = 1e-12
#: the index of departure pieces in the pieces-by-phase counters (a START piece by :func:`_series_depart`)
DEPART = 5
#: a slide's series piece slowing along its starting direction e0 ends where e0·V has fallen to this fraction of its
#: start (else at a half), its length held to (2 STOP_REACH)^(1/N) of the series' reach (docs/building.md)
STOP_REACH = 1.0 / 64.0

BREAKAWAY = 0
STICK = 1
REVERSAL = 2

STATUS_CHATTER = 1
STATUS_EVENTS_TRUNCATED = 2
STATUS_PIECES = 4

# functions whose upward zero crossing is an event
PHI_BREAK = 0  # |D|² − (µs N)²
PHI_STOP_START = 1  # −D·V
PHI_SWITCH = 2  # |V|² − r_sw²
PHI_HALF = 3  # r0/2 − e0·V
PHI_STOP_FINISH = 4  # −e0·V

# summary vector
S_E_INPUT = 0
S_E_FRICTION = 1
S_E_VISCOUS = 2
S_SLIP_TIME = 3
S_N_EVENTS = 4
S_STATUS = 5
S_N_PIECES = 6
S_N_LOCATED = 7
S_N_FAST = 8
#: fast sub-steps refused: the friction's series not at rounding, its end check, an event possible, V = 0
S_N_REFUSED = 9
#: series pieces by phase: stuck, start, slide, finish (where the time goes: docs/building.md, Speed)
S_N_PIECES_BY_MODE = 13
#: stuck, start, slide, finish, approach and departure (``DEPART``) pieces
N_PIECE_KINDS = 6
#: slides whose slowing piece ran to the stop itself (law[9])
S_N_STOP_PIECES = 19
SUMMARY_SIZE = 20

#: Fast sub-steps (stuck or sliding, a uniform record): the longest, as ρ(A) h [-].  Within it a
#: watched quantity's slope changes sign at most once (the fastest mode turns by less than π/2).
THETA_FAST = 1.5
#: Rungs of the fast sub-steps' ladder h, h/2 … h/2^(FAST_LEVELS − 1) (near events the longest that the
#: friction's series allows; series pieces below the shortest).
FAST_LEVELS = 6
#: Degree of the friction's polynomial F(τ) = Σ F_k τ^k in a fast sub-step (its chain in the augmented state).
FAST_ORDER = 24
#: Terms of the watched quantities' series in a fast sub-step (an interior extreme is a root of it);
#: with ρ h ≤ THETA_FAST the remainder is below 1.5^31/31! < 1e-28 of the fastest mode's amplitude.
FAST_POW = 31
#: The friction at the sub-step's end from its polynomial and from V/|V| of the propagated state agree to
#: this fraction of µk N, or the sub-step is redone by series pieces (a safety net under the truncation rule).
#: The kernel reads it from law[11] (``planar_building.FAST_CHECK``); this is the default.
FAST_CHECK = 1e-12
#: Truncation tolerance of the friction's polynomial in a fast sub-step (Jorba–Zou: its last two terms and |V|'s
#: below this fraction of µk N and of |V|), the same fraction FAST_CHECK accepts at the end.  The friction's error
#: is then ≤ 1e-12 µk N over a sub-step (h ≤ 1.5/ρ(A)): a force of that size over h moves the state by ~1e-15 of
#: its scale, so the answers move at rounding (the bench case 4e-14 of its peaks against 1e-16, docs/building.md
#: "h114"); the rungs near stops and departures lengthen as (1e-12/1e-16)^(1/K), and the series pieces keep
#: TRUNC_EPS.  The kernel reads it from law[10] (``planar_building.FAST_TRUNC_EPS``); this is the default.
FAST_TRUNC_EPS = 1e-12


@njit(cache=True, inline="always")
def _sq_norm_term(ws, k):
    """The order-k coefficient of |V|² = V·V from V's two directions' coefficients ws[d, 0 … k] (a Cauchy product,
    j ascending).  Inlined by numba (no call in the fast sub-step), shared by the series pieces and the sub-step."""
    acc = 0.0
    for j in range(k + 1):
        acc += ws[0, j] * ws[0, k - j] + ws[1, j] * ws[1, k - j]
    return acc


@njit(cache=True)
def _series(mode, z, a0, b, a_mat, g_vec, p_vec, l_d, slab_mass, mu_k_n, e_frozen, zs, fs, ws, ss, rs, es, vz, mus,
            exs, h_scale):
    """Taylor coefficients zs[d, k, :] of the state and fs[d, k] of the friction force in the scaled time x = τ/H.

    H = ``h_scale`` [s] (stored in zs[0, −1, 0], read by :func:`_eval`, :func:`_piece_limit`, :func:`_energies`):
    the coefficients are Z_k H^k.  Near a stop V/|V| has its radius of convergence at the stop, u ahead, and its
    coefficients in τ grow as u^{−k}: at |V| ~ 1e-11 m/s (u ~ 1e-10 s) order 30 overflowed (1e308) and the state
    became NaN; with H of the order of the piece they stay of the state's size, whatever the order.

    ws, ss, rs, es: scratch series of the direction's vector w (V or D), s = w·w, r = sqrt(s), e = w / r.
    vz: the vertical and µ(v) (``V_*``; mu_k_n is then µ_fast W).  With them the friction is µ(|V|) N(τ) V/|V|,
    N(τ) = W (ν0 + ν1 τ) and µ(r) = µ_fast − (µ_fast − µ_slow) e^{−a r}: mus[k] is the series of µ N (a product
    with the exponential's series exs, E' = −a r' E), fs the product of mus and e; a pendulum's restoring
    force gains −k_v (ν(τ) − 1) X, a product with the linear ν.  Leaving rest (START) and finishing a stop
    (FINISH) use µ(0) = µ_slow (|V| below 1e-5 v_ref and 1e-10 v_ref there).
    """
    varying = vz[V_VARYING] != 0.0
    nu0 = vz[V_NU0]
    nu1 = vz[V_NU1] * h_scale  # d/dx = H d/dτ
    k_v = vz[V_K_VERT]
    mu_0_n = mu_k_n - vz[V_DMU_N]
    m = z.shape[1]
    ns = zs.shape[1] - 1
    zs[0, ns, 0] = h_scale
    b_x = h_scale * b[0]
    b_y = h_scale * b[1]
    mat = 0 if mode == STUCK else 1
    for d in range(2):
        for i in range(m):
            zs[d, 0, i] = z[d, i]
    for k in range(ns - 1):
        # the friction coefficients of order k
        if mode == STUCK:
            fs[0, k] = 0.0
            fs[1, k] = 0.0
        elif mode == FINISH:
            for d in range(2):
                if varying:
                    fs[d, k] = mu_0_n * e_frozen[d] * (nu0 if k == 0 else (nu1 if k == 1 else 0.0))
                else:
                    fs[d, k] = mu_k_n * e_frozen[d] if k == 0 else 0.0
        else:
            for d in range(2):
                if mode == SLIDE:
                    ws[d, k] = zs[d, k, 1]
                else:
                    acc = -slab_mass * (a0[d] if k == 0 else ((b_x if d == 0 else b_y) if k == 1 else 0.0))
                    for i in range(m):
                        acc += l_d[d, i] * zs[d, k, i]
                    if varying:
                        acc -= k_v * ((nu0 - 1.0) * zs[d, k, 0] + (nu1 * zs[d, k - 1, 0] if k > 0 else 0.0))
                    ws[d, k] = acc
            ss[k] = _sq_norm_term(ws, k)
            if k == 0:
                rs[0] = math.sqrt(ss[0])
            else:
                acc = ss[k]
                for j in range(1, k):
                    acc -= rs[j] * rs[k - j]
                rs[k] = acc / (2.0 * rs[0]) if rs[0] > 0.0 else 0.0
            for d in range(2):
                acc = ws[d, k]
                for j in range(k):
                    acc -= es[d, j] * rs[k - j]
                es[d, k] = acc / rs[0] if rs[0] > 0.0 else 0.0
                if not varying:
                    fs[d, k] = mu_k_n * es[d, k]
            if varying:
                nu_k = nu0 if k == 0 else (nu1 if k == 1 else 0.0)
                if mode == SLIDE:
                    if k == 0:
                        exs[0] = math.exp(-vz[V_RATE] * rs[0])
                    else:
                        acc = 0.0
                        for j in range(1, k + 1):
                            acc += j * rs[j] * exs[k - j]
                        exs[k] = -vz[V_RATE] * acc / k
                    mus[k] = mu_k_n * nu_k - vz[V_DMU_N] * (exs[k] * nu0 + (exs[k - 1] * nu1 if k > 0 else 0.0))
                else:
                    mus[k] = mu_0_n * nu_k
                for d in range(2):
                    acc = 0.0
                    for j in range(k + 1):
                        acc += mus[j] * es[d, k - j]
                    fs[d, k] = acc
        nf = (m - 2) // 2
        for d in range(2):
            ak = a0[d] if k == 0 else ((b_x if d == 0 else b_y) if k == 1 else 0.0)
            inv = h_scale / (k + 1)
            # displacement rows: x_b' = v_b (sliding; 0 stuck), u' = u̇ (the matrices' structure, checked in Python)
            zs[d, k + 1, 0] = zs[d, k, 1] * inv if mat == 1 else 0.0
            for i in range(2, 2 + nf):
                zs[d, k + 1, i] = zs[d, k, i + nf] * inv
            for i in range(m):
                if i == 0 or 2 <= i < 2 + nf:
                    continue
                if mat == 1:
                    f_slab = fs[d, k]
                    if varying:
                        f_slab += k_v * ((nu0 - 1.0) * zs[d, k, 0] + (nu1 * zs[d, k - 1, 0] if k > 0 else 0.0))
                    acc = g_vec[mat, d, i] * ak + p_vec[d, i] * f_slab
                else:
                    acc = g_vec[mat, d, i] * ak
                for c in range(m):
                    acc += a_mat[mat, d, i, c] * zs[d, k, c]
                zs[d, k + 1, i] = acc * inv
    for d in range(2):
        fs[d, ns - 1] = 0.0


@njit(cache=True)
def _last_terms(zs, n, weights, floor_scale):
    """The weighted size of the state (at least floor_scale) and of the series' terms n and n − 1, over both directions."""
    size = floor_scale
    top1 = 0.0
    top2 = 0.0
    for d in range(2):
        for i in range(zs.shape[2]):
            size = max(size, abs(zs[d, 0, i]) * weights[i])
            top1 = max(top1, abs(zs[d, n, i]) * weights[i])
            top2 = max(top2, abs(zs[d, n - 1, i]) * weights[i])
    return size, top1, top2


@njit(cache=True)
def _piece_limit(zs, weights, floor_scale):
    """Longest τ [s] for which the series' last two terms stay below TRUNC_EPS of the state (Jorba–Zou)."""
    n_last = zs.shape[1] - 4
    h_scale = zs[0, n_last + 3, 0]
    size, top1, top2 = _last_terms(zs, n_last, weights, floor_scale)
    limit = 1e300
    if top1 > 0.0:
        limit = min(limit, (TRUNC_EPS * size / top1) ** (1.0 / n_last))
    if top2 > 0.0:
        limit = min(limit, (TRUNC_EPS * size / top2) ** (1.0 / (n_last - 1)))
    if not limit >= 0.0:
        return 0.0  # coefficients not finite (H far beyond the radius): the caller rescales
    return limit * h_scale if limit < 1e300 else 1e300


@njit(cache=True, _nrt=False)
def _eval(zs, tau, z, zd, zdd):
    """z(τ), ż(τ), z̈(τ) of both directions from the series in x = τ/H (Horner; :func:`_series`)."""
    m = zs.shape[2]
    n_ord = zs.shape[1] - 4
    h_scale = zs[0, n_ord + 3, 0]
    inv_h = 1.0 / h_scale
    inv_h2 = inv_h * inv_h
    if tau == 0.0:
        for d in range(2):
            for i in range(m):
                z[d, i] = zs[d, 0, i]
                zd[d, i] = zs[d, 1, i] * inv_h
                zdd[d, i] = 2.0 * zs[d, 2, i] * inv_h2
        return
    tau = tau * inv_h
    for d in range(2):
        for i in range(m):
            acc = zs[d, n_ord, i]
            accd = (n_ord + 1) * zs[d, n_ord + 1, i]
            accdd = (n_ord + 1) * (n_ord + 2) * zs[d, n_ord + 2, i]
            for k in range(n_ord - 1, -1, -1):
                acc = zs[d, k, i] + acc * tau
                accd = (k + 1) * zs[d, k + 1, i] + accd * tau
                accdd = (k + 1) * (k + 2) * zs[d, k + 2, i] + accdd * tau
            z[d, i] = acc
            zd[d, i] = accd * inv_h
            zdd[d, i] = accdd * inv_h2


@njit(cache=True, _nrt=False)
def _dot(a, b):
    acc = 0.0
    for i in range(a.shape[0]):
        acc += a[i] * b[i]
    return acc


@njit(cache=True, _nrt=False)
def _phi(kind, z, zd, ax_now, ay_now, tau_now, b, l_d, slab_mass, target, e0, vz, out):
    """Value and slope of the event function ``kind`` at a point (its upward zero crossing is the event).

    vz: the vertical and µ(v) of the piece (:func:`_series`); with a vertical the force on the slab other than
    friction holds the pendulum's extra restoring force −k_v (ν(τ) − 1) X and the static limit is µs N ν(τ).
    """
    _phi_core(kind, _dot(l_d[0], z[0]) - slab_mass * ax_now, _dot(l_d[1], z[1]) - slab_mass * ay_now,
              _dot(l_d[0], zd[0]) - slab_mass * b[0], _dot(l_d[1], zd[1]) - slab_mass * b[1], z[0, 0], z[1, 0],
              zd[0, 0], zd[1, 0], z[0, 1], z[1, 1], zd[0, 1], zd[1, 1], tau_now, target, e0, vz, out)


@njit(cache=True, _nrt=False)
def _phi_core(kind, dx, dy, ddx, ddy, x, y, xd, yd, vx, vy, avx, avy, tau_now, target, e0, vz, out):
    """:func:`_phi` from the force on the slab D (dx, dy; ḊD: ddx, ddy), the slab's position (x, y; ẋ: xd, yd) and
    speed (vx, vy; v̇: avx, avy)."""
    if vz[V_VARYING] != 0.0:
        nu = vz[V_NU0] + vz[V_NU1] * tau_now
        k_v = vz[V_K_VERT]
        dx -= k_v * (nu - 1.0) * x
        dy -= k_v * (nu - 1.0) * y
        ddx -= k_v * (vz[V_NU1] * x + (nu - 1.0) * xd)
        ddy -= k_v * (vz[V_NU1] * y + (nu - 1.0) * yd)
        if kind == PHI_BREAK:
            out[0] = dx * dx + dy * dy - (target * nu) ** 2
            out[1] = 2.0 * (dx * ddx + dy * ddy) - 2.0 * target * target * nu * vz[V_NU1]
            return
    if kind == PHI_BREAK:
        out[0] = dx * dx + dy * dy - target * target
        out[1] = 2.0 * (dx * ddx + dy * ddy)
    elif kind == PHI_STOP_START:
        out[0] = -(dx * vx + dy * vy)
        out[1] = -(ddx * vx + ddy * vy + dx * avx + dy * avy)
    elif kind == PHI_SWITCH:
        out[0] = vx * vx + vy * vy - target * target
        out[1] = 2.0 * (vx * avx + vy * avy)
    elif kind == PHI_HALF:
        out[0] = target - (e0[0] * vx + e0[1] * vy)
        out[1] = -(e0[0] * avx + e0[1] * avy)
    else:
        out[0] = -(e0[0] * vx + e0[1] * vy)
        out[1] = -(e0[0] * avx + e0[1] * avy)


@njit(cache=True, _nrt=False)
def _phi_at(kind, zs, tau, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out):
    _eval(zs, tau, z, zd, zdd)
    _phi(kind, z, zd, a0[0] + b[0] * tau, a0[1] + b[1] * tau, tau, b, l_d, slab_mass, target, e0, vz, out)


@njit(cache=True, _nrt=False)
def _root(kind, zs, lo, hi, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out):
    """The instant in (lo, hi] where φ rises through zero (φ(lo) ≤ 0 < or = φ(hi)); safeguarded Newton."""
    a = lo
    c = hi
    _phi_at(kind, zs, lo, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out)
    f_lo = out[0]
    _phi_at(kind, zs, hi, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out)
    f_hi = out[0]
    t = 0.5 * (lo + hi)
    if f_hi != f_lo:
        guess = lo + (hi - lo) * (-f_lo) / (f_hi - f_lo)
        if lo < guess < hi:
            t = guess
    resolution = 4e-16 * max(abs(hi), abs(lo), 1e-300)
    for _ in range(200):
        _phi_at(kind, zs, t, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out)
        f = out[0]
        if f == 0.0:
            return t
        if f < 0.0:
            a = t
        else:
            c = t
        if c - a <= resolution:
            return c
        t_new = t - f / out[1] if out[1] != 0.0 else 0.5 * (a + c)
        if not (a < t_new < c):
            t_new = 0.5 * (a + c)
        elif abs(t_new - t) <= resolution:
            return max(t_new, a)
        t = t_new
    return c


@njit(cache=True, _nrt=False)
def _first_crossing(kind, zs, length, a0, b, l_d, slab_mass, target, e0, vz, from_rest, z, zd, zdd, out, counter,
                    z_lo, zd_lo, z_hi, zd_hi):
    """First upward zero crossing of φ in [0, length], or −1.

    From the values and slopes at both ends and the one interior maximum, located when the slope
    falls through zero and φ could reach zero there (as the 1-D kernels do).  ``from_rest``: φ(0) = 0
    is the start, not a crossing (a block leaving rest): a crossing after the first maximum counts.
    z_lo, zd_lo, z_hi, zd_hi: the state and its rate at 0 and at ``length``.
    """
    _phi(kind, z_lo, zd_lo, a0[0], a0[1], 0.0, b, l_d, slab_mass, target, e0, vz, out)
    f0 = out[0]
    s0 = out[1]
    if f0 > 0.0 and not from_rest:
        return 0.0
    _phi(kind, z_hi, zd_hi, a0[0] + b[0] * length, a0[1] + b[1] * length, length, b, l_d, slab_mass, target, e0, vz, out)
    f1 = out[0]
    s1 = out[1]
    if from_rest:
        # leaving rest: φ first falls (e.g. −D·V) — a stop needs φ back up through zero
        if f1 <= 0.0:
            return -1.0
        if s0 < 0.0 and s1 > 0.0:
            lo = _slope_root(kind, zs, 0.0, length, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out, -1.0)
            counter[0] += 1
            return _root(kind, zs, lo, length, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out)
        return 0.0  # it cannot leave rest in this direction: at once
    if f1 > 0.0:
        return _root(kind, zs, 0.0, length, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out)
    reach = 2.0 * length * max(abs(s0), abs(s1))
    if s0 > 0.0 and s1 < 0.0 and max(f0, f1) + reach > 0.0:
        counter[0] += 1
        t_m = _slope_root(kind, zs, 0.0, length, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out, 1.0)
        _phi_at(kind, zs, t_m, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out)
        if out[0] > 0.0:
            return _root(kind, zs, 0.0, t_m, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out)
    return -1.0


@njit(cache=True, _nrt=False)
def _illinois_done(a, c, fa, fc):
    """The bracket [a, c] of a sign change of f (f(a) > 0 > f(c)) is at rounding, or cannot be refined."""
    return c - a <= 4e-16 * max(abs(c), 1e-300) or fa == fc


@njit(cache=True, _nrt=False)
def _illinois_point(a, c, fa, fc):
    """The next trial point in (a, c): the secant's, or the midpoint when that falls outside."""
    t = (a * fc - c * fa) / (fc - fa)
    return t if a < t < c else 0.5 * (a + c)


@njit(cache=True, _nrt=False)
def _illinois_bracket(t, f, a, c, fa, fc, side):
    """The bracket after f(t) = f ≠ 0 (Illinois: the end kept twice in a row has its value halved, so that the
    secant does not stall on one side).  Returns (a, c, fa, fc, side); side +1 when t replaced a, −1 c.

    One rule for the three sign-change searches of this kernel (:func:`_slope_root`, :func:`_locate_max`,
    :func:`_poly_max`), which differ only in the function they evaluate."""
    if f > 0.0:
        if side == 1:
            fc *= 0.5
        return t, c, f, fc, 1
    if side == -1:
        fa *= 0.5
    return a, t, fa, f, -1


@njit(cache=True, _nrt=False)
def _slope_root(kind, zs, lo, hi, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out, sign):
    """Where φ' changes sign (sign = +1: from + to −, a maximum), by Illinois on the slope."""
    _phi_at(kind, zs, lo, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out)
    fa = sign * out[1]
    _phi_at(kind, zs, hi, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out)
    fc = sign * out[1]
    a = lo
    c = hi
    side = 0
    for _ in range(200):
        if _illinois_done(a, c, fa, fc):
            break
        t = _illinois_point(a, c, fa, fc)
        _phi_at(kind, zs, t, a0, b, l_d, slab_mass, target, e0, vz, z, zd, zdd, out)
        f = sign * out[1]
        if f == 0.0:
            return t
        a, c, fa, fc, side = _illinois_bracket(t, f, a, c, fa, fc, side)
    return 0.5 * (a + c)


@njit(cache=True, _nrt=False)
def _monitors(z, zd, zdd, ax_now, ay_now, az_now, b, m1, m2, m3, sig1, sig2, sig3, val, slope, sval, sslope):
    """Watched quantities at a point: resultant pairs val[k, d] (slope[k, d]) and signed sval[j].

    The signed ones hold the vertical too: sig3[j, 2] a_z (a bearing's share of the floors' vertical inertia;
    b[2] = ȧ_z)."""
    nk = m1.shape[0]
    for k in range(nk):
        for d in range(2):
            val[k, d] = _dot(m1[k, d], z[d]) + _dot(m2[k, d], zd[d]) + m3[k, d] * (ax_now if d == 0 else ay_now)
            slope[k, d] = _dot(m1[k, d], zd[d]) + _dot(m2[k, d], zdd[d]) + m3[k, d] * b[d]
    for j in range(sig1.shape[0]):
        v = 0.0
        s = 0.0
        for d in range(2):
            v += _dot(sig1[j, d], z[d]) + _dot(sig2[j, d], zd[d]) + sig3[j, d] * (ax_now if d == 0 else ay_now)
            s += _dot(sig1[j, d], zd[d]) + _dot(sig2[j, d], zdd[d]) + sig3[j, d] * b[d]
        sval[j] = v + sig3[j, 2] * az_now
        sslope[j] = s + sig3[j, 2] * b[2]


@njit(cache=True, _nrt=False)
def _monitor_slope_at(zs, tau, a0, b, m1, m2, m3, sig1, sig2, sig3, k, kind, z, zd, zdd, val, slope, sval, sslope,
                      lz, lzd, lt, on_log):
    """Slope of one watched quantity at τ: kind 0 the resultant's ½|P|², 1 a signed value, −1 its negative.

    ``on_log``: τ is λ of an approach piece (lz, lzd, lt; :func:`_series_log`), whose time t(λ) increases: the time
    slope returned has the sign of the slope in λ."""
    if on_log:
        tau = _eval_log(lz, lzd, lt, tau, z, zd, zdd)
    else:
        _eval(zs, tau, z, zd, zdd)
    _monitors(z, zd, zdd, a0[0] + b[0] * tau, a0[1] + b[1] * tau, a0[2] + b[2] * tau, b, m1, m2, m3, sig1, sig2, sig3, val, slope, sval,
              sslope)
    if kind == 0:
        return val[k, 0] * slope[k, 0] + val[k, 1] * slope[k, 1], val[k, 0] ** 2 + val[k, 1] ** 2
    return kind * sslope[k], kind * sval[k]


@njit(cache=True, _nrt=False)
def _locate_max(zs, length, a0, b, m1, m2, m3, sig1, sig2, sig3, k, kind, z, zd, zdd, val, slope, sval, sslope, lz, lzd,
                lt, on_log):
    """The interior maximum of a watched quantity in [0, length] (its slope from + to −), by Illinois (``on_log``:
    length is in λ of an approach piece)."""
    a = 0.0
    c = length
    fa, _ = _monitor_slope_at(zs, a, a0, b, m1, m2, m3, sig1, sig2, sig3, k, kind, z, zd, zdd, val, slope, sval,
                              sslope, lz, lzd, lt, on_log)
    fc, _ = _monitor_slope_at(zs, c, a0, b, m1, m2, m3, sig1, sig2, sig3, k, kind, z, zd, zdd, val, slope, sval,
                              sslope, lz, lzd, lt, on_log)
    best = -1e300
    side = 0
    for _ in range(200):
        if _illinois_done(a, c, fa, fc):
            break
        t = _illinois_point(a, c, fa, fc)
        f, v = _monitor_slope_at(zs, t, a0, b, m1, m2, m3, sig1, sig2, sig3, k, kind, z, zd, zdd, val, slope,
                                 sval, sslope, lz, lzd, lt, on_log)
        best = max(best, v)
        if f == 0.0:
            break
        a, c, fa, fc, side = _illinois_bracket(t, f, a, c, fa, fc, side)
    return best


@njit(cache=True, _nrt=False)
def _add_viscous_power(zd, c_iso, c_floor_d, nf, n, y, pvis):
    """Add to ``pvis[0:n]`` the series of one direction's viscous power c V² + u̇ᵀ C u̇ from its state's series
    ``zd[k, :]`` (V in column 1, the floors' u̇ in columns 2 + nf …; ``y`` scratch for C u̇)."""
    for k in range(n):
        for i in range(nf):
            acc = 0.0
            for j in range(nf):
                acc += c_floor_d[i, j] * zd[k, 2 + nf + j]
            y[k, i] = acc
    for ell in range(n):
        acc = 0.0
        for j in range(ell + 1):
            acc += c_iso * zd[j, 1] * zd[ell - j, 1]
            for i in range(nf):
                acc += zd[j, 2 + nf + i] * y[ell - j, i]
        pvis[ell] += acc


@njit(cache=True)
def _energies(mode, zs, fs, tau, a0, b, total_mass, masses, c_iso, c_floor, nf, out, pin, pfr, pvis, y, vz):
    """Exact integrals over [0, τ] of the input, friction and viscous powers from the series (scratch pin … y).

    With a vertical the input holds the vertical's work ½ k_v ν1 ∫|X|² dτ (d/dt of ½ k_v ν X² less k_v ν X·V,
    as the 2-D rigid block counts it), so that input = kinetic + ½ k_v ν X² + strain + friction + viscous.
    """
    nt = zs.shape[1] - 3
    h_scale = zs[0, nt + 2, 0]
    # in x = τ/H: the ground's slope is b H, and ∫₀^τ dτ = H ∫₀^{τ/H} dx
    b_x = b[0] * h_scale
    b_y = b[1] * h_scale
    pin[:] = 0.0
    pfr[:] = 0.0
    pvis[:] = 0.0
    if vz[V_VARYING] != 0.0 and vz[V_NU1] != 0.0:
        half_rate = 0.5 * vz[V_K_VERT] * vz[V_NU1]
        for d in range(2):
            for ell in range(nt):
                acc = 0.0
                for j in range(ell + 1):
                    acc += zs[d, j, 0] * zs[d, ell - j, 0]
                pin[ell] += half_rate * acc
    for d in range(2):
        # input: −a_d (M V + Σ m_i u̇_i) = −a_d × (total relative momentum)
        for k in range(nt):
            mom = total_mass * zs[d, k, 1]
            for i in range(nf):
                mom += masses[i] * zs[d, k, 2 + nf + i]
            pin[k] -= a0[d] * mom
            pin[k + 1] -= (b_x if d == 0 else b_y) * mom
        # viscous: c V² + u̇ᵀ C u̇
        _add_viscous_power(zs[d], c_iso, c_floor[d], nf, nt, y, pvis)
        if mode != STUCK:
            for ell in range(nt):
                acc = 0.0
                for j in range(ell + 1):
                    acc += fs[d, j] * zs[d, ell - j, 1]
                pfr[ell] += acc
    # Horner on Σ c_k x^{k+1}/(k+1), x = τ/H, times H
    tau = tau / h_scale
    e_in = 0.0
    e_f = 0.0
    e_v = 0.0
    for k in range(nt, -1, -1):
        e_in = e_in * tau + pin[k] / (k + 1)
    e_in *= tau
    for k in range(nt - 1, -1, -1):
        e_f = e_f * tau + pfr[k] / (k + 1)
        e_v = e_v * tau + pvis[k] / (k + 1)
    out[0] = e_in * h_scale
    out[1] = e_f * tau * h_scale
    out[2] = e_v * tau * h_scale


@njit(cache=True)
def _series_log(w, a0, b, a_mat, g_vec, p_vec, mu_k_n, grow, lz, lzd, lt, le, lq, lrate, ltp, lex, la):
    """Taylor coefficients in λ = g ln(s/s0) of a slide slowing to a stop (g = ``grow`` = −1) or speeding up after
    a start from rest (g = +1) (``APPROACH``; s = |V| the slab's speed).

    Near a stop (and just after a start) V/|V| turns as a power of s and the series in time has its radius at the
    stop (docs/building.md, Speed); with the speed's logarithm as the independent variable the equations are
    regular: with V = s e, ṡ = e·V̇ and σ = ln s, de/dσ = V̇/ṡ − e, dt/dσ = s/ṡ, dz/dσ = ż dt/dσ, s = s0 e^{gλ}.
    lz[d, k, :] the state (V_k = (s e)_k), lzd[d, k, :] its time rates ż (the sliding rows: the same equations as
    :func:`_series`), lt the time from the piece's start [s], le the direction e, lex s, la the ground's a_d(t(λ)),
    lrate ṡ, ltp dt/dλ, lq V̇/ṡ.  Returns ṡ at the start [m/s²]; the series is only valid when g ṡ > 0.
    """
    m = w.shape[1]
    nf = (m - 2) // 2
    nl = lt.shape[0] - 1
    s0 = math.sqrt(w[0, 1] ** 2 + w[1, 1] ** 2)
    coef = s0
    for k in range(nl + 1):
        lex[k] = coef  # s0 g^k / k!
        coef = grow * coef / (k + 1)
    for d in range(2):
        for i in range(m):
            lz[d, 0, i] = w[d, i]
        le[d, 0] = w[d, 1] / s0
    lt[0] = 0.0
    for k in range(nl + 1):
        for d in range(2):
            acc = 0.0
            for j in range(k + 1):
                acc += lex[j] * le[d, k - j]
            lz[d, k, 1] = acc
            la[d, k] = a0[d] if k == 0 else b[d] * lt[k]
        for d in range(2):
            lzd[d, k, 0] = lz[d, k, 1]
            for i in range(2, 2 + nf):
                lzd[d, k, i] = lz[d, k, i + nf]
            for i in range(m):
                if i == 0 or 2 <= i < 2 + nf:
                    continue
                acc = g_vec[1, d, i] * la[d, k] + p_vec[d, i] * mu_k_n * le[d, k]
                for c in range(m):
                    acc += a_mat[1, d, i, c] * lz[d, k, c]
                lzd[d, k, i] = acc
        if k == nl:
            break
        acc = 0.0
        for j in range(k + 1):
            acc += le[0, j] * lzd[0, k - j, 1] + le[1, j] * lzd[1, k - j, 1]
        lrate[k] = acc
        if not grow * lrate[0] > 0.0:
            return lrate[0]
        acc = grow * lex[k]
        for j in range(k):
            acc -= ltp[j] * lrate[k - j]
        ltp[k] = acc / lrate[0]
        lt[k + 1] = ltp[k] / (k + 1)
        for d in range(2):
            acc = lzd[d, k, 1]
            for j in range(k):
                acc -= lq[d, j] * lrate[k - j]
            lq[d, k] = acc / lrate[0]
            le[d, k + 1] = grow * (lq[d, k] - le[d, k]) / (k + 1)
            for i in range(m):
                if i == 1:
                    continue
                acc = 0.0
                for j in range(k + 1):
                    acc += lzd[d, j, i] * ltp[k - j]
                lz[d, k + 1, i] = acc / (k + 1)
    return lrate[0]

@njit(cache=True)
def _series_depart(w, a0, b, a_mat, g_vec, p_vec, mu_k_n, zs, fs, ee, rho, h_scale, lag):
    """Taylor coefficients (in x = τ/H, as :func:`_series`) of a departure from rest at V = 0: the slow manifold,
    written V = τ^lag W(τ).  Returns False when that form does not hold.

    ``lag`` = 2: a break-away where |D| = µs N = µk N.  The slab leaves rest with V̇ = 0 and V/|V| is singular at
    the start: a series in time from any later instant τ0 has its radius at the break-away, and the direction's
    relaxation towards D, at the rate µk N/(m_b |V|), makes the series in time stiff (pieces of ≈ 8 m_b |V|/(µk N):
    ~600 pieces per departure on the bench case, docs/building.md).
    ``lag`` = 1: |D| > µk N at V = 0 (a break-away with µs > µk, or a reversal at a stop): the slab leaves with the
    finite acceleration (|D| − µk N)/m_b along D, |V| ∝ τ, and the same relaxation (its rate ∝ 1/τ) made START's
    friction along D (a lag ∝ |V| neglected) and short series pieces in time.

    With V = τ^lag W the direction e = W/|W| is regular at τ = 0, and the equation of the slab's velocity at order k,
    (k + 1) V_{k+1} = H (q_k + p_1 µk N e_k) with V_{k+1} = W_{k+1−lag}, gives e0 = D/|D| at order 0 and then, at
    each order k ≥ 1, a 2×2 linear system for the two unknowns e0·W_{k+1−lag} (along) and n0·e_k (across; n0 ⊥ e0):
    e0·e_k is fixed by |e| = 1 and n0·W by W = |W| e (with lag = 1 it holds n0·e_k |W|_0, a term of the system).
    No division by |V| (the stiff mode is never excited).  With lag = 2 the coefficients grow as k!/κ^k,
    κ = 2 µk N/|Ḋ|; the series is taken, like every other piece, only as far as its last two terms are at rounding
    (Jorba–Zou, :func:`_piece_limit`).  ee[d, k]: the direction's coefficients, rho[k]: those of |W|.
    fs = µk N e (the friction's coefficients).
    """
    m = w.shape[1]
    nf = (m - 2) // 2
    ns = zs.shape[1] - 1
    shift = lag - 1  # V_{k+1} = W_{k − shift}
    zs[0, ns, 0] = h_scale
    b_x = h_scale * b[0]
    b_y = h_scale * b[1]
    for d in range(2):
        for i in range(m):
            zs[d, 0, i] = w[d, i]
        zs[d, 0, 1] = 0.0
    e0x = 0.0
    e0y = 0.0
    w_perp = 0.0  # n0 · W_{k−shift} from the direction's coefficients known before order k
    w_x = 0.0
    w_y = 0.0
    p0 = p_vec[0, 1] * mu_k_n
    p1 = p_vec[1, 1] * mu_k_n
    for k in range(ns - 1):
        q0 = 0.0
        q1 = 0.0
        for d in range(2):
            ak = a0[d] if k == 0 else ((b_x if d == 0 else b_y) if k == 1 else 0.0)
            acc = g_vec[1, d, 1] * ak
            for c in range(m):
                acc += a_mat[1, d, 1, c] * zs[d, k, c]
            if d == 0:
                q0 = acc
            else:
                q1 = acc
        if k == 0:
            if shift == 1:
                # order 0: V_1 = 0, so µk N e0 = −q_0/p_1 = D/m_b × m_b
                ex = -q0 / p0
                ey = -q1 / p1
                norm = math.sqrt(ex * ex + ey * ey)
                if not abs(norm - 1.0) <= DEPART_EXCESS:
                    return False
            else:
                # order 0: W_0/H = q_0 + p µk N e0 with W_0 = |W|_0 e0: e0 along q_0 (D/m_b), |W|_0 > 0 when |D| > µk N
                norm = math.sqrt(q0 * q0 + q1 * q1)
                if not norm > 0.0:
                    return False
                ex = q0
                ey = q1
            e0x = ex / norm
            e0y = ey / norm
            ee[0, 0] = e0x
            ee[1, 0] = e0y
            if shift == 0:
                # along e0, per direction: |W|_0/H = q_d/e0_d + p_d (one value when p_0 = p_1: the slab's mass)
                rho[0] = h_scale * (norm + (p0 * e0x * e0x + p1 * e0y * e0y))
                if not rho[0] > 0.0:
                    return False  # |D| ≤ µk N: the slab does not leave with a finite acceleration
                w_x = rho[0] * e0x
                w_y = rho[0] * e0y
        else:
            n0x = -e0y
            n0y = e0x
            c_par = 0.0
            for j in range(1, k):
                c_par -= 0.5 * (ee[0, j] * ee[0, k - j] + ee[1, j] * ee[1, k - j])
            f = (k + 1) / h_scale
            # u f e0 + c⊥ (f |W|_0 [lag 1] − p µk N) n0 = q − f W⊥ n0 + p µk N c∥ e0, per direction
            # (W⊥ = n0·W_{k−shift} without the term of e_k)
            tie = f * rho[0] if shift == 0 else 0.0
            m00 = f * e0x
            m01 = (tie - p0) * n0x
            m10 = f * e0y
            m11 = (tie - p1) * n0y
            r0 = q0 - f * w_perp * n0x + p0 * c_par * e0x
            r1 = q1 - f * w_perp * n0y + p1 * c_par * e0y
            det = m00 * m11 - m01 * m10
            if not abs(det) > 0.0:
                return False
            u = (r0 * m11 - m01 * r1) / det
            c_perp = (m00 * r1 - m10 * r0) / det
            ee[0, k] = c_par * e0x + c_perp * n0x
            ee[1, k] = c_par * e0y + c_perp * n0y
            w_full = w_perp + (c_perp * rho[0] if shift == 0 else 0.0)
            w_x = u * e0x + w_full * n0x
            w_y = u * e0y + w_full * n0y
            # |W|'s coefficient k − shift from e0·W_{k−shift} = Σ_j (e0·e_j) |W|_{k−shift−j}
            kw = k - shift
            acc = u
            for j in range(1, kw + 1):
                acc -= (e0x * ee[0, j] + e0y * ee[1, j]) * rho[kw - j]
            rho[kw] = acc
            if kw == 0 and not acc > 0.0:
                return False  # |D| not growing at the break-away: no departure of this form
        # n0 · W_{k+1−shift} from e_1 … e_k (the term of e_{k+1}, with lag 1, is a term of the next system)
        kn = k + 1 - shift
        acc = 0.0
        for j in range(1, min(kn, k) + 1):
            acc += ((-e0y) * ee[0, j] + e0x * ee[1, j]) * rho[kn - j]
        w_perp = acc
        for d in range(2):
            fs[d, k] = mu_k_n * ee[d, k]
        for d in range(2):
            ak = a0[d] if k == 0 else ((b_x if d == 0 else b_y) if k == 1 else 0.0)
            inv = h_scale / (k + 1)
            zs[d, k + 1, 0] = zs[d, k, 1] * inv
            for i in range(2, 2 + nf):
                zs[d, k + 1, i] = zs[d, k, i + nf] * inv
            for i in range(m):
                if i == 0 or 2 <= i < 2 + nf:
                    continue
                acc = g_vec[1, d, i] * ak + p_vec[d, i] * fs[d, k]
                for c in range(m):
                    acc += a_mat[1, d, i, c] * zs[d, k, c]
                zs[d, k + 1, i] = acc * inv
            # the slab's velocity: V_{k+1} = W_{k−shift} (the recurrence's value to rounding, exact by construction)
            zs[d, k + 1, 1] = (w_x if d == 0 else w_y) if k >= shift else 0.0
    for d in range(2):
        fs[d, ns - 1] = 0.0
    return True


@njit(cache=True)
def _next_scale(limit, h_scale, rem, h_max):
    """The series' time scale H [s] to redo a piece's series with, or 0.0 when H = ``h_scale`` suits the piece's
    limit [s] (within 1e-3 H … 1e6 H)."""
    if limit < 1e-3 * h_scale:
        # H far beyond the radius (coefficients growing as (H/radius)^k, or overflowing)
        return max(limit, 1e-6 * h_scale)
    if limit > 1e6 * h_scale and h_scale < min(rem, h_max):
        # H far below it (the last coefficients could underflow): the piece's own length
        return min(rem, h_max, limit)
    return 0.0


@njit(cache=True, _nrt=False)
def _jz(size, top, order):
    """The Jorba–Zou length at which a term top·h^order is TRUNC_EPS of size (1e300 when top is 0)."""
    if top > 0.0:
        return (TRUNC_EPS * size / top) ** (1.0 / order)
    return 1e300


@njit(cache=True)
def _log_limit(lz, lt, le, weights, floor_scale):
    """Longest λ for which the approach's series (state, direction, time) have their last two terms at rounding."""
    nl = lt.shape[0] - 1
    size, top1, top2 = _last_terms(lz, nl, weights, floor_scale)
    limit = min(_jz(size, top1, nl), _jz(size, top2, nl - 1))
    limit = min(limit, _jz(1.0, max(abs(le[0, nl]), abs(le[1, nl])), nl),
                _jz(1.0, max(abs(le[0, nl - 1]), abs(le[1, nl - 1])), nl - 1))
    # the time relative to what one unit of λ takes
    return min(limit, _jz(abs(lt[1]), abs(lt[nl]), nl), _jz(abs(lt[1]), abs(lt[nl - 1]), nl - 1))


@njit(cache=True, _nrt=False)
def _eval_log(lz, lzd, lt, lam, z, zd, zdd):
    """z, ż and z̈ at λ of an approach piece (:func:`_series_log`; z̈ = (dż/dλ)/(dt/dλ)); returns t(λ) [s]."""
    nl = lt.shape[0] - 1
    t = 0.0
    tp = 0.0
    for k in range(nl, -1, -1):
        tp = tp * lam + t
        t = t * lam + lt[k]
    for d in range(2):
        for i in range(lz.shape[2]):
            v = 0.0
            r = 0.0
            dr = 0.0
            for k in range(nl, -1, -1):
                v = v * lam + lz[d, k, i]
                dr = dr * lam + r
                r = r * lam + lzd[d, k, i]
            z[d, i] = v
            zd[d, i] = r
            zdd[d, i] = dr / tp
    return t


@njit(cache=True)
def _log_time_root(lt, target, hi):
    """λ in [0, hi] where the approach's time t(λ) (increasing) reaches ``target`` [s]: safeguarded Newton."""
    nl = lt.shape[0] - 1
    a = 0.0
    c = hi
    x = hi * 0.5
    for _ in range(200):
        t = 0.0
        tp = 0.0
        for k in range(nl, -1, -1):
            tp = tp * x + t
            t = t * x + lt[k]
        f = t - target
        if f == 0.0:
            return x
        if f < 0.0:
            a = x
        else:
            c = x
        if c - a <= 4e-16 * c:
            return a
        x_new = x - f / tp if tp > 0.0 else 0.5 * (a + c)
        if not (a < x_new < c):
            x_new = 0.5 * (a + c)
        x = x_new
    return a


@njit(cache=True)
def _energies_log(lz, la, ltp, lex, lam, total_mass, masses, c_iso, c_floor, mu_k_n, out, pin, pvis, lmom, y):
    """Exact integrals over [0, λ] of an approach piece of the input, friction and viscous powers (the powers'
    series in λ times dt/dλ, as :func:`_energies` does in time); the friction's power is µk N s."""
    nl = ltp.shape[0] - 1  # ltp holds orders 0 … nl − 1
    nf = masses.shape[0]
    for ell in range(nl):
        pin[ell] = 0.0
        pvis[ell] = 0.0
    for d in range(2):
        for k in range(nl):
            acc = total_mass * lz[d, k, 1]
            for i in range(nf):
                acc += masses[i] * lz[d, k, 2 + nf + i]
            lmom[k] = acc
        for ell in range(nl):
            acc_i = 0.0
            for j in range(ell + 1):
                acc_i -= la[d, j] * lmom[ell - j]
            pin[ell] += acc_i
        _add_viscous_power(lz[d], c_iso, c_floor[d], nf, nl, y, pvis)
    e_in = 0.0
    e_f = 0.0
    e_v = 0.0
    for ell in range(nl - 1, -1, -1):
        c_i = 0.0
        c_f = 0.0
        c_v = 0.0
        for j in range(ell + 1):
            c_i += pin[j] * ltp[ell - j]
            c_f += lex[j] * ltp[ell - j]
            c_v += pvis[j] * ltp[ell - j]
        e_in = e_in * lam + c_i / (ell + 1)
        e_f = e_f * lam + c_f / (ell + 1)
        e_v = e_v * lam + c_v / (ell + 1)
    out[0] = e_in * lam
    out[1] = mu_k_n * e_f * lam
    out[2] = e_v * lam


@njit(cache=True, _nrt=False)
def _poly_value_slope(c, nterm, t):
    """Σ_{j<nterm} c[j] t^j and its derivative (Horner)."""
    v = c[nterm - 1]
    dv = 0.0
    for j in range(nterm - 2, -1, -1):
        dv = dv * t + v
        v = v * t + c[j]
    return v, dv


@njit(cache=True, _nrt=False)
def _poly_slope_at(cp, kind, nterm, t):
    """(slope, value) at t of ½|P|² (kind 0; the value returned is |P|²) or of ±P (kind ±1), from the series cp."""
    if kind == 0:
        vx, dx = _poly_value_slope(cp[0], nterm, t)
        vy, dy = _poly_value_slope(cp[1], nterm, t)
        return vx * dx + vy * dy, vx * vx + vy * vy
    v, dv = _poly_value_slope(cp[0], nterm, t)
    return kind * dv, kind * v


@njit(cache=True, _nrt=False)
def _poly_max(cp, kind, nterm, h):
    """Largest value in [0, h] of ½|P|² (kind 0: cp[0], cp[1] the series of P_x, P_y) or of ±P (kind ±1:
    cp[0]), where its slope falls through zero (Illinois on the slope, as :func:`_locate_max`)."""
    a = 0.0
    c = h
    best = -1e300
    fa, _ = _poly_slope_at(cp, kind, nterm, a)
    fc, _ = _poly_slope_at(cp, kind, nterm, c)
    side = 0
    for _ in range(200):
        if _illinois_done(a, c, fa, fc):
            break
        t = _illinois_point(a, c, fa, fc)
        f, v = _poly_slope_at(cp, kind, nterm, t)
        best = max(best, v)
        if f == 0.0:
            break
        a, c, fa, fc, side = _illinois_bracket(t, f, a, c, fa, fc, side)
    return best


@njit(cache=True, _nrt=False)
def _rows_series(rows, wa, s_eff, nterm, out, slot):
    """out[slot, j] += rows[d, j, :s_eff] · wa[d, :s_eff] summed over both directions when rows is
    (2, nterm, S), the Taylor coefficients of a watched quantity from its precomputed rows ℓÃ^j/j!."""
    for j in range(nterm):
        acc = 0.0
        for c in range(s_eff):
            acc += rows[j, c] * wa[c]
        out[slot, j] += acc


@njit(cache=True, _nrt=False)
def _chain_end(wa_d, m, k_eff, h):
    """F(h) and F'(h) of the friction's polynomial Σ_{k ≤ k_eff} c_k τ^k held in wa_d[m + 2 + k] (Horner)."""
    f_end = 0.0
    fd_end = 0.0
    for k in range(k_eff, -1, -1):
        fd_end = fd_end * h + f_end
        f_end = f_end * h + wa_d[m + 2 + k]
    return f_end, fd_end


@njit(cache=True, _nrt=False)
def _row_end(r0, r1, z_d, a_end, b_d, f_end, fd_end):
    """A watched quantity's value r0·w̃ and slope r1·w̃ on one direction's end state w̃ = [z, a_g, ȧ_g, F, F']."""
    m = z_d.shape[0]
    v = r0[m] * a_end + r0[m + 1] * b_d + r0[m + 2] * f_end + r0[m + 3] * fd_end
    s = r1[m] * a_end + r1[m + 1] * b_d + r1[m + 2] * f_end + r1[m + 3] * fd_end
    for c in range(m):
        v += r0[c] * z_d[c]
        s += r1[c] * z_d[c]
    return v, s


@njit(cache=True, _nrt=False)
def _watched_end(fend, phase, zh, ax1, ay1, az1, b, fe_x, fde_x, fe_y, fde_y, sig3, wend, val1, slope1, sval1, sslope1):
    """Watched values and slopes at a sub-step's end (as :func:`_monitors`): per direction one product of the table
    fend[phase, d] (rows ℓ and ℓÃ of every watched quantity, value and slope interleaved: the resultants' then the
    signed ones', :func:`end_rows`; stored by columns, fend[phase, d, c, r]) with the augmented end state
    [z, a_g, ȧ_g, c_0 = F(h), c_1 = F'(h)]: column by column, each row's sum in the order of a row-by-row product
    (the inputs' four columns, then z's), so that the rows accumulate independently."""
    m = zh.shape[1]
    nr = fend.shape[3]
    for d in range(2):
        a_end = ax1 if d == 0 else ay1
        f_end = fe_x if d == 0 else fe_y
        fd_end = fde_x if d == 0 else fde_y
        for r in range(nr):
            wend[d, r] = fend[phase, d, m, r] * a_end + fend[phase, d, m + 1, r] * b[d] + fend[phase, d, m + 2, r] \
                * f_end + fend[phase, d, m + 3, r] * fd_end
        for c in range(m):
            zc = zh[d, c]
            for r in range(nr):
                wend[d, r] += fend[phase, d, c, r] * zc
    nk = val1.shape[0]
    for k in range(nk):
        for d in range(2):
            val1[k, d] = wend[d, 2 * k]
            slope1[k, d] = wend[d, 2 * k + 1]
    for j in range(sig3.shape[0]):
        r = 2 * nk + 2 * j
        sval1[j] = sig3[j, 2] * az1 + wend[0, r] + wend[1, r]
        sslope1[j] = sig3[j, 2] * b[2] + wend[0, r + 1] + wend[1, r + 1]


def end_rows(fmon, fsig, m):
    """The table of :func:`_watched_end` from the watched rows' first two powers (ℓ, ℓÃ; they vanish beyond c_1):
    fend[phase, d, :, 2q] = ℓ_q, fend[phase, d, :, 2q + 1] = ℓ_q Ã on [z, a_g, ȧ_g, c_0, c_1], q over the resultants
    then the signed quantities (by columns, contiguous: one product per direction).  Built once per system and
    bearing layout (``planar_building``'s per-system cache), not per run."""
    rows = np.concatenate([fmon[:, :, :, :2, :m + 4], fsig[:, :, :, :2, :m + 4]], axis=1)  # [ph, q, d, p, c]
    ph, nq, nd = rows.shape[:3]
    return np.ascontiguousarray(np.transpose(rows, (0, 2, 4, 1, 3))).reshape(ph, nd, m + 4, 2 * nq)


@njit(cache=True, _nrt=False)
def _form_add(acc, p, w, s_eff, pw):
    """acc + w[:s_eff]ᵀ P w[:s_eff] for a symmetric P: Σ_r w_r (P_rr w_r + 2 Σ_{c>r} P_rc w_c) added term by term
    to acc (r ascending; acc carries the sum over the directions), the inner sums taken
    column by column into pw (pw[r] += P[c, r] w_c for r < c: row c of P, contiguous) so that they accumulate
    independently instead of one dependent sum after another; each inner sum in the same order as row by row
    (c ascending), so the value is the row-by-row sum's to the last bit."""
    for r in range(s_eff):
        pw[r] = 0.0
    for c in range(1, s_eff):
        wc = w[c]
        for r in range(c):
            pw[r] += p[c, r] * wc
    for r in range(s_eff):
        acc += w[r] * (p[r, r] * w[r] + 2.0 * pw[r])
    return acc


def by_columns(fprop, fvrow):
    """The propagators' rows and V's rows stored by columns (fpropt[l, p, d, c2, c] = fprop[l, p, d, c, c2],
    fvt[d, c, k] = fvrow[d, k, c]): the fast sub-step's products then run column by column.  Built once per system
    (``planar_building``'s per-system cache), not per run."""
    fpropt = np.ascontiguousarray(np.transpose(fprop, (0, 1, 2, 4, 3)))
    fvt = np.ascontiguousarray(np.transpose(fvrow, (0, 2, 1)))
    return fpropt, fvt


@njit(cache=True, _nrt=False)
def _order_at(eser, rser, nch, h, mu_k_n, fast_eps):
    """The least order k ≥ 3 at which the friction's and |V|'s series reach fast_eps over h (Jorba–Zou), or −1."""
    hk = 1.0
    for k in range(nch):
        hk1 = hk
        if k > 0:
            hk *= h
        if k >= 3:
            t_f = max(abs(eser[0, k]), abs(eser[1, k])) * hk
            t_f1 = max(abs(eser[0, k - 1]), abs(eser[1, k - 1])) * hk1
            t_r = max(abs(rser[k]) * hk, abs(rser[k - 1]) * hk1)
            if mu_k_n == 0.0 or (max(t_f, t_f1) <= fast_eps and t_r <= fast_eps * rser[0]):
                return k
    return -1


@njit(cache=True, inline="always")
def _peak_inside(val, slope, val1, slope1, k, h, peak_sq):
    """Take monitor ``k``'s ends into its running peak of |·|²; True where a maximum of |·|² may lie inside the
    piece of length ``h`` and exceed that peak (d|·|²/dτ falls through zero, the ends' reach above the peak).

    Inlined by numba (no call in the sub-step, h194), shared by the fast sub-step and the series pieces.
    """
    g0 = val[k, 0] ** 2 + val[k, 1] ** 2
    g1 = val1[k, 0] ** 2 + val1[k, 1] ** 2
    peak_sq[k] = max(peak_sq[k], g0, g1)
    s0 = val[k, 0] * slope[k, 0] + val[k, 1] * slope[k, 1]
    s1 = val1[k, 0] * slope1[k, 0] + val1[k, 1] * slope1[k, 1]
    reach = 4.0 * h * max(abs(s0), abs(s1))
    return s0 > 0.0 and s1 < 0.0 and max(g0, g1) + reach > peak_sq[k]


@njit(cache=True)
def building2d_kernel(ax, ay, az, law, dt, times, h_max, n_order, a_mat, g_vec, p_vec, l_d, weights, slab_mass, total_mass, masses,
                      c_iso, c_floor, mu_s_n, mu_k_n, v_ref, m1, m2, m3, sig1, sig2, sig3, n_fast, fpropt, fpinrow,
                      fpvis, fvt, farow1, farow2, fmon, fsig, fend, out_state, out_mon, out_sig, out_energy, peak_sq, sig_max, sig_min, ev_time, ev_kind, ev_x,
                      summary):
    """Response of the slab + shear building on the friction isolation plane to two horizontal components.

    Parameters
    ----------
    ax, ay : float64[n]
        Ground acceleration [m/s²], linear between samples.
    az : float64[n]
        Vertical ground acceleration [m/s²], up positive, linear between samples (read when law[0] ≠ 0).
    law : float64[12]
        [1 with a vertical or µ(v) else 0, g [m/s²], k_v: the stiffness that follows the normal force
        N = W (1 + a_z/g) (W/R of a pendulum, 0 for a spring) [N/m], (µ_fast − µ_slow) W [N], a [s/m],
        1 to take the approach to a stop in ln s (``APPROACH``; constant µ and N only) else 0, 1 to leave rest at a
        break-away with µs = µk by the departure series (V = τ² W), 1 to leave rest with |D| > µk N (µs > µk, a
        reversal) by the departure series V = τ W, 1 to let a slide's piece slowing along e0 run to e0·V =
        STOP_REACH r0 instead of r0/2, 1 to end such a piece at the stop itself (e0·V = 0 on its series, the speed
        left there ≤ 1e-10 v_ref) when the stop lies within its reach, instead of a FINISH piece, the fast
        sub-steps' friction truncation as a fraction of µk N (FAST_TRUNC_EPS when ≤ 0 or absent), their end check's
        fraction of µk N (FAST_CHECK when ≤ 0 or absent)];
        mu_k_n is then µ_fast W (µ_slow = µ_fast: constant µ).  Fast sub-steps are then taken stuck only (sliding: series pieces).
    dt : float
        Sample interval [s] of a uniform record (``times`` empty).
    times : float64[n] or float64[0]
        Sample times from the first [s] for a non-uniform record.
    h_max : float
        Longest piece [s].
    n_order : int
        Taylor order N of a series piece (:data:`N_ORDER`).
    a_mat : float64[2, 2, m, m]
        A of the stuck (0) and sliding (1) phases, per direction.
    g_vec : float64[2, 2, m]
        The column of the ground acceleration, per phase and direction.
    p_vec : float64[2, m]
        The column of the friction force (sliding), per direction.
    l_d : float64[2, m]
        The force on the slab other than friction: D_d = l_d · z_d − m_b a_d [N].
    weights : float64[m]
        Weights of the state's components for the truncation rule (rates on displacements).
    slab_mass, total_mass : float
        [kg].
    masses : float64[nf]
        Floor masses [kg].
    c_iso : float
        Isolator dashpot [N·s/m].
    c_floor : float64[2, nf, nf]
        C_s per direction.
    mu_s_n, mu_k_n : float
        µs N and µk N [N].
    v_ref : float
        Velocity scale [m/s]: the hand-over from START at 1e-5 v_ref, the stop's finish below 1e-10 v_ref.
    m1, m2, m3 : arrays
        Watched resultants: value_d = m1[k, d]·z_d + m2[k, d]·ż_d + m3[k, d] a_d.
    sig1, sig2, sig3 : arrays
        Watched signed values: Σ_d (sig1[j, d]·z_d + sig2[j, d]·ż_d + sig3[j, d] a_d).
    out_state : float64[n, 2, m]
    out_mon : float64[n, K, 2]
    out_sig : float64[n, J]
    out_energy : float64[3, n]
        Cumulative input, friction and viscous energies [J].
    peak_sq : float64[K]
        Peak of the squared resultants.
    sig_max, sig_min : float64[J]
    ev_time, ev_kind, ev_x : arrays
        Events: time from the first sample [s], kind, (x, y) of the slab [m].
    n_fast : int
        Fast sub-steps per sample interval of a uniform record (0: none; the tables below are for
        the ladder h_l = dt / n_fast / 2^l, l = 0 … L − 1).
    fpropt : float64[L, 2, 2, S, m]
        The first m rows of e^{Ãh_l} per rung, phase and direction, stored by columns (fpropt[l, p, d, c2, c] =
        e^{Ãh_l}[c, c2], :func:`by_columns`), Ã the augmented matrix on w̃ = [z, a_g, ȧ_g, c_0 … c_K]
        (S = m + 3 + K; c_j the chain of the friction's polynomial), the chain scaled to the rung (c_j h_l^j).
    fpinrow : float64[L, 2, 2, 2, S]
        The input power a_g (ℓ_p·w̃) integrated over a rung, as two rows: R1 = ℓ_p ∫₀^{h_l} e^{Ãτ} dτ and
        R2 = ℓ_p ∫₀^{h_l} τ e^{Ãτ} dτ (the input energy is a_g R1·w̃ + ȧ_g R2·w̃; the Van Loan form of a rank-2 Q).
    fpvis : float64[L, 2, 2, S, S]
        ∫₀^{h_l} e^{Ãᵀτ} Q e^{Ãτ} dτ for the viscous power (Van Loan).
    fvt : float64[2, S, K + 1]
        e_v Ã^k / k! of the sliding phase (the Taylor coefficients of V), by columns (fvt[d, c, k]).
    farow1, farow2 : float64[2, 2, m, m + 4]
        The first m rows of Ã and Ã² on [z, a_g, ȧ_g, c_0, c_1] (ż and z̈).
    fmon, fsig : float64[2, K_w, 2, FAST_POW, S], float64[2, J, 2, FAST_POW, S]
        ℓ Ã^j / j! of every watched quantity per phase and direction (their Taylor coefficients).
    fend : float64[2, 2, m + 4, 2 (K_w + J)]
        Their first two powers by columns, the table of :func:`_watched_end` (:func:`end_rows`).
    summary : float64[SUMMARY_SIZE]
    """
    uniform = times.shape[0] == 0
    n = ax.shape[0]
    m = a_mat.shape[2]
    nk = m1.shape[0]
    nj = sig1.shape[0]
    n_series = n_order + 3
    zs = np.zeros((2, n_series + 1, m))  # the last row holds the time scale H of the coefficients (_series)
    fs = np.zeros((2, n_series))
    w = np.zeros((2, m))
    z = np.zeros((2, m))
    zd = np.zeros((2, m))
    zdd = np.zeros((2, m))
    val = np.zeros((nk, 2))
    slope = np.zeros((nk, 2))
    sval = np.zeros(max(nj, 1))
    sslope = np.zeros(max(nj, 1))
    val1 = np.zeros((nk, 2))
    slope1 = np.zeros((nk, 2))
    sval1 = np.zeros(max(nj, 1))
    sslope1 = np.zeros(max(nj, 1))
    val2 = np.zeros((nk, 2))
    slope2 = np.zeros((nk, 2))
    sval2 = np.zeros(max(nj, 1))
    sslope2 = np.zeros(max(nj, 1))
    zl = np.zeros((2, m))
    # the watched slopes' gains on ȧ_g per phase (m2·g + m3; a sample's new ȧ_g shifts them, see below)
    gain_mon = np.zeros((2, max(nk, 1), 2))
    gain_sig = np.zeros((2, max(nj, 1), 2))
    for ph in range(2):
        for d in range(2):
            for k in range(nk):
                gain = m3[k, d]
                for c in range(m):
                    gain += m2[k, d, c] * g_vec[ph, d, c]
                gain_mon[ph, k, d] = gain
            for j in range(nj):
                gain = sig3[j, d]
                for c in range(m):
                    gain += sig2[j, d, c] * g_vec[ph, d, c]
                gain_sig[ph, j, d] = gain
    # the rows of ż that φ reads at a fast sub-step's ends: Ã's rows 0 (x_b) and 1 (v_b), and ℓ_D Ã (Ḋ)
    flrow = np.zeros((2, 2, 3, farow1.shape[3]))
    for ph in range(2):
        for d in range(2):
            for c in range(farow1.shape[3]):
                flrow[ph, d, 0, c] = farow1[ph, d, 0, c]
                flrow[ph, d, 1, c] = farow1[ph, d, 1, c]
                acc = 0.0
                for r in range(m):
                    acc += l_d[d, r] * farow1[ph, d, r, c]
                flrow[ph, d, 2, c] = acc
    zdl = np.zeros((2, m))
    zddl = np.zeros((2, m))
    zh = np.zeros((2, m))
    zdh = np.zeros((2, m))
    zddh = np.zeros((2, m))
    ws = np.zeros((2, n_series))
    ss = np.zeros(n_series)
    rs = np.zeros(n_series)
    es = np.zeros((2, n_series))
    pin = np.zeros(n_order + 2)
    pfr = np.zeros(n_order + 1)
    pvis = np.zeros(n_order + 1)
    ysc = np.zeros((n_order + 1, masses.shape[0]))
    ee = np.zeros((2, n_series))
    rho = np.zeros(n_series)
    out2 = np.zeros(2)
    energy = np.zeros(3)
    counter = np.zeros(1, dtype=np.int64)
    n_levels = fpropt.shape[0]
    n_ch = fpropt.shape[3] - m - 2
    wa = np.zeros((2, fpropt.shape[3]))
    wsc = np.zeros((2, fpropt.shape[3]))
    pw = np.zeros(fpropt.shape[3])
    vser = np.zeros((2, n_ch))
    sser = np.zeros(n_ch)
    rser = np.zeros(n_ch)
    eser = np.zeros((2, n_ch))
    cpoly = np.zeros((2, fmon.shape[3]))
    wend = np.zeros((2, fend.shape[3]))
    n_fast_steps = 0
    n_refused = np.zeros(6, dtype=np.int64)
    e0 = np.zeros(2)
    varying = law[0] != 0.0
    gravity = law[1]
    vz = np.zeros(VZ_SIZE)
    vz[V_VARYING] = law[0]
    vz[V_NU0] = 1.0
    vz[V_K_VERT] = law[2]
    vz[V_DMU_N] = law[3]
    vz[V_RATE] = law[4]
    mus = np.zeros(n_series)
    exs = np.zeros(n_series)
    bz = 0.0
    a0 = np.zeros(3)  # a_g along x, y and the vertical a_z (the watched bearing loads' share)
    b = np.zeros(3)
    a1 = np.zeros(3)
    floor_scale = 1e-6 * v_ref
    r_switch = 1e-5 * v_ref
    r_finish = 1e-10 * v_ref
    use_approach = law[5] != 0.0 and not varying
    # departures from rest at a break-away with µs = µk by the slow manifold's series (constant µ and N only)
    use_depart = law[6] != 0.0 and not varying
    # ... and leaving rest with a finite acceleration, |D| > µk N (µs > µk, reversals): V = τ W (law[7])
    use_leave = use_depart and law[7] != 0.0
    depart_pending = False
    departing = False
    depart_lag = 2
    # a slide slowing along e0 ends its series piece where e0·V falls to STOP_REACH of its start instead of a half
    # (law[8]); its piece is then held to REACH_SHRINK of the series' reach (the tail's bound stays the halving's)
    use_reach = law[8] != 0.0
    reach_shrink = (2.0 * STOP_REACH) ** (1.0 / n_order)
    # ... and such a piece ends at the stop itself when the stop lies within it (law[9])
    use_stop_piece = use_reach and law.shape[0] > 9 and law[9] != 0.0
    # the fast sub-steps' truncation tolerance of the friction's polynomial (law[10], FAST_TRUNC_EPS)
    fast_eps = law[10] if law.shape[0] > 10 and law[10] > 0.0 else FAST_TRUNC_EPS
    # ... and their end check's fraction of µk N (law[11], FAST_CHECK)
    fast_check = law[11] if law.shape[0] > 11 and law[11] > 0.0 else FAST_CHECK
    n_stop_pieces = 0
    r_approach = APPROACH_SPEED * v_ref
    nl1 = n_order + 1
    lz = np.zeros((2, nl1, m))
    lzd = np.zeros((2, nl1, m))
    lt = np.zeros(nl1)
    le = np.zeros((2, nl1))
    lq = np.zeros((2, nl1))
    lrate = np.zeros(nl1)
    ltp = np.zeros(nl1)
    lex = np.zeros(nl1)
    la = np.zeros((2, nl1))
    lmom = np.zeros(nl1)
    lam_piece = 0.0
    approach_done = False
    approach_below = r_approach
    approach_above = 0.0
    grow = -1.0
    limit = 0.0
    mode = STUCK
    x_stuck = np.zeros(2)
    from_rest = False
    half_target = 0.0
    n_ev = 0
    status = 0
    n_pieces = 0
    pieces_by_mode = np.zeros(N_PIECE_KINDS, dtype=np.int64)
    e_in = 0.0
    e_f = 0.0
    e_v = 0.0
    slip_time = 0.0
    # the first sample: at rest, stuck
    a0[0] = ax[0]
    a0[1] = ay[0]
    a0[2] = az[0]
    if varying:
        vz[V_NU0] = 1.0 + az[0] / gravity
    # the series' time scale H: about the last piece's length (the next one's radius is near), at most h_max
    h_last = min(h_max, dt if uniform else times[1] - times[0]) if n > 1 else 1.0
    _series(np.int64(STUCK), w, a0, b, a_mat, g_vec, p_vec, l_d, slab_mass, mu_k_n, e0, zs, fs, ws, ss, rs, es, vz, mus, exs,
            h_last)
    _eval(zs, 0.0, z, zd, zdd)
    _monitors(z, zd, zdd, a0[0], a0[1], a0[2], b, m1, m2, m3, sig1, sig2, sig3, val, slope, sval, sslope)
    for k in range(nk):
        peak_sq[k] = val[k, 0] ** 2 + val[k, 1] ** 2
        out_mon[0, k, 0] = val[k, 0]
        out_mon[0, k, 1] = val[k, 1]
    for j in range(nj):
        sig_max[j] = sval[j]
        sig_min[j] = sval[j]
        out_sig[0, j] = sval[j]
    for d in range(2):
        for i in range(m):
            out_state[0, d, i] = 0.0
    for i in range(n - 1):
        if uniform:
            t_i = i * dt
            dt_i = dt
        else:
            t_i = times[i]
            dt_i = times[i + 1] - t_i
        b_prev0 = b[0]
        b_prev1 = b[1]
        b[0] = (ax[i + 1] - ax[i]) / dt_i
        b[1] = (ay[i + 1] - ay[i]) / dt_i
        b[2] = (az[i + 1] - az[i]) / dt_i
        if varying:
            bz = b[2]
            vz[V_NU1] = bz / gravity
        tau = 0.0
        events_here = 0
        # the watched values at the sample carry over; their slopes take the new ȧ_g: z̈ holds g ȧ_g, so
        # slope += (m2·g + m3) Δȧ_g per direction (with a vertical or µ(v) they are recomputed at the sample)
        start_valid = i > 0 and not varying
        if start_valid:
            ph = 0 if mode == STUCK else 1
            for k in range(nk):
                for d in range(2):
                    slope1[k, d] += gain_mon[ph, k, d] * ((b[0] - b_prev0) if d == 0 else (b[1] - b_prev1))
            for j in range(nj):
                for d in range(2):
                    sslope1[j] += gain_sig[ph, j, d] * ((b[0] - b_prev0) if d == 0 else (b[1] - b_prev1))
        n_sub_i = n_fast if (uniform and n_fast > 0) else 1
        h_fast = dt_i / n_sub_i
        for j_sub in range(n_sub_i):
            tau_end = dt_i if j_sub == n_sub_i - 1 else (j_sub + 1) * h_fast
            for _ladder in range(MAX_PIECES_PER_INTERVAL):
                if tau >= tau_end:
                    break
                slow_end = tau_end
                # stuck, the floors are a fixed-base linear system whatever N(t) and µ(v) (they only move the
                # break-away limit µs N(τ), which the event test reads from vz): exact propagators; sliding,
                # only with a constant N and µ (the propagators hold a constant A and a polynomial friction)
                fast_mode = n_fast > 0 and uniform and (mode == STUCK or (mode == SLIDE and not varying))
                if fast_mode and events_here <= MAX_EVENTS_PER_INTERVAL:
                    # the longest sub-step of the ladder h, h/2, h/4 … that fits and that the exact propagators
                    # can take (else series pieces, over at most the shortest rung)
                    a0[0] = ax[i] + b[0] * tau
                    a0[1] = ay[i] + b[1] * tau
                    a0[2] = az[i] + b[2] * tau
                    if varying:
                        vz[V_NU0] = 1.0 + (az[i] + bz * tau) / gravity
                    lev0 = 0
                    while lev0 < n_levels - 1 and tau + h_fast / (1 << lev0) > tau_end + 1e-12 * h_fast:
                        lev0 += 1
                    h_lev = h_fast / (1 << lev0)
                    refused = 0
                    if tau + h_lev <= tau_end + 1e-12 * h_fast:
                        # one sub-step stuck or sliding by the exact propagators of the linear part (written here, not
                        # as calls: h194, the calls into _fast_step and _fast_try with ~60 array arguments each cost
                        # ~0.6 µs a sub-step; the answers are bit for bit theirs): the longest rung of the ladder h_lev
                        # = h_{lev0}, h_lev/2 … that the friction's series and the events allow.  The augmented state
                        # per direction is w̃ = [z, a_g, ȧ_g, c_0 … c_K] with c_j = F^{(j)}/j! the chain of the
                        # friction's polynomial F(τ) = Σ F_k τ^k (F_k from the recurrences of |V| and V/|V|, V's
                        # coefficients from the rows e_v Ã^k / k!), so w̃(h) = e^{Ãh} w̃(0) is exact for that polynomial
                        # and the energies are the Van Loan quadratic forms w̃ᵀ P w̃.  taken ≥ 0: the rung taken; zh,
                        # zdh, zddh hold the end, val1 … sslope1 the watched values there, energy[0:3] the energies over
                        # the sub-step.  Otherwise, having changed nothing read below (series pieces then run), minus
                        # the reason on the shortest rung tried: 1 the friction's series does not reach fast_eps, 2 the
                        # friction at the end does not match V/|V| of the propagated state to fast_check µk N, 3 an
                        # event may lie in the sub-step (break-away; the speed along e0 halving), 4 V = 0.  Locals:
                        # fx_*.
                        taken = -1000
                        fx_m = w.shape[1]
                        fx_phase = 0 if mode == STUCK else 1
                        fx_nch = fpropt.shape[3] - fx_m - 2  # chain entries c_0 .. c_K
                        fx_n_lev = fpropt.shape[0]
                        for fx_d in range(2):
                            for fx_c in range(fx_m):
                                wa[fx_d, fx_c] = w[fx_d, fx_c]
                            wa[fx_d, fx_m] = a0[fx_d]
                            wa[fx_d, fx_m + 1] = b[fx_d]
                            for fx_j in range(fx_nch):
                                wa[fx_d, fx_m + 2 + fx_j] = 0.0
                        fx_k_eff = 1
                        fx_lev_first = lev0
                        if mode == SLIDE:
                            fx_converged = False
                            fx_scale = max(mu_k_n, 1e-300)
                            fx_hk = 1.0
                            fx_inv_r = 0.0
                            # V's coefficients e_v Ã^k/k! w̃ (fvt[d, c, k]: the rows by columns): the share of [z, a_g, ȧ_g] for every
                            # order at once, column by column (the orders accumulate independently), then per order the chain's
                            # c_0 … c_{k-1} (known only once the orders below are): each sum in the order of a row-by-row product
                            for fx_d in range(2):
                                for fx_k in range(fx_nch):
                                    vser[fx_d, fx_k] = 0.0
                                for fx_c in range(fx_m + 2):
                                    fx_wc = wa[fx_d, fx_c]
                                    for fx_k in range(fx_nch):
                                        vser[fx_d, fx_k] += fvt[fx_d, fx_c, fx_k] * fx_wc
                            for fx_k in range(fx_nch):
                                for fx_d in range(2):
                                    fx_acc = vser[fx_d, fx_k]
                                    for fx_c in range(fx_m + 2, fx_m + 2 + fx_k):
                                        fx_acc += fvt[fx_d, fx_c, fx_k] * wa[fx_d, fx_c]
                                    vser[fx_d, fx_k] = fx_acc
                                sser[fx_k] = _sq_norm_term(vser, fx_k)
                                if fx_k == 0:
                                    if not sser[0] > 0.0:
                                        taken = -4
                                        break
                                    rser[0] = math.sqrt(sser[0])
                                    # one reciprocal for the divisions by |V|_0 (three an order before; h134: the bench's kernel 1–3 % faster)
                                    fx_inv_r = 1.0 / rser[0]
                                else:
                                    fx_acc = sser[fx_k]
                                    for fx_j in range(1, fx_k):
                                        fx_acc -= rser[fx_j] * rser[fx_k - fx_j]
                                    rser[fx_k] = 0.5 * fx_acc * fx_inv_r
                                for fx_d in range(2):
                                    fx_acc = vser[fx_d, fx_k]
                                    for fx_j in range(fx_k):
                                        fx_acc -= eser[fx_d, fx_j] * rser[fx_k - fx_j]
                                    eser[fx_d, fx_k] = fx_acc * fx_inv_r
                                    wa[fx_d, fx_m + 2 + fx_k] = mu_k_n * eser[fx_d, fx_k]
                                fx_hk1 = fx_hk
                                if fx_k > 0:
                                    fx_hk *= h_lev
                                if fx_k >= 3:
                                    fx_t_f = max(abs(eser[0, fx_k]), abs(eser[1, fx_k])) * fx_hk * mu_k_n
                                    fx_t_f1 = max(abs(eser[0, fx_k - 1]), abs(eser[1, fx_k - 1])) * fx_hk1 * mu_k_n
                                    fx_t_r = abs(rser[fx_k]) * fx_hk
                                    fx_t_r1 = abs(rser[fx_k - 1]) * fx_hk1
                                    if max(fx_t_f, fx_t_f1) <= fast_eps * fx_scale and (mu_k_n == 0.0 or max(fx_t_r, fx_t_r1) <= fast_eps * rser[0]):
                                        fx_k_eff = fx_k
                                        fx_converged = True
                                        break
                            if taken == -1000 and not fx_converged:
                                # the whole series is there: the longest shorter rung at which it reaches rounding
                                for fx_lev in range(lev0 + 1, fx_n_lev):
                                    fx_k_eff = _order_at(eser, rser, fx_nch, h_lev / (1 << (fx_lev - lev0)), mu_k_n, fast_eps)
                                    if fx_k_eff > 0:
                                        fx_lev_first = fx_lev
                                        fx_converged = True
                                        break
                            if taken == -1000 and not fx_converged:
                                taken = -1
                        # the rungs from fx_lev_first down: each the length fx_h, the friction's polynomial of degree
                        # fx_k_eff, its end checked to fast_check µk N; taken, or refused (fx_code: 2 the end check, 3 a
                        # possible event) with nothing read below changed
                        if taken == -1000:
                            fx_code = 0
                            for fx_lev in range(fx_lev_first, fx_n_lev):
                                fx_h = h_lev / (1 << (fx_lev - lev0))
                                fx_fpropt_l = fpropt[fx_lev]
                                fx_fpinrow_l = fpinrow[fx_lev]
                                fx_fpvis_l = fpvis[fx_lev]
                                # ż's entries that φ reads, at the start and the end (work rows of the end's rates, not read by the caller)
                                fx_rate_l = zdh
                                fx_rate_h = zddh
                                fx_r_int = 0.0
                                if mode == SLIDE:
                                    # ∫₀^h |V| dτ = h Σ_j |V|_j h^j/(j + 1), by Horner (no power a term)
                                    for fx_j in range(fx_k_eff, -1, -1):
                                        fx_r_int = fx_r_int * fx_h + rser[fx_j] / (fx_j + 1)
                                    fx_r_int *= fx_h
                                # stuck, the chain is zero (the friction is not an input of the held slab's floors): [z, a_g, ȧ_g] only
                                fx_s_eff = fx_m + 3 + fx_k_eff if mode == SLIDE else fx_m + 2
                                # the tables are for the chain scaled to this rung, c_j h^j (entries of one size: rounding stays relative)
                                for fx_d in range(2):
                                    for fx_c in range(fx_m + 2):
                                        wsc[fx_d, fx_c] = wa[fx_d, fx_c]
                                    fx_hk = 1.0
                                    for fx_k in range(fx_k_eff + 1):
                                        wsc[fx_d, fx_m + 2 + fx_k] = wa[fx_d, fx_m + 2 + fx_k] * fx_hk
                                        fx_hk *= fx_h
                                # z(h) = E w̃ column by column (fpropt_l[phase, d, c2, c] = E[c, c2]; each entry summed in the order of a
                                # row-by-row product, the entries independently)
                                for fx_d in range(2):
                                    for fx_c in range(fx_m):
                                        zh[fx_d, fx_c] = 0.0
                                    for fx_c2 in range(fx_s_eff):
                                        fx_wc = wsc[fx_d, fx_c2]
                                        for fx_c in range(fx_m):
                                            zh[fx_d, fx_c] += fx_fpropt_l[fx_phase, fx_d, fx_c2, fx_c] * fx_wc
                                # φ at the ends reads only ℓ_D·z, ℓ_D·ż and z[0], z[1], ż[0], ż[1]: ż's entries from the rows ℓ_D Ã (flrow[…, 2])
                                # and Ã's rows 0, 1 on [z, a_g, ȧ_g, c_0, c_1]; the whole ż, z̈ at the start only when the watched values there
                                # are recomputed (the end's come from the watched rows below)
                                fx_fe_x, fx_fde_x = _chain_end(wa[0], fx_m, fx_k_eff, fx_h)
                                fx_fe_y, fx_fde_y = _chain_end(wa[1], fx_m, fx_k_eff, fx_h)
                                for fx_d in range(2):
                                    fx_f_end = fx_fe_x if fx_d == 0 else fx_fe_y
                                    fx_fd_end = fx_fde_x if fx_d == 0 else fx_fde_y
                                    fx_a_end = a0[fx_d] + b[fx_d] * fx_h
                                    for fx_q in range(3):
                                        fx_acc_l = flrow[fx_phase, fx_d, fx_q, fx_m] * a0[fx_d] + flrow[fx_phase, fx_d, fx_q, fx_m + 1] * b[fx_d] + flrow[
                                            fx_phase, fx_d, fx_q, fx_m + 2] * wa[fx_d, fx_m + 2] + flrow[fx_phase, fx_d, fx_q, fx_m + 3] * wa[fx_d, fx_m + 3]
                                        fx_acc_h = flrow[fx_phase, fx_d, fx_q, fx_m] * fx_a_end + flrow[fx_phase, fx_d, fx_q, fx_m + 1] * b[fx_d] + flrow[
                                            fx_phase, fx_d, fx_q, fx_m + 2] * fx_f_end + flrow[fx_phase, fx_d, fx_q, fx_m + 3] * fx_fd_end
                                        for fx_c2 in range(fx_m):
                                            fx_acc_l += flrow[fx_phase, fx_d, fx_q, fx_c2] * w[fx_d, fx_c2]
                                            fx_acc_h += flrow[fx_phase, fx_d, fx_q, fx_c2] * zh[fx_d, fx_c2]
                                        fx_rate_l[fx_d, fx_q] = fx_acc_l
                                        fx_rate_h[fx_d, fx_q] = fx_acc_h
                                    if not start_valid:
                                        for fx_c in range(fx_m):
                                            fx_acc_l = farow1[fx_phase, fx_d, fx_c, fx_m] * a0[fx_d] + farow1[fx_phase, fx_d, fx_c, fx_m + 1] * b[fx_d] + farow1[
                                                fx_phase, fx_d, fx_c, fx_m + 2] * wa[fx_d, fx_m + 2] + farow1[fx_phase, fx_d, fx_c, fx_m + 3] * wa[fx_d, fx_m + 3]
                                            fx_acd_l = farow2[fx_phase, fx_d, fx_c, fx_m] * a0[fx_d] + farow2[fx_phase, fx_d, fx_c, fx_m + 1] * b[fx_d] + farow2[
                                                fx_phase, fx_d, fx_c, fx_m + 2] * wa[fx_d, fx_m + 2] + farow2[fx_phase, fx_d, fx_c, fx_m + 3] * wa[fx_d, fx_m + 3]
                                            for fx_c2 in range(fx_m):
                                                fx_acc_l += farow1[fx_phase, fx_d, fx_c, fx_c2] * w[fx_d, fx_c2]
                                                fx_acd_l += farow2[fx_phase, fx_d, fx_c, fx_c2] * w[fx_d, fx_c2]
                                            zl[fx_d, fx_c] = w[fx_d, fx_c]
                                            zdl[fx_d, fx_c] = fx_acc_l
                                            zddl[fx_d, fx_c] = fx_acd_l
                                out2[0] = fx_fe_x
                                out2[1] = fx_fe_y
                                fx_ax1 = a0[0] + b[0] * fx_h
                                fx_ay1 = a0[1] + b[1] * fx_h
                                if mode == SLIDE:
                                    # the friction's polynomial at the end against V/|V| of the propagated state
                                    fx_r_end = math.sqrt(zh[0, 1] ** 2 + zh[1, 1] ** 2)
                                    if not fx_r_end > 0.0:
                                        fx_code = 2
                                        continue
                                    fx_off = False
                                    for fx_d in range(2):
                                        if abs(out2[fx_d] - mu_k_n * zh[fx_d, 1] / fx_r_end) > fast_check * mu_k_n:
                                            fx_off = True
                                            break
                                    if fx_off:
                                        fx_code = 2
                                        continue
                                    fx_kind = PHI_HALF
                                    fx_target = half_target
                                else:
                                    fx_kind = PHI_BREAK
                                    fx_target = mu_s_n
                                # an event in the sub-step (φ rising through zero at an end or at an interior maximum): series pieces
                                _phi_core(fx_kind, _dot(l_d[0], w[0]) - slab_mass * a0[0], _dot(l_d[1], w[1]) - slab_mass * a0[1],
                                          fx_rate_l[0, 2] - slab_mass * b[0], fx_rate_l[1, 2] - slab_mass * b[1], w[0, 0], w[1, 0], fx_rate_l[0, 0],
                                          fx_rate_l[1, 0], w[0, 1], w[1, 1], fx_rate_l[0, 1], fx_rate_l[1, 1], 0.0, fx_target, e0, vz, out2)
                                fx_f0 = out2[0]
                                fx_s0 = out2[1]
                                _phi_core(fx_kind, _dot(l_d[0], zh[0]) - slab_mass * fx_ax1, _dot(l_d[1], zh[1]) - slab_mass * fx_ay1,
                                          fx_rate_h[0, 2] - slab_mass * b[0], fx_rate_h[1, 2] - slab_mass * b[1], zh[0, 0], zh[1, 0], fx_rate_h[0, 0],
                                          fx_rate_h[1, 0], zh[0, 1], zh[1, 1], fx_rate_h[0, 1], fx_rate_h[1, 1], fx_h, fx_target, e0, vz, out2)
                                fx_f1 = out2[0]
                                fx_s1 = out2[1]
                                if fx_f0 > 0.0 or fx_f1 > 0.0:
                                    fx_code = 3
                                    continue
                                if fx_s0 > 0.0 and fx_s1 < 0.0 and max(fx_f0, fx_f1) + 2.0 * fx_h * max(abs(fx_s0), abs(fx_s1)) > 0.0:
                                    fx_code = 3
                                    continue
                                # ---- committed: watched values, peaks, energies ----
                                if start_valid:
                                    # the watched values at the start are the last piece's (or sub-step's) end values
                                    for fx_k in range(m1.shape[0]):
                                        for fx_d in range(2):
                                            val[fx_k, fx_d] = val1[fx_k, fx_d]
                                            slope[fx_k, fx_d] = slope1[fx_k, fx_d]
                                    for fx_j in range(sig1.shape[0]):
                                        sval[fx_j] = sval1[fx_j]
                                        sslope[fx_j] = sslope1[fx_j]
                                else:
                                    _monitors(zl, zdl, zddl, a0[0], a0[1], a0[2], b, m1, m2, m3, sig1, sig2, sig3, val, slope, sval, sslope)
                                # the end's watched values and slopes from their rows ℓ, ℓÃ on w̃(h) = [z(h), a_g(h), ȧ_g, F(h), F'(h)] (the
                                # rows vanish beyond c_0, c_1): one product each instead of ż, z̈ and the monitors' three rows
                                _watched_end(fend, fx_phase, zh, fx_ax1, fx_ay1, a0[2] + b[2] * fx_h, b, fx_fe_x, fx_fde_x, fx_fe_y, fx_fde_y, sig3, wend, val1, slope1,
                                             sval1, sslope1)
                                fx_nterm = fmon.shape[3]
                                fx_nk = m1.shape[0]
                                for fx_k in range(fx_nk):
                                    if _peak_inside(val, slope, val1, slope1, fx_k, fx_h, peak_sq):
                                        counter[0] += 1
                                        for fx_d in range(2):
                                            for fx_j in range(fx_nterm):
                                                cpoly[fx_d, fx_j] = 0.0
                                            _rows_series(fmon[fx_phase, fx_k, fx_d], wa[fx_d], fx_s_eff, fx_nterm, cpoly, fx_d)
                                        peak_sq[fx_k] = max(peak_sq[fx_k], _poly_max(cpoly, np.int64(0), fx_nterm, fx_h))
                                for fx_j in range(sig1.shape[0]):
                                    sig_max[fx_j] = max(sig_max[fx_j], sval[fx_j], sval1[fx_j])
                                    sig_min[fx_j] = min(sig_min[fx_j], sval[fx_j], sval1[fx_j])
                                    fx_reach = 2.0 * fx_h * max(abs(sslope[fx_j]), abs(sslope1[fx_j]))
                                    fx_up = sslope[fx_j] > 0.0 and sslope1[fx_j] < 0.0 and max(sval[fx_j], sval1[fx_j]) + fx_reach > sig_max[fx_j]
                                    fx_down = sslope[fx_j] < 0.0 and sslope1[fx_j] > 0.0 and min(sval[fx_j], sval1[fx_j]) - fx_reach < sig_min[fx_j]
                                    if fx_up or fx_down:
                                        counter[0] += 1
                                        for fx_jj in range(fx_nterm):
                                            cpoly[0, fx_jj] = 0.0
                                        for fx_d in range(2):
                                            _rows_series(fsig[fx_phase, fx_j, fx_d], wa[fx_d], fx_s_eff, fx_nterm, cpoly, np.int64(0))
                                        # the vertical's share (a bearing's P_g a_z/g), linear in τ: not in the tables' augmented state
                                        cpoly[0, 0] += sig3[fx_j, 2] * a0[2]
                                        cpoly[0, 1] += sig3[fx_j, 2] * b[2]
                                        if fx_up:
                                            sig_max[fx_j] = max(sig_max[fx_j], _poly_max(cpoly, np.int64(1), fx_nterm, fx_h))
                                        else:
                                            sig_min[fx_j] = min(sig_min[fx_j], -_poly_max(cpoly, np.int64(-1), fx_nterm, fx_h))
                                # the input power a_g (ℓ_p·w̃) with a_g = a0 + ȧ_g τ: its integral a0 (R1·w̃) + ȧ_g (R2·w̃), R1 = ℓ_p ∫e^{Ãτ}dτ and
                                # R2 = ℓ_p ∫τ e^{Ãτ}dτ (fpinrow: the Van Loan form of a rank-2 power, as two rows); the viscous power's form is
                                # symmetric (below)
                                fx_e_in = 0.0
                                fx_e_v = 0.0
                                for fx_d in range(2):
                                    fx_r1 = 0.0
                                    fx_r2 = 0.0
                                    for fx_c in range(fx_s_eff):
                                        fx_r1 += fx_fpinrow_l[fx_phase, fx_d, 0, fx_c] * wsc[fx_d, fx_c]
                                        fx_r2 += fx_fpinrow_l[fx_phase, fx_d, 1, fx_c] * wsc[fx_d, fx_c]
                                    fx_e_in += wsc[fx_d, fx_m] * fx_r1 + wsc[fx_d, fx_m + 1] * fx_r2
                                    fx_e_v = _form_add(fx_e_v, fx_fpvis_l[fx_phase, fx_d], wsc[fx_d], fx_s_eff, pw)
                                if vz[V_VARYING] != 0.0 and mode == STUCK:
                                    # the vertical's work ½ k_v ν1 ∫|X|² dτ on the held slab (X constant), as _energies counts it
                                    fx_e_in += 0.5 * vz[V_K_VERT] * vz[V_NU1] * (w[0, 0] ** 2 + w[1, 0] ** 2) * fx_h
                                energy[0] = fx_e_in
                                energy[1] = mu_k_n * fx_r_int
                                energy[2] = fx_e_v
                                taken = fx_lev
                                break
                            if taken == -1000:
                                taken = -fx_code
                        if taken >= 0:
                            h_lev = h_fast / (1 << taken)
                        else:
                            refused = -taken
                            n_refused[refused] += 1
                    else:
                        refused = 5
                    if refused == 0:
                        n_fast_steps += 1
                        e_in += energy[0]
                        e_f += energy[1]
                        e_v += energy[2]
                        for d in range(2):
                            for c in range(m):
                                w[d, c] = zh[d, c]
                        if mode == STUCK:
                            for d in range(2):
                                w[d, 0] = x_stuck[d]
                                w[d, 1] = 0.0
                        else:
                            slip_time += h_lev
                            r = math.sqrt(w[0, 1] ** 2 + w[1, 1] ** 2)
                            e0[0] = w[0, 1] / r
                            e0[1] = w[1, 1] / r
                            half_target = 0.5 * r
                        start_valid = True
                        from_rest = False
                        tau = tau_end if tau_end - (tau + h_lev) <= 1e-12 * h_fast else tau + h_lev
                        continue
                if n_fast > 0 and uniform and not (varying and mode == SLIDE) and mode != APPROACH and not \
                        (mode == START and depart_pending):
                    # back to the ladder after the shortest rung (sliding with N(t) or µ(v), which the
                    # propagators do not take, runs on to the sub-step's end)
                    slow_end = min(tau_end, tau + h_fast / (1 << (n_levels - 1)))
                for _guard in range(MAX_PIECES_PER_INTERVAL):
                    if tau >= slow_end:
                        break
                    a0[0] = ax[i] + b[0] * tau
                    a0[1] = ay[i] + b[1] * tau
                    a0[2] = az[i] + b[2] * tau
                    rem = slow_end - tau
                    if varying:
                        vz[V_NU0] = 1.0 + (az[i] + bz * tau) / gravity
                    on_log = mode == APPROACH
                    if on_log:
                        rate0 = _series_log(w, a0, b, a_mat, g_vec, p_vec, mu_k_n, grow, lz, lzd, lt, le, lq, lrate,
                                            ltp, lex, la)
                        lam_limit = _log_limit(lz, lt, le, weights, floor_scale) if grow * rate0 > 0.0 else 0.0
                        if grow < 0.0:
                            lam_end = math.log(lex[0] / r_finish) if lex[0] > r_finish else 0.0
                        else:
                            lam_end = math.log(r_approach / lex[0]) if lex[0] < r_approach else 0.0
                        if not lam_limit >= APPROACH_MIN or lam_end <= 0.0:
                            # ṡ near zero (the slab neither stopping nor speeding away) or the approach's end
                            # reached: slide on in time, or finish the stop
                            r = lex[0]
                            mode = FINISH if (lam_end <= 0.0 and grow < 0.0) else SLIDE
                            if not lam_limit >= APPROACH_MIN:
                                # not again before the speed has halved (slowing) or doubled (speeding up)
                                if grow < 0.0:
                                    approach_below = 0.5 * r
                                else:
                                    approach_above = 2.0 * r
                            e0[0] = w[0, 1] / r
                            e0[1] = w[1, 1] / r
                            half_target = 0.5 * r
                            start_valid = False
                            continue
                        lam_piece = min(lam_limit, lam_end)
                        approach_done = lam_piece == lam_end
                        piece = _eval_log(lz, lzd, lt, lam_piece, zh, zdh, zddh)
                        length = piece
                        if piece >= rem:
                            lam_piece = _log_time_root(lt, rem, lam_piece)
                            approach_done = False
                            _eval_log(lz, lzd, lt, lam_piece, zh, zdh, zddh)
                            piece = rem
                            length = rem
                        _eval_log(lz, lzd, lt, 0.0, zl, zdl, zddl)
                        n_pieces += 1
                        pieces_by_mode[APPROACH] += 1
                        t_event = -1.0
                        kind_phi = -1
                    else:
                        departing = False
                        if mode == START and depart_pending:
                            # leaving rest with µs = µk: the slow manifold's series from the break-away, as far as
                            # it reaches rounding and the slab keeps moving away (D·V > 0 at the end), else START
                            depart_pending = False
                            h_scale = min(h_max, rem)
                            limit = 0.0
                            for _rescale in range(8):
                                departing = _series_depart(w, a0, b, a_mat, g_vec, p_vec, mu_k_n, zs, fs, ee, rho,
                                                           h_scale, depart_lag)
                                if not departing:
                                    break
                                limit = _piece_limit(zs, weights, floor_scale)
                                h_scale = _next_scale(limit, h_scale, rem, h_max)
                                if h_scale == 0.0:
                                    break
                            if departing:
                                length = min(rem, h_max, limit)
                                _eval(zs, length, zh, zdh, zddh)
                                push = (_dot(l_d[0], zh[0]) - slab_mass * (a0[0] + b[0] * length)) * zh[0, 1] + (
                                    _dot(l_d[1], zh[1]) - slab_mass * (a0[1] + b[1] * length)) * zh[1, 1]
                                departing = push > 0.0 and length > 0.0
                        if not departing:
                            h_scale = min(h_max, 2.0 * h_last)
                            limit = 0.0
                            for _rescale in range(8):
                                _series(mode, w, a0, b, a_mat, g_vec, p_vec, l_d, slab_mass, mu_k_n, e0, zs, fs, ws, ss,
                                        rs, es, vz, mus, exs, h_scale)
                                limit = _piece_limit(zs, weights, floor_scale)
                                h_scale = _next_scale(limit, h_scale, rem, h_max)
                                if h_scale == 0.0:
                                    break
                        h_last = min(limit, h_max, dt_i)
                        n_pieces += 1
                        pieces_by_mode[DEPART if departing else mode] += 1
                        length = min(rem, h_max, limit)
                        _eval(zs, 0.0, zl, zdl, zddl)
                        # slowing along e0: towards a stop, whose singularity (V/|V|'s branch point) is ahead at ~ the
                        # time to the stop (see the event test below)
                        slowing = mode == SLIDE and use_reach and e0[0] * zdl[0, 1] + e0[1] * zdl[1, 1] < 0.0
                        if mode == FINISH:
                            # the stop is due within ~ r/|ṙ|: do not run the frozen direction much beyond it
                            rdot = abs(e0[0] * zdl[0, 1] + e0[1] * zdl[1, 1])
                            r_now = e0[0] * zl[0, 1] + e0[1] * zl[1, 1]
                            if rdot > 0.0:
                                length = min(length, 4.0 * r_now / rdot)
                        if length < rem and length < 1e-15 * dt_i:
                            length = min(rem, 1e-15 * dt_i)
                        _eval(zs, length, zh, zdh, zddh)
                        # ---- event in this piece? ----
                        t_event = -1.0
                        kind_phi = -1
                        if events_here > MAX_EVENTS_PER_INTERVAL:
                            pass
                        elif mode == STUCK:
                            t_event = _first_crossing(np.int64(PHI_BREAK), zs, length, a0, b, l_d, slab_mass, mu_s_n, e0, vz, False, z, zd,
                                                      zdd, out2, counter, zl, zdl, zh, zdh)
                            kind_phi = PHI_BREAK
                        elif mode == START:
                            t_event = _first_crossing(np.int64(PHI_STOP_START), zs, length, a0, b, l_d, slab_mass, 0.0, e0, vz, from_rest, z,
                                                      zd, zdd, out2, counter, zl, zdl, zh, zdh)
                            kind_phi = PHI_STOP_START
                            if t_event >= 0.0:
                                _eval(zs, t_event, zh, zdh, zddh)
                            # a departure's piece hands over to SLIDE at its end, not at r_switch
                            t_sw = -1.0 if departing else _first_crossing(np.int64(PHI_SWITCH), zs, length if t_event < 0.0 else t_event, a0, b, l_d,
                                                   slab_mass, r_switch, e0, vz, False, z, zd, zdd, out2, counter, zl, zdl, zh, zdh)
                            if t_sw > 0.0:
                                t_event = t_sw
                                kind_phi = PHI_SWITCH
                        elif mode == SLIDE:
                            t_event = _first_crossing(np.int64(PHI_HALF), zs, length, a0, b, l_d, slab_mass, half_target, e0, vz, False, z,
                                                      zd, zdd, out2, counter, zl, zdl, zh, zdh)
                            kind_phi = PHI_HALF
                            far = min(rem, h_max, reach_shrink * limit)
                            if slowing and t_event >= 0.0 and far > t_event:
                                # the speed halves within the series' reach: go on towards the stop, to e0·V =
                                # STOP_REACH r0 (within 1 − STOP_REACH of the time to it) and at most REACH_SHRINK of
                                # the reach, so that the tail summed up to there keeps the halving's bound
                                length = far
                                _eval(zs, length, zh, zdh, zddh)
                                t_event = -1.0
                                if use_stop_piece:
                                    # the stop itself within that reach: e0·V = 0 located on this series (the
                                    # friction V/|V| of the series' own V up to there, not frozen as in FINISH) and
                                    # taken as the stop when the speed left there is below FINISH's entry speed
                                    t_stop = _first_crossing(np.int64(PHI_STOP_FINISH), zs, length, a0, b, l_d, slab_mass, 0.0,
                                                             e0, vz, False, z, zd, zdd, out2, counter, zl, zdl, zh, zdh)
                                    if t_stop > 0.0:
                                        _eval(zs, t_stop, z, zd, zdd)
                                        if math.sqrt(z[0, 1] ** 2 + z[1, 1] ** 2) <= r_finish:
                                            t_event = t_stop
                                            kind_phi = PHI_STOP_FINISH
                                            n_stop_pieces += 1
                                if t_event < 0.0:
                                    t_event = _first_crossing(np.int64(PHI_HALF), zs, length, a0, b, l_d, slab_mass,
                                                              2.0 * STOP_REACH * half_target, e0, vz, False, z, zd, zdd,
                                                              out2, counter, zl, zdl, zh, zdh)
                        else:
                            t_event = _first_crossing(np.int64(PHI_STOP_FINISH), zs, length, a0, b, l_d, slab_mass, 0.0, e0, vz, False, z,
                                                      zd, zdd, out2, counter, zl, zdl, zh, zdh)
                            kind_phi = PHI_STOP_FINISH
                        piece = length if t_event < 0.0 else t_event
                        if t_event >= 0.0:
                            _eval(zs, piece, zh, zdh, zddh)
                    # ---- values at both ends, energies, peaks ----
                    if start_valid:
                        for k in range(nk):
                            for d in range(2):
                                val[k, d] = val1[k, d]
                                slope[k, d] = slope1[k, d]
                        for j in range(nj):
                            sval[j] = sval1[j]
                            sslope[j] = sslope1[j]
                    else:
                        _monitors(zl, zdl, zddl, a0[0], a0[1], a0[2], b, m1, m2, m3, sig1, sig2, sig3, val, slope, sval, sslope)
                    a1[0] = a0[0] + b[0] * piece
                    a1[1] = a0[1] + b[1] * piece
                    a1[2] = a0[2] + b[2] * piece
                    _monitors(zh, zdh, zddh, a1[0], a1[1], a1[2], b, m1, m2, m3, sig1, sig2, sig3, val1, slope1, sval1, sslope1)
                    if piece > 0.0:
                        if on_log:
                            _energies_log(lz, la, ltp, lex, lam_piece, total_mass, masses, c_iso, c_floor, mu_k_n,
                                          energy, pin, pvis, lmom, ysc)
                        else:
                            _energies(mode, zs, fs, piece, a0, b, total_mass, masses, c_iso, c_floor, masses.shape[0],
                                      energy, pin, pfr, pvis, ysc, vz)
                        e_in += energy[0]
                        e_f += energy[1]
                        e_v += energy[2]
                        if mode != STUCK:
                            slip_time += piece
                    for k in range(nk):
                        inside = _peak_inside(val, slope, val1, slope1, k, piece, peak_sq)  # updates peak_sq[k]
                        if piece > 0.0 and inside:
                            counter[0] += 1
                            best = _locate_max(zs, lam_piece if on_log else piece, a0, b, m1, m2, m3, sig1, sig2, sig3, k, np.int64(0),
                                               z, zd, zdd, val2, slope2, sval2, sslope2, lz, lzd, lt, on_log)
                            peak_sq[k] = max(peak_sq[k], best)
                    for j in range(nj):
                        sig_max[j] = max(sig_max[j], sval[j], sval1[j])
                        sig_min[j] = min(sig_min[j], sval[j], sval1[j])
                        reach = 2.0 * piece * max(abs(sslope[j]), abs(sslope1[j]))
                        if piece > 0.0 and sslope[j] > 0.0 and sslope1[j] < 0.0 and max(sval[j], sval1[j]) + reach > \
                                sig_max[j]:
                            counter[0] += 1
                            best = _locate_max(zs, lam_piece if on_log else piece, a0, b, m1, m2, m3, sig1, sig2, sig3, j, np.int64(1),
                                               z, zd, zdd, val2, slope2, sval2, sslope2, lz, lzd, lt, on_log)
                            sig_max[j] = max(sig_max[j], best)
                        if piece > 0.0 and sslope[j] < 0.0 and sslope1[j] > 0.0 and min(sval[j], sval1[j]) - reach < \
                                sig_min[j]:
                            counter[0] += 1
                            best = _locate_max(zs, lam_piece if on_log else piece, a0, b, m1, m2, m3, sig1, sig2, sig3, j, np.int64(-1),
                                               z, zd, zdd, val2, slope2, sval2, sslope2, lz, lzd, lt, on_log)
                            sig_min[j] = min(sig_min[j], -best)
                    # the state at the piece's end
                    for d in range(2):
                        for c in range(m):
                            w[d, c] = zh[d, c]
                    if mode == STUCK:
                        for d in range(2):
                            w[d, 0] = x_stuck[d]
                            w[d, 1] = 0.0
                    tau = slow_end if (t_event < 0.0 and length == rem) else tau + piece
                    start_valid = t_event < 0.0
                    if piece > 0.0:
                        from_rest = False
                    a1[0] = ax[i] + b[0] * tau
                    a1[1] = ay[i] + b[1] * tau
                    a1[2] = az[i] + b[2] * tau
                    if t_event < 0.0 or kind_phi == PHI_HALF:
                        if departing and mode == START:
                            # the end of a departure's piece: slide on in time at a speed START would have switched
                            # at; below it (the piece cut by the sample's end) START goes on
                            r = math.sqrt(w[0, 1] ** 2 + w[1, 1] ** 2)
                            if r >= r_switch:
                                mode = SLIDE
                                e0[0] = w[0, 1] / r
                                e0[1] = w[1, 1] / r
                                half_target = 0.5 * r
                                start_valid = False
                        # hand-overs that are not stops: a slide's piece end (the speed halved along e0, or not)
                        # renews the friction's direction; a slide slowing below r_finish enters FINISH; FINISH that
                        # did not stop slides on.  The FINISH test is made at every piece end of a slide, not only
                        # when the speed halved within one piece: where |D| is close to µk N the slab decelerates
                        # slowly, each piece (∝ the time left to the stop) takes less than half of the speed, and a
                        # slide tested only at halvings went on down to |V| ~ 1e-16 m/s, where V/|V| is rounding
                        if mode == SLIDE:
                            r = math.sqrt(w[0, 1] ** 2 + w[1, 1] ** 2)
                            half_target = 0.5 * r
                            if r > 0.0:
                                e0[0] = w[0, 1] / r
                                e0[1] = w[1, 1] / r
                            if r < r_finish:
                                # decelerating below r_finish: finish the stop with the friction's direction frozen
                                if varying:
                                    vz[V_NU0] = 1.0 + (az[i] + bz * tau) / gravity
                                _series(np.int64(SLIDE), w, a1, b, a_mat, g_vec, p_vec, l_d, slab_mass, mu_k_n, e0, zs, fs, ws,
                                        ss, rs, es, vz, mus, exs, h_last)
                                _eval(zs, 0.0, z, zd, zdd)
                                if e0[0] * zd[0, 1] + e0[1] * zd[1, 1] < 0.0:
                                    mode = FINISH
                                    start_valid = False
                            elif use_approach and r < r_approach:
                                # slowing, with pieces cut short by the stop's singularity ~ s/|ṡ| ahead: the rest
                                # of the approach in ln s (the watched values at this end stand: the same equations)
                                s_rate = (w[0, 1] * zdh[0, 1] + w[1, 1] * zdh[1, 1]) / r
                                if (r < approach_below if s_rate < 0.0 else r > approach_above) and s_rate != 0.0 and \
                                        limit < APPROACH_ENTRY * r / abs(s_rate):
                                    mode = APPROACH
                                    grow = 1.0 if s_rate > 0.0 else -1.0
                        elif mode == APPROACH:
                            if approach_done:
                                # slowing, at the finish's speed: the last of the stop with the direction frozen,
                                # as in SLIDE; speeding up, at r_approach: slide on in time (the same equations)
                                r = math.sqrt(w[0, 1] ** 2 + w[1, 1] ** 2)
                                e0[0] = w[0, 1] / r
                                e0[1] = w[1, 1] / r
                                half_target = 0.5 * r
                                if grow < 0.0:
                                    mode = FINISH
                                    start_valid = False
                                else:
                                    mode = SLIDE
                        elif mode == FINISH:
                            r = math.sqrt(w[0, 1] ** 2 + w[1, 1] ** 2)
                            start_valid = False
                            if r > 0.0:
                                mode = SLIDE
                                e0[0] = w[0, 1] / r
                                e0[1] = w[1, 1] / r
                                half_target = 0.5 * r
                        continue
                    # ---- the event ----
                    if kind_phi == PHI_SWITCH:
                        # leaving rest, at 1e-5 v_ref: speeding up in ln s (with the approach), else in time
                        mode = APPROACH if use_approach else SLIDE
                        grow = 1.0
                        r = math.sqrt(w[0, 1] ** 2 + w[1, 1] ** 2)
                        e0[0] = w[0, 1] / r
                        e0[1] = w[1, 1] / r
                        half_target = 0.5 * r
                        continue
                    # a stop (START or FINISH) or a break-away (STUCK): V = 0 exactly
                    events_here += 1
                    approach_below = r_approach
                    approach_above = 0.0
                    for d in range(2):
                        w[d, 1] = 0.0
                    dx = _dot(l_d[0], w[0]) - slab_mass * a1[0]
                    dy = _dot(l_d[1], w[1]) - slab_mass * a1[1]
                    limit = mu_s_n
                    if varying:
                        nu_now = 1.0 + (az[i] + bz * tau) / gravity
                        dx -= vz[V_K_VERT] * (nu_now - 1.0) * w[0, 0]
                        dy -= vz[V_K_VERT] * (nu_now - 1.0) * w[1, 0]
                        limit = mu_s_n * nu_now
                    hold = math.sqrt(dx * dx + dy * dy)
                    if mode == STUCK:
                        kind = BREAKAWAY
                        mode = START
                        from_rest = True
                        depart_lag = 2 if hold <= mu_k_n * (1.0 + DEPART_EXCESS) else 1
                        depart_pending = use_depart and (depart_lag == 2 or use_leave)
                        if depart_pending:
                            # the departure's series runs to the sub-step's end (not to the ladder's shortest rung)
                            slow_end = tau_end
                    elif hold <= limit:
                        kind = STICK
                        mode = STUCK
                        x_stuck[0] = w[0, 0]
                        x_stuck[1] = w[1, 0]
                    else:
                        kind = REVERSAL
                        mode = START
                        from_rest = True
                        # leaving the stop with |D| > µs N ≥ µk N: a finite acceleration, V = τ W
                        depart_lag = 1
                        depart_pending = use_leave
                        if depart_pending:
                            slow_end = tau_end
                    if n_ev < ev_time.shape[0]:
                        ev_time[n_ev] = t_i + tau
                        ev_kind[n_ev] = kind
                        ev_x[n_ev, 0] = w[0, 0]
                        ev_x[n_ev, 1] = w[1, 0]
                    n_ev += 1
                    if events_here > MAX_EVENTS_PER_INTERVAL:
                        status |= STATUS_CHATTER
                        mode = STUCK
                        x_stuck[0] = w[0, 0]
                        x_stuck[1] = w[1, 0]
                else:
                    status |= STATUS_PIECES
            else:
                status |= STATUS_PIECES
        # ---- sample i + 1 ----
        if not start_valid:
            # the last piece ended in an event: the watched values in the new phase
            a1[0] = ax[i + 1]
            a1[1] = ay[i + 1]
            a1[2] = az[i + 1]
            if varying:
                vz[V_NU0] = 1.0 + az[i + 1] / gravity
            _series(SLIDE if mode == APPROACH else mode, w, a1, b, a_mat, g_vec, p_vec, l_d, slab_mass, mu_k_n, e0, zs,
                    fs, ws, ss, rs, es, vz, mus, exs, h_last)
            _eval(zs, 0.0, z, zd, zdd)
            _monitors(z, zd, zdd, a1[0], a1[1], a1[2], b, m1, m2, m3, sig1, sig2, sig3, val1, slope1, sval1, sslope1)
        for d in range(2):
            for c in range(m):
                out_state[i + 1, d, c] = w[d, c]
        for k in range(nk):
            out_mon[i + 1, k, 0] = val1[k, 0]
            out_mon[i + 1, k, 1] = val1[k, 1]
            peak_sq[k] = max(peak_sq[k], val1[k, 0] ** 2 + val1[k, 1] ** 2)
        for j in range(nj):
            out_sig[i + 1, j] = sval1[j]
            sig_max[j] = max(sig_max[j], sval1[j])
            sig_min[j] = min(sig_min[j], sval1[j])
        out_energy[0, i + 1] = e_in
        out_energy[1, i + 1] = e_f
        out_energy[2, i + 1] = e_v
    if n_ev > ev_time.shape[0]:
        status |= STATUS_EVENTS_TRUNCATED
    summary[S_E_INPUT] = e_in
    summary[S_E_FRICTION] = e_f
    summary[S_E_VISCOUS] = e_v
    summary[S_SLIP_TIME] = slip_time
    summary[S_N_EVENTS] = n_ev
    summary[S_STATUS] = status
    summary[S_N_PIECES] = n_pieces
    summary[S_N_LOCATED] = counter[0]
    summary[S_N_FAST] = n_fast_steps
    for k in range(1, 5):
        summary[S_N_REFUSED + k - 1] = n_refused[k]
    for k in range(N_PIECE_KINDS):
        summary[S_N_PIECES_BY_MODE + k] = pieces_by_mode[k]
    summary[S_N_STOP_PIECES] = n_stop_pieces
