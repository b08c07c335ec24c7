"""The multi-surface bearing: backbone, loops and validation (isolator.bearing)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.bearing import Bearing, parse_bearing
from isolator.errors import DesignError

G = 9.80665


def _fail(message):
    return DesignError(f"d.toml: {message}")


def triple(r=(2.1, 0.3, 0.3, 2.1), mu=(0.06, 0.02, 0.02, 0.10), d=(0.4, 0.05, 0.05, 0.4), h=(0, 0, 0, 0)):
    return parse_bearing({"type": "triple", "surface": [
        {"radius_m": ri, "height_m": hi, "mu": mi, "displacement_capacity_m": di}
        for ri, mi, di, hi in zip(r, mu, d, h, strict=True)]}, _fail)


def test_triple_backbone_matches_the_issue_and_fenz_constantinou_closed_forms():
    bb = triple().backbone()
    # the issue's numbers, to their printed precision
    issue = [(0, 0.02), (0.024, 0.06), (0.120, 0.10), (0.752, 0.2505), (0.848, 0.2905), (0.900, 0.3771)]
    assert len(bb.displacement_m) == 6
    for (x, f), xk, fk in zip(issue, bb.displacement_m, bb.force_per_weight, strict=True):
        assert abs(xk - x) <= 5e-4 and abs(fk - f) <= 5e-5
    # Fenz & Constantinou (2008, EESD 37, Table I) in closed form, to 1e-12
    r1, r2, r3, r4 = 2.1, 0.3, 0.3, 2.1
    m1, m2, m3, m4 = 0.06, 0.02, 0.02, 0.10
    d1, d2, d3, d4 = 0.4, 0.05, 0.05, 0.4
    u1 = (m1 - m2) * r2 + (m1 - m3) * r3
    u2 = u1 + (m4 - m1) * (r1 + r3)
    f_dr1 = m1 + d1 / r1
    u3 = u2 + (f_dr1 - m4) * (r1 + r4)
    f_dr4 = m4 + d4 / r4
    u4 = u3 + (f_dr4 - f_dr1) * (r2 + r4)
    f_ult = f_dr4 + (d1 + d2 + d3 + d4 - u4) / (r2 + r3)
    expected_x = [0.0, u1, u2, u3, u4, d1 + d2 + d3 + d4]
    expected_f = [m2, m1, m4, f_dr1, f_dr4, f_ult]
    np.testing.assert_allclose(bb.displacement_m, expected_x, rtol=0, atol=1e-12)
    np.testing.assert_allclose(bb.force_per_weight, expected_f, rtol=0, atol=1e-12)
    # the stiffnesses of the five regimes: W/0.6, W/2.4 (not 2.7: the plates rotate), W/4.2, W/2.4, W/0.6
    np.testing.assert_allclose(1.0 / bb.stiffness_per_weight_1_m, [0.6, 2.4, 4.2, 2.4, 0.6], rtol=1e-12)
    assert bb.regimes == ("I", "II", "III", "IV", "V")
    assert bb.ultimate_displacement_m == pytest.approx(0.9, abs=1e-15)
    # the inner rims are reached together at the ultimate force µ2 + d1/R1 + d2/R2 (surface 2's rim)
    assert f_ult == pytest.approx(m2 + d1 / r1 + d2 / r2, abs=1e-12)


def test_effective_radius_and_capacity_use_the_height():
    b = triple(r=(2.2, 0.35, 0.35, 2.2), h=(0.1, 0.05, 0.05, 0.1), d=(0.44, 0.07, 0.07, 0.44))
    s = b.surfaces[0]
    assert s.effective_radius_m == pytest.approx(2.1)
    assert s.effective_capacity_m == pytest.approx(0.44 * 2.1 / 2.2)
    assert b.ultimate_displacement_m == pytest.approx(2 * 0.44 * 2.1 / 2.2 + 2 * 0.07 * 0.3 / 0.35)


def test_double_with_equal_surfaces_is_a_single_pendulum_of_summed_radius():
    b = parse_bearing({"type": "double", "surface": [
        {"radius_m": 1.5, "mu": 0.05, "displacement_capacity_m": 0.3},
        {"radius_m": 1.5, "mu": 0.05, "displacement_capacity_m": 0.3}]}, _fail)
    bb = b.backbone()
    np.testing.assert_allclose(bb.displacement_m, [0.0, 0.6], atol=1e-15)
    np.testing.assert_allclose(bb.force_per_weight, [0.05, 0.05 + 0.6 / 3.0], atol=1e-15)
    assert bb.regimes == ("1+2",)


def test_single_pendulum_loop_is_the_bilinear_formula():
    b = parse_bearing({"type": "single", "surface": [{"radius_m": 2.0, "mu": 0.05}]}, _fail)
    w, d = 1.0e6, 0.2
    lp = b.loop_properties(d, w, G)
    assert lp.effective_stiffness_N_per_m == pytest.approx(w / 2.0 + 0.05 * w / d, rel=1e-13)
    assert lp.energy_per_cycle_J == pytest.approx(4 * 0.05 * w * d, rel=1e-13)
    assert lp.effective_damping_ratio == pytest.approx(4 * 0.05 * d / (2 * math.pi * (d / 2.0 + 0.05) * d), rel=1e-13)


def test_quasi_static_cycle_in_regime_III_matches_the_closed_form_loop():
    """Fenz & Constantinou: unloading from (D, F) retraces regimes I, II, III with doubled offsets."""
    b = triple()
    d = 0.3
    xs, rs = b.quasi_static_path([d, -d, d])
    r1, r2, r3, r4 = 2.1, 0.3, 0.3, 2.1
    m1, m2, m4 = 0.06, 0.02, 0.10
    f_d = m4 + (d - 0.12) / (r1 + r4)  # regime III at D
    u1 = 2 * ((m1 - m2) * r2 + (m1 - m2) * r3)  # regime I of the unloading: 2u* (µ3 = µ2)
    u2 = u1 + 2 * (m4 - m1) * (r1 + r3)  # regime II: 2u**
    unloading = [(d, f_d), (d, f_d - 2 * m2), (d - u1, f_d - 2 * m1), (d - u2, f_d - 2 * m4), (-d, -f_d)]
    expected = [(0.0, 0.0), (0.0, m2), (0.024, m1), (0.12, m4), *unloading,
                *[(-x, -f) for x, f in unloading[1:]]]
    np.testing.assert_allclose(np.c_[xs, rs], expected, rtol=0, atol=1e-13)
    lp = b.loop_properties(d, 1.0, G)
    # E_D of the closed polygon, by the shoelace formula on the closed-form vertices
    loop = np.array(unloading + [(-x, -f) for x, f in unloading[1:]])
    area = 0.5 * abs(np.sum(loop[:-1, 0] * loop[1:, 1] - loop[1:, 0] * loop[:-1, 1]))
    assert lp.energy_per_cycle_J == pytest.approx(area, rel=1e-12)
    assert lp.effective_stiffness_N_per_m == pytest.approx(f_d / d, rel=1e-13)
    assert lp.regime == "III"


def test_loop_reaching_the_rims_is_stable_and_bounded_by_the_backbone():
    b = triple()
    for d in (0.8, 0.89):
        xs, rs = b.quasi_static_path([d, -d, d, -d, d])
        # the loop is periodic after the first half cycle
        assert rs[-1] == pytest.approx(b.backbone().force_per_weight_at(d), abs=1e-13)
    with pytest.raises(ValueError, match="ultimate"):
        b.quasi_static_path([0.95])


@pytest.mark.parametrize("surfaces, match", [
    ([(2.1, 0.06, 0.4), (2.2, 0.02, 0.05), (0.3, 0.02, 0.05), (2.1, 0.1, 0.4)], "surface 2: R_eff,2 = 2.2 m must be <"),
    ([(2.1, 0.06, 0.4), (0.3, 0.08, 0.05), (0.3, 0.02, 0.05), (2.1, 0.1, 0.4)], "surface 2: mu_2 = 0.08 must not exceed"),
    ([(2.1, 0.06, 0.4), (0.3, 0.02, 0.01), (0.3, 0.02, 0.05), (2.1, 0.1, 0.4)], "surface 2: effective capacity"),
    ([(2.1, 0.06, 0.4), (0.3, 0.02, 0.05), (0.3, 0.02, 0.02), (2.1, 0.1, 0.4)], "surface 3: effective capacity"),
    ([(2.1, 0.06, 0.4), (0.3, 0.02, 0.05), (2.5, 0.02, 0.05), (2.1, 0.1, 0.4)], "surface 3: R_eff,3"),
])
def test_invalid_triple_geometry_is_one_line_naming_the_surface(surfaces, match):
    table = {"type": "triple", "surface": [{"radius_m": r, "mu": m, "displacement_capacity_m": d}
                                           for r, m, d in surfaces]}
    with pytest.raises(DesignError, match=match) as info:
        parse_bearing(table, _fail)
    assert "\n" not in str(info.value) and str(info.value).startswith("d.toml: bearing surface")


@pytest.mark.parametrize("table, match", [
    ({"type": "quad", "surface": []}, "bearing.type"),
    ({"type": "double", "surface": [{"radius_m": 1, "mu": 0.05, "displacement_capacity_m": 0.2}]}, "needs 2"),
    ({"type": "double", "surface": [{"radius_m": 1, "mu": 0.05}, {"radius_m": 1, "mu": 0.05}]},
     "surface 1: missing key 'displacement_capacity_m'"),
    ({"type": "single", "surface": [{"radius_m": 1, "mu": 0.05, "radius": 2}]}, "did you mean 'radius_m'"),
    ({"type": "single", "surface": [{"radius_m": 1, "height_m": 1, "mu": 0.05}]}, "height_m"),
    ({"type": "single", "surface": [{"radius_m": 1, "mu": 0.05, "mu_kinetic": 0.05}]}, "friction one way"),
    ({"type": "double", "surface": [{"radius_m": 1, "mu_kinetic": 0.05, "mu_static": 0.07,
                                     "displacement_capacity_m": 0.2},
                                    {"radius_m": 1, "mu": 0.05, "displacement_capacity_m": 0.2}]},
     r"surface 1: mu_static \(0.07\) > mu_kinetic \(0.05\) is not modelled on a double bearing: its sliders are "
     "massless"),
    ({"type": "double", "surface": [{"radius_m": 2.1, "mu": 0.06, "displacement_capacity_m": 0.4},
                                    {"radius_m": 0.3, "mu_slow": 0.01, "mu_fast": 0.02, "rate_s_per_m": 30,
                                     "displacement_capacity_m": 0.05}]},
     r"surface 1: give µ\(v\) with mu_slow < mu_fast on every surface of a double bearing with µ\(v\)"),
    ({"type": "single", "surface": [{"radius_m": 1, "mu": 1.2}]}, "< 1"),
    ({"type": "single", "surface": [{"radius_m": -1, "mu": 0.1}]}, "radius_m"),
    ({"type": "single", "kind": 2, "surface": [{"radius_m": 1, "mu": 0.1}]}, "unknown key 'bearing.kind'"),
])
def test_invalid_bearing_tables(table, match):
    with pytest.raises(DesignError, match=match):
        parse_bearing(table, _fail)


def test_friction_factor_scales_every_surface():
    b = triple().with_friction_factor(1.2)
    assert isinstance(b, Bearing)
    np.testing.assert_allclose(b.mu_kinetic, [0.072, 0.024, 0.024, 0.12])


# ---- the design file's [bearing] table (isolator.design) -------------------------------------------

TRIPLE_TOML = """
name = "TFP"
mass_kg = 1.0e5
[bearing]
type = "triple"
[[bearing.surface]]
radius_m = 2.2
height_m = 0.1
mu = 0.06
displacement_capacity_m = 0.419047619047619
[[bearing.surface]]
radius_m = 0.3
mu = 0.02
displacement_capacity_m = 0.05
[[bearing.surface]]
radius_m = 0.3
mu = 0.02
displacement_capacity_m = 0.05
[[bearing.surface]]
radius_m = 2.2
height_m = 0.1
mu = 0.10
displacement_capacity_m = 0.419047619047619
"""


def _design(tmp_path, text, name="d.toml"):
    from isolator.design import Design

    path = tmp_path / name
    path.write_text(text)
    return Design.from_toml(path)


def test_design_file_with_a_triple_bearing(tmp_path):
    d = _design(tmp_path, TRIPLE_TOML)
    assert d.bearing.kind == "triple"
    np.testing.assert_allclose(d.bearing.backbone().displacement_m, [0, 0.024, 0.12, 0.752, 0.848, 0.9], atol=1e-12)
    # the equivalent single pendulum is regime III: R_eff,1 + R_eff,4, F/W intercept of its line
    assert d.radius_m == pytest.approx(4.2, rel=1e-14)
    assert d.mu_kinetic == pytest.approx(0.1 - 0.12 / 4.2, rel=1e-12)
    assert d.displacement_capacity_m == pytest.approx(0.9, rel=1e-14)
    assert d.as_dict()["bearing"]["type"] == "triple"
    # effective properties from the loop, not from the equivalent bilinear model
    lp = d.bearing.loop_properties(0.3, d.weight_N, d.gravity_m_s2)
    eff = d.effective_properties(0.3)
    assert eff.effective_stiffness_N_per_m == pytest.approx(lp.effective_stiffness_N_per_m, rel=1e-14)
    assert eff.effective_damping_ratio == pytest.approx(lp.effective_damping_ratio, rel=1e-14)
    assert math.isnan(d.effective_properties(0.95).effective_period_s)
    upper = d.with_friction_factor(1.2, "upper bound")
    np.testing.assert_allclose(upper.bearing.mu_kinetic, [0.072, 0.024, 0.024, 0.12])


def test_design_file_with_a_single_bearing_is_todays_pendulum(tmp_path):
    d = _design(tmp_path, 'name = "FP"\nmass_kg = 1000\n[bearing]\ntype = "single"\n[[bearing.surface]]\n'
                'radius_m = 2.1\nheight_m = 0.1\nmu_kinetic = 0.05\nmu_static = 0.07\ndisplacement_capacity_m = 0.42\n')
    assert d.bearing.is_simple and d.radius_m == pytest.approx(2.0)
    assert (d.mu_static, d.mu_kinetic) == (0.07, 0.05)
    assert d.displacement_capacity_m == pytest.approx(0.42 * 2.0 / 2.1)


@pytest.mark.parametrize("extra, match", [
    ("radius_m = 2.0\n", "key 'radius_m' with a \\[bearing\\] table"),
    ("mu_static = 0.05\n", "key 'mu_static' with a \\[bearing\\] table"),
])
def test_design_file_bearing_conflicts(tmp_path, extra, match):
    with pytest.raises(DesignError, match=match):
        _design(tmp_path, extra + TRIPLE_TOML.replace('name = "TFP"\n', 'name = "TFP"\n'))


def test_design_file_invalid_surface_is_one_line(tmp_path):
    bad = TRIPLE_TOML.replace("radius_m = 0.3\nmu = 0.02\ndisplacement_capacity_m = 0.05\n[[bearing.surface]]\n"
                              "radius_m = 0.3\nmu = 0.02",
                              "radius_m = 0.3\nmu = 0.08\ndisplacement_capacity_m = 0.05\n[[bearing.surface]]\n"
                              "radius_m = 0.3\nmu = 0.02", 1)
    with pytest.raises(DesignError) as info:
        _design(tmp_path, bad)
    message = str(info.value)
    assert message.startswith(str(tmp_path / "d.toml") + ": bearing surface 2: mu_2 = 0.08") and "\n" not in message


def test_report_of_a_triple_bearing_design_states_the_model_and_the_bearing_keys(records_dir, tmp_path):
    import json

    from typer.testing import CliRunner

    from isolator.cli import app

    design = tmp_path / "tfp.toml"
    design.write_text(TRIPLE_TOML)
    out = tmp_path / "tfp.pdf"
    result = CliRunner().invoke(app, ["report", str(records_dir / "at2" / "RSN1044_NORTHR_NWH360.AT2"),
                                      "-d", str(design), "-o", str(out), "--no-pdf"])
    assert result.exit_code == 0, result.output
    numbers = json.loads(out.with_suffix(".json").read_text())
    assert numbers["model"] == "1d-multisurface" and "triple" in numbers["model_reason"]
    assert list(numbers["regimes"]) == ["I", "II", "III"] and numbers["ultimate_displacement_reached"] is False
    assert sum(numbers["surface_peak_displacement_m"][1:3]) < numbers["peak_displacement_m"]
    assert abs(numbers["energy_balance_error_J_per_kg"]) <= 1e-9 * numbers["energy_input_J_per_kg"]
