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
        [--mu-static 0.06 --mu-kinetic 0.06]
"""

from __future__ import annotations

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


def main(argv=None) -> None:
    from benchmarks.planar_building_slides import slides, traced_args, traced_run

    args = traced_args(argv, __doc__.splitlines()[0])
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


if __name__ == "__main__":
    main()
