"""A hostile sweep (session 14): what session 13 left standing, then ``design``, ``review`` and ``report`` on the
new models as a hostile user (docs/security.md, "Session 14 sweep").  Each case failed on main before its fix: an
engine's refusal that named the instant but not the design file, a property bound that took a bearing outside the
rules its file was read by, a capacity of a nanometre read as a design, a refusal printed after a compile note, and
``--set`` values that were a traceback or silently the last one.

The refusals come before any analysis, so each case costs a design read and a short synthetic record.
"""

from __future__ import annotations

import math
import re

import pytest
from _model_designs import BUILDING, TRIPLE
from _records import assert_one_line_exit_2, at2_text
from typer.testing import CliRunner

from isolator.cli import app

RUNNER = CliRunner()

#: A friction pendulum (the review's and the design search's), R = 2.5 m, µ = 0.06, capacity 0.6 m.
FPS = 'name = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\ndisplacement_capacity_m = 0.6\n'

#: The triple pendulum of _model_designs with µ(v) at the reader's least slope and a little above it:
#: µ_fast − µ_slow = 1e-3 on every surface, rate 1.1 s/m, so a (µ_fast − µ_slow) = 1.1e-3 per m/s ≥ 1e-3.
EDGE_SLOW = {"0.06": "0.059", "0.02": "0.019", "0.10": "0.099"}


def _edge_triple(bounds: str) -> str:
    text = re.sub(r"^mu = (\S+)$", lambda m: f"mu_slow = {EDGE_SLOW[m.group(1)]}\nmu_fast = {m.group(1)}\n"
                  "rate_s_per_m = 1.1", TRIPLE, flags=re.MULTILINE)
    return text.replace("mass_kg = 1.0e5\n", f"mass_kg = 1.0e5\n{bounds}")


def _records(tmp_path, n: int = 200) -> dict:
    """x, y (0.3 g at 1 Hz) and an "Up" vertical of 1.5 g at 1 Hz: g + a_z first ≤ 0 at t = asin(1/1.5)/(2π) + 1/2
    = 0.616 s (the closed form; the engine reports the first sample below, 0.62 s)."""
    out = {}
    for name, amp, phase in (("x", 0.3, 0.0), ("y", 0.3, math.pi / 2), ("z", 1.5, 0.0)):
        text = at2_text([amp * math.sin(2 * math.pi * i * 0.01 + phase) for i in range(n)])
        if name == "z":
            text = text.replace("Test Station, 90", "Test Station, UP")
        out[name] = tmp_path / f"{name}.AT2"
        out[name].write_text(text)
    return out


def _suite_and_design(tmp_path, design_text: str):
    """A one-pair SUITE.toml of two 2 s square waves (0.1 g) and the design file ``design_text``."""
    (tmp_path / "x.AT2").write_text(at2_text([0.1 * (-1) ** (i // 20) for i in range(200)]))
    (tmp_path / "y.AT2").write_text(at2_text([0.1 * (-1) ** (i // 30) for i in range(200)]))
    suite = tmp_path / "suite.toml"
    suite.write_text('[[pair]]\nname = "a"\nx = "x.AT2"\ny = "y.AT2"\n')
    design = tmp_path / "d.toml"
    design.write_text(design_text)
    return suite, design


# ---- the engines' own refusals name the design file and the record's files (one place: cli.pairs.refusal_line)

@pytest.mark.parametrize("command", ["simulate", "report"])
def test_an_engine_refusal_names_the_design_and_every_file_of_the_record(tmp_path, command):
    """main: "error: the triple bearing lifts off at t = 0.62 s …" — the time, not the design file nor the record."""
    files = _records(tmp_path)
    design = tmp_path / "tfp.toml"
    design.write_text(TRIPLE)
    args = [command, str(files["x"]), "--pair", str(files["y"]), "--vertical", str(files["z"]), "--design",
            str(design)] + (["--json"] if command == "simulate" else ["-o", str(tmp_path / "r.pdf")])
    line = assert_one_line_exit_2(RUNNER.invoke(app, args),
                                  f"{design} under {files['x']} + {files['y']} + {files['z']}: ",
                                  "the triple bearing lifts off at t = 0.62 s")
    assert line.count(str(design)) == 1
    assert not (tmp_path / "r.pdf").exists()


def test_a_batch_row_names_the_design_and_the_record_of_a_refusal():
    """main: an InvalidSystemError row named the design alone ("d.toml: …"), not the record it was refused under."""
    from isolator.batch.worker import row_error
    from isolator.errors import InvalidSystemError, SolverError

    err = InvalidSystemError("d.toml: the building's fastest rate 3.4e+10 1/s needs 457833761 sub-steps")
    assert row_error(err, "r.AT2", "d.toml") == ("d.toml under r.AT2: the building's fastest rate 3.4e+10 1/s "
                                                 "needs 457833761 sub-steps")
    assert row_error(SolverError("the step size fell below 1e-13"), "r.AT2", "d.toml") == (
        "d.toml under r.AT2: the step size fell below 1e-13")


# ---- a property bound is read by the rules its bearing was read by

def test_a_lower_bound_below_the_rate_slope_floor_is_refused_naming_design_and_bound(tmp_path):
    """main: λ_min = 0.85 took the edge law's slope 1.1e-3 to 9.35e-4 per m/s, below the reader's 1e-3
    (bearing.MIN_RATE_SLOPE_S_PER_M), and the review ran it; now one line before any analysis."""
    suite, design = _suite_and_design(tmp_path, _edge_triple("lambda_min = 0.85\nlambda_max = 1.2\n"))
    result = RUNNER.invoke(app, ["review", "-d", str(design), "-t", "example", "-s", str(suite), "-j", "1",
                                 "--no-cache", "-o", str(tmp_path / "rv.pdf")])
    assert_one_line_exit_2(result, f"{design}: at the lower bound (λ = 0.85), bearing surface 1: ",
                           "= 0.000935 per m/s at rest, below 0.001")
    assert not (tmp_path / "rv.pdf").exists()


def test_an_upper_bound_that_keeps_an_inner_surface_from_regime_ii_is_refused(tmp_path):
    """main: λ = 2.5 on the triple asked d*_3 ≥ 2.5 × (0.10 − 0.02) × 0.3 = 0.06 m of an inner surface of 0.05 m (the
    rule the reader holds at nominal), and was reviewed; λ = 2 (0.048 m) and the edge law's bounds read."""
    from isolator.design import Design, DesignError

    path = tmp_path / "d.toml"
    path.write_text(TRIPLE)
    design = Design.from_toml(path)
    with pytest.raises(DesignError, match=re.escape(f"{path}: at the upper bound (λ = 2.5), bearing surface 3: "
                                                    "effective capacity d*_3 = 0.05 m is too small to reach regime "
                                                    "II: it must be >= (mu_4 - mu_3) R_eff,3 = 0.06 m")):
        design.with_friction_factor(2.5, "upper bound")
    scaled = design.with_friction_factor(2.0, "upper bound")
    assert [s.mu_kinetic for s in scaled.bearing.surfaces] == pytest.approx([0.12, 0.04, 0.04, 0.20])
    path.write_text(_edge_triple("lambda_min = 0.95\nlambda_max = 1.2\n"))
    edge = Design.from_toml(path)
    for factor in (0.95, 1.0, 1.2):  # slopes 1.045e-3, 1.1e-3, 1.32e-3
        surfaces = edge.with_friction_factor(factor, "bound").bearing.surfaces
        assert all(s.rate_s_per_m * (s.mu_fast - s.mu_slow) == pytest.approx(1.1e-3 * factor) for s in surfaces)


# ---- a capacity no bearing has

def test_a_capacity_below_a_millimetre_is_refused_naming_file_and_surface(tmp_path):
    """main: an outer capacity of 1e-9 m read and ran (69.7 s, exit 0; session 13).  (An inner one is refused by
    the regime-II rule already.)"""
    design = tmp_path / "d.toml"
    design.write_text(TRIPLE.replace("displacement_capacity_m = 0.4", "displacement_capacity_m = 1e-9", 1))
    (tmp_path / "r.AT2").write_text(at2_text([0.1 * (-1) ** i for i in range(200)]))
    result = RUNNER.invoke(app, ["simulate", str(tmp_path / "r.AT2"), "--design", str(design)])
    assert_one_line_exit_2(result, f"{design}: bearing surface 1: displacement_capacity_m = 1e-09 m is below 1 mm")


def test_the_least_capacity_reads(tmp_path):
    """The floor is 1 mm, 25 × below the least catalogue surface: 1 mm outer surfaces read (the inner ones keep
    their regime-II rule: (0.06 - 0.02) × 0.3 = 0.012 m).  The outer µ are made equal: an outer surface of lower
    friction must reach regime III, d*_1 >= (µ4 - µ1) R_eff,1 (session 16), which 1 mm is not at 0.06/0.10."""
    from isolator.bearing import MIN_CAPACITY_M
    from isolator.design import Design

    path = tmp_path / "d.toml"
    path.write_text(TRIPLE.replace("displacement_capacity_m = 0.4", "displacement_capacity_m = 0.001")
                    .replace("mu = 0.10", "mu = 0.06"))
    assert MIN_CAPACITY_M == 1e-3
    assert [s.displacement_capacity_m for s in Design.from_toml(path).bearing.surfaces] == [1e-3, 0.05, 0.05, 1e-3]


# ---- a refusal comes before the kernel is loaded (the s10 flake)

@pytest.mark.parametrize(("pair", "module"), [(False, "building"), (True, "planar_building")])
def test_a_slab_too_light_is_refused_before_the_kernel_loads(tmp_path, monkeypatch, pair, module):
    """The s10 "slab too light" tests failed once under -n 2 at load ~10: the kernel's warm-up ran before the
    refusal, and a cached load slower than 2 s printed "note: compiling …" before the error (two lines).  main
    loaded the kernel first (here the warm-up raises); now the sub-step count is refused before it."""
    import importlib

    solver = importlib.import_module(f"isolator.solver.{module}")

    def loaded():
        raise AssertionError("the kernel was loaded for a design the driver refuses")

    monkeypatch.setattr(solver, "_warm_up", loaded)
    design = tmp_path / "d.toml"
    design.write_text(BUILDING.replace("mass_kg = 1.6e6", "mass_kg = 1100000.0001", 1))
    files = _records(tmp_path)
    args = ["simulate", str(files["x"]), "--design", str(design)] + (["--pair", str(files["y"])] if pair else [])
    assert_one_line_exit_2(RUNNER.invoke(app, args), f"{design} under {files['x']}",
                           "sub-steps per sample interval of 0.01 s (at most 5000)")


# ---- --set abuse

@pytest.mark.parametrize(("settings", "words"), [
    # main: TypeError traceback (None < 1.0 in the review's parameters), exit 1
    (["min_ratio="], "review parameter 'min_ratio' needs a number (its default is 1), got ''"),
    (["min_ratio=none"], "review parameter 'min_ratio' needs a number (its default is 1), got 'none'"),
    # main: the last one ran, without a word
    (["min_ratio=0.9", "min_ratio=0.8"], "--set min_ratio is given twice ('0.9' and '0.8'): give it once"),
])
def test_review_set_abuse_is_one_line(tmp_path, settings, words):
    suite, design = _suite_and_design(tmp_path, FPS)
    args = ["review", "-d", str(design), "-t", "example", "-s", str(suite), "-j", "1", "--no-cache", "-o",
            str(tmp_path / "rv.pdf")]
    for item in settings:
        args += ["--set", item]
    assert_one_line_exit_2(RUNNER.invoke(app, args), words)
    assert not (tmp_path / "rv.pdf").exists()


def test_report_set_twice_is_one_line(tmp_path):
    """main: ``report … --set D_over_R_max=0.2 --set D_over_R_max=0.3`` wrote the report at 0.3 without a word."""
    files = _records(tmp_path)
    design = tmp_path / "tfp.toml"
    design.write_text(TRIPLE)
    result = RUNNER.invoke(app, ["report", str(files["x"]), "--pair", str(files["y"]), "--design", str(design),
                                 "--set", "D_over_R_max=0.2", "--set", "D_over_R_max=0.3", "-o",
                                 str(tmp_path / "r.pdf")])
    assert_one_line_exit_2(result, "--set D_over_R_max is given twice ('0.2' and '0.3')")
    assert not (tmp_path / "r.pdf").exists()


def test_a_design_space_of_no_design_is_refused_before_any_review(tmp_path):
    """main: ``design --vary radius_m=-1,-2`` reviewed both candidates to their reading error and wrote a chart of
    nothing, exit 0 (42 s); one invalid candidate among valid ones stays a row (docs/design_search.md)."""
    suite, design = _suite_and_design(tmp_path, FPS)
    result = RUNNER.invoke(app, ["design", "-d", str(design), "-t", "example", "-s", str(suite), "-j", "1",
                                 "--vary", "radius_m=-1,-2", "-o", str(tmp_path / "c.pdf")])
    assert_one_line_exit_2(result, f"--vary gives no candidate that is a design: {design} with radius_m=-1: key "
                                   "'radius_m' must be > 0, got -1 (and 1 other candidate refused)")
    assert not (tmp_path / "c.pdf").exists()
