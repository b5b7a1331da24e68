"""Energy fluctuation over a turn, coefficient of speed fluctuation, flywheel sizing.

The textbook model (e.g. Shigley, *Mechanical Engineering Design*, sec. on
flywheels): with the net torque ``T(theta) - T_mean`` on a shaft of inertia
``J`` turning at mean speed ``omega``, the kinetic energy swings by

    Delta E = max_theta E(theta) - min_theta E(theta),  E(theta) = int_0^theta (T - T_mean) dtheta

and the coefficient of speed fluctuation is
``C_s = (omega_max - omega_min) / omega_mean ~= Delta E / (J omega^2)``. A
flywheel for a chosen ``C_s`` therefore needs ``J = Delta E / (C_s omega^2)``,
less the inertia already on the shaft.
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.errors import ParameterError

__all__ = [
    "energy_fluctuation",
    "speed_fluctuation_coefficient",
    "flywheel_inertia",
]


def _cumulative(values, theta):
    dt = np.diff(theta)
    steps = 0.5 * (values[..., 1:] + values[..., :-1]) * dt
    return np.concatenate([np.zeros(values.shape[:-1] + (1,)), np.cumsum(steps, axis=-1)], -1)


def energy_fluctuation(torque, theta):
    """Largest swing of the kinetic energy over one period.

    Parameters
    ----------
    torque : array_like, shape (..., n)
        Net driving torque on the shaft over one period, ends included [N*m].
    theta : array_like, shape (n,)
        Input angles, from 0 to the period [rad].

    Returns
    -------
    ndarray, shape (...)
        ``Delta E`` [J].
    """
    torque = np.asarray(torque, dtype=float)
    theta = np.asarray(theta, dtype=float)
    period = theta[-1] - theta[0]
    mean = np.trapezoid(torque, theta, axis=-1) / period
    energy = _cumulative(torque - mean[..., None], theta)
    return np.max(energy, axis=-1) - np.min(energy, axis=-1)


def speed_fluctuation_coefficient(delta_energy, inertia, omega_mean):
    """``C_s = Delta E / (J omega_mean^2)`` [-]."""
    return np.asarray(delta_energy) / (np.asarray(inertia) * np.asarray(omega_mean) ** 2)


def flywheel_inertia(delta_energy, omega_mean, coefficient, inertia_present=0.0):
    """Flywheel inertia for a chosen coefficient of speed fluctuation.

    Parameters
    ----------
    delta_energy : float or array_like
        ``Delta E`` over a period [J].
    omega_mean : float or array_like
        Mean shaft speed [rad/s].
    coefficient : float or array_like
        Wanted ``C_s = (omega_max - omega_min)/omega_mean``, 0 < C_s < 1 [-].
    inertia_present : float or array_like, optional
        Inertia already on the shaft (mean of ``J_eq``) [kg*m^2].

    Returns
    -------
    ndarray
        Inertia to add [kg*m^2]; 0 when what is present already suffices.
    """
    c = np.asarray(coefficient, dtype=float)
    bad = ~((c > 0.0) & (c < 1.0))
    if np.any(bad):
        shown = coefficient if c.ndim == 0 else c[bad].flat[0]
        raise ParameterError("machine.speed_fluctuation", shown, "0 < speed_fluctuation < 1")
    need = np.asarray(delta_energy) / (coefficient * np.asarray(omega_mean) ** 2)
    return np.maximum(need - inertia_present, 0.0)
