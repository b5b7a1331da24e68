"""Helpers shared by the studies."""

from __future__ import annotations

import numpy as np

from rotorkin.analysis.timing import shaft_speed
from rotorkin.core.errors import ParameterError

__all__ = ["build_params", "angle_grid", "time_domain", "undefined_warnings"]


def build_params(cls, section: str, values: dict, aliases: dict | None = None):
    """Build a parameter dataclass, naming the config key in any error.

    Parameters
    ----------
    cls : type
        Frozen parameter dataclass whose ``__post_init__`` raises
        :class:`~rotorkin.core.errors.ParameterError` named by field.
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


def time_domain(motion, speed, slugs, period):
    """Columns and peaks of member velocity, acceleration and jerk in time.

    Parameters
    ----------
    motion : rotorkin.core.motion.Motion
        Motion over one period (1-d ``theta``).
    speed : float or sequence of float
        ``cfg["run"]["speed"]``: constant shaft speed or a profile [rad/s].
    slugs : tuple of str
        Column stems of the two members, e.g. ``("rotor1", "rotor2")``.
    period : float
        Period of the input angle [rad].

    Returns
    -------
    (columns, summary, omega) : dict, dict, tuple
        Columns ``<slug>_speed_<u>_per_s``, ``_accel_<u>_per_s2``, ``_jerk_<u>_per_s3``
        (u = rad or m) with their docs, peak values for the summary, and
        ``(omega, omega_dot, omega_ddot)`` at the samples.
    """

    omega = shaft_speed(motion.theta, speed, period)
    v, a, j = motion.in_time(*omega)
    u = motion.unit
    columns, docs, summary = {}, {}, {}
    columns["shaft_speed_rpm"] = omega[0] * 30.0 / np.pi
    docs["shaft_speed_rpm"] = "input shaft speed"
    for k, slug in enumerate(slugs):
        name = motion.members[k]
        for label, values, suffix, what in (
            ("speed", v[k], f"{u}_per_s", "velocity"),
            ("accel", a[k], f"{u}_per_s2", "acceleration"),
            ("jerk", j[k], f"{u}_per_s3", "jerk"),
        ):
            key = f"{slug}_{label}_{suffix}"
            columns[key] = values
            docs[key] = f"{what} of {name} in time, at the shaft speed of shaft_speed_rpm"
            summary[f"{slug}_{label}_peak_{suffix}"] = float(np.max(np.abs(values)))
    summary["shaft_speed_mean_rpm"] = float(np.mean(omega[0][:-1]) * 30.0 / np.pi)
    return columns, docs, summary, omega


#: Why a summary key shared by several drives can have no value.
UNDEFINED_BECAUSE = {
    "torque_ripple": "the mean shaft torque is 0, so (max - min) / mean has no value",
    "torque_ripple_with_inertia": "the mean shaft torque is 0, so (max - min) / mean has no value",
    "mechanical_efficiency": "the machine does no net work on the shaft, so work delivered "
    "over work put in has no value",
    "speed_fluctuation_without_flywheel": "every inertia of [machine] is 0 (inertia_shaft and "
    "the members'), so nothing bounds the speed",
}


def undefined_warnings(summary: dict, because: dict | None = None) -> tuple[str, ...]:
    """One warning line per summary value that is not finite, saying why.

    Parameters
    ----------
    summary : dict
        A study's summary.
    because : dict, optional
        Summary key -> the model input that leaves it without a value (naming the
        config key to set); :data:`UNDEFINED_BECAUSE` covers the shared keys.
    """
    reasons = {**UNDEFINED_BECAUSE, **(because or {})}
    out = []
    for key, value in summary.items():
        if isinstance(value, (float, np.floating)) and not np.isfinite(value):
            out.append(f"{key} is not defined: {reasons.get(key, 'a model input makes it so')}")
    return tuple(out)
