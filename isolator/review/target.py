r"""Target spectra: the MCE_R two-period shape (ASCE 7-22 11.4.5.1 / 11.4.6), EN 1998-1 3.2.2.2, or a table.

TARGET.toml holds one of

* ``S_MS``, ``S_M1`` [g], ``T_L`` [s] — the two-period MCE_R spectrum (REVIEW_RULES 1.1)::

      S_a(T) = S_MS (0.4 + 0.6 T/T_0)   T < T_0 = 0.2 S_M1/S_MS
             = S_MS                     T_0 ≤ T ≤ T_S = S_M1/S_MS
             = S_M1 / T                 T_S < T ≤ T_L
             = S_M1 T_L / T²            T > T_L

  (``S_DS``, ``S_D1`` instead give the MCE_R as 1.5 × the design spectrum);
* ``a_g_g``, ``S``, ``T_B``, ``T_C``, ``T_D`` — the EN 1998-1 3.2.2.2 elastic spectrum at 5 %
  (η = 1);
* ``spectrum_csv = "file"`` — two columns, period [s] and Sa [g], interpolated linearly in
  log–log, refused outside its period range.

An optional ``name`` labels it in the report.  Optional ``magnitude_range = [6.5, 7.5]`` and
``distance_km_range = [0, 30]`` give the controlling earthquake (the deaggregation's magnitude and
distance ranges) against which the suite's record metadata is checked (ASCE 7-22 17.3.2 [U]); likewise
``vs30_m_s_range = [180, 360]`` (the site's V_s30) and ``mechanisms = ["strike-slip"]`` (the controlling
fault mechanisms; compared case-insensitively).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from isolator.errors import TargetError, key_hint

RANGE_KEYS = ("magnitude_range", "distance_km_range", "vs30_m_s_range")

#: An earthquake's magnitude, distance and site as an engineer means them (low, high, unit, why): a suite's
#: ``magnitude = 1e-300`` and ``distance_km = 1e300`` were read and compared with the target's ranges (session 17
#: sweep's leftover).  The suite's metadata and the target's ``*_range`` ends (a low end of 0: no lower bound) share
#: them.
EARTHQUAKE_RANGES = {
    "magnitude": (1.0, 10.0, "", "a moment magnitude: records that move a structure come from M 4-9.5 (the largest "
                                 "measured, Valdivia 1960)"),
    "distance_km": (0.0, 1000.0, "km", "a source-to-site distance: strong motions reach ~500 km (Mexico City 1985: "
                                       "350 km); is it in metres?"),
    "vs30_m_s": (50.0, 3500.0, "m/s", "a site's V_s30: soft clay ~100 m/s, hard rock 1500-3000 m/s; is it in ft/s "
                                      "or km/s?"),
}


def outside_earthquake(key: str, value: float) -> str:
    """"" if ``value`` lies in :data:`EARTHQUAKE_RANGES` ``[key]``, else the sentence after "'key' = value is ..."."""
    low, high, unit, why = EARTHQUAKE_RANGES[key]
    if low <= value <= high:
        return ""
    return f"outside [{low:g}, {high:g}]{' ' + unit if unit else ''}: {why}"
TARGET_KEYS = {"name", "S_MS", "S_M1", "S_DS", "S_D1", "T_L", "a_g_g", "S", "T_B", "T_C", "T_D", "spectrum_csv",
               "mechanisms", *RANGE_KEYS}


@dataclass(frozen=True)
class Target:
    """A 5 %-damped target spectrum.

    Attributes
    ----------
    kind : str
        ``"asce7-two-period"``, ``"en1998-elastic"`` or ``"table"``.
    parameters : dict
        The numbers that define it (S_MS, S_M1 [g], T_L [s]; or a_g [g], S, T_B, T_C, T_D [s]).
    name : str
        Label [-].
    periods_s, sa_table_g : numpy.ndarray
        The table of a tabulated target [s], [g].
    """

    kind: str
    parameters: dict
    name: str = "target"
    source: str = "<target>"
    periods_s: np.ndarray = field(default_factory=lambda: np.empty(0))
    sa_table_g: np.ndarray = field(default_factory=lambda: np.empty(0))
    controlling: dict = field(default_factory=dict)  #: magnitude/distance_km/vs30_m_s ranges, mechanisms

    def sa_g(self, periods_s, *, clip: bool = False) -> np.ndarray:
        """Target spectral acceleration at the periods [g].

        ``clip=True`` holds a tabulated target constant beyond its ends (used only to bracket
        the ELF fixed point, never for a check).

        Raises
        ------
        TargetError
            A period outside a tabulated target's range.
        """
        T = np.atleast_1d(np.asarray(periods_s, dtype=np.float64))
        p = self.parameters
        if self.kind == "asce7-two-period":
            sms, sm1, tl = p["S_MS"], p["S_M1"], p["T_L"]
            t0, ts = 0.2 * sm1 / sms, sm1 / sms
            with np.errstate(divide="ignore", invalid="ignore"):
                return np.where(T < t0, sms * (0.4 + 0.6 * T / t0),
                                np.where(T <= ts, sms, np.where(T <= tl, sm1 / T, sm1 * tl / T ** 2)))
        if self.kind == "en1998-elastic":
            ag, s, tb, tc, td = p["a_g_g"], p["S"], p["T_B"], p["T_C"], p["T_D"]
            eta = 1.0  # 5 % damping (EN 1998-1 3.2.2.2(3))
            with np.errstate(divide="ignore", invalid="ignore"):
                return ag * s * np.where(T < tb, 1.0 + T / tb * (eta * 2.5 - 1.0),
                                         np.where(T <= tc, eta * 2.5,
                                                  np.where(T <= td, eta * 2.5 * tc / T, eta * 2.5 * tc * td / T ** 2)))
        lo, hi = self.periods_s[0], self.periods_s[-1]
        if clip:
            T = np.clip(T, lo, hi)
        if np.any(T < lo * (1 - 1e-12)) or np.any(T > hi * (1 + 1e-12)):
            raise TargetError(f"{self.source}: the tabulated target covers {lo:g}–{hi:g} s; periods "
                              f"{T.min():.4g}–{T.max():.4g} s are needed")
        return np.exp(np.interp(np.log(T), np.log(self.periods_s), np.log(self.sa_table_g)))

    @property
    def long_period_s(self) -> float:
        """T_L (ASCE) or T_D (EN) or the table's last period [s]."""
        return {"asce7-two-period": self.parameters.get("T_L"),
                "en1998-elastic": self.parameters.get("T_D")}.get(self.kind, float(self.periods_s[-1])
                                                                   if self.periods_s.size else math.inf)

    def as_dict(self) -> dict:
        out = {"kind": self.kind, "name": self.name, "source": self.source, **self.parameters, **self.controlling}
        if self.kind == "table":
            out["periods_s"] = self.periods_s.tolist()
            out["sa_g"] = self.sa_table_g.tolist()
        return out


def design_values(target: Target) -> dict | None:
    """S_DS, S_D1 [g] and T_L [s] of the design spectrum behind a two-period target, with their basis.

    The design spectrum is 2/3 of the MCE_R (ASCE 7-22 11.4.5: S_DS = 2/3 S_MS, S_D1 = 2/3 S_M1); a target
    read from ``S_DS``, ``S_D1`` returns the values as given.  ``None`` for an EN 1998-1 or tabulated target:
    neither gives the 12.8.1.1 coefficients (the fixed-base C_s of ASCE 7-22 17.5.4.3(1) is then not computed).
    """
    if target.kind != "asce7-two-period":
        return None
    p = target.parameters
    given = p.get("from_design_values")
    if given:
        return {"S_DS": float(given["S_DS"]), "S_D1": float(given["S_D1"]), "T_L": p["T_L"],
                "basis": "S_DS, S_D1 as given in the target"}
    return {"S_DS": 2.0 * p["S_MS"] / 3.0, "S_D1": 2.0 * p["S_M1"] / 3.0, "T_L": p["T_L"],
            "basis": "S_DS = 2/3 S_MS, S_D1 = 2/3 S_M1 of the MCE_R target (ASCE 7-22 11.4.5)"}


def two_period_target(S_MS: float, S_M1: float, T_L: float, name: str = "MCE_R") -> Target:
    """The ASCE 7-22 two-period MCE_R spectrum (11.4.5.1 with 11.4.6).

    Parameters
    ----------
    S_MS, S_M1 : float
        Short-period and 1-s MCE_R spectral accelerations [g], > 0.
    T_L : float
        Long-period transition period [s], > S_M1/S_MS.
    """
    if not (S_MS > 0 and S_M1 > 0 and T_L > 0):
        raise TargetError(f"S_MS, S_M1 and T_L must be > 0 (got {S_MS!r}, {S_M1!r}, {T_L!r})")
    if T_L <= S_M1 / S_MS:
        raise TargetError(f"T_L = {T_L:g} s must exceed T_S = S_M1/S_MS = {S_M1 / S_MS:g} s")
    return Target("asce7-two-period", {"S_MS": float(S_MS), "S_M1": float(S_M1), "T_L": float(T_L)}, name=name)


#: The largest spectrum table read [bytes]: a spectrum has at most thousands of rows (a larger
#: "table" is a wrong file, and /dev/zero would fill the memory).
MAX_TABLE_BYTES = 10_000_000
#: Spectral accelerations of a code target [g] and its corner periods [s]: outside, T_S = S_M1/S_MS
#: and the spectrum's shape overflow or mean nothing (issue 26: S_MS = 1e-308).
TARGET_SA_RANGE_G = (1e-4, 10.0)
TARGET_PERIOD_RANGE_S = (1e-3, 100.0)


def _read_csv(path: Path, source: str):
    from isolator.io._common import input_file_problem

    problem = input_file_problem(path)  # from the metadata: a FIFO or /dev/zero is never opened
    if problem == "no such file":
        raise TargetError(f"{source}: spectrum_csv {path}: no such file")
    if problem is not None:
        raise TargetError(f"{source}: spectrum_csv {path}: {problem}")
    if path.stat().st_size > MAX_TABLE_BYTES:
        raise TargetError(f"{source}: spectrum_csv {path}: {path.stat().st_size} bytes is more than a spectrum "
                          f"table holds (at most {MAX_TABLE_BYTES} bytes)")
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise TargetError(f"{source}: spectrum_csv {path}: no such file") from None
    except (OSError, UnicodeDecodeError) as err:
        raise TargetError(f"{source}: spectrum_csv {path}: cannot read ({err})") from None
    rows, headers = [], []
    for number, line in enumerate(text.splitlines(), 1):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        parts = [p for p in line.replace(";", ",").replace("\t", ",").split(",") if p.strip()]
        if len(parts) == 1:
            parts = line.split()
        try:
            values = [float(p) for p in parts]
        except ValueError:
            if not rows and not headers:  # a header line
                headers.append(number)
                continue
            if not rows:  # a second header line: the table is not what it seems (two tables? a note?)
                raise TargetError(f"{path}: line {number}: a second header line ({line!r}); a spectrum table "
                                  f"has one header line at most (line {headers[0]}), then 'period_s, sa_g' "
                                  "rows") from None
            raise TargetError(f"{path}: line {number}: not two numbers ({line!r})") from None
        if len(values) != 2:
            raise TargetError(f"{path}: line {number}: expected 'period_s, sa_g', got {len(values)} values")
        rows.append(values)
    table = np.array(rows, dtype=np.float64).reshape(-1, 2)
    if table.shape[0] < 2:
        raise TargetError(f"{path}: a spectrum table needs at least two rows (period s, Sa g)")
    if np.any(~np.isfinite(table)) or np.any(table <= 0):
        raise TargetError(f"{path}: periods and Sa must be finite and > 0")
    if np.any(np.diff(table[:, 0]) <= 0):
        raise TargetError(f"{path}: periods must increase strictly")
    return table[:, 0], table[:, 1]


def load_target(path) -> Target:
    """Read TARGET.toml (see the module docstring), with the controlling magnitude and distance ranges."""
    import dataclasses

    from isolator.design import load_toml

    mapping = load_toml(path, "target file", TargetError)
    controlling = {}
    for key in RANGE_KEYS:
        if key not in mapping:
            continue
        value = mapping[key]
        if not (isinstance(value, list) and len(value) == 2 and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v >= 0
                for v in value) and value[0] <= value[1]):
            raise TargetError(f"{path}: key '{key}' must be [low, high] with 0 ≤ low ≤ high, got {value!r}")
        quantity = key.removesuffix("_range")
        for end in value:
            problem = "" if end == value[0] == 0 else outside_earthquake(quantity, end)
            if problem:
                raise TargetError(f"{path}: key '{key}' end {end:g} is {problem}")
        controlling[key] = [float(v) for v in value]
    if "mechanisms" in mapping:
        value = mapping["mechanisms"]
        if not (isinstance(value, list) and value and all(isinstance(v, str) and v.strip() for v in value)):
            raise TargetError(f"{path}: key 'mechanisms' must be a list of texts (e.g. [\"strike-slip\"]), "
                              f"got {value!r}")
        controlling["mechanisms"] = [v.strip() for v in value]
    target = _load_spectrum(path)
    return dataclasses.replace(target, controlling=controlling) if controlling else target


def _load_spectrum(path) -> Target:
    """Read TARGET.toml (see the module docstring).

    Raises
    ------
    TargetError
        One line naming the file and the key.
    """
    from isolator.design import load_toml

    path = Path(path)
    source = str(path)
    mapping = load_toml(path, "target file", TargetError)
    unknown = sorted(set(mapping) - TARGET_KEYS)
    if unknown:
        raise TargetError(f"{source}: unknown key '{unknown[0]}'{key_hint(unknown[0], sorted(TARGET_KEYS))}")
    name = mapping.get("name", path.stem)
    if not isinstance(name, str):
        raise TargetError(f"{source}: key 'name' must be text")

    def number(key):
        value = mapping[key]
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
            raise TargetError(f"{source}: key '{key}' must be a number > 0, got {value!r}")
        if key.startswith("T_"):
            (lo, hi), what = TARGET_PERIOD_RANGE_S, "a period [s]"
        elif key == "S":
            (lo, hi), what = (0.5, 5.0), "a soil factor (EN 1998-1 Table 3.2: 1 to 1.8)"
        else:
            (lo, hi), what = TARGET_SA_RANGE_G, "a spectral acceleration [g]"
        if not lo <= value <= hi:
            raise TargetError(f"{source}: key '{key}' = {value:g} is outside [{lo:g}, {hi:g}], {what}")
        return float(value)

    forms = {"two-period MCE_R (S_MS, S_M1, T_L)": ("S_MS", "S_M1", "T_L"),
             "design values (S_DS, S_D1, T_L)": ("S_DS", "S_D1", "T_L"),
             "EN 1998-1 (a_g_g, S, T_B, T_C, T_D)": ("a_g_g", "S", "T_B", "T_C", "T_D"),
             "table (spectrum_csv)": ("spectrum_csv",)}
    present = [label for label, keys in forms.items() if any(k in mapping for k in keys if k != "T_L")]
    if len(present) != 1:
        raise TargetError(f"{source}: give exactly one target: " + "; or ".join(forms)
                          + (f" (found {', '.join(present)})" if present else ""))
    keys = forms[present[0]]
    missing = [k for k in keys if k not in mapping]
    if missing:
        raise TargetError(f"{source}: missing key '{missing[0]}' for the {present[0]} target")
    if keys[0] in ("S_MS", "S_DS"):
        # the numbers first: their messages name the file (inside the `try` they named it twice, "t.toml: t.toml:
        # key 'S_MS' …"; session 24 sweep)
        short, long_, t_l = (number(key) for key in keys)
        factor = 1.0 if keys[0] == "S_MS" else 1.5  # MCE_R = 1.5 × design spectrum (REVIEW_RULES 1.1)
        try:
            target = two_period_target(factor * short, factor * long_, t_l)
        except TargetError as err:
            raise TargetError(f"{source}: {err}") from None
        extra = None if keys[0] == "S_MS" else {"from_design_values": {"S_DS": mapping["S_DS"],
                                                                       "S_D1": mapping["S_D1"]}}
        return _named(target, name, source, extra=extra)
    if keys[0] == "a_g_g":
        values = {k: number(k) for k in keys}
        if not values["T_B"] < values["T_C"] < values["T_D"]:
            raise TargetError(f"{source}: need T_B < T_C < T_D")
        return Target("en1998-elastic", values, name=name, source=source)
    csv = mapping["spectrum_csv"]
    if not isinstance(csv, str):
        raise TargetError(f"{source}: key 'spectrum_csv' must be a file name")
    periods, sa = _read_csv(path.parent / csv, source)
    return Target("table", {"spectrum_csv": csv}, name=name, source=source, periods_s=periods, sa_table_g=sa)


def _named(target: Target, name: str, source: str, extra: dict | None = None) -> Target:
    return Target(target.kind, {**target.parameters, **(extra or {})}, name=name, source=source)
