"""An independent reference for the 2-D building bench: the building under a pair, by ``solve_ivp`` with events.

Shares no code with the engines (``isolator.solver.planar_building*``, ``isolator.solver.building*``)
nor with :mod:`isolator.bench.building_reference` (the 1-D one, written with the full mass matrix):
the equations of docs/building.md in two horizontal directions, written with the slab's own
equation solved for its acceleration.  Per direction d (x, y), x_b the slab's displacement
relative to the ground, u the floors' displacements relative to the slab, a_g the ground's:

* the floors:   m_i (ü_i + ẍ_b + a_g) = −(C_d u̇ + K_d u)_i;
* the slab:     m_b ẍ_b = D − f,  D = −m_b a_g − K x_b + 1ᵀ(K_d u + C_d u̇)  (the force that holds
  the slab still), f the friction: µk W v_b/|v_b| while sliding (W = g M, the whole weight);
* stuck (v_b = 0, ẍ_b = 0) while |D| ≤ µs W (the Euclidean norm: coupled friction);
* a stop (|v_b| → 0): stuck if |D| ≤ µs W, otherwise a new start along D.

Method (as the rigid block's :mod:`isolator.bench.planar_reference`): scipy ``solve_ivp``
restarted at every sample (the record is linear in between, no step straddles its kinks),
in Cartesian form:

* stuck: DOP853 (rtol 1e-12) on the floors with a terminal event |D|² = (µs W)² (rising);
* a start from rest: DOP853 with the friction along e = D/|D| at the break-away, until
  |v_b| = 10 ``v_eps`` (``v_eps`` = 1e-13 m/s): the direction of the slab's acceleration
  (D − f)/m_b is e there, and the slab's velocity stays below 1e-12 m/s while the direction is
  frozen, so the floors feel no more than that;
* fast sliding (|v_b| ≥ ``v_switch`` = 1 mm/s): DOP853 at rtol 1e-12, terminal event
  |v_b| = v_switch (falling);
* slow sliding (|v_b| < v_switch, where v_b/|v_b| makes the equations stiff): Radau (implicit,
  L-stable, with its exact Jacobian) at rtol 1e-12 with terminal events |v_b| = v_switch
  (rising) and |v_b| = v_eps (falling: the stop).  At the stop the slab is set to rest where it
  is: it would travel v_eps h/2 more over the time h it needs to stop, and the floors feel a
  slab acceleration off by its deceleration over h, a velocity of v_eps at most.  (Finishing
  the stop at constant deceleration instead moved the floors at constant acceleration over h,
  which is long when the net force nearly vanishes — µs = µk at a stop — and cost 1e-8 of the
  peaks: found by turning the pair, see the tests.)

Its own error: linear in ``v_eps`` (the stop instants are early by v_eps/|deceleration|):
on 3 s of the PTS pair ×2, 2.8e-10 of the peak floor acceleration at v_eps = 1e-11, 2.7e-11
at 1e-12, 2.5e-12 at 1e-13 (each against 1e-14); against the exact 1-D engine on a collinear
pair (20 s of NWH360) 3e-14 of the slab's peak, 2e-13 of the floors', 5e-12 of the floor
accelerations (tests/bench/test_bench_planar_building.py checks it against the 1-D reference,
and its rotation invariance, to 1e-9): enough to bound an exact engine's, far below OpenSees'.
"""

from __future__ import annotations

import math

import numpy as np

#: relative tolerance of the integrations [-]
REFERENCE_RTOL = 1e-12
#: a start ends at this multiple of v_eps, so that the sliding form begins above its stop threshold v_eps
START_SPEED_FACTOR = 10.0
#: bound on the phases within one sample interval (starts, stops, form switches)
MAX_PHASES_PER_INTERVAL = 2000


def planar_building_reference(ax_m_s2, ay_m_s2, dt_s: float, *, masses_kg, stiffness_matrices,
                              damping_matrices, total_mass_kg: float, isolator_stiffness_N_per_m: float,
                              mu_static: float, mu_kinetic: float, gravity_m_s2: float,
                              rtol: float = REFERENCE_RTOL, v_eps: float = 1e-13, v_switch: float = 1e-3) -> dict:
    """Histories of the 2-D building at the samples, by event-located ``solve_ivp``.

    Parameters
    ----------
    ax_m_s2, ay_m_s2 : array_like
        Ground acceleration along x and y [m/s²], linear between samples at ``dt_s`` [s].
    masses_kg : array_like
        m_i, bottom to top [kg].
    stiffness_matrices, damping_matrices : tuple of array_like
        (K_x, K_y) [N/m] and (C_x, C_y) [N·s/m] on the floors' displacements relative to the slab.
    total_mass_kg : float
        M [kg]; W = g M.
    isolator_stiffness_N_per_m : float
        K = W/R [N/m], the same in every direction.
    mu_static, mu_kinetic : float
        Friction coefficients [-].
    gravity_m_s2 : float
        g [m/s²].
    rtol : float
        Relative tolerance of every integration [-].
    v_eps, v_switch : float
        Speed of a start's end and a stop's finish, and of the switch between the slow and the
        fast form [m/s].

    Returns
    -------
    dict
        ``slab_displacement_m`` (N, 2), ``floor_displacement_m`` (N, n, 2) relative to the slab,
        ``floor_absolute_acceleration_m_s2`` (N, n, 2), ``n_starts``, ``n_stops``, ``events``
        (a list of (time [s], kind): "start", "stop", "stop and restart", "turned back").

    Raises
    ------
    RuntimeError
        When an integration fails or a sample interval needs more than
        :data:`MAX_PHASES_PER_INTERVAL` phases.
    """
    from scipy.integrate import solve_ivp

    ground = np.column_stack([np.asarray(ax_m_s2, dtype=float), np.asarray(ay_m_s2, dtype=float)])
    m = np.asarray(masses_kg, dtype=float)
    k_s = [np.asarray(k, dtype=float) for k in stiffness_matrices]
    c_s = [np.asarray(c, dtype=float) for c in damping_matrices]
    n = m.size
    m_b = total_mass_kg - m.sum()
    weight = gravity_m_s2 * total_mass_kg
    k_iso = isolator_stiffness_N_per_m
    # state y: x_b (2), v_b (2), u (n × 2, floor-major), u̇ (n × 2); the system is linear but for the
    # friction: y' = A y + G a_g + P f, with A, G per phase and f the friction force on the slab (2,) [N]
    size = 4 + 4 * n
    xb, vb, uu, ud = slice(0, 2), slice(2, 4), slice(4, 4 + 2 * n), slice(4 + 2 * n, size)
    story = np.zeros((2 * n, size))  # (K_d u + C_d u̇)_i along d is row 2i + d of story @ y
    for d in range(2):
        story[d::2, 4 + d:4 + 2 * n:2] = k_s[d]
        story[d::2, 4 + 2 * n + d::2] = c_s[d]
    hold = np.zeros((2, size))  # D = hold @ y − m_b a_g
    for d in range(2):
        hold[d, d] = -k_iso
        hold[d] += story[d::2].sum(axis=0)
    per_floor_mass = np.repeat(m, 2)[:, None]
    a_stuck = np.zeros((size, size))
    a_stuck[uu, ud] = np.eye(2 * n)
    a_stuck[ud] = -story / per_floor_mass
    a_slide = a_stuck.copy()
    a_slide[xb, vb] = np.eye(2)
    a_slide[vb] = hold / m_b
    a_slide[ud] -= np.tile(hold / m_b, (n, 1))
    g_stuck = np.zeros((size, 2))
    g_stuck[ud] = np.tile(-np.eye(2), (n, 1))
    g_slide = np.zeros((size, 2))
    g_slide[vb] = -np.eye(2)
    p_friction = np.zeros((size, 2))  # the friction force's share: −f/m_b on the slab, +f/m_b on the floors
    p_friction[vb] = -np.eye(2) / m_b
    p_friction[ud] = np.tile(np.eye(2) / m_b, (n, 1))
    friction_force = mu_kinetic * weight

    def story_forces(y):
        """(K_d u + C_d u̇) per floor and direction, (n, 2) [N]."""
        return (story @ y).reshape(n, 2)

    def holding(y, a_g):
        """D, the force on the slab other than friction (2,) [N]."""
        return hold @ y - m_b * a_g

    def friction(y, mode, direction):
        """f (2,) [N]: along ``direction`` at a start, along v_b while sliding."""
        if mode == "start":
            return friction_force * direction
        speed = math.hypot(y[2], y[3])
        return friction_force * y[vb] / speed if speed > 0.0 else np.zeros(2)

    def slab_acceleration(y, a_g, mode, direction):
        """ẍ_b (2,) [m/s²] in ``mode``: "stuck", "start" (friction along ``direction``), "slide"."""
        if mode == "stuck":
            return np.zeros(2)
        return (holding(y, a_g) - friction(y, mode, direction)) / m_b

    def floor_accelerations(y, a_g, slab_acc):
        """ü (n, 2), relative to the slab [m/s²]."""
        return -story_forces(y) / m[:, None] - a_g - slab_acc

    def rhs(t, y, a0, slope, mode, direction):
        a_g = a0 + slope * t
        if mode == "stuck":
            return a_stuck @ y + g_stuck @ a_g
        return a_slide @ y + g_slide @ a_g + p_friction @ friction(y, mode, direction)

    def jacobian(t, y, a0, slope, mode, direction):
        """∂y'/∂y while sliding: A + P ∂f/∂v_b, ∂f/∂v_b = µk W (I − e eᵀ)/|v_b|."""
        speed = math.hypot(y[2], y[3])
        e = y[vb] / speed
        out = a_slide.copy()
        out[:, vb] += p_friction @ (friction_force / speed * (np.eye(2) - np.outer(e, e)))
        return out

    def terminal(function, direction):
        function.terminal, function.direction = True, direction
        return function

    def speed_reaches(level, direction):
        """A terminal event: |v_b| crosses ``level`` [m/s] in ``direction``."""
        return terminal(lambda s, z, *_: math.hypot(z[2], z[3]) - level, direction)

    y = np.zeros(size)
    mode, direction = "stuck", np.zeros(2)
    slow = True
    n_starts = n_stops = 0
    events_log = []  # (time [s], kind)
    out_y = np.zeros((ground.shape[0], y.size))
    out_acc = np.zeros((ground.shape[0], n, 2))
    out_acc[0] = ground[0] + floor_accelerations(y, ground[0], np.zeros(2))

    def start(y, t, a0, slope):
        """A start from rest along D: (mode, direction)."""
        d = holding(y, a0 + slope * t)
        return "start", d / np.linalg.norm(d)

    for i in range(ground.shape[0] - 1):
        a0, slope = ground[i], (ground[i + 1] - ground[i]) / dt_s
        t = 0.0
        for _ in range(MAX_PHASES_PER_INTERVAL):
            if t >= dt_s:
                break
            if mode == "stuck":
                def breakaway(s, z, a0, slope, *_):
                    d = holding(z, a0 + slope * s)
                    return d @ d - (mu_static * weight) ** 2
                if breakaway(t, y, a0, slope) > 0.0:  # already beyond: a start at once
                    mode, direction = start(y, t, a0, slope)
                    n_starts += 1
                    events_log.append((i * dt_s + t, "start"))
                    continue
                method, events = "DOP853", [terminal(breakaway, 1.0)]
            elif mode == "start":
                events = [speed_reaches(START_SPEED_FACTOR * v_eps, 1.0),
                          terminal(lambda s, z, a0, slope, mode, e: z[2] * e[0] + z[3] * e[1], -1.0)]
                method = "DOP853"
            else:
                if slow:
                    events = [speed_reaches(v_switch, 1.0), speed_reaches(v_eps, -1.0)]
                    method = "Radau"
                else:
                    events = [speed_reaches(v_switch, -1.0)]
                    method = "DOP853"
            sol = solve_ivp(rhs, (t, dt_s), y, method=method, rtol=rtol, atol=1e-15, events=events,
                            args=(a0, slope, mode, direction), **({"jac": jacobian} if method == "Radau" else {}))
            if sol.status < 0:
                raise RuntimeError(f"reference: solve_ivp failed near sample {i}: {sol.message}")
            y = sol.y[:, -1].copy()
            if sol.status == 0:
                break
            t = float(sol.t[-1])
            fired = [k for k, times in enumerate(sol.t_events) if len(times)]
            if mode == "stuck":
                mode, direction = start(y, t, a0, slope)
                n_starts += 1
                events_log.append((i * dt_s + t, "start"))
            elif mode == "start":
                if fired[0] == 0:  # reached v_eps: sliding
                    mode, slow = "slide", True
                else:  # the slab turned back before v_eps: a stop
                    y[vb] = 0.0
                    n_stops += 1
                    mode = "stuck"
                    events_log.append((i * dt_s + t, "turned back"))
            elif not slow or fired[0] == 0:  # a switch between the fast and the slow form
                slow = not slow
            else:  # the stop: |v_b| = v_eps; the slab stops here (see the module's docstring)
                y[vb] = 0.0
                n_stops += 1
                d = holding(y, a0 + slope * t)
                if d @ d <= (mu_static * weight) ** 2:
                    mode = "stuck"
                    events_log.append((i * dt_s + t, "stop"))
                else:
                    mode, direction = start(y, t, a0, slope)
                    n_starts += 1
                    events_log.append((i * dt_s + t, "stop and restart"))
        else:
            raise RuntimeError(f"reference: more than {MAX_PHASES_PER_INTERVAL} phases in sample interval {i}")
        out_y[i + 1] = y
        slab_acc = slab_acceleration(y, ground[i + 1], mode, direction)
        out_acc[i + 1] = ground[i + 1] + slab_acc + floor_accelerations(y, ground[i + 1], slab_acc)
    return {"slab_displacement_m": out_y[:, xb], "floor_displacement_m": out_y[:, uu].reshape(-1, n, 2),
            "floor_absolute_acceleration_m_s2": out_acc, "n_starts": n_starts, "n_stops": n_stops,
            "events": events_log}
