"""Input paths: one path names exactly one file; non-regular files are named without being opened."""

from __future__ import annotations

import os
import time

import numpy as np
import obspy
import pytest

from isolator.io._common import input_file_problem, literal_pattern


def _text_record(path, n):
    np.savetxt(path, np.column_stack([np.arange(n) * 0.01, np.sin(np.arange(n) * 0.1)]), delimiter=",")


def test_glob_characters_name_exactly_one_file(tmp_path):
    _text_record(tmp_path / "x1.csv", 300)  # what obspy's glob would pick for x[1].csv
    _text_record(tmp_path / "x[1].csv", 200)
    assert len(obspy.read(str(tmp_path / "x[1].csv"), format="ISOLATOR_TEXT")[0]) == 300  # the hazard
    assert len(obspy.read(literal_pattern(tmp_path / "x[1].csv"), format="ISOLATOR_TEXT")[0]) == 200
    for name in ("a*b.csv", "what?.csv"):
        _text_record(tmp_path / name, 50)
        assert len(obspy.read(literal_pattern(tmp_path / name), format="ISOLATOR_TEXT")[0]) == 50


def test_problems_are_found_from_metadata_alone(tmp_path):
    fifo = tmp_path / "pipe.AT2"
    os.mkfifo(fifo)
    (tmp_path / "loop1").symlink_to(tmp_path / "loop2")
    (tmp_path / "loop2").symlink_to(tmp_path / "loop1")
    (tmp_path / "dangling").symlink_to(tmp_path / "gone")
    (tmp_path / "empty").write_bytes(b"")
    (tmp_path / "ok").write_text("1\n")
    start = time.perf_counter()
    assert input_file_problem(fifo) == "is a FIFO (named pipe), not a regular file"
    assert input_file_problem(tmp_path / "loop1") == "symbolic-link loop"
    assert input_file_problem(tmp_path / "dangling") == f"dangling symbolic link (to {tmp_path / 'gone'})"
    assert input_file_problem(tmp_path / "absent") == "no such file"
    assert input_file_problem(tmp_path) == "is a folder, not a file"
    assert input_file_problem(tmp_path / "empty") == "file is empty"
    assert input_file_problem("/dev/null") == "is a character device, not a regular file"
    assert input_file_problem(tmp_path / "ok") is None
    assert time.perf_counter() - start < 1.0


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads any file")
def test_unreadable_file(tmp_path):
    path = tmp_path / "secret"
    path.write_text("1\n")
    path.chmod(0)
    assert input_file_problem(path) == "cannot be read (Permission denied)"
