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

The readers only parse; they raise :class:`ValueError` with a one-line message (without
the file name) for malformed content.  Units, component choice and every check on the
values belong to :func:`isolator.motion.read_ground_motion`, which names the file.
"""

from __future__ import annotations
