"""What the bench's cases and methods share: :class:`BenchCase` (a problem) and
:class:`MethodOutput` (what every method returns), below :mod:`~isolator.bench.cases`,
:mod:`~isolator.bench.methods` and :mod:`~isolator.bench.pairs`, which all use them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

HARMONIC_PHASE = 0.5 * math.pi  #: φ of the paper, Eq. 2 [rad]


@dataclass
class BenchCase:
    """One benchmark problem: a system and a ground motion, per unit mass (SI or Eq. 2 units).

    ``kind`` is ``"harmonic"`` (dimensionless, g = 1, a_g = ω² cos(ωt + π/2), from rest,
    compared on the last of ``n_periods`` forcing periods) or ``"record"`` (a sampled
    accelerogram [m/s²] taken as linear between samples, compared on every sample).
    """

    name: str
    kind: str
    mu_static: float
    mu_kinetic: float
    stiffness_per_mass: float  #: κ [1/s²] (k for harmonic cases)
    damping_per_mass: float  #: c [1/s] (η for harmonic cases)
    gravity: float  #: g [m/s²] (1 for harmonic cases)
    duration: float  #: [s] (dimensionless time for harmonic cases)
    output_time: np.ndarray = field(repr=False)  #: comparison times
    window_start: float = 0.0  #: start of the window where peak/A and ζ are measured
    acceleration_m_s2: np.ndarray | None = field(default=None, repr=False)
    dt_s: float | None = None
    alpha: float | None = None
    omega: float | None = None
    n_periods: int | None = None
    exact_zeta: float | None = None  #: analytic steady-state ζ (harmonic)
    exact_amplitude: float | None = None  #: analytic steady-state A (harmonic)

    def ground_acceleration(self, t) -> np.ndarray:
        """a_g at times ``t`` (first-order hold for records)."""
        t = np.asarray(t, dtype=float)
        if self.kind == "harmonic":
            return self.omega ** 2 * np.cos(self.omega * t + HARMONIC_PHASE)
        return np.interp(t, self.output_time, self.acceleration_m_s2)

    def ground_acceleration_at(self, t: float) -> float:
        """a_g at one time ``t`` (the fast path of the solve_ivp right-hand sides)."""
        if self.kind == "harmonic":
            return self.omega ** 2 * math.cos(self.omega * t + HARMONIC_PHASE)
        acc = self.acceleration_m_s2
        u = t / self.dt_s
        i = min(max(int(u), 0), acc.size - 2)
        frac = min(max(u - i, 0.0), 1.0)
        return float(acc[i] + frac * (acc[i + 1] - acc[i]))

    @property
    def static_friction(self) -> float:
        return self.mu_static * self.gravity

    @property
    def kinetic_friction(self) -> float:
        return self.mu_kinetic * self.gravity

    @property
    def window_length(self) -> float:
        return self.duration - self.window_start


@dataclass
class MethodOutput:
    """What every method returns (units of the case)."""

    displacement: np.ndarray  #: X at ``case.output_time``
    velocity: np.ndarray  #: X' at ``case.output_time``
    peak: float  #: records: max |X|; harmonic: A = half peak-to-peak on the last period
    residual: float  #: X at the end of the run
    slip_ratio: float  #: slip time / window length (ζ, Eq. 3)
    n_events: int = -1  #: break-aways + stops, when the method knows them
