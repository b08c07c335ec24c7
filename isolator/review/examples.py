"""The bundled review example: a target (ASCE 7-22 MCE_R) and a suite of 8 real record pairs."""

from __future__ import annotations

from pathlib import Path

DATA = Path(__file__).resolve().parents[1] / "data"
EXAMPLES = {"target": DATA / "targets" / "example.toml", "suite": DATA / "suites" / "example" / "suite.toml"}


def resolve_example(kind: str, argument: str) -> str:
    """``example`` names the bundled target or suite (``kind`` "target" or "suite"); anything else is returned."""
    return str(EXAMPLES[kind]) if argument == "example" else str(argument)
