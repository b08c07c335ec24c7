"""The 2-D building's measurement tools: the departures cut by a sample's end, the slides' sample bounds, the
kernel's time split by clock (``benchmarks.planar_building_split``, ``benchmarks.planar_building_slide_cost``).

Hand-made traces in the traced kernel's record format (``benchmarks.planar_building_slides._RECORDS``): the counts
and bounds are worked out by hand beside each assertion.  No kernel runs here.
"""

from __future__ import annotations

import pytest

from benchmarks.planar_building_slide_cost import split_by_clock
from benchmarks.planar_building_slides import slides
from benchmarks.planar_building_split import bounds, cut_excess, departures

DT = 0.01


def _piece(t, length, rem, departing=False, mode=2):
    return ("piece", t, mode, departing, 0, length, rem, -1, -1.0)


def _fast(t, fraction):
    return ("fast", t, fraction, 2)


def _trace():
    """Two slides: the first's departure series ends at its reach (2 ms, 8 ms left in the sample), the second's at
    its sample's end (0.1 ms after the break-away), then START, 3 stiff pieces, a refused sub-step and rungs."""
    return [
        ("event", 1.002, 0, 1.0),  # break-away
        _piece(1.002, 2e-3, 8e-3, departing=True),
        _piece(1.004, 5e-4, 6e-3),
        _fast(1.0045, 0.5),
        _fast(1.010, 1.0),  # first whole sub-step: sample 101
        _fast(1.020, 1.0),  # last whole sub-step: sample 102, ends at 103
        _fast(1.030, 0.25),
        _piece(1.0325, 1e-3, 7.5e-3),
        ("event", 1.0335, 1, 0.7),  # stick: ends in sample 103, its end 104
        ("event", 2.0099, 0, 1.0),  # break-away in sample 200, 0.1 ms before its end
        _piece(2.0099, 1e-4, 1e-4, departing=True),
        _piece(2.0100, 3.1e-4, 3.1e-4, mode=1),
        _piece(2.0101, 1e-6, 3e-4),
        _piece(2.01011, 1e-6, 3e-4),
        _piece(2.01012, 1e-6, 3e-4),
        ("refused", 2.0102, 1, 2),
        _fast(2.0103, 1.0 / 32.0),
        _fast(2.0106, 1.0 / 16.0),
        ("event", 2.0150, 1, 0.8),  # stick in sample 201 (no whole sub-step): its end 202
    ]


def test_departures_tell_a_cut_from_a_reach_and_count_their_steps():
    rows = departures(slides(_trace()))
    assert [r["start"] for r in rows] == [1.002, 2.0099]
    first, second = rows
    # the first: the departure piece (2 ms < 8 ms left) and one SLIDE piece, one rung, before sample 101's whole step
    assert first["cut"] is False and first["tau_s"] == pytest.approx(2e-3)
    assert (first["pieces"], first["rungs"], first["refused"]) == (2, 1, 0)
    # the second has no whole sub-step: all of it is departure (5 pieces, 2 rungs, 1 refused)
    assert second["cut"] is True and second["tau_s"] == pytest.approx(1e-4)
    assert (second["pieces"], second["rungs"], second["refused"]) == (5, 2, 1)
    excess = cut_excess(rows)
    assert (excess["cut"], excess["uncut"]) == (1, 1)
    assert (excess["median pieces"], excess["median rungs"]) == (2, 1)
    assert (excess["excess pieces"], excess["excess rungs"]) == (3, 1)


def test_bounds_are_the_samples_of_the_break_away_the_whole_sub_steps_and_the_stop():
    assert bounds(slides(_trace()), DT) == [[100, 101, 103, 104], [200, 202, 202, 202]]


def test_the_clock_split_covers_every_sample_once():
    kinds = split_by_clock([[100, 101, 103, 104], [200, 202, 202, 202]], 300)
    assert kinds == {"departure": [(100, 101), (200, 202)], "cruise": [(101, 103)], "approach": [(103, 104)],
                     "stuck": [(0, 100), (104, 200), (202, 300)]}
    spans = sorted(span for parts in kinds.values() for span in parts)
    assert spans[0][0] == 0 and spans[-1][1] == 300
    assert all(a[1] == b[0] for a, b in zip(spans[:-1], spans[1:], strict=True))
