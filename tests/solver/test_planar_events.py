"""The closed-form finish of a stop in the planar engine (planar_events.coast_to_rest, settled).

Per unit mass, the last speed r of a stop is finished along a fixed direction with the
speed quadratic in time.  Checked against the exact answer of a collinear stop under a
linear ground acceleration (a flat slider without spring or dashpot: r is then exactly
quadratic), and against an independent integration of a turning 2-D stop (scipy's
solve_ivp on the LOG-form equations, s = ln r the independent variable).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from isolator.solver import planar_rk as rk
from isolator.solver.planar_events import SETTLED_TURN, coast_to_rest, settled

G = 9.81


def _flat_slider(mu=0.1, kappa=0.0):
    prm = np.zeros(rk.P_SIZE)
    prm[rk.P_MU_S] = prm[rk.P_MU_K] = mu
    prm[rk.P_KAPPA] = kappa
    return prm


def test_collinear_stop_under_linear_forcing_is_exact():
    """ṙ = −a_x(τ) − µg with a_x = a0 + a1 τ: r(t) = r0 + ṙ0 t − ½ a1 t², stop at its root."""
    prm = _flat_slider(mu=0.1)
    a0, a1, r0, tau = 0.5, 30.0, 1e-3, 0.004
    frc = np.array([a0, a1, 0.0, 0.0, G, 0.0, 1.0])
    y = np.array([0.02, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, tau])  # X, e = +x, energies, τ
    rdot = -(a0 + a1 * tau) - 0.1 * G
    dtt = coast_to_rest(tau, y, r0, rdot, 1.0, prm, frc)
    # the exact root of r0 + ṙ0 t − ½ a1 t² (hand-checkable: a quadratic)
    exact = (rdot + math.sqrt(rdot * rdot + 2.0 * a1 * r0)) / a1
    assert abs(dtt - exact) <= 1e-15
    assert abs(dtt - r0 / -rdot) > 1e3 * 1e-15  # the constant-deceleration time is not it
    distance = r0 * exact + 0.5 * rdot * exact ** 2 - a1 * exact ** 3 / 6.0
    assert abs(y[0] - 0.02 - distance) <= 1e-17 and y[1] == 0.0  # the rounding of 0.02 + D
    assert abs(y[5] - 0.1 * G * distance) <= 1e-18  # friction work µ g D


def test_stop_is_cut_at_the_interval_end():
    prm = _flat_slider()
    frc = np.array([0.5, 0.0, 0.0, 0.0, G, 0.0, 1.0])
    y = np.array([0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    assert coast_to_rest(0.0, y, 1e-3, -1.481, 1e-5, prm, frc) == 1e-5
    assert coast_to_rest(0.0, y, 1e-3, 0.2, 1.0, prm, frc) == 0.0  # not decelerating: nothing to finish


def _log_form_stop(prm, frc, tau, x, e, r0):
    """Independent reference: the stop in LOG form (s = ln r) by solve_ivp, to 1e-12 r0, then
    the last sliver at constant deceleration (an error of order (1e-12 r0)²)."""
    mu = prm[rk.P_MU_K]

    def rhs(s, z):
        r = math.exp(s)
        t, x1, x2, e1, e2 = z
        fx, fy = -prm[rk.P_KAPPA] * x1 - (frc[0] + frc[1] * t), -prm[rk.P_KAPPA] * x2 - (frc[2] + frc[3] * t)
        ef = e1 * fx + e2 * fy
        rdot = ef - mu * (frc[4] + frc[5] * t)
        return [r / rdot, r * r * e1 / rdot, r * r * e2 / rdot, (fx - ef * e1) / rdot, (fy - ef * e2) / rdot]

    s0 = math.log(r0)
    sol = solve_ivp(rhs, (s0, s0 + math.log(1e-12)), [tau, x[0], x[1], e[0], e[1]], method="DOP853",
                    rtol=1e-13, atol=1e-20)
    t, x1, x2, _, _ = sol.y[:, -1]
    tau_per_s = rhs(s0 + math.log(1e-12), sol.y[:, -1])[0]  # r/ṙ at the end: minus the time still to go
    return t - tau_per_s, x1, x2


def test_turning_stop_against_an_independent_integration():
    """A 2-D stop whose direction turns slowly (|de/ds| below the settled bound): the finish's time
    and distance agree with solve_ivp to far better than the constant-deceleration finish."""
    prm = _flat_slider(mu=0.06, kappa=G / 2.0)  # a pendulum's stiffness, as a spring
    frc = np.array([0.3, 12.0, -0.25, 7.0, G, 0.0, 1.0])
    tau, x, r0 = 0.003, (0.01, -0.004), 2e-6
    fx, fy = -prm[rk.P_KAPPA] * x[0] - (frc[0] + frc[1] * tau), -prm[rk.P_KAPPA] * x[1] - (frc[2] + frc[3] * tau)
    fm = math.hypot(fx, fy)
    turn = 0.0014  # the angle between e and F [rad]: |de/ds| = F⊥/|ṙ| ≈ 0.46 · 0.0014 / 0.13 = 0.005
    e = (math.cos(turn) * fx / fm + math.sin(turn) * fy / fm, -math.sin(turn) * fx / fm + math.cos(turn) * fy / fm)
    rdot = e[0] * fx + e[1] * fy - 0.06 * G
    assert rdot < 0.0
    t_ref, x1_ref, x2_ref = _log_form_stop(prm, frc, tau, x, e, r0)
    y = np.array([x[0], x[1], e[0], e[1], 0.0, 0.0, 0.0, tau])
    dtt = coast_to_rest(tau, y, r0, rdot, 1.0, prm, frc)
    err_time = abs(tau + dtt - t_ref)
    err_linear = abs(tau + r0 / -rdot - t_ref)
    turn_per_s = abs(e[0] * fy - e[1] * fx) / -rdot  # |de/ds|
    assert 0.004 < turn_per_s < SETTLED_TURN
    assert err_time <= 0.05 * err_linear  # the curvature of r(t) is in, to the direction's turn
    assert err_time <= 2.0 * (r0 / -rdot) * turn_per_s ** 2  # the bound of settled()'s docstring
    # X: the distance r0²/(2|ṙ|) ≈ 1.5e-11 m along a direction that is off by up to the angle `turn`
    assert math.hypot(y[0] - x1_ref, y[1] - x2_ref) <= r0 * r0 / -rdot * turn


def test_settled_direction():
    prm = _flat_slider()
    frc = np.array([-0.4, 0.0, 0.3, 0.0, G, 0.0, 1.0])  # F = −a_g = (0.4, −0.3), |F| = 0.5
    ahead = np.array([0.0, 0.0, 0.8, -0.6, 0.0, 0.0, 0.0, 0.0])
    behind = ahead.copy()
    behind[2:4] *= -1.0
    still = np.zeros(8)
    turning = np.zeros(8)
    turning[2] = 2.0 * SETTLED_TURN
    assert settled(0.0, ahead, still, prm, frc)
    assert not settled(0.0, ahead, turning, prm, frc)
    assert not settled(0.0, behind, still, prm, frc)  # F behind the motion: an unstable direction
