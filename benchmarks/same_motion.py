"""The motion-signature distances docs/review.md quotes (the same-motion check of isolator/review/selection.py).

    python -m benchmarks.same_motion            # from the repository root; needs ../shared/records/pairs

Prints the closest distinct pairs of the shared real pairs, then how far copies of the first pair move
(rotated by 30°, scaled by 1.7, shifted by 3 s, linearly resampled to dt/2 and 2 dt).
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np

from isolator.review.selection import SAME_MOTION_TOLERANCE, motion_signature, signature_distance
from isolator.review.suite import load_suite

PAIRS = Path(__file__).resolve().parents[1].parent / "shared" / "records" / "pairs"


def main() -> None:
    suite = load_suite([str(PAIRS)], trim=True)
    signatures = {p.name: motion_signature(p.ax_m_s2, p.ay_m_s2, p.dt_s) for p in suite.pairs}
    distances = sorted((signature_distance(signatures[a], signatures[b]), a, b)
                       for a, b in itertools.combinations(signatures, 2))
    print(f"{len(suite.pairs)} real pairs; tolerance {SAME_MOTION_TOLERANCE}")
    for d, a, b in distances[:5]:
        print(f"  {d:8.4f}  {a} / {b}")
    p = suite.pairs[0]
    base = signatures[p.name]
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    t = np.arange(p.npts) * p.dt_s
    copies = {"rotated 30°": (c * p.ax_m_s2 - s * p.ay_m_s2, s * p.ax_m_s2 + c * p.ay_m_s2, p.dt_s),
              "scaled 1.7": (1.7 * p.ax_m_s2, 1.7 * p.ay_m_s2, p.dt_s),
              "shifted 3 s": (np.r_[np.zeros(int(3 / p.dt_s)), p.ax_m_s2], np.r_[np.zeros(int(3 / p.dt_s)), p.ay_m_s2],
                              p.dt_s)}
    for factor in (0.5, 2.0):
        t2 = np.arange(0.0, t[-1], p.dt_s * factor)
        copies[f"resampled to {p.dt_s * factor:g} s"] = (np.interp(t2, t, p.ax_m_s2), np.interp(t2, t, p.ay_m_s2),
                                                        p.dt_s * factor)
    print(f"copies of {p.name} (dt {p.dt_s:g} s)")
    for label, (ax, ay, dt) in copies.items():
        print(f"  {signature_distance(base, motion_signature(ax, ay, dt)):10.3g}  {label}")


if __name__ == "__main__":
    main()
