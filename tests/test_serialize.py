"""isolator.serialize: the one JSON-safe helper."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from isolator.serialize import dumps, finite_or_none, json_safe


def test_json_safe_values():
    value = {"a": np.float64(1.5), 2: [np.int32(3), (math.nan, -math.inf)], "b": np.bool_(True), "c": "text",
             "d": None}
    safe = json_safe(value)
    assert safe == {"a": 1.5, "2": [3, [None, None]], "b": True, "c": "text", "d": None}
    assert type(safe["a"]) is float and type(safe["2"][0]) is int and type(safe["b"]) is bool
    assert json.loads(dumps(value)) == safe
    assert finite_or_none(np.float32(2.0)) == 2.0 and finite_or_none(math.inf) is None


def test_strict_json_refuses_what_it_cannot_write():
    with pytest.raises(TypeError):
        dumps({"array": np.zeros(3)})  # arrays are not silently turned into text
