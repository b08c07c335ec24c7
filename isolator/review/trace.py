"""Traceability of a review: the software that ran it, the SHA-256 of every input file, and a re-check.

A review's JSON carries ``software`` {``name``, ``version``, ``commit``, ``dirty``} (the commit when
isolator runs from a git checkout, else ``None``), ``inputs`` {path: sha256} of the design, the target
(and its spectrum table), the SUITE.toml and every record file, and ``run`` (the arguments that
reproduce it).  :func:`verify_review` reads such a JSON, checks that every input still has its
hash, runs the review again from those inputs and compares every number of the checks, the scale
factors and each analysis: the same inputs must give the same numbers.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import subprocess
from pathlib import Path

#: relative difference below which two numbers of a re-run are the same (the engine is deterministic;
#: this allows for the last bits of a sum taken in another order)
VERIFY_RTOL = 1e-9


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


def _numbers(review: dict) -> dict:
    """The numbers a re-run must reproduce, flattened: {"where": value}."""
    out = {}
    for row in review.get("checks", []):
        key = f"check {row['id']}" + (f" {row.get('pair')} {row.get('bound')}" if "pair" in row else "")
        out[f"{key} status"] = row["status"]
        out[f"{key} value"] = row["value"]
        out[f"{key} limit"] = row["limit"]
    for name, factor in review.get("scale_factors", {}).items():
        out[f"scale factor {name}"] = factor
    for bound, values in review.get("bounds", {}).items():
        for name, r in values.get("pairs", {}).items():
            for key in ("peak_displacement_m", "base_shear_coefficient", "residual_displacement_m"):
                out[f"{bound} {name} {key}"] = r.get(key)
    out["design_displacement_m"] = review.get("design_displacement_m", {}).get("value")
    out["design_total_displacement_m"] = review.get("design_total_displacement_m", {}).get("value")
    return out


def _same(a, b) -> bool:
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        if math.isnan(a) and math.isnan(b):
            return True
        return abs(a - b) <= VERIFY_RTOL * max(abs(a), abs(b), 1e-300)
    return a == b


def compare(saved: dict, again: dict) -> list[str]:
    """The numbers of ``saved`` that ``again`` does not reproduce (one text per difference)."""
    old, new = _numbers(saved), _numbers(again)
    differences = [f"{key}: {old.get(key)!r} in the JSON, {new.get(key)!r} recomputed"
                   for key in sorted(set(old) | set(new)) if not _same(old.get(key), new.get(key))]
    return differences


def verify_review(json_path, *, jobs: int | None = None) -> dict:
    """Re-check a review JSON against its inputs: same input files, same numbers.

    Returns
    -------
    dict
        ``ok`` (bool), ``changed_inputs`` (paths whose hash differs or that are missing),
        ``differences`` (numbers not reproduced), ``software`` (of the JSON and of this run).

    Raises
    ------
    isolator.review.errors.ReviewError
        The JSON cannot be read or is not a review JSON.
    """
    from isolator.design import Design
    from isolator.review.errors import ReviewError
    from isolator.review.run import run_review
    from isolator.review.suite import load_suite
    from isolator.review.target import load_target

    try:
        saved = json.loads(Path(json_path).read_text(encoding="utf-8"))
    except (OSError, ValueError) as err:
        raise ReviewError(f"{json_path}: cannot read the review JSON ({err})") from None
    if not isinstance(saved, dict) or not {"inputs", "run", "checks"} <= set(saved):
        raise ReviewError(f"{json_path}: not a review JSON with inputs and run (written by isolator review)")
    changed = []
    for path, digest in saved["inputs"].items():
        if not Path(path).is_file():
            changed.append(f"{path} (missing)")
        elif file_sha256(path) != digest:
            changed.append(f"{path} (sha256 differs)")
    out = {"ok": False, "changed_inputs": changed, "differences": [],
           "software": {"json": saved.get("software"), "now": software()}}
    if changed:
        return out
    run = saved["run"]
    review = run_review(Design.from_toml(saved["design"]["source"]), load_target(saved["target"]["source"]),
                        load_suite(run["suite_arguments"], units=run.get("units"), trim=run.get("trim", False)),
                        code=saved["code"], scaling=saved["scaling"], jobs=jobs,
                        parameters=run.get("parameter_overrides") or {}, nominal=run.get("nominal", True))
    out["differences"] = compare(saved, review.to_dict())
    out["ok"] = not out["differences"]
    return out
