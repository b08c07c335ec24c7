"""A new hostile sweep (session 10) of what the tool grew since the last ones: the ``[bearing]`` surfaces of a
double/triple pendulum and the ``[superstructure]`` floors.  Each break found is a design value that passed the
reading and broke (or silently fooled) the solver; each must now be one line on stderr naming the file, the surface
or floor and the key, exit 2, before any analysis.

The refusals come before the record is analysed, so each case costs a design read (the record is a short synthetic
one, written here).
"""

from __future__ import annotations

import pytest
from _model_designs import BUILDING, TRIPLE
from _records import at2_text
from typer.testing import CliRunner

from isolator.cli import app

RUNNER = CliRunner()


def _refused(tmp_path, design_text: str, *needles: str) -> str:
    (tmp_path / "r.AT2").write_text(at2_text([0.1 * (-1) ** i for i in range(200)]))
    design = tmp_path / "d.toml"
    design.write_text(design_text)
    result = RUNNER.invoke(app, ["simulate", str(tmp_path / "r.AT2"), "--design", str(design)])
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert result.exit_code == 2, result.output
    assert len(lines) == 1 and "Traceback" not in result.output, result.output
    for needle in (str(design), *needles):
        assert needle in lines[0], (needle, lines[0])
    return lines[0]


def _replace(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new)


@pytest.mark.parametrize(("old", "new", "surface", "words"), [
    # main: OverflowError from the solver's sub-step count (exit 1); since session 17 a radius no engineer means
    ("radius_m = 0.3", "radius_m = 1e-300", 2, ("key 'radius_m' = 1e-300 is outside [0.05, 50] m",)),
    ("radius_m = 0.3", "radius_m = 1e-11", 2, ("key 'radius_m' = 1e-11 is outside [0.05, 50] m",)),
    # R_eff = R - h = 1e-11 m: g/R_eff = 1e12 1/s², past the rigid block's K/M limit
    ("radius_m = 2.1\n", "radius_m = 2.1\nheight_m = 2.09999999999\n", 1,
     ("R_eff = ", "above 1e+10 1/s²", "no isolator is that stiff")),
])
def test_a_surface_stiffer_than_any_isolator_is_refused_in_one_line(tmp_path, old, new, surface, words):
    """g/R_eff of a surface is held to the limit a design's own radius_m is (MAX_STIFFNESS_PER_MASS), and R to
    what an engineer means (isolator.bearing.MEANT_RANGES, session 17)."""
    text = TRIPLE.replace(old, new, 1) if "height" in new else _replace(TRIPLE, old, new)
    _refused(tmp_path, text, f"bearing surface {surface}: {words[0]}", *words[1:])


def test_the_stiffest_surface_accepted_reads(tmp_path):
    """The smallest radius an engineer means reads: inner radii of 0.05 m (session 17; 1e-9 m, g/R = 9.8e9 1/s²,
    read before, the rigid block's limit)."""
    from isolator.design import Design

    path = tmp_path / "d.toml"
    path.write_text(_replace(TRIPLE, "radius_m = 0.3", "radius_m = 0.05"))
    bearing = Design.from_toml(path).bearing
    assert [s.effective_radius_m for s in bearing.surfaces] == [2.1, 0.05, 0.05, 2.1]


@pytest.mark.parametrize(("old", "new"), [
    # main: 1e-300 N/m read and solved, the stories cut loose from the slab (1st-story shear 8e-18 W_s), exit 0
    ("stiffness_x_N_per_m = 6.0e8", "stiffness_x_N_per_m = 1e-300"),
    # main: the solver's refusal, one line without the design file (1e148 sub-steps per sample)
    ("stiffness_x_N_per_m = 6.0e8", "stiffness_x_N_per_m = 1e300"),
    ("stiffness_x_N_per_m = 6.0e8", "stiffness_x_N_per_m = 6.0e8\nstiffness_y_N_per_m = 1e300"),
])
def test_an_absurd_story_stiffness_is_refused_naming_file_floor_and_key(tmp_path, old, new):
    key = "stiffness_y_N_per_m" if "stiffness_y" in new else "stiffness_x_N_per_m"
    _refused(tmp_path, BUILDING.replace(old, new, 1), f"floor 1 (from the bottom): key '{key}' must lie in [1, 1e+14]")


def test_the_story_stiffness_range_holds_every_bundled_building():
    """The range keeps the example building (1.5e9-3.4e9 N/m) and the tests' (4e8-6e8 N/m)."""
    from pathlib import Path

    from isolator.design import Design
    from isolator.superstructure import STORY_STIFFNESS_RANGE_N_PER_M

    low, high = STORY_STIFFNESS_RANGE_N_PER_M
    example = Design.from_toml(Path(__file__).resolve().parents[1] / "data" / "example_building.toml")
    stiffnesses = [f.stiffness_x_N_per_m for f in example.superstructure.floors]
    assert stiffnesses == [3.4e9, 3.1e9, 2.7e9, 2.2e9, 1.5e9]
    assert all(low <= k <= high for k in stiffnesses)


def _suite(tmp_path, factor: str):
    """A one-pair SUITE.toml with the engineer's ``factor``; returns it and the pair's PGA [g] as written."""
    import math

    pga = 0.0
    for name, phase in (("x.AT2", 0.0), ("y.AT2", 1.0)):
        values = [0.3 * math.sin(2 * math.pi * 0.01 * i + phase) * math.exp(-0.002 * i) for i in range(1500)]
        (tmp_path / name).write_text(at2_text(values))
        pga = max(pga, *(abs(float(f"{v:15.7E}")) for v in values))
    suite = tmp_path / "suite.toml"
    suite.write_text(f'[[pair]]\nname = "a"\nx = "x.AT2"\ny = "y.AT2"\nscale_factor = {factor}\n')
    return suite, pga


@pytest.mark.parametrize("factor", ["1e300", "1e-300", "200.0"])
@pytest.mark.parametrize("command", ["review", "design"])
def test_an_engineer_scale_factor_past_the_pga_range_is_refused_before_any_analysis(tmp_path, factor, command):
    """A SUITE.toml factor is held to --scale-to-pga's range [1e-6, 50] g on the pair's PGA (0.29 g here: 200 ×
    0.29 g = 59 g).  On main a factor of 1e300 was analysed and its spectrum "passed" at 1.5e299 × the target."""
    suite, pga = _suite(tmp_path, factor)
    design = tmp_path / "d.toml"
    design.write_text("name = \"FPS\"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\n"
                      "displacement_capacity_m = 0.6\n")
    args = ["-d", str(design), "-t", "example", "-s", str(suite), "-o", str(tmp_path / "out.pdf"), "-j", "1"]
    args = ["review", *args, "--scaling", "given", "--no-cache"] if command == "review" else [
        "design", *args, "--vary", "radius_m=2:3:2"]
    result = RUNNER.invoke(app, args)
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert result.exit_code == 2, result.output
    assert len(lines) == 1 and "Traceback" not in result.output, result.output
    assert f"{suite}: pair 'a': scale_factor = {float(factor):g} takes its PGA of {pga:.4g} g to" in lines[0], lines[0]
    assert "outside [1e-06, 50] g" in lines[0]
    assert not (tmp_path / "out.pdf").exists()


def test_bench_over_the_root_folder_checks_its_outputs_without_walking_the_tree(tmp_path):
    """``bench --records /``: main walked the whole tree to list the inputs and died on /proc's unreadable links
    (PermissionError traceback).  Now the five outputs are checked alone: here bench.csv is a folder, refused in one
    line before any work."""
    (tmp_path / "out" / "bench.csv").mkdir(parents=True)
    result = RUNNER.invoke(app, ["bench", "--records", "/", "--out", str(tmp_path / "out"), "--quick"])
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert result.exit_code == 2, result.output
    assert len(lines) == 1 and str(tmp_path / "out" / "bench.csv") in lines[0], result.output


def test_bench_output_linked_into_the_records_is_an_input(tmp_path):
    """An output that resolves into the records' tree (a link to a record) is still refused as an input."""
    (tmp_path / "records").mkdir()
    (tmp_path / "records" / "r.AT2").write_text("a record\n")
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "bench.md").symlink_to(tmp_path / "records" / "r.AT2")
    result = RUNNER.invoke(app, ["bench", "--records", str(tmp_path / "records"), "--out", str(tmp_path / "out")])
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert result.exit_code == 2, result.output
    assert len(lines) == 1 and "is an input" in lines[0], result.output
    assert (tmp_path / "records" / "r.AT2").read_text() == "a record\n"


@pytest.mark.parametrize("key", ["mu_static", "radius_m", "displacement_capacity_m"])
def test_design_varying_a_key_the_bearing_surfaces_replace_is_one_line(tmp_path, key):
    """``design --vary mu_static=…`` of a triple pendulum: main analysed every candidate to the same error ('key
    'mu_static' with a [bearing] table') and wrote a chart of none, exit 0."""
    suite, _ = _suite(tmp_path, "1.0")
    design = tmp_path / "tfp.toml"
    design.write_text(TRIPLE)
    result = RUNNER.invoke(app, ["design", "-d", str(design), "-t", "example", "-s", str(suite), "--vary",
                                 f"{key}=0.05:0.1:2", "-o", str(tmp_path / "c.pdf"), "-j", "1"])
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert result.exit_code == 2, result.output
    assert len(lines) == 1 and f"--vary {key}: {design} gives its bearing surface by surface" in lines[0], lines
    assert not (tmp_path / "c.pdf").exists()


def test_a_building_of_thousands_of_floors_is_refused_at_once(tmp_path):
    """2000 floors of 1 kg: main read them and ran past 120 s (the solve grows with the cube of the floors)."""
    floor = "[[superstructure.floor]]\nmass_kg = 1.0\nstory_height_m = 3.0\nstiffness_x_N_per_m = 6.0e8\n"
    head, rest = BUILDING.split("[[superstructure.floor]]", 1)
    layout = "[[bearing_position]]" + rest.split("[[bearing_position]]", 1)[1]
    _refused(tmp_path, head + floor * 2000 + layout, "[superstructure]: 2000 [[superstructure.floor]] entries, "
             "more than 200")
    from isolator.superstructure import MAX_FLOORS

    assert MAX_FLOORS >= 163  # the tallest building built (Burj Khalifa, 163 floors) still reads


@pytest.mark.parametrize("pair", [False, True], ids=["1-D building", "2-D building"])
def test_a_slab_too_light_for_its_first_story_is_refused_naming_the_design(tmp_path, pair):
    """A base slab of 1e-4 kg under floors of 1.1e6 kg (a mass_kg typed as the floors' sum): the first story's rate
    ~2.4e6 1/s asks ~16,000 sub-steps per 0.01 s sample.  The 1-D building refused it without naming the design
    file; the 2-D building ran on for minutes (a slab of 1e-5 of the floors on a real pair: > 300 s) — both now one
    line naming the design, exit 2 (coordinator, session 10)."""
    text = _replace(BUILDING, "mass_kg = 1.6e6", "mass_kg = 1100000.0001")
    design = tmp_path / "d.toml"
    design.write_text(text)
    wave = [0.1 * (-1) ** i for i in range(200)]
    (tmp_path / "r.AT2").write_text(at2_text(wave))
    (tmp_path / "r2.AT2").write_text(at2_text([0.5 * v for v in wave]))
    args = ["simulate", str(tmp_path / "r.AT2"), "--design", str(design)]
    if pair:
        args += ["--pair", str(tmp_path / "r2.AT2")]
    result = RUNNER.invoke(app, args)
    lines = [line for line in result.output.splitlines() if line.strip()]
    assert result.exit_code == 2, result.output
    assert len(lines) == 1 and "Traceback" not in result.output, result.output
    # the design and the record are named (session 14: "D under R: …"), then the refusal
    assert f"{design} under " in lines[0] and ": the building's fastest rate" in lines[0], lines[0]
    assert "sub-steps per sample interval of 0.01 s (at most 5000)" in lines[0], lines[0]
