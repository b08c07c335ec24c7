"""h227's signer audit, its 'noticed and left alone' taken up (h229): Table 17.5-1's last entry a printed parameter,
the design-search column of the superstructure shear said as what it is, a candidate's name that does not print the
base design's numbers as its own, and the [plan] eccentricity beside the bearing layout's said in the torsion basis.
Each test fails on c765efa (said in its docstring)."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from isolator.design import NAME_MAX_CHARS, Design
from isolator.review import parameters as P
from isolator.review.codes import asce7_22
from isolator.review.target import two_period_target

ROOT = Path(__file__).resolve().parents[2]
G = 9.80665


def _b_m_by_hand(beta: float, at_50: float) -> float:
    """Table 17.5-1 between 30 % and 50 % written out: 1.7, 1.9 at 40 %, ``at_50`` at 50 % and beyond."""
    if beta >= 0.5:
        return at_50
    if beta >= 0.4:
        return 1.9 + (at_50 - 1.9) * (beta - 0.4) / 0.1
    return 1.7 + 0.2 * (beta - 0.3) / 0.1


def test_b_m_at_50pct_is_a_printed_parameter_that_decides_b_m_above_40pct():
    """B_M at β ≥ 50 % was hard-coded 2.0, neither printed nor overridable, though P1 stops at 1.9 (REVIEW_RULES 1.9).
    Now ``B_M_at_50pct`` [S]: default 2.0, in the parameter table every review prints, 1.9 settable.  A pendulum of
    µ 0.2, R 2.5 m under S_M1 = 1.0 g (T_S ≤ T_M ≤ T_L: S_a T² = S_M1 T) has β_M ≈ 0.44; its D_M is the fixed point
    D = g S_M1 T(D) / (4π² B(β(D))), T = 2π/√(g/R + µg/D), β = 2µ/(π(µ + D/R)), found here by bisection with the
    table by hand.  On c765efa: 'unknown review parameter B_M_at_50pct'."""
    from isolator.review.run import elf_values

    values = P.resolve("asce7-22", {"B_M_at_50pct": "1.9"})
    assert values["B_M_at_50pct"] == 1.9 and P.resolve("asce7-22")["B_M_at_50pct"] == 2.0
    row = next(r for r in P.table("asce7-22", P.resolve("asce7-22")) if r["name"] == "B_M_at_50pct")
    assert row["value"] == 2.0 and row["mark"] == "S" and "Table 17.5-1" in row["rule"]
    with pytest.raises(Exception, match="B_M_at_50pct' = 2.1 is outside"):
        P.resolve("asce7-22", {"B_M_at_50pct": 2.1})

    design = Design.from_mapping({"name": "h", "mass_kg": 1000.0, "radius_m": 2.5, "mu_static": 0.2})
    target = two_period_target(1.5, 1.0, 8.0)
    for at_50 in (2.0, 1.9):
        def gap(d, at_50=at_50):
            t = 2 * math.pi / math.sqrt(G / 2.5 + 0.2 * G / d)
            beta = 2 * 0.2 / (math.pi * (0.2 + d / 2.5))
            return G * 1.0 * t / (4 * math.pi ** 2 * _b_m_by_hand(beta, at_50)) - d

        lo, hi = 0.1, 0.5
        assert gap(lo) > 0 > gap(hi)
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if gap(mid) > 0 else (lo, mid)
        elf = elf_values(design, 0.2, target, "asce7-22", {**P.resolve("asce7-22"), "B_M_at_50pct": at_50})
        assert elf["D_M_m"] == pytest.approx(lo, rel=1e-9) and 0.4 < elf["beta_M"] < 0.5
        assert elf["B_M"] == pytest.approx(_b_m_by_hand(elf["beta_M"], at_50), rel=1e-12)
        assert any(f"B_M_at_50pct = {at_50:g}" in note for note in elf["notes"])
    # below 40 % the parameter decides nothing
    assert asce7_22.damping_coefficient(0.35, 1.9) == asce7_22.damping_coefficient(0.35) == pytest.approx(1.8)


def test_design_search_doc_says_the_superstructure_column_is_the_response_history_value():
    """docs/design_search.md described `superstructure_shear_over_W` as "today the ELF V_s/W"; the column is the
    `superstructure_shear` row's value (design_workers.candidate_row), which is the RHA shear ÷ R_I and never the ELF
    V_s (checks.superstructure_shear: the ELF value is on the limit side).  On c765efa the doc's row says 'ELF V_s/W'
    as the value."""
    from isolator.review import checks as C

    row = C.superstructure_shear(0.11, 0.6, 0.2, r_i=2.0)
    assert row["value"] == pytest.approx(0.1) and row["limit"] == pytest.approx(0.066)
    doc = (ROOT / "docs" / "design_search.md").read_text()
    line = next(x for x in doc.splitlines() if x.startswith("| `superstructure_shear_over_W`"))
    assert "today the ELF" not in line and "response-history superstructure shear / W ÷ R_I" in line


def test_a_candidate_name_says_its_values_first_not_the_base_numbers():
    """The recommended design was named "FPS R = 4.0 m … [radius_m=4.5, mu_kinetic=0.06]": every page of its review
    read R = 4.0 m.  Now "[radius_m=4.5, mu_kinetic=0.09, mu_static=0.105] varied from the base design: FPS R = 4.0 m
    …" — the values first, µs that followed µk included (0.07 × 0.09/0.06).  The name is no identifier (candidates
    are keyed by content); a base name of NAME_MAX_CHARS still makes a valid candidate.  On c765efa: ImportError of
    ``candidate_name``."""
    from isolator.review.design_grid import candidate_mappings, candidate_name

    base = tomllib.loads((ROOT / "data" / "example_design.toml").read_text())
    mappings = candidate_mappings(base, base["mu_kinetic"], [("radius_m", [4.5]), ("mu_kinetic", [0.06, 0.09])])
    names = [candidate_name(base, m, {"radius_m": m["radius_m"], "mu_kinetic": m["mu_kinetic"]}) for m in mappings]
    assert names[0] == f"[radius_m=4.5, mu_kinetic=0.06] varied from the base design: {base['name']}"
    assert names[1] == f"[radius_m=4.5, mu_kinetic=0.09, mu_static=0.105] varied from the base design: {base['name']}"
    assert Design.from_mapping({**mappings[1], "name": names[1]}).name == names[1]
    long_base = {**base, "name": "B" * NAME_MAX_CHARS}
    name = candidate_name(long_base, mappings[1], {"radius_m": 4.5, "mu_kinetic": 0.09})
    assert Design.from_mapping({**mappings[1], "name": name}).name == name
    with pytest.raises(Exception, match="more than a design's name may be"):
        Design.from_mapping({**mappings[1], "name": "B" * (NAME_MAX_CHARS + 1)})


def test_the_torsion_basis_says_which_eccentricity_it_used_and_by_how_much_the_layout_differs():
    """The example building gives [plan] eccentricity_m = 0.5 m and 20 bearings of equal load placed symmetrically
    about the centre of mass: the layout's centre of rigidity (a pendulum's stiffness ∝ its load: the load-weighted
    centroid, computed here from the file) is at the centre of mass.  Eq. 17.5-3 uses the plan's 0.5 m (1.169); with
    the layout's 0 m it would be 1 + 16/P_T² × 12 × 0.05 × 34/(34² + 26²) = 1.131 → the floor 1.15.  The review's
    basis (in D_TM_capacity's note, the ELF page) and page 1's Plan line now say so; on c765efa they said nothing
    (ImportError of ``eccentricity_said``; without it, KeyError 'eccentricity_layout_m')."""
    from isolator.report.review_pages import eccentricity_said
    from isolator.superstructure import review_inputs

    design = Design.from_toml(ROOT / "data" / "example_building.toml")
    raw = tomllib.loads((ROOT / "data" / "example_building.toml").read_text())["bearing_position"]
    loads = np.array([b.get("gravity_load_N", 9.3e6 * G / len(raw)) for b in raw])  # the file: equal shares of W
    xc = float(np.dot(loads, [b["x_m"] for b in raw]) / loads.sum())
    yc = float(np.dot(loads, [b["y_m"] for b in raw]) / loads.sum())
    out = asce7_22.torsion_factor(design.plan, P.resolve("asce7-22"), review_inputs(design))
    assert out["eccentricity_layout_m"] == pytest.approx([abs(yc), abs(xc)], abs=1e-12)
    assert out["eccentricity_difference_m"] == pytest.approx(0.5 - min(abs(xc), abs(yc)), abs=1e-12)
    x = np.array([b["x_m"] for b in raw])
    y = np.array([b["y_m"] for b in raw])
    p_t = math.sqrt(np.mean(x * x + y * y)) / math.sqrt((34.0 ** 2 + 26.0 ** 2) / 12)
    with_layout = max(1 + (16.0 / p_t ** 2) * 12 * (abs(xc) + 0.05 * 34) / (34 ** 2 + 26 ** 2),
                      1 + (12.0 / p_t ** 2) * 12 * (abs(yc) + 0.05 * 26) / (34 ** 2 + 26 ** 2), 1.15)
    assert out["factor_with_layout_eccentricity"] == pytest.approx(with_layout, rel=1e-12) == 1.15
    assert out["factor"] == pytest.approx(1.16923, rel=1e-5)
    assert "e = 0.5 m from [plan] eccentricity_m (used)" in out["basis"] and "disagree by 0.5 m" in out["basis"]
    assert "D_TM/D_M = 1.15 (the floor)" in out["basis"]
    assert "0.5 m apart" in eccentricity_said(out)
    agreeing = asce7_22.torsion_factor({**design.plan, "eccentricity_m": 0.0}, P.resolve("asce7-22"),
                                       review_inputs(design))
    assert "they agree" in agreeing["basis"] and eccentricity_said(agreeing) == ""
    no_layout = asce7_22.torsion_factor(design.plan, P.resolve("asce7-22"), {})
    assert "eccentricity_difference_m" not in no_layout and "[plan] eccentricity_m" not in no_layout["basis"]
