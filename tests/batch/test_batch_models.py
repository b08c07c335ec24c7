"""Batch columns of the models with more than one number per quantity: the building above the isolators
(per story, per floor, per bearing) and a triple friction pendulum (per surface), and the row schema.

The columns are compared with :func:`isolator.analysis.analyse` of the same design under the same scaled
record (a real record: Northridge NWH360 scaled to 1.5 g drives the triple pendulum through regimes I-V to
its ultimate displacement and lifts the building's bearings off).
"""

from __future__ import annotations

import math
import sys
import tomllib
from pathlib import Path

import pandas as pd
import pytest

from isolator.batch import ReadOptions, comparable, run_batch
from isolator.batch.store import COLUMNS, LIST_COLUMNS, MODEL_COLUMNS, ROW_SCHEMA, PartStore, is_column

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _model_designs import BUILDING, RECORD, RIGID_BLOCK, SCALE_G, TRIPLE, designs_file_text  # noqa: E402
from test_batch import read  # noqa: E402
from test_batch_hardening import suite  # noqa: E402, F401 - the two synthetic records and two designs

MODEL_DESIGNS = designs_file_text(RIGID_BLOCK, BUILDING, TRIPLE)


@pytest.fixture(autouse=True)
def _private_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ISOLATOR_CACHE_DIR", str(tmp_path / "cache"))
    from isolator import atomic

    monkeypatch.setattr(atomic, "_SECRET", None)


@pytest.fixture(scope="module")
def model_batch(records_dir, tmp_path_factory):
    """(table, analyses by design index) of the three designs under NWH360 scaled to 1.5 g."""
    from isolator.analysis import analyse
    from isolator.design import Design
    from isolator.motion import read_ground_motion
    from isolator.units import STANDARD_GRAVITY

    folder = tmp_path_factory.mktemp("models")
    designs = folder / "designs.toml"
    designs.write_text(MODEL_DESIGNS)
    record = records_dir / RECORD
    result = run_batch([str(record)], designs, folder / "t.csv", options=ReadOptions(scale_to_pga_g=SCALE_G),
                       jobs=1)
    assert result.n_failed == 0, list(result.table["error"])
    motion = read_ground_motion(record).scaled_to_pga(SCALE_G * STANDARD_GRAVITY)
    analyses = [analyse(Design.from_mapping(mapping), motion, harmonic=False)
                for mapping in tomllib.loads(MODEL_DESIGNS)["design"]]
    return read(folder / "t.csv"), analyses


def test_building_columns_equal_the_analysis(model_batch):
    table, analyses = model_batch
    flat = analyses[1].flat()
    row = table.iloc[1]
    assert row["model"] == "1d-building"
    for key in ("story_drift_m", "story_drift_ratio", "floor_peak_acceleration_m_s2", "bearing_axial_load_max_N",
                "bearing_axial_load_min_N"):
        values = [row[f"{key}_{i}"] for i in range(1, len(flat[key]) + 1)]
        assert values == pytest.approx(flat[key], rel=1e-15, abs=0.0), key
        assert f"{key}_{len(flat[key]) + 1}" not in table.columns  # as many columns as the longest list
    assert row["superstructure_shear_coefficient"] == pytest.approx(flat["superstructure_shear_coefficient"],
                                                                    rel=1e-15)
    # the batch's base shear (engineering: M × peak transmitted acceleration / W) is the building's peak isolator
    # force over W: one number under one name
    assert row["base_shear_coefficient"] == pytest.approx(flat["base_shear_coefficient"], rel=1e-12)
    assert row["n_bearings_uplifted"] == flat["n_bearings_uplifted"] == sum(
        load < 0 for load in flat["bearing_axial_load_min_N"])
    assert flat["n_bearings_uplifted"] > 0  # the narrow layout lifts bearings off: the uplift path is exercised
    assert row["energy_strain_final_J_per_kg"] == pytest.approx(flat["energy_strain_final_J_per_kg"], rel=1e-15,
                                                                abs=1e-300)
    # the rigid block's row leaves the building's and the bearing's columns empty
    rigid = table.iloc[0]
    assert rigid["model"] == "1d-exact"
    assert all(pd.isna(rigid[column]) for column in table.columns
               if column.startswith(LIST_COLUMNS) or column in MODEL_COLUMNS)


def test_triple_pendulum_columns_equal_the_analysis(model_batch):
    table, analyses = model_batch
    flat = analyses[2].flat()
    row = table.iloc[2]
    assert row["model"] == "1d-multisurface" and row["bearing_type"] == "triple"
    surfaces = [row[f"surface_peak_displacement_m_{i}"] for i in range(1, 5)]
    assert surfaces == pytest.approx(flat["surface_peak_displacement_m"], rel=1e-15, abs=0.0)
    assert "surface_peak_displacement_m_5" not in table.columns
    assert row["n_rim_contacts"] == flat["n_rim_contacts"] > 0
    assert bool(row["ultimate_displacement_reached"]) is flat["ultimate_displacement_reached"] is True
    assert row["regimes_reached"] == "I, II, III, IV, V" == ", ".join(flat["regimes"])
    for key in ("ultimate_displacement_m", "impact_impulse_m_s", "max_impact_velocity_m_s", "energy_impact_J_per_kg",
                "peak_force_per_weight"):
        assert row[key] == pytest.approx(flat[key], rel=1e-15), key
    # every surface's peak on the surface is within its capacity d_i (the rims hold)
    capacities = [s.displacement_capacity_m for s in analyses[2].design.bearing.surfaces]
    assert all(peak <= cap * (1 + 1e-12) for peak, cap in zip(surfaces, capacities, strict=True))
    assert row["peak_displacement_m"] == pytest.approx(flat["ultimate_displacement_m"], rel=1e-12)


def test_columns_are_defined_once_and_numbered_columns_are_known():
    assert len(COLUMNS) == len(set(COLUMNS)) and set(MODEL_COLUMNS) <= set(COLUMNS)
    assert not set(LIST_COLUMNS) & set(COLUMNS)
    assert is_column("story_drift_ratio_12") and is_column("surface_peak_displacement_m_4")
    assert not is_column("story_drift_ratio_0") and not is_column("story_drift_ratio_x") and not is_column("injected")


def _at_another_schema(monkeypatch, schema: str) -> None:
    """Make this process's batch write rows (and their keys) as an isolator of row schema ``schema`` would."""
    import importlib

    for name in ("plan", "worker", "run", "store"):  # the modules (``isolator.batch.plan`` is also a function)
        monkeypatch.setattr(importlib.import_module(f"isolator.batch.{name}"), "ROW_SCHEMA", schema)


@pytest.mark.parametrize("where", ["table", "parts"])
def test_rows_stored_under_another_schema_are_recomputed_with_a_note(suite, tmp_path, where):  # noqa: F811
    records, designs = suite
    out = tmp_path / "t.csv"
    with pytest.MonkeyPatch.context() as patch:
        _at_another_schema(patch, "1:00000000")
        if where == "parts":  # an interrupted run of the older isolator: its parts, no table
            patch.setattr(PartStore, "remove", lambda self: None)
        old = run_batch([str(records)], designs, out, jobs=1)
        assert set(old.table["row_schema"]) == {"1:00000000"}
    if where == "parts":
        out.unlink()
    # the same row under the current schema has another key: nothing is reused, the rows are recomputed
    result = run_batch([str(records)], designs, out, jobs=1)
    assert result.n_resumed == 0 and result.n_rows == 4
    assert any(note.startswith("4 stored row(s)") and "another schema" in note and ROW_SCHEMA in note
               for note in result.notes), result.notes
    table = read(out)
    assert set(table["row_schema"]) == {ROW_SCHEMA}
    run_batch([str(records)], designs, tmp_path / "straight.csv", jobs=1)
    pd.testing.assert_frame_equal(comparable(table), comparable(read(tmp_path / "straight.csv")))
    # and a rerun under the current schema reuses every row, without a note
    again = run_batch([str(records)], designs, out, jobs=1)
    assert again.n_resumed == 4 and not any("schema" in note for note in again.notes)


def test_model_columns_survive_a_resume(records_dir, tmp_path):
    """A finished table with numbered columns is reused as it is (its columns are known on reading)."""
    designs = tmp_path / "designs.toml"
    designs.write_text(MODEL_DESIGNS)
    record = records_dir / RECORD
    out = tmp_path / "t.csv"
    run_batch([str(record)], designs, out, options=ReadOptions(scale_to_pga_g=SCALE_G), jobs=1)
    first = read(out)
    again = run_batch([str(record)], designs, out, options=ReadOptions(scale_to_pga_g=SCALE_G), jobs=1)
    assert again.n_resumed == 3
    pd.testing.assert_frame_equal(read(out), first)
    assert first.loc[1, "story_drift_ratio_3"] > 0 and math.isnan(first.loc[0, "story_drift_ratio_3"])
