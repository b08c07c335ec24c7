"""The keys and the store of ``isolator design``'s finished rows (what makes a search resumable).

This module holds the version of the code a row was computed with (:func:`code_version`: isolator's
version and a digest of the review and 2-D engine sources), the content digest of any JSON-able value
(:func:`content_digest`), the key of everything a row depends on besides the design
(:func:`search_context_key`: target, suite samples, code, scaling, parameters) and :class:`RowStore`, one
JSON file per finished candidate, written atomically, read back by key.
"""

from __future__ import annotations

import functools
import hashlib
import json
from pathlib import Path

#: bump when the meaning of a stored row changes
STORE_VERSION = "design-1"

# ---- keys -------------------------------------------------------------------------------------

@functools.lru_cache(maxsize=1)
def code_version() -> str:
    """isolator's version and a digest of the review and 2-D engine sources: changed code misses the store."""
    from isolator import __version__

    root = Path(__file__).resolve().parents[1]
    digest = hashlib.sha256()
    for path in sorted([*(root / "review").rglob("*.py"), *(root / "solver").glob("planar*.py"), root / "design.py"]):
        digest.update(path.read_bytes())
    return f"{STORE_VERSION}+{__version__}+{digest.hexdigest()[:16]}"


def content_digest(value) -> str:
    """SHA-256 of the JSON of ``value`` (keys sorted), 32 hex digits."""
    return hashlib.sha256(json.dumps(value, sort_keys=True, default=repr).encode()).hexdigest()[:32]


def search_context_key(target, suite, code: str, scaling: str, parameters: dict | None) -> str:
    """Key of everything a row depends on besides the design: target, suite samples, code, scaling, parameters."""
    # a pair's given scale factor and its "matched" flag change a review as its samples do
    return content_digest([code_version(), target.as_dict(),
                           [(p.name, p.content_key(), getattr(p, "scale_factor", None), getattr(p, "matched", None))
                            for p in suite.pairs],
                           suite.failed, code, scaling, parameters or {}])


# ---- the store of finished rows ---------------------------------------------------------------

class RowStore:
    """One JSON file per finished candidate under ``directory``, named by the candidate's key (atomic writes)."""

    def __init__(self, directory):
        self.directory = Path(directory)

    def get(self, key: str):
        from isolator.atomic import MAX_CACHE_ENTRY_BYTES, read_regular_file

        try:  # a FIFO or a link to /dev/zero in the store is no row, never a blocked or endless read
            row = json.loads(read_regular_file(self.directory / f"{key}.json", MAX_CACHE_ENTRY_BYTES).decode("utf-8"))
        except (OSError, ValueError, RecursionError):  # RecursionError: nesting past the stack (s17)
            return None
        return row if isinstance(row, dict) and row.get("key") == key else None

    def put(self, row: dict) -> None:
        from isolator.atomic import write_text_atomically
        from isolator.serialize import json_safe

        write_text_atomically(self.directory / f"{row['key']}.json", json.dumps(json_safe(row), allow_nan=False))
