r"""The robust method of the 2-D multi-surface model: implicit steps on the smooth formulation.

The event-driven kernel (:mod:`isolator.solver.planar_multisurface_kernel`) follows the sliding set
from event to event.  Where three friction circles meet at small angles, or two sliding circles
close towards tangency while the motion curves, the sliding set changes faster than events can be
resolved (a group joins and leaves in turn) and its compliance matrix becomes singular; the kernel
then stops with a status.  This module integrates the same model without any event:

per unit mass and in units of the weight (n = g), with the groups' displacements ū_k, their
back-forces b_k = ū_k/R̄_k and friction circles of radius µ_k, one **backward-Euler step** of length
h from (X, V, ū) is the minimiser of a strictly convex function of the force r (its dual):

    Ψ(r) = g |r|²/2 + α Σ_k R̄_k (|r − b_k| − µ_k)₊² / 2 − p·r,   α = (1 + c h)/h²,  p = V/h − ā,

(ā the mean ground acceleration over the step), after which every group slides by the exact
return of its rigid–plastic element with linear hardening, δ_k = R̄_k (|r − b_k| − µ_k)₊ (r − b_k)/|r − b_k|,
X ← X + Σ δ_k, V ← Σ δ_k / h.  This is the incremental variational form of the model (the δ_k minimise
Σ_k [g|ū_k + δ_k|²/(2R̄_k) + g µ_k |δ_k|] + (1 + ch)|Σδ_k|²/(2h²) − p·Σδ_k, and r is its Lagrange
multiplier): whatever the geometry of the circles — corners at any angle, tangency, three circles
through one point, a stop, a stick — the step has exactly one answer, found by Newton's method on a
2-D strongly convex function (bounded iterations, backtracking).  r is the projection-type answer of
the time-discrete problem, so a stick is exact (V = 0, r = −ā/g inside every circle) and no event
needs locating.

The step is first order; each step is taken twice (h, then two halves of h/2), the difference is
the local error estimate that sets the step size (relative tolerance ``tol`` of the peak
displacement and velocity), and the two are combined (Richardson, 2·y_{h/2} − y_h) for second-order
accuracy where the motion is smooth.  A step whose velocity turns back or vanishes (a reversal, a stop) is cut
where its velocity still points forward, so the combination holds on both sides (step doubling cannot see such an
event in a step's first half).  The error is measured against the event-driven kernel on the records it finishes
(docs/multisurface.md) and converges with ``tol``.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.jit import njit
from isolator.solver.planar_multisurface_kernel import (
    EV_BREAKAWAY,
    EV_STICK,
    S_E_F,
    S_E_IN,
    S_E_V,
    S_FAIL_T,
    S_N_EVENTS,
    S_N_REJECTED,
    S_N_STEPS,
    S_PEAK_A,
    S_PEAK_V,
    S_PEAK_X,
    S_SIZE,
    S_SLIP_TIME,
    S_STATUS,
    S_STEPS_MULTI,
    STATUS_EVENTS_TRUNCATED,
    STATUS_RIM,
    STATUS_STEP_LIMIT,
    breakaway,
    element_mask,
    surface_peaks,
)

#: the Newton iteration on Ψ (2-D, strongly convex) stops after this many iterations at the latest
MAX_NEWTON = 60
#: the ellipsoid method's cuts after Newton did not converge (step_force): its area falls by 0.77 a cut, so 2000 cuts
#: take an ellipse 1e113 times smaller than the first, far past the rounding of r
MAX_ELLIPSOID = 2000
#: Newton's iterations on Ψ with the plain step; later ones leave out a component of ∇Ψ at its rounding floor
NEWTON_PLAIN = 3
#: accepted plus rejected steps allowed inside one sample interval (the loop's bound: at most 1/H_MIN_FRACTION
#: accepted steps of the smallest length, each after at most a few rejected ones)
MAX_STEPS_PER_INTERVAL = 3_000_000
#: smallest step as a fraction of the sample interval (the floor): there the step is taken whatever its error
#: estimate (progress is guaranteed; counted in the summary's S_STEPS_MULTI slot).  Not a hard floor: a step taken at
#: it with an error estimate above 1 shrinks the next below it (docs/multisurface.md, "Steps below the floor")
H_MIN_FRACTION = 1e-6
#: the arrival at the ultimate displacement is an event of the steps (arrival_time, arrive): the last ARRIVAL_FRACTION
#: of the sample interval before it is taken in one move onto the ultimate circle, the impact after it.  Every group
#: on its rim closing into alignment with the mass moving outward, the rims' reaction grows as 1/sin of the rims'
#: angles, the step the error test allows is a fixed fraction of the time left (a Zeno sequence: Chuetsu-oki 65025
#: ×1.556 with Fenz & Constantinou's TFP at µ × 0.765, step_tol 1e-9, 24.4088 s: 0.04–0.07 of it a step, ~3,600 steps
#: from 2.6e-3 s before the arrival to a step of 1.6e-15 s, where Newton's α = 1/h² lost the force: "found no force";
#: docs/multisurface.md, "The arrival at the ultimate as an event of the steps").  The floor's size, so that no step
#: below it is needed.  The reaction's impulse over the move (∝ 1/√(time left): 2 h g r·ē) is taken off the outward
#: velocity before the impact, so the impulse reported is the arrival's whatever the move's length (measured: the
#: move started 1e-8 … 1e-11 s before the arrival, the same to 2e-9 m/s)
ARRIVAL_FRACTION = H_MIN_FRACTION

#: be_step's flag: the step's force was not found (Newton did not converge in MAX_NEWTON iterations)
UNSOLVED = 1 << 40
#: the run's status bit for it (past the event kernel's STATUS_* bits)
STATUS_UNSOLVED = 64
#: the run's status bit: one sample interval needed more than MAX_FORCE_EVALS_PER_INTERVAL evaluations of Ψ's gradient
STATUS_WORK = 1 << 12
#: the work allowed in one sample interval, in evaluations of Ψ's gradient (each a return of every group) by the
#: three backward-Euler solves of every step, Newton's iterations and their line searches: a bound on the time one
#: interval can take (~10 s at the bound).  Measured: the answered runs of tests/solver/test_planar_multisurface*.py
#: and of the TFP review test need at most 377,005 in an interval (Landers YER ×MCE_R, cut TFP, upper bound); the
#: ultimate with sliders on their rims pointing different ways (Superstition Hills PTS in that test, 12.05 s) needs
#: tens of millions (one such interval ran 200 s before this bound).  Past it the run stops with the instant (never
#: a silent truncation)
MAX_FORCE_EVALS_PER_INTERVAL = 1_000_000
#: the tolerance at which that bound holds as it is: a first-order step with a step-doubling estimate grows as √tol, so
#: at a tighter tolerance the bound grows as √(WORK_TOL / tol) (work_bound).  Measured: Chuetsu-oki 65025 ×1.556 with
#: Fenz & Constantinou's TFP, nominal friction, at step_tol 1e-9: the groups close into alignment on their rims
#: before the ultimate impact at 24.45 s (r from 0.5 to 3.7 W, every group sliding along its rim, 70–100 gradients
#: a solve, steps 2.8e-6 → 1.7e-7 s, set by the velocity's error): more than 1,000,000 gradients in that interval,
#: where step_tol 1e-7 and 1e-8 needed fewer
WORK_TOL = 1e-7
#: the relative rounding of a position returned onto a rim (a few units in the last place of c̄): α times it is the
#: floor of Ψ's gradient where groups are at their rims (step_force)
RIM_ROUNDING = 8e-16
#: the displacement's error scale is held above this many machine epsilons of Σ R̄ µ + Σ R̄ |r|, the rounding of the
#: groups' slips (a slip R̄ (|r − ū/R̄| − µ) moves in quanta of R̄ ulp(r), ~1.7e-17 m on IELC's double, and the three
#: solves' X differ by it): at rest the running peak is ~0 and the scale step_tol × the floor fell below it at tight
#: tolerances, the steps were rejected on rounding down to the floor and accepted there whatever their error — the
#: rigid block's (N. California 89146 ×1.5 on IELC's double, step_tol 3e-10: 141,017 such steps; docs/multisurface.md,
#: h225's section) and the building's (planar_building_multisurface_kernel, which takes this constant: AOM017 ×1.5,
#: step_tol 3e-10, the slide started late, 2.05e-1 of the peak; docs/building.md, "A tighter step_tol gave a worse
#: answer")
SLIP_QUANTA = 4.0
#: the doubles' machine epsilon
DOUBLE_EPS = 2.220446049250313e-16
#: the relative rounding of a sliding group's slip (a few units in the last place of |r − b|): α R̄ (|b| + µ) times it
#: is the floor of Ψ's gradient from the sliding groups near their circles (step_force; a term in |r| made the floor
#: ~1e2 at an impact, r ~ 1e5 W, and Newton stopped on a wrong force: balances open by 5.8e-2 and 4.5)
SLIP_ROUNDING = 4e-16
#: a step cut where its velocity turns (a reversal or a stop) ends where the velocity still points forward; that velocity
#: is rounding when it is below this fraction of |X| over the cut's length (the slips' last bits over the step: a step
#: of 7e-7 s at |X| = 0.32 m left 6.8e-10 m/s, 6.6 ulp of X, where step_tol 8e-10 asked 6.4e-10 m/s: the cut was
#: refused and the reversal's error, 1.4e-6 of the peak, stayed — NWH360 on a double with an intermediate rim)
CUT_ROUNDING = 1e-14
#: a group is on its rim when |ū| ≥ c̄ (1 − RIM_ON) (the rim's return puts it on the circle to the last bits)
RIM_ON = 1e-12
#: a group counts as having left its rim (and its next arrival as a new rim contact, S_N_RIM_CONTACTS) only once
#: |ū| < c̄ (1 − RIM_AWAY): the steps' own excursions off a rim they stay on are far smaller (the backward-Euler chord
#: of a slide along the rim, ~(h|V|)²/(2c̄), ≲ 1e-6 of c̄ at step_tol 1e-7), a departure a slider makes is ≳ 1e-3
#: of c̄ (a rim contact counted per arrival at |ū| = c̄ moved with the tolerance: PTS ×2.5 with Fenz & Constantinou's
#: TFP at µ × 0.85, 220 / 118 at step_tol 1e-7 / 1e-8)
RIM_AWAY = 1e-3
#: every group on its rim is the ultimate displacement (a rigid stop) when each ū_k/c̄_k lies within this angle
#: [rad] of their sum's direction: the rims then admit no outward velocity with a finite force.  Groups further
#: apart turn on their rims under finite (large) forces, which the steps resolve
ALIGNED = 1e-7

#: a group's slip turning by more than this angle [rad] inside a step (between its slip over the last step and over
#: the first half, or between the halves) refuses the step (it is retried shorter, down to the floor): the friction's
#: direction then turns on a time scale shorter than the step, the step's error expansion in h does not hold there
#: and step doubling does not see it.  A group slowing to a near stop while the mass slides on (its slip speed through
#: a minimum, its friction turning at ~g µ / speed) turned by 102° inside one step of 5.8e-5 s accepted with an
#: estimate of 0.00, leaving a velocity error of ~5e-6 m/s that did not fall with step_tol (NWH360 ×1.2 with the
#: reversed record ×0.72 on the double with an intermediate rim, 3.612 s; docs/multisurface.md, "A group's slip
#: turning inside a step").  Where the mass itself turns back the reversal cut takes the step (the groups' slips
#: all turn there); after a cut's stop, a stick or an impact the last step's slip is not compared
SLIP_TURN = 0.1

# the state vector: X, V, energies (input, friction, viscous, impacts), then ū of each group, then the carried group's
# slot (carry_slot: k + 1 when the step that ended in this state carried the mass on group k's rim, be_step; else 0)
Y_X = 0
Y_V = 2
Y_EIN = 4
Y_EF = 5
Y_EV = 6
Y_EIMP = 7
Y_U = 8

# the summary's slots past the event kernel's (planar_multisurface_kernel.S_SIZE)
S_N_RIM_CONTACTS = S_SIZE  #: elements reaching their rims (arrivals after leaving by more than RIM_AWAY)
S_N_ULTIMATE = S_SIZE + 1  #: impacts at the ultimate displacement (every element on its rim)
S_IMPULSE = S_SIZE + 2  #: Σ velocity lost in those impacts [m/s] (impulse per unit mass)
S_MAX_IMPACT_V = S_SIZE + 3  #: largest velocity lost in one impact [m/s]
S_E_IMP = S_SIZE + 4  #: kinetic energy lost in the impacts [J/kg]
S_PEAK_R = S_SIZE + 5  #: largest |F/W| of the surfaces (the rims' reaction left out)
S_FIRST_ULT = S_SIZE + 6  #: time the ultimate displacement was first reached [s] (-1: never)
S_MAX_WORK = S_SIZE + 7  #: the most evaluations of Ψ's gradient one sample interval needed
S_FAIL_RIMS = S_SIZE + 8  #: the groups on their rims where the run stopped
S_SIZE_STEPS = S_SIZE + 9


@njit(cache=True)
def work_bound(tol):
    """The evaluations of Ψ's gradient allowed in one sample interval at the local error tolerance ``tol``:
    MAX_FORCE_EVALS_PER_INTERVAL, times √(WORK_TOL / tol) below WORK_TOL."""
    return MAX_FORCE_EVALS_PER_INTERVAL * max(1.0, math.sqrt(WORK_TOL / tol))


@njit(cache=True)
def _rim_point(rx, ry, u1, u2, kappa, mu):
    # the return of an element of stiffness κ [1/m] (1/R̄ plus the rim's multiplier): ū + (|r − κū| − µ)₊ e/κ
    d1 = rx - kappa * u1
    d2 = ry - kappa * u2
    dn = math.sqrt(d1 * d1 + d2 * d2)
    if not dn > mu:
        return u1, u2
    s = (dn - mu) / (kappa * dn)
    return u1 + s * d1, u2 + s * d2


#: a slip along the rim shorter than this fraction of c̄ takes its direction from :func:`short_chord`
SHORT_CHORD = 1e-6


@njit(cache=True)
def short_chord(qt, sn, e1, e2, u1, u2, rim):
    """The direction q of a short slip δ = w − ū along the rim (|δ| = sn < SHORT_CHORD c̄, w = c̄ e on the circle):
    (q1, q2, q·t), t the tangent at w, q·t's sign the one given (``qt``, from δ/|δ|).

    δ/|δ| itself carries the rounding of w and ū, ~ulp(c̄)/|δ| in its normal part, so 1 − q·t was ~(ulp(c̄)/|δ|)²
    against its value ~(|δ|/2c̄)²; µ times that in the tangential balance moved the polished slip of
    :func:`rim_return` by ~1e-12 m (a group turning on its rim by 1e-13 m: its slip 0.9–16 times the answer as r moved
    1e-12 along the normal, and Newton on Ψ found no force — NWH360 ×1 with the reversed record ×0.6 along y, a double
    with an intermediate rim under 2 stories, 0.917 s).  Here q·e = ((c̄ − |ū|) + |ū| |e − ē|²/2)/|δ| (ē = ū/|ū|:
    c̄ − |ū| taken as 0 for ū on its rim) and q·t = ±√(1 − (q·e)²)."""
    un = math.sqrt(u1 * u1 + u2 * u2)
    if not un > 0.0:
        return (qt * -e2 + math.sqrt(max(1.0 - qt * qt, 0.0)) * e1, qt * e1 + math.sqrt(max(1.0 - qt * qt, 0.0)) * e2,
                qt)
    d1 = e1 - u1 / un
    d2 = e2 - u2 / un
    # ū on its rim as the steps read it (within RIM_ON): c̄ − |ū| is the rounding of ū, taken as 0 (an ulp of c̄
    # against a slip of 1e-13 m tilts the chord by 3e-5 and takes µ (q·e)²/2 ~ 2e-11 W off the friction along the rim)
    gap = 0.0 if un >= rim * (1.0 - RIM_ON) else rim - un
    qe = min(max((gap + 0.5 * un * (d1 * d1 + d2 * d2)) / sn, -1.0), 1.0)
    qt = math.copysign(math.sqrt(1.0 - qe * qe), qt)
    return qe * e1 - qt * e2, qe * e2 + qt * e1, qt


@njit(cache=True)
def rim_return(rx, ry, u1, u2, rb, mu, rim):
    """The return of one element whose free return would cross its rim |ū| = c̄ [m].

    With the rim, the element's new position w minimises |w − R̄ r|²/(2R̄) + µ|w − ū| on the disc
    |w| ≤ c̄ (ū inside it): its minimiser lies on the circle, where the rim's multiplier ν ≥ 0 adds
    to the stiffness, κ = 1/R̄ + ν, and w(κ) is the free return of stiffness κ.  |w(κ)| falls
    monotonically with κ (a regularisation path), so the one root |w(κ)| = c̄ is bracketed and
    found by bisection to the last bit of κ.  ``held`` when w = ū (the rim holds the element: r − b
    lies in the friction circle plus the rim's normal cone).

    Returns
    -------
    (w1, w2, kappa, held) : the new position [m] (|w| = c̄), κ [1/m], and whether the element stays.
    """
    lo = 1.0 / rb
    hi = 2.0 * lo
    for _ in range(2100):
        w1, w2 = _rim_point(rx, ry, u1, u2, hi, mu)
        if w1 * w1 + w2 * w2 <= rim * rim:
            break
        if hi > 1e290:
            break  # |w| → 0 as κ → ∞: not reached for a finite r; a guard against overflow
        lo = hi
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if not (lo < mid < hi):
            break
        w1, w2 = _rim_point(rx, ry, u1, u2, mid, mu)
        if w1 * w1 + w2 * w2 > rim * rim:
            lo = mid
        else:
            hi = mid
    w1, w2 = _rim_point(rx, ry, u1, u2, hi, mu)
    held = w1 == u1 and w2 == u2
    wn = math.sqrt(w1 * w1 + w2 * w2)
    if wn > 0.0:
        # on the circle to the last bit (the bisection's end is inside it by ~1e-16 of c̄)
        w1 *= rim / wn
        w2 *= rim / wn
    if held or not wn > 0.0:
        return w1, w2, hi, held
    # The bisection's answer polished by Newton's method on the tangential balance of the point on the circle,
    # F(θ) = (r − µ q)·t = 0 (q the slip's direction, t the tangent at w), F' = −c̄ D with D = κ + µ (1 − (q·t)²)/|w − ū|
    # > 0, then κ from the radial balance (r − µ q)·e = c̄ κ: the root in κ reaches w only through |w(κ)|, which for a
    # short slip along the rim moves with κ through the chord's radial part alone (second order in the slip).
    # Measured: on constructed short slips the bisection alone is already within 5e-11 of the slip (the tests), but
    # with this polish the PTS ×2 double's worst interval needs 72,448 gradients instead of 428,987 and 65025 with the
    # TFP balances to 4.7e-6 instead of 6.2e-5 (refused); how it helps Newton there is not established.
    # (the unit vector e of w turned by each correction, not an angle: a collinear answer, e = (±1, 0) with no
    # tangential force, stays exactly collinear)
    e1 = w1 / rim
    e2 = w2 / rim
    fbest = np.inf
    kappa = hi
    for _ in range(8):
        v1 = rim * e1 - u1
        v2 = rim * e2 - u2
        sn = math.sqrt(v1 * v1 + v2 * v2)
        if not sn > 0.0:
            break
        q1 = v1 / sn
        q2 = v2 / sn
        qt = -q1 * e2 + q2 * e1
        if sn < SHORT_CHORD * rim:
            q1, q2, qt = short_chord(qt, sn, e1, e2, u1, u2, rim)
        f = -(rx - mu * q1) * e2 + (ry - mu * q2) * e1
        if not abs(f) < fbest:
            break
        fbest = abs(f)
        kap = ((rx - mu * q1) * e1 + (ry - mu * q2) * e2) / rim
        den = kap + mu * (1.0 - qt * qt) / sn
        if not (kap > 0.0 and den > 0.0):
            break
        w1 = rim * e1
        w2 = rim * e2
        kappa = kap
        step = f / (rim * den)
        if abs(step) <= 2.2e-16:
            break
        cs = math.cos(step)
        sn_ = math.sin(step)
        e1, e2 = e1 * cs - e2 * sn_, e1 * sn_ + e2 * cs
        en = math.sqrt(e1 * e1 + e2 * e2)
        e1 /= en
        e2 /= en
    return w1, w2, kappa, held


@njit(cache=True)
def rim_holds(d1, d2, u1, u2, mu, rim):
    """Whether an element on its rim (|ū| ≥ c̄ (1 − RIM_ON)) stays where it is under r, d = r − b = r − ū/R̄ [W].

    The exact condition of the step's problem at w = ū (its optimality, 0 ∈ b − r + µ B + N(ū), B the unit disc
    and N(ū) = {ν e, ν ≥ 0} the rim's normal cone at ū, e = ū/|ū|): d lies in the friction disc plus the rim's
    outward normals, |d·t| ≤ µ and d·e ≥ 0 (the case |d| ≤ µ is the ordinary stick, taken before).  Decided here on
    d itself, not on the rim's return: the bisection and polish of :func:`rim_return` end on ū only to rounding, so
    an element held by its rim came out "sliding along it" by ~1e-16 rad in some of the step's three solves and not
    in the others, and the step's Richardson combination was refused (its sliding set differed) for as long as the
    rim held it — first-order steps, each losing its O(h²) numerical dissipation (Chuetsu-oki 65025 with Fenz &
    Constantinou's TFP, 28.30 s, surface 1 held on its rim with the mass free: 144 such steps lost 9.1e-5 J/kg, the
    balance open by 1.8e-5 of the input; at step_tol 1e-8 the refusal by the balance guard, 2.8e-5)."""
    un2 = u1 * u1 + u2 * u2
    if un2 < (rim * (1.0 - RIM_ON)) ** 2:
        return False
    un = math.sqrt(un2)
    dn = (d1 * u1 + d2 * u2) / un
    dt = (-d1 * u2 + d2 * u1) / un
    return dn >= 0.0 and abs(dt) <= mu


@njit(cache=True)
def element_return(rx, ry, u1, u2, rb, mu, rim):
    """The slip of one element under the force r [W] and its share of Ψ and of Ψ's Hessian.

    Returns (δ1, δ2, T, a, c, m1, m2, state): the slip δ [m], T(r) = sup_w [r·(w − ū) − (|w|² −
    |ū|²)/(2R̄) − µ|w − ū|] over |w| ≤ c̄ (its gradient is δ, its Hessian J = ∂δ/∂r = a I + c m mᵀ [m],
    a, c ≥ 0, m a unit vector), and the state: 0 stuck, 1 sliding, 2 sliding on the rim, 3 held by the rim."""
    d1 = rx - u1 / rb
    d2 = ry - u2 / rb
    dn = math.sqrt(d1 * d1 + d2 * d2)
    ex = dn - mu
    if not ex > 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0
    lam = rb * ex
    v1 = lam * d1 / dn
    v2 = lam * d2 / dn
    if (u1 + v1) ** 2 + (u2 + v2) ** 2 <= rim * rim:
        q = mu / dn
        e1 = d1 / dn
        e2 = d2 / dn
        return v1, v2, 0.5 * rb * ex * ex, rb * (1.0 - q), rb * q, e1, e2, 1
    if rim_holds(d1, d2, u1, u2, mu, rim):
        return 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 3
    w1, w2, kappa, held = rim_return(rx, ry, u1, u2, rb, mu, rim)
    if held:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 3
    s1 = w1 - u1
    s2 = w2 - u2
    sn = math.sqrt(s1 * s1 + s2 * s2)
    tval = rx * s1 + ry * s2 - (rim * rim - u1 * u1 - u2 * u2) / (2.0 * rb) - mu * sn
    # J = t tᵀ / (κ + µ (1 − (q·t)²)/|δ|): θ of w = c̄ (cos θ, sin θ) moves with the tangential force (the
    # stationarity of the one-variable problem on the circle, differentiated)
    t1 = -w2 / rim
    t2 = w1 / rim
    qt = (s1 * t1 + s2 * t2) / sn if sn > 0.0 else 0.0
    if 0.0 < sn < SHORT_CHORD * rim:
        _, _, qt = short_chord(qt, sn, w1 / rim, w2 / rim, u1, u2, rim)
    den = kappa + (mu * (1.0 - qt * qt) / sn if sn > 0.0 else 0.0)
    return s1, s2, max(tval, 0.0), 0.0, 1.0 / den, t1, t2, 2


@njit(cache=True)
def _groups_sum(y, ng):
    """The sum of the ng groups' displacements in the state y [m]: its two components and its length."""
    s1 = 0.0
    s2 = 0.0
    for k in range(ng):
        s1 += y[Y_U + 2 * k]
        s2 += y[Y_U + 2 * k + 1]
    return s1, s2, math.sqrt(s1 * s1 + s2 * s2)


@njit(cache=True)
def at_ultimate(y, rim):
    """Every group on its rim, all along one direction (within ALIGNED): the mass is held on the ultimate circle."""
    ng = rim.shape[0]
    s1 = 0.0
    s2 = 0.0
    for k in range(ng):
        u1 = y[Y_U + 2 * k]
        u2 = y[Y_U + 2 * k + 1]
        if u1 * u1 + u2 * u2 < (rim[k] * (1.0 - RIM_ON)) ** 2:
            return False
        s1 += u1
        s2 += u2
    sn = math.sqrt(s1 * s1 + s2 * s2)
    if not sn > 0.0:
        return False
    for k in range(ng):
        u1 = y[Y_U + 2 * k]
        u2 = y[Y_U + 2 * k + 1]
        if abs(u1 * s2 - u2 * s1) > ALIGNED * sn * math.sqrt(u1 * u1 + u2 * u2) or u1 * s1 + u2 * s2 <= 0.0:
            return False
    return True


@njit(cache=True)
def carry_slot(ng):
    """The index of the state's last slot: k + 1 when the step that ended there carried the mass on group k's rim
    circle (:func:`carried_group`), else 0; the next step then takes that group on its half disc (:func:`half_discs`)."""
    return Y_U + 2 * ng


@njit(cache=True)
def half_discs(y, rim, ult=-1):
    """The groups whose set for a step from y is the disc of radius c̄/2 tangent inside the rim at ū (bit k for group
    k; :func:`group_return`): every group when the mass is held on the ultimate circle (``ult`` = 1, or with ``ult``
    = -1 :func:`at_ultimate` of y), the carrying group when the step that ended in y carried the mass on its rim
    circle and it is still on its rim."""
    ng = rim.shape[0]
    if ult == 1 or (ult < 0 and at_ultimate(y, rim)):
        return (1 << ng) - 1
    k = int(y[carry_slot(ng)]) - 1
    if k >= 0 and y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2 >= (rim[k] * (1.0 - RIM_ON)) ** 2:
        return 1 << k
    return 0


@njit(cache=True)
def _velocity_along(out, t1, t2):
    """Turn the step's end velocity onto the unit tangent (t1, t2) of the circle the mass moves on, its magnitude and
    its sense along the tangent kept."""
    vn = math.sqrt(out[Y_V] ** 2 + out[Y_V + 1] ** 2)
    sg = 1.0 if out[Y_V] * t1 + out[Y_V + 1] * t2 >= 0.0 else -1.0
    out[Y_V] = sg * vn * t1
    out[Y_V + 1] = sg * vn * t2


@njit(cache=True)
def carried_group(y, mask, rim):
    """The group that carries the mass on its rim circle in a step from y with be_step's mask: the only group that
    slid, on its rim at the step's start and end (the others held or stuck); -1 when there is none."""
    ng = rim.shape[0]
    slid = mask & ((1 << ng) - 1)
    if popcount(slid) != 1:
        return -1
    for k in range(ng):
        if slid >> k & 1:
            on_start = y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2 >= (rim[k] * (1.0 - RIM_ON)) ** 2
            return k if (on_start and mask >> (ng + k) & 1) else -1
    return -1


@njit(cache=True)
def group_return(rx, ry, y, k, rb, mu, rim, half):
    """:func:`element_return` of group k in the state y; with bit k of ``half`` set (:func:`half_discs`: held on the
    ultimate circle, or the group carrying the mass on its rim) the group's set for the step is the disc of radius
    c̄/2 tangent inside its rim at ū, not the rim's disc.

    Why: with the mass held on the ultimate circle |X| = Σ c̄ (every group on its rim, along one direction), the
    bearing leaves the circle when the rims' reaction λ = F·e + |V|²/|X| falls to 0 (F the force per unit mass
    without the rims).  A backward-Euler step from the circle with V along its tangent ends at X + hV − h²F: inside
    the circle when 2|X| h² F_in > h²|V|² — the test λ' = −F_in + |V|²/(2|X|) < 0, half the centripetal need, so
    between λ' < 0 < λ the steps left the circle and came back in micro-impacts (PTS ×2 double: ~400, impulse 1.6 %
    high, balance open 2.5e-5).  On the disc of radius c̄_k/2 tangent at ū_k (curvature 2/c̄_k) the step's chord
    test is |δ|² + c̄_k δ·e ≤ 0: for aligned groups turning together (δ_k ∝ c̄_k) the same for every group and for
    the mass, −F_in + |V|²/|X| — the exact λ.  The step's end on that disc is put back on the rim after it (outward
    by O(|δ|²/c̄): the motion is the projected one) and the velocity along the end's tangent (:func:`be_step`).

    The same holds for one group carrying the mass on its rim circle, the other groups held (:func:`carried_group`):
    the mass moves on that group's circle, and on the full disc the step saw half the centripetal need of the rim's
    reaction.  Chuetsu-oki 65025 ×1.556 with Fenz & Constantinou's TFP at µ × 1.4835 (the review's upper bound),
    25.5206 s: the inner group carried the mass at 1.21 m/s on its rim (c̄ 0.214 m), b = |ū|/R̄ = 0.357 W, and the
    step's r·e = 0.357 W (half of (|V|²/c̄ − a_g·e)/g = 0.71 W): the rim's reaction ν = r·e − b sat at 0 instead of
    0.35 W, so the steps left the rim and came back (the rim contacts counted in hundreds), the returns pushed the
    force to 1.1 W, where a held outer group slid (|(r − b₁)·t₁| = µ₁ with the rims 3° apart), and the steps fell
    to 1e-7 s until Newton failed ("found no force at t = 25.5209 s")."""
    u1 = y[Y_U + 2 * k]
    u2 = y[Y_U + 2 * k + 1]
    if not half >> k & 1:
        return element_return(rx, ry, u1, u2, rb[k], mu[k], rim[k])
    un = math.sqrt(u1 * u1 + u2 * u2)
    half = 0.5 * rim[k]
    e1 = u1 / un
    e2 = u2 / un
    c1 = u1 - half * e1
    c2 = u2 - half * e2
    return element_return(rx - c1 / rb[k], ry - c2 / rb[k], half * e1, half * e2, rb[k], mu[k], half)


@njit(cache=True)
def popcount(bits):
    """The number of set bits of a non-negative integer."""
    n = 0
    while bits:
        n += bits & 1
        bits >>= 1
    return n


@njit(cache=True)
def _psi_grad(rx, ry, y, rb, mu, rim, alpha, px, py, g, half=0, mx=1.0, my=1.0):
    # Ψ(r) of the module docstring and its gradient F = g M r + α ΔX(r) − p (M = diag(mx, my): be_step's metric)
    acc = 0.5 * g * (mx * rx * rx + my * ry * ry) - px * rx - py * ry
    fx = g * mx * rx - px
    fy = g * my * ry - py
    for k in range(rb.shape[0]):
        s1, s2, tk, _, _, _, _, state = group_return(rx, ry, y, k, rb, mu, rim, half)
        if state:
            acc += alpha * tk
            fx += alpha * s1
            fy += alpha * s2
    return acc, fx, fy


@njit(cache=True)
def _held(y, rb, mu, r1, r2):
    # r = (r1, r2) inside every friction circle
    for k in range(rb.shape[0]):
        d1 = r1 - y[Y_U + 2 * k] / rb[k]
        d2 = r2 - y[Y_U + 2 * k + 1] / rb[k]
        if d1 * d1 + d2 * d2 > mu[k] * mu[k]:
            return False
    return True


@njit(cache=True)
def rest_holds(y, rb, mu, rim, r1, r2):
    """Whether the force r = (r1, r2) [W] holds every group of the state y at rest: a group inside its friction
    circle, or a group on its rim inside its circle plus the rim's outward normals (the rim carries an outward push:
    :func:`rim_holds`, the step's optimality at δ = 0).  The loop's stick test (its break-away is the event kernel's
    ``breakaway`` with the groups on their rims ``held``) and be_step's test of a step without slip."""
    for k in range(rb.shape[0]):
        u1 = y[Y_U + 2 * k]
        u2 = y[Y_U + 2 * k + 1]
        d1 = r1 - u1 / rb[k]
        d2 = r2 - u2 / rb[k]
        if d1 * d1 + d2 * d2 <= mu[k] * mu[k]:
            continue
        if not rim_holds(d1, d2, u1, u2, mu[k], rim[k]):
            return False
    return True


@njit(cache=True)
def step_force(y, rb, mu, rim, alpha, px, py, g, rx, ry, mx=1.0, my=1.0, ult=-1):
    """The force r/W of one backward-Euler step: the minimiser of Ψ (module docstring), by Newton's method
    from the guess (rx, ry), the step cut back until Ψ or |∇Ψ| decreases.  Returns (rx, ry, iterations, evaluations
    of ∇Ψ).  ``mx, my``: Ψ's metric g r·M r/2 (be_step's per-direction masses; 1 for the rigid block); ``ult``: the
    step's classification of the ultimate (:func:`half_discs`)."""
    ng = rb.shape[0]
    half = half_discs(y, rim, ult)
    iso_m = mx == my
    # stuck: p/(g M) inside every circle is the answer (Ψ's gradient g M r − p vanishes there)
    if _held(y, rb, mu, px / (g * mx), py / (g * my)):
        return px / (g * mx), py / (g * my), 0, 0
    # one group sliding has a closed form: r − b_k ∥ p − g b_k, |r − b_k| = (|p − g b_k| + αR̄µ)/(g + αR̄); it is
    # the answer when that r lies inside every other circle, else the nearest such point starts Newton (the
    # valley of Ψ is curved along a circle: from far away the Cartesian steps crawl) — unless the guess lies lower
    best = np.inf
    guess_x = rx
    guess_y = ry
    for k in range(ng):
        b1 = y[Y_U + 2 * k] / rb[k]
        b2 = y[Y_U + 2 * k + 1] / rb[k]
        q1 = px - g * b1
        q2 = py - g * b2
        qn = math.sqrt(q1 * q1 + q2 * q2)
        if not qn > g * mu[k]:
            continue  # p/g inside circle k: group k does not slide alone
        w = alpha * rb[k]
        rho = (qn + w * mu[k]) / (g + w)
        cx = b1 + rho * q1 / qn
        cy = b2 + rho * q2 / qn
        # past its rim the closed form does not hold (it still starts Newton)
        lam = rb[k] * (rho - mu[k])
        past = (y[Y_U + 2 * k] + lam * q1 / qn) ** 2 + (y[Y_U + 2 * k + 1] + lam * q2 / qn) ** 2 > rim[k] * rim[k]
        if half >> k & 1:
            # on its half disc (at the ultimate, or carrying the mass) the group's set is the disc of radius c̄/2
            # tangent inside its rim at ū
            un = math.sqrt(y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2)
            w1 = 0.5 * rim[k] * y[Y_U + 2 * k] / un + lam * q1 / qn
            w2 = 0.5 * rim[k] * y[Y_U + 2 * k + 1] / un + lam * q2 / qn
            past = w1 * w1 + w2 * w2 > 0.25 * rim[k] * rim[k]
        worst = 1e-300 if past else 0.0
        for j in range(ng):
            if j != k:
                d1 = cx - y[Y_U + 2 * j] / rb[j]
                d2 = cy - y[Y_U + 2 * j + 1] / rb[j]
                worst = max(worst, math.sqrt(d1 * d1 + d2 * d2) - mu[j])
        if worst == 0.0 and iso_m:
            return cx, cy, 0, 0
        if worst < best:
            best = worst
            rx = cx
            ry = cy
    # |∇Ψ| below this is the rounding of its terms (g r and p)
    # and of α ΔX on the rims: a group on its rim returns to a point of its circle, rounded to ~1e-16 of c̄, and α ~ 1/h²
    # multiplies that rounding (an impact's step: α 2.7e7 1/s², c̄ 0.4 m, so |∇Ψ| cannot fall below ~1e-9 while
    # g r and p are ~1e4: without this term Newton ran its 60 iterations and their line searches on rounding, ~4000
    # gradients per solve, and the work bound stopped the run: the PTS ×2 double at 5.83 s)
    on_rims = 0.0
    for k in range(ng):
        if math.isfinite(rim[k]) and y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2 >= 0.25 * rim[k] * rim[k]:
            on_rims += rim[k]
    f_floor0 = 1e-15 * (abs(px) + abs(py) + g) + RIM_ROUNDING * alpha * on_rims
    # and of α Σ δ_k off the rims: a sliding group's slip R̄ (|r − b| − µ) near its circle rounds to ~R̄ ε (|b| + µ)
    # (the difference |r − b| − µ), times α (Superstition Hills PTS ×2.5 on the TFP, 2.9 s: two groups sliding at a closing corner, ∇Ψ's
    # rounding 1e-9 against the old floor 2e-12 and only g along the corner's soft direction, so Newton ran its 60
    # iterations on rounding in ordinary steps, ~3400 gradients per solve: the run hit the work bound at 12.76 s)
    slip_round = 0.0
    for k in range(ng):
        slip_round += rb[k] * (math.sqrt(y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2) / rb[k] + mu[k])
    f_floor = f_floor0 + SLIP_ROUNDING * alpha * slip_round
    r_scale = 0.0
    for k in range(ng):
        r_scale = max(r_scale, mu[k])
    psi, fx, fy = _psi_grad(rx, ry, y, rb, mu, rim, alpha, px, py, g, half, mx, my)
    evals = 1
    if best < np.inf:
        # Newton starts from the lower of the guess (the last step's force) and that point: with one group sliding
        # along its rim and another inside at its circle, 7° apart, the one-group point lay 0.07 W off along the
        # rim's strip and Newton crawled back along it, 0.003 W an iteration (26–57 iterations a solve, ~300–940
        # gradients a step); the guess, 3e-5 W off, converges in a few (NWH360 ×1.2 on the double with an
        # intermediate rim, 3.0–3.058 s: the work bound; docs/multisurface.md, "Once per step")
        psi_g, gx, gy = _psi_grad(guess_x, guess_y, y, rb, mu, rim, alpha, px, py, g, half, mx, my)
        evals += 1
        if psi_g < psi:
            rx = guess_x
            ry = guess_y
            fx = gx
            fy = gy
    cm = np.zeros(ng)
    cv = np.zeros((ng, 2))
    it = 0
    while it < MAX_NEWTON:
        it += 1
        f0 = math.sqrt(fx * fx + fy * fy)
        if f0 <= f_floor:
            break
        # H = (g + a) I + Σ c_k m_k m_kᵀ; its determinant from the parts, each ≥ 0: (g + a)² + (g + a) Σ c_k +
        # Σ_{j<k} c_j c_k (m_j × m_k)² (h11 h22 − h12² cancels to nothing when a rank-one term of a rim is huge)
        iso = g * mx
        h12 = 0.0
        h11 = 0.0
        h22 = 0.0
        csum = 0.0
        cross = 0.0
        for k in range(ng):
            _, _, _, ak, ck, m1, m2, state = group_return(rx, ry, y, k, rb, mu, rim, half)
            if state:
                iso += alpha * ak
                ck *= alpha
                for j in range(k):
                    if cm[j] > 0.0:
                        w = cv[j, 0] * m2 - cv[j, 1] * m1
                        cross += cm[j] * ck * w * w
                cm[k] = ck
                cv[k, 0] = m1
                cv[k, 1] = m2
                h11 += ck * m1 * m1
                h12 += ck * m1 * m2
                h22 += ck * m2 * m2
                csum += ck
            else:
                cm[k] = 0.0
        s11 = h11
        s22 = h22
        h11 += iso
        h22 += iso + g * (my - mx)
        det = iso * iso + iso * csum + cross  # ≥ g² > 0: Ψ is g-strongly convex
        if not iso_m:
            # diag(p, q) + Σ c_k m_k m_kᵀ: pq + p Σ c_k m_k2² + q Σ c_k m_k1² + the same cross terms, each ≥ 0
            q_m = iso + g * (my - mx)
            det = iso * q_m + iso * s22 + q_m * s11 + cross
        # Newton's step in H's eigenbasis, a component of ∇Ψ at or below its rounding floor left out: on a rim H is
        # ~α/D along the tangent and only g along the normal (PTS ×2 double, 5.83 s: 7.6e10 and 9.8), so the floor's
        # rounding of the normal part (~1e-7 there) made a normal step of 1e-8 that swamped the tangential 5e-14 the
        # answer needed, and the line search's φ' was rounding of both signs: 60 iterations, ~4000 gradients
        tr = h11 + h22
        lam_big = 0.5 * (tr + math.sqrt((h11 - h22) ** 2 + 4.0 * h12 * h12))
        lam_small = det / lam_big
        a1 = h11 - lam_small
        a2 = h12
        b1 = h12
        b2 = h22 - lam_small
        if a1 * a1 + a2 * a2 < b1 * b1 + b2 * b2:
            a1 = b1
            a2 = b2
        an = math.sqrt(a1 * a1 + a2 * a2)
        if an > 0.0:
            a1 /= an
            a2 /= an
        else:
            a1 = 1.0
            a2 = 0.0
        f_big = fx * a1 + fy * a2
        f_small = -fx * a2 + fy * a1
        if abs(f_big) <= f_floor:
            f_big = 0.0
        if abs(f_small) <= f_floor:
            f_small = 0.0
        if f_big == 0.0 and f_small == 0.0:
            break
        s1 = -(f_big / lam_big) * a1 + (f_small / lam_small) * a2
        s2 = -(f_big / lam_big) * a2 - (f_small / lam_small) * a1
        if it <= NEWTON_PLAIN:
            # the plain step first: the truncated one, taken from the start, moved the 35° pulse of the tests through
            # regimes IV and V by 3e-6 of the peak (1e-6 asserted, within it before)
            s1 = -(h22 * fx - h12 * fy) / det
            s2 = -(-h12 * fx + h11 * fy) / det
        if abs(s1) + abs(s2) <= 4e-16 * (abs(rx) + abs(ry) + r_scale):
            # the correction is below the rounding of r
            break
        # the step along s: Ψ is convex and C¹, so φ'(t) = ∇Ψ(r + t s)·s grows with t; the full step is taken when
        # φ'(1) ≤ |φ'(0)|/2 (past a kink the Hessian of the start does not see, e.g. a group that starts sliding or
        # leaves its rim inside the step, it is not), else a t in (0, 1) with |φ'(t)| ≤ |φ'(0)|/2 by regula falsi
        # (Illinois) on φ' — signs of the gradient, not differences of Ψ, which rounding swamps when r is large
        d0 = fx * s1 + fy * s2
        if not d0 < 0.0:
            break  # no descent left above rounding
        _, gx, gy = _psi_grad(rx + s1, ry + s2, y, rb, mu, rim, alpha, px, py, g, half, mx, my)
        evals += 1
        d1 = gx * s1 + gy * s2
        t = 1.0
        if d1 > -0.5 * d0:
            ta = 0.0
            da = d0
            tb = 1.0
            db = d1
            side = 0
            found = False
            for _ in range(100):
                span = db - da
                t = (ta * db - tb * da) / span if span > 0.0 else 0.5 * (ta + tb)
                if not (ta < t < tb):
                    t = 0.5 * (ta + tb)
                    if not (ta < t < tb):
                        break
                _, gx, gy = _psi_grad(rx + t * s1, ry + t * s2, y, rb, mu, rim, alpha, px, py, g, half, mx, my)
                evals += 1
                dt = gx * s1 + gy * s2
                if abs(dt) <= -0.5 * d0:
                    found = True
                    break
                if dt < 0.0:
                    ta = t
                    da = dt
                    if side == -1:
                        db *= 0.5
                    side = -1
                else:
                    tb = t
                    db = dt
                    if side == 1:
                        da *= 0.5
                    side = 1
            if not found:
                if ta == 0.0:
                    break  # the bracket closed at the start: r is the minimiser to rounding
                t = ta
                _, gx, gy = _psi_grad(rx + t * s1, ry + t * s2, y, rb, mu, rim, alpha, px, py, g, half, mx, my)
                evals += 1
        rx += t * s1
        ry += t * s2
        fx = gx
        fy = gy
    if it >= MAX_NEWTON and math.sqrt(fx * fx + fy * fy) > f_floor:
        # Newton did not converge: the minimiser sits on kinks of Ψ that the Hessian of no single point sees (groups
        # held on their rims pointing nearly the same way, whose tangential strips |(r − b_k)·t_k| ≤ µ_k bound a long
        # thin valley, another group sliding: Chuetsu-oki 65025 at 26.988 s, two rims 0.7° apart; the steps zig-zag
        # along the valley's edges).  The central-cut ellipsoid method on ∇Ψ converges for any convex function: the
        # minimiser lies within |∇Ψ(r)|/g of r (Ψ is g-strongly convex), and each cut keeps the half-ellipse
        # {∇Ψ(c)·(r − c) ≤ 0} that holds it, the area falling by 0.77 per gradient; it stops when ∇Ψ is rounding or
        # the ellipse is below the rounding of r
        rad = math.sqrt(fx * fx + fy * fy) / (g * min(mx, my))
        f0x = fx
        f0y = fy
        p11 = rad * rad
        p12 = 0.0
        p22 = rad * rad
        cx = rx
        cy = ry
        solved = False
        for _ in range(MAX_ELLIPSOID):
            if math.sqrt(fx * fx + fy * fy) <= f_floor:
                solved = True
                break
            gpg = p11 * fx * fx + 2.0 * p12 * fx * fy + p22 * fy * fy
            if not gpg > 0.0:
                break
            sq = math.sqrt(gpg)
            q1 = (p11 * fx + p12 * fy) / sq
            q2 = (p12 * fx + p22 * fy) / sq
            cx -= q1 / 3.0
            cy -= q2 / 3.0
            p11 = 4.0 / 3.0 * (p11 - 2.0 / 3.0 * q1 * q1)
            p12 = 4.0 / 3.0 * (p12 - 2.0 / 3.0 * q1 * q2)
            p22 = 4.0 / 3.0 * (p22 - 2.0 / 3.0 * q2 * q2)
            _, fx, fy = _psi_grad(cx, cy, y, rb, mu, rim, alpha, px, py, g, half, mx, my)
            evals += 1
            if math.sqrt(max(p11 + p22, 0.0)) <= 4e-16 * (abs(cx) + abs(cy) + r_scale):
                solved = True
                break
        if solved or math.sqrt(fx * fx + fy * fy) <= math.sqrt(f0x * f0x + f0y * f0y):
            rx = cx
            ry = cy
        else:
            fx = f0x
            fy = f0y
        if not solved and math.sqrt(fx * fx + fy * fy) > 1e-6 * (abs(px) + abs(py) + g * (abs(rx) + abs(ry))):
            return rx, ry, -1, evals  # not converged: the gradient is not rounding
    return rx, ry, it, evals


@njit(cache=True)
def be_step(y, h, abar_x, abar_y, g, c, rb, mu, rim, rguess, out, rout, m_x=1.0, m_y=1.0, ult=-1, block=False,
            leave=False, x_balance=False):
    """One backward-Euler step of length h [s] from the state y into out; the force r/W into rout[:2], the evaluations
    of Ψ's gradient it took into rout[2].

    ``m_x, m_y``: the slab's mass per direction (per unit of the mass g r acts on; 1 for the rigid block), the
    balance m_d (V'_d − V_d)/h + c V'_d = −g r_d − ā_d: Ψ gets the metric M_d = (1 + ch)/(m_d + ch) and the
    momentum p_d = M_d (m_d V_d/h − ā_d) (a building's floors that differ along x and y).

    ``ult``: the step's classification of the ultimate (1 held on the ultimate circle, 0 not), given by the caller
    for the whole step and its two halves alike (planar_multisurface_stepper); -1 takes :func:`at_ultimate` of y,
    and the velocity is then turned onto the ultimate circle only when the end is aligned too.

    ``block``: the rigid block's steps and the building's (isotropic and anisotropic): a step without slip whose
    force needed to hold the mass leaves a group's held set takes V from the momentum balance, and a group carries
    the mass only if its return slid along its rim (docs/multisurface.md, "A restart below the rounding").

    ``leave``: held on the ultimate circle, the velocity is turned onto its tangent only when every group that slid
    slid along its rim (its return on the rim, not inside it to a rounding of it): a group leaving its rim inward from
    rest slips ~A h² ≪ RIM_ON c̄ and ends "on its rim", and turned, the inward velocity was lost in every step (the
    building's steps and the rigid block's three solves set it: docs/building.md, h220's section, docs/multisurface.md,
    h225's; the rigid block's stop probes leave it False).

    ``x_balance``: where every group that slid returned inside its rim (none on its rim at the end, none on a half
    disc), X moves by h V' (V' the momentum balance's) instead of the sum of the groups' slips, equal in exact
    arithmetic, and the group that slid most takes the difference: the slips move in quanta of R̄ ulp(r) whatever h,
    and their sum drifted by ~7e-18 m a step (the building's isotropic steps set it: docs/building.md, h224's
    section; the rigid block's leave it False).

    Returns the bit set of the groups that slid, and above it (shifted by the number of groups) the bit
    set of the groups on their rims at the step's end (|ū| ≥ c̄ (1 − RIM_ON))."""
    ng = rb.shape[0]
    alpha = (1.0 + c * h) / (h * h)
    unit = m_x == 1.0 and m_y == 1.0
    met_x = 1.0
    met_y = 1.0
    if unit:
        px = y[Y_V] / h - abar_x
        py = y[Y_V + 1] / h - abar_y
    else:
        met_x = (1.0 + c * h) / (m_x + c * h)
        met_y = (1.0 + c * h) / (m_y + c * h)
        px = met_x * (m_x * y[Y_V] / h - abar_x)
        py = met_y * (m_y * y[Y_V + 1] / h - abar_y)
    given = ult >= 0
    if not given:
        ult = 1 if at_ultimate(y, rim) else 0
    rx, ry, iterations, evals = step_force(y, rb, mu, rim, alpha, px, py, g, rguess[0], rguess[1], met_x, met_y, ult)
    half = half_discs(y, rim, ult)
    rout[0] = rx
    rout[1] = ry
    rout[2] = evals
    dx1 = 0.0
    dx2 = 0.0
    fric = 0.0
    mask = np.int64(0)
    along = 0  # the groups whose return slid along their rims (state 2), not inside to a rounding of them
    for k in range(ng):
        u1 = y[Y_U + 2 * k]
        u2 = y[Y_U + 2 * k + 1]
        v1, v2, _, _, _, _, _, state = group_return(rx, ry, y, k, rb, mu, rim, half)
        if state == 1 or state == 2:
            if state == 2:
                along |= 1 << k
                # on the circle exactly (the return's w, not ū + δ rounded)
                w1 = u1 + v1
                w2 = u2 + v2
                wn = math.sqrt(w1 * w1 + w2 * w2)
                scale = rim[k] / wn if wn > 0.0 else 1.0
                out[Y_U + 2 * k] = w1 * scale
                out[Y_U + 2 * k + 1] = w2 * scale
                if half >> k & 1:
                    # the half disc's point put on the rim (outward by O(δ²/c̄)): the motion is the projected one
                    v1 = out[Y_U + 2 * k] - u1
                    v2 = out[Y_U + 2 * k + 1] - u2
            else:
                out[Y_U + 2 * k] = u1 + v1
                out[Y_U + 2 * k + 1] = u2 + v2
            dx1 += v1
            dx2 += v2
            fric += g * mu[k] * math.sqrt(v1 * v1 + v2 * v2)
            mask |= 1 << k
        else:
            out[Y_U + 2 * k] = u1
            out[Y_U + 2 * k + 1] = u2
        if out[Y_U + 2 * k] ** 2 + out[Y_U + 2 * k + 1] ** 2 >= (rim[k] * (1.0 - RIM_ON)) ** 2:
            mask |= 1 << (ng + k)
    out[Y_X] = y[Y_X] + dx1
    out[Y_X + 1] = y[Y_X + 1] + dx2
    # V from the momentum balance rather than ΣΔ/h (equal in exact arithmetic): the slips' rounding divided
    # by a small step would swamp the error estimate
    if not unit and (mask & ((1 << ng) - 1) or (block and not rest_holds(y, rb, mu, rim, px / (met_x * g),
                                                                            py / (met_y * g)))):
        # (``block`` with unequal masses: the force needed to hold the slab, (m V/h − ā)/g per direction, leaves a
        # group's held set — the anisotropic building leaving a rim inward from rest; docs/building.md, session 25)
        out[Y_V] = (m_x * y[Y_V] - h * (g * rx + abar_x)) / (m_x + c * h)
        out[Y_V + 1] = (m_y * y[Y_V + 1] - h * (g * ry + abar_y)) / (m_y + c * h)
    elif mask & ((1 << ng) - 1) or (unit and block and not rest_holds(y, rb, mu, rim, px / g, py / g)):
        # (the rigid block: also when no group's slip rose above the rounding of its ū — ~1e-17 m, A h² at a start
        # from rest with h ≲ 3e-9 s — while p/g leaves a group's held set: the mass moves, V = h A.  Zeroed there, a
        # restart from a stop was lost in every step the step-doubling allowed (the full step slid, its halves
        # did not: the estimate |V|/tol): 70,000 steps of 2.6e-24 … 1.1e-9 s until the step bound (NWH360 ×1.2 with
        # the reversed record ×0.72 on the double with an intermediate rim, step_tol 3e-10, 0.9124 s;
        # docs/multisurface.md, "A restart below the rounding")
        out[Y_V] = (y[Y_V] - h * (g * rx + abar_x)) / (1.0 + c * h)
        out[Y_V + 1] = (y[Y_V + 1] - h * (g * ry + abar_y)) / (1.0 + c * h)
    else:
        out[Y_V] = 0.0
        out[Y_V + 1] = 0.0
    if x_balance and mask & ((1 << ng) - 1) and not mask >> ng and not along and not half and iterations >= 0:
        # X from the same balance, X + h V' (ΣΔ in exact arithmetic), where every group that slid returned inside its
        # rim (no projection onto a rim, no velocity turned after this): a group's slip moves in quanta of
        # R̄ ulp(r) (~1.7e-17 m on IELC's double, whatever h), with a bias, and X summed them — AOM017 ×1.5's 1 mm
        # slide erred by 4.3e-9 of its peak at step_tol 1e-10 (43 step_tol; docs/building.md, h224's section).  The
        # difference goes to the group that slid most, so that X stays the groups' sum (the rims and the ultimate
        # are |ū_k| = c̄_k: X apart from Σū by the differences summed passed the ultimate by 1e-12 of it)
        e1 = h * out[Y_V] - dx1
        e2 = h * out[Y_V + 1] - dx2
        most = -1
        d_most = -1.0
        for k in range(ng):
            if mask >> k & 1:
                d_k = (out[Y_U + 2 * k] - y[Y_U + 2 * k]) ** 2 + (out[Y_U + 2 * k + 1] - y[Y_U + 2 * k + 1]) ** 2
                if d_k > d_most:
                    most = k
                    d_most = d_k
        out[Y_U + 2 * most] += e1
        out[Y_U + 2 * most + 1] += e2
        dx1 += e1
        dx2 += e2
        out[Y_X] = y[Y_X] + dx1
        out[Y_X + 1] = y[Y_X + 1] + dx2
    out[Y_EIN] = y[Y_EIN] - (abar_x * dx1 + abar_y * dx2)
    out[Y_EF] = y[Y_EF] + fric
    out[Y_EV] = y[Y_EV] + c * (dx1 * dx1 + dx2 * dx2) / h
    out[Y_EIMP] = y[Y_EIMP]
    carried = -1 if ult == 1 else carried_group(y, mask, rim)
    if block and carried >= 0 and not along >> carried & 1:
        # (the rigid block) a group sliding inward off its rim by less than the rounding of ū (its slip ~A h² below
        # ~1e-17 m in a short step) ends "on its rim" but does not carry the mass: turned onto the rim's tangent,
        # its inward velocity was lost in every such step and the mass crept along the rim at ~5e-9 m/s under an
        # inward pull of 0.16 W (step_tol 3e-10, 0.9125 s of NWH360 ×1.2 on the double with an intermediate rim;
        # docs/multisurface.md, "A restart below the rounding")
        carried = -1
    # the carrying group for the next step: this step's, else the one that carried into this step while it goes on
    # sliding along its rim with other groups sliding too (the mass is then free, and the force is set by their
    # frictions' tangential balances, the same to O(h) on either disc; on the full disc the next step that carries
    # the mass again would see half the centripetal need: Chuetsu-oki 65025's upper bound at 26.3237 s, the inner
    # group carrying on its rim and surface 1's group 3.8° behind, at its friction: the two discs chattered)
    k = int(y[carry_slot(ng)]) - 1
    if carried < 0 and ult == 0 and k >= 0 and half >> k & 1 and mask >> k & 1 and mask >> (ng + k) & 1:
        out[carry_slot(ng)] = k + 1.0
    else:
        out[carry_slot(ng)] = carried + 1.0
    if (ult == 1 and mask >> ng == (1 << ng) - 1 and (given or at_ultimate(out, rim))
            and not (leave and mask & ((1 << ng) - 1) & ~along)):
        # held on the ultimate circle from start to end: the velocity along the end's tangent, its magnitude kept
        s1, s2, sn = _groups_sum(out, ng)
        _velocity_along(out, -s2 / sn, s1 / sn)
    elif carried >= 0:
        # one group sliding, along its rim, the others not sliding: the mass is carried on that group's rim circle
        # (centred at the other groups' sum), so its velocity is along that circle's tangent at the end, its
        # magnitude kept — the backward-Euler velocity is the chord's, outward at the end by w²h/(2c̄), and the next
        # step's force then depended on the previous step's length (the full and half steps disagreed by ~0.2 W on
        # the rim's reaction, and the steps shrank to tol |V| / 2 m/s² ~ 1e-7 s: the misaligned ultimate)
        _velocity_along(out, -out[Y_U + 2 * carried + 1] / rim[carried], out[Y_U + 2 * carried] / rim[carried])
    elif (mask >> ng == (1 << ng) - 1 and ultimate_impact(y, out, g, rb) > 0.0
            and iterations < 0):
        # an impact in a short step: the normal part of Newton's residual is the impulse's rounding (α ~ 1/h² times
        # the last bit of a position on the rim), gone with the outward velocity; its tangential part moves V by
        # h times it at most, which must be rounding too, else the force is not found
        _, fx, fy = _psi_grad(rx, ry, y, rb, mu, rim, alpha, px, py, g, half, met_x, met_y)
        xn = math.sqrt(out[Y_X] ** 2 + out[Y_X + 1] ** 2)
        ft = abs(fx * out[Y_X + 1] - fy * out[Y_X]) / xn if xn > 0.0 else math.sqrt(fx * fx + fy * fy)
        if h * ft <= 1e-9 * (math.sqrt(y[Y_V] ** 2 + y[Y_V + 1] ** 2) + h * g):
            iterations = 0
    if iterations < 0:
        mask |= UNSOLVED
    return mask


@njit(cache=True)
def ultimate_impact(y, out, g, rb):
    """The plastic impact at the ultimate displacement, at the end of a step from y that put every group on its rim.

    With the groups on their rims along one direction ē (within :data:`ALIGNED`), the rims admit no outward
    velocity with a finite force: the velocity's outward part V·ē > 0 is removed (a rigid stop, coefficient of
    restitution 0; Fenz & Constantinou's ultimate).  The backward-Euler step that arrived there already bore the
    rim's reaction (its position is on the rims to the last bit, as every rim is put: :func:`rim_return`); the
    kinetic energy its reaction and the removal took — the step's whole energy defect, input less the changes
    of kinetic and stored energy, friction and viscous work — goes to the impact energy, so the balance closes.
    It is taken on arrival only: a step that starts held on the ultimate circle (:func:`at_ultimate`) keeps the mass
    on it in the step itself (:func:`be_step`), so the velocity removed here is always an impact's (booked and
    counted).
    Returns the velocity removed [m/s] (0 when none)."""
    ng = rb.shape[0]
    s1, s2, sn = _groups_sum(out, ng)
    if not sn > 0.0:
        return 0.0
    e1 = s1 / sn
    e2 = s2 / sn
    for k in range(ng):
        u1 = out[Y_U + 2 * k]
        u2 = out[Y_U + 2 * k + 1]
        if abs(u1 * e2 - u2 * e1) > ALIGNED * math.sqrt(u1 * u1 + u2 * u2) or u1 * e1 + u2 * e2 <= 0.0:
            return 0.0
    vn = out[Y_V] * e1 + out[Y_V + 1] * e2
    if not vn > 0.0:
        return 0.0
    out[Y_V] -= vn * e1
    out[Y_V + 1] -= vn * e2
    defect = ((out[Y_EIN] - y[Y_EIN]) - 0.5 * (out[Y_V] ** 2 + out[Y_V + 1] ** 2 - y[Y_V] ** 2 - y[Y_V + 1] ** 2)
              - (out[Y_EF] - y[Y_EF]) - (out[Y_EV] - y[Y_EV]))
    for k in range(ng):
        defect -= g * ((out[Y_U + 2 * k] ** 2 + out[Y_U + 2 * k + 1] ** 2)
                       - (y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2)) / (2.0 * rb[k])
    out[Y_EIMP] += defect
    return vn


@njit(cache=True)
def arrival_time(y, rim):
    """The time [s] the mass in the state y takes to the ultimate circle |X| = Σ c̄ at its outward speed, every group
    on its rim (not yet along one direction: :func:`at_ultimate`) and the mass moving outward; -1 otherwise.

    The gap to the circle, Σ c̄ − |Σ ū|, falls as the groups close into alignment (∝ the square of their angles);
    measured on Chuetsu-oki 65025 (the lower bound, 24.4088 s) this first-order estimate matched the steps' own
    arrival to 1e-4 of it from 4e-7 s down to 1e-11 s before it (the outward speed 0.8925 → 0.8922 m/s)."""
    ng = rim.shape[0]
    if at_ultimate(y, rim):
        return -1.0
    total = 0.0
    for k in range(ng):
        if y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2 < (rim[k] * (1.0 - RIM_ON)) ** 2:
            return -1.0
        total += rim[k]
    s1, s2, sn = _groups_sum(y, ng)
    if not sn > 0.0:
        return -1.0
    vn = (y[Y_V] * s1 + y[Y_V + 1] * s2) / sn
    if not vn > 0.0:
        return -1.0
    return max(total - sn, 0.0) / vn


@njit(cache=True)
def arrive(y, dt, abar_x, abar_y, g, c, mu, rim, out):
    """The move of the last ``dt`` [s] before the ultimate into out: X moved at the velocity of y, every group put on
    its rim along X's direction, the work of that move booked (input −ā·ΔX, friction Σ g µ_k |Δū_k|, viscous
    c|ΔX|²/dt); the velocity is left for :func:`ultimate_impact` (its outward part removed, the energy defect booked
    as the impact's), the carried slot cleared.  The rims' reaction over dt (∝ 1/√ of the time left) is not in it:
    the caller takes its impulse, 2 dt g r·ē, off the outward velocity before the impact."""
    ng = rim.shape[0]
    for j in range(out.shape[0]):
        out[j] = y[j]
    x1 = y[Y_X] + dt * y[Y_V]
    x2 = y[Y_X + 1] + dt * y[Y_V + 1]
    xn = math.sqrt(x1 * x1 + x2 * x2)
    e1 = x1 / xn
    e2 = x2 / xn
    dx1 = 0.0
    dx2 = 0.0
    fric = 0.0
    for k in range(ng):
        d1 = rim[k] * e1 - y[Y_U + 2 * k]
        d2 = rim[k] * e2 - y[Y_U + 2 * k + 1]
        out[Y_U + 2 * k] = rim[k] * e1
        out[Y_U + 2 * k + 1] = rim[k] * e2
        dx1 += d1
        dx2 += d2
        fric += g * mu[k] * math.sqrt(d1 * d1 + d2 * d2)
    out[Y_X] = y[Y_X] + dx1
    out[Y_X + 1] = y[Y_X + 1] + dx2
    out[Y_EIN] = y[Y_EIN] - (abar_x * dx1 + abar_y * dx2)
    out[Y_EF] = y[Y_EF] + fric
    out[Y_EV] = y[Y_EV] + c * (dx1 * dx1 + dx2 * dx2) / dt
    out[carry_slot(ng)] = 0.0


@njit(cache=True)
def groups_within_rims(y, ub, rim):
    """The groups' displacements ū of the state ``y`` into ``ub`` (a row per group of ``rim``); False when one lies
    outside its rim (a guard: the rim's return keeps every group on or inside its circle)."""
    inside = True
    for k in range(rim.shape[0]):
        ub[k, 0] = y[Y_U + 2 * k]
        ub[k, 1] = y[Y_U + 2 * k + 1]
        if ub[k, 0] ** 2 + ub[k, 1] ** 2 > (rim[k] * (1.0 + 1e-9)) ** 2:
            inside = False
    return inside


@njit(cache=True)
def arrival_step(y, rim, r, g, h, hi, tau):
    """The next step's length and whether it is the move onto the ultimate (``arrive``), before a step of ``h`` at
    ``tau`` in a sample interval of ``hi``: with every group on its rim closing into alignment and the mass moving
    outward (:func:`arrival_time`), the steps end ``ARRIVAL_FRACTION`` × hi before the arrival, and the last of it
    is one move when the force of the last step (``r``, in units of ``g``) could not stop the outward speed in that
    time.

    Returns
    -------
    tuple
        ``(h, jump)``.
    """
    t_arr = arrival_time(y, rim)
    if t_arr > 0.0:
        t_jump = ARRIVAL_FRACTION * hi
        if 1.01 * t_jump < t_arr < t_jump + h and t_arr - t_jump < hi - tau:
            return t_arr - t_jump, False
        if (t_arr <= 1.01 * t_jump and t_arr < hi - tau
                and 2.0 * t_arr * g * math.sqrt(r[0] * r[0] + r[1] * r[1])
                < (y[Y_V] * y[Y_X] + y[Y_V + 1] * y[Y_X + 1]) / math.sqrt(y[Y_X] ** 2 + y[Y_X + 1] ** 2)):
            return t_arr, True
    return h, False


@njit(cache=True)
def put_on_rims(y, rim, bits):
    """Put the groups in ``bits`` of the state y on their rims (ū_k scaled to |ū_k| = c̄_k), X moved with them."""
    for k in range(rim.shape[0]):
        if bits >> k & 1:
            u1 = y[Y_U + 2 * k]
            u2 = y[Y_U + 2 * k + 1]
            un = math.sqrt(u1 * u1 + u2 * u2)
            if un > 0.0:
                y[Y_U + 2 * k] = u1 * rim[k] / un
                y[Y_U + 2 * k + 1] = u2 * rim[k] / un
                y[Y_X] += y[Y_U + 2 * k] - u1
                y[Y_X + 1] += y[Y_U + 2 * k + 1] - u2


@njit(cache=True)
def accept_step(y, y1, y2, ny, keep, ng, rim, m1, mh, m2, jump, from_rest=False):
    """The accepted step's end state, written over ``y`` (which holds the step's start).

    The Richardson combination 2 y2 − y1 of the whole step ``y1`` and the two halves ``y2`` (second order) where the
    same groups slid in the three solves (masks ``m1``, ``mh``, ``m2``), nothing jumped (``jump``: an impact) and the
    velocity kept its sense; across a change of the sliding set (a stop, a start, a join) or a reversal (the friction
    turns over) the error expansion does not hold and the two halves are kept.  ``from_rest``: the step starts at
    V = 0 at a located event (a reversal or a break-away the caller cut the previous step at), so the motion is
    smooth over the whole step and the velocity's sense is the step's own: combined where the masks agree.  ``y[keep]`` is the halves' (an energy
    the combination does not take).  A group on its rim in all three solves is put back on its circle after the
    combination (the chord of two points on it lies inside by O(h²)), X moved with it; when the extrapolation of a
    group arriving at its rim crossed it, the halves are kept.
    """
    low = (1 << ng) - 1
    if (not jump and m1 == mh and mh == m2
            and (y[Y_V] * y2[Y_V] + y[Y_V + 1] * y2[Y_V + 1] > 0.0 or m2 & low == 0
                 or (from_rest and y[Y_V] == 0.0 and y[Y_V + 1] == 0.0))):
        for j in range(ny):
            y[j] = 2.0 * y2[j] - y1[j]
        y[keep] = y2[keep]
        for k in range(ng):
            if not m2 >> (ng + k) & 1 and y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2 > rim[k] * rim[k]:
                for j in range(ny):
                    y[j] = y2[j]
                return
        put_on_rims(y, rim, m2 >> ng)
    else:
        for j in range(ny):
            y[j] = y2[j]


@njit(cache=True)
def vertical_work(y0, y1, rb, dn):
    """Book into y1's input the work of the vertical motion over a step from y0 to y1 in which n rose by ``dn``
    [m/s²]: the step took n at its mean n̄ (linear in time), so its stored-energy change is n̄ ΔP (P = Σ|ū_k|²/(2R̄_k)),
    and n_1 P_1 − n_0 P_0 = n̄ ΔP + dn (P_0 + P_1)/2 exactly: the balance closes as without a vertical."""
    p0 = 0.0
    p1 = 0.0
    for k in range(rb.shape[0]):
        p0 += (y0[Y_U + 2 * k] ** 2 + y0[Y_U + 2 * k + 1] ** 2) / (2.0 * rb[k])
        p1 += (y1[Y_U + 2 * k] ** 2 + y1[Y_U + 2 * k + 1] ** 2) / (2.0 * rb[k])
    y1[Y_EIN] += 0.5 * dn * (p0 + p1)


@njit(cache=True)
def departing_carrier(y, m1, mh, m2, rim):
    """The group k that a step from y (not at the ultimate, carrying nothing: :func:`carry_slot` 0) takes off its rim
    while carrying the mass: k on its rim at y, the only group sliding in the step's three solves (masks m1, mh, m2 of
    :func:`be_step`), off its rim at the end of one of them; else -1.  Such a departure is the full disc's verdict,
    which sees half the centripetal need of the mass carried on k's rim circle (:func:`group_return`): the loop
    retakes the step on k's half disc (the exact rim reaction), and keeps the departure only if it holds there."""
    ng = rim.shape[0]
    if int(y[carry_slot(ng)]) != 0:
        return -1
    low = (1 << ng) - 1
    slid = m1 & low
    if popcount(slid) != 1 or mh & low != slid or m2 & low != slid:
        return -1
    k = 0
    while not slid >> k & 1:
        k += 1
    if y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2 < (rim[k] * (1.0 - RIM_ON)) ** 2:
        return -1  # not on its rim at the step's start
    if (m1 & mh & m2) >> (ng + k) & 1:
        return -1
    return k


@njit(cache=True)
def three_solves(y, h, tau, raw, c, rb, mu, rim, r, y1, yh, y2, r1, rh, r2, ult):
    """The step's three backward-Euler solves from y at τ [s] in its sample interval: the whole step of h into y1, its
    halves into yh and y2 (forces and evaluations into r1, rh, r2), the ground's acceleration and n at each solve's
    middle (``raw`` = a_x, its slope, a_y, its slope, n, its slope at the interval's start), the vertical's work
    booked (:func:`vertical_work`).  ``ult``: the ultimate classified once for the three (:func:`be_step`).
    Returns the three masks of :func:`be_step`."""
    m1 = be_step(y, h, raw[0] + raw[1] * (tau + 0.5 * h), raw[2] + raw[3] * (tau + 0.5 * h),
                 raw[4] + raw[5] * (tau + 0.5 * h), c, rb, mu, rim, r, y1, r1, 1.0, 1.0, ult, np.bool_(True), np.bool_(True))
    mh = be_step(y, 0.5 * h, raw[0] + raw[1] * (tau + 0.25 * h), raw[2] + raw[3] * (tau + 0.25 * h),
                 raw[4] + raw[5] * (tau + 0.25 * h), c, rb, mu, rim, r1, yh, rh, 1.0, 1.0, ult, np.bool_(True), np.bool_(True))
    if raw[5] != 0.0:
        vertical_work(y, y1, rb, raw[5] * h)
        vertical_work(y, yh, rb, 0.5 * raw[5] * h)
    m2 = be_step(yh, 0.5 * h, raw[0] + raw[1] * (tau + 0.75 * h), raw[2] + raw[3] * (tau + 0.75 * h),
                 raw[4] + raw[5] * (tau + 0.75 * h), c, rb, mu, rim, rh, y2, r2, 1.0, 1.0, ult, np.bool_(True), np.bool_(True))
    if raw[5] != 0.0:
        vertical_work(yh, y2, rb, 0.5 * raw[5] * h)
    return m1, mh, m2


@njit(cache=True)
def step_error(y1, y2, m1, mh, m2, ng, xs, vs):
    """The step's local error estimate in units of the tolerance: the full step y1 against the halves y2 in X and V
    (``xs``, ``vs`` the tolerance in m and m/s), and in the groups' split of X except where every group slides along
    its rim in the three solves (there the split is slaved to the motion; planar_multisurface_stepper)."""
    low = (1 << ng) - 1
    err = 0.0
    for j in range(2):
        err = max(err, abs(y2[Y_X + j] - y1[Y_X + j]) / xs, abs(y2[Y_V + j] - y1[Y_V + j]) / vs)
    if not (m1 == mh and mh == m2 and m2 == (low << ng | low)):
        for k in range(2 * ng):
            err = max(err, abs(y2[Y_U + k] - y1[Y_U + k]) / xs)
    return err


@njit(cache=True)
def _arrived(y1, y2, ng, rim, free):
    # the combination 2 y2 − y1 puts one of the groups in ``free`` (bits) on or past its rim
    for k in range(ng):
        if free >> k & 1:
            u1 = 2.0 * y2[Y_U + 2 * k] - y1[Y_U + 2 * k]
            u2 = 2.0 * y2[Y_U + 2 * k + 1] - y1[Y_U + 2 * k + 1]
            if u1 * u1 + u2 * u2 >= rim[k] * rim[k]:
                return True
    return False


@njit(cache=True)
def locate_arrival(y, h, tau, raw, c, rb, mu, rim, rim_free, free, r, y1, yh, y2, r1, rh, r2):
    """The length [s] of the longest step from y (at τ in its sample interval, shorter than h) whose three solves,
    with the rims of the groups in ``free`` (bits) lifted (``rim_free``), agree on the sliding set and whose
    Richardson combination keeps those groups inside their rims (``rim``): the instant one of them reaches its rim,
    by bisection on the length to its last bit (:func:`arrival_next`).  0 when the lifted step of h does not reach a
    rim (nothing to locate).  The second return is the evaluations of Ψ's gradient it took."""
    lo = 0.0
    s = h
    work = 0.0
    for d in range(200):  # the length's binary digits (arrival_next ends the search)
        m1, mh, m2 = three_solves(y, s, tau, raw, c, rb, mu, rim_free, r, y1, yh, y2, r1, rh, r2, np.int64(0))
        work += r1[2] + rh[2] + r2[2]
        lo, s = arrival_next(lo, s, h, d, m1, mh, m2, y1, y2, rim, free)
        if s < 0.0:
            break
    return lo, work


@njit(cache=True)
def arrival_next(lo, s, h, d, m1, mh, m2, y1, y2, rim, free):
    """One trial of the located arrival's bisection (:func:`locate_arrival`; a model whose steps carry more than the
    mass runs its own three solves, planar_building_multisurface_kernel): after the d-th trial, of length s (d = 0:
    the whole step h; then lo + h/2^d, the length's binary digits from the largest) whose three solves with the
    arriving groups' rims lifted have the masks m1, mh, m2 and end in y1 (the whole) and y2 (the halves), the
    bracket's lower end and the next trial's length (-1: done).  The whole step goes on only when its combination
    reaches a rim of ``free`` (solved; else lo = 0: nothing to locate); a shorter trial becomes lo when its solves
    agree on the sliding set and its combination stays inside the rims.  Done when the digits fall below lo's ulp
    (at most 200 trials)."""
    ng = rim.shape[0]
    solved = not (m1 | mh | m2) & UNSOLVED
    if d == 0:
        if not (solved and _arrived(y1, y2, ng, rim, free)):
            return 0.0, -1.0
    elif solved and m1 == mh and mh == m2 and not _arrived(y1, y2, ng, rim, free):
        lo = s
    nxt = lo + h * 0.5 ** (d + 1)
    return lo, (nxt if lo < nxt and d + 1 < 200 else -1.0)


@njit(cache=True)
def group_stops(mh, m2, ng):
    """The groups that slid in a step's first half and not in its second while another group slid on (be_step's
    masks ``mh``, ``m2``): a group's stop inside the step with the mass still moving (0 when none)."""
    low = (1 << ng) - 1
    if not m2 & low:
        return 0  # nothing slides at the end: the mass's stop (the loop's cut at a reversal or a stop)
    return mh & low & ~m2


@njit(cache=True)
def locate_stop(y, h, tau, raw, c, rb, mu, rim, want, r, y1, yh, y2, r1, rh, r2, ult):
    """The length [s] of the longest step from y (at τ in its sample interval, shorter than h) whose three solves all
    end with be_step's mask ``want`` (the sliding set of the step's first half and its groups on their rims): the
    instant a group of that set stops while the others slide on, by bisection on the length to its last bit (the
    solves into y1, yh, y2 and r1, rh, r2).  0 when no trial agrees.  The second return is the evaluations of Ψ's
    gradient it took.  (Assumes the solves agree on every length below the stop: a later change of the set is a
    later step's.)"""
    lo = 0.0
    work = 0.0
    for d in range(1, 200):  # the length's binary digits, from the largest, until they fall below lo's ulp
        s = lo + h * 0.5 ** d
        if not lo < s:
            break
        m1, mh, m2 = three_solves(y, s, tau, raw, c, rb, mu, rim, r, y1, yh, y2, r1, rh, r2, ult)
        work += r1[2] + rh[2] + r2[2]
        if m1 == want and mh == want and m2 == want:
            lo = s
    return lo, work


@njit(cache=True)
def arrival_impact(y, rim, free):
    """The plastic impact at a located arrival at the ultimate (:func:`locate_arrival`): the groups in ``free`` (bits),
    within rounding of their rims in y, are put on them (X moved with them); when every group is then on its rim
    along one direction ē (:func:`at_ultimate`) the velocity's outward part V·ē > 0 is removed and its kinetic
    energy ½(V·ē)² booked as the impact's (the exact model's: multisurface_kernel).  Returns V·ē [m/s] (0 when the
    mass does not move outward), or -1 when the groups are not at the ultimate (y then holds the groups put on
    their rims only)."""
    ng = rim.shape[0]
    put_on_rims(y, rim, free)
    if not at_ultimate(y, rim):
        return -1.0
    s1, s2, sn = _groups_sum(y, ng)
    e1 = s1 / sn
    e2 = s2 / sn
    vn = y[Y_V] * e1 + y[Y_V + 1] * e2
    if not vn > 0.0:
        return 0.0
    y[Y_V] -= vn * e1
    y[Y_V + 1] -= vn * e2
    y[Y_EIMP] += 0.5 * vn * vn
    return vn


@njit(cache=True)
def _angle(a1, a2, b1, b2):
    # the angle [rad] between two non-zero vectors
    return math.atan2(abs(a1 * b2 - a2 * b1), a1 * b1 + a2 * b2)


@njit(cache=True)
def slip_turn(y, yh, y2, qlast, both):
    """The largest angle [rad] a group's slip turns through over a step: for each group in ``both`` (bits: it slid in
    the two halves), between its slip over the last accepted step (``qlast``, a row per group; 0 when it did not
    slide) and its slip over the first half (yh − y), and between the two halves' slips (yh − y, y2 − yh)."""
    turn = 0.0
    for k in range(qlast.shape[0]):
        if not both >> k & 1:
            continue
        a1 = yh[Y_U + 2 * k] - y[Y_U + 2 * k]
        a2 = yh[Y_U + 2 * k + 1] - y[Y_U + 2 * k + 1]
        b1 = y2[Y_U + 2 * k] - yh[Y_U + 2 * k]
        b2 = y2[Y_U + 2 * k + 1] - yh[Y_U + 2 * k + 1]
        if (a1 != 0.0 or a2 != 0.0) and (b1 != 0.0 or b2 != 0.0):
            turn = max(turn, _angle(a1, a2, b1, b2))
            if qlast[k, 0] != 0.0 or qlast[k, 1] != 0.0:
                turn = max(turn, _angle(qlast[k, 0], qlast[k, 1], a1, a2))
    return turn


@njit(cache=True)
def planar_multisurface_stepper(t, ax, ay, nz, rb, mu, rim, members, tmat, c, tol, scales,
                                out_x, out_v, out_a, out_en, ev_t, ev_k, summary, surf_peak, first, ub):
    """Response of a mass on a multi-surface bearing to a piecewise-linear pair, by implicit steps.

    The arguments are those of :func:`~isolator.solver.planar_multisurface_kernel.planar_multisurface_kernel`
    (``nz`` = g + a_z at the samples, linear between them), ``tol`` the relative tolerance of the local error
    estimate and ``scales`` = (displacement floor [m], velocity floor [m/s]) of the error norm.  A step takes n at
    its mean over the step (as it takes the ground's acceleration), and books the vertical's work
    (:func:`vertical_work`).  Events (breakaway, stick) are recorded at the end of the step in which they happen.
    """
    n = t.shape[0]
    ng = rb.shape[0]
    ny = carry_slot(ng) + 1
    y = np.zeros(ny)
    y1 = np.zeros(ny)
    yh = np.zeros(ny)
    y2 = np.zeros(ny)
    y0 = np.zeros(ny)
    ne = members.shape[0]
    low = (1 << ng) - 1
    rim_before = np.int64(0)
    rest_rims = np.int64(0)  # the groups on their rims at the last declared rest (breakaway's held)
    n_rim = 0
    away = (1 << ng) - 1  # the groups off their rims by more than RIM_AWAY (their next arrival is a rim contact)
    n_ult = 0
    impulse = 0.0
    impact_v = 0.0
    max_imp_v = 0.0
    peak_r = 0.0
    first_ult = -1.0
    f_max = 0.0
    r1 = np.zeros(3)
    rh = np.zeros(3)
    r2 = np.zeros(3)
    max_work = 0.0
    # the located arrival at the ultimate (locate_arrival): its three solves, their combination, the lifted rims
    ya1 = np.zeros(ny)
    yah = np.zeros(ny)
    ya2 = np.zeros(ny)
    ya = np.zeros(ny)
    ra = np.zeros(3)
    rc1 = np.zeros(3)  # the retaken step's forces (departing_carrier)
    rch = np.zeros(3)
    rim_free = np.zeros(ng)
    qlast = np.zeros((ng, 2))  # each group's slip over the last accepted step (slip_turn)

    r = np.zeros(2)
    raw = np.zeros(6)
    for j in range(first.shape[0]):
        first[j] = -1.0
    x_floor = scales[0]
    v_floor = scales[1]
    max_evals = work_bound(tol)
    rb_mu = 0.0  # Σ R̄ µ and Σ R̄ of the groups: the rounding of their slips (SLIP_QUANTA)
    rb_sum = 0.0
    for k in range(ng):
        rb_mu += rb[k] * mu[k]
        rb_sum += rb[k]
    peak_x = 0.0
    peak_v = 0.0
    peak_a = math.sqrt(ax[0] * ax[0] + ay[0] * ay[0])
    slip = 0.0
    n_ev = 0
    n_steps = 0
    n_rej = 0
    n_floor = 0
    status = 0
    fail_t = -1.0
    moving = False
    h_sugg = -1.0
    cut_h = -1.0  # the length of a step cut at a reversal or a stop (or -1)
    after_stop = False  # the last accepted step ended at a group's located stop (locate_stop)
    out_x[0, 0] = 0.0
    out_x[0, 1] = 0.0
    out_v[0, 0] = 0.0
    out_v[0, 1] = 0.0
    out_a[0, 0] = ax[0]
    out_a[0, 1] = ay[0]
    out_en[0, 0] = 0.0
    out_en[1, 0] = 0.0
    out_en[2, 0] = 0.0
    last = 0
    for i in range(n - 1):
        hi = t[i + 1] - t[i]
        slope_x = (ax[i + 1] - ax[i]) / hi
        slope_y = (ay[i + 1] - ay[i]) / hi
        raw[0] = ax[i]
        raw[1] = slope_x
        raw[2] = ay[i]
        raw[3] = slope_y
        slope_z = (nz[i + 1] - nz[i]) / hi
        raw[4] = nz[i]
        raw[5] = slope_z
        tau = 0.0
        h_floor = H_MIN_FRACTION * hi
        h = hi if (h_sugg <= 0.0 or h_sugg > hi) else h_sugg
        steps_here = 0
        work = 0.0
        while tau < hi:
            steps_here += 1
            if steps_here > MAX_STEPS_PER_INTERVAL:
                status |= STATUS_STEP_LIMIT
                fail_t = t[i] + tau
                break
            if not moving:
                # at rest: it holds (exactly: X, ū and the energies stay) until −a_g/g leaves a friction circle,
                # the first root of a quadratic per group, where the steps start again with a small one
                for k in range(ng):
                    ub[k, 0] = y[Y_U + 2 * k]
                    ub[k, 1] = y[Y_U + 2 * k + 1]
                # a group at rest on its rim lets go only of a force whose part along the rim, or (pulling inward)
                # whose whole, leaves its circle: the rim carries the outward push (rest_holds)
                tb, kb = breakaway(ub, rb, mu, raw, tau, hi, rest_rims)
                if slope_z != 0.0:  # the vertical's work on the stored energy n P while at rest
                    vertical_work(y, y, rb, slope_z * ((hi if kb < 0 else tb) - tau))
                if kb < 0:
                    a1 = ax[i + 1]
                    a2 = ay[i + 1]
                    peak_a = max(peak_a, math.sqrt(a1 * a1 + a2 * a2))
                    r[0] = -a1 / nz[i + 1]
                    r[1] = -a2 / nz[i + 1]
                    tau = hi
                    break
                tau = tb
                h = min(h, 1e-3 * hi)
                moving = True
                n_ev += 1
                if n_ev <= ev_t.shape[0]:
                    ev_t[n_ev - 1] = t[i] + tau
                    ev_k[n_ev - 1] = EV_BREAKAWAY
            h = min(h, hi - tau)
            # the arrival at the ultimate (every group on its rim closing into alignment, the mass moving outward): the
            # steps end ARRIVAL_FRACTION × hi before it and the last of it is one move (arrive), the impact after it
            h_keep = h
            h, jump = arrival_step(y, rim, r, nz[i] + slope_z * tau, h, hi, tau)
            last_step = h >= hi - tau
            # at or below the floor a step is taken whatever its error estimate (progress; counted in S_STEPS_MULTI)
            at_floor = not h > h_floor
            dv_jump = 0.0
            ult = np.int64(-1)
            located = False
            stop_cut = False
            # the error's displacement scale, above the slips' rounding (SLIP_QUANTA)
            xs = max(tol * max(peak_x, x_floor),
                     SLIP_QUANTA * DOUBLE_EPS * (rb_mu + rb_sum * math.sqrt(r[0] * r[0] + r[1] * r[1])))
            if jump:
                g = nz[i] + slope_z * (tau + 0.5 * h)
                arrive(y, h, ax[i] + slope_x * (tau + 0.5 * h), ay[i] + slope_y * (tau + 0.5 * h), g, c, mu, rim, y2)
                # the rims' reaction over the move, taken off the outward velocity before the impact: it grows as
                # 1/√(time left) (the gap closes ∝ the rims' angles², the reaction ∝ 1/angle), so its impulse over
                # h is 2 h g r·ē with r the last step's force.  Measured (65025, lower bound, 24.4088 s, the steps'
                # loop in Python at step_tol 1e-9, the move started 1e-8 / 1e-9 / 1e-10 / 1e-11 s before the
                # arrival): the outward speed there 0.8922624 / 0.8922288 / 0.8922182 / 0.8922149 m/s, less this
                # impulse 0.89221332 m/s to 2e-9 at all four
                xn = math.sqrt(y[Y_X] ** 2 + y[Y_X + 1] ** 2)
                rn = (r[0] * y[Y_X] + r[1] * y[Y_X + 1]) / xn
                if rn > 0.0:
                    y2[Y_V] -= 2.0 * h * g * rn * y[Y_X] / xn
                    y2[Y_V + 1] -= 2.0 * h * g * rn * y[Y_X + 1] / xn
                dv_jump = ultimate_impact(y, y2, g, rb)
                if slope_z != 0.0:
                    vertical_work(y, y2, rb, slope_z * h)
                m1 = low << ng | low
                mh = m1
                m2 = m1
                r2[0] = -(ax[i] + slope_x * (tau + h)) / (nz[i] + slope_z * (tau + h))
                r2[1] = -(ay[i] + slope_y * (tau + h)) / (nz[i] + slope_z * (tau + h))
                err = 0.0
            else:
                # mean ground acceleration over [τ, τ+h], its halves (linear inside the sample interval; three_solves)
                # n = g + a_z at its mean over each step (linear: at the step's middle), as ā
                # (the vertical's work booked after each solve, the first half's before the second starts from it)
                # the ultimate classified once, at the step's start, for the three solves: classified at each solve's
                # start and end, a full step that ended 1.27e-7 rad out of alignment (> ALIGNED) took the chord's
                # velocity while its first half (6.4e-8 rad) was turned onto the ultimate circle and the second half
                # started on the half discs; the two motions' velocities differed by h × 24 m/s², an error first
                # order in h, and the steps settled at 4.75e-9 s until the work bound (NWH360 ×1.2 on the double with
                # an intermediate rim, 2.97154 s; docs/multisurface.md, "Once per step")
                ult = 1 if at_ultimate(y, rim) else 0
                m1, mh, m2 = three_solves(y, h, tau, raw, c, rb, mu, rim, r, y1, yh, y2, r1, rh, r2, ult)
                work += r1[2] + rh[2] + r2[2]
                k_dep = departing_carrier(y, m1, mh, m2, rim) if ult == 0 else -1
                if k_dep >= 0:
                    # a group carrying the mass on its rim, leaving it in the full disc's solves: retaken on its half
                    # disc (the exact rim reaction, |V|²/c̄ for the centripetal need, group_return); sliding on its rim
                    # to every solve's end there (carried, or with other groups sliding) the retake is the step.  On the full disc the
                    # steps left the rim and came back in turn (chord outward, the half need), the other group
                    # sliding by ~1e-9 m at each return: a velocity error of 5.1e-5 / 2.2e-5 m/s at step_tol 1e-7 /
                    # 3e-8 (NWH360 ×1.2 with the reversed record ×0.72 on the double with an intermediate rim, 4.2511
                    # s, the outer group stopped and the inner carrying on its rim; docs/multisurface.md, "The
                    # carrier's departure")
                    y[carry_slot(ng)] = k_dep + 1.0
                    m1c, mhc, m2c = three_solves(y, h, tau, raw, c, rb, mu, rim, r, ya1, yah, ya2, rc1, rch, ra, ult)
                    work += rc1[2] + rch[2] + ra[2]
                    kept = 1 << k_dep | 1 << (ng + k_dep)
                    if m1c & kept == kept and mhc & kept == kept and m2c & kept == kept and not (m1c | mhc | m2c) & UNSOLVED:
                        for j in range(ny):
                            y1[j] = ya1[j]
                            yh[j] = yah[j]
                            y2[j] = ya2[j]
                        for j in range(3):
                            r1[j] = rc1[j]
                            rh[j] = rch[j]
                            r2[j] = ra[j]
                        m1 = m1c
                        mh = mhc
                        m2 = m2c
                    else:
                        y[carry_slot(ng)] = 0.0
                if work > max_evals:
                    status |= STATUS_WORK
                    fail_t = t[i] + tau
                    summary[S_FAIL_RIMS] = popcount(rim_before)
                    break
                if (m1 | mh | m2) & UNSOLVED:
                    # Newton did not converge (seen with sliders on their rims pointing different ways at the
                    # ultimate): the step is refused and retried at a quarter (as an implicit integrator refuses a step
                    # whose Newton iteration fails); at the floor the run stops with the time rather than go on from a
                    # wrong force.  (Chuetsu-oki 65025 ×1.556, the review's nominal bound at step_tol 1e-8: one solve at
                    # 30.6036 s stopped the run, every group on its rim; the same code compiled apart went past it)
                    if not at_floor:
                        n_rej += 1
                        h = max(0.25 * h, h_floor)
                        continue
                    status |= STATUS_UNSOLVED
                    fail_t = t[i] + tau
                    summary[S_FAIL_RIMS] = popcount(rim_before)
                    break
                if (ult == 0 and not after_stop and group_stops(mh, m2, ng)
                        and 0.5 * h * (raw[4] + raw[5] * (tau + 0.5 * h)) * math.sqrt((r2[0] - rh[0]) ** 2 + (r2[1] - rh[1]) ** 2)
                        > tol * max(peak_v, v_floor)):
                    # a group that slid in the first half stops inside the step while another slides on: the force
                    # jumps there (from the stopping group's friction circle to the others' edges and rims), an
                    # error first order in the step that the two halves, taken apart, keep.  The stop is located
                    # (locate_stop: the longest step whose three solves all slide the first half's set, so its
                    # combination holds) and the step ends there; the next starts with the group stopped (and is
                    # taken as it comes: the stop is at its start).  Taken as its halves, the step with masks 5/7/5
                    # (the outer group stopping while the inner slides along its rim) moved the velocity by 2.4e-5
                    # m/s at step_tol 1e-7 (NWH360 ×1.2 with the reversed record ×0.72 on the double with an
                    # intermediate rim, 4.6946 s; docs/multisurface.md, "The step after an arrival, a group's stop
                    # located").  Only where the stepped-over jump, h/2 g |r2 − rh|, exceeds the velocity tolerance:
                    # located always, the 35° collinear pair of test_planar_multisurface_rim.py took 31,020 steps
                    # instead of 24,731.  Only a stop located past the floor (h_floor): one within it of the step's
                    # start is a switch of the sliding set at the start, left to the step's error estimate (retried
                    # shorter, as without the location).  Cut there, the step fell below the floor, where steps are
                    # taken whatever their error: the 35° elliptical pulse at step_tol 1e-8 (test_planar_multisurface_
                    # rim.py) cut a step at 9.4e-12 s (0.88049 s, the outer groups stopping as the inner starts),
                    # accepted the next at err 169, and the perturbed motion chattered at 0.965 s: 135,713 steps
                    # against 77,999 (docs/multisurface.md, "The located stop's cost")
                    lo, w_stop = locate_stop(y, h, tau, raw, c, rb, mu, rim, mh, r, ya1, yah, ya2, rc1, rch, ra, ult)
                    work += w_stop
                    if lo > h_floor:
                        m1, mh, m2 = three_solves(y, lo, tau, raw, c, rb, mu, rim, r, y1, yh, y2, r1, rh, r2, ult)
                        work += r1[2] + rh[2] + r2[2]
                        last_step = False
                        h = lo
                        stop_cut = True
                # the groups' split of X is in the estimate except where every group slides along its rim in the three
                # solves: there the force sits on all their friction edges at once (over-determined: each pair of them
                # fixes r), the split between them is slaved to the motion and relaxes as fast as the steps' α, and the
                # full and half steps differ only in it (Chuetsu-oki 65025 ×1.556, nominal friction, 26.2573 s: the
                # split 0.81 of the tolerance, X 4.6e-6, V 1.7e-4 of theirs; the steps fell to 6.5e-7 s with ~7,000
                # gradients each until the work bound).  On the rims |ū_k| = c̄_k: the stored energy does not depend
                # on the split, and the friction work it does is in the balance
                err = step_error(y1, y2, m1, mh, m2, ng, xs, tol * max(peak_v, v_floor))
            n_steps += 1
            if err > 1.0:
                if not at_floor:
                    n_rej += 1
                    h = max(h * max(0.1, 0.9 / math.sqrt(err)), h_floor)
                    continue
                n_floor += 1
            turned = y[Y_V] * y2[Y_V] + y[Y_V + 1] * y2[Y_V + 1]
            if not (jump or at_floor) and turned > 0.0:
                # a group's slip turning inside the step (SLIP_TURN): retried shorter
                turn = slip_turn(y, yh, y2, qlast, mh & m2 & low)
                if turn > SLIP_TURN:
                    n_rej += 1
                    h = max(h * max(0.1, 0.9 * SLIP_TURN / turn), h_floor)
                    continue
            if (cut_h != h and not jump and y1[Y_EIMP] == y[Y_EIMP] and y2[Y_EIMP] == y[Y_EIMP]
                    and (y[Y_V] != 0.0 or y[Y_V + 1] != 0.0) and (turned < 0.0 or (turned == 0.0 and not m2 & low))):
                # the velocity turned back or vanished inside the step (a reversal or a stop): the friction's jump
                # there is first order in the step (the velocity off by the time before it × the jump) and
                # invisible to the halves when it falls in the first (both solves take it whole); the step is cut
                # where its velocity still points forward (bisection on its length, to rounding), so the same
                # groups slide to its end and its combination holds, and the velocity there (at most the velocity
                # tolerance) is taken away (docs/building.md, "Reversals located")
                lo = 0.0
                part = h
                for _ in range(200):  # the length's binary digits, from the largest, until they fall below its ulp
                    part *= 0.5
                    t_try = lo + part
                    if not lo < t_try:
                        break
                    be_step(y, t_try, ax[i] + slope_x * (tau + 0.5 * t_try), ay[i] + slope_y * (tau + 0.5 * t_try),
                            nz[i] + slope_z * (tau + 0.5 * t_try), c, rb, mu, rim, r, y0, rh, 1.0, 1.0, np.int64(-1),
                            np.bool_(True), np.bool_(False))  # ``leave`` passed: one version with three_solves'
                    work += rh[2]
                    if y[Y_V] * y0[Y_V] + y[Y_V + 1] * y0[Y_V + 1] > 0.0:
                        lo = t_try
                if lo > 0.0:
                    be_step(y, lo, ax[i] + slope_x * (tau + 0.5 * lo), ay[i] + slope_y * (tau + 0.5 * lo),
                            nz[i] + slope_z * (tau + 0.5 * lo), c, rb, mu, rim, r, y0, rh, 1.0, 1.0, np.int64(-1),
                            np.bool_(True), np.bool_(False))  # ``leave`` passed: one version with three_solves'
                    if math.sqrt(y0[Y_V] ** 2 + y0[Y_V + 1] ** 2) <= max(
                            tol * max(peak_v, v_floor), CUT_ROUNDING * math.sqrt(y[Y_X] ** 2 + y[Y_X + 1] ** 2) / lo):
                        h = lo
                        cut_h = lo
                        continue
            free = np.int64(0)  # the groups off their rims at the step's start
            for k in range(ng):
                if y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2 < (rim[k] * (1.0 - RIM_ON)) ** 2:
                    free |= 1 << k
            if (ult == 0 and free and (y1[Y_EIMP] != y[Y_EIMP] or yh[Y_EIMP] != y[Y_EIMP]
                                       or y2[Y_EIMP] != y[Y_EIMP])):
                # the step reached the ultimate: a group arrived at its rim with the others on theirs, along one
                # direction, and the rims took the outward velocity.  Taken at the step's end, the impulse was the
                # chord's: the backward-Euler velocity of a step ending on the rim, all of it removed, so the finite
                # force's change over the step before the arrival (h × ~4 m/s² at the TFP's regime V) was counted as
                # impulse (6.2e-5 of it on the tests' sine pulse against the exact 1-D model).  The arrival located:
                # the step's three solves with the arriving groups' rims lifted (smooth to it: the Richardson
                # combination holds), their combination on the rim by bisection on the step's length to its last
                # bit, the impulse the outward velocity there (arrival_impact)
                for k in range(ng):
                    rim_free[k] = math.inf if free >> k & 1 else rim[k]
                lo, w_arr = locate_arrival(y, h, tau, raw, c, rb, mu, rim, rim_free, free, r, ya1, yah, ya2, r1, rh,
                                           ra)
                work += w_arr
                if lo > 0.0:
                    m1a, mha, m2a = three_solves(y, lo, tau, raw, c, rb, mu, rim_free, r, ya1, yah, ya2, r1, rh, ra,
                                                 np.int64(0))
                    for j in range(ny):
                        ya[j] = y[j]
                    accept_step(ya, ya1, ya2, ny, ny - 1, ng, rim, m1a, mha, m2a, np.bool_(False), np.bool_(True))
                    vn = arrival_impact(ya, rim, free)
                    if vn >= 0.0:
                        err_a = step_error(ya1, ya2, m1a, mha, m2a, ng, xs, tol * max(peak_v, v_floor))
                        if err_a > 1.0 and not at_floor:
                            n_rej += 1
                            h = max(lo * max(0.1, 0.9 / math.sqrt(err_a)), h_floor)
                            continue
                        located = True
                        dv_jump = vn
                        err = err_a
                        last_step = last_step and lo == h
                        h = lo
                        on = 0
                        for k in range(ng):
                            if ya[Y_U + 2 * k] ** 2 + ya[Y_U + 2 * k + 1] ** 2 >= (rim[k] * (1.0 - RIM_ON)) ** 2:
                                on |= 1 << k
                        m1 = m1a
                        mh = mha
                        m2 = (m2a & low) | on << ng
                        r2[0] = ra[0]
                        r2[1] = ra[1]
            # accepted: the Richardson combination where it holds, else the two half steps (accept_step)
            for j in range(ny):
                y0[j] = y[j]
            if located:
                for j in range(ny):
                    y[j] = ya[j]
            else:
                accept_step(y, y1, y2, ny, ny - 1, ng, rim, m1, mh, m2, jump, np.bool_(True))
            if cut_h == h:
                # the step cut at a reversal or a stop: the velocity left (below its tolerance) is taken away, its
                # kinetic energy booked as friction
                y[Y_EF] += 0.5 * (y[Y_V] ** 2 + y[Y_V + 1] ** 2)
                y[Y_V] = 0.0
                y[Y_V + 1] = 0.0
            for k in range(ng):  # each group's slip over the accepted step (slip_turn); none after a cut's stop or an impact
                slid = cut_h != h and y[Y_EIMP] == y0[Y_EIMP] and (m1 | m2) >> k & 1
                qlast[k, 0] = y[Y_U + 2 * k] - y0[Y_U + 2 * k] if slid else 0.0
                qlast[k, 1] = y[Y_U + 2 * k + 1] - y0[Y_U + 2 * k + 1] if slid else 0.0
            cut_h = -1.0
            after_stop = stop_cut
            r[0] = r2[0]
            r[1] = r2[1]
            tau = hi if last_step else tau + h
            on_rim = m2 >> ng
            if on_rim & away:
                n_rim += popcount(element_mask(on_rim & away, members))
                away &= ~on_rim
            for k in range(ng):
                if y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2 < (rim[k] * (1.0 - RIM_AWAY)) ** 2:
                    away |= 1 << k
            rim_before = on_rim
            rigid = on_rim == low
            if rigid:
                # every element on its rim: the bearing is at its ultimate displacement; a step that booked an
                # impact energy (ultimate_impact: the step's energy defect, the kinetic energy the rigid stop took)
                # is (part of) a plastic impact: its velocity change is the impact's
                if first_ult < 0.0:
                    first_ult = t[i] + tau
                f_max = 0.0
                for k in range(ng):
                    f_max = max(f_max, math.sqrt(y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2) / rb[k] + mu[k])
                dv = math.sqrt((y[Y_V] - y0[Y_V]) ** 2 + (y[Y_V + 1] - y0[Y_V + 1]) ** 2)
                if jump or located:
                    dv = dv_jump  # the impact's alone (the rims' reaction before it, the finite force, not an impulse)
                if y[Y_EIMP] != y0[Y_EIMP]:
                    # an arrival's impact (ultimate_impact books its energy in the step, and only an arrival's: a
                    # slide along the ultimate circle keeps the mass on it without one); its velocity change is
                    # counted here (a velocity-change test, 2h × the largest finite force, missed a slow arrival
                    # in a long step: PTS ×2 double at 6.00 s, 0.058 m/s, and left its energy in the balance)
                    impact_v += dv
                    # the impulse is not a force of the surfaces: the transmitted acceleration is the ground's
                    r[0] = -(ax[i] + slope_x * tau) / (nz[i] + slope_z * tau)
                    r[1] = -(ay[i] + slope_y * tau) / (nz[i] + slope_z * tau)
                    impulsive = True
                else:
                    impulsive = False
            else:
                impulsive = False
            if impact_v > 0.0 and not impulsive:
                n_ult += 1
                impulse += impact_v
                max_imp_v = max(max_imp_v, impact_v)
                impact_v = 0.0
            vn = math.sqrt(y[Y_V] ** 2 + y[Y_V + 1] ** 2)
            if (m1 | m2) & low:
                slip += h
                sl = (m2 if m2 & low else m1) & low
                em = element_mask(sl & ~on_rim, members) | (element_mask(on_rim, members) << ne)
                if first[em] < 0.0:
                    first[em] = t[i] + tau
            fr = math.sqrt(r[0] * r[0] + r[1] * r[1])
            if rigid:
                fr = min(fr, f_max)
            peak_r = max(peak_r, fr)
            g = nz[i] + slope_z * tau  # n at the step's end
            if (vn == 0.0 and on_rim != low
                    and rest_holds(y, rb, mu, rim, -(ax[i] + slope_x * tau) / g, -(ay[i] + slope_y * tau) / g)):
                # at rest with −a_g/g inside every circle, or held by a rim (rest_holds): stuck (the quadratic then
                # finds the break-away); a rest of the steps with −a_g/g outside a circle is left to the next step.
                # A rest against a rim was not declared (the test asked for no group on its rim): the steps went on
                # through it and its break-away was theirs, not the closed form (tests/solver/
                # test_planar_multisurface_rim_rest.py; docs/multisurface.md, "A rest against a rim").  Not at the
                # ultimate (every group on its rim): declared there, the TFP's 0.8 g sine pulse at step_tol 1e-9 ran
                # into the work bound after the break-away (1.118 s), as the building's did (its _outside)
                n_ev += 1
                if n_ev <= ev_t.shape[0]:
                    ev_t[n_ev - 1] = t[i] + tau
                    ev_k[n_ev - 1] = EV_STICK
                moving = False
                rest_rims = on_rim  # the groups at rest on their rims (their rims carry the outward push)
                qlast[:, :] = 0.0
            peak_x = max(peak_x, math.sqrt(y[Y_X] ** 2 + y[Y_X + 1] ** 2))
            peak_v = max(peak_v, vn)
            a1 = -g * r[0] - c * y[Y_V]
            a2 = -g * r[1] - c * y[Y_V + 1]
            a_mag = math.sqrt(a1 * a1 + a2 * a2)
            if rigid:
                # every group on its rim: the force is the rims' reaction.  Where the groups close into alignment
                # it grows as 1/sin of the angle between two rims' normals (a toggle: two groups sliding along
                # their rims fix F by F·t_k = µ_k) and does not converge with step_tol (F&C TFP, PTS ×2.5:
                # 1.6e4 → 2.0e5 m/s² at 1e-7 → 1e-8); the closing ends in the plastic impact, whose impulse is
                # reported.  The transmitted acceleration takes the reaction up to what the mass on the rims can
                # need without an impact: the largest surface force, or the ground's acceleration (held), plus
                # the dashpot and the centripetal |V|²/|X| of a slide along the ultimate circle
                ag_x = ax[i] + slope_x * tau
                ag_y = ay[i] + slope_y * tau
                x_abs = math.sqrt(y[Y_X] ** 2 + y[Y_X + 1] ** 2)
                a_cap = max(g * f_max, math.sqrt(ag_x * ag_x + ag_y * ag_y)) + c * vn
                if x_abs > 0.0:
                    a_cap += vn * vn / x_abs
                a_mag = min(a_mag, a_cap)
            peak_a = max(peak_a, a_mag)
            if not groups_within_rims(y, ub, rim):
                status |= STATUS_RIM
                fail_t = t[i] + tau
            if status:
                break
            surface_peaks(ub, rb, members, tmat, surf_peak)
            # (a step accepted at the floor with err > 1 makes the next shorter than the floor, and the run of steps
            # after it is taken whatever their error, each shorter: docs/multisurface.md, "Steps below the floor").
            # After the arrival's move and impact (jump) the step goes on from the approach's, but not below the
            # floor: the approach's steps are set by the rims' reaction closing as 1/angle (77 W, 2.6e-10 s at
            # step_tol 3e-10), which the impact ends; from the ultimate a step that short has a chord whose sagitta
            # on the inner group's half disc, (|V| h)²/(c̄/2) ~ 8e-19 m, is below the rounding of ū (~3e-18 m), and
            # its half step's force was not found (NWH360 ×1.2 with the reversed record ×0.72 on the double with an
            # intermediate rim, 2.97152 s; docs/multisurface.md, "The step after an arrival")
            h = max(h_keep, h_floor) if jump else h * min(5.0, 0.9 / math.sqrt(max(err, 1e-12)))
        max_work = max(max_work, work)
        if status:
            break
        h_sugg = h
        out_x[i + 1, 0] = y[Y_X]
        out_x[i + 1, 1] = y[Y_X + 1]
        out_v[i + 1, 0] = y[Y_V]
        out_v[i + 1, 1] = y[Y_V + 1]
        out_a[i + 1, 0] = -nz[i + 1] * r[0] - c * y[Y_V]
        out_a[i + 1, 1] = -nz[i + 1] * r[1] - c * y[Y_V + 1]
        out_en[0, i + 1] = y[Y_EIN]
        out_en[1, i + 1] = y[Y_EF]
        out_en[2, i + 1] = y[Y_EV]
        last = i + 1
    for j in range(last + 1, n):
        out_x[j, 0] = np.nan
        out_x[j, 1] = np.nan
    if n_ev > ev_t.shape[0]:
        status |= STATUS_EVENTS_TRUNCATED
    summary[S_PEAK_X] = peak_x
    summary[S_PEAK_V] = peak_v
    summary[S_PEAK_A] = peak_a
    summary[S_SLIP_TIME] = slip
    summary[S_E_IN] = y[Y_EIN]
    summary[S_E_F] = y[Y_EF]
    summary[S_E_V] = y[Y_EV]
    summary[S_N_EVENTS] = n_ev
    summary[S_STATUS] = status
    summary[S_N_STEPS] = n_steps
    summary[S_N_REJECTED] = n_rej
    summary[S_FAIL_T] = fail_t
    summary[S_STEPS_MULTI] = n_floor
    if impact_v > 0.0:
        n_ult += 1
        impulse += impact_v
        max_imp_v = max(max_imp_v, impact_v)
    summary[S_N_RIM_CONTACTS] = n_rim
    summary[S_N_ULTIMATE] = n_ult
    summary[S_IMPULSE] = impulse
    summary[S_MAX_IMPACT_V] = max_imp_v
    summary[S_E_IMP] = y[Y_EIMP]
    summary[S_PEAK_R] = peak_r
    summary[S_FIRST_ULT] = first_ult
    summary[S_MAX_WORK] = max_work

