"""The 2-D building's fast sub-steps at the friction's truncation tolerance 1e-16 and 1e-12, alternated in one process.

``planar_building.FAST_TRUNC_EPS`` is the Jorba–Zou tolerance of the friction's polynomial in a fast sub-step (its
last two terms below that fraction of µk N, |V|'s below that fraction of |V|): 1e-16 was the rule before (the series
pieces' own), 1e-12 the default (the fraction the sub-step's end check accepts; docs/building.md, h114).  For each
case of :func:`benchmarks.planar_building_stop_piece.cases` (the bench's 2-D building, µs > µk, 3 stories with a
dashpot on ABY and on PTS x with a zero second component): the fast sub-steps and pieces, the answers' largest
differences (histories over their peaks, event times, peaks, energies) and the kernel's CPU per call, the two
tolerances alternated call by call (medians of ``--runs``)::

    OPENBLAS_NUM_THREADS=1 .venv/bin/python -m benchmarks.planar_building_fast_eps [--records ../shared/records]
        [--runs 21]
"""

from __future__ import annotations

import argparse
from pathlib import Path

from benchmarks.planar_building_stop_piece import alternate

#: the previous rule (the series pieces' TRUNC_EPS) and the default
BEFORE, AFTER = 1e-16, 1e-12


def _describe(old, new) -> str:
    return (f"fast sub-steps {old.n_fast_steps} -> {new.n_fast_steps}, refused {sum(old.n_fast_refused)} -> "
            f"{sum(new.n_fast_refused)}, pieces {old.n_pieces} -> {new.n_pieces}")


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", default="../shared/records")
    parser.add_argument("--runs", type=int, default=21)
    args = parser.parse_args(argv)
    alternate(Path(args.records), args.runs, "FAST_TRUNC_EPS", BEFORE, AFTER, _describe)


if __name__ == "__main__":
    main()
