"""Per-point baselines: each drive's closed form as a plain scalar loop with ``math``.

The fastest reasonable port of the kinematics to scalar Python, the yardstick of the
"one point at a time" comparisons: one loop over the angles, every value from its
closed form with :mod:`math` functions (bound to local names), every constant of the
design computed once before the loop, results appended to Python lists and turned
into one array at the end. No matrices, no numpy scalars (a 3x3 numpy product per
point is several times slower: ``per_point_matrices`` in ``bench_kinematics.py``).
Each returns the same rows as the library (checked by ``bench_kinematics.py``
before timing).
"""

from __future__ import annotations

import math

import numpy as np


def wobble(theta, tilt, alpha, n, width, pistons):
    """Rows ``Phi_1, Phi_2, Phi_1', Phi_2', Phi_1'', Phi_2'', Phi_1''', Phi_2''', dA, dB``."""
    sin, cos, atan = math.sin, math.cos, math.atan
    c = cos(tilt)
    k = 1.0 - c * c
    g = (1.0 + c) / (1.0 - c)
    a0, b0 = 0.5 * (1.0 + c * c), 0.5 * k
    h = 0.5 * alpha
    ca, sa = cos(alpha), sin(alpha)
    nc, a2, a3 = n * c, -n * n * c * k, 2.0 * n**3 * c * k
    two_gamma = 2.0 * (0.25 * math.pi - 0.5 * math.pi / pistons)
    ka, kb = -two_gamma - width, 2.0 * math.pi / pistons + two_gamma - width
    rows = [[] for _ in range(10)]
    q1, q2, d11, d12, d21, d22, d31, d32, da, db = (r.append for r in rows)
    for th in theta.tolist():
        v2 = 2.0 * n * th
        s2, c2 = sin(v2), cos(v2)
        s_1, c_1 = s2 * ca - c2 * sa, c2 * ca + s2 * sa  # 2u = 2 varphi - alpha
        s_2, c_2 = s2 * ca + c2 * sa, c2 * ca - s2 * sa  # 2u = 2 varphi + alpha
        base = th + n * th
        p1 = base - h + atan(s_1 / (g - c_1))
        p2 = base + h + atan(s_2 / (g - c_2))
        i1 = 1.0 / (a0 - b0 * c_1)
        i2 = 1.0 / (a0 - b0 * c_2)
        q1(p1)
        q2(p2)
        d11(1.0 + nc * i1)
        d12(1.0 + nc * i2)
        d21(a2 * s_1 * i1 * i1)
        d22(a2 * s_2 * i2 * i2)
        d31(a3 * i1 * i1 * (k * s_1 * s_1 * i1 - c_1))
        d32(a3 * i2 * i2 * (k * s_2 * s_2 * i2 - c_2))
        da(p2 - p1 + ka)
        db(kb - (p2 - p1))
    return np.array(rows)


def eccentric(beta, rc, e):
    """Rows ``z, z', dz, dz', d2z, d2z', d3z, d3z'`` (knife edge or roller: finite ``rc``)."""
    sin, cos, sqrt = math.sin, math.cos, math.sqrt
    e2 = e * e
    r2 = rc * rc
    rows = [[] for _ in range(8)]
    z0, z1, z2, z3, z4, z5, z6, z7 = (r.append for r in rows)
    for b in beta.tolist():
        s, c = sin(b), cos(b)
        w = e2 * s * s
        w1 = 2.0 * e2 * s * c
        w2 = 2.0 * e2 * (c * c - s * s)
        root = sqrt(r2 - w)
        f0 = -w / (root + rc)
        f1 = -0.5 / root
        f2 = f1 * 0.5 / (root * root)
        f3 = f2 * 1.5 / (root * root)
        a1 = f1 * w1
        a2 = f2 * w1 * w1 + f1 * w2
        a3 = f3 * w1 * w1 * w1 + 3.0 * f2 * w1 * w2 - 4.0 * f1 * w1
        h0, h1 = e * c, e * s
        z0(f0 + h0)
        z1(f0 - h0)
        z2(a1 - h1)
        z3(a1 + h1)
        z4(a2 - h0)
        z5(a2 + h0)
        z6(a3 + h1)
        z7(a3 - h1)
    return np.array(rows)


def guide_bar(theta, lam, u, i12, phase):
    """Rows ``q_1, q_2, q_1', q_2', ...`` of the crank-driven drive."""
    sin, cos, atan = math.sin, math.cos, math.atan
    k = lam * (1.0 - lam * lam)
    l2 = lam * lam
    u1, u2, u3 = u * i12, u * i12 * i12, u * i12**3
    rows = [[] for _ in range(8)]
    appends = [r.append for r in rows]
    for th in theta.tolist():
        x1 = th / i12
        for m, x in enumerate((x1, x1 + phase)):
            s, c = sin(x), cos(x)
            d = 1.0 + 2.0 * lam * c + l2
            appends[m]((x - atan(lam * s / (1.0 + lam * c))) / u)
            appends[2 + m]((1.0 + lam * c) / d / u1)
            appends[4 + m](k * s / (d * d) / u2)
            appends[6 + m](k * (d * c + 4.0 * lam * s * s) / (d * d * d) / u3)
    return np.array(rows)


def noncircular(theta, n, m, e, pa, beta, root, sigma, offset):
    """Rows ``q_1, q_2, q_1', q_2', ...`` of the non-circular gear drive."""
    sin, cos, atan = math.sin, math.cos, math.atan
    br = beta + root
    ne, nne = n * e, n * n * e
    rows = [[] for _ in range(8)]
    appends = [r.append for r in rows]
    for th in theta.tolist():
        for r, (t, off) in enumerate(((n * th, 0.0), (n * (th + sigma), offset))):
            s, c = sin(t), cos(t)
            d = beta - e * c
            d1, d2 = ne * s, nne * c
            appends[r]((t + 2.0 * atan(e * s / (br - e * c))) / m - off)
            appends[2 + r](pa / d)
            appends[4 + r](-pa * d1 / (d * d))
            appends[6 + r](pa * (2.0 * d1 * d1 / (d * d * d) - d2 / (d * d)))
    return np.array(rows)


def rhomboid(alpha, a1, b1):
    """Rows ``phi_1, phi_2, phi_1', phi_2', ...`` of the first-harmonic law (eq. 16)."""
    sin, cos = math.sin, math.cos
    half_pi = 0.5 * math.pi
    rows = [[] for _ in range(8)]
    p0, p1, p2, p3, p4, p5, p6, p7 = (r.append for r in rows)
    for al in alpha.tolist():
        c1, s1 = cos(2.0 * al), sin(2.0 * al)
        f0 = a1 * c1 + b1 * s1
        f1 = b1 * c1 - a1 * s1
        psi = half_pi + f0
        p0(al + 0.5 * psi)
        p1(al - 0.5 * psi)
        p2(1.0 + f1)
        p3(1.0 - f1)
        p4(-2.0 * f0)
        p5(2.0 * f0)
        p6(-4.0 * f1)
        p7(4.0 * f1)
    return np.array(rows)


def wobble_matrices(theta, n, phi, alpha, beta, pistons):
    """The wobble cam as the paper's method is usually ported: 3x3 numpy matrices per point.

    Builds ``A_theta``, ``A_phi``, ``A_varphi`` (eq. 2-4), takes the products with the
    roller axes (eq. 5, 12-13), the rotor angles from the yz projections (eq. 14,
    ``atan2``), the slider angle from eq. 15 (``acos``), the chamber angles (eq. 18-19)
    and the derivatives from their closed forms. Not the baseline (:func:`wobble` is
    several times faster); kept to show what the matrices cost. Rows as :func:`wobble`,
    the rotor angles wrapped to (-pi, pi].
    """
    out = np.empty((10, len(theta)))
    h = 0.5 * alpha
    r3 = np.array([[0.0, 0.0], [-math.sin(h), math.sin(h)], [math.cos(h), math.cos(h)]])
    gamma = math.pi / 4.0 - math.pi / (2.0 * pistons)
    for i in range(len(theta)):
        th = float(theta[i])
        vp = n * th
        ct, st = math.cos(th), math.sin(th)
        cp, sp = math.cos(phi), math.sin(phi)
        cv, sv = math.cos(vp), math.sin(vp)
        a_theta = np.array([[1.0, 0.0, 0.0], [0.0, ct, st], [0.0, -st, ct]])  # eq. 4
        a_phi = np.array([[cp, 0.0, sp], [0.0, 1.0, 0.0], [-sp, 0.0, cp]])  # eq. 3
        a_varphi = np.array([[1.0, 0.0, 0.0], [0.0, cv, sv], [0.0, -sv, cv]])  # eq. 2
        r0 = a_theta @ a_phi @ a_varphi @ r3  # eq. 5, 13
        out[0, i] = math.atan2(r0[1, 0], r0[2, 0])  # eq. 14
        out[1, i] = math.atan2(r0[1, 1], r0[2, 1])
        sm, cm = math.sin(vp - h), math.cos(vp - h)
        sq, cq = math.sin(vp + h), math.cos(vp + h)
        c2 = cp * cp
        num = sm * sq + c2 * cm * cq
        den = math.sqrt((sm * sm + c2 * cm * cm) * (sq * sq + c2 * cq * cq))
        slider = math.acos(num / den)  # eq. 15
        k = 1.0 - c2
        for j, (s, c) in enumerate(((sm, cm), (sq, cq))):
            d = s * s + c2 * c * c
            s2, cos2 = 2.0 * s * c, c * c - s * s
            out[2 + j, i] = 1.0 + n * cp / d
            out[4 + j, i] = -n * n * cp * k * s2 / (d * d)
            out[6 + j, i] = n**3 * 2.0 * cp * k / (d * d) * (k * s2 * s2 / d - cos2)
        out[8, i] = slider - 2.0 * gamma - beta  # eq. 19
        out[9, i] = 2.0 * math.pi / pistons + 2.0 * gamma - slider - beta  # eq. 18
    return out
