"""Reading a record file into a GroundMotion: format detection, units, components, checks.

Units are never guessed: they come from the file (AT2: g; V2, SMC: cm/s²; K-NET: the
header's scale factor; SAC: ``kuser0``), from an instrument response (StationXML), or
from the caller (``units=``).  A record whose units are known from nowhere is refused.

Reading applies no processing, with one exception that follows the data provider's own
convention: K-NET records have their mean removed (NIED's "counts × scale factor, minus
the mean").  It is recorded in :attr:`GroundMotion.processing` like any other step.
"""

from __future__ import annotations

import math
import os
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from isolator.errors import (
    ComponentError,
    CountsError,
    GapsError,
    InstrumentResponseError,
    MissingTimeStepError,
    MissingUnitsError,
    RecordError,
    RecordFormatError,
    RecordNotFoundError,
    RecordOptionError,
    RecordValuesError,
    TimeStepConflictError,
    UnitsConflictError,
    UnitsError,
    one_line,
)
from isolator.motion.components import axis_letter, component_label, component_names
from isolator.motion.ground_motion import MAX_ABS_ACCELERATION_G, MIN_SAMPLES, GroundMotion
from isolator.units import STANDARD_GRAVITY, acceleration_factor_to_m_s2

#: Time steps a record may have [s]: accelerograms sample at 100 Hz to 1 kHz (dt 0.001 to
#: 0.05 s).  Below 10 µs (100 kHz) a time step is a corrupt header (DT= 1e-300 made the
#: predominant period sit on its search floor and A0 = 0); above 0.5 s the record cannot
#: carry ground shaking (0.1 to 25 Hz) and its spectrum would need unbounded work.
RECORD_DT_RANGE_S = (1e-5, 0.5)
#: The largest record file read [bytes]: 64 MiB, 2.9 times the 1,000,000-sample text record of
#: docs/performance.md ("A long record", 23.4 MB by its command; the largest of ../shared/records is 0.27 MB).
#: A larger file is refused from its size before any reader opens it: `info` on 100 MB of zero bytes took 39 s
#: and 262 MB (obspy's format detection alone 5.8 s), on 8 GB it ran past 60 s and 2.9 GB (Session 15 sweep,
#: docs/security.md).
MAX_RECORD_BYTES = 64 * 2**20
#: The most segments (obspy traces) a record file may hold: an accelerogram has one per channel, a few more where
#: its data have gaps.  obspy's ``Stream.get_gaps`` compares every pair of segments: a 1 MB MiniSEED of 2,000
#: three-sample segments of one channel took 42 s to its "gaps" refusal, 20,000 (10 MB) ran past 120 s (Session
#: 16 sweep, docs/security.md); 200 is about 0.4 s by that rate.
MAX_SEGMENTS = 200
#: The largest ``--response`` inventory read [bytes]: obspy parsed a 16.4 MB StationXML (61 copies of its example
#: network, responses included) in 4.2 s, so 64 MiB is ~17 s; 100 MB of zero bytes took 16.6 s and 267 MB to
#: "Unknown format" (Session 16 sweep, docs/security.md).  One station's response is ~0.3 MB.
MAX_INVENTORY_BYTES = 64 * 2**20
#: Suffixes read as plain text when no reader claims the file by content.
TEXT_SUFFIXES = frozenset({".txt", ".csv", ".acc", ".dat", ".tsv", ".asc", ".th", ".xy"})
#: SAC ``idep`` codes for quantities that are not acceleration.
_SAC_NOT_ACCELERATION = {6: "displacement (IDISP)", 7: "velocity (IVEL)"}
_SAC_IACC = 8  #: SAC ``idep`` of acceleration (nm/s² by the SAC convention)


#: Formats whose header alone names the station and the component, by file suffix (:func:`read_header`).
_HEADER_FORMATS = {".at2": "PEER_AT2", ".smc": "USGS_SMC"}
_FORMAT_NAMES = {"PEER_AT2": "PEER AT2", "ISOLATOR_TEXT": "plain text", "CSMIP_V2": "CSMIP V2",
                 "USGS_SMC": "USGS SMC"}


def _fail(path: Path | str, message: str, kind: type[RecordError] = RecordFormatError, **attributes) -> RecordError:
    """A typed record error whose one-line message starts with the file's name."""
    return kind(one_line(f"{path}: {message}"), path=str(path), **attributes)


def _read_stream(path: Path, dt_s: float | None):
    """obspy.read with our plugins; explicit text reading as the fallback; RecordError otherwise."""
    import obspy

    from isolator.io import detect, looks_like_text, read_head
    from isolator.io._common import literal_pattern
    from isolator.io.obspy_formats import detect_obspy_format

    head = read_head(path)
    if not head:
        raise _fail(path, "file is empty", RecordNotFoundError)
    if not head.strip():
        raise _fail(path, "file holds only blank space", RecordNotFoundError)
    suffix = path.suffix.lower()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fmt = None
        fmt = detect(path)  # our own formats first: their errors then name the format, and dt_s reaches text
        if suffix == ".at2" and fmt != "PEER_AT2":
            if not looks_like_text(head):
                raise _fail(path, "binary content: not a PEER AT2 text file")
            fmt = "PEER_AT2"  # let the AT2 reader say what is wrong
        try:
            if fmt is None:
                try:  # the format obspy's autodetection would pick, found without its metadata scans
                    return obspy.read(literal_pattern(path), format=detect_obspy_format(path))
                except TypeError as err:
                    if "Unknown format" not in str(err):
                        raise
                if not looks_like_text(head):
                    raise _fail(path, "unrecognised binary format (not one obspy or isolator reads)")
                if suffix not in TEXT_SUFFIXES and not _plain_numeric(head):
                    raise _fail(path, "unsupported format: not a format obspy reads, nor AT2, V2, SMC "
                                      "or plain numeric columns")
                fmt = "ISOLATOR_TEXT"
            options = {"dt_s": dt_s} if fmt == "ISOLATOR_TEXT" else {}
            return obspy.read(literal_pattern(path), format=fmt, **options)
        except RecordError as err:  # a reader's typed error (no time step …): name the file and the format
            if err.path:
                raise
            raise err.located(path, _FORMAT_NAMES.get(fmt, "")) from None
        except Exception as err:  # obspy's readers raise many types for damaged files
            reason = one_line(err) or type(err).__name__
            if fmt in _FORMAT_NAMES:  # our readers' messages say exactly what is wrong
                raise _fail(path, f"{_FORMAT_NAMES[fmt]}: {reason}") from None
            raise _fail(path, f"cannot be read with obspy: {reason}") from None


def _plain_numeric(head: bytes) -> bool:
    """True if the head's first non-comment line is made of numbers (a headerless text record)."""
    from isolator.io import numeric_columns

    return numeric_columns(head) in (1, 2)


def _matches(trace, wanted: str) -> bool:
    names = component_names(trace)
    channel = names["channel"]
    candidates = {trace.id, channel, names["orientation"], component_label(trace)}
    candidates.add(axis_letter(names["orientation"]) or axis_letter(channel))
    if len(channel) == 3:
        candidates.add(channel[2])
    wanted = wanted.strip().lower()
    return wanted in {c.lower() for c in candidates if c}


def _select(path: Path, stream, component: str | None):
    labels = [component_label(trace) for trace in stream]
    if component is None:
        if len(stream) == 1:
            return stream[0]
        raise _fail(path, f"holds {len(stream)} components ({', '.join(labels)}); none was chosen", ComponentError)
    chosen = [trace for trace in stream if _matches(trace, component)]
    if not chosen:
        raise _fail(path, f"no component {component!r} (choices: {', '.join(labels)})", ComponentError, given=component)
    if len(chosen) > 1:
        names = ", ".join(f"{component_label(t)} = {t.id}" for t in chosen)
        raise _fail(path, f"component {component!r} is ambiguous: it matches {names}; the full trace id is unique",
                    ComponentError, given=component)
    return chosen[0]


def _merge(path: Path, stream) -> None:
    """``--merge``: join each channel's segments (obspy ``Stream.merge``), refusing segments of different rates.

    obspy raises a bare ``Exception`` for one channel's segments at different sampling rates (a traceback
    through ``info --merge``, Session 15 sweep): no merge can join them without resampling one, a guess.
    """
    rates: dict[str, set] = {}
    for trace in stream:
        rates.setdefault(trace.id, set()).add(float(trace.stats.sampling_rate))
    for trace_id, found in rates.items():
        if len(found) > 1:
            raise _fail(path, f"channel {trace_id} has segments at different sampling rates ("
                              + ", ".join(f"{rate:g}" for rate in sorted(found)) + " Hz): they cannot be merged "
                              "without resampling one; give each segment in a file of its own")
    for trace_id in rates:
        _refuse_differing_overlap(path, trace_id, sorted((trace for trace in stream if trace.id == trace_id),
                                                         key=lambda trace: trace.stats.starttime))
    stream.merge(method=1, fill_value="interpolate")


def _refuse_differing_overlap(path: Path, trace_id: str, segments) -> None:
    """Refuse two segments of one channel that overlap with different samples.

    obspy's ``merge(method=1)`` keeps the later segment's samples where two overlap (Session 15 sweep): which
    one holds the ground motion is a guess.  Each segment is compared with the earlier one reaching latest; an
    overlap is identical when the later segment's samples sit on the earlier one's sample times (to 1e-3 of a
    step) and equal them exactly.
    """
    reach = segments[0]  # the segment reaching latest so far: any earlier one a segment overlaps, it overlaps
    for later in segments[1:]:  # bounded: each segment once
        earlier = reach
        if later.stats.endtime > reach.stats.endtime:
            reach = later
        dt = earlier.stats.delta
        end = earlier.stats.endtime
        if later.stats.starttime > end + 1e-3 * dt:
            continue  # a gap (interpolated by --merge and recorded), no overlap
        offset = (later.stats.starttime - earlier.stats.starttime) / dt
        first = round(offset)
        count = min(len(earlier.data) - first, len(later.data))
        aligned = abs(offset - first) <= 1e-3
        if aligned and np.array_equal(earlier.data[first:first + count], later.data[:count]):
            continue
        overlap_end = min(end, later.stats.endtime)
        why = ("with different samples" if aligned else
               f"at sample times {abs(offset - first):.3g} of a step apart")
        raise _fail(path, f"channel {trace_id}: two segments overlap from {later.stats.starttime} to "
                          f"{overlap_end} {why}; a merge joins only segments whose overlap is identical, and which of "
                          "these holds the ground motion is not known: keep one")


def _check_gaps(path: Path, stream, merge: bool) -> list[dict]:
    if len(stream) > MAX_SEGMENTS:  # before obspy's get_gaps, whose time grows with the square of the segments
        raise _fail(path, f"holds {len(stream)} segments, more than any accelerogram (one per channel, a few more "
                          f"where the data have gaps); isolator reads files of up to {MAX_SEGMENTS} segments",
                    RecordValuesError)
    gaps = stream.get_gaps()
    if not gaps:
        if len({trace.id for trace in stream}) < len(stream) and merge:
            _merge(path, stream)
            return [{"step": "merge", "method": "obspy Stream.merge(method=1, fill_value='interpolate')",
                     "gaps": 0}]
        if len({trace.id for trace in stream}) < len(stream):
            raise _fail(path, "holds several segments of the same channel, not merged", GapsError)
        return []
    first = gaps[0]
    if not merge:
        kind = "overlap" if first[6] < 0 else "gap"
        raise _fail(
            path,
            f"{len(gaps)} gap(s)/overlap(s) in the data (first: {kind} of {abs(first[6]):g} s in "
            f"{'.'.join(first[:4])} at {first[4]}), not merged",
            GapsError,
        )
    _merge(path, stream)
    return [{"step": "merge", "method": "obspy Stream.merge(method=1, fill_value='interpolate')",
             "gaps": len(gaps), "gap_lengths_s": [float(g[6]) for g in gaps]}]


def _units_factor(path: Path, units: str, source: str) -> float:
    try:
        return acceleration_factor_to_m_s2(units)
    except UnitsError as err:
        raise _fail(path, f"{err} ({source})", RecordOptionError, given=units, parameter="units") from None


def _file_units(trace) -> tuple[str | None, str]:
    """Units stated by the file itself, and a description of where they were found."""
    stats = trace.stats
    fmt = str(stats.get("_format", ""))
    if fmt == "PEER_AT2":
        return "g", "file header (AT2: g)"
    if fmt == "CSMIP_V2":
        return stats.units, f"file header (CSMIP V2: {stats.units})"
    if fmt == "USGS_SMC":
        return stats.units, "file format (USGS SMC corrected: cm/s2)"
    if fmt == "ISOLATOR_TEXT" and stats.get("units"):
        named = stats.get("isolator_text", {}).get("units_from")
        return stats.units, f"file header ({named})" if named else f"file header ('# units: {stats.units}')"
    if fmt == "SAC":
        stated = str(stats.sac.get("kuser0", "") or "").strip()
        if stated and stated.lower().replace(" ", "") in _known_units():
            return stated, f"SAC header kuser0 = {stated!r}"
    return None, ""


def _known_units() -> set[str]:
    from isolator.units import ACCELERATION_UNITS_TO_M_S2

    return set(ACCELERATION_UNITS_TO_M_S2)


#: A K-NET header's 'Duration Time(s)' (whole seconds) may differ from the samples' span by this much [s].
KNET_DURATION_TOLERANCE_S = 1.0
#: A K-NET header's 'Max. Acc. (gal)' (3 decimals) may differ from the demeaned samples' peak by this fraction [-];
#: the shared records' seven K-NET components agree to 5e-4 gal.
KNET_PEAK_TOLERANCE = 0.01


def _check_knet_header(path: Path, stats, demeaned_m_s2: np.ndarray) -> None:
    """A K-NET file whose samples disagree with its own header is refused: a file cut short (half of it read as a
    70.6 s record under 'Duration Time(s) 138') or a 'Scale Factor' or samples of another record (session 25 sweep).
    A step out of range and samples all zero keep their own messages."""
    knet = stats.get("knet", {})
    duration_s, span_s = knet.get("duration"), stats.npts * stats.delta
    step_told = not stats.delta > 0 or dt_problem(stats.delta)  # a step out of range: its own message, later
    if duration_s is not None and not step_told and abs(span_s - duration_s) > KNET_DURATION_TOLERANCE_S:
        raise _fail(path, f"K-NET header states 'Duration Time(s) {duration_s:g}' but the file holds {stats.npts} "
                          f"samples at {stats.delta:g} s ({span_s:g} s): truncated, or a header of another record",
                    RecordFormatError)
    stated_gal, peak_gal = knet.get("accmax"), 100.0 * float(np.max(np.abs(demeaned_m_s2)))
    if stated_gal is not None and peak_gal > 0 and not abs(peak_gal - stated_gal) <= max(KNET_PEAK_TOLERANCE * stated_gal, 1e-3):
        raise _fail(path, f"K-NET header states 'Max. Acc. (gal) {stated_gal:g}' but the samples × its 'Scale "
                          f"Factor' peak at {peak_gal:.5g} gal: a scale factor or samples of another record",
                    RecordFormatError)


def _to_m_s2(path: Path, trace, units, response, counts_factor) -> tuple[np.ndarray, str, list[dict]]:
    """Acceleration in m/s² and the description of the units' source."""
    stats = trace.stats
    fmt = str(stats.get("_format", ""))
    steps: list[dict] = []
    if fmt == "SAC" and int(stats.sac.get("idep", 5)) in _SAC_NOT_ACCELERATION:
        raise _fail(path, f"SAC header says the data are {_SAC_NOT_ACCELERATION[int(stats.sac.idep)]}, "
                          "not acceleration", RecordValuesError)
    if fmt == "SAC":  # kuser0 naming a length or a velocity states the data are not accelerations, whatever --units
        from isolator.io.text import NOT_ACCELERATION_UNITS

        stated = str(stats.sac.get("kuser0", "") or "").strip()
        if stated.lower().replace(" ", "") in NOT_ACCELERATION_UNITS:
            raise _fail(path, f"SAC header kuser0 = {stated!r} is a unit of length or velocity: the data are not "
                              "accelerations", RecordValuesError)
    if response is not None:
        if units is not None or counts_factor is not None:
            raise _fail(path, "an instrument response and units or a counts factor were given: one or the other, not both",
                        RecordOptionError, parameter="response")
        import obspy

        from isolator.io._common import input_file_problem, literal_pattern

        problem = input_file_problem(response)
        if problem is None and os.path.getsize(response) > MAX_INVENTORY_BYTES:
            problem = _too_large(os.path.getsize(response), "larger than a network's StationXML with its "
                                 "responses; isolator reads inventories", MAX_INVENTORY_BYTES)
        if problem is not None:
            raise _fail(path, f"cannot remove the instrument response: {response}: {problem}",
                        InstrumentResponseError)
        try:
            inventory = obspy.read_inventory(literal_pattern(response))
            corrected = trace.copy()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                corrected.remove_response(inventory=inventory, output="ACC")
        except Exception as err:
            raise _fail(path, f"cannot remove the instrument response from {response}: {one_line(err)}",
                        InstrumentResponseError, given=str(response)) from None
        steps.append({"step": "remove_response", "inventory": str(response), "output": "ACC"})
        return corrected.data.astype(np.float64), f"instrument response ({Path(response).name}, output ACC)", steps
    if counts_factor is not None:
        if units is None:
            raise _fail(path, "a counts factor was given without the units it converts counts into", RecordOptionError,
                        parameter="units")
        if not (math.isfinite(counts_factor) and counts_factor > 0):
            raise _fail(path, f"counts factor {counts_factor} is not a positive number", RecordOptionError,
                        given=counts_factor, parameter="counts_factor")
        factor = counts_factor * _units_factor(path, units, "units given")
        return _as_float64(trace) * factor, f"--counts-factor {counts_factor:g} {units} per count", steps
    if fmt == "KNET":
        # obspy's K-NET reader turns the header's 'Scale Factor' (gal per count) into calib [m/s² per count]
        data = _as_float64(trace) * float(stats.calib)
        steps.append({"step": "demean", "reason": "K-NET convention (NIED): counts × scale factor, minus the mean"})
        if units is not None and _units_factor(path, units, "units given") != 1.0:
            raise _fail(path, f"the K-NET scale factor gives m/s2 but the units given are {units}", UnitsConflictError,
                        given=units)
        data = data - data.mean()
        _check_knet_header(path, stats, data)
        return data, "K-NET scale factor (header, gal per count → m/s2)", steps
    if np.issubdtype(trace.data.dtype, np.integer):
        raise _fail(path, "holds integer counts and neither an instrument response (StationXML) nor a counts "
                          "factor with units was given", CountsError)
    file_units, source = _file_units(trace)
    if file_units is not None:
        factor = _units_factor(path, file_units, source)
        if units is not None and _units_factor(path, units, "units given") != factor:
            raise _fail(path, f"the file states {file_units} ({source}) but the units given are {units}",
                        UnitsConflictError, given=units)
        return _as_float64(trace) * factor, source, steps
    if units is None:
        kind = _FORMAT_NAMES.get(fmt, fmt) or "this"
        raise _fail(path, f"{kind} file does not state its units (g, m/s2, gal or cm/s2?)", MissingUnitsError)
    channel = stats.channel or ""
    if fmt in ("MSEED", "SAC", "GSE2", "SEISAN") and len(channel) == 3 and channel[1] in "HL":
        raise _fail(path, f"channel {channel} is a seismometer (velocity) channel; acceleration from it "
                          "needs the instrument response", CountsError)
    source = f"--units {units}"
    if fmt == "SAC" and int(stats.sac.get("idep", 5)) == _SAC_IACC:
        # the header says "acceleration" and, by the SAC convention, nm/s²; files rarely follow it, so the
        # units given are used, but the table says so instead of trusting them silently
        source += " (the SAC header says acceleration, IACC, in nm/s² by convention: check the units)"
        steps.append({"step": "units", "reason": "SAC idep = IACC states acceleration without a usable unit; "
                                                 f"the units given ({units}) were used"})
    return _as_float64(trace) * _units_factor(path, units, "units given"), source, steps


def _as_float64(trace) -> np.ndarray:
    """The trace's samples as float64 (a masked array is refused upstream)."""
    return np.asarray(trace.data, dtype=np.float64)


def _check_values(path: Path, acceleration_m_s2: np.ndarray, dt_s: float, allow_zero: bool = False) -> None:
    if acceleration_m_s2.size < MIN_SAMPLES:
        raise _fail(path, f"only {acceleration_m_s2.size} sample(s); a record needs at least {MIN_SAMPLES}",
                    RecordValuesError)
    problem = dt_problem(dt_s)
    if problem:
        raise _fail(path, problem, RecordValuesError)
    finite = np.isfinite(acceleration_m_s2)
    if not finite.all():
        index = int(np.flatnonzero(~finite)[0])
        raise _fail(path, f"non-finite value ({acceleration_m_s2[index]}) at sample {index} "
                          f"(t = {index * dt_s:g} s)", RecordValuesError)
    peak_m_s2 = float(np.max(np.abs(acceleration_m_s2)))
    if peak_m_s2 > MAX_ABS_ACCELERATION_G * STANDARD_GRAVITY:
        raise _fail(path, f"peak |a| = {peak_m_s2:.4g} m/s2 ({peak_m_s2 / STANDARD_GRAVITY:.4g} g) exceeds "
                          f"{MAX_ABS_ACCELERATION_G:g} g: wrong units?", RecordValuesError)
    if peak_m_s2 == 0.0 and not allow_zero:  # the record's fault: every measure (A0 = PGV²/PGA …) would be 0/0
        raise _fail(path, f"every one of its {acceleration_m_s2.size} samples is zero: no ground motion",
                    RecordValuesError)


def dt_problem(dt_s: float) -> str:
    """Why ``dt_s`` [s] is not the time step of an accelerogram, or "" (see :data:`RECORD_DT_RANGE_S`)."""
    low, high = RECORD_DT_RANGE_S
    if not math.isfinite(dt_s):
        return f"time step dt = {dt_s:g} s is not a finite number"
    if dt_s <= 0:
        return f"time step dt = {dt_s:g} s is not positive"
    if dt_s < low:
        return (f"time step dt = {dt_s:g} s is below {low:g} s (sampling above 100 kHz): no accelerogram has it; "
                "a corrupt header?")
    if dt_s > high:
        return (f"time step dt = {dt_s:g} s is above {high:g} s (sampling below 2 Hz): too coarse for ground "
                "shaking (0.1 to 25 Hz); no accelerogram has it")
    return ""


def _provenance(path: Path, trace, label: str) -> dict:
    stats = trace.stats
    provenance: dict[str, Any] = {
        "path": str(path),
        "format": str(stats.get("_format", "")),
        "network": stats.network,
        "station": stats.station,
        "location": stats.location,
        "channel": stats.channel,
        "component": label,
    }
    if stats.starttime.timestamp != 0:
        provenance["starttime"] = str(stats.starttime)
    for key in ("peer_at2", "usgs_smc", "csmip_v2"):
        if key in stats:
            header = stats[key]
            for name in ("event", "date", "station_name"):
                if header.get(name):
                    provenance[name] = header[name]
            if key == "peer_at2" and header.get("station"):
                provenance["station"] = header["station"]
    if "knet" in stats:
        provenance["event_origin_time"] = str(stats.knet.get("evot", ""))
        provenance["magnitude"] = float(stats.knet.get("mag", math.nan))
    if "sac" in stats and stats.sac.get("kevnm"):
        provenance["event"] = str(stats.sac.kevnm).strip()
    return {key: value for key, value in provenance.items() if value not in ("", None)}


def _check_path(path: Path) -> None:
    from isolator.io._common import input_file_problem

    problem = input_file_problem(path)  # from metadata: a FIFO or a device never blocks the reader
    if problem == "is a folder, not a file":
        raise _fail(path, "is a directory, not a record file", RecordNotFoundError)
    if problem is not None:
        raise _fail(path, problem, RecordNotFoundError)
    try:
        with open(path, "rb") as handle:
            handle.read(1)
    except OSError as err:
        raise _fail(path, f"cannot be opened: {err.strerror or err}", RecordNotFoundError) from None
    size = path.stat().st_size
    if size == 0:
        raise _fail(path, "file is empty", RecordNotFoundError)
    if size > MAX_RECORD_BYTES:
        raise _fail(path, _too_large(size, "larger than any accelerogram (a 1,000,000-sample record is ~23 MB as "
                                           "text); isolator reads record files", MAX_RECORD_BYTES),
                    RecordNotFoundError)


def _too_large(size: int, what: str, limit: int) -> str:
    """The words for a file refused from its size."""
    return f"is {size / 2**20:.1f} MiB, {what} up to {limit // 2**20} MiB"


def read_header(path: str | Path) -> tuple[str, dict] | None:
    """(component label, provenance) of a PEER AT2 or USGS SMC file from its header alone.

    A few lines are read, not the samples (a fraction of a millisecond, the format's obspy
    reader with ``headonly=True``, :func:`isolator.io.read_header`): what a batch needs
    to find the files of one station among many.  None for another format, or for a file
    that is not what its suffix says or cannot be read (reading it in full says why).
    """
    from isolator.io import claims
    from isolator.io import read_header as read_format_header

    path = Path(path)
    fmt = _HEADER_FORMATS.get(path.suffix.lower())
    if fmt is None or not path.is_file():
        return None
    try:
        if not claims(path, fmt):  # a bounded look at the file's head first: text, the format's header
            return None
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            trace = read_format_header(path, fmt)
        label = component_label(trace)
        return label, _provenance(path, trace, label)
    except Exception:  # noqa: BLE001 - any reader failure: not a header we can use here
        return None


def list_components(path: str | Path, *, merge: bool = False) -> list[str]:
    """Components (channels) a record file holds, as accepted by ``component=``.

    Parameters
    ----------
    path : str or path-like
        Record file [-].
    merge : bool, optional
        Join segments of the same channel (see :func:`read_ground_motion`) [-].

    Returns
    -------
    list of str
        One label per component: channel code, orientation, or ``"HN1 (180)"`` [-].

    Raises
    ------
    RecordError
        If the file cannot be read.
    """
    path = Path(path)
    _check_path(path)
    stream = _read_stream(path, None)
    _check_gaps(path, stream, merge)
    return [component_label(trace) for trace in stream]


def _record_path(path) -> Path:
    """``path`` as a Path; anything that is not a path is refused (issue 26: None was a TypeError)."""
    from isolator.errors import RecordNotFoundError

    if isinstance(path, bytes):
        path = os.fsdecode(path)
    if not isinstance(path, (str, os.PathLike)) or not os.fspath(path):
        raise RecordNotFoundError(f"a record is named by a file path, got {path!r}", given=path, parameter="path")
    return Path(path)


def read_ground_motion(
    path: str | Path,
    *,
    component: str | None = None,
    units: str | None = None,
    merge: bool = False,
    response: str | Path | None = None,
    counts_factor: float | None = None,
    dt_s: float | None = None,
    allow_zero: bool = False,
    defaults: bool = False,
) -> GroundMotion:
    """Read a record file into a :class:`GroundMotion` in m/s².

    Parameters
    ----------
    path : str or path-like
        Record file: any obspy format, PEER AT2, CSMIP V2, USGS SMC or plain text [-].
    component : str, optional
        Channel code (``HNE``), its last letter (``E``), orientation (``180``, ``Up``,
        ``NS``), the axis letter of an orientation (``N`` for azimuth 0/180/360, ``E``
        for 90/270, ``Z`` for Up/UD) or trace id; required when the file holds several
        components [-].
    units : {"g", "m/s2", "gal", "cm/s2"}, optional
        Units of the values, for formats that do not state them; must agree with the
        file when it does [-].
    merge : bool, optional
        Join segments of a channel with gaps, filling gaps by linear interpolation
        (obspy ``Stream.merge(method=1, fill_value="interpolate")``); without it a gap
        is an error [-].
    response : str or path-like, optional
        StationXML inventory; the response is removed with obspy ``remove_response``
        (output acceleration) [-].
    counts_factor : float, optional
        Units (given by ``units``) per count, for records in counts [unit/count].
    dt_s : float, optional
        Time step of a one-column text file; checked against the file otherwise [s].
    allow_zero : bool, optional
        Accept a record whose samples are all zero (one component of a pair may be at
        rest; a pair refuses only when every horizontal component is zero) [-].
    defaults : bool, optional
        ``units`` and ``dt_s`` only for a file that does not state them (a batch that
        mixes formats): the file is read as it is, and again with the units (the time
        step) when it raises :class:`~isolator.errors.MissingUnitsError`
        (:class:`~isolator.errors.MissingTimeStepError`).  Without it they must agree
        with a file that states its own [-].

    Returns
    -------
    GroundMotion
        float64 acceleration [m/s²] with units source, provenance and (empty or
        provider-convention) processing.

    Raises
    ------
    RecordError
        One line naming the file and the problem: missing, empty, unrecognised or
        damaged file, truncated data, dt ≤ 0, NaN/inf, non-monotonic time, text in a
        numeric column, fewer than two samples, |a| > 50 g, gaps without ``merge``,
        unknown or conflicting units, ambiguous or unknown component.
    """
    path = _record_path(path)
    if defaults and counts_factor is None:  # a counts factor needs its units, always
        return with_defaults(lambda **given: read_ground_motion(
            path, component=component, merge=merge, response=response, allow_zero=allow_zero, **given),
            units=units, dt_s=dt_s)
    stream, steps = _read_checked_stream(path, merge, dt_s)
    return _motion(path, stream, _select(path, stream, component), steps, units, response, counts_factor, dt_s,
                   allow_zero)


def read_ground_motions(
    path: str | Path,
    *,
    units: str | None = None,
    merge: bool = False,
    response: str | Path | None = None,
    counts_factor: float | None = None,
    dt_s: float | None = None,
    allow_zero: bool = False,
    defaults: bool = False,
) -> list[GroundMotion]:
    """Every component of a record file, in file order, from one reading of the file.

    The same as :func:`read_ground_motion` with each label of :func:`list_components` in
    turn (same arguments, same checks, same results), without parsing the file once per
    component: a pair or a pair with its vertical from a CSMIP V2 file or a MiniSEED
    stream reads it once instead of four times.

    Raises
    ------
    RecordError
        As :func:`read_ground_motion`, for the file or for any of its components.
    """
    path = _record_path(path)
    if defaults and counts_factor is None:
        return with_defaults(lambda **given: read_ground_motions(
            path, merge=merge, response=response, allow_zero=allow_zero, **given), units=units, dt_s=dt_s)
    stream, steps = _read_checked_stream(path, merge, dt_s)
    return [_motion(path, stream, trace, steps, units, response, counts_factor, dt_s, allow_zero)
            for trace in list(stream)]


def with_defaults(read, *, units: str | None = None, dt_s: float | None = None):
    """``read(**given)`` as the file says first, then with the units or the time step its typed error
    asks for (:class:`MissingUnitsError`: ``units``; :class:`MissingTimeStepError`: ``dt_s``).

    Parameters
    ----------
    read : callable
        Reads the file; takes ``units=`` and ``dt_s=`` keywords [-].
    units : str, optional
        Units for a file that does not state them [-].
    dt_s : float, optional
        Time step for a one-column file that gives none [s].

    Raises
    ------
    RecordError
        The error of the last reading (a missing value that was not given is raised as it is).
    """
    fallbacks = ((MissingUnitsError, "units", units), (MissingTimeStepError, "dt_s", dt_s))
    given: dict = {}
    for _ in range(len(fallbacks) + 1):  # each fallback is added once: at most three readings
        try:
            return read(**given)
        except (MissingUnitsError, MissingTimeStepError) as err:
            name, value = next((name, value) for kind, name, value in fallbacks if isinstance(err, kind))
            if value is None or name in given:
                raise
            given[name] = value
    raise AssertionError("unreachable: the last reading returns or raises")  # pragma: no cover


def _read_checked_stream(path: Path, merge: bool, dt_s: float | None):
    """(stream, processing steps of merging) of a record file: the checks before a component is chosen."""
    _check_path(path)
    if dt_s is not None and not (math.isfinite(dt_s) and dt_s > 0):
        raise _fail(path, f"the time step given, {dt_s:g} s, is not positive", RecordOptionError, given=dt_s,
                    parameter="dt_s")
    if dt_s is not None and dt_problem(dt_s):
        raise _fail(path, "the time step given: " + dt_problem(dt_s), RecordOptionError, given=dt_s,
                    parameter="dt_s")
    stream = _read_stream(path, dt_s)
    if len(stream) == 0:
        raise _fail(path, "holds no data")
    steps = _check_gaps(path, stream, merge)
    return stream, steps


def _motion(path: Path, stream, trace, steps, units, response, counts_factor, dt_s, allow_zero) -> GroundMotion:
    """One component (``trace`` of ``stream``) of a record file as a :class:`GroundMotion` in m/s²."""
    components = [component_label(item) for item in stream]
    if np.ma.isMaskedArray(trace.data):
        raise _fail(path, "data are masked (gaps), not merged", GapsError)
    if trace.stats.npts < MIN_SAMPLES:
        raise _fail(path, f"only {trace.stats.npts} sample(s); a record needs at least {MIN_SAMPLES}", RecordValuesError)
    if dt_s is not None and abs(trace.stats.delta - dt_s) > 1e-9 * max(dt_s, 1.0):
        raise _fail(path, f"the file's time step is {trace.stats.delta:g} s but the time step given is {dt_s:g} s",
                    TimeStepConflictError, given=dt_s)
    raw = np.asarray(trace.data, dtype=np.float64)
    finite = np.isfinite(raw)
    if not finite.all():
        index = int(np.flatnonzero(~finite)[0])
        raise _fail(path, f"non-finite value ({raw[index]}) at sample {index} (t = {index * trace.stats.delta:g} s)",
                    RecordValuesError)
    acceleration_m_s2, units_source, unit_steps = _to_m_s2(path, trace, units, response, counts_factor)
    acceleration_m_s2 = np.ascontiguousarray(acceleration_m_s2, dtype=np.float64)
    _check_values(path, acceleration_m_s2, float(trace.stats.delta), allow_zero)
    label = component_label(trace)
    result = trace.copy() if response is None else trace
    result.data = acceleration_m_s2
    result.stats.units = "m/s2"
    result.stats.units_source = units_source
    provenance = _provenance(path, trace, label)
    text_info = trace.stats.get("isolator_text") or {}
    if text_info.get("time_s") is not None:  # a time column with unequal steps: kept as it is
        result.stats.sample_time_s = np.asarray(text_info["time_s"], dtype=np.float64)
        steps_s = np.diff(result.stats.sample_time_s)
        provenance["sampling"] = f"unequal steps from {steps_s.min():g} to {steps_s.max():g} s"
    return GroundMotion(
        trace=result,
        units_source=units_source,
        provenance=provenance,
        processing=list(steps) + unit_steps,
        component=label,
        components=components,
    )
