r"""Adapter: a design and a ground motion → the solver's system and the paper's point.

A record is mapped onto the harmonic motion with the same peak ground acceleration and
peak ground velocity (exact for a harmonic record: a sampled cosine of amplitude A0 and
angular frequency Ω has PGA = A0 Ω² and PGV = A0 Ω):

.. math::  A_0 = \frac{PGV^2}{PGA},\quad \Omega = \frac{PGA}{PGV},\quad
           \alpha = \frac{PGA}{\mu_s g},\quad k = \frac{K A_0}{M g},\quad
           \eta = \frac{\gamma}{M}\sqrt{\frac{A_0}{g}}

(Nicolas 2017, Eq. 6; for a friction pendulum k = A0/R.)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from isolator.design import Design


@dataclass(frozen=True)
class DimensionlessPoint:
    """The paper's dimensionless parameters of a design under a ground motion.

    Attributes
    ----------
    alpha : float
        α = PGA / (µs g) [-] (Eq. 6).
    k : float
        k = K A0 / (M g) [-].
    eta : float
        η = (γ/M) sqrt(A0/g) [-].
    mu_s, mu_k : float
        Friction coefficients [-].
    a0_m : float
        A0 = PGV²/PGA, the equivalent harmonic ground-displacement amplitude [m].
    omega_rad_s : float
        Ω = PGA/PGV, the equivalent angular frequency [rad/s].
    regime : str or None
        For a double or triple bearing, the backbone regime whose line gives the single
        pendulum of the point (:meth:`isolator.bearing.Bearing.point_regime`); None for one
        surface.
    regime_reason : str
        Which regime and why, in one sentence ("" for one surface).
    """

    alpha: float
    k: float
    eta: float
    mu_s: float
    mu_k: float
    a0_m: float
    omega_rad_s: float
    regime: str | None = None
    regime_reason: str = ""

    def as_dict(self) -> dict:
        return {"alpha": self.alpha, "k": self.k, "eta": self.eta, "mu_s": self.mu_s, "mu_k": self.mu_k,
                "a0_m": self.a0_m, "omega_rad_s": self.omega_rad_s, "point_regime": self.regime,
                "point_regime_reason": self.regime_reason}


def dimensionless_point(design: Design, pga_m_s2: float, pgv_m_s: float, *,
                        regimes_entered=None) -> DimensionlessPoint:
    """The paper's (α, k, η) of a design under a motion of given PGA and PGV.

    For a double or triple bearing the paper's single pendulum is a line of the bearing's
    backbone: the regime the motion reached when its ``regimes_entered`` are given
    (:meth:`isolator.bearing.Bearing.point_regime`), else the design's equivalent (every
    element sliding: regime III of a triple).  k = A0/R and α = PGA/(µ g) on that line.

    Parameters
    ----------
    design : Design
        The isolator.
    pga_m_s2 : float
        Peak ground acceleration [m/s²], > 0.
    pgv_m_s : float
        Peak ground velocity [m/s], > 0.
    regimes_entered : mapping, optional
        The response's ``regimes`` (name → first time [s]) of a double or triple bearing.

    Returns
    -------
    DimensionlessPoint
    """
    from isolator.errors import RecordInputError

    # the record's fault, not the design's: a record of zeros (or scaled to nothing) has no
    # equivalent harmonic motion (A0 = PGV²/PGA, Eq. 6 of the paper needs A0 > 0)
    if not (pga_m_s2 > 0 and pgv_m_s > 0):
        raise RecordInputError(f"the record has PGA = {pga_m_s2:g} m/s² and PGV = {pgv_m_s:g} m/s: no ground "
                               "motion to analyse (both must be > 0)")
    g = design.gravity_m_s2
    a0_m = pgv_m_s ** 2 / pga_m_s2
    if not (math.isfinite(a0_m) and a0_m > 0 and math.isfinite(pga_m_s2 / pgv_m_s)):
        raise RecordInputError(f"the record's equivalent amplitude PGV²/PGA = {a0_m:g} m is not a positive "
                               f"finite number (PGA = {pga_m_s2:g} m/s², PGV = {pgv_m_s:g} m/s): a motion that "
                               "small is below floating-point resolution")
    mu_s, mu_k = design.mu_static, design.mu_kinetic
    k = design.stiffness_N_per_m * a0_m / (design.mass_kg * g)
    regime, reason = None, ""
    bearing = design.bearing
    if bearing is not None and not bearing.is_simple:
        if regimes_entered is None:
            regime = "III" if bearing.kind == "triple" else "+".join(str(i + 1) for i in range(len(bearing.surfaces)))
            reason = (f"before the response: the design's equivalent single pendulum (every element sliding, regime "
                      f"{regime})")
        else:
            regime, radius, mu, reason = bearing.point_regime(regimes_entered)
            mu_s = mu_k = mu
            k = a0_m / radius
    return DimensionlessPoint(
        alpha=pga_m_s2 / (mu_s * g),
        k=k,
        eta=design.damping_per_mass * math.sqrt(a0_m / g),
        mu_s=mu_s,
        mu_k=mu_k,
        a0_m=a0_m,
        omega_rad_s=pga_m_s2 / pgv_m_s,
        regime=regime,
        regime_reason=reason,
    )


@dataclass(frozen=True)
class Adaptation:
    """Everything the solver and the classification need about a design under a motion."""

    design: Design
    system: object  #: isolator.solver.system.System (per unit mass)
    point: DimensionlessPoint
    intensity: object  #: isolator.motion.IntensityMeasures

    def on_response(self, response) -> Adaptation:
        """This adaptation with the paper's point on the regime the response reached (a new object).

        Only a double or triple bearing's point changes (:func:`dimensionless_point` with the
        response's ``regimes``); any other design's point does not depend on the response.
        """
        bearing = self.design.bearing
        regimes = getattr(response, "regimes", None)
        if bearing is None or bearing.is_simple or regimes is None:
            return self
        point = dimensionless_point(self.design, self.intensity.pga_m_s2, self.intensity.pgv_m_s,
                                    regimes_entered=regimes)
        return Adaptation(design=self.design, system=self.system, point=point, intensity=self.intensity)

    def dimensional_dict(self) -> dict:
        """K [N/m], γ [N·s/m], µs, µk, M [kg]: the dimensional system."""
        d = self.design
        return {"mass_kg": d.mass_kg, "stiffness_N_per_m": d.stiffness_N_per_m,
                "damping_Ns_per_m": d.damping_Ns_per_m, "mu_static": d.mu_static, "mu_kinetic": d.mu_kinetic,
                "configuration": self.system.configuration}


def adapt(design: Design, motion, intensity=None) -> Adaptation:
    """Map a design and a ground motion onto the solver and the paper.

    Parameters
    ----------
    design : Design
        The isolator.
    motion : isolator.motion.GroundMotion or isolator.motion.MotionPair
        The ground acceleration [m/s²]: one component, or a pair (its horizontal
        resultant places it on the paper's point, :func:`motion_intensity`).
    intensity : isolator.motion.IntensityMeasures, optional
        The motion's intensity measures if already computed (they cost a response
        spectrum; a batch computes them once per record for all its designs).

    Returns
    -------
    Adaptation
    """
    if intensity is None:
        intensity = motion_intensity(motion)
    point = dimensionless_point(design, intensity.pga_m_s2, intensity.pgv_m_s)
    return Adaptation(design=design, system=design.system(), point=point, intensity=intensity)


def engineering_quantities(design: Design, response) -> dict:
    """What a reviewer reads for an isolator under a record (SI units).

    Parameters
    ----------
    design : Design
        The isolator.
    response : isolator.solver.base.SolverResult
        Its response to the record (peaks are resultants in the plane).

    Returns
    -------
    dict
        ``isolated_period_s`` (T = 2π sqrt(M/K)), ``peak_displacement_m`` D,
        ``effective_stiffness_N_per_m``, ``effective_period_s`` and
        ``effective_damping_ratio`` at D (see :meth:`Design.effective_properties`),
        ``peak_transmitted_force_N`` = M × peak absolute acceleration of the mass
        (the horizontal force through the isolator into the superstructure),
        ``base_shear_coefficient`` = that force / (M g), and ``design_force_N`` (the
        bilinear force K D + µk M g at D).
    """
    peak_d = float(response.peak_displacement_m)
    effective = design.effective_properties(peak_d)
    force_N = design.mass_kg * float(response.peak_transmitted_acceleration_m_s2)
    return {
        "isolated_period_s": design.isolated_period_s,
        "peak_displacement_m": peak_d,
        "residual_displacement_m": float(response.residual_displacement_m),
        "effective_stiffness_N_per_m": effective.effective_stiffness_N_per_m,
        "effective_period_s": effective.effective_period_s,
        "effective_damping_ratio": effective.effective_damping_ratio,
        "peak_transmitted_force_N": force_N,
        "base_shear_coefficient": force_N / design.weight_N,
        "design_force_N": effective.design_force_N,
    }


def motion_keywords(design: Design) -> dict:
    """The isolator keywords of :class:`isolator.solver.models.Scene` of a design (per unit mass).

    A friction pendulum is given by its radius (κ = g/R, or n(t)/R with a vertical
    record); any other design by K/M.  µ(v) is passed when the design gives it, which
    selects the 2-D engine even for one component.

    Parameters
    ----------
    design : Design
        The isolator.

    Returns
    -------
    dict
        ``mu_static``, ``mu_kinetic``, ``radius_m`` or ``stiffness_per_mass`` [1/s²],
        ``damping_per_mass`` [1/s], ``gravity_m_s2`` [m/s²] and, for µ(v), ``mu_slow``,
        ``mu_fast``, ``rate_s_per_m`` [s/m].
    """
    keywords = {"mu_static": design.mu_static, "mu_kinetic": design.mu_kinetic,
                "damping_per_mass": design.damping_per_mass, "gravity_m_s2": design.gravity_m_s2}
    if design.is_pendulum:
        keywords["radius_m"] = design.radius_m
    else:
        keywords["stiffness_per_mass"] = design.stiffness_per_mass
    if design.velocity_dependent:  # µ(v) replaces the constant kinetic coefficient
        del keywords["mu_kinetic"]
        keywords.update(mu_slow=design.mu_slow, mu_fast=design.mu_fast, rate_s_per_m=design.rate_s_per_m)
    return keywords


#: Why a pair's horizontal intensity measures carry no predominant period.
PAIR_PREDOMINANT_PERIOD_REASON = ("a pair's horizontal resultant has no single response spectrum: see each "
                                  "component's spectrum")


def motion_intensity(motion):
    """The intensity measures that place a motion on the paper's point: of the component, or of the pair's
    horizontal resultant.

    For a pair (X, Y) the measures are those of the horizontal vector a(t) = (a_x, a_y):
    PGA = max |a|, PGV = max |v| (trapezoidal velocity from rest), PGD = max |d| (the
    baseline-corrected displacement of each component), Arias = the sum of the components'
    (∫|a|² dt), D5–95 of |a|²; A0 = PGV²/PGA and Ω = PGA/PGV as for one component.  The
    predominant period is NaN (:data:`PAIR_PREDOMINANT_PERIOD_REASON`).  A "pair" of one
    horizontal and a vertical is its horizontal component's.

    Parameters
    ----------
    motion : isolator.motion.GroundMotion or isolator.motion.MotionPair
        Ground acceleration [m/s²].

    Returns
    -------
    isolator.motion.IntensityMeasures
    """
    import numpy as np

    from isolator.motion.measures import (
        IntensityMeasures,
        arias_intensity_m_s,
        displacement_m,
        significant_duration_s,
        velocity_m_s,
    )

    parts = getattr(motion, "components", None)
    if not isinstance(parts, dict):
        return motion.intensity_measures()
    if "y" not in parts:
        return parts["x"].intensity_measures()
    x, y = parts["x"], parts["y"]
    dt, times = motion.dt_s, motion.sample_times_s
    ax, ay = x.acceleration_m_s2, y.acceleration_m_s2
    pga = float(np.max(np.hypot(ax, ay)))
    pgv = float(np.max(np.hypot(velocity_m_s(ax, dt, times), velocity_m_s(ay, dt, times))))
    pgd = float(np.max(np.hypot(displacement_m(ax, dt, times), displacement_m(ay, dt, times))))
    both = pga > 0 and pgv > 0
    return IntensityMeasures(
        pga_m_s2=pga, pgv_m_s=pgv, pgd_m=pgd,
        arias_m_s=arias_intensity_m_s(ax, dt, times) + arias_intensity_m_s(ay, dt, times),
        d5_95_s=significant_duration_s(np.hypot(ax, ay), dt, time_s=times),
        predominant_period_s=math.nan,
        a0_equiv_m=pgv ** 2 / pga if both else math.nan,
        omega_equiv_rad_s=pga / pgv if both else math.nan,
    )
