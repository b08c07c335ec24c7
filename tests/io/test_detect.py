"""isolator.io.detect: the public format detection that reading uses."""

from __future__ import annotations

import numpy as np
import pytest
from _records import at2_text

from isolator.io import detect, numeric_columns, read_head


def test_own_formats_are_detected(tmp_path):
    at2 = tmp_path / "rec.AT2"
    at2.write_text(at2_text([0.01 * np.sin(0.3 * i) for i in range(20)]))
    assert detect(at2) == "PEER_AT2"
    text = tmp_path / "rec.csv"
    text.write_text("# units: g\n0.00,0.1\n0.01,0.2\n0.02,0.3\n")
    assert detect(text) == "ISOLATOR_TEXT"
    assert numeric_columns(read_head(text)) == 2
    binary = tmp_path / "rec.bin"
    binary.write_bytes(b"\x00\x01\xfe\xff" * 100)
    assert detect(binary) is None


@pytest.mark.shared
def test_detect_on_the_shared_records(records_dir):
    assert detect(records_dir / "at2" / "IELC180.AT2") == "PEER_AT2"
    assert detect(records_dir / "other" / "0111a.smc") == "USGS_SMC"
    assert detect(records_dir / "other" / "ce89486SampleInput.v2") == "CSMIP_V2"
    assert detect(records_dir / "converted" / "converted_RSN1044_NORTHR_NWH360.mseed") is None  # obspy's
