"""The numbers of a report: the analysis schema, written as JSON beside the PDF (or alone).

The analysis itself is :func:`isolator.analysis.analyse`; the report adds no physics.
:func:`summary_dict` is :meth:`isolator.analysis.Analysis.to_dict` (plus the PDF's path
when one is written); :func:`write_json` writes it atomically.
"""

from __future__ import annotations

import json
from pathlib import Path

from isolator.analysis import Analysis, analyse, verdicts  # noqa: F401 - the report's names for them
from isolator.atomic import atomic_path
from isolator.motion.examples import EXAMPLE_RECORDS, resolve_record  # noqa: F401 - re-exported


def summary_dict(analysis: Analysis, pdf_path=None) -> dict:
    """The JSON of a report: the analysis schema (``docs/schema.md``) and ``pdf`` when one is written."""
    out = analysis.to_dict()
    if pdf_path is not None:
        out["pdf"] = str(pdf_path)
    return out


def write_json(analysis: Analysis, json_path, pdf_path=None) -> dict:
    """Write :func:`summary_dict` to ``json_path`` atomically (strict JSON); returns the dict."""
    summary = summary_dict(analysis, pdf_path)
    with atomic_path(Path(json_path)) as tmp_json:
        with open(tmp_json, "w") as stream:
            json.dump(summary, stream, indent=2, allow_nan=False)
            stream.write("\n")
    return summary
