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


def test_miniseed_stream_of_three_channels(records_dir, tmp_path):
    from obspy import Stream, Trace, UTCDateTime

    source = read_ground_motion_pair(records_dir / "other" / "ce89486SampleInput.v2", component="all")
    traces = []
    for channel, motion in zip(("HNZ", "HNN", "HNE"), (source.z, source.x, source.y), strict=False):  # the vertical first
        trace = Trace(data=motion.acceleration_m_s2.astype(np.float64))
        trace.stats.update({"network": "CE", "station": "89486", "channel": channel, "delta": motion.dt_s,
                            "starttime": UTCDateTime(2022, 12, 20, 10, 34, 1)})
        traces.append(trace)
    path = tmp_path / "three.mseed"
    Stream(traces).write(str(path), format="MSEED")
    with pytest.raises(RecordError, match="does not state its units"):
        read_ground_motion_pair(path, component="all")
    pair = read_ground_motion_pair(path, component="all", units="m/s2")
    assert (pair.x.component, pair.y.component, pair.z.component) == ("HNN", "HNE", "HNZ")
    for ours, theirs in ((pair.x, source.x), (pair.y, source.y), (pair.z, source.z)):
        np.testing.assert_array_equal(ours.acceleration_m_s2, theirs.acceleration_m_s2)


def test_unequal_steps_of_two_components_are_joined_exactly(tmp_path):
    # dt 0.02 s and 0.03 s: the union of the sample times has unequal steps (0.01 and 0.02 s)
    rng = np.random.default_rng(3)
    t_x, t_y = 0.02 * np.arange(301), 0.03 * np.arange(201)
    a_x, a_y = rng.normal(0, 2.0, t_x.size), rng.normal(0, 2.0, t_y.size)
    paths = []
    for name, t, a in (("x.txt", t_x, a_x), ("y.txt", t_y, a_y)):
        np.savetxt(tmp_path / name, np.column_stack([t, a]), fmt="%.17g", header="units: m/s2")
        paths.append(tmp_path / name)
    pair = read_ground_motion_pair(*paths, resample=True)
    assert pair.sample_times_s is not None and pair.duration_s == pytest.approx(6.0)
    # the same piecewise-linear signals on the uniform 0.01 s grid (every breakpoint is on it)
    grid = 0.01 * np.arange(601)
    np.testing.assert_allclose(np.interp(grid, pair.time_s, pair.x.acceleration_m_s2), np.interp(grid, t_x, a_x),
                               atol=1e-12)
    np.testing.assert_allclose(np.interp(grid, pair.time_s, pair.y.acceleration_m_s2), np.interp(grid, t_y, a_y),
                               atol=1e-12)
    # the 2-D engine on the two samplings of one signal (issue 10: the answer must not depend on the sampling)
    joined, uniform = _two_samplings(pair, grid, t_x, a_x, t_y, a_y)
    assert joined.peak_displacement_m == pytest.approx(uniform.peak_displacement_m, rel=1e-9)
    assert joined.residual_displacement_m == pytest.approx(uniform.residual_displacement_m, rel=1e-9)


def _two_samplings(pair, grid, t_x, a_x, t_y, a_y):
    from isolator.solver.planar import simulate_pair

    joined = simulate_pair(pair.x.acceleration_m_s2, pair.y.acceleration_m_s2, time_s=pair.time_s,
                           mu_static=0.05, radius_m=2.0)
    uniform = simulate_pair(np.interp(grid, t_x, a_x), np.interp(grid, t_y, a_y), 0.01, mu_static=0.05,
                            radius_m=2.0)
    return joined, uniform


def test_two_samplings_of_one_pair_agree_to_the_issue_tolerance(tmp_path):
    # read from files and joined by --resample, as a user would (planar before 06d906b differed by 2e-8 here)
    rng = np.random.default_rng(3)
    t_x, t_y = 0.02 * np.arange(301), 0.03 * np.arange(201)
    a_x, a_y = rng.normal(0, 2.0, t_x.size), rng.normal(0, 2.0, t_y.size)
    for name, t, a in (("x.txt", t_x, a_x), ("y.txt", t_y, a_y)):
        np.savetxt(tmp_path / name, np.column_stack([t, a]), fmt="%.17g", header="units: m/s2")
    pair = read_ground_motion_pair(tmp_path / "x.txt", tmp_path / "y.txt", resample=True)
    joined, uniform = _two_samplings(pair, 0.01 * np.arange(601), t_x, a_x, t_y, a_y)
    assert joined.peak_displacement_m == pytest.approx(uniform.peak_displacement_m, rel=1e-9)


def test_start_times_that_differ_by_whole_samples_are_trimmed_into_line(tmp_path):
    rng = np.random.default_rng(8)
    a_x, a_y = rng.normal(0, 1.0, 400), rng.normal(0, 1.0, 400)
    for name, t0, a in (("x.txt", 0.0, a_x), ("y.txt", 0.05, a_y)):  # Y starts 5 samples later
        np.savetxt(tmp_path / name, np.column_stack([t0 + 0.01 * np.arange(a.size), a]), fmt="%.17g",
                   header="units: m/s2")
    with pytest.raises(ComponentMismatchError) as caught:
        read_ground_motion_pair(tmp_path / "x.txt", tmp_path / "y.txt")
    assert caught.value.kind == "start"
    pair = read_ground_motion_pair(tmp_path / "x.txt", tmp_path / "y.txt", trim=True)
    assert pair.npts == 395 and pair.processing[0]["dropped_samples"] == {"x": 5, "y": 5}
    np.testing.assert_array_equal(pair.x.acceleration_m_s2, a_x[5:])
    np.testing.assert_array_equal(pair.y.acceleration_m_s2, a_y[:395])


def test_kiknet_surface_set_by_its_suffixes(pairs_dir, tmp_path):
    import shutil

    # KiK-net names the surface set .NS2/.EW2/.UD2 (the borehole .NS1 …); the content is K-NET ASCII
    for suffix in ("NS", "EW", "UD"):
        shutil.copy(pairs_dir / "iwatemiyagi2008_AOM017" / f"AOM0170806140843.{suffix}",
                    tmp_path / f"AOM0170806140843.{suffix}2")
    pair = read_ground_motion_pair(tmp_path / "AOM0170806140843.EW2", component="all")
    knet = read_ground_motion_pair(pairs_dir / "iwatemiyagi2008_AOM017" / "AOM0170806140843.NS", component="all")
    for ours, theirs in zip(pair.components.values(), knet.components.values(), strict=False):
        np.testing.assert_array_equal(ours.acceleration_m_s2, theirs.acceleration_m_s2)


def _v2_channels(path, out_dir):
    """The channel blocks of a CSMIP V2 file, each written as a one-channel V2 file of its own."""
    text = path.read_text(errors="replace").splitlines(keepends=True)
    blocks, current = [], []
    for line in text:
        current.append(line)
        if line.startswith("/&"):
            blocks.append(current)
            current = []
    files = []
    for k, block in enumerate(blocks, 1):
        files.append(out_dir / f"chan{k}.v2")
        # the header states the channels the file holds: one
        files[-1].write_text("".join(block).replace("(3 Chns of  3 at Sta)", "(1 Chns of  3 at Sta)"))
    return files


def test_vertical_file_of_several_channels_gives_its_vertical(records_dir, tmp_path):
    """--vertical FILE takes the file's one vertical channel; a multi-channel --pair file is refused."""
    v2 = records_dir / "other" / "ce89486SampleInput.v2"
    every = read_ground_motion_pair(v2, component="all")
    x, y, _ = _v2_channels(v2, tmp_path)  # one-channel V2 files: 180 and 90
    pair = read_ground_motion_pair(x, y, v2)
    assert (pair.x.component, pair.y.component, pair.z.component) == ("HN1 (180)", "HN2 (90)", "HNZ (Up)")
    for axis in "xyz":
        np.testing.assert_array_equal(pair.components[axis].acceleration_m_s2,
                                      every.components[axis].acceleration_m_s2)
    # a second horizontal given as a file of several channels: one line saying what to do
    with pytest.raises(RecordError, match=r"holds 3 components .*; the second horizontal of a pair is a file of "
                                          r"one component") as caught:
        read_ground_motion_pair(x, v2)
    assert caught.value.parameter == "second_file"
    # a vertical file of several channels with no vertical among them
    two = tmp_path / "two.v2"  # the two horizontal channels only
    two.write_text((x.read_text() + y.read_text()).replace("(1 Chns of  3 at Sta)", "(2 Chns of  3 at Sta)", 1))
    with pytest.raises(RecordError, match=r"holds 2 components .* no vertical; the vertical of a pair is a file "
                                          r"of one component or the one vertical channel of a file") as caught:
        read_ground_motion_pair(x, y, two)
    assert caught.value.parameter == "vertical"


def test_cli_pair_and_vertical_file_messages(records_dir, tmp_path):
    from typer.testing import CliRunner

    from isolator.cli import app

    v2 = records_dir / "other" / "ce89486SampleInput.v2"
    x = _v2_channels(v2, tmp_path)[0]
    result = CliRunner().invoke(app, ["simulate", str(x), "--pair", str(v2), "--mu-s", "0.06", "--radius-m", "2"])
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and "--component pair" in lines[0] and "trace id" not in lines[0]


def test_one_motion_twice_is_not_a_pair(pairs_dir, tmp_path):
    x = pairs_dir / "superstitionhills1987_PTS" / "RSN723_SUPER.B_B-PTS225.AT2"
    with pytest.raises(RecordError, match="is given as both X and Y; a pair is two different") as caught:
        read_ground_motion_pair(x, x)
    assert caught.value.parameter == "pair"
    copy = tmp_path / "copy.AT2"
    copy.write_bytes(x.read_bytes())
    with pytest.raises(RecordError, match=r"copy.AT2 225 is the same motion as RSN723_SUPER.B_B-PTS225.AT2 225"):
        read_ground_motion_pair(x, copy)


def test_cli_hints_name_the_option_that_fixes_the_mistake(pairs_dir):
    """--component is X's option: a message about the second file or the vertical does not point to it."""
    from typer.testing import CliRunner

    from isolator.cli import app

    folder = pairs_dir / "superstitionhills1987_PTS"
    x, y = folder / "RSN723_SUPER.B_B-PTS225.AT2", folder / "RSN723_SUPER.B_B-PTS315.AT2"
    cases = {
        ("--component", "all"): "a pair from one file needs two horizontal components (or give the second file)",
        ("--vertical", str(y), "--trim"): "component 315 is not a vertical (Up, UD, HNZ …); give --vertical a "
                                          "file of one component, or a file with one vertical channel",
        ("--pair", str(x)): "is given as both X and Y; a pair is two different horizontal components",
    }
    for extra, message in cases.items():
        result = CliRunner().invoke(app, ["simulate", str(x), *extra, "--mu-s", "0.06", "--radius-m", "2"])
        lines = result.output.strip().splitlines()
        assert result.exit_code == 2 and len(lines) == 1, result.output
        assert lines[0].endswith(message), lines[0]


def test_a_file_of_several_channels_is_parsed_once(records_dir, monkeypatch):
    """read_ground_motions: every channel from one parse, each equal to its own read_ground_motion."""
    import isolator.motion.read as read

    v2 = records_dir / "other" / "ce89486SampleInput.v2"
    calls = []
    original = read._read_stream
    monkeypatch.setattr(read, "_read_stream", lambda path, dt_s: calls.append(path) or original(path, dt_s))
    every = read_ground_motion_pair(v2, component="all")
    assert len(calls) == 1  # it was 4: the list of channels, then once per channel
    for axis, label in (("x", "180"), ("y", "90"), ("z", "Up")):
        alone = read_ground_motion(v2, component=label)
        motion = every.components[axis]
        np.testing.assert_array_equal(motion.acceleration_m_s2, alone.acceleration_m_s2)
        assert (motion.component, motion.components, motion.units_source, motion.processing) == \
            (alone.component, alone.components, alone.units_source, alone.processing)
        assert motion.provenance == alone.provenance


def test_read_header_reads_the_header_only(pairs_dir, tmp_path):
    from isolator.motion.read import read_header

    path = pairs_dir / "superstitionhills1987_PTS" / "RSN723_SUPER.B_B-PTS225.AT2"
    label, provenance = read_header(path)
    full = read_ground_motion(path)
    assert label == full.component == "225"
    assert (provenance["station"], provenance["event"]) == (full.provenance["station"], full.provenance["event"])
    # not a header: another format, binary bytes under an AT2 name, a folder
    assert read_header(pairs_dir / "lahabra2014_WLT" / "CIWLT.V2") is None
    junk = tmp_path / "junk.AT2"
    junk.write_bytes(bytes(range(256)) * 1000)
    assert read_header(junk) is None
    assert read_header(tmp_path) is None


def test_two_zero_components_are_no_ground_motion_not_one_motion_twice(tmp_path):
    x, y = tmp_path / "x.txt", tmp_path / "y.txt"
    for path in (x, y):
        path.write_text("0 0\n0.01 0\n0.02 0\n0.03 0\n")
    with pytest.raises(RecordError, match="every horizontal component is zero"):
        read_ground_motion_pair(x, y, units="g")
