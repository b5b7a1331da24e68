"""The opposed-piston reactor driven by the double eccentric discs: the two joined.

:mod:`rotorkin.machines.opposed_piston` computes the reactor from the pistons'
:class:`~rotorkin.core.motion.Motion` and plain numbers; this module supplies
them from the drive (:mod:`rotorkin.drives.eccentric_cam.kinematics`): the
travels ``(z, z')`` of eq. 1, 3 and the smallest gap change of eq. 5 (at
``beta = 90 deg``).
"""

from __future__ import annotations

import numpy as np

from rotorkin.analysis import flywheel as fw
from rotorkin.analysis import torque as tq
from rotorkin.analysis.timing import shaft_speed
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.machines import opposed_piston as op

__all__ = ["opposed_piston", "closed_forms", "reactor_state", "shaft_speeds", "reactor_summary"]


def opposed_piston(params: ec.EccentricCam, **machine) -> op.OpposedPiston:
    """The reactor on the drive ``params``: the machine's fields ``machine`` (SI) and the
    drive's smallest gap change ``Delta_min = 2 (sqrt(Rc^2 - e^2) - Rc)`` (eq. 5) and
    piston stroke ``2 e`` (the reactor is at least that long).

    Parameters
    ----------
    params : EccentricCam
    **machine
        :class:`~rotorkin.machines.opposed_piston.OpposedPiston` fields other than
        ``gap_change_min`` (``device_length`` [m], ``bore`` [m], ``fluid``,
        ``initial_pressure`` [Pa], ``polytropic_exponent``, ``bulk_modulus`` [Pa],
        ``back_pressure`` [Pa]).

    Returns
    -------
    OpposedPiston
    """
    return op.OpposedPiston(
        **machine,
        gap_change_min=ec.gap_change_extreme(params)[0],
        piston_stroke=ec.piston_stroke(params),
    )


def reactor_state(params: ec.EccentricCam, reactor: op.OpposedPiston, inertia, speed,
                  beta) -> dict:  # fmt: skip
    """Volume, pressure, piston forces and shaft torques at the shaft angles ``beta``.

    Parameters
    ----------
    params : EccentricCam
        One design, or designs whose fields are columns (d, 1).
    reactor : OpposedPiston
        Its fields floats or columns (d, 1).
    inertia : (float, (float, float))
        ``J_shaft`` [kg*m^2] and the piston masses [kg]; for designs, ``J_shaft``
        (d, 1) and the masses (2, d, 1).
    speed : float or sequence of float or ndarray, shape (d, 1)
        ``run.speed`` [rad/s] (:func:`shaft_speeds`).
    beta : ndarray, shape (n,)
        Shaft angles [rad].

    Returns
    -------
    dict of ndarray
        ``V``, ``dV``, ``p`` (1, n); ``F`` (2, n); ``shaft``, ``inertia``, ``net``,
        ``J_eq``, ``omega``, ``omega_dot``, ``omega_ddot`` (n,); for designs the axis
        ``d`` before the angles'; ``motion``, the pistons'
        :class:`~rotorkin.core.motion.Motion` at ``beta``.
    """
    m = ec.motion(params, beta)
    V, dV, _, _ = op.enclosed_volume(reactor, m)
    p, _ = op.pressure(reactor, m)
    F = tq.member_torques(op.net_pressure(reactor, p), op.volume_derivatives_dq(reactor, m))
    shaft = tq.shaft_torque_from_members(F, m.dq)
    omega, omega_dot, omega_ddot = shaft_speeds(beta, speed, ec.period(params))
    js, masses = inertia
    t_in = tq.inertia_torque(js, masses, m.dq, m.d2q, omega, omega_dot)
    return {
        "V": V,
        "dV": dV,
        "p": p,
        "F": F,
        "shaft": shaft,
        "inertia": t_in,
        "net": shaft - t_in,
        "J_eq": tq.equivalent_inertia(js, masses, m.dq),
        "omega": omega,
        "omega_dot": omega_dot,
        "omega_ddot": omega_ddot,
        "motion": m,
    }


def shaft_speeds(beta, speed, period: float):
    """:func:`~rotorkin.analysis.timing.shaft_speed`, or constant speeds of many designs.

    Parameters
    ----------
    beta : ndarray, shape (n,)
        Shaft angles [rad].
    speed : float or sequence of float or ndarray, shape (d, 1)
        A speed or a profile (``run.speed``, one design or all designs alike), or one
        constant speed per design as a column (d, 1) [rad/s].
    period : float
        Period of a profile [rad].

    Returns
    -------
    (omega, omega_dot, omega_ddot) : tuple of ndarray, shape (n,) or (d, n)
        For constant speeds of designs, ``omega_dot`` and ``omega_ddot`` are 0-d zeros
        (they broadcast).
    """
    if np.ndim(speed) < 2:
        return shaft_speed(beta, speed, period)
    omega = np.broadcast_to(np.asarray(speed, dtype=float), np.broadcast_shapes(
        np.shape(speed), np.shape(beta)))  # fmt: skip
    zero = np.zeros(())
    return omega, zero, zero


def reactor_summary(params: ec.EccentricCam, reactor: op.OpposedPiston, inertia, speed,
                    coefficient, beta, state: dict | None = None) -> dict:  # fmt: skip
    """Torque, inertia and flywheel keys of the study's summary (floats or arrays (d,)).

    Parameters
    ----------
    params, reactor, inertia, speed
        As :func:`reactor_state` (one design, or columns (d, 1) of designs).
    coefficient : float or ndarray, shape (d,)
        ``machine.speed_fluctuation``, the wanted coefficient of speed fluctuation.
    beta : ndarray, shape (n,)
        Shaft angles over one turn, ends included [rad].
    state : dict, optional
        :func:`reactor_state` at ``beta`` if already at hand.
    """
    period = ec.period(params)
    st = reactor_state(params, reactor, inertia, speed, beta) if state is None else state
    omega_mean = np.mean(st["omega"][..., :-1], axis=-1)
    dq, d2q = st["motion"].dq, st["motion"].d2q
    js, masses = inertia
    net_const = st["shaft"] - tq.inertia_torque(js, masses, dq, d2q, omega_mean[..., None], 0.0)
    delta_e = fw.energy_fluctuation(net_const, beta)
    j_mean = np.trapezoid(st["J_eq"], beta, axis=-1) / period
    with np.errstate(divide="ignore", invalid="ignore"):
        cs = np.where(j_mean > 0.0, delta_e / (j_mean * omega_mean**2), np.nan)
    work = tq.cycle_integral(st["shaft"], beta)
    shape = np.shape(work)
    back = np.asarray(reactor.back_pressure, dtype=float)
    back = back[..., 0] if back.ndim else back  # columns (d, 1) of designs
    out = {
        "back_pressure_bar": back / 1e5,
        "piston_force_peak_N": np.max(np.abs(st["F"]), axis=(0, -1)),
        "indicated_work_J": work,
        "mean_torque_Nm": work / period,
        "shaft_torque_min_Nm": np.min(st["shaft"], axis=-1),
        "shaft_torque_max_Nm": np.max(st["shaft"], axis=-1),
        "shaft_torque_peak_Nm": np.max(np.abs(st["shaft"]), axis=-1),
        "shaft_torque_with_inertia_peak_Nm": np.max(np.abs(st["net"]), axis=-1),
        "inertia_torque_peak_Nm": np.max(np.abs(st["inertia"]), axis=-1),
        "equivalent_inertia_mean_kgm2": j_mean,
        "energy_fluctuation_J": delta_e,
        "speed_fluctuation_without_flywheel": cs,
        "speed_fluctuation": np.asarray(coefficient, dtype=float),
        "flywheel_inertia_kgm2": fw.flywheel_inertia(delta_e, omega_mean, coefficient, j_mean),
    }
    return {k: np.broadcast_to(v, shape) if shape else np.asarray(v).item() for k, v in out.items()}


def closed_forms(params: ec.EccentricCam, reactor: op.OpposedPiston) -> dict:
    """The summary keys with closed forms, for one design or arrays of designs.

    The eccentricity ratios, the gap change at 90 deg (eq. 5, 6) and its share of
    the device length, the knife edge's for comparison, the stroke ``2 e``, the
    largest pressure angle, the reactor's volume extremes and the pressure at the
    largest volume (the smallest pressure; the largest is ``p0`` at ``V0``).

    Returns
    -------
    dict of str -> ndarray or NumPy scalar
        Keys of :data:`rotorkin.drives.eccentric_cam.sweep.KEYS`' metrics in the
        units their suffix names; ``cavitation`` as bool.
    """
    e, rc = np.asarray(params.eccentricity, dtype=float), params.contact_radius
    L = np.asarray(reactor.device_length, dtype=float)
    dmin, bmin = ec.gap_change_extreme(params)
    knife = ec.gap_change_extreme(ec.EccentricCam(params.disc_radius, e))[0]
    vmin, vmax = op.volume_extremes(reactor)
    p0 = np.asarray(reactor.initial_pressure, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        p_end = op.pressure_from_volume(reactor, vmax)
    return {
        "lambda": params.lam,
        "lambda_contact": e / rc,
        "gap_change_min_mm": dmin * 1e3,
        "gap_change_min_ratio": dmin / e,
        "gap_change_min_angle_deg": np.degrees(bmin),
        "gap_change_to_length": np.abs(dmin) / L,
        "gap_change_to_length_percent": 100.0 * np.abs(dmin) / L,
        "gap_change_min_knife_edge_mm": knife * 1e3,
        "piston_stroke_mm": ec.piston_stroke(params) * 1e3,
        "pressure_angle_max_deg": np.degrees(ec.pressure_angle_max(params)),
        "device_length_mm": L * 1e3,
        "bore_mm": np.asarray(reactor.bore, dtype=float) * 1e3,
        "piston_area_cm2": reactor.area * 1e4,
        "enclosed_volume_min_cm3": vmin * 1e6,
        "enclosed_volume_max_cm3": vmax * 1e6,
        "chamber_volume_min_cm3": vmin * 1e6,
        "chamber_volume_max_cm3": vmax * 1e6,
        "volume_change_cm3": (vmax - vmin) * 1e6,
        "volume_change_relative": (vmax - vmin) / vmin,
        "compression_ratio_geometric": vmax / vmin,
        "initial_pressure_bar": p0 / 1e5,
        "pressure_max_bar": p0 / 1e5,
        "pressure_min_bar": p_end / 1e5,
        "pressure_ripple_bar": (p0 - p_end) / 1e5,
        "pressure_ripple_relative": (p0 - p_end) / p0,
        "cavitation": p_end <= 0.0,
    }
