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
