"""Plain-text reader: real one/two-column records, strict detection, layouts, bad files."""

from __future__ import annotations

import numpy as np
import obspy
import pytest

from isolator.errors import MissingTimeStepError
from isolator.io.at2 import _read_at2
from isolator.io.text import _is_text, _read_text


@pytest.mark.shared
def test_elcentro_txt_is_the_at2_plus_a_zero(records_dir):
    trace = _read_text(records_dir / "other/elcentro.txt")[0]
    at2 = _read_at2(records_dir / "at2/elCentro.AT2")[0]
    assert trace.stats.npts == 1560 and trace.stats.delta == 0.02
    np.testing.assert_array_equal(trace.data[:1559], at2.data)
    assert trace.data[-1] == 0.0
    assert "units" not in trace.stats  # the file does not state units


@pytest.mark.shared
def test_one_column_needs_dt_and_equals_the_at2(records_dir):
    with pytest.raises(MissingTimeStepError, match="no time step"):
        _read_text(records_dir / "other/IELC180.acc")
    trace = _read_text(records_dir / "other/IELC180.acc", dt_s=0.01)[0]
    np.testing.assert_array_equal(trace.data, _read_at2(records_dir / "at2/IELC180.AT2")[0].data)


@pytest.mark.shared
def test_csv_with_comment_header(records_dir):
    trace = _read_text(records_dir / "other/Chi-Chi_1999_TCU068-090.csv")[0]
    assert trace.stats.npts == 13102
    assert trace.stats.delta == 0.005
    assert round(float(np.max(np.abs(trace.data))), 4) == 0.5660
    assert trace.stats.isolator_text.comments[1] == "# Time (s),Acceleration (g's)"


@pytest.mark.shared
def test_detector_does_not_claim_real_files_without_our_metadata(records_dir):
    for folder in ("at2", "other", "converted"):
        for path in sorted((records_dir / folder).iterdir()):
            assert not _is_text(path), path


def test_detector_claims_files_with_units_metadata(tmp_path):
    path = tmp_path / "record.dat"
    path.write_text("# units: g\n# dt_s: 0.01\n0.1\n-0.2\n0.3\n")
    assert _is_text(path)
    trace = obspy.read(str(path))[0]  # autodetected through the entry point
    assert trace.stats._format == "ISOLATOR_TEXT"
    assert trace.stats.units == "g" and trace.stats.delta == 0.01
    other = tmp_path / "table.dat"
    other.write_text("# a table\n1 2 3\n4 5 6\n")
    assert not _is_text(other)
    words = tmp_path / "notes.txt"
    words.write_text("# units: g\nhello world\n")
    assert not _is_text(words)


@pytest.mark.parametrize(
    "text",
    [
        "0.0,0.1\n0.5,0.2\n1.0,0.3",
        "0.0;0.1\r\n0.5;0.2\r\n1.0;0.3\r\n",
        "% comment\ntime acc\n0.0 0.1\n0.5\t0.2 \n1.0   0.3\n",
        "! c\n# c\n\n0.0 , 0.1\n0.5 , 0.2\n1.0 , 0.3\n",
    ],
)
def test_two_column_layouts(tmp_path, text):
    path = tmp_path / "r.txt"
    path.write_text(text)
    trace = _read_text(path)[0]
    np.testing.assert_array_equal(trace.data, [0.1, 0.2, 0.3])
    assert trace.stats.delta == 0.5


def test_start_time_kept(tmp_path):
    path = tmp_path / "r.txt"
    path.write_text("10.0 1\n10.1 2\n10.2 3\n")
    trace = _read_text(path)[0]
    assert trace.stats.isolator_text.t0_s == 10.0
    assert trace.stats.delta == pytest.approx(0.1)


@pytest.mark.parametrize(
    ("text", "options", "message"),
    [
        ("0 0.1\n0.01 0.2\n0.005 0.3\n", {}, "time column does not increase at data row 3"),
        ("0 0.1\n0 0.2\n", {}, "does not increase"),
        ("0 0.1\n0.01 0.2\n0.05 0.3\n", {}, "not evenly spaced"),
        ("0 0.1\n0.01 abc\n", {}, "non-numeric value 'abc'"),
        ("0 0.1 1\n", {}, "3 columns"),
        ("0 0.1\n0.01\n", {}, "columns"),
        ("0.1\n0.2\n", {}, "no time step"),
        ("# dt_s: -0.01\n0.1\n0.2\n", {}, "not positive"),
        ("0.1\n0.2\n", {"dt_s": 0.0}, "not positive"),
        ("0 0.1\n0.01 0.2\n", {"dt_s": 0.02}, "disagrees"),
        ("# only comments\n", {}, "no numeric data"),
    ],
)
def test_malformed_text_raises_one_line_value_error(tmp_path, text, options, message):
    path = tmp_path / "bad.txt"
    path.write_text(text)
    with pytest.raises(ValueError) as caught:
        _read_text(path, **options)
    assert message in str(caught.value)
    assert "\n" not in str(caught.value)
