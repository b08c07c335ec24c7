"""The planar engine against OpenSees on one real pair: time and error of both, one run.

Usage::

    pip install "isolator[bench]"      # openseespy (Linux wheels need libblas3, liblapack3)
    PYTHONPATH=. python benchmarks/opensees_pair.py [--pair superstitionhills1987_PTS] [--mu 0.06]
                                                    [--radius 2.0] [--yield-mm 0.5] [--repeat 3]

Model (the same for both): a rigid mass on a single friction pendulum of radius R,
Coulomb friction µ, both horizontal components at once, no vertical.

* **isolator** — :func:`isolator.solver.planar.simulate_pair` (DOP853 between exact
  events, its default rtol, 1e-11).
* **OpenSees** — openseespy, a 3-D model (ndm 3, ndf 6) with two coincident nodes and
  ``singleFPBearing`` (``frictionModel Coulomb``, Reff = R, its usual elastic
  stiffness before sliding kInit = µW/u_y with u_y = ``--yield-mm``, a stiff
  elastic vertical material), gravity applied statically, then both components as
  ``UniformExcitation`` patterns; Newmark (γ = 1/2, β = 1/4) with Newton at the
  record's dt (step halved on non-convergence, as in the OpenSees examples).
* **truth** — the independent reference of the tests (tests/planar_reference.py:
  scipy solve_ivp, DOP853 / Radau at rtol 1e-12 with stop events).

Errors are relative to the reference's peak resultant displacement: of the peak, of
the residual, and the largest difference over the sampled history.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from planar_throughput import load

from isolator.solver.planar import simulate_pair
from tests.planar_reference import reference_pair

G = 9.80665
VERTICAL_STIFFNESS_PER_WEIGHT = 1e7  #: [1/m] the static deflection is 0.1 µm


def opensees_pair(dt, ax, ay, *, mu, radius, yield_m, mass=1.0, substeps=1):
    """Relative displacement history (n, 2) of a single friction pendulum in OpenSees."""
    import openseespy.opensees as ops

    weight = mass * G
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(1, 0.0, 0.0, 0.0)
    ops.node(2, 0.0, 0.0, 0.0, "-mass", mass, mass, mass, 0.0, 0.0, 0.0)
    ops.fix(1, 1, 1, 1, 1, 1, 1)
    ops.fix(2, 0, 0, 0, 1, 1, 1)
    ops.uniaxialMaterial("Elastic", 1, VERTICAL_STIFFNESS_PER_WEIGHT * weight)  # stiff vertical spring
    ops.uniaxialMaterial("Elastic", 2, 0.0)
    ops.frictionModel("Coulomb", 1, mu)
    k_init = mu * weight / yield_m
    ops.element("singleFPBearing", 1, 1, 2, 1, radius, k_init, "-P", 1, "-T", 2, "-My", 2, "-Mz", 2,
                "-orient", 0, 0, 1, 1, 0, 0)
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(2, 0.0, 0.0, -weight, 0.0, 0.0, 0.0)
    ops.system("BandGeneral")
    ops.numberer("Plain")
    ops.constraints("Plain")
    ops.test("NormDispIncr", 1e-12, 25)
    ops.integrator("LoadControl", 0.1)
    ops.algorithm("Newton")
    ops.analysis("Static")
    ops.analyze(10)
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()
    ops.timeSeries("Path", 2, "-dt", dt, "-values", *ax.tolist())
    ops.timeSeries("Path", 3, "-dt", dt, "-values", *ay.tolist())
    ops.pattern("UniformExcitation", 2, 1, "-accel", 2)
    ops.pattern("UniformExcitation", 3, 2, "-accel", 3)
    ops.system("BandGeneral")
    ops.numberer("Plain")
    ops.constraints("Plain")
    ops.test("NormDispIncr", 1e-10, 25)
    ops.integrator("Newmark", 0.5, 0.25)
    ops.algorithm("Newton")
    ops.analysis("Transient")
    # the whole record in one analyze() call (as an OpenSees user would run it), recorded
    # to a file; a step that does not converge is redone in halves from where it stopped
    with tempfile.TemporaryDirectory() as folder:
        path = str(Path(folder) / "disp.out")
        ops.recorder("Node", "-file", path, "-time", "-precision", 17, "-node", 2, "-dof", 1, 2, "disp")
        t_end = (ax.size - 1) * dt
        guard = 0
        while ops.getTime() < t_end - 1e-9 * dt:
            guard += 1
            if guard > 100000:
                raise RuntimeError(f"OpenSees did not converge near t = {ops.getTime():.3f} s")
            remaining = round((t_end - ops.getTime()) / dt)
            on_sample = abs(ops.getTime() / dt - round(ops.getTime() / dt)) < 1e-9
            if remaining >= 1 and on_sample and ops.analyze(remaining * substeps, dt / substeps) == 0:
                break
            step = dt / substeps
            while ops.analyze(1, step) != 0:
                step *= 0.5
                if step < 1e-8 * dt:
                    raise RuntimeError(f"OpenSees did not converge near t = {ops.getTime():.3f} s")
            # finish the sample interval in steps of the size that converged
            next_sample = (math.floor(ops.getTime() / dt + 1e-9) + 1) * dt
            while ops.getTime() < next_sample - 1e-9 * dt:
                ops.analyze(1, min(step, next_sample - ops.getTime()))
        ops.remove("recorders")
        rows = np.loadtxt(path, ndmin=2)
    index = np.rint(rows[:, 0] / dt).astype(int)
    on_sample = np.abs(rows[:, 0] - index * dt) < 1e-9 * dt
    out = np.zeros((ax.size, 2))
    out[index[on_sample]] = rows[on_sample, 1:3]
    ops.wipe()
    return out


def errors(history, ref):
    resultant = np.hypot(history[:, 0], history[:, 1])
    scale = ref.peak_displacement_m
    return (abs(resultant.max() - scale) / scale,
            abs(resultant[-1] - ref.residual_displacement_m) / scale,
            np.max(np.abs(history - ref.displacement_m)) / scale)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pair", default="superstitionhills1987_PTS")
    parser.add_argument("--mu", type=float, default=0.06)
    parser.add_argument("--radius", type=float, default=2.0)
    parser.add_argument("--yield-mm", type=float, default=0.5)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--substeps", type=int, default=1, help="OpenSees steps per sample interval")
    args = parser.parse_args(argv)
    try:
        import openseespy.opensees  # noqa: F401
    except (ImportError, RuntimeError) as exc:  # openseespy raises RuntimeError when libblas is missing
        raise SystemExit(f"openseespy does not import here: {exc}") from None
    dt, ax, ay, _ = load(args.pair)
    t = dt * np.arange(ax.size)
    start = time.perf_counter()
    ref = reference_pair(t, ax, ay, mu_s=args.mu, radius=args.radius)
    ref_seconds = time.perf_counter() - start

    ours, theirs = [], []
    for _ in range(args.repeat):
        r = simulate_pair(ax, ay, dt, mu_static=args.mu, radius_m=args.radius)
        ours.append(r.solver_seconds)
        start = time.perf_counter()
        history = opensees_pair(dt, ax, ay, mu=args.mu, radius=args.radius, yield_m=1e-3 * args.yield_mm,
                                substeps=args.substeps)
        theirs.append(time.perf_counter() - start)
    t_ours, t_theirs = statistics.median(ours), statistics.median(theirs)
    e_ours = errors(r.displacement_m, ref)
    # our peak is located between samples; compare the sampled one too, as OpenSees only has samples
    e_ours = (abs(r.peak_displacement_m - ref.peak_displacement_m) / ref.peak_displacement_m,) + e_ours[1:]
    e_theirs = errors(history, ref)
    print(f"pair {args.pair}: {ax.size} samples, dt = {dt} s; single friction pendulum R = {args.radius} m, "
          f"µ = {args.mu}; reference (solve_ivp) {ref_seconds:.1f} s, peak {1e3 * ref.peak_displacement_m:.3f} mm")
    print(f"{'method':30s} {'seconds':>9s} {'peak err':>9s} {'resid err':>9s} {'hist err':>9s}")
    print(f"{'isolator simulate_pair':30s} {t_ours:9.4f} {e_ours[0]:9.1e} {e_ours[1]:9.1e} {e_ours[2]:9.1e}")
    label = f"OpenSees FP uy={args.yield_mm}mm dt/{args.substeps}"
    print(f"{label:30s} {t_theirs:9.4f} {e_theirs[0]:9.1e} {e_theirs[1]:9.1e} {e_theirs[2]:9.1e}")
    print(f"isolator is {t_theirs / t_ours:.0f}x faster, with {e_theirs[2] / max(e_ours[2], 1e-300):.1e}x lower "
          f"history error ({e_theirs[0] / max(e_ours[0], 1e-300):.1e}x on the peak)")


if __name__ == "__main__":
    main()
