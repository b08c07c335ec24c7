"""Page helpers the report's PDFs share: the A4 page, its title, captions, tables of rows, numbers as text.

Rendering only (no physics): :mod:`isolator.report.pdf` (one component),
:mod:`isolator.report.pair` (a pair) and the review's pages lay their pages out with them.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np

from isolator.report import figures

A4_IN = (8.27, 11.69)  #: A4 page [in]


def fmt(value, digits: int = 4) -> str:
    """A number for a reader: ``digits`` significant figures, 'n/a' for None/NaN, '∞' for inf."""
    if value is None:
        return "n/a"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    value = float(value)
    if math.isnan(value):
        return "n/a"
    if math.isinf(value):
        return "inf"
    return format(value, f".{digits}g")


def tail(text: str, width: int) -> str:
    """``text`` cut at the front to ``width`` characters (file names keep their end)."""
    return text if len(text) <= width else "…" + text[-(width - 1):]


def page(number: int, subtitle: str, titles):
    """A new A4 page: ``titles[number - 1]`` at the top left, ``subtitle`` (shortened) at the top right."""
    fig = figures.new_figure(figsize=A4_IN)
    fig.text(0.05, 0.975, titles[number - 1], fontsize=13, weight="bold", va="top")
    fig.text(0.95, 0.975, textwrap.shorten(subtitle, 80, placeholder="…"), fontsize=7.5, va="top", ha="right",
             color="0.35")
    return fig


def caption(fig, text: str, y: float = 0.012) -> None:
    """A wrapped caption at the foot of a page (figure coordinates)."""
    fig.text(0.05, y, textwrap.fill(text, 150), fontsize=7.2, va="bottom", ha="left", color="0.15")


def table(fig, x: float, y: float, title: str, rows, width: float = 0.43, line: float = 0.0145) -> float:
    """Rows of (name, value) text at figure coordinates; returns the y below the table."""
    fig.text(x, y, title, fontsize=9.5, weight="bold", va="top")
    y -= line * 1.35
    for name, value in rows:
        fig.text(x, y, name, fontsize=7.8, va="top")
        fig.text(x + 0.42 * width, y, value, fontsize=7.8, va="top")
        y -= line
    return y - line * 0.6


def cells(fig, y: float, columns, texts, *, bold: bool = False, colour="k", size: float = 7.6) -> None:
    """One row of a table: ``texts`` at the figure x positions ``columns``, at height ``y``."""
    for x, text in zip(columns, texts, strict=True):
        fig.text(x, y, text, fontsize=size, va="top", weight="bold" if bold else "normal",
                 color=colour(x) if callable(colour) else colour)
