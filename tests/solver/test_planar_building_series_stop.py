"""The 2-D building's stop in one piece (``STOP_PIECE``; docs/building.md, "The stop in one piece").

A slide's series piece slowing along its direction ran to e0·V = STOP_REACH r0, and below 1e-10 v_ref a FINISH
piece (the friction frozen along e0) ended at the stop: 3–4 pieces per stop below ~1e-7 m/s.  Now, when the stop
(e0·V = 0) lies within the piece's reach (held to REACH_SHRINK of it, as before), the piece ends at the stop itself,
located on its own series (the friction V/|V| of the series' V up to there), if the speed left there is below
FINISH's entry speed.  Checked against the route it replaces (1e-10), the 1-D building (an independent exact kernel)
and on the series itself: the slab's equation holds to rounding up to the stop, and the series taken past the stop
is not the solution.  Against the independent solve_ivp reference: test_planar_building.py's real pairs (the cases
that stop, to 1e-10, with their stop pieces; that test ran here too, on a second run of the same references, 21.6 s
of 1 min at load 8, until h145).
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.solver import planar_building
from isolator.solver import planar_building_kernel as kernel
from isolator.solver.building import simulate_building
from isolator.solver.planar_building import simulate_planar_building
from isolator.superstructure import BearingLayout

from .test_planar_building import BUILDING, G, make_superstructure, pair_segment
from .test_planar_building_series import _bench_pair_mu, _residual, slowing_series
from .test_planar_building_stops import _assert_same_answer, _run_bench_pair, bench_pair  # noqa: F401 (fixture)


def _stops(r):
    """Stops that end a slide: sticks (1) and reversals (2)."""
    return int(np.count_nonzero((r.event_kind == 1) | (r.event_kind == 2)))


def test_the_stop_piece_gives_the_finish_answer_with_one_piece_less_per_stop(bench_pair, monkeypatch):  # noqa: F811
    """PTS 0-4 s, µs = µk: every stop is reached by the slowing piece itself, no FINISH piece is left, and the answer
    is the FINISH route's to 1e-10 (measured on PTS 0-20 s: events 3.6e-15 s, histories 2.2e-14 of their peaks)."""
    new = _run_bench_pair(bench_pair)
    monkeypatch.setattr(planar_building, "STOP_PIECE", False)
    old = _run_bench_pair(bench_pair)
    assert new.message == old.message == "ok" and new.event_names == old.event_names
    stops = _stops(new)
    assert stops >= 2
    assert new.n_stop_pieces == stops and old.n_stop_pieces == 0
    assert new.n_pieces_by_phase[3] == 0 and old.n_pieces_by_phase[3] == stops  # FINISH pieces
    assert new.n_pieces <= old.n_pieces - 2 * stops
    _assert_same_answer(new, old)
    assert abs(new.energy_balance_error_J_per_kg) <= 1e-13 * new.energy_input_J_per_kg


def test_mu_s_above_mu_k_and_a_dashpot_with_bearings(records_dir, bench_pair, monkeypatch):  # noqa: F811
    """The bench building with µs = 0.072 > µk = 0.06 (PTS 0-4 s), and 3 stories with a dashpot and five bearings on
    Hector Mine ABY 0-12 s: the stop pieces are taken and give the old route's answer, bearing loads included."""
    (acc_x, acc_y), dt = pair_segment(records_dir, "hectormine1999_ABY", 0.0, 12.0, taper_s=0.0)
    layout = BearingLayout(x_m=(-6.0, 6.0, -6.0, 6.0, 0.0), y_m=(-5.0, -5.0, 5.0, 5.0, 0.0),
                           gravity_loads_N=(2e6, 2e6, 2e6, 2e6, 4.3e6))
    structure = make_superstructure([3e5, 3e5, 3e5], [8e8, 6e8, 4e8], [6.4e8, 4.8e8, 3.2e8], 0.05)
    total = 1.4 * 9e5

    def aby():
        return simulate_planar_building(acc_x, acc_y, dt, superstructure=structure, total_mass_kg=total,
                                        stiffness_N_per_m=total * G / 2.5, mu_static=0.05, mu_kinetic=0.04,
                                        damping_Ns_per_m=3e5, bearing_layout=layout)

    new_runs = (_bench_pair_mu(bench_pair, 0.072), aby())
    monkeypatch.setattr(planar_building, "STOP_PIECE", False)
    old_runs = (_bench_pair_mu(bench_pair, 0.072), aby())
    for new, old in zip(new_runs, old_runs, strict=True):
        assert new.message == old.message == "ok" and new.event_names == old.event_names
        assert new.n_stop_pieces >= 2 and new.n_pieces < old.n_pieces
        _assert_same_answer(new, old)
    new, old = new_runs[1], old_runs[1]
    # the overturning moments and the bearings' exact load extremes (watched between samples)
    scale = np.max(np.abs(old.overturning_moment_Nm))
    assert np.max(np.abs(new.overturning_moment_Nm - old.overturning_moment_Nm)) <= 1e-10 * scale
    for a, b in ((new.signed_max, old.signed_max), (new.signed_min, old.signed_min)):
        assert np.max(np.abs(a - b)) <= 1e-10 * np.max(np.abs(b))


def test_a_zero_second_component_stops_in_one_piece_as_the_1d_building(records_dir):
    """A pair with a zero second component is the 1-D building (an independent exact kernel): its slides stop in the
    slowing piece itself (V/|V| is constant, the series reaches far), with the 1-D building's events and history."""
    (acc_x, _), dt = pair_segment(records_dir, "superstitionhills1987_PTS", 5.0, 10.0, taper_s=0.0)
    design = dict(BUILDING, stiffness_N_per_m=1e6 * G / 2.5, mu_static=0.04, mu_kinetic=0.03)
    one = simulate_building(acc_x, dt, **design)
    two = simulate_planar_building(acc_x, np.zeros_like(acc_x), dt, **design)
    assert two.message == "ok" and two.event_names == one.event_names
    assert two.n_stop_pieces >= 3 and two.n_stop_pieces == _stops(two) and two.n_pieces_by_phase[3] == 0
    assert np.max(np.abs(two.event_time_s - one.event_time_s)) <= 1e-10
    scale = np.max(np.abs(one.displacement_m))
    assert np.max(np.abs(two.displacement_m[:, 0] - one.displacement_m)) <= 1e-10 * scale
    assert np.max(np.abs(two.velocity_m_s[:, 0] - one.velocity_m_s)) <= 1e-10 * np.max(np.abs(one.velocity_m_s))
    assert two.peak_displacement_m == pytest.approx(one.peak_displacement_m, rel=1e-10)
    assert two.energy_friction_J_per_kg == pytest.approx(one.energy_friction_J_per_kg, rel=1e-10)


def _stop_on_series(zs, off, hi):
    """The root of e0·V on the series in [0, hi] (bisection to the last bit) and V there."""
    m = zs.shape[2]
    z, zd, zdd = np.zeros((2, m)), np.zeros((2, m)), np.zeros((2, m))

    def along(tau):
        kernel._eval(zs, tau, z, zd, zdd)
        return off @ z[:, 1]

    lo = 0.0
    assert along(lo) > 0.0 and along(hi) < 0.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        lo, hi = (mid, hi) if along(mid) > 0.0 else (lo, mid)
    along(lo)
    return lo, z[:, 1].copy()


def test_the_last_piece_reaches_the_stop_exactly_and_is_wrong_past_it():
    """At |V| = 1e-9 m/s, V 1e-12 rad off D, |D| = 0.8 µk N: the stop (e0·V = 0) lies within the piece's reach held
    to REACH_SHRINK, the slab's equation holds to rounding up to it with V/|V| from the series' own V, the speed left
    there is far below FINISH's 1e-10 v_ref, and the time to it is the deceleration's s m_b/((1 − 0.8) µk N) to
    first order.  Past the stop the series keeps the friction's direction while V/|V| reverses: the residual is then
    ~µk N/m_b, so a piece must end at its stop.  At 1e-4 m/s, 0.3 rad off D with |D| = 0.2 µk N (the direction still
    turning) the stop is beyond the reach and the route is not taken there."""
    speed = 1e-9
    system, zs, a0, b, mu_k_n, off, limit = slowing_series(speed, 1e-12)
    reach = (2.0 * kernel.STOP_REACH) ** (1.0 / kernel.N_ORDER) * limit
    stop, v_stop = _stop_on_series(zs, off, reach)
    assert stop < reach
    decel = (1.0 - 0.8) * mu_k_n / system.slab_mass_kg
    assert stop == pytest.approx(speed / decel, rel=1e-3)
    assert np.hypot(*v_stop) <= 1e-6 * speed
    for fraction in (1e-3, 0.5, 0.9, 0.999, 1.0 - 1e-6):  # at the stop itself V/|V| is rounding
        worst, _ = _residual(system, zs, a0, b, fraction * stop, mu_k_n)
        assert worst <= 1e-11, (fraction, worst)
    worst, _ = _residual(system, zs, a0, b, 1.05 * stop, mu_k_n)
    assert worst > 1e-2
    # the direction still turning strongly (V 0.3 rad off D, |D| = 0.2 µk N: the transient ∝ u^β, β = 0.25): the stop
    # lies beyond the reach and the slowing piece ends at STOP_REACH r0 as before (measured 0.29 of the time to it)
    system, zs, a0, b, mu_k_n, off, limit = slowing_series(1e-4, 0.3, d_ratio=0.2)
    reach = (2.0 * kernel.STOP_REACH) ** (1.0 / kernel.N_ORDER) * limit
    assert reach < 0.5 * 1e-4 * system.slab_mass_kg / ((1.0 - 0.2) * mu_k_n)
