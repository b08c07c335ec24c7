"""The 2-D building on the isolation plane (issue 22) against an independent reference.

The reference here shares no code with :mod:`isolator.solver.planar_building`: per direction
the equations in the (X, u) coordinates with the full coupled mass matrix [[M_tot, mᵀ], [m, M]],
the damping matrix from numpy's symmetric eigenproblem of M^{-1/2} K M^{-1/2}, the friction
µk W V/|V| in Cartesian form, integrated by scipy ``solve_ivp`` at rtol 1e-12 sample interval by
sample interval: DOP853 while |V| ≥ 1e-3 m/s, Radau (implicit) below, where V/|V| makes the
equations stiff; the stop is the event |V| = 1e-13 m/s, the last 1e-13 m/s finished at constant
deceleration; a start from rest begins at 1e-13 m/s (1e-11 made the reference itself off by 8e-10) along the force on the slab; break-aways
are solve_ivp events of |D|² − (µs W)² on the stuck equations; the energies are extra states.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from isolator.solver.building import simulate_building
from isolator.solver.planar import simulate_pair
from isolator.solver.planar_building import simulate_planar_building
from isolator.superstructure import BearingLayout, Floor, Superstructure

G = 9.80665
REF_RTOL = 1e-12
V_EPS = 1e-13
V_SWITCH = 1e-3


def make_superstructure(masses, kx, ky=None, zeta=0.05, heights=None):
    ky = kx if ky is None else ky
    heights = heights or [3.5] * len(masses)
    return Superstructure(floors=tuple(Floor(m, h, a, b) for m, h, a, b in zip(masses, heights, kx, ky, strict=True)),
                          damping_ratio=zeta, gravity_m_s2=G)


def _story_matrices(masses, stiffnesses, zeta):
    n = masses.size
    k_mat = np.zeros((n, n))
    for i, k in enumerate(stiffnesses):
        k_mat[i, i] += k
        if i > 0:
            k_mat[i - 1, i - 1] += k
            k_mat[i - 1, i] -= k
            k_mat[i, i - 1] -= k
    root_m = np.sqrt(masses)
    lam, psi = np.linalg.eigh(k_mat / np.outer(root_m, root_m))
    c_mat = (root_m[:, None] * psi) @ np.diag(2 * zeta * np.sqrt(lam)) @ (root_m[:, None] * psi).T
    return k_mat, c_mat


def reference_planar_building(acc_x, acc_y, dt, masses, kx, ky, zeta, total_mass, k_iso, c_iso, mu_s, mu_k, acc_z=None,
                              pendulum=False, law=None, rtol=REF_RTOL, slow_method="Radau"):
    """Samples, events, energies and the resultant peaks of X and of every story drift (solve_ivp).

    slow_method: solve_ivp's method below V_SWITCH (near the stops and breakaways).

    acc_z: a vertical, linear between samples: N(t) = W (1 + a_z/g) in the friction µ N, the static limit µs N and,
    with ``pendulum``, the restoring stiffness k_iso N/W (its work ½∫k_iso ν̇ |X|² dt counted in the input).
    law = (µ_slow, µ_fast, a): µ(|V|) = µ_fast − (µ_fast − µ_slow) e^{−a|V|} instead of µ_k (µ_slow leaving rest).
    """
    acc_z = np.zeros_like(acc_x) if acc_z is None else acc_z

    def mu_of(r):
        return mu_k if law is None else law[1] - (law[1] - law[0]) * math.exp(-law[2] * r)

    def nu_of(t, c0, cz):
        return 1.0 + (c0 + cz * t) / G
    masses = np.asarray(masses, float)
    n = masses.size
    mats = [_story_matrices(masses, kx, zeta), _story_matrices(masses, ky, zeta)]
    m_b = total_mass - masses.sum()
    weight = G * total_mass
    full_mass = np.zeros((n + 1, n + 1))
    full_mass[0, 0] = total_mass
    full_mass[0, 1:] = full_mass[1:, 0] = masses
    full_mass[1:, 1:] = np.diag(masses)
    inv_mass = np.linalg.inv(full_mass)
    q = n + 1  # per direction: [X, u]; y = [q_x, q_y, qdot_x, qdot_y, E_in, E_fr, E_vis]
    nq = 2 * q

    def parts(y):
        pos = [y[d * q:(d + 1) * q] for d in range(2)]
        vel = [y[nq + d * q:nq + (d + 1) * q] for d in range(2)]
        return pos, vel

    def hold(y, a, nu=1.0):
        pos, vel = parts(y)
        k_now = k_iso * nu if pendulum else k_iso
        return np.array([-m_b * a[d] - k_now * pos[d][0] - c_iso * vel[d][0]
                         + np.sum(mats[d][0] @ pos[d][1:] + mats[d][1] @ vel[d][1:]) for d in range(2)])

    def rhs(t, y, a0, b, sliding, c0=0.0, cz=0.0):
        a = a0 + b * t
        nu = nu_of(t, c0, cz)
        k_now = k_iso * nu if pendulum else k_iso
        pos, vel = parts(y)
        dy = np.zeros_like(y)
        v_slab = np.array([vel[0][0], vel[1][0]])
        r = math.hypot(*v_slab)
        e = v_slab / r if (sliding and r > 0.0) else np.zeros(2)
        for d in range(2):
            k_mat, c_mat = mats[d]
            dy[d * q:(d + 1) * q] = vel[d]
            if sliding:
                force = np.concatenate([[-c_iso * vel[d][0] - k_now * pos[d][0] - mu_of(r) * weight * nu * e[d]],
                                        -(c_mat @ vel[d][1:] + k_mat @ pos[d][1:])]) - full_mass[:, 0] * a[d]
                dy[nq + d * q:nq + (d + 1) * q] = inv_mass @ force
            else:
                dy[nq + d * q + 1:nq + (d + 1) * q] = -(c_mat @ vel[d][1:] + k_mat @ pos[d][1:]) / masses - a[d]
            dy[2 * nq] += -a[d] * (m_b * vel[d][0] + masses @ (vel[d][0] + vel[d][1:]))
            dy[2 * nq + 2] += c_iso * vel[d][0] ** 2 + vel[d][1:] @ c_mat @ vel[d][1:]
            if pendulum:
                dy[2 * nq] += 0.5 * k_iso * cz / G * pos[d][0] ** 2
        dy[2 * nq + 1] = mu_of(r) * weight * nu * r if sliding else 0.0
        return dy

    def drift(y, j):
        pos, _ = parts(y)
        return np.array([pos[d][1 + j] - (pos[d][j] if j > 0 else 0.0) for d in range(2)])

    def drift_rate(y, j):
        _, vel = parts(y)
        return np.array([vel[d][1 + j] - (vel[d][j] if j > 0 else 0.0) for d in range(2)])

    y = np.zeros(2 * nq + 3)
    stuck, slow = True, True
    samples = [y.copy()]
    events = []
    peak_x = 0.0
    drift_peak = np.zeros(n)

    def start_from_rest(y, a, nu=1.0):
        d_vec = hold(y, a, nu)
        y = y.copy()
        y[nq] += V_EPS * d_vec[0] / np.linalg.norm(d_vec)
        y[nq + q] += V_EPS * d_vec[1] / np.linalg.norm(d_vec)
        return y

    for i in range(acc_x.size - 1):
        a0 = np.array([acc_x[i], acc_y[i]])
        b = (np.array([acc_x[i + 1], acc_y[i + 1]]) - a0) / dt
        c0, cz = acc_z[i], (acc_z[i + 1] - acc_z[i]) / dt
        t = 0.0
        for _ in range(2000):
            peak_fns = [lambda t, y, *r: y[0] * y[nq] + y[q] * y[nq + q]]
            peak_fns += [lambda t, y, *r, j=j: drift(y, j) @ drift_rate(y, j) for j in range(n)]
            for f in peak_fns:
                f.direction = -1.0
            if stuck:
                def brk(t, y, *r, a0=a0, b=b, c0=c0, cz=cz):
                    nu = nu_of(t, c0, cz)
                    d_vec = hold(y, a0 + b * t, nu)
                    return d_vec @ d_vec - (mu_s * weight * nu) ** 2
                brk.terminal, brk.direction = True, 1.0
                fns = [brk]
                method = "DOP853"
            else:
                def speed(t, y, *r, level=V_EPS if slow else V_SWITCH):
                    return math.hypot(y[nq], y[nq + q]) - level
                speed.terminal, speed.direction = True, -1.0
                fns = [speed]
                if slow:
                    def fast(t, y, *r):
                        return math.hypot(y[nq], y[nq + q]) - V_SWITCH
                    fast.terminal, fast.direction = True, 1.0
                    fns.append(fast)
                method = slow_method if slow else "DOP853"
            if stuck and t == 0.0 and i == 0:
                d0 = hold(y, a0, nu_of(0.0, c0, cz))
                if d0 @ d0 > (mu_s * weight * nu_of(0.0, c0, cz)) ** 2:
                    raise AssertionError("the reference starts at rest below µs W")
            sol = solve_ivp(rhs, (t, dt), y, method=method, rtol=rtol, atol=1e-15,
                            args=(a0, b, not stuck, c0, cz), events=fns + peak_fns)
            if sol.status < 0:
                raise RuntimeError(sol.message)
            for ye in sol.y_events[len(fns)]:
                peak_x = max(peak_x, math.hypot(ye[0], ye[q]))
            for j in range(n):
                for ye in sol.y_events[len(fns) + 1 + j]:
                    drift_peak[j] = max(drift_peak[j], np.linalg.norm(drift(ye, j)))
            for yv in sol.y.T:
                peak_x = max(peak_x, math.hypot(yv[0], yv[q]))
                for j in range(n):
                    drift_peak[j] = max(drift_peak[j], np.linalg.norm(drift(yv, j)))
            y = sol.y[:, -1].copy()
            if sol.status != 1:
                break
            t = sol.t[-1]
            a = a0 + b * t
            if stuck:
                y = start_from_rest(y, a, nu_of(t, c0, cz))
                stuck, slow = False, True
                events.append((i * dt + t, "breakaway"))
                continue
            if not slow or len(sol.t_events[1]):
                slow = not slow  # crossed V_SWITCH
                continue
            # the stop: the last V_EPS at constant deceleration
            dy = rhs(t, y, a0, b, True, c0, cz)
            v_slab = np.array([y[nq], y[nq + q]])
            r = np.linalg.norm(v_slab)
            rdot = v_slab @ np.array([dy[nq], dy[nq + q]]) / r
            step = min(r / max(-rdot, 1e-300), dt - t)
            y[:nq] += step * y[nq:2 * nq]
            y[nq:2 * nq] += step * dy[nq:2 * nq]
            y[nq] = y[nq + q] = 0.0
            t += step
            a = a0 + b * t
            nu = nu_of(t, c0, cz)
            if np.linalg.norm(hold(y, a, nu)) <= mu_s * weight * nu:
                stuck = True
                events.append((i * dt + t, "stick"))
            else:
                y = start_from_rest(y, a, nu)
                slow = True
                events.append((i * dt + t, "reversal"))
        samples.append(y.copy())
    samples = np.array(samples)
    return {"X": samples[:, [0, q]], "V": samples[:, [nq, nq + q]],
            "u": np.stack([samples[:, 1:q], samples[:, q + 1:nq]], axis=2),
            "energy": samples[-1, 2 * nq:], "events": events, "peak_x": peak_x, "drift_peak": drift_peak}


def pair_segment(records_dir, folder, start_s, duration_s, scale=1.0, taper_s=0.2):
    from isolator.motion import read_ground_motion

    files = sorted((records_dir / "pairs" / folder).glob("*.AT2"))
    motions = [read_ground_motion(f) for f in files[:2]]
    dt = motions[0].dt_s
    i0 = int(round(start_s / dt))
    n = min(int(round(duration_s / dt)) + 1, *(m.npts - i0 for m in motions))
    ramp = np.minimum(1.0, np.arange(n) * dt / taper_s) if taper_s else 1.0
    return [scale * ramp * m.acceleration_m_s2[i0:i0 + n] for m in motions], dt


def _rel(a, b):
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b))) / np.max(np.abs(b)))


CASES = {
    # name: pair, start, duration, scale, masses, kx, ky, ζ, total mass, R (or K), c_iso, µs, µk
    "1 story, pendulum": ("superstitionhills1987_PTS", 8.0, 1.5, 1.0, [4e5], [3e8], [2e8], 0.05, 6e5,
                          {"radius_m": 2.0}, 0.0, 0.06, 0.042),
    "2 stories, flat + spring + dashpot": ("hectormine1999_ABY", 8.0, 1.5, 2.0, [3e5, 2e5], [6e8, 3e8],
                                           [4e8, 3.5e8], 0.03, 7e5, {"stiffness_N_per_m": 2.0e6}, 1.5e5, 0.07, 0.05),
    "2 stiff stories (T1 = 0.05 s), µs = µk": ("superstitionhills1987_PTS", 9.0, 1.5, 1.0, [3e5, 2e5], [6e9, 4e9],
                                                [5e9, 5e9], 0.05, 7e5, {"radius_m": 2.0}, 0.0, 0.05, 0.05),
    "4 stories, pendulum, no spring in y": ("landers1992_YER", 10.0, 2.0, 1.0, [2e5] * 4,
                                            [8e8, 6e8, 5e8, 3e8], [5e8, 4e8, 3e8, 2e8], 0.05, 1.2e6,
                                            {"radius_m": 3.0}, 0.0, 0.05, 0.035),
    "1 story, flat slider, no spring": ("hectormine1999_ABY", 9.0, 1.5, 2.0, [4e5], [2e8], [1e8], 0.02, 6e5,
                                        {"stiffness_N_per_m": 0.0}, 0.0, 0.06, 0.045),
}


def _run_case(records_dir, name):
    pair, start, duration, scale, masses, kx, ky, zeta, total, spring, c_iso, mu_s, mu_k = CASES[name]
    (acc_x, acc_y), dt = pair_segment(records_dir, pair, start, duration, scale)
    k_iso = total * G / spring["radius_m"] if "radius_m" in spring else spring["stiffness_N_per_m"]
    ours = simulate_planar_building(acc_x, acc_y, dt, superstructure=make_superstructure(masses, kx, ky, zeta),
                                    total_mass_kg=total, stiffness_N_per_m=k_iso, mu_static=mu_s, mu_kinetic=mu_k,
                                    damping_Ns_per_m=c_iso)
    ref = reference_planar_building(acc_x, acc_y, dt, masses, kx, ky, zeta, total, k_iso, c_iso, mu_s, mu_k)
    return ours, ref


#: The cases whose slides stop (sticks and reversals), with how many stops the slowing piece itself ends at, at
#: least (``STOP_PIECE``, docs/building.md "The stop in one piece"; measured 2 of 3, 2 of 2, 3 of 3, 1 of 1: 4 of
#: the 5 cases, 9 stops, 8 by the slowing piece).  Those are held to 1e-10 of the reference below.
STOP_PIECES = {"2 stories, flat + spring + dashpot": 2, "2 stiff stories (T1 = 0.05 s), µs = µk": 2,
               "4 stories, pendulum, no spring in y": 3, "1 story, flat slider, no spring": 1}


@pytest.mark.parametrize("name", list(CASES))
def test_real_pairs_against_solve_ivp(records_dir, name):
    """Each case against the reference; the cases that stop, to 1e-10 and in one piece per stop (these checks were
    test_planar_building_series_stop.py's, on a second run of the same cases and references: one run now)."""
    ours, ref = _run_case(records_dir, name)
    assert ours.message == "ok"
    assert ours.n_events >= 1 and ours.slip_time_s > 0.2, "the case must slide"
    assert ours.event_names == [kind for _, kind in ref["events"]]
    assert np.max(np.abs(ours.event_time_s - [t for t, _ in ref["events"]])) <= 1e-8
    assert _rel(ours.displacement_m, ref["X"]) <= 1e-9
    assert _rel(ours.velocity_m_s, ref["V"]) <= 1e-9
    assert _rel(ours.floor_displacement_m, ref["u"]) <= 1e-9
    assert ours.peak_displacement_m == pytest.approx(ref["peak_x"], rel=1e-9)
    assert ours.story_drift_m == pytest.approx(ref["drift_peak"], rel=1e-9)
    e_in, e_f, e_v = ref["energy"] / ours.building.total_mass_kg
    assert ours.energy_input_J_per_kg == pytest.approx(e_in, rel=1e-9)
    assert ours.energy_friction_J_per_kg == pytest.approx(e_f, rel=1e-9)
    assert ours.energy_viscous_J_per_kg == pytest.approx(e_v, abs=1e-9 * e_in)
    assert abs(ours.energy_balance_error_J_per_kg) <= 1e-9 * ours.energy_input_J_per_kg
    if name not in STOP_PIECES:
        return
    # the stop in one piece against the same reference: events, X, V, the peak and the friction's work to 1e-10
    # (measured <= 8.7e-12); the floors of the stiff case read 1.2e-10 after its last break-away (0.27 s), with or
    # without this route
    assert np.count_nonzero((ours.event_kind == 1) | (ours.event_kind == 2)) >= 1
    assert ours.n_stop_pieces >= STOP_PIECES[name]
    assert np.max(np.abs(ours.event_time_s - [t for t, _ in ref["events"]])) <= 1e-10
    for key, ref_key, tol in (("displacement_m", "X", 1e-10), ("velocity_m_s", "V", 1e-10),
                              ("floor_displacement_m", "u", 1e-9)):
        scale = np.max(np.abs(ref[ref_key]))
        assert np.max(np.abs(getattr(ours, key) - ref[ref_key])) <= tol * scale, key
    assert ours.peak_displacement_m == pytest.approx(ref["peak_x"], rel=1e-10)
    assert ours.energy_friction_J_per_kg == pytest.approx(e_f, rel=1e-10)


BUILDING = {"superstructure": make_superstructure([3e5, 2e5, 1.5e5], [5e8, 4e8, 2e8], [4e8, 3e8, 2.5e8], 0.05),
            "total_mass_kg": 1e6, "stiffness_N_per_m": 1e6 * G / 2.0, "mu_static": 0.07, "mu_kinetic": 0.05,
            "damping_Ns_per_m": 1e5}


def test_zero_second_component_is_the_1d_building(records_dir):
    (acc_x, _), dt = pair_segment(records_dir, "superstitionhills1987_PTS", 5.0, 10.0, taper_s=0.0)
    one = simulate_building(acc_x, dt, **BUILDING)
    two = simulate_planar_building(acc_x, np.zeros_like(acc_x), dt, **BUILDING)
    assert one.n_events >= 6 and two.event_names == one.event_names
    assert np.max(np.abs(two.event_time_s - one.event_time_s)) <= 1e-9
    assert np.all(two.displacement_m[:, 1] == 0.0) and np.all(two.floor_displacement_m[:, :, 1] == 0.0)
    assert _rel(two.displacement_m[:, 0], one.displacement_m) <= 1e-9
    assert _rel(two.floor_displacement_m[:, :, 0], one.floor_displacement_m) <= 1e-9
    for key in ("story_drift_m", "floor_peak_acceleration_m_s2"):
        assert getattr(two, key) == pytest.approx(getattr(one, key), rel=1e-9)
    for key in ("peak_displacement_m", "peak_velocity_m_s", "superstructure_shear_coefficient",
                "base_shear_coefficient", "energy_input_J_per_kg", "energy_friction_J_per_kg",
                "energy_viscous_J_per_kg", "slip_time_s"):
        assert getattr(two, key) == pytest.approx(getattr(one, key), rel=1e-9), key
    # the y-only pair is the 1-D building with the y stiffnesses
    y_only = simulate_planar_building(np.zeros_like(acc_x), acc_x, dt, **BUILDING)
    one_y = simulate_building(acc_x, dt, direction="y", **BUILDING)
    assert _rel(y_only.floor_displacement_m[:, :, 1], one_y.floor_displacement_m) <= 1e-9
    assert y_only.story_drift_m == pytest.approx(one_y.story_drift_m, rel=1e-9)


def test_rotation_invariance(records_dir):
    # a building with equal stiffness along x and y: rotating the pair rotates the response
    (acc_x, acc_y), dt = pair_segment(records_dir, "hectormine1999_ABY", 8.0, 6.0, scale=2.0)
    s = make_superstructure([3e5, 2e5], [5e8, 3e8], [5e8, 3e8], 0.05)
    kwargs = {**BUILDING, "superstructure": s, "total_mass_kg": 8e5, "stiffness_N_per_m": 8e5 * G / 2.0}
    base = simulate_planar_building(acc_x, acc_y, dt, **kwargs)
    angle = math.radians(37.0)
    c, s_ = math.cos(angle), math.sin(angle)
    turned = simulate_planar_building(c * acc_x - s_ * acc_y, s_ * acc_x + c * acc_y, dt, **kwargs)
    assert base.n_events >= 4 and turned.event_names == base.event_names
    expected = base.displacement_m @ np.array([[c, s_], [-s_, c]])
    assert _rel(turned.displacement_m, expected) <= 1e-9
    for key in ("peak_displacement_m", "peak_velocity_m_s", "superstructure_shear_coefficient",
                "base_shear_coefficient", "energy_input_J_per_kg", "energy_friction_J_per_kg"):
        assert getattr(turned, key) == pytest.approx(getattr(base, key), rel=1e-9), key
    assert turned.story_drift_m == pytest.approx(base.story_drift_m, rel=1e-9)
    assert turned.floor_peak_acceleration_m_s2 == pytest.approx(base.floor_peak_acceleration_m_s2, rel=1e-9)


def test_whole_pair_energy_balance_and_peaks_bound_the_samples(records_dir):
    (acc_x, acc_y), dt = pair_segment(records_dir, "superstitionhills1987_PTS", 0.0, 44.6, taper_s=0.0)
    s = make_superstructure([3e5, 3e5, 2.5e5, 2.5e5, 2e5], [9e8, 8e8, 6e8, 5e8, 3e8], [7e8, 6e8, 5e8, 4e8, 3e8])
    r = simulate_planar_building(acc_x, acc_y, dt, superstructure=s, total_mass_kg=1.9e6,
                                 stiffness_N_per_m=1.9e6 * G / 2.5, mu_static=0.07, mu_kinetic=0.05,
                                 damping_Ns_per_m=2e5)
    assert r.message == "ok" and r.n_events > 10
    assert abs(r.energy_balance_error_J_per_kg) <= 1e-9 * r.energy_input_J_per_kg
    assert r.energy_history_J_per_kg[:, -1] == pytest.approx(
        [r.energy_input_J_per_kg, r.energy_friction_J_per_kg, r.energy_viscous_J_per_kg])
    assert r.peak_displacement_m >= np.max(np.hypot(*r.displacement_m.T))
    u = r.floor_displacement_m
    drift = np.linalg.norm(np.diff(np.concatenate([np.zeros((u.shape[0], 1, 2)), u], axis=1), axis=1), axis=2)
    assert np.all(r.story_drift_m >= np.max(drift, axis=0))
    assert np.all(r.story_drift_m <= 1.05 * np.max(drift, axis=0))
    acc = np.linalg.norm(r.floor_absolute_acceleration_m_s2, axis=2)
    assert np.all(r.floor_peak_acceleration_m_s2 >= np.max(acc, axis=0))
    summary = r.summary()
    assert len(summary["story_drift_ratio"]) == 5 and summary["superstructure_shear_coefficient"] > 0


def test_never_sliding_is_the_fixed_base_response_per_direction(records_dir):
    # µs large: the plane holds and each direction responds as its fixed-base building (the 1-D
    # building's stuck phase, itself checked against the modal recurrence), stiff stories included
    (acc_x, acc_y), dt = pair_segment(records_dir, "superstitionhills1987_PTS", 5.0, 10.0, scale=0.3)
    s = make_superstructure([3e5, 2e5, 1e5], [3e10, 2e10, 1e10], [2e10, 1.5e10, 1e10], 0.04)
    assert s.fixed_base_periods_s("y")[0] < 0.06
    kwargs = {"superstructure": s, "total_mass_kg": 1e6, "stiffness_N_per_m": 1e6, "mu_static": 0.95,
              "mu_kinetic": 0.9}
    r = simulate_planar_building(acc_x, acc_y, dt, **kwargs)
    assert r.n_events == 0 and np.all(r.displacement_m == 0.0)
    for d, acc in enumerate((acc_x, acc_y)):
        one = simulate_building(acc, dt, direction="xy"[d], **kwargs)
        assert _rel(r.floor_displacement_m[:, :, d], one.floor_displacement_m) <= 1e-9
    assert abs(r.energy_balance_error_J_per_kg) <= 1e-9 * r.energy_input_J_per_kg


def test_stiff_stories_converge_to_the_2d_rigid_block(records_dir):
    (acc_x, acc_y), dt = pair_segment(records_dir, "superstitionhills1987_PTS", 5.0, 15.0, taper_s=0.0)
    rigid = simulate_pair(acc_x, acc_y, dt, mu_static=0.06, mu_kinetic=0.05, radius_m=2.0)
    errors = []
    for scale in (1.0, 100.0, 1000.0):
        s = make_superstructure([3e5, 2e5], [scale * 3e8, scale * 2e8], [scale * 2e8, scale * 2e8], 0.05)
        r = simulate_planar_building(acc_x, acc_y, dt, superstructure=s, total_mass_kg=8e5,
                                     stiffness_N_per_m=8e5 * G / 2.0, mu_static=0.06, mu_kinetic=0.05)
        errors.append(_rel(r.displacement_m, rigid.displacement_m))
    assert errors[2] < 1e-3
    assert errors[1] < errors[0] / 2 and errors[2] < errors[1] / 2


def test_bearing_loads_by_hand_on_a_square():
    # four bearings on a 2 m square: P = W/4 + (M_x x_k + M_y y_k)/4 (Σ x_k² = 4), with M_d = Σ F_i,d H_i
    dt = 0.005
    t = np.arange(0.0, 6.0 + dt / 2, dt)
    acc_x = 6.0 * np.sin(2 * np.pi * 1.5 * t)
    acc_y = 4.0 * np.sin(2 * np.pi * 1.1 * t + 0.4)
    s = make_superstructure([4e5, 4e5], [4e8, 3e8], [3e8, 2e8], 0.05, heights=[5.0, 5.0])
    layout = BearingLayout(x_m=(-1.0, 1.0, 1.0, -1.0), y_m=(-1.0, -1.0, 1.0, 1.0),
                           gravity_loads_N=(2.5 * G * 1e5,) * 4)
    r = simulate_planar_building(acc_x, acc_y, dt, superstructure=s, total_mass_kg=1e6,
                                 stiffness_N_per_m=1e6 * G / 2.0, mu_static=0.1, mu_kinetic=0.08,
                                 bearing_layout=layout)
    floor_acc = r.floor_absolute_acceleration_m_s2  # (N, floors, 2)
    moment = -np.einsum("nfd,f->nd", floor_acc, np.array([4e5 * 5.0, 4e5 * 10.0]))
    assert r.overturning_moment_Nm == pytest.approx(moment, rel=1e-12, abs=1e-9 * np.max(np.abs(moment)))
    loads = r.bearing_loads()
    w4 = G * 1e6 / 4
    by_hand = w4 + (moment[:, 0] * np.array(layout.x_m)[:, None] + moment[:, 1] * np.array(layout.y_m)[:, None]) / 4
    assert loads["axial_load_N"] == pytest.approx(by_hand, rel=1e-12, abs=1e-6 * w4)
    # the exact extremes bound the sampled loads and exceed them by little
    assert np.all(np.array(loads["bearing_axial_load_max_N"]) >= by_hand.max(axis=1))
    assert np.all(np.array(loads["bearing_axial_load_min_N"]) <= by_hand.min(axis=1))
    assert np.all(np.array(loads["bearing_axial_load_max_N"]) <= by_hand.max(axis=1) + 1e-3 * np.ptp(by_hand))
    assert loads["n_bearings_uplifted"] == int(np.sum(np.array(loads["bearing_axial_load_min_N"]) < 0))
    assert loads["n_bearings_uplifted"] >= 1
    assert r.summary()["n_bearings_uplifted"] == loads["n_bearings_uplifted"]


def test_pair_with_a_design_runs_end_to_end(records_dir, tmp_path):
    # the registry, the analysis and `isolator simulate --pair --design --json` run the 2-D building
    import json

    from typer.testing import CliRunner

    from isolator.analysis import analyse
    from isolator.cli import app
    from isolator.design import Design
    from isolator.motion import MotionPair, read_ground_motion

    from .test_building_registry import BUILDING_KEYS, TOML

    design_file = tmp_path / "building.toml"
    design_file.write_text(TOML)
    folder = records_dir / "pairs" / "hectormine1999_ABY"
    x_path, y_path = sorted(folder.glob("*.AT2"))
    design = Design.from_toml(design_file)
    pair = MotionPair(read_ground_motion(x_path), read_ground_motion(y_path))
    data = analyse(design, pair, harmonic=False).to_dict()
    assert data["model"] == "2d-building"
    flat = data if "story_drift_ratio" in data else {**data, **data.get("response", {})}
    assert BUILDING_KEYS <= flat.keys() and len(flat["bearing_axial_load_max_N"]) == 4
    direct = simulate_planar_building(pair.x.acceleration_m_s2, pair.y.acceleration_m_s2, pair.dt_s,
                                      superstructure=design.superstructure, total_mass_kg=design.mass_kg,
                                      stiffness_N_per_m=design.stiffness_N_per_m, mu_static=design.mu_static,
                                      mu_kinetic=design.mu_kinetic, damping_Ns_per_m=design.damping_Ns_per_m,
                                      bearing_layout=design.bearing_layout)
    assert flat["story_drift_m"] == pytest.approx(direct.story_drift_m.tolist(), rel=1e-12)
    result = CliRunner().invoke(app, ["simulate", str(x_path), "--pair", str(y_path), "--design", str(design_file),
                                      "--json"])
    assert result.exit_code == 0, result.output
    cli = json.loads(result.stdout)
    assert cli["model"] == "2d-building" and BUILDING_KEYS <= cli.keys()
    assert cli["bearing_axial_load_min_N"] == pytest.approx(direct.bearing_axial_load_min_N, rel=1e-12)


def test_unequal_steps_mirror_and_bad_input(records_dir):
    # samples inserted on the straight line between samples change nothing (the same piecewise-linear
    # signal): the non-uniform path equals the uniform one; y → −y mirrors the response exactly
    from isolator.errors import RecordInputError

    (acc_x, acc_y), dt = pair_segment(records_dir, "hectormine1999_ABY", 8.0, 4.0, scale=2.0)
    uniform = simulate_planar_building(acc_x, acc_y, dt, **BUILDING)
    t = dt * np.arange(acc_x.size)
    extra = np.sort(np.random.default_rng(5).uniform(t[0], t[-1], 150))
    t_all = np.union1d(t, extra)
    dense = simulate_planar_building(np.interp(t_all, t, acc_x), np.interp(t_all, t, acc_y), time_s=t_all,
                                     **BUILDING)
    keep = np.searchsorted(t_all, t)
    assert uniform.n_events >= 4 and dense.event_names == uniform.event_names
    assert np.max(np.abs(dense.event_time_s - uniform.event_time_s)) <= 1e-9
    assert _rel(dense.displacement_m[keep], uniform.displacement_m) <= 1e-9
    assert _rel(dense.floor_displacement_m[keep], uniform.floor_displacement_m) <= 1e-9
    assert dense.story_drift_m == pytest.approx(uniform.story_drift_m, rel=1e-9)
    assert dense.energy_input_J_per_kg == pytest.approx(uniform.energy_input_J_per_kg, rel=1e-9)
    mirrored = simulate_planar_building(acc_x, -acc_y, dt, **BUILDING)
    assert np.array_equal(mirrored.displacement_m[:, 0], uniform.displacement_m[:, 0])
    assert np.array_equal(mirrored.displacement_m[:, 1], -uniform.displacement_m[:, 1])
    assert np.array_equal(mirrored.story_drift_m, uniform.story_drift_m)
    with pytest.raises(RecordInputError, match="differ in length"):
        simulate_planar_building(acc_x, acc_y[:-1], dt, **BUILDING)
    with pytest.raises(RecordInputError, match="NaN"):
        simulate_planar_building(acc_x, np.full_like(acc_y, np.nan), dt, **BUILDING)


def test_no_friction_no_spring_is_a_free_linear_system(records_dir):
    # µ = 0 and no pendulum: no horizontal force on the system, so the total relative momentum is
    # −M_total × the ground velocity in each direction (exact trapezoid of the piecewise-linear record)
    (acc_x, acc_y), dt = pair_segment(records_dir, "hectormine1999_ABY", 8.0, 6.0, taper_s=0.0)
    masses = np.array([3e5, 2e5, 1e5])
    total = 9e5
    r = simulate_planar_building(acc_x, acc_y, dt, superstructure=make_superstructure(masses, [5e8, 4e8, 2e8]),
                                 total_mass_kg=total, stiffness_N_per_m=0.0, mu_static=0.0)
    for d, acc in enumerate((acc_x, acc_y)):
        ground_velocity = np.concatenate([[0.0], np.cumsum(0.5 * (acc[1:] + acc[:-1]) * dt)])
        momentum = total * r.velocity_m_s[:, d] + r.floor_velocity_m_s[:, :, d] @ masses
        assert _rel(momentum, -total * ground_velocity) <= 1e-10
    assert abs(r.energy_balance_error_J_per_kg) <= 1e-9 * r.energy_input_J_per_kg
    assert r.energy_friction_J_per_kg == 0.0 and r.message == "ok"


# ---- a vertical (N(t) = W (1 + a_z/g)) and µ(v) with a superstructure ----
def triple_segment(records_dir, folder, names, start_s, duration_s, scale=1.0, taper_s=0.2):
    """x, y, z of a station (scaled alike, tapered from rest) and dt."""
    from isolator.motion import read_ground_motion

    motions = [read_ground_motion(records_dir / "pairs" / folder / name) for name in names]
    dt = motions[0].dt_s
    i0 = int(round(start_s / dt))
    n = min(int(round(duration_s / dt)) + 1, *(m.npts - i0 for m in motions))
    ramp = np.minimum(1.0, np.arange(n) * dt / taper_s)
    return [scale * ramp * m.acceleration_m_s2[i0:i0 + n] for m in motions], dt


APEEL2 = ("lomaprieta1989_APEEL2", ["np01002p_4225a_a.smc", "np01002p_4225c_a.smc", "np01002p_4225b_a.smc"])
VERTICAL_CASES = {
    # name: start, duration, scale, masses, kx, ky, ζ, total mass, pendulum R or spring K, c_iso, µs, µk or law,
    # with the vertical
    "2 stories, pendulum, vertical": (5.0, 2.5, 1.0, [3e5, 2e5], [6e8, 3e8], [4e8, 3.5e8], 0.05, 7e5,
                                      {"radius_m": 2.0}, 0.0, 0.06, 0.045, True),
    "1 story, spring + dashpot, vertical, µ(v)": (5.0, 2.5, 1.0, [4e5], [3e8], [2e8], 0.03, 6e5,
                                                  {"stiffness_N_per_m": 1.5e6}, 1.0e5, 0.07, (0.04, 0.065, 25.0),
                                                  True),
    "3 stories, pendulum, µ(v), no vertical": (5.0, 2.5, 1.0, [2e5] * 3, [8e8, 6e8, 4e8], [5e8, 4e8, 3e8], 0.05,
                                               9e5, {"radius_m": 3.0}, 0.0, 0.06, (0.035, 0.06, 40.0), False),
}


def _run_vertical_case(records_dir, name):
    start, duration, scale, masses, kx, ky, zeta, total, spring, c_iso, mu_s, mu_k, vertical = VERTICAL_CASES[name]
    (acc_x, acc_y, acc_z), dt = triple_segment(records_dir, APEEL2[0], APEEL2[1], start, duration, scale)
    pendulum = "radius_m" in spring
    k_iso = total * G / spring["radius_m"] if pendulum else spring["stiffness_N_per_m"]
    law = mu_k if isinstance(mu_k, tuple) else None
    friction = dict(mu_kinetic=mu_k) if law is None else dict(mu_slow=law[0], mu_fast=law[1], rate_s_per_m=law[2])
    ours = simulate_planar_building(acc_x, acc_y, dt, superstructure=make_superstructure(masses, kx, ky, zeta),
                                    total_mass_kg=total, stiffness_N_per_m=k_iso, mu_static=mu_s,
                                    damping_Ns_per_m=c_iso, az_m_s2=acc_z if vertical else None, pendulum=pendulum,
                                    **friction)
    # rtol 1e-13 and DOP853 at low speed too: the reference's Radau steps near the stops erred on the µ(v) case,
    # erratically with scipy's release (1.17.0: 8.1e-9 of the peak at 1e-12; 1.17.1: 1.2e-8 of the peak velocity
    # 1e-4 s after the 0.1049 s breakaway at 1e-13 and 3e-14, BDF at 1e-13 the same, while ours and the reference's
    # DOP853 or LSODA at 1e-12 / 1e-13 agree to 5e-13; session 18)
    ref = reference_planar_building(acc_x, acc_y, dt, masses, kx, ky, zeta, total, k_iso, c_iso, mu_s,
                                    None if law else mu_k, acc_z=acc_z if vertical else None, pendulum=pendulum,
                                    law=law, rtol=1e-13, slow_method="DOP853")
    return ours, ref, acc_z


@pytest.mark.parametrize("name", list(VERTICAL_CASES))
def test_a_vertical_and_mu_v_against_solve_ivp(records_dir, name):
    """N(t) and µ(v) enter the series pieces as products (ν linear within a sample; e^{−a|V|} by its own
    recurrence): exact to the series' truncation; here ≤ 1e-9 of the peaks against the reference."""
    ours, ref, acc_z = _run_vertical_case(records_dir, name)
    assert ours.message == "ok"
    assert ours.n_fast_steps > 0, "stuck, the exact propagators run with a vertical or µ(v) too"
    assert ours.n_events >= 1 and ours.slip_time_s > 0.2, "the case must slide"
    assert np.max(np.abs(acc_z)) > 0.5, "the vertical must matter (ν = 1 ± 0.085)"
    assert ours.event_names == [kind for _, kind in ref["events"]]
    assert np.max(np.abs(ours.event_time_s - [t for t, _ in ref["events"]])) <= 1e-8
    assert _rel(ours.displacement_m, ref["X"]) <= 1e-9
    assert _rel(ours.velocity_m_s, ref["V"]) <= 1e-9
    assert _rel(ours.floor_displacement_m, ref["u"]) <= 1e-9
    assert ours.peak_displacement_m == pytest.approx(ref["peak_x"], rel=1e-9)
    assert ours.story_drift_m == pytest.approx(ref["drift_peak"], rel=1e-9)
    e_in, e_f, e_v = ref["energy"] / ours.building.total_mass_kg
    assert ours.energy_input_J_per_kg == pytest.approx(e_in, rel=1e-9)
    assert ours.energy_friction_J_per_kg == pytest.approx(e_f, rel=1e-9)
    assert ours.energy_viscous_J_per_kg == pytest.approx(e_v, rel=1e-9, abs=1e-12 * e_in)
    assert abs(ours.energy_balance_error_J_per_kg) <= 1e-9 * ours.energy_input_J_per_kg


def test_a_zero_vertical_and_equal_mu_v_give_the_constant_answer(records_dir):
    """A zero vertical: bit for bit the run without one; µ_slow = µ_fast: the constant-µ run (another path:
    series pieces while sliding against the fast sub-steps) to ≤ 1e-11."""
    (acc_x, acc_y, _), dt = triple_segment(records_dir, APEEL2[0], APEEL2[1], 3.0, 3.0, 2.0)
    common = dict(superstructure=make_superstructure([3e5, 2e5], [6e8, 3e8], [4e8, 3.5e8]), total_mass_kg=7e5,
                  stiffness_N_per_m=7e5 * G / 2.0, mu_static=0.06, pendulum=True)
    plain = simulate_planar_building(acc_x, acc_y, dt, mu_kinetic=0.045, **common)
    zero = simulate_planar_building(acc_x, acc_y, dt, mu_kinetic=0.045, az_m_s2=np.zeros_like(acc_x), **common)
    assert plain.n_events >= 2
    for key in ("displacement_m", "velocity_m_s", "floor_displacement_m", "isolator_force_N", "event_time_s"):
        assert np.array_equal(getattr(plain, key), getattr(zero, key))
    assert plain.energy_input_J_per_kg == zero.energy_input_J_per_kg
    same = simulate_planar_building(acc_x, acc_y, dt, mu_slow=0.045, mu_fast=0.045, rate_s_per_m=30.0, **common)
    # µ(v) slides by series pieces only (stuck it takes the propagators): another path while sliding
    assert 0 < same.n_fast_steps < plain.n_fast_steps and same.n_pieces_by_phase[2] > plain.n_pieces_by_phase[2]
    assert same.event_names == plain.event_names
    assert np.max(np.abs(same.event_time_s - plain.event_time_s)) <= 1e-11
    for key in ("displacement_m", "velocity_m_s", "floor_displacement_m"):
        assert _rel(getattr(same, key), getattr(plain, key)) <= 1e-11
    assert same.energy_input_J_per_kg == pytest.approx(plain.energy_input_J_per_kg, rel=1e-11)


def test_the_vertical_is_checked():
    """Uplift (g + a_z ≤ 0) and a half-given µ(v) are refused in one line."""
    from isolator.errors import InvalidSystemError

    acc = np.array([0.0, 1.0, -1.0, 0.0])
    common = dict(superstructure=make_superstructure([3e5], [6e8]), total_mass_kg=7e5, stiffness_N_per_m=1e6,
                  mu_static=0.06)
    with pytest.raises(InvalidSystemError, match="lifts the building"):
        simulate_planar_building(acc, acc, 0.01, az_m_s2=np.array([0.0, -10.0, 0.0, 0.0]), **common)
    with pytest.raises(InvalidSystemError, match="missing rate_s_per_m"):
        simulate_planar_building(acc, acc, 0.01, mu_slow=0.03, mu_fast=0.05, **common)
    with pytest.raises(InvalidSystemError, match="must not exceed mu_static"):
        simulate_planar_building(acc, acc, 0.01, mu_slow=0.07, mu_fast=0.08, rate_s_per_m=10.0, **common)


def test_the_bearing_loads_carry_the_vertical(records_dir):
    """P_k = P_k,g (1 + a_z/g) + ΔP_k,x M_x + ΔP_k,y M_y: the histories by hand from the response's moments and the
    vertical, and the exact extremes (located between samples, the vertical's share included) bound them within 2 %."""
    from pathlib import Path

    from isolator.design import Design

    design = Design.from_toml(Path(__file__).resolve().parents[2] / "data" / "example_building.toml")
    (acc_x, acc_y, acc_z), dt = triple_segment(records_dir, APEEL2[0], APEEL2[1], 5.5, 1.5, 2.5)
    g = design.gravity_m_s2
    r = simulate_planar_building(acc_x, acc_y, dt, superstructure=design.superstructure,
                                 total_mass_kg=design.mass_kg, stiffness_N_per_m=design.mass_kg * g / design.radius_m,
                                 mu_static=design.mu_static, mu_kinetic=design.mu_kinetic, az_m_s2=acc_z,
                                 pendulum=True, bearing_layout=design.bearing_layout)
    layout = design.bearing_layout
    loads = r.bearing_loads()
    by_hand = (np.asarray(layout.gravity_loads_N)[:, None] * (1.0 + acc_z / g)[None, :]
               + layout.overturning_coefficients("x")[:, None] * r.overturning_moment_Nm[:, 0][None, :]
               + layout.overturning_coefficients("y")[:, None] * r.overturning_moment_Nm[:, 1][None, :])
    share = np.asarray(layout.gravity_loads_N)[:, None] * (acc_z / g)[None, :]
    assert np.max(np.abs(share)) > 0.05 * np.max(np.abs(by_hand - np.asarray(layout.gravity_loads_N)[:, None]))
    assert np.max(np.abs(loads["axial_load_N"] - by_hand)) <= 1e-9 * np.max(layout.gravity_loads_N)
    high = np.asarray(loads["bearing_axial_load_max_N"])
    low = np.asarray(loads["bearing_axial_load_min_N"])
    assert np.all(high >= by_hand.max(axis=1) - 1e-9 * high) and np.all(high <= 1.02 * by_hand.max(axis=1))
    assert np.all(low <= by_hand.min(axis=1) + 1e-9 * high) and np.all(low >= by_hand.min(axis=1) - 0.02 * high)


def test_the_reason_names_the_scene_features_that_chose_the_2d_building(records_dir):
    """The registry's reason for the 2-D building says which of the pair, the vertical and µ(v) chose it (a pair with a
    vertical used to print "two horizontal components" only); the run through the registry reports the same reason."""
    from pathlib import Path

    from isolator.design import Design
    from isolator.solver.base import Scene
    from isolator.solver.models import select_model, simulate

    design = Design.from_toml(Path(__file__).resolve().parents[2] / "data" / "example_building.toml")
    acc = np.array([0.0, 0.3, -0.2, 0.1])
    constant = {"mu_static": 0.06, "mu_kinetic": 0.05, "radius_m": 2.5}
    rate = {"mu_static": 0.06, "mu_kinetic": 0.05, "mu_slow": 0.04, "mu_fast": 0.06, "rate_s_per_m": 20.0,
            "radius_m": 2.5}
    cases = {  # (ay, az, isolator) → the features the reason must name, and those it must not
        "pair": ((acc, None, constant), ["two horizontal"], ["vertical", "µ(v)"]),
        "pair+vertical": ((acc, acc, constant), ["two horizontal", "vertical"], ["µ(v)"]),
        "one+vertical": ((None, acc, constant), ["one horizontal", "vertical"], ["two horizontal", "µ(v)"]),
        "one+mu(v)": ((None, None, rate), ["one horizontal", "µ(v)"], ["two horizontal", "vertical"]),
        "pair+vertical+mu(v)": ((acc, acc, rate), ["two horizontal", "vertical", "µ(v)"], []),
    }
    for label, ((ay, az, iso), said, unsaid) in cases.items():
        name, reason = select_model(Scene(ax_m_s2=acc, ay_m_s2=ay, az_m_s2=az, dt_s=0.01, isolator=iso,
                                          design=design))
        assert name == "2d-building", label
        assert all(word in reason for word in said) and not any(word in reason for word in unsaid), (label, reason)
    (acc_x, acc_y, acc_z), dt = triple_segment(records_dir, APEEL2[0], APEEL2[1], 5.5, 0.5, 1.0)
    scene = Scene(ax_m_s2=acc_x, ay_m_s2=acc_y, az_m_s2=acc_z, dt_s=dt, isolator=constant, design=design)
    run = simulate(scene)
    assert run.model == "2d-building" and run.model_reason == select_model(scene)[1]
    assert "vertical" in run.model_reason


def test_a_vertical_stuck_by_the_propagators_equals_the_series_pieces(records_dir):
    """With a vertical the stuck intervals go by the exact propagators (the floors' fixed-base system; the
    break-away limit µs N(τ) in the event test, the vertical's work and a bearing's P_g a_z/g added): the same
    record with samples inserted on its straight lines runs series pieces only (the non-uniform path) and must
    agree to 1e-9 in the histories, events, energies and the bearing loads' exact extremes."""
    from pathlib import Path

    from isolator.design import Design

    design = Design.from_toml(Path(__file__).resolve().parents[2] / "data" / "example_building.toml")
    (acc_x, acc_y, acc_z), dt = triple_segment(records_dir, APEEL2[0], APEEL2[1], 8.0, 3.0, 1.0)
    g = design.gravity_m_s2
    common = dict(superstructure=design.superstructure, total_mass_kg=design.mass_kg,
                  stiffness_N_per_m=design.mass_kg * g / design.radius_m, mu_static=design.mu_static,
                  mu_kinetic=design.mu_kinetic, pendulum=True, bearing_layout=design.bearing_layout)
    uniform = simulate_planar_building(acc_x, acc_y, dt, az_m_s2=acc_z, **common)
    t = dt * np.arange(acc_x.size)
    t_all = np.union1d(t, np.sort(np.random.default_rng(3).uniform(t[0], t[-1], 40)))
    dense = simulate_planar_building(*(np.interp(t_all, t, a) for a in (acc_x, acc_y)), time_s=t_all,
                                     az_m_s2=np.interp(t_all, t, acc_z), **common)
    keep = np.searchsorted(t_all, t)
    assert uniform.n_fast_steps > 100 and uniform.n_pieces_by_phase[0] < uniform.n_fast_steps
    assert dense.n_fast_steps == 0 and uniform.n_events >= 6 and uniform.slip_time_s > 0.2
    assert dense.event_names == uniform.event_names
    assert np.max(np.abs(dense.event_time_s - uniform.event_time_s)) <= 1e-9
    assert _rel(dense.displacement_m[keep], uniform.displacement_m) <= 1e-9
    assert _rel(dense.floor_displacement_m[keep], uniform.floor_displacement_m) <= 1e-9
    assert dense.story_drift_m == pytest.approx(uniform.story_drift_m, rel=1e-9)
    assert dense.energy_input_J_per_kg == pytest.approx(uniform.energy_input_J_per_kg, rel=1e-9)
    assert abs(uniform.energy_balance_error_J_per_kg) <= 1e-9 * uniform.energy_input_J_per_kg
    fine, coarse = dense.bearing_loads(), uniform.bearing_loads()
    scale = max(design.bearing_layout.gravity_loads_N)
    for key in ("bearing_axial_load_max_N", "bearing_axial_load_min_N"):
        assert np.max(np.abs(np.subtract(fine[key], coarse[key]))) <= 1e-9 * scale, key
