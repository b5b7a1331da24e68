"""Shaft speed over the input angle: constant, or a periodic profile.

A speed profile is given as samples of ``omega`` at evenly spaced input angles
over one period; it is interpolated by a periodic cubic spline in the angle,
so that ``d omega / d theta`` and ``d2 omega / d theta2`` are continuous. The
time derivatives follow from the chain rule ``d/dt = omega d/dtheta``:

    omega_dot  = omega omega_theta
    omega_ddot = omega (omega_theta^2 + omega omega_thetatheta)
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.errors import ParameterError

__all__ = ["shaft_speed", "mean_speed", "SPEED_MIN", "SPEED_MAX"]

#: Admissible shaft speeds [rad/s]: 0.01 rpm to 100 000 rpm.
SPEED_MIN, SPEED_MAX = 0.01 * np.pi / 30.0, 1e5 * np.pi / 30.0


def shaft_speed(theta, speed, period: float):
    """Shaft speed and its first two time derivatives at the input angles.

    Parameters
    ----------
    theta : array_like, shape (...)
        Input angle [rad].
    speed : float or sequence of float
        A constant speed [rad/s], or samples of the speed at
        ``theta_k = k period / n``, ``k = 0 .. n-1`` (periodic, so the sample at
        ``period`` is the first one again) [rad/s]; each ``SPEED_MIN <= omega <=
        SPEED_MAX`` (0.01 rpm to 100 000 rpm).
    period : float
        Period of the profile in the input angle [rad].

    Returns
    -------
    (omega, omega_dot, omega_ddot) : tuple of ndarray, shape (...)
        [rad/s, rad/s^2, rad/s^3].
    """
    theta = np.asarray(theta, dtype=float)
    samples = np.atleast_1d(np.asarray(speed, dtype=float))
    if samples.ndim != 1 or samples.size == 0 or not np.all(np.isfinite(samples)):
        raise ParameterError(
            "run.speed", _in_rpm(samples), "a finite speed or a list of finite speeds"
        )
    if np.any(samples <= 0):
        raise ParameterError("run.speed", _in_rpm(samples), "speeds > 0 (the shaft turns one way)")
    slack = 1e-12  # the bounds as written in rpm, converted
    if np.any((samples < SPEED_MIN * (1 - slack)) | (samples > SPEED_MAX * (1 + slack))):
        raise ParameterError(
            "run.speed",
            _in_rpm(samples),
            "0.01 rpm <= speed <= 100000 rpm (beyond, times and accelerations of the period "
            "leave the floating-point range)",
        )
    if samples.size == 1:
        omega = np.full(theta.shape, samples[0])
        return omega, np.zeros(theta.shape), np.zeros(theta.shape)
    if samples.size < 3:
        raise ParameterError(
            "run.speed", f"{samples.size} samples", "one speed, or at least 3 samples"
        )
    from scipy.interpolate import CubicSpline

    nodes = np.linspace(0.0, period, samples.size + 1)
    spline = CubicSpline(nodes, np.append(samples, samples[0]), bc_type="periodic")
    phase = np.mod(theta, period)
    omega = spline(phase)
    w1 = spline(phase, 1)
    w2 = spline(phase, 2)
    return omega, omega * w1, omega * (w1**2 + omega * w2)


def mean_speed(speed, period: float, samples: int = 20_001) -> float:
    """Time-averaged shaft speed over one ``period`` of a speed (constant or profile) [rad/s]."""
    theta = np.linspace(0.0, period, samples)
    omega = shaft_speed(theta, speed, period)[0]
    return float(period / np.trapezoid(1.0 / omega, theta))


def _in_rpm(samples: np.ndarray) -> str:
    """The speed as a person reads it in a message: rpm, not the rad/s used inside."""
    values = [f"{v * 30.0 / np.pi:.6g}" for v in np.ravel(samples)]
    return f"{values[0]} rpm" if len(values) == 1 else f"[{', '.join(values)}] rpm"
