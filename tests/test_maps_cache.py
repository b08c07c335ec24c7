"""The map cache: damaged, reshaped, made-up or pickled entries are recomputed (and said so); workers capped."""

from __future__ import annotations

import numpy as np
import pytest

from isolator.errors import CacheEntryError
from isolator.maps import RegimeMap, cache_dir, regime_map
from isolator.parallel import available_cores, capped_workers

FRAME = {"k_range": (0.0, 2.0), "alpha_range": (0.0, 4.0), "n_k": 8, "n_alpha": 8}


@pytest.fixture(autouse=True)
def _private_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ISOLATOR_CACHE_DIR", str(tmp_path / "cache"))


def _entry():
    fresh = regime_map(0.5, 0.25, workers=1, **FRAME)
    (path,) = cache_dir().glob("map-*.npz")
    return fresh, path


def _rewrite(path, rmap, **overrides):
    arrays = {name: getattr(rmap, name) for name in RegimeMap._ARRAYS}
    arrays.update(overrides)
    fake = RegimeMap(**arrays, eta=rmap.eta, mu_s=rmap.mu_s, mu_k=rmap.mu_k)
    with open(path, "wb") as stream:  # a valid content key: only the solver can tell
        np.savez(stream, **arrays, params=np.array([rmap.eta, rmap.mu_s, rmap.mu_k, 0.0]),
                 content_key=np.array(fake.content_key()))


def _assert_recomputed(fresh, path, words):
    again = regime_map(0.5, 0.25, workers=1, **FRAME)
    assert not again.from_cache
    assert any(words in note and str(path) in note and "recomputed" in note for note in again.notes), again.notes
    np.testing.assert_array_equal(again.regime, fresh.regime)
    # and the rewritten entry is good again
    assert regime_map(0.5, 0.25, workers=1, **FRAME).from_cache


def test_intact_entry_is_read_without_a_note():
    fresh, _ = _entry()
    cached = regime_map(0.5, 0.25, workers=1, **FRAME)
    assert cached.from_cache and cached.notes == []
    np.testing.assert_array_equal(cached.amplitude, fresh.amplitude)


def test_truncated_entry_is_recomputed():
    fresh, path = _entry()
    path.write_bytes(path.read_bytes()[:200])  # BadZipFile
    _assert_recomputed(fresh, path, "unreadable")


def test_flipped_byte_breaks_the_content_key():
    fresh, path = _entry()
    rmap = RegimeMap.load(path)
    amplitude = rmap.amplitude.copy()
    amplitude[3, 3] += 1e-3
    arrays = {name: getattr(rmap, name) for name in RegimeMap._ARRAYS} | {"amplitude": amplitude}
    with open(path, "wb") as stream:
        np.savez(stream, **arrays, params=np.array([0.5, 0.25, 0.25, 0.0]), content_key=np.array(rmap.content_key()))
    with pytest.raises(CacheEntryError, match="content key"):
        RegimeMap.load(path)
    _assert_recomputed(fresh, path, "content key")


def test_wrong_shapes_are_refused():
    fresh, path = _entry()
    _rewrite(path, fresh, regime=fresh.regime[:4])
    _assert_recomputed(fresh, path, "shape")


def test_made_up_regimes_with_a_valid_key_are_caught_by_the_solver():
    fresh, path = _entry()
    # every ST ↔ SL swapped and every amplitude doubled: each grid point now disagrees
    _rewrite(path, fresh, regime=(2 - fresh.regime).astype(np.int8), amplitude=2 * fresh.amplitude)
    assert np.all((fresh.regime != 1) | (fresh.amplitude > 0))
    _assert_recomputed(fresh, path, "disagrees with the solver")


def test_codes_outside_the_regimes_are_refused():
    fresh, path = _entry()
    _rewrite(path, fresh, regime=np.full_like(fresh.regime, 7))
    _assert_recomputed(fresh, path, "codes outside")


def test_pickled_arrays_are_never_loaded():
    fresh, path = _entry()
    arrays = {name: getattr(fresh, name) for name in RegimeMap._ARRAYS}
    arrays["k"] = np.array([object()] * 8, dtype=object)
    with open(path, "wb") as stream:
        np.savez(stream, **arrays, params=np.array([0.5, 0.25, 0.25, 0.0]), content_key=np.array("x"))
    with pytest.raises(CacheEntryError, match="unreadable"):
        RegimeMap.load(path)
    _assert_recomputed(fresh, path, "unreadable")


def test_workers_are_capped_at_the_cores():
    cores = available_cores()
    note = f"{cores + 14} workers asked, {cores} used (this machine gives this process {cores} cores)"
    assert capped_workers(cores + 14) == (cores, note)
    assert capped_workers(1) == (1, "")
    rmap = regime_map(0.5, 0.25, workers=cores + 14, use_cache=False, **FRAME)
    assert rmap.notes == [note]
