"""Tables and builders shared by the tests (imported as ``_records``; see conftest.py).

``RECORD_TABLE`` and ``PGV_TABLE_CM_S`` copy the tables of ``../shared/records/README.md``;
``BAD_RECORDS`` builds every kind of malformed record file in a temporary folder.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

#: The README's table: file → (NPTS, DT [s], PGA as printed [g], options needed to read it).
#: PGA strings keep the README's digits; tests compare to that many decimals.
RECORD_TABLE: dict[str, tuple[int, float, str, dict]] = {
    "at2/IELC180.AT2": (4000, 0.01, "0.3129", {}),
    "at2/elCentro.AT2": (1559, 0.02, "0.3188", {}),
    "at2/elCentro_verification.at2": (1559, 0.02, "0.3188", {}),
    "at2/ARL360.at2": (2000, 0.02, "0.3081", {}),
    "at2/RSN1044_NORTHR_NWH360.AT2": (2000, 0.02, "0.5904", {}),
    "at2/RSN1004_NORTHR_SPV360.AT2": (9559, 0.005, "0.9320", {}),
    "at2/RSN1120_KOBE_TAK000.AT2": (4096, 0.01, "0.6177", {}),
    "at2/TAK000.AT2": (4096, 0.01, "0.6177", {}),
    "at2/RSN1106_KOBE_KJM000.AT2": (7500, 0.02, "0.8342", {}),
    "at2/RSN779_LOMAP_LGP000.AT2": (5001, 0.005, "0.5700", {}),
    "at2/TCU052-N.AT2": (18000, 0.005, "0.4190", {}),
    "at2/RSN1176_KOCAELI_YPT060.AT2": (7000, 0.005, "0.2268", {}),
    "other/elcentro.txt": (1560, 0.02, "0.3188", {"units": "g"}),
    "other/IELC180.acc": (4000, 0.01, "0.3129", {"units": "g", "dt_s": 0.01}),
    "other/Chi-Chi_1999_TCU068-090.csv": (13102, 0.005, "0.5660", {"units": "g"}),
    "other/ce89486SampleInput.v2#180": (10100, 0.01, "0.3958", {"component": "180"}),
    "other/ce89486SampleInput.v2#90": (10100, 0.01, "0.2670", {"component": "90"}),
    "other/ce89486SampleInput.v2#Up": (10100, 0.01, "0.1110", {"component": "Up"}),
    "other/0111a.smc": (6001, 0.005, "0.1065", {}),
    "other/AOM0081801241951.NS": (13800, 0.01, "0.0369", {}),
    "other/AOM0081801241951.EW": (13800, 0.01, "0.0308", {}),
    "other/AOM0081801241951.UD": (13800, 0.01, "0.0190", {}),
    "other/test.knet": (5900, 0.01, "0.00447", {}),
    "converted/converted_RSN1044_NORTHR_NWH360.mseed": (2000, 0.02, "0.5904", {"units": "m/s2"}),
    "converted/converted_RSN1044_NORTHR_NWH360.sac": (2000, 0.02, "0.5904", {}),
    "converted/converted_RSN779_LOMAP_LGP000.mseed": (5001, 0.005, "0.5700", {"units": "m/s2"}),
    "converted/converted_RSN779_LOMAP_LGP000.sac": (5001, 0.005, "0.5700", {}),
}

#: The README's PGV table (cm/s, plain trapezoidal integration, no filtering).
PGV_TABLE_CM_S: dict[str, float] = {
    "at2/IELC180.AT2": 29.7, "at2/elCentro.AT2": 36.1, "at2/ARL360.at2": 23.1,
    "at2/RSN1044_NORTHR_NWH360.AT2": 96.6, "at2/RSN1004_NORTHR_SPV360.AT2": 76.2,
    "at2/TAK000.AT2": 120.6, "at2/RSN1106_KOBE_KJM000.AT2": 91.1, "at2/RSN779_LOMAP_LGP000.AT2": 96.1,
    "at2/TCU052-N.AT2": 118.5, "at2/RSN1176_KOCAELI_YPT060.AT2": 69.7,
    "other/Chi-Chi_1999_TCU068-090.csv": 176.9,
}


def decimals(printed: str) -> int:
    """Number of decimals of a number as printed in the README ("0.00447" → 5)."""
    return len(printed.split(".")[1]) if "." in printed else 0


def record_path(records_dir: Path, key: str) -> Path:
    """Path of a RECORD_TABLE key (``file#component`` keys name one channel)."""
    return records_dir / key.split("#")[0]


# --------------------------------------------------------------------------------------
# Malformed records, built in tmp_path
# --------------------------------------------------------------------------------------

AT2_HEADER = (
    "PEER NGA STRONG MOTION DATABASE RECORD\n"
    "Synthetic-01, 1/1/2000, Test Station, 90\n"
    "ACCELERATION TIME SERIES IN UNITS OF G\n"
)


def at2_text(values, npts: int | None = None, dt: str = ".0100") -> str:
    """An NGA-West2-style AT2 file holding ``values`` (g), 5 per line."""
    values = list(values)
    npts = len(values) if npts is None else npts
    body = ""
    for start in range(0, len(values), 5):
        body += "".join(f"{v:15.7E}" if isinstance(v, float) else f"{v:>15}" for v in values[start:start + 5]) + "\n"
    return AT2_HEADER + f"NPTS=   {npts}  DT=   {dt} SEC,\n" + body


def _gappy_mseed(path: Path) -> None:
    from obspy import Stream, Trace, UTCDateTime

    first = Trace(np.sin(np.arange(500) * 0.1), header={"delta": 0.01, "station": "GAP", "channel": "HNE",
                                                        "starttime": UTCDateTime(2020, 1, 1)})
    second = first.copy()
    second.stats.starttime = first.stats.endtime + 0.5  # 0.49 s missing
    Stream([first, second]).write(str(path), format="MSEED")


_SINE = [0.01 * np.sin(0.3 * i) for i in range(20)]

#: name → (file name, builder(path), read options, words the message must hold)
BAD_RECORDS = {
    "empty": ("empty.AT2", lambda p: p.write_text(""), {}, ["empty"]),
    "blank": ("blank.txt", lambda p: p.write_text("\n  \n"), {"units": "g"}, ["blank"]),
    "only_comments": ("comments.txt", lambda p: p.write_text("# nothing\n# here\n"), {"units": "g"}, ["no numeric"]),
    "truncated": ("trunc.AT2", lambda p: p.write_text(at2_text(_SINE, npts=25)), {}, ["truncated", "NPTS=25"]),
    "too_many": ("many.AT2", lambda p: p.write_text(at2_text(_SINE, npts=15)), {}, ["more", "NPTS=15"]),
    "dt_zero": ("dt0.AT2", lambda p: p.write_text(at2_text(_SINE, dt="0.0")), {}, ["DT=0", "not positive"]),
    "dt_negative": ("dtneg.AT2", lambda p: p.write_text(at2_text(_SINE, dt="-.0100")), {}, ["not positive"]),
    "dt_zero_option": ("one.acc", lambda p: p.write_text("0.1\n0.2\n0.3\n"), {"units": "g", "dt_s": 0.0},
                       ["time step given", "not positive"]),
    "nan": ("nan.AT2", lambda p: p.write_text(at2_text(_SINE[:7] + ["NaN"] + _SINE[8:])), {}, ["non-finite", "sample 7"]),
    "inf": ("inf.txt", lambda p: p.write_text("0 0.1\n0.01 inf\n0.02 0.3\n"), {"units": "g"}, ["non-finite"]),
    "non_monotonic_time": ("time.csv", lambda p: p.write_text("0.00,0.1\n0.01,0.2\n0.03,0.3\n0.02,0.1\n"),
                           {"units": "g"}, ["time column does not increase"]),
    "uneven_time_with_dt": ("uneven.txt", lambda p: p.write_text("0 0.1\n0.01 0.2\n0.03 0.3\n0.04 0.1\n"),
                            {"units": "g", "dt_s": 0.01}, ["not evenly spaced"]),
    "text_in_column": ("text.csv", lambda p: p.write_text("0.00,0.1\n0.01,abc\n0.02,0.3\n"), {"units": "g"},
                       ["non-numeric", "abc"]),
    "text_in_at2": ("text.AT2", lambda p: p.write_text(at2_text(_SINE[:12] + ["oops"] + _SINE[13:])), {},
                    ["non-numeric", "oops"]),
    "three_columns": ("three.txt", lambda p: p.write_text("0 0.1 5\n0.01 0.2 6\n"), {"units": "g"}, ["3 columns"]),
    "no_dt_one_column": ("nodt.acc", lambda p: p.write_text("0.1\n0.2\n0.3\n"), {"units": "g"}, ["no time step"]),
    "binary_at2": ("garbage.AT2", lambda p: p.write_bytes(bytes(np.random.default_rng(1).integers(0, 256, 4000,
                                                                                              dtype=np.uint8))),
                   {}, ["binary"]),
    "binary_unknown": ("garbage.bin", lambda p: p.write_bytes(b"\x00\x01\xfe\xff" * 1000), {}, ["unrecognised"]),
    "no_npts_line": ("header.AT2", lambda p: p.write_text(AT2_HEADER + "values follow\n 0.1 0.2\n"), {},
                     ["NPTS"]),
    "absurd_magnitude": ("huge.AT2", lambda p: p.write_text(at2_text(_SINE[:5] + [80.0] + _SINE[6:])), {},
                         ["exceeds 50 g", "units"]),
    "absurd_units": ("gal_as_g.txt", lambda p: p.write_text("0 100\n0.01 -980\n0.02 300\n"), {"units": "g"},
                     ["exceeds 50 g"]),
    "single_sample": ("one.AT2", lambda p: p.write_text(at2_text([0.1])), {}, ["only 1 sample"]),
    "single_row": ("one.txt", lambda p: p.write_text("0.0 0.1\n"), {"units": "g"}, ["only 1 sample"]),
    "gaps": ("gappy.mseed", _gappy_mseed, {"units": "m/s2"}, ["gap", "not merged"]),
    "no_units": ("nounits.txt", lambda p: p.write_text("0 0.1\n0.01 0.2\n0.02 0.3\n"), {}, ["does not state its units"]),
    "unknown_units": ("units.txt", lambda p: p.write_text("0 0.1\n0.01 0.2\n"), {"units": "furlong/s2"},
                      ["unknown acceleration unit"]),
    "conflicting_units": ("conflict.AT2", lambda p: p.write_text(at2_text(_SINE)), {"units": "gal"},
                          ["states g", "units given are gal"]),
    "missing": ("missing.AT2", lambda p: None, {}, ["no such file"]),
    # hostile inputs (issue 13): never a hang, never "no such file" for what exists
    "fifo": ("pipe.AT2", lambda p: __import__("os").mkfifo(p), {}, ["FIFO", "not a regular file"]),
    "symlink_loop": ("loop.AT2", lambda p: (p.symlink_to(p.with_name("loop2.AT2")),
                                            p.with_name("loop2.AT2").symlink_to(p)), {}, ["symbolic-link loop"]),
    "dangling_link": ("dangling.AT2", lambda p: p.symlink_to(p.with_name("gone.AT2")), {},
                      ["dangling symbolic link"]),
    "folder": ("folder.AT2", lambda p: p.mkdir(), {}, ["is a directory"]),
    "all_zero": ("zeros.AT2", lambda p: p.write_text(at2_text([0.0] * 20)), {}, ["every one of its 20 samples is zero"]),
    "dt_tiny": ("dttiny.AT2", lambda p: p.write_text(at2_text(_SINE, dt="1e-300")), {}, ["below 1e-05 s"]),
    "dt_huge": ("dthuge.AT2", lambda p: p.write_text(at2_text(_SINE, dt="100.0")), {}, ["above 0.5 s"]),
    "dt_option_huge": ("coarse.acc", lambda p: p.write_text("0.1\n0.2\n0.3\n"), {"units": "g", "dt_s": 100.0},
                       ["time step given", "above 0.5 s"]),
}

#: The typed error (``isolator.errors``) of the bad records a caller can act on, and the command-line
#: option the CLI names for it (the library's message never names a flag).
BAD_RECORD_TYPES = {
    "dt_zero_option": ("RecordOptionError", "--dt"),
    "dt_option_huge": ("RecordOptionError", "--dt"),
    "no_dt_one_column": ("MissingTimeStepError", "--dt"),
    "gaps": ("GapsError", "--merge"),
    "no_units": ("MissingUnitsError", "--units"),
    "unknown_units": ("RecordOptionError", "--units"),
    "conflicting_units": ("UnitsConflictError", "--units says gal"),
    "missing": ("RecordNotFoundError", ""),
    "empty": ("RecordNotFoundError", ""),
    "nan": ("RecordValuesError", ""),
    "absurd_magnitude": ("RecordValuesError", ""),
    "truncated": ("RecordFormatError", ""),
    "binary_unknown": ("RecordFormatError", ""),
    "fifo": ("RecordNotFoundError", ""),
    "symlink_loop": ("RecordNotFoundError", ""),
    "dangling_link": ("RecordNotFoundError", ""),
    "folder": ("RecordNotFoundError", ""),
    "all_zero": ("RecordValuesError", ""),
    "dt_tiny": ("RecordValuesError", ""),
    "dt_huge": ("RecordValuesError", ""),
}


def assert_one_line_exit_2(result, *needles: str) -> str:
    """A CLI mistake as the brief wants it: exit 2, one non-empty line holding every needle, no traceback."""
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert result.exit_code == 2, result.output
    assert len(lines) == 1 and "Traceback" not in result.output, result.output
    for needle in needles:
        assert needle in lines[0], (needle, lines[0])
    return lines[0]
