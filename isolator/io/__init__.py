"""Readers for the ground-motion file formats that obspy does not read itself.

One module per format, each an obspy waveform plugin (``_is_<fmt>`` strict detector,
``_read_<fmt>`` returning an :class:`obspy.Stream`, the format's header kept in
``stats.<fmt>``), registered through entry points in ``pyproject.toml`` so that, once
isolator is installed, ``obspy.read("RSN1044_NORTHR_NWH360.AT2")`` works and obspy's
format autodetection finds these formats:

========================  ==========================  =====================================
obspy format name         module                      files
========================  ==========================  =====================================
``PEER_AT2``              :mod:`isolator.io.at2`      PEER / NGA ``.AT2`` accelerograms (g)
``ISOLATOR_TEXT``         :mod:`isolator.io.text`     plain one- or two-column text / CSV
``CSMIP_V2``              :mod:`isolator.io.v2`       CSMIP / CGS Volume 2 (cm/s²)
``USGS_SMC``              :mod:`isolator.io.smc`      USGS SMC corrected accelerograms (cm/s²)
========================  ==========================  =====================================

The readers only parse; they raise :class:`~isolator.errors.RecordFormatError` (a
:class:`ValueError`, as obspy's readers raise) with a one-line message without the file
name for malformed content, or another typed :mod:`isolator.errors` error where the
caller can act on it (:class:`~isolator.errors.MissingTimeStepError`).  Units, component choice and every check on the
values belong to :func:`isolator.motion.read_ground_motion`, which names the file.
"""

from __future__ import annotations

import functools

from isolator.io._common import head_lines, looks_like_text, read_head

#: Our formats in the order they are tried: obspy format name → (module, detector name).
FORMATS = {"PEER_AT2": ("isolator.io.at2", "_is_at2"), "CSMIP_V2": ("isolator.io.v2", "_is_v2"),
           "USGS_SMC": ("isolator.io.smc", "_is_smc"), "ISOLATOR_TEXT": ("isolator.io.text", "_is_text")}

__all__ = ["FORMATS", "claims", "detect", "head_lines", "looks_like_text", "numeric_columns", "read_head",
           "read_header"]


def claims(path, fmt: str) -> bool:
    """True when the strict detector of our format ``fmt`` (a key of :data:`FORMATS`) claims ``path``.

    The detector reads a bounded head of the file (the obspy plugin's ``isFormat``), so a
    caller can check a file is what its suffix says before reading it.

    Parameters
    ----------
    path : str or path-like
        The file [-].
    fmt : str
        ``"PEER_AT2"``, ``"CSMIP_V2"``, ``"USGS_SMC"`` or ``"ISOLATOR_TEXT"`` [-].
    """
    import importlib

    module, detector = FORMATS[fmt]
    return bool(getattr(importlib.import_module(module), detector)(path))


def detect(path) -> str | None:
    """The obspy format name of one of isolator's own formats that claims ``path``, or None.

    Each format's strict detector (the obspy plugin's ``isFormat``) is tried in the order
    of :data:`FORMATS`; None means none of them (obspy's own formats are left to
    :func:`obspy.read`).

    Parameters
    ----------
    path : str or path-like
        The file [-].

    Returns
    -------
    str or None
        ``"PEER_AT2"``, ``"CSMIP_V2"``, ``"USGS_SMC"``, ``"ISOLATOR_TEXT"`` or None [-].
    """
    return next((name for name in FORMATS if claims(path, name)), None)


def read_header(path, fmt: str):
    """The header of a file of our format ``fmt`` as an obspy Trace without samples (``headonly``).

    The format's reader is reached through its obspy entry point (``readFormat`` of
    ``obspy.plugin.waveform.<fmt>``, what :func:`obspy.read` calls), without
    :func:`obspy.read`'s per-call work (globbing, stream assembly): a few lines of the file
    are read, a fraction of a millisecond, what a batch needs to group many files by station.

    Parameters
    ----------
    path : str or path-like
        The file [-].
    fmt : str
        A key of :data:`FORMATS` [-].

    Returns
    -------
    obspy.Trace
        ``stats`` from the header, no data [-].

    Raises
    ------
    ValueError
        A damaged header (:class:`~isolator.errors.RecordFormatError`).
    """
    return _entry_point(fmt, "readFormat")(str(path), headonly=True)[0]


@functools.cache
def _entry_point(fmt: str, name: str):
    """The loaded obspy entry point ``name`` (isFormat, readFormat) of waveform format ``fmt``; one scan."""
    from importlib.metadata import entry_points

    (found,) = entry_points().select(group=f"obspy.plugin.waveform.{fmt}", name=name)
    return found.load()


def numeric_columns(head: bytes) -> int | None:
    """Number of numeric columns of the first non-comment line of a file's head, or None (not numbers).

    Parameters
    ----------
    head : bytes
        The first bytes of the file (:func:`read_head`) [-].
    """
    from isolator.io.text import numeric_columns as columns  # obspy loads with the reader: not at import

    return columns(head)
