"""Which corner steps are implicit (``corner_implicit``): a corner of two groups by its normals' sine, a corner of
three by how close its compliance C = Σ R̄_k e_k e_kᵀ is to singular, κ = √det C / tr C.  The reason, checked on
the model's own rates: the split of V between two groups relaxes at a rate ∝ |V|/s², while three circles through r
whose closest pair is as nearly tangent relax at ≈ 5 |V|/κ², set by the third normal (docs/multisurface.md, "The
corner steps by time, and the three-group switch")."""

from __future__ import annotations

import numpy as np
import pytest

from isolator.solver import planar_multisurface_kernel as pk

G = 9.80665
RB = np.array([1.8, 0.6, 1.8])  # Fenz & Constantinou's groups: surface 1, surfaces 2 + 3, surface 4
MU = np.array([0.06, 0.02, 0.10])
M = pk.M_U + 2 * RB.size
RAW = np.array([0.3, 1.0, -0.2, 0.5, G, 0.0])  # a_x, a_x', a_y, a_y', n, n'


def _state(mask, theta, phi, third, vdir, vmag=0.5):
    # the reduced state (X, V, θ_a, φ and, for three groups, the third normal's angle from e_a) and its expansion
    v = np.zeros(M)
    v[pk.M_X:pk.M_X + 2] = (0.05, 0.02)
    v[pk.M_V:pk.M_V + 2] = (vmag * np.cos(vdir), vmag * np.sin(vdir))
    v[pk.M_R:pk.M_R + 2] = (theta, phi)
    if third is not None:
        v[pk.M_U + 4] = third
    y = np.zeros(M)
    pk.expand_state(v, RB, MU, mask, 0, 1, y)
    return v, y


def _kappa(y, mask):
    # independent of the kernel: the normals from r and the ū, C summed and numpy's determinant
    r = y[pk.M_R:pk.M_R + 2]
    c = np.zeros((2, 2))
    for k in range(RB.size):
        if mask >> k & 1:
            e = r - y[pk.M_U + 2 * k:pk.M_U + 2 * k + 2] / RB[k]
            e /= np.hypot(*e)
            c += RB[k] * np.outer(e, e)
    return np.sqrt(np.linalg.det(c)) / np.trace(c)


def _fastest_rate(v, mask):
    # the largest eigenvalue of the reduced state's Jacobian, by central differences of reduced_rhs
    act = [pk.M_X, pk.M_X + 1, pk.M_V, pk.M_V + 1, pk.M_R, pk.M_R + 1] + ([pk.M_U + 4] if mask == 0b111 else [])
    work, d0, d1 = np.zeros(M), np.zeros(M), np.zeros(M)
    jac = np.zeros((len(act), len(act)))
    for q, p in enumerate(act):
        up, dn = v.copy(), v.copy()
        up[p] += 1e-9
        dn[p] -= 1e-9
        assert pk.reduced_rhs(0.0, up, RAW, RB, MU, mask, 0.0, 0, 1, work, d1)
        assert pk.reduced_rhs(0.0, dn, RAW, RB, MU, mask, 0.0, 0, 1, work, d0)
        jac[:, q] = (d1[act] - d0[act]) / 2e-9
    ev = np.linalg.eigvals(jac)
    return ev[np.argmax(np.abs(ev))]


def test_a_three_group_corner_relaxes_at_its_spread_not_at_its_closest_pair():
    rates = {}
    for phi in (1e-3, 1e-2):
        v2, y2 = _state(0b011, 0.7, phi, None, 0.7 + phi / 2)
        v3, y3 = _state(0b111, 0.7, phi, 0.3, 0.8)
        lam2, lam3 = _fastest_rate(v2, 0b011), _fastest_rate(v3, 0b111)
        assert lam2.real < 0.0 and lam3.real < 0.0 and abs(lam2.imag) <= 1e-6 * abs(lam2)
        rates[phi] = (abs(lam2), abs(lam3))
        kappa = _kappa(y3, 0b111)
        # measured: 5.0 here; 4.1–5.5 (5th–95th percentile) at 700 three-group corner steps of PTS
        assert 2.0 <= abs(lam3) * kappa ** 2 / 0.5 <= 10.0
        # the same closest pair alone is stiffer by five orders of magnitude at 1e-3
        assert abs(lam3) <= 1e-2 * abs(lam2)
    # two groups: ∝ 1/s² (100x for a tenth of the sine, to 1 %); three: nearly unchanged (its κ barely moves)
    assert rates[1e-3][0] / rates[1e-2][0] == pytest.approx(100.0, rel=1e-2)
    assert rates[1e-3][1] / rates[1e-2][1] == pytest.approx(1.0, rel=0.1)


@pytest.mark.parametrize("seed", range(4))
def test_the_switch_reads_the_sine_for_two_groups_and_kappa_for_three(seed):
    rng = np.random.default_rng(seed)
    for _ in range(50):
        theta = rng.uniform(-np.pi, np.pi)
        phi = 10.0 ** rng.uniform(-5.0, -0.5) * rng.choice((-1.0, 1.0))
        _, y2 = _state(0b011, theta, phi, None, theta + phi / 2)
        assert pk.corner_implicit(y2, RB, 0b011) == (abs(np.sin(phi)) < pk.IMPLICIT_ANGLE)
        third = 10.0 ** rng.uniform(-3.5, -0.5) * rng.choice((-1.0, 1.0))
        _, y3 = _state(0b111, theta, phi, third, theta)
        kappa = _kappa(y3, 0b111)
        if abs(kappa / pk.IMPLICIT_SPREAD - 1.0) > 1e-9:
            assert pk.corner_implicit(y3, RB, 0b111) == (kappa < pk.IMPLICIT_SPREAD)
    # a closest pair below IMPLICIT_ANGLE with the third normal 0.3 rad away: explicit; all three within 5e-3: implicit
    _, y3 = _state(0b111, 0.7, 1e-3, 0.3, 0.8)
    assert pk.corner_angle(y3, RB, 0b111) < pk.IMPLICIT_ANGLE and not pk.corner_implicit(y3, RB, 0b111)
    _, y3 = _state(0b111, 0.7, 1e-3, 5e-3, 0.702)
    assert pk.corner_implicit(y3, RB, 0b111)
