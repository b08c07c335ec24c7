"""What the record commands share for a pair of components (and a vertical): options, reading, output.

No command lives here: ``simulate`` (:mod:`isolator.cli.records`), ``batch`` and
``report`` use these helpers so that a pair is read, solved and printed the same way
everywhere.  Reading and model errors end the command with one line and exit code 2.
"""

from __future__ import annotations

from isolator.cli.common import error_line, user_error

#: Help texts of the pair and friction options.
PAIR_HELP = {
    "pair": "Second horizontal component (Y) from another file: a coupled 2-D analysis of both components.",
    "vertical": "Vertical component (Z, up positive) from another file: the normal force n = g + a_z "
                "(and κ = n/R for a pendulum given by --radius-m).",
    "component": "Component to read from a multi-component file: channel code (HNE), its last letter (E), "
                 "orientation (180, Up, NS), axis letter (N, E, Z) or trace id; or 'pair' (its two "
                 "horizontal components, a 2-D analysis) or 'all' (with the vertical).",
    "trim": "Cut components of different lengths or start times to their common window (recorded in "
            "'processing').",
    "resample": "Put components that differ in time step (or anything else) on the union of their sample "
                "times over their common window: the same piecewise-linear signals, nothing approximated "
                "(recorded in 'processing').",
    "mu_slow": "Velocity-dependent friction µ(v) = µ_fast − (µ_fast − µ_slow) exp(−a|v|): µ at low velocity "
               "(with --mu-fast and --rate-s-per-m; the 2-D engine).",
    "mu_fast": "Velocity-dependent friction: µ at high velocity.",
    "rate": "Velocity-dependent friction: the rate a [s/m].",
    "radius": "Radius of a friction pendulum R [m]: κ = g/R, or κ(t) = n(t)/R with a vertical component "
              "(instead of --stiffness-per-mass).",
}

def wants_set(pair: str | None, vertical: str | None, component: str | None) -> bool:
    """True when the command reads more than one component (a pair, a vertical, or 'pair'/'all')."""
    return pair is not None or vertical is not None or (component or "").lower() in ("pair", "all")


def load_motion_set_for_cli(record, pair=None, vertical=None, component=None, units=None, merge=False,
                            dt_s=None, response=None, counts_factor=None, trim=False, resample=False):
    """Read the components of an analysis; a bad file or a mismatch ends the command (one line, exit 2).

    Returns
    -------
    isolator.motion.MotionPair
    """
    from isolator.errors import ComponentMismatchError, RecordError, UnitsError
    from isolator.motion import read_ground_motion_pair

    try:
        return read_ground_motion_pair(record, pair, vertical, component=component, units=units, merge=merge,
                                       response=response, counts_factor=counts_factor, dt_s=dt_s, trim=trim,
                                       resample=resample)
    except ComponentMismatchError as err:  # the message names each component's file
        user_error(f"{record}: {error_line(err)}")
    except (RecordError, UnitsError) as err:
        user_error(error_line(err))


def system_keywords(*, mu_s, mu_k=None, stiffness_per_mass=0.0, damping_per_mass=0.0, gravity=None,
                    radius_m=None, mu_slow=None, mu_fast=None, rate_s_per_m=None) -> dict:
    """The friction-isolator keywords of :func:`isolator.solver.models.simulate_motion` from the options."""
    if radius_m is not None and stiffness_per_mass:
        user_error("give either --radius-m (a pendulum) or --stiffness-per-mass, not both")
    velocity = [mu_slow, mu_fast, rate_s_per_m]
    if any(v is not None for v in velocity) and not all(v is not None for v in velocity):
        user_error("velocity-dependent friction needs --mu-slow, --mu-fast and --rate-s-per-m together")
    keywords = {"mu_static": mu_s, "mu_kinetic": mu_k, "stiffness_per_mass": stiffness_per_mass,
                "damping_per_mass": damping_per_mass, "gravity_m_s2": gravity, "radius_m": radius_m,
                "mu_slow": mu_slow, "mu_fast": mu_fast, "rate_s_per_m": rate_s_per_m}
    return {key: value for key, value in keywords.items() if value is not None}


def solve(record_label: str, x, y=None, z=None, *, dt_s: float, time_s=None, system: dict, design=None,
          files=()):
    """Run :func:`~isolator.solver.models.simulate_motion` (the model the scene needs); errors end the command.

    ``files``: the record's files (X, then the --pair and --vertical ones; default ``record_label``).  An engine's
    refusal (a rim it does not model, its step-size floor, lift-off, its work bound: :class:`SolverError`) and a
    design the engine refuses (:class:`InvalidSystemError`) end it in one line naming the design file and the
    record's files (:func:`refusal_line`).
    """
    from isolator.errors import InvalidSystemError, RecordInputError, SolverError
    from isolator.solver.models import simulate_motion

    try:
        return simulate_motion(x, y, z, dt_s, time_s=time_s, design=design, **system)
    except RecordInputError as err:
        user_error(f"{record_label}: {err}")
    except (InvalidSystemError, SolverError) as err:
        if design is None and isinstance(err, InvalidSystemError):  # the isolator options' own numbers
            user_error(str(err))
        user_error(refusal_line(err, files or record_label, design))


def refusal_line(err, files, design=None) -> str:
    """An analysis' refusal as the command line shows it: ``DESIGN under X + Y + Z: what and when``.

    The one place the commands (``simulate``, ``report``) turn an engine's refusal into their line: the engines
    name the instant (``reaches its rim at t = 0.3795 s``), this names the files the user ran (session 14).
    """
    from isolator.errors import analysis_owner, owned

    source = getattr(design, "source", None)
    return owned(analysis_owner(files, source), err, source)


def history_columns(result) -> tuple[str, list]:
    """CSV header and columns of the time histories of a 1-D or a 2-D response."""
    if result.displacement_m.ndim == 1:
        return ("time_s,ground_acceleration_m_s2,displacement_m,velocity_m_s,absolute_acceleration_m_s2",
                [result.time_s, result.ground_acceleration_m_s2, result.displacement_m, result.velocity_m_s,
                 result.absolute_acceleration_m_s2])
    names = ["time_s", "ground_acceleration_x_m_s2", "ground_acceleration_y_m_s2"]
    columns = [result.time_s, result.ground_acceleration_m_s2[:, 0], result.ground_acceleration_m_s2[:, 1]]
    if result.vertical_acceleration_m_s2 is not None:
        names.append("ground_acceleration_z_m_s2")
        columns.append(result.vertical_acceleration_m_s2)
    for quantity in ("displacement_m", "velocity_m_s", "absolute_acceleration_m_s2"):
        stem, unit = quantity.split("_m", 1)
        values = getattr(result, quantity)
        names += [f"{stem}_x_m{unit}", f"{stem}_y_m{unit}"]
        columns += [values[:, 0], values[:, 1]]
    return ",".join(names), columns


def result_rows(result, summary: dict) -> list[tuple[str, str, str]]:
    """Table rows (name, value, unit) of a 1-D or 2-D response, the model first."""
    duration_s = float(result.time_s[-1] - result.time_s[0])
    rows = [
        ("model", summary["model"], f"({summary['model_reason']})"),
        ("peak displacement", f"{summary['peak_displacement_m']:.6g}", "m (resultant)"),
        ("residual displacement", f"{summary['residual_displacement_m']:.6g}",
         f"m  (x {summary['residual_displacement_x_m']:.6g}, y {summary['residual_displacement_y_m']:.6g})"),
        ("peak velocity", f"{summary['peak_velocity_m_s']:.6g}", "m/s"),
        ("peak transmitted acc.", f"{summary['peak_transmitted_acceleration_m_s2']:.6g}", "m/s²"),
        ("slip time", f"{summary['slip_time_s']:.6g}", f"s  of {duration_s:.6g} s"),
        ("uplift time", f"{summary['uplift_time_s']:.6g}", f"s  ({summary['n_uplifts']} uplift(s))"),
        ("events", f"{summary['n_events']}", ""),
        ("energy input", f"{summary['energy_input_J_per_kg']:.6g}", "J/kg"),
        ("energy friction", f"{summary['energy_friction_J_per_kg']:.6g}", "J/kg"),
        ("energy viscous", f"{summary['energy_viscous_J_per_kg']:.6g}", "J/kg"),
        ("energy balance error", f"{summary['energy_balance_error_J_per_kg']:.2e}", "J/kg"),
        ("solver time", f"{summary['solver_seconds'] * 1e3:.3g}", "ms"),
        ("status", summary["solver_status"], ""),
    ]
    return rows
