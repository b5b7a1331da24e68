"""The rotary-blade engine on the rhomboid drive at a set of shaft angles: its loads'
torques on the blade pairs and the output shaft (one design, or columns of designs).

Used by the study (:mod:`rotorkin.drives.rhomboid_cam.study`) and the sweep kernel
(:mod:`rotorkin.drives.rhomboid_cam.sweep`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from rotorkin.analysis import torque as at
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.machines import rotary_blade as rb
from rotorkin.machines import rotary_blade_stirling as rbs

__all__ = ["Loads", "State", "machine_state"]


class Loads(NamedTuple):
    """The pressure model and its data.

    ``model`` is ``"linear"`` (paper, eq. 29: ``torque_high``, ``torque_low`` [N m]),
    ``"isothermal"`` (``gas`` and ``charge`` = ``m_j R`` per chamber [J/K]) or
    ``"adiabatic"`` / ``"schmidt"`` (``gas`` the :class:`~rotorkin.machines.rotary_blade.
    StirlingLoads`, ``stirling`` the solved circuits).
    """

    model: str
    torque_high: float
    torque_low: float
    gas: rb.IsothermalGas | rbs.StirlingLoads | None = None
    charge: np.ndarray | None = None
    stirling: rbs.StirlingSolution | None = None


class State(NamedTuple):
    """The machine at a set of output-shaft angles (see :func:`machine_state`)."""

    motion: object  # rotorkin.core.motion.Motion of the blade pairs
    stroke: np.ndarray  # +1 while psi rises, -1 while it falls
    volume: np.ndarray  # (2B, ...) [m^3]
    dvolume: np.ndarray  # (2B, ...) dV/dalpha [m^3/rad]
    pressure: np.ndarray | None  # (2B, ...) [Pa], None for the linear model
    members: np.ndarray  # (2, ...) torques on the blade pairs [N m]
    torque: np.ndarray  # (...) torque of the loads on the output shaft [N m]
    cold_volume: np.ndarray | None = None  # (2B, ...) cold set, Stirling models [m^3]
    cold_dvolume: np.ndarray | None = None  # (2B, ...) [m^3/rad]


def machine_state(params, machine, loads: Loads, alpha, stroke=None) -> State:
    """Volumes, pressures and torques at the output-shaft angles ``alpha`` (any shape).

    Member torques: the linear model's ``(M_1, -M_1)`` (eq. 24, 29), or
    ``M_i = sum_j p_j dV_j/dq_i`` from the gas pressures; the shaft torque by
    virtual work ``T = sum_i M_i phi_i'`` (positive when it drives the shaft). The
    Stirling models add the cold set's ``sum_j p_j dV_cold,j/dalpha`` (its blade pairs
    are driven by a second converter ``lag`` behind; ``members`` are the hot set's).

    Parameters
    ----------
    stroke : array_like, optional
        +1 / -1 for rising / falling ``psi``; default
        :func:`rotorkin.drives.rhomboid_cam.kinematics.stroke_direction`.
    """
    law = (params.psi_min, params.a, params.b)
    alpha = np.asarray(alpha, dtype=float)
    mo = rc.motion(params, alpha)
    stroke = rc.stroke_direction(*law, alpha) if stroke is None else np.asarray(stroke)
    volume = rb.chamber_volumes(machine, mo.q)
    dvolume = rb.chamber_volume_derivative(machine, mo.dq)
    pressure = None
    if loads.stirling is not None:
        sol = loads.stirling
        lag = sol.lag if np.ndim(sol.lag) == 0 else sol.lag[:, None]  # designs' lags (m,)
        cold = rc.motion(params, alpha - lag)
        st = rbs.stirling_state(machine, sol, mo, cold)
        return State(mo, stroke, volume, dvolume, st["pressure"], st["members"], st["shaft"],
                     st["volume_cold"], st["dvolume_cold"])  # fmt: skip
    if loads.model == "linear":
        psi = rc.psi_law(*law, alpha)[0]
        m1 = rc.blade_torque(loads.torque_high, loads.torque_low, params.psi_min, psi, stroke)
        members = rc.linear_member_torques(m1)
    else:
        strokes = rb.chamber_strokes(machine, stroke)
        pressure = rb.isothermal_pressure(loads.gas, loads.charge, volume, strokes)
        members = rb.gas_member_torques(machine, pressure)
    torque = at.shaft_torque_from_members(members, mo.dq)
    return State(mo, stroke, volume, dvolume, pressure, members, torque)


def drive_torque(machine, state: State, omega):
    """``D_i = J_i qdd_i - M_i``: what the drive must put on blade pair ``i`` [N m].

    ``qdd_i = q_i'' w^2 + q_i' w_dot`` at the shaft speed ``omega = (w, w_dot, ...)``;
    shape ``(2, n)``, or ``(2, m, n)`` for a machine of ``(m, 1)`` columns of designs.
    """
    mo = state.motion
    J = np.asarray(machine.member_inertias, dtype=float)
    J = J.reshape(J.shape + (1,) * (np.ndim(mo.d2q) - J.ndim))
    qdd = mo.d2q * omega[0] ** 2 + mo.dq * omega[1]
    return J * qdd - state.members
