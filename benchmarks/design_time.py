"""Time of a design search: the README example's suite over R × µk, every candidate reviewed, with its chart.

The bundled example (``--target example --suite example --isolator data/example_review.toml``: 8 pairs)
over ``--radii`` radii from 1.5 to 4.5 m × ``--mus`` kinetic friction coefficients from 0.03 to 0.12
(13 × 10 = 130 candidates; each reviewed at the lower, upper and nominal friction, as ``isolator review``
does: 130 × 8 × 3 = 3 120 bidirectional analyses, 2 080 of them at the two bounds).

Warm: a first search over the same space (numba's disk cache loaded, matplotlib imported, the paper's regime
maps of the chart and of the recommended review cached on disk) is not counted.  Each timed run starts from the loaded
suite with an empty store (every candidate reviewed) and ends with the chart, the tables and the
recommended candidate's full review PDF written.  The split of the review work is summed over the
candidates (CPU seconds of the workers): spectra (the memo's computing time), analyses, and the rest of
each review (ELF values, period grid, scaling, checks, the row).  ``--growth`` also times 1, 4 and 7 µ
values (13, 52, 91 candidates) to show how the time grows with candidates.  Prints a table;
docs/design_search.md quotes it.

    python -m benchmarks.design_time --jobs 2 [--growth] [--isolator data/example_design.toml]   # from the repository root
"""

from __future__ import annotations

import argparse
import os
import resource
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: the base design of the timed space (the measurements in docs/design_search.md#speed use it; the example's
#: own base file, data/example_design.toml, differs only in its 2.0 m capacity: --isolator)
DESIGN = "data/example_review.toml"


def one_search(radii: int, mus: int, jobs: int, out: Path, design: str = DESIGN) -> dict:
    from isolator.review import load_suite, load_target, resolve_example
    from isolator.review.design_outputs import write_outputs
    from isolator.review.design_space import search

    target = load_target(resolve_example("target", "example"))
    suite = load_suite(resolve_example("suite", "example"))
    vary = [f"radius_m=1.5:4.5:{radii}", f"mu_kinetic=0.03:0.12:{mus}"] if mus > 1 else \
        [f"radius_m=1.5:4.5:{radii}", "mu_kinetic=0.03"]
    from isolator.cli.common import collector_skips_existing_objects

    cpu_start = _cpu_seconds()
    start = time.perf_counter()
    with collector_skips_existing_objects():  # as the command does
        result = search(ROOT / design, target, suite, vary, jobs=jobs, store_dir=None)
    searched = time.perf_counter()
    out_json = write_outputs(result, out, target, suite, jobs=jobs)
    end = time.perf_counter()
    cpu = _cpu_seconds() - cpu_start
    rows = result.rows
    worker = {key: sum(r.get(key, 0.0) or 0.0 for r in rows) for key in ("review_seconds", "spectra_seconds",
                                                                             "analyses_seconds")}
    t = out_json["timing_s"]
    return {"candidates": len(rows), "passing": out_json["n_passing"], "errors": out_json["n_errors"],
            "pairs": len(suite.pairs), "search_s": searched - start, "spectra_cpu_s": worker["spectra_seconds"],
            "analyses_cpu_s": worker["analyses_seconds"], "cpu_s": cpu,
            "rest_cpu_s": worker["review_seconds"] - worker["spectra_seconds"] - worker["analyses_seconds"],
            "tables_s": t["tables"], "paper_map_s": t["paper_map"], "chart_s": t["chart"],
            "recommended_review_s": t["recommended_review"], "total_s": end - start,
            "recommended": out_json["recommended"]}


def _cpu_seconds() -> float:
    """User + system CPU time of this process and of its finished children (the pool's workers) [s]."""
    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--radii", type=int, default=13)
    parser.add_argument("--mus", type=int, default=10)
    parser.add_argument("--isolator", default=DESIGN, help=f"base design file (default {DESIGN})")
    parser.add_argument("--growth", action="store_true", help="also 1, 4 and 7 µ values")
    parser.add_argument("--skip-warm-up", action="store_true",
                        help="the caches are warm from an earlier run of the same space")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        # warm-up, not counted: the same space, so that every disk cache (numba, the paper's maps) is warm
        if not args.skip_warm_up:
            one_search(args.radii, args.mus, args.jobs, Path(folder) / "warm" / "design.pdf", args.isolator)
        sizes = ([1, 4, 7] if args.growth else []) + [args.mus]
        runs = [one_search(args.radii, mus, args.jobs, Path(folder) / f"run{mus}" / "design.pdf", args.isolator)
                for mus in sizes]
    main_run = runs[-1]
    print(f"design search: {args.isolator}, example suite ({main_run['pairs']} pairs), {args.radii} radii × {args.mus} µk = "
          f"{main_run['candidates']} candidates × {main_run['pairs']} pairs × 3 frictions, --jobs {args.jobs}, "
          f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}, "
          f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}")
    print(f"{main_run['passing']} pass, {main_run['errors']} not analysed; recommended (base_shear): "
          + (", ".join(f"{k} = {main_run['recommended'][k]:.4g}" for k in ("radius_m", "mu_kinetic",
                                                                          "base_shear_coefficient"))
             if main_run["recommended"] else "none"))
    print()
    print("| stage | seconds |")
    print("|---|---|")
    print(f"| search, wall ({args.jobs} processes) | {main_run['search_s']:.2f} |")
    print(f"| · spectra (worker seconds, summed over candidates) | {main_run['spectra_cpu_s']:.2f} |")
    print(f"| · analyses (worker seconds, summed) | {main_run['analyses_cpu_s']:.2f} |")
    print(f"| · ELF, grid, scaling, checks, row (worker seconds, summed) | {main_run['rest_cpu_s']:.2f} |")
    print(f"| tables (CSV, Parquet) | {main_run['tables_s']:.2f} |")
    print(f"| paper's regime map (cached on disk) | {main_run['paper_map_s']:.2f} |")
    print(f"| chart PDF | {main_run['chart_s']:.2f} |")
    print(f"| recommended candidate's review + PDF | {main_run['recommended_review_s']:.2f} |")
    print(f"| **total, wall** | **{main_run['total_s']:.2f}** |")
    print(f"| CPU, this process and its workers (user + system) | {main_run['cpu_s']:.2f} |")
    print(f"| CPU / {args.jobs}: the wall time on {args.jobs} idle cores, at best | {main_run['cpu_s'] / args.jobs:.2f} |")
    if args.growth:
        print()
        print("| candidates | search wall s | total wall s | CPU s | CPU per candidate ms |")
        print("|---|---|---|---|---|")
        for run in runs:
            print(f"| {run['candidates']} | {run['search_s']:.2f} | {run['total_s']:.2f} | {run['cpu_s']:.2f} | "
                  f"{1000 * run['cpu_s'] / run['candidates']:.0f} |")


if __name__ == "__main__":
    main()
