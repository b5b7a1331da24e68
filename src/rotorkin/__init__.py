"""rotorkin: drives of rotary variable-volume machines.

Exact kinematics (positions and three derivatives with respect to the input
angle) of the four drives of the source papers, the chambers they breathe, the
torque they carry and the cams that make them.
"""

from rotorkin.core.errors import ConfigError, ParameterError, RotorkinError

#: The package's version: the one place it is written (pyproject.toml reads it from here).
__version__ = "0.1.0"

__all__ = ["ConfigError", "Motion", "ParameterError", "RotorkinError", "__version__"]


def __getattr__(name: str):
    # Motion needs numpy: imported on first use, so that ``rotorkin --help`` starts fast
    if name == "Motion":
        from rotorkin.core.motion import Motion

        return Motion
    raise AttributeError(f"module 'rotorkin' has no attribute {name!r}")
