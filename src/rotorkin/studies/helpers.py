"""Helpers shared by the studies."""

from __future__ import annotations

import numpy as np

from rotorkin.analysis.timing import shaft_speed
from rotorkin.core.errors import ParameterError

__all__ = ["build_params", "angle_grid", "time_domain", "time_peaks", "time_peak_keys",
           "undefined_warnings"]  # fmt: skip


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
    columns, docs = {}, {}
    columns["shaft_speed_rpm"] = omega[0] * 30.0 / np.pi
    docs["shaft_speed_rpm"] = "input shaft speed"
    for k, slug in enumerate(slugs):
        name = motion.members[k]
        for label, values, what in (("speed", v[k], "velocity"), ("accel", a[k], "acceleration"),
                                    ("jerk", j[k], "jerk")):  # fmt: skip
            key = f"{slug}_{label}_{u}_per_s{_POWER[label]}"
            columns[key] = values
            docs[key] = f"{what} of {name} in time, at the shaft speed of shaft_speed_rpm"
    summary = {k: float(x) for k, x in time_peaks(motion, omega, slugs, (v, a, j)).items()}
    return columns, docs, summary, omega


_POWER = {"speed": "", "accel": "2", "jerk": "3"}


def _peak_key(slug: str, label: str, unit: str) -> str:
    return f"{slug}_{label}_peak_{unit}_per_s{_POWER[label]}"


def time_peak_keys(slugs, unit: str = "rad") -> tuple[str, ...]:
    """The keys of :func:`time_peaks` for members ``slugs`` moving in ``unit``, in order."""
    return (*(_peak_key(slug, label, unit) for slug in slugs for label in _POWER),
            "shaft_speed_mean_rpm")  # fmt: skip


def time_peaks(motion, omega, slugs, rates=None) -> dict:
    """Peaks of the members' velocity, acceleration and jerk in time; the mean shaft speed.

    For one design or many: the peaks are over the last axis (the angles), so a
    motion of shape ``(2, d, n)`` (designs as columns against ``n`` angles) gives
    arrays ``(d,)``.

    Parameters
    ----------
    motion : rotorkin.core.motion.Motion
        Motion of the two members over one period, ends included.
    omega : tuple of array_like
        ``(omega, omega_dot, omega_ddot)`` at the angles (broadcasting with ``motion.q[0]``).
    slugs : tuple of str
        Key stems of the two members.
    rates : tuple of ndarray, optional
        ``motion.in_time(*omega)`` if already at hand.

    Returns
    -------
    dict
        ``<slug>_speed_peak_<u>_per_s``, ``_accel_peak_<u>_per_s2``,
        ``_jerk_peak_<u>_per_s3`` (u the motion's unit) and ``shaft_speed_mean_rpm``
        (the mean over the period's samples, the end left out).
    """
    v, a, j = motion.in_time(*omega) if rates is None else rates
    out = {}
    for k, slug in enumerate(slugs):
        for label, values in (("speed", v[k]), ("accel", a[k]), ("jerk", j[k])):
            out[_peak_key(slug, label, motion.unit)] = np.max(np.abs(values), axis=-1)
    w = np.broadcast_to(np.asarray(omega[0], dtype=float), np.shape(v[0]))
    out["shaft_speed_mean_rpm"] = np.mean(w[..., :-1], axis=-1) * 30.0 / np.pi
    return out


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
