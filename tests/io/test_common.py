"""isolator.io._common: the parsing helpers every text reader shares."""

from __future__ import annotations

import io

import numpy as np
import pytest

from isolator.io._common import (
    DETECT_BYTES,
    head_lines,
    iter_line_chunks,
    looks_like_text,
    numbers_from_lines,
    open_text,
    parse_float,
    read_head,
    split_numbers,
)


def test_fortran_numbers():
    assert parse_float("1.5D-03") == 1.5e-3 and parse_float("-2.0d+2") == -200.0 and parse_float(".5E1") == 5.0
    # fixed-width fields that touch are split where one number ends and the next begins
    assert split_numbers("1.5E+00-2.2E+00 3.0E-01") == ["1.5E+00", "-2.2E+00", "3.0E-01"]
    assert split_numbers("  0.1  -0.2 ") == ["0.1", "-0.2"]
    with pytest.raises(ValueError, match="'abc'"):
        split_numbers("0.1 abc 0.3")


def test_numbers_from_lines_fast_and_slow_paths_agree():
    plain = ["0.1 0.2 0.3", "-4.0E+00 5"]
    np.testing.assert_array_equal(numbers_from_lines(plain), [0.1, 0.2, 0.3, -4.0, 5.0])
    touching = ["1.0E+00-2.0E+00", "3.0D+00"]
    np.testing.assert_array_equal(numbers_from_lines(touching), [1.0, -2.0, 3.0])
    with pytest.raises(ValueError, match="'x1' on data line 2"):
        numbers_from_lines(["1 2", "3 x1"])


def test_text_detection_and_head_lines():
    assert looks_like_text(b"0.1 0.2\n0.3\n") and not looks_like_text(b"") and not looks_like_text(b"a\x00b")
    assert not looks_like_text(bytes(range(1, 30)) * 10)  # control characters
    assert head_lines(b"a\r\nb\rc\n\n d \n") == ["a", "b", "c", " d "]
    # a head cut at the byte limit drops its last, possibly partial line
    cut = (b"1.0 2.0\n" * DETECT_BYTES)[:DETECT_BYTES - 3] + b"1.2"
    assert len(cut) == DETECT_BYTES and head_lines(cut)[-1] == "1.0 2.0"


def test_read_head_leaves_a_buffer_where_it_was(tmp_path):
    buffer = io.BytesIO(b"header\n1 2 3\n")
    buffer.seek(3)
    assert read_head(buffer, 4) == b"der\n" and buffer.tell() == 3
    assert read_head(io.StringIO("é1"), 8) == "é1".encode("latin-1")
    assert read_head(tmp_path / "absent.txt") == b""
    path = tmp_path / "f.txt"
    path.write_bytes(b"x" * 100)
    assert read_head(path, 10) == b"x" * 10


def test_open_text_and_chunks(tmp_path):
    path = tmp_path / "crlf.txt"
    path.write_bytes(b"1\r\n2\r\n3\r\n4\r\n5\r\n")
    with open_text(path) as stream:
        chunks = list(iter_line_chunks(stream, chunk_lines=2))
    assert chunks == [["1", "2"], ["3", "4"], ["5"]]
    assert list(iter_line_chunks(open_text(io.BytesIO(b"a\nb")), chunk_lines=10)) == [["a", "b"]]
