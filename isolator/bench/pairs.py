r"""The 2-D cases of the bench: real pairs on a friction pendulum, our planar engine against OpenSees.

A :class:`PairCase` is two horizontal components (and optionally the vertical one)
of a real record, read from the bench's records folder, on a single friction
pendulum (R = 2 m, µ = 0.06; one case with µ(v)).  Every method answers through the
same interface as the 1-D methods, ``method(case, setting) -> MethodOutput``, with
``displacement`` and ``velocity`` of shape (N, 2) at the record's samples and
resultant peak and residual.

Methods (:data:`PAIR_METHODS`)
------------------------------
``planar engine simulate_pair (ours)``
    :func:`isolator.solver.planar.simulate_pair` (DOP853 between exactly located
    events, its default rtol 1e-11).
``independent reference (solve_ivp DOP853/Radau, rtol 1e-12)``
    :func:`isolator.bench.planar_reference.reference_pair`, the **truth** of every
    2-D row: it shares no code with the engine; its own error is ~1e-14 of the
    peak (docs/planar.md).  Its row reports its discrepancy with ours.
``OpenSees singleFPBearing, Newmark + Newton``
    :func:`isolator.bench.opensees.opensees_pair` at the record's dt (and dt/10 in
    the full run); rows say "openseespy not installed" when it does not import.
``solve_ivp LSODA, regularised friction``
    One integration of the 2-D equations with V/|V| replaced by
    V/sqrt(|V|² + v_reg²), v_reg = 1 mm/s (no events, no static friction);
    rtol 1e-4 and 1e-7.

Errors (:func:`pair_errors`, against the truth): peak resultant |X| (relative),
residual |X_end − X_ref,end| [m], slip-time ratio, and trajectory
max_k |X_k − X_ref,k| / max_k |X_ref,k| over the samples.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from isolator.bench.base import MethodOutput
from isolator.units import STANDARD_GRAVITY as STANDARD_GRAVITY_M_S2

PAIR_OURS = "planar engine simulate_pair (ours)"
PAIR_TRUTH = "independent reference (solve_ivp DOP853/Radau, rtol 1e-12)"
OPENSEES = "OpenSees singleFPBearing, Newmark + Newton"
IVP_REGULARISED = "solve_ivp LSODA, regularised friction"
#: regularisation speed of the solve_ivp baseline's friction direction V/sqrt(|V|² + v_reg²) [m/s]
REGULARISED_VELOCITY_M_S = 1e-3
ERROR_FLOOR = 1e-16

#: The pendulum of the 2-D cases (issue 10's example): R = 2 m, µ = 0.06.
PAIR_RADIUS_M = 2.0
PAIR_MU = 0.06
#: The µ(v) case: µ_slow = µs = 0.06, µ_fast = 0.10, a = 20 s/m (PTFE-like; OpenSees VelDependent, same law).
PAIR_MU_V = {"mu_slow": 0.06, "mu_fast": 0.10, "rate_s_per_m": 20.0}

#: (label, folder, x file, y file, vertical file or None, µ(v)?, seconds kept or None) of the full run.
PAIR_FILES = [
    ("superstitionhills1987_PTS", "pairs/superstitionhills1987_PTS", "RSN723_SUPER.B_B-PTS225.AT2",
     "RSN723_SUPER.B_B-PTS315.AT2", None, False, None),
    ("hectormine1999_ABY", "pairs/hectormine1999_ABY", "RSN1762_HECTOR_ABY090.AT2", "RSN1762_HECTOR_ABY360.AT2",
     None, False, None),
    ("lomaprieta1989_APEEL2 + vertical", "pairs/lomaprieta1989_APEEL2", "np01002p_4225a_a.smc",
     "np01002p_4225c_a.smc", "np01002p_4225b_a.smc", False, None),
    ("superstitionhills1987_PTS", "pairs/superstitionhills1987_PTS", "RSN723_SUPER.B_B-PTS225.AT2",
     "RSN723_SUPER.B_B-PTS315.AT2", None, True, None),
]
#: The one small 2-D case of ``--quick``: the first 12 s of the PTS pair (its strong motion, 0.3 m of sliding).
PAIR_FILES_QUICK = [("superstitionhills1987_PTS first 12 s", "pairs/superstitionhills1987_PTS",
                     "RSN723_SUPER.B_B-PTS225.AT2", "RSN723_SUPER.B_B-PTS315.AT2", None, False, 12.0)]


@dataclass
class PairCase:
    """Two horizontal components (and a vertical) on a friction pendulum, per unit mass (SI)."""

    name: str
    ax_m_s2: np.ndarray = field(repr=False)
    ay_m_s2: np.ndarray = field(repr=False)
    az_m_s2: np.ndarray | None = field(repr=False)
    dt_s: float
    mu_static: float
    radius_m: float
    mu_slow: float | None = None
    mu_fast: float | None = None
    rate_s_per_m: float | None = None
    gravity: float = STANDARD_GRAVITY_M_S2
    kind: str = "pair"

    @property
    def output_time(self) -> np.ndarray:
        return self.dt_s * np.arange(self.ax_m_s2.size)

    @property
    def duration(self) -> float:
        return self.dt_s * (self.ax_m_s2.size - 1)

    @property
    def friction(self) -> dict:
        """µ(v) keywords of the engine and the reference ({} for constant µ)."""
        if self.mu_slow is None:
            return {}
        return {"mu_slow": self.mu_slow, "mu_fast": self.mu_fast, "rate_s_per_m": self.rate_s_per_m}


def pair_case(name: str, ax_m_s2, ay_m_s2, dt_s: float, az_m_s2=None, *, mu_static: float = PAIR_MU,
              radius_m: float = PAIR_RADIUS_M, **friction) -> PairCase:
    """A pair case from acceleration samples [m/s²] at a uniform ``dt_s`` [s], trimmed to the shortest."""
    arrays = [np.ascontiguousarray(a, dtype=float) for a in (ax_m_s2, ay_m_s2, az_m_s2) if a is not None]
    n = min(a.size for a in arrays)
    arrays = [a[:n] for a in arrays]
    return PairCase(name, arrays[0], arrays[1], arrays[2] if len(arrays) > 2 else None, float(dt_s),
                    mu_static, radius_m, **friction)


def pair_cases(quick: bool, records_dir: Path) -> list[PairCase]:
    """The 2-D cases whose files are in ``records_dir`` (:data:`PAIR_FILES`, or the quick one)."""
    from isolator.motion import read_ground_motion

    cases = []
    for label, folder, fx, fy, fz, velocity_dependent, keep_s in PAIR_FILES_QUICK if quick else PAIR_FILES:
        paths = [Path(records_dir) / folder / f for f in (fx, fy, fz) if f is not None]
        if not all(p.is_file() for p in paths):
            continue
        motions = [read_ground_motion(p) for p in paths]
        dt = motions[0].dt_s
        if any(abs(m.dt_s - dt) > 1e-9 * dt for m in motions):
            continue  # not a pair on one time base: nothing to compare
        accs = [m.acceleration_m_s2 for m in motions]
        if keep_s is not None:
            accs = [a[:round(keep_s / dt) + 1] for a in accs]
        friction = PAIR_MU_V if velocity_dependent else {}
        mu = PAIR_MU_V["mu_slow"] if velocity_dependent else PAIR_MU
        law = (f"mu(v) {friction['mu_slow']:g}..{friction['mu_fast']:g}, a={friction['rate_s_per_m']:g} s/m"
               if velocity_dependent else f"mu={mu:g}")
        cases.append(pair_case(f"pair {label} (FP R={PAIR_RADIUS_M:g} m, {law})", accs[0], accs[1], dt,
                               accs[2] if fz else None, mu_static=mu, **friction))
    return cases


# ======================================================================================
# Methods
# ======================================================================================

def planar_solver(case: PairCase, setting=None) -> MethodOutput:
    """Ours: :func:`isolator.solver.planar.simulate_pair` at its default tolerance."""
    from isolator.solver.planar import simulate_pair

    r = simulate_pair(case.ax_m_s2, case.ay_m_s2, case.dt_s, az_m_s2=case.az_m_s2, mu_static=case.mu_static,
                      radius_m=case.radius_m, gravity_m_s2=case.gravity, **case.friction)
    return MethodOutput(r.displacement_m, r.velocity_m_s, r.peak_displacement_m, r.residual_displacement_m,
                        r.slip_time_s / case.duration, r.n_events)


def reference_solver(case: PairCase, setting=None) -> MethodOutput:
    """The truth: the independent solve_ivp reference (:mod:`isolator.bench.planar_reference`)."""
    from isolator.bench.planar_reference import reference_pair

    ref = reference_pair(case.output_time, case.ax_m_s2, case.ay_m_s2, case.az_m_s2, mu_s=case.mu_static,
                         radius=case.radius_m, g=case.gravity, mu_slow=case.mu_slow, mu_fast=case.mu_fast,
                         rate=case.rate_s_per_m)
    # slip time from the events: a slide runs from a break-away to the next stick (or the end)
    slip, start = 0.0, None
    for t, kind in sorted(ref.events):
        if kind == "breakaway" and start is None:
            start = t
        elif kind == "stick" and start is not None:
            slip, start = slip + t - start, None
    if start is not None:
        slip += case.duration - start
    return MethodOutput(ref.displacement_m, ref.velocity_m_s, ref.peak_displacement_m, ref.residual_displacement_m,
                        slip / case.duration, ref.n_stops + ref.n_breakaways)


def opensees_solver(case: PairCase, setting: str = "dt/1") -> MethodOutput:
    """OpenSees ``singleFPBearing`` at ``setting`` = "dt/N" (N steps per sample interval).

    Only the sampled displacement is recorded: the peak is the sampled one, the
    slip ratio unknown (NaN).
    """
    from isolator.bench.opensees import opensees_pair

    substeps = int(str(setting).split("/")[1])
    x = opensees_pair(case.dt_s, case.ax_m_s2, case.ay_m_s2, case.az_m_s2, mu=case.mu_static,
                      radius_m=case.radius_m, gravity_m_s2=case.gravity, substeps=substeps, **case.friction)
    resultant = np.hypot(x[:, 0], x[:, 1])
    v = np.gradient(x, case.dt_s, axis=0)
    return MethodOutput(x, v, float(resultant.max()), float(resultant[-1]), math.nan)


def ivp_regularised(case: PairCase, rtol: float) -> MethodOutput:
    """solve_ivp (LSODA) on the 2-D equations with a regularised friction direction, no events.

    V/|V| → V/sqrt(|V|² + v_reg²) (v_reg = :data:`REGULARISED_VELOCITY_M_S`): static
    friction and sticking are lost (the block creeps at |V| ~ v_reg |F|/(µn)).
    """
    from scipy.integrate import solve_ivp

    t = case.output_time
    ax, ay = case.ax_m_s2, case.ay_m_s2
    nz = case.gravity + (case.az_m_s2 if case.az_m_s2 is not None else np.zeros_like(ax))
    dt, last = case.dt_s, ax.size - 2
    v_reg2 = REGULARISED_VELOCITY_M_S ** 2
    mu_slow, mu_fast, rate = case.mu_slow, case.mu_fast, case.rate_s_per_m

    def rhs(tt, y):
        u = tt / dt
        i = min(max(int(u), 0), last)
        f = min(max(u - i, 0.0), 1.0)
        gx = ax[i] + f * (ax[i + 1] - ax[i])
        gy = ay[i] + f * (ay[i + 1] - ay[i])
        n = nz[i] + f * (nz[i + 1] - nz[i])
        if n <= 0.0:  # uplift: no friction, no restoring force
            return [y[2], y[3], -gx, -gy]
        speed = math.hypot(y[2], y[3])
        mu = case.mu_static if mu_slow is None else mu_fast - (mu_fast - mu_slow) * math.exp(-rate * speed)
        scale = mu * n / math.sqrt(speed * speed + v_reg2)
        kappa = n / case.radius_m
        return [y[2], y[3], -scale * y[2] - kappa * y[0] - gx, -scale * y[3] - kappa * y[1] - gy]

    sol = solve_ivp(rhs, (0.0, case.duration), np.zeros(4), method="LSODA", rtol=rtol, atol=rtol * 1e-3,
                    t_eval=t)
    if sol.status < 0:
        raise RuntimeError(f"solve_ivp LSODA: {sol.message}")
    x, v = sol.y[:2].T.copy(), sol.y[2:].T.copy()
    resultant = np.hypot(x[:, 0], x[:, 1])
    slip = float(np.mean(np.hypot(v[:, 0], v[:, 1]) > REGULARISED_VELOCITY_M_S))
    return MethodOutput(x, v, float(resultant.max()), float(resultant[-1]), slip)


def pair_errors(out: MethodOutput, ref: MethodOutput) -> dict:
    """Errors of ``out`` against ``ref`` (resultants; trajectory relative to the largest sampled |X_ref|)."""
    ref_resultant = np.hypot(ref.displacement[:, 0], ref.displacement[:, 1])
    scale = max(float(ref_resultant.max()), ERROR_FLOOR)
    diff = np.hypot(*(out.displacement - ref.displacement).T)
    finite = bool(np.all(np.isfinite(out.displacement)))
    zeta = abs(out.slip_ratio - ref.slip_ratio)
    return {
        "error_peak_rel": max(abs(out.peak - ref.peak) / max(abs(ref.peak), ERROR_FLOOR), ERROR_FLOOR),
        "error_residual_abs": max(float(np.hypot(*(out.displacement[-1] - ref.displacement[-1]))), ERROR_FLOOR),
        "error_zeta": max(zeta, ERROR_FLOOR) if math.isfinite(zeta) else math.nan,
        "error_trajectory": max(float(diff.max()) / scale, ERROR_FLOOR) if finite else math.inf,
    }


@dataclass
class PairMethod:
    """A baseline of the 2-D cases and its settings (full and ``--quick`` runs)."""

    name: str
    function: object
    settings: list
    quick_settings: list
    setting_name: str
    #: () -> (available, reason): a baseline whose package is optional
    available: object = None


def _always() -> tuple[bool, str]:
    return True, ""


def _opensees_available() -> tuple[bool, str]:
    from isolator.bench.opensees import opensees_available

    return opensees_available()


#: The 2-D registry: the baselines compared with the truth (ours and the truth are run by the harness).
PAIR_METHODS: dict[str, PairMethod] = {m.name: m for m in [
    PairMethod(OPENSEES, opensees_solver, ["dt/1", "dt/10"], ["dt/1"], "steps", _opensees_available),
    PairMethod(IVP_REGULARISED, ivp_regularised, [1e-4, 1e-7], [1e-4, 1e-7], "rtol", _always),
]}


def pair_methods(quick: bool = False) -> list[PairMethod]:
    """The baselines of :data:`PAIR_METHODS` with the settings of a full or a ``quick`` run."""
    from dataclasses import replace

    return [replace(m, settings=m.quick_settings) if quick else m for m in PAIR_METHODS.values()]
