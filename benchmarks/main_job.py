"""Wall time of the README's main job and of ``isolator --help``, warm, median of N runs.

Run from the repository root (``PYTHONPATH`` is passed on, so a worktree's ``isolator`` wins)::

    .venv/bin/python benchmarks/main_job.py            # 5 runs each
    .venv/bin/python benchmarks/main_job.py --runs 9
    .venv/bin/python benchmarks/main_job.py --stages   # and the CPU time of each stage of one run
    .venv/bin/python benchmarks/main_job.py --against ../main/.venv/bin/isolator   # before/after, alternated

Each run is a fresh ``isolator`` process, launch to exit, as a user types it; the wall time
is what the user waits, the CPU time (user + system of the child) what the process spent,
which other jobs on a shared machine disturb less.  One untimed
run first fills the caches a second run of the same command finds (numba's compiled
functions on disk, the regime map under ``$ISOLATOR_CACHE_DIR``): "warm" means that.  The
report goes to a temporary folder, not to ``reports/``.  The load average is printed
before and after: on a shared machine, compare medians taken at similar loads.
"""

from __future__ import annotations

import argparse
import os
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MAIN_JOB = ["report", "--design", "data/example_pendulum.toml", "example:knet", "--scale-to-pga", "0.3",
            "-o", "{out}/example.pdf"]
HEAVY = ("numpy", "scipy", "obspy", "matplotlib", "numba", "dask", "pandas")


def _isolator_command() -> list[str]:
    """The ``isolator`` console script of this interpreter's environment, else the module entry."""
    script = Path(sys.executable).with_name("isolator")
    if script.is_file():
        return [str(script)]
    return [sys.executable, "-c", "from isolator.cli import app; app()"]


def _time(command: list[str]) -> tuple[float, float]:
    """(wall time, CPU time of the child: user + system) [s] of one run, launch to exit."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(command, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall_s = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(command)} failed (exit {done.returncode}): {done.stderr.strip()[-500:]}")
    cpu_s = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall_s, cpu_s


def _heavy_modules_after_import() -> list[str]:
    """Which of the heavy libraries ``import isolator`` loads (should be none)."""
    code = (f"import sys, isolator; heavy = {HEAVY!r}; "
            "print(' '.join(sorted(m for m in heavy if m in sys.modules)))")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True)
    return done.stdout.split()


def _stages(out: Path) -> list[tuple[str, float]]:
    """CPU time [s] of the main job's stages, in this process: the CLI itself, with timers around its steps.

    The steps are wrapped where the ``report`` command looks them up (reading the record,
    the analysis, the PDF); what remains is start-up: the interpreter, the CLI, and the
    imports of numpy, numba (and its first compiled call) and obspy on the way.
    """
    import contextlib
    import importlib
    import io

    start = time.process_time()
    from isolator import analysis
    from isolator.cli import app, report
    from isolator.report import pdf

    spent: dict[str, float] = {}

    def timed(name, function):
        def wrapper(*args, **kwargs):
            begin = time.process_time()
            try:
                return function(*args, **kwargs)
            finally:
                spent[name] = spent.get(name, 0.0) + time.process_time() - begin
        return wrapper

    def write_report(*args, **kwargs):
        begin = time.process_time()
        for module in ("matplotlib.figure", "matplotlib.backends.backend_pdf"):
            importlib.import_module(module)
        spent["import matplotlib"] = time.process_time() - begin
        return timed("render the 4 pages, write PDF and JSON", original_write)(*args, **kwargs)

    original_write = pdf.write_report
    report.load_record_for_cli = timed("read the record (obspy)", report.load_record_for_cli)
    analysis.analyse = timed("analyse: IMs, solver, harmonic map", analysis.analyse)
    pdf.write_report = write_report
    with contextlib.redirect_stdout(io.StringIO()):
        app([part.format(out=out) for part in MAIN_JOB], standalone_mode=False)
    total = time.process_time() - start
    return [("start-up: CLI, numpy, numba, obspy imports", total - sum(spent.values())), *spent.items(),
            ("total (this process, after the interpreter started)", total)]


def _row(name: str, values: list[float]) -> str:
    runs = " ".join(f"{v:.2f}" for v in values)
    return f"{name:52s} {statistics.median(values):7.2f} {min(values):7.2f} {max(values):7.2f}   {runs}"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5, help="timed runs of each command (default 5)")
    parser.add_argument("--stages", action="store_true", help="also print the CPU time of each stage of one run")
    parser.add_argument("--in-process", metavar="DIR", help=argparse.SUPPRESS)  # the --stages child
    parser.add_argument("--against", metavar="ISOLATOR", help="another installation's isolator script (e.g. "
                        "../main/.venv/bin/isolator), run in alternation with this tree's")
    args = parser.parse_args(argv)
    if args.in_process:
        for name, seconds in _stages(Path(args.in_process)):
            print(f"  {name:52s} {seconds:6.2f}")
        return 0
    if args.runs < 1:
        parser.error("--runs must be ≥ 1")
    isolator = _isolator_command()
    trees = {"": isolator}
    if args.against:  # another installation (e.g. main's), run in alternation with this tree
        if not Path(args.against).is_file():
            parser.error(f"--against {args.against}: no such file")
        trees[" (--against)"] = [str(Path(args.against).resolve())]
    out = Path(tempfile.mkdtemp(prefix="isolator-main-job-"))
    timed: dict[str, list] = {}
    try:
        load_before = os.getloadavg()[0]
        for script in trees.values():
            _time(script + [part.format(out=out) for part in MAIN_JOB])  # warm-up: numba cache, map cache
        for _ in range(args.runs):  # in alternation: the machine's load episodes hit every tree alike
            for label, script in trees.items():
                timed.setdefault(f"isolator report (main job){label}", []).append(
                    _time(script + [part.format(out=out) for part in MAIN_JOB]))
        for _ in range(args.runs):
            for label, script in trees.items():
                timed.setdefault(f"isolator --help{label}", []).append(_time(script + ["--help"]))
        load_after = os.getloadavg()[0]
        pdf_bytes = (out / "example.pdf").stat().st_size
        stages = ""
        if args.stages:  # a fresh process, the caches warm
            stages = subprocess.run([sys.executable, __file__, "--in-process", str(out)], cwd=ROOT, check=True,
                                    capture_output=True, text=True).stdout
    finally:
        shutil.rmtree(out, ignore_errors=True)
    print(f"main job: isolator {' '.join(MAIN_JOB).format(out='OUT')}")
    print(f"{args.runs} warm runs each after one warm-up; {platform.python_implementation()} "
          f"{platform.python_version()}, {os.cpu_count()} CPUs, load average {load_before:.2f} before, "
          f"{load_after:.2f} after")
    if args.against:
        print(f"--against: {args.against}")
    print(f"{'launch to exit [s]':52s} {'median':>7s} {'min':>7s} {'max':>7s}   runs")
    for name, runs in timed.items():
        print(_row(f"{name}, wall", [wall for wall, _ in runs]))
        print(_row(f"{name}, CPU", [cpu for _, cpu in runs]))
    if stages:
        print("CPU time by stage, one run [s]:")
        print(stages, end="")
    heavy = _heavy_modules_after_import()
    loaded = ", ".join(heavy) if heavy else "none of " + ", ".join(HEAVY)
    print(f"PDF size {pdf_bytes / 1024:.0f} KiB; `import isolator` loads: {loaded}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
