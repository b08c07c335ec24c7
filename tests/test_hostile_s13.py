"""A new hostile sweep (session 13) of what the tool grew since session 10: double and triple pendulums under a
pair, with a vertical, with µ(v) surfaces; a building on them; batch sweeps of such designs (docs/security.md,
"Session 13 sweep").  Each break found is an input that passed the reading and broke the solver (a traceback, or
minutes of grinding) or ran a whole batch to the same error; each must now be one line on stderr naming the file
(or the flag) and the problem, exit 2, before any analysis.

The refusals come before the record is analysed, so each case costs a design read (the record is a short synthetic
one, written here).
"""

from __future__ import annotations

import re

import pytest
from _model_designs import TRIPLE, designs_file_text
from _records import assert_one_line_exit_2, at2_text
from typer.testing import CliRunner

from isolator.cli import app

RUNNER = CliRunner()

#: The triple pendulum of _model_designs with µ(v) on every surface: (mu, mu_slow) per surface, rate 20 s/m.
SLOW = {"0.06": "0.04", "0.02": "0.01", "0.10": "0.07"}


def _rate_triple(rate: str = "20", slow: dict | None = None) -> str:
    slow = SLOW if slow is None else slow
    return re.sub(r"^mu = (\S+)$", lambda m: f"mu_slow = {slow[m.group(1)]}\nmu_fast = {m.group(1)}\n"
                  f"rate_s_per_m = {rate}", TRIPLE, flags=re.MULTILINE)


def _simulate(tmp_path, design_text: str):
    (tmp_path / "r.AT2").write_text(at2_text([0.3 * (-1) ** (i // 20) for i in range(200)]))
    design = tmp_path / "d.toml"
    design.write_text(design_text)
    return design, RUNNER.invoke(app, ["simulate", str(tmp_path / "r.AT2"), "--design", str(design), "--json"])


@pytest.mark.parametrize(("rate", "slow", "words"), [
    # int13: numpy LinAlgError traceback from the µ(v) series kernels (1-D and 2-D), exit 1
    ("1e-300", None, "key 'rate_s_per_m' = 1e-300 is outside [1, 10000] s/m"),  # since session 17 (MEANT_RANGES)
    # int13: the 2-D engine ground 79 s and gave up without naming the design; 1e-3 ran past 90 s
    ("1e-2", None, "key 'rate_s_per_m' = 0.01 is outside [1, 10000] s/m"),
    # mu_slow within 1e-14 of mu_fast: int13's engines gave up ("the step size fell below 1e-13"), no file named
    ("20", {"0.06": "0.05999999999999", "0.02": "0.01999999999999", "0.10": "0.09999999999999"},
     "per m/s at rest, below 0.001"),
    # int13: the 2-D engine gave up at t = 4e-9 s, no file named; the single pendulum's limit (RATE_MAX_S_PER_M)
    ("1e300", None, "rate_s_per_m = 1e+300 s/m exceeds 10000 s/m"),
])
def test_a_rate_law_the_series_model_cannot_follow_is_refused_naming_file_and_surface(tmp_path, rate, slow, words):
    design, result = _simulate(tmp_path, _rate_triple(rate, slow))
    assert_one_line_exit_2(result, str(design), "bearing surface 1: ", words)


def test_the_rate_bounds_keep_laws_the_engines_answer(tmp_path):
    """The least slope is 1e-3 per m/s: a slope of 1.1e-3 (rate 1.1 s/m, µ_fast - µ_slow = 1e-3) reads, and the
    2-D engine answered it under a pair in 4.4 s (docs/security.md); the tests' µ(v) bearings (slope ≥ 0.2) read."""
    from isolator.design import Design

    path = tmp_path / "d.toml"
    edge = {"0.06": "0.059", "0.02": "0.019", "0.10": "0.099"}
    for text in (_rate_triple("1.1", edge), _rate_triple("1e4"), _rate_triple()):
        path.write_text(text)
        surfaces = Design.from_toml(path).bearing.surfaces
        assert all(s.rate_s_per_m * (s.mu_fast - s.mu_slow) >= 1e-3 for s in surfaces)


def test_a_grid_of_a_key_every_bearing_replaces_is_refused_before_the_batch(tmp_path):
    """int13: ``batch --grid mu_static=…`` over triple pendulums analysed every row to the same error and exited 1
    after the batch (4 rows, 4 failed, 8.8 s); now one line naming the flag and the designs file, exit 2, no table."""
    record = tmp_path / "r.AT2"
    record.write_text(at2_text([0.3 * (-1) ** (i // 20) for i in range(200)]))
    designs = tmp_path / "designs.toml"
    designs.write_text(designs_file_text(TRIPLE, _rate_triple()))
    out = tmp_path / "out.csv"
    result = RUNNER.invoke(app, ["batch", str(record), "--designs", str(designs), "--output", str(out),
                                 "--grid", "mu_static=0.01:0.1:2"])
    assert_one_line_exit_2(result, "--grid mu_static", str(designs), "[bearing]")
    assert not out.exists()
