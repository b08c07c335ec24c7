"""The mechanical system: Coulomb friction, a linear spring and a linear dashpot.

Everything per unit mass, so that the mass never appears in the solver:
``X'' = -µ(X') g sign(X') - κ X - c X' - a_g(t)`` with κ = K/M and c = γ/M.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from isolator.units import STANDARD_GRAVITY

FRICTION_MODEL_2_RATIO = 0.7  #: µk/µs of the paper's friction model 2 (Table 1)


from isolator.errors import InvalidSystemError  # noqa: E402,F401 - defined with the other typed errors


def classify_configuration(damping: float, stiffness: float) -> str:
    """The paper's configuration (Table 2) of a system with friction.

    Parameters
    ----------
    damping : float
        c = γ/M [1/s] (or η in dimensionless form).
    stiffness : float
        κ = K/M [1/s²] (or k in dimensionless form).

    Returns
    -------
    str
        ``"1"`` friction only, ``"2"`` + damper, ``"3"`` + spring, ``"4a"``
        under-damped (η² < 4k), ``"4b"`` critically damped (η² = 4k exactly),
        ``"4c"`` over-damped.
    """
    if damping == 0.0 and stiffness == 0.0:
        return "1"
    if stiffness == 0.0:
        return "2"
    if damping == 0.0:
        return "3"
    disc = damping * damping - 4.0 * stiffness
    if disc < 0.0:
        return "4a"
    if disc == 0.0:
        return "4b"
    return "4c"


#: Largest K/M [1/s²] accepted: a natural period of 2π/1e4 = 0.6 ms (a pendulum radius of 0.1 µm).
#: Stiffer than that, the isolator is rigid for every sampled record, the solver would
#: need ~ω dt sub-steps per sample, and K/M² overflows near 1e154.
MAX_STIFFNESS_PER_MASS = 1e8
#: Largest γ/M [1/s] accepted: a relaxation time M/γ of 10 ns, far beyond any damper.
MAX_DAMPING_PER_MASS = 1e8


def _check_finite_nonnegative(name: str, value: float, maximum: float = math.inf, why: str = "") -> float:
    value = float(value)
    if not math.isfinite(value) or value < 0.0:
        raise InvalidSystemError(f"{name} must be a finite number ≥ 0, got {value!r}")
    if value > maximum:
        raise InvalidSystemError(f"{name} = {value:g} exceeds {maximum:g}{why}")
    return value


@dataclass(frozen=True)
class System:
    """A block on a moving ground with friction, spring and dashpot (per unit mass).

    Parameters
    ----------
    mu_static : float
        Static friction coefficient µs [-].
    mu_kinetic : float, optional
        Kinetic friction coefficient µk ≤ µs [-]; defaults to µs (friction model 1).
    stiffness_per_mass : float
        κ = K/M [1/s²]; for a friction pendulum of radius R, g/R.
    damping_per_mass : float
        c = γ/M [1/s].
    gravity_m_s2 : float
        Acceleration of gravity [m/s²] (standard gravity by default).
    """

    mu_static: float
    mu_kinetic: float | None = None
    stiffness_per_mass: float = 0.0
    damping_per_mass: float = 0.0
    gravity_m_s2: float = STANDARD_GRAVITY

    def __post_init__(self) -> None:
        mu_s = _check_finite_nonnegative("mu_static", self.mu_static)
        mu_k = mu_s if self.mu_kinetic is None else _check_finite_nonnegative("mu_kinetic", self.mu_kinetic)
        if mu_k > mu_s:
            raise InvalidSystemError(f"mu_kinetic ({mu_k}) must not exceed mu_static ({mu_s})")
        object.__setattr__(self, "mu_static", mu_s)
        object.__setattr__(self, "mu_kinetic", mu_k)
        object.__setattr__(self, "stiffness_per_mass", _check_finite_nonnegative(
            "stiffness_per_mass", self.stiffness_per_mass, MAX_STIFFNESS_PER_MASS,
            " 1/s² (a natural period below 0.6 ms: the isolator is rigid for any record)"))
        object.__setattr__(self, "damping_per_mass", _check_finite_nonnegative(
            "damping_per_mass", self.damping_per_mass, MAX_DAMPING_PER_MASS,
            " 1/s (a relaxation time M/γ below 10 ns: no damper is that strong)"))
        g = float(self.gravity_m_s2)
        if not math.isfinite(g) or g <= 0.0:
            raise InvalidSystemError(f"gravity_m_s2 must be a finite number > 0, got {g!r}")
        object.__setattr__(self, "gravity_m_s2", g)

    @property
    def configuration(self) -> str:
        """The paper's configuration: 1, 2, 3, 4a, 4b or 4c (Table 2)."""
        return classify_configuration(self.damping_per_mass, self.stiffness_per_mass)

    @property
    def static_friction_m_s2(self) -> float:
        """µs g: the largest ground acceleration a stuck, unloaded block can follow [m/s²]."""
        return self.mu_static * self.gravity_m_s2

    @property
    def kinetic_friction_m_s2(self) -> float:
        """µk g: the friction deceleration while sliding [m/s²]."""
        return self.mu_kinetic * self.gravity_m_s2
