"""isolator.report.pdf: four pages whose text is the analysis' numbers, light fonts, atomic output."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from isolator.analysis import analyse
from isolator.design import Design
from isolator.motion import GroundMotion
from isolator.report import figures
from isolator.report.pdf import PAGE_TITLES, fmt, write_report
from isolator.units import STANDARD_GRAVITY

pypdf = pytest.importorskip("pypdf")
DATA = Path(__file__).resolve().parents[2] / "data"


@pytest.fixture(scope="module")
def damped_analysis(tmp_path_factory):
    """The damped example pendulum (η > 0: all three forces) under 30 s of a 1 Hz sine of 0.25 g."""
    dt = 0.01
    t = np.arange(3001) * dt
    acc = 0.25 * STANDARD_GRAVITY * np.sin(2 * np.pi * 1.0 * t) * np.minimum(1.0, t / 5.0)
    motion = GroundMotion.from_array(acc, dt, units_source="synthetic, m/s2", component="X")
    design = Design.from_toml(DATA / "example_pendulum_damped.toml")
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("ISOLATOR_CACHE_DIR", str(tmp_path_factory.mktemp("cache")))
        return analyse(design, motion, map_resolution=8, workers=1, record_label="sine 1 Hz")


@pytest.fixture(scope="module")
def written(damped_analysis, tmp_path_factory):
    out = tmp_path_factory.mktemp("pdf") / "review.pdf"
    summary = write_report(damped_analysis, out, command="isolator report --design damped.toml sine")
    return out, summary


def _texts(path: Path) -> list[str]:
    return [" ".join(page.extract_text().split()) for page in pypdf.PdfReader(str(path)).pages]


def test_four_pages_with_their_titles_and_the_json_beside(written):
    out, summary = written
    texts = _texts(out)
    assert len(texts) == len(PAGE_TITLES) == 4
    for title, text in zip(PAGE_TITLES, texts, strict=True):
        assert " ".join(title.split()) in text
    on_disk = json.loads(out.with_suffix(".json").read_text())
    assert on_disk == summary and on_disk["pdf"] == str(out)
    assert sorted(p.name for p in out.parent.iterdir()) == ["review.json", "review.pdf"]  # no temporary left


def test_the_pages_print_the_analysis_numbers(written, damped_analysis):
    out, summary = written
    page1, page2, page3, page4 = _texts(out)
    a = damped_analysis
    for value in (a.adaptation.point.alpha, a.adaptation.point.k, a.adaptation.point.eta,
                  a.response.peak_displacement_m, a.response.residual_displacement_m):
        assert fmt(value) in page1
    assert a.record_class.regime in page1 and a.harmonic_class.regime in page1
    assert "isolator report --design damped.toml sine" in page1  # the command line in the footer
    assert f"isolated period T = {a.design.isolated_period_s:.3g} s" in page2
    final_input_kJ = a.response.energy_input_J_per_kg * a.design.mass_kg / 1e3
    assert f"at the end input {fmt(final_input_kJ)} kJ" in page3  # caption from the exact energies
    assert f"Regime map at η = {fmt(a.adaptation.point.eta, 3)}" in page4
    assert f"the record: {a.record_class.regime}, A = {fmt(a.record_class.amplitude, 3)}" in page4


def test_fonts_are_type3_not_embedded_truetype(written):
    """Type 3 glyph procedures: no fontTools subsetting of TrueType files (the slow step), text kept."""
    out, _ = written
    reader = pypdf.PdfReader(str(out))
    subtypes = set()
    for page in reader.pages:
        fonts = page["/Resources"]["/Font"]
        for ref in fonts.values():
            font = ref.get_object()
            subtypes.add(font["/Subtype"])
            assert "/FontFile2" not in font.get("/FontDescriptor", {})
    assert subtypes == {"/Type3"}


def test_a_failure_while_rendering_leaves_the_previous_report(damped_analysis, tmp_path, monkeypatch):
    out = tmp_path / "review.pdf"
    out.write_bytes(b"%PDF-1.4 previous report\n")

    def broken(*args, **kwargs):
        raise RuntimeError("renderer failed on page 3")

    monkeypatch.setattr(figures, "response_page", broken)
    with pytest.raises(RuntimeError, match="page 3"):
        write_report(damped_analysis, out)
    assert out.read_bytes() == b"%PDF-1.4 previous report\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["review.pdf"]  # no partial PDF, no JSON


def test_a_report_needs_the_map(damped_analysis, tmp_path):
    from dataclasses import replace

    with pytest.raises(ValueError, match="map_resolution"):
        write_report(replace(damped_analysis, harmonic_map=None), tmp_path / "x.pdf")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("value,digits,expected", [
    (None, 4, "n/a"), (math.nan, 4, "n/a"), (math.inf, 4, "inf"), (True, 4, "yes"), (False, 4, "no"),
    (np.int64(42), 4, "42"), (0.0839387, 4, "0.08394"), (2.0, 4, "2"), (123456.0, 3, "1.23e+05"),
    (np.float64(-1.5e-7), 2, "-1.5e-07"),
])
def test_fmt(value, digits, expected):
    assert fmt(value, digits) == expected
