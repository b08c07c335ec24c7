"""Helpers shared by the text-based record readers: opening, line reading, number parsing.

Parsing is chunked (``CHUNK_LINES`` lines at a time) so that a record of millions of
samples is read in bounded memory: only one chunk of text is held at a time besides the
float64 result.
"""

from __future__ import annotations

import errno
import glob
import io
import math
import os
import re
import stat
import sys
from collections.abc import Iterator
from typing import IO

import numpy as np

from isolator.errors import RecordFormatError

CHUNK_LINES = 65536  # lines parsed per numpy call; bounds the temporary text held in memory
DETECT_BYTES = 8192  # bytes looked at by the format detectors
#: The UTF-8 byte-order mark as the latin-1 text the readers decode (spreadsheets save CSV with it): it is not part
#: of the first line, whose "# units: g" it would otherwise hide (Session 15 sweep, docs/security.md).
UTF8_BOM = "\xef\xbb\xbf"

# A floating-point number as written by Fortran formats (E, F, optionally D exponents).
NUMBER_RE = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?")
_ONLY_NUMBER_CHARS_RE = re.compile(r"^[\s0-9.EeDd+-]*$")


def input_file_problem(path) -> str | None:
    """What is wrong with ``path`` as an input file, in words; None for a readable regular file.

    Decided from the file's metadata alone, never by opening it, so that a FIFO or a
    device answers at once instead of blocking.  Distinguishes a symbolic-link loop and a
    dangling link from a missing file.

    Parameters
    ----------
    path : str or path-like
        The file a command is asked to read.

    Returns
    -------
    str or None
        ``"no such file"``, ``"symbolic-link loop"``, ``"dangling symbolic link (to …)"``,
        ``"is a folder, not a file"``, ``"is a FIFO (named pipe), not a regular file"``,
        ``"file is empty"``, ``"cannot be read (Permission denied)"`` …, or None.
    """
    from isolator.atomic import file_kind

    path = os.fspath(path)
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        if os.path.islink(path):
            return f"dangling symbolic link (to {os.readlink(path)})"
        return "no such file"
    except OSError as err:
        if err.errno == errno.ELOOP:
            return "symbolic-link loop"
        return f"cannot be read ({err.strerror or err})"
    if stat.S_ISDIR(mode):
        return "is a folder, not a file"
    if not stat.S_ISREG(mode):
        return f"is {file_kind(mode)}, not a regular file"
    if not os.access(path, os.R_OK):
        return "cannot be read (Permission denied)"
    if os.stat(path).st_size == 0:
        return "file is empty"
    return None


def literal_pattern(path) -> str:
    """``path`` as a glob pattern that matches exactly that file.

    :func:`obspy.read` expands ``*``, ``?`` and ``[…]`` in a ``str`` path, so that
    ``x[1].AT2`` would read ``x1.AT2``; escaping them makes a path name exactly one file.
    The path is made absolute, so that it is never taken for a URL.
    """
    # absolute: obspy downloads anything with "://" in its first characters; abspath also
    # collapses "a://b" to "a:/b", so a local path can never be taken for a URL
    return glob.escape(os.path.abspath(os.fspath(path)))


def read_head(filename_or_buf, nbytes: int = DETECT_BYTES) -> bytes:
    """First ``nbytes`` bytes of a path or a binary/text buffer, leaving a buffer's position alone."""
    if hasattr(filename_or_buf, "read"):
        position = filename_or_buf.tell()
        try:
            head = filename_or_buf.read(nbytes)
        finally:
            filename_or_buf.seek(position)
        return head.encode("latin-1") if isinstance(head, str) else bytes(head)
    try:
        with open(filename_or_buf, "rb") as handle:
            return handle.read(nbytes)
    except (OSError, TypeError):
        return b""


def looks_like_text(head: bytes) -> bool:
    """True when ``head`` is plausibly ASCII text (no NUL bytes, few control characters)."""
    head = head.removeprefix(UTF8_BOM.encode("latin-1"))
    if not head or b"\x00" in head:
        return False
    control = sum(1 for byte in head if byte < 32 and byte not in (9, 10, 13, 12))
    non_ascii = sum(1 for byte in head if byte > 126)
    return control == 0 and non_ascii <= len(head) // 100


def head_lines(head: bytes) -> list[str]:
    """Lines of a detection head, any line ending (LF, CRLF, CR CR LF), blank lines dropped."""
    text = head.decode("latin-1").removeprefix(UTF8_BOM)
    lines = [line for line in re.split(r"\r\n|\r|\n", text) if line.strip()]
    if head and not head.endswith((b"\n", b"\r")) and len(head) >= DETECT_BYTES and lines:
        lines.pop()  # the last line may be cut by the byte limit
    return lines


def open_text(filename_or_buf) -> IO[str]:
    """A text stream with universal newlines over a path or a buffer (latin-1, never fails), past a UTF-8 BOM."""
    if hasattr(filename_or_buf, "read"):
        raw = filename_or_buf.read()
        if isinstance(raw, bytes):
            raw = raw.decode("latin-1")
        return io.StringIO(raw.removeprefix(UTF8_BOM), newline=None)
    stream = open(os.fspath(filename_or_buf), encoding="latin-1", newline=None)
    if stream.read(len(UTF8_BOM)) != UTF8_BOM:
        stream.seek(0)
    return stream


def refuse_step_beyond_float(dt_s: float, written: str, named: str, corrupt: str = "file",
                             value_shown: bool = False) -> None:
    """Refuse a record's time step that is beyond a float, below its smallest normal number, or written non-zero
    and read as 0.0 — the one wording of every reader (the AT2 header's DT, a text record's ``# dt_s:``).

    ObsPy keeps the rate 1/dt: an infinite step is 0 Hz and a subnormal one an infinite rate, and both came back as
    "time step dt = 0 s is not positive"; ``1e-400`` is read as 0.0 and was told the same (sessions 19-22).

    Parameters
    ----------
    dt_s : float
        The step as read [s].
    written : str
        The step as the file writes it ('' when computed, e.g. a time column's mean step): a text of 0.0 with a
        non-zero digit before its exponent (``1e-400``) underflowed.
    named : str
        How the message names the step (``header DT=1e400 s``, ``'# dt_s: 1e-400'``).
    corrupt : str
        What may be corrupt (``header``, ``file``).
    value_shown : bool
        Add the subnormal value read (`` of 4.94e-324 s``) after ``named``.

    Raises
    ------
    RecordFormatError
        One line naming the step as written.
    """
    if math.isinf(dt_s):
        raise RecordFormatError(f"{named} overflows: beyond any number (a float ends at 1.8e308 s); "
                                f"a corrupt {corrupt}?")
    zero_written_nonzero = dt_s == 0 and bool(re.search(r"[1-9]", re.split("[EeDd]", written)[0]))
    if 0 < abs(dt_s) < sys.float_info.min or zero_written_nonzero:
        shown = f" of {dt_s:.3g} s" if value_shown and dt_s else ""
        raise RecordFormatError(f"{named}{shown} underflows: below a float's smallest normal number (2.2e-308); no "
                                f"accelerogram has such a step (1e-05 to 0.5 s); a corrupt {corrupt}?")


def parse_float(token: str) -> float:
    """A float from a Fortran-style token (``D`` exponents accepted)."""
    return float(token.replace("D", "E").replace("d", "e"))


def split_numbers(line: str) -> list[str]:
    """The numeric tokens of a line; fixed-width fields that touch (``1.5E+0-2.2E+0``) are split.

    Raises
    ------
    ValueError
        If the line holds something that is not a number.
    """
    tokens = line.split()
    try:
        for token in tokens:
            parse_float(token)
        return tokens
    except ValueError:
        pass
    if _ONLY_NUMBER_CHARS_RE.match(line):
        found = NUMBER_RE.findall(line)
        if "".join(found) == "".join(line.split()):
            return found
    bad = next((t for t in tokens if not _is_number(t)), line.strip())
    raise RecordFormatError(f"non-numeric value {bad[:30]!r}")


def _is_number(token: str) -> bool:
    try:
        parse_float(token)
    except ValueError:
        return False
    return True


def numbers_from_lines(lines: list[str]) -> np.ndarray:
    """All numbers in ``lines`` as float64, fast path first (one numpy conversion).

    Raises
    ------
    ValueError
        Naming the first offending token and its line index within ``lines``.
    """
    try:
        return np.array(" ".join(lines).split(), dtype=np.float64)
    except ValueError:
        pass
    values: list[float] = []
    for index, line in enumerate(lines):
        try:
            values.extend(parse_float(t) for t in split_numbers(line))
        except ValueError as err:
            raise RecordFormatError(f"{err} on data line {index + 1}") from None
    return np.asarray(values, dtype=np.float64)


def iter_line_chunks(stream: IO[str], chunk_lines: int = CHUNK_LINES) -> Iterator[list[str]]:
    """Lists of at most ``chunk_lines`` lines (newline stripped) from a text stream."""
    chunk: list[str] = []
    for line in stream:
        chunk.append(line.rstrip("\r\n"))
        if len(chunk) >= chunk_lines:
            yield chunk
            chunk = []
    if chunk:
        yield chunk
