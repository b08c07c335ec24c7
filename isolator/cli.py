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
