"""Method "events" of the 2-D multi-surface model never answers wrong without a word (h186, docs/multisurface.md "The
2-D event kernel's own balance check, its zero step's origin, one re-step loop").

* Its energy balance is read as "auto" reads it (EVENTS_BALANCE_TOL): Hector Mine ABY at rtol 1e-6 (outside RTOL_RANGE,
  opened here) was 0.25 of the peak off the kernel at 1e-13 with the balance open by 5.5e-3, and returned.
* The zero-length Radau step's origin (h178 guarded its division): an event found at a corner step's start (θ = 0: a
  group that joined with its λ already negative) was "located" by a re-step of length 0, which the Radau step refused,
  and the refused re-step's stale end state (a state of another θ) was taken as the step's end: Superstition Hills PTS
  at rtol 1e-5, 5.718 s, X jumped by 1.5e-2 m and V by 6.2e-2 m/s.  The state at θ = 0 is the start's.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import isolator.solver.planar_multisurface as pm
from isolator.bench.tfp import tfp_bearing
from isolator.errors import SolverError
from isolator.motion import read_ground_motion

EXAMPLE = Path(__file__).resolve().parents[2] / "isolator" / "data" / "suites" / "example"


def _pair(folder, x, y, seconds=None):
    mx, my = (read_ground_motion(EXAMPLE / folder / name) for name in (x, y))
    n = min(mx.npts, my.npts) if seconds is None else int(round(seconds / mx.dt_s)) + 1
    return mx.acceleration_m_s2[:n], my.acceleration_m_s2[:n], mx.dt_s


def test_events_refuses_an_answer_whose_energy_balance_is_open(monkeypatch):
    ax, ay, dt = _pair("hectormine1999_ABY", "RSN1762_HECTOR_ABY090.AT2", "RSN1762_HECTOR_ABY360.AT2")
    # at the default rtol the balance closes (the check refuses no good answer)
    good = pm.simulate_bearing_pair(ax, ay, dt, bearing=tfp_bearing(), method="events")
    assert abs(good.energy_balance_error_J_per_kg) <= pm.EVENTS_BALANCE_TOL * good.energy_input_J_per_kg
    # rtol 1e-6 (refused by RTOL_RANGE since h171; opened here to reach a broken answer): on d556246 it returned an
    # answer 0.25 of the peak off, balance open by 5.5e-3 (the test failed there: no SolverError)
    monkeypatch.setattr(pm, "RTOL_RANGE", (1e-13, 1e-5))
    with pytest.raises(SolverError, match=r"energy balance open by [0-9.e+-]+ of the input") as err:
        pm.simulate_bearing_pair(ax, ay, dt, bearing=tfp_bearing(), rtol=1e-6, method="events")
    assert "\n" not in str(err.value)


def test_an_event_at_a_corner_steps_start_keeps_the_state_of_that_start(monkeypatch):
    # PTS 0-5.75 s at rtol 1e-5, method "events", its balance check off (the kernel's own answer is tested): at
    # 5.718368 s a group joins a corner of three with its λ at once -111; the next step's leave is at θ = 0.  Every
    # sample the kernel answers (it may stop: a SolverError) lies within 1e-3 of the peak from the kernel at rtol 1e-13.
    # measured 3.8e-5 of the peak up to the stop (chatter at 5.71837 s); on d556246 the stale re-step's state was taken
    # there and the run went on, 0.116 of the peak off
    ax, ay, dt = _pair("superstitionhills1987_PTS", "RSN723_SUPER.B_B-PTS225.AT2", "RSN723_SUPER.B_B-PTS315.AT2", 5.75)
    tight = pm.simulate_bearing_pair(ax, ay, dt, bearing=tfp_bearing(), rtol=1e-13, method="events")
    peak = float(np.max(np.hypot(*tight.displacement_m.T)))
    monkeypatch.setattr(pm, "RTOL_RANGE", (1e-13, 1e-5))
    monkeypatch.setattr(pm, "EVENTS_BALANCE_TOL", np.inf)
    run = pm._run
    seen = []

    def kept(*args):
        out = run(*args)
        seen.append(out[0].copy())
        return out

    monkeypatch.setattr(pm, "_run", kept)
    try:
        pm.simulate_bearing_pair(ax, ay, dt, bearing=tfp_bearing(), rtol=1e-5, method="events")
    except SolverError:
        pass
    x = seen[-1]
    answered = np.isfinite(x[:, 0])
    assert answered[:int(round(5.7 / dt))].all()
    off = float(np.max(np.hypot(*(x[answered] - tight.displacement_m[answered]).T))) / peak
    assert off < 1e-3, off
