"""Wall and CPU time of the README's review command, as a user runs it: a fresh process, launch to exit.

    .venv/bin/python benchmarks/review_cli_time.py --set horizontal_only=true   # data/example_building.toml
    .venv/bin/python benchmarks/review_cli_time.py --design data/example_review.toml --runs 7
    .venv/bin/python benchmarks/review_cli_time.py --set horizontal_only=true --stages   # + where the time goes
    .venv/bin/python benchmarks/review_cli_time.py --set horizontal_only=true --against ../main/.venv/bin/isolator

Runs ``isolator review --design DESIGN --target example --suite example -o TMP/review.pdf --no-cache``
once untimed (numba's compiled functions and the regime map's disk cache loaded: "warm"), then
``--runs`` times; ``--no-cache`` makes every run analyse every pair and bound again (without it a
rerun is served from the analysis cache in a few tenths of a second).  Prints the median, the
runs, the load average before and after, and the stages of the last run from the review's JSON
(``timing_s``).  ``--stages`` adds one more run in a fresh interpreter that calls the CLI in-process,
so that its steps can be timed (wall and CPU of each; the workers' CPU counts where the pool is
reaped).  ``--against`` runs another installation's ``isolator`` in alternation with this tree's
(before/after on a shared machine).  Run from the repository root; this tree's ``isolator`` is the
console script beside this interpreter.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def isolator_command() -> list[str]:
    """The ``isolator`` script beside this interpreter (or the CLI through ``-c``)."""
    script = Path(sys.executable).with_name("isolator")
    return [str(script)] if script.is_file() else [sys.executable, "-c", "from isolator.cli import app; app()"]


def _arguments(args, out: Path) -> list[str]:
    """The review command's arguments (after ``isolator``)."""
    command = ["review", "--design", args.design, "--target", "example", "--suite", "example",
               "-o", str(out / "review.pdf"), "--no-cache"]
    if args.jobs is not None:
        command += ["--jobs", str(args.jobs)]
    for setting in args.set:
        command += ["--set", setting]
    return command


def run_child(command: list[str]) -> tuple[float, float]:
    """(wall, CPU of the child and its workers: user + system) [s]."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(command, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(command)} failed (exit {done.returncode}): {done.stderr.strip()[-800:]}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def _stages(command: list[str], out: Path) -> list[tuple[str, float, float]]:
    """(stage, wall [s], CPU [s]) of one review run in this process (a fresh interpreter, caches warm).

    The CLI itself runs, with timers around the steps it looks up at call time: the suite (reading,
    checks, motion signatures), the review's ELF values, spectra, analyses and checks, matplotlib's
    import, the PDF and JSON.  A stage's CPU is that of the thread it ran in; the analyses' adds the
    worker processes' (reaped when the pool closes).  With a pool, the report's spectra are computed
    while the analyses run (isolator.review.run): their wall times overlap, so "the rest" is
    computed from CPU only.  What remains is start-up (the interpreter excluded) and glue.
    """
    import contextlib
    import importlib
    import io

    wall0, cpu0 = time.perf_counter(), _cpu()
    from isolator.cli import app
    from isolator.report import review_pages
    from isolator.review import assess, run, suite, worker

    spent: dict[str, list[float]] = {}

    def timed(name, function, children: bool = False):
        def wrapper(*args, **kwargs):
            wall, cpu = time.perf_counter(), time.thread_time() + (_children() if children else 0.0)
            try:
                return function(*args, **kwargs)
            finally:
                entry = spent.setdefault(name, [0.0, 0.0])
                entry[0] += time.perf_counter() - wall
                entry[1] += time.thread_time() + (_children() if children else 0.0) - cpu
        return wrapper

    def import_matplotlib():
        for module in ("matplotlib.figure", "matplotlib.backends.backend_pdf"):
            importlib.import_module(module)

    original_pdf = review_pages.write_review_pdf

    def write_pdf(*args, **kwargs):
        timed("import matplotlib", import_matplotlib)()
        return timed("PDF (7 pages) and JSON", original_pdf)(*args, **kwargs)

    suite.load_suite = timed("read the suite, motion signatures", suite.load_suite)
    run.elf_values = timed("ELF values of the bounds", run.elf_values)
    run.pair_spectra = timed("spectra (pairs, RotD100)", run.pair_spectra)
    run.rotd50 = timed("spectra (RotD50)", run.rotd50)
    worker.run_tasks = timed("analyses (parent + workers' CPU)", worker.run_tasks, children=True)
    assess.assess = timed("checks (assess)", assess.assess)
    review_pages.write_review_pdf = write_pdf
    started = time.perf_counter() - wall0, _cpu() - cpu0
    with contextlib.redirect_stdout(io.StringIO()):
        app(command, standalone_mode=False)
    wall, cpu = time.perf_counter() - wall0, _cpu() - cpu0
    rows = [("import isolator.cli", *started)]
    rows += [(name, w, c) for name, (w, c) in spent.items()]
    rest = cpu - sum(r[2] for r in rows)
    return [*rows, ("the rest (start-up of the command, glue)", math.nan, rest),
            ("total (after the interpreter started)", wall, cpu)]


def _children() -> float:
    """CPU time of this process's reaped children (user + system) [s]."""
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return children.ru_utime + children.ru_stime


def _cpu() -> float:
    """CPU time of this process and its reaped children (user + system) [s]."""
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--design", default="data/example_building.toml")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--jobs", type=int, default=None, help="passed on as --jobs (default: the command's)")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="review parameters, passed on (the building needs horizontal_only=true: the example "
                             "suite's Loma Prieta pair has a vertical)")
    parser.add_argument("--stages", action="store_true", help="also time the stages of one more run, in-process")
    parser.add_argument("--against", metavar="ISOLATOR", help="another installation's isolator script (e.g. "
                        "/work/main/.venv/bin/isolator), run in alternation with this tree's")
    parser.add_argument("--in-process", metavar="DIR", help=argparse.SUPPRESS)  # the --stages child
    args = parser.parse_args(argv)
    if args.in_process:
        command = _arguments(args, Path(args.in_process))
        for name, wall, cpu in _stages(command, Path(args.in_process)):
            print(f"  {name:44s} {wall:7.2f} {cpu:7.2f}")
        return 0
    if args.runs < 1:
        parser.error("--runs must be ≥ 1")
    trees = {"this tree": (isolator_command(), sys.executable)}
    if args.against:  # another installation's console script (e.g. main's), its interpreter beside it
        other = Path(args.against).resolve()
        if not other.is_file():
            parser.error(f"--against {args.against}: no such file")
        trees[str(other)] = ([str(other)], str(other.with_name("python")))
    out = Path(tempfile.mkdtemp(prefix="isolator-review-time-"))
    try:
        arguments = _arguments(args, out)
        load_before = os.getloadavg()
        for script, _ in trees.values():
            run_child(script + arguments)  # warm-up
        runs = {name: [] for name in trees}
        for _ in range(args.runs):  # in alternation, so that the machine's load episodes hit both alike
            for name, (script, _) in trees.items():
                runs[name].append(run_child(script + arguments))
        load_after = os.getloadavg()
        stages = {}
        if args.stages:  # a fresh interpreter, the caches warm
            for name, (_, python) in trees.items():
                child = [python, __file__, "--in-process", str(out), "--design", args.design]
                child += [] if args.jobs is None else ["--jobs", str(args.jobs)]
                for setting in args.set:
                    child += ["--set", setting]
                stages[name] = subprocess.run(child, cwd=ROOT, check=True, capture_output=True, text=True).stdout
        timing = {}
        for candidate in out.glob("review*.json"):
            timing = json.loads(candidate.read_text()).get("timing_s", {}) or {}
    finally:
        shutil.rmtree(out, ignore_errors=True)
    print(f"isolator {' '.join(arguments).replace(str(out), 'OUT')}")
    print(f"{args.runs} warm runs after one untimed run{' each, in alternation' if len(trees) > 1 else ''}; "
          f"load average before {load_before}, after {load_after}")
    for name, timed in runs.items():
        walls, cpus = [w for w, _ in timed], [c for _, c in timed]
        print(f"{name}:")
        print(f"  wall [s]: median {statistics.median(walls):.2f}, runs {' '.join(f'{w:.2f}' for w in walls)}")
        print(f"  CPU  [s]: median {statistics.median(cpus):.2f}, runs {' '.join(f'{c:.2f}' for c in cpus)} "
              "(the command and its worker processes)")
        if name in stages:
            print(f"  one more run in-process, by stage {'wall [s]':>18s} {'CPU [s]':>7s}")
            print(stages[name], end="")
    if timing:
        print("stages of the last run (the review's JSON, timing_s):")
        for key, value in timing.items():
            if isinstance(value, (int, float)):
                print(f"  {key:40s} {value:.3f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
