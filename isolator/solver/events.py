"""Events of the stick–slip motion: stop, stick or reverse, break-away.

* **stop** — the velocity of a sliding block reaches zero.  Located by a
  safeguarded Newton–bisection on a bracket that is guaranteed to hold exactly one
  root (see :mod:`isolator.solver.kernel` for why a piece never hides two).
* **stick or reverse** — at a stop the block sticks if the static friction can hold
  the spring and inertia forces, ``|κ X + a_g| <= µs g``; otherwise it reverses at
  once, towards ``-sign(κ X + a_g)``.
* **break-away** — a stuck block starts to slide at the first instant where
  ``|κ X + a_g| > µs g``.  With a piecewise-linear record this is linear in time
  inside a sample interval, so the instant is exact.

Event kinds are small integers so that the compiled kernel can store them.
"""

from __future__ import annotations

from numba import njit

from isolator.solver.segments import ramp_state

BREAKAWAY = 0  #: stuck → sliding
STICK = 1  #: sliding → stuck (a stop the static friction holds)
REVERSAL = 2  #: sliding → sliding the other way (a stop it cannot hold)
EVENT_NAMES = ("breakaway", "stick", "reversal")

#: Newton–bisection iterations before giving up on more digits (bisection alone
#: halves the bracket each time; 200 halvings exhaust any double bracket).
_MAX_ITERATIONS = 200


@njit(cache=True)
def ramp_root(which, sign, lo, hi, x0, v0, p, q, c, kappa):
    """Root of the velocity (which=0), the acceleration (1) or κV + cA (2) of a slip piece.

    The bracket ``[lo, hi]`` must hold exactly one sign change of ``sign·f`` from
    positive (or zero at ``lo``) to non-positive; the iteration never leaves it.

    Parameters
    ----------
    which : int
        0: root of V(τ); 1: root of the relative acceleration A(τ); 2: root of
        κV + cA, where the transmitted acceleration is extremal.
    sign : float
        +1 or -1: the sign that ``f`` has at ``lo``.
    lo, hi : float
        Bracket in local time [s].
    x0, v0, p, q, c, kappa : float
        The slip piece (see :func:`isolator.solver.segments.ramp_state`).

    Returns
    -------
    float
        The root τ* [s], to a few ulps.
    """
    a = lo
    b = hi
    t = 0.5 * (a + b)
    for _ in range(_MAX_ITERATIONS):
        x, v, acc = ramp_state(t, x0, v0, p, q, c, kappa)
        jerk = q - c * acc - kappa * v  # A' = q - c A - κ V
        if which == 0:
            f = sign * v
            df = sign * acc
        elif which == 1:
            f = sign * acc
            df = sign * jerk
        else:
            # extremum of the transmitted acceleration: d/dτ (κ X + c V) = κ V + c A
            f = sign * (kappa * v + c * acc)
            df = sign * (kappa * acc + c * jerk)
        if f > 0.0:
            a = t
        else:
            b = t
        if b - a <= 4e-16 * max(b, 1e-300) or f == 0.0:
            break
        # Newton step, accepted only if it stays strictly inside the bracket
        t_new = t - f / df if df != 0.0 else 0.5 * (a + b)
        if not (a < t_new < b):
            t_new = 0.5 * (a + b)
        t = t_new
    return b if which == 0 else t


@njit(cache=True)
def breakaway_time(x_stuck, a_start, slope, tau_lo, tau_hi, kappa, mu_s_g):
    """First instant in ``[tau_lo, tau_hi]`` where ``|κ X + a_g(τ)| > µs g``.

    Parameters
    ----------
    x_stuck : float
        Displacement of the stuck block [m].
    a_start : float
        Ground acceleration at τ = 0 of the piece [m/s²].
    slope : float
        Its slope in the piece [m/s³].
    tau_lo, tau_hi : float
        Search interval in local time [s].
    kappa : float
        Stiffness per unit mass [1/s²].
    mu_s_g : float
        Static friction per unit mass µs g [m/s²].

    Returns
    -------
    tuple
        ``(tau_b, direction)``: the instant [s] and the direction ±1 in which the
        block starts to slide, or ``(-1.0, 0)`` if it stays stuck to ``tau_hi``.
    """
    f_end = kappa * x_stuck + a_start + slope * tau_hi
    if abs(f_end) <= mu_s_g:
        return -1.0, 0
    level = mu_s_g if f_end > 0.0 else -mu_s_g
    if slope != 0.0:
        tau_b = (level - kappa * x_stuck - a_start) / slope
    else:
        tau_b = tau_lo
    if tau_b < tau_lo:
        tau_b = tau_lo
    if tau_b > tau_hi:
        tau_b = tau_hi
    direction = -1 if f_end > 0.0 else 1
    return tau_b, direction
