"""A double and a triple pendulum's review, read as its signer reads it (session 17).

* 17.5.4.3(3)'s activation note named "regime III of a triple" on a double, whose backbone has no regime III
  (its regimes are 1, 1+2, 1: the largest compliance is 1+2, both surfaces sliding, from F/W = µ_2).
* The paper's dimensionless point (Appendix A: α = PGA/(µ g), k = A0/R) of a double or triple is taken on the
  regime each motion reached (isolator.adapter.dimensionless_point): the review says which, pair by pair, and
  never mixes regimes in one median (the design tool's columns).
* The uplift row (17.2.4.7) on a tall narrow building that lifts and on a wide one that does not.
"""

from __future__ import annotations

import pytest

from isolator.design import Design
from isolator.review.codes import asce7_22
from isolator.review.run import run_review
from isolator.review.suite import load_suite
from isolator.review.target import two_period_target

TARGET = two_period_target(1.5, 0.9, 8.0)


def _double(lam: bool = True) -> Design:
    extra = {"lambda_max": 1.3, "lambda_min": 0.8} if lam else {}
    return Design.from_mapping({"name": "double", "mass_kg": 1.0e6, **extra, "bearing": {"type": "double", "surface": [
        {"radius_m": 2.0, "mu": 0.04, "displacement_capacity_m": 0.5},
        {"radius_m": 2.5, "mu": 0.07, "displacement_capacity_m": 0.5}]}})


def _triple() -> Design:
    return Design.from_mapping({"name": "tfp", "mass_kg": 1.0e6, "lambda_max": 1.3, "lambda_min": 0.8,
                                "bearing": {"type": "triple", "surface": [
                                    {"radius_m": r, "mu": m, "displacement_capacity_m": d} for r, m, d in
                                    zip((2.1, 0.3, 0.3, 2.1), (0.06, 0.02, 0.02, 0.10), (0.8, 0.05, 0.05, 0.8),
                                        strict=True)]}})


def test_the_activation_regime_is_named_for_the_bearing_type():
    """The 'outer' reading of 17.5.4.3(3) starts where the backbone's compliance is largest: a double's regime 1+2
    (both surfaces, from F/W = µ_2 = 0.07: the line x/(R1 + R2) + µ_2 meets the first surface's at x = (µ2 − µ1) R1),
    a triple's regime III (from µ_4 = 0.10)."""
    double, triple = _double(), _triple()
    assert asce7_22.activation_regime(double) == "regime 1+2 of the double (both surfaces slide)"
    assert asce7_22.activation_force_per_weight(double) == pytest.approx(0.07, rel=1e-15)
    assert asce7_22.activation_regime(triple) == "regime III of the triple (both outer surfaces slide)"
    assert asce7_22.activation_force_per_weight(triple) == pytest.approx(0.10, rel=1e-15)
    assert asce7_22.activation_regime(Design.from_mapping({"name": "fps", "mass_kg": 1e6, "radius_m": 2.5,
                                                           "mu_static": 0.05})) == ""


@pytest.fixture(scope="module")
def double_review(inputs):
    return run_review(_double(), TARGET, load_suite(inputs / "suite.toml"), jobs=1, nominal=False)


def test_the_activation_note_of_a_double_names_its_own_regime(double_review):
    row = next(r for r in double_review.checks if r["id"] == "V_s_activation_limit")
    assert "regime 1+2 of the double (both surfaces slide)" in row["note"]
    assert "regime III" not in row["note"] and "triple" not in row["note"]
    # V_b = max(1.3 × 0.07, 1.5 × 0.07) W = 0.105 W (the backbone's force at the start of 1+2, upper / nominal)
    assert "W = 0.105 W" in row["note"]


G = 9.80665


def _line(regime: str, lam: float) -> tuple[float, float]:
    """(R, µ) of the double's backbone line, written out: surface 1 alone F/W = x/R1 + µ1; both sliding
    F/W = x/(R1 + R2) + (µ1 R1 + µ2 R2)/(R1 + R2) (x = R1 (F − µ1) + R2 (F − µ2))."""
    r1, r2, mu1, mu2 = 2.0, 2.5, 0.04 * lam, 0.07 * lam
    return (r1, mu1) if regime == "1" else (r1 + r2, (mu1 * r1 + mu2 * r2) / (r1 + r2))


def test_a_doubles_point_entering_only_surface_1_is_on_surface_1():
    """The double's backbone is 1, 1+2, then 1 again past surface 2's rim (x = 0.96 m): the point of a motion that
    entered only '1' was put on regime 1+2 (R 4.5 m) because the name '1' matched the regime past the rim too
    (Hector Mine ABY, upper bound, /tmp/h165/double.toml: k 0.01364 = A0/4.5 instead of A0/2.0)."""
    bearing = _double().bearing
    assert bearing.backbone().regimes == ("1", "1+2", "1")
    name, radius, mu, reason = bearing.point_regime({"1": 6.14})
    assert (name, radius, mu) == ("1", 2.0, pytest.approx(0.04, rel=1e-14))
    assert "reached regime 1 (first at 6.14 s)" in reason
    name, radius, mu, _ = bearing.point_regime({"1": 1.0, "1+2": 3.0, "2": 5.0})
    assert (name, radius, mu) == ("1+2", pytest.approx(4.5, rel=1e-14), pytest.approx(_line("1+2", 1.0)[1], rel=1e-14))


def test_appendix_a_of_a_double_says_which_regime_each_point_stands_on(double_review, tmp_path):
    import pypdf

    from isolator.report.review_pages import write_review_pdf

    r = write_review_pdf(double_review, tmp_path / "double.pdf")
    seen = set()
    for bound, lam in (("lower", 0.8), ("upper", 1.3)):
        for name, a in r["bounds"][bound]["pairs"].items():
            on = "1+2" if "1+2" in a["regimes"] else "1"  # both surfaces slid, else surface 1 only
            radius, mu = _line(on, lam)
            a0 = a["pgv_m_s"] ** 2 / a["pga_m_s2"]
            assert a["point_regime"] == on, (bound, name)
            assert a["mu_s"] == pytest.approx(mu, rel=1e-13)
            assert a["k"] == pytest.approx(a0 / radius, rel=1e-13)
            assert a["alpha"] == pytest.approx(a["pga_m_s2"] / (mu * G), rel=1e-13)
            seen.add(on)
    text = " ".join(" ".join(page.extract_text().split()) for page in pypdf.PdfReader(tmp_path / "double.pdf").pages)
    appendix = text[text.index("Appendix A"):]
    assert "α = PGA/(µ g) and k = A0/R on the line F/W = x/R + µ of the backbone regime each motion reached" in appendix
    assert "on (lo)" in appendix and "on (up)" in appendix and "#1 1+2 1+2" in appendix  # the short suite's: 1+2
    assert "not on an equivalent µs no analysis ran" in appendix
    assert "not drawn for a building or a double or triple bearing" in appendix
    assert "Right: the paper's (k, α) regime map" not in appendix  # no map is drawn: the caption said one was
    assert seen  # the regimes reached are the suite's, whichever they are


def test_the_design_searchs_paper_point_never_mixes_regimes():
    from isolator.review.design_workers import paper_regime

    points = [(0.1, 5.0, 0.0), (0.2, 7.0, 0.0), (0.3, 9.0, 0.0)]
    assert paper_regime([None, None, None], points) == (None, points)  # one surface: µs, every point
    assert paper_regime(["1+2"] * 3, points) == ("1+2", points)
    assert paper_regime(["1", "1+2", "1+2"], points) == ("mixed: 1 ×1, 1+2 ×2", [])  # no median across lines


# ---- 17.2.4.7: a tall narrow building lifts its bearings, a wide one does not --------------------------------------

def _tower(half_m: float) -> Design:
    """Six 4 m stories (0.4e6 kg each, 2e9 N/m) on a 0.6e6 kg base slab, four bearings at (±half, ±half) m."""
    floors = [{"mass_kg": 4.0e5, "story_height_m": 4.0, "stiffness_x_N_per_m": 2.0e9} for _ in range(6)]
    positions = [{"x_m": sx * half_m, "y_m": sy * half_m, "axial_capacity_N": 2.0e7} for sx in (-1, 1) for sy in (-1, 1)]
    return Design.from_mapping({"name": f"tower {half_m:g}", "mass_kg": 3.0e6, "radius_m": 3.0, "mu_static": 0.06,
                                "mu_kinetic": 0.05, "displacement_capacity_m": 2.0, "lambda_max": 1.3,
                                "lambda_min": 0.8, "plan": {"b_m": 2 * half_m, "d_m": 2 * half_m},
                                "superstructure": {"damping_ratio": 0.05, "response_modification_R": 8.0,
                                                   "floor": floors}, "bearing_position": positions})


@pytest.fixture(scope="module")
def towers(inputs):
    suite = load_suite(inputs / "suite.toml")
    return {half: run_review(_tower(half), TARGET, suite, jobs=1, nominal=False) for half in (3.0, 20.0)}


def test_the_uplift_row_of_a_tower_that_lifts_and_of_one_that_does_not(towers):
    """Three real pairs (fewer than n_for_mean 7: the suite value is the most unfavourable, the least load), no
    vertical: 2.3.6's minimum 0.9 D − E_v − E_h = (0.9 − 0.2 × 1.5) D − E_h = 0.6 D − E_h on each bearing's share
    D = W/4.  The note said 'max of 3 analyses' of a least load; it is the least of them."""
    share = 3.0e6 * G / 4
    for half, status in ((3.0, "fail"), (20.0, "pass")):
        r = towers[half]
        row = next(c for c in r.checks if c["id"] == "uplift")
        per = {(b, name): [low + (0.6 - 1.0) * share for low in a["bearing_axial_load_min_N"]]
               for b in ("lower", "upper") for name, a in r.analyses[b].items()}
        least = min(min(min(loads[k] for (b2, _), loads in per.items() if b2 == b) for k in range(4))
                    for b in ("lower", "upper"))
        lifted = [f"{name} ({b})" for (b, name), loads in per.items() if min(loads) < 0]
        assert row["status"] == status and row["value"] == pytest.approx(least, rel=1e-13)
        assert (least < 0) is (status == "fail")
        assert "least load, the least of 3 analyses per bound, the smaller bound" in row["note"]
        assert "max of 3" not in row["note"]
        assert f"{len(lifted)} analysis(es) lift a bearing" in row["note"]
        assert "min 0.6 D − E_h" in row["note"] and "no vertical analysed, so E_v is applied" in row["note"]
        assert "no vertical components in the suite" in row["note"]
        if lifted:
            assert f"({', '.join(lifted[:4])}" in row["note"]
        else:
            assert "lift a bearing (" not in row["note"]


def test_the_overturning_load_scales_as_one_over_the_lever_arm(towers):
    """Same floors, same friction, the bearings symmetric about the centre of mass: the horizontal response is the
    same, and each bearing's overturning load E_h = share − its least load varies as 1/half exactly (20/3)."""
    share = 3.0e6 * G / 4
    for b in ("lower", "upper"):
        for name, narrow in towers[3.0].analyses[b].items():
            wide = towers[20.0].analyses[b][name]
            assert narrow["peak_displacement_m"] == pytest.approx(wide["peak_displacement_m"], rel=1e-12)
            for lo3, lo20 in zip(narrow["bearing_axial_load_min_N"], wide["bearing_axial_load_min_N"], strict=True):
                assert (share - lo3) == pytest.approx((share - lo20) * 20.0 / 3.0, rel=1e-9)


def test_the_transmitted_row_names_its_analysis_and_an_impacts_force(inputs, monkeypatch):
    """/tmp/h165/double.toml over the example suite: transmitted_over_pga failed 1.469 > 1 on Chuetsu-oki 65025
    (lower), an analysis at the ultimate (its peak the plastic impact on the rims); the note named no analysis, and
    below the ultimate the largest was 0.359 (Landers YER, upper).  A fail stands; the note now says both."""
    from isolator.review import worker

    real = worker.analyse_task
    aby = next(p.ax_m_s2 for p in load_suite(inputs / "suite.toml").pairs if p.name == "hectormine1999_ABY")

    def analyse(task):  # ABY reaches the ultimate and transmits 2 × its PGA (an impact)
        result = real(task)
        if task["ax"].shape == aby.shape and (task["ax"] == aby).all():
            return {**result, "ultimate_displacement_reached": True, "impact_impulse_m_s": 0.25,
                    "transmitted_over_pga": 2.0 + result["transmitted_over_pga"]}
        return result

    monkeypatch.setattr(worker, "analyse_task", analyse)
    design = Design.from_mapping({"name": "fps", "mass_kg": 1.0e6, "radius_m": 2.5, "mu_static": 0.06,
                                  "mu_kinetic": 0.05, "displacement_capacity_m": 5.0, "lambda_max": 1.3,
                                  "lambda_min": 0.8})
    r = run_review(design, TARGET, load_suite(inputs / "suite.toml"), jobs=1, nominal=False)
    row = next(c for c in r.checks if c["id"] == "transmitted_over_pga")
    below = max((a["transmitted_over_pga"], f"{name} ({b})") for b in ("lower", "upper")
                for name, a in r.analyses[b].items() if name != "hectormine1999_ABY")
    top = max(("lower", "upper"), key=lambda b: r.analyses[b]["hectormine1999_ABY"]["transmitted_over_pga"])
    assert row["status"] == "fail" and row["value"] == r.analyses[top]["hectormine1999_ABY"]["transmitted_over_pga"]
    assert (f": hectormine1999_ABY ({top}), which reached the bearing's ultimate displacement (its peak is the plastic "
            "impact on the rims") in row["note"]
    assert f"below the ultimate the largest is {below[0]:.4g} ({below[1]})" in row["note"]


def test_the_transmitted_row_names_its_analysis(review):
    row = next(c for c in review.checks if c["id"] == "transmitted_over_pga")
    value, name = max((a["transmitted_over_pga"], f"{name} ({b})") for b, results in review.analyses.items()
                      for name, a in results.items())
    assert row["value"] == value and f"any bound: {name}" in row["note"]


def test_the_single_record_report_of_a_double_names_its_surfaces_not_only_the_equivalent(inputs, tmp_path):
    """`isolator report` of /tmp/h165/double.toml printed 'pendulum R = 4.5 m, µs = 0.05667, µk = 0.05667': the
    every-surface-sliding equivalent, a pendulum no analysis ran, as if it were the isolator."""
    import numpy as np
    import pypdf

    from isolator.analysis import analyse
    from isolator.motion import GroundMotion
    from isolator.report.pair import write_pair_report

    pair = next(p for p in load_suite(inputs / "suite.toml").pairs if p.name == "hectormine1999_ABY")
    analysis = analyse(_double(lam=False), GroundMotion.from_array(np.asarray(pair.ax_m_s2), pair.dt_s))
    write_pair_report(analysis, tmp_path / "r.pdf")
    text = " ".join(" ".join(page.extract_text().split()) for page in pypdf.PdfReader(tmp_path / "r.pdf").pages)
    assert "isolator double: R_i = 2/2.5 m (equivalent R 4.5 m)" in text
    assert "friction µ_i = 0.04/0.07 (equivalent µ 0.05667: every surface sliding)" in text
    assert "pendulum R = 4.5 m" not in text


def test_the_parameters_say_what_a_double_or_triple_uses():
    from isolator.review import parameters as P

    table = {row["name"]: row for row in P.table("asce7-22", P.resolve("asce7-22", {}))}
    assert "a double or triple: × its lower bound's breakaway force / W" in table["weak_pga_fraction"]["meaning"]
    assert "a double's 1+2: both surfaces slide" in table["multisurface_activation"]["meaning"]
