"""Regime maps: a coarse grid against direct threshold computations; the cache; the triple point."""

from __future__ import annotations

import numpy as np
import pytest

from isolator.maps import IN_PROCESS_POINTS, REGIME_NAMES, design_frame, nice_ceiling, regime_map, triple_point
from isolator.solver.harmonic import harmonic_response
from isolator.solver.thresholds import harmonic_thresholds


@pytest.fixture(autouse=True)
def _cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ISOLATOR_CACHE_DIR", str(tmp_path / "cache"))


def _regime_from_transitions(alpha, transitions):
    regime = "ST"
    for tr in transitions:
        if alpha > tr["alpha"]:
            regime = tr["to"]
    return regime


@pytest.mark.parametrize("eta,k_range,alpha_range,n_k", [
    (0.0, (0.0, 1.0), (0.0, 6.0), 3),   # inside Fig. 5a's frame (configuration 3, model 1)
    (0.05, (0.0, 5.0), (0.0, 8.0), 7),  # Fig. 7b
    (0.5, (0.0, 5.0), (0.0, 10.0), 7),  # Fig. 6 frame
])
def test_coarse_map_matches_thresholds(eta, k_range, alpha_range, n_k):
    mu_s = 0.25
    rmap = regime_map(eta, mu_s, k_range=k_range, alpha_range=alpha_range, n_k=n_k, n_alpha=11, workers=2)
    assert rmap.regime.shape == (11, n_k)
    checked = 0
    for j, k in enumerate(rmap.k):
        thresholds = harmonic_thresholds(k, eta, mu_s, alpha_max=alpha_range[1], n_grid=60)
        for i, alpha in enumerate(rmap.alpha):
            if any(abs(alpha - tr["alpha"]) < 1e-3 * alpha for tr in thresholds.transitions):
                continue  # on a boundary: either side is right
            expected = _regime_from_transitions(alpha, thresholds.transitions)
            assert REGIME_NAMES[rmap.regime[i, j]] == expected, (k, alpha)
            checked += 1
    assert checked > 5 * n_k
    # every transition along α is kept (not one curve): the map's list equals the direct one in each column
    for j in range(rmap.k.size):
        column = [REGIME_NAMES[c] for c in rmap.regime[:, j]]
        changes = sum(a != b for a, b in zip(column[:-1], column[1:], strict=True))
        assert len(rmap.transitions_along_alpha(j)) == changes


def test_map_cache_roundtrip(tmp_path):
    first = regime_map(0.2, 0.1, k_range=(0.0, 0.2), alpha_range=(0.0, 8.0), n_k=5, n_alpha=6, workers=1)
    assert not first.from_cache
    files = list((tmp_path / "cache" / "maps").iterdir())
    assert len(files) == 1 and files[0].suffix == ".npz"
    second = regime_map(0.2, 0.1, k_range=(0.0, 0.2), alpha_range=(0.0, 8.0), n_k=5, n_alpha=6, workers=1)
    assert second.from_cache
    for name in ("regime", "amplitude", "dominant", "rho_ef"):
        np.testing.assert_array_equal(getattr(first, name), getattr(second, name))
    regime_map(0.3, 0.1, k_range=(0.0, 0.2), alpha_range=(0.0, 8.0), n_k=5, n_alpha=6, workers=1)
    assert len(list((tmp_path / "cache" / "maps").iterdir())) == 2  # another η, another key


def test_parallel_equals_serial():
    kwargs = dict(k_range=(0.0, 3.0), alpha_range=(0.5, 6.0), n_k=16, n_alpha=17, use_cache=False)
    assert kwargs["n_k"] * kwargs["n_alpha"] >= IN_PROCESS_POINTS  # large enough to really use the pool
    serial = regime_map(0.5, 0.25, workers=1, **kwargs)
    parallel = regime_map(0.5, 0.25, workers=2, **kwargs)
    np.testing.assert_array_equal(serial.regime, parallel.regime)
    np.testing.assert_allclose(serial.amplitude, parallel.amplitude)


def test_triple_point_has_equal_forces():
    alpha_hat, k_hat = triple_point(0.5, 0.25)
    assert k_hat == pytest.approx(0.5 * np.sqrt(alpha_hat * 0.25))
    r = harmonic_response(alpha_hat, k_hat, 0.5, 0.25)
    assert r.rho_ev == pytest.approx(1.0, rel=1e-9)
    assert r.rho_ef == pytest.approx(1.0, rel=1e-6)
    assert r.rho_vf == pytest.approx(1.0, rel=1e-5)
    assert triple_point(0.0, 0.25) is None


def test_design_frame_is_rounded_and_contains_the_point():
    frame = design_frame(9.84, 0.0805)
    assert frame["k"][1] >= 0.0805 * 2.5 and frame["alpha"][1] >= 9.84 * 1.5
    assert nice_ceiling(0.2013) == 0.3 and nice_ceiling(14.76) == 15.0 and nice_ceiling(3.0) == 3.0


def test_refined_boundaries_equal_the_thresholds():
    """Bisected boundaries of a coarse Fig. 6 map sit on harmonic_thresholds' transitions."""
    from isolator.maps import boundary_segments

    rmap = regime_map(0.5, 0.25, k_range=(0.0, 5.0), alpha_range=(0.0, 10.0), n_k=5, n_alpha=9, workers=1,
                      refine=True)
    assert rmap.boundary_k.size >= 2 * rmap.k.size - 1
    for k in rmap.k:
        found = sorted(rmap.boundary_alpha[rmap.boundary_k == k])
        direct = [tr["alpha"] for tr in harmonic_thresholds(k, 0.5, 0.25, alpha_max=10.0, n_grid=60).transitions]
        assert len(found) == len(direct)
        np.testing.assert_allclose(found, direct, rtol=2e-4)
    assert len(boundary_segments(rmap, "SS", "SL")) == rmap.k.size - 1
    again = regime_map(0.5, 0.25, k_range=(0.0, 5.0), alpha_range=(0.0, 10.0), n_k=5, n_alpha=9, workers=1,
                       refine=True)
    assert again.from_cache and again.boundary_k.size == rmap.boundary_k.size
