"""Torques by virtual work, inertia of the members seen at the shaft, work and ripple.

Sign convention: a torque on the input shaft is positive when it acts in the
sense of rotation (it drives the shaft). The gas in chamber ``j`` at pressure
``p_j`` does work ``p_j dV_j`` on the mechanism, so its torque on the input
shaft is ``p_j dV_j/dtheta``: positive while a chamber expands under pressure
(an engine's power stroke), negative while the shaft compresses it (a pump).
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "gas_torque",
    "member_torques",
    "shaft_torque_from_members",
    "equivalent_inertia",
    "inertia_torque",
    "kinetic_energy",
    "cycle_integral",
    "torque_ripple",
    "SHAFT_TORQUE_KEYS",
    "shaft_torque_summary",
]


def gas_torque(pressure, dvolume):
    """Torque of the chamber pressures on the input shaft, ``sum_j p_j dV_j/dtheta``.

    Parameters
    ----------
    pressure : array_like, shape (n_chambers, ...)
        Absolute chamber pressures [Pa].
    dvolume : array_like, shape (n_chambers, ...)
        ``dV_j / dtheta`` [m^3/rad].

    Returns
    -------
    ndarray, shape (...)
        [N*m], positive when the gas drives the shaft.
    """
    return np.sum(np.asarray(pressure) * np.asarray(dvolume), axis=0)


def member_torques(pressure, dvolume_dq):
    """Generalized forces of the chamber pressures on the working members.

    ``M_i = sum_j p_j dV_j/dq_i``: the torque (or force, for a piston) the gas
    exerts on member ``i`` in the sense of increasing ``q_i``.

    Parameters
    ----------
    pressure : array_like, shape (n_chambers, ...)
        [Pa].
    dvolume_dq : array_like, shape (n_members, n_chambers, ...)
        Partial derivatives of each chamber volume with respect to each member
        position [m^3/rad or m^2].

    Returns
    -------
    ndarray, shape (n_members, ...)
        [N*m or N].
    """
    return np.sum(np.asarray(dvolume_dq) * np.asarray(pressure)[None], axis=1)


def shaft_torque_from_members(member_torque, dq):
    """Torque on the input shaft from member torques by virtual work, ``sum_i M_i q_i'``.

    Parameters
    ----------
    member_torque : array_like, shape (n_members, ...)
        [N*m or N].
    dq : array_like, shape (n_members, ...)
        Kinematic coefficients ``dq_i/dtheta`` [rad/rad or m/rad].

    Returns
    -------
    ndarray, shape (...)
        [N*m].
    """
    return np.sum(np.asarray(member_torque) * np.asarray(dq), axis=0)


def equivalent_inertia(inertia_shaft, inertia_members, dq):
    """Inertia seen at the shaft, ``J_eq = J_shaft + sum_i J_i q_i'^2``.

    Parameters
    ----------
    inertia_shaft : float or array_like
        [kg*m^2]; an array broadcasts against ``dq[0]`` (e.g. (designs, 1)).
    inertia_members : array_like, shape (n_members,) or (n_members, ...)
        Moments of inertia [kg*m^2] (masses [kg] for pistons); trailing axes
        broadcast against those of ``dq`` (e.g. (n_members, designs, 1)).
    dq : array_like, shape (n_members, ...)
        Kinematic coefficients.

    Returns
    -------
    ndarray, shape (...)
        [kg*m^2].
    """
    j = _members(inertia_members, np.ndim(dq))
    return inertia_shaft + np.sum(j * np.asarray(dq) ** 2, axis=0)


def inertia_torque(inertia_shaft, inertia_members, dq, d2q, omega, omega_dot=0.0):
    """Torque the shaft must supply to move the members' inertia.

    From ``d/dt (1/2 J_eq omega^2) = omega * T_inertia``:

        T_inertia = sum_i J_i (q_i' q_i'' omega^2 + q_i'^2 omega_dot) + J_shaft omega_dot

    Parameters
    ----------
    inertia_shaft : float or array_like
        [kg*m^2]; broadcasts as in :func:`equivalent_inertia`.
    inertia_members : array_like, shape (n_members,) or (n_members, ...)
        [kg*m^2] (or [kg]); broadcast as in :func:`equivalent_inertia`.
    dq, d2q : array_like, shape (n_members, ...)
        First and second kinematic coefficients.
    omega, omega_dot : float or array_like, shape (...)
        Shaft speed and acceleration [rad/s, rad/s^2].

    Returns
    -------
    ndarray, shape (...)
        [N*m]: positive when the shaft gives energy to the members.
    """
    dq, d2q = np.asarray(dq), np.asarray(d2q)
    j = _members(inertia_members, dq.ndim)
    w, wd = np.asarray(omega, dtype=float), np.asarray(omega_dot, dtype=float)
    members = np.sum(j * (dq * d2q * w**2 + dq**2 * wd), axis=0)
    return members + inertia_shaft * wd


def _members(inertia_members, ndim: int) -> np.ndarray:
    """The members' inertias with trailing unit axes to broadcast against ``ndim``-d ``dq``."""
    j = np.asarray(inertia_members, dtype=float)
    return j.reshape(j.shape + (1,) * (ndim - j.ndim))


def kinetic_energy(inertia_shaft, inertia_members, dq, omega):
    """Kinetic energy of shaft and members, ``1/2 J_eq omega^2`` [J]."""
    return 0.5 * equivalent_inertia(inertia_shaft, inertia_members, dq) * np.asarray(omega) ** 2


def cycle_integral(values, theta, axis=-1):
    """Integral over one period sampled at ``theta`` (ends included), by the trapezoid rule.

    On a periodic smooth integrand the trapezoid rule over a full period is
    spectrally accurate.
    """
    return np.trapezoid(values, theta, axis=axis)


def torque_ripple(torque, axis=-1):
    """``(max - min) / |mean|`` of a torque over a period (NaN when the mean is 0).

    A mean below ``1e-12`` of the span counts as zero (round-off of a torque
    whose mean is zero in exact arithmetic).

    ``torque`` holds one period sampled with both ends included; the repeated
    end is left out of the mean.
    """
    t = np.asarray(torque, dtype=float)
    core = np.take(t, np.arange(t.shape[axis] - 1), axis=axis)
    mean = np.mean(core, axis=axis)
    span = np.max(t, axis=axis) - np.min(t, axis=axis)
    zero = np.abs(mean) <= 1e-12 * span
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(zero, np.nan, span / np.abs(mean))


#: The keys of :func:`shaft_torque_summary`, in order.
SHAFT_TORQUE_KEYS = (
    "torque_ripple",
    "torque_ripple_with_inertia",
    "shaft_torque_max_Nm",
    "shaft_torque_min_Nm",
    "shaft_torque_with_inertia_max_Nm",
    "shaft_torque_with_inertia_min_Nm",
)


def shaft_torque_summary(torque, with_inertia) -> dict:
    """Ripple and extremes of a shaft torque over a period, without and with inertia.

    ``torque`` is the torque of the loads alone (gas, fluid), ``with_inertia`` the same
    less the torque that accelerates the moving parts; both ``(..., n)`` over one period
    (ends included). Returns :data:`SHAFT_TORQUE_KEYS` -> arrays ``(...)``.
    """
    return {
        "torque_ripple": torque_ripple(torque),
        "torque_ripple_with_inertia": torque_ripple(with_inertia),
        "shaft_torque_max_Nm": np.max(torque, axis=-1),
        "shaft_torque_min_Nm": np.min(torque, axis=-1),
        "shaft_torque_with_inertia_max_Nm": np.max(with_inertia, axis=-1),
        "shaft_torque_with_inertia_min_Nm": np.min(with_inertia, axis=-1),
    }
