"""Design: an isolator described in a TOML file, validated, with its engineering quantities.

A design file holds one isolator, for example a friction pendulum::

    name = "FPS R = 2.0 m, mu = 0.06"
    mass_kg = 250000.0          # supported mass [kg]
    radius_m = 2.0              # radius of curvature [m]  (or stiffness_N_per_m)
    mu_static = 0.06            # static friction coefficient [-]
    mu_kinetic = 0.05           # optional, default mu_static (friction model 1)
    damping_ratio = 0.05        # optional supplemental damper, fraction of critical
                                # at the pendulum frequency (or damping_Ns_per_m)

Exactly one of ``radius_m`` / ``stiffness_N_per_m``; at most one of
``damping_Ns_per_m`` / ``damping_ratio``.  Every mistake raises :class:`DesignError`
with a one-line message naming the file and the key.

The friction-pendulum quantities follow the usual bilinear idealisation (e.g. AASHTO
Guide Specifications for Seismic Isolation Design, EN 15129): at a displacement D,
``K_eff = K + µk M g / D``, ``T_eff = 2π sqrt(M / K_eff)`` and
``β_eff = E_D / (2π K_eff D²)`` with the energy per cycle ``E_D = 4 µk M g D`` (friction)
``+ π γ ω_eff D²`` (damper at the effective frequency).
"""

from __future__ import annotations

import math
import os
import re
import sys
from dataclasses import dataclass, field, replace
from pathlib import Path

from isolator.units import STANDARD_GRAVITY

#: the longest design name [characters]: a name heads every table, CSV row and report page
NAME_MAX_CHARS = 200
#: what a design search or a batch grid appends to a name, " [radius_m=2.5, mu_static=0.06]", is not counted in
#: NAME_MAX_CHARS up to this length [characters]
SUFFIX_MAX_CHARS = 2000
#: the longest design description [characters]: free text, a paragraph or a page (a report shows its first 40
#: characters), not a file pasted in (10^6 characters were read and carried by every candidate, h203)
DESCRIPTION_MAX_CHARS = 10_000
_CANDIDATE_SUFFIX = re.compile(r" \[[A-Za-z_.]+=[^,\[\]]+(?:, [A-Za-z_.]+=[^,\[\]]+)*\]$")
#: how a design search names a candidate: its values first, then the base design's name ("[radius_m=4.5,
#: mu_kinetic=0.06] varied from the base design: FPS R = 4.0 m …"), so that no page reads the base's numbers as the
#: candidate's; the bracketed values and these words are not counted in NAME_MAX_CHARS (up to SUFFIX_MAX_CHARS)
CANDIDATE_WORDS = " varied from the base design: "
_CANDIDATE_PREFIX = re.compile(r"^\[[A-Za-z_.]+=[^,\[\]]+(?:, [A-Za-z_.]+=[^,\[\]]+)*\]" + re.escape(CANDIDATE_WORDS))

#: keys a design file may hold, with their meaning (used in messages and the README)
DESIGN_KEYS = {
    "name": "design name (text)",
    "description": "free text (optional)",
    "mass_kg": "supported mass M [kg], > 0",
    "radius_m": "friction-pendulum radius of curvature R [m], > 0",
    "stiffness_N_per_m": "generic restoring stiffness K [N/m], >= 0",
    "mu_static": "static friction coefficient µs [-], > 0",
    "mu_kinetic": "kinetic friction coefficient µk [-], 0 <= µk <= µs (default µs)",
    "damping_Ns_per_m": "supplemental linear damper γ [N·s/m], >= 0",
    "damping_ratio": "supplemental damper as a fraction of critical at sqrt(K/M) [-], 0 <= ζ < 1",
    "mu_slow": "velocity-dependent friction: µ at zero sliding velocity [-], 0 <= µ_slow <= µ_fast",
    "mu_fast": "velocity-dependent friction: µ at high sliding velocity [-], < 1",
    "rate_s_per_m": "velocity-dependent friction: rate a in µ(v) = µ_fast - (µ_fast - µ_slow) exp(-a|v|) [s/m], > 0",
    "displacement_capacity_m": "displacement capacity of the bearing (resultant) [m], > 0",
    "lambda_max": "upper-bound property modification factor on µ [-], >= 1",
    "lambda_min": "lower-bound property modification factor on µ [-], 0 < λ_min <= 1",
    "mu_upper": "upper-bound kinetic friction coefficient [-], >= µk",
    "mu_lower": "lower-bound kinetic friction coefficient [-], 0 < µ_lower <= µk",
    "lambda_ae_max": "λ for aging and environment, maximum [-], >= 1",
    "lambda_ae_min": "λ for aging and environment, minimum [-], 0 < λ <= 1",
    "lambda_test_max": "λ for heating, rate and scragging (prototype tests), maximum [-], >= 1",
    "lambda_test_min": "λ for heating, rate and scragging (prototype tests), minimum [-], 0 < λ <= 1",
    "lambda_spec_max": "λ for permitted manufacturing variation, maximum [-], >= 1",
    "lambda_spec_min": "λ for permitted manufacturing variation, minimum [-], 0 < λ <= 1",
    "plan": "table: plan dimensions b_m, d_m [m], eccentricity_m [m], y_m [m] or P_T [-] (torsion factor)",
    "superstructure": "table: damping_ratio and [[superstructure.floor]] entries (isolator.superstructure)",
    "bearing_position": "array of tables: x_m, y_m [m] from the centre of mass, gravity_load_N [N] (optional)",
    "bearing": "table: type single/double/triple and [[bearing.surface]] entries (docs/multisurface.md)",
}

#: keys of the optional ``[plan]`` table
PLAN_KEYS = {
    "b_m": "plan dimension b [m], > 0",
    "d_m": "plan dimension d [m], > 0",
    "eccentricity_m": "actual eccentricity between the centres of mass and rigidity [m], >= 0 (default 0)",
    "y_m": "distance from the centre of rigidity to the bearing considered, perpendicular to the loading [m], >= 0",
    "P_T": "ratio of torsional to translational period of the isolation system [-], > 0",
}
#: A plan dimension b or d [m]: 1 cm (an isolated cabinet) to 10 km, the bearings' own bound
#: (superstructure.BEARING_POSITION_MAX_M).  Below it r_I = sqrt((b² + d²)/12) of ASCE 7-22 Eq. 17.5-4 vanishes:
#: b = d = 1e-300 m underflowed to r_I = 0 and P_T's division was a ZeroDivisionError traceback from `report` and
#: `review` (Session 15 sweep, docs/security.md).
PLAN_DIMENSION_RANGE_M = (1e-2, 1e4)

#: the three ways a file may give the bounds of µ (one at most)
BOUND_FORMS = (("lambda_max", "lambda_min"), ("mu_upper", "mu_lower"),
               ("lambda_ae_max", "lambda_ae_min", "lambda_test_max", "lambda_test_min", "lambda_spec_max",
                "lambda_spec_min"))


#: The largest TOML file read [bytes]: a 200 MB design file of comments was read whole (13.5 s, 441 MB; session 17
#: sweep), so a few GB would exhaust the memory.  The largest real inputs are far below: a building on the layout
#: bound (10,000 [[bearing_position]] tables) is 0.46 MiB, a batch designs file of 10,000 designs 0.9 MiB.
MAX_TOML_BYTES = 64 * 2**20
#: The largest design, target or suite file read [bytes] (a batch's designs file keeps MAX_TOML_BYTES): tomllib parses
#: 0.5-3 MiB per second of CPU (an array of numbers the slowest), so 64 MiB of junk took up to 2 minutes to refuse (a
#: 10 MB array: 100 s at load 9, session 25 sweep).  The largest real one, a building on the 10,000-bearing bound with
#: 200 floors, is 0.5 MiB; 4 MiB is eight times that and parses in at most 8 s.
MAX_ONE_TOML_BYTES = 4 * 2**20
#: A key of this many dotted parts (``a.b.c…``, bare or quoted) is refused before tomllib reads the file: its time
#: grows as the square of a key's parts (2,000 / 5,000 / 10,000 parts: 0.28 / 0.85 / 2.8 s; a 100 kB key of
#: 50,000 ran past a minute; session 17 sweep).  Scanning 61 MiB of floats for it takes 8.4 s (/tmp/h166).
MAX_KEY_PARTS = 32
DEEP_TOML_KEY = re.compile(r"""(?<![\w"'-])(?:(?:[\w-]+|"[^"\n]*"|'[^'\n]*')[ \t]*\.[ \t]*)"""
                           + f"{{{MAX_KEY_PARTS}}}")


def load_toml(path, what: str, error_type: type[Exception], *, max_bytes: int = MAX_ONE_TOML_BYTES) -> dict:
    """Read a TOML file; a missing, unreadable or invalid file raises ``error_type``.

    Parameters
    ----------
    path : str or path-like
        The file.
    what : str
        What the file is, for the message ("design file", "designs file").
    error_type : type
        The exception raised, with one line naming the file and the problem.
    max_bytes : int
        The largest file read (:data:`MAX_ONE_TOML_BYTES`; a batch's designs file :data:`MAX_TOML_BYTES`).
    """
    import tomllib

    from isolator.io._common import input_file_problem

    if not isinstance(path, (str, os.PathLike)) or not os.fspath(path):
        raise error_type(f"a {what} is named by a file path, got {path!r}")
    path = Path(path)
    problem = input_file_problem(path)  # before opening: a FIFO must not block, a loop is not "missing"
    if problem == "no such file":
        raise error_type(f"{path}: no such {what}")
    if problem is not None and problem != "file is empty":
        raise error_type(f"{path}: {problem}")
    try:
        size = path.stat().st_size
        if size > max_bytes:
            raise error_type(f"{path}: is {size / 2**20:.1f} MiB, larger than any {what} (isolator reads a {what} up "
                             f"to {max_bytes // 2**20} MiB; 10,000 bearing positions take about 0.5 MiB, 10,000 "
                             "designs 0.9 MiB)")
        with path.open("rb") as stream:  # read at most the bound: a file that grows meanwhile is not read whole
            data = stream.read(max_bytes + 1)
        if len(data) > max_bytes:
            raise error_type(f"{path}: grew past {max_bytes // 2**20} MiB while read")
        # a byte-order mark (Notepad's "UTF-8 with BOM") is an encoding's mark, not content: tomllib called it "Invalid
        # statement (at line 1, column 1)"
        text = data.decode("utf-8-sig")
    except FileNotFoundError:
        raise error_type(f"{path}: no such {what}") from None
    except UnicodeDecodeError as err:  # a binary file was "cannot read the design file ('utf-8' codec can't …)"
        line = data.count(b"\n", 0, err.start) + 1
        raise error_type(f"{path}: not UTF-8 text (line {line}: byte 0x{data[err.start]:02x}): a binary file, or text "
                         "saved in another encoding (save it as UTF-8; TOML is UTF-8)") from None
    except OSError as err:
        raise error_type(f"{path}: cannot read the {what} ({' '.join(str(err).split())})") from None
    if not text.strip():  # an empty design file said "missing key 'mass_kg'" (h203): it is missing every key
        raise error_type(f"{path}: the {what} is empty")
    deep = DEEP_TOML_KEY.search(text)
    if deep:  # tomllib's time grows as the square of a key's parts: 10,000 took 2.8 s, 50,000 ran past a minute
        line = text.count("\n", 0, deep.start()) + 1
        raise error_type(f"{path}: line {line}: a key of {MAX_KEY_PARTS} or more dotted parts; isolator's files nest "
                         "keys 3 deep at most (superstructure.floor.mass_kg)")
    try:
        content = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise error_type(f"{path}: not valid TOML ({' '.join(str(err).split())})") from None
    except RecursionError:  # arrays or inline tables nested 100,000 deep: tomllib recurses per level
        raise error_type(f"{path}: not valid TOML (arrays or tables nested deeper than Python's stack)") from None
    huge = _huge_integer(content)
    if huge is not None:  # every reader takes float(value): an integer of 400 digits was an OverflowError traceback
        key, digits = huge
        raise error_type(f"{path}: key '{key}' is an integer of {digits} digits, beyond any number (a float ends at "
                         "1.8e308)")
    return content


def _huge_integer(content) -> tuple[str, int] | None:
    """(key, digits) of the first integer of a TOML document too large for a float, or None."""
    from collections import deque

    queue = deque([("", content)])
    while queue:  # bounded: each value is visited once, in the file's order
        key, value = queue.popleft()
        if isinstance(value, dict):
            queue.extend((f"{key}.{k}" if key else str(k), v) for k, v in value.items())
        elif isinstance(value, list):
            queue.extend((key, v) for v in value)
        elif isinstance(value, int) and not isinstance(value, bool) and abs(value) > sys.float_info.max:
            return key, len(str(abs(value)))
    return None


from isolator.errors import DesignError, key_hint, printable  # noqa: E402,F401 - the design's error, defined with the others

#: Supported mass M accepted [kg]: from a gram (a laboratory specimen) to 1e10 kg (ten times
#: the heaviest isolated structure); outside, K/M and γ/M lose their meaning (1e-320 kg is
#: a subnormal number: K/M overflows).
MASS_RANGE_KG = (1e-3, 1e10)


def _check_meant(fail, **values) -> None:
    """Refuse a number no engineer means (:data:`isolator.bearing.MEANT_RANGES`), naming the key."""
    from isolator.bearing import outside_meant

    for key, value in values.items():
        kind = "mu" if key.startswith("mu_") else key
        problem = "" if value is None else outside_meant(kind, value)
        if problem:
            raise fail(f"key '{key}' = {value:g} is {problem}")


def _check_derived(fail, mass_kg, stiffness_N_per_m, damping_Ns_per_m, radius_m, damping_ratio) -> None:
    """Refuse a design whose K/M or γ/M the solver cannot take, naming the key at fault."""
    from isolator.solver.system import MAX_DAMPING_PER_MASS, MAX_STIFFNESS_PER_MASS

    low, high = MASS_RANGE_KG
    if not low <= mass_kg <= high:
        raise fail(f"key 'mass_kg' must lie in [{low:g}, {high:g}] kg, got {mass_kg:g}")
    kappa = stiffness_N_per_m / mass_kg
    if not kappa <= MAX_STIFFNESS_PER_MASS:
        key = "radius_m" if radius_m is not None else "stiffness_N_per_m"
        given = f"{radius_m:g} m" if radius_m is not None else f"{stiffness_N_per_m:g} N/m"
        raise fail(f"key '{key}' = {given} gives K/M = {kappa:.3g} 1/s² (natural period "
                   f"{2 * math.pi / math.sqrt(kappa):.3g} s), above {MAX_STIFFNESS_PER_MASS:g} 1/s²: "
                   "no isolator is that stiff")
    c = damping_Ns_per_m / mass_kg
    if not c <= MAX_DAMPING_PER_MASS:
        key = "damping_ratio" if damping_ratio is not None else "damping_Ns_per_m"
        raise fail(f"key '{key}' gives γ/M = {c:.3g} 1/s, above {MAX_DAMPING_PER_MASS:g} 1/s: no damper is "
                   "that strong")


@dataclass(frozen=True)
class EffectiveProperties:
    """Equivalent-linear properties of the isolator at one displacement (SI units)."""

    displacement_m: float
    effective_stiffness_N_per_m: float
    effective_period_s: float
    effective_damping_ratio: float
    design_force_N: float  #: K D + µk M g (+ γ ω_eff D): the bilinear force at D

    def as_dict(self) -> dict:
        return {
            "displacement_m": self.displacement_m,
            "effective_stiffness_N_per_m": self.effective_stiffness_N_per_m,
            "effective_period_s": self.effective_period_s,
            "effective_damping_ratio": self.effective_damping_ratio,
            "design_force_N": self.design_force_N,
        }


@dataclass(frozen=True)
class Design:
    """A validated isolator design (SI units).

    Parameters
    ----------
    name : str
        Design name [-].
    mass_kg : float
        Supported mass M [kg].
    mu_static : float
        Static friction coefficient µs [-].
    mu_kinetic : float
        Kinetic friction coefficient µk ≤ µs [-].
    radius_m : float or None
        Friction-pendulum radius of curvature R [m] (None for a generic spring).
    stiffness_N_per_m : float
        Restoring stiffness K [N/m]; M g / R for a pendulum.
    damping_Ns_per_m : float
        Supplemental damper γ [N·s/m].
    damping_ratio_input : float or None
        The damping ratio given in the file, if it was given that way [-].
    description : str
        Free text [-].
    source : str
        Where the design came from (file name) [-].
    gravity_m_s2 : float
        Gravity used for K = M g / R and for the friction force [m/s²].
    mu_slow, mu_fast : float or None
        Velocity-dependent friction µ(v) = µ_fast − (µ_fast − µ_slow) exp(−a|v|) [-] (all three or none).
    rate_s_per_m : float or None
        The rate a of µ(v) [s/m].
    displacement_capacity_m : float or None
        Displacement capacity of the bearing (resultant) [m].
    property_factors : dict
        The bounding keys as given (``lambda_max``/``lambda_min``, ``mu_upper``/``mu_lower`` or the
        λ_ae/λ_test/λ_spec factors) [-]; combined per code by :mod:`isolator.review.bounds`.
    plan : dict or None
        The ``[plan]`` table: ``b_m``, ``d_m``, ``eccentricity_m``, ``y_m`` or ``P_T``.
    """

    name: str
    mass_kg: float
    mu_static: float
    mu_kinetic: float
    radius_m: float | None
    stiffness_N_per_m: float
    damping_Ns_per_m: float
    damping_ratio_input: float | None = None
    description: str = ""
    source: str = "<design>"
    gravity_m_s2: float = STANDARD_GRAVITY
    mu_slow: float | None = None
    mu_fast: float | None = None
    rate_s_per_m: float | None = None
    displacement_capacity_m: float | None = None
    property_factors: dict = field(default_factory=dict)
    plan: dict | None = None
    #: the building above the isolation plane (:class:`isolator.superstructure.Superstructure`), if any
    superstructure: object = None
    #: the bearings' positions and gravity loads (:class:`isolator.superstructure.BearingLayout`), if any
    bearing_layout: object = None
    bearing: object = None  #: an isolator.bearing.Bearing from a [bearing] table, else None

    # ---- construction ----------------------------------------------------------------

    @classmethod
    def from_toml(cls, path, gravity_m_s2: float = STANDARD_GRAVITY) -> Design:
        """Read and validate a design file.

        Parameters
        ----------
        path : str or Path
            TOML file [-].
        gravity_m_s2 : float
            Gravity [m/s²].

        Returns
        -------
        Design
        """
        mapping = load_toml(path, "design file", DesignError)
        if isinstance(mapping, dict) and "name" not in mapping:
            mapping = {"name": Path(path).stem, **mapping}  # the file's stem names an unnamed design
        return cls.from_mapping(mapping, source=str(path), gravity_m_s2=gravity_m_s2)

    @classmethod
    def from_mapping(cls, mapping: dict, source: str = "<design>",
                     gravity_m_s2: float = STANDARD_GRAVITY) -> Design:
        """Validate a design given as a dict (the content of a TOML file).

        Raises
        ------
        DesignError
            A message like ``"design.toml: key 'radius_m' must be > 0, got -1"``.
        """
        def fail(message: str) -> DesignError:
            return DesignError(f"{source}: {message}")

        if not isinstance(mapping, dict):
            raise fail("a design must be a table of keys")
        unknown = [key for key in mapping if key not in DESIGN_KEYS]
        if unknown:
            key = unknown[0]
            raise fail(f"unknown key '{key}'{key_hint(key, DESIGN_KEYS)}")
        bearing = None
        if "bearing" in mapping:  # surface by surface; the top-level keys become its equivalent single pendulum
            from isolator.bearing import equivalent_design_keys, parse_bearing

            bearing = parse_bearing(mapping["bearing"], fail, float(gravity_m_s2))
            mapping = equivalent_design_keys(bearing, mapping, fail)

        def number(key: str, *, minimum: float = 0.0, strict: bool = False, required: bool = False):
            if key not in mapping:
                if required:
                    raise fail(f"missing key '{key}' ({DESIGN_KEYS[key]})")
                return None
            value = mapping[key]
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise fail(f"key '{key}' must be a number, got {value!r}")
            value = float(value)
            if not math.isfinite(value):
                raise fail(f"key '{key}' must be finite, got {value}")
            if strict and not value > minimum:
                raise fail(f"key '{key}' must be > {minimum:g}, got {value:g}")
            if not strict and value < minimum:
                raise fail(f"key '{key}' must be >= {minimum:g}, got {value:g}")
            return value

        name = mapping.get("name")
        if name is None:
            raise fail(f"missing key 'name' ({DESIGN_KEYS['name']})")
        if not isinstance(name, str) or not name.strip():
            raise fail(f"key 'name' must be a non-empty text, got {name!r}")
        if not name.isprintable():  # it names rows of CSV tables and report pages: an ESC sequence there drove the
            # terminal of whoever printed the table (`batch` wrote "\x1b]0;pwned\x07 FPS" raw; session 17 sweep)
            raise fail(f"key 'name' holds a control or format character ('{printable(name)}'): a design's name is "
                       "printed in tables, CSV files and reports; use letters, digits, spaces and punctuation")
        written = (_CANDIDATE_PREFIX.sub("", _CANDIDATE_SUFFIX.sub("", name))
                   if len(name) <= NAME_MAX_CHARS + SUFFIX_MAX_CHARS else name)
        if len(written.strip()) > NAME_MAX_CHARS:  # it heads every table, CSV row and report page (a 100,000-character
            # name was read, session 19 sweep); a search's candidates append their values in brackets to it
            raise fail(f"key 'name' is {len(name.strip()):,} characters long, more than a design's name may be "
                       f"({NAME_MAX_CHARS}): it heads tables and report pages; put longer text in 'description'")
        description = mapping.get("description", "")
        if not isinstance(description, str):
            raise fail(f"key 'description' must be text, got {description!r}")
        if len(description) > DESCRIPTION_MAX_CHARS:
            raise fail(f"key 'description' is {len(description):,} characters long, more than a design's description "
                       f"may be ({DESCRIPTION_MAX_CHARS:,}): it is free text, shortened to 40 characters in "
                       "reports; keep longer notes in a file of their own")

        mass_kg = number("mass_kg", strict=True, required=True)
        mu_static = number("mu_static", strict=True, required=True)
        mu_kinetic = number("mu_kinetic")
        if mu_kinetic is None:
            mu_kinetic = mu_static
        elif mu_kinetic > mu_static:
            raise fail(f"key 'mu_kinetic' ({mu_kinetic:g}) must not exceed 'mu_static' ({mu_static:g})")
        if mu_static >= 1.0:
            raise fail(f"key 'mu_static' must be < 1 for a sliding isolator, got {mu_static:g}")

        has_radius, has_stiffness = "radius_m" in mapping, "stiffness_N_per_m" in mapping
        if has_radius and has_stiffness:
            raise fail("give either 'radius_m' (friction pendulum) or 'stiffness_N_per_m', not both")
        if not (has_radius or has_stiffness):
            raise fail("missing key 'radius_m' (friction pendulum) or 'stiffness_N_per_m' (generic spring)")
        g = float(gravity_m_s2)
        if has_radius:
            radius_m = number("radius_m", strict=True)
            stiffness = mass_kg * g / radius_m
        else:
            radius_m = None
            stiffness = number("stiffness_N_per_m")

        if "damping_Ns_per_m" in mapping and "damping_ratio" in mapping:
            raise fail("give at most one of 'damping_Ns_per_m' and 'damping_ratio'")
        damping_ratio = number("damping_ratio")
        if damping_ratio is not None and not damping_ratio < 1.0:
            # a fraction of critical, as [superstructure]'s: 1.5 (150 %, an over-critical damper) ran without a word
            # and 5 is most likely 5 % typed as a percent (session 17 sweep); an over-critical damper (the paper's
            # configuration 4c, exact in the kernels) is given by its coefficient
            raise fail(f"key 'damping_ratio' must lie in [0, 1), a fraction of critical (5 % is 0.05), got "
                       f"{damping_ratio:g}; give an over-critical damper as 'damping_Ns_per_m'")
        if damping_ratio is not None:
            if stiffness == 0.0 and damping_ratio > 0.0:
                raise fail("key 'damping_ratio' needs a restoring stiffness (radius_m or stiffness_N_per_m > 0); "
                           "give 'damping_Ns_per_m' instead")
            damping = 2.0 * damping_ratio * math.sqrt(stiffness * mass_kg)
        else:
            damping = number("damping_Ns_per_m") or 0.0
        _check_derived(fail, mass_kg, stiffness, damping, radius_m, damping_ratio)

        # velocity-dependent friction (all three or none): 0 <= µ_slow <= µ_fast < 1, 0 < a <= RATE_MAX_S_PER_M
        from isolator.solver.system import RATE_MAX_S_PER_M
        velocity_keys = ("mu_slow", "mu_fast", "rate_s_per_m")
        given = [key for key in velocity_keys if key in mapping]
        mu_slow = mu_fast = rate = None
        if given:
            if len(given) != 3:
                missing = [key for key in velocity_keys if key not in mapping]
                raise fail(f"velocity-dependent friction needs 'mu_slow', 'mu_fast' and 'rate_s_per_m' together; "
                           f"missing {', '.join(repr(k) for k in missing)}")
            mu_slow, mu_fast = number("mu_slow"), number("mu_fast")
            rate = number("rate_s_per_m", strict=True)
            if rate > RATE_MAX_S_PER_M:  # the engine's bound, read here: a design search's candidates are designs
                raise fail(f"key 'rate_s_per_m' = {rate:g} s/m exceeds {RATE_MAX_S_PER_M:g} s/m: µ would change "
                           f"from mu_slow to mu_fast within {1.0 / rate:.1g} m/s, which the 2-D engine cannot follow "
                           "in bounded steps; so steep a law is Coulomb friction at mu_fast (give 'mu_kinetic'; "
                           "measured rates are 10-200 s/m)")
            if mu_slow > mu_fast:
                raise fail(f"key 'mu_slow' ({mu_slow:g}) must not exceed 'mu_fast' ({mu_fast:g})")
            if mu_fast >= 1.0:
                raise fail(f"key 'mu_fast' must be < 1 for a sliding isolator, got {mu_fast:g}")
        capacity = number("displacement_capacity_m", strict=True)
        if bearing is None:  # a [bearing]'s surfaces were checked each; the keys are then its equivalent pendulum
            # µk = 0 is the paper's (kept); a µk of 1e-300 was read (session 18 sweep)
            _check_meant(fail, radius_m=radius_m, mu_static=mu_static, mu_kinetic=mu_kinetic or None, mu_slow=mu_slow,
                         mu_fast=mu_fast, rate_s_per_m=rate, displacement_capacity_m=capacity)
        factors = _property_factors(mapping, number, fail, mu_kinetic)
        plan = _plan(mapping.get("plan"), fail)
        from isolator.superstructure import parse_bearing_layout, parse_superstructure

        superstructure = parse_superstructure(mapping.get("superstructure"), mass_kg, g, source)
        bearing_layout = parse_bearing_layout(mapping.get("bearing_position"), mass_kg * g, source)
        return cls(name=name.strip(), mass_kg=mass_kg, mu_static=mu_static, mu_kinetic=mu_kinetic,
                   radius_m=radius_m, stiffness_N_per_m=stiffness, damping_Ns_per_m=damping,
                   damping_ratio_input=damping_ratio, description=description, source=source,
                   gravity_m_s2=g, mu_slow=mu_slow, mu_fast=mu_fast, rate_s_per_m=rate,
                   displacement_capacity_m=capacity, property_factors=factors, plan=plan,
                   superstructure=superstructure, bearing_layout=bearing_layout, bearing=bearing)

    def with_friction_factor(self, factor: float, label: str) -> Design:
        """The same design with every friction coefficient multiplied by ``factor`` (a property bound).

        Parameters
        ----------
        factor : float
            λ applied to µs, µk and µ_slow/µ_fast [-], > 0.
        label : str
            Appended to the name, e.g. ``"upper bound"``.

        Returns
        -------
        Design
        """
        if not (factor > 0 and math.isfinite(factor)):
            raise DesignError(f"{self.source}: property modification factor must be > 0, got {factor!r}")
        if self.mu_static * factor >= 1.0 or (self.mu_fast is not None and self.mu_fast * factor >= 1.0):
            raise DesignError(f"{self.source}: µ × λ = {self.mu_static * factor:g} must stay < 1 ({label})")
        return replace(self, name=f"{self.name} ({label})", mu_static=self.mu_static * factor,
                       mu_kinetic=self.mu_kinetic * factor, mu_slow=None if self.mu_slow is None else self.mu_slow * factor,
                       mu_fast=None if self.mu_fast is None else self.mu_fast * factor,
                       bearing=None if self.bearing is None else self.bearing.with_friction_factor(
                           factor, lambda message: DesignError(f"{self.source}: at the {label} (λ = {factor:g}), "
                                                               f"{message}")))

    @property
    def velocity_dependent(self) -> bool:
        """True when µ(v) is given (µ_slow, µ_fast, a)."""
        return self.rate_s_per_m is not None

    # ---- derived quantities -------------------------------------------------------------

    @property
    def is_pendulum(self) -> bool:
        """True for a friction pendulum (given by its radius)."""
        return self.radius_m is not None

    @property
    def weight_N(self) -> float:
        """W = M g [N]."""
        return self.mass_kg * self.gravity_m_s2

    @property
    def stiffness_per_mass(self) -> float:
        """κ = K/M [1/s²]."""
        return self.stiffness_N_per_m / self.mass_kg

    @property
    def damping_per_mass(self) -> float:
        """c = γ/M [1/s]."""
        return self.damping_Ns_per_m / self.mass_kg

    @property
    def natural_frequency_rad_s(self) -> float:
        """ω_n = sqrt(K/M) [rad/s] (0 without a spring)."""
        return math.sqrt(self.stiffness_per_mass)

    @property
    def isolated_period_s(self) -> float:
        """T = 2π sqrt(M/K) = 2π sqrt(R/g) for a pendulum [s] (inf without a spring)."""
        omega = self.natural_frequency_rad_s
        return 2.0 * math.pi / omega if omega > 0 else math.inf

    @property
    def damping_ratio(self) -> float:
        """γ / (2 sqrt(K M)) [-] (inf for a damper without a spring, 0 without a damper)."""
        if self.damping_Ns_per_m == 0.0:
            return 0.0
        if self.stiffness_N_per_m == 0.0:
            return math.inf
        return self.damping_Ns_per_m / (2.0 * math.sqrt(self.stiffness_N_per_m * self.mass_kg))

    def system(self, gravity_m_s2: float | None = None):
        """The solver's per-unit-mass system (µs, µk, K/M, γ/M, g).

        Parameters
        ----------
        gravity_m_s2 : float, optional
            Gravity for the friction force [m/s²]; the design's by default.

        Returns
        -------
        isolator.solver.system.System
        """
        from isolator.solver.system import System

        return System(mu_static=self.mu_static, mu_kinetic=self.mu_kinetic,
                      stiffness_per_mass=self.stiffness_per_mass, damping_per_mass=self.damping_per_mass,
                      gravity_m_s2=self.gravity_m_s2 if gravity_m_s2 is None else gravity_m_s2)

    def effective_properties(self, displacement_m: float) -> EffectiveProperties:
        r"""Equivalent-linear stiffness, period and damping at a displacement.

        .. math::  K_{eff} = K + \frac{\mu_k M g}{D},\quad
                   T_{eff} = 2\pi\sqrt{M/K_{eff}},\quad
                   \beta_{eff} = \frac{4\mu_k M g D + \pi\gamma\omega_{eff} D^2}{2\pi K_{eff} D^2}

        Parameters
        ----------
        displacement_m : float
            Peak isolator displacement D [m].

        Returns
        -------
        EffectiveProperties
            NaN stiffness, period and damping when D = 0 (the isolator did not slide).
        """
        d = abs(float(displacement_m))
        if self.bearing is not None and not self.bearing.is_simple:
            return EffectiveProperties(*self.bearing.effective_properties(d, self.mass_kg, self.gravity_m_s2,
                                                                          self.damping_Ns_per_m))
        friction_N = self.mu_kinetic * self.weight_N
        if d == 0.0:
            nan = math.nan
            return EffectiveProperties(0.0, nan, nan, nan, friction_N)
        k_eff = self.stiffness_N_per_m + friction_N / d
        omega_eff = math.sqrt(k_eff / self.mass_kg)
        energy_J = 4.0 * friction_N * d + math.pi * self.damping_Ns_per_m * omega_eff * d * d
        beta = energy_J / (2.0 * math.pi * k_eff * d * d)
        force_N = self.stiffness_N_per_m * d + friction_N + self.damping_Ns_per_m * omega_eff * d
        return EffectiveProperties(d, k_eff, 2.0 * math.pi / omega_eff, beta, force_N)

    def as_dict(self) -> dict:
        """The design's input and derived numbers (SI units)."""
        return {
            "name": self.name,
            "source": self.source,
            "kind": "friction pendulum" if self.is_pendulum else "flat slider with spring",
            "mass_kg": self.mass_kg,
            "radius_m": self.radius_m,
            "stiffness_N_per_m": self.stiffness_N_per_m,
            "mu_static": self.mu_static,
            "mu_kinetic": self.mu_kinetic,
            "damping_Ns_per_m": self.damping_Ns_per_m,
            "damping_ratio": self.damping_ratio,
            "isolated_period_s": self.isolated_period_s,
            "gravity_m_s2": self.gravity_m_s2,
            "mu_slow": self.mu_slow,
            "mu_fast": self.mu_fast,
            "rate_s_per_m": self.rate_s_per_m,
            "displacement_capacity_m": self.displacement_capacity_m,
            "property_factors": dict(self.property_factors),
            "plan": None if self.plan is None else dict(self.plan),
            "superstructure": None if self.superstructure is None else self.superstructure.as_dict(),
            "bearing_position": None if self.bearing_layout is None else self.bearing_layout.as_dict(),
            "bearing": None if self.bearing is None else self.bearing.as_dict(),
        }


def _property_factors(mapping: dict, number, fail, mu_kinetic: float) -> dict:
    """The bounding keys of a design file, checked (one form, pairs complete, λ_min ≤ 1 ≤ λ_max, the bounds' µ)."""
    from isolator.bearing import outside_meant

    forms = [form for form in BOUND_FORMS if any(key in mapping for key in form)]
    if not forms:
        return {}
    if len(forms) > 1:
        raise fail(f"give the friction bounds one way: {'/'.join(forms[0][:2])} or {'/'.join(forms[1][:2])}, "
                   "not both")
    form = forms[0]
    missing = [key for key in form if key not in mapping]
    if missing:
        raise fail(f"missing key '{missing[0]}' (bounds need {', '.join(form)})")
    values = {key: number(key, strict=True) for key in form}
    if form[0] == "mu_upper":
        if values["mu_upper"] < mu_kinetic:
            raise fail(f"key 'mu_upper' ({values['mu_upper']:g}) must be >= the nominal µk ({mu_kinetic:g})")
        if values["mu_lower"] > mu_kinetic:
            raise fail(f"key 'mu_lower' ({values['mu_lower']:g}) must be <= the nominal µk ({mu_kinetic:g})")
        for key, value in values.items():
            problem = outside_meant("mu", value)
            if problem:
                raise fail(f"key '{key}' = {value:g} is {problem}")
        return values
    for key, value in values.items():
        if key.endswith("_max") and value < 1.0:
            raise fail(f"key '{key}' must be >= 1, got {value:g}")
        if key.endswith("_min") and value > 1.0:
            raise fail(f"key '{key}' must be <= 1, got {value:g}")
    # the bounds' friction is a friction coefficient too: lambda_max = 1e300 was read (an upper-bound µ of 6e298)
    # and lambda_min = 1e-300 (a lower bound of no friction at all; session 17 sweep)
    highest = math.prod(value for key, value in values.items() if key.endswith("_max"))
    lowest = math.prod(value for key, value in values.items() if key.endswith("_min"))
    for which, product in (("max", highest), ("min", lowest)):
        problem = outside_meant("mu", mu_kinetic * product) if mu_kinetic > 0 else ""
        if problem:
            keys = " x ".join(key for key in values if key.endswith(f"_{which}"))
            raise fail(f"the bound's friction µk x {keys} = {mu_kinetic * product:g} is {problem}")
    return values


def _plan(table, fail) -> dict | None:
    """The optional ``[plan]`` table, checked."""
    if table is None:
        return None
    if not isinstance(table, dict):
        raise fail("key 'plan' must be a table ([plan] with b_m, d_m, eccentricity_m, y_m or P_T)")
    unknown = [key for key in table if key not in PLAN_KEYS]
    if unknown:
        raise fail(f"unknown key 'plan.{unknown[0]}'{key_hint(unknown[0], PLAN_KEYS)}")
    out = {}
    for key, value in table.items():
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise fail(f"key 'plan.{key}' must be a finite number, got {value!r}")
        if value < 0 or (key in ("b_m", "d_m", "P_T") and value == 0):
            raise fail(f"key 'plan.{key}' must be {'> 0' if key in ('b_m', 'd_m', 'P_T') else '>= 0'}, "
                       f"got {value:g}")
        out[key] = float(value)
    for key in ("b_m", "d_m"):
        if key not in out:
            raise fail(f"missing key 'plan.{key}' ({PLAN_KEYS[key]})")
        low, high = PLAN_DIMENSION_RANGE_M
        if not low <= out[key] <= high:
            raise fail(f"key 'plan.{key}' must lie in [{low:g}, {high:g}] m, a plan dimension, got {out[key]:g}")
    # both are lengths within the plan (`eccentricity_m = 1e300` was read: session 24 sweep)
    diagonal = math.hypot(out["b_m"], out["d_m"])
    for key, within in (("eccentricity_m", "the centres of mass and rigidity both lie within the plan"),
                        ("y_m", "the centre of rigidity and the bearing considered lie within the plan")):
        if out.get(key, 0.0) > diagonal:
            raise fail(f"key 'plan.{key}' = {out[key]:g} m is longer than the plan's diagonal ({diagonal:.4g} m, "
                       f"b_m = {out['b_m']:g}, d_m = {out['d_m']:g}): {within}")
    return out
