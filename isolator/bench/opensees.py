"""The OpenSees baseline of the 2-D bench: openseespy's coupled friction pendulum (``singleFPBearing``).

Ported from ``benchmarks/opensees_pair.py``.  A 3-D model (ndm 3, ndf 6): two
coincident nodes joined by a ``singleFPBearing`` (Reff = R, the usual elastic
stiffness before sliding kInit = µW/u_y with u_y = 0.5 mm, a stiff elastic vertical
material), gravity applied statically, then the horizontal components (and the
vertical one, when the case has it) as ``UniformExcitation`` patterns; Newmark
(γ = 1/2, β = 1/4) with Newton, at the record's dt or a fraction of it, in one
``analyze`` call (a step that does not converge is redone in halves, as in the
OpenSees examples).  Friction: ``frictionModel Coulomb`` (constant µ) or
``VelDependent`` (µ(v) = µ_fast − (µ_fast − µ_slow) e^{−a v}, the same law as ours).

The error of this model is mostly the element's own formulation (elastic stick
branch, its large-displacement geometry), not its time step: docs/planar.md shows it
does not shrink with a 10× smaller step nor a 100× stiffer kInit.

openseespy is optional (``pip install "isolator[bench]"``); :func:`opensees_available`
says whether it imports here, and why not.
"""

from __future__ import annotations

import atexit
import math
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

#: stick displacement of the bearing's elastic branch, kInit = µW/u_y [m] (OpenSees examples use ~0.5 mm)
OPENSEES_YIELD_DISPLACEMENT_M = 5e-4
#: stiffness of the vertical material per unit weight [1/m]: a static deflection of 0.1 µm
VERTICAL_STIFFNESS_PER_WEIGHT = 1e7
#: guard on the number of analyze() restarts after non-converged steps
MAX_RESTARTS = 100000


class OpenSeesUnavailable(RuntimeError):
    """openseespy does not import here (not installed, or its shared libraries are missing)."""


def opensees_available() -> tuple[bool, str]:
    """(True, "") when ``openseespy.opensees`` imports, else (False, the reason)."""
    try:
        import openseespy.opensees  # noqa: F401
    except ImportError:
        return False, "openseespy not installed"
    except RuntimeError as exc:  # openseespy raises RuntimeError when libblas/liblapack are missing
        return False, f"openseespy does not load ({exc})"
    _silence_exit_message()
    return True, ""


_silenced = False


def _silence_exit_message() -> None:
    """OpenSees's library writes "Process 0 Terminating" on stderr when the process exits,
    after everything we print: point stderr at /dev/null at exit, so that the bench ends
    with its own last line.  (Exit handlers run last-registered first: whatever runs
    after this one, the library's and those registered before openseespy was imported,
    writes nothing to the terminal.)"""
    global _silenced
    if _silenced:
        return
    _silenced = True

    def close_stderr() -> None:
        try:
            sys.stderr.flush()
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, 2)
        except (OSError, ValueError):
            pass

    atexit.register(close_stderr)


def opensees_pair(dt_s: float, ax_m_s2, ay_m_s2, az_m_s2=None, *, mu: float, radius_m: float,
                  mu_slow: float | None = None, mu_fast: float | None = None, rate_s_per_m: float | None = None,
                  gravity_m_s2: float = 9.80665, yield_m: float = OPENSEES_YIELD_DISPLACEMENT_M,
                  substeps: int = 1) -> np.ndarray:
    """Relative displacement history (N, 2) [m] of a single friction pendulum in OpenSees.

    Parameters
    ----------
    dt_s : float
        Sample interval of the record [s].
    ax_m_s2, ay_m_s2, az_m_s2 : array_like
        Ground acceleration [m/s²] (vertical up positive, optional).
    mu : float
        Coulomb friction coefficient [-] (when ``mu_slow`` is None).
    radius_m : float
        Effective radius of the pendulum [m].
    mu_slow, mu_fast, rate_s_per_m : float, optional
        Velocity-dependent friction (OpenSees ``VelDependent``), [-], [-], [s/m].
    yield_m : float
        Elastic displacement before sliding [m] (kInit = µW/yield_m).
    substeps : int
        OpenSees steps per sample interval.

    Raises
    ------
    OpenSeesUnavailable
        When openseespy does not import.
    RuntimeError
        When OpenSees does not converge even at 1e-8 of the step.
    """
    ops = load_opensees()
    mass = 1.0
    weight = mass * gravity_m_s2
    isolated_mass_model(ops, mass, mass, planar=True)
    if mu_slow is None:
        ops.frictionModel("Coulomb", 1, mu)
    else:
        ops.frictionModel("VelDependent", 1, mu_slow, mu_fast, rate_s_per_m)
    single_fp_bearing(ops, weight, radius_m, (mu if mu_slow is None else mu_slow) * weight / yield_m)
    (rows,) = shake(ops, dt_s, (ax_m_s2, ay_m_s2, az_m_s2), weight, substeps, [("-node", 2, "-dof", 1, 2, "disp")])
    return on_samples(rows, dt_s, len(ax_m_s2), 2)


def load_opensees():
    """The ``openseespy.opensees`` module.

    Raises
    ------
    OpenSeesUnavailable
        When openseespy does not import (with the reason).
    """
    ok, why = opensees_available()
    if not ok:
        raise OpenSeesUnavailable(why)
    import openseespy.opensees as ops

    return ops


def isolated_mass_model(ops, horizontal_mass_kg: float, vertical_mass_kg: float, *, planar: bool) -> None:
    """A fresh 3-D model (ndm 3, ndf 6): node 1 the ground (fixed), node 2 the isolated mass above it.

    Node 2 carries ``horizontal_mass_kg`` along x and y and ``vertical_mass_kg`` along z
    [kg]; it moves along x, along y when ``planar`` (held otherwise) and vertically on the
    bearing's stiff vertical material; its rotations are fixed.  Both nodes sit at the origin
    (the bearings are zero-length elements).
    """
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(1, 0.0, 0.0, 0.0)
    ops.node(2, 0.0, 0.0, 0.0, "-mass", horizontal_mass_kg, horizontal_mass_kg, vertical_mass_kg, 0.0, 0.0, 0.0)
    ops.fix(1, 1, 1, 1, 1, 1, 1)
    ops.fix(2, 0, 0 if planar else 1, 0, 1, 1, 1)


def single_fp_bearing(ops, weight_N: float, radius_m: float, k_init_N_per_m: float,
                      tolerance_N: float | None = None) -> None:
    """Element 1, a ``singleFPBearing`` from node 1 to node 2 on friction model 1 (defined by the caller).

    Reff = ``radius_m``, kInit = ``k_init_N_per_m``; material 1 (elastic, a static deflection
    of 0.1 µm under ``weight_N``) along the axis, material 2 (zero stiffness) in torsion and
    bending; the axis along global z.  ``tolerance_N``: the element's own equilibrium
    tolerance (``-iter 25 tol``, a force [N]; OpenSees' default 1e-12 suits a weight of order 1,
    not a building's 3e7 N, where it fails to converge and every such step is redone in halves).
    """
    ops.uniaxialMaterial("Elastic", 1, VERTICAL_STIFFNESS_PER_WEIGHT * weight_N)  # stiff vertical spring
    ops.uniaxialMaterial("Elastic", 2, 0.0)
    iteration = () if tolerance_N is None else ("-iter", 25, tolerance_N)
    ops.element("singleFPBearing", 1, 1, 2, 1, radius_m, k_init_N_per_m, "-P", 1, "-T", 2, "-My", 2, "-Mz", 2,
                "-orient", 0, 0, 1, 1, 0, 0, *iteration)


def shake(ops, dt_s: float, components, weight_N: float, substeps: int, recorders: list,
          numberer: str = "Plain") -> list:
    """Gravity on node 2, then the record: the rows of each Node recorder (:func:`run_transient`).

    ``components`` are the ground accelerations [m/s²] along x, y and z (``None`` for a
    direction without one), applied as ``UniformExcitation`` patterns on time series 2, 3, 4.
    """
    apply_gravity(ops, 2, weight_N, numberer=numberer)
    n_samples = 0
    for direction, acc in enumerate(components, start=1):
        if acc is None:
            continue
        values = np.asarray(acc, dtype=float)
        n_samples = values.size
        ops.timeSeries("Path", 1 + direction, "-dt", dt_s, "-values", *values.tolist())
        ops.pattern("UniformExcitation", 1 + direction, direction, "-accel", 1 + direction)
    return run_transient(ops, dt_s, n_samples, substeps, recorders, numberer=numberer)


def apply_gravity(ops, node: int, weight_N: float, numberer: str = "Plain") -> None:
    """The weight on ``node`` as a static load in 10 steps, held constant from time 0 on."""
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(node, 0.0, 0.0, -weight_N, 0.0, 0.0, 0.0)
    ops.system("BandGeneral")
    ops.numberer(numberer)
    ops.constraints("Plain")
    ops.test("NormDispIncr", 1e-12, 25)
    ops.integrator("LoadControl", 0.1)
    ops.algorithm("Newton")
    ops.analysis("Static")
    ops.analyze(10)
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()


def run_transient(ops, dt_s: float, n_samples: int, substeps: int, recorders: list,
                  numberer: str = "Plain") -> list:
    """Newmark (½, ¼) + Newton over the record; the rows of each Node recorder (``recorders``:
    the arguments after ``-file … -time -precision 17``), read back; the model is wiped after."""
    ops.system("BandGeneral")
    ops.numberer(numberer)
    ops.constraints("Plain")
    ops.test("NormDispIncr", 1e-10, 25)
    ops.integrator("Newmark", 0.5, 0.25)
    ops.algorithm("Newton")
    ops.analysis("Transient")
    try:
        with tempfile.TemporaryDirectory() as folder:
            paths = [str(Path(folder) / f"out{i}.txt") for i in range(len(recorders))]
            for path, args in zip(paths, recorders, strict=True):
                ops.recorder("Node", "-file", path, "-time", "-precision", 17, *args)
            analyze_record(ops, dt_s, n_samples, substeps)
            ops.remove("recorders")
            return [np.loadtxt(path, ndmin=2) for path in paths]
    finally:
        ops.wipe()


def on_samples(rows: np.ndarray, dt_s: float, n_samples: int, n_columns: int) -> np.ndarray:
    """The recorder's rows that fall on the record's samples (zero at t = 0, the state at rest)."""
    index = np.rint(rows[:, 0] / dt_s).astype(int)
    on_sample = (np.abs(rows[:, 0] - index * dt_s) < 1e-9 * dt_s) & (index >= 0) & (index < n_samples)
    out = np.zeros((n_samples, n_columns))
    out[index[on_sample]] = rows[on_sample, 1:1 + n_columns]
    return out


def analyze_record(ops, dt_s: float, n_samples: int, substeps: int) -> None:
    """The whole record in one analyze() call; a failing step is redone in halves from where it stopped."""
    t_end = (n_samples - 1) * dt_s
    for _ in range(MAX_RESTARTS):
        if ops.getTime() >= t_end - 1e-9 * dt_s:
            return
        remaining = round((t_end - ops.getTime()) / dt_s)
        on_sample = abs(ops.getTime() / dt_s - round(ops.getTime() / dt_s)) < 1e-9
        if remaining >= 1 and on_sample and ops.analyze(remaining * substeps, dt_s / substeps) == 0:
            return
        step = dt_s / substeps
        while ops.analyze(1, step) != 0:
            step *= 0.5
            if step < 1e-8 * dt_s:
                raise RuntimeError(f"OpenSees did not converge near t = {ops.getTime():.3f} s")
        # finish the sample interval in steps of the size that converged
        next_sample = (math.floor(ops.getTime() / dt_s + 1e-9) + 1) * dt_s
        for _ in range(math.ceil(dt_s / step) + 2):
            if ops.getTime() >= next_sample - 1e-9 * dt_s:
                break
            ops.analyze(1, min(step, next_sample - ops.getTime()))
    raise RuntimeError(f"OpenSees: more than {MAX_RESTARTS} restarts")
