"""The slide along the rims of a µ(v) pendulum in the plane: the constraint's force (h192, issue 23).

Independent truths written here: the forward law µ(v) = µ_f − (µ_f − µ_s) e^(−a v) and its inverse in closed form,
the two-surface root in closed form (Ẋ = c_1 t_1 + c_2 t_2), the residual and the power balance evaluated with this
file's own law, the rotation invariance."""

import math

import numpy as np
import pytest

from isolator.errors import SolverError
from isolator.solver import planar_rim_slide
from isolator.solver.planar_rim_slide import rim_spread, slide_along_rims

# the lower-bound TFP's laws of docs/multisurface.md (h181): µ_slow/µ_fast per surface, a = 20 s/m
MU_S = np.array([0.04, 0.01, 0.01, 0.07])
MU_F = np.array([0.06, 0.02, 0.02, 0.10])
A = np.array([20.0, 20.0, 20.0, 20.0])


def mu_forward(v, mu_s, mu_f, a):
    return mu_f - (mu_f - mu_s) * np.exp(-a * v)


def psi_inverse(s, mu_s, mu_f, a):
    """The slide rate along the tangent at tangential friction s: 0 held (|s| ≤ µ_s), else the inverse of µ(v)."""
    x = np.minimum(np.abs(s), mu_f)
    return np.where(x > mu_s, np.sign(s) * np.log((mu_f - mu_s) / (mu_f - np.maximum(x, mu_s))) / a, 0.0)


def on_rims(angles, caps):
    return np.column_stack((caps * np.cos(angles), caps * np.sin(angles)))


def rotation(phi):
    return np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])


def test_two_rims_apart_take_any_velocity_in_closed_form():
    caps = np.array([0.4, 0.05])
    u = on_rims(np.array([0.3, 0.3 + 0.144]), caps)  # PTS's 8.3°-ish apart
    b = np.array([[0.011, -0.004], [0.002, 0.007]])
    mu_s, mu_f, a = MU_S[:2], MU_F[:2], A[:2]
    t = np.column_stack((-np.sin([0.3, 0.444]), np.cos([0.3, 0.444])))
    for c in ([0.12, -0.05], [0.3, 0.1], [-0.02, -0.4]):  # a|c| ≤ 8: µ_f − µ ≥ 3e-4 (µ_f − µ_s), resolvable
        c = np.array(c)
        xdot = t.T @ c  # any Ẋ is a combination of the two tangents: no impact is due
        sense = np.sign(c)
        s_true = sense * mu_forward(np.abs(c), mu_s, mu_f, a)
        r_true = np.linalg.solve(t, s_true + np.einsum("ij,ij->i", b, t))
        r, psi, res, its = slide_along_rims(xdot, b, u, mu_s, mu_f, a)
        assert np.max(np.abs(r - r_true)) < 5e-12
        assert np.max(np.abs(np.einsum("ij,ij->i", r[None, :] - b, t) - s_true)) < 1e-12
        fast = A[:2] * np.abs(c) < 10.0  # below that ψ' ≤ e^10/(a (µ_f − µ_s)): ψ to rounding × ψ'
        assert np.max(np.abs(psi - c)[fast], initial=0.0) < 1e-11
        assert res < 1e-11 and its <= 60


def test_four_rims_root_power_balance_and_rotation(monkeypatch):
    caps = np.array([0.4, 0.05, 0.05, 0.4])
    ang = np.array([0.50, 0.62, 0.58, 0.50 + 0.1445])
    u = on_rims(ang, caps)
    b = np.array([[0.01, 0.02], [0.003, -0.001], [-0.002, 0.004], [0.02, 0.01]])
    t = np.column_stack((-np.sin(ang), np.cos(ang)))
    xdot = 0.3 * t[0] + 0.02 * np.array([math.cos(0.55), math.sin(0.55)])  # mostly along the outer rim
    r, psi, res, its = slide_along_rims(xdot, b, u, MU_S, MU_F, A)
    assert res < 1e-9 and its <= 60
    s = np.einsum("ij,ij->i", r[None, :] - b, t)
    psi_own = psi_inverse(s, MU_S, MU_F, A)
    held = np.abs(s) <= MU_S
    assert np.all(psi[held] == 0.0) and np.all(np.abs(s) < MU_F)
    assert np.max(np.abs(psi - psi_own)) < 1e-14
    assert np.max(np.abs(t.T @ psi_own - xdot)) < 1e-9
    # the rims' reactions do no work: the power r·Ẋ − Σ b_j·u̇_j is the friction's Σ s_j ψ_j ≥ 0
    udot = psi[:, None] * t
    power = r @ xdot - np.sum(b * udot)
    assert abs(power - np.sum(s * psi)) <= np.hypot(*r) * res + 1e-15 and power > 0.0
    # PTS's speed at its first impact (0.868 m/s) across these rims (0.075 apart, sine): surfaces 1 and 2 take it at
    # ~7 m/s in opposite senses, µ within rounding of µ_fast — the forward law answers; against the closed form over
    # those two (this file's µ(v)), and the held two inside their dead zones (so it is the convex problem's root)
    fast = 0.868 * np.array([math.cos(0.55), math.sin(0.55)])
    r_f, psi_f, res_f, its_f = slide_along_rims(fast, b, u, MU_S, MU_F, A)
    c = np.linalg.solve(t[:2].T, fast)
    s_true = np.sign(c) * mu_forward(np.abs(c), MU_S[:2], MU_F[:2], A[:2])
    r_true = np.linalg.solve(t[:2], s_true + np.einsum("ij,ij->i", b[:2], t[:2]))
    assert its_f == -1 and res_f < 1e-14 and np.max(np.abs(c)) > 7.0
    assert np.max(np.abs(r_f - r_true)) < 1e-15 and np.max(np.abs(psi_f[:2] - c)) < 1e-14
    assert np.all(psi_f[2:] == 0.0)
    assert np.all(np.abs(np.einsum("ij,ij->i", r_f[None, :] - b, t)[2:]) <= MU_S[2:])
    # three surfaces sliding, two at µ_fast to rounding (rims 0/1/2/0.5 rad, 2 m/s): the stall's set (one surface)
    # is not the root's; its supersets are searched — the answer certified by the convex problem's conditions with
    # this file's own law (sliding: s_j = µ_j(ψ_j) in its sense; held: |s_j| ≤ µ_slow; Σ ψ_j t_j = Ẋ)
    u3 = on_rims(np.array([0.0, 1.0, 2.0, 0.5]), caps)
    t3 = np.column_stack((-np.sin([0.0, 1.0, 2.0, 0.5]), np.cos([0.0, 1.0, 2.0, 0.5])))
    x3 = 2.0 * np.array([math.cos(2.5), math.sin(2.5)])
    r3, psi3, res3, its3 = slide_along_rims(x3, np.zeros((4, 2)), u3, MU_S, MU_F, A)
    s3 = t3 @ r3
    on = psi3 != 0.0
    assert its3 == -1 and np.count_nonzero(on) == 3 and np.max(np.abs(t3.T @ psi3 - x3)) < 1e-14
    assert np.max(np.abs(s3[on] - np.sign(psi3[on]) * mu_forward(np.abs(psi3[on]), MU_S[on], MU_F[on], A[on]))) < 1e-15
    assert np.all(np.abs(s3[~on]) <= MU_S[~on])
    # without the search (the stall's own set only) it is refused by name
    monkeypatch.setattr(planar_rim_slide, "MAX_SET_SEARCH", 0)
    with pytest.raises(SolverError, match="does not resolve here"):
        slide_along_rims(x3, np.zeros((4, 2)), u3, MU_S, MU_F, A)
    # rotating the whole state rotates the force
    q = rotation(1.1)
    r_rot, psi_rot, _, _ = slide_along_rims(q @ xdot, b @ q.T, u @ q.T, MU_S, MU_F, A)
    assert np.max(np.abs(r_rot - q @ r)) < 1e-13
    assert np.max(np.abs(psi_rot - psi)) < 1e-11


def test_aligned_rims_are_the_impact_and_are_refused_by_name():
    caps = np.array([0.4, 0.05, 0.05, 0.4])
    u = on_rims(np.full(4, 0.35), caps)
    assert rim_spread(u) < 1e-15
    apart = on_rims(np.array([0.35, 0.35, 0.35, 0.35 + math.asin(0.144)]), caps)
    x = apart.sum(axis=0)
    e4 = apart[3] / caps[3]
    assert rim_spread(apart) == pytest.approx(abs(e4[0] * x[1] - e4[1] * x[0]) / math.hypot(*x), rel=1e-14)
    with pytest.raises(SolverError, match="aligned .*the ultimate's impact is due"):
        slide_along_rims([0.5, 0.1], np.zeros((4, 2)), u, MU_S, MU_F, A)
    with pytest.raises(SolverError, match="µ_fast > µ_slow"):
        slide_along_rims([0.5, 0.1], np.zeros((4, 2)), apart, MU_S, MU_S, A)


def lower_bound_tfp_maps():
    """B (b = B u) and S (ū = S u) of the review's lower-bound TFP (R 2.1/0.3/0.3/2.1 m, plates 0.4/0.05 m)."""
    from isolator.bearing import parse_bearing
    from isolator.errors import DesignError

    bearing = parse_bearing({"type": "triple", "surface": [
        {"radius_m": r, "mu_slow": s, "mu_fast": f, "rate_s_per_m": 20.0, "displacement_capacity_m": d}
        for (r, d), s, f in zip([(2.1, 0.4), (0.3, 0.05), (0.3, 0.05), (2.1, 0.4)], MU_S, MU_F, strict=True)]},
        DesignError)
    rbar, _, _ = bearing.elements()
    smat = np.linalg.inv(bearing.surface_matrix())
    return smat / rbar[:, None], smat, rbar, bearing.effective_capacities_m.astype(float)


def test_three_sliding_one_between_its_levels_is_found_by_the_grown_set():
    """A state met closing along these rims (h199): surfaces 2 and 3 at µ_fast to rounding, surface 2 between µ_slow
    and µ_fast at ~0.5 m/s; the stall's set and its supersets do not converge from their seeds (refused on
    edf7ccb: 'does not resolve here'); the set grown from the pairs answers — certified by the convex problem's
    conditions with this file's own law."""
    bmat, _, _, caps = lower_bound_tfp_maps()
    ang = np.array([0.5001731855354982, 0.6199205030288358, 0.5788464920912926, 0.6445])
    u = on_rims(ang, caps)
    b = bmat @ u
    xdot = np.array([0.02649932293741722, 0.367698050361364])
    t = np.column_stack((-np.sin(ang), np.cos(ang)))
    r, psi, res, _ = slide_along_rims(xdot, b, u, MU_S, MU_F, A)
    s = np.einsum("ij,ij->i", r[None, :] - b, t)
    on = psi != 0.0
    assert np.count_nonzero(on) == 3 and res < 1e-14 and np.max(np.abs(t.T @ psi - xdot)) < 1e-14
    assert np.max(np.abs(s[on] - np.sign(psi[on]) * mu_forward(np.abs(psi[on]), MU_S[on], MU_F[on], A[on]))) < 1e-15
    assert np.all(np.abs(s[~on]) <= MU_S[~on])
    assert 0.3 < abs(psi[1]) < 0.7 and abs(abs(s[1]) - MU_F[1]) > 1e-9  # the one between its levels


def test_the_closing_along_the_rims_balances_its_energy():
    """The mass carried by four misaligned rims (the review's TFP laws, B and S), under a ground acceleration and a
    damper, integrated for 0.5 ms (rtol 1e-6, ~1 s CPU): the energy booked as the kernel books it (friction g Σ∫(r − b_i)·dū_i) balances the
    input, kinetic, potential and viscous energies (the independent truth: the rims' reactions do no work).  Measured
    (h199, rtol 1e-8, to the first event at 8.9 ms): 2.3e-12 of 1.9e-3 J/kg; the same state turned by 0.9 rad gave
    the turned answer to DOP853's error (t 3.5e-9 s, friction 5.9e-10 of 9.2e-4) — 12 s of CPU, not a test here."""
    bmat, smat, rbar, caps = lower_bound_tfp_maps()
    ang = np.array([0.50, 0.62, 0.58, 0.6445])
    xdot = 0.3 * np.array([-math.sin(0.5), math.cos(0.5)])
    out = planar_rim_slide.close_along_rims(
        0.0, xdot, on_rims(ang, caps), bmat, smat, rbar, MU_S, MU_F, A, 9.80665, 0.3, np.array([0.0, 1.0]),
        np.array([0.5, 0.5]), np.array([-0.5, -0.5]), 0.0005, rtol=1e-6)
    assert out["reason"] == "end" and out["t"] == 0.0005
    # h216: the one change of the sliding set (a held surface reaching its dead zone's edge) located and the
    # integration restarted there: 3.6e-16 of 1.0e-4 at rtol 1e-6 (2.1e-11 with the kink inside a step, on 8e44dd2)
    assert out["set_changes"] == 1
    assert out["friction"] > 5e-5 and abs(out["balance"]) < 1e-10 * out["input"]
    assert out["largest_held"] <= 1.0 and np.allclose(np.hypot(out["u"][:, 0], out["u"][:, 1]), caps, rtol=1e-14)
    # h221: the implicit step (Radau with slide_derivatives' Jacobian, 72 forces against DOP853's 148) on the same
    # closing: the same located change and end to its own error at rtol 1e-6 (measured: u 3.7e-12 m, Ẋ 2.7e-10 m/s,
    # friction 6.5e-8 relative; its balance 4.5e-12 of 1.0e-4 J/kg — Radau's error, not DOP853's)
    imp = planar_rim_slide.close_along_rims(
        0.0, xdot, on_rims(ang, caps), bmat, smat, rbar, MU_S, MU_F, A, 9.80665, 0.3, np.array([0.0, 1.0]),
        np.array([0.5, 0.5]), np.array([-0.5, -0.5]), 0.0005, rtol=1e-6, method="Radau")
    assert imp["reason"] == "end" and imp["set_changes"] == 1 and abs(imp["balance"]) < 1e-6 * imp["input"]
    assert np.max(np.abs(imp["u"] - out["u"])) < 1e-10 and np.max(np.abs(imp["xdot"] - out["xdot"])) < 1e-8
    assert abs(imp["friction"] - out["friction"]) < 1e-6 * out["friction"]


def test_the_slide_derivatives_match_finite_differences():
    """h221: the implicit step's Jacobian — the derivatives of r and ψ in the rims' angles and Ẋ from the forward
    law's saddle system — against central differences of the numpy root (h = 1e-9: within the set, the difference's
    error ~h² plus the rounding of the root × 1/h), on h199's three-sliding state (surfaces 1 and 3 at µ_fast to
    rounding, dψ/dθ ~ 1.5e5 m/s per rad: the slide's stiffness) and a two-sliding one (ψ from the tangents alone).
    Measured: 1.3e-6 (three) of the largest entry."""
    worst = []
    bmat, _, _, caps = lower_bound_tfp_maps()
    # the three-sliding roots cost ~70 ms each (the forward law's grown sets): three columns there — θ_2 (the stiff
    # one), θ_4 (held: through B alone), Ẋ_y; every column of the two-sliding state (~5 ms a root)
    states = [(np.array([0.5001731855354982, 0.6199205030288358, 0.5788464920912926, 0.6445]),
               np.array([0.02649932293741722, 0.367698050361364]), (1, 3, 5)),
              (np.array([0.50, 0.62, 0.58, 0.6445]),
               0.3 * np.array([-math.sin(0.5), math.cos(0.5)]) - 0.02 * np.array([math.cos(0.55), math.sin(0.55)]),
               range(6))]
    for ang, xdot, columns in states:
        u = on_rims(ang, caps)
        r, psi, _, _ = slide_along_rims(xdot, bmat @ u, u, MU_S, MU_F, A)
        dr, dpsi = planar_rim_slide.slide_derivatives(bmat @ u, u, r, psi, bmat, MU_S, MU_F, A)
        h = 1e-9
        for q in columns:
            ends = []
            for sign in (1.0, -1.0):
                aa, xx = ang.copy(), xdot.copy()
                if q < 4:
                    aa[q] += sign * h
                else:
                    xx[q - 4] += sign * h
                uu = on_rims(aa, caps)
                rr, pp, _, _ = slide_along_rims(xx, bmat @ uu, uu, MU_S, MU_F, A)
                ends.append((rr, pp))
            worst.append((np.max(np.abs((ends[0][0] - ends[1][0]) / (2 * h) - dr[:, q])) / (1.0 + np.max(np.abs(dr))),
                          np.max(np.abs((ends[0][1] - ends[1][1]) / (2 * h) - dpsi[:, q])) / np.max(np.abs(dpsi))))
        assert np.all(dpsi[psi == 0.0] == 0.0)
    assert np.max(worst) < 1e-5


def concurrence(ang, caps, bmat, members, sense):
    """The signed concurrence C(θ) = −Σ_i w_i (b_i·t_i + σ_i µ_f,i) of three lines (r − b_i)·t_i = σ_i µ_f,i,
    w = (t_2×t_3, t_3×t_1, t_1×t_2) (Σ w_i t_i = 0, so r drops out): 0 where they meet, computed here alone."""
    t = np.column_stack((-np.sin(ang), np.cos(ang)))[members]
    b = (bmat @ on_rims(ang, caps))[members]
    def cross(p, q):
        return p[0] * q[1] - p[1] * q[0]

    w = np.array([cross(t[1], t[2]), cross(t[2], t[0]), cross(t[0], t[1])])
    return -float(np.sum(w * (np.einsum("ij,ij->i", b, t) + sense * MU_F[members])))


def test_the_saturated_mode_of_pts_slide_is_the_law_s_sliding_mode():
    """h221: PTS's slide along the rims (the review's lower bound, 12.29005 s, 0.15 ms after "all on rims"):
    surfaces 1, 2, 3 at µ_fast beyond the law's resolution, their lines concurrent — the law's root swaps which of
    2 and 3 is a hair below µ_fast on either side (Radau's step collapsed here).  Independent truths: the law's
    own roots (numpy) on either side of the constraint move toward it (a sliding mode) and the saturated rates lie
    between them; the concurrence computed here alone is stationary along the saturated rates (to 1e-6 of its rate
    along the law's); the force is the law's; then 1 ms integrated from there (rtol 1e-8, ~0.4 s CPU): the energy
    balances, the constraint's drift stays below 1e-10, surface 4 leaves its dead zone at 0.806 ms (located)."""
    bmat, smat, rbar, caps = lower_bound_tfp_maps()
    ang = np.array([0.3494470994740643, 0.1970958857924142, 0.19958411314589533, 0.3425063447486146])
    xdot = np.array([0.8638007303187606, 0.06333687617891821])
    members, sense = np.array([0, 1, 2]), np.array([-1.0, 1.0, 1.0])
    u = on_rims(ang, caps)
    r_f, psi_f, residual = planar_rim_slide.saturated_slide(xdot, bmat @ u, u, bmat, [1, 1, 1, 0], sense, MU_S, MU_F, A)
    assert residual < 1e-11 and np.all(sense * psi_f[:3] > 1.5) and psi_f[3] == 0.0
    assert np.max(np.abs(t_of(ang).T @ psi_f - xdot)) < 1e-13

    def drift_rate(psi, h=1e-9):  # dC/dt along θ̇ = ψ/d, by central differences
        return (concurrence(ang + h * psi / caps, caps, bmat, members, sense)
                - concurrence(ang - h * psi / caps, caps, bmat, members, sense)) / (2 * h)

    sides = []
    for shift in (-1e-10, 1e-10):  # surface 3's angle across the constraint: the law's own root on either side
        a3 = ang.copy()
        a3[2] += shift
        us = on_rims(a3, caps)
        r_s, psi_s, _, _ = slide_along_rims(xdot, bmat @ us, us, MU_S, MU_F, A)
        sides.append((concurrence(a3, caps, bmat, members, sense), drift_rate(psi_s), psi_s))
        assert np.max(np.abs(r_s - r_f)) < 1e-8
    (c_a, rate_a, psi_a), (c_b, rate_b, psi_b) = sides
    assert c_a * c_b < 0.0 and rate_a * c_a < 0.0 and rate_b * c_b < 0.0  # both sides move toward C = 0
    alpha = (psi_f[1] - psi_b[1]) / (psi_a[1] - psi_b[1])
    assert 0.0 < alpha < 1.0 and np.max(np.abs(psi_f - (psi_b + alpha * (psi_a - psi_b)))) < 1e-8
    assert abs(drift_rate(psi_f)) < 1e-6 * min(abs(rate_a), abs(rate_b))
    out = planar_rim_slide.close_along_rims(
        0.0, xdot, u, bmat, smat, rbar, MU_S, MU_F, A, 9.80665, 0.0, np.array([0.0, 1.0]),
        np.array([3.27, 3.27 - 29.1]), np.array([1.74, 1.74]), 0.001, rtol=1e-8, method="Radau")
    assert out["reason"] == "end" and [m for _, m in out["modes"]] == [(1, 2, 3), (1, 2, 3)]
    assert out["modes"][1][0] == pytest.approx(0.000806043, abs=1e-9) and out["set_changes"] == 1
    assert abs(out["balance"]) < 1e-8 * out["friction"] and out["drift"] < 1e-10
    assert np.allclose(np.hypot(out["u"][:, 0], out["u"][:, 1]), caps, rtol=1e-14)


def t_of(ang):
    return np.column_stack((-np.sin(ang), np.cos(ang)))
