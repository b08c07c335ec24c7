"""The harness: time every method on every case and measure its errors against the reference.

1-D cases: our solver is compared with the tightest event-located ``solve_ivp`` run
(DOP853, rtol 1e-12), the baselines with our solver.  2-D cases
(:mod:`isolator.bench.pairs`): ours and every baseline are compared with the
independent reference (the truth).  :func:`pareto_summary` says where ours stands
(speed-up at equal error, accuracy gain at equal time) and, on 2-D cases, its time
and error against OpenSees at the record's dt, measured in the same run.
"""

from __future__ import annotations

import math
import statistics
import time
from collections.abc import Callable

import numpy as np

from isolator.bench.cases import BenchCase, harmonic_case
from isolator.bench.methods import (
    OURS,
    MethodOutput,
    exact_solver,
    implicit_fixed_step,
    ivp_with_events,
    methods,
    newmark_elastic_plastic,
)
from isolator.bench.pairs import (
    OPENSEES,
    PAIR_OURS,
    PAIR_TRUTH,
    pair_errors,
    pair_methods,
    planar_solver,
    reference_solver,
)

ERROR_FLOOR = 1e-16  #: errors below this are reported as this (round-off)


CROSS_CHECK = ("solve_ivp DOP853 + events (tightest)", 1e-12)
#: our rows (1-D exact solver, 2-D planar engine) and the references they are checked against (not baselines)
OURS_METHODS = (OURS, PAIR_OURS)
REFERENCE_METHODS = (CROSS_CHECK[0], PAIR_TRUTH)
#: the OpenSees setting of the headline ratio: OpenSees at the record's own dt
OPENSEES_HEADLINE_SETTING = "dt/1"


def errors(case: BenchCase, out: MethodOutput, ref: MethodOutput) -> dict:
    """Errors of ``out`` against ``ref``: peak (relative), residual [m], ζ, trajectory (relative to the peak)."""
    scale = max(float(np.max(np.abs(ref.displacement))), ERROR_FLOOR)
    traj = float(np.max(np.abs(out.displacement - ref.displacement))) / scale
    peak = abs(out.peak - ref.peak) / max(abs(ref.peak), ERROR_FLOOR)
    return {
        "error_peak_rel": max(peak, ERROR_FLOOR),
        "error_residual_abs": max(abs(out.residual - ref.residual), ERROR_FLOOR),
        "error_zeta": max(abs(out.slip_ratio - ref.slip_ratio), ERROR_FLOOR),
        "error_trajectory": max(traj, ERROR_FLOOR) if np.all(np.isfinite(out.displacement)) else math.inf,
    }


def time_method(function, case, setting, repeats: int, budget_s: float = 2.0, min_total_s: float = 0.2,
                max_runs: int = 50, count: list | None = None):
    """Median wall time [s] of at least ``repeats`` runs, more (up to ``max_runs``) while the
    total stays under ``min_total_s``; a single run if the first takes more than ``budget_s``.
    The number of runs is appended to ``count`` when given."""
    times = []
    out = None
    while True:
        start = time.perf_counter()
        out = function(case, setting)
        times.append(time.perf_counter() - start)
        if times[0] > budget_s or len(times) >= max_runs:
            break
        if len(times) >= max(1, repeats) and sum(times) >= min_total_s:
            break
    if count is not None:
        count.append(len(times))
    return statistics.median(times), out


#: our runs between two runs of the baseline in :func:`time_interleaved`, and its rounds per repeat
OURS_PER_BASELINE_RUN = 5
ROUNDS_PER_REPEAT = 2


def time_interleaved(ours, baseline, case, setting, rounds: int, ours_per_round: int = OURS_PER_BASELINE_RUN):
    """Median wall times [s] of ``ours`` and ``baseline`` (at ``setting``), timed in alternation.

    Each of ``rounds`` rounds runs ours ``ours_per_round`` times, then the baseline once: both
    medians come from the same stretch of time, so their ratio does not carry the drift of a
    shared machine's speed between two separate measurements (it moved by ±25 % from minute to
    minute on the 2-core bench machine, in episodes of a tenth of a second to a few seconds;
    docs/planar.md).

    Returns
    -------
    tuple
        ``(ours_seconds, ours_output, ours_runs, baseline_seconds, baseline_output, baseline_runs)``.
    """
    ours_times, base_times = [], []
    ours_out = base_out = None
    for _ in range(max(1, rounds)):
        for _ in range(max(1, ours_per_round)):
            start = time.perf_counter()
            ours_out = ours(case, None)
            ours_times.append(time.perf_counter() - start)
        start = time.perf_counter()
        base_out = baseline(case, setting)
        base_times.append(time.perf_counter() - start)
    return (statistics.median(ours_times), ours_out, len(ours_times),
            statistics.median(base_times), base_out, len(base_times))


def time_against_opensees(ours, baseline, case, rounds: int, ours_per_round: int = OURS_PER_BASELINE_RUN):
    """:func:`time_interleaved` of ours and an OpenSees ``baseline`` at the record's dt (setting 1),
    or ours alone (``rounds × ours_per_round`` runs) when openseespy does not import here.

    Returns
    -------
    tuple
        ``(ours_seconds, ours_output, ours_runs, baseline_seconds, baseline_output, baseline_runs, why)``;
        the baseline's three are None, and ``why`` the reason, when OpenSees did not run.
    """
    from isolator.bench.opensees import opensees_available

    available, why = opensees_available()
    if available:
        return (*time_interleaved(ours, baseline, case, 1, rounds, ours_per_round), "")
    times = []
    out = None
    for _ in range(max(1, rounds) * max(1, ours_per_round)):
        start = time.perf_counter()
        out = ours(case, None)
        times.append(time.perf_counter() - start)
    return statistics.median(times), out, len(times), None, None, None, why


def time_ours_and_opensees(ours, baseline, case, rounds: int, ours_per_round: int, ours_missing: str = "",
                           progress=None):
    """:func:`time_against_opensees` after one untimed run of ours (numba's code loaded, caches filled);
    or, when ours cannot run here (``ours_missing`` says why), the OpenSees ``baseline`` alone,
    ``rounds`` runs (median).

    Returns
    -------
    tuple
        As :func:`time_against_opensees`; ours' three are None when ours did not run.
    """
    from isolator.bench.opensees import opensees_available

    say = progress or (lambda line: None)
    available, why = opensees_available()
    if not ours_missing:
        ours(case, None)
        say(f"{case.name}: ours and OpenSees, {rounds} rounds in alternation" if available else
            f"{case.name}: ours alone ({why}), {max(1, rounds) * max(1, ours_per_round)} runs")  # it said "and OpenSees"
        return time_against_opensees(ours, baseline, case, rounds, ours_per_round)
    if not available:
        return None, None, None, None, None, None, why
    say(f"{case.name}: OpenSees alone ({ours_missing}), {rounds} runs")
    times, out = [], None
    for _ in range(max(1, rounds)):
        start = time.perf_counter()
        out = baseline(case, 1)
        times.append(time.perf_counter() - start)
    return None, None, None, statistics.median(times), out, len(times), ""


def time_rounds(runs: dict, rounds: int) -> tuple[dict, dict, dict]:
    """``runs``: name -> (callable without arguments, calls per round); every name in turn, round by round
    (alternation: the ratios between names come from the same minutes).  Returns the median seconds, the number of
    calls and the last answer, each by name."""
    times = {name: [] for name in runs}
    last = {}
    for _ in range(max(1, rounds)):
        for name, (call, per_round) in runs.items():
            for _ in range(max(1, per_round)):
                start = time.perf_counter()
                last[name] = call()
                times[name].append(time.perf_counter() - start)
    return ({name: statistics.median(values) for name, values in times.items()},
            {name: len(values) for name, values in times.items()}, last)


def warm_up() -> None:
    """Compile or load every numba function once, so that timings measure solving: the 1-D engine by the model
    registry's warm-up (:func:`isolator.solver.models.warm_up`), the harmonic solver and the baselines here."""
    from isolator.solver import models, record

    models.warm_up(record.MODEL_NAME)
    case = harmonic_case("warm-up", 1.5, 1.0, 0.5, 0.25, 0.2, n_periods=1)
    exact_solver(case)
    implicit_fixed_step(case, 0.5)
    newmark_elastic_plastic(case, 0.5)


def warm_up_pairs() -> None:
    """Load the planar engine's numba functions once (2-D cases), by the model registry's warm-up."""
    from isolator.solver import models, planar

    models.warm_up(planar.MODEL_NAME)


def _failed_row(method: str, case, setting, note: str) -> dict:
    """A row for a baseline that could not run here (e.g. openseespy not installed)."""
    return {"method": method, "case": case.name, "setting": setting, "seconds": math.nan,
            "error_peak_rel": math.nan, "error_residual_abs": math.nan, "error_zeta": math.nan,
            "error_trajectory": math.nan, "n_events": -1, "note": note}


def run_pair_case(case, quick: bool, repeats: int, progress: Callable[[str], None] | None = None) -> list[dict]:
    """The rows of one 2-D case: ours and every baseline against the truth (the independent reference)."""
    runs: list[int] = []
    headline = next((m for m in pair_methods(quick) if m.name == OPENSEES), None)
    timed = {}  #: (method, setting) -> (seconds, output, runs) of the baseline timed alongside ours
    if headline is not None and OPENSEES_HEADLINE_SETTING in headline.settings and headline.available()[0]:
        # ours and OpenSees at the record's dt in alternation: the headline ratio from one stretch of time
        seconds, ours, n_ours, base_seconds, base_out, n_base = time_interleaved(
            planar_solver, headline.function, case, OPENSEES_HEADLINE_SETTING, ROUNDS_PER_REPEAT * repeats)
        runs.append(n_ours)
        timed[(OPENSEES, OPENSEES_HEADLINE_SETTING)] = (base_seconds, base_out, n_base)
    else:
        seconds, ours = time_method(planar_solver, case, None, repeats, count=runs)
    truth_seconds, truth = time_method(reference_solver, case, None, 1)
    rows = [{"method": PAIR_OURS, "case": case.name, "setting": "-", "seconds": seconds, "runs": runs[-1],
             **pair_errors(ours, truth), "n_events": ours.n_events},
            {"method": PAIR_TRUTH, "case": case.name, "setting": 1e-12, "seconds": truth_seconds, "runs": 1,
             **pair_errors(truth, ours), "n_events": truth.n_events}]
    if progress:
        progress(f"{case.name}: ours {seconds * 1e3:.3g} ms, reference {truth_seconds:.3g} s, "
                 f"peak error {rows[0]['error_peak_rel']:.1e}")
    for method in pair_methods(quick):
        available, why = method.available()
        for setting in method.settings:
            if not available:
                rows.append(_failed_row(method.name, case, setting, why))
                continue
            if (method.name, setting) in timed:
                seconds, out, n_runs = timed[(method.name, setting)]
                runs.append(n_runs)
            else:
                seconds, out = time_method(method.function, case, setting, repeats, count=runs)
            rows.append({"method": method.name, "case": case.name, "setting": setting, "seconds": seconds,
                         "runs": runs[-1], **pair_errors(out, truth), "n_events": out.n_events})
            if progress:
                progress(f"  {method.name} {method.setting_name}={setting}: {seconds:.3g} s, "
                         f"trajectory error {rows[-1]['error_trajectory']:.2e}")
    return rows


def run_bench(quick: bool = False, records_dir=None, repeats: int | None = None,
              cases: list[BenchCase] | None = None, progress: Callable[[str], None] | None = None):
    """Run every method on every case (``cases``, or :func:`~isolator.bench.cases.bench_cases`).

    Returns
    -------
    rows : list of dict
        One row per (method, case, setting) with keys ``method``, ``case``, ``setting``,
        ``seconds`` (median wall time [s]), ``error_peak_rel`` [-], ``error_residual_abs``
        [m, or A0 for harmonic cases], ``error_zeta`` [-] and ``error_trajectory`` [-,
        max |X - X_ref| / max |X_ref|].
    pareto : list of dict
        Per case, where our solver stands against the baselines (see :func:`pareto_summary`).
    """
    repeats = (3 if quick else 5) if repeats is None else repeats
    if cases is None:
        from isolator.bench.cases import bench_cases

        cases = bench_cases(quick, records_dir)
    warm_up()
    if any(case.kind == "pair" for case in cases):
        warm_up_pairs()
    rows = []
    for case in cases:
        if case.kind == "pair":
            rows.extend(run_pair_case(case, quick, repeats, progress))
            continue
        seconds, ours = time_method(exact_solver, case, None, repeats)
        cross_name, cross_tol = CROSS_CHECK
        cross_seconds, cross = time_method(lambda c, tol: ivp_with_events(c, tol, "DOP853"), case, cross_tol, 1)
        row = {"method": OURS, "case": case.name, "setting": "-", "seconds": seconds, **errors(case, ours, cross),
               "n_events": ours.n_events}
        if case.kind == "harmonic":
            row["error_zeta_analytic"] = max(abs(ours.slip_ratio - case.exact_zeta), ERROR_FLOOR)
            row["error_amplitude_analytic_rel"] = max(abs(ours.peak - case.exact_amplitude) / case.exact_amplitude,
                                                      ERROR_FLOOR)
        rows.append(row)
        rows.append({"method": cross_name, "case": case.name, "setting": cross_tol, "seconds": cross_seconds,
                     **errors(case, cross, ours), "n_events": cross.n_events})
        if progress:
            progress(f"{case.name}: ours {seconds * 1e3:.3g} ms, cross-check {cross_seconds:.3g} s")
        for method in methods(quick)[1:]:
            settings = method.harmonic_settings if case.kind == "harmonic" else method.settings
            for setting in settings:
                seconds, out = time_method(method.function, case, setting, repeats)
                rows.append({"method": method.name, "case": case.name, "setting": setting, "seconds": seconds,
                             **errors(case, out, ours), "n_events": out.n_events})
                if progress:
                    progress(f"  {method.name} {method.setting_name}={setting}: {seconds:.3g} s, "
                             f"trajectory error {rows[-1]['error_trajectory']:.2e}")
    pareto = pareto_summary(rows)
    by_case = pareto_by_case(pareto)
    for row in rows:  # the ratios ride along on our rows too
        if row["method"] in OURS_METHODS and row["case"] in by_case:
            row.update({k: v for k, v in by_case[row["case"]].items()
                        if k.startswith(("speedup", "accuracy", "opensees"))})
    return rows, pareto


def pareto_by_case(pareto):
    return {p["case"]: p for p in pareto}


#: the engineering accuracy at which speed-ups are also quoted (trajectory error)
ENGINEERING_ERROR = 1e-3


def pareto_summary(rows: list[dict], error_key: str = "error_trajectory") -> list[dict]:
    """Per case: is ours on the Pareto front, and by how much.

    ``speedup_at_equal_error``: time of the fastest baseline whose error is at most
    ours, divided by ours (``None``: no baseline reaches our error).
    ``speedup_at_1e-3``: the same at the engineering accuracy 1e-3.
    ``accuracy_gain_at_equal_time``: error of the most accurate baseline that runs at
    most as long as ours, divided by ours (``None``: no baseline is as fast).
    ``accuracy_gain_vs_fastest``: error of the fastest baseline over ours, with
    ``fastest_time_ratio`` its time over ours.  The DOP853 cross-check is left out of
    the baselines (its error and ours are the same number, their discrepancy);
    ``cross_check_time_ratio`` is its time over ours.  On 2-D cases, with OpenSees at
    the record's dt: ``opensees_time_ratio`` (its median time over ours, in the same
    run) and ``opensees_error_ratio`` / ``opensees_peak_error_ratio`` (its trajectory
    and peak errors over ours, both against the truth); None where it did not run.
    A case without any baseline that ran is left out.
    """
    summary = []
    for case in dict.fromkeys(r["case"] for r in rows):
        ours = next(r for r in rows if r["case"] == case and r["method"] in OURS_METHODS)
        # the cross-check / the truth is not a baseline: its error and ours are the same discrepancy
        base = [r for r in rows if r["case"] == case and r["method"] not in OURS_METHODS + REFERENCE_METHODS
                and math.isfinite(r[error_key])]
        if not base:
            continue
        cross = [r for r in rows if r["case"] == case and r["method"] in REFERENCE_METHODS]
        t0, e0 = ours["seconds"], ours[error_key]
        reach = [r for r in base if r[error_key] <= e0]
        reach_eng = [r for r in base if r[error_key] <= ENGINEERING_ERROR]
        as_fast = [r for r in base if r["seconds"] <= t0]
        fastest = min(base, key=lambda r: r["seconds"])
        most_accurate = min(base, key=lambda r: r[error_key])
        dominated = any(r["seconds"] <= t0 and r[error_key] <= e0 for r in base)

        def label(r):
            return f"{r['method']} @ {r['setting']}"

        summary.append({
            "case": case,
            "seconds": t0,
            "error": e0,
            "on_pareto_front": not dominated,
            "speedup_at_equal_error": min(r["seconds"] for r in reach) / t0 if reach else None,
            "speedup_at_1e-3": (min(r["seconds"] for r in reach_eng) / t0) if reach_eng else None,
            "speedup_at_1e-3_vs": label(min(reach_eng, key=lambda r: r["seconds"])) if reach_eng else "none reaches it",
            "accuracy_gain_at_equal_time": (min(r[error_key] for r in as_fast) / e0) if as_fast else None,
            "accuracy_gain_vs_fastest": fastest[error_key] / e0,
            "fastest_baseline": label(fastest),
            "fastest_time_ratio": fastest["seconds"] / t0,
            "most_accurate_baseline": label(most_accurate),
            "most_accurate_error": most_accurate[error_key],
            "most_accurate_time_ratio": most_accurate["seconds"] / t0,
            "cross_check_time_ratio": cross[0]["seconds"] / t0 if cross else None,
            **_opensees_ratios(rows, case, ours, error_key),
        })
    return summary


def _opensees_ratios(rows: list[dict], case: str, ours: dict, error_key: str) -> dict:
    """OpenSees at the record's dt against ours on one 2-D case (time and error ratios, same run)."""
    if ours["method"] != PAIR_OURS:
        return {}
    theirs = [r for r in rows if r["case"] == case and r["method"] == OPENSEES
              and r["setting"] == OPENSEES_HEADLINE_SETTING and math.isfinite(r[error_key])]
    if not theirs:
        return {"opensees_time_ratio": None, "opensees_error_ratio": None, "opensees_peak_error_ratio": None}
    r = theirs[0]
    return {"opensees_time_ratio": r["seconds"] / ours["seconds"],
            "opensees_error_ratio": r[error_key] / ours[error_key],
            "opensees_peak_error_ratio": r["error_peak_rel"] / ours["error_peak_rel"],
            "opensees_runs": r.get("runs"), "ours_runs": ours.get("runs")}
