"""The differential vane pump on this drive: what the pump needs from the drive (JHIT 2012).

The pump (:mod:`rotorkin.machines.vane_pump`) is built from the impellers'
motion and plain numbers. This module gives it those numbers:

* the smallest and largest relative angle ``r = q_2 - q_1`` over a period,
  taken at the two equal-speed points of the drive
  (:func:`~rotorkin.drives.guide_bar.kinematics.equal_speed_angles`), where ``r`` is
  stationary (closed form, no sampling);
* the default vane angle, the drive's theoretical vane angle gamma_0 (section 3,
  eq. 5, 6; :func:`~rotorkin.drives.guide_bar.kinematics.vane_angle`).
"""

from __future__ import annotations

import numpy as np

from rotorkin.analysis import torque as tq
from rotorkin.analysis.timing import shaft_speed
from rotorkin.core.angles import fmt_deg
from rotorkin.core.errors import ParameterError
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar.schema import VanePumpMachine
from rotorkin.machines import pump_flow as pf
from rotorkin.machines import vane_pump as vp

__all__ = ["CHECKS", "pump_state", "relative_angle_extremes", "turning_angles",
           "default_vane_angle", "inadmissible", "vane_pump", "displacement"]  # fmt: skip

#: The machine section's defaults (SI), the one source of the pump's defaults.
_MACHINE = VanePumpMachine().model_dump()


def relative_angle_extremes(params: gb.GuideBar):
    """Smallest and largest relative angle ``r = q_2 - q_1`` over a period [rad].

    ``r`` is stationary exactly at the two equal-speed points of the drive
    (driving angles ``-Sigma/2`` and ``pi - Sigma/2`` of mechanism 1), so its
    extremes are its values there (closed form, no sampling).

    Parameters
    ----------
    params : GuideBar
        Floats or arrays (one value per design).

    Returns
    -------
    (r_min, r_max) : tuple of float or ndarray
        [rad], the broadcast shape of the parameters; ``r_max - r_min = 2 pi/u - 2 gamma_0``.
    """
    shape = np.broadcast_shapes(*(np.shape(getattr(params, f)) for f in gb.FIELDS))
    t = np.stack([np.broadcast_to(v, shape) for v in gb.equal_speed_angles(params.phase)])
    q = gb.impeller_angles(params, t * np.asarray(params.input_gear_ratio, dtype=float))[0]
    r = q[1] - q[0]  # (2 points, ...)
    lo, hi = np.min(r, axis=0), np.max(r, axis=0)
    return (float(lo), float(hi)) if np.ndim(lo) == 0 else (lo, hi)


def turning_angles(params: gb.GuideBar) -> np.ndarray:
    """Input angles in ``[0, 2 pi i12)`` where ``r`` turns back: the equal-speed points [rad].

    The driving angles ``-Sigma/2`` and ``pi - Sigma/2`` of mechanism 1
    (:func:`~rotorkin.drives.guide_bar.kinematics.equal_speed_angles`) times ``i12``,
    sorted: where the pump's ports switch (closed form, one design).
    """
    i12 = float(params.input_gear_ratio)
    t = np.array(gb.equal_speed_angles(float(params.phase)), dtype=float) * i12
    return np.sort(np.mod(t, float(gb.period(params))))


def default_vane_angle(params: gb.GuideBar):
    """The pump's default vane angle: the drive's theoretical gamma_0 (section 3) [rad]."""
    return gb.vane_angle(params.lam, params.gear_ratio, params.phase, params.driver)


#: The checks of :func:`inadmissible`: the pump's (:data:`rotorkin.machines.vane_pump.CHECKS`)
#: and, last, the default vane angle gamma_0 too wide for ``vanes_per_impeller``.
CHECKS = (*vp.CHECKS, "vanes_per_impeller")


def inadmissible(
    params: gb.GuideBar,
    vanes_per_impeller=_MACHINE["vanes_per_impeller"],
    vane_angle=_MACHINE["vane_angle"],
    hub_radius=_MACHINE["hub_radius"],
    casing_radius=_MACHINE["casing_radius"],
    axial_width=_MACHINE["axial_width"],
):
    """The first check of :data:`CHECKS` each design fails, as index + 1 (0: admissible).

    ``vane_angle = None`` takes :func:`default_vane_angle`; where that is too wide
    for the vanes the fault is ``vanes_per_impeller`` (the last check).

    Returns
    -------
    ndarray of int16
        The broadcast shape of the drive's and the pump's parameters.
    """
    r_min, r_max = relative_angle_extremes(params)
    default = vane_angle is None
    gamma = default_vane_angle(params) if default else vane_angle
    reason = vp.inadmissible(r_min, r_max, gamma, vanes_per_impeller, hub_radius, casing_radius,
                             axial_width)  # fmt: skip
    if default:
        reason[reason == vp.CHECKS.index("vane_angle") + 1] = len(CHECKS)
    return reason


def vane_pump(
    params: gb.GuideBar,
    vanes_per_impeller: int = _MACHINE["vanes_per_impeller"],
    vane_angle: float | None = _MACHINE["vane_angle"],
    hub_radius: float = _MACHINE["hub_radius"],
    casing_radius: float = _MACHINE["casing_radius"],
    axial_width: float = _MACHINE["axial_width"],
) -> vp.VanePump:
    """The pump on this drive; ``vane_angle = None`` takes the drive's gamma_0 [rad].

    Parameters
    ----------
    params : GuideBar
        The drive (already validated).
    vanes_per_impeller, vane_angle, hub_radius, casing_radius, axial_width
        As :class:`rotorkin.machines.vane_pump.VanePump` ([-], [rad], [m], [m], [m]).

    Raises
    ------
    ParameterError
        Named by field (:func:`inadmissible`): the pump's, and with the default vane
        angle a ``vanes_per_impeller`` too large for gamma_0.
    """
    r_min, r_max = relative_angle_extremes(params)
    reason = inadmissible(params, vanes_per_impeller, vane_angle, hub_radius, casing_radius,
                          axial_width)  # fmt: skip
    gamma = default_vane_angle(params) if vane_angle is None else vane_angle
    if np.any(reason == len(CHECKS)):
        g0 = float(np.ravel(gamma)[0])
        swing = float(np.ravel(np.subtract(r_max, r_min))[0])
        gmax = float(vp.vane_angle_max(vanes_per_impeller, swing))
        z_max = int(np.floor(2.0 * np.pi / (2.0 * g0 + swing) * (1.0 + 1e-12)))
        raise ParameterError(
            "vanes_per_impeller",
            str(vanes_per_impeller),
            f"1 <= vanes_per_impeller <= {z_max} with the default vane_angle = gamma_0 "
            f"= {fmt_deg(g0)} (Z (2 vane_angle + swing {fmt_deg(swing)}) <= 360 deg); "
            f"or give vane_angle <= {fmt_deg(gmax)}",
        )
    gamma = float(gamma) if np.ndim(gamma) == 0 else gamma
    return vp.VanePump(r_min, r_max, gamma, vanes_per_impeller, hub_radius, casing_radius,
                       axial_width)  # fmt: skip


def displacement(params: gb.GuideBar, pump: vp.VanePump) -> dict:
    """Volume discharged, per period, per input-gear turn and per impeller revolution [m^3].

    Per period ``2 pi i12``: :func:`rotorkin.machines.vane_pump.displacement`. Per
    input turn: that over ``i12``. An impeller advances ``2 pi/u`` per period, so
    per impeller revolution: ``u`` times it.

    Returns
    -------
    dict
        ``"per_period"``, ``"per_input_turn"``, ``"per_impeller_rev"`` [m^3].
    """
    per_period = vp.displacement(pump)
    out = {
        "per_period": per_period,
        "per_input_turn": per_period / np.asarray(params.input_gear_ratio, dtype=float),
        "per_impeller_rev": per_period * np.asarray(params.gear_ratio, dtype=float),
    }
    return {k: float(v) if np.ndim(v) == 0 else v for k, v in out.items()}


def pump_state(
    params: gb.GuideBar,
    pump: vp.VanePump,
    ports: vp.PortPressures,
    inertia,
    speed,
    theta,
    windows: pf.LandWindows | None = None,
    omega=None,
) -> dict:
    """Chambers, pressures, flow and torques of the pump at the input angles ``theta``.

    Parameters
    ----------
    params : GuideBar
        The drive of the pump.
    pump : VanePump
    ports : PortPressures
    inertia : (float, (float, float))
        ``J_shaft`` and the impeller inertias [kg*m^2].
    speed : float or sequence of float
        ``run.speed`` [rad/s] (constant or a profile over one period).
    theta : ndarray, shape (n,)
        Input angles [rad].
    windows : LandWindows, optional
        The ports' sealing land (:func:`land_params`): the chambers' trapped
        pressure in the closed windows; None: ideal ports.
    omega : tuple of ndarray, optional
        ``shaft_speed(theta, speed, period)`` if already at hand (designs of one period).

    Returns
    -------
    dict of ndarray
        ``V``, ``dV``, ``p`` (2 Z, n); ``M`` (2, n); ``shaft``, ``inertia``,
        ``net``, ``J_eq``, ``flow`` (geometric), ``omega``, ``omega_dot`` (n,);
        ``motion``, the impellers' :class:`~rotorkin.core.motion.Motion` at ``theta``.
    """
    period = gb.period(params)
    motion = gb.motion(params, theta)
    dq, d2q = motion.dq, motion.d2q
    V, dV = vp.chamber_volumes(pump, motion)
    if windows is None:
        p = vp.chamber_pressures(ports, dV)
    else:
        p = pf.port_pressures(ports, windows, V, dV, theta)
    M = tq.member_torques(p, vp.volume_derivatives_dq(pump, motion))
    shaft = tq.shaft_torque_from_members(M, dq)
    omega, omega_dot, _ = shaft_speed(theta, speed, period) if omega is None else omega
    js, jm = inertia
    t_in = tq.inertia_torque(js, jm, dq, d2q, omega, omega_dot)
    return {
        "V": V,
        "dV": dV,
        "p": p,
        "M": M,
        "shaft": shaft,
        "inertia": t_in,
        "net": shaft - t_in,
        "J_eq": tq.equivalent_inertia(js, jm, dq),
        "flow": vp.flow_rate(pump, motion, omega),
        "omega": omega,
        "omega_dot": omega_dot,
        "motion": motion,
    }
