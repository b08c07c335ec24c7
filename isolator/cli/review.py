"""``isolator review``: option checks and one-line errors over :func:`isolator.review.run.run_review`."""

from __future__ import annotations

from pathlib import Path

import typer

from isolator.cli.common import (
    app,
    check_given_scale_factors,
    check_pdf_output,
    parse_set,
    refuse_record_flags_for_a_suite_file,
    say,
)
from isolator.cli.common import user_error as _user_error


@app.command("review")
def review(
    design: str = typer.Option(None, "--design", "-d", help="Design file (TOML) with the friction bounds "
                               "(lambda_max/lambda_min, mu_upper/mu_lower or the λ_ae/λ_test/λ_spec factors), "
                               "displacement_capacity_m and an optional \\[plan] table."),
    target: str = typer.Option(None, "--target", "-t", help="TARGET.toml (S_MS, S_M1, T_L; or spectrum_csv), or "
                               "`example` for the bundled MCE_R target."),
    suite: list[str] = typer.Option(None, "--suite", "-s", help="SUITE.toml, or record files, folders and globs "
                                    "grouped into pairs by station (repeatable); `example` for the bundled suite."),
    code: str = typer.Option("asce7-22", "--code", help="asce7-22 or en15129."),
    scaling: str = typer.Option(None, "--scaling", help="common (one factor for all pairs), fit (shape "
                                "factor per pair, then a common factor) or given (the suite's scale_factor values, "
                                "checked, never rescaled). Default: given when every pair of the suite gives its "
                                "scale_factor, else common."),
    output: str = typer.Option(None, "--output", "-o", help="PDF to write (default reports/review_DESIGN.pdf); "
                               "the JSON goes beside it, the analysis cache in a folder beside it."),
    as_json: bool = typer.Option(False, "--json", help="Print the review's JSON on stdout."),
    jobs: int = typer.Option(None, "--jobs", "-j", help="Local worker processes (default: all cores)."),
    scheduler: str = typer.Option(None, "--scheduler", help="Dask scheduler address (instead of local processes)."),
    settings: list[str] = typer.Option(None, "--set", help="Review parameter NAME=VALUE (see docs/review.md), "
                                       "e.g. --set min_ratio=0.9 (repeatable)."),
    units: str = typer.Option(None, "--units", "-u", help="Units of records that do not state them (files and "
                              "folders given to --suite; a SUITE.toml has its own)."),
    trim: bool = typer.Option(False, "--trim", help="Trim the components of a pair to their common span when "
                              "their lengths differ (files and folders given to --suite)."),
    no_cache: bool = typer.Option(False, "--no-cache", help="Analyse everything again (ignore and keep no cache)."),
    verify: str = typer.Option(None, "--verify", help="Re-check a review JSON: the same input files (SHA-256) and, "
                               "run again, the same numbers; exit 1 when not."),
) -> None:
    """Code-based design review over a ground-motion suite scaled to a target, at both property bounds.

    Every pair × {lower, upper, nominal} friction runs through the 2-D engine; the PDF's page 1 lists the
    checks with their clauses (pass / fail / not checked); the JSON holds every number.  See docs/review.md.
    """
    import json
    import shlex
    import sys

    from isolator.design import Design, DesignError
    from isolator.errors import ReviewError
    from isolator.motion import RecordError
    from isolator.review.examples import resolve_example
    from isolator.review.run import CODES
    from isolator.review.scaling import SCALING_METHODS, default_scaling
    from isolator.units import UnitsError

    if verify is not None:
        _verify(verify, jobs)
        return
    for flag, value in (("--design", design), ("--target", target), ("--suite", suite)):
        if value is None or value == []:
            _user_error(f"missing option {flag}")
        if value == "" or value == [""]:  # `--target ''` was "missing option --target": it was given, empty
            _user_error(f"{flag} '': a file is named by a path" + (" (or 'example')" if flag != "--design" else ""))
    if code not in CODES:
        _user_error(f"--code must be one of {', '.join(CODES)}, got {code!r}")
    if scaling is not None and scaling not in SCALING_METHODS:
        _user_error(f"--scaling must be one of {', '.join(SCALING_METHODS)}, got {scaling!r}")
    if jobs is not None and jobs < 1:
        _user_error(f"--jobs must be ≥ 1, got {jobs}")
    if scheduler is not None:  # refused before any input is read, as batch does
        from isolator.cli.common import error_line
        from isolator.errors import BatchError
        from isolator.parallel import check_scheduler

        try:
            check_scheduler(scheduler)
        except BatchError as err:
            _user_error(error_line(err))
    if jobs is not None:  # more processes than cores only add memory and contention
        from isolator.parallel import capped_workers

        jobs, note = capped_workers(jobs)
        if note:
            say(f"note: {note}")
    if output is None:
        output = str(Path("reports") / f"review_{Path(design).stem}.pdf")
    check_pdf_output(output)
    parameters = parse_set(settings)
    try:
        from isolator.review.parameters import from_design, resolve
        from isolator.review.suite import load_suite
        from isolator.review.target import load_target

        values = resolve(code, parameters)
        the_design = Design.from_toml(design)
        from_design(code, values, the_design, parameters)  # a --set of a value the design fixes: refused at once
        the_target = load_target(resolve_example("target", target))
        suite_args = [resolve_example("suite", s) for s in suite]
        target_file = resolve_example("target", target)
        refuse_record_flags_for_a_suite_file(suite_args, units, trim)
        refuse_review_over_inputs(output, no_cache, [design, target_file, *suite_args])
        the_suite = load_suite(suite_args, units=units, trim=trim)
        check_given_scale_factors(the_suite)
        if scaling is None:
            try:
                scaling = default_scaling(the_suite.names, the_suite.given_factors)
            except ValueError as err:
                raise ReviewError(f"{suite_args[0]}: {err}") from None
        # every file the review reads (the target's table, each record) is an input too
        refuse_review_over_inputs(output, no_cache, [design, target_file, *suite_args, *review_inputs(
            the_target, target_file, the_suite)])
    except (DesignError, ReviewError, RecordError, UnitsError, OSError) as err:
        _user_error(str(err))
    from isolator.atomic import output_lock
    from isolator.report.review_pages import failed_analyses, write_review_pdf
    from isolator.review.run import run_review

    cache_dir = None if no_cache else review_cache_dir(output)
    command = "isolator " + " ".join(shlex.quote(arg) for arg in sys.argv[1:])
    try:
        with output_lock(output):  # a second review on this -o is refused, naming this one
            result = run_review(the_design, the_target, the_suite, code=code, scaling=scaling, jobs=jobs,
                                scheduler=scheduler, parameters=parameters, cache_dir=cache_dir, rotd50_points=12,
                                paper_map_resolution=30)
            out = write_review_pdf(result, output, command=command)
    except (DesignError, ReviewError) as err:
        _user_error(str(err))
    except OSError as err:  # OutputError (read-only folder, full disk, lock held) names its path already
        _user_error(str(err) if str(err).startswith(str(getattr(err, "filename", None) or "\0"))
                    else f"{output}: cannot write ({err.strerror or err})")
    if as_json:
        typer.echo(json.dumps(out, indent=2))
        return
    counts = out["check_counts"]
    typer.echo(f"review   {output} ({out['pdf_pages']} pages), numbers in {Path(output).with_suffix('.json')}")
    typer.echo(pairs_line(out, scaling))
    for failure in out["suite"]["failed"]:
        typer.echo(f"failed   {failure['name']}: {failure['error']}")
    n_run, broken = failed_analyses(out)
    typer.echo(f"analyses {n_run} run, {len(broken)} failed" + (" (the rows needing them say not checked)" if broken
                                                                else ""))
    for name, bound, error in broken:
        typer.echo(f"failed   {name} ({bound}): {error}")
    width = max(len(c["id"]) for c in out["checks"])
    for c in out["checks"]:
        value = "n/a" if c["value"] is None else f"{c['value']:.4g}"
        limit = "n/a" if c["limit"] is None else f"{c['limit']:.4g}"
        where = f"  ({c['pair']}, {c['bound']})" if "pair" in c else ""
        typer.echo(f"{c['status']:<12} {c['id']:<{width}}  {value} vs {limit} {c['unit']}  [{c['clause']}]{where}")
    typer.echo(f"checks   {counts['pass']} pass, {counts['fail']} fail, {counts['not checked']} not checked")



def pairs_line(out: dict, scaling: str | None) -> str:
    """The console's ``pairs`` line of a review's JSON: read and failed, the factors and how they were formed (the
    JSON's ``run.scaling_basis``: a matched suite is never rescaled, whatever ``--scaling`` said — the line said
    "(common)" for it), the period range."""
    factors = out["scale_factors"].values()
    return (f"pairs    {len(out['suite']['pairs'])} read, {len(out['suite']['failed'])} failed to read; scale factors "
            f"{min(factors):.4g}–{max(factors):.4g} ({out.get('run', {}).get('scaling_basis') or scaling}), range "
            f"{out['period_range_s'][0]:.4g}–{out['period_range_s'][1]:.4g} s")


def review_cache_dir(output) -> Path:
    """The analysis cache of a review writing ``output``: ``.STEM.cache`` beside it."""
    return Path(output).parent / f".{Path(output).stem}.cache"


def review_inputs(target, target_file, suite) -> list:
    """Every file a review reads beyond its arguments: the target's table and each record of the suite."""
    files = []
    table = (getattr(target, "parameters", None) or {}).get("spectrum_csv")
    if table:
        files.append(Path(target_file).parent / table)
    for pair in suite.pairs:
        files.extend(getattr(pair, "paths", None) or [])
    files.extend(spec.path for spec in (getattr(suite, "specs", None) or ()) for spec in
                 (spec.x, spec.y, spec.z) if spec is not None)
    return files


def refuse_review_over_inputs(output, no_cache: bool, inputs) -> None:
    """Refuse a review whose PDF, JSON or cache folder would be (or hold) one of its inputs.

    Raises
    ------
    isolator.atomic.OutputIsInputError
        One line naming the output and the input.
    """
    import errno
    import os

    from isolator.atomic import OutputIsInputError, refuse_overwriting_inputs

    output = Path(output)
    refuse_overwriting_inputs([output, output.with_suffix(".json")], inputs)
    if not no_cache:
        cache = os.path.realpath(review_cache_dir(output))
        for item in inputs:
            where = os.path.realpath(item)
            if where == cache or where.startswith(cache + os.sep):
                raise OutputIsInputError(review_cache_dir(output), f"the review's cache folder holds an input "
                                         f"({item}); refusing to write into it: choose another output",
                                         errno.EEXIST)


def _verify(path: str, jobs) -> None:
    """``--verify``: one line per changed input or number not reproduced; exit 1 unless all agree."""
    from isolator.design import DesignError
    from isolator.errors import ReviewError
    from isolator.motion import RecordError
    from isolator.review.verify import verify_review
    from isolator.units import UnitsError

    try:
        result = verify_review(path, jobs=jobs)
    except (DesignError, ReviewError, RecordError, UnitsError) as err:
        _user_error(str(err))
    for changed in result["changed_inputs"]:
        typer.echo(f"changed  {changed}")
    for difference in result["differences"][:20]:
        typer.echo(f"differs  {difference}")
    if len(result["differences"]) > 20:
        typer.echo(f"differs  … and {len(result['differences']) - 20} more")
    if not result["ok"]:
        typer.echo(f"verify   {path}: NOT reproduced")
        raise typer.Exit(1)
    typer.echo(f"verify   {path}: same inputs (SHA-256), same numbers (relative {1e-9:g})")
