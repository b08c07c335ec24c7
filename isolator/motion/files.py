"""Which files hold records, and which files and components belong together: file discovery.

What a batch, a review suite or a command needs before reading a sample: the record
files of folders and glob patterns (:func:`expand_records`), the sibling files of a
K-NET / KiK-net set (:func:`knet_siblings`), the components of a file to analyse
(:func:`record_components`) and the sets of one-component files of one station
(:func:`station_sets`, from the files' headers only).
"""

from __future__ import annotations

import glob as _glob
import os
import re
from collections import deque
from pathlib import Path

from isolator.errors import BatchError, RecordError
from isolator.motion.components import label_is_vertical
from isolator.motion.read import list_components, read_header

#: K-NET (.NS/.EW/.UD) and KiK-net (1: borehole, 2: surface) file suffixes of one set.
KNET_SUFFIXES = {"": ("NS", "EW", "UD"), "1": ("NS1", "EW1", "UD1"), "2": ("NS2", "EW2", "UD2")}
#: Files a folder holds that are never records (a batch's own lock and MAC files, and the checksum
#: lists that travel with record folders, included).
_NOT_RECORDS = re.compile(r"^(readme.*|(sha\d*sums|md5sums)(\.txt)?"
                          r"|.*\.(md|json|toml|pdf|png|parquet|py|xml|zip|gz|lock|jsonl))$", re.IGNORECASE)


def _is_output(path, outputs) -> bool:
    """True if ``path`` is one of the batch's outputs, its part files, lock or report folder."""
    real = os.path.realpath(path)
    for output in outputs:
        out = os.path.realpath(output)
        if real in (out, out + ".lock") or real.startswith(out + ".parts" + os.sep) or \
                real.startswith(out.rstrip(os.sep) + os.sep):
            return True
    return False


#: The deepest folder a records folder is walked into, and the most files it may list: a batch plans at most
#: 1,000,000 rows (isolator.batch.plan.MAX_PLAN_ROWS), and no records archive nests 64 folders deep, so a walk
#: past either is a link pointing back up the tree in a way the loop check cannot see, or the wrong folder.
MAX_FOLDER_DEPTH = 64
MAX_FOLDER_FILES = 1_000_000


def folder_files(folder: str) -> list[str]:
    """Every entry of ``folder`` and its subfolders that is not a folder, hidden names and ``*.parts`` left out.

    Linked folders are followed, as a user who put a link to a folder of records beside the others expects (the
    session 15 sweep: rglob left them out without a word); each folder is walked once, by its device and inode,
    so a link back up the tree ends there.  A FIFO, a socket, a dangling link or a link loop is kept: its row
    says what it is (:func:`isolator.io._common.input_file_problem`), nothing is skipped unsaid.

    Raises
    ------
    BatchError
        A folder that cannot be listed, deeper than :data:`MAX_FOLDER_DEPTH` or holding more than
        :data:`MAX_FOLDER_FILES` files.
    """
    found: list[str] = []
    walked: set = set()
    queue = deque([(folder, 0)])
    while queue:  # bounded: each folder (device, inode) once, at most MAX_FOLDER_DEPTH deep
        current, depth = queue.popleft()  # breadth first: a folder reached twice keeps its shortest name
        try:
            identity = (os.stat(current).st_dev, os.stat(current).st_ino)
            if identity in walked:
                continue  # a second way to a folder already listed: its files are in once
            walked.add(identity)
            with os.scandir(current) as entries:  # real folders before links to folders, then by name
                listed = sorted(entries, key=lambda entry: (entry.is_symlink(), entry.name))
        except OSError as err:
            raise BatchError(f"{current}: cannot list this folder ({err.strerror or err}); give the readable "
                             "folders or files instead") from None
        for entry in listed:
            if entry.name.startswith("."):
                continue
            try:
                is_folder = entry.is_dir()  # follows a link; a FIFO, a dangling link is not a folder
            except OSError:  # a link loop raised ELOOP here: the whole batch stopped, "recs/loop: cannot write"
                is_folder = False  # listed as a file: its row says "symbolic-link loop", the others run
            if not is_folder:
                found.append(os.path.join(current, entry.name))
                if len(found) > MAX_FOLDER_FILES:
                    raise BatchError(f"{folder}: holds more than {MAX_FOLDER_FILES:,} files, more than the "
                                     "largest batch: give its subfolders one by one")
            elif not entry.name.endswith(".parts"):
                if entry.is_symlink() and _encloses(os.path.realpath(entry.path), current):
                    raise BatchError(f"{entry.path}: links to {os.path.realpath(entry.path)}, a folder holding "
                                     "it (a loop): remove the link, or give the folders meant")
                if depth + 1 > MAX_FOLDER_DEPTH:
                    raise BatchError(f"{entry.path}: more than {MAX_FOLDER_DEPTH} folders deep below {folder}: "
                                     "give a folder nearer the records")
                queue.append((entry.path, depth + 1))
    return found


def _encloses(outer: str, folder: str) -> bool:
    """True if the real folder ``outer`` is ``folder`` or holds it."""
    inner = os.path.realpath(folder)
    return inner == outer or inner.startswith(outer.rstrip(os.sep) + os.sep)


def expand_records(arguments, outputs=(), excluded: list | None = None, repeated: list | None = None) -> list[str]:
    """Record files from files, folders (recursively, sorted) and glob patterns.

    A literal path that does not exist is kept (its rows will say why); a glob that
    matches nothing and an empty folder are user mistakes.  Files of the batch itself
    (``outputs``: the table, its ``.parts/`` and lock, the summary, chart and reports
    folder) and any ``*.parts`` folder are never records, so that ``-o`` may sit inside
    the records folder.  A file named more than once (``x.AT2 x.AT2``, ``x.AT2 ./x.AT2``,
    a folder and a pattern that overlap) is kept once; ``repeated`` receives each such file
    once, as first given, for the caller to say so.

    Raises
    ------
    BatchError
    """
    files: list[str] = []
    outputs = [str(item) for item in outputs if item]
    excluded = [] if excluded is None else excluded

    def wanted(path) -> bool:
        if _is_output(path, outputs):
            excluded.append(str(path))  # run_batch checks that such a file is the batch's own
            return False
        return True

    for argument in arguments:
        argument = str(argument)
        if not argument:  # `batch ''` ran a row that failed (exit 1): a mistake in the command, as an unmatched glob
            raise BatchError("a record is named by a file path, got ''")
        if os.path.isdir(argument):
            found = sorted(path for path in folder_files(argument) if not _NOT_RECORDS.match(os.path.basename(path))
                           and wanted(path))
            if not found:
                raise BatchError(f"{argument}: folder holds no record files")
            files.extend(found)
        elif _glob.has_magic(argument) and not os.path.lexists(argument):
            # a FIFO or a dangling link that matches is kept: its row says what it is (never skipped unsaid)
            found = sorted(p for p in _glob.glob(argument, recursive=True) if not os.path.isdir(p) and wanted(p))
            if not found:
                raise BatchError(f"{argument}: no file matches this pattern")
            files.extend(found)
        else:  # a literal path, even with [ ] * ? in its name, names exactly that file
            files.append(argument)
    unique, seen = [], {}
    for path in files:
        key = os.path.abspath(path)
        if key not in seen:
            seen[key] = 1
            unique.append(path)
        else:
            seen[key] += 1
            if seen[key] == 2 and repeated is not None:
                repeated.append(next(p for p in unique if os.path.abspath(p) == key))
    if not unique:
        raise BatchError("no record given")
    return unique

def knet_siblings(path: Path) -> list[Path] | None:
    """The files of a K-NET / KiK-net set that ``path`` belongs to (those that exist, in NS, EW, UD
    order), or None if its suffix is not one of :data:`KNET_SUFFIXES`."""
    path = Path(path)
    suffix = path.suffix.lstrip(".").upper()
    for names in KNET_SUFFIXES.values():
        if suffix in names:
            siblings = []
            for name in names:
                candidates = [path.with_suffix("." + name), path.with_suffix("." + name.lower())]
                found = next((c for c in candidates if c.exists()), None)
                if found is not None:
                    siblings.append(found)
            return siblings
    return None


#: Suffixes of formats that hold one component per file: never listed at planning.
_ONE_COMPONENT_SUFFIXES = frozenset({".at2", ".smc", ".txt", ".csv", ".acc", ".dat", ".tsv", ".asc", ".th", ".xy",
                                     ".sac"})
#: Analyses of a whole file: its two horizontal components ("pair") or with the vertical ("all").
SET_COMPONENTS = ("pair", "all")


def _knet_set_member(path: str) -> tuple[bool, bool]:
    """(belongs to a K-NET/KiK-net set of two horizontals, is the set's first existing file)."""
    siblings = knet_siblings(Path(path))
    if siblings is None:
        return False, False
    horizontal = [p for p in siblings if not p.suffix.upper().startswith(".UD")]
    if len(horizontal) != 2:
        return False, False
    return True, os.path.abspath(siblings[0]) == os.path.abspath(path)


def record_components(path: str, component: str | None) -> list[str | None]:
    """Components to analyse in a file.

    * ``None`` (the default): ``["pair"]`` for a file with two horizontal components
      (a multi-channel file, or the first file of a K-NET set), ``[]`` for the other
      files of that set, ``[None]`` (the file's one component) otherwise;
    * ``"pair"`` / ``"all"``: the same, the vertical included for ``"all"``;
    * ``"all-horizontal"``: every horizontal component of a multi-component file, one by one;
    * any other label: ``[component]``.

    A file that cannot be listed gives ``[None]`` (or ``[component]``): the read then
    fails with the file's message, in the rows.
    """
    if component not in (None, "all-horizontal", *SET_COMPONENTS):
        return [component]
    knet, first = _knet_set_member(path)
    if knet and component != "all-horizontal":
        return [component or "pair"] if first else []
    if component is None and Path(path).suffix.lower() in _ONE_COMPONENT_SUFFIXES:
        return [None]
    try:
        labels = list_components(path)
    except (RecordError, ValueError, OSError):
        return [component if component in SET_COMPONENTS else None]
    horizontal = [label for label in labels if not label_is_vertical(label)]
    if component == "all-horizontal":
        return horizontal if len(labels) > 1 and horizontal else [None]
    if len(horizontal) == 2:
        return [component or "pair"]
    return [component if component in SET_COMPONENTS else None]


def station_sets(files, component: str | None) -> dict[str, tuple[str, ...]]:
    """Pairs made of several one-component files: one station's horizontals (and vertical).

    Files of one component each (PEER AT2, SMC, …) that sit in one folder and whose headers
    name the same network, station and event form a set when it holds exactly two
    horizontal components with different labels, and at most one vertical.  Only the
    headers are read (a few lines a file).  Anything else (one file of the station, the same
    component twice, as ``TAK000.AT2`` beside ``RSN1120_KOBE_TAK000.AT2``, a header without
    station or event, a file that cannot be read) leaves the files alone, analysed one
    component each; two files of one motion under different labels are refused when the
    pair is read (an error row).

    Returns
    -------
    dict
        ``{x path: (y path,) or (y path, z path)}`` for the first horizontal (sorted) of
        each set; the other members of a set are the keys' partners.  Empty unless
        ``component`` is None, ``"pair"`` or ``"all"``.
    """
    if component not in (None, *SET_COMPONENTS):
        return {}
    groups: dict = {}
    for path in files:
        header = _station_header(path)
        if header is not None:
            key, label = header
            groups.setdefault(key, []).append((path, label, label_is_vertical(label)))
    sets = {}
    for items in groups.values():
        horizontal = sorted(item for item in items if not item[2])
        vertical = [item for item in items if item[2]]
        if len(horizontal) != 2 or len(vertical) > 1 or horizontal[0][1] == horizontal[1][1]:
            continue
        sets[horizontal[0][0]] = (horizontal[1][0], *(item[0] for item in vertical))
    return sets


def _station_header(path: str):
    """((folder, network, station, event), component label) from the header of a PEER AT2 or USGS SMC
    file (a few lines read, not the samples), or None: another format, no station or event in the
    header, a file that cannot be read (its rows will say why)."""
    header = read_header(path)
    if header is None:
        return None
    label, prov = header
    station, event = prov.get("station", ""), prov.get("event", prov.get("event_origin_time", ""))
    if not station or not event:
        return None
    return (os.path.dirname(os.path.abspath(path)), prov.get("network", ""), station, event), label


