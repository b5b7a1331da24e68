"""Fused evaluation of the blade-pair law of the rhomboid lever-cam converter.

The law of :func:`rotorkin.drives.rhomboid_cam.kinematics.psi_law` (eq. 13-15) and
the blade angles of :func:`~rotorkin.drives.rhomboid_cam.kinematics.blade_angles`
(eq. 21-22), rearranged so that each point costs one ``tan``, whatever the number of
harmonics:

* ``t = tan alpha``: ``cos 2alpha = (1 - t)(1 + t)/(1 + t^2)``,
  ``sin 2alpha = 2 t/(1 + t^2)``;
* the harmonics ``cos 2k alpha``, ``sin 2k alpha`` (``k = 3, 5, ...``) by turning
  the first one by ``4 alpha`` again and again (angle sums: the rounding grows by
  about one ulp per harmonic);
* ``psi = pi/2 + f0 + sum(a_k cos + b_k sin)``, ``f0 = a_1 cos 2alpha + b_1 sin 2alpha``
  and its derivatives; the blade pairs ``phi_{1,2} = alpha +- psi/2``.

:func:`psi_point` is the formula: numpy evaluates it on blocks (the fallback); with
numba it is compiled into one loop after the block's numpy ``tan``
(:mod:`rotorkin.core.fused`). Both give the same numbers.
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.fused import at, compiled_loop, evaluate, formula

__all__ = ["blades_point", "first_harmonic_point", "law_fused", "psi_point"]

_HALF_PI = 0.5 * np.pi


@formula
def first_harmonic_point(t, a1, b1):
    """``cos 2alpha``, ``sin 2alpha`` from ``t = tan alpha``, and the first harmonic's part.

    Returns ``c1, s1, f0 = a1 c1 + b1 s1, f1 = b1 c1 - a1 s1``.
    """
    d = 1.0 / (t * t + 1.0)
    c1 = (1.0 - t) * (1.0 + t) * d
    s1 = 2.0 * t * d
    return c1, s1, a1 * c1 + b1 * s1, b1 * c1 - a1 * s1


@formula
def psi_from(f0, f1, hc, hs, hc2, hs3):
    """``psi`` and its derivatives from the first harmonic's and the higher ones' sums."""
    return _HALF_PI + f0 + hc, 2.0 * f1 + hs, -4.0 * f0 - hc2, -8.0 * f1 - hs3


@formula
def psi_point(t, a1, b1, ak, bk, wk):
    """``psi, psi', psi'', psi'''`` at ``t = tan alpha``.

    ``a1``, ``b1``: the first harmonic; ``ak``, ``bk``: the higher ones (1-d), of
    angular frequencies ``wk = 2k``.
    """
    c1, s1, f0, f1 = first_harmonic_point(t, a1, b1)
    c4 = (c1 - s1) * (c1 + s1)
    s4 = 2.0 * s1 * c1
    ck = c1
    sk = s1
    hc = 0.0
    hs = 0.0
    hc2 = 0.0
    hs3 = 0.0
    for j in range(ak.shape[0]):
        ck, sk = ck * c4 - sk * s4, sk * c4 + ck * s4
        p = ak[j] * ck + bk[j] * sk
        q = bk[j] * ck - ak[j] * sk
        w = wk[j]
        hc = hc + p
        hs = hs + w * q
        hc2 = hc2 + w * w * p
        hs3 = hs3 + w * w * w * q
    return psi_from(f0, f1, hc, hs, hc2, hs3)


@formula
def first_point(t, a1, b1):
    """:func:`psi_point` without higher harmonics (a loop the compiler can vectorise)."""
    _, _, f0, f1 = first_harmonic_point(t, a1, b1)
    return psi_from(f0, f1, 0.0, 0.0, 0.0, 0.0)


@compiled_loop
def _psi_loop(t, a1, b1, ak, bk, wk, o0, o1, o2, o3):
    for i in range(o0.shape[0]):
        o0[i], o1[i], o2[i], o3[i] = psi_point(at(t, i), at(a1, i), b1, ak, bk, wk)


@compiled_loop
def _psi_loop_first(t, a1, b1, o0, o1, o2, o3):
    for i in range(o0.shape[0]):
        o0[i], o1[i], o2[i], o3[i] = first_point(at(t, i), at(a1, i), b1)


@formula
def blades_point(alpha, p0, p1, p2, p3):
    """Both blade pairs ``alpha +- psi/2`` and derivatives, pair 1 then pair 2 per order."""
    return (alpha + 0.5 * p0, alpha - 0.5 * p0, 1.0 + 0.5 * p1, 1.0 - 0.5 * p1, 0.5 * p2,
            -(0.5 * p2), 0.5 * p3, -(0.5 * p3))  # fmt: skip


@compiled_loop
def _blade_loop(t, alpha, a1, b1, ak, bk, wk, o0, o1, o2, o3, o4, o5, o6, o7):
    for i in range(o0.shape[0]):
        p0, p1, p2, p3 = psi_point(at(t, i), at(a1, i), b1, ak, bk, wk)
        r = blades_point(at(alpha, i), p0, p1, p2, p3)
        o0[i], o1[i], o2[i], o3[i], o4[i], o5[i], o6[i], o7[i] = r


@compiled_loop
def _blade_loop_first(t, alpha, a1, b1, o0, o1, o2, o3, o4, o5, o6, o7):
    for i in range(o0.shape[0]):
        p0, p1, p2, p3 = first_point(at(t, i), at(a1, i), b1)
        r = blades_point(at(alpha, i), p0, p1, p2, p3)
        o0[i], o1[i], o2[i], o3[i], o4[i], o5[i], o6[i], o7[i] = r


def law_fused(a1, b1, ak, bk, alpha, *, blades=False, threads=None, kernel=None, out=None):
    """The law ``psi`` (or both blade pairs' angles) and derivatives, block by block.

    Parameters
    ----------
    a1 : array_like
        First cosine coefficient [rad] (per design, from ``psi_min``).
    b1 : float
        First sine coefficient [rad].
    ak, bk : ndarray, shape (K,)
        Higher harmonics ``a3, a5, ...``, ``b3, b5, ...`` [rad].
    alpha : array_like
        Output-shaft angle [rad]; broadcasts with ``a1``.
    blades : bool
        Return the blade pairs' angles ``alpha +- psi/2`` and derivatives instead.
    threads : int, optional
        Threads for large inputs (:func:`rotorkin.core.fused.split`).
    kernel : {"auto", "numpy", "numba"}, optional
        :func:`rotorkin.core.fused.use_compiled`.
    out : ndarray, optional
        Float64 C-contiguous array of the result's shape to write into.

    Returns
    -------
    ndarray, shape (4, ...) or (4, 2, ...)
        ``psi`` and its 1st-3rd derivatives [rad/rad^n]; with ``blades``, those of
        pair 1 and pair 2 (axis 1).
    """
    ak = np.ascontiguousarray(ak, dtype=float)
    bk = np.ascontiguousarray(bk, dtype=float)
    wk = 2.0 * (2.0 * np.arange(1, ak.size + 1) + 1.0)
    b1 = float(b1)

    def block(x, o, compiled):
        t = np.tan(x["alpha"])
        if compiled:
            if blades and ak.size:
                _blade_loop(t, x["alpha"], x["a1"], b1, ak, bk, wk, *o)
            elif blades:
                _blade_loop_first(t, x["alpha"], x["a1"], b1, *o)
            elif ak.size:
                _psi_loop(t, x["a1"], b1, ak, bk, wk, *o)
            else:
                _psi_loop_first(t, x["a1"], b1, *o)
            return
        p = psi_point(t, x["a1"], b1, ak, bk, wk)
        values = blades_point(x["alpha"], *p) if blades else p
        for row, value in zip(o, values, strict=True):
            row[...] = value

    rows = 8 if blades else 4
    flat_out = None if out is None else out.reshape(rows, *out.shape[(2 if blades else 1) :])
    res = evaluate(
        {"alpha": alpha, "a1": a1}, rows, block, threads=threads, kernel=kernel, out=flat_out
    )
    return res.reshape(4, 2, *res.shape[1:]) if blades else res
