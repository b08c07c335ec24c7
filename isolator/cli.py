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
