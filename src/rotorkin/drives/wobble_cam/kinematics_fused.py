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

from rotorkin.core.fused import at, compiled_loop, formula

__all__ = ["atan_arguments", "general_outputs", "linear_outputs"]


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
        s1, c1, s2, c2 = spin_trig(t[i], at(ca, i), at(sa, i), at(ca2, i), at(sa2, i))
        hh = at(h, i)
        aa0, bb0, kk = at(a0, i), at(b0, i), at(k, i)
        vt = at(th, i) * n1
        p1 = (vt + (-hh)) + e1[i]
        p2 = (vt + hh) + e2[i]
        q1[i] = p1
        q2[i] = p2
        a, b = rates(s1, c1, aa0, bb0)
        d11[i] = a * at(nc, i) + 1.0
        d31[i] = third(b, s1, a, c1, kk, at(a3, i))
        d21[i] = (b * a) * at(a2, i)
        a, b = rates(s2, c2, aa0, bb0)
        d12[i] = a * at(nc, i) + 1.0
        d32[i] = third(b, s2, a, c2, kk, at(a3, i))
        d22[i] = (b * a) * at(a2, i)
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
        s1, c1, s2, c2 = spin_trig(t[i], at(ca, i), at(sa, i), at(ca2, i), at(sa2, i))
        hh = at(h, i)
        aa0, bb0, kk, cc, m, f = at(a0, i), at(b0, i), at(k, i), at(c, i), at(mck, i), at(ck2, i)
        u1, u2, u3 = at(g1, i), at(g2, i), at(g3, i)
        u1s = u1 * u1
        u1c = u1 * u1 * u1
        u12 = 3.0 * u1 * u2
        p1 = (vt[i] + (-hh)) + e1[i]
        p2 = (vt[i] + hh) + e2[i]
        q1[i] = p1
        q2[i] = p2
        a, b = rates(s1, c1, aa0, bb0)
        f1 = a * cc
        f2 = (b * a) * m
        f3 = third(b, s1, a, c1, kk, f)
        d11[i] = f1 * u1 + 1.0
        d21[i] = f2 * u1s + f1 * u2
        d31[i] = (f3 * u1c + f2 * u12) + f1 * u3
        a, b = rates(s2, c2, aa0, bb0)
        f1 = a * cc
        f2 = (b * a) * m
        f3 = third(b, s2, a, c2, kk, f)
        d12[i] = f1 * u1 + 1.0
        d22[i] = f2 * u1s + f1 * u2
        d32[i] = (f3 * u1c + f2 * u12) + f1 * u3
        if chambers:
            d = p2 - p1
            da[i] = d + at(ka, i)
            db[i] = at(kb, i) - d
