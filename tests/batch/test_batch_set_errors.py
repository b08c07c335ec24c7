"""A batch row of a station's set (X with its Y file) names the set's files in its error, or the one file at fault.

On main (session 14) the ``error`` column named only the X file: an engine's refusal on the pair read
``designs.toml[design 0] under X: …`` (the ``record_files`` column had both), and a Y file its reader refused read
``X: Y: …``, blaming X first.  The engine's refusal here is the 2-D building's sub-step bound (a slab of 1e-4 kg
under 1.1e6 kg of floors), reached before its kernel loads, so each row costs a read of the two PTS files.
"""

from __future__ import annotations

from _model_designs import BUILDING, designs_file_text

from isolator.batch import ReadOptions, run_batch
from isolator.batch.worker import row_error
from isolator.errors import SolverError


def _pts_set(records_dir, tmp_path):
    folder = tmp_path / "pts"
    folder.mkdir()
    source = records_dir / "pairs" / "superstitionhills1987_PTS"
    x, y = (folder / f"RSN723_SUPER.B_B-PTS{angle}.AT2" for angle in (225, 315))
    for path in (x, y):
        path.write_bytes((source / path.name).read_bytes())
    return folder, x, y


def test_an_engine_refusal_on_a_set_names_the_design_and_both_files(records_dir, tmp_path):
    folder, x, y = _pts_set(records_dir, tmp_path)
    designs = tmp_path / "designs.toml"
    designs.write_text(designs_file_text(BUILDING.replace("mass_kg = 1.6e6", "mass_kg = 1100000.0001", 1)))
    result = run_batch([str(folder)], designs, tmp_path / "t.csv", jobs=1, options=ReadOptions(trim=True))
    assert result.n_failed == 1
    row = result.table.iloc[0]
    assert row["component"] == "pair" and row["record_files"] == f"{x.name}; {y.name}"
    assert row["error"].startswith(f"{designs}[design 0] under {x} + {y}: the building's fastest rate "), row["error"]
    assert "sub-steps per sample interval of 0.01 s (at most 5000)" in row["error"]


def test_a_partner_file_its_reader_refuses_is_the_one_named(records_dir, tmp_path):
    folder, x, y = _pts_set(records_dir, tmp_path)
    lines = y.read_text().splitlines()
    lines[8] = lines[8].replace("E", "Q", 1)  # one value of the Y file is no number
    y.write_text("\n".join(lines) + "\n")
    designs = tmp_path / "designs.toml"
    designs.write_text('[[design]]\nname = "FP"\nmass_kg = 1000.0\nradius_m = 2.0\nmu_static = 0.05\n')
    result = run_batch([str(folder)], designs, tmp_path / "t.csv", jobs=1, options=ReadOptions(trim=True))
    error = result.table.iloc[0]["error"]
    assert result.n_failed == 1 and error.startswith(f"{y}: "), error
    assert str(x) not in error  # main: "X: Y: PEER AT2: non-numeric value … on line 9"


def test_row_error_names_every_file_of_a_set():
    """The lines of the other failures: X alone as before; X + Y + Z for a set."""
    refusal = SolverError("the step size fell below 1e-13")
    assert row_error(refusal, "x.AT2", "d.toml") == "d.toml under x.AT2: the step size fell below 1e-13"
    assert row_error(refusal, "x.AT2", "d.toml", ("y.AT2", "z.AT2")) == (
        "d.toml under x.AT2 + y.AT2 + z.AT2: the step size fell below 1e-13")
    assert row_error(KeyError("a defect"), "x.AT2", "d.toml", ("y.AT2",)) == (
        "d.toml under x.AT2 + y.AT2: internal error in isolator (please report it with this record and design)")
    from isolator.solver.record import RecordInputError

    # a record's error that names no file: the set's files own it
    assert row_error(RecordInputError("a record of zeros"), "x.AT2", None, ("y.AT2",)) == (
        "x.AT2 + y.AT2: a record of zeros")
    assert row_error(RecordInputError("x.AT2: a record of zeros"), "x.AT2", None) == "x.AT2: a record of zeros"
