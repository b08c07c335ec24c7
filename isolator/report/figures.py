"""Figures of the report and of the README: record, response, regime map, A(α).

Every function draws on axes it is given (or a new figure) and returns the figure; no
file I/O here.  Units on every axis; captions are written by :mod:`isolator.report.pdf`.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.units import STANDARD_GRAVITY

#: colours of the paper's Fig. 6
COLOUR_FRICTION = "#cfe6f7"  # light blue
COLOUR_VISCOUS = "#f7d0cf"  # light red
COLOUR_AMPLIFIED = "#c8c8c8"  # light grey
COLOUR_SLIDING = "#ffe2b0"  # stick/slip shading on time histories


#: The report's style.  Fonts are embedded as Type 3 (glyph procedures written by matplotlib
#: itself): text stays selectable and extractable, and the PDF is written without fontTools
#: subsetting each TrueType font (Type 42), which took about 1.6 s of a 4-page report.
RC_PARAMS = {"pdf.fonttype": 3, "ps.fonttype": 3, "font.size": 8.5, "axes.titlesize": 9,
             "axes.labelsize": 8.5, "legend.fontsize": 7.5, "xtick.labelsize": 7.5,
             "ytick.labelsize": 7.5, "axes.grid": True, "grid.alpha": 0.3}


def new_figure(**kwargs):
    """A matplotlib ``Figure`` in the report's style, outside pyplot.

    Built directly (no ``matplotlib.pyplot``: no GUI backend, no global list of open
    figures to close, 0.1 s less to import); ``fig.savefig`` picks the PDF or PNG writer
    from the file name.  The style is applied to the process's rcParams (a few
    microseconds, every call, so that a change elsewhere does not leak into a report);
    tick labels read it when the figure is drawn.

    Parameters
    ----------
    **kwargs
        Passed to ``matplotlib.figure.Figure`` (``figsize`` [in], ``layout``…).
    """
    import matplotlib
    from matplotlib.figure import Figure

    matplotlib.rcParams.update(RC_PARAMS)
    return Figure(**kwargs)


def distance_to_edge(mask) -> np.ndarray:
    """Euclidean distance [cells] from each True cell of a 2-D mask to the nearest False cell.

    The exact Euclidean distance transform (``scipy.ndimage.distance_transform_edt`` of the
    mask), computed separably: first the distance along each row to the nearest False cell,
    then D²(r, c) = min over r' of (g(r', c)² + (r − r')²).  O(rows² × columns) time and
    O(rows × columns) memory, a few milliseconds on a regime-map grid; it spares the report
    the import of scipy.ndimage.  False cells get 0; a mask without False cells gets inf.
    """
    mask = np.asarray(mask, dtype=bool)
    n_rows, n_cols = mask.shape
    cols = np.arange(n_cols, dtype=float)
    # along the rows: distance to the nearest False cell on the left and on the right
    left = np.maximum.accumulate(np.where(mask, -np.inf, cols), axis=1)
    right = np.minimum.accumulate(np.where(mask, np.inf, cols)[:, ::-1], axis=1)[:, ::-1]
    g2 = np.minimum(cols - left, right - cols) ** 2
    rows = np.arange(n_rows, dtype=float)
    offsets2 = (rows[:, None] - rows[None, :]) ** 2  # (r, r')
    d2 = np.empty(mask.shape)
    for c in range(n_cols):  # bounded: one pass per column
        d2[:, c] = np.min(g2[None, :, c] + offsets2, axis=1)
    return np.sqrt(d2)


#: Horizontal resolution of a drawn time axis: buckets of a decimated curve, and the
#: number of pieces of a time axis below which neighbouring shaded intervals are merged.
#: A page is ~2000 device pixels wide at 300 dpi, so nothing visible is lost.
PIXELS_PER_AXIS = 2000


def extreme_indices(n_buckets: int, *series) -> np.ndarray:
    """Indices that keep every series' envelope: first, last, and per bucket the minimum and maximum.

    A curve drawn through these samples (at most ``2 n_buckets + 2`` per series) is, at
    the resolution of ``n_buckets`` columns, the curve through all samples: each column
    spans the same range.  Short series are returned whole.

    Parameters
    ----------
    n_buckets : int
        Columns of the drawing [-].
    *series : numpy.ndarray
        Equal-length arrays drawn together (e.g. X and the force of a hysteresis loop).

    Returns
    -------
    numpy.ndarray
        Sorted unique sample indices.
    """
    n = len(series[0])
    if n <= 4 * n_buckets:
        return np.arange(n)
    length = n // n_buckets
    used = length * n_buckets
    starts = np.arange(n_buckets) * length
    picks = [np.array([0, n - 1])]
    for values in series:
        blocks = np.asarray(values[:used]).reshape(n_buckets, length)
        picks += [starts + blocks.argmin(axis=1), starts + blocks.argmax(axis=1)]
        if used < n:
            tail = np.asarray(values[used:])
            picks.append(used + np.array([tail.argmin(), tail.argmax()]))
    return np.unique(np.concatenate(picks))


def merge_intervals(intervals, min_gap_s: float) -> np.ndarray:
    """Intervals with gaps shorter than ``min_gap_s`` [s] joined (a gap below a pixel is invisible).

    Parameters
    ----------
    intervals : array_like
        (n, 2) start and end times [s], sorted.
    min_gap_s : float
        Gaps up to this length are closed [s].

    Returns
    -------
    numpy.ndarray
        (m, 2) merged intervals, m ≤ n.
    """
    intervals = np.asarray(intervals, dtype=float).reshape(-1, 2)
    if intervals.shape[0] < 2:
        return intervals
    gaps = intervals[1:, 0] - intervals[:-1, 1]
    breaks = np.flatnonzero(gaps > min_gap_s)
    starts = intervals[np.concatenate(([0], breaks + 1)), 0]
    ends = intervals[np.concatenate((breaks, [intervals.shape[0] - 1])), 1]
    return np.column_stack([starts, ends])


def shade_intervals(ax, intervals, label="sliding", colour=COLOUR_SLIDING, span_s=None) -> None:
    """Shade time intervals (e.g. slip) behind a time history, as one artist.

    Intervals closer than a pixel (``span_s / PIXELS_PER_AXIS``) are merged, so a record
    with hundreds of thousands of slips draws at most ``PIXELS_PER_AXIS`` bars.

    Parameters
    ----------
    span_s : float, optional
        Length of the time axis [s]; the extent of the intervals by default.
    """
    intervals = np.asarray(intervals, dtype=float).reshape(-1, 2)
    if intervals.shape[0] == 0:
        return
    if span_s is None:
        span_s = float(intervals[-1, 1] - intervals[0, 0])
    merged = merge_intervals(intervals, span_s / PIXELS_PER_AXIS)
    ax.broken_barh(list(zip(merged[:, 0], merged[:, 1] - merged[:, 0], strict=True)), (0.0, 1.0),
                   transform=ax.get_xaxis_transform(), facecolors=colour, alpha=0.7, lw=0, label=label, zorder=0)


def plot_decimated(ax, x, y, **style):
    """``ax.plot(x, y)`` through :func:`extreme_indices` of y: the same picture, bounded size."""
    index = extreme_indices(PIXELS_PER_AXIS, y)
    return ax.plot(np.asarray(x)[index], np.asarray(y)[index], **style)


# ---- regime map ------------------------------------------------------------------------


def draw_regime_map(ax, rmap, *, design_point=None, triple=None, show_legend=True, title=None):
    """The (k, α) map of the paper's Figs. 5–7 on ``ax``.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    rmap : isolator.maps.RegimeMap
    design_point : tuple, optional
        (k, α, label) of a design to mark.
    triple : tuple, optional
        (α̂, k̂) of the triple point.
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    k, alpha = rmap.k, rmap.alpha
    kk, aa = np.meshgrid(k, alpha)
    handles = []
    # dominance regions (friction light blue, viscous light red, elastic hatched) from the
    # continuous log-ratio of each force to the larger of the two others, so that the
    # region edges are interpolated between grid points rather than drawn as steps
    moving = rmap.regime > 0
    amplitude = np.where(moving, rmap.amplitude, 0.0)
    forces = {"friction": np.full(amplitude.shape, rmap.mu_k), "elastic": kk * amplitude,
              "viscous": rmap.eta * amplitude * np.sqrt(np.maximum(aa, 0.0) * rmap.mu_s)}

    def margin(name):
        others = np.maximum(*[forces[o] for o in forces if o != name])
        with np.errstate(divide="ignore", invalid="ignore"):
            values = np.log10(forces[name] / others)
        return np.nan_to_num(values, nan=-10.0, posinf=10.0, neginf=-10.0)

    ax.contourf(kk, aa, margin("friction"), levels=[0.0, 11.0], colors=[COLOUR_FRICTION], zorder=0)
    ax.contourf(kk, aa, margin("viscous"), levels=[0.0, 11.0], colors=[COLOUR_VISCOUS], zorder=0)
    hatch = ax.contourf(kk, aa, margin("elastic"), levels=[0.0, 11.0], colors="none", hatches=["////"], zorder=1)
    try:
        hatch.set_edgecolor("#9a9a9a")
        hatch.set_linewidth(0.0)
    except AttributeError:
        pass
    handles += [Patch(facecolor=COLOUR_FRICTION, label="friction dominant"),
                Patch(facecolor=COLOUR_VISCOUS, label="viscous dominant"),
                Patch(facecolor="white", hatch="////", edgecolor="#9a9a9a", label="elastic dominant")]
    # A > 1 region, interpolated on the amplitude field
    if (amplitude > 1.0).any():
        ax.contourf(kk, aa, np.minimum(amplitude, 1e6), levels=[1.0, 1e7], colors=[COLOUR_AMPLIFIED], alpha=0.75,
                    zorder=2)
        handles.append(Patch(facecolor=COLOUR_AMPLIFIED, alpha=0.75, label="A > 1 (amplified)"))
    # regime boundaries: ST | SS at α = 1 from the regime codes; every SS | SL change from the
    # slip-time ratio ζ (= 1 exactly in SL), so SS/SL/SS/SL sequences along α all show
    if alpha[0] < 1.0 < alpha[-1]:
        ax.axhline(1.0, color="k", lw=1.0, zorder=4)  # α_SS = 1 exactly, whatever k and η
    if (~moving & (aa > 1.0)).any():  # ST islands above α = 1 (stuck for good after a transient)
        ax.contour(kk, aa, np.where(aa <= 1.0, 1.0, moving.astype(float)), levels=[0.5], colors=["k"],
                   linewidths=[1.0], zorder=4)
    if rmap.boundary_k.size:
        from matplotlib.collections import LineCollection

        from isolator.maps import boundary_segments

        # refined: each change of regime located by bisection in every column, joined across columns
        segments = boundary_segments(rmap, "SS", "SL") + boundary_segments(rmap, "SL", "SS")
        ax.add_collection(LineCollection(segments, colors="red", linewidths=1.6, zorder=4))
        islands = boundary_segments(rmap, "SS", "ST") + boundary_segments(rmap, "ST", "SS")
        islands = [seg for seg in islands if seg[:, 1].min() > 1.0]
        if islands:
            ax.add_collection(LineCollection(islands, colors="k", linewidths=1.0, zorder=4))
    elif (rmap.regime == 2).any() and (rmap.regime == 1).any():
        zeta = np.where(moving, rmap.zeta, 0.0)
        ax.contour(kk, aa, zeta, levels=[0.999], colors=["red"], linewidths=[1.6], zorder=4)
    handles += [Line2D([], [], color="k", lw=1.0, label="ST | SS boundary (α = 1)"),
                Line2D([], [], color="red", lw=1.6, label="SS | SL boundaries (ζ = 1)")]
    # ρ = 1 curves
    with np.errstate(divide="ignore", invalid="ignore"):
        for field, colour, name in ((rmap.rho_ef, "magenta", "ρ_ef = 1"), (rmap.rho_vf, "orange", "ρ_vf = 1")):
            values = np.where(moving, np.log10(field), np.nan)
            if np.nanmin(values, initial=np.inf) < 0 < np.nanmax(values, initial=-np.inf):
                ax.contour(kk, aa, values, levels=[0.0], colors=[colour], linewidths=1.3, zorder=5)
                handles.append(Line2D([], [], color=colour, lw=1.3, label=name))
    if rmap.eta > 0:
        k_line = np.linspace(k[0], k[-1], 200)
        a_line = k_line ** 2 / (rmap.eta ** 2 * rmap.mu_s)  # ρ_ev = 1 exactly
        ok = (a_line >= max(alpha[0], 1.0)) & (a_line <= alpha[-1])
        if ok.any():
            ax.plot(k_line[ok], a_line[ok], color="green", lw=1.3, zorder=5)
            handles.append(Line2D([], [], color="green", lw=1.3, label="ρ_ev = 1"))
        k_crit = rmap.eta ** 2 / 4.0
        if k[0] < k_crit < k[-1]:
            ax.axvline(k_crit, color="blue", ls="--", lw=1.0, zorder=5)
            handles.append(Line2D([], [], color="blue", ls="--", lw=1.0, label="η² = 4k (critical damping)"))
    # resonance: undamped line α = k/µs, and the line of largest A
    k_line = np.linspace(k[0], k[-1], 200)
    a_res = k_line / rmap.mu_s
    ok = (a_res >= max(alpha[0], 1.0)) & (a_res <= alpha[-1])
    if ok.any():
        ax.plot(k_line[ok], a_res[ok], color="k", ls="--", lw=1.0, zorder=5)
        handles.append(Line2D([], [], color="k", ls="--", lw=1.0, label="α = k/µs (undamped resonance)"))
    k_r, a_r = rmap.resonance_line()
    if k_r.size > 2:
        ax.plot(k_r, a_r, color="blue", lw=1.2, zorder=5)
        handles.append(Line2D([], [], color="blue", lw=1.2, label="resonance line (max A)"))
    if triple is not None:
        a_hat, k_hat = triple
        if k[0] <= k_hat <= k[-1] and alpha[0] <= a_hat <= alpha[-1]:
            ax.plot([k_hat], [a_hat], "o", ms=7, mfc="none", mec="k", mew=1.6, zorder=7)
            handles.append(Line2D([], [], marker="o", ls="none", mfc="none", mec="k", mew=1.6,
                                  label=f"triple point (k̂ = {k_hat:.3g}, α̂ = {a_hat:.3g})"))
    # regime names at the centre of each region
    from isolator.metrics import REGIMES

    for code, name in enumerate(REGIMES):
        mask = rmap.regime == code
        if mask.any():
            # the label goes where the region is deepest (farthest from its edges)
            depth = distance_to_edge(np.pad(mask, 1))[1:-1, 1:-1]
            rows, cols = np.nonzero(depth >= max(0.75 * depth.max(), 1.0))
            if rows.size:
                nearest = int(np.argmin((rows - rows.mean()) ** 2 + (cols - cols.mean()) ** 2))
                i, j = rows[nearest], cols[nearest]
                ax.text(k[j], alpha[i], name, ha="center", va="center", fontsize=10, weight="bold",
                        zorder=8, bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.7})
    if design_point is not None:
        kd, ad, label = design_point
        ax.plot([kd], [ad], marker="*", ms=13, color="gold", mec="k", mew=1.0, zorder=9, ls="none")
        handles.append(Line2D([], [], marker="*", ms=11, color="gold", mec="k", ls="none", label=label))
    ax.set_xlim(k[0], k[-1])
    ax.set_ylim(alpha[0], alpha[-1])
    ax.set_xlabel("dimensionless stiffness k = K A0 / (M g)  [-]")
    ax.set_ylabel("reduced acceleration α = A0 Ω² / (µs g)  [-]")
    ax.grid(False)
    ax.set_title(title or f"Harmonic regime map, η = {rmap.eta:g}, µs = {rmap.mu_s:g}, µk = {rmap.mu_k:g}")
    if show_legend:
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), frameon=False)
    return handles


def regime_map_figure(rmap, *, triple=None, design_point=None, title=None):
    """A stand-alone figure of a regime map with its legend on the right."""
    fig = new_figure(figsize=(9.0, 5.6), layout="constrained")
    ax = fig.subplots()
    draw_regime_map(ax, rmap, triple=triple, design_point=design_point, title=title)
    return fig


def draw_amplitude_curve(ax, alphas, amplitudes, regimes, *, steady=None, alpha_record=None,
                         amplitude_record=None, k=0.0, eta=0.0):
    """A(α) at fixed k and η, coloured by regime, with the record's α marked.

    Points at resonant growth (``steady`` False: no steady amplitude) are drawn as
    triangles at the top of the axes, which is capped so that the rest stays readable.
    """
    steady = np.ones(alphas.shape, bool) if steady is None else np.asarray(steady, bool)
    colours = {0: "k", 1: "tab:orange", 2: "tab:blue"}
    names = {0: "ST", 1: "SS", 2: "SL"}
    finite = amplitudes[steady]
    reference = [1.0] + ([amplitude_record] if amplitude_record is not None else [])
    top = 1.15 * max(float(np.nanmax(finite)) if finite.size else 1.0, *reference)
    top = min(top, 1.3 * max(float(np.nanpercentile(finite, 90)) if finite.size else 1.0, *reference) + 0.5)
    for code in (0, 1, 2):
        mask = (regimes == code) & steady
        if mask.any():
            ax.plot(alphas[mask], amplitudes[mask], ".", ms=3.5, color=colours[code], label=f"harmonic, {names[code]}")
    ax.plot(alphas[steady], np.minimum(amplitudes[steady], top), "-", color="0.6", lw=0.7, zorder=0)
    clipped = steady & (amplitudes > top)
    if clipped.any():
        ax.plot(alphas[clipped], np.full(clipped.sum(), 0.97 * top), "^", color="0.3", ms=4,
                label="A above the axis")
    if (~steady).any():
        ax.plot(alphas[~steady], np.full((~steady).sum(), 0.97 * top), "^", color="red", ms=5,
                label="resonant growth (unbounded A)")
    ax.axhline(1.0, color="0.3", ls=":", lw=1.0, label="A = 1")
    if alpha_record is not None:
        ax.axvline(alpha_record, color="red", lw=1.0, ls="--", label=f"record α = {alpha_record:.3g}")
    if amplitude_record is not None and alpha_record is not None:
        ax.plot([alpha_record], [amplitude_record], "D", color="red", ms=6, label=f"record A = {amplitude_record:.3g}")
    ax.set_xlabel("reduced acceleration α  [-]")
    ax.set_ylabel("amplitude A = X_pp / (2 A0)  [-]")
    ax.set_title(f"Harmonic amplitude A(α) at the design's k = {k:.3g}, η = {eta:.3g}")
    ax.set_ylim(0.0, top)
    ax.legend(loc="best", frameon=True)


# ---- record and response pages -------------------------------------------------------


def record_page(fig, motion, window_s, periods_s, psa_m_s2, isolated_period_s, effective_period_s=None):
    """Page 2: acceleration, velocity, displacement and the 5 %-damped spectrum."""
    from isolator.motion import displacement_m, velocity_m_s

    t = motion.time_s
    acc = motion.acceleration_m_s2
    axes = fig.subplots(4, 1, gridspec_kw={"height_ratios": [1, 1, 1, 1.25]})
    series = [(acc / STANDARD_GRAVITY, "ground acceleration  [g]"),
              (velocity_m_s(acc, motion.dt_s, motion.sample_times_s), "ground velocity  [m/s]"),
              (displacement_m(acc, motion.dt_s, motion.sample_times_s), "ground displacement  [m]")]
    for ax, (values, label) in zip(axes[:3], series, strict=True):
        ax.axvspan(*window_s, color="0.92", lw=0, zorder=0, label="D5-95 window")
        plot_decimated(ax, t, values, lw=0.6, color="k")
        peak = int(np.argmax(np.abs(values)))
        ax.plot([t[peak]], [values[peak]], "o", color="red", ms=3.5,
                label=f"peak {abs(values[peak]):.3g} at {t[peak]:.2f} s")
        ax.set_ylabel(label)
        ax.set_xlim(t[0], t[-1])
        ax.legend(loc="lower right", bbox_to_anchor=(1.0, 1.0), frameon=False, ncol=2, borderaxespad=0.2)
    axes[2].set_xlabel("time  [s]")
    ax = axes[3]
    ax.plot(periods_s, psa_m_s2 / STANDARD_GRAVITY, color="k", lw=1.0, label="PSA, 5 % damping")
    ax.axvline(isolated_period_s, color="tab:blue", ls="--", lw=1.1,
               label=f"isolated period T = {isolated_period_s:.3g} s")
    if effective_period_s is not None and math.isfinite(effective_period_s):
        ax.axvline(effective_period_s, color="tab:green", ls=":", lw=1.3,
                   label=f"effective period T_eff = {effective_period_s:.3g} s")
    ax.set_xscale("log")
    plain_log_labels(ax)
    ax.set_xlabel("oscillator period  [s]")
    ax.set_ylabel("pseudo-spectral acceleration  [g]")
    ax.set_xlim(periods_s[0], periods_s[-1])
    ax.legend(loc="upper right", frameon=True)
    return axes


def plain_log_labels(*axes) -> None:
    """Tick labels of the log axes of ``axes`` as plain numbers (0.1, 1, 3, 10), not 10⁻¹ or 3×10⁰.

    The same ticks as matplotlib's default (its ``LogFormatter`` decides which minor ticks carry a label);
    only the text changes: an engineer reads periods in seconds, and the labels need no mathtext, whose
    parser matplotlib builds on the first use in a process (~0.3 s of a report).
    """
    from matplotlib.ticker import LogFormatter

    class PlainLogFormatter(LogFormatter):
        def __call__(self, x, pos=None):
            return format(x, "g") if super().__call__(x, pos) else ""

    for ax in axes:
        for axis in (ax.xaxis, ax.yaxis):
            if axis.get_scale() == "log":
                axis.set_major_formatter(PlainLogFormatter())
                axis.set_minor_formatter(PlainLogFormatter(labelOnlyBase=False))


def energy_histories(response, mass_kg: float) -> dict:
    """Energy over time [J], exact at the samples (the solver's closed-form integrals).

    input = -M ∫ a_g Ẋ dt, friction = M µk g ∫ |Ẋ| dt, viscous = M c ∫ Ẋ² dt (cumulative,
    from the kernel), kinetic = M Ẋ²/2, potential = M κ X²/2.
    """
    s = response.system
    x, v = response.displacement_m, response.velocity_m_s
    e_in, e_f, e_v = response.energy_history_J_per_kg
    return {
        "input": mass_kg * e_in,
        "friction": mass_kg * e_f,
        "viscous": mass_kg * e_v,
        "kinetic + potential": mass_kg * (0.5 * v * v + 0.5 * s.stiffness_per_mass * x * x),
    }


def response_page(fig, response, mass_kg: float, slip_intervals):
    """Page 3: displacement, velocity, accelerations with slip shading; hysteresis; energies."""
    grid = fig.add_gridspec(4, 2, height_ratios=[1, 1, 1, 1.5])
    t = response.time_s
    ax_x = fig.add_subplot(grid[0, :])
    ax_v = fig.add_subplot(grid[1, :], sharex=ax_x)
    ax_a = fig.add_subplot(grid[2, :], sharex=ax_x)
    for ax in (ax_x, ax_v, ax_a):
        shade_intervals(ax, slip_intervals, span_s=float(t[-1] - t[0]))
    plot_decimated(ax_x, t, response.displacement_m, color="k", lw=0.7, label="relative displacement X")
    ax_x.set_ylabel("X  [m]")
    plot_decimated(ax_v, t, response.velocity_m_s, color="k", lw=0.7, label="relative velocity dX/dt")
    ax_v.set_ylabel("dX/dt  [m/s]")
    plot_decimated(ax_a, t, response.ground_acceleration_m_s2 / STANDARD_GRAVITY, color="0.65", lw=0.6,
                   label="ground")
    plot_decimated(ax_a, t, response.absolute_acceleration_m_s2 / STANDARD_GRAVITY, color="tab:red", lw=0.8,
                   label="transmitted (absolute, of the mass)")
    ax_a.set_ylabel("acceleration  [g]")
    ax_a.set_xlabel("time  [s]")
    ax_a.set_xlim(t[0], t[-1])
    for ax in (ax_x, ax_v, ax_a):  # legends above the axes: the traces fill the frame
        ax.legend(loc="lower right", bbox_to_anchor=(1.0, 1.0), frameon=False, ncol=3, borderaxespad=0.2)
    ax_h = fig.add_subplot(grid[3, 0])
    force_kN = -mass_kg * response.absolute_acceleration_m_s2 / 1e3
    loop = extreme_indices(PIXELS_PER_AXIS, response.displacement_m, force_kN)  # the loop's extremes kept
    ax_h.plot(response.displacement_m[loop], force_kN[loop], color="k", lw=0.6)
    ax_h.set_xlabel("relative displacement X  [m]")
    ax_h.set_ylabel("isolator force  [kN]")
    ax_h.set_title("Force-displacement loop")
    ax_e = fig.add_subplot(grid[3, 1])
    energies = energy_histories(response, mass_kg)
    styles = {"input": ("k", "-"), "friction": ("tab:blue", "-"), "viscous": ("tab:red", "-"),
              "kinetic + potential": ("tab:green", "--")}
    for name, values in energies.items():
        if name == "viscous" and response.system.damping_per_mass == 0.0:
            continue
        colour, style = styles[name]
        plot_decimated(ax_e, t, values / 1e3, color=colour, ls=style, lw=1.0, label=name)
    ax_e.set_xlabel("time  [s]")
    ax_e.set_ylabel("energy  [kJ]")
    ax_e.set_title("Energy balance over time")
    ax_e.legend(loc="upper left", frameon=True)  # cumulative curves leave the upper left empty
    return energies
