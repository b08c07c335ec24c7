"""The 2-D building's stops: the isolator force never exceeds what the spring and the static friction can give.

A physical bound, independent of the solver: the isolator force on the slab is the spring's −K X plus the
friction, whose magnitude is µk N while sliding and at most µs N while stuck (no dashpot here), so at every
instant |F_iso| ≤ K |X| + µs N and its peak over time ≤ K max|X| + µs N.  A stop that the kernel failed to declare
(the slab left sliding at |V| ~ 1e-16 m/s, where V/|V| is rounding and the series' derivatives are noise) broke
it: the example building under Hector Mine ABY × 1.568 read 0.142 W against 0.072 W (docs/building.md).  Here on
every pair of the example suite (isolator/data/suites/example, in the repository), whole records, two friction
bounds, each with many stops.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from isolator.design import Design
from isolator.solver.planar_building import simulate_planar_building

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "data" / "example_building.toml"
SUITE = ROOT / "isolator" / "data" / "suites" / "example" / "suite.toml"
#: the example's µs/µk at nominal and at about its upper bound (λ_max ≈ 1.48)
FRICTION = ((0.06, 0.05), (0.089, 0.074))
#: every pair scaled to this peak ground acceleration [m/s²]: the slab slides and stops many times
PGA_M_S2 = 6.0


@pytest.fixture(scope="module")
def building():
    return Design.from_toml(EXAMPLE)


@pytest.fixture(scope="module")
def pairs():
    from isolator.review import load_suite

    return load_suite(SUITE).pairs


@pytest.mark.parametrize("index", range(8))
def test_the_isolator_force_stays_within_the_spring_and_the_static_friction(building, pairs, index):
    pair = pairs[index]
    factor = PGA_M_S2 / pair.pga_m_s2
    weight = building.mass_kg * building.gravity_m_s2
    stiffness = weight / building.radius_m
    for mu_s, mu_k in FRICTION:
        r = simulate_planar_building(factor * pair.ax_m_s2, factor * pair.ay_m_s2, pair.dt_s,
                                     superstructure=building.superstructure, total_mass_kg=building.mass_kg,
                                     stiffness_N_per_m=stiffness, mu_static=mu_s, mu_kinetic=mu_k,
                                     gravity_m_s2=building.gravity_m_s2)
        assert r.message == "ok"
        assert np.count_nonzero(r.event_kind == 1) >= 1  # a stop that sticks: the case under test
        # at every sample ...
        bound = stiffness * np.hypot(*r.displacement_m.T) + mu_s * weight
        assert np.all(np.hypot(*r.isolator_force_N.T) <= bound * (1 + 1e-9) + 1e-9 * weight)
        # ... and the exact peak located between samples
        assert r.base_shear_coefficient <= (r.peak_displacement_m / building.radius_m + mu_s) * (1 + 1e-9), \
            (pair.name, mu_s, r.base_shear_coefficient, r.peak_displacement_m / building.radius_m + mu_s)


@pytest.fixture(scope="module")
def bench_pair(records_dir):
    """The bench's 2-D building (5 floors, T1 = 0.5/0.4 s, R = 2.5 m, µ = 0.06) under PTS 0-4 s: 6 events, 2 stops."""
    from isolator.bench.building import BUILDING_PAIR, FIXED_BASE_PERIOD_Y_S, building_case
    from isolator.motion import read_ground_motion

    _, folder, fx, fy = BUILDING_PAIR
    mx, my = (read_ground_motion(records_dir / folder / f) for f in (fx, fy))
    keep = round(4.0 / mx.dt_s) + 1
    return building_case("PTS 0-4 s", mx.acceleration_m_s2[:keep], mx.dt_s,
                         acceleration_y_m_s2=my.acceleration_m_s2[:keep], period_y_s=FIXED_BASE_PERIOD_Y_S)


def _run_bench_pair(case):
    return simulate_planar_building(case.acceleration_m_s2, case.acceleration_y_m_s2, case.dt_s,
                                    superstructure=case.superstructure, total_mass_kg=case.total_mass_kg,
                                    stiffness_N_per_m=case.isolator_stiffness_N_per_m, mu_static=case.mu,
                                    mu_kinetic=case.mu, gravity_m_s2=case.gravity_m_s2)


def _assert_same_answer(other, base):
    """Two runs of one building on one pair agree to 1e-10: event times, histories, peaks, drift, energies."""
    assert np.max(np.abs(other.event_time_s - base.event_time_s)) <= 1e-10
    for a, b in ((other.displacement_m, base.displacement_m), (other.velocity_m_s, base.velocity_m_s),
                 (other.floor_displacement_m, base.floor_displacement_m)):
        assert np.max(np.abs(a - b)) <= 1e-10 * np.max(np.abs(b))
    assert other.peak_displacement_m == pytest.approx(base.peak_displacement_m, rel=1e-10)
    assert other.story_drift_m == pytest.approx(base.story_drift_m, rel=1e-10)
    assert other.energy_friction_J_per_kg == pytest.approx(base.energy_friction_J_per_kg, rel=1e-10)
    assert abs(other.energy_balance_error_J_per_kg) <= 1e-10 * other.energy_input_J_per_kg


@pytest.mark.parametrize("order", (12, 30))
def test_the_series_order_changes_nothing_but_the_pieces(bench_pair, monkeypatch, order):
    """Every series piece is exact to rounding whatever its Taylor order, so two orders give one answer.

    Order 30 once turned this run into NaN at its first stop: V/|V|'s coefficients in τ grow as u^{−k} (u the time
    left to the stop, ~1e-10 s at |V| ~ 1e-11 m/s) and overflowed; they are now in x = τ/H with H of the piece's
    length."""
    from isolator.solver import planar_building_kernel

    base = _run_bench_pair(bench_pair)
    monkeypatch.setattr(planar_building_kernel, "N_ORDER", order)
    other = _run_bench_pair(bench_pair)
    assert base.message == other.message == "ok"
    assert np.count_nonzero(base.event_kind == 1) >= 2 and other.event_names == base.event_names
    assert other.n_pieces != base.n_pieces  # the order was taken
    _assert_same_answer(other, base)


def test_an_order_outside_the_tested_range_is_refused(bench_pair, monkeypatch):
    from isolator.solver import planar_building_kernel

    monkeypatch.setattr(planar_building_kernel, "N_ORDER", 2)
    with pytest.raises(ValueError, match="N_ORDER"):
        _run_bench_pair(bench_pair)


def test_the_approach_in_ln_s_gives_the_time_series_answer(bench_pair, monkeypatch):
    """The APPROACH phase (series in ln s, off by default: not faster yet) against the series in time."""
    from isolator.solver import planar_building

    base = _run_bench_pair(bench_pair)
    monkeypatch.setattr(planar_building, "STOP_APPROACH", True)
    other = _run_bench_pair(bench_pair)
    assert other.message == "ok" and other.n_pieces_by_phase[4] > 0 and base.n_pieces_by_phase[4] == 0
    assert other.event_names == base.event_names
    _assert_same_answer(other, base)


def test_the_departure_series_gives_the_start_answer_in_a_quarter_of_the_pieces(bench_pair, monkeypatch):
    """Departures from rest with µs = µk by the slow manifold's series (DEPARTURE_SERIES, on by default) against
    START (friction along D up to 1e-5 v_ref, its lag ∝ |V| neglected) and stiff series pieces in time.

    The old route's own error is its lag (~1e-11 of the histories), so the two agree to 1e-10, not to rounding."""
    from isolator.solver import planar_building

    new = _run_bench_pair(bench_pair)
    monkeypatch.setattr(planar_building, "DEPARTURE_SERIES", False)
    old = _run_bench_pair(bench_pair)
    assert new.message == old.message == "ok" and new.event_names == old.event_names
    breakaways = int(np.count_nonzero(new.event_kind == 0))
    assert breakaways >= 3 and new.n_pieces_by_phase[5] == breakaways and old.n_pieces_by_phase[5] == 0
    assert new.n_pieces < 0.4 * old.n_pieces  # the route's purpose (PTS 0-4 s: 200 against 1 396 pieces)
    _assert_same_answer(new, old)


def test_the_departure_series_solves_the_slabs_equation_with_the_exact_direction():
    """The departure's series (V = τ² W, never dividing by |V|) satisfies ż = A z + g a_g + p µk N V/|V| with V/|V|
    taken from the series' own V, at 1e-3 … 1 of its piece, to rounding — an independent check of the recurrence
    for the direction (e0 = D/|D| at the break-away, then along and across e0 order by order)."""
    from isolator.solver import planar_building_kernel as kernel
    from isolator.solver.planar_building import planar_building_system
    from isolator.superstructure import Floor, Superstructure

    structure = Superstructure(floors=tuple(Floor(2e5, 3.2, k, 0.7 * k) for k in (6e8, 4e8, 2e8)), damping_ratio=0.05,
                               gravity_m_s2=9.81)
    system = planar_building_system(structure, total_mass_kg=9e5, stiffness_N_per_m=9e5 * 9.81 / 2.0, mu_static=0.05,
                                    damping_Ns_per_m=3e4)
    m = 2 * system.n_floors + 2
    rng = np.random.default_rng(7)
    w = np.zeros((2, m))
    w[:, 0] = (0.03, -0.02)
    w[:, 2:] = rng.normal(scale=1e-3, size=(2, m - 2))
    mu_k_n = system.mu_kinetic * system.weight_N
    m_b = system.slab_mass_kg
    e = np.array([np.cos(0.6), np.sin(0.6)])
    a0 = np.array([(system.l_d[d] @ w[d] - mu_k_n * e[d]) / m_b for d in range(2)] + [0.0])  # |D| = µk N
    b = np.append(-25.0 * e + 8.0 * np.array([-e[1], e[0]]), 0.0)  # |D| growing, D turning [m/s³]
    ns = kernel.N_ORDER + 3
    zs, fs = np.zeros((2, ns + 1, m)), np.zeros((2, ns))
    assert kernel._series_depart(w, a0, b, system.a_mat, system.g_vec, system.p_vec, mu_k_n, zs, fs,
                                 np.zeros((2, ns)), np.zeros(ns), 2e-3, 2)
    weights = np.ones(m)
    weights[0] = weights[2:2 + system.n_floors] = system.fastest_rate_per_s
    length = kernel._piece_limit(zs, weights, 1e-12)
    assert 1e-4 < length < 1e-1
    z, zd, zdd = np.zeros((2, m)), np.zeros((2, m)), np.zeros((2, m))
    for fraction in (1e-3, 0.1, 0.5, 1.0):
        tau = fraction * length
        kernel._eval(zs, tau, z, zd, zdd)
        speed = np.hypot(z[0, 1], z[1, 1])
        assert speed > 0.0 and (system.l_d[0] @ z[0] - m_b * (a0[0] + b[0] * tau)) * z[0, 1] > 0.0
        for d in range(2):
            rate = system.a_mat[1, d] @ z[d] + system.g_vec[1, d] * (a0[d] + b[d] * tau) + \
                system.p_vec[d] * mu_k_n * z[d, 1] / speed
            scale = np.abs(system.a_mat[1, d]) @ np.abs(z[d]) + np.abs(system.p_vec[d]) * mu_k_n
            assert np.all(np.abs(zd[d] - rate) <= 1e-11 * scale[1]), (fraction, d, zd[d] - rate)
    # the form holds only at a break-away with |D| = µk N: 1e-9 above it is refused (START leaves rest there)
    a_off = a0.copy()
    a_off[:2] -= 1e-9 * mu_k_n * e / m_b
    assert not kernel._series_depart(w, a_off, b, system.a_mat, system.g_vec, system.p_vec, mu_k_n, zs, fs,
                                     np.zeros((2, ns)), np.zeros(ns), 2e-3, 2)
