"""Example records that resolve without a file of the user's: real records shipped by a dependency.

``example:knet`` is the K-NET record bundled with obspy's test data (no download).
"""

from __future__ import annotations

from isolator.errors import RecordNotFoundError

#: Record names that resolve without a file of the user's: (module, path parts, label).
EXAMPLE_RECORDS = {
    "example:knet": ("obspy.io.nied", ("tests", "data", "test.knet"),
                     "test.knet (obspy's K-NET sample)"),
}


def resolve_record(argument: str) -> tuple[str, str]:
    """A record argument → (path, label); ``example:knet`` is obspy's bundled K-NET record.

    Parameters
    ----------
    argument : str
        A file path, or one of :data:`EXAMPLE_RECORDS` [-].

    Returns
    -------
    (str, str)
        The file path and the label shown in reports [-].

    Raises
    ------
    RecordNotFoundError
        An unknown ``example:`` name, or the bundled file missing from the installation.
    """
    if not argument.startswith("example:"):
        return argument, argument
    if argument not in EXAMPLE_RECORDS:
        raise RecordNotFoundError(f"unknown example record {argument!r} (choose one of: "
                                  f"{', '.join(EXAMPLE_RECORDS)})", path=argument)
    import importlib
    from pathlib import Path

    module, parts, label = EXAMPLE_RECORDS[argument]
    path = Path(importlib.import_module(module).__file__).parent.joinpath(*parts)
    if not path.is_file():
        raise RecordNotFoundError(f"{argument}: the bundled file {path} is missing from this installation",
                                  path=argument)
    return str(path), label
