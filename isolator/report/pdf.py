"""The multi-page PDF of an engineering review, and the JSON of the same numbers beside it.

Pages: 1 summary (design, record, results, verdicts), 2 the record (acceleration,
velocity, displacement, response spectrum), 3 the response (time histories with
stick/slip shading, force–displacement loop, energy balance), 4 the design on the
harmonic regime map and the A(α) curve.  Both files are written atomically.
"""

from __future__ import annotations

import textwrap
from pathlib import Path

import numpy as np

from isolator.atomic import atomic_paths, dump_json
from isolator.metrics import REGIME_WORDS, slip_intervals
from isolator.report import figures
from isolator.report.layout import caption, fmt, page, table, tail
from isolator.report.model_pages import model_pages
from isolator.report.summary import Analysis, parameters_sentence, summary_dict, verdicts
from isolator.units import STANDARD_GRAVITY

PAGE_TITLES = ("1  Summary", "2  Ground motion", "3  Isolator response", "4  Harmonic regime map")


def _summary_page(a: Analysis, summary: dict, command: str):
    record_name = Path(a.record_label).name if Path(a.record_label).is_file() else a.record_label
    fig = page(1, f"{a.design.name} | {record_name}", PAGE_TITLES)
    d, p, r, im = a.design, a.adaptation.point, a.response, a.adaptation.intensity
    eng = a.engineering
    fig.text(0.05, 0.945, "Friction isolator - engineering review", fontsize=11, va="top")
    design_rows = [("name", textwrap.shorten(d.name, 38, placeholder="…")),
                   ("design file", tail(Path(d.source).name, 38)),
                   ("type", "friction pendulum" if d.is_pendulum else "flat slider with spring"),
                   ("mass M", f"{d.mass_kg:.6g} kg  (W = {fmt(d.weight_N / 1e3)} kN)")]
    if d.description:
        design_rows.insert(1, ("description", textwrap.shorten(d.description, 40, placeholder="…")))
    if d.is_pendulum:
        design_rows.append(("radius R", f"{fmt(d.radius_m)} m"))
    design_rows += [("stiffness K", f"{fmt(d.stiffness_N_per_m / 1e3)} kN/m"),
                    ("friction µs / µk", f"{fmt(d.mu_static)} / {fmt(d.mu_kinetic)}"),
                    ("damper γ", f"{fmt(d.damping_Ns_per_m / 1e3)} kN·s/m  (ratio {fmt(d.damping_ratio, 3)})"),
                    ("isolated period T", f"{fmt(d.isolated_period_s)} s"),
                    ("paper configuration", a.adaptation.system.configuration)]
    prov = a.motion.provenance
    record_rows = [("record", tail(record_name, 40))]
    for key, name in (("event", "event"), ("date", "date"), ("station", "station"),
                      ("station_name", "station name"), ("event_origin_time", "event origin (UTC)"),
                      ("starttime", "record start (UTC)"),
                      ("magnitude", "magnitude")):
        if key in prov:
            value = prov[key]
            record_rows.append((name, tail(fmt(value, 3) if isinstance(value, float) else str(value), 40)))
    record_rows += [("component", a.motion.component or "-"), ("format", str(prov.get("format", "-"))),
                    ("units from", textwrap.shorten(a.motion.units_source, 40, placeholder="…")),
                    ("samples", f"{a.motion.npts} × {fmt(a.motion.dt_s)} s = {fmt(a.motion.duration_s)} s")]
    for step in a.motion.processing:
        words = step.get("step", "")
        if "factor" in step:
            words += f" ×{fmt(step['factor'])}"
        if "target_pga_m_s2" in step:
            words += f" to PGA {fmt(step['target_pga_m_s2'] / STANDARD_GRAVITY, 3)} g"
        record_rows.append(("processing", textwrap.shorten(words, 40, placeholder="…")))
    im_rows = [("PGA", f"{fmt(im.pga_m_s2)} m/s²  ({fmt(im.pga_m_s2 / STANDARD_GRAVITY)} g)"),
               ("PGV", f"{fmt(im.pgv_m_s)} m/s"), ("PGD (baseline-corr.)", f"{fmt(im.pgd_m)} m"),
               ("Arias intensity", f"{fmt(im.arias_m_s)} m/s"), ("duration D5-95", f"{fmt(im.d5_95_s)} s"),
               ("predominant period", f"{fmt(im.predominant_period_s, 3)} s"),
               ("A0 = PGV²/PGA", f"{fmt(p.a0_m)} m"), ("Ω = PGA/PGV", f"{fmt(p.omega_rad_s)} rad/s")]
    y = table(fig, 0.05, 0.915, "Design", design_rows)
    y = table(fig, 0.05, y, "Record", record_rows)
    y_left = table(fig, 0.05, y, "Intensity measures", im_rows)

    point_rows = [("alpha = PGA/(µs g)", fmt(p.alpha)), ("k = K A0/(M g)", fmt(p.k)),
                  ("eta = (γ/M) sqrt(A0/g)", fmt(p.eta)), ("µs / µk", f"{fmt(p.mu_s)} / {fmt(p.mu_k)}")]
    result_rows = [
        ("peak displacement", f"{fmt(r.peak_displacement_m)} m"),
        ("residual displacement", f"{fmt(r.residual_displacement_m)} m"),
        ("peak velocity", f"{fmt(r.peak_velocity_m_s)} m/s"),
        ("peak transmitted acc.", f"{fmt(r.peak_transmitted_acceleration_m_s2)} m/s²  "
                                  f"({fmt(r.peak_transmitted_acceleration_m_s2 / STANDARD_GRAVITY)} g)"),
        ("peak transmitted force", f"{fmt(eng['peak_transmitted_force_N'] / 1e3)} kN"),
        ("base shear coefficient", fmt(eng["base_shear_coefficient"])),
        ("effective stiffness at D", f"{fmt(eng['effective_stiffness_N_per_m'] / 1e3)} kN/m"),
        ("effective period at D", f"{fmt(eng['effective_period_s'])} s"),
        ("effective damping at D", fmt(eng["effective_damping_ratio"], 3)),
        ("slip time / events", f"{fmt(r.slip_time_s)} s / {r.n_events}"),
        ("energy input", f"{fmt(r.energy_input_J_per_kg * d.mass_kg / 1e3)} kJ"),
        ("energy friction / viscous", f"{fmt(r.energy_friction_J_per_kg * d.mass_kg / 1e3)} / "
                                      f"{fmt(r.energy_viscous_J_per_kg * d.mass_kg / 1e3)} kJ"),
        ("energy balance error", f"{r.energy_balance_error_J_per_kg * d.mass_kg:.2e} J"),
    ]
    y = table(fig, 0.53, 0.915, "Equivalent harmonic point (paper, Eq. 6)", point_rows)
    y = table(fig, 0.53, y, "Key results (exact solver)", result_rows)
    rc, hc = a.record_class, a.harmonic_class
    fig.text(0.53, y, "Classification", fontsize=9.5, weight="bold", va="top")
    y -= 0.02
    rows = [("", "record", "harmonic map"), ("regime", rc.regime, hc.regime),
            ("slip-time ratio ζ", fmt(rc.zeta, 3), fmt(hc.zeta, 3)),
            ("amplitude A", fmt(rc.amplitude, 3), fmt(hc.amplitude, 3)),
            ("amplified (A > 1)", fmt(rc.amplified), fmt(hc.amplified)),
            ("dominant force", rc.dominant_force, hc.dominant_force),
            ("dominant (Eq. 5 ρ)", rc.dominant_force_rho, hc.dominant_force_rho),
            ("ρ_ev / ρ_vf / ρ_ef", f"{fmt(rc.rho_ev, 3)} / {fmt(rc.rho_vf, 3)} / {fmt(rc.rho_ef, 3)}",
             f"{fmt(hc.rho_ev, 3)} / {fmt(hc.rho_vf, 3)} / {fmt(hc.rho_ef, 3)}")]
    for i, (name, left, right) in enumerate(rows):
        weight = "bold" if i == 0 else "normal"
        fig.text(0.53, y, name, fontsize=7.8, va="top", weight=weight)
        fig.text(0.665, y, left, fontsize=7.8, va="top", weight=weight)
        fig.text(0.81, y, right, fontsize=7.8, va="top", weight=weight)
        y -= 0.0145
    y_right = y - 0.01
    y = min(y_left, y_right) - 0.005
    fig.text(0.05, y, "Checks that apply to one record (nominal properties; `isolator review` for a suite)",
             fontsize=9.5, weight="bold", va="top")
    y -= 0.02
    colours = {"pass": "#1a7f37", "fail": "#c62828", "not checked": "#6e6e6e"}
    for row in summary["checks"]:
        fig.text(0.06, y, row["id"], fontsize=7.6, va="top")
        fig.text(0.25, y, f"{fmt(row['value'])} vs {fmt(row['limit'])} {row['unit']}", fontsize=7.6, va="top")
        fig.text(0.42, y, row["status"], fontsize=7.6, va="top", weight="bold", color=colours[row["status"]])
        fig.text(0.52, y, textwrap.shorten(f"{row['clause']}; {row['note']}", 72, placeholder="…"), fontsize=6.4,
                 va="top", color="0.3")
        y -= 0.0132
    y -= 0.006
    fig.text(0.05, y, "Notes (the paper's measures are labelled as such)", fontsize=9.5, weight="bold", va="top")
    y -= 0.02
    notes = list(verdicts(a))
    if a.scaling_note:
        notes.insert(0, a.scaling_note)
    notes.append(parameters_sentence(summary["parameters"]))
    if not a.harmonic.steady:
        notes.append(f"Harmonic solver: {a.harmonic.status} (A is the amplitude reached, a lower bound).")
    for note in notes:
        wrapped = textwrap.wrap(note, 125)
        for j, line in enumerate(wrapped):
            fig.text(0.06, y, ("• " if j == 0 else "  ") + line, fontsize=7.8, va="top")
            y -= 0.0135
    caption(fig, f"isolator {summary['software']['version']}, {a.created_utc}.  Command: {command}  "
                  "Exact event-driven solution of M. Nicolas (2017)'s friction-spring-dashpot block, the record "
                  "taken as linear between samples.  Definitions: regime from the slip-time ratio ζ over D5-95 "
                  "(ST never slides, SL slides the whole window); A = half peak-to-peak relative displacement / A0; "
                  "dominant force from the peaks of µk M g, K|X|, γ|dX/dt|.  Numbers identical to the JSON beside "
                  "this PDF.")
    return fig


def write_report(analysis: Analysis, pdf_path, *, command: str = "", parameters: list[dict] | None = None) -> dict:
    """Render an analysis as a PDF and write its JSON beside it (same name, ``.json``); returns the JSON dict.

    The PDF only draws what the analysis holds: it needs the design on the regime map
    (``analyse(..., map_resolution=N)``).

    Parameters
    ----------
    analysis : Analysis
        From :func:`isolator.analysis.analyse` with ``map_resolution``.
    pdf_path : str or Path
        Output PDF [-]; the JSON goes beside it.
    command : str
        The command line, printed in the footer.
    parameters : list of dict, optional
        The review parameters of its checks (:func:`isolator.report.summary.report_parameters`; default: their
        defaults), printed on page 1 and in the JSON.

    Raises
    ------
    ValueError
        An analysis without the regime map or without the harmonic problem.
    """
    from matplotlib.backends.backend_pdf import PdfPages

    a = analysis
    if a.harmonic_map is None or a.harmonic_class is None:
        raise ValueError("a report needs the harmonic problem and the regime map: analyse(..., map_resolution=N)")
    pdf_path = Path(pdf_path)
    json_path = pdf_path.with_suffix(".json")
    summary = summary_dict(a, pdf_path, parameters)
    d, p, r = a.design, a.adaptation.point, a.response
    rc, hc = a.record_class, a.harmonic_class
    record_name = Path(a.record_label).name if Path(a.record_label).is_file() else a.record_label
    label = f"{d.name} | {record_name}"
    hmap = a.harmonic_map
    rmap, triple, map_resolution = hmap.regime_map, hmap.triple_point, hmap.resolution
    alphas, amplitudes, regimes, steady = hmap.alphas, hmap.amplitudes, hmap.regimes, hmap.steady

    with atomic_paths([pdf_path, json_path]) as (tmp_pdf, tmp_json):  # one set: both files or neither
        with PdfPages(tmp_pdf) as pdf:
            fig = _summary_page(a, summary, command)
            pdf.savefig(fig)

            # page 2: the record
            fig = page(2, label, PAGE_TITLES)
            fig.subplots_adjust(left=0.11, right=0.95, top=0.93, bottom=0.1, hspace=0.38)
            window = rc.window_s
            periods = np.geomspace(0.05, max(6.0, 1.5 * min(d.isolated_period_s, 20.0)), 120)
            psa = a.motion.response_spectrum(periods)
            figures.record_page(fig, a.motion, window, periods, psa, d.isolated_period_s,
                                a.engineering["effective_period_s"])
            caption(fig, "Ground acceleration as used in the analysis (after the processing listed on page 1); "
                          "velocity by trapezoidal integration from rest; displacement by double integration "
                          "with a least-squares quadratic baseline removed (display only: the solver uses the "
                          "acceleration).  Grey band: strong-motion window D5-95 (5 % to 95 % of the Arias "
                          "intensity).  Bottom: 5 %-damped pseudo-acceleration spectrum (exact first-order-hold "
                          "linear oscillator) with the isolated period 2π sqrt(M/K) and the effective period at "
                          "the peak displacement marked.")
            pdf.savefig(fig)

            # page 3: the response
            fig = page(3, label, PAGE_TITLES)
            fig.subplots_adjust(left=0.1, right=0.96, top=0.93, bottom=0.1, hspace=0.42, wspace=0.3)
            energies = figures.response_page(fig, r, d.mass_kg, slip_intervals(r))
            final = {name: values[-1] / 1e3 for name, values in energies.items()}
            caption(fig, "Exact response (closed forms between stick/slip events).  Shaded: the block slides "
                          f"relative to the ground ({fmt(r.slip_time_s)} s in all, {r.n_events} events).  "
                          "Transmitted acceleration = absolute acceleration of the supported mass; isolator "
                          "force = -M × that acceleration (friction + spring + damper).  Energy curves: "
                          "the solver's exact cumulative energies (input = -M∫a_g dX/dt dt, friction = "
                          "M µk g∫|dX/dt| dt, viscous = M(γ/M)∫(dX/dt)² dt); at the end input "
                          f"{fmt(final['input'])} kJ = kinetic + potential + friction {fmt(final['friction'])} kJ "
                          f"+ viscous {fmt(final['viscous'])} kJ, balance error "
                          f"{fmt(r.energy_balance_error_J_per_kg * d.mass_kg)} J.")
            pdf.savefig(fig)

            # page 4: the map
            fig = page(4, label, PAGE_TITLES)
            grid = fig.add_gridspec(2, 1, height_ratios=[1.35, 1], left=0.1, right=0.66, top=0.93,
                                    bottom=0.11, hspace=0.3)
            ax_map = fig.add_subplot(grid[0])
            figures.draw_regime_map(ax_map, rmap, triple=triple,
                                    design_point=(p.k, p.alpha, f"design, this record\n(k = {fmt(p.k, 3)}, "
                                                                f"α = {fmt(p.alpha, 3)})"),
                                    title=f"Regime map at η = {fmt(p.eta, 3)}, µs = {fmt(p.mu_s, 3)}, "
                                          f"µk = {fmt(p.mu_k, 3)}")
            ax_amp = fig.add_subplot(grid[1])
            figures.draw_amplitude_curve(ax_amp, alphas, amplitudes, regimes, steady=steady, alpha_record=p.alpha,
                                         amplitude_record=rc.amplitude, k=p.k, eta=p.eta)
            ax_amp.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), frameon=False)
            caption(fig, f"Top: the paper's (k, α) map (Figs. 5-7) at the design's η, µs, µk, zoomed to the "
                          f"design, {map_resolution} × {map_resolution} steady harmonic solutions.  Regime "
                          "boundaries are every change of regime along α; grey: A > 1; colours: the dominant "
                          "force (largest of kA, ηAω, µk, Eq. 5); ρ = 1 curves where they cross the frame.  The "
                          "star is the record's equivalent point (A0 = PGV²/PGA).  Bottom: steady amplitude of the "
                          "harmonic motion at the design's k and η against α, the record's α and its A marked.  "
                          f"Harmonic prediction at the star: {hc.regime} ({REGIME_WORDS[hc.regime]}), A = "
                          f"{fmt(hc.amplitude, 3)}; the record: {rc.regime}, A = {fmt(rc.amplitude, 3)}.")
            pdf.savefig(fig)
            for fig in model_pages(a, summary, label, len(PAGE_TITLES) + 1):  # the building's page
                pdf.savefig(fig)
            info = pdf.infodict()
            info["Title"] = f"isolator review: {label}"
            info["Creator"] = f"isolator {summary['software']['version']}"
        dump_json(summary, tmp_json)
    return summary
