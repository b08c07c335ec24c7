"""run_review: a design over a scaled suite at its property bounds, checked clause by clause.

Order of work (each step a module of this package): property bounds (bounds) → ELF reference
values per bound (codes) → period range and grid → spectra of every pair (spectra) → scale
factors (scaling) → every pair × bound through the one analysis (worker:
:func:`isolator.analysis.analyse`, the model the scene needs; cached, in parallel) → design values
over the suite (mean of ≥ 7 else max) and checks (assess).  The :class:`Review` is built once,
complete; :meth:`Review.to_dict` is the JSON of every number the PDF shows.
"""

from __future__ import annotations

import datetime as _dt
import math
from dataclasses import dataclass, field

import numpy as np

from isolator.errors import ReviewError, analysis_owner, owned
from isolator.review import checks as C
from isolator.review import parameters as P
from isolator.review.bounds import friction_bounds
from isolator.review.codes import asce7_22, en15129
from isolator.review.scaling import SCALING_METHODS, period_grid, scale_factors, suite_mean
from isolator.review.spectra import pair_spectra, rotd50
from isolator.serialize import json_safe

CODES = ("asce7-22", "en15129")
#: Version of :meth:`Review.to_dict` (bump on any rename or change of meaning; docs/changelog.md).
SCHEMA_VERSION = 2
#: Which schema the review's JSON follows (an analysis' is ``"isolator.analysis"``, with its own version).
SCHEMA_NAME = "isolator.review"
PLOT_PERIODS_S = np.geomspace(0.05, 10.0, 90)
#: Errors of an analysis that say the engine cannot take the scene or finish it (a design it does not model, a
#: double/triple bearing's rim in the plane, a step guard): the review stops rather than leave the pair out of
#: every suite value (the pair that reaches a rim is the one the capacity rows need).
ENGINE_REFUSALS = ("InvalidSystemError:", "DesignError:", "SolverError:")


@dataclass
class Review:
    """Everything a review found (SI units; see :meth:`to_dict`)."""

    design: object
    target: object
    suite: object
    code: str
    scaling: str
    parameters: dict
    bounds: object
    elf: dict
    period_range_s: tuple
    grid_s: np.ndarray
    factors: dict
    spectra: dict  #: plot periods, per pair rotd100 / components, target, suite mean (scaled)
    suite_ratio: np.ndarray
    analyses: dict  #: bound → pair → result (:func:`isolator.review.worker.analyse_task`: an analysis row)
    design_values: dict
    checks: list
    notes: list = field(default_factory=list)
    timing: dict = field(default_factory=dict)
    created_utc: str = ""
    paper_map: dict | None = None  #: the paper's regime map and the pairs' equivalent points (context)
    trace: dict = field(default_factory=dict)  #: software, inputs {path: sha256}, run (the arguments)
    required_ratio: float | None = None  #: suite average / target required (110 % for a matched suite)
    parameter_sources: dict = field(default_factory=dict)  #: parameters the design fixes → how (17.5.4.2)
    structure: dict = field(default_factory=dict)  #: the superstructure's ELF inputs (W_s/W, T_fixed, R_I)

    # ---- JSON ------------------------------------------------------------------------------

    def to_dict(self) -> dict:
        """The review's JSON (the Contract keys of issue 11, and every number of the PDF)."""
        bounds = {}
        for bound in ("lower", "upper", "nominal"):
            if bound not in self.analyses:
                continue
            pairs = {name: {k: v for k, v in r.items() if k != "orbit_m"} for name, r in self.analyses[bound].items()}
            bounds[bound] = {"mu": self.bound_mu[bound], **self.surface_friction(bound), "pairs": pairs,
                             **self.design_values.get(bound, {})}
        elf = {b: {k: v for k, v in self.elf[b].items()} for b in self.elf}
        env = self.design_values["envelope"]
        return json_safe({
            "schema": SCHEMA_NAME,
            "schema_version": SCHEMA_VERSION,
            "created_utc": self.created_utc,
            "code": self.code,
            "scaling": self.scaling,
            "design": self.design.as_dict(),
            "target": self.target.as_dict(),
            "suite": {"source": self.suite.source, "pairs": [
                {"name": p.name, "files": p.files, "components": p.component_names, "dt_s": p.dt_s, "npts": p.npts,
                 "high_pass_hz": p.high_pass_hz, "processing": p.processing, "metadata": p.metadata,
                 "scale_factor_given": p.scale_factor, "matched": p.matched} for p in self.suite.pairs],
                "failed": self.suite.failed, "closest_motions": self.suite.closest},
            "parameters": P.table(self.code, self.parameters, self.parameter_sources),
            "property_bounds": self.bounds.as_dict(),
            "period_range_s": list(self.period_range_s),
            "period_grid": {"n": int(self.grid_s.size), "lo_s": float(self.grid_s[0]), "hi_s": float(self.grid_s[-1]),
                            "spacing": "log", "includes": "both ends and the T_M values inside the range",
                            "periods_s": self.grid_s.tolist(), "suite_ratio": self.suite_ratio.tolist()},
            "spectrum_basis": "RotD100" if self.code == "asce7-22" else "components (mean of both)",
            "spectrum_conventions": "5 % damping; exact first-order-hold recurrence; peaks of the continuous "
                                    "response, between samples included; no padding, no filtering",
            "scale_factors": dict(self.factors),
            "min_ratio_required": self.min_ratio_required,
            "suite_min_ratio": float(np.min(self.suite_ratio)),
            "suite_min_ratio_period_s": float(self.grid_s[int(np.argmin(self.suite_ratio))]),
            "suite_mean_ratio": float(np.mean(self.suite_ratio)),
            "elf": elf,
            "D_TM_m": self.design_values["elf_D_TM_m"],
            "torsion": self.design_values["torsion"],
            "bounds": bounds,
            "design_displacement_m": {"value": env["D_M_rha_m"], "rule": env["rule"], "n": env["n"],
                                      "governing_bound": env["D_M_bound"]},
            "design_total_displacement_m": env["D_TM"],
            "design_base_shear_coefficient": {"value": env["V_b_over_W"], "governing_bound": env["V_b_bound"]},
            "structure": {**self.structure, **self.design_values.get("structure", {})},
            "checks": self.checks,
            "check_counts": C.status_counts(self.checks),
            "spread": self.design_values.get("spread", {}),
            "notes": self.notes,
            "timing_s": self.timing,
            **self.trace,
        })

    @property
    def bound_mu(self) -> dict:
        return {"lower": self.bounds.mu_lower, "upper": self.bounds.mu_upper, "nominal": self.bounds.mu_nominal}

    def surface_friction(self, bound: str) -> dict:
        """A double or triple bearing's friction at a bound, surface by surface in file order (λ on every µ_i, as
        the bound's analyses and ELF ran: :meth:`isolator.design.Design.with_friction_factor`): ``lambda``,
        ``surface_mu`` (kinetic) and, with µ(v), ``surface_mu_slow`` / ``surface_mu_fast``; empty for one surface
        (``mu`` is then its own µ)."""
        if not asce7_22.is_multisurface(self.design):
            return {}
        factor = {"lower": self.bounds.lambda_min, "upper": self.bounds.lambda_max, "nominal": 1.0}[bound]
        surfaces = (self.design if factor == 1.0 else self.design.with_friction_factor(factor, f"{bound} bound")
                    ).bearing.surfaces
        out = {"lambda": factor, "surface_mu": [s.mu_kinetic for s in surfaces]}
        if any(s.mu_fast is not None for s in surfaces):
            out |= {"surface_mu_slow": [s.mu_slow for s in surfaces], "surface_mu_fast": [s.mu_fast for s in surfaces]}
        return out

    @property
    def min_ratio_required(self) -> float:
        if self.required_ratio is not None:
            return self.required_ratio
        return self.parameters["min_ratio"] if self.code == "asce7-22" else self.parameters["en_min_ratio"]


def elf_values(design, mu, target, code, params, t_fixed_s: float | None = None) -> dict:
    """The ELF values of one bound; with a superstructure also D'_M of Eq. 17.6-1 at its fixed-base period."""
    if code == "en15129":  # the effective period of the isolated system at its design displacement, η damping
        eta_min = params.get("eta_min", P.PARAMETERS["eta_min"].default)
        return asce7_22.elf_displacement(design, mu, target, form="SaM",
                                         reduction=lambda beta: en15129.damping_divisor(beta, eta_min))
    out = asce7_22.elf_displacement(design, mu, target, form=params.get("D_M_form", "SaM"),
                                    b_m_at_50=params.get("B_M_at_50pct", asce7_22.B_M_TABLE[-1][1]))
    if code == "asce7-22" and out["D_M_m"] > 0:
        out.update(asce7_22.superstructure_shear(out["V_b_over_W"], out["beta_M"], params))
    if t_fixed_s is not None:
        out["T_fixed_s"] = t_fixed_s
        out["D_M_prime_m"] = asce7_22.displacement_with_flexible_superstructure(out["D_M_m"], t_fixed_s,
                                                                                out["T_M_s"])
    return out


def structure_inputs(design) -> dict:
    """The superstructure's ELF inputs (ASCE 7-22 17.5.4.2, Eq. 17.6-1) of a design; empty for a rigid block.

    ``T_fixed_s`` is the shorter of the fixed-base fundamental periods along x and y
    (:meth:`isolator.superstructure.Superstructure.fixed_base_periods_s`): the larger D'_M, the stricter floor.
    """
    from isolator.superstructure import review_inputs

    found = review_inputs(design)
    if "T_fixed_s" not in found:
        return {}
    periods = found["T_fixed_s"]
    s = design.superstructure
    return {"n_floors": s.n_floors, "Ws_over_W": found["Ws_over_W"], "T_fixed_x_s": periods["x"],
            "T_fixed_y_s": periods["y"], "T_fixed_s": min(periods.values()),
            "response_modification_R": s.response_modification_R, "basis": found["basis"]}


def run_review(design, target, suite, *, code: str = "asce7-22", scaling: str = "common", jobs: int | None = None,
               scheduler: str | None = None, parameters: dict | None = None, cache_dir=None,
               nominal: bool = True, rotd50_points: int = 0, paper_map_resolution: int = 0,
               spectra_source=None, analysis_cache=None) -> Review:
    """Review a design over a suite scaled to a target, at its lower and upper property bounds.

    Parameters
    ----------
    design : isolator.design.Design
    target : isolator.review.target.Target
    suite : isolator.review.suite.Suite
    code : {"asce7-22", "en15129"}
    scaling : {"common", "fit"}
        How the scale factors are formed (:mod:`isolator.review.scaling`).
    jobs : int, optional
        Local worker processes (default: all cores).
    scheduler : str, optional
        Address of a Dask scheduler (instead of local processes).
    parameters : dict, optional
        Overrides of :data:`isolator.review.parameters.PARAMETERS`.
    cache_dir : path-like, optional
        Folder of the analysis cache (resumable reviews).
    nominal : bool
        Also analyse the nominal properties.
    rotd50_points : int
        Periods at which RotD50 is computed (informational; 0: none).
    paper_map_resolution : int
        Grid points per axis of the paper's harmonic regime map around the pairs' equivalent points
        (context only, cached on disk; 0: none).
    spectra_source : callable, optional
        ``(pair, periods_s) -> dict`` returning what :func:`~isolator.review.spectra.pair_spectra` returns for
        the pair at those periods (a design search shares one memo of spectra over its candidates).
    analysis_cache : object, optional
        An analysis cache with ``get(key)``/``put(key, result)`` used instead of the folder ``cache_dir``
        (a design search shares one in memory over the candidates of equal analyses).

    Returns
    -------
    Review

    Raises
    ------
    ReviewError
        An unknown code or scaling method, ``jobs`` that is not a whole number ≥ 1, a parameter outside
        its range, or every analysis failed.
    """
    import time

    from isolator.review.assess import assess
    from isolator.review.worker import Cache, default_jobs, run_tasks, task_key

    clock = time.perf_counter()
    timing = {}
    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1):
        raise ReviewError(f"jobs must be a whole number ≥ 1 of worker processes, got {jobs!r}")
    if code not in CODES:
        raise ReviewError(f"code must be one of {', '.join(CODES)}, got {code!r}")
    if scaling not in SCALING_METHODS:
        raise ReviewError(f"scaling must be one of {', '.join(SCALING_METHODS)}, got {scaling!r}")
    params = P.resolve(code, parameters)
    params, sources = P.from_design(code, params, design, parameters)
    structure = structure_inputs(design)
    notes = []
    bounds = friction_bounds(design, code=code, f_ae=params.get("f_ae", P.PARAMETERS["f_ae"].default))
    designs = {"lower": design.with_friction_factor(bounds.lambda_min, "lower bound"),
               "upper": design.with_friction_factor(bounds.lambda_max, "upper bound")}
    if nominal:
        designs["nominal"] = design
    if bounds.lambda_min == bounds.lambda_max == 1.0:
        notes.append("the design gives no property bounds: lower = upper = nominal")

    # ELF reference values per bound (17.5)
    # ELF at the kinetic friction; with µ(v), at µ_fast (the friction of seismic sliding speeds)
    elf = {b: elf_values(designs[b], designs[b].mu_fast if designs[b].velocity_dependent else designs[b].mu_kinetic,
                   target, code, params, structure.get("T_fixed_s")) for b in designs}
    if design.velocity_dependent:
        notes.append("velocity-dependent friction: the ELF values use µ_fast of each bound; the analyses µ(v)")
    for b in designs:
        notes.extend(f"ELF {b}: {n}" for n in elf[b]["notes"])

    # period range
    t_upper, t_lower = elf["upper"]["T_M_s"], elf["lower"]["T_M_s"]
    if not (math.isfinite(t_upper) and math.isfinite(t_lower)):
        t_upper = t_lower = design.isolated_period_s
        notes.append("T_M undefined (no ELF sliding): the range is taken around the pendulum period")
    if code == "asce7-22":
        lo, hi = params["range_lo_factor"] * t_upper, params["range_hi_factor"] * t_lower
        required = params["min_ratio"]
    else:
        lo, hi = params["en_range_lo_factor"] * t_upper, params["en_range_hi_factor"] * t_lower
        required = params["en_min_ratio"]
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
        raise ReviewError(f"no scaling period range: T_M upper {t_upper:.4g} s, lower {t_lower:.4g} s "
                          f"give {lo:.4g}–{hi:.4g} s")
    base, grid = period_grid(lo, hi, params["grid_points"], (t_upper, t_lower))
    fit_mask = np.isin(grid, base)

    # spectra of every pair on the grid (the scale factors need them before any analysis); those at the plot
    # periods and RotD50 are for the report: computed while the analyses run (each period is its own oscillator,
    # so splitting the periods changes no number)
    g = design.gravity_m_s2
    plot = np.unique(np.concatenate([PLOT_PERIODS_S, [lo, hi]]))

    def spectra_of(pair, periods):
        return (spectra_source(pair, periods) if spectra_source is not None
                else pair_spectra(pair.ax_m_s2, pair.ay_m_s2, pair.dt_s, periods))

    on_grid = []
    for pair in suite.pairs:
        s = spectra_of(pair, grid)
        on_grid.append(s["rotd100_m_s2"] / g if code == "asce7-22"
                       else np.vstack([s["psa_x_m_s2"], s["psa_y_m_s2"]]) / g)
    timing["spectra"] = time.perf_counter() - clock
    target_grid = target.sa_g(grid)
    weak = [p.name for p, s in zip(suite.pairs, on_grid, strict=False) if not np.all(np.asarray(s) > 0)]
    if weak:
        raise ReviewError(f"pair '{weak[0]}' has a zero spectrum in the period range: it cannot be scaled")
    factors, scaling_basis, required = _factors(suite, scaling, np.array(on_grid), target_grid, required, fit_mask,
                                                code, params, notes)
    ratio = suite_mean(np.array(on_grid), factors) / target_grid
    names = suite.names

    def report_spectra() -> dict:
        """The scaled spectra at the plot periods, and RotD50 (informational) [g]."""
        on_plot = [{k: v / g for k, v in spectra_of(pair, plot).items()} for pair in suite.pairs]
        key = "rotd100_m_s2" if code == "asce7-22" else None
        plot_pairs = {name: (s[key] if key else 0.5 * (s["psa_x_m_s2"] + s["psa_y_m_s2"])) * f
                      for name, s, f in zip(names, on_plot, factors, strict=False)}
        out = {"periods_s": plot, "target_g": _safe_target(target, plot), "pairs_scaled_g": plot_pairs,
               "suite_mean_scaled_g": np.mean(list(plot_pairs.values()), axis=0),
               "grid_s": grid, "target_grid_g": target_grid}
        if rotd50_points:
            t50 = np.geomspace(lo, hi, rotd50_points)
            out["rotd50"] = {"periods_s": t50, "pairs_scaled_g": {
                p.name: f * rotd50(p.ax_m_s2, p.ay_m_s2, p.dt_s, t50) / g
                for p, f in zip(suite.pairs, factors, strict=False)}}
        return out

    # analyses: every pair × bound (one run per distinct friction)
    tasks, index = {}, {}
    horizontal_only = bool(params.get("horizontal_only"))
    if horizontal_only and any(pair.az_m_s2 is not None for pair in suite.pairs):
        notes.append("horizontal_only: the suite's vertical components are not analysed")
    for b, d in designs.items():
        for pair, f in zip(suite.pairs, factors, strict=False):
            vertical = None if horizontal_only else pair.az_m_s2
            dropped = vertical is None and pair.az_m_s2 is not None  # a different analysis: a different key
            k = task_key(pair.content_key() + (":horizontal-only" if dropped else ""), f, d)
            index[(b, pair.name)] = k
            tasks.setdefault(k, {"ax": pair.ax_m_s2, "ay": pair.ay_m_s2, "az": vertical, "dt": pair.dt_s,
                                 "factor": float(f), "design": d})
    start = time.perf_counter()
    cache = analysis_cache if analysis_cache is not None else Cache(cache_dir)
    workers = jobs or default_jobs()
    if workers > 1 or scheduler:  # other processes analyse: this one draws up the report's spectra meanwhile
        from concurrent.futures import ThreadPoolExecutor

        with ThreadPoolExecutor(1, thread_name_prefix="isolator-review-analyses") as waiting:
            analysed = waiting.submit(run_tasks, tasks, jobs=workers, scheduler=scheduler, cache=cache)
            spectra_start = time.perf_counter()
            spectra = report_spectra()
            timing["spectra"] += time.perf_counter() - spectra_start
            results, n_cached = analysed.result()
        timing["analyses"] = time.perf_counter() - start  # wall time until the last analysis came back
    else:
        results, n_cached = run_tasks(tasks, jobs=workers, scheduler=scheduler, cache=cache)
        timing["analyses"] = time.perf_counter() - start
        spectra_start = time.perf_counter()
        spectra = report_spectra()
        timing["spectra"] += time.perf_counter() - spectra_start
    if isinstance(cache, Cache):  # entries found damaged or edited are said (an in-memory cache has none)
        notes.extend(filter(None, [cache.note()]))
    timing["analyses_cached"] = n_cached
    timing["analyses_total"] = len(tasks)
    analyses = {b: {name: _for_design(results[index[(b, name)]], designs[b], f)
                    for name, f in zip(names, factors, strict=False)} for b in designs}
    failed = sorted({name for b in analyses for name, r in analyses[b].items() if "error" in r})
    refused = [(b, name, r["error"]) for b in analyses for name, r in analyses[b].items()
               if r.get("error", "").startswith(ENGINE_REFUSALS)]
    if refused:  # the engine cannot take this design under the suite's motions: never drop floors or surfaces
        b, name, error = refused[0]
        pair = next(p for p in suite.pairs if p.name == name)
        vertical = pair.az_m_s2 is not None and not horizontal_only
        files = [pair.files[k] for k in ("x", "y", "z") if k in pair.files and (k != "z" or vertical)]
        message = error.split(": ", 1)[-1]  # the row's error: "SolverError: what and when"
        raise ReviewError(owned(f"the engine refuses {analysis_owner(files, design.source)} (pair '{name}', {b} "
                                "bound)", message, design.source)
                          + ("; the pair has a vertical component (review parameter horizontal_only = true analyses "
                             "the horizontal components only)" if vertical else ""))
    if len(failed) == len(names):
        first = next(r["error"] for b in analyses for r in analyses[b].values() if "error" in r)
        raise ReviewError(f"every analysis failed ({first})")
    for name in failed:
        notes.append(f"analysis of pair '{name}' failed: "
                     + next(analyses[b][name]["error"] for b in analyses if "error" in analyses[b][name]))
    for b in analyses:  # a result the solver itself flagged (chatter guard, unfinished interval …) is said, not hidden
        notes.extend(f"analysis of pair '{name}' ({b} bound) is used, but its solver says: {r['solver_status']}"
                     for name, r in analyses[b].items() if "error" not in r and r.get("solver_status", "ok") != "ok")

    rigid_block = paper_map_applies(design)
    paper_map = (_paper_map(designs, analyses, paper_map_resolution, jobs) if paper_map_resolution and rigid_block
                 else None)
    if paper_map_resolution and not rigid_block:
        notes.append("the paper's harmonic regime map (Appendix A) is that of a rigid block on one surface: not drawn "
                     "for a building or a multi-surface bearing")
    from isolator.review.trace import input_hashes, software

    trace = {"software": software(), "inputs": input_hashes(design, target, suite),
             "run": {"suite_arguments": list(suite.arguments), **suite.options, "nominal": nominal,
                     "parameter_overrides": dict(parameters or {}), "scaling_basis": scaling_basis}}
    basis = dict(design=design, target=target, suite=suite, code=code, scaling=scaling, parameters=params,
                 bounds=bounds, elf=elf, period_range_s=(float(lo), float(hi)), grid_s=grid,
                 factors=dict(zip(names, map(float, factors), strict=False)), spectra=spectra, suite_ratio=ratio,
                 analyses=analyses, notes=notes, timing=timing, paper_map=paper_map, trace=trace,
                 required_ratio=required, parameter_sources=sources, structure=structure, created_utc=_dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC"))
    assessment = assess(basis, designs, min_ratio_required=required)
    timing["total"] = time.perf_counter() - clock
    return Review(**{**basis, **assessment})


def _factors(suite, scaling, spectra, target_grid, required, fit_mask, code, params, notes):
    """The scale factors as analysed, how they were formed, and the ratio the suite must reach.

    ``given`` (and any spectrally matched suite) uses the suite's factors unchanged (1 where a matched
    pair gives none); ``common`` / ``fit`` compute them (:func:`isolator.review.scaling.scale_factors`).
    """
    from isolator.review.scaling import given_factors

    names = suite.names
    if suite.matched:
        if code == "asce7-22":
            required = params["spectral_matching_min"]
        given = [1.0 if f is None else f for f in suite.given_factors]
        if scaling != "given":
            notes.append(f"spectrally matched suite: the records are not rescaled (scaling '{scaling}' not applied)")
        return np.asarray(given, dtype=np.float64), "matched", required
    if scaling == "given":
        try:
            return given_factors(names, suite.given_factors), "given", required
        except ValueError as err:  # it named no file (h203): the suite's own words, as its other refusals
            raise ReviewError(f"suite {suite.source}: {err}") from None
    if any(f is not None for f in suite.given_factors):
        notes.append(f"the suite's scale_factor values are not used (scaling '{scaling}'); scaling 'given' checks them")
    return (scale_factors(spectra, target_grid, method=scaling, min_ratio=required, fit_mask=fit_mask), scaling,
            required)


def _for_design(result: dict, design, factor: float) -> dict:
    """One pair's result for a design, with its scale factor: an analysis is shared by designs that differ only in
    what does not change it (the displacement capacity, :func:`isolator.review.worker.design_key`), so the
    demand on the capacity is this design's."""
    out = dict(result, scale_factor=float(factor))
    if "error" not in out:
        capacity = design.displacement_capacity_m
        out["displacement_capacity_m"] = capacity
        out["displacement_demand_ratio"] = None if capacity is None else out["peak_displacement_m"] / capacity
    return out


def _safe_target(target, periods):
    """The target at the plot periods, NaN outside a tabulated target's range."""
    if target.kind != "table":
        return target.sa_g(periods)
    inside = (periods >= target.periods_s[0]) & (periods <= target.periods_s[-1])
    out = np.full(periods.size, np.nan)
    out[inside] = target.sa_g(periods[inside])
    return out


def paper_map_applies(design) -> bool:
    """The paper's harmonic regime map applies: a rigid block on one surface (no superstructure, no double or
    triple bearing); the review's Appendix A and the design search's chart draw it only then."""
    return design.superstructure is None and not asce7_22.is_multisurface(design)


def _paper_map(designs: dict, analyses: dict, resolution: int, jobs) -> dict | None:
    """The paper's harmonic regime map (Nicolas 2017, Figs. 5–7) at the nominal friction, with each pair's
    equivalent point (k, α) = (K A0/(M g), PGA/(µs g)), A0 = PGV²/PGA of the scaled resultant motion, and its
    peak displacement / A0 (the analysis' ``k``, ``alpha``, ``eta``, ``peak_displacement_over_a0``)."""
    from isolator.maps import design_frame, regime_map

    bound = "nominal" if "nominal" in analyses else "lower"
    d = designs[bound]
    ok = {name: r for name, r in analyses[bound].items() if "error" not in r}
    points = {name: (r["k"], r["alpha"], r["peak_displacement_over_a0"]) for name, r in ok.items()}
    if not points:
        return None
    eta = float(np.median([r["eta"] for r in ok.values()]))
    frame = design_frame(max(p[1] for p in points.values()), max(p[0] for p in points.values()))
    rmap = regime_map(eta, d.mu_static, d.mu_kinetic, k_range=frame["k"], alpha_range=frame["alpha"],
                      n_k=resolution, n_alpha=resolution, workers=jobs)
    return {"map": rmap, "bound": bound, "eta": eta, "points": points}
