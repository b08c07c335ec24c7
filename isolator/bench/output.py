"""Output of the bench: CSV, Markdown tables and the log error / log time plot."""

from __future__ import annotations

import math
import statistics
from pathlib import Path

from isolator.bench.methods import OURS
from isolator.bench.pairs import PAIR_OURS

ROW_KEYS = ["method", "case", "setting", "seconds", "error_peak_rel", "error_residual_abs", "error_zeta",
            "error_trajectory"]
#: the columns after ROW_KEYS: events counted, timed runs (2-D) and why a baseline did not run
EXTRA_KEYS = ["n_events", "runs", "note"]


def rows_to_csv(rows: list[dict]) -> str:
    """The rows as CSV text (ROW_KEYS columns, then n_events, runs and note)."""
    lines = [",".join(ROW_KEYS + EXTRA_KEYS)]
    for r in rows:
        cells = []
        for key in ROW_KEYS + EXTRA_KEYS:
            value = r.get(key, "")
            cells.append(f'"{value}"' if isinstance(value, str) and "," in value else
                         (f"{value:.6g}" if isinstance(value, float) else str(value)))
        lines.append(",".join(cells))
    return "\n".join(lines) + "\n"


def pareto_to_csv(pareto: list[dict]) -> str:
    keys = list(dict.fromkeys(k for p in pareto for k in p))  # 2-D cases add the OpenSees ratios
    lines = [",".join(keys)]
    for p in pareto:
        cells = []
        for k in keys:
            v = p.get(k, "")
            cells.append(f"{v:.4g}" if isinstance(v, float) else (f'"{v}"' if isinstance(v, str) and "," in v
                                                                   else str(v)))
        lines.append(",".join(cells))
    return "\n".join(lines) + "\n"


def _ratio(value, fmt=".3g"):
    return "—" if value is None else f"{value:{fmt}}×"


def _speed_words(time_ratio: float) -> str:
    return f"{time_ratio:.3g}× slower" if time_ratio >= 1.0 else f"{1.0 / time_ratio:.3g}× faster"


def pareto_markdown(pareto: list[dict]) -> str:
    """The Pareto headline as a Markdown table."""
    lines = ["| case | ours: time | ours: error | on front | speed-up at equal error | speed-up at error 1e-3 "
             "| accuracy gain at equal time | fastest baseline: time, error gain | most accurate baseline |",
             "|---|---|---|---|---|---|---|---|---|"]
    for p in pareto:
        eq_err = _ratio(p["speedup_at_equal_error"]) if p["speedup_at_equal_error"] else "none reaches it"
        if p["speedup_at_equal_error"] is None and p.get("cross_check_time_ratio"):
            eq_err += f" (the rtol 1e-12 reference: {p['cross_check_time_ratio']:.3g}× slower)"
        eq_time = _ratio(p["accuracy_gain_at_equal_time"]) if p["accuracy_gain_at_equal_time"] else "none as fast"
        eng = (f"{p['speedup_at_1e-3']:.3g}× ({p['speedup_at_1e-3_vs']})" if p["speedup_at_1e-3"] else
               "none reaches it")
        lines.append(
            f"| {p['case']} | {p['seconds'] * 1e3:.3g} ms | {p['error']:.1e} | "
            f"{'yes' if p['on_pareto_front'] else 'NO'} "
            f"| {eq_err} | {eng} | {eq_time} | {_speed_words(p['fastest_time_ratio'])}, "
            f"{p['accuracy_gain_vs_fastest']:.2g}× less accurate ({p['fastest_baseline']}) | "
            f"{p['most_accurate_baseline']}: error {p['most_accurate_error']:.1e}, "
            f"{_speed_words(p['most_accurate_time_ratio'])} |")
    return "\n".join(lines) + "\n"


def rows_markdown(rows: list[dict]) -> str:
    """All rows as a Markdown table."""
    lines = ["| case | method | setting | time [ms] | peak (rel) | residual (abs) | ζ | trajectory (rel) |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        setting = r["setting"] if isinstance(r["setting"], str) else f"{r['setting']:g}"
        if r.get("note"):  # a baseline that did not run here
            lines.append(f"| {r['case']} | {r['method']} | {setting} | {r['note']} | — | — | — | — |")
            continue
        lines.append(f"| {r['case']} | {r['method']} | {setting} | {r['seconds'] * 1e3:.3g} | "
                     f"{r['error_peak_rel']:.1e} | {r['error_residual_abs']:.1e} | {_error(r['error_zeta'])} | "
                     f"{r['error_trajectory']:.1e} |")
    return "\n".join(lines) + "\n"


def _error(value: float) -> str:
    return f"{value:.1e}" if math.isfinite(value) else "—"


def opensees_summary(pareto: list[dict]) -> list[str]:
    """Summary lines of the 2-D cases: ours against OpenSees at the record's dt, measured in one run.

    One line per 2-D case, then the medians over the cases (time ratio = OpenSees'
    median time over ours, the two timed in alternation where OpenSees runs; error ratio =
    OpenSees' trajectory (peak) error over ours, both against the independent reference).
    """
    pairs = [p for p in pareto if "opensees_time_ratio" in p]
    if not pairs:
        return []
    ran = [p for p in pairs if p["opensees_time_ratio"] is not None]
    if not ran:
        return ["2-D vs OpenSees: not measured (openseespy not installed, or it does not load here)"]
    lines = []
    for p in ran:
        lines.append(f"2-D {p['case']}: ours {p['seconds'] * 1e3:.3g} ms (median of {p.get('ours_runs')}), "
                     f"{_speed_words(1.0 / p['opensees_time_ratio'])} than OpenSees at the record's dt "
                     f"(median of {p.get('opensees_runs')}, interleaved with ours), trajectory error {p['error']:.1e}: "
                     f"{p['opensees_error_ratio']:.2g}× lower (peak: {p['opensees_peak_error_ratio']:.2g}× lower)")
    time_ratio = statistics.median(p["opensees_time_ratio"] for p in ran)
    error_ratio = statistics.median(p["opensees_error_ratio"] for p in ran)
    peak_ratio = statistics.median(p["opensees_peak_error_ratio"] for p in ran)
    lines.append(f"2-D summary over {len(ran)} pair(s), medians: ours is {time_ratio:.3g}× faster than OpenSees "
                 f"(singleFPBearing, Newmark + Newton at the record's dt) with {error_ratio:.2g}× lower "
                 f"trajectory error ({peak_ratio:.2g}× lower on the peak), measured in this run")
    return lines


def plot(rows: list[dict], path: Path, error_key: str = "error_trajectory") -> None:
    """Log error against log time, one curve per method, one panel per case."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cases = list(dict.fromkeys(r["case"] for r in rows))
    names = list(dict.fromkeys(r["method"] for r in rows))
    n_col = 2 if len(cases) > 1 else 1
    n_row = int(math.ceil(len(cases) / n_col))
    fig, axes = plt.subplots(n_row, n_col, figsize=(6.0 * n_col, 4.2 * n_row), squeeze=False)
    markers = "o^svDPX*<>h"  # 11 markers over 10 colours: no two methods look alike
    colors = plt.get_cmap("tab10").colors  # one colour per method across panels (1-D and 2-D methods differ)
    legend = {}
    for ax, case in zip(axes.ravel(), cases, strict=False):
        for i, name in enumerate(names):
            # in the order of the settings (coarse to fine), so each curve is the method's own path
            pts = [(r["seconds"], r[error_key]) for r in rows if r["case"] == case and r["method"] == name
                   and math.isfinite(r["seconds"]) and math.isfinite(r[error_key])]
            if not pts:
                continue
            t, e = zip(*pts, strict=True)
            style = dict(marker=markers[i % len(markers)], color=colors[i % len(colors)], label=name)
            if name in (OURS, PAIR_OURS):
                style.update(color="k", marker="o", markersize=11, zorder=5)
            lines = ax.loglog(t, e, "-" if len(t) > 1 else "", **style)
            legend.setdefault(name, lines[0])
        ax.set_title(case, fontsize=9)
        ax.set_xlabel("wall time [s] (median)")
        ax.set_ylabel("max trajectory error / peak [-]")
        ax.grid(True, which="major", alpha=0.3)
    for ax in axes.ravel()[len(cases):]:
        ax.axis("off")
    n_legend_col = 3 if n_col > 1 else 1
    fig.legend(list(legend.values()), list(legend.keys()), loc="lower center", ncol=n_legend_col, fontsize=8,
               frameon=False)
    # room for the legend: ~0.18 in per row of labels plus the axis label above it [in / figure height]
    legend_in = 0.18 * math.ceil(len(legend) / n_legend_col) + 0.4
    fig.set_figheight(4.2 * n_row + legend_in)
    fig.tight_layout(rect=(0, legend_in / (4.2 * n_row + legend_in), 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)
