"""The bundled review example: a target (ASCE 7-22 MCE_R) and a suite of 8 real record pairs."""

from __future__ import annotations

import os
from pathlib import Path

DATA = Path(__file__).resolve().parents[1] / "data"
EXAMPLES = {"target": DATA / "targets" / "example.toml", "suite": DATA / "suites" / "example" / "suite.toml"}


def resolve_example(kind: str, argument: str) -> str:
    """``example`` names the bundled target or suite (``kind`` "target" or "suite"); anything else is returned.

    A file or folder named ``example`` in the working folder is what the user names: it is read, not
    the bundled example (issue 26: ``--suite example`` took the bundled suite over ``./example``).
    """
    if argument == "example" and not os.path.lexists(argument):
        return str(EXAMPLES[kind])
    return str(argument)
