"""Shared inputs of the review tests: three short real pairs, a design, a target, and one review of them."""

from __future__ import annotations

from pathlib import Path

import pytest

from isolator.design import Design
from isolator.review.suite import load_suite
from isolator.review.target import two_period_target

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "isolator" / "data" / "suites" / "example"
SHORT = [("landers1992_YER", "RSN900_LANDERS_YER270.AT2", "RSN900_LANDERS_YER360.AT2", ""),
         ("hectormine1999_ABY", "RSN1762_HECTOR_ABY090.AT2", "RSN1762_HECTOR_ABY360.AT2", ""),
         ("superstitionhills1987_PTS", "RSN723_SUPER.B_B-PTS225.AT2", "RSN723_SUPER.B_B-PTS315.AT2", "trim = true")]
DESIGN = """name = "A very long design name that would overprint the first page of the review if nothing cut it short"
mass_kg = 1.0e6
radius_m = 2.5
mu_static = 0.06
mu_kinetic = 0.05
displacement_capacity_m = 0.5
lambda_max = 1.3
lambda_min = 0.8
"""


@pytest.fixture(scope="session")
def inputs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("review")
    body = ""
    for name, x, y, extra in SHORT:
        body += f'[[pair]]\nname = "{name}"\nx = "{EXAMPLE / name / x}"\ny = "{EXAMPLE / name / y}"\n{extra}\n'
    (folder / "suite.toml").write_text(body)
    (folder / "design.toml").write_text(DESIGN)
    (folder / "target.toml").write_text("S_MS = 1.5\nS_M1 = 0.9\nT_L = 8.0\n")
    return folder


@pytest.fixture(scope="session")
def review(inputs):
    from isolator.review.run import run_review

    return run_review(Design.from_toml(inputs / "design.toml"), two_period_target(1.5, 0.9, 8.0),
                      load_suite(inputs / "suite.toml"), jobs=1, cache_dir=inputs / "cache")


