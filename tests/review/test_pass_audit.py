"""The audit of the rows that can say ``pass`` (issue 22): none passes over part of the suite.

An analysis that failed, or that its solver flagged (``solver_status`` other than ``ok``), is left out of the suite
values; a row computed from the analyses then cannot pass (it is ``not checked``, naming them), a failure stands,
and ``suite_size`` counts only the pairs analysed at every bound.  The rows from the spectra, the ELF or the design
alone are not touched.
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.design import Design
from isolator.review import worker
from isolator.review.assess import FROM_ANALYSES
from isolator.review.run import run_review
from isolator.review.suite import load_suite
from isolator.review.target import two_period_target

#: a capacity so large that every analysis passes it, so that a 'pass' is what the flag must take away
DESIGN = {"name": "audit", "mass_kg": 1.0e6, "radius_m": 2.5, "mu_static": 0.06, "mu_kinetic": 0.05,
          "displacement_capacity_m": 5.0, "lambda_max": 1.3, "lambda_min": 0.8}
TARGET = two_period_target(1.5, 0.9, 8.0)


def _review(inputs, tmp_path, monkeypatch, spoil):
    real = worker.analyse_task

    def analyse(task):
        result = real(task)
        same = task["ax"].shape == ABY[0].shape and np.array_equal(task["ax"], ABY[0])
        return spoil(result) if same else result

    suite = load_suite(inputs / "suite.toml")
    ABY[:] = [next(p.ax_m_s2 for p in suite.pairs if p.name == "hectormine1999_ABY")]
    monkeypatch.setattr(worker, "analyse_task", analyse)
    return run_review(Design.from_mapping(DESIGN), TARGET, suite, jobs=1, nominal=False, cache_dir=tmp_path / "c")


ABY: list = []


@pytest.mark.parametrize("spoil,said", [
    (lambda r: {"error": "RuntimeError: made to fail by the test"}, "hectormine1999_ABY (lower): failed"),
    (lambda r: {**r, "solver_status": "chatter guard: made up by the test"},
     "hectormine1999_ABY (lower): its solver says chatter guard"),
])
def test_no_row_passes_over_part_of_the_suite(inputs, tmp_path, monkeypatch, spoil, said):
    r = _review(inputs, tmp_path, monkeypatch, spoil)
    rows = {row["id"]: row for row in r.checks}
    assert rows["suite_size"]["value"] == 2 and "hectormine1999_ABY" in rows["suite_size"]["note"]
    from_analyses = [row for row in r.checks if row["id"] in FROM_ANALYSES]
    assert from_analyses and not [row["id"] for row in from_analyses if row["status"] == "pass"]
    # the capacity rows were computed and would pass: they say why they do not
    for id_ in ("record_capacity", "D_M_capacity", "D_TM_capacity"):
        assert rows[id_]["status"] == "not checked" and said in rows[id_]["note"], id_
        assert "would pass over the analyses that ran" in rows[id_]["note"]
    # rows of the spectra and the selection are not touched
    assert rows["suite_spectrum"]["status"] == "pass" and rows["distinct_motions"]["status"] == "pass"


def test_a_complete_suite_keeps_its_passes(review):
    """The session's review: every analysis ran and none is flagged, so the capacity rows pass as computed."""
    rows = {row["id"]: row for row in review.checks}
    assert rows["suite_size"]["value"] == 3 and "every pair analysed at every bound" in rows["suite_size"]["note"]
    assert not [row for row in review.checks if "not usable" in row["note"]]
