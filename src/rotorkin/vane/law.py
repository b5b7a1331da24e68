"""The motion a rotary two-member drive gives a vane machine: :class:`RotaryLaw`.

Every vane machine (twin-rotor engine, differential vane pump, rotary-blade
engine) is two coaxial members whose vanes bound the chambers; all it needs from
its drive is the members' angles ``q_1(theta), q_2(theta)`` over the shaft angle
with three exact derivatives, and the shaft angle ``period`` after which the
relative angle ``r = q_2 - q_1`` and the speed ratios repeat. From those this
module finds, for any drive:

* the stationary points of ``r`` in one period (its turning points, where every
  chamber is at a dead centre): sign changes of ``r'`` on a grid, refined by a
  safeguarded Newton iteration on the exact ``r''`` (a drive may give them in
  closed form instead);
* the extremes and swing of ``r``, the volume cycles per shaft turn;
* a stroke counter: 1 at the largest ``r`` nearest ``theta = 0``, one more at
  every turning point, linear in between.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from rotorkin.core.errors import ParameterError
from rotorkin.core.motion import Motion

__all__ = [
    "RotaryLaw",
    "turning_points",
    "relative_extremes",
    "strokes_per_turn",
    "stroke_counter",
    "mounted",
]

_TWO_PI = 2.0 * np.pi
#: Grid of the search for turning points, per period.
_SEARCH = 4096


@dataclass(frozen=True)
class RotaryLaw:
    """Two coaxial members turned by one shaft, as a vane machine sees them.

    Attributes
    ----------
    motion : callable
        ``motion(theta) -> Motion`` of the two members [rad], any shape of theta.
    period : float
        Shaft angle after which ``r = q_2 - q_1`` and the speed ratios repeat;
        ``2 pi / period`` or ``period / 2 pi`` is an integer [rad] (a drive with
        gears may repeat only after several turns).
    turning : tuple of float, optional
        The stationary points of ``r`` in ``[0, period)`` in closed form, sorted;
        found numerically when None.
    """

    motion: Callable[..., Motion]
    period: float
    turning: tuple[float, ...] | None = None

    def __post_init__(self):
        p = float(self.period)
        k = max(_TWO_PI / p, p / _TWO_PI) if np.isfinite(p) and p > 0 else 0.5
        if not (k >= 1.0 and abs(k - round(k)) < 1e-9 * k):
            raise ValueError(f"period {p!r} must divide a turn or be a whole number of turns")

    @property
    def span(self) -> float:
        """Shaft angle after which the whole machine repeats: a turn, or the period [rad]."""
        return max(float(self.period), _TWO_PI)


def _rdot(law: RotaryLaw, theta):
    m = law.motion(theta)
    return m.dq[1] - m.dq[0], m.d2q[1] - m.d2q[0]


def turning_points(law: RotaryLaw, samples: int = _SEARCH) -> np.ndarray:
    """Shaft angles in ``[0, period)`` where ``r' = 0`` and changes sign, sorted [rad].

    Sign changes of ``r'`` on ``samples`` angles, each bracket refined by Newton
    steps on the exact ``r''`` kept inside the bracket (bisection otherwise), to
    rounding. Zeros of ``r'`` where it does not change sign (an inflection with a
    dwell) are not turning points. A root within 1e-12 of a period's end is put at 0.
    """
    if law.turning is not None:
        return np.asarray(law.turning, dtype=float)
    p = float(law.period)
    t = np.linspace(0.0, p, samples + 1)
    f = _rdot(law, t)[0]
    scale = float(np.max(np.abs(f))) if f.size else 0.0
    f = np.where(np.abs(f) <= 1e-14 * scale, 0.0, f)
    # a bracket [t_i, t_i+1] with a sign change; an exact zero counts once (at its sample)
    s = np.sign(f)
    nz = np.flatnonzero(s != 0)
    if nz.size < 2:
        return np.zeros(0)
    # carry signs over exact zeros: compare consecutive nonzero samples
    a_idx, b_idx = nz[:-1], nz[1:]
    change = s[a_idx] != s[b_idx]
    # the wrap from the last nonzero sample to the first one of the next period
    lo, hi = t[a_idx[change]], t[b_idx[change]]
    if s[nz[-1]] != s[nz[0]]:
        lo = np.append(lo, t[nz[-1]])
        hi = np.append(hi, t[nz[0]] + p)
    if lo.size == 0:
        return np.zeros(0)
    flo = _rdot(law, lo)[0]
    x = 0.5 * (lo + hi)
    for _ in range(100):
        fx, dfx = _rdot(law, x)
        left = np.sign(fx) == np.sign(flo)
        lo, hi = np.where(left, x, lo), np.where(left, hi, x)
        flo = np.where(left, fx, flo)
        with np.errstate(divide="ignore", invalid="ignore"):
            newton = x - fx / dfx
        inside = np.isfinite(newton) & (newton > lo) & (newton < hi)
        x_new = np.where(inside, newton, 0.5 * (lo + hi))
        if np.all(np.abs(x_new - x) <= 4e-16 * p):
            x = x_new
            break
        x = x_new
    x = np.mod(x, p)
    x = np.where((x < 1e-12 * p) | (p - x < 1e-12 * p), 0.0, x)
    return np.unique(np.sort(x))


def relative_extremes(law: RotaryLaw, points=None) -> tuple[float, float]:
    """Smallest and largest ``r = q_2 - q_1`` over a period [rad]."""
    points = turning_points(law) if points is None else points
    if len(points) == 0:
        return _sampled_extremes(law)
    q = law.motion(np.asarray(points)).q
    r = q[1] - q[0]
    return float(np.min(r)), float(np.max(r))


def _sampled_extremes(law: RotaryLaw):
    q = law.motion(np.linspace(0.0, law.period, 257)).q
    r = q[1] - q[0]
    return float(np.min(r)), float(np.max(r))


def strokes_per_turn(law: RotaryLaw, points=None) -> float:
    """Turning points of ``r`` per shaft turn: the strokes each chamber makes in one turn.

    A whole number when the period divides the turn; may be a fraction when the
    law repeats only after several turns.
    """
    points = turning_points(law) if points is None else points
    return len(points) * _TWO_PI / float(law.period)


def stroke_counter(law: RotaryLaw, theta, points=None):
    """Strokes since chamber 1's reference, ``c(theta)``: integers at the turning points.

    ``c = 1`` at the largest ``r`` that is nearest ``theta = 0`` (the start of a
    compression for a chamber that grows with ``r``), one more at each later
    turning point, linear in the shaft angle in between.
    """
    points = turning_points(law) if points is None else np.asarray(points, dtype=float)
    p, n = float(law.period), len(points)
    if n == 0:
        raise ParameterError("drive", "a drive without relative motion",
                             "a drive that swings the members against each other")  # fmt: skip
    at = law.motion(points)
    r = at.q[1] - at.q[0]
    d2 = at.d2q
    is_max = (d2[1] - d2[0]) < 0
    if not np.any(is_max):
        is_max = r >= np.max(r)
    dist = np.minimum(points, p - points)
    ref = int(np.flatnonzero(is_max)[np.argmin(np.where(is_max, dist, np.inf)[is_max])])
    theta = np.asarray(theta, dtype=float)
    knots = np.concatenate([points - p, points, points + p])
    counts = np.arange(-n, 2 * n, dtype=float) - ref + 1.0
    base = np.floor(theta / p)
    local = theta - base * p
    c = np.interp(local, knots, counts) + n * base
    near = np.round(c)
    return np.where(np.abs(c - near) < 1e-9, near, c)  # on a turning point, within rounding


def mounted(motion: Motion, shift: float) -> Motion:
    """The motion with member 2 turned by ``shift`` [rad]: where the machine mounts its vanes."""
    if shift == 0.0:
        return motion
    q = motion.q.copy()
    q[1] = q[1] + shift
    return replace(motion, q=q)
