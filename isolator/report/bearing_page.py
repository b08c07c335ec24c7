"""The report's page of a double or triple friction pendulum: the backbone with the loop, each surface
against its capacity, the regimes reached, the rims and the ultimate displacement (issue 23;
docs/multisurface.md).

Rendering only: the backbone is the bearing's (:meth:`isolator.bearing.Bearing.backbone`, in the analysis
under ``design.bearing``: ``backbone_displacement_m``, ``backbone_force_per_weight``, ``backbone_regimes``);
the loop is the response's force per weight against its displacement; every other number is a key of
:meth:`isolator.analysis.Analysis.to_dict` (``surface_peak_displacement_m``, ``regimes``,
``n_rim_contacts``, ``ultimate_displacement_reached``, ``impact_impulse_m_s`` …).
"""

from __future__ import annotations

import math
import textwrap

import numpy as np

from isolator.report.figures import PIXELS_PER_AXIS, extreme_indices, plot_decimated
from isolator.report.layout import caption, cells, fmt, page
from isolator.units import STANDARD_GRAVITY

#: The label of the response's loop on the page (tests find the line by it).
LOOP_LABEL = "response: F/W against displacement"
#: The label of the backbone's transition points.
POINTS_LABEL = "backbone transition points"


def has_multisurface_bearing(numbers: dict) -> bool:
    """True when the response is the series model's (``surface_peak_displacement_m`` is a list): a double or
    triple bearing, or a single pendulum rerun with its rim when it reached its displacement capacity."""
    return isinstance(numbers.get("surface_peak_displacement_m"), list)


def bearing_dict(numbers: dict, response=None) -> dict:
    """The bearing drawn (:meth:`isolator.bearing.Bearing.as_dict`): the design's ``[bearing]``, else the
    response's own (a single pendulum rerun with its rim has no ``[bearing]`` table)."""
    bearing = (numbers.get("design") or {}).get("bearing")
    if bearing is None and getattr(response, "bearing", None) is not None:
        bearing = response.bearing.as_dict()
    if bearing is None:
        raise ValueError("a multi-surface page needs the bearing: the design's [bearing] or the response's")
    return bearing


def backbone_polyline(bearing: dict) -> tuple[np.ndarray, np.ndarray]:
    """The backbone from −ultimate to +ultimate through the origin's stick step, as a polyline (x [m], F/W [-]).

    Parameters
    ----------
    bearing : dict
        ``design.bearing`` of the analysis (:meth:`isolator.bearing.Bearing.as_dict`).
    """
    x = np.asarray(bearing["backbone_displacement_m"], dtype=np.float64)
    r = np.asarray(bearing["backbone_force_per_weight"], dtype=np.float64)
    xs = np.concatenate((-x[::-1], x))  # odd symmetry: the bearing is the same both ways
    rs = np.concatenate((-r[::-1], r))
    return xs, rs


def draw_backbone_and_loop(ax, bearing: dict, displacement_m, force_per_weight) -> None:
    """The response's loop (F/W against x) over the bearing's backbone, the transition points marked.

    A planar response is drawn as the resultant force against the resultant displacement (the
    backbone is then the envelope of a radial excursion).
    """
    x = np.asarray(displacement_m, dtype=np.float64)
    r = np.asarray(force_per_weight, dtype=np.float64)
    planar = x.ndim == 2
    if planar:
        x, r = np.hypot(x[:, 0], x[:, 1]), np.hypot(r[:, 0], r[:, 1])
    keep = extreme_indices(PIXELS_PER_AXIS, x, r)  # the loop's extremes kept, a page's resolution
    ax.plot(x[keep], r[keep], color="0.35", lw=0.6, label=LOOP_LABEL + (" (resultants)" if planar else ""))
    bx, br = backbone_polyline(bearing)
    if planar:  # resultants are never negative: the backbone from rest outward
        bx, br = bx[bx.size // 2:], br[br.size // 2:]
    ax.plot(bx, br, color="tab:red", lw=1.2, ls="--", label="backbone from rest (Fenz & Constantinou series model)")
    px = np.asarray(bearing["backbone_displacement_m"], dtype=np.float64)
    pr = np.asarray(bearing["backbone_force_per_weight"], dtype=np.float64)
    ax.plot(px, pr, "o", color="tab:red", ms=4, label=POINTS_LABEL)
    names = list(bearing["backbone_regimes"])
    ultimate = float(bearing["ultimate_displacement_m"])
    for k, (xk, rk) in enumerate(zip(px, pr, strict=True)):
        text = names[k] if k < len(names) else "ultimate"
        if bearing["type"] != "triple" and k < len(names):
            text = f"{text} slide"
        ax.annotate(text, (xk, rk), textcoords="offset points", xytext=(-4, 6), ha="right", fontsize=7.5,
                    color="tab:red", weight="bold")
    if math.isfinite(ultimate):
        for sign in (1.0,) if planar else (1.0, -1.0):
            ax.axvline(sign * ultimate, color="tab:red", lw=0.8, ls=":")
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.axvline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel("bearing displacement" + (" |X|" if planar else " X") + "  [m]")
    ax.set_ylabel("bearing force / weight  F/W  [-]")
    ax.set_title("Backbone and force-displacement loop")
    ax.legend(loc="upper left", fontsize=6.8, frameon=True)


def draw_displacement_history(ax, time_s, displacement_m, bearing: dict, ultimate_first_time_s=None) -> None:
    """The bearing's displacement over time with the backbone's transition displacements (±)."""
    t = np.asarray(time_s, dtype=np.float64)
    x = np.asarray(displacement_m, dtype=np.float64)
    planar = x.ndim == 2
    if planar:
        x = np.hypot(x[:, 0], x[:, 1])
    plot_decimated(ax, t, x, color="k", lw=0.7, label="resultant displacement" if planar else "displacement")
    points = bearing["backbone_displacement_m"]
    for k, xk in enumerate(points[1:], start=1):
        last = k == len(points) - 1 and math.isfinite(float(bearing["ultimate_displacement_m"]))
        for sign in (1.0,) if planar else (1.0, -1.0):  # dotted: where a regime starts; solid: the ultimate
            ax.axhline(sign * xk, color="tab:red", lw=0.6, ls="-" if last else ":")
    if ultimate_first_time_s is not None:
        ax.axvline(ultimate_first_time_s, color="tab:red", lw=1.0, label="ultimate displacement first reached")
    ax.set_xlim(t[0], t[-1])
    ax.set_xlabel("time  [s]")
    ax.set_ylabel("displacement  [m]")
    ax.legend(loc="lower right", bbox_to_anchor=(1.0, 1.0), frameon=False, ncol=2, fontsize=6.8, borderaxespad=0.2)


def loop_force_per_weight(response) -> tuple[np.ndarray, str]:
    """The force per weight the loop draws, and what it is in words.

    The solver's bearing F/W at the samples (``force_per_weight``) where the response holds it; else
    −(absolute acceleration)/g, which is (F + γV)/W: the bearing's F/W when the design has no damper.
    """
    force = getattr(response, "force_per_weight", None)
    if force is not None:
        return np.asarray(force), "the solver's F/W at the samples"
    gravity = float(getattr(response, "gravity_m_s2", STANDARD_GRAVITY))
    return (-np.asarray(response.absolute_acceleration_m_s2) / gravity,
            "−(absolute acceleration)/g at the samples, = (F + γV)/W: F/W without a damper")


def surface_rows(numbers: dict, bearing: dict) -> list[tuple]:
    """Per surface (file order): number, R, R_eff, µ, capacity d on the surface, peak on the surface, peak/d.

    The peaks (``surface_peak_displacement_m``) and the capacities are both on the surface (d, not d*):
    their ratio is that of the effective values.
    """
    rows = []
    surfaces = bearing["surfaces"]
    for i, (surface, peak) in enumerate(zip(surfaces, numbers["surface_peak_displacement_m"], strict=True)):
        capacity = surface["displacement_capacity_m"]
        ratio = None if not capacity else peak / capacity
        rows.append((i + 1, surface["radius_m"], surface["effective_radius_m"], surface["mu_kinetic"], capacity,
                     surface["effective_capacity_m"], peak, ratio))
    return rows


def regime_sentence(numbers: dict, bearing: dict) -> str:
    """Which regimes the motion reached and when (``regimes``: first time each was entered), and which not."""
    regimes = numbers.get("regimes") or {}
    reached = ", ".join(f"{name} at {fmt(time, 4)} s" for name, time in sorted(regimes.items(),
                                                                                key=lambda item: item[1]))
    missing = [name for name in bearing["backbone_regimes"] if name not in regimes]
    what = "Regimes entered (first time)" if bearing["type"] == "triple" else "Sliding surfaces (first time)"
    sentence = f"{what}: {reached or 'none (the bearing never slid)'}"
    if missing:
        sentence += f"; not reached: {', '.join(missing)}"
    return sentence + "."


def bearing_page(number: int, label: str, numbers: dict, response=None, mass_kg: float | None = None):
    """The page of a double or triple bearing: backbone and loop, surfaces, regimes, rims, the ultimate.

    Parameters
    ----------
    number : int
        The page's number in its report.
    label : str
        The report's subtitle (design | record).
    numbers : dict
        :meth:`isolator.analysis.Analysis.to_dict` of a double or triple bearing's analysis.
    response : object
        The analysis' response (``time_s``, ``displacement_m``, ``force_per_weight``,
        ``ultimate_first_time_s``).
    mass_kg : float, optional
        The supported mass [kg], for the impulse in N·s (default: the design's).

    Returns
    -------
    matplotlib.figure.Figure
    """
    bearing = bearing_dict(numbers, response)
    mass = float(numbers["design"]["mass_kg"] if mass_kg is None else mass_kg)
    title = ("The pendulum and its rim" if bearing["type"] == "single"
             else f"The {bearing['type']} pendulum: backbone, surfaces, rims")
    fig = page(1, label, (f"{number}  {title}",))
    ax_loop = fig.add_axes((0.1, 0.56, 0.85, 0.37))
    force, force_words = loop_force_per_weight(response)
    draw_backbone_and_loop(ax_loop, bearing, response.displacement_m, force)
    ax_hist = fig.add_axes((0.1, 0.36, 0.8, 0.14))
    first_ultimate = getattr(response, "ultimate_first_time_s", None)
    draw_displacement_history(ax_hist, response.time_s, response.displacement_m, bearing, first_ultimate)

    y = 0.3
    order = {"triple": " (file order: 1 outer bottom, 2 inner bottom, 3 inner top, 4 outer top)",
             "double": " (file order: 1 bottom, 2 top)"}.get(bearing["type"], "")
    fig.text(0.05, y, f"Surface{'s' if len(bearing['surfaces']) > 1 else ''}{order}", fontsize=9.5, weight="bold",
             va="top")
    y -= 0.02
    columns = (0.06, 0.14, 0.23, 0.32, 0.4, 0.5, 0.6, 0.72, 0.82)
    head = ("surface", "R [m]", "R_eff [m]", "µ", "d [m]", "d* [m]", "peak [m]", "peak / d", "")
    cells(fig, y, columns, head, bold=True)
    for i, r_eff, reff, mu, capacity, capacity_eff, peak, ratio in surface_rows(numbers, bearing):
        y -= 0.0135
        at_rim = ratio is not None and ratio >= 1.0 - 1e-9
        cells(fig, y, columns, (str(i), fmt(r_eff), fmt(reff), fmt(mu, 3), fmt(capacity), fmt(capacity_eff),
                                fmt(peak), fmt(ratio, 3), "on its rim" if at_rim else ""),
              colour="tab:red" if at_rim else "k")
    y -= 0.025
    single = bearing["type"] == "single"
    sentences = [regime_sentence(numbers, bearing),
                 f"Rim contacts: {numbers['n_rim_contacts']} " + (
                     "(the slider reaching the displacement capacity: a rigid stop)." if single else
                     "(a slider reaching its capacity d* on a surface; it stops there while the force pushes "
                     "outward and the force passes to the other surfaces).")]
    if numbers["ultimate_displacement_reached"]:
        when = "" if first_ultimate is None else f" first at {fmt(first_ultimate, 4)} s"
        sentences.append(
            f"ULTIMATE DISPLACEMENT REACHED{when}: {fmt(numbers['ultimate_displacement_m'])} m "
            f"({'the displacement capacity' if single else 'every slider on its rim'}), a rigid stop with plastic impact(s): impulse {fmt(mass * numbers['impact_impulse_m_s'])} "
            f"N·s in all (M × Σ|V| = {fmt(mass)} kg × {fmt(numbers['impact_impulse_m_s'])} m/s), largest impact "
            f"velocity {fmt(numbers['max_impact_velocity_m_s'])} m/s"
            + ("" if numbers.get("energy_impact_J_per_kg") is None else
               f", energy lost in impacts {fmt(mass * numbers['energy_impact_J_per_kg'] / 1e3)} kJ")
            + ".  The motion is held there, never continued past it.")
    else:
        sentences.append(f"The ultimate displacement {fmt(numbers['ultimate_displacement_m'])} m was not reached "
                         f"(peak {fmt(numbers['peak_displacement_m'])} m, "
                         f"{fmt(numbers['peak_displacement_m'] / numbers['ultimate_displacement_m'], 3)} of it).")
    peak_words = f"Peak bearing force {fmt(numbers['peak_force_per_weight'])} W (peak_force_per_weight)"
    magnitude = np.hypot(force[:, 0], force[:, 1]) if np.ndim(force) == 2 else np.abs(force)
    held = float(np.max(magnitude)) if np.size(magnitude) else 0.0
    if held > numbers["peak_force_per_weight"] * (1.0 + 1e-9):  # a rim's reaction while the bearing is held there
        peak_words += (f"; the loop's largest |F/W| at the samples is {fmt(held)}, the rim's reaction while the "
                       "bearing is held on it")
    sentences.append(peak_words + ".")
    for sentence in sentences:
        for j, line in enumerate(textwrap.wrap(sentence, 112)):
            fig.text(0.06, y, ("• " if j == 0 else "  ") + line, fontsize=7.8, va="top",
                     color="tab:red" if sentence.startswith("ULTIMATE") else "k",
                     weight="bold" if sentence.startswith("ULTIMATE") else "normal")
            y -= 0.0135
    caption(fig, f"Model {numbers['model']}: {numbers['model_reason']}.  Top: the bearing's force per weight "
                  f"against its displacement under the record ({force_words}) over the backbone "
                  "from rest (piecewise linear, its transition points marked with the regime that starts there, "
                  "mirrored for negative displacements; dotted: ± the ultimate displacement Σ d_i*).  Middle: the "
                  "displacement with the transition displacements (dotted) and ± the ultimate (solid).  Table: each surface's peak displacement on "
                  "the surface against its capacity d on the surface (d* = d R_eff/R is the effective capacity; "
                  "the ratio is the same).  Every number is the analysis' own (the JSON beside this PDF).")
    return fig
