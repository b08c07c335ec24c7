"""The compiled force of the µ(v) slide along the rims (h204, issue 23) against the numpy module (h192/h199, the
independent reference) and against the convex problem's conditions written here with this file's own law."""

import math

import numpy as np

from isolator.solver.planar_rim_slide import rim_frames, slide_along_rims
from isolator.solver.planar_rim_slide_kernel import FROM_GROWN, FROM_SEED, NOT_FOUND, rim_slide_force

MU_S = np.array([0.04, 0.01, 0.01, 0.07])
MU_F = np.array([0.06, 0.02, 0.02, 0.10])
A = np.array([20.0, 20.0, 20.0, 20.0])
CAPS = np.array([0.4, 0.05, 0.05, 0.4])
# b = B u of the review's lower-bound TFP (R 2.1/0.3/0.3/2.1 m): /tmp/h199/pts_state.npz's bmat
BMAT = np.array([[1 / 2.1, 0, 0, 0], [1 / 2.1, 1 / 0.3, 0, 0], [0, 0, 1 / 0.3, 1 / 2.1], [0, 0, 0, 1 / 2.1]])
# PTS at its first "all on rims" (h199: t = 12.289903479634537 s): Ẋ, then u_1..u_4
PTS = [0.8652783307174143, 0.0638643450559487, 0.37554276072867926, 0.1377230367958897, 0.04914620138831163,
       0.00920059177985393, 0.04904564521028322, 0.009722380670752552, 0.3767663486806817, 0.13433956417164303]


def certify(xdot, b, t, r, psi):
    """The root's conditions with this file's law: sliding s_j = σ µ_j(|ψ_j|), held |s_j| ≤ µ_slow, Σ ψ t = Ẋ."""
    s = np.einsum("ij,ij->i", r[None, :] - b, t)
    on = psi != 0.0
    law = s[on] - np.sign(psi[on]) * (MU_F[on] - (MU_F[on] - MU_S[on]) * np.exp(-A[on] * np.abs(psi[on])))
    return float(np.max(np.abs(law))), float(np.max(np.abs(t.T @ psi - xdot))), bool(np.all(np.abs(s[~on]) <= MU_S[~on]))


def states():
    u = np.reshape(PTS[2:], (4, 2))
    u = u * (CAPS / np.hypot(u[:, 0], u[:, 1]))[:, None]
    out = [(np.array(PTS[:2]), u)]
    # h199's state with three sliding, one between its levels
    ang = np.array([0.5001731855354982, 0.6199205030288358, 0.5788464920912926, 0.6445])
    out.append((np.array([0.02649932293741722, 0.367698050361364]), CAPS[:, None] * np.column_stack((np.cos(ang),
                                                                                                       np.sin(ang)))))
    rng = np.random.default_rng(7)
    for scale in (0.01, 0.1, 0.5, 2.0) * 5:
        ang = 0.4 + rng.uniform(-0.1, 0.1, 4)
        out.append((scale * rng.normal(size=2), CAPS[:, None] * np.column_stack((np.cos(ang), np.sin(ang)))))
    return out


def test_compiled_force_is_the_numpy_force_and_the_root():
    """22 states (PTS's, h199's, 20 random across 0.01–2 m/s): the compiled force within 5e-12 of numpy's (whose own
    residual on Σ ψ t − Ẋ is up to ~5e-11 where its Newton on Φ stops at the rounding floor) and the root's conditions
    to rounding; seeded with its own answer it answers from the seed (to 1e-13); rotation invariance."""
    for xdot, u in states():
        b = BMAT @ u
        _, t = rim_frames(u)
        r0, psi0, _, _ = slide_along_rims(xdot, b, u, MU_S, MU_F, A)
        r, psi = np.zeros(2), np.zeros(4)
        assert rim_slide_force(xdot, b, t, MU_S, MU_F, A, 1e-13, np.zeros(4), r, psi) == FROM_GROWN
        assert np.max(np.abs(r - r0)) < 5e-12
        assert np.all((psi != 0.0) == (psi0 != 0.0))
        law, res, held = certify(xdot, b, t, r, psi)
        assert law < 4e-15 and res < 1e-13 * (1.0 + math.hypot(*xdot)) and held
        r2, psi2 = np.zeros(2), np.zeros(4)
        assert rim_slide_force(xdot, b, t, MU_S, MU_F, A, 1e-13, psi.copy(), r2, psi2) == FROM_SEED
        assert np.max(np.abs(r2 - r)) < 1e-13
        phi = 0.9
        q = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
        r3, psi3 = np.zeros(2), np.zeros(4)
        assert rim_slide_force(q @ xdot, b @ q.T, t @ q.T, MU_S, MU_F, A, 1e-13, np.zeros(4), r3, psi3) > 0
        assert np.max(np.abs(r3 - q @ r)) < 1e-13


def test_aligned_rims_are_not_found():
    """Tangents that do not span the plane (the rims aligned: the ultimate's impact) give no force."""
    u = CAPS[:, None] * np.array([math.cos(0.35), math.sin(0.35)])[None, :]
    _, t = rim_frames(u)
    r, psi = np.zeros(2), np.zeros(4)
    assert rim_slide_force(np.array([0.5, 0.1]), BMAT @ u, t, MU_S, MU_F, A, 1e-13, np.zeros(4), r, psi) == NOT_FOUND
