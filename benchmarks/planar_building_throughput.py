"""Throughput of the 2-D building model (issue 22): solver time per pair for 1 to 6 stories.

Prints one row per case: stories, fixed-base period along x, events, fast sub-steps (exact
propagators), series pieces, located extrema, the kernel's wall time and the process's CPU time over
the call (best of 5 each; the propagators are built by the first call and reused) on one real pair
(Superstition Hills PTS by default). The CPU time is the figure to compare on a shared machine: the
wall time grows with the load. Rerun:

    .venv/bin/python benchmarks/planar_building_throughput.py [PAIR_FOLDER]

``--profile`` instead splits the kernel time of the bench's 2-D building (``isolator bench``, the OpenSees
comparison: 5 floors, PTS 0-20 s) into fast sub-steps and series pieces by phase (medians of ``--runs``)::

    OPENBLAS_NUM_THREADS=1 .venv/bin/python -m benchmarks.planar_building_throughput --profile [--runs 7]
        [--no-departure-series]

(``--no-departure-series``: the departures from rest by START and series in time, as before the departure
series; the same answer to 1e-10, docs/building.md.)

The split is a linear model, not an instrumented count: the same building with µ = 0.95 never slides and runs
fast sub-steps only (stuck), which gives a stuck sub-step's cost; the rest of the bench case's kernel time is
charged to its series pieces and sliding sub-steps (a sliding sub-step costs about twice a stuck one,
docs/building.md), so the per-piece figure printed is a range.

``--substeps`` times the fast sub-steps themselves, stuck and sliding, part by part, with a clock read inside an
instrumented copy of the kernel (written to a temporary folder and compiled there; the installed kernel is not
touched)::

    OPENBLAS_NUM_THREADS=1 .venv/bin/python -m benchmarks.planar_building_throughput --substeps [--runs 7]

It prints the kernel time split into stuck sub-steps, sliding sub-steps and the rest (series pieces, the sample loop),
µs per sub-step, the sliding sub-steps' rungs (h, h/2 … h/32) and, per sub-step, the friction's series, the
propagation with the event test, the watched values at the end, the peaks and the energy forms (the sub-step is
written into the kernel since h194: no calls to time). The clock (``clock_gettime``, ~25 ns a read, 9 reads a sub-step)
is included in the figures. The copy is made by
inserting lines at marker lines of the kernel's source; a marker not found stops the script with its text.

``--split`` times the whole call a user makes on the bench's 2-D building (the registry's ``2d-building`` model from a
Scene, as ``isolator bench`` and ``benchmarks.building_opensees --pair`` time "ours") and splits it into the Python
before ``_run``, ``_run`` before the kernel (tables from the per-system cache, work arrays), the kernel, ``_run`` after
it (result assembly) and the rest (the registry, the bench's drift histories); medians of ``--runs`` calls, wall
time (``perf_counter``)::

    OPENBLAS_NUM_THREADS=1 .venv/bin/python -m benchmarks.planar_building_throughput --split [--runs 21]

Timings depend on the machine and its load (the kernel runs on one core).
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np

from isolator.motion import read_ground_motion
from isolator.solver.planar_building import simulate_planar_building
from isolator.superstructure import Floor, Superstructure
from isolator.units import STANDARD_GRAVITY

DEFAULT_PAIR = Path(__file__).resolve().parents[2] / "shared" / "records" / "pairs" / "superstitionhills1987_PTS"


def main(folder: Path = DEFAULT_PAIR) -> None:
    motions = [read_ground_motion(f) for f in sorted(folder.glob("*.AT2"))[:2]]
    n_samples = min(m.npts for m in motions)
    ax, ay = (m.acceleration_m_s2[:n_samples] for m in motions)
    dt = motions[0].dt_s
    print(f"pair {folder.name}: {n_samples} samples × {dt:g} s; pendulum R = 2.5 m, µs = 0.06, µk = 0.05, "
          "k_y = 0.8 k_x")
    print(f"{'stories':>7} {'T1x [s]':>8} {'events':>6} {'fast':>6} {'pieces':>7} {'located':>7} {'wall [ms]':>9} "
          f"{'cpu [ms]':>8}")
    for n, stiffness_scale in ((1, 1.0), (3, 1.0), (5, 1.0), (6, 1.0), (5, 30.0)):
        floors = tuple(Floor(2.5e5, 3.5, stiffness_scale * k, 0.8 * stiffness_scale * k)
                       for k in np.linspace(9e8, 4e8, n))
        s = Superstructure(floors=floors, damping_ratio=0.05, gravity_m_s2=STANDARD_GRAVITY)
        total = 1.4 * s.mass_kg
        wall = cpu = np.inf
        for _ in range(5):
            start = time.process_time()
            r = simulate_planar_building(ax, ay, dt, superstructure=s, total_mass_kg=total,
                                         stiffness_N_per_m=total * STANDARD_GRAVITY / 2.5, mu_static=0.06,
                                         mu_kinetic=0.05)
            cpu = min(cpu, time.process_time() - start)
            wall = min(wall, r.solver_seconds)
        print(f"{n:>7} {s.fixed_base_periods_s()[0]:>8.3f} {r.n_events:>6} {r.n_fast_steps:>6} {r.n_pieces:>7} "
              f"{r.n_extrema_located:>7} {1e3 * wall:>9.1f} {1e3 * cpu:>8.1f}")


def _bench_case(records: Path):
    """The bench's 2-D building case (:mod:`isolator.bench.building`): PTS 0-20 s, 5 floors."""
    from isolator.bench.building import BUILDING_PAIR, FIXED_BASE_PERIOD_Y_S, building_case

    _, folder, fx, fy = BUILDING_PAIR
    mx, my = (read_ground_motion(records / folder / f) for f in (fx, fy))
    keep = round(20.0 / mx.dt_s) + 1
    return building_case("2-D building PTS 0-20 s", mx.acceleration_m_s2[:keep], mx.dt_s,
                         acceleration_y_m_s2=my.acceleration_m_s2[:keep], period_y_s=FIXED_BASE_PERIOD_Y_S)


def _kernel_runs(case, mu: float, runs: int):
    """Median kernel wall time [s] and the last response of ``runs`` calls (the first call builds the tables)."""
    kernel = []
    for _ in range(runs + 1):
        r = simulate_planar_building(case.acceleration_m_s2, case.acceleration_y_m_s2, case.dt_s,
                                     superstructure=case.superstructure, total_mass_kg=case.total_mass_kg,
                                     stiffness_N_per_m=case.isolator_stiffness_N_per_m, mu_static=mu, mu_kinetic=mu,
                                     gravity_m_s2=case.gravity_m_s2)
        kernel.append(r.solver_seconds)
    return float(np.median(kernel[1:])), r


def profile(records: Path, runs: int) -> None:
    """Where the bench case's kernel time goes (module docstring)."""
    case = _bench_case(records)
    t_case, r = _kernel_runs(case, case.mu, runs)
    t_stuck, r_stuck = _kernel_runs(case, 0.95, runs)
    per_stuck = t_stuck / max(r_stuck.n_fast_steps, 1)
    stuck, start, slide, finish, approach, depart = r.n_pieces_by_phase
    stops = int(np.count_nonzero(r.event_kind == 1)) + int(np.count_nonzero(r.event_kind == 2))
    print(f"{case.name}: {case.acceleration_m_s2.size} samples, µ = {case.mu}, {r.n_events} events, "
          f"peak {r.peak_displacement_m:.6f} m")
    print(f"kernel {1e3 * t_case:.1f} ms (median of {runs}); {r.n_fast_steps} fast sub-steps, {r.n_pieces} series "
          f"pieces (stuck {stuck}, leaving rest by the departure series {depart}, by START {start}, sliding "
          f"{slide}, finishing a stop {finish}, in ln s {approach}; "
          f"{(depart + start + slide + finish + approach) / max(stops, 1):.1f} pieces per slide, departure to stop, "
          f"over {stops} stops); fast "
          f"sub-steps refused {r.n_fast_refused} (series not at rounding, end check, event, V = 0); extrema "
          f"located {r.n_extrema_located}")
    print(f"never sliding (µ = 0.95): kernel {1e3 * t_stuck:.1f} ms for {r_stuck.n_fast_steps} stuck sub-steps = "
          f"{1e6 * per_stuck:.1f} µs each")
    for factor, label in ((1.0, "stuck"), (2.0, "sliding")):
        fast = factor * per_stuck * r.n_fast_steps
        piece = (t_case - fast) / max(r.n_pieces, 1)
        print(f"  sub-steps at the {label} cost: {1e3 * fast:.1f} ms; series pieces {1e3 * (t_case - fast):.1f} ms "
              f"({100 * (t_case - fast) / t_case:.0f} %), {1e6 * piece:.1f} µs per piece")
    print(f"load average (1, 5, 15 min): {os.getloadavg()}")


#: the instrumented copy's clock (CLOCK_MONOTONIC through ctypes, callable from numba) and its njit without a cache
_CLOCK = '''from numba import njit as _numba_njit
import ctypes as _ctypes
_clock_gettime = _ctypes.CDLL(None).clock_gettime
_clock_gettime.argtypes = [_ctypes.c_int, _ctypes.c_void_p]
_clock_gettime.restype = _ctypes.c_int


def njit(*args, **kwargs):
    kwargs.pop("cache", None)
    return _numba_njit(args[0]) if args and callable(args[0]) else _numba_njit(*args, **kwargs)


@_numba_njit
def _now(buf):
    _clock_gettime(1, buf.ctypes.data)
    return buf[0] * 1e9 + buf[1]
'''
#: (marker line of the kernel, lines to insert, before or after it, in which function): the clock reads. Slots of the
#: enlarged summary: 20 + (stuck 0 / sliding 2) + (taken 0 / refused 1) the sub-steps' time, 10 more their count,
#: 24 + rung the sliding rungs taken, 40 + 5 phase + part the parts, 59 the kernel's whole time
_PROBES = (
    ("from isolator.solver.jit import njit", [_CLOCK], "replace", None),
    ("SUMMARY_SIZE = 20", ["SUMMARY_SIZE = 60"], "replace", None),
    ("    counter = np.zeros(1, dtype=np.int64)", ["    counter = np.zeros(16, dtype=np.int64)"], "replace", None),
    ("    n = ax.shape[0]", ["    tbuf = np.zeros(2, dtype=np.int64)", "    t_start = _now(tbuf)"], "after",
     "building2d_kernel"),
    ("                        taken = -1000", ["                        mode_was = mode", "                        t_a = _now(tbuf)"], "before", "building2d_kernel"),
    ("                        taken = -1000", ["                        _t0 = _now(counter[14:])", "                        _pb = 1 if mode != STUCK else 0"], "after",
     "building2d_kernel"),
    ("                        if taken >= 0:", [
        "                        slot = 20 + (0 if mode_was == STUCK else 2) + (0 if taken >= 0 else 1)",
        "                        summary[slot] += _now(tbuf) - t_a",
        "                        summary[slot + 10] += 1",
        "                        if taken >= 0 and mode_was != STUCK:",
        "                            summary[24 + taken] += 1"], "before", "building2d_kernel"),
    ("    summary[S_N_LOCATED] = counter[0]", [
        "    summary[59] = _now(tbuf) - t_start", "    summary[51] = counter[11]", "    summary[53] = counter[13]",
        "    for _q in range(1, 11):", "        summary[39 + _q] = counter[_q]"], "after", "building2d_kernel"),
    ("                            fx_code = 0", ["                            counter[1 + 5 * _pb] += _now(counter[14:]) - _t0"], "before",
     "building2d_kernel"),
    ("                                fx_fpvis_l = fpvis[fx_lev]", ["                                _t0 = _now(counter[14:])"], "after", "building2d_kernel"),
    ("                                # ---- committed: watched values, peaks, energies ----",
     ["                                _t1 = _now(counter[14:])", "                                counter[2 + 5 * _pb] += _t1 - _t0"], "before", "building2d_kernel"),
    ("                                fx_nterm = fmon.shape[3]", ["                                _t2 = _now(counter[14:])", "                                counter[3 + 5 * _pb] += _t2 - _t1"],
     "before", "building2d_kernel"),
    ("                                fx_e_in = 0.0", ["                                _t3 = _now(counter[14:])", "                                counter[4 + 5 * _pb] += _t3 - _t2"], "before",
     "building2d_kernel"),
    ("                                energy[2] = fx_e_v", ["                                counter[5 + 5 * _pb] += _now(counter[14:]) - _t3"], "after",
     "building2d_kernel"),
)


def _instrumented(folder: Path):
    """The kernel's module with the clock reads of :data:`_PROBES`, imported from ``folder``."""
    import importlib.util

    import isolator.solver.planar_building_kernel as kernel

    lines = Path(kernel.__file__).read_text().split("\n")
    for marker, insert, where, function in _PROBES:
        current = None
        hits = []
        for i, line in enumerate(lines):
            if line.startswith("def "):
                current = line[4:line.index("(")]
            same = line == marker or (marker.endswith("(") and line.startswith(marker))
            if same and (function is None or current == function):
                hits.append(i)
        if len(hits) != 1:
            raise SystemExit(f"--substeps: the kernel's line {marker!r} (in {function}) was found {len(hits)} times")
        i = hits[0]
        if where == "replace":
            lines[i:i + 1] = insert
        elif where == "before":
            lines[i:i] = insert
        else:
            lines[i + 1:i + 1] = insert
    path = folder / "planar_building_kernel_timed.py"
    path.write_text("\n".join(lines))
    spec = importlib.util.spec_from_file_location("planar_building_kernel_timed", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def split(records: Path, runs: int) -> None:
    """Where the bench's whole 2-D building call goes (module docstring, ``--split``)."""
    import types

    import isolator.solver.planar_building as planar_building
    from isolator.bench.building import _ours_planar_building

    case = _bench_case(records)
    _ours_planar_building(case)  # compiles or loads the kernel, fills the per-system cache
    clock = time.perf_counter
    marks = {}
    installed = planar_building._pk
    run = planar_building._run

    def kernel(*args):
        marks["k0"] = clock()
        installed.building2d_kernel(*args)
        marks["k1"] = clock()

    def timed_run(*args, **kwargs):
        marks["r0"] = clock()
        out = run(*args, **kwargs)
        marks["r1"] = clock()
        return out

    proxy = types.SimpleNamespace(**{k: v for k, v in vars(installed).items() if not k.startswith("__")})
    proxy.building2d_kernel = kernel
    planar_building._pk, planar_building._run = proxy, timed_run
    rows = []
    try:
        for _ in range(runs):
            t0 = clock()
            _ours_planar_building(case)
            t1 = clock()
            rows.append([marks["r0"] - t0, marks["k0"] - marks["r0"], marks["k1"] - marks["k0"],
                         marks["r1"] - marks["k1"], t1 - marks["r1"], t1 - t0])
    finally:
        planar_building._pk, planar_building._run = installed, run
    med = 1e3 * np.median(np.array(rows), axis=0)
    print(f"{case.name}: the whole call {med[5]:.2f} ms (median of {runs}); before _run {med[0]:.3f}, _run before the "
          f"kernel {med[1]:.3f}, kernel {med[2]:.2f}, _run after the kernel {med[3]:.3f}, after _run {med[4]:.3f} ms; "
          f"outside the kernel {med[5] - med[2]:.2f} ms ({100 * (med[5] - med[2]) / med[5]:.0f} %)")
    print(f"load average (1, 5, 15 min): {os.getloadavg()}")


def substeps(records: Path, runs: int) -> None:
    """The fast sub-steps' time on the bench case and never sliding (module docstring, ``--substeps``)."""
    import tempfile
    import types

    import isolator.solver.planar_building as planar_building

    case = _bench_case(records)
    with tempfile.TemporaryDirectory() as folder:
        timed = _instrumented(Path(folder))
        captured = {}

        def kernel(*args):
            timed.building2d_kernel(*args)
            captured["summary"] = args[-1].copy()

        proxy = types.SimpleNamespace(**{k: v for k, v in vars(timed).items() if not k.startswith("__")})
        proxy.building2d_kernel = kernel
        installed = planar_building._pk
        planar_building._pk = proxy
        try:
            for mu in (case.mu, 0.95):
                rows = []
                for _ in range(runs + 1):  # the first call compiles the copy
                    simulate_planar_building(case.acceleration_m_s2, case.acceleration_y_m_s2, case.dt_s,
                                             superstructure=case.superstructure, total_mass_kg=case.total_mass_kg,
                                             stiffness_N_per_m=case.isolator_stiffness_N_per_m, mu_static=mu,
                                             mu_kinetic=mu, gravity_m_s2=case.gravity_m_s2)
                    rows.append(captured["summary"][20:60].copy())
                s = np.median(np.array(rows[1:]), axis=0)
                total = s[39]
                print(f"µ = {mu}: kernel {total / 1e6:.2f} ms (median of {runs}, instrumented)")
                for label, k in (("stuck sub-steps taken", 0), ("stuck refused", 1), ("sliding sub-steps taken", 2),
                                 ("sliding refused", 3)):
                    print(f"  {label}: {s[k + 10]:.0f}, {s[k] / 1e6:.2f} ms ({100 * s[k] / total:.0f} %), "
                          f"{s[k] / max(s[k + 10], 1) / 1e3:.2f} µs each")
                print(f"  sliding rungs taken (h, h/2 … h/32): {s[4:10].astype(int).tolist()}")
                for phase, label in ((0, "stuck"), (1, "sliding")):
                    count = max(s[10 + 2 * phase] + s[11 + 2 * phase], 1)
                    parts = (s[20 + 5 * phase:25 + 5 * phase] / count / 1e3).tolist()
                    print(f"  per {label} sub-step [µs]: friction's series {parts[0]:.2f}, propagation and event test "
                          f"{parts[1]:.2f}, watched values at the end {parts[2]:.2f}, peaks {parts[3]:.2f}, energy "
                          f"forms {parts[4]:.2f}")
                rest = total - s[0:4].sum()
                print(f"  the rest (series pieces, the sample loop): {rest / 1e6:.2f} ms ({100 * rest / total:.0f} %)")
        finally:
            planar_building._pk = installed
    print(f"load average (1, 5, 15 min): {os.getloadavg()}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("pair", nargs="?", type=Path, default=DEFAULT_PAIR)
    parser.add_argument("--profile", action="store_true", help="split the bench case's kernel time")
    parser.add_argument("--records", type=Path, default=DEFAULT_PAIR.parents[1])
    parser.add_argument("--substeps", action="store_true", help="time the fast sub-steps part by part")
    parser.add_argument("--split", action="store_true", help="split the whole call: Python around the kernel, kernel")
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--no-departure-series", action="store_true",
                        help="leave rest by START and series in time (planar_building.DEPARTURE_SERIES = False)")
    args = parser.parse_args()
    if args.no_departure_series:
        import isolator.solver.planar_building as planar_building

        planar_building.DEPARTURE_SERIES = False
    if args.split:
        split(args.records, args.runs)
    elif args.substeps:
        substeps(args.records, args.runs)
    elif args.profile:
        profile(args.records, args.runs)
    else:
        main(args.pair)
