r"""One analysis of a design under a ground motion, and the one schema of its numbers.

:func:`analyse` is the pipeline that ``isolator report``, ``isolator batch`` (and the
code review) share::

    adapt (design × motion → system, dimensionless point α, k, η)
      → simulate (the exact solver on the record)
      → classify the record response (regime over D5–95, A, dominant force)
      → the harmonic problem at the equivalent point (classified by the same rules)
      → compare → engineering quantities
      → optionally the design on the harmonic regime map (map, triple point, A(α) curve)

The result, :class:`Analysis`, holds the objects; :meth:`Analysis.to_dict` is the one
schema (``schema_version`` :data:`SCHEMA_VERSION`, units in every dimensional key,
JSON-safe through :func:`isolator.serialize.json_safe`).  ``isolator simulate --json``,
the batch rows (:meth:`Analysis.row`) and the report JSON are slices of it.  The schema
is documented in ``docs/schema.md``.

The response type is open: :attr:`Analysis.model` names the solver model that produced
:attr:`Analysis.response` and :attr:`Analysis.model_reason` says why it was chosen (one
horizontal component → the 1-D exact solver), so that a two-component analysis can
carry its own response type under the same schema.

References
----------
M. Nicolas (2017), hal-01432172: Eq. 6 (α, k, η), Eq. 3 (ζ), Eq. 5 (force ratios).
"""

from __future__ import annotations

import datetime as _dt
import time
from dataclasses import dataclass, field

from isolator.serialize import json_safe

#: Version of the dict of :meth:`Analysis.to_dict` (bump on any rename or change of meaning).
SCHEMA_VERSION = 1
#: The solver model of a one-component analysis (the name :func:`isolator.solver.planar.select_model` gives it).
MODEL_1D = "1d-exact"
#: The model of a one-component analysis of a design with a superstructure (:mod:`isolator.solver.building`).
MODEL_1D_BUILDING = "1d-building"
#: Why a one-component analysis runs it.
MODEL_1D_REASON = "one horizontal component, constant friction, no vertical: the exact 1-D kernel"
#: Fields of a :class:`~isolator.metrics.Classification` written flat as ``<field>_record`` / ``<field>_harmonic``.
CLASSIFICATION_FIELDS = ("regime", "zeta", "amplitude", "amplified", "dominant_force", "dominant_force_rho",
                         "rho_ev", "rho_vf", "rho_ef")
#: Keys of the batch row taken from :meth:`Analysis.to_dict` (the record and design columns are the batch's own).
ROW_KEYS = (
    "model", "model_reason", "alpha", "k", "eta", "configuration",
    "peak_displacement_m", "residual_displacement_m", "residual_displacement_x_m", "residual_displacement_y_m",
    "peak_velocity_m_s", "peak_transmitted_acceleration_m_s2", "slip_time_s", "uplift_time_s", "n_uplifts",
    "n_events", "energy_input_J_per_kg", "energy_friction_J_per_kg", "energy_viscous_J_per_kg",
    "energy_balance_error_J_per_kg", "solver_status", "displacement_capacity_m", "displacement_demand_ratio",
    "window_start_s", "window_end_s", "harmonic_steady", "harmonic_status", "n_disagreements",
    "solver_seconds", "harmonic_seconds",
    *(f"{name}_{source}" for name in CLASSIFICATION_FIELDS for source in ("record", "harmonic")),
)
#: Engineering quantities also written flat in the batch row.
ROW_ENGINEERING_KEYS = ("effective_period_s", "effective_damping_ratio", "peak_transmitted_force_N",
                        "base_shear_coefficient")
#: Status of the harmonic columns when the harmonic problem is not solved (``harmonic=False``).
HARMONIC_NOT_COMPUTED = "not computed"

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


@dataclass
class Analysis:
    """Everything known about one design under one ground motion (SI units).

    Attributes
    ----------
    design : isolator.design.Design
    motion : isolator.motion.GroundMotion
        The motion analysed (after any scaling).
    adaptation : isolator.adapter.Adaptation
        System, dimensionless point and intensity measures.
    response : object
        The solver's response (:class:`isolator.solver.record.Response` for :data:`MODEL_1D`).
    model, model_reason : str
        The solver model used and why.
    record_class : isolator.metrics.Classification
    harmonic : isolator.solver.harmonic.HarmonicResponse or None
        The steady harmonic response at the equivalent point (None when not computed).
    harmonic_class : isolator.metrics.Classification or None
    engineering : dict
        :func:`isolator.adapter.engineering_quantities` (SI units in the keys).
    disagreements : list of str
        Where record and harmonic classifications differ.
    harmonic_seconds : float
        Time spent on the harmonic problem (0 when it came from the cache) [s].
    harmonic_map : HarmonicMap or None
        The design on the regime map, when asked for.
    """

    design: object
    motion: object
    adaptation: object
    response: object
    model: str
    model_reason: str
    record_class: object
    harmonic: object
    harmonic_class: object
    engineering: dict
    disagreements: list
    record_label: str = ""
    scaling_note: str = ""
    created_utc: str = ""
    harmonic_seconds: float = 0.0
    harmonic_map: HarmonicMap | None = None
    extra: dict = field(default_factory=dict)

    # ---- the schema ----------------------------------------------------------------

    def to_dict(self) -> dict:
        """The one schema of an analysis (see ``docs/schema.md``), JSON-safe.

        Returns
        -------
        dict
            ``schema_version``, ``model``, ``model_reason``; the point (``alpha``, ``k``,
            ``eta``, ``mu_s``, ``mu_k`` [-], ``a0_m``, ``omega_rad_s``); the response
            (``peak_displacement_m`` …, energies in J/kg); the classifications flat
            (``regime_record``, ``regime_harmonic``, …); ``engineering``; ``design``;
            ``system``; ``record``; ``map`` when computed; ``verdicts``; ``software``.
        """
        from isolator import __version__

        p = self.adaptation.point
        motion = self.motion
        out = self._flat()
        out["disagreements"] = list(self.disagreements)
        out["engineering"] = dict(self.engineering)
        out["design"] = self.design.as_dict()
        out["system"] = self.adaptation.dimensional_dict()
        out["record"] = record_dict(motion, self.record_label)
        out["record"].update(provenance=motion.provenance, processing=list(motion.processing),
                             scaling=self.scaling_note, intensity_measures=self.adaptation.intensity.as_dict())
        if self.harmonic_map is not None:
            out["map"] = self.harmonic_map.to_dict(p.alpha, p.k)
        out["verdicts"] = verdicts(self)
        out["checks"] = checks(self)
        out["software"] = {"name": "isolator", "version": __version__}
        out["created_utc"] = self.created_utc
        return json_safe(out)

    def _flat(self) -> dict:
        """The flat keys of the schema (identity, point, response, classifications), in schema order."""
        out: dict = {"schema_version": SCHEMA_VERSION, "model": self.model, "model_reason": self.model_reason}
        out.update(self.adaptation.point.as_dict())
        out["configuration"] = self.adaptation.system.configuration
        out.update(self.response.summary())
        rc, hc = self.record_class, self.harmonic_class
        for name in CLASSIFICATION_FIELDS:
            out[f"{name}_record"] = getattr(rc, name)
            out[f"{name}_harmonic"] = None if hc is None else getattr(hc, name)
        out["window_start_s"], out["window_end_s"] = (float(v) for v in rc.window_s)
        out["harmonic_steady"] = None if self.harmonic is None else bool(self.harmonic.steady)
        out["harmonic_status"] = HARMONIC_NOT_COMPUTED if self.harmonic is None else self.harmonic.status
        out["harmonic_seconds"] = self.harmonic_seconds
        out["n_disagreements"] = None if hc is None else len(self.disagreements)
        capacity = getattr(self.design, "displacement_capacity_m", None)
        out["displacement_capacity_m"] = capacity
        out["displacement_demand_ratio"] = None if capacity is None else self.response.peak_displacement_m / capacity
        return out

    def row(self) -> dict:
        """The batch's slice of :meth:`to_dict`: :data:`ROW_KEYS` and :data:`ROW_ENGINEERING_KEYS`, flat.

        Built from the same pieces as :meth:`to_dict` without its nested groups and sentences
        (a batch makes thousands of rows), through the same JSON-safe helper.
        """
        flat = self._flat()
        row = {key: flat[key] for key in ROW_KEYS}
        row.update({key: self.engineering[key] for key in ROW_ENGINEERING_KEYS})
        return json_safe(row)


def record_dict(motion, label: str) -> dict:
    """The ``record`` group of the schema that every output shares: label, component, units, sampling.

    Parameters
    ----------
    motion : isolator.motion.GroundMotion
        The motion analysed [m/s²].
    label : str
        How the user named the record [-].

    Returns
    -------
    dict
        ``label``, ``component``, ``units_source``, ``npts``, ``dt_s`` [s], ``duration_s`` [s].
    """
    return {"label": label, "component": motion.component, "units_source": motion.units_source,
            "npts": motion.npts, "dt_s": motion.dt_s, "duration_s": motion.duration_s}


def schema_row(full: dict, keys) -> dict:
    """A batch row from an analysis dict (:meth:`to_dict` of a pair analysis): ``keys`` and
    :data:`ROW_ENGINEERING_KEYS`, flat."""
    row = {key: full[key] for key in keys}
    row.update({key: full["engineering"][key] for key in ROW_ENGINEERING_KEYS})
    return row


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
    motion : isolator.motion.GroundMotion
        One horizontal component of ground acceleration [m/s²] (already scaled if asked).
    intensity : isolator.motion.IntensityMeasures, optional
        The motion's intensity measures if already computed (a batch computes them once
        per record for all its designs).
    window_s : tuple, optional
        Strong-motion window (D5–95) [s] if already computed; computed otherwise.
    harmonic : bool
        Also solve and classify the harmonic problem at the equivalent point (the
        harmonic keys are None and ``harmonic_status`` is :data:`HARMONIC_NOT_COMPUTED`
        without it).
    map_resolution : int, optional
        Also place the design on the regime map at this resolution (:func:`harmonic_map`).
    workers : int, optional
        Processes for the map.
    record_label : str
        How the record was named by the user [-].
    scaling_note : str
        A sentence on scaling, kept with the numbers [-].

    Returns
    -------
    Analysis

    A pair of components (:class:`~isolator.motion.MotionPair`) or a design with µ(v)
    needs the 2-D engine: the analysis is then a :class:`~isolator.pair_analysis.PairAnalysis`
    (same ``model``/``model_reason`` and response keys; no harmonic classification,
    which is a 1-D notion), and ``intensity``, ``window_s``, ``harmonic``,
    ``map_resolution`` do not apply.

    Raises
    ------
    isolator.solver.record.RecordInputError
        A motion the solver cannot take.
    """
    from isolator.adapter import adapt, engineering_quantities, motion_keywords
    from isolator.metrics import classify_record, compare
    from isolator.solver.models import Scene, select_model, simulate

    scene = Scene.of(motion, motion_keywords(design), design)
    one_component = not (scene.has_y or scene.has_z)  # the 1-D building raises on a pair, in analyse_pair
    if select_model(scene)[0] not in (MODEL_1D, MODEL_1D_BUILDING) or not one_component:
        from isolator.pair_analysis import analyse_pair

        return analyse_pair(design, motion, record_label=record_label, scaling_note=scaling_note)
    motion = getattr(motion, "x", motion)  # a MotionPair of one component is that component
    adaptation = adapt(design, motion, intensity)
    point = adaptation.point
    response = simulate(scene)
    record_class = classify_record(response, point, design, window_s=window_s)
    harmonic_response = harmonic_class = None
    harmonic_seconds = 0.0
    if harmonic:
        harmonic_response, harmonic_class, harmonic_seconds = _harmonic_at(point)
    disagreements = [] if harmonic_class is None else compare(record_class, harmonic_class)
    return Analysis(
        design=design, motion=motion, adaptation=adaptation, response=response, model=response.model,
        model_reason=response.model_reason,
        record_class=record_class, harmonic=harmonic_response, harmonic_class=harmonic_class,
        engineering=engineering_quantities(design, response), disagreements=disagreements,
        record_label=record_label, scaling_note=scaling_note,
        created_utc=_dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC"),
        harmonic_seconds=harmonic_seconds,
        harmonic_map=None if map_resolution is None else harmonic_map(point, map_resolution, workers),
    )


def checks(analysis: Analysis) -> list[dict]:
    """The review checks that apply to one record (:func:`isolator.review.record_checks.record_checks`):
    capacity, D/R, restoring force, transmitted/PGA, scale factor, usable band."""
    from isolator.review.record_checks import record_checks

    return record_checks(analysis.design, analysis.motion, analysis.engineering)


def verdicts(analysis: Analysis) -> list[str]:
    """Plain sentences on the analysis: regime, amplification, dominant force, residual displacement."""
    from isolator.metrics import REGIME_WORDS

    rc, hc = analysis.record_class, analysis.harmonic_class
    eng = analysis.engineering
    p = analysis.adaptation.point
    prediction = "not computed" if hc is None else f"{hc.regime} ({REGIME_WORDS[hc.regime]})"
    if rc.regime == "ST":
        out = [f"Regime under the record: ST - the isolator never slides (alpha = PGA/(mu_s g) = {p.alpha:.3g}"
               f"{' <= 1' if p.alpha <= 1 else ''}): the superstructure moves with the ground, not isolated; "
               f"harmonic prediction: {prediction}."]
    else:
        out = [f"Regime under the record: {rc.regime} ({REGIME_WORDS[rc.regime]}), slip-time ratio over D5-95 "
               f"zeta = {rc.zeta:.3f}; harmonic prediction: {prediction}."]
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
