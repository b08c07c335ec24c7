"""Benchmark cases: the paper's harmonic problem (Eq. 2) and recorded accelerograms on a pendulum.

A :class:`BenchCase` is a system and a ground motion per unit mass: dimensionless
(g = 1) for harmonic cases, SI for records.  Records come from an explicit folder
(``isolator bench --records DIR``), never from a path relative to the installed package.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from isolator.bench.base import HARMONIC_PHASE, BenchCase  # noqa: F401 - HARMONIC_PHASE: known here too
from isolator.units import STANDARD_GRAVITY as STANDARD_GRAVITY_M_S2

HARMONIC_SAMPLES_PER_PERIOD = 1000  #: output grid on the last forcing period


def harmonic_case(name: str, alpha: float, k: float, eta: float, mu_s: float, mu_k: float | None = None,
                  n_periods: int | None = None) -> BenchCase:
    """A harmonic case (Eq. 2) run from rest to its steady state plus two periods.

    Parameters
    ----------
    alpha, k, eta : float
        Reduced acceleration, stiffness and damping (Eq. 6) [-].
    mu_s, mu_k : float
        Friction coefficients [-].
    n_periods : int, optional
        Forcing periods simulated; by default two more than the exact solver needs
        to reach the periodic state, at least 4.
    """
    from isolator.solver.harmonic import harmonic_response

    mu_k = mu_s if mu_k is None else mu_k
    exact = harmonic_response(alpha, k, eta, mu_s, mu_k)
    if n_periods is None:
        n_periods = max(4, exact.periods_run + 2)
    omega = math.sqrt(alpha * mu_s)
    period = 2.0 * math.pi / omega
    start = (n_periods - 1) * period
    out = start + np.linspace(0.0, period, HARMONIC_SAMPLES_PER_PERIOD + 1)
    return BenchCase(name=name, kind="harmonic", mu_static=mu_s, mu_kinetic=mu_k, stiffness_per_mass=k,
                     damping_per_mass=eta, gravity=1.0, duration=n_periods * period, output_time=out,
                     window_start=start, alpha=alpha, omega=omega, n_periods=n_periods,
                     exact_zeta=exact.zeta, exact_amplitude=exact.amplitude)


def record_case(name: str, acceleration_m_s2, dt_s: float, *, mu_static: float, mu_kinetic: float | None = None,
                stiffness_per_mass: float = 0.0, damping_per_mass: float = 0.0,
                gravity_m_s2: float = STANDARD_GRAVITY_M_S2) -> BenchCase:
    """A recorded ground motion [m/s², dt_s in s] with an isolator (per unit mass)."""
    acc = np.ascontiguousarray(acceleration_m_s2, dtype=float)
    times = dt_s * np.arange(acc.size)
    return BenchCase(name=name, kind="record", mu_static=mu_static,
                     mu_kinetic=mu_static if mu_kinetic is None else mu_kinetic,
                     stiffness_per_mass=stiffness_per_mass, damping_per_mass=damping_per_mass,
                     gravity=gravity_m_s2, duration=float(times[-1]), output_time=times,
                     acceleration_m_s2=acc, dt_s=float(dt_s))


#: The friction-pendulum design of the record cases: R = 2 m (T = 2.84 s), µs = 0.06, µk = 0.05.
PENDULUM_RADIUS_M = 2.0
PENDULUM_MU_STATIC = 0.06
PENDULUM_MU_KINETIC = 0.05

#: Harmonic cases, one per configuration of the paper (Table 2): (name, α, k, η, µs, µk).
HARMONIC_CASES = [
    ("harmonic config 1 (friction)", 1.2, 0.0, 0.0, 0.25, 0.25),
    ("harmonic config 2 (+ dashpot)", 2.0, 0.0, 0.5, 0.25, 0.2),
    ("harmonic config 3 (+ spring)", 1.3, 0.1, 0.0, 0.25, 0.2),
    ("harmonic config 4a (complete)", 1.5, 1.0, 0.5, 0.25, 0.2),
]
#: Records of ../shared/records used by the full bench (the first one by --quick), with the
#: damping of an added viscous damper c = γ/M [1/s] (0.44 1/s: 10 % of critical at T = 2.84 s).
RECORD_FILES = [("at2/RSN1044_NORTHR_NWH360.AT2", 0.0), ("at2/IELC180.AT2", 0.0),
                ("at2/RSN779_LOMAP_LGP000.AT2", 0.44)]

def bench_cases(quick: bool = False, records_dir: Path | None = None) -> list:
    """The benchmark's cases: the harmonic configurations, the records of :data:`RECORD_FILES`
    and the 2-D pairs of :data:`isolator.bench.pairs.PAIR_FILES` found in ``records_dir``
    (none without it)."""
    harmonic = HARMONIC_CASES[:1] + HARMONIC_CASES[3:] if quick else HARMONIC_CASES
    cases = [harmonic_case(*spec) for spec in harmonic]
    if records_dir is not None and Path(records_dir).is_dir():
        records_dir = Path(records_dir)
        from isolator.motion import read_ground_motion

        for rel, damping in RECORD_FILES[:1] if quick else RECORD_FILES:
            path = records_dir / rel
            if not path.is_file():
                continue
            motion = read_ground_motion(path)
            damper = f" + damper c={damping:g}/s" if damping else ""
            cases.append(record_case(
                f"record {path.stem} (FP R={PENDULUM_RADIUS_M:g} m{damper})", motion.acceleration_m_s2, motion.dt_s,
                mu_static=PENDULUM_MU_STATIC, mu_kinetic=PENDULUM_MU_KINETIC,
                stiffness_per_mass=STANDARD_GRAVITY_M_S2 / PENDULUM_RADIUS_M, damping_per_mass=damping))
        from isolator.bench.pairs import pair_cases

        cases.extend(pair_cases(quick, records_dir))
    return cases
