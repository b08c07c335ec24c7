"""The kernel's time of single slides of the bench's 2-D building: runs over [0, A] and [0, B], alternated.

The bench's 2-D building (5 floors, PTS, µ = 0.06, :mod:`isolator.bench.building`) is run over the pair's first A
and first B seconds for each window [A, B] that brackets one slide (break-away to stop; the slide's times are those
``benchmarks.planar_building_split`` prints), every run's kernel timed by the thread's CPU clock, the runs
alternated (forwards, then backwards) ``--runs`` times in one process.  A slide's cost is the difference of the
two medians, its pieces and fast sub-steps the difference of the two runs' counts.  The default windows are a
departure cut by a sample's end 0.10 ms after its break-away (8.7399 s), one cut 0.41 ms after (3.4196 s), one
cut 0.77 ms after (5.7792 s) and three slides whose departure series ended at its own reach (docs/building.md,
h144).  With ``--split FILE`` (the slides' sample bounds that ``benchmarks.planar_building_split --bounds FILE``
writes) every sample bound of every slide is a run's end, and the kernel's time of the whole pair is split by clock
into the slides' departures (the break-away's sample to the first whole-h fast sub-step), cruises, approaches (the
last whole-h sub-step's end to the stop's sample end) and the rest (stuck)::

    OPENBLAS_NUM_THREADS=1 .venv/bin/python -m benchmarks.planar_building_slide_cost [--records ../shared/records]
        [--runs 15] [--window NAME:A:B ...] [--split FILE]

A run over the first T seconds is the whole run's history up to T (the kernel is causal) but for v_ref (the speed
scale of START's and FINISH's thresholds, from the record's largest sample): each truncated run's kernel gets the
whole pair's v_ref (:func:`runner`), so its slides are the whole run's.  Only the kernel's call is timed.
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

#: name → (A, B) [s]: each window brackets one slide of the bench case (PTS, µs = µk = 0.06)
WINDOWS = {
    "cut 0.10 ms after 8.7399 s": (8.73, 8.91),
    "cut 0.41 ms after 3.4196 s": (3.41, 3.64),
    "cut 0.77 ms after 5.7792 s": (5.77, 6.16),
    "reach-ended, 2.8072 s": (2.80, 2.98),
    "reach-ended, 7.1624 s": (7.16, 7.36),
    "reach-ended, 8.2352 s": (8.23, 8.50),
}


def _parse_window(text: str) -> tuple[str, tuple[float, float]]:
    try:
        name, a, b = text.rsplit(":", 2)
        lo, hi = float(a), float(b)
    except ValueError:
        raise SystemExit(f"--window {text!r}: expected NAME:A:B with A < B in seconds") from None
    if not 0.0 < lo < hi:
        raise SystemExit(f"--window {text!r}: expected 0 < A < B")
    return name, (lo, hi)


def runner(records: Path):
    """A function T ↦ (the kernel's thread CPU seconds, response) of the bench's 2-D building over the pair's first T
    seconds, its kernel given the whole pair's v_ref (the kernel's argument of that name, checked)."""
    import inspect

    import numpy as np

    import isolator.solver.planar_building as planar_building
    from isolator.bench.building import BUILDING_PAIR, FIXED_BASE_PERIOD_Y_S, building_case
    from isolator.motion import read_ground_motion

    _, folder, fx, fy = BUILDING_PAIR
    mx, my = (read_ground_motion(records / folder / f) for f in (fx, fy))
    installed = planar_building._pk.building2d_kernel
    at = list(inspect.signature(installed.py_func).parameters).index("v_ref")
    clock = {}

    def pinned(*args):
        args = list(args)
        args[at] = clock["v_ref"]
        start = time.thread_time()
        installed(*args)
        clock["seconds"] = time.thread_time() - start

    def run(seconds: float):
        keep = round(seconds / mx.dt_s) + 1
        case = building_case("2-D building", mx.acceleration_m_s2[:keep], mx.dt_s,
                             acceleration_y_m_s2=my.acceleration_m_s2[:keep], period_y_s=FIXED_BASE_PERIOD_Y_S)
        # simulate_planar_building's v_ref, over the whole pair
        clock["v_ref"] = max(case.mu * case.gravity_m_s2, float(np.max(np.abs(mx.acceleration_m_s2))),
                             float(np.max(np.abs(my.acceleration_m_s2))), 1e-12) * mx.dt_s
        planar_building._pk.building2d_kernel = pinned
        try:
            r = planar_building.simulate_planar_building(
                case.acceleration_m_s2, case.acceleration_y_m_s2, case.dt_s, superstructure=case.superstructure,
                total_mass_kg=case.total_mass_kg, stiffness_N_per_m=case.isolator_stiffness_N_per_m,
                mu_static=case.mu, mu_kinetic=case.mu, gravity_m_s2=case.gravity_m_s2)
        finally:
            planar_building._pk.building2d_kernel = installed
        return clock["seconds"], r

    return run


def timed(run, ends, runs: int):
    """{T: [seconds …]}, {T: (pieces, fast sub-steps)}: the runs over [0, T] alternated, forwards then backwards."""
    for t in ends:
        run(t)  # the first call of each length builds its tables
    times = {t: [] for t in ends}
    counts = {}
    for i in range(runs):
        for t in ends if i % 2 == 0 else ends[::-1]:
            seconds, r = run(t)
            times[t].append(seconds)
            counts[t] = (r.n_pieces, r.n_fast_steps)
    return times, counts


def split_by_clock(bounds: list[list[int]], n_samples: int) -> dict[str, list[tuple[int, int]]]:
    """The sample intervals [i, j) of each kind: per slide [break-away's sample, first whole sub-step) departure,
    then cruise, then approach up to the stop's sample end (a slide without a whole sub-step is all departure); the
    intervals between slides (and before the first, after the last) stuck."""
    kinds = {"departure": [], "cruise": [], "approach": [], "stuck": []}
    last = 0
    for i0, i1, i2, i3 in bounds:
        if i0 > last:
            kinds["stuck"].append((last, i0))
        kinds["departure"].append((i0, i1))
        if i2 > i1:
            kinds["cruise"].append((i1, i2))
        if i3 > i2:
            kinds["approach"].append((i2, i3))
        last = i3
    if n_samples > last:
        kinds["stuck"].append((last, n_samples))
    return kinds


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", default="../shared/records")
    parser.add_argument("--runs", type=int, default=15)
    parser.add_argument("--window", action="append", default=[], help="NAME:A:B (seconds), repeatable")
    parser.add_argument("--split", default=None, help="the slides' sample bounds (planar_building_split --bounds)")
    args = parser.parse_args(argv)
    if args.runs < 1:
        raise SystemExit("--runs must be at least 1")
    windows = dict(_parse_window(w) for w in args.window) if args.window else WINDOWS
    run = runner(Path(args.records))
    if args.split:
        _split(run, Path(args.split), args.runs)
        return
    ends = sorted({t for pair in windows.values() for t in pair})
    times, counts = timed(run, ends, args.runs)
    print(f"kernel CPU, medians of {args.runs} runs alternated; a slide = the run over [0, B] minus over [0, A]")
    for name, (a, b) in windows.items():
        cost = statistics.median(times[b]) - statistics.median(times[a])
        print(f"  {name:30s} [{a:g}, {b:g}] s: {1e3 * cost:7.3f} ms, {counts[b][0] - counts[a][0]:4d} pieces, "
              f"{counts[b][1] - counts[a][1]:4d} fast sub-steps")
    whole = ", ".join(f"{t:g} s {1e3 * statistics.median(v):.2f} ms" for t, v in times.items())
    print(f"  the runs themselves: {whole}")


def _split(run, path: Path, runs: int) -> None:
    import json

    data = json.loads(path.read_text())
    dt, n_samples, bounds = data["dt_s"], data["n_samples"], data["bounds"]
    kinds = split_by_clock(bounds, n_samples)
    ends = sorted({j for spans in kinds.values() for span in spans for j in span} - {0})
    times, counts = timed(run, [j * dt for j in ends], runs)
    pieces = {0: 0, **{j: counts[j * dt][0] for j in ends}}
    # differences of the medians and of the minima over the runs (a single run's time moves by milliseconds under
    # load: sums of per-round differences were dominated by it); each kind's span sums telescope to the whole pair's
    stats = {name: {0: 0.0, **{j: f(times[j * dt]) for j in ends}}
             for name, f in (("median", statistics.median), ("minimum", min))}
    print(f"the kernel's time split by clock over {len(bounds)} slides ({runs} runs over [0, T] alternated; the "
          f"whole pair's median {1e3 * stats['median'][max(ends)]:.2f} ms, minimum {1e3 * stats['minimum'][max(ends)]:.2f} ms)")
    for kind, spans in kinds.items():
        n = sum(pieces[j] - pieces[i] for i, j in spans)
        parts = []
        for name, at in stats.items():
            cost = sum(at[j] - at[i] for i, j in spans)
            parts.append(f"{name} {1e3 * cost:7.3f} ms ({100 * cost / at[max(ends)]:5.1f} %)")
        print(f"  {kind:10s} " + ", ".join(parts) + f", {n:5d} pieces")


if __name__ == "__main__":
    main()
