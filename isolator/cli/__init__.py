"""Command-line interface: thin wrappers over the public API, no physics here.

One module per command group (:mod:`~isolator.cli.records`: info, simulate;
:mod:`~isolator.cli.harmonic`: harmonic, threshold; :mod:`~isolator.cli.report`:
report, regime-map; :mod:`~isolator.cli.batch`; :mod:`~isolator.cli.bench`;
:mod:`~isolator.cli.review`) over the
shared helpers of :mod:`~isolator.cli.common`.  Heavy imports (numpy, numba, obspy,
matplotlib) happen inside the commands so that ``isolator --help`` answers at once.
User mistakes end with one line on stderr and exit code 2, never a traceback.
"""

from __future__ import annotations

# registering the commands on ``app`` (in the order of ``isolator --help``)
from isolator.cli import batch, bench, harmonic, records, report, review  # noqa: E402,F401,I001
from isolator.cli.common import RECORD_HELP, app, load_record_for_cli

__all__ = ["RECORD_HELP", "app", "load_record_for_cli"]
