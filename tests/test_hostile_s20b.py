"""Session 19's sweep left seven findings standing (docs/security.md, "Session 19 sweep", its last list): a design
name of 100,000 characters read; an AT2 DT of 1e400 told "dt = 0 s"; `surface = [1, 2, 3, 4]` told "needs 4
entries"; a 2-D TFP rtol of 1e-14 called "looser"; an EN 15129 review printing an f_ae it does not read (and hiding
the η floor 0.55, an unverified value); a run-time setting given as text a TypeError; the superstructure shear row's
note saying only the governing limit (docs/security.md, "Session 20: session 19's leftovers").
"""

from __future__ import annotations

import math
import re
from types import SimpleNamespace

import pytest
from _records import at2_text
from typer.testing import CliRunner

from isolator.cli import app
from isolator.design import Design
from isolator.errors import DesignError

RUNNER = CliRunner()
DESIGN = 'name = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\n'
SINE = at2_text([0.1 * math.sin(2 * math.pi * i * 0.01) for i in range(200)])


def _one_line(result) -> str:
    assert result.exit_code == 2 and (result.exception is None or isinstance(result.exception, SystemExit))
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in result.output, result.stderr
    return lines[0]


# ---- 1. a design's name is bounded, and the bound said

def test_a_design_name_beyond_its_bound_is_refused_with_the_bound(tmp_path, monkeypatch):
    """e9efb0c read a 100,000-character name (it would head every table and report page)."""
    from isolator.design import NAME_MAX_CHARS, Design
    from isolator.errors import DesignError

    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(SINE)
    (tmp_path / "d.toml").write_text(DESIGN.replace('"FPS"', '"' + "N" * 100_000 + '"'))
    line = _one_line(RUNNER.invoke(app, ["simulate", "x.AT2", "--design", "d.toml"]))
    assert line == (f"error: d.toml: key 'name' is 100,000 characters long, more than a design's name may be "
                    f"({NAME_MAX_CHARS}): it heads tables and report pages; put longer text in 'description'")
    base = {"mass_kg": 1e6, "radius_m": 2.5, "mu_static": 0.06}
    assert Design.from_mapping({"name": "N" * NAME_MAX_CHARS, **base}).name == "N" * 200  # the bound itself is read
    with pytest.raises(DesignError, match="201 characters long"):
        Design.from_mapping({"name": "N" * 201, **base})
    # a search's or a grid's candidates append their values to a name at the bound: still read
    grid = "N" * 200 + " [radius_m=2.5, mu_static=0.06, bearing.surface.radius_m=3]"
    assert Design.from_mapping({"name": grid, **base}).name == grid
    with pytest.raises(DesignError, match="characters long"):  # a bracket of other words is the name's own
        Design.from_mapping({"name": "N" * 200 + " [version two]", **base})


# ---- 2. an AT2 DT beyond a float says so

@pytest.mark.parametrize("dt, words", [("1e400", "header DT=1e400 s overflows: beyond any number"),
                                       ("-1E+999", "header DT=-1E+999 s overflows"),
                                       ("1e-320", "header DT=1e-320 s underflows: below a float's smallest normal"),
                                       ("1e-400", "header DT=1e-400 s underflows")])
def test_an_at2_dt_beyond_a_float_names_the_overflow(tmp_path, monkeypatch, dt, words):
    """e9efb0c: DT=1e400 (float: inf, 0 Hz) and DT=1e-320 (a subnormal: 1/DT inf) said `time step dt = 0 s is not
    positive`; 1e-400 (float: 0.0) `header DT=0 s is not positive`."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "x.AT2").write_text(re.sub(r"DT=\s*\S+", f"DT= {dt}", SINE, count=1))
    line = _one_line(RUNNER.invoke(app, ["simulate", "x.AT2", "--mu-s", "0.05"]))
    assert line.startswith("error: x.AT2: PEER AT2: ") and words in line


# ---- 3. a [bearing]'s surfaces of the wrong kind are told so

@pytest.mark.parametrize("surface, words", [
    ("surface = [1, 2, 3, 4]", "bearing surface 1 must be a table ([[bearing.surface]] with radius_m, mu_kinetic, …), "
                               "got an integer (1)"),
    ('surface = "x"', "key 'bearing.surface' must be an array of tables, one [[bearing.surface]] per surface (a "
                      "triple bearing has 4), got a text ('x')"),
    ("", "a triple bearing needs 4 [[bearing.surface]] entries; the design has none"),
    ("surface = [{radius_m = 1.0}, true]", "bearing surface 2 must be a table"),
])
def test_bearing_surfaces_of_the_wrong_kind_are_named(tmp_path, surface, words):
    """e9efb0c: `surface = [1, 2, 3, 4]` said `a triple bearing needs 4 [[bearing.surface]] entries` (it has 4)."""

    path = tmp_path / "t.toml"
    path.write_text(f'name = "t"\nmass_kg = 1e6\n[bearing]\ntype = "triple"\n{surface}\n')
    with pytest.raises(DesignError) as error:
        Design.from_toml(path)
    assert str(error.value) == f"{path}: {words}" or (words in str(error.value) and "\n" not in str(error.value))


# ---- 4. the 2-D TFP's rtol: tighter is called tighter

def test_the_2d_tfp_rtol_says_tighter_or_looser():
    """e9efb0c: rtol = 1e-14 said "looser, its answer breaks on real pairs" (1e-14 is tighter than 1e-13)."""
    from isolator.errors import InvalidSystemError
    from isolator.solver.planar_multisurface import RTOL_RANGE, tolerance

    with pytest.raises(InvalidSystemError, match=r"rtol = 1e-14 is outside \[1e-13, 1e-09\].*: tighter than 1e-13, "
                                                 r"where the kernel's error has reached its floor") as tight:
        tolerance(1e-14)
    assert "looser" not in str(tight.value)
    with pytest.raises(InvalidSystemError, match=r"looser than 1e-09, the kernel's answer breaks") as loose:
        tolerance(1e-8)
    assert "tighter" not in str(loose.value)
    with pytest.raises(InvalidSystemError, match=r"rtol = nan is outside .*: not a number"):
        tolerance(float("nan"))
    assert tolerance(RTOL_RANGE[0]) == 1e-13 and tolerance("1e-10") == 1e-10  # the range's ends and a text as before


# ---- 5. EN 15129: f_ae is not read (refused when set); the η floor, unverified, is a printed parameter

def test_an_en_review_refuses_a_parameter_it_does_not_read(tmp_path):
    """e9efb0c: `review --code en15129 --set f_ae=0.5` was taken and printed as used ("f_ae = 0.5 (set)"): the EN
    bounds are the plain product of the λ factors (EN 1998-2 7.5.2.4), f_ae is read by no EN computation."""
    from isolator.errors import ReviewError
    from isolator.review.parameters import resolve

    with pytest.raises(ReviewError, match=r"review parameter 'f_ae' is not read by the en15129 review: EN 1998-2 "
                                          r"7\.5\.2\.4 bounds are the plain product"):
        resolve("en15129", {"f_ae": 0.5})
    with pytest.raises(ReviewError, match=r"'gamma_x' is not read by the asce7-22 review: it serves EN 1998-1"):
        resolve("asce7-22", {"gamma_x": 1.5})
    assert resolve("asce7-22", {"gamma_x": 1.5}, other_codes=True)["gamma_x"] == 1.5  # the record checks' reading
    (tmp_path / "d.toml").write_text(DESIGN)
    result = RUNNER.invoke(app, ["review", "--design", str(tmp_path / "d.toml"), "--target", "example", "--suite",
                                 "example", "--code", "en15129", "--set", "f_ae=0.5", "-o", str(tmp_path / "r.pdf")])
    assert "review parameter 'f_ae' is not read by the en15129 review" in _one_line(result)
    assert not (tmp_path / "r.pdf").exists()


def test_the_en_damping_floor_is_a_printed_parameter_the_elf_reads():
    """e9efb0c: η = sqrt(10/(5 + ξ)) ≥ 0.55 (EN 1998-1 3.2.2.2(3), unverified: REVIEW_RULES 2 "all U unless
    marked") was a constant of the code, neither a parameter nor printed.  ξ = 0.5 here: sqrt(0.1/0.55) = 0.426
    below the floor, so B = 1/0.55; with eta_min = 1 no reduction (B = 1)."""
    from isolator.design import Design
    from isolator.review.codes import en15129
    from isolator.review.parameters import resolve, table
    from isolator.review.run import elf_values
    from isolator.review.target import two_period_target

    rows = {row["name"]: row for row in table("en15129", resolve("en15129"))}
    assert rows["eta_min"]["value"] == rows["eta_min"]["default"] == 0.55 and rows["eta_min"]["mark"] == "U"
    assert en15129.damping_divisor(0.5) == 1.0 / 0.55 and en15129.damping_divisor(0.5, 0.4) == pytest.approx(
        1.0 / math.sqrt(0.1 / 0.55), rel=1e-15)
    design = Design.from_mapping({"name": "d", "mass_kg": 1e6, "radius_m": 2.5, "mu_static": 0.06})
    target = two_period_target(1.5, 0.9, 8.0)
    default = elf_values(design, 0.06, target, "en15129", resolve("en15129"))
    beta = default["beta_M"]
    assert beta > 0.05 and default["B_M"] == pytest.approx(1.0 / max(math.sqrt(0.1 / (0.05 + beta)), 0.55), rel=1e-14)
    assert elf_values(design, 0.06, target, "en15129", resolve("en15129", {"eta_min": 1.0}))["B_M"] == 1.0


# ---- 6. a run-time setting of the wrong kind: one line

@pytest.mark.parametrize("name, value, words", [
    ("FAST_TRUNC_EPS", "1e-10", "planar_building.FAST_TRUNC_EPS = '1e-10' is not a number (a run-time setting in "
                                "1e-16 … 0.01, measured range)"),
    ("FAST_CHECK", None, "planar_building.FAST_CHECK = None is not a number"),
    ("FAST_TRUNC_EPS", True, "planar_building.FAST_TRUNC_EPS = True is not a number"),
    ("FAST_TRUNC_EPS", 1.0, "planar_building.FAST_TRUNC_EPS = 1.0 is outside (1e-16, 0.01) (measured range)"),
    ("STOP_PIECE", "no", "planar_building.STOP_PIECE = 'no' is not True or False"),
])
def test_a_run_time_setting_of_the_wrong_kind_is_one_line(monkeypatch, name, value, words):
    """e9efb0c: planar_building.FAST_TRUNC_EPS = "1e-10" was a TypeError from the range's comparison ('<=' not
    supported between float and str); STOP_PIECE = "no" read as true."""
    from isolator.solver import planar_building

    planar_building._check_settings()  # the defaults pass
    monkeypatch.setattr(planar_building, name, value)
    with pytest.raises(ValueError) as error:
        planar_building._check_settings()
    assert str(error.value).startswith(words) and "\n" not in str(error.value)


# ---- 7. the superstructure shear row says what was computed, with or without a superstructure

def _shear_row(superstructure, structure):
    from isolator.review.assess import _superstructure_shear_row
    from isolator.review.parameters import resolve

    elf = {b: {"T_M_s": 3.0, "beta_M": 0.2, "V_s_over_W": v} for b, v in (("lower", 0.10), ("upper", 0.12))}
    review = SimpleNamespace(parameters=resolve("asce7-22"), elf=elf, design=SimpleNamespace(
        superstructure=superstructure), design_values={"structure": structure,
                                                        "envelope": {"rule": "mean", "n": 7}})
    fixed_base = {"per_bound": {}, "missing": "needs the superstructure's response_modification_R"}
    return _superstructure_shear_row(review, 0.12, {"upper": 0.078, "nominal": 0.06}, fixed_base)


def test_the_superstructure_shear_row_says_what_was_computed():
    """e9efb0c, a rigid block: `needs the superstructure shear of the response histories (a design with a
    [superstructure] analysed by the building model); limit 17.5.4.3(3) activation V_st/W = 0.09` — the 17.6.4.2
    limit 0.6 × 0.12 computed and not said, nor that 17.5.4.3(1) and (2) were not computed."""
    activation = 0.09 * 1.0 ** (1 - 2.5 * 0.2)  # max(0.078, 1.5 × 0.06) × (W_s/W = 1)^(1 − 2.5 β)
    row = _shear_row(None, {})
    assert row["status"] == "not checked" and row["value"] is None and row["limit"] == pytest.approx(activation)
    note = row["note"]
    assert note.startswith("no value: the design has no [superstructure], so its analyses (the isolated mass as one "
                           "rigid block) give no superstructure shear")
    assert "17.6.4.2 0.6 × ELF V_s/W = 0.6 × 0.12 = 0.072" in note and "17.5.4.3(3) activation V_st/W = 0.09" in note
    assert "17.5.4.3(3) activation V_st/W = 0.09 governs" in note
    assert "17.5.4.3(1) not computed: needs the superstructure's response_modification_R" in note
    assert "17.5.4.3(2) not computed: needs wind_shear_over_W" in note
    row = _shear_row(SimpleNamespace(n_floors=3), {})  # a superstructure the analyses gave no shear of
    assert row["note"].startswith("no value: the design's 3-floor [superstructure] was not analysed by the building "
                                  "model") and "governs" in row["note"]
    row = _shear_row(SimpleNamespace(n_floors=3), {"superstructure_shear_coefficient": 0.2,
                                                   "superstructure_shear_bound": "upper"})
    assert row["value"] == pytest.approx(0.2) and row["status"] == "pass"
    assert "RHA superstructure shear / W ÷ R_I = 0.2 / 1" in row["note"] and "no value" not in row["note"]
    assert "17.5.4.3(1) not computed" in row["note"] and "17.5.4.3(2) not computed" in row["note"]


# h195's sweep of this round's inputs (its other findings were the same leftovers as above)


def test_an_at2_npts_beyond_any_record_is_named(tmp_path, monkeypatch):
    """e9efb0c: an NPTS of 400 digits was numpy's "Maximum allowed dimension exceeded"."""
    monkeypatch.chdir(tmp_path)
    assert "NPTS=   200" in SINE
    (tmp_path / "x.AT2").write_text(SINE.replace("NPTS=   200", "NPTS= " + "9" * 400))
    result = RUNNER.invoke(app, ["simulate", "x.AT2", "--mu-s", "0.05"])
    assert result.exit_code == 2 and isinstance(result.exception, SystemExit), result.output
    assert "header NPTS of 400 digits is more than the 1e+09 samples" in _one_line(result)


def test_a_floor_list_of_the_wrong_kind_says_which_entry():
    """e9efb0c: floor = [{}, 2] was told "needs at least one [[superstructure.floor]] entry"."""
    with pytest.raises(DesignError, match=r"key 'floor': entry 2 is 2, not a table of keys"):
        Design.from_mapping({"name": "FPS", "mass_kg": 1e6, "radius_m": 2.5, "mu_static": 0.06,
                             "superstructure": {"damping_ratio": 0.05, "floor": [{}, 2]}})
