"""Spherical cam of the wobble-cam drive: grooves, walls, pressure angle, curvature, crossings.

The cam is a hollow spherical shell around the wobble plate, turning at ``psi = -theta``
(Chen Hu et al. 2015, section 1, Fig. 2); each of the 4 inner rollers runs in a groove
cut from the shell's inner surface. The groove centre-line is the roller centre seen
from the cam, eq. 10-11 (:func:`rotorkin.drives.wobble_cam.kinematics.groove_points`), on the
sphere ``r = sphere_radius``. Derived here (see ``docs/cams.md``):

* walls: envelope of the roller cylinder (radial axis ``e_r``, radius rho), exactly the
  ruled surfaces ``lambda e_r +- rho n``, ``n = e_r x t``; the contact normal is ``+-n``;
* geodesic curvature ``kappa_g = (g' x g'') . e_r / |g'|^3`` and the undercut limit
  ``rho < R / sqrt(1 + (r kappa_g)^2)`` on the sphere R (strictest at R_i);
* pressure angle between ``n`` and the roller centre's velocity relative to the
  Z-shaft (the plate's spin, what the cam imposes), or in the fixed frame;
* crossings of the centre-lines (the figure-eight's own, and between grooves).

Shell: radii ``r -+ shell_thickness/2``; grooves from ``R_i`` to ``R_i + groove_depth``.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from rotorkin.analysis.fits import fit_clearance
from rotorkin.core.angles import fmt_deg, fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.core.minimize import bounded_min
from rotorkin.drives.wobble_cam import cam_walls
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.drives.wobble_cam.cam_crossings import (
    GrooveCrossing,
    groove_crossings,
    groove_separation,
)
from rotorkin.drives.wobble_cam.cam_walls import walls_present
from rotorkin.drives.wobble_cam.grooves import (
    _SEARCH_SAMPLES,
    _partials,
    distinct_grooves,
    groove_derivatives,
    groove_period,
)
from rotorkin.machines.twin_rotor import first_violation

#: The fit of the rollers in their grooves and on their shafts when no clearance is given
#: (ISO 286 close running fit).
RUNNING_FIT = "H8/f7"

__all__ = [
    "RUNNING_FIT",
    "ROLLER_NAMES",
    "ROLLER_SLUGS",
    "SphericalCam",
    "CAM_KEYS",
    "CAM_CHECKED",
    "cam_violation",
    "from_config",
    "groove_period",
    "distinct_grooves",
    "groove_derivatives",
    "groove_frame",
    "frame_of",
    "groove_walls",
    "pressure_angle",
    "geodesic_curvature",
    "curvature_of",
    "curvature_radius",
    "roller_radius_limit",
    "sharpest_bend",
    "check_roller_radius",
    "guided",
    "wall_gaps",
    "pressure_angle_peaks",
    "summary",
    "shape_summary",
    "GrooveCrossing",
    "groove_crossings",
    "groove_separation",
]

#: Shaft angles over a turn at which :func:`summary` measures the share with both walls.
_TURN_SAMPLES = 72000
#: People's names of the rollers, in the order of ``wobble_cam.roller_offsets`` (group 1: 1, 1').
ROLLER_NAMES = ("1", "1'", "2", "2'")
#: The same names for file names and CSV column stems.
ROLLER_SLUGS = ("1", "1p", "2", "2p")


#: Fields of :class:`SphericalCam` set by the ``[cam]`` section (the sphere radius is the
#: drive's).
CAM_KEYS = ("roller_radius", "shell_thickness", "groove_depth", "running_clearance",
            "roller_length", "roller_end_gap")  # fmt: skip
#: Fields of :class:`SphericalCam` in the order it checks them (:func:`cam_violation`).
CAM_CHECKED = ("sphere_radius", "shell_thickness", "groove_depth", "roller_radius",
               "running_clearance", "roller_end_gap", "roller_length")  # fmt: skip


def cam_violation(sphere_radius, roller_radius=0.004, shell_thickness=0.012, groove_depth=0.008,
                  running_clearance=None, roller_length=None, roller_end_gap=0.0005):  # fmt: skip
    """Which field of the spherical cam is not admissible, per design (arrays broadcast).

    Returns
    -------
    ndarray of int16
        0 where the cam is admissible, else ``1 + CAM_CHECKED.index(field)`` of the first
        field out of range (the rules of :class:`SphericalCam`): ``r > 0``;
        ``0 < t < 2 r``; ``t/2 < d < t``; ``0 < rho < R_i = r - t/2``;
        ``0 <= c <= rho/2`` (``c`` None: the :data:`RUNNING_FIT` clearance at ``2 rho``);
        ``0 <= gap < R_b - sqrt(R_i^2 + rho^2)``, ``R_b = R_i + d``;
        ``0 < L <= sqrt((R_b - gap)^2 - rho^2) - R_i`` (``L`` None: that largest).
    """
    with np.errstate(invalid="ignore"):
        r, rho, t, d, gap = (np.asarray(v, dtype=float) for v in (sphere_radius, roller_radius,
                                                                   shell_thickness, groove_depth,
                                                                   roller_end_gap))  # fmt: skip
        ri = r - 0.5 * t
        rb = ri + d
        ok_rho = np.isfinite(rho) & (rho > 0.0) & (rho < ri)
        if running_clearance is None:  # the fit's table at the roller's diameter, where valid
            size = np.where(ok_rho & (rho <= 0.25), rho, 0.004)
            c = np.where(ok_rho, fit_clearance(RUNNING_FIT, 2.0 * size), np.nan)
        else:
            c = np.asarray(running_clearance, dtype=float)
        top = rb - np.sqrt(ri * ri + rho * rho)
        longest = np.sqrt((rb - gap) ** 2 - rho * rho) - ri
        length = longest if roller_length is None else np.asarray(roller_length, dtype=float)
        return first_violation(
            [
                ~(np.isfinite(r) & (r > 0.0)),
                ~(np.isfinite(t) & (t > 0.0) & (t < 2.0 * r)),
                ~(np.isfinite(d) & (d > 0.5 * t) & (d < t)),
                ~ok_rho,
                ~(np.isfinite(c) & (c >= 0.0) & (c <= 0.5 * rho)),
                ~(np.isfinite(gap) & (gap >= 0.0) & (gap < top)),
                ~(np.isfinite(length) & (length > 0.0) & (length <= longest * (1.0 + 1e-12))),
            ]
        )


@dataclass(frozen=True)
class SphericalCam:
    """Geometry of the spherical cam shell and its grooves (SI).

    Parameters
    ----------
    sphere_radius : float
        Radius r of the roller centres = the groove centre-line sphere [m]
        (config ``drive.sphere_radius``).
    roller_radius : float, optional
        Radius rho of the inner rollers [m], ``0 < rho < R_i`` (``cam.roller_radius``).
    shell_thickness : float, optional
        Radial thickness of the shell, centred on r [m], ``0 < t < 2 r``
        (``cam.shell_thickness``).
    groove_depth : float, optional
        Radial depth of the grooves from the inner surface [m],
        ``t/2 < d < t``: the groove must reach the roller centres (radius r) and
        leave a floor (a groove through the shell would cut the figure-eight's
        lobes out) (``cam.groove_depth``).
    running_clearance : float or None, optional
        Diametral running clearance c between roller and groove [m]: the groove is
        ``2 rho + c`` wide (``cam.running_clearance``). None (default): the mean clearance
        of the ISO 286 close running fit H8/f7 at the roller diameter
        (:func:`rotorkin.analysis.fits.fit_clearance`; 31.5 um at 8 mm);
        ``0 <= c <= rho/2``.
    roller_length : float or None, optional
        Length L of the inner roller along its (radial) shaft [m] (``cam.roller_length``).
        Its outer end stands ``roller_end_gap`` inside the groove bottom, its inner end no
        deeper than the shell's inner radius: ``0 < L <= sqrt((R_b - gap)^2 - rho^2) - R_i``
        (the largest that fits; the default, None).
    roller_end_gap : float, optional
        Gap between the roller's outer end (its rim) and the groove bottom R_b [m]
        (``cam.roller_end_gap``, default 0.5 mm), ``0 <= gap < R_b - sqrt(R_i^2 + rho^2)``.
    """

    sphere_radius: float
    roller_radius: float = 0.004
    shell_thickness: float = 0.012
    groove_depth: float = 0.008
    running_clearance: float | None = None
    roller_length: float | None = None
    roller_end_gap: float = 0.0005

    def __post_init__(self):
        code = int(cam_violation(self.sphere_radius, self.roller_radius, self.shell_thickness,
                                 self.groove_depth, self.running_clearance, self.roller_length,
                                 self.roller_end_gap))  # fmt: skip
        if code:
            self._refuse(CAM_CHECKED[code - 1])
        for name in ("sphere_radius", "roller_radius", "shell_thickness", "groove_depth",
                     "roller_end_gap"):  # fmt: skip
            object.__setattr__(self, name, float(getattr(self, name)))
        rho = self.roller_radius
        c = self.running_clearance
        c = float(fit_clearance(RUNNING_FIT, 2.0 * rho)) if c is None else float(c)
        object.__setattr__(self, "running_clearance", c)
        longest = self.roller_outer_end - self.inner_radius
        length = longest if self.roller_length is None else float(self.roller_length)
        object.__setattr__(self, "roller_length", min(length, longest))

    def _refuse(self, name: str):
        """Raise the :class:`ParameterError` of the field ``name`` (:data:`CAM_CHECKED`)."""
        r, t, d = (float(v) for v in (self.sphere_radius, self.shell_thickness,
                                      self.groove_depth))  # fmt: skip
        rho, gap = float(self.roller_radius), float(self.roller_end_gap)
        ri = r - 0.5 * t
        rb = ri + d
        if name == "sphere_radius":
            raise ParameterError(name, fmt_mm(r), "sphere_radius > 0 mm")
        if name == "shell_thickness":
            raise ParameterError(name, fmt_mm(t),
                                 f"0 mm < shell_thickness < {fmt_mm(2.0 * r)} (twice the sphere "
                                 "radius: the shell spans sphere_radius -+ "
                                 "shell_thickness/2)")  # fmt: skip
        if name == "groove_depth":
            raise ParameterError(name, fmt_mm(d),
                                 f"{fmt_mm(0.5 * t)} < groove_depth < {fmt_mm(t)} (the groove, "
                                 "cut from the shell's inner surface, must reach the roller "
                                 "centres at sphere_radius and leave a floor: shell_thickness/2 "
                                 "< groove_depth < shell_thickness)")  # fmt: skip
        if name == "roller_radius":
            raise ParameterError(name, fmt_mm(rho),
                                 f"0 mm < roller_radius < {fmt_mm(ri)} (the shell's inner "
                                 "radius)")  # fmt: skip
        if name == "running_clearance":
            c = self.running_clearance
            c = fit_clearance(RUNNING_FIT, 2.0 * rho) if c is None else c
            raise ParameterError(name, fmt_mm(float(c)),
                                 f"0 mm <= running_clearance <= {fmt_mm(0.5 * rho)} (half the "
                                 "roller radius)")  # fmt: skip
        if name == "roller_end_gap":
            top = rb - np.sqrt(ri * ri + rho * rho)
            raise ParameterError(name, fmt_mm(gap),
                                 f"0 mm <= roller_end_gap < {fmt_mm(top)} (a roller reaching "
                                 "from the shell's inner radius must fit below the groove "
                                 "bottom)")  # fmt: skip
        longest = np.sqrt((rb - gap) ** 2 - rho * rho) - ri
        length = longest if self.roller_length is None else self.roller_length
        raise ParameterError(name, fmt_mm(float(length)),
                             f"0 mm < roller_length <= {fmt_mm(longest)}, the largest that fits: "
                             f"from the shell's inner radius {fmt_mm(ri)} to roller_end_gap = "
                             f"{fmt_mm(gap)} inside the groove bottom {fmt_mm(rb)}")  # fmt: skip

    @property
    def inner_radius(self) -> float:
        """Inner radius of the shell ``R_i = r - t/2`` [m]."""
        return self.sphere_radius - 0.5 * self.shell_thickness

    @property
    def outer_radius(self) -> float:
        """Outer radius of the shell ``R_o = r + t/2`` [m]."""
        return self.sphere_radius + 0.5 * self.shell_thickness

    @property
    def bottom_radius(self) -> float:
        """Radius of the groove bottom ``R_b = R_i + groove_depth`` [m]."""
        return self.inner_radius + self.groove_depth

    @property
    def groove_half_width(self) -> float:
        """Half the groove width, ``rho + c/2`` [m]: the walls' offset from the roller axis."""
        return self.roller_radius + 0.5 * self.running_clearance

    @property
    def roller_outer_end(self) -> float:
        """Distance of the roller's outer end face from the sphere centre [m].

        Its rim, at ``sqrt(s^2 + rho^2)``, stands ``roller_end_gap`` inside the groove bottom.
        """
        rim = self.bottom_radius - float(self.roller_end_gap)
        return float(np.sqrt(rim * rim - self.roller_radius**2))

    @property
    def roller_span(self) -> tuple[float, float]:
        """Distances of the roller's inner and outer end faces from the sphere centre [m]."""
        return (self.roller_outer_end - self.roller_length, self.roller_outer_end)


# --------------------------------------------------------------------------------------------
# config
# --------------------------------------------------------------------------------------------
def from_config(cfg: dict):
    """The drive and the cam of a validated wobble-cam config (SI values).

    Returns
    -------
    (WobbleCam, SphericalCam)
        Errors name the config key (``drive.plate_tilt``, ``cam.groove_depth``, ...).
    """
    d = cfg["drive"]
    pistons = (cfg.get("machine") or {}).get("pistons_per_rotor", 4)
    try:
        drive = wc.WobbleCam(
            plate_tilt=d["plate_tilt"],
            roller_axis_angle=d.get("roller_axis_angle", np.pi / 2.0),
            spin_ratio=d.get("spin_ratio", -2.0),
            sphere_radius=d.get("sphere_radius", 0.06),
            pistons_per_rotor=pistons,
            spin_a=tuple(d.get("spin_a", ())),
            spin_b=tuple(d.get("spin_b", ())),
        )
    except ParameterError as exc:
        key = "machine.pistons_per_rotor" if exc.name == "pistons_per_rotor" else exc.name
        key = key if "." in key else f"drive.{key}"
        raise ParameterError(key, exc.value, exc.admissible) from None
    c = cfg.get("cam") or {}
    try:
        cam = SphericalCam(drive.sphere_radius,
                           **{k: c[k] for k in CAM_KEYS if c.get(k) is not None})  # fmt: skip
    except ParameterError as exc:
        raise ParameterError(config_key(exc.name), exc.value, exc.admissible) from None
    return drive, cam


def config_key(name: str) -> str:
    """Config key of a :class:`SphericalCam` field (``sphere_radius`` is the drive's)."""
    return "drive.sphere_radius" if name == "sphere_radius" else f"cam.{name}"


# --------------------------------------------------------------------------------------------
# centre-lines and their derivatives
# --------------------------------------------------------------------------------------------
def groove_frame(drive: wc.WobbleCam, theta):
    """Unit radial ``e_r``, tangent ``t`` and wall normal ``n = e_r x t`` (cam frame).

    Returns
    -------
    (e_r, t, n) : tuple of ndarray, shape (4, 3, ...)
    """
    return frame_of(*groove_derivatives(drive, theta)[:2])


def frame_of(g, d1):
    """:func:`groove_frame` from the centre-lines ``g`` and their derivatives ``d1``."""
    e_r = g / np.linalg.norm(g, axis=1, keepdims=True)
    t = d1 / np.linalg.norm(d1, axis=1, keepdims=True)
    return e_r, t, np.cross(e_r, t, axis=1)


def _check_pair(drive: wc.WobbleCam, cam: SphericalCam) -> None:
    if abs(cam.sphere_radius - drive.sphere_radius) > 1e-12 * drive.sphere_radius:
        raise ParameterError(
            "sphere_radius",
            f"{fmt_mm(drive.sphere_radius)} (cam: {fmt_mm(cam.sphere_radius)})",
            "the same sphere radius for the drive and its cam",
        )


def groove_walls(drive: wc.WobbleCam, cam: SphericalCam, theta, radius=None):
    """Wall curves of the 4 grooves on the sphere of ``radius`` (cam frame) [m].

    ``w_+- = sqrt(R^2 - h^2) e_r +- h n``, ``h = rho + c/2`` (``cam.groove_half_width``, the
    roller radius plus half the running clearance): the exact envelope of a cylinder of
    radius h on the roller axis (radial) cut by the sphere R, i.e. the centre-line offset
    along the sphere by ``arcsin(h/R)``, perpendicular to its tangent.

    Parameters
    ----------
    drive, cam : WobbleCam, SphericalCam
    theta : array_like, shape (...)
        Shaft angle [rad].
    radius : float or array_like, optional
        Sphere radius R [m], ``R > h``; default ``cam.sphere_radius`` (broadcast with theta).

    Returns
    -------
    ndarray, shape (4, 2, 3, ...)
        Roller, wall (0: ``+n``, left of the roller's travel seen from outside;
        1: ``-n``), coordinate.
    """
    _check_pair(drive, cam)
    rad = cam.sphere_radius if radius is None else np.asarray(radius, dtype=float)
    h = cam.groove_half_width
    if np.any(rad <= h):
        raise ParameterError(
            "radius",
            fmt_mm(np.min(rad)),
            f"radius > {fmt_mm(h)} (half the groove width)",
        )
    e_r, _, n = groove_frame(drive, theta)
    lam = np.sqrt(rad * rad - h * h)
    return np.stack([lam * e_r + h * n, lam * e_r - h * n], 1)


# --------------------------------------------------------------------------------------------
# checks along the groove
# --------------------------------------------------------------------------------------------
def pressure_angle(drive: wc.WobbleCam, theta, frame: str = "shaft"):
    """Pressure angle of the 4 rollers along their grooves [rad], in ``[0, pi/2]``.

    Angle between the contact force direction (the wall normal ``n``, friction
    neglected) and the velocity of the roller centre:

    * ``frame="shaft"`` (default): relative to the Z-shaft, ``dvarphi/dtheta dp/du``,
      the plate's spin that the cam imposes; in the shaft frame the cam axis (x) and
      the plate axis (x2) are both fixed, as in a classical cam pair;
    * ``frame="fixed"``: in the fixed frame (spin plus the shaft's revolution).

    ``mu = atan2(|t . v|, |n . v|)`` (v lies in the sphere's tangent plane). The
    velocity relative to the cam is ``dg/dtheta``, along ``t``: at 90 deg to ``n``
    always, so it cannot serve.

    Returns
    -------
    ndarray, shape (4, ...)
    """
    if frame not in ("shaft", "fixed"):
        raise ParameterError("frame", repr(frame), "'shaft' or 'fixed'")
    p, pt, pu, spin = _partials(drive, theta)
    v = pu * spin[1] if frame == "shaft" else pt + pu * spin[1]
    v = np.moveaxis(v, 0, 1)
    _, t, n = groove_frame(drive, theta)
    return np.arctan2(np.abs(np.sum(t * v, axis=1)), np.abs(np.sum(n * v, axis=1)))


def geodesic_curvature(drive: wc.WobbleCam, theta):
    """Signed geodesic curvature of the 4 centre-lines on the sphere r [1/m].

    ``kappa_g = (g' x g'') . e_r / |g'|^3``; positive when the groove turns towards
    ``+n`` (left of the travel, seen from outside the sphere).

    Returns
    -------
    ndarray, shape (4, ...)
    """
    return curvature_of(*groove_derivatives(drive, theta))


def curvature_of(g, d1, d2):
    """:func:`geodesic_curvature` from the centre-lines and their first two derivatives."""
    e_r = g / np.linalg.norm(g, axis=1, keepdims=True)
    num = np.sum(np.cross(d1, d2, axis=1) * e_r, axis=1)
    return num / np.linalg.norm(d1, axis=1) ** 3


def curvature_radius(drive: wc.WobbleCam, theta):
    """Radius of curvature ``1/|kappa_g|`` of the centre-lines in the tangent plane [m], (4, ...)"""
    k = np.abs(geodesic_curvature(drive, theta))
    with np.errstate(divide="ignore"):
        return np.where(k > 0.0, 1.0 / np.where(k > 0.0, k, 1.0), np.inf)


def roller_radius_limit(drive: wc.WobbleCam, theta, radius=None):
    """Largest roller radius whose groove walls stay free of cusps, on the sphere R [m].

    ``rho_lim = R / sqrt(1 + (r kappa_g)^2) = R sin(a)``, ``a`` the angular radius of
    the osculating small circle of the centre-line (derived here: the wall at angular
    offset ``arcsin(rho/R)`` degenerates when that offset reaches ``a``). For a
    gentle bend (``r kappa_g >> 1``) it is ``(R/r) / |kappa_g|``.

    Parameters
    ----------
    radius : float, optional
        R [m]; default ``drive.sphere_radius``. Use the shell's inner radius for the
        check (the strictest radius where there is a wall).

    Returns
    -------
    ndarray, shape (4, ...)
    """
    rad = drive.sphere_radius if radius is None else float(radius)
    k = geodesic_curvature(drive, theta)
    return rad / np.sqrt(1.0 + (drive.sphere_radius * k) ** 2)


def sharpest_bend(drive: wc.WobbleCam, roller: int | None = None):
    """Largest ``|kappa_g|`` over the grooves: ``(kappa_max [1/m], theta [rad], roller)``.

    Remembered per drive (the last 512; a drive of arrays is not remembered): a sweep
    checks every design of one drive with its own machine and cam sizes.
    """
    try:
        return _sharpest_bend_remembered(drive, roller)
    except TypeError:  # a drive holding arrays cannot be a key
        return _sharpest_bend(drive, roller)


@functools.lru_cache(maxsize=512)
def _sharpest_bend_remembered(drive: wc.WobbleCam, roller: int | None):
    return _sharpest_bend(drive, roller)


def _sharpest_bend(drive: wc.WobbleCam, roller: int | None):
    period = groove_period(drive)
    theta = np.linspace(0.0, period, _SEARCH_SAMPLES, endpoint=False)
    k = np.abs(geodesic_curvature(drive, theta))
    rollers = np.arange(4) if roller is None else np.array([roller])
    step = period / _SEARCH_SAMPLES
    start = theta[np.argmax(k[rollers], axis=-1)]
    # the sampled peak of each roller refined at once (Brent in a bracket of +-1 sample)
    th, val = bounded_min(
        lambda x: -np.abs(geodesic_curvature(drive, x)[rollers, np.arange(len(rollers))]),
        start - step,
        start + step,
        xatol=1e-12,
    )
    best = int(np.argmin(val))  # the first roller of the largest bend
    return float(-val[best]), float(th[best] % period), int(rollers[best])


def check_roller_radius(drive: wc.WobbleCam, cam: SphericalCam) -> float:
    """Raise ``ParameterError("roller_radius")`` where the roller undercuts a wall.

    The walls stand ``h = rho + c/2`` off the roller axis (``cam.groove_half_width``); the
    check is ``h < R_i / sqrt(1 + (r kappa_g)^2)`` (:func:`roller_radius_limit` at the
    inner shell radius, the strictest radius where the wall exists) everywhere on every
    groove, i.e. ``rho`` below that limit less half the running clearance; the message
    names the shaft angle, the roller and both radii.

    Returns
    -------
    float
        The limit of the walls' offset [m] (the groove's half-width ``h`` is below it; the
        roller radius below it less ``c/2``).
    """
    _check_pair(drive, cam)
    kmax, theta, roller = sharpest_bend(drive)
    limit = cam.inner_radius / np.sqrt(1.0 + (drive.sphere_radius * kmax) ** 2)
    if cam.groove_half_width >= limit:
        raise ParameterError(
            "roller_radius",
            fmt_mm(cam.roller_radius),
            f"roller_radius < {fmt_mm(limit - 0.5 * cam.running_clearance)}: at shaft angle "
            f"theta = {fmt_deg(theta)} "
            f"(roller {ROLLER_NAMES[roller]}) the groove centre-line bends with radius "
            f"{fmt_mm(1.0 / kmax)} in the tangent plane, and a larger roller makes a cusp in "
            f"the inner groove wall at the shell's inner radius {fmt_mm(cam.inner_radius)}",
        )
    return float(limit)


# --------------------------------------------------------------------------------------------
# crossings
# --------------------------------------------------------------------------------------------
def guided(drive: wc.WobbleCam, cam: SphericalCam, theta):
    """Whether each roller runs between both walls of its groove at ``theta``.

    Both walls must be there along the roller's whole contact lines, at the configured
    running clearance (:func:`rotorkin.drives.wobble_cam.cam_walls.walls_present`: another
    branch's channel, intersected with the contact lines, cuts a gap into each wall around
    every crossing; one wall or the other is missing over about ``2 h (cot a + 1/sin a)``
    of the path at a crossing angle ``a``, ``h`` the groove's half-width, measured at the
    roller's inner end). The gaps are kept for the last 16 drive and cam pairs.

    Parameters
    ----------
    drive, cam : WobbleCam, SphericalCam
    theta : array_like, shape (...)
        Shaft angle [rad].

    Returns
    -------
    ndarray of bool, shape (4, ...)
    """
    _check_pair(drive, cam)
    return walls_present(drive, cam, theta, wall_gaps(drive, cam)).all(axis=1)


@functools.lru_cache(maxsize=16)
def wall_gaps(drive: wc.WobbleCam, cam: SphericalCam) -> tuple:
    """:func:`rotorkin.drives.wobble_cam.cam_walls.wall_gaps` of a drive and its cam (kept)."""
    return tuple(cam_walls.wall_gaps(drive, cam))


def pressure_angle_peaks(drive: wc.WobbleCam, cam: SphericalCam, samples: int = 2881) -> dict:
    """Largest pressure angles over one turn, where and of which roller.

    Sampled at ``samples`` shaft angles over ``[0, 2 pi]`` (as :func:`summary`).

    Returns
    -------
    dict
        ``name -> (angle [rad], theta [rad], roller index)`` for

        * ``"any"``: largest of any roller (shaft frame), crossings included;
        * ``"guided"``: the same away from the crossings (:func:`guided`);
        * ``"fixed_guided"``: the same in the fixed frame;
        * ``"best"``: over the turn, the largest of the smallest pressure angle of the 4
          rollers (the best-placed roller guides the plate), crossings included;
        * ``"best_guided"``: the same over the rollers between both walls only
          (``pi/2`` where none is);

        the roller is the one reaching the angle (for the best: the best-placed one).
    """
    theta = np.linspace(0.0, 2.0 * np.pi, samples)
    ok = guided(drive, cam, theta)
    mu = pressure_angle(drive, theta)
    fixed = pressure_angle(drive, theta, "fixed")

    def peak(values):  # the first shaft angle reaching the maximum, then its roller
        j = int(np.argmax(np.max(values, axis=0)))
        i = int(np.argmax(values[:, j]))
        return float(values[i, j]), float(theta[j]), i

    def best(values):
        k = np.argmin(values, axis=0)
        low = values[k, np.arange(values.shape[1])]
        j = int(np.argmax(low))
        if not np.isfinite(low[j]):
            return 0.5 * np.pi, float(theta[j]), -1
        return float(low[j]), float(theta[j]), int(k[j])

    return {
        "any": peak(mu),
        "guided": peak(np.where(ok, mu, -1.0)),
        "fixed_guided": peak(np.where(ok, fixed, -1.0)),
        "best": best(mu),
        "best_guided": best(np.where(ok, mu, np.inf)),
    }


#: The keys of :func:`shape_summary`, in the order :func:`summary` lists them.
_SHAPE_KEYS = (
    "cam_pressure_angle_max_deg",
    "cam_pressure_angle_max_theta_deg",
    "cam_pressure_angle_best_roller_max_deg",
    "cam_curvature_radius_min_mm",
    "cam_curvature_min_theta_deg",
    "cam_roller_radius_limit_mm",
)


def shape_summary(drive: wc.WobbleCam, cam: SphericalCam, samples: int = 2881) -> dict:
    """The keys of :func:`summary` that follow from the grooves' shape alone.

    The pressure angles of every roller (crossings included) and the sharpest bend, with
    the undercut limit it sets: neither the crossings nor the walls are searched (a
    figure's titles need these without the cost of the rest).
    """
    _check_pair(drive, cam)
    theta = np.linspace(0.0, 2.0 * np.pi, samples)
    mu = pressure_angle(drive, theta)
    k = int(np.argmax(np.max(mu, axis=0)))
    kmax, th_k, _ = sharpest_bend(drive)
    return {
        "cam_pressure_angle_max_deg": float(np.degrees(mu[:, k].max())),
        "cam_pressure_angle_max_theta_deg": float(np.degrees(theta[k])),
        "cam_pressure_angle_best_roller_max_deg": float(np.degrees(mu.min(axis=0).max())),
        "cam_curvature_radius_min_mm": 1e3 / kmax,
        "cam_curvature_min_theta_deg": float(np.degrees(th_k)),
        "cam_roller_radius_limit_mm": 1e3
        * (
            cam.inner_radius / np.sqrt(1.0 + (drive.sphere_radius * kmax) ** 2)
            - 0.5 * cam.running_clearance
        ),
    }


def summary(drive: wc.WobbleCam, cam: SphericalCam, samples: int = 2881) -> dict:
    """Scalar results for a study's ``summary.json`` (units in the key names).

    ``cam_pressure_angle_max_deg``: largest pressure angle of any roller (shaft frame);
    ``cam_pressure_angle_best_roller_max_deg``: over the turn, the largest of the
    smallest pressure angle of the 4 rollers at each shaft angle (all 4 rollers hold
    the one plate, so the best-placed one guides it);
    ``cam_pressure_angle_fixed_max_deg``: largest in the fixed frame;
    ``cam_pressure_angle_guided_max_deg`` and ``..._theta_deg``: largest of any roller
    away from the crossings (:func:`guided`, :func:`pressure_angle_peaks`) and where;
    ``cam_pressure_angle_best_guided_roller_max_deg`` and ``..._theta_deg``: the
    best-roller value over the rollers between both walls;
    ``cam_curvature_radius_min_mm``: smallest ``1/|kappa_g|`` on r and
    ``cam_curvature_min_theta_deg`` where (first roller reaching it);
    ``cam_roller_radius_limit_mm``: undercut limit at the inner radius R_i;
    ``cam_groove_period_deg``; ``cam_distinct_grooves``; ``cam_self_crossings``
    and ``cam_crossings_between_grooves`` (counts over the distinct grooves);
    ``cam_crossing_angle_min_deg``; ``cam_unguided_length_max_mm`` (the longest path of a
    roller centre with one wall or the other missing at a crossing, :func:`wall_gaps`);
    ``cam_both_walls_fraction`` (share of the turn with both walls along a roller's
    contact lines, mean of the 4 rollers, :func:`guided` on 72000 angles);
    ``cam_groove_separation_mm`` (closest centre-lines of two different grooves, 0 where
    they cross); ``cam_groove_width_mm`` (``2 rho + c``); ``cam_running_clearance_mm``.
    """
    shape = shape_summary(drive, cam, samples)
    period = groove_period(drive)
    crossings = groove_crossings(drive)
    distinct = distinct_grooves(drive)
    n_self = sum(c.rollers[0] == c.rollers[1] for c in crossings)
    peaks = pressure_angle_peaks(drive, cam, samples)
    gaps = wall_gaps(drive, cam)
    turn = np.linspace(0.0, 2.0 * np.pi, _TURN_SAMPLES, endpoint=False)
    return {
        "cam_roller_radius_mm": cam.roller_radius * 1e3,
        **{k: shape[k] for k in _SHAPE_KEYS[:3]},
        "cam_pressure_angle_fixed_max_deg": float(
            np.degrees(pressure_angle(drive, np.linspace(0.0, 2.0 * np.pi, samples), "fixed").max())
        ),
        "cam_pressure_angle_guided_max_deg": float(np.degrees(peaks["guided"][0])),
        "cam_pressure_angle_guided_max_theta_deg": float(np.degrees(peaks["guided"][1])),
        "cam_pressure_angle_best_guided_roller_max_deg": float(np.degrees(peaks["best_guided"][0])),
        "cam_pressure_angle_best_guided_roller_max_theta_deg": float(
            np.degrees(peaks["best_guided"][1])
        ),
        **{k: shape[k] for k in _SHAPE_KEYS[3:]},
        "cam_groove_period_deg": float(np.degrees(period)),
        "cam_distinct_grooves": len(distinct),
        "cam_self_crossings": int(n_self),
        "cam_crossings_between_grooves": len(crossings) - int(n_self),
        "cam_crossing_angle_min_deg": float(
            np.degrees(min((c.angle for c in crossings), default=np.nan))
        ),
        "cam_unguided_length_max_mm": 1e3
        * max((x[3] for x in cam_walls.unguided_stretches(drive, gaps)), default=0.0),
        "cam_both_walls_fraction": float(np.mean(walls_present(drive, cam, turn, gaps).all(1))),
        "cam_groove_separation_mm": groove_separation(drive)[0] * 1e3,
        "cam_groove_width_mm": 2e3 * cam.groove_half_width,
        "cam_running_clearance_mm": 1e3 * cam.running_clearance,
    }
