r"""The building case of the bench (issue 22): ours against OpenSees on a 5-story building.

A 5-story shear building (5 floors of 500 t, story height 3.5 m, equal story stiffnesses
giving a fixed-base T1 = 0.5 s, ζ = 5 % in every fixed-base mode) on a 500 t base slab
(M = 3000 t) on a friction pendulum R = 2.5 m, µ = 0.06 (Coulomb, µs = µk), one horizontal
direction of a real record.

Three solutions of the same equations (docs/building.md), at the record's samples:

``exact 1-D building (ours)``
    :func:`isolator.solver.building.simulate_building` (model ``1d-building``): exact
    propagation between events located to rounding.
``independent reference (solve_ivp DOP853 + events, rtol 1e-12)``
    :func:`isolator.bench.building_reference.building_reference` (no code shared with ours):
    **our error** is our discrepancy with it.
``OpenSees singleFPBearing + zeroLength stories, Newmark + Newton``
    :func:`isolator.bench.opensees_building.opensees_building` at the record's dt:
    **its error** is measured against ours (ours is within ~1e-10 of the reference, so
    ours stands for the truth at OpenSees' level of error).

Errors, each relative to the reference solution's largest value over the samples:
``slab`` (x_b, the isolator's displacement), ``drift`` (u_i − u_{i−1}, all stories),
``floor_acc`` (absolute floor accelerations, all floors), and the relative error of the
sampled peaks (isolator displacement, each story drift, each floor acceleration: the worst).
Ours and OpenSees are timed in alternation (:func:`isolator.bench.harness.time_interleaved`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from isolator.units import STANDARD_GRAVITY as STANDARD_GRAVITY_M_S2

BUILDING_OURS = "exact 1-D building (ours)"
BUILDING_TRUTH = "independent reference (solve_ivp DOP853 + events, rtol 1e-12)"
BUILDING_OPENSEES = "OpenSees singleFPBearing + zeroLength stories, Newmark + Newton"

#: The bench's building: 5 floors of 500 t, 3.5 m stories, fixed-base T1 = 0.5 s, ζ = 5 %, slab 500 t.
N_FLOORS = 5
FLOOR_MASS_KG = 5.0e5
STORY_HEIGHT_M = 3.5
FIXED_BASE_PERIOD_S = 0.5
DAMPING_RATIO = 0.05
SLAB_MASS_KG = 5.0e5
RADIUS_M = 2.5
MU = 0.06
#: (label, file under --records, seconds kept) of the full and the quick run
BUILDING_RECORD = ("RSN1044_NORTHR_NWH360", "at2/RSN1044_NORTHR_NWH360.AT2")
BUILDING_SECONDS = {"full": 20.0, "quick": 8.0}


def uniform_story_stiffness(n_floors: int, floor_mass_kg: float, period_s: float) -> float:
    """k of a uniform shear building (n equal floors m, equal stories k) with fixed-base T1 [N/m].

    ω1 = 2 sqrt(k/m) sin(π / (2(2n + 1))) (the lowest eigenvalue of the uniform chain fixed
    at one end, free at the other).
    """
    omega = 2.0 * math.pi / period_s
    return floor_mass_kg * (omega / (2.0 * math.sin(math.pi / (2.0 * (2 * n_floors + 1))))) ** 2


@dataclass
class BuildingCase:
    """One building bench case: the building, its isolation and a record (SI units)."""

    name: str
    acceleration_m_s2: np.ndarray = field(repr=False)
    dt_s: float
    superstructure: object = field(repr=False)  #: :class:`isolator.superstructure.Superstructure`
    total_mass_kg: float
    radius_m: float
    mu: float
    gravity_m_s2: float = STANDARD_GRAVITY_M_S2

    @property
    def isolator_stiffness_N_per_m(self) -> float:
        """K = W/R = g M / R [N/m]."""
        return self.gravity_m_s2 * self.total_mass_kg / self.radius_m


def building_case(name: str, acceleration_m_s2, dt_s: float, *, n_floors: int = N_FLOORS,
                  floor_mass_kg: float = FLOOR_MASS_KG, story_height_m: float = STORY_HEIGHT_M,
                  period_s: float = FIXED_BASE_PERIOD_S, damping_ratio: float = DAMPING_RATIO,
                  slab_mass_kg: float = SLAB_MASS_KG, radius_m: float = RADIUS_M, mu: float = MU) -> BuildingCase:
    """A uniform shear building case (equal floors and stories, fixed-base T1 = ``period_s``)."""
    from isolator.superstructure import Floor, Superstructure

    k = uniform_story_stiffness(n_floors, floor_mass_kg, period_s)
    floors = tuple(Floor(floor_mass_kg, story_height_m, k, k) for _ in range(n_floors))
    structure = Superstructure(floors=floors, damping_ratio=damping_ratio, gravity_m_s2=STANDARD_GRAVITY_M_S2)
    return BuildingCase(name, np.ascontiguousarray(acceleration_m_s2, dtype=float), float(dt_s), structure,
                        n_floors * floor_mass_kg + slab_mass_kg, radius_m, mu)


def building_cases(quick: bool, records_dir: Path) -> list[BuildingCase]:
    """The building case when its record is in ``records_dir`` (first 8 s quick, 20 s full)."""
    from isolator.motion import read_ground_motion

    label, rel = BUILDING_RECORD
    path = Path(records_dir) / rel
    if not path.is_file():
        return []
    motion = read_ground_motion(path)
    seconds = BUILDING_SECONDS["quick" if quick else "full"]
    acc = motion.acceleration_m_s2[:round(seconds / motion.dt_s) + 1]
    return [building_case(f"building {label} 0-{seconds:g} s (5 stories, T1=0.5 s, FP R=2.5 m, mu=0.06)",
                          acc, motion.dt_s)]


def _histories(slab, floor_disp, floor_acc) -> dict:
    """The compared histories: slab displacement, story drifts, floor absolute accelerations."""
    floor_disp = np.asarray(floor_disp, dtype=float)
    drift = np.diff(np.concatenate([np.zeros((floor_disp.shape[0], 1)), floor_disp], axis=1), axis=1)
    return {"slab": np.asarray(slab, dtype=float), "drift": drift, "floor_acc": np.asarray(floor_acc, dtype=float)}


def ours_building(case: BuildingCase, setting=None) -> dict:
    """Ours: :func:`isolator.solver.building.simulate_building` (exact)."""
    from isolator.solver.building import simulate_building

    r = simulate_building(case.acceleration_m_s2, case.dt_s, superstructure=case.superstructure,
                          total_mass_kg=case.total_mass_kg, stiffness_N_per_m=case.isolator_stiffness_N_per_m,
                          mu_static=case.mu, mu_kinetic=case.mu, gravity_m_s2=case.gravity_m_s2)
    out = _histories(r.displacement_m, r.floor_displacement_m, r.floor_absolute_acceleration_m_s2)
    out["exact_peaks"] = {"slab": float(r.peak_displacement_m), "drift": np.asarray(r.story_drift_m),
                          "floor_acc": np.asarray(r.floor_peak_acceleration_m_s2)}
    return out


def reference_building(case: BuildingCase, setting=None) -> dict:
    """The independent reference (:mod:`isolator.bench.building_reference`)."""
    from isolator.bench.building_reference import building_reference

    s = case.superstructure
    r = building_reference(case.acceleration_m_s2, case.dt_s, masses_kg=s.masses_kg,
                           stiffness_matrix=s.stiffness_matrix(), damping_matrix=s.damping_matrix(),
                           total_mass_kg=case.total_mass_kg, isolator_stiffness_N_per_m=case.isolator_stiffness_N_per_m,
                           mu_static=case.mu, mu_kinetic=case.mu, gravity_m_s2=case.gravity_m_s2)
    return _histories(r["slab_displacement_m"], r["floor_displacement_m"], r["floor_absolute_acceleration_m_s2"])


def opensees_building_solver(case: BuildingCase, setting=1) -> dict:
    """OpenSees (:func:`isolator.bench.opensees_building.opensees_building`), ``setting`` substeps per dt."""
    from isolator.bench.opensees_building import opensees_building

    s = case.superstructure
    r = opensees_building(case.dt_s, case.acceleration_m_s2, masses_kg=s.masses_kg,
                          stiffnesses_N_per_m=s.story_stiffnesses(), damping_matrix=s.damping_matrix(),
                          total_mass_kg=case.total_mass_kg, radius_m=case.radius_m, mu=case.mu,
                          gravity_m_s2=case.gravity_m_s2, substeps=int(setting or 1))
    return _histories(r["slab_displacement_m"], r["floor_displacement_m"], r["floor_absolute_acceleration_m_s2"])


def sampled_peaks(histories: dict) -> dict:
    """Peaks over the samples: |x_b|, per story |drift|, per floor |a| (m, m, m/s²)."""
    return {"slab": float(np.max(np.abs(histories["slab"]))),
            "drift": np.max(np.abs(histories["drift"]), axis=0),
            "floor_acc": np.max(np.abs(histories["floor_acc"]), axis=0)}


def building_errors(histories: dict, truth: dict) -> dict:
    """Trajectory errors (max over samples / the truth's largest value) and the worst sampled-peak error."""
    out = {}
    peaks, true_peaks = sampled_peaks(histories), sampled_peaks(truth)
    for key in ("slab", "drift", "floor_acc"):
        scale = max(float(np.max(np.abs(truth[key]))), 1e-300)
        out[f"error_{key}"] = float(np.max(np.abs(histories[key] - truth[key]))) / scale
        out[f"error_peak_{key}"] = float(np.max(np.abs(np.atleast_1d(peaks[key]) - np.atleast_1d(true_peaks[key]))
                                                / np.maximum(np.atleast_1d(true_peaks[key]), 1e-300)))
    out["error_max"] = max(out["error_slab"], out["error_drift"], out["error_floor_acc"])
    return out


def run_building_case(case: BuildingCase, rounds: int = 3, ours_per_round: int = 5, progress=None) -> dict:
    """Ours, the reference and OpenSees on one case: times, peaks and errors.

    Ours and OpenSees (at the record's dt) are timed in alternation, ``rounds`` rounds of
    ``ours_per_round`` runs of ours then one of OpenSees (medians); the reference runs once.

    Returns
    -------
    dict
        ``case``, ``n_samples``, ``dt_s``, ``ours`` / ``reference`` / ``opensees`` entries
        (``seconds``, ``runs``, ``peaks``, errors) and ``time_ratio`` / ``error_ratio``
        (OpenSees over ours; None when OpenSees did not run), ``opensees_note``.
    """
    from isolator.bench.harness import time_against_opensees

    say = progress or (lambda line: None)
    ours_building(case)  # compile / load the kernel and cache the system before timing
    say(f"{case.name}: ours and OpenSees, {rounds} rounds in alternation")
    ours_s, ours_out, ours_runs, os_s, os_out, os_runs, why = time_against_opensees(
        ours_building, opensees_building_solver, case, rounds, ours_per_round)
    result = {"case": case.name, "n_samples": int(case.acceleration_m_s2.size), "dt_s": case.dt_s}
    say(f"{case.name}: the independent reference (solve_ivp, once)")
    start = time.perf_counter()
    truth = reference_building(case)
    ref_s = time.perf_counter() - start
    ours_errors = building_errors(ours_out, truth)
    result["ours"] = {"method": BUILDING_OURS, "seconds": ours_s, "runs": ours_runs,
                      "peaks": _listed(ours_out["exact_peaks"]), "sampled_peaks": _listed(sampled_peaks(ours_out)),
                      **ours_errors}
    result["reference"] = {"method": BUILDING_TRUTH, "seconds": ref_s, "runs": 1,
                           "sampled_peaks": _listed(sampled_peaks(truth))}
    if os_out is None:
        result["opensees"] = {"method": BUILDING_OPENSEES, "seconds": None, "note": why}
        result["time_ratio"] = result["error_ratio"] = None
        return result
    os_errors = building_errors(os_out, ours_out)
    os_vs_truth = building_errors(os_out, truth)
    result["opensees"] = {"method": BUILDING_OPENSEES, "setting": "dt/1", "seconds": os_s, "runs": os_runs,
                          "sampled_peaks": _listed(sampled_peaks(os_out)), **os_errors,
                          "error_max_vs_reference": os_vs_truth["error_max"]}
    result["time_ratio"] = os_s / ours_s
    result["error_ratio"] = os_errors["error_max"] / max(ours_errors["error_max"], 1e-16)
    return result


def _listed(peaks: dict) -> dict:
    return {key: (value.tolist() if isinstance(value, np.ndarray) else value) for key, value in peaks.items()}


def building_summary(results: list[dict]) -> list[str]:
    """One line per building case: ours against OpenSees, time and error ratios, measured in this run."""
    lines = []
    for r in results:
        ours, os_ = r["ours"], r["opensees"]
        if r["time_ratio"] is None:
            lines.append(f"{r['case']}: ours {ours['seconds'] * 1e3:.3g} ms, error {ours['error_max']:.1e} against "
                         f"the reference; vs OpenSees: not measured ({os_.get('note')})")
            continue
        lines.append(f"{r['case']}: ours {ours['seconds'] * 1e3:.3g} ms (median of {ours['runs']}), "
                     f"{r['time_ratio']:.3g}× faster than OpenSees at the record's dt ({os_['seconds'] * 1e3:.3g} ms, "
                     f"median of {os_['runs']}, interleaved); largest error (isolator displacement, drifts, floor "
                     f"accelerations) ours {ours['error_max']:.1e} vs the reference, OpenSees {os_['error_max']:.1e} "
                     f"vs ours: {r['error_ratio']:.2g}× lower")
    return lines


def building_markdown(results: list[dict]) -> str:
    """The building cases as a Markdown table: time, errors, peaks from each method."""
    head = ("| case | method | time [ms] | slab traj. | drift traj. | floor acc. traj. | worst peak | "
            "peak isolator disp. [m] | peak drifts [mm] | peak floor acc. [m/s²] |\n"
            "|---|---|---|---|---|---|---|---|---|---|\n")
    lines = []
    for r in results:
        for key in ("ours", "reference", "opensees"):
            e = r[key]
            peaks = e.get("peaks") or e.get("sampled_peaks")
            if e.get("seconds") is None:
                lines.append(f"| {r['case']} | {e['method']} | — | {e.get('note', '')} | | | | | | |")
                continue
            worst_peak = max(e.get(f"error_peak_{k}", float("nan")) for k in ("slab", "drift", "floor_acc")) \
                if "error_peak_slab" in e else float("nan")
            err = [f"{e[k]:.1e}" if k in e else "(truth)" for k in ("error_slab", "error_drift", "error_floor_acc")]
            lines.append(f"| {r['case']} | {e['method']} | {e['seconds'] * 1e3:.3g} | {err[0]} | {err[1]} | {err[2]} | "
                         f"{'' if math.isnan(worst_peak) else f'{worst_peak:.1e}'} | {peaks['slab']:.4f} | "
                         f"{' '.join(f'{1e3 * d:.2f}' for d in peaks['drift'])} | "
                         f"{' '.join(f'{a:.3f}' for a in peaks['floor_acc'])} |")
    return head + "\n".join(lines) + "\n"
