r"""The slide along the rims of a µ(v) multi-surface pendulum in the plane: the constraint's force (issue 23).

At the ultimate of ``2d-multisurface+mu(v)`` every surface i is on its rim, |u_i| = d_i*, its outward normal
e_i = u_i/|u_i| and its tangent t_i = (−e_iy, e_ix).  A surface sliding *along* its rim moves as
u̇_i = ψ_i((r − b_i)·t_i) t_i (:func:`isolator.solver.planar_multisurface_rate_kernel.rim_slide`: ψ the inverse of
µ(v) on the tangent, the normal part (r − b_i)·e_i the rim's frictionless reaction).  With no surface sliding
inside its rim there is no pivot: the force r per unit normal load is the root of

    Σ_j ψ_j((r − b_j)·t_j) t_j = Ẋ                                   (sum over the surfaces sliding along their rims)

— the gradient of the strictly convex Σ_j Ψ_j((r − b_j)·t_j) − r·Ẋ, Ψ_j' = ψ_j, so the root is unique where the
tangents span the plane.  :func:`slide_along_rims` solves it by a damped Newton on the 2 × 2 system
A = Σ_j ψ_j' t_j t_jᵀ (bounded: :data:`MAX_NEWTON` iterations, :data:`MAX_HALVINGS` halvings each, the step kept
inside every law's domain |(r − b_j)·t_j| < µ_fast); its error is the residual it returns, asserted against the
tolerance.  With two surfaces the root is in closed form (Ẋ = c_1 t_1 + c_2 t_2, (r − b_j)·t_j = µ_j(c_j)): the
tests hold the Newton to it.

Where the tangents are parallel (:func:`rim_spread` = 0, the rims aligned with the mass's direction) A is of rank 1:
the mass is carried on the rims' common circle, Ẋ·e is not a slide of any surface — only there is the plastic
impact of the ultimate due, removing Ẋ·e alone.  :func:`slide_along_rims` refuses that case by name
(:class:`~isolator.errors.SolverError`); with the rims apart (sine > :data:`ALIGNED_SINE`) it answers for any Ẋ:
no impact is due.

Wired into the driver (h226): the kernel stops where every surface is on its rim with the rims apart
(``STATUS_ALL_RIMS``) and :func:`isolator.solver.planar_multisurface_rate.hand_over` carries the slide on with
:func:`close_along_rims` (Radau, :func:`compiled_root`).  :func:`close_along_rims` integrates that closing from
a given state in numpy (DOP853 on the rims' angles and Ẋ, its energy booked as the kernel books it): the reference
the kernel's mode "all on rims" is to be held to.  With ``method="Radau"`` (h221) it steps implicitly with
:func:`slide_derivatives`' Jacobian and takes the law's sliding mode where three or more surfaces are at µ_fast
beyond its resolution (:func:`saturated_slide`): PTS's slide then reaches the alignment (docs/multisurface.md, h221).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from scipy.optimize import linprog

from isolator.errors import SolverError
from isolator.solver import planar_rim_slide_kernel

#: Newton iterations of :func:`slide_along_rims` (bounded), and halvings of one step (each keeps the laws' domain)
MAX_NEWTON = 200
MAX_HALVINGS = 60
#: Below this sine between two sliding rims' tangents the rims count as aligned (A of rank 1: refused)
ALIGNED_SINE = 1e-9
#: Where the Newton stops at the rounding floor (µ within rounding of µ_fast), the residual it accepts, relative
RESOLVED = 1e-8
#: Up to this many surfaces the forward law's sliding set is searched over the stall set's supersets
MAX_SET_SEARCH = 6


def rim_frames(u) -> tuple[np.ndarray, np.ndarray]:
    """Outward normals e_i and tangents t_i = (−e_iy, e_ix) [n × 2] of surfaces at displacements u [n × 2] (m)."""
    u = np.asarray(u, dtype=float)
    rho = np.hypot(u[:, 0], u[:, 1])
    if not np.all(rho > 0.0):
        raise SolverError("a surface on its rim has zero displacement: its rim's normal is undefined")
    e = u / rho[:, None]
    t = np.column_stack((-e[:, 1], e[:, 0]))
    return e, t


def rim_spread(u) -> float:
    """The largest sine between a surface's rim normal e_i and the mass's direction X/|X|, X = Σ u_i (the kernel's
    ``S_IMPACT_SPREAD``): 0 where the rims are aligned, the only state where the ultimate's impact is due."""
    e, _ = rim_frames(u)
    x = np.sum(np.asarray(u, dtype=float), axis=0)
    norm = math.hypot(x[0], x[1])
    if not norm > 0.0:
        raise SolverError("the mass is at the origin: the rims' alignment is undefined")
    return float(np.max(np.abs(e[:, 0] * x[1] - e[:, 1] * x[0])) / norm)


def _laws(s, mu_s, mu_f, a):
    """Ψ_j(s_j), ψ_j(s_j) = Ψ_j', ψ_j' of the true law on the tangent (0 in the dead zone |s| ≤ µ_slow, held; past
    it ψ = sign(s) ln((µ_f − µ_s)/(µ_f − |s|))/a, the inverse of µ(v)); None outside |s| < µ_fast.
    Ψ(s) = (g ln(g/g₀) + g₀ − g)/a, g = µ_f − |s|, g₀ = µ_f − µ_s: the integral of ψ from the onset."""
    x = np.abs(s)
    if not np.all(x < mu_f):
        return None
    g0 = mu_f - mu_s
    g = np.where(x > mu_s, mu_f - x, g0)
    big = np.log(g0 / g) / a
    pot = (g * np.log(g / g0) + g0 - g) / a
    psi = np.sign(s) * big
    dpsi = np.where(x > mu_s, 1.0 / (a * g), 0.0)
    return pot, psi, dpsi


def _start(b, t, mu_f):
    """A force strictly inside every law's domain |(r − b_j)·t_j| < µ_fast,j with the largest margin (a linear
    programme); refused by name where the strips do not meet."""
    bt = np.einsum("ij,ij->i", b, t)
    n = len(t)
    # variables (r_x, r_y, m): maximise m subject to ±t_j·r + m ≤ µ_fast,j ± b_j·t_j
    a_ub = np.vstack((np.column_stack((t, np.ones(n))), np.column_stack((-t, np.ones(n)))))
    sol = linprog([0.0, 0.0, -1.0], A_ub=a_ub, b_ub=np.concatenate((mu_f + bt, mu_f - bt)),
                  bounds=[(None, None), (None, None), (None, None)], method="highs")
    if sol.status != 0 or not sol.x[2] > 0.0:
        raise SolverError(
            "the surfaces on their rims admit no force inside their friction laws (|f·t| < µ_fast for all): "
            "their restoring terms are too far apart")
    return np.asarray(sol.x[:2], dtype=float)


def _forward_sets(xdot, b, t, s, psi, mu_s, mu_f, a, tol):
    """:func:`_forward` over the set sliding at the stall, then over its supersets (each new surface in the sense of
    its force at the stall; at most 2ⁿ sets, n ≤ :data:`MAX_SET_SEARCH`): the convex problem's root is unique, so the
    first set whose answer passes the checks (held surfaces in their dead zones, rates in their senses) is it."""
    n = len(t)
    stall = [j for j in range(n) if abs(s[j]) > mu_s[j]]
    others = [j for j in range(n) if j not in stall]
    if n > MAX_SET_SEARCH:
        others = []
    for extra in range(len(others) + 1):
        for add in itertools.combinations(others, extra):
            chosen = sorted(stall + list(add))
            if len(chosen) < 2:
                continue
            guess = psi.copy()
            for j in add:
                guess[j] = math.copysign(1e-3, s[j]) if s[j] != 0.0 else 1e-3
            ans = _forward(xdot, b, t, s, guess, mu_s, mu_f, a, tol, np.array(chosen))
            if ans is not None:
                return ans
    return None


def _forward(xdot, b, t, s, psi, mu_s, mu_f, a, tol, slide, checked=True):
    """Where ψ' has outgrown the rounding (µ near µ_fast), the same root by the forward law over the set sliding at
    the stall (|s_j| > µ_slow), each in its sense σ_j: unknowns the rates ψ_j and r, equations
    (r − b_j)·t_j = σ_j µ_j(σ_j ψ_j) (µ continued through the onset in that sense) and Σ ψ_j t_j = Ẋ — Newton on the
    saddle system [−µ', T; Tᵀ, 0], well conditioned at any speed while one sliding surface's µ' or exactly two
    sliding tangents fix the split (bounded: :data:`MAX_NEWTON`).  None where it does not converge to ``tol``, or
    the answer leaves a held surface outside its dead zone or a rate against its sense (the caller refuses)."""
    ns = len(slide)
    if ns < 2:
        return None
    ts = t[slide]
    sig = np.where(psi[slide] != 0.0, np.sign(psi[slide]), np.sign(s[slide]))
    if not np.all(sig != 0.0):
        return None
    m_s, m_f, aa = mu_s[slide], mu_f[slide], a[slide]
    bt = np.einsum("ij,ij->i", b[slide], ts)
    rates = psi[slide].astype(float).copy()
    r_s = np.linalg.lstsq(ts, s[slide] + bt, rcond=None)[0]
    jac = np.zeros((ns + 2, ns + 2))
    for _ in range(MAX_NEWTON):
        power = -aa * sig * rates
        if not np.all(power < 700.0):  # a rate driven far against its sense: this set is not the answer
            return None
        decay = np.exp(power)
        fric = sig * (m_s - (m_f - m_s) * np.expm1(power))
        f = np.concatenate((ts @ r_s - bt - fric, ts.T @ rates - xdot))
        if math.hypot(f[-2], f[-1]) <= tol and np.max(np.abs(f[:ns])) <= 4.0 * np.finfo(float).eps:
            break
        jac[:ns, :ns] = np.diag(-aa * (m_f - m_s) * decay)
        jac[:ns, ns:] = ts
        jac[ns:, :ns] = ts.T
        try:
            delta = np.linalg.solve(jac, -f)
        except np.linalg.LinAlgError:
            return None
        if not np.all(np.isfinite(delta)):
            return None
        rates = rates + delta[:ns]
        r_s = r_s + delta[ns:]
    else:
        return None
    s_all = np.einsum("ij,ij->i", r_s[None, :] - b, t)
    held = np.ones(len(t), dtype=bool)
    held[slide] = False
    if checked and not (np.all(np.abs(s_all[held]) <= mu_s[held]) and np.all(rates * sig > 0.0)):
        return None
    out = np.zeros(len(t))
    out[slide] = rates
    res = t.T @ out - xdot
    return r_s, out, math.hypot(res[0], res[1]), -1


def _grown_sets(xdot, b, t, mu_s, mu_f, a, tol):
    """The forward law's sliding set grown from each pair (h199): where the stall's set and its supersets do not
    converge from their seeds (three surfaces sliding, the third between µ_slow and µ_fast — met along PTS's closing),
    every pair and sense is solved by :func:`_forward`; a surface outside its dead zone at the answer joins with the
    rate its own inverse law gives there as the seed (bounded: 2n growths per pair).  The first answer that passes
    :func:`_forward`'s checks is the convex problem's unique root."""
    n = len(t)
    if n > MAX_SET_SEARCH:
        return None
    eps = np.finfo(float).eps
    for pair in itertools.combinations(range(n), 2):
        for sense in itertools.product((1.0, -1.0), repeat=2):
            slide = list(pair)
            psi = np.zeros(n)
            s = np.zeros(n)
            for j, sg in zip(pair, sense, strict=True):
                psi[j] = 1e-3 * sg
                s[j] = 0.999 * mu_f[j] * sg
            for _ in range(2 * n):
                ans = _forward(xdot, b, t, s, psi, mu_s, mu_f, a, tol, np.array(slide), checked=False)
                if ans is None:
                    break
                r_s, rates = ans[0], ans[1]
                s = np.einsum("ij,ij->i", r_s[None, :] - b, t)
                bad = [j for j in range(n) if j not in slide and abs(s[j]) > mu_s[j]]
                if not bad:
                    final = _forward(xdot, b, t, s, rates, mu_s, mu_f, a, tol, np.array(slide))
                    if final is not None:
                        return final
                    break
                psi = rates.copy()
                for j in bad:
                    gap = max(mu_f[j] - abs(s[j]), 4.0 * eps * mu_f[j])
                    psi[j] = math.copysign(math.log((mu_f[j] - mu_s[j]) / gap) / a[j] if gap < mu_f[j] - mu_s[j]
                                           else 1e-6, s[j])
                    slide.append(j)
                slide.sort()
    return None


def _forward_any(xdot, b, t, r, psi, mu_s, mu_f, a, tol):
    """The forward law's answer at the Newton's last force ``r``: the stall's set and its supersets, else the set
    grown from the pairs; None where neither answers."""
    s_now = np.einsum("ij,ij->i", r[None, :] - b, t)
    fwd = _forward_sets(xdot, b, t, s_now, psi, mu_s, mu_f, a, tol)
    return fwd if fwd is not None else _grown_sets(xdot, b, t, mu_s, mu_f, a, tol)


def slide_along_rims(xdot, b, u, mu_s, mu_f, a, *, rtol=1e-13):
    """The force r [-, per unit normal load] that moves surfaces on their rims at the mass's velocity Ẋ.

    ``xdot`` Ẋ [2] (m/s); ``b`` the surfaces' restoring terms b_j [n × 2] (-); ``u`` their displacements [n × 2] (m),
    each on its rim; ``mu_s``, ``mu_f``, ``a`` the laws µ_j(v) = µ_f − (µ_f − µ_s) e^(−a v) [n].  Each surface is
    held (|(r − b_j)·t_j| ≤ µ_slow,j) or slides along its rim at ψ_j.  r minimises the convex
    Φ(r) = Σ_j Ψ_j((r − b_j)·t_j) − r·Ẋ (its gradient is the equation); damped Newton on Φ, bounded.
    Returns (r [2], the rates ψ_j [n] (m/s, along t_j), the residual |Σ ψ_j t_j − Ẋ| (m/s), iterations; −1 where
    the Newton stalled on the law's slope and the forward law with two sliding surfaces answered, :func:`_forward`).
    Raises :class:`~isolator.errors.SolverError` where the tangents do not span the plane (the rims aligned: the
    ultimate's impact) or where the Newton does not reach ``rtol`` of the velocity scale (nor the rounding floor).
    """
    xdot = np.asarray(xdot, dtype=float)
    b = np.asarray(b, dtype=float)
    mu_s = np.asarray(mu_s, dtype=float)
    mu_f = np.asarray(mu_f, dtype=float)
    a = np.asarray(a, dtype=float)
    if not (np.all(mu_f > mu_s) and np.all(a > 0.0)):
        raise SolverError(
            "the slide along the rims needs µ_fast > µ_slow and a > 0 on every surface (µ_fast = µ_slow is constant "
            "friction: the constant-µ model's rim slide)")
    _, t = rim_frames(u)
    n = len(t)
    sine = max((abs(t[i, 0] * t[j, 1] - t[i, 1] * t[j, 0]) for i in range(n) for j in range(i + 1, n)), default=0.0)
    if not sine > ALIGNED_SINE:
        raise SolverError(
            f"the rims of the {n} surface(s) are aligned (largest sine {sine:.3g}): the mass is carried on their "
            "common circle, the ultimate's impact is due (not a slide along the rims)")
    r = _start(b, t, mu_f)
    scale = math.hypot(xdot[0], xdot[1]) + float(np.max((mu_f - mu_s) / a))
    eps = np.finfo(float).eps

    def evaluate(rr):
        s = np.einsum("ij,ij->i", rr[None, :] - b, t)
        law = _laws(s, mu_s, mu_f, a)
        if law is None:
            return None
        pot, psi, dpsi = law
        return float(np.sum(pot) - rr @ xdot), psi, dpsi

    state = evaluate(r)
    for it in range(MAX_NEWTON):
        phi, psi, dpsi = state
        grad = t.T @ psi - xdot
        err = math.hypot(grad[0], grad[1])
        # near µ_fast ψ' = 1/(a (µ_fast − |s|)) is large: the residual cannot fall below ψ' × the rounding of s
        floor = 16.0 * eps * float(np.sum(dpsi * (1.0 + math.hypot(r[0], r[1]) + np.hypot(b[:, 0], b[:, 1]))))
        if err <= rtol * scale:
            return r, psi, err, it
        if err <= floor:
            if err > RESOLVED * scale:
                fwd = _forward_any(xdot, b, t, r, psi, mu_s, mu_f, a, rtol * scale)
                if fwd is not None:
                    return fwd
                raise SolverError(
                    f"the slide along the rims needs rates the µ(v) law does not resolve here (largest "
                    f"{float(np.max(np.abs(psi))):.3g} m/s, slope ψ' up to {float(np.max(dpsi)):.3g} m/s per unit "
                    f"friction, µ_fast − µ down to {1.0 / float(np.max(a * dpsi)):.3g}): the Newton stops at a "
                    f"residual of {err:.3g} m/s of {math.hypot(xdot[0], xdot[1]):.3g}")
            return r, psi, err, it
        # a held surface has ψ' = 0: the model takes its slope at the onset, 1/(a (µ_f − µ_s)), so that the
        # Newton matrix is regular wherever the tangents span the plane (the line search on Φ keeps the descent)
        model = np.where(dpsi > 0.0, dpsi, 1.0 / (a * (mu_f - mu_s)))
        step = np.linalg.solve((t * model[:, None]).T @ t, -grad)
        lam = 1.0
        for _ in range(MAX_HALVINGS):
            trial = evaluate(r + lam * step)
            if trial is not None:
                tgrad = t.T @ trial[1] - xdot
                if trial[0] <= phi + 1e-4 * lam * float(grad @ step) or math.hypot(tgrad[0], tgrad[1]) < err:
                    break
            lam *= 0.5
        else:
            break
        r = r + lam * step
        state = trial
    psi = state[1]
    res = t.T @ psi - xdot
    # the Newton on Φ crawls where a law is near µ_fast (met along a closing, h199): the forward law's sets
    fwd = _forward_any(xdot, b, t, r, psi, mu_s, mu_f, a, rtol * scale)
    if fwd is not None:
        return fwd
    raise SolverError(
        f"the force of the slide along the rims did not converge ({MAX_NEWTON} Newton iterations; residual "
        f"{math.hypot(res[0], res[1]):.3g} m/s)")


def slide_derivatives(b, u, r, psi, bmat, mu_s, mu_f, a, *, sliding=None):
    """The derivatives of the slide's force r and rates ψ (:func:`slide_along_rims`'s root) with respect to the
    surfaces' angles θ_q on their rims (u_q = d_q (cos θ_q, sin θ_q)) and the mass's velocity Ẋ, within the sliding
    set of the root given (ψ_i ≠ 0; the held ones stay at ψ = 0) — the implicit function theorem on the forward
    law's saddle system (h221).  Over the sliding set S (each in its sense σ_i, m_i(ψ) = σ_i µ_i(σ_i ψ)):

        F_i = (r − b_i)·t_i − m_i(ψ_i) = 0 (i ∈ S),   G = Σ_{i∈S} ψ_i t_i − Ẋ = 0,   b = B u,

    K = ∂(F, G)/∂(ψ_S, r) = [−diag m', T; Tᵀ, 0] (T the sliding tangents as rows; m' = a (µ_f − µ_s) e^(−a|ψ|), the
    reciprocal of the inverse law's slope ψ' — the 2 × 2 Schur complement Tᵀ diag(ψ') T = Σ ψ' t tᵀ is h216's
    matrix, but the saddle form stays well conditioned where ψ' ~ 1/(a (µ_f − |s|)) has outgrown the rounding), and
    ∂F_i/∂θ_q = −B_iq d_q t_q·t_i − δ_iq (r − b_i)·e_i, ∂G/∂θ_q = −ψ_q e_q, ∂G/∂Ẋ = −I, ∂F/∂Ẋ = 0 (∂t_q/∂θ_q = −e_q,
    ∂u_q/∂θ_q = d_q t_q).  Returns (dr [2 × (n + 2)], dψ [n × (n + 2)]), the columns θ_1..θ_n, Ẋ_x, Ẋ_y.
    ``sliding`` [n, bool] overrides the set (default ψ ≠ 0): a held surface named in it enters at its onset slope
    m' = a (µ_f − µ_s) with ψ = 0 — the one-sided derivative toward its start (the implicit step's Jacobian where
    fewer than two slide, e.g. Ẋ along one rim's tangent, where the two-sided one does not exist).
    Raises :class:`~isolator.errors.SolverError` where K is singular (fewer than two sliding tangents apart)."""
    u, b, r, psi = (np.asarray(x, dtype=float) for x in (u, b, r, psi))
    e, t = rim_frames(u)
    cap = np.hypot(u[:, 0], u[:, 1])
    n = len(cap)
    slide = np.flatnonzero(psi != 0.0 if sliding is None else np.asarray(sliding, dtype=bool))
    ns = len(slide)
    ts = t[slide]
    slope = a[slide] * (mu_f[slide] - mu_s[slide]) * np.exp(-a[slide] * np.abs(psi[slide]))
    kmat = np.zeros((ns + 2, ns + 2))
    kmat[:ns, :ns] = -np.diag(slope)
    kmat[:ns, ns:] = ts
    kmat[ns:, :ns] = ts.T
    rhs = np.zeros((ns + 2, n + 2))
    # ∂F_i/∂θ_q: the restoring terms turn with every surface's angle, the tangent with its own
    rhs[:ns, :n] = -np.asarray(bmat, dtype=float)[slide] * cap[None, :] * (ts @ t.T)
    rhs[np.arange(ns), slide] -= np.einsum("ij,ij->i", r[None, :] - b[slide], e[slide])
    rhs[ns:, :n] = -(psi[:, None] * e).T
    rhs[ns:, n:] = -np.eye(2)
    if ns < 2 or not abs(np.linalg.det(ts.T @ ts)) > ALIGNED_SINE ** 2:
        raise SolverError(
            f"the slide's derivatives need two sliding tangents apart ({ns} sliding): the saddle system is singular")
    sol = np.linalg.solve(kmat, -rhs)
    dpsi = np.zeros((n, n + 2))
    dpsi[slide] = sol[:ns]
    return sol[ns:], dpsi


#: The deficit µ_fast − |s| below which a sliding surface counts as at µ_fast (:func:`saturated_slide`, h221): µ(v) =
#: µ_f − (µ_f − µ_s) e^(−a v) resolves v only while the deficit is above the rounding of µ (~4e-18 at µ_f = 0.02);
#: with three or more surfaces there, the split of their rates is beyond the law's resolution
SATURATED_GAP = 1e-12


def saturated_slide(xdot, b, u, bmat, member, sense, mu_s, mu_f, a, *, floor=0.0):
    """The slide along the rims with the surfaces ``member`` (k ≥ 3) at µ_fast taken exactly, (r − b_i)·t_i =
    σ_i µ_f,i (``sense`` σ_i, in the order of the members) — h221, the limit that :func:`slide_along_rims` cannot
    resolve: with k ≥ 3 such lines for the 2 unknowns of r, their concurrence is a constraint on the rims' angles
    (a sliding mode: on either side of it the law's root swaps which surface is a hair below µ_fast, ~1e-25 apart in
    the angles), and the rates are its multipliers.  r is the lines' least-squares point (exact on the constraint;
    the residual returned is the drift); the other surfaces slide by their own law at r (held in their dead zones);
    the members' rates solve Σ ψ_j t_j = Ẋ and the hidden constraints' time derivatives, Σ_i w_i d/dt[(r − b_i)·t_i]
    = 0 for each w in the null space of the members' tangents (Σ w_i t_i = 0, so ṙ drops out):

        Σ_i w_i [Σ_q B_iq (t_q·t_i) ψ_q + ((r − b_i)·e_i / d_i) ψ_i] = 0          (ḃ_i = Σ_q B_iq ψ_q t_q, θ̇_i = ψ_i/d_i)

    ``floor`` > 0 continues a non-member's law past its domain (its deficit µ_f − |s| taken as at least ``floor``):
    :func:`close_along_rims` stops where a deficit reaches a gap ≫ floor (the surface joins), so only its trial
    stages and difference Jacobians see the continuation.  Returns (r [2], ψ [n], the lines' residual).  Raises
    :class:`~isolator.errors.SolverError` where a non-member is past µ_fast at r (floor 0) or the system is
    singular."""
    u, b, bmat = (np.asarray(x, dtype=float) for x in (u, b, bmat))
    e, t = rim_frames(u)
    cap = np.hypot(u[:, 0], u[:, 1])
    n = len(cap)
    fset = np.flatnonzero(np.asarray(member, dtype=bool))
    rest_set = np.setdiff1d(np.arange(n), fset)
    if len(fset) < 3:
        raise SolverError(f"the saturated slide needs three or more surfaces at µ_fast ({len(fset)} given)")
    tf = t[fset]
    lines = np.einsum("ij,ij->i", b[fset], tf) + np.asarray(sense, dtype=float) * mu_f[fset]
    r = np.linalg.lstsq(tf, lines, rcond=None)[0]
    residual = float(np.max(np.abs(tf @ r - lines)))
    s = np.einsum("ij,ij->i", r[None, :] - b, t)
    psi = np.zeros(n)
    for q in rest_set:
        x = abs(s[q])
        if not (x < mu_f[q] or floor > 0.0):
            raise SolverError(f"the saturated slide leaves surface {q + 1} past its µ_fast ({x:.6g} ≥ {mu_f[q]:.6g})")
        if x > mu_s[q]:
            psi[q] = math.copysign(math.log((mu_f[q] - mu_s[q]) / max(mu_f[q] - x, floor)) / a[q], s[q])
    null = np.linalg.svd(tf.T)[2][2:]  # (k − 2) × k: Σ_i w_i t_i = 0
    hidden = -(null @ (bmat[fset] * (tf @ t.T)))
    hidden[:, fset] -= null * (np.einsum("ij,ij->i", r[None, :] - b[fset], e[fset]) / cap[fset])[None, :]
    system = np.vstack((tf.T, hidden[:, fset]))
    rhs = np.concatenate((np.asarray(xdot, dtype=float) - t.T @ psi, -hidden @ psi))
    try:
        psi[fset] = np.linalg.solve(system, rhs)
    except np.linalg.LinAlgError as exc:
        raise SolverError("the saturated slide's rates are singular (the members' tangents do not span)") from exc
    return r, psi, residual


#: Where :func:`close_along_rims` stops before the alignment: 1 − |X|/Σ d* (the gap closes linearly in time while the
#: angle between the rims closes as its square root; the friction work left is ~ µ g × that angle, ≤ 1e-6 rad here)
ALIGNED_GAP = 1e-12
#: Where the law's root is not found at a segment's start (an accepted state) with the rims this close to their
#: alignment (1 − |X|/Σ d*), the alignment is taken there (h226): the last degree of the approach, rates ∝ 1/sine,
#: is resolved by neither force (h204); the gap left is reported (``gap``), the impact's error ~ |Ẋ| × the sine left
ALIGNED_FALLBACK_GAP = 1e-8


#: The implicit methods of :func:`close_along_rims` (scipy's, with :func:`slide_derivatives`'s Jacobian, h221)
IMPLICIT = ("Radau", "BDF")

#: Bound on the segments of :func:`close_along_rims` (each ends at a located change of the sliding set)
MAX_SEGMENTS = 10_000


def compiled_root():
    """A root of the slide's force for :func:`close_along_rims` (``root=``): the compiled
    :func:`isolator.solver.planar_rim_slide_kernel.rim_slide_force` (1.4–63 µs a force against numpy's 10–60 ms,
    within 1.7e-12 of it: h204), seeded by its previous answer; where it finds no set, :func:`slide_along_rims`
    (which then answers or refuses by name).  Returns (root, counts): counts["compiled"], counts["numpy"]."""
    seed = np.zeros(0)
    counts = {"compiled": 0, "numpy": 0}

    def root(xdot, b, u, mu_s, mu_f, a):
        nonlocal seed
        _, t = rim_frames(u)
        if seed.size != len(t):
            seed = np.zeros(len(t))
        r = np.zeros(2)
        psi = np.zeros(len(t))
        found = planar_rim_slide_kernel.rim_slide_force(
            np.ascontiguousarray(xdot, dtype=float), np.ascontiguousarray(b, dtype=float), np.ascontiguousarray(t),
            np.asarray(mu_s, dtype=float), np.asarray(mu_f, dtype=float), np.asarray(a, dtype=float), 1e-13, seed,
            r, psi)
        if found == planar_rim_slide_kernel.NOT_FOUND:
            counts["numpy"] += 1
            r, psi, res, it = slide_along_rims(xdot, b, u, mu_s, mu_f, a)
        else:
            counts["compiled"] += 1
            res = float(np.hypot(*(t.T @ psi - np.asarray(xdot, dtype=float))))
            it = 0
        seed = np.array(psi, dtype=float)
        return r, psi, res, it

    return root, counts


def close_along_rims(t0, xdot, u, bmat, smat, rbar, mu_s, mu_f, a, g, c, times, ax, ay, t_end, *, rtol=1e-10,
                     gap_end=ALIGNED_GAP, max_segments=MAX_SEGMENTS, method="DOP853", saturated_gap=SATURATED_GAP,
                     root=slide_along_rims, max_forces=None):
    """The mass carried by surfaces that are all on their rims, the rims apart: integrated to the alignment (h199).

    State: each surface's angle θ_i on its rim (u_i = d_i (cos θ_i, sin θ_i), d_i = |u_i| at the start) and Ẋ;
    θ̇_i = ψ_i/d_i with r and the rates from :func:`slide_along_rims`, Ẍ = −g r − c Ẋ − a_g(t) (a_g linear between
    the samples ``times``/``ax``/``ay``); b = B u (``bmat``).  DOP853 at ``rtol`` (numpy, not compiled; ~10–90 ms a
    force at the saturated rates).  The sliding set changes where a surface's |(r − b_i)·t_i| crosses µ_slow,i (its
    dead zone's edge: ψ_i' jumps from 0 to 1/(a (µ_f − µ_s)), a rate changing sign passes through it): each crossing
    is located as an event and the integration restarted there (h216), so that within a segment the set is fixed
    and the right-hand side smooth; at most ``max_segments`` segments (refused by name past it).  It stops at the
    first of: the rims aligned (1 − |X|/Σ d ≤ ``gap_end``: the
    ultimate's impact is due there, of e·Ẋ only), a surface's rim reaction (r − b_i)·e_i turning negative (it
    leaves its rim inward: the kernel's regime), the mass at rest (|Ẋ| ≤ 1e-9 m/s), ``t_end``.

    Returns a dict: ``t``, ``u`` [n × 2], ``xdot``, ``reason`` (``"aligned"``, ``"leaves"``, ``"rest"``, ``"end"``),
    the energies per unit mass over the closing (``input``, ``friction`` = g Σ∫(r − b_i)·dū_i on the elements
    ū = S u as the kernel books it, ``viscous``, ``kinetic``/``potential`` at both ends as pairs, ``balance`` =
    input − Δkinetic − Δpotential − friction − viscous), ``least_saturation`` (the least a_i|ψ_i| of a sliding
    surface met: ≥ ~37 means µ = µ_fast to rounding, the constant-µ law), ``largest_held`` (the largest
    |(r − b_i)·t_i|/µ_slow,i of a held surface: ≤ 1), ``forces`` (the force evaluations) and ``set_changes`` (the
    located crossings of a dead zone's edge).

    ``method`` "Radau" or "BDF" (h221): the segments of the law's root are stepped implicitly with
    :func:`slide_derivatives`' Jacobian, and the saturated mode is taken: where three or more sliding surfaces' lines
    (r − b_i)·t_i = σ_i µ_f,i meet within ``saturated_gap`` (an event), the slide goes on by :func:`saturated_slide`
    (DOP853: its rates are set by the geometry, not stiff) until a member's deficit (µ_f − µ_s) e^(−a|ψ|) would
    exceed the gap (it leaves the set; with fewer than three the law's root again), another surface's deficit falls
    to the gap (it joins), or a dead zone's edge; the dict then also holds ``saturated_segments``, ``drift`` (the
    largest lines' residual at a saturated segment's end: the constraint's drift), ``set_exits`` (members dropped at
    a segment's start, their rate below the resolution or against their sense) and ``modes`` (each segment's start
    and its saturated members, numbered from 1; () for the law's root).

    ``root``: the law's root (the signature and answer of :func:`slide_along_rims`, the default); the driver's
    hand-over passes :func:`compiled_root`'s (h226).  ``max_forces``: a bound on the force evaluations (None: none),
    refused by name past it.
    """
    from scipy.integrate import solve_ivp

    if method not in IMPLICIT + ("DOP853",):
        raise SolverError(f"the closing along the rims has no method {method!r} (DOP853, Radau or BDF)")

    u = np.asarray(u, dtype=float)
    cap = np.hypot(u[:, 0], u[:, 1])
    n = len(cap)
    total = float(np.sum(cap))
    rbar = np.asarray(rbar, dtype=float)
    log = {"forces": 0, "least_saturation": math.inf, "largest_held": 0.0, "saturated_segments": 0, "drift": 0.0,
           "set_exits": 0, "modes": [], "no_force": 0}
    mode = {"set": None, "sense": None}  # the saturated mode's members and senses (None: the law's root)
    level = np.log((mu_f - mu_s) / saturated_gap)  # a|ψ| at which the deficit (µ_f − µ_s) e^(−a|ψ|) is the gap

    def frame(theta):
        e = np.column_stack((np.cos(theta), np.sin(theta)))
        return cap[:, None] * e, e, np.column_stack((-e[:, 1], e[:, 0]))

    last = {}

    def force(z):
        key = z[:n + 2].tobytes()
        if key in last:  # the events at a step's end share one force (h216)
            return last[key]
        if max_forces is not None and log["forces"] >= max_forces:
            raise SolverError(f"the slide along the rims reached no event in {max_forces} force evaluations (from t = "
                              f"{float(t0):.9g} s; the last segment from t = {time_now:.9g} s)")
        uu, e, t = frame(z[:n])
        b = bmat @ uu
        if mode["set"] is None:
            try:
                r, psi, _, _ = root(z[n:n + 2], b, uu, mu_s, mu_f, a)
            except SolverError:
                if method not in IMPLICIT:
                    raise
                # a collocation iterate where no force exists (the strips |(r − b_j)·t_j| < µ_fast,j apart: met on a
                # first step too long for rates ~250 m/s on 0.05 m caps, h226): NaN makes the implicit method's Newton
                # fail and the step shrink; at an accepted state the method stops and the closing is refused by name
                r, psi = np.full(2, np.nan), np.full(n, np.nan)
                log["no_force"] += 1
        else:
            r, psi, _ = saturated_slide(z[n:n + 2], b, uu, bmat, mode["set"], mode["sense"], mu_s, mu_f, a,
                                        floor=1e-3 * saturated_gap)
        log["forces"] += 1
        last.clear()
        last[key] = (uu, e, t, b, r, psi)
        return last[key]

    def rate(time_now, z):
        _, _, t, b, r, psi = force(z)
        gx = float(np.interp(time_now, times, ax))
        gy = float(np.interp(time_now, times, ay))
        v = z[n:n + 2]
        sliding = psi != 0.0
        s = np.einsum("ij,ij->i", r[None, :] - b, t)
        if np.any(sliding):
            log["least_saturation"] = min(log["least_saturation"], float(np.min(a[sliding] * np.abs(psi[sliding]))))
        if not np.all(sliding):
            log["largest_held"] = max(log["largest_held"], float(np.max(np.abs(s[~sliding]) / mu_s[~sliding])))
        out = np.empty_like(z)
        out[:n] = psi / cap
        out[n] = -g * r[0] - c * v[0] - gx
        out[n + 1] = -g * r[1] - c * v[1] - gy
        out[n + 2] = -(gx * v[0] + gy * v[1])
        out[n + 3] = g * float(np.sum((r[None, :] - b) * (smat @ (psi[:, None] * t))))
        out[n + 4] = c * float(v @ v)
        return out

    def jacobian(time_now, z):
        uu, e, t, b, r, psi = force(z)
        sliding = psi != 0.0
        dr, dpsi = slide_derivatives(b, uu, r, psi, bmat, mu_s, mu_f, a,
                                     sliding=sliding if np.count_nonzero(sliding) >= 2 else np.ones(n, dtype=bool))
        v = z[n:n + 2]
        jac = np.zeros((n + 5, n + 5))
        jac[:n, :n + 2] = dpsi / cap[:, None]
        jac[n:n + 2, :n + 2] = -g * dr
        jac[n:n + 2, n:n + 2] -= c * np.eye(2)
        jac[n + 2, n:n + 2] = -np.array([np.interp(time_now, times, ax), np.interp(time_now, times, ay)])
        # the friction power g Σ_i (r − b_i)·w_i, w = S (ψ t): through r, b = B u, ψ and the tangents
        w = smat @ (psi[:, None] * t)
        h = smat.T @ (r[None, :] - b)
        power = np.sum(w, axis=0) @ dr + np.einsum("j,jp->p", np.einsum("ij,ij->i", h, t), dpsi)
        power[:n] -= cap * np.einsum("ij,ij->i", t, bmat.T @ w) + psi * np.einsum("ij,ij->i", h, e)
        jac[n + 3, :n + 2] = g * power
        jac[n + 4, n:n + 2] = 2.0 * c * v
        return jac

    def aligned(_, z):
        x = np.sum(frame(z[:n])[0], axis=0)
        return (total - math.hypot(x[0], x[1])) / total - gap_end

    def leaves(_, z):
        _, e, _, b, r, _ = force(z)
        return float(np.min(np.einsum("ij,ij->i", r[None, :] - b, e)))

    def rest(_, z):
        return math.hypot(z[n], z[n + 1]) - 1e-9

    def edge(i, direction):
        def crossing(_, z):
            _, _, t, b, r, _ = force(z)  # the step's shared force: its frame and b = B u too
            return abs(float((r - b[i]) @ t[i])) - float(mu_s[i])
        crossing.terminal = True
        crossing.direction = direction
        return crossing

    def lines_residual(z, member, sense):
        uu, _, t = frame(z[:n])
        tf = t[member]
        lines = np.einsum("ij,ij->i", (bmat @ uu)[member], tf) + sense * mu_f[member]
        return float(np.max(np.abs(tf @ np.linalg.lstsq(tf, lines, rcond=None)[0] - lines)))

    def concurrent(_, z):
        psi = force(z)[5]
        if np.count_nonzero(psi) < 3:
            return 1.0
        return lines_residual(z, psi != 0.0, np.sign(psi[psi != 0.0])) - saturated_gap

    def member_leaves(i, sense):
        def deficit(_, z):
            return a[i] * sense * force(z)[5][i] - level[i]
        deficit.terminal = True
        deficit.direction = -1
        return deficit

    def joins(i):
        def deficit(_, z):
            _, _, t, b, r, _ = force(z)
            return mu_f[i] - abs(float((r - b[i]) @ t[i])) - saturated_gap
        deficit.terminal = True
        deficit.direction = -1
        return deficit

    for event in (aligned, leaves, rest, concurrent):
        event.terminal = True
        event.direction = -1
    def held_at(z):
        """Each surface inside its dead zone at z: its edge is met going out (+1), a sliding surface's going in (−1)."""
        _, _, t, b, r, _ = force(z)
        return np.abs(np.einsum("ij,ij->i", r[None, :] - b, t)) <= mu_s

    def switch(member, sense, z):
        """The saturated mode on ``member`` (three or more, in the ``sense`` given), else the law's root again (the
        held set read afresh at z)."""
        nonlocal held
        last.clear()
        if np.count_nonzero(member) >= 3:
            mode["set"], mode["sense"] = member, np.asarray(sense, dtype=float)
        else:
            mode["set"] = mode["sense"] = None
            held = held_at(z)

    def saturate(z):
        """The saturated mode on the surfaces sliding at z (three or more: the ``concurrent`` event)."""
        psi = force(z)[5]
        switch(psi != 0.0, np.sign(psi[psi != 0.0]), z)

    z = np.concatenate((np.arctan2(u[:, 1], u[:, 0]), np.asarray(xdot, dtype=float), np.zeros(3)))
    z0 = z.copy()
    held = held_at(z)
    time_now, reason, changes, stalled = float(t0), "end", 0, 0
    if method in IMPLICIT and concurrent(time_now, z) <= 0.0:  # handed over on the saturated mode's constraint
        saturate(z)
    for _ in range(max_segments):
        edges = [edge(i, 1 if held[i] else -1) for i in range(n)]
        if mode["set"] is not None:  # the saturated mode (h221): the implicit method, its Jacobian by differences
            members = np.flatnonzero(mode["set"])
            margin = a[members] * mode["sense"] * force(z)[5][members] - level[members]
            if np.min(margin) <= 0.0:
                # a member whose rate is below µ_fast's resolution or against its sense (met where a fourth line
                # joins three concurrent ones, PTS at 12.29109 s): it leaves the set, its rate its own law's
                worst = int(np.argmin(margin))
                member = mode["set"].copy()
                member[members[worst]] = False
                log["set_exits"] += 1
                switch(member, np.delete(mode["sense"], worst), z)
                continue
            log["modes"].append((time_now, tuple(int(i) + 1 for i in members)))
            quits = [member_leaves(i, sg) for i, sg in zip(members, mode["sense"], strict=True)]
            others = [i for i in range(n) if not mode["set"][i]]
            sol = solve_ivp(rate, (time_now, float(t_end)), z, method=method, rtol=rtol, atol=1e-2 * rtol,
                            events=(aligned, leaves, rest, *quits, *[joins(i) for i in others],
                                    *[edges[i] for i in others]))
            if sol.status < 0:
                raise SolverError(f"the saturated slide along the rims was not integrated from t = {time_now:.6g} "
                                  f"s: {sol.message}")
            stalled = stalled + 1 if float(sol.t[-1]) == time_now else 0
            if stalled > 2 * n:
                raise SolverError(f"the saturated set of the slide along the rims does not settle at t = "
                                  f"{time_now:.9g} s: a surface joins and leaves it at the same instant (a tangency "
                                  f"the set's rules do not resolve; met on PTS at rtol 1e-6)")
            z, time_now = sol.y[:, -1], float(sol.t[-1])
            log["saturated_segments"] += 1
            log["drift"] = max(log["drift"], lines_residual(z, mode["set"], mode["sense"]))
            if sol.status == 0:
                break
            hit = [k for k, hits in enumerate(sol.t_events) if len(hits)][0]
            if hit < 3:
                reason = ("aligned", "leaves", "rest")[hit]
                break
            hit -= 3
            member, sense = mode["set"].copy(), list(mode["sense"])
            if hit < len(members):
                member[members[hit]] = False
                del sense[hit]
            elif hit < len(members) + len(others):
                joined = others[hit - len(members)]
                member[joined] = True
                sense.insert(int(np.count_nonzero(member[:joined])), float(np.sign(force(z)[5][joined])))
            else:
                held[others[hit - len(members) - len(others)]] ^= True
                changes += 1
            switch(member, sense, z)
            continue
        implicit = method in IMPLICIT
        if implicit and not np.all(np.isfinite(force(z)[5])):
            left = aligned(time_now, z) + gap_end
            if left <= ALIGNED_FALLBACK_GAP:
                reason = "aligned"
                break
            raise SolverError(f"the force of the slide along the rims is not found at t = {time_now:.9g} s (the rims "
                              f"{left:.3g} short of their alignment, 1 − |X|/Σd)")
        log["modes"].append((time_now, ()))
        extra = {"jac": jacobian} if implicit else {}
        psi0 = force(z)[5]
        if implicit and np.all(np.isfinite(psi0)) and np.any(psi0 != 0.0):
            # the first step: a thousandth of a radian at the fastest rim's rate (scipy's own guess, from the
            # slope alone, was ~1e3 × too long where the rates start at ~250 m/s on 0.05 m caps: its stages left
            # the force's domain and the step collapsed, h226)
            extra["first_step"] = min(float(t_end) - time_now, 1e-3 / float(np.max(np.abs(psi0) / cap)))
        sol = solve_ivp(rate, (time_now, float(t_end)), z, method=method, rtol=rtol, atol=1e-2 * rtol,
                        events=(aligned, leaves, rest, *edges, *((concurrent,) if implicit else ())), **extra)
        if sol.status < 0:
            raise SolverError(f"the closing along the rims was not integrated from t = {time_now:.6g} s: "
                              f"{sol.message}")
        z, time_now = sol.y[:, -1], float(sol.t[-1])
        if sol.status == 0:
            break
        hit = [k for k, hits in enumerate(sol.t_events) if len(hits)]
        if hit[0] < 3:
            reason = ("aligned", "leaves", "rest")[hit[0]]
            break
        if hit[0] == 3 + n:  # three or more lines at µ_fast concurrent within the gap: the saturated mode
            saturate(z)
            continue
        for k in hit:
            if k < 3 + n:
                held[k - 3] = not held[k - 3]
        changes += 1
    else:
        raise SolverError(f"the closing along the rims changed its sliding set more than {max_segments} times "
                          f"(stopped at t = {time_now:.6g} s)")
    z1 = z
    log["set_changes"] = changes

    def stored(z):
        ub = smat @ frame(z[:n])[0]
        return 0.5 * float(z[n] ** 2 + z[n + 1] ** 2), g * float(np.sum(np.sum(ub * ub, axis=1) / (2.0 * rbar)))

    (k0, p0), (k1, p1) = stored(z0), stored(z1)
    e_in, e_f, e_v = (float(x) for x in z1[n + 2:])
    x1 = np.sum(frame(z1[:n])[0], axis=0)
    return {"t": time_now, "gap": 1.0 - math.hypot(x1[0], x1[1]) / total, "u": frame(z1[:n])[0], "xdot": z1[n:n + 2].copy(), "reason": reason,
            "input": e_in, "friction": e_f, "viscous": e_v, "kinetic": (k0, k1), "potential": (p0, p1),
            "balance": e_in - (k1 - k0) - (p1 - p0) - e_f - e_v, **log}
