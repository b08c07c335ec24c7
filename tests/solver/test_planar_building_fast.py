"""The 2-D building's fast sub-steps (exact propagators; docs/building.md, "The fast sub-steps' input energy and
watched rows"): the input energy as two precomputed rows, the watched values at a sub-step's end from one table, and
a break-away inside a sample whose ends are both below the static limit (the sub-step's event test must refuse it).

Independent truths: the Van Loan form and a quadrature of the input power; the floors' equations of motion and the
slab's equation applied to the state history; the fixed-base response solved here by scipy's matrix exponential.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad_vec
from scipy.linalg import expm
from scipy.optimize import brentq

from isolator.solver import planar_building_kernel as pk
from isolator.solver.building import van_loan
from isolator.solver.planar_building import (
    _augmented,
    _fast_tables,
    _watched,
    planar_building_system,
    simulate_planar_building,
)
from isolator.superstructure import BearingLayout, Floor, Superstructure

G = 9.80665


def _building(n=3, zeta=0.05):
    floors = tuple(Floor(3e5, 3.5, k, 0.8 * k) for k in np.linspace(8e8, 4e8, n))
    return Superstructure(floors=floors, damping_ratio=zeta, gravity_m_s2=G)


def _pair(records_dir, seconds, folder="superstitionhills1987_PTS"):
    from isolator.motion import read_ground_motion

    files = sorted((records_dir / "pairs" / folder).glob("*.AT2"))[:2]
    mx, my = (read_ground_motion(f) for f in files)
    n = round(seconds / mx.dt_s) + 1
    return mx.acceleration_m_s2[:n].copy(), my.acceleration_m_s2[:n].copy(), mx.dt_s


def test_the_input_rows_are_the_van_loan_form_and_the_power_integral():
    s = _building()
    total = 1.4 * s.mass_kg
    system = planar_building_system(s, total_mass_kg=total, stiffness_N_per_m=total * G / 2.5, mu_static=0.06,
                                    mu_kinetic=0.05, damping_Ns_per_m=3e4)
    h = 0.01
    prop, rows, *_ = _fast_tables(system, h, _watched(system, None))
    aug = _augmented(system)
    m = 2 * s.n_floors + 2
    size = aug.shape[-1]
    rng = np.random.default_rng(7)
    checked = 0
    for lev in (0, 3, pk.FAST_LEVELS - 1):
        h_lev = h / 2 ** lev
        scale = np.ones(size)
        scale[m + 2:] = h_lev ** np.arange(pk.FAST_ORDER + 1)
        for phase in range(2):
            for d, one in enumerate(system.directions):
                q_in = np.zeros((size, size))
                q_in[:m + 3, :m + 3] = one.q_in
                scaled = aug[phase, d] * scale[:, None] / scale[None, :]
                w = rng.normal(size=size) * np.r_[np.full(m, 0.1), 3.0, 50.0, 1e5 * rng.normal(size=size - m - 2)]
                by_rows = w[m] * rows[lev, phase, d, 0] @ w + w[m + 1] * rows[lev, phase, d, 1] @ w
                # the linear block alone (no chain): its rows come from the linear block's own exponential
                lin = w.copy()
                lin[m + 2:] = 0.0
                form_lin = lin[:m + 2] @ van_loan(aug[phase, d, :m + 2, :m + 2], q_in[:m + 2, :m + 2], h_lev) @ lin[:m + 2]
                rows_lin = lin[m] * rows[lev, phase, d, 0] @ lin + lin[m + 1] * rows[lev, phase, d, 1] @ lin
                assert rows_lin == pytest.approx(form_lin, rel=1e-12, abs=1e-13 * abs(form_lin))
                form = w @ van_loan(scaled, q_in, h_lev) @ w
                assert by_rows == pytest.approx(form, rel=1e-10)
                checked += 1
    assert checked == 12
    # the power a_g(τ) ℓ_p·w̃(τ) integrated by quadrature on the whole augmented matrix (one rung, sliding, x)
    lev, phase, d = 2, 1, 0
    h_lev = h / 2 ** lev
    scale = np.ones(size)
    scale[m + 2:] = h_lev ** np.arange(pk.FAST_ORDER + 1)
    scaled = aug[phase, d] * scale[:, None] / scale[None, :]
    q_in = np.zeros((size, size))
    q_in[:m + 3, :m + 3] = system.directions[d].q_in
    w = rng.normal(size=size)
    power = quad_vec(lambda t: (expm(scaled * t) @ w) @ q_in @ (expm(scaled * t) @ w), 0.0, h_lev, epsrel=1e-13)[0]
    by_rows = w[m] * rows[lev, phase, d, 0] @ w + w[m + 1] * rows[lev, phase, d, 1] @ w
    assert by_rows == pytest.approx(power, rel=1e-10)


def test_the_watched_values_at_every_sample_follow_from_the_state(records_dir):
    # the values at a sub-step's end come from one table of rows (ℓ, ℓÃ); here they are rebuilt from the state
    # history by the equations themselves: the floors' absolute accelerations −M⁻¹(K_s u + C_s u̇) in both phases,
    # the overturning moments −Σ m_i H_i a_i, the slab's friction force S − m_b a_g while held and
    # K X + c V + µk N V/|V| while sliding, the bearings' loads by rigid-slab statics
    ax, ay, dt = _pair(records_dir, 12.0)
    s = _building(4)
    total = 1.4 * s.mass_kg
    k_iso = total * G / 2.5
    c_iso = 2e4
    layout = BearingLayout(x_m=(-6.0, 6.0, 6.0, -6.0), y_m=(-4.0, -4.0, 4.0, 4.0), gravity_loads_N=(total * G / 4,) * 4)
    r = simulate_planar_building(ax, ay, dt, superstructure=s, total_mass_kg=total, stiffness_N_per_m=k_iso,
                                 mu_static=0.06, mu_kinetic=0.05, damping_Ns_per_m=c_iso, bearing_layout=layout)
    assert r.status == 0 and r.n_events > 10 and r.n_fast_steps > 1000
    b = r.building
    u, ud = r.floor_displacement_m, r.floor_velocity_m_s  # (N, floors, 2)
    acc = np.stack([-np.linalg.solve(np.diag(b.masses_kg), b.stiffness_matrices[d] @ u[:, :, d].T
                                     + b.damping_matrices[d] @ ud[:, :, d].T).T for d in range(2)], axis=2)
    a_floor = r.floor_absolute_acceleration_m_s2
    assert np.max(np.abs(a_floor - acc)) <= 1e-11 * np.max(np.abs(acc))
    moment = -np.einsum("nfd,f->nd", acc, b.masses_kg * b.floor_heights_m)
    assert np.max(np.abs(r.overturning_moment_Nm - moment)) <= 1e-11 * np.max(np.abs(moment))
    shear = -np.einsum("nfd,f->nd", acc, b.masses_kg)
    assert np.max(np.abs(r.superstructure_shear_N - shear)) <= 1e-11 * np.max(np.abs(shear))
    x, v = r.displacement_m, r.velocity_m_s
    speed = np.hypot(v[:, 0], v[:, 1])
    ground = np.column_stack([ax, ay])
    held = speed == 0.0
    sliding = speed > 1e-6
    assert held.sum() > 100 and sliding.sum() > 100
    force = r.isolator_force_N
    scale = np.max(np.abs(force))
    hold = shear - b.slab_mass_kg * ground
    assert np.max(np.abs(force[held] - hold[held])) <= 1e-11 * scale
    slide = k_iso * x + c_iso * v + 0.05 * total * G * v / np.maximum(speed, 1e-300)[:, None]
    assert np.max(np.abs(force[sliding] - slide[sliding])) <= 1e-9 * scale
    loads = r.bearing_loads()["axial_load_N"]
    by_hand = total * G / 4 + (moment[:, 0] * np.array(layout.x_m)[:, None] / 144.0
                               + moment[:, 1] * np.array(layout.y_m)[:, None] / 64.0)
    assert np.max(np.abs(loads - by_hand)) <= 1e-11 * total * G
    # the energy balance closes
    assert abs(r.energy_balance_error_J_per_kg) <= 1e-12 * r.energy_input_J_per_kg


def _fixed_base(building, direction):
    """[u, u̇, a_g, ȧ_g]' = F [u, u̇, a_g, ȧ_g] of the floors on a held slab, and the holding force's row."""
    n = building.n_floors
    k_s = building.stiffness_matrices[direction]
    c_s = building.damping_matrices[direction]
    m_inv = np.diag(1.0 / building.masses_kg)
    f = np.zeros((2 * n + 2, 2 * n + 2))
    f[:n, n:2 * n] = np.eye(n)
    f[n:2 * n, :n] = -m_inv @ k_s
    f[n:2 * n, n:2 * n] = -m_inv @ c_s
    f[n:2 * n, 2 * n] = -1.0
    f[2 * n, 2 * n + 1] = 1.0
    # D = 1ᵀ(K_s u + C_s u̇) − m_b a_g: the first story's force on the slab less the slab's own inertia
    row = np.r_[k_s.sum(axis=0), c_s.sum(axis=0), -building.slab_mass_kg, 0.0]
    return f, row


def test_a_break_away_inside_a_sample_near_the_static_limit(records_dir):
    # the static limit µs N is set just below the largest holding force of the first 3 s, which lies inside a sample
    # whose two ends are below the limit: the sub-step's test from the ends' values and slopes must refuse the
    # sub-step, and the break-away must be found at the root of |D| = µs N of the exact fixed-base response
    ax, ay, dt = _pair(records_dir, 3.0)
    s = _building(3)
    total = 1.4 * s.mass_kg
    k_iso = total * G / 2.5
    probe = simulate_planar_building(ax, ay, dt, superstructure=s, total_mass_kg=total, stiffness_N_per_m=k_iso,
                                     mu_static=0.95)
    b = probe.building
    n = b.n_floors
    systems = [_fixed_base(b, d) for d in range(2)]
    steps = [expm(f * dt) for f, _ in systems]
    states = [np.zeros(2 * n + 2) for _ in range(2)]
    starts = []
    for i in range(ax.size - 1):
        for d, acc in enumerate((ax, ay)):
            states[d][2 * n] = acc[i]
            states[d][2 * n + 1] = (acc[i + 1] - acc[i]) / dt
        starts.append([st.copy() for st in states])
        states = [steps[d] @ states[d] for d in range(2)]

    def holding(i, tau):
        return np.hypot(*(systems[d][1] @ expm(systems[d][0] * tau) @ starts[i][d] for d in range(2)))

    ends = np.array([holding(i, 0.0) for i in range(len(starts))])
    # the samples' holding force agrees with the kernel's (a consistency check of this reference)
    kernel_hold = np.hypot(*probe.isolator_force_N[:-1].T)
    assert np.max(np.abs(ends - kernel_hold)) <= 1e-9 * ends.max()
    # the interior maxima of |D| between samples, densely sampled and refined
    grid = np.linspace(0.0, dt, 41)
    best_i, best_tau, best = -1, 0.0, 0.0
    for i in range(len(starts)):
        values = [holding(i, t) for t in grid[1:-1]]
        j = int(np.argmax(values))
        if values[j] > best:
            best_i, best_tau, best = i, grid[1 + j], values[j]
    lo, hi = max(best_tau - dt / 40, 0.0), min(best_tau + dt / 40, dt)
    for _ in range(60):  # golden-free ternary refinement of the interior maximum
        a, c = lo + (hi - lo) / 3, hi - (hi - lo) / 3
        if holding(best_i, a) < holding(best_i, c):
            lo = a
        else:
            hi = c
    tau_max = 0.5 * (lo + hi)
    peak = holding(best_i, tau_max)
    limit = peak * (1.0 - 1e-7)
    # both ends of that sample are below the limit, and no earlier sample reaches it
    assert ends[best_i] < limit and ends[best_i + 1] < limit
    assert ends[:best_i].max() < limit
    t_root = brentq(lambda t: holding(best_i, t) - limit, 0.0, tau_max, xtol=1e-15, rtol=1e-15)
    mu_s = limit / (total * G)
    r = simulate_planar_building(ax, ay, dt, superstructure=s, total_mass_kg=total, stiffness_N_per_m=k_iso,
                                 mu_static=mu_s, mu_kinetic=0.8 * mu_s)
    assert r.n_events >= 1 and r.event_kind[0] == 0
    assert r.event_time_s[0] == pytest.approx(best_i * dt + t_root, abs=1e-10)
    assert r.n_fast_refused[2] >= 1  # the event test refused at least one sub-step
    # the same record with the limit just above the peak: held throughout that sample
    r_above = simulate_planar_building(ax, ay, dt, superstructure=s, total_mass_kg=total, stiffness_N_per_m=k_iso,
                                       mu_static=peak * (1.0 + 1e-7) / (total * G))
    assert r_above.n_events == 0 or r_above.event_time_s[0] > (best_i + 1) * dt


def _form_by_rows(p, w, s_eff):
    """The viscous form as the kernel summed it before (one dependent sum per row, c ascending)."""
    total = 0.0
    for r in range(s_eff):
        acc = 0.0
        for c in range(r + 1, s_eff):
            acc += p[r, c] * w[c]
        total += w[r] * (p[r, r] * w[r] + 2.0 * acc)
    return total


def test_the_viscous_form_by_columns_is_the_row_sum_and_the_power_integral():
    # the fast sub-step's viscous energy w̃ᵀ P w̃ is now summed column by column (pk._form_add); it must be the
    # row-by-row sum to the last bit (same terms, same order) and the integral of the viscous power
    # w̃(τ)ᵀ Q_vis w̃(τ) over the rung, w̃(τ) = e^{Ãτ} w̃ by scipy's expm, on the chain scaled to the rung
    s = _building(4)
    total = 1.4 * s.mass_kg
    system = planar_building_system(s, total_mass_kg=total, stiffness_N_per_m=total * G / 2.5, mu_static=0.06,
                                    mu_kinetic=0.05, damping_Ns_per_m=3e4)
    h = 0.01
    p_vis = _fast_tables(system, h, _watched(system, None))[2]
    aug = _augmented(system)
    m = 2 * s.n_floors + 2
    size = aug.shape[-1]
    pw = np.zeros(size)
    rng = np.random.default_rng(11)
    checked = 0
    for lev, phase, k_eff in ((0, 1, 12), (pk.FAST_LEVELS - 1, 1, pk.FAST_ORDER), (2, 0, -1)):
        h_lev = h / 2 ** lev
        s_eff = m + 3 + k_eff
        scale = np.ones(size)
        scale[m + 2:] = h_lev ** np.arange(pk.FAST_ORDER + 1)
        for d, one in enumerate(system.directions):
            w = np.zeros(size)
            w[:s_eff] = rng.normal(size=s_eff) * np.r_[np.full(m, 0.1), 3.0, 50.0,
                                                        3e4 * 0.5 ** np.arange(size - m - 2)][:s_eff]
            ours = pk._form_add(0.0, p_vis[lev, phase, d], w, s_eff, pw)
            assert ours == _form_by_rows(p_vis[lev, phase, d], w, s_eff)
            assert pk._form_add(ours, p_vis[lev, phase, d], w, s_eff, pw) == pytest.approx(2.0 * ours, rel=1e-15)
            q_vis = np.zeros((size, size))
            q_vis[:m + 3, :m + 3] = one.q_vis
            scaled = aug[phase, d] * scale[:, None] / scale[None, :]
            power = quad_vec(lambda t, a=scaled, x=w, q=q_vis: (expm(a * t) @ x) @ q @ (expm(a * t) @ x), 0.0,
                             h_lev, epsrel=1e-13)[0]
            assert power > 0.0
            assert ours == pytest.approx(power, rel=1e-10)
            checked += 1
    assert checked == 6
