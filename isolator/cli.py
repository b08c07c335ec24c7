"""Command-line interface: thin wrappers over the public API, no physics here.

Heavy imports (numpy, numba, obspy, matplotlib) happen inside the commands so that
``isolator --help`` answers at once.  User mistakes end with one line on stderr and
exit code 2, never a traceback.
"""

from __future__ import annotations

import typer

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    help="Exact analysis of friction isolators (friction + spring + dashpot) under ground motion.",
)


@app.callback()
def _main() -> None:
    """isolator: friction isolators under harmonic and recorded ground motion."""


# ======================================================================================
# Ground-motion input: the `info` command and the record reader shared with `simulate`.
# (Block owned by the ground-motion issue; other commands live above/below it.)
# ======================================================================================

#: Help texts of the record options, shared by every command that reads a record.
RECORD_HELP = {
    "component": "Component to read from a multi-component file: channel code (HNE), its last "
    "letter (E), orientation (180, Up, NS), axis letter (N, E, Z) or trace id.",
    "units": "Units of the values for formats that do not state them: g, m/s2, gal or cm/s2.",
    "merge": "Join segments of a channel that has gaps, filling gaps by linear interpolation "
    "(otherwise a gap is an error).",
    "dt": "Time step of a one-column text record, in seconds.",
    "response": "StationXML file: remove the instrument response (records in counts).",
    "counts_factor": "Units (see --units) per count, for records in counts.",
}


def load_record_for_cli(
    path,
    component: str | None = None,
    units: str | None = None,
    merge: bool = False,
    dt_s: float | None = None,
    response=None,
    counts_factor: float | None = None,
):
    """Read a record for a command; a bad record ends the command with one line and exit code 2.

    Parameters are those of :func:`isolator.motion.read_ground_motion`.

    Returns
    -------
    isolator.motion.GroundMotion
        The acceleration in m/s² with its metadata.
    """
    from isolator.motion import RecordError, read_ground_motion
    from isolator.units import UnitsError

    try:
        return read_ground_motion(
            path, component=component, units=units, merge=merge, dt_s=dt_s,
            response=response, counts_factor=counts_factor,
        )
    except (RecordError, UnitsError) as err:
        typer.echo(f"error: {' '.join(str(err).split())}", err=True)
        raise typer.Exit(2) from None


def _json_safe(value):
    """Floats that JSON can hold (NaN and ±inf become null), recursively."""
    import math

    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {str(key): _json_safe(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_safe(item) for item in value]
    if hasattr(value, "item") and not isinstance(value, (str, bytes)):
        return _json_safe(value.item())
    return value


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
    import json

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
        typer.echo(json.dumps(_json_safe(summary), allow_nan=False))
        return
    rows = [
        ("record", str(record), ""),
        ("format", summary["format"], ""),
        ("component", motion.component, f"(of: {', '.join(motion.components)})"),
        ("units from", motion.units_source, ""),
        ("samples", f"{motion.npts}", ""),
        ("time step", f"{motion.dt_s:g}", "s"),
        ("duration", f"{motion.duration_s:.6g}", "s"),
        ("PGA", f"{measures.pga_m_s2:.6g}", f"m/s²  ({measures.pga_m_s2 / 9.80665:.4f} g)"),
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
    width = max(len(name) for name, _, _ in rows)
    for name, value, unit in rows:
        typer.echo(f"{name:<{width}}  {value} {unit}".rstrip())


# ======================================================================================
# Solver commands: harmonic (the paper's problem), threshold, simulate (a record).
# ======================================================================================


def _echo_table(rows) -> None:
    """Print (name, value, unit) rows aligned, one per line."""
    width = max(len(name) for name, _, _ in rows)
    for name, value, unit in rows:
        typer.echo(f"{name:<{width}}  {value} {unit}".rstrip())


def _user_error(message: str) -> None:
    """End the command with one line on stderr and exit code 2."""
    typer.echo(f"error: {' '.join(str(message).split())}", err=True)
    raise typer.Exit(2)


def _fmt(value, spec: str = ".6g") -> str:
    return "n/a" if value is None else format(value, spec)


@app.command()
def harmonic(
    alpha: float = typer.Option(..., "--alpha", help="Reduced acceleration α = A0 Ω²/(µs g) (Eq. 6)."),
    k: float = typer.Option(0.0, "--k", help="Dimensionless stiffness k = K A0/(M g)."),
    eta: float = typer.Option(0.0, "--eta", help="Dimensionless damping η = (γ/M) sqrt(A0/g)."),
    mu_s: float = typer.Option(..., "--mu-s", help="Static friction coefficient µs."),
    mu_k: float = typer.Option(None, "--mu-k", help="Kinetic friction coefficient µk ≤ µs (default µs)."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
) -> None:
    """Steady response to a harmonic ground motion: the paper's problem, solved exactly.

    Runs from rest (φ = π/2) until the motion is periodic, or grows linearly at
    resonance, and reports the regime (ST stick, SS stick-slip, SL permanent slip),
    ζ, A, ẋ_rms, the energies per period and the force ratios of Eq. 5.
    """
    import json

    from isolator.solver.harmonic import harmonic_response
    from isolator.solver.system import InvalidSystemError

    try:
        response = harmonic_response(alpha, k, eta, mu_s, mu_k)
    except InvalidSystemError as err:
        _user_error(str(err))
    summary = response.summary()
    if as_json:
        typer.echo(json.dumps(_json_safe(summary), allow_nan=False))
        return
    regime_words = {"ST": "stick (no relative motion)", "SS": "stick-slip", "SL": "permanent slip"}
    _echo_table([
        ("configuration", response.configuration, f"(k = {k:g}, η = {eta:g}, µs = {mu_s:g}, µk = {response.mu_k:g})"),
        ("regime", response.regime, f"({regime_words[response.regime]})"),
        ("steady", str(response.steady), f"({response.status}, cycle of {response.cycle_periods} period(s), "
                                         f"{response.periods_run} periods run)"),
        ("zeta", f"{response.zeta:.6g}", "slip time / period (Eq. 3)"),
        ("amplitude A", f"{response.amplitude:.6g}", "half peak-to-peak of x = X/A0"
                                                     + ("  (> 1: ground motion amplified)" if response.amplitude > 1 else "")),
        ("xdot_rms", f"{response.xdot_rms:.6g}", "(Eq. 4)"),
        ("energy_friction", f"{response.energy_friction:.6g}", "∆e_f per period (Eq. 9)"),
        ("energy_viscous", f"{response.energy_viscous:.6g}", "∆e_v per period (Eq. 10)"),
        ("work_input", f"{response.work_input:.6g}", "∆w_i per period (Eq. 11)"),
        ("balance residual", f"{response.energy_balance_residual:.2e}", "∆e_f + ∆e_v + ∆w_i (Eq. 8)"),
        ("rho_ev", _fmt(response.rho_ev), "elastic/viscous (Eq. 5)"),
        ("rho_vf", _fmt(response.rho_vf), "viscous/friction"),
        ("rho_ef", _fmt(response.rho_ef), "elastic/friction"),
        ("dominant force", response.dominant_force, ""),
        ("growth rate β", _fmt(response.growth_rate), "dA/dt at resonance (Eq. 26)"),
    ])


@app.command()
def threshold(
    k: float = typer.Option(0.0, "--k", help="Dimensionless stiffness k."),
    eta: float = typer.Option(0.0, "--eta", help="Dimensionless damping η."),
    mu_s: float = typer.Option(..., "--mu-s", help="Static friction coefficient µs."),
    mu_k: float = typer.Option(None, "--mu-k", help="Kinetic friction coefficient µk ≤ µs (default µs)."),
    alpha_max: float = typer.Option(6.0, "--alpha-max", help="Upper end of the α scan."),
    grid: int = typer.Option(120, "--grid", min=4, help="Grid points of the α scan before bisection."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
) -> None:
    """Regime thresholds along α: α_SS = 1, α_SL and every transition up to --alpha-max."""
    import json

    from isolator.solver.harmonic import harmonic_thresholds
    from isolator.solver.system import InvalidSystemError

    try:
        result = harmonic_thresholds(k, eta, mu_s, mu_k, alpha_max=alpha_max, n_grid=grid)
    except InvalidSystemError as err:
        _user_error(str(err))
    if as_json:
        typer.echo(json.dumps(_json_safe(result.summary()), allow_nan=False))
        return
    rows = [("alpha_ss", f"{result.alpha_ss:g}", "(stick below)"),
            ("alpha_sl", _fmt(result.alpha_sl, ".9g"),
             f"(permanent slip from here up to α = {alpha_max:g})" if result.alpha_sl else
             f"(not permanent slip at α = {alpha_max:g})")]
    rows += [("transition", f"{tr['alpha']:.9g}", f"{tr['from']} → {tr['to']}") for tr in result.transitions]
    _echo_table(rows)


def _write_csv_atomically(path, header: str, columns) -> None:
    """Write columns to CSV through a temporary file and a rename: never half a file."""
    import os
    import tempfile
    from pathlib import Path

    import numpy as np

    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    handle, tmp_name = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    try:
        with os.fdopen(handle, "w") as stream:
            np.savetxt(stream, np.column_stack(columns), delimiter=",", header=header, comments="", fmt="%.17g")
        os.replace(tmp_name, target)
    except BaseException:
        if os.path.exists(tmp_name):
            os.unlink(tmp_name)
        raise


@app.command()
def simulate(
    record: str = typer.Argument(..., help="Record file: PEER AT2, plain text (time, acceleration), "
                                 "MiniSEED, SAC, K-NET, CSMIP V2, USGS SMC …"),
    mu_s: float = typer.Option(..., "--mu-s", help="Static friction coefficient µs."),
    mu_k: float = typer.Option(None, "--mu-k", help="Kinetic friction coefficient µk ≤ µs (default µs)."),
    stiffness_per_mass: float = typer.Option(0.0, "--stiffness-per-mass", help="K/M [1/s²] (g/R for a pendulum)."),
    damping_per_mass: float = typer.Option(0.0, "--damping-per-mass", help="γ/M [1/s]."),
    gravity: float = typer.Option(None, "--gravity", help="Gravity for the friction force [m/s²] "
                                  "(standard gravity 9.80665 by default; records in g are always converted "
                                  "with standard gravity)."),
    component: str = typer.Option(None, "--component", "-c", help=RECORD_HELP["component"]),
    units: str = typer.Option(None, "--units", "-u", help=RECORD_HELP["units"]),
    merge: bool = typer.Option(False, "--merge", help=RECORD_HELP["merge"]),
    dt: float = typer.Option(None, "--dt", help=RECORD_HELP["dt"]),
    response: str = typer.Option(None, "--response", help=RECORD_HELP["response"]),
    counts_factor: float = typer.Option(None, "--counts-factor", help=RECORD_HELP["counts_factor"]),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
    out_csv: str = typer.Option(None, "--out-csv", help="Write the time histories to this CSV file."),
) -> None:
    """Exact response of a friction–spring–dashpot isolator to a recorded ground acceleration.

    The record is taken as linear between samples; the response to it is exact
    (closed forms between stick/slip events located to machine precision).
    Energies are per unit mass (J/kg).
    """
    import json

    from isolator.solver.record import RecordInputError, simulate_record
    from isolator.solver.system import InvalidSystemError, System

    try:
        kwargs = {} if gravity is None else {"gravity_m_s2": gravity}
        system = System(mu_static=mu_s, mu_kinetic=mu_k, stiffness_per_mass=stiffness_per_mass,
                        damping_per_mass=damping_per_mass, **kwargs)
    except InvalidSystemError as err:
        _user_error(str(err))
    motion = load_record_for_cli(record, component, units, merge, dt, response, counts_factor)
    try:
        result = simulate_record(motion.acceleration_m_s2, motion.dt_s, system=system)
    except RecordInputError as err:
        _user_error(f"{record}: {err}")
    summary = {"record": str(record), "component": motion.component, "units_source": motion.units_source,
               "npts": motion.npts, "dt_s": motion.dt_s, **result.summary()}
    if out_csv:
        try:
            _write_csv_atomically(
                out_csv,
                "time_s,ground_acceleration_m_s2,displacement_m,velocity_m_s,absolute_acceleration_m_s2",
                [result.time_s, result.ground_acceleration_m_s2, result.displacement_m,
                 result.velocity_m_s, result.absolute_acceleration_m_s2])
        except OSError as err:
            _user_error(f"{out_csv}: cannot write ({err.strerror or err})")
    if as_json:
        typer.echo(json.dumps(_json_safe(summary), allow_nan=False))
        return
    _echo_table([
        ("record", str(record), f"[{motion.component}, units from {motion.units_source}]"),
        ("samples", f"{motion.npts} × {motion.dt_s:g} s", ""),
        ("configuration", system.configuration, f"(µs = {system.mu_static:g}, µk = {system.mu_kinetic:g}, "
                                                f"K/M = {system.stiffness_per_mass:g} 1/s², "
                                                f"γ/M = {system.damping_per_mass:g} 1/s)"),
        ("peak displacement", f"{result.peak_displacement_m:.6g}", "m"),
        ("residual displacement", f"{result.residual_displacement_m:.6g}", "m"),
        ("peak velocity", f"{result.peak_velocity_m_s:.6g}", "m/s"),
        ("peak transmitted acc.", f"{result.peak_transmitted_acceleration_m_s2:.6g}", "m/s²"),
        ("slip time", f"{result.slip_time_s:.6g}", f"s  of {result.time_s[-1] - result.time_s[0]:.6g} s"),
        ("events", f"{result.n_events}", "(break-away, stick, reversal)"),
        ("energy input", f"{result.energy_input_J_per_kg:.6g}", "J/kg"),
        ("energy friction", f"{result.energy_friction_J_per_kg:.6g}", "J/kg"),
        ("energy viscous", f"{result.energy_viscous_J_per_kg:.6g}", "J/kg"),
        ("energy balance error", f"{result.energy_balance_error_J_per_kg:.2e}", "J/kg"),
        ("solver time", f"{result.solver_seconds * 1e3:.3g}", "ms"),
        ("status", result.message, ""),
    ] + ([("time histories", out_csv, "")] if out_csv else []))


# ======================================================================================
# Speed against error: the `bench` command.  (Block owned by the benchmark issue.)
# ======================================================================================

def _write_text_atomically(path, text: str) -> None:
    """Write text through a temporary file in the same folder and a rename: never half a file."""
    import os
    import tempfile
    from pathlib import Path

    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    try:
        with os.fdopen(handle, "w", encoding="utf-8", newline="\n") as stream:
            stream.write(text)
        os.replace(temporary, target)
    except BaseException:
        if os.path.exists(temporary):
            os.unlink(temporary)
        raise


@app.command()
def bench(
    quick: bool = typer.Option(False, "--quick", help="A representative subset (under a minute)."),
    as_json: bool = typer.Option(False, "--json", help="Print the rows as one JSON list instead of tables."),
    out: str = typer.Option("reports/bench", "--out", help="Folder for bench.csv, bench_pareto.csv, bench.json, "
                                                            "bench.md and bench.png."),
    records: str = typer.Option(None, "--records", help="Folder of the shared records "
                                                        "(default: ../shared/records beside the repository)."),
    repeats: int = typer.Option(None, "--repeats", min=1, help="Runs per timing (median); default 3 quick, 5 full."),
) -> None:
    """Speed against error: our exact solver against fixed-step, Newmark and solve_ivp methods.

    Runs the harmonic cases of every configuration and friction-pendulum records, times
    every method (median of several runs, in this process) and measures the errors of
    peak and residual displacement, slip-time ratio and trajectory; writes the table
    (CSV, JSON, Markdown) and a log error / log time plot to --out.
    """
    import json
    import os
    import platform
    import tempfile
    import time
    from pathlib import Path

    from isolator import bench as bench_module

    records_dir = Path(records) if records else None
    if records_dir is not None and not records_dir.is_dir():
        _user_error(f"{records}: no such folder of records")
    out_dir = Path(out)
    try:
        out_dir.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        _user_error(f"{out}: cannot create the output folder ({err.strerror or err})")
    if records_dir is None and not bench_module.default_records_dir().is_dir():
        typer.echo(f"note: no records at {bench_module.default_records_dir()}: harmonic cases only "
                   "(give --records DIR)", err=True)
    started = time.perf_counter()
    progress = None if as_json else (lambda line: typer.echo(line, err=True))
    rows, pareto = bench_module.run_bench(quick=quick, records_dir=records_dir, repeats=repeats, progress=progress)
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
    document = {"command": command, "wall_seconds": wall_s, "machine": machine, "rows": rows, "pareto": pareto}
    try:
        _write_text_atomically(out_dir / "bench.csv", bench_module.rows_to_csv(rows))
        _write_text_atomically(out_dir / "bench_pareto.csv", bench_module.pareto_to_csv(pareto))
        _write_text_atomically(out_dir / "bench.json", json.dumps(_json_safe(document), indent=1, allow_nan=False))
        _write_text_atomically(out_dir / "bench.md", bench_module.pareto_markdown(pareto) + "\n"
                               + bench_module.rows_markdown(rows))
        handle, temporary = tempfile.mkstemp(dir=out_dir, prefix=".bench.", suffix=".png")
        os.close(handle)
        try:
            bench_module.plot(rows, Path(temporary))
            os.replace(temporary, out_dir / "bench.png")
        finally:
            if os.path.exists(temporary):
                os.unlink(temporary)
    except OSError as err:
        _user_error(f"{out}: cannot write ({err.strerror or err})")
    if as_json:
        typer.echo(json.dumps(_json_safe(rows), allow_nan=False))
        return
    typer.echo(bench_module.pareto_markdown(pareto))
    typer.echo(bench_module.rows_markdown(rows))
    typer.echo(f"{len(rows)} runs in {wall_s:.1f} s on {machine['processor']} ({machine['cpus']} CPUs); "
               f"written to {out_dir}/bench.csv, bench_pareto.csv, bench.json, bench.md, bench.png")
