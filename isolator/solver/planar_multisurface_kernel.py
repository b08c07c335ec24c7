r"""The compiled record loop of a multi-surface friction pendulum in the plane (model ``2d-multisurface``).

Per unit mass, X and V in the horizontal plane relative to the ground; the bearing is the
series model of :mod:`isolator.solver.multisurface_series` with every element a rigid–plastic
element with linear hardening *in the plane*.  In units of the normal force (r = F/(M n), n = g + a_z: every
surface carries the same normal force, the sliders being massless)
element k has the back-force b_k = ū_k/R̄_k (a vector) and the friction circle of radius µ_k
around it:

* stuck:   |r − b_k| ≤ µ_k;
* sliding: r − b_k = µ_k e_k with ū̇_k = λ_k e_k, λ_k ≥ 0;

the bearing's displacement is X = Σ ū_k and the mass obeys X'' = −n r − c V − a_g.  Under a vertical
the stored energy is n Σ|ū_k|²/(2R̄_k) and the input gains the vertical's work ∫ ṅ Σ|ū_k|²/(2R̄_k) dt
(the rates' ``M_EIN``, ``_corr_xy`` in a one-group phase, the stuck intervals in closed form).  The
rate problem (the v_k = ū̇_k minimise Σ µ_k |v_k| + b_k·v_k with Σ v_k = V) makes r the
support point, in the direction V, of the intersection D of the friction discs.  So:

* **one group sliding** (the support point on one circle's arc): r = b_a + µ_a V/|V| with
  ū_a = X − S (S the displacement of the stuck elements), i.e. exactly the planar rigid block
  on a pendulum of radius R̄_a centred at S.  It is integrated with the planar engine's own
  DOP853 steps (:mod:`isolator.solver.planar_dop853`: START, POLAR, Cartesian and LOG forms,
  the stop finished by :func:`~isolator.solver.planar_events.coast_to_rest`) with the centre
  folded into the forcing, a_g* = a_g − (n/R̄_a) S;
* **two or more groups sliding** (the support point at a corner of D, or on a point several
  circles share): differentiating |r − b_k| = µ_k gives e_k·ṙ = λ_k/R̄_k, hence
  V = C ṙ with the compliance C = Σ_active R̄_k e_k e_kᵀ, ṙ = C⁻¹ V.  The state
  (X, V, r, ū_k, energies) is integrated with a DOP853 step written here (scipy's tableau, written out in planar_multisurface_tableau);
* a group **joins** when |r − b_j| reaches µ_j, **leaves** when λ_k reaches 0 (both located
  by an Illinois secant on re-stepped DOP853 sub-steps to 1e-13 of the step);
* where the two sliding normals of a corner of two groups are within IMPLICIT_ANGLE of each other the split of V
  between the groups relaxes at a rate ∝ |V|/s² (s = e_a × e_b): the corner runs on Radau IIA steps
  (``radau_step``) in its reduced state (X, V, the normal's direction θ_a, the opening φ: ``reduce_corner``); a
  corner of three groups relaxes at ≈ 4.4 |V|/κ² (κ = √det C / tr C, set by the normals' spread, not by the closest
  pair) and takes them where κ < IMPLICIT_SPREAD, likewise with the third normal's angle from e_a
  (``reduce_state``; ``corner_implicit`` chooses);
* a corner of two groups closing to tangency (s falling at a finite rate: tangency in finite time, where C
  is singular) is stepped over at |s| < CROSS_ANGLE (``cross_tangency``: docs/multisurface.md);
* at a join the sliding set is the rate problem's (``sliding_set``);
* when a group joins along the direction of the sliding ones (|e_a × e_j| < MERGE_ANGLE: a
  collinear motion, e.g. a pair whose second component is zero) the circles are tangent and
  C is singular: the groups then slide as one pendulum of radius Σ R̄ and friction
  Σ R̄_k µ_k / Σ R̄ along that direction, which is the 1-D series model exactly;
* **stuck**: holds while −a_g/n ∈ D; the break-away is the first root of a quadratic in local
  time per group (a_g linear); after a stop the stick test is the same, otherwise the group
  whose circle −a_g/n has left starts (a reversal).

Elements of equal friction start together from rest (equal circles) and stay together: they
are one *group* (R̄ summed, ū shared in proportion to R̄), which is how the inner surfaces of
a triple pendulum with µ2 = µ3 slide in regime I.

The rim |ū_k| = c̄_k is **not** modelled in the plane: the first step that would cross one
stops the run with ``STATUS_RIM`` and its time (the driver raises a SolverError); the motion
never runs past a rim silently.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver import planar_multisurface_tableau as _dop
from isolator.solver.dense import lu_factor, lu_solve
from isolator.solver.jit import njit
from isolator.solver.planar_control import (
    ENTER_LOG,
    LAG_MAX_RAD,
    LEAVE_LOG,
    POLAR_VELOCITY_TOL,
    R_FLOOR_FRACTION,
    STABLE_CARTESIAN,
    STABLE_POLAR,
    enter_polar,
    leave_log,
    stop_ahead,
)
from isolator.solver.planar_dop853 import dop853_step
from isolator.solver.planar_events import (
    PH_APPROACH,
    PH_POLAR,
    PH_SLIDE,
    PH_START,
    coast_to_rest,
    force_scale,
    land_on,
    locate_peak,
    peak_value,
    rate_of_peak,
    settled,
    start_lag,
    tangent_bound,
    velocity,
)
from isolator.solver.planar_rk import (
    CARTESIAN,
    LOG,
    NSTATE,
    P_C,
    P_INV_R,
    P_MU_K,
    P_MU_S,
    P_PENDULUM,
    P_SIZE,
    POLAR,
    START,
    forcing,
    norm,
    rhs,
    start_direction,
    step_factor,
)

# phases: the planar engine's codes for the one-group forms, and two of our own
PH_STUCK = 0
PH_MULTI = 10  #: two or more groups sliding (corner of D): the Cartesian state of this module

# event kinds
EV_BREAKAWAY = 0
EV_STICK = 1
EV_REVERSAL = 2
EV_JOIN = 3  #: a group starts sliding while others slide
EV_LEAVE = 4  #: a group stops sliding while others slide
EVENT_NAMES = ("breakaway", "stick", "reversal", "join", "leave")

STATUS_CHATTER = 1
STATUS_EVENTS_TRUNCATED = 2
STATUS_STEP_LIMIT = 4
STATUS_RIM = 8  #: a slider reached its rim: not modelled in 2-D, the run stops there
STATUS_SINGULAR = 16  #: the compliance of the sliding groups became singular (no answer after it)
STATUS_STIFF = 64  #: (SC_EXACT_ONLY set) more than MAX_STIFF_STEPS_PER_INTERVAL corner steps in one sample interval
STATUS_REDUCED = 32  #: stopped at the first reduction (SC_EXACT_ONLY set): its answer is exact for a collinear record only

MAX_EVENTS_PER_INTERVAL = 1000
MAX_STEPS_PER_INTERVAL = 200000
#: with SC_EXACT_ONLY set, the corner steps allowed in one sample interval: a corner of two circles closing towards
#: tangency is stiff (PTS at 5.6 s: DOP853's step fell to 4e-9 s) and ends in a reduction that the caller discards, so
#: the run stops there rather than spend most of its time on it (a corner away from tangency takes a few per interval)
MAX_STIFF_STEPS_PER_INTERVAL = 1000

#: a group joining along the direction of the sliding ones within this angle [rad] (tangent circles: a collinear
#: motion) slides on with them as one pendulum, the 1-D series model
MERGE_ANGLE = 1e-4
#: sliding normals exactly parallel (a corner closed to rounding without a crossing) slide on as one (a reduction,
#: counted in S_N_MERGED): a closing corner is otherwise crossed (CROSS_ANGLE)
CLOSE_ANGLE = 0.0
#: a corner of two groups whose signed sine closes below this passes through tangency in one Taylor step
CROSS_ANGLE = 1e-5

# summary layout
S_PEAK_X = 0
S_PEAK_V = 1
S_PEAK_A = 2
S_SLIP_TIME = 3
S_E_IN = 4
S_E_F = 5
S_E_V = 6
S_N_EVENTS = 7
S_STATUS = 8
S_N_STEPS = 9
S_N_REJECTED = 10
S_FAIL_T = 11  #: time of a rim contact or a failure [s] (-1: none)
S_STEPS_MULTI = 12
S_N_MERGED = 13  #: groups made to slide as one along a fixed direction (a join along the motion, a corner closing
#: below MERGE_ANGLE) or a slow corner left to one group: exact for a collinear record only
S_SIZE = 14

# scales (as the planar driver builds them)
SC_R_MIN = 0
SC_R_SWITCH = 1
SC_X_FLOOR = 2
SC_V_FLOOR = 3
SC_R_SWITCH_LO = 4
#: optional: > 0 stops the run (STATUS_REDUCED) where it would go on through a reduction (groups sliding as one along
#: a fixed direction, a slow corner left to one group), exact for a collinear record only: a caller that answers a
#: record that is not collinear with another method then stops at once instead of finishing a run it discards
SC_EXACT_ONLY = 5
#: optional (after SC_EXACT_ONLY): the scale [W] of the force point r in the multi-group steps' error norm, whose
#: absolute tolerance on r is rtol × this.  Default (absent or ≤ 0): the largest friction coefficient µ_max, the
#: radius of the largest friction circle — r's own scale, as the peaks are X's and V's.  Before, rtol × 1e-3 W held
#: every corner step: r (the component that carries the corner's fast mode) set the error of 2 470 of 2 470 explicit
#: corner steps at s = 0.02–0.05 on PTS, X and V of none (docs/multisurface.md, "What sets the corner steps")
SC_R_TOL = 6

# work counters of the multi-group steps (the kernel's ``stats`` argument, int64[ST_SIZE]; docs/multisurface.md)
ST_RADAU = 0  #: implicit (Radau IIA) steps taken, event location and peaks included
ST_RADAU_MAIN = 1  #: implicit steps of the main loop (not re-steps for an event or a peak)
ST_DOP_MAIN = 2  #: explicit (DOP853) multi-group steps of the main loop
ST_REF_NEWTON = 3  #: implicit steps of the main loop refused because Newton did not converge
ST_REF_ERROR = 4  #: implicit steps of the main loop refused by the error test
ST_NEWTON = 5  #: simplified-Newton iterations
ST_JAC = 6  #: Jacobian evaluations
ST_LU = 7  #: LU factorisations of the iteration matrix
ST_RATES = 8  #: evaluations of the multi-group rates inside the implicit steps
ST_RESTEP = 9  #: multi-group steps re-taken to locate an event or a peak
ST_REF_DOP = 10  #: explicit multi-group steps refused
ST_NEWTON_DIVERGED = 11  #: Newton solves ended because the increment grew
ST_NEWTON_MAXIT = 12  #: Newton solves ended after NEWTON_MAX iterations
ST_NEWTON_SINGULAR = 13  #: Newton solves ended because a stage's compliance was singular or its rates not finite
ST_RADAU_THREE = 14  #: implicit steps on a corner of three groups, in the reduced state (``reduce_state``)
ST_SIZE = 15

# the Cartesian multi-group state: X, V, r, energies, then ū of each group
M_X = 0
M_V = 2
M_R = 4
M_EIN = 6
M_EF = 7
M_EV = 8
M_U = 9

_A = np.ascontiguousarray(_dop.A)
_B = np.ascontiguousarray(_dop.B)
_C = np.ascontiguousarray(_dop.C)
_E3 = np.ascontiguousarray(_dop.E3)
_E5 = np.ascontiguousarray(_dop.E5)
_NS = _dop.N_STAGES


@njit(cache=True)
def _forcing(tau, raw):
    # raw = (a_x0, a_x', a_y0, a_y', n0, n')
    return raw[0] + raw[1] * tau, raw[2] + raw[3] * tau, raw[4] + raw[5] * tau


@njit(cache=True)
def stored_per_n(y, rb):
    """Σ_k |ū_k|²/(2R̄_k) of the multi-group state (the stored energy per unit n) [m²]."""
    acc = 0.0
    for k in range(rb.shape[0]):
        acc += (y[M_U + 2 * k] ** 2 + y[M_U + 2 * k + 1] ** 2) / (2.0 * rb[k])
    return acc


@njit(cache=True)
def stored_groups(ub, rb):
    """Σ_k |ū_k|²/(2R̄_k) of the groups' displacements ``ub`` (a row per group) [m²]."""
    acc = 0.0
    for k in range(rb.shape[0]):
        acc += (ub[k, 0] ** 2 + ub[k, 1] ** 2) / (2.0 * rb[k])
    return acc


@njit(cache=True)
def multi_rhs(tau, y, raw, rb, mu, mask, c, d):
    """Derivative of the multi-group state (see the module docstring); False where C is singular."""
    ng = rb.shape[0]
    axx, ayy, nn = _forcing(tau, raw)
    c11 = 0.0
    c12 = 0.0
    c22 = 0.0
    for k in range(ng):
        if mask >> k & 1:
            e1 = y[M_R] - y[M_U + 2 * k] / rb[k]
            e2 = y[M_R + 1] - y[M_U + 2 * k + 1] / rb[k]
            en = math.sqrt(e1 * e1 + e2 * e2)
            e1 /= en
            e2 /= en
            # the normal, kept in the group's rate slots until λ is known
            d[M_U + 2 * k] = e1
            d[M_U + 2 * k + 1] = e2
            c11 += rb[k] * e1 * e1
            c12 += rb[k] * e1 * e2
            c22 += rb[k] * e2 * e2
        else:
            d[M_U + 2 * k] = 0.0
            d[M_U + 2 * k + 1] = 0.0
    det = c11 * c22 - c12 * c12
    trace = c11 + c22
    if not det > 1e-24 * trace * trace:
        return False
    v1 = y[M_V]
    v2 = y[M_V + 1]
    rd1 = (c22 * v1 - c12 * v2) / det
    rd2 = (-c12 * v1 + c11 * v2) / det
    fric = 0.0
    for k in range(ng):
        if mask >> k & 1:
            e1 = d[M_U + 2 * k]
            e2 = d[M_U + 2 * k + 1]
            lam = rb[k] * (e1 * rd1 + e2 * rd2)
            d[M_U + 2 * k] = lam * e1
            d[M_U + 2 * k + 1] = lam * e2
            fric += mu[k] * lam
    d[M_X] = v1
    d[M_X + 1] = v2
    d[M_V] = -nn * y[M_R] - c * v1 - axx
    d[M_V + 1] = -nn * y[M_R + 1] - c * v2 - ayy
    d[M_R] = rd1
    d[M_R + 1] = rd2
    d[M_EIN] = -(axx * v1 + ayy * v2)
    if raw[5] != 0.0:
        # the work of the vertical motion: ṅ Σ|ū_k|²/(2R̄_k) (the stored energy is n Σ|ū_k|²/(2R̄_k))
        d[M_EIN] += raw[5] * stored_per_n(y, rb)
    d[M_EF] = nn * fric
    d[M_EV] = c * (v1 * v1 + v2 * v2)
    return True


@njit(cache=True)
def multi_step(tau, y, f0, h, raw, rb, mu, mask, c, ynew, fnew, atol, rtol, kk, yt):
    """One DOP853 step (scipy's tableau and error norm) of the multi-group state; (ok, err)."""
    m = y.shape[0]
    for j in range(m):
        kk[0, j] = f0[j]
    for s in range(1, _NS):
        # the stage state where the rates read it (V, r, the sliding groups' ū): X, the energies and the stuck
        # groups' ū do not enter them (left as they are in yt)
        for j in range(M_V, M_EIN):
            acc = 0.0
            for q in range(s):
                acc += _A[s, q] * kk[q, j]
            yt[j] = y[j] + h * acc
        for k in range((m - M_U) // 2):
            if mask >> k & 1:
                for j in range(M_U + 2 * k, M_U + 2 * k + 2):
                    acc = 0.0
                    for q in range(s):
                        acc += _A[s, q] * kk[q, j]
                    yt[j] = y[j] + h * acc
            elif raw[5] != 0.0:
                # under a vertical the stuck groups' ū enter the input's rate (multi_rhs: ṅ Σ|ū_k|²/(2R̄_k))
                yt[M_U + 2 * k] = y[M_U + 2 * k]
                yt[M_U + 2 * k + 1] = y[M_U + 2 * k + 1]
        if not multi_rhs(tau + _C[s] * h, yt, raw, rb, mu, mask, c, kk[s]):
            return False, np.inf
    for j in range(m):
        acc = 0.0
        for q in range(_NS):
            acc += _B[q] * kk[q, j]
        ynew[j] = y[j] + h * acc
    if not multi_rhs(tau + h, ynew, raw, rb, mu, mask, c, fnew):
        return False, np.inf
    for j in range(m):
        kk[_NS, j] = fnew[j]
    e5 = 0.0
    e3 = 0.0
    for j in range(m):
        sc = atol[j] + rtol * max(abs(y[j]), abs(ynew[j]))
        a5 = 0.0
        a3 = 0.0
        for q in range(_NS + 1):
            a5 += _E5[q] * kk[q, j]
            a3 += _E3[q] * kk[q, j]
        e5 += (a5 / sc) ** 2
        e3 += (a3 / sc) ** 2
    if e5 == 0.0 and e3 == 0.0:
        return True, 0.0
    err = abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * m)
    if not err < np.inf:
        return False, np.inf
    return True, err


# Radau IIA, three stages (order 5, stiffly accurate, L-stable; Hairer & Wanner, *Solving ODEs II*, §IV.5):
# the step of a corner whose normals are close to parallel, where the split of V between the groups relaxes at a
# rate ∝ 1/angle² (docs/multisurface.md) and the explicit DOP853 steps would fall to the relaxation time
_SQ6 = math.sqrt(6.0)
_RC = np.array([(4.0 - _SQ6) / 10.0, (4.0 + _SQ6) / 10.0, 1.0])
_RA = np.array([[(88.0 - 7.0 * _SQ6) / 360.0, (296.0 - 169.0 * _SQ6) / 1800.0, (-2.0 + 3.0 * _SQ6) / 225.0],
                [(296.0 + 169.0 * _SQ6) / 1800.0, (88.0 + 7.0 * _SQ6) / 360.0, (-2.0 - 3.0 * _SQ6) / 225.0],
                [(16.0 - _SQ6) / 36.0, (16.0 + _SQ6) / 36.0, 1.0 / 9.0]])


def _radau_eigenbasis():
    # A⁻¹ = T Λ T⁻¹ with Λ = [[γ, 0, 0], [0, α, β], [0, −β, α]] (its real eigenvalue γ and the pair α ± iβ), T real:
    # the 3n × 3n Newton system splits into one real and one complex n × n system (Hairer & Wanner, §IV.8; RADAU5)
    w, vec = np.linalg.eig(np.linalg.inv(_RA))
    kr = int(np.argmin(np.abs(w.imag)))
    kc = int(np.argmax(w.imag))
    t = np.empty((3, 3))
    t[:, 0] = vec[:, kr].real / np.abs(vec[:, kr].real).max()
    t[:, 1] = vec[:, kc].real
    t[:, 2] = vec[:, kc].imag
    ti = np.linalg.inv(t)
    lam = ti @ np.linalg.inv(_RA) @ t
    return t, ti, float(lam[0, 0]), float(lam[1, 1]), float(lam[1, 2])


_RT, _RTI, _RGAMMA, _RALPHA, _RBETA = _radau_eigenbasis()
#: corners whose sliding normals make an angle below this [rad] take the implicit steps.  The fast mode's rate is
#: ≈ 40/s² 1/s (F&C's corner), so DOP853's stability bound ≈ 6 s²/40 s: at s = 0.02 … 0.05 it takes ~3× the steps
#: of Radau IIA at a tenth of their cost (PTS at 0.02 instead of 0.05: 1 178 instead of 1 933 implicit steps,
#: 6 569 instead of 4 003 explicit ones, the same answer to 5e-11 of the peak)
IMPLICIT_ANGLE = 0.02
#: corners of three or more groups take the implicit steps where C = Σ R̄_k e_k e_kᵀ is this close to singular,
#: κ = √det C / tr C (for two groups κ = √(R̄_a R̄_b) s/(R̄_a + R̄_b)).  Three circles through r do not relax at the
#: closest pair's 1/s² (the third normal keeps C regular): their fast rate is ≈ 4.4 |V|/κ² (PTS, the Jacobian of the
#: reduced state at 700 logged three-group steps: 4.1–5.5, against the closest pair's 55 |V|/s² on two groups), so
#: the smallest sine sent them to the implicit steps where the explicit ones are no shorter (docs/multisurface.md,
#: "The corner steps by time, and the three-group switch").  At κ = 0.01 and |V| = 0.5 m/s that rate is ~2e4 1/s and
#: DOP853's steps ~1e-4 s, a fifth of the implicit steps' ~5e-4 s there (an implicit step costs ~5 explicit ones);
#: below it, as κ → 0 (three normals parallel), the explicit steps would collapse.  PTS at 0 / 0.003 / 0.006 / 0.01
#: / 0.02: 621 / 627 / 639 / 680 / 806 implicit corner steps, the same time within the noise
IMPLICIT_SPREAD = 0.01
#: a corner of two groups closing towards tangency steps at most this fraction of its time to tangency s/|ṡ| (the
#: simplified Newton's Jacobian, ∝ 1/s², then changes by at most (1 − CLOSING_STEP)^−2 over the step, about half of
#: that from the step's middle, where it is taken).  PTS: 0.15 / 0.25 / 0.35 gave 1 121 / 951 / 1 027 implicit steps,
#: 19 / 23 / 76 of them refused by Newton
CLOSING_STEP = 0.25
#: the same for a corner opening after a tangency (the Jacobian then falls by at most (1 + OPENING_STEP)^−2)
OPENING_STEP = 0.3
#: the implicit steps' embedded estimate (RADAU5's, the error of an order-3 companion of the order-5 step: it
#: overstates the step's own error) over this is what a reduced corner's step is held to.  Chosen by measurement
#: (docs/multisurface.md, "The corner's implicit steps checked by their embedded estimate"): with the second estimate
#: at only the refused steps, PTS took 2 815 / ~2 450 / ~2 300 / 1 298 implicit steps at 1 / 10 / 30 / 100 (965 with
#: the step doubling before); now Christchurch CBGS 0–12 s at rtol 1e-11 is 4.9e-10 of the peak from the old kernel at
#: 1e-12 (the old kernel at 1e-11: 5.0e-10)
EST_SCALE = 100.0
#: an implicit step refused twice in a row is retried at most this fraction of the refused one
REFUSED_AGAIN = 0.25
#: simplified-Newton iterations of one implicit step before it is refused (the step is then shortened)
NEWTON_MAX = 20
#: a simplified-Newton increment this small (in units of the step's local error tolerance) ends the iteration
NEWTON_FLOOR = 1e-2
#: an implicit step reuses the Jacobian of the step before it when that step was accepted (the state is where it
#: ended, same sliding groups) and its Newton iteration contracted at least this fast (RADAU5's THET, Hairer & Wanner
#: §IV.8); a refused step or a slower contraction takes a new one
JAC_THETA = 1e-3


@njit(cache=True)
def corner_angle(y, rb, mask):
    """Smallest |sin| of the angle between two sliding normals of the multi-group state (1 if none close)."""
    best = 1.0
    for k in range(rb.shape[0]):
        if not mask >> k & 1:
            continue
        a1 = y[M_R] - y[M_U + 2 * k] / rb[k]
        a2 = y[M_R + 1] - y[M_U + 2 * k + 1] / rb[k]
        an = math.sqrt(a1 * a1 + a2 * a2)
        for q in range(k + 1, rb.shape[0]):
            if not mask >> q & 1:
                continue
            b1 = y[M_R] - y[M_U + 2 * q] / rb[q]
            b2 = y[M_R + 1] - y[M_U + 2 * q + 1] / rb[q]
            bn = math.sqrt(b1 * b1 + b2 * b2)
            if a1 * b1 + a2 * b2 > 0.0:
                best = min(best, abs(a1 * b2 - a2 * b1) / (an * bn))
    return best


@njit(cache=True)
def compliance(y, rb, mask):
    """C = Σ R̄_k e_k e_kᵀ over the groups of ``mask`` in the multi-group state: (C11, C12, C22, their count)."""
    n = 0
    c11 = 0.0
    c12 = 0.0
    c22 = 0.0
    for k in range(rb.shape[0]):
        if mask >> k & 1:
            n += 1
            e1, e2 = _normal(y, rb, k)
            c11 += rb[k] * e1 * e1
            c12 += rb[k] * e1 * e2
            c22 += rb[k] * e2 * e2
    return c11, c12, c22, n


@njit(cache=True)
def corner_implicit(y, rb, mask):
    """Whether the corner of the multi-group state takes the implicit steps: two groups whose normals' sine is below
    IMPLICIT_ANGLE, three or more whose compliance's κ = √det C / tr C is below IMPLICIT_SPREAD."""
    c11, c12, c22, n = compliance(y, rb, mask)
    if n < 3:
        return corner_angle(y, rb, mask) < IMPLICIT_ANGLE
    det = max(c11 * c22 - c12 * c12, 0.0)
    return math.sqrt(det) < IMPLICIT_SPREAD * (c11 + c22)


@njit(cache=True)
def _active(mask, m, act):
    """The components of the multi-group state that the implicit step solves for: X, V, r and the sliding groups'
    ū (the energies are quadratures and the stuck groups' ū stay: nothing depends on them).  Returns their count."""
    na = 0
    for p in range(M_EIN):
        act[na] = p
        na += 1
    for k in range((m - M_U) // 2):
        if mask >> k & 1:
            act[na] = M_U + 2 * k
            act[na + 1] = M_U + 2 * k + 1
            na += 2
    return na


@njit(cache=True)
def _radau_matrix(h, jac, na, e1, p1, e2, p2):
    """The simplified-Newton matrix of the three stages over the active components, h⁻¹ A⁻¹ ⊗ I − I ⊗ J, in A's
    eigenbasis (:func:`_radau_eigenbasis`): γ/h − J (real, ``e1``) and (α − iβ)/h − J (complex, ``e2``), LU-factored
    in place: False if singular, or if h is not positive (a zero step reached it at rtol >= 1e-5 with a division by zero:
    the caller then gives up with its singular status, h178)."""
    if not h > 0.0:
        return False
    for p in range(na):
        for q in range(na):
            e1[p, q] = -jac[p, q]
            e2[p, q] = -jac[p, q]
        e1[p, p] += _RGAMMA / h
        e2[p, p] += complex(_RALPHA / h, -_RBETA / h)
    return lu_factor(e1, p1) and lu_factor(e2, p2)


@njit(cache=True)
def _radau_newton(h, z, fz, act, na, e1, p1, e2, p2, dz, w1, w2):
    """One simplified-Newton increment ``dz`` of the stage increments z (rates ``fz`` at the stages): with W = T⁻¹Z,
    (h⁻¹Λ − J) ΔW = T⁻¹F − h⁻¹ΛW, solved as one real and one complex system, and ΔZ = T ΔW."""
    for q in range(na):
        p = act[q]
        zt0 = 0.0
        zt1 = 0.0
        zt2 = 0.0
        f0 = 0.0
        f1 = 0.0
        f2 = 0.0
        for j in range(3):
            zj = z[j * na + q]
            fj = fz[j, p]
            zt0 += _RTI[0, j] * zj
            zt1 += _RTI[1, j] * zj
            zt2 += _RTI[2, j] * zj
            f0 += _RTI[0, j] * fj
            f1 += _RTI[1, j] * fj
            f2 += _RTI[2, j] * fj
        w1[q] = f0 - _RGAMMA / h * zt0
        w2[q] = complex(f1 - (_RALPHA * zt1 + _RBETA * zt2) / h, f2 - (-_RBETA * zt1 + _RALPHA * zt2) / h)
    lu_solve(e1, p1, w1)
    lu_solve(e2, p2, w2)
    for q in range(na):
        a = w1[q]
        b = w2[q].real
        c = w2[q].imag
        for i in range(3):
            dz[i * na + q] = _RT[i, 0] * a + _RT[i, 1] * b + _RT[i, 2] * c


@njit(cache=True)
def _corner_pair(mask, ng):
    """The two sliding groups (ka, kb) of a corner of exactly two groups; (-1, -1) otherwise."""
    ka = -1
    kb = -1
    for k in range(ng):
        if mask >> k & 1:
            if ka < 0:
                ka = k
            elif kb < 0:
                kb = k
            else:
                return -1, -1
    if kb < 0:
        return -1, -1
    return ka, kb


@njit(cache=True)
def reduce_corner(y, rb, ka, kb, v):
    """The reduced state of a corner of two groups: ``y`` with the slots of r holding the direction θ_a of the
    normal e_a and the signed angle φ from e_a to e_b [rad] (the other slots as in y; the two groups' ū are
    functions of X, θ_a and φ, :func:`expand_corner`)."""
    for p in range(y.shape[0]):
        v[p] = y[p]
    a1, a2 = _normal(y, rb, ka)
    b1, b2 = _normal(y, rb, kb)
    v[M_R] = math.atan2(a2, a1)
    v[M_R + 1] = math.atan2(a1 * b2 - a2 * b1, a1 * b1 + a2 * b2)


@njit(cache=True)
def _place_pair(y, rb, ka, kb, s1, s2, n1, n2):
    """Place the displacements of two groups with ū_a + ū_b = s and centres b_b − b_a = n: b_a = (s − R̄_b n)/(R̄_a
    + R̄_b), ū_a = R̄_a b_a, ū_b = s − ū_a (the sum exact).  Returns b_a."""
    rs = rb[ka] + rb[kb]
    ca1 = (s1 - rb[kb] * n1) / rs
    ca2 = (s2 - rb[kb] * n2) / rs
    y[M_U + 2 * ka] = rb[ka] * ca1
    y[M_U + 2 * ka + 1] = rb[ka] * ca2
    y[M_U + 2 * kb] = s1 - y[M_U + 2 * ka]
    y[M_U + 2 * kb + 1] = s2 - y[M_U + 2 * ka + 1]
    return ca1, ca2


@njit(cache=True)
def expand_corner(v, rb, mu, ka, kb, y):
    """The multi-group state of a reduced corner state (:func:`reduce_corner`).  With e_a, e_b the normals at θ_a
    and θ_a + φ the centres differ by b_b − b_a = µ_a e_a − µ_b e_b (r on both circles), and ū_a + ū_b = X − Σ the
    stuck ū, so b_a = (X − Σ stuck ū − R̄_b (µ_a e_a − µ_b e_b))/(R̄_a + R̄_b), r = b_a + µ_a e_a: r is on both
    circles exactly, and the corner's opening is φ itself (in r and ū it is a difference of nearly equal lengths,
    |b_a − b_b| − (µ_a − µ_b) ∝ φ², which loses its digits as the corner closes)."""
    _expand_normals(v, rb, mu, ka, kb, y, math.cos(v[M_R]), math.sin(v[M_R]), math.cos(v[M_R] + v[M_R + 1]),
                    math.sin(v[M_R] + v[M_R + 1]))


@njit(cache=True)
def _expand_normals(v, rb, mu, ka, kb, y, a1, a2, b1, b2):
    # expand_corner with the normals e_a = (a1, a2), e_b = (b1, b2) of the reduced state v given
    for p in range(v.shape[0]):
        y[p] = v[p]
    d1 = mu[ka] * a1 - mu[kb] * b1
    d2 = mu[ka] * a2 - mu[kb] * b2
    w1 = v[M_X]
    w2 = v[M_X + 1]
    for k in range(rb.shape[0]):
        if k != ka and k != kb:
            w1 -= v[M_U + 2 * k]
            w2 -= v[M_U + 2 * k + 1]
    ba1, ba2 = _place_pair(y, rb, ka, kb, w1, w2, d1, d2)
    y[M_R] = ba1 + mu[ka] * a1
    y[M_R + 1] = ba2 + mu[ka] * a2


@njit(cache=True)
def third_group(mask, ng, ka, kb):
    """The sliding group other than ka and kb on a corner of exactly three groups; -1 otherwise."""
    kc = -1
    for k in range(ng):
        if mask >> k & 1 and k != ka and k != kb:
            if kc >= 0:
                return -1
            kc = k
    return kc


@njit(cache=True)
def reduced_pair(y, rb, mask):
    """The groups (ka, kb) whose angles the reduced state carries: the two of a corner of two groups, or the two of
    a corner of three whose normals are closest to parallel (the third's angle is then carried too:
    :func:`reduce_state`); (-1, -1) for more groups."""
    ng = rb.shape[0]
    ka, kb = _corner_pair(mask, ng)
    if ka >= 0:
        return ka, kb
    best = 2.0
    n = 0
    for k in range(ng):
        if not mask >> k & 1:
            continue
        n += 1
        a1, a2 = _normal(y, rb, k)
        for q in range(k + 1, ng):
            if not mask >> q & 1:
                continue
            b1, b2 = _normal(y, rb, q)
            sn = abs(a1 * b2 - a2 * b1)
            if a1 * b1 + a2 * b2 > 0.0 and sn < best:
                best = sn
                ka = k
                kb = q
    if n != 3:
        return -1, -1
    return ka, kb


@njit(cache=True)
def reduce_state(y, rb, mask, ka, kb, v):
    """:func:`reduce_corner`, and on a corner of three groups the third's normal as its angle from e_a [rad] in the
    first of its ū slots (the second 0): r and the three ū are functions of X and the three angles."""
    reduce_corner(y, rb, ka, kb, v)
    kc = third_group(mask, rb.shape[0], ka, kb)
    if kc >= 0:
        a1, a2 = _normal(y, rb, ka)
        c1, c2 = _normal(y, rb, kc)
        v[M_U + 2 * kc] = math.atan2(a1 * c2 - a2 * c1, a1 * c1 + a2 * c2)
        v[M_U + 2 * kc + 1] = 0.0


@njit(cache=True)
def _expand_three(v, rb, mu, ka, kb, kc, y, a1, a2, b1, b2, c1, c2):
    # three circles through r with the normals e_a, e_b, e_c: ū_k = R̄_k (r − µ_k e_k) and Σ ū_k = X − Σ stuck ū give
    # r = (X − Σ stuck ū + Σ R̄_k µ_k e_k)/Σ R̄_k; ū_b is the rest (the sum exact)
    for p in range(v.shape[0]):
        y[p] = v[p]
    w1 = v[M_X]
    w2 = v[M_X + 1]
    for k in range(rb.shape[0]):
        if k != ka and k != kb and k != kc:
            w1 -= v[M_U + 2 * k]
            w2 -= v[M_U + 2 * k + 1]
    rs = rb[ka] + rb[kb] + rb[kc]
    r1 = (w1 + rb[ka] * mu[ka] * a1 + rb[kb] * mu[kb] * b1 + rb[kc] * mu[kc] * c1) / rs
    r2 = (w2 + rb[ka] * mu[ka] * a2 + rb[kb] * mu[kb] * b2 + rb[kc] * mu[kc] * c2) / rs
    y[M_R] = r1
    y[M_R + 1] = r2
    y[M_U + 2 * ka] = rb[ka] * (r1 - mu[ka] * a1)
    y[M_U + 2 * ka + 1] = rb[ka] * (r2 - mu[ka] * a2)
    y[M_U + 2 * kc] = rb[kc] * (r1 - mu[kc] * c1)
    y[M_U + 2 * kc + 1] = rb[kc] * (r2 - mu[kc] * c2)
    y[M_U + 2 * kb] = w1 - y[M_U + 2 * ka] - y[M_U + 2 * kc]
    y[M_U + 2 * kb + 1] = w2 - y[M_U + 2 * ka + 1] - y[M_U + 2 * kc + 1]


@njit(cache=True)
def expand_state(v, rb, mu, mask, ka, kb, y):
    """The multi-group state of a reduced state (:func:`reduce_state`): :func:`expand_corner`, or three circles."""
    kc = third_group(mask, rb.shape[0], ka, kb)
    if kc < 0:
        expand_corner(v, rb, mu, ka, kb, y)
        return
    ta = v[M_R]
    _expand_three(v, rb, mu, ka, kb, kc, y, math.cos(ta), math.sin(ta), math.cos(ta + v[M_R + 1]),
                  math.sin(ta + v[M_R + 1]), math.cos(ta + v[M_U + 2 * kc]), math.sin(ta + v[M_U + 2 * kc]))


@njit(cache=True)
def reduced_rhs(tau, v, raw, rb, mu, mask, c, ka, kb, yw, d):
    """Derivative of the reduced corner state: X, V and the energies as in :func:`multi_rhs`, θ̇_k = e_k⊥·ṙ/µ_k
    (ṙ − ḃ_k ⊥ e_k, ḃ_k = λ_k e_k/R̄_k ∥ e_k), φ̇ = θ̇_b − θ̇_a; the two groups' ū slots are not integrated (0)."""
    a1 = math.cos(v[M_R])
    a2 = math.sin(v[M_R])
    b1 = math.cos(v[M_R] + v[M_R + 1])
    b2 = math.sin(v[M_R] + v[M_R + 1])
    kc = third_group(mask, rb.shape[0], ka, kb)
    c1 = 0.0
    c2 = 0.0
    if kc < 0:
        _expand_normals(v, rb, mu, ka, kb, yw, a1, a2, b1, b2)
    else:
        c1 = math.cos(v[M_R] + v[M_U + 2 * kc])
        c2 = math.sin(v[M_R] + v[M_U + 2 * kc])
        _expand_three(v, rb, mu, ka, kb, kc, yw, a1, a2, b1, b2, c1, c2)
    if not multi_rhs(tau, yw, raw, rb, mu, mask, c, d):
        return False
    ta = (a1 * d[M_R + 1] - a2 * d[M_R]) / mu[ka]
    tb = (b1 * d[M_R + 1] - b2 * d[M_R]) / mu[kb]
    tc = 0.0
    if kc >= 0:
        tc = (c1 * d[M_R + 1] - c2 * d[M_R]) / mu[kc]
    d[M_R] = ta
    d[M_R + 1] = tb - ta
    for k in (ka, kb):
        d[M_U + 2 * k] = 0.0
        d[M_U + 2 * k + 1] = 0.0
    if kc >= 0:
        # the third normal's angle from e_a, in its first ū slot (reduce_state)
        d[M_U + 2 * kc] = tc - ta
        d[M_U + 2 * kc + 1] = 0.0
    return True


@njit(cache=True)
def _rates(tau, v, raw, rb, mu, mask, c, ka, kb, yw, d):
    # the rates of the multi-group state (ka < 0) or of the reduced corner state
    if ka < 0:
        return multi_rhs(tau, v, raw, rb, mu, mask, c, d)
    return reduced_rhs(tau, v, raw, rb, mu, mask, c, ka, kb, yw, d)


@njit(cache=True)
def _stage_rates(tau, y, h, z, act, na, raw, rb, mu, mask, c, fz, yt, ka, kb, yw, st):
    # the rates fz[i] at the three stages y + z_i (z over the active components): False where C is singular
    st[ST_RATES] += 3
    for i in range(3):
        for p in range(y.shape[0]):
            yt[p] = y[p]
        for q in range(na):
            yt[act[q]] += z[i * na + q]
        if not _rates(tau + _RC[i] * h, yt, raw, rb, mu, mask, c, ka, kb, yw, fz[i]):
            return False
    return True


@njit(cache=True)
def _node_basis(x, i):
    """The Lagrange polynomial of the collocation node c_i over the nodes (0, c_1, c_2, c_3) at x (in units of the
    step): the collocation polynomial of a step from y is y + Σ_i z_i L_i(τ/h)."""
    acc = 1.0
    for k in range(-1, 3):
        if k != i:
            ck = 0.0 if k < 0 else _RC[k]
            acc *= (x - ck) / (_RC[i] - ck)
    return acc


@njit(cache=True)
def _predict(zsrc, na, x0, ratio, zdst):
    """Newton's start for a step of ``ratio`` × the source step's length beginning at x0 (in units of the source
    step) on the source step's collocation polynomial (stage increments ``zsrc``): the new stage increments read
    off that polynomial (Hairer & Wanner, *Solving ODEs II*, §IV.8: the previous step's polynomial extrapolated)."""
    for j in range(3):
        x = x0 + _RC[j] * ratio
        for q in range(na):
            zdst[j * na + q] = 0.0
        for i in range(3):
            w = _node_basis(x, i) - _node_basis(x0, i)
            for q in range(na):
                zdst[j * na + q] += w * zsrc[i * na + q]


@njit(cache=True)
def _radau_solve(tau, y, h, raw, rb, mu, mask, c, e1, p1, e2, p2, act, na, sc, ynew, ka, kb, yw, st, z, fz, res,
                 yt, w1, w2, jr):
    """One Radau IIA step of length h from (τ, y) by simplified Newton on the active components (``e1``, ``e2``:
    the factored iteration matrices of :func:`_radau_matrix`; ``z``: in, Newton's start for the stage increments; out,
    the converged ones), the others by the collocation's quadrature of their rates at the converged stages: False
    if it fails.  ``fz`` (3 × m), ``res`` (≥ 3 na), ``yt`` (m), ``w1``, ``w2`` (≥ na, complex): work arrays;
    ``jr[2]``: out, the iteration's last contraction rate (0 when the first increment was already converged)."""
    m = y.shape[0]
    n3 = 3 * na
    fz[:, :] = 0.0
    res[:] = 0.0
    yt[:] = 0.0
    last = np.inf
    for it in range(NEWTON_MAX):
        st[ST_NEWTON] += 1
        if not _stage_rates(tau, y, h, z, act, na, raw, rb, mu, mask, c, fz, yt, ka, kb, yw, st):
            st[ST_NEWTON_SINGULAR] += 1
            return False
        _radau_newton(h, z, fz, act, na, e1, p1, e2, p2, res, w1, w2)
        dn = 0.0
        for i in range(3):
            for q in range(na):
                z[i * na + q] += res[i * na + q]
                dn += (res[i * na + q] / sc[act[q]]) ** 2
        dn = math.sqrt(dn / n3)
        # the contraction rate of the iteration: its remaining error is ≈ dn θ/(1 − θ) (Hairer & Wanner, §IV.8).
        # Near a closing corner the rates carry the state's rounding times ∝ 1/s², which puts a floor under dn
        # (PTS at s = 7e-4: 1.5e-4 with the step's tolerance 1 in these units): an increment at that floor, far below
        # the tolerance, ends the iteration instead of failing it
        theta = dn / last if it >= 1 else 1.0
        floor = it >= 2 and dn <= NEWTON_FLOOR
        if not dn < np.inf or (it >= 2 and dn > last and not floor):
            st[ST_NEWTON_DIVERGED if dn < np.inf else ST_NEWTON_SINGULAR] += 1
            return False
        last = dn
        # Newton's remaining error well below the local error allowed (1 in these units)
        done = dn <= 1e-4 or floor or (theta < 1.0 and dn * theta / (1.0 - theta) <= NEWTON_FLOOR)
        if not done and it >= 1 and dn > NEWTON_FLOOR and (theta >= 0.99 or dn * theta ** (NEWTON_MAX - 1 - it) / (1.0 - theta)
                                     > NEWTON_FLOOR):
            # at this contraction the iterations left cannot reach the floor: refused now, not after them (RADAU5)
            st[ST_NEWTON_MAXIT] += 1
            return False
        if done:
            jr[2] = theta if it >= 1 else 0.0
            # the rates at the converged stages: the quadrature of the other components (stiffly accurate: the
            # last stage's row of A is the weights)
            if not _stage_rates(tau, y, h, z, act, na, raw, rb, mu, mask, c, fz, yt, ka, kb, yw, st):
                return False
            for p in range(m):
                ynew[p] = y[p] + h * (_RA[2, 0] * fz[0, p] + _RA[2, 1] * fz[1, p] + _RA[2, 2] * fz[2, p])
            for q in range(na):
                ynew[act[q]] = y[act[q]] + z[2 * na + q]
            return True
    st[ST_NEWTON_MAXIT] += 1
    return False


#: the implicit steps' memory (``radau_step``'s ``rm``, float64[2, RM_Z + 3 m]): row RM_PENDING holds the last
#: step solved, row RM_PREV the one that ended where the current step starts; per row its flag, the sliding
#: groups, the length of its last half step, the state it ended at (as the next step reads it) and that half
#: step's stage increments
RM_PENDING = 0
RM_PREV = 1
RM_FLAG = 0
RM_MASK = 1
RM_H = 2
RM_KEY = 3


#: the rows of the implicit steps' float work array (:func:`radau_memory`, ``rm[1]``, float64[W_ROWS, m])
W_YW = 0
W_TOL = 1
W_V = 2
W_FV = 3
W_SC = 4
W_VJ = 5
W_FJ = 6
W_YP = 7
W_FP = 8
W_VNEW = 9
W_YT = 10
W_EST = 11
W_YT2 = 12
W_F0 = 13
W_W1 = 14
W_W = 15
W_ROWS = 16


@njit(cache=True)
def radau_memory(m):
    """The implicit steps' memory and work arrays for a multi-group state of m components (``radau_step``'s
    ``rm``), allocated once per run instead of once per step: (memory float64[2, RM_KEY + 4 m] (below), float
    vectors float64[W_ROWS, m], the stage rates float64[3, m], the stage increments and Newton's increment
    float64[2, 3 m], the active components and the two pivot vectors int64[3, m], the Jacobian and the real
    matrix float64[2, m²], the complex matrix complex128[m²] and vector complex128[m], and the Jacobian's record
    float64[3]: valid flag, its sliding groups, the contraction rate of the last Newton solve with it)."""
    return (np.zeros((2, RM_KEY + 4 * m)), np.zeros((W_ROWS, m)), np.zeros((3, m)), np.zeros((2, 3 * m)),
            np.zeros((3, m), dtype=np.int64), np.zeros((2, m * m)), np.zeros(m * m, dtype=np.complex128),
            np.zeros(m, dtype=np.complex128), np.zeros(3))


@njit(cache=True)
def _recall(rm, mask, v, m):
    """True when the memory holds the step that ended at v with these sliding groups (the pending one is promoted:
    a step starting where it ended was accepted)."""
    if rm[RM_PENDING, RM_FLAG] == 1.0 and rm[RM_PENDING, RM_MASK] == mask:
        same = True
        for p in range(m):
            if rm[RM_PENDING, RM_KEY + p] != v[p]:
                same = False
                break
        if same:
            rm[RM_PREV, :] = rm[RM_PENDING, :]
            rm[RM_PENDING, RM_FLAG] = 0.0
    if rm[RM_PREV, RM_FLAG] != 1.0 or rm[RM_PREV, RM_MASK] != mask:
        return False
    for p in range(m):
        if rm[RM_PREV, RM_KEY + p] != v[p]:
            return False
    return True


@njit(cache=True)
def radau_step(tau, y, f0, h, raw, rb, mu, mask, c, ynew, fnew, atol, rtol, st, rm):
    """One implicit step of the multi-group state: Radau IIA over h, its error by RADAU5's embedded estimate
    (:func:`_radau_estimate`, the step's own factored matrix: no second solve; before, the step was taken once more
    as two halves and checked by their difference, three Newton solves per step); (ok, err) with err squared so that
    the order-8 step factor of the explicit steps (err^(−1/8)) gives the estimate's own (err^(−1/4)).  Newton solves
    for the active components only (:func:`_active`).  Newton starts from the previous step's collocation polynomial
    (:func:`_predict`, ``rm``, when the state is where that step ended).

    A corner of exactly two groups is stepped in its reduced state (:func:`reduce_corner`: X, V, θ_a, φ; r and
    the two ū are functions of them, on both circles exactly): its opening φ is a state of its own instead of a
    difference of nearly equal lengths of r and ū, so the steps are set by the motion, not by the rounding of the
    opening (PTS: 28 705 implicit steps in r and ū, docs/multisurface.md).  A corner of exactly three groups is
    stepped in the same state with the third normal's angle from e_a besides (:func:`reduce_state`: r and the three
    ū on the three circles exactly; 7 unknowns instead of the Cartesian state's 12, so its Newton systems are 7 × 7:
    PTS 1 712 → 1 245 implicit steps, docs/multisurface.md, "A reduced state for three groups").  The step's error
    is measured on the reduced state (the angles' tolerance: r's over the largest µ).  ``rm``:
    :func:`radau_memory` (no array is allocated per step)."""
    m = y.shape[0]
    st[ST_RADAU] += 1
    st[ST_LU] += 2
    ka, kb = reduced_pair(y, rb, mask)
    kc = third_group(mask, rb.shape[0], ka, kb) if ka >= 0 else -1
    mem, fw, fz, z3, iw, mats, cmat, cvec, jr = rm
    yw = fw[W_YW]
    act = iw[0]
    tol = fw[W_TOL]
    tol[:] = atol
    if ka >= 0:
        v = fw[W_V]
        reduce_state(y, rb, mask, ka, kb, v)
        fv = fw[W_FV]
        if not reduced_rhs(tau, v, raw, rb, mu, mask, c, ka, kb, yw, fv):
            return False, np.inf
        tol[M_R] = atol[M_R] / max(mu[ka], mu[kb])
        tol[M_R + 1] = tol[M_R]
        for p in range(M_EIN):
            act[p] = p
        na = M_EIN
        if kc >= 0:
            st[ST_RADAU_THREE] += 1
            tol[M_R] = atol[M_R] / max(mu[ka], mu[kb], mu[kc])
            tol[M_R + 1] = tol[M_R]
            tol[M_U + 2 * kc] = tol[M_R]
            act[na] = M_U + 2 * kc
            na += 1
    else:
        v = y
        fv = f0
        na = _active(mask, m, act)
    n3 = 3 * na
    zf = z3[0]
    zf[:] = 0.0
    sc = fw[W_SC]
    for p in range(m):
        sc[p] = tol[p] + rtol * abs(v[p])
    recalled = _recall(mem, mask, v, m)
    zsrc = mem[RM_PREV, RM_KEY + m:RM_KEY + m + n3]
    ratio = 1.0
    if recalled:
        ratio = h / mem[RM_PREV, RM_H]
        _predict(zsrc, na, 1.0, ratio, zf)
    # the Jacobian of the step before, where that step was accepted (the state is where it ended) with the same
    # sliding groups and its Newton iteration contracted fast (JAC_THETA, RADAU5's rule); else a new one
    jac = mats[0, :na * na].reshape((na, na))
    yp = fw[W_YP]
    if not (recalled and jr[0] == 1.0 and jr[1] == mask and jr[2] <= JAC_THETA):
        st[ST_JAC] += 1
        jr[0] = 0.0
        # the Jacobian's point: the step's middle on the previous step's polynomial where there is one (the corner's
        # fast mode goes as 1/s², so across a closing step the start's Jacobian is off by (1 − CLOSING_STEP)^−2, the
        # middle's by about half that), else the start
        vj = fw[W_VJ]
        vj[:] = v
        tj = tau
        fj = fv
        if recalled:
            for i in range(3):
                w = _node_basis(1.0 + 0.5 * ratio, i) - _node_basis(1.0, i)
                for q in range(na):
                    vj[act[q]] += w * zsrc[i * na + q]
            fj = fw[W_FJ]
            tj = tau + 0.5 * h
            if not _rates(tj, vj, raw, rb, mu, mask, c, ka, kb, yw, fj):
                vj[:] = v
                tj = tau
                fj = fv
        yp[:] = vj
        fp = fw[W_FP]
        for qa in range(na):
            q = act[qa]
            # a difference step of √ε times the component's own scale (atol/rtol + |y|)
            dq = 1.5e-8 * max(sc[q] / rtol, 1e-12)
            yp[q] = vj[q] + dq
            if not _rates(tj, yp, raw, rb, mu, mask, c, ka, kb, yw, fp):
                dq = -dq
                yp[q] = vj[q] + dq
                if not _rates(tj, yp, raw, rb, mu, mask, c, ka, kb, yw, fp):
                    return False, np.inf
            for pa in range(na):
                jac[pa, qa] = (fp[act[pa]] - fj[act[pa]]) / dq
            yp[q] = vj[q]
        jr[0] = 1.0
        jr[1] = mask
    # the Jacobian is kept for the next step only if this one is accepted with a fast contraction (jr[2], set by
    # _radau_solve): a refusal takes it out
    valid = jr[0]
    jr[0] = 0.0
    e1 = mats[1, :na * na].reshape((na, na))
    p1 = iw[1]
    p1[:] = 0
    e2 = cmat[:na * na].reshape((na, na))
    p2 = iw[2]
    p2[:] = 0
    vnew = fw[W_VNEW]
    if not (_radau_matrix(h, jac, na, e1, p1, e2, p2)
            and _radau_solve(tau, v, h, raw, rb, mu, mask, c, e1, p1, e2, p2, act, na, sc, vnew, ka, kb, yw, st,
                             zf, fz, z3[1], fw[W_YT], fw[W_W1], cvec, jr)):
        return False, np.inf
    if ka >= 0:
        expand_state(vnew, rb, mu, mask, ka, kb, ynew)
    else:
        ynew[:] = vnew
    if not multi_rhs(tau + h, ynew, raw, rb, mu, mask, c, fnew):
        return False, np.inf
    # the embedded estimate (RADAU5's: Hairer & Wanner, *Solving ODEs II*, §IV.8), (γ/h − J)⁻¹ (f(y0) + Σ e_i z_i / h)
    # with the factored real system of the step itself: one solve instead of the two half steps the step was checked
    # with before (three Newton solves per step; PTS 8 775 Newton iterations for 965 steps).  Its (γ/h − J)⁻¹ is
    # Shampine's filter: at each sample the forcing's slope jumps and the state starts a boundary layer of length
    # ~1/|λ| (s²/40 s) that the L-stable step damps whatever h, and that the unfiltered estimate counts as error
    err = _radau_estimate(tau, v, fv, h, zf, act, na, m, e1, p1, tol, rtol, vnew, raw, rb, mu, mask, c, ka, kb, yw,
                          False, st, fw)
    if err >= 1.0 or tau == 0.0 or not recalled:
        # refused as it stands, or the first step of a sample interval or of a corner: the estimate once more from f
        # at y0 + the estimate (RADAU5's second filtering, which takes out the stiff components the first one leaves
        # in a boundary layer).  Without it at the samples' starts, Christchurch CBGS 0–12 s was 1.1e-9 of the peak
        # from the kernel at rtol 1e-12 instead of 4.9e-10
        err = _radau_estimate(tau, v, fv, h, zf, act, na, m, e1, p1, tol, rtol, vnew, raw, rb, mu, mask, c, ka, kb,
                              yw, True, st, fw)
    if not err < np.inf:
        return False, np.inf
    if err < 1.0:
        jr[0] = valid
    # the memory: this step, keyed on the state the next step will read (the reduced state of ynew)
    mem[RM_PENDING, RM_FLAG] = 1.0
    mem[RM_PENDING, RM_MASK] = mask
    mem[RM_PENDING, RM_H] = h
    if ka >= 0:
        reduce_state(ynew, rb, mask, ka, kb, yp)
    else:
        yp[:] = vnew
    for p in range(m):
        mem[RM_PENDING, RM_KEY + p] = yp[p]
    for q in range(n3):
        mem[RM_PENDING, RM_KEY + m + q] = zf[q]
    # err ~ h⁴: raised to the power 8/4 so that the order-8 step factor of the explicit steps (err^(−1/8)) is the
    # estimate's own (err^(−1/4))
    return True, err * err


#: RADAU5's weights of the embedded estimate, e_i/h on the stage increments z_i (Hairer & Wanner, §IV.8)
_RE = np.array([-(13.0 + 7.0 * _SQ6) / 3.0, (-13.0 + 7.0 * _SQ6) / 3.0, -1.0 / 3.0])


@njit(cache=True)
def _radau_estimate(tau, v, fv, h, z, act, na, m, e1, p1, tol, rtol, vnew, raw, rb, mu, mask, c, ka, kb, yw, again,
                    st, fw):
    """The scaled error of a Radau IIA step by RADAU5's embedded estimate (γ/h − J)⁻¹ (f0 + Σ e_i z_i/h) on the
    active components (``e1``: the step's factored real system; the energies, quadratures, are not checked), over
    EST_SCALE on a reduced corner (of two or three groups); with ``again``, f0 taken at v + the first estimate, which the
    call without ``again`` for this step left in ``fw[W_EST]`` (``fw``: the work rows of :func:`radau_memory`)."""
    est = fw[W_EST]
    w = fw[W_W]
    f0 = fv
    if again:
        yt = fw[W_YT2]
        for p in range(m):
            yt[p] = v[p]
        for q in range(na):
            yt[act[q]] += est[act[q]]
        f0 = fw[W_F0]
        st[ST_RATES] += 1
        if not _rates(tau, yt, raw, rb, mu, mask, c, ka, kb, yw, f0):
            return np.inf
    _radau_raw(v, f0, h, z, act, na, m, e1, p1, est, w)
    err = 0.0
    for q in range(na):
        p = act[q]
        s = tol[p] + rtol * max(abs(v[p]), abs(vnew[p]))
        err += (est[p] / s) ** 2
    return math.sqrt(err / na) / (EST_SCALE if ka >= 0 else 1.0)


@njit(cache=True)
def _radau_raw(v, f0, h, z, act, na, m, e1, p1, est, w):
    # (γ/h − J)⁻¹ (f0 + Σ e_i z_i/h) on the active components of est (w: a work vector of ≥ na)
    for q in range(na):
        w[q] = f0[act[q]] + (_RE[0] * z[q] + _RE[1] * z[na + q] + _RE[2] * z[2 * na + q]) / h
    lu_solve(e1, p1, w)
    for q in range(na):
        est[act[q]] = w[q]


@njit(cache=True)
def corner_step(tau, y, f0, h, raw, rb, mu, mask, c, ynew, fnew, atol, rtol, kk, yt, st, rm):
    """One step of the multi-group state: DOP853, or Radau IIA where the corner is stiff (``corner_implicit``)."""
    if corner_implicit(y, rb, mask):
        return radau_step(tau, y, f0, h, raw, rb, mu, mask, c, ynew, fnew, atol, rtol, st, rm)
    return multi_step(tau, y, f0, h, raw, rb, mu, mask, c, ynew, fnew, atol, rtol, kk, yt)


@njit(cache=True)
def sliding_set(y, rb, cand, must):
    """The sliding groups among the bit set ``cand`` (groups whose circles all pass through r) for the velocity V.

    The rate problem's optimality conditions: with the set S sliding, ṙ = C_S⁻¹ V must give λ_k = R̄_k e_k·ṙ ≥ 0
    for k in S, and must not carry r out of the circle of any other j in cand (e_j·ṙ ≤ 0).  They are those of
    the strictly convex min_ṙ ½ Σ_k R̄_k max(e_k·ṙ, 0)² − V·ṙ, so at most one S of two or more groups
    (spanning normals) meets them; every subset holding the group just reached (bit set ``must``: r crossed its
    circle, so it slides) is tried (≤ 4 groups: ≤ 7 sets).  Returns S, or 0 if none."""
    ng = rb.shape[0]
    v1 = y[M_V]
    v2 = y[M_V + 1]
    best = 0
    for sub in range(1, 1 << ng):
        if sub & ~cand or not sub & must:
            continue
        c11, c12, c22, nb = compliance(y, rb, sub)
        det = c11 * c22 - c12 * c12
        trace = c11 + c22
        if nb < 2 or not det > 1e-24 * trace * trace:
            continue
        rd1 = (c22 * v1 - c12 * v2) / det
        rd2 = (-c12 * v1 + c11 * v2) / det
        scale = math.sqrt(rd1 * rd1 + rd2 * rd2) * 1e-12
        ok = True
        for k in range(ng):
            if cand >> k & 1:
                e1, e2 = _normal(y, rb, k)
                rate = e1 * rd1 + e2 * rd2
                if sub >> k & 1:
                    ok = ok and rate >= -scale
                else:
                    ok = ok and rate <= scale
        if ok:
            best = sub
            break
    return best


@njit(cache=True)
def _normal(y, rb, k):
    # the unit normal e_k = (r − b_k)/|r − b_k| of group k in the multi-group state
    e1 = y[M_R] - y[M_U + 2 * k] / rb[k]
    e2 = y[M_R + 1] - y[M_U + 2 * k + 1] / rb[k]
    en = math.sqrt(e1 * e1 + e2 * e2)
    return e1 / en, e2 / en


@njit(cache=True)
def corner_sine(y, d, rb, mu, ka, kb):
    """Signed sine s = e_a × e_b of a corner of two groups and its rate ṡ (ė_k = (ṙ − ḃ_k)⊥ / µ_k)."""
    a1, a2 = _normal(y, rb, ka)
    b1, b2 = _normal(y, rb, kb)
    da1 = (d[M_R] - d[M_U + 2 * ka] / rb[ka]) / mu[ka]
    da2 = (d[M_R + 1] - d[M_U + 2 * ka + 1] / rb[ka]) / mu[ka]
    db1 = (d[M_R] - d[M_U + 2 * kb] / rb[kb]) / mu[kb]
    db2 = (d[M_R + 1] - d[M_U + 2 * kb + 1] / rb[kb]) / mu[kb]
    # the tangential parts (the radial parts of ė vanish: |e| = 1)
    pa = da1 * a1 + da2 * a2
    pb = db1 * b1 + db2 * b2
    da1 -= pa * a1
    da2 -= pa * a2
    db1 -= pb * b1
    db2 -= pb * b2
    return a1 * b2 - a2 * b1, da1 * b2 - da2 * b1 + a1 * db2 - a2 * db1


@njit(cache=True)
def cross_tangency(tau, dt, y, d, raw, rb, mu, c, ka, kb, rate):
    """Carry a corner of two groups through tangency: its signed sine s passes through 0 at the rate ṡ (finite:
    the corner closes as the path turns, docs/multisurface.md), while its stiffness grows as 1/s².  Over the
    short dt = −2 s/ṡ, X, V and ū_a + ū_b (= X − the stuck ū) advance by their Taylor expansion to second
    order, the energies by the trapezoid rule; the pair's relative geometry is the one before, mirrored about the line of centres (the distance of
    the centres is even in time about the tangency, and r goes to the other intersection of the two circles,
    where the sine is −s), then turned rigidly so that V ∥ R̄_a e_a + R̄_b e_b: the rest state of the corner's
    fast mode (the split of V between the groups, λ_a/R̄_a = λ_b/R̄_b), which relaxes at a rate ∝ 1/s².  ``rate``
    is ṡ before the crossing (the caller's secant over its last step: s is linear in time there, while the
    instantaneous ṡ carries the fast mode's residue ∝ 1/s² of the last step's error)."""
    axx, ayy, nn = _forcing(tau, raw)
    ca1 = y[M_U + 2 * ka] / rb[ka]
    ca2 = y[M_U + 2 * ka + 1] / rb[ka]
    d1 = y[M_U + 2 * kb] / rb[kb] - ca1
    d2 = y[M_U + 2 * kb + 1] / rb[kb] - ca2
    dist = math.sqrt(d1 * d1 + d2 * d2)
    if not dist > 0.0:
        return False
    q1 = y[M_R] - ca1
    q2 = y[M_R + 1] - ca2
    # r − c_a mirrored about the line of centres: |r − c_a| and |r − c_b| unchanged
    along = (q1 * d1 + q2 * d2) / (dist * dist)
    q1 = 2.0 * along * d1 - q1
    q2 = 2.0 * along * d2 - q2
    jerk1 = -nn * d[M_R] - c * d[M_V] - raw[1]
    jerk2 = -nn * d[M_R + 1] - c * d[M_V + 1] - raw[3]
    if raw[5] != 0.0:  # n(t) = g + a_z: −ṅ r too
        jerk1 -= raw[5] * y[M_R]
        jerk2 -= raw[5] * y[M_R + 1]
    dx1 = dt * (d[M_X] + 0.5 * dt * d[M_V])
    dx2 = dt * (d[M_X + 1] + 0.5 * dt * d[M_V + 1])
    y[M_X] += dx1
    y[M_X + 1] += dx2
    y[M_V] += dt * (d[M_V] + 0.5 * dt * jerk1)
    y[M_V + 1] += dt * (d[M_V + 1] + 0.5 * dt * jerk2)
    # the stuck groups stay: ū_a + ū_b moves with X (second order)
    s1 = y[M_U + 2 * ka] + y[M_U + 2 * kb] + dx1
    s2 = y[M_U + 2 * ka + 1] + y[M_U + 2 * kb + 1] + dx2
    w1 = rb[ka] * q1 / mu[ka] + rb[kb] * (q1 - d1) / mu[kb]
    w2 = rb[ka] * q2 / mu[ka] + rb[kb] * (q2 - d2) / mu[kb]
    beta0 = math.atan2(w1 * y[M_V + 1] - w2 * y[M_V], w1 * y[M_V] + w2 * y[M_V + 1])
    # the rest state of the fast mode to first order in s: the turn β at which the sine goes on at the rate it
    # had (s is linear in time through the tangency; β0, the rest state to zeroth order, leaves ṡ ≈ 0 and the
    # fast mode to relax at ~1/s² from there): an Illinois secant on β in a bracket grown from β0
    fd = np.empty(y.shape[0])
    width = 4.0 * abs(s_of(y, rb, ka, kb)) + 1e-12
    lo = beta0 - width
    hi = beta0 + width
    glo = _turned(lo, y, fd, q1, q2, d1, d2, s1, s2, tau + dt, raw, rb, mu, c, ka, kb) - rate
    ghi = _turned(hi, y, fd, q1, q2, d1, d2, s1, s2, tau + dt, raw, rb, mu, c, ka, kb) - rate
    for _ in range(8):
        if glo * ghi < 0.0:
            break
        lo = beta0 - 2.0 * (beta0 - lo)
        hi = beta0 + 2.0 * (hi - beta0)
        glo = _turned(lo, y, fd, q1, q2, d1, d2, s1, s2, tau + dt, raw, rb, mu, c, ka, kb) - rate
        ghi = _turned(hi, y, fd, q1, q2, d1, d2, s1, s2, tau + dt, raw, rb, mu, c, ka, kb) - rate
    beta = beta0
    if glo * ghi < 0.0:
        side = 0
        for _ in range(100):
            beta = (lo * ghi - hi * glo) / (ghi - glo)
            if not (lo < beta < hi):
                beta = 0.5 * (lo + hi)
            gv = _turned(beta, y, fd, q1, q2, d1, d2, s1, s2, tau + dt, raw, rb, mu, c, ka, kb) - rate
            if (gv > 0.0) == (ghi > 0.0):
                hi = beta
                ghi = gv
                if side == 1:
                    glo *= 0.5
                side = 1
            else:
                lo = beta
                glo = gv
                if side == -1:
                    ghi *= 0.5
                side = -1
            if hi - lo <= 1e-15 * (abs(beta) + 1e-12) or gv == 0.0:
                break
    _turned(beta, y, fd, q1, q2, d1, d2, s1, s2, tau + dt, raw, rb, mu, c, ka, kb)
    # the energies by the trapezoid rule on their rates before and after (second order)
    for o in (M_EIN, M_EF, M_EV):
        y[o] += 0.5 * dt * (d[o] + fd[o])
    return abs(beta) < 0.1


@njit(cache=True)
def s_of(y, rb, ka, kb):
    """The signed sine e_a × e_b of a corner of two groups."""
    a1, a2 = _normal(y, rb, ka)
    b1, b2 = _normal(y, rb, kb)
    return a1 * b2 - a2 * b1


@njit(cache=True)
def _turned(beta, y, fd, q1, q2, d1, d2, s1, s2, tau, raw, rb, mu, c, ka, kb):
    # the pair's relative geometry (q = r − c_a, d = c_b − c_a) turned by β and placed with ū_a + ū_b = s; the rate
    # of the corner's sine there
    cs = math.cos(beta)
    sn = math.sin(beta)
    n1 = cs * d1 - sn * d2
    n2 = sn * d1 + cs * d2
    ca1, ca2 = _place_pair(y, rb, ka, kb, s1, s2, n1, n2)
    y[M_R] = ca1 + cs * q1 - sn * q2
    y[M_R + 1] = ca2 + sn * q1 + cs * q2
    if not multi_rhs(tau, y, raw, rb, mu, (1 << ka) | (1 << kb), c, fd):
        return np.nan
    return corner_sine(y, fd, rb, mu, ka, kb)[1]


@njit(cache=True)
def _lambda(y, d, rb, k):
    # λ_k = R̄_k e_k·ṙ of group k in the multi-group state
    e1 = y[M_R] - y[M_U + 2 * k] / rb[k]
    e2 = y[M_R + 1] - y[M_U + 2 * k + 1] / rb[k]
    en = math.sqrt(e1 * e1 + e2 * e2)
    return rb[k] * (e1 * d[M_R] + e2 * d[M_R + 1]) / en


@njit(cache=True)
def _outside(r1, r2, ub, rb, mu, j):
    # |r − b_j|² − µ_j² (> 0: r is outside the friction circle of group j)
    d1 = r1 - ub[j, 0] / rb[j]
    d2 = r2 - ub[j, 1] / rb[j]
    return d1 * d1 + d2 * d2 - mu[j] * mu[j]


@njit(cache=True)
def _set_frc(frc, raw, s1, s2, inv_r):
    # the one-group forcing: a_g* = a_g − (n/R̄) S, so that the planar pendulum is centred at S
    frc[0] = raw[0] - raw[4] * inv_r * s1
    frc[1] = raw[1] - raw[5] * inv_r * s1
    frc[2] = raw[2] - raw[4] * inv_r * s2
    frc[3] = raw[3] - raw[5] * inv_r * s2
    frc[4] = raw[4]
    frc[5] = raw[5]
    frc[6] = 1.0


@njit(cache=True)
def _one_group_r(x1, x2, e1, e2, s, rc, mue):
    # r of the sliding group(s) of a one-group phase: (X − S)/R̄ + µ e.  Groups sliding as one along a
    # collinear motion (s[4] = 1) keep the direction e0 = (s[2], s[3]) of their tangent circles: the
    # direction of a decelerating slide is unstable as |V| → 0 (it sits near −F/|F|) and turns away from
    # the line by the amplified rounding before a stop, which must not enter the groups' state
    if s[4] > 0.0:
        e1 = s[2]
        e2 = s[3]
    return (x1 - s[0]) / rc + mue * e1, (x2 - s[1]) / rc + mue * e2


@njit(cache=True)
def _one_group_settle(ub, comp, x1, x2, e1, e2, s, rc, mue, rb, mu):
    # the groups of a one-group phase at X: ū_k = R̄_k (r − µ_k e)
    r1, r2 = _one_group_r(x1, x2, e1, e2, s, rc, mue)
    if s[4] > 0.0:
        e1 = s[2]
        e2 = s[3]
    for k in range(rb.shape[0]):
        if comp >> k & 1:
            ub[k, 0] = rb[k] * (r1 - mu[k] * e1)
            ub[k, 1] = rb[k] * (r2 - mu[k] * e2)


@njit(cache=True)
def _direction(phase, x, tau, y, prm, frc):
    v1, v2 = velocity(phase, x, tau, y, prm, frc)
    vn = norm(v1, v2)
    if vn > 0.0:
        return v1 / vn, v2 / vn, vn
    return 0.0, 0.0, 0.0


@njit(cache=True)
def _holds(ub, rb, mu, axx, ayy, nn):
    # −a_g/n inside every friction circle (the stuck bearing holds)
    worst = -1.0
    worst_k = -1
    for k in range(rb.shape[0]):
        d1 = -axx / nn - ub[k, 0] / rb[k]
        d2 = -ayy / nn - ub[k, 1] / rb[k]
        ex = math.sqrt(d1 * d1 + d2 * d2) - mu[k]
        if ex > 0.0 and (worst_k < 0 or ex > worst):
            worst = ex
            worst_k = k
    return worst_k


@njit(cache=True)
def _quadratic_roots(qa, qb, qc):
    """The real roots of qa τ² + qb τ + qc (the numerically stable pair; inf where there is none)."""
    c0 = np.inf
    c1 = np.inf
    disc = qb * qb - 4.0 * qa * qc
    if disc >= 0.0:
        sq = math.sqrt(disc)
        if qa != 0.0:
            # the stable pair of roots
            qq = -0.5 * (qb + (sq if qb >= 0.0 else -sq))
            c0 = qq / qa
            c1 = qc / qq if qq != 0.0 else np.inf
        elif qb != 0.0:
            c0 = -qc / qb
    return c0, c1


@njit(cache=True)
def _rim_breakaway(b1, b2, e1, e2, mu, raw, tau0, tau1):
    """First τ in [τ0, τ1] where a group held on its rim (unit outward normal e, back-force b) lets go; -1 if none.

    With w = a_g + n b (linear in τ) the force on the element is d = r − b = −w/n.  The rim carries any outward push
    (d·e ≥ 0, i.e. w·e ≤ 0: the element is held while |d·t| ≤ µ, t the rim's tangent — :func:`rim_holds` of the
    stepper, the optimality of the step's problem at the rim); a pull inward (w·e > 0) is the ordinary friction disc
    |d| ≤ µ.  So the group lets go where f = (w·t)² + max(w·e, 0)² − (µ n)² turns positive: on the branch w·e ≤ 0 the
    first upward root of the quadratic (w·t)² − (µ n)², on w·e > 0 of |w|² − (µ n)² (f is continuous and smooth
    across w·e = 0, where the two agree)."""
    t1 = -e2
    t2 = e1
    w0x = raw[0] + raw[4] * b1
    w1x = raw[1] + raw[5] * b1
    w0y = raw[2] + raw[4] * b2
    w1y = raw[3] + raw[5] * b2
    wt0 = w0x * t1 + w0y * t2
    wt1 = w1x * t1 + w1y * t2
    we0 = w0x * e1 + w0y * e2
    we1 = w1x * e1 + w1y * e2
    we = we0 + we1 * tau0
    n0 = raw[4] + raw[5] * tau0
    wt = wt0 + wt1 * tau0
    if wt * wt + max(we, 0.0) ** 2 > (mu * n0) ** 2:
        return tau0
    root = -1.0
    for branch in range(2):
        # 0: the outward push held (w·e ≤ 0), the tangential part against the friction; 1: a pull inward, all of it
        qa = wt1 * wt1 - (mu * raw[5]) ** 2
        qb = 2.0 * wt0 * wt1 - 2.0 * mu * mu * raw[4] * raw[5]
        qc = wt0 * wt0 - (mu * raw[4]) ** 2
        if branch == 1:
            qa += we1 * we1
            qb += 2.0 * we0 * we1
            qc += we0 * we0
        c0, c1 = _quadratic_roots(qa, qb, qc)
        for tr in (c0, c1):
            on_branch = (we0 + we1 * tr <= 0.0) if branch == 0 else (we0 + we1 * tr >= 0.0)
            if (tau0 <= tr <= tau1 and on_branch and (root < 0.0 or tr < root)
                    and 2.0 * qa * tr + qb >= 0.0):
                root = tr
    return root


@njit(cache=True)
def breakaway(ub, rb, mu, raw, tau0, tau1, held=0):
    """First τ in [τ0, τ1] where −a_g/n leaves a friction circle (a stuck bearing breaks away).

    |a_g + n b_k|² − (µ_k n)² = 0 is a quadratic in τ (a_g and n linear, raw = (a_x, a_x', a_y, a_y',
    n, n')); returns (τ, group) or (-1, -1).  ``held``: the groups (bit k for group k) at rest on their rims, whose
    rim carries the outward push (:func:`_rim_breakaway`); 0 (the event kernel's, and a rest off every rim) is the
    plain test."""
    best = -1.0
    best_k = -1
    for k in range(rb.shape[0]):
        b1 = ub[k, 0] / rb[k]
        b2 = ub[k, 1] / rb[k]
        un = math.sqrt(ub[k, 0] * ub[k, 0] + ub[k, 1] * ub[k, 1])
        if held >> k & 1 and un > 0.0:
            root = _rim_breakaway(b1, b2, ub[k, 0] / un, ub[k, 1] / un, mu[k], raw, tau0, tau1)
            if root >= 0.0 and (best_k < 0 or root < best):
                best = root
                best_k = k
            continue
        w0x = raw[0] + raw[4] * b1
        w1x = raw[1] + raw[5] * b1
        w0y = raw[2] + raw[4] * b2
        w1y = raw[3] + raw[5] * b2
        qa = w1x * w1x + w1y * w1y - (mu[k] * raw[5]) ** 2
        qb = 2.0 * (w0x * w1x + w0y * w1y) - 2.0 * mu[k] * mu[k] * raw[4] * raw[5]
        qc = w0x * w0x + w0y * w0y - (mu[k] * raw[4]) ** 2
        if (qa * tau0 + qb) * tau0 + qc > 0.0:
            root = tau0
        else:
            root = -1.0
            c0, c1 = _quadratic_roots(qa, qb, qc)
            for tr in (c0, c1):
                # an upward crossing inside the stretch: q grows there
                if tau0 <= tr <= tau1 and (root < 0.0 or tr < root) and 2.0 * qa * tr + qb >= 0.0:
                    root = tr
        if root >= 0.0 and (best_k < 0 or root < best):
            best = root
            best_k = k
    return best, best_k


@njit(cache=True)
def _record(ev_t, ev_k, n_ev, t, kind):
    if n_ev < ev_t.shape[0]:
        ev_t[n_ev] = t
        ev_k[n_ev] = kind
    return n_ev + 1


@njit(cache=True)
def _over_rim(ub, rb, rim, comp):
    for k in range(rb.shape[0]):
        if comp >> k & 1 and ub[k, 0] * ub[k, 0] + ub[k, 1] * ub[k, 1] > rim[k] * rim[k]:
            return True
    return False


@njit(cache=True)
def surface_peaks(ub, rb, members, tmat, surf_peak):
    """Raise surf_peak [m] to |u| of every real surface at the groups' displacements ub (u = T ū)."""
    # |u| on every real surface: u = T ū with ū of element i = (R̄_i / R̄_group) ū_group
    ne = members.shape[0]
    for j in range(tmat.shape[0]):
        s1 = 0.0
        s2 = 0.0
        for i in range(ne):
            if tmat[j, i] != 0.0:
                g = int(members[i, 0])
                w = members[i, 1] / rb[g]
                s1 += tmat[j, i] * w * ub[g, 0]
                s2 += tmat[j, i] * w * ub[g, 1]
        v = math.sqrt(s1 * s1 + s2 * s2)
        if v > surf_peak[j]:
            surf_peak[j] = v


@njit(cache=True)
def _groups_moved(my, ub, rb, rim, comp, members, tmat, surf_peak):
    """Copy the groups' displacements ū from the corner state my into ub and raise the surface peaks [m];
    True where a group is past its rim."""
    for k in range(ub.shape[0]):
        ub[k, 0] = my[M_U + 2 * k]
        ub[k, 1] = my[M_U + 2 * k + 1]
    surface_peaks(ub, rb, members, tmat, surf_peak)
    return _over_rim(ub, rb, rim, comp)


@njit(cache=True)
def element_mask(mask, members):
    """The bit set of series elements of a bit set of groups."""
    out = 0
    for i in range(members.shape[0]):
        if mask >> int(members[i, 0]) & 1:
            out |= 1 << i
    return out


@njit(cache=True)
def _corr_xy(x1a, x2a, x1b, x2b, s, rc, raw, ta, tb):
    # the input of a one-group piece from (τ_a, X_a) to (τ_b, X_b) less what the planar steps count there.  They count
    # ∫ (−a_g*·V + ½κ'|X|²) dt with a_g* = a_g − (n/R̄) S and κ = n/R̄; the input is ∫ (−a_g·V + ṅ P) dt with the stored
    # energy per unit n P = P_0 + |X − S|²/(2R̄) (P_0 the stuck groups' and a composite's constant part).  The
    # difference ∫ (−(n/R̄) S·V + ṅ (P_0 + |S|²/(2R̄) − X·S/R̄)) dt integrates exactly (S is constant):
    # −(n_b X_b − n_a X_a)·S/R̄ + (n_b − n_a)(P_0 + |S|²/(2R̄)), the constant in s[5] (_phase_constant)
    if raw[5] == 0.0:
        return -raw[4] / rc * (s[0] * (x1b - x1a) + s[1] * (x2b - x2a))
    na = raw[4] + raw[5] * ta
    nb = raw[4] + raw[5] * tb
    return -(s[0] * (nb * x1b - na * x1a) + s[1] * (nb * x2b - na * x2a)) / rc + (nb - na) * s[5]


@njit(cache=True)
def _phase_constant(s, ub, rb, mu, comp, rc, mue):
    # s[5] = P_0 + |S|²/(2R̄) of a one-group phase (_corr_xy): the stuck groups' Σ|ū_k|²/(2R̄_k), and for groups
    # sliding as one (r − b_k = µ_k e, Σ ū_k = X − S) Σ R̄_k (µ − µ_k)²/2, µ = Σ R̄_k µ_k / R̄ (0 for one group)
    acc = 0.0
    for k in range(rb.shape[0]):
        if comp >> k & 1:
            acc += 0.5 * rb[k] * (mue - mu[k]) ** 2
        else:
            acc += (ub[k, 0] ** 2 + ub[k, 1] ** 2) / (2.0 * rb[k])
    s[5] = acc + (s[0] * s[0] + s[1] * s[1]) / (2.0 * rc)


@njit(cache=True)
def _slaved(tau, y, prm, frc):
    # the direction of a START-form velocity (slaved to F)
    _, _, nn, kap, kdot, fx, fy = forcing(tau, y[0], y[1], prm, frc)
    return start_direction(abs(y[2]), y[0], y[1], fx, fy, kap, kdot, frc, prm[P_MU_K] * nn, prm[P_C])


@njit(cache=True)
def _r_of(mode, xv, yv, prm, frc, s, rc, mue):
    # r = F/(M n) of the sliding group(s) in a one-group form at independent variable xv
    if mode == LOG or mode == POLAR:
        e1 = yv[2]
        e2 = yv[3]
    elif mode == CARTESIAN:
        vn = norm(yv[2], yv[3])
        e1 = yv[2] / vn if vn > 0.0 else 0.0
        e2 = yv[3] / vn if vn > 0.0 else 0.0
    else:
        e1, e2 = _slaved(xv, yv, prm, frc)
    return _one_group_r(yv[0], yv[1], e1, e2, s, rc, mue)


@njit(cache=True)
def _joins_in_step(mode, x, y, f, h, theta_max, prm, frc, yb, fb, atol, rtol, s, rc, mue, ub, rb, mu, comp, ynew,
                   fnew):
    """The first group whose friction circle the sliding group's r reaches inside a step: (θ, group) or (2, -1).

    Illinois secant on g(θ) = |r − b_j|² − µ_j² of DOP853 sub-steps from the step start, to 1e-13 of the step.
    """
    best = 2.0
    best_k = -1
    for j in range(rb.shape[0]):
        if comp >> j & 1:
            continue
        r1, r2 = _r_of(mode, x + h, ynew, prm, frc, s, rc, mue)
        g1 = _outside(r1, r2, ub, rb, mu, j)
        if not g1 > 0.0:
            continue
        r1, r2 = _r_of(mode, x, y, prm, frc, s, rc, mue)
        g0 = _outside(r1, r2, ub, rb, mu, j)
        lo = 0.0
        hi = 1.0
        glo = min(g0, 0.0)
        ghi = g1
        side = 0
        th = 1.0
        for _ in range(80):
            th = (lo * ghi - hi * glo) / (ghi - glo) if ghi != glo else 0.5 * (lo + hi)
            if not (lo < th < hi):
                th = 0.5 * (lo + hi)
            dop853_step(mode, x, y, f, th * h, prm, frc, yb, fb, atol, rtol)
            r1, r2 = _r_of(mode, x + th * h, yb, prm, frc, s, rc, mue)
            gv = _outside(r1, r2, ub, rb, mu, j)
            if gv > 0.0:
                hi = th
                ghi = gv
                if side == 1:
                    glo *= 0.5
                side = 1
            else:
                lo = th
                glo = gv
                if side == -1:
                    ghi *= 0.5
                side = -1
            if hi - lo <= 1e-13:
                break
        if hi < best and hi <= theta_max:
            best = hi
            best_k = j
    return best, best_k


#: the re-steps' secant on θ stops where its bracket is this narrow (in units of the step), or after so many re-steps:
#: an event (a group leaving or joining) and a peak of |X| or |V| inside a multi-group step
LOCATE_BRACKET = 1e-13
LOCATE_RESTEPS = 80
PEAK_BRACKET = 1e-12
PEAK_RESTEPS = 60
#: what a re-step's secant follows (:func:`_restep_value`)
RS_LEAVE = 0
RS_JOIN = 1
RS_PEAK = 2


@njit(cache=True)
def _restep_value(what, k, o, myb, mfb, rb, mu, ub):
    """The function whose sign change the re-steps locate, at a re-step's end (myb, mfb): RS_LEAVE −λ_k (group k
    leaves where it turns positive), RS_JOIN group k's circle reached (:func:`_outside`), RS_PEAK the rate of
    |y[o:o+2]|²/2 (a peak of |X| or |V| where it turns negative)."""
    if what == RS_LEAVE:
        return -_lambda(myb, mfb, rb, k)
    if what == RS_JOIN:
        return _outside(myb[M_R], myb[M_R + 1], ub, rb, mu, k)
    return myb[o] * mfb[o] + myb[o + 1] * mfb[o + 1]


@njit(cache=True)
def _secant_resteps(what, k, o, glo, ghi, rising, bracket, n_max, tau, my, mf, h, raw, rb, mu, comp, c, myb, mfb,
                    matol, rtol, kk, yt, st, rm, ub):
    """Illinois secant on the fraction θ ∈ (0, 1) of a multi-group step where :func:`_restep_value` changes sign
    (``glo``, ``ghi``: its values at θ = 0 and 1; ``rising``: from ≤ 0 to > 0, else from > 0 to ≤ 0), each value from
    a re-step of θh from the step's start (DOP853 or Radau IIA, :func:`corner_step`); at most ``n_max`` re-steps,
    until the bracket is ``bracket`` wide.  (θ at the bracket's far end, the largest |y[o:o+2]| over the re-steps'
    ends: RS_PEAK only.)  The one loop of the event location and the peaks (h186: written twice before)."""
    lo = 0.0
    hi = 1.0
    best = 0.0
    side = 0
    for _ in range(n_max):
        th = (lo * ghi - hi * glo) / (ghi - glo) if ghi != glo else 0.5 * (lo + hi)
        if not (lo < th < hi):
            th = 0.5 * (lo + hi)
        st[ST_RESTEP] += 1
        corner_step(tau, my, mf, th * h, raw, rb, mu, comp, c, myb, mfb, matol, rtol, kk, yt, st, rm)
        if what == RS_PEAK:
            best = max(best, norm(myb[o], myb[o + 1]))
        gv = _restep_value(what, k, o, myb, mfb, rb, mu, ub)
        if (gv > 0.0) == rising:
            hi = th
            ghi = gv
            if side == 1:
                glo *= 0.5
            side = 1
        else:
            lo = th
            glo = gv
            if side == -1:
                ghi *= 0.5
            side = -1
        if hi - lo <= bracket:
            break
    return hi, best


@njit(cache=True)
def _locate_multi(kind, k, tau, my, mf, h, raw, rb, mu, comp, c, myb, mfb, matol, rtol, kk, yt, st, rm):
    """Fraction θ of a multi-group step where group k leaves (kind 0: λ_k = 0) or joins (kind 1); 0 where it does
    at the step's start."""
    ng = rb.shape[0]
    ub = np.empty((ng, 2))
    for q in range(ng):
        ub[q, 0] = my[M_U + 2 * q]
        ub[q, 1] = my[M_U + 2 * q + 1]
    what = RS_LEAVE if kind == 0 else RS_JOIN
    g0 = _restep_value(what, k, 0, my, mf, rb, mu, ub)
    if g0 >= 0.0:
        return 0.0
    st[ST_RESTEP] += 1
    corner_step(tau, my, mf, h, raw, rb, mu, comp, c, myb, mfb, matol, rtol, kk, yt, st, rm)
    ghi = _restep_value(what, k, 0, myb, mfb, rb, mu, ub)
    hi, _ = _secant_resteps(what, k, 0, g0, ghi, True, LOCATE_BRACKET, LOCATE_RESTEPS, tau, my, mf, h, raw, rb, mu,
                            comp, c, myb, mfb, matol, rtol, kk, yt, st, rm, ub)
    return hi


@njit(cache=True)
def _multi_peak(o, tau, my, mf, h, g0, g1, raw, rb, mu, comp, c, myb, mfb, matol, rtol, kk, yt, st, rm):
    """Largest |y[o:o+2]| inside a multi-group step where its rate goes from + to −: Illinois secant on
    the rate of its square over re-steps (:func:`_secant_resteps`)."""
    _, best = _secant_resteps(RS_PEAK, -1, o, g0, g1, False, PEAK_BRACKET, PEAK_RESTEPS, tau, my, mf, h, raw, rb, mu,
                              comp, c, myb, mfb, matol, rtol, kk, yt, st, rm, np.empty((0, 2)))
    return best


@njit(cache=True)
def _closing_corner(my, rb, comp):
    """The common normal of the sliding groups when all their normals lie within CLOSE_ANGLE, else (0, 0)."""
    f1 = 0.0
    f2 = 0.0
    first_k = True
    for k in range(rb.shape[0]):
        if comp >> k & 1:
            e1 = my[M_R] - my[M_U + 2 * k] / rb[k]
            e2 = my[M_R + 1] - my[M_U + 2 * k + 1] / rb[k]
            en = math.sqrt(e1 * e1 + e2 * e2)
            e1 /= en
            e2 /= en
            if first_k:
                f1 = e1
                f2 = e2
                first_k = False
            elif abs(f1 * e2 - f2 * e1) > CLOSE_ANGLE or f1 * e1 + f2 * e2 < 0.0:
                return 0.0, 0.0
    return f1, f2


@njit(cache=True)
def _join(kj, phase, x, tau, y, f, prm, frc, raw, s, rc, mue, comp, ub, rb, mu, my, mf, c):
    """Group kj joins the sliding group(s) of a one-group phase: a composite along a collinear motion, else
    the multi-group state.  Returns (phase, comp, rc, mue)."""
    mode = START if phase == PH_START else (LOG if phase == PH_APPROACH else (
        POLAR if phase == PH_POLAR else CARTESIAN))
    r1, r2 = _r_of(mode, x, y, prm, frc, s, rc, mue)
    if mode == LOG or mode == POLAR:
        e1 = y[2]
        e2 = y[3]
    elif mode == CARTESIAN:
        vn = norm(y[2], y[3])
        e1 = y[2] / vn
        e2 = y[3] / vn
    else:
        e1, e2 = _slaved(tau, y, prm, frc)
    _one_group_settle(ub, comp, y[0], y[1], e1, e2, s, rc, mue, rb, mu)
    if s[4] > 0.0:
        e1 = s[2]
        e2 = s[3]
    d1 = r1 - ub[kj, 0] / rb[kj]
    d2 = r2 - ub[kj, 1] / rb[kj]
    dn = math.sqrt(d1 * d1 + d2 * d2)
    cross = abs(e1 * d2 - e2 * d1) / dn
    comp |= 1 << kj
    if cross < MERGE_ANGLE and e1 * d1 + e2 * d2 > 0.0:
        # tangent circles along the motion: one pendulum of the summed compliance
        if s[4] == 0.0:
            s[2] = e1
            s[3] = e2
            s[4] = 1.0
        rc = 0.0
        rmu = 0.0
        s[0] = y[0]
        s[1] = y[1]
        for k in range(rb.shape[0]):
            if comp >> k & 1:
                rc += rb[k]
                rmu += rb[k] * mu[k]
                s[0] -= ub[k, 0]
                s[1] -= ub[k, 1]
        mue = rmu / rc
        prm[P_MU_S] = mue
        prm[P_MU_K] = mue
        prm[P_INV_R] = 1.0 / rc
        _set_frc(frc, raw, s[0], s[1], 1.0 / rc)
        rhs(mode, x, y, prm, frc, f)
        return phase, comp, rc, mue
    v1, v2 = velocity(phase, x, tau, y, prm, frc)
    my[M_X] = y[0]
    my[M_X + 1] = y[1]
    my[M_V] = v1
    my[M_V + 1] = v2
    my[M_R] = r1
    my[M_R + 1] = r2
    for k in range(rb.shape[0]):
        my[M_U + 2 * k] = ub[k, 0]
        my[M_U + 2 * k + 1] = ub[k, 1]
    # the rate problem's set among the sliding groups and the one reached
    chosen = sliding_set(my, rb, comp, 1 << kj)
    if chosen != 0:
        comp = chosen
    multi_rhs(tau, my, raw, rb, mu, comp, c, mf)
    return PH_MULTI, comp, rc, mue


@njit(cache=True)
def _at_rest(tau, t0, y, e1, e2, f, prm, frc, raw, s, rc, mue, comp, ub, rb, mu, ev_t, ev_k, n_ev, e_in, e_f, e_v,
             ein_corr, members, tmat, surf_peak, first):
    """The mass is at rest at X = y[0:2] (its last direction e): settle the groups, then stick or restart."""
    e_in += y[4] + ein_corr
    e_f += y[5]
    e_v += y[6]
    _one_group_settle(ub, comp, y[0], y[1], e1, e2, s, rc, mue, rb, mu)
    surface_peaks(ub, rb, members, tmat, surf_peak)
    axx, ayy, nn = _forcing(tau, raw)
    k = _holds(ub, rb, mu, axx, ayy, nn)
    x1 = y[0]
    x2 = y[1]
    y[:] = 0.0
    y[0] = x1
    y[1] = x2
    if k < 0:
        return PH_STUCK, 0, rc, mue, _record(ev_t, ev_k, n_ev, t0 + tau, np.int64(EV_STICK)), e_in, e_f, e_v
    comp = 1 << k
    rc = rb[k]
    mue = mu[k]
    s[0] = x1 - ub[k, 0]
    s[1] = x2 - ub[k, 1]
    s[4] = 0.0
    prm[P_MU_S] = mue
    prm[P_MU_K] = mue
    prm[P_INV_R] = 1.0 / rc
    _set_frc(frc, raw, s[0], s[1], 1.0 / rc)
    rhs(np.int64(START), tau, y, prm, frc, f)
    em = element_mask(comp, members)
    if first[em] < 0.0:
        first[em] = t0 + tau
    return PH_START, comp, rc, mue, _record(ev_t, ev_k, n_ev, t0 + tau, np.int64(EV_REVERSAL)), e_in, e_f, e_v


@njit(cache=True)
def planar_multisurface_kernel(t, ax, ay, nz, rb, mu, rim, members, tmat, c, scales, rtol,
                               out_x, out_v, out_a, out_en, ev_t, ev_k, summary, surf_peak, first, ub, stats):
    """Response of a mass on a multi-surface bearing to a piecewise-linear pair of components.

    Parameters
    ----------
    t : float64[n]
        Sample times [s] from 0, strictly increasing.
    ax, ay : float64[n]
        Ground acceleration [m/s²].
    nz : float64[n]
        n = g + a_z [m/s²] (g without a vertical record).
    rb, mu, rim : float64[ng]
        Per group: R̄ [m] (summed over its elements), µ [-], rim on |ū| [m].
    members : float64[ne, 2]
        Per series element: its group and its R̄ [m].
    tmat : float64[ns, ne]
        Real surfaces from the elements (u = T ū).
    c : float
        Damping per unit mass [1/s].
    scales : float64[5] or float64[6]
        Speed and tolerance scales (SC_*); an optional sixth, SC_EXACT_ONLY > 0, stops the run at the first
        reduction exact only for a collinear record (STATUS_REDUCED); an optional seventh, SC_R_TOL, the force
        point's scale in the corner steps' error norm (default µ_max).
    rtol : float
        Relative tolerance of the DOP853 steps.
    out_x, out_v, out_a : float64[n, 2]
        X [m], V [m/s], transmitted acceleration −n r − cV [m/s²] at the samples.
    out_en : float64[3, n]
        Cumulative input, friction and viscous energy [J/kg].
    ev_t, ev_k : arrays
        Events (time, kind) while room lasts.
    summary : float64[S_SIZE]
    surf_peak : float64[ns]
        Largest |u| per real surface (effective geometry) at step ends [m].
    first : float64[2**ne]
        First time each set of sliding elements was entered [s] (-1: never).
    ub : float64[ng, 2]
        Group displacements (in: zero; out: the final state) [m].
    stats : int64[ST_SIZE]
        Work counters of the multi-group steps (ST_*), added to.
    """
    n = t.shape[0]
    ng = rb.shape[0]
    nm = M_U + 2 * ng
    y = np.zeros(NSTATE)
    f = np.zeros(NSTATE)
    ynew = np.zeros(NSTATE)
    fnew = np.zeros(NSTATE)
    yb = np.zeros(NSTATE)
    fb = np.zeros(NSTATE)
    atol = np.full(NSTATE, np.inf)
    my = np.zeros(nm)
    mf = np.zeros(nm)
    mynew = np.zeros(nm)
    mfnew = np.zeros(nm)
    myb = np.zeros(nm)
    mfb = np.zeros(nm)
    matol = np.full(nm, np.inf)
    kk = np.zeros((_NS + 1, nm))
    rm = radau_memory(nm)  #: the implicit steps' memory and work arrays (radau_step)
    yt = np.zeros(nm)
    frc = np.zeros(7)
    work = np.zeros(2)
    raw = np.zeros(6)
    prm = np.zeros(P_SIZE)
    prm[P_PENDULUM] = 1.0
    prm[P_C] = c
    s = np.zeros(6)  #: centre S of a one-group phase [m], direction e0 and flag of a collinear one (see _one_group_r),
    #: and the constant of its input's correction under a vertical (_corr_xy)
    for j in range(first.shape[0]):
        first[j] = -1.0
    phase = np.int64(PH_STUCK)
    comp = np.int64(0)  #: the sliding groups (bit set)
    rc = 1.0
    mue = 0.0
    x = 0.0
    h_sugg = -1.0
    ds_sugg = -0.5
    r_min = scales[SC_R_MIN]
    r_switch = scales[SC_R_SWITCH]
    r_switch_lo = scales[SC_R_SWITCH_LO]
    r_floor = r_min * R_FLOOR_FRACTION
    s_end = math.log(r_min)
    s_floor = math.log(r_floor)
    s_stop = s_end
    peak_x = 0.0
    peak_v = 0.0
    peak_a = norm(ax[0], ay[0])
    slip = 0.0
    n_ev = np.int64(0)
    status = 0
    n_steps = 0
    n_rej = 0
    n_multi = 0
    n_merged = 0
    exact_only = scales.shape[0] > SC_EXACT_ONLY and scales[SC_EXACT_ONLY] > 0.0
    r_scale = 0.0  #: the force point's scale in the corner steps' error norm (SC_R_TOL) [W]
    if scales.shape[0] > SC_R_TOL and scales[SC_R_TOL] > 0.0:
        r_scale = scales[SC_R_TOL]
    else:
        for k in range(ng):
            r_scale = max(r_scale, mu[k])
    if not r_scale > 0.0:
        r_scale = 1e-3
    just_rejected = False
    e_in = 0.0  #: energies of the phases already closed [J/kg]
    e_f = 0.0
    e_v = 0.0
    ein_corr = 0.0  #: −∫(n/R̄) S·V dt of the current one-group phase (y[4] counts the work of a_g*)
    fail_t = -1.0
    out_x[0, 0] = 0.0
    out_x[0, 1] = 0.0
    out_v[0, 0] = 0.0
    out_v[0, 1] = 0.0
    out_a[0, 0] = ax[0]
    out_a[0, 1] = ay[0]
    out_en[0, 0] = 0.0
    out_en[1, 0] = 0.0
    out_en[2, 0] = 0.0
    X1 = 0.0  #: X of a stuck bearing
    X2 = 0.0
    failed = False
    for i in range(n - 1):
        hi = t[i + 1] - t[i]
        inv_hi = 1.0 / hi
        raw[0] = ax[i]
        raw[1] = (ax[i + 1] - ax[i]) * inv_hi
        raw[2] = ay[i]
        raw[3] = (ay[i + 1] - ay[i]) * inv_hi
        raw[4] = nz[i]
        raw[5] = (nz[i + 1] - nz[i]) * inv_hi
        if phase == PH_STUCK and _holds(ub, rb, mu, ax[i], ay[i], nz[i]) < 0 and _holds(
                ub, rb, mu, ax[i + 1], ay[i + 1], nz[i + 1]) < 0:
            # |a_g + n b| − µ n is convex in τ: held at both ends, held throughout
            if nz[i + 1] != nz[i]:  # the work of the vertical motion on the stored energy n Σ|ū_k|²/(2R̄_k)
                e_in += (nz[i + 1] - nz[i]) * stored_groups(ub, rb)
            out_x[i + 1, 0] = X1
            out_x[i + 1, 1] = X2
            out_v[i + 1, 0] = 0.0
            out_v[i + 1, 1] = 0.0
            out_a[i + 1, 0] = ax[i + 1]
            out_a[i + 1, 1] = ay[i + 1]
            out_en[0, i + 1] = e_in
            out_en[1, i + 1] = e_f
            out_en[2, i + 1] = e_v
            peak_a = max(peak_a, norm(ax[i + 1], ay[i + 1]))
            continue
        tau = 0.0
        if phase == PH_APPROACH:
            y[7] = 0.0
        elif phase != PH_STUCK:
            x = 0.0
        if phase != PH_STUCK and phase != PH_MULTI:
            _set_frc(frc, raw, s[0], s[1], 1.0 / rc)
            rhs(START if phase == PH_START else (LOG if phase == PH_APPROACH else (
                POLAR if phase == PH_POLAR else CARTESIAN)), x, y, prm, frc, f)
        elif phase == PH_MULTI:
            multi_rhs(0.0, my, raw, rb, mu, comp, c, mf)
        events_here = 0
        steps_here = 0
        while tau < hi:
            steps_here += 1
            if steps_here > MAX_STEPS_PER_INTERVAL:
                status |= STATUS_STEP_LIMIT
                fail_t = t[i] + tau
                failed = True
                break
            if events_here > MAX_EVENTS_PER_INTERVAL:
                status |= STATUS_CHATTER
                fail_t = t[i] + tau
                failed = True
                break
            if exact_only and phase == PH_MULTI and steps_here > MAX_STIFF_STEPS_PER_INTERVAL:
                status |= STATUS_STIFF
                fail_t = t[i] + tau
                failed = True
                break
            target = hi
            # ------------------------------------------------------------------ stuck
            if phase == PH_STUCK:
                tb, kb = breakaway(ub, rb, mu, raw, tau, target)
                if raw[5] != 0.0:  # the work of the vertical motion while stuck (as above)
                    e_in += raw[5] * ((target if kb < 0 else tb) - tau) * stored_groups(ub, rb)
                if kb < 0:
                    tau = target
                    break
                axx, ayy, nn = _forcing(tb, raw)
                kx = _holds(ub, rb, mu, axx, ayy, nn)
                if kx >= 0:
                    # the circle −a_g/n is furthest outside (a record that starts beyond several)
                    kb = kx
                peak_a = max(peak_a, norm(ax[i] + raw[1] * tau, ay[i] + raw[3] * tau), norm(axx, ayy))
                tau = tb
                comp = 1 << kb
                rc = rb[kb]
                mue = mu[kb]
                s[0] = X1 - ub[kb, 0]
                s[1] = X2 - ub[kb, 1]
                s[4] = 0.0
                prm[P_MU_S] = mue
                prm[P_MU_K] = mue
                prm[P_INV_R] = 1.0 / rc
                _phase_constant(s, ub, rb, mu, comp, rc, mue)
                _set_frc(frc, raw, s[0], s[1], 1.0 / rc)
                y[:] = 0.0
                y[0] = X1
                y[1] = X2
                y[4] = 0.0
                ein_corr = 0.0
                x = tau
                phase = np.int64(PH_START)
                rhs(np.int64(START), tau, y, prm, frc, f)
                n_ev = _record(ev_t, ev_k, n_ev, t[i] + tau, np.int64(EV_BREAKAWAY))
                em = element_mask(comp, members)
                if first[em] < 0.0:
                    first[em] = t[i] + tau
                events_here += 1
                h_sugg = 0.01 * hi
                continue
            # ------------------------------------------------------------------ several groups
            if phase == PH_MULTI:
                vmag = norm(my[M_V], my[M_V + 1])
                if vmag < r_switch_lo:
                    # too slow for the corner (the cone of the sliding directions closes on a stop): the
                    # group with the largest share goes on alone (the one-group forms locate the stop); an
                    # approximation, counted with the merges
                    n_merged += 1
                    if exact_only:
                        status |= STATUS_REDUCED
                        fail_t = t[i] + tau
                        failed = True
                        break
                    best = -1.0
                    kb = np.int64(-1)
                    for k in range(ng):
                        if comp >> k & 1:
                            lam = _lambda(my, mf, rb, k)
                            if lam > best:
                                best = lam
                                kb = k
                    for k in range(ng):
                        ub[k, 0] = my[M_U + 2 * k]
                        ub[k, 1] = my[M_U + 2 * k + 1]
                    e_in += my[M_EIN]
                    e_f += my[M_EF]
                    e_v += my[M_EV]
                    comp = 1 << kb
                    rc = rb[kb]
                    mue = mu[kb]
                    s[0] = my[M_X] - ub[kb, 0]
                    s[1] = my[M_X + 1] - ub[kb, 1]
                    s[4] = 0.0
                    prm[P_MU_S] = mue
                    prm[P_MU_K] = mue
                    prm[P_INV_R] = 1.0 / rc
                    _phase_constant(s, ub, rb, mu, comp, rc, mue)
                    _set_frc(frc, raw, s[0], s[1], 1.0 / rc)
                    y[:] = 0.0
                    y[0] = my[M_X]
                    y[1] = my[M_X + 1]
                    x = tau
                    ein_corr = 0.0
                    if vmag > 0.0:
                        y[2] = my[M_V]
                        y[3] = my[M_V + 1]
                        phase = np.int64(PH_SLIDE)
                        rhs(np.int64(CARTESIAN), tau, y, prm, frc, f)
                    else:
                        phase = np.int64(PH_START)
                        rhs(np.int64(START), tau, y, prm, frc, f)
                    n_ev = _record(ev_t, ev_k, n_ev, t[i] + tau, np.int64(EV_LEAVE))
                    events_here += 1
                    continue
                hmax = target - tau
                h = hmax if (h_sugg <= 0.0 or h_sugg >= hmax) else h_sugg
                for j in range(2):
                    matol[M_X + j] = rtol * max(peak_x, scales[SC_X_FLOOR])
                    matol[M_V + j] = rtol * max(peak_v, scales[SC_V_FLOOR])
                    matol[M_R + j] = rtol * r_scale
                for k in range(ng):
                    matol[M_U + 2 * k] = matol[M_X]
                    matol[M_U + 2 * k + 1] = matol[M_X]
                etol = rtol * max(abs(my[M_EIN]) + my[M_EF] + my[M_EV], scales[SC_V_FLOOR] ** 2)
                matol[M_EIN] = etol
                matol[M_EF] = etol
                matol[M_EV] = etol
                implicit = corner_implicit(my, rb, comp)
                stats[ST_RADAU_MAIN if implicit else ST_DOP_MAIN] += 1
                ok, err = corner_step(tau, my, mf, h, raw, rb, mu, comp, c, mynew, mfnew, matol, rtol, kk, yt, stats, rm)
                n_steps += 1
                n_multi += 1
                if not ok or err > 1.0:
                    n_rej += 1
                    stats[(ST_REF_NEWTON if not ok else ST_REF_ERROR) if implicit else ST_REF_DOP] += 1
                    h_sugg = h * (0.25 if not ok else step_factor(err))
                    if implicit and just_rejected:
                        # refused again: at a sample the forcing's slope jumps and the corner's fast mode starts a
                        # boundary layer, in which the implicit steps' estimate does not fall as h⁶ (it rose from
                        # 1.8 to 4.4 while h fell from 5.4e-3 to 1.7e-3 s: PTS, ten refusals at one sample)
                        h_sugg = min(h_sugg, REFUSED_AGAIN * h)
                    just_rejected = True
                    if h_sugg < 1e-14 * hi:
                        status |= STATUS_SINGULAR
                        fail_t = t[i] + tau
                        failed = True
                        break
                    continue
                # events inside the step: a sliding group's λ reaching 0, a stuck one's circle reached
                theta = 2.0
                kind = -1
                which = -1
                for k in range(ng):
                    if comp >> k & 1:
                        if _lambda(mynew, mfnew, rb, k) < 0.0:
                            th = _locate_multi(0, k, tau, my, mf, h, raw, rb, mu, comp, c, myb, mfb, matol, rtol,
                                               kk, yt, stats, rm)
                            if th < theta:
                                theta = th
                                kind = EV_LEAVE
                                which = k
                    else:
                        for q in range(2):
                            ub[k, q] = my[M_U + 2 * k + q]
                        if _outside(mynew[M_R], mynew[M_R + 1], ub, rb, mu, k) > 0.0:
                            th = _locate_multi(1, k, tau, my, mf, h, raw, rb, mu, comp, c, myb, mfb, matol, rtol,
                                               kk, yt, stats, rm)
                            if th < theta:
                                theta = th
                                kind = EV_JOIN
                                which = k
                if kind >= 0 and theta > 0.0:
                    stats[ST_RESTEP] += 1
                    ok2, _ = corner_step(tau, my, mf, theta * h, raw, rb, mu, comp, c, myb, mfb, matol, rtol,
                                        kk, yt, stats, rm)
                    if not ok2:
                        # the re-step to the event refused (Radau IIA's Newton or a singular stage): myb is not its
                        # end but a state of another θ (h186 (c): it was handed on as the step's end).  The step is
                        # refused as a whole and retaken at a quarter of the event's fraction, so the event falls into
                        # a later step; a step that keeps shrinking meets the main steps' floor (STATUS_SINGULAR) or
                        # MAX_STEPS_PER_INTERVAL
                        stats[ST_REF_NEWTON if implicit else ST_REF_DOP] += 1
                        n_rej += 1
                        just_rejected = True
                        h_sugg = 0.25 * theta * h
                        continue
                    mynew[:] = myb
                    mfnew[:] = mfb
                    h = theta * h
                elif kind >= 0:
                    # the event at the step's start (θ = 0: a group that joined with its λ already negative leaves at
                    # once, PTS at rtol 1e-5, 5.718 s: a corner of three groups, two normals parallel to rounding):
                    # the state is the start's.  Before (h186), a re-step of length 0 here reached the Radau matrix's
                    # division by h (h178 made it refuse), and the refused re-step's stale myb (a state of another
                    # θ) was taken as the step's end
                    mynew[:] = my
                    mfnew[:] = mf
                    h = 0.0
                for wp in range(2):
                    o = M_X if wp == 0 else M_V
                    g0 = my[o] * mf[o] + my[o + 1] * mf[o + 1]
                    g1 = mynew[o] * mfnew[o] + mynew[o + 1] * mfnew[o + 1]
                    v0 = norm(my[o], my[o + 1])
                    v1 = norm(mynew[o], mynew[o + 1])
                    if g0 > 0.0 >= g1 and tangent_bound(v0, g0 / max(v0, 1e-300), v1, g1 / max(v1, 1e-300), h) > (
                            peak_x if wp == 0 else peak_v):
                        best = _multi_peak(o, tau, my, mf, h, g0, g1, raw, rb, mu, comp, c, myb, mfb, matol, rtol,
                                           kk, yt, stats, rm)
                        if wp == 0:
                            peak_x = max(peak_x, best)
                        else:
                            peak_v = max(peak_v, best)
                tau = target if (kind < 0 and h == hmax) else tau + h
                slip += h
                pa, pb = _corner_pair(comp, ng)
                s_prev = s_of(my, rb, pa, pb) if pa >= 0 else 0.0
                my[:] = mynew
                mf[:] = mfnew
                peak_x = max(peak_x, norm(my[M_X], my[M_X + 1]))
                peak_v = max(peak_v, norm(my[M_V], my[M_V + 1]))
                peak_a = max(peak_a, norm(mf[M_V] + ax[i] + raw[1] * tau, mf[M_V + 1] + ay[i] + raw[3] * tau))
                if _groups_moved(my, ub, rb, rim, comp, members, tmat, surf_peak):
                    status |= STATUS_RIM
                    fail_t = t[i] + tau
                    failed = True
                    break
                if kind < 0:
                    fac = step_factor(err)
                    if just_rejected:
                        fac = min(1.0, fac)
                    h_sugg = h * fac
                    just_rejected = False
                    ka = np.int64(-1)
                    kb = np.int64(-1)
                    nact = 0
                    for k in range(ng):
                        if comp >> k & 1:
                            nact += 1
                            if ka < 0:
                                ka = k
                            else:
                                kb = k
                    if nact == 2:
                        # a corner of two groups closing to tangency (its sine s falling at a finite rate) is
                        # stepped over: the circles become tangent in finite time, where C is singular
                        sn, snd = corner_sine(my, mf, rb, mu, ka, kb)
                        if h > 0.0 and 0.0 < abs(s_prev) < IMPLICIT_ANGLE:
                            # the secant over the step (the implicit steps' end state carries the fast mode's
                            # residue, which ṡ sees ∝ 1/s²: PTS at 5.6594 s, ṡ −3.26 along the approach, −2.9 to
                            # +6.6 at its last steps' ends): s is linear in time here
                            snd = (sn - s_prev) / h
                            # the Jacobian of the corner's fast mode goes as 1/s²: a step that changes s by more than
                            # CLOSING_STEP (OPENING_STEP) of itself leaves it too far from the step's start for the
                            # simplified Newton, which then fails (PTS: 470 of 2 931 implicit steps refused so)
                            if snd != 0.0:
                                h_sugg = min(h_sugg, (CLOSING_STEP if sn * snd < 0.0 else OPENING_STEP) * abs(sn / snd))
                        if abs(sn) < CROSS_ANGLE and sn * snd < 0.0 and tau - 2.0 * sn / snd < hi:
                            dcr = -2.0 * sn / snd
                            myb[:] = my
                            if not cross_tangency(tau, dcr, myb, mf, raw, rb, mu, c, ka, kb, snd):
                                # the landing turn found no rest state of the fast mode near V
                                status |= STATUS_SINGULAR
                                fail_t = t[i] + tau
                                failed = True
                                break
                            # a stuck group's circle reached inside the crossing would be joined late, with r off it
                            # by the overshoot (Christchurch CBGS at 19.81 s: 1.25e-6, the balance then leaking to
                            # 4.6e-7 of the input): the corner steps go on instead, and locate that join
                            missed = False
                            for k in range(ng):
                                if not comp >> k & 1 and _outside(myb[M_R], myb[M_R + 1], ub, rb, mu, k) > 0.0:
                                    missed = True
                            if not missed:
                                my[:] = myb
                                tau += dcr
                                slip += dcr
                                multi_rhs(tau, my, raw, rb, mu, comp, c, mf)
                                peak_x = max(peak_x, norm(my[M_X], my[M_X + 1]))
                                peak_v = max(peak_v, norm(my[M_V], my[M_V + 1]))
                                if _groups_moved(my, ub, rb, rim, comp, members, tmat, surf_peak):
                                    status |= STATUS_RIM
                                    fail_t = t[i] + tau
                                    failed = True
                                    break
                                continue
                    e01, e02 = _closing_corner(my, rb, comp)
                    if e01 != 0.0 or e02 != 0.0:
                        # the corner closes (a motion that straightens: the circles approach tangency, where the
                        # corner's dynamics is stiff): the groups slide on as one along their common normal
                        e_in += my[M_EIN]
                        e_f += my[M_EF]
                        e_v += my[M_EV]
                        rc = 0.0
                        rmu = 0.0
                        s[0] = my[M_X]
                        s[1] = my[M_X + 1]
                        for k in range(ng):
                            if comp >> k & 1:
                                rc += rb[k]
                                rmu += rb[k] * mu[k]
                                s[0] -= ub[k, 0]
                                s[1] -= ub[k, 1]
                        mue = rmu / rc
                        s[2] = e01
                        s[3] = e02
                        s[4] = 1.0
                        prm[P_MU_S] = mue
                        prm[P_MU_K] = mue
                        prm[P_INV_R] = 1.0 / rc
                        _phase_constant(s, ub, rb, mu, comp, rc, mue)
                        _set_frc(frc, raw, s[0], s[1], 1.0 / rc)
                        y[:] = 0.0
                        y[0] = my[M_X]
                        y[1] = my[M_X + 1]
                        x = tau
                        ein_corr = 0.0
                        enter_polar(tau, y, my[M_V], my[M_V + 1], norm(my[M_V], my[M_V + 1]), prm, frc, f)
                        phase = np.int64(PH_POLAR)
                        n_merged += 1
                        if exact_only:
                            status |= STATUS_REDUCED
                            fail_t = t[i] + tau
                            failed = True
                            break
                    continue
                events_here += 1
                h_sugg = -1.0
                if kind == EV_JOIN:
                    # the set that slides on: the rate problem's among the sliding groups and the one reached (a
                    # group whose λ would be negative at once leaves here, not one step later)
                    chosen = sliding_set(my, rb, comp | 1 << which, 1 << which)
                    comp = chosen if chosen != 0 else comp | 1 << which
                    multi_rhs(tau, my, raw, rb, mu, comp, c, mf)
                    n_ev = _record(ev_t, ev_k, n_ev, t[i] + tau, np.int64(EV_JOIN))
                    em = element_mask(comp, members)
                    if first[em] < 0.0:
                        first[em] = t[i] + tau
                    continue
                # a group leaves
                comp &= ~(1 << which)
                n_ev = _record(ev_t, ev_k, n_ev, t[i] + tau, np.int64(EV_LEAVE))
                em = element_mask(comp, members)
                if first[em] < 0.0:
                    first[em] = t[i] + tau
                n_left = 0
                kb = np.int64(-1)
                for k in range(ng):
                    if comp >> k & 1:
                        n_left += 1
                        kb = k
                if n_left >= 2:
                    multi_rhs(tau, my, raw, rb, mu, comp, c, mf)
                    continue
                # one group left: the planar pendulum forms
                e_in += my[M_EIN]
                e_f += my[M_EF]
                e_v += my[M_EV]
                rc = rb[kb]
                mue = mu[kb]
                s[0] = my[M_X] - ub[kb, 0]
                s[1] = my[M_X + 1] - ub[kb, 1]
                s[4] = 0.0
                prm[P_MU_S] = mue
                prm[P_MU_K] = mue
                prm[P_INV_R] = 1.0 / rc
                _phase_constant(s, ub, rb, mu, comp, rc, mue)
                _set_frc(frc, raw, s[0], s[1], 1.0 / rc)
                y[:] = 0.0
                y[0] = my[M_X]
                y[1] = my[M_X + 1]
                vmag = norm(my[M_V], my[M_V + 1])
                x = tau
                ein_corr = 0.0
                enter_polar(tau, y, my[M_V], my[M_V + 1], vmag, prm, frc, f)
                phase = np.int64(PH_POLAR)
                continue
            # ------------------------------------------------------------------ one group: planar forms
            if phase == PH_APPROACH:
                r = math.exp(x)
                rdot = r / f[7]
                fscale = force_scale(y[7], y, r, prm, frc)
                if x <= s_stop and s_stop > s_floor and not settled(y[7], y, f, prm, frc):
                    s_stop = s_floor
                if x > s_stop and rdot > -LEAVE_LOG * fscale:
                    x = leave_log(tau, y, r, prm, frc, f)
                    phase = np.int64(PH_SLIDE)
                    h_sugg = r / max(fscale, 1e-300)
                    continue
                if x > s_stop:
                    ds = max(ds_sugg, s_stop - x)
                    speed_tol = POLAR_VELOCITY_TOL * rtol * max(peak_v, scales[SC_V_FLOOR])
                    atol[0] = rtol * max(peak_x, scales[SC_X_FLOOR])
                    atol[1] = atol[0]
                    atol[2] = np.inf
                    atol[3] = np.inf
                    atol[4] = rtol * max(abs(y[4]) + y[5] + y[6] + abs(e_in), scales[SC_V_FLOOR] ** 2)
                    atol[5] = atol[4]
                    atol[6] = atol[4]
                    atol[7] = max(rtol * hi, speed_tol / max(-rdot, 1e-300))
                    ok, err = dop853_step(np.int64(LOG), x, y, f, ds, prm, frc, ynew, fnew, atol, rtol)
                    n_steps += 1
                    if not ok or err > 1.0:
                        n_rej += 1
                        ds_sugg = ds * (0.25 if not ok else step_factor(err))
                        just_rejected = True
                        if abs(ds_sugg) < 1e-9:
                            x = leave_log(tau, y, r, prm, frc, f)
                            phase = np.int64(PH_SLIDE)
                            h_sugg = r / max(fscale, 1e-300)
                        continue
                    hit = ynew[7] >= target
                    theta = 1.0
                    if hit:
                        theta = land_on(np.int64(LOG), x, y, f, ds, np.int64(7), target, ynew[7], fnew[7], prm, frc, yb,
                                        fb, atol, rtol, work)
                    th_j, kj = _joins_in_step(np.int64(LOG), x, y, f, ds, theta, prm, frc, yb, fb, atol, rtol, s, rc, mue,
                                              ub, rb, mu, comp, ynew, fnew)
                    if kj >= 0:
                        theta = th_j
                        hit = False
                    if theta < 1.0 or kj >= 0:
                        dop853_step(np.int64(LOG), x, y, f, theta * ds, prm, frc, ynew, fnew, atol, rtol)
                    g0 = rate_of_peak(np.int64(0), np.int64(LOG), y, f)
                    g1 = rate_of_peak(np.int64(0), np.int64(LOG), ynew, fnew)
                    if g0 > 0.0 >= g1:
                        v0 = norm(y[0], y[1])
                        v1 = norm(ynew[0], ynew[1])
                        if tangent_bound(v0, g0, v1, g1, ynew[7] - y[7]) > peak_x:
                            peak_x = max(peak_x, locate_peak(np.int64(0), np.int64(LOG), x, y, f, theta * ds, v0, g0,
                                                             v1, g1, ynew[7] - y[7], prm, frc, yb, fb, atol, rtol,
                                                             work))
                    if hit:
                        ynew[7] = target
                    ein_corr += _corr_xy(y[0], y[1], ynew[0], ynew[1], s, rc, raw, y[7], ynew[7])
                    slip += ynew[7] - y[7]
                    x += theta * ds
                    y[:] = ynew
                    f[:] = fnew
                    tau = y[7]
                    peak_x = max(peak_x, norm(y[0], y[1]))
                    if not hit and kj < 0:
                        ds_sugg = ds * (min(1.0, step_factor(err)) if just_rejected else step_factor(err))
                    just_rejected = False
                    if kj >= 0:
                        r = math.exp(x)
                        phase, comp, rc, mue = _join(kj, phase, x, tau, y, f, prm, frc, raw, s, rc, mue, comp, ub,
                                                     rb, mu, my, mf, c)
                        if phase != PH_MULTI:  # groups sliding as one: the phase's constant (_corr_xy)
                            _phase_constant(s, ub, rb, mu, comp, rc, mue)
                        if phase != PH_MULTI:
                            n_merged += 1
                            if exact_only:
                                status |= STATUS_REDUCED
                                fail_t = t[i] + tau
                                failed = True
                                break
                        if phase == PH_MULTI:
                            e_in += y[4] + ein_corr
                            e_f += y[5]
                            e_v += y[6]
                            my[M_EIN] = 0.0
                            my[M_EF] = 0.0
                            my[M_EV] = 0.0
                        n_ev = _record(ev_t, ev_k, n_ev, t[i] + tau, np.int64(EV_JOIN))
                        em = element_mask(comp, members)
                        if first[em] < 0.0:
                            first[em] = t[i] + tau
                        events_here += 1
                        h_sugg = -1.0
                        continue
                    if hit or x > s_stop:
                        continue
                    if s_stop > s_floor and not settled(y[7], y, f, prm, frc):
                        s_stop = s_floor
                        continue
                # the stop: the last speed in closed form
                r = math.exp(x)
                x0_1 = y[0]
                x0_2 = y[1]
                dtt = coast_to_rest(tau, y, r, r / f[7], target, prm, frc)
                ein_corr += _corr_xy(x0_1, x0_2, y[0], y[1], s, rc, raw, tau, tau + dtt)
                tau += dtt
                slip += dtt
                peak_x = max(peak_x, norm(y[0], y[1]))
                phase, comp, rc, mue, n_ev, e_in, e_f, e_v = _at_rest(
                    tau, t[i], y, y[2], y[3], f, prm, frc, raw, s, rc, mue, comp, ub, rb, mu, ev_t, ev_k, n_ev,
                    e_in, e_f, e_v, ein_corr, members, tmat, surf_peak, first)
                if phase == PH_START:  # a restart: the new one-group phase's constant (_corr_xy)
                    _phase_constant(s, ub, rb, mu, comp, rc, mue)
                ein_corr = 0.0
                if phase == PH_STUCK:
                    X1 = y[0]
                    X2 = y[1]
                    axx, ayy, nn = _forcing(tau, raw)
                    peak_a = max(peak_a, norm(axx, ayy))
                x = tau
                s_stop = s_end
                events_here += 1
                h_sugg = 0.01 * hi
                continue
            # START, POLAR, SLIDE (Cartesian)
            mode = START if phase == PH_START else (POLAR if phase == PH_POLAR else CARTESIAN)
            fm = 0.0
            if phase == PH_POLAR:
                r = y[7]
                fscale = force_scale(tau, y, r, prm, frc)
                fm = fscale - mue * (raw[4] + raw[5] * tau)
                rdot = f[7]
                h_try = h_sugg if h_sugg > 0.0 else target - tau
                if (r <= r_floor and rdot <= 0.0) or stop_ahead(r, rdot, fscale, h_try):
                    y[2] *= r
                    y[3] *= r
                    y[7] = 0.0
                    phase = np.int64(PH_SLIDE)
                    rhs(np.int64(CARTESIAN), tau, y, prm, frc, f)
                    continue
            if phase == PH_SLIDE:
                r = norm(y[2], y[3])
                fscale = force_scale(tau, y, r, prm, frc)
                rdot = (y[2] * f[2] + y[3] * f[3]) / r if r > 0.0 else 0.0
                if r <= r_floor and rdot <= 0.0:
                    x0_1 = y[0]
                    x0_2 = y[1]
                    e1 = 0.0
                    e2 = 0.0
                    if r > 0.0:
                        y[2] /= r
                        y[3] /= r
                        e1 = y[2]
                        e2 = y[3]
                        dtt = coast_to_rest(tau, y, r, rdot, target, prm, frc)
                        ein_corr += _corr_xy(x0_1, x0_2, y[0], y[1], s, rc, raw, tau, tau + dtt)
                        tau += dtt
                        slip += dtt
                        peak_x = max(peak_x, norm(y[0], y[1]))
                    phase, comp, rc, mue, n_ev, e_in, e_f, e_v = _at_rest(
                        tau, t[i], y, e1, e2, f, prm, frc, raw, s, rc, mue, comp, ub, rb, mu, ev_t, ev_k, n_ev,
                        e_in, e_f, e_v, ein_corr, members, tmat, surf_peak, first)
                    if phase == PH_START:  # a restart: the new one-group phase's constant (_corr_xy)
                        _phase_constant(s, ub, rb, mu, comp, rc, mue)
                    ein_corr = 0.0
                    if phase == PH_STUCK:
                        X1 = y[0]
                        X2 = y[1]
                    x = tau
                    events_here += 1
                    h_sugg = 0.01 * hi
                    continue
                if r < 0.5 * r_switch_lo and not rdot < -ENTER_LOG * fscale:
                    y[2] = r
                    y[3] = 0.0
                    phase = np.int64(PH_START)
                    rhs(np.int64(START), tau, y, prm, frc, f)
                    continue
                h_try = h_sugg if h_sugg > 0.0 else target - tau
                if stop_ahead(r, rdot, fscale, h_try):
                    y[2] /= r
                    y[3] /= r
                    y[7] = tau
                    x = math.log(r)
                    if rhs(np.int64(LOG), x, y, prm, frc, f):
                        phase = np.int64(PH_APPROACH)
                        s_stop = s_end
                        ds_sugg = -0.5
                        continue
                    y[2] *= r
                    y[3] *= r
                    x = tau
                    rhs(np.int64(CARTESIAN), tau, y, prm, frc, f)
                else:
                    enter_polar(tau, y, y[2], y[3], r, prm, frc, f)
                    phase = np.int64(PH_POLAR)
                    mode = np.int64(POLAR)
                    fm = fscale - mue * (raw[4] + raw[5] * tau)
            hmax = target - tau
            h = hmax if (h_sugg <= 0.0 or h_sugg >= hmax) else h_sugg
            if phase == PH_SLIDE:
                h_stable = STABLE_CARTESIAN * r / max(fscale, 1e-300)
                h = min(h, h_stable)
            elif phase == PH_POLAR:
                h_stable = STABLE_POLAR * y[7] / max(fm, 1e-300)
                h = min(h, h_stable)
            atol[0] = rtol * max(peak_x, scales[SC_X_FLOOR])
            atol[1] = atol[0]
            atol[4] = rtol * max(abs(y[4]) + y[5] + y[6] + abs(e_in), scales[SC_V_FLOOR] ** 2)
            atol[5] = atol[4]
            atol[6] = atol[4]
            atol[2] = rtol * max(peak_v, scales[SC_V_FLOOR])
            atol[7] = np.inf
            atol[3] = atol[2] if mode == CARTESIAN else np.inf
            if mode == POLAR:
                atol[2] *= POLAR_VELOCITY_TOL
                atol[7] = atol[2]
                atol[2] /= y[7]
                atol[3] = atol[2]
            ok, err = dop853_step(mode, tau, y, f, h, prm, frc, ynew, fnew, atol, rtol)
            n_steps += 1
            if not ok or err > 1.0:
                n_rej += 1
                h_sugg = h * (0.25 if not ok else step_factor(err))
                just_rejected = True
                continue
            theta = 1.0
            restop = mode == START and ynew[2] < 0.0 and fnew[2] < 0.0
            if restop:
                theta = land_on(np.int64(START), tau, y, f, h, np.int64(2), 0.0, ynew[2], fnew[2], prm, frc, yb, fb,
                                atol, rtol, work)
            th_j, kj = _joins_in_step(mode, tau, y, f, h, theta, prm, frc, yb, fb, atol, rtol, s, rc, mue, ub, rb,
                                      mu, comp, ynew, fnew)
            if kj >= 0:
                theta = th_j
                restop = False
            if theta < 1.0:
                dop853_step(mode, tau, y, f, theta * h, prm, frc, ynew, fnew, atol, rtol)
                h *= theta
            if restop:
                ynew[2] = 0.0
            ein_corr += _corr_xy(y[0], y[1], ynew[0], ynew[1], s, rc, raw, tau, tau + h)
            for which in range(2):
                # |X| and |V| may peak inside the step (the planar engine's bracket and secant)
                g0 = rate_of_peak(which, mode, y, f)
                g1 = rate_of_peak(which, mode, ynew, fnew)
                if g0 > 0.0 >= g1:
                    v0 = peak_value(which, mode, y)
                    v1 = peak_value(which, mode, ynew)
                    if tangent_bound(v0, g0, v1, g1, h) > (peak_x if which == 0 else peak_v):
                        best = locate_peak(which, mode, tau, y, f, h, v0, g0, v1, g1, h, prm, frc, yb, fb, atol,
                                           rtol, work)
                        if which == 0:
                            peak_x = max(peak_x, best)
                        else:
                            peak_v = max(peak_v, best)
            tau = target if (h == hmax and theta == 1.0) else tau + h
            y[:] = ynew
            f[:] = fnew
            slip += h
            peak_x = max(peak_x, norm(y[0], y[1]))
            e1, e2, vn = _direction(phase, tau, tau, y, prm, frc)
            peak_v = max(peak_v, vn)
            r1, r2 = _one_group_r(y[0], y[1], e1, e2, s, rc, mue)
            nn_t = raw[4] + raw[5] * tau
            vv1, vv2 = velocity(phase, tau, tau, y, prm, frc)
            peak_a = max(peak_a, norm(nn_t * r1 + c * vv1, nn_t * r2 + c * vv2))
            if vn > 0.0:
                _one_group_settle(ub, comp, y[0], y[1], e1, e2, s, rc, mue, rb, mu)
                surface_peaks(ub, rb, members, tmat, surf_peak)
                if _over_rim(ub, rb, rim, comp):
                    status |= STATUS_RIM
                    fail_t = t[i] + tau
                    failed = True
                    break
            if kj < 0 and not restop:
                fac = step_factor(err)
                if just_rejected:
                    fac = min(1.0, fac)
                h_sugg = h * fac
            just_rejected = False
            x = tau
            if restop:
                e1, e2 = _slaved(tau, y, prm, frc)
                phase, comp, rc, mue, n_ev, e_in, e_f, e_v = _at_rest(
                    tau, t[i], y, e1, e2, f, prm, frc, raw, s, rc, mue, comp, ub, rb, mu, ev_t, ev_k, n_ev, e_in,
                    e_f, e_v, ein_corr, members, tmat, surf_peak, first)
                if phase == PH_START:  # a restart: the new one-group phase's constant (_corr_xy)
                    _phase_constant(s, ub, rb, mu, comp, rc, mue)
                ein_corr = 0.0
                if phase == PH_STUCK:
                    X1 = y[0]
                    X2 = y[1]
                events_here += 1
                h_sugg = 0.01 * hi
                continue
            if kj >= 0:
                phase, comp, rc, mue = _join(kj, phase, x, tau, y, f, prm, frc, raw, s, rc, mue, comp, ub, rb, mu,
                                             my, mf, c)
                if phase != PH_MULTI:  # groups sliding as one: the phase's constant (_corr_xy)
                    _phase_constant(s, ub, rb, mu, comp, rc, mue)
                if phase != PH_MULTI:
                    n_merged += 1
                    if exact_only:
                        status |= STATUS_REDUCED
                        fail_t = t[i] + tau
                        failed = True
                        break
                if phase == PH_MULTI:
                    e_in += y[4] + ein_corr
                    e_f += y[5]
                    e_v += y[6]
                    my[M_EIN] = 0.0
                    my[M_EF] = 0.0
                    my[M_EV] = 0.0
                    multi_rhs(tau, my, raw, rb, mu, comp, c, mf)
                n_ev = _record(ev_t, ev_k, n_ev, t[i] + tau, np.int64(EV_JOIN))
                em = element_mask(comp, members)
                if first[em] < 0.0:
                    first[em] = t[i] + tau
                events_here += 1
                h_sugg = -1.0
                continue
            if phase == PH_START and (y[2] >= r_switch or (
                    y[2] >= r_switch_lo and start_lag(tau, y, prm, frc) > LAG_MAX_RAD)):
                v1, v2 = velocity(np.int64(PH_START), x, tau, y, prm, frc)
                enter_polar(tau, y, v1, v2, y[2], prm, frc, f)
                phase = np.int64(PH_POLAR)
        if failed:
            break
        # ---- the sample
        if phase == PH_STUCK:
            out_x[i + 1, 0] = X1
            out_x[i + 1, 1] = X2
            out_v[i + 1, 0] = 0.0
            out_v[i + 1, 1] = 0.0
            out_a[i + 1, 0] = ax[i + 1]
            out_a[i + 1, 1] = ay[i + 1]
            out_en[0, i + 1] = e_in
            out_en[1, i + 1] = e_f
            out_en[2, i + 1] = e_v
            peak_a = max(peak_a, norm(ax[i + 1], ay[i + 1]))
        elif phase == PH_MULTI:
            out_x[i + 1, 0] = my[M_X]
            out_x[i + 1, 1] = my[M_X + 1]
            out_v[i + 1, 0] = my[M_V]
            out_v[i + 1, 1] = my[M_V + 1]
            out_a[i + 1, 0] = mf[M_V] + ax[i + 1]
            out_a[i + 1, 1] = mf[M_V + 1] + ay[i + 1]
            out_en[0, i + 1] = e_in + my[M_EIN]
            out_en[1, i + 1] = e_f + my[M_EF]
            out_en[2, i + 1] = e_v + my[M_EV]
        else:
            v1, v2 = velocity(phase, x, hi, y, prm, frc)
            e1, e2, vn = _direction(phase, x, hi, y, prm, frc)
            r1, r2 = _one_group_r(y[0], y[1], e1, e2, s, rc, mue)
            out_x[i + 1, 0] = y[0]
            out_x[i + 1, 1] = y[1]
            out_v[i + 1, 0] = v1
            out_v[i + 1, 1] = v2
            out_a[i + 1, 0] = -nz[i + 1] * r1 - c * v1
            out_a[i + 1, 1] = -nz[i + 1] * r2 - c * v2
            out_en[0, i + 1] = e_in + y[4] + ein_corr
            out_en[1, i + 1] = e_f + y[5]
            out_en[2, i + 1] = e_v + y[6]
            peak_a = max(peak_a, norm(out_a[i + 1, 0], out_a[i + 1, 1]))
    if failed:
        for j in range(n):
            if j > i:
                out_x[j, 0] = np.nan
                out_x[j, 1] = np.nan
    # final element state and energies
    if phase == PH_MULTI:
        for k in range(ng):
            ub[k, 0] = my[M_U + 2 * k]
            ub[k, 1] = my[M_U + 2 * k + 1]
        e_in += my[M_EIN]
        e_f += my[M_EF]
        e_v += my[M_EV]
    elif phase != PH_STUCK:
        e1, e2, vn = _direction(phase, x, tau, y, prm, frc)
        if vn > 0.0:
            _one_group_settle(ub, comp, y[0], y[1], e1, e2, s, rc, mue, rb, mu)
        e_in += y[4] + ein_corr
        e_f += y[5]
        e_v += y[6]
    if n_ev > ev_t.shape[0]:
        status |= STATUS_EVENTS_TRUNCATED
    summary[S_PEAK_X] = peak_x
    summary[S_PEAK_V] = peak_v
    summary[S_PEAK_A] = peak_a
    summary[S_SLIP_TIME] = slip
    summary[S_E_IN] = e_in
    summary[S_E_F] = e_f
    summary[S_E_V] = e_v
    summary[S_N_EVENTS] = n_ev
    summary[S_STATUS] = status
    summary[S_N_STEPS] = n_steps
    summary[S_N_REJECTED] = n_rej
    summary[S_FAIL_T] = fail_t
    summary[S_STEPS_MULTI] = n_multi
    summary[S_N_MERGED] = n_merged
