"""Suites: SUITE.toml, grouping of files into pairs, duplicates, mismatched lengths, a bad record."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from isolator.errors import SuiteError
from isolator.review.suite import load_suite

EXAMPLE = Path(__file__).resolve().parents[2] / "isolator" / "data" / "suites" / "example"
YER = ("landers1992_YER", "RSN900_LANDERS_YER270.AT2", "RSN900_LANDERS_YER360.AT2")
ABY = ("hectormine1999_ABY", "RSN1762_HECTOR_ABY090.AT2", "RSN1762_HECTOR_ABY360.AT2")
PTS = ("superstitionhills1987_PTS", "RSN723_SUPER.B_B-PTS225.AT2", "RSN723_SUPER.B_B-PTS315.AT2")


def _copy(tmp_path, *pairs):
    for folder, *files in pairs:
        (tmp_path / folder).mkdir(exist_ok=True)
        for name in files:
            shutil.copy(EXAMPLE / folder / name, tmp_path / folder / name)


def _toml(tmp_path, body: str) -> Path:
    path = tmp_path / "suite.toml"
    path.write_text(body)
    return path


def _pair(name, folder, x, y, extra=""):
    return f'[[pair]]\nname = "{name}"\nx = "{folder}/{x}"\ny = "{folder}/{y}"\n{extra}\n'


def test_bundled_suite_reads_eight_pairs_with_the_trims_recorded():
    suite = load_suite(EXAMPLE / "suite.toml")
    assert len(suite.pairs) == 8 and not suite.failed
    pts = next(p for p in suite.pairs if "PTS" in p.name)
    assert pts.npts == 2231 and any("trim" in step["step"] for step in pts.processing)
    apeel = next(p for p in suite.pairs if "APEEL2" in p.name)
    assert apeel.az_m_s2 is not None and apeel.npts == 7165
    duzce = next(p for p in suite.pairs if "DZC" in p.name)
    assert duzce.high_pass_hz == pytest.approx(0.08)  # the larger of the two header corners
    # PGA of the README's table, in g
    assert max(abs(duzce.ax_m_s2).max(), abs(duzce.ay_m_s2).max()) / 9.80665 == pytest.approx(0.5150, abs=1e-4)


def test_files_and_folders_are_grouped_by_station(tmp_path):
    _copy(tmp_path, YER, ABY)
    suite = load_suite([str(tmp_path)])
    assert sorted(suite.names) == ["Amboy", "Yermo Fire Station"] and not suite.failed


def test_duplicates_are_refused_naming_both_files(tmp_path):
    _copy(tmp_path, YER, ABY)
    shutil.copy(tmp_path / YER[0] / YER[1], tmp_path / ABY[0] / "copy_of_yer.AT2")
    path = _toml(tmp_path, _pair("Y", *YER) + _pair("A", ABY[0], ABY[1], "copy_of_yer.AT2"))
    with pytest.raises(SuiteError) as info:
        load_suite(path)
    message = str(info.value)
    assert "same samples" in message and YER[1] in message and "copy_of_yer.AT2" in message and "\n" not in message


def test_different_lengths_need_trim(tmp_path):
    _copy(tmp_path, PTS)
    with pytest.raises(SuiteError, match="pair 'P': components differ in length .*2235.*2231"):
        load_suite(_toml(tmp_path, _pair("P", *PTS)))
    suite = load_suite(_toml(tmp_path, _pair("P", *PTS, "trim = true")))
    assert suite.pairs[0].npts == 2231
    assert suite.pairs[0].processing[0]["samples"] == {"x": 2235, "y": 2231}


def test_a_bad_record_fails_its_pair_only(tmp_path):
    _copy(tmp_path, YER, ABY)
    bad = tmp_path / ABY[0] / ABY[2]
    bad.write_text(bad.read_text()[:3000])  # truncated: fewer values than NPTS
    suite = load_suite(_toml(tmp_path, _pair("Y", *YER) + _pair("A", *ABY)))
    assert suite.names == ["Y"]
    assert suite.failed[0]["name"] == "A" and ABY[2] in suite.failed[0]["error"]


def test_suite_toml_mistakes_are_one_line(tmp_path):
    with pytest.raises(SuiteError, match="no \\[\\[pair\\]\\] tables"):
        load_suite(_toml(tmp_path, 'units = "g"\n'))
    with pytest.raises(SuiteError, match="missing key 'y'"):
        load_suite(_toml(tmp_path, '[[pair]]\nx = "a.AT2"\n'))
    with pytest.raises(SuiteError, match="unknown key 'z_file'"):
        load_suite(_toml(tmp_path, '[[pair]]\nx = "a"\ny = "b"\nz_file = "c"\n'))
    with pytest.raises(SuiteError, match="no pair could be read"):
        load_suite(_toml(tmp_path, '[[pair]]\nx = "a.AT2"\ny = "b.AT2"\n'))
    assert np.isfinite(1.0)
