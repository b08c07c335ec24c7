"""Atomic file output: a file is either complete or absent, never half written.

Every output of isolator (CSV, JSON, PDF, PNG, Parquet, cached maps, batch parts) is
written to a temporary file beside its target and renamed onto it once complete;
a failure (or Ctrl-C) removes the temporary file and leaves any older target intact.

The rules an output obeys (``docs/security.md``):

- an output that is a symbolic link is written *through* the link: the temporary file
  is made in the folder of the link's final target and renamed onto that target, so
  the link survives and points at the new content;
- an output that exists and is not a regular file (a folder, a device such as
  ``/dev/full``, a FIFO, a socket) is refused, unless the caller allows streaming and
  the target is a character device or a FIFO (``/dev/stdout``): then it is written in
  place, not atomically, because that is what the user asked for;
- an output that resolves to one of the command's inputs is refused
  (:func:`refuse_overwriting_inputs`);
- two runs that write the same output: the second is refused while the first holds
  ``<output>.lock`` (:func:`output_lock`);
- a set of outputs that belong together (a PDF and its JSON) is written completely or not at all
  (:func:`atomic_paths`): every file is written and flushed before the first rename;
- a temporary file left by a run that was killed (its name carries the writer's host and pid) is
  removed by the next run that writes into the same folder (:func:`remove_stale_temporaries`);
- every failure to write raises :class:`OutputError`, whose message names the path.
"""

from __future__ import annotations

import errno
import hashlib
import hmac
import os
import re
import socket
import stat
import tempfile
import time
from contextlib import contextmanager
from pathlib import Path

#: A temporary file unclaimed for this long is stale even without the writer's pid in its name
#: (names written before the pid was added: ``.NAME.XXXXXXXX.SUFFIX``) [s].
LEGACY_TEMPORARY_AGE_S = 3600.0
#: ``.NAME.~HOST-PID.XXXXXXXX.SUFFIX``: the temporary file of ``NAME`` written by process PID on HOST.
_TEMPORARY = re.compile(r"^\.(?P<name>.+)\.~(?P<host>[A-Za-z0-9-]{0,32})-(?P<pid>\d+)\.[A-Za-z0-9_]{8}(?P<suffix>.*)$")
_LEGACY_TEMPORARY = re.compile(r"^\.(?P<name>.+)\.[a-z0-9_]{8}(?P<suffix>\.[A-Za-z0-9]+)$")
#: The extensions isolator writes: an old temporary is recognised only with one of them.
_OUTPUT_SUFFIXES = {".pdf", ".json", ".csv", ".png", ".svg", ".parquet", ".npz", ".jsonl", ".md", ".txt", ".key"}
_CLEANED_FOLDERS: set[str] = set()


def _host_tag() -> str:
    return re.sub(r"[^A-Za-z0-9-]", "-", socket.gethostname())[:32]


class OutputError(OSError):
    """An output that cannot or must not be written; ``str(err)`` is one line naming the path.

    A subclass of :class:`OSError` (``err.filename`` is the output, ``err.strerror`` the
    reason) so that callers which catch write errors catch it too.
    """

    def __init__(self, path, reason: str, code: int = errno.EIO):
        super().__init__(code, reason, str(path))

    def __str__(self) -> str:
        return f"{self.filename}: {self.strerror}"


class OutputIsInputError(OutputError):
    """An output that resolves to one of the command's inputs."""


class OutputLockedError(OutputError):
    """An output that another run is writing (its lock file exists and its holder lives)."""


_KINDS = ((stat.S_ISDIR, "a folder"), (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
          (stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISSOCK, "a socket"))


def file_kind(mode: int) -> str:
    """Words for what a non-regular file is ("a folder", "a FIFO (named pipe)", …)."""
    return next((words for test, words in _KINDS if test(mode)), "not a regular file")


def _reason(err: OSError) -> str:
    return err.strerror or " ".join(str(err).split()) or type(err).__name__


def resolve_output(path, *, allow_stream: bool = False) -> tuple[Path, bool]:
    """The file an output really writes, and whether it is streamed in place.

    Parameters
    ----------
    path : str or path-like
        The output as the user gave it.
    allow_stream : bool
        Accept an existing character device or FIFO (``/dev/stdout``) as a stream.

    Returns
    -------
    (Path, bool)
        The final target (symbolic links followed, the folder made absolute) and True when
        that target is a stream to write in place.

    Raises
    ------
    OutputError
        A symbolic-link loop, or an existing target that is not a regular file.
    """
    given = Path(path)
    try:
        mode = os.stat(given).st_mode  # follows links, /proc/self/fd magic links included
    except FileNotFoundError:
        return Path(os.path.realpath(given)), False  # a new file, or a dangling link: its would-be target
    except OSError as err:
        if err.errno == errno.ELOOP:
            raise OutputError(given, "symbolic-link loop", errno.ELOOP) from None
        raise OutputError(given, f"cannot write ({_reason(err)})", err.errno or errno.EIO) from None
    if stat.S_ISREG(mode):
        return Path(os.path.realpath(given)), False
    if allow_stream and (stat.S_ISCHR(mode) or stat.S_ISFIFO(mode)):
        return given, True  # written in place through the name given (/dev/stdout → a pipe)
    raise OutputError(given, f"is {file_kind(mode)}, not a regular file; outputs are written only to "
                             "regular files", errno.EINVAL)


@contextmanager
def atomic_path(path, *, allow_stream: bool = False):
    """Yield a temporary path beside the output's target; rename it onto the target on success.

    The temporary name keeps the target's extension (``.pdf``, ``.png``, ``.parquet``…)
    so that writers that infer the format from it work unchanged, and starts with a
    dot so that it stays out of listings.  The file gets ordinary permissions (mkstemp
    makes 0600) and is flushed to disk before the rename.  A symbolic link is written
    through (the temporary file lives in the folder of its final target).

    Parameters
    ----------
    path : str or path-like
        The file to write; its folder is created if needed.
    allow_stream : bool
        If the target is a character device or FIFO (``/dev/stdout``), yield it as is
        and let the caller write in place (not atomic: what the user asked for).

    Raises
    ------
    OutputError
        Any failure to write (the message names ``path``), or a target that is not a
        regular file.
    """
    target, stream = resolve_output(path, allow_stream=allow_stream)
    if stream:
        try:
            yield target
        except OSError as err:
            if isinstance(err, OutputError):
                raise
            raise OutputError(path, f"cannot write ({_reason(err)})", err.errno or errno.EIO) from None
        return
    temporary = None
    try:
        temporary = _temporary_beside(target)
        yield Path(temporary)
        _flush(temporary)
        os.replace(temporary, target)
    except OutputError:
        raise
    except Exception as raised:
        err = write_failure(raised)
        if err is None:
            raise
        raise OutputError(path, f"cannot write ({_reason(err)})", err.errno or errno.EIO) from None
    finally:
        if temporary is not None and os.path.lexists(temporary):
            os.unlink(temporary)


def write_failure(raised: BaseException) -> OSError | None:
    """The OSError behind an exception raised while writing, or None when it is not a write failure.

    A writer can hide the disk's error behind its own: after ENOSPC, matplotlib's PDF writer
    closes its page stream and raises ``zlib.error`` from that close, with the OSError as its
    context.  That is still a full disk, and is reported as one (one line naming the output),
    not as a 100-line traceback.  The chain is followed a bounded number of links.
    """
    seen = raised
    for _ in range(8):
        if seen is None:
            return None
        if isinstance(seen, OSError):
            return seen
        seen = seen.__cause__ or seen.__context__
    return None


def _temporary_beside(target: Path) -> str:
    """A new empty temporary file beside ``target``, named after it, this host and this process."""
    target.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(target.parent)
    handle, temporary = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.~{_host_tag()}-{os.getpid()}.",
                                         suffix=target.suffix)
    os.close(handle)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(temporary, 0o666 & ~umask)
    return temporary


def _flush(temporary) -> None:
    with open(temporary, "rb+") as stream_handle:
        os.fsync(stream_handle.fileno())


def _stale(entry: os.DirEntry, now: float, host: str) -> bool:
    match = _TEMPORARY.match(entry.name)
    if match is not None:
        suffix = Path(match["name"]).suffix
        if match["suffix"] != suffix:
            return False
        # a writer on another host cannot be asked whether it lives: its temporary is left alone
        return match["host"] == host and not _alive(int(match["pid"]))
    match = _LEGACY_TEMPORARY.match(entry.name)
    if match is None or match["suffix"] != Path(match["name"]).suffix or match["suffix"] not in _OUTPUT_SUFFIXES:
        return False
    try:
        return now - entry.stat(follow_symlinks=False).st_mtime > LEGACY_TEMPORARY_AGE_S
    except OSError:
        return False


def remove_stale_temporaries(folder) -> list[Path]:
    """Remove the temporary files that killed runs left in ``folder``; return them.

    A temporary file is named ``.NAME.~HOST-PID.XXXXXXXX.SUFFIX`` (:func:`atomic_path`); it is stale
    when PID is not a live process on this host (the run that wrote it was killed before it could
    rename or remove it).  A name of the older form without host and pid is stale once it is
    older than :data:`LEGACY_TEMPORARY_AGE_S`.  Each folder is scanned once per process (an output
    folder holds at most a few temporary files, a batch's ``.parts`` folder thousands of parts).

    Parameters
    ----------
    folder : str or path-like
        The folder to clean.

    Returns
    -------
    list of Path
        The files removed (empty when the folder was already cleaned by this process).
    """
    key = os.path.realpath(folder)
    if key in _CLEANED_FOLDERS:
        return []
    _CLEANED_FOLDERS.add(key)
    removed = []
    now, host = time.time(), _host_tag()
    try:
        with os.scandir(key) as entries:
            for entry in entries:
                if entry.name.startswith(".") and entry.is_file(follow_symlinks=False) and _stale(entry, now, host):
                    try:
                        os.unlink(entry.path)
                        removed.append(Path(entry.path))
                    except OSError:
                        pass  # read-only folder, or another run removed it first: nothing to do
    except OSError:
        pass
    return removed


@contextmanager
def atomic_paths(paths, *, remove=()):
    """Yield temporary paths for a set of outputs; rename them all onto their targets on success.

    A set of files that belong together (a review's PDF and JSON, a report's PDF and JSON, everything
    ``isolator design`` writes) is written completely or not at all: every file is written and flushed
    to disk before the first rename, so a full disk, a write error or an exception in any of them
    leaves every older target as it was and removes every temporary file.  A Ctrl-C or SIGTERM that
    arrives during the renames waits until they are done (:func:`interrupts_deferred`), so an
    interrupt leaves the old set or the new one.  (Only a crash between two renames, a SIGKILL or a
    power cut, can still mix two runs, which the lock of :func:`output_lock` prevents from going
    unnoticed.)

    Parameters
    ----------
    paths : sequence of str or path-like
        The outputs of the set; streams are not allowed.
    remove : sequence of str or path-like
        Files of an older set that the new set does not have (a design search's recommended review when
        no candidate passes any more): removed with the renames, and only if they land.

    Yields
    ------
    list of Path
        One temporary file per output, in the order given, each with the output's extension.

    Raises
    ------
    OutputError
        Any failure to write (the message names the output that failed).
    """
    paths = [Path(path) for path in paths]
    targets = [resolve_output(path)[0] for path in paths]
    temporaries: list[str] = []
    current = paths[0] if paths else None
    try:
        for path, target in zip(paths, targets, strict=True):
            current = path
            temporaries.append(_temporary_beside(target))
        yield [Path(temporary) for temporary in temporaries]
        for path, temporary in zip(paths, temporaries, strict=True):
            current = path
            _flush(temporary)
        with interrupts_deferred():
            for path, temporary, target in zip(paths, temporaries, targets, strict=True):
                current = path
                os.replace(temporary, target)
            for stale in remove:
                current = Path(stale)
                if os.path.isfile(stale):
                    os.unlink(stale)
    except OutputError:
        raise
    except Exception as raised:
        err = write_failure(raised)
        if err is None:
            raise
        # an error inside the caller's block names the temporary it failed on: blame its output; a write to an
        # open stream names none: blame the temporary written last (the one being written when it failed)
        failed = next((path for path, temporary in zip(paths, temporaries, strict=False)
                       if err.filename is not None and os.fspath(err.filename) == temporary), None)
        if failed is None:
            failed = _written_last(paths, temporaries) or current
        raise OutputError(failed, f"cannot write ({_reason(err)}); no file of its set was written",
                          err.errno or errno.EIO) from None
    finally:
        for temporary in temporaries:
            if os.path.lexists(temporary):
                os.unlink(temporary)


@contextmanager
def interrupts_deferred():
    """Hold SIGINT and SIGTERM until the block ends, then act on the first that came.

    A few renames must not be cut in two by Ctrl-C.  The handlers are swapped only in the main thread (the
    only one where Python runs them); elsewhere the block runs as it is.  A signal that arrived is passed
    to the handler that was in place (Ctrl-C's KeyboardInterrupt, the commands' SIGTERM one) once the block
    has finished.
    """
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    wanted = [s for s in (signal.SIGINT, signal.SIGTERM) if callable(signal.getsignal(s))]
    caught: list = []
    saved = {s: signal.signal(s, lambda number, frame: caught.append((number, frame))) for s in wanted}
    try:
        yield
    finally:
        for number, handler in saved.items():
            signal.signal(number, handler)
        if caught:
            number, frame = caught[0]
            saved[number](number, frame)


def dump_json(data, path) -> None:
    """Write ``data`` to ``path`` as strict JSON (no NaN; two-space indent, a final newline).

    Meant for a temporary of :func:`atomic_path` or :func:`atomic_paths`: the JSON of an
    output set is written beside its PDF and both land together.
    """
    import json

    with open(path, "w", encoding="utf-8") as stream:
        json.dump(data, stream, indent=2, allow_nan=False)
        stream.write("\n")


def _written_last(paths, temporaries) -> Path | None:
    """The output whose temporary was modified last (ties: the later in the set), or None."""
    stamps = []
    for index, (path, temporary) in enumerate(zip(paths, temporaries, strict=False)):
        try:
            stamps.append((os.stat(temporary).st_mtime_ns, index, path))
        except OSError:
            continue
    return max(stamps)[2] if stamps else None


def write_text_atomically(path, text: str) -> None:
    """Write ``text`` (UTF-8) to ``path`` atomically (see :func:`atomic_path`)."""
    with atomic_path(path) as temporary:
        temporary.write_text(text, encoding="utf-8")


def _same_file(a: Path, b: Path) -> bool:
    try:
        return os.path.samefile(a, b)
    except OSError:  # one of them does not exist (yet): compare where they resolve to
        return os.path.realpath(a) == os.path.realpath(b)


def refuse_overwriting_inputs(outputs, inputs) -> None:
    """Refuse any output that is (resolves to, or is a hard link of) one of the inputs.

    Every command calls this with all it writes and all it reads before it writes
    anything.

    Parameters
    ----------
    outputs : iterable of str or path-like or None
        The files the command will write (None entries are ignored).
    inputs : iterable of str or path-like or None
        The files the command reads (None entries and non-paths such as
        ``example:knet`` that do not exist are compared by resolved name only).

    Raises
    ------
    OutputIsInputError
        Naming the output and the input it would overwrite.
    """
    inputs = [Path(item) for item in inputs if item is not None]
    for output in outputs:
        if output is None:
            continue
        out = Path(output)
        for source in inputs:
            if _same_file(out, source):
                detail = "" if str(out) == str(source) else f" ({source})"
                raise OutputIsInputError(out, f"is an input of this command{detail}; refusing to overwrite "
                                              "it: choose another output", errno.EEXIST)


def _holder(lock: Path) -> tuple[int | None, str, str]:
    try:
        text = lock.read_text(encoding="utf-8", errors="replace")
    except OSError:
        return None, "", ""
    fields = dict(part.split("=", 1) for part in text.split() if "=" in part)
    try:
        pid = int(fields.get("pid", ""))
    except ValueError:
        pid = None
    return pid, fields.get("host", ""), fields.get("since", "")


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def lock_path(path) -> Path:
    """The lock file of an output: ``<final target>.lock`` beside it."""
    target, _ = resolve_output(path, allow_stream=True)
    return target.with_name(target.name + ".lock")


@contextmanager
def output_lock(path):
    """Hold an exclusive lock on an output for the duration of a run.

    The lock is a file ``<output>.lock`` created with ``O_CREAT | O_EXCL`` holding
    ``pid=… host=… since=…``.  A lock whose holder is a dead process on this host is
    stale and taken over; a lock held by a live process (or by another host) refuses
    the run.

    Raises
    ------
    OutputLockedError
        One line naming the holder and the lock file.
    OutputError
        The lock cannot be created (read-only folder …).
    """
    lock = lock_path(path)
    host = socket.gethostname()
    content = f"pid={os.getpid()} host={host} since={time.strftime('%Y-%m-%dT%H:%M:%S%z')}\n"
    held = hold_interrupts()  # created and written whole, or not at all: a SIGTERM there left an empty lock
    ours = None
    try:
        ours = _create_lock(path, lock, host, content)
        held = release_interrupts(held)  # a SIGTERM held meanwhile is raised here, inside the clean-up's reach
        yield lock
    finally:
        release_interrupts(held)
        try:
            now = os.stat(lock)
            if ours is not None and (now.st_dev, now.st_ino) == ours:
                os.unlink(lock)
        except OSError:
            pass


def hold_interrupts():
    """Hold SIGINT and SIGTERM back until :func:`release_interrupts`: what to restore (None: not held).

    A report killed by SIGTERM just after creating its lock, before writing its holder into it, left
    ``r.pdf.lock`` behind: the clean-up read an empty lock as someone else's (CI, 2026-11-29).  Meanwhile the two
    signals are only remembered by a handler of their own — Python runs every handler in the main thread, whichever
    thread the system gave the signal to (a signal mask would hold it back in one thread only).  Outside the main
    thread (where handlers cannot be set) nothing is held.
    """
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        return None
    pending: list[int] = []

    def remember(signum, frame):
        pending.append(signum)

    return {number: signal.signal(number, remember) for number in (signal.SIGINT, signal.SIGTERM)}, pending


def release_interrupts(held):
    """Restore the handlers :func:`hold_interrupts` replaced, then raise a signal it held to them; None always."""
    if held is not None:
        import signal

        previous, pending = held
        for number, handler in previous.items():
            signal.signal(number, signal.SIG_DFL if handler is None else handler)
        if pending:
            number = pending[0]
            pending.clear()  # raised once, even if this is called again from a clean-up
            signal.raise_signal(number)
    return None


def _create_lock(path, lock: Path, host: str, content: str) -> tuple[int, int]:
    """Create ``lock`` exclusively with ``content``; its (device, inode), by which the clean-up knows it."""
    for _ in range(3):  # bounded: one take-over of a stale lock, then a retry if another run raced us
        try:
            lock.parent.mkdir(parents=True, exist_ok=True)
            handle = os.open(lock, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
        except FileExistsError:
            pid, holder_host, since = _holder(lock)
            if pid is not None and holder_host == host and not _alive(pid):
                try:
                    os.unlink(lock)  # stale: its process is gone
                except FileNotFoundError:
                    pass
                continue
            who = f"process {pid} on {holder_host or 'an unknown host'}" if pid else "another run"
            raise OutputLockedError(path, f"is being written by {who}{' since ' + since if since else ''} "
                                          f"(lock {lock}); wait for it, or delete the lock if that run is gone",
                                    errno.EBUSY) from None
        except OSError as err:
            raise OutputError(path, f"cannot write (its lock {lock}: {_reason(err)})",
                              err.errno or errno.EIO) from None
        break
    else:
        raise OutputLockedError(path, f"its lock {lock} keeps changing hands; try again", errno.EBUSY)
    try:
        with os.fdopen(handle, "w", encoding="utf-8") as stream:
            stream.write(content)
            stream.flush()
            status = os.fstat(stream.fileno())
    except OSError as err:
        try:
            os.unlink(lock)
        except OSError:
            pass
        raise OutputError(path, f"cannot write (its lock {lock}: {_reason(err)})", err.errno or errno.EIO) from None
    return status.st_dev, status.st_ino


_SECRET: bytes | None = None


#: The longest cache entry read back [bytes]: a review's cached analysis or a design search's row is a few kB
#: (0.7-2.3 kB measured, Session 15); the bound keeps a damaged or hostile entry from making a run read without end.
MAX_CACHE_ENTRY_BYTES = 64 * 2**20


def open_regular_file(path):
    """``path`` opened for binary reading if it is a regular file; never blocks (a FIFO) nor reads a device.

    Raises
    ------
    OSError
        The file is missing (``FileNotFoundError``), unreadable or not a regular file.
    """
    handle = os.open(path, os.O_RDONLY | os.O_NONBLOCK)  # O_NONBLOCK: a FIFO opens at once; no effect on a file
    try:
        if not stat.S_ISREG(os.fstat(handle).st_mode):
            raise OSError(errno.EINVAL, "not a regular file", str(path))
    except OSError:
        os.close(handle)
        raise
    return os.fdopen(handle, "rb")


def read_regular_file(path, limit: int = 4096) -> bytes:
    """The content of a regular file of at most ``limit`` bytes (a key, a cache entry).

    A key file replaced by a FIFO blocked every batch for ever, a link to ``/dev/zero`` read until the memory
    ran out (Session 15 sweep, docs/security.md): the file is opened by :func:`open_regular_file`.

    Raises
    ------
    OSError
        The file is missing (``FileNotFoundError``), unreadable, not a regular file, or longer than ``limit``.
    """
    with open_regular_file(path) as stream:
        if os.fstat(stream.fileno()).st_size > limit:
            raise OSError(errno.EFBIG, f"longer than {limit} bytes", str(path))
        return stream.read(limit)


def user_secret() -> bytes:
    """This user's key for content keys of outputs that a later run reads back (32 random bytes).

    Kept in ``$ISOLATOR_CACHE_DIR/batch.key`` (or ``~/.cache/isolator/batch.key``), mode 0600 — the
    key the batch's part lines use: whoever can write a cache folder but cannot read this key
    cannot make an entry that passes.  Without a writable cache the key lives for this process only
    (earlier entries are then recomputed, never trusted).
    """
    global _SECRET
    if _SECRET is not None:
        return _SECRET
    root = os.environ.get("ISOLATOR_CACHE_DIR")
    path = (Path(root) if root else Path.home() / ".cache" / "isolator") / "batch.key"
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        try:
            handle = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        except FileExistsError:
            key = read_regular_file(path)
        else:
            key = os.urandom(32)
            with os.fdopen(handle, "wb") as stream:
                stream.write(key)
        if len(key) < 32:
            raise OSError("short key")
    except OSError:
        key = os.urandom(32)
    _SECRET = key
    return key


def keyed_digest(data: bytes) -> str:
    """HMAC-SHA256 of ``data`` under this user's key (:func:`user_secret`)."""
    return hmac.new(user_secret(), data, hashlib.sha256).hexdigest()


def digest_matches(data: bytes, digest) -> bool:
    """Whether ``digest`` is :func:`keyed_digest` of ``data`` (constant-time comparison)."""
    return isinstance(digest, str) and hmac.compare_digest(digest, keyed_digest(data))
