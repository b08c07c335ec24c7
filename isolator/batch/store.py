"""Where rows go: part files (one JSON-lines file per finished task) and the final table."""

from __future__ import annotations

import hashlib
import hmac
import json
import os
import re
import time
import uuid
from pathlib import Path

from isolator.analysis import ROW_ENGINEERING_KEYS, ROW_KEYS, SCHEMA_VERSION, TIMING_KEYS
from isolator.atomic import atomic_path, keyed_digest, read_regular_file, write_text_atomically
from isolator.serialize import dumps, json_safe

#: The batch's own columns that name a row and its record (then the record's intensity measures).
RECORD_COLUMNS = (
    "record", "component", "design_index", "design_name", "error",
    # record provenance
    "record_format", "record_station", "record_station_name", "record_network", "record_channel",
    "record_event", "record_date", "record_starttime", "record_units_source", "record_npts", "record_dt_s",
    "record_duration_s", "record_scale_factor", "record_processing", "record_files", "motion_sha256",
    # the components of a pair (and the vertical), their PGA
    "component_x", "component_y", "component_z", "pga_x_m_s2", "pga_y_m_s2", "pga_z_m_s2",
    # intensity measures (of the motion analysed, after scaling)
    "pga_m_s2", "pgv_m_s", "pgd_m", "arias_m_s", "d5_95_s", "predominant_period_s", "a0_equiv_m",
    "omega_equiv_rad_s",
)
#: The design's columns.
DESIGN_COLUMNS = ("design_file_index", "design_kind", "mass_kg", "radius_m", "stiffness_N_per_m", "mu_static",
                  "mu_kinetic", "damping_Ns_per_m", "damping_ratio", "isolated_period_s")
#: Columns that measure time: they differ between two runs of the same batch.
TIMING_COLUMNS = ("read_seconds", *TIMING_KEYS, "row_seconds")

#: Scalar results that only some models give (the building above the isolators, docs/building.md; a double
#: or triple pendulum, docs/multisurface.md), under the analysis schema's names; empty in the other rows.
#: ``regimes_reached`` is the schema's ``regimes`` (a dict) as text: the regimes entered, in order of entry;
#: ``regimes_first_time_s`` the same dict's first times, as JSON text in that order (issue 23: ``{"I": first
#: time [s], …}``); ``ultimate_first_time_s`` when every surface first reached its rim (empty if never).
MODEL_COLUMNS = (
    "superstructure_shear_coefficient", "n_bearings_uplifted", "energy_strain_final_J_per_kg",
    "bearing_type", "regimes_reached", "regimes_first_time_s", "n_rim_contacts", "ultimate_displacement_reached",
    "ultimate_displacement_m", "ultimate_first_time_s",
    "impact_impulse_m_s", "max_impact_velocity_m_s", "energy_impact_J_per_kg", "peak_force_per_weight",
)
#: Lists of the analysis schema (per story and floor bottom to top, per bearing and per surface in file
#: order), written as one numbered column per item: ``story_drift_ratio_1`` is the bottom story.  As many
#: numbered columns as the longest list of the table (:func:`list_columns`).
LIST_COLUMNS = ("story_drift_m", "story_drift_ratio", "floor_peak_acceleration_m_s2", "bearing_axial_load_max_N",
                "bearing_axial_load_min_N", "surface_peak_displacement_m")

#: Column order of the table (columns of every row; a row may leave some empty): record + design + the
#: analysis' row keys (:data:`isolator.analysis.ROW_KEYS`, :data:`~isolator.analysis.ROW_ENGINEERING_KEYS`)
#: + the models' own + timing + the row's key and schema — each name listed once, in its own module; the
#: numbered columns of :data:`LIST_COLUMNS` follow.
COLUMNS = (
    *RECORD_COLUMNS, *DESIGN_COLUMNS,
    *(key for key in ROW_KEYS if key not in TIMING_KEYS), *ROW_ENGINEERING_KEYS, *MODEL_COLUMNS,
    *TIMING_COLUMNS, "row_key", "row_schema",
)

#: What a row holds: the analysis schema's version and a digest of the column list.  Part of every row key
#: (:func:`isolator.batch.plan.row_key`) and written in the ``row_schema`` column: a row stored by an
#: isolator whose schema or columns differ is recomputed, never reused with columns missing or meaning
#: something else.
ROW_SCHEMA = f"{SCHEMA_VERSION}:" + hashlib.sha256("\0".join((*COLUMNS, *LIST_COLUMNS)).encode()).hexdigest()[:8]

_COLUMN_SET = frozenset(COLUMNS)
_LIST_COLUMN = re.compile(r"^(" + "|".join(re.escape(key) for key in LIST_COLUMNS) + r")_([1-9][0-9]{0,3})$")


def is_column(name) -> bool:
    """True for a column of the table: one of :data:`COLUMNS` or a numbered :data:`LIST_COLUMNS` column."""
    return isinstance(name, str) and (name in _COLUMN_SET or _LIST_COLUMN.match(name) is not None)


def list_columns(counts: dict) -> list[str]:
    """The numbered columns for lists of the given lengths (``{key: n}``), in :data:`LIST_COLUMNS` order."""
    return [f"{key}_{i}" for key in LIST_COLUMNS for i in range(1, int(counts.get(key, 0)) + 1)]


def model_columns(flat: dict) -> dict:
    """The row's :data:`MODEL_COLUMNS` and numbered :data:`LIST_COLUMNS` from the analysis' flat keys.

    Parameters
    ----------
    flat : dict
        :meth:`isolator.analysis.Analysis.flat` (the keys a model does not give are left out).

    Returns
    -------
    dict
        Column → value: the scalars as the analysis holds them, each list item in its numbered column.
    """
    out = {key: flat[key] for key in MODEL_COLUMNS if flat.get(key) is not None}
    regimes = flat.get("regimes")
    if isinstance(regimes, dict):
        entered = sorted(regimes, key=lambda name: regimes[name])
        out["regimes_reached"] = ", ".join(entered)
        out["regimes_first_time_s"] = json.dumps({name: regimes[name] for name in entered})
    for key in LIST_COLUMNS:
        values = flat.get(key)
        if values is not None:
            out.update({f"{key}_{i}": value for i, value in enumerate(values, start=1)})
    return out

def content_key(data: bytes) -> str:
    """HMAC-SHA256 of ``data`` under this user's key (:func:`isolator.atomic.user_secret`, shared with the
    review cache: ``$ISOLATOR_CACHE_DIR/batch.key``, mode 0600)."""
    return keyed_digest(data)


def _valid_row(row, planned) -> bool:
    """A part row holds only known columns with JSON scalars, and a planned key."""
    if not isinstance(row, dict) or row.get("row_key") not in planned:
        return False
    return all(is_column(key) and (value is None or isinstance(value, (str, int, float, bool)))
               for key, value in row.items())


def other_schema(row) -> bool:
    """A stored row written under another :data:`ROW_SCHEMA` (an older isolator wrote none)."""
    return isinstance(row, dict) and row.get("row_schema") != ROW_SCHEMA


def _canonical(row) -> bytes:
    return json.dumps(row, sort_keys=True, allow_nan=False, separators=(",", ":")).encode("utf-8")


#: The longest line of a part file: a row is ~3.4 KB (117 columns), a building's or a triple pendulum's numbered
#: columns add a few KB; a longer line is damage.  Lines are read one at a time, so a part file of any size (a 1 GB
#: file of NULs held 3.3 GB resident and took 32 s, session 23 sweep) is read in bounded memory.
MAX_PART_LINE_BYTES = 1 << 20


def _part_lines(part: Path):
    """The lines of one part file, each at most :data:`MAX_PART_LINE_BYTES`; None for a longer line (then the rest of
    the part is not read), for a part that is empty (a part holds at least one row) or not a regular file, or
    unreadable."""
    try:
        if not part.is_file() or part.stat().st_size == 0:
            yield None
            return
        with open(part, "rb") as stream:
            while raw := stream.readline(MAX_PART_LINE_BYTES + 1):
                if len(raw) > MAX_PART_LINE_BYTES:  # not a part this batch wrote: the rest of it is not read
                    yield None
                    return
                yield raw
    except OSError:
        yield None


class PartStore:
    """``<output>.parts/``: one JSON-lines file per finished task, written atomically.

    Each line is ``{"row": {…}, "key": HMAC}``: a line whose content key does not match
    (truncated, bit-flipped, crafted), that is not JSON or not UTF-8, or whose row holds
    unknown columns, nested values or a key outside the plan, is skipped and counted in
    :attr:`damaged`; its row is then recomputed.  A whole row written under another
    :data:`ROW_SCHEMA` (its key is not planned: the schema is part of every key) is counted
    in :attr:`other_schema`, not as damage.
    """

    def __init__(self, output):
        output = Path(output)
        self.directory = output.with_name(output.name + ".parts")
        self.damaged = 0  #: part lines skipped by the last :meth:`rows`
        self.other_schema = 0  #: rows of another schema met by the last :meth:`rows` (recomputed)

    def rows(self, planned=None) -> list[dict]:
        """Rows of every complete part that pass the checks (see the class docstring).

        Parameters
        ----------
        planned : set of str, optional
            Row keys of the current plan; rows outside it are ignored (not counted as damaged).
        """
        self.damaged = self.other_schema = 0
        if not self.directory.is_dir():
            return []
        rows = []
        for part in sorted(self.directory.glob("part-*.jsonl")):
            for raw in _part_lines(part):
                if raw is None:  # a line longer than any row, an empty part, a folder, FIFO or loop: not ours
                    self.damaged += 1
                    continue
                if not raw.strip():
                    continue
                try:
                    line = json.loads(raw.decode("utf-8"))
                    row, key = line["row"], line["key"]
                    if not isinstance(key, str) or not hmac.compare_digest(key, content_key(_canonical(row))):
                        raise ValueError("content key")
                except (ValueError, KeyError, TypeError, AttributeError, RecursionError):  # JSON/Unicode: ValueError;
                    # RecursionError: arrays nested past the stack (session 17 sweep)
                    self.damaged += 1
                    continue
                if planned is not None and isinstance(row, dict) and row.get("row_key") not in planned:
                    self.other_schema += other_schema(row)
                    continue  # another plan's (or schema's) row: not ours to use, not damage
                if not _valid_row(row, planned if planned is not None else {row.get("row_key")}):
                    self.damaged += 1
                    continue
                rows.append(row)
        return rows

    def write(self, rows: list[dict]) -> None:
        if not rows:
            return
        self.directory.mkdir(parents=True, exist_ok=True)
        name = f"part-{time.time_ns():020d}-{uuid.uuid4().hex[:8]}.jsonl"
        tmp = self.directory / f".{name}.tmp"
        with open(tmp, "w", encoding="utf-8") as stream:
            for row in rows:
                safe = json_safe(row)
                stream.write(dumps({"row": safe, "key": content_key(_canonical(safe))}) + "\n")
            stream.flush()
            os.fsync(stream.fileno())
        os.replace(tmp, self.directory / name)

    def remove(self) -> None:
        import shutil

        shutil.rmtree(self.directory, ignore_errors=True)


def table_key_path(output: Path) -> Path:
    """Where the content key of a finished table is kept: ``.<name>.key`` beside it."""
    output = Path(output)
    return output.with_name(f".{output.name}.key")


def table_is_ours(output: Path) -> bool:
    """True when the table at ``output`` is whole and was written by this user's batch (its content key matches)."""
    try:
        stored = read_regular_file(table_key_path(output)).decode("ascii").strip()  # a FIFO, /dev/zero: not ours
        return hmac.compare_digest(stored, content_key(output.read_bytes()))
    except (OSError, UnicodeDecodeError):
        return False


def existing_rows(output: Path, keys: set, ours: bool | None = None) -> tuple[list[dict], int]:
    """Rows of a finished table at ``output`` whose key is planned (a rerun after completion).

    Only a table whose content key (written beside it by :func:`write_table_atomically`)
    still matches is reused: an edited or foreign table is recomputed, never trusted.
    ``ours`` is :func:`table_is_ours`'s verdict when the caller has it (the table is hashed once); None: taken here.

    Returns
    -------
    tuple
        (the rows, how many of the table's rows were written under another :data:`ROW_SCHEMA`).
    """
    if ours is None:
        ours = output.is_file() and table_is_ours(output)
    if not ours:
        return [], 0
    import pandas as pd

    try:
        table = pd.read_parquet(output) if output.suffix.lower() == ".parquet" else pd.read_csv(
            output, keep_default_na=False, na_values=[""])
    except Exception:  # noqa: BLE001 - an unreadable old table is simply recomputed
        return [], 0
    schemas = table["row_schema"].astype(object) if "row_schema" in table.columns else None
    n_other = len(table) if schemas is None else int((schemas != ROW_SCHEMA).sum())
    if "row_key" not in table.columns or any(not is_column(column) for column in table.columns):
        return [], n_other
    table = table[table["row_key"].isin(keys)]
    table = table.astype(object).where(table.notna(), None)
    rows = table.to_dict("records")
    for row in rows:
        if row.get("error") is None:
            row["error"] = ""
    return rows, n_other


def to_table(rows: list[dict]):
    """Rows → DataFrame: :data:`COLUMNS`, then the numbered :data:`LIST_COLUMNS` as long as the longest list of
    the rows; sorted by record, component, design."""
    import pandas as pd

    table = pd.DataFrame(rows)
    numbered = [column for column in table.columns if column not in _COLUMN_SET and is_column(column)]
    counts: dict = {}
    for column in numbered:
        key, number = _LIST_COLUMN.match(column).groups()
        counts[key] = max(counts.get(key, 0), int(number))
    order = [*COLUMNS, *list_columns(counts)]
    missing = [column for column in order if column not in table.columns]
    if missing:  # added at once (one column at a time fragments the frame), empty as None
        table = pd.concat([table, pd.DataFrame({column: pd.Series([None] * len(table), index=table.index,
                                                                  dtype=object) for column in missing})], axis=1)
    extra = [c for c in table.columns if c not in order]
    table = table[order + extra]
    table["error"] = table["error"].fillna("").astype(str)
    table = table.sort_values(["record", "component", "design_index"], kind="mergesort").reset_index(drop=True)
    return table


def write_table_atomically(table, path, *, keyed: bool = False) -> None:
    """CSV or Parquet (by suffix) through a temporary file and a rename: never half a file.

    With ``keyed``, the table's content key is written beside it (:func:`table_key_path`)
    so that a rerun may reuse its rows.
    """
    path = Path(path)
    with atomic_path(path) as tmp:
        if path.suffix.lower() == ".parquet":
            out = table.copy()
            for column in out.columns:
                if out[column].dtype == object:
                    values = out[column].dropna()
                    if len(values) and all(isinstance(v, str) for v in values):
                        out[column] = out[column].astype("string")
                    elif len(values) and all(isinstance(v, bool) for v in values):
                        out[column] = out[column].astype("boolean")
                    elif len(values) and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
                        out[column] = out[column].astype(float)
                    else:
                        out[column] = out[column].astype("string")
            out.to_parquet(tmp, index=False)
        else:
            table.to_csv(tmp, index=False)
        signature = content_key(tmp.read_bytes()) if keyed else ""
    if keyed:
        write_text_atomically(table_key_path(path), signature + "\n")


def comparable(table):
    """The table without its timing columns (what must be equal between two runs)."""
    return table.drop(columns=[c for c in TIMING_COLUMNS if c in table.columns])
