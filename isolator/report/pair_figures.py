"""Figures of a bidirectional (pair) response: orbit, resultant displacement, hysteresis per direction.

Drawing only: every number comes from the response object (``time_s``,
``displacement_m`` (N, 2), ``absolute_acceleration_m_s2`` (N, 2),
``peak_displacement_m``); no file I/O, units on every axis.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.report.figures import new_figure


def resultant(values: np.ndarray) -> np.ndarray:
    """Euclidean norm of each row of an (N, 2) history [same unit as the input]."""
    values = np.asarray(values, dtype=np.float64)
    return np.hypot(values[:, 0], values[:, 1])


def draw_orbit(ax, displacement_m: np.ndarray, *, capacity_m: float | None = None,
               peak_m: float | None = None, labels=("X", "Y")) -> None:
    """Orbit X_x against X_y [m], equal axes, with the displacement-capacity circle if given."""
    x, y = displacement_m[:, 0], displacement_m[:, 1]
    ax.plot(x, y, color="k", lw=0.6, label="orbit of the bearing")
    ax.plot([x[-1]], [y[-1]], "s", color="tab:blue", ms=4, label=f"residual {math.hypot(x[-1], y[-1]):.3g} m")
    r = resultant(displacement_m)
    at = int(np.argmax(r))
    ax.plot([x[at]], [y[at]], "o", color="red", ms=4,
            label=f"peak at the samples {r[at]:.3g} m" if peak_m is None else f"peak {peak_m:.3g} m")
    theta = np.linspace(0.0, 2.0 * math.pi, 361)
    extent = float(np.max(r)) * 1.1 or 1e-3
    if capacity_m is not None and math.isfinite(capacity_m):
        ax.plot(capacity_m * np.cos(theta), capacity_m * np.sin(theta), color="tab:red", ls="--", lw=1.1,
                label=f"displacement capacity {capacity_m:.3g} m")
        extent = max(extent, 1.1 * capacity_m)
    ax.set_xlim(-extent, extent)
    ax.set_ylim(-extent, extent)
    ax.set_aspect("equal", adjustable="box")
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.axvline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel(f"displacement {labels[0]}  [m]")
    ax.set_ylabel(f"displacement {labels[1]}  [m]")
    ax.set_title("Orbit (relative displacement in the plane)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), frameon=False)


def pair_response_page(fig, response, mass_kg: float, *, capacity_m: float | None = None,
                       labels=("X", "Y")) -> dict:
    """Orbit, resultant displacement history and the force-displacement loop in each direction.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    response : PairResponse
        From :func:`isolator.solver.planar.simulate_pair` (or any object with the same fields).
    mass_kg : float
        Supported mass [kg]: isolator force = -M × absolute acceleration of the mass.
    capacity_m : float, optional
        Displacement capacity of the bearing [m] (the circle on the orbit).
    labels : tuple of str
        Names of the two horizontal directions (component labels).

    Returns
    -------
    dict
        The axes drawn, by name.
    """
    from matplotlib.ticker import MaxNLocator

    t = np.asarray(response.time_s)
    disp = np.asarray(response.displacement_m)
    force_kN = -mass_kg * np.asarray(response.absolute_acceleration_m_s2) / 1e3
    grid = fig.add_gridspec(3, 2, height_ratios=[1.5, 0.8, 1.0])
    ax_orbit = fig.add_subplot(grid[0, 0])
    draw_orbit(ax_orbit, disp, capacity_m=capacity_m, peak_m=response.peak_displacement_m, labels=labels)
    ax_r = fig.add_subplot(grid[1, :])
    ax_r.plot(t, resultant(disp), color="k", lw=0.7, label="resultant |X|")
    ax_r.plot(t, disp[:, 0], color="tab:blue", lw=0.5, alpha=0.7, label=labels[0])
    ax_r.plot(t, disp[:, 1], color="tab:orange", lw=0.5, alpha=0.7, label=labels[1])
    if capacity_m is not None and math.isfinite(capacity_m):
        ax_r.axhline(capacity_m, color="tab:red", ls="--", lw=1.0, label="capacity")
    ax_r.set_xlim(t[0], t[-1])
    ax_r.set_xlabel("time  [s]")
    ax_r.set_ylabel("displacement  [m]")
    ax_r.legend(loc="lower right", bbox_to_anchor=(1.0, 1.0), frameon=False, ncol=4, borderaxespad=0.2)
    axes = {"orbit": ax_orbit, "resultant": ax_r}
    for column, name in enumerate(labels):
        ax = fig.add_subplot(grid[2, column])
        ax.plot(disp[:, column], force_kN[:, column], color="k", lw=0.6)
        ax.set_xlabel(f"displacement {name}  [m]")
        ax.set_ylabel(f"isolator force {name}  [kN]")
        ax.set_title(f"Force-displacement loop, {name}")
        ax.xaxis.set_major_locator(MaxNLocator(5))
        axes[f"hysteresis_{name}"] = ax
    return axes


def pair_response_figure(response, mass_kg: float, *, capacity_m: float | None = None, labels=("X", "Y")):
    """A stand-alone A4 figure of :func:`pair_response_page` (for a PNG or the report)."""
    fig = new_figure(figsize=(8.27, 11.69))
    fig.subplots_adjust(left=0.1, right=0.96, top=0.95, bottom=0.06, hspace=0.45, wspace=0.32)
    pair_response_page(fig, response, mass_kg, capacity_m=capacity_m, labels=labels)
    return fig
