"""The 2-D building's sampled resultants taken at their candidates only (`largest_resultant`, `sampled_floor`).

The truth is numpy's own `np.max(np.hypot(x, y), axis=-1)` over every sample: the candidates' route must give the
same value bit for bit, on near-ties built to a few ulp, on zeros, subnormal and overflowing squares and on NaN.
"""

import numpy as np
import pytest

from isolator.solver.planar_building import largest_resultant, sampled_floor


def _truth(x, y):
    return np.max(np.hypot(x, y), axis=-1)


def _inverted_pairs(rng, scale, count):
    """Pairs of points within a few ulp of the radius ``scale`` whose sum of squares and hypot order them
    oppositely (s_p > s_q, hypot_p < hypot_q): the largest square is then not the largest resultant."""
    angles = rng.uniform(0.0, 2.0 * np.pi, 4000)
    radius = scale * (1.0 + rng.integers(-3, 4, 4000) * np.finfo(float).eps)
    x, y = radius * np.cos(angles), radius * np.sin(angles)
    squares, lengths = x * x + y * y, np.hypot(x, y)
    pairs = []
    for p in range(x.size):  # bounded: 4000 points
        q = np.flatnonzero((squares < squares[p]) & (lengths > lengths[p]))
        if q.size:
            pairs.append(((x[p], y[p]), (x[q[0]], y[q[0]])))
        if len(pairs) == count:
            break
    return pairs


def _near_ties(rng, rows, samples, scale):
    """Rows of smaller resultants holding one inverted pair each, at random places."""
    x = rng.standard_normal((rows, samples)) * scale * 0.3
    y = rng.standard_normal((rows, samples)) * scale * 0.3
    for r, (first, second) in enumerate(_inverted_pairs(rng, scale, rows)):
        where = rng.choice(samples, 2, replace=False)
        x[r, where], y[r, where] = (first[0], second[0]), (first[1], second[1])
    return x, y


@pytest.mark.parametrize("scale", [1.0, 3.7e-9, 2.0e5, 1e-150, 1e150])
def test_largest_resultant_equals_hypot_everywhere_on_near_ties(scale):
    rng = np.random.default_rng(7)
    for _ in range(20):
        x, y = _near_ties(rng, 10, 301, scale)
        assert np.array_equal(largest_resultant(x, y), _truth(x, y))


def test_largest_resultant_special_values():
    zeros = np.zeros((2, 50))
    assert np.array_equal(largest_resultant(zeros, zeros), np.zeros(2))
    tiny = np.array([[3e-160, -4e-160, 1e-161], [5e-324, 0.0, -5e-324]])
    assert np.array_equal(largest_resultant(tiny, tiny[::-1]), _truth(tiny, tiny[::-1]))
    huge = np.array([[1e200, -3e200, 2e199]])
    assert np.array_equal(largest_resultant(huge, huge * 0.5), _truth(huge, huge * 0.5))
    bad = np.array([[1.0, np.nan, 2.0]])
    assert np.isnan(largest_resultant(bad, bad)[0]) and np.isnan(_truth(bad, bad)[0])


def test_sampled_floor_against_the_histories_resultants():
    """The peaks held at or above the samples' resultants of the response's own layout: slab (samples, 2), floors
    (samples, n, 2) relative to the slab, drifts u_i − u_{i−1}; a located peak above them is kept."""
    rng = np.random.default_rng(3)
    n, samples = 4, 500
    m = 2 * n + 2
    state = rng.standard_normal((samples, 2, m))
    x_b, v_b = state[:, :, 0], state[:, :, 1]
    u = np.transpose(state[:, :, 2:2 + n], (0, 2, 1))
    drift = np.diff(np.concatenate([np.zeros((samples, 1, 2)), u], axis=1), axis=1)
    sampled = np.concatenate([[_truth(x_b[:, 0], x_b[:, 1]), _truth(v_b[:, 0], v_b[:, 1])],
                              _truth(drift[..., 0].T, drift[..., 1].T)])
    for shift in (-1e-3, 0.0, 1e-3):  # located peaks below, at and above the samples' largest
        peaks = np.concatenate([sampled * (1.0 + shift), [7.0, 8.0]])  # two more watched values, left alone
        out = sampled_floor(peaks, state, n)
        assert np.array_equal(out[:2 + n], np.maximum(peaks[:2 + n], sampled))
        assert np.array_equal(out[2 + n:], [7.0, 8.0])
