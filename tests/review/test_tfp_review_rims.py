"""A TFP review on real pairs that reach the rims in the plane completes (issue 23).

Fenz & Constantinou's triple pendulum with its outer capacities cut to 0.2 m (ultimate 0.5 m), two short real
pairs of the bundled suite scaled to the target: the analyses run on ``2d-multisurface`` with the rims (the
implicit steps; the event-driven kernel has none), and the review reads their rim keys: an analysis held at the
ultimate fails ``record_capacity`` with its impulse, the capacity is the bearing's ultimate.  Before the rims in
the plane this review stopped in one line at the first rim contact.
"""

from __future__ import annotations

import pytest

from isolator.design import Design
from isolator.review.run import run_review
from isolator.review.suite import load_suite
from isolator.review.target import two_period_target
from tests.review.conftest import EXAMPLE

SURFACES = [{"radius_m": 2.1, "mu": 0.06, "displacement_capacity_m": 0.2},
            {"radius_m": 0.3, "mu": 0.02, "displacement_capacity_m": 0.05},
            {"radius_m": 0.3, "mu": 0.02, "displacement_capacity_m": 0.05},
            {"radius_m": 2.1, "mu": 0.10, "displacement_capacity_m": 0.2}]
PAIRS = [("superstitionhills1987_PTS", "RSN723_SUPER.B_B-PTS225.AT2", "RSN723_SUPER.B_B-PTS315.AT2"),
         ("duzce1999_DZC", "RSN1605_DUZCE_DZC180.AT2", "RSN1605_DUZCE_DZC270.AT2")]


@pytest.fixture(scope="module")
def tfp_review(tmp_path_factory):
    folder = tmp_path_factory.mktemp("tfp_rims")
    body = ""
    for name, x, y in PAIRS:
        if not (EXAMPLE / name / x).is_file():
            pytest.skip(f"the bundled suite has no {name}/{x}")
        body += f'[[pair]]\nname = "{name}"\nx = "{EXAMPLE / name / x}"\ny = "{EXAMPLE / name / y}"\ntrim = true\n'
    (folder / "suite.toml").write_text(body)
    design = Design.from_mapping({"name": "tfp", "mass_kg": 1.0e6, "lambda_max": 1.2, "lambda_min": 0.85,
                                  "bearing": {"type": "triple", "surface": SURFACES}})
    return design, run_review(design, two_period_target(1.5, 0.9, 8.0), load_suite(folder / "suite.toml"), jobs=1,
                              nominal=False, parameters={"n_for_mean": 3})


def test_a_tfp_review_over_real_pairs_reaching_the_rims_completes(tfp_review):
    design, r = tfp_review
    analyses = [a for b in r.analyses for a in r.analyses[b].values()]
    assert len(analyses) == 2 * len(PAIRS)  # every pair at both bounds: none left out
    assert {a["model"] for a in analyses} == {"2d-multisurface"}
    on_rims = [a for a in analyses if a["n_rim_contacts"] > 0]
    assert on_rims and all("rim" in a["model_reason"] for a in on_rims)
    ultimate = design.bearing.ultimate_displacement_m  # 0.5 m
    for a in analyses:
        # never past the ultimate, the outer surfaces within their capacities (the inner ones carry the series
        # model's element rims: exact when aligned, docs/multisurface.md)
        assert a["peak_displacement_m"] <= ultimate * (1 + 1e-12)
        for i in (0, 3):
            assert a["surface_peak_displacement_m"][i] <= SURFACES[i]["displacement_capacity_m"] * (1 + 1e-12)
        # the energy balance closes with the impacts counted (the steps' numerical dissipation left: ≤ 1e-6)
        assert abs(a["energy_balance_error_J_per_kg"]) <= 1e-6 * a["energy_input_J_per_kg"]
    reached = [(b, name) for b in r.analyses for name, a in r.analyses[b].items() if a["ultimate_displacement_reached"]]
    assert reached  # the scaled pairs drive the bearing to its ultimate
    assert all(r.analyses[b][n]["impact_impulse_m_s"] > 0.0 for b, n in reached)
    rows = {row["id"]: row for row in r.checks}
    assert rows["D_M_capacity"]["limit"] == pytest.approx(ultimate, rel=1e-12)
    failing = [row for row in r.checks if row["id"] == "record_capacity" and row["status"] == "fail"]
    assert {(row["bound"], row["pair"]) for row in failing} >= set(reached)
    assert all("N·s" in row["note"] for row in failing if (row["bound"], row["pair"]) in set(reached))
