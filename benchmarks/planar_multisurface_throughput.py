"""Throughput and accuracy of the 2-D multi-surface model (triple friction pendulum) on the real pairs.

Runs :func:`isolator.solver.planar_multisurface.simulate_bearing_pair` on every pair of
../shared/records/pairs (both horizontals, trimmed to the shorter) for Fenz & Constantinou's
triple pendulum (R_eff = 2.1/0.3/0.3/2.1 m, µ = 0.06/0.02/0.02/0.10, d* = 0.4/0.05/0.05/0.4 m),
each pair at its own amplitude times ``--scale``, and prints per pair the method that ran
("events": the event-driven kernel, exact between events; "steps": the implicit steps, which
``method="auto"`` runs where the events cannot be resolved), the samples per second of the
compiled code (solver time only, median of --repeat runs; for "steps" it includes the event-driven
attempt; "CPU M/s": the same from this thread's CPU time over the whole call, which a loaded machine inflates
less than the wall clock), the steps, the peak, the energy balance (|input − kinetic − stored − friction − viscous − impact| / input) and
the regimes; a pair that drives a slider to its rim is reported
as such (the rim in the plane is not modelled: the run stops there).

With ``--accuracy`` it also prints each answer's largest distance from two references, as a
fraction of the peak: the implicit steps at a 10× tighter tolerance (their convergence), and the
event-driven kernel where it finishes with its energy balance closed (an independent method).

With ``--vertical`` only the pairs with a vertical component run, with it (model
``2d-multisurface+vertical``: n = g + a_z on every surface), its amplitude times ``--scale`` too; with
``--vertical both`` each such pair runs without and with its vertical, alternately (the vertical's cost).

With ``--before FILE`` (a copy of an earlier event kernel, e.g. ``git show
<rev>:isolator/solver/planar_multisurface_kernel.py > /tmp/old/pmk_old.py``) each pair is also run
on that kernel, the two alternately in the same process (old, new, old, new, ...), and the line
gives both rates (median of --repeat each) and the largest distance between the two histories
as a fraction of the peak.

    python -m benchmarks.planar_multisurface_throughput [--repeat 5] [--scale 2] [--accuracy] [--rtol 1e-9]
                                                       [--records ../shared/records] [--before FILE]
                                                       [--vertical [with|both]]
"""

from __future__ import annotations

import argparse
import importlib
import statistics
import sys
import time
from pathlib import Path

import numpy as np

import benchmarks.planar_throughput as _records
from benchmarks.planar_throughput import SOURCES, load


def _kernel_copy(path):
    # an earlier event kernel's module, imported by name from its folder (numba caches its compiled code by module)
    folder, name = str(Path(path).resolve().parent), Path(path).stem
    if folder not in sys.path:
        sys.path.insert(0, folder)
    return importlib.import_module(name).planar_multisurface_kernel


def _distance(a, b, peak):
    ok = np.isfinite(a[:, 0]) & np.isfinite(b[:, 0])
    return float(np.max(np.hypot(*(a[ok] - b[ok]).T))) / peak


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs per pair (median)")
    parser.add_argument("--scale", type=float, default=1.0, help="factor on both components")
    parser.add_argument("--method", default="auto", choices=("auto", "events", "steps"))
    parser.add_argument("--rtol", type=float, default=None,
                        help="the event kernel's relative tolerance (default: its DEFAULT_RTOL; RTOL_RANGE)")
    parser.add_argument("--accuracy", action="store_true", help="distances from the two references")
    parser.add_argument("--records", help="the records folder (holding pairs/); default: ../shared/records of the "
                        "repository's parent")
    parser.add_argument("--before", help="a copy of an earlier event kernel's module, run alternately with this one")
    parser.add_argument("--vertical", nargs="?", const="with", choices=("with", "both"),
                        help="only the pairs with a vertical, with it ('both': without and with, alternately)")
    args = parser.parse_args(argv)
    if args.records:
        _records.PAIRS = Path(args.records) / "pairs"

    from isolator.bearing import parse_bearing
    from isolator.errors import DesignError, SolverError
    from isolator.solver import planar_multisurface_kernel as _pm
    from isolator.solver.planar_multisurface import (
        DEFAULT_RTOL,
        DEFAULT_STEP_TOL,
        EVENTS_BALANCE_TOL,
        simulate_bearing_pair,
    )

    rtol = DEFAULT_RTOL if args.rtol is None else args.rtol

    kernels = [("new", _pm.planar_multisurface_kernel)]
    if args.before:
        kernels.insert(0, ("before", _kernel_copy(args.before)))

    tfp = parse_bearing({"type": "triple", "surface": [
        {"radius_m": r, "mu": m, "displacement_capacity_m": d}
        for r, m, d in ((2.1, 0.06, 0.4), (0.3, 0.02, 0.05), (0.3, 0.02, 0.05), (2.1, 0.10, 0.4))]}, DesignError)
    print(f"scale {args.scale:g}, method {args.method}, rtol {rtol:g}, step tolerance {DEFAULT_STEP_TOL:g}")
    print(f"{'pair':26s} {'samples':>8s} {'method':>6s} {'M samples/s':>12s} {'CPU M/s':>8s} {'steps':>7s} {'peak x [m]':>10s} {'balance':>8s} "
          + (f"{'vs tol/10':>10s} {'vs events':>10s} " if args.accuracy else "") + " regimes")
    rates = []
    cpu_rates = []
    before_rates = []
    before_cpu = []
    total_n = 0
    total_t = 0.0
    for folder in SOURCES:
        dt, ax, ay, az = load(folder)
        if args.vertical and az is None:
            continue
        ax = args.scale * ax
        ay = args.scale * ay
        az = None if az is None or not args.vertical else args.scale * az
        # (name, event kernel, vertical): "before" runs the earlier kernel, "flat" this one without the vertical
        runs = [(name, kernel, az) for name, kernel in kernels]
        if args.vertical == "both":
            runs.insert(0, ("flat", kernels[-1][1], None))
        try:
            times = {name: [] for name, _, _ in runs}
            cpus = {name: [] for name, _, _ in runs}
            answers = {}
            for _ in range(args.repeat):
                for name, kernel, vert in runs:
                    _pm.planar_multisurface_kernel = kernel
                    start = time.thread_time()
                    answers[name] = simulate_bearing_pair(ax, ay, dt, bearing=tfp, method=args.method, az_m_s2=vert,
                                                          rtol=rtol)
                    cpus[name].append(time.thread_time() - start)
                    times[name].append(answers[name].solver_seconds)
        except SolverError as exc:
            print(f"{folder:26s} {ax.size:8d}   {str(exc)[:90]}")
            continue
        finally:
            _pm.planar_multisurface_kernel = kernels[-1][1]
        res = answers["new"]
        cpu = cpus["new"]
        if args.vertical == "both":
            flat = answers["flat"]
            print(f"{'  without the vertical':26s} {ax.size:8d} {'':>6s} "
                  f"{ax.size / statistics.median(times['flat']) / 1e6:12.3f} "
                  f"{ax.size / statistics.median(cpus['flat']) / 1e6:8.3f} {flat.n_steps:7d} "
                  f"{flat.peak_displacement_m:10.4f}  ({'steps' if 'implicit steps' in flat.model_reason else 'events'})")
        if args.before:
            old = answers["before"]
            before_rates.append(ax.size / statistics.median(times["before"]) / 1e6)
            before_cpu.append(ax.size / statistics.median(cpus["before"]) / 1e6)
            apart = _distance(old.displacement_m, res.displacement_m, res.peak_displacement_m)
            print(f"{'  before':26s} {ax.size:8d} {'':>6s} {before_rates[-1]:12.3f} {before_cpu[-1]:8.3f} "
                  f"{old.n_steps:7d} {old.peak_displacement_m:10.4f}  (history {apart:.1e} of the peak apart)")
        times = times["new"]
        t = statistics.median(times)
        rate = ax.size / t / 1e6
        rates.append(rate)
        cpu_rates.append(ax.size / statistics.median(cpu) / 1e6)
        total_n += ax.size
        total_t += t
        how = "steps" if "implicit steps" in res.model_reason else "events"
        extra = ""
        if args.accuracy:
            peak = res.peak_displacement_m
            fine = simulate_bearing_pair(ax, ay, dt, bearing=tfp, method="steps", step_tol=DEFAULT_STEP_TOL / 10,
                                         az_m_s2=az)
            extra = f"{_distance(res.displacement_m, fine.displacement_m, peak):10.1e} "
            try:
                ev = simulate_bearing_pair(ax, ay, dt, bearing=tfp, method="events", az_m_s2=az, rtol=rtol)
                closed = abs(ev.energy_balance_error_J_per_kg) <= EVENTS_BALANCE_TOL * ev.energy_input_J_per_kg
                extra += f"{_distance(res.displacement_m, ev.displacement_m, peak):10.1e} " if closed else (
                    f"{'(imbal.)':>10s} ")
            except SolverError:
                extra += f"{'(stops)':>10s} "
        print(f"{folder:26s} {ax.size:8d} {how:>6s} {rate:12.3f} {cpu_rates[-1]:8.3f} {res.n_steps:7d} {res.peak_displacement_m:10.4f} "
              f"{abs(res.energy_balance_error_J_per_kg) / res.energy_input_J_per_kg:8.1e} "
              f"{extra} {' '.join(res.regimes)}")
    if rates:
        print(f"median {statistics.median(rates):.3f} M samples/s, slowest {min(rates):.3f}, "
              f"all samples / all time {total_n / total_t / 1e6:.3f} M samples/s; CPU: median "
              f"{statistics.median(cpu_rates):.3f} M samples/s")
    if before_rates:
        print(f"before: median {statistics.median(before_rates):.3f} M samples/s; CPU: median "
              f"{statistics.median(before_cpu):.3f} M samples/s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
