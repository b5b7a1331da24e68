"""Compiled loops of the wobble-cam kinematics (the ``fast`` extra: numba).

The arithmetic of one block of :func:`rotorkin.drives.wobble_cam.fast.rotor_kinematics`
fused into two loops over the points, around the block's numpy transcendental calls:

1. ``t = tan varphi`` (numpy);
2. :func:`atan_arguments`: ``S_k/(g - C_k)`` of both rotors;
3. ``arctan`` of both (numpy, in place);
4. :func:`linear_outputs` (linear spin law) or :func:`general_outputs` (any spin law):
   ``Phi_k``, its three derivatives and the chamber angles, written straight into
   the output.

The operations and their order are those of the numpy block
(:func:`rotorkin.drives.wobble_cam.fast._block`): with numba's default (no
fast-math) the two paths give the same numbers, bit for bit in practice (tested
to 1e-14). Per-point design values (tilt, roller axis angle, piston width varying
per point) arrive as arrays, constants as numbers (:func:`rotorkin.core.fused.at`).
"""

from __future__ import annotations

from rotorkin.core.fused import at, compiled_loop, formula, select

__all__ = [
    "atan_arguments",
    "atan_arguments_grid",
    "extremes_grid",
    "general_outputs",
    "general_point",
    "linear_outputs",
    "linear_point",
]


@formula
def spin_trig(t, ca, sa, ca2, sa2):
    """``S_1, C_1, S_2, C_2`` (``sin 2u_k``, ``cos 2u_k``) from ``t = tan varphi``.

    ``cos^2 varphi = 1/(1 + t^2)``, ``sin 2varphi/2 = t cos^2 varphi``,
    ``cos 2varphi = 2 cos^2 varphi - 1``; ``2u_k = 2 varphi -+ alpha`` by angle sums
    with ``ca = cos alpha``, ``sa = sin alpha``, ``ca2 = 2 ca``, ``sa2 = 2 sa``.
    """
    c2v = 1.0 / (t * t + 1.0)
    s2v = t * c2v
    c2v = c2v * 2.0 - 1.0
    t1 = s2v * ca2
    t2 = c2v * sa
    t3 = c2v * ca
    t4 = s2v * sa2
    return t1 - t2, t3 + t4, t1 + t2, t3 - t4


@formula
def rates(s, c, a0, b0):
    """``1/D`` and ``S/D`` with ``D = a0 - b0 C`` (``a0 = (1 + c^2)/2``, ``b0 = k/2``)."""
    a = 1.0 / (a0 - c * b0)
    return a, s * a


@formula
def third(b, s, a, c, k, factor):
    """``factor/D^2 (k S^2/D - C)`` from ``b = S/D`` and ``a = 1/D``."""
    return a * a * ((b * s * k) - c) * factor


@compiled_loop
def atan_arguments(t, ca, sa, ca2, sa2, gamma, r1, r2):
    """``r_k = S_k/(gamma - C_k)`` of both rotors at ``t = tan varphi`` (into r1, r2)."""
    for i in range(t.shape[0]):
        s1, c1, s2, c2 = spin_trig(t[i], at(ca, i), at(sa, i), at(ca2, i), at(sa2, i))
        g = at(gamma, i)
        r1[i] = s1 / (g - c1)
        r2[i] = s2 / (g - c2)


@formula
def linear_point(t, vt, e1, e2, ca, sa, ca2, sa2, hh, aa0, bb0, kk, nc, a2, a3):
    """Both rotors' ``Phi_k`` and three derivatives under the linear spin law.

    ``t = tan varphi``, ``vt = theta (1 + n)``, ``e_k`` the arctangents of both rotors;
    returns ``Phi_1, Phi_2, Phi_1', Phi_2', Phi_1'', Phi_2'', Phi_1''', Phi_2'''``.
    """
    s1, c1, s2, c2 = spin_trig(t, ca, sa, ca2, sa2)
    p1 = (vt + (-hh)) + e1
    p2 = (vt + hh) + e2
    a, b = rates(s1, c1, aa0, bb0)
    d11 = a * nc + 1.0
    d31 = third(b, s1, a, c1, kk, a3)
    d21 = (b * a) * a2
    a, b = rates(s2, c2, aa0, bb0)
    d12 = a * nc + 1.0
    d32 = third(b, s2, a, c2, kk, a3)
    d22 = (b * a) * a2
    return p1, p2, d11, d12, d21, d22, d31, d32


@formula
def _general_rotor(s, c, aa0, bb0, kk, cc, m, f, u1, u1s, u1c, u2, u12, u3):
    """``Phi'``, ``Phi''``, ``Phi'''`` of one rotor under any spin law (Faa di Bruno)."""
    a, b = rates(s, c, aa0, bb0)
    f1 = a * cc
    f2 = (b * a) * m
    f3 = third(b, s, a, c, kk, f)
    return f1 * u1 + 1.0, f2 * u1s + f1 * u2, (f3 * u1c + f2 * u12) + f1 * u3


@formula
def general_point(t, vt, e1, e2, ca, sa, ca2, sa2, hh, aa0, bb0, kk, cc, m, f, u1, u2, u3):
    """:func:`linear_point` of any spin law with derivatives ``u1, u2, u3`` (Faa di Bruno)."""
    s1, c1, s2, c2 = spin_trig(t, ca, sa, ca2, sa2)
    u1s = u1 * u1
    u1c = u1 * u1 * u1
    u12 = 3.0 * u1 * u2
    p1 = (vt + (-hh)) + e1
    p2 = (vt + hh) + e2
    d11, d21, d31 = _general_rotor(s1, c1, aa0, bb0, kk, cc, m, f, u1, u1s, u1c, u2, u12, u3)
    d12, d22, d32 = _general_rotor(s2, c2, aa0, bb0, kk, cc, m, f, u1, u1s, u1c, u2, u12, u3)
    return p1, p2, d11, d12, d21, d22, d31, d32


@compiled_loop
def linear_outputs(
    t, th, n1, e1, e2, ca, sa, ca2, sa2, h, a0, b0, k, nc, a2, a3, ka, kb,
    q1, q2, d11, d12, d21, d22, d31, d32, chambers, da, db,
):  # fmt: skip
    """Outputs of the linear spin law into ``q_k``, ``d1k``... (``da``, ``db`` if ``chambers``).

    ``theta + varphi = theta n1``, ``n1 = 1 + n``; ``e1``, ``e2`` the arctangents of both rotors;
    ``Phi' = 1 + n c/D``, ``Phi'' = -n^2 c k S/D^2``, ``Phi''' = 2 n^3 c k/D^2 (k S^2/D - C)``.
    """
    for i in range(t.shape[0]):
        p1, p2, d11[i], d12[i], d21[i], d22[i], d31[i], d32[i] = linear_point(
            t[i], at(th, i) * n1, e1[i], e2[i], at(ca, i), at(sa, i), at(ca2, i), at(sa2, i),
            at(h, i), at(a0, i), at(b0, i), at(k, i), at(nc, i), at(a2, i), at(a3, i),
        )  # fmt: skip
        q1[i] = p1
        q2[i] = p2
        if chambers:
            d = p2 - p1
            da[i] = d + at(ka, i)
            db[i] = at(kb, i) - d


@compiled_loop
def general_outputs(
    t, vt, e1, e2, ca, sa, ca2, sa2, h, a0, b0, k, c, mck, ck2, g1, g2, g3, ka, kb,
    q1, q2, d11, d12, d21, d22, d31, d32, chambers, da, db,
):  # fmt: skip
    """Outputs of any spin law with derivatives ``g1, g2, g3`` (Faa di Bruno to order 3)."""
    for i in range(t.shape[0]):
        p1, p2, d11[i], d12[i], d21[i], d22[i], d31[i], d32[i] = general_point(
            t[i], vt[i], e1[i], e2[i], at(ca, i), at(sa, i), at(ca2, i), at(sa2, i), at(h, i),
            at(a0, i), at(b0, i), at(k, i), at(c, i), at(mck, i), at(ck2, i), at(g1, i),
            at(g2, i), at(g3, i),
        )  # fmt: skip
        q1[i] = p1
        q2[i] = p2
        if chambers:
            d = p2 - p1
            da[i] = d + at(ka, i)
            db[i] = at(kb, i) - d


# --------------------------------------------------------------------------------------------
# designs x angles, reduced per design (the sweeps' peaks: no curve is stored)
# --------------------------------------------------------------------------------------------
@formula
def _larger(a, b):
    """``numpy.maximum(a, b)`` without a branch (a NaN in either is the result)."""
    return select((a > b) | (a != a), a, b)


@formula
def _smaller(a, b):
    """``numpy.minimum(a, b)`` without a branch."""
    return select((a < b) | (a != a), a, b)


@compiled_loop
def atan_arguments_grid(t, ca, sa, ca2, sa2, gamma, r1, r2):
    """:func:`atan_arguments` at the angles' ``t`` (rows of ``r_k``) of designs (columns)."""
    for j in range(r1.shape[0]):
        tj = t[j]
        for d in range(r1.shape[1]):
            s1, c1, s2, c2 = spin_trig(tj, at(ca, d), at(sa, d), at(ca2, d), at(sa2, d))
            g = at(gamma, d)
            r1[j, d] = s1 / (g - c1)
            r2[j, d] = s2 / (g - c2)


@compiled_loop
def extremes_grid(t, vt, e1, e2, ca, sa, ca2, sa2, h, a0, b0, k, c1, c2, c3, u1, u2, u3,
                  linear, acc):  # fmt: skip
    """Fold angles (rows of ``e_k``) into each design's (columns) running extremes ``acc``
    (6, designs), over both rotors: the largest ``|Phi''|`` and ``|Phi'''|``, the
    extremes of ``Phi'`` and of the slider angle ``Phi_2 - Phi_1``.

    ``linear``: :func:`linear_point` with ``c1, c2, c3 = n c, -n^2 c k, 2 n^3 c k`` and
    ``vt = theta (1 + n)``; else :func:`general_point` with ``c1, c2, c3 = c, -c k,
    2 c k`` and the spin law's derivatives ``u_k`` at the angles. The inner loop runs
    over designs: each update of ``acc`` is elementwise (``numpy.maximum``'s NaN rule),
    so it vectorises; ``acc`` is C-contiguous, started at -inf/+inf by the caller.
    """
    for j in range(e1.shape[0]):
        tj, vj = t[j], vt[j]
        for d in range(e1.shape[1]):
            if linear:
                p1, p2, d11, d12, d21, d22, d31, d32 = linear_point(
                    tj, vj, e1[j, d], e2[j, d], at(ca, d), at(sa, d), at(ca2, d), at(sa2, d),
                    at(h, d), at(a0, d), at(b0, d), at(k, d), at(c1, d), at(c2, d), at(c3, d),
                )  # fmt: skip
            else:
                p1, p2, d11, d12, d21, d22, d31, d32 = general_point(
                    tj, vj, e1[j, d], e2[j, d], at(ca, d), at(sa, d), at(ca2, d), at(sa2, d),
                    at(h, d), at(a0, d), at(b0, d), at(k, d), at(c1, d), at(c2, d), at(c3, d),
                    u1[j], u2[j], u3[j],
                )  # fmt: skip
            s = p2 - p1
            acc[0, d] = _larger(acc[0, d], _larger(abs(d21), abs(d22)))
            acc[1, d] = _larger(acc[1, d], _larger(abs(d31), abs(d32)))
            acc[2, d] = _smaller(acc[2, d], _smaller(d11, d12))
            acc[3, d] = _larger(acc[3, d], _larger(d11, d12))
            acc[4, d] = _smaller(acc[4, d], s)
            acc[5, d] = _larger(acc[5, d], s)
