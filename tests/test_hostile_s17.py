"""A hostile sweep (session 17): what session 16's sweep left (a gravity of 1e300 answered, an over-critical damping
ratio ran, a triple's states named twice, a relative cache folder made in the working folder, a refusal without its
reason) and what the new sweep found (docs/security.md, "Session 17 sweep").
Each case failed on main before its fix (a silent guess, a wrong regime's line, a folder made unasked).
"""

from __future__ import annotations

import json
import math
import os
import re
import subprocess
import sys
import tomllib

import pytest
from _model_designs import TRIPLE
from _records import assert_one_line_exit_2, at2_text
from typer.testing import CliRunner

from isolator.cli import app

RUNNER = CliRunner()


def _record(tmp_path, peak_g=0.1, n=200, name="x.AT2"):
    """A 1 Hz sine of ``peak_g`` at 0.01 s."""
    path = tmp_path / name
    path.write_text(at2_text([peak_g * math.sin(2 * math.pi * i * 0.01) for i in range(n)]))
    return path


# ---- 1. physical flags: a number an engineer cannot mean is refused, naming the flag and its range

@pytest.mark.parametrize("options, words", [
    (["--gravity", "1e300"], "--gravity 1e+300 is outside [9.7, 10] m/s²"),
    (["--gravity", "981"], "--gravity 981 is outside [9.7, 10] m/s²"),  # cm/s²
    (["--gravity", "1"], "--gravity 1 is outside"),  # g itself
    (["--radius-m", "2500"], "--radius-m 2500 is outside [0.05, 50] m"),  # mm
    (["--mu-s", "1e-300"], "--mu-s 1e-300 is outside [0.0001, 1)"),  # harmonic's and regime-map's range
    (["--radius-m", "2", "--mu-slow", "0", "--mu-fast", "0.08", "--rate-s-per-m", "20"], "--mu-slow 0 is outside"),
    (["--radius-m", "2", "--mu-slow", "0.03", "--mu-fast", "0.08", "--rate-s-per-m", "1e-300"],
     "--rate-s-per-m 1e-300 is outside [1, 10000] s/m"),
])
def test_simulate_refuses_physical_flags_no_engineer_means(tmp_path, options, words):
    """main: each ran and answered (exit 0; --gravity 1e300: nothing slid)."""
    record = _record(tmp_path)
    base = [] if "--mu-s" in options else ["--mu-s", "0.05"]
    result = RUNNER.invoke(app, ["simulate", str(record), *base, *options])
    assert_one_line_exit_2(result, words)


def test_gravity_beside_a_design_is_bounded_too(tmp_path):
    design = tmp_path / "d.toml"
    design.write_text('name = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\n')
    result = RUNNER.invoke(app, ["simulate", str(_record(tmp_path)), "--design", str(design), "--gravity", "32.2"])
    assert_one_line_exit_2(result, "--gravity 32.2 is outside [9.7, 10] m/s²")


def test_earth_gravity_and_the_library_messages_are_kept(tmp_path):
    """The range adds to the library's checks: 0 and 1.5 keep their own messages; 9.81 still runs."""
    record = _record(tmp_path)
    assert_one_line_exit_2(RUNNER.invoke(app, ["simulate", str(record), "--mu-s", "0.05", "--gravity", "0"]),
                           "gravity_m_s2 must be a finite number > 0")
    assert_one_line_exit_2(RUNNER.invoke(app, ["simulate", str(record), "--mu-s", "1.5"]), "must be < 1")
    ran = RUNNER.invoke(app, ["simulate", str(record), "--mu-s", "0.05", "--gravity", "9.81", "--json"])
    assert ran.exit_code == 0, ran.output


# ---- 2. the isolator's damping ratio is a fraction of critical

@pytest.mark.parametrize("zeta", ["1.5", "5", "1"])
def test_an_over_critical_damping_ratio_is_refused_naming_the_file_and_key(tmp_path, zeta):
    """main: damping_ratio = 1.5 (and 5, likely 5 % typed as a percent) was read and ran."""
    from isolator.design import Design, DesignError

    design = tmp_path / "d.toml"
    design.write_text(f'name = "FPS"\nmass_kg = 1e6\nradius_m = 2.5\nmu_static = 0.06\ndamping_ratio = {zeta}\n')
    with pytest.raises(DesignError, match=rf"d.toml: key 'damping_ratio' must lie in \[0, 1\), a fraction of "
                                          rf"critical .*got {zeta}; give an over-critical damper as "
                                          r"'damping_Ns_per_m'"):
        Design.from_toml(design)


def test_an_over_critical_damper_given_by_its_coefficient_is_kept():
    """The paper's configuration 4c stays reachable: γ = 2 ζ sqrt(K M) with ζ = 1.5, as damping_Ns_per_m."""
    from isolator.design import Design

    mass, radius = 1e6, 2.5
    gamma = 2 * 1.5 * math.sqrt(mass * 9.80665 / radius * mass)
    design = Design.from_mapping({"name": "FPS", "mass_kg": mass, "radius_m": radius, "mu_static": 0.06,
                                  "damping_Ns_per_m": gamma})
    assert design.system().configuration == "4c"
    assert design.damping_ratio == pytest.approx(1.5, rel=1e-12)


# ---- 3. a triple's states where one inner slider slides alone have a name of their own

#: Fenz & Constantinou's triple with µ3 = 0.04 instead of 0.02 (its inner surfaces start one after the other).
TRIPLE_UNEQUAL_INNER = "mu = 0.04".join(TRIPLE.rsplit("mu = 0.02", 1))


def test_a_motion_on_one_inner_surface_is_not_read_as_both(tmp_path):
    """µ2 = 0.02 < µ3 = 0.04: under a 0.025 g sine only surface 2 slides (its peak > 0, surface 3's exactly 0).
    main named that state "I", as the next one (both inner sliding), so the backbone read I, I and the single
    pendulum of the response was taken on the second: R = R̄2 + R̄3 = 0.6 m, µ = 0.03.  Now the state is
    "I (one inner)" and the point is on its own line: R = R̄2 = 0.3 m, µ = µ2 = 0.02."""
    from isolator.design import Design

    design = tmp_path / "tri.toml"
    design.write_text(TRIPLE_UNEQUAL_INNER)
    record = _record(tmp_path, peak_g=0.025, n=300)
    result = RUNNER.invoke(app, ["simulate", str(record), "--design", str(design), "--json"])
    assert result.exit_code == 0, result.output
    summary = json.loads(result.stdout)
    peaks = summary["surface_peak_displacement_m"]
    assert peaks[1] > 1e-4 and peaks[0] == peaks[2] == peaks[3] == 0.0, peaks  # what happened: surface 2 alone
    assert list(summary["regimes"]) == ["I (one inner)"]
    bearing = Design.from_toml(design).bearing
    assert bearing.backbone().regimes == ("I (one inner)", "I", "II", "III", "IV", "V", "V (one inner)")
    name, radius, mu, _ = bearing.point_regime(summary["regimes"])
    assert (name, radius, mu) == ("I (one inner)", pytest.approx(bearing.elements()[0][1], rel=1e-12),
                                  pytest.approx(0.02, rel=1e-12))


def test_the_symmetric_triple_keeps_fenz_and_constantinou_names():
    from isolator.design import Design

    assert Design.from_mapping(tomllib.loads(TRIPLE)).bearing.backbone().regimes == (
        "I", "II", "III", "IV", "V")


# ---- 4. environment and refusals with their reason

def test_a_relative_cache_folder_is_refused_before_any_folder_is_made(tmp_path, monkeypatch):
    """main: ISOLATOR_CACHE_DIR=cache made ./cache/maps in the working folder (a new cache in every folder)."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("ISOLATOR_CACHE_DIR", "cache")
    result = RUNNER.invoke(app, ["regime-map", "-n", "4", "-o", str(tmp_path / "m.png")])
    assert_one_line_exit_2(result, "ISOLATOR_CACHE_DIR=cache is a relative path")
    assert list(tmp_path.iterdir()) == []


def test_bench_repeats_refusal_gives_its_reason():
    """main: "Input should be less than or equal to 20", without why."""
    result = RUNNER.invoke(app, ["bench", "--repeats", "21"])
    assert_one_line_exit_2(result, "--repeats 21 is more than 20 runs per timing: the docs' medians take 3")


# ---- 5. a design file's numbers no engineer means (the new sweep)

@pytest.mark.parametrize("keys, words", [
    ({"radius_m": 1e300}, "key 'radius_m' = 1e+300 is outside [0.05, 50] m"),
    ({"radius_m": 2500.0}, "key 'radius_m' = 2500 is outside [0.05, 50] m"),  # mm, as --radius-m
    ({"mu_static": 1e-300}, "key 'mu_static' = 1e-300 is outside [0.0001, 1)"),
    ({"displacement_capacity_m": 1e300}, "key 'displacement_capacity_m' = 1e+300 is outside [0.001, 10] m"),
    ({"displacement_capacity_m": 1e-300}, "key 'displacement_capacity_m' = 1e-300 is outside [0.001, 10] m"),
    ({"mu_slow": 1e-300, "mu_fast": 0.06, "rate_s_per_m": 20.0}, "key 'mu_slow' = 1e-300 is outside"),
    ({"mu_slow": 0.03, "mu_fast": 0.06, "rate_s_per_m": 1e-300}, "key 'rate_s_per_m' = 1e-300 is outside [1, 10000]"),
    ({"lambda_max": 1e300, "lambda_min": 0.9}, "µk x lambda_max = 6e+298 is outside [0.0001, 1)"),
    ({"lambda_max": 1.2, "lambda_min": 1e-300}, "µk x lambda_min = 6e-302 is outside [0.0001, 1)"),
    ({"mu_upper": 1.5, "mu_lower": 0.03}, "key 'mu_upper' = 1.5 is outside [0.0001, 1)"),
])
def test_design_numbers_no_engineer_means_are_refused_as_the_flags_are(keys, words):
    """main: each was read (a radius of 1e300 m reviewed by `design --vary radius_m=1e300,2`, exit 0); the
    command-line flags and the design file now share one table of ranges (isolator.bearing.MEANT_RANGES)."""
    from isolator.design import Design, DesignError

    mapping = {"name": "FPS", "mass_kg": 1e6, "radius_m": 2.5, "mu_static": 0.06, **keys}
    with pytest.raises(DesignError) as caught:
        Design.from_mapping(mapping, source="d.toml")
    assert str(caught.value).startswith("d.toml: ") and words in str(caught.value), str(caught.value)


@pytest.mark.parametrize("surface, words", [
    ({"radius_m": 1e300}, "bearing surface 4: key 'radius_m' = 1e+300 is outside [0.05, 50] m"),
    ({"displacement_capacity_m": 1e300}, "bearing surface 4: key 'displacement_capacity_m' = 1e+300 is outside"),
    ({"mu": 1e-300}, "bearing surface 4: key 'mu' = 1e-300 is outside [0.0001, 1)"),
])
def test_a_triple_surface_number_no_engineer_means_is_refused(surface, words):
    from isolator.design import Design, DesignError

    mapping = tomllib.loads(TRIPLE)
    mapping["bearing"]["surface"][3].update(surface)
    with pytest.raises(DesignError, match=re.escape(words)):
        Design.from_mapping(mapping, source="d.toml")


# ---- 6. the new sweep: a design file's keys, each wrong in turn

def test_a_bearing_type_given_as_an_array_or_a_table_is_one_line(tmp_path):
    """main: a traceback (TypeError: unhashable type: 'list') from `simulate --design`."""
    design = tmp_path / "d.toml"
    for value in ('["triple"]', "{ a = 1 }"):
        design.write_text(f'name = "t"\nmass_kg = 1e5\n[bearing]\ntype = {value}\n')
        result = RUNNER.invoke(app, ["simulate", str(_record(tmp_path)), "--design", str(design)])
        assert_one_line_exit_2(result, "key 'bearing.type' must be one of 'single', 'double', 'triple', got")


# ---- 7. the new sweep: standard output that cannot take the answer

@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="no /dev/full on this system")
@pytest.mark.parametrize("args", [["harmonic", "--alpha", "2", "--mu-s", "0.1"],
                                  ["harmonic", "--alpha", "2", "--mu-s", "0.1", "--json"]])
def test_a_full_standard_output_is_one_line(args):
    """main: `isolator harmonic … > /dev/full` ended in a traceback (OSError: No space left on device)."""
    with open("/dev/full", "w") as full:
        done = subprocess.run([sys.executable, "-c", "from isolator.cli import app; app()", *args], stdout=full, stderr=subprocess.PIPE,
                              text=True, timeout=120)
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    assert done.returncode == 2 and lines == ["error: standard output: cannot write (No space left on device)"], \
        done.stderr


# ---- 8. the new sweep: a design's name that drives a terminal

@pytest.mark.parametrize("name", ["\x1b]0;pwned\x07 FPS", "FPS\u202e", "two\nlines"])
def test_a_design_name_with_control_characters_is_refused(name):
    """main: read, and `batch` wrote it raw into its CSV table (`cat t.csv` set the terminal's title)."""
    from isolator.design import Design, DesignError

    with pytest.raises(DesignError, match=r"d.toml: key 'name' holds a control or format character \('.*\\(x[0-9a-f]{2}|u[0-9a-f]{4}|n)"):
        Design.from_mapping({"name": name, "mass_kg": 1e6, "radius_m": 2.5, "mu_static": 0.06}, source="d.toml")


def test_a_design_name_in_any_script_is_kept():
    from isolator.design import Design

    name = "café 建物 Ωμέγα"
    assert Design.from_mapping({"name": name, "mass_kg": 1e6, "radius_m": 2.5, "mu_static": 0.06}).name == name


# ---- 9. the new sweep: a TOML file of absurd size

def test_a_toml_file_beyond_64_mib_is_refused_before_it_is_read(tmp_path):
    """main: read whole (a 200 MB design file of comments: 13.5 s and 441 MB, then simulated); a few GB would
    exhaust the memory.  A sparse file: its size is stated, nothing is read."""
    from isolator.design import Design, DesignError

    path = tmp_path / "big.toml"
    with path.open("wb") as stream:
        stream.truncate(65 * 2**20)
    with pytest.raises(DesignError, match=r"big.toml: is 65.0 MiB, larger than any design file \(isolator reads "
                                          r"a design file up to 4 MiB"):
        Design.from_toml(path)


# ---- 10. the new sweep: JSON nested past Python's stack (a review JSON, a cache entry, a batch part)

DEEP = "[" * 100_000 + "]" * 100_000


def test_a_review_json_nested_too_deep_is_one_line(tmp_path):
    """main: a traceback (RecursionError) from `review --verify` (json's decoder recurses per level)."""
    path = tmp_path / "deep.json"
    path.write_text(DEEP)
    assert_one_line_exit_2(RUNNER.invoke(app, ["review", "--verify", str(path)]),
                           "deep.json: cannot read the review JSON (maximum recursion depth exceeded")


def test_cache_entries_and_batch_parts_nested_too_deep_are_damaged_not_fatal(tmp_path):
    """main: the review's analysis cache, the design search's row store and a batch's part lines let RecursionError
    through (a traceback at the next run); each is now a damaged entry, recomputed."""
    from isolator.batch.store import PartStore
    from isolator.review.design_store import RowStore
    from isolator.review.worker import Cache

    (tmp_path / "k.json").write_text(DEEP)
    cache = Cache(tmp_path)
    assert cache.get("k") is None and cache.rejected == [tmp_path / "k.json"]
    assert RowStore(tmp_path).get("k") is None
    store = PartStore(tmp_path / "t.csv")
    store.directory.mkdir()
    (store.directory / "part-0.jsonl").write_text(DEEP + "\n")
    assert store.rows() == [] and store.damaged == 1


# ---- 11. the new sweep: TOML nested past the stack, keys of absurd depth

@pytest.mark.parametrize("text, words", [
    ("name = " + "[" * 100_000 + "]" * 100_000 + "\n", "not valid TOML (arrays or tables nested deeper than Python's"),
    ("x = " + "{a = " * 100_000 + "1" + "}" * 100_000 + "\n", "not valid TOML (arrays or tables nested deeper"),
    ("a." * 50_000 + "b = 1\n", "line 1: a key of 32 or more dotted parts"),
    ('"a".' * 40 + "b = 1\n", "line 1: a key of 32 or more dotted parts"),
])
def test_toml_nested_or_dotted_past_reason_is_one_line(tmp_path, text, words):
    """main: a traceback (RecursionError) for the nested arrays and tables; the 100 kB key of 50,000 parts ran past
    a minute (tomllib's time grows as the square of a key's parts)."""
    from isolator.design import Design, DesignError

    path = tmp_path / "d.toml"
    path.write_text(text)
    with pytest.raises(DesignError, match=re.escape(words)):
        Design.from_toml(path)


def test_real_files_pass_the_key_depth_scan():
    from isolator.design import DEEP_TOML_KEY

    assert DEEP_TOML_KEY.search("superstructure.floor.mass_kg = 1\nx = 1.2345\npath = \"../a.b.c.AT2\"\n") is None
