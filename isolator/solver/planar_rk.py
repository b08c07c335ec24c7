r"""Right-hand sides and the Dormand–Prince 8(5,3) step of the planar (2-D) kernel.

Per unit mass, relative to the ground, inside one sample interval (local time τ):

.. math::  X'' = -\mu(|V|)\, n(\tau)\, V/|V| - \kappa(\tau) X - c V - a_g(\tau)

with :math:`a_g`, :math:`n = g + a_z` linear in τ and κ = n/R (pendulum) or K/M.
Writing :math:`F = -\kappa X - a_g` for the non-dissipative force, the motion is
integrated in one of four forms (``mode``), each regular where it is used:

* ``CARTESIAN`` (0): state (X, V), independent variable τ; sliding away from V = 0
  and free flight (no friction while n ≤ 0).
* ``LOG`` (1): approach to a stop.  V = r e with r = |V|, independent variable
  s = ln r (decreasing).  Since :math:`\dot r = -\mu n + e\cdot F - c r < 0`,

  .. math::  \frac{d\tau}{ds} = \frac{r}{\dot r},\quad
             \frac{dX}{ds} = \frac{r^2 e}{\dot r},\quad
             \frac{de}{ds} = \frac{F - (e\cdot F) e}{\dot r},

  all smooth down to r → 0, where V/|V| is singular in Cartesian form: the stop
  (a finite-time event under Coulomb friction) is reached without ever
  regularising the friction law.
* ``START`` (2): the first instants after a start from rest (break-away or a
  stop the static friction cannot hold).  The velocity direction is slaved to
  F (its relaxation rate |F|/r is unbounded as r → 0, an infinitely stiff mode),
  so the motion is integrated as r' = e·F − µ(r) n − c r, X' = r e with e on the
  slow manifold (F/|F| trailing by θ ≈ τ_r ψ'/(1 + τ_r'), τ_r = r/|F| and ψ' the
  turning rate of F; :func:`start_direction`) until r reaches a switch value where
  the error of that direction is below the integration tolerance (measured in
  docs/planar.md).
* ``POLAR`` (3): slow sliding.  Speed r (component 7) and direction e = V/|V|
  (components 2, 3) as separate variables: r' = e·F − µ(r) n − c r,
  e' = (F − (e·F) e)/r, X' = r e; the stiff mode is e relaxing onto F at the
  rate e·F/r.

Energies per unit mass are integrated with the motion (components 4–6): input
``-a_g·V + ½ κ' |X|²`` (the second term is the work of the vertical motion on a
pendulum), friction ``µ n |V|`` and viscous ``c |V|²``.

The step is Dormand & Prince's DOP853 (Hairer, Nørsett & Wanner, *Solving ODEs I*,
§II.10) with scipy's coefficient tables and its 5th/3rd-order error estimate.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from scipy.integrate._ivp import dop853_coefficients as _dop

#: numba fast-math flags that keep NaN/inf semantics (the step tests for both): FMA contraction,
#: reassociation, reciprocal division, no signed zeros
_FAST = {"contract", "reassoc", "arcp", "nsz"}

CARTESIAN = 0
LOG = 1
START = 2
POLAR = 3

#: state size: X (2), V or e or (r, -) (2), energies input/friction/viscous (3), τ (log mode)
NSTATE = 8

# parameter vector layout (built by isolator.solver.planar)
P_MU_S = 0
P_MU_K = 1
P_MU_SLOW = 2
P_MU_FAST = 3
P_RATE = 4
P_VELDEP = 5
P_C = 6
P_KAPPA = 7
P_INV_R = 8
P_PENDULUM = 9
P_SIZE = 10

_A = np.ascontiguousarray(_dop.A[:12, :12])
_B = np.ascontiguousarray(_dop.B)
_C = np.ascontiguousarray(_dop.C[:12])
_E3 = np.ascontiguousarray(_dop.E3)
_E5 = np.ascontiguousarray(_dop.E5)


@njit(cache=True)
def friction_coefficient(r, prm):
    """µ(|V|) [-]: constant µk, or µ_fast − (µ_fast − µ_slow) e^{−a |V|}."""
    if prm[P_VELDEP] > 0.0:
        return prm[P_MU_FAST] - (prm[P_MU_FAST] - prm[P_MU_SLOW]) * math.exp(-prm[P_RATE] * r)
    return prm[P_MU_K]


@njit(cache=True)
def forcing(tau, x1, x2, prm, frc):
    """Ground and normal force at local time τ.

    ``frc`` = (a_x0, a_x', a_y0, a_y', n0, n', contact) for the current interval.

    Returns
    -------
    tuple of float
        ``(a_x, a_y, n, κ, κ', F_x, F_y)``: ground acceleration [m/s²], normal
        acceleration n = g + a_z [m/s²], stiffness per mass κ [1/s²] and its rate
        [1/s³], and the non-dissipative force F = −κX − a_g [m/s²].
    """
    axx = frc[0] + frc[1] * tau
    ayy = frc[2] + frc[3] * tau
    nn = frc[4] + frc[5] * tau
    if prm[P_PENDULUM] > 0.0:
        # frc[6]: 1 in contact, 0 in flight.  The phase, not the sign of n, decides,
        # because steps end exactly where n = 0 and rounding must not switch κ there.
        if frc[6] > 0.0:
            kap = nn * prm[P_INV_R]
            kdot = frc[5] * prm[P_INV_R]
        else:
            kap = 0.0  # uplift: the dish carries no load, so no restoring force
            kdot = 0.0
    else:
        kap = prm[P_KAPPA]
        kdot = 0.0
    return axx, ayy, nn, kap, kdot, -kap * x1 - axx, -kap * x2 - ayy


@njit(cache=True)
def start_direction(r, x1, x2, fx, fy, kap, kdot, frc, fr, c):
    """Direction of a slow (START form) velocity: F/|F| lagging by θ.

    The velocity direction relaxes onto F at the rate |F|/r (θ' = ψ' − (|F|/r) sin θ,
    ψ the direction of F); on the slow manifold, with the relaxation time
    τ_r = r/|F| itself changing at τ_r' = ṙ/|F| − r|F|'/|F|², θ = τ_r ψ'/(1 + τ_r')
    (exact for r growing linearly under a steadily turning F; the neglected terms
    are O(τ_r² ψ'')).  ``fr`` is the friction force µ(r) n [m/s²] and ``c`` the
    damping [1/s], which give ṙ ≈ |F| − fr − c r.
    """
    fm = math.hypot(fx, fy)
    if fm == 0.0:
        return 0.0, 0.0
    e1 = fx / fm
    e2 = fy / fm
    # F' = −κ'X − κV − a_g' with V ≈ r F/|F|
    dfx = -kdot * x1 - kap * r * e1 - frc[1]
    dfy = -kdot * x2 - kap * r * e2 - frc[3]
    rdot = fm - fr - c * r
    dfl = (e1 * dfx + e2 * dfy) / fm  # |F|'/|F|
    psi1 = (e1 * dfy - e2 * dfx) / fm  # ψ'
    # ψ'' from F'' = −2κ'V − κV', V ≈ r e, V' ≈ ṙ e (a_g, κ linear in the interval)
    psi2 = -2.0 * psi1 * dfl  # the F'' terms are along e: no turning
    tau_r = r / fm
    # 1 + τ_r' = 1 + ṙ/|F| − τ_r |F|'/|F|, kept ≥ 1/2 (a fast re-stop)
    one = max(1.0 + rdot / fm - tau_r * dfl, 0.5)
    sin_t = tau_r * psi1 / one - tau_r * tau_r * psi2 / (one * (2.0 * one - 1.0 if one > 0.75 else 0.5))
    if sin_t > 0.5:
        sin_t = 0.5
    elif sin_t < -0.5:
        sin_t = -0.5
    cos_t = math.sqrt(1.0 - sin_t * sin_t)
    return cos_t * e1 + sin_t * e2, -sin_t * e1 + cos_t * e2


@njit(cache=True, fastmath=_FAST)
def rhs(mode, x, y, prm, frc, d):
    """Derivative of the state in ``mode`` at independent variable ``x`` (into ``d``).

    Returns False where the LOG form is not valid (the speed no longer decreases).
    """
    c = prm[P_C]
    tau = y[7] if mode == LOG else x
    axx, ayy, nn, kap, kdot, fx, fy = forcing(tau, y[0], y[1], prm, frc)
    pin = 0.5 * kdot * (y[0] * y[0] + y[1] * y[1])
    if mode == CARTESIAN:
        v1 = y[2]
        v2 = y[3]
        r = math.hypot(v1, v2)
        fr = 0.0
        e1 = 0.0
        e2 = 0.0
        if nn > 0.0 and r > 0.0:
            fr = friction_coefficient(r, prm) * nn
            e1 = v1 / r
            e2 = v2 / r
        d[0] = v1
        d[1] = v2
        d[2] = fx - fr * e1 - c * v1
        d[3] = fy - fr * e2 - c * v2
        d[4] = -(axx * v1 + ayy * v2) + pin
        d[5] = fr * r
        d[6] = c * r * r
        d[7] = 0.0
        return True
    if mode == START:
        r = y[2]
        fr = friction_coefficient(abs(r), prm) * nn if nn > 0.0 else 0.0
        e1, e2 = start_direction(r, y[0], y[1], fx, fy, kap, kdot, frc, fr, c)
        d[0] = r * e1
        d[1] = r * e2
        d[2] = e1 * fx + e2 * fy - fr - c * r
        d[3] = 0.0
        d[4] = -(axx * e1 + ayy * e2) * r + pin
        d[5] = fr * abs(r)
        d[6] = c * r * r
        d[7] = 0.0
        return True
    if mode == POLAR:
        # speed r (component 7) and direction e = V/|V| (components 2, 3, as in LOG form);
        # e' = (F − (e·F) e)/r, the direction's relaxation rate e·F/r is the stiff mode
        r = y[7]
        if not r > 0.0:
            return False
        e1 = y[2]
        e2 = y[3]
        fr = friction_coefficient(r, prm) * nn if nn > 0.0 else 0.0
        ef = e1 * fx + e2 * fy
        d[0] = r * e1
        d[1] = r * e2
        d[2] = (fx - ef * e1) / r
        d[3] = (fy - ef * e2) / r
        d[4] = -(axx * e1 + ayy * e2) * r + pin
        d[5] = fr * r
        d[6] = c * r * r
        d[7] = ef - fr - c * r
        return True
    # LOG: independent variable s = ln r
    r = math.exp(x)
    e1 = y[2]
    e2 = y[3]
    fr = friction_coefficient(r, prm) * nn if nn > 0.0 else 0.0
    ef = e1 * fx + e2 * fy
    rdot = -fr + ef - c * r
    if not rdot < 0.0:
        return False
    w = 1.0 / rdot
    rw = r * w
    d[0] = r * rw * e1
    d[1] = r * rw * e2
    d[2] = (fx - ef * e1) * w
    d[3] = (fy - ef * e2) * w
    d[4] = (-(axx * e1 + ayy * e2) * r + pin) * rw
    d[5] = fr * r * rw
    d[6] = c * r * r * rw
    d[7] = rw
    return True


@njit(cache=True, fastmath=_FAST)
def dop853_step(mode, x, y, f0, h, prm, frc, k, ytmp, ynew, fnew, atol, rtol):
    """One DOP853 step of length ``h`` (may be negative) from (x, y) with y' = f0.

    Parameters
    ----------
    atol : float64[NSTATE]
        Absolute tolerance per component; components with atol = inf are not
        error-controlled.
    rtol : float
        Relative tolerance [-].

    Returns
    -------
    tuple
        ``(ok, err)``: ok is False if a stage left the domain of ``mode``;
        err is the scaled error norm (accept when ≤ 1).  ``ynew``/``fnew`` hold the
        new state and its derivative.
    """
    # loops over the fixed state size with the stage index outside and zero
    # coefficients skipped (50 of the 66 below-diagonal entries are used)
    for j in range(NSTATE):
        k[0, j] = f0[j]
    for s in range(1, 12):
        for j in range(NSTATE):
            ytmp[j] = 0.0
        for m in range(s):
            a = _A[s, m]
            if a != 0.0:
                for j in range(NSTATE):
                    ytmp[j] += a * k[m, j]
        for j in range(NSTATE):
            ytmp[j] = y[j] + h * ytmp[j]
        if not rhs(mode, x + _C[s] * h, ytmp, prm, frc, k[s]):
            return False, np.inf
    for j in range(NSTATE):
        ytmp[j] = 0.0
    for m in range(12):
        b = _B[m]
        if b != 0.0:
            for j in range(NSTATE):
                ytmp[j] += b * k[m, j]
    for j in range(NSTATE):
        ynew[j] = y[j] + h * ytmp[j]
    if not rhs(mode, x + h, ynew, prm, frc, fnew):
        return False, np.inf
    for j in range(NSTATE):
        k[12, j] = fnew[j]
    err5 = 0.0
    err3 = 0.0
    count = 0
    for j in range(NSTATE):
        if not atol[j] < np.inf:
            continue
        e5 = 0.0
        e3 = 0.0
        for m in range(13):
            e5 += _E5[m] * k[m, j]
            e3 += _E3[m] * k[m, j]
        sc = atol[j] + rtol * max(abs(y[j]), abs(ynew[j]))
        e5 /= sc
        e3 /= sc
        err5 += e5 * e5
        err3 += e3 * e3
        count += 1
    if err5 == 0.0 and err3 == 0.0:
        return True, 0.0
    err = abs(h) * err5 / math.sqrt((err5 + 0.01 * err3) * count)
    if not err < np.inf:
        return False, np.inf
    return True, err


@njit(cache=True)
def step_factor(err):
    """Step-size factor after a step with scaled error ``err`` (order 8 controller)."""
    if err == 0.0:
        return 10.0
    return min(10.0, max(0.2, 0.9 * err ** (-1.0 / 8.0)))
