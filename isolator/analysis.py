r"""One analysis of a design under a ground motion, and the one schema of its numbers.

:func:`analyse` is the pipeline that ``isolator report``, ``isolator batch`` and the code
review share, for one component, a pair, or a pair and a vertical::

    the scene (design × motion) → the model registry chooses and runs the model it needs
      → the paper's point (α, k, η from the horizontal PGA and PGV)
      → classify the record response (regime and ζ over D5–95; A and the dominant force in 1-D)
      → the harmonic problem at the equivalent point (1-D only), compared
      → engineering quantities
      → optionally the design on the harmonic regime map (1-D only)

The result, :class:`Analysis`, is one type whatever the model; :meth:`Analysis.to_dict` is
the one schema (``schema_version`` :data:`SCHEMA_VERSION`, units in every dimensional key,
JSON-safe through :func:`isolator.serialize.json_safe`).  A measure that does not apply to
a response (the paper's A and the harmonic comparison of a planar response) is ``null`` and
``not_applicable`` says why.  ``isolator simulate --json``, the batch rows
(:meth:`Analysis.row`), the review's per-pair results and the report JSON are slices of it
(``docs/schema.md``).

References
----------
M. Nicolas (2017), hal-01432172: Eq. 6 (α, k, η), Eq. 3 (ζ), Eq. 5 (force ratios).
"""

from __future__ import annotations

import dataclasses
import datetime as _dt
import time
from dataclasses import dataclass, field

from isolator.serialize import json_safe
from isolator.solver.base import SUMMARY_KEYS

#: Version of the dict of :meth:`Analysis.to_dict` (bump on any rename or change of meaning; docs/changelog.md).
SCHEMA_VERSION = 2
#: Which schema a JSON follows (the review's is ``"isolator.review"``, with its own version).
SCHEMA_NAME = "isolator.analysis"
#: Fields of a :class:`~isolator.metrics.Classification` written flat as ``<field>_record`` / ``<field>_harmonic``.
CLASSIFICATION_FIELDS = ("regime", "zeta", "amplitude", "amplified", "dominant_force", "dominant_force_rho",
                         "rho_ev", "rho_vf", "rho_ef")
#: The solver's keys that are timings (they differ between two runs of the same analysis).
TIMING_KEYS = ("solver_seconds", "harmonic_seconds")
#: Keys of the batch row taken flat from :meth:`Analysis.to_dict` (the record and design columns are the batch's
#: own; ``isolator.batch.store.COLUMNS`` is record + design + these + :data:`ROW_ENGINEERING_KEYS` + timing).
ROW_KEYS = (
    "model", "model_reason", "alpha", "k", "eta", "configuration",
    *(key for key in SUMMARY_KEYS if key not in ("model", "model_reason", "configuration", *TIMING_KEYS)),
    "displacement_capacity_m", "displacement_demand_ratio", "peak_displacement_over_a0", "transmitted_over_pga",
    "window_start_s", "window_end_s", "harmonic_steady", "harmonic_status", "n_disagreements",
    *(f"{name}_{source}" for name in CLASSIFICATION_FIELDS for source in ("record", "harmonic")),
    *TIMING_KEYS,
)
#: Engineering quantities also written flat in the batch row.
ROW_ENGINEERING_KEYS = ("effective_period_s", "effective_damping_ratio", "peak_transmitted_force_N",
                        "base_shear_coefficient")
#: Status of the harmonic columns when the harmonic problem is not solved (``harmonic=False``).
HARMONIC_NOT_COMPUTED = "not computed"
#: Status of the harmonic columns of a planar response, and why.
HARMONIC_NOT_APPLICABLE = "not applicable"
HARMONIC_NOT_APPLICABLE_REASON = ("the paper's harmonic problem is that of a rigid block on one surface in one "
                                  "dimension (Nicolas 2017): a planar or multi-surface response is not compared "
                                  "with it")
#: Why a planar response has no regime map.
MAP_NOT_APPLICABLE_REASON = "the paper's regime map is of the one-dimensional harmonic problem"
#: Why the one-record checks are absent when the caller added none (:meth:`Analysis.with_checks`).
CHECKS_NOT_ADDED_REASON = ("not computed: the caller adds the one-record review checks (isolator report does for "
                           "one component; isolator review checks a suite of pairs)")

_HARMONIC_CACHE: dict = {}
_HARMONIC_CACHE_MAX = 50_000  #: entries (a steady response with 2 samples per period: ~1 kB each)


@dataclass
class HarmonicMap:
    """The design on the paper's harmonic regime map (what page 4 of a report draws).

    Attributes
    ----------
    frame : dict
        ``{"k": (k_min, k_max), "alpha": (α_min, α_max)}`` around the design's point [-].
    resolution : int
        Grid points per axis [-].
    regime_map : isolator.maps.RegimeMap
        The sampled map (refined boundaries).
    triple_point : tuple or None
        (α̂, k̂) where the three forces are equal (None without damping or outside the frame) [-].
    alphas, amplitudes, regimes, steady : numpy.ndarray
        The steady amplitude A(α) at the design's k and η, its regime codes and steady flags [-].
    """

    frame: dict
    resolution: int
    regime_map: object
    triple_point: tuple | None
    alphas: object
    amplitudes: object
    regimes: object
    steady: object

    def to_dict(self, alpha: float, k: float) -> dict:
        """The map's numbers for the schema (``map`` key); ``alpha``, ``k`` the design's point [-]."""
        rmap = self.regime_map
        return {"k_range": list(self.frame["k"]), "alpha_range": list(self.frame["alpha"]),
                "resolution": self.resolution, "computed_s": rmap.elapsed_s, "from_cache": rmap.from_cache,
                "triple_point": None if self.triple_point is None else {"alpha": self.triple_point[0],
                                                                         "k": self.triple_point[1]},
                "regime_at_design": rmap.regime_at(alpha, k)}


@dataclass(frozen=True)
class Analysis:
    """Everything known about one design under one ground motion (SI units), whatever the model.

    Attributes
    ----------
    design : isolator.design.Design
    motion : isolator.motion.GroundMotion or isolator.motion.MotionPair
        The motion analysed (after any scaling): one component, or a pair (and a vertical).
    adaptation : isolator.adapter.Adaptation
        System, dimensionless point and intensity measures (of the horizontal resultant for a pair).
    response : isolator.solver.base.SolverResult
        The model's response (``response.model`` and ``model_reason`` say which ran and why).
    record_class : isolator.metrics.Classification
        The record's classification (fields that do not apply to a planar response are None).
    harmonic : isolator.solver.harmonic.HarmonicResponse or None
        The steady harmonic response at the equivalent point (None when not computed or not applicable).
    harmonic_class : isolator.metrics.Classification or None
    engineering : dict
        :func:`isolator.adapter.engineering_quantities` (SI units in the keys).
    disagreements : tuple of str
        Where record and harmonic classifications differ.
    not_applicable : dict
        Schema key → why it is null for this analysis.
    checks : tuple of dict or None
        The one-record review checks, when the caller added them (:meth:`with_checks`).
    harmonic_seconds : float
        Time spent on the harmonic problem (0 when it came from the cache) [s].
    harmonic_map : HarmonicMap or None
        The design on the regime map, when asked for (one component only).
    """

    design: object
    motion: object
    adaptation: object
    response: object
    record_class: object
    harmonic: object
    harmonic_class: object
    engineering: dict
    disagreements: tuple = ()
    not_applicable: dict = field(default_factory=dict)
    checks: tuple | None = None
    record_label: str = ""
    scaling_note: str = ""
    created_utc: str = ""
    harmonic_seconds: float = 0.0
    harmonic_map: HarmonicMap | None = None

    @property
    def model(self) -> str:
        """The solver model that ran (:func:`isolator.solver.models.select_model`)."""
        return self.response.model

    @property
    def model_reason(self) -> str:
        """Why that model."""
        return self.response.model_reason

    @property
    def is_planar(self) -> bool:
        """The response moves in the plane ((N, 2) histories)."""
        return self.response.is_planar

    @property
    def paper_applies(self) -> bool:
        """The paper's measures apply: a 1-D response of a block on one surface (:func:`paper_applies`)."""
        return paper_applies(self.response)

    @property
    def components(self) -> dict:
        """The ground motions analysed, by axis name (``x``; ``y``, ``z`` for a pair)."""
        parts = getattr(self.motion, "components", None)
        return parts if isinstance(parts, dict) else {"x": self.motion}

    @property
    def displacement_demand_ratio(self) -> float | None:
        """Peak (resultant) displacement / the design's displacement capacity (None without one) [-]."""
        capacity = getattr(self.design, "displacement_capacity_m", None)
        return None if capacity is None else self.response.peak_displacement_m / capacity

    def with_checks(self, checks) -> Analysis:
        """This analysis with the one-record review checks added by the caller (a new object).

        Parameters
        ----------
        checks : list of dict
            Rows of :func:`isolator.review.record_checks.record_checks`.
        """
        return dataclasses.replace(self, checks=tuple(checks))

    # ---- the schema ----------------------------------------------------------------

    def to_dict(self) -> dict:
        """The one schema of an analysis (see ``docs/schema.md``), JSON-safe.

        Returns
        -------
        dict
            ``schema`` (:data:`SCHEMA_NAME`), the flat keys (:meth:`flat`), ``not_applicable``, ``disagreements``, ``engineering``,
            ``design``, ``system``, ``record``, ``map`` when computed, ``verdicts``, ``checks``,
            ``software``, ``created_utc``.
        """
        from isolator import __version__

        p = self.adaptation.point
        out = {"schema": SCHEMA_NAME, **self.flat()}
        out["not_applicable"] = dict(self.not_applicable)
        if self.checks is None:
            out["not_applicable"]["checks"] = CHECKS_NOT_ADDED_REASON
        out["disagreements"] = list(self.disagreements)
        out["engineering"] = dict(self.engineering)
        out["design"] = self.design.as_dict()
        out["system"] = self.adaptation.dimensional_dict()
        out["record"] = record_dict(self.motion, self.record_label, scaling=self.scaling_note,
                                    intensity=self.adaptation.intensity)
        if self.harmonic_map is not None:
            out["map"] = self.harmonic_map.to_dict(p.alpha, p.k)
        out["verdicts"] = verdicts(self)
        out["checks"] = [] if self.checks is None else [dict(row) for row in self.checks]
        out["software"] = {"name": "isolator", "version": __version__}
        out["created_utc"] = self.created_utc
        return json_safe(out)

    def flat(self) -> dict:
        """The flat keys of the schema (identity, point, response, demand, classifications), in schema order."""
        out: dict = {"schema_version": SCHEMA_VERSION, "model": self.model, "model_reason": self.model_reason}
        p = self.adaptation.point
        out.update(p.as_dict())
        out.update(self.response.summary())
        rc, hc = self.record_class, self.harmonic_class
        for name in CLASSIFICATION_FIELDS:
            out[f"{name}_record"] = getattr(rc, name)
            out[f"{name}_harmonic"] = None if hc is None else getattr(hc, name)
        out["window_start_s"], out["window_end_s"] = (float(v) for v in rc.window_s)
        out["harmonic_steady"] = None if self.harmonic is None else bool(self.harmonic.steady)
        if self.harmonic is not None:
            out["harmonic_status"] = self.harmonic.status
        else:
            out["harmonic_status"] = HARMONIC_NOT_COMPUTED if self.paper_applies else HARMONIC_NOT_APPLICABLE
        out["harmonic_seconds"] = self.harmonic_seconds
        out["n_disagreements"] = None if hc is None else len(self.disagreements)
        out["displacement_capacity_m"] = getattr(self.design, "displacement_capacity_m", None)
        out["displacement_demand_ratio"] = self.displacement_demand_ratio
        peak = self.response.peak_displacement_m
        out["peak_displacement_over_a0"] = peak / p.a0_m
        pga = self.adaptation.intensity.pga_m_s2
        out["transmitted_over_pga"] = self.response.peak_transmitted_acceleration_m_s2 / pga if pga > 0 else None
        return out

    def row(self) -> dict:
        """The batch's slice of :meth:`to_dict`: :data:`ROW_KEYS` and :data:`ROW_ENGINEERING_KEYS`, flat.

        Built from the same pieces as :meth:`to_dict` without its nested groups and sentences
        (a batch makes thousands of rows), through the same JSON-safe helper.
        """
        flat = self.flat()
        row = {key: flat[key] for key in ROW_KEYS}
        row.update({key: self.engineering[key] for key in ROW_ENGINEERING_KEYS})
        return json_safe(row)


def record_dict(motion, label: str, *, scaling: str = "", intensity=None) -> dict:
    """The ``record`` group of the schema: one component or a pair, the same keys.

    Parameters
    ----------
    motion : isolator.motion.GroundMotion or isolator.motion.MotionPair
        The motion analysed [m/s²].
    label : str
        How the user named the record [-].
    scaling : str
        The sentence on scaling [-].
    intensity : isolator.motion.IntensityMeasures, optional
        The measures the analysis used (of the horizontal resultant for a pair).

    Returns
    -------
    dict
        ``label``; ``component`` (the component's label; null for a pair); ``components`` (per axis
        ``x``/``y``/``z``: path, component, units_source, pga_m_s2, processing); ``units_source``;
        ``npts``; ``dt_s`` [s] (the mean step when unequal); ``duration_s`` [s]; ``uniform_sampling``;
        ``provenance`` (of X's file); ``processing`` (the steps applied to the motion, or to the set);
        ``scaling``; ``intensity_measures`` (when given).
    """
    parts = getattr(motion, "components", None)
    if isinstance(parts, dict):
        components = motion.describe()
        first = parts["x"]
        component = None
    else:
        first = motion
        components = {"x": {"path": motion.provenance.get("path", ""), "component": motion.component,
                            "pga_m_s2": motion.pga_m_s2, "units_source": motion.units_source,
                            "processing": list(motion.processing)}}
        component = motion.component
    out = {"label": label, "component": component, "components": components, "units_source": first.units_source,
           "npts": motion.npts, "dt_s": motion.dt_s, "duration_s": motion.duration_s,
           "uniform_sampling": motion.sample_times_s is None, "provenance": dict(first.provenance),
           "processing": list(motion.processing), "scaling": scaling}
    if intensity is not None:
        out["intensity_measures"] = intensity.as_dict()
    return out


def _harmonic_at(point) -> tuple:
    """(HarmonicResponse, Classification, seconds) at a point; cached per process (seconds 0 on a hit)."""
    from isolator.metrics import classify_harmonic
    from isolator.solver.harmonic import harmonic_response

    key = (point.alpha, point.k, point.eta, point.mu_s, point.mu_k)
    hit = _HARMONIC_CACHE.get(key)
    if hit is not None:
        return hit[0], hit[1], 0.0
    start = time.perf_counter()
    # the classification reads the exact event metrics, not the dense output: 2 samples per period
    harmonic = harmonic_response(*key, samples_per_period=2)
    classification = classify_harmonic(harmonic)
    seconds = time.perf_counter() - start
    if len(_HARMONIC_CACHE) < _HARMONIC_CACHE_MAX:
        _HARMONIC_CACHE[key] = (harmonic, classification)
    return harmonic, classification, seconds


def harmonic_map(point, map_resolution: int, workers: int | None = None) -> HarmonicMap:
    """The design's point on the harmonic regime map: map, triple point and A(α) at its k and η.

    Parameters
    ----------
    point : isolator.adapter.DimensionlessPoint
        The design's equivalent point [-].
    map_resolution : int
        Grid points per axis of the map (the A(α) curve has twice as many) [-].
    workers : int, optional
        Processes (default :func:`isolator.parallel.default_workers`).

    Returns
    -------
    HarmonicMap
    """
    import numpy as np

    from isolator.maps import amplitude_curve, design_frame, regime_map, triple_point

    p = point
    frame = design_frame(p.alpha, p.k)
    rmap = regime_map(p.eta, p.mu_s, p.mu_k, k_range=frame["k"], alpha_range=frame["alpha"],
                      n_k=map_resolution, n_alpha=map_resolution, workers=workers, refine=True)
    triple = triple_point(p.eta, p.mu_s, p.mu_k, alpha_max=frame["alpha"][1]) if p.eta > 0 else None
    alphas = np.unique(np.concatenate((np.linspace(1.0 + 1e-6, frame["alpha"][1], 2 * map_resolution), [p.alpha])))
    amplitudes, regimes, steady = amplitude_curve(p.k, p.eta, p.mu_s, p.mu_k, alphas, workers=workers)
    return HarmonicMap(frame=frame, resolution=int(map_resolution), regime_map=rmap, triple_point=triple,
                       alphas=alphas, amplitudes=amplitudes, regimes=regimes, steady=steady)


def analyse(design, motion, *, intensity=None, window_s: tuple | None = None, harmonic: bool = True,
            map_resolution: int | None = None, workers: int | None = None, record_label: str = "",
            scaling_note: str = "") -> Analysis:
    """Analyse a design under a ground motion: the one pipeline of report, batch and review.

    Parameters
    ----------
    design : isolator.design.Design
        The isolator.
    motion : isolator.motion.GroundMotion or isolator.motion.MotionPair
        One horizontal component, or a pair (and a vertical), of ground acceleration [m/s²]
        (already scaled if asked).  The model is the one the scene needs
        (:func:`isolator.solver.models.select_model`).
    intensity : isolator.motion.IntensityMeasures, optional
        The motion's intensity measures if already computed (a batch computes them once
        per record for all its designs); for a pair, those of the horizontal resultant
        (:func:`isolator.adapter.motion_intensity`).
    window_s : tuple, optional
        Strong-motion window (D5–95) [s] on the response's time axis if already computed;
        computed otherwise (of the horizontal resultant for a pair).
    harmonic : bool
        Also solve and classify the harmonic problem at the equivalent point (1-D responses;
        the harmonic keys are None and ``harmonic_status`` is :data:`HARMONIC_NOT_COMPUTED`
        without it).
    map_resolution : int, optional
        Also place the design on the regime map at this resolution (:func:`harmonic_map`; 1-D).
    workers : int, optional
        Processes for the map.
    record_label : str
        How the record was named by the user [-].
    scaling_note : str
        A sentence on scaling, kept with the numbers [-].

    Returns
    -------
    Analysis

    Raises
    ------
    isolator.errors.DesignError
        ``design`` is not a :class:`~isolator.design.Design`.
    isolator.errors.MotionError
        ``motion`` is not a ground motion or pair; ``window_s`` is not two finite times in
        order; ``harmonic`` is not a bool.
    isolator.errors.RecordInputError
        A motion the solver cannot take (a record of zeros: no equivalent point).
    isolator.solver.system.InvalidSystemError
        An isolator the solver cannot take; a ``map_resolution`` or ``workers`` out of range.
    """
    _check_arguments(design, motion, window_s, harmonic, workers)
    from isolator.adapter import PAIR_PREDOMINANT_PERIOD_REASON, adapt, engineering_quantities, motion_keywords
    from isolator.metrics import PLANAR_NOT_APPLICABLE, classify_record, compare
    from isolator.solver.models import Scene, simulate

    parts = getattr(motion, "components", None)
    if isinstance(parts, dict) and set(parts) == {"x"}:
        motion = parts["x"]  # a MotionPair of one component is that component
    adaptation = adapt(design, motion, intensity)
    response = simulate(Scene.of(motion, motion_keywords(design), design))
    adaptation = adaptation.on_response(response)  # a double or triple: the point on the regime reached
    point = adaptation.point
    record_class = classify_record(response, point, design, window_s=window_s)
    not_applicable: dict = {}
    if isinstance(parts, dict) and "y" in parts:
        not_applicable["record.intensity_measures.predominant_period_s"] = PAIR_PREDOMINANT_PERIOD_REASON
    harmonic_response = harmonic_class = harmonic_map_ = None
    harmonic_seconds = 0.0
    if not paper_applies(response):
        not_applicable.update({f"{name}_record": reason for name, reason in PLANAR_NOT_APPLICABLE.items()})
        not_applicable.update({f"{name}_harmonic": HARMONIC_NOT_APPLICABLE_REASON for name in CLASSIFICATION_FIELDS})
        not_applicable.update(harmonic_status=HARMONIC_NOT_APPLICABLE_REASON, map=MAP_NOT_APPLICABLE_REASON)
    else:
        if harmonic:
            harmonic_response, harmonic_class, harmonic_seconds = _harmonic_at(point)
        if map_resolution is not None:
            harmonic_map_ = harmonic_map(point, map_resolution, workers)
    disagreements = () if harmonic_class is None else tuple(compare(record_class, harmonic_class))
    return Analysis(
        design=design, motion=motion, adaptation=adaptation, response=response, record_class=record_class,
        harmonic=harmonic_response, harmonic_class=harmonic_class,
        engineering=engineering_quantities(design, response), disagreements=disagreements,
        not_applicable=not_applicable, record_label=record_label, scaling_note=scaling_note,
        created_utc=_dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC"),
        harmonic_seconds=harmonic_seconds, harmonic_map=harmonic_map_,
    )


def _check_arguments(design, motion, window_s, harmonic, workers) -> None:
    """Refuse what :func:`analyse` cannot take with a typed error and a sentence (never a bare AttributeError)."""
    import math

    from isolator.design import Design
    from isolator.errors import DesignError, InvalidSystemError, MotionError
    from isolator.motion import GroundMotion, MotionPair

    if not isinstance(design, Design):
        raise DesignError(f"analyse needs an isolator.design.Design, got {type(design).__name__}")
    if not isinstance(motion, (GroundMotion, MotionPair)):
        raise MotionError(f"analyse needs a GroundMotion or a MotionPair, got {type(motion).__name__}")
    if not isinstance(harmonic, bool):
        raise MotionError(f"harmonic must be True or False, got {harmonic!r}")
    if window_s is not None:
        try:
            start, end = (float(value) for value in window_s)
        except (TypeError, ValueError):
            raise MotionError(f"window_s must be two times (start, end) in seconds, got {window_s!r}") from None
        if not (math.isfinite(start) and math.isfinite(end) and start < end):
            raise MotionError(f"window_s = {window_s!r} must be two finite times in seconds with start < end")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise InvalidSystemError(f"workers must be a whole number ≥ 1, got {workers!r}")


def paper_applies(response) -> bool:
    """The paper's classification, harmonic problem and map apply to ``response``: a 1-D response of a block on
    one surface (the solver's ``system`` of µs, µk, K/M, γ/M), not a planar or multi-surface one."""
    return not response.is_planar and getattr(response, "system", None) is not None


def _capacity_sentence(analysis: Analysis, ratio: float) -> str:
    """The capacity sentence of a planar response: its demand is the centre of mass's peak, and it says so — the
    bearings' own demand (torsion; EN 1998-1 10.3(2)'s γ_x) is the review's ``record_capacity`` row, not this."""
    word = "within" if ratio <= 1.0 else "EXCEEDS"
    return (f"Peak resultant displacement of the centre of mass {analysis.response.peak_displacement_m:.4g} m {word} "
            f"the displacement capacity {analysis.design.displacement_capacity_m:.4g} m (ratio {ratio:.3g}; no "
            "torsion or reliability factor: the bearings' demand is the review's record_capacity row).")


def verdicts(analysis: Analysis) -> list[str]:
    """Plain sentences on the analysis: regime, the paper's A, dominant force, demand, uplift, residual.

    Each sentence is written where its measure applies (the paper's A and the dominant force
    for a 1-D response; the displacement demand and uplift for a planar one).
    """
    from isolator.metrics import REGIME_WORDS

    rc, hc = analysis.record_class, analysis.harmonic_class
    eng = analysis.engineering
    p = analysis.adaptation.point
    r = analysis.response
    out = []
    if not analysis.paper_applies:
        ratio = analysis.displacement_demand_ratio
        # a bearing held at its rims (solver.multisurface); a building without a rim past its capacity says so itself
        reached = getattr(r, "ultimate_displacement_reached", False) and getattr(r, "rim_modelled", True)
        if ratio is not None and not reached:  # at the rim the ratio is 1 by construction: the sentence below
            out.append(_capacity_sentence(analysis, ratio))
        if reached:
            out.append(f"The bearing REACHED its ultimate displacement {r.ultimate_displacement_m:.4g} m (its "
                       "displacement capacity: every slider on its rim): plastic impact(s), impulse "
                       f"{analysis.design.mass_kg * r.impact_impulse_m_s:.4g} "
                       "N·s in all; the motion is held there, not continued past it.")
        if r.uplift_time_s > 0:
            out.append(f"The bearing lifts off {r.n_uplifts} time(s), {r.uplift_time_s:.3g} s "
                       "in all (n = g + a_z <= 0: no friction, no restoring force).")
        out.append(f"Residual displacement {r.residual_displacement_m:.3g} m "
                   f"(x {r.residual_displacement_x_m:.3g} m, y {r.residual_displacement_y_m:.3g} m).")
        return out
    prediction = "not computed" if hc is None else f"{hc.regime} ({REGIME_WORDS[hc.regime]})"
    if rc.regime == "ST":
        out.append(f"Regime under the record: ST - the isolator never slides (alpha = PGA/(mu_s g) = {p.alpha:.3g}"
                   f"{' <= 1' if p.alpha <= 1 else ''}): the superstructure moves with the ground, not isolated; "
                   f"harmonic prediction: {prediction}.")
    else:
        out.append(f"Regime under the record: {rc.regime} ({REGIME_WORDS[rc.regime]}), slip-time ratio over D5-95 "
                   f"zeta = {rc.zeta:.3f}; harmonic prediction: {prediction}.")
    # the paper's measure, labelled: A is relative to A0 = PGV²/PGA, not to the ground's displacement
    out.append(f"Paper's measure A = {rc.amplitude:.3g} ({'>' if rc.amplified else '<='} 1): half peak-to-peak "
               f"displacement / A0, A0 = PGV²/PGA = {p.a0_m:.3g} m (the harmonic motion of equal PGA and PGV, "
               "not the ground's displacement).")
    out.append(f"Dominant force: {rc.dominant_force} (force peaks); harmonic prediction: "
               f"{'not computed' if hc is None else hc.dominant_force}.")
    if eng["peak_displacement_m"] > 0:
        ratio = abs(eng["residual_displacement_m"]) / eng["peak_displacement_m"]
        out.append(f"Residual displacement {eng['residual_displacement_m'] * 1e3:.3g} mm "
                   f"= {100 * ratio:.3g} % of the peak.")
    out.extend(f"Disagreement - {note}." for note in analysis.disagreements)
    if hc is not None and not analysis.disagreements:
        out.append("Record and harmonic map agree on regime, amplification and dominant force.")
    return out
