"""Outputs under hostile conditions (issue 26): a kill during a write, a disk that fills between two
files of one output set, a read-only folder.

A full disk is a real one where the tests may mount a small tmpfs (root on Linux); elsewhere those
tests skip with the reason.
"""

from __future__ import annotations

import errno
import os
import signal
import subprocess
import sys
import textwrap
import uuid
from pathlib import Path

import pytest

from isolator import atomic
from isolator.atomic import OutputError, atomic_path, atomic_paths, remove_stale_temporaries, write_text_atomically


@pytest.fixture
def small_disk(tmp_path):
    """A 256 KiB tmpfs mounted under tmp_path (skips where mounting is not allowed)."""
    mount = tmp_path / "disk"
    mount.mkdir()
    if sys.platform != "linux" or os.geteuid() != 0:
        pytest.skip("mounting a small tmpfs needs root on Linux")
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "tmpfs", str(mount)], capture_output=True)
    if done.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here: {done.stderr.decode(errors='replace').strip()}")
    try:
        yield mount
    finally:
        subprocess.run(["umount", "-l", str(mount)], check=False)


def _kill_during_write(target: Path) -> None:
    """A child process that dies by SIGKILL inside atomic_path, with half of ``target`` written."""
    code = textwrap.dedent(f"""
        import os, signal
        from isolator.atomic import atomic_path
        with atomic_path({str(target)!r}) as temporary:
            temporary.write_bytes(b"%PDF-1.4 half a file")
            os.kill(os.getpid(), signal.SIGKILL)
    """)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True)
    assert done.returncode == -signal.SIGKILL, done.stderr


def test_a_kill_during_a_write_leaves_a_temporary_that_the_next_run_removes(tmp_path):
    target = tmp_path / "review.pdf"
    _kill_during_write(target)
    left = [p.name for p in tmp_path.iterdir()]
    assert len(left) == 1 and left[0].startswith(".review.pdf.~") and left[0].endswith(".pdf")  # the kill's trace
    atomic._CLEANED_FOLDERS.discard(os.path.realpath(tmp_path))  # a new run: a new process
    write_text_atomically(target, "complete")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["review.pdf"]
    assert target.read_text() == "complete"


def test_temporaries_of_live_writers_and_other_files_are_left_alone(tmp_path):
    host = atomic._host_tag()
    live = tmp_path / f".r.pdf.~{host}-{os.getpid()}.abcdefgh.pdf"  # this process: alive
    other_host = tmp_path / ".r.pdf.~elsewhere-1.abcdefgh.pdf"  # cannot be asked: left
    user_file = tmp_path / ".notes.abcdefgh"  # a hidden file that merely looks like a name
    fresh_legacy = tmp_path / ".r.pdf.abcdefgh.pdf"  # an old-form temporary, fresh: maybe a live writer
    old_legacy = tmp_path / ".r.json.k2j4h5g6.json"
    for path in (live, other_host, user_file, fresh_legacy, old_legacy):
        path.write_text("x")
    os.utime(old_legacy, (1e9, 1e9))
    os.utime(user_file, (1e9, 1e9))
    assert remove_stale_temporaries(tmp_path) == [old_legacy]
    assert remove_stale_temporaries(tmp_path) == []  # one scan per folder and process
    assert live.exists() and other_host.exists() and user_file.exists() and fresh_legacy.exists()


def test_an_output_set_is_written_completely_or_not_at_all_on_a_full_disk(small_disk):
    pdf, json_path = small_disk / "r.pdf", small_disk / "r.json"
    pdf.write_bytes(b"old pdf")
    json_path.write_text('{"run": "old"}')
    with pytest.raises(OutputError) as info:
        with atomic_paths([pdf, json_path]) as (tmp_pdf, tmp_json):
            tmp_pdf.write_bytes(b"new pdf " * 1000)
            with open(tmp_json, "wb") as stream:
                stream.write(os.urandom(1 << 20))  # does not fit: ENOSPC
    assert info.value.errno == errno.ENOSPC
    assert str(info.value).startswith(f"{json_path}: cannot write (No space left on device)")
    assert "\n" not in str(info.value)
    assert (pdf.read_bytes(), json_path.read_text()) == (b"old pdf", '{"run": "old"}')  # the old set, whole
    assert sorted(p.name for p in small_disk.iterdir()) == ["r.json", "r.pdf"]  # no temporary left
    with atomic_paths([pdf, json_path]) as (tmp_pdf, tmp_json):  # room enough: both land
        tmp_pdf.write_bytes(b"new pdf")
        tmp_json.write_text('{"run": "new"}')
    assert (pdf.read_bytes(), json_path.read_text()) == (b"new pdf", '{"run": "new"}')


def test_an_error_in_the_set_leaves_every_older_file(tmp_path, monkeypatch):
    pdf, json_path = tmp_path / "r.pdf", tmp_path / "r.json"
    pdf.write_bytes(b"old")
    json_path.write_text("old")

    def no_space(fd):  # the disk fills while the JSON is flushed, after the PDF was
        if os.readlink(f"/proc/self/fd/{fd}").endswith(".json"):
            raise OSError(errno.ENOSPC, "No space left on device")
    monkeypatch.setattr(atomic.os, "fsync", no_space)
    with pytest.raises(OutputError, match=r"r\.json: cannot write \(No space left on device\); no file of its set"):
        with atomic_paths([pdf, json_path]) as (tmp_pdf, tmp_json):
            tmp_pdf.write_bytes(b"new")
            tmp_json.write_text("new")
    assert (pdf.read_bytes(), json_path.read_text()) == (b"old", "old")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.json", "r.pdf"]


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_a_read_only_folder_is_one_line_naming_the_output(tmp_path):
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o555)
    try:
        with pytest.raises(OutputError, match=r"^.*ro/x\.pdf: cannot write \(Permission denied\)$"):
            with atomic_path(folder / "x.pdf") as temporary:
                temporary.write_bytes(b"x")
    finally:
        folder.chmod(0o755)


def test_a_read_only_mount_is_one_line_naming_the_output(small_disk):
    subprocess.run(["mount", "-o", "remount,ro", str(small_disk)], check=True)
    target = small_disk / f"{uuid.uuid4().hex}.pdf"
    with pytest.raises(OutputError) as info:
        with atomic_paths([target, target.with_suffix(".json")]) as temporaries:
            for temporary in temporaries:
                temporary.write_text("x")
    assert str(info.value) == f"{target}: cannot write (Read-only file system); no file of its set was written"
