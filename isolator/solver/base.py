"""What every solver model takes and returns: a :class:`Scene` and a :class:`SolverResult`.

The registry (:mod:`isolator.solver.models`) chooses the model a scene needs and runs it;
the models (:mod:`isolator.solver.record` for the exact 1-D kernel,
:mod:`isolator.solver.planar` for the 2-D engine, …) take a :class:`Scene` and return a
subclass of :class:`SolverResult`.  This module sits below both so that the models can
use these types without importing the registry (in the manner of
``scipy.integrate._ivp.base``).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

#: The scalar results every model reports, in the order of the analysis schema (``docs/schema.md``).
#: :meth:`SolverResult.summary` returns exactly these keys (plus a model's :attr:`~SolverResult.EXTRA_SUMMARY_KEYS`).
SUMMARY_KEYS = (
    "model", "model_reason",
    "peak_displacement_m", "residual_displacement_m", "residual_displacement_x_m", "residual_displacement_y_m",
    "peak_velocity_m_s", "peak_transmitted_acceleration_m_s2", "slip_time_s", "uplift_time_s", "n_uplifts",
    "n_events", "energy_input_J_per_kg", "energy_friction_J_per_kg", "energy_viscous_J_per_kg",
    "energy_kinetic_final_J_per_kg", "energy_potential_final_J_per_kg", "energy_balance_error_J_per_kg",
    "solver_seconds", "configuration", "solver_status",
)
#: Summary keys read from an attribute of another name.
_ATTRIBUTE_OF = {"solver_status": "message"}


@dataclass(frozen=True)
class Scene:
    """What a solver model is asked to solve: the ground motion and the isolator (SI units).

    Attributes
    ----------
    ax_m_s2 : numpy.ndarray
        First horizontal ground acceleration [m/s²], linear between samples.
    ay_m_s2, az_m_s2 : numpy.ndarray or None
        Second horizontal and vertical (up positive) ground acceleration [m/s²].
    dt_s : float or None
        Sample interval [s]; or give ``time_s``.
    time_s : numpy.ndarray or None
        Sample times [s], strictly increasing (unequal steps allowed).
    isolator : Mapping
        The keywords of :func:`isolator.solver.planar.simulate_pair`: ``mu_static``,
        ``mu_kinetic``, ``radius_m`` or ``stiffness_per_mass`` [1/s²], ``damping_per_mass``
        [1/s], ``gravity_m_s2`` [m/s²], or ``mu_slow``, ``mu_fast``, ``rate_s_per_m`` [s/m]
        for µ(v) (:func:`isolator.adapter.motion_keywords` gives them for a design); ``rtol``, the
        relative tolerance of the engine's steps (``simulate_pair``'s, and ``2d-multisurface``'s event
        kernel's in its ``RTOL_RANGE``; absent: the default).
    design : isolator.design.Design or None
        The design, for a model that needs more than the equivalent single bearing
        (a superstructure, a multi-surface bearing); None for a bare isolator.
    """

    ax_m_s2: np.ndarray
    ay_m_s2: np.ndarray | None = None
    az_m_s2: np.ndarray | None = None
    dt_s: float | None = None
    time_s: np.ndarray | None = None
    isolator: Mapping = field(default_factory=dict)
    design: object = None

    @property
    def has_y(self) -> bool:
        """A second horizontal component is given (even if it is zero)."""
        return self.ay_m_s2 is not None

    @property
    def has_z(self) -> bool:
        """A vertical component is given."""
        return self.az_m_s2 is not None

    @property
    def velocity_dependent(self) -> bool:
        """The friction is µ(v) (any of ``mu_slow``, ``mu_fast``, ``rate_s_per_m`` given)."""
        return any(self.isolator.get(k) is not None for k in ("mu_slow", "mu_fast", "rate_s_per_m"))

    @classmethod
    def of(cls, motion, isolator: Mapping, design=None) -> Scene:
        """The scene of a :class:`~isolator.motion.GroundMotion` or a :class:`~isolator.motion.MotionPair`.

        Parameters
        ----------
        motion : GroundMotion or MotionPair
            One component, or components ``x``, ``y``, ``z`` on one time base [m/s²].
        isolator : Mapping
            The isolator keywords (see the class docstring).
        design : Design, optional
            The design they come from.
        """
        parts = getattr(motion, "components", None)
        if not isinstance(parts, dict):
            parts = {"x": motion}
        return cls(ax_m_s2=parts["x"].acceleration_m_s2,
                   ay_m_s2=parts["y"].acceleration_m_s2 if "y" in parts else None,
                   az_m_s2=parts["z"].acceleration_m_s2 if "z" in parts else None,
                   dt_s=motion.dt_s, time_s=motion.sample_times_s, isolator=dict(isolator), design=design)


@dataclass(kw_only=True)
class SolverResult:
    """The one result type of the solver models (SI units; energies per unit mass [J/kg]).

    Every model returns a subclass with at least these fields; :meth:`summary` gives
    :data:`SUMMARY_KEYS` (attributes of the same name; ``solver_status`` is
    :attr:`message`).  A model that reports more scalars lists them in
    :attr:`EXTRA_SUMMARY_KEYS`.

    The energy input is the work of −M a_g on the relative motion (plus, on a pendulum
    with a vertical record, that of the vertical motion); the balance
    ``input = kinetic + potential + friction + viscous`` holds to
    ``energy_balance_error_J_per_kg``.
    """

    #: scalar keys a model adds to :data:`SUMMARY_KEYS` (attributes of the same names)
    EXTRA_SUMMARY_KEYS = ()
    #: words of the event codes in :attr:`event_kind`
    EVENT_NAMES = ("breakaway", "stick", "reversal")  # the codes of isolator.solver.events (numba-free here)

    time_s: np.ndarray
    ground_acceleration_m_s2: np.ndarray
    displacement_m: np.ndarray  #: block minus ground: (N,) along the one component, or (N, 2)
    velocity_m_s: np.ndarray
    absolute_acceleration_m_s2: np.ndarray  #: acceleration of the mass (transmitted)
    event_time_s: np.ndarray
    event_kind: np.ndarray  #: codes into :attr:`EVENT_NAMES`
    peak_displacement_m: float  #: resultant in the plane
    residual_displacement_m: float  #: signed along the component in 1-D; resultant in 2-D
    peak_velocity_m_s: float
    peak_transmitted_acceleration_m_s2: float
    slip_time_s: float  #: time with V ≠ 0 (sliding, or in flight) [s]
    n_events: int
    energy_input_J_per_kg: float
    energy_friction_J_per_kg: float
    energy_viscous_J_per_kg: float
    energy_kinetic_final_J_per_kg: float
    energy_potential_final_J_per_kg: float
    energy_balance_error_J_per_kg: float
    #: cumulative energies at the samples [J/kg], rows: input, friction, viscous
    energy_history_J_per_kg: np.ndarray
    status: int = 0
    message: str = "ok"
    solver_seconds: float = 0.0
    #: which model ran and why (set by :func:`isolator.solver.models.simulate`)
    model: str = ""
    model_reason: str = ""

    @property
    def event_names(self) -> list[str]:
        """Event kinds as words."""
        return [self.EVENT_NAMES[k] for k in self.event_kind]

    @property
    def is_planar(self) -> bool:
        """The histories are (N, 2): the response moves in the plane."""
        return np.ndim(self.displacement_m) == 2

    def summary(self) -> dict:
        """The scalar results under the analysis schema's names (:data:`SUMMARY_KEYS`, then the model's own)."""
        return {key: getattr(self, _ATTRIBUTE_OF.get(key, key)) for key in (*SUMMARY_KEYS, *self.EXTRA_SUMMARY_KEYS)}
