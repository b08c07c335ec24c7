"""isolator.roots.brentq returns SciPy's brentq result bit for bit (the review's ELF fixed point depends on it)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq as scipy_brentq

from isolator.roots import brentq

FUNCTIONS = [
    ("cubic", lambda x: x ** 3 - 2 * x - 5, 2.0, 3.0),
    ("cos - x", lambda x: math.cos(x) - x, 0.0, 1.0),
    ("exp - 3", lambda x: math.exp(x) - 3.0, -4.0, 5.0),
    ("steep tanh", lambda x: math.tanh(40.0 * (x - 0.3)), -1.0, 1.0),
    ("flat near root", lambda x: (x - 1.0) ** 5, 0.0, 3.0),
    ("root at an end", lambda x: x * (x + 1.0), 0.0, 2.0),
    ("reversed bracket", lambda x: math.log(x), 5.0, 0.2),
    ("discontinuous step", lambda x: -1.0 if x < 0.7 else 1.0, 0.0, 1.0),
    ("tiny values", lambda x: 1e-200 * (x - 0.5), 0.0, 1.0),
    ("wide bracket", lambda x: math.atan(x - 1234.5), -1e6, 1e6),
]


@pytest.mark.parametrize(("name", "f", "a", "b"), FUNCTIONS, ids=[row[0] for row in FUNCTIONS])
@pytest.mark.parametrize(("xtol", "rtol"), [(2e-12, 8.881784197001252e-16), (1e-14, 1e-12), (1e-3, 1e-6)])
def test_equals_scipy_bit_for_bit(name, f, a, b, xtol, rtol):
    try:
        expected = scipy_brentq(f, a, b, xtol=xtol, rtol=rtol)
    except RuntimeError:  # SciPy does not converge in 100 iterations ((x - 1)^5 at the tight tolerance): nor do we
        with pytest.raises(RuntimeError, match="no convergence"):
            brentq(f, a, b, xtol=xtol, rtol=rtol)
        return
    assert brentq(f, a, b, xtol=xtol, rtol=rtol) == expected


def test_random_polynomials_equal_scipy():
    """300 random cubics on random brackets with a sign change: every root identical to SciPy's."""
    rng = np.random.default_rng(7)
    compared = 0
    for _ in range(2000):
        c = rng.normal(size=4)
        a, b = sorted(rng.uniform(-3.0, 3.0, size=2))

        def f(x, c=c):
            return ((c[0] * x + c[1]) * x + c[2]) * x + c[3]

        if f(a) * f(b) >= 0:
            continue
        assert brentq(f, a, b, xtol=1e-14, rtol=1e-12) == scipy_brentq(f, a, b, xtol=1e-14, rtol=1e-12)
        compared += 1
        if compared == 300:
            break
    assert compared == 300


def test_review_elf_equation_equals_scipy():
    """The ELF fixed point D = D_M(D) of the bundled example designs, as asce7_22.elf_displacement poses it."""
    from isolator.design import Design
    from isolator.review.codes.asce7_22 import damping_coefficient, effective_properties
    from isolator.review.examples import resolve_example
    from isolator.review.target import load_target

    target = load_target(resolve_example("target", "example"))
    compared = 0
    for name in ("example_review.toml", "example_building.toml", "example_pendulum.toml"):
        design = Design.from_toml(f"data/{name}")
        for mu in (0.6 * design.mu_kinetic, design.mu_kinetic, 1.4 * design.mu_kinetic):
            def gap(d, design=design, mu=mu):
                _, t, beta = effective_properties(design, mu, d)
                sa = float(target.sa_g(t, clip=True)[0])
                return design.gravity_m_s2 * sa * t * t / (4.0 * math.pi ** 2 * damping_coefficient(beta)) - d

            grid = np.geomspace(1e-5, 50.0, 400)
            values = np.array([gap(d) for d in grid])
            crossings = np.flatnonzero((values[:-1] > 0) & (values[1:] <= 0))
            for i in crossings:
                lo, hi = grid[i], grid[i + 1]
                assert brentq(gap, lo, hi, xtol=1e-14, rtol=1e-12) == scipy_brentq(gap, lo, hi, xtol=1e-14,
                                                                                 rtol=1e-12)
                compared += 1
    assert compared >= 6


@pytest.mark.parametrize(("kwargs", "error", "message"), [
    ({"xtol": 0.0}, ValueError, "xtol"), ({"rtol": 1e-17}, ValueError, "rtol"),
    ({"maxiter": 2}, RuntimeError, "no convergence")])
def test_refusals(kwargs, error, message):
    with pytest.raises(error, match=message):
        brentq(lambda x: math.cos(x) - x, 0.0, 1.0, **kwargs)
    with pytest.raises(ValueError, match="opposite signs"):
        brentq(lambda x: x * x + 1.0, -1.0, 1.0)
    with pytest.raises(ValueError, match="NaN"):
        brentq(lambda x: math.sqrt(x) - 0.5 if x >= 0 else math.nan, -1.0, 1.0)
