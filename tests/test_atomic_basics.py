"""isolator.atomic, the basic promise: an output is complete or absent, and replaced in one step.

(The hardening branch adds tests/test_atomic.py for links, non-regular files, inputs and locks.)
"""

from __future__ import annotations

import os
import stat

import pytest

from isolator.atomic import atomic_path, write_text_atomically


def _leftovers(folder):
    """Hidden temporary files the writer may have left beside its target."""
    return sorted(p.name for p in folder.iterdir() if p.name.startswith("."))


def test_complete_write_lands_on_the_target(tmp_path):
    target = tmp_path / "out" / "table.csv"  # the folder does not exist yet
    with atomic_path(target) as temporary:
        assert temporary.parent == target.parent and temporary.suffix == ".csv"
        assert temporary.name.startswith(".") and temporary != target
        temporary.write_bytes(b"a,b\n1,2\n")
        assert not target.exists()  # nothing visible before the block ends
    assert target.read_bytes() == b"a,b\n1,2\n"
    assert _leftovers(target.parent) == []


def test_failure_leaves_no_file_and_no_temporary(tmp_path):
    target = tmp_path / "report.pdf"
    with pytest.raises(RuntimeError, match="renderer failed"):
        with atomic_path(target) as temporary:
            temporary.write_bytes(b"%PDF-1.4 half a page")
            raise RuntimeError("renderer failed")
    assert not target.exists()
    assert _leftovers(tmp_path) == []


def test_failure_keeps_the_previous_version_intact(tmp_path):
    target = tmp_path / "results.json"
    target.write_text('{"version": 1}\n')
    with pytest.raises(KeyboardInterrupt):
        with atomic_path(target) as temporary:
            temporary.write_text('{"vers')
            raise KeyboardInterrupt  # Ctrl-C in the middle of a write
    assert target.read_text() == '{"version": 1}\n'
    assert _leftovers(tmp_path) == []


def test_replacement_is_one_rename(tmp_path):
    """A reader holding the old file keeps reading it whole; the new content arrives as a new inode."""
    target = tmp_path / "map.npz"
    target.write_bytes(b"old" * 1000)
    old_inode = target.stat().st_ino
    with open(target, "rb") as reader:
        with atomic_path(target) as temporary:
            temporary.write_bytes(b"new" * 2000)
            assert target.read_bytes() == b"old" * 1000  # still the old file during the write
        assert reader.read() == b"old" * 1000  # the open handle is not truncated
    assert target.read_bytes() == b"new" * 2000
    assert target.stat().st_ino != old_inode  # replaced by rename, not rewritten in place


def test_permissions_follow_the_umask_not_mkstemp(tmp_path):
    previous = os.umask(0o027)
    try:
        target = tmp_path / "chart.png"
        with atomic_path(target) as temporary:
            temporary.write_bytes(b"\x89PNG")
    finally:
        os.umask(previous)
    assert stat.S_IMODE(target.stat().st_mode) == 0o666 & ~0o027  # 0640, not mkstemp's 0600


def test_write_text_atomically_is_utf8(tmp_path):
    target = tmp_path / "note.txt"
    write_text_atomically(target, "µs = 0.06, α = 5, ζ = 0.69\n")
    assert target.read_bytes() == "µs = 0.06, α = 5, ζ = 0.69\n".encode()
    write_text_atomically(target, "second\n")
    assert target.read_text(encoding="utf-8") == "second\n"
    assert _leftovers(tmp_path) == []
