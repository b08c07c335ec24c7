"""PEER / NGA ``.AT2`` accelerograms as an obspy waveform plugin (format ``PEER_AT2``).

An AT2 file is a few text header lines, one line giving the number of points and the
time step, then the accelerations in g, several per line.  The variants handled (all
found in ``../shared/records/at2``):

* ``NPTS=  4000, DT= .01000 SEC`` (PEER 2000), ``NPTS=   2000  DT=   .0200 SEC`` (NGA-West2,
  no comma), the same followed by filter corners (``…SEC,   4 POLE @ 33.0 HZ…``), and the
  older NGA order ``  4096   0.0100   NPTS, DT``;
* the NPTS line anywhere in the first ``MAX_HEADER_LINES`` non-blank lines (the OpenSees
  "verification" El Centro has it on line 7, after ``*** Begin data ***``), header lines
  that themselves hold numbers;
* LF, CRLF and CR CR LF line endings (blank lines are skipped), no final newline;
* 5 values per line (E15.7) or 8 (F10.5), fixed-width fields that touch;
* a non-numeric trailer line after the NPTS values (``*** End Data ***``).

The values are in g by the format's definition (PEER writes "UNITS OF G"); the reader
records ``stats.units = "g"`` and keeps the header in ``stats.peer_at2``.  It does not
convert: :func:`isolator.motion.read_ground_motion` does, once, to m/s².
"""

from __future__ import annotations

import math
import re
import sys

import numpy as np
from obspy import Stream, Trace
from obspy.core.util import AttribDict

from isolator.errors import RecordFormatError
from isolator.io._common import (
    head_lines,
    iter_line_chunks,
    looks_like_text,
    numbers_from_lines,
    open_text,
    parse_float,
    read_head,
    refuse_step_beyond_float,
    split_numbers,
)

MAX_HEADER_LINES = 12  # non-blank lines searched for the NPTS/DT line
#: The most samples an AT2 header may announce (1e9 float64 samples are 8 GB; a day at 1 kHz is 8.6e7).
MAX_NPTS = 10**9

_FLOAT = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?"
_NPTS_DT_RE = re.compile(rf"NPTS\s*=\s*([-+]?\d+)\s*,?\s*DT\s*=\s*({_FLOAT})", re.IGNORECASE)
_NPTS_DT_REVERSED_RE = re.compile(rf"^\s*([-+]?\d+)\s+({_FLOAT})\s+NPTS\s*,\s*DT\b", re.IGNORECASE)
_UNITS_G_RE = re.compile(r"UNITS\s+OF\s+G\b|\(\s*G\s*\)|\bIN\s+G\b|UNITS\s+ARE\s+\(?G\b", re.IGNORECASE)
_NOT_ACCELERATION_RE = re.compile(r"\b(VELOCITY|DISPLACEMENT)\b.*\b(TIME|UNITS)\b", re.IGNORECASE)
_UNITS_STATED_RE = re.compile(r"UNITS\s+OF\s+([^\s,]+)", re.IGNORECASE)
_TRAILER_RE = re.compile(r"^\s*(\*|END\b)", re.IGNORECASE)


def _match_npts_dt(line: str) -> tuple[int, float] | None:
    match = _NPTS_DT_RE.search(line) or _NPTS_DT_REVERSED_RE.search(line)
    if match is None:
        return None
    return int(match.group(1)), parse_float(match.group(2))


def _dt_text(line: str) -> str:
    """The DT as written in the NPTS/DT line (at most 40 characters)."""
    match = _NPTS_DT_RE.search(line) or _NPTS_DT_REVERSED_RE.search(line)
    text = match.group(2) if match else "?"
    return text if len(text) <= 40 else f"{text[:20]}…{text[-10:]} ({len(text)} characters)"


def _is_at2(filename_or_buf) -> bool:
    """True if the file is a PEER AT2 accelerogram (strict).

    Strict means: text, an ``NPTS=…, DT=…`` line (or ``npts dt NPTS, DT``) within the first
    ``MAX_HEADER_LINES`` non-blank lines and after at least one header line, and the line
    after it (if any) made only of numbers.

    Parameters
    ----------
    filename_or_buf : str or path-like or file-like
        The file to test [-].

    Returns
    -------
    bool
        Whether :func:`_read_at2` should be used [-].
    """
    head = read_head(filename_or_buf)
    if not looks_like_text(head):
        return False
    lines = head_lines(head)[: MAX_HEADER_LINES + 1]
    for index, line in enumerate(lines[:MAX_HEADER_LINES]):
        if index == 0 or _match_npts_dt(line) is None:
            continue
        if index + 1 < len(lines):
            try:
                split_numbers(lines[index + 1])
            except ValueError:
                return False
        return True
    return False


def _parse_title(header: list[str]) -> dict[str, str]:
    """Event, date, station and component from the second header line, when it has them.

    ``Northridge-01, 1/17/1994, Newhall - Fire Sta, 360`` (NGA-West2) and
    ``IMPERIAL VALLEY 5/19/40 0439, EL CENTRO ARRAY #9, 180 (USGS STATION 117)`` (PEER 2000).
    """
    if len(header) < 2 or not re.search(r"PEER|PACIFIC|NGA", header[0], re.IGNORECASE):
        return {}
    parts = [part.strip() for part in header[1].split(",")]
    if len(parts) < 3 or not all(parts):
        return {}
    info: dict[str, str] = {"component": parts[-1].split()[0], "station": parts[-2]}
    first = ", ".join(parts[:-2])
    date = re.search(r"\d{1,2}/\d{1,2}/\d{2,4}", first)
    if date:
        info["date"] = date.group(0)
        event = (first[: date.start()] + first[date.end():]).strip(" ,")
        event = re.sub(r"^\s*\d{4}\s*|\s*\d{4}\s*$", "", event) if event else event
        info["event"] = event.strip(" ,")
    else:
        info["event"] = first
    return info


def _read_values(stream, npts: int, first_line_number: int) -> tuple[np.ndarray, list[str]]:
    """Exactly ``npts`` numbers from the rest of ``stream``, and any trailer lines."""
    data = np.empty(npts, dtype=np.float64)
    count = 0
    trailer: list[str] = []
    line_number = first_line_number
    for chunk in iter_line_chunks(stream):
        if trailer:
            extra = [line for line in chunk if line.strip()]
            trailer.extend(extra)
            line_number += len(chunk)
            continue
        try:
            values = numbers_from_lines(chunk)
            slow = False
        except ValueError:
            slow = True
        if not slow:
            if count + values.size > npts:
                raise RecordFormatError(f"holds more than the header's NPTS={npts} values")
            data[count:count + values.size] = values
            count += values.size
            line_number += len(chunk)
            continue
        for line in chunk:
            line_number += 1
            if not line.strip():
                continue
            if trailer:
                trailer.append(line.strip())
                continue
            try:
                tokens = split_numbers(line)
            except ValueError as err:
                if _TRAILER_RE.match(line):
                    trailer.append(line.strip())
                    continue
                raise RecordFormatError(f"{err} on line {line_number}") from None
            if count + len(tokens) > npts:
                raise RecordFormatError(f"holds more than the header's NPTS={npts} values")
            data[count:count + len(tokens)] = [parse_float(t) for t in tokens]
            count += len(tokens)
    if count < npts:
        raise RecordFormatError(f"truncated: {count} values but the header says NPTS={npts}")
    return data, trailer


def _read_at2(filename_or_buf, headonly: bool = False, **kwargs) -> Stream:
    """Read a PEER AT2 file into a one-trace :class:`obspy.Stream` (values in g).

    Parameters
    ----------
    filename_or_buf : str or path-like or file-like
        The AT2 file [-].
    headonly : bool, optional
        Read the header only; the trace then has no data [-].
    **kwargs
        Ignored (obspy passes its own reading options).

    Returns
    -------
    obspy.Stream
        One trace: ``data`` float64 in g, ``stats.delta`` the DT [s], ``stats.units = "g"``,
        ``stats.peer_at2`` the header (lines, title fields, npts, dt, trailer).

    Raises
    ------
    ValueError
        One-line message for a missing NPTS/DT line, DT ≤ 0, NPTS ≤ 0, a non-numeric value,
        fewer or more values than NPTS, or a PEER velocity/displacement file.
    """
    with open_text(filename_or_buf) as stream:
        header: list[str] = []
        line_number = 0
        npts_dt = None
        for line in stream:
            line_number += 1
            line = line.rstrip("\r\n")
            if not line.strip():
                continue
            header.append(line.rstrip())
            npts_dt = _match_npts_dt(line)
            if npts_dt is not None or len(header) >= MAX_HEADER_LINES:
                break
        if not header:
            raise RecordFormatError("file is empty")
        if npts_dt is None:
            raise RecordFormatError(
                f"not a PEER AT2 file: no 'NPTS=…, DT=…' line in the first {MAX_HEADER_LINES} lines"
            )
        npts, dt_s = npts_dt
        header_text = "\n".join(header[:-1])
        if _NOT_ACCELERATION_RE.search(header_text) and not re.search("ACCELERATION", header_text, re.I):
            raise RecordFormatError("PEER file holds velocity or displacement, not acceleration")
        stated = _UNITS_STATED_RE.search(header_text)
        if stated and stated.group(1).upper().rstrip(".,") not in ("G", "G'S"):
            raise RecordFormatError(f"header states units {stated.group(1)!r}; a PEER AT2 file is in g")
        if not math.isfinite(dt_s) or abs(dt_s) < sys.float_info.min:  # 1e400, 1e-320, 1e-400: said "dt = 0 s"
            written = _dt_text(header[-1])
            refuse_step_beyond_float(dt_s, written, f"header DT={written} s", corrupt="header")
        if not dt_s > 0:
            raise RecordFormatError(f"header DT={dt_s:g} s is not positive")
        if npts < 1:
            raise RecordFormatError(f"header NPTS={npts} holds no samples")
        if npts > MAX_NPTS:  # 400 digits were numpy's "Maximum allowed dimension exceeded" (session 19 sweep)
            shown = f"={npts}" if npts < 10**20 else f" of {len(str(npts))} digits"
            raise RecordFormatError(f"header NPTS{shown} is more than the {MAX_NPTS:.0e} samples this reader takes: "
                                    "a corrupt header?")
        if headonly:
            data, trailer = np.empty(0, dtype=np.float64), []
        else:
            data, trailer = _read_values(stream, npts, line_number)

    peer = AttribDict()
    peer.header_lines = header
    peer.npts = npts
    peer.dt = dt_s
    peer.units = "g"
    peer.units_stated_in_header = bool(_UNITS_G_RE.search(header_text))
    peer.trailer = trailer
    peer.update(_parse_title(header))
    trace = Trace(data=data)
    trace.stats.delta = dt_s
    if headonly:
        trace.stats.npts = npts
    trace.stats.units = "g"
    trace.stats.peer_at2 = peer
    return Stream([trace])
