"""Atomic file output: a file is either complete or absent, never half written.

Every output of isolator (CSV, JSON, PDF, PNG, Parquet, cached maps, batch parts) is
written to a temporary file beside its target and renamed onto it once complete;
a failure (or Ctrl-C) removes the temporary file and leaves any older target intact.
"""

from __future__ import annotations

import os
import tempfile
from contextlib import contextmanager
from pathlib import Path


@contextmanager
def atomic_path(path):
    """Yield a temporary path beside ``path``; rename it onto ``path`` on success.

    The temporary name keeps the target's extension (``.pdf``, ``.png``, ``.parquet``…)
    so that writers that infer the format from it work unchanged, and starts with a
    dot so that it stays out of listings.  The file gets ordinary permissions (mkstemp
    makes 0600) and is flushed to disk before the rename.

    Parameters
    ----------
    path : str or path-like
        The file to write; its folder is created if needed.
    """
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=target.suffix)
    os.close(handle)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(temporary, 0o666 & ~umask)
    try:
        yield Path(temporary)
        with open(temporary, "rb+") as stream:
            os.fsync(stream.fileno())
        os.replace(temporary, target)
    finally:
        if os.path.exists(temporary):
            os.unlink(temporary)


def write_text_atomically(path, text: str) -> None:
    """Write ``text`` (UTF-8) to ``path`` atomically."""
    with atomic_path(path) as temporary:
        temporary.write_text(text, encoding="utf-8")
