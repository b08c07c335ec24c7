"""The reviews of ``isolator design``'s candidates: one group per worker, local processes or Dask.

This module holds what is shared between candidates because it is equal (:class:`SpectraMemo`, the 5 %
spectra of each pair per period computed once per process; :class:`MemoryCache`, the analyses of one
group), the table row of a reviewed candidate (:func:`candidate_row`, :func:`check_statuses`) or of one
that could not be reviewed (:func:`error_row`), the review of one group (:func:`review_group`) and the
iteration over the groups in this process, on local worker processes or on a Dask cluster
(:func:`iterate_groups`).  See :mod:`isolator.review.design_space` for what is shared and why.
"""

from __future__ import annotations

import math
import time

import numpy as np

from isolator.errors import ReviewError
from isolator.review.assess import incomplete_analyses

# ---- shared spectra and analyses --------------------------------------------------------------

class SpectraMemo:
    """The 5 % spectra of each pair per period, each computed once (see the module docstring).

    Called as ``memo(pair, periods_s)`` it returns what :func:`isolator.review.spectra.pair_spectra` returns;
    only the periods it has not seen are computed.  :meth:`forget` drops all but the ``keep`` periods.
    """

    def __init__(self, keep_s=()):
        self.keep = {float(t) for t in keep_s}
        self.values: dict = {}  # (pair key, period) → (psa_x, psa_y, rotd100) [m/s²]
        self.pair_keys: dict = {}  # id(pair) → (pair, content key): the pair is held, so its id stays its own
        self.computed = 0
        self.seconds = 0.0

    def _pair_key(self, pair) -> str:
        held = self.pair_keys.get(id(pair))
        if held is None or held[0] is not pair:
            held = self.pair_keys[id(pair)] = (pair, pair.content_key())
        return held[1]

    def __call__(self, pair, periods_s) -> dict:
        from isolator.review.spectra import pair_spectra

        start = time.perf_counter()
        key = self._pair_key(pair)
        periods = np.atleast_1d(np.asarray(periods_s, dtype=np.float64))
        missing = np.array(sorted({float(t) for t in periods if (key, float(t)) not in self.values}))
        if missing.size:
            fresh = pair_spectra(pair.ax_m_s2, pair.ay_m_s2, pair.dt_s, missing)
            for i, t in enumerate(missing):
                self.values[(key, float(t))] = (fresh["psa_x_m_s2"][i], fresh["psa_y_m_s2"][i],
                                                fresh["rotd100_m_s2"][i])
            self.computed += missing.size
        rows = np.array([self.values[(key, float(t))] for t in periods]).reshape(periods.size, 3)
        self.seconds += time.perf_counter() - start
        return {"psa_x_m_s2": rows[:, 0].copy(), "psa_y_m_s2": rows[:, 1].copy(), "rotd100_m_s2": rows[:, 2].copy()}

    def forget(self) -> None:
        """Keep only the periods of :attr:`keep` (the plot periods every review uses)."""
        self.values = {k: v for k, v in self.values.items() if k[1] in self.keep}


class MemoryCache:
    """An analysis cache in memory (``get``/``put`` of :class:`isolator.review.worker.Cache`)."""

    def __init__(self):
        self.results: dict = {}

    def get(self, key: str):
        return self.results.get(key)

    def put(self, key: str, result: dict) -> None:
        if "error" not in result:
            self.results[key] = result


# ---- one candidate ------------------------------------------------------------------------------

def candidate_row(review, values: dict) -> dict:
    """The table row of a candidate from its review (every number as the review's JSON gives it).

    Parameters
    ----------
    review : isolator.review.run.Review
    values : dict
        The varied keys and their values.
    """
    r = review.to_dict()
    checks = r["checks"]
    status = check_statuses(checks)
    failing = [c["id"] for c in checks if c["status"] == "fail"]
    # a review over part of the suite (an analysis failed or its solver flagged it) has no failing row where its
    # rows would pass — they are 'not checked' (assess.no_pass_on_part) — and it 'passed' and could be recommended
    incomplete = incomplete_analyses(review.analyses)
    by_id = {c["id"]: c for c in checks if "pair" not in c}  # the design-level rows (not per analysis)
    restoring = by_id.get("restoring_force") or by_id.get("restoring_capability") or {}
    r_value, r_limit = restoring.get("value"), restoring.get("limit")
    margin = (r_value / r_limit - 1.0) if (r_value is not None and r_limit) else None
    design = review.design
    nominal = review.analyses.get("nominal") or review.analyses.get("lower") or {}
    # the paper's dimensionless point of each pair (k = K A0/(M g), α = PGA/(µs g), η = c sqrt(A0/g)), as the
    # review's page 5 places them; a double or triple's on the backbone regime each motion reached (k = A0/R,
    # α = PGA/(µ g) of that regime's line): a median is taken over one regime only, never across regimes
    points = [(a["k"], a["alpha"], a["eta"]) for a in nominal.values()  # the analysis' point (isolator.analysis)
              if "error" not in a and a.get("k") is not None and math.isfinite(a["k"])]
    on = [a.get("point_regime") for a in nominal.values()
          if "error" not in a and a.get("k") is not None and math.isfinite(a["k"])]
    regime, points = paper_regime(on, points)
    factors = list(r["scale_factors"].values())
    row = {
        **values,
        "error": None,
        "passes": not failing and not incomplete,
        "first_failing_check": failing[0] if failing else ("incomplete_analyses" if incomplete else None),
        "n_failing_checks": len(failing),
        "n_not_checked": sum(c["status"] == "not checked" for c in checks),
        **design_columns(design),
        "displacement_capacity_m": design.displacement_capacity_m,
        "isolated_period_s": design.isolated_period_s,
        "design_displacement_m": r["design_displacement_m"]["value"],
        "design_total_displacement_m": r["design_total_displacement_m"]["value"],
        "base_shear_coefficient": r["design_base_shear_coefficient"]["value"],
        "governing_bound": r["design_displacement_m"]["governing_bound"],
        "base_shear_governing_bound": r["design_base_shear_coefficient"]["governing_bound"],
        "elf_total_displacement_m": r["D_TM_m"],
        "superstructure_shear_over_W": (by_id.get("superstructure_shear") or {}).get("value"),
        "restoring_force_over_W": r_value,
        "restoring_force_limit_over_W": r_limit,
        "restoring_force_margin": margin,
        "residual_displacement_m": (by_id.get("residual_displacement") or {}).get("value"),
        "period_range_lo_s": r["period_range_s"][0],
        "period_range_hi_s": r["period_range_s"][1],
        "scale_factor_min": min(factors),
        "scale_factor_max": max(factors),
        "paper_k": float(np.median([p[0] for p in points])) if points else None,
        "paper_alpha": float(np.median([p[1] for p in points])) if points else None,
        "paper_eta": float(np.median([p[2] for p in points])) if points else None,
        "paper_regime": regime,
    }
    row.update({f"check_{cid}": s for cid, s in status.items()})
    return row


def paper_regime(regimes: list, points: list) -> tuple[str | None, list]:
    """The regime the candidate's paper point stands on, and the points whose median is taken.

    ``regimes``: each pair's ``point_regime`` (None for one surface).  One surface: (None, every point).  A double or
    triple whose motions all reached one regime: (that regime, every point).  Motions on different regimes: their
    points are on different lines (k = A0/R, α = PGA/(µ g) with each line's R and µ), so no median means anything:
    ("mixed: 1 ×3, 1+2 ×5", []), and the columns are empty.
    """
    named = [name for name in regimes if name]
    if not named:
        return None, points
    counts = {name: named.count(name) for name in dict.fromkeys(named)}
    if len(counts) == 1:
        return named[0], points
    return "mixed: " + ", ".join(f"{name} ×{n}" for name, n in counts.items()), []


def design_columns(design) -> dict:
    """The candidate's radius and friction as the engineer gave them.

    A single surface: ``radius_m``, ``mu_kinetic``, ``mu_static``.  A double or triple pendulum has no one radius or
    µ: its ``Design`` holds the equivalent single pendulum of its last sliding regime (:func:`isolator.bearing.
    equivalent_single`), which the table showed as ``radius_m`` and ``mu_kinetic`` (session 20: "R 4.2 m, µ 0.08"
    for the example triple, whose surfaces are 2.1/0.3/0.3/2.1 m).  Its row gives the surfaces
    (``bearing_surfaces``) and the equivalent values under their own names (:data:`BEARING_COLUMNS`), the single
    surface's columns empty."""
    bearing = getattr(design, "bearing", None)
    if bearing is None or bearing.is_simple:
        return {"radius_m": design.radius_m, "mu_kinetic": design.mu_kinetic, "mu_static": design.mu_static}
    return {"radius_m": None, "mu_kinetic": None, "mu_static": None,
            "bearing_surfaces": surfaces_text(bearing),
            "equivalent_radius_m": design.radius_m, "equivalent_mu": design.mu_kinetic}


#: The columns of a double's or triple's row (:func:`design_columns`), in the table after ``mu_static``.
BEARING_COLUMNS = ("bearing_surfaces", "equivalent_radius_m", "equivalent_mu")


def surfaces_text(bearing) -> str:
    """``"triple: R 2.1/0.3/0.3/2.1 m, mu 0.06/0.02/0.02/0.1, d* 0.8/0.05/0.05/0.8 m"`` (surface by surface, as
    the design file gives them; µ(v) surfaces as ``mu_slow-mu_fast``; ``d*`` only when the surfaces have rims)."""
    def mu(surface) -> str:
        if getattr(surface, "rate_s_per_m", None) is not None:
            return f"{surface.mu_slow:g}-{surface.mu_fast:g}"
        return f"{surface.mu_kinetic:g}"

    surfaces = bearing.surfaces
    text = (f"{bearing.kind}: R {'/'.join(f'{s.radius_m:g}' for s in surfaces)} m, "
            f"mu {'/'.join(mu(s) for s in surfaces)}")
    capacities = [s.displacement_capacity_m for s in surfaces]
    if all(c is not None for c in capacities):
        text += f", d* {'/'.join(f'{c:g}' for c in capacities)} m"
    return text


def check_statuses(checks: list) -> dict:
    """One status per check id: ``fail`` if any of its rows fails (a check may have a row per analysis, e.g.
    ``record_capacity``), else ``pass`` if any passes, else ``not checked``."""
    out: dict = {}
    for c in checks:
        previous = out.get(c["id"])
        if previous is None or c["status"] == "fail" or (c["status"] == "pass" and previous == "not checked"):
            out[c["id"]] = c["status"]
    return out


def error_row(values: dict, mapping: dict, reason: str) -> dict:
    """The row of a candidate that could not be reviewed."""
    return {**values, "error": reason, "passes": False, "first_failing_check": None,
            **{k: mapping.get(k) for k in ("radius_m", "mu_kinetic", "mu_static", "displacement_capacity_m")
               if k not in values}}



def candidate_source(source: str, values: dict) -> str:
    """A candidate's source in its messages: the file and the numbers that replaced the file's."""
    return f"{source} with " + ", ".join(f"{k}={v:.6g}" for k, v in values.items())

def review_group(context: dict, group: list[dict], memo: SpectraMemo | None = None) -> list[dict]:
    """Review the candidates of one group (one worker; they share one analysis cache).

    Parameters
    ----------
    context : dict
        ``target``, ``suite``, ``code``, ``scaling``, ``parameters``, ``source`` (the design file's name).
    group : list of dict
        ``{"index", "values", "mapping", "key"}`` per candidate.
    memo : SpectraMemo, optional
        The spectra memo (default: this process's).

    Returns
    -------
    list of dict
        One row per candidate (with ``candidate`` and ``key``).
    """
    from isolator.design import Design
    from isolator.errors import DesignError
    from isolator.review.run import PLOT_PERIODS_S, run_review

    memo = memo if memo is not None else _process_memo(PLOT_PERIODS_S)
    cache = MemoryCache()
    rows = []
    for item in group:
        start, spectra_before = time.perf_counter(), memo.seconds
        values, mapping = item["values"], item["mapping"]
        analyses_s = 0.0
        try:
            # the candidate is not the file: its source says which numbers replaced the file's
            design = Design.from_mapping(mapping, source=candidate_source(context["source"], values))
            review = run_review(design, context["target"], context["suite"], code=context["code"],
                                scaling=context["scaling"], jobs=1, parameters=context["parameters"],
                                spectra_source=memo, analysis_cache=cache)
            row = candidate_row(review, values)
            analyses_s = review.timing.get("analyses", 0.0)
            row["analyses_cached"] = review.timing.get("analyses_cached", 0)
        except (DesignError, ReviewError) as err:
            row = error_row(values, mapping, " ".join(str(err).split()))
        except (ValueError, ArithmeticError) as err:  # a numerical failure of one candidate is its row, not a crash
            row = error_row(values, mapping, f"{type(err).__name__}: {' '.join(str(err).split())}")
        row.update(candidate=item["index"], key=item["key"], review_seconds=time.perf_counter() - start,
                   spectra_seconds=memo.seconds - spectra_before, analyses_seconds=analyses_s)
        rows.append(row)
    memo.forget()
    return rows


_MEMO: SpectraMemo | None = None


def _process_memo(keep_s) -> SpectraMemo:
    """This process's spectra memo (each worker process keeps its own)."""
    global _MEMO
    if _MEMO is None:
        _MEMO = SpectraMemo(keep_s)
    return _MEMO


#: the context of a local search, inherited by forked workers (not pickled for each group)
_LOCAL_CONTEXT: dict = {}


def _review_local_group(group: list[dict]) -> list[dict]:
    return review_group(_LOCAL_CONTEXT, group)


def _review_shipped_group(task: dict) -> list[dict]:
    return review_group(task["context"], task["group"])


def iterate_groups(groups: list[list[dict]], context: dict, jobs: int, scheduler: str | None):
    """Yield the rows of each group as groups finish (in this process, on local processes, or on Dask)."""
    global _LOCAL_CONTEXT
    if scheduler:
        yield from _iterate_dask(groups, context, scheduler)
        return
    if jobs <= 1 or len(groups) <= 1:
        for group in groups:
            yield review_group(context, group)
        return
    from concurrent.futures import as_completed

    from isolator.parallel import process_pool
    from isolator.review.worker import warm_up

    warm_up()  # the compiled engines load once, before the fork
    _process_memo(_plot_periods())
    _LOCAL_CONTEXT = context
    try:
        with process_pool(jobs) as pool:
            futures = {pool.submit(_review_local_group, group): group for group in groups}
            for future in as_completed(futures):
                try:
                    yield future.result()
                except Exception as err:  # noqa: BLE001 - a lost worker: its rows are not stored, a rerun retries
                    yield [_lost_row(item, err) for item in futures[future]]
    finally:
        _LOCAL_CONTEXT = {}


def _iterate_dask(groups: list[list[dict]], context: dict, address: str):
    """Yield the rows of each group from a Dask cluster (the context is sent once, scattered)."""
    from isolator.batch.executors import check_scheduler

    try:
        from distributed import Client, as_completed
    except ImportError as err:  # pragma: no cover - dask is a dependency
        raise ReviewError(f"scheduler {address}: dask.distributed is not installed ({err})",
                                parameter="scheduler") from None
    try:
        check_scheduler(address)
        security = None
        if address.startswith("tls://"):
            from distributed.security import Security

            security = Security()
        client = Client(address, timeout=10, security=security)
    except (OSError, TimeoutError, ValueError) as err:
        raise ReviewError(f"scheduler {address}: cannot connect ({' '.join(str(err).split())})",
                                parameter="scheduler") from None
    try:
        shipped = client.scatter(context, broadcast=True)
        futures = {client.submit(_review_shipped_group, {"context": shipped, "group": g}, pure=False): g
                   for g in groups}
        for future in as_completed(list(futures)):
            try:
                yield future.result()
            except Exception as err:  # noqa: BLE001 - a lost worker: a rerun retries its rows
                yield [_lost_row(item, err) for item in futures[future]]
    finally:
        client.close()


def _lost_row(item: dict, err: Exception) -> dict:
    row = error_row(item["values"], item["mapping"],
                    f"worker lost ({type(err).__name__}: {' '.join(str(err).split())})")
    row.update(candidate=item["index"], key=item["key"], lost=True)
    return row


def _plot_periods():
    from isolator.review.run import PLOT_PERIODS_S

    return PLOT_PERIODS_S
