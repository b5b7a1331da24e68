"""Fused evaluation of the rotor angles of the non-circular gear drive.

The closed form of :func:`rotorkin.drives.noncircular_gears.kinematics.motion`
(``q_1 = phi2(theta)``, ``q_2 = phi2(theta + sigma) - phi2(sigma)``, the derivatives
from :func:`~rotorkin.drives.noncircular_gears.kinematics.ratio`) rearranged so that
each point costs one ``tan`` and one ``arctan`` per rotor, in dimensionless terms
(``C/a = e``, ``B/a = beta``, ``S/a = root``, ``p/a = pa``):

* ``t_k = n theta_k`` (``theta_1 = theta``, ``theta_2 = theta + sigma``) and
  ``tau = tan(t_k/2)``: ``cos t_k = (1 - tau)(1 + tau)/(1 + tau^2)``,
  ``sin t_k = 2 tau/(1 + tau^2)``;
* ``phi2(t) = (t + 2 atan(e sin t/(beta + root - e cos t)))/m`` (module text of
  :mod:`~rotorkin.drives.noncircular_gears.kinematics`: the denominator is at least
  ``beta + root - e > 0``, so no branch jumps);
* ``D = beta - e cos t``, ``D' = n e sin t``, ``D'' = n^2 e cos t`` and
  ``R = pa/D``, ``R' = -pa D'/D^2``, ``R'' = pa (2 D'^2/D^3 - D''/D^2)``.

:func:`rotor_point` and :func:`atan_argument` are the formulas: numpy evaluates
them on blocks (the fallback); with numba they are compiled into loops around the
block's numpy ``tan`` and ``arctan`` (:mod:`rotorkin.core.fused`). Both give the same
numbers.
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.fused import at, compiled_loop, evaluate, formula

__all__ = ["atan_argument", "half_angle_trig", "motion_fused", "rotor_point"]


@formula
def half_angle_trig(tau):
    """``cos t``, ``sin t`` from ``tau = tan(t/2)``."""
    d = 1.0 / (tau * tau + 1.0)
    return (1.0 - tau) * (1.0 + tau) * d, 2.0 * tau * d


@formula
def atan_argument(c, s, e, beta, root):
    """``e sin t/(beta + root - e cos t)``: ``phi2 = (t + 2 atan(.))/m``."""
    return e * s / (beta + root - e * c)


@formula
def rotor_point(t, c, s, atan, n, m, e, pa, beta, offset):
    """``phi2 - offset`` and its derivatives ``R, R', R''`` at ``t = n phi1``."""
    d = beta - e * c
    d1 = n * e * s
    d2 = n * n * e * c
    dd = d * d
    return (
        (t + 2.0 * atan) / m - offset,
        pa / d,
        -pa * d1 / dd,
        pa * (2.0 * d1 * d1 / (dd * d) - d2 / dd),
    )


@compiled_loop
def _driving_loop(n, theta, sigma, t1, t2, h1, h2):
    """``t_1 = n theta``, ``t_2 = n (theta + sigma)`` and their halves."""
    for i in range(t1.shape[0]):
        nn, th = at(n, i), at(theta, i)
        a = nn * th
        b = nn * (th + at(sigma, i))
        t1[i], t2[i], h1[i], h2[i] = a, b, a * 0.5, b * 0.5


@compiled_loop
def _atan_ratio_loop(t1, t2, tau1, tau2, n, m, e, pa, beta, root, r1, r2, o2, o3, o4, o5, o6,
                     o7):  # fmt: skip
    """The arctangents' arguments and ``R, R', R''`` of both rotors: ``c``, ``s`` once."""
    for i in range(r1.shape[0]):
        nn, mm, ee, pp, bb = at(n, i), at(m, i), at(e, i), at(pa, i), at(beta, i)
        rr = at(root, i)
        c, s = half_angle_trig(tau1[i])
        r1[i] = atan_argument(c, s, ee, bb, rr)
        _, o2[i], o4[i], o6[i] = rotor_point(t1[i], c, s, 0.0, nn, mm, ee, pp, bb, 0.0)
        c, s = half_angle_trig(tau2[i])
        r2[i] = atan_argument(c, s, ee, bb, rr)
        _, o3[i], o5[i], o7[i] = rotor_point(t2[i], c, s, 0.0, nn, mm, ee, pp, bb, 0.0)


@compiled_loop
def _angle_loop(t1, t2, e1, e2, m, offset, o0, o1):
    """``phi2(t_k) - offset_k = (t_k + 2 atan(.))/m - offset_k``."""
    for i in range(o0.shape[0]):
        mm = at(m, i)
        o0[i] = (t1[i] + 2.0 * e1[i]) / mm
        o1[i] = (t2[i] + 2.0 * e2[i]) / mm - at(offset, i)


def _block(x, o, compiled):
    m = o.shape[1]
    design = (x["e"], x["beta"], x["root"])
    if compiled:  # 5 calls a block: t_k, tan, arguments and ratios, arctan, angles
        w = np.empty((6, m))
        t, tau, e = w[0:2], w[2:4], w[4:6]
        _driving_loop(x["n"], x["theta"], x["sigma"], *t, *tau)
        np.tan(tau, out=tau)
        _atan_ratio_loop(*t, *tau, x["n"], x["m"], x["e"], x["pa"], x["beta"], x["root"], *e,
                         *o[2:])  # fmt: skip
        np.arctan(e, out=e)
        _angle_loop(*t, *e, x["m"], x["offset"], o[0], o[1])
        return
    t = np.empty((2, m))
    np.multiply(x["n"], x["theta"], out=t[0])
    np.multiply(x["n"], x["theta"] + x["sigma"], out=t[1])
    tau = np.multiply(t, 0.5)
    np.tan(tau, out=tau)
    for k, offset in ((0, 0.0), (1, x["offset"])):
        c, s = half_angle_trig(tau[k])
        atan = np.arctan(atan_argument(c, s, *design))
        values = rotor_point(t[k], c, s, atan, x["n"], x["m"], x["e"], x["pa"], x["beta"], offset)
        for order, value in enumerate(values):
            o[2 * order + k] = value


def motion_fused(lobes, rotor_lobes, eccentricity, pa, beta, root, sigma, offset, theta, *,
                 threads=None, kernel=None, out=None):  # fmt: skip
    """Angles of both rotors and their derivatives, block by block.

    Parameters
    ----------
    lobes, rotor_lobes, eccentricity : array_like
        ``n``, ``m``, ``e`` of the design.
    pa, beta, root : array_like
        ``p/a``, ``B/a``, ``S/a`` (the closure root and its consequences).
    sigma : array_like
        Phase of driving gear 2 [rad].
    offset : array_like
        ``phi2(sigma)`` [rad]: rotor 2 is measured from its position at ``theta = 0``.
    theta : array_like
        Output shaft angle [rad]; broadcasts with the parameters.
    threads : int, optional
        Threads for large inputs (:func:`rotorkin.core.fused.split`).
    kernel : {"auto", "numpy", "numba"}, optional
        :func:`rotorkin.core.fused.use_compiled`.
    out : ndarray, optional
        ``(4, 2, ...)`` float64 C-contiguous array to write into.

    Returns
    -------
    ndarray, shape (4, 2, ...)
        ``q, dq, d2q, d3q`` of rotor 1 and rotor 2 (axis 1) [rad, -, 1/rad, 1/rad^2].
    """
    inputs = {
        "theta": theta,
        "n": lobes,
        "m": rotor_lobes,
        "e": eccentricity,
        "pa": pa,
        "beta": beta,
        "root": root,
        "sigma": sigma,
        "offset": offset,
    }
    flat_out = None if out is None else out.reshape(8, *out.shape[2:])
    res = evaluate(inputs, 8, _block, threads=threads, kernel=kernel, out=flat_out)
    return res.reshape(4, 2, *res.shape[1:])
