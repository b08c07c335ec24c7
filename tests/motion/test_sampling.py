"""Records whose samples are not evenly spaced: read, measured and solved as they are.

Truth: a uniform record with extra samples inserted on the straight lines between its
samples is the same piecewise-linear signal, so every exact quantity (velocity by the
trapezoidal rule, the response spectrum, the isolator response) must not change.
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.motion import GroundMotion, read_ground_motion, velocity_m_s
from isolator.solver.record import simulate_record


def _with_collinear_samples(acc, dt, seed=0):
    rng = np.random.default_rng(seed)
    times, values = [0.0], [acc[0]]
    for i in range(acc.size - 1):
        for u in np.sort(rng.uniform(0.1, 0.9, rng.integers(0, 3))):
            times.append((i + u) * dt)
            values.append(acc[i] + u * (acc[i + 1] - acc[i]))
        times.append((i + 1) * dt)
        values.append(acc[i + 1])
    return np.array(values), np.array(times)


@pytest.fixture(scope="module")
def elcentro(records_dir):
    return read_ground_motion(records_dir / "at2" / "elCentro.AT2")


def test_text_file_with_unequal_steps_reads_and_solves_as_the_uniform_record(tmp_path, elcentro):
    values_g, times_s = _with_collinear_samples(elcentro.acceleration_m_s2 / 9.80665, elcentro.dt_s)
    path = tmp_path / "digitised.txt"
    np.savetxt(path, np.column_stack([times_s + 5.0, values_g]), fmt="%.17g", header="units: g")
    motion = read_ground_motion(path)
    assert not motion.is_uniform and "unequal steps" in motion.provenance["sampling"]
    np.testing.assert_allclose(motion.time_s, times_s, atol=1e-12)
    # the trapezoidal rule is the exact integral of the piecewise-linear signal: the ground
    # velocity at the original samples is the same (PGV may rise at an inserted sample)
    original = np.flatnonzero(np.isclose(times_s / elcentro.dt_s, np.round(times_s / elcentro.dt_s), atol=1e-9))
    assert original.size == elcentro.npts
    np.testing.assert_allclose(velocity_m_s(motion.acceleration_m_s2, motion.dt_s, motion.time_s)[original],
                               velocity_m_s(elcentro.acceleration_m_s2, elcentro.dt_s), atol=1e-12)
    assert motion.intensity_measures().pgv_m_s >= elcentro.intensity_measures().pgv_m_s
    periods = np.array([0.1, 1.0, 3.0])
    np.testing.assert_allclose(motion.response_spectrum(periods), elcentro.response_spectrum(periods), rtol=1e-11)
    system = dict(mu_static=0.05, stiffness_per_mass=9.80665 / 2.0)
    ours = simulate_record(motion.acceleration_m_s2, time_s=motion.time_s, **system)
    uniform = simulate_record(elcentro.acceleration_m_s2, elcentro.dt_s, **system)
    assert ours.peak_displacement_m == pytest.approx(uniform.peak_displacement_m, rel=1e-12)
    assert ours.residual_displacement_m == pytest.approx(uniform.residual_displacement_m, rel=1e-10)


def test_processing_that_assumes_equal_steps_refuses_and_linear_resampling_restores_them(elcentro):
    values, times = _with_collinear_samples(elcentro.acceleration_m_s2, elcentro.dt_s, seed=4)
    motion = GroundMotion.from_array(values, time_s=times)
    with pytest.raises(ValueError, match="evenly spaced"):
        motion.bandpassed(0.1, 10.0)
    back = motion.resampled(elcentro.dt_s, method="linear")
    assert back.is_uniform and back.npts == elcentro.npts
    np.testing.assert_allclose(back.acceleration_m_s2, elcentro.acceleration_m_s2, atol=1e-12)
    window = motion.trimmed(2.0, 4.0)
    assert window.time_s[0] == 0.0 and window.duration_s == pytest.approx(2.0, abs=elcentro.dt_s)
