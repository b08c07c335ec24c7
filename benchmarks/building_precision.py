"""Work–precision of the 2-D building (issue 22): CPU time and error as each accuracy parameter is loosened.

The bench's building (:mod:`isolator.bench.building`: 5 floors, FP R = 2.5 m, µ = 0.06) under real pairs, 0-20 s,
through the registry's ``2d-building`` model as the bench times it.  For each pair the independent reference
(:func:`isolator.bench.building.reference_building`, solve_ivp rtol 1e-12) runs once, OpenSees once (its error
against the reference, when openseespy is installed), then every setting is timed ``--rounds`` times, the
settings alternated within each round (process CPU time, medians).  Each row: CPU per call, the error against the
reference (the bench's ``error_max``: the worst of the slab, drift and floor-acceleration trajectories over the
reference's largest value), the difference from the default setting's answer (the same measure), and OpenSees'
error over ours.  Rerun::

    OPENBLAS_NUM_THREADS=1 .venv/bin/python -m benchmarks.building_precision [--records ../shared/records]
        [--pairs PTS,YER,DZC] [--rounds 5] [--settings default,fast_eps=1e-8,order=12,...]

The run-time parameters it varies (module constants read at each call): ``fast_eps`` =
``planar_building.FAST_TRUNC_EPS`` (the fast sub-steps' friction polynomial truncation, default 1e-12),
``order`` = ``planar_building_kernel.N_ORDER`` (the series pieces' Taylor order, default 18), ``theta`` =
``planar_building_kernel.THETA`` (the series pieces' longest ρ h, default 0.75), ``departure`` =
``planar_building.DEPARTURE_SERIES`` (0: departures by START and pieces), ``check`` = ``planar_building.FAST_CHECK``
(the fast sub-steps' end check, default 1e-12; run-time since h184: ``check=1e-8+fast_eps=1e-8`` is the bench's
second 2-D building row).  The kernel's compile-time ``TRUNC_EPS`` of the series pieces is not varied here: it needs
a fresh compilation (docs/building.md, h172, gives the scratch recipe and its numbers).  The last column is the
energy balance's error of each setting's last call over its input energy (the registry's result).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

from isolator.bench import building as bench_building
from isolator.solver import planar_building
from isolator.solver import planar_building_kernel as kernel

#: name -> (folder under pairs/, x file, y file): the bench's PTS pair and two more (README.md of the records)
PAIRS = {"PTS": ("superstitionhills1987_PTS", "RSN723_SUPER.B_B-PTS225.AT2", "RSN723_SUPER.B_B-PTS315.AT2"),
         "YER": ("landers1992_YER", "RSN900_LANDERS_YER270.AT2", "RSN900_LANDERS_YER360.AT2"),
         "DZC": ("duzce1999_DZC", "RSN1605_DUZCE_DZC180.AT2", "RSN1605_DUZCE_DZC270.AT2")}
DEFAULT_SETTINGS = ("default", "fast_eps=1e-10", "fast_eps=1e-8", "fast_eps=1e-6", "fast_eps=1e-4", "order=14",
                    "order=12", "order=10", "order=8", "theta=1.5", "departure=0")
_KNOBS = {"fast_eps": (planar_building, "FAST_TRUNC_EPS", float), "order": (kernel, "N_ORDER", int),
          "theta": (kernel, "THETA", float), "departure": (planar_building, "DEPARTURE_SERIES", lambda v: bool(int(v))),
          "check": (planar_building, "FAST_CHECK", float)}


def _refuse(message: str) -> None:
    """A user mistake: one line on stderr, exit 2."""
    print(f"building_precision: {message}", file=sys.stderr)
    raise SystemExit(2)


def parse_setting(text: str) -> dict:
    """``default`` or ``knob=value[,...]`` joined by ``+`` (e.g. ``order=12+fast_eps=1e-8``)."""
    if text == "default":
        return {}
    out = {}
    for part in text.split("+"):
        key, _, value = part.partition("=")
        if key not in _KNOBS or not value:
            _refuse(f"--settings: {part!r} is not one of {', '.join(_KNOBS)}=VALUE")
        try:
            out[key] = _KNOBS[key][2](value)
        except ValueError:
            _refuse(f"--settings: {part!r}: {value!r} is not a number")
    return out


def _apply(setting: dict, defaults: dict) -> None:
    for key, (module, name, _) in _KNOBS.items():
        setattr(module, name, setting.get(key, defaults[key]))


def pair_case(records: Path, name: str, seconds: float):
    folder, fx, fy = PAIRS[name]
    from isolator.motion import read_ground_motion

    mx, my = (read_ground_motion(records / "pairs" / folder / f) for f in (fx, fy))
    n = min(mx.acceleration_m_s2.size, my.acceleration_m_s2.size, round(seconds / mx.dt_s) + 1)
    return bench_building.building_case(f"{name} 0-{seconds:g} s", mx.acceleration_m_s2[:n], mx.dt_s,
                                        acceleration_y_m_s2=my.acceleration_m_s2[:n],
                                        period_y_s=bench_building.FIXED_BASE_PERIOD_Y_S)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--records", default="../shared/records")
    parser.add_argument("--pairs", default="PTS,YER,DZC")
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--settings", default=",".join(DEFAULT_SETTINGS))
    args = parser.parse_args(argv)
    names = args.pairs.split(",")
    for name in names:
        if name not in PAIRS:
            _refuse(f"--pairs: {name!r} is not one of {', '.join(PAIRS)}")
    for name in names:
        folder = Path(args.records) / "pairs" / PAIRS[name][0]
        if not folder.is_dir():
            _refuse(f"--records: {folder} is not a folder (the shared records' pairs/)")
    labels = args.settings.split(",")
    settings = {label: parse_setting(label) for label in labels}
    defaults = {key: getattr(module, attr) for key, (module, attr, _) in _KNOBS.items()}
    from isolator.bench.opensees import opensees_available

    with_opensees = opensees_available()[0]
    print("| pair | setting | CPU per call [ms] | ours vs the reference | vs the default | OpenSees vs the reference "
          "| OpenSees' error / ours | energy balance / input |")
    print("|---|---|---|---|---|---|---|---|")
    for name in names:
        case = pair_case(Path(args.records), name, args.seconds)
        for label in labels:  # compiled, tables cached; a value the model refuses stops here in one line
            _apply(settings[label], defaults)
            try:
                bench_building.ours_building(case)
            except ValueError as error:
                _refuse(f"--settings: {label}: {error}")
            finally:
                _apply({}, defaults)
        truth = bench_building.reference_building(case)
        os_error = (bench_building.building_errors(bench_building.opensees_building_solver(case), truth)["error_max"]
                    if with_opensees else float("nan"))
        cpu = {label: [] for label in labels}
        answers = {}
        try:
            for _ in range(max(1, args.rounds)):
                for label in labels:
                    _apply(settings[label], defaults)
                    start = time.process_time()
                    answers[label] = bench_building.ours_building(case)
                    cpu[label].append(time.process_time() - start)
        finally:
            _apply({}, defaults)
        base = answers.get("default")
        for label in labels:
            error = bench_building.building_errors(answers[label], truth)["error_max"]
            vs_default = ("—" if base is None else
                          f"{bench_building.building_errors(answers[label], base)['error_max']:.1e}")
            print(f"| {name} | {label} | {1e3 * float(np.median(cpu[label])):.2f} | {error:.2e} | {vs_default} | "
                  f"{os_error:.2g} | {os_error / max(error, 1e-300):.1e} | "
                  f"{answers[label].get('energy_balance', float('nan')):.1e} |", flush=True)
    print(f"load average (1, 5, 15 min): {os.getloadavg()}; {time.strftime('%H:%M UTC', time.gmtime())}")


if __name__ == "__main__":
    main()
