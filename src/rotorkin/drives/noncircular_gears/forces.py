"""Forces of the non-circular gear drive: both meshes and the bearings of shaft and rotors.

Frame: the plane of the gears, ``x`` from the shaft's axis to the rotors' axis (the
line of centres), ``y`` normal to it. Gear pair ``i`` meshes at the pitch point on the
line of centres, at ``r1`` from the shaft and ``r2 = a - r1`` from the rotors' axis.

* **Tangential force** ``F_t,i = D_i / r2`` at the pitch point (normal to the line of
  centres): ``D_i`` is the torque the drive must put on rotor ``i`` (machine and inertia,
  :mod:`rotorkin.vane`); a force along the line of centres has no moment about
  either axis. The shaft then needs ``F_t,i r1 = D_i r1/r2 = D_i q_i'``: the
  virtual-work torque, pair by pair.
* **Local pressure angle.** A non-circular pitch curve's tangent is inclined to the
  normal of the line of centres by ``nu`` with ``tan nu = r1'/r1`` (polar tangent
  angle of the driving curve at the contact); the teeth's normal is inclined by the
  tool's pressure angle ``alpha_0`` (``drive.pressure_angle``) to the tangent, so the
  force makes ``alpha = alpha_0 + nu`` or ``alpha_0 - nu`` with the normal of the line
  of centres, by the flank that carries it. Here the larger, ``alpha_0 + |nu|``: an
  upper bound of the normal force ``F_n = |F_t| / cos(alpha)`` whichever flank drives.
* **Contact stress** (Hertz line contact over ``drive.face_width``): the flanks' radii
  of curvature at the pitch point are taken as the pitch curves' radii of curvature
  times ``sin(alpha)``, exact for circular involute gears (``r sin alpha_0``), a local
  approximation for non-circular ones.
* **Friction**: a mesh loses ``contact.friction_mesh`` of the power it transmits (slip
  ``r1 cos(alpha)`` per rad of shaft); bearings ``contact.friction_bearing`` at
  ``contact.bearing_radius``.
* **Bearings**: each rotor's bearing carries its mesh force ``F_n``; the shaft's
  bearings carry the vector sum of both meshes' forces on the driving gears.
"""

from __future__ import annotations

import numpy as np

from rotorkin.analysis.pairs import Pair
from rotorkin.drives.noncircular_gears import kinematics as ng

__all__ = ["mesh_forces", "pairs"]


def mesh_forces(params: ng.NoncircularGears, theta, drive_torque, pressure_angle):
    """Tangential and normal mesh forces, radii and pressure angle of both pairs.

    Parameters
    ----------
    params : NoncircularGears
    theta : ndarray, shape (n,)
        Shaft angles [rad].
    drive_torque : ndarray, shape (2, n)
        Torque the drive puts on each rotor, along +q_i [N m].
    pressure_angle : float
        The tool's pressure angle alpha_0 [rad].

    Returns
    -------
    dict of ndarray, shape (2, n)
        ``r1``, ``r2`` [m], ``alpha`` [rad], ``ft`` (signed, + pushes rotor i forward),
        ``fn`` [N].
    """
    theta = np.asarray(theta, dtype=float)
    offsets = np.array([0.0, float(ng._phase(params))])[:, None]
    phi1 = theta[None, :] + offsets  # each driving gear's own angle at the contact
    a = float(params.centre_distance)
    n, e = float(params.lobes), float(params.eccentricity)
    r1 = ng.pitch_radius(params, "driving", phi1)
    dr1 = -r1 * r1 * n * e * np.sin(n * phi1) / float(ng.pitch_parameter(params))
    nu = np.arctan2(dr1, r1)
    alpha = float(pressure_angle) + np.abs(nu)
    r2 = a - r1
    ft = np.asarray(drive_torque, dtype=float) / r2
    return {"r1": r1, "r2": r2, "alpha": alpha, "ft": ft, "fn": np.abs(ft) / np.cos(alpha),
            "phi1": phi1}  # fmt: skip


def pairs(params, theta, drive_torque, motion, pressure_angle, face_width, bearing_radius):
    """The meshes and bearings as :class:`~rotorkin.analysis.pairs.Pair` s over ``theta``."""
    f = mesh_forces(params, theta, drive_torque, pressure_angle)
    rb = float(bearing_radius)
    out = []
    fx = fy = 0.0  # force of the driven gears on the driving gears, summed
    for i in (0, 1):
        rho1 = 1.0 / ng.curvature(params, "driving", f["phi1"][i])
        phi2 = ng.driven_angle(params, f["phi1"][i])[0]  # the driven gear's own angle there
        rho2 = 1.0 / ng.curvature(params, "driven", phi2)
        s = np.sin(f["alpha"][i])
        out.append(Pair(
            f"mesh {i + 1} (shaft gear - rotor {i + 1} gear)", f"mesh{i + 1}", "mesh",
            f["fn"][i], f["r1"][i] * np.cos(f["alpha"][i]),
            ("line", rho1 * s, rho2 * s, float(face_width)),
            "along the line of action at the pitch point, inclined alpha_0 + |nu| to the "
            "normal of the line of centres",
        ))  # fmt: skip
        out.append(Pair(
            f"rotor {i + 1} bearing", f"rotor{i + 1}_bearing", "bearing", f["fn"][i],
            rb * np.abs(motion.dq[i]), None, "the mesh force of pair " + str(i + 1),
        ))  # fmt: skip
        fx = fx - f["fn"][i] * s
        fy = fy - np.sign(f["ft"][i]) * f["fn"][i] * np.cos(f["alpha"][i])
    out.append(Pair("shaft bearings", "shaft_bearing", "bearing", np.hypot(fx, fy),
                    np.full_like(np.asarray(theta, dtype=float), rb), None,
                    "vector sum of both meshes' forces on the shaft's gears"))  # fmt: skip
    return out
