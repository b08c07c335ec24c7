"""``batch``: many records × many designs into one table, resumable, locally or on Dask."""

from __future__ import annotations

import typer

from isolator.cli.common import (
    RECORD_HELP,
    app,
    check_outputs,
    echo_table,
    error_line,
    say,
    user_error,
    write_error,
)
from isolator.cli.pairs import PAIR_HELP


@app.command()
def batch(
    records: list[str] = typer.Argument(..., help="Record files, folders (searched recursively) or glob patterns."),
    designs: str = typer.Option(..., "--designs", "-d", help="TOML file with a list of [[design]] tables "
                                "(the keys of a design file)."),
    grid: list[str] = typer.Option(None, "--grid", help="KEY=START:STOP:COUNT: sweep a numeric design key over "
                                   "COUNT values from START to STOP inclusive, for every design (repeatable: "
                                   "the cartesian product)."),
    units: str = typer.Option(None, "--units", "-u", help="Units of the records whose file does not state them "
                              "(text, MiniSEED …): g, m/s2, gal or cm/s2.  Files that state theirs are read as "
                              "they say."),
    component: str = typer.Option(None, "--component", "-c", help=RECORD_HELP["component"] + "  Or 'pair' "
                                  "(the default for a file with two horizontal components: CSMIP V2, MiniSEED "
                                  "streams, K-NET sets; and for two one-component files of one station and event, "
                                  "e.g. PEER AT2, given together; a coupled 2-D analysis), 'all' (with the "
                                  "vertical), or 'all-horizontal': every horizontal component alone."),
    dt: float = typer.Option(None, "--dt", help="Time step [s] of the one-column text records that give none "
                             "(other files keep their own)."),
    trim: bool = typer.Option(False, "--trim", help=PAIR_HELP["trim"]),
    resample: bool = typer.Option(False, "--resample", help=PAIR_HELP["resample"]),
    scale_to_pga: float = typer.Option(None, "--scale-to-pga", help="Scale every record to this peak ground "
                                       "acceleration, in g."),
    output: str = typer.Option(..., "--output", "-o", help="Table to write: .csv or .parquet."),
    jobs: int = typer.Option(None, "--jobs", "-j", min=1, help="Local processes (default: the idle cores)."),
    scheduler: str = typer.Option(None, "--scheduler", help="Run on an existing dask.distributed cluster, "
                                  "e.g. tcp://10.0.0.5:8786."),
    reports: str = typer.Option(None, "--reports", help="Also write the PDF report of every row in this folder "
                                "(slow)."),
    summary: str = typer.Option(None, "--summary", help="Write the per-design suite summary (CSV)."),
    chart: str = typer.Option(None, "--chart", help="Write the design chart of a grid sweep (PDF): contours of "
                              "peak displacement and transmitted acceleration over the first two swept keys."),
    map_resolution: int = typer.Option(30, "--map-resolution", min=8, max=400,
                                       help="Regime-map resolution of the --reports pages."),
    no_harmonic: bool = typer.Option(False, "--no-harmonic", help="Skip the harmonic classification at the "
                                     "equivalent point (most of the time of a large sweep); its columns stay "
                                     "empty."),
) -> None:
    """Many records × many designs into one table: resumable, parallel, locally or on Dask.

    One row per (record, component, design) with the record's provenance and intensity
    measures, the design, the paper's point (k, α, η), every result of `simulate`, the
    record and harmonic classifications, the solver time and an `error` column.  Rows are
    saved as tasks finish (OUTPUT.parts/); run the same command again to resume.  Exit
    code 1 if any row failed, 2 for a mistake in the command.
    """
    import math
    import os
    import sys

    from isolator.batch import BatchError, ReadOptions, parse_grid, run_batch
    from isolator.motion import MAX_ABS_ACCELERATION_G
    from isolator.motion.ground_motion import MIN_TARGET_PGA_G
    from isolator.motion.read import dt_problem

    try:
        grids = [parse_grid(spec) for spec in grid or []]
        if len({key for key, _ in grids}) != len(grids):
            raise BatchError("--grid: each key may be swept once")
        _refuse_grid_of_replaced_keys(designs, grids)
        if dt is not None and not (math.isfinite(dt) and dt > 0):
            raise BatchError(f"--dt must be a time step > 0 in seconds, got {dt:g}")
        if dt is not None and dt_problem(dt):
            raise BatchError(f"--dt: {dt_problem(dt)}")
        if scale_to_pga is not None and not MIN_TARGET_PGA_G <= scale_to_pga <= MAX_ABS_ACCELERATION_G:
            raise BatchError(f"--scale-to-pga must lie in [{MIN_TARGET_PGA_G:g}, {MAX_ABS_ACCELERATION_G:g}] g, "
                             f"got {scale_to_pga:g}")
        if scheduler is not None:
            from isolator.parallel import check_scheduler

            check_scheduler(scheduler)
        if units is not None:
            from isolator.units import UnitsError, acceleration_factor_to_m_s2

            try:
                acceleration_factor_to_m_s2(units)
            except UnitsError as err:
                raise BatchError(f"--units: {err}") from None
        for path, suffix in ((summary, ".csv"), (chart, ".pdf")):
            if path is not None and not path.lower().endswith(suffix):
                raise BatchError(f"{path}: must end with {suffix}")
        if chart is not None and len(grids) < 2:
            raise BatchError("--chart needs a grid sweep over two keys (two --grid options)")
        if trim and resample:
            raise BatchError("--trim and --resample both align the components of a pair: give one")
        for flag, path in (("--summary", summary), ("--chart", chart)):
            if path is not None and os.path.realpath(path) == os.path.realpath(output):
                raise BatchError(f"{flag} {path} is the table -o {output}: give each output its own file")
    except BatchError as err:
        user_error(error_line(err))
    check_outputs([output, summary, chart], [designs, *records])
    if jobs is not None:  # more processes than cores only add memory and contention (-j 100000 forked 1,539)
        from isolator.parallel import capped_workers

        jobs, note = capped_workers(jobs)
        if note:
            say(f"note: {note}")
    options = ReadOptions(units=units, scale_to_pga_g=scale_to_pga, dt_s=dt, harmonic=not no_harmonic, trim=trim,
                          resample=resample)

    progress_bar, callback = None, None
    if sys.stderr.isatty():
        from rich.console import Console
        from rich.progress import (
            BarColumn,
            MofNCompleteColumn,
            Progress,
            ProgressColumn,
            TextColumn,
            TimeElapsedColumn,
            TimeRemainingColumn,
        )
        from rich.text import Text

        class RateColumn(ProgressColumn):
            def render(self, task):
                speed = task.finished_speed or task.speed
                return Text(f"{speed:.1f} rows/s" if speed else "… rows/s")

        progress_bar = Progress(TextColumn("batch"), BarColumn(), MofNCompleteColumn(), TextColumn("rows"),
                                RateColumn(), TimeElapsedColumn(), TextColumn("left"), TimeRemainingColumn(),
                                console=Console(stderr=True), transient=True)
        bar_task = progress_bar.add_task("batch", total=None)

        def callback(total=None, completed=None, advance=None):
            if total is not None:
                progress_bar.update(bar_task, total=total, completed=completed or 0)
            if advance:
                progress_bar.advance(bar_task, advance)

        progress_bar.start()
    try:
        result = run_batch(records, designs, output, grids=grids, component=component, options=options,
                           jobs=jobs, scheduler=scheduler, reports_dir=reports, map_resolution=map_resolution,
                           progress=callback, extra_outputs=[summary, chart])
    except BatchError as err:
        if progress_bar is not None:
            progress_bar.stop()
        user_error(error_line(err))
    except OSError as err:  # an output that is an input, locked by another run, or unwritable
        if progress_bar is not None:
            progress_bar.stop()
        write_error(err, output)
    except KeyboardInterrupt:
        if progress_bar is not None:
            progress_bar.stop()
        typer.echo(f"interrupted: finished rows are kept in {output}.parts/; run the same command again to resume",
                   err=True)
        raise typer.Exit(130) from None
    if progress_bar is not None:
        progress_bar.stop()
    for message in result.lost_messages:
        say(f"lost: {message}")
    for note in result.notes:
        say(f"note: {note}")
    rows = [("table", result.output, f"({len(result.table.columns)} columns)")]
    if result.n_resumed:
        rows.append(("resumed", f"{result.n_resumed} rows", "(done by an earlier run)"))
    seconds = result.seconds
    rows.append(("time", f"{sum(seconds.values()):.3g} s", f"(plan {seconds['plan']:.2g} s, compute "
                                                          f"{seconds['compute']:.3g} s, write {seconds['write']:.2g} s)"))
    if result.n_failed:
        first = result.table.loc[result.table["error"] != "", "error"].iloc[0]
        rows.append(("first error", first, ""))
    if summary is not None or chart is not None:
        from isolator.batch import design_chart, suite_summary, write_table_atomically

        swept = [key for key, _ in grids]
        try:
            if summary is not None:
                write_table_atomically(suite_summary(result.table, swept), summary, keyed=True)
                rows.append(("summary", summary, ""))
            if chart is not None:
                pages = design_chart(result.table, swept[:2], chart)
                rows.append(("chart", chart, f"({pages} pages)"))
        except OSError as err:
            write_error(err, summary if chart is None else chart)
    echo_table(rows)
    typer.echo(result.final_line())
    if result.n_failed or result.n_lost_tasks:
        raise typer.Exit(1)


def _refuse_grid_of_replaced_keys(designs_file: str, grids) -> None:
    """A --grid of a key every design's [bearing] replaces (radius, friction, capacity) made every row fail alike,
    exit 1 after the whole batch (``--grid mu_static=…`` over triple pendulums; session 13 sweep): one line instead,
    as ``design --vary`` (session 10).  A designs file with any design that keeps the key sweeps it as before."""
    from isolator.batch import BatchError, load_design_mappings
    from isolator.bearing import REPLACED_DESIGN_KEYS

    replaced = [key for key, _ in grids if key in REPLACED_DESIGN_KEYS]
    if not replaced:
        return
    mappings = load_design_mappings(designs_file)
    if all(isinstance(m, dict) and "bearing" in m for m in mappings):
        raise BatchError(f"--grid {replaced[0]}: every design of {designs_file} gives its bearing surface by surface "
                         f"([bearing]), whose [[bearing.surface]] entries replace '{replaced[0]}': sweep a key the "
                         "designs keep (mass_kg, damping_ratio, the property factors)")
