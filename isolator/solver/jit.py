"""``njit`` for every compiled kernel of isolator, its disk cache filed under the kernel's own sources.

numba keys a function's on-disk cache on the contents of the *one* file that defines it
(``numba.core.caching``: the source stamp is that file's SHA-256).  A kernel inlines the
``@njit`` functions and module constants it imports from other modules, so a change in one of
those alone (``multisurface_series.py`` under ``multisurface_kernel.py``, a constant of
``planar_layout.py``) left a stale compiled kernel in use in an editable install.

Here numba's cache directory (``numba.config.CACHE_DIR``, which numba reads when a function is
decorated: ``UserProvidedCacheLocator``) is set, while an isolator kernel is decorated, to a
folder named by a digest of numba's version and of the sources of the kernel's module and of
every isolator module it imports at module level, transitively (:func:`kernel_sources`).  A
change in any of those files the module's kernels under a new folder, so they compile once
again; a change elsewhere compiles nothing.  The setting is put back after each decoration, so
other numba code of the same process keeps its own.

The folders are ``$NUMBA_CACHE_DIR/numba-<digest>`` when that variable is set (numba's own
setting, honoured), else ``isolator/__pycache__/numba-<digest>`` beside the sources (where numba's
in-tree cache was: a fresh clone, or CI, compiles once, as before), else, in a read-only install,
``$ISOLATOR_CACHE_DIR/numba-<digest>`` or ``~/.cache/isolator/numba-<digest>``.  A folder in use
has its time stamp renewed by every process that uses it; folders unused for :data:`KEEP_OLD_DAYS`
are removed when a new one is made.
"""

from __future__ import annotations

import functools
import hashlib
import os
import re
import shutil
import time
from pathlib import Path

import numba
from numba.core import config

#: The package's root folder (``isolator/``).
PACKAGE = Path(__file__).resolve().parents[1]
#: Folders no process used for this many days are removed when a new one is made [d].
KEEP_OLD_DAYS = 7.0
#: Module-level ``from isolator.x import y`` (one line or a parenthesised list) and ``import isolator.x`` lines
#: (an indented import is not seen by a compiled kernel: it calls only what its module holds at import).
_IMPORT = re.compile(r"^(?:from\s+(isolator(?:\.\w+)*)\s+import\s+(?:\(([^)]*)\)|([^\n]*))"
                     r"|import\s+(isolator(?:\.\w+)*))", re.MULTILINE)


@functools.cache  # one look-up per module and process: the kernel modules share most of their imports
def _module_path(name: str) -> Path | None:
    """The source file of the isolator module ``name`` (a package's ``__init__.py``), None if none."""
    base = PACKAGE.parent.joinpath(*name.split("."))
    for path in (base.with_suffix(".py"), base / "__init__.py"):
        if path.is_file():
            return path
    return None


@functools.cache
def _imports(path: Path) -> frozenset[str]:
    """The isolator modules a source imports at module level (``from isolator.a import b`` counts ``a.b`` when it
    is a module, else ``a``)."""
    found = set()
    for match in _IMPORT.finditer(path.read_text(encoding="utf-8")):
        if match.group(4):
            found.add(match.group(4))
            continue
        source = match.group(1)
        found.add(source)
        for name in re.sub(r"#[^\n]*", "", match.group(2) or match.group(3) or "").split(","):
            words = name.split()
            if words and _module_path(f"{source}.{words[0]}") is not None:
                found.add(f"{source}.{words[0]}")
    return frozenset(found)


@functools.cache
def kernel_sources(module_file: str) -> tuple[Path, ...]:
    """The source of a kernel module and of every isolator module it imports at module level, transitively
    (sorted paths): what its compiled functions can inline."""
    seen = {Path(module_file).resolve(): None}
    todo = list(seen)
    while todo:  # bounded: each module enters once
        for name in _imports(todo.pop()):
            path = _module_path(name)
            if path is not None and path not in seen and path != Path(__file__).resolve():
                seen[path] = None
                todo.append(path)
    return tuple(sorted(seen))


@functools.cache
def cache_dir(module_file: str) -> str:
    """The folder of the compiled kernels of the module at ``module_file``, for its sources (:func:`kernel_sources`)
    and this numba (made if absent, its time stamp renewed: a folder in use is never an old one) [path]."""
    digest = hashlib.sha256(f"numba {numba.__version__}\n".encode())
    for path in kernel_sources(module_file):
        label = path.relative_to(PACKAGE).as_posix() if path.is_relative_to(PACKAGE) else path.as_posix()
        digest.update(label.encode() + b"\0" + path.read_bytes() + b"\0")
    name = f"numba-{digest.hexdigest()[:16]}"
    user = os.environ.get("ISOLATOR_CACHE_DIR")
    roots = [PACKAGE / "__pycache__", Path(user) if user else Path.home() / ".cache" / "isolator"]
    if os.environ.get("NUMBA_CACHE_DIR"):  # the user's own choice of numba's cache folder comes first
        roots.insert(0, Path(os.environ["NUMBA_CACHE_DIR"]))
    for root in roots:
        folder = root / name
        try:
            new = not folder.is_dir()
            folder.mkdir(parents=True, exist_ok=True)
            os.utime(folder)
            probe = folder / f".probe-{os.getpid()}"
            probe.write_bytes(b"")
            probe.unlink()
        except OSError:
            continue
        if new:
            _remove_old(root)
        return str(folder)
    return ""  # nowhere writable: numba's own locators decide (as before)


def _remove_old(root: Path) -> None:
    """Remove the ``numba-*`` folders under ``root`` that no process used for :data:`KEEP_OLD_DAYS`."""
    limit = time.time() - KEEP_OLD_DAYS * 86400.0
    for folder in root.glob("numba-*"):
        try:
            if folder.is_dir() and folder.stat().st_mtime < limit:
                shutil.rmtree(folder, ignore_errors=True)
        except OSError:
            continue


def njit(*args, **kwargs):
    """``numba.njit`` with its disk cache under :func:`cache_dir` of the decorated function's module (same
    arguments, bare or called).

    Examples
    --------
    ``@njit(cache=True)`` or ``@njit(cache=True, inline="always")`` over a kernel function.
    """
    if args and callable(args[0]):  # bare @njit
        return _decorated(numba.njit, args[0], (), kwargs)

    def decorate(function):
        return _decorated(numba.njit, function, args, kwargs)

    return decorate


def _decorated(jit, function, args, kwargs):
    """``jit(*args, **kwargs)(function)`` with numba's cache setting at the function's folder, then put back."""
    previous = config.CACHE_DIR
    config.CACHE_DIR = cache_dir(function.__code__.co_filename) or previous
    try:
        return jit(*args, **kwargs)(function)
    finally:
        config.CACHE_DIR = previous
