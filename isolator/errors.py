"""Typed errors: callers catch them by type, never by matching message text.

Every error isolator raises for a user's input derives from :class:`IsolatorError`
(and from :class:`ValueError`, so code written against the older plain errors keeps
working).  Messages are one line and say what is wrong with the file or the value;
they never name a command-line flag.  The command line adds which flag fixes it, by
type (:data:`isolator.cli.common.FLAG_HINTS`), and the batch runner decides what to
retry by type (:class:`MissingUnitsError`, :class:`MissingTimeStepError`).

Hierarchy::

    IsolatorError
    ├── RecordError                   a record file that cannot become a ground motion
    │   ├── RecordNotFoundError       missing, a folder, unreadable, empty
    │   ├── RecordFormatError         unrecognised or damaged content (truncated, text in a column …)
    │   ├── RecordValuesError         bad values: NaN, too few samples, |a| > 50 g, dt out of range, all zero
    │   ├── MissingUnitsError         the file does not state its units and none were given
    │   ├── UnitsConflictError        the units given disagree with the file's
    │   ├── MissingTimeStepError      a one-column file without a time step, none given
    │   ├── TimeStepConflictError     the time step given disagrees with the file's
    │   ├── ComponentError            several components and none chosen, or an unknown/ambiguous choice
    │   ├── GapsError                 gaps or several segments of a channel, not merged
    │   ├── CountsError               integer counts without a response or a counts factor
    │   ├── InstrumentResponseError   the instrument response cannot be removed
    │   └── RecordOptionError         a reading option that is wrong in itself (``parameter`` says which)
    ├── UnitsError                    an acceleration unit isolator does not know
    ├── DesignError                   a design file or mapping that is not a valid isolator
    ├── InvalidSystemError            solver parameters out of their domain (µk > µs, α ≤ 0 …)
    ├── RecordInputError              arrays the solver cannot take (non-uniform time, NaN …)
    └── BatchError                    a batch that cannot be planned (designs file, record patterns, grid)
"""

from __future__ import annotations


class IsolatorError(ValueError):
    """Base of every error isolator raises for a user's input (one-line message)."""

    #: Name of the library parameter the error concerns ("units", "dt_s", "component" …), or "".
    parameter: str = ""

    def __init__(self, message: str = "", *, parameter: str | None = None):
        super().__init__(" ".join(str(message).split()))
        if parameter is not None:
            self.parameter = parameter


class RecordError(IsolatorError):
    """A record that cannot be turned into a ground motion; the message names the file.

    Attributes
    ----------
    path : str
        The record file ("" when raised by a reader that does not know it).
    given : object
        The value given by the caller that the error concerns, if any (e.g. the units).
    """

    def __init__(self, message: str = "", *, path: str = "", given=None, parameter: str | None = None):
        super().__init__(message, parameter=parameter)
        self.path = str(path)
        self.given = given

    def located(self, path, prefix: str = "") -> RecordError:
        """The same error (same type and attributes) with ``path: prefix`` in front of its message."""
        head = f"{path}: {prefix}: " if prefix else f"{path}: "
        return type(self)(head + str(self), path=str(path), given=self.given, parameter=self.parameter)


class RecordNotFoundError(RecordError):
    """The record file is missing, is a folder, cannot be opened or is empty."""


class RecordFormatError(RecordError):
    """Unrecognised or damaged record content (binary garbage, truncated data, text in a column …)."""


class RecordValuesError(RecordError):
    """Values that cannot be ground acceleration: NaN/inf, too few samples, |a| > 50 g, bad time step."""


class MissingUnitsError(RecordError):
    """The file does not state its units and none were given."""

    parameter = "units"


class UnitsConflictError(RecordError):
    """The units given disagree with the units the file states (``given`` holds them)."""

    parameter = "units"


class MissingTimeStepError(RecordError):
    """A one-column file gives no time step and none was given."""

    parameter = "dt_s"


class TimeStepConflictError(RecordError):
    """The time step given disagrees with the file's (``given`` holds it) [s]."""

    parameter = "dt_s"


class ComponentError(RecordError):
    """Several components and none chosen, or a choice that matches none or several."""

    parameter = "component"


class GapsError(RecordError):
    """Gaps, overlaps or several segments of a channel that were not asked to be merged."""

    parameter = "merge"


class CountsError(RecordError):
    """Integer counts with no instrument response or counts factor to turn them into acceleration."""

    parameter = "counts_factor"


class InstrumentResponseError(RecordError):
    """The instrument response cannot be read or removed."""

    parameter = "response"


class RecordOptionError(RecordError):
    """A reading option that is wrong in itself; ``parameter`` names it (``dt_s``, ``units`` …)."""


class UnitsError(IsolatorError):
    """An acceleration unit that isolator does not know."""

    parameter = "units"


class DesignError(IsolatorError):
    """A design file or mapping that is not a valid isolator; the message names the file and the key."""


class InvalidSystemError(IsolatorError):
    """Solver or harmonic-problem parameters outside their domain (µk > µs, α ≤ 0, negative stiffness …)."""


class RecordInputError(IsolatorError):
    """Arrays the solver cannot take: non-uniform or non-increasing time, NaN, fewer than two samples."""


class BatchError(IsolatorError):
    """A batch that cannot be planned: designs file, record patterns, grid specification, scheduler."""
