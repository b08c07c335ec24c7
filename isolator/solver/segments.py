r"""Closed-form slip segments: the motion between two events.

While the block slides in one direction ``s`` the equation of motion is linear
(Nicolas 2017, Eq. 1, per unit mass, relative coordinate X):

.. math::  X'' + c X' + \kappa X = u(\tau),

with :math:`c = \gamma/M` [1/s], :math:`\kappa = K/M` [1/s²] and a forcing
:math:`u` that is either a ramp (a sampled record taken as piecewise linear,
:math:`u = p + q\tau`) or a harmonic (the paper's case,
:math:`u = p + F\cos(\theta_0 + \omega\tau)`).  Everything is written in the
*local* time :math:`\tau` of the segment, so nothing grows with the length of a run.

With :math:`m = -c/2` and :math:`d^2 = c^2/4 - \kappa` (the sign of :math:`d^2`
separates configurations 4a/4b/4c: under-, critically and over-damped, Eq. 27) the
solution is

.. math::

    X(\tau) &= E_0 X_0 + E_1 (V_0 - m X_0) + p H_1 + q H_2, \\
    V(\tau) &= E_0 V_0 + E_1 (m V_0 - \kappa X_0 + p) + q H_1,

where :math:`E_1 = e^{m\tau}\sinh(d\tau)/d` is the impulse response,
:math:`E_0 = e^{m\tau}\cosh(d\tau)` and :math:`H_{j+1} = \int_0^\tau H_j`,
:math:`H_0 = E_1`.  These are the paper's Eqs. 16–17 (configuration 1), 19–20 (2),
23–24 (3) and 28–39 (4a–4c), collected into one set of entire functions of
:math:`(c, \kappa, \tau)`; the harmonic particular solution is the same
:math:`H_1` for the complex shift :math:`m \to m - i\omega` (:func:`harmonic_h1`).

Uniform accuracy.  Each function is evaluated by whichever of three forms is
well conditioned at ``(c, κ, τ)``; none divides by a quantity that can vanish:

* *Taylor* — the power series of the solution, when the segment is short compared
  with every time scale of the system (``r = max(|m|, |d|) τ <= 1.5``).  No division
  at all, so critical damping (d = 0), k → 0, η → 0 and resonance are regular.
* *eigen* — the two exponentials :math:`e^{\lambda_\pm\tau}` with
  :math:`\lambda_\pm = m \pm d`, when they are well separated
  (``2|d| >= min |λ±|``); the smaller root is computed as
  :math:`\lambda_+ = \kappa/\lambda_-` (no cancellation when κ → 0).
* *division* — :math:`H_1 = (1 - E_0 + m E_1)/\kappa` and its recursions, when the
  eigenvalues are close (near-critical damping) but the segment is long; there
  :math:`|\kappa|\tau^2 > 1`, so the division is harmless.

The special configurations keep their simplest closed forms: friction only
(``c = κ = 0``) is a polynomial, friction + damper (``κ = 0``) uses
:math:`\varphi_j(-c\tau)` functions.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.solver.jit import njit

#: Segments with max(|m|, |d|)·τ below this are evaluated by power series [-].
TAYLOR_RADIUS = 1.5
#: |d|·τ below this: cosh/sinh (or cos/sin) by series in d²τ² [-].
SMALL_ARGUMENT = 0.5
_MAX_TERMS = 80


# ---------------------------------------------------------------------------
# φ-functions  φ_j(z) = Σ_n z^n / (n + j)!
# ---------------------------------------------------------------------------
@njit(cache=True)
def phi_functions(z):
    """φ1, φ2, φ3, φ4 of a real argument, accurate for every z ≤ 0 and small z > 0.

    Parameters
    ----------
    z : float
        Argument [-].

    Returns
    -------
    tuple of float
        ``(φ1(z), φ2(z), φ3(z), φ4(z))`` with φ1(z) = (e^z - 1)/z, φ_{j+1} = (φ_j - 1/j!)/z.
    """
    if abs(z) < 2.0:
        # series: φ_j(z) = Σ z^n/(n+j)!; |z| < 2 → 30 terms reach 1e-18
        p1 = 0.0
        p2 = 0.0
        p3 = 0.0
        p4 = 0.0
        zn = 1.0  # z^n / n!
        for n in range(40):
            # z^n/(n+1)! etc. built from z^n/n!
            t1 = zn / (n + 1)
            t2 = t1 / (n + 2)
            t3 = t2 / (n + 3)
            t4 = t3 / (n + 4)
            p1 += t1
            p2 += t2
            p3 += t3
            p4 += t4
            zn = zn * z / (n + 1)
            if abs(t1) < 1e-18 * abs(p1) and n > 3:
                break
        return p1, p2, p3, p4
    ez = math.exp(z)
    p1 = (ez - 1.0) / z
    p2 = (p1 - 1.0) / z
    p3 = (p2 - 0.5) / z
    p4 = (p3 - 1.0 / 6.0) / z
    return p1, p2, p3, p4


@njit(cache=True)
def phi1_complex(z):
    """φ1(z) = (e^z - 1)/z for a complex argument, uniformly accurate [-]."""
    if abs(z) < 1.0:
        total = 0.0 + 0.0j
        term = 1.0 + 0.0j  # z^n/(n+1)!
        for n in range(40):
            total += term
            term = term * z / (n + 2)
            if abs(term) < 1e-18 * abs(total):
                break
        return total
    return (np.exp(z) - 1.0) / z


# ---------------------------------------------------------------------------
# cosh(dτ), sinh(dτ)/d for signed d² (cos/sin when d² < 0), no overflow
# ---------------------------------------------------------------------------
@njit(cache=True)
def _scaled_cosh_sinh(m, d2, tau):
    """E0 = e^{mτ} cosh(dτ) and E1 = e^{mτ} sinh(dτ)/d for signed d², real or complex m.

    d² < 0 gives e^{mτ} cos(ω_d τ) and e^{mτ} sin(ω_d τ)/ω_d; d² = 0 gives e^{mτ}
    and τ e^{mτ}; both forms meet smoothly through the series in d²τ².  Real m ≤ 0
    serves the ramp basis, complex m the harmonic one (numba compiles each).
    """
    w = d2 * tau * tau
    if abs(w) < SMALL_ARGUMENT * SMALL_ARGUMENT:
        c_sum = 0.0
        s_sum = 0.0
        term_c = 1.0  # w^n/(2n)!
        term_s = 1.0  # w^n/(2n+1)!
        for n in range(30):
            c_sum += term_c
            s_sum += term_s
            term_c = term_c * w / ((2 * n + 1) * (2 * n + 2))
            term_s = term_s * w / ((2 * n + 2) * (2 * n + 3))
            if abs(term_c) < 1e-18 and abs(term_s) < 1e-18:
                break
        em = np.exp(m * tau)
        return em * c_sum, em * (s_sum * tau)
    if d2 > 0.0:
        d = math.sqrt(d2)
        e_plus = np.exp((m + d) * tau)
        e_minus = np.exp((m - d) * tau)
        return 0.5 * (e_plus + e_minus), (e_plus - e_minus) / (2.0 * d)
    wd = math.sqrt(-d2)
    em = np.exp(m * tau)
    return em * math.cos(wd * tau), em * (math.sin(wd * tau) / wd)


# ---------------------------------------------------------------------------
# Ramp forcing: E0, E1, H1, H2, H3
# ---------------------------------------------------------------------------
# Reciprocals used by the power series (divisions are the slow part of a series term)
_N = np.arange(_MAX_TERMS + 4, dtype=np.float64)
_RECIP_STEP = 1.0 / np.maximum((_N + 1.0) * _N, 1.0)  # 1/((n+1) n)
_RECIP_K1 = 1.0 / (_N + 1.0)  # 1/(k+1)
_RECIP_K12 = 1.0 / ((_N + 1.0) * (_N + 2.0))  # 1/((k+1)(k+2))
_RECIP_K123 = 1.0 / ((_N + 1.0) * (_N + 2.0) * (_N + 3.0))  # 1/((k+1)(k+2)(k+3))


@njit(cache=True)
def _ramp_basis_taylor(tau, c, kappa):
    # Power series of the impulse response e(τ) = Σ z_n, z_n = e_n τ^n, from
    # e'' = -c e' - κ e, e(0) = 0, e'(0) = 1.
    a = -c * tau
    b = -kappa * tau * tau
    tau2 = tau * tau
    tau3 = tau2 * tau
    z_prev = 0.0  # z_0
    z_cur = tau  # z_1
    e1 = tau
    h1 = tau2 / 2.0
    h2 = tau3 / 6.0
    h3 = tau3 * tau / 24.0
    de1 = 1.0  # Σ n z_n / τ  (= E1')
    inv_tau = 1.0 / tau
    # no damper (a = 0): every even term z_2, z_4, ... is zero, so the loop steps over them.  The odd terms are the
    # general recurrence's to the bit (z_{n+1} = (0 + b z_{n-1}) / ((n+1) n)), and it stops after the same term: the
    # general test after a zero term, |z_{n+1}| <= 1e-17 |e1|, covers its test after the odd one (1e-18).
    undamped = c == 0.0
    for n in range(2 if undamped else 1, _MAX_TERMS, 2 if undamped else 1):
        # z_{n+1} from z_n and z_{n-1} (undamped: z_cur holds z_{n-1}, z_n = 0)
        z_next = b * z_cur * _RECIP_STEP[n] if undamped else (a * n * z_cur + b * z_prev) * _RECIP_STEP[n]
        k = n + 1
        e1 += z_next
        h1 += z_next * tau * _RECIP_K1[k]
        h2 += z_next * tau2 * _RECIP_K12[k]
        h3 += z_next * tau3 * _RECIP_K123[k]
        de1 += k * z_next * inv_tau
        z_prev = z_cur
        z_cur = z_next
        if undamped:
            if abs(z_next) <= 1e-17 * abs(e1):
                break
        elif abs(z_next) <= 1e-18 * abs(e1) and abs(z_prev) <= 1e-17 * abs(e1):
            break
    e0 = de1 + 0.5 * c * e1  # E0 = E1' - m E1
    return e0, e1, h1, h2, h3


@njit(cache=True)
def ramp_basis(tau, c, kappa):
    """Basis functions of a slip segment under constant + ramp forcing.

    Parameters
    ----------
    tau : float
        Local time since the start of the segment [s] (or dimensionless time) ≥ 0.
    c : float
        Damping per unit mass γ/M [1/s] (η in dimensionless form) ≥ 0.
    kappa : float
        Stiffness per unit mass K/M [1/s²] (k in dimensionless form) ≥ 0.

    Returns
    -------
    tuple of float
        ``(E0, E1, H1, H2, H3)``: E0 = e^{mτ}cosh(dτ), E1 = e^{mτ}sinh(dτ)/d [s],
        H1 = ∫E1 [s²], H2 = ∫H1 [s³], H3 = ∫H2 [s⁴], with m = -c/2, d² = c²/4 - κ.

    References
    ----------
    Nicolas (2017), Eqs. 16–17, 19–20, 23–24, 28–39, written in local time.
    """
    if tau <= 0.0:
        return 1.0, 0.0, 0.0, 0.0, 0.0
    if c == 0.0 and kappa == 0.0:
        # configuration 1: friction only — polynomials (Eq. 16)
        return 1.0, tau, tau * tau / 2.0, tau ** 3 / 6.0, tau ** 4 / 24.0
    if kappa == 0.0:
        # configuration 2: friction + damper — e^{-cτ} through φ-functions (Eq. 19)
        z = -c * tau
        p1, p2, p3, p4 = phi_functions(z)
        return 0.5 * (1.0 + math.exp(z)), tau * p1, tau * tau * p2, tau ** 3 * p3, tau ** 4 * p4
    m = -0.5 * c
    d2 = 0.25 * c * c - kappa
    r = max(abs(m), math.sqrt(abs(d2))) * tau
    if r <= TAYLOR_RADIUS:
        return _ramp_basis_taylor(tau, c, kappa)
    e0, e1 = _scaled_cosh_sinh(m, d2, tau)
    if d2 > 0.0:
        d = math.sqrt(d2)
        lam_minus = m - d  # the fast root, < 0
        lam_plus = kappa / lam_minus  # the slow root, computed without cancellation
        if 2.0 * d >= abs(lam_plus):
            # well-separated real roots (over-damped, configuration 4c)
            inv = 1.0 / (lam_plus - lam_minus)
            a1, a2, a3, a4 = phi_functions(lam_plus * tau)
            b1, b2, b3, b4 = phi_functions(lam_minus * tau)
            h1 = tau * (a1 - b1) * inv
            h2 = tau * tau * (a2 - b2) * inv
            h3 = tau ** 3 * (a3 - b3) * inv
            return e0, e1, h1, h2, h3
    # near-critical or under-damped, long segment: |κ| τ² > 1, the division is safe
    h1 = (1.0 - e0 + m * e1) / kappa
    h2 = (tau - e1 - c * h1) / kappa
    h3 = (0.5 * tau * tau - h1 - c * h2) / kappa
    return e0, e1, h1, h2, h3


# ---------------------------------------------------------------------------
# Harmonic forcing: H1 for the complex shift μ = m - iω
# ---------------------------------------------------------------------------
@njit(cache=True)
def harmonic_h1(tau, c, kappa, omega):
    r"""Particular integral of a slip segment under harmonic forcing.

    .. math::  \mathcal H_1(\tau) = \int_0^\tau e^{(m - i\omega)u}\,\frac{\sinh(du)}{d}\,du,

    so that the response from rest to :math:`F\cos(\theta_0 + \omega\tau)` is
    :math:`\mathrm{Re}\,[F e^{i\theta_0} e^{i\omega\tau}\mathcal H_1(\tau)]`.  At exact
    resonance (c = 0, κ = ω²) one root of the shifted system is zero and the
    closed form gives the secular term τ/(2iω) without any special case
    (the paper's Eq. 26 growth).

    Parameters
    ----------
    tau : float
        Local time [-] (dimensionless time of Eq. 2) ≥ 0.
    c, kappa : float
        η and k of Eq. 2 (damping and stiffness per unit mass).
    omega : float
        Forcing frequency ω [-].

    Returns
    -------
    complex
    """
    if tau <= 0.0:
        return 0.0 + 0.0j
    mu = complex(-0.5 * c, -omega)
    d2 = 0.25 * c * c - kappa
    absd = math.sqrt(abs(d2))
    r = max(abs(mu), absd) * tau
    if r <= TAYLOR_RADIUS:
        # series of e^{μu} S(u): z_{n+1} = (2μτ n z_n - κ_μ τ² z_{n-1})/((n+1) n)
        kmu = mu * mu - d2
        a = 2.0 * mu * tau
        b = -kmu * tau * tau
        z_prev = 0.0 + 0.0j
        z_cur = complex(tau, 0.0)
        h1 = complex(tau * tau / 2.0, 0.0)
        for n in range(1, _MAX_TERMS):
            z_next = (a * n * z_cur + b * z_prev) / ((n + 1) * n)
            h1 += z_next * tau / (n + 2)
            z_prev = z_cur
            z_cur = z_next
            if abs(z_next) <= 1e-18 * abs(h1) / tau and abs(z_prev) <= 1e-17 * abs(h1) / tau:
                break
        return h1
    if d2 > 0.0:
        d = complex(absd, 0.0)
    else:
        d = complex(0.0, absd)
    lam_p = mu + d
    lam_m = mu - d
    if 2.0 * absd >= min(abs(lam_p), abs(lam_m)):
        # well-separated roots of the shifted system; one of them may be 0 (resonance)
        return tau * (phi1_complex(lam_p * tau) - phi1_complex(lam_m * tau)) / (lam_p - lam_m)
    e0, e1 = _scaled_cosh_sinh(mu, d2, tau)
    kmu = mu * mu - d2  # |κ_μ| τ² > 1 here
    return (1.0 - e0 + mu * e1) / kmu


@njit(cache=True)
def segment_state(tau, x0, v0, p, q, force, theta0, c, kappa, omega):
    """State after a slip segment of length τ under u = p + q τ + F cos(θ0 + ωτ).

    Records use the ramp (``force = 0``); the paper's harmonic case uses ``q = 0``,
    ``force = -ω²`` (Eq. 2).  Both are the same closed form.

    Parameters
    ----------
    tau : float
        Local time since the start of the segment [s] (or dimensionless).
    x0, v0 : float
        Displacement [m] and velocity [m/s] at τ = 0.
    p, q : float
        Constant part of the forcing per unit mass [m/s²] (ground acceleration plus
        kinetic friction, with their signs) and its slope [m/s³].
    force, theta0, omega : float
        Amplitude [m/s²], phase at τ = 0 [rad] and frequency [rad/s] of a harmonic
        part of the forcing (``force = 0`` for none).
    c, kappa : float
        Damping [1/s] and stiffness [1/s²] per unit mass.

    Returns
    -------
    tuple of float
        ``(x, v, a, j)``: displacement, velocity, relative acceleration and its rate
        (the jerk) at τ.
    """
    e0, e1, h1, h2, _ = ramp_basis(tau, c, kappa)
    hc = harmonic_h1(tau, c, kappa, omega) if force != 0.0 else 0.0j
    return state_from_basis(e0, e1, h1, h2, hc, tau, x0, v0, p, q, force, theta0, c, kappa, omega)


@njit(cache=True)
def state_from_basis(e0, e1, h1, h2, hc, tau, x0, v0, p, q, force, theta0, c, kappa, omega):
    """:func:`segment_state` from basis values already evaluated at τ.

    Slip pieces of one fixed length recur (a record's sample interval, a harmonic
    piece of 1/16 period): their basis is computed once and reused through this.
    """
    m = -0.5 * c
    x = e0 * x0 + e1 * (v0 - m * x0) + p * h1 + q * h2
    v = e0 * v0 + e1 * (m * v0 - kappa * x0 + p) + q * h1
    u = p + q * tau
    du = q
    if force != 0.0:
        phase = theta0 + omega * tau
        cos_phase = math.cos(phase)
        sin_phase = math.sin(phase)
        rot_hc = complex(cos_phase, sin_phase) * hc  # e^{i(θ0 + ωτ)} H1μ
        x += force * rot_hc.real
        v += force * (-omega * rot_hc.imag + math.cos(theta0) * e1)
        u += force * cos_phase
        du -= force * omega * sin_phase
    a = u - c * v - kappa * x
    jerk = du - c * a - kappa * v
    return x, v, a, jerk
