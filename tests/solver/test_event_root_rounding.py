"""The event root finder stops where Newton's correction falls below rounding (h183).

When the iterate already is the root to rounding, ``t - f/df`` rounds back to ``t`` itself, an end of the
bracket.  The root finder used to take that for a step out of the bracket and bisect from the bracket's far
end back to the same point: ~50 more evaluations of the closed form per root (El Centro under the TFP: 1 739
evaluations for 171 roots, 840 after).  Independent truth: the undamped free oscillation V = cos τ, whose stop
is π/2.
"""

from __future__ import annotations

import math

import pytest

import isolator.solver.events as events


@pytest.fixture
def counted(monkeypatch):
    """Count the closed-form evaluations of the pure-Python root finders (``py_func``)."""
    calls = []
    original = events.segment_state.py_func

    def state(*args):
        calls.append(args[0])
        return original(*args)

    monkeypatch.setattr(events, "segment_state", state)
    return calls


def test_stop_root_does_not_bisect_back_after_convergence(counted):
    # x0 = 0, v0 = 1, κ = 1: V = cos τ; at fl(π/2) cos is 6.1e-17 > 0 and the Newton step rounds to no move
    root = events.segment_root.py_func(0, 1.0, 0.0, 2.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.5)
    assert abs(root - math.pi / 2) <= 4e-16
    assert len(counted) <= 8  # 4 here; 42 on d556246 (the bisection from τ = 2 back to π/2)

