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


#: Largest K/M [1/s²] accepted: a natural period of 2π/1e5 = 63 µs (a pendulum radius of 1 nm),
#: the stiffest case the solver is tested on (tests/solver/test_hard_cases.py).  Stiffer than
#: that the isolator is rigid for every sampled record, the work grows as ω dt sub-steps per
#: sample, and K/M beyond ~1e154 overflows (1e300 was an OverflowError).
MAX_STIFFNESS_PER_MASS = 1e10
#: Largest γ/M [1/s] accepted: a relaxation time M/γ of 1 ps, the strongest damper tested.
MAX_DAMPING_PER_MASS = 1e12


#: Friction coefficients are below 1: µ ≥ 1 is a friction force above the weight, which no sliding
#: isolator has (PTFE or composite on steel: 0.02-0.15); ``--mu-s 1.5`` was accepted (issue 26).
MU_MAX = 1.0
#: Rate of µ(v) = µ_fast - (µ_fast - µ_slow) exp(-a|v|) accepted [s/m]: measured rates of PTFE on
#: steel are 10-200 s/m (Constantinou et al. 1990).  Steeper, µ changes within 1/a < 0.1 mm/s and
#: the 2-D engine's steps through the change grow as a: on El Centro (1559 samples) 55,000 steps at
#: 1e4, 2 million at 1e7 (19 s), and more than 100,000 steps in one sample interval at 1e8, which
#: cut the answer short (issue 26).  The response tends to Coulomb friction at µ_fast (within
#: 2e-4 of its peak at 1e5 s/m, 3e-6 at 1e7): that is the model to give for a steeper law.
RATE_MAX_S_PER_M = 1e4


def check_nonnegative(name: str, value, maximum: float = math.inf, why: str = "") -> float:
    """A parameter as a finite float in [0, ``maximum``], or :class:`InvalidSystemError` (one line naming it; ``why``
    follows the bound: its unit and reason)."""
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise InvalidSystemError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(value) or value < 0.0:
        raise InvalidSystemError(f"{name} must be a finite number ≥ 0, got {value!r}")
    if value > maximum:
        raise InvalidSystemError(f"{name} = {value:g} exceeds {maximum:g}{why}")
    return value


def check_friction_coefficient(name: str, value) -> float:
    """A friction coefficient as a float in [0, :data:`MU_MAX`), or :class:`InvalidSystemError`."""
    value = check_nonnegative(name, value)
    if value >= MU_MAX:
        raise InvalidSystemError(f"{name} = {value:g} must be < {MU_MAX:g}: a friction force above the weight "
                                 "(sliding isolators have 0.02-0.15)")
    return value


def check_friction_rate(value) -> float:
    """The rate a of µ(v) [s/m] in (0, :data:`RATE_MAX_S_PER_M`], or :class:`InvalidSystemError` with the reason."""
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise InvalidSystemError(f"rate_s_per_m must be a number, got {value!r}") from None
    if not math.isfinite(value) or value <= 0.0:
        raise InvalidSystemError(f"rate_s_per_m must be a finite number > 0 (0 is constant friction at mu_slow: "
                                 f"give mu_kinetic instead), got {value!r}")
    if value > RATE_MAX_S_PER_M:
        raise InvalidSystemError(f"rate_s_per_m = {value:g} s/m exceeds {RATE_MAX_S_PER_M:g} s/m: µ would change "
                                 f"from mu_slow to mu_fast within {1.0 / value:.1g} m/s, which the 2-D engine "
                                 "cannot follow in bounded steps; so steep a law is Coulomb friction at mu_fast "
                                 "(measured rates are 10-200 s/m)")
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
        mu_s = check_friction_coefficient("mu_static", self.mu_static)
        mu_k = mu_s if self.mu_kinetic is None else check_friction_coefficient("mu_kinetic", self.mu_kinetic)
        if mu_k > mu_s:
            raise InvalidSystemError(f"mu_kinetic ({mu_k}) must not exceed mu_static ({mu_s})")
        object.__setattr__(self, "mu_static", mu_s)
        object.__setattr__(self, "mu_kinetic", mu_k)
        object.__setattr__(self, "stiffness_per_mass", check_nonnegative(
            "stiffness_per_mass", self.stiffness_per_mass, MAX_STIFFNESS_PER_MASS,
            " 1/s² (a natural period below 63 µs: the isolator is rigid for any record)"))
        object.__setattr__(self, "damping_per_mass", check_nonnegative(
            "damping_per_mass", self.damping_per_mass, MAX_DAMPING_PER_MASS,
            " 1/s (a relaxation time M/γ below 1 ps: no damper is that strong)"))
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
