r"""Amplitude scaling of a suite to a target spectrum over a period range (ASCE 7-22 17.3.3, 16.2.3).

One factor per pair, applied to both components.  The check: the suite average of the scaled
spectra (RotD100 for ASCE 7; the components' PSA for EN 1998) is nowhere below
``min_ratio`` × target on the period grid.  Two ways of forming the factors (REVIEW_RULES 1.5):

* ``common`` — one factor k for every pair, the smallest with
  :math:`\min_T \overline{k S_i}(T)/S_T(T) = r`, i.e. :math:`k = r \max_T S_T(T)/\bar S(T)`;
* ``fit`` — first a shape factor per pair, :math:`f_i = \exp(\operatorname{mean}_T \ln(S_T/S_i))`
  over the log-spaced grid (log least squares, the PEER NGA-West2 tool's choice), then one common
  k as above on the f_i-scaled spectra; :math:`SF_i = k f_i`.

* ``given`` — the engineer's factors from SUITE.toml (``scale_factor`` per pair), used as they are:
  the check then tests the designer's suite, it is not met by construction.  Spectrally matched
  suites (``matched = true``, 16.2.3.3) are never rescaled either (factor 1 unless given) and the
  average must reach ``spectral_matching_min`` (1.10) × target over the range.

``common`` and ``fit`` are exact on the grid (no iteration).  The grid is ``grid_points`` log-spaced periods from the
lower to the upper end of the range inclusive, plus the T_M values inside it.
"""

from __future__ import annotations

import numpy as np

SCALING_METHODS = ("common", "fit", "given")


def default_scaling(names, factors) -> str:
    """The scaling a suite asks for when none is named: ``given`` when every pair gives its factor (the tool then
    checks the engineer's suite and never rescales it), ``common`` when none does; ``ValueError`` naming the first
    pair without a factor when only some give one."""
    given = [f is not None for f in factors]
    if all(given) and given:
        return "given"
    if any(given):
        missing = next(name for name, g in zip(names, given, strict=True) if not g)
        raise ValueError(f"pair '{missing}' gives no scale_factor while other pairs do: give every pair its factor, "
                         "or have them computed (scaling common or fit)")
    return "common"


def given_factors(names, factors) -> np.ndarray:
    """The engineer's factors of a suite, one per pair; ``ValueError`` naming the first pair without one."""
    missing = [name for name, f in zip(names, factors, strict=True) if f is None]
    if missing:
        raise ValueError(f"scaling 'given' needs a scale_factor for every pair; pair '{missing[0]}' has none"
                         + (f" (and {len(missing) - 1} more)" if len(missing) > 1 else ""))
    return np.asarray(factors, dtype=np.float64)


def period_grid(lo_s: float, hi_s: float, points: int = 300, extra_s=()) -> tuple[np.ndarray, np.ndarray]:
    """The log-spaced grid of the range and the grid with ``extra_s`` periods inside the range added.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        The ``points`` log-spaced periods (ends included) [s], and the sorted union with the extra
        periods that fall inside [lo, hi] [s].
    """
    if not (0 < lo_s < hi_s):
        raise ValueError(f"period range must satisfy 0 < lo < hi, got {lo_s!r}, {hi_s!r}")
    base = np.geomspace(lo_s, hi_s, int(points))
    extra = [float(t) for t in extra_s if np.isfinite(t) and lo_s <= t <= hi_s]
    return base, np.unique(np.concatenate([base, extra]))


def scale_factors(spectra, target_g, *, method: str = "common", min_ratio: float = 1.0,
                  fit_mask=None) -> np.ndarray:
    """One factor per pair so that the suite average is ≥ ``min_ratio`` × target at every grid period.

    Parameters
    ----------
    spectra : array_like, shape (n_pairs, n_periods) or (n_pairs, n_components, n_periods)
        The spectra that are averaged (RotD100 per pair; or each component's PSA) [any unit].
    target_g : array_like, shape (n_periods,)
        The target on the same grid [same unit].
    method : {"common", "fit"}
    min_ratio : float
        Required ratio of the average to the target [-].
    fit_mask : array_like of bool, optional
        Periods used for the ``fit`` shape factors (the log-spaced ones); all by default.

    Returns
    -------
    numpy.ndarray
        The factor of each pair [-].
    """
    s = np.asarray(spectra, dtype=np.float64)
    target = np.asarray(target_g, dtype=np.float64)
    if s.ndim == 2:
        s = s[:, None, :]
    if method not in ("common", "fit"):
        raise ValueError(f"scaling method must be one of {', '.join(SCALING_METHODS)}, got {method!r}")
    if np.any(s <= 0) or np.any(target <= 0):
        raise ValueError("spectra and target must be > 0 on the grid")
    if method == "common":
        shape = np.ones(s.shape[0])
    else:
        mask = np.ones(target.size, bool) if fit_mask is None else np.asarray(fit_mask, bool)
        logs = np.log(target[mask])[None, None, :] - np.log(s[:, :, mask])
        shape = np.exp(logs.mean(axis=(1, 2)))
    mean = suite_mean(s, shape)
    # rounded up by a few ulps so that the scaled average meets the ratio exactly, not at 1 - 1e-16
    k = min_ratio * float(np.max(target / mean)) * (1.0 + 1e-12)
    return k * shape


def suite_mean(spectra, factors) -> np.ndarray:
    """Average over pairs (and components) of the scaled spectra."""
    s = np.asarray(spectra, dtype=np.float64)
    if s.ndim == 2:
        s = s[:, None, :]
    return (np.asarray(factors, dtype=np.float64)[:, None, None] * s).mean(axis=(0, 1))
