"""``isolator review --verify``: a review JSON re-checked against its inputs (same files, same numbers).

:func:`verify_review` reads a review JSON, checks that every input file still has the SHA-256 the JSON
records (:mod:`isolator.review.trace`), runs the review again from those inputs (no cache) and compares
every number of the checks, the scale factors and each analysis.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from isolator.review.trace import file_sha256, software

#: relative difference below which two numbers of a re-run are the same (the engine is deterministic;
#: this allows for the last bits of a sum taken in another order)
VERIFY_RTOL = 1e-9

#: The longest review JSON ``--verify`` reads [bytes]: the example review's is 124 kB; the bound keeps a device
#: (``/dev/zero``) or a huge file from being read until the memory runs out.
MAX_REVIEW_JSON_BYTES = 64 * 2**20


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
    isolator.errors.ReviewError
        The JSON cannot be read or is not a review JSON.
    """
    from isolator.atomic import read_regular_file
    from isolator.design import Design
    from isolator.errors import ReviewError
    from isolator.io._common import input_file_problem
    from isolator.review.run import run_review
    from isolator.review.suite import load_suite
    from isolator.review.target import load_target

    # a FIFO blocked for ever and /dev/zero was read until the memory ran out (15 GB in 4 min; session 24 sweep):
    # a regular file only, read up to a bound
    problem = input_file_problem(json_path)
    if problem is not None:
        raise ReviewError(f"{json_path}: cannot read the review JSON ({problem})")
    try:
        saved = json.loads(read_regular_file(json_path, MAX_REVIEW_JSON_BYTES).decode("utf-8"))
    except (OSError, ValueError, RecursionError) as err:  # RecursionError: arrays nested 100,000 deep (s17)
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
