r"""The force of the µ(v) slide along the rims in the plane, compiled (h204, issue 23).

The same root as :func:`isolator.solver.planar_rim_slide.slide_along_rims` (numpy, the tests' independent
reference): surfaces i all on their rims (tangents t_i), each held (|(r − b_i)·t_i| ≤ µ_slow,i) or sliding along its
rim at ψ_i in its sense σ_i with (r − b_i)·t_i = σ_i µ_i(σ_i ψ_i), µ(v) = µ_f − (µ_f − µ_s) e^(−a v), and
Σ ψ_i t_i = Ẋ.  The root is unique where the tangents span the plane (the convex problem of the numpy module).

Only the forward law's saddle system is solved here (:func:`saddle`: Newton on [−µ', T; Tᵀ, 0], well conditioned at
any speed, the same equations and stopping rule as ``planar_rim_slide._forward``), over

1. the set and rates of the previous answer (``seed``: along a slide the set seldom changes), then
2. the sets grown from every pair of surfaces and senses (``planar_rim_slide._grown_sets``, h199): a surface outside
   its dead zone at an answer joins with the rate its own inverse law gives there (bounded: 2n growths per pair).

The first answer whose held surfaces are inside their dead zones and whose rates are in their senses is the root.
Everything is bounded (:data:`MAX_NEWTON` iterations per set); a status < 0 says no set answered (the caller
refuses, or asks the numpy module).  Dense solves by :mod:`isolator.solver.dense` (LU with partial pivoting).
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.dense import lu_factor, lu_solve
from isolator.solver.jit import njit

#: Newton iterations of one set's saddle system (as ``planar_rim_slide.MAX_NEWTON``)
MAX_NEWTON = 200
#: The force's statuses: answered from the seed's set, from a grown set; no set answered
FROM_SEED = 1
FROM_GROWN = 2
NOT_FOUND = -1
#: At most this many surfaces (the pairs' growth is searched exhaustively)
MAX_SURFACES = 6


@njit(cache=True)
def saddle(xdot, b, t, member, seed, mu_s, mu_f, a, tol, checked, r_out, psi_out):
    """Newton on the forward law's saddle system over the surfaces with ``member[i]`` (each in the sense of
    ``seed[i]``, the seed rates).  True with ``r_out``, ``psi_out`` (0 off the set) where it converges to ``tol`` on
    Σ ψ t − Ẋ and to 4 ε on the laws, and (``checked``) the held surfaces are in their dead zones and the rates in
    their senses; False otherwise (the outputs then undefined)."""
    n = t.shape[0]
    ns = 0
    for i in range(n):
        if member[i]:
            ns += 1
    if ns < 2:
        return False
    idx = np.empty(ns, dtype=np.int64)
    k = 0
    for i in range(n):
        if member[i]:
            idx[k] = i
            k += 1
    sig = np.empty(ns)
    rates = np.empty(ns)
    bt = np.empty(ns)
    for k in range(ns):
        i = idx[k]
        if seed[i] == 0.0:
            return False
        sig[k] = 1.0 if seed[i] > 0.0 else -1.0
        rates[k] = seed[i]
        bt[k] = b[i, 0] * t[i, 0] + b[i, 1] * t[i, 1]
    # the force's seed: least squares of T r = σ µ(ψ) + b·t (normal equations, 2 × 2)
    nrm = np.zeros(5)  # TᵀT's m00, m01, m11 and Tᵀ(σ µ + b·t)
    for k in range(ns):
        i = idx[k]
        rhs = sig[k] * (mu_f[i] - (mu_f[i] - mu_s[i]) * math.exp(-a[i] * abs(rates[k]))) + bt[k]
        nrm[0] += t[i, 0] * t[i, 0]
        nrm[1] += t[i, 0] * t[i, 1]
        nrm[2] += t[i, 1] * t[i, 1]
        nrm[3] += t[i, 0] * rhs
        nrm[4] += t[i, 1] * rhs
    det = nrm[0] * nrm[2] - nrm[1] * nrm[1]
    if not abs(det) > 0.0:
        return False
    rx = (nrm[2] * nrm[3] - nrm[1] * nrm[4]) / det
    ry = (nrm[0] * nrm[4] - nrm[1] * nrm[3]) / det
    size = ns + 2
    jac = np.zeros((size, size))
    f = np.empty(size)
    piv = np.empty(size, dtype=np.int64)
    eps4 = 4.0 * np.finfo(np.float64).eps
    converged = False
    for _ in range(MAX_NEWTON):
        worst = 0.0
        gx = -xdot[0]
        gy = -xdot[1]
        for k in range(ns):
            i = idx[k]
            power = -a[i] * sig[k] * rates[k]
            if not power < 700.0:  # a rate driven far against its sense: this set is not the answer
                return False
            fric = sig[k] * (mu_s[i] - (mu_f[i] - mu_s[i]) * math.expm1(power))
            f[k] = t[i, 0] * rx + t[i, 1] * ry - bt[k] - fric
            worst = max(worst, abs(f[k]))
            gx += rates[k] * t[i, 0]
            gy += rates[k] * t[i, 1]
        f[ns] = gx
        f[ns + 1] = gy
        if math.hypot(gx, gy) <= tol and worst <= eps4:
            converged = True
            break
        jac[:, :] = 0.0
        for k in range(ns):
            i = idx[k]
            jac[k, k] = -a[i] * (mu_f[i] - mu_s[i]) * math.exp(-a[i] * sig[k] * rates[k])
            jac[k, ns] = t[i, 0]
            jac[k, ns + 1] = t[i, 1]
            jac[ns, k] = t[i, 0]
            jac[ns + 1, k] = t[i, 1]
        if not lu_factor(jac, piv):
            return False
        for k in range(size):
            f[k] = -f[k]
        lu_solve(jac, piv, f)
        for k in range(size):
            if not math.isfinite(f[k]):
                return False
        for k in range(ns):
            rates[k] += f[k]
        rx += f[ns]
        ry += f[ns + 1]
    if not converged:
        return False
    for i in range(n):
        psi_out[i] = 0.0
    for k in range(ns):
        psi_out[idx[k]] = rates[k]
        if checked and not rates[k] * sig[k] > 0.0:
            return False
    if checked:
        for i in range(n):
            if not member[i]:
                s = (rx - b[i, 0]) * t[i, 0] + (ry - b[i, 1]) * t[i, 1]
                if not abs(s) <= mu_s[i]:
                    return False
    r_out[0] = rx
    r_out[1] = ry
    return True


@njit(cache=True)
def rim_slide_force(xdot, b, t, mu_s, mu_f, a, rtol, seed, r_out, psi_out):
    """The force r (``r_out``) and rates ψ (``psi_out``) of surfaces all on their rims (tangents ``t`` [n × 2],
    restoring terms ``b`` [n × 2]) moving the mass at Ẋ (``xdot``); ``seed`` [n]: the previous answer's rates
    (zeros for none).  Returns :data:`FROM_SEED`, :data:`FROM_GROWN` or :data:`NOT_FOUND` (≤ :data:`MAX_SURFACES`
    surfaces; the tolerance ``rtol`` × (|Ẋ| + max (µ_f − µ_s)/a) on Σ ψ t − Ẋ, as the numpy module)."""
    n = t.shape[0]
    if n > MAX_SURFACES:
        return NOT_FOUND
    scale = math.hypot(xdot[0], xdot[1])
    widest = 0.0
    for i in range(n):
        widest = max(widest, (mu_f[i] - mu_s[i]) / a[i])
    tol = rtol * (scale + widest)
    member = np.zeros(n, dtype=np.bool_)
    count = 0
    for i in range(n):
        if seed[i] != 0.0:
            member[i] = True
            count += 1
    if count >= 2 and saddle(xdot, b, t, member, seed, mu_s, mu_f, a, tol, True, r_out, psi_out):
        return FROM_SEED
    eps = np.finfo(np.float64).eps
    psi = np.zeros(n)
    trial = np.zeros(n)
    r = np.zeros(2)
    for p in range(n):
        for q in range(p + 1, n):
            for sense in range(4):
                sp = 1.0 if sense % 2 == 0 else -1.0
                sq = 1.0 if sense < 2 else -1.0
                member[:] = False
                member[p] = True
                member[q] = True
                psi[:] = 0.0
                psi[p] = 1e-3 * sp
                psi[q] = 1e-3 * sq
                for _ in range(2 * n):
                    if not saddle(xdot, b, t, member, psi, mu_s, mu_f, a, tol, False, r, trial):
                        break
                    grew = False
                    for i in range(n):
                        psi[i] = trial[i]
                    for i in range(n):
                        if member[i]:
                            continue
                        s = (r[0] - b[i, 0]) * t[i, 0] + (r[1] - b[i, 1]) * t[i, 1]
                        if abs(s) > mu_s[i]:
                            gap = max(mu_f[i] - abs(s), 4.0 * eps * mu_f[i])
                            rate = math.log((mu_f[i] - mu_s[i]) / gap) / a[i] if gap < mu_f[i] - mu_s[i] else 1e-6
                            psi[i] = rate if s > 0.0 else -rate
                            member[i] = True
                            grew = True
                    if not grew:
                        if saddle(xdot, b, t, member, psi, mu_s, mu_f, a, tol, True, r_out, psi_out):
                            return FROM_GROWN
                        break
    return NOT_FOUND

