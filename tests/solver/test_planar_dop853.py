"""The generated DOP853 step of the planar kernel against scipy's own DOP853 step.

``isolator/solver/planar_dop853.py`` is written by ``tools/generate_dop853.py``; these
tests check that it is up to date and that one step of it equals one step of scipy's
Runge–Kutta code (``scipy.integrate._ivp.rk.rk_step`` with the DOP853 tableau, and
scipy's error norm) on the same right-hand side, in every form of the motion.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate._ivp import dop853_coefficients as dop
from scipy.integrate._ivp.rk import rk_step

from isolator.solver import planar_rk as rk
from isolator.solver.planar_dop853 import dop853_step
from tools.generate_dop853 import TARGET, source


def test_generated_module_is_up_to_date():
    assert TARGET.read_text(encoding="utf-8") == source(), "run: python -m tools.generate_dop853"


def _system():
    prm = np.zeros(rk.P_SIZE)
    prm[rk.P_MU_S] = 0.08
    prm[rk.P_MU_K] = 0.08
    prm[rk.P_MU_SLOW] = 0.05
    prm[rk.P_MU_FAST] = 0.11
    prm[rk.P_RATE] = 20.0
    prm[rk.P_VELDEP] = 1.0
    prm[rk.P_C] = 0.3
    prm[rk.P_INV_R] = 1.0 / 2.5
    prm[rk.P_PENDULUM] = 1.0
    # a_x = 1.2 + 8 τ, a_y = -0.7 - 5 τ, n = 9.81 - 3 τ (a vertical record), in contact
    frc = np.array([1.2, 8.0, -0.7, -5.0, 9.81, -3.0, 1.0])
    return prm, frc


# (mode, x, state, h): X, V (or direction e, or speed r), energies, r or τ; each step long enough
# that its error estimate (1e-4 to 0.1 of the tolerance) stands far above the rounding of the
# stage sums (≈ 1e-5 here), which the compiler may order differently from scipy
CASES = [
    (rk.CARTESIAN, 0.004, [0.031, -0.012, 0.21, -0.08, 0.5, 0.2, 0.01, 0.0], 2e-2),
    (rk.POLAR, 0.002, [0.031, -0.012, 0.6, -0.8, 0.5, 0.2, 0.01, 0.004], 3e-4),
    (rk.START, 0.001, [0.031, -0.012, 2e-4, 0.0, 0.5, 0.2, 0.01, 0.0], 5e-3),
    (rk.LOG, np.log(0.02), [0.031, -0.012, 0.6, -0.8, 0.5, 0.2, 0.01, 0.003], -0.3),
]


def _constant_friction(prm):
    prm = prm.copy()
    prm[rk.P_VELDEP] = 0.0
    return prm


@pytest.mark.parametrize("mode, x, state, h, constant", [case + (False,) for case in CASES]
                         + [CASES[1] + (True,)], ids=["cartesian", "polar", "start", "log", "polar-constant-mu"])
def test_step_equals_scipy_dop853(mode, x, state, h, constant):
    prm, frc = _system()
    if constant:
        prm = _constant_friction(prm)
    y = np.array(state, dtype=float)
    f0 = np.empty(rk.NSTATE)
    assert rk.rhs(mode, x, y, prm, frc, f0)
    stages = np.empty((dop.N_STAGES + 1, rk.NSTATE))
    tableau = (dop.A[:dop.N_STAGES, :dop.N_STAGES], dop.B, dop.C[:dop.N_STAGES])
    if mode == rk.POLAR and prm[rk.P_VELDEP] > 0.0:
        # µ(v) in POLAR form: the step carries q = e^(−a r) through its stages (q' = −a q ṙ, a ninth
        # variable, from q = e^(−a r) at the start); the same tableau on that augmented system
        a = prm[rk.P_RATE]

        def fun(t, z):
            d = np.empty(rk.NSTATE)
            assert rk.rhs(mode, t, z[:rk.NSTATE], prm, frc, d)
            mu = prm[rk.P_MU_FAST] - (prm[rk.P_MU_FAST] - prm[rk.P_MU_SLOW]) * z[-1]
            n = frc[4] + frc[5] * t
            # rhs used e^(−a r): put µ(q) in its place in ṙ and the friction power
            fr_exact = rk.friction_coefficient(z[7], prm) * n
            d[7] += fr_exact - mu * n
            d[5] += (mu * n - fr_exact) * z[7]
            return np.append(d, -a * z[-1] * d[7])

        z0 = np.append(y, np.exp(-a * y[7]))
        stages9 = np.empty((dop.N_STAGES + 1, rk.NSTATE + 1))
        z_new, _ = rk_step(fun, x, z0, fun(x, z0), h, *tableau, stages9)
        expected = z_new[:rk.NSTATE]
        stages[:] = stages9[:, :rk.NSTATE]
        f_expected = np.empty(rk.NSTATE)  # the step ends on the exact form's derivative
        assert rk.rhs(mode, x + h, expected, prm, frc, f_expected)
        # and the augmented method is the plain one to within its own error (≈ err·tolerance)
        plain = rk_step(lambda t, z: _rhs(mode, t, z, prm, frc), x, y, f0, h, *tableau,
                        np.empty((dop.N_STAGES + 1, rk.NSTATE)))[0]
        np.testing.assert_allclose(expected, plain, rtol=0, atol=1e-12)
    else:
        expected, f_expected = rk_step(lambda t, z: _rhs(mode, t, z, prm, frc), x, y, f0, h, *tableau, stages)
    rtol = 1e-9
    atol = np.full(rk.NSTATE, 1e-12)
    atol[7] = np.inf if mode in (rk.CARTESIAN, rk.START) else 1e-12
    controlled = atol < np.inf
    scale = atol[controlled] + rtol * np.maximum(np.abs(y), np.abs(expected))[controlled]
    err5 = np.linalg.norm((stages.T @ dop.E5)[controlled] / scale) ** 2
    err3 = np.linalg.norm((stages.T @ dop.E3)[controlled] / scale) ** 2
    err_expected = abs(h) * err5 / np.sqrt((err5 + 0.01 * err3) * controlled.sum())

    ynew = np.empty(rk.NSTATE)
    fnew = np.empty(rk.NSTATE)
    ok, err = dop853_step(mode, x, y, f0, h, prm, frc, ynew, fnew, atol, rtol)
    assert ok
    # the same tableau on the same right-hand side: equal to rounding (the generated code
    # sums the stages in another order); the step changes y by far more than that
    change = np.abs(expected - y)
    assert np.max(change[[0, 1]]) > 1e-8
    np.testing.assert_allclose(ynew, expected, rtol=1e-13, atol=1e-16)
    np.testing.assert_allclose(fnew, f_expected, rtol=1e-12, atol=1e-15)
    assert err == pytest.approx(err_expected, rel=1e-6)
    assert 1e-4 < err_expected < 1.0


def _rhs(mode, t, z, prm, frc):
    d = np.empty(rk.NSTATE)
    assert rk.rhs(mode, t, z, prm, frc, d)
    return d


def test_step_refuses_a_stage_outside_the_form():
    """A LOG step whose stages reach a speed that no longer decreases reports not ok."""
    prm, frc = _system()
    # e along F: the speed grows, the LOG form (approach to a stop) is not valid there
    y = np.array([0.0, 0.0, -1.0, 0.4, 0.0, 0.0, 0.0, 0.0])
    f0 = np.zeros(rk.NSTATE)
    assert not rk.rhs(rk.LOG, np.log(0.01), y, prm, frc, f0)
    ok, err = dop853_step(rk.LOG, np.log(0.01), y, f0, -0.1, prm, frc, np.empty(8), np.empty(8),
                          np.full(8, 1e-12), 1e-9)
    assert not ok and err == np.inf
