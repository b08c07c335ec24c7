"""A one-line note for the user while something slow and silent runs: the first compilation of an engine.

numba compiles the 1-D kernel and the 2-D engine on their first use after installation
(the 2-D engine in about 40 s on a 2-core machine) and caches the machine code on disk;
later runs load it in a fraction of a second.  Without a word, a first run looks like a
hang.  The command line sets :data:`ENABLED`; the library then prints one line on stderr
if loading takes longer than :data:`NOTE_AFTER_S`, and nothing when the cache answers.
"""

from __future__ import annotations

import contextlib
import sys
import threading

#: print the notes (set by the command line; the Python API stays silent)
ENABLED = False
#: a load that takes longer than this is a compilation: say so [s]
NOTE_AFTER_S = 2.0


def _say(message: str) -> None:
    print(f"note: {message}", file=sys.stderr, flush=True)


@contextlib.contextmanager
def note_if_slow(message: str, after_s: float = NOTE_AFTER_S):
    """Print ``note: message`` on stderr if the block has not finished after ``after_s`` seconds
    (only when :data:`ENABLED`); the block itself runs unchanged."""
    if not ENABLED:
        yield
        return
    timer = threading.Timer(after_s, _say, args=(message,))
    timer.daemon = True
    timer.start()
    try:
        yield
    finally:
        timer.cancel()
