"""The 1-D System and the 2-D engine read K/M and γ/M by one rule (isolator.solver.system.check_nonnegative).

Each wrote it (system._check_finite_nonnegative, planar._finite_nonnegative); the 1-D one did not catch a value
that is no number: System(stiffness_per_mass=None) was a raw TypeError ("float() argument must be … not
'NoneType'") where the 2-D engine said one line.  Now both say the same line.
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.errors import InvalidSystemError
from isolator.solver.planar import simulate_pair
from isolator.solver.system import System, check_nonnegative


@pytest.mark.parametrize(("key", "value", "line"), [
    ("stiffness_per_mass", None, "stiffness_per_mass must be a number, got None"),
    ("damping_per_mass", "x", "damping_per_mass must be a number, got 'x'"),
    ("stiffness_per_mass", -1.0, "stiffness_per_mass must be a finite number ≥ 0, got -1.0"),
    ("damping_per_mass", float("nan"), "damping_per_mass must be a finite number ≥ 0, got nan"),
])
def test_the_1d_system_and_the_2d_engine_refuse_a_parameter_in_the_same_line(key, value, line):
    with pytest.raises(InvalidSystemError) as one_d:
        System(mu_static=0.05, **{key: value})
    with pytest.raises(InvalidSystemError) as two_d:
        simulate_pair(np.ones(3), np.zeros(3), 0.01, mu_static=0.05, **{key: value})
    assert str(one_d.value) == str(two_d.value) == line


def test_the_bound_and_its_reason_follow_the_value():
    assert check_nonnegative("k", 3) == 3.0 and check_nonnegative("k", 2.0, 2.0) == 2.0
    with pytest.raises(InvalidSystemError, match=r"^k = 3 exceeds 2 1/s²$"):
        check_nonnegative("k", 3.0, 2.0, " 1/s²")
