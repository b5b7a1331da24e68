"""The law of a tabulated drive: two member angles versus the shaft angle as a Fourier series.

A :class:`FourierLaw` is the one representation of both inputs, a table (CSV, CAD
motion study, measured rig) and a Fourier series typed in by the user::

    q_i(theta) = offset_i + mean_ratio_i theta
                 + sum_k cos_ik cos(k w theta) + sin_ik sin(k w theta),   w = 2 pi / P,

with a period ``P`` that divides the turn. :func:`motion` evaluates it and its exact
first to third derivatives for any array of shaft angles.

Interpolation of a table
------------------------
A table spans one period with both end points included and uniform steps. The
linear trend through its end points is taken out of each member's angle; what is
left is periodic, and its trigonometric interpolant (the FFT of the ``n - 1``
distinct samples) is the fit: exact at the samples and spectrally accurate for the
smooth motions of real mechanisms (the error falls faster than any power of the
step). A periodic cubic spline would be the other choice; its third derivative
(the jerk the bearings and rollers feel) is piecewise constant and jumps at every
knot, and its error falls only as the fourth power of the step. The trigonometric
fit has a smooth jerk and is exact for the sum of harmonics that a periodic
mechanism is. With ``harmonics`` given, the fit is the least-squares fit of a
linear trend and that many harmonics (for uniform samples the harmonics' part is
the interpolant cut to that order): a low-pass filter for noisy measured data,
whose trend no longer hangs on the noise of two end points.

Non-uniform tables are refused. For uniform samples the fit is an FFT, exact,
O(n log n) and its error is bounded by the spectrum the samples cannot resolve.
For non-uniform samples it would be a least-squares problem whose conditioning is
set by the largest gap between samples: where the gap exceeds the shortest
wavelength fitted, the series is free to oscillate between samples while matching
them, an error in the derivatives that no residual at the samples shows. The
sources of tables (CAD motion studies, encoders read at fixed angle steps,
rotorkin's own ``motion.csv``) write uniform steps; a table sampled at fixed time
steps is best resampled at fixed shaft angle steps where it is made.

Checks of a table
-----------------
Refused in one line (:class:`~rotorkin.core.errors.ParameterError` naming
``drive.table``): fewer than 8 or more than 100001 rows, a value that is not a
finite number, shaft angles not strictly increasing, a span that is not one period
``360 deg / k`` with both end points, non-uniform steps, member angles wrapped into
one turn (a step over 180 deg between rows, ten-fold larger than its neighbours)
and a motion that is not periodic.

Periodicity criterion: after the trend is taken out, the angles join in value
across the ends by construction; what is checked is that they join in slope. The
slope on each side of a row is estimated by a least-squares cubic through the 8
samples on that side (fewer for short tables); the difference ``J_j`` of the two
is the slope jump for a kink and ``O(h^3 q'''')`` for smooth data. At the ends
(the first row joined to the last) the table is refused when ``|J|`` exceeds all
of: ``1 %`` of the member's largest slope ``max |dq/dtheta|``; 6 times the median
of ``|J_j|`` at the rows at least a window away from the ends (the estimate's
noise on measured data); and twice the change of ``J`` when estimated from every
second sample (a kink's jump does not depend on the step, while the estimate's
error for a smooth feature too narrow for the window grows eight-fold). Smooth
periodic tables pass, coarse ones (8 rows) too, and narrow peaks at the ends as
long as a peak spans a few steps; so does a cam drive's rotor table at 721 rows
(its slope jump about 4e-5 of the largest slope) and noisy measurements. A kink
of 2 % of the largest slope at the ends is refused once every second sample
still resolves the motion (from 121 rows for a law of 7 harmonics), unless noise
hides it.

Error estimate
--------------
:func:`fit_error` fits the table again from every second sample (every d-th with
d the smallest divisor of the number of intervals, or from half the harmonics
when that number is prime) and compares: the angles against the data at the
samples left out, the derivatives against the full fit on the samples and the
midpoints between them. The coarser fit's error is larger than the full fit's
for data the full fit resolves (its unresolved spectrum starts at half the
frequency), so the numbers over-estimate the full fit's error within the table's
range; a roundoff floor ``8 eps max|q| (H w)^order`` is added (H harmonics).
"""

from __future__ import annotations

import csv
import re
import stat
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rotorkin.core.errors import ParameterError, shown
from rotorkin.core.motion import Motion

__all__ = [
    "FourierLaw",
    "FitError",
    "motion",
    "from_fourier",
    "from_table",
    "from_csv",
    "fit_error",
    "read_table",
    "TABLE",
    "MIN_ROWS",
    "MAX_ROWS",
    "MAX_HARMONICS",
    "MAX_FILE_BYTES",
    "KINK_TOLERANCE",
]

#: Name of the parameter the table errors name.
TABLE = "drive.table"
#: Fewest and most rows of a table (both end points included).
MIN_ROWS = 8
MAX_ROWS = 100_001
#: Most harmonics of a Fourier series given by the user.
MAX_HARMONICS = 1000
#: Largest CSV file read [bytes].
MAX_FILE_BYTES = 16 * 2**20
#: Largest slope jump across the ends of a table, as a fraction of the largest slope.
KINK_TOLERANCE = 0.01
#: ... as a multiple of the median of the same estimate inside the table (its noise) ...
_KINK_NOISE = 6.0
#: ... and of the change of the estimate from every second sample (its discretisation error).
_KINK_RICHARDSON = 2.0
#: Samples on each side of a row from which its one-sided slopes are estimated.
_KINK_WINDOW = 8
#: Relative tolerance of the steps of a table and of ``2 pi / P`` being an integer.
_UNIFORM = 1e-6
_PERIOD = 1e-9
#: Size of one (harmonics x angles) array in :func:`motion` [bytes]; a few live at once.
_CHUNK_BYTES = 8e6
_EPS = np.finfo(float).eps


# --------------------------------------------------------------------------------------------
# the law
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class FourierLaw:
    """Angles of two members as a Fourier series of the shaft angle.

    ``q_i = offset_i + mean_ratio_i theta + sum_k cos[i, k-1] cos(k w theta)
    + sin[i, k-1] sin(k w theta)``, ``k = 1..H``, ``w = 2 pi / period``.

    Attributes
    ----------
    period : float
        Period P of the motion [rad]; ``2 pi / P`` is an integer.
    offset : ndarray, shape (2,)
        Constant term of each member [rad].
    mean_ratio : ndarray, shape (2,)
        Mean speed of each member over the shaft's (advance over a period / P) [-].
    cos, sin : ndarray, shape (2, H)
        Coefficients of the harmonics 1..H of the fundamental ``2 pi / P`` [rad].
    """

    period: float
    offset: np.ndarray
    mean_ratio: np.ndarray
    cos: np.ndarray
    sin: np.ndarray

    def __post_init__(self):
        offset = np.array(self.offset, dtype=float).reshape(2)
        ratio = np.array(self.mean_ratio, dtype=float).reshape(2)
        a = np.array(self.cos, dtype=float, ndmin=2)
        b = np.array(self.sin, dtype=float, ndmin=2)
        if a.shape != b.shape or a.ndim != 2 or a.shape[0] != 2:
            raise ValueError(f"cos and sin must both have shape (2, H), not {a.shape}, {b.shape}")
        if _turn_divisions(float(self.period)) is None:
            raise ValueError(f"period {self.period!r} rad does not divide the turn")
        for name, value in (("offset", offset), ("mean_ratio", ratio), ("cos", a), ("sin", b)):
            value.setflags(write=False)
            object.__setattr__(self, name, value)
        object.__setattr__(self, "period", float(self.period))

    @property
    def harmonics(self) -> int:
        """Number H of harmonics."""
        return self.cos.shape[1]

    @property
    def turn_divisions(self) -> int:
        """How many periods make a turn: ``2 pi / P``."""
        return round(2.0 * np.pi / self.period)

    def __call__(self, theta, members=("member 1", "member 2")) -> Motion:
        """:func:`motion` of this law."""
        return motion(self, theta, members)


@dataclass(frozen=True, eq=False)
class FitError:
    """A-posteriori estimate of the error of a table's fit (largest over the table's range).

    Attributes
    ----------
    q, dq, d2q, d3q : ndarray, shape (2,)
        Bound of the error of each member's angle [rad] and of its first to third
        derivatives [rad/rad^n].
    method : str
        How it was estimated, e.g. ``"fit from every 2nd sample"``.
    """

    q: np.ndarray
    dq: np.ndarray
    d2q: np.ndarray
    d3q: np.ndarray
    method: str

    def __getitem__(self, order: int) -> np.ndarray:
        """The bound of the derivative of order 0..3."""
        return (self.q, self.dq, self.d2q, self.d3q)[order]

    @property
    def array(self) -> np.ndarray:
        """All the bounds, shape (4, 2): order 0..3 by member."""
        return np.stack([self.q, self.dq, self.d2q, self.d3q])


def motion(law: FourierLaw, theta, members=("member 1", "member 2")) -> Motion:
    """Angles of both members and their exact derivatives 1..3 at shaft angles ``theta``.

    Parameters
    ----------
    law : FourierLaw
    theta : float or array_like, any shape
        Shaft angle [rad].
    members : tuple of two str, optional
        Names of the members in the :class:`~rotorkin.core.motion.Motion`.

    Returns
    -------
    Motion
        ``q``, ``dq``, ``d2q``, ``d3q`` of shape ``(2,) + theta.shape`` [rad/rad^n].

    The harmonics are evaluated as one matrix product per chunk of angles, the
    chunks small enough that an (angles x harmonics) array stays under about 8 MB
    (three of them live at once).
    The harmonics see ``theta`` reduced modulo the period, so they keep their
    accuracy far from the origin.
    """
    theta = np.asarray(theta, dtype=float)
    t = theta.reshape(-1)
    out = np.zeros((4, 2, t.size))
    out[0] = law.offset[:, None] + law.mean_ratio[:, None] * t
    out[1] = law.mean_ratio[:, None]
    h = law.harmonics
    if h and t.size:
        w = 2.0 * np.pi / law.period
        k = np.arange(1, h + 1, dtype=float)
        kw = k * w
        a, b = law.cos, law.sin
        # rows: (order, member); columns: cos(k x) then sin(k x)
        on_cos = np.stack([a, kw * b, -(kw**2) * a, -(kw**3) * b]).reshape(8, h)
        on_sin = np.stack([b, -kw * a, -(kw**2) * b, kw**3 * a]).reshape(8, h)
        matrix = np.concatenate([on_cos, on_sin], axis=1)
        x = np.mod(t, law.period) * w
        step = max(1, int(_CHUNK_BYTES // (8 * h)))
        for start in range(0, t.size, step):
            phase = np.multiply.outer(k, x[start : start + step])
            basis = np.empty((2 * h, phase.shape[1]))
            np.cos(phase, out=basis[:h])
            np.sin(phase, out=basis[h:])
            out[:, :, start : start + step] += (matrix @ basis).reshape(4, 2, -1)
    q, dq, d2q, d3q = (o.reshape((2,) + theta.shape) for o in out)
    return Motion(theta, q, dq, d2q, d3q, members=tuple(members), unit="rad")


# --------------------------------------------------------------------------------------------
# a Fourier series given by the user
# --------------------------------------------------------------------------------------------
def _turn_divisions(period: float) -> int | None:
    """``2 pi / period`` if it is an integer >= 1 within ``1e-9`` relative, else None."""
    if not (np.isfinite(period) and period > 0.0):
        return None
    k = 2.0 * np.pi / period
    r = round(k)
    return r if r >= 1 and abs(k - r) <= _PERIOD * k else None


def _numbers(value, name: str) -> np.ndarray:
    """``value`` as a 1-D float array, or a one-line error naming ``name``."""
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(name, shown(value), "numbers") from None
    if a.ndim > 1:
        raise ParameterError(name, f"an array of shape {a.shape}", "a list of numbers") from None
    a = a.reshape(-1)
    if not np.all(np.isfinite(a)):
        raise ParameterError(name, shown(list(a)), "finite numbers")
    return a


def from_fourier(period, mean_ratio, offset, a1, b1, a2, b2) -> FourierLaw:
    """A law from its Fourier series.

    Parameters
    ----------
    period : float
        Period P [rad]; ``2 pi / P`` an integer (e.g. ``2 pi``, ``pi / 2``).
    mean_ratio : pair of float
        Mean speed of each member over the shaft's [-].
    offset : pair of float
        Constant term of each member [rad].
    a1, b1, a2, b2 : sequence of float
        Cosine and sine coefficients of members 1 and 2 for the harmonics
        ``k = 1, 2, ...`` of ``2 pi / P`` [rad]; ``a_i`` and ``b_i`` equally long,
        at most 1000; the shorter member is padded with zeros.
    """
    p = _numbers(period, "drive.period")
    if p.size != 1 or _turn_divisions(float(p[0])) is None:
        raise ParameterError(
            "drive.period",
            f"{np.degrees(p[0]):.6g} deg" if p.size == 1 else shown(list(p)),
            "360 deg / k with k = 1, 2, 3 ... (the motion repeats k times a turn)",
        )
    pair = {}
    for name, value in (("drive.mean_ratio", mean_ratio), ("drive.offset", offset)):
        v = _numbers(value, name)
        if v.size != 2:
            raise ParameterError(name, shown(list(v)), "two numbers, one per member")
        pair[name] = v
    coeffs = []
    for i, (a, b) in enumerate(((a1, b1), (a2, b2)), start=1):
        a = _numbers(a, f"drive.a{i}")
        b = _numbers(b, f"drive.b{i}")
        if a.size != b.size:
            raise ParameterError(
                f"drive.b{i}",
                f"{b.size} coefficients",
                f"as many as drive.a{i} ({a.size}): the harmonics 1, 2, ... of member {i}",
            )
        if a.size > MAX_HARMONICS:
            raise ParameterError(
                f"drive.a{i}", f"{a.size} harmonics", f"at most {MAX_HARMONICS} harmonics"
            )
        coeffs.append((a, b))
    h = max(a.size for a, _ in coeffs)
    cos = np.zeros((2, h))
    sin = np.zeros((2, h))
    for i, (a, b) in enumerate(coeffs):
        cos[i, : a.size] = a
        sin[i, : b.size] = b
    return FourierLaw(
        2.0 * np.pi / _turn_divisions(float(p[0])),
        pair["drive.offset"],
        pair["drive.mean_ratio"],
        cos,
        sin,
    )


# --------------------------------------------------------------------------------------------
# a table
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class _Table:
    """A checked table: uniform samples over one period, trend taken out."""

    theta0: float  # first shaft angle [rad]
    period: float  # P = 2 pi / k exactly [rad]
    slope: np.ndarray  # (2,) mean ratio from the end points
    periodic: np.ndarray  # (2, N) angles minus the trend at the N distinct samples
    scale: float  # largest |q| of the table, for roundoff floors [rad]


def _deg(x) -> str:
    return f"{float(np.degrees(x)):.6g} deg"


def _checked(theta, q1, q2, name: str, where: str = "") -> _Table:
    """The table, checked; a one-line ParameterError naming ``name`` otherwise."""
    at = f"{where} " if where else ""
    cols = []
    for label, value in (("theta", theta), ("q1", q1), ("q2", q2)):
        try:
            a = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            raise ParameterError(name, f"{at}column {label}", "numbers in every row") from None
        if a.ndim != 1:
            raise ParameterError(
                name, f"{at}column {label} of shape {a.shape}", "a column of numbers (1-D)"
            )
        cols.append(a)
    rows = {c.size for c in cols}
    if len(rows) != 1:
        raise ParameterError(
            name,
            f"{at}columns of {cols[0].size}, {cols[1].size} and {cols[2].size} rows",
            "three columns of equal length (theta, q1, q2)",
        )
    n = cols[0].size
    if n < MIN_ROWS:
        raise ParameterError(
            name,
            f"{at}{n} rows",
            f"at least {MIN_ROWS} rows over one period, both end points included",
        )
    if n > MAX_ROWS:
        raise ParameterError(name, f"{at}{n} rows", f"at most {MAX_ROWS} rows")
    data = np.stack(cols)
    bad = ~np.isfinite(data)
    if bad.any():
        c, j = np.argwhere(bad)[np.argmin(np.argwhere(bad)[:, 1])]
        label = ("theta", "q1", "q2")[c]
        raise ParameterError(
            name, f"{at}row {j + 1} ({label} = {data[c, j]})", "finite numbers in every row"
        )
    th, q = data[0], data[1:]
    step = np.diff(th)
    if np.any(step <= 0.0):
        j = int(np.argmax(step <= 0.0)) + 1
        raise ParameterError(
            name,
            f"{at}row {j + 1} (theta = {_deg(th[j])} after {_deg(th[j - 1])})",
            "shaft angles strictly increasing from row to row",
        )
    span = th[-1] - th[0]
    k = _turn_divisions(span)
    if k is None:
        raise ParameterError(
            name,
            f"{at}a span of {_deg(span)}",
            "one period 360 deg / k (k = 1, 2, 3 ...) with both end points included, "
            "e.g. 0 to 360 deg",
        )
    period = 2.0 * np.pi / k
    intervals = n - 1
    h = period / intervals
    deviation = np.abs(step - h)
    j = int(np.argmax(deviation))
    if deviation[j] > _UNIFORM * h:
        raise ParameterError(
            name,
            f"{at}row {j + 2} (a step of {_deg(step[j])} where the mean step is {_deg(h)})",
            "uniform steps of the shaft angle (within 1e-6 of the step); resample the "
            "table at a fixed step of the shaft angle",
        )
    dq = np.diff(q, axis=1)
    big = np.abs(dq)
    near = np.maximum(np.roll(big, 1, axis=1), np.roll(big, -1, axis=1))
    jump = (big > np.pi) & (big > 10.0 * near)
    if jump.any():
        i, j = np.argwhere(jump)[0]
        raise ParameterError(
            name,
            f"{at}q{i + 1} rows {j + 1} to {j + 2} (a step of {_deg(dq[i, j])})",
            "continuous member angles, not wrapped into one turn (numpy.unwrap undoes that)",
        )
    slope = (q[:, -1] - q[:, 0]) / period
    periodic = q[:, :intervals] - slope[:, None] * (h * np.arange(intervals))
    _check_joint(periodic, big.max(axis=1) / h, h, name, at)
    return _Table(float(th[0]), period, slope, periodic, float(np.abs(q).max()))


def _slope_weights(m: int) -> np.ndarray:
    """Weights of the slope at 0 of the least-squares cubic through f(0), f(1) ... f(m-1)."""
    x = np.arange(m, dtype=float)
    return np.linalg.pinv(np.vander(x, 4, increasing=True))[1]


def _check_joint(periodic, largest_slope, h, name, at):
    """Refuse a table whose members do not join in slope across its ends (module docstring)."""
    n = periodic.shape[1]
    m = min(_KINK_WINDOW, max(4, n // 2))
    weights = _slope_weights(m)
    # slope from the samples ahead minus slope from the samples behind, at every sample
    jump = np.zeros_like(periodic)
    for i, w in enumerate(weights):
        jump += w * (np.roll(periodic, -i, axis=1) + np.roll(periodic, i, axis=1))
    jump /= h
    # the same at the ends from every second sample: a kink gives the same jump, the
    # estimate's own error (a smooth feature too narrow for the window) grows as h^3
    wide = sum(
        w * (periodic[:, (2 * i) % n] + periodic[:, (-2 * i) % n]) for i, w in enumerate(weights)
    ) / (2.0 * h)
    far = np.arange(m, n - m + 1)
    if far.size == 0:
        far = np.arange(1, n)
    noise = np.median(np.abs(jump[:, far]), axis=1)
    at_ends = np.abs(jump[:, 0])
    limit = np.maximum.reduce(
        [
            KINK_TOLERANCE * largest_slope,
            _KINK_NOISE * noise,
            _KINK_RICHARDSON * np.abs(wide - jump[:, 0]),
        ]
    )
    bad = at_ends > limit
    if bad.any():
        i = int(np.argmax(bad))
        ratio = at_ends[i] / largest_slope[i]
        raise ParameterError(
            name,
            f"{at}q{i + 1} (its slope jumps by {at_ends[i]:.3g} from the last row to the first, "
            f"{100.0 * ratio:.3g} % of its largest slope)",
            "a periodic motion that joins smoothly across the ends of the table (slope jump "
            "under 1 % of the largest slope); the table must cover exactly one period",
        )


def _harmonics(harmonics, n: int) -> int:
    """Number of harmonics of the fit of ``n`` distinct samples (``n // 2`` by default)."""
    if harmonics is None:
        return n // 2
    try:
        h = int(harmonics)
        ok = h == harmonics and not isinstance(harmonics, bool)
    except (TypeError, ValueError, OverflowError):
        ok = False
    if not ok or not 1 <= h <= n // 2:
        raise ParameterError(
            "drive.harmonics",
            shown(harmonics),
            f"an integer from 1 to {n // 2} (half the {n} distinct rows of the table)",
        )
    return h


def _coefficients(samples, harmonics):
    """Mean, cosine and sine coefficients of the trigonometric fit of uniform samples.

    ``samples`` (2, n) at ``x_j = 2 pi j / n``; the fit is
    ``a0 + sum_k a_k cos(k x) + b_k sin(k x)`` for ``k = 1..harmonics``; at
    ``harmonics = n / 2`` (n even) the last term is the Nyquist cosine.
    """
    n = samples.shape[1]
    spec = np.fft.rfft(samples, axis=1) / n
    a = 2.0 * spec[:, 1 : harmonics + 1].real
    b = -2.0 * spec[:, 1 : harmonics + 1].imag
    if 2 * harmonics == n:
        a[:, -1] *= 0.5
        b[:, -1] = 0.0
    return spec[:, 0].real, a, b


def _trimmed(a, b, scale):
    """Drop the trailing harmonics whose root-sum-square amplitude is below roundoff.

    Below ``2 eps scale`` they are the FFT's roundoff: they change the angles by
    that much and the derivatives by noise amplified by ``k^order``.
    """
    power = (a**2 + b**2).max(axis=0)
    tail = np.cumsum(power[::-1])[::-1]  # tail[k]: power from harmonic k + 1 on
    keep = int(np.count_nonzero(tail > (2.0 * _EPS * scale) ** 2))
    return a[:, :keep], b[:, :keep]


def _low_pass(samples, harmonics):
    """Uniform samples (last axis) without their harmonics above ``harmonics``."""
    spec = np.fft.rfft(samples, axis=-1)
    spec[..., harmonics + 1 :] = 0.0
    return np.fft.irfft(spec, n=samples.shape[-1], axis=-1)


def _fit(periodic, step, harmonics, scale):
    """Slope correction, mean, cosine and sine coefficients of the fit of uniform samples.

    ``periodic`` (2, n): the angles minus the trend through the end points, at
    ``theta_j = theta_0 + j step``. With all the harmonics the samples carry, the fit
    interpolates them and the trend stays. With fewer it is the least-squares fit of
    the trend's slope and the harmonics together (noise at the end points then does
    not tilt the trend): the slope moves by the correction that minimises the
    residual left by the low-pass filter.
    """
    n = periodic.shape[1]
    correction = np.zeros(2)
    if 2 * harmonics + 1 < n:
        ramp = step * np.arange(n)
        rest = ramp - _low_pass(ramp, harmonics)
        correction = (periodic - _low_pass(periodic, harmonics)) @ rest / (rest @ rest)
        periodic = periodic - correction[:, None] * ramp
    a0, a, b = _coefficients(periodic, harmonics)
    return (correction, a0, *_trimmed(a, b, scale))


def _scale(table: _Table) -> float:
    return max(table.scale, np.abs(table.periodic).max(), 1e-300)


def _law(table: _Table, correction, a0, a, b) -> FourierLaw:
    """The law of a table from coefficients about its first angle."""
    slope = table.slope + correction
    w = 2.0 * np.pi / table.period
    shift = np.arange(1, a.shape[1] + 1) * (w * np.mod(table.theta0, table.period))
    c, s = np.cos(shift), np.sin(shift)
    return FourierLaw(table.period, a0 - slope * table.theta0, slope, a * c - b * s, a * s + b * c)


def from_table(theta, q1, q2, harmonics=None, *, name: str = TABLE) -> FourierLaw:
    """The law of a table of member angles over one period.

    Parameters
    ----------
    theta : array_like, shape (n,)
        Shaft angles [rad], strictly increasing, uniform steps, spanning one period
        ``P = 2 pi / k`` with both end points included (e.g. 0 to 2 pi).
    q1, q2 : array_like, shape (n,)
        Angles of the members [rad], continuous (not wrapped into one turn).
    harmonics : int, optional
        Cut the fit to this many harmonics: the least-squares fit of a linear trend
        and that many harmonics to the ``n - 1`` distinct rows (the last row is the
        first one's periodic image), a low-pass filter for noisy data. Default: the
        interpolant, exact at the samples, with the trend through the end points.
    name : str, optional
        Parameter the errors name.

    Returns
    -------
    FourierLaw
        Trailing harmonics below roundoff are dropped. :func:`fit_error` estimates
        its error.
    """
    return _from_checked(_checked(theta, q1, q2, name), harmonics)


def _from_checked(table: _Table, harmonics) -> FourierLaw:
    p = table.periodic
    step = table.period / p.shape[1]
    return _law(table, *_fit(p, step, _harmonics(harmonics, p.shape[1]), _scale(table)))


def _on_grid(correction, a0, a, b, step, size):
    """The fit on ``size`` uniform angles over the period, shape (4, 2, size).

    Values and derivatives 1..3 of ``correction (theta - theta_0) + a0 + sum_k
    a_k cos(k x) + b_k sin(k x)`` (``x = 2 pi j / size``), by FFT; ``size`` more
    than twice the harmonics; ``step`` the table's.
    """
    w = 2.0 * np.pi / (step * size)
    k = np.arange(1, a.shape[1] + 1)
    spec = np.zeros((2, size // 2 + 1), dtype=complex)
    out = np.empty((4, 2, size))
    for order in range(4):
        spec[:, 0] = a0 * size if order == 0 else 0.0
        spec[:, 1 : k.size + 1] = 0.5 * size * (a - 1j * b) * (1j * k * w) ** order
        out[order] = np.fft.irfft(spec, n=size, axis=1)
    out[0] += correction[:, None] * (step * np.arange(size))
    out[1] += correction[:, None]
    return out


def _smallest_divisor(n: int) -> int | None:
    """Smallest divisor d >= 2 of n leaving at least 4 samples, else None."""
    for d in range(2, n // 4 + 1):
        if n % d == 0:
            return d
    return None


def fit_error(theta, q1, q2, harmonics=None, *, name: str = TABLE) -> FitError:
    """An over-estimate of the error of :func:`from_table`'s fit of this table.

    The table is fitted again from every d-th sample (d = 2 when the number of
    intervals is even, else its smallest divisor; from half the harmonics when it
    is prime) with at most as many harmonics. Returned, per member and order, the
    largest difference of that coarser fit: for the angles against the data at the
    samples it left out, for the derivatives against the full fit on the samples
    and midpoints; plus a roundoff floor ``8 eps max|q| (H w)^order``. For data
    the full fit resolves, the coarser fit's error is the larger (it is blind from
    half the frequency on), so this bounds the full fit's error over the table's
    range. With ``harmonics``, the data's noise counts as error of the angles.
    """
    table = _checked(theta, q1, q2, name)
    p = table.periodic
    n = p.shape[1]
    h = _harmonics(harmonics, n)
    step = table.period / n
    scale = _scale(table)
    full = _fit(p, step, h, scale)
    d = _smallest_divisor(n)
    if d is not None:
        coarse = _fit(p[:, ::d], d * step, min(h, (n // d) // 2), scale)
        left_out = np.arange(n) % d != 0
        suffix = {2: "nd", 3: "rd"}.get(d, "th")
        method = f"fit from every {d}{suffix} sample"
    else:
        coarse = _fit(p, step, h // 2, scale)
        left_out = np.ones(n, dtype=bool)
        method = "fit from half the harmonics"
    half = 0.5 * step
    on_full = _on_grid(*full, half, 2 * n)
    on_coarse = _on_grid(*coarse, half, 2 * n)
    diff = np.abs(on_coarse - on_full).max(axis=2)
    diff[0] = np.abs(on_coarse[0][:, ::2] - p)[:, left_out].max(axis=1)
    top = max(full[2].shape[1], 1) * 2.0 * np.pi / table.period
    floor = 8.0 * _EPS * table.scale * top ** np.arange(4)
    return FitError(*(diff + floor[:, None]), method=method)


# --------------------------------------------------------------------------------------------
# CSV
# --------------------------------------------------------------------------------------------
_UNITS = {
    "deg": "deg",
    "degree": "deg",
    "degrees": "deg",
    "°": "deg",
    "rad": "rad",
    "radian": "rad",
    "radians": "rad",
}
_BRACKETED = re.compile(r"^(.*?)\s*(?:\[\s*([^\]]*?)\s*\]|\(\s*([^)]*?)\s*\))$")
_SUFFIXED = re.compile(r"^(.*?)_(deg|rad)$", re.IGNORECASE)


def _unit(column: str) -> str | None:
    """``"deg"`` or ``"rad"`` from a header cell (``x [deg]``, ``x (rad)``, ``x_deg``), or None."""
    match = _BRACKETED.match(column)
    if match:
        return _UNITS.get((match.group(2) or match.group(3) or "").lower())
    match = _SUFFIXED.match(column)
    return match.group(2).lower() if match else None


def _cut_list(names, most: int = 160) -> str:
    text = ", ".join(names)
    return text if len(text) <= most else text[: most - 3] + f"... ({len(names)} columns)"


def read_table(path, columns=None, *, name: str = TABLE):
    """Shaft angle and two member angles from a CSV file, in radians.

    Parameters
    ----------
    path : str or Path
        A regular file of at most 16 MiB, UTF-8. Lines starting with ``#`` and blank
        lines are skipped; the first other line is the header. Cells are separated by
        commas (or semicolons or tabs, as the header is).
    columns : sequence of 3 str, optional
        Header names of the shaft angle and the two member angles; default the first
        three columns. E.g. rotorkin's ``motion.csv``:
        ``["theta_deg", "rotor1_angle_deg", "rotor2_angle_deg"]``.
    name : str, optional
        Parameter the errors name.

    Each column read names its unit: ``theta [deg]``, ``theta (rad)``, ``theta_deg``,
    ``theta_rad`` (deg, degree(s), rad, radian(s)).

    Returns
    -------
    (theta, q1, q2) : tuple of ndarray [rad]
    """
    path = Path(path)
    label = shown(path.name)
    try:
        info = path.stat()
    except OSError as exc:
        raise ParameterError(name, label, f"a readable CSV file ({exc.strerror})") from None
    if not stat.S_ISREG(info.st_mode):
        raise ParameterError(name, label, "a regular file (not a folder, device or pipe)")
    if info.st_size > MAX_FILE_BYTES:
        raise ParameterError(
            name, f"{label} ({info.st_size / 2**20:.1f} MiB)", "a CSV file of at most 16 MiB"
        )
    try:
        with open(path, "rb") as f:
            raw = f.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise ParameterError(name, label, f"a readable CSV file ({exc.strerror})") from None
    if len(raw) > MAX_FILE_BYTES:
        raise ParameterError(name, f"{label} (over 16 MiB)", "a CSV file of at most 16 MiB")
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise ParameterError(name, label, "a UTF-8 text file") from None
    if "\x00" in text:
        raise ParameterError(name, label, "a text file (it holds NUL bytes)")
    lines = text.splitlines()
    content = [
        (number, line)
        for number, line in enumerate(lines, start=1)
        if line.strip() and not line.lstrip().startswith("#")
    ]
    if not content:
        raise ParameterError(
            name, f"{label} (no header)", "a header naming the columns with their units"
        )
    head_line = content[0][1]
    delimiter = next((d for d in ",;\t" if d in head_line), ",")
    header = [cell.strip() for cell in next(csv.reader([head_line], delimiter=delimiter))]
    if columns is None:
        if len(header) < 3:
            raise ParameterError(
                name,
                f"{label} header {shown(head_line)}",
                "at least three columns: shaft angle, member 1, member 2 (comma separated)",
            )
        index = [0, 1, 2]
    else:
        if isinstance(columns, str) or len(columns) != 3:
            raise ParameterError(
                name, f"columns {shown(columns)}", "three column names: shaft, member 1, member 2"
            )
        index = []
        for column in columns:
            found = [i for i, cell in enumerate(header) if cell == str(column).strip()]
            if not found:
                found = [i for i, c in enumerate(header) if c.lower() == str(column).lower()]
            if not found:
                raise ParameterError(
                    name,
                    f"{label} column {shown(column)}",
                    f"one of the columns {_cut_list(header)}",
                )
            index.append(found[0])
    units = []
    for i in index:
        unit = _unit(header[i])
        if unit is None:
            raise ParameterError(
                name,
                f"{label} column {shown(header[i])} without a unit",
                "a unit in each header cell read: 'theta [deg]', 'theta (rad)', 'theta_deg' "
                "or 'theta_rad'",
            )
        units.append(unit)
    rows = content[1:]
    if len(rows) > MAX_ROWS:
        raise ParameterError(name, f"{label} ({len(rows)} rows)", f"at most {MAX_ROWS} rows")
    values = np.empty((3, len(rows)))
    last = max(index)
    for r, (number, line) in enumerate(rows):
        if '"' in line:
            cells = next(csv.reader([line], delimiter=delimiter))
        else:
            cells = line.split(delimiter)
        if len(cells) <= last:
            raise ParameterError(
                name,
                f"{label} line {number} ({len(cells)} cells)",
                f"a cell in each column read ({len(header)} columns in the header)",
            )
        for c, i in enumerate(index):
            try:
                values[c, r] = float(cells[i])
            except ValueError:
                values[c, r] = np.nan
            if not np.isfinite(values[c, r]):
                raise ParameterError(
                    name,
                    f"{label} line {number} column {shown(header[i])}: {shown(cells[i].strip())}",
                    "a finite number in every cell of the columns read",
                )
    for c, unit in enumerate(units):
        if unit == "deg":
            values[c] = np.radians(values[c])
    return values[0], values[1], values[2]


def from_csv(path, columns=None, harmonics=None, *, name: str = TABLE) -> FourierLaw:
    """:func:`from_table` of :func:`read_table` (errors name the file and the row)."""
    theta, q1, q2 = read_table(path, columns, name=name)
    return _from_checked(_checked(theta, q1, q2, name, shown(Path(path).name)), harmonics)
