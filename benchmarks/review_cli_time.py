"""Wall and CPU time of the README's review command, as a user runs it: a fresh process, launch to exit.

    .venv/bin/python benchmarks/review_cli_time.py --set horizontal_only=true   # data/example_building.toml
    .venv/bin/python benchmarks/review_cli_time.py --design data/example_review.toml --runs 7

Runs ``isolator review --design DESIGN --target example --suite example -o TMP/review.pdf --no-cache``
once untimed (numba's compiled functions and the regime map's disk cache loaded: "warm"), then
``--runs`` times; ``--no-cache`` makes every run analyse every pair and bound again (without it a
rerun is served from the analysis cache in a few tenths of a second).  Prints the median, the
runs, the load average before and after, and the stages of the last run from the review's JSON
(``timing``).  Run from the repository root; the worktree's ``isolator`` is the one on PATH of
this interpreter's environment.
"""

from __future__ import annotations

import argparse
import json
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


def _isolator() -> list[str]:
    script = Path(sys.executable).with_name("isolator")
    return [str(script)] if script.is_file() else [sys.executable, "-c", "from isolator.cli import app; app()"]


def _run(command: list[str]) -> tuple[float, float]:
    """(wall, CPU of the child and its workers: user + system) [s]."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(command, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(command)} failed (exit {done.returncode}): {done.stderr.strip()[-800:]}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--design", default="data/example_building.toml")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--jobs", type=int, default=None, help="passed on as --jobs (default: the command's)")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="review parameters, passed on (the building needs horizontal_only=true: the example "
                             "suite's Loma Prieta pair has a vertical)")
    args = parser.parse_args(argv)
    if args.runs < 1:
        parser.error("--runs must be ≥ 1")
    out = Path(tempfile.mkdtemp(prefix="isolator-review-time-"))
    try:
        command = _isolator() + ["review", "--design", args.design, "--target", "example", "--suite", "example",
                                 "-o", str(out / "review.pdf"), "--no-cache"]
        if args.jobs is not None:
            command += ["--jobs", str(args.jobs)]
        for setting in args.set:
            command += ["--set", setting]
        load_before = os.getloadavg()
        _run(command)  # warm-up
        runs = [_run(command) for _ in range(args.runs)]
        load_after = os.getloadavg()
        timing = {}
        for candidate in out.glob("review*.json"):
            timing = json.loads(candidate.read_text()).get("timing", {}) or {}
    finally:
        shutil.rmtree(out, ignore_errors=True)
    walls, cpus = [w for w, _ in runs], [c for _, c in runs]
    print(f"isolator {' '.join(command[len(_isolator()):]).replace(str(out), 'OUT')}")
    print(f"{args.runs} warm runs after one untimed run; load average before {load_before}, after {load_after}")
    print(f"wall [s]: median {statistics.median(walls):.2f}, runs {' '.join(f'{w:.2f}' for w in walls)}")
    print(f"CPU  [s]: median {statistics.median(cpus):.2f}, runs {' '.join(f'{c:.2f}' for c in cpus)} "
          "(the command and its worker processes)")
    if timing:
        print("stages of the last run (the review's JSON, timing):")
        for key, value in timing.items():
            if isinstance(value, (int, float)):
                print(f"  {key:40s} {value:.3f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
