"""Names of the components of a record: channel codes, orientations, labels, verticals.

The lowest layer of :mod:`isolator.motion`: it reads only a trace's ``stats`` (any
format) or a label string, and imports nothing of isolator.  The reader
(:mod:`isolator.motion.read`), the pairs (:mod:`isolator.motion.pair`) and file
discovery (:mod:`isolator.motion.files`) share it.
"""

from __future__ import annotations

import re

UNNAMED_COMPONENT = "unnamed"  # label of the one component of a file that names none
#: Orientation names of a vertical component (lower case tokens of a component label).
VERTICAL_NAMES = frozenset({"up", "down", "ud", "u-d", "vert", "vertical", "z", "v", "dwn"})
#: Format headers (``stats.<key>``) and the attribute that holds the orientation in each.
_ORIENTATION_KEYS = (("peer_at2", "component"), ("csmip_v2", "orientation"), ("usgs_smc", "component"),
                     ("isolator_text", "component"))


def component_names(trace) -> dict[str, str]:
    """Channel code and orientation (component name) of an obspy trace, whatever its format.

    Parameters
    ----------
    trace : obspy.Trace
        A trace as a reader returns it (format header in ``stats.<format>``) [-].

    Returns
    -------
    dict
        ``{"channel": …, "orientation": …}``, "" where the file names none [-].
    """
    stats = trace.stats
    orientation = ""
    for key, attribute in _ORIENTATION_KEYS:
        if key in stats:
            orientation = str(stats[key].get(attribute, "") or "")
            break
    return {"channel": stats.channel or "", "orientation": orientation}


def component_label(trace) -> str:
    """How a component is shown to the user: channel code, orientation, or ``"HN1 (180)"`` [-]."""
    names = component_names(trace)
    channel, orientation = names["channel"], names["orientation"]
    if channel and orientation and orientation.lower() != channel.lower():
        return f"{channel} ({orientation})"
    return channel or orientation or UNNAMED_COMPONENT


def axis_letter(name: str) -> str:
    """N, E or Z for an orientation name: azimuths on the N-S (0, 180, 360) or E-W (90, 270)
    axis, K-NET's NS/EW/UD, Up/Down; "" otherwise [-]."""
    name = name.strip().upper()
    if name in ("NS", "N-S"):
        return "N"
    if name in ("EW", "E-W"):
        return "E"
    if name in ("UD", "U-D", "UP", "DOWN", "VERT", "Z"):
        return "Z"
    try:
        azimuth_deg = float(name)
    except ValueError:
        return ""
    remainder = azimuth_deg % 180.0
    return "N" if remainder == 0.0 else ("E" if remainder == 90.0 else "")


def label_is_vertical(label: str) -> bool:
    """True for a vertical component label of :func:`~isolator.motion.list_components` (Z, UD, U-D,
    Up, Down, Vert, or a channel code ending in Z: ``HNZ (Up)``); the label-level twin of
    :func:`is_vertical`."""
    text = label.upper()
    orientation = re.search(r"\(([^)]*)\)", text)
    names = [text.split(" (")[0].strip()] + ([orientation.group(1).strip()] if orientation else [])
    for name in names:
        if name in ("Z", "UD", "U-D", "UP", "DOWN", "VERT", "VERTICAL", "V"):
            return True
        if len(name) == 3 and name.isalpha() and name.endswith("Z"):
            return True
    return False


def is_vertical(motion) -> bool:
    """True when a :class:`~isolator.motion.GroundMotion`'s label or channel code names the
    vertical (Up, UD, HNZ, …)."""
    channel = str(motion.provenance.get("channel", "") or "")
    if len(channel) == 3 and channel[2].upper() == "Z":
        return True
    tokens = re.findall(r"[a-z0-9-]+", motion.component.lower())
    return any(token in VERTICAL_NAMES for token in tokens)
