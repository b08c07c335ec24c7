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
* the analyses of candidates that differ only in a key no analysis reads (:data:`CHECK_ONLY_KEYS`; none
  since the rim: the displacement capacity changes the analysis of a pendulum that reaches it) are run once: those candidates form one group on one worker, with one analysis cache in memory
  (keyed by the analysis inputs, :func:`isolator.review.worker.task_key`).

A candidate that cannot be reviewed (an invalid combination, no ELF period range, every analysis
failed) is a row with its reason.  Finished rows are kept in a store beside the outputs, keyed by
the candidate's inputs (design numbers, target, suite samples, code, scaling, parameters and the
version of the code): a rerun reviews only what is missing.

The recommended candidate of an objective is the best of the candidates that pass every check
(no check fails; ``not checked`` rows do not count against it), ties broken by the other
objectives and then by the order of the candidates.

The search is split by what it does: the space and the recommendation (:mod:`isolator.review.design_grid`),
the keys and store of finished rows (:mod:`isolator.review.design_store`), the reviews of the candidates on
workers (:mod:`isolator.review.design_workers`), the search and its result (here) and what is written: the
chart's data, the tables, the recommended review (:mod:`isolator.review.design_outputs`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path

from isolator.errors import ReviewError
from isolator.review.design_grid import (
    CHECK_ONLY_KEYS,
    OBJECTIVES,
    VARY_KEYS,
    Candidate,
    candidate_mappings,
    candidate_name,
    parse_vary,
    recommend,
    vary_key_problem,
)
from isolator.review.design_store import RowStore, content_digest, search_context_key
from isolator.review.design_workers import BEARING_COLUMNS, iterate_groups

#: the columns of the table before the per-check statuses (``check_<id>``)
COLUMNS = ("candidate", "error", "passes", "first_failing_check", "n_failing_checks", "n_not_checked",
           "radius_m", "mu_kinetic", "mu_static", "displacement_capacity_m", "isolated_period_s",
           "design_displacement_m", "design_total_displacement_m", "base_shear_coefficient", "governing_bound",
           "base_shear_governing_bound", "elf_total_displacement_m", "superstructure_shear_over_W",
           "restoring_force_over_W", "restoring_force_limit_over_W", "restoring_force_margin",
           "residual_displacement_m", "period_range_lo_s", "period_range_hi_s", "scale_factor_min",
           "scale_factor_max", "paper_k", "paper_alpha", "paper_eta", "paper_regime", "analyses_cached", "review_seconds",
           "spectra_seconds", "analyses_seconds", "key")


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
        columns = [c for c in COLUMNS if c not in self.varied_keys]
        if any(c in row for row in self.rows for c in BEARING_COLUMNS):  # a double or triple: its surfaces
            at = columns.index("mu_static") + 1
            columns[at:at] = BEARING_COLUMNS
        order = [*self.varied_keys, *columns, *checks]
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


def _refuse_a_space_of_no_design(candidates: list, source: str) -> None:
    """Refuse a space none of whose candidates reads as a design, before any review (``parameter`` "vary").

    One invalid candidate is a row with its reason (the module docstring); a space of none reviewed every
    candidate to its reading error and wrote a chart of nothing, exit 0 (``--vary radius_m=-1,-2``: 42 s; session
    14 sweep), as session 10's ``--vary mu_static`` of a triple did.  Stops at the first candidate that reads
    (bounded by the candidates, at most :data:`~isolator.review.design_grid.MAX_CANDIDATES`).
    """
    from isolator.design import Design
    from isolator.review.design_workers import candidate_source

    first = None
    for c in candidates:
        try:
            Design.from_mapping(c.mapping, source=candidate_source(source, c.values))
            return
        except (ValueError, ArithmeticError) as err:  # DesignError, or what a candidate's row would say
            first = first or err
    if first is not None:
        others = len(candidates) - 1
        raise ReviewError(f"gives no candidate that is a design: {first}"
                          + (f" (and {others} other candidate{'s' if others > 1 else ''} refused)" if others else ""),
                          parameter="vary")


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
            raise ReviewError(vary_key_problem(key), parameter="vary")
        if not values or not all(math.isfinite(x) for x in values):
            raise ReviewError(f"{key!r}: the values must be finite numbers", parameter="vary")
    mappings = candidate_mappings(design_mapping, design.mu_kinetic, ranges)
    keys = [k for k, _ in ranges]
    context_key = search_context_key(target, suite, code, scaling, parameters)
    candidates = []
    for index, mapping in enumerate(mappings):
        values = {k: mapping[k] for k in keys}
        numbers = {k: v for k, v in mapping.items() if k != "name"}
        group = content_digest({k: v for k, v in numbers.items() if k not in CHECK_ONLY_KEYS})
        mapping = {**mapping, "name": candidate_name(design_mapping, mapping, values)}
        candidates.append(Candidate(index, values, mapping, key=content_digest([context_key, numbers]), group=group))

    _refuse_a_space_of_no_design(candidates, str(design.source))
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
    for finished in iterate_groups(todo, context, workers, scheduler):
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


#: the public name (``isolator.design_search``)
design_search = search
