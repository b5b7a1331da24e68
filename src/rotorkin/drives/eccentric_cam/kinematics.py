"""Double eccentric discs on one shaft driving two opposed pistons.

Source: Zhu Ruilin, Zhu Guolin, "Analysis of the motions of the double eccentric
cams used in a process intensification equipment", Engineering Sciences (China)
14(10), 2012 (in Chinese). Equation and figure numbers below are the paper's.

Two circular discs of radius ``R`` sit on one shaft with eccentricity ``e``
(``lambda = e/R < 1``); each pushes one piston of an opposed-piston reactor of
length ``L``. The shaft angle is ``beta`` (``beta = omega t``); the two discs are
mounted half a turn apart, so at ``beta = 0`` the left piston is at its top
(``+e``) and the right piston at its bottom (``-e``).

Conventions (the paper's, made explicit):

* ``z`` (left) and ``z'`` (right) [m] are the travels of the pistons' inner
  faces from their mid (balanced, ``o-o``) positions, **positive towards the
  reactor centre** (eq. 1, 3). For the left piston this is "up" in the
  paper's Fig. 2; at ``beta = 0``: ``z = +e``, ``z' = -e``.
* Each follower axis passes through the shaft axis. In the frame of a
  follower (x along its axis, towards the reactor centre, origin on the shaft
  axis), the left disc centre is at ``e (cos beta, sin beta)`` and the right
  disc centre at ``-e (cos beta, sin beta)``.
* The paper's "gap change" is ``Delta = z + z'`` (eq. 5): the sum of the
  inward travels. The distance between the inner faces is ``L0 - Delta``;
  ``Delta <= 0`` means the faces stand farther apart than in the balanced
  position (the reactor volume can only grow, the pressure only drop).
  ``delta = Delta / e`` (eq. 6).

Followers:

* ``knife_edge``: point contact on the follower axis (eq. 1-6).
* ``flat``: a contact plate normal to the piston axis, tangent to the disc:
  harmonic travel ``+-e cos beta``, ``Delta = 0`` (eq. 7, 8).
* ``roller``: a roller of radius ``r`` whose centre stays on the follower axis
  at ``R + r`` from the disc centre (derived here, the paper leaves it open):
  the knife-edge formulas with the *contact radius* ``R + r`` in place of
  ``R`` (also in the ``-R`` term, so that ``z(0) = e``). It lies between the
  two: ``|Delta_flat| = 0 < |Delta_roller| < |Delta_knife_edge|``.

Misprints of the paper (OCR): the additional term is printed
``sqrt((1 - lambda)^2 - sin^2 beta) - 1/lambda``; read ``(1/lambda)^2``. The
definition ``lambda - lambda = e/R`` reads ``lambda = e/R``. The example
``Delta/L = 21.4/2000 = 2.14 %`` reads ``21.4/1000``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.core.angles import fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.core.motion import Motion, compose
from rotorkin.drives.eccentric_cam.kinematics_fused import travels_fused

__all__ = [
    "FOLLOWERS",
    "EccentricCam",
    "contact_radius",
    "invalid_parameter",
    "harmonic_travel",
    "additional_travel",
    "travels",
    "travel_peaks",
    "piston_travels",
    "gap_change",
    "decomposition",
    "gap_change_extreme",
    "piston_stroke",
    "pressure_angle",
    "pressure_angle_max",
    "motion",
    "period",
    "adjuster_eccentricity",
    "adjuster_slide",
    "section_semi_axes",
    "section_travels",
]

#: Admissible follower kinds.
FOLLOWERS = ("knife_edge", "flat", "roller")


def contact_radius(disc_radius, follower, roller_radius):
    """Radius ``Rc`` of the circle the follower point runs on, relative to the disc [m].

    ``R`` for a knife edge, ``R + r`` for a roller (the roller centre), ``inf``
    for a flat face (a straight line: the harmonic limit). Broadcasts.

    Parameters
    ----------
    disc_radius : array_like
        R [m].
    follower : str or array_like of str
        ``"knife_edge"``, ``"flat"`` or ``"roller"``.
    roller_radius : array_like
        r [m], used by ``"roller"`` only.

    Returns
    -------
    ndarray
        Rc [m].
    """
    R = np.asarray(disc_radius, dtype=float)
    r = np.asarray(roller_radius, dtype=float)
    f = np.asarray(follower)
    return np.where(f == "knife_edge", R, np.where(f == "roller", R + r, np.inf))


def invalid_parameter(disc_radius, eccentricity, follower, roller_radius):
    """The first violated parameter of each design, ``""`` where all are admissible.

    Checked in this order: ``disc_radius`` (finite, ``R > 0``), ``eccentricity``
    (finite, ``0 < e < R``: ``lambda = e/R < 1``, or the disc would not contain
    the shaft axis), ``follower`` (one of :data:`FOLLOWERS`), ``roller_radius``
    (finite, ``r >= 0``; ``r > 0`` for a roller follower). Broadcasts.

    Returns
    -------
    ndarray of str
        A field name of :class:`EccentricCam` per design, or ``""``.
    """
    R = np.asarray(disc_radius, dtype=float)
    e = np.asarray(eccentricity, dtype=float)
    f = np.asarray(follower)
    r = np.asarray(roller_radius, dtype=float)
    with np.errstate(invalid="ignore"):
        checks = (
            ("disc_radius", ~(np.isfinite(R) & (R > 0.0))),
            ("eccentricity", ~(np.isfinite(e) & (e > 0.0) & (e < R))),
            ("follower", ~np.isin(f, FOLLOWERS)),
            ("roller_radius", ~(np.isfinite(r) & (r >= 0.0)) | ((f == "roller") & ~(r > 0.0))),
        )
    shape = np.broadcast_shapes(*(bad.shape for _, bad in checks))
    out = np.full(shape, "", dtype=f"<U{max(len(n) for n, _ in checks)}")
    for name, bad in reversed(checks):
        out[np.broadcast_to(bad, shape)] = name
    return out


def _first(values, mask):
    """The first element of ``values`` where ``mask`` (both broadcast)."""
    v, m = np.broadcast_arrays(np.asarray(values), np.asarray(mask))
    return v[m].flat[0] if v.ndim else v[()]


@dataclass(frozen=True)
class EccentricCam:
    """Parameters of the double eccentric-disc drive (SI); floats or broadcasting arrays.

    Parameters
    ----------
    disc_radius : float or array_like
        Disc radius R [m], ``R > 0``. Paper: 80 mm.
    eccentricity : float or array_like
        Eccentricity e of the disc centre from the shaft axis [m],
        ``0 < e < R``. Paper: 40 mm (``lambda = 0.5``).
    follower : {"knife_edge", "flat", "roller"} or array_like of str, optional
        Piston follower (default ``"knife_edge"``, the paper's Fig. 2).
    roller_radius : float or array_like, optional
        Roller radius r [m] of a roller follower, ``r > 0`` for
        ``follower = "roller"``; ignored by the other followers (default 0).

    Raises
    ------
    ParameterError
        Naming the first violated field (:func:`invalid_parameter`), its value
        and the admissible range.
    """

    disc_radius: float
    eccentricity: float
    follower: str = "knife_edge"
    roller_radius: float = 0.0

    def __post_init__(self):
        bad = invalid_parameter(
            self.disc_radius, self.eccentricity, self.follower, self.roller_radius
        )
        if not bad.any():
            return
        name = str(_first(bad, bad != ""))
        mask = bad == name
        value = _first(getattr(self, name), mask)
        if name == "follower":
            raise ParameterError(
                "follower", repr(str(value)), "one of " + ", ".join(map(repr, FOLLOWERS))
            )
        value = float(value)
        if name == "disc_radius":
            raise ParameterError(name, fmt_mm(value), "disc_radius > 0 mm")
        if name == "eccentricity":
            R = float(_first(self.disc_radius, mask))
            raise ParameterError(
                name,
                fmt_mm(value),
                f"0 mm < eccentricity < {fmt_mm(R)}: the eccentricity must be below "
                "disc_radius (lambda = e/R < 1), or the disc would not contain the shaft axis",
            )
        if not (np.isfinite(value) and value >= 0.0):
            raise ParameterError(name, fmt_mm(value), "roller_radius >= 0 mm")
        raise ParameterError(name, fmt_mm(value), "roller_radius > 0 mm for follower = 'roller'")

    @property
    def lam(self):
        """Eccentricity ratio ``lambda = e/R`` [-] (paper, section 2)."""
        return _value(
            np.asarray(self.eccentricity, dtype=float) / np.asarray(self.disc_radius, dtype=float)
        )

    @property
    def contact_radius(self):
        """Radius ``Rc`` of the circle the follower point runs on [m] (:func:`contact_radius`)."""
        return _value(contact_radius(self.disc_radius, self.follower, self.roller_radius))


def _value(x):
    """A NumPy scalar for a 0-d result, the array otherwise."""
    return np.asarray(x)[()]


# --------------------------------------------------------------------------------------------
# the two parts of a piston's travel
# --------------------------------------------------------------------------------------------
def harmonic_travel(eccentricity, beta):
    """Harmonic part ``e cos beta`` of the left piston's travel and its derivatives.

    Paper: the vertical travel of the disc centre (Fig. 3), ``xi = cos beta``
    in units of e (Fig. 6); also the whole travel of a flat follower (eq. 7).

    Parameters
    ----------
    eccentricity : array_like
        e [m].
    beta : array_like
        Shaft angle [rad].

    Returns
    -------
    tuple of 4 ndarray
        ``e cos beta`` [m] and its 1st-3rd derivatives [m/rad^n].
    """
    e = np.asarray(eccentricity, dtype=float)
    b = np.asarray(beta, dtype=float)
    c, s = np.cos(b), np.sin(b)
    return e * c, -e * s, -e * c, e * s


def additional_travel(contact_radius, eccentricity, beta):
    """Additional (non-harmonic) part ``sqrt(Rc^2 - e^2 sin^2 beta) - Rc`` and derivatives.

    Paper: ``e mu`` with ``mu = sqrt((1/lambda)^2 - sin^2 beta) - 1/lambda``
    (eq. 2, Fig. 6) for ``Rc = R``; also ``Delta/2`` (section 3, Fig. 11). It is
    the same for both pistons and never positive. ``Rc = R + r`` for a roller
    (derived here); ``Rc = inf`` gives 0 (flat face).

    Parameters
    ----------
    contact_radius : array_like
        Rc [m], ``Rc > e``.
    eccentricity : array_like
        e [m].
    beta : array_like
        Shaft angle [rad].

    Returns
    -------
    tuple of 4 ndarray
        The term [m] and its 1st-3rd derivatives [m/rad^n]. With
        ``w = e^2 sin^2 beta`` and ``S = sqrt(Rc^2 - w)``: ``f = S - Rc``,
        ``f' = -w'/(2S)``, chain rule to order 3 (``w' = e^2 sin 2beta``,
        ``w'' = 2 e^2 cos 2beta``, ``w''' = -4 e^2 sin 2beta``).
    """
    Rc = np.asarray(contact_radius, dtype=float)
    e = np.asarray(eccentricity, dtype=float)
    b = np.asarray(beta, dtype=float)
    e2 = e * e
    s2, c2 = np.sin(2.0 * b), np.cos(2.0 * b)
    w = (0.5 * e2) * (1.0 - c2)  # e^2 sin^2 beta, without cancellation near 0
    w_d = (e2 * s2, 2.0 * e2 * c2, -4.0 * e2 * s2)
    finite = np.isfinite(Rc)
    Rf = np.where(finite, Rc, 2.0 * np.abs(e) + 1.0)  # any Rc > e: masked out below
    S = np.sqrt(Rf * Rf - w)
    # S - Rc = -w / (S + Rc): accurate for small e/Rc
    f0 = -w / (S + Rf)
    f = (f0, -0.5 / S, -0.25 / S**3, -0.375 / S**5)
    out = compose(f, (w, *w_d))
    return tuple(np.where(finite, v, 0.0) for v in out)


def travels(contact_radius, eccentricity, beta):
    """Travels ``(z, z')`` of the left and right pistons and their derivatives.

    ``z = A + e cos beta``, ``z' = A - e cos beta`` with the additional part
    ``A = sqrt(Rc^2 - e^2 sin^2 beta) - Rc`` (:func:`additional_travel`,
    :func:`harmonic_travel`); eq. 1, 3 for a knife edge (``Rc = R``), eq. 7, 8 for
    a flat face (``Rc = inf``, ``A = 0``). Broadcasts.

    Parameters
    ----------
    contact_radius : array_like
        Rc [m] (:func:`contact_radius`).
    eccentricity : array_like
        e [m].
    beta : array_like
        Shaft angle [rad].

    Returns
    -------
    tuple of 4 ndarray, shape (2, ...)
        ``(z, z')`` [m], positive towards the reactor centre, and their
        1st-3rd derivatives with respect to beta [m/rad^n].

    Notes
    -----
    Evaluated block by block from one ``tan(beta/2)`` and one square root per point
    (:func:`rotorkin.drives.eccentric_cam.kinematics_fused.travels_fused`; compiled
    loops when numba is installed, ``$ROTORKIN_KERNEL`` chooses); the same values as
    :func:`additional_travel` plus or minus :func:`harmonic_travel`.
    """
    return tuple(travels_fused(contact_radius, eccentricity, beta))


def piston_travels(params: EccentricCam, beta):
    """:func:`travels` of the drive ``params`` (eq. 1, 3; eq. 7, 8 for a flat face).

    Returns ``(z, z')`` [m] and their 1st-3rd derivatives [m/rad^n], shape (2, ...).
    """
    return travels(params.contact_radius, params.eccentricity, beta)


def travel_peaks(contact_radius, eccentricity, beta):
    """Largest ``|d^k z/dbeta^k|`` of either piston over the angles ``beta`` (last axis).

    Parameters
    ----------
    contact_radius, eccentricity : array_like
        Rc, e [m]; shape (n, 1) against angles (m,) gives one peak per design.
    beta : array_like
        Shaft angles sampled over a period [rad].

    Returns
    -------
    tuple of 3 ndarray
        Peaks of the velocity, acceleration and jerk coefficients [m/rad^n].
    """
    q = travels(contact_radius, eccentricity, beta)
    axes = (0, q[0].ndim - 1)
    return tuple(np.abs(q[k]).max(axis=axes) for k in (1, 2, 3))


def gap_change(params: EccentricCam, beta):
    """Gap change ``Delta = z + z'`` (eq. 5) and its derivatives [m, m/rad^n].

    ``Delta = 2 (sqrt(R^2 - e^2 sin^2 beta) - R) <= 0`` for a knife edge,
    ``R -> R + r`` for a roller, 0 for a flat face (eq. 7, 8). Period pi,
    symmetric about 90 deg, zero at ``k pi``, most negative at 90 deg.
    """
    a = additional_travel(params.contact_radius, params.eccentricity, beta)
    return tuple(2.0 * v for v in a)


def decomposition(params: EccentricCam, beta):
    """Dimensionless travels of Fig. 6 and 8: ``xi``, ``mu``, ``x``, ``x'``, ``delta``.

    ``x = z/e = xi + mu`` (eq. 2), ``x' = z'/e = mu - xi`` (eq. 4, ``xi' = -xi``),
    ``delta = x + x' = 2 mu`` (eq. 6).

    Returns
    -------
    dict of str -> ndarray
        Keys ``"xi"``, ``"mu"``, ``"x"``, ``"x_right"``, ``"delta"`` [-].
    """
    beta = np.asarray(beta, dtype=float)
    e = np.asarray(params.eccentricity, dtype=float)
    mu = additional_travel(params.contact_radius, e, beta)[0] / e
    xi = np.broadcast_to(np.cos(beta), mu.shape)
    return {"xi": xi, "mu": mu, "x": xi + mu, "x_right": mu - xi, "delta": 2.0 * mu}


def gap_change_extreme(params: EccentricCam) -> tuple[float, float]:
    """Most negative gap change over a turn and where it occurs.

    ``Delta_min = 2 (sqrt(Rc^2 - e^2) - Rc)`` at ``beta = 90 deg`` (and 270 deg),
    eq. 5; 0 for a flat face (where 90 deg is reported for uniformity).

    Returns
    -------
    (Delta_min, beta) : tuple
        [m] (a NumPy scalar, or an array for array parameters), [rad].
    """
    return _value(gap_change(params, np.pi / 2.0)[0]), np.pi / 2.0


def piston_stroke(params: EccentricCam):
    """Stroke of each piston, ``z(0) - z(pi) = 2 e`` [m], for every follower.

    ``z`` falls monotonically from ``+e`` to ``-e`` on ``[0, pi]``: ``dz/dbeta =
    -e sin beta (1 + e cos beta / S)`` and ``S > e |cos beta|`` since ``Rc > e``.
    """
    return _value(2.0 * np.asarray(params.eccentricity, dtype=float))


def pressure_angle(params: EccentricCam, beta):
    """Pressure angle of the left piston: between the contact normal and the piston axis [rad].

    Derived here: the contact normal passes through the disc centre, so
    ``sin(alpha_p) = e sin(beta) / Rc`` (knife edge ``Rc = R``, roller
    ``Rc = R + r``); 0 for a flat face. Positive when the normal leans towards
    ``+sin beta``. The right piston's is the negative of this.
    """
    b = np.asarray(beta, dtype=float)
    e = np.asarray(params.eccentricity, dtype=float)
    return np.arcsin(e * np.sin(b) / params.contact_radius)


def pressure_angle_max(params: EccentricCam):
    """Largest pressure angle over a turn, ``arcsin(e / Rc)`` at 90 deg [rad]."""
    return _value(pressure_angle(params, np.pi / 2.0))


# --------------------------------------------------------------------------------------------
# the drive interface
# --------------------------------------------------------------------------------------------
def motion(params: EccentricCam, beta) -> Motion:
    """Motion of the left and right pistons, ``q = (z, z')`` [m], over shaft angle beta [rad]."""
    beta = np.asarray(beta, dtype=float)
    q, dq, d2q, d3q = piston_travels(params, beta)
    return Motion(beta, q, dq, d2q, d3q, members=("left piston", "right piston"), unit="m")


def period(params: EccentricCam) -> float:
    """Shaft angle after which the pistons' motion repeats: 2 pi [rad].

    (The gap change alone repeats every pi.)
    """
    return 2.0 * np.pi


# --------------------------------------------------------------------------------------------
# the adjuster of the paper's Fig. 2: an inclined disc slid along the shaft
# --------------------------------------------------------------------------------------------
def adjuster_eccentricity(inclination, slide):
    """Eccentricity ``e = s tan(alpha)`` set by an inclined disc slid along the shaft [m].

    Paper, section 2 (Fig. 2): the rotor is a circular cylinder of radius ``R`` whose
    own axis makes the angle ``alpha`` with the shaft axis and crosses it at the
    point ``o''``; the rotor can slide along the shaft to change ``e``. In the plane
    of a piston (normal to the shaft, at the axial distance ``s`` from ``o''``) the
    rotor's axis stands ``s tan(alpha)`` from the shaft axis: that is ``e``. At
    ``alpha = 0`` (or ``s = 0``) there is no eccentricity. Broadcasts.

    Parameters
    ----------
    inclination : array_like
        alpha [rad], ``0 <= alpha < pi/2``.
    slide : array_like
        s [m], the axial distance of the piston plane from ``o''``.
    """
    return np.asarray(slide, dtype=float) * np.tan(np.asarray(inclination, dtype=float))


def adjuster_slide(inclination, eccentricity):
    """The slide ``s = e / tan(alpha)`` that sets the eccentricity ``e`` (``alpha > 0``) [m]."""
    return np.asarray(eccentricity, dtype=float) / np.tan(np.asarray(inclination, dtype=float))


def section_semi_axes(disc_radius, inclination):
    """Semi-axes ``(a, b) = (R / cos(alpha), R)`` of the rotor's section in a piston plane [m].

    Derived here. Shaft axis ``Z``; the rotor's axis passes through ``o''`` (the
    origin) with the direction ``(sin alpha, 0, cos alpha)``. A point ``(X, Y, s)`` of
    the piston plane ``Z = s`` lies on the cylinder of radius ``R`` when its distance
    from that axis is ``R``. With ``dX = X - s tan(alpha)`` (measured from the point
    where the axis pierces the plane, the section's centre, ``e`` from the shaft),
    the squared distance is ``dX^2 + Y^2 - (dX sin alpha)^2``, so

        dX^2 cos^2(alpha) + Y^2 = R^2:

    an ellipse centred ``e`` from the shaft axis, semi-major axis ``a = R/cos(alpha)``
    along the eccentricity (the line from the shaft axis to the centre), semi-minor
    ``b = R`` across it. The paper draws the section as the circle of radius ``R``;
    the two agree at ``alpha = 0``.
    """
    R = np.asarray(disc_radius, dtype=float)
    return R / np.cos(np.asarray(inclination, dtype=float)), R


def _knife_on_ellipse(a, b, e_signed, beta):
    """Distance from the shaft axis of the follower axis' crossing with the section [m].

    In the ellipse's own axes (``u = (cos beta, sin beta)`` along the major axis,
    ``v`` across) the point ``(rho, 0)`` of the follower axis is at
    ``(rho cos beta - e, -rho sin beta)``; on the ellipse when
    ``A rho^2 - 2 B rho + C = 0`` with ``A = cos^2/a^2 + sin^2/b^2``,
    ``B = e cos beta / a^2``, ``C = e^2/a^2 - 1 < 0``: the positive root.
    """
    c, s = np.cos(beta), np.sin(beta)
    A = c * c / (a * a) + s * s / (b * b)
    B = e_signed * c / (a * a)
    C = e_signed * e_signed / (a * a) - 1.0
    return (B + np.sqrt(B * B - A * C)) / A


def _roller_on_ellipse(a, b, r, e_signed, beta, iterations=60):
    """Distance from the shaft axis of the roller centre on the section's parallel curve [m].

    The roller centre is ``r`` out along the section's outward normal from the
    contact point ``(a cos t, b sin t)`` (ellipse axes), i.e. at
    ``(cos t (a + r b/k), sin t (b + r a/k))`` with ``k = sqrt(b^2 cos^2 t + a^2 sin^2 t)``;
    ``t`` puts it on the follower axis (Newton's method, derivative by complex step,
    started where the normal is parallel to the follower axis).
    """
    c, s = np.cos(beta), np.sin(beta)

    def centre(t):
        ct, st = np.cos(t), np.sin(t)
        k = np.sqrt(b * b * ct * ct + a * a * st * st)
        return ct * (a + r * b / k), st * (b + r * a / k)

    def g(t):
        xi, eta = centre(t)
        return (e_signed + xi) * s + eta * c

    t = np.arctan2(-b * s, a * c)
    h = 1e-20
    for _ in range(iterations):
        dg = np.imag(g(t + 1j * h)) / h
        step = g(t) / dg
        t = t - step
        if np.all(np.abs(step) < 1e-15):
            break
    xi, eta = centre(t)
    return (e_signed + xi) * c - eta * s


def section_travels(disc_radius, eccentricity, inclination, follower, roller_radius, beta):
    """Travels ``(z, z')`` of the pistons on the rotors' exact (elliptic) section [m].

    The section in a piston plane of a rotor inclined by ``alpha``
    (:func:`section_semi_axes`): an ellipse of semi-axes ``a = R/cos(alpha)`` along
    the eccentricity and ``b = R`` across, centred ``e`` from the shaft axis, turning
    with the shaft (left: centre ``e u``, right ``-e u``, ``u = (cos beta, sin beta)``
    in a follower's frame). The follower point on the piston axis is
    ``rho(beta)`` from the shaft axis:

    * knife edge: where the axis crosses the ellipse (:func:`_knife_on_ellipse`);
    * roller of radius ``r``: on the ellipse's parallel curve at ``r``;
    * flat face: the ellipse's support function along the axis,
      ``rho = +-e cos beta + sqrt(a^2 cos^2 beta + b^2 sin^2 beta)``.

    The travel is measured from the mid position as in the paper (top ``+e`` at
    ``beta = 0``, bottom ``-e`` at ``pi``): ``z = rho - (a + r)`` (``r = 0`` but for
    a roller). At ``alpha = 0`` this is eq. 1, 3 (knife edge), 7, 8 (flat face) and
    the roller law of :func:`travels`. A flat face no longer keeps the gap
    constant: ``Delta = 2 (sqrt(a^2 cos^2 beta + b^2 sin^2 beta) - a)``, down to
    ``2 R (1 - 1/cos(alpha))`` at 90 deg. Floats (one design) and angles.

    Returns
    -------
    ndarray, shape (2, ...)
        ``(z, z')`` [m], positive towards the reactor centre.
    """
    beta = np.asarray(beta, dtype=float)
    e = float(eccentricity)
    a, b = (float(v) for v in section_semi_axes(disc_radius, inclination))
    r = float(roller_radius) if follower == "roller" else 0.0
    out = []
    for sign in (1.0, -1.0):
        if follower == "flat":
            rho = sign * e * np.cos(beta) + np.hypot(a * np.cos(beta), b * np.sin(beta))
        elif follower == "roller":
            rho = _roller_on_ellipse(a, b, r, sign * e, beta)
        else:
            rho = _knife_on_ellipse(a, b, sign * e, beta)
        out.append(rho - (a + r))
    return np.stack(out)
