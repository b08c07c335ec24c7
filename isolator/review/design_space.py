r"""Design search: every candidate of a design space reviewed exactly as ``isolator review`` reviews it.

A design file gives the isolator; each ``vary`` replaces one of its numbers by a range
(``radius_m=1.5:4.5:13``: 13 values from 1.5 to 4.5 inclusive, or a list ``radius_m=2,2.5,3``).
The candidates are the product of the ranges.  Each one is a complete design: when ``mu_kinetic``
varies and ``mu_static`` does not, every other friction coefficient of the file (µs, and µ_slow,
µ_fast, µ_upper, µ_lower when given) follows µk by its ratio to µk in the file.

Every candidate goes through :func:`isolator.review.run.run_review` — its own property bounds and
ELF values, its own period range, the suite scaled for that range, every pair at the lower,
upper and nominal friction, every check — with nothing approximated or interpolated between
candidates.  What is shared is only what is equal:

* the spectra of a record at a period are computed once per worker process (a memo keyed by the
  record's samples and the period; the oscillator at one period does not depend on the others, so a
  value from the memo is bit-identical to a fresh one);
* the analyses of candidates that differ only in a key no analysis reads (``displacement_capacity_m``)
  are run once: those candidates form one group on one worker, with one analysis cache in memory
  (keyed by the analysis inputs, :func:`isolator.review.worker.task_key`).

A candidate that cannot be reviewed (an invalid combination, no ELF period range, every analysis
failed) is a row with its reason.  Finished rows are kept in a store beside the outputs, keyed by
the candidate's inputs (design numbers, target, suite samples, code, scaling, parameters and the
version of the code): a rerun reviews only what is missing.

The recommended candidate of an objective is the best of the candidates that pass every check
(no check fails; ``not checked`` rows do not count against it), ties broken by the other
objectives and then by the order of the candidates.
"""

from __future__ import annotations

import functools
import hashlib
import itertools
import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from isolator.errors import ReviewError

#: numbers of a design file that ``vary`` may replace
VARY_KEYS = ("radius_m", "mu_kinetic", "mu_static", "displacement_capacity_m", "mass_kg", "stiffness_N_per_m",
             "damping_ratio", "damping_Ns_per_m", "mu_slow", "mu_fast", "rate_s_per_m", "lambda_max", "lambda_min",
             "mu_upper", "mu_lower", "lambda_ae_max", "lambda_ae_min", "lambda_test_max", "lambda_test_min",
             "lambda_spec_max", "lambda_spec_min")

#: friction coefficients that follow a varied µk by their ratio to µk in the design file
FRICTION_FOLLOWERS = ("mu_static", "mu_slow", "mu_fast", "mu_upper", "mu_lower")

#: keys that change no analysis, only the checks (candidates differing only in these share their analyses)
CHECK_ONLY_KEYS = ("displacement_capacity_m",)

#: objective → (column minimised, what it is)
OBJECTIVES = {
    "base_shear": ("base_shear_coefficient", "design base-shear coefficient V_b/W (response history, larger bound)"),
    "displacement": ("design_total_displacement_m", "design total displacement D_TM (torsion and ELF floor)"),
    "residual": ("residual_displacement_m", "suite residual displacement (larger bound)"),
}

#: largest number of candidates of one search (a bound on the loop; split larger searches)
MAX_CANDIDATES = 20_000

#: bump when the meaning of a stored row changes
STORE_VERSION = "design-1"

#: the columns of the table before the per-check statuses (``check_<id>``)
COLUMNS = ("candidate", "error", "passes", "first_failing_check", "n_failing_checks", "n_not_checked",
           "radius_m", "mu_kinetic", "mu_static", "displacement_capacity_m", "isolated_period_s",
           "design_displacement_m", "design_total_displacement_m", "base_shear_coefficient", "governing_bound",
           "base_shear_governing_bound", "elf_total_displacement_m", "superstructure_shear_over_W",
           "restoring_force_over_W", "restoring_force_limit_over_W", "restoring_force_margin",
           "residual_displacement_m", "period_range_lo_s", "period_range_hi_s", "scale_factor_min",
           "scale_factor_max", "paper_k", "paper_alpha", "paper_eta", "analyses_cached", "review_seconds",
           "spectra_seconds", "analyses_seconds", "key")


# ---- the design space ----------------------------------------------------------------------

def parse_vary(spec: str) -> tuple[str, list[float]]:
    """``KEY=START:STOP:COUNT`` (COUNT values, both ends included) or ``KEY=V1,V2,…`` → (key, values).

    Parameters
    ----------
    spec : str
        e.g. ``"radius_m=1.5:4.5:13"`` or ``"mu_kinetic=0.04,0.06"`` [-].

    Raises
    ------
    ReviewError
        Unknown key, unparsable or non-finite numbers, COUNT < 1, COUNT = 1 with START ≠ STOP, repeated values.
    """
    def fail(message: str):
        return ReviewError(f"{spec!r}: {message}", parameter="vary")

    if "=" not in spec:
        raise fail("expected KEY=START:STOP:COUNT or KEY=V1,V2,…, e.g. radius_m=1.5:4.5:13")
    key, _, text = (part.strip() for part in spec.partition("="))
    if key not in VARY_KEYS:
        import difflib

        close = difflib.get_close_matches(key, VARY_KEYS, n=1, cutoff=0.6)
        hint = f" (did you mean {close[0]!r}?)" if close else f" (one of: {', '.join(VARY_KEYS)})"
        raise fail(f"{key!r} is not a number of a design file that can vary{hint}")
    if ":" in text:
        parts = text.split(":")
        if len(parts) != 3:
            raise fail(f"expected {key}=START:STOP:COUNT")
        try:
            start, stop = float(parts[0]), float(parts[1])
        except ValueError:
            raise fail("START and STOP must be numbers") from None
        try:
            count = int(parts[2])
        except ValueError:
            raise fail(f"COUNT must be a whole number, got {parts[2]!r}") from None
        if not (math.isfinite(start) and math.isfinite(stop)):
            raise fail("START and STOP must be finite")
        if count < 1:
            raise fail(f"COUNT must be >= 1, got {count}")
        if count == 1 and start != stop:
            raise fail("COUNT = 1 needs START = STOP")
        if count > MAX_CANDIDATES:
            raise fail(f"COUNT = {count} exceeds {MAX_CANDIDATES} candidates")
        values = [float(v) for v in np.linspace(start, stop, count)]
        if len(set(values)) != len(values):
            raise fail("START = STOP with COUNT > 1 gives the same value twice")
        return key, values
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise fail("the list must hold numbers separated by commas") from None
    if not values or not all(math.isfinite(v) for v in values):
        raise fail("the values must be finite numbers")
    if len(set(values)) != len(values):
        raise fail("a value is repeated")
    return key, values


def candidate_mappings(base: dict, base_mu_kinetic: float, vary: list[tuple[str, list[float]]]) -> list[dict]:
    """The design mappings of the product of the ranges (first key slowest), in order.

    Parameters
    ----------
    base : dict
        The design file's content (its TOML table).
    base_mu_kinetic : float
        µk of the design file (µs when the file gives no µk) [-].
    vary : list of (key, values)
        The ranges, as :func:`parse_vary` returns them.

    Raises
    ------
    ReviewError
        A key varied twice, a key the design's form excludes (``radius_m`` of a spring design …),
        or more than :data:`MAX_CANDIDATES` candidates.
    """
    keys = [key for key, _ in vary]
    if not keys:
        raise ReviewError("nothing varies: give at least one range", parameter="vary")
    if len(set(keys)) != len(keys):
        twice = next(k for k in keys if keys.count(k) > 1)
        raise ReviewError(f"{twice!r} is varied twice", parameter="vary")
    exclusive = (("radius_m", "stiffness_N_per_m"), ("damping_ratio", "damping_Ns_per_m"))
    for a, b in exclusive:
        for key, other in ((a, b), (b, a)):
            if key in keys and other in base:
                raise ReviewError(f"{key!r} cannot vary: the design gives {other!r} (one or the other)",
                                        parameter="vary")
    n = math.prod(len(values) for _, values in vary)
    if n > MAX_CANDIDATES:
        raise ReviewError(f"{n} candidates exceed {MAX_CANDIDATES}: split the search", parameter="vary")
    out = []
    for combination in itertools.product(*(values for _, values in vary)):
        mapping = dict(base)
        chosen = dict(zip(keys, combination, strict=True))
        if "mu_kinetic" in chosen and base_mu_kinetic > 0:
            ratio = chosen["mu_kinetic"] / base_mu_kinetic
            for follower in FRICTION_FOLLOWERS:
                if follower in base and follower not in chosen:
                    mapping[follower] = base[follower] * ratio
        mapping.update(chosen)
        out.append(mapping)
    return out


@dataclass
class Candidate:
    """One point of the design space: its index, the varied values and the design mapping."""

    index: int
    values: dict  #: varied key → value
    mapping: dict  #: the complete design table
    key: str = ""  #: content key of the row (inputs and code version)
    group: str = ""  #: candidates of one group share every analysis


# ---- keys -------------------------------------------------------------------------------------

@functools.lru_cache(maxsize=1)
def code_version() -> str:
    """isolator's version and a digest of the review and 2-D engine sources: changed code misses the store."""
    from isolator import __version__

    root = Path(__file__).resolve().parents[1]
    digest = hashlib.sha256()
    for path in sorted([*(root / "review").rglob("*.py"), *(root / "solver").glob("planar*.py"), root / "design.py"]):
        digest.update(path.read_bytes())
    return f"{STORE_VERSION}+{__version__}+{digest.hexdigest()[:16]}"


def _digest(value) -> str:
    return hashlib.sha256(json.dumps(value, sort_keys=True, default=repr).encode()).hexdigest()[:32]


def search_context_key(target, suite, code: str, scaling: str, parameters: dict | None) -> str:
    """Key of everything a row depends on besides the design: target, suite samples, code, scaling, parameters."""
    # a pair's given scale factor and its "matched" flag change a review as its samples do
    return _digest([code_version(), target.as_dict(),
                    [(p.name, p.content_key(), getattr(p, "scale_factor", None), getattr(p, "matched", None))
                     for p in suite.pairs],
                    suite.failed, code, scaling, parameters or {}])


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
    by_id = {c["id"]: c for c in checks if "pair" not in c}  # the design-level rows (not per analysis)
    restoring = by_id.get("restoring_force") or by_id.get("restoring_capability") or {}
    r_value, r_limit = restoring.get("value"), restoring.get("limit")
    margin = (r_value / r_limit - 1.0) if (r_value is not None and r_limit) else None
    design = review.design
    nominal = review.analyses.get("nominal") or review.analyses.get("lower") or {}
    # the paper's dimensionless point of each pair (k = K A0/(M g), α = PGA/(µs g), η = c sqrt(A0/g)), as the
    # review's page 5 places them
    points = [(a["k"], a["alpha"], a["eta"]) for a in nominal.values()  # the analysis' point (isolator.analysis)
              if "error" not in a and a.get("k") is not None and math.isfinite(a["k"])]
    factors = list(r["scale_factors"].values())
    row = {
        **values,
        "error": None,
        "passes": not failing,
        "first_failing_check": failing[0] if failing else None,
        "n_failing_checks": len(failing),
        "n_not_checked": sum(c["status"] == "not checked" for c in checks),
        "radius_m": design.radius_m,
        "mu_kinetic": design.mu_kinetic,
        "mu_static": design.mu_static,
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
    }
    row.update({f"check_{cid}": s for cid, s in status.items()})
    return row


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
            design = Design.from_mapping(mapping, source=f"{context['source']} with " + ", ".join(
                f"{k}={v:.6g}" for k, v in values.items()))
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


def _iterate_groups(groups: list[list[dict]], context: dict, jobs: int, scheduler: str | None):
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


# ---- the store of finished rows ---------------------------------------------------------------

class RowStore:
    """One JSON file per finished candidate under ``directory``, named by the candidate's key (atomic writes)."""

    def __init__(self, directory):
        self.directory = Path(directory)

    def get(self, key: str):
        try:
            row = json.loads((self.directory / f"{key}.json").read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None
        return row if isinstance(row, dict) and row.get("key") == key else None

    def put(self, row: dict) -> None:
        from isolator.atomic import write_text_atomically
        from isolator.serialize import json_safe

        write_text_atomically(self.directory / f"{row['key']}.json", json.dumps(json_safe(row), allow_nan=False))


# ---- the search -------------------------------------------------------------------------------

@dataclass
class DesignSearch:
    """The reviewed candidates, the recommendation and what the chart shows."""

    design: object  #: the design file's Design
    vary: list  #: [(key, values)]
    objective: str
    rows: list  #: one dict per candidate, in candidate order
    code: str
    scaling: str
    parameters: dict
    target_name: str
    suite_source: str
    mappings: list = field(default_factory=list)  #: the design table of each candidate
    n_resumed: int = 0
    n_lost: int = 0
    timing: dict = field(default_factory=dict)

    @property
    def varied_keys(self) -> list[str]:
        return [key for key, _ in self.vary]

    def recommended(self, objective: str | None = None) -> dict | None:
        """The best candidate of ``objective`` among those that pass every check (None when none passes)."""
        return recommend(self.rows, objective or self.objective)

    def table(self):
        """The rows as a pandas DataFrame (columns: the varied keys, :data:`COLUMNS`, then ``check_<id>``)."""
        import pandas as pd

        table = pd.DataFrame(self.rows)
        checks = sorted({c for row in self.rows for c in row if c.startswith("check_")},
                        key=lambda c: next(i for i, row in enumerate(self.rows) if c in row))
        order = [*self.varied_keys, *(c for c in COLUMNS if c not in self.varied_keys), *checks]
        for column in order:
            if column not in table.columns:
                table[column] = None
        return table[order]

    def to_dict(self) -> dict:
        """The ``--json`` object: ``candidates``, ``objective``, ``recommended`` (and what the search was)."""
        from isolator.serialize import json_safe

        contract = [*self.varied_keys, "design_displacement_m", "design_total_displacement_m",
                    "base_shear_coefficient", "passes", "first_failing_check", "error"]

        def entry(row):
            if row is None:
                return None
            return {**{k: row.get(k) for k in contract},
                    **{k: v for k, v in row.items() if k not in contract and k not in ("key", "lost")}}

        return json_safe({
            "schema_version": 1,
            "design": self.design.as_dict(),
            "vary": {key: list(values) for key, values in self.vary},
            "code": self.code,
            "scaling": self.scaling,
            "parameters": self.parameters,
            "target": self.target_name,
            "suite": self.suite_source,
            "objective": self.objective,
            "objective_column": OBJECTIVES[self.objective][0],
            "n_candidates": len(self.rows),
            "n_passing": sum(bool(r.get("passes")) for r in self.rows),
            "n_errors": sum(r.get("error") is not None for r in self.rows),
            "n_resumed": self.n_resumed,
            "candidates": [entry(r) for r in self.rows],
            "recommended": entry(self.recommended()),
            "recommended_by_objective": {name: (None if (best := self.recommended(name)) is None
                                                else best["candidate"]) for name in OBJECTIVES},
            "timing_s": self.timing,
        })


def recommend(rows: list[dict], objective: str) -> dict | None:
    """The passing row with the smallest objective column (ties: the other objectives, then candidate order).

    Raises
    ------
    ReviewError
        An unknown objective.
    """
    if objective not in OBJECTIVES:
        raise ReviewError(f"objective {objective!r}: choose one of {', '.join(OBJECTIVES)}",
                                parameter="objective")
    order = [OBJECTIVES[objective][0], *(c for name, (c, _) in OBJECTIVES.items() if name != objective)]

    def value(row, column):
        v = row.get(column)
        return v if isinstance(v, (int, float)) and math.isfinite(v) else math.inf

    passing = [r for r in rows if r.get("passes") and r.get("error") is None
               and math.isfinite(value(r, order[0]))]
    if not passing:
        return None
    return min(passing, key=lambda r: (*(value(r, c) for c in order), r["candidate"]))


def search(design, target, suite, vary, *, objective: str = "base_shear", code: str = "asce7-22",
           scaling: str | None = "common", parameters: dict | None = None, jobs: int | None = None,
           scheduler: str | None = None, store_dir=None, progress=None, design_mapping: dict | None = None
           ) -> DesignSearch:
    """Review every candidate of a design space (see the module docstring).

    Parameters
    ----------
    design : isolator.design.Design or path-like
        The design file (or its Design: then ``design_mapping`` or the file at ``design.source`` is read).
    target : isolator.review.target.Target
    suite : isolator.review.suite.Suite
    vary : list of str or list of (str, list of float)
        The ranges (``"radius_m=1.5:4.5:13"`` or ``("radius_m", [1.5, 2.0])``).
    objective : {"base_shear", "displacement", "residual"}
        What the recommendation minimises (:data:`OBJECTIVES`).
    code, scaling, parameters
        As for :func:`isolator.review.run.run_review`; ``scaling=None`` chooses as ``isolator review`` does
        (``given`` when every pair of the suite gives its scale factor, else ``common``).
    jobs : int, optional
        Local worker processes (default: the idle cores).
    scheduler : str, optional
        Address of a Dask scheduler (instead of local processes).
    store_dir : path-like, optional
        Folder of the finished rows (resumable search); none by default.
    progress : callable, optional
        ``progress(done, total)`` after each group.
    design_mapping : dict, optional
        The design file's table (default: read from the file).

    Returns
    -------
    DesignSearch

    Raises
    ------
    ReviewError
        A bad range, key or objective (``parameter`` names it).
    """
    from isolator.design import Design, load_toml
    from isolator.errors import DesignError
    from isolator.review import parameters as P
    from isolator.review.run import CODES
    from isolator.review.scaling import SCALING_METHODS
    from isolator.review.worker import default_jobs

    clock = time.perf_counter()
    if objective not in OBJECTIVES:
        raise ReviewError(f"objective {objective!r}: choose one of {', '.join(OBJECTIVES)}",
                                parameter="objective")
    if code not in CODES:
        raise ReviewError(f"code must be one of {', '.join(CODES)}, got {code!r}", parameter="code")
    if scaling is None:  # as `isolator review` chooses: the suite's own factors when every pair gives one
        from isolator.review.scaling import default_scaling

        try:
            scaling = default_scaling(suite.names, suite.given_factors)
        except ValueError as err:
            raise ReviewError(f"{suite.source}: {err}", parameter="scaling") from None
    if scaling not in SCALING_METHODS:
        raise ReviewError(f"scaling must be one of {', '.join(SCALING_METHODS)}, got {scaling!r}",
                                parameter="scaling")
    P.resolve(code, parameters)  # a bad parameter is refused before any work
    if not isinstance(design, Design):
        path = Path(design)
        design_mapping = load_toml(path, "design file", DesignError)
        if isinstance(design_mapping, dict) and "name" not in design_mapping:
            design_mapping = {"name": path.stem, **design_mapping}
        design = Design.from_mapping(design_mapping, source=str(path))
    elif design_mapping is None:
        design_mapping = load_toml(design.source, "design file", DesignError)
        design_mapping.setdefault("name", design.name)
    ranges = [parse_vary(v) if isinstance(v, str) else (str(v[0]), [float(x) for x in v[1]]) for v in vary]
    for key, values in ranges:
        if key not in VARY_KEYS:
            raise ReviewError(f"{key!r} is not a number of a design file that can vary", parameter="vary")
        if not values or not all(math.isfinite(x) for x in values):
            raise ReviewError(f"{key!r}: the values must be finite numbers", parameter="vary")
    mappings = candidate_mappings(design_mapping, design.mu_kinetic, ranges)
    keys = [k for k, _ in ranges]
    context_key = search_context_key(target, suite, code, scaling, parameters)
    candidates = []
    for index, mapping in enumerate(mappings):
        values = {k: mapping[k] for k in keys}
        numbers = {k: v for k, v in mapping.items() if k != "name"}
        group = _digest({k: v for k, v in numbers.items() if k not in CHECK_ONLY_KEYS})
        mapping = {**mapping, "name": f"{design_mapping['name']} [" + ", ".join(
            f"{k}={v:.6g}" for k, v in values.items()) + "]"}
        candidates.append(Candidate(index, values, mapping, key=_digest([context_key, numbers]), group=group))

    store = RowStore(store_dir) if store_dir is not None else None
    rows: dict[int, dict] = {}
    if store is not None:
        for c in candidates:
            hit = store.get(c.key)
            if hit is not None:
                rows[c.index] = {**hit, "candidate": c.index}
    n_resumed = len(rows)
    groups: dict[str, list[dict]] = {}
    for c in candidates:
        if c.index not in rows:
            groups.setdefault(c.group, []).append({"index": c.index, "values": c.values, "mapping": c.mapping,
                                                   "key": c.key})
    context = {"target": target, "suite": suite, "code": code, "scaling": scaling, "parameters": parameters,
               "source": str(design.source)}
    todo = list(groups.values())
    n_lost = 0
    workers = max(1, min(int(jobs or default_jobs()), len(todo) or 1))
    if progress is not None:
        progress(len(rows), len(candidates))
    for finished in _iterate_groups(todo, context, workers, scheduler):
        for row in finished:
            lost = row.pop("lost", False)
            n_lost += bool(lost)
            rows[row["candidate"]] = row
            if store is not None and not lost:
                store.put(row)
        if progress is not None:
            progress(len(rows), len(candidates))
    ordered = [rows[c.index] for c in candidates]
    return DesignSearch(design=design, vary=ranges, objective=objective, rows=ordered, code=code, scaling=scaling,
                        parameters=dict(parameters or {}), target_name=getattr(target, "name", ""),
                        suite_source=str(suite.source), mappings=[c.mapping for c in candidates], n_resumed=n_resumed, n_lost=n_lost,
                        timing={"reviews": time.perf_counter() - clock})


# ---- what the chart shows ------------------------------------------------------------------------

def chart_data(result: DesignSearch) -> dict:
    """The numbers behind the design chart: the grid of the two main varied keys and each cell's state.

    With more than two varied keys, the chart is the slice through the recommended candidate (the
    first candidate when none passes): the other keys are held at its values.

    Returns
    -------
    dict
        ``x_key``, ``y_key`` (None with one varied key), ``x``, ``y`` (the values), ``fixed`` (the other
        keys' values), ``candidate`` (index per cell, shape (ny, nx)), ``design_total_displacement_m``,
        ``base_shear_coefficient`` (NaN where not analysed), ``passes`` (bool), ``state`` (per cell:
        ``"pass"``, the first failing check id, or ``"not analysed"``), ``recommended`` (x, y) or None,
        ``paper`` (per candidate of the slice: k, α, state) and ``objective``.
    """
    keys = result.varied_keys
    x_key, y_key = keys[0], (keys[1] if len(keys) > 1 else None)
    best = result.recommended()
    anchor = best if best is not None else result.rows[0]
    fixed = {k: anchor[k] for k in keys[2:]}
    xs = list(dict(result.vary)[x_key])
    ys = list(dict(result.vary)[y_key]) if y_key else [None]
    shape = (len(ys), len(xs))
    cell = np.full(shape, -1, dtype=int)
    d_tm = np.full(shape, np.nan)
    vb = np.full(shape, np.nan)
    passes = np.zeros(shape, dtype=bool)
    state = np.full(shape, "not analysed", dtype=object)
    paper = []
    for row in result.rows:
        if any(row[k] != v for k, v in fixed.items()):
            continue
        i = ys.index(row[y_key]) if y_key else 0
        j = xs.index(row[x_key])
        cell[i, j] = row["candidate"]
        if row.get("error") is None:
            d_tm[i, j] = _number(row.get("design_total_displacement_m"))
            vb[i, j] = _number(row.get("base_shear_coefficient"))
            passes[i, j] = bool(row["passes"])
            state[i, j] = "pass" if row["passes"] else row["first_failing_check"]
        if row.get("paper_k") is not None and row.get("paper_alpha") is not None:
            paper.append((row["paper_k"], row["paper_alpha"], state[i, j], row["candidate"]))
    rec = None
    if best is not None and all(best[k] == v for k, v in fixed.items()):
        rec = (best[x_key], best[y_key] if y_key else None)
    return {"x_key": x_key, "y_key": y_key, "x": np.array(xs, float), "y": np.array(ys, float) if y_key else None,
            "fixed": fixed, "candidate": cell, "design_total_displacement_m": d_tm, "base_shear_coefficient": vb,
            "passes": passes, "state": state, "recommended": rec, "recommended_candidate":
            None if best is None else best["candidate"], "paper": paper, "objective": result.objective}


def _number(value) -> float:
    return float(value) if isinstance(value, (int, float)) and value is not None else math.nan


def paper_context(data: dict, result: DesignSearch, resolution: int = 30, jobs: int | None = None) -> dict | None:
    """The paper's harmonic regime map behind the candidates' (k, α) points (Nicolas 2017, Figs. 5–7).

    The map is drawn at the recommended candidate's nominal friction (the first analysed candidate's when none
    passes) with η = 0 unless the design has a damper (then the median over the suite, as the review does).
    In the paper's variables the map depends only on η and µk/µs, so it is every candidate's map when these
    are equal (the usual case: µs follows µk by the design's ratio); ``shared`` says whether they are.
    """
    from isolator.maps import design_frame, regime_map

    analysed = [r for r in result.rows if r.get("error") is None and r.get("paper_k") is not None]
    if resolution <= 0 or not analysed:
        return None
    anchor = next((r for r in analysed if r["candidate"] == data["recommended_candidate"]), analysed[0])
    ratios = {round(r["mu_kinetic"] / r["mu_static"], 12) for r in analysed}
    design = result.design
    if design.damping_Ns_per_m > 0:
        eta_note = "η from the design's damper (median over the suite)"
        eta = float(anchor.get("paper_eta") or 0.0)
    else:
        eta_note, eta = "no damper: η = 0", 0.0
    frame = design_frame(max(r["paper_alpha"] for r in analysed), max(r["paper_k"] for r in analysed))
    rmap = regime_map(eta, anchor["mu_static"], anchor["mu_kinetic"], k_range=frame["k"],
                      alpha_range=frame["alpha"], n_k=resolution, n_alpha=resolution, workers=jobs)
    return {"map": rmap, "eta": eta, "mu_static": anchor["mu_static"], "mu_kinetic": anchor["mu_kinetic"],
            "shared": len(ratios) == 1 and design.damping_Ns_per_m == 0, "note": eta_note}


# ---- outputs -------------------------------------------------------------------------------------

def output_paths(pdf_path) -> dict:
    """Where a search writes: the chart PDF, the tables beside it, the recommended review, the row store."""
    pdf = Path(pdf_path)
    stem = pdf.with_suffix("")
    return {"chart": pdf, "csv": stem.with_suffix(".csv"), "parquet": stem.with_suffix(".parquet"),
            "json": stem.with_suffix(".json"), "recommended_pdf": Path(f"{stem}.recommended.pdf"),
            "recommended_toml": Path(f"{stem}.recommended.toml"),
            "recommended_json": Path(f"{stem}.recommended.json"), "store": pdf.parent / f".{pdf.stem}.design"}


def ranking_columns(result: DesignSearch) -> list[str]:
    """Columns of the chart's ranking page."""
    column = OBJECTIVES[result.objective][0]
    first = ["candidate", *result.varied_keys, column]
    rest = [c for c in ("design_total_displacement_m", "base_shear_coefficient", "restoring_force_margin",
                        "governing_bound") if c not in first]
    return [*first, *rest]


def write_outputs(result: DesignSearch, pdf_path, target, suite, *, command: str = "", jobs: int | None = None,
                  scheduler: str | None = None, paper_map_resolution: int = 30) -> dict:
    """Write the table (CSV, Parquet, JSON), the chart PDF and the recommended candidate's full review.

    Every file is written atomically.  The recommended candidate is reviewed again by
    :func:`~isolator.review.run.run_review` with the review command's extras (RotD50, the paper's map) and
    written by :func:`~isolator.report.review_pages.write_review_pdf`; its numbers are those of its row.
    When no candidate passes, a recommended review left by an earlier run is removed (it would mislead).

    Returns
    -------
    dict
        The search JSON (:meth:`DesignSearch.to_dict`) with ``outputs`` and ``timing_s`` completed.
    """
    from isolator.atomic import atomic_path, write_text_atomically
    from isolator.design import Design
    from isolator.report.design_chart import write_design_chart
    from isolator.report.review_pages import write_review_pdf
    from isolator.review.run import run_review
    from isolator.serialize import json_safe

    paths = output_paths(pdf_path)
    timing = dict(result.timing)
    start = time.perf_counter()
    table = result.table()
    with atomic_path(paths["csv"]) as tmp:
        table.to_csv(tmp, index=False)
    with atomic_path(paths["parquet"]) as tmp:
        _parquet_ready(table).to_parquet(tmp, index=False)
    timing["tables"] = time.perf_counter() - start

    start = time.perf_counter()
    data = chart_data(result)
    data["paper_map"] = paper_context(data, result, paper_map_resolution, jobs)
    timing["paper_map"] = time.perf_counter() - start
    start = time.perf_counter()
    best = result.recommended()
    column = OBJECTIVES[result.objective][0]
    lines = [("objective", f"{result.objective}: least {OBJECTIVES[result.objective][1]}"),
             ("candidates", f"{len(result.rows)} ({sum(bool(r.get('passes')) for r in result.rows)} pass, "
                            f"{sum(r.get('error') is not None for r in result.rows)} not analysed)"),
             ("code, scaling", f"{result.code}, {result.scaling}")]
    if best is None:
        lines.append(("recommended", "none: no candidate passes every check"))
    else:
        lines += [("recommended", ", ".join(f"{k} = {best[k]:.4g}" for k in result.varied_keys)),
                  (column, f"{best[column]:.4g}"),
                  ("D_M, D_TM", f"{best['design_displacement_m']:.4g} m, {best['design_total_displacement_m']:.4g} m"),
                  ("V_b/W", f"{best['base_shear_coefficient']:.4g} ({best['base_shear_governing_bound']} bound)")]
    failing = {}
    for r in result.rows:
        if r.get("first_failing_check"):
            failing[r["first_failing_check"]] = failing.get(r["first_failing_check"], 0) + 1
    lines += [(f"first fails: {k}", f"{n} candidates") for k, n in sorted(failing.items(), key=lambda kv: -kv[1])]
    if data["paper_map"] is not None:
        pm = data["paper_map"]
        lines.append(("paper's map", f"µs {pm['mu_static']:.3g}, µk {pm['mu_kinetic']:.3g}, {pm['note']}"
                      + ("; the same for every candidate" if pm["shared"] else "; at the recommended candidate")))
    ranked = sorted((r for r in result.rows if r.get("passes") and r.get("error") is None),
                    key=lambda r: (_number(r.get(column)), r["candidate"]))
    subtitle = f"{result.design.name} | {result.target_name} | {result.suite_source}"
    pages = write_design_chart(paths["chart"], data, {"subtitle": subtitle, "lines": lines}, ranked,
                               ranking_columns(result))
    timing["chart"] = time.perf_counter() - start

    start = time.perf_counter()
    review_out = None
    if best is not None:
        # the recommended design as a design file of its own: `isolator review --design` of it reproduces the review
        write_text_atomically(paths["recommended_toml"], design_toml(
            result.mappings[best["candidate"]],
            f"Recommended by `isolator design` ({result.objective}) from {result.design.source}: "
            + ", ".join(f"{k} = {best[k]!r}" for k in result.varied_keys)))
        review = run_review(Design.from_toml(paths["recommended_toml"]), target, suite, code=result.code,
                            scaling=result.scaling, jobs=jobs, scheduler=scheduler,
                            parameters=result.parameters, rotd50_points=12, paper_map_resolution=paper_map_resolution,
                            cache_dir=paths["store"] / "recommended")
        review_out = write_review_pdf(review, paths["recommended_pdf"], command=command)
    else:
        for stale in (paths["recommended_pdf"], paths["recommended_json"], paths["recommended_toml"]):
            if stale.is_file():
                stale.unlink()
    timing["recommended_review"] = time.perf_counter() - start

    result.timing = timing
    out = result.to_dict()
    out["outputs"] = {"chart": str(paths["chart"]), "chart_pages": pages, "csv": str(paths["csv"]),
                      "parquet": str(paths["parquet"]), "json": str(paths["json"]),
                      "recommended_pdf": str(paths["recommended_pdf"]) if review_out else None,
                      "recommended_json": str(paths["recommended_json"]) if review_out else None,
                      "recommended_design": str(paths["recommended_toml"]) if review_out else None,
                      "store": str(paths["store"])}
    out["command"] = command
    with atomic_path(paths["json"]) as tmp:
        tmp.write_text(json.dumps(json_safe(out), indent=2, allow_nan=False) + "\n", encoding="utf-8")
    return out


def design_toml(mapping: dict, comment: str = "") -> str:
    """A design table as TOML text: numbers written to round-trip exactly, sub-tables (``[plan]``,
    ``[superstructure]``) and arrays of tables (``[[superstructure.floor]]``, ``[[bearing_position]]``).

    Raises
    ------
    ReviewError
        A value TOML cannot hold (not a number, text, boolean, list or table; a non-finite number).
    """
    import re

    def key(k):
        return k if re.fullmatch(r"[A-Za-z0-9_-]+", k) else json.dumps(k, ensure_ascii=False)

    def value(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, int):
            return str(v)
        if isinstance(v, float) and math.isfinite(v):
            return repr(v)
        if isinstance(v, str):
            return json.dumps(v, ensure_ascii=False)  # a JSON string is a valid TOML basic string
        if isinstance(v, list) and not any(isinstance(x, dict) for x in v):
            return "[" + ", ".join(value(x) for x in v) + "]"
        raise ReviewError(f"design value {v!r} cannot be written as TOML")

    def is_tables(v):
        return isinstance(v, list) and v and all(isinstance(x, dict) for x in v)

    def emit(table: dict, prefix: str, lines: list) -> None:
        lines += [f"{key(k)} = {value(v)}" for k, v in table.items() if not isinstance(v, dict) and not is_tables(v)]
        for k, v in table.items():
            name = f"{prefix}.{key(k)}" if prefix else key(k)
            if isinstance(v, dict):
                lines += ["", f"[{name}]"]
                emit(v, name, lines)
            elif is_tables(v):
                for item in v:
                    lines += ["", f"[[{name}]]"]
                    emit(item, name, lines)

    lines = [f"# {line}" for line in comment.splitlines()]
    emit(mapping, "", lines)
    return "\n".join(lines) + "\n"


def _parquet_ready(table):
    """Object columns typed for Parquet (text, booleans or numbers; None stays missing)."""
    out = table.copy()
    for column in out.columns:
        if out[column].dtype != object:
            continue
        values = out[column].dropna()
        if len(values) and all(isinstance(v, bool) for v in values):
            out[column] = out[column].astype("boolean")
        elif len(values) and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
            out[column] = out[column].astype(float)
        else:
            out[column] = out[column].astype("string")
    return out


#: the public name (``isolator.design_search``)
design_search = search
