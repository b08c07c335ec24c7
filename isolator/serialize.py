"""JSON-safe values: the one place where results are turned into what JSON can hold.

Every JSON that isolator writes (``--json`` outputs, the report JSON, batch part files,
the bench document) goes through :func:`json_safe`, so the same value is written the
same way everywhere: NaN and ±inf become ``null``, NumPy scalars become Python ones,
tuples become lists and dict keys become strings.
"""

from __future__ import annotations

import json
import math


def finite_or_none(value) -> float | None:
    """``float(value)`` if it is finite, otherwise ``None`` (JSON's null) [-]."""
    value = float(value)
    return value if math.isfinite(value) else None


def json_safe(value):
    """A copy of ``value`` that :func:`json.dumps` writes with ``allow_nan=False``.

    Parameters
    ----------
    value : object
        Floats, ints, bools, strings, None, NumPy scalars, dicts, lists, tuples (nested) [-].

    Returns
    -------
    object
        The same structure with non-finite floats as None, NumPy scalars as Python
        scalars, tuples as lists and dict keys as strings; any other object is left as
        it is (``json.dumps`` then says which type it cannot write).
    """
    if isinstance(value, float):  # numpy.float64 is a float too: written as a plain float
        return float(value) if math.isfinite(value) else None
    if isinstance(value, dict):
        return {str(key): json_safe(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(item) for item in value]
    if hasattr(value, "item") and not isinstance(value, (str, bytes)) and getattr(value, "ndim", 0) == 0:
        return json_safe(value.item())
    return value


def dumps(value, **options) -> str:
    """``json.dumps(json_safe(value), allow_nan=False, **options)``: strict JSON, never NaN."""
    return json.dumps(json_safe(value), allow_nan=False, **options)
