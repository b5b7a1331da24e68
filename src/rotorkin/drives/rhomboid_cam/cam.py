"""The rhomboid cam: pitch curve, actual profile, pressure angles and checks for its rollers.

Zhuravlev, Donchenko, Sherstyukov 2012 (``papers/rhomboid_cam.md``) give the
pitch curve ``rho(alpha) = 2l cos(psi(alpha)/2)`` (eq. 3) on which the four
rollers at the vertices A, B, C, D of the rhombus roll
(:mod:`rotorkin.drives.rhomboid_cam.kinematics`); everything else here is derived.

Conventions (ours where the paper is silent):

* The cam is a fixed **disc cam**; the rollers roll on its outside. By eq. 10
  all four roller centres lie on the one pitch curve at every instant, at the
  polar angles ``alpha + k pi/2`` (k = 0..3 for A, B, C, D), so the rhombus
  holds every roller on the cam in both senses (form closure: when A and C
  are pulled off the cam, B and D are pressed on it, and vice versa).
* The actual (cut) profile is the pitch curve offset **inwards** by the roller
  radius ``r``; it has a cusp (undercut) wherever ``r`` reaches the radius of
  curvature of a convex stretch of the pitch curve.
* **Pressure angle** of a roller: the angle between the contact force (along
  the common normal of roller and cam, through the roller centre) and the
  velocity of the roller centre relative to the output shaft, which carries
  the diagonals of the rhombus: relative to the shaft each roller only moves
  along its diagonal, radially. By kinematic inversion this is the classic
  pressure angle of a radial roller follower on a disc cam turning at
  ``-alpha``: ``tan mu = rho'(alpha_k) / rho(alpha_k)`` with the outward normal
  ``rho e_r - rho' e_t``. Signed: positive while the roller moves outwards
  (``rho' > 0``). Of the contact force ``N``, ``N cos mu`` acts along the
  diagonal (on the links) and ``N sin mu`` turns the shaft.

All functions broadcast over ``alpha``; the law ``(psi_min, a, b)`` and the link
length are as in :mod:`rotorkin.drives.rhomboid_cam.kinematics`.
"""

from __future__ import annotations

import numpy as np

from rotorkin.cams import edges, planar
from rotorkin.cams.planar import Curve, Part, ProfileCheck
from rotorkin.core.angles import fmt_deg, fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.core.minimize import bounded_min
from rotorkin.drives.rhomboid_cam import kinematics as rc

__all__ = [
    "ProfileCheck",
    "ROLLERS",
    "actual_profile",
    "cam_part",
    "check_profile",
    "pitch_curve",
    "pitch_radius_of_curvature",
    "pressure_angles",
    "profile_check",
    "radius_of_curvature",
    "roller_alphas",
    "roller_radius_limit",
]

#: Names of the rollers, at the polar angles alpha + k pi/2.
ROLLERS = ("A", "B", "C", "D")

_HALF_PI = 0.5 * np.pi
_GRID = 2048  # samples of the half turn [0, pi) (the cam has period pi)
_CLEAR = 1024  # profile samples of the full turn for the clearance


def roller_alphas(alpha):
    """Polar angles of the rollers A, B, C, D on the pitch curve, ``alpha + k pi/2`` [rad].

    Returns
    -------
    ndarray, shape (4, ...)
    """
    alpha = np.asarray(alpha, dtype=float)
    return alpha[None] + _HALF_PI * np.arange(4).reshape((4,) + (1,) * alpha.ndim)


def pitch_curve(link_length, psi_min, a, b, alpha):
    """Pitch curve point and derivatives ``(p, dp, d2p)``, each shape (2, ...) [m, m/rad^n].

    ``p = rho(alpha) (cos alpha, sin alpha)``, ``rho = 2l cos(psi/2)`` (eq. 3).
    """
    return rc.profile_point(link_length, psi_min, a, b, alpha)


def pitch_radius_of_curvature(link_length, psi_min, a, b, alpha):
    """Signed radius of curvature of the pitch curve [m]: positive convex, negative concave.

    ``1 / kappa`` with ``kappa`` of
    :func:`rotorkin.drives.rhomboid_cam.kinematics.profile_curvature`.
    """
    return radius_of_curvature(rc.profile_curvature(link_length, psi_min, a, b, alpha))


def radius_of_curvature(kappa):
    """``1 / kappa`` [m], infinite where the curvature ``kappa`` is 0 (a straight piece)."""
    k = np.asarray(kappa, dtype=float)
    with np.errstate(divide="ignore"):
        return np.where(k == 0.0, np.inf, 1.0 / np.where(k == 0.0, 1.0, k))


def actual_profile(link_length, psi_min, a, b, roller_radius, alpha):
    """Point of the actual (cut) cam profile touched by the roller centred at ``p(alpha)`` [m].

    ``q = p - r n`` with ``n`` the outward unit normal of the pitch curve
    (:func:`rotorkin.cams.planar.offset_curve` with ``d = -r``).

    Returns
    -------
    ndarray, shape (2, ...)
    """
    p, dp, _ = pitch_curve(link_length, psi_min, a, b, alpha)
    return planar.offset_curve(p, dp, -float(roller_radius))


def pressure_angles(link_length, psi_min, a, b, alpha):
    """Pressure angle of each of the rollers A, B, C, D [rad] (module docstring).

    ``mu_k = arctan(rho'(alpha_k) / rho(alpha_k))`` at ``alpha_k = alpha + k pi/2``:
    the angle between the contact normal and the radial velocity of the roller
    centre relative to the output shaft. Independent of ``link_length`` (kept
    for a uniform signature). All four rollers touch the cam at every instant.

    Parameters
    ----------
    link_length : float
        Side ``2l`` of the rhombus [m].
    psi_min : float
        [rad].
    a, b : sequence of float
        Higher harmonics [rad].
    alpha : array_like
        Output-shaft angle [rad], any shape.

    Returns
    -------
    ndarray, shape ``(4, *alpha.shape)``
        Signed, in ``(-pi/2, pi/2)``; positive while the roller moves outwards.
    """
    r0, r1 = rc.profile_radius(link_length, psi_min, a, b, roller_alphas(alpha))[:2]
    return np.arctan2(r1, r0)


def _refine(fun, grid, i, h):
    """Minimise the scalar ``fun`` near ``grid[i]`` (bracket +-h); returns (x, f)."""
    x, f = bounded_min(fun, grid[i] - h, grid[i] + h, xatol=1e-12)
    x, f = float(x), float(f)
    f0 = float(fun(grid[i]))
    return (x, f) if f <= f0 else (float(grid[i]), f0)


def _wrap(alpha):
    """Angle folded to [0, pi) (the cam and all four rollers repeat after half a turn)."""
    return float(np.mod(alpha, np.pi))


def profile_check(link_length, psi_min, a, b, roller_radius) -> ProfileCheck:
    """Profile checks of the rhomboid cam for a roller radius; never raises.

    * smallest convex (and concave) radius of curvature of the pitch curve and
      where: a roller with ``r >= min_convex_radius`` undercuts the cam;
    * largest pressure angle over the four rollers and the turn
      (:func:`pressure_angles`);
    * the minimum clearance between a roller and the cam away from its own
      contact (:func:`rotorkin.cams.planar.facing_clearance`): all four rollers
      share the cam; a negative value means a roller cuts into another flank;
    * the smallest distance of the actual profile from the centre.

    Extremes are found on a grid of 2048 points per half turn and refined by a
    bounded scalar minimisation (to ~1e-12 rad); the clearance on 1024
    profile samples per turn. Angles are reported in ``[0, pi)`` (the cam has
    period pi). Invalid inputs give ``nan`` fields and ``undercut = True``.

    Parameters
    ----------
    link_length : float
        [m].
    psi_min : float
        [rad].
    a, b : sequence of float
        [rad].
    roller_radius : float
        [m], >= 0.

    Returns
    -------
    ProfileCheck
        ``extra`` holds ``roller_gap`` (between neighbouring rollers, ``2l - 2r``
        [m]), ``pitch_radius_min``, ``pitch_radius_max`` [m],
        ``undercut_intervals`` (ndarray (k, 2) of alpha [rad] in [0, pi)).
    """
    nan = float("nan")
    failed = ProfileCheck(float(roller_radius), nan, nan, nan, nan, nan, True, nan, nan, nan)
    try:
        with np.errstate(all="ignore"):
            L, r = float(link_length), float(roller_radius)
            rho = rc.profile_radius(L, psi_min, a, b, np.pi * np.arange(_GRID) / _GRID)[0]
            if not (L > 0.0 and r >= 0.0 and np.all(rho > 0.0)):  # not a cam (psi out of (0, pi))
                return failed
            return _profile_check(L, float(psi_min), a, b, r)
    except (ValueError, ArithmeticError, TypeError):
        return failed


def _clearance(L, law, r):
    """The checks that depend on the roller radius: ``(min_clearance, its alpha, profile_min)``.

    ``min_clearance`` [m] of :func:`rotorkin.cams.planar.facing_clearance` on 1024
    profile samples per turn, its roller's angle in ``[0, pi)`` (nan when ``inf``) and
    the smallest distance of the actual profile from the centre [m] (2048 samples per
    half turn).
    """
    q = actual_profile(L, *law, r, np.pi * np.arange(_GRID) / _GRID)
    s = 2.0 * np.pi * np.arange(_CLEAR) / _CLEAR
    p, dp, _ = pitch_curve(L, *law, s)
    prof = planar.offset_curve(p, dp, -r)
    half = _CLEAR // 2  # roller centres over half a turn cover every position (symmetry)
    gap, _ = planar.facing_clearance(
        p[:, :half], prof, planar.outward_normal(dp), r, np.arange(half)
    )
    ic = int(np.argmin(gap))
    clearance = float(gap[ic])
    alpha = _wrap(s[ic]) if np.isfinite(clearance) else float("nan")
    return clearance, alpha, float(np.min(np.hypot(q[0], q[1])))


def _profile_check(L, psi_min, a, b, r) -> ProfileCheck:
    law = (psi_min, a, b)
    h = np.pi / _GRID
    g = h * np.arange(_GRID)

    def kappa(x):
        return rc.profile_curvature(L, *law, x)

    k = kappa(g)
    i = int(np.argmax(k))
    x_cv, f_cv = _refine(lambda x: -kappa(x), g, i, h)
    min_convex = 1.0 / -f_cv if -f_cv > 0.0 else float("inf")
    j = int(np.argmin(k))
    _, f_cc = _refine(kappa, g, j, h)
    min_concave = -1.0 / f_cc if f_cc < 0.0 else float("inf")

    def mu(x):
        return pressure_angles(L, *law, x)[0]

    m = mu(g)
    im = int(np.argmax(np.abs(m)))
    x_mu, f_mu = _refine(lambda x: -np.abs(mu(x)), g, im, h)

    rho = rc.profile_radius(L, *law, g)[0]
    clearance, clearance_alpha, profile_min = _clearance(L, law, r)
    undercut = bool(r >= min_convex) or not np.isfinite(min_convex)
    return ProfileCheck(
        roller_radius=r,
        min_convex_radius=float(min_convex),
        min_convex_radius_alpha=_wrap(x_cv),
        min_concave_radius=float(min_concave),
        max_pressure_angle=float(-f_mu),
        max_pressure_angle_alpha=_wrap(x_mu),
        undercut=undercut,
        min_clearance=clearance,
        min_clearance_alpha=clearance_alpha,
        profile_min_radius=profile_min,
        extra={
            "roller_gap": L - 2.0 * r,
            "pitch_radius_min": float(np.min(rho)),
            "pitch_radius_max": float(np.max(rho)),
            "undercut_intervals": planar.undercut_intervals(g, k, -r),
        },
    )


def _mm_below(x) -> str:
    """A length limit [m] in mm rounded *down* to 4 significant digits: ``'41.04 mm'``.

    A roller radius below the stated value is then below the limit itself.
    """
    v = float(x) * 1e3
    if not (np.isfinite(v) and v > 0.0):
        return fmt_mm(x)
    unit = 10.0 ** (np.floor(np.log10(v)) - 3)
    return f"{np.floor(v / unit) * unit:.4g} mm"


def roller_radius_limit(link_length, psi_min, a=(), b=(), rtol=1e-7):
    """Largest roller radius that :func:`check_profile` admits, and the check that sets it.

    Every roller radius ``0 <= r < limit`` passes :func:`check_profile`. The limit is
    the smallest of: the smallest convex radius of curvature of the pitch curve
    (undercut), half the side ``2l`` (neighbouring rollers), and the smallest roller
    radius at which the clearance to another flank turns negative or the actual
    profile reaches the cam centre. The last is found by a scan of 16 radii below the
    other two limits, then bisection of the first failing interval to ``rtol`` of the
    limit (the same clearance function as :func:`profile_check`, so a roller just below
    the limit passes the check and one just above fails it).

    Parameters
    ----------
    link_length : float
        Side ``2l`` of the rhombus [m].
    psi_min : float
        [rad].
    a, b : sequence of float
        Higher harmonics [rad].
    rtol : float, optional
        Relative width of the final bisection interval.

    Returns
    -------
    (limit, reason) : float, str
        The limit [m] and what sets it: ``"undercut"``, ``"rollers"`` (neighbouring
        rollers touch), ``"clearance"`` (a roller reaches another flank, e.g. across the
        cam's waist) or ``"centre"``; ``(nan, "cam")`` when the law is not a cam.
    """
    L = float(link_length)
    chk0 = profile_check(L, psi_min, a, b, 0.0)
    if not chk0.ok:
        return float("nan"), "cam"
    law = (float(psi_min), a, b)
    limit, reason = float(chk0.min_convex_radius), "undercut"
    if 0.5 * L < limit:
        limit, reason = 0.5 * L, "rollers"

    def fails(r) -> str:
        clearance, _, profile_min = _clearance(L, law, r)
        if clearance < 0.0:
            return "clearance"
        return "" if profile_min > 0.0 else "centre"

    lo, hi = 0.0, None
    for r in limit * np.append(np.arange(1, 16) / 16.0, 1.0 - rtol):
        if fails(r):
            hi = r
            break
        lo = r
    if hi is None:
        return limit, reason
    while hi - lo > rtol * limit:
        mid = 0.5 * (lo + hi)
        if fails(mid):
            hi = mid
        else:
            lo = mid
    return float(lo), fails(hi)


_LIMIT_REASONS = {
    "undercut": "the smallest convex radius of curvature of the pitch curve; a larger roller "
    "undercuts the cam",
    "rollers": "half the side 2l of the rhombus; neighbouring rollers overlap above it",
    "clearance": "the largest roller that clears every other flank of the cam; a larger one "
    "reaches across the cam's waist",
    "centre": "the largest roller whose actual profile stays clear of the cam centre",
}


def check_profile(link_length, psi_min, a, b, roller_radius, name="roller_radius"):
    """Raise :class:`ParameterError` named ``name`` unless the roller fits the cam.

    Errors: ``r < 0``; a roller that fails any of: ``r <`` the smallest convex radius
    of curvature (else it undercuts the cam), a clearance ``>= 0`` to every other
    flank, neighbouring rollers apart (``2r < 2l``), the actual profile clear of the
    cam centre. The message states the admissible range ``roller_radius < limit``
    (:func:`roller_radius_limit`, rounded down to 4 digits) and what this roller
    does wrong: for an undercut, the angle alpha of the smallest radius and the
    stretch of alpha where the profile has a cusp; for an overlap, the roller's angle
    and by how much.

    Returns
    -------
    ProfileCheck
        The checks, when they pass.
    """
    r = float(roller_radius)
    if not (np.isfinite(r) and r >= 0.0):
        raise ParameterError(name, fmt_mm(r), "roller_radius >= 0 mm")
    chk = profile_check(link_length, psi_min, a, b, r)
    clash = chk.min_clearance < 0.0
    rollers = not chk.extra.get("roller_gap", 0.0) > 0.0
    centre = not chk.profile_min_radius > 0.0
    if not (chk.undercut or clash or rollers or centre):
        return chk
    limit, reason = roller_radius_limit(link_length, psi_min, a, b)
    if reason == "cam":  # pragma: no cover - the drive rejects such laws first
        raise ParameterError(name, fmt_mm(r), "a law whose pitch curve is a cam (rho > 0)")
    head = f"roller_radius < {_mm_below(limit)} ({_LIMIT_REASONS[reason]})"
    if chk.undercut:
        spans = chk.extra.get("undercut_intervals", np.empty((0, 2)))
        where = ", ".join(f"{fmt_deg(lo)} .. {fmt_deg(hi)}" for lo, hi in spans)
        detail = (
            f"this roller undercuts the cam: the pitch curve's smallest convex radius of "
            f"curvature is {fmt_mm(chk.min_convex_radius)} at alpha = "
            f"{fmt_deg(chk.min_convex_radius_alpha)} (and alpha + 180 deg); cusp in the actual "
            f"profile for alpha in {where or 'a point'}"
        )
    elif clash:
        detail = (
            f"the roller at alpha = {fmt_deg(chk.min_clearance_alpha)} overlaps another flank "
            f"of the cam by {fmt_mm(-chk.min_clearance)}"
        )
    elif rollers:
        detail = f"neighbouring rollers overlap (2 roller_radius >= 2l = {fmt_mm(link_length)})"
    else:
        detail = "the actual profile reaches the cam centre"
    raise ParameterError(name, fmt_mm(r), f"{head}; {detail}")


def cam_part(params: rc.RhomboidCam, roller_radius, thickness, tolerance, gap=0.0) -> Part:
    """The cam plate as a :class:`~rotorkin.cams.planar.Part` for the CAD writers.

    Curves (drawn at ``alpha = 0``): ``profile`` (the outline to cut, layer PROFILE: the
    pitch curve offset inwards by ``roller_radius + gap``, as clamped cubic B-spline
    pieces within ``tolerance`` of that offset, :func:`rotorkin.cams.edges.fit_closed`),
    ``pitch`` (PITCH), ``roller_A`` ... ``roller_D`` (ROLLER, exact circles) and
    ``rhombus`` (LINKAGE, the roller centres ABCD). Polygons follow their curves within
    ``tolerance`` (chordal). The check is not made here (see :func:`check_profile`).

    Parameters
    ----------
    params : RhomboidCam
    roller_radius, thickness, tolerance : float
        [m].
    gap : float
        Running gap between each roller and the cam [m] (the rhombus holds the four
        rollers on the cam by form closure, so they need one).
    """
    L, law = params.link_length, (params.psi_min, params.a, params.b)
    r = float(roller_radius)

    def pitch(t):
        return pitch_curve(L, *law, t)[0]

    def profile(t):
        return actual_profile(L, *law, r + float(gap), t)

    two_pi = 2.0 * np.pi
    t_prof = planar.resample_closed(profile, 0.0, two_pi, tolerance)
    t_pitch = planar.resample_closed(pitch, 0.0, two_pi, tolerance)
    pieces = edges.fit_closed(profile, two_pi, tolerance)[0]
    outline = Curve("profile", "PROFILE", profile(t_prof).T.copy(), True, None, pieces)
    curves = [outline, Curve("pitch", "PITCH", pitch(t_pitch).T.copy())]
    v = rc.rhombus_vertices(L, *law, 0.0)
    if r > 0.0:
        curves += [
            planar.circle_curve(f"roller_{n}", "ROLLER", v[k], r, tolerance)
            for k, n in enumerate(ROLLERS)
        ]
    curves.append(Curve("rhombus", "LINKAGE", np.asarray(v, dtype=float).reshape(4, 2)))
    return Part(
        name="rhomboid_cam",
        outline=outline,
        thickness=float(thickness),
        curves=tuple(curves),
        title=f"rhomboid cam, roller radius {fmt_mm(r)}, drawn at alpha = 0",
        notes=(
            f"profile: the pitch curve offset inwards by roller radius {fmt_mm(r)} + running "
            f"gap {fmt_mm(gap)}",
        ),
        gaps=(("roller on cam", float(gap)),),
    )
