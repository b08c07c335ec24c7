"""Design files of the models with more than one number per quantity, shared by the report and batch tests:
a three-story building on a narrow bearing layout (docs/building.md) and the triple pendulum of Fenz &
Constantinou's backbone (docs/multisurface.md; R_eff 2.1/0.3/0.3/2.1 m, µ 0.06/0.02/0.02/0.10,
d* 0.4/0.05/0.05/0.4 m).  Under Northridge NWH360 scaled to 1.5 g the building's bearings lift off and
the triple pendulum passes regimes I-V to its ultimate displacement.
"""

from __future__ import annotations

import re

RIGID_BLOCK = """name = "FPS"
mass_kg = 1.6e6
radius_m = 2.5
mu_static = 0.06
"""

BUILDING = """name = "three stories on a narrow layout"
mass_kg = 1.6e6
radius_m = 2.5
mu_static = 0.06
mu_kinetic = 0.05
[superstructure]
damping_ratio = 0.05
[[superstructure.floor]]
mass_kg = 4.0e5
story_height_m = 4.0
stiffness_x_N_per_m = 6.0e8
[[superstructure.floor]]
mass_kg = 4.0e5
story_height_m = 3.5
stiffness_x_N_per_m = 5.0e8
[[superstructure.floor]]
mass_kg = 3.0e5
story_height_m = 3.5
stiffness_x_N_per_m = 4.0e8
[[bearing_position]]
x_m = -2.0
y_m = -6.0
[[bearing_position]]
x_m = 2.0
y_m = -6.0
[[bearing_position]]
x_m = 2.0
y_m = 6.0
[[bearing_position]]
x_m = -2.5
y_m = 6.0
"""

TRIPLE = """name = "TFP of Fenz and Constantinou"
mass_kg = 1.0e5
[bearing]
type = "triple"
[[bearing.surface]]
radius_m = 2.1
mu = 0.06
displacement_capacity_m = 0.4
[[bearing.surface]]
radius_m = 0.3
mu = 0.02
displacement_capacity_m = 0.05
[[bearing.surface]]
radius_m = 0.3
mu = 0.02
displacement_capacity_m = 0.05
[[bearing.surface]]
radius_m = 2.1
mu = 0.10
displacement_capacity_m = 0.4
"""

#: The record and the PGA [g] it is scaled to.
RECORD = "at2/RSN1044_NORTHR_NWH360.AT2"
SCALE_G = 1.5


def designs_file_text(*designs: str) -> str:
    """Design files as one batch designs file: each a ``[[design]]`` table, its tables moved under it."""
    out = []
    for text in designs:
        text = re.sub(r"^\[\[(.+)\]\]$", r"[[design.\1]]", text, flags=re.MULTILINE)
        text = re.sub(r"^\[([^\[\]]+)\]$", r"[design.\1]", text, flags=re.MULTILINE)
        out.append("[[design]]\n" + text)
    return "\n".join(out)
