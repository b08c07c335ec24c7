"""Ground motion: a recorded acceleration history in m/s², its processing and intensity measures.

:func:`read_ground_motion` turns a record file — anything :func:`obspy.read` reads
(MiniSEED, SAC, K-NET, GSE2, SEISAN, …) plus isolator's own plugins (PEER AT2, CSMIP V2,
USGS SMC, plain text, see :mod:`isolator.io`) — into a :class:`GroundMotion`: one obspy
``Trace`` of float64 acceleration in m/s², with where its units came from, its
provenance and the list of processing steps applied.  Every malformed input raises
:class:`RecordError`, a one-line message naming the file and the problem.

Units are never guessed: they come from the file (AT2: g; V2, SMC: cm/s²; K-NET: the
header's scale factor; SAC: ``kuser0``), from an instrument response (StationXML), or
from the caller (``units=``, the CLI's ``--units``).  A record whose units are known
from nowhere is refused.

Reading applies no processing, with one exception that follows the data provider's own
convention: K-NET records have their mean removed (NIED's "counts × scale factor, minus
the mean").  It is recorded in :attr:`GroundMotion.processing` like any other step.
Processing methods (:meth:`GroundMotion.demeaned`, :meth:`~GroundMotion.tapered`,
:meth:`~GroundMotion.bandpassed`, …) use obspy's Trace methods and return a new object.
"""

from isolator.errors import ComponentMismatchError, RecordError
from isolator.motion.components import UNNAMED_COMPONENT
from isolator.motion.examples import EXAMPLE_RECORDS, resolve_record
from isolator.motion.ground_motion import MAX_ABS_ACCELERATION_G, MIN_SAMPLES, GroundMotion
from isolator.motion.load import RecordOptions, read_motion
from isolator.motion.measures import (
                                      PREDOMINANT_PERIODS_S,
                                      IntensityMeasures,
                                      arias_intensity_m_s,
                                      displacement_m,
                                      intensity_measures,
                                      significant_duration_s,
                                      velocity_m_s,
)
from isolator.motion.pair import MotionPair, read_ground_motion_pair
from isolator.motion.read import (
                                      TEXT_SUFFIXES,
                                      list_components,
                                      read_ground_motion,
                                      read_ground_motions,
)
from isolator.motion.spectra import DEFAULT_DAMPING_RATIO, pseudo_acceleration_spectrum

__all__ = ["RecordOptions", "read_motion", "DEFAULT_DAMPING_RATIO", "EXAMPLE_RECORDS", "MAX_ABS_ACCELERATION_G", "MIN_SAMPLES",
           "PREDOMINANT_PERIODS_S", "TEXT_SUFFIXES", "UNNAMED_COMPONENT", "GroundMotion", "IntensityMeasures",
           "RecordError", "ComponentMismatchError", "MotionPair", "read_ground_motion_pair", "arias_intensity_m_s", "displacement_m", "intensity_measures", "list_components",
           "pseudo_acceleration_spectrum", "read_ground_motion", "read_ground_motions", "resolve_record", "significant_duration_s",
           "velocity_m_s"]
