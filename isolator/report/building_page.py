"""The report's page of the building above the isolators: drift and floor-acceleration profiles, shears,
the bearings' axial loads (issue 22; docs/building.md).

Rendering only: every number comes from the analysis (:meth:`isolator.analysis.Analysis.to_dict`: the keys
``story_drift_m``, ``story_drift_ratio``, ``floor_peak_acceleration_m_s2``,
``superstructure_shear_coefficient``, ``base_shear_coefficient``, ``bearing_axial_load_max_N``,
``bearing_axial_load_min_N``, ``n_bearings_uplifted``; the design's floors and bearing layout under
``design``), or from the response's own :meth:`~isolator.solver.building.BuildingResponse.bearing_loads`
(when each uplift starts and how long it lasts).  The story-drift limit is the review parameter
``drift_limit_rha`` (ASCE 7-22 17.6.4.4, marked [U] in REVIEW_RULES.md: printed with its value; ``isolator
report --set drift_limit_rha=…`` changes it, the value then read from the report's ``parameters``).
"""

from __future__ import annotations

import textwrap

import numpy as np

from isolator.report.layout import caption, cells, fmt, page
from isolator.units import STANDARD_GRAVITY

#: The review parameter of the story-drift limit with response-history analysis (isolator.review.parameters).
DRIFT_LIMIT_PARAMETER = "drift_limit_rha"


def has_building(numbers: dict) -> bool:
    """True when the analysis carries a superstructure's results (``story_drift_ratio`` is a list)."""
    return isinstance(numbers.get("story_drift_ratio"), list) and bool(numbers["story_drift_ratio"])


def drift_limit(numbers: dict | None = None) -> dict:
    """The story-drift limit the page draws: the review parameter's value in the report's ``parameters`` (``report
    --set drift_limit_rha=…``), else its default; its mark and clause.

    Returns
    -------
    dict
        ``name``, ``ratio`` [-] (limit drift / story height h_sx), ``mark`` (``"U"``), ``rule``, ``default`` [-],
        ``set`` (True when the value was given with ``--set``).
    """
    from isolator.review.parameters import PARAMETERS

    parameter = PARAMETERS[DRIFT_LIMIT_PARAMETER]
    row = next((r for r in (numbers or {}).get("parameters") or () if r["name"] == DRIFT_LIMIT_PARAMETER), None)
    value = parameter.default if row is None else row["value"]
    return {"name": parameter.name, "ratio": float(value), "mark": parameter.mark, "rule": parameter.rule,
            "default": float(parameter.default), "set": row is not None and row.get("source") == "set"}


def profile_heights(story_heights_m) -> tuple[np.ndarray, np.ndarray]:
    """(floor heights H_i above the isolation plane, mid-heights of the stories) [m], bottom to top."""
    h = np.asarray(story_heights_m, dtype=np.float64)
    floors = np.cumsum(h)
    return floors, floors - 0.5 * h


def draw_drift_profile(ax, drift_ratio, story_heights_m, limit: dict) -> None:
    """Peak story drift ratio of each story against height, as a step over the story, with the limit.

    The line labelled ``"story drift ratio (peak)"`` has one marker per story at its mid-height, x
    equal to the analysis' ``story_drift_ratio``.
    """
    ratio = np.asarray(drift_ratio, dtype=np.float64)
    floors, mids = profile_heights(story_heights_m)
    bottoms = floors - np.asarray(story_heights_m, dtype=np.float64)
    steps_x = np.repeat(ratio, 2)
    steps_y = np.column_stack((bottoms, floors)).ravel()
    ax.plot(steps_x, steps_y, color="k", lw=1.0)
    ax.plot(ratio, mids, "o", color="k", ms=3.5, label="story drift ratio (peak)")
    ax.axvline(limit["ratio"], color="tab:red", ls="--", lw=1.1,
               label=f"limit {fmt(limit['ratio'], 3)} h_sx ({limit['rule']}; parameter {limit['name']} "
                     f"[{limit['mark']}])")
    _frame_profile(ax, max(float(np.max(ratio)), limit["ratio"]), floors, "peak story drift / story height  [-]",
                   "height above the isolation plane  [m]", "Story drift ratio profile")


def _frame_profile(ax, x_top: float, floors, xlabel: str, ylabel: str, title: str) -> None:
    """Limits, ticks at the floors, labels and the legend below, of a profile against height."""
    ax.set_xlim(0.0, 1.15 * x_top)
    ax.set_ylim(0.0, 1.05 * float(floors[-1]))
    ax.set_yticks(floors)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.legend(loc="upper left", bbox_to_anchor=(0.0, -0.16), frameon=False, fontsize=6.8)


def draw_acceleration_profile(ax, floor_acceleration_m_s2, story_heights_m, pga_m_s2: float | None, *,
                              resultant: bool = False) -> None:
    """Peak absolute floor acceleration against floor height [g], the ground's PGA at height 0 (that of the
    horizontal resultant for a pair: ``resultant``).

    The line labelled ``"floor peak absolute acceleration"`` has x equal to the analysis'
    ``floor_peak_acceleration_m_s2`` / g and y the floor heights.
    """
    acc_g = np.asarray(floor_acceleration_m_s2, dtype=np.float64) / STANDARD_GRAVITY
    floors, _ = profile_heights(story_heights_m)
    ax.plot(acc_g, floors, "o-", color="tab:blue", lw=1.0, ms=3.5, label="floor peak absolute acceleration")
    top = float(np.max(acc_g))
    if pga_m_s2 is not None:
        ax.plot([pga_m_s2 / STANDARD_GRAVITY], [0.0], "s", color="0.4", ms=4.5,
                label=f"ground PGA{' (horizontal resultant)' if resultant else ''} "
                      f"{fmt(pga_m_s2 / STANDARD_GRAVITY, 3)} g", clip_on=False)
        top = max(top, pga_m_s2 / STANDARD_GRAVITY)
    _frame_profile(ax, top, floors, "peak absolute acceleration  [g]", "floor height  [m]",
                   "Floor acceleration profile")


def draw_bearing_loads(ax, load_max_N, load_min_N, gravity_N) -> None:
    """Each bearing's axial-load range [kN] (compression positive), its gravity load, tension flagged.

    One vertical bar per bearing from the minimum to the maximum load; the bars whose minimum is
    below zero (uplift, ASCE 7-22 17.2.4.7) are red and labelled.
    """
    low = np.asarray(load_min_N, dtype=np.float64) / 1e3
    high = np.asarray(load_max_N, dtype=np.float64) / 1e3
    number = np.arange(1, low.size + 1)
    uplift = low < 0.0
    colours = np.where(uplift, "tab:red", "tab:blue")
    ax.bar(number, high - low, bottom=low, width=0.5, color=colours, alpha=0.75, label="min to max axial load")
    if gravity_N is not None:
        ax.plot(number, np.asarray(gravity_N, dtype=np.float64) / 1e3, "_", color="k", ms=14, mew=1.5,
                label="gravity load")
    ax.axhline(0.0, color="k", lw=0.8)
    for k in np.flatnonzero(uplift):
        ax.annotate("uplift", (number[k], high[k]), textcoords="offset points", xytext=(0, 3), ha="center",
                    fontsize=7, color="tab:red", weight="bold")
    ax.margins(y=0.12)
    ax.set_xticks(number)
    ax.set_xlabel("bearing (file order)")
    ax.set_ylabel("axial load, compression +  [kN]")
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), frameon=False, fontsize=6.8, ncol=2,
              title="Bearing axial loads (rigid-slab statics)", title_fontsize=8)


def draw_bearing_plan(ax, x_m, y_m, uplifted) -> None:
    """The bearings in plan from the centre of mass [m], numbered, the uplifted ones in red."""
    x, y = np.asarray(x_m, dtype=np.float64), np.asarray(y_m, dtype=np.float64)
    flags = np.asarray(uplifted, dtype=bool)
    ax.plot(x[~flags], y[~flags], "s", color="tab:blue", ms=6, label="bearing")
    if flags.any():
        ax.plot(x[flags], y[flags], "s", color="tab:red", ms=6, label="bearing in tension (uplift)")
    for k, (xk, yk) in enumerate(zip(x, y, strict=True)):
        ax.annotate(str(k + 1), (xk, yk), textcoords="offset points", xytext=(5, 4), fontsize=7)
    ax.plot([0.0], [0.0], "+", color="k", ms=9, label="centre of mass")
    span = max(float(np.max(np.abs(np.concatenate((x, y))))), 1e-3) * 1.3
    ax.set_xlim(-span, span)
    ax.set_ylim(-span, span)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (along the first component)  [m]")
    ax.set_ylabel("y  [m]")
    ax.set_title("Layout (plan)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), frameon=False, fontsize=6.8)


def building_page(number: int, label: str, numbers: dict, response=None):
    """The page of the building: profiles, shears, the story table and the bearings' loads.

    Parameters
    ----------
    number : int
        The page's number in its report.
    label : str
        The report's subtitle (design | record).
    numbers : dict
        :meth:`isolator.analysis.Analysis.to_dict` of an analysis with a superstructure.
    response : object, optional
        The analysis' response: its ``bearing_loads()`` gives when each uplift starts and lasts.

    Returns
    -------
    matplotlib.figure.Figure
    """
    structure = numbers["design"]["superstructure"]
    heights = [floor["story_height_m"] for floor in structure["floors"]]
    limit = drift_limit(numbers)
    fig = page(1, label, (f"{number}  The building above the isolators",))
    ax_drift = fig.add_axes((0.1, 0.69, 0.35, 0.24))
    draw_drift_profile(ax_drift, numbers["story_drift_ratio"], heights, limit)
    ax_acc = fig.add_axes((0.6, 0.69, 0.35, 0.24))
    record = numbers.get("record") or {}
    pga = record.get("intensity_measures", {}).get("pga_m_s2")
    draw_acceleration_profile(ax_acc, numbers["floor_peak_acceleration_m_s2"], heights, pga,
                              resultant=len(record.get("components") or {}) > 1)

    y = 0.585
    fig.text(0.05, y, "Stories and floors (bottom to top; peaks over the record, exact)", fontsize=9.5,
             weight="bold", va="top")
    y -= 0.02
    columns = (0.06, 0.13, 0.25, 0.37, 0.5, 0.62, 0.77)
    head = ("story", "h [m]", "drift [mm]", "drift / h", "/ limit", "floor H [m]", "floor acc. [m/s² | g]")
    cells(fig, y, columns, head, bold=True)
    floors, _ = profile_heights(heights)
    rows = list(zip(heights, numbers["story_drift_m"], numbers["story_drift_ratio"], floors,
                    numbers["floor_peak_acceleration_m_s2"], strict=True))
    shown = rows if len(rows) <= 12 else rows[:6] + rows[-6:]  # a tall building: bottom and top stories
    for i, (h, drift, ratio, floor, acc) in enumerate(shown):
        y -= 0.0135
        story = i + 1 if len(rows) <= 12 or i < 6 else len(rows) - len(shown) + i + 1
        over = ratio > limit["ratio"]
        texts = (str(story), fmt(h), fmt(drift * 1e3), fmt(ratio, 3), fmt(ratio / limit["ratio"], 3),
                 fmt(floor), f"{fmt(acc)} | {fmt(acc / STANDARD_GRAVITY, 3)}")
        cells(fig, y, columns, texts, colour=lambda x, over=over: "tab:red" if over and x in columns[3:5] else "k")
    y -= 0.022
    weight_ratio = structure["weight_N"] / (numbers["design"]["mass_kg"] * numbers["design"]["gravity_m_s2"])
    shears = [("superstructure shear coefficient V_s/W_s (peak first-story shear, spring + damper)",
               fmt(numbers["superstructure_shear_coefficient"])),
              ("base shear coefficient V_b/W (peak isolator force: spring, dashpot, friction)",
               fmt(numbers["base_shear_coefficient"])),
              ("W_s / W (floors' weight over the whole isolated weight)", fmt(weight_ratio)),
              *_period_rows(structure),
              ("modal damping ratio ζ", fmt(structure["damping_ratio"])),
              ("story drift limit (response history)", f"{fmt(limit['ratio'], 3)} h_sx, {limit['rule']}"),
              ("  its review parameter", f"{limit['name']} [{limit['mark']}], "
                                          + (f"set to {fmt(limit['ratio'], 3)} (--set; default {fmt(limit['default'], 3)})"
                                             if limit["set"] else "at its default"))]
    for name, value in shears:
        fig.text(0.06, y, name, fontsize=7.6, va="top")
        fig.text(0.6, y, value, fontsize=7.6, va="top")
        y -= 0.0135

    loads_max, loads_min = numbers.get("bearing_axial_load_max_N"), numbers.get("bearing_axial_load_min_N")
    layout = numbers["design"].get("bearing_position")
    if loads_max is not None and loads_min is not None and layout is not None:
        timing = _uplift_timing(response)
        n_up = numbers["n_bearings_uplifted"]
        words = (f"{n_up} of {len(loads_min)} bearing(s) go into tension (uplift, ASCE 7-22 17.2.4.7)"
                 if n_up else f"No bearing goes into tension (all {len(loads_min)} stay in compression)")
        if timing:
            words += ": " + "; ".join(f"bearing {k + 1} from {fmt(start, 4)} s, {fmt(duration, 3)} s in all"
                                      for k, (start, duration) in timing.items())
        y -= 0.006
        for line in textwrap.wrap(words + ".", 120)[:3]:
            fig.text(0.06, y, line, fontsize=7.6, va="top", color="tab:red" if n_up else "k",
                     weight="bold" if n_up else "normal")
            y -= 0.0135
        height = min(0.2, y - 0.07 - 0.125)
        ax_loads = fig.add_axes((0.1, 0.125, 0.4, height))
        draw_bearing_loads(ax_loads, loads_max, loads_min, layout["gravity_load_N"])
        ax_plan = fig.add_axes((0.58, 0.125, 0.2, height))
        draw_bearing_plan(ax_plan, layout["x_m"], layout["y_m"], [low < 0.0 for low in loads_min])
    else:
        fig.text(0.06, y - 0.01, "No [[bearing_position]] in the design: no bearing axial loads.", fontsize=7.6,
                 va="top")
    caption(fig, f"Model {numbers['model']}: {numbers['model_reason']}.  Every number is the analysis' own "
                  "(the JSON beside this PDF): drift = peak over the record of the relative displacement of the "
                  "floors above and below a story (resultant in the plane for a pair), its ratio to the story "
                  "height; floor acceleration = peak absolute (ground + slab + floor) acceleration; the "
                  "superstructure shear is the peak first-story spring + damper force over W_s = g × the floors' "
                  "mass.  Bearing axial loads: gravity share + overturning from the floors' inertia forces at "
                  "their heights, distributed over the layout by rigid-slab statics (docs/building.md); a "
                  "negative minimum is tension (uplift), not released by the model.")
    return fig


def _period_rows(structure: dict) -> list[tuple]:
    """The fixed-base periods (the six longest) along x, and along y where the stories differ [s]."""
    x, y = structure["fixed_base_periods_x_s"][:6], structure["fixed_base_periods_y_s"][:6]
    if x == y:
        return [("fixed-base periods along x and y [s]", ", ".join(fmt(t, 3) for t in x))]
    return [("fixed-base periods along x [s]", ", ".join(fmt(t, 3) for t in x)),
            ("fixed-base periods along y [s]", ", ".join(fmt(t, 3) for t in y))]


def _uplift_timing(response) -> dict:
    """Bearing index → (first instant [s], total duration [s]) of tension, from the response's loads."""
    loads = getattr(response, "bearing_loads", None)
    out = loads() if callable(loads) else None
    if not out:
        return {}
    return {k: (start, duration) for k, (start, duration) in
            enumerate(zip(out["uplift_start_s"], out["uplift_duration_s"], strict=True)) if start is not None}
