"""What ``isolator design`` writes: the chart's data, the tables, the chart PDF and the recommended review.

This module holds the numbers behind the design chart (:func:`chart_data`: the grid of the two main varied
keys, each cell's state, the recommended point; :func:`paper_context`: the paper's regime map behind the
candidates' (k, α) points), where a search writes (:func:`output_paths`), the ranking page's columns
(:func:`ranking_columns`), the writing of every output atomically (:func:`write_outputs`) and the
recommended design as a design file of its own (:func:`design_toml`).
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np

from isolator.errors import ReviewError
from isolator.review.design_grid import OBJECTIVES
from isolator.review.design_space import DesignSearch

# ---- what the chart shows ------------------------------------------------------------------------

def chart_data(result: DesignSearch) -> dict:
    """The numbers behind the design chart: the grid of the two main varied keys and each cell's state.

    With more than two varied keys, the chart is the slice through the recommended candidate (the
    first candidate when none passes): the other keys are held at its values.

    Returns
    -------
    dict
        ``x_key``, ``y_key`` (None with one varied key), ``x``, ``y`` (the values), ``fixed`` (the other
        keys' values), ``candidate`` (index per cell, shape (ny, nx)), ``design_total_displacement_m``,
        ``base_shear_coefficient`` (NaN where not analysed), ``passes`` (bool), ``state`` (per cell:
        ``"pass"``, the first failing check id, or ``"not analysed"``), ``recommended`` (x, y) or None,
        ``paper`` (per candidate of the slice: k, α, state) and ``objective``.
    """
    keys = result.varied_keys
    x_key, y_key = keys[0], (keys[1] if len(keys) > 1 else None)
    best = result.recommended()
    anchor = best if best is not None else result.rows[0]
    fixed = {k: anchor[k] for k in keys[2:]}
    xs = list(dict(result.vary)[x_key])
    ys = list(dict(result.vary)[y_key]) if y_key else [None]
    shape = (len(ys), len(xs))
    cell = np.full(shape, -1, dtype=int)
    d_tm = np.full(shape, np.nan)
    vb = np.full(shape, np.nan)
    passes = np.zeros(shape, dtype=bool)
    state = np.full(shape, "not analysed", dtype=object)
    paper = []
    for row in result.rows:
        if any(row[k] != v for k, v in fixed.items()):
            continue
        i = ys.index(row[y_key]) if y_key else 0
        j = xs.index(row[x_key])
        cell[i, j] = row["candidate"]
        if row.get("error") is None:
            d_tm[i, j] = _number(row.get("design_total_displacement_m"))
            vb[i, j] = _number(row.get("base_shear_coefficient"))
            passes[i, j] = bool(row["passes"])
            state[i, j] = "pass" if row["passes"] else row["first_failing_check"]
        if row.get("paper_k") is not None and row.get("paper_alpha") is not None:
            paper.append((row["paper_k"], row["paper_alpha"], state[i, j], row["candidate"]))
    rec = None
    if best is not None and all(best[k] == v for k, v in fixed.items()):
        rec = (best[x_key], best[y_key] if y_key else None)
    return {"x_key": x_key, "y_key": y_key, "x": np.array(xs, float), "y": np.array(ys, float) if y_key else None,
            "fixed": fixed, "candidate": cell, "design_total_displacement_m": d_tm, "base_shear_coefficient": vb,
            "passes": passes, "state": state, "recommended": rec, "recommended_candidate":
            None if best is None else best["candidate"], "paper": paper, "objective": result.objective,
            "paper_regimes": sorted({r["paper_regime"] for r in result.rows if r.get("paper_regime")}),
            "isolated": _isolated_kind(result.design)}


def _isolated_kind(design) -> str:
    """What the search's candidates are, for the chart's caption: "a building on a double pendulum", "a triple
    pendulum", "a rigid block on one surface" …"""
    bearing = getattr(getattr(design, "bearing", None), "kind", "single") or "single"
    on = {"single": "one surface", "double": "a double pendulum", "triple": "a triple pendulum"}.get(bearing, bearing)
    return f"a building on {on}" if design.superstructure is not None else (
        "a rigid block on one surface" if bearing == "single" else on)


def _number(value) -> float:
    return float(value) if isinstance(value, (int, float)) and value is not None else math.nan


def paper_context(data: dict, result: DesignSearch, resolution: int = 30, jobs: int | None = None) -> dict | None:
    """The paper's harmonic regime map behind the candidates' (k, α) points (Nicolas 2017, Figs. 5–7).

    The map is drawn at the recommended candidate's nominal friction (the first analysed candidate's when none
    passes) with η = 0 unless the design has a damper (then the median over the suite, as the review does).
    In the paper's variables the map depends only on η and µk/µs, so it is every candidate's map when these
    are equal (the usual case: µs follows µk by the design's ratio); ``shared`` says whether they are.
    """
    from isolator.maps import design_frame, regime_map
    from isolator.review.run import paper_map_applies

    analysed = [r for r in result.rows if r.get("error") is None and r.get("paper_k") is not None]
    if resolution <= 0 or not analysed or not paper_map_applies(result.design):
        return None  # the map is a rigid block's on one surface (as isolator review: not for a building, a double …)
    anchor = next((r for r in analysed if r["candidate"] == data["recommended_candidate"]), analysed[0])
    ratios = {round(r["mu_kinetic"] / r["mu_static"], 12) for r in analysed}
    design = result.design
    if design.damping_Ns_per_m > 0:
        eta_note = "η from the design's damper (median over the suite)"
        eta = float(anchor.get("paper_eta") or 0.0)
    else:
        eta_note, eta = "no damper: η = 0", 0.0
    frame = design_frame(max(r["paper_alpha"] for r in analysed), max(r["paper_k"] for r in analysed))
    rmap = regime_map(eta, anchor["mu_static"], anchor["mu_kinetic"], k_range=frame["k"],
                      alpha_range=frame["alpha"], n_k=resolution, n_alpha=resolution, workers=jobs)
    return {"map": rmap, "eta": eta, "mu_static": anchor["mu_static"], "mu_kinetic": anchor["mu_kinetic"],
            "shared": len(ratios) == 1 and design.damping_Ns_per_m == 0, "note": eta_note}


# ---- outputs -------------------------------------------------------------------------------------

def output_paths(pdf_path) -> dict:
    """Where a search writes: the chart PDF, the tables beside it, the recommended review, the row store."""
    pdf = Path(pdf_path)
    stem = pdf.with_suffix("")
    return {"chart": pdf, "csv": stem.with_suffix(".csv"), "parquet": stem.with_suffix(".parquet"),
            "json": stem.with_suffix(".json"), "recommended_pdf": Path(f"{stem}.recommended.pdf"),
            "recommended_toml": Path(f"{stem}.recommended.toml"),
            "recommended_json": Path(f"{stem}.recommended.json"), "store": pdf.parent / f".{pdf.stem}.design"}


def ranking_columns(result: DesignSearch) -> list[str]:
    """Columns of the chart's ranking page."""
    column = OBJECTIVES[result.objective][0]
    first = ["candidate", *result.varied_keys, column]
    rest = [c for c in ("design_total_displacement_m", "base_shear_coefficient", "restoring_force_margin",
                        "governing_bound") if c not in first]
    return [*first, *rest]


def write_outputs(result: DesignSearch, pdf_path, target, suite, *, command: str = "", jobs: int | None = None,
                  scheduler: str | None = None, paper_map_resolution: int = 30) -> dict:
    """Write the table (CSV, Parquet, JSON), the chart PDF and the recommended candidate's full review.

    The files are one set (:func:`isolator.atomic.atomic_paths`): everything is computed first (the recommended
    review too), then every file is written to its temporary and the set renamed at once, so an interrupt or a
    write error leaves the older set whole, never a mixture of two runs.  The recommended candidate is reviewed
    again by :func:`~isolator.review.run.run_review` with the review command's extras (RotD50, the paper's map) and
    written by :func:`~isolator.report.review_pages.write_review_pdf`; its numbers are those of its row.  When no
    candidate passes, a recommended review left by an earlier run is removed with the renames (it would mislead).

    Returns
    -------
    dict
        The search JSON (:meth:`DesignSearch.to_dict`) with ``outputs`` and ``timing_s`` completed.
    """
    import hashlib
    import tomllib

    from isolator.atomic import atomic_paths
    from isolator.design import Design
    from isolator.report.design_chart import write_design_chart
    from isolator.report.review_pages import write_review_pdf
    from isolator.review.run import run_review
    from isolator.serialize import json_safe

    paths = output_paths(pdf_path)
    timing = dict(result.timing)
    start = time.perf_counter()
    table = result.table()
    timing["tables"] = time.perf_counter() - start

    start = time.perf_counter()
    data = chart_data(result)
    data["paper_map"] = paper_context(data, result, paper_map_resolution, jobs)
    timing["paper_map"] = time.perf_counter() - start
    best = result.recommended()
    lines = _summary_lines(result, best, data)
    column = OBJECTIVES[result.objective][0]
    ranked = sorted((r for r in result.rows if r.get("passes") and r.get("error") is None),
                    key=lambda r: (_number(r.get(column)), r["candidate"]))
    subtitle = f"{result.design.name} | {result.target_name} | {result.suite_source}"

    start = time.perf_counter()
    review, toml_text = None, None
    if best is not None:
        # the recommended design as a design file of its own: `isolator review --design` of it reproduces the review
        toml_text = design_toml(
            result.mappings[best["candidate"]],
            f"Recommended by `isolator design` ({result.objective}) from {result.design.source}: "
            + ", ".join(f"{k} = {best[k]!r}" for k in result.varied_keys))
        source = paths["recommended_toml"]
        mapping = tomllib.loads(toml_text)
        if "name" not in mapping:
            mapping = {"name": source.stem, **mapping}  # as Design.from_toml names an unnamed design
        review = run_review(Design.from_mapping(mapping, source=str(source)), target, suite, code=result.code,
                            scaling=result.scaling, jobs=jobs, scheduler=scheduler,
                            parameters=result.parameters, rotd50_points=12, paper_map_resolution=paper_map_resolution,
                            cache_dir=paths["store"] / "recommended")
        # the file is written with the set, after the review: its trace names the bytes it will hold
        inputs = review.trace.get("inputs", {})
        review.trace["inputs"] = {str(source): hashlib.sha256(toml_text.encode("utf-8")).hexdigest(),
                                  **{k: v for k, v in inputs.items() if k != str(source)}}
    timing["recommended_review"] = time.perf_counter() - start

    names = ["csv", "parquet", "chart", *(["recommended_toml", "recommended_pdf", "recommended_json"]
                                          if review is not None else []), "json"]
    stale = [] if review is not None else [paths[k] for k in ("recommended_pdf", "recommended_json",
                                                              "recommended_toml")]
    with atomic_paths([paths[k] for k in names], remove=stale) as temporaries:
        tmp = dict(zip(names, temporaries, strict=True))
        table.to_csv(tmp["csv"], index=False)
        _parquet_ready(table).to_parquet(tmp["parquet"], index=False)
        start = time.perf_counter()
        pages = write_design_chart(paths["chart"], data, {"subtitle": subtitle, "lines": lines}, ranked,
                                   ranking_columns(result), into=tmp["chart"])
        timing["chart"] = time.perf_counter() - start
        if review is not None:
            tmp["recommended_toml"].write_text(toml_text, encoding="utf-8")
            write_review_pdf(review, paths["recommended_pdf"], command=command,
                             into=(tmp["recommended_pdf"], tmp["recommended_json"]))
        result.timing = timing
        out = result.to_dict()
        out["outputs"] = {"chart": str(paths["chart"]), "chart_pages": pages, "csv": str(paths["csv"]),
                          "parquet": str(paths["parquet"]), "json": str(paths["json"]),
                          "recommended_pdf": str(paths["recommended_pdf"]) if review else None,
                          "recommended_json": str(paths["recommended_json"]) if review else None,
                          "recommended_design": str(paths["recommended_toml"]) if review else None,
                          "store": str(paths["store"])}
        out["command"] = command
        tmp["json"].write_text(json.dumps(json_safe(out), indent=2, allow_nan=False) + "\n", encoding="utf-8")
    return out


def _summary_lines(result: DesignSearch, best: dict | None, data: dict) -> list:
    """The (name, value) rows printed beside the paper's map on the chart page."""
    column = OBJECTIVES[result.objective][0]
    lines = [("objective", f"{result.objective}: least {OBJECTIVES[result.objective][1]}"),
             ("candidates", f"{len(result.rows)} ({sum(bool(r.get('passes')) for r in result.rows)} pass, "
                            f"{sum(r.get('error') is not None for r in result.rows)} not analysed)"),
             ("code, scaling", f"{result.code}, {result.scaling}")]
    if best is None:
        lines.append(("recommended", "none: no candidate passes every check"))
    else:
        lines += [("recommended", ", ".join(f"{k} = {best[k]:.4g}" for k in result.varied_keys)),
                  (column, f"{best[column]:.4g}"),
                  ("D_M, D_TM", f"{best['design_displacement_m']:.4g} m, {best['design_total_displacement_m']:.4g} m"),
                  ("V_b/W", f"{best['base_shear_coefficient']:.4g} ({best['base_shear_governing_bound']} bound)")]
    failing = {}
    for r in result.rows:
        if r.get("first_failing_check"):
            failing[r["first_failing_check"]] = failing.get(r["first_failing_check"], 0) + 1
    lines += [(f"first fails: {k}", f"{n} candidates") for k, n in sorted(failing.items(), key=lambda kv: -kv[1])]
    if data["paper_map"] is not None:
        pm = data["paper_map"]
        lines.append(("paper's map", f"µs {pm['mu_static']:.3g}, µk {pm['mu_kinetic']:.3g}, {pm['note']}"
                      + ("; the same for every candidate" if pm["shared"] else "; at the recommended candidate")))
    return lines


def design_toml(mapping: dict, comment: str = "") -> str:
    """A design table as TOML text: numbers written to round-trip exactly, sub-tables (``[plan]``,
    ``[superstructure]``) and arrays of tables (``[[superstructure.floor]]``, ``[[bearing_position]]``).

    Raises
    ------
    ReviewError
        A value TOML cannot hold (not a number, text, boolean, list or table; a non-finite number).
    """
    import re

    def key(k):
        return k if re.fullmatch(r"[A-Za-z0-9_-]+", k) else json.dumps(k, ensure_ascii=False)

    def value(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, int):
            return str(v)
        if isinstance(v, float) and math.isfinite(v):
            return repr(v)
        if isinstance(v, str):
            return json.dumps(v, ensure_ascii=False)  # a JSON string is a valid TOML basic string
        if isinstance(v, list) and not any(isinstance(x, dict) for x in v):
            return "[" + ", ".join(value(x) for x in v) + "]"
        raise ReviewError(f"design value {v!r} cannot be written as TOML")

    def is_tables(v):
        return isinstance(v, list) and v and all(isinstance(x, dict) for x in v)

    def emit(table: dict, prefix: str, lines: list) -> None:
        lines += [f"{key(k)} = {value(v)}" for k, v in table.items() if not isinstance(v, dict) and not is_tables(v)]
        for k, v in table.items():
            name = f"{prefix}.{key(k)}" if prefix else key(k)
            if isinstance(v, dict):
                lines += ["", f"[{name}]"]
                emit(v, name, lines)
            elif is_tables(v):
                for item in v:
                    lines += ["", f"[[{name}]]"]
                    emit(item, name, lines)

    lines = [f"# {line}" for line in comment.splitlines()]
    emit(mapping, "", lines)
    return "\n".join(lines) + "\n"


def _parquet_ready(table):
    """Object columns typed for Parquet (text, booleans or numbers; None stays missing)."""
    out = table.copy()
    for column in out.columns:
        if out[column].dtype != object:
            continue
        values = out[column].dropna()
        if len(values) and all(isinstance(v, bool) for v in values):
            out[column] = out[column].astype("boolean")
        elif len(values) and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
            out[column] = out[column].astype(float)
        else:
            out[column] = out[column].astype("string")
    return out
