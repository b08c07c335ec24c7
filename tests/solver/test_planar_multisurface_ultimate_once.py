"""The rigid block's implicit steps at the ultimate on a double with an intermediate rim (issue 23).

The scene: surfaces (R̄, µ, rim) = (2.0, 0.03, 0.03), (2.0, 0.07, 0.3) under Northridge NWH360 (from 2 s) ×1.2 along
x and the reversed record ×0.72 along y, `2d-multisurface` by its implicit steps at step_tol 1e-7.  It stopped at the
steps' work bound twice (docs/multisurface.md, "Once per step"):

- at 2.97154 s, just after the impact at the ultimate: the full step and its halves classified the ultimate each at
  their own start and end (``ALIGNED``), so the full step (ending 1.27e-7 rad out of alignment) kept the chord's
  velocity while its halves were turned onto the ultimate circle; their velocities differed at first order in h and
  the steps settled at 4.75e-9 s.  Now the step classifies once, at its start, for the three solves;
- at 3.058 s, one group sliding along its rim and the other sliding inside, their edges 7° apart: each force solve
  started Newton from the one-group closed form, 0.07 W off along the rim's strip, and crawled back (26–57 iterations
  a solve).  Now Newton starts from the lower (in Ψ) of that point and the step's guess.

The truths here: the expansion of the step-doubling estimate (the full step and its halves agree to O(h²) when they
follow one motion), the uniqueness of Ψ's minimiser (the same force from any start), the ultimate circle Σ c̄, the
energy balance, and the pair's mirror symmetry.
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.solver import planar_multisurface_stepper as ps
from isolator.solver.planar_multisurface import simulate_bearing_pair
from tests.solver.test_building import real_segment
from tests.solver.test_building_multisurface import bearing

G = 9.80665
SURFACES = [(2.0, 0.03, 0.03), (2.0, 0.07, 0.3)]
RB = np.array([2.0, 2.0])
MU = np.array([0.03, 0.07])
RIM = np.array([0.03, 0.3])


def three_solves(y, r, h, abar, ult):
    """The full step and its two halves from y (ā constant), as the step loop takes them: their masks and ends."""
    y1, yh, y2 = (np.zeros_like(y) for _ in range(3))
    r1, rh, r2 = (np.zeros(3) for _ in range(3))
    m1 = ps.be_step(y, h, abar[0], abar[1], G, 0.0, RB, MU, RIM, r, y1, r1, 1.0, 1.0, ult)
    mh = ps.be_step(y, 0.5 * h, abar[0], abar[1], G, 0.0, RB, MU, RIM, r1, yh, rh, 1.0, 1.0, ult)
    m2 = ps.be_step(yh, 0.5 * h, abar[0], abar[1], G, 0.0, RB, MU, RIM, rh, y2, r2, 1.0, 1.0, ult)
    return (m1, mh, m2), y1, y2


def test_the_three_solves_of_a_step_from_the_ultimate_follow_one_motion():
    """The state the steps recorded at 2.971526 s (every group on its rim, aligned: the inner group sliding along its
    rim, the outer held on its rim by its larger friction), stepped with the ultimate classified once at the start:
    the full step and its halves agree in velocity to O(h²) at every h, across the band (4.27e-9 … 5.2e-9 s) where,
    classified per solve, the full step left the alignment (> ALIGNED) and its first half did not (their velocities
    apart by up to 9.4e-8 m/s at h = 4.27e-9 s: h × 22 m/s²)."""
    y = np.array([-0.2922332235752485, -0.15329625905027655, -0.41110352434071185, 0.7836988905374065,
                  1.9879402696186452, 0.7808164944759834, 0.0, 0.5926686177589751, -0.026566656688660317,
                  -0.013936023550025307, -0.2656665668866032, -0.13936023550025306, 0.0])
    r = np.array([-0.07539482603997445, 0.22444264696560284])
    abar = (0.7393705904646304, -2.2010303676156924)
    assert ps.at_ultimate(y, RIM)
    for h in (3e-9, 4.2663e-9, 4.5033e-9, 4.7403e-9, 4.9774e-9, 5.2144e-9, 7e-9, 1e-8, 1e-7, 1e-6, 1e-5):
        masks, y1, y2 = three_solves(y, r, h, abar, 1)
        assert masks[0] == masks[1] == masks[2] == 13, h  # the inner group sliding, both on their rims
        # measured: 1.2e-8 m/s at h = 1e-5 s, 1.2e-10 at 1e-6, ≤ 1.2e-14 at h ≤ 1e-8 (rounding)
        assert np.max(np.abs(y2[ps.Y_V:ps.Y_V + 2] - y1[ps.Y_V:ps.Y_V + 2])) <= 200.0 * h * h + 1e-13, h
        assert np.max(np.abs(y2[ps.Y_X:ps.Y_X + 2] - y1[ps.Y_X:ps.Y_X + 2])) <= 2.0 * h * h + 1e-15, h


def test_newton_starts_from_the_lower_of_the_step_s_guess_and_the_one_group_point():
    """The state at 3.039075 s (the inner group sliding along its rim, carrying slot set; the outer sliding inside at
    0.99 of its rim, their edges 7° apart), h = 1.458e-5 s: from the step's guess (the last step's force) Newton
    converges in a few iterations; from a far guess it starts at the one-group point and crawls along the rim's strip
    (32 iterations).  Ψ is strongly convex: both end at its one minimiser."""
    y = np.array([-0.31157465992254196, -0.0963720953497104, -0.1419124919516674, 0.8419037550881036,
                  1.9930448708533057, 0.8172627923957163, 0.0, 0.5926691353845663, -0.029953714815317636,
                  -0.0016658237489665046, -0.28162094510724184, -0.09470627160073929, 1.0])
    guess = (-0.15330078955682216, 0.02152352087878781)
    h = 1.4580622709728143e-05
    abar = (-4.535537505598048, 0.6593136024287967)
    alpha = 1.0 / (h * h)
    px, py = y[ps.Y_V] / h - abar[0], y[ps.Y_V + 1] / h - abar[1]
    near = ps.step_force(y, RB, MU, RIM, alpha, px, py, G, guess[0], guess[1])
    far = ps.step_force(y, RB, MU, RIM, alpha, px, py, G, 0.0, 0.0)
    assert 0 < near[2] <= 8 and near[3] <= 12  # measured: 4 iterations, 5 gradients
    assert far[2] >= 20  # measured: 32 (the crawl the guess avoids)
    assert abs(near[0] - far[0]) + abs(near[1] - far[1]) <= 1e-12


@pytest.fixture(scope="module")
def scene(records_dir):
    if not (records_dir / "at2" / "RSN1044_NORTHR_NWH360.AT2").exists():
        pytest.skip("RSN1044_NORTHR_NWH360.AT2 is not in ../shared/records")
    acc, dt = real_segment(records_dir, "RSN1044_NORTHR_NWH360.AT2", 2.0, 6.0)
    n = int(round(3.3 / dt)) + 1  # the steps are causal: the first 3.3 s of the 6 s scene, both stops in it
    ax, ay = 1.2 * acc[:n], 0.72 * acc[::-1][:n].copy()
    dbl = bearing("double", SURFACES)
    return [simulate_bearing_pair(ax, s * ay, dt, bearing=dbl, method="steps", step_tol=1e-7) for s in (1.0, -1.0)]


def test_the_double_with_an_intermediate_rim_answers_to_the_ultimate(scene):
    """It stopped at the work bound at 2.97154 s (then, the classification fixed, at 3.05847 s); it now answers:
    the ultimate circle Σ c̄ = 0.33 m reached, the impacts' impulse reported, the balance closed to the steps'
    dissipation, and the mirrored pair (y → −y) the mirrored answer."""
    res, mirror = scene
    assert res.ultimate_displacement_reached
    assert res.peak_displacement_m == pytest.approx(0.33, rel=1e-12)
    # measured: 2 impacts, 1.51522 m/s in all (the largest 0.894 m/s); 6 rim contacts
    assert res.n_impacts >= 1 and 1.0 < res.impact_impulse_m_s < 2.0
    assert res.energy_impact_J_per_kg > 0.0
    # measured 1.7e-6 of the input at step_tol 1e-7 (∝ step_tol: docs/multisurface.md, "Once per step")
    assert abs(res.energy_balance_error_J_per_kg) <= 3e-6 * res.energy_input_J_per_kg
    # measured bitwise (0.0)
    assert np.max(np.abs(mirror.displacement_m * [1.0, -1.0] - res.displacement_m)) <= 1e-12 * res.peak_displacement_m
    assert mirror.impact_impulse_m_s == pytest.approx(res.impact_impulse_m_s, rel=1e-12)
