"""Fused evaluation of the piston travels of the double eccentric cam.

The closed form of :func:`rotorkin.drives.eccentric_cam.kinematics.travels` (eq. 1-8)
rearranged so that each point costs one ``tan`` and one ``sqrt``:

* ``t = tan(beta/2)``: ``cos beta = (1 - t)(1 + t)/(1 + t^2)``,
  ``sin beta = 2 t/(1 + t^2)`` (both accurate to a few ulp relative to their own
  size; ``|t| < 2e16`` for any double, so ``t^2`` cannot overflow);
* ``w = e^2 sin^2 beta``, ``w' = 2 e^2 sin beta cos beta``,
  ``w'' = 2 e^2 (cos beta - sin beta)(cos beta + sin beta)``, ``w''' = -4 w'``;
* the additional travel ``A = S - Rc = -w/(S + Rc)``, ``S = sqrt(Rc^2 - w)``, and its
  derivatives by the chain rule through ``f(w) = sqrt(Rc^2 - w)``
  (``f' = -1/(2S)``, ``f'' = -1/(4S^3)``, ``f''' = -3/(8S^5)``); ``Rc = inf`` (flat
  face) gives ``A = 0`` and its derivatives ``0``;
* ``z = A + e cos beta``, ``z' = A - e cos beta`` and their derivatives.

:func:`travel_point` is the formula: numpy evaluates it on blocks of points
(the fallback); with numba (the ``fast`` extra) it is compiled into one loop
after the block's numpy ``tan`` (:mod:`rotorkin.core.fused`). Both give the same
numbers.
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.fused import at, compiled_loop, evaluate, formula

__all__ = ["travel_point", "travels_fused"]


@formula
def travel_point(t, rc, e):
    """``z, z'`` and their 1st-3rd derivatives at ``t = tan(beta/2)`` (8 values).

    Order: ``z, z', dz, dz', d2z, d2z', d3z, d3z'`` [m, m/rad^n].
    """
    d = 1.0 / (t * t + 1.0)
    c = (1.0 - t) * (1.0 + t) * d
    s = 2.0 * t * d
    e2 = e * e
    w = e2 * (s * s)
    w1 = 2.0 * e2 * (s * c)
    w2 = 2.0 * e2 * ((c - s) * (c + s))
    w3 = -4.0 * w1
    root = np.sqrt(rc * rc - w)
    f0 = -w / (root + rc)
    f1 = -0.5 / root
    r2 = root * root
    f2 = -0.25 / (r2 * root)
    f3 = -0.375 / (r2 * r2 * root)
    a1 = f1 * w1
    a2 = f2 * (w1 * w1) + f1 * w2
    a3 = f3 * (w1 * w1 * w1) + 3.0 * f2 * w1 * w2 + f1 * w3
    h0 = e * c
    h1 = -(e * s)
    return f0 + h0, f0 - h0, a1 + h1, a1 - h1, a2 - h0, a2 + h0, a3 - h1, a3 + h1


@compiled_loop
def _travel_loop(t, rc, e, o0, o1, o2, o3, o4, o5, o6, o7):
    for i in range(o0.shape[0]):
        r = travel_point(at(t, i), at(rc, i), at(e, i))
        o0[i], o1[i], o2[i], o3[i] = r[0], r[1], r[2], r[3]
        o4[i], o5[i], o6[i], o7[i] = r[4], r[5], r[6], r[7]


def _block(x, o, compiled):
    t = np.tan(0.5 * np.asarray(x["beta"]))
    if compiled:
        _travel_loop(t, x["rc"], x["e"], *o)
    else:
        for row, value in zip(o, travel_point(t, x["rc"], x["e"]), strict=True):
            row[...] = value


def travels_fused(contact_radius, eccentricity, beta, *, threads=None, kernel=None, out=None):
    """Travels ``(z, z')`` of both pistons and their derivatives, block by block.

    The values of :func:`rotorkin.drives.eccentric_cam.kinematics.travels`, from
    :func:`travel_point`.

    Parameters
    ----------
    contact_radius : array_like
        Rc [m] (``inf`` for a flat face).
    eccentricity : array_like
        e [m].
    beta : array_like
        Shaft angle [rad]; broadcasts with the parameters.
    threads : int, optional
        Threads for large inputs (:func:`rotorkin.core.fused.split`).
    kernel : {"auto", "numpy", "numba"}, optional
        numpy operations or compiled loops (:func:`rotorkin.core.fused.use_compiled`).
    out : ndarray, optional
        ``(4, 2, ...)`` float64 array to write into.

    Returns
    -------
    ndarray, shape (4, 2, ...)
        ``(z, z')`` [m] (axis 1) and their 1st-3rd derivatives (axis 0) [m/rad^n].
    """
    inputs = {"beta": beta, "rc": contact_radius, "e": eccentricity}
    flat_out = None if out is None else out.reshape(8, *out.shape[2:])
    res = evaluate(inputs, 8, _block, threads=threads, kernel=kernel, out=flat_out)
    return res.reshape(4, 2, *res.shape[1:])
