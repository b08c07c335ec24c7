"""The review's parameters: every number a code clause needs that the rules file does not fix.

Each entry has its default, its mark from ``REVIEW_RULES.md`` (§0: **V** verified, **S** secondary
source, **U** unverified — must be a parameter, printed in the report — or *practice* /
*convention* / *interpretation*), the rule it serves and a short meaning.  Every review prints the
values it used with their marks; any of them can be changed (``--set name=value`` on the command
line, ``parameters={…}`` in :func:`isolator.review.run.run_review`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from isolator.errors import ReviewError


@dataclass(frozen=True)
class Parameter:
    name: str
    default: object
    mark: str
    rule: str
    meaning: str
    codes: tuple = ("asce7-22", "en15129")


PARAMETERS = {p.name: p for p in [
    Parameter("n_pairs_min", 7, "U", "ASCE 7-22 17.3.2", "minimum number of pairs in the suite", ("asce7-22",)),
    Parameter("n_records_min_en", 3, "U", "EN 1998-1 3.2.3.1.2", "minimum number of records", ("en15129",)),
    Parameter("range_lo_factor", 0.75, "U", "ASCE 7-22 17.3.3", "period range from f × T_M (upper bound)",
              ("asce7-22",)),
    Parameter("range_hi_factor", 1.25, "U", "ASCE 7-22 17.3.3", "period range to f × T_M (lower bound)",
              ("asce7-22",)),
    Parameter("en_range_lo_factor", 0.2, "U", "EN 1998-1 3.2.3.1.2(4)", "range from f × T_eff", ("en15129",)),
    Parameter("en_range_hi_factor", 2.0, "U", "EN 1998-1 3.2.3.1.2(4)", "range to f × T_eff", ("en15129",)),
    Parameter("min_ratio", 1.00, "U", "ASCE 7-22 17.3.3 / 16.2.3.2",
              "suite-average RotD100 ≥ min_ratio × target at every period of the range (0.90 alternative)",
              ("asce7-22",)),
    Parameter("mean_ratio_min", None, "interpretation", "ASCE 7-22 16.2.3.2",
              "with min_ratio 0.90: mean over the range of the ratio ≥ this ('generally matches')",
              ("asce7-22",)),
    Parameter("en_min_ratio", 0.90, "U", "EN 1998-1 3.2.3.1.2(4)",
              "mean component spectrum ≥ en_min_ratio × elastic spectrum over the range", ("en15129",)),
    Parameter("grid_points", 300, "convention", "ASCE 7-22 17.3.3",
              "log-spaced periods of the range (plus both ends and the T_M values)"),
    Parameter("sf_flag_low", 0.25, "practice", "reviewer practice, not code", "scale factors below are flagged"),
    Parameter("sf_flag_high", 4.0, "practice", "reviewer practice, not code", "scale factors above are flagged"),
    Parameter("usable_band_factor", 1.25, "practice", "NGA-West2 usable band",
              "lowest usable frequency = factor × high-pass corner"),
    Parameter("f_ae", 0.75, "S", "ASCE 7-22 17.2.8.4", "weight of the aging/environment factor", ("asce7-22",)),
    Parameter("restoring_min", 0.025, "S/U", "ASCE 7-22 17.2.4.4",
              "F(D) − F(D/2) ≥ restoring_min × W (FPS: D ≥ 2 restoring_min R)", ("asce7-22",)),
    Parameter("D_M_form", "SaM", "U", "ASCE 7-22 17.5.3.1",
              "D_M = g S_a(T_M) T_M²/(4π² B_M) ('SaM') or g S_M1 T_M/(4π² B_M) ('SM1')", ("asce7-22",)),
    Parameter("B_M_at_50pct", 2.0, "S", "ASCE 7-22 Table 17.5-1",
              "damping coefficient B_M at β_M ≥ 50 % (linear from 1.9 at 40 %; P2 and a third code 2.0, P1 stops at "
              "1.9 from 40 %): decides B_M only above β_M = 40 %", ("asce7-22",)),
    Parameter("accidental_e", 0.05, "S", "ASCE 7-22 17.5.3.3",
              "accidental eccentricity as a fraction of the plan dimension perpendicular to the loading", ("asce7-22",)),
    Parameter("D_TM_floor", 1.15, "S", "ASCE 7-22 17.5.3.3 (Eq. 17.5-3)", "D_TM ≥ floor × D_M", ("asce7-22",)),
    Parameter("P_T_min", 1.0, "S", "ASCE 7-22 17.5.3.3", "P_T not taken below this", ("asce7-22",)),
    Parameter("abrupt_hysteresis", False, "S", "ASCE 7-22 17.5.4.2 (Eq. 17.5-8)",
              "exponent 1 − 3.5 β_M instead of 1 − 2.5 β_M", ("asce7-22",)),
    Parameter("Ws_over_W", 1.0, "U", "ASCE 7-22 17.5.4.2", "seismic weight above the isolation / total",
              ("asce7-22",)),
    Parameter("R_I", 1.0, "U", "ASCE 7-22 17.5.4.2 (R_I = 3R/8, 1 ≤ R_I ≤ 2)",
              "response modification of the superstructure (1.0 is the most conservative)", ("asce7-22",)),
    Parameter("importance_factor_Ie", 1.0, "U", "ASCE 7-22 17.5.4.3(1) / 12.8.1.1 (Table 1.5-2)",
              "importance factor I_e of the fixed-base ELF force C_s W_s (17.5.4.3(1))", ("asce7-22",)),
    Parameter("n_for_mean", 7, "U", "ASCE 7-22 17.6.3.4 / EN 1998-1 4.3.3.4.3(3)",
              "mean of the suite when ≥ n analyses, otherwise the maximum"),
    Parameter("f_disp", 0.8, "U", "ASCE 7-22 17.6.4.1", "RHA total displacement ≥ f × D_TM (ELF)", ("asce7-22",)),
    Parameter("f_below", 0.9, "U", "ASCE 7-22 17.6.4.2", "RHA isolation-system shear ≥ f × V_b (ELF)",
              ("asce7-22",)),
    Parameter("f_above_rha", 0.6, "U", "ASCE 7-22 17.6.4.2", "RHA superstructure shear ≥ f × V_s (regular)",
              ("asce7-22",)),
    Parameter("D_over_R_max", 0.25, "practice", "small-angle pendulum (F = W D/R)",
              "D/R beyond which the pendulum relation and most bearings' geometry do not hold"),
    Parameter("residual_max_m", None, "practice", "no clause in ASCE 7-22 Ch. 17",
              "limit on the design residual displacement [m] (none: reported, not checked)"),
    Parameter("transmitted_over_pga_max", 1.0, "practice", "isolation effectiveness (practice)",
              "peak transmitted acceleration / PGA of the scaled pair"),
    Parameter("spectral_matching_min", 1.10, "S", "ASCE 7-22 16.2.3.3",
              "spectrally matched suites: average ≥ this × target over the range (Ch. 16; U that Ch. 17 keeps it)",
              ("asce7-22",)),
    Parameter("wind_shear_over_W", None, "input", "ASCE 7-22 17.2.4.2 / 17.5.4.3(2)",
              "design (factored) wind base shear / W; none: the wind rows are not checked", ("asce7-22",)),
    Parameter("drift_limit_rha", 0.020, "U", "ASCE 7-22 17.6.4.4", "story drift ratio limit with RHA",
              ("asce7-22",)),
    Parameter("dead_load_factor_max", 1.2, "U", "ASCE 7-22 17.2.4.6 / 2.3.6 (1.2D + E_v + E_h + L)",
              "factor on each bearing's gravity share for its maximum vertical load (stability); E_v added unless "
              "the analysis has its vertical", ("asce7-22",)),
    Parameter("dead_load_factor_min", 0.9, "U", "ASCE 7-22 17.2.4.6 / 17.2.4.7 / 2.3.6 (0.9D − E_v + E_h)",
              "factor on each bearing's gravity share for its minimum vertical load (uplift, stability); E_v "
              "subtracted unless the analysis has its vertical", ("asce7-22",)),
    Parameter("vertical_Ev_coefficient", 0.2, "U", "ASCE 7-22 12.4.2.2 (E_v = 0.2 S_DS D, S_MS for the MCE_R)",
              "E_v = coefficient × S_MS × D on the gravity share, for an analysis without its vertical component",
              ("asce7-22",)),
    Parameter("capacity_at_corner", True, "U", "REVIEW_RULES 1.10 / ASCE 7-22 17.2.4.6 (capacity at D_TM); "
              "EN 1998-1 10.3(2) (each isolator's displacement)",
              "each analysis's capacity row reads the corner bearing: the centre-of-mass displacement × the "
              "review's torsion factor (ASCE: D_TM/D_M of Eq. 17.5-3; EN: the largest δ_i of EN 1998-1 10.9.6); "
              "false: the centre of mass"),
    Parameter("multisurface_activation", "outer", "U", "ASCE 7-22 17.5.4.3(3) (REVIEW_RULES 1.9: for sliders the "
              "breakaway friction)",
              "a double or triple bearing's force that fully activates it: 'outer' the backbone's force at the start "
              "of the regime of the largest compliance (a triple's regime III: both outer surfaces slide; a double's "
              "1+2: both surfaces slide), 'breakaway' its force at rest (its smallest µ_i); a single surface: µs either "
              "way", ("asce7-22",)),
    Parameter("activation_nominal_factor", 1.5, "U", "ASCE 7-22 17.5.4.3(3) (REVIEW_RULES 1.9)",
              "the force that fully activates the isolation system: the greater of its upper-bound value and this "
              "factor × its nominal value (the row also prints its verdict with the upper bound alone)", ("asce7-22",)),
    Parameter("horizontal_only", False, "input", "ASCE 7-22 17.3.2 (pairs of horizontal components)",
              "analyse the pairs without their vertical components (a model that does not take a vertical, e.g. the "
              "building); false: a vertical is analysed or the review refuses it"),
    Parameter("weak_pga_fraction", 0.1, "practice", "record selection (practice)",
              "a scaled pair with resultant PGA < fraction × the lower bound's breakaway g can hardly move the "
              "isolator (a single surface: × λ_min µs; a double or triple: × its lower bound's breakaway force / W, "
              "its smallest µ_i)"),
    Parameter("bandwidth_min", 0.25, "practice", "record selection (practice)",
              "Vanmarcke spectral bandwidth below which a component is not an earthquake record (sinusoid)"),
    Parameter("gamma_x", 1.2, "U", "EN 1998-1 10.3(2)", "reliability factor on isolator displacements",
              ("en15129",)),
    Parameter("delta", 0.5, "U", "EN 1998-2 7.7.1 / EN 15129", "restoring capability d_Ed/d_r ≥ δ", ("en15129",)),
    Parameter("eta_min", 0.55, "U", "EN 1998-1 3.2.2.2(3) (REVIEW_RULES 2)",
              "least damping correction η = sqrt(10/(5 + ξ)) of the elastic spectrum at the isolation system's "
              "effective damping (0.55: ξ = 28 %)", ("en15129",)),
    Parameter("en_accidental_e", 0.05, "U", "EN 1998-1 4.3.2(1) / 10.9.6",
              "accidental eccentricity / the plan dimension ⟂ the loading, in each isolator's torsion amplification "
              "δ_i = 1 + e_tot y_i / r²", ("en15129",)),
]}


@dataclass(frozen=True)
class Range:
    """The values a parameter may take, and why: a value outside is refused with the reason."""

    lo: float
    hi: float
    reason: str
    lo_open: bool = False  #: the lower bound itself is excluded (a factor of 0 means nothing)


#: Every parameter's range with its reason (issue 26: ``usable_band_factor=0`` divided by zero,
#: ``min_ratio=1e300`` overflowed, ``grid_points=1e7`` and ``range_lo_factor=1e-6`` never ended).
RANGES = {
    "n_pairs_min": Range(1, 1000, "a number of pairs of a suite (ASCE 7-22 17.3.2 asks 7)"),
    "n_records_min_en": Range(1, 1000, "a number of records of a suite (EN 1998-1 3.2.3.1.2 asks 3)"),
    "range_lo_factor": Range(0.1, 1.0, "the range starts at a fraction of T_M (ASCE 7-22 17.3.3: 0.75; Ch. 16: "
                                       "0.2); below 0.1 the spectra reach periods no isolated structure has"),
    "range_hi_factor": Range(1.0, 5.0, "the range ends at a multiple of T_M (ASCE 7-22 17.3.3: 1.25); beyond 5 "
                                       "the records' usable band is usually passed"),
    "en_range_lo_factor": Range(0.1, 1.0, "the range starts at a fraction of T_eff (EN 1998-1: 0.2)"),
    "en_range_hi_factor": Range(1.0, 5.0, "the range ends at a multiple of T_eff (EN 1998-1: 2)"),
    "min_ratio": Range(0.5, 2.0, "a ratio of the target (ASCE 7-22 16.2.3.2: 1.0, or 0.9 with the mean)"),
    "mean_ratio_min": Range(0.5, 2.0, "a ratio of the target (ASCE 7-22 16.2.3.2: 1.0)"),
    "en_min_ratio": Range(0.5, 2.0, "a ratio of the elastic spectrum (EN 1998-1 3.2.3.1.2(4): 0.9)"),
    "spectral_matching_min": Range(0.5, 2.0, "a ratio of the target (ASCE 7-22 16.2.3.3: 1.1)"),
    "grid_points": Range(10, 10000, "periods of the scaling range (each costs a spectrum per record; fewer than "
                                    "10 miss the range's shape)"),
    "sf_flag_low": Range(0.0, 1.0, "a scale factor below 1 (practice flags < 0.25)", lo_open=True),
    "sf_flag_high": Range(1.0, 100.0, "a scale factor above 1 (practice flags > 4)"),
    "usable_band_factor": Range(1.0, 10.0, "the lowest usable frequency is at or above the high-pass corner "
                                           "(NGA-West2: 1.25 × the corner)"),
    "f_ae": Range(0.0, 1.0, "a weight of the aging and environment factor (ASCE 7-22 17.2.8.4: 0.75; 1 the "
                            "whole factor)"),
    "restoring_min": Range(0.0, 1.0, "a fraction of the weight W (ASCE 7-22 17.2.4.4: 0.025)"),
    "B_M_at_50pct": Range(1.9, 2.0, "Table 17.5-1's last entry: 2.0 (P2), 1.9 (P1, held from 40 %); B_M does not "
                                    "fall with β"),
    "accidental_e": Range(0.0, 0.5, "a fraction of the plan dimension (ASCE 7-22 17.5.3.3: 0.05)"),
    "D_TM_floor": Range(1.0, 2.0, "a multiple of D_M (ASCE 7-22 Eq. 17.5-3: 1.15)"),
    # below 0.1 the y/P_T² of Eq. 17.5-3 grows without bound: 1e-300 squared to 0, a ZeroDivisionError (Session 15)
    "P_T_min": Range(0.1, 10.0, "a ratio of periods (ASCE 7-22 17.5.3.3: 1.0; Eq. 17.5-3 divides by its square)"),
    "Ws_over_W": Range(0.0, 1.0, "a fraction of the total weight", lo_open=True),
    "R_I": Range(1.0, 2.0, "ASCE 7-22 17.5.4.2: 1 ≤ R_I ≤ 2"),
    "importance_factor_Ie": Range(1.0, 1.5, "an importance factor (ASCE 7-22 Table 1.5-2: 1.0, 1.25 or 1.5)"),
    "activation_nominal_factor": Range(1.0, 3.0, "a factor on the nominal activation force (ASCE 7-22 17.5.4.3(3): "
                                                 "1.5)"),
    "n_for_mean": Range(1, 1000, "a number of analyses (ASCE 7-22 17.6.3.4: 7)"),
    "f_disp": Range(0.0, 1.0, "a fraction of the ELF displacement (ASCE 7-22 17.6.4.1: 0.8)", lo_open=True),
    "f_below": Range(0.0, 1.0, "a fraction of the ELF shear (ASCE 7-22 17.6.4.2: 0.9)", lo_open=True),
    "f_above_rha": Range(0.0, 1.0, "a fraction of the ELF shear (ASCE 7-22 17.6.4.2: 0.6)", lo_open=True),
    "D_over_R_max": Range(0.0, 1.0, "a ratio D/R of a pendulum (practice: 0.25)", lo_open=True),
    "residual_max_m": Range(0.0, 10.0, "a displacement [m]", lo_open=True),
    "transmitted_over_pga_max": Range(0.0, 100.0, "a ratio of accelerations (practice: 1)", lo_open=True),
    "wind_shear_over_W": Range(0.0, 1.0, "a base shear as a fraction of the weight"),
    "drift_limit_rha": Range(0.0, 0.1, "a story drift ratio (ASCE 7-22 17.6.4.4: 0.020)", lo_open=True),
    "weak_pga_fraction": Range(0.0, 1.0, "a fraction of the lower bound's breakaway acceleration"),
    "bandwidth_min": Range(0.0, 1.0, "a Vanmarcke bandwidth (between 0 and 1)"),
    "dead_load_factor_max": Range(1.0, 2.0, "a factor on the dead load (ASCE 7-22 2.3.6: 1.2)"),
    "dead_load_factor_min": Range(0.0, 1.0, "a factor on the dead load (ASCE 7-22 2.3.6: 0.9)"),
    "vertical_Ev_coefficient": Range(0.0, 1.0, "a coefficient of S_MS D (ASCE 7-22 12.4.2.2: 0.2)"),
    "gamma_x": Range(1.0, 3.0, "a reliability factor (EN 1998-1 10.3(2): 1.2)"),
    "delta": Range(0.0, 1.0, "a ratio d_Ed/d_r (EN 1998-2 7.7.1: 0.5)", lo_open=True),
    "eta_min": Range(0.1, 1.0, "a least damping correction of the spectrum (EN 1998-1 3.2.2.2(3): 0.55; 1 no "
                               "reduction by damping)"),
    "en_accidental_e": Range(0.0, 0.5, "a fraction of the plan dimension (EN 1998-1 4.3.2(1): 0.05)"),
}
#: Pairs (low, high) of parameters whose low must stay below their high.
ORDERED = (("sf_flag_low", "sf_flag_high"), ("range_lo_factor", "range_hi_factor"),
           ("en_range_lo_factor", "en_range_hi_factor"))


def _check_range(name: str, value) -> None:
    bounds = RANGES.get(name)
    if bounds is None or value is None or isinstance(value, (bool, str)):
        return
    below = value <= bounds.lo if bounds.lo_open else value < bounds.lo
    if below or value > bounds.hi:
        interval = f"{'(' if bounds.lo_open else '['}{bounds.lo:g}, {bounds.hi:g}]"
        raise ReviewError(f"review parameter '{name}' = {value:g} is outside {interval}: {bounds.reason}")


#: Why a parameter of one code is not read by the other's review (said when it is set there).
NOT_READ = {("f_ae", "en15129"): "EN 1998-2 7.5.2.4 bounds are the plain product of the λ factors, no 0.75 "
                                  "combination (REVIEW_RULES 2)"}


def resolve(code: str, overrides: dict | None = None, *, other_codes: bool = False) -> dict:
    """The parameter values of a review: defaults of ``code`` with ``overrides`` applied.

    ``other_codes``: take a parameter of the other code's review too (the record checks of ``report`` and
    ``batch``, which read ASCE 7-22's values whatever review the same ``--set`` serves); otherwise it is refused,
    since the review would print it as used and not read it (``--set f_ae=0.5`` of an EN 15129 review).

    Raises
    ------
    ReviewError
        An unknown parameter name, one of the other code's review, a value of the wrong kind, a value outside its
        range (:data:`RANGES`, with the reason) or a low bound at or above its high (:data:`ORDERED`).
    """
    values = {name: p.default for name, p in PARAMETERS.items() if code in p.codes}
    for name, value in (overrides or {}).items():
        if name not in PARAMETERS:
            raise ReviewError(f"unknown review parameter '{name}' (known: {', '.join(PARAMETERS)})")
        if not other_codes and code not in PARAMETERS[name].codes:
            why = NOT_READ.get((name, code), f"it serves {PARAMETERS[name].rule} only")
            raise ReviewError(f"review parameter '{name}' is not read by the {code} review: {why}")
        default = PARAMETERS[name].default
        values[name] = _coerce(name, value, default)
        _check_range(name, values[name])
    for low, high in ORDERED:
        if low in values and high in values and values[low] >= values[high]:
            raise ReviewError(f"review parameters '{low}' = {values[low]:g} and '{high}' = {values[high]:g}: "
                              f"the first must be below the second")
    if code == "asce7-22" and values.get("mean_ratio_min") is None and values.get("min_ratio", 1.0) < 1.0:
        values["mean_ratio_min"] = 1.0  # REVIEW_RULES 1.5: with 0.90 also require mean ≥ 1.00
    return values


def _coerce(name: str, value, default):
    if isinstance(default, bool):
        if isinstance(value, str) and value.lower() in ("true", "false", "1", "0", "yes", "no"):
            return value.lower() in ("true", "1", "yes")
        if isinstance(value, bool):
            return value
        raise ReviewError(f"review parameter '{name}' must be true or false, got {value!r}")
    if isinstance(default, str):
        allowed = {"D_M_form": ("SaM", "SM1"), "multisurface_activation": ("outer", "breakaway")}.get(name)
        if allowed and value not in allowed:
            raise ReviewError(f"review parameter '{name}' must be one of {', '.join(allowed)}, got {value!r}")
        return str(value)
    if isinstance(value, str) and value.lower() in ("none", "null", ""):
        if default is None:  # a parameter that may be left unset (mean_ratio_min …)
            return None
        # `--set min_ratio=` was a TypeError traceback from the comparisons downstream (session 14 sweep)
        raise ReviewError(f"review parameter '{name}' needs a number (its default is {default:g}), got {value!r}")
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ReviewError(f"review parameter '{name}' must be a number, got {value!r}") from None
    if not math.isfinite(number) or number < 0:
        raise ReviewError(f"review parameter '{name}' must be a finite number ≥ 0, got {value!r}")
    if isinstance(default, int) and not isinstance(default, bool):
        if number != int(number) or number < 1:
            raise ReviewError(f"review parameter '{name}' must be a whole number ≥ 1, got {value!r}")
        return int(number)
    return number


#: Parameters a design's superstructure fixes (ASCE 7-22 17.5.4.2): then they are the design's, not assumed.
FROM_DESIGN = ("Ws_over_W", "R_I")


def from_design(code: str, values: dict, design, overrides: dict | None = None) -> tuple[dict, dict]:
    """The parameter values with those the design's ``[superstructure]`` fixes, and where each came from.

    ``Ws_over_W`` = Σ m_i / ``mass_kg`` (W_s = g Σ m_i, 17.5.4.2) whenever the design has a superstructure;
    ``R_I`` = 3R/8 within [1, 2] (17.5.4.2) when it gives ``response_modification_R``.

    Returns
    -------
    tuple
        ``(values, sources)``: ``sources`` maps a parameter taken from the design to the sentence that says how.

    Raises
    ------
    ReviewError
        ``--set`` of a parameter the design fixes (the design and the override would disagree silently).
    """
    s = getattr(design, "superstructure", None)
    if code != "asce7-22" or s is None:
        return values, {}
    fixed = {"Ws_over_W": (s.mass_kg / design.mass_kg,
                           f"the design's {s.n_floors} floors: Σ m_i / mass_kg = {s.mass_kg:.6g} / "
                           f"{design.mass_kg:.6g} kg (17.5.4.2)")}
    r = getattr(s, "response_modification_R", None)
    if r is not None:
        fixed["R_I"] = (min(max(3.0 * r / 8.0, 1.0), 2.0),
                        f"3R/8 within [1, 2] with the design's R = {r:g} (17.5.4.2)")
    clash = [name for name in fixed if name in (overrides or {})]
    if clash:
        raise ReviewError(f"review parameter '{clash[0]}' is fixed by the design's [superstructure] "
                          f"({fixed[clash[0]][0]:.4g}: {fixed[clash[0]][1]}); do not override it")
    return {**values, **{name: value for name, (value, _) in fixed.items()}}, \
        {name: basis for name, (_, basis) in fixed.items()}


def table(code: str, values: dict, sources: dict | None = None) -> list[dict]:
    """Rows {name, value, default, mark, rule, meaning, source} of the parameters used (``source``: "design …"
    for a value the design fixes, "set" for an override, "default" otherwise — the caller knows overrides)."""
    sources = sources or {}
    return [{"name": name, "value": values[name], "default": PARAMETERS[name].default, "mark": PARAMETERS[name].mark,
             "rule": PARAMETERS[name].rule, "meaning": PARAMETERS[name].meaning,
             **({"source": f"design: {sources[name]}"} if name in sources else {})}
            for name in values if name in PARAMETERS]
