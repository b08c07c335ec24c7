"""The OpenSees baseline of the building bench: a shear building on a ``singleFPBearing`` (issue 22).

The same building as :mod:`isolator.solver.building` (model ``1d-building``), built in
openseespy the way an engineer would, on the rigid-block set-up of
:func:`isolator.bench.opensees.opensees_pair` (ndm 3, ndf 6):

* node 1, the ground (fixed); node 2, the base slab (mass m_b = M − Σ m_i), joined to the
  ground by one ``singleFPBearing`` (Reff = R, kInit = µW/u_y with u_y = 0.5 mm, a stiff
  elastic vertical material, ``frictionModel Coulomb`` µ) carrying the whole weight
  W = g M as a static vertical load on the slab, so that its restoring force is W/R·x and its
  friction µW, as in ours;
* nodes 3 … n+2, the floors (mass m_i along x; vertical and rotations fixed; y fixed in 1-D),
  all at the slab's coordinates (a shear building's heights enter no force; ``zeroLength``
  elements need coincident nodes);
* the story springs k_i as ``zeroLength`` elements (``Elastic`` material, direction 1)
  between consecutive floors, the first from the slab;
* the classical damping C_s = M Φ diag(2ζω_j) Φᵀ M (on the floor displacements relative to
  the slab) exactly, as a network of linear dashpots (``Elastic`` material with E = 0 and
  η = c): c_ij = −C_ij between floors i and j, c_i0 = Σ_j C_ij between floor i and the slab
  (a full symmetric C is such a network; some c are negative, which OpenSees accepts);
  no Rayleigh damping;
* the ground acceleration as a ``UniformExcitation`` along x; Newmark (γ = 1/2, β = 1/4)
  + Newton at the record's dt, a failed step redone in halves
  (:func:`isolator.bench.opensees.run_transient`).

The friction of ``singleFPBearing`` is Coulomb with the element's elastic stick branch
(u_y); this, not the step, is most of its error (docs/bench.md).

openseespy is optional (``pip install "isolator[bench]"``).
"""

from __future__ import annotations

import numpy as np

from isolator.bench.opensees import (
    OPENSEES_YIELD_DISPLACEMENT_M,
    VERTICAL_STIFFNESS_PER_WEIGHT,
    OpenSeesUnavailable,
    apply_gravity,
    on_samples,
    opensees_available,
    run_transient,
)


def dashpot_network(damping_matrix) -> tuple[np.ndarray, np.ndarray]:
    """Dashpot coefficients that realise a symmetric damping matrix on displacements relative to a base.

    Parameters
    ----------
    damping_matrix : array_like
        C (n × n) [N·s/m], acting on the floors' velocities relative to the base slab.

    Returns
    -------
    tuple
        ``(to_base, between)``: c_i0 = Σ_j C_ij [N·s/m] (floor i to the slab) and the
        (n × n) matrix c_ij = −C_ij for i ≠ j (zero diagonal) between floors i and j.
        Σ_j c_ij (u̇_i − u̇_j) + c_i0 u̇_i = (C u̇)_i, and the slab receives 1ᵀ C u̇.
    """
    c = np.asarray(damping_matrix, dtype=float)
    between = -c.copy()
    np.fill_diagonal(between, 0.0)
    return c.sum(axis=1), between


def opensees_building(dt_s: float, acceleration_m_s2, *, masses_kg, stiffnesses_N_per_m, damping_matrix,
                      total_mass_kg: float, radius_m: float, mu: float, gravity_m_s2: float = 9.80665,
                      yield_m: float = OPENSEES_YIELD_DISPLACEMENT_M, substeps: int = 1) -> dict:
    """Histories of a shear building on a friction pendulum in OpenSees, one horizontal direction.

    Parameters
    ----------
    dt_s : float
        Sample interval of the record [s].
    acceleration_m_s2 : array_like
        Ground acceleration along x [m/s²].
    masses_kg, stiffnesses_N_per_m : array_like
        Floor masses m_i [kg] and story stiffnesses k_i [N/m], bottom to top.
    damping_matrix : array_like
        C_s [N·s/m] on the floors' displacements relative to the slab
        (:meth:`isolator.superstructure.Superstructure.damping_matrix`).
    total_mass_kg : float
        M, floors + slab [kg]; the bearing carries W = g M.
    radius_m : float
        Effective radius of the pendulum [m] (restoring stiffness W/R).
    mu : float
        Coulomb friction coefficient [-].
    yield_m : float
        The bearing's elastic displacement before sliding [m] (kInit = µW/yield_m).
    substeps : int
        OpenSees steps per sample interval.

    Returns
    -------
    dict
        ``slab_displacement_m`` (N,) relative to the ground, ``floor_displacement_m`` (N, n)
        relative to the slab, ``floor_absolute_acceleration_m_s2`` (N, n), at the samples.

    Raises
    ------
    OpenSeesUnavailable
        When openseespy does not import.
    RuntimeError
        When OpenSees does not converge even at 1e-8 of the step.
    """
    ok, why = opensees_available()
    if not ok:
        raise OpenSeesUnavailable(why)
    import openseespy.opensees as ops

    acc = np.asarray(acceleration_m_s2, dtype=float)
    masses = np.asarray(masses_kg, dtype=float)
    stiffnesses = np.asarray(stiffnesses_N_per_m, dtype=float)
    n = masses.size
    slab_mass = float(total_mass_kg) - float(masses.sum())
    weight = float(total_mass_kg) * gravity_m_s2
    to_base, between = dashpot_network(damping_matrix)
    floor_nodes = [3 + i for i in range(n)]

    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(1, 0.0, 0.0, 0.0)
    ops.node(2, 0.0, 0.0, 0.0, "-mass", slab_mass, slab_mass, total_mass_kg, 0.0, 0.0, 0.0)
    ops.fix(1, 1, 1, 1, 1, 1, 1)
    ops.fix(2, 0, 1, 0, 1, 1, 1)  # 1-D: the slab moves along x (and vertically on its stiff spring)
    for node, m in zip(floor_nodes, masses, strict=True):
        ops.node(node, 0.0, 0.0, 0.0, "-mass", m, m, 0.0, 0.0, 0.0, 0.0)
        ops.fix(node, 0, 1, 1, 1, 1, 1)
    ops.uniaxialMaterial("Elastic", 1, VERTICAL_STIFFNESS_PER_WEIGHT * weight)
    ops.uniaxialMaterial("Elastic", 2, 0.0)
    ops.frictionModel("Coulomb", 1, mu)
    ops.element("singleFPBearing", 1, 1, 2, 1, radius_m, mu * weight / yield_m, "-P", 1, "-T", 2, "-My", 2,
                "-Mz", 2, "-orient", 0, 0, 1, 1, 0, 0)
    material, element = 10, 10
    below = [2] + floor_nodes[:-1]
    for i in range(n):  # story springs, and the dashpots from each floor to the slab
        material += 1
        element += 1
        ops.uniaxialMaterial("Elastic", material, float(stiffnesses[i]))
        ops.element("zeroLength", element, below[i], floor_nodes[i], "-mat", material, "-dir", 1)
        material += 1
        element += 1
        ops.uniaxialMaterial("Elastic", material, 0.0, float(to_base[i]))
        ops.element("zeroLength", element, 2, floor_nodes[i], "-mat", material, "-dir", 1)
    for i in range(n):
        for j in range(i + 1, n):
            if between[i, j] == 0.0:
                continue
            material += 1
            element += 1
            ops.uniaxialMaterial("Elastic", material, 0.0, float(between[i, j]))
            ops.element("zeroLength", element, floor_nodes[i], floor_nodes[j], "-mat", material, "-dir", 1)

    apply_gravity(ops, 2, weight, numberer="RCM")
    ops.timeSeries("Path", 2, "-dt", dt_s, "-values", *acc.tolist())
    ops.pattern("UniformExcitation", 2, 1, "-accel", 2)
    nodes = [2, *floor_nodes]
    # -timeSeries adds the ground's acceleration: absolute accelerations
    disp_rows, acc_rows = run_transient(ops, dt_s, acc.size, substeps,
                                        [("-node", *nodes, "-dof", 1, "disp"),
                                         ("-timeSeries", 2, "-node", *floor_nodes, "-dof", 1, "accel")],
                                        numberer="RCM")
    disp = on_samples(disp_rows, dt_s, acc.size, n + 1)
    floor_acc = on_samples(acc_rows, dt_s, acc.size, n)
    floor_acc[0] = acc[0]  # at rest before the record: the floors move with the ground
    return {"slab_displacement_m": disp[:, 0], "floor_displacement_m": disp[:, 1:] - disp[:, :1],
            "floor_absolute_acceleration_m_s2": floor_acc}

