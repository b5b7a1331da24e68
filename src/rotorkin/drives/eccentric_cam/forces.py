"""Kinetostatics of the double eccentric discs: the force in every load-carrying pair.

The members are the two pistons (``q = (z, z')`` [m], positive towards the reactor
centre, :mod:`rotorkin.drives.eccentric_cam.kinematics`). The machine's force on
piston ``i`` is ``M_i`` [N] along ``+q_i`` (the reactor's ``-p A``,
:mod:`rotorkin.machines.opposed_piston`). At the run speed the disc must apply
along the piston axis

    D_i = m_i qdd_i - M_i,      qdd_i = q_i'' w^2 + q_i' w_dot

(``m_i`` the piston's mass with its rod and follower, ``w`` the shaft speed).

Frames and signs (derived here, the paper gives no forces):

* Each piston is described in its follower's frame: origin on the shaft axis, x
  along the piston axis towards the reactor centre, y such that the disc turns
  with ``+1`` rad per rad of shaft about ``+z = x * y`` (counter-clockwise seen
  in the xy-plane): the left disc centre is at ``c = e (cos beta, sin beta)``, the
  right one at ``c = -e (cos beta, sin beta)``. In the paper's Fig. 2 both pistons
  stand above the shaft with parallel axes, so the two frames are the same frame
  shifted along the shaft: forces of the two discs add as vectors in it.
* The follower point ``P = (Rc + q_i, 0)`` (knife tip, ``Rc = R``; roller centre,
  ``Rc = R + r``) runs on the pitch circle of the disc; the contact normal is
  ``n = (P - c) / Rc`` (unit, from the disc into the follower) and the contact
  point on the disc ``C = c + R n``. A flat face has ``n = (1, 0)`` and touches the
  disc at its point furthest along x, ``C = c + (R, 0)``.
* Frictionless contact (friction is first order: it is charged as a loss, it does
  not change the normal forces): the disc pushes the piston with ``N n``, with

      N_i = D_i / n_x,      n_x = sqrt(Rc^2 - e^2 sin^2 beta) / Rc  (1 for a flat face).

  ``N_i >= 0`` while the follower stays on its disc: nothing holds it there but
  the fluid pressure ``-M_i = p A`` (no return spring); ``N_i < 0`` means the
  piston would lift off (summary ``follower_lift_off``).
* Side thrust ``H_i = N_i n_y`` [N]: the force of the piston on its guide along
  +y (its sign says which wall carries it: ``> 0`` the +y wall). The left knife
  edge or roller leans to ``-y`` while its piston falls (``0 < beta < pi``).
  A flat face pushes along the axis (``H = 0``) but off it, at ``y = C_y``: its
  tilting moment about the piston axis is ``T_i = -C_y N_i`` [N m] (about +z, on the
  piston); the guide takes it as a couple. Splitting the side thrust and moment into the two
  bushes of a guide needs their spacing, which the config does not give.
* Disc on the shaft: the disc receives ``-N n`` at ``C``; its moment about the
  shaft axis ``C x (-N n)`` (positive in the sense of rotation) summed over both
  discs is the torque the pistons put on the shaft: ``-sum_i D_i q_i'`` (virtual
  work), tested. The load ``N`` of each disc goes to the frame through the shaft
  bearings (journal speed = ``contact.bearing_radius`` per rad of shaft; how it
  splits between the two bearings needs the shaft's axial geometry, not given);
  ``shaft_radial_load`` is the magnitude of the sum of both discs' loads.

Slips [m per rad of shaft]: the disc's surface at ``C`` moves with ``z x C`` and
the piston with ``(q', 0)``; the relative speed along the tangent ``(-n_y, n_x)``
is the sliding speed of a knife edge (``|C|``-sized) or a flat face
(``R + e cos beta`` on the left), and the rolling speed of a roller, whose spin on
its pin is that speed over ``r``. The guide slides at ``|q'|``.

Neglected, and why: the discs' mass (not in the config; the two discs are half a
turn apart, so their centrifugal forces ``m_d e w^2`` cancel on the shaft and
leave a rocking couple only), the roller's spin inertia (its mass is part of
``machine.piston_mass``), friction in the normal forces (first order).

Hertz geometry (``("line", r1, r2)``, width ``contact.roller_width``): flat face
``(R, inf)``; roller ``(R, r)``; knife edge ``(R, drive.tip_radius)`` when a tip
radius is given, else none (a sharp edge has no finite contact stress). The travel
law takes the knife's tip as a point (eq. 1); a rounded tip's contact runs on the
circle ``R + tip_radius``, the roller law of that radius.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.analysis import pairs as pairs_mod
from rotorkin.analysis.pairs import Pair
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.drives.eccentric_cam.reactor import reactor_state

__all__ = ["ContactState", "contact_state", "pairs", "own_summary", "work_through_drive",
           "forces_summary", "SIDES"]  # fmt: skip

#: The two pistons, in the drive's order of members.
SIDES = ("left", "right")


@dataclass(frozen=True)
class ContactState:
    """Forces and geometry of both disc-follower contacts, shape (2, n): left, right.

    Attributes
    ----------
    drive : ndarray
        ``D = m qdd - M`` [N], what the disc must apply along the piston axis.
    normal : ndarray
        ``N`` [N], along ``n`` on the follower (``< 0``: lift-off).
    n : ndarray, shape (2, 2, n)
        Contact normal (x, y) per piston, from the disc into the follower.
    point : ndarray, shape (2, 2, n)
        Contact point ``C`` on the disc, follower frame [m].
    side_thrust : ndarray
        ``H = N n_y`` [N], the piston on its guide along +y.
    tilting_moment : ndarray
        ``-C_y N n_x`` [N m], moment of the contact force about the piston axis, +z (flat
        face; 0 for a follower whose force passes through its axis).
    slip : ndarray
        Sliding (knife, flat) or rolling (roller) speed at the contact [m/rad].
    guide_slip : ndarray
        ``|q'|`` [m/rad].
    spin : ndarray
        Roller spin on its pin [rad/rad] (0 but for a roller).
    shaft_torque : ndarray, shape (n,)
        Torque of the contact forces on the shaft, positive in the sense of rotation [N m].
    shaft_load : ndarray, shape (2, n)
        Sum of both discs' loads on the shaft (x, y) [N].
    """

    drive: np.ndarray
    normal: np.ndarray
    n: np.ndarray
    point: np.ndarray
    side_thrust: np.ndarray
    tilting_moment: np.ndarray
    slip: np.ndarray
    guide_slip: np.ndarray
    spin: np.ndarray
    shaft_torque: np.ndarray
    shaft_load: np.ndarray


def contact_state(params: ec.EccentricCam, beta, machine_force, masses, omega,
                  omega_dot, travels=None) -> ContactState:  # fmt: skip
    """Contact forces of both pistons at the shaft angles ``beta`` (vectorised).

    Parameters
    ----------
    params : EccentricCam
        One design (floats), or designs whose numeric fields are columns (d, 1); one
        follower for all.
    beta : ndarray, shape (n,)
        Shaft angles [rad].
    machine_force : ndarray, shape (2, n) or (2, d, n)
        ``M_i`` [N], the machine's force on each piston along ``+q_i``.
    masses : (float, float) or ndarray, shape (2, d, 1)
        Piston masses [kg].
    omega, omega_dot : ndarray, shape (n,) or (d, n), or float
        Shaft speed [rad/s] and acceleration [rad/s^2] at ``beta``.
    travels : tuple of ndarray, optional
        :func:`~rotorkin.drives.eccentric_cam.kinematics.piston_travels` at ``beta``, if
        already at hand.

    Returns
    -------
    ContactState
        Shapes as documented there, with the designs' axis ``d`` before the angles'.
    """
    beta = np.asarray(beta, dtype=float)
    q, dq, d2q, _ = ec.piston_travels(params, beta) if travels is None else travels
    m = np.asarray(masses, dtype=float)
    m = m.reshape(m.shape + (1,) * (q.ndim - m.ndim))
    qdd = d2q * np.asarray(omega) ** 2 + dq * np.asarray(omega_dot)
    D = m * qdd - np.asarray(machine_force, dtype=float)
    R, e = np.asarray(params.disc_radius, dtype=float), np.asarray(params.eccentricity, dtype=float)
    ec_, es_ = e * np.cos(beta), e * np.sin(beta)
    cx, cy = np.stack([ec_, -ec_]), np.stack([es_, -es_])  # disc centres (2 pistons, ...)
    flat = params.follower == "flat"
    if flat:
        nx, ny = np.ones(cx.shape), np.zeros(cx.shape)
    else:
        rc = np.asarray(params.contact_radius, dtype=float)
        nx, ny = (rc + q - cx) / rc, (0.0 - cy) / rc
    Cx, Cy = cx + R * nx, cy + R * ny
    N = D / nx
    # the disc's surface relative to the piston, (-C_y - q', C_x), along the tangent (-n_y, n_x)
    slip = np.abs((-Cy - dq) * -ny + Cx * nx)
    roller = params.follower == "roller"
    spin = slip / np.asarray(params.roller_radius, dtype=float) if roller else 0.0 * slip
    fx, fy = -N * nx, -N * ny  # the follower on the disc
    torque = np.sum(Cx * fy - Cy * fx, axis=0)
    return ContactState(
        drive=D,
        normal=N,
        n=np.stack([nx, ny], axis=1),
        point=np.stack([Cx, Cy], axis=1),
        side_thrust=N * ny,
        tilting_moment=-Cy * N * nx if flat else np.zeros_like(N),
        slip=slip,
        guide_slip=np.abs(dq),
        spin=spin,
        shaft_torque=torque,
        shaft_load=np.stack([fx[0] + fx[1], fy[0] + fy[1]]),
    )


def pairs(params: ec.EccentricCam, state: ContactState, bearing_radius: float,
          tip_radius: float = 0.0) -> list[Pair]:  # fmt: skip
    """The load-carrying pairs: per piston its disc contact, its guide, the roller pin
    (roller followers), and the disc's load on the shaft bearings.

    Parameters
    ----------
    params : EccentricCam
        One design, or designs as columns (d, 1) (:func:`contact_state`).
    state : ContactState
        From :func:`contact_state`.
    bearing_radius : float or ndarray, shape (d, 1)
        Journal radius of the roller pins and shaft bearings [m] (``contact.bearing_radius``).
    tip_radius : float or ndarray, shape (d, 1), optional
        Knife edge's tip radius [m]; below 1 nm: no contact stress (NaN for such designs
        of an array).
    """
    R = np.asarray(params.disc_radius, dtype=float)[()]
    follower = params.follower
    if follower == "flat":
        kind, geometry, what = "sliding", ("line", R, np.inf), "flat face"
    elif follower == "roller":
        roller = np.asarray(params.roller_radius, dtype=float)[()]
        kind, geometry, what = "rolling", ("line", R, roller), "roller"
    elif np.ndim(tip_radius):
        # below a nanometre the tip is an edge (and its curvature would overflow)
        tip = np.asarray(tip_radius, dtype=float)
        geometry = ("line", R, np.where(tip >= 1e-9, tip, np.nan))
        kind, what = "sliding", "knife edge"
    else:
        geometry = ("line", R, float(tip_radius)) if tip_radius >= 1e-9 else None
        kind, what = "sliding", "knife edge"
    out = []
    for k, side in enumerate(SIDES):
        N = state.normal[k]
        out.append(Pair(
            f"{side} disc on its {what}", f"{side}_{follower}", kind, np.abs(N),
            state.slip[k], geometry,
            f"Along the contact normal, disc into follower, in the {side} follower's frame (x "
            "along the piston towards the reactor centre); the disc can only push: "
            "follower_force_min_N < 0 means lift-off.",
        ))  # fmt: skip
        out.append(Pair(
            f"{side} piston on its guide", f"{side}_guide", "sliding",
            np.abs(state.side_thrust[k]), state.guide_slip[k], None,
            f"Side thrust N n_y across the {side} piston axis (y of its follower frame); "
            "+y wall when N n_y > 0.",
        ))  # fmt: skip
        if follower == "roller":
            out.append(Pair(
                f"{side} roller on its pin", f"{side}_roller_pin", "bearing", np.abs(N),
                bearing_radius * np.abs(state.spin[k]), None,
                f"The {side} contact force through the roller centre into its pin.",
            ))  # fmt: skip
        out.append(Pair(
            f"{side} disc on the shaft bearings", f"{side}_disc_shaft", "bearing", np.abs(N),
            np.full_like(N, bearing_radius), None,
            f"Radial load -N n of the {side} disc on the shaft, carried to the frame by the "
            "shaft bearings (journal at shaft speed).",
        ))  # fmt: skip
    return out


def own_summary(state: ContactState) -> dict:
    """The drive's own force keys: follower force peak and minimum, lift-off, side thrust,
    tilting moment on the guides, net radial load of both discs on the shaft.

    Floats for one design; arrays (d,) for a state of designs (d, n).
    """
    axes = (0, -1)  # the pistons and the angles
    out = {
        "follower_force_peak_N": np.max(np.abs(state.normal), axis=axes),
        "follower_force_min_N": np.min(state.normal, axis=axes),
        "follower_lift_off": np.min(state.normal, axis=axes) < 0.0,
        "side_thrust_peak_N": np.max(np.abs(state.side_thrust), axis=axes),
        "guide_tilting_moment_peak_Nm": np.max(np.abs(state.tilting_moment), axis=axes),
        "shaft_radial_load_peak_N": np.max(np.hypot(*state.shaft_load), axis=-1),
    }
    return {k: v.item() if np.ndim(v) == 0 else v for k, v in out.items()}


def work_through_drive(state: ContactState, beta):
    """Work the shaft hands to the pistons per turn through the discs [J] (>= 0).

    The fluid is a conservative spring (no net work over a turn), so the drive's
    efficiency is taken on the work that passes through it: the integral of the
    contact forces' torque on the shaft where it resists the shaft,
    ``oint max(-T_contact, 0) dbeta``. A float, or an array (d,) for designs (d, n).
    """
    return np.trapezoid(np.maximum(-state.shaft_torque, 0.0), beta, axis=-1)[()]


def forces_summary(params: ec.EccentricCam, reactor, inertia, speed, beta,
                   model: pairs_mod.ContactModel, bearing_radius, tip_radius,
                   state: dict | None = None) -> dict:  # fmt: skip
    """Contact, bearing, friction, efficiency and the drive's own force keys of the summary.

    Parameters
    ----------
    params, reactor, inertia, speed
        As :func:`~rotorkin.drives.eccentric_cam.reactor.reactor_state`; designs as
        columns (d, 1) share one follower.
    beta : ndarray, shape (n,)
        Shaft angles over one turn, ends included [rad].
    model : ContactModel
        The ``[contact]`` section (floats, or columns (d, 1) for designs).
    bearing_radius, tip_radius : float or ndarray, shape (d, 1)
        ``contact.bearing_radius``, ``drive.tip_radius`` [m] (:func:`pairs`).
    state : dict, optional
        :func:`~rotorkin.drives.eccentric_cam.reactor.reactor_state` at ``beta`` if
        already at hand.

    Returns
    -------
    dict
        Floats (one design) or arrays (d,) (designs).
    """
    st = reactor_state(params, reactor, inertia, speed, beta) if state is None else state
    m = st["motion"]
    contact = contact_state(params, beta, st["F"], inertia[1], st["omega"], st["omega_dot"],
                            (m.q, m.dq, m.d2q, m.d3q))  # fmt: skip
    prs = pairs(params, contact, bearing_radius, tip_radius)
    work = work_through_drive(contact, beta)
    batch = np.ndim(work) > 0
    out = pairs_mod.summary(prs, beta, -work, model, st["omega"], batch=batch)
    out["work_through_drive_J"] = work if batch else float(work)
    out.update(own_summary(contact))
    return out
