"""The ELF rows of a triple friction pendulum against Fenz & Constantinou's closed forms (issue 23), written here.

Fenz & Constantinou (2008), Earthquake Engng Struct. Dyn. 37, 163–183: for µ2 = µ3 < µ1 < µ4 and effective radii
R̄_i = R_i − h_i the backbone F/W(u) from rest is piecewise linear —

* regime I (sliding on 2 and 3): F/W = µ2 + u/(R̄2 + R̄3), up to u* = (µ1 − µ2)(R̄2 + R̄3), F/W = µ1;
* regime II (1 and 3): slope 1/(R̄1 + R̄3), up to u** = u* + (µ4 − µ1)(R̄1 + R̄3), F/W = µ4;
* regime III (1 and 4): slope 1/(R̄1 + R̄4), until slider 1 reaches its rim, F/W = µ1 + d1*/R̄1 with
  d_i* = d_i R̄_i/R_i;

and the ultimate displacement (every slider on its rim) is Σ d_i*.  The bearing is a series of rigid-plastic
elements with linear hardening, so its cycles follow Masing's rule: the loop between ±D has the backbone's F(D) at
its tips and the area E_D = 8 W ∫₀ᴰ f − 4 W D f(D) (f = F/W of the backbone), exact for a piecewise-linear f.
From these, without calling the bearing's code: K_M = W f(D)/D, T_M = 2π √(D/(g f(D))), β_M = E_D/(2π K_M D²),
and D_M the fixed point D = g S_a(T_M) T_M²/(4π² B_M(β_M)) (ASCE 7-22 17.5.3, B_M of Table 17.5-1 and the
two-period S_a of 11.4.5.1 as in REVIEW_RULES 1.1 / 1.9, both written here).  λ multiplies every µ_i of a bound.
The test's design keeps D_M inside regime III at both bounds (below every rim: h32 owns the 2-D rims).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from isolator.design import Design
from isolator.review.codes import asce7_22
from isolator.review.target import two_period_target

G = 9.80665
S_MS, S_M1, T_L = 1.5, 0.9, 8.0
#: surfaces 1 … 4 (outer-bottom first): R, h, µ, d
SURFACES = [(2.2, 0.15, 0.06, 0.40), (0.4, 0.08, 0.02, 0.06), (0.4, 0.08, 0.02, 0.06), (2.2, 0.15, 0.10, 0.40)]
MASS_KG = 1.0e6
B_TABLE = ((0.02, 0.8), (0.05, 1.0), (0.10, 1.2), (0.20, 1.5), (0.30, 1.7), (0.40, 1.9), (0.50, 2.0))


def _design() -> Design:
    return Design.from_mapping({"name": "tfp by hand", "mass_kg": MASS_KG, "bearing": {"type": "triple", "surface": [
        {"radius_m": r, "height_m": h, "mu": mu, "displacement_capacity_m": d} for r, h, mu, d in SURFACES]}})


def _backbone(lam: float):
    """Vertices (u [m], F/W [-]) of Fenz & Constantinou's regimes I–III at friction × lam, and the end of III."""
    rb = [r - h for r, h, _, _ in SURFACES]
    mu = [m * lam for _, _, m, _ in SURFACES]
    d1 = SURFACES[0][3] * rb[0] / SURFACES[0][0]
    u1 = (mu[0] - mu[1]) * (rb[1] + rb[2])
    u2 = u1 + (mu[3] - mu[0]) * (rb[0] + rb[2])
    f3 = mu[0] + d1 / rb[0]
    u3 = u2 + (f3 - mu[3]) * (rb[0] + rb[3])
    return np.array([0.0, u1, u2, u3]), np.array([mu[1], mu[0], mu[3], f3])


def _f(u: float, lam: float) -> float:
    x, f = _backbone(lam)
    assert 0 < u <= x[-1], "the test stays within regimes I–III"
    return float(np.interp(u, x, f))


def _integral(d: float, lam: float) -> float:
    """∫₀ᴰ f(s) ds [m], exact for the piecewise-linear backbone (trapezoids between its vertices)."""
    x, f = _backbone(lam)
    points = np.concatenate([x[x < d], [d]])
    values = np.interp(points, x, f)  # f(0) = µ2: the backbone starts sliding at µ2 W
    return float(np.sum(0.5 * (values[1:] + values[:-1]) * np.diff(points)))


def _loop(d: float, lam: float) -> tuple[float, float, float]:
    """(T_M [s], β_M [-], f(D) [-]) of the Masing loop between ±D."""
    f = _f(d, lam)
    energy_per_weight = 8.0 * _integral(d, lam) - 4.0 * d * f
    return 2 * math.pi * math.sqrt(d / (G * f)), energy_per_weight / (2 * math.pi * f * d), f


def _sa(t: float) -> float:
    t0, ts = 0.2 * S_M1 / S_MS, S_M1 / S_MS
    if t < t0:
        return S_MS * (0.4 + 0.6 * t / t0)
    if t <= ts:
        return S_MS
    return S_M1 / t if t <= T_L else S_M1 * T_L / t ** 2


def _b_m(beta: float) -> float:
    betas, values = zip(*B_TABLE, strict=True)
    return float(np.interp(beta, betas, values))


def _d_m(lam: float) -> float:
    x, _ = _backbone(lam)

    def gap(d):
        t, beta, _ = _loop(d, lam)
        return G * _sa(t) * t * t / (4 * math.pi ** 2 * _b_m(beta)) - d

    lo, hi = x[2] * (1 + 1e-9), x[3] * (1 - 1e-9)  # regime III
    assert gap(lo) > 0 > gap(hi), "the design keeps D_M inside regime III"
    return brentq(gap, lo, hi, xtol=1e-15, rtol=1e-14)


@pytest.mark.parametrize("lam", [0.8, 1.0, 1.3])
def test_triple_pendulum_elf_rows_from_the_closed_forms(lam):
    design = _design().with_friction_factor(lam, f"λ = {lam}")
    # λ on every µ_i of the bound
    assert [s.mu_kinetic for s in design.bearing.surfaces] == pytest.approx([m * lam for _, _, m, _ in SURFACES],
                                                                           rel=1e-15)
    elf = asce7_22.elf_displacement(design, design.mu_kinetic, two_period_target(S_MS, S_M1, T_L))
    d = _d_m(lam)
    t, beta, f = _loop(d, lam)
    assert elf["D_M_m"] == pytest.approx(d, rel=1e-10)
    assert elf["T_M_s"] == pytest.approx(t, rel=1e-10)
    assert elf["beta_M"] == pytest.approx(beta, rel=1e-10)
    assert elf["B_M"] == pytest.approx(_b_m(beta), rel=1e-10)
    assert elf["V_b_over_W"] == pytest.approx(f, rel=1e-10)  # k_M D_M / W = F(D_M)/W, the loop's tip
    assert elf["k_M_N_per_m"] == pytest.approx(MASS_KG * G * f / d, rel=1e-10)
    assert any("regime III" in note for note in elf["notes"])
    # 17.2.4.4 on the backbone: F(D) − F(D/2) per unit weight
    assert asce7_22.restoring_force_ratio(design, d) == pytest.approx(f - _f(0.5 * d, lam), rel=1e-12)
    # 17.5.4.3(3): the force that fully activates the bearing, where regime III (surfaces 1 and 4) begins: µ4 λ;
    # the breakaway: µ2 λ
    assert asce7_22.activation_force_per_weight(design) == pytest.approx(0.10 * lam, rel=1e-14)
    assert asce7_22.breakaway_force_per_weight(design) == pytest.approx(0.02 * lam, rel=1e-14)


def test_triple_pendulum_capacity_is_the_ultimate_displacement():
    """The review's displacement capacity of a triple pendulum is Σ d_i R̄_i/R_i (every slider on its rim)."""
    design = _design()
    ultimate = sum(d * (r - h) / r for r, h, _, d in SURFACES)
    assert design.displacement_capacity_m == pytest.approx(ultimate, rel=1e-14)
    assert asce7_22.ultimate_displacement_m(design) == pytest.approx(ultimate, rel=1e-14)


def test_masing_area_of_the_single_pendulum_is_4_mu_w_d():
    """The loop formula of this file on one surface (f = µ + u/R) gives E_D = 4 µ W D: the check of the check."""
    mu, r, d = 0.05, 2.5, 0.3
    integral = mu * d + d * d / (2 * r)
    assert 8 * integral - 4 * d * (mu + d / r) == pytest.approx(4 * mu * d, rel=1e-14)
