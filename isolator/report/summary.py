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

#: The review parameters (:data:`isolator.review.parameters.PARAMETERS`) that the single-record report's pages
#: use: its checks (:func:`isolator.review.record_checks.record_checks`) and the building page's drift limit.
REPORT_PARAMETERS = ("D_over_R_max", "restoring_min", "transmitted_over_pga_max", "sf_flag_low", "sf_flag_high",
                     "range_hi_factor", "usable_band_factor", "capacity_at_corner", "accidental_e", "D_TM_floor",
                     "P_T_min", "drift_limit_rha")


def report_parameters(overrides: dict | None = None) -> list[dict]:
    """The parameters of a report with their values, defaults, marks and clauses (``source`` "set" for an override).

    Parameters
    ----------
    overrides : dict, optional
        name → value (text from ``--set`` or a number), checked as the review checks them.

    Raises
    ------
    isolator.errors.ReviewError
        A name the report does not use, or a value of the wrong kind or outside its range.
    """
    from isolator.errors import ReviewError
    from isolator.review.parameters import resolve, table

    overrides = dict(overrides or {})
    unknown = [name for name in overrides if name not in REPORT_PARAMETERS]
    if unknown:
        raise ReviewError(f"'{unknown[0]}' is not a parameter of the report (its pages use: "
                          f"{', '.join(REPORT_PARAMETERS)})")
    values = resolve("asce7-22", overrides)
    empty = [name for name in overrides if values[name] is None]
    if empty:
        raise ReviewError(f"review parameter '{empty[0]}' must be a number for the report, got "
                          f"{overrides[empty[0]]!r}")
    rows = table("asce7-22", {name: values[name] for name in REPORT_PARAMETERS})
    return [{**row, "source": "set"} if row["name"] in overrides else row for row in rows]


def parameter_value(numbers: dict, name: str):
    """A report parameter's value from a report's numbers (``parameters``), else its default."""
    for row in numbers.get("parameters") or report_parameters():
        if row["name"] == name:
            return row["value"]
    raise KeyError(name)


def parameters_sentence(rows: list[dict]) -> str:
    """One sentence listing the report's parameters (value, mark; which were set), for the PDF."""
    return "Parameters of the checks (isolator report --set NAME=VALUE): " + ", ".join(
        f"{row['name']} = {row['value']:g} [{row['mark']}]" + (" (set)" if row.get("source") == "set" else "")
        for row in rows) + "."


def summary_dict(analysis: Analysis, pdf_path=None, parameters: list[dict] | None = None) -> dict:
    """The JSON of a report: the analysis schema (``docs/schema.md``), ``parameters`` (the review parameters its
    pages used, :func:`report_parameters`; the defaults when not given) and ``pdf`` when one is written."""
    out = analysis.to_dict()
    out["parameters"] = parameters if parameters is not None else report_parameters()
    if pdf_path is not None:
        out["pdf"] = str(pdf_path)
    return out


def write_json(analysis: Analysis, json_path, pdf_path=None, parameters: list[dict] | None = None) -> dict:
    """Write :func:`summary_dict` to ``json_path`` atomically (strict JSON); returns the dict."""
    summary = summary_dict(analysis, pdf_path, parameters)
    with atomic_path(Path(json_path)) as tmp_json:
        with open(tmp_json, "w") as stream:
            json.dump(summary, stream, indent=2, allow_nan=False)
            stream.write("\n")
    return summary
