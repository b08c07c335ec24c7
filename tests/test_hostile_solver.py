"""Solver inputs that gave a cut-short or absurd answer without a word (issue 26): a µ(v) law too steep
to follow, a solver that could not finish, friction coefficients no isolator has."""

from __future__ import annotations

import numpy as np
import pytest
from typer.testing import CliRunner

from isolator.cli import app
from isolator.errors import InvalidSystemError, IsolatorError, SolverError
from isolator.solver import planar
from isolator.solver.harmonic import harmonic_response
from isolator.solver.system import RATE_MAX_S_PER_M, System


@pytest.fixture
def elcentro(records_dir):
    """(path, ax, ay = 0, dt) of El Centro (1559 samples at 0.02 s); skips without ../shared."""
    from isolator.motion import read_ground_motion

    path = records_dir / "at2" / "elCentro.AT2"
    motion = read_ground_motion(path)
    return path, motion.acceleration_m_s2, np.zeros(motion.npts), motion.dt_s


@pytest.mark.parametrize("rate, words", [
    (1e8, r"rate_s_per_m = 1e\+08 s/m exceeds 10000 s/m"),
    (0.0, "0 is constant friction at mu_slow"),
    (float("nan"), "finite number > 0"),
])
def test_a_velocity_law_too_steep_or_flat_is_refused_with_the_reason(rate, words):
    with pytest.raises(InvalidSystemError, match=words):
        planar.simulate_pair(np.array([0.0, 1.0, 0.0]), np.zeros(3), 0.01, mu_static=0.05, radius_m=2.0,
                             mu_slow=0.03, mu_fast=0.08, rate_s_per_m=rate)


def test_the_steepest_rate_accepted_is_solved_and_near_its_coulomb_limit(elcentro):
    _, ax, ay, dt = elcentro
    law = planar.simulate_pair(ax, ay, dt, mu_static=0.08, radius_m=2.0, mu_slow=0.03, mu_fast=0.08,
                               rate_s_per_m=RATE_MAX_S_PER_M)
    coulomb = planar.simulate_pair(ax, ay, dt, mu_static=0.08, radius_m=2.0)  # µ = µ_fast at any speed
    assert law.message == "ok" and np.all(np.isfinite(law.displacement_m))
    # µ(v) < µ_fast only below ~1e-4 m/s: the peak is Coulomb's to 1e-3 (measured 8e-4), and below it
    assert 0.0 < (coulomb.peak_displacement_m - law.peak_displacement_m) / coulomb.peak_displacement_m < 1e-3


def test_a_solver_that_cannot_finish_raises_instead_of_answering(monkeypatch, elcentro):
    monkeypatch.setattr(planar, "check_friction_rate", float)  # let the 1e8 s/m through to the engine
    _, ax, ay, dt = elcentro
    with pytest.raises(SolverError, match=r"could not finish: step guard: more than 100000 steps in one sample "
                                          r"interval.*\(at t = [0-9.]+ s\)") as info:
        planar.simulate_pair(ax, ay, dt, mu_static=0.05, radius_m=2.0, mu_slow=0.03, mu_fast=0.08,
                             rate_s_per_m=1e8)
    assert isinstance(info.value, IsolatorError)


@pytest.mark.parametrize("keywords, words", [
    (dict(mu_static=1.5), "mu_static = 1.5 must be < 1"),
    (dict(mu_static=0.1, mu_kinetic=float("inf")), "mu_kinetic must be a finite number"),
])
def test_friction_coefficients_above_the_weight_are_refused(keywords, words):
    with pytest.raises(InvalidSystemError, match=words):
        System(**keywords)
    with pytest.raises(InvalidSystemError, match=words):
        planar.simulate_pair(np.array([0.0, 1.0, 0.0]), np.zeros(3), 0.01, radius_m=2.0, **keywords)


@pytest.mark.parametrize("mu_s", [1e-300, 2.0, 1.0])
def test_harmonic_friction_outside_its_range_is_refused(mu_s):
    with pytest.raises(InvalidSystemError, match=r"mu_s = .* must lie in \[0.0001, 1\)"):
        harmonic_response(2.0, 1.0, 0.0, mu_s)


@pytest.mark.parametrize("args, words", [
    (["--mu-s", "0.05", "--radius-m", "2", "--mu-slow", "0.03", "--mu-fast", "0.08", "--rate-s-per-m", "1e8"],
     "exceeds 10000 s/m"),
    (["--mu-s", "1.5"], "mu_static = 1.5 must be < 1"),
    (["--mu-s", "0.1", "--radius-m", "2", "--mu-slow", "0.03", "--mu-fast", "1", "--rate-s-per-m", "20"],
     "mu_fast = 1 must be < 1"),
    (["--mu-s", "0.1", "--radius-m", "2", "--mu-slow", "0.03", "--mu-fast", "0.1", "--rate-s-per-m", "0"],
     "0 is constant friction"),
])
def test_simulate_refuses_in_one_line(args, words, elcentro):
    result = CliRunner().invoke(app, ["simulate", str(elcentro[0]), *args])
    assert result.exit_code == 2 and len(result.stderr.splitlines()) == 1 and words in result.stderr


@pytest.mark.parametrize("args, words", [
    (["harmonic", "--alpha", "2", "--mu-s", "1e-300"], "mu_s = 1e-300 must lie in"),
    (["threshold", "--mu-s", "2"], "mu_s = 2 must lie in"),
])
def test_harmonic_commands_refuse_in_one_line(args, words):
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 2 and len(result.stderr.splitlines()) == 1 and words in result.stderr
