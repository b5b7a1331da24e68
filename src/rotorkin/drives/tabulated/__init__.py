"""Tabulated drive: the angles of two rotors versus the shaft angle, given by the user.

The motion comes from a CSV table (a CAD motion study, a measured rig, another
program, rotorkin's own ``motion.csv``) or directly as a Fourier series; both become
one :class:`rotorkin.drives.tabulated.law.FourierLaw`, whose
:func:`~rotorkin.drives.tabulated.law.motion` gives the member angles and their exact
first to third derivatives with respect to the shaft angle.
"""

from rotorkin.drives.tabulated.law import FourierLaw, from_csv, from_fourier, from_table
from rotorkin.drives.tabulated.spec import SPEC

__all__ = ["FourierLaw", "from_csv", "from_fourier", "from_table", "SPEC"]
