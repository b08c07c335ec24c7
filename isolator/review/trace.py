"""Traceability of a review: the software that ran it, the SHA-256 of every input file, and a re-check.

A review's JSON carries ``software`` {``name``, ``version``, ``commit``, ``dirty``} (the commit when
isolator runs from a git checkout, else ``None``), ``inputs`` {path: sha256} of the design, the target
(and its spectrum table), the SUITE.toml and every record file, and ``run`` (the arguments that
reproduce it).  :func:`isolator.review.verify.verify_review` re-checks such a JSON.
"""

from __future__ import annotations

import functools
import hashlib
import subprocess
from pathlib import Path


def file_sha256(path) -> str:
    """SHA-256 of a file's bytes (hex)."""
    digest = hashlib.sha256()
    with open(path, "rb") as stream:
        for block in iter(lambda: stream.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


@functools.lru_cache(maxsize=1)
def software() -> dict:
    """``name``, ``version``, and — when isolator runs from a git checkout — ``commit`` and ``dirty``."""
    from isolator import __version__

    root = Path(__file__).resolve().parents[2]
    out = {"name": "isolator", "version": __version__, "commit": None, "dirty": None}
    if not (root / ".git").exists():
        return out
    try:
        commit = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True, text=True,
                                timeout=10, check=True).stdout.strip()
        status = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"],
                                capture_output=True, text=True, timeout=10, check=True).stdout
    except (OSError, subprocess.SubprocessError):
        return out
    out.update(commit=commit or None, dirty=bool(status.strip()))
    return out


def input_files(design, target, suite) -> list[str]:
    """The files a review read: design, target (and its table), SUITE.toml, every record (in that order)."""
    files = [design.source, target.source]
    if target.kind == "table":
        files.append(str(Path(target.source).parent / target.parameters["spectrum_csv"]))
    files += [a for a in suite.arguments if str(a).lower().endswith(".toml")]
    for pair in suite.pairs:
        files += pair.paths
    seen, out = set(), []
    for f in files:
        if f and f not in seen and Path(f).is_file():
            seen.add(f)
            out.append(str(f))
    return out


def input_hashes(design, target, suite) -> dict:
    """{path: sha256} of :func:`input_files`."""
    return {path: file_sha256(path) for path in input_files(design, target, suite)}
