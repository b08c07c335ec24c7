"""Time of a design review: 11 real pairs × 2 property bounds (22 bidirectional analyses) + the PDF.

Warm: the first run (numba's disk cache loaded, matplotlib imported) is not counted; then the
median of ``--runs`` runs, each from reading the suite to the written PDF and JSON, without the
analysis cache (every analysis recomputed).  Prints a table; docs/performance.md quotes it.

    PYTHONPATH=$PWD python benchmarks/review_time.py --jobs 2 --runs 5
"""

from __future__ import annotations

import argparse
import os
import statistics
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAIRS = ROOT.parent / "shared" / "records" / "pairs"
#: the 12 shared pairs but the weakest (AOM017, 0.021 g): 11 pairs
FOLDERS = ["superstitionhills1987_PTS", "landers1992_YER", "hectormine1999_ABY", "duzce1999_DZC",
           "chichi1999_CHY028", "chuetsuoki2007_65025", "darfield2010_GDLC", "christchurch2011_CBGS",
           "lomaprieta1989_APEEL2", "lahabra2014_WLT", "ncalifornia2012_89146"]


def one_review(jobs: int, out: Path) -> dict:
    from isolator.design import Design
    from isolator.report.review_pages import write_review_pdf
    from isolator.review.run import run_review
    from isolator.review.suite import load_suite
    from isolator.review.target import load_target

    start = time.perf_counter()
    suite = load_suite([str(PAIRS / f) for f in FOLDERS], trim=True)
    read = time.perf_counter()
    review = run_review(Design.from_toml(ROOT / "data" / "example_review.toml"),
                        load_target(ROOT / "isolator" / "data" / "targets" / "example.toml"), suite, jobs=jobs,
                        nominal=False, rotd50_points=12, paper_map_resolution=30)
    done = time.perf_counter()
    write_review_pdf(review, out)
    end = time.perf_counter()
    return {"pairs": len(suite.pairs), "analyses": review.timing["analyses_total"], "read_s": read - start,
            "spectra_s": review.timing["spectra"], "analyses_s": review.timing["analyses"],
            "review_s": done - read, "pdf_s": end - done, "total_s": end - start}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    if not PAIRS.is_dir():
        raise SystemExit(f"needs the shared pairs at {PAIRS}")
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder) / "review.pdf"
        one_review(args.jobs, out)  # warm-up, not counted
        runs = [one_review(args.jobs, out) for _ in range(args.runs)]
    print(f"review of {runs[0]['pairs']} pairs × 2 bounds = {runs[0]['analyses']} analyses + PDF, "
          f"--jobs {args.jobs}, {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}, "
          f"median of {args.runs} warm runs")
    print(f"{'stage':<12} {'median s':>9} {'min s':>8} {'max s':>8}")
    for key in ("read_s", "spectra_s", "analyses_s", "review_s", "pdf_s", "total_s"):
        values = [r[key] for r in runs]
        print(f"{key[:-2]:<12} {statistics.median(values):9.2f} {min(values):8.2f} {max(values):8.2f}")


if __name__ == "__main__":
    main()
