"""The 2-D building's per-system cache (docs/building.md, "What a call costs outside the kernel"): the watched rows and
the kernel's column-ordered tables are built once per system, bearing layout and sub-step length and reused by later
runs. A table kept for another design, layout or sample interval must never be used: each run through warm caches
equals the same run from cold caches, bit for bit, and differs from the design it followed.

Independent truths: the tables rebuilt here by explicit loops from their definitions (the transposes, the end rows'
interleaving); the bearings' loads by rigid-slab statics from the run's own overturning moments (a stale layout's
rows would give the other layout's loads); a cold run (every cache emptied).
"""

from __future__ import annotations

import numpy as np
import pytest

import isolator.solver.planar_building as pb
from isolator.solver import planar_building_kernel as pk
from isolator.superstructure import BearingLayout, Floor, Superstructure

G = 9.80665
KEYS = ("displacement_m", "velocity_m_s", "floor_displacement_m", "floor_absolute_acceleration_m_s2",
        "isolator_force_N", "overturning_moment_Nm", "event_time_s", "event_kind", "peak_resultants", "signed_max",
        "signed_min", "energy_history_J_per_kg")


def _building(stiffness_scale=1.0, zeta=0.05, n=3):
    floors = tuple(Floor(3e5, 3.5, stiffness_scale * k, 0.8 * stiffness_scale * k) for k in np.linspace(8e8, 4e8, n))
    return Superstructure(floors=floors, damping_ratio=zeta, gravity_m_s2=G)


def _pair(records_dir, seconds):
    from isolator.motion import read_ground_motion

    files = sorted((records_dir / "pairs" / "superstitionhills1987_PTS").glob("*.AT2"))[:2]
    if len(files) < 2:
        pytest.skip("the PTS pair is not in the shared records")
    mx, my = (read_ground_motion(f) for f in files)
    n = round(seconds / mx.dt_s) + 1
    return mx.acceleration_m_s2[:n].copy(), my.acceleration_m_s2[:n].copy(), mx.dt_s


def _layout(half_x, half_y, total):
    return BearingLayout(x_m=(-half_x, half_x, half_x, -half_x), y_m=(-half_y, -half_y, half_y, half_y),
                         gravity_loads_N=(total * G / 4,) * 4)


def _run(ax, ay, dt, s, *, layout=None, zeta_iso=0.0, mu=0.06):
    total = 1.4 * s.mass_kg
    return pb.simulate_planar_building(ax, ay, dt, superstructure=s, total_mass_kg=total,
                                       stiffness_N_per_m=total * G / 2.5, mu_static=mu, mu_kinetic=0.05,
                                       damping_Ns_per_m=zeta_iso * total, bearing_layout=layout)


def _cold(*args, **kwargs):
    pb._SYSTEMS.clear()
    pb._PROPAGATORS.clear()
    return _run(*args, **kwargs)


def _same(a, b) -> bool:
    return all(np.array_equal(getattr(a, k), getattr(b, k)) for k in KEYS) and \
        a.energy_input_J_per_kg == b.energy_input_J_per_kg and a.n_pieces == b.n_pieces


def test_a_warm_run_after_another_design_equals_its_cold_run(records_dir):
    ax, ay, dt = _pair(records_dir, 8.0)
    base = _building()
    total = 1.4 * base.mass_kg
    first = dict(layout=_layout(6.0, 4.0, total))
    # each variant changes what one cached table depends on: the floors' stiffness (the propagators), their damping
    # (the viscous form), the isolator's dashpot (the system), the bearing layout (the watched rows), the sample
    # interval (the sub-step length h: every rung's table)
    variants = [
        ("stiffer floors", (ax, ay, dt, _building(1.7)), first),
        ("more damping", (ax, ay, dt, _building(1.0, 0.08)), first),
        ("a dashpot", (ax, ay, dt, base), dict(first, zeta_iso=0.05)),
        ("another layout", (ax, ay, dt, base), dict(layout=_layout(9.0, 3.0, total))),
        ("a longer sample interval", (ax, ay, 1.3 * dt, base), first),
    ]
    rate = pb.planar_building_system(base, total_mass_kg=total, stiffness_N_per_m=total * G / 2.5,
                                     mu_static=0.06, mu_kinetic=0.05).fastest_rate_per_s
    h = [step / np.ceil(rate * step / pk.THETA_FAST) for step in (dt, 1.3 * dt)]
    assert abs(h[1] / h[0] - 1.0) > 0.01  # the sub-step's length changes too
    cold = {name: _cold(*args, **kw) for name, args, kw in variants}
    pb._SYSTEMS.clear()
    pb._PROPAGATORS.clear()
    reference = _run(ax, ay, dt, base, **first)
    for name, args, kw in variants:
        _run(ax, ay, dt, base, **first)  # the caches now hold the base design's tables
        warm = _run(*args, **kw)
        assert _same(warm, cold[name]), name
        assert not np.array_equal(warm.displacement_m, reference.displacement_m) or not np.array_equal(
            warm.overturning_moment_Nm, reference.overturning_moment_Nm) or not np.array_equal(
            warm.signed_max, reference.signed_max), f"{name}: the variant does not change the answer"
        assert warm.status == 0 and warm.n_fast_steps > 100


def test_a_second_layout_on_one_system_gets_its_own_loads(records_dir):
    # one system, two layouts run one after the other: each bearing's extreme loads are its own layout's statics on
    # the run's overturning moments (a table kept for the first layout would give the first layout's loads)
    ax, ay, dt = _pair(records_dir, 8.0)
    s = _building()
    total = 1.4 * s.mass_kg
    for half_x, half_y in ((6.0, 4.0), (10.0, 2.5), (6.0, 4.0)):
        layout = _layout(half_x, half_y, total)
        r = _run(ax, ay, dt, s, layout=layout)
        m = r.overturning_moment_Nm
        by_hand = total * G / 4 + (m[:, 0] * np.array(layout.x_m)[:, None] / (4 * half_x ** 2)
                                   + m[:, 1] * np.array(layout.y_m)[:, None] / (4 * half_y ** 2))
        loads = r.bearing_loads()
        # the exact extremes lie between samples: at least the sampled ones, and within the sampled range's slope
        assert np.all(np.array(loads["bearing_axial_load_max_N"]) >= by_hand.max(axis=1) - 1e-9 * total * G)
        assert np.all(np.array(loads["bearing_axial_load_min_N"]) <= by_hand.min(axis=1) + 1e-9 * total * G)
        spread = np.max(by_hand.max(axis=1) - by_hand.min(axis=1))
        assert np.all(np.array(loads["bearing_axial_load_max_N"]) <= by_hand.max(axis=1) + 0.02 * spread)
        assert np.all(np.array(loads["bearing_axial_load_min_N"]) >= by_hand.min(axis=1) - 0.02 * spread)


def test_the_cached_tables_are_their_definitions_and_runs_do_not_change_them(records_dir):
    ax, ay, dt = _pair(records_dir, 4.0)
    s = _building(n=2)
    total = 1.4 * s.mass_kg
    layout = _layout(5.0, 5.0, total)
    r = _cold(ax, ay, dt, s, layout=layout)
    system = r.building
    n_fast = max(1, int(np.ceil(system.fastest_rate_per_s * dt / pk.THETA_FAST)))
    h = dt / n_fast
    watched, tables = pb._run_tables(system, layout, h)
    fpropt, fpinrow, fpvis, fvt, farow1, farow2, fmon, fsig, fend = tables
    fresh = pb._watched(system, layout)
    assert all(np.array_equal(a, b) for a, b in zip(watched, fresh, strict=True))
    prop, _, _, v_rows, *_ = pb._fast_tables(system, h, fresh)
    m = 2 * s.n_floors + 2
    levels, _, _, size, _ = fpropt.shape
    for lev in range(levels):
        for p in range(2):
            for d in range(2):
                for c in range(m):
                    for c2 in range(size):
                        assert fpropt[lev, p, d, c2, c] == prop[lev, p, d, c, c2]
    for d in range(2):
        for k in range(v_rows.shape[1]):
            for c in range(size):
                assert fvt[d, c, k] == v_rows[d, k, c]
    nk = fmon.shape[1]
    for p in range(2):
        for d in range(2):
            for q in range(nk + fsig.shape[1]):
                rows = fmon[p, q, d] if q < nk else fsig[p, q - nk, d]
                for c in range(m + 4):
                    assert fend[p, d, c, 2 * q] == rows[0, c] and fend[p, d, c, 2 * q + 1] == rows[1, c]
    for t in (fpropt, fvt, fend):
        assert t.flags.c_contiguous
    kept = [t.copy() for t in (*watched, *tables)]
    again = _run(ax, ay, dt, s, layout=layout)
    assert _same(again, r)
    watched2, tables2 = pb._run_tables(system, layout, h)
    assert all(a is b for a, b in zip((*watched, *tables), (*watched2, *tables2), strict=True))
    assert all(np.array_equal(a, b) for a, b in zip(kept, (*watched2, *tables2), strict=True))
