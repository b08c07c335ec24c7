"""The 2-D building's accuracy parameters as knobs (docs/building.md, h172): the fast sub-steps' friction truncation
``planar_building.FAST_TRUNC_EPS`` refused outside its measured range, and a looser value's answer within its
measured bound of the default's on a real pair (the end check FAST_CHECK = 1e-12 µk N bounds the sub-steps' friction
whatever the truncation: on the bench's PTS 0-20 s, 1e-10 ... 1e-2 moved the answer by 6e-14 ... 6.3e-13 of its
scale, and every looser value was slower — more sub-steps refused by that check).  That end check is a run-time
setting too (``planar_building.FAST_CHECK``, h184): refused outside its measured range, and looser together with the
truncation it takes fewer series pieces, the answer within its measured bound of the default's and the energy
balance still closed (docs/building.md, h184)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.bench.building import FIXED_BASE_PERIOD_Y_S, building_case
from isolator.solver import planar_building
from isolator.solver import planar_building_kernel as kernel

from .test_planar_building_fast_eps import _assert_within
from .test_planar_building_stops import _run_bench_pair, bench_pair  # noqa: F401 (fixture)


@pytest.mark.parametrize(("setting", "value", "measured"), [
    *(("FAST_TRUNC_EPS", value, r"\(1e-16, 0\.01\)") for value in (0.0, -1e-12, math.nan, math.inf, 1e-1, 1e-17)),
    *(("FAST_CHECK", value, r"\(1e-14, 1e-06\)") for value in (0.0, -1e-12, math.nan, math.inf, 1e-5, 1e-15)),
])
def test_a_setting_outside_its_measured_range_is_refused(monkeypatch, setting, value, measured):
    """≤ 0 or NaN the kernel would silently replace by its default; outside the range (the truncation (1e-16, 1e-2),
    the end check (1e-14, 1e-6)) it is not measured."""
    t = np.arange(200) * 0.01
    case = building_case("sine", 3.0 * np.sin(2 * np.pi * t), 0.01, acceleration_y_m_s2=2.0 * np.cos(3 * t),
                         period_y_s=FIXED_BASE_PERIOD_Y_S)
    monkeypatch.setattr(planar_building, setting, value)
    with pytest.raises(ValueError, match=rf"{setting} = .* is outside {measured}"):
        _run_bench_pair(case)


@pytest.mark.parametrize("value", (1e-8, 1e-2))
def test_a_looser_truncation_stays_within_its_measured_bound_of_the_default(bench_pair, monkeypatch, value):  # noqa: F811
    """PTS 0-4 s: the same events, histories, peaks and energies to 1e-12 of their scale (measured on 0-20 s: 1.0e-13
    at 1e-8, 2.1e-13 at 1e-2), and more sub-steps refused by the end check than at the default (why it is slower)."""
    base = _run_bench_pair(bench_pair)
    monkeypatch.setattr(planar_building, "FAST_TRUNC_EPS", value)
    loose = _run_bench_pair(bench_pair)
    _assert_within(loose, base, 1e-12)
    assert loose.n_fast_refused[1] > base.n_fast_refused[1]


def test_the_loose_end_check_takes_fewer_pieces_within_its_measured_bound(bench_pair, monkeypatch):  # noqa: F811
    """PTS 0-4 s with the end check and the truncation both at the bench's second row's 1e-8 (default 1e-12 each):
    fewer sub-steps refused for their friction's series and fewer series pieces (why it is faster), the same events,
    the friction (the isolator's force) within the check's 1e-8 µk N of the default's answer, the other histories,
    peaks and energies within 1e-10 of their scale, the energy balance closed to 1e-11 of the input.  Measured: 8
    events, times within 1.6e-12 s; refused (series) 14 -> 8, pieces 96 -> 88; the force 2.4e-9 µk N, the velocity
    7.5e-11, the floor accelerations 3.6e-11, the peaks 2.2e-11, the energies 2.3e-12, the balance 1.8e-12 (1.9e-14 at
    the default); on 0-20 s the bench's error against the independent reference 1.14e-11 -> 3.4e-11."""
    assert planar_building.FAST_CHECK == kernel.FAST_CHECK == 1e-12  # the default unchanged
    base = _run_bench_pair(bench_pair)
    monkeypatch.setattr(planar_building, "FAST_CHECK", 1e-8)
    monkeypatch.setattr(planar_building, "FAST_TRUNC_EPS", 1e-8)
    loose = _run_bench_pair(bench_pair)
    assert loose.n_fast_refused[0] < base.n_fast_refused[0] and loose.n_pieces < base.n_pieces
    assert loose.message == base.message == "ok" and loose.event_names == base.event_names
    assert np.max(np.abs(loose.event_time_s - base.event_time_s)) <= 1e-11
    mu_k_n = bench_pair.mu * bench_pair.total_mass_kg * bench_pair.gravity_m_s2
    assert np.max(np.abs(loose.isolator_force_N - base.isolator_force_N)) <= 1e-8 * mu_k_n
    for key in ("displacement_m", "velocity_m_s", "floor_displacement_m", "floor_absolute_acceleration_m_s2",
                "superstructure_shear_N", "energy_history_J_per_kg"):
        a, b = getattr(loose, key), getattr(base, key)
        assert np.max(np.abs(a - b)) <= 1e-10 * np.max(np.abs(b)), key
    assert np.max(np.abs(loose.peak_resultants - base.peak_resultants) / np.abs(base.peak_resultants)) <= 1e-10
    e_in = base.energy_input_J_per_kg
    for key in ("energy_input_J_per_kg", "energy_friction_J_per_kg", "energy_viscous_J_per_kg"):
        assert abs(getattr(loose, key) - getattr(base, key)) <= 1e-10 * e_in, key
    assert abs(loose.energy_balance_error_J_per_kg) <= 1e-11 * loose.energy_input_J_per_kg
