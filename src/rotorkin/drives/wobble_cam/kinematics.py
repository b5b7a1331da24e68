"""Wobble plate + spherical figure-eight cam: the differential drive of a twin-rotor engine.

Source: Chen Hu, Xu Haijun, Pan Cunyun, Zou Teng'an, Jiang Lei, "Kinematic
performance of new-type power transmission mechanism in twin-rotor piston
engine", J. National University of Defense Technology 37(5), 2015 (in Chinese).
Equation numbers below are the paper's.

The output shaft turns about the fixed x axis by ``theta``; its middle section
is tilted by the plate tilt ``phi``; the wobble plate spins on it by ``varphi``
(the *spin law*, ``varphi = spin_ratio * theta``, paper: ``-2 theta``); the cam
shell turns by ``psi = -theta``. Four radial roller shafts on the plate, in two
groups at ``roller_axis_angle = alpha`` to each other in the plate plane, drive
rotor 1 (group 1) and rotor 2 (group 2) through straight slider rails.

Conventions (the paper is silent on some):

* Fixed frame xyz, x along the output shaft. Frames follow eq. 2-5 and 9:
  ``r|0 = A_theta A_phi A_varphi r|3``, cam frame ``r|4 = A_psi^T r|0``.
* A point of the plate at angle ``c`` in the plate plane (from z3 towards y3)
  and radius r is ``r|3 = r [0, sin c, cos c]``; it is the eq.-8 point with
  ``varphi -> varphi + c``. Rollers: group 1 at ``c = -alpha/2, pi - alpha/2``,
  group 2 at ``c = +alpha/2, pi + alpha/2`` (eq. 12).
* Rotor angle ``Phi_k``: angle of group k's shaft projected on the yz plane,
  measured from +z towards +y (the direction in which positive ``theta`` turns
  the shaft frame). ``Phi_k = theta + E(varphi + s_k alpha/2)``,
  ``s_1 = -1, s_2 = +1``, ``E(u) = atan2(sin u, cos(phi) cos u)`` on its
  continuous branch. This per-rotor form is derived here; the paper gives only
  the angle between the rotors, eq. 15.
* Chambers (N pistons and 2 rails per rotor, eq. 18-19 generalised from the
  paper's N = 4): ``gamma = pi/4 - pi/(2N)`` (pi/8 at N = 4); rotor 1 pistons
  at ``Phi_1 + gamma + 2 pi k/N``, rotor 2 pistons at ``Phi_2 - gamma + 2 pi k/N``;
  chamber kind A (between a rotor-1 piston and the rotor-2 piston ahead of it)
  ``delta_A = alpha' - 2 gamma - beta``, kind B
  ``delta_B = 2 pi/N + 2 gamma - alpha' - beta``. N must be even: the two rails
  of a rotor are pi apart and eq. 18-19 need the pistons to repeat every pi.

Misprints of the paper: eq. 5 prints ``A_psi`` for ``A_theta``; eq. 8 and 11
print ``cos phi cos phi`` for ``cos(phi) cos(varphi)``; eq. 18's text says
``alpha'_2 = 90 deg - alpha'_1`` where the equation (right) says ``pi``. The
paper's symbols phi and varphi are swapped against ours in eq. 2-3 and 14-15
(the OCR's); here ``phi`` is always the plate tilt and ``varphi`` the spin.

The slider-angle limits and chamber angles (eq. 17-20,
:mod:`rotorkin.drives.wobble_cam.chambers`) and the fused fast path of the
kinematics (:mod:`rotorkin.drives.wobble_cam.fast`) live in their own modules;
every public name is importable from here. The piston offset gamma and the
chamber count are the machine's (:mod:`rotorkin.machines.twin_rotor`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.core.angles import angle_near, fmt_deg, fmt_mm
from rotorkin.core.batch import number, refuse_first
from rotorkin.core.errors import ParameterError
from rotorkin.core.motion import Motion
from rotorkin.drives.wobble_cam.chambers import (
    CHAMBERS,
    PISTON_OFFSET,
    chamber_angles,
    chamber_count,
    chamber_gaps,
    compression_ratio_violation,
    design_kind_a,
    max_plate_tilt,
    piston_offset,
    piston_width,
    slider_angle_extremes,
    slider_angle_limits,
    zero_width_ratio,
)
from rotorkin.drives.wobble_cam.fast import rotor_kinematics
from rotorkin.drives.wobble_cam.schema import PLATE_TILT_MIN, SPIN_RATIO_MAX
from rotorkin.machines.twin_rotor import check_pistons as _check_pistons
from rotorkin.machines.twin_rotor import first_violation

__all__ = [
    "CHECKED",
    "violation",
    "slowest_spin",
    "roller_axis_angle_limits",
    "chamber_gaps",
    "zero_width_ratio",
    "compression_ratio_violation",
    "design_kind_a",
    "piston_width",
    "PISTON_OFFSET",
    "CHAMBERS",
    "piston_offset",
    "chamber_count",
    "slider_angle_limits",
    "WobbleCam",
    "PistonLayout",
    "max_plate_tilt",
    "spin_angle",
    "spin_law",
    "cam_angle",
    "projected_angle",
    "rotor_angles_from_spin",
    "rotor_angles",
    "Kinematics",
    "kinematics",
    "motion",
    "period",
    "slider_angle",
    "slider_angle_extremes",
    "chamber_angles",
    "min_compression_ratio",
    "piston_layout",
    "roller_offsets",
    "roller_offsets_against",
    "plate_point",
    "groove_point",
    "roller_positions",
    "groove_points",
    "volume_cycles",
    "power_strokes",
    "volume_cycles_per_rev",
    "power_strokes_per_rev",
]


# --------------------------------------------------------------------------------------------
# parameters
# --------------------------------------------------------------------------------------------
#: Fields of :class:`WobbleCam` that :func:`violation` checks, in the order it checks them.
CHECKED = (
    "pistons_per_rotor",
    "roller_axis_angle",
    "plate_tilt",
    "spin_ratio",
    "sphere_radius",
    "spin_a",
)
#: Shaft angles on which a spin-law correction is checked for a monotone spin.
_SPIN_CHECK = np.linspace(0.0, 2.0 * np.pi, 4097)


def roller_axis_angle_limits(pistons=4):
    """Open range of the roller axis angle alpha admitting some plate tilt (eq. 20) [rad].

    ``pi/2 - pi/N < alpha < pi/2 + pi/N`` (45..135 deg at N = 4); broadcasts.
    """
    n = np.asarray(pistons, dtype=float)
    return np.pi / 2.0 - np.pi / n, np.pi / 2.0 + np.pi / n


def violation(
    plate_tilt,
    roller_axis_angle,
    spin_ratio,
    sphere_radius,
    pistons_per_rotor=4,
    spin_a=(),
    spin_b=(),
):
    """Which parameter of the drive is not admissible, per design.

    Parameters broadcast together (floats or arrays): plate tilt phi [rad],
    roller axis angle alpha [rad], spin ratio n [-], sphere radius r [m],
    pistons per rotor N [-].

    Returns
    -------
    ndarray of int16
        0 where admissible, else ``1 + CHECKED.index(name)`` of the first
        parameter (in the order of :data:`CHECKED`) out of range: N even and >= 2;
        alpha in :func:`roller_axis_angle_limits`; ``PLATE_TILT_MIN <= phi <
        max_plate_tilt(alpha, N)`` (0.5 deg, eq. 20); n a nonzero multiple of 0.5
        (the motion repeats every shaft turn) with ``|n| <= SPIN_RATIO_MAX``; r > 0;
        the correction ``spin_a``, ``spin_b`` (shared by all designs) keeps the spin monotone,
        ``sign(n) dvarphi/dtheta > 0`` on 4097 angles of a turn (:func:`slowest_spin`).
    """
    with np.errstate(invalid="ignore", divide="ignore"):
        n_p = np.asarray(pistons_per_rotor, dtype=float)
        ok_n = (n_p >= 2) & (n_p % 2 == 0)
        n_f = np.where(ok_n, n_p, 4.0)
        a = np.asarray(roller_axis_angle, dtype=float)
        lo, hi = roller_axis_angle_limits(n_f)
        p = np.asarray(plate_tilt, dtype=float)
        lim = max_plate_tilt(a, n_f)
        n = np.asarray(spin_ratio, dtype=float)
        twice = np.round(2.0 * n)
        half_int = (np.abs(n) <= SPIN_RATIO_MAX) & (twice != 0.0) & (np.abs(2.0 * n - twice) < 1e-9)
        r = np.asarray(sphere_radius, dtype=float)
        return first_violation(
            [
                ~ok_n,
                ~(np.isfinite(a) & (lo < a) & (a < hi)),
                ~(np.isfinite(p) & (p >= PLATE_TILT_MIN) & (p < lim)),
                ~half_int,
                ~(np.isfinite(r) & (r > 0.0)),
                ~(slowest_spin(n, spin_a, spin_b) > 0.0),
            ]
        )


def slowest_spin(spin_ratio, spin_a=(), spin_b=()):
    """Lowest ``sign(n) dvarphi/dtheta`` over a turn (4097 angles): > 0 for a monotone spin [-].

    ``|n| + min(sign(n) c'(theta))`` with the correction ``c`` of :func:`spin_angle`;
    broadcasts over ``spin_ratio`` (the correction is shared).
    """
    n = np.asarray(spin_ratio, dtype=float)
    if not (len(spin_a) or len(spin_b)):
        return np.abs(n)
    rate = spin_angle(0.0, spin_a, spin_b, _SPIN_CHECK)[1]
    return np.abs(n) + np.where(n > 0.0, np.min(rate), -np.max(rate))


def _raise_violation(params, name):
    """ParameterError naming the field ``name`` of ``params``, its value and its range."""
    n_p = params.pistons_per_rotor
    a = float(params.roller_axis_angle)
    if name == "roller_axis_angle":
        lo, hi = (float(x) for x in roller_axis_angle_limits(n_p))
        raise ParameterError(
            name,
            fmt_deg(a),
            f"{fmt_deg(lo)} < roller_axis_angle < {fmt_deg(hi)} (eq. 20: beyond, no plate "
            f"tilt is admissible for {n_p}-piston rotors)",
        )
    if name == "plate_tilt":
        lim = float(max_plate_tilt(a, n_p))
        raise ParameterError(
            name,
            fmt_deg(float(params.plate_tilt)),
            f"0.5 deg <= plate_tilt < {np.degrees(lim):.2f} deg (eq. 20 limit at "
            f"roller_axis_angle = {fmt_deg(a)}, {n_p} pistons per rotor)",
        )
    if name == "spin_ratio":
        raise ParameterError(
            name,
            f"{float(params.spin_ratio):g}",
            f"a nonzero multiple of 0.5 with |spin_ratio| <= {SPIN_RATIO_MAX:g} (e.g. -2, the "
            "paper's law), so that the motion repeats every shaft turn",
        )
    if name == "sphere_radius":
        raise ParameterError(name, fmt_mm(float(params.sphere_radius)), "sphere_radius > 0 mm")
    if name == "spin_a":
        low = float(slowest_spin(params.spin_ratio, params.spin_a, params.spin_b))
        raise ParameterError(
            "spin_a",
            f"{list(params.spin_a)} (spin_b = {list(params.spin_b)})",
            "a correction that keeps the spin monotone: sign(spin_ratio) dvarphi/dtheta "
            f"> 0 everywhere (lowest here {low:.4g})",
        )
    _check_pistons(n_p)  # pistons_per_rotor: raises


@dataclass(frozen=True)
class WobbleCam:
    """Parameters of the wobble-plate + spherical-cam drive (SI).

    Parameters
    ----------
    plate_tilt : float
        Tilt phi of the shaft's middle section (the plate axis) [rad];
        ``0 < phi < max_plate_tilt(roller_axis_angle)`` (eq. 20). Table 1: 45 deg.
    roller_axis_angle : float, optional
        Angle alpha between the two roller groups in the plate plane [rad];
        ``pi/4 < alpha < 3 pi/4``. Table 1: 90 deg (default).
    spin_ratio : float, optional
        n in the spin law ``varphi = n theta`` (plate spin relative to the
        tilted shaft section); a nonzero multiple of 0.5 so that the motion
        repeats every shaft turn. Paper: -2 (default).
    sphere_radius : float, optional
        Radius r of the inner roller centres, i.e. of the groove centre-line
        sphere [m] (default 0.06, the config default; the paper gives no value).
    pistons_per_rotor : int, optional
        Pistons N on each rotor, even, >= 2 (paper: 4, default). It only sets the
        interference limits of eq. 20 (and the chamber bookkeeping).
    spin_a, spin_b : tuple of float, optional
        Periodic correction of the spin law (not in the paper; for synthesis):
        ``varphi = n theta + sum_k a_k cos(k theta) + b_k sin(k theta)``,
        ``k = 1, 2, ...`` [rad]. Empty (default): the paper's linear law.
    """

    plate_tilt: float
    roller_axis_angle: float = np.pi / 2.0
    spin_ratio: float = -2.0
    sphere_radius: float = 0.06
    pistons_per_rotor: int = 4
    spin_a: tuple = ()
    spin_b: tuple = ()

    def __post_init__(self):
        _check_pistons(self.pistons_per_rotor)
        args = (self.plate_tilt, self.roller_axis_angle, self.spin_ratio, self.sphere_radius)
        coeffs = {
            k: np.asarray(getattr(self, k), dtype=float).ravel() for k in ("spin_a", "spin_b")
        }
        finite = all(np.all(np.isfinite(c)) for c in coeffs.values())
        # one pass over the fields in CHECKED's order; the spin law's monotony last, and
        # only with finite coefficients
        law = (coeffs["spin_a"], coeffs["spin_b"]) if finite else ((), ())
        self._refuse(violation(*args, self.pistons_per_rotor, *law))
        for name, c in coeffs.items():
            if not np.all(np.isfinite(c)):
                raise ParameterError(name, str(list(c)), "finite coefficients [rad]")
            object.__setattr__(self, name, tuple(float(v) for v in c))

    def _refuse(self, code) -> None:
        """Raise the error of the first refused field (of the first refused design: the
        fields may be columns of designs, one number of pistons)."""
        if np.ndim(code):
            refuse_first(self, code)
        elif code:
            _raise_violation(self, CHECKED[int(code) - 1])


# --------------------------------------------------------------------------------------------
# laws of the plate and the cam
# --------------------------------------------------------------------------------------------
def spin_angle(spin_ratio, spin_a, spin_b, theta):
    """Plate spin ``varphi(theta)`` and its derivatives (paper: ``varphi = -2 theta``).

    ``varphi = n theta + c(theta)``, with the periodic correction
    ``c = sum_k a_k cos(k theta) + b_k sin(k theta)`` (k = 1, 2, ...; empty for
    the paper's law). The correction is 2 pi periodic, so the motion still
    repeats every shaft turn.

    Parameters
    ----------
    spin_ratio : float or array_like
        n [-]; an array broadcasts with ``theta`` (e.g. shape (k, 1) against (m,)).
    spin_a, spin_b : sequence of float
        ``a_k``, ``b_k`` [rad] (may be empty).
    theta : array_like
        Shaft angle [rad].

    Returns
    -------
    tuple of 4 ndarray
        ``varphi`` [rad], ``dvarphi/dtheta`` [-], ``d2``, ``d3`` [1/rad, 1/rad^2]
        (the last two are zero for the linear law), of the broadcast shape.
    """
    theta = np.asarray(theta, dtype=float)
    n = np.asarray(spin_ratio, dtype=float)
    zero = np.zeros(np.broadcast_shapes(n.shape, theta.shape))
    out = [n * theta + zero, zero + n, zero.copy(), zero.copy()]
    for coeffs, phase in ((spin_a, 0.0), (spin_b, -0.5 * np.pi)):
        # a cos(k t + phase): a sin term is a cos term shifted by -pi/2
        for k, amp in enumerate(coeffs, start=1):
            if amp == 0.0:
                continue
            arg = k * theta + phase
            c, s = np.cos(arg), np.sin(arg)
            out[0] = out[0] + amp * c
            out[1] = out[1] - amp * k * s
            out[2] = out[2] - amp * k * k * c
            out[3] = out[3] + amp * k**3 * s
    return tuple(out)


def spin_law(params: WobbleCam, theta):
    """Plate spin ``varphi(theta)`` and its derivatives under the params' spin law.

    :func:`spin_angle` with ``params.spin_ratio``, ``spin_a``, ``spin_b``.
    """
    return spin_angle(params.spin_ratio, params.spin_a, params.spin_b, theta)


def cam_angle(theta):
    """Cam shell angle ``psi = -theta`` (bevel gearbox, equal and opposite) [rad]."""
    return -np.asarray(theta, dtype=float)


def projected_angle(plate_tilt, u):
    """Angle of a plate radius projected on the shaft frame's y1z1 plane, and derivatives.

    A plate radius at angle ``u`` in the plate plane (from z2 towards y2) seen
    along the shaft axis makes the angle ``E(u) = atan2(sin u, cos(phi) cos u)``
    with z1 (eq. 14 with theta = 0). We use the branch that is continuous in u,

    ``E = u + atan2((1 - c) sin u cos u, sin^2 u + c cos^2 u)``, ``c = cos(phi)``,

    (the second term stays within (-pi/2, pi/2) since c > 0; this is
    :func:`rotorkin.core.angles.angle_near` with reference u), so ``E(u + pi) = E(u) + pi``.
    Derivatives, with ``D = sin^2 u + c^2 cos^2 u = (1 + c^2)/2 - (1 - c^2)/2 cos 2u``:
    ``E' = c/D``, ``E'' = -c D'/D^2``, ``E''' = -c D''/D^2 + 2 c D'^2/D^3``.

    Parameters
    ----------
    plate_tilt : array_like
        phi [rad], ``0 <= phi < pi/2``.
    u : array_like
        Angle in the plate plane [rad] (broadcast with ``plate_tilt``).

    Returns
    -------
    tuple of 4 ndarray
        ``E`` [rad], ``dE/du`` [-], ``d2E/du2`` [1/rad], ``d3E/du3`` [1/rad^2].
    """
    u = np.asarray(u, dtype=float)
    c = np.cos(np.asarray(plate_tilt, dtype=float))
    su, cu = np.sin(u), np.cos(u)
    # = u + atan2((1 - c) sin u cos u, sin^2 u + c cos^2 u): the vector measured from angle u
    e0 = angle_near(su, c * cu, u)
    a, b = 0.5 * (1.0 + c * c), 0.5 * (1.0 - c * c)
    s2, c2 = np.sin(2.0 * u), np.cos(2.0 * u)
    d0 = a - b * c2
    d1 = 2.0 * b * s2
    d2 = 4.0 * b * c2
    e1 = c / d0
    e2 = -c * d1 / d0**2
    e3 = -c * d2 / d0**2 + 2.0 * c * d1**2 / d0**3
    return e0, e1, e2, e3


def rotor_angles_from_spin(plate_tilt, roller_axis_angle, spin, theta, *, threads=None):
    """Angles of both rotors and their derivatives, for any spin law (eq. 13-14).

    ``Phi_k = theta + E(u_k)``, ``u_k = varphi(theta) + s_k alpha/2``,
    ``s_1 = -1``, ``s_2 = +1`` (see :func:`projected_angle`); the chain rule
    (Faa di Bruno, as :func:`rotorkin.core.motion.compose`) gives the derivatives from
    those of the spin law, so a spin law with a periodic correction only needs
    its value and three derivatives. Evaluated by the fused, blocked fast path
    :func:`rotorkin.drives.wobble_cam.fast.rotor_kinematics` (4 transcendental
    calls per point, no temporaries of the full size).

    Parameters
    ----------
    plate_tilt, roller_axis_angle : float or array_like
        phi and alpha [rad] (broadcast with ``theta``).
    spin : sequence of 4 array_like, or float
        ``varphi, varphi', varphi'', varphi'''`` at ``theta`` [rad, -, 1/rad, 1/rad^2];
        a number n stands for the linear law ``varphi = n theta``.
    theta : array_like, shape (...)
        Shaft angle [rad].
    threads : int, optional
        Threads for large arrays (default ``$ROTORKIN_THREADS`` or 1); the
        values do not depend on it.

    Returns
    -------
    tuple of 4 ndarray, shape (2, ...)
        ``Phi``, ``dPhi/dtheta``, ``d2Phi/dtheta2``, ``d3Phi/dtheta3`` of
        rotor 1 (index 0) and rotor 2 (index 1) [rad, -, 1/rad, 1/rad^2].
        Angles are measured in the yz plane from +z towards +y; at theta = 0
        and varphi = 0 rotor 1 is at ``-alpha'_max/2``, rotor 2 at ``+alpha'_max/2``.
    """
    rotor, _ = rotor_kinematics(plate_tilt, roller_axis_angle, spin, theta, threads=threads)
    return tuple(rotor)


def _spin(params: WobbleCam, theta):
    """The spin law as :func:`rotor_kinematics` takes it: n when linear, else 4 arrays."""
    if params.spin_a or params.spin_b:
        return spin_law(params, theta)
    return float(params.spin_ratio)


def rotor_angles(params: WobbleCam, theta, *, threads=None):
    """Rotor angles and derivatives under the params' spin law.

    See :func:`rotor_angles_from_spin`; returns 4 arrays of shape ``(2, *theta.shape)``.
    """
    theta = np.asarray(theta, dtype=float)
    return rotor_angles_from_spin(
        params.plate_tilt, params.roller_axis_angle, _spin(params, theta), theta, threads=threads
    )


@dataclass(frozen=True)
class Kinematics:
    """Rotor angles, their three derivatives and the chamber angles (see :func:`kinematics`).

    Attributes
    ----------
    q, dq, d2q, d3q : ndarray, shape (2, ...)
        ``Phi_k`` and its derivatives with respect to theta, rotor 1 at index 0
        [rad, -, 1/rad, 1/rad^2].
    chamber_a, chamber_b : ndarray, shape (...)
        ``delta_A``, ``delta_B`` [rad] (eq. 18-19, :func:`chamber_angles`).
    """

    q: np.ndarray
    dq: np.ndarray
    d2q: np.ndarray
    d3q: np.ndarray
    chamber_a: np.ndarray
    chamber_b: np.ndarray

    @property
    def slider(self) -> np.ndarray:
        """Slider angle ``alpha' = Phi_2 - Phi_1`` [rad] (eq. 15)."""
        return self.q[1] - self.q[0]


def kinematics(params: WobbleCam, theta, piston_width, *, threads=None) -> Kinematics:
    """Rotor angles, derivatives and chamber angles of both kinds, in one fused pass.

    The same values as :func:`rotor_angles` followed by
    ``chamber_angles(piston_width, q[1] - q[0], pistons=pistons_per_rotor)``, computed
    block by block (:func:`rotorkin.drives.wobble_cam.fast.rotor_kinematics`).

    Parameters
    ----------
    params : WobbleCam
    theta : array_like, shape (...)
        Shaft angle [rad].
    piston_width : float or array_like
        beta [rad] (e.g. ``piston_layout(params, eps).piston_width``).
    threads : int, optional
        Threads for large arrays (default ``$ROTORKIN_THREADS`` or 1).
    """
    theta = np.asarray(theta, dtype=float)
    rotor, cham = rotor_kinematics(
        params.plate_tilt,
        params.roller_axis_angle,
        _spin(params, theta),
        theta,
        chamber=(piston_width, params.pistons_per_rotor),
        threads=threads,
    )
    return Kinematics(*rotor, *cham)


def motion(params: WobbleCam, theta) -> Motion:
    """Motion of rotor 1 and rotor 2 (``q = (Phi_1, Phi_2)`` [rad]) over shaft angle theta."""
    theta = np.asarray(theta, dtype=float)
    q, dq, d2q, d3q = rotor_angles(params, theta)
    return Motion(theta, q, dq, d2q, d3q, members=("rotor 1", "rotor 2"), unit="rad")


def period(params: WobbleCam) -> float:
    """Shaft angle after which the motion repeats: 2 pi [rad].

    With a spin ratio that is a multiple of 0.5, each rotor has then turned by
    ``2 pi (1 + n)``, a multiple of pi, which maps its 2 rails and 4 pistons
    onto themselves; all derivatives are 2 pi periodic (in fact ``pi/|n|``).
    """
    return 2.0 * np.pi


# --------------------------------------------------------------------------------------------
# slider angle
# --------------------------------------------------------------------------------------------
def slider_angle(plate_tilt, roller_axis_angle, spin_angle):
    """Angle alpha' between the rails of rotor 1 and rotor 2 (eq. 15) [rad].

    ``alpha' = Phi_2 - Phi_1 = E(varphi + alpha/2) - E(varphi - alpha/2)``; it
    depends on the spin angle only (period pi) and lies in (0, pi). Same value
    as the paper's arccos form, eq. 15, without its loss of sign and precision.

    Parameters
    ----------
    plate_tilt, roller_axis_angle : array_like
        phi and alpha [rad].
    spin_angle : array_like
        Plate spin varphi [rad] (all three broadcast together).
    """
    half = 0.5 * np.asarray(roller_axis_angle, dtype=float)
    v = np.asarray(spin_angle, dtype=float)
    return projected_angle(plate_tilt, v + half)[0] - projected_angle(plate_tilt, v - half)[0]


# --------------------------------------------------------------------------------------------
# roller trajectories and groove centre-lines
# --------------------------------------------------------------------------------------------
def roller_offsets(roller_axis_angle):
    """Angles c of the 4 rollers in the plate plane (from z3 towards y3) [rad], shape (4,).

    Order: group 1 (``-alpha/2``, ``pi - alpha/2``), group 2 (``alpha/2``,
    ``pi + alpha/2``); roller 1 is index 0 (eq. 12).
    """
    h = 0.5 * np.asarray(roller_axis_angle, dtype=float)
    return np.stack([-h, np.pi - h, h, np.pi + h])


def roller_offsets_against(params: WobbleCam, theta):
    """:func:`roller_offsets` of ``params`` shaped to broadcast against its points at ``theta``.

    Shape (4, 1, ...) with the axes of ``theta`` and of the drive's fields broadcast: (4, 1)
    for one design against angles (n,), (4, d, 1) or (4, 1, 1) for columns of designs
    (fields of shape (d, 1)) against them.
    """
    c = roller_offsets(params.roller_axis_angle)
    fields = (params.plate_tilt, params.roller_axis_angle, params.sphere_radius)
    shape = np.broadcast_shapes(np.shape(theta), *(np.shape(v) for v in fields))
    return c.reshape(c.shape[:1] + (1,) * (len(shape) - (c.ndim - 1)) + c.shape[1:])


def plate_point(plate_tilt, radius, theta, spin_angle, offset):
    """Plate point at angle ``offset`` and ``radius``, in the fixed frame (eq. 7-8) [m].

    ``r|0 = A_theta A_phi A_varphi r [0, sin c, cos c]
    = r [sin(phi) cos u, cos(theta) sin u + sin(theta) cos(phi) cos u,
    -sin(theta) sin u + cos(theta) cos(phi) cos u]``, ``u = varphi + c``.

    Parameters
    ----------
    plate_tilt : array_like
        phi [rad].
    radius : array_like
        r [m].
    theta, spin_angle, offset : array_like
        Shaft angle theta, plate spin varphi and the point's angle c in the plate
        plane [rad]; all five arguments broadcast together.

    Returns
    -------
    ndarray, shape (3, ...)
        x, y, z of the broadcast inputs.
    """
    theta = np.asarray(theta, dtype=float)
    u = np.asarray(spin_angle, dtype=float) + offset
    sp, cp = np.sin(plate_tilt), np.cos(plate_tilt)
    su, cu = np.sin(u), np.cos(u)
    st, ct = np.sin(theta), np.cos(theta)
    x = sp * cu
    y = ct * su + st * cp * cu
    z = -st * su + ct * cp * cu
    return radius * np.stack(np.broadcast_arrays(x, y, z))


def groove_point(plate_tilt, radius, theta, cam, spin_angle, offset):
    """The plate point of :func:`plate_point` seen in the cam frame (eq. 10-11) [m].

    ``r|4 = A_psi^T r|0``; the first two rotations combine to ``A_(theta - psi)``.
    With ``psi = -theta`` and ``varphi = -2 theta`` it closes after ``theta = pi``.
    Arguments as :func:`plate_point`, with the cam angle psi [rad] after theta.

    Returns
    -------
    ndarray, shape (3, ...)
    """
    return plate_point(
        plate_tilt,
        radius,
        np.asarray(theta, dtype=float) - np.asarray(cam, dtype=float),
        spin_angle,
        offset,
    )


def _per_roller(params: WobbleCam, theta):
    theta = np.asarray(theta, dtype=float)
    c = roller_offsets_against(params, theta)
    return theta, spin_law(params, theta)[0], c


def roller_positions(params: WobbleCam, theta):
    """Inner-roller centres of the 4 rollers in the fixed frame (Fig. 8) [m].

    Returns
    -------
    ndarray, shape (4, 3, ...)
        Roller (order of :func:`roller_offsets`), coordinate x y z, ``theta``'s shape.
    """
    theta, v, c = _per_roller(params, theta)
    p = plate_point(params.plate_tilt, params.sphere_radius, theta, v, c)
    return np.moveaxis(p, 0, 1)


def groove_points(params: WobbleCam, theta):
    """Groove centre-line points of the 4 rollers in the cam frame (Fig. 9) [m].

    Returns
    -------
    ndarray, shape (4, 3, ...)
    """
    theta, v, c = _per_roller(params, theta)
    p = groove_point(params.plate_tilt, params.sphere_radius, theta, cam_angle(theta), v, c)
    return np.moveaxis(p, 0, 1)


# --------------------------------------------------------------------------------------------
# pistons for a design compression ratio (eq. 21-22), cycle counts
# --------------------------------------------------------------------------------------------
def _gaps(params: WobbleCam):
    """Smallest and largest centre-line gap of chamber kinds A and B [rad] (floats; arrays
    for columns of designs)."""
    g = chamber_gaps(params.plate_tilt, params.roller_axis_angle, params.pistons_per_rotor)
    return tuple((number(lo), number(hi)) for lo, hi in g)


def min_compression_ratio(params: WobbleCam) -> float:
    """Compression ratio reached with zero-width pistons; any design ratio must exceed it.

    The piston width beta of :func:`piston_layout` is positive iff
    ``eps > g_max / g_min``, the ratio of the largest to the smallest
    centre-line gap of the tighter chamber kind
    (:func:`rotorkin.drives.wobble_cam.chambers.zero_width_ratio`).
    """
    return float(zero_width_ratio(_gaps(params)))


@dataclass(frozen=True)
class PistonLayout:
    """Piston width and chamber extremes for a design compression ratio.

    Attributes
    ----------
    compression_ratio : float
        Design ratio eps, reached by the tighter chamber kind.
    piston_width : float
        beta [rad].
    chamber_a_min, chamber_a_max, chamber_b_min, chamber_b_max : float
        Extremes of delta_A and delta_B [rad].
    compression_ratio_a, compression_ratio_b : float
        ``delta_max / delta_min`` of each kind.
    design_kind : str
        ``"A"`` or ``"B"``: the kind with the smaller minimum (ratio = eps).
    """

    compression_ratio: float
    piston_width: float
    chamber_a_min: float
    chamber_a_max: float
    chamber_b_min: float
    chamber_b_max: float
    compression_ratio_a: float
    compression_ratio_b: float
    design_kind: str

    @property
    def swing(self) -> float:
        """``delta_max - delta_min = alpha'_max - alpha'_min`` (eq. 23) [rad]."""
        return self.chamber_a_max - self.chamber_a_min


def piston_layout(params: WobbleCam, compression_ratio: float, width=None) -> PistonLayout:
    """Piston width beta giving the design compression ratio (eq. 21-22, generalised).

    The chamber kind with the smaller minimum angle gets exactly
    ``eps = delta_max/delta_min`` (volume proportional to angle, no clearance
    volume): with its centre-line gaps ``g_min, g_max``,
    ``beta = (eps g_min - g_max) / (eps - 1)``. At ``alpha = 90 deg`` both kinds
    coincide (``alpha'_max + alpha'_min = pi``) and this is eq. 21 (N = 4),
    ``beta = (eps+1)/(eps-1) alpha'_min - pi (eps+3) / (4 (eps-1))``; for N pistons
    ``beta = (eps+1)/(eps-1) alpha'_min - (pi + (eps-1)(pi/2 - pi/N)) / (eps-1)``. For other
    alpha the paper's eq. 21 does not hold (it assumes
    ``alpha'_max + alpha'_min = pi``); the other kind then has a lower ratio
    (Fig. 11).

    Parameters
    ----------
    params : WobbleCam
    compression_ratio : float
        eps, ``min_compression_ratio(params) < eps < inf``.

    For columns of designs (``params`` holding arrays, ``compression_ratio`` one or an
    array) every field is an array of the designs, ``design_kind`` an array of "A"/"B".
    With ``width`` (pistons as manufactured, e.g. a tolerance analysis holding the nominal
    width) beta is that width and the compression ratio the one it gives.

    Raises
    ------
    ParameterError
        named ``"compression_ratio"`` when eps is not admissible (of the first such design).
    """
    eps, fixed = number(compression_ratio), width
    ga, gb = _gaps(params)
    bad = compression_ratio_violation((ga, gb), eps) if fixed is None else False
    if np.any(bad):
        lo_ratio = zero_width_ratio((ga, gb))
        first = np.unravel_index(np.argmax(bad), np.shape(bad))
        raise ParameterError(
            "compression_ratio",
            f"{float(np.broadcast_to(eps, np.shape(bad))[first]):g}",
            f"compression_ratio > {float(np.broadcast_to(lo_ratio, np.shape(bad))[first]):.4g} "
            "(the ratio of zero-width pistons at this plate tilt and roller axis angle; a "
            "smaller one needs a negative piston width, eq. 21)",
        )
    kind_a = design_kind_a((ga, gb))
    kind = ("A" if kind_a else "B") if np.ndim(kind_a) == 0 else np.where(kind_a, "A", "B")
    beta = number(piston_width((ga, gb), eps) if fixed is None else fixed)
    if fixed is not None:  # the design kind's ratio at this width
        lo, hi = np.where(kind_a, ga[0], gb[0]) - beta, np.where(kind_a, ga[1], gb[1]) - beta
        eps = number(hi / lo)
    a = (ga[0] - beta, ga[1] - beta)
    b = (gb[0] - beta, gb[1] - beta)
    return PistonLayout(
        compression_ratio=eps,
        piston_width=beta,
        chamber_a_min=a[0],
        chamber_a_max=a[1],
        chamber_b_min=b[0],
        chamber_b_max=b[1],
        compression_ratio_a=a[1] / a[0],
        compression_ratio_b=b[1] / b[0],
        design_kind=kind,
    )


# --------------------------------------------------------------------------------------------
# counts
# --------------------------------------------------------------------------------------------
def volume_cycles(spin_ratio):
    """Volume cycles of each chamber per shaft turn, ``2 |n|`` (alpha' has period pi in varphi).

    Paper section 1.2 and 4.2.3: 4 at n = -2. Broadcasts over ``spin_ratio`` [-];
    whole numbers (as floats) for the admissible multiples of 0.5.
    """
    return np.round(2.0 * np.abs(np.asarray(spin_ratio, dtype=float)))


def power_strokes(spin_ratio, pistons=4, strokes_per_cycle=4):
    """Power strokes per shaft turn: ``2N chambers x 2 |n| / (strokes_per_cycle / 2)``.

    A four-stroke cycle takes two volume cycles: 16 at N = 4, n = -2 (paper
    section 1.2). Broadcasts over ``spin_ratio`` and ``pistons``.
    """
    chambers = 2.0 * np.asarray(pistons, dtype=float)
    return np.round(chambers * volume_cycles(spin_ratio) * 2 / strokes_per_cycle)


def volume_cycles_per_rev(params: WobbleCam) -> int:
    """:func:`volume_cycles` of the params' spin ratio, an int."""
    return int(volume_cycles(params.spin_ratio))


def power_strokes_per_rev(params: WobbleCam, strokes_per_cycle: int = 4) -> int:
    """:func:`power_strokes` of the params, an int (16 at N = 4, n = -2)."""
    return int(power_strokes(params.spin_ratio, params.pistons_per_rotor, strokes_per_cycle))
