"""isolator.report.text_lines: the review's text lines land where matplotlib's own Text puts them, as the same text."""

from __future__ import annotations

import pytest

from isolator.report import figures
from isolator.report.text_lines import TextLines, text_lines

pypdf = pytest.importorskip("pypdf")

#: (x, y, text, size, style): every alignment the review's pages use, sizes 7-13 pt, bold, grey, monospace, Greek
LINES = [
    (0.05, 0.975, "Design review: summary and checks", 13, {"weight": "bold"}),
    (0.95, 0.952, "5-story building on FPS R = 4.0 m, mu_s = 0.06 | example MCE_R", 7.5, {"ha": "right", "color": "0.35"}),
    (0.05, 0.9, "record_capacity", 7.4, {}),
    (0.245, 0.9, "ASCE 7-22 17.2.4.6 (corner bearing)", 7.4, {}),
    (0.76, 0.9, "fail", 7.4, {"weight": "bold", "color": "#c62828"}),
    (0.07, 0.8882, "µs = 0.06, µk = 0.05; α = PGA/(µs g); D_M ≥ 0.8 D'_TM — γ_x × 1.27 = 1.537 m", 7.0, {"color": "0.3"}),
    (0.05, 0.87, "3f1c0a9be2d84c51f1e8a7b6c5d4e3f2a1b0c9d8e7f6a5b4c3d2e1f0a9b8c7d6", 7.0, {"family": "monospace"}),
    (0.5, 0.5, "baseline aligned", 9.5, {"va": "baseline"}),
    (0.05, 0.012, "isolator 0.1.0, commit 04dc28b71c9f · page 3", 7.0, {"va": "bottom", "color": "0.35"}),
]


def _runs(path):
    """(text, x, y, size) of every text run of page 1, from the PDF's own text matrices [pt]."""
    runs = []

    def visit(text, cm, tm, font, size):
        if text.strip():
            runs.append((text, cm[4] + tm[4], cm[5] + tm[5], size * abs(tm[0] or 1)))

    pypdf.PdfReader(str(path)).pages[0].extract_text(visitor_text=visit)
    return runs


def _page(tmp_path, name, draw):
    fig = figures.new_figure(figsize=(8.27, 11.69))
    for x, y, text, size, style in LINES:
        draw(fig, x, y, text, size, style)
    out = tmp_path / name
    fig.savefig(out)
    return _runs(out)


def test_same_text_at_the_same_places_as_matplotlib_text(tmp_path):
    """Every line's string, size, x and baseline equal those of fig.text with the same alignment (to 0.01 pt), except
    a line with a glyph above the font's ascent, which Text sets a few hundredths of a point lower."""
    reference = _page(tmp_path, "text.pdf", lambda fig, x, y, text, size, style: fig.text(
        x, y, text, fontsize=size, va=style.get("va", "top"), **{k: v for k, v in style.items() if k != "va"}))
    ours = _page(tmp_path, "lines.pdf", lambda fig, x, y, text, size, style: text_lines(fig).add(
        x, y, text, size=size, **style))
    assert len(ours) == len(reference) >= len(LINES)
    assert [run[0] for run in ours] == [run[0] for run in reference]
    for mine, theirs in zip(ours, reference, strict=True):
        assert (mine[1], mine[3]) == pytest.approx((theirs[1], theirs[3]), abs=0.01), (mine, theirs)
        if "|" in mine[0]:  # '|' rises above the font's ascent: Text lowers that line's baseline by 0.03 pt
            assert 0.01 < mine[2] - theirs[2] < 0.1, (mine, theirs)
        else:
            assert mine[2] == pytest.approx(theirs[2], abs=0.01), (mine, theirs)


def test_one_artist_per_figure_in_drawing_order_and_one_line_per_call():
    fig = figures.new_figure()
    text_lines(fig).add(0.1, 0.9, "first", size=7)
    text_lines(fig).add(0.1, 0.8, "second", size=7)
    assert [a for a in fig.artists if isinstance(a, TextLines)] == [text_lines(fig)]
    assert text_lines(fig).texts() == ["first", "second"]
    with pytest.raises(ValueError, match="one line per call"):
        text_lines(fig).add(0.1, 0.7, "two\nlines", size=7)
    with pytest.raises(ValueError, match="alignment"):
        text_lines(fig).add(0.1, 0.7, "centred", size=7, ha="center")
