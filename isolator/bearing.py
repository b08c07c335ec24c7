r"""Multi-surface friction pendulums: single, double and triple bearings with rims.

A design file may describe its bearing surface by surface (outer-bottom first: 1, 2, 3, 4
in Fenz & Constantinou's numbering)::

    [bearing]
    type = "triple"            # "single" | "double" | "triple"

    [[bearing.surface]]        # surface 1 (outer, bottom)
    radius_m = 2.2
    height_m = 0.1             # slider height: R_eff = R − h (default 0)
    mu = 0.06                  # or mu_kinetic (+ mu_static), or mu_slow/mu_fast/rate_s_per_m
    displacement_capacity_m = 0.42

    [[bearing.surface]]        # surface 2 (inner, bottom) ... then 3 and 4

Per surface: effective radius :math:`R_{eff,i} = R_i - h_i`, capacity
:math:`d_i^* = d_i R_{eff,i}/R_i` (the displacement of the bearing's axis when the slider
is at the rim).  The force–displacement law is the series model of
:mod:`isolator.solver.multisurface_series`: for a triple pendulum it reproduces the five
regimes of Fenz & Constantinou (2008) — I: sliding on 2 and 3; II: on 1 and 3; III: on 1
and 4; IV: 1 on its rim, sliding on 2 and 4; V: 1 and 4 on their rims, sliding on 2 and
3 — and ends at the ultimate displacement :math:`\sum_i d_i^*`, where every slider is on
its rim.

References
----------
D. M. Fenz, M. C. Constantinou (2008), Earthquake Engng Struct. Dyn. 37, 163–183, and
Earthquake Spectra 24(4), 1011–1028.  ASCE 7-22 §17.2.8.4 / AASHTO GSID: effective
stiffness and damping from the force–displacement loop.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from isolator.errors import DesignError, key_hint, printable
from isolator.solver.multisurface_series import (
    DECREASING_RATE_REASON,
    STATIC_FRICTION_REASON,
    excursion,
    max_regimes,
    series_elements,
    settle,
    stick_window,
    surface_matrix,
)
from isolator.solver.system import MAX_STIFFNESS_PER_MASS, RATE_MAX_S_PER_M
from isolator.units import STANDARD_GRAVITY

#: The number of surfaces of each bearing type.
SURFACES_PER_TYPE = {"single": 1, "double": 2, "triple": 4}

#: Least slope at rest a (µ_fast - µ_slow) [s/m] of a surface's µ(v) on a double or triple bearing: the series
#: models invert each µ_i(v) (the slide speed from the force), whose derivative 1/(a (µ_fast - µ)) grows without
#: bound as the slope vanishes.  rate_s_per_m = 1e-300 was a LinAlgError traceback (1-D and 2-D); 1e-2 ground for
#: 79 s before the 2-D engine gave up, 1e-3 ran past 90 s (slopes 2e-4 and 2e-5; session 13, docs/security.md).
#: Below 1e-3 the law differs from constant friction at mu_slow by < 2e-3 at 2 m/s, faster than sliders move.
MIN_RATE_SLOPE_S_PER_M = 1e-3

#: Least displacement capacity d_i of a surface [m].  No bearing is built with less travel on a surface (catalogue
#: triple pendulums: inner surfaces 25-75 mm, outer 100-500 mm; a double's 100-600 mm), so a smaller one is a
#: mistake in units or a lost digit, not a design: read as given, the slider sits at its rim from its first slip and
#: the rim's contacts, not the isolator, are analysed (an outer capacity of 1e-9 m ran for 69.7 s and answered,
#: session 13 sweep, docs/security.md).  1 mm is 25 times below the least catalogue value.
MIN_CAPACITY_M = 1e-3
#: What a structural engineer can mean by a design's numbers, read from a design file and its command-line flags
#: alike (key: (low, high, unit, why)); outside, the number is another unit or a slip of the keyboard: a design's
#: radius_m = 1e300 or a capacity of 1e300 m was read, and `design --vary radius_m=1e300,2` reviewed it (23 s, exit
#: 0), while `--radius-m 2500` (mm) ran as 2.5 km (session 17 sweep).  A friction coefficient's upper end, 1, is
#: open and has its own message; its lower one is harmonic's (isolator.solver.harmonic.MU_S_RANGE).
MEANT_RANGES = {
    "radius_m": (0.05, 50.0, "m", "a sliding surface's radius: isolation periods 0.45-14 s (2500 is mm, 98 in)"),
    "mu": (1e-4, 1.0, "", "a friction coefficient (sliding isolators have 0.02-0.15; below 1e-4 it is no friction "
                          "at all)"),
    "rate_s_per_m": (1.0, 1e4, "s/m", "measured rates of PTFE on steel are 10-200 s/m; below 1 s/m µ stays at "
                                      "mu_slow through any earthquake's velocities: give mu_kinetic instead"),
    "displacement_capacity_m": (MIN_CAPACITY_M, 10.0, "m", "a bearing's travel: 25-600 mm per surface are built "
                                                          "(MIN_CAPACITY_M's note); 10 m is 16 times that"),
}


def outside_meant(kind: str, value: float) -> str:
    """"" if ``value`` lies in :data:`MEANT_RANGES` ``[kind]``, else the sentence after "<key> = <value> is ..."."""
    low, high, unit, why = MEANT_RANGES[kind]
    inside = low <= value < high if not unit else low <= value <= high
    if inside:
        return ""
    shown = f"[{low:g}, {high:g})" if not unit else f"[{low:g}, {high:g}] {unit}"
    return f"outside {shown}: {why}"

#: Keys of a ``[[bearing.surface]]`` entry.
SURFACE_KEYS = {
    "radius_m": "radius of curvature R_i [m], > 0",
    "height_m": "height h_i of the slider over the surface (R_eff = R - h) [m], 0 <= h < R (default 0)",
    "mu": "friction coefficient µ_i [-] (kinetic = static)",
    "mu_kinetic": "kinetic friction coefficient µ_i [-]",
    "mu_static": "static friction coefficient [-] >= mu_kinetic (single surface only)",
    "mu_slow": "velocity-dependent friction µ at rest [-] (<= mu_fast; on every surface or none)",
    "mu_fast": "velocity-dependent friction µ at high speed [-]",
    "rate_s_per_m": "velocity-dependent friction rate [s/m]",
    "displacement_capacity_m": "displacement capacity d_i on the surface [m], > 0 (required for double/triple)",
}

#: Keys of the ``[bearing]`` table.
BEARING_KEYS = {"type": "single | double | triple", "surface": "the surfaces, [[bearing.surface]], outer-bottom first"}

#: Regime names of a triple pendulum (Fenz & Constantinou 2008), from the state of the outer elements.
TRIPLE_REGIMES = ("I", "II", "III", "IV", "V")


@dataclass(frozen=True)
class Surface:
    """One concave surface of a bearing (SI units).

    Attributes
    ----------
    radius_m : float
        Radius of curvature R [m].
    height_m : float
        Slider height h [m]; R_eff = R − h.
    mu_kinetic : float
        Kinetic friction coefficient [-].
    mu_static : float
        Static friction coefficient [-] (= µk except for a single surface).
    displacement_capacity_m : float or None
        Capacity d on the surface [m] (None: no rim).
    mu_slow, mu_fast, rate_s_per_m : float or None
        Velocity-dependent friction µ(v) = µ_fast − (µ_fast − µ_slow) e^{−a v} (a double or triple:
        on every surface or none; model ``1d-multisurface+mu(v)``).
    """

    radius_m: float
    height_m: float
    mu_kinetic: float
    mu_static: float
    displacement_capacity_m: float | None
    mu_slow: float | None = None
    mu_fast: float | None = None
    rate_s_per_m: float | None = None

    @property
    def effective_radius_m(self) -> float:
        """R_eff = R − h [m]."""
        return self.radius_m - self.height_m

    @property
    def effective_capacity_m(self) -> float:
        """d* = d R_eff / R [m] (inf without a capacity)."""
        if self.displacement_capacity_m is None:
            return math.inf
        if self.height_m == 0.0:
            return self.displacement_capacity_m  # d exactly (d R/R may round away from d)
        return self.displacement_capacity_m * self.effective_radius_m / self.radius_m


@dataclass(frozen=True)
class Backbone:
    """The monotonic force–displacement curve of a bearing from rest (piecewise linear).

    Attributes
    ----------
    displacement_m : numpy.ndarray
        Transition points x_k [m]: the start of each regime, then the ultimate
        displacement (when the bearing has rims).
    force_per_weight : numpy.ndarray
        F/W at those points [-].
    stiffness_per_weight_1_m : numpy.ndarray
        Slope of each regime, dF/dx / W = 1/Σ R̄ [1/m] (one fewer than the points when
        the last point is the ultimate displacement; inf for a rigid step).
    regimes : tuple of str
        The name of each regime (I–V for a triple pendulum; the sliding surfaces otherwise).
    ultimate_displacement_m : float
        Σ d_i* [m] (inf without rims).
    """

    displacement_m: np.ndarray
    force_per_weight: np.ndarray
    stiffness_per_weight_1_m: np.ndarray
    regimes: tuple
    ultimate_displacement_m: float

    def force_per_weight_at(self, displacement_m: float) -> float:
        """F/W on the backbone at x ≥ 0 [-] (the upper end of a rigid step)."""
        x = float(displacement_m)
        if x > self.ultimate_displacement_m:
            raise ValueError(f"{x:g} m is beyond the ultimate displacement {self.ultimate_displacement_m:g} m")
        k = int(np.searchsorted(self.displacement_m, x, side="right")) - 1
        k = min(max(k, 0), self.stiffness_per_weight_1_m.size - 1)
        return float(self.force_per_weight[k] + self.stiffness_per_weight_1_m[k] * (x - self.displacement_m[k]))


@dataclass(frozen=True)
class LoopProperties:
    """Effective (equivalent-linear) properties of a bearing cycled between ±D (SI units)."""

    displacement_m: float
    effective_stiffness_N_per_m: float
    effective_period_s: float
    effective_damping_ratio: float
    energy_per_cycle_J: float
    force_at_displacement_N: float
    regime: str  #: the backbone regime at D

    def as_dict(self) -> dict:
        return {"displacement_m": self.displacement_m,
                "effective_stiffness_N_per_m": self.effective_stiffness_N_per_m,
                "effective_period_s": self.effective_period_s,
                "effective_damping_ratio": self.effective_damping_ratio,
                "energy_per_cycle_J": self.energy_per_cycle_J,
                "force_at_displacement_N": self.force_at_displacement_N, "regime": self.regime}


@dataclass(frozen=True)
class Bearing:
    """A friction-pendulum bearing of 1, 2 or 4 concave surfaces.

    Parameters
    ----------
    kind : {"single", "double", "triple"}
    surfaces : tuple of Surface
        In file order (outer-bottom first).
    """

    kind: str
    surfaces: tuple

    # ---- the series model ---------------------------------------------------------------
    @property
    def effective_radii_m(self) -> np.ndarray:
        return np.array([s.effective_radius_m for s in self.surfaces])

    @property
    def mu_kinetic(self) -> np.ndarray:
        return np.array([s.mu_kinetic for s in self.surfaces])

    @property
    def mu_static(self) -> np.ndarray:
        """Static friction per surface (= element) [-]; above µk only on a single surface."""
        return np.array([s.mu_static for s in self.surfaces])

    @property
    def effective_capacities_m(self) -> np.ndarray:
        return np.array([s.effective_capacity_m for s in self.surfaces])

    def elements(self):
        """The series elements (R̄ [m], µ [-], rim c̄ [m]); see :func:`series_elements`."""
        return series_elements(self.kind, self.effective_radii_m, self.mu_kinetic, self.effective_capacities_m)

    def surface_matrix(self) -> np.ndarray:
        """T with u = T ū (effective displacement on each real surface from the elements') [-]."""
        return surface_matrix(self.kind, self.effective_radii_m)

    @property
    def has_rims(self) -> bool:
        return all(s.displacement_capacity_m is not None for s in self.surfaces)

    @property
    def ultimate_displacement_m(self) -> float:
        """Σ d_i* [m]: every slider on its rim (inf when a surface has no capacity)."""
        return float(np.sum(self.effective_capacities_m))

    @property
    def is_simple(self) -> bool:
        """True for one surface (today's single pendulum)."""
        return self.kind == "single"

    def regime_name(self, mask: int, rimmed: int) -> str:
        """The name of a state: sliding elements ``mask`` and elements on a rim ``rimmed`` (bit sets).

        A triple pendulum's regimes follow Fenz & Constantinou: I (inner sliding, no outer
        on its rim), II (one outer sliding), III (both outer), IV (one outer on its rim, the
        other sliding), V (both outer on their rims); an unloading state with one outer on
        its rim and only the inner sliding has no name of its own (``""``).  In each of F&C's
        regimes both inner sliders slide; a state where one of them slides alone (the other
        not yet started, µ2 ≠ µ3, or on its rim first, unequal inner capacities or radii) is
        the regime's name with ``" (one inner)"``: it was named I, I or V, V before (session 17
        sweep), and a motion that entered only the first was read as having reached the second
        (:meth:`point_regime`).  Other types name the sliding surfaces: ``"1"``, ``"2"``, ``"1+2"``.
        """
        if self.kind != "triple":
            return "+".join(str(i + 1) for i in range(len(self.surfaces)) if mask >> i & 1)
        outer_active = (mask & 1) + (mask >> 3 & 1)
        outer_rim = (rimmed & 1) + (rimmed >> 3 & 1)
        if mask == 0:
            return ""
        if outer_rim == 0:
            name = TRIPLE_REGIMES[outer_active]
        elif outer_rim == 1:
            name = "IV" if outer_active == 1 else ""
        else:
            name = "V"
        inner_active = (mask >> 1 & 1) + (mask >> 2 & 1)
        return f"{name} (one inner)" if name and inner_active == 1 else name

    def backbone(self) -> Backbone:
        """The monotonic loading curve from rest, its transition points and regimes."""
        rbar, mu, rim = self.elements()
        size = max_regimes(rbar.size)
        reg_x, reg_r, reg_rsum = np.empty(size), np.empty(size), np.empty(size)
        reg_mask = np.zeros(size, dtype=np.int64)
        n_reg = excursion(1.0, np.zeros(rbar.size), rbar, mu, rim, 0.0, reg_x, reg_r, reg_rsum, reg_mask)
        rimmed = 0
        names = []
        slopes = []
        for k in range(n_reg):
            # elements that started and are no longer sliding are on their rims
            started_before = 0
            for j in range(k):
                started_before |= int(reg_mask[j])
            rimmed = started_before & ~int(reg_mask[k])
            if reg_rsum[k] == 0.0 and k == n_reg - 1:
                break  # the ultimate displacement: a point, not a regime
            names.append(self.regime_name(int(reg_mask[k]), rimmed))
            slopes.append(math.inf if reg_rsum[k] == 0.0 else 1.0 / reg_rsum[k])
        return Backbone(displacement_m=reg_x[:n_reg].copy(), force_per_weight=reg_r[:n_reg].copy(),
                        stiffness_per_weight_1_m=np.array(slopes), regimes=tuple(names),
                        ultimate_displacement_m=self.ultimate_displacement_m)

    def point_regime(self, regimes_entered) -> tuple[str, float, float, str]:
        """The backbone regime a motion reached, as a single pendulum: its line F/W = x/R + µ.

        The regime reached is the last one along the backbone among those the motion
        entered (``regimes_entered``: the response's ``regimes``, name → first time [s]).
        Its line's compliance R = Σ R̄ of the sliding elements and its F/W intercept µ
        make the single pendulum of the paper's point (Nicolas 2017, Eq. 6: k = A0/R,
        α = PGA/(µ g)).  Past the rims (regimes IV and V of a triple, a double's last
        surface after the first's rim) the line's intercept is ≤ 0 — the bearing stiffens,
        no pendulum has that line — and the point is taken on the last regime before them
        with an intercept > 0; the reason says so.

        Parameters
        ----------
        regimes_entered : mapping or sequence of str
            Names of the regimes the motion entered (first times as values, if a mapping).

        Returns
        -------
        tuple
            ``(regime, radius_m, mu, reason)``: the regime the point is taken on, R [m],
            µ [-], and one sentence.
        """
        bb = self.backbone()
        times = dict(regimes_entered) if isinstance(regimes_entered, dict) else dict.fromkeys(regimes_entered)
        # a name counts at its first place: a double's "1" again past surface 2's rim is told from the "1" it starts in
        # by no name (the response keeps each name's first time), so entering "1" is not reaching past the rim
        reached = [k for k, name in enumerate(bb.regimes) if name in times and name not in bb.regimes[:k]]
        if not reached:
            k = 0
            top = None
        else:
            top = max(reached)
            k = top
        while k > 0 and not self._pendulum_line(bb, k)[1] > 0.0:
            k -= 1
        radius, mu = self._pendulum_line(bb, k)
        name = bb.regimes[k]
        line = f"R = {radius:.4g} m (sum of the sliding elements' R), mu = {mu:.4g} (the line's F/W intercept)"
        if top is None:
            reason = f"the bearing never slid: the point is on regime {name}, where sliding begins: {line}"
        elif top == k:
            when = times.get(name)
            at = "" if when is None else f" (first at {when:.4g} s)"
            reason = f"the motion reached regime {name}{at}: the point is on its line, {line}"
        else:
            reason = (f"the motion reached regime {bb.regimes[top]}, whose line has an F/W intercept <= 0 (the bearing "
                      f"stiffens at the rims: no single pendulum has it): the point is on regime {name}, the last "
                      f"reached with a pendulum's line, {line}")
        return name, radius, mu, reason

    @staticmethod
    def _pendulum_line(bb: Backbone, k: int) -> tuple[float, float]:
        # (R [m], µ [-]) of regime k's line F/W = x/R + µ; (0, -inf) for a rigid step
        slope = float(bb.stiffness_per_weight_1_m[k])
        if not (math.isfinite(slope) and slope > 0.0):
            return 0.0, -math.inf
        radius = 1.0 / slope
        return radius, float(bb.force_per_weight[k] - bb.displacement_m[k] / radius)

    def quasi_static_path(self, targets_m, *, leg_ends: list | None = None) -> tuple[np.ndarray, np.ndarray]:
        """The force along a displacement-controlled path from rest, as a polyline.

        Parameters
        ----------
        targets_m : sequence of float
            Turning points of the imposed displacement [m], each within ±ultimate.
        leg_ends : list, optional
            Appended with the index of the vertex that ends each leg.

        Returns
        -------
        tuple of numpy.ndarray
            ``(x_m, force_per_weight)``: the vertices of F/W against x, in order, vertical
            steps included (a reversal, a rigid rim).
        """
        rbar, mu, rim = self.elements()
        u = np.zeros(rbar.size)
        size = max_regimes(rbar.size)
        reg_x, reg_r, reg_rsum = np.empty(size), np.empty(size), np.empty(size)
        reg_mask = np.zeros(size, dtype=np.int64)
        x = 0.0
        xs, rs = [0.0], [0.0]
        ultimate = self.ultimate_displacement_m
        for target in targets_m:
            target = float(target)
            if abs(target) > ultimate * (1.0 + 1e-12):
                raise ValueError(f"target {target:g} m is beyond the ultimate displacement {ultimate:g} m")
            if target == x:
                continue
            s = 1.0 if target > x else -1.0
            n_reg = excursion(s, u, rbar, mu, rim, x, reg_x, reg_r, reg_rsum, reg_mask)
            r_end = reg_r[0]
            for k in range(n_reg):
                if s * (reg_x[k] - target) > 0.0:
                    break
                xs.append(float(reg_x[k]))
                rs.append(float(reg_r[k]))
                r_end = reg_r[k]
                if reg_rsum[k] > 0.0:
                    r_end = reg_r[k] + (target - reg_x[k]) / reg_rsum[k]
            xs.append(target)
            rs.append(float(r_end))
            if leg_ends is not None:
                leg_ends.append(len(xs) - 1)
            settle(s, u, rbar, mu, rim, r_end)
            x = target
        return np.array(xs), np.array(rs)

    def stick_window(self, element_displacement_m) -> tuple[float, float]:
        """(F/W)_lo, (F/W)_hi that the stuck bearing holds at the given element state [-]."""
        rbar, mu, rim = self.elements()
        return stick_window(np.asarray(element_displacement_m, dtype=np.float64), rbar, mu, rim)

    def loop_properties(self, displacement_m: float, weight_N: float, gravity_m_s2: float) -> LoopProperties:
        r"""Effective stiffness, period and damping of the stable loop between ±D.

        .. math::  K_{eff} = \frac{F(+D) - F(-D)}{2D},\quad
                   \beta_{eff} = \frac{E_D}{2\pi K_{eff} D^2},\quad
                   T_{eff} = 2\pi\sqrt{\frac{W}{g K_{eff}}}

        (ASCE 7-22 §17.2.8.4, §17.8.5.2 and Eq. 17.8-1; AASHTO GSID 8.2.) The loop is the
        quasi-static cycle −D → +D → −D after a first loading to +D (the series model's
        loops are stable from the second half cycle); E_D is its exact polygon area.

        Parameters
        ----------
        displacement_m : float
            D [m], 0 < D ≤ the ultimate displacement.
        weight_N : float
            W = M g [N].
        gravity_m_s2 : float
            g [m/s²] (for the period).
        """
        d = abs(float(displacement_m))
        if not d > 0.0:
            raise ValueError("the loop needs a displacement > 0")
        ends: list = []
        xs, rs = self.quasi_static_path([d, -d, d, -d], leg_ends=ends)
        # the closed loop: the last two legs, from the vertex at the end of the second leg (-D)
        start = ends[1]
        loop_x, loop_r = xs[start:], rs[start:]
        area = 0.5 * float(np.sum(loop_x[:-1] * loop_r[1:] - loop_x[1:] * loop_r[:-1]))
        r_plus, r_minus = float(rs[ends[2]]), float(rs[ends[3]])
        k_eff = weight_N * (r_plus - r_minus) / (2.0 * d)
        energy = abs(area) * weight_N
        beta = energy / (2.0 * math.pi * k_eff * d * d)
        period = 2.0 * math.pi * math.sqrt(weight_N / (gravity_m_s2 * k_eff))
        bb = self.backbone()
        k = int(np.searchsorted(bb.displacement_m, d, side="left")) - 1
        regime = bb.regimes[min(max(k, 0), len(bb.regimes) - 1)]
        return LoopProperties(d, k_eff, period, beta, energy, r_plus * weight_N, regime)

    def as_dict(self) -> dict:
        """The bearing's input and derived numbers (SI units)."""
        bb = self.backbone()
        return {
            "type": self.kind,
            "surfaces": [{"radius_m": s.radius_m, "height_m": s.height_m, "effective_radius_m": s.effective_radius_m,
                          "mu_kinetic": s.mu_kinetic, "mu_static": s.mu_static,
                          "displacement_capacity_m": s.displacement_capacity_m,
                          "effective_capacity_m": None if s.displacement_capacity_m is None
                          else s.effective_capacity_m} for s in self.surfaces],
            "ultimate_displacement_m": self.ultimate_displacement_m,
            "backbone_displacement_m": bb.displacement_m.tolist(),
            "backbone_force_per_weight": bb.force_per_weight.tolist(),
            "backbone_regimes": list(bb.regimes),
        }

    def effective_properties(self, displacement_m: float, mass_kg: float, gravity_m_s2: float,
                             damping_Ns_per_m: float = 0.0) -> tuple:
        """The fields of :class:`isolator.design.EffectiveProperties` at D, from the loop (:meth:`loop_properties`).

        A supplemental damper adds π γ ω_eff D² to E_D and γ ω_eff D to the force, as for
        the single pendulum (:meth:`isolator.design.Design.effective_properties`).  NaN when
        D = 0 or D is beyond the ultimate displacement (the loop does not exist there).

        Returns
        -------
        tuple
            (D [m], K_eff [N/m], T_eff [s], β_eff [-], force at D [N]).
        """
        d = abs(float(displacement_m))
        weight = mass_kg * gravity_m_s2
        if d == 0.0 or d > self.ultimate_displacement_m:
            nan = math.nan
            return d, nan, nan, nan, nan
        lp = self.loop_properties(d, weight, gravity_m_s2)
        omega = math.sqrt(lp.effective_stiffness_N_per_m / mass_kg)
        energy = lp.energy_per_cycle_J + math.pi * damping_Ns_per_m * omega * d * d
        beta = energy / (2.0 * math.pi * lp.effective_stiffness_N_per_m * d * d)
        return (d, lp.effective_stiffness_N_per_m, lp.effective_period_s, beta,
                lp.force_at_displacement_N + damping_Ns_per_m * omega * d)

    def with_friction_factor(self, factor: float, fail=DesignError) -> Bearing:
        """Every µ_i multiplied by λ (a property bound) [-], read again by the rules of :func:`parse_bearing`.

        λ moves the friction, so the rules that hold friction are checked again: a µ(v) law's slope at rest
        a λ (µ_fast − µ_slow) (:data:`MIN_RATE_SLOPE_S_PER_M`; a law at 1.1e-3 read at nominal fell to 9.35e-4
        at λ = 0.85 and was run, session 14) and a triple's regime-II reach d*_i ≥ λ (µ_o − µ_i) R_eff,i.
        ``fail(message) -> DesignError`` says where (the design file and the bound).
        """
        from dataclasses import replace

        if max(max(s.mu_kinetic, s.mu_static) for s in self.surfaces) * factor >= 1.0:
            raise fail(f"a bearing surface's µ × λ ({factor:g}) must stay < 1")

        def scaled(v):
            return None if v is None else v * factor

        bearing = replace(self, surfaces=tuple(replace(s, mu_kinetic=s.mu_kinetic * factor,
                                                       mu_static=s.mu_static * factor, mu_slow=scaled(s.mu_slow),
                                                       mu_fast=scaled(s.mu_fast)) for s in self.surfaces))
        if self.kind != "single":
            for i, s in enumerate(bearing.surfaces, start=1):
                if s.rate_s_per_m is not None and s.mu_slow < s.mu_fast:  # parse_bearing's rule: µ(v), not a flat law
                    _check_rate(s, f"bearing surface {i}", fail, factor)
        _check_geometry(bearing, fail)
        return bearing


def _what(value) -> str:
    """A TOML value named by its kind and (at most 40 characters of) its text, for a message."""
    kinds = {bool: "a boolean", int: "an integer", float: "a number", str: "a text", list: "an array"}
    kind = next((k for t, k in kinds.items() if isinstance(value, t)), f"a {type(value).__name__}")
    text = printable(repr(value))
    return f"{kind} ({text if len(text) <= 40 else text[:37] + '…'})"


def parse_bearing(table, fail, gravity_m_s2: float = STANDARD_GRAVITY) -> Bearing:
    """Validate a ``[bearing]`` table.

    Parameters
    ----------
    table : dict
        The table as read from TOML.
    fail : callable
        ``fail(message) -> DesignError`` (prefixes the file name).
    gravity_m_s2 : float
        g [m/s²]: a surface's stiffness per mass g/R_eff is held to the rigid block's limit.

    Returns
    -------
    Bearing

    Raises
    ------
    DesignError
        One line naming the key or the surface and the rule it breaks.
    """
    if not isinstance(table, dict):
        raise fail("key 'bearing' must be a table ([bearing] with type and [[bearing.surface]] entries)")
    for key in table:
        if key not in BEARING_KEYS:
            raise fail(f"unknown key 'bearing.{key}'{key_hint(key, BEARING_KEYS)}")
    kind = table.get("type")
    if not isinstance(kind, str) or kind not in SURFACES_PER_TYPE:  # an array or table: unhashable (session 17)
        raise fail(f"key 'bearing.type' must be one of {', '.join(repr(k) for k in SURFACES_PER_TYPE)}, got {kind!r}")
    entries = table.get("surface")
    n = SURFACES_PER_TYPE[kind]
    needs = f"a {kind} bearing needs {n} [[bearing.surface]] entr{'y' if n == 1 else 'ies'}"
    if entries is None:
        raise fail(f"{needs}; the design has none")
    if not isinstance(entries, list):  # it said "needs 4 entries" of `surface = "x"` (session 19 sweep)
        raise fail(f"key 'bearing.surface' must be an array of tables, one [[bearing.surface]] per surface (a {kind} "
                   f"bearing has {n}), got {_what(entries)}")
    for i, entry in enumerate(entries, start=1):  # `surface = [1, 2, 3, 4]` has 4 entries, none a table
        if not isinstance(entry, dict):
            raise fail(f"bearing surface {i} must be a table ([[bearing.surface]] with radius_m, mu_kinetic, …), "
                       f"got {_what(entry)}")
    if len(entries) != n:
        raise fail(f"a {kind} bearing needs {n} [[bearing.surface]] entr{'y' if n == 1 else 'ies'}, got {len(entries)}")
    surfaces = tuple(_surface(entry, i + 1, kind, fail) for i, entry in enumerate(entries))
    for i, surface in enumerate(surfaces, start=1):
        # as a design's radius_m: g/R_eff = 1e301 1/s² (R = 1e-300 m) overflowed the solver's sub-step count
        kappa = gravity_m_s2 / surface.effective_radius_m
        if not kappa <= MAX_STIFFNESS_PER_MASS:
            raise fail(f"bearing surface {i}: R_eff = {surface.effective_radius_m:g} m gives g/R_eff = {kappa:.3g} "
                       f"1/s², above {MAX_STIFFNESS_PER_MASS:g} 1/s²: no isolator is that stiff")
    rate_law = [s.rate_s_per_m is not None and s.mu_slow < s.mu_fast for s in surfaces]
    if kind != "single" and any(rate_law) and not all(rate_law):
        i = rate_law.index(False) + 1
        raise fail(f"bearing surface {i}: give µ(v) with mu_slow < mu_fast on every surface of a {kind} bearing "
                   "with µ(v), or a constant mu on every surface (a surface of constant friction in series with "
                   "µ(v) ones is not modelled)")
    for i, s in enumerate(surfaces, start=1):
        if kind != "single" and rate_law[i - 1]:
            _check_rate(s, f"bearing surface {i}", fail)
    bearing = Bearing(kind=kind, surfaces=surfaces)
    _check_geometry(bearing, fail)
    return bearing


def _check_rate(surface: Surface, where: str, fail, factor: float | None = None) -> None:
    """µ(v) of a series bearing's surface: neither steeper than the engines follow nor too flat to invert.

    ``factor``: the property bound λ the surface was scaled by (:meth:`Bearing.with_friction_factor`), None for the
    design as read; the hint of a refused slope then says which λ the law holds to, not to give µ = mu_slow.
    """
    rate = surface.rate_s_per_m
    if rate > RATE_MAX_S_PER_M:
        raise fail(f"{where}: rate_s_per_m = {rate:g} s/m exceeds {RATE_MAX_S_PER_M:g} s/m: µ would change from "
                   f"mu_slow to mu_fast within {1.0 / rate:.1g} m/s; so steep a law is constant friction at mu_fast "
                   "(give 'mu'; measured rates are 10-200 s/m)")
    slope = rate * (surface.mu_fast - surface.mu_slow)
    if slope < MIN_RATE_SLOPE_S_PER_M:
        if factor is None:
            hint = "give 'mu' = mu_slow"
        else:  # the design read at λ = 1: its slope is slope/λ, and λ scales it (µ_fast, µ_slow both × λ)
            nominal = slope / factor if factor > 0.0 else 0.0
            # the smallest λ that keeps the slope, rounded up to 3 decimals so that the λ printed reads
            lowest = math.ceil(MIN_RATE_SLOPE_S_PER_M / nominal * 1e3) / 1e3 if nominal > 0.0 else math.inf
            hint = (f"the design's own slope {nominal:.3g} stays above {MIN_RATE_SLOPE_S_PER_M:g} for λ >= {lowest:g}: "
                    "give a lower bound at or above that, or this bound as a design of constant 'mu'")
        raise fail(f"{where}: µ(v) rises by rate_s_per_m × (mu_fast - mu_slow) = {slope:.3g} per m/s at rest, "
                   f"below {MIN_RATE_SLOPE_S_PER_M:g}: the law is constant friction at mu_slow over any slider's "
                   f"speed and the series model cannot invert it ({hint})")


def _surface(entry: dict, index: int, kind: str, fail) -> Surface:
    where = f"bearing surface {index}"
    for key in entry:
        if key not in SURFACE_KEYS:
            raise fail(f"{where}: unknown key '{key}'{key_hint(key, SURFACE_KEYS)}")

    def number(key, *, required=False, positive=False):
        if key not in entry:
            if required:
                raise fail(f"{where}: missing key '{key}' ({SURFACE_KEYS[key]})")
            return None
        value = entry[key]
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise fail(f"{where}: key '{key}' must be a finite number, got {value!r}")
        value = float(value)
        if value < 0.0 or (positive and value == 0.0):
            raise fail(f"{where}: key '{key}' must be {'> 0' if positive else '>= 0'}, got {value:g}")
        return value

    radius = number("radius_m", required=True, positive=True)
    height = number("height_m") or 0.0
    if not height < radius:
        raise fail(f"{where}: height_m ({height:g}) must be < radius_m ({radius:g}) so that R_eff = R - h > 0")
    forms = [f for f in (("mu",), ("mu_kinetic", "mu_static"), ("mu_slow", "mu_fast", "rate_s_per_m"))
             if any(k in entry for k in f)]
    if len(forms) != 1:
        raise fail(f"{where}: give the friction one way: 'mu', or 'mu_kinetic' (+ 'mu_static'), "
                   "or 'mu_slow', 'mu_fast' and 'rate_s_per_m'")
    mu_slow = mu_fast = rate = None
    if forms[0] == ("mu",):
        mu_k = mu_s = number("mu", positive=True)
    elif forms[0][0] == "mu_kinetic":
        mu_k = number("mu_kinetic", required=True, positive=True)
        mu_s = number("mu_static")
        mu_s = mu_k if mu_s is None else mu_s
        if mu_s < mu_k:
            raise fail(f"{where}: mu_static ({mu_s:g}) must be >= mu_kinetic ({mu_k:g})")
    else:
        mu_slow = number("mu_slow", required=True)
        mu_fast = number("mu_fast", required=True, positive=True)
        rate = number("rate_s_per_m", required=True, positive=True)
        if mu_slow > mu_fast:
            why = "" if kind == "single" else f" on a {kind} bearing: {DECREASING_RATE_REASON}"
            raise fail(f"{where}: mu_slow ({mu_slow:g}) must not exceed mu_fast ({mu_fast:g}){why}")
        mu_k = mu_fast
        mu_s = mu_slow
    if max(mu_k, mu_s) >= 1.0:
        raise fail(f"{where}: friction must be < 1 for a sliding surface, got {max(mu_k, mu_s):g}")
    if kind != "single" and mu_s != mu_k and rate is None:
        raise fail(f"{where}: mu_static ({mu_s:g}) > mu_kinetic ({mu_k:g}) is not modelled on a {kind} bearing: "
                   f"{STATIC_FRICTION_REASON}; give 'mu' (or mu_static = mu_kinetic)")
    capacity = number("displacement_capacity_m", required=kind != "single", positive=True)
    if capacity is not None and capacity < MIN_CAPACITY_M:
        raise fail(f"{where}: displacement_capacity_m = {capacity:g} m is below {MIN_CAPACITY_M * 1e3:g} mm: no "
                   "bearing surface has so little travel (25-500 mm are built); is it in metres?")
    for key, range_kind, value in (("radius_m", "radius_m", radius), ("displacement_capacity_m",
                                   "displacement_capacity_m", capacity),  # a > 1e4 s/m: the engine's own message
                                   ("rate_s_per_m", "rate_s_per_m", None if rate is None or rate > 1e4 else rate),
                                   ("mu_slow" if mu_slow is not None else "mu", "mu", mu_s),
                                   # µk ≤ µs: 1e-300 was read (session 18 sweep); 'mu', µ_fast ≥ µ_slow: above
                                   ("mu_kinetic", "mu", mu_k if forms[0][0] == "mu_kinetic" else None)):
        problem = "" if value is None else outside_meant(range_kind, value)
        if problem:
            raise fail(f"{where}: key '{key}' = {value:g} is {problem}")
    return Surface(radius_m=radius, height_m=height, mu_kinetic=mu_k, mu_static=mu_s,
                   displacement_capacity_m=capacity, mu_slow=mu_slow, mu_fast=mu_fast, rate_s_per_m=rate)


def _check_geometry(bearing: Bearing, fail) -> None:
    """The orderings the series model covers (Fenz & Constantinou 2008)."""
    if bearing.kind != "triple":
        return
    s = bearing.surfaces
    for inner, outer in ((1, 0), (2, 3)):
        si, so = s[inner], s[outer]
        i, o = inner + 1, outer + 1
        if not si.effective_radius_m < so.effective_radius_m:
            raise fail(f"bearing surface {i}: R_eff,{i} = {si.effective_radius_m:g} m must be < R_eff,{o} = "
                       f"{so.effective_radius_m:g} m (inner surfaces are the smaller, Fenz & Constantinou 2008)")
        if si.mu_kinetic > so.mu_kinetic:
            raise fail(f"bearing surface {i}: mu_{i} = {si.mu_kinetic:g} must not exceed mu_{o} = {so.mu_kinetic:g} "
                       "(the inner surfaces slide first, regime I of Fenz & Constantinou 2008)")
        _check_reaches(s, inner, outer, "II", "", fail)
    # The outer surface of lower friction slides alone (regime II) until the force reaches the other's µ W; on its
    # rim before that, the bearing enters a state Fenz & Constantinou's regimes do not have (the slider on one outer
    # rim, no outer surface sliding: the backbone named it "", session 16 sweep).  Either outer may be the lower
    # one: µ1 > µ4 is the bearing upside down, whose series model and responses are those of µ1 < µ4 with the
    # surfaces in reverse order (tests/test_hostile_s16.py), and the regime names count outer surfaces, not which.
    first, other = (0, 3) if s[0].mu_kinetic <= s[3].mu_kinetic else (3, 0)
    _check_reaches(s, first, other, "III", f" (surface {first + 1} slides alone until the force reaches "
                   f"mu_{other + 1} W, Fenz & Constantinou 2008)", fail)


def _check_reaches(surfaces, lower: int, upper: int, regime: str, why: str, fail) -> None:
    """Surface ``lower`` (index) slides alone until the force reaches the next friction level, µ_upper W: its effective
    capacity must hold that travel, d* >= (µ_upper − µ_lower) R_eff, or the bearing reaches its rim before ``regime``
    (Fenz & Constantinou 2008)."""
    sl, su = surfaces[lower], surfaces[upper]
    i, o = lower + 1, upper + 1
    need = (su.mu_kinetic - sl.mu_kinetic) * sl.effective_radius_m
    if sl.effective_capacity_m < need:
        raise fail(f"bearing surface {i}: effective capacity d*_{i} = {sl.effective_capacity_m:.4g} m is too small "
                   f"to reach regime {regime}: it must be >= (mu_{o} - mu_{i}) R_eff,{i} = {need:.4g} m{why}")


#: Top-level design keys that a ``[bearing]`` table replaces.
REPLACED_DESIGN_KEYS = ("radius_m", "stiffness_N_per_m", "mu_static", "mu_kinetic", "mu_slow", "mu_fast",
                        "rate_s_per_m", "displacement_capacity_m")


def equivalent_single(bearing: Bearing) -> tuple[float, float]:
    """(radius [m], µ [-]) of the single pendulum equal to the bearing where every element slides.

    The regime of largest compliance on the backbone (regime III of a triple pendulum,
    both surfaces of a double): its line F/W = x/R + µ.  It is what a single number needs
    (the paper's dimensionless point, a design's isolated period); the response is
    computed on the whole bearing.
    """
    bb = bearing.backbone()
    compliance = [1.0 / k if k > 0 else 0.0 for k in bb.stiffness_per_weight_1_m]
    k = int(np.argmax(compliance))
    radius = compliance[k]
    return radius, float(bb.force_per_weight[k] - bb.displacement_m[k] / radius)


def equivalent_design_keys(bearing: Bearing, mapping: dict, fail) -> dict:
    """The design mapping with the top-level keys of the bearing's equivalent single pendulum.

    Parameters
    ----------
    bearing : Bearing
    mapping : dict
        The design file's table; it must not give the keys the bearing replaces.
    fail : callable
        ``fail(message) -> DesignError``.

    Returns
    -------
    dict
        ``mapping`` with ``radius_m``, the friction keys and ``displacement_capacity_m``
        (the ultimate displacement Σ d*) of the bearing: the surface itself for a single
        bearing, :func:`equivalent_single` for a double or triple.
    """
    given = [key for key in REPLACED_DESIGN_KEYS if key in mapping]
    if given:
        raise fail(f"key '{given[0]}' with a [bearing] table: give the radius, friction and capacity of each "
                   "surface in [[bearing.surface]]")
    out = {key: value for key, value in mapping.items() if key != "bearing"}
    if bearing.is_simple:
        s = bearing.surfaces[0]
        out["radius_m"] = s.effective_radius_m
        if s.rate_s_per_m is not None:
            out.update(mu_static=s.mu_slow, mu_slow=s.mu_slow, mu_fast=s.mu_fast, rate_s_per_m=s.rate_s_per_m)
        else:
            out.update(mu_static=s.mu_static, mu_kinetic=s.mu_kinetic)
    else:
        radius, mu = equivalent_single(bearing)
        out.update(radius_m=radius, mu_static=mu, mu_kinetic=mu)
    if bearing.has_rims:
        out["displacement_capacity_m"] = bearing.ultimate_displacement_m
    return out


__all__ = ["Backbone", "Bearing", "DesignError", "LoopProperties", "Surface", "parse_bearing",
           "equivalent_design_keys", "equivalent_single", "SURFACE_KEYS", "SURFACES_PER_TYPE"]
