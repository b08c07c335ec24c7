"""A saturated pair at a corner in the plane (2d-multisurface+mu(v)): two surfaces sliding near µ_fast with slips a
small angle apart, where the inverse law φ is not resolvable (h141 measured the cause; h151 built the solve).

The scene: the tests' TFP under 0.7 g sin(πt) along x and 0.02 g sin(2πt/1.6) along y.  At 0.7172 s the outer
surfaces are held on their rims (regime V), the inner pair slides at a·s = 27.73 each (2.77 m/s), µ_fast − |r − b| ≈
9e-15 on both, their slips 2.19e-2 rad apart (their circles' centres 4.4e-4 apart across the motion): r at the
corner.  On main the run stopped there: "the step size fell below 1e-13 of the sample interval at t = 0.717204 s"
(the force's Newton in r stalled at |G| = 1.8e-8 with ∂G/∂r of condition 8e10).  Now the force is found with every
law forward at such a corner (``corner_force``) and the Jacobian by the implicit function theorem on its system.  Truths: the energy balance, rotation invariance (the record turned by 35° gives the
turned history), and the model's own equations at the corner solved to 60 digits (mpmath) on a state of the run.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.solver.multisurface_rate import rate_laws
from isolator.solver.planar_multisurface_rate import simulate_bearing_pair_rate
from tests.solver.test_planar_multisurface_rate import TFP, G, rotate


def corner_pulse():
    t = np.arange(0.0, 0.74, 0.02)  # to 0.72 s: past the corner (0.7172 s), before the first rim impact (0.7336 s)
    return 0.7 * G * np.sin(2 * np.pi * t / 2.0), 0.02 * G * np.sin(2 * np.pi * t / 1.6)


def test_saturated_pair_at_a_corner_runs_balances_and_is_rotation_invariant():
    ax, ay = corner_pulse()
    one = simulate_bearing_pair_rate(ax, ay, 0.02, bearing=TFP)
    theta = np.radians(35.0)
    bx, by = rotate(ax, ay, theta)
    two = simulate_bearing_pair_rate(bx, by, 0.02, bearing=TFP)
    back_x, back_y = rotate(two.displacement_m[:, 0], two.displacement_m[:, 1], -theta)
    peak = one.peak_displacement_m
    err = max(np.max(np.abs(back_x - one.displacement_m[:, 0])), np.max(np.abs(back_y - one.displacement_m[:, 1])))
    print("corner:", one.regimes, "peak", peak, "35°", err / peak, "balance", one.energy_balance_error_J_per_kg,
          two.energy_balance_error_J_per_kg, "of", one.energy_input_J_per_kg, "steps", one.n_steps)
    assert "V" in one.regimes and not one.ultimate_displacement_reached
    assert one.peak_velocity_m_s > 2.7  # the inner pair carries the mass at a·s > 27 each
    assert err <= 1e-9 * peak
    for res in (one, two):
        assert abs(res.energy_balance_error_J_per_kg) <= 1e-9 * res.energy_input_J_per_kg


def corner_state():
    """A state of the corner (regime V, the probe's surfaces rounded to 1 µm: the inner pair saturated with slips
    ~2e-2 rad apart, a·s 22.5 and ~60) and the kernel's arrays for it."""
    from isolator.solver import planar_multisurface_rate_kernel as K

    mu_s, mu_f, rate = rate_laws(TFP, "x")
    rbar, _, _ = TFP.elements()
    smat = np.linalg.inv(TFP.surface_matrix())
    bmat = smat / rbar[:, None]
    # outer surfaces held at their rims, 1.2e-2 rad apart; the inner ones where the run had them (h141's probe)
    u = np.array([[-0.399812, -0.012256], [-0.027055, -0.000744], [-0.027051, -0.000904], [-0.399818, -0.012056]])
    y = np.concatenate(([-2.77215556, -0.07199841], u.ravel()))
    mode = np.array([K.HELD, K.SLIDING, K.SLIDING, K.HELD], dtype=np.int64)
    bf = np.zeros((4, 2))
    K.back_forces(y, bmat, bf)
    smode = np.zeros(4, dtype=np.int64)
    K.split_modes(mode, smode)
    gmap = np.zeros((4, 5))
    lock = np.zeros(4, dtype=np.int64)
    pivot = K.set_split(smode, 1, lock, bmat, gmap)
    return K, mu_s, mu_f, rate, bmat, smat, y, mode, bf, gmap, lock, pivot


def corner_start(bf, mu_f, y):
    """The corner of the two inner µ_fast circles on the motion's side (a start for the force's Newton)."""
    cx, cy = 0.5 * (bf[1] + bf[2])
    d = bf[2] - bf[1]
    half = math.hypot(*d) / 2
    across = np.array([-d[1], d[0]]) / (2 * half)
    side = math.sqrt(mu_f[1] ** 2 - half ** 2)
    return np.array([cx, cy]) + side * across * (1 if across @ y[:2] > 0 else -1)


def test_corner_force_is_the_60_digit_root_at_the_corner():
    """The kernel's corner_force against Σ φ_i(|r − b_i|) f̂_i = Ẋ solved to 60 digits (main has no such solve and
    its solve_force stalls there)."""
    mp = pytest.importorskip("mpmath")
    K, mu_s, mu_f, rate, bmat, smat, y, mode, bf, gmap, lock, pivot = corner_state()
    # the reference: 60 digits, Newton on r from the circles' corner
    mp.mp.dps = 60
    b = [[mp.mpf(float(x)) for x in bf[i]] for i in range(4)]
    vel = [mp.mpf(float(y[0])), mp.mpf(float(y[1]))]

    def phi(i, rho):
        return mp.log(mp.mpf(mu_f[i] - mu_s[i]) / (mp.mpf(mu_f[i]) - rho)) / mp.mpf(rate[i])

    def equations(rx, ry):
        sx, sy = -vel[0], -vel[1]
        for i in (1, 2):
            fx, fy = rx - b[i][0], ry - b[i][1]
            rho = mp.sqrt(fx * fx + fy * fy)
            s = phi(i, rho)
            sx += s * fx / rho
            sy += s * fy / rho
        return [sx, sy]

    r = corner_start(bf, mu_f, y)
    sv = np.zeros(4)
    assert K.corner_force(y[0], y[1], bf, mode, mu_s, mu_f, rate, pivot, gmap, lock, 1.0, 0.0, r, sv)
    # the reference from there (inside both discs: φ finite), converged in 60 digits on the φ form of the equations
    root = mp.findroot(equations, (mp.mpf(float(r[0])), mp.mpf(float(r[1]))), tol=mp.mpf(10) ** -40)
    r_ref = np.array([float(root[0]), float(root[1])])
    s_ref = float(phi(2, mp.sqrt((root[0] - b[2][0]) ** 2 + (root[1] - b[2][1]) ** 2)))
    gap = min(mu_f[i] - math.hypot(*(r_ref - bf[i])) for i in (1, 2))
    print("corner root: r", r - r_ref, "s", sv[2] - s_ref, "gap", gap, "a s", rate[2] * s_ref)
    # saturated: µ_fast − |r − b| at the rounding of r on one member, a·s = 22.5 on the other
    assert gap < 1e-12 and rate[2] * s_ref > 20.0
    assert np.max(np.abs(r - r_ref)) <= 1e-15 and abs(sv[2] - s_ref) <= 1e-9 * s_ref


def test_corner_jacobian_is_the_derivative_of_the_rates():
    """At the corner the state's rates are taken from corner_force and their Jacobian from the implicit function
    theorem on its 2 + |U| system (corner_jacobian): against central differences of the rates themselves (steps
    1e-7 of each component's scale), and finite everywhere (main's DΦ_j would carry 1/µ'(s) ~ e^(a s) ~ 1e27)."""
    K, mu_s, mu_f, rate, bmat, smat, y, mode, bf, gmap, lock, pivot = corner_state()
    m = y.size
    r0 = corner_start(bf, mu_f, y)
    sv = np.zeros(4)
    assert K.corner_force(y[0], y[1], bf, mode, mu_s, mu_f, rate, pivot, gmap, lock, 1.0, 0.0, r0, sv)

    def rates(state, want_jac=False):
        r = r0.copy()
        dy = np.empty(m)
        jac = np.zeros((m, m))
        good, _ = K.rhs(state, 0.0, 0.0, G, 0.0, bmat, smat, mode, mu_s, mu_f, rate, pivot, gmap, lock, 1.0, 0.0, r,
                        np.zeros((4, 2)), dy, jac, want_jac)
        assert good
        return dy, jac

    dy, jac = rates(y, True)
    assert np.all(np.isfinite(jac))
    fd = np.empty((m, m))
    for q in range(m):
        step = 1e-7 * (3.0 if q < 2 else 0.4)
        up = y.copy()
        up[q] += step
        down = y.copy()
        down[q] -= step
        fd[:, q] = (rates(up)[0] - rates(down)[0]) / (2 * step)
    scale = np.max(np.abs(fd), axis=1, keepdims=True) + 1e-300
    err = np.max(np.abs(jac - fd) / scale)
    print("corner Jacobian vs central differences:", err, "largest entry", np.max(np.abs(jac)))
    assert err <= 1e-5


def test_pts_lower_bound_of_the_review_passes_its_corner(records_dir):
    """The review's scene (/tmp/coord/muv_tfp.toml's TFP, 0.4 m plates, a = 20 s/m, under PTS ×1.512437746473765):
    on main the work bound stopped it at 12.736 s (the outer pair 1 and 4 at a·s 26.4, slips 2.7e-2 rad apart: a
    corner).  Now it passes there; to 12.8 s the run's only refusal is after the slide along the rims (every surface
    on its rim at 12.2899 s, the rims 0.144 apart; the slide handed over to close_along_rims reaches their alignment
    at 12.2912246 s, where the impact of 0.8146 m/s is taken and the common circle's slide is not modelled, h226) —
    the status checks (work bound, step floor) come first in the driver."""
    from isolator.errors import SolverError
    from tests.solver.test_planar_multisurface_rate import read_pair, review_tfp

    bearing = review_tfp()
    ax, ay, dt = read_pair(records_dir, 12.8)
    factor = 1.512437746473765
    with pytest.raises(SolverError, match=r"reached its rim at t = 12\.2899 s with the rims 0\.144 apart .* alignment at "
                                          r"t = 12\.2912246 s .* impact of 0\.8146 m/s") as info:
        simulate_bearing_pair_rate(factor * ax, factor * ay, dt, bearing=bearing)
    assert "\n" not in str(info.value)
