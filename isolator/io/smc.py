"""USGS SMC (strong-motion CD) accelerograms as an obspy waveform plugin (``USGS_SMC``).

Layout: 11 text lines (the first gives the data type, e.g. ``2 CORRECTED ACCELEROGRAM``),
48 integers (8 per line, I10), 50 reals (5 per line, E15.7), comment lines starting with
``|``, then the samples 8 per line in 10-character fields **with no separator**
(``1.5057E+0-2.2223E+0``).  Integer header: [1] year, [2] Julian day, [3] hour,
[4] minute, [5] second, [6] millisecond, [15] number of comment lines, [16] NPTS; real
header [1]: sampling rate [Hz]; −32768 and 1.7e38 mean "not given".  Corrected
accelerograms are in cm/s² by the format's definition: ``stats.units = "cm/s2"``.
Uncorrected accelerograms (type 0, counts) and velocity/displacement files are refused.
"""

from __future__ import annotations

import re

import numpy as np
from obspy import Stream, Trace, UTCDateTime
from obspy.core.util import AttribDict

from isolator.errors import RecordFormatError
from isolator.io._common import looks_like_text, open_text, parse_float, read_head

TEXT_LINES = 11
INT_LINES = 6
REAL_LINES = 10
FIELD_WIDTH = 10  # characters per sample
INT_MISSING = -32768
REAL_MISSING = 1.7e38

_FIRST_LINE_RE = re.compile(r"^\s*(\d)\s+(\w+(?:\s\w+)*)\s*$")
_COMPONENT_RE = re.compile(r"component\s*=\s*(\S+)", re.IGNORECASE)


def _is_smc(filename_or_buf) -> bool:
    """True for a USGS SMC file: ``<digit> … ACCELEROGRAM|VELOCITY|DISPLACEMENT`` on line 1
    and eight integers on line 12 (strict).

    Parameters
    ----------
    filename_or_buf : str or path-like or file-like
        The file to test [-].

    Returns
    -------
    bool
        Whether :func:`_read_smc` should be used [-].
    """
    head = read_head(filename_or_buf)
    if not looks_like_text(head):
        return False
    lines = re.split(r"\r\n|\r|\n", head.decode("latin-1"))
    if len(lines) <= TEXT_LINES or not _FIRST_LINE_RE.match(lines[0]):
        return False
    if not re.search(r"ACCELEROGRAM|VELOCITY|DISPLACEMENT", lines[0], re.IGNORECASE):
        return False
    fields = lines[TEXT_LINES].split()
    return len(fields) == 8 and all(re.fullmatch(r"-?\d+", f) for f in fields)


def _read_smc(filename_or_buf, headonly: bool = False, **kwargs) -> Stream:
    """Read a corrected USGS SMC accelerogram.

    Parameters
    ----------
    filename_or_buf : str or path-like or file-like
        The SMC file [-].
    headonly : bool, optional
        Ignored; the file is parsed whole [-].
    **kwargs
        Ignored (obspy passes its own reading options).

    Returns
    -------
    obspy.Stream
        One trace, data float64 in cm/s², ``stats.usgs_smc`` the text header, integer and
        real headers, comments and component.

    Raises
    ------
    ValueError
        One-line message: not a corrected accelerogram, missing NPTS or sampling rate,
        non-numeric or missing values.
    """
    with open_text(filename_or_buf) as stream:
        lines = [line.rstrip("\r\n") for line in stream]
    if not lines or not any(line.strip() for line in lines):
        raise RecordFormatError("file is empty")
    kind = lines[0].strip()
    if not re.search(r"\bCORRECTED ACCELEROGRAM", kind, re.IGNORECASE) or kind.startswith("0"):
        raise RecordFormatError(f"SMC data type {kind!r} is not a corrected accelerogram")
    header_end = TEXT_LINES + INT_LINES + REAL_LINES
    if len(lines) < header_end:
        raise RecordFormatError("truncated SMC header")
    try:
        ints = [int(v) for line in lines[TEXT_LINES:TEXT_LINES + INT_LINES] for v in line.split()]
        reals = [parse_float(v) for line in lines[TEXT_LINES + INT_LINES:header_end] for v in line.split()]
    except ValueError:
        raise RecordFormatError("malformed SMC integer or real header") from None
    if len(ints) < 17 or len(reals) < 2:
        raise RecordFormatError("malformed SMC integer or real header")
    npts, rate_hz = ints[16], reals[1]
    if npts == INT_MISSING or npts < 1:
        raise RecordFormatError("SMC header gives no number of samples")
    if rate_hz >= REAL_MISSING or not rate_hz > 0:
        raise RecordFormatError(f"SMC sampling rate {rate_hz:g} Hz is not positive")
    index = header_end
    comments = []
    while index < len(lines) and lines[index].startswith("|"):
        comments.append(lines[index])
        index += 1
    data = np.empty(npts, dtype=np.float64)
    filled = 0
    for number, line in enumerate(lines[index:], start=index + 1):
        line = line.rstrip()
        for start in range(0, len(line), FIELD_WIDTH):
            field = line[start:start + FIELD_WIDTH].strip()
            if not field:
                continue
            if filled >= npts:
                raise RecordFormatError(f"holds more than the header's NPTS={npts} values")
            try:
                data[filled] = parse_float(field)
            except ValueError:
                raise RecordFormatError(f"non-numeric value {field!r} on line {number}") from None
            filled += 1
    if filled < npts:
        raise RecordFormatError(f"truncated: {filled} values but the header says NPTS={npts}")

    info = AttribDict()
    info.text_header = lines[:TEXT_LINES]
    info.int_header = ints
    info.real_header = reals
    info.comments = comments
    component = next((m for m in map(_COMPONENT_RE.search, lines[:TEXT_LINES]) if m), None)
    info.component = component.group(1) if component else ""
    info.event = lines[3][25:].strip() if len(lines) > 3 else ""
    info.station_name = lines[5].split("=", 1)[-1].split(" component")[0].strip(" ,") if "=" in lines[5] else ""
    info.units = "cm/s2"
    trace = Trace(data=data)
    trace.stats.sampling_rate = rate_hz
    year, julday, hour, minute, second, millisecond = ints[1:7]
    if INT_MISSING not in (year, julday, hour, minute):
        start = UTCDateTime(year=year, julday=julday, hour=hour, minute=minute)
        start += (0 if second == INT_MISSING else second) + (0 if millisecond == INT_MISSING else millisecond / 1000)
        trace.stats.starttime = start
    trace.stats.station = lines[2].strip()[:5]
    trace.stats.units = "cm/s2"
    trace.stats.usgs_smc = info
    return Stream([trace])
