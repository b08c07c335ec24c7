"""Where the 2-D multi-surface event kernel's time goes, per real pair: corner steps, one group, events, Python.

Runs :func:`isolator.solver.planar_multisurface.simulate_bearing_pair` (``method="events"``) on every pair of the
records folder for Fenz & Constantinou's triple pendulum (the bearing of
:mod:`benchmarks.planar_multisurface_throughput`) with an instrumented copy of the event kernel: the kernel's own
source (``isolator/solver/planar_multisurface_kernel.py``) with a cycle counter (LLVM's ``readcyclecounter``, the
time-stamp counter) read at a few fixed places of its record loop, written to a temporary folder and compiled
beside it.  The counts go to spare slots of the kernel's ``stats`` array.  Per pair it prints, per column, the least
(``--stat min``, the default: the run least disturbed by other processes) or the median over ``--repeat`` runs of

* ``call``: the whole call's wall clock; ``kernel``: the compiled loop's (``solver_seconds``); their difference is
  the Python around it (checks, scales, the result's arrays);
* the kernel's time split (ms of the counter, calibrated against ``time.perf_counter``): ``dop`` the explicit
  (DOP853) corner steps of the main loop, ``radau`` its implicit (Radau IIA) corner steps, ``locate`` the joins
  and leaves found inside a corner step and located (the re-stepped secant, :func:`_locate_multi`, and the step
  re-taken to the event), ``peaks`` the peaks located inside corner steps, ``corner`` the rest of the corner
  phase (step control, the tangency crossing, sliding sets, the stiffness guard), ``one`` the one-group phases
  (the planar engine's forms, stops), ``stuck`` the stuck phases inside sample intervals, ``samples`` the sample
  intervals' set-up, the stuck intervals skipped whole and the samples' outputs;
* the step counts (``stats``: explicit and implicit corner steps, all steps), and the main loop's accepted corner
  steps by the corner's sine s (the smallest |sin| between two sliding normals, ``corner_angle``) in bands
  (BAND_EDGES): their count, mean length over the sample interval, and count per unit of ln s (a corner closing
  or opening at a steady rate ṡ has the time scale s/|ṡ|: steps of a fixed fraction of it are a fixed number per
  unit of ln s); and per band the time of its explicit and implicit corner steps (refused ones included), the record
  time the corner spent in the band and its accepted steps per sample interval, of them implicit (a corner that
  hovers in a band spends record time there at many steps per interval: docs/multisurface.md, h125, h135).

The counter is the wall clock: on a loaded machine a run's split carries the time it was descheduled, so take the
fractions from a quiet run (``call`` close to the call's CPU time); the least values of the columns need not come
from one run, so they need not add up.  The instrumented kernel computes what the kernel does (the same histories
to the bit on the 10 finishing pairs, checked 12:48 UTC 2026-11-27), at a few % more time: each counter read costs
~20 ns, and the corner's sine is evaluated once more per corner step for the bands.

    OPENBLAS_NUM_THREADS=1 python -m benchmarks.planar_multisurface_split [--repeat 3] [--records ../shared/records]
                                                                          [--only PTS,DZC]
"""

from __future__ import annotations

import argparse
import hashlib
import importlib
import math
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import benchmarks.planar_throughput as _records
from benchmarks.planar_throughput import SOURCES, load

#: the first spare slot of ``stats`` (the kernel uses ST_SIZE of them) and the buckets from it
SLOT = 32
N_BUCKETS = 9
#: the corner's sine s (corner_angle) in bands, from the tangency crossing (CROSS_ANGLE) to 1: the main loop's
#: accepted corner steps counted per band, with their summed length over the sample interval (in 1e-6)
BAND_EDGES = (1e-5, 1e-3, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0)
N_BANDS = len(BAND_EDGES) - 1
B_LOOP = 0  #: slots SLOT + 0 … 4: the record loop's phases (stuck, corner, one group, interval set-up, sample output)
B_DOP = 5
B_RADAU = 6
B_LOCATE = 7
B_PEAKS = 8

_COUNTER = '''
from numba.extending import intrinsic as _intrinsic
from numba.core import types as _types, cgutils as _cgutils
from llvmlite import ir as _ir


@_intrinsic
def _cycles(typingctx):
    def codegen(context, builder, signature, args):
        fn = _cgutils.get_or_insert_function(builder.module, _ir.FunctionType(_ir.IntType(64), []),
                                             "llvm.readcyclecounter")
        return builder.call(fn, [])
    return _types.int64(), codegen
'''

# (anchor in the kernel's source, text put before it, text put after it); each anchor must occur exactly once
PATCHES = (
    ("from isolator.solver.jit import njit\n", "", _COUNTER + f"\n_BAND_EDGES = np.array({BAND_EDGES})\n"),
    ("    for i in range(n - 1):\n", f"    _last = _cycles()\n    _bk = {B_LOOP + 3}\n",
     f"        _now = _cycles()\n        stats[{SLOT} + _bk] += _now - _last\n        _last = _now\n"
     f"        _bk = {B_LOOP + 3}\n"),
    ("        while tau < hi:\n", "",
     f"            _now = _cycles()\n            stats[{SLOT} + _bk] += _now - _last\n            _last = _now\n"
     "            _bk = 0 if phase == PH_STUCK else (1 if phase == PH_MULTI else 2)\n"),
    ("                ok, err = corner_step(tau, my, mf, h, raw, rb, mu, comp, c, mynew, mfnew, matol, rtol, kk, yt,"
     " stats, rm)\n",
     "                _t0 = _cycles()\n",
     "                _dc = _cycles() - _t0\n"
     f"                stats[{SLOT + B_DOP} + (1 if implicit else 0)] += _dc\n"
     "                _sa = corner_angle(my, rb, comp)\n"
     "                _bd = 0\n"
     "                while _bd < 6 and _sa >= _BAND_EDGES[_bd + 1]:\n"
     "                    _bd += 1\n"
     f"                stats[{SLOT + N_BUCKETS + 2 * N_BANDS} + (_bd + {N_BANDS} if implicit else _bd)] += _dc\n"
     f"                stats[{SLOT + N_BUCKETS + 4 * N_BANDS} + _bd] += 1 if implicit and ok and err <= 1.0 else 0\n"
     "                if ok and err <= 1.0:\n"
     f"                    stats[{SLOT + N_BUCKETS} + _bd] += 1\n"
     f"                    stats[{SLOT + N_BUCKETS + N_BANDS} + _bd] += int(1e6 * h / hi)\n"),
    ("                theta = 2.0\n                kind = -1\n                which = -1\n",
     "                _t1 = _cycles()\n", ""),
    ("                for wp in range(2):\n                    o = M_X if wp == 0 else M_V\n",
     f"                _t2 = _cycles()\n                stats[{SLOT + B_LOCATE}] += _t2 - _t1\n", ""),
    ("                tau = target if (kind < 0 and h == hmax) else tau + h\n",
     f"                stats[{SLOT + B_PEAKS}] += _cycles() - _t2\n", ""),
    ("        # ---- the sample\n", "",
     f"        _now = _cycles()\n        stats[{SLOT} + _bk] += _now - _last\n        _last = _now\n"
     f"        _bk = {B_LOOP + 4}\n"),
)


def instrumented_kernel():
    """The event kernel's module with the cycle counters patched in, compiled from a temporary folder."""
    from isolator.solver import planar_multisurface_kernel as pm

    source = Path(pm.__file__).read_text()
    for anchor, before, after in PATCHES:
        if source.count(anchor) != 1:
            raise SystemExit(f"the kernel's source changed: {anchor.strip()[:60]!r} is not found once; update "
                             f"benchmarks/planar_multisurface_split.py")
        source = source.replace(anchor, before + anchor + after)
    name = "pmk_split_" + hashlib.sha256(source.encode()).hexdigest()[:12]
    folder = Path(tempfile.gettempdir()) / "isolator_split"
    folder.mkdir(exist_ok=True)
    (folder / f"{name}.py").write_text(source)
    if str(folder) not in sys.path:
        sys.path.insert(0, str(folder))
    return importlib.import_module(name)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="runs per pair (median)")
    parser.add_argument("--records", help="the records folder (holding pairs/); default: ../shared/records")
    parser.add_argument("--only", help="comma-separated parts of the pairs' names")
    parser.add_argument("--stat", choices=("min", "median"), default="min",
                        help="per column over the runs: the least (the least disturbed by other processes on a "
                             "shared machine; default) or the median")
    args = parser.parse_args(argv)
    if args.records:
        _records.PAIRS = Path(args.records) / "pairs"

    from isolator.bearing import parse_bearing
    from isolator.errors import DesignError, SolverError
    from isolator.solver import planar_multisurface as drv
    from isolator.solver import planar_multisurface_kernel as pm

    split = instrumented_kernel()
    if SLOT < pm.ST_SIZE:
        raise SystemExit(f"the kernel's stats have {pm.ST_SIZE} slots: move SLOT past them")
    kernel, size, run = pm.planar_multisurface_kernel, pm.ST_SIZE, drv._run
    captured = {}

    def counting_run(*a):
        out = run(*a)
        captured["stats"] = out[-1].copy()
        return out

    clock = split.__dict__["_cycles"]
    from numba import njit

    read = njit(lambda: clock())
    read()
    t0, c0 = time.perf_counter(), read()
    time.sleep(0.2)
    hz = (read() - c0) / (time.perf_counter() - t0)

    tfp = parse_bearing({"type": "triple", "surface": [
        {"radius_m": r, "mu": m, "displacement_capacity_m": d}
        for r, m, d in ((2.1, 0.06, 0.4), (0.3, 0.02, 0.05), (0.3, 0.02, 0.05), (2.1, 0.10, 0.4))]}, DesignError)
    print(f"counter {hz / 1e9:.3f} GHz; ms, {'least' if args.stat == 'min' else 'median'} of {args.repeat} runs "
          f"per column")
    print(f"{'pair':22s} {'call':>6s} {'kernel':>6s} | {'dop':>5s} {'radau':>5s} {'locate':>6s} {'peaks':>5s} "
          f"{'corner':>6s} {'one':>5s} {'stuck':>5s} {'samples':>7s} | dop/step radau/step | steps (dop, radau)")
    pm.ST_SIZE = SLOT + N_BUCKETS + 5 * N_BANDS
    drv._run = counting_run
    pm.planar_multisurface_kernel = split.planar_multisurface_kernel
    try:
        dt, ax, ay, _ = load(next(iter(SOURCES)))
        drv.simulate_bearing_pair(ax[:200], ay[:200], dt, bearing=tfp, method="events")  # compiles the copy
        for folder in SOURCES:
            if args.only and not any(part in folder for part in args.only.split(",")):
                continue
            dt, ax, ay, _ = load(folder)
            rows = []
            band_ms = []
            try:
                for _ in range(args.repeat):
                    start = time.perf_counter()
                    res = drv.simulate_bearing_pair(ax, ay, dt, bearing=tfp, method="events")
                    call = time.perf_counter() - start
                    st = captured["stats"]
                    cyc = st[SLOT:SLOT + N_BUCKETS] / hz
                    # the loop's corner bucket holds the steps, events and peaks: its rest is the corner's own
                    rest = cyc[B_LOOP + 1] - cyc[B_DOP] - cyc[B_RADAU] - cyc[B_LOCATE] - cyc[B_PEAKS]
                    rows.append((call, res.solver_seconds, cyc[B_DOP], cyc[B_RADAU], cyc[B_LOCATE], cyc[B_PEAKS],
                                 rest, cyc[B_LOOP + 2], cyc[B_LOOP], cyc[B_LOOP + 3] + cyc[B_LOOP + 4]))
                    band_ms.append(st[SLOT + N_BUCKETS + 2 * N_BANDS:SLOT + N_BUCKETS + 4 * N_BANDS] / hz * 1e3)
            except SolverError as exc:
                print(f"{folder[:22]:22s} {str(exc)[:90]}")
                continue
            stat = np.min if args.stat == "min" else np.median
            m = stat(np.array(rows), axis=0) * 1e3
            bm = stat(np.array(band_ms), axis=0)
            n_dop, n_radau = int(st[pm.ST_DOP_MAIN]), int(st[pm.ST_RADAU_MAIN])
            per = (f"{1e3 * m[2] / n_dop:6.2f} µs" if n_dop else f"{'-':>9s}") + (
                f" {1e3 * m[3] / n_radau:8.2f} µs" if n_radau else f" {'-':>11s}")
            print(f"{folder[:22]:22s} {m[0]:6.2f} {m[1]:6.2f} | {m[2]:5.2f} {m[3]:5.2f} {m[4]:6.2f} {m[5]:5.2f} "
                  f"{m[6]:6.2f} {m[7]:5.2f} {m[8]:5.2f} {m[9]:7.2f} | {per} | {res.n_steps} ({n_dop}, {n_radau})")
            counts = st[SLOT + N_BUCKETS:SLOT + N_BUCKETS + N_BANDS]
            lengths = st[SLOT + N_BUCKETS + N_BANDS:SLOT + N_BUCKETS + 2 * N_BANDS] / 1e6
            if counts.sum():
                print(f"{'':22s} accepted corner steps by the corner's sine s: count, mean h/dt, count per unit ln s")
                print(f"{'':22s} " + "; ".join(
                    f"{BAND_EDGES[b]:g}–{BAND_EDGES[b + 1]:g}: {counts[b]}, {lengths[b] / max(counts[b], 1):.3f}, "
                    f"{counts[b] / math.log(BAND_EDGES[b + 1] / BAND_EDGES[b]):.0f}" for b in range(N_BANDS)))
                implicit = st[SLOT + N_BUCKETS + 4 * N_BANDS:SLOT + N_BUCKETS + 5 * N_BANDS]
                print(f"{'':22s} by band: ms of explicit + implicit corner steps (refused ones included), record "
                      f"seconds in the band, accepted steps per sample interval (of them implicit)")
                print(f"{'':22s} " + "; ".join(
                    f"{BAND_EDGES[b]:g}–{BAND_EDGES[b + 1]:g}: {bm[b]:.2f} + {bm[N_BANDS + b]:.2f} ms, "
                    f"{lengths[b] * dt:.2f} s, {counts[b] / max(lengths[b], 1e-9):.1f} ({implicit[b]})"
                    for b in range(N_BANDS)))
            sys.stdout.flush()
    finally:
        pm.ST_SIZE, drv._run, pm.planar_multisurface_kernel = size, run, kernel
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
