"""A path names exactly one file; scaling stays within what the reader accepts."""

from __future__ import annotations

import numpy as np
import pytest
from _records import at2_text

from isolator.motion import GroundMotion, RecordError, list_components, read_ground_motion


@pytest.mark.parametrize("name, decoy", [("x[1].AT2", "x1.AT2"), ("a*.AT2", "ab.AT2"), ("b?.AT2", "bc.AT2"),
                                         ("solo[2].AT2", None)])
def test_glob_characters_are_literal(tmp_path, name, decoy):
    wanted = [0.01 * np.sin(0.3 * i) for i in range(20)]
    (tmp_path / name).write_text(at2_text(wanted, dt=".0200"))
    if decoy:  # what obspy's glob expansion would have read instead
        (tmp_path / decoy).write_text(at2_text([0.02 * np.cos(0.1 * i) for i in range(40)]))
    motion = read_ground_motion(tmp_path / name)
    assert (motion.npts, motion.dt_s) == (20, 0.02)
    np.testing.assert_allclose(motion.acceleration_m_s2 / 9.80665, wanted, atol=1e-9)
    assert list_components(tmp_path / name) == [motion.component]


def test_a_path_is_never_a_url(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "http:").mkdir()
    (tmp_path / "http:" / "x.AT2").write_text(at2_text([0.01, 0.02, -0.01, 0.0, 0.03]))
    assert read_ground_motion("http://x.AT2").npts == 5  # a local file, never a download


def test_scaling_is_bounded_like_reading():
    motion = GroundMotion.from_array(np.sin(np.arange(200) * 0.1), 0.01)
    with pytest.raises(ValueError, match="target PGA 100 g exceeds 50 g"):
        motion.scaled_to_pga(100 * 9.80665)
    with pytest.raises(ValueError, match="below 1e-06 g"):
        motion.scaled_to_pga(1e-300)
    assert motion.scaled_to_pga(0.3 * 9.80665).pga_m_s2 == pytest.approx(0.3 * 9.80665)


def test_record_error_is_typed(tmp_path):
    with pytest.raises(RecordError):
        read_ground_motion(tmp_path)


def test_sac_iacc_with_units_given_is_stated_not_silent(tmp_path):
    import obspy

    trace = obspy.Trace(0.1 * np.sin(np.arange(300) * 0.1), header={"delta": 0.01})
    trace.stats.sac = obspy.core.AttribDict({"idep": 8})  # IACC: acceleration, nm/s² by convention
    trace.write(str(tmp_path / "a.sac"), format="SAC")
    motion = read_ground_motion(tmp_path / "a.sac", units="g")
    assert motion.units_source.startswith("--units g (the SAC header says acceleration, IACC, in nm/s²")
    assert motion.processing[-1]["step"] == "units"
    assert motion.pga_m_s2 == pytest.approx(np.abs(trace.data).max() * 9.80665, rel=1e-6)  # float32 in SAC
