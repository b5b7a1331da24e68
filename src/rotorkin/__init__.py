"""rotorkin: drives of rotary variable-volume machines.

Exact kinematics (positions and three derivatives with respect to the input
angle) of the four drives of the source papers, the chambers they breathe, the
torque they carry and the cams that make them.
"""

from rotorkin.core.errors import ConfigError, ParameterError, RotorkinError
from rotorkin.core.motion import Motion

__version__ = "0.1.0"

__all__ = ["ConfigError", "Motion", "ParameterError", "RotorkinError", "__version__"]
