"""`isolator design` on a double and a triple pendulum, end to end on a short cut of the bundled suite (h190).

A double or triple has no single radius or µ: its table row names its surfaces (``bearing_surfaces``) and gives
the equivalent pendulum of its last sliding regime under its own name (``equivalent_radius_m``, ``equivalent_mu``),
not as ``radius_m``/``mu_kinetic`` (up to e9efb0c the example triple's row said radius_m 4.2, mu_kinetic 0.08)."""

from __future__ import annotations

from pathlib import Path

import pytest

from isolator.review.design_space import search
from isolator.review.suite import load_suite
from isolator.review.target import two_period_target

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "isolator" / "data" / "suites" / "example"
PAIRS = [("landers1992_YER", "RSN900_LANDERS_YER270.AT2", "RSN900_LANDERS_YER360.AT2"),
         ("hectormine1999_ABY", "RSN1762_HECTOR_ABY090.AT2", "RSN1762_HECTOR_ABY360.AT2"),
         ("superstitionhills1987_PTS", "RSN723_SUPER.B_B-PTS225.AT2", "RSN723_SUPER.B_B-PTS315.AT2")]
SAMPLES = 600  # the first 600 samples (12 s at 0.02 s, 6 s at 0.01 s) of each component: a fast suite
DOUBLE = ('name = "DFP R 2.5/2.5 m, mu 0.04/0.07"\nmass_kg = 1.0e6\nlambda_max = 1.3\nlambda_min = 0.8\n'
          '[bearing]\ntype = "double"\n' + "".join(f"[[bearing.surface]]\nradius_m = 2.5\nmu = {mu}\n"
                                                 "displacement_capacity_m = 0.5\n" for mu in (0.04, 0.07)))


def _cut(source: Path, target: Path, samples: int) -> None:
    lines = source.read_text().splitlines()
    dt = lines[3].split("DT=")[1].split()[0]
    values = " ".join(lines[4:]).split()[:samples]
    body = [" ".join(values[i:i + 5]) for i in range(0, len(values), 5)]
    target.write_text("\n".join([*lines[:3], f"NPTS= {len(values):6d}  DT= {dt} SEC", *body]) + "\n")


@pytest.fixture(scope="module")
def short_suite(tmp_path_factory):
    folder = tmp_path_factory.mktemp("cut")
    body = ""
    for name, x, y in PAIRS:
        for file in (x, y):
            _cut(EXAMPLE / name / file, folder / file, SAMPLES)
        body += f'[[pair]]\nname = "{name}"\nx = "{folder / x}"\ny = "{folder / y}"\n'
    (folder / "suite.toml").write_text(body)
    (folder / "double.toml").write_text(DOUBLE)
    return folder, load_suite(folder / "suite.toml")


@pytest.mark.parametrize("design, vary, surfaces, radius, mu", [
    # regime III of a triple with zero heights (Fenz & Constantinou 2008): both outer surfaces slide, R1 + R4
    ("triple", "lambda_ae_max=1.0,1.2", "triple: R 2.1/0.3/0.3/2.1 m, mu 0.06/0.02/0.02/0.1, d* 0.8/0.05/0.05/0.8 m",
     2.1 + 2.1, None),
    # a double with both surfaces sliding: F/W = x/(R1 + R2) + (mu1 R1 + mu2 R2)/(R1 + R2)
    ("double", "lambda_max=1.2,1.3", "double: R 2.5/2.5 m, mu 0.04/0.07, d* 0.5/0.5 m", 2.5 + 2.5,
     (0.04 * 2.5 + 0.07 * 2.5) / 5.0),
])
def test_design_search_on_a_double_and_a_triple_names_its_surfaces(short_suite, design, vary, surfaces, radius, mu):
    folder, suite = short_suite
    path = ROOT / "data" / "example_triple.toml" if design == "triple" else folder / "double.toml"
    result = search(path, two_period_target(0.75, 0.45, 8.0), suite, [vary], parameters={"n_pairs_min": 3}, jobs=1)
    table = result.table()
    columns = list(table.columns)
    assert columns[columns.index("mu_static") + 1:columns.index("mu_static") + 4] == [
        "bearing_surfaces", "equivalent_radius_m", "equivalent_mu"]
    assert len(table) == 2 and table["error"].isna().all(), table["error"].tolist()
    assert table["radius_m"].isna().all() and table["mu_kinetic"].isna().all() and table["mu_static"].isna().all()
    assert (table["bearing_surfaces"] == surfaces).all()
    assert table["equivalent_radius_m"].tolist() == pytest.approx([radius, radius], rel=1e-12)
    if mu is not None:
        assert table["equivalent_mu"].tolist() == pytest.approx([mu, mu], rel=1e-12)
    assert (table["design_displacement_m"] > 0).all() and (table["base_shear_coefficient"] > 0).all()
    assert result.to_dict()["candidates"][0]["bearing_surfaces"] == surfaces


def test_a_triples_row_columns_without_running_it():
    """The row's design columns alone (no engine): a single pendulum keeps radius_m/µ, a triple names its surfaces."""
    from isolator.design import Design
    from isolator.review.design_workers import design_columns

    triple = design_columns(Design.from_toml(ROOT / "data" / "example_triple.toml"))
    assert triple["radius_m"] is None and triple["mu_kinetic"] is None and triple["mu_static"] is None
    assert triple["bearing_surfaces"] == "triple: R 2.1/0.3/0.3/2.1 m, mu 0.06/0.02/0.02/0.1, d* 0.8/0.05/0.05/0.8 m"
    assert triple["equivalent_radius_m"] == pytest.approx(2.1 + 2.1, rel=1e-12)
    single = design_columns(Design.from_mapping({"name": "FPS", "mass_kg": 1e6, "radius_m": 2.5, "mu_static": 0.07,
                                                 "mu_kinetic": 0.06}))
    assert single == {"radius_m": 2.5, "mu_kinetic": 0.06, "mu_static": 0.07}
