"""The OpenSees baseline of the triple friction pendulum bench: ``TripleFrictionPendulum`` (issue 23).

OpenSees' element (Dao et al. 2013, EESD; ndm 3, ndf 6) under a rigid mass, set up as the
rigid block of :func:`isolator.bench.opensees.opensees_pair`: two coincident nodes, the
element between them, gravity applied statically, the horizontal component(s) as
``UniformExcitation`` patterns, Newmark (γ = 1/2, β = 1/4) + Newton at the record's dt
(a failed step redone in halves, :func:`isolator.bench.opensees.analyze_record`).

The element's arguments, in its own numbering (pendulum 1 = the two inner surfaces, which it
takes as identical; 2 = the outer surface of the lower friction, 3 = the other outer):
``frnTag1 frnTag2 frnTag3`` (``frictionModel Coulomb`` µ2 = µ3, µ1, µ4), ``vertMatTag`` (a
stiff elastic compression material), ``rotZ/X/YMatTag``, ``L1 L2 L3`` (R_eff = R − h of
surfaces 2, 1, 4), ``d1 d2 d3`` (the effective capacities d* of the same), ``W`` (the axial
force of its first trial), ``uy`` (elastic displacement before sliding, 0.5 mm as for
``singleFPBearing``), ``kvt`` (tension stiffness), ``minFv``, ``tol``.  In 1-D the mass
is held along y (a zero second component gives the same answer).
"""

from __future__ import annotations

import numpy as np

from isolator.bench.opensees import (
    OPENSEES_YIELD_DISPLACEMENT_M,
    VERTICAL_STIFFNESS_PER_WEIGHT,
    isolated_mass_model,
    load_opensees,
    on_samples,
    shake,
)

#: the element's convergence tolerance (its documentation recommends 1e-10 … 1e-3)
ELEMENT_TOLERANCE = 1e-10


def tfp_arguments(bearing) -> tuple[tuple, tuple, tuple]:
    """(µ, L, d) of OpenSees' three pendulums from a Fenz–Constantinou triple bearing.

    Parameters
    ----------
    bearing : isolator.bearing.Bearing
        ``kind == "triple"``, surfaces 1–4 outer-bottom first.

    Returns
    -------
    tuple
        ``((µ_inner, µ_outer_low, µ_outer_high), (L1, L2, L3) [m], (d1, d2, d3) [m])``.

    Raises
    ------
    ValueError
        When the bearing is not a triple with identical inner surfaces (the element's assumption).
    """
    if bearing.kind != "triple":
        raise ValueError(f"OpenSees' TripleFrictionPendulum models a triple bearing, not a {bearing.kind}")
    s1, s2, s3, s4 = bearing.surfaces
    if (s2.effective_radius_m, s2.mu_kinetic, s2.effective_capacity_m) != (
            s3.effective_radius_m, s3.mu_kinetic, s3.effective_capacity_m):
        raise ValueError("OpenSees' TripleFrictionPendulum needs identical inner surfaces (2 and 3)")
    low, high = (s1, s4) if s1.mu_kinetic <= s4.mu_kinetic else (s4, s1)
    return ((s2.mu_kinetic, low.mu_kinetic, high.mu_kinetic),
            (s2.effective_radius_m, low.effective_radius_m, high.effective_radius_m),
            (s2.effective_capacity_m, low.effective_capacity_m, high.effective_capacity_m))


def opensees_tfp(dt_s: float, ax_m_s2, ay_m_s2=None, *, bearing, gravity_m_s2: float = 9.80665,
                 yield_m: float = OPENSEES_YIELD_DISPLACEMENT_M, substeps: int = 1) -> np.ndarray:
    """Displacement history of a mass on OpenSees' ``TripleFrictionPendulum`` at the samples [m].

    Parameters
    ----------
    dt_s : float
        Sample interval [s].
    ax_m_s2, ay_m_s2 : array_like
        Ground acceleration [m/s²]; without ``ay_m_s2`` the mass moves along x only.
    bearing : isolator.bearing.Bearing
        A triple bearing (:func:`tfp_arguments`).
    yield_m : float
        The element's uy [m].
    substeps : int
        OpenSees steps per sample interval.

    Returns
    -------
    numpy.ndarray
        (N,) along x in 1-D, (N, 2) with ``ay_m_s2``.

    Raises
    ------
    OpenSeesUnavailable
        When openseespy does not import.
    """
    ops = load_opensees()
    (mu1, mu2, mu3), lengths, capacities = tfp_arguments(bearing)
    planar = ay_m_s2 is not None
    mass = 1.0
    weight = mass * gravity_m_s2
    isolated_mass_model(ops, mass, mass, planar=planar)
    for tag, mu in ((1, mu1), (2, mu2), (3, mu3)):
        ops.frictionModel("Coulomb", tag, mu)
    ops.uniaxialMaterial("Elastic", 1, VERTICAL_STIFFNESS_PER_WEIGHT * weight)
    ops.uniaxialMaterial("Elastic", 2, 10.0 * weight)  # rotations are fixed at node 2: any small value
    ops.element("TripleFrictionPendulum", 1, 1, 2, 1, 2, 3, 1, 2, 2, 2, *lengths, *capacities, weight, yield_m,
                1e-3 * weight, 1e-3 * weight, ELEMENT_TOLERANCE)
    (rows,) = shake(ops, dt_s, (ax_m_s2, ay_m_s2), weight, substeps, [("-node", 2, "-dof", 1, 2, "disp")])
    out = on_samples(rows, dt_s, len(ax_m_s2), 2)
    return out if planar else out[:, 0]
