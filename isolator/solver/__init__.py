"""The exact event-driven solver: closed-form slip segments between stick/slip events."""

from isolator.solver.harmonic import HarmonicResponse, alpha_sl_friction_only, harmonic_response
from isolator.solver.linear import linear_peak_displacement, pseudo_acceleration_spectrum
from isolator.solver.record import RecordInputError, Response, simulate_record
from isolator.solver.system import InvalidSystemError, System, classify_configuration
from isolator.solver.thresholds import RegimeThresholds, harmonic_thresholds

__all__ = [
    "HarmonicResponse", "RegimeThresholds", "alpha_sl_friction_only", "harmonic_response",
    "harmonic_thresholds", "linear_peak_displacement", "pseudo_acceleration_spectrum",
    "RecordInputError", "Response", "simulate_record", "InvalidSystemError", "System",
    "classify_configuration",
]
