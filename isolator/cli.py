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
    _echo_table(rows)


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
    import numpy as np

    from isolator.atomic import atomic_path

    with atomic_path(path) as temporary:
        np.savetxt(temporary, np.column_stack(columns), delimiter=",", header=header, comments="", fmt="%.17g")


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
# Engineering review: the `report` and `regime-map` commands.
# (Block owned by the report issue; designs, adapter, maps, classification and report
# live in isolator/design.py, adapter.py, metrics.py, maps.py and isolator/report/.)
# ======================================================================================


@app.command()
def report(
    record: str = typer.Argument(..., help="Record file (any format `info` reads), or `example:knet` for the "
                                 "real K-NET record bundled with obspy (no download)."),
    design: str = typer.Option(..., "--design", "-d", help="Design file (TOML): name, mass_kg, radius_m or "
                               "stiffness_N_per_m, mu_static; optional mu_kinetic, damping_Ns_per_m or "
                               "damping_ratio."),
    component: str = typer.Option(None, "--component", "-c", help=RECORD_HELP["component"]),
    units: str = typer.Option(None, "--units", "-u", help=RECORD_HELP["units"]),
    merge: bool = typer.Option(False, "--merge", help=RECORD_HELP["merge"]),
    dt: float = typer.Option(None, "--dt", help=RECORD_HELP["dt"]),
    scale_to_pga: float = typer.Option(None, "--scale-to-pga", help="Scale the record to this peak ground "
                                       "acceleration, in g (e.g. 0.3); stated on the summary page."),
    output: str = typer.Option(None, "--output", "-o", help="PDF to write (default reports/DESIGN_RECORD.pdf); "
                               "the JSON of the same numbers is written beside it."),
    map_resolution: int = typer.Option(40, "--map-resolution", min=8, max=400,
                                       help="Grid points per axis of the regime map (cached on disk)."),
) -> None:
    """Engineering-review PDF (and JSON) of an isolator design under a ground-motion record.

    Pages: summary and verdicts; the record and its spectrum; the response (time
    histories, hysteresis, energy); the design on the paper's harmonic regime map.
    """
    import shlex
    import sys
    from pathlib import Path

    from isolator.design import Design, DesignError
    from isolator.report.summary import resolve_record

    try:
        the_design = Design.from_toml(design)
    except DesignError as err:
        _user_error(str(err))
    try:
        record_path, record_label = resolve_record(record)
    except ValueError as err:
        _user_error(str(err))
    motion = load_record_for_cli(record_path, component, units, merge, dt)
    scaling_note = ""
    if scale_to_pga is not None:
        if not scale_to_pga > 0:
            _user_error(f"--scale-to-pga must be > 0 (in g), got {scale_to_pga:g}")
        from isolator.units import STANDARD_GRAVITY

        original_g = motion.pga_m_s2 / STANDARD_GRAVITY
        try:
            motion = motion.scaled_to_pga(scale_to_pga * STANDARD_GRAVITY)
        except ValueError as err:
            _user_error(f"{record_label}: {err}")
        scaling_note = (f"Record scaled to the design PGA {scale_to_pga:g} g (from {original_g:.4g} g, "
                        f"factor {scale_to_pga / original_g:.4g}).")
    if output is None:
        record_stem = record.split(":", 1)[1] if record.startswith("example:") else Path(record).stem
        output = str(Path("reports") / f"{Path(design).stem}_{record_stem}.pdf")
    if Path(output).suffix.lower() != ".pdf":
        _user_error(f"--output must end with .pdf, got {output}")
    from isolator.report.pdf import write_report
    from isolator.report.summary import analyse
    from isolator.solver.record import RecordInputError

    try:
        analysis = analyse(the_design, motion, record_label=record_label, scaling_note=scaling_note)
    except (RecordInputError, ValueError) as err:
        _user_error(f"{record_label}: {err}")
    command = "isolator " + " ".join(shlex.quote(arg) for arg in sys.argv[1:])
    try:
        summary = write_report(analysis, output, map_resolution=map_resolution, command=command)
    except OSError as err:
        _user_error(f"{output}: cannot write ({err.strerror or err})")
    _echo_table([
        ("report", output, "(4 pages)"),
        ("numbers", str(Path(output).with_suffix(".json")), ""),
        ("point", f"α = {summary['alpha']:.4g}, k = {summary['k']:.4g}, η = {summary['eta']:.4g}", ""),
        ("regime", f"{summary['regime_record']} (record) / {summary['regime_harmonic']} (harmonic)", ""),
        ("amplitude A", f"{summary['amplitude_record']:.3g} (record) / {summary['amplitude_harmonic']:.3g} "
                        "(harmonic)", ""),
        ("dominant force", f"{summary['dominant_force_record']} / {summary['dominant_force_harmonic']}", ""),
        ("peak displacement", f"{summary['peak_displacement_m']:.4g}", "m"),
        ("peak transmitted acc.", f"{summary['peak_transmitted_acceleration_m_s2']:.4g}", "m/s²"),
    ] + [("disagreement", note, "") for note in summary["disagreements"]])


@app.command("regime-map")
def regime_map_command(
    eta: float = typer.Option(None, "--eta", help="Dimensionless damping η (default 0.5)."),
    mu_s: float = typer.Option(None, "--mu-s", help="Static friction coefficient µs (default 0.25)."),
    mu_k: float = typer.Option(None, "--mu-k", help="Kinetic friction coefficient µk ≤ µs (default µs)."),
    frame: str = typer.Option(None, "--frame", help="A paper frame: fig5a (k, α in [0, 6], η = 0) or fig6 "
                              "(k in [0, 5], α in [0, 10], η = 0.5); sets η and µs = 0.25 unless given."),
    k_max: float = typer.Option(6.0, "--k-max", help="Upper end of k."),
    alpha_max: float = typer.Option(6.0, "--alpha-max", help="Upper end of α."),
    resolution: int = typer.Option(100, "--resolution", "-n", min=4, max=1000, help="Grid points per axis."),
    workers: int = typer.Option(None, "--workers", min=1, help="Processes (default: up to 2)."),
    no_cache: bool = typer.Option(False, "--no-cache", help="Compute even if cached (and do not store)."),
    refine: bool = typer.Option(False, "--refine", help="Locate every regime boundary by bisection in each "
                                "column (exact boundaries instead of grid steps; slower)."),
    output: str = typer.Option(None, "--output", "-o", help="Write the figure (PNG or PDF)."),
) -> None:
    """The paper's (k, α) regime map (Figs. 5-7): regimes, A > 1, dominant force, triple point."""
    import time
    from pathlib import Path

    from isolator.maps import PAPER_FRAMES, regime_map, triple_point
    from isolator.solver.system import InvalidSystemError

    k_range, alpha_range = (0.0, k_max), (0.0, alpha_max)
    if frame is not None:
        if frame not in PAPER_FRAMES:
            _user_error(f"unknown --frame {frame!r} (choose one of: {', '.join(PAPER_FRAMES)})")
        spec = PAPER_FRAMES[frame]
        k_range, alpha_range = spec["k"], spec["alpha"]
        eta = spec["eta"] if eta is None else eta
        mu_s = spec["mu_s"] if mu_s is None else mu_s
    eta = 0.5 if eta is None else eta
    mu_s = 0.25 if mu_s is None else mu_s
    if not (k_range[1] > 0 and alpha_range[1] > 1):
        _user_error("--k-max must be > 0 and --alpha-max > 1")
    try:
        start = time.perf_counter()
        rmap = regime_map(eta, mu_s, mu_k, k_range=k_range, alpha_range=alpha_range, n_k=resolution,
                          n_alpha=resolution, workers=workers, use_cache=not no_cache, refine=refine)
        wall = time.perf_counter() - start
        triple = triple_point(eta, mu_s, mu_k, alpha_max=alpha_range[1]) if eta > 0 else None
    except InvalidSystemError as err:
        _user_error(str(err))
    rows = [("grid", f"{resolution} × {resolution}", f"(k in [{k_range[0]:g}, {k_range[1]:g}], "
                                                      f"α in [{alpha_range[0]:g}, {alpha_range[1]:g}])"),
            ("parameters", f"η = {eta:g}, µs = {mu_s:g}, µk = {rmap.mu_k:g}", ""),
            ("time", f"{wall:.3g} s", "(read from cache)" if rmap.from_cache else
             f"(computed, {workers or 'up to 2'} worker(s))"),
            ("triple point", "none in frame" if triple is None else f"α̂ = {triple[0]:.4g}, k̂ = {triple[1]:.4g}", "")]
    if output:
        from isolator.report.figures import regime_map_figure

        title = f"Harmonic regime map, η = {eta:g}, µs = {mu_s:g}, µk = {rmap.mu_k:g}" + (
            f" (frame of the paper's {frame.replace('fig', 'Fig. ')})" if frame else "")
        fig = regime_map_figure(rmap, triple=triple, title=title)
        target = Path(output)
        try:
            target.parent.mkdir(parents=True, exist_ok=True)
            tmp = target.with_name(f".{target.name}.tmp{target.suffix}")
            fig.savefig(tmp, dpi=130)
            tmp.replace(target)
        except OSError as err:
            _user_error(f"{output}: cannot write ({err.strerror or err})")
        rows.append(("figure", output, ""))
    _echo_table(rows)

# ======================================================================================
# End of the report block.
# ======================================================================================

# ======================================================================================
# Batch: many records × many designs into one table (isolator/batch.py).
# (Block owned by the batch issue; the `bench` command goes after it.)
# ======================================================================================


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
    component: str = typer.Option(None, "--component", "-c", help=RECORD_HELP["component"] + "  Or "
                                  "'all-horizontal': every horizontal component of multi-component files."),
    dt: float = typer.Option(None, "--dt", help="Time step [s] of the one-column text records that give none "
                             "(other files keep their own)."),
    scale_to_pga: float = typer.Option(None, "--scale-to-pga", help="Scale every record to this peak ground "
                                       "acceleration, in g."),
    output: str = typer.Option(..., "--output", "-o", help="Table to write: .csv or .parquet."),
    jobs: int = typer.Option(None, "--jobs", "-j", min=1, help="Local processes (default: all cores)."),
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
    import sys

    from isolator.batch import BatchError, ReadOptions, parse_grid, run_batch

    try:
        grids = [parse_grid(spec) for spec in grid or []]
        if len({key for key, _ in grids}) != len(grids):
            raise BatchError("--grid: each key may be swept once")
        if dt is not None and not (math.isfinite(dt) and dt > 0):
            raise BatchError(f"--dt must be a time step > 0 in seconds, got {dt:g}")
        if scale_to_pga is not None and not scale_to_pga > 0:
            raise BatchError(f"--scale-to-pga must be > 0 (in g), got {scale_to_pga:g}")
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
    except BatchError as err:
        _user_error(str(err))
    options = ReadOptions(units=units, scale_to_pga_g=scale_to_pga, dt_s=dt, harmonic=not no_harmonic)

    progress_bar, callback = None, None
    if sys.stderr.isatty():
        from rich.console import Console
        from rich.progress import (BarColumn, MofNCompleteColumn, Progress, ProgressColumn, TextColumn,
                                   TimeElapsedColumn, TimeRemainingColumn)
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
                           progress=callback)
    except BatchError as err:
        if progress_bar is not None:
            progress_bar.stop()
        _user_error(str(err))
    except OSError as err:
        if progress_bar is not None:
            progress_bar.stop()
        _user_error(f"{getattr(err, 'filename', None) or output}: cannot write ({err.strerror or err})")
    except KeyboardInterrupt:
        if progress_bar is not None:
            progress_bar.stop()
        typer.echo(f"interrupted: finished rows are kept in {output}.parts/; run the same command again to resume",
                   err=True)
        raise typer.Exit(130) from None
    if progress_bar is not None:
        progress_bar.stop()
    for message in result.lost_messages:
        typer.echo(f"lost: {message}", err=True)
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
                write_table_atomically(suite_summary(result.table, swept), summary)
                rows.append(("summary", summary, ""))
            if chart is not None:
                pages = design_chart(result.table, swept[:2], chart)
                rows.append(("chart", chart, f"({pages} pages)"))
        except OSError as err:
            _user_error(f"cannot write ({err.strerror or err})")
    _echo_table(rows)
    typer.echo(result.final_line())
    if result.n_failed or result.n_lost_tasks:
        raise typer.Exit(1)

# ======================================================================================
# End of the batch block.
# ======================================================================================


# ======================================================================================
# Speed against error: the `bench` command.  (Block owned by the benchmark issue.)
# ======================================================================================

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
    import time
    from pathlib import Path

    from isolator import bench as bench_module
    from isolator.atomic import atomic_path, write_text_atomically

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
        write_text_atomically(out_dir / "bench.csv", bench_module.rows_to_csv(rows))
        write_text_atomically(out_dir / "bench_pareto.csv", bench_module.pareto_to_csv(pareto))
        write_text_atomically(out_dir / "bench.json", json.dumps(_json_safe(document), indent=1, allow_nan=False))
        write_text_atomically(out_dir / "bench.md", bench_module.pareto_markdown(pareto) + "\n"
                              + bench_module.rows_markdown(rows))
        with atomic_path(out_dir / "bench.png") as temporary:
            bench_module.plot(rows, temporary)
    except OSError as err:
        _user_error(f"{out}: cannot write ({err.strerror or err})")
    if as_json:
        typer.echo(json.dumps(_json_safe(rows), allow_nan=False))
        return
    typer.echo(bench_module.pareto_markdown(pareto))
    typer.echo(bench_module.rows_markdown(rows))
    typer.echo(f"{len(rows)} runs in {wall_s:.1f} s on {machine['processor']} ({machine['cpus']} CPUs); "
               f"written to {out_dir}/bench.csv, bench_pareto.csv, bench.json, bench.md, bench.png")


# The design-review command lives in its own module (isolator.review.command).
from isolator.review.command import register as _register_review  # noqa: E402

_register_review(app)
