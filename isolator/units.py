"""Physical constants and unit conversions: the one place where units are named.

Every quantity inside isolator is SI: metres, seconds, kilograms, m/s² for
accelerations.  Conversions from the units engineers meet in record files happen
here and nowhere else.
"""

from __future__ import annotations

STANDARD_GRAVITY = 9.80665  # m/s², standard gravity (CGPM 1901); also converts records in g

#: Factor that turns one unit of acceleration into m/s².
ACCELERATION_UNITS_TO_M_S2: dict[str, float] = {
    "g": STANDARD_GRAVITY,
    "m/s2": 1.0,
    "m/s**2": 1.0,
    "m/s^2": 1.0,
    "cm/s2": 0.01,
    "cm/s**2": 0.01,
    "cm/s^2": 0.01,
    "gal": 0.01,
    "mm/s2": 0.001,
}

#: Spellings accepted on the command line (``--units``) and in metadata.
ACCELERATION_UNIT_CHOICES = ("g", "m/s2", "gal", "cm/s2")


from isolator.errors import UnitsError  # noqa: E402,F401 - defined with the other typed errors


def acceleration_factor_to_m_s2(units: str) -> float:
    """Factor that converts an acceleration in ``units`` to m/s².

    Parameters
    ----------
    units : str
        One of ``g``, ``m/s2``, ``gal``, ``cm/s2`` (case-insensitive; ``m/s**2`` and
        ``m/s^2`` spellings are accepted too).

    Returns
    -------
    float
        Multiply a value in ``units`` by this to get m/s² [m/s² per unit].
    """
    key = units.strip().lower().replace(" ", "")
    if key not in ACCELERATION_UNITS_TO_M_S2:
        choices = ", ".join(ACCELERATION_UNIT_CHOICES)
        raise UnitsError(f"unknown acceleration unit {units!r} (choose one of: {choices})")
    return ACCELERATION_UNITS_TO_M_S2[key]
