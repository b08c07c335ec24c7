"""Commands on one record: ``info`` (what the file holds) and ``simulate`` (the exact response)."""

from __future__ import annotations

import typer

from isolator.cli.common import (
    RECORD_HELP,
    app,
    check_outputs,
    check_static_friction,
    echo_json,
    echo_table,
    error_line,
    load_record_for_cli,
    user_error,
    write_csv_atomically,
    write_error,
)
from isolator.cli.pairs import PAIR_HELP


@app.command()
def info(
    record: str = typer.Argument(..., help="Record file: MiniSEED, SAC, K-NET, … (obspy), PEER AT2, "
                                 "CSMIP V2, USGS SMC or plain text."),
    component: str = typer.Option(None, "--component", "-c", help=RECORD_HELP["component"]),
    units: str = typer.Option(None, "--units", "-u", help=RECORD_HELP["units"]),
    merge: bool = typer.Option(False, "--merge", help=RECORD_HELP["merge"]),
    dt: float = typer.Option(None, "--dt", help=RECORD_HELP["dt"]),
    response: str = typer.Option(None, "--response", help=RECORD_HELP["response"]),
    counts_factor: float = typer.Option(None, "--counts-factor", help=RECORD_HELP["counts_factor"]),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
) -> None:
    """Read a ground-motion record and print its size, units source and intensity measures."""
    from isolator.units import STANDARD_GRAVITY

    motion = load_record_for_cli(record, component, units, merge, dt, response, counts_factor)
    measures = motion.intensity_measures()
    summary = {
        "path": str(record),
        "format": motion.provenance.get("format", ""),
        "component": motion.component,
        "components": list(motion.components),
        "npts": motion.npts,
        "dt_s": motion.dt_s,
        "duration_s": motion.duration_s,
        "units_source": motion.units_source,
        **measures.as_dict(),
        "provenance": motion.provenance,
        "processing": list(motion.processing),
    }
    if as_json:
        echo_json(summary)
        return
    rows = [
        ("record", str(record), ""),
        ("format", summary["format"], ""),
        ("component", motion.component, f"(of: {', '.join(motion.components)})"),
        ("units from", motion.units_source, ""),
        ("samples", f"{motion.npts}", ""),
        ("time step", f"{motion.dt_s:g}", "s" if motion.is_uniform else
         f"s (mean; {motion.provenance.get('sampling', 'unequal steps')})"),
        ("duration", f"{motion.duration_s:.6g}", "s"),
        ("PGA", f"{measures.pga_m_s2:.6g}", f"m/s²  ({measures.pga_m_s2 / STANDARD_GRAVITY:.4f} g)"),
        ("PGV", f"{measures.pgv_m_s:.6g}", "m/s"),
        ("PGD", f"{measures.pgd_m:.6g}", "m   (baseline-corrected)"),
        ("Arias intensity", f"{measures.arias_m_s:.6g}", "m/s"),
        ("duration D5-95", f"{measures.d5_95_s:.6g}", "s"),
        ("predominant period", f"{measures.predominant_period_s:.4g}", "s   (peak of 5% PSA)"),
        ("A0 = PGV²/PGA", f"{measures.a0_equiv_m:.6g}", "m"),
        ("Ω = PGA/PGV", f"{measures.omega_equiv_rad_s:.6g}", "rad/s"),
    ]
    for key in ("event", "date", "station", "station_name", "starttime"):
        if key in motion.provenance:
            rows.insert(3, (key.replace("_", " "), str(motion.provenance[key]), ""))
    for step in motion.processing:
        rows.append(("processing", step.get("step", ""), step.get("reason", "")))
    echo_table(rows)



@app.command()
def simulate(
    record: str = typer.Argument(..., help="Record file (X): PEER AT2, plain text (time, acceleration), "
                                 "MiniSEED, SAC, K-NET, CSMIP V2, USGS SMC …"),
    mu_s: float = typer.Option(None, "--mu-s", help="Static friction coefficient µs (or give --design)."),
    design: str = typer.Option(None, "--design", help="Design file (TOML) instead of the isolator options; "
                               "with a [superstructure] the building on the isolation plane is solved."),
    mu_k: float = typer.Option(None, "--mu-k", help="Kinetic friction coefficient µk ≤ µs (default µs)."),
    stiffness_per_mass: float = typer.Option(0.0, "--stiffness-per-mass", help="K/M [1/s²] (g/R for a pendulum)."),
    damping_per_mass: float = typer.Option(0.0, "--damping-per-mass", help="γ/M [1/s]."),
    gravity: float = typer.Option(None, "--gravity", help="Gravity for the friction force [m/s²] "
                                  "(standard gravity by default; records in g are always converted "
                                  "with standard gravity)."),
    radius_m: float = typer.Option(None, "--radius-m", help=PAIR_HELP["radius"]),
    mu_slow: float = typer.Option(None, "--mu-slow", help=PAIR_HELP["mu_slow"]),
    mu_fast: float = typer.Option(None, "--mu-fast", help=PAIR_HELP["mu_fast"]),
    rate_s_per_m: float = typer.Option(None, "--rate-s-per-m", help=PAIR_HELP["rate"]),
    pair: str = typer.Option(None, "--pair", help=PAIR_HELP["pair"]),
    vertical: str = typer.Option(None, "--vertical", help=PAIR_HELP["vertical"]),
    component: str = typer.Option(None, "--component", "-c", help=PAIR_HELP["component"]),
    trim: bool = typer.Option(False, "--trim", help=PAIR_HELP["trim"]),
    resample: bool = typer.Option(False, "--resample", help=PAIR_HELP["resample"]),
    units: str = typer.Option(None, "--units", "-u", help=RECORD_HELP["units"]),
    merge: bool = typer.Option(False, "--merge", help=RECORD_HELP["merge"]),
    dt: float = typer.Option(None, "--dt", help=RECORD_HELP["dt"]),
    response: str = typer.Option(None, "--response", help=RECORD_HELP["response"]),
    counts_factor: float = typer.Option(None, "--counts-factor", help=RECORD_HELP["counts_factor"]),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
    out_csv: str = typer.Option(None, "--out-csv", help="Write the time histories (every component) to this "
                                "CSV file ('-' or /dev/stdout: to standard output, instead of the table)."),
) -> None:
    """Response of a friction isolator to a recorded ground acceleration: one component, a pair, a vertical.

    The model is the one the scene needs, and the output says which ran and why: one
    component with constant friction and no vertical → the exact 1-D kernel (closed
    forms between stick/slip events located to machine precision); two horizontal
    components (--pair, --component pair|all), a vertical (--vertical) or µ(v)
    (--mu-slow/--mu-fast/--rate-s-per-m) → the 2-D engine.  Records are linear
    between samples (unequal steps allowed).  Energies are per unit mass (J/kg).
    """
    if trim and resample:  # both align a pair's components; which one applied was not said (issue 26)
        user_error("--trim and --resample both align the components of a pair: give one")
    the_design = None
    if design is not None:
        the_design, system, nominal = _design_isolator(design, mu_s, mu_k, stiffness_per_mass, damping_per_mass,
                                                       radius_m, mu_slow, mu_fast, rate_s_per_m, gravity)
    elif mu_s is None:
        user_error("Missing option '--mu-s' (the isolator), or give --design DESIGN.toml "
                   "(see 'isolator simulate --help')")
    if design is None:
        check_static_friction(mu_s)
        system, nominal = _option_isolator(mu_s, mu_k, stiffness_per_mass, damping_per_mass, gravity, radius_m,
                                           mu_slow, mu_fast, rate_s_per_m)
    streamed = out_csv == "-" or (out_csv is not None and _is_stdout(out_csv))
    if streamed and as_json:  # the CSV was written and the JSON asked for dropped, silently (session 24 sweep)
        user_error(f"--json and --out-csv {out_csv} both write to standard output: give one (or the CSV a file)")
    check_outputs([None if out_csv == "-" else out_csv], [record, response, pair, vertical, design], streams=[out_csv])
    from contextlib import nullcontext

    from isolator.atomic import OutputError, output_lock, resolve_output

    # a file's lock is made before the analysis, as report's: a folder that cannot be written is one line at once
    # (`--out-csv /proc/x.csv` ran a building for 13 s first, session 16 sweep); a stream (-, a pipe) has none
    locked = out_csv is not None and not streamed and not resolve_output(out_csv, allow_stream=True)[1]
    try:
        with output_lock(out_csv) if locked else nullcontext():
            _simulate_and_print(record, pair, vertical, component, trim, resample, units, merge, dt, response,
                                counts_factor, as_json, out_csv, streamed, system, nominal, the_design)
    except OutputError as err:  # the lock: an unwritable folder, another run on this file
        write_error(err, out_csv)


#: Earth's gravity as an engineer means it (``--gravity``; low, high [m/s²], why): ``--gravity 1e300`` answered
#: (nothing slid) and ``981`` (cm/s²) ran without a word (session 17 sweep).  The other physical flags share the
#: design file's ranges (:data:`isolator.bearing.MEANT_RANGES`); the library's own checks come first (0, negative,
#: non-finite, µ ≥ 1, a > 1e4 s/m keep their messages); K/M and γ/M keep the solver's tested bounds
#: (isolator.solver.system: the paper's configurations use them beyond an isolator's).
GRAVITY_RANGE_M_S2 = (9.7, 10.0, "Earth's gravity, 9.76-9.84 at its surface and 9.8, 9.81 or 10 in hand checks; "
                                 "1 is g itself, 32.2 ft/s², 386 in/s², 981 cm/s²")


#: ``--stiffness-per-mass`` and ``--damping-per-mass`` as an engineer means them (0: none; else low, high, unit,
#: why).  ``1e-300`` ran as a period of 6e150 s without a word, and above the solver's bounds the refusal named
#: the System's keyword, not the flag (session 18 sweep).  The high ends are the solver's tested bounds.
PER_MASS_FLAG_RANGES = {
    "--stiffness-per-mass": (1e-6, "MAX_STIFFNESS_PER_MASS", "1/s²",
                             "K/M = (2π/T)²; below 1e-6 the period (6283 s) is longer than any record: give 0 for "
                             "no restoring force; above, the isolator is rigid (T < 63 µs)"),
    "--damping-per-mass": (1e-6, "MAX_DAMPING_PER_MASS", "1/s",
                           "γ/M; below 1e-6 the relaxation time M/γ (11.6 days) is longer than any record: give 0 "
                           "for no damper; above, M/γ is below 1 ps"),
}


def check_per_mass_flags(stiffness_per_mass, damping_per_mass) -> None:
    """Refuse ``--stiffness-per-mass``/``--damping-per-mass`` outside 0 or :data:`PER_MASS_FLAG_RANGES`, naming
    the flag (a NaN, an infinity and a negative number too)."""
    from isolator.solver import system as solver_system

    for flag, value in (("--stiffness-per-mass", stiffness_per_mass), ("--damping-per-mass", damping_per_mass)):
        low, bound, unit, why = PER_MASS_FLAG_RANGES[flag]
        high = getattr(solver_system, bound)
        if value is not None and value != 0 and not low <= value <= high:  # NaN fails the comparison too
            user_error(f"{flag} {value:g} is outside 0 or [{low:g}, {high:g}] {unit}: {why}")


def check_flag_ranges(**given) -> None:
    """Refuse a physical flag outside its range in one line naming it, the range and why (``given``: the flag's
    name with ``_`` for ``-`` and without ``--``, its value or None)."""
    from isolator.bearing import outside_meant

    for name, value in given.items():
        if value is None:
            continue
        flag = "--" + name.replace("_", "-")
        if name == "gravity":
            low, high, why = GRAVITY_RANGE_M_S2
            problem = "" if low <= value <= high else f"outside [{low:g}, {high:g}] m/s²: {why}"
        else:
            problem = outside_meant("mu" if name.startswith("mu_") else name, value)
        if problem:
            user_error(f"{flag} {value:g} is {problem}")


def _design_isolator(design, mu_s, mu_k, stiffness_per_mass, damping_per_mass, radius_m, mu_slow, mu_fast,
                     rate_s_per_m, gravity):
    """The design file's isolator keywords, its nominal system; refuses isolator options beside it."""
    from isolator.adapter import motion_keywords
    from isolator.design import Design, DesignError
    from isolator.units import STANDARD_GRAVITY

    given = [name for name, value in (("--mu-s", mu_s), ("--mu-k", mu_k), ("--radius-m", radius_m),
                                      ("--mu-slow", mu_slow), ("--mu-fast", mu_fast),
                                      ("--rate-s-per-m", rate_s_per_m)) if value is not None]
    given += [name for name, value in (("--stiffness-per-mass", stiffness_per_mass),
                                       ("--damping-per-mass", damping_per_mass)) if value]
    if given:
        user_error(f"give the isolator with --design or with {given[0]} and its other options, not both")
    if gravity is not None:
        check_gravity_flag(gravity)
    try:
        the_design = Design.from_toml(design, gravity_m_s2=STANDARD_GRAVITY if gravity is None else gravity)
    except DesignError as err:
        user_error(str(err))
    return the_design, motion_keywords(the_design), the_design.system()


def _option_isolator(mu_s, mu_k, stiffness_per_mass, damping_per_mass, gravity, radius_m, mu_slow, mu_fast,
                     rate_s_per_m):
    """The isolator keywords and nominal system of the command-line options (checked before any file is read)."""
    import math

    from isolator.cli.pairs import system_keywords
    from isolator.solver.system import InvalidSystemError, System, check_friction_coefficient, check_friction_rate

    system = system_keywords(mu_s=mu_s, mu_k=mu_k, stiffness_per_mass=stiffness_per_mass,
                             damping_per_mass=damping_per_mass, gravity=gravity, radius_m=radius_m,
                             mu_slow=mu_slow, mu_fast=mu_fast, rate_s_per_m=rate_s_per_m)
    if radius_m is not None and not (math.isfinite(radius_m) and radius_m > 0):
        user_error(f"--radius-m must be a finite number > 0, got {radius_m:g}")
    check_per_mass_flags(stiffness_per_mass, damping_per_mass)
    try:  # the isolator is checked before any file is read
        kwargs = {} if gravity is None else {"gravity_m_s2": gravity}
        kappa = stiffness_per_mass if radius_m is None else System(mu_static=mu_s, **kwargs).gravity_m_s2 / radius_m
        nominal = System(mu_static=mu_s, mu_kinetic=mu_k, stiffness_per_mass=kappa,
                         damping_per_mass=damping_per_mass, **kwargs)
        for name, value in (("mu_slow", mu_slow), ("mu_fast", mu_fast)):  # the engine's own checks, before the
            if value is not None:  # record is read and before the ranges below (their messages kept)
                check_friction_coefficient(name, value)
        if rate_s_per_m is not None:
            check_friction_rate(rate_s_per_m)
    except InvalidSystemError as err:
        user_error(error_line(err))
    check_flag_ranges(gravity=gravity, radius_m=radius_m, mu_s=mu_s, mu_slow=mu_slow, mu_fast=mu_fast,
                      rate_s_per_m=rate_s_per_m)
    return system, nominal


def check_gravity_flag(gravity) -> None:
    """``--gravity`` beside a design file: the System's checks (finite, > 0), then :data:`GRAVITY_RANGE_M_S2`."""
    from isolator.solver.system import InvalidSystemError, System

    try:
        System(mu_static=0.1, gravity_m_s2=gravity)
    except InvalidSystemError as err:
        user_error(error_line(err))
    check_flag_ranges(gravity=gravity)


def _simulate_and_print(record, pair, vertical, component, trim, resample, units, merge, dt, response,
                        counts_factor, as_json, out_csv, streamed, system, nominal, the_design) -> None:
    from isolator.analysis import SCHEMA_NAME, SCHEMA_VERSION, record_dict
    from isolator.cli.pairs import history_columns, load_motion_set_for_cli, result_rows, solve, wants_set

    if wants_set(pair, vertical, component):
        motions = load_motion_set_for_cli(record, pair, vertical, component, units, merge, dt, response,
                                          counts_factor, trim, resample)
        parts = motions.components
        result = solve(record, parts["x"].acceleration_m_s2, parts["y"].acceleration_m_s2 if "y" in parts else None,
                       parts["z"].acceleration_m_s2 if "z" in parts else None, dt_s=motions.dt_s,
                       time_s=motions.sample_times_s, system=system, design=the_design,
                       files=[record, pair, vertical])
        described = ", ".join(f"{axis} = {m.component}" for axis, m in parts.items())
        samples = (motions.npts, motions.dt_s, motions.sample_times_s is None)
        record_group = record_dict(motions, str(record))
    else:
        motion = load_record_for_cli(record, component, units, merge, dt, response, counts_factor)
        result = solve(record, motion.acceleration_m_s2, dt_s=motion.dt_s, time_s=motion.sample_times_s,
                       system=system, design=the_design)
        described = f"{motion.component}, units from {motion.units_source}"
        samples = (motion.npts, motion.dt_s, motion.is_uniform)
        record_group = record_dict(motion, str(record))

    # the analysis schema's slice for a record without a design: model and why, record, response keys
    results = result.summary()
    summary = {"schema": SCHEMA_NAME, "schema_version": SCHEMA_VERSION, "model": results.pop("model"),
               "model_reason": results.pop("model_reason"), "record": record_group, **results}
    if out_csv:
        header, columns = history_columns(result)
        try:
            # standard output however named is written in place: /dev/stdout of `>> log.txt` resolves to log.txt,
            # which the rename replaced (the log's earlier lines lost; session 19 sweep)
            write_csv_atomically("-" if streamed else out_csv, header, columns, allow_stream=True)
        except OSError as err:
            write_error(err, out_csv)
    if streamed:
        return  # standard output holds the CSV: no table after it
    if as_json:
        echo_json(summary)
        return
    step = f"{samples[1]:g} s" if samples[2] else f"unequal steps (mean {samples[1]:g} s)"
    echo_table([
        ("record", str(record), f"[{described}]"),
        ("samples", f"{samples[0]} × {step}", ""),
        ("configuration", summary["configuration"], f"(µs = {nominal.mu_static:g}, µk = {nominal.mu_kinetic:g}, "
                                                    f"K/M = {nominal.stiffness_per_mass:g} 1/s², "
                                                    f"γ/M = {nominal.damping_per_mass:g} 1/s)"),
        *result_rows(result, summary),
        *_building_rows(summary),
    ] + ([("time histories", out_csv, "")] if out_csv else []))


def _building_rows(summary: dict) -> list[tuple[str, str, str]]:
    """Table rows of the building above the isolators (model 1d-building), none otherwise."""
    if "story_drift_ratio" not in summary:
        return []

    def listed(values, scale=1.0):
        return ", ".join(f"{scale * v:.4g}" for v in values)

    rows = [("story drift ratio", listed(summary["story_drift_ratio"]), "per story, bottom to top"),
            ("floor peak acc.", listed(summary["floor_peak_acceleration_m_s2"]), "m/s², per floor, absolute"),
            ("superstructure shear", f"{summary['superstructure_shear_coefficient']:.4g}", "× W_s (peak 1st story)"),
            ("base shear", f"{summary['base_shear_coefficient']:.4g}", "× W (peak isolator force)")]
    if summary.get("bearing_axial_load_min_N") is not None:
        rows += [("bearing load max", listed(summary["bearing_axial_load_max_N"], 1e-3), "kN, compression +"),
                 ("bearing load min", listed(summary["bearing_axial_load_min_N"], 1e-3), "kN, tension −"),
                 ("bearings uplifted", f"{summary['n_bearings_uplifted']}", "")]
    return rows


def _is_stdout(path: str) -> bool:
    """True if ``path`` is this process's standard output (``/dev/stdout``, its tty or pipe)."""
    import os
    import sys

    try:
        return os.path.samestat(os.stat(path), os.fstat(sys.stdout.fileno()))
    except (OSError, ValueError, AttributeError):  # no such file, or stdout is not a real file (tests)
        return path in ("/dev/stdout", "/proc/self/fd/1")
