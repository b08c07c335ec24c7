"""The review of the example building, recomputed by hand as the reviewing isolation engineer would (issue 22).

Every expected number here is written from first principles in this file (the TOML's inputs, ASCE/SEI 7-22
Chapter 17 as ``../shared/REVIEW_RULES.md`` gives it, numpy's ``eigh`` and scipy's ``brentq``), never by calling
the routine that computes it; the code's numbers are read from what a user reads (the review's JSON, the
design's derived values, a 2-D building response).  ``data/example_building.toml``: 5 floors
(Σ m_i = 7.4e6 kg) on a 9.3e6 kg isolated mass, R = 4 m, µs/µk = 0.06/0.05, 20 bearings on an 8 m grid,
plan 34 m × 26 m, actual eccentricity 0.5 m, R = 8 (R_I = 3R/8 = 3 → 2).
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from isolator.design import Design

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "data" / "example_building.toml"
SUITE = ROOT / "isolator" / "data" / "suites" / "example"
G = 9.80665  # standard gravity [m/s²], the design's default

# ---- the example's inputs, copied from data/example_building.toml (a change there must be a change here) ----
TOTAL_MASS_KG = 9.3e6
RADIUS_M = 4.0
MU_STATIC, MU_KINETIC = 0.06, 0.05
FLOOR_MASS_KG = np.array([1.6e6, 1.5e6, 1.5e6, 1.5e6, 1.3e6])
STORY_HEIGHT_M = np.array([4.0, 3.6, 3.6, 3.6, 3.6])
STORY_K_N_PER_M = np.array([3.4e9, 3.1e9, 2.7e9, 2.2e9, 1.5e9])
R_SYSTEM = 8.0
PLAN_B_M, PLAN_D_M, ECCENTRICITY_M = 34.0, 26.0, 0.5
BEARING_X_M = np.tile([-16.0, -8.0, 0.0, 8.0, 16.0], 4)  # file order: rows of constant y
BEARING_Y_M = np.repeat([-12.0, -4.0, 4.0, 12.0], 5)
AXIAL_CAPACITY_N = 1.2e7
#: ASCE 7-22 17.2.8.4 (Eqs. 17.2-1/-2) with f_ae = 0.75 and the file's λ factors
LAMBDA_MAX = (1.0 + 0.75 * (1.10 - 1.0)) * 1.20 * 1.15
LAMBDA_MIN = (1.0 - 0.75 * (1.0 - 1.00)) * 0.90 * 0.85
#: the example target (isolator/data/targets/example.toml): two-period MCE_R
S_MS, S_M1, T_L = 1.5, 0.9, 8.0


@pytest.fixture(scope="module")
def design():
    return Design.from_toml(EXAMPLE)


def test_the_inputs_copied_here_are_the_files(design):
    """The hand values below start from these numbers: they must be the example's."""
    s = design.superstructure
    assert design.mass_kg == TOTAL_MASS_KG and design.radius_m == RADIUS_M
    assert (design.mu_static, design.mu_kinetic) == (MU_STATIC, MU_KINETIC)
    assert [f.mass_kg for f in s.floors] == FLOOR_MASS_KG.tolist()
    assert [f.story_height_m for f in s.floors] == STORY_HEIGHT_M.tolist()
    assert [f.stiffness_x_N_per_m for f in s.floors] == STORY_K_N_PER_M.tolist()
    assert [f.stiffness_y_N_per_m for f in s.floors] == STORY_K_N_PER_M.tolist()
    assert s.response_modification_R == R_SYSTEM
    assert list(design.bearing_layout.x_m) == BEARING_X_M.tolist()
    assert list(design.bearing_layout.y_m) == BEARING_Y_M.tolist()
    assert design.plan["b_m"] == PLAN_B_M and design.plan["d_m"] == PLAN_D_M
    assert design.plan["eccentricity_m"] == ECCENTRICITY_M


# ---- hand values ---------------------------------------------------------------------------------------------


def hand_ws_over_w() -> float:
    """W_s/W: W_s the seismic weight above the isolation interface without the base level (17.5.4.2)."""
    return FLOOR_MASS_KG.sum() / TOTAL_MASS_KG  # 7.4/9.3


def hand_r_i() -> float:
    """R_I = 3R/8, not less than 1 nor more than 2 (17.5.4.2): 3 × 8/8 = 3 → 2."""
    return min(max(3.0 * R_SYSTEM / 8.0, 1.0), 2.0)


def hand_fixed_base_periods_s() -> np.ndarray:
    """Fixed-base periods of the shear building, longest first: K φ = ω² M φ by numpy's eigh on M^-½ K M^-½."""
    n = FLOOR_MASS_KG.size
    k = np.zeros((n, n))
    for i in range(n):  # story i joins floor i-1 (the fixed base for i = 0) to floor i
        k[i, i] += STORY_K_N_PER_M[i]
        if i > 0:
            k[i - 1, i - 1] += STORY_K_N_PER_M[i]
            k[i - 1, i] -= STORY_K_N_PER_M[i]
            k[i, i - 1] -= STORY_K_N_PER_M[i]
    scale = np.diag(FLOOR_MASS_KG ** -0.5)
    omega_sq = np.linalg.eigh(scale @ k @ scale)[0]
    return np.sort(2.0 * math.pi / np.sqrt(omega_sq))[::-1]


def hand_p_t() -> float:
    """P_T = sqrt(Σ(x_i² + y_i²)/N) / r_I, r_I = sqrt((b² + d²)/12) (Eqs. 17.5-4/-5): mean x² = 128 m²,
    mean y² = 80 m², r_I = 12.356 m → P_T = 14.422/12.356 = 1.1672."""
    r_i = math.sqrt((PLAN_B_M ** 2 + PLAN_D_M ** 2) / 12.0)
    return math.sqrt(np.mean(BEARING_X_M ** 2 + BEARING_Y_M ** 2)) / r_i


def hand_torsion_factor() -> float:
    """D_TM/D_M = 1 + (y/P_T²) 12 e/(b² + d²) (Eq. 17.5-3), e = 0.5 m + 5 % of the dimension ⟂ loading, y the
    farthest bearing ⟂ loading: along x y = 12 m, e = 1.8 m → 1.1038; along y y = 16 m, e = 2.2 m → 1.1692."""
    p_t = max(hand_p_t(), 1.0)
    along_x = 1.0 + (12.0 / p_t ** 2) * 12.0 * (ECCENTRICITY_M + 0.05 * PLAN_D_M) / (PLAN_B_M ** 2 + PLAN_D_M ** 2)
    along_y = 1.0 + (16.0 / p_t ** 2) * 12.0 * (ECCENTRICITY_M + 0.05 * PLAN_B_M) / (PLAN_B_M ** 2 + PLAN_D_M ** 2)
    return max(along_x, along_y, 1.15)


def hand_target_g(period_s: float) -> float:
    """ASCE 7-22 11.4.5.1 two-period MCE_R spectrum [g]."""
    t0, ts = 0.2 * S_M1 / S_MS, S_M1 / S_MS
    if period_s < t0:
        return S_MS * (0.4 + 0.6 * period_s / t0)
    if period_s <= ts:
        return S_MS
    if period_s <= T_L:
        return S_M1 / period_s
    return S_M1 * T_L / period_s ** 2


def hand_elf(mu: float) -> dict:
    """ELF of a friction pendulum at kinetic friction µ (17.5.3, 17.5.4, REVIEW_RULES §1.7, §1.9).

    k_M = W/R + µW/D, so T_M = 2π / sqrt(g/R + µg/D); β_M = 2µ/(π(µ + D/R)); B_M by Table 17.5-1 (linear);
    D_M the fixed point of D = g S_a(T_M) T_M² / (4π² B_M); V_b/W = D/R + µ; V_st = V_b (W_s/W)^(1 − 2.5β_M);
    V_s = V_st/R_I; D'_M = D_M / sqrt(1 + (T/T_M)²) with T the fixed-base fundamental period (Eq. 17.6-1).
    """
    table_beta = [0.02, 0.05, 0.10, 0.20, 0.30, 0.40, 0.50]
    table_b = [0.8, 1.0, 1.2, 1.5, 1.7, 1.9, 2.0]

    def period(d):
        return 2.0 * math.pi / math.sqrt(G / RADIUS_M + mu * G / d)

    def beta(d):
        return 2.0 * mu / (math.pi * (mu + d / RADIUS_M))

    def image(d):
        t = period(d)
        return G * hand_target_g(t) * t * t / (4.0 * math.pi ** 2 * float(np.interp(beta(d), table_beta, table_b)))

    d_m = brentq(lambda d: image(d) - d, 0.05, 5.0, xtol=1e-15, rtol=1e-14)
    b = beta(d_m)
    v_b = d_m / RADIUS_M + mu
    v_st = v_b * hand_ws_over_w() ** (1.0 - 2.5 * b)
    t_fixed = hand_fixed_base_periods_s()[0]
    return {"D_M_m": d_m, "T_M_s": period(d_m), "beta_M": b, "V_b_over_W": v_b, "V_st_over_W": v_st,
            "V_s_over_W": v_st / hand_r_i(), "D_M_prime_m": d_m / math.sqrt(1.0 + (t_fixed / period(d_m)) ** 2)}


# ---- the design's derived numbers ------------------------------------------------------------------------------


def test_design_derived_numbers_equal_the_hand_values(design):
    from isolator.review.run import structure_inputs

    s = design.superstructure
    assert hand_ws_over_w() == pytest.approx(0.7956989247, rel=1e-9)
    assert s.weight_N == pytest.approx(FLOOR_MASS_KG.sum() * G, rel=1e-13)  # W_s = 72.57 MN
    periods = hand_fixed_base_periods_s()
    assert periods[0] == pytest.approx(0.4907, abs=5e-5)  # the TOML's comment: 0.491 / 0.190 / 0.124 / 0.095 / 0.077
    for direction in ("x", "y"):
        np.testing.assert_allclose(s.fixed_base_periods_s(direction), periods, rtol=1e-10)
    found = structure_inputs(design)
    assert found["Ws_over_W"] == pytest.approx(hand_ws_over_w(), rel=1e-13)
    assert found["T_fixed_s"] == pytest.approx(periods[0], rel=1e-10)
    torsion = design.bearing_layout.torsion_parameters(PLAN_B_M, PLAN_D_M)
    assert torsion["P_T"] == pytest.approx(hand_p_t(), rel=1e-13)
    assert hand_p_t() == pytest.approx(1.16724, abs=1e-5)
    assert (torsion["y_for_loading_x_m"], torsion["y_for_loading_y_m"]) == (12.0, 16.0)
    # every bearing carries W/20 = 4.56 MN (no gravity_load_N given: equal shares of W = g × mass_kg)
    np.testing.assert_allclose(design.bearing_layout.gravity_loads_N, TOTAL_MASS_KG * G / 20, rtol=1e-15)


# ---- one real pair: bearing loads, drift, shear from the code's own histories -------------------------------


@pytest.fixture(scope="module")
def pts_building(design):
    """The example building under the Superstition Hills PTS pair (bundled suite, byte copies of the shared pair),
    ×1.56 (about the review's common factor), 2-D building model; (response, ax, ay)."""
    from isolator.motion.read import read_ground_motion
    from isolator.solver.planar_building import simulate_planar_building

    x = read_ground_motion(SUITE / "superstitionhills1987_PTS" / "RSN723_SUPER.B_B-PTS225.AT2")
    y = read_ground_motion(SUITE / "superstitionhills1987_PTS" / "RSN723_SUPER.B_B-PTS315.AT2")
    n = min(x.npts, y.npts)
    assert x.dt_s == y.dt_s == 0.01
    ax, ay = 1.56 * x.acceleration_m_s2[:n], 1.56 * y.acceleration_m_s2[:n]
    response = simulate_planar_building(
        ax, ay, x.dt_s, superstructure=design.superstructure, total_mass_kg=TOTAL_MASS_KG,
        stiffness_N_per_m=TOTAL_MASS_KG * G / RADIUS_M, mu_static=MU_STATIC, mu_kinetic=MU_KINETIC,
        bearing_layout=design.bearing_layout)
    assert response.message == "ok"
    return response, ax, ay


def test_bearing_axial_loads_are_rigid_slab_statics_of_the_floor_accelerations(pts_building):
    """P_k(t) = W/20 + M_x(t) x_k / Σx² + M_y(t) y_k / Σy² with M = Σ_i (−m_i a_i,abs) H_i, H_i the floor's height
    above the isolation plane (the grid is symmetric: Σx = Σy = Σxy = 0, so the plane distribution is that)."""
    response, _, _ = pts_building
    heights = np.cumsum(STORY_HEIGHT_M)  # 4, 7.6, 11.2, 14.8, 18.4 m
    acc = response.floor_absolute_acceleration_m_s2  # (samples, floors, 2)
    moment = -np.einsum("i,ti,i->t", FLOOR_MASS_KG, acc[:, :, 0], heights), \
        -np.einsum("i,ti,i->t", FLOOR_MASS_KG, acc[:, :, 1], heights)
    share = TOTAL_MASS_KG * G / 20.0
    hand = (share + np.outer(BEARING_X_M, moment[0]) / np.sum(BEARING_X_M ** 2)
            + np.outer(BEARING_Y_M, moment[1]) / np.sum(BEARING_Y_M ** 2))
    loads = response.bearing_loads()
    np.testing.assert_allclose(loads["axial_load_N"], hand, rtol=0, atol=1e-9 * share)
    # the reported extremes are the exact ones between samples: never inside the sampled range, and close to it
    high, low = np.array(response.bearing_axial_load_max_N), np.array(response.bearing_axial_load_min_N)
    assert np.all(high >= hand.max(axis=1) - 1e-9 * share) and np.all(low <= hand.min(axis=1) + 1e-9 * share)
    np.testing.assert_allclose(high, hand.max(axis=1), rtol=5e-3)
    np.testing.assert_allclose(low, hand.min(axis=1), rtol=5e-3)
    # the corner bearing (16, 12) sees both overturning moments: the layout's largest load
    assert int(np.argmax(high)) in (0, 4, 15, 19)
    assert response.n_bearings_uplifted == int(np.sum(low < 0.0))


def test_one_component_bearing_loads_and_drift_by_hand(design):
    """The 1-D building (model ``1d-building``) under the PTS 225° component alone, × 1.56: P_k = W/20 + M x_k / Σx²,
    M = −Σ m_i a_i,abs H_i from its floor-acceleration history; drift ratio = peak |u_i − u_(i−1)| / h_i."""
    from isolator.motion.read import read_ground_motion
    from isolator.solver.building import simulate_design_building

    x = read_ground_motion(SUITE / "superstitionhills1987_PTS" / "RSN723_SUPER.B_B-PTS225.AT2")
    response = simulate_design_building(design, 1.56 * x.acceleration_m_s2, x.dt_s)
    moment = -(response.floor_absolute_acceleration_m_s2 * FLOOR_MASS_KG) @ np.cumsum(STORY_HEIGHT_M)
    share = TOTAL_MASS_KG * G / 20.0
    hand = share + np.outer(BEARING_X_M, moment) / np.sum(BEARING_X_M ** 2)
    np.testing.assert_allclose(response.bearing_loads()["axial_load_N"], hand, rtol=0, atol=1e-9 * share)
    high = np.array(response.bearing_axial_load_max_N)
    assert np.all(high >= hand.max(axis=1) - 1e-9 * share)
    np.testing.assert_allclose(high, hand.max(axis=1), rtol=5e-3)
    # loading along x only: the bearings of one column (same x) carry the same load
    np.testing.assert_allclose(high.reshape(4, 5), np.broadcast_to(high[:5], (4, 5)), rtol=1e-12)
    u = response.floor_displacement_m
    sampled = np.max(np.abs(np.diff(np.concatenate([np.zeros((u.shape[0], 1)), u], axis=1), axis=1)), axis=0)
    ratio = np.asarray(response.story_drift_ratio)
    assert np.all(ratio >= sampled / STORY_HEIGHT_M * (1 - 1e-12))
    # the exact peak lies between samples: a 2nd-mode (0.19 s) swing sampled at 0.01 s can peak up to
    # 1/cos(π dt/T) − 1 = 1.4 % above its samples (measured: top story 0.52 %, the others ≤ 0.2 %)
    np.testing.assert_allclose(ratio, sampled / STORY_HEIGHT_M, rtol=1.0 / math.cos(math.pi * 0.01 / 0.19) - 1.0)


def test_story_drift_ratio_is_the_peak_drift_over_the_story_height(pts_building):
    """Δ_x = u_x − u_(x−1) (u relative to the slab, u_0 = 0) per direction; the ratio is max_t |Δ(t)| / h_sx of the
    resultant in the plane, story by story (17.6.4.4)."""
    response, _, _ = pts_building
    u = response.floor_displacement_m  # (samples, floors, 2)
    drift = np.diff(np.concatenate([np.zeros_like(u[:, :1]), u], axis=1), axis=1)
    sampled = np.max(np.hypot(drift[..., 0], drift[..., 1]), axis=0) / STORY_HEIGHT_M
    ratio = np.asarray(response.story_drift_ratio)
    assert np.all(ratio >= sampled * (1 - 1e-12))
    np.testing.assert_allclose(ratio, sampled, rtol=5e-3)
    np.testing.assert_allclose(response.story_drift_m, ratio * STORY_HEIGHT_M, rtol=1e-14)


def test_superstructure_shear_is_the_floors_inertia(pts_building):
    """The first story's shear (spring + damper) equals Σ m_i a_i,abs (each floor's equilibrium); the coefficient is
    its resultant peak over W_s = g Σ m_i (not over W)."""
    response, _, _ = pts_building
    inertia = np.einsum("i,tid->td", FLOOR_MASS_KG, response.floor_absolute_acceleration_m_s2)
    np.testing.assert_allclose(response.superstructure_shear_N, -inertia, rtol=0,
                               atol=1e-9 * np.abs(inertia).max())
    sampled = np.max(np.hypot(inertia[:, 0], inertia[:, 1])) / (G * FLOOR_MASS_KG.sum())
    assert sampled * (1 - 1e-12) <= response.superstructure_shear_coefficient <= sampled * 1.005


# ---- the review's JSON, row by row ----------------------------------------------------------------------------


@pytest.fixture(scope="module")
def review(design, tmp_path_factory):
    """The example building reviewed as docs/review.md says (``horizontal_only``) over three pairs of the example
    suite (PTS, Landers YER, Loma Prieta APEEL2 whose vertical is left out), lower and upper bounds: the ELF does
    not depend on the suite, and with 3 < 7 analyses every suite value is the maximum (17.6.3.4)."""
    from isolator.review import load_suite, load_target, resolve_example, run_review

    folder = tmp_path_factory.mktemp("suite")
    (folder / "suite.toml").write_text(
        "[[pair]]\nname = \"PTS\"\n"
        f"x = \"{SUITE / 'superstitionhills1987_PTS' / 'RSN723_SUPER.B_B-PTS225.AT2'}\"\n"
        f"y = \"{SUITE / 'superstitionhills1987_PTS' / 'RSN723_SUPER.B_B-PTS315.AT2'}\"\ntrim = true\n"
        "[[pair]]\nname = \"YER\"\n"
        f"x = \"{SUITE / 'landers1992_YER' / 'RSN900_LANDERS_YER270.AT2'}\"\n"
        f"y = \"{SUITE / 'landers1992_YER' / 'RSN900_LANDERS_YER360.AT2'}\"\n"
        "[[pair]]\nname = \"APEEL2\"\ntrim = true\n"
        f"x = \"{SUITE / 'lomaprieta1989_APEEL2' / 'np01002p_4225a_a.smc'}\"\n"
        f"y = \"{SUITE / 'lomaprieta1989_APEEL2' / 'np01002p_4225c_a.smc'}\"\n"
        f"z = \"{SUITE / 'lomaprieta1989_APEEL2' / 'np01002p_4225b_a.smc'}\"\n")
    # the example's 1.4 m capacity is passed on PTS (1.574 / 1.477 m at the lower / upper bound): the 2-D building has
    # no rim, so those analyses say so and the rows over them are not checked; the hand values here are the rows'
    # over usable analyses, so the capacity is set beyond every peak (it enters no row checked below)
    result = run_review(dataclasses.replace(design, displacement_capacity_m=2.0),
                        load_target(resolve_example("target", "example")), load_suite(folder / "suite.toml"),
                        jobs=1, nominal=False, parameters={"horizontal_only": True})
    return result.to_dict()


def _row(review_json: dict, check_id: str) -> dict:
    (row,) = [r for r in review_json["checks"] if r["id"] == check_id]
    return row


def test_review_elf_values_equal_the_hand_values(review):
    assert {p["name"]: p["value"] for p in review["parameters"]}["Ws_over_W"] == pytest.approx(hand_ws_over_w(),
                                                                                            rel=1e-13)
    assert {p["name"]: p["value"] for p in review["parameters"]}["R_I"] == hand_r_i() == 2.0
    assert review["property_bounds"]["mu_upper"] == pytest.approx(MU_KINETIC * LAMBDA_MAX, rel=1e-13)
    assert review["property_bounds"]["mu_lower"] == pytest.approx(MU_KINETIC * LAMBDA_MIN, rel=1e-13)
    assert review["torsion"]["P_T"] == pytest.approx(hand_p_t(), rel=1e-12)
    assert review["torsion"]["factor"] == pytest.approx(hand_torsion_factor(), rel=1e-12)
    assert review["structure"]["T_fixed_s"] == pytest.approx(hand_fixed_base_periods_s()[0], rel=1e-10)
    for bound, lam in (("lower", LAMBDA_MIN), ("upper", LAMBDA_MAX)):
        hand, elf = hand_elf(MU_KINETIC * lam), review["elf"][bound]
        for key in ("D_M_m", "T_M_s", "beta_M", "V_b_over_W", "V_st_over_W", "V_s_over_W", "D_M_prime_m"):
            assert elf[key] == pytest.approx(hand[key], rel=1e-9), (bound, key)
        assert elf["D_TM_m"] == pytest.approx(hand["D_M_m"] * hand_torsion_factor(), rel=1e-9)
    # the numbers as printed: lower bound D_M = 0.6331 m, T_M = 3.601 s, β_M = 0.1239, V_s/W = 0.08392
    lower = hand_elf(MU_KINETIC * LAMBDA_MIN)
    assert (round(lower["D_M_m"], 4), round(lower["T_M_s"], 3), round(lower["V_s_over_W"], 5)) == (0.6331, 3.601,
                                                                                                   0.08392)


def test_review_building_rows_are_their_hand_values(review):
    """Each building row's value and limit, recomputed from the analyses' rows of the JSON and the hand ELF."""
    bounds = ("lower", "upper")
    pairs = {b: list(review["bounds"][b]["pairs"].values()) for b in bounds}
    assert all(len(rows) == 3 and all("error" not in r for r in rows) for rows in pairs.values())
    assert {r["model"] for b in bounds for r in pairs[b]} == {"2d-building"}
    elf = {"lower": hand_elf(MU_KINETIC * LAMBDA_MIN), "upper": hand_elf(MU_KINETIC * LAMBDA_MAX)}

    # 17.6.4.2: the RHA first-story shear over W_s × W_s/W ÷ R_I (fewer than 7 analyses: the maximum), larger bound
    rha = max(max(r["superstructure_shear_coefficient"] for r in pairs[b]) for b in bounds)
    row = _row(review, "superstructure_shear")
    assert row["value"] == pytest.approx(rha * hand_ws_over_w() / hand_r_i(), rel=1e-12)
    # limit: the largest of 0.6 V_s (the larger bound), 17.5.4.3(3): V_st with V_b = the activation force
    # max(µs upper, 1.5 µs nominal) W = max(0.089, 0.09) W, at each bound's β_M, and 17.5.4.3(1): the fixed-base
    # C_s W_s at T_M (12.8.1.1 with R = 8, I_e = 1, S_DS = 2/3 × 1.5 = 1.0 g, S_D1 = 2/3 × 0.9 = 0.6 g: at
    # T_M ≈ 3.1–3.6 s S_D1/(T R) = 0.021–0.024 < 0.044 S_DS I_e, so C_s = 0.044 by Eq. 12.8-5)
    activation = max(MU_STATIC * LAMBDA_MAX, 1.5 * MU_STATIC)
    v_st_activation = max(activation * hand_ws_over_w() ** (1 - 2.5 * elf[b]["beta_M"]) for b in bounds)
    s_ds, s_d1 = 2.0 / 3.0 * S_MS, 2.0 / 3.0 * S_M1
    c_s = {b: max(min(s_ds / R_SYSTEM, s_d1 / (elf[b]["T_M_s"] * R_SYSTEM)), 0.044 * s_ds, 0.01) for b in bounds}
    assert c_s["lower"] == c_s["upper"] == pytest.approx(0.044)
    fixed_base = max(c_s.values()) * hand_ws_over_w()
    limit = max(0.6 * max(elf[b]["V_s_over_W"] for b in bounds), v_st_activation, fixed_base)
    assert row["limit"] == pytest.approx(limit, rel=1e-9) and limit == pytest.approx(v_st_activation, rel=1e-12)
    assert row["status"] == ("pass" if row["value"] >= limit else "fail") and row["unit"] == "V/W"
    # 17.5.4.3(1) on its own row: the ELF V_s/W with the smaller margin (the upper bound's) ≥ C_s W_s/W
    row = _row(review, "V_s_fixed_base_limit")
    assert row["limit"] == pytest.approx(fixed_base, rel=1e-12)
    assert row["value"] == pytest.approx(min(elf[b]["V_s_over_W"] for b in bounds), rel=1e-9)
    assert row["status"] == "pass"

    # 17.6.4.4: the largest story's drift ratio (max over the pairs, larger bound)
    drift = max(max(max(r["story_drift_ratio"]) for r in pairs[b]) for b in bounds)
    row = _row(review, "story_drift")
    assert row["value"] == pytest.approx(drift, rel=1e-12) and row["limit"] == 0.020 and row["unit"] == "h_sx"
    for r in pairs["upper"]:
        np.testing.assert_allclose(r["story_drift_m"], np.array(r["story_drift_ratio"]) * STORY_HEIGHT_M, rtol=1e-13)

    # 17.2.4.7: the least bearing load (the smallest over the pairs, the smaller bound) under 2.3.6's minimum
    # combination (0.9 − 0.2 S_MS) D − E_h = 0.6 D − E_h: the history's minimum W/20 − E_h shifted by −0.4 W/20
    # (no vertical analysed, so E_v = 0.2 S_MS D applies; every share is W/20)
    share = TOTAL_MASS_KG * G / 20
    least = min(min(min(r["bearing_axial_load_min_N"]) for r in pairs[b]) for b in bounds)
    row = _row(review, "uplift")
    assert row["value"] == pytest.approx(least + (0.9 - 0.2 * S_MS - 1.0) * share, rel=1e-12) and row["unit"] == "N"
    assert row["status"] == ("pass" if row["value"] >= 0 else "fail")
    assert f"unfactored least load {least:.4g} N" in row["note"]

    # 17.2.4.6: the largest bearing load (the largest over the pairs, larger bound) under (1.2 + 0.2 S_MS) D + E_h
    # = 1.5 D + E_h, over its capacity 12 MN
    most = max(max(max(r["bearing_axial_load_max_N"]) for r in pairs[b]) for b in bounds)
    row = _row(review, "vertical_load_stability")
    assert row["value"] == pytest.approx((most + (1.2 + 0.2 * S_MS - 1.0) * share) / AXIAL_CAPACITY_N, rel=1e-12)
    assert row["limit"] == 1.0 and f"unfactored {most:.4g} N" in row["note"]
    # every bearing's gravity share is W/20: the extremes straddle it by the overturning of the same analysis
    for r in pairs["lower"] + pairs["upper"]:
        share = TOTAL_MASS_KG * G / 20
        assert all(lo < share < hi for lo, hi in zip(r["bearing_axial_load_min_N"], r["bearing_axial_load_max_N"],
                                                     strict=True))

    # 17.6.4.1 with Eq. 17.6-1: the RHA total displacement ≥ 0.8 D'_TM, D'_TM = D'_M × the torsion factor
    row = _row(review, "D_TM_elf_floor")
    assert row["limit"] == pytest.approx(0.8 * max(elf[b]["D_M_prime_m"] for b in bounds) * hand_torsion_factor(),
                                         rel=1e-9)
    d_rha = max(max(r["peak_displacement_m"] for r in pairs[b]) for b in bounds)
    assert row["value"] == pytest.approx(d_rha * hand_torsion_factor(), rel=1e-12)

    # floor accelerations: reported, never a verdict
    row = _row(review, "floor_acceleration")
    peak = max(max(max(r["floor_peak_acceleration_m_s2"]) for r in pairs[b]) for b in bounds)
    assert row["status"] == "not checked" and row["value"] == pytest.approx(peak, rel=1e-12)
    assert row["unit"] == "m/s²"


def test_review_notes_say_what_the_rows_computed(review, design):
    """What an engineer reads beside a pass: the bearing loads are unfactored (the design cannot carry factored
    loads: its gravity loads must add up to W), the left-out vertical is said, the spectra's peaks are the continuous
    response's (issue 26), not the samples'."""
    from isolator.errors import DesignError
    from isolator.superstructure import parse_bearing_layout

    stability = _row(review, "vertical_load_stability")  # factored by 2.3.6 [U], the factors said
    assert "factored (2.3.6 [U]): max 1.5 D + E_h, min 0.6 D − E_h" in stability["note"]
    assert "no vertical analysed, so E_v is applied" in stability["note"] and "not applied [U]" not in stability["note"]
    assert "are the engineer's gravity_load_N" not in stability["note"]
    share = TOTAL_MASS_KG * G / 20  # 1.2 × the share on every bearing (a factored dead load) is refused
    with pytest.raises(DesignError, match="add up to"):
        parse_bearing_layout([{"x_m": x, "y_m": y, "gravity_load_N": 1.2 * share}
                              for x, y in zip(BEARING_X_M, BEARING_Y_M, strict=True)], TOTAL_MASS_KG * G)
    uplift = _row(review, "uplift")
    assert "factored (2.3.6 [U])" in uplift["note"] and "not applied [U]" not in uplift["note"]
    assert "the verticals of 1 pair(s) not analysed (horizontal_only)" in uplift["note"]
    assert "no vertical components" not in uplift["note"]
    assert "between samples included" in review["spectrum_conventions"]
    assert "sample instants" not in review["spectrum_conventions"]


def test_the_docs_table_of_the_example_is_the_hand_values():
    """docs/review.md prints the example building's ELF inputs: each figure there is the hand value, rounded."""
    text = (ROOT / "docs" / "review.md").read_text(encoding="utf-8")
    lower, upper = hand_elf(MU_KINETIC * LAMBDA_MIN), hand_elf(MU_KINETIC * LAMBDA_MAX)
    figures = [f"| W_s/W | {hand_ws_over_w():.4f} |", f"| R_I | {hand_r_i():g} |",
               f"| T (fixed base) | {hand_fixed_base_periods_s()[0]:.4f} s |", f"| P_T | {hand_p_t():.3f} |",
               f"| D_TM/D_M | {hand_torsion_factor():.3f} |"]
    for elf, mu in ((lower, "lower µ 0.03825"), (upper, "upper µ 0.07418")):
        assert f"{MU_KINETIC * (LAMBDA_MIN if mu.startswith('lower') else LAMBDA_MAX):.4g}" in mu
        figures.append(f"({mu}) | {elf['D_M_m']:.4f} m, {elf['T_M_s']:.3f} s, {elf['beta_M']:.4f} |")
        figures.append(f"| {elf['V_b_over_W']:.4f}, {elf['V_st_over_W']:.4f}, {elf['V_s_over_W']:.5f} |")
    figures.append(f"| {lower['D_M_prime_m']:.4f} m, {upper['D_M_prime_m']:.4f} m |")
    for figure in figures:
        assert figure in text, figure


def _keys(node, out: set, named: bool = False) -> set:
    """Every key of a JSON tree, but the names that are data (pairs, paths, parameter overrides)."""
    if isinstance(node, dict):
        for key, value in node.items():
            if not named:
                out.add(key)
            _keys(value, out, named=key in ("pairs", "inputs", "scale_factors", "parameter_overrides", "files",
                                            "components", "samples") and isinstance(value, dict))
    elif isinstance(node, list):
        for item in node:
            _keys(item, out)
    return out


def test_every_key_of_the_review_json_is_documented(review):
    """docs/schema.md names every key the example building's review writes (the classification keys by their
    ``<field>_record`` / ``<field>_harmonic`` stem)."""
    text = (ROOT / "docs" / "schema.md").read_text(encoding="utf-8")
    missing = sorted(key for key in _keys(review, set())
                     if f"`{key}`" not in text
                     and not (key.rsplit("_", 1)[-1] in ("record", "harmonic") and f"`{key.rsplit('_', 1)[0]}`" in text))
    assert not missing, missing


def test_the_energy_history_starts_at_zero(pts_building):
    """Sample 0's energies are 0 (the kernel writes from sample 1 on; they were np.empty memory: a run of the
    example building under Hector Mine ABY said "the state became non-finite: no result" in 4 fresh processes of 5)."""
    response, _, _ = pts_building
    assert np.all(response.energy_history_J_per_kg[:, 0] == 0.0)
    assert response.message == "ok" and np.all(np.isfinite(response.energy_history_J_per_kg))


def test_the_isolator_force_never_exceeds_its_physical_bound(design):
    """|F_isolator| ≤ K |X| + µs W (no dashpot): the spring and at most the static friction. The example building
    under Hector Mine ABY × 1.568 (the review's common factor), nominal µ 0.06/0.05, first 15.1 s: peak X = 0.048 m
    gives ≤ (0.048/4 + 0.06) W = 0.072 W."""
    from isolator.motion.read import read_ground_motion
    from isolator.solver.planar_building import simulate_planar_building

    x = read_ground_motion(SUITE / "hectormine1999_ABY" / "RSN1762_HECTOR_ABY090.AT2")
    y = read_ground_motion(SUITE / "hectormine1999_ABY" / "RSN1762_HECTOR_ABY360.AT2")
    factor, n = 1.5680289956125797, 756
    response = simulate_planar_building(
        factor * x.acceleration_m_s2[:n], factor * y.acceleration_m_s2[:n], x.dt_s,
        superstructure=design.superstructure, total_mass_kg=TOTAL_MASS_KG, stiffness_N_per_m=TOTAL_MASS_KG * G / RADIUS_M,
        mu_static=MU_STATIC, mu_kinetic=MU_KINETIC, bearing_layout=design.bearing_layout)
    bound = response.peak_displacement_m / RADIUS_M + MU_STATIC
    sampled = np.max(np.hypot(*response.isolator_force_N.T)) / (TOTAL_MASS_KG * G)
    assert sampled <= bound  # the samples respect it (0.063 W) ...
    assert response.base_shear_coefficient <= bound * (1 + 1e-9)  # ... and the exact peak (0.142 W before the stop fix)


def test_an_analysis_its_solver_flagged_is_said_in_the_notes(design, tmp_path):
    """A result whose solver_status is not "ok" (chatter guard, unfinished interval) enters the suite values as it is;
    the review's notes (page 1 of the PDF) say which analysis and what the solver said — it was silent. The
    analyses come from a recording cache, then are served again with one flagged."""
    from isolator.review import load_suite, load_target, resolve_example, run_review

    class Recorder:
        def __init__(self):
            self.entries = {}

        def get(self, key):
            return self.entries.get(key)

        def put(self, key, result):
            self.entries[key] = result

    (tmp_path / "suite.toml").write_text(
        "[[pair]]\nname = \"PTS\"\ntrim = true\n"
        f"x = \"{SUITE / 'superstitionhills1987_PTS' / 'RSN723_SUPER.B_B-PTS225.AT2'}\"\n"
        f"y = \"{SUITE / 'superstitionhills1987_PTS' / 'RSN723_SUPER.B_B-PTS315.AT2'}\"\n")
    suite = load_suite(tmp_path / "suite.toml")
    target = load_target(resolve_example("target", "example"))
    cache = Recorder()
    clean = run_review(design, target, suite, jobs=1, nominal=False, analysis_cache=cache)
    assert not any("its solver says" in note for note in clean.notes)
    key = sorted(cache.entries)[0]
    cache.entries[key] = {**cache.entries[key],
                          "solver_status": "chatter guard: more than 1000 events in one sample interval"}
    flagged = run_review(design, target, suite, jobs=1, nominal=False, analysis_cache=cache)
    said = [note for note in flagged.notes if "its solver says: chatter guard" in note]
    assert len(said) == 1 and "'PTS'" in said[0]
