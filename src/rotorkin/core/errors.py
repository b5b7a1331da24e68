"""Error family of rotorkin.

Every error a user can cause derives from :class:`RotorkinError`. Messages are
one line and name the offending parameter, its value and what is admissible;
the command line turns them into one line on stderr and exit code 2.
"""

from __future__ import annotations

__all__ = ["RotorkinError", "ParameterError", "ConfigError", "shown"]


class RotorkinError(Exception):
    """Base class of every error rotorkin raises on purpose."""


class ParameterError(RotorkinError, ValueError):
    """A model parameter outside its admissible range.

    Parameters
    ----------
    name : str
        The parameter's name as the user knows it (config key or field name).
    value : object
        The offending value, already formatted for people where useful
        (e.g. ``"70 deg"``).
    admissible : str
        What would be accepted, e.g. ``"0.5 deg <= plate_tilt < 65.53 deg"``.
    """

    def __init__(self, name: str, value: object, admissible: str):
        self.name = name
        self.value = value
        self.admissible = admissible
        super().__init__(f"{name} = {value} is not admissible: {admissible}")


class ConfigError(RotorkinError):
    """A configuration that cannot be read: unknown key, wrong type, missing unit, bad file."""


def shown(text, most: int = 80) -> str:
    """A user's string, quoted for a one-line message and cut to ``most`` characters."""
    text = str(text)
    return repr(text if len(text) <= most else text[: most - 3] + "...")
