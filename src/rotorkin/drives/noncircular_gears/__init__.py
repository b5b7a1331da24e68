"""Non-circular gears: two gear pairs from the output shaft to two coaxial rotors.

The classic drive of cat-and-mouse (scissor) engines and differential pumps:
n-lobed "modified ellipses" (Litvin et al. 2009) rolling on conjugate driven
gears, phase-shifted on the shaft. :mod:`.kinematics` holds the pitch curves,
the rotors' motion with exact derivatives and the convexity checks; any vane
machine runs on it (:mod:`rotorkin.vane`).
"""

from rotorkin.drives.noncircular_gears.kinematics import NoncircularGears, motion, period
from rotorkin.drives.noncircular_gears.spec import SPEC

__all__ = ["NoncircularGears", "motion", "period", "SPEC"]
