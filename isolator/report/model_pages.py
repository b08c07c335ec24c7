"""The pages a report adds for what a model carries beyond the isolator: the building above it
(:mod:`isolator.report.building_page`), a double or triple bearing (:mod:`isolator.report.bearing_page`).

Both reports (one component, :mod:`isolator.report.pdf`; the planar and multi-surface one,
:mod:`isolator.report.pair`) append :func:`model_pages` after their own pages; rendering only.
"""

from __future__ import annotations

from isolator.report.bearing_page import bearing_page, has_multisurface_bearing
from isolator.report.building_page import building_page, has_building


def n_model_pages(numbers: dict) -> int:
    """How many pages :func:`model_pages` adds for an analysis' numbers (:meth:`~isolator.analysis.Analysis.to_dict`)."""
    return int(has_building(numbers)) + int(has_multisurface_bearing(numbers))


def model_pages(analysis, numbers: dict, label: str, first_number: int) -> list:
    """The model's own pages of a report, numbered from ``first_number``.

    Parameters
    ----------
    analysis : isolator.analysis.Analysis
        The analysis rendered (its response gives the histories drawn).
    numbers : dict
        Its :meth:`~isolator.analysis.Analysis.to_dict` (every number printed comes from it).
    label : str
        The report's subtitle.
    first_number : int
        The number of the first page added.

    Returns
    -------
    list of matplotlib.figure.Figure
    """
    pages = []
    if has_building(numbers):
        pages.append(building_page(first_number + len(pages), label, numbers, analysis.response))
    if has_multisurface_bearing(numbers):
        pages.append(bearing_page(first_number + len(pages), label, numbers, analysis.response,
                                  analysis.design.mass_kg))
    return pages
