"""Step control of the planar kernel: its tuning constants and the pieces its loop repeats.

:func:`isolator.solver.planar_kernel.planar_kernel` is one compiled loop over the
samples; what it does in several places lives here, compiled into it
(``inline="always"``: the same machine code as when it was written out at each place):

* :func:`stop_ahead` — the test that hands a decelerating slide to the LOG form;
* :func:`peak_in_step` — the peak bracket: a rate of |X|, |V| or |a| that goes from + to −
  inside a step brackets a peak, located (:func:`~isolator.solver.planar_events.locate_peak`)
  only when the tangents at the step's ends can beat the running peak (the LOG form's steps;
  the main step writes it out, where this form compiled slower);
* :func:`come_to_rest` — a stop: stick or restart, and its event;
* :func:`leave_log` — from the LOG form back to the Cartesian one (a turn, not a stop);
* :func:`enter_polar` — into the POLAR form (speed and direction) from a velocity;
* :func:`store_sample` — the state written at a sample.

The constants' measured effects (steps, rejections, time on the bench pairs) are in
docs/dev-notes.md; the accuracy they keep, in docs/planar.md.
"""

from __future__ import annotations

import numpy as np

from isolator.solver.jit import njit
from isolator.solver.planar_events import PH_STUCK, at_rest, locate_peak, record_event, tangent_bound
from isolator.solver.planar_layout import EV_REVERSAL, EV_STICK
from isolator.solver.planar_rk import CARTESIAN, POLAR, rhs

#: approach to a stop: enter the LOG form when d|V|/dt < −ENTER_LOG·(µn + |F|), leave it above −LEAVE_LOG·(…)
ENTER_LOG = 0.02
LEAVE_LOG = 0.01
#: ... and when the stop is predicted within this many steps (|V| < AHEAD_STEPS·|d|V|/dt|·h): the LOG
#: form's first steps, where the direction has not settled, are its most expensive
AHEAD_STEPS = 1.0
#: h·(|F| + µn)/|V| kept below this in Cartesian form (DOP853's real stability interval is ≈ [−6, 0])
STABLE_CARTESIAN = 12.0
#: START form kept above SC_R_SWITCH_LO only while the slaved direction lags F by less than this [rad]
LAG_MAX_RAD = 1e-3
#: POLAR steps kept below STABLE_POLAR·r/|F| (the direction relaxes at the rate e·F/r): DOP853's error
#: estimate on the stiff direction grows fast beyond h·|F|/r ≈ 3.  The POLAR form carries every slide,
#: slow or fast (a step costs about 255 ns against 430 in Cartesian form, for the same steps where both
#: work); the Cartesian form is left for flight and as the hand-over to the LOG form
STABLE_POLAR = 3.0
#: the first POLAR step of a sample interval is tried at this fraction of the suggested step: the
#: forcing's slope jumps at the sample, and with it the direction's lag behind F, which the suggestion
#: (from the interval before) did not see
KINK_STEP = 0.8
#: a stop whose direction has not settled at r_min (:func:`~isolator.solver.planar_events.settled`) is
#: finished in closed form from this fraction of r_min instead: its direction still turns by a finite
#: angle per unit of ln r, which the finish along a fixed direction turns into an error of the stop
#: instant ∝ r_min.  So is a stop reached outside the LOG form
R_FLOOR_FRACTION = 1e-2
#: the speed and direction of a slide (POLAR form) are held to this multiple of the velocity tolerance
#: rtol·max|V|, X and the energies to rtol itself: every peak and residual stays within 6e-11 of the
#: reference's peak (`python -m benchmarks.planar_accuracy`) and two samplings of a white-noise pair
#: agree to 1e-9 (`python -m benchmarks.planar_sampling`)
POLAR_VELOCITY_TOL = 10.0


@njit(cache=True, _nrt=False, inline="always")
def stop_ahead(r, rdot, fscale, h):
    """Does a slide at speed r [m/s] decelerate fast (ṙ < −ENTER_LOG·(|F| + µn), ``fscale`` [m/s²])
    towards a stop predicted within AHEAD_STEPS steps of h [s]?  Then the LOG form takes over."""
    return rdot < -ENTER_LOG * fscale and r < AHEAD_STEPS * (-rdot) * h


@njit(cache=True, _nrt=False, inline="always")
def peak_in_step(peak, which, mode, x, y, f, h, v0, g0, v1, g1, span, prm, frc, yb, fb, atol, rtol, work):
    """The running peak of |X| (``which`` 0), |V| (1) or transmitted |a| (2) after a step.

    ``v0``, ``v1`` are the values at the step's ends and ``g0``, ``g1`` the rates of their squares
    (:func:`~isolator.solver.planar_events.rate_of_peak`); g0 > 0 ≥ g1 brackets a peak inside the
    step, located (:func:`~isolator.solver.planar_events.locate_peak`, from the step start x, y, f
    of size h in the independent variable, ``span`` [s] long) only when the tangents at the ends
    (:func:`~isolator.solver.planar_events.tangent_bound`) exceed ``peak``.
    """
    if g0 > 0.0 >= g1 and tangent_bound(v0, g0, v1, g1, span) > peak:
        return max(peak, locate_peak(which, mode, x, y, f, h, v0, g0, v1, g1, span, prm, frc, yb, fb, atol, rtol,
                                     work))
    return peak


@njit(cache=True, _nrt=False, inline="always")
def come_to_rest(tau, t_event, y, prm, frc, f, ev_t, ev_k, n_ev):
    """The block is at rest at local time τ [s]: stick or restart (:func:`~isolator.solver.planar_events.at_rest`),
    the event (a stick or a reversal) logged at ``t_event`` [s].  Returns ``(phase, n_ev)``."""
    phase = at_rest(tau, y, prm, frc, f)
    return phase, record_event(ev_t, ev_k, n_ev, t_event, EV_STICK if phase == PH_STUCK else EV_REVERSAL)


@njit(cache=True, _nrt=False, inline="always")
def leave_log(tau, y, r, prm, frc, f):
    """From the LOG form (direction in y[2:4], time in y[7]) back to the Cartesian form at speed r [m/s];
    returns the time, the Cartesian form's independent variable [s]."""
    y[2] *= r
    y[3] *= r
    rhs(np.int64(CARTESIAN), tau, y, prm, frc, f)
    return y[7]


@njit(cache=True, _nrt=False, inline="always")
def enter_polar(tau, y, v1, v2, r, prm, frc, f):
    """Into the POLAR form at velocity (v1, v2) [m/s] of speed r > 0: direction in y[2:4], speed in y[7]."""
    y[2] = v1 / r
    y[3] = v2 / r
    y[7] = r
    rhs(np.int64(POLAR), tau, y, prm, frc, f)


@njit(cache=True, _nrt=False, inline="always")
def store_sample(j, v1, v2, a1, a2, y, out_x, out_v, out_a, out_en):
    """Write sample j: X = y[0:2] [m], V = (v1, v2) [m/s], the transmitted acceleration (a1, a2) [m/s²]
    and the cumulative energies y[4:7] [J/kg]."""
    out_x[j, 0] = y[0]
    out_x[j, 1] = y[1]
    out_v[j, 0] = v1
    out_v[j, 1] = v2
    out_a[j, 0] = a1
    out_a[j, 1] = a2
    out_en[0, j] = y[4]
    out_en[1, j] = y[5]
    out_en[2, j] = y[6]
