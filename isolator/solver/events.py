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

import numpy as np

from isolator.solver.jit import njit
from isolator.solver.segments import segment_state

BREAKAWAY = 0  #: stuck → sliding
STICK = 1  #: sliding → stuck (a stop the static friction holds)
REVERSAL = 2  #: sliding → sliding the other way (a stop it cannot hold)
EVENT_NAMES = ("breakaway", "stick", "reversal")

#: Newton–bisection iterations before giving up on more digits (bisection alone
#: halves the bracket each time; 200 halvings exhaust any double bracket).
_MAX_ITERATIONS = 200


@njit(cache=True)
def segment_root(which, sign, lo, hi, x0, v0, p, q, force, theta0, c, kappa, omega, guess):
    """Root of the velocity (which=0), the acceleration (1) or κV + cA (2) of a slip piece.

    The bracket ``[lo, hi]`` must hold exactly one sign change of ``sign·f`` from
    positive (or zero at ``lo``) to non-positive; the iteration never leaves it.

    Parameters
    ----------
    which : int
        0: root of V(τ); 1: root of the relative acceleration A(τ); 2: root of
        κV + cA, where the transmitted acceleration is extremal.
    sign : float
        +1 or -1: the sign that ``f`` has just after ``lo``.
    lo, hi : float
        Bracket in local time [s].
    x0, v0, p, q, force, theta0, c, kappa, omega : float
        The slip piece (see :func:`isolator.solver.segments.segment_state`).
    guess : float
        First iterate (e.g. the secant through the bracket ends); ignored unless
        strictly inside the bracket.

    Returns
    -------
    float
        The root τ* [s], to rounding.
    """
    a = lo
    b = hi
    t = 0.5 * (a + b)
    if lo < guess < hi:
        t = guess
    for _ in range(_MAX_ITERATIONS):
        x, v, acc, jerk = segment_state(t, x0, v0, p, q, force, theta0, c, kappa, omega)
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
        if f == 0.0:
            return t
        if f > 0.0:
            a = t
        else:
            b = t
        if b - a <= 4e-16 * b:
            return b
        # Newton step, accepted only if it stays strictly inside the bracket
        t_new = t - f / df if df != 0.0 else 0.5 * (a + b)
        if not (a < t_new < b):
            if df != 0.0 and abs(t_new - t) <= 2e-16 * t:
                # the correction is below rounding (t_new == t, an end of the bracket): t is the root to rounding;
                # bisecting on from the bracket's far end would only take ~50 more evaluations to come back here
                return t
            t_new = 0.5 * (a + b)
        elif abs(t_new - t) <= 2e-16 * t:
            return t_new  # quadratic convergence reached rounding level
        t = t_new
    return t


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
        ``(tau_b, direction, crossing)``: the instant [s] and the direction ±1 in which
        the block starts to slide, or ``(-1.0, 0, False)`` if it stays stuck to
        ``tau_hi``; ``crossing`` is true when the force crosses µs g at ``tau_b``
        (then the net force there is exactly s(µs − µk)g) and false when it already
        exceeds it at ``tau_lo`` (a record that starts beyond the threshold).
    """
    f_lo = kappa * x_stuck + a_start + slope * tau_lo
    if abs(f_lo) > mu_s_g:  # already beyond at τ_lo (a record that starts there): a jump, not a crossing
        return tau_lo, (-1 if f_lo > 0.0 else 1), False
    f_end = kappa * x_stuck + a_start + slope * tau_hi
    if abs(f_end) <= mu_s_g:  # both ends inside and the force linear in τ: stuck throughout
        return -1.0, 0, False
    direction = -1 if f_end > 0.0 else 1
    level = mu_s_g if f_end > 0.0 else -mu_s_g
    if slope != 0.0:
        tau_b = (level - kappa * x_stuck - a_start) / slope
    else:
        tau_b = tau_lo
    if tau_b < tau_lo:
        tau_b = tau_lo
    if tau_b > tau_hi:
        tau_b = tau_hi
    return tau_b, direction, True


@njit(cache=True)
def secant_guess(lo, hi, f_lo, f_hi):
    """The secant's zero through (lo, f_lo), (hi, f_hi): a first iterate for :func:`segment_root`."""
    if f_lo == f_hi:
        return 0.5 * (lo + hi)
    return lo + (hi - lo) * f_lo / (f_lo - f_hi)


@njit(cache=True)
def find_stop(s, from_rest, rem, x, v, v_end, acc_start, acc_end, p, q, force, theta0, c, kappa, omega):
    """First stop of a slip piece in (0, rem], exact, or -1 if it slides through.

    The piece must be short enough for its velocity to be unimodal (at most one
    zero of the acceleration; see :mod:`isolator.solver.kernel`), which makes the
    test below decisive: the velocity reaches zero inside the piece if and only if
    it has the wrong sign at the end, or at its interior extremum.

    Parameters
    ----------
    s : float
        Sliding direction ±1.
    from_rest : bool
        The piece starts with V = 0 (after a break-away or a reversal), so s·V
        rises first and a zero at τ = 0 is not a stop.
    rem : float
        Length of the piece [s].
    x, v, v_end : float
        Displacement and velocity at the start, velocity at the end of the piece.
    acc_start, acc_end : float
        Relative acceleration at the start and the end of the piece.
    p, q, force, theta0, c, kappa, omega : float
        The forcing and the system (see :func:`isolator.solver.segments.segment_state`).

    Returns
    -------
    tuple of float
        ``(t_stop, t_extremum, v_extremum)``: the stop time (-1 if none) and, when it
        had to be located, the interior extremum of the velocity (else -1, 0).
    """
    t_ext = -1.0
    v_ext = 0.0
    if s * v_end <= 0.0:
        if not from_rest:
            guess = secant_guess(0.0, rem, v, v_end)
            return segment_root(np.int64(0), s, 0.0, rem, x, v, p, q, force, theta0, c, kappa, omega, guess), t_ext, v_ext
        # s·V rises first, so the stop lies after its maximum
        guess = secant_guess(0.0, rem, acc_start, acc_end)
        t_ext = segment_root(np.int64(1), s, 0.0, rem, x, v, p, q, force, theta0, c, kappa, omega, guess)
        _, v_ext, _, _ = segment_state(t_ext, x, v, p, q, force, theta0, c, kappa, omega)
        if s * v_ext <= 0.0:
            return t_ext, t_ext, v_ext  # no positive excursion: a grazing touch
        guess = secant_guess(t_ext, rem, v_ext, v_end)
        return segment_root(np.int64(0), s, t_ext, rem, x, v, p, q, force, theta0, c, kappa, omega, guess), t_ext, v_ext
    if s * acc_start < 0.0 and s * acc_end > 0.0:
        # s·V has an interior minimum: does it reach zero?
        guess = secant_guess(0.0, rem, acc_start, acc_end)
        t_ext = segment_root(np.int64(1), -s, 0.0, rem, x, v, p, q, force, theta0, c, kappa, omega, guess)
        _, v_ext, _, _ = segment_state(t_ext, x, v, p, q, force, theta0, c, kappa, omega)
        if s * v_ext <= 0.0:
            guess = secant_guess(0.0, t_ext, v, v_ext)
            return segment_root(np.int64(0), s, 0.0, t_ext, x, v, p, q, force, theta0, c, kappa, omega, guess), t_ext, v_ext
    return -1.0, t_ext, v_ext


@njit(cache=True)
def record_event(ev_time, ev_kind, ev_x, n_ev, time, kind, x):
    """Store an event if the arrays have room; return the new event count (always counted)."""
    if n_ev < ev_time.shape[0]:
        ev_time[n_ev] = time
        ev_kind[n_ev] = kind
        ev_x[n_ev] = x
    return n_ev + 1
