"""Batch: many records × many designs into one table — resumable, parallel, local or on Dask.

The work is planned in the parent process and executed by one of two executors chosen
at the start (local processes, or an existing ``dask.distributed`` cluster); the code
that computes rows (:func:`run_task`) is the same for both.

* **Cases.** Records (files, folders, globs) × components × designs (a ``[[design]]``
  list in a TOML file, each optionally swept by ``--grid KEY=START:STOP:COUNT``, the
  cartesian product).  One row per (record, component, design).
* **Tasks.** Work is grouped by record: a task reads one record (once per worker
  process: a small per-process cache serves the other tasks of the same record) and
  runs all its designs, so that reading, the intensity measures and process overhead
  are paid once per record, not once per row.  The harmonic classification at the
  equivalent point is cached per process per distinct (α, k, η, µs, µk).
* **Never lose work.** Each finished task is written as one JSON-lines part file in
  ``<output>.parts/`` (written to a temporary name, then renamed: a part is whole or
  absent).  A row has a deterministic key (record path, component, design hash, read
  options); a new run with the same arguments skips the keys already present and the
  final table (sorted by record, component, design index) is the same as that of an
  uninterrupted run, except the timing columns (:data:`TIMING_COLUMNS`).  The final
  CSV or Parquet file is written through a temporary file and an atomic rename; the
  parts are removed after it.
* **Errors.** A record that cannot be read gives one row per design with the one-line
  message in ``error``; an invalid design (from the file or a grid value) gives rows
  with ``error`` for that design; the batch goes on.
"""

from isolator.batch.charts import SUMMARY_RESPONSES, design_chart, suite_summary
from isolator.batch.plan import (
                                 GRID_KEYS,
                                 DesignCase,
                                 ReadOptions,
                                 Task,
                                 expand_designs,
                                 expand_records,
                                 is_vertical,
                                 load_design_mappings,
                                 make_tasks,
                                 parse_grid,
                                 plan,
                                 record_components,
                                 row_key,
                                 station_sets,
)
from isolator.batch.run import BatchResult, run_batch
from isolator.batch.store import COLUMNS, TIMING_COLUMNS, PartStore, comparable, to_table, write_table_atomically
from isolator.batch.worker import run_task
from isolator.errors import BatchError

__all__ = ["COLUMNS", "GRID_KEYS", "SUMMARY_RESPONSES", "TIMING_COLUMNS", "BatchError", "BatchResult",
           "DesignCase", "PartStore", "ReadOptions", "Task", "comparable", "design_chart", "expand_designs",
           "expand_records", "is_vertical", "load_design_mappings", "make_tasks", "parse_grid", "plan",
           "record_components", "row_key", "run_batch", "run_task", "station_sets", "suite_summary", "to_table",
           "write_table_atomically"]
