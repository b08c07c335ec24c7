"""The building engines' one sub-step rule (isolator.solver.record.building_substeps), checked once per run.

The 1-D building, the 1-D building on a multi-surface bearing and the 2-D building each wrote the rule (the longest
sample interval over the step their fastest rate allows, at most MAX_SUBSTEPS_PER_INTERVAL) with the same line, and
each ran it twice: in its public entry before the kernel loads (session 14) and again inside its run.  Now one
function, called once by each entry, its count passed on.  The refusal's line is tests/test_hostile_s14.py's.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.errors import InvalidSystemError
from isolator.solver import building, building_multisurface, planar_building
from isolator.solver.record import MAX_SUBSTEPS_PER_INTERVAL, building_substeps

REASON = "the base slab is too light for the first story's stiffness, or a story too stiff for its mass"


def test_the_count_is_the_longest_interval_over_the_step():
    assert building_substeps(0.01, None, 0.004, "b") == 3  # 2.5 steps: the ceiling
    assert building_substeps(0.01, None, 0.02, "b") == 1
    assert building_substeps(0.01, None, math.inf, "b") == 1  # a system that does not move: one step
    times = np.array([0.0, 0.01, 0.035, 0.04])  # unequal: the longest interval 0.025 s sets the count
    assert building_substeps(0.0133, times, 0.01, "b") == 3


def test_the_bound_is_inclusive_and_the_refusal_one_line():
    assert building_substeps(0.01, None, 0.01 / 4999.5, "b") == MAX_SUBSTEPS_PER_INTERVAL == 5000
    with pytest.raises(InvalidSystemError) as refused:
        building_substeps(0.01, None, 0.01 / 5000.5, "the building's fastest rate 3.4e+10 1/s")
    assert str(refused.value) == ("the building's fastest rate 3.4e+10 1/s needs 5001 sub-steps per sample interval "
                                  f"of 0.01 s (at most 5000): {REASON}")
    with pytest.raises(InvalidSystemError, match=r"^b needs inf sub-steps"):
        building_substeps(0.01, None, 0.0, "b")  # a step that vanished: refused, not a ZeroDivisionError


def _superstructure():
    from isolator.superstructure import Floor, Superstructure

    return Superstructure(floors=(Floor(4e5, 3.0, 4e10, 4e10), Floor(3e5, 3.0, 3e10, 3e10)), damping_ratio=0.05,
                          gravity_m_s2=9.81)


def _calls(monkeypatch, module):
    calls = []

    def counted(*args, **kwargs):
        calls.append(building_substeps(*args, **kwargs))
        return calls[-1]

    monkeypatch.setattr(module, "building_substeps", counted)
    return calls


def _runs():
    from isolator.bearing import parse_bearing

    t = np.arange(400) * 0.01
    ax, ay = 3.0 * np.sin(2 * np.pi * t), 2.0 * np.cos(2 * np.pi * 0.7 * t)
    s = _superstructure()
    bearing = parse_bearing({"type": "double", "surface": [
        dict(radius_m=2.0, mu=0.05, displacement_capacity_m=0.3) for _ in range(2)]}, ValueError)
    common = dict(superstructure=s, total_mass_kg=9e5)
    return {
        building: lambda: building.simulate_building(ax, 0.01, stiffness_N_per_m=9e5 * 9.81 / 2.0, mu_static=0.05,
                                                     **common),
        building_multisurface: lambda: building_multisurface.simulate_building_bearing(ax, 0.01, bearing=bearing,
                                                                                       **common),
        planar_building: lambda: planar_building.simulate_planar_building(
            ax, ay, 0.01, stiffness_N_per_m=9e5 * 9.81 / 2.0, mu_static=0.05, **common),
    }


@pytest.mark.parametrize("module", [building, building_multisurface, planar_building],
                         ids=["1d-building", "1d-building-bearing", "2d-building"])
def test_each_driver_counts_once_per_run_and_runs_on_that_count(monkeypatch, module):
    run = _runs()[module]
    first = run()  # loads the kernel (its warm-up counts its own tiny record)
    calls = _calls(monkeypatch, module)
    again = run()
    assert len(calls) == 1
    assert np.array_equal(again.displacement_m, first.displacement_m)  # the same count, the same answer
    if module is not building_multisurface:  # the count from the fastest rate, as each driver wrote it before
        from isolator.solver import building_kernel, planar_building_kernel

        rate = again.building.fastest_rate_per_s
        theta = building_kernel.THETA if module is building else planar_building_kernel.THETA_FAST
        assert calls[0] == max(1, math.ceil(rate * 0.01 / theta)) > 1
