"""The two eccentric discs as cam profiles: pitch circles, follower pressure angles, checks.

Zhu Ruilin, Zhu Guolin 2012 (``papers/eccentric_pistons.md``): two discs of
radius ``R`` on one shaft, eccentricity ``e``, half a turn apart, each pushing
one piston (:mod:`rotorkin.drives.eccentric_cam.kinematics`). Derived here:

* Each disc is drawn in the frame of its follower at ``beta = 0``: origin on
  the shaft axis, x along the follower axis towards the reactor centre. The
  left disc's centre is at ``(e, 0)``, the right disc's at ``(-e, 0)`` (the
  drive's convention); the two discs are the same part mounted half a turn apart.
* The actual profile is the disc itself (a circle of radius ``R``). The pitch
  curve - the path of the follower point relative to the disc - is the circle
  of radius ``Rc``: ``R`` for a knife edge (the profile itself), ``R + r`` for a
  roller follower (the disc grown by ``r``). A flat face has no pitch curve.
* The pitch circle is convex everywhere with radius ``Rc``; a roller outside a
  convex disc never undercuts it and no other roller shares the disc, so the
  clearance check does not apply (``inf``).
* Pressure angle: between the contact normal (through the disc centre and the
  follower point) and the follower's velocity (along its axis):
  ``sin mu = e sin beta / Rc`` for the left piston, ``-`` that for the right
  (:func:`rotorkin.drives.eccentric_cam.kinematics.pressure_angle`); 0 for a flat face.
"""

from __future__ import annotations

import numpy as np

from rotorkin.cams import planar
from rotorkin.cams.planar import Curve, Part, ProfileCheck
from rotorkin.core.angles import fmt_mm
from rotorkin.drives.eccentric_cam import kinematics as ec

__all__ = [
    "SIDES",
    "cam_parts",
    "disc_centres",
    "follower_points",
    "pressure_angles",
    "profile_check",
]

#: The two discs, in the drive's order of members.
SIDES = ("left", "right")


def disc_centres(params: ec.EccentricCam, beta):
    """Disc centres in their followers' frames, shape (2, 2, ...) [m]: left, right; (x, y).

    Left ``e (cos beta, sin beta)``, right ``-e (cos beta, sin beta)``.
    """
    b = np.asarray(beta, dtype=float)
    e = np.asarray(params.eccentricity, dtype=float)
    u = np.stack([e * np.cos(b), e * np.sin(b)])
    return np.stack([u, -u])


def follower_points(params: ec.EccentricCam, beta):
    """Follower points on their axes, shape (2, 2, ...) [m]: left, right; (x, y).

    The point of the follower that runs on the pitch circle: the knife edge's
    tip or the roller centre, at ``x = Rc + z`` (``z``, ``z'`` the travels) on the
    axis. For a flat face: the point of the face on its axis, ``x = R + z``.
    """
    b = np.asarray(beta, dtype=float)
    q = ec.piston_travels(params, b)[0]
    rc = params.contact_radius
    x0 = np.where(np.isfinite(rc), rc, np.asarray(params.disc_radius, dtype=float))
    return np.stack([np.stack([x0 + q[k], np.zeros_like(q[k])]) for k in (0, 1)])


def pressure_angles(params: ec.EccentricCam, beta):
    """Pressure angle of each piston's follower [rad], shape (2, ...): left, right.

    Between the contact normal (through the disc centre) and the follower's
    axis: ``arcsin(e sin beta / Rc)`` for the left, its negative for the right;
    zero for a flat face (module docstring).
    """
    mu = ec.pressure_angle(params, beta)
    return np.stack([mu, -mu])


def profile_check(params: ec.EccentricCam) -> ProfileCheck:
    """Checks of the discs for their follower (closed form; never raises).

    ``min_convex_radius`` is the pitch radius ``Rc`` (constant; its angle
    reported as 0), the pressure angle peaks at ``arcsin(e/Rc)`` at
    ``beta = 90 deg``, no undercut, clearance ``inf`` (one follower per disc),
    ``profile_min_radius = R - e`` (the disc's nearest point to the shaft axis).
    ``extra``: ``gap_change_min`` [m] (eq. 5).
    """
    R, e = float(params.disc_radius), float(params.eccentricity)
    rc = params.contact_radius
    flat = params.follower == "flat"
    return ProfileCheck(
        roller_radius=float(params.roller_radius) if params.follower == "roller" else 0.0,
        min_convex_radius=float(rc),
        min_convex_radius_alpha=0.0,
        min_concave_radius=float("inf"),
        max_pressure_angle=0.0 if flat else float(ec.pressure_angle_max(params)),
        max_pressure_angle_alpha=0.5 * np.pi,
        undercut=False,
        min_clearance=float("inf"),
        min_clearance_alpha=float("nan"),
        profile_min_radius=R - e,
        extra={"gap_change_min": ec.gap_change_extreme(params)[0]},
    )


def cam_parts(params: ec.EccentricCam, thickness, tolerance) -> list[Part]:
    """The two discs as :class:`~rotorkin.cams.planar.Part` s, drawn at ``beta = 0``.

    Each part, in its follower's frame: ``profile`` (the disc, PROFILE, exact
    circle), ``pitch`` (PITCH; the roller-centre circle ``R + r`` or, for a
    knife edge, the profile itself; none for a flat face), ``roller`` (ROLLER,
    roller followers only) and ``shaft_axis`` (AXIS, a cross of two short lines
    at the shaft axis, R/10 long, to locate the bore).

    Parameters
    ----------
    params : EccentricCam
    thickness, tolerance : float
        [m].
    """
    R, r = float(params.disc_radius), float(params.roller_radius)
    centres = disc_centres(params, 0.0)
    followers = follower_points(params, 0.0)
    mark = 0.1 * R
    parts = []
    for k, side in enumerate(SIDES):
        c = centres[k]
        outline = planar.circle_curve("profile", "PROFILE", c, R, tolerance)
        curves = [outline]
        if params.follower != "flat":
            curves.append(planar.circle_curve("pitch", "PITCH", c, params.contact_radius,
                                              tolerance))  # fmt: skip
        if params.follower == "roller":
            curves.append(planar.circle_curve("roller", "ROLLER", followers[k], r, tolerance))
        curves += [
            Curve("shaft_axis_x", "AXIS", np.array([[-mark, 0.0], [mark, 0.0]]), closed=False),
            Curve("shaft_axis_y", "AXIS", np.array([[0.0, -mark], [0.0, mark]]), closed=False),
        ]
        parts.append(
            Part(
                name=f"disc_{side}",
                outline=outline,
                thickness=float(thickness),
                curves=tuple(curves),
                title=f"{side} eccentric disc R = {fmt_mm(R)}, e = {fmt_mm(params.eccentricity)}"
                f", {params.follower} follower, drawn at beta = 0 in its follower's frame",
            )
        )
    return parts
