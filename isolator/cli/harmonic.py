"""The paper's problem: ``harmonic`` (steady response) and ``threshold`` (regime transitions along α)."""

from __future__ import annotations

import typer

from isolator.cli.common import app, echo_json, echo_table, fmt, user_error


@app.command()
def harmonic(
    alpha: float = typer.Option(..., "--alpha", help="Reduced acceleration α = A0 Ω²/(µs g) (Eq. 6)."),
    k: float = typer.Option(0.0, "--k", help="Dimensionless stiffness k = K A0/(M g)."),
    eta: float = typer.Option(0.0, "--eta", help="Dimensionless damping η = (γ/M) sqrt(A0/g)."),
    mu_s: float = typer.Option(..., "--mu-s", help="Static friction coefficient µs."),
    mu_k: float = typer.Option(None, "--mu-k", help="Kinetic friction coefficient µk ≤ µs (default µs)."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
) -> None:
    """Steady response to a harmonic ground motion: the paper's problem, solved exactly.

    Runs from rest (φ = π/2) until the motion is periodic, or grows linearly at
    resonance, and reports the regime (ST stick, SS stick-slip, SL permanent slip),
    ζ, A, ẋ_rms, the energies per period and the force ratios of Eq. 5.
    """
    from isolator.errors import InvalidSystemError
    from isolator.metrics import REGIME_WORDS
    from isolator.solver.harmonic import harmonic_response

    try:
        response = harmonic_response(alpha, k, eta, mu_s, mu_k)
    except InvalidSystemError as err:
        user_error(str(err))
    summary = response.summary()
    if as_json:
        echo_json(summary)
        return
    echo_table([
        ("configuration", response.configuration, f"(k = {k:g}, η = {eta:g}, µs = {mu_s:g}, µk = {response.mu_k:g})"),
        ("regime", response.regime, f"({REGIME_WORDS[response.regime]})"),
        ("steady", str(response.steady), f"({response.status}, cycle of {response.cycle_periods} period(s), "
                                         f"{response.periods_run} periods run)"),
        ("zeta", f"{response.zeta:.6g}", "slip time / period (Eq. 3)"),
        ("amplitude A", f"{response.amplitude:.6g}", "half peak-to-peak of x = X/A0"
                                                     + ("  (> 1: ground motion amplified)" if response.amplitude > 1 else "")),
        ("xdot_rms", f"{response.xdot_rms:.6g}", "(Eq. 4)"),
        ("energy_friction", f"{response.energy_friction:.6g}", "∆e_f per period (Eq. 9)"),
        ("energy_viscous", f"{response.energy_viscous:.6g}", "∆e_v per period (Eq. 10)"),
        ("work_input", f"{response.work_input:.6g}", "∆w_i per period (Eq. 11)"),
        ("balance residual", f"{response.energy_balance_residual:.2e}", "∆e_f + ∆e_v + ∆w_i (Eq. 8)"),
        ("rho_ev", fmt(response.rho_ev), "elastic/viscous (Eq. 5)"),
        ("rho_vf", fmt(response.rho_vf), "viscous/friction"),
        ("rho_ef", fmt(response.rho_ef), "elastic/friction"),
        ("dominant force", response.dominant_force, ""),
        ("growth rate β", fmt(response.growth_rate), "dA/dt at resonance (Eq. 26)"),
    ])


@app.command()
def threshold(
    k: float = typer.Option(0.0, "--k", help="Dimensionless stiffness k."),
    eta: float = typer.Option(0.0, "--eta", help="Dimensionless damping η."),
    mu_s: float = typer.Option(..., "--mu-s", help="Static friction coefficient µs."),
    mu_k: float = typer.Option(None, "--mu-k", help="Kinetic friction coefficient µk ≤ µs (default µs)."),
    alpha_max: float = typer.Option(6.0, "--alpha-max", help="Upper end of the α scan."),
    grid: int = typer.Option(120, "--grid", min=4, help="Grid points of the α scan before bisection."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object instead of a table."),
) -> None:
    """Regime thresholds along α: α_SS = 1, α_SL and every transition up to --alpha-max."""
    from isolator.errors import InvalidSystemError
    from isolator.solver.thresholds import harmonic_thresholds

    try:
        result = harmonic_thresholds(k, eta, mu_s, mu_k, alpha_max=alpha_max, n_grid=grid)
    except InvalidSystemError as err:
        user_error(str(err))
    if as_json:
        echo_json(result.summary())
        return
    rows = [("alpha_ss", f"{result.alpha_ss:g}", "(stick below)"),
            ("alpha_sl", fmt(result.alpha_sl, ".9g"),
             f"(permanent slip from here up to α = {alpha_max:g})" if result.alpha_sl else
             f"(not permanent slip at α = {alpha_max:g})")]
    rows += [("transition", f"{tr['alpha']:.9g}", f"{tr['from']} → {tr['to']}") for tr in result.transitions]
    echo_table(rows)
