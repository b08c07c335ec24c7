"""detect_obspy_format finds the format obspy's own autodetection finds, file by file."""

from __future__ import annotations

import warnings
from pathlib import Path

import obspy
import pytest
from obspy.core.util.base import _read_from_plugin

from isolator.io.obspy_formats import detect_obspy_format

OBSPY_DATA = Path(obspy.__file__).parent / "io"
BUNDLED = ["nied/tests/data/test.knet", "sac/tests/data/LMOW.BHE.SAC", "mseed/tests/data/1T_MONN_00_EDH.mseed",
           "gse2/tests/data/loc_RJOB20050831023349.z"]


def _obspy_autodetected(path: Path) -> str | None:
    """The format name obspy.read's autodetection settles on (None: obspy knows no format)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            return _read_from_plugin("waveform", str(path))[1]
        except TypeError as err:
            assert "Unknown format" in str(err)
            return None


@pytest.mark.parametrize("relative", BUNDLED)
def test_obspy_bundled_files(relative):
    path = OBSPY_DATA / relative
    if not path.is_file():
        pytest.skip(f"{path} not in this obspy installation")
    expected = _obspy_autodetected(path)
    assert expected is not None  # a real waveform file: the comparison is not vacuous
    assert detect_obspy_format(path) == expected


def test_every_shared_record(records_dir):
    files = sorted(p for p in records_dir.rglob("*") if p.is_file())
    assert files
    assert {str(p): detect_obspy_format(p) for p in files} == {str(p): _obspy_autodetected(p) for p in files}


def test_text_that_no_plugin_claims(tmp_path):
    path = tmp_path / "notes.dat"
    path.write_text("this is not a seismogram\n")
    assert detect_obspy_format(path) is None and _obspy_autodetected(path) is None
