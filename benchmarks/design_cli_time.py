"""Wall and CPU time of `isolator design` on the bundled example, as a user runs it: a fresh process, launch to exit.

    .venv/bin/python -m benchmarks.design_cli_time                      # docs/design_search.md's command
    .venv/bin/python -m benchmarks.design_cli_time --vary radius_m=4.0,4.5 --vary mu_kinetic=0.03,0.06 --runs 3
    .venv/bin/python -m benchmarks.design_cli_time --runs 3 --against /work/main/.venv/bin/isolator

Runs ``isolator design --target example --suite example --isolator data/example_design.toml --vary … -o
TMP/design.pdf --jobs J`` once untimed (numba's compiled functions and the regime map's disk cache loaded),
then ``--runs`` times, in alternation with ``--against`` (another installation's ``isolator``: before/after
on a shared machine).  Each run writes to a new folder, so that no design store or analysis cache serves it.
Prints the medians of the wall and CPU times, the runs, the load average, and the per-candidate worker
seconds of the last run's table (``review_seconds``, ``analyses_seconds``: median and largest over the
candidates).  Run from the repository root, as a module (it shares its timing with benchmarks/review_cli_time.py).
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import tempfile
import time
from pathlib import Path

from benchmarks.review_cli_time import isolator_command, run_child

#: docs/design_search.md's example space: 7 radii × 4 µk = 28 candidates
EXAMPLE_VARY = ["radius_m=2.0:5.0:7", "mu_kinetic=0.03:0.12:4"]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--isolator", default="data/example_design.toml", help="the base design file")
    parser.add_argument("--vary", action="append", default=None, help="passed on (default: the docs' space)")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--against", metavar="ISOLATOR", help="another installation's isolator script, run in "
                        "alternation with this tree's")
    args = parser.parse_args(argv)
    if args.runs < 1:
        parser.error("--runs must be ≥ 1")
    vary = args.vary or EXAMPLE_VARY
    trees = {"this tree": isolator_command()}
    if args.against:
        other = Path(args.against).resolve()
        if not other.is_file():
            parser.error(f"--against {args.against}: no such file")
        trees[str(other)] = [str(other)]
    base = Path(tempfile.mkdtemp(prefix="isolator-design-time-"))
    counter = iter(range(10 ** 6))

    def command(script):
        out = base / f"run{next(counter)}"
        arguments = ["design", "--target", "example", "--suite", "example", "--isolator", args.isolator,
                     "-o", str(out / "design.pdf"), "--jobs", str(args.jobs)]
        for setting in vary:
            arguments += ["--vary", setting]
        return script + arguments, out

    try:
        load_before = os.getloadavg()
        for script in trees.values():
            run_child(command(script)[0])  # warm-up
        runs = {name: [] for name in trees}
        tables = {}
        for _ in range(args.runs):  # in alternation, so that the machine's load episodes hit both alike
            for name, script in trees.items():
                cmd, out = command(script)
                runs[name].append(run_child(cmd))
                tables[name] = out / "design.csv"
        load_after = os.getloadavg()
        import pandas as pd

        per = {name: pd.read_csv(path) for name, path in tables.items()}
    finally:
        shutil.rmtree(base, ignore_errors=True)
    print(f"isolator design --isolator {args.isolator} " + " ".join(f"--vary {v}" for v in vary)
          + f" --jobs {args.jobs}")
    print(f"{args.runs} runs after one untimed run{' each, in alternation' if len(trees) > 1 else ''}; "
          f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; load average before {load_before}, "
          f"after {load_after}")
    for name, timed in runs.items():
        walls, cpus = [w for w, _ in timed], [c for _, c in timed]
        table = per[name]
        print(f"{name}: {len(table)} candidates")
        print(f"  wall [s]: median {statistics.median(walls):.2f}, runs {' '.join(f'{w:.2f}' for w in walls)}")
        print(f"  CPU  [s]: median {statistics.median(cpus):.2f}, runs {' '.join(f'{c:.2f}' for c in cpus)} "
              "(the command and its worker processes)")
        for key in ("review_seconds", "analyses_seconds"):
            if key in table:
                values = table[key].dropna()
                print(f"  per candidate, {key} (worker): median {values.median():.2f}, largest {values.max():.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
