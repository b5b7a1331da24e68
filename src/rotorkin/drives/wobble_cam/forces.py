"""Kinetostatics of the wobble-cam drive: the force in every load-carrying pair, at speed.

Bodies: the Z-shaft (turns by ``theta`` about the fixed x axis), the wobble plate (on the
shaft's inclined section, spins by ``varphi`` about its axis ``x2``), the cam shell (turns
by ``psi = -theta``), rotor 1 and rotor 2 (turn by ``Phi_1``, ``Phi_2``), and the bevel
gearbox (Chen Hu et al. 2015, section 1.1: two equal large bevels, one on the Z-shaft and
one on the cam shaft, and two equal small idler bevels on fixed axes; the outputs turn
equal and opposite). Each of the 4 radial roller shafts of the plate carries an inner
roller in its figure-eight groove and an outer roller in a slider rail of its rotor
(rollers 1, 1' drive rotor 1; 2, 2' rotor 2; order of ``kinematics.roller_offsets``).

Frames and signs
----------------
* Vectors are in the fixed frame xyz (x along the Z-shaft), except where said.
* Positive ``theta``, ``Phi_k`` and ``varphi`` turn right-handed about ``-x`` (``-x2``): they
  take +z towards +y (eq. 4). The cam turns right-handed about ``+x`` (``psi = -theta``).
  A torque on the shaft, a rotor or the plate is positive along its positive turning
  direction; the cam shell's along ``+x``.
* Roller centres: ``p_j = r e_j`` (inner, on the groove sphere) and ``q_j = R e_j``
  (outer, ``R = drive.rail_radius``), ``e_j`` the unit roller-shaft direction (eq. 8).
* Rail: a rotor's rail is a slot with flat walls parallel to the rotor's meridian plane
  through the roller shaft (the rotor angle is the shaft's projection on yz, so the shaft
  stays in that plane); its normal is ``e_Phi = (0, z, -y)/sqrt(y^2 + z^2)`` of ``e_j``,
  the direction of increasing ``Phi``. ``F_j`` is the force roller j puts on its rail
  along ``+e_Phi`` (> 0: the roller drives the rotor forward); the rail puts ``-F_j e_Phi``
  on the roller.
* Groove: ``n_j = e_r x t`` (:func:`rotorkin.drives.wobble_cam.cam.groove_frame`, turned to
  the fixed frame by ``A_psi``), ``t`` the roller's travel along the groove. ``N_j`` is the
  force the cam puts on roller j along ``+n_j``: ``N_j > 0`` is carried by the ``-n`` wall
  (wall 1 of ``cam.groove_walls``), ``N_j < 0`` by the ``+n`` wall (wall 0).

Equations (the drive's own, derived here; the paper gives kinematics only)
--------------------------------------------------------------------------
* Rotor k (bearings about x): ``sum_j F_j rho_j = D_k = J_k qdd_k - M_k`` over its two
  rollers, ``rho_j = R sqrt(e_y^2 + e_z^2)``; the two rollers of a group have the same
  lever arm and share equally (rigid plate and rotor, equal contact stiffness).
* Plate, about its axis ``x2`` (the plate bearing carries no moment about it):
  ``sum_j m_j N_j - sum_j F_j k_j = dH/dt . x2``, ``m_j = r (e_j x n_j) . x2``,
  ``k_j = R (e_j x e_Phi_j) . x2``. The 4 grooves are statically indeterminate; the
  load is shared as by 4 contacts of equal stiffness on a rigid plate turned by a small
  spin: ``N_j = S m_j / sum_i m_i^2`` (the least-squares solution). All four rollers
  carry load, also while one runs through a crossing of groove branches, where a plain
  cylindrical roller has no wall (``cam.guided``): with the paper's grooves the other
  pair then stands at up to 90 deg pressure angle (``cam.pressure_angle``), so with
  walls only away from the crossings the plate's spin is not held at
  ``theta = 22.5 deg + k 45 deg`` and the forces grow without bound. The crossings need a
  follower that bridges them (e.g. an elongated "boat" follower); the study reports the
  load the rollers carry through the crossings (``groove_crossing_force_max_N``).
  :func:`solve` takes a mask of the rollers that carry load for the strict case.
  Opposite rollers carry equal and opposite ``N`` (a couple: no net force on the plate).
* Plate, the other 5 equations: the plate bearing, force ``f_b = -sum(pair forces)``
  (the plate's centre of mass is the fixed point O) and moment
  ``m_b = dH/dt - sum(moments about O)`` (``m_b . x2 = 0``). Two bearings at
  ``+-plate_bearing_span/2`` along ``x2`` carry ``f_b/2 +- (m_b x x2)/span``.
* Plate inertia: axisymmetric, ``H = J_a w_a x2 + J_t w_perp``,
  ``w = -omega (x + varphi' x2)``: the gyroscopic couple (perpendicular to ``x2``) loads
  the plate bearings; its spin part (``J_a dw_a/dt``, zero at a constant speed with the
  linear spin law) passes through the grooves.
* Torques the drive delivers: the plate bearing on the Z-shaft ``T_Z = m_b . x``, the
  grooves on the cam shell ``T_C = -sum_j N_j r (e_j x n_j) . x``; by virtual work
  ``T_Z + T_C = sum_k M_k Phi_k' - sum_k J_k qdd_k Phi_k' - P_plate/omega`` (the total
  output torque ``T``, per unit of shaft speed; both outputs turn at ``omega``).
* Outputs (``drive.output``): the load takes ``T_cam = s T`` at the cam shell and
  ``T_shaft = (1 - s) T`` at the Z-shaft, ``s = 0`` ("shaft"), 1 ("cam") or
  ``drive.cam_torque_share`` ("both"). The bevel gearbox carries the difference
  ``G = T_cam - T_C`` (torque it puts on the cam shell; ``-G`` on the Z-shaft): each large
  bevel meshes with both idlers, tangential force ``|G| / (2 r_p)`` per mesh, normal force
  that over ``cos(pressure angle)``; an idler's two meshes push it the same way
  (``2 F_t``) plus its axial thrust ``2 F_t tan(a) sin(delta_s)``,
  ``tan(delta_s) = 1/bevel_ratio``. ``T_C / T`` is the split the mechanism makes by itself
  (the gearbox idle); "shaft" means the cam shell drives no load of its own. The split is
  statically determinate (the plate is a differential between shaft and cam, the groove
  of the spin law ``varphi(tau)`` being run at ``tau = (theta_shaft + theta_cam)/2``):
  ``T_C = -sum_k D_k (Phi_k' - 1)/2``, ``T_Z = -sum_k D_k (Phi_k' + 1)/2`` without plate
  inertia. The gas torques on the rotors are equal and opposite, so
  ``T_C - T_Z = sum_k J_k qdd_k``: the cam shell takes half of the gas torque on average,
  and with ``output = "both"``, ``cam_torque_share = 0.5`` the gearbox carries only half the
  rotors' inertia torque.
* Cam shell: the grooves' moment less its x component is a tilting couple carried by two
  bearings at ``+-cam_bearing_span/2`` along x (on the housing); the large bevel's axial
  thrust ``2 F_t tan(a) sin(delta_L)`` is reported apart.

Neglected: the Z-shaft's, cam shell's and idlers' own inertia (constant-axis bodies: no
torque at a constant run speed; with a speed profile, ``J theta''`` changes the output
torque, not the pairs), the rollers' spin inertia (small), the rails' and rollers' masses
on the rotors (in ``machine.inertia_rotor_*``), gravity, friction in the force balance
(friction is first order, :mod:`rotorkin.analysis.pairs`), the Z-shaft's main bearings.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.analysis import pairs as pr
from rotorkin.core.angles import fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.drives.wobble_cam import cam as cs
from rotorkin.drives.wobble_cam import kinematics as wc

__all__ = [
    "OUTPUTS",
    "ForceParams",
    "Forces",
    "from_config",
    "rail_violation",
    "solve",
    "pairs",
    "summary",
    "SUMMARY_KEYS",
    "columns",
]

#: Values of ``drive.output``: which output the load is taken from.
OUTPUTS = ("shaft", "cam", "both")
#: Idler bevels of the gearbox (paper: two small bevel gears).
IDLERS = 2
_NAMES = cs.ROLLER_NAMES
_SLUGS = cs.ROLLER_SLUGS


@dataclass(frozen=True)
class ForceParams:
    """Outputs, gearbox, rails, bearings and plate inertia (``drive.*`` keys; SI).

    ``output``, ``cam_torque_share``, ``bevel_ratio``, ``bevel_pitch_radius``,
    ``bevel_pressure_angle`` [rad], ``rail_radius``, ``rail_roller_radius``,
    ``plate_bearing_span``, ``cam_bearing_span``, ``plate_inertia_axial``,
    ``plate_inertia_transverse`` [kg m^2]; ``bearing_radius`` is ``contact.bearing_radius``.
    """

    output: str = "shaft"
    cam_torque_share: float = 0.5
    bevel_ratio: float = 2.0
    bevel_pitch_radius: float = 0.040
    bevel_pressure_angle: float = np.radians(20.0)
    rail_radius: float = 0.080
    rail_roller_radius: float = 0.006
    plate_bearing_span: float = 0.040
    cam_bearing_span: float = 0.100
    plate_inertia_axial: float = 0.002
    plate_inertia_transverse: float = 0.001
    bearing_radius: float = 0.010

    def __post_init__(self):
        if self.output not in OUTPUTS:
            raise ParameterError("output", repr(self.output), "'shaft', 'cam' or 'both'")
        if not 0.0 <= self.cam_torque_share <= 1.0:
            raise ParameterError(
                "cam_torque_share", f"{self.cam_torque_share:g}", "0 <= cam_torque_share <= 1"
            )

    @property
    def share(self) -> float:
        """Fraction ``s`` of the output torque taken at the cam shell."""
        return {"shaft": 0.0, "cam": 1.0}.get(self.output, float(self.cam_torque_share))


_KEYS = tuple(f for f in ForceParams.__dataclass_fields__ if f != "bearing_radius")


def force_params(cfg: dict, cam: cs.SphericalCam) -> ForceParams:
    """The force parameters of a validated config (missing keys: the defaults).

    Raises ParameterError named ``drive.rail_radius`` when the rail rollers do not clear
    the cam shell (``rail_radius > sphere_radius + shell_thickness/2 + rail_roller_radius``).
    """
    d = cfg["drive"]
    values = {k: d[k] for k in _KEYS if k in d}
    contact = cfg.get("contact") or {}
    values["bearing_radius"] = float(contact.get("bearing_radius", 0.010))
    try:
        fp = ForceParams(**values)
    except ParameterError as exc:
        raise ParameterError(f"drive.{exc.name}", exc.value, exc.admissible) from None
    if rail_violation(fp.rail_radius, cam.outer_radius, fp.rail_roller_radius):
        least = cam.outer_radius + fp.rail_roller_radius
        raise ParameterError(
            "drive.rail_radius",
            fmt_mm(fp.rail_radius),
            f"rail_radius > {fmt_mm(least)} (the rail rollers run outside the cam shell: "
            "sphere_radius + shell_thickness/2 + rail_roller_radius)",
        )
    return fp


def rail_violation(rail_radius, shell_outer_radius, rail_roller_radius):
    """Where the rail rollers do not clear the cam shell (arrays broadcast): ``True`` unless
    ``rail_radius > shell_outer_radius + rail_roller_radius``."""
    with np.errstate(invalid="ignore"):
        return ~(np.asarray(rail_radius) > np.asarray(shell_outer_radius) + rail_roller_radius)


def from_config(cfg: dict):
    """Drive, cam (:func:`rotorkin.drives.wobble_cam.cam.from_config`) and force parameters."""
    drive, cam = cs.from_config(cfg)
    return drive, cam, force_params(cfg, cam)


@dataclass(frozen=True)
class Forces:
    """Pair forces and torques over the shaft angles (shapes: (4, n) per roller, (n,)).

    Attributes
    ----------
    theta : shaft angles [rad]
    groove_force : N_j, the cam on roller j along ``+n_j`` [N] (sign: which wall)
    rail_force : F_j, roller j on its rail along ``+e_Phi`` [N]
    groove_radius : signed radius of curvature of the loaded wall at the contact [m]
        (+ convex, - concave, inf straight), across the contact line, on the sphere r
    groove_slip, rail_slip : rolling speed of the roller on the groove / rail per unit
        shaft speed [m/rad]
    guided : whether roller j is taken as between both walls of its groove
    unguided : angles where no roller is between both walls (all four then carry load)
    plate_bearing : (2, 3, n) forces of the two plate bearings on the plate [N]
    plate_bearing_force, plate_bearing_moment : f_b (3, n) [N], m_b (3, n) [N m]
    gyroscopic : dH/dt of the plate (3, n) [N m]
    cam_bearing : (2, 3, n) forces of the cam shell's bearings on it [N]
    cam_thrust : axial thrust of the cam shell's large bevel [N]
    cam_moment : moment of the rollers on the cam shell about O (3, n) [N m]
    torque_shaft_plate : T_Z, the plate bearing's torque on the Z-shaft [N m]
    torque_cam_grooves : T_C, the grooves' torque on the cam shell about +x [N m]
    torque_total : T_Z + T_C [N m]
    output_shaft, output_cam : torque delivered to the load at each output [N m]
    gearbox_torque : G, the gearbox's torque on the cam shell (-G on the Z-shaft) [N m]
    mesh_force : normal force of one bevel mesh [N]
    idler_bearing : load of one idler's bearing [N]
    plate_power : power of the plate's inertia per unit shaft speed, P_plate/omega [N m]
    """

    theta: np.ndarray
    groove_force: np.ndarray
    rail_force: np.ndarray
    groove_radius: np.ndarray
    groove_slip: np.ndarray
    rail_slip: np.ndarray
    guided: np.ndarray
    unguided: np.ndarray
    plate_bearing: np.ndarray
    plate_bearing_force: np.ndarray
    plate_bearing_moment: np.ndarray
    gyroscopic: np.ndarray
    cam_bearing: np.ndarray
    cam_thrust: np.ndarray
    cam_moment: np.ndarray
    torque_shaft_plate: np.ndarray
    torque_cam_grooves: np.ndarray
    torque_total: np.ndarray
    output_shaft: np.ndarray
    output_cam: np.ndarray
    gearbox_torque: np.ndarray
    mesh_force: np.ndarray
    idler_bearing: np.ndarray
    plate_power: np.ndarray
    spin_rate: np.ndarray


def _to_fixed(v, theta):
    """Cam-frame vectors (4, 3, n) to the fixed frame: ``r|0 = A_psi r|4``, ``psi = -theta``."""
    psi = wc.cam_angle(theta)
    c, s = np.cos(psi), np.sin(psi)
    return np.stack([v[:, 0], c * v[:, 1] + s * v[:, 2], -s * v[:, 1] + c * v[:, 2]], axis=1)


def solve(
    drive: wc.WobbleCam,
    cam: cs.SphericalCam,
    fp: ForceParams,
    theta,
    member_torque,
    rotor_inertia=(0.0, 0.0),
    omega=1.0,
    omega_dot=0.0,
    guided=None,
) -> Forces:
    """Forces in every pair at the shaft angles ``theta`` (vectorised; see the module text).

    Parameters
    ----------
    drive, cam, fp : WobbleCam, SphericalCam, ForceParams
    theta : array_like, shape (n,)
        Shaft angles [rad].
    member_torque : array_like, shape (2, n)
        The machine's torques ``M_k`` on rotor 1 and rotor 2, along ``+Phi_k`` [N m].
    rotor_inertia : pair of float
        ``J_1``, ``J_2`` [kg m^2].
    omega, omega_dot : float or array_like, shape (n,)
        Shaft speed [rad/s] and acceleration [rad/s^2].
    guided : ndarray of bool, shape (4, n), optional
        Rollers that carry groove load (default all four; ``cam.guided`` gives those
        between both walls, away from the crossings).

    Columns of designs: ``drive`` holding arrays of shape (d, 1) (one spin law), the
    torques (2, d, n) and the inertias (d, 1) give every force of shape (..., d, n) (a
    vector's xyz axis before the designs': (3, d, n), (4, 3, d, n)).
    """
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    omega = np.broadcast_to(np.asarray(omega, dtype=float), theta.shape)
    omega_dot = np.broadcast_to(np.asarray(omega_dot, dtype=float), theta.shape)
    moments = np.asarray(member_torque, dtype=float)
    phi, r, big_r = drive.plate_tilt, drive.sphere_radius, fp.rail_radius
    shape = np.broadcast_shapes(theta.shape, np.shape(phi), np.shape(r),
                                np.shape(drive.roller_axis_angle))  # fmt: skip
    ax = -1 - len(shape)  # the xyz axis of the vectors (3, *shape) and (4, 3, *shape)

    def _dot(a, b):
        return np.sum(a * b, axis=ax)

    def _cross(a, b):  # numpy's cross product, its arithmetic, without moving the axes
        a, b = np.broadcast_arrays(a, b)
        (a0, a1, a2), (b0, b1, b2) = (
            [v[(slice(None),) * (v.ndim + ax) + (i,)] for i in range(3)] for v in (a, b)
        )
        return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=ax)

    spin = wc.spin_law(drive, theta)
    q, dq, d2q, _ = wc.rotor_angles(drive, theta)
    jr = [np.asarray(j, dtype=float) for j in rotor_inertia]
    # D_k, (2, n)
    need = np.stack([jr[k] * (d2q[k] * omega**2 + dq[k] * omega_dot) - moments[k]
                     for k in (0, 1)])  # fmt: skip

    # geometry: roller directions, rail normals, groove normals (fixed frame), plate axis
    c = wc.roller_offsets_against(drive, theta)
    e = np.moveaxis(wc.plate_point(phi, 1.0, theta, spin[0], c), 0, 1)  # (4, 3, n)
    e_u = np.moveaxis(wc.plate_point(phi, 1.0, theta, spin[0], c + 0.5 * np.pi), 0, 1)
    yz = np.hypot(e[:, 1], e[:, 2])  # (4, n)
    e_phi = np.stack([np.zeros_like(yz), e[:, 2] / yz, -e[:, 1] / yz], axis=1)
    x_hat = np.array([1.0, 0.0, 0.0]).reshape((3,) + (1,) * len(shape))
    x2 = np.stack(
        np.broadcast_arrays(np.cos(phi), -np.sin(phi) * np.sin(theta), -np.sin(phi) * np.cos(theta))
    )
    lines = cs.groove_derivatives(drive, theta)
    _, t_cam, n_cam = cs.frame_of(*lines[:2])
    n = _to_fixed(n_cam, theta)
    dg = lines[1]
    kappa = cs.curvature_of(*lines)
    if guided is None:
        guided = np.ones((4,) + shape, dtype=bool)
    g = np.broadcast_to(np.asarray(guided, dtype=bool), (4,) + shape).astype(float)

    # rails: each rotor's two rollers share D_k
    rho = big_r * yz
    group = np.array([0, 0, 1, 1])
    rail = need[group] / (2.0 * rho)  # F_j, (4, n)

    # plate inertia: H = J_a w_a x2 + J_t w_perp, w = -omega (x + varphi' x2)
    ja, jt = fp.plate_inertia_axial, fp.plate_inertia_transverse
    cphi = np.cos(phi)
    w_a = -omega * (cphi + spin[1])
    w_a_dot = -omega_dot * (cphi + spin[1]) - omega**2 * spin[2]
    x_x2 = _cross(np.broadcast_to(x_hat, x2.shape), x2)  # x cross x2
    x2_dot = -omega * x_x2
    w_perp_dot = -omega_dot * (x_hat - cphi * x2) - omega**2 * cphi * x_x2
    dh = ja * (w_a_dot * x2 + w_a * x2_dot) + jt * w_perp_dot  # (3, n)
    w_plate = -omega * (x_hat + spin[1] * x2)
    plate_power = _dot(w_plate, dh) / omega

    # grooves: spin equation, least-squares sharing over the guided rollers
    arm_g = r * _dot(_cross(e, n), x2[None])  # m_j
    arm_r = big_r * _dot(_cross(e, e_phi), x2[None])  # k_j
    demand = _dot(dh, x2) + np.sum(rail * arm_r, axis=0)
    weight = np.sum(g * arm_g**2, axis=0)
    lost = ~(weight > 0.0)  # no roller between both walls: all four taken as guided
    g = np.where(lost, 1.0, g)
    weight = np.sum(g * arm_g**2, axis=0)
    groove = demand * g * arm_g / weight

    # plate bearing
    force_on_plate = groove[:, None] * n - rail[:, None] * e_phi
    moment_on_plate = r * groove[:, None] * _cross(e, n) - big_r * rail[:, None] * _cross(e, e_phi)
    f_b = -np.sum(force_on_plate, axis=0)
    m_b = dh - np.sum(moment_on_plate, axis=0)
    couple = _cross(m_b, x2) / fp.plate_bearing_span
    plate_bearing = np.stack([0.5 * f_b + couple, 0.5 * f_b - couple])

    # torques on the Z-shaft and the cam shell; outputs and gearbox
    t_z = m_b[0]
    cam_moment = -r * np.sum(groove[:, None] * _cross(e, n), axis=0)
    t_c = cam_moment[0]
    total = t_z + t_c
    s = fp.share
    out_cam = s * total
    gear = out_cam - t_c
    alpha = fp.bevel_pressure_angle
    f_t = np.abs(gear) / (IDLERS * fp.bevel_pitch_radius)
    mesh = f_t / np.cos(alpha)
    delta_s = np.arctan(1.0 / fp.bevel_ratio)
    idler = 2.0 * f_t * np.hypot(1.0, np.tan(alpha) * np.sin(delta_s))
    thrust = IDLERS * f_t * np.tan(alpha) * np.sin(0.5 * np.pi - delta_s)

    # cam shell bearings: the grooves' net force and tilting couple
    f_cam = -np.sum(groove[:, None] * n, axis=0)
    tilt = cam_moment - cam_moment[0] * x_hat
    couple_c = _cross(tilt, np.broadcast_to(x_hat, tilt.shape)) / fp.cam_bearing_span
    cam_bearing = np.stack([-0.5 * f_cam - couple_c, -0.5 * f_cam + couple_c])

    # loaded wall's radius across the contact line: s/kappa - rho_roller, s = -sign(N)
    side = -np.sign(groove)
    k_wall = side * kappa / (1.0 - side * cam.roller_radius * kappa)
    with np.errstate(divide="ignore"):
        wall_radius = np.where(k_wall != 0.0, 1.0 / np.where(k_wall != 0.0, k_wall, 1.0), np.inf)

    # slips: groove rolling speed |dg/dtheta|; rail: the outer roller relative to its rotor
    de = -_cross(np.broadcast_to(x_hat, e.shape), e) + spin[1] * e_u
    rel = big_r * (de + dq[group][:, None] * _cross(np.broadcast_to(x_hat, e.shape), e))
    return Forces(
        theta=theta,
        groove_force=groove,
        rail_force=rail,
        groove_radius=wall_radius,
        groove_slip=np.linalg.norm(dg, axis=1),
        rail_slip=np.linalg.norm(rel, axis=1),
        guided=g > 0.0,
        unguided=lost,
        plate_bearing=plate_bearing,
        plate_bearing_force=f_b,
        plate_bearing_moment=m_b,
        gyroscopic=dh,
        cam_bearing=cam_bearing,
        cam_thrust=thrust,
        cam_moment=cam_moment,
        torque_shaft_plate=t_z,
        torque_cam_grooves=t_c,
        torque_total=total,
        output_shaft=total - out_cam,
        output_cam=out_cam,
        gearbox_torque=gear,
        mesh_force=mesh,
        idler_bearing=idler,
        plate_power=plate_power,
        spin_rate=spin[1],
    )


# --------------------------------------------------------------------------------------------
# pairs, summary keys, columns
# --------------------------------------------------------------------------------------------
def pairs(f: Forces, cam: cs.SphericalCam, fp: ForceParams, model: pr.ContactModel) -> list:
    """The load-carrying pairs of :func:`solve`'s forces, as :class:`rotorkin.analysis.pairs.Pair`.

    Groove contacts: line contact of the inner roller (``cam.roller_radius``) against the
    loaded wall over ``min(contact.roller_width, cam.groove_depth)`` (the wall is only the
    groove's depth deep). Rail contacts: the outer roller (``drive.rail_roller_radius``)
    on a flat wall over ``contact.roller_width``. The bevel meshes have no tooth geometry
    here (no Hertz stress); each mesh pair stands for the 2 meshes of its large bevel
    (force of one mesh, slip counted for both, so the friction loss is both meshes').
    """
    width = min(model.roller_width, cam.groove_depth)
    out = []
    for j in range(4):
        out.append(
            pr.Pair(
                f"roller {_NAMES[j]} on its groove",
                f"groove{_SLUGS[j]}",
                "rolling",
                f.groove_force[j],
                f.groove_slip[j],
                ("line", cam.roller_radius, f.groove_radius[j], width),
                "cam frame normal n = e_r x t of the groove; N > 0 (cam on roller along +n) "
                "is carried by the -n wall, N < 0 by the +n wall (left of the travel).",
            )
        )
    for j in range(4):
        out.append(
            pr.Pair(
                f"roller {_NAMES[j]} on its rotor rail",
                f"rail{_SLUGS[j]}",
                "rolling",
                f.rail_force[j],
                f.rail_slip[j],
                ("line", fp.rail_roller_radius, np.inf),
                f"along the rail normal e_Phi (tangential in yz); > 0 drives rotor "
                f"{1 + j // 2} forward; flat rail wall.",
            )
        )
    spin = fp.bearing_radius * np.abs(f.spin_rate)
    for k, end in enumerate(("upper", "lower")):
        out.append(
            pr.Pair(
                f"plate bearing ({end}) on the inclined crank",
                f"plate_bearing_{'ab'[k]}",
                "bearing",
                np.linalg.norm(f.plate_bearing[k], axis=0),
                spin,
                None,
                f"at {'+-'[k]}plate_bearing_span/2 along the plate axis x2; carries f_b/2 "
                f"{'+-'[k]} (m_b x x2)/span, the plate's tilting couple incl. its gyroscopic one.",
            )
        )
    for k in range(2):
        out.append(
            pr.Pair(
                f"cam shell bearing {k + 1}",
                f"cam_bearing_{'ab'[k]}",
                "bearing",
                np.linalg.norm(f.cam_bearing[k], axis=0),
                np.full_like(f.theta, fp.bearing_radius),
                None,
                f"at {'+-'[k]}cam_bearing_span/2 along x, on the housing; the grooves' tilting "
                "couple on the cam shell (radial load; the bevel thrust apart).",
            )
        )
    pitch = IDLERS * fp.bevel_pitch_radius * np.cos(fp.bevel_pressure_angle)
    for side in ("Z-shaft", "cam"):
        out.append(
            pr.Pair(
                f"bevel mesh of the {side} gear with an idler",
                f"bevel_mesh_{'shaft' if side == 'Z-shaft' else 'cam'}",
                "mesh",
                f.mesh_force,
                np.full_like(f.theta, pitch),
                None,
                "normal tooth force of one of the large bevel's 2 idler meshes, "
                "|G| / (2 r_p cos a); the slip counts both meshes.",
            )
        )
    out.append(
        pr.Pair(
            "bevel idler bearing",
            "bevel_idler_bearing",
            "bearing",
            f.idler_bearing,
            np.full_like(f.theta, IDLERS * fp.bearing_radius * fp.bevel_ratio),
            None,
            "one idler's bearing: its 2 meshes' tangential forces (same way) and axial thrust; "
            "the slip counts both idlers.",
        )
    )
    return out


def _mean(values, theta):
    return np.trapezoid(values, theta, axis=-1) / (theta[-1] - theta[0])


#: The keys of :func:`summary`, in order.
SUMMARY_KEYS = (
    "cam_shell_torque_share",
    "cam_shell_natural_torque_share",
    "output_torque_mean_Nm",
    "shaft_output_torque_mean_Nm",
    "cam_shell_torque_mean_Nm",
    "groove_roller_force_max_N",
    "groove_contact_stress_max_MPa",
    "rail_roller_force_max_N",
    "rail_contact_stress_max_MPa",
    "plate_bearing_load_max_N",
    "plate_bearing_moment_max_Nm",
    "plate_gyroscopic_moment_max_Nm",
    "cam_bearing_load_max_N",
    "cam_tilting_moment_max_Nm",
    "cam_bevel_thrust_max_N",
    "gearbox_torque_max_Nm",
    "bevel_mesh_force_max_N",
    "bevel_idler_bearing_load_max_N",
    "groove_crossing_force_max_N",
    "groove_crossing_fraction",
)


def summary(f: Forces, plist, model: pr.ContactModel, guided=None) -> dict:
    """The drive's own summary keys (units in the names; see the docs page).

    ``guided`` (shape (4, n), :func:`rotorkin.drives.wobble_cam.cam.guided`): the rollers
    between both walls; the others run through a groove crossing, and
    ``groove_crossing_force_max_N`` is the largest load one of them carries there.

    For the forces of columns of designs (:func:`solve`; angles last, designs before them)
    every key is an array of the designs: each peak over the pairs and the angles of one
    design.
    """
    th = f.theta
    batch = np.ndim(f.torque_total) > 1

    def peak(x):  # the largest over all but the designs' axis (the one before the angles)
        x = np.asarray(x)
        return np.max(x, axis=tuple(range(x.ndim - 2)) + (-1,)) if batch else float(np.max(x))

    crossing = np.zeros(f.groove_force.shape, bool) if guided is None else ~np.asarray(guided)
    total = _mean(f.torque_total, th)
    with np.errstate(divide="ignore", invalid="ignore"):
        share = np.where(total != 0.0, _mean(f.output_cam, th) / total, np.nan)
        natural = np.where(total != 0.0, _mean(f.torque_cam_grooves, th) / total, np.nan)
    by_slug = {p.slug: p for p in plist}

    def peak_stress(stem):  # NaN where no angle has a stress (a roller that never loads)
        vals = np.abs(np.stack(np.broadcast_arrays(
            *(pr.stress(by_slug[f"{stem}{s}"], model) for s in _SLUGS))))  # fmt: skip
        top = np.fmax.reduce(np.fmax.reduce(vals, axis=-1), axis=0) / 1e6
        return top if batch else float(top)

    tilt = f.plate_bearing_moment
    cam_tilt = np.hypot(f.cam_moment[1], f.cam_moment[2])
    out = {
        "cam_shell_torque_share": share,
        "cam_shell_natural_torque_share": natural,
        "output_torque_mean_Nm": total,
        "shaft_output_torque_mean_Nm": _mean(f.output_shaft, th),
        "cam_shell_torque_mean_Nm": _mean(f.output_cam, th),
        "groove_roller_force_max_N": peak(np.abs(f.groove_force)),
        "groove_contact_stress_max_MPa": peak_stress("groove"),
        "rail_roller_force_max_N": peak(np.abs(f.rail_force)),
        "rail_contact_stress_max_MPa": peak_stress("rail"),
        "plate_bearing_load_max_N": peak(np.linalg.norm(f.plate_bearing, axis=1)),
        "plate_bearing_moment_max_Nm": peak(np.linalg.norm(tilt, axis=0)),
        "plate_gyroscopic_moment_max_Nm": peak(np.linalg.norm(f.gyroscopic, axis=0)),
        "cam_bearing_load_max_N": peak(np.linalg.norm(f.cam_bearing, axis=1)),
        "cam_tilting_moment_max_Nm": peak(cam_tilt),
        "cam_bevel_thrust_max_N": peak(f.cam_thrust),
        "gearbox_torque_max_Nm": peak(np.abs(f.gearbox_torque)),
        "bevel_mesh_force_max_N": peak(f.mesh_force),
        "bevel_idler_bearing_load_max_N": peak(f.idler_bearing),
        "groove_crossing_force_max_N": peak(np.where(crossing, np.abs(f.groove_force), 0.0)),
        "groove_crossing_fraction": np.mean(np.any(crossing, axis=0), axis=-1),
    }
    if batch:
        return out
    return {k: float(v) for k, v in out.items()}


def columns(f: Forces) -> tuple[dict, dict]:
    """The drive's own motion.csv columns: torques of the outputs and gearbox, loaded walls."""
    cols, docs = {}, {}

    def add(name, values, doc):
        cols[name] = np.asarray(values, dtype=float)
        docs[name] = doc

    add("plate_torque_on_shaft_Nm", f.torque_shaft_plate,
        "T_Z: torque of the plate bearing on the Z-shaft, along +theta.")  # fmt: skip
    add("groove_torque_on_cam_Nm", f.torque_cam_grooves,
        "T_C: torque of the rollers on the cam shell along its turning (+x).")  # fmt: skip
    add("shaft_output_torque_Nm", f.output_shaft,
        "Torque the Z-shaft delivers to its load (drive.output), inertia of the rotors and "
        "plate included.")  # fmt: skip
    add("cam_output_torque_Nm", f.output_cam,
        "Torque the cam shell delivers to its load (drive.output), along its turning.")  # fmt: skip
    add("gearbox_torque_Nm", f.gearbox_torque,
        "G: torque the bevel gearbox puts on the cam shell (-G on the Z-shaft).")  # fmt: skip
    grooves = np.asarray(f.groove_force, dtype=float)
    # a force below 1e-9 of the groove's largest is rounding of a zero: no wall carries it
    floor = 1e-9 * np.max(np.abs(grooves), axis=-1, keepdims=True)
    loaded = np.where(np.abs(grooves) > floor, -np.sign(grooves), 0.0)
    for j in range(4):
        add(f"groove{_SLUGS[j]}_loaded_wall", loaded[j],
            f"Wall of groove {_NAMES[j]} carrying its roller: +1 the +n wall (left of the "
            "travel seen from outside the sphere), -1 the -n wall, 0 none (a force below "
            "1e-9 of the groove's largest).")  # fmt: skip
    return cols, docs
