"""A group's stop located inside a step, only past the step floor (model ``2d-multisurface``, implicit steps;
docs/multisurface.md, "The located stop's cost").

The loop locates a group's stop inside a step (``locate_stop``: the longest step whose three solves all slide the
first half's set) and cuts the step there.  A stop located within the floor of the step's start (Fenz &
Constantinou's TFP under the 0.6 g / 0.5 g elliptical pulse at step_tol 1e-8, 0.88049 s: the outer groups stopping
as the inner group starts, cut at 9.4e-12 s) put the next steps below the floor, where a step is taken whatever its
error: one was accepted at 169 times its tolerance, and the motion so perturbed chattered at 0.965 s (135,713 steps
against 77,999 without the location).  Now such a stop is left to the step's error estimate (retried shorter).  The
truths: no step is accepted over its error at the floor, and the run agrees with the same run at a tenfold tighter
tolerance.
"""

from __future__ import annotations

import numpy as np

from isolator.solver import planar_multisurface_stepper as stepper
from isolator.solver.planar_multisurface import simulate_bearing_pair
from tests.solver.test_planar_multisurface_rim import TFP, G

#: the run at step_tol 1e-8 against 1e-9, the largest distance of the displacement and velocity histories (of their
#: peaks): 1.65e-8 and 3.25e-7 measured (main: 2.1e-7 and 6.2e-6 against this 1e-9 run)
XBOUND = 5e-8
VBOUND = 1e-6


def test_a_stop_at_a_steps_start_leaves_no_step_over_its_error_below_the_floor(monkeypatch):
    summaries = []
    kernel = stepper.planar_multisurface_stepper

    def recorded(*args):
        kernel(*args)
        summaries.append(args[18].copy())  # the run's summary (planar_multisurface_stepper's argument)

    monkeypatch.setattr(stepper, "planar_multisurface_stepper", recorded)
    t = np.arange(0.0, 1.0, 0.01)
    ax = 0.6 * G * np.sin(2 * np.pi * t / 2.0)
    ay = 0.5 * G * np.cos(2 * np.pi * t / 1.7)
    tight, tighter = [simulate_bearing_pair(ax, ay, 0.01, bearing=TFP, step_tol=tol) for tol in (1e-8, 1e-9)]
    # steps taken at the floor with their error above the tolerance: 0 (main: the step after the 9.4e-12 s cut)
    assert summaries[-2][stepper.S_STEPS_MULTI] == 0
    assert tight.ultimate_displacement_reached and tight.n_impacts == 1
    peak = tighter.peak_displacement_m
    dx = np.max(np.abs(tight.displacement_m - tighter.displacement_m)) / peak
    dv = np.max(np.abs(tight.velocity_m_s - tighter.velocity_m_s)) / tighter.peak_velocity_m_s
    assert dx <= XBOUND and dv <= VBOUND, (dx, dv)
