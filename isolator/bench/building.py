r"""The building cases of the bench (issue 22): ours against OpenSees on a 5-story building, 1-D and 2-D.

A 5-story shear building (5 floors of 500 t, story height 3.5 m, equal story stiffnesses
giving a fixed-base T1 = 0.5 s along x — and 0.4 s along y in 2-D —, ζ = 5 % in every
fixed-base mode) on a 500 t base slab (M = 3000 t) on a friction pendulum R = 2.5 m,
µ = 0.06 (Coulomb, µs = µk): one horizontal component of a real record (1-D), or a real
pair (2-D: both components, coupled friction on the isolation plane).

Three solutions of the same equations (docs/building.md), at the record's samples:

``exact 1-D building (ours)`` / ``exact 2-D building (ours)``
    :func:`isolator.solver.building.simulate_building` (model ``1d-building``), or the
    registry's ``2d-building`` model under a pair: exact propagation between events
    located to rounding.
``independent reference``
    :func:`isolator.bench.building_reference.building_reference` in 1-D,
    :func:`isolator.bench.planar_building_reference.planar_building_reference` in 2-D
    (solve_ivp at rtol 1e-12 with located events; no code shared with ours):
    **our error** is our discrepancy with it.
``OpenSees singleFPBearing + zeroLength stories, Newmark + Newton``
    :func:`isolator.bench.opensees_building.opensees_building` at the record's dt:
    **its error** is measured against ours (ours is within ~1e-10 of the reference, so
    ours stands for the truth at OpenSees' level of error), and against the reference
    when ours is not available (the 2-D building before its engine landed).

Errors, each relative to the reference solution's largest value over the samples (in 2-D
the length of the vector difference over the largest resultant): ``slab`` (x_b, the
isolator's displacement), ``drift`` (u_i − u_{i−1}, all stories), ``floor_acc`` (absolute
floor accelerations, all floors), and the relative error of the sampled peaks (isolator
displacement, each story drift, each floor acceleration, resultants in 2-D: the worst).
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
BUILDING_OURS_2D = "exact 2-D building (ours)"
BUILDING_TRUTH = "independent reference (solve_ivp DOP853 + events, rtol 1e-12)"
BUILDING_TRUTH_2D = "independent reference (solve_ivp DOP853/Radau + events, rtol 1e-12)"
#: the registry's name of the 2-D building model (issue 22)
PLANAR_BUILDING_MODEL = "2d-building"
BUILDING_OPENSEES = "OpenSees singleFPBearing + zeroLength stories, Newmark + Newton"

#: The bench's building: 5 floors of 500 t, 3.5 m stories, fixed-base T1 = 0.5 s, ζ = 5 %, slab 500 t.
N_FLOORS = 5
FLOOR_MASS_KG = 5.0e5
STORY_HEIGHT_M = 3.5
FIXED_BASE_PERIOD_S = 0.5
#: fixed-base T1 along y of the 2-D case [s] (the two directions differ, as in a real building)
FIXED_BASE_PERIOD_Y_S = 0.4
DAMPING_RATIO = 0.05
SLAB_MASS_KG = 5.0e5
RADIUS_M = 2.5
MU = 0.06
#: (label, file under --records, seconds kept) of the full and the quick run
BUILDING_RECORD = ("RSN1044_NORTHR_NWH360", "at2/RSN1044_NORTHR_NWH360.AT2")
BUILDING_SECONDS = {"full": 20.0, "quick": 8.0}
#: (label, folder under --records, x file, y file) of the 2-D case: Superstition Hills 1987, Parachute Test Site
BUILDING_PAIR = ("superstitionhills1987_PTS", "pairs/superstitionhills1987_PTS", "RSN723_SUPER.B_B-PTS225.AT2",
                 "RSN723_SUPER.B_B-PTS315.AT2")
BUILDING_PAIR_SECONDS = {"full": 20.0, "quick": 4.0}
#: The 2-D row's second setting (h184): the fast sub-steps' end check and their friction's truncation both at this
#: fraction of µk N (``planar_building.FAST_CHECK`` and ``FAST_TRUNC_EPS``, defaults 1e-12).  On PTS, YER and DZC
#: 0-20 s its error against the independent reference was 1.6e-11-3.4e-11 (OpenSees 0.58-0.74) at 5-9 % less CPU
#: (docs/building.md, h184); the bench measures its error and its ratio again in every run.
BUILDING_LOOSE_CHECK = 1e-8


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
    #: the second horizontal component [m/s²] (2-D), or None (1-D, along x)
    acceleration_y_m_s2: np.ndarray | None = field(default=None, repr=False)

    @property
    def planar(self) -> bool:
        """Both horizontal components (the 2-D building)."""
        return self.acceleration_y_m_s2 is not None

    @property
    def isolator_stiffness_N_per_m(self) -> float:
        """K = W/R = g M / R [N/m]."""
        return self.gravity_m_s2 * self.total_mass_kg / self.radius_m


def building_case(name: str, acceleration_m_s2, dt_s: float, *, acceleration_y_m_s2=None, n_floors: int = N_FLOORS,
                  floor_mass_kg: float = FLOOR_MASS_KG, story_height_m: float = STORY_HEIGHT_M,
                  period_s: float = FIXED_BASE_PERIOD_S, period_y_s: float | None = None,
                  damping_ratio: float = DAMPING_RATIO, slab_mass_kg: float = SLAB_MASS_KG, radius_m: float = RADIUS_M,
                  mu: float = MU) -> BuildingCase:
    """A uniform shear building case (equal floors and stories, fixed-base T1 = ``period_s`` along x and
    ``period_y_s`` along y, default the same), 2-D when ``acceleration_y_m_s2`` is given (trimmed to the
    shorter component)."""
    from isolator.superstructure import Floor, Superstructure

    k = uniform_story_stiffness(n_floors, floor_mass_kg, period_s)
    k_y = k if period_y_s is None else uniform_story_stiffness(n_floors, floor_mass_kg, period_y_s)
    floors = tuple(Floor(floor_mass_kg, story_height_m, k, k_y) for _ in range(n_floors))
    structure = Superstructure(floors=floors, damping_ratio=damping_ratio, gravity_m_s2=STANDARD_GRAVITY_M_S2)
    ax = np.ascontiguousarray(acceleration_m_s2, dtype=float)
    ay = None
    if acceleration_y_m_s2 is not None:
        ay = np.ascontiguousarray(acceleration_y_m_s2, dtype=float)
        n = min(ax.size, ay.size)
        ax, ay = ax[:n], ay[:n]
    return BuildingCase(name, ax, float(dt_s), structure, n_floors * floor_mass_kg + slab_mass_kg, radius_m, mu,
                        acceleration_y_m_s2=ay)


def building_cases(quick: bool, records_dir: Path) -> list[BuildingCase]:
    """The building cases whose records are in ``records_dir``: 1-D (NWH360, first 8 s quick, 20 s full)
    and 2-D (the PTS pair, first 4 s quick, 20 s full)."""
    from isolator.motion import read_ground_motion

    key = "quick" if quick else "full"
    cases = []
    label, rel = BUILDING_RECORD
    path = Path(records_dir) / rel
    if path.is_file():
        motion = read_ground_motion(path)
        seconds = BUILDING_SECONDS[key]
        acc = motion.acceleration_m_s2[:round(seconds / motion.dt_s) + 1]
        cases.append(building_case(f"building {label} 0-{seconds:g} s (5 stories, T1=0.5 s, FP R=2.5 m, mu=0.06)",
                                   acc, motion.dt_s))
    label, folder, fx, fy = BUILDING_PAIR
    paths = [Path(records_dir) / folder / f for f in (fx, fy)]
    if all(p.is_file() for p in paths):
        mx, my = (read_ground_motion(p) for p in paths)
        seconds = BUILDING_PAIR_SECONDS[key]
        keep = round(seconds / mx.dt_s) + 1
        if abs(mx.dt_s - my.dt_s) <= 1e-9 * mx.dt_s:
            cases.append(building_case(
                f"2-D building pair {label} 0-{seconds:g} s (5 stories, T1=0.5/0.4 s, FP R=2.5 m, mu=0.06)",
                mx.acceleration_m_s2[:keep], mx.dt_s, acceleration_y_m_s2=my.acceleration_m_s2[:keep],
                period_y_s=FIXED_BASE_PERIOD_Y_S))
    return cases


def _histories(slab, floor_disp, floor_acc) -> dict:
    """The compared histories: slab displacement, story drifts, floor absolute accelerations
    ((N,), (N, n), (N, n) in 1-D; (N, 2), (N, n, 2), (N, n, 2) in 2-D)."""
    floor_disp = np.asarray(floor_disp, dtype=float)
    ground = np.zeros((floor_disp.shape[0], 1) + floor_disp.shape[2:])
    drift = np.diff(np.concatenate([ground, floor_disp], axis=1), axis=1)
    return {"slab": np.asarray(slab, dtype=float), "drift": drift, "floor_acc": np.asarray(floor_acc, dtype=float)}


def is_planar(histories: dict) -> bool:
    """The histories are 2-D: the slab's displacement has an (x, y) axis."""
    return np.asarray(histories["slab"]).ndim == 2


def _magnitude(values, planar: bool) -> np.ndarray:
    """|values|: the absolute value in 1-D, the length of the (x, y) vector (last axis) in 2-D."""
    values = np.asarray(values, dtype=float)
    return np.hypot(values[..., 0], values[..., 1]) if planar else np.abs(values)


def planar_building_available() -> tuple[bool, str]:
    """(True, "") when the registry has the 2-D building model, else (False, why)."""
    from isolator.solver.models import MODELS

    if PLANAR_BUILDING_MODEL in MODELS:
        return True, ""
    return False, f"the {PLANAR_BUILDING_MODEL} model is not in the solver registry (not on this branch)"


def _bench_design(case: BuildingCase):
    """The design the registry's models read for the case (its superstructure, mass, g; no bearing layout)."""
    from types import SimpleNamespace

    return SimpleNamespace(superstructure=case.superstructure, mass_kg=case.total_mass_kg,
                           gravity_m_s2=case.gravity_m_s2, bearing_layout=None, source="bench building")


def ours_building(case: BuildingCase, setting=None, check: float | None = None) -> dict:
    """Ours: :func:`isolator.solver.building.simulate_building` (exact), or the registry's
    ``2d-building`` model under the case's pair (``check``: its fast sub-steps' end check and truncation, None for
    the defaults)."""
    if case.planar:
        return _ours_planar_building(case, check)
    from isolator.solver.building import simulate_building

    r = simulate_building(case.acceleration_m_s2, case.dt_s, superstructure=case.superstructure,
                          total_mass_kg=case.total_mass_kg, stiffness_N_per_m=case.isolator_stiffness_N_per_m,
                          mu_static=case.mu, mu_kinetic=case.mu, gravity_m_s2=case.gravity_m_s2)
    out = _histories(r.displacement_m, r.floor_displacement_m, r.floor_absolute_acceleration_m_s2)
    out["exact_peaks"] = {"slab": float(r.peak_displacement_m), "drift": np.asarray(r.story_drift_m),
                          "floor_acc": np.asarray(r.floor_peak_acceleration_m_s2)}
    return out


def _ours_planar_building(case: BuildingCase, check: float | None = None) -> dict:
    """Ours in 2-D: the registry's ``2d-building`` model on the case's pair (exact resultant peaks); ``check``: the
    fast sub-steps' end check and friction truncation (``planar_building.FAST_CHECK`` and ``FAST_TRUNC_EPS``, put
    back after the call), None for the defaults."""
    from isolator.solver import planar_building
    from isolator.solver.base import Scene
    from isolator.solver.models import simulate

    scene = Scene(ax_m_s2=case.acceleration_m_s2, ay_m_s2=case.acceleration_y_m_s2, dt_s=case.dt_s,
                  isolator={"mu_static": case.mu, "mu_kinetic": case.mu, "radius_m": case.radius_m,
                            "gravity_m_s2": case.gravity_m_s2}, design=_bench_design(case))
    saved = planar_building.FAST_CHECK, planar_building.FAST_TRUNC_EPS
    if check is not None:
        planar_building.FAST_CHECK = planar_building.FAST_TRUNC_EPS = check
    try:
        r = simulate(scene)
    finally:
        planar_building.FAST_CHECK, planar_building.FAST_TRUNC_EPS = saved
    if r.model != PLANAR_BUILDING_MODEL:
        raise RuntimeError(f"the registry ran {r.model!r} for the 2-D building, not {PLANAR_BUILDING_MODEL!r}")
    out = _histories(r.displacement_m, r.floor_displacement_m, r.floor_absolute_acceleration_m_s2)
    out["exact_peaks"] = {"slab": float(r.peak_displacement_m), "drift": np.asarray(r.story_drift_m),
                          "floor_acc": np.asarray(r.floor_peak_acceleration_m_s2)}
    # the energy balance's error over the input energy (J/kg over J/kg; the input is > 0 once the ground moves)
    out["energy_balance"] = float(r.energy_balance_error_J_per_kg) / max(float(r.energy_input_J_per_kg), 1e-300)
    return out


def reference_building(case: BuildingCase, setting=None) -> dict:
    """The independent reference (:mod:`isolator.bench.building_reference`, in 2-D
    :mod:`isolator.bench.planar_building_reference`)."""
    s = case.superstructure
    if case.planar:
        from isolator.bench.planar_building_reference import planar_building_reference

        r = planar_building_reference(
            case.acceleration_m_s2, case.acceleration_y_m_s2, case.dt_s, masses_kg=s.masses_kg,
            stiffness_matrices=(s.stiffness_matrix("x"), s.stiffness_matrix("y")),
            damping_matrices=(s.damping_matrix("x"), s.damping_matrix("y")), total_mass_kg=case.total_mass_kg,
            isolator_stiffness_N_per_m=case.isolator_stiffness_N_per_m, mu_static=case.mu, mu_kinetic=case.mu,
            gravity_m_s2=case.gravity_m_s2)
        return _histories(r["slab_displacement_m"], r["floor_displacement_m"], r["floor_absolute_acceleration_m_s2"])
    from isolator.bench.building_reference import building_reference

    r = building_reference(case.acceleration_m_s2, case.dt_s, masses_kg=s.masses_kg,
                           stiffness_matrix=s.stiffness_matrix(), damping_matrix=s.damping_matrix(),
                           total_mass_kg=case.total_mass_kg, isolator_stiffness_N_per_m=case.isolator_stiffness_N_per_m,
                           mu_static=case.mu, mu_kinetic=case.mu, gravity_m_s2=case.gravity_m_s2)
    return _histories(r["slab_displacement_m"], r["floor_displacement_m"], r["floor_absolute_acceleration_m_s2"])


def opensees_building_solver(case: BuildingCase, setting=1) -> dict:
    """OpenSees (:func:`isolator.bench.opensees_building.opensees_building`), ``setting`` substeps per dt."""
    from isolator.bench.opensees_building import opensees_building

    s = case.superstructure
    r = opensees_building(case.dt_s, case.acceleration_m_s2, case.acceleration_y_m_s2, masses_kg=s.masses_kg,
                          stiffnesses_N_per_m=s.story_stiffnesses("x"), damping_matrix=s.damping_matrix("x"),
                          stiffnesses_y_N_per_m=s.story_stiffnesses("y"), damping_matrix_y=s.damping_matrix("y"),
                          total_mass_kg=case.total_mass_kg, radius_m=case.radius_m, mu=case.mu,
                          gravity_m_s2=case.gravity_m_s2, substeps=int(setting or 1))
    return _histories(r["slab_displacement_m"], r["floor_displacement_m"], r["floor_absolute_acceleration_m_s2"])


def sampled_peaks(histories: dict) -> dict:
    """Peaks over the samples: |x_b|, per story |drift|, per floor |a| (m, m, m/s²; resultants in 2-D)."""
    planar = is_planar(histories)
    return {"slab": float(np.max(_magnitude(histories["slab"], planar))),
            "drift": np.max(_magnitude(histories["drift"], planar), axis=0),
            "floor_acc": np.max(_magnitude(histories["floor_acc"], planar), axis=0)}


def building_errors(histories: dict, truth: dict) -> dict:
    """Trajectory errors (max over samples / the truth's largest value; vector differences in 2-D) and the
    worst sampled-peak error."""
    out = {}
    planar = is_planar(truth)
    peaks, true_peaks = sampled_peaks(histories), sampled_peaks(truth)
    for key in ("slab", "drift", "floor_acc"):
        scale = max(float(np.max(_magnitude(truth[key], planar))), 1e-300)
        out[f"error_{key}"] = float(np.max(_magnitude(histories[key] - truth[key], planar))) / scale
        out[f"error_peak_{key}"] = float(np.max(np.abs(np.atleast_1d(peaks[key]) - np.atleast_1d(true_peaks[key]))
                                                / np.maximum(np.atleast_1d(true_peaks[key]), 1e-300)))
    out["error_max"] = max(out["error_slab"], out["error_drift"], out["error_floor_acc"])
    return out


def run_building_case(case: BuildingCase, rounds: int = 3, ours_per_round: int = 5, progress=None) -> dict:
    """Ours, the reference and OpenSees on one case: times, peaks and errors.

    Ours and OpenSees (at the record's dt) are timed in alternation, ``rounds`` rounds of
    ``ours_per_round`` runs of ours then one of OpenSees (medians); the reference runs once.
    When ours cannot run (a 2-D case on a branch without the ``2d-building`` model), OpenSees
    runs ``rounds`` times alone and its error is measured against the reference.

    Returns
    -------
    dict
        ``case``, ``planar``, ``n_samples``, ``dt_s``, ``ours`` / ``reference`` / ``opensees``
        entries (``seconds``, ``runs``, ``peaks``, errors; ``seconds`` None and a ``note`` for
        a method that did not run) and ``time_ratio`` / ``error_ratio`` (OpenSees over ours;
        None when either did not run); in 2-D with both run also ``ours_loose``: ours at
        :data:`BUILDING_LOOSE_CHECK`, timed in a three-way alternation with ours at the defaults and OpenSees
        (``default_seconds``, ``default_time_ratio`` from the same rounds), its errors against the reference,
        its own ``time_ratio`` and ``error_ratio`` (OpenSees' error against ours at the defaults over its error).
    """
    from isolator.bench.harness import time_ours_and_opensees

    say = progress or (lambda line: None)
    ours_method = BUILDING_OURS_2D if case.planar else BUILDING_OURS
    ours_ok, ours_why = planar_building_available() if case.planar else (True, "")
    result = {"case": case.name, "planar": case.planar, "n_samples": int(case.acceleration_m_s2.size),
              "dt_s": case.dt_s, "time_ratio": None, "error_ratio": None}
    ours_s, ours_out, ours_runs, os_s, os_out, os_runs, os_why = time_ours_and_opensees(
        ours_building, opensees_building_solver, case, rounds, ours_per_round, "" if ours_ok else ours_why, say)
    say(f"{case.name}: the independent reference (solve_ivp, once)")
    start = time.perf_counter()
    truth = reference_building(case)
    ref_s = time.perf_counter() - start
    if ours_out is not None:
        result["ours"] = {"method": ours_method, "seconds": ours_s, "runs": ours_runs,
                          "peaks": _listed(ours_out["exact_peaks"]),
                          "sampled_peaks": _listed(sampled_peaks(ours_out)), **building_errors(ours_out, truth)}
    else:
        result["ours"] = {"method": ours_method, "seconds": None, "note": ours_why}
    result["reference"] = {"method": BUILDING_TRUTH_2D if case.planar else BUILDING_TRUTH, "seconds": ref_s,
                           "runs": 1, "sampled_peaks": _listed(sampled_peaks(truth))}
    if os_out is None:
        result["opensees"] = {"method": BUILDING_OPENSEES, "seconds": None, "note": os_why}
        return result
    os_vs_truth = building_errors(os_out, truth)
    os_errors = building_errors(os_out, ours_out) if ours_out is not None else os_vs_truth
    result["opensees"] = {"method": BUILDING_OPENSEES, "setting": "dt/1", "seconds": os_s, "runs": os_runs,
                          "errors_against": "ours" if ours_out is not None else "the reference",
                          "sampled_peaks": _listed(sampled_peaks(os_out)), **os_errors,
                          "error_max_vs_reference": os_vs_truth["error_max"]}
    if ours_out is not None:
        result["time_ratio"] = os_s / ours_s
        result["error_ratio"] = os_errors["error_max"] / max(result["ours"]["error_max"], 1e-16)
        if case.planar:
            result["ours_loose"] = _loose_row(case, rounds, ours_per_round, truth, os_errors["error_max"], say)
    return result


def _loose_row(case: BuildingCase, rounds: int, ours_per_round: int, truth: dict, os_error: float, say) -> dict:
    # ours at BUILDING_LOOSE_CHECK, ours at the defaults and OpenSees in one three-way alternation (round by round:
    # the defaults ``ours_per_round`` times, the loose as often, OpenSees once): the loose row's time ratio and the
    # default's in the same minutes, each measured here; the loose row's own errors against the reference
    from isolator.bench.harness import time_rounds

    say(f"{case.name}: ours at end check {BUILDING_LOOSE_CHECK:g}, ours at the defaults and OpenSees, {rounds} rounds "
        "in alternation")
    medians, counts, last = time_rounds(
        {"default": (lambda: ours_building(case), ours_per_round),
         "loose": (lambda: ours_building(case, check=BUILDING_LOOSE_CHECK), ours_per_round),
         "opensees": (lambda: opensees_building_solver(case), 1)}, rounds)
    seconds, default_s, os_s, out = medians["loose"], medians["default"], medians["opensees"], last["loose"]
    row = {"method": f"{BUILDING_OURS_2D}, end check {BUILDING_LOOSE_CHECK:g}", "check": BUILDING_LOOSE_CHECK,
           "seconds": seconds, "runs": counts["loose"], "default_seconds": default_s,
           "errors_against": "the reference", **building_errors(out, truth), "opensees_seconds": os_s,
           "opensees_runs": counts["opensees"], "time_ratio": os_s / seconds, "default_time_ratio": os_s / default_s}
    row["error_ratio"] = os_error / max(row["error_max"], 1e-16)
    return row


def _listed(peaks: dict) -> dict:
    return {key: (value.tolist() if isinstance(value, np.ndarray) else value) for key, value in peaks.items()}


def building_summary(results: list[dict]) -> list[str]:
    """One line per building case: ours against OpenSees, time and error ratios, measured in this run."""
    lines = []
    what = "largest error (isolator displacement, drifts, floor accelerations)"
    for r in results:
        ours, os_ = r["ours"], r["opensees"]
        if ours["seconds"] is None:
            theirs = (f"OpenSees {os_['seconds'] * 1e3:.3g} ms (median of {os_['runs']}), {what} "
                      f"{os_['error_max']:.1e} vs the reference" if os_["seconds"] is not None
                      else f"OpenSees not run ({os_.get('note')})")
            lines.append(f"{r['case']}: ours not run ({ours.get('note')}); {theirs}")
            continue
        if r["time_ratio"] is None:
            lines.append(f"{r['case']}: ours {ours['seconds'] * 1e3:.3g} ms, error {ours['error_max']:.1e} against "
                         f"the reference; vs OpenSees: not measured ({os_.get('note')})")
            continue
        lines.append(f"{r['case']}: ours {ours['seconds'] * 1e3:.3g} ms (median of {ours['runs']}), "
                     f"{r['time_ratio']:.3g}× faster than OpenSees at the record's dt ({os_['seconds'] * 1e3:.3g} ms, "
                     f"median of {os_['runs']}, interleaved); {what} ours {ours['error_max']:.1e} vs the reference, "
                     f"OpenSees {os_['error_max']:.1e} vs ours: {r['error_ratio']:.2g}× lower")
        loose = r.get("ours_loose")
        if loose:
            lines.append(f"{r['case']} at end check {loose['check']:g}: ours {loose['seconds'] * 1e3:.3g} ms (median "
                         f"of {loose['runs']}), {loose['time_ratio']:.3g}× faster than OpenSees "
                         f"({loose['opensees_seconds'] * 1e3:.3g} ms, median of {loose['opensees_runs']}; in the same "
                         f"rounds ours at the defaults {loose['default_seconds'] * 1e3:.3g} ms, "
                         f"{loose['default_time_ratio']:.3g}×); {what} ours {loose['error_max']:.1e} vs the reference, "
                         f"{loose['error_ratio']:.2g}× lower than OpenSees'")
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
