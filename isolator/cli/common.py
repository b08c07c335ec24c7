"""What every command shares: the Typer app, record options, one-line errors, tables, JSON.

Library errors say what is wrong with a file or a value; the commands turn them into
one line on stderr and exit code 2 (:func:`user_error`), never a traceback.
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



def echo_json(value) -> None:
    """Print ``value`` as one line of strict JSON (NaN and ±inf as null)."""
    from isolator.serialize import dumps

    typer.echo(dumps(value))


def echo_table(rows) -> None:
    """Print (name, value, unit) rows aligned, one per line."""
    width = max(len(name) for name, _, _ in rows)
    for name, value, unit in rows:
        typer.echo(f"{name:<{width}}  {value} {unit}".rstrip())


def user_error(message: str) -> None:
    """End the command with one line on stderr and exit code 2."""
    typer.echo(f"error: {' '.join(str(message).split())}", err=True)
    raise typer.Exit(2)


def fmt(value, spec: str = ".6g") -> str:
    """``value`` formatted with ``spec``, or ``"n/a"`` for None."""
    return "n/a" if value is None else format(value, spec)


def write_csv_atomically(path, header: str, columns) -> None:
    """Write columns to CSV through a temporary file and a rename: never half a file."""
    import numpy as np

    from isolator.atomic import atomic_path

    with atomic_path(path) as temporary:
        np.savetxt(temporary, np.column_stack(columns), delimiter=",", header=header, comments="", fmt="%.17g")
