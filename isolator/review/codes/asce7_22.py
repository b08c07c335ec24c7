r"""ASCE/SEI 7-22 Chapter 17: equivalent-lateral-force reference values of a friction isolation system.

Formulas and their sources are those of ``REVIEW_RULES.md`` §1.8–1.10 (marks there); per bound
of the friction coefficient µ, with W the supported weight and g = 9.80665 m/s²:

.. math::
   k_M(D) = K + \mu W / D,\quad T_M = 2\pi\sqrt{W/(k_M g)}                       (17.5-2)
   \beta_M = E_{loop}/(2\pi k_M D^2),\ E_{loop} = 4\mu W D\ (+\ \pi\gamma\omega D^2)
   D_M = g\,S_a(T_M)\,T_M^2/(4\pi^2 B_M)\quad(\text{or } g S_{M1} T_M/(4\pi^2 B_M))  (17.5-1)
   D_{TM} = D_M\,[1 + (y/P_T^2)\,12e/(b^2 + d^2)] \ge 1.15 D_M                    (17.5-3)
   V_b = k_M D_M,\quad V_{st} = V_b (W_s/W)^{1 - 2.5\beta_M},\quad V_s = V_{st}/R_I  (17.5-7/-8/-6)

D_M is the largest fixed point of D ↦ g S_a(T(D)) T(D)²/(4π² B(β(D))), found by a scan of D over
1e-5…50 m (400 log-spaced points) and Brent's method on the bracketing interval (relative
tolerance 1e-12).  Restoring force (17.2.4.4): F(D) − F(D/2) ≥ 0.025 W.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.review.parameters import PARAMETERS
from isolator.review.target import Target

#: Table 17.5-1 damping coefficient B_M at β_M [S: P1, P2; P1 stops at 1.9 for ≥ 40 %]; the last entry is the
#: default of the review parameter ``B_M_at_50pct`` (the value at β ≥ 50 %, where the sources differ)
B_M_TABLE = ((0.02, 0.8), (0.05, 1.0), (0.10, 1.2), (0.20, 1.5), (0.30, 1.7), (0.40, 1.9), (0.50, 2.0))
CLAUSE = {"D_M": "ASCE 7-22 17.5.3.1 (Eq. 17.5-1)", "T_M": "ASCE 7-22 17.5.3.2 (Eq. 17.5-2)",
          "B_M": "ASCE 7-22 Table 17.5-1", "D_TM": "ASCE 7-22 17.5.3.3 (Eq. 17.5-3)",
          "V_b": "ASCE 7-22 17.5.4.1 (Eq. 17.5-7)", "V_st": "ASCE 7-22 17.5.4.2 (Eq. 17.5-8)",
          "restoring": "ASCE 7-22 17.2.4.4", "limits_V_s": "ASCE 7-22 17.5.4.3"}


def damping_coefficient(beta: float, b_m_at_50: float = B_M_TABLE[-1][1]) -> float:
    """B_M of Table 17.5-1, linear between the tabulated β, constant beyond the ends [-].

    Parameters
    ----------
    beta : float
        Effective damping ratio β_M [-].
    b_m_at_50 : float
        B_M at β ≥ 50 % (review parameter ``B_M_at_50pct``: 2.0 in P2 and a third code; P1 stops at 1.9 from 40 %).
    """
    betas, values = zip(*B_M_TABLE, strict=False)
    return float(np.interp(beta, betas, (*values[:-1], b_m_at_50)))


def effective_properties(design, mu: float, displacement_m: float) -> tuple[float, float, float]:
    """k_M [N/m], T_M [s], β_M [-] at a displacement (17.5.3.2).

    A single surface: the bilinear model (friction µ, spring K, damper γ).  A double or triple
    friction pendulum: the bearing's own stable loop between ±D (:meth:`isolator.design.Design.effective_properties`,
    ``Bearing.loop_properties``; its µ_i are those of the bound, ``mu`` is not used); NaN beyond the
    bearing's ultimate displacement, where no loop exists.
    """
    d = float(displacement_m)
    if is_multisurface(design):
        props = design.effective_properties(d)
        return props.effective_stiffness_N_per_m, props.effective_period_s, props.effective_damping_ratio
    w = design.weight_N
    k = design.stiffness_N_per_m + mu * w / d
    omega = math.sqrt(k / design.mass_kg)
    energy = 4.0 * mu * w * d + math.pi * design.damping_Ns_per_m * omega * d * d
    return k, 2.0 * math.pi / omega, energy / (2.0 * math.pi * k * d * d)


def is_multisurface(design) -> bool:
    """True for a double or triple friction pendulum (a ``[bearing]`` of more than one surface)."""
    bearing = getattr(design, "bearing", None)
    return bearing is not None and not bearing.is_simple


def ultimate_displacement_m(design) -> float:
    """The bearing's ultimate displacement Σ d_i* of a double or triple pendulum [m]; inf otherwise."""
    return design.bearing.ultimate_displacement_m if is_multisurface(design) else math.inf


def elf_displacement(design, mu: float, target: Target, *, form: str = "SaM", reduction=None,
                     b_m_at_50: float = B_M_TABLE[-1][1]) -> dict:
    """D_M, T_M, β_M, B_M and V_b/W of one property bound (17.5.3).

    Parameters
    ----------
    design : isolator.design.Design
        The isolator (mass, K, γ).
    mu : float
        Kinetic friction coefficient of the bound [-].
    target : Target
        MCE_R spectrum.
    form : {"SaM", "SM1"}
        Eq. 17.5-1 with S_a(T_M) T_M² (7-22) or S_M1 T_M (7-16; ASCE two-period targets only).
    reduction : callable, optional
        β ↦ the divisor of the 5 % spectrum (default: B_M of Table 17.5-1; EN: 1/η).
    b_m_at_50 : float
        Table 17.5-1's B_M at β ≥ 50 % (review parameter ``B_M_at_50pct``), when ``reduction`` is not given.

    Returns
    -------
    dict
        ``D_M_m``, ``T_M_s``, ``beta_M``, ``B_M``, ``k_M_N_per_m``, ``V_b_over_W``, ``mu``, ``form``,
        ``notes`` (list of text).
    """
    g = design.gravity_m_s2
    use_sm1 = form == "SM1" and target.kind == "asce7-two-period"
    table = reduction is None
    reduction = reduction or (lambda b: damping_coefficient(b, b_m_at_50))

    def image(d):
        _, t, beta = effective_properties(design, mu, d)
        b = reduction(beta)
        if use_sm1:
            return g * target.parameters["S_M1"] * t / (4.0 * math.pi ** 2 * b)
        return g * float(target.sa_g(t, clip=True)[0]) * t * t / (4.0 * math.pi ** 2 * b)

    notes = []
    ultimate = ultimate_displacement_m(design)
    top = min(50.0, ultimate)
    grid = np.geomspace(1e-5, top, 400)
    gap = np.array([image(d) - d for d in grid])
    crossings = np.flatnonzero((gap[:-1] > 0) & (gap[1:] <= 0))
    beyond_ultimate = bool(gap[-1] > 0 and math.isfinite(ultimate))
    if beyond_ultimate:
        notes.append(f"the ELF demand exceeds the bearing's ultimate displacement {ultimate:.4g} m (every slider on "
                     "its rim): no D_M within the bearing")
        d_m = math.nan
    elif gap[-1] > 0:
        notes.append("no ELF fixed point below 50 m: the isolator has no restoring capacity at this demand")
        d_m = math.nan
    elif crossings.size == 0:
        notes.append("the ELF demand does not exceed the friction: no sliding (D_M = 0)")
        d_m = 0.0
    else:
        from isolator.roots import brentq  # SciPy's brentq bit for bit, without importing scipy.optimize

        i = int(crossings[-1])
        d_m = float(brentq(lambda d: image(d) - d, grid[i], grid[i + 1], xtol=1e-14, rtol=1e-12))
        if crossings.size > 1:
            notes.append(f"{crossings.size} ELF fixed points; the largest is used")
    if not d_m > 0:
        return {"D_M_m": d_m, "T_M_s": math.nan, "beta_M": math.nan, "B_M": math.nan, "k_M_N_per_m": math.nan,
                "V_b_over_W": math.nan if math.isnan(d_m) else breakaway_force_per_weight(design, mu), "mu": mu,
                "form": form, "notes": notes, "beyond_ultimate": beyond_ultimate}
    k, t, beta = effective_properties(design, mu, d_m)
    if is_multisurface(design):
        regime = design.bearing.loop_properties(d_m, design.weight_N, g).regime
        notes.append(f"T_M, β_M from the {design.bearing.kind} pendulum's loop between ±D_M (regime {regime} at D_M)")
    if t > target.long_period_s:
        notes.append(f"T_M = {t:.3g} s exceeds T_L = {target.long_period_s:g} s: the S_aM and S_M1 forms differ")
    if table and beta > B_M_TABLE[-2][0]:  # only here does B_M_at_50pct decide B_M (the sources differ above 40 %)
        notes.append(f"β_M = {beta:.3g} above 40 %: B_M = {reduction(beta):.4g} "
                     + ("held at" if beta >= B_M_TABLE[-1][0] else "interpolated from 1.9 at 40 % to")
                     + f" B_M_at_50pct = {b_m_at_50:g} at 50 % [S: P2; P1 stops at 1.9 from 40 %] (Table 17.5-1)")
    return {"D_M_m": d_m, "T_M_s": t, "beta_M": beta, "B_M": reduction(beta), "k_M_N_per_m": k,
            "V_b_over_W": k * d_m / design.weight_N, "mu": mu, "form": "SM1" if use_sm1 else "SaM", "notes": notes,
            "beyond_ultimate": False}


def displacement_with_flexible_superstructure(d_m: float, t_fixed_s: float, t_m_s: float) -> float:
    """D'_M = D_M / sqrt(1 + (T/T_M)²) of Eq. 17.6-1 [m], T the superstructure's fixed-base period [s]."""
    if not (math.isfinite(d_m) and math.isfinite(t_m_s) and t_m_s > 0):
        return math.nan
    return d_m / math.sqrt(1.0 + (t_fixed_s / t_m_s) ** 2)


def breakaway_force_per_weight(design, mu_static: float | None = None) -> float:
    """The force per unit weight at which the isolation system starts to slide [-].

    µs for a single surface (``mu_static`` when given, else the design's); for a double or triple
    pendulum the backbone's force at rest (the smallest friction of the first sliding surfaces).
    """
    if is_multisurface(design):
        return float(design.bearing.backbone().force_per_weight[0])
    return design.mu_static if mu_static is None else mu_static


def activation_force_per_weight(design, mode: str = "outer") -> float:
    """The force per unit weight that fully activates the isolation system (17.5.4.3(3)) [-].

    µs for a single surface; for a double or triple pendulum (review parameter ``multisurface_activation`` [U])
    ``"outer"``: the backbone's force at the start of the regime where every element of largest compliance slides
    (regime III of a triple pendulum), ``"breakaway"``: its force at rest (REVIEW_RULES 1.9's breakaway friction).
    """
    if not is_multisurface(design):
        return design.mu_static
    if mode == "breakaway":
        return breakaway_force_per_weight(design)
    bb = design.bearing.backbone()
    return float(bb.force_per_weight[_largest_compliance(bb)])


def _largest_compliance(bb) -> int:
    """Index of the backbone's regime of the largest compliance (1/stiffness; a rigid step has none)."""
    compliance = [1.0 / k if k > 0 else 0.0 for k in bb.stiffness_per_weight_1_m]
    return int(np.argmax(compliance))


def activation_regime(design) -> str:
    """Which regime 17.5.4.3(3)'s 'outer' reading starts, named for the design's bearing type [-].

    A triple pendulum: "regime III of the triple (both outer surfaces slide)"; a double: "regime 1+2 of the double
    (both surfaces slide)"; "" for a single surface (µs: no regime to name).
    """
    if not is_multisurface(design):
        return ""
    bearing = design.bearing
    name = bearing.backbone().regimes[_largest_compliance(bearing.backbone())]
    if bearing.kind == "triple" and name == "III":
        sliding = "both outer surfaces slide"
    else:
        surfaces = name.split("+")
        sliding = ("both surfaces slide" if len(surfaces) == 2 == len(bearing.surfaces) else
                   f"surface{'s' if len(surfaces) > 1 else ''} {' and '.join(surfaces)} slide"
                   f"{'' if len(surfaces) > 1 else 's'}")
    return f"regime {name} of the {bearing.kind} ({sliding})"


def torsion_amplification(y_m: float, eccentricity_m: float, p_t: float, b_m: float, d_m: float) -> float:
    """1 + (y / P_T²) · 12 e / (b² + d²), the bracket of Eq. 17.5-3 (ASCE 7-22 17.5.3.3) [-].

    Parameters
    ----------
    y_m : float
        Distance of the element of interest from the centre of rigidity, perpendicular to the loading [m].
    eccentricity_m : float
        Actual + accidental eccentricity e [m].
    p_t : float
        P_T of Eq. 17.5-4 [-] (> 0).
    b_m, d_m : float
        Plan dimensions [m].
    """
    return 1.0 + (y_m / p_t ** 2) * 12.0 * eccentricity_m / (b_m * b_m + d_m * d_m)


def direction_factors(plan: dict, layout: dict, params: dict, p_t: float, e_perp_b: float,
                      e_perp_d: float) -> list[float]:
    """Eq. 17.5-3's bracket for the two loading directions [-]: ⟂ b (loading along y, y measured along x) with the
    actual eccentricity ``e_perp_b``, ⟂ d (loading along x) with ``e_perp_d`` [m], each plus ``accidental_e`` × that
    plan dimension; ``y`` the given ``y_m``, else the layout's farthest bearing ⟂ loading, else half the dimension."""
    b, d = plan["b_m"], plan["d_m"]
    return [torsion_amplification(plan.get("y_m", layout_y if layout_y is not None else 0.5 * perpendicular),
                                  e + params["accidental_e"] * perpendicular, p_t, b, d)
            for perpendicular, layout_y, e in ((b, layout.get("y_for_loading_y_m"), e_perp_b),
                                               (d, layout.get("y_for_loading_x_m"), e_perp_d))]


def torsion_factor(plan: dict | None, params: dict, layout: dict | None = None) -> dict:
    """D_TM / D_M of Eq. 17.5-3 (the larger of the two loading directions), with its basis.

    ``e`` = actual eccentricity + ``accidental_e`` × the plan dimension ⟂ loading (``b_m`` along x,
    ``d_m`` along y); ``y`` the given ``y_m``, else the design's bearing layout's farthest bearing ⟂
    loading, else half the plan dimension ⟂ loading (a corner bearing, assumed); ``P_T`` the given value,
    else the layout's (Eq. 17.5-4), else ``P_T_min`` (the most conservative) — never below ``P_T_min``.
    No [plan]: the floor.

    Parameters
    ----------
    plan : dict or None
        The design's ``[plan]`` table.
    params : dict
        ``accidental_e``, ``D_TM_floor``, ``P_T_min``.
    layout : dict, optional
        From the design's ``[[bearing_position]]`` (:func:`isolator.superstructure.review_inputs`): ``P_T``,
        ``y_for_loading_x_m`` (max |y|), ``y_for_loading_y_m`` (max |x|) [m].
    """
    floor = params["D_TM_floor"]
    if plan is None:
        return {"factor": floor, "basis": f"no [plan] in the design: D_TM = {floor:g} D_M (the floor of Eq. 17.5-3)",
                "assumed": True}
    layout = layout or {}
    b, d = plan["b_m"], plan["d_m"]
    p_t_source = "given" if "P_T" in plan else ("the bearing layout" if "P_T" in layout else "assumed")
    p_t_raw = plan.get("P_T", layout.get("P_T", params["P_T_min"]))
    p_t = max(p_t_raw, params["P_T_min"])
    # a P_T below the floor said "P_T = 1 (the bearing layout)": the layout gave 0.29, the floor P_T_min was used
    p_t_said = (f"P_T = {p_t:.4g} ({p_t_source})" if p_t_raw >= params["P_T_min"] else
                f"P_T = {p_t:.4g} (P_T_min; {p_t_source}: {p_t_raw:.4g})")
    e_plan = plan.get("eccentricity_m", 0.0)
    raw = max(direction_factors(plan, layout, params, p_t, e_plan, e_plan))
    disagree = eccentricity_disagreement(plan, layout, params, p_t)
    y_source = "given" if "y_m" in plan else ("the bearing layout" if "y_for_loading_x_m" in layout else "assumed")
    return {"factor": max(raw, floor), "raw_factor": raw, "P_T": p_t, "P_T_raw": p_t_raw,
            "basis": f"Eq. 17.5-3 with b = {b:g} m, d = {d:g} m, {p_t_said}"
                     + {"given": "",
                        "the bearing layout": ", y = the farthest bearing perpendicular to the loading (the bearing "
                                              "layout)",
                        "assumed": ", y = half the plan dimension (corner bearing, assumed)"}[y_source]
                     + (f"; floor {floor:g} governs" if raw < floor else "") + disagree.pop("said", ""),
            "assumed": y_source == "assumed" or p_t_source == "assumed", **disagree}


def eccentricity_disagreement(plan: dict, layout: dict, params: dict, p_t: float) -> dict:
    """Which actual eccentricity Eq. 17.5-3 used where the design gives both ``[plan]``'s and a bearing layout's.

    The layout's actual eccentricity ⟂ the loading is the offset of its centre of rigidity from the centre of mass
    (``layout["rigidity_centre_m"]``: |ȳ| for loading along x, |x̄| along y).  Eq. 17.5-3 uses ``[plan]``'s
    ``eccentricity_m`` (as given); the returned ``said`` tells the signer so, the layout's values, by how much they
    differ and D_TM/D_M with the layout's instead.  Empty where the design does not give both.

    Returns
    -------
    dict
        ``eccentricity_plan_m``, ``eccentricity_layout_m`` (⟂ loading x, ⟂ loading y) [m],
        ``eccentricity_difference_m`` (the larger |difference|) [m], ``factor_with_layout_eccentricity`` [-] and
        ``said`` (text for the basis).
    """
    centre = layout.get("rigidity_centre_m")
    if "eccentricity_m" not in plan or centre is None:
        return {}
    e_plan = float(plan["eccentricity_m"])
    e_x, e_y = abs(centre[1]), abs(centre[0])  # ⟂ loading along x: the y offset; along y: the x offset
    factor = max(max(direction_factors(plan, layout, params, p_t, e_y, e_x)), params["D_TM_floor"])
    difference = max(abs(e_plan - e_x), abs(e_plan - e_y))
    floor_said = " (the floor)" if factor == params["D_TM_floor"] else ""
    verdict = (f"they disagree by {difference:.3g} m; the bearing layout's would give D_TM/D_M = {factor:.4g}"
               f"{floor_said}"
               if difference > 1e-9 * max(1.0, e_plan) else "they agree")
    return {"eccentricity_plan_m": e_plan, "eccentricity_layout_m": [e_x, e_y],
            "eccentricity_difference_m": difference, "factor_with_layout_eccentricity": factor,
            "said": f"; actual eccentricity e = {e_plan:g} m from [plan] eccentricity_m (used), the bearing layout's "
                    f"centre of rigidity {e_x:.3g} m (⟂ loading x) and {e_y:.3g} m (⟂ loading y) from the centre of "
                    f"mass: {verdict}"}


def superstructure_shear(v_b_over_w: float, beta: float, params: dict) -> dict:
    """V_st/W and V_s/W from V_b/W (Eqs. 17.5-8, 17.5-6)."""
    exponent = 1.0 - (3.5 if params["abrupt_hysteresis"] else 2.5) * beta
    v_st = v_b_over_w * params["Ws_over_W"] ** exponent
    return {"V_st_over_W": v_st, "V_s_over_W": v_st / params["R_I"]}


def activation_shear_over_w(mu_static_upper: float, mu_static_nominal: float, nominal_factor: float) -> float:
    """Breakaway friction force of the isolation system / W (17.5.4.3: greater of UB or 1.5 × nominal; the 1.5 is
    the review parameter ``activation_nominal_factor`` [U], its default in :data:`isolator.review.parameters.
    PARAMETERS`)."""
    return max(mu_static_upper, nominal_factor * mu_static_nominal)


def vertical_load_factors(s_ms: float, params: dict, *, vertical_analysed: bool) -> tuple[float, float]:
    """The factors on a bearing's gravity share D for its maximum and minimum vertical load (17.2.4.6 / 17.2.4.7,
    the 2.3.6 combinations with E_v = c S_MS D of 12.4.2.2, S_MS for the MCE_R) [-] — all [U].

    ``(dead_load_factor_max + c S_MS, dead_load_factor_min − c S_MS)``, c = ``vertical_Ev_coefficient``; when the
    analysis had its vertical component the loads already carry it, so E_v is not added again: the dead-load
    factors alone.
    """
    e_v = 0.0 if vertical_analysed else params["vertical_Ev_coefficient"] * s_ms
    return params["dead_load_factor_max"] + e_v, params["dead_load_factor_min"] - e_v


def restoring_force_ratio(design, displacement_m: float) -> float:
    """(F(D) − F(D/2)) / W (17.2.4.4): K D / (2W) of the bilinear model, D/(2R) for a friction pendulum; on a
    double or triple pendulum's backbone (loading from rest), NaN beyond its ultimate displacement."""
    if is_multisurface(design):
        d = float(displacement_m)
        backbone = design.bearing.backbone()
        if not (math.isfinite(d) and 0.0 <= d <= backbone.ultimate_displacement_m):
            return math.nan
        return backbone.force_per_weight_at(d) - backbone.force_per_weight_at(0.5 * d)
    return design.stiffness_N_per_m * 0.5 * displacement_m / design.weight_N


def activation_superstructure_shear_over_w(v_activation_over_w: float, beta: float, params: dict) -> float:
    """V_st/W of Eq. 17.5-8 with V_b = the force that fully activates the isolation system (17.5.4.3(3)) [-]."""
    exponent = 1.0 - (3.5 if params["abrupt_hysteresis"] else 2.5) * beta
    return v_activation_over_w * params["Ws_over_W"] ** exponent


def fixed_base_seismic_coefficient(s_ds: float, s_d1: float, t_l: float, period_s: float, r: float,
                                   i_e: float) -> dict:
    """C_s of the equivalent lateral force of a fixed-base structure (ASCE 7-22 12.8.1.1) [-], and which equation
    governs.

    ::

        C_s = S_DS / (R/I_e)                                     (12.8-2)
            ≤ S_D1 / (T (R/I_e))          for T ≤ T_L            (12.8-3)
            ≤ S_D1 T_L / (T² (R/I_e))     for T > T_L            (12.8-4)
        C_s ≥ max(0.044 S_DS I_e, 0.01)                          (12.8-5)

    The minimum 0.5 S_1/(R/I_e) of Eq. 12.8-6 (sites with S_1 ≥ 0.6 g) needs the mapped S_1, which the review's
    target does not give: not applied (said in the row).

    Parameters
    ----------
    s_ds, s_d1 : float
        Design spectral accelerations at short periods and at 1 s [g].
    t_l : float
        Long-period transition period [s].
    period_s : float
        The period T [s] (> 0): T_M for 17.5.4.3(1).
    r : float
        Response modification coefficient R of the fixed-base structure (Table 12.2-1) [-], > 0.
    i_e : float
        Importance factor I_e (Table 1.5-2) [-], > 0.

    Returns
    -------
    dict
        ``C_s`` [-] and ``equation`` (the one that governs, e.g. ``"12.8-3"``).
    """
    if not (period_s > 0 and r > 0 and i_e > 0):
        raise ValueError(f"period {period_s!r}, R {r!r} and I_e {i_e!r} must be > 0")
    ratio = r / i_e
    plateau = s_ds / ratio
    if period_s <= t_l:
        cap, cap_eq = s_d1 / (period_s * ratio), "12.8-3"
    else:
        cap, cap_eq = s_d1 * t_l / (period_s * period_s * ratio), "12.8-4"
    c_s, equation = (plateau, "12.8-2") if plateau <= cap else (cap, cap_eq)
    minimum = max(0.044 * s_ds * i_e, 0.01)
    if c_s < minimum:
        c_s, equation = minimum, "12.8-5 (0.044 S_DS I_e)" if 0.044 * s_ds * i_e >= 0.01 else "12.8-5 (0.01)"
    return {"C_s": c_s, "equation": equation}


def fixed_base_limits(elf: dict, design_spectrum: dict | None, r: float | None, params: dict) -> dict:
    """17.5.4.3(1): per bound, the fixed-base ELF force of W_s at T_M over W, C_s(T_M) × W_s/W [-].

    Parameters
    ----------
    elf : dict
        Per bound: ``T_M_s``.
    design_spectrum : dict or None
        ``S_DS``, ``S_D1`` [g], ``T_L`` [s] and ``basis`` (:func:`isolator.review.target.design_values`).
    r : float or None
        The superstructure's R (the design's ``response_modification_R``): 12.8 sizes a fixed-base structure,
        so its own R applies, not R_I [U].
    params : dict
        ``importance_factor_Ie``, ``Ws_over_W``.

    Returns
    -------
    dict
        ``per_bound``: bound → {``C_s``, ``equation``, ``T_M_s``, ``V_over_W``}; ``basis`` (one sentence);
        ``missing``: why nothing was computed (then ``per_bound`` is empty).
    """
    if r is None:
        return {"per_bound": {}, "missing": "needs the superstructure's R (response_modification_R in the design's "
                                            "[superstructure]) for the fixed-base ELF of Section 12.8"}
    if design_spectrum is None:
        return {"per_bound": {}, "missing": "needs S_DS, S_D1 and T_L (a two-period target): the target gives no "
                                            "12.8.1.1 coefficients"}
    i_e, ws = params["importance_factor_Ie"], params["Ws_over_W"]
    per = {}
    for b in ("lower", "upper"):
        t_m = elf.get(b, {}).get("T_M_s", math.nan)
        if math.isfinite(t_m) and t_m > 0:
            c = fixed_base_seismic_coefficient(design_spectrum["S_DS"], design_spectrum["S_D1"], design_spectrum["T_L"],
                                               t_m, r, i_e)
            per[b] = {**c, "T_M_s": t_m, "V_over_W": c["C_s"] * ws}
    basis = (f"C_s of 12.8.1.1 at T = T_M with the superstructure's R = {r:g} (not R_I) and I_e = {i_e:g} "
             f"(importance_factor_Ie [U]); S_DS = {design_spectrum['S_DS']:.4g} g, S_D1 = "
             f"{design_spectrum['S_D1']:.4g} g, T_L = {design_spectrum['T_L']:g} s ({design_spectrum['basis']}); "
             f"× W_s/W = {ws:.4g}; Eq. 12.8-6 (0.5 S_1/(R/I_e) where S_1 ≥ 0.6 g) not applied: S_1 is not an input")
    return {"per_bound": per, "basis": basis,
            "missing": None if per else "no ELF T_M (the ELF found no sliding)"}


def requirement_rows(elf: dict, params: dict, *, mu_static_lower: float, mu_static_upper: float,
                     mu_static_nominal: float, story_drift_ratio: float | None = None,
                     story_drift_note: str = "", bearing_axial_loads_N: dict | None = None,
                     fixed_base: dict | None = None, multisurface: bool = False,
                     activation_mode: str = "outer", activation_regime: str = "") -> list[dict]:
    """The Chapter 17 requirements beside the response-history checks, each with its clause and status.

    ``pass`` / ``fail`` only where the review computes the quantity; otherwise ``not checked`` naming
    what is missing.  ``story_drift_ratio`` (largest story drift / story height over the analyses) and
    ``bearing_axial_loads_N`` (``{"min": …, "max": …}`` over the analyses) are the hooks for a
    superstructure and bearing layout model: ``story_drift_ratio`` the design value (suite rule, envelope of
    the bounds, largest story) with ``story_drift_note`` saying which; ``bearing_axial_loads_N``
    ``{"max": [per bearing], "capacity": [per bearing] or None, "note": …}``.

    Parameters
    ----------
    elf : dict
        Per bound ("lower", "upper"): the ELF values (``T_M_s``, ``beta_M``, ``V_s_over_W``).
    params : dict
        The review's parameters (``wind_shear_over_W``, ``drift_limit_rha``, ``Ws_over_W``, …).
    mu_static_lower, mu_static_upper, mu_static_nominal : float
        Breakaway force / W of the lower bound (the wind row) and the force / W that fully activates the
        isolation system at the upper and nominal properties (17.5.4.3(3)) [-]: µs of a single surface
        (:func:`breakaway_force_per_weight`, :func:`activation_force_per_weight`).
    fixed_base : dict, optional
        17.5.4.3(1)'s limits (:func:`fixed_base_limits`); without it the row is ``not checked``.
    multisurface : bool
        A double or triple bearing: the notes say what the forces are (the backbone's at rest for the wind row, at
        the start of the regime of the largest compliance for 17.5.4.3(3), :func:`activation_force_per_weight`),
        not µs.
    activation_mode : {"outer", "breakaway"}
        Which force activates a double or triple (``multisurface_activation``), for the note.
    activation_regime : str
        The regime the 'outer' reading starts, named for the bearing type (:func:`activation_regime`), for the note.
    """
    from isolator.review import checks as C

    rows = []
    breakaway = "force / W (the bearing's backbone at rest: its smallest µ_i)" if multisurface else "µs"
    wind = params.get("wind_shear_over_W")
    if wind is None:
        rows.append(C.check("wind_restraint", "ASCE 7-22 17.2.4.2", C.NOT_CHECKED, None, mu_static_lower,
                            "needs the design wind base shear / W (parameter wind_shear_over_W); the isolation system "
                            f"must not slide under wind: lower-bound breakaway {breakaway} = {mu_static_lower:.4g}", "V/W"))
    else:
        # it said "breakaway friction µs" on a double or triple too, whose limit is the backbone at rest (its smallest µ_i)
        rows.append(C.at_most("wind_restraint", "ASCE 7-22 17.2.4.2", wind, mu_static_lower,
                              f"design wind base shear / W ≤ lower-bound breakaway {breakaway} = {mu_static_lower:.4g} "
                              "(no sliding under wind; friction as the wind restraint, a reading of the clause)", "V/W"))
    rows.append(C.check("fire_resistance", "ASCE 7-22 17.2.4.3", C.NOT_CHECKED, note="the isolation system's fire "
                        "rating is not an input of the review"))
    rows.append(C.check("displacement_restraint", "ASCE 7-22 17.2.4.5", C.NOT_CHECKED,
                        note="no displacement restraint is an input or modelled: the bearings alone must accommodate "
                             "the total displacement (D_TM_capacity; each analysis in record_capacity)"))
    loads = bearing_axial_loads_N or {}
    rows.append(C.vertical_load_stability(loads.get("max"), loads.get("capacity"), loads.get("note", ""),
                                          basis=loads.get("basis")))
    rows.append(C.check("inspection_replacement", "ASCE 7-22 17.2.4.8", C.NOT_CHECKED,
                        note="access for inspection and replacement: reviewer's list"))
    t_m = [elf[b].get("T_M_s", math.nan) for b in ("lower", "upper") if b in elf]
    t_text = ", ".join(f"{t:.3g} s" for t in t_m if math.isfinite(t)) or "undefined"
    rows.append(C.check("analysis_procedure", "ASCE 7-22 17.4", C.NOT_CHECKED, max(t_m, default=None), None,
                        "response-history analysis is used (17.4.2 permits it for any isolated structure) [U]; the ELF "
                        "limits of 17.4.1 (S_1, site class, height, stories, regularity) need site and structure data; "
                        f"T_M = {t_text}", "s"))
    v_s = {b: elf[b].get("V_s_over_W", math.nan) for b in ("lower", "upper") if b in elf}
    rows.append(_fixed_base_row(v_s, fixed_base))
    if wind is None:
        rows.append(C.check("V_s_wind_limit", "ASCE 7-22 17.5.4.3(2) [U]", C.NOT_CHECKED, None, None,
                            "V_s ≥ the factored design wind base shear: needs wind_shear_over_W", "V/W"))
    else:
        lowest = min(v_s.values(), default=math.nan)
        rows.append(C.at_least("V_s_wind_limit", "ASCE 7-22 17.5.4.3(2) [U]", lowest, wind,
                               "smaller ELF V_s/W of the two bounds ≥ the (factored) design wind base shear / W",
                               "V/W"))
    factor = params.get("activation_nominal_factor", PARAMETERS["activation_nominal_factor"].default)
    v_act = activation_shear_over_w(mu_static_upper, mu_static_nominal, factor)
    margins = {}
    for b, value in v_s.items():
        beta = elf[b].get("beta_M", math.nan)
        if math.isfinite(value) and math.isfinite(beta):
            margins[b] = (value, activation_superstructure_shear_over_w(v_act, beta, params))
    if margins:
        b = min(margins, key=lambda k: margins[k][0] / margins[k][1])
        rows.append(C.at_least("V_s_activation_limit", "ASCE 7-22 17.5.4.3(3) [U]", margins[b][0], margins[b][1],
                               f"ELF V_s/W ({b} bound) ≥ V_st of Eq. 17.5-8 with V_b = the activation force "
                               + ((f"max(upper, {factor:g} × nominal) of the backbone's force at the start of the regime "
                                   "of the largest compliance ("
                                   + (f"{activation_regime}; " if activation_regime else "")
                                   + "multisurface_activation 'outer' [U]: REVIEW_RULES 1.9 names the breakaway "
                                   "friction for sliders, the bearing's breakaway is its smallest µ_i) "
                                   if activation_mode == "outer" else
                                   f"max(upper, {factor:g} × nominal) of the bearing's breakaway force (the backbone at rest: "
                                   "its smallest µ_i; multisurface_activation 'breakaway' [U]) ")
                                  if multisurface else f"max(µs upper, {factor:g} µs nominal) ")
                               + f"W = {v_act:.4g} W" + _activation_reading(margins[b], mu_static_upper,
                                                                           mu_static_nominal, factor), "V/W"))
    else:
        rows.append(C.check("V_s_activation_limit", "ASCE 7-22 17.5.4.3(3) [U]", C.NOT_CHECKED, None, None,
                            "no ELF V_s (the ELF found no sliding)", "V/W"))
    rows.append(C.story_drift(story_drift_ratio, params.get("drift_limit_rha"), story_drift_note))
    return rows


def _activation_reading(value_limit: tuple, upper: float, nominal: float, factor: float) -> str:
    """What 17.5.4.3(3)'s row hangs on, for its note: which term of max(upper, factor × nominal) [U] governs, the
    row's margin, and its verdict under the other reading (the upper-bound force alone, without the factor)."""
    value, limit = value_limit
    scaled = factor * nominal
    words = (f" (upper {upper:.4g}, {factor:g} × nominal {nominal:.4g} = {scaled:.4g}: "
             + (f"the {factor:g} × nominal reading governs (activation_nominal_factor {factor:g} [U])" if scaled > upper
                else "the upper bound governs") + ")")
    if not limit > 0 or not math.isfinite(value):
        return words
    words += f"; margin {100.0 * (value / limit - 1.0):+.3g} %"
    if scaled > upper and scaled > 0:  # without the factor the limit scales by upper / (factor × nominal)
        other = limit * upper / scaled
        words += (f"; with the upper bound alone (the other reading) the limit is {other:.4g}: "
                  f"{'pass' if value >= other else 'fail'}, margin {100.0 * (value / other - 1.0):+.3g} %"
                  if other > 0 else "")
    return words


def _fixed_base_row(v_s: dict, fixed_base: dict | None) -> dict:
    """17.5.4.3(1): ELF V_s/W ≥ C_s(T_M) W_s/W of the fixed-base structure, the bound with the smaller margin."""
    from isolator.review import checks as C

    clause, fixed_base = "ASCE 7-22 17.5.4.3(1) [U]", fixed_base or {}
    per = {b: f for b, f in fixed_base.get("per_bound", {}).items() if math.isfinite(v_s.get(b, math.nan))}
    if not per:
        why = fixed_base.get("missing") or "needs the fixed-base structure's R and the design spectrum"
        return C.check("V_s_fixed_base_limit", clause, C.NOT_CHECKED, None, None,
                       f"V_s ≥ the fixed-base ELF force of W_s at T_M (Section 12.8): {why}", "V/W")
    b = min(per, key=lambda k: v_s[k] / per[k]["V_over_W"])
    f = per[b]
    return C.at_least("V_s_fixed_base_limit", clause, v_s[b], f["V_over_W"],
                      f"ELF V_s/W ({b} bound) ≥ C_s W_s/W with C_s = {f['C_s']:.4g} at T_M = {f['T_M_s']:.4g} s "
                      f"(Eq. {f['equation']} governs); {fixed_base['basis']}", "V/W")
