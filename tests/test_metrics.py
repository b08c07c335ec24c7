"""Classification: a sampled harmonic record is classified as the harmonic solver classifies it.

This ties the record generalisation to the paper.  The record is a sampled cosine
a_g = A0 Ω² cos(Ωt) (so PGV = A0 Ω and A0 = PGV²/PGA up to the O(dt²) trapezoid
error), 60 forcing periods long; the slip-time ratio is read over D5–95 (periods
3–57) and the amplitude over the last 10 periods, where the response is periodic.
The harmonic prediction is computed at the record's own equivalent point.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.adapter import adapt
from isolator.design import Design
from isolator.metrics import classify_harmonic, classify_record, compare, regime_from_slip
from isolator.motion import GroundMotion
from isolator.solver.harmonic import harmonic_response
from isolator.solver.record import simulate_record

G = 9.80665


def sampled_sine_case(alpha, k, eta, mu_s, mu_k=None, a0_m=0.05, periods=60, samples_per_period=100):
    mu_k = mu_s if mu_k is None else mu_k
    mass = 1000.0
    omega = math.sqrt(alpha * mu_s * G / a0_m)
    design = Design.from_mapping({"name": "sine", "mass_kg": mass, "stiffness_N_per_m": k * mass * G / a0_m,
                                  "damping_Ns_per_m": eta * mass / math.sqrt(a0_m / G),
                                  "mu_static": mu_s, "mu_kinetic": mu_k})
    period = 2 * math.pi / omega
    dt = period / samples_per_period
    t = np.arange(periods * samples_per_period + 1) * dt
    motion = GroundMotion.from_array(a0_m * omega ** 2 * np.cos(omega * t), dt)
    adaptation = adapt(design, motion)
    response = simulate_record(motion.acceleration_m_s2, dt, system=adaptation.system)
    record = classify_record(response, adaptation.point, amplitude_window_s=(t[-1] - 10 * period, t[-1]))
    p = adaptation.point
    harmonic = classify_harmonic(harmonic_response(p.alpha, p.k, p.eta, p.mu_s, p.mu_k))
    return record, harmonic


CASES = [
    # (alpha, k, eta, mu_s, mu_k), expected regime, expected amplified
    ((0.8, 0.0, 0.0, 0.25), "ST", False),
    ((1.2, 0.0, 0.0, 0.25), "SS", False),  # configuration 1, below α_SL = 1.862
    ((3.0, 0.0, 0.0, 0.25), "SL", False),
    ((1.5, 0.1, 0.05, 0.25), "SS", False),
    ((1.4, 0.0, 0.3, 0.25, 0.175), "SS", False),  # friction model 2 with a damper
    ((4.0, 1.0, 0.5, 0.25), "SL", True),  # Fig. 6 frame, near the resonance line: A > 1
    ((2.0, 0.05, 0.02, 0.06, 0.05), "SL", True),  # a real pendulum's corner
]


@pytest.mark.parametrize("case,regime,amplified", CASES)
def test_sampled_sine_classified_as_harmonic(case, regime, amplified):
    record, harmonic = sampled_sine_case(*case)
    assert harmonic.regime == regime and harmonic.amplified == amplified
    assert record.regime == harmonic.regime
    assert record.amplified == harmonic.amplified
    assert record.amplitude == pytest.approx(harmonic.amplitude, rel=2e-2, abs=1e-3)
    assert record.zeta == pytest.approx(harmonic.zeta, abs=2e-2)
    assert record.dominant_force == harmonic.dominant_force
    assert record.dominant_force_rho == harmonic.dominant_force_rho
    assert compare(record, harmonic) == []


def test_regime_rule():
    assert regime_from_slip(False, 0.0) == "ST"
    assert regime_from_slip(True, 0.4) == "SS"
    assert regime_from_slip(True, 1.0) == "SL"


def test_disagreements_are_named():
    record, harmonic = sampled_sine_case(3.0, 0.0, 0.0, 0.25)
    from dataclasses import replace

    other = replace(record, regime="SS", amplified=True, amplitude=1.5, dominant_force="elastic")
    notes = compare(other, harmonic)
    assert len(notes) == 3 and notes[0].startswith("regime")
