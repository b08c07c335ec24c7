"""The design chart of a design search: rendering only (the numbers come from the search's chart data).

Page 1: contours of the design total displacement D_TM and of the base-shear coefficient V_b/W over
the two main varied keys, each cell of the failing region shaded by its first failing check (legend),
the recommended candidate marked; the same candidates on the paper's (k, α) map, labelled as the
paper's measure (context, not a verdict).  Page 2: the passing candidates ranked by the objective.
"""

from __future__ import annotations

import textwrap

import numpy as np

from isolator.atomic import atomic_path
from isolator.report import figures
from isolator.report.layout import A4_IN, fmt

#: colour of a state of a cell; failing checks take the colours of :data:`FAIL_COLOURS` in order
PASS_COLOUR = "#ffffff"
NOT_ANALYSED_COLOUR = "#9e9e9e"
FAIL_COLOURS = ("#e57373", "#ffb74d", "#ba68c8", "#4fc3f7", "#aed581", "#f06292", "#ffd54f", "#7986cb",
                "#a1887f", "#4db6ac", "#dce775", "#90a4ae")
LABELS = {"radius_m": "R [m]", "mu_kinetic": "µk [-]", "mu_static": "µs [-]",
          "displacement_capacity_m": "displacement capacity [m]", "mass_kg": "M [kg]",
          "design_total_displacement_m": "D_TM [m]", "design_displacement_m": "D_M [m]",
          "base_shear_coefficient": "V_b/W [-]", "residual_displacement_m": "residual [m]",
          "restoring_force_margin": "restoring margin [-]", "governing_bound": "D_M bound", "candidate": "#"}


def state_colours(states) -> dict:
    """A colour per state: pass white, not analysed grey, each failing check its own colour (first seen first)."""
    out, n = {}, 0
    for state in states:
        if state in out:
            continue
        if state == "pass":
            out[state] = PASS_COLOUR
        elif state == "not analysed":
            out[state] = NOT_ANALYSED_COLOUR
        else:
            out[state] = FAIL_COLOURS[n % len(FAIL_COLOURS)]
            n += 1
    return out


def cell_edges(values) -> np.ndarray:
    """Edges of the cells around sorted grid values (midpoints; ends half a spacing out)."""
    v = np.asarray(values, dtype=float)
    if v.size == 1:
        half = 0.05 * abs(v[0]) if v[0] != 0 else 0.5
        return np.array([v[0] - half, v[0] + half])
    mid = 0.5 * (v[1:] + v[:-1])
    return np.concatenate([[v[0] - (mid[0] - v[0])], mid, [v[-1] + (v[-1] - mid[-1])]])


def _label(key) -> str:
    return LABELS.get(key, key)


def _shade_states(ax, data, colours) -> None:
    """Each cell coloured by its state (pass cells left white)."""
    from matplotlib.colors import ListedColormap

    states = list(colours)
    index = np.vectorize(states.index)(data["state"]).astype(float)
    index[data["state"] == "pass"] = np.nan
    cmap = ListedColormap([colours[s] for s in states])
    ax.pcolormesh(cell_edges(data["x"]), cell_edges(data["y"]), np.ma.masked_invalid(index), cmap=cmap,
                  vmin=-0.5, vmax=len(states) - 0.5, alpha=0.55, shading="flat", zorder=1)


def _contour_panel(ax, data, field: str, title: str, unit: str, colours) -> None:
    x, y, z = data["x"], data["y"], data[field]
    _shade_states(ax, data, colours)
    finite = np.isfinite(z)
    if finite.sum() >= 4 and x.size >= 2 and y.size >= 2:
        filled = np.where(finite, z, np.nanmax(z))  # contours need a full grid; unanalysed cells are shaded grey
        lines = ax.contour(x, y, filled, levels=8, colors="k", linewidths=0.8, zorder=3)
        ax.clabel(lines, fontsize=6.5, fmt=lambda v: fmt(v, 3))
    xx, yy = np.meshgrid(x, y)
    ax.scatter(xx.ravel(), yy.ravel(), s=4, color="0.3", zorder=4)
    if data["recommended"] is not None:
        ax.scatter([data["recommended"][0]], [data["recommended"][1]], marker="*", s=220, color="gold",
                   edgecolor="k", zorder=6, label="recommended")
    ax.set_xlabel(_label(data["x_key"]))
    ax.set_ylabel(_label(data["y_key"]))
    ax.set_title(f"{title} [{unit}]", fontsize=9)


def _line_panel(ax, data, field: str, title: str, unit: str, colours) -> None:
    x = data["x"]
    edges = cell_edges(x)
    for j, state in enumerate(data["state"][0]):
        if state != "pass":
            ax.axvspan(edges[j], edges[j + 1], color=colours[state], alpha=0.55, lw=0, zorder=1)
    ax.plot(x, data[field][0], "k.-", zorder=3)
    if data["recommended"] is not None:
        j = int(np.argmin(np.abs(x - data["recommended"][0])))
        ax.scatter([x[j]], [data[field][0][j]], marker="*", s=220, color="gold", edgecolor="k", zorder=6)
    ax.set_xlabel(_label(data["x_key"]))
    ax.set_ylabel(f"{title} [{unit}]")
    ax.set_title(title, fontsize=9)


def _paper_panel(ax, data, colours) -> None:
    pm = data.get("paper_map")
    if pm is not None:
        figures.draw_regime_map(ax, pm["map"], show_legend=False)
    points = data["paper"]
    for state in colours:
        chosen = [(k, a) for k, a, s, _ in points if s == state]
        if chosen:
            ax.scatter(*zip(*chosen, strict=True), s=16, color=colours[state] if state != "pass" else "#1a7f37",
                       edgecolor="k", linewidths=0.3, zorder=5)
    best = [(k, a) for k, a, _, c in points if c == data["recommended_candidate"]]
    if best:
        ax.scatter(*zip(*best, strict=True), marker="*", s=220, color="gold", edgecolor="k", zorder=6)
    on = data.get("paper_regimes")  # a double or triple: each candidate's point on the regime its motions reached
    ax.set_xlabel("k = A0 / R of the regime reached [-]" if on else "k = K A0 / (M g) [-]")
    ax.set_ylabel("α = PGA / (µ g), µ of the regime reached [-]" if on else "α = PGA / (µs g) [-]")
    title = "the paper's measure (Nicolas 2017): context, not a check"
    ax.set_title(title, fontsize=8.5)


def _legend(fig, colours, y: float) -> None:
    from matplotlib.patches import Patch

    handles = [Patch(facecolor=c, edgecolor="0.4", alpha=0.55 if s != "pass" else 1.0,
                     label="passes every check" if s == "pass" else
                     ("not analysed" if s == "not analysed" else f"first failing: {s}"))
               for s, c in colours.items()]
    fig.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, y), ncol=3, fontsize=7, frameon=False)


def _chart_page(summary: dict, data: dict):
    fig = figures.new_figure(figsize=A4_IN)
    fig.text(0.05, 0.975, "Design search: the trade-off", fontsize=13, weight="bold", va="top")
    # the subtitle was cut at 110 characters and the summary's values at 60, and still ran off the page (session 25)
    for k, text in enumerate(textwrap.wrap(summary["subtitle"], 120)[:2]):
        fig.text(0.95, 0.952 - k * 0.011, text, fontsize=7.5, va="top", ha="right", color="0.35")
    colours = state_colours(["pass", *data["state"].ravel().tolist(), *(p[2] for p in data["paper"])])
    two_d = data["y_key"] is not None and data["x"].size >= 2 and data["y"].size >= 2
    panel = _contour_panel if two_d else _line_panel
    ax1 = fig.add_axes([0.08, 0.60, 0.38, 0.30])
    ax2 = fig.add_axes([0.57, 0.60, 0.38, 0.30])
    panel(ax1, data, "design_total_displacement_m", "design total displacement D_TM", "m", colours)
    panel(ax2, data, "base_shear_coefficient", "base-shear coefficient V_b/W", "-", colours)
    _legend(fig, colours, 0.555)
    ax3 = fig.add_axes([0.08, 0.1, 0.38, 0.32])
    _paper_panel(ax3, data, colours)
    _summary_lines(fig, summary["lines"])
    fig.text(0.05, 0.012, textwrap.fill(chart_caption(data), 150), fontsize=6.8, va="bottom", color="0.15")
    return fig


def _summary_lines(fig, lines: list, top: float = 0.42, bottom: float = 0.075) -> None:
    """The (name, value) rows beside the paper's panel, each wrapped within its column (names at 18 characters of
    bold 7.6 pt, values at 40), down to ``bottom``; rows that do not fit are counted on a last line (the table has
    them)."""
    step, y = 0.0132, top
    for n, (name, value) in enumerate(lines):
        names = textwrap.wrap(str(name), 18, break_long_words=True) or [""]
        values = textwrap.wrap(" ".join(str(value).split()), 40, break_long_words=True) or [""]
        height = step * max(len(names), len(values))
        if y - height < bottom + step and n < len(lines) - 1:
            fig.text(0.50, y, f"… {len(lines) - n} more rows: the table's columns", fontsize=7.6, va="top")
            return
        for k, text in enumerate(names):
            fig.text(0.50, y - k * step, text, fontsize=7.6, weight="bold", va="top")
        for k, text in enumerate(values):
            fig.text(0.655, y - k * step, text, fontsize=7.6, va="top")
        y -= height + 0.004


def chart_caption(data: dict) -> str:
    """The chart page's caption: what is drawn — the paper's regime map only where it is (``data["paper_map"]``: a
    rigid block on one surface), each candidate's point on the line it stands on."""
    caption = ("Every candidate was reviewed exactly as 'isolator review' reviews it (its own ELF values and period "
               "range, the suite scaled for that range, every pair at the lower, upper and nominal friction, every "
               "check); nothing is interpolated between candidates.  Contours: the design values of the reviews. "
               "Shading: the first failing check of each candidate (cells centred on the candidates). Bottom left: "
               "each candidate at the median over the suite of the paper's dimensionless point at nominal friction")
    if data.get("paper_regimes"):
        caption += (" on the backbone regime its motions reached (k = A0/R, α = PGA/(µ g) of that regime's line, "
                    "A0 = PGV²/PGA of the scaled pair; column paper_regime); a candidate whose motions reached "
                    "different regimes has no median point (not drawn).")
    else:
        caption += " (k = K A0/(M g), α = PGA/(µs g), A0 = PGV²/PGA of the scaled pair)."
    if data.get("paper_map") is not None:
        caption += (" Behind the points, the paper's harmonic regime map, which classifies a rigid block on one "
                    "surface under a one-component harmonic motion: context only.")
    else:
        caption += (" No regime map is drawn: the paper's map is a rigid block's on one surface"
                    + (f", and these candidates are {data['isolated']}" if data.get("isolated") and
                       data["isolated"] != "a rigid block on one surface" else "") + "; the points are context only.")
    if data["fixed"]:
        caption += " Other varied keys held at " + ", ".join(f"{k} = {fmt(v)}" for k, v in data["fixed"].items()) + "."
    return caption


def _ranking_page(summary: dict, rows: list, columns: list):
    fig = figures.new_figure(figsize=A4_IN)
    fig.text(0.05, 0.975, "Design search: passing candidates by the objective", fontsize=13, weight="bold", va="top")
    y = 0.93
    xs = np.linspace(0.05, 0.85, len(columns))
    for x, column in zip(xs, columns, strict=True):
        fig.text(x, y, _label(column)[:24], fontsize=7, weight="bold", va="top")
    y -= 0.016
    if not rows:
        fig.text(0.05, y, "no candidate passes every check", fontsize=8, va="top")
    for row in rows[:55]:
        for x, column in zip(xs, columns, strict=True):
            value = row.get(column)
            fig.text(x, y, fmt(value) if isinstance(value, (int, float)) and not isinstance(value, bool)
                     else str(value), fontsize=7, va="top")
        y -= 0.0145
    if len(rows) > 55:
        fig.text(0.05, y, f"… {len(rows) - 55} more in the table", fontsize=7, va="top")
    return fig


def write_design_chart(pdf_path, data: dict, summary: dict, ranked: list, columns: list, *, into=None) -> int:
    """Write the chart PDF atomically; return its page count.

    Parameters
    ----------
    pdf_path : path-like
    data : dict
        :func:`isolator.review.design_outputs.chart_data` (with an optional ``paper_map``).
    summary : dict
        ``subtitle`` (text) and ``lines`` ((name, value) rows printed beside the paper's map).
    ranked : list of dict
        The passing rows, best first.
    columns : list of str
        The columns of the ranking page.
    into : path-like, optional
        The temporary file of a larger output set to write instead (``isolator design``'s,
        :func:`isolator.atomic.atomic_paths`); the caller renames it onto ``pdf_path``.
    """
    from contextlib import nullcontext

    from matplotlib.backends.backend_pdf import PdfPages

    pages = (lambda: _chart_page(summary, data), lambda: _ranking_page(summary, ranked, columns))
    with (nullcontext(into) if into is not None else atomic_path(pdf_path)) as tmp, PdfPages(tmp) as pdf:
        for make in pages:
            pdf.savefig(make())
        pdf.infodict()["Title"] = "isolator design search"
    return len(pages)

