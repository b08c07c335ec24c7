"""The harmonic driver against the paper (Nicolas 2017): closed forms, figures, energy."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from isolator.solver.harmonic import alpha_sl_friction_only, force_ratios, harmonic_response
from isolator.solver.thresholds import harmonic_thresholds
from tests.reference import reference_harmonic

MU = 0.25  # µs of the paper's figures


@pytest.mark.parametrize("mu_k, expected", [(MU, 1.862), (0.7 * MU, 1.486)])
def test_alpha_sl_of_configuration_1_is_found_by_the_solver(mu_k, expected):
    """Eq. 15: α_SL = sqrt(1 + π²/4 (µk/µs)²), found by scanning and bisecting regimes."""
    found = harmonic_thresholds(0.0, 0.0, MU, mu_k, alpha_max=3.0, n_grid=40).alpha_sl
    assert found == pytest.approx(alpha_sl_friction_only(MU, mu_k), rel=1e-7)
    assert round(found, 3) == expected


def test_zeta_at_alpha_1_2_matches_the_paper_and_eq_14():
    """Fig. 2a: ζ = 0.57 at α = 1.2, model 1; and Eqs. 13–14 solved independently."""
    alpha = 1.2
    r = harmonic_response(alpha, 0.0, 0.0, MU)
    assert r.regime == "SS" and r.steady
    assert r.zeta == pytest.approx(0.57, abs=0.005)
    omega = math.sqrt(alpha * MU)
    phi = math.pi / 2
    # forward slip starts where the ground acceleration -ω² sin(ωt) reaches -µs (Eq. 13)
    # and stops where Eq. 14 holds (it is -v(t_f) for the forward slip)
    t0 = math.asin(1 / alpha) / omega
    eq14 = lambda tf: MU * (tf - t0) + omega * (math.sin(omega * tf + phi) - math.sin(omega * t0 + phi))  # noqa: E731
    tf = brentq(eq14, t0 + 1e-3 / omega, t0 + math.pi / omega)
    assert r.zeta == pytest.approx(2 * (tf - t0) * omega / (2 * math.pi), rel=1e-10)


def test_no_motion_below_alpha_1():
    for k, eta in [(0.0, 0.0), (1.0, 0.5)]:
        r = harmonic_response(0.999, k, eta, MU)
        assert r.regime == "ST" and r.amplitude == 0.0 and r.zeta == 0.0 and r.event_time.size == 0


def test_barely_sliding_just_above_alpha_1():
    r = harmonic_response(1.0 + 1e-9, 4.5, 0.0, MU)
    assert r.steady and r.regime == "SS" and 0.0 < r.amplitude < 1e-12


def test_amplitude_tends_to_one_for_large_alpha():
    """Fig. 2f: with friction only, A grows with α towards 1."""
    amplitudes = [harmonic_response(a, 0.0, 0.0, MU).amplitude for a in (1.5, 3.0, 10.0, 50.0)]
    assert all(np.diff(amplitudes) > 0)
    assert amplitudes[-1] == pytest.approx(1.0, abs=0.01)


@pytest.mark.parametrize("k", [0.5, 1.0, 4.0])
def test_resonance_of_configuration_3_grows_linearly_at_the_closed_form_rate(k):
    """k_r = α µs (Eq. 25): permanent slip with A = β t (Eq. 26), β = (k − 4µk/π)/(2√k)."""
    r = harmonic_response(k / MU, k, 0.0, MU)
    assert not r.steady and r.status == "resonant growth" and r.regime == "SL"
    assert r.growth_rate == pytest.approx((k - 4 * MU / math.pi) / (2 * math.sqrt(k)), rel=1e-6)


def test_super_harmonic_windows_give_a_ss_sl_ss_sl_sequence():
    """Sec. 3.3: for 4.1 < k < 5.3 (model 1) increasing α gives SS/SL/SS/SL."""
    result = harmonic_thresholds(4.5, 0.0, MU, alpha_max=6.0)
    sequence = [tr["to"] for tr in result.transitions]
    assert sequence[:4] == ["SS", "SL", "SS", "SL"]
    assert result.alpha_sl == pytest.approx(result.transitions[3]["alpha"])


CASES = [  # (α, k, η, µk): every configuration, both friction models
    (1.2, 0.0, 0.0, MU), (2.0, 0.0, 0.0, 0.7 * MU), (2.5, 0.0, 0.5, MU), (1.5, 0.3, 0.0, MU),
    (3.0, 1.0, 0.25, MU), (2.0, 0.25, 1.0, 0.7 * MU), (2.5, 1.0, 2.0, MU), (4.0, 0.5, 3.0, MU),
]


@pytest.mark.parametrize("alpha, k, eta, mu_k", CASES)
def test_steady_cycle_agrees_with_the_reference_and_balances_energy(alpha, k, eta, mu_k):
    r = harmonic_response(alpha, k, eta, MU, mu_k)
    assert r.steady
    # Eq. 8 over the steady cycle; Eq. 9: ∆e_f = 4 µk A for a period-1 cycle with two reversals of motion
    assert abs(r.energy_balance_residual) <= 1e-9 * r.energy_friction
    if r.cycle_periods == 1:
        assert r.energy_friction == pytest.approx(4 * mu_k * r.amplitude, rel=1e-9)
    assert r.energy_viscous == pytest.approx(eta * (2 * math.pi / r.omega) * r.xdot_rms ** 2, rel=1e-12)
    period = 2 * math.pi / r.omega
    t_end = r.periods_run * period
    t_start = t_end - r.cycle_periods * period
    ref = reference_harmonic(alpha, k, eta, MU, mu_k, t_end=t_end, t_out=t_start + r.cycle_time)
    assert np.max(np.abs(ref["x"] - r.cycle_x)) <= 1e-9 * max(r.amplitude, 1e-3)
    assert np.max(np.abs(ref["xdot"] - r.cycle_xdot)) <= 1e-9 * max(r.amplitude * r.omega, 1e-3)


@pytest.mark.parametrize("alpha, k, eta, mu_k", CASES[2:5])
def test_mirrored_ground_motion_mirrors_the_response(alpha, k, eta, mu_k):
    up = harmonic_response(alpha, k, eta, MU, mu_k)
    down = harmonic_response(alpha, k, eta, MU, mu_k, phase=math.pi / 2 + math.pi)
    assert down.amplitude == pytest.approx(up.amplitude, rel=1e-9)
    assert down.zeta == pytest.approx(up.zeta, rel=1e-9)
    assert down.regime == up.regime


def test_force_ratios_and_triple_point():
    """Eq. 5, and the triple point k̂ = η sqrt(α̂ µs) where all three forces are equal."""
    eta, alpha = 0.5, 2.0
    k_hat = eta * math.sqrt(alpha * MU)
    amplitude = MU / k_hat  # makes k A = µk
    rho_ev, rho_vf, rho_ef, _ = force_ratios(k_hat, eta, alpha, MU, MU, amplitude)
    assert (rho_ev, rho_vf, rho_ef) == pytest.approx((1.0, 1.0, 1.0), rel=1e-12)
    assert force_ratios(1.0, 0.0, 2.0, MU, MU, 0.3)[0] is None  # η = 0: elastic/viscous is infinite
    assert force_ratios(0.0, 0.0, 2.0, MU, MU, 0.3)[3] == "friction"


def test_thresholds_refuse_bad_parameters():
    from isolator.solver.system import InvalidSystemError

    with pytest.raises(InvalidSystemError, match="mu_k"):
        harmonic_response(2.0, 0.0, 0.0, MU, 0.3)
    with pytest.raises(InvalidSystemError, match="alpha_max"):
        harmonic_thresholds(0.0, 0.0, MU, alpha_max=0.5)
