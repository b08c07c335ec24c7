"""``bench``: speed against error of our exact solver and classical methods."""

from __future__ import annotations

import typer

from isolator.cli.common import app, check_outputs, echo_json, say, user_error, write_error

#: What `bench` writes into --out.
BENCH_FILES = ("bench.csv", "bench_pareto.csv", "bench.json", "bench.md", "bench.png")
#: The most runs of a timing: the medians of docs/bench.md take 3 (quick) or 5 (full); the quick bench at one run
#: is 32 runs in 8.0 s (docs/security.md, Session 10 sweep), so 20 is minutes, and `--repeats 1000000000` ran on
#: without end (Session 16 sweep).
MAX_REPEATS = 20


@app.command()
def bench(
    quick: bool = typer.Option(False, "--quick", help="A representative subset (under a minute)."),
    as_json: bool = typer.Option(False, "--json", help="Print the rows as one JSON list instead of tables."),
    out: str = typer.Option("reports/bench", "--out", help="Folder for bench.csv, bench_pareto.csv, bench.json, "
                                                            "bench.md and bench.png."),
    records: str = typer.Option("../shared/records", "--records", help="Folder of the records of the bench "
                                "(at2/RSN1044_NORTHR_NWH360.AT2, pairs/superstitionhills1987_PTS/…, "
                                "as in ../shared/records)."),
    repeats: int = typer.Option(None, "--repeats", min=1,
                                help=f"Runs per timing (median, at most {MAX_REPEATS}); default 3 quick, 5 full."),
) -> None:
    """Speed against error: our exact solver against fixed-step, Newmark, solve_ivp and OpenSees.

    Runs the harmonic cases of every configuration, friction-pendulum records, real
    pairs in 2-D (against OpenSees' singleFPBearing when openseespy imports) and a
    5-story building on a friction pendulum and a triple friction pendulum (against
    OpenSees' models of the same), times
    every method (median of several runs, in this process) and measures the errors of
    peak and residual displacement, slip-time ratio and trajectory; writes the table
    (CSV, JSON, Markdown) and a log error / log time plot to --out.
    """
    if repeats is not None and repeats > MAX_REPEATS:  # click's own refusal named the bound, not why (session 16)
        user_error(f"--repeats {repeats} is more than {MAX_REPEATS} runs per timing: the docs' medians take 3 "
                   "(quick) or 5 (full, the default), and each run repeats the whole bench (8 s for the quick one)")
    for flag, given in (("--out", out), ("--records", records)):  # Path('') is '.': the bench ran on the working folder
        if not given:
            user_error(f"{flag} '': a folder is named by a path (give . for the working folder)")
    if out == "-":  # a folder named '-' was made and written
        user_error("--out - : --out is a folder for five files, not standard output; print the rows with --json")
    import os
    import platform
    import time
    from pathlib import Path

    from isolator import bench as bench_module
    from isolator.atomic import atomic_paths
    from isolator.serialize import dumps

    records_dir = Path(records)
    if not records_dir.is_dir():  # a file was told "no such folder"
        what = "is a file, not a folder" if records_dir.exists() else "no such folder"
        user_error(f"{records}: {what} of records (give the folder of the bench records with --records)")
    out_dir = Path(out)
    if out_dir.exists() and not out_dir.is_dir():  # mkdir said "File exists" of the file it would not replace
        user_error(f"--out {out}: is a file, not a folder (--out is the folder for {', '.join(BENCH_FILES)})")
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        user_error(f"{out}: cannot create the output folder ({err.strerror or err})")
    # --out may be the records folder itself: none of the five files may replace a record.  An output is a record
    # when it resolves into the records' tree (walking that tree was unbounded, and --records / met /proc's
    # unreadable links with a traceback)
    root = os.path.realpath(records_dir)
    outputs = [out_dir / name for name in BENCH_FILES]
    check_outputs(outputs, [path for path in outputs if os.path.isfile(path) and os.path.commonpath(
        [root, os.path.realpath(path)]) == root])
    started = time.perf_counter()
    progress = None if as_json else say
    from isolator.bench.opensees import opensees_available

    available, why = opensees_available()
    if not available:  # said by no line: the bench's progress claimed "ours and OpenSees" (session 23 sweep)
        say(f"note: {why}: the OpenSees baselines are left out, ours is timed alone (pip install "
            "\"isolator[bench]\" for them)")
    cases = bench_module.bench_cases(quick, records_dir)
    if not any(case.kind == "record" for case in cases):
        say(f"note: none of the bench records in {records_dir}: harmonic cases only")
    elif not any(case.kind == "pair" for case in cases):
        say(f"note: none of the bench pairs in {records_dir}/pairs: no 2-D cases")
    rows, pareto = bench_module.run_bench(quick=quick, repeats=repeats, cases=cases, progress=progress)
    building_cases = bench_module.building_cases(quick, records_dir)
    if not building_cases:
        say(f"note: the building's record is not in {records_dir}: no building case")
    buildings = [bench_module.run_building_case(case, rounds=repeats or (3 if quick else 5), progress=progress)
                 for case in building_cases]
    building_lines = bench_module.building_summary(buildings)
    tfps = [bench_module.run_tfp_case(case, rounds=repeats or (3 if quick else 5), progress=progress)
            for case in bench_module.tfp_cases(quick, records_dir)]
    building_lines += bench_module.tfp_summary(tfps)
    wall_s = time.perf_counter() - started
    machine = {"platform": platform.platform(), "processor": platform.processor() or platform.machine(),
               "cpus": os.cpu_count(), "python": platform.python_version()}
    try:
        import numpy
        import scipy

        machine.update(numpy=numpy.__version__, scipy=scipy.__version__)
    except ImportError:  # pragma: no cover - both are dependencies
        pass
    command = "isolator bench" + (" --quick" if quick else "")
    summary = bench_module.opensees_summary(pareto)
    try:
        load = os.getloadavg()
        machine["load_average_1_5_15"] = [round(x, 2) for x in load]
    except OSError:  # pragma: no cover - not on every platform
        pass
    document = {"command": command, "wall_seconds": wall_s, "machine": machine, "rows": rows, "pareto": pareto,
                "summary_2d": summary, "building": buildings, "triple_friction_pendulum": tfps,
                "summary_building": building_lines}
    texts = {"bench.csv": bench_module.rows_to_csv(rows), "bench_pareto.csv": bench_module.pareto_to_csv(pareto),
             "bench.json": dumps(document, indent=1),
             "bench.md": bench_module.pareto_markdown(pareto) + "\n" + bench_module.rows_markdown(rows)
             + "".join(f"\n{line}\n" for line in summary)
             + ("\n" + bench_module.building_markdown(buildings) if buildings else "")
             + "".join(f"\n{line}\n" for line in building_lines)}
    try:  # one set, renamed at once: each file was renamed in turn, so an interrupt mixed two benches' files
        with atomic_paths(outputs) as temporaries:
            for name, temporary in zip(BENCH_FILES, temporaries, strict=True):
                if name in texts:
                    temporary.write_text(texts[name], encoding="utf-8")
                else:
                    bench_module.plot(rows, temporary)
    except OSError as err:
        write_error(err, out)
    if as_json:
        echo_json(rows)
        return
    typer.echo(bench_module.pareto_markdown(pareto))
    typer.echo(bench_module.rows_markdown(rows))
    for line in summary:
        typer.echo(line)
    if buildings:
        typer.echo(bench_module.building_markdown(buildings))
    for line in building_lines:
        typer.echo(line)
    typer.echo(f"{len(rows)} runs in {wall_s:.1f} s on {machine['processor']} ({machine['cpus']} CPUs); "
               f"written to {out_dir}/bench.csv, bench_pareto.csv, bench.json, bench.md, bench.png")
