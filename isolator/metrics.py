r"""Classification of a response: one set of definitions for harmonic and record alike.

A response — the harmonic solver's steady cycle or a record's exact response — is
classified by the same rules (:func:`classify`), fed by :func:`classify_harmonic` or
:func:`classify_record`:

* **regime** (:func:`regime_from_slip`): ``ST`` if the block never slides, ``SL`` if it
  slides the whole observation window (slip-time ratio ζ = 1: no stick inside it),
  ``SS`` otherwise.  Harmonic: ζ over the steady cycle (Eq. 3).  Record: ζ over the
  strong-motion window D5–95 (between 5 % and 95 % of the Arias intensity; of the
  horizontal resultant |a| for a pair), from the exact event times (break-away starts a
  slip, stick ends it) — the exact slip time, in 1-D and in 2-D alike.
* **amplification**: A = (max X − min X) / (2 A0), half the peak-to-peak relative
  displacement over the ground amplitude A0 (A0 = PGV²/PGA for a record);
  ``amplified`` when A > 1.
* **dominant force**: the largest of the friction (µk M g while sliding), spring
  (K |X|) and damper (γ |Ẋ|) force peaks.  Harmonic: the amplitudes kA, ηAω and µk
  (Eq. 5).  Record: the peaks over the record, ``max K|X|``, ``max γ|Ẋ|`` and µk M g
  (µs M g at most if it never slid).  The paper's ratios ρ_ev, ρ_vf, ρ_ef (Eq. 5) at
  the equivalent point (α, k, η) with the record's A are reported too, with the
  dominance they imply (``dominant_force_rho``).

A planar (2-D) or multi-surface response is classified by regime and ζ only: A, the dominant force and the
Eq. 5 ratios are of the paper's 1-D block; they are None and :data:`PLANAR_NOT_APPLICABLE`
says why.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

#: The regimes of the paper, in the order of their codes (0, 1, 2), and what they mean.
REGIMES = ("ST", "SS", "SL")
REGIME_WORDS = {"ST": "stick (no sliding)", "SS": "stick-slip", "SL": "permanent slip"}
FORCE_NAMES = ("friction", "elastic", "viscous")
_A_1D = ("the paper's A (half the peak-to-peak displacement / A0) is of a rigid block on one surface under one "
         "component; not of a planar or multi-surface response (see peak_displacement_over_a0)")
#: Classification fields that do not apply to a planar response, and why.
PLANAR_NOT_APPLICABLE = {
    "amplitude": _A_1D, "amplified": _A_1D,
    "dominant_force": "the paper's force peaks (µk M g, K|X|, γ|dX/dt|) classify a block on one surface in 1-D",
    **{name: "the paper's Eq. 5 ratios need its A, a 1-D measure"
       for name in ("dominant_force_rho", "rho_ev", "rho_vf", "rho_ef")},
}


@dataclass(frozen=True)
class Classification:
    """Regime, amplification and dominant force of one response (dimensionless).

    Attributes
    ----------
    source : str
        ``"harmonic"`` or ``"record"``.
    regime : str
        ``"ST"``, ``"SS"`` or ``"SL"``.
    zeta : float
        Slip-time ratio over the observation window, from the exact slip time [-].
    amplitude : float or None
        A = half peak-to-peak relative displacement / A0 [-] (None for a planar response).
    amplified : bool or None
        A > 1.
    dominant_force : str or None
        ``"friction"``, ``"elastic"`` or ``"viscous"`` (from the force peaks).
    rho_ev, rho_vf, rho_ef : float or None
        Eq. 5 ratios at (α, k, η) with this A (None where 0/0 or infinite, or planar).
    dominant_force_rho : str or None
        Dominance implied by the Eq. 5 amplitudes kA, ηAω, µk.
    window_s : tuple
        (start, end) of the observation window [s] (dimensionless time for harmonic).
    """

    source: str
    regime: str
    zeta: float
    amplitude: float | None
    amplified: bool | None
    dominant_force: str | None
    rho_ev: float | None
    rho_vf: float | None
    rho_ef: float | None
    dominant_force_rho: str | None
    window_s: tuple = (0.0, 0.0)

    def as_dict(self) -> dict:
        out = asdict(self)
        out["window_s"] = list(self.window_s)
        return out


def regime_from_slip(moved: bool, zeta: float) -> str:
    """ST if the block never slid; SL if it slid the whole window (ζ = 1); SS otherwise."""
    if not moved:
        return "ST"
    return "SL" if zeta >= 1.0 else "SS"


def dominant_of(friction: float, elastic: float, viscous: float) -> str:
    """Name of the largest of three force magnitudes (friction wins ties)."""
    forces = {"friction": friction, "elastic": elastic, "viscous": viscous}
    return max(forces, key=forces.get)


def classify(source: str, moved: bool, zeta: float, amplitude: float, force_peaks: tuple,
             alpha: float, k: float, eta: float, mu_s: float, mu_k: float,
             window_s: tuple = (0.0, 0.0)) -> Classification:
    """The one classification rule (see the module docstring).

    Parameters
    ----------
    source : str
        ``"harmonic"`` or ``"record"``.
    moved : bool
        Whether the block slid at all.
    zeta : float
        Slip-time ratio over the window [-].
    amplitude : float
        A [-].
    force_peaks : tuple
        (friction, elastic, viscous) force magnitudes, in any common unit.
    alpha, k, eta, mu_s, mu_k : float
        The dimensionless point [-].
    window_s : tuple
        Observation window [s].
    """
    from isolator.solver.harmonic import force_ratios

    rho_ev, rho_vf, rho_ef, dominant_rho = force_ratios(k, eta, alpha, mu_s, mu_k, amplitude)
    regime = regime_from_slip(moved, zeta)
    return Classification(source=source, regime=regime, zeta=float(zeta), amplitude=float(amplitude),
                          amplified=bool(amplitude > 1.0), dominant_force=dominant_of(*force_peaks),
                          rho_ev=rho_ev, rho_vf=rho_vf, rho_ef=rho_ef, dominant_force_rho=dominant_rho,
                          window_s=tuple(float(t) for t in window_s))


def classify_harmonic(response) -> Classification:
    """Classify the harmonic solver's steady response (same rules as a record).

    Parameters
    ----------
    response : isolator.solver.harmonic.HarmonicResponse

    Returns
    -------
    Classification
    """
    r = response
    moved = r.regime != "ST"
    omega = math.sqrt(r.alpha * r.mu_s)
    peaks = (r.mu_k, r.k * r.amplitude, r.eta * r.amplitude * omega)  # Eq. 5 amplitudes
    period = 2.0 * math.pi / omega
    return classify("harmonic", moved, r.zeta if moved else 0.0, r.amplitude, peaks,
                    r.alpha, r.k, r.eta, r.mu_s, r.mu_k, (0.0, r.cycle_periods * period))


def slip_intervals(response) -> np.ndarray:
    """Slip intervals [s] of a record response, from its exact events, shape (n, 2)."""
    times = np.asarray(response.event_time_s, dtype=float)
    kinds = np.asarray(response.event_kind)
    intervals = []
    start = None
    for t, kind in zip(times, kinds, strict=True):
        if kind == 0 and start is None:  # break-away
            start = t
        elif kind == 1 and start is not None:  # stick
            intervals.append((start, t))
            start = None
    if start is not None:
        intervals.append((start, float(response.time_s[-1])))
    return np.array(intervals, dtype=float).reshape(-1, 2)


def strong_motion_window_s(acceleration_m_s2, dt_s: float, start_fraction: float = 0.05,
                           end_fraction: float = 0.95, time_s=None) -> tuple[float, float]:
    """Times [s] at which the Arias intensity reaches 5 % and 95 % (D5–95 window).

    ``time_s`` gives the sample times of a record with unequal steps [s] (``dt_s`` unused).
    """
    from isolator.motion.measures import arias_window_s

    window = arias_window_s(acceleration_m_s2, dt_s, start_fraction, end_fraction, time_s)
    if window is None:  # a record of zeros: the whole record
        n = np.asarray(acceleration_m_s2).size
        return 0.0, float((n - 1) * dt_s if time_s is None else time_s[-1] - time_s[0])
    return window


def classify_record(response, point, design=None, *, window_s: tuple | None = None,
                    amplitude_window_s: tuple | None = None) -> Classification:
    """Classify a record response by the rules of :func:`classify`.

    Parameters
    ----------
    response : isolator.solver.base.SolverResult
        The response to the record: 1-D (all fields) or planar (regime and ζ; the rest
        None, see :data:`PLANAR_NOT_APPLICABLE`).
    point : isolator.adapter.DimensionlessPoint
        The record's equivalent dimensionless point (gives A0 and α, k, η).
    design : Design, optional
        Unused beyond the point's parameters; forces are per unit mass.
    window_s : tuple, optional
        Window [s] of the slip-time ratio ζ; the strong-motion window D5–95 by default.
    amplitude_window_s : tuple, optional
        Window [s] of the peak-to-peak displacement; the whole record by default.
        (A harmonic record's steady amplitude is read over its last periods.)

    Returns
    -------
    Classification
    """
    from isolator.solver.record import sample_timing

    t = response.time_s
    dt, unequal = sample_timing(t)
    ground = np.asarray(response.ground_acceleration_m_s2)
    planar = ground.ndim == 2
    one_block = not planar and getattr(response, "system", None) is not None  # the paper's block on one surface
    if window_s is None:  # D5–95 of the horizontal resultant: |a|² is the sum of the components' squares
        from isolator.motion.measures import energy_window_s

        window = energy_window_s([ground[:, 0], ground[:, 1]] if planar else [ground], dt, (0.05, 0.95),
                                 time_s=unequal)  # exact for the piecewise-linear components
        t0, t1 = (0.0, float(t[-1] - t[0])) if window is None else window  # a record of zeros: the whole record
        window_s = (t[0] + t0, t[0] + t1)
    w0, w1 = window_s
    intervals = slip_intervals(response)
    moved = intervals.shape[0] > 0
    overlap = np.clip(np.minimum(intervals[:, 1], w1) - np.maximum(intervals[:, 0], w0), 0.0, None)
    length = w1 - w0
    slip = float(overlap.sum())
    inside = [(a, b) for a, b in intervals if b > w0 and a < w1]
    # ζ = 1 exactly when one slip interval covers the whole window (no stick inside it)
    if moved and len(inside) == 1 and inside[0][0] <= w0 and inside[0][1] >= w1:
        zeta = 1.0
    else:
        zeta = min(slip / length, 1.0 - 1e-12) if length > 0 else 0.0
    # a block that slid only outside the window has ζ = 0 but moved: SS, not ST
    if not one_block:
        return Classification(source="record", regime=regime_from_slip(moved, zeta), zeta=float(zeta),
                              amplitude=None, amplified=None, dominant_force=None, rho_ev=None, rho_vf=None,
                              rho_ef=None, dominant_force_rho=None, window_s=(float(w0), float(w1)))
    x = np.asarray(response.displacement_m)
    v = np.asarray(response.velocity_m_s)
    if amplitude_window_s is not None:
        mask = (t >= amplitude_window_s[0]) & (t <= amplitude_window_s[1])
        x_window, v_window = x[mask], v[mask]
    else:
        x_window, v_window = x, v
    amplitude = 0.5 * (float(x_window.max()) - float(x_window.min())) / point.a0_m
    system = response.system
    # stuck throughout, the friction force is what holds the block: |a_g| ≤ µs g
    friction = system.kinetic_friction_m_s2 if moved else min(
        float(np.max(np.abs(response.ground_acceleration_m_s2))), system.static_friction_m_s2)
    peaks = (friction, system.stiffness_per_mass * float(np.max(np.abs(x_window))),
             system.damping_per_mass * float(np.max(np.abs(v_window))))
    return classify("record", moved, zeta, amplitude, peaks, point.alpha, point.k, point.eta,
                    point.mu_s, point.mu_k, (w0, w1))


def compare(record: Classification, harmonic: Classification) -> list[str]:
    """Sentences naming each disagreement between the record and the harmonic prediction."""
    notes = []
    if record.regime != harmonic.regime:
        notes.append(f"regime: the record gives {record.regime} ({REGIME_WORDS[record.regime]}, sliding "
                     f"{100 * record.zeta:.0f} % of the strong motion), the harmonic map predicts "
                     f"{harmonic.regime} ({REGIME_WORDS[harmonic.regime]}, zeta = {harmonic.zeta:.2f})")
    if record.amplified != harmonic.amplified:
        notes.append(f"amplification: the record gives A = {record.amplitude:.3g}, the harmonic map "
                     f"A = {harmonic.amplitude:.3g} (one above 1, the other not)")
    if record.dominant_force != harmonic.dominant_force:
        notes.append(f"dominant force: {record.dominant_force} for the record, "
                     f"{harmonic.dominant_force} for the harmonic map")
    return notes
