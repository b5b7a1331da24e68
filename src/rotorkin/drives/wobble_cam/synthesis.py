"""Wobble-plate + spherical cam: spin laws for a target chamber-angle law.

Chen Hu et al. 2015 (``papers/wobble_cam.md``) use the spin law
``varphi = -2 theta`` (the cam grooves impose it) and note that other laws are
possible. The drive accepts a periodic correction
``varphi = n theta + sum_k a_k cos k theta + b_k sin k theta``
(:class:`rotorkin.drives.wobble_cam.kinematics.WobbleCam`, ``spin_a``, ``spin_b``). The
slider angle ``alpha'`` - and with it every chamber angle ``delta`` (eq. 18-19) -
depends on theta only through ``varphi``, so a target law ``alpha'(theta)`` is
met by solving ``alpha'(varphi) = alpha'_target`` for ``varphi`` on each
monotone branch, then fitting the correction ``varphi - n theta`` by FFT.

Inverse in closed form (derived here, checked in the tests): with
``c = cos(phi)`` and ``h = alpha/2``, eq. 15 gives
``cot alpha' = [(c^2 - 1) cos 2 varphi + (c^2 + 1) cos 2h] / (2 c sin 2h)``, so
``alpha'`` rises with ``cos 2 varphi`` and, with the extremes
``alpha'_max = alpha'(0)``, ``alpha'_min = alpha'(pi/2)`` (eq. 17),

    tan^2 v = sin(alpha'_max - alpha') sin(alpha'_min) / (sin(alpha' - alpha'_min) sin(alpha'_max))

for ``v`` in [0, pi/2] (``|varphi|`` reduced to the branch). Written with the
distances to the extremes it keeps full precision at the extremes, where
``varphi`` is ill-determined by ``alpha'`` itself.

Target laws (one family): ``alpha'_target = alpha'_min + (alpha'_max - alpha'_min) cos^2(P/2)``
with a *chamber phase* ``P(theta)`` that grows by 2 pi per chamber cycle, P = 0
at the largest slider angle (the paper's law has it at ``theta = 0``):

* ``sine_chamber``: ``P = 2|n| theta``; every chamber angle is a pure sine of theta
  between the paper's extremes,
  ``delta = delta_min + (delta_max - delta_min)(1 + cos 2|n| theta)/2``.
* ``dwell_min_volume``: ``P' = 2|n| [r + (1 - r) G(2x)]``, ``x = 2|n| theta``,
  ``G(y) = (8/3) sin^4(y/2) = 1 - (4/3) cos y + (1/3) cos 2y`` (mean 1), i.e.
  ``P = x - (1 - r)(2/3) sin 2x + (1 - r)/12 sin 4x``: near each extreme of the
  slider angle the chamber phase runs at ``r`` times its mean rate, and that rate
  is flat there to third order (``P'' = P''' = P'''' = 0``), so the chamber lingers
  near its minimum volume. Because ``delta_A + delta_B`` is constant (eq. 18), the
  minimum of one chamber kind is the maximum of the other: to give *every*
  chamber a longer dwell at minimum volume the law slows at both extremes (and so
  also dwells at maximum volume). ``r`` is solved so that the dwell fraction (the
  share of a chamber cycle within :data:`~rotorkin.synthesis.DWELL_TOLERANCE` of
  the swing from the minimum) equals ``--target``.

An exactly flat bottom (``delta`` constant over an interval) would need the
plate to stop spinning (``varphi' = 0`` on an interval), which the drive refuses
(its spin must stay strictly monotone) and no finite Fourier correction
represents; the laws above are analytic, so their corrections converge
geometrically and a few dozen nonzero harmonics reproduce them to ~1e-12 deg.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from rotorkin.core.errors import ParameterError
from rotorkin.core.schema import validate_model
from rotorkin.drives.wobble_cam import cam as cs
from rotorkin.drives.wobble_cam import figures_synthesis, schema, study
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.synthesis import (
    DWELL_TOLERANCE,
    SynthesisResult,
    dwell_fraction,
    parse_fraction,
    synthesized_raw_config,
)

__all__ = [
    "TARGETS",
    "SLOW_MIN",
    "chamber_phase",
    "target_slider_angle",
    "spin_for_slider_angle",
    "fit_spin_correction",
    "spin_law_for_target",
    "dwell_fractions",
    "slow_for_dwell",
    "synthesize",
]

TARGETS = ("sine_chamber", "dwell_min_volume")
#: Smallest rate ratio r of the dwell law (the chamber phase at 5 % of its mean rate).
SLOW_MIN = 0.05
#: Samples per shaft turn of the FFT fit.
_FFT_SAMPLES = 16384
#: Coefficients below this are dropped [rad].
_DROP = 1e-14
#: Samples per period for the measured (dwell, peaks) quantities.
_FINE = 20_000


def chamber_phase(spin_ratio, slow, theta):
    """Chamber phase ``P(theta)`` of the target laws and ``dP/dtheta``.

    ``P = x - (1 - r)(2/3) sin 2x + (1 - r)/12 sin 4x``, ``x = 2|n| theta``
    (``r = slow``; ``r = 1``: the uniform phase of ``sine_chamber``).

    Parameters
    ----------
    spin_ratio : float
        n of the base law ``varphi = n theta``.
    slow : float
        Rate ratio r at the extremes, ``0 < r <= 1`` (1: the uniform phase).
    theta : array_like
        Shaft angle [rad].

    Returns
    -------
    (P, dP) : tuple of ndarray
        [rad], [-].
    """
    k = 2.0 * abs(float(spin_ratio))
    x = k * np.asarray(theta, dtype=float)
    w = 1.0 - float(slow)
    P = x - w * (2.0 / 3.0) * np.sin(2.0 * x) + (w / 12.0) * np.sin(4.0 * x)
    dP = k * (1.0 - w * (4.0 / 3.0) * np.cos(2.0 * x) + (w / 3.0) * np.cos(4.0 * x))
    return P, dP


def target_slider_angle(spin_ratio, plate_tilt, roller_axis_angle, slow, theta):
    """Target slider angle ``alpha'_min + swing cos^2(P/2)`` and its distances to the extremes.

    Parameters
    ----------
    spin_ratio : float
        n of the base law.
    plate_tilt, roller_axis_angle : float
        phi and alpha [rad].
    slow : float
        Rate ratio r of :func:`chamber_phase`.
    theta : array_like
        Shaft angle [rad].

    Returns
    -------
    (alpha, above_min, below_max, P) : tuple of ndarray
        ``alpha'`` [rad], ``alpha' - alpha'_min`` and ``alpha'_max - alpha'`` (each to
        full relative precision) [rad], the chamber phase P [rad].
    """
    amax, amin = (float(v) for v in wc.slider_angle_extremes(plate_tilt, roller_axis_angle))
    swing = amax - amin
    P = chamber_phase(spin_ratio, slow, theta)[0]
    above = swing * np.cos(0.5 * P) ** 2
    below = swing * np.sin(0.5 * P) ** 2
    return amin + above, above, below, P


def spin_for_slider_angle(above_min, below_max, phase, spin_ratio, plate_tilt, roller_axis_angle):
    """Spin angle ``varphi`` giving a slider angle, on the branch fixed by the chamber phase.

    Closed-form inverse of eq. 15 (module doc):
    ``v = atan2(sqrt(sin(alpha'_max - alpha') sin alpha'_min), sqrt(sin(alpha' - alpha'_min)
    sin alpha'_max))`` in [0, pi/2]; on branch ``k = floor(P/pi)`` the spin magnitude is
    ``k pi/2 + v`` (k even: from a maximum to a minimum) or ``(k + 1) pi/2 - v`` (k odd),
    with the sign of n.

    Parameters
    ----------
    above_min, below_max : array_like
        ``alpha' - alpha'_min >= 0`` and ``alpha'_max - alpha' >= 0`` [rad].
    phase : array_like
        Chamber phase P [rad], continuous and increasing, ``P = k pi`` at the extremes.
    spin_ratio : float
        n (its sign is the sense of the spin).
    plate_tilt, roller_axis_angle : float
        phi, alpha [rad].

    Returns
    -------
    ndarray
        varphi [rad].
    """
    amax, amin = (float(v) for v in wc.slider_angle_extremes(plate_tilt, roller_axis_angle))
    num = np.sqrt(np.maximum(np.sin(below_max), 0.0) * np.sin(amin))
    den = np.sqrt(np.maximum(np.sin(above_min), 0.0) * np.sin(amax))
    v = np.arctan2(num, den)
    k = np.floor(np.asarray(phase, dtype=float) / np.pi)
    even = np.mod(k, 2.0) == 0.0
    mag = np.where(even, 0.5 * np.pi * k + v, 0.5 * np.pi * (k + 1.0) - v)
    return np.sign(float(spin_ratio)) * mag


def fit_spin_correction(spin_samples, spin_ratio, max_harmonic=None):
    """Fourier coefficients of the correction ``varphi - n theta`` (FFT of one turn).

    Parameters
    ----------
    spin_samples : array_like, shape (M,)
        ``varphi`` at ``theta_j = 2 pi j / M``, j = 0..M-1 [rad].
    spin_ratio : float
        n.
    max_harmonic : int, optional
        Highest harmonic kept; default: up to the last one above 1e-14 rad.

    Returns
    -------
    (spin_a, spin_b, mean) : tuple
        Coefficient tuples for harmonics 1..K (``varphi = n theta + sum a_k cos k theta +
        b_k sin k theta``), zeros below 1e-14 rad, trailing zeros dropped; ``mean``: the
        constant term the drive cannot carry (zero for the laws here, returned to be checked).
    """
    v = np.asarray(spin_samples, dtype=float)
    M = v.size
    theta = 2.0 * np.pi * np.arange(M) / M
    C = np.fft.rfft(v - float(spin_ratio) * theta) / M
    a = 2.0 * C.real[1:]
    b = -2.0 * C.imag[1:]
    a[np.abs(a) < _DROP] = 0.0
    b[np.abs(b) < _DROP] = 0.0
    big = np.flatnonzero((a != 0.0) | (b != 0.0))
    K = int(big[-1]) + 1 if big.size else 0
    if max_harmonic is not None:
        K = min(K, int(max_harmonic))
    return _trim(a[:K]), _trim(b[:K]), float(C.real[0])


def _trim(c):
    """Coefficients as a tuple without trailing zeros."""
    nz = np.flatnonzero(c)
    return tuple(c[: nz[-1] + 1].tolist()) if nz.size else ()


def spin_law_for_target(params: wc.WobbleCam, slow=1.0, max_harmonic=None) -> wc.WobbleCam:
    """The drive with the spin correction that gives the target law (``slow`` = r; 1: sine).

    Parameters
    ----------
    params : WobbleCam
        Base drive (its own correction, if any, is replaced).
    slow : float, optional
        Rate ratio r of :func:`chamber_phase`.
    max_harmonic : int, optional
        Cap on the highest harmonic of the correction.

    Returns
    -------
    WobbleCam
        ``params`` with ``spin_a``, ``spin_b`` set.
    """
    theta = 2.0 * np.pi * np.arange(_FFT_SAMPLES) / _FFT_SAMPLES
    n, phi, alpha = params.spin_ratio, params.plate_tilt, params.roller_axis_angle
    _, above, below, P = target_slider_angle(n, phi, alpha, slow, theta)
    varphi = spin_for_slider_angle(above, below, P, n, phi, alpha)
    a, b, mean = fit_spin_correction(varphi, n, max_harmonic)
    if abs(mean) > 1e-9:  # pragma: no cover - the target laws are odd in theta
        raise ParameterError("spin correction", f"mean {mean:.3g} rad", "a zero-mean correction")
    return dataclasses.replace(params, spin_a=a, spin_b=b)


def dwell_fractions(params: wc.WobbleCam, slider, tolerance=None):
    """Share of a chamber cycle spent near the smallest and the largest slider angle.

    Parameters
    ----------
    params : WobbleCam
        For the extremes.
    slider : array_like, shape (..., M)
        ``alpha'`` over one shaft turn, end point excluded [rad].
    tolerance : float, optional
        Band as a fraction of the swing (default :data:`rotorkin.synthesis.DWELL_TOLERANCE`).

    Returns
    -------
    (near_min, near_max) : tuple of ndarray
        Fractions in [0, 1]; near the minimum of ``alpha'`` is the minimum volume
        of chamber kind A, near the maximum that of kind B.
    """

    tol = DWELL_TOLERANCE if tolerance is None else float(tolerance)
    amax, amin = (
        float(v) for v in wc.slider_angle_extremes(params.plate_tilt, params.roller_axis_angle)
    )
    band = tol * (amax - amin)
    return dwell_fraction(slider, amin, band), dwell_fraction(slider, amax, band)


def _target_dwell(params, slow):
    theta = 2.0 * np.pi * np.arange(_FINE) / _FINE
    T = target_slider_angle(
        params.spin_ratio, params.plate_tilt, params.roller_axis_angle, slow, theta
    )
    return float(dwell_fractions(params, T[0])[0])


def _law_dwell(params):
    theta = 2.0 * np.pi * np.arange(_FINE) / _FINE
    v = wc.spin_law(params, theta)[0]
    return dwell_fractions(params, wc.slider_angle(params.plate_tilt, params.roller_axis_angle, v))


def slow_for_dwell(params: wc.WobbleCam, fraction: float, admissible=None) -> float:
    """Rate ratio r of the dwell law whose dwell fraction at minimum volume is ``fraction``.

    Brent's method on ``r`` (the fraction falls as r grows).

    Parameters
    ----------
    params : WobbleCam
        Base drive.
    fraction : float
        Wanted dwell fraction.
    admissible : Feasible, optional
        The rate ratios the grooves admit (:func:`feasible_dwell`); default: the whole
        family ``SLOW_MIN <= r <= 1`` (no groove constraint).

    Raises
    ------
    ParameterError
        Named ``target`` with the admissible range (and why it ends there).
    """

    if admissible is None:
        s_lo, s_hi, why = SLOW_MIN, 1.0, ""
    else:
        s_lo, s_hi, why = admissible.slow_min, admissible.slow_max, admissible.why
    lo, hi = _target_dwell(params, s_hi), _target_dwell(params, s_lo)
    lo_ok = fraction > lo if s_hi == 1.0 else fraction >= lo
    if not (lo_ok and fraction <= hi):
        paper = float(_law_dwell(dataclasses.replace(params, spin_a=(), spin_b=()))[0])
        sign = "<" if s_hi == 1.0 else "<="
        raise ParameterError(
            "target",
            f"{fraction:.4g}",
            f"a dwell fraction {_round4(lo, up=sign == '<=')} {sign} target <= "
            f"{_round4(hi, up=False)} ({why}the sine law dwells "
            f"{_target_dwell(params, 1.0):.4g}, the paper's law {paper:.4g}; a chamber cycle "
            "counts as dwelling within 2 % of the swing of its minimum)",
        )
    if fraction >= hi:
        return float(s_lo)
    if fraction <= lo:
        return float(s_hi)
    from scipy.optimize import brentq  # imported where used (0.2 s)

    return float(brentq(lambda r: _target_dwell(params, r) - fraction, s_lo, s_hi, xtol=1e-12))


def _round4(x: float, up: bool) -> str:
    """``x`` to 4 significant digits, rounded inwards (a printed bound stays admissible)."""
    if x <= 0.0:
        return f"{x:.4g}"
    e = int(np.floor(np.log10(x))) - 3
    q = x / 10.0**e
    return f"{(np.ceil(q) if up else np.floor(q)) * 10.0**e:.4g}"


# --------------------------------------------------------------------------------------------
# groove constraints: the configured roller must follow the grooves of the law
# --------------------------------------------------------------------------------------------
#: Safety factor on the roller radius: the grooves' roller radius limit must be at least
#: 1.01 x ``cam.roller_radius`` (an undercut margin, as for the planar cams).
UNDERCUT_FACTOR = 1.01
#: Default bound on the peak pressure angle of the best-placed roller [rad]; raised to the
#: baseline law's peak where that is higher (the paper's law: 30.4 deg).
PRESSURE_ANGLE_LIMIT = np.radians(45.0)
#: Shaft-angle samples of the pressure angle (as :func:`rotorkin.drives.wobble_cam.cam.summary`).
_PA_SAMPLES = 2881
#: Rate ratios scanned for the admissible dwell range, then refined by bisection.
_SCAN = 20
#: Bisection stops when the bracket of r is this narrow.
_SLOW_XTOL = 1e-6


def groove_limits(params: wc.WobbleCam, cam) -> tuple[float, float]:
    """Roller radius limit and peak pressure angle of the grooves of a spin law.

    The limit is that of :func:`rotorkin.drives.wobble_cam.cam.check_roller_radius` (what
    ``rotorkin export`` enforces): ``R_i / sqrt(1 + (r kappa_max)^2)`` at the sharpest
    bend of any groove; the pressure angle is
    ``cam_pressure_angle_best_roller_max_deg`` of :func:`rotorkin.drives.wobble_cam.cam.summary`
    (over the turn, the largest of the smallest pressure angle of the 4 rollers: all 4
    hold the one plate, so the best-placed one guides it; a single roller reaches 90 deg
    with every law, the paper's included).

    Returns
    -------
    (limit, pressure_angle) : tuple of float
        [m], [rad].
    """

    kmax = cs.sharpest_bend(params)[0]
    limit = cam.inner_radius / np.sqrt(1.0 + (params.sphere_radius * kmax) ** 2)
    mu = cs.pressure_angle(params, np.linspace(0.0, 2.0 * np.pi, _PA_SAMPLES))
    return float(limit), float(np.max(np.min(mu, axis=0)))


def _meets(limits, roller_radius, pa_limit) -> tuple[bool, bool]:
    """(roller follows the grooves with the safety factor, pressure angle within the bound)."""
    return (
        limits[0] >= UNDERCUT_FACTOR * roller_radius,
        limits[1] <= pa_limit,
    )


@dataclasses.dataclass(frozen=True)
class Feasible:
    """The dwell laws whose grooves the configured roller follows.

    Attributes
    ----------
    slow_min, slow_max : float
        Admissible rate ratios ``slow_min <= r <= slow_max`` (``slow_min``: the longest dwell).
    dwell_min, dwell_max : float
        The dwell fractions at ``slow_max`` and ``slow_min``.
    why : str
        What ends the range at the long-dwell side, ``"longer dwells: ...; "`` (for
        messages; empty when the family's longest dwell is admissible).
    """

    slow_min: float
    slow_max: float
    dwell_min: float
    dwell_max: float
    why: str


def feasible_dwell(params: wc.WobbleCam, cam, pa_limit: float, harmonics=None) -> Feasible:
    """The admissible range of the dwell law's rate ratio r under the groove constraints.

    Constraints: groove roller radius limit ``>= 1.01 cam.roller_radius`` and the
    best-placed roller's peak pressure angle ``<= pa_limit`` (:func:`groove_limits`).
    ``r`` is scanned on 20 values in ``[SLOW_MIN, 1]``; the run of admissible values
    holding the smallest admissible r (the longest dwell) is kept and both its ends are
    refined by bisection to 1e-6 (each end on the admissible side).

    Raises
    ------
    ParameterError
        ``cam.roller_radius`` when no law of the family has grooves the roller follows;
        ``--max-pressure-angle`` when the pressure angle bound leaves none.
    """
    rho = float(cam.roller_radius)

    def limits(r):
        return groove_limits(spin_law_for_target(params, r, harmonics), cam)

    def check(r):
        return _meets(limits(r), rho, pa_limit)

    grid = np.linspace(SLOW_MIN, 1.0, _SCAN)
    scanned = [limits(r) for r in grid]
    checks = [_meets(v, rho, pa_limit) for v in scanned]
    ok = [a and b for a, b in checks]
    if not any(ok):
        if not any(a for a, _ in checks):
            best = max(v[0] for v in scanned)
            raise ParameterError(
                "cam.roller_radius",
                f"{rho * 1e3:.4g} mm",
                f"roller_radius < {best / UNDERCUT_FACTOR * 1e3:.4g} mm: with a larger roller no "
                "dwell law of this family has grooves the roller can follow (their roller "
                "radius limit, with a 1 % margin)",
            )
        least = min(v[1] for v, (a, _) in zip(scanned, checks, strict=True) if a)
        raise ParameterError(
            "max_pressure_angle",
            f"{np.degrees(pa_limit):.4g} deg",
            f">= {np.degrees(least):.4g} deg: every dwell law the roller can follow has a larger "
            "peak pressure angle of its best-placed roller",
        )
    j = ok.index(True)
    k = j
    while k + 1 < len(grid) and ok[k + 1]:
        k += 1

    def bisect(good, bad):
        while abs(bad - good) > _SLOW_XTOL:
            mid = 0.5 * (good + bad)
            if all(check(mid)):
                good = mid
            else:
                bad = mid
        return good

    s_min = float(grid[j]) if j == 0 else bisect(float(grid[j]), float(grid[j - 1]))
    s_max = float(grid[k]) if k == len(grid) - 1 else bisect(float(grid[k]), float(grid[k + 1]))
    why = ""
    if j > 0:
        roller_ok, pa_ok = check(float(grid[j - 1]))
        parts = []
        if not roller_ok:
            parts.append(
                f"the roller (cam.roller_radius = {rho * 1e3:.4g} mm) undercuts the grooves"
            )
        if not pa_ok:
            parts.append(
                f"the best-placed roller's pressure angle exceeds {np.degrees(pa_limit):.4g} deg"
            )
        why = "longer dwells: " + " and ".join(parts) + "; " if parts else ""
    return Feasible(
        slow_min=s_min,
        slow_max=s_max,
        dwell_min=_target_dwell(params, s_max),
        dwell_max=_target_dwell(params, s_min),
        why=why,
    )


def forward_error(params: wc.WobbleCam, slow, theta):
    """Largest ``|alpha'(varphi(theta)) - alpha'_target(theta)|`` over ``theta`` [rad].

    The forward analysis: the drive's spin law and slider angle (eq. 15) against the target.
    """
    v = wc.spin_law(params, theta)[0]
    got = wc.slider_angle(params.plate_tilt, params.roller_axis_angle, v)
    want = target_slider_angle(
        params.spin_ratio, params.plate_tilt, params.roller_axis_angle, slow, theta
    )[0]
    return float(np.max(np.abs(got - want)))


# --------------------------------------------------------------------------------------------
# the command's entry point
# --------------------------------------------------------------------------------------------
def groove_closing_angle(params: wc.WobbleCam) -> float:
    """Shaft angle after which a groove centre-line closes in the cam frame [rad] (pi at n = -2).

    After ``k pi`` the cam frame has turned ``2 k pi`` relative to the shaft and the
    spin by ``k n pi`` (the correction is 2 pi periodic): closed when ``k n`` is even.
    """
    n2 = int(round(2.0 * params.spin_ratio))
    k = next(k for k in (1, 2, 4) if (k * n2) % 4 == 0)
    return k * np.pi


def _drive(cfg) -> wc.WobbleCam:
    d = cfg["drive"]
    return wc.WobbleCam(
        plate_tilt=d["plate_tilt"],
        roller_axis_angle=d["roller_axis_angle"],
        spin_ratio=d["spin_ratio"],
        sphere_radius=d["sphere_radius"],
        pistons_per_rotor=cfg["machine"]["pistons_per_rotor"],
        spin_a=tuple(d.get("spin_a", ())),
        spin_b=tuple(d.get("spin_b", ())),
    )


_GROOVE_ROWS = (
    ("cam_curvature_radius_min_mm", "groove min radius of curvature [mm]"),
    ("cam_roller_radius_limit_mm", "groove roller radius limit [mm]"),
    ("cam_roller_radius_mm", "cam.roller_radius [mm]"),
    ("cam_self_crossings", "groove self-crossings"),
)


def _groove_checks(cfg, params) -> dict:
    """Groove checks of :func:`rotorkin.drives.wobble_cam.cam.summary` for the drive ``params``.

    Keys of :data:`_GROOVE_ROWS`; one the cams module does not report is ``"n/a"``.
    """

    cam = cs.from_config(cfg)[1]
    summary = cs.summary(params, cam)
    return {k: summary.get(k, "n/a") for k, _ in _GROOVE_ROWS}


def _run_error(res, params, slow):
    """Largest |delta_A(run) - delta_A(target)| over the run's samples [deg]."""
    theta = np.radians(res.columns["theta_deg"])
    target = target_slider_angle(
        params.spin_ratio, params.plate_tilt, params.roller_axis_angle, slow, theta
    )[0]
    offset = 2.0 * res.summary["piston_offset_gamma_deg"] + res.summary["piston_width_deg"]
    return float(np.max(np.abs(res.columns["chamber_a_angle_deg"] - (np.degrees(target) - offset))))


#: Summary keys whose rise is a cost of the synthesized law (named in a note), with labels.
_COSTS = (
    ("rotor_accel_peak_per_rad", "rotor accel peak", "1/rad"),
    ("rotor_jerk_peak_per_rad2", "rotor jerk peak", "1/rad2"),
    ("flywheel_inertia_kgm2", "flywheel inertia", "kg m2"),
    ("torque_ripple", "torque ripple", ""),
)


def _pa_limit(options, base_pa) -> float:
    """The pressure-angle bound [rad]: ``--max-pressure-angle`` or max(45 deg, the baseline's)."""
    limit = (options or {}).get("max_pressure_angle")
    if limit is None:
        return max(float(PRESSURE_ANGLE_LIMIT), float(base_pa))
    return float(limit)


def _check_final(synth, cam, pa_limit, harmonics):
    """Refuse a synthesized law whose grooves the roller cannot follow (it would be written).

    Uses :func:`rotorkin.drives.wobble_cam.cam.check_roller_radius` itself (``rotorkin export``'s
    check) besides :func:`groove_limits`.
    """

    limits = groove_limits(synth, cam)
    roller_ok, pa_ok = _meets(limits, cam.roller_radius, pa_limit)
    try:
        cs.check_roller_radius(synth, cam)
    except ParameterError:
        roller_ok = False
    if roller_ok and pa_ok:
        return limits
    name, value = ("--harmonics", str(harmonics)) if harmonics is not None else ("target", "")
    what = (
        f"the groove roller radius limit {limits[0] * 1e3:.4g} mm < {UNDERCUT_FACTOR} x "
        f"cam.roller_radius = {cam.roller_radius * 1e3:.4g} mm"
        if not roller_ok
        else f"the pressure angle {np.degrees(limits[1]):.4g} deg > {np.degrees(pa_limit):.4g} deg"
    )
    raise ParameterError(
        name,
        value or "default",
        f"a law whose grooves the roller can follow; this one fails: {what}"
        + (" (raise --harmonics or leave it out)" if harmonics is not None else ""),
    )


def synthesize(cfg, raw, objective, target, harmonics, options=None):
    """Spin correction for ``sine_chamber`` or ``dwell_min_volume`` (``--target`` dwell fraction).

    See :func:`rotorkin.synthesis.synthesize`; ``options`` may hold
    ``max_pressure_angle`` [rad]. The grooves of the synthesized law are constrained:
    their roller radius limit at least 1.01 ``cam.roller_radius`` (what ``rotorkin export``
    checks) and the best-placed roller's peak pressure angle at most
    ``max(45 deg, the baseline's)`` or ``--max-pressure-angle``; a dwell target beyond
    the longest admissible dwell is refused, and without ``--target`` the longest admissible
    dwell is synthesized. The synthesized config is evaluated (``rotorkin run``'s study)
    and its chamber angle compared with the target at every sample; the drive's own
    functions are compared on 20001 angles.
    """

    res0 = study.evaluate(cfg)  # validates the baseline, with config key names in its errors
    base = _drive(cfg)
    cam = cs.from_config(cfg)[1]
    limits0 = groove_limits(base, cam)
    pa_limit = _pa_limit(options, limits0[1])
    feasible = None
    if objective == "sine_chamber":
        if target is not None:
            raise ParameterError(
                "target",
                repr(target),
                "no target for sine_chamber (the law is fixed: a pure sine between the "
                "extremes of the paper's law)",
            )
        slow, wanted = 1.0, None
        limits = groove_limits(spin_law_for_target(base, 1.0, harmonics), cam)
        roller_ok, pa_ok = _meets(limits, cam.roller_radius, pa_limit)
        if not roller_ok:
            raise ParameterError(
                "cam.roller_radius",
                f"{cam.roller_radius * 1e3:.4g} mm",
                f"roller_radius < {limits[0] / UNDERCUT_FACTOR * 1e3:.4g} mm for sine_chamber: "
                f"the sine law's grooves (roller radius limit {limits[0] * 1e3:.4g} mm, with a "
                "1 % margin) are too sharp for a larger roller",
            )
        if not pa_ok:
            raise ParameterError(
                "max_pressure_angle",
                f"{np.degrees(pa_limit):.4g} deg",
                f">= {np.degrees(limits[1]):.4g} deg for sine_chamber (the peak pressure angle "
                "of the sine law's best-placed roller)",
            )
    else:
        feasible = feasible_dwell(base, cam, pa_limit, harmonics)
        if target is None:
            wanted, slow = feasible.dwell_max, feasible.slow_min
        else:
            wanted = parse_fraction(target)
            slow = slow_for_dwell(base, wanted, feasible)
    synth = spin_law_for_target(base, slow, harmonics)
    limits1 = _check_final(synth, cam, pa_limit, harmonics)
    updates = {"drive": {"spin_a": list(synth.spin_a), "spin_b": list(synth.spin_b)}}
    res1 = study.evaluate(
        validate_model(schema.WobbleConfig, synthesized_raw_config(raw, updates, objective))
    )
    fine = np.linspace(0.0, 2.0 * np.pi, 20_001)
    err_drive = forward_error(synth, slow, fine)
    err_run = _run_error(res1, synth, slow)
    err_base = forward_error(base, slow, fine)
    round_trip = max(float(np.degrees(err_drive)), err_run)
    d0, d1 = _law_dwell(base), _law_dwell(synth)
    rate0, rate1 = (wc.spin_law(p, fine)[1] for p in (base, synth))
    kmax = max(len(synth.spin_a), len(synth.spin_b))
    nonzero = len(
        set(np.flatnonzero(np.asarray(synth.spin_a, dtype=float)).tolist())
        | set(np.flatnonzero(np.asarray(synth.spin_b, dtype=float)).tolist())
    )
    # verdict: the target law reproduced (and the dwell reached), better than the baseline
    # on the objective, the groove constraints met
    if objective == "sine_chamber":
        target_met = round_trip <= 1e-6
        better = err_drive < err_base
        objective_row = (
            "objective: deviation from a pure sine [deg]",
            float(np.degrees(err_base)),
            float(np.degrees(err_drive)),
        )
    else:
        target_met = round_trip <= 1e-6 and abs(float(d1[0]) - wanted) <= 1e-4
        better = float(d1[0]) > float(d0[0])
        objective_row = (
            "objective: dwell at min volume [% of cycle]",
            100 * float(d0[0]),
            100 * float(d1[0]),
        )
    roller_ok0, pa_ok0 = _meets(limits0, cam.roller_radius, pa_limit)
    constraints_met = all(_meets(limits1, cam.roller_radius, pa_limit))
    law = f"{base.spin_ratio:g} theta" + (" + correction" if base.spin_a or base.spin_b else "")
    keys = (
        ("chamber_angle_min_deg", "chamber angle min [deg]"),
        ("chamber_angle_max_deg", "chamber angle max [deg]"),
        ("rotor_speed_ratio_min", "rotor speed ratio min"),
        ("rotor_speed_ratio_max", "rotor speed ratio max"),
        ("rotor_accel_peak_per_rad", "rotor accel peak [1/rad]"),
        ("rotor_jerk_peak_per_rad2", "rotor jerk peak [1/rad2]"),
        ("indicated_work_J", "indicated work [J/rev]"),
        ("torque_ripple", "torque ripple"),
        ("flywheel_inertia_kgm2", "flywheel inertia [kg m2]"),
    )
    rows = [
        objective_row,
        ("spin law varphi", law, f"{base.spin_ratio:g} theta + {nonzero} harmonics"),
        ("highest harmonic", 0, kmax),
        ("deviation from target law [deg]", np.degrees(err_base), np.degrees(err_drive)),
        ("dwell at min volume, kind A [%]", 100 * float(d0[0]), 100 * float(d1[0])),
        ("dwell at min volume, kind B [%]", 100 * float(d0[1]), 100 * float(d1[1])),
        ("plate spin rate min", float(np.min(rate0)), float(np.min(rate1))),
        ("plate spin rate max", float(np.max(rate0)), float(np.max(rate1))),
    ]
    if feasible is not None:
        rows.append(
            (
                "admissible dwell [% of cycle]",
                "",
                f"{100 * feasible.dwell_min:.4g} - {100 * feasible.dwell_max:.4g}",
            )
        )
    rows += [(label, res0.summary[k], res1.summary[k]) for k, label in keys]
    grooves0, grooves1 = _groove_checks(cfg, base), _groove_checks(cfg, synth)
    rows += [(label, grooves0[k], grooves1[k]) for k, label in _GROOVE_ROWS]
    rows += [
        (
            "groove pressure angle, best roller, peak [deg]",
            float(np.degrees(limits0[1])),
            float(np.degrees(limits1[1])),
        ),
        (
            "check: roller limit >= 1.01 x cam.roller_radius",
            bool(roller_ok0),
            bool(limits1[0] >= UNDERCUT_FACTOR * cam.roller_radius),
        ),
        ("check: pressure angle bound [deg]", "", float(np.degrees(pa_limit))),
        ("check: pressure angle within bound", bool(pa_ok0), bool(limits1[1] <= pa_limit)),
        ("round trip |delta error| [deg]", "", round_trip),
        ("target met", "", bool(target_met)),
        ("better on the objective", "", bool(better)),
        (
            "constraints met (roller, pressure angle)",
            bool(roller_ok0 and pa_ok0),
            bool(constraints_met),
        ),
        (
            "target met, better, constraints met",
            "",
            bool(target_met and better and constraints_met),
        ),
    ]
    metrics = {
        "target_law": objective,
        "dwell_tolerance_of_swing": DWELL_TOLERANCE,
        "target_dwell_fraction": wanted,
        "phase_rate_ratio": slow,
        "baseline_deviation_from_target_deg": float(np.degrees(err_base)),
        "round_trip_error_drive_deg": float(np.degrees(err_drive)),
        "round_trip_error_run_deg": err_run,
        "baseline_dwell_fraction_min_volume_a": float(d0[0]),
        "baseline_dwell_fraction_min_volume_b": float(d0[1]),
        "synthesized_dwell_fraction_min_volume_a": float(d1[0]),
        "synthesized_dwell_fraction_min_volume_b": float(d1[1]),
        "baseline_spin_rate_min": float(np.min(rate0)),
        "baseline_spin_rate_max": float(np.max(rate0)),
        "synthesized_spin_rate_min": float(np.min(rate1)),
        "synthesized_spin_rate_max": float(np.max(rate1)),
        "correction_nonzero_harmonics": nonzero,
        "correction_highest_harmonic": kmax,
        "admissible_dwell_fraction_min": None if feasible is None else feasible.dwell_min,
        "admissible_dwell_fraction_max": None if feasible is None else feasible.dwell_max,
        "pressure_angle_limit_deg": float(np.degrees(pa_limit)),
        "undercut_factor": UNDERCUT_FACTOR,
        "baseline_groove_roller_radius_limit_mm": limits0[0] * 1e3,
        "synthesized_groove_roller_radius_limit_mm": limits1[0] * 1e3,
        "baseline_groove_pressure_angle_best_roller_max_deg": float(np.degrees(limits0[1])),
        "synthesized_groove_pressure_angle_best_roller_max_deg": float(np.degrees(limits1[1])),
        "target_met": bool(target_met),
        "better": bool(better),
        "baseline_constraints_met": bool(roller_ok0 and pa_ok0),
        "constraints_met": bool(constraints_met),
    }
    for k, _ in keys:
        metrics[f"baseline_{k}"] = res0.summary[k]
        metrics[f"synthesized_{k}"] = res1.summary[k]
    for k, _ in _GROOVE_ROWS:
        metrics[f"baseline_{k}"] = grooves0[k]
        metrics[f"synthesized_{k}"] = grooves1[k]
    notes = []
    costs = [
        f"{label} {res0.summary[k]:.3g} -> {res1.summary[k]:.3g}{' ' + unit if unit else ''} "
        f"(x {res1.summary[k] / res0.summary[k]:.3g})"
        for k, label, unit in _COSTS
        if res0.summary[k] > 0.0 and res1.summary[k] > 1.1 * res0.summary[k]
    ]
    c0, c1 = grooves0["cam_self_crossings"], grooves1["cam_self_crossings"]
    if isinstance(c0, int) and isinstance(c1, int) and c1 > c0:
        costs.append(f"groove self-crossings {c0} -> {c1}")
    if costs:
        notes.append("costs of this law against the baseline: " + "; ".join(costs))
    if feasible is not None:
        notes.append(
            f"admissible dwell fractions {feasible.dwell_min:.4g} - {feasible.dwell_max:.4g}: "
            f"groove roller radius limit >= {UNDERCUT_FACTOR} x cam.roller_radius = "
            f"{UNDERCUT_FACTOR * cam.roller_radius * 1e3:.4g} mm and the best-placed roller's "
            f"pressure angle <= {np.degrees(pa_limit):.4g} deg"
            + (" (--target not given: the longest admissible dwell)" if target is None else "")
        )
    if res1.summary["rotor_speed_ratio_max"] > 0.0 > res1.summary["rotor_speed_ratio_min"]:
        notes.append(
            "the rotors reverse during each cycle with this law (rotor speed ratio changes "
            "sign): ask for a shorter dwell"
        )
    if objective == "dwell_min_volume":
        notes.append(
            f"the chamber phase runs at {slow:.4g} x its mean rate near both extremes of the "
            "slider angle: delta_A + delta_B is constant (eq. 18), so every chamber dwells at "
            "its minimum volume (and also at its maximum)"
        )
    if round_trip > 1e-6:
        notes.append(
            f"the correction with harmonics <= {kmax} reproduces the target to "
            f"{round_trip:.3g} deg only: raise --harmonics"
        )
    if not better:
        notes.append("the synthesized law is not better than the baseline on the objective")
    offset = 2.0 * float(wc.piston_offset(base.pistons_per_rotor)) + np.radians(
        res0.summary["piston_width_deg"]
    )
    theta_g = np.linspace(0.0, groove_closing_angle(base), 1441)
    grooves = wc.groove_points(synth, theta_g) * 1e3
    table = {"theta_deg": np.degrees(theta_g)}
    for i in range(4):
        for j, ax in enumerate("xyz"):
            table[f"groove{i + 1}_{ax}_mm"] = grooves[i, j]
    theta_c = np.linspace(0.0, 2.0 * np.pi, 1441)
    target_c = target_slider_angle(
        base.spin_ratio, base.plate_tilt, base.roller_axis_angle, slow, theta_c
    )[0]
    laws = {"theta_deg": np.degrees(theta_c), "chamber_a_target_deg": np.degrees(target_c - offset)}
    for tag, p in (("baseline", base), ("synthesized", synth)):
        sp = wc.spin_law(p, theta_c)
        laws[f"chamber_a_{tag}_deg"] = np.degrees(
            wc.slider_angle(p.plate_tilt, p.roller_axis_angle, sp[0]) - offset
        )
        laws[f"spin_{tag}_deg"] = np.degrees(sp[0])
        laws[f"spin_rate_{tag}"] = sp[1]

    target_fig = target_slider_angle(
        base.spin_ratio, base.plate_tilt, base.roller_axis_angle, slow, figures_synthesis.LAW_THETA
    )[0]
    closing = groove_closing_angle(base)

    def plot(outdir):
        return figures_synthesis.plot_wobble(
            outdir, base, synth, target_fig, closing, offset, objective
        )

    title = {
        "sine_chamber": "every chamber angle a pure sine of the shaft angle",
        "dwell_min_volume": f"a dwell at minimum volume of {100 * (wanted or 0):.4g} % "
        "of each chamber cycle",
    }[objective]
    return SynthesisResult(
        drive_type="wobble_cam",
        objective=objective,
        title=f"wobble cam: spin-law correction for {title}",
        rows=tuple(rows),
        parameters={
            "spin_ratio": base.spin_ratio,
            "spin_a": list(synth.spin_a),
            "spin_b": list(synth.spin_b),
            "phase_rate_ratio": slow,
        },
        metrics=metrics,
        updates=updates,
        notes=tuple(notes),
        plot=plot,
        tables={"chamber_law.csv": laws, "grooves.csv": table},
    )
