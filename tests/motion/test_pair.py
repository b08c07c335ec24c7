"""Reading pairs: two files, multi-channel files, K-NET sets; mismatches refused or repaired."""

from __future__ import annotations

import numpy as np
import pytest

from isolator.motion import RecordError, read_ground_motion
from isolator.motion.pair import ComponentMismatchError, read_ground_motion_pair

G = 9.80665


@pytest.fixture(scope="module")
def pairs_dir(records_dir):
    return records_dir / "pairs"


def test_csmip_v2_pair_and_all(records_dir):
    path = records_dir / "other" / "ce89486SampleInput.v2"
    pair = read_ground_motion_pair(path, component="pair")
    assert (pair.x.component, pair.y.component, pair.z) == ("HN1 (180)", "HN2 (90)", None)
    every = read_ground_motion_pair(path, component="all")
    # the README's per-channel PGA (0.3958 / 0.2670 / 0.1110 g), units from the V2 header per channel
    assert [round(m.pga_m_s2 / G, 4) for m in every.components.values()] == [0.3958, 0.2670, 0.1110]
    assert every.z.component == "HNZ (Up)" and every.processing == []
    np.testing.assert_array_equal(every.x.acceleration_m_s2,
                                  read_ground_motion(path, component="180").acceleration_m_s2)


def test_vertical_in_the_middle_of_the_file_is_recognised(pairs_dir):
    pair = read_ground_motion_pair(pairs_dir / "ncalifornia2012_89146" / "CE89146.V2", component="all")
    assert (pair.x.component, pair.y.component, pair.z.component) == ("HN1 (360)", "HN3 (90)", "HNZ (Up)")


def test_knet_set_from_any_of_its_files(pairs_dir):
    pair = read_ground_motion_pair(pairs_dir / "iwatemiyagi2008_AOM017" / "AOM0170806140843.UD", component="all")
    assert (pair.x.component, pair.y.component, pair.z.component) == ("NS", "EW", "UD")
    # README: 20.557 / 16.452 / 6.922 gal after the NIED demean
    assert [round(m.pga_m_s2 * 100, 3) for m in pair.components.values()] == [20.557, 16.452, 6.922]


def test_two_at2_files_of_different_lengths(pairs_dir):
    folder = pairs_dir / "superstitionhills1987_PTS"
    x, y = folder / "RSN723_SUPER.B_B-PTS225.AT2", folder / "RSN723_SUPER.B_B-PTS315.AT2"
    with pytest.raises(ComponentMismatchError) as caught:
        read_ground_motion_pair(x, y)
    assert caught.value.kind == "length"
    assert "2235" in str(caught.value) and "2231" in str(caught.value) and "\n" not in str(caught.value)
    trimmed = read_ground_motion_pair(x, y, trim=True)
    assert trimmed.x.npts == trimmed.y.npts == 2231
    assert trimmed.processing == [{"step": "trim_to_common_window", "npts": 2231,
                                   "dropped_samples": {"x": 4, "y": 0}}]
    np.testing.assert_array_equal(trimmed.x.acceleration_m_s2, read_ground_motion(x).acceleration_m_s2[:2231])


def test_smc_files_with_three_lengths_and_a_vertical_given_as_horizontal(pairs_dir):
    folder = pairs_dir / "lomaprieta1989_APEEL2"
    a, b, c = (folder / f"np01002p_4225{k}_a.smc" for k in "abc")
    with pytest.raises(ComponentMismatchError, match="7183 samples.*7184 samples.*7165 samples"):
        read_ground_motion_pair(a, c, b)
    assert read_ground_motion_pair(a, c, b, trim=True).npts == 7165
    with pytest.raises(RecordError, match="is vertical"):
        read_ground_motion_pair(a, b)


def test_different_time_steps_need_resampling_onto_the_union_grid(pairs_dir):
    coarse = pairs_dir / "landers1992_YER" / "RSN900_LANDERS_YER270.AT2"  # dt 0.02 s
    fine = pairs_dir / "duzce1999_DZC" / "RSN1605_DUZCE_DZC180.AT2"  # dt 0.005 s
    for options in ({}, {"trim": True}):
        with pytest.raises(ComponentMismatchError) as caught:
            read_ground_motion_pair(coarse, fine, **options)
        assert caught.value.kind == "dt" and "0.02 s" in str(caught.value) and "0.005 s" in str(caught.value)
    pair = read_ground_motion_pair(coarse, fine, resample=True)
    assert pair.processing[0]["step"] == "common_time_grid" and pair.dt_s == 0.005
    # the coarse record lies on the fine grid: its piecewise-linear signal is unchanged at its own samples
    original = read_ground_motion(coarse)
    np.testing.assert_allclose(pair.x.acceleration_m_s2[::4], original.acceleration_m_s2[:pair.npts // 4 + 1],
                               rtol=0, atol=1e-15)


def test_one_component_file_asked_for_a_pair_is_one_line(records_dir):
    with pytest.raises(RecordError, match="holds one component"):
        read_ground_motion_pair(records_dir / "at2" / "IELC180.AT2", component="pair")
