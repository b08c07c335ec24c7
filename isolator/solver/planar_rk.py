r"""Right-hand sides of the planar (2-D) kernel, in the four forms of the motion.

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
* ``POLAR`` (3): sliding.  Speed r (component 7) and direction e = V/|V|
  (components 2, 3) as separate variables: r' = e·F − µ(r) n − c r,
  e' = (F − (e·F) e)/r, X' = r e; the stiff mode is e relaxing onto F at the
  rate e·F/r.

Energies per unit mass are integrated with the motion (components 4–6): input
``-a_g·V + ½ κ' |X|²`` (the second term is the work of the vertical motion on a
pendulum), friction ``µ n |V|`` and viscous ``c |V|²``.

The DOP853 step that integrates them is :mod:`isolator.solver.planar_dop853` (generated,
unrolled); :func:`step_factor` is its step-size controller.

Every compiled function the record loop calls (here, in ``planar_dop853`` and in
``planar_events``) is ``@njit(..., _nrt=False)``: none allocates, and without numba's
reference counting an array argument costs nothing, where it otherwise costs an atomic
increment and decrement per call — measured at ≈ 9 % of the samples of a profile of the
engine and a 1.2–1.3× slower record (docs/planar.md).  Only ``planar_kernel`` (which
allocates its work arrays) keeps it.
"""

from __future__ import annotations

import math

from isolator.solver.jit import njit

#: numba fast-math flags that keep NaN/inf semantics (the step tests for both): FMA contraction,
#: reassociation, reciprocal division, no signed zeros
FASTMATH = {"contract", "reassoc", "arcp", "nsz"}

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

@njit(cache=True, fastmath=FASTMATH, _nrt=False)
def norm(a, b):
    """√(a² + b²): the length of a plane vector.  Not ``math.hypot``, which guards
    against overflow and underflow at a tenth of a DOP853 step's cost; the forces,
    speeds and displacements here are far from both limits."""
    return math.sqrt(a * a + b * b)


@njit(cache=True, _nrt=False)
def friction_coefficient(r, prm):
    """µ(|V|) [-]: constant µk, or µ_fast − (µ_fast − µ_slow) e^{−a |V|}."""
    if prm[P_VELDEP] > 0.0:
        return prm[P_MU_FAST] - (prm[P_MU_FAST] - prm[P_MU_SLOW]) * math.exp(-prm[P_RATE] * r)
    return prm[P_MU_K]


@njit(cache=True, _nrt=False)
def friction_slope(r, prm):
    """dµ/d|V| [s/m]: 0 for constant µk, a (µ_fast − µ_slow) e^{−a |V|} for µ(v)."""
    if prm[P_VELDEP] > 0.0:
        return prm[P_RATE] * (prm[P_MU_FAST] - prm[P_MU_SLOW]) * math.exp(-prm[P_RATE] * r)
    return 0.0


@njit(cache=True, _nrt=False)
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


@njit(cache=True, _nrt=False)
def start_direction(r, x1, x2, fx, fy, kap, kdot, frc, fr, c):
    """Direction of a slow (START form) velocity: F/|F| lagging by θ.

    The velocity direction relaxes onto F at the rate |F|/r (θ' = ψ' − (|F|/r) sin θ,
    ψ the direction of F); on the slow manifold, with the relaxation time
    τ_r = r/|F| itself changing at τ_r' = ṙ/|F| − r|F|'/|F|², θ = τ_r ψ'/(1 + τ_r')
    (exact for r growing linearly under a steadily turning F; the neglected terms
    are O(τ_r² ψ'')).  ``fr`` is the friction force µ(r) n [m/s²] and ``c`` the
    damping [1/s], which give ṙ ≈ |F| − fr − c r.
    """
    fm = norm(fx, fy)
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


@njit(cache=True, fastmath=FASTMATH, _nrt=False)
def derivative(mode, x, x1, x2, y2, y3, y7, prm, frc):
    """Derivative of the state in ``mode`` at independent variable ``x``.

    The arguments are the components the right-hand side reads: X = (x1, x2) and
    y2, y3, y7 (velocity, direction or speed, and τ in LOG form, per ``mode``); the
    energies (components 4–6) are quadratures.  |V| is ``sqrt(v1² + v2²)``, not
    ``hypot``: speeds here are far from overflow and underflow, and ``hypot`` costs
    a sixth of a step.  The unrolled DOP853 steps call the form's own function
    (:func:`derivative_cartesian` …), which numba inlines into every stage (``inline="always"``;
    LLVM did not inline this four-form function, and a call per stage cost 6–9 % of a record).

    Returns
    -------
    tuple
        ``(ok, d0, …, d7)``: ok is False where the form is not valid (the speed no
        longer decreases in LOG form, a non-positive speed in POLAR form).
    """
    if mode == CARTESIAN:
        return derivative_cartesian(x, x1, x2, y2, y3, y7, prm, frc)
    if mode == START:
        return derivative_start(x, x1, x2, y2, y3, y7, prm, frc)
    if mode == POLAR:
        return derivative_polar(x, x1, x2, y2, y3, y7, prm, frc)
    return derivative_log(x, x1, x2, y2, y3, y7, prm, frc)


@njit(cache=True, fastmath=FASTMATH, _nrt=False, inline="always")
def derivative_cartesian(x, x1, x2, y2, y3, y7, prm, frc):
    """:func:`derivative` in CARTESIAN form: V = (y2, y3)."""
    c = prm[P_C]
    axx, ayy, nn, kap, kdot, fx, fy = forcing(x, x1, x2, prm, frc)
    pin = 0.5 * kdot * (x1 * x1 + x2 * x2)
    r = math.sqrt(y2 * y2 + y3 * y3)
    fr_r = 0.0  # µ n / |V|
    fr = 0.0
    if nn > 0.0 and r > 0.0:
        fr = friction_coefficient(r, prm) * nn
        fr_r = fr / r
    return (True, y2, y3, fx - (fr_r + c) * y2, fy - (fr_r + c) * y3, -(axx * y2 + ayy * y3) + pin,
            fr * r, c * r * r, 0.0)


@njit(cache=True, fastmath=FASTMATH, _nrt=False, inline="always")
def derivative_start(x, x1, x2, y2, y3, y7, prm, frc):
    """:func:`derivative` in START form: speed y2, direction slaved to F (:func:`start_direction`)."""
    c = prm[P_C]
    axx, ayy, nn, kap, kdot, fx, fy = forcing(x, x1, x2, prm, frc)
    pin = 0.5 * kdot * (x1 * x1 + x2 * x2)
    r = y2
    fr = friction_coefficient(abs(r), prm) * nn if nn > 0.0 else 0.0
    e1, e2 = start_direction(r, x1, x2, fx, fy, kap, kdot, frc, fr, c)
    return (True, r * e1, r * e2, e1 * fx + e2 * fy - fr - c * r, 0.0, -(axx * e1 + ayy * e2) * r + pin,
            fr * abs(r), c * r * r, 0.0)


@njit(cache=True, fastmath=FASTMATH, _nrt=False, inline="always")
def derivative_polar(x, x1, x2, y2, y3, y7, prm, frc):
    """:func:`derivative` in POLAR form: speed r (component 7) and direction e = V/|V|
    (components 2, 3, as in LOG form); e' = (F − (e·F) e)/r, the direction's relaxation
    rate e·F/r is the stiff mode."""
    return polar_with_friction(friction_coefficient(y7, prm), x, x1, x2, y2, y3, y7, prm, frc)


@njit(cache=True, fastmath=FASTMATH, _nrt=False, inline="always")
def derivative_polar_q(x, x1, x2, y2, y3, y7, q, prm, frc):
    """:func:`derivative_polar` for µ(v) with q = e^{−a r} given (an auxiliary variable of the
    step, q' = −a q ṙ): µ = µ_fast − (µ_fast − µ_slow) q without an ``exp``, which costs ≈ 20 % of
    a µ(v) record otherwise (docs/planar.md).  Returns the derivative and q'."""
    ok, d0, d1, d2, d3, d4, d5, d6, d7 = polar_with_friction(
        prm[P_MU_FAST] - (prm[P_MU_FAST] - prm[P_MU_SLOW]) * q, x, x1, x2, y2, y3, y7, prm, frc)
    return ok, d0, d1, d2, d3, d4, d5, d6, d7, -prm[P_RATE] * q * d7


@njit(cache=True, fastmath=FASTMATH, _nrt=False, inline="always")
def polar_with_friction(mu, x, x1, x2, y2, y3, y7, prm, frc):
    """The POLAR form's derivative (:func:`derivative_polar`) with the friction coefficient µ
    given: the one body of :func:`derivative_polar` and :func:`derivative_polar_q`."""
    r = y7
    if not r > 0.0:
        return False, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    c = prm[P_C]
    axx, ayy, nn, kap, kdot, fx, fy = forcing(x, x1, x2, prm, frc)
    pin = 0.5 * kdot * (x1 * x1 + x2 * x2)
    fr = mu * nn if nn > 0.0 else 0.0
    ef = y2 * fx + y3 * fy
    ir = 1.0 / r
    return (True, r * y2, r * y3, (fx - ef * y2) * ir, (fy - ef * y3) * ir, -(axx * y2 + ayy * y3) * r + pin,
            fr * r, c * r * r, ef - fr - c * r)


@njit(cache=True, fastmath=FASTMATH, _nrt=False, inline="always")
def derivative_log(x, x1, x2, y2, y3, y7, prm, frc):
    """:func:`derivative` in LOG form: independent variable s = ln r, τ = y7."""
    c = prm[P_C]
    axx, ayy, nn, kap, kdot, fx, fy = forcing(y7, x1, x2, prm, frc)
    pin = 0.5 * kdot * (x1 * x1 + x2 * x2)
    r = math.exp(x)
    fr = friction_coefficient(r, prm) * nn if nn > 0.0 else 0.0
    ef = y2 * fx + y3 * fy
    rdot = -fr + ef - c * r
    if not rdot < 0.0:
        return False, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    w = 1.0 / rdot
    rw = r * w
    return (True, r * rw * y2, r * rw * y3, (fx - ef * y2) * w, (fy - ef * y3) * w,
            (-(axx * y2 + ayy * y3) * r + pin) * rw, fr * r * rw, c * r * r * rw, rw)


@njit(cache=True, fastmath=FASTMATH, _nrt=False)
def rhs(mode, x, y, prm, frc, d):
    """Derivative of the state ``y`` in ``mode`` at ``x``, into ``d`` (see :func:`derivative`).

    Returns False where the form is not valid.
    """
    ok, d[0], d[1], d[2], d[3], d[4], d[5], d[6], d[7] = derivative(mode, x, y[0], y[1], y[2], y[3], y[7], prm,
                                                                    frc)
    return ok


@njit(cache=True, _nrt=False)
def step_factor(err):
    """Step-size factor after a step with scaled error ``err`` (order 8 controller): 0.9 err^(−1/8) in [0.2, 10]."""
    return factor_of_root(eighth_root(max(err, 1e-10)))


@njit(cache=True, _nrt=False)
def factor_of_root(root):
    """The order-8 step factor from root = max(err, 1e-10)^(1/8): 0.9/root in [0.2, 10] (err = 0 gives 10)."""
    return min(10.0, max(0.2, 0.9 / root))


@njit(cache=True, fastmath=FASTMATH, _nrt=False)
def eighth_root(err):
    """err^(1/8) as three square roots (a third of the cost of ``pow`` here)."""
    return math.sqrt(math.sqrt(math.sqrt(err)))
