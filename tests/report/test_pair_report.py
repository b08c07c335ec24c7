"""The bidirectional report: model stated, numbers from the analysis, orbit with the capacity circle."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from typer.testing import CliRunner

from isolator.analysis import analyse
from isolator.cli import app
from isolator.design import Design
from isolator.motion import read_ground_motion_pair
from isolator.solver.models import simulate_motion

DESIGN = """name = "FP R2"
mass_kg = 1000.0
radius_m = 2.0
mu_static = 0.05
displacement_capacity_m = 0.05
"""


@pytest.fixture(scope="module")
def v2(records_dir):
    return records_dir / "other" / "ce89486SampleInput.v2"


def test_report_on_a_pair_states_the_model_and_its_numbers(v2, tmp_path):
    design = tmp_path / "fp.toml"
    design.write_text(DESIGN)
    out = tmp_path / "pair.pdf"
    result = CliRunner().invoke(app, ["report", str(v2), "--component", "all", "-d", str(design), "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "2d+vertical" in result.stdout
    numbers = json.loads(out.with_suffix(".json").read_text())
    assert numbers["model"] == "2d+vertical" and "vertical component" in numbers["model_reason"]
    pair = read_ground_motion_pair(v2, component="all")
    direct = simulate_motion(pair.x.acceleration_m_s2, pair.y.acceleration_m_s2, pair.z.acceleration_m_s2,
                             pair.dt_s, mu_static=0.05, mu_kinetic=0.05, radius_m=2.0, damping_per_mass=0.0)
    assert numbers["peak_displacement_m"] == pytest.approx(direct.peak_displacement_m, rel=1e-12)
    assert numbers["displacement_demand_ratio"] == pytest.approx(direct.peak_displacement_m / 0.05,
                                                                            rel=1e-12)
    assert len(re.findall(rb"/Type\s*/Page\b(?!s)", out.read_bytes())) == 3
    assert any("capacity" in sentence for sentence in numbers["verdicts"])


def test_orbit_draws_the_capacity_circle_and_the_histories(v2):
    from isolator.report.pair_figures import pair_response_figure

    design = Design.from_mapping({"name": "FP", "mass_kg": 1000.0, "radius_m": 2.0, "mu_static": 0.05,
                                  "displacement_capacity_m": 0.05})
    analysis = analyse(design, read_ground_motion_pair(v2))
    fig = pair_response_figure(analysis.response, design.mass_kg, capacity_m=0.05, labels=("180", "90"))
    orbit = fig.axes[0]
    circle = next(line for line in orbit.get_lines() if "capacity" in str(line.get_label()))
    radius = np.hypot(*circle.get_data())
    np.testing.assert_allclose(radius, 0.05, rtol=1e-12)
    path = next(line for line in orbit.get_lines() if line.get_label() == "orbit of the bearing")
    np.testing.assert_array_equal(np.column_stack(path.get_data()), analysis.response.displacement_m)
    loops = [ax for ax in fig.axes if ax.get_title().startswith("Force-displacement loop")]
    assert [ax.get_title() for ax in loops] == ["Force-displacement loop, 180", "Force-displacement loop, 90"]
    force = loops[1].get_lines()[0].get_data()[1]
    np.testing.assert_allclose(force, -1000.0 * analysis.response.absolute_acceleration_m_s2[:, 1] / 1e3)


def test_a_design_with_velocity_dependent_friction_on_one_component_gets_the_2d_report(records_dir, tmp_path):
    design = tmp_path / "ptfe.toml"
    design.write_text(DESIGN + "mu_slow = 0.03\nmu_fast = 0.08\nrate_s_per_m = 20.0\n")
    out = tmp_path / "one.pdf"
    result = CliRunner().invoke(app, ["report", str(records_dir / "at2" / "IELC180.AT2"), "-d", str(design),
                                      "-o", str(out)])
    assert result.exit_code == 0, result.output
    numbers = json.loads(out.with_suffix(".json").read_text())
    assert numbers["model"] == "2d+mu(v)" and "µ(v)" in numbers["model_reason"]
    assert numbers["residual_displacement_y_m"] == 0.0
