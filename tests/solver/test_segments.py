"""Closed-form slip segments against 50-digit arithmetic, in every damping regime.

The truth is mpmath at 50 digits: the textbook formulas (H1 = (1 - E0 + m E1)/κ and
its recursions, the φ-functions for κ = 0), whose cancellations cost nothing at that
precision, and direct quadrature where a formula divides by zero (exact resonance).
isolator switches between series, eigen and division forms in double precision.
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from isolator.solver.segments import harmonic_h1, ramp_basis, segment_state

mp.mp.dps = 50
CRITICAL = 2.0 * math.sqrt(4.9)

RAMP_CASES = [
    # (c, κ): friction only, damper only (weak, strong), spring only, 4a, 4b exactly and ± 1e-12,
    # vanishing k and η, strongly over-damped with tiny κ, very stiff
    (0.0, 0.0), (0.3, 0.0), (50.0, 0.0), (0.0, 4.9), (0.3, 4.9),
    (CRITICAL, 4.9), (CRITICAL * (1 + 1e-12), 4.9), (CRITICAL * (1 - 1e-12), 4.9),
    (1e-9, 1e-12), (1e3, 1e-6), (1e3, 1e5), (0.0, 1e6), (5.0, 1e6),
]


def _e0_e1(m, d2, tau):
    if d2 == 0:
        return mp.exp(m * tau), tau * mp.exp(m * tau)
    d = mp.sqrt(mp.mpc(d2))
    return mp.re(mp.exp(m * tau) * mp.cosh(d * tau)), mp.re(mp.exp(m * tau) * mp.sinh(d * tau) / d)


def _reference_basis(tau, c, kappa):
    tau, c, kappa = mp.mpf(tau), mp.mpf(c), mp.mpf(kappa)
    m = -c / 2
    e0, e1 = _e0_e1(m, c * c / 4 - kappa, tau)
    if kappa != 0:
        h1 = (1 - e0 + m * e1) / kappa
        h2 = (tau - e1 - c * h1) / kappa
        h3 = (tau ** 2 / 2 - h1 - c * h2) / kappa
    elif c != 0:
        # κ = 0: E1 = (1 - e^{-cτ})/c, then integrate term by term
        h1 = (tau - (1 - mp.exp(-c * tau)) / c) / c
        h2 = (tau ** 2 / 2 - h1) / c
        h3 = (tau ** 3 / 6 - h2) / c
    else:
        h1, h2, h3 = tau ** 2 / 2, tau ** 3 / 6, tau ** 4 / 24
    return [e0, e1, h1, h2, h3]


@pytest.mark.parametrize("tau", [1e-3, 0.02, 0.3, 2.0, 10.0])
@pytest.mark.parametrize("c,kappa", RAMP_CASES)
def test_ramp_basis_matches_high_precision_quadrature(tau, c, kappa):
    got = ramp_basis(tau, c, kappa)
    want = _reference_basis(tau, c, kappa)
    for name, g, w in zip(("E0", "E1", "H1", "H2", "H3"), got, want, strict=False):
        w = float(w)
        assert math.isfinite(g)
        assert abs(g - w) <= 1e-11 * abs(w) + 1e-300, (name, g, w)


HARMONIC_CASES = [
    # (c, κ, ω): exact resonance, near resonance, damped, over-damped, config 1 and 2,
    # critical ± 1e-12, vanishing k and η, a super-harmonic resonance
    (0.0, 1.0, 1.0), (0.0, 1.0, 1.0 + 1e-9), (0.5, 1.0, 1.0), (0.5, 0.0625, 0.7), (0.0, 0.0, 0.6),
    (0.3, 0.0, 0.6), (1e-9, 1e-12, 0.5), (2.0, 1.0, 0.5), (2.0 * (1 + 1e-12), 1.0, 0.5),
    (0.0, 6.0, math.sqrt(6.0)), (10.0, 1.0, 0.5), (0.0, 4.5, 0.75),
]


@pytest.mark.parametrize("tau", [0.01, 0.5, 3.0, 20.0])
@pytest.mark.parametrize("c,kappa,omega", HARMONIC_CASES)
def test_harmonic_particular_integral_matches_quadrature(tau, c, kappa, omega):
    m = -mp.mpf(c) / 2
    d2 = mp.mpf(c) ** 2 / 4 - kappa
    mu = m - 1j * mp.mpf(omega)
    kappa_mu = mu * mu - d2  # the shifted system: zero at exact resonance
    if abs(kappa_mu) > mp.mpf("1e-30"):
        d = mp.sqrt(mp.mpc(d2))
        if d2 == 0:
            e0, e1 = mp.exp(mu * tau), tau * mp.exp(mu * tau)
        else:
            e0, e1 = mp.exp(mu * tau) * mp.cosh(d * tau), mp.exp(mu * tau) * mp.sinh(d * tau) / d
        want = complex((1 - e0 + mu * e1) / kappa_mu)
    else:
        d = mp.sqrt(mp.mpc(d2))
        want = complex(mp.quad(lambda u: mp.exp(mu * u) * mp.sinh(d * u) / d, mp.linspace(0, tau, 8)))
    got = harmonic_h1(tau, c, kappa, omega)
    assert abs(got - want) <= 1e-11 * abs(want)


def test_exact_resonance_has_the_secular_term():
    # c = 0, κ = ω²: the response from rest to cos(ωτ) is τ sin(ωτ)/(2ω)
    omega = 1.3
    for tau in (0.1, 5.0, 400.0):
        x, v, _, _ = segment_state(tau, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, omega ** 2, omega)
        assert x == pytest.approx(tau * math.sin(omega * tau) / (2 * omega), rel=1e-10, abs=1e-13)


@pytest.mark.parametrize("c,kappa", RAMP_CASES)
@pytest.mark.parametrize("force", [0.0, -0.7])
def test_segments_compose(c, kappa, force):
    """Going τ1 then τ2 (with the forcing shifted) equals going τ1 + τ2 at once."""
    omega = 0.9
    x0, v0, p, q, theta0 = 0.01, -0.3, 0.4, -2.0, 0.3
    tau1, tau2 = 0.013, 0.029
    if force != 0.0:
        q = 0.0
    x_once, v_once, _, _ = segment_state(tau1 + tau2, x0, v0, p, q, force, theta0, c, kappa, omega)
    x1, v1, _, _ = segment_state(tau1, x0, v0, p, q, force, theta0, c, kappa, omega)
    x2, v2, _, _ = segment_state(tau2, x1, v1, p + q * tau1, q, force, theta0 + omega * tau1, c, kappa, omega)
    scale = 1.0 + abs(x_once)
    assert abs(x2 - x_once) <= 1e-13 * scale
    assert abs(v2 - v_once) <= 1e-12 * (1.0 + abs(v_once))


def test_no_overflow_in_long_segments():
    # local time keeps every exponent bounded; a very long, heavily damped segment stays finite
    for c, kappa in [(50.0, 0.0), (1e3, 1e5), (0.3, 4.9)]:
        values = ramp_basis(1e4, c, kappa)
        assert all(np.isfinite(values))
