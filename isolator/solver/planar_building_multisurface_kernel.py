r"""The compiled loop of a shear building on a double or triple friction pendulum under a pair: implicit steps.

The bearing is the 2-D series model of the rigid block's implicit steps
(:mod:`isolator.solver.planar_multisurface_stepper`: one backward-Euler step is a 2-D strongly convex minimisation
in the force r, every geometry of the friction circles, the rims and the ultimate); the floors ride on the slab.

**The floors inside one step, exactly.**  Over a backward-Euler step of length h the slab's acceleration relative to
the ground is constant, ẍ_b = (V' − V)/h, and the ground's is linear, a_g(τ) = a_0 + s τ.  The floors, relative to
the slab, are the fixed-base shear building with classical modal damping (the same matrices as the 2-D building,
:mod:`isolator.superstructure`), per direction in its mass-normalised modes q̃_i (scaled by 1/√M, M the total mass):

    q̃_i'' + 2ζω_i q̃_i' + ω_i² q̃_i = −Γ̃_i (a_g(τ) + ẍ_b),   Γ̃_i = φ_iᵀ M_s 1 / √M,

whose solution over the step is a closed form (a particular part linear in τ and the damped oscillation), so the
floors' end state is exact and affine in V'.  The first story's force on the slab over the step is the floors'
momentum balance, ∫S dτ = −M [Σ Γ̃_i Δq̃_i' + (1 − m_b/M) ∫(a_g + ẍ_b) dτ], and the slab's backward-Euler balance per
unit total mass becomes

    µ_h (V' − V)/h + c V' = −g r − ā − Σ Γ̃_i (q̃'_i,free − q̃'_i(0))/h,   µ_h = 1 − Σ Γ̃_i² e^{−ζω_i h} sin(ω_d,i h)/(ω_d,i h)

(q̃'_free the floors' end velocities with ẍ_b = 0): an effective slab mass µ_h in (m_b/M, ~1] (the slab alone for a
step short against the floors' periods, the whole mass for stiff floors) and a modified mean acceleration.  With
the floors the same along x and y (µ_h isotropic) that is the rigid block's step with g/µ_h, c/µ_h and the mean
acceleration ā' = (ā + Σ Γ̃ Δq̃'_free/h)/µ_h: Ψ is divided by µ_h, its minimiser is the same, so
:func:`~isolator.solver.planar_multisurface_stepper.be_step` takes the step unchanged (its rims, its ultimate, its
carried groups), and the floors are then propagated with the ẍ_b that step gives.  Stiff floors cost nothing:
their modes are exact for any ω h.  Floors that differ along x and y make µ_h differ by direction (µ_x, µ_y):
the step is then be_step's with the slab's mass per direction, m_d (V'_d − V_d)/h + c V'_d = −g r_d − ā'_d, whose
dual Ψ has the diagonal metric M_d = (1 + ch)/(µ_d + ch) (Newton on Ψ; the one-group closed form only starts it),
the modes and their tables per direction.

A velocity change the step makes that is not its momentum balance (the plastic impact at the ultimate, the
velocity turned onto a rim circle) is an impulse on the slab alone: the floors keep their absolute velocities
(q̃'_i −= Γ̃_i ΔV).  The energies (per unit total mass) are booked exactly for the floors — the ground's input
−Σ Γ̃_i ∫ a_g q̃'_i dτ and their viscous work Σ 2ζω_i ∫ q̃'_i² dτ as closed-form integrals — and as the rigid block's
steps book them for the slab; a step with an impact books its whole energy defect as the impact's.

The steps are taken as the rigid block's are (h, then two halves; Richardson where the same groups slid and the
velocity kept its sense; the local error on the slab's X, V and on the floors' modal displacements and velocities,
each on its own scale; a step whose groups' slip turns by more than SLIP_TURN is retried shorter, as the rigid block's).
Not taken over from the rigid block's loop: the exact hold at rest and its break-away (the floors keep moving while
the slab is stuck; a stuck step costs one force test and its error is nil, so the steps grow to the sample interval).
The arrival at the ultimate is the rigid block's: from groups off their rims it is located by bisection with their
rims lifted (:func:`locate_arrival_floors`) and the impact taken there on the slab alone
(:func:`arrival_impact_floors`); with every group on its rim closing into alignment it is the move ``arrive``.

**Events located inside a step** (step doubling cannot see an event in a step's first half: the full step and
the first half both take it whole).  A step whose velocity turns back or vanishes (a reversal, a stop) is cut where
its velocity still points forward (bisection on its length to rounding), the velocity left there taken away; a slab
at rest whose solves slide is cut at its break-away (:func:`breakaway_in`, the rims holding an outward push); a
step from V = 0 at such a cut keeps its Richardson combination where the masks agree (docs/building.md, "Reversals,
stops and break-aways located inside the steps": 1.3e-4 → 3.3e-7 of the peak at step_tol 1e-7 on Kobe ×1.6).

**Static friction** (a single surface's µs above µk: the rerun of a single pendulum at its capacity).  The slab at
rest (it starts so, and is so after every stop) is held while the force it needs stays inside the µs circle — the
steps solve with µs, and a solve that slides means a break-away inside the step (located to rounding by
:func:`breakaway_in`: the step ends there, held) or at its start; it then slides at µk.  A stop is where the sliding
velocity passes through zero: a step whose velocity turns back is cut, by bisection on its length to rounding, where
the velocity vanishes (a stop only when what is left is below the steps' velocity tolerance; that remainder is taken
from the slab as an impulse, its energy booked as friction), and the slab is at rest under µs again.  µs = µk: none
of this runs.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.jit import njit
from isolator.solver.planar_multisurface_kernel import (
    S_E_F,
    S_E_IN,
    S_E_V,
    S_FAIL_T,
    S_N_REJECTED,
    S_N_STEPS,
    S_PEAK_A,
    S_PEAK_V,
    S_PEAK_X,
    S_SLIP_TIME,
    S_STATUS,
    S_STEPS_MULTI,
    STATUS_RIM,
    STATUS_STEP_LIMIT,
    element_mask,
    surface_peaks,
)
from isolator.solver.planar_multisurface_stepper import (
    CUT_ROUNDING,
    DOUBLE_EPS,
    H_MIN_FRACTION,
    MAX_STEPS_PER_INTERVAL,
    RIM_AWAY,
    RIM_ON,
    S_E_IMP,
    S_FAIL_RIMS,
    S_FIRST_ULT,
    S_IMPULSE,
    S_MAX_IMPACT_V,
    S_MAX_WORK,
    S_N_RIM_CONTACTS,
    S_N_ULTIMATE,
    S_PEAK_R,
    SLIP_QUANTA,
    SLIP_TURN,
    STATUS_UNSOLVED,
    STATUS_WORK,
    UNSOLVED,
    Y_EF,
    Y_EIMP,
    Y_EIN,
    Y_EV,
    Y_U,
    Y_V,
    Y_X,
    accept_step,
    arrival_impact,
    arrival_next,
    arrival_step,
    arrive,
    at_ultimate,
    be_step,
    carry_slot,
    groups_within_rims,
    popcount,
    slip_turn,
    ultimate_impact,
    vertical_work,
    work_bound,
)

#: rout's slots past be_step's three (r_x, r_y, gradients): the velocity an impulse removed from the slab [m/s]
R_IMPULSE = 3
R_SIZE = 4


@njit(cache=True)
def _phi1(z):
    # (e^z − 1)/z for a complex z, without the cancellation near 0
    if abs(z) < 0.5:
        term = 1.0 + 0.0j
        total = 1.0 + 0.0j
        for k in range(2, 30):
            term = term * z / k
            total += term
            if abs(term) < 1e-17 * abs(total):
                break
        return total
    return (np.exp(z) - 1.0) / z


@njit(cache=True)
def _ecs(s, w, h):
    # (∫_0^h e^{−sτ} cos wτ dτ, ∫_0^h e^{−sτ} sin wτ dτ)
    v = h * _phi1(complex(-s * h, w * h))
    return v.real, v.imag


@njit(cache=True)
def floor_mode(q0, v0, phi0, psi, h, w, z, gm, integrals=True):
    """One mode of the floors over a step of length h [s]: q̃'' + 2ζω q̃' + ω² q̃ = −Γ̃ (φ0 + ψ τ), exact (ζ < 1).

    Returns (q̃(h), q̃'(h), ∫q̃ dτ, ∫q̃'² dτ) (the integrals 0 without ``integrals``)."""
    sig = z * w
    wd = w * math.sqrt(1.0 - z * z)
    e = math.exp(-sig * h)
    cs = math.cos(wd * h)
    sn = math.sin(wd * h)
    if not integrals:
        return _mode_core(q0, v0, phi0, psi, h, w, z, gm, e, cs, sn, 0.0, 0.0, 0.0, 0.0, 0.0, np.bool_(False))
    ic, is_ = _ecs(sig, wd, h)
    e0 = h * _phi1(complex(-2.0 * sig * h, 0.0)).real
    ic2, is2 = _ecs(2.0 * sig, 2.0 * wd, h)
    return _mode_core(q0, v0, phi0, psi, h, w, z, gm, e, cs, sn, ic, is_, e0, ic2, is2, np.bool_(True))


@njit(cache=True)
def _mode_core(q0, v0, phi0, psi, h, w, z, gm, e, cs, sn, ic, is_, e0, ic2, is2, integrals):
    # floor_mode with the step length's exponentials and integrals given (mode_table's columns)
    sig = z * w
    wd = w * math.sqrt(1.0 - z * z)
    a1 = -gm * psi / (w * w)
    a0 = (-gm * phi0 - 2.0 * z * w * a1) / (w * w)
    a = q0 - a0
    b = v0 - a1
    c2 = -(w * w * a + sig * b) / wd
    q1 = a0 + a1 * h + e * (a * cs + (b + sig * a) / wd * sn)
    v1 = a1 + e * (b * cs + c2 * sn)
    if not integrals:
        return q1, v1, 0.0, 0.0
    big_q = a0 * h + 0.5 * a1 * h * h + a * ic + (b + sig * a) / wd * is_
    sq = (a1 * a1 * h + 2.0 * a1 * (b * ic + c2 * is_) + 0.5 * (b * b + c2 * c2) * e0
          + 0.5 * (b * b - c2 * c2) * ic2 + b * c2 * is2)
    return q1, v1, big_q, max(sq, 0.0)


#: the columns of a step length's table per mode (mode_table): e^{−ζωh}, cos ω_d h, sin ω_d h and the integrals
#: ∫e^{−ζωτ}cos ω_dτ, ∫e^{−ζωτ}sin ω_dτ, ∫e^{−2ζωτ}, ∫e^{−2ζωτ}cos 2ω_dτ, ∫e^{−2ζωτ}sin 2ω_dτ over [0, h]
TABLE_SIZE = 8


@njit(cache=True)
def rout_tab(rout, nm):
    """The tables' scratch inside rout, past its R_SIZE slots, one per direction (a view: no allocation per step)."""
    return rout[R_SIZE:R_SIZE + 2 * nm * TABLE_SIZE].reshape((2, nm, TABLE_SIZE))


@njit(cache=True)
def mode_table(h, om, zeta, tab):
    """The step length's exponentials and integrals per mode into tab (TABLE_SIZE columns): they depend on h and the
    mode only, so one step's solves share them (both directions, the free and the final propagation)."""
    for i in range(om.shape[0]):
        w = om[i]
        sig = zeta * w
        wd = w * math.sqrt(1.0 - zeta * zeta)
        tab[i, 0] = math.exp(-sig * h)
        tab[i, 1] = math.cos(wd * h)
        tab[i, 2] = math.sin(wd * h)
        tab[i, 3], tab[i, 4] = _ecs(sig, wd, h)
        tab[i, 5] = h * _phi1(complex(-2.0 * sig * h, 0.0)).real
        tab[i, 6], tab[i, 7] = _ecs(2.0 * sig, 2.0 * wd, h)


@njit(cache=True)
def floor_mode_tab(q0, v0, phi0, psi, h, w, z, gm, row):
    """:func:`floor_mode` with the step's table row of the mode (:func:`mode_table`); the same formulas."""
    return _mode_core(q0, v0, phi0, psi, h, w, z, gm, row[0], row[1], row[2], row[3], row[4], row[5], row[6], row[7],
                      np.bool_(True))


@njit(cache=True)
def total_energy(y, g, rb, om, gam):
    """Kinetic (relative to the ground) + strain + the bearing's stored energy of the state y, per unit total mass."""
    ng = rb.shape[0]
    nm = om.shape[1]
    f0 = carry_slot(ng) + 1
    out = 0.0
    for d in range(2):
        v = y[Y_V + d]
        out += 0.5 * v * v
        for i in range(nm):
            q = y[f0 + 2 * nm * d + i]
            qd = y[f0 + 2 * nm * d + nm + i]
            out += v * gam[d, i] * qd + 0.5 * qd * qd + 0.5 * om[d, i] * om[d, i] * q * q
    for k in range(ng):
        out += g * (y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2) / (2.0 * rb[k])
    return out


@njit(cache=True)
def building_step(y, h, a0x, a0y, sx, sy, g, c, rb, mu, rim, om, zeta, gam, rguess, out, rout, ult=-1):
    """One backward-Euler step of the slab on the bearing with the floors propagated exactly (module docstring).

    ``a0x, a0y`` the ground's acceleration at the step's start, ``sx, sy`` its slope [m/s³]; the state y (the
    stepper's slots, then per direction the floors' q̃ and q̃') into out.  Returns be_step's mask; rout[:3] as
    be_step's, rout[R_IMPULSE] the velocity an impact removed from the slab (0 without one), rout[R_SIZE:] the
    scratch of the step length's tables (R_SIZE + 2 × TABLE_SIZE × modes long).  ``om, gam`` (2, modes): the
    floors' modes per direction; the same along x and y, the rigid block's step with g/µ_h (module docstring), else
    be_step with the slab's effective mass per direction (Ψ's diagonal metric).  ``ult``: the step's classification
    of the ultimate, be_step's (the loop classifies it once at the step's start for its three solves)."""
    ng = rb.shape[0]
    nm = om.shape[1]
    f0 = carry_slot(ng) + 1
    tab = rout_tab(rout, nm)
    same = True
    for i in range(nm):
        if om[0, i] != om[1, i] or gam[0, i] != gam[1, i]:
            same = False
    mode_table(h, om[0], zeta, tab[0])
    if same:
        tab[1, :, :] = tab[0]
    else:
        mode_table(h, om[1], zeta, tab[1])
    mu_d = np.ones(2)
    for d in range(2):
        for i in range(nm):
            x = om[d, i] * math.sqrt(1.0 - zeta * zeta) * h
            mu_d[d] -= gam[d, i] * gam[d, i] * tab[d, i, 0] * (tab[d, i, 2] / x if x > 0.0 else 1.0)
    mu_h = mu_d[0]
    iso = mu_d[0] == mu_d[1]
    a0 = (a0x, a0y)
    sl = (sx, sy)
    abar = (a0x + 0.5 * h * sx, a0y + 0.5 * h * sy)
    ap_x = 0.0
    ap_y = 0.0
    for d in range(2):
        dfree = 0.0
        for i in range(nm):
            j = f0 + 2 * nm * d + i
            _, v1, _, _ = floor_mode_tab(y[j], y[j + nm], a0[d], sl[d], h, om[d, i], zeta, gam[d, i], tab[d, i])
            dfree += gam[d, i] * (v1 - y[j + nm])
        if d == 0:
            ap_x = (abar[d] + dfree / h) / mu_h if iso else abar[d] + dfree / h
        else:
            ap_y = (abar[d] + dfree / h) / mu_h if iso else abar[d] + dfree / h
    ap = (ap_x, ap_y)
    if iso:
        gp = g / mu_h
        cp = c / mu_h
        # the rigid block's rules for a restart below the rounding (be_step's ``block``): a group sliding inward off
        # its rim by less than the rounding of ū does not carry the mass (its velocity is not turned onto the rim's
        # tangent), and a step without slip whose force is not held takes V = h A; and at the ultimate the velocity
        # is turned onto its circle only when every group that slid slid along its rim (``leave``).  Without them a
        # slab at rest leaving a rim, or the ultimate, inward lost its inward velocity in every step (Christchurch CBGS
        # ×1.5 on IELC's case at step_tol 1e-9, 6.167 s: 3,000,000 steps in one interval; Chuetsu-oki 65025, 1.741 s:
        # the work bound; docs/building.md, h220's section)
        # X moved by h V' where the groups slid inside their rims (``x_balance``: the slips' quanta summed drifted)
        mask = be_step(y, h, ap_x, ap_y, gp, cp, rb, mu, rim, rguess, out, rout, 1.0, 1.0, ult, np.bool_(True),
                       np.bool_(True), np.bool_(True))
    else:
        # the floors differ along x and y: the slab's effective mass µ_d per direction, Ψ's metric diagonal.  At the
        # ultimate the velocity is turned onto its circle only when every group that slid slid along its rim
        # (``leave``, independent of the masses): without it a slab at rest there leaving inward lost its inward
        # velocity in every step (h220's departure with k_y = k_x / 2: the work bound at 0.898 s; docs/building.md,
        # h225's section).  ``block`` too (its step without slip from the momentum balance with
        # the masses per direction): without it a slab at rest on a rim leaving inward was turned back onto it in every
        # step (k_y = k_x / 2: the work bound at 1.494 s; docs/building.md, session 25)
        gp = g
        cp = c
        mask = be_step(y, h, ap_x, ap_y, g, c, rb, mu, rim, rguess, out, rout, mu_d[0], mu_d[1], ult,
                       np.bool_(True), np.bool_(True), np.bool_(False))  # one compiled version: the same types
        mu_h = 1.0  # be_step books the friction and the dashpot with g and c themselves
    impact = out[Y_EIMP] != y[Y_EIMP]
    slid = mask & ((1 << ng) - 1)
    e_in = 0.0
    e_vf = 0.0
    for d in range(2):
        if iso:
            vpre = (y[Y_V + d] - h * (gp * rout[d] + ap[d])) / (1.0 + cp * h) if slid else 0.0
        else:
            vpre = (mu_d[d] * y[Y_V + d] - h * (g * rout[d] + ap[d])) / (mu_d[d] + c * h) if slid else 0.0
        xb = (vpre - y[Y_V + d]) / h
        dv = out[Y_V + d] - vpre
        for i in range(nm):
            j = f0 + 2 * nm * d + i
            q1, v1, big_q, sq = floor_mode_tab(y[j], y[j + nm], a0[d] + xb, sl[d], h, om[d, i], zeta, gam[d, i],
                                               tab[d, i])
            # the ground's work on the floors, −Γ̃ ∫ a_g q̃' dτ (by parts), and their dampers' 2ζω ∫ q̃'² dτ
            e_in -= gam[d, i] * ((a0[d] + sl[d] * h) * q1 - a0[d] * y[j] - sl[d] * big_q)
            e_vf += 2.0 * zeta * om[d, i] * sq
            out[j] = q1
            out[j + nm] = v1 - gam[d, i] * dv  # an impulse on the slab alone: the floors keep their absolute velocity
    dx1 = out[Y_X] - y[Y_X]
    dx2 = out[Y_X + 1] - y[Y_X + 1]
    out[Y_EIN] = y[Y_EIN] - (abar[0] * dx1 + abar[1] * dx2) + e_in
    out[Y_EF] = y[Y_EF] + mu_h * (out[Y_EF] - y[Y_EF])
    out[Y_EV] = y[Y_EV] + mu_h * (out[Y_EV] - y[Y_EV]) + e_vf
    out[Y_EIMP] = y[Y_EIMP]
    rout[R_IMPULSE] = 0.0
    if impact:
        # the plastic impact at the ultimate: the step's whole energy defect is the kinetic energy the stop took, and
        # its velocity change the impact's (the rims' reaction inside the step is part of it: the arrival's step is
        # made short, planar_building_multisurface_kernel's loop)
        out[Y_EIMP] += ((out[Y_EIN] - y[Y_EIN]) - (total_energy(out, g, rb, om, gam) - total_energy(y, g, rb, om, gam))
                        - (out[Y_EF] - y[Y_EF]) - (out[Y_EV] - y[Y_EV]))
        rout[R_IMPULSE] = max(math.sqrt((out[Y_V] - y[Y_V]) ** 2 + (out[Y_V + 1] - y[Y_V + 1]) ** 2), 1e-300)
    return mask


@njit(cache=True)
def building_solves(y, h, tau, raw, c, rb, mu, rim, r, y1, yh, y2, r1, rh, r2, ult, floors):
    """The step's three solves (:func:`building_step`: the whole step of h from y into y1, its halves into yh and y2,
    forces into r1, rh, r2), as the rigid block's :func:`~isolator.solver.planar_multisurface_stepper.three_solves`
    with its arguments (``raw`` = a_x, its slope, a_y, its slope, n, its slope at the sample interval's start; τ [s]
    into it) and ``floors`` = (ω, ζ, Γ̃) of the floors' modes: the ground's acceleration from each solve's start and
    its slope, n at each solve's middle, the vertical's work booked (:func:`vertical_work`).  Returns the masks."""
    om, zeta, gam = floors
    a0x = raw[0] + raw[1] * tau
    a0y = raw[2] + raw[3] * tau
    m1 = building_step(y, h, a0x, a0y, raw[1], raw[3], raw[4] + raw[5] * (tau + 0.5 * h), c, rb, mu, rim, om, zeta,
                       gam, r, y1, r1, ult)
    mh = building_step(y, 0.5 * h, a0x, a0y, raw[1], raw[3], raw[4] + raw[5] * (tau + 0.25 * h), c, rb, mu, rim, om,
                       zeta, gam, r1, yh, rh, ult)
    if raw[5] != 0.0:
        vertical_work(y, y1, rb, raw[5] * h)
        vertical_work(y, yh, rb, 0.5 * raw[5] * h)
    m2 = building_step(yh, 0.5 * h, raw[0] + raw[1] * (tau + 0.5 * h), raw[2] + raw[3] * (tau + 0.5 * h), raw[1],
                       raw[3], raw[4] + raw[5] * (tau + 0.75 * h), c, rb, mu, rim, om, zeta, gam, rh, y2, r2, ult)
    if raw[5] != 0.0:
        vertical_work(yh, y2, rb, 0.5 * raw[5] * h)
    return m1, mh, m2


@njit(cache=True)
def building_error(y1, y2, m1, mh, m2, ng, nm, xs, vs, qs, qds):
    """The step's local error estimate in units of the tolerance: the whole step y1 against its halves y2 in the
    slab's X and V (``xs``, ``vs`` [m, m/s]), the floors' modal q̃ and q̃' (``qs``, ``qds``) and the groups' split of
    X (``xs``), except between groups that slide along their rims in all three solves (below).  Each is a plane
    vector (X, V, a group's ū, a mode's q̃ or q̃' along x and y) and is measured by its length, so the steps do not
    depend on the pair's direction: the larger component, which they took before, is cos 35° of the length along
    35°, and Kobe KJM ×1.6 on the small TFP along 35° took 9 % fewer steps and erred by 2.0e-9 of the peak at step_tol
    1e-9 against 8.0e-10 along x (now 7.9e-10; along x the same steps; docs/building.md, "The error norm turned with
    the pair")."""
    f0 = carry_slot(ng) + 1
    low = (1 << ng) - 1
    err = max(math.hypot(y2[Y_X] - y1[Y_X], y2[Y_X + 1] - y1[Y_X + 1]) / xs,
              math.hypot(y2[Y_V] - y1[Y_V], y2[Y_V + 1] - y1[Y_V + 1]) / vs)
    for k in range(nm):
        jx = f0 + k
        jy = f0 + 2 * nm + k
        err = max(err, math.hypot(y2[jx] - y1[jx], y2[jy] - y1[jy]) / qs,
                  math.hypot(y2[jx + nm] - y1[jx + nm], y2[jy + nm] - y1[jy + nm]) / qds)
    # the groups' split of X, except between groups that slide along their rims in all three solves when two
    # or more do (or every group does, as the rigid block's steps), whatever the others do: the force sits on
    # their friction edges at once (each pair of them fixes r), their split is slaved to the motion and
    # relaxes as fast as the steps' α, and the full and half steps differ in it at first order (Chuetsu-oki
    # 65025 ×1.556 under F&C's TFP with 5 floors, 26.459 s: two groups 6° apart on their rims and the inner
    # one sliding; the split 0.81 of the tolerance in every step, X 2e-4 and V 9e-5 of theirs, the steps
    # pinned at 1.1e-6 s until the work bound; then 31.209 s: all three on their rims, the inner one sliding
    # in one solve of three).  On the rims |ū_k| = c̄_k: the stored energy does not depend on that split, and
    # the friction work it does is in the balance
    along = m1 & mh & m2 & (m1 >> ng) & (mh >> ng) & (m2 >> ng) & low
    if popcount(along) >= 2:
        # with them, the split of every group on its rim in all three solves, sliding along it in some and
        # held by it in others (at its friction limit along the rim: the slip one solve makes and another
        # does not is first order in h, so the error stayed at 1.25 of the tolerance as h fell — Chuetsu-oki
        # 65025 ×1.5562, the review's nominal bound, 31.560–31.5654 s: the outer groups sliding along their
        # rims, the inner group on its rim held in the full step and sliding in the second half, masks
        # 61/61/63 in 5,133 of 6,525 steps of ~3.5e-6 s until the work bound; h112)
        along = (m1 >> ng) & (mh >> ng) & (m2 >> ng) & low
    elif not (m1 == mh and mh == m2 and m2 == (low << ng | low)):
        along = 0
    for k in range(ng):
        if not along >> k & 1:
            err = max(err, math.hypot(y2[Y_U + 2 * k] - y1[Y_U + 2 * k], y2[Y_U + 2 * k + 1] - y1[Y_U + 2 * k + 1]) / xs)
    return err


@njit(cache=True)
def locate_arrival_floors(y, h, tau, raw, c, rb, mu, rim, rim_free, free, r, y1, yh, y2, r1, rh, r2, floors):
    """The rigid block's :func:`~isolator.solver.planar_multisurface_stepper.locate_arrival` (the same arguments) with
    the building's three solves (:func:`building_solves`, ``floors`` = (ω, ζ, Γ̃)): the length of the step from y to
    the instant a group of ``free`` reaches its rim (``rim_free``: their rims lifted), by bisection on its length to its
    last bit (its trials and bracket :func:`~isolator.solver.planar_multisurface_stepper.arrival_next`'s); 0 when the
    lifted step of h does not reach a rim.  The second return is the evaluations of Ψ's gradient it took."""
    lo = 0.0
    s = h
    work = 0.0
    for d in range(200):  # the length's binary digits (arrival_next ends the search)
        m1, mh, m2 = building_solves(y, s, tau, raw, c, rb, mu, rim_free, r, y1, yh, y2, r1, rh, r2, np.int64(0), floors)
        work += r1[2] + rh[2] + r2[2]
        lo, s = arrival_next(lo, s, h, d, m1, mh, m2, y1, y2, rim, free)
        if s < 0.0:
            break
    return lo, work


@njit(cache=True)
def arrival_impact_floors(y, rim, free, g, rb, om, gam):
    """The plastic impact at a located arrival at the ultimate on the slab alone
    (:func:`~isolator.solver.planar_multisurface_stepper.arrival_impact`: the groups in ``free`` put on their rims,
    the slab's outward velocity V·ē removed), the floors keeping their absolute velocities (q̃' −= Γ̃ ΔV) and the
    kinetic energy the impact took booked as the impact's (per unit total mass: (m_b/M) (V·ē)²/2, taken as the
    change of :func:`total_energy`, ``g`` the normal force per unit mass).  Returns arrival_impact's V·ē (-1: not at
    the ultimate)."""
    nm = om.shape[1]
    f0 = carry_slot(rb.shape[0]) + 1
    e_before = total_energy(y, g, rb, om, gam)
    e_imp = y[Y_EIMP]
    v1 = y[Y_V]
    v2 = y[Y_V + 1]
    vn = arrival_impact(y, rim, free)
    y[Y_EIMP] = e_imp
    if vn > 0.0:
        for d in range(2):
            dv = y[Y_V + d] - (v1 if d == 0 else v2)
            for i in range(nm):
                y[f0 + 2 * nm * d + nm + i] -= gam[d, i] * dv
        y[Y_EIMP] += e_before - total_energy(y, g, rb, om, gam)
    return vn


@njit(cache=True)
def _jump(y, dt, a0x, a0y, sx, sy, g, c, rb, mu, rim, om, zeta, gam, r, out, rout):
    """The last ``dt`` before the ultimate as one move and the impact (the rigid block's ``arrive`` and
    ``ultimate_impact``), the floors carried over dt with ẍ_b = 0 and then keeping their absolute velocities through
    the velocity the slab loses (the rims' reaction over the move, 2 dt g r·ē, and the impact).  Returns the mask of
    every group on its rim, sliding; rout as building_step's."""
    ng = rb.shape[0]
    nm = om.shape[1]
    f0 = carry_slot(ng) + 1
    a0 = (a0x, a0y)
    sl = (sx, sy)
    arrive(y, dt, a0x + 0.5 * dt * sx, a0y + 0.5 * dt * sy, g, c, mu, rim, out)
    e_in = 0.0
    e_vf = 0.0
    for d in range(2):
        for i in range(nm):
            j = f0 + 2 * nm * d + i
            q1, v1, big_q, sq = floor_mode(y[j], y[j + nm], a0[d], sl[d], dt, om[d, i], zeta, gam[d, i],
                                            np.bool_(True))
            e_in -= gam[d, i] * ((a0[d] + sl[d] * dt) * q1 - a0[d] * y[j] - sl[d] * big_q)
            e_vf += 2.0 * zeta * om[d, i] * sq
            out[j] = q1
            out[j + nm] = v1
    out[Y_EIN] += e_in
    out[Y_EV] += e_vf
    xn = math.sqrt(y[Y_X] ** 2 + y[Y_X + 1] ** 2)
    rn = (r[0] * y[Y_X] + r[1] * y[Y_X + 1]) / xn
    if rn > 0.0:
        out[Y_V] -= 2.0 * dt * g * rn * y[Y_X] / xn
        out[Y_V + 1] -= 2.0 * dt * g * rn * y[Y_X + 1] / xn
    ultimate_impact(y, out, g, rb)
    dv1 = out[Y_V] - y[Y_V]
    dv2 = out[Y_V + 1] - y[Y_V + 1]
    for d in range(2):
        dv = dv1 if d == 0 else dv2
        for i in range(nm):
            out[f0 + 2 * nm * d + nm + i] -= gam[d, i] * dv
    out[Y_EIMP] = y[Y_EIMP] + ((out[Y_EIN] - y[Y_EIN])
                               - (total_energy(out, g, rb, om, gam) - total_energy(y, g, rb, om, gam))
                               - (out[Y_EF] - y[Y_EF]) - (out[Y_EV] - y[Y_EV]))
    rout[0] = -(a0x + dt * sx) / g
    rout[1] = -(a0y + dt * sy) / g
    rout[2] = 0.0
    rout[R_IMPULSE] = max(math.sqrt(dv1 * dv1 + dv2 * dv2), 1e-300)
    low = (1 << ng) - 1
    return low << ng | low


@njit(cache=True)
def _outside(y, tau, a0x, a0y, sx, sy, g, sz, rb, mu, rim, om, zeta, gam, hold=False):
    """Whether the force the stuck slab needs at τ into a step from y (V = 0: the floors propagated with ẍ_b = 0)
    lies outside a friction circle: r = −(a_g + Σ Γ̃_i q̃_i'')/n, q̃'' from the modes' equations (n = g + sz τ: the
    normal force per unit mass at τ, g + a_z with a vertical of slope sz [m/s³] over the step).  A single group on
    its rim also holds any outward push (its rim's reaction): it lets go only of a force whose part along the rim,
    or (pulling inward) whose whole, leaves its circle (a single pendulum held at its capacity: without it every
    held step there broke away at once, 7.7e-4 of the peak off the 1-D building; with more groups on their rims
    the groups' circles are kept as they are — the TFP held at its ultimate ran into the work bound with them —
    unless ``hold``: then every group on its rim holds the outward push, the test of a slab at rest whose solves
    slide, :func:`planar_building_multisurface_kernel`)."""
    ng = rb.shape[0]
    nm = om.shape[1]
    f0 = carry_slot(ng) + 1
    r_x = 0.0
    r_y = 0.0
    for d in range(2):
        a0 = a0x if d == 0 else a0y
        s = sx if d == 0 else sy
        ag = a0 + s * tau
        acc = ag
        for i in range(nm):
            j = f0 + 2 * nm * d + i
            q1, v1, _, _ = floor_mode(y[j], y[j + nm], a0, s, tau, om[d, i], zeta, gam[d, i], np.bool_(False))
            acc += gam[d, i] * (-2.0 * zeta * om[d, i] * v1 - om[d, i] * om[d, i] * q1 - gam[d, i] * ag)
        if d == 0:
            r_x = -acc / (g + sz * tau)
        else:
            r_y = -acc / (g + sz * tau)
    for k in range(ng):
        u1 = y[Y_U + 2 * k]
        u2 = y[Y_U + 2 * k + 1]
        d1 = r_x - u1 / rb[k]
        d2 = r_y - u2 / rb[k]
        un = math.sqrt(u1 * u1 + u2 * u2)
        if (ng == 1 or hold) and un >= rim[k] * (1.0 - RIM_ON) and un > 0.0:
            dn = (d1 * u1 + d2 * u2) / un  # the push outward, held by the rim
            if dn > 0.0:
                d1 -= dn * u1 / un
                d2 -= dn * u2 / un
        if d1 * d1 + d2 * d2 > mu[k] * mu[k]:
            return True
    return False


#: a stuck step (V = 0 at its start, every solve stuck: the backward-Euler test is on the step's mean force) is
#: checked at this many points for the force the slab needs leaving a friction circle (the break-away)
STUCK_CHECKS = 8


@njit(cache=True)
def breakaway_in(y, h, a0x, a0y, sx, sy, g, sz, rb, mu, rim, om, zeta, gam, hold=False):
    """The break-away inside a stuck step of length h from y: the first of STUCK_CHECKS points where the force the
    slab needs leaves a circle, then bisection to rounding between it and the point before; -1 when none (``g``
    the normal force per unit mass at the step's start, ``sz`` its slope [m/s³]; ``hold`` as :func:`_outside`'s)."""
    prev = 0.0
    for j in range(1, STUCK_CHECKS + 1):
        tau = h * j / STUCK_CHECKS
        if _outside(y, tau, a0x, a0y, sx, sy, g, sz, rb, mu, rim, om, zeta, gam, hold):
            lo = prev
            hi = tau
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if not (lo < mid < hi):
                    break
                if _outside(y, mid, a0x, a0y, sx, sy, g, sz, rb, mu, rim, om, zeta, gam, hold):
                    hi = mid
                else:
                    lo = mid
            return hi
        prev = tau
    return -1.0


@njit(cache=True)
def _rim_bits(y, rim):
    # the bit set of the groups on their rims in the state y (as be_step's mask reads them)
    bits = 0
    for k in range(rim.shape[0]):
        if y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2 >= (rim[k] * (1.0 - RIM_ON)) ** 2:
            bits |= 1 << k
    return bits


@njit(cache=True)
def _on_rims(y, rim):
    # the groups on their rims in the state y
    count = 0
    for k in range(rim.shape[0]):
        if y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2 >= (rim[k] * (1.0 - RIM_AWAY)) ** 2:
            count += 1
    return count


#: the floors' watched rows are taken inside each step at points at most this angle [rad] of the fastest mode apart (a
#: peak between two points is missed by at most 1 − cos(WATCH_TURN/2) ≈ 1.2e-3 of it)
WATCH_TURN = 0.1
#: at most this many interior points in one step
MAX_WATCH_POINTS = 200


@njit(cache=True)
def _watch(y, f0, nm, lin, sig, rowx, rowy, peaks, sig_max, sig_min, sig_z, az):
    # the peaks of the watched rows' resultants (peaks[2:]) and the signed rows' extremes at the state y, the
    # vertical's share sig_z a_z added to the signed rows (a bearing's P_k,g a_z/g, the 2-D building's; 0 for the moments)
    _floor_rows(y, f0, nm, np.int64(0), lin, rowx)
    _floor_rows(y, f0, nm, np.int64(1), lin, rowy)
    for k in range(lin.shape[1]):
        peaks[2 + k] = max(peaks[2 + k], math.sqrt(rowx[k] * rowx[k] + rowy[k] * rowy[k]))
    for k in range(sig.shape[0]):
        acc = signed_row(y, f0, nm, sig, k, sig_z, az)
        sig_max[k] = max(sig_max[k], acc)
        sig_min[k] = min(sig_min[k], acc)


@njit(cache=True)
def signed_row(y, f0, nm, sig, k, sig_z, az):
    """Signed row k (an overturning moment, a bearing's axial load change) at the state y, the vertical's share
    ``sig_z[k]`` a_z added (a_z = ``az``)."""
    acc = 0.0
    for d in range(2):
        for j in range(2 * nm):
            acc += sig[k, d, j] * y[f0 + 2 * nm * d + j]
    if az != 0.0:
        acc += sig_z[k] * az
    return acc


@njit(cache=True)
def _held_force(y, f0, nm, ag, om, zeta, gam, d):
    # the force on the held slab along direction d per unit total mass, −(a_g + Σ Γ̃ q̃''), its sign as g r's
    acc = ag
    for i in range(nm):
        j = f0 + 2 * nm * d + i
        acc += gam[d, i] * (-2.0 * zeta * om[d, i] * y[j + nm] - om[d, i] * om[d, i] * y[j] - gam[d, i] * ag)
    return -acc


@njit(cache=True)
def _floor_rows(y, f0, nm, d, lin, row):
    # the watched rows (drifts, floors' absolute accelerations, first-story shear) of direction d at the state y
    for k in range(lin.shape[1]):
        acc = 0.0
        for i in range(2 * nm):
            acc += lin[d, k, i] * y[f0 + 2 * nm * d + i]
        row[k] = acc


#: a row's maximum between two watch points is located only where one of them is within this fraction of the row's
#: peak so far (between points WATCH_TURN apart the maximum exceeds them by at most 1 − cos(WATCH_TURN/2) ≈ 1.2e-3)
LOCATE_BAND = 1e-2
#: Newton's iterations on a row's maximum (safeguarded by its bracket; it stops when its step is below
#: LOCATE_ROUNDING of the bracket: the resultant is flat there, its error the square of that)
LOCATE_ITERATIONS = 60
LOCATE_ROUNDING = 1e-10


@njit(cache=True)
def floors_at(y0, tp, fx, fy, sx, sy, f0, nm, om, zeta, gam, yw):
    """The floors' modal (q̃, q̃') at τ = tp into a step from y0, exact, into yw: per direction the forcing
    a_g + ẍ_b = f_d + s_d τ (``fx, fy`` at the step's start, ``sx, sy`` the ground's slopes [m/s³])."""
    for d in range(2):
        f = fx if d == 0 else fy
        s_d = sx if d == 0 else sy
        for k in range(nm):
            jj = f0 + 2 * nm * d + k
            q1, v1, _, _ = floor_mode(y0[jj], y0[jj + nm], f, s_d, tp, om[d, k], zeta, gam[d, k], np.bool_(False))
            yw[jj] = q1
            yw[jj + nm] = v1


@njit(cache=True)
def _modal_rates(yw, tp, fx, fy, sx, sy, f0, nm, om, zeta, gam, qdd):
    # the modes' second and third derivatives at yw, τ = tp (their equation and its derivative): qdd[d, 0], qdd[d, 1]
    for d in range(2):
        f = (fx if d == 0 else fy) + (sx if d == 0 else sy) * tp
        s_d = sx if d == 0 else sy
        for k in range(nm):
            jj = f0 + 2 * nm * d + k
            w = om[d, k]
            a = -2.0 * zeta * w * yw[jj + nm] - w * w * yw[jj] - gam[d, k] * f
            qdd[d, 0, k] = a
            qdd[d, 1, k] = -2.0 * zeta * w * a - w * w * yw[jj + nm] - gam[d, k] * s_d


@njit(cache=True)
def _row_and_rates(yw, f0, nm, lin, d, k, qdd):
    # row k of direction d at yw, its first and second derivatives in τ (qdd: _modal_rates')
    v = 0.0
    v1 = 0.0
    v2 = 0.0
    for i in range(nm):
        jj = f0 + 2 * nm * d + i
        v += lin[d, k, i] * yw[jj] + lin[d, k, nm + i] * yw[jj + nm]
        v1 += lin[d, k, i] * yw[jj + nm] + lin[d, k, nm + i] * qdd[d, 0, i]
        v2 += lin[d, k, i] * qdd[d, 0, i] + lin[d, k, nm + i] * qdd[d, 1, i]
    return v, v1, v2


@njit(cache=True)
def row_rises(yw, tp, fx, fy, sx, sy, f0, nm, lin, om, zeta, gam, qdd, rise):
    """Each watched row's (d|row|²/dτ / 2, |row|) at the state yw, τ = tp into the step (the forcing as
    :func:`floors_at`'s) into rise (rows, 2): the resultant rises where the first is positive."""
    _modal_rates(yw, tp, fx, fy, sx, sy, f0, nm, om, zeta, gam, qdd)
    for k in range(lin.shape[1]):
        g = 0.0
        r2 = 0.0
        for d in range(2):
            v, v1, _ = _row_and_rates(yw, f0, nm, lin, d, k, qdd)
            g += v * v1
            r2 += v * v
        rise[k, 0] = g
        rise[k, 1] = math.sqrt(r2)


@njit(cache=True)
def held_rises(yw, tp, fx, fy, sx, sy, f0, nm, hl, off, om, zeta, gam, qdd):
    """The held slab's force per unit total mass, −(a_g + Σ Γ̃ q̃'') per direction (:func:`_held_force`: the row ``hl``
    on the modes, Σ Γ̃ (ω² q̃ + 2ζω q̃'), and ``off`` = −(1 − Σ Γ̃²) a_g(τ), (o0, os) per direction), at the state yw,
    τ = tp into a held step: (d|f|²/dτ / 2, |f|)."""
    _modal_rates(yw, tp, fx, fy, sx, sy, f0, nm, om, zeta, gam, qdd)
    g = 0.0
    r2 = 0.0
    for d in range(2):
        v, v1, _ = _row_and_rates(yw, f0, nm, hl, d, np.int64(0), qdd)
        v += off[d, 0] + off[d, 1] * tp
        v1 += off[d, 1]
        g += v * v1
        r2 += v * v
    return g, math.sqrt(r2)


@njit(cache=True)
def parabola_peak(f0, fh, f1):
    """The maximum of the parabola through (0, f0), (½, fh), (1, f1) when it is concave with its vertex inside (0, 1),
    else -1: a step's largest force from its start, the end of its first half and its end (the base shear while the
    slab slides, smooth inside a step: the events are located at the steps' ends).  p(s) = f0 + s d − s² k, d = 4 fh
    − 3 f0 − f1, k = 4 fh − 2 f0 − 2 f1; the vertex s* = d / 2k, p(s*) = f0 + d² / 4k."""
    k = 4.0 * fh - 2.0 * f0 - 2.0 * f1
    d = 4.0 * fh - 3.0 * f0 - f1
    if not (k > 0.0 and 0.0 < d < 2.0 * k):
        return -1.0
    return f0 + d * d / (4.0 * k)


@njit(cache=True)
def _near_extreme(v, high, low):
    # a signed row's value v within LOCATE_BAND of the extreme of its sign so far (``high`` ≥ 0, ``low`` ≤ 0); a row
    # at 0 is near none (a moment about the axis across a record along x is 0 throughout: its steps were all located)
    if v > 0.0:
        return v >= (1.0 - LOCATE_BAND) * high
    return v < 0.0 and v <= (1.0 - LOCATE_BAND) * low


@njit(cache=True)
def _signed_and_rates(yw, f0, nm, sgl, k, qdd, z0, zs, tp):
    # signed row k (sgl: the signed rows in the watched rows' layout, per direction) at yw, τ = tp, its first and second
    # derivatives (qdd: _modal_rates'), the vertical's share z0 + zs τ added
    v = z0 + zs * tp
    v1 = zs
    v2 = 0.0
    for d in range(2):
        a, a1, a2 = _row_and_rates(yw, f0, nm, sgl, d, k, qdd)
        v += a
        v1 += a1
        v2 += a2
    return v, v1, v2


@njit(cache=True)
def signed_rises(yw, tp, f0, nm, sgl, qdd, z0, zs, rise):
    """Each signed row's (s ds/dτ, s) at the state yw, τ = tp into the step, after :func:`row_rises` there (its modal
    rates ``qdd``): |s| rises where the first is positive.  ``z0 + zs τ`` per row: the vertical's share."""
    for k in range(sgl.shape[1]):
        v, v1, _ = _signed_and_rates(yw, f0, nm, sgl, k, qdd, z0[k], zs[k], tp)
        rise[k, 0] = v * v1
        rise[k, 1] = v


@njit(cache=True)
def row_peak(y0, lo, hi, k, fx, fy, sx, sy, f0, nm, lin, om, zeta, gam, qdd, yw, signed=False, z0=0.0, zs=0.0,
             off=None):
    """The maximum of watched row k's resultant between τ = lo and hi into a step from y0 (where it rises at lo and
    does not at hi): Newton on d|row|²/dτ = 0 with the rows' closed-form first and second derivatives, kept inside
    its bracket (bisection where a Newton step leaves it), to LOCATE_ROUNDING of the bracket.  ``signed``: row k of
    the signed rows ``lin`` (both directions summed, ``z0 + zs τ`` added: the vertical's share), its extreme of the
    largest magnitude returned with its sign.  ``off`` (2, 2), optional: per direction an offset o0 + os τ added to
    the row (the held slab's force, :func:`held_rises`)."""
    tau = 0.5 * (lo + hi)
    width = hi - lo
    best = 0.0
    for _ in range(LOCATE_ITERATIONS):
        floors_at(y0, tau, fx, fy, sx, sy, f0, nm, om, zeta, gam, yw)
        _modal_rates(yw, tau, fx, fy, sx, sy, f0, nm, om, zeta, gam, qdd)
        g = 0.0
        gp = 0.0
        r2 = 0.0
        if signed:
            v, v1, v2 = _signed_and_rates(yw, f0, nm, lin, k, qdd, z0, zs, tau)
            g = v * v1
            gp = v1 * v1 + v * v2
            if abs(v) > abs(best):
                best = v
        else:
            for d in range(2):
                v, v1, v2 = _row_and_rates(yw, f0, nm, lin, d, k, qdd)
                if off is not None:
                    v += off[d, 0] + off[d, 1] * tau
                    v1 += off[d, 1]
                g += v * v1
                gp += v1 * v1 + v * v2
                r2 += v * v
            best = max(best, math.sqrt(r2))
        if g > 0.0:
            lo = tau
        else:
            hi = tau
        nxt = tau - g / gp if gp < 0.0 else 0.5 * (lo + hi)
        if not lo < nxt < hi:
            nxt = 0.5 * (lo + hi)
        if abs(nxt - tau) <= LOCATE_ROUNDING * width or not lo < nxt < hi:
            break
        tau = nxt
    return best


@njit(cache=True)
def planar_building_multisurface_kernel(t, ax, ay, nz, c, rb, mu, rim, members, tmat, om, zeta, gam, lin, sig, tol,
                                        scales, out_y, out_r, peaks, sig_max, sig_min, summary, surf_peak, first, ub,
                                        mu_s, az, sig_z):
    """Response of a shear building on a multi-surface bearing to a piecewise-linear pair, by implicit steps.

    ``nz`` = g + a_z [m/s²] at the samples (linear between them; g without a vertical): the normal force per unit
    mass on every surface, each step taking it at its mean (as the rigid block's steps,
    :func:`~isolator.solver.planar_multisurface_stepper.planar_multisurface_stepper`) and booking the vertical's work
    (:func:`~isolator.solver.planar_multisurface_stepper.vertical_work`); the floors are horizontal shear springs, the
    vertical does not load them; ``az`` the vertical [m/s²] at the samples and ``sig_z`` its share of the signed rows
    (a bearing's P_k,g/g, 0 for the moments).  ``c`` the isolator's dashpot per unit total mass [1/s]; ``rb, mu,
    rim, members, tmat`` the stepper's groups; ``om, zeta, gam`` the floors' fixed-base modes (ω_i [rad/s], ζ, Γ̃_i = φ_iᵀ M_s 1/√M);
    ``lin`` (rows, 2 n_modes) the watched rows per direction on (q̃, q̃'), ``sig`` (rows, 2, 2 n_modes) the signed
    rows on both directions; ``scales`` = (displacement floor [m], velocity floor [m/s]) of the error norm.
    Outputs: the state and the force r/W at the samples; ``peaks`` = (|X|, |V|, the watched rows' resultants —
    their maxima located inside the steps, :func:`row_peak` —, |g r + c V|); the signed rows' extremes (located as
    the watched rows' peaks, :func:`row_peak` with ``signed``); the stepper's summary slots.

    ``mu_s`` the groups' static friction (≥ ``mu``; equal: kinetic friction throughout, the steps unchanged).  Above
    ``mu`` (module docstring, Static friction): the slab at rest is held while the force it needs stays inside the
    µs circles, slides at µk after the break-away, and is at rest again (µs) after a stop."""
    n = t.shape[0]
    ng = rb.shape[0]
    nm = om.shape[1]
    f0 = carry_slot(ng) + 1
    ny = f0 + 4 * nm
    nk = lin.shape[1]
    nj = sig.shape[0]
    y = np.zeros(ny)
    y1 = np.zeros(ny)
    yh = np.zeros(ny)
    y2 = np.zeros(ny)
    y0 = np.zeros(ny)
    r = np.zeros(2)
    r1 = np.zeros(R_SIZE + 2 * nm * TABLE_SIZE)
    rh = np.zeros(R_SIZE + 2 * nm * TABLE_SIZE)
    r2 = np.zeros(R_SIZE + 2 * nm * TABLE_SIZE)
    ra = np.zeros(R_SIZE + 2 * nm * TABLE_SIZE)
    yw = np.zeros(ny)
    rowx = np.zeros(nk)
    rowy = np.zeros(nk)
    qdd = np.zeros((2, 2, nm))
    rise0 = np.zeros((nk, 2))
    rise1 = np.zeros((nk, 2))
    r_last = np.zeros(nk)
    # the signed rows located as the watched rows' peaks: in the watched rows' layout (sgl[d, k] = sig[k, d]), their
    # (s ds/dτ, s) at the watch points, their values at the last step's end, the vertical's share at the step's start
    sgl = np.zeros((2, nj, 2 * nm))
    for k in range(nj):
        for d in range(2):
            sgl[d, k, :] = sig[k, d, :]
    srise0 = np.zeros((nj, 2))
    # the held slab's force as a row (held_rises): Σ Γ̃ (ω² q̃ + 2ζω q̃') per direction, and −(1 − Σ Γ̃²) a_g's share
    hl = np.zeros((2, 1, 2 * nm))
    hoff = np.zeros((2, 2))
    for d in range(2):
        for k in range(nm):
            hl[d, 0, k] = gam[d, k] * om[d, k] * om[d, k]
            hl[d, 0, nm + k] = gam[d, k] * 2.0 * zeta * om[d, k]
    srise1 = np.zeros((nj, 2))
    s_last = np.zeros(nj)
    sz0 = np.zeros(nj)
    szs = np.zeros(nj)
    low = (1 << ng) - 1
    raw = np.zeros(6)  # the sample interval's a_x, its slope, a_y, its slope, n, its slope (building_solves)
    floors = (om, zeta, gam)
    # the located arrival at the ultimate (locate_arrival_by): its three solves, their combination, the lifted rims
    ya1 = np.zeros(ny)
    yah = np.zeros(ny)
    ya2 = np.zeros(ny)
    ya = np.zeros(ny)
    rl = np.zeros(R_SIZE + 2 * nm * TABLE_SIZE)
    rim_free = np.zeros(ng)
    qlast = np.zeros((ng, 2))  # each group's slip over the last accepted step (slip_turn)
    ne = members.shape[0]
    for j in range(first.shape[0]):
        first[j] = -1.0
    for k in range(peaks.shape[0]):
        peaks[k] = 0.0
    for k in range(nj):
        sig_max[k] = 0.0
        sig_min[k] = 0.0
    x_floor = scales[0]
    v_floor = scales[1]
    q_floor = scales[2]
    qd_floor = scales[3]
    floor_rel = scales[4]
    max_evals = work_bound(tol)
    rb_mu = 0.0  # Σ R̄ µ and Σ R̄ of the groups: the rounding of their slips (SLIP_QUANTA)
    rb_sum = 0.0
    for k in range(ng):
        rb_mu += rb[k] * mu[k]
        rb_sum += rb[k]
    peak_x = 0.0
    peak_v = 0.0
    peak_q = 0.0
    peak_qd = 0.0
    peak_r = 0.0
    slip = 0.0
    n_steps = 0
    n_rej = 0
    n_floor = 0
    status = 0
    fail_t = -1.0
    n_rim = 0
    away = low
    n_ult = 0
    impulse = 0.0
    impact_v = 0.0
    max_imp_v = 0.0
    first_ult = -1.0
    max_work = 0.0
    h_sugg = -1.0
    static = False
    for k in range(ng):
        if mu_s[k] > mu[k]:
            static = True
    # at rest under static friction (the slab starts at rest); stop_h: the length of a step cut at a stop (or -1)
    held_s = static
    stop_h = -1.0
    prev_plain = False  # the last accepted step slid plainly (its end force starts the next step's parabola_peak)
    for j in range(ny):
        out_y[0, j] = 0.0
    out_r[0, 0] = -ax[0] / nz[0]
    out_r[0, 1] = -ay[0] / nz[0]
    peaks[nk + 2] = math.sqrt(ax[0] * ax[0] + ay[0] * ay[0])
    last = 0
    for i in range(n - 1):
        hi = t[i + 1] - t[i]
        slope_x = (ax[i + 1] - ax[i]) / hi
        slope_y = (ay[i + 1] - ay[i]) / hi
        slope_z = (nz[i + 1] - nz[i]) / hi
        slope_az = (az[i + 1] - az[i]) / hi
        raw[0] = ax[i]
        raw[1] = slope_x
        raw[2] = ay[i]
        raw[3] = slope_y
        raw[4] = nz[i]
        raw[5] = slope_z
        tau = 0.0
        h_floor = H_MIN_FRACTION * hi
        h = hi if (h_sugg <= 0.0 or h_sugg > hi) else h_sugg
        steps_here = 0
        work = 0.0
        started = False
        arrival = False
        arrival_steps = 0
        while tau < hi:
            steps_here += 1
            if steps_here > MAX_STEPS_PER_INTERVAL:
                status |= STATUS_STEP_LIMIT
                fail_t = t[i] + tau
                break
            h = min(h, hi - tau)
            # the arrival at the ultimate with every group on its rim closing into alignment (the rigid block's event,
            # planar_multisurface_stepper.arrival_time): the steps end ARRIVAL_FRACTION × hi before it, the last of it
            # is one move (arrive, the floors carried with the slab's velocity kept), the impact after it
            h_keep = h
            h, jump = arrival_step(y, rim, r, nz[i] + slope_z * tau, h, hi, tau)
            last_step = h >= hi - tau
            at_floor = not h > h_floor
            a0x = ax[i] + slope_x * tau
            a0y = ay[i] + slope_y * tau
            mu_now = mu_s if held_s else mu
            # n = g + a_z at its mean over each step (linear: at its middle), the vertical's work booked after each solve
            # (the first half's before the second starts from it), as the rigid block's steps
            # the ultimate classified once, at the step's start, for its three solves and the trial solves of its cuts
            # (the rigid block's rule, planar_multisurface_stepper; docs/multisurface.md, "Once per step"): classified
            # per solve, the second half read it at its own start (docs/building.md, "The ultimate once per step")
            ult = 1 if at_ultimate(y, rim) else 0
            if jump:
                m1 = _jump(y, h, a0x, a0y, slope_x, slope_y, nz[i] + slope_z * (tau + 0.5 * h), c, rb, mu, rim, om,
                           zeta, gam, r, y2, r2)
                mh = m1
                work += 0.0
                if slope_z != 0.0:
                    vertical_work(y, y2, rb, slope_z * h)
                    r2[0] = -(a0x + h * slope_x) / (nz[i] + slope_z * (tau + h))
                    r2[1] = -(a0y + h * slope_y) / (nz[i] + slope_z * (tau + h))
                m2 = mh
            else:
                m1, mh, m2 = building_solves(y, h, tau, raw, c, rb, mu_now, rim, r, y1, yh, y2, r1, rh, r2, ult, floors)
            if jump:
                for j in range(ny):
                    y1[j] = y2[j]
                r1[R_IMPULSE] = 0.0
                rh[R_IMPULSE] = 0.0
                r1[2] = 0.0
                rh[2] = 0.0
            work += r1[2] + rh[2] + r2[2]
            if work > max_evals:
                status |= STATUS_WORK
                fail_t = t[i] + tau
                summary[S_FAIL_RIMS] = _on_rims(y, rim)
                break
            if (not (m1 | mh | m2) & low and y[Y_V] == 0.0 and y[Y_V + 1] == 0.0 and not started
                    and h > 2.0 * h_floor):
                # stuck in all three solves: the break-away inside the step, if any, ends it (the steps restart from
                # it with a short one, as the rigid block's from its exact break-away)
                t_b = breakaway_in(y, h, a0x, a0y, slope_x, slope_y, nz[i] + slope_z * tau, slope_z, rb, mu_now, rim, om,
                                   zeta, gam, np.bool_(True))
                if t_b > h_floor:
                    h = t_b
                    started = True
                    continue
            if held_s and (m1 | mh | m2) & low and not jump and not started:
                # at rest under µs and a solve slid: the break-away is inside the step (the force the slab needs
                # leaves a µs circle: the step ends there, held) or at its start (the slab leaves at µk); none found
                # (every group held, those on their rims by them): the µs solves stand
                t_b = breakaway_in(y, h, a0x, a0y, slope_x, slope_y, nz[i] + slope_z * tau, slope_z, rb, mu_s, rim, om,
                                   zeta, gam, np.bool_(False))
                if h_floor < t_b < h and h > 2.0 * h_floor:
                    h = t_b
                    started = True
                    continue
                if 0.0 <= t_b < h:
                    held_s = False
                    continue
            at_rest = y[Y_V] == 0.0 and y[Y_V + 1] == 0.0
            if (not held_s and at_rest and (m1 | mh | m2) & low and not jump and not started
                    and h > 2.0 * h_floor):
                # at rest (from the start, a stop or a located reversal) and a solve slid: the backward-Euler test is
                # on the step's mean force, so the slide may start inside the step; the steps started it at the
                # step's start, early by up to h (Kobe KJM ×1.6, the small TFP: the break-away from the ultimate
                # 3.9e-5 s early at step_tol 1e-7, a velocity error that grew to 4e-5 of the peak).  The break-away
                # (the force the slab needs leaving a circle; an outward push held by every group on its rim) ends
                # the step, held, when it lies inside; at its start (a reversal) the step stands
                t_b = breakaway_in(y, h, a0x, a0y, slope_x, slope_y, nz[i] + slope_z * tau, slope_z, rb, mu_now, rim,
                                   om, zeta, gam, np.bool_(True))
                if h_floor < t_b < h:
                    h = t_b
                    started = True
                    continue
            rims0 = _rim_bits(y, rim)
            # the step reaches the ultimate from groups off their rims (an impact booked in a solve): its arrival is
            # located after the step's error test (locate_arrival_by, below), as the rigid block's
            reach = ult == 0 and rims0 != low and r1[R_IMPULSE] + rh[R_IMPULSE] + r2[R_IMPULSE] > 0.0 and not jump
            if ((r1[R_IMPULSE] > 0.0 or (m1 >> ng) & ~rims0 & away) and not reach and not arrival
                    and h > 4.0 * h_floor and not (m1 | mh | m2) & UNSOLVED):
                # the step brings a group onto its rim (or the bearing to its ultimate): the rim's reaction acts over
                # the whole step — at the ultimate the floors would see the impact as a pulse of that length, and at
                # any rim the reaction's work ν·δ over the step's slip (g ν δ, ν the force's jump to the next surface)
                # is lost from the balance (NWH360 with a double of an intermediate rim: 2.8e-5 of the input in one
                # step of 5e-5 s).  The step is cut to end just before the arrival (bisection on its length to
                # rounding), and the arrival is a step of at most 2 floors that starts there.  Bisected only to the
                # floor, the arrival fell up to a floor into its step, whose force (the rim's, the next surface's
                # friction) then acted from the step's start: the velocity off by up to the force's jump × a floor
                # (NWH360 on the double with an intermediate rim at step_tol 1e-9, the arrival at 3.60987 s: 6.7e-9
                # m/s, 2e-9 of the peak by the record's end).  Only an arrival from away (off the rim by more than
                # RIM_AWAY, as a rim contact is counted): a group turning on its rim touches it in nearly every step
                # (Chuetsu-oki 65025 with F&C's TFP: the work bound at 26.46 s otherwise).  The ultimate's arrival
                # from groups off their rims is located below (``reach``); one from groups on their rims (an impact
                # in a step that started at the ultimate's classification) is bisected to the floor only: the rigid
                # block's arrival event takes it from there
                lo = 0.0
                up = h
                bracket = h_floor if r1[R_IMPULSE] > 0.0 else 0.0
                for _ in range(200):  # the length's binary digits, until the bracket's ends are adjacent floats
                    mid = 0.5 * (lo + up)
                    if not lo < mid < up or up - lo <= bracket:
                        break
                    ma = building_step(y, mid, a0x, a0y, slope_x, slope_y, nz[i] + slope_z * (tau + 0.5 * mid), c, rb,
                                       mu, rim, om, zeta, gam, r, y0, ra, ult)
                    work += ra[2]
                    if ra[R_IMPULSE] > 0.0 or (ma >> ng) & ~rims0 & away:
                        up = mid
                    else:
                        lo = mid
                arrival = True
                arrival_steps = 0
                h = lo if lo > h_floor else up
                continue
            if (m1 | mh | m2) & UNSOLVED:
                if not at_floor:
                    n_rej += 1
                    h = max(0.25 * h, h_floor)
                    continue
                status |= STATUS_UNSOLVED
                fail_t = t[i] + tau
                summary[S_FAIL_RIMS] = _on_rims(y, rim)
                break
            xs = max(tol * max(peak_x, x_floor),
                     SLIP_QUANTA * DOUBLE_EPS * (rb_mu + rb_sum * math.sqrt(r[0] * r[0] + r[1] * r[1])))
            vs = tol * max(peak_v, v_floor)
            qs = tol * max(peak_q, floor_rel * peak_x, q_floor)
            qds = tol * max(peak_qd, floor_rel * peak_v, qd_floor)
            err = building_error(y1, y2, m1, mh, m2, ng, nm, xs, vs, qs, qds)
            n_steps += 1
            if err > 1.0:
                if not at_floor:
                    n_rej += 1
                    h = max(h * max(0.1, 0.9 / math.sqrt(err)), h_floor)
                    continue
                n_floor += 1
            impacted = r1[R_IMPULSE] + rh[R_IMPULSE] + r2[R_IMPULSE] > 0.0
            turned = y[Y_V] * y2[Y_V] + y[Y_V + 1] * y2[Y_V + 1]
            if not (jump or at_floor) and turned > 0.0:
                # a group's slip turning inside the step by more than SLIP_TURN: retried shorter (the rigid block's
                # rule, planar_multisurface_stepper.slip_turn)
                turn = slip_turn(y, yh, y2, qlast, mh & m2 & low)
                if turn > SLIP_TURN:
                    n_rej += 1
                    h = max(h * max(0.1, 0.9 * SLIP_TURN / turn), h_floor)
                    continue
            if (not held_s and stop_h != h and not jump and not impacted and not at_rest
                    and (turned < 0.0 or (turned == 0.0 and not (static or m2 & low)))):
                # sliding under static friction, the velocity turned back within the step: it passed through zero,
                # a stop (then at rest under µs, held or leaving at µk as the force the slab needs says).  The stop
                # is located by bisection on the step's length (to rounding) between the length whose velocity
                # still points forward and the one whose velocity has turned or vanished; a stop only when the
                # velocity there is below the steps' velocity tolerance (a fast turn in the plane is no stop)
                lo = 0.0
                up = h
                for _ in range(200):
                    mid = 0.5 * (lo + up)
                    if not (lo < mid < up):
                        break
                    building_step(y, mid, a0x, a0y, slope_x, slope_y, nz[i] + slope_z * (tau + 0.5 * mid), c, rb, mu,
                                  rim, om, zeta, gam, r, y0, ra, ult)
                    work += ra[2]
                    if y[Y_V] * y0[Y_V] + y[Y_V + 1] * y0[Y_V + 1] > 0.0:
                        lo = mid
                    else:
                        up = mid
                # under static friction the step ends where the velocity has turned or vanished (then held); under
                # kinetic friction where it still points forward (a reversal: the same groups slide to its end, so
                # the step's Richardson combination holds, and the next step starts from V = 0 with the reversed set)
                # (its velocity is rounding below CUT_ROUNDING |X| / cut: the slips' last bits over the step)
                cut = up if static else lo
                if 0.0 < lo < h:
                    # the bracket's forward end extrapolated to the velocity's zero: a solve's stick-or-slide
                    # decision for a slip V t near the ulp of |ū| is rounding, so the bisection's bracket can close
                    # short of the zero (NWH360 on the double with an intermediate rim at step_tol 1e-9, the reversal
                    # at 2.31973 s: sliding at 2.2467e-7 s into the step with 2.1e-9 m/s left, stuck at the next
                    # float; the steps then crept to the zero at the floor and took 2.9e-8 m/s away, 5e-9 of the peak
                    # later).  Over so short a length the velocity is linear in it, V0 − t (g r + ā') with r at the
                    # sliding groups' friction: its zero is lo V0 / (V0 − V(lo)) along V0
                    building_step(y, lo, a0x, a0y, slope_x, slope_y, nz[i] + slope_z * (tau + 0.5 * lo), c, rb, mu,
                                  rim, om, zeta, gam, r, y0, ra, ult)
                    v_0 = math.sqrt(y[Y_V] ** 2 + y[Y_V + 1] ** 2)
                    v_lo = (y0[Y_V] * y[Y_V] + y0[Y_V + 1] * y[Y_V + 1]) / v_0 if v_0 > 0.0 else 0.0  # (squares' underflow)
                    if 0.0 < v_lo < v_0:
                        t_zero = lo * v_0 / (v_0 - v_lo)
                        if cut < t_zero < h:
                            cut = t_zero
                if 0.0 < cut < h:
                    building_step(y, cut, a0x, a0y, slope_x, slope_y, nz[i] + slope_z * (tau + 0.5 * cut), c, rb,
                                  mu, rim, om, zeta, gam, r, y0, ra, ult)
                    if math.sqrt(y0[Y_V] ** 2 + y0[Y_V + 1] ** 2) <= max(
                            vs, CUT_ROUNDING * math.sqrt(y[Y_X] ** 2 + y[Y_X + 1] ** 2) / cut):
                        h = cut
                        stop_h = cut
                        continue
            dv_imp_x = 0.0  # the velocity a located impact took from the slab at the step's end (the rows' forcing)
            dv_imp_y = 0.0
            f_arr = -1.0  # the isolator's force per unit total mass at a located arrival, before its impact
            if reach:
                # the step reached the ultimate: taken at its end, the impulse was the velocity change of a step
                # ending on the rims, the finite force over the step counted in it (Kobe KJM ×1.6 on the small TFP,
                # 3.2375 s: 2.6e-8 / 4.6e-8 of the 1-D building's impulse at step_tol 1e-8 / 1e-9, not falling).  The
                # arrival located as the rigid block's (planar_multisurface_stepper: locate_arrival, arrival_impact):
                # the three solves with the arriving groups' rims lifted, their combination on the rim by bisection
                # on the step's length, the impulse the slab's outward velocity there, the floors keeping theirs
                for k in range(ng):
                    rim_free[k] = math.inf if (low & ~rims0) >> k & 1 else rim[k]
                lo, w_arr = locate_arrival_floors(y, h, tau, raw, c, rb, mu_now, rim, rim_free, low & ~rims0, r, ya1,
                                                  yah, ya2, r1, rh, rl, floors)
                work += w_arr
                if lo > 0.0:
                    m1a, mha, m2a = building_solves(y, lo, tau, raw, c, rb, mu_now, rim_free, r, ya1, yah, ya2, r1, rh,
                                                    rl, np.int64(0), floors)
                    for j in range(ny):
                        ya[j] = y[j]
                    accept_step(ya, ya1, ya2, ny, f0 - 1, ng, rim, m1a, mha, m2a, np.bool_(False), np.bool_(True))
                    v_x = ya[Y_V]
                    v_y = ya[Y_V + 1]
                    vn = arrival_impact_floors(ya, rim, low & ~rims0, nz[i] + slope_z * (tau + lo), rb, om, gam)
                    if vn >= 0.0:
                        err_a = building_error(ya1, ya2, m1a, mha, m2a, ng, nm, xs, vs, qs, qds)
                        if err_a > 1.0 and not at_floor:
                            n_rej += 1
                            h = max(lo * max(0.1, 0.9 / math.sqrt(err_a)), h_floor)
                            continue
                        err = err_a
                        last_step = last_step and lo == h
                        h = lo
                        m1 = m1a
                        mh = mha
                        m2 = (m2a & low) | _rim_bits(ya, rim) << ng
                        r1[R_IMPULSE] = 0.0
                        rh[R_IMPULSE] = 0.0
                        r2[R_IMPULSE] = vn
                        r2[0] = rl[0]
                        r2[1] = rl[1]
                        impacted = vn > 0.0
                        dv_imp_x = ya[Y_V] - v_x
                        dv_imp_y = ya[Y_V + 1] - v_y
                        # the surfaces' force as the groups arrive (the impulse then takes the step's end): the
                        # force's peak is there on the way to the ultimate
                        n_arr = nz[i] + slope_z * (tau + lo)
                        f_arr = math.hypot(n_arr * rl[0] + c * v_x, n_arr * rl[1] + c * v_y)
                        peak_r = max(peak_r, math.hypot(rl[0], rl[1]))
                    else:
                        reach = False
                else:
                    reach = False
            # a plain sliding step (the same groups sliding in its three solves, no impact, no stop): its base shear's
            # maximum inside it is located on the parabola through its start, its first half's end and its end
            # (parabola_peak); the start's force from the last step's end when that step was plain too
            plain = not (jump or impacted) and m1 == mh and mh == m2 and (m1 & low) != 0 and stop_h != h
            f_start = -1.0
            if plain and prev_plain:
                n_0 = nz[i] + slope_z * tau
                f_start = math.hypot(n_0 * r[0] + c * y[Y_V], n_0 * r[1] + c * y[Y_V + 1])
            for j in range(ny):
                y0[j] = y[j]
            if reach:
                for j in range(ny):
                    y[j] = ya[j]
            else:
                accept_step(y, y1, y2, ny, f0 - 1, ng, rim, m1, mh, m2, impacted, np.bool_(True))
            r[0] = r2[0]
            r[1] = r2[1]
            if stop_h == h:
                # the step cut at the stop: the slab's velocity left (below the velocity tolerance) is taken away as
                # an impulse on the slab alone (the floors keep their absolute velocity), its energy booked as friction
                e_before = total_energy(y, nz[i], rb, om, gam)  # the bearing's stored energy unchanged: any n
                for d in range(2):
                    for k in range(nm):
                        y[f0 + 2 * nm * d + nm + k] += gam[d, k] * y[Y_V + d]
                    y[Y_V + d] = 0.0
                y[Y_EF] += e_before - total_energy(y, nz[i], rb, om, gam)
            for k in range(ng):  # each group's slip over the accepted step (slip_turn); none after a stop or an impact
                slid = stop_h != h and y[Y_EIMP] == y0[Y_EIMP] and (m1 | m2) >> k & 1
                qlast[k, 0] = y[Y_U + 2 * k] - y0[Y_U + 2 * k] if slid else 0.0
                qlast[k, 1] = y[Y_U + 2 * k + 1] - y0[Y_U + 2 * k + 1] if slid else 0.0
            stop_h = -1.0
            if static:
                if y[Y_V] == 0.0 and y[Y_V + 1] == 0.0:
                    held_s = True
                if started:
                    held_s = False
            tau = hi if last_step else tau + h
            g = nz[i] + slope_z * tau  # n at the step's end
            on_rim = m2 >> ng
            if on_rim & away:
                n_rim += popcount(element_mask(on_rim & away, members))
                away &= ~on_rim
            for k in range(ng):
                if y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2 < (rim[k] * (1.0 - RIM_AWAY)) ** 2:
                    away |= 1 << k
            rigid = on_rim == low
            f_max = 0.0
            if rigid:
                if first_ult < 0.0:
                    first_ult = t[i] + tau
                for k in range(ng):
                    f_max = max(f_max, math.sqrt(y[Y_U + 2 * k] ** 2 + y[Y_U + 2 * k + 1] ** 2) / rb[k] + mu[k])
            impulsive = rh[R_IMPULSE] + r2[R_IMPULSE] > 0.0
            if impulsive:
                # the velocity the impact removed from the slab (consecutive impact steps are one impact)
                impact_v += rh[R_IMPULSE] + r2[R_IMPULSE]
                r[0] = -(ax[i] + slope_x * tau) / g
                r[1] = -(ay[i] + slope_y * tau) / g
            elif impact_v > 0.0:
                n_ult += 1
                impulse += impact_v
                max_imp_v = max(max_imp_v, impact_v)
                impact_v = 0.0
            if (m1 | m2) & low:
                slip += h
                sl = (m2 if m2 & low else m1) & low
                em = element_mask(sl & ~on_rim, members) | (element_mask(on_rim, members) << ne)
                if first[em] < 0.0:
                    first[em] = t[i] + tau
            fr = math.sqrt(r[0] * r[0] + r[1] * r[1])
            peaks[nk + 2] = max(peaks[nk + 2], f_arr)
            if not impulsive:
                # the surfaces' force (at the ultimate the rims' reaction left out, as the rigid block's); the isolator
                # force on the slab with it: held at the ultimate the bearing holds the slab against the floors
                peak_r = max(peak_r, min(fr, f_max) if rigid else fr)
                f1 = g * r[0] + c * y[Y_V]
                f2 = g * r[1] + c * y[Y_V + 1]
                f_abs = math.sqrt(f1 * f1 + f2 * f2)
                if rigid:
                    # every group on its rim: where the rims close into alignment their reaction grows as 1/sin of
                    # their angle and does not converge with step_tol (the rigid block's steps cap it the same way);
                    # the force is taken up to what the slab held at the ultimate needs against the ground and the
                    # floors, |a_g + Σ Γ̃ q̃''| (or the largest surface force), plus the dashpot and the centripetal
                    # |V|²/|X| of a slide along the ultimate circle (PTS ×2 with the small TFP: the base shear
                    # differed by 61 % between the pair and the pair turned by 0.7 rad without the cap)
                    ag_x = ax[i] + slope_x * tau
                    ag_y = ay[i] + slope_y * tau
                    h1 = _held_force(y, f0, nm, ag_x, om, zeta, gam, np.int64(0))
                    h2 = _held_force(y, f0, nm, ag_y, om, zeta, gam, np.int64(1))
                    vn = math.sqrt(y[Y_V] ** 2 + y[Y_V + 1] ** 2)
                    xn = math.sqrt(y[Y_X] ** 2 + y[Y_X + 1] ** 2)
                    a_cap = max(g * f_max, math.sqrt(h1 * h1 + h2 * h2)) + c * vn
                    if xn > 0.0:
                        a_cap += vn * vn / xn
                    f_abs = min(f_abs, a_cap)
                elif f_start >= 0.0:
                    # the base shear while the slab slides was taken at the steps' ends: its maximum inside the step
                    # on the parabola through the step's start, half and end (the first half's end state and force)
                    n_h = nz[i] + slope_z * (tau - 0.5 * h)
                    f_h = math.hypot(n_h * rh[0] + c * yh[Y_V], n_h * rh[1] + c * yh[Y_V + 1])
                    f_abs = max(f_abs, parabola_peak(f_start, f_h, f_abs))
                peaks[nk + 2] = max(peaks[nk + 2], f_abs)
            elif y[Y_V] == 0.0 and y[Y_V + 1] == 0.0:
                # the slab stopped by the impact, held at the ultimate: the bearing's force is what it needs there,
                # −(a_g + Σ Γ̃ q̃''), the floors' dampers at their velocities just after the impact
                h1 = _held_force(y, f0, nm, ax[i] + slope_x * tau, om, zeta, gam, np.int64(0))
                h2 = _held_force(y, f0, nm, ay[i] + slope_y * tau, om, zeta, gam, np.int64(1))
                peaks[nk + 2] = max(peaks[nk + 2], math.sqrt(h1 * h1 + h2 * h2))
            prev_plain = plain and not (rigid or impulsive)
            peak_x = max(peak_x, math.sqrt(y[Y_X] ** 2 + y[Y_X + 1] ** 2))
            peak_v = max(peak_v, math.sqrt(y[Y_V] ** 2 + y[Y_V + 1] ** 2))
            for j in range(2):
                for k in range(nm):
                    jj = f0 + 2 * nm * j + k
                    peak_q = max(peak_q, abs(y[jj]))
                    peak_qd = max(peak_qd, abs(y[jj + nm]))
            # the floors' watched rows inside the step (its constant ẍ_b, from its start), points at most WATCH_TURN
            # of the fastest mode apart, and at its end; between two points (the step's ends included) where a row's
            # resultant turns from rising to falling, its maximum is located (row_peak).  Not in a step with an
            # impulse (an impact: its velocity change is not the step's ẍ_b)
            n_in = min(int(h * max(om[0, nm - 1], om[1, nm - 1]) / WATCH_TURN), MAX_WATCH_POINTS)
            held_step = (y0[Y_V] == 0.0 and y0[Y_V + 1] == 0.0 and y[Y_V] == 0.0 and y[Y_V + 1] == 0.0
                         and c == 0.0)
            locate = not (jump or impacted)
            if locate and n_in == 0:
                # a short step: located only where a row at one of its ends is within LOCATE_BAND of its peak (most
                # steps are far from the rows' peaks: their rates are not computed)
                near = False
                _floor_rows(y, f0, nm, np.int64(0), lin, rowx)
                _floor_rows(y, f0, nm, np.int64(1), lin, rowy)
                for k in range(nk):
                    if max(math.sqrt(rowx[k] * rowx[k] + rowy[k] * rowy[k]), r_last[k]) >= (
                            1.0 - LOCATE_BAND) * peaks[2 + k]:
                        near = True
                for k in range(nj):
                    v = signed_row(y, f0, nm, sig, k, sig_z, az[i] + slope_az * tau)
                    if (_near_extreme(v, sig_max[k], sig_min[k])
                            or _near_extreme(s_last[k], sig_max[k], sig_min[k])):
                        near = True
                locate = near
            # the forcing a_g + ẍ_b at the step's start per direction
            fx = ax[i] + slope_x * (tau - h) + (y[Y_V] - dv_imp_x - y0[Y_V]) / h
            fy = ay[i] + slope_y * (tau - h) + (y[Y_V + 1] - dv_imp_y - y0[Y_V + 1]) / h
            for k in range(nj):  # the vertical's share of the signed rows over the step: z0 + zs τ
                sz0[k] = sig_z[k] * (az[i] + slope_az * (tau - h))
                szs[k] = sig_z[k] * slope_az
            if locate:
                row_rises(y0, 0.0, fx, fy, slope_x, slope_y, f0, nm, lin, om, zeta, gam, qdd, rise0)
                signed_rises(y0, 0.0, f0, nm, sgl, qdd, sz0, szs, srise0)
            hg0 = 0.0
            hv0 = 0.0
            if held_step:
                # the held slab's force, located as the rows' peaks where it turns from rising to falling near its peak
                for d in range(2):
                    share = 1.0
                    for k in range(nm):
                        share -= gam[d, k] * gam[d, k]
                    hoff[d, 0] = -share * (fx if d == 0 else fy)
                    hoff[d, 1] = -share * (slope_x if d == 0 else slope_y)
                hg0, hv0 = held_rises(y0, 0.0, fx, fy, slope_x, slope_y, f0, nm, hl, hoff, om, zeta, gam, qdd)
            tp0 = 0.0
            for p in range(1, n_in + 2):
                tp = h * p / (n_in + 1)
                if p <= n_in:
                    floors_at(y0, tp, fx, fy, slope_x, slope_y, f0, nm, om, zeta, gam, yw)
                    _watch(yw, f0, nm, lin, sig, rowx, rowy, peaks, sig_max, sig_min, sig_z,
                           az[i] + slope_az * (tau - h + tp))
                    if held_step:
                        # the slab held (stuck, or at the ultimate) through the step: the bearing's force is what the
                        # slab needs, −(a_g + Σ Γ̃ q̃''), per unit total mass
                        f1 = _held_force(yw, f0, nm, ax[i] + slope_x * (tau - h + tp), om, zeta, gam, np.int64(0))
                        f2 = _held_force(yw, f0, nm, ay[i] + slope_y * (tau - h + tp), om, zeta, gam, np.int64(1))
                        peaks[nk + 2] = max(peaks[nk + 2], math.sqrt(f1 * f1 + f2 * f2))
                if held_step:
                    hg1, hv1 = held_rises(yw if p <= n_in else y, tp, fx, fy, slope_x, slope_y, f0, nm, hl, hoff, om,
                                          zeta, gam, qdd)
                    if hg0 > 0.0 >= hg1 and max(hv0, hv1) >= (1.0 - LOCATE_BAND) * peaks[nk + 2]:
                        peaks[nk + 2] = max(peaks[nk + 2], row_peak(y0, tp0, tp, np.int64(0), fx, fy, slope_x, slope_y, f0, nm,
                                                                     hl, om, zeta, gam, qdd, yw, np.bool_(False), 0.0, 0.0,
                                                                     hoff))
                    hg0 = hg1
                    hv0 = hv1
                if not locate:
                    tp0 = tp
                    continue
                row_rises(yw if p <= n_in else y, tp, fx, fy, slope_x, slope_y, f0, nm, lin, om, zeta, gam, qdd,
                          rise1)
                signed_rises(yw if p <= n_in else y, tp, f0, nm, sgl, qdd, sz0, szs, srise1)
                for k in range(nk):
                    if (rise0[k, 0] > 0.0 >= rise1[k, 0]
                            and max(rise0[k, 1], rise1[k, 1]) >= (1.0 - LOCATE_BAND) * peaks[2 + k]):
                        peaks[2 + k] = max(peaks[2 + k], row_peak(y0, tp0, tp, k, fx, fy, slope_x, slope_y, f0, nm,
                                                                   lin, om, zeta, gam, qdd, yw, np.bool_(False),
                                                                   0.0, 0.0))
                    rise0[k, 0] = rise1[k, 0]
                    rise0[k, 1] = rise1[k, 1]
                for k in range(nj):
                    # a signed row's extreme (|s| turning from rising to falling, its sign kept between the points)
                    # near the extreme of its sign so far: located as the watched rows' peaks
                    if (srise0[k, 0] > 0.0 >= srise1[k, 0] and srise0[k, 1] * srise1[k, 1] > 0.0
                            and (_near_extreme(srise0[k, 1], sig_max[k], sig_min[k])
                                 or _near_extreme(srise1[k, 1], sig_max[k], sig_min[k]))):
                        v = row_peak(y0, tp0, tp, k, fx, fy, slope_x, slope_y, f0, nm, sgl, om, zeta, gam, qdd, yw,
                                     np.bool_(True), sz0[k], szs[k])
                        sig_max[k] = max(sig_max[k], v)
                        sig_min[k] = min(sig_min[k], v)
                    srise0[k, 0] = srise1[k, 0]
                    srise0[k, 1] = srise1[k, 1]
                tp0 = tp
            _watch(y, f0, nm, lin, sig, rowx, rowy, peaks, sig_max, sig_min, sig_z, az[i] + slope_az * tau)
            for k in range(nk):
                r_last[k] = math.sqrt(rowx[k] * rowx[k] + rowy[k] * rowy[k])  # the rows' resultants at the step's end
            for k in range(nj):
                s_last[k] = signed_row(y, f0, nm, sig, k, sig_z, az[i] + slope_az * tau)
            if not groups_within_rims(y, ub, rim):
                status |= STATUS_RIM
                fail_t = t[i] + tau
            if status:
                break
            surface_peaks(ub, rb, members, tmat, surf_peak)
            h = h_keep if jump else h * min(5.0, 0.9 / math.sqrt(max(err, 1e-12)))
            if started:
                h = min(h, 1e-3 * hi)
                started = False
            if arrival:
                # the step cut before the arrival, then the arrival's short step; at most two steps after the cut
                # (the motion may turn away from the rim in between: the flag would otherwise hold every later step
                # at two floors)
                arrival_steps += 1
                if impulsive or (m2 >> ng) & ~rims0 or arrival_steps > 2:
                    arrival = False
                else:
                    h = min(h, 2.0 * h_floor)
        max_work = max(max_work, work)
        if status:
            break
        h_sugg = h
        for j in range(ny):
            out_y[i + 1, j] = y[j]
        out_r[i + 1, 0] = r[0]
        out_r[i + 1, 1] = r[1]
        last = i + 1
    for j in range(last + 1, n):
        for k in range(ny):
            out_y[j, k] = np.nan
    if impact_v > 0.0:
        n_ult += 1
        impulse += impact_v
        max_imp_v = max(max_imp_v, impact_v)
    peaks[0] = peak_x
    peaks[1] = peak_v
    summary[S_PEAK_X] = peak_x
    summary[S_PEAK_V] = peak_v
    summary[S_PEAK_A] = peaks[nk + 2]
    summary[S_SLIP_TIME] = slip
    summary[S_E_IN] = y[Y_EIN]
    summary[S_E_F] = y[Y_EF]
    summary[S_E_V] = y[Y_EV]
    summary[S_E_IMP] = y[Y_EIMP]
    summary[S_STATUS] = status
    summary[S_N_STEPS] = n_steps
    summary[S_N_REJECTED] = n_rej
    summary[S_FAIL_T] = fail_t
    summary[S_STEPS_MULTI] = n_floor
    summary[S_N_RIM_CONTACTS] = n_rim
    summary[S_N_ULTIMATE] = n_ult
    summary[S_IMPULSE] = impulse
    summary[S_MAX_IMPACT_V] = max_imp_v
    summary[S_PEAK_R] = peak_r
    summary[S_FIRST_ULT] = first_ult
    summary[S_MAX_WORK] = max_work
