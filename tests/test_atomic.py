"""Outputs: written through symbolic links, never onto non-regular files or inputs, locked per run."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from isolator.atomic import (
    OutputError,
    OutputIsInputError,
    OutputLockedError,
    atomic_path,
    lock_path,
    output_lock,
    refuse_overwriting_inputs,
    resolve_output,
    write_text_atomically,
)


def test_symlink_is_written_through_to_its_target_in_the_target_folder(tmp_path):
    (tmp_path / "real").mkdir()
    target = tmp_path / "real" / "out.csv"
    target.write_text("old")
    link = tmp_path / "link.csv"
    link.symlink_to(target)
    seen = []
    with atomic_path(link) as temporary:
        seen.append(temporary.parent)
        temporary.write_text("new")
    assert link.is_symlink() and os.readlink(link) == str(target)
    assert target.read_text() == "new"
    assert seen == [target.parent.resolve()]  # atomic rename within the target's folder
    assert sorted(p.name for p in (tmp_path / "real").iterdir()) == ["out.csv"]  # no temporary left


def test_chain_of_links_and_dangling_link_reach_the_final_target(tmp_path):
    final = tmp_path / "final.txt"
    (tmp_path / "l1").symlink_to(tmp_path / "l2")
    (tmp_path / "l2").symlink_to(final)  # dangling: final does not exist yet
    write_text_atomically(tmp_path / "l1", "abc")
    assert final.read_text() == "abc" and (tmp_path / "l1").is_symlink() and (tmp_path / "l2").is_symlink()


def test_non_regular_outputs_are_refused_and_left_alone(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    with pytest.raises(OutputError, match="FIFO"):
        write_text_atomically(fifo, "x")
    assert fifo.exists() and not fifo.is_file()
    with pytest.raises(OutputError, match="folder"):
        write_text_atomically(tmp_path, "x")
    # a device is refused before anything is written (resolve only: never risk replacing /dev/null)
    with pytest.raises(OutputError, match="character device") as info:
        resolve_output("/dev/null")
    assert str(info.value).startswith("/dev/null: ")
    assert resolve_output("/dev/null", allow_stream=True)[1] is True


def test_stream_is_written_in_place_when_allowed(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    reader = subprocess.Popen([sys.executable, "-c", f"print(open({str(fifo)!r}).read(), end='')"],
                              stdout=subprocess.PIPE, text=True)
    with atomic_path(fifo, allow_stream=True) as path:
        assert path == fifo
        path.write_text("streamed\n")
    assert reader.communicate(timeout=20)[0] == "streamed\n"


def test_symlink_loop_is_named_as_such(tmp_path):
    (tmp_path / "a").symlink_to(tmp_path / "b")
    (tmp_path / "b").symlink_to(tmp_path / "a")
    with pytest.raises(OutputError, match="symbolic-link loop"):
        write_text_atomically(tmp_path / "a", "x")


def test_write_error_names_the_path(tmp_path):
    folder = tmp_path / "ro"
    folder.mkdir()
    blocker = folder / "file"
    blocker.write_text("")
    with pytest.raises(OutputError) as info:  # a file where a folder should be: ENOTDIR for anyone, root too
        write_text_atomically(blocker / "out.csv", "x")
    assert str(info.value).startswith(f"{blocker / 'out.csv'}: cannot write")
    with pytest.raises(OutputError) as info:
        with atomic_path(tmp_path / "out.bin"):
            raise OSError(28, "No space left on device")
    assert str(info.value) == f"{tmp_path / 'out.bin'}: cannot write (No space left on device)"
    assert list(folder.iterdir()) == [blocker] and not (tmp_path / "out.bin").exists()


def test_output_resolving_to_an_input_is_refused(tmp_path):
    record = tmp_path / "in.AT2"
    record.write_text("data")
    link = tmp_path / "alias.csv"
    link.symlink_to(record)
    hard = tmp_path / "hard.csv"
    os.link(record, hard)
    for output in (record, link, hard, tmp_path / "." / "in.AT2"):
        with pytest.raises(OutputIsInputError, match="is an input"):
            refuse_overwriting_inputs([None, output], [record])
    refuse_overwriting_inputs([tmp_path / "new.csv"], [record, None])  # a different file is fine
    assert record.read_text() == "data"


def test_second_writer_is_refused_naming_the_holder(tmp_path):
    out = tmp_path / "table.csv"
    with output_lock(out) as lock:
        assert lock == lock_path(out) and lock.read_text().startswith(f"pid={os.getpid()} ")
        child = subprocess.run(
            [sys.executable, "-c", "import sys; from isolator.atomic import output_lock\n"
             "try:\n    output_lock(sys.argv[1]).__enter__()\nexcept Exception as e: print(type(e).__name__, e)",
             str(out)], capture_output=True, text=True, timeout=60,
            env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)})
        assert child.stdout.startswith(f"OutputLockedError {out}: is being written by process {os.getpid()} on ")
    assert not lock.exists()  # released


def test_stale_lock_of_a_dead_process_is_taken_over(tmp_path):
    out = tmp_path / "table.csv"
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                          text=True).stdout.strip()
    import socket

    lock_path(out).write_text(f"pid={dead} host={socket.gethostname()} since=then\n")
    with output_lock(out):
        pass
    assert not lock_path(out).exists()


def test_lock_of_a_live_process_elsewhere_is_respected(tmp_path):
    out = tmp_path / "table.csv"
    lock_path(out).write_text("pid=1 host=some-other-host since=then\n")
    with pytest.raises(OutputLockedError, match="process 1 on some-other-host"):
        with output_lock(out):
            pass
    assert lock_path(out).exists()  # not ours to remove
