"""Throughput of the planar (2-D) engine on the real pairs: samples per second per core.

Usage::

    python -m benchmarks.planar_throughput [--repeat 7] [--mu 0.06] [--radius 2.0] [--rtol 1e-11]

For every pair in ../shared/records/pairs (both horizontals, trimmed to the shorter
one; and with the vertical where the station recorded one) it runs
:func:`isolator.solver.planar.simulate_pair` ``--repeat`` times on one core and
prints the median solver time (numba machine code already loaded), samples per
second, the number of DOP853 steps (and of them: rejected, in the START form after a
break-away, in the LOG form approaching a stop; plus the sub-steps that land on
instants and locate peaks), the events, the fraction of the record spent sliding and
the solver time per DOP853 step or sub-step.  docs/performance.md quotes its output.
"""

from __future__ import annotations

import argparse
import statistics
from pathlib import Path

import numpy as np

from isolator.motion import read_ground_motion
from isolator.solver.planar import simulate_pair

PAIRS = Path(__file__).resolve().parents[2] / "shared" / "records" / "pairs"

#: folder → ((file, component) for x, y and optionally z)
SOURCES = {
    "superstitionhills1987_PTS": (("RSN723_SUPER.B_B-PTS225.AT2", None), ("RSN723_SUPER.B_B-PTS315.AT2", None)),
    "landers1992_YER": (("RSN900_LANDERS_YER270.AT2", None), ("RSN900_LANDERS_YER360.AT2", None)),
    "hectormine1999_ABY": (("RSN1762_HECTOR_ABY090.AT2", None), ("RSN1762_HECTOR_ABY360.AT2", None)),
    "duzce1999_DZC": (("RSN1605_DUZCE_DZC180.AT2", None), ("RSN1605_DUZCE_DZC270.AT2", None)),
    "chichi1999_CHY028": (("RSN1197_CHICHI_CHY028-E.AT2", None), ("RSN1197_CHICHI_CHY028-N.AT2", None)),
    "chuetsuoki2007_65025": (("RSN4856_CHUETSU_65025EW.AT2", None), ("RSN4856_CHUETSU_65025NS.AT2", None)),
    "darfield2010_GDLC": (("RSN6906_DARFIELD_GDLCN55W.AT2", None), ("RSN6906_DARFIELD_GDLCS35W.AT2", None)),
    "christchurch2011_CBGS": (("RSN8063_CCHURCH_CBGSN89W.AT2", None), ("RSN8063_CCHURCH_CBGSS01W.AT2", None)),
    "lomaprieta1989_APEEL2": (("np01002p_4225a_a.smc", None), ("np01002p_4225c_a.smc", None),
                              ("np01002p_4225b_a.smc", None)),
    "lahabra2014_WLT": (("CIWLT.V2", "90"), ("CIWLT.V2", "360"), ("CIWLT.V2", "Up")),
    "iwatemiyagi2008_AOM017": (("AOM0170806140843.EW", None), ("AOM0170806140843.NS", None),
                               ("AOM0170806140843.UD", None)),
    "ncalifornia2012_89146": (("CE89146.V2", "90"), ("CE89146.V2", "360"), ("CE89146.V2", "Up")),
}


def load(folder: str):
    """(dt, ax, ay, az or None) of one pair, trimmed to the shortest component."""
    motions = [read_ground_motion(PAIRS / folder / name, component=comp) for name, comp in SOURCES[folder]]
    n = min(m.npts for m in motions)
    accs = [m.acceleration_m_s2[:n] for m in motions]
    return motions[0].dt_s, accs[0], accs[1], (accs[2] if len(accs) > 2 else None)


def measure(dt, ax, ay, az, repeat, **system):
    times = []
    result = None
    for _ in range(repeat):
        result = simulate_pair(ax, ay, dt, az_m_s2=az, **system)
        times.append(result.solver_seconds)
    return statistics.median(times), result


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--mu", type=float, default=0.06)
    parser.add_argument("--radius", type=float, default=2.0)
    parser.add_argument("--rtol", type=float, default=None, help="tolerance of the steps (default: the engine's)")
    args = parser.parse_args(argv)
    if not PAIRS.is_dir():
        raise SystemExit(f"pairs not found at {PAIRS}")
    system = dict(mu_static=args.mu, radius_m=args.radius)
    if args.rtol is not None:
        system["rtol"] = args.rtol
    print(f"friction pendulum R = {args.radius} m, µ = {args.mu}; median of {args.repeat} runs, one core")
    print(f"{'pair':28s} {'vert':>4s} {'samples':>8s} {'ms':>8s} {'Msamples/s':>10s} {'steps':>7s} "
          f"{'rej':>5s} {'start':>5s} {'log':>5s} {'sub':>5s} {'events':>6s} {'sliding':>7s} {'us/step':>7s} "
          f"{'peak mm':>8s}")
    total_n = 0
    total_t = 0.0
    for folder in SOURCES:
        dt, ax, ay, az = load(folder)
        variants = [(None, "-")] + ([(az, "z")] if az is not None else [])
        for vert, label in variants:
            seconds, r = measure(dt, ax, ay, vert, args.repeat, **system)
            total_n += ax.size
            total_t += seconds
            sliding = r.slip_time_s / (r.time_s[-1] - r.time_s[0])
            w = r.work
            sub = w["land_substeps"] + w["peak_substeps"]
            per_step = 1e6 * seconds / (r.n_steps + sub) if r.n_steps + sub else float("nan")
            print(f"{folder:28s} {label:>4s} {ax.size:8d} {1e3 * seconds:8.2f} {ax.size / seconds / 1e6:10.3f} "
                  f"{r.n_steps:7d} {w['rejected']:5d} {w['start']:5d} {w['log']:5d} {sub:5d} {r.n_events:6d} "
                  f"{sliding:7.1%} {per_step:7.2f} {1e3 * r.peak_displacement_m:8.2f}")
    print(f"{'all':28s} {'':>4s} {total_n:8d} {1e3 * total_t:8.2f} {total_n / total_t / 1e6:10.3f}")


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
