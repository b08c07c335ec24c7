"""The 1-D buildings' located extremes do not depend on what ran before them in the process.

The intermittent failure of test_building_multisurface.py's "double, mu1 < mu2, a dashpot, 1 story" under
``pytest -n 2`` (peak drift 0.0020131906 against 0.0020131978, only after some other tests in the same worker)
was no cached state: ``building_kernel._poly`` read one word past its coefficients for Newton's slope when
``_poly_root`` looked for a root of a derivative (an interior extremum, a hold force's turning point).  That word
is whatever the allocator left after the kernel's ``coef`` array, so it changes with the process's history; a
value near −1e74 moved that peak by 3.6e-6, values of −1e72 … −1e93 by up to 4e-3 of it.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from isolator.solver.building import simulate_building
from isolator.solver.building_kernel import N_TAYLOR, poly, poly_root
from isolator.solver.building_multisurface import simulate_building_bearing
from tests.solver import test_building as one_d
from tests.solver import test_building_multisurface as multi

ROOT = Path(__file__).resolve().parents[2]
TARGET = "double, mu1 < mu2, a dashpot, 1 story"  # the case that failed
ONE_D = "3 stories, flat slider + spring + dashpot"


def _cosine_coefficients(amp, omega, t_star, offset):
    """c_j = y^(j)(0) of y(τ) = offset + amp cos(ω(τ − t*)): its slope vanishes at t*, where y = offset + amp."""
    j = np.arange(N_TAYLOR + 2)
    c = amp * omega ** j * np.cos(-omega * t_star + j * math.pi / 2)
    c[0] += offset
    return c


def test_a_located_extremum_does_not_read_past_its_coefficients():
    # the coefficients sit in a longer buffer whose next word is set to ±10^e for every e: the root of the slope
    # (Newton on the slope, its own slope the next derivative) must be the closed form's t* whatever that word is
    length, t_star, amp, omega = 0.01, 0.0057, 2e-3, 2 * math.pi * 4.0
    c = _cosine_coefficients(amp, omega, t_star, 1e-4)
    buf = np.empty(c.size + 1)
    buf[:c.size] = c
    view = buf[:c.size]
    wrong = []
    for word in [sign * 10.0 ** e for sign in (1.0, -1.0) for e in range(-300, 308, 2)] + [0.0, math.nan, math.inf]:
        buf[c.size] = word
        t = poly_root(view, 1, 0.0, 1.0, 0.0, length)
        if abs(t - t_star) > 1e-14 * length or abs(poly(view, 0, t) - (1e-4 + amp)) > 1e-15 * amp:
            wrong.append(f"{buf[c.size]:.0e}: t = {t!r}")
    assert not wrong, f"the located extremum moves with the word past the coefficients: {wrong[:4]}"


_FRESH = """
import json, sys
from pathlib import Path
sys.path.insert(0, {root!r})
from tests.solver import test_building_state as s
print(json.dumps(s.peaks(Path({records!r}))))
"""


def peaks(records_dir):
    """Signed extremes (every watched functional) of the two 1-D buildings' cases: the multi-surface one and the
    1-D building on a flat slider with a spring."""
    record, start, duration, scale, (kind, surfaces), masses, ks, zeta, total, c_iso = multi.CASES[TARGET]
    acc, dt = multi.real_segment(records_dir, record, start, duration, scale)
    ours = simulate_building_bearing(acc, dt, superstructure=multi.make_superstructure(masses, ks, zeta),
                                     bearing=multi.bearing(kind, surfaces), total_mass_kg=total,
                                     damping_Ns_per_m=c_iso)
    record, start, duration, masses, ks, zeta, total, spring, c_iso, mu_s, mu_k = one_d.CASES[ONE_D]
    acc, dt = one_d.real_segment(records_dir, record, start, duration)
    plain = simulate_building(acc, dt, superstructure=one_d.make_superstructure(masses, ks, zeta),
                              total_mass_kg=total, stiffness_N_per_m=spring["stiffness_N_per_m"], mu_static=mu_s,
                              mu_kinetic=mu_k, damping_Ns_per_m=c_iso)
    return {"multi": [list(ours.peak_max), list(ours.peak_min)],
            "plain": [list(plain.peak_max), list(plain.peak_min)]}


def test_the_peaks_after_other_runs_equal_a_fresh_bounds_checked_run(records_dir):
    # the reference: a fresh process running the kernels as plain Python (NUMBA_DISABLE_JIT: every index is
    # checked, so a read past an array raises instead of reading the allocator's leftovers); here, in this process
    # after the other multi-surface cases and the 1-D buildings' (the sequence a pytest worker runs), the compiled
    # kernels must give the same extremes
    env = dict(os.environ, NUMBA_DISABLE_JIT="1", OPENBLAS_NUM_THREADS="1")
    run = subprocess.run([sys.executable, "-c", _FRESH.format(root=str(ROOT), records=str(records_dir))], cwd=ROOT,
                         env=env, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    fresh = json.loads(run.stdout.strip().splitlines()[-1])
    for name in multi.CASES:
        if name != TARGET:
            record, start, duration, scale, (kind, surfaces), masses, ks, zeta, total, c_iso = multi.CASES[name]
            acc, dt = multi.real_segment(records_dir, record, start, duration, scale)
            simulate_building_bearing(acc, dt, superstructure=multi.make_superstructure(masses, ks, zeta),
                                      bearing=multi.bearing(kind, surfaces), total_mass_kg=total,
                                      damping_Ns_per_m=c_iso)
    here = peaks(records_dir)
    for model in ("multi", "plain"):
        for ours, theirs in zip(here[model], fresh[model], strict=True):
            assert np.asarray(ours) == pytest.approx(np.asarray(theirs), rel=1e-13, abs=0.0), model
