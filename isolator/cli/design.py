"""``isolator design``: option checks, progress and one-line errors over :mod:`isolator.review.design_space`."""

from __future__ import annotations

from pathlib import Path

import typer

from isolator.cli.common import (
    app,
    check_given_scale_factors,
    check_outputs,
    check_pdf_output,
    collector_skips_existing_objects,
    echo_table,
    parse_set,
    refuse_record_flags_for_a_suite_file,
    say,
    write_error,
)
from isolator.cli.common import user_error as _user_error

#: the flag of each parameter a design-search error may name
FLAGS = {"vary": "--vary", "objective": "--objective", "code": "--code", "scaling": "--scaling",
         "scheduler": "--scheduler"}


def _search_error(err) -> None:
    flag = FLAGS.get(getattr(err, "parameter", ""), "")
    _user_error(f"{flag} {err}" if flag else str(err))


def _progress_bar():
    """A rich progress bar on stderr (only when stderr is a terminal), and its callback."""
    import sys

    if not sys.stderr.isatty():
        return None, None
    from rich.console import Console
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    bar = Progress(TextColumn("design"), BarColumn(), MofNCompleteColumn(), TextColumn("candidates"),
                   TimeElapsedColumn(), TextColumn("left"), TimeRemainingColumn(), console=Console(stderr=True),
                   transient=True)
    task = bar.add_task("design", total=None)

    def callback(done, total):
        bar.update(task, total=total, completed=done)

    bar.start()
    return bar, callback


@app.command("design")
def design(
    target: str = typer.Option(..., "--target", "-t", help="TARGET.toml, or `example` for the bundled MCE_R target."),
    suite: list[str] = typer.Option(..., "--suite", "-s", help="SUITE.toml, or record files, folders and globs "
                                    "(repeatable); `example` for the bundled suite."),
    isolator_file: str = typer.Option(..., "--isolator", "--design", "-d", help="Design file (TOML) as for "
                                      "`isolator review`; each --vary replaces one of its numbers."),
    vary: list[str] = typer.Option(..., "--vary", help="KEY=START:STOP:COUNT (both ends included) or "
                                   "KEY=V1,V2,… (repeatable; the first two are the chart's axes), e.g. "
                                   "radius_m=1.5:4.5:13 mu_kinetic=0.03:0.12:10."),
    code: str = typer.Option("asce7-22", "--code", help="asce7-22 or en15129."),
    scaling: str = typer.Option(None, "--scaling", help="common, fit or given (as for `isolator review`; default: "
                                "given when every pair of the suite gives its scale_factor, else common)."),
    objective: str = typer.Option("base_shear", "--objective", help="What the recommendation minimises among "
                                  "the candidates that pass every check: base_shear, displacement or residual."),
    output: str = typer.Option(None, "--output", "-o", help="Chart PDF (default reports/design_DESIGN.pdf); "
                               "the table (.csv, .parquet, .json) and the recommended review "
                               "(NAME.recommended.pdf/.json) beside it, finished candidates in .NAME.design/."),
    as_json: bool = typer.Option(False, "--json", help="Print the search's JSON on stdout."),
    jobs: int = typer.Option(None, "--jobs", "-j", help="Local worker processes (default: the idle cores)."),
    scheduler: str = typer.Option(None, "--scheduler", help="Dask scheduler address (instead of local processes)."),
    settings: list[str] = typer.Option(None, "--set", help="Review parameter NAME=VALUE (see docs/review.md)."),
    units: str = typer.Option(None, "--units", "-u", help="Units of records that do not state them."),
    trim: bool = typer.Option(False, "--trim", help="Trim the components of a pair to their common span."),
    no_resume: bool = typer.Option(False, "--no-resume", help="Review every candidate again (the store of "
                                   "finished candidates is not read; it is rewritten)."),
) -> None:
    """Review every candidate of a design space as `isolator review` does; chart the trade-off, recommend one.

    Each candidate (the product of the --vary ranges) gets its own ELF values and period range, the suite scaled
    for that range, every pair at both bounds and every check.  See docs/design_search.md.
    """
    import json
    import shlex
    import sys
    import time

    from isolator.atomic import OutputError, output_lock
    from isolator.errors import DesignError, RecordError, ReviewError, UnitsError
    from isolator.review.design_grid import OBJECTIVES, parse_vary
    from isolator.review.design_outputs import output_paths
    from isolator.review.examples import resolve_example
    from isolator.review.run import CODES
    from isolator.review.scaling import SCALING_METHODS

    if code not in CODES:
        _user_error(f"--code must be one of {', '.join(CODES)}, got {code!r}")
    if scaling is not None and scaling not in SCALING_METHODS:
        _user_error(f"--scaling must be one of {', '.join(SCALING_METHODS)}, got {scaling!r}")
    if objective not in OBJECTIVES:
        _user_error(f"--objective must be one of {', '.join(OBJECTIVES)}, got {objective!r}")
    if jobs is not None and jobs < 1:
        _user_error(f"--jobs must be ≥ 1, got {jobs}")
    if jobs is not None:  # as review and batch: --jobs 10**8 forked one process per candidate, up to 20,000 (h203)
        from isolator.parallel import capped_workers

        jobs, note = capped_workers(jobs)
        if note:
            say(f"note: {note}")
    try:
        ranges = [parse_vary(spec) for spec in vary]
    except ReviewError as err:
        _search_error(err)
    if output is None:
        output = str(Path("reports") / f"design_{Path(isolator_file).stem}.pdf")
    check_pdf_output(output)
    if scheduler is not None:
        from isolator.batch.executors import check_scheduler
        from isolator.errors import BatchError

        try:
            check_scheduler(scheduler)
        except BatchError as err:
            _user_error(f"--scheduler {err}")
    parameters = parse_set(settings)
    paths = output_paths(output)
    try:
        from isolator.review.parameters import resolve
        from isolator.review.suite import load_suite
        from isolator.review.target import load_target

        resolve(code, parameters)
        target_path = resolve_example("target", target)
        suite_args = [resolve_example("suite", s) for s in suite]
        refuse_record_flags_for_a_suite_file(suite_args, units, trim)
        inputs = [isolator_file, target_path, *suite_args]
        check_outputs([str(p) for k, p in paths.items() if k != "store"], [p for p in inputs if Path(p).is_file()])
        _refuse_varying_replaced_keys(isolator_file, ranges)
        the_target = load_target(target_path)
        the_suite = load_suite(suite_args, units=units, trim=trim)
        # the files a SUITE.toml lists and the target's table are inputs too: `-o rec.pdf` wrote its table rec.csv
        # over a suite record rec.csv (Session 15 sweep, docs/security.md)
        from isolator.cli.review import review_inputs

        check_outputs([str(p) for k, p in paths.items() if k != "store"],
                      [str(p) for p in review_inputs(the_target, target_path, the_suite)])
        check_given_scale_factors(the_suite)
    except (DesignError, ReviewError, RecordError, UnitsError) as err:
        _user_error(str(err))

    from isolator.review.design_outputs import write_outputs
    from isolator.review.design_space import search

    command = "isolator " + " ".join(shlex.quote(arg) for arg in sys.argv[1:])
    bar, callback = None, None
    clock = time.perf_counter()
    try:
        with output_lock(paths["chart"]):
            if no_resume and paths["store"].is_dir():
                for stale in paths["store"].glob("*.json"):
                    stale.unlink()
            bar, callback = _progress_bar()
            try:
                # the collector skips numba's and obspy's objects: each review makes many small ones (its rows),
                # and the forked workers inherit the frozen generation
                with collector_skips_existing_objects():
                    result = search(isolator_file, the_target, the_suite, ranges, objective=objective, code=code,
                                    scaling=scaling, parameters=parameters, jobs=jobs, scheduler=scheduler,
                                    store_dir=paths["store"], progress=callback)
            finally:
                if bar is not None:
                    bar.stop()
            out = write_outputs(result, output, the_target, the_suite, command=command, jobs=jobs,
                                scheduler=scheduler)
    except (DesignError, ReviewError) as err:
        _search_error(err)
    except OutputError as err:
        write_error(err, output)
    except KeyboardInterrupt:
        typer.echo(f"interrupted: finished candidates are kept in {paths['store']}/; run the same command again "
                   "to resume", err=True)
        raise typer.Exit(130) from None
    if as_json:
        typer.echo(json.dumps(out, indent=2))
    else:
        best = out["recommended"]
        rows = [("chart", out["outputs"]["chart"], f"({out['outputs']['chart_pages']} pages)"),
                ("table", out["outputs"]["csv"], f"(+ .parquet, .json; {out['n_candidates']} candidates)")]
        if out["n_resumed"]:
            rows.append(("resumed", f"{out['n_resumed']} candidates", "(done by an earlier run)"))
        rows.append(("passing", f"{out['n_passing']} of {out['n_candidates']}",
                     f"({out['n_errors']} could not be analysed)" if out["n_errors"] else ""))
        if best is None:
            rows.append(("recommended", "none", "(no candidate passes every check)"))
        else:
            varied = ", ".join(f"{k} = {best[k]:.4g}" for k in out["vary"])
            rows += [("recommended", varied, f"({objective}: {out['objective_column']} = "
                                             f"{best[out['objective_column']]:.4g})"),
                     ("review", out["outputs"]["recommended_pdf"], f"(+ {out['outputs']['recommended_json']})")]
        rows.append(("time", f"{time.perf_counter() - clock:.3g} s", ""))
        echo_table(rows)
    if result.n_lost:
        typer.echo(f"lost: {result.n_lost} candidates (a worker died); run the same command again to retry them",
                   err=True)
        raise typer.Exit(1)


def _refuse_varying_replaced_keys(isolator_file: str, ranges) -> None:
    """A design given surface by surface ([bearing]) has no top-level radius, friction or capacity: varying one
    made every candidate fail alike ("could not be analysed"), exit 0, instead of one line (session 10 sweep)."""
    from isolator.bearing import REPLACED_DESIGN_KEYS
    from isolator.design import load_toml
    from isolator.errors import DesignError

    mapping = load_toml(isolator_file, "design file", DesignError)
    replaced = [key for key, _ in ranges if key in REPLACED_DESIGN_KEYS]
    if isinstance(mapping, dict) and "bearing" in mapping and replaced:
        raise DesignError(f"--vary {replaced[0]}: {isolator_file} gives its bearing surface by surface ([bearing]); "
                          f"its [[bearing.surface]] entries replace '{replaced[0]}': vary a key the design keeps "
                          "(mass_kg, damping_ratio, the property factors)")
