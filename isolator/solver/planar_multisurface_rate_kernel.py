r"""The compiled record loop of a double or triple friction pendulum with µ(v) surfaces in the plane.

The 2-D counterpart of :mod:`isolator.solver.multisurface_rate_kernel` (model ``2d-multisurface+mu(v)``).
Per surface i (displacement u_i ∈ ℝ² on the surface, effective geometry; X = Σ u_i), in units of the
weight, the one force r = F/W ∈ ℝ² through the massless sliders obeys (coupled friction on each surface,
associated flow: the slide velocity along the friction excess f_i = r − b_i)

.. math::

    \dot u_i = \varphi_i(|f_i|)\,\frac{f_i}{|f_i|}\ (\text{sliding}),\qquad
    |f_i| \le \mu_{slow,i}\ (\text{stuck}),\qquad
    \mu_i(v) = \mu_{fast,i} - (\mu_{fast,i} - \mu_{slow,i})\,e^{-a_i v},

φ_i the inverse of µ_i, the back-forces b = B u of the series model (B = diag(1/R̄) T⁻¹ acting on each
component: the rotated slide plates of Fenz & Constantinou), and the mass Ẍ = −g r − c Ẋ − a_g(t).
Σ_i u̇_i = Ẋ fixes r (each map r ↦ φ_i(|r − b_i|)(r − b_i)/|r − b_i| is the gradient of a convex
function, strictly convex where the surface slides: the sum is strongly monotone, one root for Ẋ ≠ 0):
an index-1 DAE.  The force is found as in 1-D from a *pivot* surface k (the sliding surface with the
largest a_i |u̇_i| at the step's start, the 1-D kernel's ``pick_pivot``): u̇_k = Ẋ − Σ_{j≠k} φ_j(|f_j|) f̂_j and
f_k = µ_k(|u̇_k|) û̇_k, the forward law (well conditioned where φ_k is not); r is the root of
G(r) = r − b_k − µ_k(|u̇_k|) û̇_k, ∂G/∂r = I + DM_k Σ_j DΦ_j (a product of two symmetric
positive semi-definite matrices plus I: invertible), by Newton kept inside the discs |f_j| < µ_fast,j
(:func:`solve_force`), each collocation stage's from the force predicted along dr/dy (:func:`stage_residual`).
Two or more sliding surfaces saturated together (a_i |u̇_i| ≥ 28, left at 26: µ_fast − µ(v) near the rounding of r,
φ not resolvable) share the velocity by the 1-D model's map on each component (its ``update_lock`` and ``set_split``
on the speeds |u̇_i|: the back-forces of the set move together, u̇_ℓ = G_ℓ0 Ẋ + Σ_U G_ℓj u̇_j), exact where the
motion keeps one direction (a pair along a line, an equal double); a motion that turns while two surfaces are
saturated is not checked (docs/multisurface.md, h122).  Where the pivot and another surface slide saturated
(a·s ≥ 10) with slips apart (|ŵ × n_j| ≥ 1e-4: r at the corner of their circles |r − b| = µ_fast, where φ is not
resolvable and no set is formed) the force and the speeds come from every law forward (:func:`corner_force`) and
the Jacobian from the implicit function theorem on that system (:func:`corner_jacobian`; h151).  The state
y = (Ẋ, u_1, …, u_n) ∈ ℝ^(2+2n) is integrated by
the 3-stage Radau IIA
collocation of the 1-D kernel (its tableau, Newton start and stage matrix imported), with the analytic
Jacobian (:func:`rhs`), every step taken twice (h, two of h/2) and the difference held below the tolerance.

Modes and events (each located on re-stepped collocation steps by Illinois secant, as in 1-D):

* a sliding surface (not the pivot) stops: |f_i| = µ_slow,i from above (its slide law is continued
  through the onset, φ < 0 inside the disc); a stuck one starts: |f_i| = µ_slow,i from below;
* the mass stops (its speed decreasing to 0, the last sliding surface the pivot): the steps are cut to
  0.7 of the time to rest at the present deceleration, |Ẋ|²/(−Ẋ·Ẍ), and at |Ẋ| ≤ :data:`STOP_SPEED` of the
  speed scale the mass is put at rest (the coast left, ≤ STOP_SPEED of the peak speed for ≤ that over the
  deceleration of time, is not integrated; its kinetic energy ½|Ẋ|² is booked as friction);
* at rest the mass sticks while r_need(t) = −a_g(t)/g stays in every static disc |r_need − b_i| ≤ µ_slow,i;
  with a piecewise-linear record each disc's exit is a quadratic's root: the break-away is exact; at the
  break-away the surfaces whose disc is left start, the pivot the farthest out, in the direction of
  r_need − b_k;
* a sliding surface reaches its rim |u_i| = d_i* (put on the circle, :data:`HELD`): held while r − b_i lies in
  its static disc plus the rim's normal cone (:func:`held_value`), it slides along the rim (:data:`ON_RIM`,
  :func:`rim_slide`: its slip on the tangent, ψ(f·t) t, the rim's frictionless reaction f·e ≥ 0 normal to it) when
  |f·t| passes µ_slow, stops on it when |f·t| falls back, and leaves it inward when the reaction f·e turns negative
  (the 1-D model's held surface, which leaves only inward; a rim slider is never the pivot).  The force jumps so
  that the others take its velocity; with no surface left sliding inside its rim a stuck one starts
  (:func:`restart_free`); with every surface on its rim and the rims apart the run stops (:data:`STATUS_ALL_RIMS`,
  the driver carries the slide along the rims on), and with the rims aligned the mass is at the ultimate: a plastic
  impact removes
  its velocity (impulse |Ẋ|, energy ½|Ẋ|² booked; the tangential part too — exact where the arrival is radial, as
  in 1-D; its largest fraction is in the summary, :data:`S_IMPACT_TANGENTIAL`), then it holds or starts as from
  rest.  A start from rest pushed only along the rims (no surface free inside its rim) is not modelled
  (:data:`STATUS_RIM`, the driver refuses in one line).

Energies per unit mass: input −∫a_g·Ẋ dt, viscous c∫|Ẋ|², friction g Σ∫(r − b_i)·dū_i on the series
elements ū = T⁻¹u (the accounting of the 1-D kernels; stored g Σ|ū_i|²/(2R̄_i)), by the collocation's own
quadrature with the stage derivatives A⁻¹Z/h as the slide rates.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.dense import lu_factor, lu_solve, solve_or_refuse
from isolator.solver.events import BREAKAWAY, REVERSAL, STICK
from isolator.solver.jit import njit
from isolator.solver.multisurface_rate_kernel import (
    GUESS_FIRST_HALF,
    GUESS_SECOND_HALF,
    RADAU_A,
    RADAU_A_INV,
    RADAU_C,
    friction_at_rate,
    set_split,
    slide_rate,
    stage_matrix,
    update_lock,
)
from isolator.solver.planar_events import record_event

REGIME = 3  #: the sliding set changed (a surface started, stopped, reached, left or slid along its rim)
RIM_REACHED = 4  #: a surface reached its rim (held there or sliding along it; no impact)
ULTIMATE = 5  #: plastic impact at the ultimate displacement (every surface on its rim)
EVENT_NAMES = ("breakaway", "stick", "reversal", "regime", "rim reached", "ultimate")

# a surface's mode
STUCK = 0
SLIDING = 1  #: sliding inside its rim
ON_RIM = 2  #: sliding along its rim (its slip on the rim's tangent, the rim's frictionless reaction normal to it)
HELD = 3  #: on its rim, not sliding: r − b in the static disc plus the rim's normal cone
JUST_STOPPED = 2  #: ``fresh`` of a surface stopped at this event (1: just started); cleared by the next step taken

MAX_EVENTS_PER_INTERVAL = 1000  #: chatter guard
#: bound on the collocation double steps of one sample interval, event location included (the run stops there,
#: :data:`STATUS_WORK`); the real pairs at ×1 take ≤ 21 000 in a whole record
MAX_STEPS_PER_INTERVAL = 20000
LEVEL_TIE = 1e-13  #: static discs left within this (F/W) of each other start together
#: the mass is put at rest when decelerating at a speed ≤ this fraction of the speed scale (max(peak, 1e-3 m/s))
STOP_SPEED = 1e-10
#: the saturated set is formed only where its members slide the pivot's way to this sine of the angle (:func:`aligned_set`)
ALIGNED_SET = 1e-9

STATUS_OK = 0
STATUS_CHATTER = 1
STATUS_STEP_FAILED = 4  #: the step size fell below 1e-13 of the interval (the run stops there)
STATUS_RIM = 8  #: every surface on its rim, one of them made to slide along it from rest (not modelled: the run stops)
STATUS_WORK = 16  #: more than MAX_STEPS_PER_INTERVAL double steps in one sample interval (the run stops there)
#: every surface on its rim with the rims apart (sine > :data:`ALIGNED_SPREAD`): the mass is not at its ultimate, it
#: slides on along the rims, closing them into alignment (h181).  The run stops there, before any impact, its state
#: (the time in ``S_FAIL_T``, Ẋ in the last ``out_v`` row, u in ``u``, the energies in the summary) handed to the
#: driver, which integrates that slide (:func:`isolator.solver.planar_rim_slide.close_along_rims`, h226)
STATUS_ALL_RIMS = 32
#: the largest sine between a rim's normal and X/|X| at which every surface on its rim is the ultimate (an impact)
ALIGNED_SPREAD = 1e-9

# the summary vector
S_PEAK_X = 0
S_PEAK_V = 1
S_PEAK_A = 2
S_PEAK_R = 3
S_SLIP_TIME = 4
S_E_IN = 5
S_E_F = 6
S_E_V = 7
S_N_EVENTS = 8
S_STATUS = 9
S_N_STEPS = 10
S_FAIL_T = 11  #: time [s] where the run stopped (-1: none)
S_N_NEWTON = 12
S_RIM_SURFACE = 13  #: the surface (0-based) on its rim where the run stopped (-1: none)
S_N_RIM = 14  #: rim contacts (arrivals of a surface at its rim)
S_N_ULT = 15  #: plastic impacts at the ultimate displacement
S_IMPULSE = 16  #: Σ velocity the impacts removed [m/s]
S_MAX_IMPACT_V = 17  #: largest velocity an impact removed [m/s]
S_E_IMPACT = 18  #: the kinetic energy the impacts took [J/kg]
S_FIRST_ULT = 19  #: time of the first impact [s] (-1: none)
S_IMPACT_TANGENTIAL = 20  #: largest |Ẋ × ē|/|Ẋ| at an impact (the tangential part it removed, ē the rims' direction)
#: largest |e_i × ē| at an impact (the sine of the angle between a surface's rim normal e_i = u_i/|u_i| and ē = X/|X|:
#: 0 where the rims are aligned, the ultimate |X| = Σ d_i*; above it the mass is not at its ultimate and could go on
#: along the rims, closing them into alignment — not modelled for µ(v) in the plane, the driver refuses)
S_IMPACT_SPREAD = 21
S_IMPACT_GAP = 22  #: largest 1 − |X|/Σ|u_i| at an impact (how far inside the ultimate circle the impact was taken)
S_RIMS_SPREAD = 23  #: at STATUS_ALL_RIMS: the largest |e_i × ē| (the rims apart, sine)
S_RIMS_GAP = 24  #: at STATUS_ALL_RIMS: 1 − |X|/Σ|u_i|
S_RIMS_TANGENTIAL = 25  #: at STATUS_ALL_RIMS: |Ẋ × ē|/|Ẋ|
SUMMARY_SIZE = 26


@njit(cache=True)
def back_forces(y, bmat, out_b):
    """b_i = Σ_q B_iq u_q [-] on each component, u_q = (y[2+2q], y[3+2q])."""
    n = bmat.shape[0]
    for i in range(n):
        bx = 0.0
        by = 0.0
        for q in range(n):
            bx += bmat[i, q] * y[2 + 2 * q]
            by += bmat[i, q] * y[3 + 2 * q]
        out_b[i, 0] = bx
        out_b[i, 1] = by


@njit(cache=True)
def radial_jacobian(ex, ey, radial, tangential, out_d):
    """The 2 × 2 derivative of a radial law q(ρ) e (e = (ex, ey) the unit direction) in ``out_d``: ``radial`` = q'(ρ)
    along e, ``tangential`` = q/ρ across it."""
    out_d[0, 0] = radial * ex * ex + tangential * (1.0 - ex * ex)
    out_d[0, 1] = (radial - tangential) * ex * ey
    out_d[1, 0] = out_d[0, 1]
    out_d[1, 1] = radial * ey * ey + tangential * (1.0 - ey * ey)


@njit(cache=True)
def slide_vector(fx, fy, mu_s, mu_f, a, out_d):
    """Slide velocity [m/s] of a surface at friction excess f = r − b: φ(|f|) f/|f| (continued through the onset:
    φ < 0 inside the static disc), and its derivative d(u̇)/df in ``out_d`` [2 × 2]; NaN outside |f| < µ_fast."""
    rho = math.hypot(fx, fy)
    if not rho > 0.0:
        return math.nan, math.nan
    sp, dsp = slide_rate(rho, 1.0, mu_s, mu_f, a)
    if not math.isfinite(sp):
        return math.nan, math.nan
    ex = fx / rho
    ey = fy / rho
    radial_jacobian(ex, ey, dsp, sp / rho, out_d)
    return sp * ex, sp * ey


@njit(cache=True)
def rim_slide(fx, fy, ex, ey, mu_s, mu_f, a, out_d):
    """Slide velocity [m/s] of a surface on its rim (e = (ex, ey) its outward unit normal, t = (−ey, ex) the rim's
    tangent) at friction excess f = r − b: ψ(f·t) t, ψ(s) = φ(|s|) sign(s) the slide law along the tangent (continued
    through the onset as :func:`slide_vector`); the normal part f·e is the rim's reaction (frictionless, ≥ 0 while
    the surface stays on it).  ``out_d`` receives d(u̇)/df = ψ'(f·t) t tᵀ; NaN outside |f·t| < µ_fast."""
    tx = -ey
    ty = ex
    ft = fx * tx + fy * ty
    sp, dsp = slide_rate(abs(ft), 1.0, mu_s, mu_f, a)
    if not math.isfinite(sp):
        return math.nan, math.nan
    if ft < 0.0:
        sp = -sp
    out_d[0, 0] = dsp * tx * tx
    out_d[0, 1] = dsp * tx * ty
    out_d[1, 0] = out_d[0, 1]
    out_d[1, 1] = dsp * ty * ty
    return sp * tx, sp * ty


@njit(cache=True)
def rim_turn(fx, fy, ux, uy, mu_s, mu_f, a, out_e):
    """The direct derivative ∂u̇/∂u [1/s] of a rim slide (:func:`rim_slide`) through its tangent t = J u/|u| (the
    rim's turning; ∂t/∂u = (J − t eᵀ)/|u|): ψ' t (∂(f·t)/∂u) + ψ ∂t/∂u, in ``out_e`` [2 × 2]."""
    rho = math.hypot(ux, uy)
    ex = ux / rho
    ey = uy / rho
    tx = -ey
    ty = ex
    ft = fx * tx + fy * ty
    sp, dsp = slide_rate(abs(ft), 1.0, mu_s, mu_f, a)
    if ft < 0.0:
        sp = -sp
    # ∂t/∂u = (J − t eᵀ)/ρ, J = [[0, −1], [1, 0]]
    t00 = -tx * ex / rho
    t01 = (-1.0 - tx * ey) / rho
    t10 = (1.0 - ty * ex) / rho
    t11 = -ty * ey / rho
    gx = fx * t00 + fy * t10
    gy = fx * t01 + fy * t11
    out_e[0, 0] = dsp * tx * gx + sp * t00
    out_e[0, 1] = dsp * tx * gy + sp * t01
    out_e[1, 0] = dsp * ty * gx + sp * t10
    out_e[1, 1] = dsp * ty * gy + sp * t11


@njit(cache=True)
def contributes(md, locked):
    """Whether a surface's rate is its own slide law in the force's equation (not the pivot): sliding, not in the
    saturated set, or sliding along its rim."""
    return (md == SLIDING and locked == 0) or md == ON_RIM


@njit(cache=True)
def surface_rate(fx, fy, md, ex, ey, mu_s, mu_f, a, out_d):
    """The slide velocity of a contributing surface (:func:`contributes`): :func:`slide_vector`, or
    :func:`rim_slide` on its rim (e = (ex, ey))."""
    if md == ON_RIM:
        return rim_slide(fx, fy, ex, ey, mu_s, mu_f, a, out_d)
    return slide_vector(fx, fy, mu_s, mu_f, a, out_d)


@njit(cache=True)
def friction_vector(vx, vy, ex0, ey0, mu_s, mu_f, a, out_d):
    """The forward law µ(|v|) v/|v| [-] of a surface sliding at v [m/s] (along (ex0, ey0) at v = 0, a start from
    rest) and its derivative in ``out_d`` [2 × 2] (the tangential part µ/|v| left out at v = 0)."""
    s = math.hypot(vx, vy)
    if s > 0.0:
        ex = vx / s
        ey = vy / s
    else:
        ex = ex0
        ey = ey0
    mu, dmu = friction_at_rate(s, 1.0, mu_s, mu_f, a)
    radial_jacobian(ex, ey, dmu, mu / s if s > 0.0 else 0.0, out_d)
    return mu * ex, mu * ey


@njit(cache=True)
def force_residual(rx, ry, vx, vy, bf, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, dphi, dm, out, rim_dir):
    """G(r) = r − b_k − µ_k(|u̇_k|) û̇_k with u̇_k = G_k0 Ẋ + Σ_U G_kj φ_j(|f_j|) f̂_j (``out`` [6]: G, then ∂G/∂r row
    by row; G = ``gmap`` of :func:`isolator.solver.multisurface_rate_kernel.set_split`, U the sliding surfaces neither
    the pivot nor in the saturated set ``lock``: without a set u̇_k = Ẋ − Σ_j φ_j(|f_j|) f̂_j); False outside a disc
    |f_j| < µ_fast,j of U.  ``dphi``/``dm`` receive DΦ_j and DM_k at r."""
    k = pivot
    sx = 0.0
    sy = 0.0
    d00 = 0.0
    d01 = 0.0
    d11 = 0.0
    for j in range(mode.shape[0]):
        if j != k and contributes(mode[j], lock[j]):
            vjx, vjy = surface_rate(rx - bf[j, 0], ry - bf[j, 1], mode[j], rim_dir[j, 0], rim_dir[j, 1], mu_s[j],
                                    mu_f[j], a[j], dphi[j])
            if not math.isfinite(vjx):
                return False
            wk = gmap[k, 1 + j]
            sx += wk * vjx
            sy += wk * vjy
            d00 -= wk * dphi[j, 0, 0]
            d01 -= wk * dphi[j, 0, 1]
            d11 -= wk * dphi[j, 1, 1]
    fx, fy = friction_vector(gmap[k, 0] * vx + sx, gmap[k, 0] * vy + sy, ex0, ey0, mu_s[k], mu_f[k], a[k], dm)
    out[0] = rx - bf[k, 0] - fx
    out[1] = ry - bf[k, 1] - fy
    out[2] = 1.0 + dm[0, 0] * d00 + dm[0, 1] * d01
    out[3] = dm[0, 0] * d01 + dm[0, 1] * d11
    out[4] = dm[1, 0] * d00 + dm[1, 1] * d01
    out[5] = 1.0 + dm[1, 0] * d01 + dm[1, 1] * d11
    return True


@njit(cache=True)
def solve_force(vx, vy, bf, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, r, dphi, dm, rim_dir, stalled):
    """F/W (in ``r``, which holds a first guess) at which the sliding surfaces' rates sum to Ẋ = (vx, vy).

    The pivot k takes the rest of the velocity and its friction by the forward law (module docstring): Newton on
    the 2 × 2 system G(r) = 0 (:func:`force_residual`) from the better of two starts (the guess; the pivot
    carrying its share of Ẋ), its step halved until |G| falls (≤ 60 halvings: inside the static discs the continued
    laws are not monotone), ≤ 100 iterations.  ``dphi`` [n × 2 × 2] receives DΦ_j of the non-pivot sliding
    surfaces, ``dm`` DM_k.  Returns False when Newton does not converge (the caller shortens the step);
    ``stalled[0]`` is set where it stopped at the rounding floor with |G| > :data:`FORCE_RESIDUAL` left (∂G/∂r ~
    1e10 where a non-pivot φ_j is not resolvable: no root; :func:`rhs` then tries :func:`corner_force`).
    """
    n = mode.shape[0]
    k = pivot
    others = 0
    for j in range(n):
        if j != k and contributes(mode[j], lock[j]):
            others += 1
    c0 = gmap[k, 0]
    if others == 0 or (vx == 0.0 and vy == 0.0):
        # one surface (the forward law; or the pivot of a saturated set, its share c0 Ẋ), or at rest at a start:
        # every sliding surface at its onset, r on the pivot's static circle along the start direction (the
        # non-pivot rates are 0, :func:`rhs`)
        fx, fy = friction_vector(c0 * vx, c0 * vy, ex0, ey0, mu_s[k], mu_f[k], a[k], dm)
        r[0] = bf[k, 0] + fx
        r[1] = bf[k, 1] + fy
        return True
    out = np.empty(6)
    trial = np.empty(6)
    best = math.inf
    if math.isfinite(r[0]) and math.isfinite(r[1]) and force_residual(r[0], r[1], vx, vy, bf, mode, mu_s, mu_f, a,
                                                                        k, gmap, lock, ex0, ey0, dphi, dm, out, rim_dir):
        best = math.hypot(out[0], out[1])
    fx, fy = friction_vector(c0 * vx / (others + 1), c0 * vy / (others + 1), ex0, ey0, mu_s[k], mu_f[k], a[k], dm)
    if force_residual(bf[k, 0] + fx, bf[k, 1] + fy, vx, vy, bf, mode, mu_s, mu_f, a, k, gmap, lock, ex0, ey0, dphi, dm, trial,
                      rim_dir):
        if math.hypot(trial[0], trial[1]) < best:
            r[0] = bf[k, 0] + fx
            r[1] = bf[k, 1] + fy
            best = math.hypot(trial[0], trial[1])
    if not math.isfinite(best):
        return False
    force_residual(r[0], r[1], vx, vy, bf, mode, mu_s, mu_f, a, k, gmap, lock, ex0, ey0, dphi, dm, out, rim_dir)
    prev = math.inf
    for it in range(100):
        det = out[2] * out[5] - out[3] * out[4]
        if not (det != 0.0 and math.isfinite(det)):
            return False
        stx = (out[5] * out[0] - out[3] * out[1]) / det
        sty = (out[2] * out[1] - out[4] * out[0]) / det
        size = math.hypot(stx, sty)
        floor = 1e-15 * (math.hypot(r[0], r[1]) + mu_f[k])
        if size <= floor or (it >= 2 and size >= 0.5 * prev and size <= 1e3 * floor):
            # converged (or at the rounding floor): DΦ_j and DM_k are those at r
            stalled[0] = size > floor and math.hypot(out[0], out[1]) > FORCE_RESIDUAL
            return True
        lam = 1.0
        for _ in range(60):
            if force_residual(r[0] - lam * stx, r[1] - lam * sty, vx, vy, bf, mode, mu_s, mu_f, a, k, gmap, lock, ex0, ey0,
                              dphi, dm, trial, rim_dir) and (math.hypot(trial[0], trial[1]) < best or lam * size <= floor):
                break
            lam *= 0.5
        else:
            return False
        r[0] -= lam * stx
        r[1] -= lam * sty
        for p in range(6):
            out[p] = trial[p]
        best = math.hypot(out[0], out[1])
        prev = size
    return False


#: the force's residual |G| (F/W) past which :func:`solve_force`'s rounding-floor answer is no root: the corner of two
#: saturated circles is then tried (:func:`corner_force`)
FORCE_RESIDUAL = 1e-13
#: :func:`corner_force`'s Newton iterations at the most
CORNER_ITERATIONS = 50
#: a_i s_i from which a surface counts as saturated for :func:`corner_force` (µ_fast − µ there ≤ e^-10 of
#: µ_fast − µ_slow; with 20 PTS's lower bound stopped at 14.9669 s on the step floor, with 10 it runs to its end)
CORNER_SATURATED = 10.0
#: the sine |ŵ × n_j| from which a saturated surface's slip is apart from the pivot's (a corner); below it the slips
#: are parallel (the saturated set's map, or the answer of :func:`solve_force`)
CORNER_APART = 1e-4


@njit(cache=True)
def at_corner(r, bf, mode, lock, pivot, mu_s, mu_f):
    """Whether the force r lies at a corner of two saturated circles: the pivot k and a contributing surface j both
    within (µ_fast − µ_slow) e^(−:data:`CORNER_SATURATED`) of µ_fast (a·s ≥ CORNER_SATURATED: at the root
    r − b_k = µ_k(|u̇_k|) û̇_k), their friction directions (their slips) apart, |f̂_k × f̂_j| ≥ :data:`CORNER_APART`."""
    k = pivot
    if not (0 <= k < mode.shape[0]) or mode[k] != SLIDING:
        return False
    fkx = r[0] - bf[k, 0]
    fky = r[1] - bf[k, 1]
    rk = math.hypot(fkx, fky)
    edge = math.exp(-CORNER_SATURATED)
    if not (rk > 0.0 and mu_f[k] - rk <= (mu_f[k] - mu_s[k]) * edge):
        return False
    for j in range(mode.shape[0]):
        if j != k and mode[j] == SLIDING and lock[j] == 0:
            fx = r[0] - bf[j, 0]
            fy = r[1] - bf[j, 1]
            rj = math.hypot(fx, fy)
            if rj > 0.0 and mu_f[j] - rj <= (mu_f[j] - mu_s[j]) * edge and abs(fkx * fy - fky * fx) >= CORNER_APART * rk * rj:
                return True
    return False


@njit(cache=True)
def corner_members(mode, lock, pivot, idx):
    """The contributing non-pivot surfaces (:func:`contributes`) into ``idx``; their count, or −1 where one slides
    along its rim (its tangent law is not carried by :func:`corner_system`)."""
    nu = 0
    for j in range(mode.shape[0]):
        if j != pivot and contributes(mode[j], lock[j]):
            if mode[j] != SLIDING:
                return -1
            idx[nu] = j
            nu += 1
    return nu


@njit(cache=True)
def corner_arrays(mode, lock, pivot, r):
    """The members U (:func:`corner_members`: ``idx``, their count ``nu``, −1 with a rim slider) and the work arrays
    of :func:`corner_system` for its 2 + nu unknowns: z (r in its first two entries), res, jm, perm, dm, geo."""
    n = mode.shape[0]
    idx = np.empty(n, dtype=np.int64)
    nu = corner_members(mode, lock, pivot, idx)
    size = 2 + max(nu, 0)
    z = np.zeros(size)
    z[0] = r[0]
    z[1] = r[1]
    return (idx, nu, z, np.empty(size), np.empty((size, size)), np.zeros(size, dtype=np.int64), np.empty((2, 2)),
            np.empty((max(nu, 0), 3)))


@njit(cache=True)
def corner_system(vx, vy, bf, mu_s, mu_f, a, k, gmap, idx, nu, z, ex0, ey0, res, jm, dm, geo):
    """The force's equations with every law forward, at z = (r, s_U) (r = F/W, s_j the slide speeds of the
    contributing non-pivot surfaces U = ``idx[:nu]``): residual ``res`` [2 + nu] and Jacobian ``jm`` [(2+nu)²] of

        G(r, s) = r − b_k − µ_k(|w|) ŵ,  w = G_k0 Ẋ + Σ_U G_kj s_j n_j,  n_j = (r − b_j)/|r − b_j|,
        H_j(r, s) = |r − b_j| − µ_j(s_j),

    ∂G/∂r = I − DM_k Σ_U G_kj s_j (I − n_j n_jᵀ)/ρ_j, ∂G/∂s_j = −DM_k G_kj n_j, ∂H_j/∂r = n_jᵀ, ∂H_j/∂s_j = −µ_j'(s_j).
    ``dm`` receives DM_k at w, ``geo`` [nu × 3] (n_j, ρ_j).  Returns (ok, w_x, w_y); not ok where a ρ_j or an entry
    is not finite or zero."""
    size = 2 + nu
    for p in range(size):
        for q in range(size):
            jm[p, q] = 0.0
    wx = gmap[k, 0] * vx
    wy = gmap[k, 0] * vy
    for q in range(nu):
        j = idx[q]
        fx = z[0] - bf[j, 0]
        fy = z[1] - bf[j, 1]
        rho = math.hypot(fx, fy)
        if not (rho > 0.0 and math.isfinite(rho)):
            return False, 0.0, 0.0
        nx = fx / rho
        ny = fy / rho
        geo[q, 0] = nx
        geo[q, 1] = ny
        geo[q, 2] = rho
        wx += gmap[k, 1 + j] * z[2 + q] * nx
        wy += gmap[k, 1 + j] * z[2 + q] * ny
        mu, dmu = friction_at_rate(z[2 + q], 1.0, mu_s[j], mu_f[j], a[j])
        res[2 + q] = rho - mu
        jm[2 + q, 0] = nx
        jm[2 + q, 1] = ny
        jm[2 + q, 2 + q] = -dmu
    fx, fy = friction_vector(wx, wy, ex0, ey0, mu_s[k], mu_f[k], a[k], dm)
    res[0] = z[0] - bf[k, 0] - fx
    res[1] = z[1] - bf[k, 1] - fy
    jm[0, 0] = 1.0
    jm[1, 1] = 1.0
    for q in range(nu):
        j = idx[q]
        nx = geo[q, 0]
        ny = geo[q, 1]
        wk = gmap[k, 1 + j]
        cc = wk * z[2 + q] / geo[q, 2]
        p00 = cc * (1.0 - nx * nx)
        p01 = -cc * nx * ny
        p11 = cc * (1.0 - ny * ny)
        jm[0, 0] -= dm[0, 0] * p00 + dm[0, 1] * p01
        jm[0, 1] -= dm[0, 0] * p01 + dm[0, 1] * p11
        jm[1, 0] -= dm[1, 0] * p00 + dm[1, 1] * p01
        jm[1, 1] -= dm[1, 0] * p01 + dm[1, 1] * p11
        jm[0, 2 + q] = -wk * (dm[0, 0] * nx + dm[0, 1] * ny)
        jm[1, 2 + q] = -wk * (dm[1, 0] * nx + dm[1, 1] * ny)
    for p in range(size):
        if not math.isfinite(res[p]):
            return False, 0.0, 0.0
    return True, wx, wy


@njit(cache=True)
def corner_force(vx, vy, bf, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, r, sv):
    """F/W (in ``r``, which holds a first guess) and the slide speeds ``sv`` [m/s] of the contributing non-pivot
    surfaces at a *corner of two saturated circles*, every law used forward (never the inverse φ_j); False where it
    is not such a corner or Newton does not converge (the caller keeps :func:`solve_force`'s answer).

    The root of :func:`corner_system` (the same root as :func:`solve_force`'s, s_j = φ_j(|r − b_j|)).  Where two
    surfaces slide near µ_fast with slips a small angle θ apart, r lies at the corner of their circles |r − b| =
    µ_fast; µ_fast − |r − b_j| is a few hundred ulp of r, one ulp of r moves φ_j by ~1e-4 m/s, and the 2 × 2 Newton
    of :func:`solve_force` stalls (h141: the probe 0.7 g x + 0.02 g y at 0.7172 s, the inner pair at a·s = 27.73,
    slips 2.19e-2 rad apart: |G| = 1.8e-8, ∂G/∂r of condition 8e10), while the forward laws and the corner's
    geometry are well conditioned (1/sin θ).  Newton on the 2 + |U| unknowns with the analytic Jacobian (LU with a
    zero-pivot guard), ≤ :data:`CORNER_ITERATIONS`.  Taken only at a corner: the pivot and at least one other surface
    saturated (a·s ≥ :data:`CORNER_SATURATED`), every saturated one's slip apart from the pivot's, |ŵ × n_j| ≥
    :data:`CORNER_APART`.  Parallel saturated slips (a motion along a line, an equal double) are not a corner: there
    the split of the speed between the members rests on µ'(s) ~ e^(−a s) and is set by the rounding (h141's
    unguarded attempt moved the 1-D 35° pulse's impulse by 1.4e-3); the saturated set's map carries them."""
    n = mode.shape[0]
    k = pivot
    idx, nu, z, res, jm, perm, dm, geo = corner_arrays(mode, lock, k, r)
    if nu < 1:
        return False
    size = 2 + nu
    speed = math.hypot(vx, vy)
    for q in range(nu):
        j = idx[q]
        sp, _ = slide_rate(math.hypot(r[0] - bf[j, 0], r[1] - bf[j, 1]), 1.0, mu_s[j], mu_f[j], a[j])
        z[2 + q] = sp if math.isfinite(sp) else speed / (nu + 1)
    prev_s = math.inf
    for it in range(CORNER_ITERATIONS):
        ok, wx, wy = corner_system(vx, vy, bf, mu_s, mu_f, a, k, gmap, idx, nu, z, ex0, ey0, res, jm, dm, geo)
        if not ok or not lu_factor(jm, perm):
            return False
        lu_solve(jm, perm, res)
        # damped where a speed would move by more than 4/a_j (the law's exponential); a speed may pass 0 (the law
        # continued through the onset, as :func:`solve_force`'s: a surface about to stop)
        lam = 1.0
        for q in range(nu):
            ds = abs(res[2 + q])
            if not math.isfinite(ds):
                return False
            if a[idx[q]] * ds > 4.0:
                lam = min(lam, 4.0 / (a[idx[q]] * ds))
        big_r = 0.0
        big_s = 0.0
        for p in range(size):
            z[p] -= lam * res[p]
            if p < 2:
                big_r = max(big_r, abs(lam * res[p]))
            else:
                big_s = max(big_s, abs(lam * res[p]))
        if not (math.isfinite(big_r) and math.isfinite(big_s)):
            return False
        # converged: r to its rounding and the speeds to 1e-12, or the speeds' steps stalled at their rounding
        # (below 1e-6 of the speed: the split's sensitivity to the rounding of r grows as 1/sin²θ)
        floor_s = 1e-12 * speed
        s_done = big_s <= floor_s or (it >= 2 and lam == 1.0 and big_s >= 0.5 * prev_s and big_s <= 1e-6 * speed)
        prev_s = big_s
        if big_r <= 2e-15 * (abs(z[0]) + abs(z[1]) + mu_f[k]) and s_done:
            # a corner?  the pivot and a member saturated, every saturated member's slip apart from the pivot's
            ok, wx, wy = corner_system(vx, vy, bf, mu_s, mu_f, a, k, gmap, idx, nu, z, ex0, ey0, res, jm, dm, geo)
            ws = math.hypot(wx, wy)
            if not (ok and a[k] * ws >= CORNER_SATURATED):
                return False
            members = 0
            for q in range(nu):
                if a[idx[q]] * z[2 + q] >= CORNER_SATURATED:
                    members += 1
                    if not abs(wx * geo[q, 1] - wy * geo[q, 0]) >= CORNER_APART * ws:
                        return False
            if members == 0:
                return False
            r[0] = z[0]
            r[1] = z[1]
            for j in range(n):
                sv[j] = 0.0
            for q in range(nu):
                sv[idx[q]] = z[2 + q]
            return True
    return False


@njit(cache=True)
def corner_jacobian(y, g, c, bmat, bf, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, r, sv, out_jac):
    """∂(dy/dt)/∂y at a corner (:func:`corner_force`'s root) by the implicit function theorem on its 2 + |U| system
    (:func:`corner_system`, well conditioned there): dz/dy = −(∂F/∂z)⁻¹ ∂F/∂y for z = (r, s_U), with
    ∂G/∂Ẋ = −DM_k G_k0, ∂G/∂u_p = −B_kp I + DM_k Σ_U G_kj s_j (I − n_j n_jᵀ)/ρ_j B_jp, ∂H_j/∂u_p = −B_jp n_jᵀ; then
    Ẍ = −g r − c Ẋ − a_g, u̇_j = s_j n_j (d(u̇_j) = n_j ds_j + s_j (I − n_j n_jᵀ)/ρ_j (dr − Σ_p B_jp du_p)) and the
    pivot's and the set's rates by the split's map.  Not from DΦ_j, whose radial part 1/µ_j'(s_j) ~ e^(a s) is ~1e27
    at a·s ≈ 60 (h141).  False where the system is singular."""
    n = bmat.shape[0]
    m = 2 + 2 * n
    k = pivot
    idx, nu, z, res, jm, perm, dm, geo = corner_arrays(mode, lock, k, r)
    if nu < 1:
        return False
    size = 2 + nu
    for q in range(nu):
        z[2 + q] = sv[idx[q]]
    ok, _, _ = corner_system(y[0], y[1], bf, mu_s, mu_f, a, k, gmap, idx, nu, z, ex0, ey0, res, jm, dm, geo)
    if not ok or not lu_factor(jm, perm):
        return False
    dz = np.empty((size, m))
    col = np.empty(size)
    for s in range(m):
        if s < 2:
            col[0] = -dm[0, s] * gmap[k, 0]
            col[1] = -dm[1, s] * gmap[k, 0]
            for q in range(nu):
                col[2 + q] = 0.0
        else:
            p = (s - 2) // 2
            comp = (s - 2) % 2
            px = 0.0
            py = 0.0
            for q in range(nu):
                j = idx[q]
                nx = geo[q, 0]
                ny = geo[q, 1]
                ncomp = nx if comp == 0 else ny
                cc = gmap[k, 1 + j] * z[2 + q] / geo[q, 2] * bmat[j, p]
                px += cc * ((1.0 if comp == 0 else 0.0) - nx * ncomp)
                py += cc * ((1.0 if comp == 1 else 0.0) - ny * ncomp)
                col[2 + q] = -bmat[j, p] * ncomp
            col[0] = (-bmat[k, p] if comp == 0 else 0.0) + dm[0, 0] * px + dm[0, 1] * py
            col[1] = (-bmat[k, p] if comp == 1 else 0.0) + dm[1, 0] * px + dm[1, 1] * py
        lu_solve(jm, perm, col)
        for p in range(size):
            dz[p, s] = -col[p]
            if not math.isfinite(dz[p, s]):
                return False
    for p in range(m):
        for s in range(m):
            out_jac[p, s] = 0.0
    for p in range(2):
        for s in range(m):
            out_jac[p, s] = -g * dz[p, s] - (c if p == s else 0.0)
    for ell in range(n):
        if ell == k or lock[ell] == 1:
            out_jac[2 + 2 * ell, 0] = gmap[ell, 0]
            out_jac[3 + 2 * ell, 1] = gmap[ell, 0]
    dv = np.empty((2, m))
    for q in range(nu):
        j = idx[q]
        nx = geo[q, 0]
        ny = geo[q, 1]
        cc = z[2 + q] / geo[q, 2]
        for s in range(m):
            ex = dz[0, s]
            ey = dz[1, s]
            if s >= 2:
                p = (s - 2) // 2
                if s % 2 == 0:
                    ex -= bmat[j, p]
                else:
                    ey -= bmat[j, p]
            along = nx * ex + ny * ey
            dv[0, s] = nx * dz[2 + q, s] + cc * (ex - nx * along)
            dv[1, s] = ny * dz[2 + q, s] + cc * (ey - ny * along)
        for p in range(2):
            for s in range(m):
                out_jac[2 + 2 * j + p, s] = dv[p, s]
                for ell in range(n):
                    if ell == k or lock[ell] == 1:
                        out_jac[2 + 2 * ell + p, s] += gmap[ell, 1 + j] * dv[p, s]
    return True


@njit(cache=True)
def rim_normals(y, mode, out_e):
    """The outward unit normal e_i = u_i/|u_i| of each surface on its rim (:data:`ON_RIM`, :data:`HELD`) in ``out_e``."""
    for i in range(mode.shape[0]):
        if mode[i] == ON_RIM or mode[i] == HELD:
            ux = y[2 + 2 * i]
            uy = y[3 + 2 * i]
            rho = math.hypot(ux, uy)
            if rho > 0.0:
                out_e[i, 0] = ux / rho
                out_e[i, 1] = uy / rho


@njit(cache=True)
def rhs(y, agx, agy, g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, r, bf, out_dy, out_jac, want_jac):
    """dy/dt of y = (Ẋ, u_1..u_n) in a mode; ``r`` [2] in: a guess, out: F/W.  Returns (ok, friction power g Σ
    (r − b_i)·dū_i/dt per unit mass).  ``out_jac`` [m × m] receives ∂(dy/dt)/∂y when ``want_jac`` (the implicit
    function theorem on G(r; Ẋ, u) = 0, module docstring)."""
    n = bmat.shape[0]
    m = 2 + 2 * n
    back_forces(y, bmat, bf)
    dphi = np.zeros((n, 2, 2))
    dm = np.empty((2, 2))
    rim_dir = np.zeros((n, 2))
    rim_normals(y, mode, rim_dir)
    for p in range(m):
        out_dy[p] = 0.0
    at_rest = y[0] == 0.0 and y[1] == 0.0
    r0x = r[0]
    r0y = r[1]
    stalled = np.zeros(1, dtype=np.bool_)
    good = solve_force(y[0], y[1], bf, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, r, dphi, dm, rim_dir, stalled)
    corner = False
    sv = np.zeros(n)
    if not at_rest and (not good or stalled[0] or at_corner(r, bf, mode, lock, pivot, mu_s, mu_f)):
        # at a corner of two saturated circles every law forward (corner_force): where solve_force stalled or found
        # no force, and where it converged too (its φ_j there carries ~1e-3 of a·s of noise: µ_fast − |f_j| a few
        # hundred ulp; the stages' Newton then failed at every step longer than ~5e-7 s, the probe at 0.7332 s);
        # elsewhere the answer before (none, or the stalled one, as before h151)
        rf = np.empty(2)
        rf[0] = r0x if (math.isfinite(r0x) and math.isfinite(r0y)) else r[0]
        rf[1] = r0y if (math.isfinite(r0x) and math.isfinite(r0y)) else r[1]
        corner = corner_force(y[0], y[1], bf, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, rf, sv)
        if corner:
            r[0] = rf[0]
            r[1] = rf[1]
    if not good and not corner:
        return False, 0.0
    out_dy[0] = -g * r[0] - c * y[0] - agx
    out_dy[1] = -g * r[1] - c * y[1] - agy
    for j in range(n):
        if corner and j != pivot and contributes(mode[j], lock[j]):
            rho = math.hypot(r[0] - bf[j, 0], r[1] - bf[j, 1])
            out_dy[2 + 2 * j] = sv[j] * (r[0] - bf[j, 0]) / rho
            out_dy[3 + 2 * j] = sv[j] * (r[1] - bf[j, 1]) / rho
        elif j != pivot and contributes(mode[j], lock[j]) and not at_rest:
            vjx, vjy = surface_rate(r[0] - bf[j, 0], r[1] - bf[j, 1], mode[j], rim_dir[j, 0], rim_dir[j, 1], mu_s[j],
                                    mu_f[j], a[j], dphi[j])
            out_dy[2 + 2 * j] = vjx
            out_dy[3 + 2 * j] = vjy
    # the pivot's rate and the saturated set's by the split's map: G_ℓ0 Ẋ + Σ_U G_ℓj u̇_j (the series constraint
    # Ẋ − Σ_j u̇_j without a set)
    for ell in range(n):
        if ell == pivot or lock[ell] == 1:
            sx = 0.0
            sy = 0.0
            for j in range(n):
                if j != pivot and contributes(mode[j], lock[j]):
                    sx += gmap[ell, 1 + j] * out_dy[2 + 2 * j]
                    sy += gmap[ell, 1 + j] * out_dy[3 + 2 * j]
            out_dy[2 + 2 * ell] = gmap[ell, 0] * y[0] + sx
            out_dy[3 + 2 * ell] = gmap[ell, 0] * y[1] + sy
    power = 0.0
    for i in range(n):
        ubx = 0.0
        uby = 0.0
        for q in range(n):
            ubx += smat[i, q] * out_dy[2 + 2 * q]
            uby += smat[i, q] * out_dy[3 + 2 * q]
        power += (r[0] - bf[i, 0]) * ubx + (r[1] - bf[i, 1]) * uby
    if want_jac and corner:
        if not corner_jacobian(y, g, c, bmat, bf, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, r, sv, out_jac):
            return False, 0.0
    elif want_jac:
        k = pivot
        for p in range(m):
            for q in range(m):
                out_jac[p, q] = 0.0
        dsum = np.zeros((2, 2))
        turn = np.zeros((n, 2, 2))  # the rim slides' direct ∂u̇_j/∂u_j (rim_turn)
        for j in range(n):
            if j != k and contributes(mode[j], lock[j]):
                dsum += -gmap[k, 1 + j] * dphi[j]
                if mode[j] == ON_RIM:
                    rim_turn(r[0] - bf[j, 0], r[1] - bf[j, 1], y[2 + 2 * j], y[3 + 2 * j], mu_s[j], mu_f[j], a[j],
                             turn[j])
        amat = np.eye(2) + dm @ dsum
        det = amat[0, 0] * amat[1, 1] - amat[0, 1] * amat[1, 0]
        if not (det != 0.0 and math.isfinite(det)):
            return False, 0.0
        ainv = np.empty((2, 2))
        ainv[0, 0] = amat[1, 1] / det
        ainv[0, 1] = -amat[0, 1] / det
        ainv[1, 0] = -amat[1, 0] / det
        ainv[1, 1] = amat[0, 0] / det
        # A = I − DM Σ_U G_kj DΦ_j; dr/dẊ = A⁻¹ DM G_k0; dr/du_q = A⁻¹ (B_kq I − DM Σ_U G_kj DΦ_j B_jq)
        drv = (ainv @ dm) * gmap[k, 0]
        dru = np.empty((n, 2, 2))
        for q in range(n):
            inner = bmat[k, q] * np.eye(2)
            for j in range(n):
                if j != k and contributes(mode[j], lock[j]):
                    inner += (-gmap[k, 1 + j] * bmat[j, q]) * (dm @ dphi[j])
            if q != k and mode[q] == ON_RIM:
                inner += gmap[k, 1 + q] * (dm @ turn[q])
            dru[q] = ainv @ inner
        for p in range(2):
            for s in range(2):
                out_jac[p, s] = -g * drv[p, s] - (c if p == s else 0.0)
                for q in range(n):
                    out_jac[p, 2 + 2 * q + s] = -g * dru[q, p, s]
        # the other rates: du̇_j = DΦ_j (dr − Σ_q B_jq du_q); the pivot's and the set's: G_ℓ0 dẊ + Σ_U G_ℓj du̇_j
        for ell in range(n):
            if ell == k or lock[ell] == 1:
                for p in range(2):
                    for s in range(2):
                        out_jac[2 + 2 * ell + p, s] = gmap[ell, 0] if p == s else 0.0
        for j in range(n):
            if j != k and contributes(mode[j], lock[j]):
                dv = dphi[j] @ drv
                for p in range(2):
                    for s in range(2):
                        out_jac[2 + 2 * j + p, s] = dv[p, s]
                        for ell in range(n):
                            if ell == k or lock[ell] == 1:
                                out_jac[2 + 2 * ell + p, s] += gmap[ell, 1 + j] * dv[p, s]
                for q in range(n):
                    du = dphi[j] @ (dru[q] - bmat[j, q] * np.eye(2))
                    if q == j:
                        du += turn[j]
                    for p in range(2):
                        for s in range(2):
                            out_jac[2 + 2 * j + p, 2 + 2 * q + s] = du[p, s]
                            for ell in range(n):
                                if ell == k or lock[ell] == 1:
                                    out_jac[2 + 2 * ell + p, 2 + 2 * q + s] += gmap[ell, 1 + j] * du[p, s]
    return True, g * power


@njit(cache=True)
def stage_predict(y0, z, j, rs_last, ys_last, drdy, ys, rs):
    """Stage ``j``'s state ys = y0 + z[j] and its force's start rs[j] = rs_last[j] + (dr/dy)(ys − ys_last[j]) (the
    predictor of :func:`stage_residual`, also taken by :func:`radau_step`'s energy quadrature)."""
    m = y0.shape[0]
    for p in range(m):
        ys[p] = y0[p] + z[j, p]
    for q in range(2):
        guess = rs_last[j, q]
        for p in range(m):
            guess += drdy[q, p] * (ys[p] - ys_last[j, p])
        rs[j, q] = guess


@njit(cache=True)
def stage_residual(y0, z, h, a_start, slope, g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, rs, bf, ys, dy,
                   fz, jac, want_jac, res, rs_last, ys_last, drdy):
    """The collocation's residual −(Z − h (A ⊗ I) F(y0 + Z)) at the stage increments ``z`` [3 × m] into ``res``;
    the stage Jacobians into ``jac`` when ``want_jac``; ``rs`` [3 × 2] out: the stages' forces.  False where a stage
    has no force (outside the slide laws' domain).

    Each stage's force is sought from the *predictor* rs_last[j] + (dr/dy)(y_j − ys_last[j]): the force last found
    for that stage (at ys_last[j]) moved along the force's derivative ``drdy`` [2 × m] at the step's start (zero:
    no predictor).  Without it Newton started from the force of another state: where a non-pivot surface is near
    saturation its circle |r − b_j| = µ_fast,j moves with b_j by far more than the gap µ_fast,j − |r − b_j| within a
    step (PTS ×1.75 lower bound at 11.8755 s, a·v ≈ 15.8 on surfaces 1 and 4: b_1 moves 1e-7 in a 3e-7 s step, the
    gap is 2.7e-9), the start lies outside that circle, and the damped Newton of :func:`solve_force` stalled (its
    residual at 1.5e-6 after 100 iterations) until the steps fell to 1e-8 s and the work bound stopped the run.  On
    success ``rs_last``/``ys_last`` take the stage's force and state."""
    m = y0.shape[0]
    for j in range(3):
        stage_predict(y0, z, j, rs_last, ys_last, drdy, ys, rs)
        tj = RADAU_C[j] * h
        good, _ = rhs(ys, a_start[0] + slope[0] * tj, a_start[1] + slope[1] * tj, g, c, bmat, smat, mode, mu_s,
                      mu_f, a, pivot, gmap, lock, ex0, ey0, rs[j], bf, dy, jac[j], want_jac)
        if not good:
            return False
        for q in range(2):
            rs_last[j, q] = rs[j, q]
        for p in range(m):
            ys_last[j, p] = ys[p]
        for p in range(m):
            fz[j, p] = dy[p]
    for j in range(3):
        for p in range(m):
            total = z[j, p]
            for k in range(3):
                total -= h * RADAU_A[j, k] * fz[k, p]
            res[j * m + p] = -total
            if not math.isfinite(total):
                return False
    return True


@njit(cache=True)
def _scaled_norm(vec, scale, m):
    size = 0.0
    for q in range(vec.shape[0]):
        size = max(size, abs(vec[q]) / scale[q % m])
    return size


@njit(cache=True)
def radau_step(y0, h, a_start, slope, g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, r_guess, scale, y1,
               quad, z_full, guess, lu, piv, use_lu, drdy):
    """One Radau IIA step of length h from y0 (ground acceleration a_start + slope τ, 2-vectors); Newton's
    iterations, or −1 when Newton fails (``r_guess``: the force at y0; ``drdy``: its derivative, the stages' force
    predictor of :func:`stage_residual`).  The conventions of
    :func:`isolator.solver.multisurface_rate_kernel.radau_step` (``guess``/``z_full``: the half steps start from
    the full step's polynomial; ``use_lu``: simplified Newton with the caller's factors, full Newton where it does
    not contract); the full Newton steps are damped (halved while the scaled residual does not fall, ≤ 20 times:
    near Ẋ = 0 the friction's direction turns fast and undamped Newton cycles).  ``quad``: the step's
    (−∫a_g·Ẋ, c∫|Ẋ|², friction work) [J/kg]."""
    m = y0.shape[0]
    n = (m - 2) // 2
    z = np.zeros((3, m))
    if guess.shape[0] == 3:
        for j in range(3):
            for p in range(m):
                total = 0.0
                for k in range(3):
                    total += guess[j, k] * z_full[k, p]
                z[j, p] = total
    fz = np.empty((3, m))
    jac = np.empty((3, m, m))
    big = np.empty((3 * m, 3 * m))
    res = np.empty(3 * m)
    res_try = np.empty(3 * m)
    z_try = np.empty((3, m))
    delta = np.empty(3 * m)
    ys = np.empty(m)
    dy = np.empty(m)
    bf = np.empty((n, 2))
    rs = np.empty((3, 2))
    rs_last = np.empty((3, 2))
    ys_last = np.empty((3, m))
    for j in range(3):
        rs[j, 0] = r_guess[0]
        rs[j, 1] = r_guess[1]
        rs_last[j, 0] = r_guess[0]
        rs_last[j, 1] = r_guess[1]
        for p in range(m):
            ys_last[j, p] = y0[p]
    if guess.shape[0] != 3 and y0[0] == 0.0 and y0[1] == 0.0:
        # a start from rest: the direction of the motion is undefined at Ẋ = 0 (every Jacobian there singular);
        # Newton starts from the stages moving along the start direction e with the acceleration the mass at
        # rest has along e (linear in τ between the step's ends), the displacement shared by the sliding surfaces
        good0, _ = rhs(y0, a_start[0], a_start[1], g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, rs[0],
                       bf, dy, jac[0], np.bool_(False))
        p0 = dy[0] * ex0 + dy[1] * ey0
        good1, _ = rhs(y0, a_start[0] + slope[0] * h, a_start[1] + slope[1] * h, g, c, bmat, smat, mode, mu_s, mu_f,
                       a, pivot, gmap, lock, ex0, ey0, rs[1], bf, dy, jac[0], np.bool_(False))
        p1 = dy[0] * ex0 + dy[1] * ey0
        n_sliding = 0
        for i in range(n):
            n_sliding += mode[i]
        if good0 and good1 and n_sliding > 0:
            for j in range(3):
                tj = RADAU_C[j] * h
                speed = p0 * tj + 0.5 * (p1 - p0) * tj * tj / h
                dist = (0.5 * p0 * tj * tj + (p1 - p0) * tj * tj * tj / (6.0 * h)) / n_sliding
                z[j, 0] = speed * ex0
                z[j, 1] = speed * ey0
                for i in range(n):
                    if mode[i] == 1:
                        z[j, 2 + 2 * i] = dist * ex0
                        z[j, 3 + 2 * i] = dist * ey0
        for j in range(3):
            rs[j, 0] = r_guess[0]
            rs[j, 1] = r_guess[1]
    z_start = z.copy()
    simplified = use_lu
    prev = math.inf
    converged = False
    it = 0
    n_it = 0
    size = 0.0
    have_res = False
    while n_it < 40:
        n_it += 1
        fall_back = False
        if not have_res:
            ok = stage_residual(y0, z, h, a_start, slope, g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0,
                                rs, bf, ys, dy, fz, jac, not simplified, res, rs_last, ys_last, drdy)
        else:
            ok = True
        have_res = False
        if not ok:
            if not simplified:
                return -1
            fall_back = True
        elif simplified:
            for p in range(3 * m):
                delta[p] = res[p]
            lu_solve(lu, piv, delta)
            size = 0.0
            for j in range(3):
                for p in range(m):
                    z[j, p] += delta[j * m + p]
                    size = max(size, abs(delta[j * m + p]) / scale[p])
            if not math.isfinite(size):
                fall_back = True
            else:
                theta = size / prev if it >= 1 else 0.0
                if size <= 1e-15 or (it >= 1 and theta < 0.9 and theta * size <= 1e-16 * (1.0 - theta)):
                    converged = True
                    break
                if (it >= 1 and theta >= 1.0) or it >= 10:
                    fall_back = True
        else:
            for j in range(3):
                for p in range(m):
                    for k in range(3):
                        for q in range(m):
                            big[j * m + p, k * m + q] = ((1.0 if (j == k and p == q) else 0.0)
                                                         - h * RADAU_A[j, k] * jac[k, p, q])
            for p in range(3 * m):
                for q in range(3 * m):
                    if not math.isfinite(big[p, q]):
                        return -1
            if not solve_or_refuse(big, res, delta):
                return -1  # a singular stage matrix: the caller shortens the step
            full = _scaled_norm(delta, scale, m)
            if not math.isfinite(full):
                return -1
            norm0 = _scaled_norm(res, scale, m)
            lam = 1.0
            accepted = False
            for _ in range(20):
                for j in range(3):
                    for p in range(m):
                        z_try[j, p] = z[j, p] + lam * delta[j * m + p]
                if stage_residual(y0, z_try, h, a_start, slope, g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0,
                                  ey0, rs, bf, ys, dy, fz, jac, np.bool_(True), res_try, rs_last, ys_last, drdy):
                    if _scaled_norm(res_try, scale, m) < norm0 or lam * full <= 1e-13:
                        accepted = True
                        break
                lam *= 0.5
            if not accepted:
                return -1
            for j in range(3):
                for p in range(m):
                    z[j, p] = z_try[j, p]
            for p in range(3 * m):
                res[p] = res_try[p]
            have_res = True  # the residual and Jacobians at the new z are those just computed
            size = lam * full
            if size <= 1e-15 or (it >= 2 and size >= 0.5 * prev and size <= 1e-11):
                converged = True
                break
        if fall_back:
            simplified = False
            for j in range(3):
                for p in range(m):
                    z[j, p] = z_start[j, p]
            prev = math.inf
            it = 0
            have_res = False
            continue
        prev = size
        it += 1
    if not converged:
        return -1
    if guess.shape[0] != 3:
        for j in range(3):
            for p in range(m):
                z_full[j, p] = z[j, p]
    # the energies by the collocation's quadrature, the slide rates the stage derivatives A⁻¹Z/h (as in 1-D)
    q_in = 0.0
    q_visc = 0.0
    q_fric = 0.0
    inv_h = 1.0 / h
    for j in range(3):
        stage_predict(y0, z, j, rs_last, ys_last, drdy, ys, rs)
        tj = RADAU_C[j] * h
        agx = a_start[0] + slope[0] * tj
        agy = a_start[1] + slope[1] * tj
        good, _ = rhs(ys, agx, agy, g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, rs[j], bf, dy, jac[j],
                      np.bool_(False))
        if not good:
            return -1
        for p in range(2, m):
            total = 0.0
            for k in range(3):
                total += RADAU_A_INV[j, k] * z[k, p]
            dy[p] = total * inv_h
        stage_power = 0.0
        for i in range(n):
            ubx = 0.0
            uby = 0.0
            for q in range(n):
                ubx += smat[i, q] * dy[2 + 2 * q]
                uby += smat[i, q] * dy[3 + 2 * q]
            stage_power += (rs[j, 0] - bf[i, 0]) * ubx + (rs[j, 1] - bf[i, 1]) * uby
        w = h * RADAU_A[2, j]
        q_in -= w * (agx * ys[0] + agy * ys[1])
        q_visc += w * c * (ys[0] * ys[0] + ys[1] * ys[1])
        q_fric += w * g * stage_power
    for p in range(m):
        y1[p] = y0[p] + z[2, p]
    r_guess[0] = rs[2, 0]
    r_guess[1] = rs[2, 1]
    quad[0] = q_in
    quad[1] = q_visc
    quad[2] = q_fric
    return n_it


@njit(cache=True)
def double_step(y0, h, a_start, slope, g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, r_guess, scale, y1,
                quad):
    """Two Radau steps of h/2 (kept) and one of h (the estimate); the scaled difference (inf: failed).

    ``quad`` [4]: the halves' energies and the Newton iterations of the three steps; simplified Newton with one
    Jacobian at y0 factored for h and for h/2, as :func:`isolator.solver.multisurface_rate_kernel.double_step`.
    """
    m = y0.shape[0]
    n = (m - 2) // 2
    jac0 = np.empty((m, m))
    lu_full = np.empty((3 * m, 3 * m))
    lu_half = np.empty((3 * m, 3 * m))
    piv_full = np.zeros(3 * m, dtype=np.int64)
    piv_half = np.zeros(3 * m, dtype=np.int64)
    dy0 = np.empty(m)
    bf = np.empty((n, 2))
    r0 = r_guess.copy()
    good, _ = rhs(y0, a_start[0], a_start[1], g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, r0, bf, dy0,
                  jac0, np.bool_(True))
    use_full = np.bool_(False)
    use_half = np.bool_(False)
    # the force's derivative dr/dy = −(∂Ẍ/∂y + c [I 0])/g from the Jacobian's first rows: the stages' force predictor
    drdy = np.zeros((2, m))
    if good and not (y0[0] == 0.0 and y0[1] == 0.0):  # at rest the Jacobian is singular: full Newton
        for q in range(2):
            for p in range(m):
                drdy[q, p] = -(jac0[q, p] + (c if p == q else 0.0)) / g
                if not math.isfinite(drdy[q, p]):
                    drdy[q, p] = 0.0
        stage_matrix(h, jac0, lu_full)
        use_full = lu_factor(lu_full, piv_full)
        stage_matrix(0.5 * h, jac0, lu_half)
        use_half = lu_factor(lu_half, piv_half)
    y_full = np.empty(m)
    y_mid = np.empty(m)
    q_full = np.empty(3)
    q1 = np.empty(3)
    q2 = np.empty(3)
    z_full = np.empty((3, m))
    no_guess = np.empty((0, 3))
    a_mid = np.empty(2)
    half = 0.5 * h
    a_mid[0] = a_start[0] + slope[0] * half
    a_mid[1] = a_start[1] + slope[1] * half
    quad[3] = 0.0
    rg = r0.copy()
    it0 = radau_step(y0, h, a_start, slope, g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, rg, scale,
                     y_full, q_full, z_full, no_guess, lu_full, piv_full, use_full, drdy)
    if it0 < 0:
        return math.inf
    quad[3] = it0
    rg[0] = r0[0]
    rg[1] = r0[1]
    it1 = radau_step(y0, half, a_start, slope, g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, rg, scale,
                     y_mid, q1, z_full, GUESS_FIRST_HALF, lu_half, piv_half, use_half, drdy)
    if it1 < 0:
        return math.inf
    quad[3] += it1
    it2 = radau_step(y_mid, half, a_mid, slope, g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, ex0, ey0, rg, scale,
                     y1, q2, z_full, GUESS_SECOND_HALF, lu_half, piv_half, use_half, drdy)
    if it2 < 0:
        return math.inf
    quad[3] += it2
    err = 0.0
    for p in range(m):
        err = max(err, abs(y1[p] - y_full[p]) / scale[p])
    for k in range(3):
        quad[k] = q1[k] + q2[k]
    r_guess[0] = rg[0]
    r_guess[1] = rg[1]
    return err


@njit(cache=True)
def held_value(fx, fy, md, ex, ey, mu_s):
    """How far a standing surface holds at friction excess f = r − b (≥ 0: it holds): µ_slow − |f| in its static
    disc (:data:`STUCK`); on its rim (:data:`HELD`, e = (ex, ey) outward) the disc plus the rim's normal cone,
    µ_slow − |f·t| where f·e ≥ 0 (the rim takes the normal part) and µ_slow − |f| where f·e < 0 (continuous at
    f·e = 0): the 1-D model's held surface, which leaves its rim only inward (its window loses that side's limit)."""
    if md == HELD and fx * ex + fy * ey >= 0.0:
        return mu_s - abs(-fx * ey + fy * ex)
    return mu_s - math.hypot(fx, fy)


@njit(cache=True)
def event_values(y, r, mode, pivot, mu_s, cap, bmat, bf, out_e):
    """The event functions at a state (≥ 0: no event): slot 2i a non-pivot surface stopping (|f_i| − µ_slow,i; on
    its rim |f_i·t_i| − µ_slow,i) or a standing one starting (:func:`held_value`), slot 2i+1 a sliding surface's rim
    (d_i* − |u_i|) or a surface sliding along its rim leaving it inward (the rim's reaction f_i·e_i)."""
    n = mode.shape[0]
    back_forces(y, bmat, bf)
    for i in range(n):
        fx = r[0] - bf[i, 0]
        fy = r[1] - bf[i, 1]
        out_e[2 * i + 1] = math.inf
        md = mode[i]
        if md == SLIDING:
            out_e[2 * i] = math.inf if i == pivot else math.hypot(fx, fy) - mu_s[i]
            if math.isfinite(cap[i]):
                out_e[2 * i + 1] = cap[i] - math.hypot(y[2 + 2 * i], y[3 + 2 * i])
        elif md == ON_RIM:
            rho = math.hypot(y[2 + 2 * i], y[3 + 2 * i])
            ex = y[2 + 2 * i] / rho
            ey = y[3 + 2 * i] / rho
            out_e[2 * i] = abs(-fx * ey + fy * ex) - mu_s[i]
            out_e[2 * i + 1] = fx * ex + fy * ey
        elif md == HELD:
            rho = math.hypot(y[2 + 2 * i], y[3 + 2 * i])
            out_e[2 * i] = held_value(fx, fy, md, y[2 + 2 * i] / rho, y[3 + 2 * i] / rho, mu_s[i])
        else:
            out_e[2 * i] = mu_s[i] - math.hypot(fx, fy)


@njit(cache=True)
def aligned_set(dy, lock, pivot):
    """True when every member of the saturated set slides the pivot's way, |û̇_ℓ × û̇_k| ≤ :data:`ALIGNED_SET` and
    û̇_ℓ·û̇_k > 0 (or the set is empty): the only motions where the 1-D set's map on each component is the slow
    manifold (a pair along a line, an equal double).  Where the directions part it is not: on a saturating TFP pulse
    with a turning cross component the levels (24, 22), (22, 20), (20, 18) moved the history by 3e-4 and 1.4e-4 of
    the peak (h122; the 1-D set: 5e-13), so no set is formed there and the run stops where the slide law is not
    resolvable, refused in one line."""
    if not (0 <= pivot < lock.shape[0]):
        return True
    kx = dy[2 + 2 * pivot]
    ky = dy[3 + 2 * pivot]
    sk = math.hypot(kx, ky)
    for ell in range(lock.shape[0]):
        if lock[ell] == 1 and ell != pivot:
            lx = dy[2 + 2 * ell]
            ly = dy[3 + 2 * ell]
            sl = math.hypot(lx, ly)
            if not (abs(lx * ky - ly * kx) <= ALIGNED_SET * sl * sk and lx * kx + ly * ky > 0.0):
                return False
    return True


@njit(cache=True)
def exit_time(nx, ny, qx, qy, bf, mu_s, mode, rim_dir):
    """First local time s ≥ 0 at which r_need + q s leaves a standing surface's set (inf: never, 0: out already):
    a static disc |r − b_i| ≤ µ_slow,i, the larger root of |p + q s|² = µ² (p = r_need − b_i); for a surface held
    on its rim (outward normal e = ``rim_dir[i]``, tangent t) the disc plus the rim's normal cone
    (:func:`held_value`, convex): the first of the tangent lines p·t = ±µ crossed outward where p·e ≥ 0 and the
    circle's larger root where p·e ≤ 0."""
    first = math.inf
    qq = qx * qx + qy * qy
    for i in range(bf.shape[0]):
        px = nx - bf[i, 0]
        py = ny - bf[i, 1]
        if mode[i] == HELD:
            ex = rim_dir[i, 0]
            ey = rim_dir[i, 1]
            if held_value(px, py, np.int64(HELD), ex, ey, mu_s[i]) < 0.0:
                return 0.0
            if not qq > 0.0:
                continue
            qt = -qx * ey + qy * ex
            if qt != 0.0:
                side = mu_s[i] if qt > 0.0 else -mu_s[i]
                s = max((side - (-px * ey + py * ex)) / qt, 0.0)
                if (px + qx * s) * ex + (py + qy * s) * ey >= 0.0:
                    first = min(first, s)
            cc = px * px + py * py - mu_s[i] * mu_s[i]
            bb = 2.0 * (px * qx + py * qy)
            disc = bb * bb - 4.0 * qq * cc
            if disc >= 0.0:
                root = math.sqrt(disc)
                s = (-bb + root) / (2.0 * qq) if bb <= 0.0 else -2.0 * cc / (bb + root)
                if s >= 0.0 and (px + qx * s) * ex + (py + qy * s) * ey <= 0.0:
                    first = min(first, s)
            continue
        cc = px * px + py * py - mu_s[i] * mu_s[i]
        if cc > 0.0:
            return 0.0
        if qq > 0.0:
            bb = 2.0 * (px * qx + py * qy)
            disc = math.sqrt(max(bb * bb - 4.0 * qq * cc, 0.0))
            s = (-bb + disc) / (2.0 * qq) if bb <= 0.0 else -2.0 * cc / (bb + disc)
            first = min(first, max(s, 0.0))
    return first


@njit(cache=True)
def holds_at_rest(nx, ny, bf, mode, mu_s, rim_dir):
    """Whether r_need = (nx, ny) lies in every standing surface's set (:func:`held_value` ≥ 0)."""
    for i in range(bf.shape[0]):
        if held_value(nx - bf[i, 0], ny - bf[i, 1], mode[i], rim_dir[i, 0], rim_dir[i, 1], mu_s[i]) < 0.0:
            return False
    return True


@njit(cache=True)
def start_from_rest(nx, ny, bf, mode, mu_s, fresh, r, direction, rim_dir):
    """The mass at rest with r_need = (nx, ny) outside the intersection of the standing sets: r becomes the nearest
    point of that intersection, on the circle of the pivot k (the disc left whose nearest point b_k + µ_slow,k e,
    e = (r_need − b_k)/|r_need − b_k|, lies in every other set; where none does, a corner, the disc left farthest),
    and the surfaces on that circle start (equal circles together, within :data:`LEVEL_TIE`).  A surface held on
    its rim (:func:`held_value`) is a disc here only where r_need pulls it inward ((r_need − b)·e < 0: it leaves
    its rim, as in 1-D); pushed along its rim it slides along it (:data:`ON_RIM`) where r lands on its tangent
    line.  Returns the pivot, e in ``direction`` and r in ``r``; −1 when r_need is in every set; −2 when only rims
    are left along their tangents (no surface slides freely: not modelled)."""
    n = mode.shape[0]
    best = -1
    worst = -math.inf
    along = False
    for i in range(n):
        px0 = nx - bf[i, 0]
        py0 = ny - bf[i, 1]
        dist = math.hypot(px0, py0)
        if mode[i] == HELD and px0 * rim_dir[i, 0] + py0 * rim_dir[i, 1] >= 0.0:
            if held_value(px0, py0, np.int64(HELD), rim_dir[i, 0], rim_dir[i, 1], mu_s[i]) < -LEVEL_TIE:
                along = True
            continue
        over = dist - mu_s[i]
        if over < -LEVEL_TIE:
            continue
        px = bf[i, 0] + mu_s[i] * px0 / dist
        py = bf[i, 1] + mu_s[i] * py0 / dist
        held = True
        for j in range(n):
            if j != i and held_value(px - bf[j, 0], py - bf[j, 1], mode[j], rim_dir[j, 0], rim_dir[j, 1],
                                     mu_s[j]) < -LEVEL_TIE:
                held = False
        # the nearest point held by every other set wins; among the rest, the disc left farthest
        score = over + (1e3 if held else 0.0)
        if best < 0 or score > worst:
            worst = score
            best = i
    if best < 0:
        return -2 if along else best
    dx = nx - bf[best, 0]
    dy = ny - bf[best, 1]
    rho = math.hypot(dx, dy)
    direction[0] = dx / rho
    direction[1] = dy / rho
    r[0] = bf[best, 0] + mu_s[best] * direction[0]
    r[1] = bf[best, 1] + mu_s[best] * direction[1]
    for i in range(n):
        fx = r[0] - bf[i, 0]
        fy = r[1] - bf[i, 1]
        if mode[i] == HELD and fx * rim_dir[i, 0] + fy * rim_dir[i, 1] >= 0.0:
            if held_value(fx, fy, np.int64(HELD), rim_dir[i, 0], rim_dir[i, 1], mu_s[i]) <= LEVEL_TIE:
                mode[i] = ON_RIM
                fresh[i] = 1
        elif abs(math.hypot(fx, fy) - mu_s[i]) <= LEVEL_TIE:
            mode[i] = SLIDING
            fresh[i] = 1
    mode[best] = SLIDING
    fresh[best] = 1
    return best


@njit(cache=True)
def to_rims(y, mode, cap):
    """Every surface on its rim put back on its circle |u_i| = d_i* (a slide along the rim keeps |u_i| in the
    equations; the collocation keeps it to its local error)."""
    for i in range(mode.shape[0]):
        if mode[i] == ON_RIM or mode[i] == HELD:
            rho = math.hypot(y[2 + 2 * i], y[3 + 2 * i])
            if rho > 0.0:
                y[2 + 2 * i] *= cap[i] / rho
                y[3 + 2 * i] *= cap[i] / rho


@njit(cache=True)
def first_held(mode):
    """The first surface on its rim (−1: none): named where a run stops on the rims."""
    for i in range(mode.shape[0]):
        if mode[i] == ON_RIM or mode[i] == HELD:
            return i
    return -1


@njit(cache=True)
def trial_force(y, agx, agy, g, c, bmat, smat, mode, mu_s, mu_f, a, gmap, lock, direction, r, bf, j, smode, rt, dy):
    """The force (into ``rt``, from the guess ``r``) and the rates (``dy``) with surface j as the pivot and no
    saturated set; False where it is not found (:func:`choose_pivot`, :func:`restart_free`)."""
    n = mode.shape[0]
    split_modes(mode, smode)
    for q in range(n):
        lock[q] = 0
    k = set_split(smode, j, lock, bmat, gmap)
    rt[0] = r[0]
    rt[1] = r[1]
    jac = np.empty((dy.shape[0], dy.shape[0]))
    good, _ = rhs(y, agx, agy, g, c, bmat, smat, mode, mu_s, mu_f, a, k, gmap, lock, direction[0], direction[1],
                  rt, bf, dy, jac, np.bool_(False))
    return good


@njit(cache=True)
def choose_pivot(y, agx, agy, g, c, bmat, smat, mode, mu_s, mu_f, a, gmap, lock, direction, r, bf, pivot):
    """The pivot for a moving mass whose force was not found with ``pivot``: each surface sliding inside its rim
    tried (no saturated set), the one with the largest a_i |u̇_i| where the force is found (``pivot`` where none)."""
    n = mode.shape[0]
    m = 2 + 2 * n
    smode = np.zeros(n, dtype=np.int64)
    dy = np.empty(m)
    rt = np.empty(2)
    best = pivot
    worst = -math.inf
    for j in range(n):
        if mode[j] != SLIDING:
            continue
        good = trial_force(y, agx, agy, g, c, bmat, smat, mode, mu_s, mu_f, a, gmap, lock, direction, r, bf, j,
                           smode, rt, dy)
        if good:
            w = a[j] * math.hypot(dy[2 + 2 * j], dy[3 + 2 * j])
            if w > worst:
                worst = w
                best = j
    for q in range(n):
        lock[q] = 0
    split_modes(mode, smode)
    return set_split(smode, best, lock, bmat, gmap)


@njit(cache=True)
def restart_free(y, agx, agy, g, c, bmat, smat, mode, mu_s, mu_f, a, gmap, lock, direction, r, bf, fresh):
    """The mass moves and no surface slides inside its rim (the last one reached it): the stuck surface that takes
    the motion starts (the 1-D model's consistent mode: the force jumps so that the rates sum to Ẋ).  Each stuck
    surface is tried as the pivot; the one whose force leaves every other standing surface in its set
    (:func:`held_value`; else the least outside) starts, and is returned (the others' past starts are then taken at
    once by the next step's events).  −1: no stuck surface (every surface on its rim: the ultimate); −3: no force
    found for any."""
    n = mode.shape[0]
    m = 2 + 2 * n
    smode = np.zeros(n, dtype=np.int64)
    dy = np.empty(m)
    rt = np.empty(2)
    rim_dir = np.zeros((n, 2))
    rim_normals(y, mode, rim_dir)
    best = np.int64(-1)
    best_v = math.inf
    tried = False
    for j in range(n):
        if mode[j] != STUCK:
            continue
        tried = True
        mode[j] = SLIDING
        good = trial_force(y, agx, agy, g, c, bmat, smat, mode, mu_s, mu_f, a, gmap, lock, direction, r, bf, j,
                           smode, rt, dy)
        mode[j] = STUCK
        if not good:
            continue
        viol = 0.0
        for i in range(n):
            if i != j and (mode[i] == STUCK or mode[i] == HELD):
                viol = max(viol, -held_value(rt[0] - bf[i, 0], rt[1] - bf[i, 1], mode[i], rim_dir[i, 0],
                                             rim_dir[i, 1], mu_s[i]))
        if viol < best_v:
            best_v = viol
            best = j
    if best < 0:
        return -3 if tried else -1
    mode[best] = SLIDING
    fresh[best] = 1
    split_modes(mode, smode)
    return set_split(smode, best, lock, bmat, gmap)


@njit(cache=True)
def store_sample(y, ns, j, out_x, out_v):
    """Sample j of the outputs from the state y: X the sum of the ns surfaces' displacements, V."""
    xx = 0.0
    xy = 0.0
    for i in range(ns):
        xx += y[2 + 2 * i]
        xy += y[3 + 2 * i]
    out_x[j, 0] = xx
    out_x[j, 1] = xy
    out_v[j, 0] = y[0]
    out_v[j, 1] = y[1]


@njit(cache=True)
def _mask(mode):
    """The state's code: the sliding surfaces' bits plus 2^n times those on their rims (the 1-D model's)."""
    n = mode.shape[0]
    sliding = 0
    rimmed = 0
    for i in range(n):
        if mode[i] == SLIDING:
            sliding |= 1 << i
        elif mode[i] == ON_RIM or mode[i] == HELD:
            rimmed |= 1 << i
    return sliding + (1 << n) * rimmed


@njit(cache=True)
def stand_all(mode):
    """Every surface stands: stuck, or held on its rim."""
    for i in range(mode.shape[0]):
        mode[i] = HELD if (mode[i] == ON_RIM or mode[i] == HELD) else STUCK


@njit(cache=True)
def free_pivot(mode, pivot):
    """``pivot`` when it slides inside its rim, else the first surface that does (−1: none)."""
    if 0 <= pivot < mode.shape[0] and mode[pivot] == SLIDING:
        return pivot
    for i in range(mode.shape[0]):
        if mode[i] == SLIDING:
            return i
    return -1


@njit(cache=True)
def split_modes(mode, out_mode):
    """The modes the 1-D model's ``set_split``/``update_lock`` read (1: its rate in the series sum, 0: none): a
    surface sliding along its rim is in the sum, never the pivot nor in the saturated set (its rate is −inf there)."""
    for i in range(mode.shape[0]):
        out_mode[i] = 1 if (mode[i] == SLIDING or mode[i] == ON_RIM) else 0


@njit(cache=True)
def planar_rate_kernel(ax, ay, times, g, c, bmat, smat, mu_s, mu_f, a, cap, tol, h_first,
                       out_x, out_v, out_a, out_en, ev_t, ev_k, summary, surf_peak, state_first_time, u, lock_levels):
    """Response of a mass on a multi-surface bearing with µ(v) surfaces to a sampled pair.

    Parameters
    ----------
    ax, ay : float64[n]
        Ground acceleration [m/s²], linear between samples.
    times : float64[n]
        Sample times from the first [s].
    g, c : float
        Gravity [m/s²] and damping per unit mass [1/s].
    bmat, smat : float64[ns, ns]
        Back-force matrix B (b = B u) [1/m] and the element map ū = S u [-].
    mu_s, mu_f, a : float64[ns]
        µ_slow, µ_fast [-] and the rate [s/m] of each surface (µ_slow < µ_fast).
    cap : float64[ns]
        d_i* [m] (inf: no rim).
    tol : float
        Largest scaled difference of a step from its two halves (scales: the running peaks).
    h_first : float
        First trial step [s].
    out_x, out_v, out_a : float64[n, 2]
        Displacement [m], velocity [m/s] relative to the ground, absolute acceleration [m/s²] at the samples.
    out_en : float64[3, n]
        Input, friction and viscous energy [J/kg] at the samples.
    ev_t, ev_k, summary, surf_peak, state_first_time
        Events, the summary (``S_*``), peak |u_i|, first time of each set of sliding surfaces (index: the mask).
    u : float64[ns, 2]
        Out: the final surface displacements [m].
    lock_levels : float64[2]
        (join, leave) levels of a_i |u̇_i| of the saturated set (:data:`LOCK_LEVELS`; (inf, inf): no set).
    """
    n_samples = ax.shape[0]
    ns = mu_s.shape[0]
    m = 2 + 2 * ns
    mode = np.zeros(ns, dtype=np.int64)
    lock = np.zeros(ns, dtype=np.int64)
    lock_before = np.zeros(ns, dtype=np.int64)
    gmap = np.zeros((ns, ns + 1))
    speeds = np.zeros(ns + 1)
    fresh = np.zeros(ns, dtype=np.int64)
    y = np.zeros(m)
    y_try = np.empty(m)
    y_ev = np.empty(m)
    dy = np.empty(m)
    jac = np.empty((m, m))
    quad = np.empty(4)
    quad_ev = np.empty(4)
    bf = np.empty((ns, 2))
    e0 = np.empty(2 * ns)
    e1 = np.empty(2 * ns)
    scale = np.empty(m)
    r = np.zeros(2)
    r_try = np.zeros(2)
    r_ev = np.zeros(2)
    r1 = np.zeros(2)
    direction = np.array([1.0, 0.0])
    rim_dir = np.zeros((ns, 2))
    smode = np.zeros(ns, dtype=np.int64)
    n_rim = 0
    n_ult = 0
    impulse = 0.0
    max_imp_v = 0.0
    e_imp = 0.0
    first_ult = -1.0
    imp_tangential = 0.0
    imp_spread = 0.0
    imp_gap = 0.0
    rims_spread = 0.0
    rims_gap = 0.0
    rims_tangential = 0.0
    a_now = np.empty(2)
    slope = np.empty(2)
    for j in range(state_first_time.shape[0]):
        state_first_time[j] = -1.0
    stuck = True
    n_ev = np.int64(0)
    status = 0
    peak_x = 0.0
    peak_v = 0.0
    peak_a = math.hypot(ax[0], ay[0])
    peak_r = 0.0
    slip_time = 0.0
    e_in = 0.0
    e_f = 0.0
    e_v = 0.0
    n_steps = 0
    n_newton = 0.0
    fail_t = -1.0
    rim_surface = -1
    h = h_first
    pivot = np.int64(-1)
    x_floor = 1e-4
    v_floor = 1e-3
    for row in range(3):
        out_en[row, 0] = 0.0
    out_x[0, 0] = 0.0
    out_x[0, 1] = 0.0
    out_v[0, 0] = 0.0
    out_v[0, 1] = 0.0
    out_a[0, 0] = ax[0]
    out_a[0, 1] = ay[0]
    for idx in range(n_samples - 1):
        t_i = times[idx]
        dt_i = times[idx + 1] - t_i
        slope[0] = (ax[idx + 1] - ax[idx]) / dt_i
        slope[1] = (ay[idx + 1] - ay[idx]) / dt_i
        tau = 0.0
        events_here = 0
        steps_here = 0
        while tau < dt_i and status & (STATUS_STEP_FAILED | STATUS_RIM | STATUS_WORK | STATUS_ALL_RIMS) == 0:
            a_now[0] = ax[idx] + slope[0] * tau
            a_now[1] = ay[idx] + slope[1] * tau
            if stuck:
                back_forces(y, bmat, bf)
                rim_normals(y, mode, rim_dir)
                s_exit = exit_time(-a_now[0] / g, -a_now[1] / g, -slope[0] / g, -slope[1] / g, bf, mu_s, mode, rim_dir)
                if tau + s_exit >= dt_i:
                    break  # stuck to the end of the interval
                tau += s_exit
                nx = -(ax[idx] + slope[0] * tau) / g
                ny = -(ay[idx] + slope[1] * tau) / g
                pivot = start_from_rest(nx, ny, bf, mode, mu_s, fresh, r, direction, rim_dir)
                for i in range(ns):
                    lock[i] = 0
                if pivot == -2:  # only rims left along their tangents: no free surface to take the motion
                    status |= STATUS_RIM
                    fail_t = t_i + tau
                    rim_surface = first_held(mode)
                    break
                if pivot < 0:  # rounding at the disc's edge: nothing left it yet
                    tau = min(dt_i, tau + 1e-13 * dt_i)
                    continue
                stuck = False
                h = 0.1 * dt_i  # the steps of the stop before were cut to its approach
                n_ev = record_event(ev_t, ev_k, n_ev, t_i + tau, np.int64(BREAKAWAY))
                code = _mask(mode)
                if state_first_time[code] < 0.0:
                    state_first_time[code] = t_i + tau
                continue
            steps_here += 1
            if steps_here > MAX_STEPS_PER_INTERVAL:
                status |= STATUS_WORK
                fail_t = t_i + tau
                break
            h = min(h, dt_i - tau)
            scale[0] = max(peak_v, v_floor)
            scale[1] = scale[0]
            for p in range(2, m):
                scale[p] = max(peak_x, x_floor)
            # the pivot (the sliding surface farthest into saturation) and the saturated set at the step's start: the
            # 1-D model's update_lock and set_split on the speeds |u̇_i|, held for the step and its event search
            split_modes(mode, smode)
            pivot = set_split(smode, free_pivot(mode, pivot), lock, bmat, gmap)
            good, _ = rhs(y, a_now[0], a_now[1], g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock,
                          direction[0], direction[1], r, bf, dy, jac, np.bool_(False))
            if not good and not (y[0] == 0.0 and y[1] == 0.0):
                # no force with this pivot (after a rim: the surfaces left take the velocity, one of them may be
                # saturated, its φ unresolvable): the pivot becomes the sliding surface farthest into saturation
                pivot = choose_pivot(y, a_now[0], a_now[1], g, c, bmat, smat, mode, mu_s, mu_f, a, gmap, lock,
                                     direction, r, bf, pivot)
                good, _ = rhs(y, a_now[0], a_now[1], g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock,
                              direction[0], direction[1], r, bf, dy, jac, np.bool_(False))
            if good:
                changed = False
                for i in range(ns):
                    speeds[1 + i] = -math.inf if mode[i] == ON_RIM else math.hypot(dy[2 + 2 * i], dy[3 + 2 * i])
                    lock_before[i] = lock[i]
                k_new = update_lock(speeds, smode, a, lock, lock_levels[0], lock_levels[1])
                if not aligned_set(dy, lock, k_new):
                    for i in range(ns):
                        lock[i] = 0  # the set's map is not the slow manifold there: no set (docs, h122)
                k_new = set_split(smode, free_pivot(mode, k_new), lock, bmat, gmap)
                for i in range(ns):
                    if lock[i] != lock_before[i]:
                        changed = True
                if k_new != pivot or changed:
                    pivot = k_new
                    good, _ = rhs(y, a_now[0], a_now[1], g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock,
                                  direction[0], direction[1], r, bf, dy, jac, np.bool_(False))
            # the mass coming to rest: steps cut to 0.7 of the time to rest; at rest below STOP_SPEED
            vv = y[0] * y[0] + y[1] * y[1]
            vd = y[0] * dy[0] + y[1] * dy[1]
            if good and vv > 0.0 and vd >= 0.0 and math.sqrt(vv) <= STOP_SPEED * scale[0]:
                # still starting (a step from rest too short to leave the rounding of Ẋ = 0): from rest again, in
                # the start direction (the residue, ≤ STOP_SPEED of the speed scale, is dropped)
                e_f += 0.5 * vv
                y[0] = 0.0
                y[1] = 0.0
                vv = 0.0
                vd = 0.0
            if good and vv > 0.0 and vd < 0.0:
                if math.sqrt(vv) <= STOP_SPEED * scale[0]:
                    e_f += 0.5 * vv
                    y[0] = 0.0
                    y[1] = 0.0
                    stand_all(mode)
                    back_forces(y, bmat, bf)
                    rim_normals(y, mode, rim_dir)
                    nx = -a_now[0] / g
                    ny = -a_now[1] / g
                    if holds_at_rest(nx, ny, bf, mode, mu_s, rim_dir):
                        stuck = True
                        n_ev = record_event(ev_t, ev_k, n_ev, t_i + tau, np.int64(STICK))
                    else:
                        pivot = start_from_rest(nx, ny, bf, mode, mu_s, fresh, r, direction, rim_dir)
                        for i in range(ns):
                            lock[i] = 0
                        if pivot == -2:
                            status |= STATUS_RIM
                            fail_t = t_i + tau
                            rim_surface = first_held(mode)
                            break
                        h = 0.1 * dt_i
                        n_ev = record_event(ev_t, ev_k, n_ev, t_i + tau, np.int64(REVERSAL))
                        code = _mask(mode)
                        if state_first_time[code] < 0.0:
                            state_first_time[code] = t_i + tau
                    events_here += 1
                    if events_here > MAX_EVENTS_PER_INTERVAL:
                        status |= STATUS_CHATTER
                        stand_all(mode)
                        stuck = True
                        break
                    continue
                h = min(h, 0.7 * vv / -vd)
            if vv == 0.0 and not good:
                good = True  # at rest at a start: the first step decides
            for p in range(2):
                r_try[p] = r[p]
            err = double_step(y, h, a_now, slope, g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, direction[0],
                              direction[1], r_try, scale, y_try, quad)
            n_newton += quad[3]
            reversed_ = vv > 0.0 and y[0] * y_try[0] + y[1] * y_try[1] < 0.0
            if not err <= tol or reversed_:
                if h <= 1e-13 * dt_i:
                    status |= STATUS_STEP_FAILED
                    fail_t = t_i + tau
                    break
                if reversed_:
                    h = 0.5 * h
                elif math.isfinite(err):
                    h = h * max(0.1, 0.9 * (tol / err) ** (1.0 / 6.0))
                else:
                    h = 0.25 * h
                continue
            # events between y and y_try
            event_values(y, r, mode, pivot, mu_s, cap, bmat, bf, e0)
            for p in range(2):
                r1[p] = r_try[p]
            a_end0 = a_now[0] + slope[0] * h
            a_end1 = a_now[1] + slope[1] * h
            rhs(y_try, a_end0, a_end1, g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, direction[0], direction[1], r1,
                bf, dy, jac, np.bool_(False))
            event_values(y_try, r1, mode, pivot, mu_s, cap, bmat, bf, e1)
            first_slot = -1
            first_t = math.inf
            for slot in range(2 * ns):
                if slot % 2 == 0 and fresh[slot // 2] != 0 and e0[slot] < 0.0:
                    # a surface that has just stopped or started is at its onset: a residue of the force's rounding
                    # (−9.7e-17 on PTS at 11.1837 s, h157) is not an event already past; only the step's end tells,
                    # and a real stop or restart inside the step is located (the 1-D kernel's rule; a just-started
                    # surface's stop slot switched off for its first step missed CHY028's stop at 55.154 s, h162)
                    e0[slot] = 0.0
                if e0[slot] < 0.0:
                    t_root = 0.0  # past already (a surface started a hair late): taken at once
                elif e1[slot] < 0.0:
                    ta = 0.0
                    fa = e0[slot]
                    tb_ = h
                    fb = e1[slot]
                    side = 0
                    for _ in range(100):
                        tm = (ta * fb - tb_ * fa) / (fb - fa)
                        if not (ta < tm < tb_):
                            tm = 0.5 * (ta + tb_)
                        for p in range(2):
                            r_ev[p] = r[p]
                        double_step(y, tm, a_now, slope, g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock,
                                    direction[0], direction[1], r_ev, scale, y_ev, quad_ev)
                        n_newton += quad_ev[3]
                        steps_here += 1
                        rhs(y_ev, a_now[0] + slope[0] * tm, a_now[1] + slope[1] * tm, g, c, bmat, smat, mode, mu_s,
                            mu_f, a, pivot, gmap, lock, direction[0], direction[1], r_ev, bf, dy, jac, np.bool_(False))
                        event_values(y_ev, r_ev, mode, pivot, mu_s, cap, bmat, bf, e1)
                        fm = e1[slot]
                        if fm == 0.0:
                            tb_ = tm
                            break
                        if fm < 0.0:
                            tb_ = tm
                            fb = fm
                            if side == -1:
                                fa *= 0.5
                            side = -1
                        else:
                            ta = tm
                            fa = fm
                            if side == 1:
                                fb *= 0.5
                            side = 1
                        if tb_ - ta <= 1e-13 * dt_i:
                            break
                    t_root = tb_
                    event_values(y_try, r1, mode, pivot, mu_s, cap, bmat, bf, e1)
                else:
                    continue
                if t_root < first_t:
                    first_t = t_root
                    first_slot = slot
            if first_slot < 0:
                for i in range(ns):
                    fresh[i] = 0
                for p in range(m):
                    y[p] = y_try[p]
                to_rims(y, mode, cap)
                for p in range(2):
                    r[p] = r1[p]
                e_in += quad[0]
                e_v += quad[1]
                e_f += quad[2]
                tau += h
                slip_time += h
                n_steps += 1
                peak_v = max(peak_v, math.hypot(y[0], y[1]))
                peak_r = max(peak_r, math.hypot(r[0], r[1]))
                peak_a = max(peak_a, math.hypot(g * r[0] + c * y[0], g * r[1] + c * y[1]))
                xx = 0.0
                xy = 0.0
                for i in range(ns):
                    xx += y[2 + 2 * i]
                    xy += y[3 + 2 * i]
                    surf_peak[i] = max(surf_peak[i], math.hypot(y[2 + 2 * i], y[3 + 2 * i]))
                peak_x = max(peak_x, math.hypot(xx, xy))
                err_next = max(err, 1e-3 * tol)
                h = h * min(4.0, 0.9 * (tol / err_next) ** (1.0 / 6.0))
                continue
            # ---- the event: advance to it ----
            if first_t > 0.0:
                for p in range(2):
                    r_ev[p] = r[p]
                double_step(y, first_t, a_now, slope, g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, direction[0],
                            direction[1], r_ev, scale, y_ev, quad_ev)
                n_newton += quad_ev[3]
                for p in range(m):
                    y[p] = y_ev[p]
                to_rims(y, mode, cap)
                rhs(y, a_now[0] + slope[0] * first_t, a_now[1] + slope[1] * first_t, g, c, bmat, smat, mode, mu_s,
                    mu_f, a, pivot, gmap, lock, direction[0], direction[1], r_ev, bf, dy, jac, np.bool_(False))
                for p in range(2):
                    r[p] = r_ev[p]
                e_in += quad_ev[0]
                e_v += quad_ev[1]
                e_f += quad_ev[2]
                tau += first_t
                slip_time += first_t
                n_steps += 1
            t_now = t_i + tau
            for i in range(ns):
                surf_peak[i] = max(surf_peak[i], math.hypot(y[2 + 2 * i], y[3 + 2 * i]))
            i = first_slot // 2
            events_here += 1
            if events_here > MAX_EVENTS_PER_INTERVAL:
                status |= STATUS_CHATTER
                y[0] = 0.0
                y[1] = 0.0
                stand_all(mode)
                stuck = True
                break
            kind = np.int64(REGIME)
            md = mode[i]
            if first_slot % 2 == 1 and md == SLIDING:
                # the surface reaches its rim: put on the circle, held there (the next step's start decides,
                # from its force, whether it slides along the rim: a past event is taken at once)
                rho = math.hypot(y[2 + 2 * i], y[3 + 2 * i])
                y[2 + 2 * i] *= cap[i] / rho
                y[3 + 2 * i] *= cap[i] / rho
                mode[i] = HELD
                n_rim += 1
                kind = np.int64(RIM_REACHED)
            elif first_slot % 2 == 1:
                mode[i] = SLIDING  # along its rim, the rim's reaction turned inward: it leaves the rim
            elif md == SLIDING:
                mode[i] = STUCK
                fresh[i] = JUST_STOPPED
            elif md == ON_RIM:
                mode[i] = HELD
                fresh[i] = JUST_STOPPED
            elif md == HELD:
                back_forces(y, bmat, bf)
                rim_normals(y, mode, rim_dir)
                outward = (r[0] - bf[i, 0]) * rim_dir[i, 0] + (r[1] - bf[i, 1]) * rim_dir[i, 1] >= 0.0
                mode[i] = ON_RIM if outward else SLIDING
                fresh[i] = 1
            else:
                mode[i] = SLIDING
                fresh[i] = 1
            for q in range(ns):
                lock[q] = 0  # the set is the old mode's: chosen again at the next step's start (as in 1-D)
            n_ev = record_event(ev_t, ev_k, n_ev, t_now, kind)
            if free_pivot(mode, pivot) < 0 and not (y[0] == 0.0 and y[1] == 0.0):
                # no surface slides inside its rim while the mass moves: a stuck one takes the motion, else every
                # surface is on its rim and the mass stops there (the ultimate)
                pivot = restart_free(y, a_now[0] + slope[0] * first_t, a_now[1] + slope[1] * first_t, g, c, bmat,
                                     smat, mode, mu_s, mu_f, a, gmap, lock, direction, r, bf, fresh)
                if pivot == -3:
                    status |= STATUS_STEP_FAILED
                    fail_t = t_now
                    break
                if pivot < 0:
                    xx = 0.0
                    xy = 0.0
                    for q in range(ns):
                        xx += y[2 + 2 * q]
                        xy += y[3 + 2 * q]
                    vimp = math.hypot(y[0], y[1])
                    xn = math.hypot(xx, xy)
                    tang_here = 0.0
                    spread_here = 0.0
                    gap_here = 0.0
                    if vimp > 0.0 and xn > 0.0:
                        tang_here = abs(y[0] * xy - y[1] * xx) / (vimp * xn)
                    if xn > 0.0:
                        reach = 0.0
                        for q in range(ns):
                            uq = math.hypot(y[2 + 2 * q], y[3 + 2 * q])
                            reach += uq
                            if uq > 0.0:
                                spread_here = max(spread_here, abs(y[2 + 2 * q] * xy - y[3 + 2 * q] * xx) / (uq * xn))
                        gap_here = 1.0 - xn / reach
                    if spread_here > ALIGNED_SPREAD and vimp > 0.0:
                        # the rims apart: not the ultimate; the run stops before an impact, its state handed over
                        status |= STATUS_ALL_RIMS
                        fail_t = t_now
                        rims_spread = spread_here
                        rims_gap = gap_here
                        rims_tangential = tang_here
                        break
                    imp_tangential = max(imp_tangential, tang_here)
                    imp_spread = max(imp_spread, spread_here)
                    imp_gap = max(imp_gap, gap_here)
                    impulse += vimp
                    max_imp_v = max(max_imp_v, vimp)
                    e_imp += 0.5 * vimp * vimp
                    y[0] = 0.0
                    y[1] = 0.0
                    stand_all(mode)
                    n_ult += 1
                    if first_ult < 0.0:
                        first_ult = t_now
                    n_ev = record_event(ev_t, ev_k, n_ev, t_now, np.int64(ULTIMATE))
                    back_forces(y, bmat, bf)
                    rim_normals(y, mode, rim_dir)
                    nx = -(a_now[0] + slope[0] * first_t) / g
                    ny = -(a_now[1] + slope[1] * first_t) / g
                    if holds_at_rest(nx, ny, bf, mode, mu_s, rim_dir):
                        stuck = True
                    else:
                        pivot = start_from_rest(nx, ny, bf, mode, mu_s, fresh, r, direction, rim_dir)
                        if pivot == -2:
                            status |= STATUS_RIM
                            fail_t = t_now
                            rim_surface = first_held(mode)
                            break
                        h = 0.1 * dt_i
            code = _mask(mode)
            if not stuck and free_pivot(mode, np.int64(-1)) < 0:
                y[0] = 0.0  # nothing slides: only after rounding at a stop
                y[1] = 0.0
                stand_all(mode)
                stuck = True
            elif state_first_time[code] < 0.0:
                state_first_time[code] = t_now
        if status & (STATUS_STEP_FAILED | STATUS_RIM | STATUS_WORK | STATUS_ALL_RIMS):
            for j in range(idx + 1, n_samples):
                store_sample(y, ns, j, out_x, out_v)
                out_a[j, 0] = ax[j]
                out_a[j, 1] = ay[j]
                out_en[0, j] = e_in
                out_en[1, j] = e_f
                out_en[2, j] = e_v
            break
        j = idx + 1
        store_sample(y, ns, j, out_x, out_v)
        if stuck:
            out_a[j, 0] = ax[j]
            out_a[j, 1] = ay[j]
        else:
            split_modes(mode, smode)
            pivot = set_split(smode, free_pivot(mode, pivot), lock, bmat, gmap)
            rhs(y, ax[j], ay[j], g, c, bmat, smat, mode, mu_s, mu_f, a, pivot, gmap, lock, direction[0], direction[1], r, bf, dy,
                jac, np.bool_(False))
            out_a[j, 0] = -(g * r[0] + c * y[0])
            out_a[j, 1] = -(g * r[1] + c * y[1])
            peak_r = max(peak_r, math.hypot(r[0], r[1]))
        peak_a = max(peak_a, math.hypot(out_a[j, 0], out_a[j, 1]))
        peak_x = max(peak_x, math.hypot(xx, xy))
        peak_v = max(peak_v, math.hypot(y[0], y[1]))
        out_en[0, j] = e_in
        out_en[1, j] = e_f
        out_en[2, j] = e_v
    for i in range(ns):
        u[i, 0] = y[2 + 2 * i]
        u[i, 1] = y[3 + 2 * i]
    summary[S_PEAK_X] = peak_x
    summary[S_PEAK_V] = peak_v
    summary[S_PEAK_A] = peak_a
    summary[S_PEAK_R] = peak_r
    summary[S_SLIP_TIME] = slip_time
    summary[S_E_IN] = e_in
    summary[S_E_F] = e_f
    summary[S_E_V] = e_v
    summary[S_N_EVENTS] = n_ev
    summary[S_STATUS] = status
    summary[S_N_STEPS] = n_steps
    summary[S_FAIL_T] = fail_t
    summary[S_N_NEWTON] = n_newton
    summary[S_RIM_SURFACE] = rim_surface
    summary[S_N_RIM] = n_rim
    summary[S_N_ULT] = n_ult
    summary[S_IMPULSE] = impulse
    summary[S_MAX_IMPACT_V] = max_imp_v
    summary[S_E_IMPACT] = e_imp
    summary[S_FIRST_ULT] = first_ult
    summary[S_IMPACT_TANGENTIAL] = imp_tangential
    summary[S_IMPACT_SPREAD] = imp_spread
    summary[S_IMPACT_GAP] = imp_gap
    summary[S_RIMS_SPREAD] = rims_spread
    summary[S_RIMS_GAP] = rims_gap
    summary[S_RIMS_TANGENTIAL] = rims_tangential


__all__ = ["planar_rate_kernel", "solve_force", "EVENT_NAMES", "SUMMARY_SIZE"]
