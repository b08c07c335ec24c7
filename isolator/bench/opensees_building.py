"""The OpenSees baseline of the building bench: a shear building on a ``singleFPBearing`` (issue 22).

The same building as :mod:`isolator.solver.building` (model ``1d-building``) and, under two
horizontal components, as the 2-D building (model ``2d-building``), built in openseespy the
way an engineer would, on the rigid-block set-up of :mod:`isolator.bench.opensees` (ndm 3,
ndf 6; :func:`~isolator.bench.opensees.isolated_mass_model`):

* node 1, the ground (fixed); node 2, the base slab (mass m_b = M − Σ m_i along x and y, M
  vertically), joined to the ground by one ``singleFPBearing`` (the 3-D element: coupled
  friction on the resultant, Reff = R, kInit = µW/u_y with u_y = 0.5 mm, a stiff elastic
  vertical material, ``frictionModel Coulomb`` µ) carrying the whole weight W = g M as a
  static vertical load on the slab, so that its restoring force is W/R·x and its friction
  µW, as in ours;
* nodes 3 … n+2, the floors (mass m_i along x and y; vertical and rotations fixed; y fixed
  in 1-D), all at the slab's coordinates (a shear building's heights enter no force;
  ``zeroLength`` elements need coincident nodes);
* the story springs k_x,i and k_y,i as ``zeroLength`` elements (``Elastic`` materials,
  directions 1 and 2) between consecutive floors, the first from the slab;
* the classical damping of each direction, C = M Φ diag(2ζω_j) Φᵀ M (on the floor
  displacements relative to the slab), exactly, as a network of linear dashpots
  (``Elastic`` materials with E = 0 and η = c, directions 1 and 2): c_ij = −C_ij between
  floors i and j, c_i0 = Σ_j C_ij between floor i and the slab (a full symmetric C is such a
  network; some c are negative, which OpenSees accepts); no Rayleigh damping;
* the ground acceleration as ``UniformExcitation`` patterns along x (and y); Newmark
  (γ = 1/2, β = 1/4) + Newton at the record's dt, a failed step redone in halves
  (:func:`isolator.bench.opensees.run_transient`); absolute floor accelerations = the
  recorded relative ones + the ground's at the sample.

The friction of ``singleFPBearing`` is Coulomb with the element's elastic stick branch
(u_y); this, not the step, is most of its error (docs/bench.md).

openseespy is optional (``pip install "isolator[bench]"``).
"""

from __future__ import annotations

import numpy as np

from isolator.bench.opensees import (
    OPENSEES_YIELD_DISPLACEMENT_M,
    isolated_mass_model,
    load_opensees,
    on_samples,
    shake,
    single_fp_bearing,
)

#: the bearing element's equilibrium tolerance per unit weight (1e-13 W: OpenSees' default 1e-12 N on
#: the rigid block's W = g, scaled to the building's weight)
ELEMENT_TOLERANCE_PER_WEIGHT = 1e-13


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


def opensees_building(dt_s: float, ax_m_s2, ay_m_s2=None, *, masses_kg, stiffnesses_N_per_m, damping_matrix,
                      total_mass_kg: float, radius_m: float, mu: float, stiffnesses_y_N_per_m=None,
                      damping_matrix_y=None, gravity_m_s2: float = 9.80665,
                      yield_m: float = OPENSEES_YIELD_DISPLACEMENT_M, substeps: int = 1) -> dict:
    """Histories of a shear building on a friction pendulum in OpenSees, one or two horizontal directions.

    Parameters
    ----------
    dt_s : float
        Sample interval of the record [s].
    ax_m_s2, ay_m_s2 : array_like
        Ground acceleration along x and (2-D) y [m/s²]; without ``ay_m_s2`` the building moves along x.
    masses_kg : array_like
        Floor masses m_i [kg], bottom to top.
    stiffnesses_N_per_m, damping_matrix : array_like
        Story stiffnesses k_x,i [N/m] and C_x [N·s/m] (on the floors' displacements relative to
        the slab, :meth:`isolator.superstructure.Superstructure.damping_matrix`) along x.
    stiffnesses_y_N_per_m, damping_matrix_y : array_like, optional
        The same along y (default: those along x); used in 2-D only.
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
        ``slab_displacement_m`` relative to the ground, ``floor_displacement_m`` relative to the
        slab and ``floor_absolute_acceleration_m_s2``, at the samples: (N,), (N, n), (N, n) in
        1-D; (N, 2), (N, n, 2), (N, n, 2) in 2-D (last axis x, y).

    Raises
    ------
    OpenSeesUnavailable
        When openseespy does not import.
    RuntimeError
        When OpenSees does not converge even at 1e-8 of the step.
    """
    ops = load_opensees()
    planar = ay_m_s2 is not None
    ground = [np.asarray(ax_m_s2, dtype=float)] + ([np.asarray(ay_m_s2, dtype=float)] if planar else [])
    n_samples = ground[0].size
    masses = np.asarray(masses_kg, dtype=float)
    n = masses.size
    weight = float(total_mass_kg) * gravity_m_s2
    stories = [np.asarray(stiffnesses_N_per_m, dtype=float)]
    networks = [dashpot_network(damping_matrix)]
    if planar:
        stories.append(stories[0] if stiffnesses_y_N_per_m is None else np.asarray(stiffnesses_y_N_per_m, dtype=float))
        networks.append(networks[0] if damping_matrix_y is None else dashpot_network(damping_matrix_y))
    directions = list(range(1, len(ground) + 1))
    floor_nodes = [3 + i for i in range(n)]

    isolated_mass_model(ops, float(total_mass_kg) - float(masses.sum()), float(total_mass_kg), planar=planar)
    for node, m in zip(floor_nodes, masses, strict=True):
        ops.node(node, 0.0, 0.0, 0.0, "-mass", m, m, 0.0, 0.0, 0.0, 0.0)
        ops.fix(node, 0, 0 if planar else 1, 1, 1, 1, 1)
    ops.frictionModel("Coulomb", 1, mu)
    single_fp_bearing(ops, weight, radius_m, mu * weight / yield_m, tolerance_N=ELEMENT_TOLERANCE_PER_WEIGHT * weight)
    tag = 10

    def link(node_i: int, node_j: int, values, damping: bool) -> None:
        """A zeroLength element with one Elastic material per direction (stiffness, or a dashpot)."""
        nonlocal tag
        materials = []
        for value in values:
            tag += 1
            ops.uniaxialMaterial("Elastic", tag, *((0.0, float(value)) if damping else (float(value),)))
            materials.append(tag)
        ops.element("zeroLength", tag, node_i, node_j, "-mat", *materials, "-dir", *directions)

    below = [2] + floor_nodes[:-1]
    for i in range(n):  # story springs, and the dashpots from each floor to the slab
        link(below[i], floor_nodes[i], [k[i] for k in stories], damping=False)
        link(2, floor_nodes[i], [to_base[i] for to_base, _ in networks], damping=True)
    for i in range(n):
        for j in range(i + 1, n):
            values = [between[i, j] for _, between in networks]
            if any(v != 0.0 for v in values):
                link(floor_nodes[i], floor_nodes[j], values, damping=True)

    nodes = [2, *floor_nodes]
    disp_rows, acc_rows = shake(ops, dt_s, ground, weight, substeps,
                                [("-node", *nodes, "-dof", *directions, "disp"),
                                 ("-node", *floor_nodes, "-dof", *directions, "accel")], numberer="RCM")
    width = len(directions)
    disp = on_samples(disp_rows, dt_s, n_samples, (n + 1) * width).reshape(n_samples, n + 1, width)
    floor_acc = on_samples(acc_rows, dt_s, n_samples, n * width).reshape(n_samples, n, width)
    floor_acc += np.stack(ground, axis=-1)[:, None, :]  # relative + ground = absolute
    slab, floors = disp[:, 0], disp[:, 1:] - disp[:, :1]
    if not planar:
        slab, floors, floor_acc = slab[:, 0], floors[..., 0], floor_acc[..., 0]
    return {"slab_displacement_m": slab, "floor_displacement_m": floors, "floor_absolute_acceleration_m_s2": floor_acc}
