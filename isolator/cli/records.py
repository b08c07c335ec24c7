"""Commands on one record: ``info`` (what the file holds) and ``simulate`` (the exact response)."""

from __future__ import annotations

import typer

from isolator.cli.common import (
    RECORD_HELP,
    app,
    echo_json,
    echo_table,
    load_record_for_cli,
    user_error,
    write_csv_atomically,
)


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
        ("time step", f"{motion.dt_s:g}", "s"),
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
    record: str = typer.Argument(..., help="Record file: PEER AT2, plain text (time, acceleration), "
                                 "MiniSEED, SAC, K-NET, CSMIP V2, USGS SMC …"),
    mu_s: float = typer.Option(..., "--mu-s", help="Static friction coefficient µs."),
    mu_k: float = typer.Option(None, "--mu-k", help="Kinetic friction coefficient µk ≤ µs (default µs)."),
    stiffness_per_mass: float = typer.Option(0.0, "--stiffness-per-mass", help="K/M [1/s²] (g/R for a pendulum)."),
    damping_per_mass: float = typer.Option(0.0, "--damping-per-mass", help="γ/M [1/s]."),
    gravity: float = typer.Option(None, "--gravity", help="Gravity for the friction force [m/s²] "
                                  "(standard gravity by default; records in g are always converted "
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
    from isolator.solver.record import RecordInputError, simulate_record
    from isolator.solver.system import InvalidSystemError, System

    try:
        kwargs = {} if gravity is None else {"gravity_m_s2": gravity}
        system = System(mu_static=mu_s, mu_kinetic=mu_k, stiffness_per_mass=stiffness_per_mass,
                        damping_per_mass=damping_per_mass, **kwargs)
    except InvalidSystemError as err:
        user_error(str(err))
    motion = load_record_for_cli(record, component, units, merge, dt, response, counts_factor)
    try:
        result = simulate_record(motion.acceleration_m_s2, motion.dt_s, system=system)
    except RecordInputError as err:
        user_error(f"{record}: {err}")
    from isolator.analysis import MODEL_1D, SCHEMA_VERSION, record_dict

    # the analysis schema's slice for a record without a design: record, model and response keys
    summary = {"schema_version": SCHEMA_VERSION, "model": MODEL_1D, "record": record_dict(motion, str(record)),
               **result.summary()}
    if out_csv:
        try:
            write_csv_atomically(
                out_csv,
                "time_s,ground_acceleration_m_s2,displacement_m,velocity_m_s,absolute_acceleration_m_s2",
                [result.time_s, result.ground_acceleration_m_s2, result.displacement_m,
                 result.velocity_m_s, result.absolute_acceleration_m_s2])
        except OSError as err:
            user_error(f"{out_csv}: cannot write ({err.strerror or err})")
    if as_json:
        echo_json(summary)
        return
    echo_table([
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

