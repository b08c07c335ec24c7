"""The building in the model registry, the analysis schema and ``isolator simulate --design`` (issue 22)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from isolator.cli import app
from isolator.design import Design
from isolator.solver.building import simulate_design_building
from isolator.solver.models import Scene, select_model, simulate

BASE = {"name": "b", "mass_kg": 1.2e6, "radius_m": 2.5, "mu_static": 0.06, "mu_kinetic": 0.045,
        "damping_Ns_per_m": 3.0e5}
FLOORS = [{"mass_kg": 3e5, "story_height_m": 4.0, "stiffness_x_N_per_m": 6e8},
          {"mass_kg": 2.5e5, "story_height_m": 3.5, "stiffness_x_N_per_m": 4e8},
          {"mass_kg": 2e5, "story_height_m": 3.5, "stiffness_x_N_per_m": 2.5e8}]
BEARINGS = [{"x_m": x, "y_m": y} for x, y in [(-6.0, -4.0), (6.0, -4.0), (6.0, 4.0), (-6.0, 4.0)]]
BUILDING_KEYS = {"story_drift_m", "story_drift_ratio", "floor_peak_acceleration_m_s2",
                 "superstructure_shear_coefficient", "base_shear_coefficient", "bearing_axial_load_max_N",
                 "bearing_axial_load_min_N", "n_bearings_uplifted"}

TOML = """name = "3-story"
mass_kg = 1.2e6
radius_m = 2.5
mu_static = 0.06
mu_kinetic = 0.045
damping_Ns_per_m = 3.0e5

[superstructure]
damping_ratio = 0.05
""" + "".join(f"""
[[superstructure.floor]]
mass_kg = {f['mass_kg']}
story_height_m = {f['story_height_m']}
stiffness_x_N_per_m = {f['stiffness_x_N_per_m']}
""" for f in FLOORS) + "".join(f"""
[[bearing_position]]
x_m = {b['x_m']}
y_m = {b['y_m']}
""" for b in BEARINGS)


def building_design():
    return Design.from_mapping({**BASE, "superstructure": {"damping_ratio": 0.05, "floor": FLOORS},
                                "bearing_position": BEARINGS})


def _record(records_dir):
    from isolator.motion import read_ground_motion

    return read_ground_motion(records_dir / "at2" / "RSN1044_NORTHR_NWH360.AT2")


def test_registry_selects_the_building_only_with_floors(records_dir):
    from isolator.adapter import motion_keywords

    motion = _record(records_dir)
    design = building_design()
    scene = Scene.of(motion, motion_keywords(design), design)
    assert select_model(scene)[0] == "1d-building"
    rigid = Design.from_mapping(BASE)
    assert select_model(Scene.of(motion, motion_keywords(rigid), rigid))[0] == "1d-exact"
    result = simulate(scene)
    direct = simulate_design_building(design, motion.acceleration_m_s2, motion.dt_s)
    assert result.model == "1d-building"
    assert np.array_equal(result.displacement_m, direct.displacement_m)
    assert BUILDING_KEYS <= result.summary().keys()
    # a pair is the 2-D building's, and so is a record with a vertical: never run as the rigid block; a zero
    # vertical is bit for bit the pair with a zero second component
    pair = Scene(ax_m_s2=motion.acceleration_m_s2, ay_m_s2=0 * motion.acceleration_m_s2, dt_s=motion.dt_s,
                 isolator=motion_keywords(design), design=design)
    assert select_model(pair)[0] == "2d-building"
    vertical = Scene(ax_m_s2=motion.acceleration_m_s2, az_m_s2=0 * motion.acceleration_m_s2, dt_s=motion.dt_s,
                     isolator=motion_keywords(design), design=design)
    assert select_model(vertical)[0] == "2d-building"
    with_vertical, on_pair = simulate(vertical), simulate(pair)
    assert with_vertical.model == "2d-building"
    assert np.array_equal(with_vertical.displacement_m, on_pair.displacement_m)


def test_upper_bound_friction_reaches_the_building(records_dir):
    from isolator.adapter import motion_keywords

    motion = _record(records_dir)
    design = building_design()
    upper = design.with_friction_factor(1.3, "upper bound")
    nominal = simulate(Scene.of(motion, motion_keywords(design), design))
    bound = simulate(Scene.of(motion, motion_keywords(upper), upper))
    assert bound.system.mu_static == pytest.approx(1.3 * 0.06)
    assert bound.peak_displacement_m < nominal.peak_displacement_m
    assert bound.superstructure_shear_coefficient != nominal.superstructure_shear_coefficient


def test_analysis_schema_carries_the_building(records_dir):
    from isolator.analysis import analyse

    analysis = analyse(building_design(), _record(records_dir), harmonic=False)
    data = analysis.to_dict()
    assert data["model"] == "1d-building"
    flat = data if "story_drift_ratio" in data else {**data, **data.get("response", {})}
    assert BUILDING_KEYS <= flat.keys()
    assert len(flat["story_drift_ratio"]) == 3 and len(flat["bearing_axial_load_max_N"]) == 4
    json.dumps(data)  # JSON-safe


def test_cli_simulate_with_a_design(records_dir, tmp_path):
    design = tmp_path / "building.toml"
    design.write_text(TOML)
    record = str(records_dir / "at2" / "RSN1044_NORTHR_NWH360.AT2")
    runner = CliRunner()
    result = runner.invoke(app, ["simulate", record, "--design", str(design), "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["model"] == "1d-building" and BUILDING_KEYS <= data.keys()
    direct = simulate_design_building(Design.from_toml(design), _record(records_dir).acceleration_m_s2, 0.02)
    assert data["story_drift_m"] == pytest.approx(direct.story_drift_m.tolist(), rel=1e-15)
    table = runner.invoke(app, ["simulate", record, "--design", str(design)])
    assert table.exit_code == 0 and "story drift ratio" in table.stdout and "bearing load min" in table.stdout


@pytest.mark.parametrize(("extra", "words"), [
    (["--mu-s", "0.1"], ["--design", "--mu-s", "not both"]),
    ([], ["floor 2 (from the bottom)", "stiffness_x_N_per_m"]),
])
def test_cli_design_mistakes_are_one_line(records_dir, tmp_path, extra, words):
    design = tmp_path / "bad.toml"
    design.write_text(TOML.replace("stiffness_x_N_per_m = 400000000.0", "stiffness_x_N_per_m = -1.0")
                      if not extra else TOML)
    record = str(records_dir / "at2" / "RSN1044_NORTHR_NWH360.AT2")
    result = CliRunner().invoke(app, ["simulate", record, "--design", str(design), *extra])
    assert result.exit_code == 2
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("error:"), result.stderr
    for word in words:
        assert word in lines[0]
