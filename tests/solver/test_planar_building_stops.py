"""The 2-D building's stops: the isolator force never exceeds what the spring and the static friction can give.

A physical bound, independent of the solver: the isolator force on the slab is the spring's −K X plus the
friction, whose magnitude is µk N while sliding and at most µs N while stuck (no dashpot here), so at every
instant |F_iso| ≤ K |X| + µs N and its peak over time ≤ K max|X| + µs N.  A stop that the kernel failed to declare
(the slab left sliding at |V| ~ 1e-16 m/s, where V/|V| is rounding and the series' derivatives are noise) broke
it: the example building under Hector Mine ABY × 1.568 read 0.142 W against 0.072 W (docs/building.md).  Here on
every pair of the example suite (isolator/data/suites/example, in the repository), whole records, two friction
bounds, each with many stops.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from isolator.design import Design
from isolator.solver.planar_building import simulate_planar_building

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "data" / "example_building.toml"
SUITE = ROOT / "isolator" / "data" / "suites" / "example" / "suite.toml"
#: the example's µs/µk at nominal and at about its upper bound (λ_max ≈ 1.48)
FRICTION = ((0.06, 0.05), (0.089, 0.074))
#: every pair scaled to this peak ground acceleration [m/s²]: the slab slides and stops many times
PGA_M_S2 = 6.0


@pytest.fixture(scope="module")
def building():
    return Design.from_toml(EXAMPLE)


@pytest.fixture(scope="module")
def pairs():
    from isolator.review import load_suite

    return load_suite(SUITE).pairs


@pytest.mark.parametrize("index", range(8))
def test_the_isolator_force_stays_within_the_spring_and_the_static_friction(building, pairs, index):
    pair = pairs[index]
    factor = PGA_M_S2 / pair.pga_m_s2
    weight = building.mass_kg * building.gravity_m_s2
    stiffness = weight / building.radius_m
    for mu_s, mu_k in FRICTION:
        r = simulate_planar_building(factor * pair.ax_m_s2, factor * pair.ay_m_s2, pair.dt_s,
                                     superstructure=building.superstructure, total_mass_kg=building.mass_kg,
                                     stiffness_N_per_m=stiffness, mu_static=mu_s, mu_kinetic=mu_k,
                                     gravity_m_s2=building.gravity_m_s2)
        assert r.message == "ok"
        assert np.count_nonzero(r.event_kind == 1) >= 1  # a stop that sticks: the case under test
        # at every sample ...
        bound = stiffness * np.hypot(*r.displacement_m.T) + mu_s * weight
        assert np.all(np.hypot(*r.isolator_force_N.T) <= bound * (1 + 1e-9) + 1e-9 * weight)
        # ... and the exact peak located between samples
        assert r.base_shear_coefficient <= (r.peak_displacement_m / building.radius_m + mu_s) * (1 + 1e-9), \
            (pair.name, mu_s, r.base_shear_coefficient, r.peak_displacement_m / building.radius_m + mu_s)
