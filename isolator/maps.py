r"""Harmonic regime maps in the (k, α) plane (Nicolas 2017, Figs. 5–7), cached on disk.

Every grid point is one call of the core solver
(:func:`isolator.solver.harmonic.harmonic_response`): regime, ζ, A, the Eq. 5 ratios
and the dominant force.  Nothing of the regime logic is re-derived here; the map only
samples it.  Points with α ≤ 1 are ST without a call (the block cannot break away,
whatever k and η).  The grid is computed in parallel over processes
(:class:`concurrent.futures.ProcessPoolExecutor`), then stored as ``.npz`` under
:func:`cache_dir` keyed by a hash of the frame, the resolution, η, µs, µk and
:data:`MAP_FORMAT_VERSION` with the package version.

Lines derived from the grid (drawn by :mod:`isolator.report.figures`):

* regime boundaries: every change of regime along α, so SS/SL/SS/SL sequences show;
* the A > 1 region;
* ρ_ev = 1 (exactly α = k²/(η² µs)), ρ_vf = 1, ρ_ef = 1 and the dominance regions;
* the triple point, where ρ_ev = ρ_ef = 1: k̂ = η sqrt(α̂ µs) with k̂ A(α̂, k̂) = µk,
  solved by bisection along the ρ_ev = 1 line (:func:`triple_point`);
* the resonance line (α of the largest A at each k, where that maximum lies inside
  the frame) and the undamped resonance α = k/µs.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import time
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path

import numpy as np

from isolator.atomic import atomic_path, open_regular_file
from isolator.errors import CacheEntryError, InvalidSystemError
from isolator.metrics import FORCE_NAMES
from isolator.metrics import REGIMES as REGIME_NAMES

MAP_FORMAT_VERSION = 2  #: bump when the content of a cached map changes
REGIME_CODES = {name: code for code, name in enumerate(REGIME_NAMES)}


FORCE_CODES = {name: code for code, name in enumerate(FORCE_NAMES)}

#: The paper's frames (µs = 0.25, model 1 unless µk is given): (k_min, k_max, α_min, α_max, η)
PAPER_FRAMES = {
    "fig5a": {"k": (0.0, 6.0), "alpha": (0.0, 6.0), "eta": 0.0, "mu_s": 0.25},
    "fig6": {"k": (0.0, 5.0), "alpha": (0.0, 10.0), "eta": 0.5, "mu_s": 0.25},
}


def cache_dir() -> Path:
    """Where maps are cached: ``$ISOLATOR_CACHE_DIR/maps`` or ``~/.cache/isolator/maps``."""
    root = os.environ.get("ISOLATOR_CACHE_DIR")
    base = Path(root) if root else Path.home() / ".cache" / "isolator"
    return base / "maps"


@dataclass
class RegimeMap:
    """A sampled regime map; 2-D arrays are indexed [α, k].

    Attributes
    ----------
    k, alpha : numpy.ndarray
        Grid axes [-].
    regime : numpy.ndarray
        Regime codes (0 ST, 1 SS, 2 SL).
    amplitude, zeta : numpy.ndarray
        A and ζ of the steady response [-].
    rho_ev, rho_vf, rho_ef : numpy.ndarray
        Eq. 5 ratios (NaN where undefined or infinite).
    dominant : numpy.ndarray
        Dominant-force codes (0 friction, 1 elastic, 2 viscous).
    steady : numpy.ndarray
        False where the solver stopped at resonant growth (A is then a lower bound).
    eta, mu_s, mu_k : float
        Fixed parameters [-].
    elapsed_s : float
        Wall time of the computation [s] (0 if unknown).
    from_cache : bool
        Whether it was read from the cache.
    """

    k: np.ndarray
    alpha: np.ndarray
    regime: np.ndarray
    amplitude: np.ndarray
    zeta: np.ndarray
    rho_ev: np.ndarray
    rho_vf: np.ndarray
    rho_ef: np.ndarray
    dominant: np.ndarray
    steady: np.ndarray
    eta: float
    mu_s: float
    mu_k: float
    elapsed_s: float = 0.0
    from_cache: bool = False
    #: sentences for the user: a damaged cache entry recomputed, a worker count capped
    notes: list = field(default_factory=list)
    #: regime boundaries refined by bisection along α in each column (see :func:`refine_boundaries`):
    #: k [-], α [-], and the code 3·from + to of each change of regime
    boundary_k: np.ndarray = field(default_factory=lambda: np.zeros(0))
    boundary_alpha: np.ndarray = field(default_factory=lambda: np.zeros(0))
    boundary_kind: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int8))

    _ARRAYS = ("k", "alpha", "regime", "amplitude", "zeta", "rho_ev", "rho_vf", "rho_ef", "dominant", "steady",
               "boundary_k", "boundary_alpha", "boundary_kind")

    def regime_at(self, alpha: float, k: float) -> str:
        """Regime of the nearest grid point."""
        i = int(np.argmin(np.abs(self.alpha - alpha)))
        j = int(np.argmin(np.abs(self.k - k)))
        return REGIME_NAMES[int(self.regime[i, j])]

    def transitions_along_alpha(self, j: int) -> list[dict]:
        """Every change of regime along α in grid column j: [{alpha_lo, alpha_hi, from, to}]."""
        column = self.regime[:, j]
        out = []
        for i in np.nonzero(np.diff(column))[0]:
            out.append({"alpha_lo": float(self.alpha[i]), "alpha_hi": float(self.alpha[i + 1]),
                        "from": REGIME_NAMES[int(column[i])], "to": REGIME_NAMES[int(column[i + 1])]})
        return out

    def resonance_line(self) -> tuple[np.ndarray, np.ndarray]:
        """(k, α) where A is largest along α at fixed k, for columns whose maximum is inside the frame."""
        ks, alphas = [], []
        for j in range(self.k.size):
            column = self.amplitude[:, j]
            if not np.any(column > 0):
                continue
            i = int(np.nanargmax(column))
            if 0 < i < self.alpha.size - 1 and self.k[j] > 0:
                # vertex of the parabola through the three points around the maximum
                a_m, a_0, a_p = column[i - 1], column[i], column[i + 1]
                curvature = a_m - 2.0 * a_0 + a_p
                shift = 0.5 * (a_m - a_p) / curvature if curvature < 0 else 0.0
                step = self.alpha[i + 1] - self.alpha[i]
                ks.append(self.k[j])
                alphas.append(self.alpha[i] + float(np.clip(shift, -0.5, 0.5)) * step)
        return np.array(ks), np.array(alphas)

    def content_key(self) -> str:
        """SHA-256 over every array (dtype, shape, bytes) and the fixed parameters.

        Stored with a cached map and checked on reading: a truncated, bit-flipped or
        hand-edited entry no longer matches.  (Not a signature: anyone who can write the
        cache can recompute it; :func:`_check_cached` also recomputes random grid points.)
        """
        digest = hashlib.sha256()
        for name in self._ARRAYS:
            array = np.ascontiguousarray(getattr(self, name))
            digest.update(f"{name}:{array.dtype.str}:{array.shape};".encode())
            digest.update(array.tobytes())
        digest.update(np.array([self.eta, self.mu_s, self.mu_k], dtype=np.float64).tobytes())
        return digest.hexdigest()

    def save(self, path: Path) -> None:
        """Write as .npz atomically (temporary file, then rename), with its content key."""
        with atomic_path(path) as tmp, open(tmp, "wb") as stream:
            np.savez(stream, **{name: getattr(self, name) for name in self._ARRAYS},
                     params=np.array([self.eta, self.mu_s, self.mu_k, self.elapsed_s]),
                     content_key=np.array(self.content_key()))

    @classmethod
    def load(cls, path: Path) -> RegimeMap:
        """Read a cached map; any damage raises :class:`CacheEntryError` (never unpickles).

        Checks the schema (every array present, numeric, of the right shape and codes)
        and the content key.
        """
        import zipfile

        try:
            with open_regular_file(path) as stream, np.load(stream, allow_pickle=False) as data:  # a FIFO: no entry
                missing = [name for name in (*cls._ARRAYS, "params", "content_key") if name not in data.files]
                if missing:
                    raise CacheEntryError(f"missing arrays {', '.join(missing)}")
                params = np.asarray(data["params"], dtype=np.float64)
                if params.shape != (4,):
                    raise CacheEntryError(f"params of shape {params.shape}, expected (4,)")
                eta, mu_s, mu_k, elapsed = (float(v) for v in params)
                arrays = {name: data[name] for name in cls._ARRAYS}
                stored_key = str(data["content_key"])
        except CacheEntryError:
            raise
        except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile) as err:
            raise CacheEntryError(f"unreadable ({type(err).__name__}: {' '.join(str(err).split())[:80]})") from None
        _check_schema(arrays)
        rmap = cls(**arrays, eta=eta, mu_s=mu_s, mu_k=mu_k, elapsed_s=elapsed, from_cache=True)
        if rmap.content_key() != stored_key:
            raise CacheEntryError("content key does not match its arrays")
        return rmap


_ARRAY_KINDS = {"k": "f", "alpha": "f", "amplitude": "f", "zeta": "f", "rho_ev": "f", "rho_vf": "f",
                "rho_ef": "f", "regime": "i", "dominant": "i", "steady": "b", "boundary_k": "f",
                "boundary_alpha": "f", "boundary_kind": "i"}


def _check_schema(arrays: dict) -> None:
    for name, kind in _ARRAY_KINDS.items():
        if arrays[name].dtype.kind != kind:
            raise CacheEntryError(f"array {name} has dtype {arrays[name].dtype}, expected kind {kind!r}")
    n_k, n_alpha = arrays["k"].size, arrays["alpha"].size
    if arrays["k"].shape != (n_k,) or arrays["alpha"].shape != (n_alpha,):
        raise CacheEntryError("axes k and α must be one-dimensional")
    for name in ("regime", "amplitude", "zeta", "rho_ev", "rho_vf", "rho_ef", "dominant", "steady"):
        if arrays[name].shape != (n_alpha, n_k):
            raise CacheEntryError(f"array {name} has shape {arrays[name].shape}, expected {(n_alpha, n_k)}")
    n_boundaries = arrays["boundary_k"].shape
    if len(n_boundaries) != 1 or arrays["boundary_alpha"].shape != n_boundaries or \
            arrays["boundary_kind"].shape != n_boundaries:
        raise CacheEntryError("boundary arrays differ in shape")
    for name, valid in (("regime", 3), ("dominant", 3), ("boundary_kind", 9)):
        values = arrays[name]
        if values.size and (values.min() < 0 or values.max() >= valid):
            raise CacheEntryError(f"array {name} holds codes outside 0..{valid - 1}")


def _check_cached(rmap: RegimeMap, k_range, alpha_range, n_k, n_alpha, eta, mu_s, mu_k, n_spot: int = 12) -> None:
    """A cached map must be the map asked for: same frame and parameters, and the solver
    agrees on ``n_spot`` grid points drawn at random (a well-formed entry with made-up
    regimes is caught; the draw is unpredictable, so no crafted entry passes reliably)."""
    if (rmap.eta, rmap.mu_s, rmap.mu_k) != (float(eta), float(mu_s), float(mu_k)):
        raise CacheEntryError("parameters differ from its name")
    if rmap.k.size != n_k or rmap.alpha.size != n_alpha or \
            not np.array_equal(rmap.k, np.linspace(k_range[0], k_range[1], n_k)) or \
            not np.array_equal(rmap.alpha, np.linspace(alpha_range[0], alpha_range[1], n_alpha)):
        raise CacheEntryError("grid differs from its name")
    generator = np.random.default_rng(int.from_bytes(os.urandom(8), "little"))
    for _ in range(n_spot):
        i, j = int(generator.integers(n_alpha)), int(generator.integers(n_k))
        expected = _point(float(rmap.alpha[i]), float(rmap.k[j]), rmap.eta, rmap.mu_s, rmap.mu_k)
        amplitude = float(rmap.amplitude[i, j])
        if int(rmap.regime[i, j]) != expected[0] or not math.isclose(amplitude, expected[1], rel_tol=1e-6,
                                                                     abs_tol=1e-12):
            raise CacheEntryError(f"point α = {rmap.alpha[i]:g}, k = {rmap.k[j]:g} disagrees with the solver")


def _point(alpha: float, k: float, eta: float, mu_s: float, mu_k: float) -> tuple:
    """(regime, A, ζ, ρ_ev, ρ_vf, ρ_ef, dominant, steady) of one grid point, by the core solver."""
    from isolator.solver.harmonic import force_ratios, harmonic_response

    if alpha <= 1.0:
        rho_ev, rho_vf, rho_ef, dominant = force_ratios(k, eta, max(alpha, 1e-300), mu_s, mu_k, 0.0)
        return (0, 0.0, 0.0, rho_ev, rho_vf, rho_ef, FORCE_CODES[dominant], True)
    r = harmonic_response(alpha, k, eta, mu_s, mu_k, samples_per_period=2)
    return (REGIME_CODES[r.regime], r.amplitude, r.zeta, r.rho_ev, r.rho_vf, r.rho_ef,
            FORCE_CODES[r.dominant_force], r.steady)


def _chunk(points, *, eta, mu_s, mu_k) -> list[tuple]:
    return [_point(a, k, eta, mu_s, mu_k) for a, k in points]


#: Grids smaller than this run in this process whatever ``workers`` says [points].
IN_PROCESS_POINTS = 256


def _evaluate(points: list[tuple], eta: float, mu_s: float, mu_k: float, workers: int) -> list[tuple]:
    from isolator.parallel import map_interleaved

    if len(points) < IN_PROCESS_POINTS:
        # a pool costs ~0.15 s to start and warm up, the work of ~150 typical points (~1 ms each):
        # a report's A(α) curve (2 × 40 + 1 points) runs faster in this process
        workers = 1
    # interleaved chunks balance the cost (points near resonance take longer)
    return map_interleaved(partial(_chunk, eta=eta, mu_s=mu_s, mu_k=mu_k), points, workers, chunks_per_worker=8)


def _refine_chunk(jobs, *, eta, mu_s, mu_k, rel_tol) -> list[tuple]:
    """Bisect each (k, α_lo, α_hi, from, to) change of regime to the α where it happens."""
    from isolator.solver.thresholds import bisect_change, harmonic_regime

    out = []
    for k, lo, hi, r_lo, r_hi in jobs:
        if r_lo == 0 and lo < 1.0 <= hi:
            out.append((k, 1.0, 3 * r_lo + r_hi))  # α_SS = 1 exactly
            continue
        lo, hi = bisect_change(lambda a, k=k, r_lo=r_lo: REGIME_CODES[harmonic_regime(a, k, eta, mu_s, mu_k)] == r_lo,
                               lo, hi, rel_tol=rel_tol)
        out.append((k, 0.5 * (lo + hi), 3 * r_lo + r_hi))
    return out


def refine_boundaries(rmap: RegimeMap, workers: int | None = None, rel_tol: float = 1e-4) -> RegimeMap:
    """Locate every change of regime along α in each column by bisection with the core solver.

    Fills ``boundary_k``, ``boundary_alpha``, ``boundary_kind`` (in place, also returned).  A
    window narrower than the grid step that no grid point falls into is not seen (as in
    :func:`isolator.solver.thresholds.harmonic_thresholds` with a coarse grid).
    """
    jobs = []
    for j, k in enumerate(rmap.k):
        column = rmap.regime[:, j]
        for i in np.nonzero(np.diff(column))[0]:
            jobs.append((float(k), float(rmap.alpha[i]), float(rmap.alpha[i + 1]), int(column[i]),
                         int(column[i + 1])))
    from isolator.parallel import default_workers, map_interleaved

    workers = 1 if len(jobs) < 16 else (workers or default_workers())
    results = map_interleaved(partial(_refine_chunk, eta=rmap.eta, mu_s=rmap.mu_s, mu_k=rmap.mu_k, rel_tol=rel_tol),
                              jobs, workers, chunks_per_worker=4)
    results.sort()
    rmap.boundary_k = np.array([r[0] for r in results], dtype=float)
    rmap.boundary_alpha = np.array([r[1] for r in results], dtype=float)
    rmap.boundary_kind = np.array([r[2] for r in results], dtype=np.int8)
    return rmap


def boundary_segments(rmap: RegimeMap, kind_from: str, kind_to: str) -> list[np.ndarray]:
    """Polylines (arrays of (k, α) rows) joining the refined boundaries of one kind across columns.

    In neighbouring columns, boundaries of the same kind are paired in order when both columns
    hold as many of them, otherwise each to its nearest within three grid steps of α.
    """
    code = 3 * REGIME_CODES[kind_from] + REGIME_CODES[kind_to]
    mask = rmap.boundary_kind == code
    if not mask.any():
        return []
    ks, alphas = rmap.boundary_k[mask], rmap.boundary_alpha[mask]
    columns = [alphas[ks == k] for k in rmap.k]
    step = 3.0 * (rmap.alpha[1] - rmap.alpha[0]) if rmap.alpha.size > 1 else np.inf
    segments = []
    for j in range(rmap.k.size - 1):
        left, right = columns[j], columns[j + 1]
        if left.size == 0 or right.size == 0:
            continue
        if left.size == right.size:
            pairs = list(zip(left, right, strict=False))
        else:
            pairs = []
            for a in left:
                b = right[int(np.argmin(np.abs(right - a)))]
                if abs(b - a) <= step:
                    pairs.append((a, b))
        segments += [np.array([[rmap.k[j], a], [rmap.k[j + 1], b]]) for a, b in pairs]
    return segments


def _key(k_range, alpha_range, n_k, n_alpha, eta, mu_s, mu_k) -> str:
    from isolator import __version__

    params = {"k": [float(v) for v in k_range], "alpha": [float(v) for v in alpha_range], "n_k": int(n_k),
              "n_alpha": int(n_alpha), "eta": float(eta), "mu_s": float(mu_s), "mu_k": float(mu_k),
              "format": MAP_FORMAT_VERSION, "version": __version__}
    return hashlib.sha256(json.dumps(params, sort_keys=True).encode()).hexdigest()[:20]


def _default_workers() -> int:
    from isolator.parallel import default_workers

    return default_workers()


#: Largest number of grid points along one axis of a regime map (1000 × 1000 responses: ~10 minutes).
MAX_MAP_POINTS = 1000


def regime_map(eta: float, mu_s: float, mu_k: float | None = None, *, k_range=(0.0, 6.0),
               alpha_range=(0.0, 6.0), n_k: int = 100, n_alpha: int = 100, workers: int | None = None,
               use_cache: bool = True, refine: bool = False) -> RegimeMap:
    """The harmonic regime map over a (k, α) frame at fixed η, µs, µk.

    Parameters
    ----------
    eta : float
        Dimensionless damping η [-].
    mu_s, mu_k : float
        Friction coefficients [-]; µk defaults to µs.
    k_range, alpha_range : tuple of float
        Frame [-]; α below 1 is ST without computation.
    n_k, n_alpha : int
        Grid points along k and α.
    workers : int, optional
        Processes (2 by default, or 1 on a single core).
    use_cache : bool
        Read and write the on-disk cache (:func:`cache_dir`).
    refine : bool
        Also locate every regime boundary by bisection (:func:`refine_boundaries`).

    Returns
    -------
    RegimeMap
    """
    from isolator.parallel import capped_workers
    from isolator.solver.harmonic import MAX_DIMENSIONLESS, validate_harmonic_parameters

    for name, value in (("n_k", n_k), ("n_alpha", n_alpha)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not 2 <= value <= MAX_MAP_POINTS:
            raise InvalidSystemError(f"{name} must be a whole number of grid points in [2, {MAX_MAP_POINTS}] "
                                     f"(each point is a harmonic response, ~0.5 ms), got {value!r}")
    try:
        mu_k = mu_s if mu_k is None else float(mu_k)
        validate_harmonic_parameters(1.0, 0.0, float(eta), float(mu_s), float(mu_k))
    except (TypeError, ValueError) as err:
        if isinstance(err, InvalidSystemError):
            raise
        raise InvalidSystemError(f"eta, mu_s and mu_k must be numbers, got {eta!r}, {mu_s!r}, {mu_k!r}") from None
    for name, (low, high) in (("k", k_range), ("alpha", alpha_range)):
        if not (math.isfinite(low) and math.isfinite(high) and 0.0 <= low < high <= MAX_DIMENSIONLESS):
            raise InvalidSystemError(f"the {name} range [{low:g}, {high:g}] must lie within [0, "
                                     f"{MAX_DIMENSIONLESS:g}] (the harmonic solver's domain)")
    workers, workers_note = capped_workers(workers)
    notes = [workers_note] if workers_note else []
    base_key = _key(k_range, alpha_range, n_k, n_alpha, eta, mu_s, mu_k)
    path = cache_dir() / f"map-{base_key}{'-refined' if refine else ''}.npz"
    frame = (k_range, alpha_range, n_k, n_alpha, eta, mu_s, mu_k)

    def cached(entry: Path) -> RegimeMap | None:
        if not (use_cache and entry.exists()):
            return None
        try:
            found = RegimeMap.load(entry)
            _check_cached(found, *frame)
            return found
        except CacheEntryError as err:
            notes.append(f"cached map {entry} was damaged ({err}): recomputed")
            return None

    def store(computed: RegimeMap) -> None:
        try:
            computed.save(path)
        except OSError as err:  # a read-only cache never stops a map, but a FIFO left in an entry's place made
            # every run recompute without a word (session 15 sweep): said
            notes.append(f"the map could not be cached ({err}): the next run computes it again")

    rmap = cached(path)
    if rmap is not None:
        rmap.notes = notes
        return rmap
    base = cached(cache_dir() / f"map-{base_key}.npz") if refine else None
    if base is not None:
        rmap = refine_boundaries(base, workers)
        rmap.from_cache = False
        store(rmap)
        rmap.notes = notes
        return rmap
    k = np.linspace(k_range[0], k_range[1], n_k)
    alpha = np.linspace(alpha_range[0], alpha_range[1], n_alpha)
    start = time.perf_counter()
    points = [(float(a), float(kk)) for a in alpha for kk in k]
    results = _evaluate(points, float(eta), float(mu_s), mu_k, workers or _default_workers())
    elapsed = time.perf_counter() - start

    def grid(index, dtype=float):
        values = [np.nan if r[index] is None else r[index] for r in results]
        return np.array(values, dtype=dtype).reshape(n_alpha, n_k)

    rmap = RegimeMap(k=k, alpha=alpha, regime=grid(0, np.int8), amplitude=grid(1), zeta=grid(2),
                     rho_ev=grid(3), rho_vf=grid(4), rho_ef=grid(5), dominant=grid(6, np.int8),
                     steady=grid(7, bool), eta=float(eta), mu_s=float(mu_s), mu_k=mu_k, elapsed_s=elapsed)
    if refine:
        refine_boundaries(rmap, workers)
        rmap.elapsed_s = time.perf_counter() - start
    if use_cache:
        store(rmap)
    rmap.notes = notes
    return rmap


def amplitude_curve(k: float, eta: float, mu_s: float, mu_k: float | None, alphas,
                    workers: int | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A(α), the regime codes and the steady flags along α at fixed k and η (Figs. 5c–d, 8).

    Where ``steady`` is False the solver stopped at resonant growth (no damping): A grows
    without bound and the value returned is only the amplitude reached.
    """
    mu_k = mu_s if mu_k is None else float(mu_k)
    points = [(float(a), float(k)) for a in alphas]
    results = _evaluate(points, float(eta), float(mu_s), mu_k, workers or _default_workers())
    return (np.array([r[1] for r in results]), np.array([r[0] for r in results], dtype=np.int8),
            np.array([bool(r[7]) for r in results]))


def triple_point(eta: float, mu_s: float, mu_k: float | None = None, alpha_max: float = 50.0,
                 n_scan: int = 60) -> tuple[float, float] | None:
    """The triple point (α̂, k̂) where friction, spring and damper forces are equal.

    On the line ρ_ev = 1, k̂ = η sqrt(α̂ µs); the point is where ρ_ef = k A / µk = 1
    there too (then ρ_vf = 1 follows).  Found by a scan of α ∈ (1, alpha_max] and a
    bisection of the first sign change.

    Returns
    -------
    tuple or None
        (α̂, k̂), or None without damping or if there is no crossing in the scan.
    """
    from isolator.solver.harmonic import harmonic_response

    mu_k = mu_s if mu_k is None else float(mu_k)
    if eta <= 0.0 or mu_k <= 0.0:
        return None

    def excess(alpha: float) -> float:
        k = eta * math.sqrt(alpha * mu_s)
        return k * harmonic_response(alpha, k, eta, mu_s, mu_k, samples_per_period=2).amplitude - mu_k

    from isolator.solver.thresholds import bisect_change

    alphas = np.geomspace(1.0 + 1e-6, alpha_max, n_scan)
    values = [excess(a) for a in alphas]
    for a_lo, a_hi, f_lo, f_hi in zip(alphas[:-1], alphas[1:], values[:-1], values[1:], strict=True):
        if f_lo < 0.0 <= f_hi:
            lo, hi = bisect_change(lambda a: excess(a) < 0.0, a_lo, a_hi, iterations=40)
            alpha_hat = 0.5 * (lo + hi)
            return alpha_hat, eta * math.sqrt(alpha_hat * mu_s)
    return None


def nice_ceiling(value: float) -> float:
    """The smallest of 1, 1.5, 2, 3, 4, 5, 6, 8 × 10^n that is ≥ value (> 0)."""
    exponent = math.floor(math.log10(value))
    for step in (1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0):
        candidate = step * 10.0 ** exponent
        if candidate >= value * (1 - 1e-12):
            return float(f"{candidate:.12g}")
    return 10.0 ** (exponent + 1)


def design_frame(alpha: float, k: float) -> dict:
    """A frame around a design's point: k up to ~2.5 k (≥ 0.05), α up to ~1.5 α (≥ 3).

    The upper ends are rounded up to 1-1.5-2-3-4-5-6-8 steps so that records of similar
    intensity share a frame, and therefore a cached map.
    """
    return {"k": (0.0, nice_ceiling(max(2.5 * k, 0.05))), "alpha": (0.0, nice_ceiling(max(1.5 * alpha, 3.0)))}
