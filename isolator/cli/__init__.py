"""Command-line interface: thin wrappers over the public API, no physics here.

One module per command group (:mod:`~isolator.cli.records`: info, simulate;
:mod:`~isolator.cli.harmonic`: harmonic, threshold; :mod:`~isolator.cli.report`:
report, regime-map; :mod:`~isolator.cli.batch`; :mod:`~isolator.cli.bench`;
:mod:`~isolator.cli.review`; :mod:`~isolator.cli.design`) over the
shared helpers of :mod:`~isolator.cli.common`.  Heavy imports (numpy, numba, obspy,
matplotlib) happen inside the commands so that ``isolator --help`` answers at once.
User mistakes end with one line on stderr and exit code 2, never a traceback.
``isolator --version`` prints the version, and the git commit when run from a checkout.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

import typer

# registering the commands on ``app`` (in the order of ``isolator --help``)
from isolator.cli import batch, bench, design, harmonic, records, report, review  # noqa: E402,F401,I001
from isolator.cli.common import RECORD_HELP, app, load_record_for_cli

__all__ = ["RECORD_HELP", "app", "checkout_commit", "load_record_for_cli", "version_text"]

#: the group callback :mod:`~isolator.cli.common` registered (what every command run does first);
#: the one below adds ``--version`` to it
_GROUP_CALLBACK = app.registered_callback.callback


def checkout_commit(root: Path) -> str | None:
    """The short commit of the git checkout at ``root``, with ``+modified`` when tracked files differ
    from it; None outside a checkout (an installed wheel) or without git."""
    if not (root / ".git").exists():  # a directory in a clone, a file in a worktree
        return None
    try:
        head = subprocess.run(["git", "-C", str(root), "rev-parse", "--short", "HEAD"],
                              capture_output=True, text=True, timeout=10)
        if head.returncode != 0 or not head.stdout.strip():
            return None
        changed = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"],
                                 capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.SubprocessError):
        return None
    dirty = changed.returncode == 0 and bool(changed.stdout.strip())
    return head.stdout.strip() + ("+modified" if dirty else "")


def version_text() -> str:
    """``isolator 0.1.0``, or ``isolator 0.1.0 (git 878b052)`` when the package runs from a checkout."""
    import isolator

    commit = checkout_commit(Path(isolator.__file__).resolve().parents[1])
    return f"isolator {isolator.__version__}" + (f" (git {commit})" if commit else "")


def _print_version(value: bool) -> None:
    if value:
        typer.echo(version_text())
        raise typer.Exit()


@app.callback()
def _main(version: bool = typer.Option(False, "--version", is_eager=True, callback=_print_version,
                                       help="Print the version (and the git commit of a checkout) and exit.")
          ) -> None:
    """isolator: friction isolators under harmonic and recorded ground motion."""
    _GROUP_CALLBACK()
