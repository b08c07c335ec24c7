"""The triple friction pendulum cases of the bench (issue 23): ours against OpenSees' element.

The bearing of Fenz & Constantinou's example (issue 23): R_eff = 2.1/0.3/0.3/2.1 m,
µ = 0.06/0.02/0.02/0.10, d* = 0.4/0.05/0.05/0.4 m (h = 0), under a rigid mass, one
horizontal component of Northridge NWH360 (first 20 s; quick: 10 s), ×1 (regimes I–III)
and ×2 (regimes I–V, below the ultimate 0.9 m).

``exact multisurface (ours)``
    :func:`isolator.solver.multisurface.simulate_bearing` (model ``1d-multisurface``).
``OpenSees TripleFrictionPendulum, Newmark + Newton``
    :func:`isolator.bench.opensees_tfp.opensees_tfp` at the record's dt; **its error is
    measured against ours**.

**Our error** is measured against an independent reference when one is given to
:func:`run_tfp_case` (``benchmarks/tfp_opensees.py`` passes the tests' event-driven
``SeriesReference``, tests/solver/test_multisurface.py); the package carries none, so
``isolator bench`` reports OpenSees' error against ours and leaves ours blank.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from isolator.units import STANDARD_GRAVITY as STANDARD_GRAVITY_M_S2

TFP_OURS = "exact multisurface (ours)"
TFP_OPENSEES = "OpenSees TripleFrictionPendulum, Newmark + Newton"
#: (R_eff [m], µ [-], d* [m]) of surfaces 1–4 (Fenz & Constantinou's example, issue 23)
TFP_SURFACES = ((2.1, 0.06, 0.4), (0.3, 0.02, 0.05), (0.3, 0.02, 0.05), (2.1, 0.10, 0.4))
TFP_RECORD = ("RSN1044_NORTHR_NWH360", "at2/RSN1044_NORTHR_NWH360.AT2")
TFP_SECONDS = {"full": 20.0, "quick": 10.0}
TFP_SCALES = {"full": (1.0, 2.0), "quick": (2.0,)}


def tfp_bearing():
    """The issue's triple bearing (:data:`TFP_SURFACES`, heights 0)."""
    from isolator.bearing import Bearing, Surface

    return Bearing("triple", tuple(Surface(r, 0.0, mu, mu, d) for r, mu, d in TFP_SURFACES))


@dataclass
class TfpCase:
    """A mass on a triple bearing under one horizontal component (SI units)."""

    name: str
    acceleration_m_s2: np.ndarray = field(repr=False)
    dt_s: float
    bearing: object = field(repr=False)
    gravity_m_s2: float = STANDARD_GRAVITY_M_S2


def tfp_cases(quick: bool, records_dir: Path) -> list[TfpCase]:
    """The TFP cases whose record is in ``records_dir``."""
    from isolator.motion import read_ground_motion

    label, rel = TFP_RECORD
    path = Path(records_dir) / rel
    if not path.is_file():
        return []
    motion = read_ground_motion(path)
    key = "quick" if quick else "full"
    acc = motion.acceleration_m_s2[:round(TFP_SECONDS[key] / motion.dt_s) + 1]
    return [TfpCase(f"TFP {label} x{scale:g} 0-{TFP_SECONDS[key]:g} s", scale * acc, motion.dt_s, tfp_bearing())
            for scale in TFP_SCALES[key]]


def ours_tfp(case: TfpCase, setting=None):
    """Ours: the exact 1-D multisurface solver (its response)."""
    from isolator.solver.multisurface import simulate_bearing

    return simulate_bearing(case.acceleration_m_s2, case.dt_s, bearing=case.bearing, gravity_m_s2=case.gravity_m_s2)


def opensees_tfp_solver(case: TfpCase, setting=1) -> np.ndarray:
    """OpenSees' element at ``setting`` steps per sample (displacements at the samples)."""
    from isolator.bench.opensees_tfp import opensees_tfp

    return opensees_tfp(case.dt_s, case.acceleration_m_s2, bearing=case.bearing, gravity_m_s2=case.gravity_m_s2,
                        substeps=int(setting or 1))


def trajectory_errors(x, truth) -> dict:
    """Trajectory error (max |x − x_ref| / max |x_ref|) and sampled-peak error (relative)."""
    x, truth = np.asarray(x, dtype=float), np.asarray(truth, dtype=float)
    scale = max(float(np.max(np.abs(truth))), 1e-300)
    return {"error_trajectory": float(np.max(np.abs(x - truth))) / scale,
            "error_peak": abs(float(np.max(np.abs(x))) - float(np.max(np.abs(truth)))) / scale}


def run_tfp_case(case: TfpCase, rounds: int = 3, ours_per_round: int = 5, reference=None, progress=None) -> dict:
    """Ours and OpenSees timed in alternation, OpenSees' error against ours, ours against ``reference``.

    Parameters
    ----------
    reference : callable, optional
        ``reference(case) -> displacement at the samples`` [m], independent of ours.

    Returns
    -------
    dict
        ``case``, ``regimes`` (ours), ``ours`` / ``opensees`` entries (seconds, runs, peaks,
        errors), ``time_ratio`` and ``error_ratio`` (None when not measured).
    """
    from isolator.bench.harness import time_against_opensees

    say = progress or (lambda line: None)
    ours_tfp(case)  # load the kernel before timing
    say(f"{case.name}: ours and OpenSees, {rounds} rounds in alternation")
    ours_s, ours_res, ours_runs, os_s, os_x, os_runs, why = time_against_opensees(
        ours_tfp, opensees_tfp_solver, case, rounds, ours_per_round)
    x = np.asarray(ours_res.displacement_m)
    ours = {"method": TFP_OURS, "seconds": ours_s, "runs": ours_runs, "peak_m": float(ours_res.peak_displacement_m),
            "sampled_peak_m": float(np.max(np.abs(x)))}
    if reference is not None:
        say(f"{case.name}: the independent reference")
        ours.update(trajectory_errors(x, reference(case)))
    result = {"case": case.name, "n_samples": int(x.size), "regimes": list(getattr(ours_res, "regimes", {}) or {}),
              "ours": ours}
    if os_x is None:
        result["opensees"] = {"method": TFP_OPENSEES, "seconds": None, "note": why}
        result["time_ratio"] = result["error_ratio"] = None
        return result
    result["opensees"] = {"method": TFP_OPENSEES, "setting": "dt/1", "seconds": os_s, "runs": os_runs,
                          "sampled_peak_m": float(np.max(np.abs(os_x))), **trajectory_errors(os_x, x)}
    result["time_ratio"] = os_s / ours_s
    result["error_ratio"] = (result["opensees"]["error_trajectory"] / max(ours["error_trajectory"], 1e-16)
                             if "error_trajectory" in ours else None)
    return result


def tfp_summary(results: list[dict]) -> list[str]:
    """One line per TFP case: ours against OpenSees, measured in this run."""
    lines = []
    for r in results:
        ours, os_ = r["ours"], r["opensees"]
        head = f"{r['case']} (regimes {'-'.join(r['regimes'])}): ours {ours['seconds'] * 1e3:.3g} ms (median of {ours['runs']})"
        if r["time_ratio"] is None:
            lines.append(f"{head}; vs OpenSees: not measured ({os_.get('note')})")
            continue
        ours_error = (f"ours {ours['error_trajectory']:.1e} vs the reference, {r['error_ratio']:.2g}× lower"
                      if r["error_ratio"] is not None else "ours not measured in this run (tests: ≤ 1e-9)")
        lines.append(f"{head}, {r['time_ratio']:.3g}× faster than OpenSees' TripleFrictionPendulum at the record's "
                     f"dt ({os_['seconds'] * 1e3:.3g} ms, median of {os_['runs']}, interleaved); trajectory error "
                     f"OpenSees {os_['error_trajectory']:.1e} vs ours (peak {os_['error_peak']:.1e}), {ours_error}")
    return lines
