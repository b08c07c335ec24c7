"""An independent reference for the building bench: the 1-D building by ``solve_ivp`` with events.

Shares no code with :mod:`isolator.solver.building` (nor with its kernel): the equations of
docs/building.md written in the slab's and floors' coordinates q = [x_b, u_1 … u_n] with the
full mass matrix [[M, mᵀ], [m, diag(m)]], integrated by scipy's DOP853 at rtol 1e-12 sample
interval by sample interval (the record linear in between), stuck and sliding phases switched
at located events: a stuck slab breaks away when the holding force
D = −m_b a_g − K x_b + 1ᵀ(K_s u + C_s u̇) reaches ±µs W; a sliding slab stops at ẋ_b = 0,
then sticks if |D| ≤ µs W, else slides on the other way.  Its own error is ~1e-11 of the
peaks (rtol 1e-12 over a few hundred events), far below OpenSees' and enough to bound ours.
"""

from __future__ import annotations

import math

import numpy as np

#: relative tolerance of the reference's DOP853 integration [-]
REFERENCE_RTOL = 1e-12
#: bound on the phases within one sample interval (events per interval)
MAX_PHASES_PER_INTERVAL = 1000


def building_reference(acceleration_m_s2, dt_s: float, *, masses_kg, stiffness_matrix, damping_matrix,
                       total_mass_kg: float, isolator_stiffness_N_per_m: float, mu_static: float,
                       mu_kinetic: float, gravity_m_s2: float, rtol: float = REFERENCE_RTOL) -> dict:
    """Histories of the 1-D building at the samples, by event-located ``solve_ivp``.

    Parameters
    ----------
    acceleration_m_s2 : array_like
        Ground acceleration [m/s²], linear between samples at ``dt_s`` [s].
    masses_kg : array_like
        m_i, bottom to top [kg].
    stiffness_matrix, damping_matrix : array_like
        K_s [N/m] and C_s [N·s/m] on the floors' displacements relative to the slab.
    total_mass_kg : float
        M [kg]; W = g M.
    isolator_stiffness_N_per_m : float
        K = W/R [N/m].
    mu_static, mu_kinetic : float
        Friction coefficients [-].
    gravity_m_s2 : float
        g [m/s²].

    Returns
    -------
    dict
        ``slab_displacement_m`` (N,), ``floor_displacement_m`` (N, n) relative to the slab,
        ``floor_absolute_acceleration_m_s2`` (N, n), ``n_events``.
    """
    from scipy.integrate import solve_ivp

    acc = np.asarray(acceleration_m_s2, dtype=float)
    m = np.asarray(masses_kg, dtype=float)
    k_s = np.asarray(stiffness_matrix, dtype=float)
    c_s = np.asarray(damping_matrix, dtype=float)
    n = m.size
    m_b = total_mass_kg - m.sum()
    weight = gravity_m_s2 * total_mass_kg
    k_iso = isolator_stiffness_N_per_m
    mass = np.zeros((n + 1, n + 1))
    mass[0, 0] = total_mass_kg
    mass[0, 1:] = mass[1:, 0] = m
    mass[1:, 1:] = np.diag(m)
    inv_mass = np.linalg.inv(mass)
    drive = mass[:, 0]  # −[M; m] a_g

    def holding(y, a_g):
        return -m_b * a_g - k_iso * y[0] + np.sum(k_s @ y[1:n + 1] + c_s @ y[n + 2:])

    def accelerations(y, a_g, sliding, sign):
        """(ẍ_b, ü) in the phase."""
        u, ud = y[1:n + 1], y[n + 2:]
        if not sliding:
            return 0.0, -(c_s @ ud + k_s @ u) / m - a_g
        force = np.concatenate([[-k_iso * y[0] - mu_kinetic * weight * sign], -(c_s @ ud + k_s @ u)]) - drive * a_g
        out = inv_mass @ force
        return out[0], out[1:]

    def rhs(t, y, a0, slope, sliding, sign):
        xb_dd, u_dd = accelerations(y, a0 + slope * t, sliding, sign)
        return np.concatenate([y[n + 1:], [xb_dd], u_dd])

    y = np.zeros(2 * n + 2)
    sliding, sign, n_events = False, 0.0, 0
    out_y = np.zeros((acc.size, 2 * n + 2))
    out_floor_acc = np.zeros((acc.size, n))
    out_floor_acc[0] = acc[0] + accelerations(y, acc[0], False, 0.0)[1]
    for i in range(acc.size - 1):
        a0, slope = acc[i], (acc[i + 1] - acc[i]) / dt_s
        t = 0.0
        for _ in range(MAX_PHASES_PER_INTERVAL):
            if sliding:
                def stop(t, y, *args):
                    return y[n + 1]
                stop.direction = -sign
                events = [stop]
            else:
                def up(t, y, a0, slope, *args):
                    return holding(y, a0 + slope * t) - mu_static * weight

                def down(t, y, a0, slope, *args):
                    return holding(y, a0 + slope * t) + mu_static * weight
                up.direction, down.direction = 1.0, -1.0
                events = [up, down]
            for event in events:
                event.terminal = True
            sol = solve_ivp(rhs, (t, dt_s), y, method="DOP853", rtol=rtol, atol=1e-14 * max(1.0, float(np.abs(y).max())),
                            args=(a0, slope, sliding, sign), events=events)
            y = sol.y[:, -1].copy()
            if sol.status != 1:
                break
            t = float(sol.t[-1])
            n_events += 1
            d = holding(y, a0 + slope * t)
            if not sliding:
                sliding, sign = True, math.copysign(1.0, d)
            else:
                y[n + 1] = 0.0
                if abs(d) <= mu_static * weight:
                    sliding = False
                else:
                    sign = math.copysign(1.0, d)
        else:
            raise RuntimeError(f"reference: more than {MAX_PHASES_PER_INTERVAL} events in one sample interval")
        out_y[i + 1] = y
        xb_dd, u_dd = accelerations(y, acc[i + 1], sliding, sign)
        out_floor_acc[i + 1] = acc[i + 1] + xb_dd + u_dd
    return {"slab_displacement_m": out_y[:, 0], "floor_displacement_m": out_y[:, 1:n + 1],
            "floor_absolute_acceleration_m_s2": out_floor_acc, "n_events": n_events}
