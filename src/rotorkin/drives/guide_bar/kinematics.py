"""Two rotating guide-bar mechanisms + gears: the drive of a differential vane pump.

Source: "Kinematic and mechanical characteristics of the drive system of a
differential vane pump", J. Harbin Institute of Technology 44(9), 2012 (in
Chinese). Equation and figure numbers below are the paper's.

Input gear 1 (angle ``theta``) meshes with two equal gears (ratio
``i12 = z2/z1``), each fixed to the driving member of a rotating guide-bar
mechanism (inverted slider-crank: crank pivot A, guide pivot C, frame
``d = |AC|``, crank ``a``, ``lambda = d/a < 1`` so that the guide bar turns
fully round). The driven member of each mechanism turns an impeller through a
gear pair of ratio ``u``. Two variants: *crank-driven* (Fig. 2: the cranks are
driven, the guide bars drive the impellers) and *guide-driven* (Fig. 4: the
guide bars are driven, the cranks drive the impellers).

Conventions (the paper is silent on most; decided here):

* Every member's angle is measured positive in the sense in which that member
  turns on average. External gear meshes reverse the physical sense; we do not
  track it, so all speed ratios are positive.
* The driving member of both mechanisms turns at ``t = theta / i12``.
  Mechanism k is installed at ``sigma_k``: ``sigma_1 = 0``,
  ``sigma_2 = Sigma`` (the installation phase, ``phase``); its driving angle
  is ``x_k = sigma_k + t``.
* Crank-driven: the crank angle ``x`` is measured from the line guide pivot
  C -> crank pivot A. In units of ``a``, with C at the origin and A at
  ``(lambda, 0)``, the crank pin is at ``(lambda + cos x, sin x)`` and the
  guide bar angle is ``g(x) = angle(lambda + cos x, sin x)`` on its
  continuous branch (``g(0) = 0``, ``g(pi) = pi``). ``g'`` is eq. 1 times ``u``.
* Guide-driven: the guide bar angle ``y`` (same zero line) is the input; the
  crank pin is on the guide line at ``s = lambda cos y + sqrt(1 - lambda^2
  sin^2 y)`` from C, and the crank angle is ``h(y) = angle(s cos y - lambda,
  s sin y)`` (``h(0) = 0``, ``h(pi) = pi``); ``h`` is the inverse of ``g``.
  The paper's eq. 3 puts its ``x = 0`` at our ``y = pi``: its ratio is
  ``h'(x + pi)/u``.
* Impeller k turns by ``q_k = g(x_k)/u`` (crank-driven) or ``h(x_k)/u``
  (guide-driven) [rad]; ``q_k = 0`` where mechanism k's driving angle is 0.
  Over one period ``2 pi i12`` of theta each impeller advances by ``2 pi/u``.

Misprints of the paper (OCR): eq. 8 (guide-driven input torque) is garbled
(stray square roots); it is the virtual-work balance with the eq. 3 ratio, as
implemented in :func:`input_torque`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.core.angles import angle_near, fmt_deg
from rotorkin.core.errors import ParameterError
from rotorkin.core.motion import Motion

__all__ = [
    "DRIVERS",
    "GuideBar",
    "guide_angle",
    "crank_angle",
    "driven_angle",
    "speed_ratio_eq1",
    "speed_ratio_eq3",
    "speed_ratio_range",
    "driving_angles",
    "impeller_angles",
    "motion",
    "period",
    "equal_speed_angles",
    "vane_angle",
    "vane_angle_paper",
    "vane_angle_half_turn",
    "lambda_for_vane_angle",
    "relative_angle_swing",
    "input_torque",
    "input_torque_eq7",
]

#: Admissible driving members.
DRIVERS = ("crank", "guide")


@dataclass(frozen=True)
class GuideBar:
    """Parameters of the guide-bar + gear drive (dimensionless; angles in rad).

    Parameters
    ----------
    lam : float
        Mechanism coefficient ``lambda = d/a`` (frame over crank length),
        ``0 < lambda < 1``. Config key ``drive.lambda``. Paper: 0.5.
    gear_ratio : float
        ``u``, guide-bar (or crank) gear to impeller gear, ``u > 0``. Paper: 2.
    input_gear_ratio : float, optional
        ``i12 = z2/z1 = z9/z1``, ``i12 > 0`` (default 1; paper Fig. 10, 11: 2).
    phase : float, optional
        Installation phase ``Sigma = sigma_2 - sigma_1`` [rad], not a multiple
        of 2 pi (default pi, the paper's).
    driver : {"crank", "guide"}, optional
        Driving member of both mechanisms (default ``"crank"``, Fig. 2).
    """

    lam: float
    gear_ratio: float
    input_gear_ratio: float = 1.0
    phase: float = np.pi
    driver: str = "crank"

    def __post_init__(self):
        lam = float(self.lam)
        if not np.isfinite(lam) or lam <= 0.0:
            raise ParameterError("lam", f"{lam:g}", "0 < lambda < 1")
        if lam >= 1.0:
            raise ParameterError(
                "lam",
                f"{lam:g}",
                "0 < lambda < 1: at lambda >= 1 the guide bar would no longer turn fully "
                "round (oscillating guide bar)",
            )
        u = float(self.gear_ratio)
        if not (np.isfinite(u) and u > 0.0):
            raise ParameterError("gear_ratio", f"{u:g}", "gear_ratio u > 0")
        i12 = float(self.input_gear_ratio)
        if not (np.isfinite(i12) and i12 > 0.0):
            raise ParameterError("input_gear_ratio", f"{i12:g}", "input_gear_ratio i12 > 0")
        p = float(self.phase)
        turns = p / (2.0 * np.pi)
        if not np.isfinite(p) or abs(turns - np.round(turns)) < 1e-9:
            raise ParameterError(
                "phase",
                fmt_deg(p),
                "not a multiple of 360 deg: both impellers would move together and no "
                "chamber would change (the paper uses 180 deg)",
            )
        if self.driver not in DRIVERS:
            raise ParameterError(
                "driver", repr(self.driver), "one of " + ", ".join(map(repr, DRIVERS))
            )


# --------------------------------------------------------------------------------------------
# one mechanism: driven angle from driving angle
# --------------------------------------------------------------------------------------------
def guide_angle(lam, x):
    """Guide bar angle of a crank-driven mechanism and its derivatives (eq. 1).

    Parameters
    ----------
    lam : array_like
        ``lambda = d/a``, ``0 < lambda < 1``.
    x : array_like
        Crank angle [rad], from the line guide pivot -> crank pivot.

    Returns
    -------
    tuple of 4 ndarray
        ``g`` [rad] (continuous, ``g(x + 2 pi) = g(x) + 2 pi``) and
        ``g' = (1 + lambda cos x)/D`` (eq. 1 times u),
        ``g'' = lambda (1 - lambda^2) sin x / D^2``,
        ``g''' = lambda (1 - lambda^2)(D cos x + 4 lambda sin^2 x)/D^3``,
        with ``D = 1 + 2 lambda cos x + lambda^2``; derivatives w.r.t. x.
    """
    lam = np.asarray(lam, dtype=float)
    x = np.asarray(x, dtype=float)
    c, s = np.cos(x), np.sin(x)
    D = 1.0 + 2.0 * lam * c + lam * lam
    K = lam * (1.0 - lam * lam)
    g = angle_near(s, lam + c, x)
    return g, (1.0 + lam * c) / D, K * s / D**2, K * (D * c + 4.0 * lam * s * s) / D**3


def crank_angle(lam, y):
    """Crank angle of a guide-driven mechanism and its derivatives (eq. 3, our zero).

    Parameters
    ----------
    lam : array_like
        ``lambda = d/a``, ``0 < lambda < 1``.
    y : array_like
        Guide bar angle [rad], from the line guide pivot -> crank pivot.

    Returns
    -------
    tuple of 4 ndarray
        ``h`` [rad] (continuous, the inverse function of :func:`guide_angle`) and
        ``h' = 1 + lambda cos y / W``,
        ``h'' = -lambda (1 - lambda^2) sin y / W^3``,
        ``h''' = -lambda (1 - lambda^2) cos y (1 + 2 lambda^2 sin^2 y) / W^5``,
        with ``W = sqrt(1 - lambda^2 sin^2 y)``. The paper's eq. 3 ratio
        ``(W - lambda cos x)/(u W)`` is ``h'(x + pi)/u``.
    """
    lam = np.asarray(lam, dtype=float)
    y = np.asarray(y, dtype=float)
    c, s = np.cos(y), np.sin(y)
    W = np.sqrt(1.0 - (lam * s) ** 2)
    K = lam * (1.0 - lam * lam)
    r = lam * c + W  # crank pin distance from the guide pivot [a]
    h = angle_near(r * s, r * c - lam, y)
    return h, 1.0 + lam * c / W, -K * s / W**3, -K * c * (1.0 + 2.0 * (lam * s) ** 2) / W**5


def driven_angle(lam, x, driver: str):
    """:func:`guide_angle` (``driver = "crank"``) or :func:`crank_angle` (``"guide"``)."""
    if driver == "crank":
        return guide_angle(lam, x)
    if driver == "guide":
        return crank_angle(lam, x)
    raise ParameterError("driver", repr(driver), "one of " + ", ".join(map(repr, DRIVERS)))


def speed_ratio_eq1(lam, u, x):
    """Crank-driven impeller speed over crank speed, as printed (eq. 1, 2).

    ``omega_7 / omega_4 = (1 + lambda cos x) / ([1 + 2 lambda cos x + lambda^2] u)``.
    """
    lam, u, x = (np.asarray(v, dtype=float) for v in (lam, u, x))
    c = np.cos(x)
    return (1.0 + lam * c) / ((1.0 + 2.0 * lam * c + lam * lam) * u)


def speed_ratio_eq3(lam, u, x):
    """Guide-driven impeller speed over guide speed, as printed (eq. 3, 4; paper's zero).

    ``sqrt(1 - l^2 sin^2 x + l^2 cos^2 x - 2 l cos x W) / (u W)``,
    ``W = sqrt(1 - l^2 sin^2 x)``; equal to ``(W - l cos x)/(u W)``. The
    paper's ``x = 0`` is our ``y = pi`` (see :func:`crank_angle`).
    """
    lam, u, x = (np.asarray(v, dtype=float) for v in (lam, u, x))
    c, s = np.cos(x), np.sin(x)
    W = np.sqrt(1.0 - (lam * s) ** 2)
    num = 1.0 - (lam * s) ** 2 + (lam * c) ** 2 - 2.0 * lam * c * W
    return np.sqrt(num) / (u * W)


def speed_ratio_range(lam, u, driver: str):
    """Smallest and largest impeller speed over the driving member's speed.

    Crank-driven ``1/((1 + lambda) u)`` at ``x = 0`` and ``1/((1 - lambda) u)``
    at ``x = pi``; guide-driven ``(1 - lambda)/u`` at ``y = pi`` and
    ``(1 + lambda)/u`` at ``y = 0`` (both are monotonic in ``cos x``).

    Returns
    -------
    (min, max) : tuple of ndarray
    """
    lam, u = np.asarray(lam, dtype=float), np.asarray(u, dtype=float)
    if driver == "crank":
        return 1.0 / ((1.0 + lam) * u), 1.0 / ((1.0 - lam) * u)
    driven_angle(0.5, 0.0, driver)  # validates the name
    return (1.0 - lam) / u, (1.0 + lam) / u


# --------------------------------------------------------------------------------------------
# the pair of mechanisms and the impellers
# --------------------------------------------------------------------------------------------
def driving_angles(params: GuideBar, theta):
    """Driving angles ``x_k = sigma_k + theta / i12`` of both mechanisms [rad], shape (2, ...)."""
    t = np.asarray(theta, dtype=float) / float(params.input_gear_ratio)
    return np.stack([t, t + float(params.phase)])


def impeller_angles(params: GuideBar, theta):
    """Impeller angles ``q_k = f(x_k)/u`` and their derivatives w.r.t. theta.

    ``f`` is :func:`guide_angle` (crank-driven) or :func:`crank_angle`
    (guide-driven). ``dq_k/dtheta = f'(x_k)/(u i12)`` is eq. 1 (or eq. 3 at our
    zero) over ``i12``; ``d2q = f''/(u i12^2)``, ``d3q = f'''/(u i12^3)``.

    Parameters
    ----------
    params : GuideBar
    theta : array_like
        Input gear angle [rad].

    Returns
    -------
    tuple of 4 ndarray, shape (2, ...)
        ``q`` [rad], ``dq/dtheta`` [-], ``d2q/dtheta2`` [1/rad], ``d3q/dtheta3`` [1/rad^2].
    """
    x = driving_angles(params, theta)
    u, i12 = float(params.gear_ratio), float(params.input_gear_ratio)
    f = driven_angle(float(params.lam), x, params.driver)
    return tuple(fn / (u * i12**n) for n, fn in enumerate(f))


def motion(params: GuideBar, theta) -> Motion:
    """Motion of impeller 1 and impeller 2 (``q`` [rad]) over input gear angle theta [rad]."""
    theta = np.asarray(theta, dtype=float)
    q, dq, d2q, d3q = impeller_angles(params, theta)
    return Motion(theta, q, dq, d2q, d3q, members=("impeller 1", "impeller 2"), unit="rad")


def period(params: GuideBar) -> float:
    """Input angle after which the speeds repeat: ``2 pi i12`` [rad] (the impellers gain 2 pi/u)."""
    return 2.0 * np.pi * float(params.input_gear_ratio)


# --------------------------------------------------------------------------------------------
# equal-speed points and the vane angle (section 3)
# --------------------------------------------------------------------------------------------
def equal_speed_angles(phase):
    """Driving angles of mechanism 1 where both impellers turn equally fast [rad].

    The speed ratio depends on ``cos x`` only and is monotonic in it (both
    drivers), so ``f'(t) = f'(t + Sigma)`` iff ``cos t = cos(t + Sigma)``:
    ``t = -Sigma/2`` and ``t = pi - Sigma/2`` (mod 2 pi). Derived here; the paper
    finds them graphically (Fig. 6-8).

    Returns
    -------
    (t_a, t_b) : tuple of ndarray
        ``-Sigma/2`` and ``pi - Sigma/2`` (not wrapped) [rad].
    """
    p = np.asarray(phase, dtype=float)
    return -0.5 * p, np.pi - 0.5 * p


def _half_phase(phase):
    """``Sigma/2`` reduced into (0, pi) (the phase taken mod 2 pi)."""
    return 0.5 * np.mod(np.asarray(phase, dtype=float), 2.0 * np.pi)


def vane_angle(lam, u, phase, driver: str):
    """Theoretical vane angle gamma_0: what the slower impeller turns between equal-speed points.

    With ``a = (Sigma mod 2 pi)/2`` in (0, pi), derived here from the geometry:

    * crank-driven: ``gamma_0 = (g(a) + g(pi - a)) / u`` (impeller 1 is the slower on
      ``t in (-a, pi - a)``);
    * guide-driven: ``gamma_0 = (2 pi - h(a) - h(pi - a)) / u`` (impeller 2 is the slower).

    These equal the paper's general-Sigma formulas (:func:`vane_angle_paper`)
    for every Sigma, and eq. 5 / eq. 6 at Sigma = 180 deg. The faster impeller
    turns ``2 pi/u - gamma_0`` meanwhile.

    Parameters
    ----------
    lam, u, phase : array_like
        lambda [-], gear ratio u [-], installation phase Sigma [rad]; broadcast.
    driver : {"crank", "guide"}

    Returns
    -------
    ndarray
        gamma_0 [rad].
    """
    lam, u = np.asarray(lam, dtype=float), np.asarray(u, dtype=float)
    a = _half_phase(phase)
    f1 = driven_angle(lam, a, driver)[0]
    f2 = driven_angle(lam, np.pi - a, driver)[0]
    if driver == "crank":
        return (f1 + f2) / u
    return (2.0 * np.pi - f1 - f2) / u


def vane_angle_paper(lam, u, phase, driver: str):
    """The paper's general-Sigma vane angle, ``(theta_1 + theta_2)/u``, as printed (section 3).

    Crank-driven: ``cos theta_1 = (lambda + cos(Sigma/2)) / sqrt(1 + 2 lambda
    cos(Sigma/2) + lambda^2)``, ``cos theta_2 = (lambda - cos(Sigma/2)) / sqrt(1 -
    2 lambda cos(Sigma/2) + lambda^2)``. Guide-driven: ``cos theta_{1,2} = lambda
    sin^2(Sigma/2) +- cos(Sigma/2) sqrt(1 - lambda^2 sin^2(Sigma/2))``.
    ``theta_i = arccos(.)`` in [0, pi].
    """
    lam, u = np.asarray(lam, dtype=float), np.asarray(u, dtype=float)
    p = np.asarray(phase, dtype=float)
    c, s = np.cos(0.5 * p), np.sin(0.5 * p)
    if driver == "crank":
        c1 = (lam + c) / np.sqrt(1.0 + 2.0 * lam * c + lam * lam)
        c2 = (lam - c) / np.sqrt(1.0 - 2.0 * lam * c + lam * lam)
    elif driver == "guide":
        W = np.sqrt(1.0 - (lam * s) ** 2)
        c1 = lam * s * s + c * W
        c2 = lam * s * s - c * W
    else:
        driven_angle(0.5, 0.0, driver)  # raises
    clip = (np.clip(v, -1.0, 1.0) for v in (c1, c2))
    return sum(np.arccos(v) for v in clip) / u


def vane_angle_half_turn(lam, u, driver: str):
    """Vane angle at Sigma = 180 deg: eq. 5 (crank) or eq. 6 (guide) solved for gamma_0 [rad].

    Crank: ``gamma_0 = 2 arccos(lambda / sqrt(1 + lambda^2)) / u`` (eq. 5);
    guide: ``gamma_0 = 2 arccos(lambda) / u`` (eq. 6).
    """
    lam, u = np.asarray(lam, dtype=float), np.asarray(u, dtype=float)
    if driver == "crank":
        return 2.0 * np.arccos(lam / np.sqrt(1.0 + lam * lam)) / u
    driven_angle(0.5, 0.0, driver)  # validates the name
    return 2.0 * np.arccos(lam) / u


def lambda_for_vane_angle(gamma0, u, driver: str):
    """lambda that gives the vane angle gamma_0 at Sigma = 180 deg (eq. 5, 6 inverted).

    Crank: ``lambda = cot(u gamma_0 / 2)``, needs ``pi/4 < u gamma_0/2 < pi/2``;
    guide: ``lambda = cos(u gamma_0 / 2)``, needs ``0 < u gamma_0/2 < pi/2``.
    NaN where no ``0 < lambda < 1`` exists. Derived here.
    """
    half = 0.5 * np.asarray(u, dtype=float) * np.asarray(gamma0, dtype=float)
    if driver == "crank":
        ok = (half > np.pi / 4.0) & (half < np.pi / 2.0)
        safe = np.where(ok, half, np.pi / 3.0)
        return np.where(ok, np.cos(safe) / np.sin(safe), np.nan)
    driven_angle(0.5, 0.0, driver)  # validates the name
    ok = (half > 0.0) & (half < np.pi / 2.0)
    return np.where(ok, np.cos(half), np.nan)


def relative_angle_swing(params: GuideBar) -> float:
    """Swing (max - min) of the angle between the impellers, ``q_2 - q_1``, over a turn [rad].

    The relative angle is stationary at the equal-speed points; between them
    one impeller turns ``gamma_0``, the other ``2 pi/u - gamma_0``, so the swing
    is ``2 pi/u - 2 gamma_0``. Derived here: it sets the chamber volume change.
    """
    g0 = float(vane_angle(params.lam, params.gear_ratio, params.phase, params.driver))
    return 2.0 * np.pi / float(params.gear_ratio) - 2.0 * g0


# --------------------------------------------------------------------------------------------
# torque (section 4)
# --------------------------------------------------------------------------------------------
def input_torque(params: GuideBar, theta, m7, m8):
    """Torque on input gear 1 by virtual work, ``M1 = M7 dq_1/dtheta + M8 dq_2/dtheta`` [N*m].

    Eq. 7 (crank-driven) and eq. 8 (guide-driven; garbled in the OCR) are this
    balance ``M1 omega_1 = M7 omega_7 + M8 omega_8``, friction and inertia
    neglected.

    Parameters
    ----------
    params : GuideBar
    theta : array_like
        Input gear angle [rad].
    m7, m8 : array_like
        Resisting torques on impeller 1 and 2 [N*m]; broadcast with theta.

    Returns
    -------
    ndarray
        M1 [N*m].
    """
    _, dq, _, _ = impeller_angles(params, theta)
    return np.asarray(m7, dtype=float) * dq[0] + np.asarray(m8, dtype=float) * dq[1]


def input_torque_eq7(lam, u, i12, x1, x2, m7, m8):
    """Crank-driven input torque as printed (eq. 7).

    ``M1 = (1 + l cos x1)/([1 + 2 l cos x1 + l^2] u i12) M7 + (same at x2) M8``,
    ``x_k = sigma_k + phi`` the crank angles [rad].
    """
    i12 = np.asarray(i12, dtype=float)
    return speed_ratio_eq1(lam, u, x1) / i12 * np.asarray(m7, dtype=float) + speed_ratio_eq1(
        lam, u, x2
    ) / i12 * np.asarray(m8, dtype=float)
