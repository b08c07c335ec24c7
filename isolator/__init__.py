"""isolator: exact event-driven analysis of friction isolators under ground motion.

The physics is M. Nicolas (2017), *A comprehensive study on the behavior of a rigid
block on an oscillating ground with friction, elastic and viscous forces*
(hal-01432172), generalised from harmonic to recorded ground acceleration.
"""

from __future__ import annotations

__version__ = "0.1.0"
