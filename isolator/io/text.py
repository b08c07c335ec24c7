"""Plain-text accelerograms as an obspy waveform plugin (format ``ISOLATOR_TEXT``).

Accepted layouts: two columns (time [s], acceleration) or one column (acceleration, with
the time step given separately); comma, semicolon or whitespace separated; comment lines
starting with ``#``, ``%`` or ``!``; at most one leading row of column names; any line
ending; no final newline needed.

Metadata in comment lines, all optional, ``key: value`` or ``key = value``::

    # units: g            (g, m/s2, gal, cm/s2 — see isolator.units; or the acceleration
                          column's name: ``acc_g``, ``a (cm/s2)``; both must agree)
    # dt_s: 0.01          (time step for a one-column file) [s]
    # station: El Centro
    # component: 180

Detection is deliberately narrow.  Almost any text file of numbers *could* be an
accelerogram, and a loose ``_is_text`` would make obspy's autodetection claim every
unknown text file (other obspy text formats, tables, logs) as ours.  So ``_is_text``
answers True only for files that carry our explicit ``# units:`` metadata line in their
leading comments **and** whose first data lines are all one or two numeric columns.
Everything else is read as text only when asked for explicitly, with
``obspy.read(path, format="ISOLATOR_TEXT")``, which is what
:func:`isolator.motion.read_ground_motion` does for a text file that no other reader
claims.

The reader does not convert units: it records ``stats.units`` only if the file states
them; otherwise the caller must (``--units``).

A time column need not be evenly spaced (digitised analogue records are not): steps
equal to within printing round-off give one step ``stats.delta``; unequal steps are kept
as ``stats.isolator_text.time_s`` (times from the first sample [s]), with ``stats.delta``
their mean, and the record is solved as the piecewise-linear signal through them.
"""

from __future__ import annotations

import re

import numpy as np
from obspy import Stream, Trace, UTCDateTime
from obspy.core.util import AttribDict

from isolator.errors import MissingTimeStepError, RecordFormatError, TimeStepConflictError
from isolator.io._common import (
    head_lines,
    looks_like_text,
    open_text,
    parse_float,
    read_head,
    refuse_step_beyond_float,
)
from isolator.units import ACCELERATION_UNITS_TO_M_S2

COMMENT_PREFIXES = ("#", "%", "!")
TIME_STEP_REL_TOLERANCE = 1e-3  # allowed |Δt − dt| / dt in a time column (printing round-off)
TIME_STEP_ABS_TOLERANCE = 2e-6  # [s] round-off of times printed with 6 decimals

_META_RE = re.compile(r"^[#%!]+\s*([A-Za-z_][A-Za-z0-9_ ()/.-]*?)\s*[:=]\s*(.+?)\s*$")
_SPLIT_RE = re.compile(r"[,;\s]+")


def _is_comment(line: str) -> bool:
    return line.lstrip().startswith(COMMENT_PREFIXES)


def _metadata(comment_lines: list[str]) -> dict[str, str]:
    meta: dict[str, str] = {}
    for line in comment_lines:
        match = _META_RE.match(line.strip())
        if match:
            meta[match.group(1).strip().lower()] = match.group(2)
    return meta


def _units_statements(comment_lines: list[str]) -> list[str]:
    """Every ``# units:`` value of the comments, in order (a file may state them more than once)."""
    found = []
    for line in comment_lines:
        match = _META_RE.match(line.strip())
        if match and match.group(1).strip().lower() == "units":
            found.append(match.group(2).strip())
    return found


def _stated_step(comment_lines: list[str], *, numbers_only: bool) -> tuple[float | None, str, str]:
    """(step [s], the line as written, its value as written) of the comments' ``# dt_s:`` (or ``# dt:``) lines;
    (None, "", "") when none.  ``numbers_only``: a line whose value is not a number is a note, not a step (a file
    with a time column: ``# dt: 0.01 s`` was never read), else it is refused.

    Raises
    ------
    RecordFormatError
        A step that is not a number, or two lines that state different steps (``# dt_s: 0.02`` then
        ``# dt_s: 0.01`` took the last without a word, session 25 sweep): which one holds cannot be told.
    """
    found = []
    for line in comment_lines:
        match = _META_RE.match(line.strip())
        key = match.group(1).strip().lower() if match else ""
        if key in ("dt_s", "dt"):
            written = match.group(2)
            try:
                value = parse_float(written)
            except ValueError:  # was float()'s "could not convert string to float: '0,01'"
                if numbers_only:
                    continue
                comma = " (a decimal comma? write the step with a decimal point)" if "," in written else ""
                raise RecordFormatError(f"'# {key}: {written[:40]}' is not a number{comma}") from None
            found.append((value, f"'# {key}: {written[:40]}'", written))
    if len({value for value, _, _ in found}) > 1:
        raise RecordFormatError(f"states its time step {len(found)} times, differently ("
                                + ", ".join(line for _, line, _ in found) + "): ambiguous; keep the one line that is "
                                "right")
    return found[0] if found else (None, "", "")


def _one_unit(comment_lines: list[str]) -> str:
    """The file's units, stated once or the same each time; two different statements are refused.

    Raises
    ------
    ValueError
        The file states two different units (``# units: g`` then ``# units: cm/s2``): which one
        holds cannot be told, and the answers differ by a factor of 980.
    """
    statements = _units_statements(comment_lines)
    distinct = list(dict.fromkeys(value.lower().replace(" ", "") for value in statements))
    if len(distinct) > 1:
        raise ValueError(f"states its units {len(statements)} times, differently ("
                         + ", ".join(f"'# units: {value}'" for value in statements)
                         + "): ambiguous; keep the one line that is right")
    return statements[0] if statements else ""


#: Units of a length or a velocity, as a column name may end with them (``disp_mm``, ``v (cm/s)``).
NOT_ACCELERATION_UNITS = {"mm", "cm", "m", "in", "ft", "mm/s", "cm/s", "m/s", "in/s", "ft/s", "kine"}
_NAME_UNIT_RE = re.compile(r"(?:[_\s]|^)\(?\[?([A-Za-z/]+)\]?\)?$")


def _column_unit_problem(names: list[str]) -> str | None:
    """Words for a column named in a length or velocity unit (``acc_mm``): not an acceleration."""
    for name in names:
        match = _NAME_UNIT_RE.search(name.strip())
        if match and match.group(1).lower() in NOT_ACCELERATION_UNITS:
            return (f"column '{name}' is named in {match.group(1)}, a unit of length or velocity, not of "
                    "acceleration; isolator reads accelerograms")
    return None


#: An acceleration unit a column's name may end with (``acc_g``, ``a (cm/s2)``, ``a[m/s^2]``).
_NAME_ACCELERATION_UNIT_RE = re.compile(r"(?:^|[_\s(\[])([A-Za-z0-9/*^\u00b2]+)[)\]]?$")


def _column_units(name: str) -> str | None:
    """The acceleration unit the column ``name`` is named in (``acc_g`` → ``g``), or None."""
    match = _NAME_ACCELERATION_UNIT_RE.search(name.strip())
    unit = match.group(1).lower().replace("\u00b2", "2") if match else ""
    return unit if unit in ACCELERATION_UNITS_TO_M_S2 else None


def _stated_units(comment_lines: list[str], names: list[str]) -> tuple[str, str]:
    """The file's units and where they are stated: its ``# units:`` line or its acceleration column's name.

    A column named in an acceleration unit (``acc (cm/s2)``) states the units as a ``# units:`` line does; the
    two disagreeing (``# units: g`` over ``acc (cm/s2)``: a factor of 980) is refused, never settled by a guess.

    Raises
    ------
    ValueError
        Two different ``# units:`` lines, or a ``# units:`` line and a column name in different units.
    """
    units = _one_unit(comment_lines)
    column = names[-1] if names else ""
    named = _column_units(column)
    if named is None:
        return units, ""
    if not units:
        return named, f"column '{column}'"
    stated = units.lower().replace(" ", "")
    if ACCELERATION_UNITS_TO_M_S2.get(stated) != ACCELERATION_UNITS_TO_M_S2[named]:
        raise ValueError(f"states its units as '# units: {units}' but names its acceleration column '{column}' "
                         f"(in {named}): ambiguous; make them agree")
    return units, ""


def _numeric_fields(line: str) -> int | None:
    """Number of numeric fields of a data line, or None if one is not a number."""
    fields = [f for f in _SPLIT_RE.split(line.strip()) if f]
    try:
        for field in fields:
            parse_float(field)
    except ValueError:
        return None
    return len(fields)


def numeric_columns(head: bytes) -> int | None:
    """Number of numeric columns of the first non-comment line of a file's head, or None (not numbers).

    Parameters
    ----------
    head : bytes
        The first bytes of the file (:func:`isolator.io.read_head`) [-].
    """
    lines = [line for line in head_lines(head) if not _is_comment(line)]
    return _numeric_fields(lines[0]) if lines else None


def _is_text(filename_or_buf) -> bool:
    """True only for a text record that carries isolator's ``# units:`` metadata (strict).

    Parameters
    ----------
    filename_or_buf : str or path-like or file-like
        The file to test [-].

    Returns
    -------
    bool
        Whether obspy's autodetection should hand the file to :func:`_read_text` [-].
    """
    head = read_head(filename_or_buf)
    if not looks_like_text(head):
        return False
    lines = head_lines(head)
    comments = [line for line in lines if _is_comment(line)]
    statements = [value.lower().replace(" ", "") for value in _units_statements(comments)]
    if not any(units in ACCELERATION_UNITS_TO_M_S2 for units in statements):
        return False
    data_lines = [line for line in lines if not _is_comment(line)][:50]
    return bool(data_lines) and all(_numeric_fields(line) in (1, 2) for line in data_lines)


def _layout(stream) -> tuple[list[str], list[str] | None, str | None, int, int]:
    """Leading comments, column names, delimiter, number of columns, lines before the data."""
    comments: list[str] = []
    names: list[str] | None = None
    skip = 0
    for line in stream:
        if not line.strip() or _is_comment(line):
            if _is_comment(line):
                comments.append(line.strip())
            skip += 1
            continue
        delimiter = "," if "," in line else (";" if ";" in line else None)
        fields = [f.strip() for f in (line.split(delimiter) if delimiter else line.split())]
        fields = [f for f in fields if f]
        if names is None and fields and _numeric_fields(line) is None and not any(
            _numeric_fields(f) for f in fields
        ):
            names = fields  # one row of column names, e.g. "time,acc"
            skip += 1
            continue
        return comments, names, delimiter, len(fields), skip
    return comments, names, None, 0, skip


#: A number written with a decimal comma (``-0,0123``), alone between separators: spreadsheets of a comma locale
#: export them, and the reader took the comma for its separator (``0,0123`` a time of 0 and 123 g).
_DECIMAL_COMMA_RE = re.compile(r"(?<![\d.,])-?\d+,\d+(?![\d.,])")


def _decimal_comma_hint(filename_or_buf) -> str:
    """``; decimal commas? …`` when the file's first data lines hold numbers with decimal commas and no decimal
    point (then every refusal of the reader — a time column that does not increase, 3 columns, a step of 1 s, a
    ``# dt_s: 0,01`` — came from the commas, told in other words); else ''."""
    lines = [line for line in head_lines(read_head(filename_or_buf))[:50]
             if not line.lstrip().startswith(COMMENT_PREFIXES) or "dt" in line]
    data = [line for line in lines if any(ch.isdigit() for ch in line)]
    if data and not any("." in line for line in data) and all(_DECIMAL_COMMA_RE.search(line) for line in data):
        return ("; decimal commas? (0,0123 is read as two numbers, 0 and 123: write the numbers with a decimal point, "
                "0.0123)")
    return ""


def _read_text(filename_or_buf, dt_s: float | None = None, headonly: bool = False, **kwargs) -> Stream:
    """:func:`_parse_text`, whose refusals of a file written with decimal commas say so (session 23 sweep).

    Parameters and returns as :func:`_parse_text`.
    """
    try:
        return _parse_text(filename_or_buf, dt_s=dt_s, headonly=headonly, **kwargs)
    except (MissingTimeStepError, TimeStepConflictError):
        raise
    except ValueError as err:  # a RecordFormatError, or float()'s words for a '# dt_s: 0,01'
        hint = _decimal_comma_hint(filename_or_buf)
        if not hint:
            raise
        raise RecordFormatError(f"{err}{hint}") from None


def _parse_text(filename_or_buf, dt_s: float | None = None, headonly: bool = False, **kwargs) -> Stream:
    """Read a one- or two-column text accelerogram into a one-trace :class:`obspy.Stream`.

    Parameters
    ----------
    filename_or_buf : str or path-like or file-like
        The text file [-].
    dt_s : float, optional
        Time step for a one-column file (must agree with a ``# dt_s:`` line and with a time
        column if there is one) [s].
    headonly : bool, optional
        Ignored; the whole file is parsed to know NPTS and DT [-].
    **kwargs
        Ignored (obspy passes its own reading options).

    Returns
    -------
    obspy.Stream
        One trace, data float64 in the file's (unconverted) units; ``stats.units`` only if
        the file states them; ``stats.isolator_text`` the comments, metadata, column names
        and the time of the first sample ``t0_s`` [s].

    Raises
    ------
    ValueError
        One-line message: two different ``# units:`` lines, no data, a non-numeric field, a changing number of columns,
        more than two columns, a time column that does not increase, a missing or
        non-positive time step, ``dt_s`` given for an unevenly spaced time column.
    """
    with open_text(filename_or_buf) as stream:
        comments, names, delimiter, ncols, skip = _layout(stream)
    if ncols == 0:
        raise RecordFormatError("no numeric data lines")
    if ncols > 2:
        raise RecordFormatError(
            f"{ncols} columns; expected 1 (acceleration, with a time step) or 2 (time, acceleration)"
        )
    with open_text(filename_or_buf) as stream:
        try:
            table = np.loadtxt(
                stream, dtype=np.float64, comments=COMMENT_PREFIXES, delimiter=delimiter,
                skiprows=skip, ndmin=2,
            )
        except ValueError as err:
            message = str(err).splitlines()[0].rstrip(".;")
            message = re.sub(r";\s*use `usecols`.*$", "", message)
            message = message.replace("could not convert string", "non-numeric value")
            raise RecordFormatError(message) from None
    meta = _metadata(comments)
    problem = _column_unit_problem((names or [])[-1:])  # the acceleration column (time may be in s)
    if problem:
        raise ValueError(problem)
    units, units_from = _stated_units(comments, names or [])
    info = AttribDict()
    info.comments = comments
    info.metadata = meta
    info.column_names = names or []
    info.columns = ncols
    t0_s = 0.0
    dt_from = ""  # what gave the step, when the file gave it
    dt_written = ""  # the step as the file writes it (a '# dt_s:' line)
    stated_s, stated_line, stated_written = _stated_step(comments, numbers_only=ncols == 2)
    if ncols == 2:
        time_s, acceleration = table[:, 0], table[:, 1]
        if time_s.size >= 2:
            steps_s = np.diff(time_s)
            if not np.all(np.isfinite(time_s)):
                raise RecordFormatError("non-finite value in the time column")
            bad = np.flatnonzero(steps_s <= 0)
            if bad.size:
                i = int(bad[0])
                raise RecordFormatError(
                    f"time column does not increase at data row {i + 2} "
                    f"(t = {time_s[i]:g} s then {time_s[i + 1]:g} s)"
                )
            step_s = (time_s[-1] - time_s[0]) / (time_s.size - 1)
            tolerance_s = max(TIME_STEP_REL_TOLERANCE * step_s, TIME_STEP_ABS_TOLERANCE)
            if np.max(np.abs(steps_s - step_s)) > tolerance_s:
                if dt_s is not None:
                    raise TimeStepConflictError(f"a time step is given ({dt_s:g} s) but the time column is not evenly "
                                                f"spaced (steps from {steps_s.min():g} to {steps_s.max():g} s)",
                                                given=dt_s)
                info.time_s = time_s - time_s[0]  # unequal steps: kept, solved as they are
                dt_s = float(step_s)
                dt_from = "the time column's step"
            else:
                if dt_s is not None and abs(dt_s - step_s) > tolerance_s:
                    raise TimeStepConflictError(f"the time step given ({dt_s:g} s) disagrees with the time column's "
                                                f"{step_s:g} s", given=dt_s)
                if stated_s is not None and not abs(stated_s - step_s) <= tolerance_s:  # the column was read alone
                    raise RecordFormatError(f"{stated_line} disagrees with the time column's step of {step_s:g} s: "
                                            "which one holds? (correct the line, or drop it)")
                dt_s = float(f"{step_s:.12g}")  # drop the round-off of the division
                dt_from = "the time column's step"
        elif dt_s is None:
            dt_s = 1.0  # a single sample: the caller refuses it anyway
        t0_s = float(time_s[0])
    else:
        acceleration = table[:, 0]
        if dt_s is not None and stated_s is not None and not abs(stated_s - dt_s) <= 1e-9 * max(dt_s, 1.0):
            # --dt took the place of '# dt_s: 0.01' without a word (session 25 sweep), as --units against '# units:'
            raise TimeStepConflictError(f"the file states {stated_line} but the time step given is {dt_s:g} s",
                                        given=dt_s)
        if dt_s is None and stated_s is not None:
            dt_s, dt_from, dt_written = stated_s, stated_line, stated_written
        if dt_s is None:
            raise MissingTimeStepError("one column and no time step (none given, no '# dt_s:' line)")
    if dt_from:  # a step given by --dt keeps its own message (it names the flag)
        refuse_step_beyond_float(dt_s, dt_written, dt_from, value_shown=True)
    if not dt_s > 0:
        raise RecordFormatError(f"time step dt = {dt_s:g} s is not positive")
    info.t0_s = t0_s
    trace = Trace(data=np.ascontiguousarray(acceleration, dtype=np.float64))
    trace.stats.delta = float(dt_s)
    trace.stats.starttime = UTCDateTime(0) + t0_s
    if units:
        trace.stats.units = units
        if units_from:
            info.units_from = units_from  # stated by the column's name, not by a '# units:' line
    trace.stats.station = meta.get("station", "")[:16]
    if "component" in meta:
        info.component = meta["component"]
    trace.stats.isolator_text = info
    return Stream([trace])
