"""Design: an isolator described in a TOML file, validated, with its engineering quantities.

A design file holds one isolator, for example a friction pendulum::

    name = "FPS R = 2.0 m, mu = 0.06"
    mass_kg = 250000.0          # supported mass [kg]
    radius_m = 2.0              # radius of curvature [m]  (or stiffness_N_per_m)
    mu_static = 0.06            # static friction coefficient [-]
    mu_kinetic = 0.05           # optional, default mu_static (friction model 1)
    damping_ratio = 0.05        # optional supplemental damper, fraction of critical
                                # at the pendulum frequency (or damping_Ns_per_m)

Exactly one of ``radius_m`` / ``stiffness_N_per_m``; at most one of
``damping_Ns_per_m`` / ``damping_ratio``.  Every mistake raises :class:`DesignError`
with a one-line message naming the file and the key.

The friction-pendulum quantities follow the usual bilinear idealisation (e.g. AASHTO
Guide Specifications for Seismic Isolation Design, EN 15129): at a displacement D,
``K_eff = K + µk M g / D``, ``T_eff = 2π sqrt(M / K_eff)`` and
``β_eff = E_D / (2π K_eff D²)`` with the energy per cycle ``E_D = 4 µk M g D`` (friction)
``+ π γ ω_eff D²`` (damper at the effective frequency).
"""

from __future__ import annotations

import difflib
import math
from dataclasses import dataclass
from pathlib import Path

from isolator.units import STANDARD_GRAVITY

#: keys a design file may hold, with their meaning (used in messages and the README)
DESIGN_KEYS = {
    "name": "design name (text)",
    "description": "free text (optional)",
    "mass_kg": "supported mass M [kg], > 0",
    "radius_m": "friction-pendulum radius of curvature R [m], > 0",
    "stiffness_N_per_m": "generic restoring stiffness K [N/m], >= 0",
    "mu_static": "static friction coefficient µs [-], > 0",
    "mu_kinetic": "kinetic friction coefficient µk [-], 0 <= µk <= µs (default µs)",
    "damping_Ns_per_m": "supplemental linear damper γ [N·s/m], >= 0",
    "damping_ratio": "supplemental damper as a fraction of critical at sqrt(K/M) [-], >= 0",
}


def load_toml(path, what: str, error_type: type[Exception]) -> dict:
    """Read a TOML file; a missing, unreadable or invalid file raises ``error_type``.

    Parameters
    ----------
    path : str or path-like
        The file.
    what : str
        What the file is, for the message ("design file", "designs file").
    error_type : type
        The exception raised, with one line naming the file and the problem.
    """
    import tomllib

    from isolator.io._common import input_file_problem

    path = Path(path)
    problem = input_file_problem(path)  # before opening: a FIFO must not block, a loop is not "missing"
    if problem == "no such file":
        raise error_type(f"{path}: no such {what}")
    if problem is not None and problem != "file is empty":
        raise error_type(f"{path}: {problem}")
    try:
        text = path.read_bytes().decode("utf-8")
    except FileNotFoundError:
        raise error_type(f"{path}: no such {what}") from None
    except (OSError, UnicodeDecodeError) as err:
        raise error_type(f"{path}: cannot read the {what} ({' '.join(str(err).split())})") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise error_type(f"{path}: not valid TOML ({' '.join(str(err).split())})") from None


from isolator.errors import DesignError  # noqa: E402,F401 - the design's error, defined with the others

#: Supported mass M accepted [kg]: from a gram (a laboratory specimen) to 1e10 kg (ten times
#: the heaviest isolated structure); outside, K/M and γ/M lose their meaning (1e-320 kg is
#: a subnormal number: K/M overflows).
MASS_RANGE_KG = (1e-3, 1e10)


def _check_derived(fail, mass_kg, stiffness_N_per_m, damping_Ns_per_m, radius_m, damping_ratio) -> None:
    """Refuse a design whose K/M or γ/M the solver cannot take, naming the key at fault."""
    from isolator.solver.system import MAX_DAMPING_PER_MASS, MAX_STIFFNESS_PER_MASS

    low, high = MASS_RANGE_KG
    if not low <= mass_kg <= high:
        raise fail(f"key 'mass_kg' must lie in [{low:g}, {high:g}] kg, got {mass_kg:g}")
    kappa = stiffness_N_per_m / mass_kg
    if not kappa <= MAX_STIFFNESS_PER_MASS:
        key = "radius_m" if radius_m is not None else "stiffness_N_per_m"
        given = f"{radius_m:g} m" if radius_m is not None else f"{stiffness_N_per_m:g} N/m"
        raise fail(f"key '{key}' = {given} gives K/M = {kappa:.3g} 1/s² (natural period "
                   f"{2 * math.pi / math.sqrt(kappa):.3g} s), above {MAX_STIFFNESS_PER_MASS:g} 1/s²: "
                   "no isolator is that stiff")
    c = damping_Ns_per_m / mass_kg
    if not c <= MAX_DAMPING_PER_MASS:
        key = "damping_ratio" if damping_ratio is not None else "damping_Ns_per_m"
        raise fail(f"key '{key}' gives γ/M = {c:.3g} 1/s, above {MAX_DAMPING_PER_MASS:g} 1/s: no damper is "
                   "that strong")


@dataclass(frozen=True)
class EffectiveProperties:
    """Equivalent-linear properties of the isolator at one displacement (SI units)."""

    displacement_m: float
    effective_stiffness_N_per_m: float
    effective_period_s: float
    effective_damping_ratio: float
    design_force_N: float  #: K D + µk M g (+ γ ω_eff D): the bilinear force at D

    def as_dict(self) -> dict:
        return {
            "displacement_m": self.displacement_m,
            "effective_stiffness_N_per_m": self.effective_stiffness_N_per_m,
            "effective_period_s": self.effective_period_s,
            "effective_damping_ratio": self.effective_damping_ratio,
            "design_force_N": self.design_force_N,
        }


@dataclass(frozen=True)
class Design:
    """A validated isolator design (SI units).

    Parameters
    ----------
    name : str
        Design name [-].
    mass_kg : float
        Supported mass M [kg].
    mu_static : float
        Static friction coefficient µs [-].
    mu_kinetic : float
        Kinetic friction coefficient µk ≤ µs [-].
    radius_m : float or None
        Friction-pendulum radius of curvature R [m] (None for a generic spring).
    stiffness_N_per_m : float
        Restoring stiffness K [N/m]; M g / R for a pendulum.
    damping_Ns_per_m : float
        Supplemental damper γ [N·s/m].
    damping_ratio_input : float or None
        The damping ratio given in the file, if it was given that way [-].
    description : str
        Free text [-].
    source : str
        Where the design came from (file name) [-].
    gravity_m_s2 : float
        Gravity used for K = M g / R and for the friction force [m/s²].
    """

    name: str
    mass_kg: float
    mu_static: float
    mu_kinetic: float
    radius_m: float | None
    stiffness_N_per_m: float
    damping_Ns_per_m: float
    damping_ratio_input: float | None = None
    description: str = ""
    source: str = "<design>"
    gravity_m_s2: float = STANDARD_GRAVITY

    # ---- construction ----------------------------------------------------------------

    @classmethod
    def from_toml(cls, path, gravity_m_s2: float = STANDARD_GRAVITY) -> Design:
        """Read and validate a design file.

        Parameters
        ----------
        path : str or Path
            TOML file [-].
        gravity_m_s2 : float
            Gravity [m/s²].

        Returns
        -------
        Design
        """
        mapping = load_toml(path, "design file", DesignError)
        return cls.from_mapping(mapping, source=str(path), gravity_m_s2=gravity_m_s2)

    @classmethod
    def from_mapping(cls, mapping: dict, source: str = "<design>",
                     gravity_m_s2: float = STANDARD_GRAVITY) -> Design:
        """Validate a design given as a dict (the content of a TOML file).

        Raises
        ------
        DesignError
            A message like ``"design.toml: key 'radius_m' must be > 0, got -1"``.
        """
        def fail(message: str) -> DesignError:
            return DesignError(f"{source}: {message}")

        if not isinstance(mapping, dict):
            raise fail("a design must be a table of keys")
        unknown = [key for key in mapping if key not in DESIGN_KEYS]
        if unknown:
            key = unknown[0]
            close = difflib.get_close_matches(str(key), list(DESIGN_KEYS), n=1, cutoff=0.5)
            hint = f" (did you mean '{close[0]}'?)" if close else f" (valid keys: {', '.join(DESIGN_KEYS)})"
            raise fail(f"unknown key '{key}'{hint}")

        def number(key: str, *, minimum: float = 0.0, strict: bool = False, required: bool = False):
            if key not in mapping:
                if required:
                    raise fail(f"missing key '{key}' ({DESIGN_KEYS[key]})")
                return None
            value = mapping[key]
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise fail(f"key '{key}' must be a number, got {value!r}")
            value = float(value)
            if not math.isfinite(value):
                raise fail(f"key '{key}' must be finite, got {value}")
            if strict and not value > minimum:
                raise fail(f"key '{key}' must be > {minimum:g}, got {value:g}")
            if not strict and value < minimum:
                raise fail(f"key '{key}' must be >= {minimum:g}, got {value:g}")
            return value

        name = mapping.get("name")
        if name is None:
            raise fail(f"missing key 'name' ({DESIGN_KEYS['name']})")
        if not isinstance(name, str) or not name.strip():
            raise fail(f"key 'name' must be a non-empty text, got {name!r}")
        description = mapping.get("description", "")
        if not isinstance(description, str):
            raise fail(f"key 'description' must be text, got {description!r}")

        mass_kg = number("mass_kg", strict=True, required=True)
        mu_static = number("mu_static", strict=True, required=True)
        mu_kinetic = number("mu_kinetic")
        if mu_kinetic is None:
            mu_kinetic = mu_static
        elif mu_kinetic > mu_static:
            raise fail(f"key 'mu_kinetic' ({mu_kinetic:g}) must not exceed 'mu_static' ({mu_static:g})")
        if mu_static >= 1.0:
            raise fail(f"key 'mu_static' must be < 1 for a sliding isolator, got {mu_static:g}")

        has_radius, has_stiffness = "radius_m" in mapping, "stiffness_N_per_m" in mapping
        if has_radius and has_stiffness:
            raise fail("give either 'radius_m' (friction pendulum) or 'stiffness_N_per_m', not both")
        if not (has_radius or has_stiffness):
            raise fail("missing key 'radius_m' (friction pendulum) or 'stiffness_N_per_m' (generic spring)")
        g = float(gravity_m_s2)
        if has_radius:
            radius_m = number("radius_m", strict=True)
            stiffness = mass_kg * g / radius_m
        else:
            radius_m = None
            stiffness = number("stiffness_N_per_m")

        if "damping_Ns_per_m" in mapping and "damping_ratio" in mapping:
            raise fail("give at most one of 'damping_Ns_per_m' and 'damping_ratio'")
        damping_ratio = number("damping_ratio")
        if damping_ratio is not None:
            if stiffness == 0.0 and damping_ratio > 0.0:
                raise fail("key 'damping_ratio' needs a restoring stiffness (radius_m or stiffness_N_per_m > 0); "
                           "give 'damping_Ns_per_m' instead")
            damping = 2.0 * damping_ratio * math.sqrt(stiffness * mass_kg)
        else:
            damping = number("damping_Ns_per_m") or 0.0
        _check_derived(fail, mass_kg, stiffness, damping, radius_m, damping_ratio)
        return cls(name=name.strip(), mass_kg=mass_kg, mu_static=mu_static, mu_kinetic=mu_kinetic,
                   radius_m=radius_m, stiffness_N_per_m=stiffness, damping_Ns_per_m=damping,
                   damping_ratio_input=damping_ratio, description=description, source=source,
                   gravity_m_s2=g)

    # ---- derived quantities -------------------------------------------------------------

    @property
    def is_pendulum(self) -> bool:
        """True for a friction pendulum (given by its radius)."""
        return self.radius_m is not None

    @property
    def weight_N(self) -> float:
        """W = M g [N]."""
        return self.mass_kg * self.gravity_m_s2

    @property
    def stiffness_per_mass(self) -> float:
        """κ = K/M [1/s²]."""
        return self.stiffness_N_per_m / self.mass_kg

    @property
    def damping_per_mass(self) -> float:
        """c = γ/M [1/s]."""
        return self.damping_Ns_per_m / self.mass_kg

    @property
    def natural_frequency_rad_s(self) -> float:
        """ω_n = sqrt(K/M) [rad/s] (0 without a spring)."""
        return math.sqrt(self.stiffness_per_mass)

    @property
    def isolated_period_s(self) -> float:
        """T = 2π sqrt(M/K) = 2π sqrt(R/g) for a pendulum [s] (inf without a spring)."""
        omega = self.natural_frequency_rad_s
        return 2.0 * math.pi / omega if omega > 0 else math.inf

    @property
    def damping_ratio(self) -> float:
        """γ / (2 sqrt(K M)) [-] (inf for a damper without a spring, 0 without a damper)."""
        if self.damping_Ns_per_m == 0.0:
            return 0.0
        if self.stiffness_N_per_m == 0.0:
            return math.inf
        return self.damping_Ns_per_m / (2.0 * math.sqrt(self.stiffness_N_per_m * self.mass_kg))

    def system(self, gravity_m_s2: float | None = None):
        """The solver's per-unit-mass system (µs, µk, K/M, γ/M, g).

        Parameters
        ----------
        gravity_m_s2 : float, optional
            Gravity for the friction force [m/s²]; the design's by default.

        Returns
        -------
        isolator.solver.system.System
        """
        from isolator.solver.system import System

        return System(mu_static=self.mu_static, mu_kinetic=self.mu_kinetic,
                      stiffness_per_mass=self.stiffness_per_mass, damping_per_mass=self.damping_per_mass,
                      gravity_m_s2=self.gravity_m_s2 if gravity_m_s2 is None else gravity_m_s2)

    def effective_properties(self, displacement_m: float) -> EffectiveProperties:
        r"""Equivalent-linear stiffness, period and damping at a displacement.

        .. math::  K_{eff} = K + \frac{\mu_k M g}{D},\quad
                   T_{eff} = 2\pi\sqrt{M/K_{eff}},\quad
                   \beta_{eff} = \frac{4\mu_k M g D + \pi\gamma\omega_{eff} D^2}{2\pi K_{eff} D^2}

        Parameters
        ----------
        displacement_m : float
            Peak isolator displacement D [m].

        Returns
        -------
        EffectiveProperties
            NaN stiffness, period and damping when D = 0 (the isolator did not slide).
        """
        d = abs(float(displacement_m))
        friction_N = self.mu_kinetic * self.weight_N
        if d == 0.0:
            nan = math.nan
            return EffectiveProperties(0.0, nan, nan, nan, friction_N)
        k_eff = self.stiffness_N_per_m + friction_N / d
        omega_eff = math.sqrt(k_eff / self.mass_kg)
        energy_J = 4.0 * friction_N * d + math.pi * self.damping_Ns_per_m * omega_eff * d * d
        beta = energy_J / (2.0 * math.pi * k_eff * d * d)
        force_N = self.stiffness_N_per_m * d + friction_N + self.damping_Ns_per_m * omega_eff * d
        return EffectiveProperties(d, k_eff, 2.0 * math.pi / omega_eff, beta, force_N)

    def as_dict(self) -> dict:
        """The design's input and derived numbers (SI units)."""
        return {
            "name": self.name,
            "source": self.source,
            "kind": "friction pendulum" if self.is_pendulum else "flat slider with spring",
            "mass_kg": self.mass_kg,
            "radius_m": self.radius_m,
            "stiffness_N_per_m": self.stiffness_N_per_m,
            "mu_static": self.mu_static,
            "mu_kinetic": self.mu_kinetic,
            "damping_Ns_per_m": self.damping_Ns_per_m,
            "damping_ratio": self.damping_ratio,
            "isolated_period_s": self.isolated_period_s,
            "gravity_m_s2": self.gravity_m_s2,
        }
