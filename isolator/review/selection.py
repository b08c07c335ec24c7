r"""Record selection: the same motion twice, records that cannot matter, records that are not earthquakes.

Three looks at a suite before (and after) it is scaled (REVIEW_RULES 1.4; ASCE 7-22 17.3.2 [U] in an ASCE review,
EN 1998-1 3.2.3.1 [U] in an EN review: :data:`CLAUSES`):

* **The same motion twice.** A pair that is a rotation, an amplitude scaling, a time shift or a
  resampling of another is the same ground motion counted twice in the suite mean. Byte-equal
  samples are refused by :mod:`isolator.review.suite`; here two pairs are compared by a *motion
  signature* that each of those four operations leaves unchanged (up to the resampling's
  band-limit):

  - the shape of the 5 %-damped RotD100 spectrum at :data:`SIGNATURE_PERIODS_S` (RotD100 is
    exactly rotation-invariant, scales with the amplitude and ignores a time shift), normalised by
    its geometric mean;
  - the significant duration D5–95 of the resultant Arias intensity (rotation-, scale- and
    shift-invariant);
  - the orbit's shape: the ratio of the eigenvalues of ∫ a aᵀ dt (the 2 × 2 covariance of the two
    horizontal accelerations; rotation-, scale- and shift-invariant).  Peak values are left out: a
    resampling moves the PGA by several per cent.

  Two pairs whose signatures agree within :data:`SAME_MOTION_TOLERANCE` are refused, naming both.
  Real different records differ by far more: the closest two of the 12 shared pairs
  (``../shared/records/pairs``) are 0.53 apart; a copy of the La Habra CIWLT pair (dt = 0.02 s)
  rotated by 30°, scaled by 1.7 or shifted by 3 s is within 2e-6, linearly resampled to 0.01 s within
  0.004 and to 0.04 s within 0.043 (the short periods lose energy); ``tests/review/test_selection.py``
  checks the same on the bundled suite.
* **Records that cannot matter.** A scaled pair whose resultant PGA is below µ_lower g ×
  ``weak_pga_fraction`` (0.1: a tenth of the acceleration that starts sliding) barely moves the
  isolator and only dilutes the suite mean.
* **Not an earthquake record.** A pure or nearly pure sinusoid has a narrow Fourier spectrum:
  Vanmarcke's bandwidth δ = √(1 − λ₁²/(λ₀λ₂)) (spectral moments λ_k of the one-sided power
  spectrum) is below ``bandwidth_min`` (0.25; recorded earthquake motions give 0.5–0.9).
"""

from __future__ import annotations

import math

import numpy as np

from isolator.motion.measures import energy_window_s

#: periods of the signature spectrum [s]: long enough for a resampling of 0.01 s records not to matter
SIGNATURE_PERIODS_S = np.geomspace(0.25, 6.0, 24)
#: largest difference of two signatures that counts as the same motion (see the module docstring)
SAME_MOTION_TOLERANCE = 0.1


def resultant_arias_window(ax, ay, dt_s: float) -> tuple[float, float]:
    """(t5, t95) of the resultant Arias intensity ∫(a_x² + a_y²) dt [s] (0, 0 for a motionless pair).

    Exact for the piecewise-linear pair (:func:`isolator.motion.measures.energy_window_s`)."""
    window = energy_window_s([ax, ay], dt_s, (0.05, 0.95))
    return (0.0, 0.0) if window is None else (window[0], window[1])


def _product_integral(a, b, dt_s: float) -> float:
    """∫ a b dt of two piecewise-linear records on one time base, exact [unit_a·unit_b·s]."""
    return float(dt_s * np.sum(2.0 * a[:-1] * b[:-1] + a[:-1] * b[1:] + a[1:] * b[:-1] + 2.0 * a[1:] * b[1:]) / 6.0)


def motion_signature(ax_m_s2, ay_m_s2, dt_s: float) -> dict:
    """The invariants of a pair under rotation, scaling, time shift and resampling.

    Returns
    -------
    dict
        ``shape`` (ln RotD100 at :data:`SIGNATURE_PERIODS_S` minus its mean [-]), ``duration_s``
        (D5–95 of the resultant [s]), ``eigen_ratio`` (smaller / larger eigenvalue of ∫ a aᵀ dt [-]).
    """
    from isolator.review.spectra import pair_spectra

    ax = np.asarray(ax_m_s2, dtype=np.float64)
    ay = np.asarray(ay_m_s2, dtype=np.float64)
    rotd = pair_spectra(ax, ay, dt_s, SIGNATURE_PERIODS_S)["rotd100_m_s2"]
    with np.errstate(divide="ignore"):
        logs = np.log(rotd)
    shape = logs - logs.mean() if np.all(np.isfinite(logs)) else np.full(logs.size, np.nan)
    t5, t95 = resultant_arias_window(ax, ay, dt_s)
    xy = _product_integral(ax, ay, dt_s)
    cov = np.array([[_product_integral(ax, ax, dt_s), xy], [xy, _product_integral(ay, ay, dt_s)]])
    eig = np.linalg.eigvalsh(cov)
    return {"shape": shape, "duration_s": t95 - t5, "eigen_ratio": float(eig[0] / eig[1]) if eig[1] > 0 else 0.0}


def signature_distance(a: dict, b: dict) -> float:
    """How far apart two signatures are [-]: the largest of the spectral-shape difference (max |Δ ln|), the
    relative difference of D5–95 and the difference of the eigenvalue ratios."""
    if not (np.all(np.isfinite(a["shape"])) and np.all(np.isfinite(b["shape"]))):
        return math.inf
    parts = [float(np.max(np.abs(a["shape"] - b["shape"]))), abs(a["eigen_ratio"] - b["eigen_ratio"])]
    big = max(a["duration_s"], b["duration_s"])
    parts.append(abs(a["duration_s"] - b["duration_s"]) / big if big > 0 else 0.0)
    return max(parts)


#: upper end of the band of the bandwidth's spectral moments [Hz]: a fixed band, so that a record and the
#: same piecewise-linear signal sampled finer give one δ (the band of engineering interest of recorded motions)
BANDWIDTH_BAND_HZ = 25.0


def _end_ramp(u, h: float):
    """∫₀ʰ (1 − s/h) e^{ius} ds for angular frequencies u [rad/s] (series where uh is small)."""
    uh = u * h
    out = np.empty(u.shape, dtype=np.complex128)
    small = np.abs(uh) < 0.1
    x = 1j * uh[small]
    series = np.zeros(x.shape, dtype=np.complex128)
    term_factorial = 2.0
    for k in range(10):  # h Σ (iuh)^k / (k + 2)!: 10 terms reach rounding for |uh| < 0.1
        series += x ** k / term_factorial
        term_factorial *= k + 3
    out[small] = h * series
    big = ~small
    ub = u[big]
    out[big] = 1j / ub - (np.exp(1j * ub * h) - 1.0) / (h * ub * ub)
    return out


def spectral_bandwidth(acceleration, dt_s: float) -> float:
    """Vanmarcke's bandwidth δ = √(1 − λ₁²/(λ₀λ₂)) of a record's one-sided power spectrum [-].

    δ → 0 for a pure sinusoid, ≈ 0.5–0.9 for recorded earthquake motions.  The spectrum is the exact
    Fourier transform of the record read as piecewise linear on its duration (the samples' DFT times
    the linear interpolant's sinc², less the two half-ramps that interpolant would have outside the
    record), and the moments are taken on 0 – :data:`BANDWIDTH_BAND_HZ`, on the grid 1/(n dt) of a
    zero-padding to n ≥ 2 × samples (a power of two, so a sinusoid's leakage does not widen it): a record
    and the same signal sampled at dt/2 (collinear midpoints) share that grid and give one δ to rounding
    (issue 26; the samples' DFT up to each sampling's own Nyquist frequency differed by 2.7e-2).
    """
    a = np.asarray(acceleration, dtype=np.float64)
    if a.size < 4 or not np.any(a) or not dt_s > 0:
        return 0.0
    n = 1 << int(math.ceil(math.log2(2 * a.size)))
    df = 1.0 / (n * dt_s)
    f = np.arange(int(BANDWIDTH_BAND_HZ / df) + 1) * df
    dft = np.fft.fft(a, n)[np.arange(f.size) % n]  # the DFT is periodic in 1/dt
    u = 2.0 * math.pi * f
    duration_s = (a.size - 1) * dt_s
    spectrum = (dt_s * dft * np.sinc(f * dt_s) ** 2 - a[0] * _end_ramp(u, dt_s)
                - a[-1] * np.exp(-1j * u * duration_s) * np.conj(_end_ramp(u, dt_s)))
    power = np.abs(spectrum) ** 2
    l0, l1, l2 = (float(np.sum(power * f ** k)) for k in (0, 1, 2))
    if l0 <= 0 or l2 <= 0:
        return 0.0
    return math.sqrt(max(0.0, 1.0 - l1 * l1 / (l0 * l2)))


def closest_motions(pairs) -> dict | None:
    """The two pairs of the suite whose motion signatures are closest: {"pairs": [a, b], "distance": d}."""
    signatures = [motion_signature(p.ax_m_s2, p.ay_m_s2, p.dt_s) for p in pairs]
    best = None
    for i in range(len(pairs)):
        for j in range(i + 1, len(pairs)):
            distance = signature_distance(signatures[i], signatures[j])
            if best is None or distance < best["distance"]:
                best = {"pairs": [pairs[i].name, pairs[j].name], "distance": distance}
    return best


#: The clause each code's review cites for the two code rows (``record_selection``, ``distinct_motions``); the
#: other two are practice in both.  An EN review never cites ASCE 7 as its authority: EN 1998-1 3.2.3.1 asks
#: recorded motions qualified for the seismogenetic features of the sources and the site's soil (REVIEW_RULES §2
#: names 3.2.3.1.2 for the records; the wording is [U]), and a suite mean (4.3.3.4.3(3)) counts each motion once.
CLAUSES = {
    "asce7-22": {"record_selection": "ASCE 7-22 17.3.2 [U]",
                 "distinct_motions": "ASCE 7-22 17.3.2 (one motion counted once)"},
    "en15129": {"record_selection": "EN 1998-1 3.2.3.1 [U] (records qualified for the sources and the site)",
                "distinct_motions": "EN 1998-1 3.2.3.1.2 / 4.3.3.4.3(3) [U] (one motion counted once in the mean)"},
}


def _in_range(value, bounds) -> bool:
    return bounds[0] <= value <= bounds[1]


def selection_rows(pairs, factors, *, mu_lower: float, gravity_m_s2: float, controlling: dict,
                   params: dict, closest: dict | None, code: str = "asce7-22", mu_lower_said: str = "µ_lower"
                   ) -> list[dict]:
    """The record-selection rows of a review (the code's clauses, :data:`CLAUSES`, and practice).

    Parameters
    ----------
    pairs : list of isolator.review.suite.Pair
    factors : sequence of float
        The scale factor of each pair as analysed [-].
    mu_lower : float
        Lower-bound kinetic friction [-] (a double or triple bearing: the lower bound's breakaway force / W, its
        smallest µ_i, where it starts to slide).
    mu_lower_said : str
        What ``mu_lower`` is, in the row's note.
    gravity_m_s2 : float
    controlling : dict
        The target's ``magnitude_range``, ``distance_km_range``, ``vs30_m_s_range`` ([lo, hi]) and
        ``mechanisms`` (list of texts), each may be absent.
    params : dict
        ``weak_pga_fraction``, ``bandwidth_min``.
    closest : dict or None
        :func:`closest_motions` of the suite.
    code : {"asce7-22", "en15129"}
        Whose clauses the two code rows cite.

    Returns
    -------
    list of dict
        ``record_selection``, ``distinct_motions``, ``record_strength``, ``record_nature`` rows.
    """
    from isolator.review import checks as C

    rows = []
    outside, unknown, looked = [], [], []
    for key, label in (("magnitude", "magnitude_range"), ("distance_km", "distance_km_range"),
                       ("vs30_m_s", "vs30_m_s_range")):
        bounds = controlling.get(label)
        if bounds is None:
            continue
        looked.append(f"{key} in {bounds[0]:g}–{bounds[1]:g}")
        for p in pairs:
            value = p.metadata.get(key)
            if value is None:
                unknown.append(f"{p.name} ({key})")
            elif not _in_range(value, bounds):
                outside.append(f"{p.name}: {key} {value:g}")
    mechanisms = controlling.get("mechanisms")
    if mechanisms:
        looked.append(f"mechanism in {{{', '.join(mechanisms)}}}")
        accepted = {m.lower() for m in mechanisms}
        for p in pairs:
            value = p.metadata.get("mechanism")
            if value is None:
                unknown.append(f"{p.name} (mechanism)")
            elif value.lower() not in accepted:
                outside.append(f"{p.name}: mechanism {value}")
    shown = sorted({k for p in pairs for k in p.metadata})
    unmatched = [k for k, label in (("mechanism", "mechanisms"), ("vs30_m_s", "vs30_m_s_range"), ("pulse", None))
                 if k in shown and (label is None or label not in controlling)]
    tail = (f"; metadata given: {', '.join(shown)}" if shown else "; no pair gives metadata") + (
        f" ({', '.join(unmatched)} shown, not checked: the target states no counterpart)" if unmatched else "")
    clause = CLAUSES[code]["record_selection"]
    if not looked:
        rows.append(C.check("record_selection", clause, C.NOT_CHECKED, None, None,
                            "the target gives no controlling magnitude_range / distance_km_range / vs30_m_s_range / "
                            "mechanisms" + tail))
    elif outside:
        rows.append(C.check("record_selection", clause, C.FAIL, len(outside), 0,
                            f"outside the controlling {' and '.join(looked)}: {', '.join(outside)}"
                            + (f"; unknown for {len(unknown)}" if unknown else "") + tail, "pairs"))
    elif unknown:
        rows.append(C.check("record_selection", clause, C.NOT_CHECKED, 0, 0,
                            f"{' and '.join(looked)}: unknown for {len(unknown)} of {len(pairs)} pair(s) "
                            f"({', '.join(unknown[:6])}{'…' if len(unknown) > 6 else ''})" + tail, "pairs"))
    else:
        rows.append(C.check("record_selection", clause, C.PASS, 0, 0,
                            f"every pair within the controlling {' and '.join(looked)}" + tail, "pairs"))
    if closest is None:
        rows.append(C.check("distinct_motions", CLAUSES[code]["distinct_motions"], C.NOT_CHECKED,
                            note="one pair: nothing to compare"))
    else:
        rows.append(C.at_least("distinct_motions", CLAUSES[code]["distinct_motions"], closest["distance"],
                               SAME_MOTION_TOLERANCE,
                               f"closest two pairs {closest['pairs'][0]} / {closest['pairs'][1]}: motion signatures "
                               "(RotD100 shape, D5–95, orbit shape; invariant under rotation, scaling, time shift) "
                               "apart by the value", "-"))
    floor = params["weak_pga_fraction"] * mu_lower
    pgas = {p.name: f * float(np.max(np.hypot(p.ax_m_s2, p.ay_m_s2))) / gravity_m_s2
            for p, f in zip(pairs, factors, strict=True)}
    weak = [f"{name} {value:.3g} g" for name, value in pgas.items() if value < floor]
    rows.append(C.check("record_strength", "record selection (practice)", C.FAIL if weak else C.PASS,
                        min(pgas.values()), floor,
                        f"scaled resultant PGA ≥ {params['weak_pga_fraction']:g} × {mu_lower_said} "
                        f"{mu_lower:.4g} × g; "
                        + (f"cannot move the isolator, only dilute the mean: {', '.join(weak)}" if weak
                           else "every pair can move the isolator"), "g"))
    widths = {f"{p.name} {k}": spectral_bandwidth(a, p.dt_s) for p in pairs
              for k, a in (("x", p.ax_m_s2), ("y", p.ay_m_s2))}
    narrow = [f"{name} δ = {value:.2f}" for name, value in widths.items() if value < params["bandwidth_min"]]
    rows.append(C.check("record_nature", "record selection (practice)", C.FAIL if narrow else C.PASS,
                        min(widths.values()), params["bandwidth_min"],
                        "Vanmarcke bandwidth δ of each component (a sinusoid has δ ≈ 0, recorded motions 0.5–0.9); "
                        + (f"not an earthquake record: {', '.join(narrow)}" if narrow else "every component broad-band"),
                        "-"))
    return rows
