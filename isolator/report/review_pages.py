"""The review PDF: rendering only (every number comes from :meth:`isolator.review.run.Review.to_dict`).

Pages: 1 checks (clause, value, limit, status) with the parameters used and their marks; 2 target
and suite spectra with the period range and the floor; 3 the per-pair table at both bounds; 4
orbits of the governing pairs and the bounding envelope; 5 the paper's measures, labelled as such.
"""

from __future__ import annotations

import json
import textwrap
from pathlib import Path

import numpy as np

from isolator.atomic import atomic_path
from isolator.report import figures
from isolator.report.layout import A4_IN, fmt

TITLES = ("1  Design review: checks", "2  Target and suite spectra", "3  Analyses per pair and bound",
          "4  Orbits and bounding envelope", "5  The paper's measures (context, not a verdict)")
STATUS_COLOUR = {"pass": "#1a7f37", "fail": "#c62828", "not checked": "#6e6e6e"}
BOUND_COLOUR = {"lower": "#1f77b4", "upper": "#d62728", "nominal": "#7f7f7f"}


def short(text, width: int) -> str:
    """``text`` cut to ``width`` characters with an ellipsis (long names must not overprint)."""
    text = " ".join(str(text).split())
    return text if len(text) <= width else text[: width - 1] + "…"


def _page(number: int, subtitle: str):
    fig = figures.new_figure(figsize=A4_IN)
    fig.text(0.05, 0.975, TITLES[number - 1], fontsize=13, weight="bold", va="top")
    fig.text(0.95, 0.952, short(subtitle, 95), fontsize=7.5, va="top", ha="right", color="0.35")
    return fig


def _caption(fig, text: str, y: float = 0.012) -> None:
    fig.text(0.05, y, textwrap.fill(text, 150), fontsize=7.0, va="bottom", ha="left", color="0.15")


def _checks_page(r: dict, command: str):
    fig = _page(1, f"{r['design']['name']} | {r['target']['name']}")
    y = 0.935
    lines = [("Design", short(r["design"]["name"], 80) + f"  ({short(Path(r['design']['source']).name, 40)})"),
             ("Target", short(r["target"]["name"], 90)),
             ("Suite", f"{len(r['suite']['pairs'])} pairs read, {len(r['suite']['failed'])} failed  "
                       f"({short(r['suite']['source'], 70)})"),
             ("Code, scaling", f"{r['code']}, '{r['scaling']}' scale factors on {r['spectrum_basis']}"),
             ("Friction bounds", f"µ lower {fmt(r['property_bounds']['mu_lower'])}, nominal "
                                 f"{fmt(r['property_bounds']['mu_nominal'])}, upper "
                                 f"{fmt(r['property_bounds']['mu_upper'])}  (λ_min {fmt(r['property_bounds']['lambda_min'])},"
                                 f" λ_max {fmt(r['property_bounds']['lambda_max'])})"),
             ("Bounds basis", r["property_bounds"]["basis"]),
             ("Period range", f"{fmt(r['period_range_s'][0])} – {fmt(r['period_range_s'][1])} s "
                              f"({r['period_grid']['n']} periods); suite min ratio {fmt(r['suite_min_ratio'])} "
                              f"(required {fmt(r['min_ratio_required'])})"),
              ("Displacements", f"D_M {fmt(r['design_displacement_m']['value'])} m "
                                     f"({r['design_displacement_m']['rule']} of {r['design_displacement_m']['n']}, "
                                     f"{r['design_displacement_m']['governing_bound']} bound); total "
                                     f"{fmt(r['design_total_displacement_m']['value'])} m; ELF D_TM "
                                     f"{fmt(r['D_TM_m'])} m")]
    for name, value in lines:
        fig.text(0.05, y, name, fontsize=7.8, weight="bold", va="top")
        fig.text(0.2, y, short(value, 105), fontsize=7.8, va="top")
        y -= 0.0155
    y -= 0.008
    columns = ((0.05, "check"), (0.225, "clause"), (0.49, "value"), (0.6, "limit"), (0.7, "status"), (0.79, "unit"))
    for x, head in columns:
        fig.text(x, y, head, fontsize=7.8, weight="bold", va="top")
    y -= 0.016
    for row in r["checks"]:
        status = row["status"]
        cells = (short(row["id"], 26), short(row["clause"], 42), fmt(row["value"]), fmt(row["limit"]),
                 status, short(row.get("unit", ""), 10))
        for (x, _), cell in zip(columns, cells, strict=False):
            fig.text(x, y, cell, fontsize=7.4, va="top", color=STATUS_COLOUR[status] if cell == status else "black",
                     weight="bold" if cell == status else "normal")
        y -= 0.0118
        fig.text(0.07, y, short(row["note"], 150), fontsize=6.2, va="top", color="0.35")
        y -= 0.0128
    counts = r["check_counts"]
    fig.text(0.05, y - 0.004, f"{counts['pass']} pass, {counts['fail']} fail, {counts['not checked']} not checked",
             fontsize=8.2, weight="bold", va="top")
    y -= 0.026
    fig.text(0.05, y, "Parameters used (mark from REVIEW_RULES: U = unverified, a parameter; S = secondary source)",
             fontsize=7.8, weight="bold", va="top")
    y -= 0.0145
    params = r["parameters"]
    half = (len(params) + 1) // 2
    for i, p in enumerate(params):
        x = 0.05 if i < half else 0.52
        yy = y - (i % half) * 0.0112
        flag = " [U]" if "U" in p["mark"].split("/") else f" [{p['mark']}]"
        value = "none" if p["value"] is None else (fmt(p["value"]) if not isinstance(p["value"], str) else p["value"])
        fig.text(x, yy, short(f"{p['name']} = {value}{flag}  {p['rule']}", 78), fontsize=6.3, va="top")
    y -= half * 0.0112 + 0.006
    lines = textwrap.wrap("Notes: " + " · ".join(r["notes"]), 145) if r["notes"] else []
    for line in lines[:4]:  # the JSON has them all
        fig.text(0.05, y, line, fontsize=6.3, va="top", color="0.25")
        y -= 0.011
    _caption(fig, f"{r['created_utc']} · {short(command, 200)} · every number on this page is in the JSON beside "
                  "the PDF.  'not checked' = the review lacks the input (named in the note).")
    return fig


def _spectra_page(review, r: dict):
    fig = _page(2, r["target"]["name"])
    s = review.spectra
    ax = fig.add_axes([0.1, 0.47, 0.84, 0.43])
    lo, hi = r["period_range_s"]
    for values in s["pairs_scaled_g"].values():
        ax.loglog(s["periods_s"], values, color="0.6", lw=0.6)
    ax.loglog([], [], color="0.6", lw=0.6, label=f"scaled pairs ({r['spectrum_basis']})")
    ax.loglog(s["periods_s"], s["suite_mean_scaled_g"], color="k", lw=1.8, label="suite average (scaled)")
    ax.loglog(s["periods_s"], s["target_g"], color="#d62728", lw=1.6, label="target")
    ax.loglog(s["periods_s"], r["min_ratio_required"] * s["target_g"], color="#d62728", lw=1.0, ls="--",
              label=f"floor {fmt(r['min_ratio_required'])} × target")
    if "rotd50" in s:
        mean50 = np.mean(list(s["rotd50"]["pairs_scaled_g"].values()), axis=0)
        ax.loglog(s["rotd50"]["periods_s"], mean50, color="#2ca02c", lw=1.0, ls=":",
                  label="suite average RotD50 (information)")
    ax.axvspan(lo, hi, color="#ffe2b0", alpha=0.6, label=f"range {fmt(lo, 3)}–{fmt(hi, 3)} s")
    ax.set_xlabel("period T [s]")
    ax.set_ylabel("5 %-damped spectral acceleration [g]")
    ax.legend(loc="lower left")
    ax2 = fig.add_axes([0.1, 0.1, 0.84, 0.27])
    ax2.semilogx(review.grid_s, review.suite_ratio, color="k", lw=1.2, label="suite average / target")
    ax2.axhline(r["min_ratio_required"], color="#d62728", ls="--", lw=1.0, label="required")
    ax2.set_xlabel("period T [s] (the grid of the check)")
    ax2.set_ylabel("ratio [-]")
    ax2.legend(loc="best")
    _caption(fig, f"Top: target, scaled spectra of the pairs and their average; shaded: the scaling period range "
                  f"(ASCE 7-22 17.3.3: {fmt(review.parameters.get('range_lo_factor', 0.2))} T_M upper bound to "
                  f"{fmt(review.parameters.get('range_hi_factor', 2.0))} T_M lower bound).  Bottom: the ratio on the "
                  f"{r['period_grid']['n']} periods of the check (log-spaced, both ends and the T_M values included); "
                  f"minimum {fmt(r['suite_min_ratio'])} at {fmt(r['suite_min_ratio_period_s'], 3)} s.  Spectra: "
                  f"{r['spectrum_conventions']}.")
    return fig


def _pairs_page(r: dict):
    fig = _page(3, r["design"]["name"])
    bounds = [b for b in ("lower", "upper") if b in r["bounds"]]
    columns = [(0.05, "pair", None), (0.33, "SF", None)]
    x = 0.39
    for b in bounds:
        for key, head in (("peak_displacement_m", "D [m]"), ("base_shear_coefficient", "V/W"),
                          ("residual_displacement_m", "res. [m]")):
            columns.append((x, f"{head} {b[:2]}", (b, key)))
            x += 0.093
    y = 0.93
    for x, head, _ in columns:
        fig.text(x, y, head, fontsize=7.6, weight="bold", va="top")
    y -= 0.017
    for name, factor in r["scale_factors"].items():
        fig.text(0.05, y, short(name, 40), fontsize=7.2, va="top")
        fig.text(0.33, y, fmt(factor), fontsize=7.2, va="top")
        for x, _, where in columns[2:]:
            result = r["bounds"][where[0]]["pairs"].get(name, {})
            text = "failed" if "error" in result else fmt(result.get(where[1]))
            fig.text(x, y, text, fontsize=7.2, va="top")
        y -= 0.0135
    y -= 0.006
    for b in bounds:
        v = r["bounds"][b]
        fig.text(0.05, y, f"suite value, {b} bound (µ = {fmt(v['mu'])}): {v['rule']} of {v['n']}: D = "
                          f"{fmt(v['D_M_m'])} m, V/W = {fmt(v['base_shear_coefficient'])}, residual = "
                          f"{fmt(v['residual_displacement_m'])} m, max D = {fmt(v['peak_displacement_max_m'])} m",
                 fontsize=7.4, va="top")
        y -= 0.015
    for b in ("lower", "upper"):
        e = r["elf"][b]
        fig.text(0.05, y, f"ELF {b}: T_M = {fmt(e['T_M_s'])} s, β_M = {fmt(e['beta_M'])}, B_M = {fmt(e['B_M'])}, "
                          f"D_M = {fmt(e['D_M_m'])} m, D_TM = {fmt(e.get('D_TM_m'))} m, V_b/W = "
                          f"{fmt(e['V_b_over_W'])}", fontsize=7.4, va="top")
        y -= 0.015
    models = sorted({res.get("model", "") for b in bounds for res in r["bounds"][b]["pairs"].values()})
    fig.text(0.05, y, f"Engine: {', '.join(m for m in models if m) or 'n/a'}; torsion: "
                      f"{short(r['torsion']['basis'], 110)}", fontsize=7.2, va="top")
    y -= 0.02
    for pair in r["suite"]["pairs"]:
        steps = [s.get("step", "") for s in pair["processing"] if "trim" in s.get("step", "")]
        if steps:
            fig.text(0.05, y, short(f"{pair['name']}: {steps[0]}", 150), fontsize=6.6, va="top", color="0.3")
            y -= 0.012
    for failure in r["suite"]["failed"]:
        fig.text(0.05, y, short(f"not read: {failure['name']}: {failure['error']}", 160), fontsize=6.6, va="top",
                 color="#c62828")
        y -= 0.012
    _caption(fig, "D: peak resultant isolator displacement (vector sum of the two directions, 2-D analysis of the "
                  "scaled pair); V/W: peak transmitted (absolute) acceleration of the supported mass / g, the base "
                  "shear coefficient of the isolation system; res.: resultant residual displacement.  lo/up: lower "
                  "and upper property bounds.  Suite value: mean of ≥ n_for_mean analyses, else the maximum.")
    return fig


def _orbits_page(review, r: dict):
    fig = _page(4, r["design"]["name"])
    cap = r["design"]["displacement_capacity_m"]
    theta = np.linspace(0, 2 * np.pi, 200)
    for i, b in enumerate(("lower", "upper")):
        results = review.analyses[b]
        ok = {n: v for n, v in results.items() if "error" not in v}
        if not ok:
            continue
        name = max(ok, key=lambda n: ok[n]["peak_displacement_m"])
        orbit = np.asarray(ok[name]["orbit_m"])
        ax = fig.add_axes([0.08 + 0.46 * i, 0.58, 0.4, 0.32])
        ax.plot(orbit[:, 0], orbit[:, 1], color=BOUND_COLOUR[b], lw=0.7)
        if cap:
            ax.plot(cap * np.cos(theta), cap * np.sin(theta), color="k", ls="--", lw=0.9, label="capacity")
            ax.legend(loc="upper right")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_title(short(f"{b} bound: {name} (D = {fmt(ok[name]['peak_displacement_m'], 3)} m)", 52))
        ax.set_xlabel("X_x [m]")
        ax.set_ylabel("X_y [m]")
    ax = fig.add_axes([0.1, 0.13, 0.85, 0.35])
    names = list(r["scale_factors"])
    xs = np.arange(len(names))
    width = 0.27
    for j, b in enumerate(b for b in ("lower", "nominal", "upper") if b in r["bounds"]):
        values = [r["bounds"][b]["pairs"][n].get("peak_displacement_m", np.nan) for n in names]
        ax.bar(xs + (j - 1) * width, values, width, color=BOUND_COLOUR[b], label=f"{b} (µ = {fmt(r['bounds'][b]['mu'], 3)})")
        ax.axhline(r["bounds"][b]["D_M_m"], color=BOUND_COLOUR[b], lw=0.9, ls=":")
    if cap:
        ax.axhline(cap, color="k", ls="--", lw=1.0, label="capacity")
    ax.axhline(r["design_total_displacement_m"]["value"], color="k", lw=1.2, label="design total displacement")
    ax.set_xticks(xs, [short(n, 16) for n in names], rotation=35, ha="right", fontsize=6.8)
    ax.set_ylabel("peak resultant displacement [m]")
    ax.legend(loc="upper left", fontsize=6.8, ncol=2)
    _caption(fig, "Top: orbit (X_x against X_y) of the pair with the largest displacement at each bound, with the "
                  "displacement-capacity circle.  Bottom: the bounding envelope — each pair at the lower, nominal and "
                  "upper bound; dotted: the suite value of each bound; solid: the design total displacement "
                  "(torsion and ELF floor included).")
    return fig


def _paper_page(review, r: dict):
    fig = _page(5, r["design"]["name"])
    fig.text(0.05, 0.93, textwrap.fill(
        "These are the measures of the paper behind isolator (Nicolas 2017), shown for context.  They are NOT "
        "design checks.  A = peak relative displacement / A0 with A0 = PGV²/PGA of the (resultant, scaled) ground "
        "motion: A compares the isolator's displacement with the amplitude of the harmonic motion of equal PGA and "
        "PGV, not with the ground's displacement, so A > 1 does not mean that the isolator amplifies the ground "
        "motion.  α = PGA/(µs g) (sliding needs α > 1); slip = share of the D5-95 window spent sliding (the paper's ζ, at the samples).", 135),
        fontsize=7.6, va="top")
    ax = fig.add_axes([0.08, 0.47, 0.4, 0.34])
    y = 0.37
    for b in ("lower", "upper"):
        if b not in r["bounds"]:
            continue
        pairs = r["bounds"][b]["pairs"]
        alpha = [v.get("paper_alpha", np.nan) for v in pairs.values()]
        a = [v.get("paper_A", np.nan) for v in pairs.values()]
        ax.scatter(alpha, a, color=BOUND_COLOUR[b], label=f"{b} bound", s=18)
    ax.set_xlabel("α = PGA/(µs g) [-]")
    ax.set_ylabel("A = D / A0,  A0 = PGV²/PGA [-]")
    ax.set_title("the paper's measures of each pair", fontsize=8.5)
    ax.legend(loc="best")
    if review.paper_map is not None:
        pm = review.paper_map
        axm = fig.add_axes([0.58, 0.47, 0.38, 0.34])
        figures.draw_regime_map(axm, pm["map"], show_legend=False,
                                title=f"harmonic regime map, {pm['bound']} µ, η = {fmt(pm['eta'], 3)}")
        axm.scatter([p[0] for p in pm["points"].values()], [p[1] for p in pm["points"].values()], marker="*",
                    s=40, color="k", zorder=5, label="pairs (equivalent points)")
        axm.legend(loc="upper right", fontsize=6.5)
    fig.text(0.05, y, "pair", fontsize=7.4, weight="bold", va="top")
    for x, head in ((0.4, "α lo"), (0.48, "A lo"), (0.56, "slip lo"), (0.66, "α up"), (0.74, "A up"),
                    (0.82, "slip up")):
        fig.text(x, y, head, fontsize=7.4, weight="bold", va="top")
    y -= 0.015
    for name in r["scale_factors"]:
        fig.text(0.05, y, short(name, 50), fontsize=7.0, va="top")
        for x0, b in ((0.4, "lower"), (0.66, "upper")):
            v = r["bounds"].get(b, {}).get("pairs", {}).get(name, {})
            for dx, key in ((0.0, "paper_alpha"), (0.08, "paper_A"), (0.16, "paper_slip_ratio")):
                fig.text(x0 + dx, y, fmt(v.get(key), 3), fontsize=7.0, va="top")
        y -= 0.013
    _caption(fig, "Right: the paper's (k, α) regime map of the steady harmonic response (one component) at the "
                  "design's friction, with each scaled pair placed at its equivalent harmonic point (k = K A0/(M g), "
                  "α = PGA/(µs g)); regions and shading as in the single-record report.  The map classifies a "
                  "harmonic motion in one direction; the pairs were analysed in 2-D: context only.")
    return fig


def write_review_pdf(review, pdf_path, *, command: str = "") -> dict:
    """Write the review PDF and its JSON (same name, ``.json``) atomically; return the JSON dict."""
    from matplotlib.backends.backend_pdf import PdfPages

    r = review.to_dict()
    r["command"] = command
    pdf_path = Path(pdf_path)
    with atomic_path(pdf_path) as tmp, PdfPages(tmp) as pdf:
        for make in (lambda: _checks_page(r, command), lambda: _spectra_page(review, r),
                     lambda: _pairs_page(r), lambda: _orbits_page(review, r),
                     lambda: _paper_page(review, r)):
            fig = make()
            pdf.savefig(fig)
        info = pdf.infodict()
        info["Title"] = f"isolator review: {r['design']['name']}"
    r["pdf"] = str(pdf_path)
    with atomic_path(pdf_path.with_suffix(".json")) as tmp:
        tmp.write_text(json.dumps(r, indent=2, allow_nan=False) + "\n", encoding="utf-8")
    return r
