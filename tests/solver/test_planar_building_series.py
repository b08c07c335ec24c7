"""The 2-D building's sliding pieces: fewer per slide, the same answer (docs/building.md, "Fewer pieces per slide").

Two routes of the kernel, each against the route it replaces (the same answer to 1e-10, measured to ~1e-14) and
against independent truths:

* ``LEAVE_SERIES``: leaving rest with |D| > µk N (a break-away with µs > µk, a reversal at a stop) by the slow
  manifold's series written V = τ W(τ) (``_series_depart`` with lag 1), one piece per departure, instead of START
  (friction along D up to 1e-5 v_ref) and short series pieces in time;
* ``STOP_REACH_SERIES``: a slide's series piece slowing along its direction runs to e0·V = STOP_REACH r0 instead of
  to half its speed (its length held to (2 STOP_REACH)^(1/N) of the series' reach).
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.solver import planar_building
from isolator.solver import planar_building_kernel as kernel
from isolator.solver.building import simulate_building
from isolator.solver.planar_building import planar_building_system, simulate_planar_building
from isolator.superstructure import Floor, Superstructure

from .test_planar_building import BUILDING, CASES, G, make_superstructure, pair_segment
from .test_planar_building_stops import _assert_same_answer, _run_bench_pair, bench_pair  # noqa: F401 (fixture)


def _bench_pair_mu(case, mu_static):
    """The bench building on its pair with µs > µk (µk the bench's µ)."""
    return simulate_planar_building(case.acceleration_m_s2, case.acceleration_y_m_s2, case.dt_s,
                                    superstructure=case.superstructure, total_mass_kg=case.total_mass_kg,
                                    stiffness_N_per_m=case.isolator_stiffness_N_per_m, mu_static=mu_static,
                                    mu_kinetic=case.mu, gravity_m_s2=case.gravity_m_s2)


def test_the_stop_reach_gives_the_halving_answer_in_fewer_pieces(bench_pair, monkeypatch):  # noqa: F811
    """PTS 0-4 s, µs = µk: 4 stops.  The approach to a stop took ~28 pieces on the bench case, each cut at half the
    speed; with the reach the late ones (where V/|V|'s branch point at the stop is weak) go on to 1/64 of it."""
    new = _run_bench_pair(bench_pair)
    monkeypatch.setattr(planar_building, "STOP_REACH_SERIES", False)
    old = _run_bench_pair(bench_pair)
    assert new.message == old.message == "ok" and new.event_names == old.event_names
    assert np.count_nonzero(new.event_kind == 1) >= 2
    assert new.n_pieces_by_phase[2] < 0.75 * old.n_pieces_by_phase[2]  # sliding pieces (measured 105 against 184)
    _assert_same_answer(new, old)


def test_finite_acceleration_departures_take_one_piece_each(bench_pair, monkeypatch):  # noqa: F811
    """The bench building with µs = 0.072 > µk = 0.06 on PTS 0-4 s: every break-away leaves by one departure piece
    (V = τ W), none by START, and the answer is START's to 1e-10 (START's neglected lag is ∝ |V| below 1e-5 v_ref)."""
    new = _bench_pair_mu(bench_pair, 0.072)
    monkeypatch.setattr(planar_building, "LEAVE_SERIES", False)
    old = _bench_pair_mu(bench_pair, 0.072)
    assert new.message == old.message == "ok" and new.event_names == old.event_names
    breakaways = int(np.count_nonzero(new.event_kind == 0))
    assert breakaways >= 3
    assert new.n_pieces_by_phase[5] == breakaways and new.n_pieces_by_phase[1] == 0
    assert old.n_pieces_by_phase[5] == 0 and old.n_pieces_by_phase[1] >= breakaways
    assert new.n_pieces < 0.7 * old.n_pieces  # measured 50 against 107 (the reach on in both)
    _assert_same_answer(new, old)


def test_reversals_leave_by_the_series_and_equal_the_1d_building(records_dir, monkeypatch):
    """A pair with a zero second component is the 1-D building (an independent exact kernel).  With a stiff pendulum
    (R = 1 m) and µs = 0.03, µk = 0.02 the slab reverses 12 times at its stops (|D| > µs N there): each reversal and
    break-away leaves by one departure piece."""
    (acc_x, _), dt = pair_segment(records_dir, "superstitionhills1987_PTS", 5.0, 10.0, taper_s=0.0)
    design = dict(BUILDING, stiffness_N_per_m=1e6 * G / 1.0, mu_static=0.03, mu_kinetic=0.02)
    one = simulate_building(acc_x, dt, **design)
    two = simulate_planar_building(acc_x, np.zeros_like(acc_x), dt, **design)
    assert two.message == "ok"
    reversals = int(np.count_nonzero(two.event_kind == 2))
    breakaways = int(np.count_nonzero(two.event_kind == 0))
    assert reversals >= 10
    assert two.n_pieces_by_phase[5] == reversals + breakaways and two.n_pieces_by_phase[1] == 0
    assert two.event_names == one.event_names
    assert np.max(np.abs(two.event_time_s - one.event_time_s)) <= 1e-10
    scale = np.max(np.abs(one.displacement_m))
    assert np.max(np.abs(two.displacement_m[:, 0] - one.displacement_m)) <= 1e-10 * scale
    assert np.max(np.abs(two.displacement_m[:, 1])) == 0.0
    assert two.peak_displacement_m == pytest.approx(one.peak_displacement_m, rel=1e-10)
    assert two.energy_friction_J_per_kg == pytest.approx(one.energy_friction_J_per_kg, rel=1e-10)
    assert abs(two.energy_balance_error_J_per_kg) <= 1e-10 * two.energy_input_J_per_kg
    monkeypatch.setattr(planar_building, "LEAVE_SERIES", False)
    old = simulate_planar_building(acc_x, np.zeros_like(acc_x), dt, **design)
    assert old.n_pieces_by_phase[1] >= reversals
    _assert_same_answer(two, old)


def test_the_reference_cases_with_mu_s_above_mu_k_leave_rest_by_the_series(records_dir):
    """The real-pair cases of test_planar_building.py (against its independent solve_ivp reference, ≤ 1e-9) with
    µs > µk now leave rest by the departure series: that reference checks this route."""
    checked = 0
    for name, (pair, start, duration, scale, masses, kx, ky, zeta, total, spring, c_iso, mu_s, mu_k) in CASES.items():
        if mu_s == mu_k:
            continue
        (acc_x, acc_y), dt = pair_segment(records_dir, pair, start, duration, scale)
        k_iso = total * G / spring["radius_m"] if "radius_m" in spring else spring["stiffness_N_per_m"]
        ours = simulate_planar_building(acc_x, acc_y, dt, superstructure=make_superstructure(masses, kx, ky, zeta),
                                        total_mass_kg=total, stiffness_N_per_m=k_iso, mu_static=mu_s,
                                        mu_kinetic=mu_k, damping_Ns_per_m=c_iso)
        breakaways = int(np.count_nonzero(ours.event_kind == 0))
        assert breakaways >= 1 and ours.n_pieces_by_phase[5] == breakaways and ours.n_pieces_by_phase[1] == 0, name
        checked += 1
    assert checked >= 4


def _three_story_system():
    structure = Superstructure(floors=tuple(Floor(2e5, 3.2, k, 0.7 * k) for k in (6e8, 4e8, 2e8)), damping_ratio=0.05,
                               gravity_m_s2=9.81)
    system = planar_building_system(structure, total_mass_kg=9e5, stiffness_N_per_m=9e5 * 9.81 / 2.0, mu_static=0.06,
                                    mu_kinetic=0.05, damping_Ns_per_m=3e4)
    m = 2 * system.n_floors + 2
    rng = np.random.default_rng(11)
    w = np.zeros((2, m))
    w[:, 0] = (0.03, -0.02)
    w[:, 2:] = rng.normal(scale=1e-3, size=(2, m - 2))
    weights = np.ones(m)
    weights[0] = weights[2:2 + system.n_floors] = system.fastest_rate_per_s
    return system, w, weights


def _residual(system, zs, a0, b, tau, mu_k_n):
    """The largest residual of ż = A z + g a_g + p µk N V/|V| (V/|V| from the series' own V) at τ, per row scale."""
    m = zs.shape[2]
    z, zd, zdd = np.zeros((2, m)), np.zeros((2, m)), np.zeros((2, m))
    kernel._eval(zs, tau, z, zd, zdd)
    speed = np.hypot(z[0, 1], z[1, 1])
    worst = 0.0
    for d in range(2):
        rate = system.a_mat[1, d] @ z[d] + system.g_vec[1, d] * (a0[d] + b[d] * tau) + \
            system.p_vec[d] * mu_k_n * z[d, 1] / speed
        scale = np.abs(system.a_mat[1, d]) @ np.abs(z[d]) + np.abs(system.p_vec[d]) * mu_k_n
        worst = max(worst, abs(zd[d, 1] - rate[1]) / scale[1])
    return worst, z


def test_the_finite_acceleration_departure_solves_the_slabs_equation_and_fails_beyond_its_reach():
    """The departure series with lag 1 (V = τ W, |D| = 1.3 µk N at V = 0, D turning) satisfies the slab's equation
    with V/|V| from its own V to rounding over its piece (Jorba–Zou); taken 3× further it does not (the check can
    fail).  |D| below µk N is refused (the slab does not leave)."""
    system, w, weights = _three_story_system()
    mu_k_n = system.mu_kinetic * system.weight_N
    m_b = system.slab_mass_kg
    e = np.array([np.cos(0.6), np.sin(0.6)])
    a0 = np.array([(system.l_d[d] @ w[d] - 1.3 * mu_k_n * e[d]) / m_b for d in range(2)] + [0.0])  # |D| = 1.3 µk N
    b = np.append(-40.0 * e + 30.0 * np.array([-e[1], e[0]]), 0.0)  # D turning [m/s³]
    ns = kernel.N_ORDER + 3
    zs, fs = np.zeros((2, ns + 1, system.n_floors * 2 + 2)), np.zeros((2, ns))
    assert kernel._series_depart(w, a0, b, system.a_mat, system.g_vec, system.p_vec, mu_k_n, zs, fs,
                                 np.zeros((2, ns)), np.zeros(ns), 1e-2, 1)
    length = kernel._piece_limit(zs, weights, 1e-12)
    assert 1e-4 < length < 1e-1
    for fraction in (1e-3, 0.1, 0.5, 1.0):
        worst, z = _residual(system, zs, a0, b, fraction * length, mu_k_n)
        assert worst <= 1e-11, (fraction, worst)
    # leaving along D at the finite acceleration (|D| − µk N)/m_b
    assert z[0, 1] * e[0] + z[1, 1] * e[1] > 0.0
    worst, _ = _residual(system, zs, a0, b, 3.0 * length, mu_k_n)
    assert worst > 1e-9  # the series taken beyond its reach: not the solution (measured ~1e-6)
    a_low = np.array([(system.l_d[d] @ w[d] - 0.9 * mu_k_n * e[d]) / m_b for d in range(2)] + [0.0])
    assert not kernel._series_depart(w, a_low, b, system.a_mat, system.g_vec, system.p_vec, mu_k_n, zs, fs,
                                     np.zeros((2, ns)), np.zeros(ns), 1e-2, 1)


def slowing_series(speed, off_angle, d_ratio=0.8, h=None):
    """A slide slowing to a stop on the three-story system: |V| = speed, V off_angle [rad] off D, |D| = d_ratio µk N;
    its series in time as the kernel builds it (rescaled to its reach, from H = h or the time to the stop) and that
    reach: (system, zs, a0, b, µk N, e0, reach)."""
    system, w, weights = _three_story_system()
    mu_k_n = system.mu_kinetic * system.weight_N
    m_b = system.slab_mass_kg
    m = w.shape[1]
    e = np.array([np.cos(0.6), np.sin(0.6)])
    off = np.array([np.cos(0.6 + off_angle), np.sin(0.6 + off_angle)])
    w[:, 1] = speed * off
    a0 = np.array([(system.l_d[d] @ w[d] - d_ratio * mu_k_n * e[d]) / m_b for d in range(2)] + [0.0])
    b = np.zeros(3)
    ns = kernel.N_ORDER + 3
    zs, fs = np.zeros((2, ns + 1, m)), np.zeros((2, ns))
    scratch = [np.zeros((2, ns)), np.zeros(ns), np.zeros(ns), np.zeros((2, ns))]
    vz = np.zeros(kernel.VZ_SIZE)
    vz[kernel.V_NU0] = 1.0
    h = speed * m_b / ((1.0 - d_ratio) * mu_k_n) if h is None else h
    limit = 0.0
    for _ in range(8):
        kernel._series(kernel.SLIDE, w, a0, b, system.a_mat, system.g_vec, system.p_vec, system.l_d, m_b, mu_k_n,
                       off, zs, fs, *scratch, vz, np.zeros(ns), np.zeros(ns), h)
        limit = kernel._piece_limit(zs, weights, 1e-12)
        h_next = kernel._next_scale(limit, h, 1.0, 1.0)
        if h_next == 0.0:
            break
        h = h_next
    return system, zs, a0, b, mu_k_n, off, limit


def test_a_slide_piece_towards_a_stop_is_exact_up_to_its_reach_and_wrong_through_the_stop():
    """A slide slowing to a stop (|V| = 1e-6 m/s, |D| = 0.8 µk N, V 1e-9 rad off D): its series in time, cut where
    e0·V = STOP_REACH r0 and held to REACH_SHRINK of its reach, satisfies the slab's equation to rounding; run through
    the stop, V/|V| reverses while the series' analytic continuation does not (the residual is then ~2 µk N/m_b):
    why a slide's piece must end before its stop."""
    system, zs, a0, b, mu_k_n, off, limit = slowing_series(1e-6, 1e-9, h=1e-5)
    m = zs.shape[2]
    reach = (2.0 * kernel.STOP_REACH) ** (1.0 / kernel.N_ORDER) * limit
    # the time to the stop (e0·V = 0) and to the reach's end (e0·V = STOP_REACH r0), from the series
    taus = np.linspace(0.0, 4.0 * reach, 4001)
    z, zd, zdd = np.zeros((2, m)), np.zeros((2, m)), np.zeros((2, m))
    along = []
    for tau in taus:
        kernel._eval(zs, tau, z, zd, zdd)
        along.append(off @ z[:, 1])
    along = np.array(along)
    stop = taus[np.argmax(along <= 0.0)]
    assert stop > 0.0
    end = min(reach, taus[np.argmax(along <= kernel.STOP_REACH * 1e-6)])
    assert end > 0.5 * stop  # the piece goes beyond the halving
    for fraction in (1e-3, 0.3, 0.7, 1.0):
        worst, _ = _residual(system, zs, a0, b, fraction * end, mu_k_n)
        assert worst <= 1e-11, (fraction, worst)
    worst, _ = _residual(system, zs, a0, b, 1.2 * stop, mu_k_n)
    assert worst > 1e-2
