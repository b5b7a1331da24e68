"""Helpers shared by the studies."""

from __future__ import annotations

import numpy as np

from rotorkin.errors import ParameterError

__all__ = ["build_params", "angle_grid"]


def build_params(cls, section: str, values: dict, aliases: dict | None = None):
    """Build a parameter dataclass, naming the config key in any error.

    Parameters
    ----------
    cls : type
        Frozen parameter dataclass whose ``__post_init__`` raises
        :class:`~rotorkin.errors.ParameterError` named by field.
    section : str
        Config section the values come from (``"drive"``).
    values : dict
        Field name -> value (SI).
    aliases : dict, optional
        Field name -> config key where they differ (``{"lam": "lambda"}``).
    """
    aliases = aliases or {}
    try:
        return cls(**values)
    except ParameterError as exc:
        key = aliases.get(exc.name, exc.name)
        if "." not in key:
            key = f"{section}.{key}"
        raise ParameterError(key, exc.value, exc.admissible) from None


def angle_grid(period: float, points: int) -> np.ndarray:
    """``points`` input angles from 0 to ``period`` inclusive [rad]."""
    return np.linspace(0.0, period, int(points))
