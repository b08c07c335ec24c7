"""What every command shares: the Typer app, record options, one-line errors, tables, JSON.

Library errors say what is wrong with a file or a value; the commands turn them into
one line on stderr and exit code 2 (:func:`user_error`), never a traceback.
"""

from __future__ import annotations

import sys
import warnings
from contextlib import contextmanager

import typer
from typer.core import TyperGroup

from isolator.errors import IsolatorError, one_line, printable

try:  # typer ≥ 0.20 carries its own copy of click: its exceptions are not click's
    from typer._click import exceptions as click_exceptions
except ImportError:  # pragma: no cover - older typer over click
    from click import exceptions as click_exceptions


def say(line: str) -> None:
    """Print a note (``note: …``, ``lost: …``) on stderr, as :func:`printable` shows it."""
    typer.echo(printable(line), err=True)


def usage_line(err) -> str:
    """One line for a usage mistake: ``error: … (see 'isolator CMD --help')``."""
    message = printable(one_line(err.format_message()))
    context = getattr(err, "ctx", None)
    command = context.command_path if context is not None else "isolator"
    hint = f" (see '{command} --help')" if isinstance(err, click_exceptions.UsageError) else ""
    return f"error: {message}{hint}"


_FREEZE_REGISTERED = False


def skip_final_collection() -> None:
    """Spare the process the garbage collector's last pass over everything it leaves behind.

    A command loads numba's typing tables, obspy and matplotlib (a few hundred thousand
    objects); when the interpreter exits, its final full collection walks them all, ~0.3 s
    of a 3 s report.  ``gc.freeze()`` run from ``atexit`` (before that pass) moves them to
    the permanent generation, which the pass skips; memory goes back to the system with
    the process.  Nothing is lost: Python never promised to finalize objects that live
    until exit, and isolator closes every output before a command returns.  Registered
    once; in a long-lived process (tests) it only runs at its exit.
    """
    global _FREEZE_REGISTERED
    if not _FREEZE_REGISTERED:
        import atexit
        import gc

        atexit.register(gc.freeze)
        _FREEZE_REGISTERED = True


@contextmanager
def collector_skips_existing_objects():
    """Inside the block, the garbage collector does not walk the objects that exist on entry.

    Rendering a report creates and drops hundreds of thousands of matplotlib objects; each
    full collection they trigger would also walk everything loaded before (numba, obspy,
    the analysis), ~0.2 s of a report in all.  Those are frozen (``gc.freeze``) for the
    block and handed back to the collector after it (``gc.unfreeze``); objects made inside
    the block are collected as usual.  A process that froze objects itself is left alone.
    """
    import gc

    if gc.get_freeze_count():
        yield
        return
    gc.freeze()
    try:
        yield
    finally:
        gc.unfreeze()


@contextmanager
def terminate_as_interrupt():
    """While a command runs, SIGTERM (``kill``, a batch system's time limit) ends it as Ctrl-C does.

    SIGTERM's default ended the process at once: no line said so, and no ``finally`` ran (a review's
    ``r.pdf.lock`` stayed behind; session 18 sweep).  Now it raises :class:`KeyboardInterrupt` in the command's
    own process, so the output lock and the temporary files go, the finished work stays in the caches, and the
    command says ``interrupted`` in one line (exit 130).  A forked worker that inherits the handler dies as
    SIGTERM meant (its parent's death sends it one); a SIGTERM ignored by the caller stays ignored.
    """
    import os
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread() or \
            signal.getsignal(signal.SIGTERM) is signal.SIG_IGN:
        yield
        return
    owner = os.getpid()

    def on_terminate(signum, frame):
        if os.getpid() != owner:
            signal.signal(signal.SIGTERM, signal.SIG_DFL)
            os.kill(os.getpid(), signal.SIGTERM)
            return
        raise KeyboardInterrupt

    previous = signal.signal(signal.SIGTERM, on_terminate)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


class OneLineErrors(TyperGroup):
    """The command group: usage mistakes are one line and exit 2, and no Python warning
    reaches stderr.

    Typer prints click's usage errors (unknown flag, missing option, ``--jobs 0``,
    ``--dt abc``) as a framed box of several lines; here every one becomes
    ``error: … (see 'isolator CMD --help')``.  Warnings of numpy, obspy, matplotlib … are
    silenced for the whole run (forked workers inherit the filter): where one matters, the
    command says so in a sentence of its own.
    """

    def invoke(self, ctx):
        """A command interrupted (Ctrl-C, SIGTERM) says so in one line, exit 130: typer turned the interrupt into
        a silent exit 130 (`review` killed mid-run printed nothing; session 18 sweep); `batch` and `design` say
        where their finished work is kept before this."""
        try:
            return super().invoke(ctx)
        except KeyboardInterrupt:
            typer.echo("interrupted: outputs are written whole or not at all; run the same command again (a review "
                       "reuses the analyses it finished from its cache)", err=True)
            raise typer.Exit(130) from None

    def main(self, args=None, prog_name=None, complete_var=None, standalone_mode=True, **extra):
        skip_final_collection()
        # matplotlib logs its own warnings (not Python warnings): an MPLCONFIGDIR it cannot write printed two lines
        # ("mkdir -p failed …", "Matplotlib created a temporary cache directory …") on stderr before a figure
        # written correctly (session 16 sweep); its errors still show
        import logging  # here, not at import: logging registers an exit callback (tests/cli/test_exit.py)

        logging.getLogger("matplotlib").setLevel(logging.ERROR)
        with warnings.catch_warnings(), terminate_as_interrupt():
            warnings.simplefilter("ignore")
            try:
                result = super().main(args=args, prog_name="isolator", complete_var=complete_var,
                                      standalone_mode=False, **extra)
            except click_exceptions.NoArgsIsHelpError as err:
                if not standalone_mode:
                    raise
                typer.echo(err.format_message(), err=True)  # `isolator` alone: the help, as click prints it
                sys.exit(err.exit_code)
            except click_exceptions.ClickException as err:
                if not standalone_mode:
                    raise
                typer.echo(usage_line(err), err=True)
                sys.exit(err.exit_code if isinstance(err, click_exceptions.UsageError) else 2)
            except typer.Abort:
                if not standalone_mode:
                    raise
                typer.echo("interrupted", err=True)
                sys.exit(130)
            except OSError as err:
                # standard output that cannot take the answer (a full disk, /dev/full, a closed pipe): a traceback
                # before (`isolator harmonic … > /dev/full`, session 17 sweep); any other OSError keeps its own
                if not standalone_mode or not stdout_write_failed(err):
                    raise
                typer.echo(f"error: standard output: cannot write ({err.strerror or err})", err=True)
                sys.exit(2)
            except Exception as err:
                # a typed error of the library that a command did not turn into its own line: still
                # one line and exit 2, never a traceback (a bug, any other type, keeps its traceback)
                if not standalone_mode or not isinstance(err, IsolatorError):
                    raise
                typer.echo(f"error: {printable(one_line(error_line(err)))}", err=True)
                sys.exit(2)
        if not standalone_mode:
            return result
        sys.exit(result if isinstance(result, int) else 0)


def stdout_write_failed(err: OSError) -> bool:
    """True if ``err`` was raised writing a command's answer to standard output (click's ``echo`` without
    ``err=True``); then standard output is pointed at the null device, so that the interpreter's own flush at exit
    does not print a second error."""
    import os

    frame = None
    trace = err.__traceback__
    while trace is not None:  # bounded by the traceback's depth
        if trace.tb_frame.f_code.co_name == "echo" and trace.tb_frame.f_locals.get("err") is False:
            frame = trace.tb_frame
        trace = trace.tb_next
    if frame is None:
        return False
    try:
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, sys.stdout.fileno())
        os.close(null)
    except (OSError, ValueError, AttributeError):  # no file descriptor (tests' captured output)
        pass
    return True


app = typer.Typer(
    cls=OneLineErrors,
    add_completion=False,
    no_args_is_help=True,
    pretty_exceptions_enable=False,
    help="Exact analysis of friction isolators (friction + spring + dashpot) under ground motion.",
)


@app.callback()
def _main() -> None:
    """isolator: friction isolators under harmonic and recorded ground motion."""
    check_cache_variable()
    check_numba_threads_variable()
    from isolator.solver import notice

    notice.ENABLED = True  # a first run that compiles an engine says so on stderr (not a hang)


def check_cache_variable() -> None:
    """Refuse a relative ``ISOLATOR_CACHE_DIR`` in one line, before any command runs.

    The regime maps, the batch key (which checks a batch's earlier rows) and, where the package's folder is
    read-only, the compiled engines live under it: a relative name made a new cache folder in every working
    folder a command ran from (session 16 and 17 sweeps), a fresh key and map cache each, and a Dask worker
    resolves it in its own working folder.  Empty is the default (``~/.cache/isolator``), as before.
    """
    import os

    value = os.environ.get("ISOLATOR_CACHE_DIR")
    if value and not os.path.isabs(value):
        user_error(f"ISOLATOR_CACHE_DIR={value} is a relative path: the cache would be a new folder in each working "
                   f"folder; give an absolute one (e.g. {os.path.abspath(value)}) or unset it for ~/.cache/isolator")


def check_numba_threads_variable() -> None:
    """Refuse a ``NUMBA_NUM_THREADS`` that is not a whole number ≥ 1 in one line, before any command runs.

    numba reads it when first imported: 0 and -1 were a 61-line traceback (``ValueError: Number of threads
    specified must be > 0``) from every command that runs a solver, and a text (``abc``) was dropped for all the
    cores without a word (session 24 sweep).  Empty is unset, as numba reads it.
    """
    import os

    value = os.environ.get("NUMBA_NUM_THREADS", "")
    if not value.strip():
        return
    try:
        threads = int(value)
    except ValueError:
        threads = 0
    if threads < 1:
        user_error(f"NUMBA_NUM_THREADS={value} is not a whole number of threads ≥ 1 (numba's thread pool): give one, "
                   "or unset it for every core")


def refuse_record_flags_for_a_suite_file(suite_args, units, trim) -> None:
    """``--units`` and ``--trim`` serve records given to ``--suite`` (``review``, ``design``); a SUITE.toml states
    its own (``units``, ``trim`` of the file or a pair), and with one they were dropped without a word (session 24
    sweep)."""
    suite_file = next((str(a) for a in suite_args if str(a).lower().endswith(".toml")), None)
    given = [flag for flag, value in (("--units", units), ("--trim", trim)) if value]
    if suite_file is not None and given:
        user_error(f"{' and '.join(given)} {'serves' if len(given) == 1 else 'serve'} record files and folders given to --suite, not a SUITE.toml "
                   f"({suite_file}), which states its own: write 'units = …' or 'trim = true' in it (for the suite "
                   "or a pair)")


#: Help texts of the record options, shared by every command that reads a record.
RECORD_HELP = {
    "component": "Component to read from a multi-component file: channel code (HNE), its last "
    "letter (E), orientation (180, Up, NS), axis letter (N, E, Z) or trace id.",
    "units": "Units of the values for formats that do not state them: g, m/s2, gal or cm/s2.",
    "merge": "Join segments of a channel that has gaps, filling gaps by linear interpolation "
    "(otherwise a gap is an error).",
    "dt": "Time step of a one-column text record, in seconds.",
    "response": "StationXML file: remove the instrument response (records in counts).",
    "counts_factor": "Units (see --units) per count, for records in counts.",
}


#: The command-line option of each library parameter an error can name (``IsolatorError.parameter``).
PARAMETER_FLAGS = {"units": "--units", "dt_s": "--dt", "component": "--component", "merge": "--merge",
                   "counts_factor": "--counts-factor", "response": "--response", "grid": "--grid",
                   "scheduler": "--scheduler", "output": "--output"}


def flag_hint(err) -> str:
    """What to do on the command line about a typed library error, by its type ("" if nothing).

    The library says what is wrong with the file; this says which option fixes it.
    """
    from isolator import errors

    given = getattr(err, "given", None)
    hints = {
        errors.MissingUnitsError: "pass --units (g, m/s2, gal, cm/s2)",
        errors.UnitsConflictError: f"--units says {given}: drop it to use the file's units",
        errors.MissingTimeStepError: "give the time step with --dt",
        errors.TimeStepConflictError: f"--dt says {given:g} s: drop it to use the file's time step"
        if isinstance(given, (int, float)) else "drop --dt to use the file's time step",
        errors.ComponentMismatchError: "pass --resample to put them on the union of their sample times"
        if getattr(err, "kind", "") == "dt" else "pass --trim to cut them to their common window (or --resample)",
        errors.ComponentError: {  # by what the error concerns: X's component, the --pair or the --vertical file
            "component": "choose one with --component (or give the full trace id)",
            "second_file": "give --pair a file of one component, or read the pair from that file alone with "
                           "--component pair",
            "vertical": "give --vertical a file of one component, or a file with one vertical channel",
        }.get(getattr(err, "parameter", "component"), ""),
        errors.GapsError: "pass --merge to join the segments, filling gaps by linear interpolation",
        errors.CountsError: "give the instrument response with --response, or --counts-factor with --units",
        errors.InstrumentResponseError: "check the StationXML file given with --response",
    }
    for kind, hint in hints.items():
        if isinstance(err, kind):
            return hint
    flag = PARAMETER_FLAGS.get(getattr(err, "parameter", ""), "")
    return f"check {flag}" if flag else ""


def error_line(err) -> str:
    """A typed library error as the command line shows it: its message, then the option that fixes it."""
    hint = flag_hint(err)
    return f"{err}; {hint}" if hint else str(err)


def load_record_for_cli(
    path,
    component: str | None = None,
    units: str | None = None,
    merge: bool = False,
    dt_s: float | None = None,
    response=None,
    counts_factor: float | None = None,
):
    """Read a record for a command; a bad record ends the command with one line and exit code 2.

    Parameters are those of :func:`isolator.motion.read_ground_motion`.

    Returns
    -------
    isolator.motion.GroundMotion
        The acceleration in m/s² with its metadata.
    """
    from isolator.errors import RecordError, UnitsError
    from isolator.motion import read_ground_motion

    try:
        return read_ground_motion(
            path, component=component, units=units, merge=merge, dt_s=dt_s,
            response=response, counts_factor=counts_factor,
        )
    except (RecordError, UnitsError) as err:
        user_error(error_line(err))


def echo_json(value) -> None:
    """Print ``value`` as one line of strict JSON (NaN and ±inf as null)."""
    from isolator.serialize import dumps

    typer.echo(dumps(value))


def echo_table(rows) -> None:
    """Print (name, value, unit) rows aligned, one per line."""
    width = max(len(name) for name, _, _ in rows)
    for name, value, unit in rows:
        typer.echo(printable(f"{name:<{width}}  {value} {unit}".rstrip()))


def user_error(message: str) -> None:
    """End the command with one line on stderr and exit code 2."""
    typer.echo(f"error: {printable(one_line(message))}", err=True)
    raise typer.Exit(2)


def check_pdf_output(output: str) -> None:
    """End the command with one line unless ``--output`` names a PDF file (``report``, ``review``, ``design``).

    ``-o .pdf`` (a name that is its extension alone: to Python a hidden file of no suffix) was told
    "--output must end with .pdf, got .pdf" (session 23 sweep).
    """
    from pathlib import Path

    if Path(output).name.lower() == ".pdf":
        user_error(f"--output {output} names no file: give a name before .pdf (e.g. review.pdf)")
    if Path(output).suffix.lower() != ".pdf":
        user_error(f"--output must end with .pdf, got {output}")


def parse_set(items) -> dict:
    """``--set NAME=VALUE`` options as {name: value text} (``review``, ``report``); one line and exit 2 otherwise."""
    out = {}
    for item in items or ():
        if "=" not in item:
            user_error(f"--set {item}: expected NAME=VALUE")
        name, value = (part.strip() for part in item.split("=", 1))
        if name in out and out[name] != value:  # the last one won without a word (session 14 sweep)
            user_error(f"--set {name} is given twice ({out[name]!r} and {value!r}): give it once")
        out[name] = value
    return out


def check_static_friction(value, flag: str = "--mu-s") -> None:
    """Refuse µs = 0 given on the command line (one line naming ``flag``, exit 2).

    A design file's ``mu_static`` must be > 0, and ``harmonic`` and ``threshold`` define α
    relative to µs g; a 0 on the command line is the same mistake (no friction isolator at
    all), not a frictionless isolator to run without a word (issue 26).  Negative, non-finite
    and ≥ 1 values are refused by :class:`isolator.solver.system.System`.
    """
    if value is not None and value == 0.0:
        user_error(f"{flag} 0 is no friction at all: a friction isolator needs µs > 0, as a design file's "
                   "mu_static (sliding isolators have 0.02-0.15)")


def check_given_scale_factors(suite) -> None:
    """Refuse a SUITE.toml ``scale_factor`` that takes its pair's PGA outside [1e-6, 50] g (``--scale-to-pga``'s
    range): a factor of 1e300 was analysed and its spectrum "passed" 1.5e299 × the target (session 10 sweep)."""
    from isolator.errors import ReviewError
    from isolator.motion import MAX_ABS_ACCELERATION_G
    from isolator.motion.ground_motion import MIN_TARGET_PGA_G
    from isolator.units import STANDARD_GRAVITY

    for pair in suite.pairs:
        if pair.scale_factor is not None:
            pga_g = pair.pga_m_s2 / STANDARD_GRAVITY
            if not MIN_TARGET_PGA_G <= pair.scale_factor * pga_g <= MAX_ABS_ACCELERATION_G:
                raise ReviewError(f"{suite.source}: pair '{pair.name}': scale_factor = {pair.scale_factor:g} takes "
                                  f"its PGA of {pga_g:.4g} g to {pair.scale_factor * pga_g:.4g} g, outside "
                                  f"[{MIN_TARGET_PGA_G:g}, {MAX_ABS_ACCELERATION_G:g}] g")


def check_outputs(outputs, inputs, *, streams=()) -> None:
    """Before any work: refuse outputs that resolve to an input or are not regular files.

    Parameters
    ----------
    outputs : iterable of str or None
        What the command will write.
    inputs : iterable of str or None
        What it reads (records, design files, response files …).
    streams : iterable of str
        Outputs that may be a character device or FIFO (``/dev/stdout``), written in place.

    Ends the command with one line naming the output (exit 2) on a refusal.
    """
    from isolator.atomic import OutputError, refuse_overwriting_inputs, resolve_output

    outputs = [item for item in outputs if item is not None]
    if any(not str(item) for item in outputs):  # `--out-csv ''` took the lock of '' and ended in a traceback
        user_error("an output is named by a file path, got ''")
    try:
        refuse_overwriting_inputs(outputs, inputs)
        for output in outputs:
            resolve_output(output, allow_stream=output in streams)
    except OutputError as err:
        user_error(str(err))


def write_error(err: OSError, path) -> None:
    """End the command with one line naming the output that could not be written (exit 2)."""
    from isolator.atomic import OutputError

    if isinstance(err, OutputError):
        user_error(str(err))
    user_error(f"{getattr(err, 'filename', None) or path}: cannot write ({err.strerror or err})")


def fmt(value, spec: str = ".6g") -> str:
    """``value`` formatted with ``spec``, or ``"n/a"`` for None."""
    return "n/a" if value is None else format(value, spec)


def write_csv_atomically(path, header: str, columns, *, allow_stream: bool = False) -> None:
    """Write columns to CSV through a temporary file and a rename: never half a file.

    ``path`` "-" writes to standard output; with ``allow_stream`` a character device or
    FIFO (``/dev/stdout``) is written in place (see :func:`isolator.atomic.atomic_path`).
    """
    import numpy as np

    from isolator.atomic import atomic_path

    table = np.column_stack(columns)
    if path == "-":
        np.savetxt(sys.stdout, table, delimiter=",", header=header, comments="", fmt="%.17g")
        return
    with atomic_path(path, allow_stream=allow_stream) as temporary:
        np.savetxt(temporary, table, delimiter=",", header=header, comments="", fmt="%.17g")
