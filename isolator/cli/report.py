"""Engineering review: ``report`` (PDF and JSON of a design under a record) and ``regime-map``."""

from __future__ import annotations

import typer

from isolator.cli.common import (
    RECORD_HELP,
    app,
    check_outputs,
    check_pdf_output,
    collector_skips_existing_objects,
    echo_table,
    load_record_for_cli,
    parse_set,
    user_error,
    write_error,
)
from isolator.cli.pairs import PAIR_HELP, wants_set


def _output_pdf(output: str | None, record: str, design: str, tag: str = "") -> str:
    """The PDF to write: ``--output`` (must end with .pdf) or reports/DESIGN_RECORD<tag>.pdf."""
    from pathlib import Path

    if output is None:
        record_stem = record.split(":", 1)[1] if record.startswith("example:") else Path(record).stem
        output = str(Path("reports") / f"{Path(design).stem}_{record_stem}{tag}.pdf")
    check_pdf_output(output)
    return output


def _command_line() -> str:
    """The command as typed, quoted for a shell (printed in the report)."""
    import shlex
    import sys

    return "isolator " + " ".join(shlex.quote(arg) for arg in sys.argv[1:])


def _scaled(motion, scale_to_pga: float | None, record_label: str):
    """The motion scaled to ``scale_to_pga`` [g] (a pair by one factor: its larger horizontal PGA) and its note."""
    if scale_to_pga is None:
        return motion, ""
    from isolator.units import STANDARD_GRAVITY

    try:
        scaled = motion.scaled_to_pga(scale_to_pga * STANDARD_GRAVITY)
    except ValueError as err:
        user_error(f"{record_label}: {err}")
    return scaled, scaled.scaling_note


def ultimate_rows(numbers: dict) -> list:
    """A bearing with rims: whether the run reached the ultimate displacement (every slider on its rim, a plastic
    impact) and the impulse the stop took, or that it stayed inside (issue 23: "say so")."""
    if "ultimate_displacement_reached" not in numbers:
        return []
    if numbers.get("rim_modelled") is False:  # a building run without a rim (a vertical or µ(v)): its solver_status
        return [("ultimate displacement", "PASSED, no rim modelled" if numbers["ultimate_displacement_reached"]
                 else "not reached (no rim modelled)", "")]
    if not numbers["ultimate_displacement_reached"]:
        return [("ultimate displacement", "not reached", f"({numbers.get('n_rim_contacts', 0)} rim contact(s))")]
    impulse = numbers.get("impact_impulse_m_s", float("nan")) * numbers["design"]["mass_kg"]
    return [("ultimate displacement", "REACHED", f"(every slider on its rim, held there: plastic impact(s), impulse "
                                                 f"{impulse:.4g} N·s; {numbers.get('n_rim_contacts', 0)} rim "
                                                 "contact(s))")]


def _result_rows(numbers: dict, paper: bool, pages: int | None, output: str, json_path: str, map_notes: list) -> list:
    """The lines printed after a report: the paper's point and classification where they apply, else the demand."""
    rows = ([] if pages is None else [("report", output, f"({pages} pages)")]) + [("numbers", json_path, "")]
    if not paper:
        return rows + [
            ("model", numbers["model"], f"({numbers['model_reason']})"),
            ("peak displacement", f"{numbers['peak_displacement_m']:.4g}", "m (resultant)"),
            ("demand / capacity", "n/a" if numbers["displacement_demand_ratio"] is None
             else f"{numbers['displacement_demand_ratio']:.3g}", ""),
            *ultimate_rows(numbers),
            ("residual displacement", f"{numbers['residual_displacement_m']:.4g}", "m"),
            ("peak transmitted acc.", f"{numbers['peak_transmitted_acceleration_m_s2']:.4g}", "m/s²"),
        ]
    return rows + [
        ("point", f"α = {numbers['alpha']:.4g}, k = {numbers['k']:.4g}, η = {numbers['eta']:.4g}", ""),
        ("regime", f"{numbers['regime_record']} (record) / {numbers['regime_harmonic']} (harmonic)", ""),
        ("amplitude A", f"{numbers['amplitude_record']:.3g} (record) / {numbers['amplitude_harmonic']:.3g} "
                        "(harmonic)", ""),
        ("dominant force", f"{numbers['dominant_force_record']} / {numbers['dominant_force_harmonic']}", ""),
        ("peak displacement", f"{numbers['peak_displacement_m']:.4g}", "m"),
        ("peak transmitted acc.", f"{numbers['peak_transmitted_acceleration_m_s2']:.4g}", "m/s²"),
    ] + [("disagreement", note, "") for note in numbers["disagreements"]] + [("note", note, "") for note in map_notes]


@app.command()
def report(
    record: str = typer.Argument(..., help="Record file (any format `info` reads), or `example:knet` for the "
                                 "real K-NET record bundled with obspy (no download)."),
    design: str = typer.Option(..., "--design", "-d", help="Design file (TOML): name, mass_kg, radius_m or "
                               "stiffness_N_per_m, mu_static; optional mu_kinetic, damping_Ns_per_m or "
                               "damping_ratio."),
    component: str = typer.Option(None, "--component", "-c", help=PAIR_HELP["component"]),
    pair: str = typer.Option(None, "--pair", help=PAIR_HELP["pair"]),
    vertical: str = typer.Option(None, "--vertical", help=PAIR_HELP["vertical"]),
    trim: bool = typer.Option(False, "--trim", help=PAIR_HELP["trim"]),
    resample: bool = typer.Option(False, "--resample", help=PAIR_HELP["resample"]),
    units: str = typer.Option(None, "--units", "-u", help=RECORD_HELP["units"]),
    merge: bool = typer.Option(False, "--merge", help=RECORD_HELP["merge"]),
    dt: float = typer.Option(None, "--dt", help=RECORD_HELP["dt"]),
    scale_to_pga: float = typer.Option(None, "--scale-to-pga", help="Scale the record to this peak ground "
                                       "acceleration, in g (e.g. 0.3); stated on the summary page.  A pair is "
                                       "scaled by one factor: its larger horizontal PGA to this value."),
    output: str = typer.Option(None, "--output", "-o", help="PDF to write (default reports/DESIGN_RECORD.pdf); "
                               "the JSON of the same numbers is written beside it."),
    map_resolution: int = typer.Option(40, "--map-resolution", min=8, max=400,
                                       help="Grid points per axis of the regime map (cached on disk)."),
    no_pdf: bool = typer.Option(False, "--no-pdf", help="Write only the JSON of the numbers (beside where the PDF "
                                "would go), without rendering the PDF."),
    settings: list[str] = typer.Option(None, "--set", help="NAME=VALUE: a review parameter the report's pages use "
                                       "(repeatable): drift_limit_rha (the building page's 17.6.4.4 line), "
                                       "D_over_R_max, restoring_min, transmitted_over_pga_max, sf_flag_low, "
                                       "sf_flag_high, range_hi_factor, usable_band_factor; printed in the report."),
) -> None:
    """Engineering-review PDF (and JSON) of an isolator design under a ground-motion record.

    One component: summary and verdicts; the record and its spectrum; the response
    (time histories, hysteresis, energy); the design on the paper's harmonic regime map.
    A pair (--pair, --component pair|all, --vertical) or a design with µ(v): summary
    with the model that ran and why; the ground motion; the orbit with the
    displacement-capacity circle, the resultant displacement and the hysteresis in each
    direction.
    """
    from pathlib import Path

    from isolator.design import Design, DesignError
    from isolator.errors import ReviewError
    from isolator.motion.examples import resolve_record
    from isolator.report.summary import report_parameters

    overrides = parse_set(settings)
    try:  # checked before anything is read: one line naming the flag
        parameters = report_parameters(overrides)
    except ReviewError as err:
        user_error(f"--set: {err}")
    try:
        the_design = Design.from_toml(design)
    except DesignError as err:
        user_error(str(err))
    try:
        record_path, record_label = resolve_record(record)
    except ValueError as err:
        user_error(str(err))
    if scale_to_pga is not None:
        from isolator.motion import MAX_ABS_ACCELERATION_G
        from isolator.motion.ground_motion import MIN_TARGET_PGA_G

        if not MIN_TARGET_PGA_G <= scale_to_pga <= MAX_ABS_ACCELERATION_G:
            user_error(f"--scale-to-pga must lie in [{MIN_TARGET_PGA_G:g}, {MAX_ABS_ACCELERATION_G:g}] g, "
                       f"got {scale_to_pga:g}")
    from isolator.analysis import analyse
    from isolator.atomic import output_lock
    from isolator.cli.pairs import refusal_line
    from isolator.errors import InvalidSystemError, SolverError
    from isolator.report.analysis_report import write_analysis_report
    from isolator.report.model_pages import n_model_pages
    from isolator.report.summary import write_json
    from isolator.review.record_checks import with_record_checks

    as_set = wants_set(pair, vertical, component)
    output = _output_pdf(output, record, design, "_pair" if as_set else "")
    # the JSON sidecar too: `-o design.pdf` beside design.json must not overwrite the design file
    check_outputs([output, str(Path(output).with_suffix(".json"))], [design, record_path, pair, vertical])
    if as_set:
        from isolator.cli.pairs import load_motion_set_for_cli

        motion = load_motion_set_for_cli(record_path, pair, vertical, component, units, merge, dt, trim=trim,
                                         resample=resample)
    else:
        motion = load_record_for_cli(record_path, component, units, merge, dt)
    motion, scaling_note = _scaled(motion, scale_to_pga, record_label)
    json_path = Path(output).with_suffix(".json")
    try:
        # a second report (or review) on this -o is refused, naming this one; the PDF and the JSON are written
        # as one set (isolator.atomic.atomic_paths): both, or neither and the older set left whole
        with output_lock(output):
            try:  # the model is the one the scene needs (the solver registry); the map applies to a 1-D response
                analysis = with_record_checks(analyse(the_design, motion, record_label=record_label,
                                                      scaling_note=scaling_note, map_resolution=map_resolution),
                                              overrides)
            except (InvalidSystemError, SolverError) as err:  # the engine refuses the design under the record
                user_error(refusal_line(err, [record_label, pair, vertical] if as_set else record_label, the_design))
            except ValueError as err:  # RecordInputError: the record's numbers
                user_error(f"{record_label}: {err}")
            if no_pdf:
                numbers = write_json(analysis, json_path, parameters=parameters)
            else:
                with collector_skips_existing_objects():
                    numbers = write_analysis_report(analysis, output, command=_command_line(), parameters=parameters)
    except OSError as err:  # OutputError (lock held, read-only folder, full disk) names its path
        write_error(err, output)
    paper = analysis.paper_applies
    pages = (4 if paper else 3) + n_model_pages(numbers)  # the building's, a multi-surface bearing's page
    echo_table(_result_rows(numbers, paper, None if no_pdf else pages, output, str(json_path),
                            _map_notes(analysis)))


def _map_notes(analysis) -> list[str]:
    """What the regime map has to say (a damaged cache entry recomputed …)."""
    harmonic_map = getattr(analysis, "harmonic_map", None)
    return list(getattr(getattr(harmonic_map, "regime_map", None), "notes", []) or [])


#: Figure formats of ``regime-map -o`` (matplotlib's vector and raster writers).
FIGURE_SUFFIXES = (".png", ".pdf", ".svg")


@app.command("regime-map")
def regime_map_command(
    eta: float = typer.Option(None, "--eta", help="Dimensionless damping η (default 0.5)."),
    mu_s: float = typer.Option(None, "--mu-s", help="Static friction coefficient µs (default 0.25)."),
    mu_k: float = typer.Option(None, "--mu-k", help="Kinetic friction coefficient µk ≤ µs (default µs)."),
    frame: str = typer.Option(None, "--frame", help="A paper frame: fig5a (k, α in [0, 6], η = 0) or fig6 "
                              "(k in [0, 5], α in [0, 10], η = 0.5); sets η and µs = 0.25 unless given."),
    k_max: float = typer.Option(None, "--k-max", help="Upper end of k (default 6)."),
    alpha_max: float = typer.Option(None, "--alpha-max", help="Upper end of α (default 6)."),
    resolution: int = typer.Option(100, "--resolution", "-n", min=4, max=1000, help="Grid points per axis."),
    workers: int = typer.Option(None, "--workers", min=1, help="Processes (default: the idle cores)."),
    no_cache: bool = typer.Option(False, "--no-cache", help="Compute even if cached (and do not store)."),
    refine: bool = typer.Option(False, "--refine", help="Locate every regime boundary by bisection in each "
                                "column (exact boundaries instead of grid steps; slower)."),
    output: str = typer.Option(None, "--output", "-o", help="Write the figure (PNG or PDF)."),
) -> None:
    """The paper's (k, α) regime map (Figs. 5-7): regimes, A > 1, dominant force, triple point."""
    import time
    from pathlib import Path

    from isolator.maps import PAPER_FRAMES, regime_map, triple_point
    from isolator.parallel import capped_workers
    from isolator.solver.system import InvalidSystemError

    k_range = (0.0, 6.0 if k_max is None else k_max)
    alpha_range = (0.0, 6.0 if alpha_max is None else alpha_max)
    if frame is not None:
        if frame not in PAPER_FRAMES:
            user_error(f"unknown --frame {frame!r} (choose one of: {', '.join(PAPER_FRAMES)})")
        spec = PAPER_FRAMES[frame]
        if k_max is not None or alpha_max is not None:  # the frame's ranges replaced them, silently (session 24)
            given = "--k-max" if alpha_max is None else "--alpha-max" if k_max is None else "--k-max and --alpha-max"
            user_error(f"--frame {frame} sets k in [0, {spec['k'][1]:g}] and α in [0, {spec['alpha'][1]:g}]: "
                       f"drop {given} (or --frame)")
        k_range, alpha_range = spec["k"], spec["alpha"]
        eta = spec["eta"] if eta is None else eta
        mu_s = spec["mu_s"] if mu_s is None else mu_s
    eta = 0.5 if eta is None else eta
    mu_s = 0.25 if mu_s is None else mu_s
    if not (k_range[1] > 0 and alpha_range[1] > 1):
        user_error("--k-max must be > 0 and --alpha-max > 1")
    if output:
        suffix = Path(output).suffix.lower()
        if suffix not in FIGURE_SUFFIXES:
            user_error(f"{output}: cannot tell the figure format from {suffix or 'no suffix'!r} "
                       f"(use {', '.join(FIGURE_SUFFIXES)})")
        check_outputs([output], [])
    from contextlib import nullcontext

    from isolator.atomic import atomic_path, output_lock

    try:  # the figure's lock is made before the map is computed: a folder that cannot be written is one line at
        # once (/proc/x.png computed the map for 10 s first, session 15 sweep), as report and review do
        with output_lock(output) if output else nullcontext():
            try:
                start = time.perf_counter()
                rmap = regime_map(eta, mu_s, mu_k, k_range=k_range, alpha_range=alpha_range, n_k=resolution,
                                  n_alpha=resolution, workers=workers, use_cache=not no_cache, refine=refine)
                wall = time.perf_counter() - start
                triple = triple_point(eta, mu_s, mu_k, alpha_max=alpha_range[1]) if eta > 0 else None
            except InvalidSystemError as err:
                user_error(str(err))
            rows = [("grid", f"{resolution} × {resolution}", f"(k in [{k_range[0]:g}, {k_range[1]:g}], "
                                                              f"α in [{alpha_range[0]:g}, {alpha_range[1]:g}])"),
                    ("parameters", f"η = {eta:g}, µs = {mu_s:g}, µk = {rmap.mu_k:g}", ""),
                    ("time", f"{wall:.3g} s", "(read from cache)" if rmap.from_cache else
                     f"(computed, {capped_workers(workers)[0]} worker(s))"),
                    *[("note", note, "") for note in rmap.notes],
                    ("triple point", "none in frame" if triple is None else f"α̂ = {triple[0]:.4g}, k̂ = {triple[1]:.4g}", "")]
            if output:
                from isolator.report.figures import regime_map_figure

                title = f"Harmonic regime map, η = {eta:g}, µs = {mu_s:g}, µk = {rmap.mu_k:g}" + (
                    f" (frame of the paper's {frame.replace('fig', 'Fig. ')})" if frame else "")
                fig = regime_map_figure(rmap, triple=triple, title=title)
                with atomic_path(output) as temporary:
                    fig.savefig(temporary, dpi=130, format=suffix[1:])
                rows.append(("figure", output, ""))
    except OSError as err:  # OutputError: the lock (an unwritable folder, another run on this -o) names the path
        write_error(err, output)
    echo_table(rows)
