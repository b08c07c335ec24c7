"""The superstructure definition (issue 22): floors, modes, classical damping, bearing layout, statics."""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.design import Design, DesignError
from isolator.superstructure import bearing_axial_loads, tension_time

BASE = {"name": "b", "mass_kg": 1.0e6, "radius_m": 2.0, "mu_static": 0.06, "mu_kinetic": 0.05}


def building(floors, zeta=0.05, **extra):
    return Design.from_mapping({**BASE, "superstructure": {"damping_ratio": zeta, "floor": floors}, **extra})


def test_two_story_modes_by_hand():
    # m1 = m2 = m, k1 = k2 = k: ω² = (3 ∓ √5)/2 · k/m (Chopra, Example 10.4)
    m, k = 2.0e5, 4.0e8
    d = building([{"mass_kg": m, "story_height_m": 3.5, "stiffness_x_N_per_m": k}] * 2)
    s = d.superstructure
    omega, phi = s.modes("x")
    assert omega ** 2 == pytest.approx([(3 - math.sqrt(5)) / 2 * k / m, (3 + math.sqrt(5)) / 2 * k / m], rel=1e-13)
    assert phi.T @ s.mass_matrix() @ phi == pytest.approx(np.eye(2), abs=1e-13)
    assert s.fixed_base_periods_s("y") == pytest.approx(2 * math.pi / omega, rel=1e-13)  # y defaults to x
    assert s.weight_N == pytest.approx(2 * m * 9.80665)
    assert s.floor_heights_m.tolist() == [3.5, 7.0]


def test_classical_damping_gives_zeta_in_every_mode():
    floors = [{"mass_kg": m, "story_height_m": 3.0, "stiffness_x_N_per_m": k, "stiffness_y_N_per_m": 0.5 * k}
              for m, k in [(3e5, 9e8), (2.5e5, 7e8), (2e5, 5e8), (1e5, 2e8)]]
    s = building(floors, zeta=0.03).superstructure
    for direction in ("x", "y"):
        omega, phi = s.modes(direction)
        modal_c = phi.T @ s.damping_matrix(direction) @ phi
        assert np.diag(modal_c) == pytest.approx(2 * 0.03 * omega, rel=1e-11)
        off = modal_c - np.diag(np.diag(modal_c))
        assert np.abs(off).max() < 1e-11 * np.abs(modal_c).max()  # classical: diagonal in the modes
    assert s.fixed_base_periods_s("y")[0] == pytest.approx(math.sqrt(2) * s.fixed_base_periods_s("x")[0], rel=1e-12)


@pytest.mark.parametrize(("floors", "words"), [
    ([{"mass_kg": -1.0, "story_height_m": 3.0, "stiffness_x_N_per_m": 1e8}], ["floor 1", "'mass_kg' must be > 0"]),
    ([{"mass_kg": 1e5, "story_height_m": 3.0, "stiffness_x_N_per_m": 1e8},
      {"mass_kg": 1e5, "story_height_m": 3.0}], ["floor 2", "missing key 'stiffness_x_N_per_m'"]),
    ([{"mass_kg": 1e5, "story_height_m": 0.0, "stiffness_x_N_per_m": 1e8}], ["floor 1", "'story_height_m'"]),
    ([{"mass_kg": 1e5, "story_height_m": 3.0, "stiffness_x_N_per_m": 1e8, "stiffnes_y_N_per_m": 1e8}],
     ["floor 1", "unknown key", "did you mean 'stiffness_y_N_per_m'"]),
    ([{"mass_kg": 6e5, "story_height_m": 3.0, "stiffness_x_N_per_m": 1e8}] * 2, ["floors weigh 1.2e+06 kg"]),
    ([], ["at least one [[superstructure.floor]]"]),
])
def test_bad_floor_is_one_line_naming_it(floors, words):
    with pytest.raises(DesignError) as err:
        building(floors)
    message = str(err.value)
    assert "\n" not in message
    for word in words:
        assert word in message


def test_bad_damping_ratio():
    with pytest.raises(DesignError, match=r"'damping_ratio' must lie in \[0, 1\)"):
        building([{"mass_kg": 1e5, "story_height_m": 3.0, "stiffness_x_N_per_m": 1e8}], zeta=1.5)


ONE_FLOOR = [{"mass_kg": 5e5, "story_height_m": 4.0, "stiffness_x_N_per_m": 1e9}]
SQUARE = [{"x_m": x, "y_m": y} for x, y in [(-5.0, -5.0), (5.0, -5.0), (5.0, 5.0), (-5.0, 5.0)]]


@pytest.mark.parametrize(("bearings", "words"), [
    ([{"x_m": 0.0, "y_m": 0.0}, {"x_m": 1.0, "y_m": 0.0}], ["do not span the plan"]),
    ([{"x_m": 0.0, "y_m": 0.0}, {"x_m": 1.0, "y_m": 0.0}, {"x_m": 2.0, "y_m": 0.0}], ["do not span"]),
    ([*SQUARE, {"x_m": 5.0, "y_m": 5.0}], ["bearing_position 5", "same place as bearing_position 3"]),
    ([{"x_m": "a", "y_m": 0.0}, *SQUARE], ["bearing_position 1", "'x_m' must be a finite number"]),
    ([{**SQUARE[0], "gravity_load_N": 1e6}, *SQUARE[1:]], ["bearing_position 2", "missing key 'gravity_load_N'"]),
    ([{**b, "gravity_load_N": 1e6} for b in SQUARE], ["add up to 4e+06 N", "W = g × mass_kg"]),
    ([{**SQUARE[0], "z_m": 1.0}, *SQUARE[1:]], ["bearing_position 1", "unknown key 'z_m'"]),
])
def test_bad_bearing_is_one_line_naming_it(bearings, words):
    with pytest.raises(DesignError) as err:
        building(ONE_FLOOR, bearing_position=bearings)
    assert "\n" not in str(err.value)
    for word in words:
        assert word in str(err.value)


def test_overturning_statics_by_hand_on_a_square():
    # four bearings at (±a, ±a): a moment M about y puts ±M/(4a) on the ±x bearings; gravity W/4 each
    d = building(ONE_FLOOR, bearing_position=SQUARE)
    layout = d.bearing_layout
    a, w = 5.0, d.weight_N
    assert layout.gravity_loads_N == pytest.approx([w / 4] * 4, rel=1e-15)
    coeff_x = layout.overturning_coefficients("x")
    assert coeff_x == pytest.approx([-1 / (4 * a), 1 / (4 * a), 1 / (4 * a), -1 / (4 * a)], rel=1e-13)
    coeff_y = layout.overturning_coefficients("y")
    assert coeff_y == pytest.approx([-1 / (4 * a), -1 / (4 * a), 1 / (4 * a), 1 / (4 * a)], rel=1e-13)
    # a horizontal force F at height H; the moment large enough to lift the -x side for a while
    t = np.linspace(0.0, 1.0, 1001)
    moment = 1.5 * w * a * np.sin(np.pi * t)  # peak 1.5 W a: tension W/4 − 1.5 W a/(4a) = −W/8 on the −x side
    out = bearing_axial_loads(layout, moment, t)
    assert out["bearing_axial_load_max_N"] == pytest.approx([w / 4, 5 * w / 8, 5 * w / 8, w / 4], rel=1e-12)
    assert out["bearing_axial_load_min_N"] == pytest.approx([-w / 8, w / 4, w / 4, -w / 8], rel=1e-12)
    assert out["n_bearings_uplifted"] == 2
    # tension while sin(πt) > 2/3: from asin(2/3)/π for 1 − 2 asin(2/3)/π seconds (linear between samples)
    start = math.asin(2 / 3) / math.pi
    assert out["uplift_start_s"][0] == pytest.approx(start, abs=1e-4)
    assert out["uplift_duration_s"][0] == pytest.approx(1 - 2 * start, abs=1e-4)
    assert out["uplift_start_s"][1] is None and out["uplift_duration_s"][1] == 0.0
    # the loads always add up to W and their moment is the overturning moment
    assert out["axial_load_N"].sum(axis=0) == pytest.approx(np.full(t.size, w), rel=1e-12)
    x = np.array(layout.x_m)
    assert x @ out["axial_load_N"] == pytest.approx(moment, abs=1e-9 * w * a)


def test_unequal_layout_statics_balance_and_vertical_share():
    bearings = [{"x_m": x, "y_m": y, "gravity_load_N": p} for x, y, p in
                [(-6.0, -2.0, 3e6), (4.0, -3.0, 2.5e6), (7.0, 5.0, 2.3066e6), (-3.0, 4.0, 2e6)]]
    d = building(ONE_FLOOR, bearing_position=bearings)
    layout = d.bearing_layout
    x, y = np.array(layout.x_m), np.array(layout.y_m)
    for direction, lever, other in (("x", x, y), ("y", y, x)):
        c = layout.overturning_coefficients(direction)
        assert c.sum() == pytest.approx(0.0, abs=1e-15)
        assert c @ lever == pytest.approx(1.0, rel=1e-13)
        assert c @ other == pytest.approx(0.0, abs=1e-14)
    t = np.array([0.0, 0.01, 0.02])
    out = bearing_axial_loads(layout, np.zeros(3), t, vertical_factor=np.array([1.0, 1.2, 0.5]))
    assert out["bearing_axial_load_max_N"] == pytest.approx([1.2 * p for p in layout.gravity_loads_N], rel=1e-15)
    assert out["n_bearings_uplifted"] == 0


def test_torsion_parameters_from_the_layout():
    # P_T = sqrt(Σ(x² + y²)/N) / r_I with r_I = sqrt((b² + d²)/12): four corners of a 10 m square, b = d = 10
    d = building(ONE_FLOOR, bearing_position=SQUARE)
    out = d.bearing_layout.torsion_parameters(10.0, 10.0)
    assert out["r_I_m"] == pytest.approx(math.sqrt(200 / 12))
    assert out["P_T"] == pytest.approx(math.sqrt(50.0) / math.sqrt(200 / 12), rel=1e-14)  # = √3
    assert out["y_for_loading_x_m"] == 5.0 and out["y_for_loading_y_m"] == 5.0


def test_tension_time_cases():
    t = np.array([0.0, 1.0, 2.0, 3.0])
    assert tension_time(np.array([1.0, 2.0, 3.0, 4.0]), t) == (None, 0.0)
    start, duration = tension_time(np.array([1.0, -1.0, -1.0, 1.0]), t)
    assert start == pytest.approx(0.5) and duration == pytest.approx(2.0)
    assert tension_time(np.array([1.0, 1.0, 1.0, -1.0]), t) == (pytest.approx(2.5), pytest.approx(0.5))


def test_design_without_superstructure_is_unchanged():
    d = Design.from_mapping(BASE)
    assert d.superstructure is None and d.bearing_layout is None
    assert d.as_dict()["superstructure"] is None
    with_floors = building(ONE_FLOOR)
    assert with_floors.with_friction_factor(1.2, "upper").superstructure == with_floors.superstructure
    assert with_floors.as_dict()["superstructure"]["fixed_base_periods_x_s"] == pytest.approx(
        [2 * math.pi * math.sqrt(5e5 / 1e9)])


def test_review_inputs_from_the_design():
    floors = [{"mass_kg": 3e5, "story_height_m": 4.0, "stiffness_x_N_per_m": 6e8, "stiffness_y_N_per_m": 1.5e8}]
    d = building(floors, bearing_position=SQUARE, plan={"b_m": 10.0, "d_m": 10.0})
    from isolator.superstructure import review_inputs

    out = review_inputs(d)
    assert out["Ws_over_W"] == pytest.approx(0.3)
    assert out["T_fixed_s"]["x"] == pytest.approx(2 * math.pi * math.sqrt(3e5 / 6e8))
    assert out["T_fixed_s"]["y"] == pytest.approx(2 * out["T_fixed_s"]["x"])
    assert out["P_T"] == pytest.approx(math.sqrt(3.0)) and out["y_for_loading_x_m"] == 5.0
    assert len(out["basis"]) == 3
    assert review_inputs(Design.from_mapping(BASE)) == {}
