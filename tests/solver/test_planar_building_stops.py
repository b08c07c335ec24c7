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
