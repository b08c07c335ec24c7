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
    │   ├── ComponentMismatchError    the components of a pair differ in time step, length or start time
    │   ├── GapsError                 gaps or several segments of a channel, not merged
    │   ├── CountsError               integer counts without a response or a counts factor
    │   ├── InstrumentResponseError   the instrument response cannot be removed
    │   └── RecordOptionError         a reading option that is wrong in itself (``parameter`` says which)
    ├── MotionError                   a ground-motion operation that cannot be done (array, processing, scaling)
    ├── UnitsError                    an acceleration unit isolator does not know
    ├── DesignError                   a design file or mapping that is not a valid isolator
    ├── InvalidSystemError            solver parameters out of their domain (µk > µs, α ≤ 0 …)
    ├── RecordInputError              arrays the solver cannot take (non-uniform time, NaN …)
    ├── BatchError                    a batch that cannot be planned (designs file, record patterns, grid)
    ├── ReviewError                   a review input (parameter, code, scaling, period range) that cannot be used
    │   ├── TargetError               an invalid target spectrum file
    │   └── SuiteError                an invalid suite (file, pair, duplicate, mismatched components)
    └── CacheEntryError               a damaged regime-map cache entry (never reaches the user: the map is recomputed)

:func:`one_line` is the one place a message (or an exception's text) is folded onto one line, :func:`printable`
the one place a name or a value holding control or format characters is shown escaped (the design's name check
and every line the commands print).
"""

from __future__ import annotations


def one_line(message) -> str:
    """``message`` (any object: an exception, a string) as one line, runs of white space as one blank [-]."""
    return " ".join(str(message).split())


def key_hint(key, valid, listed: str = "valid keys") -> str:
    """The hint after "unknown key 'KEY'" of a TOML file: the valid key it meant, or the valid keys [-].

    ``Mass_kg`` and ``MASS_KG`` are ``mass_kg`` typed in another case (TOML keys are case-sensitive): the hint says
    so.  Keys are compared without case, then by likeness (:func:`difflib.get_close_matches`, cutoff 0.5); with no
    likely key, ``listed`` and every valid key.  ``MASS_KG`` and a target's ``s_ms`` were told the whole list
    (session 23 sweep): the likeness alone is case-sensitive.
    """
    import difflib

    valid = [str(item) for item in valid]
    text = str(key)
    same = [item for item in valid if item.lower() == text.lower()]
    if same:
        return f" (did you mean '{same[0]}'? keys are case-sensitive)"
    folded = {item.lower(): item for item in valid}
    close = difflib.get_close_matches(text.lower(), list(folded), n=1, cutoff=0.5)
    if close:
        return f" (did you mean '{folded[close[0]]}'?)"
    return f" ({listed}: {', '.join(valid)})"


def one_table_problem(value, table: str) -> str | None:
    """What is wrong with an array of tables ``[[table]]`` written ``[table]``, one bracket (TOML then reads one
    table): "found none" or "needs at least one entry" was said of it (session 24 sweep); None when ``value`` is not
    one table.  ``table`` is the array's full name (``superstructure.floor``), its key the last part."""
    if not isinstance(value, dict):
        return None
    key = table.rsplit(".", 1)[-1]
    return f"'{key}' is one table ([{table}]); write each {key} as [[{table}]], double brackets"


def printable(text) -> str:
    """``text`` with every character a terminal would act on shown as its escape (``\\x1b``, ``\\u202e``) [-].

    A file name, a header field or a flag's value is printed in errors, notes and tables: a name holding ESC
    sequences set the terminal's title or colours (``info $'nope\\x1b]0;title\\x07.AT2'`` printed them raw on
    stderr; click strips only colour codes, and only off a terminal), and a right-to-left override shows a name
    reversed (session 16 sweep).  Control and format characters are escaped; letters of any script stay.
    """
    text = str(text)
    if text.isprintable():
        return text
    return "".join(ch if ch.isprintable() else _escape(ch) for ch in text)


def _escape(ch: str) -> str:
    """One character as its escape; a byte of a file name that is not UTF-8 (a surrogate of Python's reading of
    it) as that byte, ``\\xe9``."""
    if 0xDC80 <= ord(ch) <= 0xDCFF:
        return f"\\x{ord(ch) - 0xDC00:02x}"
    return ch.encode("unicode_escape").decode("ascii")


def analysis_owner(records, design_source: str | None = None) -> str:
    """Who an analysis that could not be done belongs to: ``DESIGN under RECORD`` (the record alone without a
    design file); ``records`` is one path or the files of a set (X, then its --pair and --vertical files) [-]."""
    files = [str(r) for r in ([records] if isinstance(records, str) else records) if r]
    where = " + ".join(files) or "the record"
    return f"{design_source} under {where}" if design_source else where


def owned(owner: str, message, file: str | None = None) -> str:
    """``owner: message`` on one line, unless the message names the owner first already.

    An engine's refusal (a rim it does not model, its step-size floor, lift-off, its work bound) names the
    instant, not the files; ``file``: the message's own first name (a design's ``D.toml: ``), replaced by the
    owner rather than said twice.
    """
    message = one_line(message)
    if message.startswith(f"{owner}:"):
        return message
    if file and message.startswith(f"{file}: "):
        message = message[len(file) + 2:]
    return f"{owner}: {message}"


class IsolatorError(ValueError):
    """Base of every error isolator raises for a user's input (one-line message)."""

    #: Name of the library parameter the error concerns ("units", "dt_s", "component" …), or "".
    parameter: str = ""

    def __init__(self, message: str = "", *, parameter: str | None = None):
        super().__init__(one_line(message))
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


class ComponentMismatchError(RecordError):
    """The components of a pair (and a vertical) differ in time step, length or start time.

    Attributes
    ----------
    kind : {"dt", "length", "start"}
        What differs [-].
    """

    def __init__(self, message: str = "", *, kind: str = "", path: str = "", given=None,
                 parameter: str | None = None):
        super().__init__(message, path=path, given=given, parameter=parameter)
        self.kind = kind

    def located(self, path, prefix: str = "") -> RecordError:
        located = super().located(path, prefix)
        located.kind = self.kind
        return located


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


class SolverError(IsolatorError):
    """A solver that could not finish (its step guard tripped): no answer is given, never a cut-short one."""


class RecordInputError(IsolatorError):
    """Arrays the solver cannot take: non-uniform or non-increasing time, NaN, fewer than two samples."""


class BatchError(IsolatorError):
    """A batch that cannot be planned: designs file, record patterns, grid specification, scheduler."""


class MotionError(IsolatorError):
    """A ground-motion operation that cannot be done: an array that is not a record, a processing
    parameter out of range (band-pass corners, resampling step, trim window), a filter on unequal
    steps, a scaling target outside [1e-6 g, 50 g] or a record of zeros to scale."""


class ReviewError(IsolatorError):
    """A review input (target, suite, parameter, code, scaling method) that cannot be used."""


class TargetError(ReviewError):
    """An invalid target spectrum file."""


class SuiteError(ReviewError):
    """An invalid suite (file, pair, duplicate, mismatched components)."""


class CacheEntryError(IsolatorError):
    """A damaged or foreign regime-map cache entry; the map is recomputed (never shown to the user)."""
