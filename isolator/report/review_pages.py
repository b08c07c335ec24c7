"""The review PDF: rendering only (every number comes from :meth:`isolator.review.run.Review.to_dict`).

Pages, in order: the summary (the design's and the target's inputs echoed, the headline counts) and the
checks (clause, value, limit, unit, status, the whole note), flowing over as many pages as they need,
then the parameters used with their marks, the notes and the traceability table (software, command,
SHA-256 of every input file); the target and suite spectra (range, floor, T_M of both bounds marked);
the analyses per pair and bound (a numbered key with the full pair names and their metadata; analyses
past the displacement capacity marked; the spread per bound); orbits and the bounding envelope; and,
as an appendix, the paper's measures.  Every page's footer carries the software version, the commit and
a digest of the input hashes.  Text is never cut: it wraps, at 7 pt or more.
"""

from __future__ import annotations

import hashlib
import json
import textwrap
from pathlib import Path

import numpy as np

from isolator.atomic import atomic_paths
from isolator.report import figures
from isolator.report.layout import A4_IN, fmt

STATUS_COLOUR = {"pass": "#1a7f37", "fail": "#c62828", "not checked": "#6e6e6e"}
BOUND_COLOUR = {"lower": "#1f77b4", "upper": "#d62728", "nominal": "#7f7f7f"}
NOTE_PT = 7.0  #: the smallest type on any page [pt]
#: characters per line of 7 pt text across the page's width (DejaVu Sans, measured on the rendered pages)
CHARS_FULL = 140
LINE = 0.0118  #: one 7-7.5 pt line [figure fraction]
TOP, BOTTOM = 0.935, 0.055  #: where the flowing text starts and stops [figure fraction]


def short(text, width: int) -> str:
    """``text`` cut to ``width`` characters with an ellipsis (only for labels whose full text is printed
    elsewhere on the same page, e.g. a plot title)."""
    text = " ".join(str(text).split())
    return text if len(text) <= width else text[: width - 1] + "…"


def wrap(text, width: int) -> list[str]:
    """``text`` wrapped at ``width`` characters (never cut)."""
    return textwrap.wrap(" ".join(str(text).split()), width, break_long_words=True, break_on_hyphens=False) or [""]


def inputs_digest(inputs: dict) -> str:
    """SHA-256 of the sorted ``path  sha256`` lines of the inputs (one number for the footer)."""
    text = "\n".join(f"{path}  {digest}" for path, digest in sorted(inputs.items()))
    return hashlib.sha256(text.encode()).hexdigest()


def footer_text(r: dict, page: int) -> str:
    """The footer of every page: software, commit, inputs digest, date, page."""
    sw = r.get("software") or {}
    commit = sw.get("commit")
    commit_text = (f"commit {commit[:12]}" + (" (with uncommitted changes)" if sw.get("dirty") else "")
                   if commit else "not run from a git checkout")
    inputs = r.get("inputs") or {}
    return (f"isolator {sw.get('version', '?')}, {commit_text} · {r['created_utc']} · inputs: {len(inputs)} files, "
            f"digest {inputs_digest(inputs)[:16]} (each file's SHA-256 in the traceability table and the JSON) · "
            f"page {page}")


class Flow:
    """Text pages that continue on a new page when full (rows are never cut, notes wrap)."""

    def __init__(self, pdf, r: dict, counter: list):
        self.pdf, self.r, self.counter = pdf, r, counter
        self.fig = None
        self.y = TOP

    def page(self, title: str, subtitle: str = "") -> None:
        self.close()
        self.counter[0] += 1
        self.fig = new_page(title, subtitle)
        self.y = TOP
        self.title = title

    def need(self, height: float) -> None:
        if self.fig is None or self.y - height < BOTTOM:
            self.page(self.title + (" (continued)" if not self.title.endswith("(continued)") else ""))

    def text(self, x: float, text: str, size: float = NOTE_PT, **kwargs) -> None:
        """One line at ``x`` [figure fraction] with its top at the flow's height (``weight``, ``color``,
        ``family`` as ``fig.text``)."""
        line(self.fig, x, self.y, text, size, **kwargs)

    def heading(self, text: str) -> None:
        self.need(4 * LINE)
        self.y -= 0.4 * LINE
        self.text(0.05, text, 9.5, weight="bold")
        self.y -= 1.45 * LINE

    def paragraph(self, text: str, x: float = 0.05, width: int = CHARS_FULL, size: float = NOTE_PT,
                  color="0.1") -> None:
        for line in wrap(text, width):
            self.need(LINE)
            self.text(x, line, size, color=color)
            self.y -= LINE

    def close(self) -> None:
        if self.fig is not None:
            add_footer(self.fig, self.r, self.counter[0])
            self.pdf.savefig(self.fig)
            self.fig = None


def line(fig, x: float, y: float, text: str, size: float, **style) -> None:
    """One line of text on ``fig`` at (x, y) [figure fraction], ``size`` [pt], its top at y unless ``va`` says
    otherwise; ``style``: ``weight``, ``color``, ``family``, ``ha``, ``va`` as ``fig.text`` takes them.  Drawn
    by the page's :class:`isolator.report.text_lines.TextLines` (the same PDF text, half the shaping)."""
    from isolator.report.text_lines import text_lines

    text_lines(fig).add(x, y, str(text), size=size, **style)


def new_page(title: str, subtitle: str = ""):
    fig = figures.new_figure(figsize=A4_IN)
    line(fig, 0.05, 0.975, title, 13, weight="bold")
    if subtitle:
        for k, text in enumerate(wrap(subtitle, 120)[:2]):
            line(fig, 0.95, 0.952 - k * 0.011, text, 7.5, ha="right", color="0.35")
    return fig


def add_footer(fig, r: dict, page: int) -> None:
    for k, text in enumerate(reversed(wrap(footer_text(r, page), 150))):
        line(fig, 0.05, 0.012 + k * 0.011, text, NOTE_PT, va="bottom", color="0.35")


def _caption(fig, text: str, y: float = 0.04) -> None:
    """A figure page's caption, wrapped, above the footer."""
    for k, text_line in enumerate(reversed(wrap(text, CHARS_FULL))):
        line(fig, 0.05, y + k * LINE, text_line, NOTE_PT, va="bottom", color="0.15")


# ---- the summary, the checks, the parameters, the notes, the traceability -------------------------------

def _design_lines(r: dict) -> list[tuple[str, str]]:
    d, b = r["design"], r["property_bounds"]
    g = d["gravity_m_s2"]
    weight = d["mass_kg"] * g
    kind = (f"friction pendulum, R = {fmt(d['radius_m'])} m (pendulum period {fmt(d['isolated_period_s'])} s)"
            if d["radius_m"] else f"flat slider with spring K = {fmt(d['stiffness_N_per_m'] / 1e3)} kN/m")
    friction = f"µs = {fmt(d['mu_static'])}, µk = {fmt(d['mu_kinetic'])} (nominal)"
    if (d.get("bearing") or {}).get("type") in ("double", "triple"):  # the top-level numbers are its equivalent
        kind = f"equivalent single pendulum R = {fmt(d['radius_m'])} m (all surfaces sliding; see Bearing)"
        friction += " of the equivalent single pendulum; the analyses and the ELF use the bearing's surfaces"
    if d.get("mu_fast") is not None:
        friction += (f"; µ(v): µ_slow {fmt(d['mu_slow'])}, µ_fast {fmt(d['mu_fast'])}, "
                     f"a = {fmt(d['rate_s_per_m'])} s/m")
    plan = d.get("plan")
    plan_text = ("none: D_TM = " + fmt(r["torsion"]["factor"]) + " D_M (the floor of Eq. 17.5-3)" if not plan else
                 f"b × d = {fmt(plan['b_m'])} × {fmt(plan['d_m'])} m, eccentricity "
                 f"{fmt(plan.get('eccentricity_m', 0.0))} m"
                 + eccentricity_said(r["torsion"]) + ", "
                 + (f"y = {fmt(plan['y_m'])} m" if "y_m" in plan else
                    "y = the farthest bearing (the bearing layout)" if "layout" in r["torsion"]["basis"]
                    else "y = half the plan dimension (assumed)")
                 + f", P_T = {fmt(r['torsion'].get('P_T'))}"
                 + p_t_floor_said(r["torsion"])
                 + f" → D_TM/D_M = {fmt(r['torsion']['factor'])}")
    if r["torsion"].get("code") == "en15129":  # EN 1998-1 10.9.6's δ_i, not ASCE's D_TM/D_M
        plan_text = f"largest δ_i = {fmt(r['torsion']['factor'])}: {r['torsion']['basis']}"
    bounds = (f"µ lower {fmt(b['mu_lower'])} (λ_min {fmt(b['lambda_min'])}), nominal {fmt(b['mu_nominal'])}, upper "
              f"{fmt(b['mu_upper'])} (λ_max {fmt(b['lambda_max'])}); {b['basis']}")
    if "surface_mu" in r["bounds"].get("lower", {}):  # a double / triple: the µ_i each bound's analyses and ELF used
        bounds = ("µ_i (surfaces in file order) " + ", ".join(
            f"{bound} {bound_friction(r, bound)} (λ {fmt(r['bounds'][bound]['lambda'])})"
            for bound in ("lower", "nominal", "upper") if bound in r["bounds"])
                  + f"; {b['basis']}; the equivalent single pendulum's µ lower {fmt(b['mu_lower'])}, upper "
                    f"{fmt(b['mu_upper'])} (not analysed)")
    lines = [("Design", f"{d['name']}  (file {d['source']})"),
             ("Weight, isolator", f"W = {fmt(weight / 1e3)} kN (M = {fmt(d['mass_kg'])} kg); {kind}"),
             ("Friction", friction),
             ("Property bounds", bounds),
             ("Capacity", f"{fmt(d['displacement_capacity_m'])} m (bearing displacement, resultant)"
              if d["displacement_capacity_m"] else "not given (displacement_capacity_m)"),
             ("Plan", plan_text)]
    lines += _structure_lines(r)
    if d.get("damping_Ns_per_m"):
        lines.insert(3, ("Damper", f"γ = {fmt(d['damping_Ns_per_m'] / 1e3)} kN·s/m (ratio {fmt(d['damping_ratio'])})"))
    return lines


def eccentricity_said(torsion: dict) -> str:
    """" ([plan]'s, used; the bearing layout's 0 / 0 m: 0.5 m apart)" where the design gives both eccentricities and
    they differ (the rows' torsion basis says the same); "" otherwise."""
    difference = torsion.get("eccentricity_difference_m")
    if not difference:
        return ""
    e_x, e_y = torsion["eccentricity_layout_m"]
    return (f" ([plan]'s, used; the bearing layout's {fmt(e_x)} / {fmt(e_y)} m ⟂ loading x / y: {fmt(difference)} m "
            f"apart, D_TM/D_M {fmt(torsion['factor_with_layout_eccentricity'])} with it)")


def p_t_floor_said(torsion: dict) -> str:
    """" (the floor P_T_min; 0.2918 from the design)" when the design's P_T is below the floor that was used, and
    " (assumed: …)" when the design gives no P_T (Eq. 17.5-3 then takes the floor)."""
    raw, used = torsion.get("P_T_raw"), torsion.get("P_T")
    if used is not None and f"P_T = {used:.4g} (assumed)" in torsion.get("basis", ""):  # the row notes say so; page 1
        return " (assumed: the design gives neither P_T nor a bearing layout; the floor P_T_min [U])"  # did not
    return (f" (the floor P_T_min; {fmt(raw)} from the design)" if raw is not None and used is not None and raw < used
            else "")


def bound_friction(r: dict, bound: str) -> str:
    """The friction a bound's analyses ran with: ``µ_i a/b/c/d`` of a double or triple bearing (λ on every µ_i; with
    µ(v) µ_fast of each surface), else ``µ = …``."""
    v = r["bounds"].get(bound, {})
    if "surface_mu" not in v:
        return f"µ = {fmt(v.get('mu'))}"
    if "surface_mu_fast" in v:
        return "µ_fast,i " + "/".join(fmt(m) for m in v["surface_mu_fast"])
    return "µ_i " + "/".join(fmt(m) for m in v["surface_mu"])


def models_text(r: dict) -> str:
    """Each model that ran, how many analyses ran it (naming them when they are fewer than half), and its
    ``model_reason``."""
    ran: dict = {}
    for b, v in r["bounds"].items():
        for name, res in v["pairs"].items():
            if res.get("model"):
                ran.setdefault(res["model"], {"reason": res.get("model_reason", ""), "who": []})["who"].append(
                    f"#{pair_key(r).get(name, '?')} {b}")
    total = sum(len(m["who"]) for m in ran.values())
    return "; ".join(f"{model} ({len(m['who'])} analyses" + ("" if 2 * len(m["who"]) > total else
                                                             ": " + ", ".join(m["who"]))
                     + (f"): {m['reason']}" if m["reason"] else ")") for model, m in sorted(ran.items()))


def _structure_lines(r: dict) -> list[tuple[str, str]]:
    """The superstructure, the bearing layout and a multi-surface bearing, when the design has them."""
    d, s = r["design"], r.get("structure") or {}
    lines = []
    bearing = d.get("bearing")
    if bearing and bearing["type"] != "single":
        surfaces = "; ".join(f"{i}: R_eff {fmt(x['effective_radius_m'])} m, µ {fmt(x['mu_kinetic'])}, d* "
                             f"{fmt(x['effective_capacity_m'])} m" for i, x in enumerate(bearing["surfaces"], 1))
        lines.append(("Bearing", f"{bearing['type']} friction pendulum ({surfaces}); ultimate "
                                 f"{fmt(bearing['ultimate_displacement_m'])} m = the capacity; λ on every µ_i"))
    sup = d.get("superstructure")
    if sup:
        lines.append(("Superstructure", f"{len(sup['floors'])} floors, W_s/W = {fmt(s.get('Ws_over_W'))}, fixed-base "
                                        f"T = {fmt(s.get('T_fixed_x_s'))} s (x), {fmt(s.get('T_fixed_y_s'))} s (y), "
                                        f"ζ = {fmt(sup['damping_ratio'])}"
                      + (f", R = {fmt(sup['response_modification_R'])}" if sup.get("response_modification_R") else "")))
        if s.get("story_drift_ratio"):
            lines.append(("Floors (suite)", "drift ratio per story " + ", ".join(fmt(v) for v in s["story_drift_ratio"])
                          + "; peak acceleration per floor " + ", ".join(fmt(v) for v in
                                                                        s["floor_peak_acceleration_m_s2"]) + " m/s²"))
    if d.get("bearing_position"):
        lines.append(("Bearings", bearings_text(r)))
    return lines


def bearings_text(r: dict) -> str:
    """Page 1's bearing line: the layout, and the suite's least and largest axial loads — unfactored, and under the
    2.3.6 combinations the `uplift` and `vertical_load_stability` rows check (their values), each said as such."""
    layout, s = r["design"]["bearing_position"], r.get("structure") or {}
    text = f"{len(layout['x_m'])} positions" + ("" if layout.get("axial_capacity_N") is None
                                                 else ", with axial capacities")
    if not s.get("bearing_axial_load_min_N"):
        return text
    # it printed the unfactored loads alone, beside rows whose values are the factored ones (session 25: "least
    # suite load −1817 kN" on page 1, `uplift` −3.47e6 N in the checks)
    text += (f"; least suite load {fmt(min(s['bearing_axial_load_min_N']) / 1e3)} kN, largest "
             f"{fmt(max(s['bearing_axial_load_max_N']) / 1e3)} kN (unfactored)")
    factored = s.get("factored_bearing_loads")
    if factored:
        text += (f"; factored by 2.3.6 [U] as the rows say: least {fmt(min(factored['min_N']) / 1e3)} kN (uplift), "
                 f"largest {fmt(max(factored['max_N']) / 1e3)} kN (vertical_load_stability)")
    return text


def _target_text(t: dict) -> str:
    kind = t["kind"]
    if kind == "asce7-two-period":
        text = f"two-period MCE_R: S_MS = {fmt(t['S_MS'])} g, S_M1 = {fmt(t['S_M1'])} g, T_L = {fmt(t['T_L'])} s"
        if "from_design_values" in t:
            text += " (1.5 × the design values)"
    elif kind == "en1998-elastic":
        text = (f"EN 1998-1 elastic: a_g = {fmt(t['a_g_g'])} g, S = {fmt(t['S'])}, T_B/T_C/T_D = "
                f"{fmt(t['T_B'])}/{fmt(t['T_C'])}/{fmt(t['T_D'])} s")
    else:
        text = f"table {t.get('spectrum_csv')} ({len(t.get('periods_s', []))} periods)"
    for key, label, unit in (("magnitude_range", "controlling M", ""), ("distance_km_range", "distance", " km"),
                             ("vs30_m_s_range", "V_s30", " m/s")):
        if key in t:
            text += f"; {label} {fmt(t[key][0])}–{fmt(t[key][1])}{unit}"
    if "mechanisms" in t:
        text += f"; mechanisms {', '.join(t['mechanisms'])}"
    return f"{t['name']}: {text}  (file {t['source']})"


def failed_analyses(r: dict) -> tuple[int, list]:
    """From a review's JSON: how many analyses ran, and ``(pair, bound, error)`` of each that failed."""
    done = [(name, bound, a.get("error")) for bound, b in r["bounds"].items() for name, a in b["pairs"].items()]
    return len(done), [entry for entry in done if entry[2]]


def _analyses_text(r: dict) -> str:
    n_run, broken = failed_analyses(r)
    held = [f"#{pair_key(r).get(name, '?')} {b}" for b, v in r["bounds"].items() for name, a in v["pairs"].items()
            if a.get("ultimate_displacement_reached") and a.get("rim_modelled", True)]
    return f"{n_run} run, {len(broken)} failed" + (
        f" (the rows needing them say not checked): {'; '.join(f'{n} ({b}): {e}' for n, b, e in broken)}"
        if broken else "") + (
        f"; {len(held)} reached the bearing's ultimate displacement ({', '.join(held)}): held at the rims after a "
        "plastic impact, they fail the capacity rows and no row passes on their response (the suite values include "
        "them)" if held else "")


def _summary(flow: Flow, r: dict) -> None:
    flow.page("Design review: summary and checks", f"{r['design']['name']} | {r['target']['name']}")
    suite = r["suite"]
    basis = r.get("run", {}).get("scaling_basis", r["scaling"])
    words = {"common": "one common factor computed by the tool", "fit": "shape factors fitted, then a common factor",
             "given": "the engineer's factors from the suite, not rescaled",
             "matched": "spectrally matched records, not rescaled"}.get(basis, basis)
    d, dt = r["design_displacement_m"], r["design_total_displacement_m"]
    lines = _design_lines(r) + [
        ("Target", _target_text(r["target"])),
        ("Suite", f"{len(suite['pairs'])} pairs read, {len(suite['failed'])} failed to read  ({suite['source']})"),
        ("Analyses", _analyses_text(r)),
        ("Code, scaling", f"{r['code']}; {basis}: {words}; spectra {r['spectrum_basis']}"),
        ("Period range", f"{fmt(r['period_range_s'][0])} – {fmt(r['period_range_s'][1])} s ({r['period_grid']['n']} "
                         f"periods); suite min ratio {fmt(r['suite_min_ratio'])} (required "
                         f"{fmt(r['min_ratio_required'])})"),
        ("Design values", f"D_M {fmt(d['value'])} m ({d['rule']} of {d['n']}, {d['governing_bound']} bound); total "
                          f"{fmt(dt['value'])} m ({dt['governs']} governs); ELF D_TM {fmt(r['D_TM_m'])} m; V/W "
                          f"{fmt(r['design_base_shear_coefficient']['value'])} "
                          f"({r['design_base_shear_coefficient']['governing_bound']} bound)")]
    for name, value in lines:
        for k, line in enumerate(wrap(value, 104)):
            flow.need(LINE)
            if k == 0:
                flow.text(0.05, name, 7.6, weight="bold")
            flow.text(0.2, line, 7.6)
            flow.y -= LINE
    counts = r["check_counts"]
    flow.y -= 0.5 * LINE
    flow.need(2 * LINE)
    flow.text(0.05, f"{counts['pass']} pass", 10, weight="bold", color=STATUS_COLOUR["pass"])
    flow.text(0.16, f"{counts['fail']} fail", 10, weight="bold", color=STATUS_COLOUR["fail"])
    flow.text(0.26, f"{counts['not checked']} not checked", 10, weight="bold", color=STATUS_COLOUR["not checked"])
    flow.text(0.46, "every row below is counted; 'not checked' names what the review lacks", NOTE_PT, color="0.3")
    flow.y -= 1.8 * LINE


CHECK_COLUMNS = ((0.05, "check"), (0.245, "clause"), (0.5, "value"), (0.6, "limit"), (0.69, "unit"),
                 (0.76, "status"))


def _check_header(flow: Flow) -> None:
    for x, head in CHECK_COLUMNS:
        flow.text(x, head, 7.6, weight="bold")
    flow.y -= 1.15 * LINE


def _checks(flow: Flow, r: dict) -> None:
    _check_header(flow)
    for row in r["checks"]:
        note = wrap(row["note"], 128) if row["note"] else []
        clause = wrap(row["clause"], 36)
        height = (max(1, len(clause)) + len(note)) * LINE + 0.25 * LINE
        if flow.y - height < BOTTOM:
            flow.need(height + 2 * LINE)
            _check_header(flow)
        status = row["status"]
        cells = (row["id"], clause[0], fmt(row["value"]), fmt(row["limit"]), row.get("unit", ""), status)
        for (x, _), cell in zip(CHECK_COLUMNS, cells, strict=True):
            flow.text(x, cell, 7.4, color=STATUS_COLOUR[status] if cell == status else "black",
                      weight="bold" if cell == status else "normal")
        flow.y -= LINE
        for line in clause[1:]:
            flow.text(0.245, line, 7.4)
            flow.y -= LINE
        for line in note:
            flow.text(0.07, line, NOTE_PT, color="0.3")
            flow.y -= LINE
        flow.y -= 0.25 * LINE


def _parameters(flow: Flow, r: dict) -> None:
    flow.heading("Parameters used (marks: U = unverified, a parameter by rule; S = secondary source; practice, "
                 "convention, interpretation, input)")
    def said(v):  # a text parameter (D_M_form, multisurface_activation) as it is; `--set D_M_form=SM1` raised here
        return "none" if v is None else v if isinstance(v, str) else fmt(v)

    for p in r["parameters"]:
        value = said(p["value"])
        changed = "" if p["value"] == p["default"] else f" (default {said(p['default'])})"
        source = f" — from the {p['source']}" if p.get("source") else ""
        flow.paragraph(f"{p['name']} = {value}{changed} [{p['mark']}]{source} — {p['rule']}: {p['meaning']}", x=0.05)


def _notes(flow: Flow, r: dict) -> None:
    if not r["notes"]:
        return
    flow.heading("Notes")
    for note in r["notes"]:
        flow.paragraph("• " + note)


def _traceability(flow: Flow, r: dict, command: str) -> None:
    flow.heading("Traceability")
    sw = r.get("software") or {}
    flow.paragraph(f"Software: isolator {sw.get('version')}; commit {sw.get('commit') or 'none (not a git checkout)'}"
                   + (" with uncommitted changes" if sw.get("dirty") else "") + f"; run {r['created_utc']}.")
    if command:
        flow.paragraph(f"Command: {command}")
    flow.paragraph("Input files and their SHA-256 (isolator review --verify on the JSON re-checks them and reruns "
                   "the numbers):")
    for path, digest in (r.get("inputs") or {}).items():
        lines = wrap(path, 56)
        flow.need(len(lines) * LINE)
        flow.text(0.05, digest, NOTE_PT, family="monospace")
        for line in lines:
            flow.text(0.56, line, NOTE_PT)
            flow.y -= LINE


def _spectra_page(review, r: dict):
    fig = new_page("Target and suite spectra", r["target"]["name"])
    s = review.spectra
    ax = fig.add_axes([0.1, 0.5, 0.84, 0.41])
    lo, hi = r["period_range_s"]
    for values in s["pairs_scaled_g"].values():
        ax.loglog(s["periods_s"], values, color="0.6", lw=0.6)
    ax.loglog([], [], color="0.6", lw=0.6, label=f"scaled pairs ({r['spectrum_basis']})")
    ax.loglog(s["periods_s"], s["suite_mean_scaled_g"], color="k", lw=1.8, label="suite average (scaled)")
    ax.loglog(s["periods_s"], s["target_g"], color="#d62728", lw=2.6, alpha=0.55, label="target")
    same = abs(r["min_ratio_required"] - 1.0) < 1e-12
    # drawn over the target in a dark dashed line, so that it stays visible where the two coincide (ratio 1)
    ax.loglog(s["periods_s"], r["min_ratio_required"] * s["target_g"], color="#5a0000", lw=1.0, ls=(0, (4, 3)),
              zorder=5, label=f"required floor {fmt(r['min_ratio_required'])} × target"
              + (" (on the target)" if same else ""))
    if "rotd50" in s:
        mean50 = np.mean(list(s["rotd50"]["pairs_scaled_g"].values()), axis=0)
        ax.loglog(s["rotd50"]["periods_s"], mean50, color="#2ca02c", lw=1.0, ls=":",
                  label="suite average RotD50 (information)")
    ax.axvspan(lo, hi, color="#ffe2b0", alpha=0.6, label=f"range {fmt(lo, 3)}–{fmt(hi, 3)} s")
    top = ax.get_ylim()[1]
    for b, style in (("upper", (0, (1, 1.5))), ("lower", (0, (5, 2)))):
        t_m = r["elf"].get(b, {}).get("T_M_s")
        if t_m is None or not np.isfinite(t_m):
            continue
        for axis in (ax,):
            axis.axvline(t_m, color=BOUND_COLOUR[b], lw=1.1, ls=style, label=f"T_M({b}) = {fmt(t_m, 3)} s")
        ax.text(t_m, top, f" T_M({b})", rotation=90, va="top", ha="right" if b == "upper" else "left",
                fontsize=7.5, color=BOUND_COLOUR[b])
    ax.set_xlabel("period T [s]")
    ax.set_ylabel("5 %-damped spectral acceleration [g]")
    ax.legend(loc="lower left")
    ax2 = fig.add_axes([0.1, 0.18, 0.84, 0.24])
    ax2.semilogx(review.grid_s, review.suite_ratio, color="k", lw=1.2, label="suite average / target")
    ax2.axhline(r["min_ratio_required"], color="#5a0000", ls=(0, (4, 3)), lw=1.0,
                label=f"required {fmt(r['min_ratio_required'])}")
    for b in ("upper", "lower"):
        t_m = r["elf"].get(b, {}).get("T_M_s")
        if t_m is not None and np.isfinite(t_m):
            ax2.axvline(t_m, color=BOUND_COLOUR[b], lw=1.0, ls=":", label=f"T_M({b})")
    figures.plain_log_labels(ax, ax2)
    ax2.set_xlabel("period T [s] (the grid of the check)")
    ax2.set_ylabel("ratio [-]")
    ax2.legend(loc="best")
    if r["code"] == "asce7-22":
        rule = (f"ASCE 7-22 17.3.3: {fmt(review.parameters['range_lo_factor'])} T_M(upper) to "
                f"{fmt(review.parameters['range_hi_factor'])} T_M(lower)")
    else:
        rule = (f"EN 1998-1 3.2.3.1.2(4): {fmt(review.parameters['en_range_lo_factor'])} T(upper) to "
                f"{fmt(review.parameters['en_range_hi_factor'])} T(lower)")
    _caption(fig, f"Top: target, scaled spectra of the pairs and their average; shaded: the scaling period range "
                  f"({rule}); vertical lines: T_M of the upper-bound (dotted) and lower-bound (dashed) properties.  "
                  f"Bottom: the ratio on the {r['period_grid']['n']} periods of the check (log-spaced, both ends and "
                  f"the T_M values included); minimum {fmt(r['suite_min_ratio'])} at "
                  f"{fmt(r['suite_min_ratio_period_s'], 3)} s.  Spectra: {r['spectrum_conventions']}.")
    return fig


def pair_key(r: dict) -> dict:
    """Pair name → its number in the key (#1, #2, … in the suite's order)."""
    return {name: k + 1 for k, name in enumerate(r["scale_factors"])}


def _metadata_text(meta: dict) -> str:
    parts = []
    if "magnitude" in meta:
        parts.append(f"M {fmt(meta['magnitude'], 3)}")
    if "distance_km" in meta:
        parts.append(f"R {fmt(meta['distance_km'], 3)} km")
    if "mechanism" in meta:
        parts.append(meta["mechanism"])
    if "vs30_m_s" in meta:
        parts.append(f"V_s30 {fmt(meta['vs30_m_s'], 4)} m/s")
    if "pulse" in meta:
        parts.append("pulse" if meta["pulse"] else "no pulse")
    return ", ".join(parts) if parts else "no metadata given"


def _pairs(flow: Flow, r: dict) -> None:
    flow.page("Analyses per pair and bound", r["design"]["name"])
    key = pair_key(r)
    bounds = [b for b in ("lower", "nominal", "upper") if b in r["bounds"]]
    cap = r["design"]["displacement_capacity_m"]
    columns = [(0.05, "#"), (0.09, "SF")]
    groups = []
    x = 0.16
    for quantity, unit, step in (("D", "m", 0.092), ("V/W", "-", 0.083)):
        groups.append((x, f"{quantity} [{unit}] at the bound"))
        for b in bounds:
            columns.append((x, b))
            x += step
    flow.heading("Peak resultant displacement D and base shear coefficient V/W of each analysis")
    for x, head in groups:
        flow.text(x, head, 7.2, weight="bold")
    flow.y -= LINE
    for x, head in columns:
        flow.text(x, head, 7.2, weight="bold")
    flow.y -= 1.15 * LINE
    beyond = impacts = 0
    failing = {(c.get("pair"), c.get("bound")) for c in r["checks"] if c["id"] == "record_capacity"
               and c["status"] == "fail"}  # at the corner bearing with capacity_at_corner, as the checks read it
    corner = next((c.get("torsion_factor") for c in r["checks"] if c.get("torsion_factor")), None)
    for name, factor in r["scale_factors"].items():
        flow.need(LINE)
        flow.text(0.05, f"#{key[name]}", 7.4)
        flow.text(0.09, fmt(factor), 7.4)
        x = 0.16
        for quantity in ("peak_displacement_m", "base_shear_coefficient"):
            for b in bounds:
                result = r["bounds"][b]["pairs"].get(name, {})
                value = result.get(quantity)
                over = quantity == "peak_displacement_m" and (name, b) in failing  # the record_capacity rows
                beyond += bool(over)
                impact = quantity == "base_shear_coefficient" and bool(result.get("ultimate_displacement_reached")
                                                                       and result.get("rim_modelled", True))
                impacts += impact
                text = "failed" if "error" in result else fmt(value) + (" *" if over else " †" if impact else "")
                flow.text(x, text, 7.4, color=STATUS_COLOUR["fail"] if over else "black",
                          weight="bold" if over else "normal")
                x += 0.092 if quantity == "peak_displacement_m" else 0.083
        flow.y -= LINE
    flow.y -= 0.3 * LINE
    if cap:
        flow.paragraph(f"* at or beyond the displacement capacity {fmt(cap)} m "
                       + (f"at the corner bearing (torsion factor {fmt(corner)} × the centre-of-mass D shown) "
                          if corner else "")
                       + f"({beyond} analyses; each is a failing record_capacity row on the checks pages).  A "
                       "pendulum that reaches it is held there by its rim (plastic impact, the impulse on the checks pages): its peak is the capacity and "
                       "understates the demand.  Where no rim is modelled (a flat slider) the analysis continues "
                       "past it as if the surface were unbounded: those numbers are not physical.",
                       color=STATUS_COLOUR["fail"])
    if impacts:
        flow.paragraph(f"† the analysis reached the bearing's ultimate displacement ({impacts} analyses): its V/W "
                       "includes the plastic impact of the slab (or the mass) on the rims, an idealisation of the "
                       "restraint; the suite values below include it, and no row passes on them (the checks pages).",
                       color=STATUS_COLOUR["fail"])
    flow.heading("Suite values and spread per bound (D and V/W over the analyses that ran)")
    multi = "surface_mu" in r["bounds"].get("lower", {})  # a double / triple: the µ_i of each bound below the table
    heads = ((0.05, "bound"), (0.14, "λ on µ_i" if multi else "µ"), (0.22, "rule"), (0.32, "D suite [m]"), (0.42, "std [m]"), (0.5, "CV"),
             (0.57, "max/mean"), (0.66, "V/W suite"), (0.75, "std"), (0.82, "CV"), (0.88, "max/mean"))
    for x, head in heads:
        flow.text(x, head, 7.2, weight="bold")
    flow.y -= 1.15 * LINE
    for b in bounds:
        v = r["bounds"][b]
        sd = r.get("spread", {}).get(b, {})
        d, vw = sd.get("peak_displacement_m", {}), sd.get("base_shear_coefficient", {})
        cells = (b, fmt(v["lambda"] if multi else v["mu"]), f"{v['rule']} of {v['n']}", fmt(v["D_M_rha_m"]), fmt(d.get("std")), fmt(d.get("cv"), 3),
                 fmt(d.get("max_over_mean"), 3), fmt(v["base_shear_coefficient"]), fmt(vw.get("std")),
                 fmt(vw.get("cv"), 3), fmt(vw.get("max_over_mean"), 3))
        flow.need(LINE)
        for (x, _), cell in zip(heads, cells, strict=True):
            flow.text(x, cell, 7.4)
        flow.y -= LINE
    if multi:
        flow.paragraph("Friction of each bound's analyses and ELF, surface by surface (file order): "
                       + "; ".join(f"{b} {bound_friction(r, b)}" for b in bounds) + ".")
    flow.paragraph("Suite value: mean of ≥ n_for_mean analyses, else the maximum.  std: sample standard deviation; "
                   "CV = std/mean.  D: peak resultant isolator displacement (vector sum of the two directions, 2-D "
                   "analysis of the scaled pair); V/W: peak transmitted (absolute) acceleration of the supported mass "
                   "/ g, the base shear coefficient of the isolation system.")
    flow.heading("Equivalent lateral force reference values (ASCE 7-22 17.5)")
    for b in ("lower", "upper"):
        if b not in r["elf"]:
            continue
        e = r["elf"][b]
        flow.paragraph(f"ELF {b} bound ({bound_friction(r, b) if multi else 'µ = ' + fmt(e['mu'])}): T_M = {fmt(e['T_M_s'])} s, β_M = {fmt(e['beta_M'])}, "
                       f"B_M = {fmt(e['B_M'])}, D_M = {fmt(e['D_M_m'])} m, D_TM = {fmt(e.get('D_TM_m'))} m, V_b/W = "
                       f"{fmt(e['V_b_over_W'])}" + (f", V_s/W = {fmt(e['V_s_over_W'])}" if "V_s_over_W" in e else ""))
    flow.paragraph("Engine (the model each analysis ran, and why): " + (models_text(r) or "n/a")
                   + f".  Torsion: {r['torsion']['basis']}.")
    flow.heading("Key to the pairs: names, metadata, processing")
    by_name = {p["name"]: p for p in r["suite"]["pairs"]}
    for name, number in key.items():
        pair = by_name.get(name, {})
        steps = [s.get("step", "") + (f" (strike {fmt(s['strike_deg'])}°, recorded azimuths "
                                      f"{fmt(s['azimuth_x_deg'])}° / {fmt(s['azimuth_y_deg'])}°)"
                                      if "strike_deg" in s else "")
                 for s in pair.get("processing", []) if any(word in s.get("step", "") for word in ("trim", "rotated"))]
        text = f"#{number}  {name} — {_metadata_text(pair.get('metadata', {}))}"
        if pair.get("scale_factor_given") is not None:
            text += f"; given factor {fmt(pair['scale_factor_given'])}"
        if pair.get("matched"):
            text += "; spectrally matched"
        if steps:
            text += "; " + "; ".join(steps)
        text += f"; files: {', '.join(pair.get('files', {}).values())}"
        flow.paragraph(text)
    for failure in r["suite"]["failed"]:
        flow.paragraph(f"not read: {failure['name']}: {failure['error']}", color=STATUS_COLOUR["fail"])


def _orbits_page(review, r: dict):
    fig = new_page("Orbits and bounding envelope", r["design"]["name"])
    key = pair_key(r)
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
        ax.set_title(f"{b} bound: #{key[name]} (D = {fmt(ok[name]['peak_displacement_m'], 3)} m)", fontsize=8.5)
        ax.set_xlabel("X_x [m]")
        ax.set_ylabel("X_y [m]")
    ax = fig.add_axes([0.1, 0.2, 0.85, 0.3])
    names = list(r["scale_factors"])
    xs = np.arange(len(names))
    width = 0.27
    for j, b in enumerate(b for b in ("lower", "nominal", "upper") if b in r["bounds"]):
        values = [r["bounds"][b]["pairs"][n].get("peak_displacement_m", np.nan) for n in names]
        ax.bar(xs + (j - 1) * width, values, width, color=BOUND_COLOUR[b], label=f"{b} ({bound_friction(r, b)})")
        ax.axhline(r["bounds"][b]["D_M_rha_m"], color=BOUND_COLOUR[b], lw=0.9, ls=":")
    if cap:
        ax.axhline(cap, color="k", ls="--", lw=1.0, label="capacity")
    ax.axhline(r["design_total_displacement_m"]["value"], color="k", lw=1.2, label="design total displacement")
    ax.set_xticks(xs, [f"#{key[n]}" for n in names], fontsize=7.5)
    ax.set_ylabel("peak resultant displacement [m]")
    ax.legend(loc="upper left", fontsize=7, ncol=2)
    _caption(fig, "Top: orbit (X_x against X_y) of the pair with the largest displacement at each bound, with the "
                  "displacement-capacity circle.  Bottom: the bounding envelope — each pair at the lower, nominal and "
                  "upper bound; dotted: the suite value of each bound; solid: the design total displacement "
                  "(torsion and ELF floor included); dashed: the capacity.  Pairs: "
                  + "; ".join(f"#{k} {n}" for n, k in key.items()) + ".")
    return fig


def paper_regimes(r: dict) -> dict:
    """bound → pair → the backbone regime its paper's point stands on (a double or triple: the regime the motion
    reached, :meth:`isolator.bearing.Bearing.point_regime`); empty for a single surface."""
    out = {b: {name: v["point_regime"] for name, v in r["bounds"][b]["pairs"].items() if v.get("point_regime")}
           for b in ("lower", "upper") if b in r["bounds"]}
    return {b: names for b, names in out.items() if names}


def _paper_page(review, r: dict):
    fig = new_page("Appendix A  The paper's measures (context, not a verdict)", r["design"]["name"])
    regimes = paper_regimes(r)
    alpha_text = ("α = PGA/(µ g) and k = A0/R on the line F/W = x/R + µ of the backbone regime each motion reached "
                  "(the 'on' columns: R the sum of the sliding surfaces' effective R, µ the line's F/W intercept at that bound's "
                  "µ_i; a regime past a rim, whose intercept is ≤ 0, is not a pendulum: the last one before it), not on "
                  "an equivalent µs no analysis ran; sliding needs α > 1"
                  if regimes else "α = PGA/(µs g) (sliding needs α > 1)")
    for k, text in enumerate(textwrap.wrap(
        "These are the measures of the paper behind isolator (Nicolas 2017), shown for context.  They are NOT "
        "design checks.  A = peak relative displacement / A0 with A0 = PGV²/PGA of the (resultant, scaled) ground "
        "motion: A compares the isolator's displacement with the amplitude of the harmonic motion of equal PGA and "
        "PGV, not with the ground's displacement, so A > 1 does not mean that the isolator amplifies the ground "
        f"motion.  {alpha_text}; slip = share of the D5-95 window spent sliding (the paper's ζ, at the samples).",
            135)):
        line(fig, 0.05, 0.93 - k * 1.2 * 7.6 / (72 * A4_IN[1]), text, 7.6)  # lines 1.2 x 7.6 pt apart
    ax = fig.add_axes([0.08, 0.47, 0.4, 0.34])
    y = 0.37
    for b in ("lower", "upper"):
        if b not in r["bounds"]:
            continue
        pairs = r["bounds"][b]["pairs"]
        alpha = [v.get("alpha", np.nan) for v in pairs.values()]
        a = [v.get("peak_displacement_over_a0", np.nan) for v in pairs.values()]
        ax.scatter(alpha, a, color=BOUND_COLOUR[b], label=f"{b} bound", s=18)
    ax.set_xlabel("α = PGA/(µ g), µ of the regime reached [-]" if regimes else "α = PGA/(µs g) [-]")
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
        axm.legend(loc="upper right", fontsize=7)
    line(fig, 0.05, y, "pair", 7.4, weight="bold")
    heads = ((0.4, "α lo"), (0.48, "A lo"), (0.56, "slip lo"), (0.66, "α up"), (0.74, "A up"), (0.82, "slip up"))
    ons = ((0.16, "lower"), (0.26, "upper")) if regimes else ()
    for x, head in (*heads, *((x, f"on ({b[:2]})") for x, b in ons)):
        line(fig, x, y, head, 7.4, weight="bold")
    y -= 0.015
    for name in r["scale_factors"]:
        line(fig, 0.05, y, f"#{pair_key(r)[name]}", 7.0)
        for x, b in ons:
            line(fig, x, y, regimes.get(b, {}).get(name, "-"), 7.0)
        for x0, b in ((0.4, "lower"), (0.66, "upper")):
            v = r["bounds"].get(b, {}).get("pairs", {}).get(name, {})
            for dx, key in ((0.0, "alpha"), (0.08, "peak_displacement_over_a0"), (0.16, "zeta_record")):
                line(fig, x0 + dx, y, fmt(v.get(key), 3), 7.0)
        y -= 0.013
    drawn = ("Right: the paper's (k, α) regime map of the steady harmonic response (one component) at the design's "
             "friction, with each scaled pair placed at its equivalent harmonic point (k = K A0/(M g), α = PGA/(µs g)); "
             "regions and shading as in the single-record report.  The map classifies a harmonic motion in one "
             "direction; the pairs were analysed in 2-D: context only.  " if review.paper_map is not None else
             "The paper's regime map is that of a rigid block on one surface: not drawn for a building or a double or "
             "triple bearing.  ")
    _caption(fig, ("Each pair's α and k on the backbone regime its motion reached at that bound (the 'on' columns).  "
                   if regimes else "") + drawn + "Pairs numbered as in the key of the analyses page.")
    return fig


def write_review_pdf(review, pdf_path, *, command: str = "", into: tuple | None = None) -> dict:
    """Write the review PDF and its JSON (same name, ``.json``) atomically; return the JSON dict (with
    ``pdf`` and ``pdf_pages``).

    ``into``: the (PDF, JSON) temporary files of a larger output set to write instead (``isolator design``'s,
    :func:`isolator.atomic.atomic_paths`); the caller renames them.
    """
    pdf_path = Path(pdf_path)
    if into is not None:
        return _write_review_files(review, pdf_path, *into, command)
    # the PDF and its JSON are one output set: both land, or neither (a full disk between them)
    with atomic_paths([pdf_path, pdf_path.with_suffix(".json")]) as (tmp, tmp_json):
        return _write_review_files(review, pdf_path, tmp, tmp_json, command)


def _write_review_files(review, pdf_path: Path, tmp, tmp_json, command: str) -> dict:
    from matplotlib.backends.backend_pdf import PdfPages

    r = review.to_dict()
    r["command"] = command
    counter = [0]
    with PdfPages(tmp) as pdf:
        flow = Flow(pdf, r, counter)
        _summary(flow, r)
        _checks(flow, r)
        _parameters(flow, r)
        _notes(flow, r)
        _traceability(flow, r, command)
        flow.close()

        def figure_page(fig):
            counter[0] += 1
            add_footer(fig, r, counter[0])
            pdf.savefig(fig)

        figure_page(_spectra_page(review, r))
        _pairs(flow, r)
        flow.close()
        figure_page(_orbits_page(review, r))
        figure_page(_paper_page(review, r))
        info = pdf.infodict()
        info["Title"] = f"isolator review: {r['design']['name']}"
        sw = r.get("software") or {}
        info["Creator"] = f"isolator {sw.get('version')}" + (f" ({sw['commit'][:12]})" if sw.get("commit") else "")
    r["pdf"] = str(pdf_path)
    r["pdf_pages"] = counter[0]
    tmp_json.write_text(json.dumps(r, indent=2, allow_nan=False) + "\n", encoding="utf-8")
    return r
