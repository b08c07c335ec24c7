"""Suite summary (per design, across records) and the design chart of a grid sweep."""

from __future__ import annotations

import math

from isolator.atomic import atomic_path
from isolator.batch.plan import GRID_KEYS
from isolator.errors import BatchError
from isolator.metrics import REGIMES

#: Responses summarised per design across records.
SUMMARY_RESPONSES = ("peak_displacement_m", "peak_transmitted_acceleration_m_s2")


def suite_summary(table, swept_keys=()):
    """Per design, across its records (rows without error): n, mean, max and mean + σ of the
    peak displacement and the peak transmitted acceleration, and the count of each regime
    (record and harmonic).

    A motion is counted once: rows whose ``motion_sha256`` (the samples analysed and their
    time step) repeats an earlier row of the same design — the same record in two files —
    are left out of the statistics and counted in ``n_duplicate_motions``.

    σ is the sample standard deviation (n − 1 in the denominator; NaN for one record).

    Parameters
    ----------
    table : pandas.DataFrame
        The batch table.
    swept_keys : sequence of str
        Design keys of the grid, kept as columns.

    Returns
    -------
    pandas.DataFrame
        One row per design, in design order.
    """
    import pandas as pd

    keys = ["design_index", "design_name", "design_file_index"] + [k for k in GRID_KEYS if k in table.columns]
    out = []
    for _, rows in table.groupby("design_index", sort=True):
        good = rows[rows["error"] == ""]
        first = rows.iloc[0]
        entry = {key: first[key] for key in keys}
        entry["n_rows"] = len(rows)
        entry["n_failed"] = len(rows) - len(good)
        n_good = len(good)
        if "motion_sha256" in good.columns:
            digests = good["motion_sha256"].fillna("").astype(str)
            good = good[(digests == "") | ~digests.duplicated(keep="first")]
        entry["n_duplicate_motions"] = n_good - len(good)
        for name in SUMMARY_RESPONSES:
            values = pd.to_numeric(good[name], errors="coerce").dropna()
            mean = float(values.mean()) if len(values) else math.nan
            sigma = float(values.std(ddof=1)) if len(values) > 1 else math.nan
            entry[f"{name}_mean"] = mean
            entry[f"{name}_max"] = float(values.max()) if len(values) else math.nan
            entry[f"{name}_std"] = sigma
            entry[f"{name}_mean_plus_std"] = mean + sigma
        for source in ("record", "harmonic"):
            counts = good[f"regime_{source}"].value_counts()
            for regime in REGIMES:
                entry[f"n_{regime}_{source}"] = int(counts.get(regime, 0))
        out.append(entry)
    summary = pd.DataFrame(out)
    ordered = [c for c in summary.columns if c not in swept_keys or c in keys]
    return summary[ordered]


def _regime_code(values) -> float:
    """Most frequent regime of a design across records, as 0 (ST), 1 (SS), 2 (SL); NaN if none."""
    counts = {regime: int((values == regime).sum()) for regime in REGIMES}
    if not any(counts.values()):
        return math.nan
    return float(REGIMES.index(max(REGIMES, key=lambda r: (counts[r], -REGIMES.index(r)))))


def design_chart(table, keys, path) -> int:
    """Design chart of a grid sweep over two keys: a PDF, two pages per design of the file.

    Page 1: contours of the mean peak displacement over (key 1, key 2); page 2: the
    mean peak transmitted acceleration (in g).  The regime boundaries are overlaid: solid
    black where the most frequent record regime changes (ST | SS | SL), dashed grey for
    the harmonic regime at the equivalent points.

    Returns
    -------
    int
        Number of pages written.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.backends.backend_pdf import PdfPages

    from isolator.units import STANDARD_GRAVITY

    if len(keys) < 2:
        raise BatchError("the design chart needs a sweep over two keys")
    key_x, key_y = keys[0], keys[1]
    summary = suite_summary(table, keys)
    for source in ("record", "harmonic"):
        codes = []
        for index in summary["design_index"]:
            rows = table[(table["design_index"] == index) & (table["error"] == "")]
            codes.append(_regime_code(rows[f"regime_{source}"]))
        summary[f"regime_code_{source}"] = codes
    pages = 0
    quantities = (("peak_displacement_m_mean", "mean peak displacement [m]", 1.0),
                  ("peak_transmitted_acceleration_m_s2_mean", "mean peak transmitted acceleration [g]",
                   1.0 / STANDARD_GRAVITY))
    with atomic_path(path) as tmp:
        with PdfPages(tmp) as pdf:
            for _, group in summary.groupby("design_file_index", sort=True):
                xs = np.unique(group[key_x].astype(float))
                ys = np.unique(group[key_y].astype(float))
                if xs.size < 2 or ys.size < 2:
                    continue
                grid_of = {}
                for column in [q[0] for q in quantities] + ["regime_code_record", "regime_code_harmonic"]:
                    values = np.full((ys.size, xs.size), np.nan)
                    for _, row in group.iterrows():
                        i = int(np.searchsorted(ys, float(row[key_y])))
                        j = int(np.searchsorted(xs, float(row[key_x])))
                        values[i, j] = row[column]
                    grid_of[column] = values
                base = str(group.iloc[0]["design_name"]).split(" [")[0]
                n_records = int(group["n_rows"].max())
                for column, label, factor in quantities:
                    fig, ax = plt.subplots(figsize=(8.27, 6.5))
                    values = grid_of[column] * factor
                    if np.isfinite(values).sum() >= 4 and np.nanmax(values) > np.nanmin(values):
                        filled = ax.contourf(xs, ys, values, levels=14, cmap="viridis")
                        lines = ax.contour(xs, ys, values, levels=filled.levels[::2], colors="white", linewidths=0.6)
                        ax.clabel(lines, fmt="%.3g", fontsize=7)
                        fig.colorbar(filled, ax=ax, label=label)
                    for source, style, colour in (("record", "solid", "black"), ("harmonic", "dashed", "0.45")):
                        codes = grid_of[f"regime_code_{source}"]
                        finite = codes[np.isfinite(codes)]
                        if finite.size and finite.min() != finite.max():
                            ax.contour(xs, ys, codes, levels=[0.5, 1.5], colors=colour, linestyles=style,
                                       linewidths=1.6)
                    ax.plot([], [], color="black", label="regime boundary (record, most frequent)")
                    ax.plot([], [], color="0.45", linestyle="dashed", label="regime boundary (harmonic map)")
                    ax.legend(loc="upper right", fontsize=8, framealpha=0.8)
                    ax.set_xlabel(key_x)
                    ax.set_ylabel(key_y)
                    ax.set_title(f"{base}: {label}\nacross {n_records} record(s) per design", fontsize=10)
                    fig.tight_layout()
                    pdf.savefig(fig)
                    plt.close(fig)
                    pages += 1
        if pages == 0:
            raise BatchError("the design chart needs at least 2 values of each swept key")
    return pages
