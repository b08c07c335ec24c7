"""CSMIP V2 and USGS SMC readers on the real files."""

from __future__ import annotations

import numpy as np
import obspy
import pytest

from isolator.io.smc import _is_smc, _read_smc
from isolator.io.v2 import _is_v2, _read_v2

pytestmark = pytest.mark.shared


def test_v2_three_channels(records_dir):
    path = records_dir / "other/ce89486SampleInput.v2"
    assert _is_v2(path) and not _is_smc(path)
    stream = _read_v2(path)
    assert [tr.stats.channel for tr in stream] == ["HN1", "HN2", "HNZ"]
    assert [tr.stats.csmip_v2.orientation for tr in stream] == ["180", "90", "Up"]
    peaks_g = [round(float(np.max(np.abs(tr.data))) / 980.665, 4) for tr in stream]
    assert peaks_g == [0.3958, 0.2670, 0.1110]
    for trace in stream:
        assert trace.stats.npts == 10100 and trace.stats.delta == 0.01 and trace.stats.units == "cm/s2"
    assert str(stream[0].stats.starttime) == "2022-12-20T10:34:01.000000Z"
    # the header's own peak: -388.166 cm/s² at 35.020 s
    assert stream[0].data[3502] == pytest.approx(-388.16556, abs=1e-5)


def test_smc(records_dir):
    path = records_dir / "other/0111a.smc"
    assert _is_smc(path) and not _is_v2(path)
    trace = _read_smc(path)[0]
    assert trace.stats.npts == 6001 and trace.stats.delta == 0.005
    assert round(float(np.max(np.abs(trace.data))) / 980.665, 4) == 0.1065
    assert trace.data[:2].tolist() == [1.5057, -2.2223]  # touching 10-character fields
    assert trace.stats.usgs_smc.component == "360"


def test_obspy_autodetects_both(records_dir):
    assert obspy.read(str(records_dir / "other/0111a.smc"))[0].stats._format == "USGS_SMC"
    assert len(obspy.read(str(records_dir / "other/ce89486SampleInput.v2"))) == 3


def test_truncated_smc(records_dir, tmp_path):
    lines = (records_dir / "other/0111a.smc").read_bytes().split(b"\r\n")
    path = tmp_path / "cut.smc"
    path.write_bytes(b"\r\n".join(lines[:200]))
    with pytest.raises(ValueError, match="truncated"):
        _read_smc(path)


def test_v2_cut_between_channels_is_truncated_not_fewer_channels(records_dir, tmp_path):
    lines = (records_dir / "other/ce89486SampleInput.v2").read_text(encoding="latin-1").splitlines(keepends=True)
    ends = [i for i, line in enumerate(lines) if line.startswith("/&")]  # the end of each channel
    assert len(ends) == 3
    for kept in (1, 2):  # whole channels only: every block that is there is complete
        path = tmp_path / f"cut{kept}.v2"
        path.write_text("".join(lines[:ends[kept - 1] + 1]), encoding="latin-1")
        with pytest.raises(ValueError, match=f"the header states 3 channels but {kept} were found"):
            _read_v2(path)
