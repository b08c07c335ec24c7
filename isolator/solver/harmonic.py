r"""Harmonic driver: the paper's case, run to its periodic steady state.

Dimensionless form (Nicolas 2017, Eq. 2), with g = 1 and x(0) = ẋ(0) = 0, φ = π/2:

.. math::  \ddot x + \mu(\dot x)\,\mathrm{sign}(\dot x) + k x + \eta \dot x
           + \omega^2 \cos(\omega t + \varphi) = 0,\qquad \omega = \sqrt{\alpha\mu_s}.

It is the record model with ``a_g = ω² cos(ωt + φ)``, ``κ = k``, ``c = η``, solved by
the same closed forms (:func:`isolator.solver.segments.segment_state`).  Every
forcing period starts at local time 0 with phase φ, so times never grow.

The run goes period by period until the state at the period boundary repeats
(period 1 to :data:`MAX_SUBHARMONIC` forcing periods: the friction–spring coupling
has sub-harmonic responses), or, without damping, until the amplitude grows by the
same amount every period (resonance, Eq. 26: A_r = β t).  The steady cycle is then
replayed once with full bookkeeping: events, A, ζ (Eq. 3), ẋ_rms (Eq. 4), the
energies per period (Eqs. 8–11) and the force ratios (Eq. 5).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from isolator.errors import InvalidSystemError
from isolator.serialize import finite_or_none
from isolator.solver.events import BREAKAWAY, EVENT_NAMES, REVERSAL, STICK, find_stop, record_event
from isolator.solver.jit import njit
from isolator.solver.segments import harmonic_h1, ramp_basis, segment_state, state_from_basis
from isolator.solver.system import classify_configuration

PHASE_DEFAULT = 0.5 * math.pi  #: φ of the paper: zero ground acceleration at t = 0 [rad]
MAX_SUBHARMONIC = 8  #: longest steady cycle looked for, in forcing periods
PIECES_PER_PERIOD = 16  #: a slip piece spans at most 1/16 of the shortest period
STEADY_TOLERANCE = 1e-10  #: relative change of the period-boundary state deemed steady
MAX_PERIODS_DEFAULT = 3000

_GL_X, _GL_W = np.polynomial.legendre.leggauss(8)
_GL_NODES = 0.5 * (_GL_X + 1.0)
_GL_WEIGHTS = 0.5 * _GL_W

# state vector layout: x, v, stuck (1/0), s (±1), from_rest (1/0), exact_start (1/0)
_STATE_SIZE = 6
# metrics vector layout (accumulated over the periods advanced)
M_XMIN, M_XMAX, M_SLIP, M_DX_ABS, M_INT_V2, M_INT_VCOS, M_N_STICK, M_N_EVENTS, M_N_BREAK, M_CHATTER = range(10)
_METRICS_SIZE = 10
#: a slip from rest that lasts less than this phase [rad] was a grazing touch of µs
GRAZING_SKIP = 1e-12
#: safety net against chatter: events allowed in one forcing period
MAX_EVENTS_PER_PERIOD = 100_000


@njit(cache=True)
def _breakaway_phase(x_stuck, theta_now, kappa, omega, mu_s, min_delta):
    # Smallest Δθ ≥ min_delta after which |κ x + ω² cos θ| > µs: (Δθ, direction) or (-1, 0).
    # min_delta > 0 skips a crossing at the current phase that produced no motion
    # (the net force only touched µs: a grazing touch, not a break-away).
    w2 = omega * omega
    two_pi = 2.0 * math.pi
    theta_from = theta_now + min_delta
    force_now = kappa * x_stuck + w2 * math.cos(theta_from)
    if force_now > mu_s:
        return min_delta, -1
    if force_now < -mu_s:
        return min_delta, 1
    best = -1.0
    direction = 0
    c_up = (mu_s - kappa * x_stuck) / w2  # cos θ rises above this → slides backwards
    if c_up < 1.0:
        entry = two_pi - math.acos(max(c_up, -1.0))  # where cos θ increases through c_up
        delta = (entry - theta_from) % two_pi
        if delta > two_pi * (1.0 - 1e-13):
            delta = 0.0
        best = delta
        direction = -1
    c_down = (-mu_s - kappa * x_stuck) / w2  # cos θ falls below this → slides forwards
    if c_down > -1.0:
        entry = math.acos(min(c_down, 1.0))  # where cos θ decreases through c_down
        delta = (entry - theta_from) % two_pi
        if delta > two_pi * (1.0 - 1e-13):
            delta = 0.0
        if best < 0.0 or delta < best:
            best = delta
            direction = 1
    if best < 0.0:
        return -1.0, 0
    return best + min_delta, direction


@njit(cache=True)
def _advance_periods(n_periods, state, omega, kappa, c, mu_s, mu_k, phase0, piece_max,
                     record, ev_time, ev_kind, ev_x, t_out, x_out, v_out, metrics):
    """Advance ``n_periods`` forcing periods from ``state`` (updated in place).

    With ``record`` true, fills the events, the dense output at ``t_out`` (times
    from the start of this call) and the quadratures of the metrics.
    """
    period = 2.0 * math.pi / omega
    force = -omega * omega
    fast_rate = 0.5 * c + math.sqrt(abs(0.25 * c * c - kappa))  # largest |λ| of the free motion
    piece_e0, piece_e1, piece_h1, _, _ = ramp_basis(piece_max, c, kappa)
    piece_hc = harmonic_h1(piece_max, c, kappa, omega)
    x = state[0]
    v = state[1]
    stuck = state[2] != 0.0
    s = state[3]
    from_rest = state[4] != 0.0
    exact_start = state[5] != 0.0
    n_out = t_out.shape[0]
    i_out = 0
    metrics[M_XMIN] = x
    metrics[M_XMAX] = x
    for j in range(_METRICS_SIZE):
        if j > M_XMAX:
            metrics[j] = 0.0
    n_ev = 0
    grazing = False  # the last break-away slid for no time: skip that touch
    for n in range(n_periods):
        events_this_period = 0
        t0 = n * period
        t = 0.0
        while t < period:
            theta = phase0 + omega * t
            if stuck:
                dtheta, direction = _breakaway_phase(x, theta, kappa, omega, mu_s,
                                                     GRAZING_SKIP if grazing else 0.0)
                grazing = False
                if dtheta < 0.0 or t + dtheta / omega >= period:
                    # stuck to the end of the period
                    if record:
                        while i_out < n_out and t_out[i_out] <= t0 + period:
                            x_out[i_out] = x
                            v_out[i_out] = 0.0
                            i_out += 1
                    t = period
                    break
                t_b = t + dtheta / omega
                if record:
                    while i_out < n_out and t_out[i_out] <= t0 + t_b:
                        x_out[i_out] = x
                        v_out[i_out] = 0.0
                        i_out += 1
                    n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t0 + t_b, BREAKAWAY, x)
                metrics[M_N_BREAK] += 1.0
                metrics[M_N_EVENTS] += 1.0
                t = t_b
                theta = phase0 + omega * t
                stuck = False
                s = float(direction)
                from_rest = True
                exact_start = True
            rem = min(piece_max, period - t)
            if rem <= 0.0:
                break
            if exact_start:
                # the net force at break-away is exactly s (µs - µk)
                p = s * (mu_s - mu_k) + kappa * x - force * math.cos(theta)
            else:
                p = -mu_k * s
            if rem == piece_max:
                # full pieces recur: their basis was evaluated once
                x1, v1, a1, _ = state_from_basis(piece_e0, piece_e1, piece_h1, 0.0, piece_hc, rem, x, v, p, 0.0,
                                                 force, theta, c, kappa, omega)
            else:
                x1, v1, a1, _ = segment_state(rem, x, v, p, 0.0, force, theta, c, kappa, omega)
            a0 = p + force * math.cos(theta) - kappa * x - c * v
            t_stop, _, _ = find_stop(s, from_rest, rem, x, v, v1, a0, a1, p, 0.0, force, theta, c, kappa, omega)
            length = rem if t_stop < 0.0 else t_stop
            if t_stop < 0.0:
                x_end = x1
                v_end = v1
            else:
                x_end, _, _, _ = segment_state(t_stop, x, v, p, 0.0, force, theta, c, kappa, omega)
                v_end = 0.0
            if record:
                # quadratures of v² and v cos θ on the piece: composite 8-point
                # Gauss–Legendre, one sub-piece per time constant of the fastest exponent
                n_quad = min(4000, max(1, int(math.ceil(fast_rate * length))))
                sub = length / n_quad
                int_v2 = 0.0
                int_vcos = 0.0
                for jq in range(n_quad):
                    for k in range(_GL_NODES.shape[0]):
                        tk = sub * (jq + _GL_NODES[k])
                        _, vk, _, _ = segment_state(tk, x, v, p, 0.0, force, theta, c, kappa, omega)
                        int_v2 += _GL_WEIGHTS[k] * vk * vk
                        int_vcos += _GL_WEIGHTS[k] * vk * math.cos(theta + omega * tk)
                metrics[M_INT_V2] += int_v2 * sub
                metrics[M_INT_VCOS] += int_vcos * sub
                while i_out < n_out and t_out[i_out] <= t0 + t + length:
                    xo, vo, _, _ = segment_state(t_out[i_out] - t0 - t, x, v, p, 0.0, force, theta,
                                                 c, kappa, omega)
                    x_out[i_out] = xo
                    v_out[i_out] = vo
                    i_out += 1
            metrics[M_SLIP] += length
            metrics[M_DX_ABS] += abs(x_end - x)
            x = x_end
            v = v_end
            t += length
            from_rest = False
            exact_start = False
            if x < metrics[M_XMIN]:
                metrics[M_XMIN] = x
            if x > metrics[M_XMAX]:
                metrics[M_XMAX] = x
            if t_stop >= 0.0:
                force_now = kappa * x - force * math.cos(phase0 + omega * t)
                if abs(force_now) <= mu_s:
                    grazing = length <= GRAZING_SKIP / omega
                    stuck = True
                    kind = STICK
                    metrics[M_N_STICK] += 1.0
                else:
                    s = -1.0 if force_now > 0.0 else 1.0
                    from_rest = True
                    kind = REVERSAL
                metrics[M_N_EVENTS] += 1.0
                events_this_period += 1
                if events_this_period > MAX_EVENTS_PER_PERIOD:
                    metrics[M_CHATTER] = 1.0
                    stuck = True
                    v = 0.0
                    t = period
                if record:
                    n_ev = record_event(ev_time, ev_kind, ev_x, n_ev, t0 + t, kind, x)
    if record:
        # samples at the very end of the run (rounding of n·period) get the final state
        while i_out < n_out:
            x_out[i_out] = x
            v_out[i_out] = v
            i_out += 1
    state[0] = x
    state[1] = v
    state[2] = 1.0 if stuck else 0.0
    state[3] = s
    state[4] = 1.0 if from_rest else 0.0
    state[5] = 1.0 if exact_start else 0.0
    return n_ev


@njit(cache=True)
def _find_steady(omega, kappa, c, mu_s, mu_k, phase0, piece_max, max_periods, tolerance,
                 boundary_states, amplitudes):
    """Run periods until the boundary state repeats or the growth is linear.

    Returns (status, cycle, n_run, moved): status 0 periodic, 1 resonant growth,
    2 not converged; ``cycle`` the period multiple; ``boundary_states[n]`` the
    state at the start of period n; ``amplitudes[n]`` the half peak-to-peak of
    period n.
    """
    state = np.zeros(_STATE_SIZE)
    state[2] = 1.0  # starts stuck at rest
    empty = np.zeros(0)
    empty_kind = np.zeros(0, dtype=np.int8)
    metrics = np.zeros(_METRICS_SIZE)
    moved = False
    for n in range(max_periods):
        boundary_states[n, :] = state
        _advance_periods(1, state, omega, kappa, c, mu_s, mu_k, phase0, piece_max, False,
                         empty, empty_kind, empty, empty, empty, empty, metrics)
        amplitudes[n] = 0.5 * (metrics[M_XMAX] - metrics[M_XMIN])
        if metrics[M_N_EVENTS] > 0.0:
            moved = True
        boundary_states[n + 1, :] = state
        # relative to the motion itself (a stiff isolator moves by µs/k ≪ 1), down to a
        # floor below which the motion is rounding-level anyway
        scale = max(amplitudes[n], 1e-6)
        scale_v = scale * omega
        for p in range(1, MAX_SUBHARMONIC + 1):
            if n + 1 - p < 0:
                break
            prev = boundary_states[n + 1 - p]
            if (prev[2] == state[2] and prev[3] == state[3] and prev[4] == state[4]
                    and abs(prev[0] - state[0]) <= tolerance * scale
                    and abs(prev[1] - state[1]) <= tolerance * scale_v):
                return 0, p, n + 1, moved
        # undamped resonance: the amplitude grows by the same amount every period
        if c == 0.0 and n >= 60:
            d_last = amplitudes[n] - amplitudes[n - 1]
            if d_last > 0.0:
                linear = True
                for j in range(n - 29, n + 1):
                    dj = amplitudes[j] - amplitudes[j - 1]
                    if dj <= 0.0 or abs(dj - d_last) > 1e-3 * d_last:
                        linear = False
                        break
                if linear:
                    return 1, 1, n + 1, moved
    return 2, 1, max_periods, moved


@dataclass
class HarmonicResponse:
    """Steady periodic response to a harmonic ground motion (dimensionless, Eq. 2).

    Per forcing period τ = 2π/ω: ``energy_friction`` = ∆e_f (Eq. 9),
    ``energy_viscous`` = ∆e_v (Eq. 10) and ``work_input`` = ∆w_i (Eq. 11, the work of
    the inertia force, negative when the ground feeds energy in), so that
    ``energy_friction + energy_viscous + work_input = energy_balance_residual`` ≈ 0
    (Eq. 8).  Force ratios follow Eq. 5; they are ``None`` where undefined or
    infinite (η = 0 or µk = 0).
    """

    alpha: float
    k: float
    eta: float
    mu_s: float
    mu_k: float
    omega: float
    configuration: str
    regime: str
    zeta: float
    amplitude: float
    xdot_rms: float
    energy_friction: float
    energy_viscous: float
    work_input: float
    energy_balance_residual: float
    rho_ev: float | None
    rho_vf: float | None
    rho_ef: float | None
    dominant_force: str
    steady: bool
    growth_rate: float | None
    cycle_periods: int
    periods_run: int
    status: str
    cycle_time: np.ndarray = field(repr=False)
    cycle_x: np.ndarray = field(repr=False)
    cycle_xdot: np.ndarray = field(repr=False)
    event_time: np.ndarray = field(repr=False)
    event_kind: np.ndarray = field(repr=False)
    event_x: np.ndarray = field(repr=False)

    @property
    def event_names(self) -> list[str]:
        return [EVENT_NAMES[k] for k in self.event_kind]

    def summary(self) -> dict:
        """The numbers of ``isolator harmonic --json``."""
        return {
            "regime": self.regime,
            "zeta": self.zeta,
            "amplitude": self.amplitude,
            "xdot_rms": self.xdot_rms,
            "energy_friction": self.energy_friction,
            "energy_viscous": self.energy_viscous,
            "work_input": self.work_input,
            "energy_balance_residual": self.energy_balance_residual,
            "rho_ev": self.rho_ev,
            "rho_vf": self.rho_vf,
            "rho_ef": self.rho_ef,
            "dominant_force": self.dominant_force,
            "steady": self.steady,
            "growth_rate": self.growth_rate,
            "cycle_periods": self.cycle_periods,
            "periods_run": self.periods_run,
            "configuration": self.configuration,
            "alpha": self.alpha,
            "k": self.k,
            "eta": self.eta,
            "mu_s": self.mu_s,
            "mu_k": self.mu_k,
            "omega": self.omega,
        }


def force_ratios(k: float, eta: float, alpha: float, mu_s: float, mu_k: float, amplitude: float):
    r"""The paper's force ratios (Eq. 5) and the dominant force.

    .. math::  \rho_{ev} = \frac{k^2}{\eta^2\alpha\mu_s},\quad
               \rho_{vf} = \frac{\eta^2 A^2 \alpha\mu_s}{\mu_k^2},\quad
               \rho_{ef} = \frac{k A}{\mu_k}

    The dominant force is the largest of the elastic kA, viscous ηAω and friction µk
    force amplitudes (ω = sqrt(α µs)).

    Returns
    -------
    tuple
        ``(rho_ev, rho_vf, rho_ef, dominant)``; a ratio is ``None`` where it is 0/0 or
        infinite; ``dominant`` is ``"friction"``, ``"viscous"`` or ``"elastic"``.
    """
    omega = math.sqrt(alpha * mu_s)
    elastic = k * amplitude
    viscous = eta * amplitude * omega
    friction = mu_k

    def ratio(num, den):
        if den == 0.0:
            return None
        return finite_or_none(num / den)

    rho_ev = ratio(k * k, eta * eta * alpha * mu_s)
    rho_vf = ratio(eta * eta * amplitude * amplitude * alpha * mu_s, mu_k * mu_k)
    rho_ef = ratio(k * amplitude, mu_k)
    forces = {"friction": friction, "viscous": viscous, "elastic": elastic}
    dominant = max(forces, key=forces.get)
    return rho_ev, rho_vf, rho_ef, dominant


#: Largest α, k and η accepted [-].  The paper's maps span k ≤ 6, α ≤ 10, η ≤ 1; the work per
#: forcing period grows as sqrt(k / (α µs)) pieces (k = 1e9 takes 5 s, 1e12 minutes), and
#: beyond 1e6 the block is either rigid or sliding freely: nothing left to compute.
MAX_DIMENSIONLESS = 1e6


#: Static friction coefficients of the harmonic problem [-] (issue 26: µs = 1e-300 and µs = 2 were accepted).
MU_S_RANGE = (1e-4, 1.0)


def validate_harmonic_parameters(alpha: float, k: float, eta: float, mu_s: float, mu_k: float) -> None:
    """Refuse dimensionless parameters outside the harmonic problem's domain (paper, Eq. 2).

    Parameters
    ----------
    alpha, k, eta : float
        Forcing level, stiffness and damping of Eq. 2, finite, ≥ 0 and ≤ :data:`MAX_DIMENSIONLESS`;
        α > 0 [-].
    mu_s, mu_k : float
        Static and kinetic friction coefficients, 0 ≤ µk ≤ µs, µs > 0 [-].

    Raises
    ------
    InvalidSystemError
        One line naming the parameter and the bound it breaks.
    """
    for name, value in (("alpha", alpha), ("k", k), ("eta", eta), ("mu_s", mu_s)):
        if not math.isfinite(value) or value < 0.0:
            raise InvalidSystemError(f"{name} must be a finite number ≥ 0, got {value!r}")
        if name != "mu_s" and value > MAX_DIMENSIONLESS:
            raise InvalidSystemError(f"{name} = {value:g} exceeds {MAX_DIMENSIONLESS:g}: beyond it the block is "
                                     "rigid or slides freely, and the work per period grows without bound")
    if alpha <= 0.0:
        raise InvalidSystemError(f"alpha must be > 0, got {alpha!r}")
    if mu_s <= 0.0:
        raise InvalidSystemError(f"mu_s must be > 0 (α is defined relative to µs g), got {mu_s!r}")
    if not MU_S_RANGE[0] <= mu_s < MU_S_RANGE[1]:
        raise InvalidSystemError(f"mu_s = {mu_s:g} must lie in [{MU_S_RANGE[0]:g}, {MU_S_RANGE[1]:g}): a friction "
                                 "coefficient (sliding isolators have 0.02-0.15; below 1e-4 the forcing period "
                                 "2π/√(α µs) of Eq. 2 grows without bound, at 1 friction exceeds the weight)")
    if not math.isfinite(mu_k) or mu_k < 0.0 or mu_k > mu_s:
        raise InvalidSystemError(f"mu_k must lie in [0, mu_s = {mu_s}], got {mu_k!r}")


def _discretisation(alpha: float, k: float, eta: float, mu_s: float) -> tuple[float, float, float]:
    """(ω, forcing period, longest slip piece) of a harmonic problem, in Eq. 2 units."""
    omega = math.sqrt(alpha * mu_s)
    period = 2.0 * math.pi / omega
    # pieces resolve the forcing and the damped oscillation; an over-damped system adds
    # no oscillation (its fast exponential only decays), so it needs no shorter pieces
    shortest = period
    d2 = 0.25 * eta * eta - k
    if d2 < 0.0:
        shortest = min(shortest, 2.0 * math.pi / math.sqrt(-d2))
    return omega, period, shortest / PIECES_PER_PERIOD


def harmonic_response(alpha: float, k: float, eta: float, mu_s: float, mu_k: float | None = None, *,
                      phase: float = PHASE_DEFAULT, max_periods: int = MAX_PERIODS_DEFAULT,
                      samples_per_period: int = 200) -> HarmonicResponse:
    """Steady response of the block to a harmonic ground motion (the paper's problem).

    Parameters
    ----------
    alpha : float
        Reduced acceleration α = A0 Ω² / (µs g) [-] (Eq. 6).
    k : float
        Dimensionless stiffness k = K A0 / (M g) [-].
    eta : float
        Dimensionless damping η = (γ/M) sqrt(A0/g) [-].
    mu_s, mu_k : float
        Static and kinetic friction coefficients [-]; µk defaults to µs (model 1).
    phase : float
        φ [rad]; π/2 (the paper's choice) starts from zero ground acceleration.
    max_periods : int
        Give up looking for a steady state after this many forcing periods.
    samples_per_period : int
        Dense output of the steady cycle, per forcing period.

    Returns
    -------
    HarmonicResponse
    """
    mu_k = mu_s if mu_k is None else mu_k
    alpha, k, eta, mu_s, mu_k = (float(alpha), float(k), float(eta), float(mu_s), float(mu_k))
    validate_harmonic_parameters(alpha, k, eta, mu_s, mu_k)
    omega, period, piece_max = _discretisation(alpha, k, eta, mu_s)
    boundary_states = np.zeros((max_periods + 1, _STATE_SIZE))
    amplitudes = np.zeros(max_periods)
    status, cycle, n_run, moved = _find_steady(omega, k, eta, mu_s, mu_k, phase, piece_max, max_periods,
                                               STEADY_TOLERANCE, boundary_states, amplitudes)
    growth_rate = None
    if status == 1:
        growth_rate = float((amplitudes[n_run - 1] - amplitudes[n_run - 2]) / period)
    # replay the steady cycle (or the last period) with full bookkeeping
    start = n_run - cycle
    state = boundary_states[start].copy()
    n_samples = samples_per_period * cycle
    t_out = np.linspace(0.0, cycle * period, n_samples + 1)
    x_out = np.empty_like(t_out)
    v_out = np.empty_like(t_out)
    capacity = 64 * cycle
    metrics = np.zeros(_METRICS_SIZE)
    while True:
        ev_time = np.empty(capacity)
        ev_kind = np.empty(capacity, dtype=np.int8)
        ev_x = np.empty(capacity)
        n_ev = _advance_periods(cycle, state, omega, k, eta, mu_s, mu_k, phase, piece_max, True,
                                ev_time, ev_kind, ev_x, t_out, x_out, v_out, metrics)
        if n_ev <= capacity:
            break
        capacity = n_ev + 16
        state = boundary_states[start].copy()
    total_time = cycle * period
    amplitude = 0.5 * (metrics[M_XMAX] - metrics[M_XMIN])
    zeta = metrics[M_SLIP] / total_time
    if not moved and metrics[M_N_EVENTS] == 0:
        regime = "ST"
        zeta = 0.0
    elif metrics[M_N_STICK] == 0 and metrics[M_N_BREAK] == 0 and zeta > 0.0:
        regime = "SL"
        zeta = 1.0  # exact: no stick in the steady cycle
    elif metrics[M_N_EVENTS] == 0 and zeta == 0.0:
        regime = "ST"  # moved during the transient, then stuck for good
    else:
        regime = "SS"
    energy_friction = mu_k * metrics[M_DX_ABS] / cycle
    energy_viscous = eta * metrics[M_INT_V2] / cycle
    work_input = omega * omega * metrics[M_INT_VCOS] / cycle
    rho_ev, rho_vf, rho_ef, dominant = force_ratios(k, eta, alpha, mu_s, mu_k, amplitude)
    status_text = {0: "steady", 1: "resonant growth", 2: "no steady state within max_periods"}[status]
    if metrics[M_CHATTER]:
        status_text += f"; chatter guard: more than {MAX_EVENTS_PER_PERIOD} events in a period"
    return HarmonicResponse(
        alpha=alpha, k=k, eta=eta, mu_s=mu_s, mu_k=mu_k, omega=omega,
        configuration=classify_configuration(eta, k),
        regime=regime, zeta=float(zeta), amplitude=float(amplitude),
        xdot_rms=float(math.sqrt(metrics[M_INT_V2] / total_time)),
        energy_friction=float(energy_friction), energy_viscous=float(energy_viscous),
        work_input=float(work_input),
        energy_balance_residual=float(energy_friction + energy_viscous + work_input),
        rho_ev=rho_ev, rho_vf=rho_vf, rho_ef=rho_ef, dominant_force=dominant,
        steady=status == 0, growth_rate=growth_rate, cycle_periods=int(cycle), periods_run=int(n_run),
        status=status_text,
        cycle_time=t_out, cycle_x=x_out, cycle_xdot=v_out,
        event_time=ev_time[:n_ev], event_kind=ev_kind[:n_ev], event_x=ev_x[:n_ev],
    )


@dataclass
class HarmonicTransient:
    """The response from rest over a whole number of forcing periods, sampled on the last one.

    Dimensionless (Eq. 2, g = 1); ``amplitude``, ``slip_ratio`` and ``n_events`` are
    those of the last period, ``residual`` is x at the end of the run.
    """

    time: np.ndarray  #: sample times (from the start of the run) [-]
    x: np.ndarray  #: relative displacement at ``time`` [-]
    xdot: np.ndarray  #: relative velocity at ``time`` [-]
    amplitude: float  #: half peak-to-peak of x on the last period [-]
    residual: float  #: x at the end of the run [-]
    slip_ratio: float  #: slip time / period on the last period (ζ, Eq. 3) [-]
    n_events: int  #: break-aways, stops and reversals on the last period [-]


def harmonic_transient(alpha: float, k: float, eta: float, mu_s: float, mu_k: float | None = None, *,
                       n_periods: int, times, phase: float = PHASE_DEFAULT) -> HarmonicTransient:
    """Exact response from rest to ``n_periods`` forcing periods of Eq. 2, sampled on the last one.

    :func:`harmonic_response` gives the steady cycle; this gives the transient that leads
    to it (or that never ends, at undamped resonance), with the same kernel and pieces.

    Parameters
    ----------
    alpha, k, eta : float
        Reduced acceleration, stiffness and damping (Eq. 6) [-].
    mu_s, mu_k : float
        Friction coefficients; µk defaults to µs [-].
    n_periods : int
        Forcing periods run from rest, ≥ 1 [-].
    times : array_like
        Increasing sample times inside the last period, from the start of the run [-]
        (times that rounding puts just outside it are clipped to it).
    phase : float
        φ [rad], π/2 by default (Eq. 2).

    Returns
    -------
    HarmonicTransient
    """
    mu_k = mu_s if mu_k is None else mu_k
    alpha, k, eta, mu_s, mu_k = (float(alpha), float(k), float(eta), float(mu_s), float(mu_k))
    validate_harmonic_parameters(alpha, k, eta, mu_s, mu_k)
    n_periods = int(n_periods)
    if n_periods < 1:
        raise InvalidSystemError(f"n_periods must be >= 1, got {n_periods}")
    omega, period, piece_max = _discretisation(alpha, k, eta, mu_s)
    start = (n_periods - 1) * period
    t_out = np.clip(np.asarray(times, dtype=np.float64) - start, 0.0, period)
    state = np.zeros(_STATE_SIZE)
    state[2] = 1.0  # at rest, stuck
    metrics = np.zeros(_METRICS_SIZE)
    empty = np.zeros(0)
    if n_periods > 1:
        _advance_periods(n_periods - 1, state, omega, k, eta, mu_s, mu_k, phase, piece_max, False,
                         empty, np.zeros(0, dtype=np.int8), empty, empty, empty, empty, metrics)
    x_out = np.empty_like(t_out)
    v_out = np.empty_like(t_out)
    capacity = 256
    boundary = state.copy()
    while True:  # bounded: the second pass has room for every event of the first
        ev_time = np.empty(capacity)
        ev_kind = np.empty(capacity, dtype=np.int8)
        ev_x = np.empty(capacity)
        n_ev = _advance_periods(1, state, omega, k, eta, mu_s, mu_k, phase, piece_max, True,
                                ev_time, ev_kind, ev_x, t_out, x_out, v_out, metrics)
        if n_ev <= capacity:
            break
        capacity = n_ev + 16
        state = boundary.copy()
    return HarmonicTransient(time=t_out + start, x=x_out, xdot=v_out,
                             amplitude=float(0.5 * (metrics[M_XMAX] - metrics[M_XMIN])),
                             residual=float(state[0]), slip_ratio=float(metrics[M_SLIP] / period),
                             n_events=int(n_ev))


def alpha_sl_friction_only(mu_s: float, mu_k: float | None = None) -> float:
    r"""Closed-form permanent-slip threshold of configuration 1 (Eq. 15).

    .. math::  \alpha_{SL} = \sqrt{1 + \frac{\pi^2}{4}\left(\frac{\mu_k}{\mu_s}\right)^2}
    """
    mu_k = mu_s if mu_k is None else mu_k
    return math.sqrt(1.0 + (math.pi ** 2 / 4.0) * (mu_k / mu_s) ** 2)
