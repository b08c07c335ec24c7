"""The PDF (and JSON) of a design under a pair of components: summary, ground motion, response.

Rendering only: every number comes from an :class:`~isolator.analysis.Analysis` of a planar
response (the JSON beside the PDF is its :meth:`~isolator.analysis.Analysis.to_dict`).
Pages: 1 summary (the model that ran and why, design, components, results, verdicts),
2 the ground motion of each component, 3 the response (orbit with the
displacement-capacity circle, resultant displacement history, hysteresis in each
direction).  Both files are written atomically.
"""

from __future__ import annotations

import textwrap
from pathlib import Path

import numpy as np

from isolator.atomic import atomic_paths, dump_json
from isolator.report.layout import caption, fmt, table, tail
from isolator.report.layout import page as layout_page
from isolator.report.model_pages import model_pages
from isolator.report.pair_figures import pair_response_page
from isolator.report.summary import parameters_sentence, summary_dict
from isolator.serialize import json_safe
from isolator.units import STANDARD_GRAVITY

PAGE_TITLES = ("1  Summary (bidirectional)", "2  Ground motion", "3  Isolator response in the plane")


def _page(number: int, subtitle: str):
    return layout_page(number, subtitle, PAGE_TITLES)


def _planar(values) -> np.ndarray:
    """An (N, 2) history; a 1-D history is along X."""
    values = np.asarray(values, dtype=np.float64)
    return values if values.ndim == 2 else np.column_stack((values, np.zeros_like(values)))


class _Planar:
    """The fields :func:`pair_response_page` draws, with 1-D histories put along X."""

    def __init__(self, response):
        self.time_s = response.time_s
        self.displacement_m = _planar(response.displacement_m)
        self.absolute_acceleration_m_s2 = _planar(response.absolute_acceleration_m_s2)
        self.peak_displacement_m = response.peak_displacement_m


def _summary_page(analysis, numbers: dict, label: str, command: str):
    fig = _page(1, label)
    d, results, record = analysis.design, {**numbers, **numbers["engineering"]}, numbers["record"]
    fig.text(0.05, 0.935, f"Model: {numbers['model']}", fontsize=11, weight="bold", va="top")
    fig.text(0.05, 0.915, textwrap.fill(f"Why: {numbers['model_reason']}.", 110), fontsize=8.5, va="top")
    design_rows = [("name", d.name), ("mass", f"{fmt(d.mass_kg)} kg"),
                   ("isolator", f"pendulum R = {fmt(d.radius_m)} m" if d.is_pendulum
                    else f"K = {fmt(d.stiffness_N_per_m)} N/m"),
                   ("friction", f"µs = {fmt(d.mu_static)}, µk = {fmt(d.mu_kinetic)}")]
    surfaces = d.bearing.surfaces if d.bearing is not None and not d.bearing.is_simple else ()
    if surfaces:  # a double or triple: its surfaces ran; R and µ above are its every-surface-sliding equivalent only
        design_rows[2:] = [("isolator", f"{d.bearing.kind}: R_i = {'/'.join(fmt(s.radius_m) for s in surfaces)} m "
                                        f"(equivalent R {fmt(d.radius_m)} m)"),
                           ("friction", f"µ_i = {'/'.join(fmt(s.mu_kinetic) for s in surfaces)} "
                                        f"(equivalent µ {fmt(d.mu_static)}: every surface sliding)")]
    if d.velocity_dependent:
        design_rows.append(("µ(v)", f"µ_slow = {fmt(d.mu_slow)}, µ_fast = {fmt(d.mu_fast)}, "
                                    f"a = {fmt(d.rate_s_per_m)} s/m"))
    design_rows += [("damper", f"γ = {fmt(d.damping_Ns_per_m)} N·s/m"),
                    ("displacement capacity", "not given" if d.displacement_capacity_m is None
                     else f"{fmt(d.displacement_capacity_m)} m")]
    y = table(fig, 0.05, 0.875, "Design", design_rows)
    files = list(dict.fromkeys(Path(c["path"]).name for c in record["components"].values()))
    record_rows = [("file" if len(files) == 1 else f"file {i + 1}", tail(name, 34)) for i, name in enumerate(files)]
    record_rows += [(axis, f"{tail(c['component'], 14)}, PGA {fmt(c['pga_m_s2'] / STANDARD_GRAVITY)} g")
                    for axis, c in record["components"].items()]
    record_rows.append(("samples", f"{record['npts']} × {fmt(record['dt_s'])} s"
                                   + ("" if record["uniform_sampling"] else " (mean; unequal steps)")))
    record_rows += [("units from", tail(c["units_source"], 40)) for c in list(record["components"].values())[:1]]
    record_rows += [("processing", step["step"]) for step in record["processing"]]
    if record["scaling"]:
        record_rows.append(("scaling", tail(record["scaling"], 48)))
    table(fig, 0.52, 0.875, "Ground motion", record_rows)
    result_rows = [
        ("peak displacement (resultant)", f"{fmt(results['peak_displacement_m'])} m"),
        *_capacity_rows(numbers["capacity_reading"]),
        ("residual displacement", f"{fmt(results['residual_displacement_m'])} m (x {fmt(results['residual_displacement_x_m'])}, "
                                  f"y {fmt(results['residual_displacement_y_m'])})"),
        ("peak velocity", f"{fmt(results['peak_velocity_m_s'])} m/s"),
        ("peak transmitted acceleration", f"{fmt(results['peak_transmitted_acceleration_m_s2'])} m/s²"),
        ("base shear coefficient", fmt(results["base_shear_coefficient"])),
        ("effective period at the peak", f"{fmt(results['effective_period_s'])} s"),
        ("slip time", f"{fmt(results['slip_time_s'])} s"),
        ("uplift", f"{fmt(results['uplift_time_s'])} s, {results['n_uplifts']} time(s)"),
        ("events", str(results["n_events"])),
        ("energy input / friction / viscous", f"{fmt(results['energy_input_J_per_kg'])} / "
                                              f"{fmt(results['energy_friction_J_per_kg'])} / "
                                              f"{fmt(results['energy_viscous_J_per_kg'])} J/kg"),
        ("energy balance error", f"{fmt(results['energy_balance_error_J_per_kg'], 2)} J/kg"),
        ("solver", f"{fmt(results['solver_seconds'] * 1e3, 3)} ms, {results['solver_status']}"),
    ]
    y = table(fig, 0.05, min(y, 0.66), "Results", result_rows, width=0.9)
    fig.text(0.05, y, "Verdicts", fontsize=9.5, weight="bold", va="top")
    y -= 0.02
    for sentence in numbers["verdicts"]:
        fig.text(0.05, y, textwrap.fill("• " + sentence, 120), fontsize=8, va="top")
        y -= 0.03
    fig.text(0.05, y, textwrap.fill(parameters_sentence(numbers["parameters"]), 130), fontsize=7, va="top",
             color="0.3")
    caption(fig, f"isolator: {textwrap.shorten(command, 140)}.  Resultant = Euclidean norm in the horizontal "
                  "plane; X and Y are the first and second horizontal components as read.  Energies per unit mass.")
    return fig


def capacity_numbers(analysis, parameters: list[dict] | None = None) -> dict:
    """Where the report reads the displacement it compares with the capacity, as the review does
    (:func:`isolator.review.record_checks.capacity_reading`): the corner bearing with a [plan], else the centre of
    mass; with the demand ratio there (None without a capacity).  The JSON's ``capacity_reading``."""
    from isolator.review.record_checks import capacity_reading

    overrides = {row["name"]: row["value"] for row in parameters or [] if row.get("source") == "set"}
    reading = capacity_reading(analysis.design, overrides)
    ratio = analysis.displacement_demand_ratio
    return {**reading, "displacement_m": reading["factor"] * analysis.response.peak_displacement_m,
            "demand_ratio": None if ratio is None else reading["factor"] * ratio}


def _capacity_rows(reading: dict) -> list[tuple[str, str]]:
    """The demand / capacity rows of page 1, saying where the displacement is read."""
    if not reading["at_corner"]:
        return [("demand / capacity", fmt(reading["demand_ratio"], 3)
                 + ("" if reading["demand_ratio"] is None else " (centre of mass)"))]
    return [("demand / capacity (corner)", f"{fmt(reading['demand_ratio'], 3)}: the corner bearing, torsion factor "
                                           f"{fmt(reading['factor'], 4)} × the centre of mass"),
            ("torsion factor", textwrap.shorten(reading["basis"], 95, placeholder=" …"))]


def _ground_page(analysis, label: str):
    fig = _page(2, label)
    parts = analysis.components
    axes = fig.subplots(len(parts), 1, sharex=True)
    axes = np.atleast_1d(axes)
    fig.subplots_adjust(left=0.11, right=0.95, top=0.93, bottom=0.1, hspace=0.3)
    for ax, (axis, motion) in zip(axes, parts.items(), strict=False):
        values = motion.acceleration_m_s2 / STANDARD_GRAVITY
        ax.plot(motion.time_s, values, color="k", lw=0.6)
        ax.set_ylabel(f"{axis}: {motion.component}  [g]")
        ax.set_xlim(motion.time_s[0], motion.time_s[-1])
    axes[-1].set_xlabel("time  [s]")
    caption(fig, "Ground acceleration of each component as analysed (after the processing listed on page 1), "
                  "linear between samples.  Z is up positive: the normal force per unit mass is n = g + a_z.")
    return fig


def write_pair_report(analysis, pdf_path, *, command: str = "", parameters: list[dict] | None = None) -> dict:
    """Write the PDF of an :class:`~isolator.analysis.Analysis` of a planar response and its JSON (``.json``).

    The JSON is :meth:`~isolator.analysis.Analysis.to_dict` (the analysis schema)
    with ``pdf``.

    Parameters
    ----------
    analysis : isolator.analysis.Analysis
        From :func:`isolator.analysis.analyse` on a pair (or one component with µ(v)).
    pdf_path : str or Path
        Output PDF [-]; the JSON goes beside it.
    command : str
        The command line, printed on page 1.
    parameters : list of dict, optional
        The review parameters the pages use (:func:`isolator.report.summary.report_parameters`; default: their
        defaults), printed on page 1 and in the JSON.

    Returns
    -------
    dict
        The JSON written (:func:`isolator.report.summary.summary_dict`: ``to_dict()``, ``parameters``, ``pdf``).
    """
    from matplotlib.backends.backend_pdf import PdfPages

    pdf_path = Path(pdf_path)
    numbers = summary_dict(analysis, parameters=parameters)
    numbers["capacity_reading"] = capacity_numbers(analysis, numbers.get("parameters"))
    first = next(iter(analysis.components.values()))
    if pdf_path.suffix.lower() != ".pdf":
        raise ValueError(f"{pdf_path}: a report is a .pdf")
    label = f"{analysis.design.name} | {Path(analysis.record_label).name or first.component}"
    labels = tuple(m.component for m in list(analysis.components.values())[:2])
    if len(labels) < 2:
        labels = (labels[0], "Y (zero)")
    with atomic_paths([pdf_path, pdf_path.with_suffix(".json")]) as (tmp_pdf, tmp_json):  # both files or neither
        with PdfPages(tmp_pdf) as pdf:
            for fig in (_summary_page(analysis, numbers, label, command), _ground_page(analysis, label)):
                pdf.savefig(fig)
            fig = _page(3, label)
            fig.subplots_adjust(left=0.1, right=0.96, top=0.93, bottom=0.08, hspace=0.45, wspace=0.32)
            pair_response_page(fig, _Planar(analysis.response), analysis.design.mass_kg,
                               capacity_m=analysis.design.displacement_capacity_m, labels=labels)
            caption(fig, f"Model {numbers['model']}: {numbers['model_reason']}.  Top: the orbit of the bearing "
                          "(relative displacement X_x against X_y), with the displacement-capacity circle where the "
                          "design gives one.  Middle: resultant |X| and each component.  Bottom: isolator force "
                          "(−M × absolute acceleration of the mass) against displacement, in each direction.")
            pdf.savefig(fig)
            for fig in model_pages(analysis, numbers, label, len(PAGE_TITLES) + 1):  # building, multi-surface bearing
                pdf.savefig(fig)
            info = pdf.infodict()
            info["Title"] = f"isolator bidirectional review: {label}"
        numbers["pdf"] = str(pdf_path)
        dump_json(json_safe(numbers), tmp_json)
    return numbers

