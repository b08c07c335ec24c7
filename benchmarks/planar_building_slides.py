"""Where the 2-D building's slides spend their steps: every series piece and fast sub-step, per departure and per stop.

Runs the bench's 2-D building (:mod:`isolator.bench.building`: 5 floors, PTS, µ = 0.06; the first ``--seconds``)
through a copy of the kernel with a record line inserted at each fast sub-step taken or refused, each series piece
and each event, executed as plain Python (``NUMBA_DISABLE_JIT``: ~25 s for 20 s of the pair; the installed kernel is
not touched; a marker line not found stops the script with its text)::

    .venv/bin/python -m benchmarks.planar_building_slides [--records ../shared/records] [--seconds 20]
        [--mu-static 0.06 --mu-kinetic 0.06] [--per-slide]

A slide runs from a break-away or a reversal to the next stop (stick or reversal); each step is charged to the slide's
departure (nearer its start) or to its approach (nearer its stop).  Printed per half: the departure series' pieces
(``DEPART``), ``START``, ``SLIDE`` pieces by why they ended (the speed's halving or the stop's reach, the stop itself
(``STOP_PIECE``), the series' reach, the end of a sub-step or sample), ``FINISH``, the fast sub-steps over a whole sample's sub-step (h) and on the
ladder's shorter rungs (h/2 … h/32), and the sub-steps refused (1: the friction's series not at rounding on any rung;
3: an event possible).  ``--per-slide`` prints every slide's line, with |D|/(µk N) at its start and at its stop.
Counts only: the time of each kind is what ``benchmarks.planar_building_throughput --substeps`` measures.
"""

from __future__ import annotations

import argparse
import math
import os
import tempfile
from collections import Counter
from pathlib import Path

import numpy as np

#: (marker line of the kernel, the record line inserted after or before it at the marker's indentation)
_RECORDS = (
    ("n_refused[refused] += 1", "after", "TRACE.append(('refused', t_i + tau, refused, mode))"),
    ("n_fast_steps += 1", "after", "TRACE.append(('fast', t_i + tau, h_lev / h_fast, mode))"),
    ("# ---- values at both ends, energies, peaks ----", "before",
     "TRACE.append(('piece', t_i + tau, mode, departing and not on_log, piece, length, rem, kind_phi, t_event))"),
    ("if n_ev < ev_time.shape[0]:", "before", "TRACE.append(('event', t_i + tau, kind, hold / max(mu_k_n, 1e-300)))"),
)
_PHASES = {0: "STUCK", 1: "START", 2: "SLIDE", 3: "FINISH", 4: "APPROACH"}


def _traced_kernel(folder: Path):
    """The kernel's module with the record lines of :data:`_RECORDS` (its ``TRACE`` list), run as plain Python."""
    import types

    import isolator.solver.planar_building_kernel as kernel

    source = Path(kernel.__file__).read_text()
    for marker, where, line in _RECORDS:
        if source.count(marker) != 1:
            raise SystemExit(f"the kernel's line {marker!r} was found {source.count(marker)} times")
        at = source.index(marker)
        start = source.rfind("\n", 0, at) + 1
        indent = source[start:at]
        if where == "after":
            end = source.index("\n", at) + 1
            source = source[:end] + indent + line + "\n" + source[end:]
        else:
            source = source[:start] + indent + line + "\n" + source[start:]
    path = folder / "planar_building_kernel_traced.py"
    path.write_text(source)
    module = types.ModuleType("planar_building_kernel_traced")
    module.__file__ = str(path)
    module.TRACE = []
    exec(compile(source, str(path), "exec"), module.__dict__)
    return module


def _piece_kind(item) -> str:
    """A piece's label: its phase and why it ended."""
    _, _, mode, departing, piece, length, rem, kind_phi, t_event = item
    if departing:
        return "DEPART"
    name = _PHASES.get(int(mode), str(mode))
    if mode != 2:
        return name
    if t_event >= 0.0:
        return "SLIDE to the stop" if kind_phi == 4 else "SLIDE halving/reach"
    return "SLIDE sub-step end" if length >= rem else "SLIDE series reach"


def slides(trace) -> list[dict]:
    """The slides of a trace: from a break-away (0) or a reversal (2) to the next event, each step charged to the
    departure half or the approach half."""
    out = []
    current = None
    for item in trace:
        if item[0] == "event":
            if current is not None:
                current["stop"] = item
                out.append(current)
            current = {"start": item, "steps": []} if item[2] in (0, 2) else None
        elif current is not None:
            current["steps"].append(item)
    for s in out:
        t0, t1 = s["start"][1], s["stop"][1]
        s["departure"], s["approach"] = Counter(), Counter()
        for item in s["steps"]:
            half = s["departure"] if item[1] - t0 < t1 - item[1] else s["approach"]
            if item[0] == "fast":
                rung = round(-math.log2(item[2]))
                half["fast h" if rung == 0 else "rungs h/2..h/32"] += 1
            elif item[0] == "refused":
                half[f"refused ({item[2]})"] += 1
            else:
                half[_piece_kind(item)] += 1
    return out


def traced_run(records, seconds: float, mu_static=None, mu_kinetic=None):
    """(the response, its trace, µs, µk): the bench's 2-D building over the first ``seconds`` of its pair through
    the traced kernel (:func:`_traced_kernel`; NUMBA_DISABLE_JIT must be set before numba is imported), the
    warm-up run's records left out."""
    import isolator.solver.planar_building as planar_building
    from isolator.bench.building import BUILDING_PAIR, FIXED_BASE_PERIOD_Y_S, building_case
    from isolator.motion import read_ground_motion

    _, folder, fx, fy = BUILDING_PAIR
    mx, my = (read_ground_motion(Path(records) / folder / f) for f in (fx, fy))
    keep = round(seconds / mx.dt_s) + 1
    case = building_case("2-D building", mx.acceleration_m_s2[:keep], mx.dt_s,
                         acceleration_y_m_s2=my.acceleration_m_s2[:keep], period_y_s=FIXED_BASE_PERIOD_Y_S)
    mu_s = case.mu if mu_static is None else mu_static
    mu_k = mu_s if mu_kinetic is None else mu_kinetic
    installed = planar_building._pk.building2d_kernel
    with tempfile.TemporaryDirectory() as folder:
        traced = _traced_kernel(Path(folder))
        planar_building._pk.building2d_kernel = traced.building2d_kernel
        try:
            r = planar_building.simulate_planar_building(
                case.acceleration_m_s2, case.acceleration_y_m_s2, case.dt_s, superstructure=case.superstructure,
                total_mass_kg=case.total_mass_kg, stiffness_N_per_m=case.isolator_stiffness_N_per_m, mu_static=mu_s,
                mu_kinetic=mu_k, gravity_m_s2=case.gravity_m_s2)
        finally:
            planar_building._pk.building2d_kernel = installed
    # the warm-up run (planar_building._warm_up) is traced too: keep the last run's steps only
    trace = traced.TRACE
    restarts = [i for i in range(1, len(trace)) if trace[i][1] < trace[i - 1][1]]
    return r, (trace[restarts[-1]:] if restarts else trace), mu_s, mu_k


def traced_args(argv, description: str, per_slide: bool = False, bounds: bool = False) -> argparse.Namespace:
    """The traced runs' options (records, seconds, µs, µk[, per slide]) parsed, with NUMBA_DISABLE_JIT set (numba
    must not be imported before: the run stops with its reason)."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--records", default="../shared/records")
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--mu-static", type=float, default=None)
    parser.add_argument("--mu-kinetic", type=float, default=None)
    if per_slide:
        parser.add_argument("--per-slide", action="store_true")
    if bounds:
        parser.add_argument("--bounds", default=None, help="write the slides' sample bounds (JSON) to this file")
    args = parser.parse_args(argv)
    os.environ["NUMBA_DISABLE_JIT"] = "1"
    import numba

    if not numba.config.DISABLE_JIT:
        raise SystemExit("numba was imported before NUMBA_DISABLE_JIT was set: run this module on its own")
    return args


def main(argv=None) -> None:
    args = traced_args(argv, __doc__.splitlines()[0], per_slide=True)
    r, trace, mu_s, mu_k = traced_run(args.records, args.seconds, args.mu_static, args.mu_kinetic)
    print(f"PTS 0-{args.seconds:g} s, µs {mu_s:g}, µk {mu_k:g}: {r.n_events} events, {r.n_fast_steps} fast sub-steps, "
          f"{r.n_pieces} pieces {r.n_pieces_by_phase} (stuck, start, slide, finish, approach, departure)")
    found = slides(trace)
    totals = {"departure": Counter(), "approach": Counter()}
    for s in found:
        for half in totals:
            totals[half].update(s[half])
        if args.per_slide:
            print(f"  {s['start'][1]:8.4f} -> {s['stop'][1]:8.4f} s  |D|/µkN {s['start'][3]:.3f} -> "
                  f"{s['stop'][3]:.3f}  departure {dict(s['departure'])}  approach {dict(s['approach'])}")
    print(f"{len(found)} slides; departure half: total, median per slide | approach half: total, median per slide")
    for key in sorted(set(totals["departure"]) | set(totals["approach"])):
        row = [f"{totals[half][key]:6d} {float(np.median([s[half][key] for s in found])) if found else 0.0:6.1f}"
               for half in ("departure", "approach")]
        print(f"  {key:<22} {row[0]} | {row[1]}")


if __name__ == "__main__":
    main()
