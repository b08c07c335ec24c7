"""Running a batch: plan, skip what is done, execute, keep every finished task, write the table."""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

from isolator.atomic import output_lock, refuse_overwriting_inputs
from isolator.batch.plan import BatchError, ReadOptions, make_tasks, plan, row_key, set_digest
from isolator.batch.store import ROW_SCHEMA, PartStore, existing_rows, table_is_ours, to_table, write_table_atomically
from isolator.batch.worker import run_task
from isolator.parallel import check_scheduler, default_workers, iterate


@dataclass
class BatchResult:
    """What a batch did."""

    output: str
    n_rows: int
    n_failed: int  #: rows with an error
    n_resumed: int  #: rows found done from an earlier run
    n_lost_tasks: int  #: tasks whose worker died (rerun to finish them)
    lost_messages: list = field(default_factory=list)
    #: sentences for the user: damaged part lines skipped, an unencrypted scheduler …
    notes: list = field(default_factory=list)
    seconds: dict = field(default_factory=dict)
    table: object = None  #: pandas.DataFrame

    def final_line(self) -> str:
        line = f"{self.n_rows} rows, {self.n_failed} failed"
        if self.n_lost_tasks:
            line += f", {self.n_lost_tasks} task(s) lost: rerun the same command to finish them"
        return line


def run_batch(records, designs_file, output, *, grids=(), component: str | None = None,
              options: ReadOptions = ReadOptions(), jobs: int | None = None, scheduler: str | None = None,
              reports_dir: str | None = None, map_resolution: int = 30, progress=None,
              design_mappings: list | None = None, extra_outputs=()) -> BatchResult:
    """Run a batch and write its table (see the module docstring).

    Parameters
    ----------
    records : list of str
        Record files, folders or glob patterns [-].
    designs_file : str or Path
        TOML file with ``[[design]]`` tables [-].
    output : str or Path
        ``.csv`` or ``.parquet`` table to write [-].
    grids : list of (str, list of float)
        From :func:`parse_grid` [-].
    component : str, optional
        Component to read; ``"pair"``/``"all"`` (the two horizontals of a file, with the vertical), the
        default for a file with two horizontal components; or ``"all-horizontal"`` (each one alone) [-].
    options : ReadOptions
        Units for records that do not state them; scaling to a PGA [g].
    jobs : int, optional
        Local processes (default: the idle cores, :func:`isolator.parallel.default_workers`);
        ignored with ``scheduler``.
    scheduler : str, optional
        Address of a dask.distributed scheduler, e.g. ``tcp://10.0.0.1:8786``.
    reports_dir : str, optional
        Also write the PDF report of every row there (slow).
    progress : callable, optional
        ``progress(total=n)`` once, then ``progress(advance=n)`` per finished task.
    extra_outputs : list of str, optional
        Other files the command writes (summary, chart): never read as records nor inputs.

    Returns
    -------
    BatchResult

    Raises
    ------
    BatchError
        A mistake in the command (records, designs file, grid, output suffix, scheduler).
    isolator.atomic.OutputError
        An output that is an input, or that another run is writing (its lock).
    """
    clock = time.perf_counter()
    output = Path(output)
    if output.name.lower() in (".csv", ".parquet"):  # to Python a hidden file of no suffix: "must end with .csv"
        raise BatchError(f"{output}: names no file: give a name before {output.name} (e.g. table{output.name})",
                         parameter="output")
    if output.suffix.lower() not in (".csv", ".parquet"):
        raise BatchError(f"{output}: the table must end with .csv or .parquet", parameter="output")
    outputs = [output, *(extra_outputs or ()), *([reports_dir] if reports_dir else [])]
    excluded: list = []
    repeated: list = []
    files, pairs, cases = plan(records, designs_file, grids, component, options, design_mappings, outputs, excluded,
                               repeated)
    refuse_overwriting_inputs(outputs, [*files, designs_file])
    # a file among the records that an output would replace is an input unless this batch wrote it
    refuse_overwriting_inputs([item for item in excluded if not table_is_ours(Path(item))], excluded)
    notes = check_scheduler(scheduler) if scheduler else []
    if repeated:
        notes.insert(0, repeated_records_note(repeated))
    notes[:0] = shared_names_notes(cases, designs_file)
    with output_lock(output):  # a second run on the same -o is refused, naming this one
        return _run_locked(output, pairs, cases, options, jobs, scheduler, reports_dir, map_resolution, progress,
                           clock, notes)


def _run_locked(output, pairs, cases, options, jobs, scheduler, reports_dir, map_resolution, progress, clock,
                notes) -> BatchResult:
    # every planned row by its key: what it is, and where the current plan puts it
    planned = {}
    for path, comp, partners in pairs:
        content = set_digest(path, partners)
        for case in cases:
            planned[row_key(path, comp, case.design_hash, options, content)] = (path, case)
    store = PartStore(output)
    done_rows = {}
    ours = output.is_file() and table_is_ours(output)
    finished, n_other_schema = existing_rows(output, set(planned), ours)
    if output.is_file() and not ours:  # it was replaced without a word (session 23 sweep)
        notes.append(f"{output} exists and is not a table this batch wrote whole (edited by hand, truncated, or "
                     "another file): none of its rows are trusted, and it is replaced by the new table")
    for row in finished + store.rows(set(planned)):
        if row.get("row_key") in planned:
            path, case = planned[row["row_key"]]
            # a reused row takes its place in this plan: positions are never part of what it is
            done_rows[row["row_key"]] = {**row, "record": path, "design_index": case.index,
                                         "design_file_index": case.file_index}
    n_other_schema += store.other_schema
    if n_other_schema:
        notes.append(f"{n_other_schema} stored row(s) of {output} were written under another schema (this isolator "
                     f"writes row_schema {ROW_SCHEMA}): recomputed, not reused")
    if store.damaged:
        notes.append(f"{store.damaged} damaged line(s) in {store.directory} skipped (truncated, corrupt or not "
                     "written by this user); their rows are recomputed")
    workers = 1 if scheduler is None and (jobs or default_workers()) <= 1 else (jobs or default_workers())
    tasks, n_todo = make_tasks(pairs, cases, options, set(done_rows), workers, reports_dir, map_resolution)
    if progress is not None:
        progress(total=len(planned), completed=len(done_rows))
    lost, lost_messages = 0, []
    planning_seconds = time.perf_counter() - clock
    if tasks:
        for task, result in iterate(tasks, run_task, jobs=workers, scheduler=scheduler):
            if isinstance(result, BaseException):
                lost += 1
                lost_messages.append(f"{task.record}: its worker was lost ({type(result).__name__}); rerun the "
                                     "same command to finish it")
                continue
            store.write(result)
            for row in result:
                done_rows[row["row_key"]] = row
            if progress is not None:
                progress(advance=len(result))
    compute_seconds = time.perf_counter() - clock - planning_seconds
    write_start = time.perf_counter()
    table = to_table(list(done_rows.values()))
    write_table_atomically(table, output, keyed=True)
    if not lost:
        store.remove()
    write_seconds = time.perf_counter() - write_start
    n_failed = int((table["error"] != "").sum())
    notes.extend(_duplicate_motion_notes(table))
    return BatchResult(output=str(output), n_rows=len(table), n_failed=n_failed,
                       n_resumed=len(planned) - n_todo, n_lost_tasks=lost, lost_messages=lost_messages, notes=notes,
                       seconds={"plan": planning_seconds, "compute": compute_seconds, "write": write_seconds},
                       table=table)


def repeated_records_note(repeated: list) -> str:
    """One sentence for the record files named more than once on the command line: each is analysed once.

    A note, not a refusal: folders and patterns that overlap (``recs/ recs/new/*.AT2``) are a batch's usual input,
    and a second row of the same file would only be counted twice by the summary."""
    shown = ", ".join(str(p) for p in repeated[:3]) + (f" and {len(repeated) - 3} more" if len(repeated) > 3 else "")
    if len(repeated) == 1:
        return f"{shown} was given more than once: it is analysed once (one row per design)"
    return f"{len(repeated)} record files were given more than once ({shown}): each is analysed once"


def shared_names_notes(cases, source) -> list[str]:
    """One sentence per name that several ``[[design]]`` tables of the designs file share (h203: two tables named
    'a' gave two rows named 'a', told apart only by ``design_index``, without a word).  Not an error: the rows are
    right, and a copied table is a usual first step; the engineer is told which tables to rename."""
    from isolator.errors import printable

    tables: dict = {}
    read: set = set()
    for case in cases:  # a table's first case only: a grid's candidates append the same values to every table's name
        name = case.mapping.get("name")
        if case.file_index not in read and isinstance(name, str) and name.strip():
            read.add(case.file_index)
            tables.setdefault(" ".join(name.split()).casefold(), {}).setdefault(case.file_index, name.strip())
    notes = []
    for indices in tables.values():
        if len(indices) > 1:
            numbers = [str(i + 1) for i in sorted(indices)]
            shown = ", ".join(numbers[:-1]) + " and " + numbers[-1]
            notes.append(f"{source}: [[design]] tables {shown} share the name '{printable(next(iter(indices.values())))}"
                         "': their rows are told apart only by design_index (give each design its own name)")
    return notes


def _duplicate_motion_notes(table) -> list[str]:
    """A sentence for each motion held by more than one file (same samples and time step)."""
    if "motion_sha256" not in table.columns:
        return []
    files = table[table["motion_sha256"].fillna("") != ""].groupby("motion_sha256")["record"].unique()
    return [f"the same motion is in {len(names)} files ({', '.join(sorted(str(n) for n in names))}): "
            "the summary counts it once" for names in files if len(names) > 1]
