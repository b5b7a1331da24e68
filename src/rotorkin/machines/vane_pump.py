"""Differential vane pump on the guide-bar + gear drive: chambers, ports, flow, member torques.

Source of the drive: "Kinematic and mechanical characteristics of the drive
system of a differential vane pump", J. Harbin Institute of Technology 44(9),
2012 (:mod:`rotorkin.drives.guide_bar.kinematics`). The paper gives no pump geometry and no
chamber model: everything in this module is derived here.

Geometry (a cross-section normal to the common axis of the impellers):

* Two coaxial impellers turn in the same sense at the angles ``q_1``, ``q_2``
  of the drive (positive in their mean sense of rotation). Each carries ``Z``
  radial vanes (``vanes_per_impeller``) of angular width ``gamma``
  (``vane_angle``; the paper's "theoretical vane angle" gamma_0 by default),
  spanning the annulus between the hub radius ``R_h`` and the casing radius
  ``R_c`` over the axial width ``w``.
* Vane ``m`` of impeller 1 has its centre line at ``q_1 + 2 pi m / Z``; vane
  ``m`` of impeller 2 at ``q_2 + c + 2 pi m / Z`` with the mounting offset
  ``c = pi/Z - r_mid``, where ``r_mid`` is the middle of the range of the
  relative angle ``r = q_2 - q_1`` over a turn. At mid-swing the vanes of the
  two impellers therefore alternate exactly ``pi/Z`` apart ("impeller 2's vanes
  offset by pi/Z"), and the two kinds of chamber below have the same smallest
  angle.
* ``2 Z`` chambers, numbered round the casing in the sense of rotation:
  chamber ``2m`` ("A") from vane m of impeller 1 to the next vane (m) of
  impeller 2, chamber ``2m + 1`` ("B") from vane m of impeller 2 to vane m + 1 of
  impeller 1. Their angles (the angular gap between the vane centre lines minus
  one vane width) are

      phi_A = (r - r_mid) + pi/Z - gamma,    phi_B = -(r - r_mid) + pi/Z - gamma

  and their volumes ``V = phi (R_c^2 - R_h^2) w / 2``. All A chambers are
  equal, all B chambers are equal; ``phi_A + phi_B = 2 pi/Z - 2 gamma``.
* The relative angle is stationary at the two equal-speed points of the drive
  and swings by ``s = 2 pi/u - 2 gamma_0`` between them
  (:func:`rotorkin.drives.guide_bar.kinematics.relative_angle_swing`), so a chamber angle
  runs between ``phi_min = pi/Z - s/2 - gamma`` and ``phi_min + s``, once per
  period ``2 pi i12`` of the input angle. The vanes fit (no chamber angle ever
  negative) iff ``gamma <= pi/Z - s/2`` (:func:`vane_angle_max`), i.e.
  ``Z (2 gamma + s) <= 2 pi``. With ``Z = u`` and ``gamma = gamma_0`` the chambers
  close completely (``phi_min = 0``): the paper's theoretical vane angle is the
  one that leaves no dead volume.

Ports are ideal: a chamber whose volume shrinks is connected to the discharge
port (pressure ``p_d``), a growing one to the suction port (``p_s``); there is no
leakage, no compressibility and no trapped volume at the switch-over.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.core.angles import fmt_deg, fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.drives.guide_bar import kinematics as gb

__all__ = [
    "VanePump",
    "PortPressures",
    "relative_angle_extremes",
    "vane_angle_max",
    "vane_angles",
    "chamber_angles",
    "chamber_volumes",
    "volume_derivatives_dq",
    "chamber_pressures",
    "displacement",
    "flow_rate",
    "flow_ripple",
]


def relative_angle_extremes(drive: gb.GuideBar) -> tuple[float, float]:
    """Smallest and largest relative angle ``r = q_2 - q_1`` over a period [rad].

    ``r`` is stationary exactly at the two equal-speed points of the drive
    (driving angles ``-Sigma/2`` and ``pi - Sigma/2`` of mechanism 1,
    :func:`rotorkin.drives.guide_bar.kinematics.equal_speed_angles`), so its extremes are
    its values there (closed form, no sampling).

    Returns
    -------
    (r_min, r_max) : tuple of float
        [rad]; ``r_max - r_min = 2 pi/u - 2 gamma_0``.
    """
    t = np.array(gb.equal_speed_angles(drive.phase), dtype=float)
    q = gb.impeller_angles(drive, t * float(drive.input_gear_ratio))[0]
    r = q[1] - q[0]
    return float(np.min(r)), float(np.max(r))


def vane_angle_max(drive: gb.GuideBar, vanes_per_impeller: int) -> float:
    """Widest vane that fits: ``pi/Z - s/2``, ``s`` the relative-angle swing [rad].

    Derived here: with the symmetric mounting of the module docstring the
    smallest chamber angle is ``pi/Z - s/2 - gamma``; it must not be negative.
    Non-positive when ``Z s >= 2 pi`` (no vane of any width fits).
    """
    return np.pi / int(vanes_per_impeller) - 0.5 * float(gb.relative_angle_swing(drive))


@dataclass(frozen=True)
class VanePump:
    """Geometry of a differential vane pump on a guide-bar drive (SI).

    Parameters
    ----------
    drive : rotorkin.drives.guide_bar.kinematics.GuideBar
        The drive (already validated).
    vanes_per_impeller : int, optional
        ``Z >= 1`` vanes on each impeller (default 2).
    vane_angle : float or None, optional
        Angular width gamma of one vane [rad]; ``None`` (default) takes the
        drive's theoretical vane angle gamma_0 (paper section 3, eq. 5, 6).
        After construction it always holds the resolved value.
    hub_radius : float, optional
        Hub radius ``R_h`` [m], ``0 < R_h < R_c`` (default 30 mm).
    casing_radius : float, optional
        Casing (vane tip) radius ``R_c`` [m] (default 80 mm).
    axial_width : float, optional
        Axial width ``w`` of the working space [m], ``w > 0`` (default 40 mm).

    Raises
    ------
    ParameterError
        Named by field: ``hub_radius``, ``casing_radius``, ``axial_width``,
        ``vanes_per_impeller`` (not an integer >= 1, or too many to fit at the
        default vane angle) or ``vane_angle`` (not in ``(0, vane_angle_max]``).
    """

    drive: gb.GuideBar
    vanes_per_impeller: int = 2
    vane_angle: float | None = None
    hub_radius: float = 0.030
    casing_radius: float = 0.080
    axial_width: float = 0.040

    def __post_init__(self):
        rh, rc, w = float(self.hub_radius), float(self.casing_radius), float(self.axial_width)
        if not (np.isfinite(rh) and rh > 0.0):
            raise ParameterError("hub_radius", fmt_mm(rh), "hub_radius > 0 mm")
        if not (np.isfinite(rc) and rc > rh):
            raise ParameterError(
                "hub_radius",
                fmt_mm(rh),
                f"hub_radius < casing_radius = {fmt_mm(rc)} (the vanes span the annulus between)",
            )
        if not (np.isfinite(w) and w > 0.0):
            raise ParameterError("axial_width", fmt_mm(w), "axial_width > 0 mm")
        z = self.vanes_per_impeller
        if isinstance(z, bool) or not isinstance(z, (int, np.integer)) or z < 1:
            raise ParameterError("vanes_per_impeller", repr(z), "an integer >= 1")
        swing = float(gb.relative_angle_swing(self.drive))
        z_fit = int(np.floor(2.0 * np.pi / swing * (1.0 + 1e-12)))
        if z > z_fit:
            raise ParameterError(
                "vanes_per_impeller",
                str(z),
                f"1 <= vanes_per_impeller <= {z_fit}: the relative angle of the impellers "
                f"swings by {fmt_deg(swing)}, and Z (2 vane_angle + swing) <= 360 deg",
            )
        gmax = vane_angle_max(self.drive, z)
        if self.vane_angle is None:
            g0 = float(
                gb.vane_angle(
                    self.drive.lam, self.drive.gear_ratio, self.drive.phase, self.drive.driver
                )
            )
            if g0 > gmax + 1e-12:
                z_max = int(np.floor(2.0 * np.pi / (2.0 * g0 + swing) * (1.0 + 1e-12)))
                raise ParameterError(
                    "vanes_per_impeller",
                    str(z),
                    f"1 <= vanes_per_impeller <= {z_max} with the default vane_angle = gamma_0 "
                    f"= {fmt_deg(g0)} (Z (2 vane_angle + swing {fmt_deg(swing)}) <= 360 deg); "
                    f"or give vane_angle <= {fmt_deg(gmax)}",
                )
            object.__setattr__(self, "vane_angle", g0)
        g = float(self.vane_angle)
        if not (np.isfinite(g) and 0.0 < g <= gmax + 1e-12):
            raise ParameterError(
                "vane_angle",
                fmt_deg(g),
                f"0 deg < vane_angle <= {fmt_deg(gmax)} (the widest vane that fits with "
                f"vanes_per_impeller = {z}: pi/Z - swing/2, swing {fmt_deg(swing)}; wider vanes "
                "would make a chamber negative)",
            )
        object.__setattr__(self, "vane_angle", g)

    @property
    def n_chambers(self) -> int:
        """Number of chambers, ``2 Z``."""
        return 2 * int(self.vanes_per_impeller)

    @property
    def volume_per_angle(self) -> float:
        """``k = (R_c^2 - R_h^2) w / 2`` [m^3/rad]: chamber volume per radian of chamber angle."""
        rh, rc = float(self.hub_radius), float(self.casing_radius)
        return 0.5 * (rc * rc - rh * rh) * float(self.axial_width)

    @property
    def relative_angle_mid(self) -> float:
        """``r_mid``, the middle of the range of ``q_2 - q_1`` [rad]."""
        return 0.5 * sum(relative_angle_extremes(self.drive))

    @property
    def vane_offset(self) -> float:
        """Mounting offset ``c = pi/Z - r_mid`` of impeller 2's vanes from its zero [rad]."""
        return np.pi / int(self.vanes_per_impeller) - self.relative_angle_mid

    @property
    def chamber_angle_range(self) -> tuple[float, float]:
        """Smallest and largest chamber angle over a period [rad] (closed form).

        ``phi_min = pi/Z - s/2 - gamma`` (set to 0 within 1e-12 rad, the
        default design ``Z = u``, ``gamma = gamma_0``), ``phi_max = phi_min + s``.
        """
        s = float(gb.relative_angle_swing(self.drive))
        lo = np.pi / int(self.vanes_per_impeller) - 0.5 * s - float(self.vane_angle)
        lo = 0.0 if abs(lo) < 1e-12 else lo
        return lo, lo + s


@dataclass(frozen=True)
class PortPressures:
    """Absolute pressures at the ports [Pa] (config ``loads.suction_pressure``, ``_discharge_``).

    Both must be > 0 (absolute). ``discharge_pressure < suction_pressure`` is
    admitted: the machine then runs as a motor (the shaft torque turns positive).
    """

    suction_pressure: float = 1.0e5
    discharge_pressure: float = 1.0e5

    def __post_init__(self):
        for name in ("suction_pressure", "discharge_pressure"):
            v = float(getattr(self, name))
            if not (np.isfinite(v) and v > 0.0):
                raise ParameterError(name, f"{v / 1e5:.4g} bar", f"{name} > 0 bar (absolute)")


# --------------------------------------------------------------------------------------------
# geometry
# --------------------------------------------------------------------------------------------
def vane_angles(pump: VanePump, theta):
    """Angles of the vane centre lines [rad], shape (2, Z, ...).

    ``[0, m] = q_1 + 2 pi m/Z``, ``[1, m] = q_2 + c + 2 pi m/Z`` (module docstring).
    """
    theta = np.asarray(theta, dtype=float)
    z = int(pump.vanes_per_impeller)
    q = gb.impeller_angles(pump.drive, theta)[0]
    m = (2.0 * np.pi / z * np.arange(z)).reshape((z,) + (1,) * theta.ndim)
    return np.stack([q[0][None] + m, q[1][None] + pump.vane_offset + m])


def chamber_angles(pump: VanePump, theta):
    """Chamber angles and their derivatives with respect to theta, shape (2 Z, ...).

    ``phi_A = (r - r_mid) + pi/Z - gamma`` (even index), ``phi_B = -(r - r_mid)
    + pi/Z - gamma`` (odd index), ``r = q_2 - q_1``.

    Returns
    -------
    tuple of 4 ndarray, shape (2 Z, ...)
        ``phi`` [rad] and ``dphi/dtheta`` [-], ``d2phi/dtheta2`` [1/rad],
        ``d3phi/dtheta3`` [1/rad^2] (exact, from the drive's closed forms).
    """
    theta = np.asarray(theta, dtype=float)
    z = int(pump.vanes_per_impeller)
    q = gb.impeller_angles(pump.drive, theta)
    rel = [a[1] - a[0] for a in q]
    base = np.pi / z - float(pump.vane_angle)
    mid = pump.relative_angle_mid
    sign = np.tile([1.0, -1.0], z).reshape((2 * z,) + (1,) * theta.ndim)
    phi = sign * (rel[0] - mid)[None] + base
    return (phi, *(sign * d[None] for d in rel[1:]))


def chamber_volumes(pump: VanePump, theta):
    """Chamber volumes ``V = k phi`` and ``dV/dtheta``, shape (2 Z, ...).

    Returns
    -------
    (V, dV) : tuple of ndarray, shape (2 Z, ...)
        [m^3], [m^3/rad]; ``k`` = :attr:`VanePump.volume_per_angle`.
    """
    phi, dphi, _, _ = chamber_angles(pump, theta)
    k = pump.volume_per_angle
    return k * phi, k * dphi


def volume_derivatives_dq(pump: VanePump, theta):
    """Partial derivatives ``dV_j/dq_i`` [m^3/rad], shape (2, 2 Z, ...).

    ``dV_A/dq_1 = -k``, ``dV_A/dq_2 = +k``; ``dV_B/dq_1 = +k``, ``dV_B/dq_2 = -k``
    (a chamber grows when its leading vane gains on its trailing vane).
    """
    theta = np.asarray(theta, dtype=float)
    z = int(pump.vanes_per_impeller)
    k = pump.volume_per_angle
    a = np.array([[-k, k], [k, -k]])  # (member, chamber kind)
    table = np.tile(a, (1, z))  # (2, 2 Z)
    return np.broadcast_to(table.reshape(table.shape + (1,) * theta.ndim), (2, 2 * z, *theta.shape))


def chamber_pressures(dvolume, ports: PortPressures):
    """Ideal ports: ``p_d`` where ``dV/dtheta < 0`` (discharge), else ``p_s`` [Pa].

    Parameters
    ----------
    dvolume : array_like, shape (n_chambers, ...)
        ``dV/dtheta`` [m^3/rad] (the shaft turns one way, so its sign is that of dV/dt).
    ports : PortPressures

    Returns
    -------
    ndarray, shape (n_chambers, ...)
        [Pa]. At ``dV = 0`` (the switch-over) the suction pressure is taken;
        the shaft torque does not depend on that choice.
    """
    dv = np.asarray(dvolume, dtype=float)
    return np.where(dv < 0.0, float(ports.discharge_pressure), float(ports.suction_pressure))


# --------------------------------------------------------------------------------------------
# displacement and flow
# --------------------------------------------------------------------------------------------
def displacement(pump: VanePump) -> dict:
    """Volume discharged, per period, per input-gear turn and per impeller revolution [m^3].

    Each of the ``2 Z`` chambers shrinks once per period ``2 pi i12`` from its
    largest to its smallest volume: ``D_period = 2 Z k s`` (``s`` the relative
    angle swing). Per input turn: ``D_period / i12``. An impeller advances
    ``2 pi/u`` per period, so per impeller revolution: ``u D_period``.

    Returns
    -------
    dict
        ``"per_period"``, ``"per_input_turn"``, ``"per_impeller_rev"`` [m^3].
    """
    s = float(gb.relative_angle_swing(pump.drive))
    per_period = pump.n_chambers * pump.volume_per_angle * s
    return {
        "per_period": per_period,
        "per_input_turn": per_period / float(pump.drive.input_gear_ratio),
        "per_impeller_rev": per_period * float(pump.drive.gear_ratio),
    }


def flow_rate(pump: VanePump, theta, omega=1.0):
    """Instantaneous delivered flow ``Q = omega sum_j max(-dV_j/dtheta, 0)`` [m^3/s].

    With ideal ports the discharging chambers are the shrinking ones;
    ``Q = omega Z k |r'|`` (all A or all B chambers discharge at once). ``omega``
    [rad/s] broadcasts with theta (1 gives the flow per unit shaft speed,
    [m^3/rad]).
    """
    _, dv = chamber_volumes(pump, theta)
    return np.asarray(omega, dtype=float) * np.sum(np.maximum(-dv, 0.0), axis=0)


def flow_ripple(flow, time_weights=None):
    """``(max - min) / mean`` of a flow sampled over one period (ends included) [-].

    Parameters
    ----------
    flow : array_like, shape (n,)
        Flow [m^3/s] at the samples, both ends of the period included.
    time_weights : array_like, shape (n,), optional
        ``1/omega`` at the samples, to average over time when the shaft speed
        varies (default: equal weights, constant speed).
    """
    q = np.asarray(flow, dtype=float)
    wts = np.ones_like(q) if time_weights is None else np.asarray(time_weights, dtype=float)
    # trapezoid in the angle with weights dt = dtheta/omega on an even grid
    mean = np.trapezoid(q * wts) / np.trapezoid(wts)
    with np.errstate(divide="ignore", invalid="ignore"):
        return float((np.max(q) - np.min(q)) / mean) if mean > 0 else float("nan")
