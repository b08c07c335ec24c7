"""PEER AT2 reader: real header variants, obspy plugin registration, strict detection, bad files."""

from __future__ import annotations

import io

import numpy as np
import obspy
import pytest
from _records import RECORD_TABLE, at2_text, decimals, record_path

from isolator.io.at2 import _is_at2, _read_at2

AT2_KEYS = [key for key in RECORD_TABLE if key.startswith("at2/")]


@pytest.mark.shared
@pytest.mark.parametrize("key", AT2_KEYS)
def test_real_at2_matches_readme_table(records_dir, key):
    npts, dt_s, pga_g, _ = RECORD_TABLE[key]
    path = record_path(records_dir, key)
    assert _is_at2(path)
    trace = _read_at2(path)[0]
    assert trace.stats.npts == npts
    assert trace.stats.delta == pytest.approx(dt_s, rel=1e-12)
    assert trace.data.dtype == np.float64
    assert round(float(np.max(np.abs(trace.data))), decimals(pga_g)) == float(pga_g)
    assert trace.stats.units == "g"
    assert trace.stats.peer_at2.units_stated_in_header


@pytest.mark.shared
@pytest.mark.parametrize("key", AT2_KEYS)
def test_obspy_read_finds_at2_through_entry_points(records_dir, key):
    stream = obspy.read(str(record_path(records_dir, key)))
    assert stream[0].stats._format == "PEER_AT2"
    assert stream[0].stats.npts == RECORD_TABLE[key][0]


@pytest.mark.shared
def test_header_variants_share_data(records_dir):
    tak = _read_at2(records_dir / "at2/TAK000.AT2")[0]
    rsn = _read_at2(records_dir / "at2/RSN1120_KOBE_TAK000.AT2")[0]
    np.testing.assert_array_equal(tak.data, rsn.data)
    short = _read_at2(records_dir / "at2/elCentro.AT2")[0]
    verification = _read_at2(records_dir / "at2/elCentro_verification.at2")[0]
    np.testing.assert_array_equal(short.data, verification.data)
    assert verification.stats.peer_at2.trailer == ["*** End Data ***"]


@pytest.mark.shared
def test_title_line_parsed(records_dir):
    header = _read_at2(records_dir / "at2/RSN1044_NORTHR_NWH360.AT2")[0].stats.peer_at2
    assert (header.event, header.date, header.station, header.component) == (
        "Northridge-01", "1/17/1994", "Newhall - Fire Sta", "360")
    assert "event" not in _read_at2(records_dir / "at2/elCentro.AT2")[0].stats.peer_at2


@pytest.mark.shared
def test_detector_is_strict_on_other_records(records_dir):
    for path in sorted((records_dir / "other").iterdir()) + sorted((records_dir / "converted").iterdir()):
        assert not _is_at2(path), path


def test_reversed_npts_dt_order_cr_cr_lf_and_touching_fields(tmp_path):
    path = tmp_path / "old.at2"
    body = "   4096   0.0100   NPTS, DT\r\r\n" + "  -0.12345-0.23456   0.34567\r\r\n" + "   0.00001"
    path.write_bytes(("TITLE\r\r\nSOME EVENT\r\r\nACCELERATION IN UNITS OF G\r\r\n" + body).replace(
        "4096", "4").encode())
    assert _is_at2(path)
    trace = _read_at2(path)[0]
    np.testing.assert_array_equal(trace.data, [-0.12345, -0.23456, 0.34567, 0.00001])
    assert trace.stats.delta == 0.01


def test_reads_from_a_buffer():
    text = at2_text([0.1, -0.2, 0.3, 0.0, 0.05, 0.01])
    buffer = io.BytesIO(text.encode())
    assert _is_at2(buffer) and buffer.tell() == 0
    np.testing.assert_allclose(_read_at2(buffer)[0].data, [0.1, -0.2, 0.3, 0.0, 0.05, 0.01], rtol=1e-7)


def test_headonly(tmp_path):
    path = tmp_path / "h.AT2"
    path.write_text(at2_text([0.1, 0.2, 0.3]))
    trace = _read_at2(path, headonly=True)[0]
    assert trace.stats.npts == 3 and trace.data.size == 0


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (at2_text([0.1, 0.2], npts=5), "truncated: 2 values but the header says NPTS=5"),
        (at2_text([0.1, 0.2, 0.3], npts=2), "more than the header's NPTS=2"),
        (at2_text([0.1, 0.2], dt="0.0"), "not positive"),
        (at2_text([0.1, "x1", 0.3]), "non-numeric value 'x1'"),
        ("PEER NGA\nno npts here\n", "no 'NPTS=…, DT=…' line"),
        ("PEER NGA STRONG MOTION DATABASE RECORD\nX, 1/1/2000, S, 0\nVELOCITY TIME SERIES IN UNITS OF CM/S\n"
         "NPTS=   2  DT=   .0100 SEC,\n .1 .2\n", "velocity or displacement"),
        ("PEER NGA STRONG MOTION DATABASE RECORD\nX, 1/1/2000, S, 0\nACCELERATION TIME SERIES IN UNITS OF CM/S/S\n"
         "NPTS=   2  DT=   .0100 SEC,\n .1 .2\n", "header states units 'CM/S/S'"),
    ],
)
def test_malformed_at2_raises_one_line_value_error(tmp_path, text, message):
    path = tmp_path / "bad.AT2"
    path.write_text(text)
    with pytest.raises(ValueError) as caught:
        _read_at2(path)
    assert message in str(caught.value)
    assert "\n" not in str(caught.value)


def test_detector_rejects_binary_and_plain_text(tmp_path):
    binary = tmp_path / "b.AT2"
    binary.write_bytes(bytes(range(256)) * 10)
    plain = tmp_path / "p.txt"
    plain.write_text("0 0.1\n0.01 0.2\n")
    assert not _is_at2(binary)
    assert not _is_at2(plain)
    assert not _is_at2(tmp_path / "missing.AT2")


def test_entry_points_registered_and_obspy_autodetects(tmp_path):
    """After installation obspy itself reads AT2 (no shared records needed)."""
    from importlib.metadata import entry_points

    names = {ep.name for ep in entry_points(group="obspy.plugin.waveform")}
    assert {"PEER_AT2", "CSMIP_V2", "USGS_SMC", "ISOLATOR_TEXT"} <= names
    functions = {ep.name: ep.value for ep in entry_points(group="obspy.plugin.waveform.PEER_AT2")}
    assert functions == {"isFormat": "isolator.io.at2:_is_at2", "readFormat": "isolator.io.at2:_read_at2"}
    path = tmp_path / "RSN0_SYNTH.AT2"
    path.write_text(at2_text([0.1, -0.2, 0.3, 0.05, 0.0, -0.01, 0.02]))
    stream = obspy.read(str(path))
    assert stream[0].stats._format == "PEER_AT2"
    np.testing.assert_allclose(stream[0].data, [0.1, -0.2, 0.3, 0.05, 0.0, -0.01, 0.02], rtol=1e-7)
