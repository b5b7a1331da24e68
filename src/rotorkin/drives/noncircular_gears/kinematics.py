"""Kinematics of the non-circular gear drive of two coaxial rotors.

Reference for the pitch curves: F. L. Litvin, A. Fuentes-Aznar, I. Gonzalez-Perez,
K. Hayasaka, *Noncircular Gears: Design and Generation*, Cambridge University Press,
2009 (elliptical gears rotating about a focus, n-lobed "modified ellipses"). Everything
below that goes beyond the pitch curve itself (closure root, continuous closed forms,
their inverse, convexity of the driven curve, extremes of the relative angle) is derived
here and stated with its derivation.

The drive
---------
An output shaft (angle ``theta``) is parallel to the rotors' common axis at the centre
distance ``a``. It carries two identical driving gears; each meshes externally with a
driven gear fixed to one rotor. Driving gear 2 sits on the shaft turned by the phase
``sigma`` relative to driving gear 1 (default ``pi/n``).

* Driving pitch curve, polar about its rotation centre:
  ``r1(phi) = p / (1 - e cos(n phi))``, ``n = lobes``, ``0 <= e < 1``.
* Driven gear (``m = rotor_lobes``): rolling without slip with the contact point on the
  line of centres gives ``r2 = a - r1`` and
  ``dphi2/dphi1 = r1/(a - r1) = p/(B - C cos(n phi1))``, ``B = a - p``, ``C = a e``.
* Closure: one driving lobe (``2 pi/n``) turns the driven gear by ``2 pi/m`` iff
  ``p/sqrt(B^2 - C^2) = k``, ``k = n/m``. Squared, ``(1 - k^2) p^2 + 2 k^2 a p -
  k^2 a^2 (1 - e^2) = 0``, whose root with ``p > 0`` and ``B > C`` (a positive driven
  radius, ``p < a (1 - e)``) is, written without cancellation,

      ``p = a k (1 - e^2) / (k + sqrt(1 - e^2 (1 - k^2)))``

  (``p = a (1 - e^2)/2`` for ``n = m``). It exists for every ``0 <= e < 1``: ``B > C``
  reduces to ``e^2 < 1``; the other root has ``p < 0`` or ``B < 0``.

Continuous closed form of the driven angle
------------------------------------------
With ``t = n phi1``, ``S = sqrt(B^2 - C^2)``:

    ``phi2 = (t + 2 atan(C sin t / (B + S - C cos t))) / m``

Proof: ``tan(x - y)`` with ``x = atan(L tan(t/2))``, ``y = t/2``,
``L = sqrt((B + C)/(B - C))``, simplifies to ``C sin t/(B + S - C cos t)``; on
``(-pi, pi)`` both ``x`` and ``y`` lie in ``(-pi/2, pi/2)`` with the same sign, so the
difference is the principal arctangent, and ``2 x / S`` is the textbook antiderivative
of ``1/(B - C cos t)``. The right-hand side is smooth for every ``t`` (its denominator
is at least ``B + S - C > 0``), has the right derivative everywhere and vanishes at
``t = 0``, hence equals ``(p/n) int_0^t dv/(B - C cos v)`` on the whole real line: no
branch jumps and no unwrapping. ``p/(n S) = 1/m`` by closure.

Inverse (driven gear angle to driving gear angle): ``u = m phi2 = 2 atan(L tan(t/2))``
on the principal branch, so ``tan(t/2) = tan(u/2)/L``, i.e. the same form with ``C``
negated:

    ``n phi1 = u - 2 atan(C sin u / (B + S + C cos u))``

Convexity (external gears need convex pitch curves)
---------------------------------------------------
A polar curve ``r = 1/w(angle)`` is convex iff ``w + w'' >= 0``; its curvature is
``w^3 (w + w'') / (w^2 + w'^2)^(3/2)``.

* Driving: ``w + w'' = (1 + e (n^2 - 1) cos t)/p``: convex iff ``e (n^2 - 1) <= 1``.
* Driven (``w`` as a function of ``phi2``, with ``D = B - C cos t``):
  ``w = (1 + p/D)/a``, ``w' = -n C sin t/(a D)``, and
  ``w + w'' = G/(a p D)`` with ``G = p (p + D) - n^2 C (B cos t - C)``. ``G`` is
  smallest at ``t = 0`` (the driven gear's narrowest radius), where ``G >= 0``
  reduces, after substituting ``p`` and squaring, to ``(A e^2 - 1)(e^2 - 1) >= 0``,
  ``A = n^2 (m^2 - 2) + 1``: the driven pitch curve is convex iff

      ``e^2 (n^2 (m^2 - 2) + 1) <= 1``.

  A one-lobed driven gear is always convex; for ``n = m`` both conditions coincide (the
  two gears are congruent); for ``m > n`` the driven curve is the binding one.

Members
-------
The rotors turn opposite to the shaft (external meshes). Their angles are measured
positive in the rotors' own sense of rotation, so ``q`` increases with ``theta``, and from
their positions at ``theta = 0``: ``q1 = phi2(theta)``, ``q2 = phi2(theta + sigma) -
phi2(sigma)``. The speed ratios and the relative angle ``q2 - q1`` have the period
``2 pi/n``; per shaft turn each rotor turns ``n/m`` turns.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.core.angles import fmt_deg
from rotorkin.core.errors import ParameterError
from rotorkin.core.motion import Motion
from rotorkin.drives.noncircular_gears.kinematics_fused import motion_fused

__all__ = [
    "CHECKS",
    "CHECK_REASONS",
    "WHICH",
    "MAX_LOBES",
    "CENTRE_DISTANCE_RANGE",
    "NoncircularGears",
    "violation",
    "raise_violation",
    "eccentricity_limit",
    "pitch_parameter",
    "ratio",
    "ratio_extremes",
    "driven_angle",
    "driving_angle",
    "motion",
    "period",
    "pitch_radius",
    "pitch_curve",
    "curvature",
    "concave_intervals",
    "equal_speed_angles",
    "relative_angle_extremes",
]

#: Most lobes a pitch curve may have.
MAX_LOBES = 12

#: Admissible centre distance [m], bounds included.
CENTRE_DISTANCE_RANGE = (0.001, 10.0)

#: Field checked by each admissibility rule, in the order the rules are checked
#: (:func:`violation` returns ``1 + index``).
CHECKS = (
    "lobes",
    "rotor_lobes",
    "eccentricity",
    "centre_distance",
    "phase",
    "eccentricity",
    "eccentricity",
    "eccentricity",
)

#: What each rule of :data:`CHECKS` asks for.
CHECK_REASONS = (
    "integer 1..12",
    "integer 1..12",
    "0 <= e < 1",
    "0.001 m <= a <= 10 m",
    "finite",
    "closure root with p > 0 and a positive driven radius",
    "convex driving pitch curve",
    "convex driven pitch curve",
)

#: The two pitch curves.
WHICH = ("driving", "driven")

#: Relative slack of the convexity rules (a curve whose curvature just touches 0 is convex).
_CONVEX_SLACK = 1e-12


@dataclass(frozen=True)
class NoncircularGears:
    """Parameters of the drive; every field a number or an array (one value per design).

    Arrays broadcast against each other and against the angles given to the functions
    of this module (e.g. parameters of shape (k, 1) against angles of shape (j,)).

    Parameters
    ----------
    lobes : int or ndarray
        ``n``, lobes of the driving pitch curve, integer 1..12.
    rotor_lobes : int or ndarray
        ``m``, lobes of the driven pitch curve (on the rotor), integer 1..12.
    eccentricity : float or ndarray
        ``e`` of ``r1 = p/(1 - e cos(n phi))``, ``0 <= e < 1``, and small enough for
        both pitch curves to be convex (:func:`eccentricity_limit`).
    centre_distance : float or ndarray
        ``a`` [m], shaft axis to rotor axis, 0.001 m to 10 m.
    phase : float, ndarray or None
        ``sigma`` [rad], angle by which driving gear 2 is turned on the shaft relative
        to driving gear 1, finite; None: ``pi/lobes`` (speed ratios in antiphase).

    Raises
    ------
    ParameterError
        ``drive.<field>``, its value and what is admissible (:func:`violation`), for
        the first inadmissible design.
    """

    lobes: int = 2
    rotor_lobes: int = 2
    eccentricity: float = 0.1
    centre_distance: float = 0.12
    phase: float | None = None

    def __post_init__(self):
        values = (self.lobes, self.rotor_lobes, self.eccentricity, self.centre_distance,
                  self.phase)  # fmt: skip
        raise_violation(values, violation(*values))

    @classmethod
    def unchecked(cls, **fields) -> NoncircularGears:
        """A design built without :func:`violation`, to inspect an inadmissible one.

        E.g. ``concave_intervals(NoncircularGears.unchecked(lobes=4, eccentricity=0.2),
        "driving")``. The functions of this module assume ``0 <= e < 1`` and integer lobes.
        """
        obj = object.__new__(cls)
        for f in ("lobes", "rotor_lobes", "eccentricity", "centre_distance", "phase"):
            object.__setattr__(obj, f, fields.pop(f, cls.__dataclass_fields__[f].default))
        if fields:
            raise TypeError(f"unknown fields: {', '.join(sorted(fields))}")
        return obj


# --------------------------------------------------------------------------------------------
# admissibility
# --------------------------------------------------------------------------------------------
def _floats(field: str, value) -> np.ndarray:
    """``value`` as a float array; a value that is no number is refused as ``drive.<field>``."""
    try:
        arr = np.asarray(value)
        if arr.dtype == bool or arr.dtype.kind not in "biuf":
            raise TypeError
        return arr.astype(float)
    except (TypeError, ValueError):
        raise ParameterError(f"drive.{field}", repr(value), "a number") from None


def _phase_or_default(phase, n):
    """``phase`` as floats, ``pi/n`` where it is None."""
    if phase is None:
        return np.pi / n
    return _floats("phase", phase)


def _pitch_ratio(n, m, e):
    """``p/a = k (1 - e^2)/(k + sqrt(1 - e^2 (1 - k^2)))``, ``k = n/m`` (the closure root)."""
    k = n / m
    return k * (1.0 - e * e) / (k + np.sqrt(1.0 - e * e * (1.0 - k * k)))


def _convexity_margins(n, m, e):
    """``1 - e (n^2 - 1)`` (driving) and ``1 - e^2 max(n^2 (m^2 - 2) + 1, 0)`` (driven).

    Each pitch curve is convex where its margin is at least ``-_CONVEX_SLACK``.
    """
    drive = 1.0 - e * (n * n - 1.0)
    driven = 1.0 - e * e * np.maximum(n * n * (m * m - 2.0) + 1.0, 0.0)
    return drive, driven


def eccentricity_limit(lobes, rotor_lobes):
    """Largest eccentricity at which both pitch curves are convex.

    ``min(1/(n^2 - 1), 1/sqrt(n^2 (m^2 - 2) + 1))``, each term present only where its
    denominator is positive; 1 where neither is (``n = m = 1``, any ``e < 1`` will do).

    Parameters
    ----------
    lobes, rotor_lobes : array_like
        ``n``, ``m``; broadcast.

    Returns
    -------
    ndarray
        ``e_max`` [-] (admissible: ``0 <= e <= e_max``, and ``e < 1``).
    """
    n = np.asarray(lobes, dtype=float)
    m = np.asarray(rotor_lobes, dtype=float)
    d1 = n * n - 1.0
    d2 = n * n * (m * m - 2.0) + 1.0
    with np.errstate(divide="ignore", invalid="ignore"):
        e1 = np.where(d1 > 0.0, 1.0 / np.where(d1 > 0.0, d1, 1.0), 1.0)
        e2 = np.where(d2 > 1.0, 1.0 / np.sqrt(np.where(d2 > 1.0, d2, 1.0)), 1.0)
    return np.minimum(e1, e2)


def violation(lobes, rotor_lobes, eccentricity, centre_distance, phase=None):
    """Which admissibility rule each design violates first: index into :data:`CHECKS` + 1.

    Rules, in order: ``lobes`` and ``rotor_lobes`` integers 1..12; ``0 <= eccentricity
    < 1``; ``0.001 m <= centre_distance <= 10 m``; ``phase`` finite (None stands for
    ``pi/lobes``); the closure root ``p`` exists with ``p > 0`` and a positive driven
    radius (always so for admissible ``e``: a guard against rounding); the driving pitch
    curve is convex, ``e (n^2 - 1) <= 1``; the driven pitch curve is convex,
    ``e^2 (n^2 (m^2 - 2) + 1) <= 1`` (see the module text).

    Parameters
    ----------
    lobes, rotor_lobes, eccentricity, centre_distance, phase : array_like
        ``n``, ``m``, ``e`` [-], ``a`` [m], ``sigma`` [rad] or None; broadcast together.

    Returns
    -------
    ndarray of int16
        Broadcast shape of the parameters; 0 where the design is admissible.
    """
    n = _floats("lobes", lobes)
    m = _floats("rotor_lobes", rotor_lobes)
    e = _floats("eccentricity", eccentricity)
    a = _floats("centre_distance", centre_distance)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        s = _phase_or_default(phase, n)
        lo, hi = CENTRE_DISTANCE_RANGE
        bad_n = ~(np.isfinite(n) & (n == np.round(n)) & (n >= 1) & (n <= MAX_LOBES))
        bad_m = ~(np.isfinite(m) & (m == np.round(m)) & (m >= 1) & (m <= MAX_LOBES))
        bad_e = ~(np.isfinite(e) & (e >= 0.0) & (e < 1.0))
        bad_a = ~(np.isfinite(a) & (a >= lo) & (a <= hi))
        bad_s = ~np.isfinite(s)
        # what follows is evaluated on safe stand-ins where an earlier rule failed
        n_ = np.where(bad_n, 1.0, n)
        m_ = np.where(bad_m, 1.0, m)
        e_ = np.where(bad_e, 0.0, e)
        pa = _pitch_ratio(n_, m_, e_)  # p/a
        beta = 1.0 - pa
        root = np.sqrt((beta - e_) * (beta + e_))
        bad_root = ~(np.isfinite(pa) & (pa > 0.0) & (beta - e_ > 0.0))
        bad_root |= ~(np.abs(pa / np.where(root > 0.0, root, np.nan) * m_ / n_ - 1.0) < 1e-9)
        drive, driven = _convexity_margins(n_, m_, e_)
        bad_drive = drive < -_CONVEX_SLACK
        bad_driven = driven < -_CONVEX_SLACK
    bad = np.broadcast_arrays(bad_n, bad_m, bad_e, bad_a, bad_s, bad_root, bad_drive,
                              bad_driven)  # fmt: skip
    code = np.zeros(bad[0].shape, dtype=np.int16)
    for k in range(len(bad) - 1, -1, -1):  # the first violated rule wins
        code[bad[k]] = k + 1
    return code


def _floor_text(x: float) -> str:
    """``x`` to 4 significant digits, rounded down (a bound shown never admits too much)."""
    if x <= 0.0 or not np.isfinite(x):
        return f"{x:g}"
    scale = 10.0 ** (3 - int(np.floor(np.log10(x))))
    return f"{np.floor(x * scale * (1.0 + 1e-15)) / scale:.4g}"


def _admissible(code: int, n, m, e, a, s) -> tuple[str, str, str]:
    """``(field, value as people read it, what is admissible)`` for rule ``code`` (1-based)."""
    field = CHECKS[code - 1]
    value = f"{e:g}"
    if code in (1, 2):
        value = f"{n if code == 1 else m:g}"
        what = "driving" if code == 1 else "driven"
        text = f"an integer 1 <= {field} <= {MAX_LOBES} (lobes of the {what} pitch curve)"
    elif code == 3:
        text = "0 <= eccentricity < 1"
    elif code == 4:
        lo, hi = CENTRE_DISTANCE_RANGE
        value, text = f"{a:g} m", f"{lo:g} m <= centre_distance <= {hi:g} m"
    elif code == 5:
        value, text = (fmt_deg(s) if np.isfinite(s) else f"{s:g} rad"), "a finite angle"
    else:
        limit = _floor_text(float(eccentricity_limit(n, m)))
        why = {
            6: f"no closure root p > 0 with a positive driven radius for n = {n:g}, m = {m:g}",
            7: f"a {n:g}-lobed driving pitch curve is convex only for e <= 1/(n^2-1); "
            "external gears need convex pitch curves",
            8: f"driven by a {n:g}-lobed gear, a {m:g}-lobed driven pitch curve is convex only "
            "for e <= 1/sqrt(n^2 (m^2-2) + 1); external gears need convex pitch curves",
        }[code]
        text = f"0 <= eccentricity <= {limit} ({why})"
    return field, value, text


def raise_violation(values, code) -> None:
    """Raise :class:`ParameterError` for the first design whose ``code`` is not 0.

    Parameters
    ----------
    values : tuple
        ``(lobes, rotor_lobes, eccentricity, centre_distance, phase)`` as given to
        :func:`violation` (``phase`` may be None).
    code : ndarray
        What :func:`violation` returned for them.
    """
    code = np.asarray(code)
    if not code.any():
        return
    i = int(np.flatnonzero(code)[0])
    k = int(code.flat[i])
    n, m, e, a = (np.broadcast_to(_floats(f, v), code.shape).flat[i]
                  for f, v in zip(CHECKS[:4], values[:4], strict=True))  # fmt: skip
    with np.errstate(invalid="ignore", divide="ignore"):
        s = np.broadcast_to(_phase_or_default(values[4], n), code.shape).flat[i]
    field, value, admissible = _admissible(k, float(n), float(m), float(e), float(a), float(s))
    raise ParameterError(f"drive.{field}", value, admissible)


# --------------------------------------------------------------------------------------------
# constants of a design
# --------------------------------------------------------------------------------------------
def _design(params: NoncircularGears):
    """``n, m, e, a`` as float arrays and the dimensionless ``p/a, B/a, S/a``."""
    n = np.asarray(params.lobes, dtype=float)
    m = np.asarray(params.rotor_lobes, dtype=float)
    e = np.asarray(params.eccentricity, dtype=float)
    a = np.asarray(params.centre_distance, dtype=float)
    pa = _pitch_ratio(n, m, e)
    beta = 1.0 - pa
    root = np.sqrt((beta - e) * (beta + e))
    return n, m, e, a, pa, beta, root


def _phase(params: NoncircularGears):
    return _phase_or_default(params.phase, np.asarray(params.lobes, dtype=float))


def pitch_parameter(params: NoncircularGears):
    """``p`` [m] of ``r1 = p/(1 - e cos(n phi))``: the closure root (module text).

    ``p = a k (1 - e^2)/(k + sqrt(1 - e^2 (1 - k^2)))``, ``k = n/m``; ``a (1 - e^2)/2``
    for ``n = m``.
    """
    n, m, e, a, pa, *_ = _design(params)
    return a * pa


def _phase_of_t(t, e, beta, root):
    """``t + 2 atan(C sin t/(B + S - C cos t))`` (dimensionless: ``C/a = e``)."""
    return t + 2.0 * np.arctan(e * np.sin(t) / (beta + root - e * np.cos(t)))


def _t_of_phase(u, e, beta, root):
    """Inverse of :func:`_phase_of_t`: ``u - 2 atan(C sin u/(B + S + C cos u))``."""
    return u - 2.0 * np.arctan(e * np.sin(u) / (beta + root + e * np.cos(u)))


# --------------------------------------------------------------------------------------------
# one gear pair
# --------------------------------------------------------------------------------------------
def ratio(params: NoncircularGears, phi1):
    """Transmission ratio ``dphi2/dphi1 = p/(B - C cos(n phi1))`` and its derivatives.

    With ``D = B - C cos t``, ``t = n phi1``: ``D' = n C sin t``, ``D'' = n^2 C cos t``,
    ``D''' = -n^3 C sin t`` and ``R = p/D``, ``R' = -p D'/D^2``,
    ``R'' = p (2 D'^2/D^3 - D''/D^2)``, ``R''' = p (-6 D'^3/D^4 + 6 D' D''/D^3 - D'''/D^2)``.

    Parameters
    ----------
    params : NoncircularGears
    phi1 : array_like
        Driving gear angle [rad]; broadcasts with the parameters.

    Returns
    -------
    tuple of 4 ndarray
        ``R`` [-], ``R'`` [1/rad], ``R''`` [1/rad^2], ``R'''`` [1/rad^3] (driven gear
        speed over driving gear speed).
    """
    n, m, e, a, pa, beta, root = _design(params)
    t = n * np.asarray(phi1, dtype=float)
    c, s = np.cos(t), np.sin(t)
    D = beta - e * c
    D1, D2, D3 = n * e * s, n * n * e * c, -(n**3) * e * s
    return (
        pa / D,
        -pa * D1 / D**2,
        pa * (2.0 * D1 * D1 / D**3 - D2 / D**2),
        pa * (-6.0 * D1**3 / D**4 + 6.0 * D1 * D2 / D**3 - D3 / D**2),
    )


def ratio_extremes(params: NoncircularGears):
    """Smallest and largest transmission ratio: ``p/(B + C)`` and ``p/(B - C)``.

    At ``cos(n phi1) = -1`` and ``+1``; ``(1 - e)/(1 + e)`` and ``(1 + e)/(1 - e)`` for
    ``n = m``.

    Returns
    -------
    (min, max) : tuple of ndarray
    """
    n, m, e, a, pa, beta, root = _design(params)
    return pa / (beta + e), pa / (beta - e)


def driven_angle(params: NoncircularGears, phi1):
    """Driven gear angle ``phi2(phi1)`` and its derivatives, closed form.

    ``phi2 = (t + 2 atan(C sin t/(B + S - C cos t)))/m``, ``t = n phi1``: continuous on
    the whole real line, ``phi2(0) = 0``, ``phi2(phi1 + 2 pi/n) = phi2(phi1) + 2 pi/m``,
    odd in ``phi1`` (module text); the derivatives are :func:`ratio`.

    Parameters
    ----------
    params : NoncircularGears
    phi1 : array_like
        Driving gear angle [rad], from the position where the contact point is at the
        driving curve's largest radius; broadcasts with the parameters.

    Returns
    -------
    tuple of 4 ndarray
        ``phi2`` [rad], ``dphi2/dphi1`` [-], ``d2phi2/dphi1^2`` [1/rad],
        ``d3phi2/dphi1^3`` [1/rad^2].
    """
    n, m, e, a, pa, beta, root = _design(params)
    phi1 = np.asarray(phi1, dtype=float)
    phi2 = _phase_of_t(n * phi1, e, beta, root) / m
    R, R1, R2, _ = ratio(params, phi1)
    return phi2, R, R1, R2


def driving_angle(params: NoncircularGears, phi2):
    """Driving gear angle ``phi1(phi2)``, the inverse of :func:`driven_angle`, closed form.

    ``phi1 = (u - 2 atan(C sin u/(B + S + C cos u)))/n``, ``u = m phi2`` (module text).

    Returns
    -------
    ndarray
        ``phi1`` [rad]; broadcast shape of ``phi2`` and the parameters.
    """
    n, m, e, a, pa, beta, root = _design(params)
    return _t_of_phase(m * np.asarray(phi2, dtype=float), e, beta, root) / n


# --------------------------------------------------------------------------------------------
# both rotors
# --------------------------------------------------------------------------------------------
def motion(params: NoncircularGears, theta) -> Motion:
    """Motion of rotor 1 and rotor 2 over the output shaft angle.

    ``q1 = phi2(theta)``, ``q2 = phi2(theta + sigma) - phi2(sigma)`` [rad], positive in
    the rotors' own sense of rotation (opposite to the shaft's: external meshes), from
    their positions at ``theta = 0``; derivatives from :func:`driven_angle`.

    Parameters
    ----------
    params : NoncircularGears
        Numbers or arrays; they broadcast with ``theta``.
    theta : array_like
        Output shaft angle [rad].

    Returns
    -------
    Motion
        ``q``, ``dq``, ``d2q``, ``d3q`` of shape ``(2, ...)``, ``...`` the broadcast shape
        of theta and the parameters; members ``("rotor 1", "rotor 2")``, unit ``"rad"``.

    Notes
    -----
    Evaluated block by block from one ``tan`` and one ``arctan`` per rotor and point
    (:mod:`rotorkin.drives.noncircular_gears.kinematics_fused`; compiled loops when
    numba is installed, ``$ROTORKIN_KERNEL`` chooses): the values of
    :func:`driven_angle` at ``theta`` and ``theta + sigma``.
    """
    theta = np.asarray(theta, dtype=float)
    sigma = _phase(params)
    n, m, e, a, pa, beta, root = _design(params)
    offset = _phase_of_t(n * sigma, e, beta, root) / m  # phi2(sigma)
    q, dq, d2q, d3q = motion_fused(n, m, e, pa, beta, root, sigma, offset, theta)
    theta = np.broadcast_to(theta, q.shape[1:])
    return Motion(theta, q, dq, d2q, d3q, members=("rotor 1", "rotor 2"), unit="rad")


def period(params: NoncircularGears):
    """``2 pi/n`` [rad]: period of the speed ratios and of the relative angle in ``theta``.

    A float, or an array when ``lobes`` is one.
    """
    n = params.lobes
    return 2.0 * np.pi / (float(n) if np.ndim(n) == 0 else np.asarray(n, dtype=float))


def equal_speed_angles(params: NoncircularGears):
    """Shaft angles where both rotors turn equally fast: ``-sigma/2`` and ``pi/n - sigma/2``.

    ``R(theta + sigma) = R(theta)`` iff ``cos(n (theta + sigma)) = cos(n theta)`` (``R``
    is monotonic in the cosine), i.e. ``theta = -sigma/2 + j pi/n`` (for ``n sigma`` not
    a multiple of ``2 pi``). These are the stationary points of ``q2 - q1``.

    Returns
    -------
    (theta_a, theta_b) : tuple of ndarray
        [rad], not wrapped.
    """
    sigma = _phase(params)
    n = np.asarray(params.lobes, dtype=float)
    return -0.5 * sigma, np.pi / n - 0.5 * sigma


def relative_angle_extremes(params: NoncircularGears):
    """Smallest and largest relative angle ``q2 - q1`` over a period, closed form.

    The relative angle is stationary only at :func:`equal_speed_angles`; its values there,
    ``phi2(theta + sigma) - phi2(theta) - phi2(sigma)``, are its minimum and maximum
    (``2 phi2(sigma/2) - phi2(sigma)`` at ``theta = -sigma/2``, ``phi2`` being odd).

    Returns
    -------
    (min, max) : tuple of ndarray
        [rad]; their difference is the swing of the angle between the rotors.
    """
    sigma = _phase(params)
    offset = driven_angle(params, sigma)[0]
    values = [driven_angle(params, th + sigma)[0] - driven_angle(params, th)[0] - offset
              for th in equal_speed_angles(params)]  # fmt: skip
    return np.minimum(*values), np.maximum(*values)


# --------------------------------------------------------------------------------------------
# pitch curves
# --------------------------------------------------------------------------------------------
def _which(which) -> bool:
    """True for the driving curve, False for the driven; refuse anything else."""
    if isinstance(which, str) and which in WHICH:
        return which == "driving"
    raise ParameterError("which", repr(which), "one of " + ", ".join(map(repr, WHICH)))


def _driving_t(params: NoncircularGears, which: str, angle):
    """``t = n phi1`` where the gear ``which`` is at its own angle ``angle``."""
    n, m, e, a, pa, beta, root = _design(params)
    angle = np.asarray(angle, dtype=float)
    if _which(which):
        return n * angle
    return _t_of_phase(m * angle, e, beta, root)


def pitch_radius(params: NoncircularGears, which: str, angle):
    """Radius [m] of a pitch curve at its polar angle ``angle`` [rad].

    Driving: ``r1 = p/(1 - e cos(n angle))``. Driven: ``r2 = a - r1(phi1(angle))`` with
    :func:`driving_angle`, i.e. ``a (B - C cos t)/(a - C cos t)``, ``t = n phi1``.

    The polar angle of each gear is measured in its own frame, against its sense of
    rotation, from the radius that lies on the line of centres at ``theta = 0``: the point
    of polar angle ``angle`` is the contact point once the gear has turned by ``angle``.
    """
    n, m, e, a, pa, beta, root = _design(params)
    c = np.cos(_driving_t(params, which, angle))
    if _which(which):
        return a * pa / (1.0 - e * c)
    return a * (beta - e * c) / (1.0 - e * c)


def pitch_curve(params: NoncircularGears, which: str, angle):
    """Points ``(x, y)`` [m] of a pitch curve in its own frame (:func:`pitch_radius`).

    ``x = r cos(angle)``, ``y = r sin(angle)``, the gear's centre at the origin, the x axis
    towards the other gear's centre at ``theta = 0``. Both curves are symmetric about it.

    In mesh, in one plane (driving centre at the origin turning counter-clockwise by
    ``phi1``, driven centre at ``(a, 0)`` turning clockwise by ``phi2 = driven_angle``),
    a driving point is at ``Rot(phi1) (x, -y)`` and a driven point at
    ``(a, 0) + Rot(pi - phi2) (x, y)`` (each own angle runs against its gear's rotation);
    the points of own angles ``phi1`` and ``phi2`` then coincide on the line of centres,
    where the curves touch.
    """
    r = pitch_radius(params, which, angle)
    angle = np.asarray(angle, dtype=float)
    return r * np.cos(angle), r * np.sin(angle)


def curvature(params: NoncircularGears, which: str, angle):
    """Signed curvature [1/m] of a pitch curve at its polar angle, positive where convex.

    ``kappa = w^3 (w + w'')/(w^2 + w'^2)^(3/2)`` with ``w = 1/r`` (module text):

    * driving: ``w = (1 - e cos t)/p``, ``w' = n e sin t/p``,
      ``w + w'' = (1 + e (n^2 - 1) cos t)/p``;
    * driven: ``w = (1 + p/D)/a``, ``w' = -n C sin t/(a D)``,
      ``w + w'' = (p (p + D) - n^2 C (B cos t - C))/(a p D)``, ``D = B - C cos t``;

    ``t = n phi1`` at the contact of that angle.
    """
    n, m, e, a, pa, beta, root = _design(params)
    t = _driving_t(params, which, angle)
    c, s = np.cos(t), np.sin(t)
    if _which(which):  # in units of 1/a
        w = (1.0 - e * c) / pa
        w1 = n * e * s / pa
        ww = (1.0 + e * (n * n - 1.0) * c) / pa
    else:
        D = beta - e * c
        w = 1.0 + pa / D
        w1 = -n * e * s / D
        ww = (pa * (pa + D) - n * n * e * (beta * c - e)) / (pa * D)
    return w**3 * ww / (w * w + w1 * w1) ** 1.5 / a


def _scalar_design(params: NoncircularGears):
    values = (params.lobes, params.rotor_lobes, params.eccentricity, params.centre_distance,
              params.phase)  # fmt: skip
    if any(np.size(v) != 1 for v in values if v is not None):
        raise ValueError("concave_intervals takes one design, not arrays of parameters")


def concave_intervals(params: NoncircularGears, which: str, samples: int | None = None):
    """Polar angle intervals [rad] where a pitch curve is concave, over one turn of its gear.

    Exact (``samples=None``): the driving curve is concave where ``cos t < -1/(e (n^2-1))``,
    one interval per lobe centred on ``(2 j + 1) pi/n``; the driven curve where
    ``cos t > (p a + n^2 C^2)/(C (p + n^2 B))``, one interval per lobe centred on
    ``2 pi j/m`` (``t = n phi1``, half-widths mapped through :func:`driven_angle`).
    Empty where :func:`violation` finds the curve convex.

    With ``samples``: the sign of :func:`curvature` on ``samples`` equally spaced angles
    of one turn, interval ends interpolated linearly between samples.

    Parameters
    ----------
    params : NoncircularGears
        One design (scalar fields).
    which : {"driving", "driven"}
    samples : int, optional

    Returns
    -------
    list of (start, end)
        Sorted by midpoint, midpoints in ``[-pi/(2 l), 2 pi - pi/(2 l))``, ``l`` the
        curve's lobes (the first interval may start below 0: angles are mod 2 pi).
    """
    _scalar_design(params)
    driving = _which(which)
    n, m, e, a, pa, beta, root = (float(v) for v in _design(params))
    lobes = n if driving else m
    if samples is not None:
        return _sampled_intervals(params, which, int(samples), lobes)
    drive, driven = _convexity_margins(n, m, e)
    if (drive if driving else driven) >= -_CONVEX_SLACK:
        return []
    if driving:
        w = np.arccos(min(1.0, 1.0 / (e * (n * n - 1.0)))) / n
        centres = (2.0 * np.arange(n) + 1.0) * np.pi / n
    else:
        cstar = (pa + n * n * e * e) / (e * (pa + n * n * beta))
        t = np.arccos(np.clip(cstar, -1.0, 1.0))
        w = float(_phase_of_t(t, e, beta, root)) / m
        centres = 2.0 * np.pi * np.arange(m) / m
    return [(float(c - w), float(c + w)) for c in centres]


def _sampled_intervals(params, which, samples, lobes):
    """:func:`concave_intervals` from the sign of the curvature on a grid."""
    if samples < 8:
        raise ValueError("samples must be at least 8")
    step = 2.0 * np.pi / samples
    k = curvature(params, which, step * np.arange(samples))
    bad = k < 0.0
    if not bad.any():
        return []
    if bad.all():
        return [(0.0, 2.0 * np.pi)]
    first = int(np.argmin(bad))  # a convex sample: start there, no run crosses the seam
    idx = first + np.arange(samples + 1)
    kk = k[idx % samples]
    bb = kk < 0.0
    starts = np.flatnonzero(~bb[:-1] & bb[1:]) + 1  # first concave sample of each run
    ends = np.flatnonzero(bb[:-1] & ~bb[1:]) + 1  # first convex sample after each run

    def cross(i):  # zero of the curvature between samples i - 1 and i
        return step * (idx[i - 1] + kk[i - 1] / (kk[i - 1] - kk[i]))

    out = []
    half = np.pi / (2.0 * lobes)
    for i, j in zip(starts, ends, strict=True):
        lo, hi = cross(i), cross(j)
        shift = 2.0 * np.pi * np.floor((0.5 * (lo + hi) + half) / (2.0 * np.pi))
        out.append((float(lo - shift), float(hi - shift)))
    return sorted(out, key=lambda iv: iv[0] + iv[1])
