"""CPU and wall time of the design review's spectra stage, as `benchmarks/review_time.py` runs the review.

The same 11 real pairs of ``../shared/records/pairs`` and the same design (``data/example_review.toml``) and
target: one review (``run_review``, 2 bounds, no nominal) fixes the period grid and the scale factors; then each
timed run computes what the review's spectra stage computes — every pair's 5 % PSA and RotD100
(``pair_spectra``) on the grid and the plot periods — and, apart, RotD50 on 12 periods of the range (what
``rotd50_points=12`` adds after the stage).  Warm (numba's disk cache loaded by the untimed first run); the
least and the median of ``--runs``; CPU time is ``time.process_time`` of this process (the stage runs in the
review's own process).  docs/performance.md quotes it.

    .venv/bin/python -m benchmarks.spectra_stage_time --runs 5
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from pathlib import Path

import numpy as np

from benchmarks.review_time import FOLDERS, PAIRS, ROOT


def main() -> None:
    from isolator.design import Design
    from isolator.review.run import PLOT_PERIODS_S, run_review
    from isolator.review.spectra import pair_spectra, rotd50
    from isolator.review.suite import load_suite
    from isolator.review.target import load_target

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    if not PAIRS.is_dir():
        raise SystemExit(f"needs the shared pairs at {PAIRS}")
    suite = load_suite([str(PAIRS / f) for f in FOLDERS], trim=True)
    review = run_review(Design.from_toml(ROOT / "data" / "example_review.toml"),
                        load_target(Path(ROOT) / "isolator" / "data" / "targets" / "example.toml"), suite, jobs=1,
                        nominal=False)
    lo, hi = review.period_range_s
    periods = np.concatenate([review.grid_s, np.unique(np.concatenate([PLOT_PERIODS_S, [lo, hi]]))])
    t50 = np.geomspace(lo, hi, 12)

    def stage() -> tuple[float, float, float, float]:
        cpu, wall = time.process_time(), time.perf_counter()
        for pair in suite.pairs:
            pair_spectra(pair.ax_m_s2, pair.ay_m_s2, pair.dt_s, periods)
        cpu_1, wall_1 = time.process_time(), time.perf_counter()
        for pair in suite.pairs:
            rotd50(pair.ax_m_s2, pair.ay_m_s2, pair.dt_s, t50)
        return cpu_1 - cpu, wall_1 - wall, time.process_time() - cpu_1, time.perf_counter() - wall_1

    stage()  # warm
    runs = [stage() for _ in range(args.runs)]
    print(f"spectra stage: {len(suite.pairs)} pairs, {periods.size} periods (grid {review.grid_s.size} + plot), "
          f"range {lo:.3f}-{hi:.3f} s; RotD50 on {t50.size} periods; {os.cpu_count()} cores, "
          f"load average {os.getloadavg()[0]:.1f}, {args.runs} warm runs")
    for i, name in enumerate(("PSA + RotD100 CPU s", "PSA + RotD100 wall s", "RotD50 CPU s", "RotD50 wall s")):
        values = [r[i] for r in runs]
        print(f"{name:<22} least {min(values):6.3f}  median {statistics.median(values):6.3f}  "
              f"runs {' '.join(f'{v:.3f}' for v in values)}")


if __name__ == "__main__":
    main()
