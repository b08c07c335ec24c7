"""One way to read a record: :func:`read_motion` for one component, a pair, or a pair with its vertical.

``read_motion(path, options)`` returns a :class:`~isolator.motion.GroundMotion` when
one component is asked for and a :class:`~isolator.motion.MotionPair` when a set is:
a second file (``options.pair``), a vertical file (``options.vertical``), or
``component="pair"`` / ``"all"`` (the components of one file or of a K-NET set).  The
command line, the batch and the Python API read through it, so that one file gives the
same motion whichever way it is read.

The units and the time step given apply the same way to every file of a set and to a
single file: with ``defaults=False`` (the command line) they must agree with a file that
states its own; with ``defaults=True`` (a batch that mixes formats) they are used only
for a file that does not state them: each file is read first as it is, and again with
the units (or the time step) when it raises :class:`~isolator.errors.MissingUnitsError`
(:class:`~isolator.errors.MissingTimeStepError`), by type, never by message.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from isolator.motion.ground_motion import GroundMotion
from isolator.motion.pair import PAIR_CHOICES, MotionPair, read_ground_motion_pair
from isolator.motion.read import read_ground_motion


@dataclass(frozen=True)
class RecordOptions:
    """How a record is read (hashable: a cache key).

    Attributes
    ----------
    component : str, optional
        The component of a multi-component file (see
        :func:`~isolator.motion.read_ground_motion`), or ``"pair"`` / ``"all"`` for the
        two horizontals (and the vertical) of one file or K-NET set [-].
    pair : str, optional
        The second horizontal component's file (Y) [-].
    vertical : str, optional
        The vertical component's file (Z) [-].
    units : {"g", "m/s2", "gal", "cm/s2"}, optional
        Units of the values for files that do not state them [-].
    dt_s : float, optional
        Time step of one-column text files [s].
    defaults : bool
        ``units`` and ``dt_s`` only for the files that do not state them (else they must
        agree with a file that does) [-].
    merge : bool
        Join segments of a channel with gaps [-].
    response : str, optional
        StationXML inventory whose response is removed [-].
    counts_factor : float, optional
        Units per count, for records in counts [unit/count].
    trim, resample : bool
        Repair the components of a set that differ (see :func:`~isolator.motion.pair.align`) [-].
    """

    component: str | None = None
    pair: str | None = None
    vertical: str | None = None
    units: str | None = None
    dt_s: float | None = None
    defaults: bool = False
    merge: bool = False
    response: str | None = None
    counts_factor: float | None = None
    trim: bool = False
    resample: bool = False

    @property
    def wants_set(self) -> bool:
        """True when more than one component is read (a second file, a vertical, ``pair``/``all``)."""
        return (self.pair is not None or self.vertical is not None
                or (self.component or "").lower() in PAIR_CHOICES)


def read_motion(path: str | Path, options: RecordOptions = RecordOptions()) -> GroundMotion | MotionPair:
    """Read one component, or the set of components ``options`` asks for, of a record.

    Parameters
    ----------
    path : str or path-like
        The record file (the X component of a set) [-].
    options : RecordOptions
        What to read and how [-].

    Returns
    -------
    GroundMotion or MotionPair
        A MotionPair when :attr:`RecordOptions.wants_set`, else a GroundMotion [m/s²].

    Raises
    ------
    RecordError
        One line naming the file and the problem (see
        :func:`~isolator.motion.read_ground_motion` and
        :func:`~isolator.motion.read_ground_motion_pair`).
    """
    reading = {"units": options.units, "dt_s": options.dt_s, "defaults": options.defaults, "merge": options.merge,
               "response": options.response, "counts_factor": options.counts_factor}
    if options.wants_set:
        return read_ground_motion_pair(path, options.pair, options.vertical, component=options.component,
                                       trim=options.trim, resample=options.resample, **reading)
    return read_ground_motion(path, component=options.component, **reading)
