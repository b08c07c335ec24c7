"""The 1-D µ(v) multi-surface model (1d-multisurface+mu(v)) against the 2-D one (2d-multisurface+mu(v)) with a
zero second component: one motion, so the same regimes entered at the same instants and the same history.

The truth of the rim pulse's "V (one inner)": in regime V (surfaces 1 and 4 on their rims) the two equal inner
surfaces share the velocity by µ(v_2) − µ(v_3) = (b_2 − b_3) (equal radii and laws), so d = b_2 − b_3 decays
monotonically (ḋ ∝ −(v_2 − v_3), of d's sign) and cannot reach 0 in finite time (d ≡ 0 is a solution): both inner
sliders slide until the first of them reaches its rim, at the ultimate (0.73381 s), where the other one, d ~ 1e-13
behind, arrives in the same instant to rounding.  "V (one inner)" is entered there, not before.  Base 4412bf7: the
1-D kernel booked a stop and a restart of the pivot surface at 0.71735 s (its rate, the rest of the velocity, crossed
0 for one 6.5e-12 s step where the split had relaxed to rounding), 0.0164 s early (h177).
"""

from __future__ import annotations

import numpy as np

from isolator.solver.multisurface_rate import simulate_bearing_rate
from isolator.solver.multisurface_rate_kernel import ULTIMATE
from isolator.solver.planar_multisurface_rate import simulate_bearing_pair_rate
from tests.solver.test_planar_multisurface_rate import TFP, G, read_pair


def both(acc, dt):
    one = simulate_bearing_rate(acc, dt, bearing=TFP)
    two = simulate_bearing_pair_rate(acc, np.zeros_like(acc), dt, bearing=TFP)
    return one, two


def test_one_inner_after_the_rims_is_entered_at_the_ultimate_in_both_models():
    """The hostile rim pulse (0.7 g, regimes I–V, the ultimate): measured (h177, 08:56 UTC) every regime time within
    4.0e-15 s, "V (one inner)" 0.7338075738939254 / …247 s, the history 2.2e-15 of the peak; base: 0.7174 s in 1-D."""
    t = np.arange(0.0, 0.8, 0.02)
    one, two = both(0.7 * G * np.sin(2 * np.pi * t / 2.0), 0.02)
    assert list(one.regimes) == list(two.regimes) == ["I", "II", "III", "IV", "V", "V (one inner)"]
    for name in one.regimes:
        assert abs(one.regimes[name] - two.regimes[name]) <= 1e-12, name
    for res in (one, two):
        ultimate = res.event_time_s[np.asarray(res.event_kind) == ULTIMATE]
        assert ultimate.size >= 1 and abs(res.regimes["V (one inner)"] - ultimate[0]) <= 1e-12
    assert np.max(np.abs(two.displacement_m[:, 0] - one.displacement_m)) <= 1e-12 * one.peak_displacement_m
    assert np.max(np.abs(two.velocity_m_s[:, 0] - one.velocity_m_s)) <= 1e-12 * one.peak_velocity_m_s
    assert one.n_rim_contacts == two.n_rim_contacts == 4


def test_pulse_regimes_and_history_agree():
    """The 0.25 g pulse (I, II, III, III (one inner)): measured (h177) regime times within 7.0e-13 s (the inner stop
    located by the rate in 1-D, by |f| = µ_slow in 2-D, on different steps), history 2.0e-15 of the peak."""
    t = np.arange(0.0, 1.0, 0.02)
    one, two = both(0.25 * G * np.sin(2 * np.pi * t / 2.0), 0.02)
    assert list(one.regimes) == list(two.regimes) == ["I", "II", "III", "III (one inner)"]
    for name in one.regimes:
        assert abs(one.regimes[name] - two.regimes[name]) <= 1e-11, name
    assert np.max(np.abs(two.displacement_m[:, 0] - one.displacement_m)) <= 1e-12 * one.peak_displacement_m


def test_a_real_record_regimes_and_history_agree(records_dir):
    """Superstition Hills PTS225 (first 5.5 s, 30 events, I … III (one inner), inner sliders stopping one at a time):
    measured (h177) regime times within 1.5e-11 s, history 5.7e-11 of the peak (each kernel's own step sequence at
    step_tol 1e-11: agreement to the tolerance, not to rounding).  Asserted ≤ 1e-9."""
    ax, _, dt = read_pair(records_dir, 5.5)
    one, two = both(ax, dt)
    assert list(one.regimes) == list(two.regimes) and len(one.regimes) >= 5 and one.n_events >= 20
    for name in one.regimes:
        assert abs(one.regimes[name] - two.regimes[name]) <= 1e-9, name
    assert np.max(np.abs(two.displacement_m[:, 0] - one.displacement_m)) <= 1e-9 * one.peak_displacement_m
