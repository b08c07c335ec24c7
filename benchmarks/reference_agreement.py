"""Largest disagreement between the exact solver and the independent solve_ivp reference.

Every configuration (1, 2, 3, 4a, 4b and 4b ± 1e-12, 4c, vanishing k and η; friction
models 1 and 2) on a synthetic pulse record, and a friction pendulum on real records
from ../shared/records/at2 when present.  The reference is tests/reference.py
(DOP853, rtol 1e-12, event location, restarted at every sample).

    python -m benchmarks.reference_agreement      # from the repository root

(run as a module, so that the ``tests`` package is importable without editing sys.path)
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from isolator.solver.record import simulate_record
from isolator.units import STANDARD_GRAVITY as G
from tests.reference import reference_record
from tests.solver.test_record import SYSTEMS, synthetic_record

ROOT = Path(__file__).resolve().parents[1]
REAL = ["RSN1044_NORTHR_NWH360.AT2", "IELC180.AT2", "RSN779_LOMAP_LGP000.AT2"]


def compare(acc, dt, params):
    ours = simulate_record(acc, dt, **params)
    ref = reference_record(acc, dt, **params)
    scale = max(ours.peak_displacement_m, 1e-12)
    ref_times = np.array([t for t, _ in ref["events"]])
    same_events = ours.n_events == ref_times.size
    return {
        "dx_rel": float(np.max(np.abs(ours.displacement_m - ref["displacement_m"])) / scale),
        "dv_m_s": float(np.max(np.abs(ours.velocity_m_s - ref["velocity_m_s"]))),
        "dt_event_s": float(np.max(np.abs(ours.event_time_s - ref_times))) if same_events and ref_times.size else 0.0,
        "events": f"{ours.n_events}/{ref_times.size}",
    }


def main() -> None:
    rows = []
    acc, dt = synthetic_record()
    for name, params in SYSTEMS.items():
        rows.append((f"synthetic, config {name}", compare(acc, dt, params)))
    records = ROOT.parent / "shared" / "records" / "at2"
    if records.is_dir():
        from isolator.motion import read_ground_motion

        pendulum = dict(mu_static=0.06, mu_kinetic=0.042, stiffness_per_mass=G / 2.0,
                        damping_per_mass=2 * 0.1 * math.sqrt(G / 2.0))
        for name in REAL:
            motion = read_ground_motion(records / name)
            rows.append((f"{name}, R=2m µ=0.06/0.042 10% damper",
                         compare(motion.acceleration_m_s2, motion.dt_s, pendulum)))
    print(f"{'case':58s} {'max|ΔX|/peak':>13s} {'max|ΔV| m/s':>12s} {'max|Δt_event| s':>16s} {'events':>8s}")
    for name, r in rows:
        print(f"{name:58s} {r['dx_rel']:13.2e} {r['dv_m_s']:12.2e} {r['dt_event_s']:16.2e} {r['events']:>8s}")
    worst = max(rows, key=lambda row: row[1]["dx_rel"])
    print(f"\nlargest disagreement: {worst[1]['dx_rel']:.2e} of the peak displacement ({worst[0]})")


if __name__ == "__main__":
    main()
