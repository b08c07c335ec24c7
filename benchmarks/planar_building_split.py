"""The 2-D building's sliding steps split by kind: departure, cruise, approach (one bench call, counts).

Runs the bench's 2-D building (5 floors, PTS 0–``--seconds``, µ = 0.06 unless ``--mu-static``/``--mu-kinetic``)
through :mod:`benchmarks.planar_building_slides`' traced copy of the kernel (plain Python under
``NUMBA_DISABLE_JIT``, ~1 min; the installed kernel is untouched) and splits each slide (break-away or reversal to
the next stop) in three: the **departure** from the slide's start to its first fast sub-step over a whole sample's
sub-step h, the **approach** after its last such sub-step to the stop, the **cruise** between (a slide without a
whole sub-step is all departure).  Printed per kind: series pieces (the departure series, ``SLIDE``, the stop's
piece), fast sub-steps over a whole h, fast sub-steps on the ladder's shorter rungs h/2 … h/32, and sub-steps
refused (then series pieces).  The time of each kind: ``benchmarks.planar_building_throughput --substeps`` gives a
stuck and a sliding sub-step's µs and the pieces' share (docs/building.md, h121)::

    .venv/bin/python -m benchmarks.planar_building_split [--records ../shared/records] [--seconds 20]
        [--mu-static 0.06 --mu-kinetic 0.06] [--bounds FILE]

Then the departures one by one (:func:`departures`): the departure series' piece from rest and whether a sample's
end cut it (its length is the time left in the sample) or its own reach ended it, and the departure's steps; the
departures cut by a sample's end are compared with the median of those that were not (docs/building.md, h144: a
departure cut 0.1 ms after its break-away takes ~140 stiff series pieces).  ``--bounds FILE`` writes each slide's
sample bounds (:func:`bounds`) as JSON for ``benchmarks.planar_building_slide_cost --split FILE``, which times the
kinds by the kernel's clock.
"""

from __future__ import annotations

import math
import statistics
from collections import Counter

KINDS = ("departure", "cruise", "approach")


def split(slides: list[dict]) -> dict:
    """Counts per kind (:data:`KINDS`) over the slides of :func:`benchmarks.planar_building_slides.slides`."""
    totals = {kind: Counter() for kind in KINDS}
    for s in slides:
        steps = s["steps"]
        whole = [i for i, item in enumerate(steps) if item[0] == "fast" and abs(item[2] - 1.0) < 1e-9]
        first, last = (whole[0], whole[-1]) if whole else (len(steps), len(steps))
        for i, item in enumerate(steps):
            kind = "departure" if i < first else ("approach" if i > last else "cruise")
            if item[0] == "fast":
                totals[kind]["fast h" if abs(item[2] - 1.0) < 1e-9 else "rungs h/2..h/32"] += 1
            elif item[0] == "refused":
                totals[kind]["refused"] += 1
            else:
                totals[kind]["pieces"] += 1
    return totals


def departures(slides: list[dict]) -> list[dict]:
    """Each slide's departure (the steps before its first whole-h fast sub-step, as :func:`split`): its start [s], the
    departure series' piece length τ_s [s] (None when the slide has none), ``cut`` — that piece ended at the end of
    its sample (its length reached the time left there) rather than at its series' reach —, and the departure's
    series pieces, rungs and refused sub-steps."""
    out = []
    for s in slides:
        steps = s["steps"]
        whole = [i for i, item in enumerate(steps) if item[0] == "fast" and abs(item[2] - 1.0) < 1e-9]
        first = whole[0] if whole else len(steps)
        row = {"start": s["start"][1], "tau_s": None, "cut": False, "pieces": 0, "rungs": 0, "refused": 0}
        for item in steps[:first]:
            if item[0] == "fast":
                row["rungs"] += 1
            elif item[0] == "refused":
                row["refused"] += 1
            elif item[0] == "piece":
                row["pieces"] += 1
                _, _, _, departing, _, length, rem, _, _ = item
                if departing and row["tau_s"] is None:
                    row["tau_s"] = length
                    row["cut"] = length >= rem
        out.append(row)
    return out


def bounds(slides: list[dict], dt: float) -> list[list[int]]:
    """Per slide the sample indices [i0, i1, i2, i3]: the break-away's sample, the first whole-h fast sub-step's
    sample, the end of the last one's sample, the end of the stop's sample (i1 = i2 = i3 when the slide has no
    whole-h sub-step).  A whole-h sub-step fills one sample on the bench building (one sub-step per sample) and
    the trace records a sub-step at its start."""
    out = []
    for s in slides:
        i0 = math.floor(s["start"][1] / dt + 1e-9)
        i3 = math.ceil(s["stop"][1] / dt - 1e-9)
        whole = [item[1] for item in s["steps"] if item[0] == "fast" and abs(item[2] - 1.0) < 1e-9]
        if whole:
            i1, i2 = round(whole[0] / dt), round(whole[-1] / dt) + 1
        else:
            i1 = i2 = i3
        out.append([i0, i1, i2, i3])
    return out


def cut_excess(rows: list[dict]) -> dict:
    """The departures cut by a sample's end against the others: counts, the medians of series pieces and rungs of
    the uncut ones, and the cut ones' pieces and rungs beyond those medians (summed)."""
    cut = [r for r in rows if r["cut"]]
    uncut = [r for r in rows if not r["cut"]]

    def median(key):
        return statistics.median(r[key] for r in uncut) if uncut else 0.0

    med_pieces, med_rungs = median("pieces"), median("rungs")
    return {"cut": len(cut), "uncut": len(uncut), "median pieces": med_pieces, "median rungs": med_rungs,
            "excess pieces": sum(max(r["pieces"] - med_pieces, 0.0) for r in cut),
            "excess rungs": sum(max(r["rungs"] - med_rungs, 0.0) for r in cut)}


def main(argv=None) -> None:
    from benchmarks.planar_building_slides import slides, traced_args, traced_run

    args = traced_args(argv, __doc__.splitlines()[0], bounds=True)
    r, trace, mu_s, mu_k = traced_run(args.records, args.seconds, args.mu_static, args.mu_kinetic)
    found = slides(trace)
    print(f"PTS 0-{args.seconds:g} s, µs {mu_s:g}, µk {mu_k:g}: {r.n_events} events, {len(found)} slides, "
          f"{r.n_fast_steps} fast sub-steps, {r.n_pieces} pieces {r.n_pieces_by_phase} (stuck, start, slide, finish, "
          "approach, departure)")
    totals = split(found)
    keys = ("pieces", "fast h", "rungs h/2..h/32", "refused")
    print(f"  {'':10s} " + " ".join(f"{k:>16s}" for k in keys))
    for kind in KINDS:
        print(f"  {kind:10s} " + " ".join(f"{totals[kind][k]:16d}" for k in keys))
    rows = departures(found)
    print("departures: start [s], the departure series' piece τ_s [s] (cut: ended at its sample's end), pieces, "
          "rungs, refused")
    for row in rows:
        tau = "   (none)" if row["tau_s"] is None else f"{row['tau_s']:9.2e}"
        print(f"  {row['start']:9.4f} {tau} {'cut' if row['cut'] else '   '} {row['pieces']:5d} {row['rungs']:5d} "
              f"{row['refused']:4d}")
    e = cut_excess(rows)
    print(f"  {e['cut']} cut by a sample's end, {e['uncut']} not (median {e['median pieces']:g} pieces, "
          f"{e['median rungs']:g} rungs); the cut ones' excess over that median: {e['excess pieces']:g} pieces, "
          f"{e['excess rungs']:g} rungs")
    if args.bounds:
        import json
        from pathlib import Path

        dt = float(r.time_s[1] - r.time_s[0])
        Path(args.bounds).write_text(json.dumps({"dt_s": dt, "n_samples": int(r.time_s.size) - 1,
                                                 "bounds": bounds(found, dt)}))
        print(f"the slides' sample bounds written to {args.bounds}")


if __name__ == "__main__":
    main()
