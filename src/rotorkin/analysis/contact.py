"""Hertz contact of a roller on a cam, a groove or a gear flank: sizes, pressures, stresses.

Two elastic bodies touching at a point or along a line, frictionless, small
strains, the contact small against the radii (K. L. Johnson, *Contact
Mechanics*, CUP 1985, ch. 4; Roark's *Formulas for Stress and Strain*, the
table of bodies in contact). The materials enter through the effective modulus

    1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2

and the geometry through the effective radius ``1 / R = 1 / r1 + 1 / r2`` of
the signed radii of curvature: positive for a convex surface, negative for a
concave one (a groove's far flank, an internal gear), ``np.inf`` for a flat.

Line contact (two parallel cylinders: a roller on a cam track), force ``P`` on
a length ``L`` (Johnson eqs. 4.43 ff)::

    b = sqrt(4 P R / (pi L E*)),   p_max = 2 P / (pi b L)

with the largest principal shear below the surface, on the plane of symmetry,
``tau_max = p_max / phi^(5/2) = 0.3003 p_max`` at the depth
``z = b / sqrt(phi) = 0.7862 b`` (``phi`` the golden ratio: the maximum of
``tau / p_max = s - s^2 / sqrt(1 + s^2)``, ``s = z / b``, lies at ``s^2 = 1 / phi``).

Point contact (a crowned roller, a ball): principal radii in aligned planes,
``1 / Rx = 1 / rx1 + 1 / rx2`` and ``1 / Ry = 1 / ry1 + 1 / ry2``, the gap
``x^2 / (2 Rx) + y^2 / (2 Ry)``. The contact is an ellipse with the pressure
``p_max sqrt(1 - x^2 / a^2 - y^2 / b^2)``; with ``q`` the ratio of the minor to
the major semi-axis, the modulus ``m = 1 - q^2`` and the complete elliptic
integrals ``K(m)``, ``E(m)``, the two compatibility conditions (Johnson sec.
4.2) give

    R_major / R_minor = (E / q^2 - K) / (K - E)
    major^3 = 3 P R_major (K - E) / (pi E* m),   p_max = 3 P / (2 pi a b)

and the approach of distant points ``delta = p_max q major K / E*``, where
``R_major = max(Rx, Ry)`` lies along the major axis. The combinations ``K - E``
and ``E / q^2 - K`` are evaluated without cancellation through Carlson's
symmetric integrals (DLMF 19.25.1)::

    K - E = (m / 3) R_D(0, q^2, 1),   E / q^2 - K = (m / 3) R_D(0, 1, q^2),   K = R_F(0, q^2, 1)

so the ratio of the radii is ``R_D(0, 1, q^2) / R_D(0, q^2, 1)``, decreasing
in ``q``, solved for ``q`` by bisection on ``log q``, vectorised. Equal radii
(a sphere) give ``q = 1`` and the circle ``a = (3 P R / (4 E*))^(1/3)``,
``p_max = 3 P / (2 pi a^2)``.

Geometry without a Hertz contact is marked NaN, never an error (a cam's
curvature runs over all values along its profile): a curvature sum ``<= 0``
(a concave body as tight as or tighter than the convex one: conformal, or no
point of contact), a radius of zero (an edge), two flats (no length scale; the
effective radius is ``inf`` there but the contact results are NaN), and in a
point contact a direction flat on both bodies (that is a line contact). A
negative force is a programming error (the caller passes the magnitude of the
compressive force; a contact does not carry tension) and raises ``ValueError``,
as does a roller length ``<= 0``. Zero force gives a zero contact and zero
pressure.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from rotorkin.core.errors import ParameterError

__all__ = [
    "Material",
    "STEEL",
    "LineContact",
    "PointContact",
    "effective_modulus",
    "effective_radius",
    "line_contact",
    "point_contact",
    "safety_factor",
]

_PHI = (1.0 + math.sqrt(5.0)) / 2.0
#: Largest subsurface principal shear of a line contact, per unit peak pressure.
TAU_RATIO = _PHI**-2.5
#: Its depth below the surface, per unit half-width.
TAU_DEPTH_RATIO = _PHI**-0.5


@dataclass(frozen=True)
class Material:
    """An isotropic elastic material: Young's modulus [Pa] and Poisson's ratio [-].

    Each may be a float or, for many designs at once, a NumPy array (the two broadcast)."""

    youngs_modulus: float
    poisson_ratio: float

    def __post_init__(self):
        e = _scalar(self.youngs_modulus)
        if e is None or not np.all(np.isfinite(e) & (e > 0.0)):
            raise ParameterError(
                "contact.youngs_modulus", _text(self.youngs_modulus), "a finite value > 0 Pa"
            )
        nu = _scalar(self.poisson_ratio)
        if nu is None or not np.all((nu >= 0.0) & (nu < 0.5)):
            raise ParameterError(
                "contact.poisson_ratio", _text(self.poisson_ratio), "0 <= poisson_ratio < 0.5"
            )


def _scalar(value):
    """``value`` as a float, or a float array for a NumPy array of many designs; None if
    it is no number."""
    if isinstance(value, (bool, str, bytes)):
        return None
    if isinstance(value, np.ndarray) and value.ndim > 0 and value.dtype.kind in "iuf":
        return value.astype(float)
    try:
        return float(value)
    except (TypeError, ValueError):
        return None


def _text(value) -> str:
    text = repr(value) if isinstance(value, str) else str(value)
    text = " ".join(text.split())
    return text if len(text) <= 60 else text[:57] + "..."


#: Structural steel: E = 210 GPa, nu = 0.3.
STEEL = Material(210e9, 0.3)


class LineContact(NamedTuple):
    """Result of :func:`line_contact`, arrays of the broadcast shape.

    ``b`` the half-width of the contact strip [m], ``p_max`` the peak pressure
    [Pa], ``tau_max`` the largest principal shear stress below the surface
    [Pa], ``depth`` its depth below the surface [m].
    """

    b: np.ndarray
    p_max: np.ndarray
    tau_max: np.ndarray
    depth: np.ndarray


class PointContact(NamedTuple):
    """Result of :func:`point_contact`, arrays of the broadcast shape.

    ``a`` the semi-axis of the contact ellipse along x (the plane of the
    radii ``rx``) [m], ``b`` the semi-axis along y [m], ``p_max`` the peak
    pressure [Pa], ``approach`` the approach of distant points of the two
    bodies [m].
    """

    a: np.ndarray
    b: np.ndarray
    p_max: np.ndarray
    approach: np.ndarray


def effective_modulus(m1: Material, m2: Material) -> float:
    """E* [Pa] of two materials: ``1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2``."""
    c1 = (1.0 - m1.poisson_ratio**2) / m1.youngs_modulus
    c2 = (1.0 - m2.poisson_ratio**2) / m2.youngs_modulus
    return 1.0 / (c1 + c2)


def effective_radius(r1, r2):
    """Effective radius of two signed radii of curvature, ``1 / R = 1 / r1 + 1 / r2``.

    Radii are positive on a convex surface, negative on a concave one and
    ``np.inf`` on a flat (either sign). Two flats give ``inf``. Where the sum
    of the curvatures is ``<= 0`` otherwise (a concave body as tight as or
    tighter than the convex one: conformal, or no point or line of contact),
    where a radius is zero (an edge) or NaN, the result is NaN.
    """
    r1 = np.asarray(r1, dtype=float)
    r2 = np.asarray(r2, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # 1/denormal: a point
        curvature = 1.0 / r1 + 1.0 / r2
        radius = 1.0 / curvature
    both_flat = np.isinf(r1) & np.isinf(r2)
    bad = ~(curvature > 0.0) | (r1 == 0.0) | (r2 == 0.0)
    out = np.where(both_flat, np.inf, np.where(bad, np.nan, radius))
    return out[()]


def _hertz_radius(r1, r2):
    """The effective radius where it makes a Hertz contact, NaN elsewhere (two flats too)."""
    radius = effective_radius(r1, r2)
    return np.where(np.isfinite(radius), radius, np.nan)


def _check_force(force):
    force = np.asarray(force, dtype=float)
    if np.any(force < 0.0):
        raise ValueError(
            "contact force must be the magnitude of a compression (>= 0); "
            f"got a minimum of {np.nanmin(force)} N"
        )
    return force


def line_contact(force, length, r1, r2, m1: Material = STEEL, m2: Material = STEEL) -> LineContact:
    """Hertz contact of two parallel cylinders pressed by ``force`` [N] over ``length`` [m].

    ``r1``, ``r2`` are the signed radii of curvature across the line of contact
    (a roller on a cam: roller radius and the cam's radius of curvature at the
    contact, negative where the cam is concave; ``np.inf`` for a plane). All
    arguments broadcast. Results are NaN where the geometry is no Hertz
    contact (see :func:`effective_radius`; two flats too). Raises
    ``ValueError`` for a negative force or a length ``<= 0``.
    """
    force = _check_force(force)
    length = np.asarray(length, dtype=float)
    if np.any(length <= 0.0):
        raise ValueError(f"contact length must be > 0 m; got a minimum of {np.nanmin(length)} m")
    e_star = effective_modulus(m1, m2)
    radius = _hertz_radius(r1, r2)
    load = force / length
    b = np.sqrt(4.0 * load * radius / (math.pi * e_star))
    with np.errstate(divide="ignore", invalid="ignore"):
        p_max = np.where(load == 0.0, 0.0 * radius, 2.0 * load / (math.pi * b))
    b, p_max = np.broadcast_arrays(b, p_max)
    return LineContact(b[()], p_max[()], (TAU_RATIO * p_max)[()], (TAU_DEPTH_RATIO * b)[()])


def _minor_ratio(ratio, iterations: int = 64):
    """The ratio q <= 1 of minor to major semi-axis for ``ratio = R_major / R_minor >= 1``.

    Bisection on ``log q`` in ``[log(0.5 / ratio), 0]``, where the ratio of
    the radii (decreasing in q) brackets: at ``q = 0.5 / ratio`` it exceeds
    ``ratio`` (for small q it grows like ``1 / (q^2 (ln(4 / q) - 1))``).
    NaN ratios give NaN.
    """
    from scipy.special import elliprd  # 0.1 s to import: only point contacts need it

    ratio = np.asarray(ratio, dtype=float)
    good = np.isfinite(ratio) & (ratio >= 1.0)
    target = np.where(good, ratio, 1.0)
    lo = np.log(0.5 / target)
    hi = np.zeros_like(target)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        q2 = np.exp(2.0 * mid)
        value = elliprd(0.0, 1.0, q2) / elliprd(0.0, q2, 1.0)
        above = value > target  # q too small
        lo = np.where(above, mid, lo)
        hi = np.where(above, hi, mid)
    q = np.exp(0.5 * (lo + hi))
    q = np.where(target == 1.0, 1.0, q)
    return np.where(good, q, np.nan)


def point_contact(
    force, rx1, ry1, rx2, ry2, m1: Material = STEEL, m2: Material = STEEL
) -> PointContact:
    """Hertz contact of two bodies with principal radii in aligned planes, pressed by ``force`` [N].

    ``rx1``, ``rx2`` are the signed radii of curvature of the two bodies in the
    x-z plane, ``ry1``, ``ry2`` in the y-z plane (a crowned roller on a cam:
    ``rx1`` the roller radius, ``ry1`` the crown radius, ``rx2`` the cam's
    radius of curvature, ``ry2 = np.inf``; a ball: ``rx1 = ry1``). All
    arguments broadcast. The semi-axis ``a`` lies along x, ``b`` along y.
    Results are NaN where either direction has no Hertz contact (see
    :func:`effective_radius`; a direction flat on both bodies is a line
    contact, :func:`line_contact`). Raises ``ValueError`` for a negative force.
    """
    from scipy.special import elliprd, elliprf  # 0.1 s to import: here, not at import

    force = _check_force(force)
    e_star = effective_modulus(m1, m2)
    rx = _hertz_radius(rx1, rx2)
    ry = _hertz_radius(ry1, ry2)
    force, rx, ry = np.broadcast_arrays(force, rx, ry)
    r_major = np.maximum(rx, ry)
    q = _minor_ratio(r_major / np.minimum(rx, ry))
    q2 = q * q
    # major^3 = 3 P R_major (K - E) / (pi E* m), K - E = (m / 3) R_D(0, q^2, 1)
    major = np.cbrt(force * r_major * elliprd(0.0, q2, 1.0) / (math.pi * e_star))
    minor = q * major
    with np.errstate(divide="ignore", invalid="ignore"):
        p_max = np.where(force == 0.0, 0.0 * major, 1.5 * force / (math.pi * major * minor))
    approach = p_max * minor * elliprf(0.0, q2, 1.0) / e_star
    along_x = rx >= ry
    a = np.where(along_x, major, minor)
    b = np.where(along_x, minor, major)
    # NaN geometry: np.maximum / >= already carry the NaN into major and q
    return PointContact(a[()], b[()], p_max[()], approach[()])


def safety_factor(p_max, allowable):
    """``allowable / p_max``; ``inf`` where ``p_max == 0`` (no load), NaN where ``p_max`` is NaN."""
    p_max = np.asarray(p_max, dtype=float)
    allowable = np.asarray(allowable, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(p_max == 0.0, np.inf, allowable / p_max)
    return out[()]
