"""CSMIP / CGS Volume 2 (``.v2``) corrected accelerograms as an obspy plugin (``CSMIP_V2``).

A V2 file holds one block per channel (three in the usual station file).  Each block:
a 25-line text header, an integer and a real header, then three data blocks —
acceleration, velocity, displacement — each introduced by a line such as
``10100 points of accel data equally spaced at 0.010 sec, in cm/sec2. (8f10.5)`` and
written 8 values per line in fixed 10-character fields (fields may touch), and the
channel ends with a line starting ``/&``.  Only the acceleration is read, in cm/s² as the
format states; ``stats.units = "cm/s2"``.  Each channel becomes one trace with channel
code ``HN1``, ``HN2``, … (``HNZ`` for the vertical) and its orientation (``180``, ``90``,
``Up``) in ``stats.csmip_v2.orientation``.
"""

from __future__ import annotations

import re

import numpy as np
from obspy import Stream, Trace, UTCDateTime
from obspy.core.util import AttribDict

from isolator.errors import RecordFormatError
from isolator.io._common import head_lines, looks_like_text, open_text, parse_float, read_head

FIELD_WIDTH = 10  # characters per value in the data blocks (8F10.x)

_FIRST_LINE_RE = re.compile(r"^\s*Corrected accelerogram\b", re.IGNORECASE)
_BLOCK_RE = re.compile(
    r"^\s*(\d+)\s+points of (accel|veloc|displ)\w* data equally spaced at\s+([-+0-9.Ee]+)\s*sec"
    r"(?:,\s*in\s+([^.(]+?)\.?\s*(?:\(|$))?",
    re.IGNORECASE,
)
_CHANNELS_RE = re.compile(r"\((\d+)\s+Chns\s+of", re.IGNORECASE)  #: channels the file holds
_CHANNEL_RE = re.compile(r"Chan\s+(\d+)\s*:\s*([^\s]+)(\s+Deg)?", re.IGNORECASE)
_START_RE = re.compile(
    r"Start time:\s*(\d+)/(\d+)/(\d+),\s*(\d+):\s*(\d+):\s*([\d.]+)\s*UTC", re.IGNORECASE
)
_STATION_RE = re.compile(r"Station No\.\s*(\d+)", re.IGNORECASE)
#: A channel's text header states its step ("At equally-spaced intervals of   0.010  sec."): a data block's DT that
#: disagrees was read alone, the header's never compared (a block of 0.020 s under 0.010 s; session 25 sweep).
_INTERVALS_RE = re.compile(r"equally-spaced\s+intervals\s+of\s+([-+0-9.Ee]+)\s*sec", re.IGNORECASE)
_UNITS = {"cm/sec2": "cm/s2", "cm/sec/sec": "cm/s2", "g": "g", "m/sec2": "m/s2"}


def _is_v2(filename_or_buf) -> bool:
    """True for a CSMIP Volume 2 file: first line ``Corrected accelerogram`` and the
    ``points of … data equally spaced at`` line in the first block (strict).

    Parameters
    ----------
    filename_or_buf : str or path-like or file-like
        The file to test [-].

    Returns
    -------
    bool
        Whether :func:`_read_v2` should be used [-].
    """
    head = read_head(filename_or_buf)
    if not looks_like_text(head):
        return False
    lines = head_lines(head)
    return bool(lines) and bool(_FIRST_LINE_RE.match(lines[0])) and any(
        _BLOCK_RE.match(line) for line in lines[:80]
    )


def _fixed_width_values(lines: list[str], count: int, first_line_number: int) -> np.ndarray:
    values = np.empty(count, dtype=np.float64)
    filled = 0
    for offset, line in enumerate(lines):
        line = line.rstrip()
        for start in range(0, len(line), FIELD_WIDTH):
            field = line[start:start + FIELD_WIDTH].strip()
            if not field:
                continue
            if filled >= count:
                raise RecordFormatError(f"more values than announced on line {first_line_number + offset}")
            try:
                values[filled] = parse_float(field)
            except ValueError:
                raise RecordFormatError(
                    f"non-numeric value {field!r} on line {first_line_number + offset}"
                ) from None
            filled += 1
    if filled < count:
        raise RecordFormatError(f"truncated: {filled} values but the header says {count}")
    return values


def _start_time(text_header: list[str]) -> UTCDateTime | None:
    for line in text_header:
        match = _START_RE.search(line)
        if match:
            month, day, year, hour, minute = (int(match.group(i)) for i in range(1, 6))
            year += 2000 if year < 50 else (1900 if year < 100 else 0)
            return UTCDateTime(year, month, day, hour, minute) + float(match.group(6))
    return None


def _read_v2(filename_or_buf, headonly: bool = False, **kwargs) -> Stream:
    """Read the acceleration channels of a CSMIP V2 file.

    Parameters
    ----------
    filename_or_buf : str or path-like or file-like
        The V2 file [-].
    headonly : bool, optional
        Ignored; the file is parsed whole [-].
    **kwargs
        Ignored (obspy passes its own reading options).

    Returns
    -------
    obspy.Stream
        One trace per channel, data float64 in cm/s², ``stats.csmip_v2`` the channel's
        text header, number, orientation, units and station name.

    Raises
    ------
    ValueError
        One-line message: no channel, non-numeric or missing values, DT ≤ 0.
    """
    with open_text(filename_or_buf) as stream:
        lines = [line.rstrip("\r\n") for line in stream]
    traces: list[Trace] = []
    index = 0
    text_header: list[str] = []
    channel_start = 0
    while index < len(lines):
        line = lines[index]
        match = _BLOCK_RE.match(line)
        if match is None:
            if line.startswith("/&"):
                text_header, channel_start = [], index + 1
            elif index - channel_start < 25:
                text_header.append(line)
            index += 1
            continue
        count, kind, dt_s = int(match.group(1)), match.group(2).lower(), parse_float(match.group(3))
        nlines = -(-count // 8)
        block = lines[index + 1:index + 1 + nlines]
        if kind == "accel":
            if not dt_s > 0:
                raise RecordFormatError(f"DT={dt_s:g} s is not positive on line {index + 1}")
            stated = next((m for m in map(_INTERVALS_RE.search, text_header) if m), None)
            if stated is not None and not abs(parse_float(stated.group(1)) - dt_s) <= 1e-6 * dt_s:
                raise RecordFormatError(f"DT={dt_s:g} s on line {index + 1} disagrees with the channel's header "
                                        f"('equally-spaced intervals of {stated.group(1)} sec'): which one holds?")
            units_text = (match.group(4) or "").strip().lower()
            units = _UNITS.get(units_text.replace(" ", ""))
            if units is None:
                raise RecordFormatError(f"unknown acceleration units {units_text!r} on line {index + 1}")
            data = _fixed_width_values(block, count, index + 2)
            info = AttribDict()
            info.text_header = text_header
            channel = next((m for m in map(_CHANNEL_RE.search, text_header) if m), None)
            info.channel_number = int(channel.group(1)) if channel else len(traces) + 1
            info.orientation = channel.group(2) if channel else ""
            info.units = units
            info.station_name = text_header[6][:40].strip() if len(text_header) > 6 else ""
            trace = Trace(data=data)
            trace.stats.delta = dt_s
            start = _start_time(text_header)
            if start is not None:
                trace.stats.starttime = start
            station = next((m for m in map(_STATION_RE.search, text_header) if m), None)
            trace.stats.network = "CE"
            trace.stats.station = station.group(1) if station else ""
            vertical = info.orientation.lower() in ("up", "down", "vert", "z")
            trace.stats.channel = "HNZ" if vertical else f"HN{info.channel_number}"
            trace.stats.units = units
            trace.stats.csmip_v2 = info
            traces.append(trace)
        index += 1 + nlines
    if not traces:
        raise RecordFormatError("no 'points of accel data' block found")
    # the first header states the channels the file holds ("(3 Chns of  3 at Sta)"): a file cut
    # between channels must not pass for a file of fewer channels
    stated = next((m for m in map(_CHANNELS_RE.search, lines[:25]) if m), None)
    if stated is not None and len(traces) < int(stated.group(1)):
        raise RecordFormatError(f"truncated: the header states {int(stated.group(1))} channels but "
                         f"{len(traces)} were found")
    return Stream(traces)
