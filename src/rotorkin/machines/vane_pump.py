"""Differential vane pump: two coaxial impellers with vanes; chambers, ports, flow, member torques.

The pump is driven by any drive that turns two coaxial impellers in the same
sense at unequal, periodically varying speeds (e.g. the drive of "Kinematic and
mechanical characteristics of the drive system of a differential vane pump",
J. Harbin Institute of Technology 44(9), 2012). This module needs from the drive
only the impellers' motion (:class:`rotorkin.core.motion.Motion`: angles ``q_1``,
``q_2`` and their derivatives with respect to the input angle ``theta``) and two
plain numbers, the smallest and largest relative angle ``r = q_2 - q_1`` over a
period. The paper gives no pump geometry and no chamber model: everything in this
module is derived here.

Geometry (a cross-section normal to the common axis of the impellers):

* Two coaxial impellers turn in the same sense at the angles ``q_1``, ``q_2``
  (positive in their mean sense of rotation). Each carries ``Z`` radial vanes
  (``vanes_per_impeller``) of angular width ``gamma`` (``vane_angle``; by default
  the drive's "theoretical vane angle" gamma_0, chosen by the drive's package),
  spanning the annulus between the hub radius ``R_h`` and the casing radius
  ``R_c`` over the axial width ``w``.
* Vane ``m`` of impeller 1 has its centre line at ``q_1 + 2 pi m / Z``; vane
  ``m`` of impeller 2 at ``q_2 + c + 2 pi m / Z`` with the mounting offset
  ``c = pi/Z - r_mid``, where ``r_mid = (r_min + r_max)/2`` is the middle of the
  range of the relative angle over a period. At mid-swing the vanes of the two
  impellers therefore alternate exactly ``pi/Z`` apart ("impeller 2's vanes
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
* The relative angle swings by ``s = r_max - r_min`` once per period, so a
  chamber angle runs between ``phi_min = pi/Z - s/2 - gamma`` and
  ``phi_min + s``. The vanes fit (no chamber angle ever negative) iff
  ``gamma <= pi/Z - s/2`` (:func:`vane_angle_max`), i.e.
  ``Z (2 gamma + s) <= 2 pi``. With the drive's theoretical vane angle and ``Z``
  equal to its gear ratio the chambers close completely (``phi_min = 0``): no
  dead volume.

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
from rotorkin.core.motion import Motion

__all__ = [
    "CHECKS",
    "PORT_FIELDS",
    "inadmissible",
    "ports_inadmissible",
    "vanes_that_fit",
    "VanePump",
    "PortPressures",
    "vane_angle_max",
    "vane_angles",
    "chamber_angles",
    "chamber_volumes",
    "volume_derivatives_dq",
    "chamber_pressures",
    "displacement",
    "flow_rate",
    "flow_ripple",
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


def vane_angle_max(vanes_per_impeller, swing):
    """Widest vane that fits: ``pi/Z - s/2`` [rad].

    Derived here: with the symmetric mounting of the module docstring the
    smallest chamber angle is ``pi/Z - s/2 - gamma``; it must not be negative.
    Non-positive when ``Z s >= 2 pi`` (no vane of any width fits).

    Parameters
    ----------
    vanes_per_impeller : array_like
        ``Z`` [-].
    swing : array_like
        Swing ``s = r_max - r_min`` of the relative angle [rad]; broadcasts with ``Z``.

    Returns
    -------
    ndarray
        [rad].
    """
    return np.pi / np.asarray(vanes_per_impeller) - 0.5 * np.asarray(swing, dtype=float)


#: What :func:`inadmissible` checks, in order; its codes are index + 1. Entry k names the
#: field that check k charges.
CHECKS = (
    "hub_radius",  # > 0
    "hub_radius",  # < casing_radius
    "axial_width",  # > 0
    "vanes_per_impeller",  # an integer >= 1
    "relative_angle_max",  # finite, >= relative_angle_min
    "vanes_per_impeller",  # Z (2 gamma + s) <= 2 pi for some gamma > 0
    "vane_angle",  # 0 < gamma <= pi/Z - s/2
)


def _is_count(z):
    """Whether each ``z`` is an integer >= 1 (booleans and strings are not)."""
    if isinstance(z, bool) or (np.ndim(z) == 0 and not isinstance(z, (int, np.integer))):
        return np.zeros((), dtype=bool)
    z = np.asarray(z)
    if not np.issubdtype(z.dtype, np.integer):
        return np.zeros(z.shape, dtype=bool)
    return z >= 1


def vanes_that_fit(swing):
    """Most vanes per impeller that fit a relative-angle swing ``s``: ``floor(2 pi / s)`` [-].

    The vanes fit with some width ``gamma > 0`` iff ``Z s < 2 pi`` (allowing
    ``Z s = 2 pi`` within 1e-12 relative); unlimited (inf) at ``s = 0``.
    """
    s = np.asarray(swing, dtype=float)
    with np.errstate(divide="ignore"):
        return np.floor(2.0 * np.pi / s * (1.0 + 1e-12))


def inadmissible(
    relative_angle_min,
    relative_angle_max,
    vane_angle,
    vanes_per_impeller=2,
    hub_radius=0.030,
    casing_radius=0.080,
    axial_width=0.040,
):
    """The first check of :data:`CHECKS` each design fails, as index + 1 (0: admissible).

    Parameters
    ----------
    relative_angle_min, relative_angle_max, vane_angle, vanes_per_impeller, hub_radius, \
casing_radius, axial_width : array_like
        As :class:`VanePump`; broadcast together.

    Returns
    -------
    ndarray of int16
    """
    lo, hi, g, rh, rc, w = (np.asarray(v, dtype=float) for v in (
        relative_angle_min, relative_angle_max, vane_angle, hub_radius, casing_radius,
        axial_width))  # fmt: skip
    count = _is_count(vanes_per_impeller)
    zr = np.asarray(vanes_per_impeller)
    integer = np.issubdtype(zr.dtype, np.integer)
    z = np.where(count, zr, 1).astype(float) if integer else np.ones(count.shape)
    with np.errstate(invalid="ignore", divide="ignore"):
        swing = hi - lo
        bad = (
            ~(np.isfinite(rh) & (rh > 0.0)),
            ~(np.isfinite(rc) & (rc > rh)),
            ~(np.isfinite(w) & (w > 0.0)),
            ~count,
            ~(np.isfinite(lo) & np.isfinite(hi) & (hi >= lo)),
            (swing > 0.0) & (z > vanes_that_fit(swing)),
            ~(np.isfinite(g) & (g > 0.0) & (g <= vane_angle_max(z, swing) + 1e-12)),
        )
    bad = np.broadcast_arrays(*bad)
    reason = np.zeros(bad[0].shape, dtype=np.int16)
    for k in range(len(bad) - 1, -1, -1):  # the first failed check wins
        reason[bad[k]] = k + 1
    return reason


def _scalar(x):
    """A 0-d result as a Python float; arrays unchanged."""
    return float(x) if np.ndim(x) == 0 else x


@dataclass(frozen=True)
class VanePump:
    """Geometry of a differential vane pump (SI).

    The fields may be arrays (one value per design, broadcasting together) for the
    closed-form properties; the functions of the angle need one ``vanes_per_impeller``.

    Parameters
    ----------
    relative_angle_min, relative_angle_max : float
        Smallest and largest relative angle ``r = q_2 - q_1`` of the impellers
        over a period [rad] (given by the drive), ``r_min <= r_max``.
    vane_angle : float
        Angular width gamma of one vane [rad], ``0 < gamma <= pi/Z - s/2``.
    vanes_per_impeller : int, optional
        ``Z >= 1`` vanes on each impeller (default 2), ``Z s <= 2 pi``.
    hub_radius : float, optional
        Hub radius ``R_h`` [m], ``0 < R_h < R_c`` (default 30 mm).
    casing_radius : float, optional
        Casing (vane tip) radius ``R_c`` [m] (default 80 mm).
    axial_width : float, optional
        Axial width ``w`` of the working space [m], ``w > 0`` (default 40 mm).

    Raises
    ------
    ParameterError
        Named by the field of the first failed check (:func:`inadmissible`), with
        its value and the admissible range.
    """

    relative_angle_min: float
    relative_angle_max: float
    vane_angle: float
    vanes_per_impeller: int = 2
    hub_radius: float = 0.030
    casing_radius: float = 0.080
    axial_width: float = 0.040

    def __post_init__(self):
        values = (self.relative_angle_min, self.relative_angle_max, self.vane_angle,
                  self.vanes_per_impeller, self.hub_radius, self.casing_radius,
                  self.axial_width)  # fmt: skip
        reason = inadmissible(*values)
        if reason.any():
            i = int(np.flatnonzero(reason)[0])
            raise self._error(int(reason.flat[i]) - 1, i, reason.shape)
        object.__setattr__(self, "vane_angle", _scalar(np.asarray(self.vane_angle, dtype=float)))

    def _error(self, check: int, i: int, shape) -> ParameterError:
        """The :class:`ParameterError` of check ``check`` at design ``i`` (flat index)."""

        def at(name):
            v = np.broadcast_to(np.asarray(getattr(self, name)), shape).flat[i]
            return v.item() if hasattr(v, "item") else v

        rh, rc, lo, hi = (at(n) for n in ("hub_radius", "casing_radius", "relative_angle_min",
                                          "relative_angle_max"))  # fmt: skip
        if check == 0:
            return ParameterError("hub_radius", fmt_mm(rh), "hub_radius > 0 mm")
        if check == 1:
            return ParameterError(
                "hub_radius",
                fmt_mm(rh),
                f"hub_radius < casing_radius = {fmt_mm(rc)} (the vanes span the annulus between)",
            )
        if check == 2:
            return ParameterError("axial_width", fmt_mm(at("axial_width")), "axial_width > 0 mm")
        z = at("vanes_per_impeller")
        if check == 3:
            return ParameterError("vanes_per_impeller", repr(z), "an integer >= 1")
        if check == 4:
            return ParameterError(
                "relative_angle_max", fmt_deg(hi), f"finite, >= relative_angle_min {fmt_deg(lo)}"
            )
        swing = hi - lo
        if check == 5:
            return ParameterError(
                "vanes_per_impeller",
                str(z),
                f"1 <= vanes_per_impeller <= {int(vanes_that_fit(swing))}: the relative angle of "
                f"the impellers swings by {fmt_deg(swing)}, and Z (2 vane_angle + swing) "
                "<= 360 deg",
            )
        gmax = float(vane_angle_max(z, swing))
        return ParameterError(
            "vane_angle",
            fmt_deg(at("vane_angle")),
            f"0 deg < vane_angle <= {fmt_deg(gmax)} (the widest vane that fits with "
            f"vanes_per_impeller = {z}: pi/Z - swing/2, swing {fmt_deg(swing)}; wider vanes "
            "would make a chamber negative)",
        )

    @property
    def swing(self):
        """Swing ``s = r_max - r_min`` of the relative angle over a period [rad]."""
        lo, hi = (np.asarray(v, dtype=float) for v in (self.relative_angle_min,
                                                         self.relative_angle_max))  # fmt: skip
        return _scalar(hi - lo)

    @property
    def vane_angle_max(self):
        """Widest vane that fits, ``pi/Z - s/2`` [rad] (:func:`vane_angle_max`)."""
        return _scalar(vane_angle_max(self.vanes_per_impeller, self.swing))

    @property
    def n_chambers(self):
        """Number of chambers, ``2 Z``."""
        z = self.vanes_per_impeller
        return 2 * int(z) if np.ndim(z) == 0 else 2 * np.asarray(z)

    @property
    def volume_per_angle(self):
        """``k = (R_c^2 - R_h^2) w / 2`` [m^3/rad]: chamber volume per radian of chamber angle."""
        rh, rc, w = (np.asarray(v, dtype=float) for v in (self.hub_radius, self.casing_radius,
                                                            self.axial_width))  # fmt: skip
        return _scalar(0.5 * (rc * rc - rh * rh) * w)

    @property
    def relative_angle_mid(self):
        """``r_mid``, the middle of the range of ``q_2 - q_1`` [rad]."""
        lo, hi = (np.asarray(v, dtype=float) for v in (self.relative_angle_min,
                                                         self.relative_angle_max))  # fmt: skip
        return _scalar(0.5 * (lo + hi))

    @property
    def vane_offset(self):
        """Mounting offset ``c = pi/Z - r_mid`` of impeller 2's vanes from its zero [rad]."""
        return _scalar(np.pi / np.asarray(self.vanes_per_impeller) - self.relative_angle_mid)

    @property
    def chamber_angle_range(self):
        """Smallest and largest chamber angle over a period [rad] (closed form).

        ``phi_min = pi/Z - s/2 - gamma`` (set to 0 within 1e-12 rad: chambers that
        close completely), ``phi_max = phi_min + s``.
        """
        s = self.swing
        lo = np.pi / np.asarray(self.vanes_per_impeller) - 0.5 * s - self.vane_angle
        lo = np.where(np.abs(lo) < 1e-12, 0.0, lo)
        return _scalar(lo), _scalar(lo + s)


#: Fields of :class:`PortPressures`, in the order they are checked (codes index + 1).
PORT_FIELDS = ("suction_pressure", "discharge_pressure")


def ports_inadmissible(suction_pressure, discharge_pressure):
    """The first port pressure each design gets wrong (not > 0), index + 1 into :data:`PORT_FIELDS`.

    Returns
    -------
    ndarray of int16
        0 where both are admissible.
    """
    ps, pd = (np.asarray(v, dtype=float) for v in (suction_pressure, discharge_pressure))
    with np.errstate(invalid="ignore"):
        bad = np.broadcast_arrays(~(np.isfinite(ps) & (ps > 0.0)), ~(np.isfinite(pd) & (pd > 0.0)))
    return np.where(bad[0], 1, np.where(bad[1], 2, 0)).astype(np.int16)


@dataclass(frozen=True)
class PortPressures:
    """Absolute pressures at the ports [Pa] (config ``loads.suction_pressure``, ``_discharge_``).

    Both must be > 0 (absolute). ``discharge_pressure < suction_pressure`` is
    admitted: the machine then runs as a motor (the shaft torque turns positive).
    """

    suction_pressure: float = 1.0e5
    discharge_pressure: float = 6.0e5

    def __post_init__(self):
        reason = ports_inadmissible(self.suction_pressure, self.discharge_pressure)
        if reason.any():
            i = int(np.flatnonzero(reason)[0])
            name = PORT_FIELDS[int(reason.flat[i]) - 1]
            v = float(np.broadcast_to(np.asarray(getattr(self, name)), reason.shape).flat[i])
            raise ParameterError(name, f"{v / 1e5:.4g} bar", f"{name} > 0 bar (absolute)")


# --------------------------------------------------------------------------------------------
# geometry
# --------------------------------------------------------------------------------------------
def vane_angles(pump: VanePump, motion: Motion):
    """Angles of the vane centre lines [rad], shape (2, Z, ...).

    ``[0, m] = q_1 + 2 pi m/Z``, ``[1, m] = q_2 + c + 2 pi m/Z`` (module docstring).

    Parameters
    ----------
    pump : VanePump
    motion : rotorkin.core.motion.Motion
        The impellers' motion; ``motion.q`` has shape (2, ...) [rad].
    """
    q = np.asarray(motion.q, dtype=float)
    z = int(pump.vanes_per_impeller)
    m = (2.0 * np.pi / z * np.arange(z)).reshape((z,) + (1,) * (q.ndim - 1))
    return np.stack([q[0][None] + m, q[1][None] + pump.vane_offset + m])


def chamber_angles(pump: VanePump, motion: Motion):
    """Chamber angles and their derivatives with respect to theta, shape (2 Z, ...).

    ``phi_A = (r - r_mid) + pi/Z - gamma`` (even index), ``phi_B = -(r - r_mid)
    + pi/Z - gamma`` (odd index), ``r = q_2 - q_1``.

    Returns
    -------
    tuple of 4 ndarray, shape (2 Z, ...)
        ``phi`` [rad] and ``dphi/dtheta`` [-], ``d2phi/dtheta2`` [1/rad],
        ``d3phi/dtheta3`` [1/rad^2] (exact, from the motion's derivatives).
    """
    rel = motion.relative
    z = int(pump.vanes_per_impeller)
    base = np.pi / z - float(pump.vane_angle)
    mid = pump.relative_angle_mid
    sign = np.tile([1.0, -1.0], z).reshape((2 * z,) + (1,) * np.ndim(rel[0]))
    phi = sign * (rel[0] - mid)[None] + base
    return (phi, *(sign * d[None] for d in rel[1:]))


def chamber_volumes(pump: VanePump, motion: Motion):
    """Chamber volumes ``V = k phi`` and ``dV/dtheta``, shape (2 Z, ...).

    Returns
    -------
    (V, dV) : tuple of ndarray, shape (2 Z, ...)
        [m^3], [m^3/rad]; ``k`` = :attr:`VanePump.volume_per_angle`.
    """
    phi, dphi, _, _ = chamber_angles(pump, motion)
    k = pump.volume_per_angle
    return k * phi, k * dphi


def volume_derivatives_dq(pump: VanePump, motion: Motion):
    """Partial derivatives ``dV_j/dq_i`` [m^3/rad], shape (2, 2 Z, ...).

    ``dV_A/dq_1 = -k``, ``dV_A/dq_2 = +k``; ``dV_B/dq_1 = +k``, ``dV_B/dq_2 = -k``
    (a chamber grows when its leading vane gains on its trailing vane).
    """
    shape = np.shape(motion.q)[1:]
    z = int(pump.vanes_per_impeller)
    k = pump.volume_per_angle
    a = np.array([[-k, k], [k, -k]])  # (member, chamber kind)
    table = np.tile(a, (1, z))  # (2, 2 Z)
    return np.broadcast_to(table.reshape(table.shape + (1,) * len(shape)), (2, 2 * z, *shape))


def chamber_pressures(ports: PortPressures, dvolume):
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
def displacement(pump: VanePump) -> float:
    """Volume discharged per period of the relative angle, ``2 Z k s`` [m^3].

    Each of the ``2 Z`` chambers shrinks once per period from its largest to its
    smallest volume, by ``k s`` (``s`` the relative-angle swing).
    """
    return pump.n_chambers * pump.volume_per_angle * pump.swing


def flow_rate(pump: VanePump, motion: Motion, omega=1.0):
    """Instantaneous delivered flow ``Q = omega sum_j max(-dV_j/dtheta, 0)`` [m^3/s].

    With ideal ports the discharging chambers are the shrinking ones;
    ``Q = omega Z k |r'|`` (all A or all B chambers discharge at once). ``omega``
    [rad/s] broadcasts with the motion's angles (1 gives the flow per unit shaft
    speed, [m^3/rad]).
    """
    _, dv = chamber_volumes(pump, motion)
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
