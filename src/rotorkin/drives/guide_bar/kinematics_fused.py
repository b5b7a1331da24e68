"""Fused evaluation of the impeller angles of the guide-bar drive.

The closed forms of :func:`rotorkin.drives.guide_bar.kinematics.impeller_angles` and
:func:`~rotorkin.drives.guide_bar.kinematics.impeller_rates` rearranged so that each
point costs one ``tan`` and one ``arctan`` per mechanism (and a square root per
mechanism when the guide bars drive):

* the driving angles ``x_1 = theta/i12``, ``x_2 = x_1 + Sigma``; ``t_k = tan(x_k/2)``
  gives ``cos x_k = (1 - t_k)(1 + t_k)/(1 + t_k^2)``, ``sin x_k = 2 t_k/(1 + t_k^2)``
  (a few ulp relative to their size; ``|t| < 2e16`` for any double). One ``tan`` and
  angle sums with ``cos Sigma``, ``sin Sigma`` would do for ``x_2`` too, but would
  round differently from the mechanism's own angle: where both impellers turn
  equally fast the pump's ports switch over, and there the sign of the last ulp
  of ``q_2' - q_1'`` picks the chamber pressures of the pair forces;
* crank-driven, the guide bar angle ``g(x) = x + atan(-lambda sin x/(1 + lambda cos x))``
  (the vector ``(lambda + cos x, sin x)`` rotated by ``-x`` is
  ``(1 + lambda cos x, -lambda sin x)``, whose first component is positive for
  ``lambda < 1``: the continuous branch, as
  :func:`~rotorkin.drives.guide_bar.kinematics.guide_angle`);
* guide-driven, the crank angle ``h(y) = y + atan(lambda sin y/W)``,
  ``W = sqrt(1 - lambda^2 sin^2 y)`` (the crank pin rotated by ``-y`` is
  ``(W, lambda sin y)``, as :func:`~rotorkin.drives.guide_bar.kinematics.crank_angle`);
* their derivatives (:func:`~rotorkin.drives.guide_bar.kinematics.guide_rates`,
  :func:`~rotorkin.drives.guide_bar.kinematics.crank_rates`), and the impellers'
  ``q_k = f(x_k)/u``, ``q_k^(n) = f^(n)(x_k)/(u i12^n)``.

The formulas below are evaluated by numpy on blocks of points (the fallback), or
compiled by numba into loops around the block's numpy ``tan`` and ``arctan``
(:mod:`rotorkin.core.fused`); both give the same numbers.
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.fused import at, compiled_loop, evaluate, formula, select

__all__ = [
    "QUARTER_TURN_ZERO",
    "atan_argument",
    "driven_rates_point",
    "half_angle_trig",
    "impellers_fused",
]

#: ``|cos x|`` at or below this is rounding noise of the half-angle form (2 ulp of 1).
QUARTER_TURN_ZERO = 2.0 * np.finfo(float).eps


@formula
def half_angle_trig(t):
    """``cos x``, ``sin x`` from ``t = tan(x/2)``.

    Near a quarter turn (``t`` near +-1) ``cos x`` carries the rounding of ``t``: an
    absolute error of about 1e-16. Values within ``QUARTER_TURN_ZERO`` of 0 are that
    noise and are set to 0, so that the quarter-turn points of both mechanisms give
    the same numbers (there both impellers turn equally fast and the pump's ports
    switch over: exactly equal speeds take the switch-over's own rule).
    """
    d = 1.0 / (t * t + 1.0)
    c = (1.0 - t) * (1.0 + t) * d
    return select(np.abs(c) <= QUARTER_TURN_ZERO, 0.0, c), 2.0 * t * d


@formula
def crank_atan_argument(c, s, lam):
    """:func:`atan_argument` of a crank-driven mechanism."""
    return -(lam * s) / (1.0 + lam * c)


@formula
def guide_atan_argument(c, s, lam):
    """:func:`atan_argument` of a guide-driven mechanism."""
    ls = lam * s
    return ls / np.sqrt(1.0 - ls * ls)


@formula
def atan_argument(c, s, lam, guide):
    """The driven angle minus the driving angle is the arctangent of this (see module)."""
    return select(guide, guide_atan_argument(c, s, lam), crank_atan_argument(c, s, lam))


@formula
def crank_rates_point(c, s, lam, k):
    """The crank-driven law of :func:`driven_rates_point`: ``g', g'', g'''``."""
    lc = lam * c
    dd = 1.0 + 2.0 * lc + lam * lam
    r = 1.0 / dd
    r2 = r * r
    return (1.0 + lc) * r, k * s * r2, k * (dd * c + 4.0 * lam * (s * s)) * (r2 * r)


@formula
def guide_rates_point(c, s, lam, k):
    """The guide-driven law of :func:`driven_rates_point`: ``h', h'', h'''``."""
    ls = lam * s
    iw = 1.0 / np.sqrt(1.0 - ls * ls)
    iw2 = iw * iw
    iw3 = iw2 * iw
    return (1.0 + (lam * c) * iw, -(k * s) * iw3,
            -(k * c) * (1.0 + 2.0 * (ls * ls)) * (iw3 * iw2))  # fmt: skip


@formula
def driven_rates_point(c, s, lam, k, guide):
    """``f', f'', f'''`` of the driven member w.r.t. its driving angle.

    With ``k = lambda (1 - lambda^2)``: crank-driven ``g' = (1 + lambda c)/D``,
    ``g'' = k s/D^2``, ``g''' = k (D c + 4 lambda s^2)/D^3``, ``D = 1 + 2 lambda c + lambda^2``;
    guide-driven ``h' = 1 + lambda c/W``, ``h'' = -k s/W^3``,
    ``h''' = -k c (1 + 2 lambda^2 s^2)/W^5``. One division per law (reciprocals). numpy
    evaluates both laws on a block and selects; the compiled loops evaluate each point's
    own law only (:func:`_rates`).
    """
    h1, h2, h3 = guide_rates_point(c, s, lam, k)
    g1, g2, g3 = crank_rates_point(c, s, lam, k)
    return select(guide, h1, g1), select(guide, h2, g2), select(guide, h3, g3)


@formula
def _rates(c, s, lam, k, guide):
    """:func:`driven_rates_point` of one point in a compiled loop: its own law only."""
    if guide:
        return guide_rates_point(c, s, lam, k)
    return crank_rates_point(c, s, lam, k)


@compiled_loop
def _driving_loop(theta, i12, phase, x1, x2, h1, h2):
    """The driving angles ``x_1 = theta/i12``, ``x_2 = x_1 + Sigma`` and their halves."""
    for i in range(x1.shape[0]):
        a = at(theta, i) / at(i12, i)
        b = a + at(phase, i)
        x1[i], x2[i], h1[i], h2[i] = a, b, a * 0.5, b * 0.5


@compiled_loop
def _atan_rate_loop(t1, t2, lam, k, guide, w1, w2, w3, r1, r2, o2, o3, o4, o5, o6, o7):
    """The arctangents' arguments and every derivative: ``c``, ``s`` once per point."""
    for i in range(r1.shape[0]):
        c1, s1 = half_angle_trig(t1[i])
        c2, s2 = half_angle_trig(t2[i])
        la, kk, gd = at(lam, i), at(k, i), at(guide, i)
        v1, v2, v3 = at(w1, i), at(w2, i), at(w3, i)
        if gd:  # each point's own law (one design: a loop-invariant branch)
            r1[i] = guide_atan_argument(c1, s1, la)
            r2[i] = guide_atan_argument(c2, s2, la)
        else:
            r1[i] = crank_atan_argument(c1, s1, la)
            r2[i] = crank_atan_argument(c2, s2, la)
        f1, f2, f3 = _rates(c1, s1, la, kk, gd)
        o2[i], o4[i], o6[i] = f1 * v1, f2 * v2, f3 * v3
        f1, f2, f3 = _rates(c2, s2, la, kk, gd)
        o3[i], o5[i], o7[i] = f1 * v1, f2 * v2, f3 * v3


@compiled_loop
def _angle_loop(x1, x2, e1, e2, iu, o0, o1):
    """``q_k = (x_k + atan(.))/u``."""
    for i in range(o0.shape[0]):
        iuu = at(iu, i)
        o0[i] = (x1[i] + e1[i]) * iuu
        o1[i] = (x2[i] + e2[i]) * iuu


@compiled_loop
def _rate_loop(t1, t2, lam, k, guide, w1, w2, w3, o0, o1, o2, o3, o4, o5):
    for i in range(o0.shape[0]):
        c1, s1 = half_angle_trig(t1[i])
        c2, s2 = half_angle_trig(t2[i])
        la, kk, gd = at(lam, i), at(k, i), at(guide, i)
        v1, v2, v3 = at(w1, i), at(w2, i), at(w3, i)
        f1, f2, f3 = _rates(c1, s1, la, kk, gd)
        o0[i], o2[i], o4[i] = f1 * v1, f2 * v2, f3 * v3
        f1, f2, f3 = _rates(c2, s2, la, kk, gd)
        o1[i], o3[i], o5[i] = f1 * v1, f2 * v2, f3 * v3


def _constants(x):
    """Per-design values: ``k = lambda (1 - lambda^2)``, ``1/u``, ``1/(u i12^n)``."""
    lam, u, i12 = x["lam"], x["u"], x["i12"]
    w1 = 1.0 / (u * i12)
    w2 = w1 / i12
    return {"k": lam * (1.0 - lam * lam), "iu": 1.0 / u, "w1": w1, "w2": w2, "w3": w2 / i12}


_CONSTANT_INPUTS = ("lam", "u", "i12")


def _driving(x, m):
    """``x_1``, ``x_2`` (2, m) and ``t_k = tan(x_k/2)`` (2, m) of a block."""
    xs = np.empty((2, m))
    np.divide(x["theta"], x["i12"], out=xs[0])
    np.add(xs[0], x["phase"], out=xs[1])
    t = np.multiply(xs, 0.5)
    np.tan(t, out=t)
    return xs, t


def _angle_block(x, o, compiled):
    m = o.shape[1]
    design = (x["lam"], x["k"], x["guide"])
    scale = (x["iu"], x["w1"], x["w2"], x["w3"])
    if compiled:  # 5 calls a block: x_k, tan, arguments and derivatives, arctan, q_k
        w = np.empty((6, m))
        xs, t, e = w[0:2], w[2:4], w[4:6]
        _driving_loop(x["theta"], x["i12"], x["phase"], *xs, *t)
        np.tan(t, out=t)
        _atan_rate_loop(*t, *design, *scale[1:], *e, *o[2:])
        np.arctan(e, out=e)
        _angle_loop(*xs, *e, scale[0], o[0], o[1])
        return
    xs, t = _driving(x, m)
    c1, s1 = half_angle_trig(t[0])
    c2, s2 = half_angle_trig(t[1])
    e1 = np.arctan(atan_argument(c1, s1, x["lam"], x["guide"]))
    e2 = np.arctan(atan_argument(c2, s2, x["lam"], x["guide"]))
    o[0] = (xs[0] + e1) * x["iu"]
    o[1] = (xs[1] + e2) * x["iu"]
    for mech, (c, s) in enumerate(((c1, s1), (c2, s2))):
        for order, f in enumerate(driven_rates_point(c, s, *design), start=1):
            o[2 * order + mech] = f * scale[order]


def _rate_block(x, o, compiled):
    _, t = _driving(x, o.shape[1])
    design = (x["lam"], x["k"], x["guide"])
    scale = (x["w1"], x["w2"], x["w3"])
    if compiled:
        _rate_loop(t[0], t[1], *design, *scale, *o)
        return
    c1, s1 = half_angle_trig(t[0])
    c2, s2 = half_angle_trig(t[1])
    for mech, (c, s) in enumerate(((c1, s1), (c2, s2))):
        for order, f in enumerate(driven_rates_point(c, s, *design)):
            o[2 * order + mech] = f * scale[order]


def impellers_fused(lam, gear_ratio, input_gear_ratio, phase, guide, theta, *, angles=True,
                    threads=None, kernel=None, out=None):  # fmt: skip
    """Impeller angles and derivatives (or the derivatives alone), block by block.

    Parameters
    ----------
    lam, gear_ratio, input_gear_ratio, phase : array_like
        ``lambda``, ``u``, ``i12``, ``Sigma`` [rad] (checked by the caller).
    guide : bool or array_like of bool
        True where the guide bars drive, False where the cranks drive.
    theta : array_like
        Input gear angle [rad]; broadcasts with the parameters.
    angles : bool
        Also the angles ``q`` (two arctangents per point); else the derivatives only.
    threads : int, optional
        Threads for large inputs (:func:`rotorkin.core.fused.split`).
    kernel : {"auto", "numpy", "numba"}, optional
        :func:`rotorkin.core.fused.use_compiled`.
    out : ndarray, optional
        Float64 C-contiguous array of the result's shape to write into.

    Returns
    -------
    ndarray, shape (4, 2, ...) or (3, 2, ...)
        ``q, dq/dtheta, d2q/dtheta2, d3q/dtheta3`` of impeller 1 and 2 (axis 1)
        [rad, -, 1/rad, 1/rad^2]; without ``q`` when not ``angles``.
    """
    inputs = {
        "theta": theta,
        "lam": lam,
        "u": gear_ratio,
        "i12": input_gear_ratio,
        "phase": phase,
        "guide": np.asarray(guide, dtype=float),
    }
    orders = 4 if angles else 3
    res = evaluate(
        inputs,
        2 * orders,
        _angle_block if angles else _rate_block,
        threads=threads,
        kernel=kernel,
        out=None if out is None else out.reshape(2 * orders, *out.shape[2:]),
        constants=(_constants, _CONSTANT_INPUTS),
    )
    return res.reshape(orders, 2, *res.shape[1:])
