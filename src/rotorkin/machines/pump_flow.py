"""The vane pump's real flow: sealing land and trapped pressure, leakage, compression loss.

The chambers and the ideal ports of the differential vane pump are in
:mod:`rotorkin.machines.vane_pump`; this module takes them to the flow the outlet
receives.

Ports: a chamber whose volume shrinks is connected to the discharge port
(pressure ``p_d``), a growing one to the suction port (``p_s``). Every chamber
switches at the turning points of ``r`` (all at once: A and B chambers are in
antiphase). With a sealing land (``port_land`` ``L``, a shaft angle, default 0:
ideal ports) every chamber is closed to both ports while the shaft is within
``L/2`` of a turning point; the fluid trapped in it follows ``dp = -K dV/V``
(:func:`trapped_pressure`), and its pressure is the chamber's pressure there (the
torques follow from it).

Flow losses (:class:`Gaps`, all zero by default but the compressibility): the
flow delivered is the geometric flow less

* the leakage through the clearances of every vane, laminar plane Poiseuille flow
  ``Q = b h^3 dp / (12 mu L)`` (pressure-driven only: the Couette flow of the
  moving wall, ``b h U / 2``, is left out). Every vane parts a chamber at ``p_d``
  from one at ``p_s`` (all A chambers discharge while all B chambers suck, and
  the other way round), so each of the ``2 Z`` vanes leaks with ``dp = p_d - p_s``
  through

  - its tip (clearance ``h_t`` to the casing): ``b = w``, ``L = gamma R_c``;
  - its root (clearance ``h_h`` to the hub of the other impeller): ``b = w``,
    ``L = gamma R_h``;
  - its two side faces (clearance ``h_s`` each, to the end covers): a sector land
    whose length grows with the radius, ``L = gamma rho``; integrating
    ``dQ = h_s^3 dp d rho / (12 mu gamma rho)`` from ``R_h`` to ``R_c`` gives
    ``Q = h_s^3 dp ln(R_c/R_h) / (12 mu gamma)`` per face;

* the compression loss: a chamber switched from suction to discharge at its
  largest volume ``V_max = k phi_max`` holds fluid at ``p_s``; bringing it to
  ``p_d`` takes back ``V_max (p_d - p_s) / K`` from the discharge port (``K`` the
  bulk modulus; first order in ``dp / K``). Each of the ``2 Z`` chambers does so
  once per period. The re-expansion of the smallest volume at the other
  switch-over is a loss on the suction side only, the same mass. With a sealing
  land the chamber opens to the outlet at ``V_o`` holding ``p_o`` (its trapped
  pressure then), and the loss is ``V_o (p_d - p_o) / K`` (:func:`land_windows`);
* the geometric flow of the closed windows: a chamber discharging while it is
  closed delivers nothing to the outlet (:func:`delivered_flow`).

Sources: H. E. Merritt, *Hydraulic Control Systems*, Wiley 1967, ch. 2 (the bulk
modulus of the fluid) and ch. 3 (the continuity equation of a control volume,
``dp/dt = (K/V)(sum Q_in - dV/dt)``; laminar flow through plane clearances);
J. Ivantysyn, M. Ivantysynova, *Hydrostatic Pumps and Motors*, Akademia Books 2001
(the pressure in a displacement chamber closed at its reversal, volumetric losses,
flow pulsation). Chapters, not equation numbers: the forms used here are derived
on this page and checked by the tests against numeric integration.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.core.angles import fmt_deg, fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.machines.vane_pump import (
    PortPressures,
    VanePump,
    _scalar,
    chamber_angles,
    chamber_pressures,
    chamber_volumes,
    flow_ripple,
)

__all__ = [
    "GAP_FIELDS",
    "gaps_inadmissible",
    "Gaps",
    "gap_flow",
    "leakage_conductances",
    "leakage_flow",
    "compression_loss",
    "check_port_land",
    "LandWindows",
    "land_windows",
    "closed_windows",
    "trapped_pressure",
    "port_pressures",
    "delivered_flow",
    "pump_flow",
    "flow_keys",
    "cavitation_warning",
    "VAPOUR_PRESSURE",
]


# --------------------------------------------------------------------------------------------
# flow losses: leakage through the vane clearances, compression at the switch-over
# --------------------------------------------------------------------------------------------
#: Fields of :class:`Gaps`, in the order they are checked (codes index + 1).
GAP_FIELDS = ("tip_clearance", "side_clearance", "hub_clearance", "fluid_viscosity",
              "bulk_modulus", "vapour_pressure")  # fmt: skip
#: Default cavitation floor [Pa] (config ``loads.vapour_pressure``): 0.1 bar, absolute.
VAPOUR_PRESSURE = 1.0e4


def gaps_inadmissible(tip_clearance, side_clearance, hub_clearance, fluid_viscosity,
                      bulk_modulus, vapour_pressure=VAPOUR_PRESSURE):  # fmt: skip
    """The first field of :data:`GAP_FIELDS` each design gets wrong, index + 1 (0: admissible).

    Clearances and the vapour pressure finite and ``>= 0``; viscosity and bulk modulus
    finite and ``> 0``.
    """
    values = [np.asarray(v, dtype=float) for v in (tip_clearance, side_clearance, hub_clearance,
                                                   fluid_viscosity, bulk_modulus,
                                                   vapour_pressure)]  # fmt: skip
    with np.errstate(invalid="ignore"):
        bad = [~(np.isfinite(v) & (v >= 0.0)) for v in values[:3]]
        bad += [~(np.isfinite(v) & (v > 0.0)) for v in values[3:5]]
        bad += [~(np.isfinite(values[5]) & (values[5] >= 0.0))]
    bad = np.broadcast_arrays(*bad)
    reason = np.zeros(bad[0].shape, dtype=np.int16)
    for k in range(len(bad) - 1, -1, -1):
        reason[bad[k]] = k + 1
    return reason


@dataclass(frozen=True)
class Gaps:
    """Clearances of the vanes and the fluid (SI): what the flow losses need.

    Parameters
    ----------
    tip_clearance : float, optional
        Radial gap ``h_t`` between a vane tip and the casing [m] (default 0: no leakage).
    side_clearance : float, optional
        Axial gap ``h_s`` between each side face of a vane and its end cover [m] (default 0).
    hub_clearance : float, optional
        Radial gap ``h_h`` between a vane root and the other impeller's hub [m] (default 0).
    fluid_viscosity : float, optional
        Dynamic viscosity ``mu`` [Pa*s], ``> 0`` (default 0.03: mineral oil ISO VG 32 at 40 C).
    bulk_modulus : float, optional
        Bulk modulus ``K`` of the fluid [Pa], ``> 0`` (default 1.5 GPa: mineral oil).
    vapour_pressure : float, optional
        Cavitation floor [Pa], absolute, ``>= 0`` (default 0.1 bar): a trapped chamber
        whose pressure falls below it cavitates (:func:`land_windows`).
    """

    tip_clearance: float = 0.0
    side_clearance: float = 0.0
    hub_clearance: float = 0.0
    fluid_viscosity: float = 0.03
    bulk_modulus: float = 1.5e9
    vapour_pressure: float = VAPOUR_PRESSURE

    def __post_init__(self):
        values = [getattr(self, f) for f in GAP_FIELDS]
        reason = gaps_inadmissible(*values)
        if reason.any():
            i = int(np.flatnonzero(reason)[0])
            k = int(reason.flat[i]) - 1
            name = GAP_FIELDS[k]
            v = float(np.broadcast_to(np.asarray(values[k], dtype=float), reason.shape).flat[i])
            if k < 3:
                raise ParameterError(name, fmt_mm(v), f"{name} >= 0 mm")
            if name == "vapour_pressure":
                raise ParameterError(name, f"{v / 1e5:.4g} bar", f"{name} >= 0 bar (absolute)")
            unit = "Pa*s" if name == "fluid_viscosity" else "Pa"
            raise ParameterError(name, f"{v:.4g} {unit}", f"{name} > 0 {unit}")


def gap_flow(width, gap, length, pressure_drop, viscosity):
    """Laminar flow through a plane gap, ``Q = b h^3 dp / (12 mu L)`` [m^3/s] (plane Poiseuille).

    Parameters
    ----------
    width : array_like
        Width ``b`` of the gap across the flow [m].
    gap : array_like
        Height ``h`` of the gap [m].
    length : array_like
        Length ``L`` of the gap along the flow [m], ``> 0``.
    pressure_drop : array_like
        ``dp`` [Pa]; the flow runs from the high to the low pressure.
    viscosity : array_like
        Dynamic viscosity ``mu`` [Pa*s].
    """
    b, h, n, dp, mu = (np.asarray(v, dtype=float) for v in (width, gap, length, pressure_drop,
                                                            viscosity))  # fmt: skip
    return _scalar(b * h**3 * dp / (12.0 * mu * n))


def leakage_conductances(pump: VanePump, gaps: Gaps) -> dict:
    """Leakage per vane and per pascal of pressure difference, by path [m^3/(s Pa)].

    ``"tip"``: ``w h_t^3 / (12 mu gamma R_c)``; ``"hub"``: ``w h_h^3 / (12 mu gamma R_h)``;
    ``"side"``: both faces, ``2 h_s^3 ln(R_c/R_h) / (12 mu gamma)`` (module docstring).
    """
    rh, rc, w, g = (
        np.asarray(v, dtype=float)
        for v in (pump.hub_radius, pump.casing_radius, pump.axial_width, pump.vane_angle)
    )
    mu = gaps.fluid_viscosity
    side = (
        2.0
        * np.asarray(gaps.side_clearance, dtype=float) ** 3
        * np.log(rc / rh)
        / (12.0 * np.asarray(mu, dtype=float) * g)
    )
    return {
        "tip": gap_flow(w, gaps.tip_clearance, g * rc, 1.0, mu),
        "side": _scalar(side),
        "hub": gap_flow(w, gaps.hub_clearance, g * rh, 1.0, mu),
    }


def leakage_flow(pump: VanePump, gaps: Gaps, ports: PortPressures) -> dict:
    """Leakage from the discharge to the suction chambers, by path and ``"total"`` [m^3/s].

    ``2 Z G (p_d - p_s)`` with ``G`` a path's :func:`leakage_conductances`: every
    vane parts a discharging chamber from a sucking one. The same at every angle
    (only at the switch-over instants, a set of measure zero, are both sides at
    ``p_s``); negative when ``p_d < p_s`` (a motor: the leakage then adds to the
    flow it takes).
    """
    dp = np.asarray(ports.discharge_pressure, dtype=float) - np.asarray(
        ports.suction_pressure, dtype=float)  # fmt: skip
    n = np.asarray(pump.n_chambers, dtype=float)
    out = {k: _scalar(n * g * dp) for k, g in leakage_conductances(pump, gaps).items()}
    out["total"] = _scalar(out["tip"] + out["side"] + out["hub"])
    return out


def compression_loss(pump: VanePump, gaps: Gaps, ports: PortPressures):
    """Volume taken back from the discharge port per period to compress the chambers [m^3].

    ``2 Z k phi_max (p_d - p_s) / K``: each chamber switches to the discharge port
    once per period at its largest volume ``k phi_max``, full of fluid at ``p_s``
    (module docstring; first order in ``dp / K``).
    """
    dp = np.asarray(ports.discharge_pressure, dtype=float) - np.asarray(
        ports.suction_pressure, dtype=float)  # fmt: skip
    v_max = np.asarray(pump.volume_per_angle, dtype=float) * pump.chamber_angle_range[1]
    n = np.asarray(pump.n_chambers, dtype=float)
    return _scalar(n * v_max * dp / np.asarray(gaps.bulk_modulus, dtype=float))


# --------------------------------------------------------------------------------------------
# the ports' sealing land: chambers closed around the turning points, trapped pressure
# --------------------------------------------------------------------------------------------
def _strokes(turning, period):
    """Shaft angles between consecutive turning points of ``r``, cyclic [rad], shape (m,)."""
    t = np.sort(np.asarray(turning, dtype=float))
    return np.diff(np.append(t, t[0] + float(period)))


def check_port_land(pump: VanePump, land, turning, period) -> None:
    """Refuse a sealing land that does not fit the law or the pump.

    Admissible: ``0 <= L < `` the shortest stroke (the shaft angle between two
    turning points of ``r``: wider windows would overlap and a chamber would never
    open), and ``L = 0`` when the chambers close completely (``phi_min = 0``: a
    chamber closed at zero volume would lock its fluid, ``p -> inf``).

    Raises
    ------
    ParameterError
        Named ``port_land``.
    """
    land = float(land)
    t = np.asarray(turning, dtype=float)
    stroke = float(np.min(_strokes(t, period))) if t.size else float(period)
    if not (np.isfinite(land) and 0.0 <= land < stroke):
        raise ParameterError(
            "port_land",
            fmt_deg(land),
            f"0 deg <= port_land < {fmt_deg(stroke)}, the shortest stroke (the shaft angle "
            "between two turning points of the relative angle, where the ports switch)",
        )
    if land > 0.0 and float(pump.chamber_angle_range[0]) <= 0.0:
        raise ParameterError(
            "port_land",
            fmt_deg(land),
            "port_land = 0 deg while the chambers close completely (smallest chamber angle "
            "0 deg: a chamber closed at zero volume locks its fluid); a vane_angle below "
            f"{fmt_deg(pump.vane_angle_max)} leaves the dead volume a sealing land needs",
        )


@dataclass(frozen=True)
class LandWindows:
    """The closed windows of one pump round the ``m`` turning points of ``r`` (SI).

    Arrays of shape (m, 2 Z): turning point, chamber. A window runs from the
    closing angle ``theta_t - L/2`` to the opening angle ``theta_t + L/2``.

    Attributes
    ----------
    turning : ndarray, shape (m,)
        Turning points of ``r`` in one period, sorted [rad].
    period : float
        Period of the law [rad].
    land : float
        Sealing land ``L`` [rad].
    bulk_modulus : float
        ``K`` [Pa].
    is_min : ndarray of bool
        The chamber is at its smallest volume at the turning point (closed full of
        discharge fluid); else at its largest (closed full of suction fluid).
    volume_close, volume_turn, volume_open : ndarray
        Chamber volume at the closing angle, the turning point, the opening angle [m^3].
    pressure_close, pressure_turn, pressure_open : ndarray
        Trapped pressure there [Pa] (:func:`trapped_pressure`).
    lost_volume : float
        Geometric discharge of the closed windows per period [m^3]: a chamber
        shrinking while it is closed delivers nothing to the outlet.
    compression_volume : float
        Volume taken back from the outlet per period to bring the chambers that open
        to it from their trapped pressure to ``p_d`` [m^3] (first order in dp/K).
    pressure_peak, pressure_min : float
        Highest and lowest chamber pressure of the windows [Pa]; with ``L = 0``,
        the port pressures (no chamber is ever trapped).
    """

    turning: np.ndarray
    period: float
    land: float
    bulk_modulus: float
    is_min: np.ndarray
    volume_close: np.ndarray
    volume_turn: np.ndarray
    volume_open: np.ndarray
    pressure_close: np.ndarray
    pressure_turn: np.ndarray
    pressure_open: np.ndarray
    lost_volume: float
    compression_volume: float
    pressure_peak: float
    pressure_min: float


def trapped_pressure(volume, volume_closed, pressure_closed, bulk_modulus):
    """Pressure of fluid closed in a chamber, ``p = p_0 - K ln(V / V_0)`` [Pa].

    The continuity equation of a closed control volume with a constant bulk modulus,
    ``dp = -K dV / V`` (Merritt 1967, ch. 3, with no flow in or out), integrated from
    the closing state ``(V_0, p_0)``: exact for constant ``K``, no leakage.

    Parameters
    ----------
    volume, volume_closed : array_like
        ``V`` and ``V_0`` [m^3], ``> 0``; broadcast together.
    pressure_closed : array_like
        ``p_0`` [Pa].
    bulk_modulus : array_like
        ``K`` [Pa].
    """
    v, v0, p0, k = (
        np.asarray(x, dtype=float) for x in (volume, volume_closed, pressure_closed, bulk_modulus)
    )
    return _scalar(p0 - k * np.log(v / v0))


def land_windows(pump: VanePump, ports: PortPressures, gaps: Gaps, motion_of, turning, period,
                 land=0.0) -> LandWindows:  # fmt: skip
    """The closed windows of a pump on a law, from the motion at their ends (closed form).

    Every chamber is at a dead centre at each turning point ``theta_t`` of ``r``:
    at its smallest volume it was discharging and is closed full of fluid at
    ``p_d``, at its largest it was sucking and is closed at ``p_s``. While closed,
    its pressure follows :func:`trapped_pressure` (no leakage); it opens to the other
    port at ``theta_t + L/2``. Since ``V`` is monotonic on each side of
    ``theta_t``, the window's pressure extremes are at its ends and at ``theta_t``.

    Parameters
    ----------
    pump : VanePump
    ports : PortPressures
    gaps : Gaps
        For ``bulk_modulus``.
    motion_of : callable
        ``motion_of(theta) -> Motion`` of the impellers, any shape of theta.
    turning : array_like, shape (m,)
        Turning points of ``r`` in one period [rad].
    period : float
        Period of the law [rad].
    land : float, optional
        Sealing land ``L`` [rad] (:func:`check_port_land`); 0: ideal ports.

    Returns
    -------
    LandWindows
    """
    check_port_land(pump, land, turning, period)
    land = float(land)
    t = np.sort(np.asarray(turning, dtype=float))
    half = 0.5 * land
    motion = motion_of(np.stack([t - half, t, t + half]))  # (3, m)
    v = chamber_volumes(pump, motion)[0]  # (2 Z, 3, m)
    d2 = chamber_angles(pump, motion)[2][:, 1].T  # (m, 2 Z)
    vc, vt, vo = (v[:, i].T for i in range(3))
    mid = float(pump.volume_per_angle) * (np.pi / int(pump.vanes_per_impeller)
                                          - float(pump.vane_angle))  # fmt: skip
    is_min = np.where(d2 != 0.0, d2 > 0.0, vt < mid)
    ps, pd = float(ports.suction_pressure), float(ports.discharge_pressure)
    k = float(gaps.bulk_modulus)
    pc = np.where(is_min, pd, ps)
    if half > 0.0:
        pt, po = trapped_pressure(vt, vc, pc, k), trapped_pressure(vo, vc, pc, k)
    else:
        pt = po = pc
    lost = float(np.sum(np.where(is_min, vc - vt, vt - vo)))
    compression = float(np.sum(np.where(is_min, 0.0, vo * (pd - po)))) / k
    every = np.stack([pc, pt, po])
    return LandWindows(t, float(period), land, k, is_min, vc, vt, vo, pc, pt, po, lost,
                       compression, float(np.max(every)), float(np.min(every)))  # fmt: skip


def closed_windows(theta, turning, period, land):
    """Whether each shaft angle is in a closed window, and the window's turning point.

    Parameters
    ----------
    theta : array_like, shape (...)
        Shaft angles [rad].
    turning : array_like, shape (m,)
        Turning points of ``r`` in one period, sorted [rad].
    period : float
        Period of the law [rad].
    land : float
        ``L`` [rad]; the window is ``|theta - theta_t| < L/2`` (open at its ends).

    Returns
    -------
    (closed, index) : (ndarray of bool, ndarray of int), shape (...)
        ``index`` of the nearest turning point (mod the period).
    """
    th = np.asarray(theta, dtype=float)
    t = np.asarray(turning, dtype=float)
    p = float(period)
    d = th[..., None] - t
    d = d - p * np.round(d / p)  # into [-p/2, p/2]
    index = np.argmin(np.abs(d), axis=-1)
    near = np.take_along_axis(d, index[..., None], axis=-1)[..., 0]
    return np.abs(near) < 0.5 * float(land), index


def port_pressures(ports: PortPressures, windows: LandWindows, volume, dvolume, theta):
    """Chamber pressures with the sealing land [Pa], shape (2 Z, ...).

    Outside the windows the ideal ports' (:func:`chamber_pressures`); inside, the
    trapped pressure from the window's closing state. With ``L = 0`` exactly
    :func:`chamber_pressures`.

    Parameters
    ----------
    volume, dvolume : array_like, shape (2 Z, ...)
        ``V`` [m^3] and ``dV/dtheta`` [m^3/rad] at ``theta``.
    theta : array_like, shape (...)
        Shaft angles [rad].
    """
    ideal = chamber_pressures(ports, dvolume)
    if windows.land == 0.0:
        return ideal
    closed, index = closed_windows(theta, windows.turning, windows.period, windows.land)
    v0 = np.moveaxis(windows.volume_close[index], -1, 0)  # (2 Z, ...)
    p0 = np.moveaxis(windows.pressure_close[index], -1, 0)
    trapped = trapped_pressure(volume, v0, p0, windows.bulk_modulus)
    return np.where(closed[None], trapped, ideal)


def delivered_flow(dvolume, closed, omega, leakage=0.0):
    """Flow delivered to the outlet at the shaft angles [m^3/s], shape (...).

    ``omega sum_j max(-dV_j/dtheta, 0)`` (:func:`flow_rate`) outside the closed
    windows, 0 inside (every chamber is closed), less the leakage (constant over
    the angle, :func:`leakage_flow`). With no window and no leakage exactly the
    ideal flow.

    Parameters
    ----------
    dvolume : array_like, shape (2 Z, ...)
        ``dV/dtheta`` [m^3/rad].
    closed : array_like of bool, shape (...)
        :func:`closed_windows`.
    omega : array_like
        Shaft speed [rad/s], broadcasting with the angles.
    leakage : float, optional
        Total leakage [m^3/s].
    """
    dv = np.asarray(dvolume, dtype=float)
    q = np.asarray(omega, dtype=float) * np.sum(np.maximum(-dv, 0.0), axis=0)
    return np.where(closed, 0.0, q) - leakage


def pump_flow(pump: VanePump, ports: PortPressures, gaps: Gaps, windows: LandWindows,
              flow_mean, time_per_period, dvolume, theta, omega) -> dict:  # fmt: skip
    """The flow a pump delivers, its losses and its ripple, over a sampled turn (SI).

    Delivered mean ``Q_d = Q_g - Q_land - Q_L - Q_c``: the geometric mean flow less
    the geometric flow of the closed windows (:attr:`LandWindows.lost_volume` per
    period), the leakage (:func:`leakage_flow`) and the compression loss
    (:attr:`LandWindows.compression_volume` per period); volumetric efficiency
    ``Q_d / Q_g``. The curve is :func:`delivered_flow` (the compression loss is an
    impulse at the opening and is in the mean only); its ripple ``(max - min)/mean``
    takes the time mean of the curve (:func:`flow_ripple`).

    Parameters
    ----------
    flow_mean : float
        Geometric mean flow ``Q_g`` [m^3/s] (the displacement over its time).
    time_per_period : float
        Time of one period of the law at the run speed [s].
    dvolume : ndarray, shape (2 Z, n)
        ``dV/dtheta`` at ``theta`` [m^3/rad].
    theta : ndarray, shape (n,)
        Shaft angles over whole periods, ends included [rad].
    omega : ndarray, shape (n,)
        Shaft speed at ``theta`` [rad/s].

    Returns
    -------
    dict
        ``"leakage"`` (dict by path, :func:`leakage_flow`), ``"compression"``,
        ``"land_loss"``, ``"delivered_mean"`` [m^3/s], ``"volumetric_efficiency"``,
        ``"delivered"`` (n,) [m^3/s], ``"closed"`` (n,) bool, ``"delivered_max"``,
        ``"delivered_min"`` [m^3/s], ``"delivered_ripple"``, ``"trapped_peak"``,
        ``"trapped_min"`` [Pa].
    """
    leak = leakage_flow(pump, gaps, ports)
    t_period = float(time_per_period)
    compression = windows.compression_volume / t_period
    land_loss = windows.lost_volume / t_period
    delivered_mean = flow_mean - land_loss - leak["total"] - compression
    closed = closed_windows(theta, windows.turning, windows.period, windows.land)[0]
    curve = delivered_flow(dvolume, closed, omega, leak["total"])
    return {
        "leakage": leak,
        "compression": compression,
        "land_loss": land_loss,
        "delivered_mean": delivered_mean,
        "volumetric_efficiency": delivered_mean / flow_mean if flow_mean > 0.0 else float("nan"),
        "delivered": curve,
        "closed": closed,
        "delivered_max": float(np.max(curve)),
        "delivered_min": float(np.min(curve)),
        "delivered_ripple": flow_ripple(curve, 1.0 / np.asarray(omega, dtype=float)),
        "trapped_peak": windows.pressure_peak,
        "trapped_min": windows.pressure_min,
    }


_M3S_TO_L_PER_MIN = 60.0e3


def flow_keys(flow: dict, ports: PortPressures, land) -> dict:
    """Summary keys of :func:`pump_flow` (l/min, bar, deg), the same for every drive."""
    leak = flow["leakage"]
    dp = float(ports.discharge_pressure) - float(ports.suction_pressure)
    return {
        "leakage_l_per_min": leak["total"] * _M3S_TO_L_PER_MIN,
        "leakage_tip_l_per_min": leak["tip"] * _M3S_TO_L_PER_MIN,
        "leakage_side_l_per_min": leak["side"] * _M3S_TO_L_PER_MIN,
        "leakage_hub_l_per_min": leak["hub"] * _M3S_TO_L_PER_MIN,
        "compression_loss_l_per_min": flow["compression"] * _M3S_TO_L_PER_MIN,
        "land_loss_l_per_min": flow["land_loss"] * _M3S_TO_L_PER_MIN,
        "flow_delivered_mean_l_per_min": flow["delivered_mean"] * _M3S_TO_L_PER_MIN,
        "flow_delivered_max_l_per_min": flow["delivered_max"] * _M3S_TO_L_PER_MIN,
        "flow_delivered_min_l_per_min": flow["delivered_min"] * _M3S_TO_L_PER_MIN,
        "flow_delivered_ripple": flow["delivered_ripple"],
        "volumetric_efficiency": flow["volumetric_efficiency"],
        "hydraulic_power_delivered_W": dp * flow["delivered_mean"],
        "port_land_deg": float(np.degrees(land)),
        "trapped_pressure_peak_bar": flow["trapped_peak"] / 1e5,
        "trapped_pressure_min_bar": flow["trapped_min"] / 1e5,
    }


def cavitation_warning(trapped_min, vapour_pressure) -> str | None:
    """One line when the trapped pressure falls below the cavitation floor, else None.

    The closed-form pressure below the floor has no physical meaning (the fluid
    releases gas or vapour and the chamber no longer follows ``dp = -K dV/V``); the
    run goes on and reports the number, with this warning.
    """
    if not float(trapped_min) < float(vapour_pressure):
        return None
    return (
        f"trapped_pressure_min_bar = {trapped_min / 1e5:.4g} bar is below "
        f"loads.vapour_pressure = {vapour_pressure / 1e5:.4g} bar: the chamber closed at its "
        "largest volume cavitates (the pressure below the floor is the model's, not the "
        "fluid's); a smaller machine.port_land or a higher loads.suction_pressure avoids it"
    )
