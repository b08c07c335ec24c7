"""Batch on pairs: a file with two horizontal components is analysed as a pair by default; rows state the model."""

from __future__ import annotations

import pytest

from isolator.batch import record_components, run_batch
from isolator.solver.models import simulate_motion

DESIGNS = """
[[design]]
name = "FP"
mass_kg = 1000.0
radius_m = 2.0
mu_static = 0.05
displacement_capacity_m = 0.15

[[design]]
name = "FP PTFE"
mass_kg = 1000.0
radius_m = 2.0
mu_static = 0.06
mu_slow = 0.03
mu_fast = 0.08
rate_s_per_m = 20.0
"""


def test_planning_pairs(records_dir):
    v2 = str(records_dir / "other" / "ce89486SampleInput.v2")
    knet = records_dir / "pairs" / "iwatemiyagi2008_AOM017"
    assert record_components(v2, None) == ["pair"]
    assert record_components(v2, "all") == ["all"]
    assert record_components(v2, "180") == ["180"]
    assert len(record_components(v2, "all-horizontal")) == 2
    assert record_components(str(records_dir / "at2" / "IELC180.AT2"), None) == [None]
    # a K-NET set: one pair, from the first file of the set only
    assert [record_components(str(knet / f"AOM0170806140843.{s}"), None) for s in ("NS", "EW", "UD")] == \
        [["pair"], [], []]


def test_rows_state_the_model_and_match_the_engine(records_dir, tmp_path):
    designs = tmp_path / "designs.toml"
    designs.write_text(DESIGNS)
    v2 = records_dir / "other" / "ce89486SampleInput.v2"
    at2 = records_dir / "at2" / "IELC180.AT2"
    result = run_batch([str(v2), str(at2)], designs, tmp_path / "t.csv", jobs=1)
    table = result.table.set_index(["component", "design_name"])
    assert result.n_failed == 0 and len(table) == 4
    assert table.loc[("pair", "FP"), "model"] == "2d"
    assert table.loc[("pair", "FP PTFE"), "model"] == "2d+mu(v)"
    assert table.loc[("180", "FP"), "model"] == "1d-exact"
    assert table.loc[("180", "FP PTFE"), "model"] == "2d+mu(v)"
    assert all(isinstance(reason, str) and reason for reason in table["model_reason"])
    row = table.loc[("pair", "FP")]
    assert (row["component_x"], row["component_y"]) == ("HN1 (180)", "HN2 (90)")
    from isolator.motion import read_ground_motion_pair

    pair = read_ground_motion_pair(v2)
    direct = simulate_motion(pair.x.acceleration_m_s2, pair.y.acceleration_m_s2, dt_s=pair.dt_s, mu_static=0.05,
                             radius_m=2.0)
    assert row["peak_displacement_m"] == pytest.approx(direct.peak_displacement_m, rel=1e-12)
    assert row["displacement_demand_ratio"] == pytest.approx(direct.peak_displacement_m / 0.15, rel=1e-12)
    assert row["residual_displacement_y_m"] == pytest.approx(direct.residual_displacement_y_m, rel=1e-12)
    assert table.loc[("180", "FP"), "residual_displacement_y_m"] == 0.0
    one = table.loc[("180", "FP")]
    assert one["displacement_demand_ratio"] == pytest.approx(one["peak_displacement_m"] / 0.15, rel=1e-12)


def test_a_pair_whose_components_differ_is_a_row_error(records_dir, tmp_path):
    designs = tmp_path / "designs.toml"
    designs.write_text(DESIGNS)
    result = run_batch([str(records_dir / "pairs" / "lahabra2014_WLT" / "CIWLT.V2")], designs, tmp_path / "t.csv",
                       jobs=1)
    assert result.n_failed == 2
    assert all("different lengths" in error and "15050" in error for error in result.table["error"])


def test_trim_repairs_the_pair_and_is_recorded(records_dir, tmp_path):
    from isolator.batch import ReadOptions

    designs = tmp_path / "designs.toml"
    designs.write_text(DESIGNS)
    path = str(records_dir / "pairs" / "lahabra2014_WLT" / "CIWLT.V2")
    result = run_batch([path], designs, tmp_path / "t.csv", jobs=1, options=ReadOptions(trim=True))
    assert result.n_failed == 0
    row = result.table.iloc[0]
    assert row["record_npts"] == 15029 and row["record_processing"] == "trim_to_common_window"  # the shortest, HN2
    # the row key changes with --trim: a batch without it is not resumed into one with it
    assert ReadOptions(trim=True).fingerprint() != ReadOptions().fingerprint()


# ---- pairs made of two one-component files (PEER AT2: one file per component) ----------------

def _pts(records_dir):
    folder = records_dir / "pairs" / "superstitionhills1987_PTS"
    return folder / "RSN723_SUPER.B_B-PTS225.AT2", folder / "RSN723_SUPER.B_B-PTS315.AT2"


def _pts_copy(records_dir, tmp_path):
    """(designs file, a folder holding copies of the two PTS files, X, Y) in tmp_path."""
    designs = tmp_path / "designs.toml"
    designs.write_text(DESIGNS)
    x, y = _pts(records_dir)
    folder = tmp_path / "pts"
    folder.mkdir()
    for path in (x, y):
        (folder / path.name).write_bytes(path.read_bytes())
    return designs, folder, x, y


def _scaled_values(at2_lines, factor):
    """The value lines of an AT2 file (after its four header lines), every sample times ``factor``."""
    return [" ".join(f"{factor * float(v):.7E}" for v in line.split()) for line in at2_lines[4:]]


def test_station_sets_pair_the_two_horizontals_of_one_station(records_dir, tmp_path):
    from isolator.batch import station_sets

    x, y = _pts(records_dir)
    assert station_sets([str(x), str(y)], None) == {str(x): (str(y),)}
    assert station_sets([str(y), str(x)], "all") == {str(x): (str(y),)}  # X is the first by name
    assert station_sets([str(x), str(y)], "225") == {}  # one component asked: no set
    assert station_sets([str(x), str(y)], "all-horizontal") == {}
    assert station_sets([str(x)], None) == {}  # one file of the station: analysed alone
    # the same component twice (one motion in two files) is not a pair
    twin = tmp_path / "twin" / "copy_of_225.AT2"
    twin.parent.mkdir()
    twin.write_bytes(x.read_bytes())
    assert station_sets([str(x), str(twin)], None) == {}
    # two files of one station in different folders are not a set
    other = tmp_path / "other" / y.name
    other.parent.mkdir()
    other.write_bytes(y.read_bytes())
    assert station_sets([str(x), str(other)], None) == {}
    # different stations and events (the shared at2 folder: TAK000 twice, under two event names)
    at2 = sorted(str(p) for p in (records_dir / "at2").iterdir())
    assert station_sets(at2, None) == {}


def test_batch_analyses_two_files_of_one_station_as_a_pair(records_dir, tmp_path):
    from isolator.batch import ReadOptions
    from isolator.motion import read_ground_motion_pair

    designs = tmp_path / "designs.toml"
    designs.write_text(DESIGNS)
    x, y = _pts(records_dir)
    # the components differ in length (2235 and 2231 samples): one error row per design, naming both
    result = run_batch([str(x.parent)], designs, tmp_path / "t.csv", jobs=1)
    assert result.n_failed == 2 and set(result.table["component"]) == {"pair"}
    assert all("different lengths" in e and y.name in e for e in result.table["error"])
    # with --trim: one 2-D row per design, on the pair read as `simulate X --pair Y --trim` reads it
    result = run_batch([str(y), str(x)], designs, tmp_path / "t2.csv", jobs=1, options=ReadOptions(trim=True))
    assert result.n_failed == 0 and len(result.table) == 2
    row = result.table.set_index("design_name").loc["FP"]
    # its 0.15 m capacity is reached: rerun with the rim in the plane (issue 23)
    assert row["record"] == str(x) and row["component"] == "pair" and row["model"] == "2d+rim"
    assert row["record_files"] == f"{x.name}; {y.name}"
    assert (row["component_x"], row["component_y"]) == ("225", "315") and row["record_npts"] == 2231
    pair = read_ground_motion_pair(x, y, trim=True)
    from isolator.design import Design

    design = Design.from_mapping({"name": "FP", "mass_kg": 1000.0, "radius_m": 2.0, "mu_static": 0.05,
                                  "displacement_capacity_m": 0.15}, source="designs.toml")
    direct = simulate_motion(pair.x.acceleration_m_s2, pair.y.acceleration_m_s2, dt_s=pair.dt_s, mu_static=0.05,
                             radius_m=2.0, design=design)
    assert direct.model == "2d+rim" and direct.peak_displacement_m == pytest.approx(0.15, rel=1e-12)
    assert row["peak_displacement_m"] == pytest.approx(direct.peak_displacement_m, rel=1e-12)
    assert row["residual_displacement_x_m"] == pytest.approx(direct.residual_displacement_x_m, rel=1e-12)
    # 'all' needs a vertical: the station has none among the records given
    result = run_batch([str(x), str(y)], designs, tmp_path / "t3.csv", jobs=1, component="all",
                       options=ReadOptions(trim=True))
    assert result.n_failed == 2
    assert all("no vertical component" in e and "'all' needs one" in e for e in result.table["error"])
    # one component asked: each file alone, 1-D
    result = run_batch([str(x), str(y)], designs, tmp_path / "t4.csv", jobs=1, component="all-horizontal")
    assert sorted(result.table["component"].astype(str)) == ["225", "225", "315", "315"]


def test_a_changed_partner_file_recomputes_the_pair_rows(records_dir, tmp_path):
    from isolator.batch import ReadOptions

    designs, folder, x, y = _pts_copy(records_dir, tmp_path)
    options = ReadOptions(trim=True)
    first = run_batch([str(folder)], designs, tmp_path / "t.csv", jobs=1, options=options)
    again = run_batch([str(folder)], designs, tmp_path / "t.csv", jobs=1, options=options)
    assert again.n_resumed == 2
    # the Y file changes (its samples scaled by 2, in the header's units): the pair's rows are recomputed
    lines = (folder / y.name).read_text().splitlines()
    scaled = lines[:4] + _scaled_values(lines, 2.0)
    (folder / y.name).write_text("\n".join(scaled) + "\n")
    changed = run_batch([str(folder)], designs, tmp_path / "t.csv", jobs=1, options=options)
    assert changed.n_resumed == 0
    assert set(changed.table["row_key"]).isdisjoint(first.table["row_key"])
    assert changed.table["pga_y_m_s2"].iloc[0] == pytest.approx(2 * first.table["pga_y_m_s2"].iloc[0], rel=1e-6)


def test_a_station_set_with_its_vertical_file(records_dir, tmp_path):
    """Three AT2 files of one station (the vertical made here from the 315 file: label UP, half its
    samples): 'pair' takes the horizontals, 'all' adds the vertical (the 2-D engine with n(t))."""
    from isolator.batch import ReadOptions, station_sets

    designs, folder, x, y = _pts_copy(records_dir, tmp_path)
    lines = y.read_text().splitlines()
    title = lines[1].rsplit(",", 1)[0] + ", UP"
    values = _scaled_values(lines, 0.5)
    (folder / "RSN723_SUPER.B_B-PTSUP.AT2").write_text("\n".join([lines[0], title, *lines[2:4], *values]) + "\n")
    files = sorted(str(p) for p in folder.iterdir())
    sets = station_sets(files, "all")
    assert sets == {str(folder / x.name): (str(folder / y.name), str(folder / "RSN723_SUPER.B_B-PTSUP.AT2"))}
    options = ReadOptions(trim=True)
    result = run_batch([str(folder)], designs, tmp_path / "t.csv", jobs=1, component="all", options=options)
    assert result.n_failed == 0 and len(result.table) == 2
    row = result.table.set_index("design_name").loc["FP"]
    assert row["model"] == "2d+vertical+rim" and row["component_z"] == "UP"  # past its 0.15 m capacity: the rim
    assert row["record_files"] == f"{x.name}; {y.name}; RSN723_SUPER.B_B-PTSUP.AT2"
    pair = result.table.set_index("design_name")
    plain = run_batch([str(folder)], designs, tmp_path / "t2.csv", jobs=1, options=options)
    assert set(plain.table["model"]) == {"2d+rim", "2d+mu(v)"}  # the default: the horizontals only
    # both held at the rim (peak 0.15 m): the vertical shows in the residual
    assert pair.loc["FP", "residual_displacement_m"] != plain.table.set_index("design_name").loc[
        "FP", "residual_displacement_m"]
