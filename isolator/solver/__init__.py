"""The solvers: the model registry (:mod:`.models`: select_model, simulate), the exact 1-D kernel, the 2-D engine,
the harmonic problem."""

from isolator.errors import InvalidSystemError, RecordInputError
from isolator.solver.base import SUMMARY_KEYS, Scene, SolverResult
from isolator.solver.harmonic import HarmonicResponse, alpha_sl_friction_only, harmonic_response
from isolator.solver.linear import linear_peak_displacement, pseudo_acceleration_spectrum
from isolator.solver.models import MODELS, select_model, simulate, simulate_motion
from isolator.solver.record import Response, simulate_record
from isolator.solver.system import System, classify_configuration
from isolator.solver.thresholds import RegimeThresholds, harmonic_thresholds

__all__ = [
    "HarmonicResponse", "RegimeThresholds", "alpha_sl_friction_only", "harmonic_response",
    "harmonic_thresholds", "linear_peak_displacement", "pseudo_acceleration_spectrum",
    "RecordInputError", "Response", "simulate_record", "InvalidSystemError", "System",
    "classify_configuration", "MODELS", "SUMMARY_KEYS", "Scene", "SolverResult", "select_model", "simulate",
    "simulate_motion",
]
