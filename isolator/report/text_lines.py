"""One-line strings of a text page, drawn straight through the renderer (the review PDF's rows and notes).

Rendering only.  ``fig.text`` makes a ``matplotlib.text.Text`` per string, and ``Text.draw`` shapes every
string twice with matplotlib 3.11 (FreeType and libraqm): once to measure its box for the alignment, once to
write it.  On the review's text pages (~24 000 glyphs, shaping 30-70 µs per glyph and pass on the shared
machine) the measuring pass is a third of the PDF's time.  A line aligned left at its top, bottom or baseline
needs no box: matplotlib places a single line's baseline at the font's ascent below its top (its descent
above its bottom) unless the line's own glyphs reach higher (lower): '|' or '√' in DejaVu Sans do, and Text
then sets that line a few hundredths of a point lower (tests/report/test_text_lines.py); here every line of
a font and size shares one baseline.  So :class:`TextLines` asks the renderer for
those two numbers once per font and size, and calls ``renderer.draw_text`` per line: the PDF gets the same
text objects (font, size, glyphs, kerning; selectable and extractable) as through ``fig.text``.  Only
right-aligned strings are measured (their width).
"""

from __future__ import annotations

from matplotlib.artist import Artist
from matplotlib.colors import to_rgba
from matplotlib.font_manager import FontProperties
from matplotlib.text import Text

ALIGN_H = ("left", "right")
ALIGN_V = ("top", "baseline", "bottom")


class TextLines(Artist):
    """Lines of text at figure coordinates, drawn in the order they were added (one artist per page).

    ``add(x, y, text, size=…, weight=…, color=…, family=…, ha=…, va=…)`` takes ``fig.text``'s arguments for
    one line (no newline, no mathtext: a ``$`` prints as itself); :func:`text_lines` returns a figure's
    instance.
    """

    zorder = 3  # as matplotlib's Text: above patches and lines drawn on the figure itself

    def __init__(self):
        super().__init__()
        self.rows: list[tuple] = []
        self._fonts: dict = {}

    def add(self, x: float, y: float, text: str, *, size: float, weight: str = "normal", color="k",
            family: str | None = None, ha: str = "left", va: str = "top") -> None:
        """One line at figure fraction (x, y) [-], ``size`` [pt]."""
        if "\n" in text:
            raise ValueError(f"one line per call, got {text!r}")
        if ha not in ALIGN_H or va not in ALIGN_V:
            raise ValueError(f"alignment {ha!r}/{va!r} not one of {ALIGN_H}/{ALIGN_V}")
        key = (float(size), weight, family)
        if key not in self._fonts:
            self._fonts[key] = FontProperties(size=size, weight=weight, family=family)
        self.rows.append((x, y, text, key, to_rgba(color), ha, va))
        self.stale = True

    def texts(self) -> list[str]:
        """The lines' strings, in drawing order."""
        return [row[2] for row in self.rows]

    def _ascent_descent(self, renderer, prop) -> tuple[float, float]:
        """(ascent, descent) [display units] matplotlib gives a one-line ``Text`` of ``prop`` whose glyphs
        stay within the font's ascent and descent (its OS/2 or hhea metrics, scaled): the box of a space, which
        has no ink, set on its baseline at 0."""
        box = Text(0.0, 0.0, " ", fontproperties=prop, va="baseline", figure=self.figure).get_window_extent(
            renderer)
        return box.y1, -box.y0

    def draw(self, renderer) -> None:
        if not self.get_visible() or not self.rows:
            return
        renderer.open_group("text_lines", self.get_gid())
        width, height = self.figure.bbox.width, self.figure.bbox.height
        flip = renderer.flipy()
        canvas_height = renderer.get_canvas_width_height()[1]
        metrics = {key: self._ascent_descent(renderer, prop) for key, prop in self._fonts.items()}
        gc = renderer.new_gc()
        for x, y, text, key, colour, ha, va in self.rows:
            if not text:
                continue
            prop = self._fonts[key]
            ascent, descent = metrics[key]
            px = x * width
            if ha == "right":
                px -= renderer.get_text_width_height_descent(text, prop, ismath=False)[0]
            py = y * height - (ascent if va == "top" else -descent if va == "bottom" else 0.0)
            gc.set_foreground(colour, isRGBA=True)
            renderer.draw_text(gc, px, canvas_height - py if flip else py, text, prop, 0.0, ismath=False)
        gc.restore()
        renderer.close_group("text_lines")
        self.stale = False


def text_lines(fig) -> TextLines:
    """``fig``'s :class:`TextLines` (added to it on the first call)."""
    for artist in fig.artists:
        if isinstance(artist, TextLines):
            return artist
    return fig.add_artist(TextLines())
