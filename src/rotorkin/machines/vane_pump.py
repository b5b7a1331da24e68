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
antiphase). The ports' sealing land, the leakage through the vane clearances,
the compression loss and the flow delivered are in :mod:`rotorkin.machines.pump_flow`.
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
    base = np.pi / z - np.asarray(pump.vane_angle, dtype=float)  # a column of designs, too
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
    k = np.asarray(pump.volume_per_angle, dtype=float)  # a column of designs, too
    sign = np.tile([[-1.0, 1.0], [1.0, -1.0]], (1, z))  # (member, chamber): (2, 2 Z)
    return np.broadcast_to(sign.reshape(sign.shape + (1,) * len(shape)) * k, (2, 2 * z, *shape))


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
    return np.where(dv < 0.0, np.asarray(ports.discharge_pressure, dtype=float),
                    np.asarray(ports.suction_pressure, dtype=float))  # fmt: skip


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
    flow : array_like, shape (..., n)
        Flow [m^3/s] at the samples, both ends of the period included (designs on
        the leading axes).
    time_weights : array_like, shape (n,) or (..., n), optional
        ``1/omega`` at the samples, to average over time when the shaft speed
        varies (default: equal weights, constant speed).

    Returns
    -------
    float or ndarray, shape (...)
        NaN where the mean flow is not positive.
    """
    q = np.asarray(flow, dtype=float)
    wts = np.ones_like(q) if time_weights is None else np.asarray(time_weights, dtype=float)
    # trapezoid in the angle with weights dt = dtheta/omega on an even grid
    mean = np.trapezoid(q * wts, axis=-1) / np.trapezoid(wts, axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        ripple = np.where(mean > 0, (np.max(q, axis=-1) - np.min(q, axis=-1)) / mean, np.nan)
    return _scalar(ripple)
