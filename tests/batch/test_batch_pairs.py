"""Batch on pairs: a file with two horizontal components is analysed as a pair by default; rows state the model."""

from __future__ import annotations

import pytest

from isolator.batch import record_components, run_batch
from isolator.solver.planar import simulate_motion

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
