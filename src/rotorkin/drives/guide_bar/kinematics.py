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
from rotorkin.drives.guide_bar.kinematics_fused import impellers_fused

__all__ = [
    "DRIVERS",
    "FIELDS",
    "inadmissible",
    "raise_inadmissible",
    "GuideBar",
    "guide_rates",
    "guide_angle",
    "crank_rates",
    "crank_angle",
    "driven_rates",
    "driven_angle",
    "speed_ratio_eq1",
    "speed_ratio_eq3",
    "speed_ratio_range",
    "driving_angles",
    "impeller_rates",
    "impeller_angles",
    "motion",
    "period",
    "input_period",
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
#: Admissible driving members.
DRIVERS = ("crank", "guide")

#: Parameters of :class:`GuideBar` in the order they are checked (:func:`inadmissible`).
FIELDS = ("lam", "gear_ratio", "input_gear_ratio", "phase", "driver")


def inadmissible(lam, gear_ratio, input_gear_ratio=1.0, phase=np.pi, driver="crank"):
    """Which parameter each design violates first: index into :data:`FIELDS` plus 1 (0: none).

    Admissible: ``0 < lam < 1`` (at ``lam >= 1`` the guide bar no longer turns
    fully round), ``gear_ratio > 0``, ``input_gear_ratio > 0``, ``phase`` finite
    and not a multiple of ``2 pi`` (both impellers would move together),
    ``driver`` one of :data:`DRIVERS`.

    Parameters
    ----------
    lam, gear_ratio, input_gear_ratio, phase : array_like
        lambda [-], u [-], i12 [-], Sigma [rad]; broadcast together.
    driver : str or array_like of str
        Broadcasts with the others.

    Returns
    -------
    ndarray of int16
        Broadcast shape of the parameters.
    """
    lam, u, i12, p = (np.asarray(v, dtype=float) for v in (lam, gear_ratio, input_gear_ratio,
                                                          phase))  # fmt: skip
    known = np.isin(np.asarray(driver), DRIVERS)
    with np.errstate(invalid="ignore"):
        turns = p / (2.0 * np.pi)
        bad = (
            ~(np.isfinite(lam) & (lam > 0.0) & (lam < 1.0)),
            ~(np.isfinite(u) & (u > 0.0)),
            ~(np.isfinite(i12) & (i12 > 0.0)),
            ~np.isfinite(p) | (np.abs(turns - np.round(turns)) < 1e-9),
            ~known,
        )
    bad = np.broadcast_arrays(*bad)
    reason = np.zeros(bad[0].shape, dtype=np.int16)
    for k in range(len(bad) - 1, -1, -1):  # the first violated parameter wins
        reason[bad[k]] = k + 1
    return reason


def _admissible(field: str, value) -> tuple[str, str]:
    """``(value as people read it, admissible range)`` for :class:`ParameterError`."""
    if field == "lam":
        text = "0 < lambda < 1"
        if np.isfinite(value) and value >= 1.0:
            text += (": at lambda >= 1 the guide bar would no longer turn fully round "
                     "(oscillating guide bar)")  # fmt: skip
        return f"{value:g}", text
    if field == "phase":
        return fmt_deg(value), (
            "not a multiple of 360 deg: both impellers would move together and no chamber "
            "would change (the paper uses 180 deg)"
        )
    if field == "driver":
        return repr(value), "one of " + ", ".join(map(repr, DRIVERS))
    symbol = {"gear_ratio": "u", "input_gear_ratio": "i12"}[field]
    return f"{value:g}", f"{field} {symbol} > 0"


def raise_inadmissible(fields, values, reason) -> None:
    """Raise :class:`ParameterError` for the first design whose ``reason`` is not 0.

    ``fields`` names the parameters, ``values`` their values (broadcast with
    ``reason``), ``reason`` the codes of an ``inadmissible`` function (index + 1).
    """
    reason = np.asarray(reason)
    if not reason.any():
        return
    i = int(np.flatnonzero(reason)[0])
    k = int(reason.flat[i]) - 1
    value = np.broadcast_to(np.asarray(values[k]), reason.shape).flat[i]
    value = value.item() if hasattr(value, "item") else value
    raise ParameterError(fields[k], *_admissible(fields[k], value))


@dataclass(frozen=True)
class GuideBar:
    """Parameters of the guide-bar + gear drive (dimensionless; angles in rad).

    Every field is a float or an array (one value per design); arrays broadcast
    against each other and against the input angles of :func:`impeller_angles`
    (e.g. parameters of shape (n, 1) against angles of shape (m,)).

    Parameters
    ----------
    lam : float or ndarray
        Mechanism coefficient ``lambda = d/a`` (frame over crank length),
        ``0 < lambda < 1``. Config key ``drive.lambda``. Paper: 0.5.
    gear_ratio : float or ndarray
        ``u``, guide-bar (or crank) gear to impeller gear, ``u > 0``. Paper: 2.
    input_gear_ratio : float or ndarray, optional
        ``i12 = z2/z1 = z9/z1``, ``i12 > 0`` (default 1; paper Fig. 10, 11: 2).
    phase : float or ndarray, optional
        Installation phase ``Sigma = sigma_2 - sigma_1`` [rad], not a multiple
        of 2 pi (default pi, the paper's).
    driver : {"crank", "guide"} or ndarray of str, optional
        Driving member of both mechanisms (default ``"crank"``, Fig. 2).

    Raises
    ------
    ParameterError
        Named by the field (:func:`inadmissible`), with its value and the
        admissible range.
    """

    lam: float
    gear_ratio: float
    input_gear_ratio: float = 2.0
    phase: float = np.pi
    driver: str = "crank"

    def __post_init__(self):
        values = tuple(getattr(self, f) for f in FIELDS)
        raise_inadmissible(FIELDS, values, inadmissible(*values))


# --------------------------------------------------------------------------------------------
# one mechanism: driven angle from driving angle
# --------------------------------------------------------------------------------------------
def guide_rates(lam, x):
    """Derivatives of the guide bar angle of a crank-driven mechanism w.r.t. x (eq. 1).

    Parameters
    ----------
    lam : array_like
        ``lambda = d/a``, ``0 < lambda < 1``.
    x : array_like
        Crank angle [rad], from the line guide pivot -> crank pivot; broadcasts with lam.

    Returns
    -------
    tuple of 3 ndarray
        ``g' = (1 + lambda cos x)/D`` (eq. 1 times u),
        ``g'' = lambda (1 - lambda^2) sin x / D^2``,
        ``g''' = lambda (1 - lambda^2)(D cos x + 4 lambda sin^2 x)/D^3``,
        with ``D = 1 + 2 lambda cos x + lambda^2`` [-, 1/rad, 1/rad^2].
    """
    lam = np.asarray(lam, dtype=float)
    x = np.asarray(x, dtype=float)
    c, s = np.cos(x), np.sin(x)
    D = 1.0 + 2.0 * lam * c + lam * lam
    K = lam * (1.0 - lam * lam)
    return (1.0 + lam * c) / D, K * s / D**2, K * (D * c + 4.0 * lam * s * s) / D**3


def guide_angle(lam, x):
    """Guide bar angle of a crank-driven mechanism and its derivatives (eq. 1).

    Parameters
    ----------
    lam, x : array_like
        As :func:`guide_rates`.

    Returns
    -------
    tuple of 4 ndarray
        ``g = angle(lambda + cos x, sin x)`` [rad] (continuous,
        ``g(x + 2 pi) = g(x) + 2 pi``) and ``g', g'', g'''`` (:func:`guide_rates`).
    """
    lam = np.asarray(lam, dtype=float)
    x = np.asarray(x, dtype=float)
    g = angle_near(np.sin(x), lam + np.cos(x), x)
    return (g, *guide_rates(lam, x))


def crank_rates(lam, y):
    """Derivatives of the crank angle of a guide-driven mechanism w.r.t. y (eq. 3, our zero).

    Parameters
    ----------
    lam : array_like
        ``lambda = d/a``, ``0 < lambda < 1``.
    y : array_like
        Guide bar angle [rad], from the line guide pivot -> crank pivot; broadcasts with lam.

    Returns
    -------
    tuple of 3 ndarray
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
    return 1.0 + lam * c / W, -K * s / W**3, -K * c * (1.0 + 2.0 * (lam * s) ** 2) / W**5


def crank_angle(lam, y):
    """Crank angle of a guide-driven mechanism and its derivatives (eq. 3, our zero).

    Parameters
    ----------
    lam, y : array_like
        As :func:`crank_rates`.

    Returns
    -------
    tuple of 4 ndarray
        ``h = angle(s cos y - lambda, s sin y)`` [rad], ``s = lambda cos y + W``
        the crank pin's distance from the guide pivot [a] (continuous, the inverse
        function of :func:`guide_angle`), and ``h', h'', h'''`` (:func:`crank_rates`).
    """
    lam = np.asarray(lam, dtype=float)
    y = np.asarray(y, dtype=float)
    c, s = np.cos(y), np.sin(y)
    r = lam * c + np.sqrt(1.0 - (lam * s) ** 2)  # crank pin distance from the guide pivot [a]
    h = angle_near(r * s, r * c - lam, y)
    return (h, *crank_rates(lam, y))


def _by_driver(crank_fn, guide_fn, driver, *args):
    """``crank_fn(*args)`` where the driver is the crank, ``guide_fn(*args)`` where the guide bar.

    Both return tuples of arrays; with an array of drivers both are evaluated and
    picked element-wise.
    """
    if isinstance(driver, str):
        if driver == "crank":
            return crank_fn(*args)
        if driver == "guide":
            return guide_fn(*args)
        raise ParameterError("driver", repr(driver), "one of " + ", ".join(map(repr, DRIVERS)))
    d = np.asarray(driver)
    if not np.all(np.isin(d, DRIVERS)):
        bad = d[~np.isin(d, DRIVERS)].flat[0]
        raise ParameterError("driver", repr(bad), "one of " + ", ".join(map(repr, DRIVERS)))
    crank = d == "crank"
    return tuple(np.where(crank, a, b) for a, b in zip(crank_fn(*args), guide_fn(*args),
                                                       strict=True))  # fmt: skip


def driven_angle(lam, driver, x):
    """:func:`guide_angle` (``driver = "crank"``) or :func:`crank_angle` (``"guide"``).

    ``driver`` may be an array of those names, broadcasting with ``lam`` and ``x``.
    """
    return _by_driver(guide_angle, crank_angle, driver, lam, x)


def driven_rates(lam, driver, x):
    """:func:`guide_rates` (``driver = "crank"``) or :func:`crank_rates` (``"guide"``).

    ``driver`` may be an array of those names, broadcasting with ``lam`` and ``x``.
    """
    return _by_driver(guide_rates, crank_rates, driver, lam, x)


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
    return np.sqrt(np.maximum(num, 0.0)) / (u * W)


def _speed_ratio_range_crank(lam, u):
    return 1.0 / ((1.0 + lam) * u), 1.0 / ((1.0 - lam) * u)


def _speed_ratio_range_guide(lam, u):
    return (1.0 - lam) / u, (1.0 + lam) / u


def speed_ratio_range(lam, u, driver):
    """Smallest and largest impeller speed over the driving member's speed.

    Crank-driven ``1/((1 + lambda) u)`` at ``x = 0`` and ``1/((1 - lambda) u)``
    at ``x = pi``; guide-driven ``(1 - lambda)/u`` at ``y = pi`` and
    ``(1 + lambda)/u`` at ``y = 0`` (both are monotonic in ``cos x``).

    Parameters
    ----------
    lam, u : array_like
        lambda [-], gear ratio u [-]; broadcast.
    driver : {"crank", "guide"} or array_like of str
        Broadcasts with lam and u.

    Returns
    -------
    (min, max) : tuple of ndarray
    """
    lam, u = np.asarray(lam, dtype=float), np.asarray(u, dtype=float)
    return _by_driver(_speed_ratio_range_crank, _speed_ratio_range_guide, driver, lam, u)


# --------------------------------------------------------------------------------------------
# the pair of mechanisms and the impellers
# --------------------------------------------------------------------------------------------
def driving_angles(params: GuideBar, theta):
    """Driving angles ``x_k = sigma_k + theta / i12`` of both mechanisms [rad], shape (2, ...).

    ``...`` is the broadcast shape of theta and the parameters.
    """
    t = np.asarray(theta, dtype=float) / np.asarray(params.input_gear_ratio, dtype=float)
    return np.stack(np.broadcast_arrays(t, t + np.asarray(params.phase, dtype=float)))


def impeller_rates(params: GuideBar, theta):
    """Derivatives of the impeller angles w.r.t. theta, without the angles (no arctangent).

    ``dq_k/dtheta = f'(x_k)/(u i12)`` is eq. 1 (or eq. 3 at our zero) over
    ``i12``; ``d2q = f''/(u i12^2)``, ``d3q = f'''/(u i12^3)``
    (:func:`driven_rates`). Evaluated block by block from one ``tan`` per point
    (:mod:`rotorkin.drives.guide_bar.kinematics_fused`; compiled loops when numba is
    installed, ``$ROTORKIN_KERNEL`` chooses).

    Returns
    -------
    tuple of 3 ndarray, shape (2, ...)
        ``dq/dtheta`` [-], ``d2q/dtheta2`` [1/rad], ``d3q/dtheta3`` [1/rad^2].
    """
    return tuple(_fused(params, theta, angles=False))


def impeller_angles(params: GuideBar, theta):
    """Impeller angles ``q_k = f(x_k)/u`` and their derivatives w.r.t. theta.

    ``f`` is :func:`guide_angle` (crank-driven) or :func:`crank_angle`
    (guide-driven); the derivatives are :func:`impeller_rates`. Evaluated block by
    block from one ``tan`` and two ``arctan`` per point
    (:mod:`rotorkin.drives.guide_bar.kinematics_fused`), the same values.

    Parameters
    ----------
    params : GuideBar
        Floats or arrays; they broadcast with ``theta``.
    theta : array_like
        Input gear angle [rad].

    Returns
    -------
    tuple of 4 ndarray, shape (2, ...)
        ``q`` [rad], ``dq/dtheta`` [-], ``d2q/dtheta2`` [1/rad], ``d3q/dtheta3`` [1/rad^2];
        ``...`` the broadcast shape of theta and the parameters.
    """
    return tuple(_fused(params, theta, angles=True))


def _guide_flag(driver):
    """True where the guide bars drive (``driver`` a name or an array of names), checked."""
    if isinstance(driver, str):
        if driver not in DRIVERS:
            raise ParameterError("driver", repr(driver), "one of " + ", ".join(map(repr, DRIVERS)))
        return driver == "guide"
    d = np.asarray(driver)
    if not np.all(np.isin(d, DRIVERS)):
        bad = d[~np.isin(d, DRIVERS)].flat[0]
        raise ParameterError("driver", repr(bad), "one of " + ", ".join(map(repr, DRIVERS)))
    return d == "guide"


def _fused(params: GuideBar, theta, angles: bool):
    """:func:`~rotorkin.drives.guide_bar.kinematics_fused.impellers_fused` of ``params``."""
    return impellers_fused(
        params.lam,
        params.gear_ratio,
        params.input_gear_ratio,
        params.phase,
        _guide_flag(params.driver),
        theta,
        angles=angles,
    )


def motion(params: GuideBar, theta) -> Motion:
    """Motion of impeller 1 and impeller 2 (``q`` [rad]) over input gear angle theta [rad]."""
    q, dq, d2q, d3q = impeller_angles(params, theta)
    theta = np.asarray(theta, dtype=float)
    if theta.shape != q.shape[1:]:
        theta = np.broadcast_to(theta, q.shape[1:])
    return Motion(theta, q, dq, d2q, d3q, members=("impeller 1", "impeller 2"), unit="rad")


def input_period(input_gear_ratio):
    """Input angle after which the speeds repeat: ``2 pi i12`` [rad] (the impellers gain 2 pi/u).

    A float, or an array when ``input_gear_ratio`` is one.
    """
    i12 = input_gear_ratio
    return 2.0 * np.pi * (float(i12) if np.ndim(i12) == 0 else np.asarray(i12, dtype=float))


def period(params: GuideBar):
    """:func:`input_period` of the drive's ``input_gear_ratio`` [rad]."""
    return input_period(params.input_gear_ratio)


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


def _vane_angle_crank(lam, u, a):
    return ((guide_angle(lam, a)[0] + guide_angle(lam, np.pi - a)[0]) / u,)


def _vane_angle_guide(lam, u, a):
    return ((2.0 * np.pi - crank_angle(lam, a)[0] - crank_angle(lam, np.pi - a)[0]) / u,)


def vane_angle(lam, u, phase, driver):
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
    driver : {"crank", "guide"} or array_like of str
        Broadcasts with the others.

    Returns
    -------
    ndarray
        gamma_0 [rad].
    """
    lam, u = np.asarray(lam, dtype=float), np.asarray(u, dtype=float)
    a = _half_phase(phase)
    return _by_driver(_vane_angle_crank, _vane_angle_guide, driver, lam, u, a)[0]


def vane_angle_paper(lam, u, phase, driver):
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

    def crank():
        return (lam + c) / np.sqrt(1.0 + 2.0 * lam * c + lam * lam), (lam - c) / np.sqrt(
            1.0 - 2.0 * lam * c + lam * lam
        )

    def guide():
        W = np.sqrt(1.0 - (lam * s) ** 2)
        return lam * s * s + c * W, lam * s * s - c * W

    clip = (np.clip(v, -1.0, 1.0) for v in _by_driver(crank, guide, driver))
    return sum(np.arccos(v) for v in clip) / u


def vane_angle_half_turn(lam, u, driver):
    """Vane angle at Sigma = 180 deg: eq. 5 (crank) or eq. 6 (guide) solved for gamma_0 [rad].

    Crank: ``gamma_0 = 2 arccos(lambda / sqrt(1 + lambda^2)) / u`` (eq. 5);
    guide: ``gamma_0 = 2 arccos(lambda) / u`` (eq. 6).
    """
    lam, u = np.asarray(lam, dtype=float), np.asarray(u, dtype=float)
    return _by_driver(
        lambda: (2.0 * np.arccos(lam / np.sqrt(1.0 + lam * lam)) / u,),
        lambda: (2.0 * np.arccos(lam) / u,),
        driver,
    )[0]


def lambda_for_vane_angle(gamma0, u, driver):
    """lambda that gives the vane angle gamma_0 at Sigma = 180 deg (eq. 5, 6 inverted).

    Crank: ``lambda = cot(u gamma_0 / 2)``, needs ``pi/4 < u gamma_0/2 < pi/2``;
    guide: ``lambda = cos(u gamma_0 / 2)``, needs ``0 < u gamma_0/2 < pi/2``.
    NaN where no ``0 < lambda < 1`` exists. Derived here.
    """
    half = 0.5 * np.asarray(u, dtype=float) * np.asarray(gamma0, dtype=float)

    def crank():
        ok = (half > np.pi / 4.0) & (half < np.pi / 2.0)
        safe = np.where(ok, half, np.pi / 3.0)
        return (np.where(ok, np.cos(safe) / np.sin(safe), np.nan),)

    def guide():
        ok = (half > 0.0) & (half < np.pi / 2.0)
        return (np.where(ok, np.cos(half), np.nan),)

    return _by_driver(crank, guide, driver)[0]


def relative_angle_swing(params: GuideBar):
    """Swing (max - min) of the angle between the impellers, ``q_2 - q_1``, over a turn [rad].

    The relative angle is stationary at the equal-speed points; between them
    one impeller turns ``gamma_0``, the other ``2 pi/u - gamma_0``, so the swing
    is ``2 pi/u - 2 gamma_0``. Derived here: it sets the chamber volume change.
    """
    g0 = vane_angle(params.lam, params.gear_ratio, params.phase, params.driver)
    return 2.0 * np.pi / np.asarray(params.gear_ratio, dtype=float) - 2.0 * g0


# --------------------------------------------------------------------------------------------
# torque (section 4)
# --------------------------------------------------------------------------------------------
def input_torque(params: GuideBar, m7, m8, theta):
    """Torque on input gear 1 by virtual work, ``M1 = M7 dq_1/dtheta + M8 dq_2/dtheta`` [N*m].

    Eq. 7 (crank-driven) and eq. 8 (guide-driven; garbled in the OCR) are this
    balance ``M1 omega_1 = M7 omega_7 + M8 omega_8``, friction and inertia
    neglected.

    Parameters
    ----------
    params : GuideBar
    m7, m8 : array_like
        Resisting torques on impeller 1 and 2 [N*m]; broadcast with theta.
    theta : array_like
        Input gear angle [rad].

    Returns
    -------
    ndarray
        M1 [N*m].
    """
    dq = impeller_rates(params, theta)[0]
    return np.asarray(m7, dtype=float) * dq[0] + np.asarray(m8, dtype=float) * dq[1]


def input_torque_eq7(lam, u, i12, m7, m8, x1, x2):
    """Crank-driven input torque as printed (eq. 7).

    ``M1 = (1 + l cos x1)/([1 + 2 l cos x1 + l^2] u i12) M7 + (same at x2) M8``,
    ``x_k = sigma_k + phi`` the crank angles [rad].
    """
    i12 = np.asarray(i12, dtype=float)
    return speed_ratio_eq1(lam, u, x1) / i12 * np.asarray(m7, dtype=float) + speed_ratio_eq1(
        lam, u, x2
    ) / i12 * np.asarray(m8, dtype=float)
