"""The report's pages of the building above the isolators and of a triple pendulum: what they draw is the
analysis' own numbers (the drift profile is ``story_drift_ratio``; the backbone's points are
``Bearing.backbone()``'s transition points; the loop is the response's samples), on a real record
(Northridge NWH360 scaled to 1.5 g: the building's bearings lift off, the triple pendulum passes regimes
I-V to its ultimate displacement)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from _model_designs import BUILDING, RECORD, SCALE_G, TRIPLE, designs_file_text
from typer.testing import CliRunner

from isolator.analysis import analyse
from isolator.cli import app
from isolator.design import Design
from isolator.motion import read_ground_motion
from isolator.report.bearing_page import LOOP_LABEL, POINTS_LABEL, bearing_page, surface_rows
from isolator.report.building_page import building_page, drift_limit
from isolator.report.layout import fmt
from isolator.units import STANDARD_GRAVITY

pypdf = pytest.importorskip("pypdf")
runner = CliRunner()


@pytest.fixture(autouse=True)
def _cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ISOLATOR_CACHE_DIR", str(tmp_path / "cache"))


@pytest.fixture(scope="module")
def motion(records_dir):
    return read_ground_motion(records_dir / RECORD).scaled_to_pga(SCALE_G * STANDARD_GRAVITY)


def _design(tmp_path_factory, text: str, name: str):
    path = tmp_path_factory.mktemp("designs") / name
    path.write_text(text)
    return path, Design.from_toml(path)


@pytest.fixture(scope="module")
def building(tmp_path_factory, motion):
    path, design = _design(tmp_path_factory, BUILDING, "building.toml")
    analysis = analyse(design, motion, harmonic=False)
    return path, analysis, analysis.to_dict()


@pytest.fixture(scope="module")
def triple(tmp_path_factory, motion):
    path, design = _design(tmp_path_factory, TRIPLE, "tfp.toml")
    analysis = analyse(design, motion, harmonic=False)
    return path, analysis, analysis.to_dict()


def _axes(fig, title: str):
    return next(ax for ax in fig.axes if ax.get_title() == title)


def _line(ax, label: str):
    return next(line for line in ax.get_lines() if str(line.get_label()).startswith(label))


def _texts(fig) -> str:
    return " ".join(text.get_text() for text in fig.texts)


def test_building_page_draws_the_analysis_profiles_and_loads(building):
    _, analysis, numbers = building
    fig = building_page(5, "label", numbers, analysis.response)
    drift = _axes(fig, "Story drift ratio profile")
    x, y = _line(drift, "story drift ratio (peak)").get_data()
    np.testing.assert_array_equal(x, numbers["story_drift_ratio"])
    np.testing.assert_allclose(y, [2.0, 5.75, 9.25], rtol=1e-15)  # mid-heights of stories 4, 3.5, 3.5 m
    limit = _line(drift, "limit")
    assert drift_limit()["ratio"] == 0.020 and list(limit.get_xdata()) == [0.020, 0.020]
    assert "drift_limit_rha [U]" in limit.get_label() and "17.6.4.4" in limit.get_label()
    acc = _axes(fig, "Floor acceleration profile")
    x, y = _line(acc, "floor peak absolute acceleration").get_data()
    np.testing.assert_allclose(x * STANDARD_GRAVITY, numbers["floor_peak_acceleration_m_s2"], rtol=1e-15)
    np.testing.assert_allclose(y, [4.0, 7.5, 11.0], rtol=1e-15)
    # the bearings: one bar per bearing from its minimum to its maximum load, tension flagged
    bars = next(ax for ax in fig.axes if ax.get_ylabel().startswith("axial load")).patches
    np.testing.assert_allclose([bar.get_y() * 1e3 for bar in bars], numbers["bearing_axial_load_min_N"], rtol=1e-12)
    np.testing.assert_allclose([(bar.get_y() + bar.get_height()) * 1e3 for bar in bars],
                               numbers["bearing_axial_load_max_N"], rtol=1e-12)
    flagged = [t for ax in fig.axes for t in ax.texts if t.get_text() == "uplift"]
    assert len(flagged) == numbers["n_bearings_uplifted"] > 0
    text = _texts(fig)
    assert fmt(numbers["superstructure_shear_coefficient"]) in text and fmt(numbers["base_shear_coefficient"]) in text
    assert f"{numbers['n_bearings_uplifted']} of 4 bearing(s) go into tension" in text
    for ratio in numbers["story_drift_ratio"]:
        assert fmt(ratio, 3) in text


def test_building_report_has_the_building_page(records_dir, building, tmp_path):
    path, analysis, numbers = building
    out = tmp_path / "building.pdf"
    result = runner.invoke(app, ["report", str(records_dir / RECORD), "-d", str(path), "--scale-to-pga",
                                 str(SCALE_G), "-o", str(out), "--map-resolution", "8"])
    assert result.exit_code == 0, result.output
    assert "(5 pages)" in result.stdout
    written = json.loads(out.with_suffix(".json").read_text())
    assert written["story_drift_ratio"] == numbers["story_drift_ratio"]
    assert written["bearing_axial_load_min_N"] == numbers["bearing_axial_load_min_N"]
    pages = pypdf.PdfReader(str(out)).pages
    assert len(pages) == 5
    last = " ".join(pages[4].extract_text().split())
    assert "The building above the isolators" in last and "drift_limit_rha" in last


def test_report_set_moves_the_drift_limit_and_prints_it(records_dir, building, tmp_path):
    """``report --set drift_limit_rha=0.004``: the JSON's ``parameters`` carry it (source "set"), the page draws the
    limit there, its "/ limit" column divides by it and the page says it was set (default 0.020)."""
    from isolator.report.summary import report_parameters

    path, analysis, numbers = building
    out = tmp_path / "building.pdf"
    result = runner.invoke(app, ["report", str(records_dir / RECORD), "-d", str(path), "--scale-to-pga",
                                 str(SCALE_G), "-o", str(out), "--map-resolution", "8", "--no-pdf",
                                 "--set", "drift_limit_rha=0.004"])
    assert result.exit_code == 0, result.output
    written = json.loads(out.with_suffix(".json").read_text())
    row = next(r for r in written["parameters"] if r["name"] == "drift_limit_rha")
    assert row["value"] == 0.004 and row["default"] == 0.02 and row["source"] == "set" and row["mark"] == "U"
    assert all("source" not in r for r in written["parameters"] if r["name"] != "drift_limit_rha")
    fig = building_page(5, "label", {**numbers, "parameters": report_parameters({"drift_limit_rha": "0.004"})},
                        analysis.response)
    limit = _line(_axes(fig, "Story drift ratio profile"), "limit")
    assert list(limit.get_xdata()) == [0.004, 0.004]
    text = _texts(fig)
    assert "set to 0.004 (--set; default 0.02)" in text
    for ratio in numbers["story_drift_ratio"]:
        assert fmt(ratio / 0.004, 3) in text


def test_triple_pendulum_page_draws_the_backbone_and_the_loop(triple):
    _, analysis, numbers = triple
    response, backbone = analysis.response, analysis.design.bearing.backbone()
    fig = bearing_page(4, "label", numbers, response, analysis.design.mass_kg)
    ax = _axes(fig, "Backbone and force-displacement loop")
    x, r = _line(ax, POINTS_LABEL).get_data()
    np.testing.assert_array_equal(x, backbone.displacement_m)
    np.testing.assert_array_equal(r, backbone.force_per_weight)
    np.testing.assert_allclose(x, [0.0, 0.024, 0.120, 0.752, 0.848, 0.900], atol=1e-12)  # Fenz & Constantinou
    assert [t.get_text() for t in ax.texts] == ["I", "II", "III", "IV", "V", "ultimate"]
    # the loop: samples of the response (decimated to the page, extremes kept)
    lx, lr = _line(ax, LOOP_LABEL).get_data()
    pairs = set(zip(response.displacement_m, response.force_per_weight, strict=True))
    assert all((a, b) in pairs for a, b in zip(lx, lr, strict=True))
    assert np.max(np.abs(lx)) == np.max(np.abs(response.displacement_m))
    assert np.max(np.abs(lr)) == np.max(np.abs(response.force_per_weight))
    # the surfaces against their capacities, the regimes and the ultimate with its impulse
    rows = surface_rows(numbers, numbers["design"]["bearing"])
    assert [row[6] for row in rows] == numbers["surface_peak_displacement_m"]
    assert [row[4] for row in rows] == [0.4, 0.05, 0.05, 0.4]
    text = _texts(fig)
    assert numbers["ultimate_displacement_reached"] and "ULTIMATE DISPLACEMENT REACHED" in text
    assert f"impulse {fmt(analysis.design.mass_kg * numbers['impact_impulse_m_s'])} N·s" in text
    assert f"Rim contacts: {numbers['n_rim_contacts']}" in text and numbers["n_rim_contacts"] > 0
    for name, time in numbers["regimes"].items():
        assert f"{name} at {fmt(time, 4)} s" in text
    assert list(numbers["regimes"]) == ["I", "II", "III", "IV", "V"]


def test_double_pendulum_page_names_the_sliding_surfaces(motion):
    design = Design.from_mapping({"name": "DCFP", "mass_kg": 1.0e5, "bearing": {"type": "double", "surface": [
        {"radius_m": 2.2, "mu": 0.04, "displacement_capacity_m": 0.3},
        {"radius_m": 2.2, "mu": 0.07, "displacement_capacity_m": 0.3}]}})
    analysis = analyse(design, motion.scaled_to_pga(0.4 * STANDARD_GRAVITY), harmonic=False)
    numbers = analysis.to_dict()
    fig = bearing_page(4, "label", numbers, analysis.response)
    ax = _axes(fig, "Backbone and force-displacement loop")
    backbone = design.bearing.backbone()
    np.testing.assert_array_equal(_line(ax, POINTS_LABEL).get_xdata(), backbone.displacement_m)
    assert [t.get_text() for t in ax.texts][: len(backbone.regimes)] == [f"{n} slide" for n in backbone.regimes]
    assert "Sliding surfaces (first time)" in _texts(fig)
    # the console's line: inside the rims at 0.4 g
    from isolator.cli.report import ultimate_rows

    assert not numbers["ultimate_displacement_reached"]
    assert ultimate_rows(numbers) == [("ultimate displacement", "not reached",
                                       f"({numbers['n_rim_contacts']} rim contact(s))")]
    assert ultimate_rows({**numbers, "rim_modelled": False}) == [("ultimate displacement",
                                                                  "not reached (no rim modelled)", "")]


def test_triple_report_scaled_to_a_pga_on_one_component(records_dir, triple, tmp_path):
    """`--scale-to-pga` on the report of a double or triple bearing (one component): the scaled record's numbers."""
    from isolator.solver.multisurface import simulate_bearing

    path, analysis, numbers = triple
    out = tmp_path / "tfp.pdf"
    result = runner.invoke(app, ["report", str(records_dir / RECORD), "-d", str(path), "--scale-to-pga",
                                 str(SCALE_G), "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "(4 pages)" in result.stdout
    written = json.loads(out.with_suffix(".json").read_text())
    ultimate = next(line for line in result.stdout.splitlines() if line.startswith("ultimate displacement"))
    impulse = analysis.design.mass_kg * written["impact_impulse_m_s"]
    assert written["ultimate_displacement_reached"] and ultimate.split()[2] == "REACHED", ultimate
    assert f"impulse {impulse:.4g} N·s; {written['n_rim_contacts']} rim contact(s)" in ultimate, ultimate
    motion = read_ground_motion(records_dir / RECORD).scaled_to_pga(SCALE_G * STANDARD_GRAVITY)
    direct = simulate_bearing(motion.acceleration_m_s2, motion.dt_s, bearing=analysis.design.bearing)
    assert written["peak_displacement_m"] == pytest.approx(direct.peak_displacement_m, rel=1e-12)
    assert written["surface_peak_displacement_m"] == numbers["surface_peak_displacement_m"]
    assert written["record"]["scaling"].startswith("Record scaled to the design PGA 1.5 g")
    assert written["record"]["intensity_measures"]["pga_m_s2"] == pytest.approx(SCALE_G * STANDARD_GRAVITY, rel=1e-12)
    pages = pypdf.PdfReader(str(out)).pages
    assert len(pages) == 4
    last = " ".join(pages[3].extract_text().split())
    assert "backbone" in last and "ULTIMATE DISPLACEMENT REACHED" in last


def test_single_pendulum_rerun_with_its_rim_gets_the_page(motion, tmp_path, records_dir):
    """A single pendulum whose peak reaches its displacement capacity is rerun with the rim (1d-multisurface):
    the page draws its own bearing (no [bearing] table in the design) and states the impacts."""
    design_path = tmp_path / "fp.toml"
    design_path.write_text('name = "FP rim"\nmass_kg = 1.0e5\nradius_m = 2.0\nmu_static = 0.06\n'
                           'mu_kinetic = 0.05\ndisplacement_capacity_m = 0.6\n')
    analysis = analyse(Design.from_toml(design_path), motion, harmonic=False)
    numbers = analysis.to_dict()
    assert analysis.model == "1d-multisurface" and numbers["design"]["bearing"] is None
    fig = bearing_page(4, "label", numbers, analysis.response)
    ax = _axes(fig, "Backbone and force-displacement loop")
    backbone = analysis.response.bearing.backbone()
    np.testing.assert_array_equal(_line(ax, POINTS_LABEL).get_xdata(), [0.0, 0.6])
    np.testing.assert_array_equal(_line(ax, POINTS_LABEL).get_ydata(), backbone.force_per_weight)
    assert backbone.force_per_weight[1] == pytest.approx(0.05 + 0.6 / 2.0, rel=1e-15)  # µk + d/R
    text = _texts(fig)
    assert "ULTIMATE DISPLACEMENT REACHED" in text and "(the displacement capacity)" in text
    assert f"Rim contacts: {numbers['n_rim_contacts']}" in text and numbers["n_rim_contacts"] > 0
    out = tmp_path / "fp.pdf"
    result = runner.invoke(app, ["report", str(records_dir / RECORD), "-d", str(design_path), "--scale-to-pga",
                                 str(SCALE_G), "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "(4 pages)" in result.stdout and len(pypdf.PdfReader(str(out)).pages) == 4


PAIR = ("pairs/landers1992_YER/RSN900_LANDERS_YER270.AT2",
        "pairs/landers1992_YER/RSN900_LANDERS_YER360.AT2")


def test_building_under_a_pair_report_and_batch_columns(records_dir, building, tmp_path):
    """The 2-D building (a pair): the pair report's fourth page and the batch row carry the analysis' lists."""
    from isolator.batch import run_batch
    from isolator.errors import InvalidSystemError
    from isolator.motion import read_ground_motion_pair

    path, _, _ = building
    x, y = (records_dir / name for name in PAIR)
    design = Design.from_toml(path)
    try:
        analysis = analyse(design, read_ground_motion_pair(x, y), harmonic=False)
    except InvalidSystemError as err:  # main without the 2-D building model (docs/building.md)
        pytest.skip(f"no 2-D building model here: {err}")
    numbers = analysis.to_dict()
    assert analysis.model.startswith("2d") and analysis.is_planar
    fig = building_page(4, "label", numbers, analysis.response)
    drift_x, _ = _line(_axes(fig, "Story drift ratio profile"), "story drift ratio (peak)").get_data()
    np.testing.assert_array_equal(drift_x, numbers["story_drift_ratio"])
    acc_x, _ = _line(_axes(fig, "Floor acceleration profile"), "floor peak absolute acceleration").get_data()
    np.testing.assert_allclose(acc_x * STANDARD_GRAVITY, numbers["floor_peak_acceleration_m_s2"], rtol=1e-15)
    out = tmp_path / "pair.pdf"
    result = runner.invoke(app, ["report", str(x), "--pair", str(y), "-d", str(path), "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "(4 pages)" in result.stdout
    written = json.loads(out.with_suffix(".json").read_text())
    assert written["story_drift_ratio"] == numbers["story_drift_ratio"]
    last = " ".join(pypdf.PdfReader(str(out)).pages[3].extract_text().split())
    assert "The building above the isolators" in last and "horizontal resultant" in last
    designs = tmp_path / "designs.toml"
    designs.write_text(designs_file_text(BUILDING))
    table = run_batch([str(x), str(y)], designs, tmp_path / "t.csv", jobs=1).table
    assert len(table) == 1 and table.loc[0, "error"] == "" and table.loc[0, "model"] == analysis.model
    for key in ("story_drift_ratio", "floor_peak_acceleration_m_s2", "bearing_axial_load_min_N"):
        assert [table.loc[0, f"{key}_{i}"] for i in range(1, len(numbers[key]) + 1)] == pytest.approx(
            numbers[key], rel=1e-15, abs=0.0), key
    assert table.loc[0, "superstructure_shear_coefficient"] == pytest.approx(
        numbers["superstructure_shear_coefficient"], rel=1e-15)


def test_triple_pendulum_under_a_pair_report_and_batch_columns(records_dir, triple, tmp_path):
    """The 2-D triple pendulum (a pair): the page draws Bearing.backbone() over the resultant loop; the pair
    report's fourth page and the batch pair row carry the analysis' per-surface values."""
    from isolator.batch import run_batch
    from isolator.errors import RecordInputError
    from isolator.motion import read_ground_motion_pair

    path, _, _ = triple
    x, y = (records_dir / name for name in PAIR)
    design = Design.from_toml(path)
    try:
        analysis = analyse(design, read_ground_motion_pair(x, y), harmonic=False)
    except RecordInputError as err:  # main without the 2-D multi-surface model (docs/multisurface.md)
        pytest.skip(f"no 2-D multi-surface model here: {err}")
    numbers = analysis.to_dict()
    assert analysis.is_planar and len(numbers["surface_peak_displacement_m"]) == 4
    fig = bearing_page(4, "label", numbers, analysis.response)
    ax = _axes(fig, "Backbone and force-displacement loop")
    np.testing.assert_array_equal(_line(ax, POINTS_LABEL).get_xdata(), design.bearing.backbone().displacement_m)
    lx, _ = _line(ax, LOOP_LABEL).get_data()
    assert np.max(lx) == pytest.approx(numbers["peak_displacement_m"], rel=1e-2)  # resultant, at the samples
    assert numbers["regimes"] and all(f"{name} at {fmt(t, 4)} s" in _texts(fig)
                                      for name, t in numbers["regimes"].items())
    out = tmp_path / "pair.pdf"
    result = runner.invoke(app, ["report", str(x), "--pair", str(y), "-d", str(path), "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "(4 pages)" in result.stdout
    assert json.loads(out.with_suffix(".json").read_text())["surface_peak_displacement_m"] == numbers[
        "surface_peak_displacement_m"]
    designs = tmp_path / "designs.toml"
    designs.write_text(designs_file_text(TRIPLE))
    table = run_batch([str(x), str(y)], designs, tmp_path / "t.csv", jobs=1).table
    assert table.loc[0, "error"] == "" and table.loc[0, "model"] == analysis.model
    assert [table.loc[0, f"surface_peak_displacement_m_{i}"] for i in range(1, 5)] == pytest.approx(
        numbers["surface_peak_displacement_m"], rel=1e-15, abs=0.0)
    assert table.loc[0, "n_rim_contacts"] == numbers["n_rim_contacts"]
    assert table.loc[0, "regimes_reached"] == ", ".join(sorted(numbers["regimes"], key=numbers["regimes"].get))
