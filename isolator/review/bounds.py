r"""Property bounds of the friction coefficient: λ_max, λ_min per code.

ASCE/SEI 7-22 17.2.8.4 (Eqs. 17.2-1, 17.2-2; REVIEW_RULES 1.6, [S] P1; f_ae = 0.75 a parameter):

.. math::  \lambda_{max} = (1 + f_{ae}(\lambda_{ae,max} - 1))\,\lambda_{test,max}\,\lambda_{spec,max}
           \lambda_{min} = (1 - f_{ae}(1 - \lambda_{ae,min}))\,\lambda_{test,min}\,\lambda_{spec,min}

EN 1998-2 7.5.2.4 / EN 15129: the plain product of the factors (REVIEW_RULES 2, [U]).
A design may instead give ``lambda_max``/``lambda_min`` or ``mu_upper``/``mu_lower`` directly.
The bounds multiply every friction coefficient of the design (µs, µk, µ_slow, µ_fast).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class FrictionBounds:
    """λ factors and the bounded kinetic friction."""

    lambda_min: float
    lambda_max: float
    mu_lower: float
    mu_nominal: float
    mu_upper: float
    basis: str  #: how the factors were formed

    def as_dict(self) -> dict:
        return {"lambda_min": self.lambda_min, "lambda_max": self.lambda_max, "mu_lower": self.mu_lower,
                "mu_nominal": self.mu_nominal, "mu_upper": self.mu_upper, "basis": self.basis}


def combine_lambda(ae: float, test: float, spec: float, *, side: str, code: str = "asce7-22",
                   f_ae: float = 0.75) -> float:
    """One bound of λ from its three factors.

    Parameters
    ----------
    ae, test, spec : float
        λ_ae, λ_test, λ_spec of that side [-].
    side : {"max", "min"}
    code : {"asce7-22", "en15129"}
    f_ae : float
        ASCE 7-22 17.2.8.4 factor on the aging/environment part [-] (0.75).

    Returns
    -------
    float
    """
    if code == "en15129":
        return ae * test * spec
    if side == "max":
        return (1.0 + f_ae * (ae - 1.0)) * test * spec  # Eq. 17.2-1
    return (1.0 - f_ae * (1.0 - ae)) * test * spec  # Eq. 17.2-2


def friction_bounds(design, *, code: str = "asce7-22", f_ae: float = 0.75) -> FrictionBounds:
    """The λ bounds of a design (nominal only — λ = 1 — when the design gives none).

    Parameters
    ----------
    design : isolator.design.Design
    code : {"asce7-22", "en15129"}
    f_ae : float
        See :func:`combine_lambda` [-].
    """
    f = design.property_factors
    mu = design.mu_kinetic
    if "lambda_ae_max" in f:
        lmax = combine_lambda(f["lambda_ae_max"], f["lambda_test_max"], f["lambda_spec_max"], side="max",
                              code=code, f_ae=f_ae)
        lmin = combine_lambda(f["lambda_ae_min"], f["lambda_test_min"], f["lambda_spec_min"], side="min",
                              code=code, f_ae=f_ae)
        basis = (f"ASCE 7-22 17.2.8.4 Eqs. 17.2-1/-2 with f_ae = {f_ae:g}" if code != "en15129"
                 else "EN 15129 / EN 1998-2 7.5.2.4: plain product of λ factors")
    elif "lambda_max" in f:
        lmax, lmin, basis = f["lambda_max"], f["lambda_min"], "λ_max, λ_min given in the design"
    elif "mu_upper" in f:
        lmax, lmin, basis = f["mu_upper"] / mu, f["mu_lower"] / mu, "µ_upper, µ_lower given in the design"
    else:
        lmax = lmin = 1.0
        basis = "no bounds in the design: nominal properties only (λ = 1)"
    return FrictionBounds(lambda_min=lmin, lambda_max=lmax, mu_lower=lmin * mu, mu_nominal=mu, mu_upper=lmax * mu,
                          basis=basis)
