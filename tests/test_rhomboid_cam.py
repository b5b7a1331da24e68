"""Tests of the rhomboid lever-cam drive against independent models written here.

The independent models: the Fourier law summed term by term from eq. 13 with
the first harmonic solved from eq. 15 here; the rhombus built from the blade
arm points by intersecting circles (every side 2l, the blade axes through the
side midpoints); the curvature from the circle through three nearby points;
the work by brute-force quadrature on a very fine grid and by the total
travel of psi.
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from scipy.optimize import brentq

from rotorkin.core.angles import angle_near
from rotorkin.core.errors import ParameterError
from rotorkin.drives import evaluate
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.drives.rhomboid_cam import schema
from rotorkin.machines import rotary_blade as rb

TWO_PI = 2.0 * np.pi


# --- independent models -------------------------------------------------------------------
def psi_ref(alpha, psi_min, a=(), b=()):
    """Eq. 13 summed term by term; a_1, b_1 solved from eq. 15 here."""
    alpha = np.asarray(alpha, dtype=float)
    a1 = np.pi / 2 - psi_min - sum(a)
    b1 = -sum((2 * i + 3) * bk for i, bk in enumerate(b))
    out = np.pi / 2 + a1 * np.cos(2 * alpha) + b1 * np.sin(2 * alpha)
    for i, ak in enumerate(a):
        out = out + ak * np.cos(2 * (2 * i + 3) * alpha)
    for i, bk in enumerate(b):
        out = out + bk * np.sin(2 * (2 * i + 3) * alpha)
    return out


def circle_intersections(c1, c2, r1, r2):
    """Both intersection points of two circles (standard construction)."""
    d = np.linalg.norm(c2 - c1)
    x = (d**2 + r1**2 - r2**2) / (2 * d)
    h = np.sqrt(max(r1**2 - x**2, 0.0))
    ex = (c2 - c1) / d
    ey = np.array([-ex[1], ex[0]])
    base = c1 + x * ex
    return base + h * ey, base - h * ey


def e(t):
    return np.array([np.cos(t), np.sin(t)])


def rhombus_from_blades(phi1, phi2, side):
    """Rhombus ABCD of side ``side`` whose side midpoints lie on the blade axes at distance side/2.

    A is the second common point (not O) of the circles of radius l about the
    arm points of pairs 1 and 2; then every next vertex is the reflection of
    the previous one in the next side midpoint.
    """
    l = side / 2
    m_ab, m_bc, m_cd, m_da = l * e(phi1), -l * e(phi2), -l * e(phi1), l * e(phi2)
    p, q = circle_intersections(m_ab, m_da, l, l)
    A = p if np.linalg.norm(p) > np.linalg.norm(q) else q
    B = 2 * m_ab - A
    C = 2 * m_bc - B
    D = 2 * m_cd - C
    closure = 2 * m_da - D
    return np.array([A, B, C, D]), closure, np.array([m_ab, m_bc, m_cd, m_da])


def random_law(rng, n=2, scale=0.08):
    """Small random higher harmonics (psi stays well inside (0, pi))."""
    psi_min = rng.uniform(np.radians(20), np.radians(70))
    a = tuple(rng.uniform(-scale, scale, n) / np.arange(1, n + 1))
    b = tuple(rng.uniform(-scale, scale, n) / np.arange(1, n + 1) ** 2)
    return psi_min, a, b


def torque_ref(psi, dpsi, m1, m2, psi_min):
    """Eq. 29 as read: M_p when psi rises, M_c when it falls."""
    a, b = (m1 - m2) / 2, (m1 + m2) / 2
    x = (psi - np.pi / 2) / (np.pi / 2 - psi_min)
    return np.where(dpsi > 0, a - b * x, -a - b * x)


SEEDS = [0, 1, 2, 3, 4]
NON_MONOTONE = (np.radians(40.0), (0.4,), ())


# --- the law ------------------------------------------------------------------------------
@pytest.mark.parametrize("seed", SEEDS)
def test_psi_law_against_term_by_term_series(seed):
    rng = np.random.default_rng(seed)
    psi_min, a, b = random_law(rng, n=3)
    al = rng.uniform(-4, 4, 200)
    np.testing.assert_allclose(rc.psi_law(psi_min, a, b, al)[0], psi_ref(al, psi_min, a, b),
                               rtol=0, atol=1e-13)  # fmt: skip


@pytest.mark.parametrize("seed", SEEDS)
def test_psi_derivatives_by_finite_differences(seed):
    rng = np.random.default_rng(seed)
    psi_min, a, b = random_law(rng, n=3)
    al = rng.uniform(-4, 4, 50)
    h = 1e-5
    p = rc.psi_law(psi_min, a, b, al)
    pp = rc.psi_law(psi_min, a, b, al + h)
    pm = rc.psi_law(psi_min, a, b, al - h)
    # central differences of the independent series (order 1) and of the closed forms (2, 3):
    # truncation ~ h^2 |f'''| / 6 < 1e-8 for frequencies up to 14
    fd1 = (psi_ref(al + h, psi_min, a, b) - psi_ref(al - h, psi_min, a, b)) / (2 * h)
    np.testing.assert_allclose(p[1], fd1, atol=1e-7)
    np.testing.assert_allclose(p[2], (pp[1] - pm[1]) / (2 * h), atol=1e-6)
    np.testing.assert_allclose(p[3], (pp[2] - pm[2]) / (2 * h), atol=1e-5)


def test_first_harmonic_coefficients():
    a1, b1 = rc.first_harmonic(0.5, (0.1, -0.02), (0.03, 0.01))
    assert a1 == pytest.approx(np.pi / 2 - 0.5 - 0.08, abs=1e-15)
    assert b1 == pytest.approx(-(3 * 0.03 + 5 * 0.01), abs=1e-15)


@pytest.mark.parametrize("seed", SEEDS)
def test_periodicity_and_symmetry(seed):
    rng = np.random.default_rng(seed)
    psi_min, a, b = random_law(rng)
    al = rng.uniform(-4, 4, 100)
    p0 = rc.psi_law(psi_min, a, b, al)
    p1 = rc.psi_law(psi_min, a, b, al + np.pi)
    p2 = rc.psi_law(psi_min, a, b, al + np.pi / 2)
    for k in range(4):
        np.testing.assert_allclose(p1[k], p0[k], atol=1e-10)
        # eq. 10 differentiated: psi^(k)(alpha + pi/2) = -psi^(k)(alpha) for k >= 1
        np.testing.assert_allclose(p2[k], (np.pi if k == 0 else 0.0) - p0[k], atol=1e-10)
    par = rc.RhomboidCam(0.1, psi_min, a, b)
    assert rc.period(par) == pytest.approx(np.pi)
    m0, m1 = rc.motion(par, al), rc.motion(par, al + np.pi)
    np.testing.assert_allclose(m1.q, m0.q + np.pi, atol=1e-10)
    np.testing.assert_allclose(m1.dq, m0.dq, atol=1e-10)


def test_shapes_0d_1d_3d():
    psi_min, a, b = 0.6, (0.05,), (0.01, -0.004)
    al3 = np.random.default_rng(7).uniform(0, 3, (2, 3, 4))
    par = rc.RhomboidCam(0.12, psi_min, a, b)
    fns = [
        lambda x: rc.psi_law(psi_min, a, b, x),
        lambda x: rc.blade_angles(psi_min, a, b, x),
        lambda x: rc.profile_radius(0.12, psi_min, a, b, x),
        lambda x: rc.profile_point(0.12, psi_min, a, b, x),
        lambda x: (rc.profile_curvature(0.12, psi_min, a, b, x),),
        lambda x: (rc.profile_radius_eq19(0.12, psi_min, a, b, x),),
        lambda x: (rc.rhombus_vertices(0.12, psi_min, a, b, x),),
        lambda x: (rc.blade_arm_points(0.12, psi_min, a, b, x),),
        lambda x: (rc.stroke_direction(psi_min, a, b, x),),
        lambda x: (rc.shaft_torque(psi_min, a, b, 100.0, 40.0, x),),
        lambda x: (rc.motion(par, x).q, rc.motion(par, x).d3q),
    ]
    for f in fns:
        r3 = f(al3)
        r1 = f(al3.ravel())
        r0 = f(al3[1, 2, 3])
        for x3, x1, x0 in zip(r3, r1, r0, strict=True):
            lead = x3.shape[: x3.ndim - 3]
            assert x3.shape == lead + (2, 3, 4)
            assert x0.shape == lead
            np.testing.assert_array_equal(x3.reshape(lead + (-1,)), x1)
            np.testing.assert_array_equal(x3[..., 1, 2, 3], x0)


def test_psi_min_broadcasts_with_alpha():
    pm = np.array([[0.3], [0.7], [1.2]])
    al = np.linspace(0, 3, 5)
    got = rc.psi_law(pm, (0.02,), (0.01,), al)[0]
    assert got.shape == (3, 5)
    for i in range(3):
        np.testing.assert_allclose(got[i], psi_ref(al, pm[i, 0], (0.02,), (0.01,)), atol=1e-14)


# --- blades, rhombus, cam -----------------------------------------------------------------
@pytest.mark.parametrize("seed", SEEDS)
def test_blade_angles(seed):
    rng = np.random.default_rng(seed)
    psi_min, a, b = random_law(rng)
    al = rng.uniform(-4, 4, 40)
    phi, d1, d2, d3 = rc.blade_angles(psi_min, a, b, al)
    psi = psi_ref(al, psi_min, a, b)
    np.testing.assert_allclose(phi[0], al + psi / 2, atol=1e-13)
    np.testing.assert_allclose(phi[1], al - psi / 2, atol=1e-13)
    h = 1e-5
    fp, fm = rc.blade_angles(psi_min, a, b, al + h), rc.blade_angles(psi_min, a, b, al - h)
    for k, tol in ((0, 1e-7), (1, 1e-6), (2, 1e-5)):
        np.testing.assert_allclose((fp[k] - fm[k]) / (2 * h), (d1, d2, d3)[k], atol=tol)


@pytest.mark.parametrize("seed", SEEDS)
def test_rhombus_against_circle_construction(seed):
    rng = np.random.default_rng(seed)
    psi_min, a, b = random_law(rng)
    L = rng.uniform(0.05, 0.3)
    al = rng.uniform(-4, 4, 12)
    verts = rc.rhombus_vertices(L, psi_min, a, b, al)
    mids = rc.blade_arm_points(L, psi_min, a, b, al)
    rho = rc.profile_radius(L, psi_min, a, b, al)[0]
    psi = psi_ref(al, psi_min, a, b)
    for j, alpha in enumerate(al):
        v, closure, m = rhombus_from_blades(alpha + psi[j] / 2, alpha - psi[j] / 2, L)
        np.testing.assert_allclose(closure, v[0], atol=1e-12)
        np.testing.assert_allclose(np.linalg.norm(v - np.roll(v, 1, axis=0), axis=1), L, rtol=1e-12)
        np.testing.assert_allclose(verts[:, :, j], v, atol=1e-12)
        np.testing.assert_allclose(mids[:, :, j], m, atol=1e-12)
        # A at polar angle alpha, at the profile radius (eq. 3)
        assert angle_near(v[0, 1], v[0, 0], alpha) == pytest.approx(alpha, abs=1e-12)
        assert np.linalg.norm(v[0]) == pytest.approx(rho[j], rel=1e-12)
        # the diagonals are perpendicular; OB = 2l sin(psi/2) (eq. 4 corrected)
        assert np.dot(v[0], v[1]) == pytest.approx(0.0, abs=1e-12)
        assert np.linalg.norm(v[1]) == pytest.approx(L * np.sin(psi[j] / 2), rel=1e-12)


@pytest.mark.parametrize("seed", SEEDS)
def test_all_four_vertices_lie_on_the_cam(seed):
    """B, C, D on the same pitch curve as A (eq. 8/10): radius equals rho at their polar angle."""
    rng = np.random.default_rng(seed)
    psi_min, a, b = random_law(rng)
    L = 0.15
    al = rng.uniform(-4, 4, 30)
    v = rc.rhombus_vertices(L, psi_min, a, b, al)
    for i in range(4):
        ang = angle_near(v[i, 1], v[i, 0], al + i * np.pi / 2)
        np.testing.assert_allclose(ang, al + i * np.pi / 2, atol=1e-12)
        r = rc.profile_radius(L, psi_min, a, b, ang)[0]
        np.testing.assert_allclose(np.hypot(v[i, 0], v[i, 1]), r, rtol=1e-12)


@pytest.mark.parametrize("seed", SEEDS)
def test_profile_derivatives_by_finite_differences(seed):
    rng = np.random.default_rng(seed)
    psi_min, a, b = random_law(rng)
    L = 0.12
    al = rng.uniform(-4, 4, 30)
    h = 1e-5
    r, rp, rm = (rc.profile_radius(L, psi_min, a, b, x) for x in (al, al + h, al - h))
    for k in range(3):
        np.testing.assert_allclose((rp[k] - rm[k]) / (2 * h), r[k + 1], atol=1e-8 * 10**k)
    p, pp, pm = (rc.profile_point(L, psi_min, a, b, x) for x in (al, al + h, al - h))
    np.testing.assert_allclose(p[0], np.stack([r[0] * np.cos(al), r[0] * np.sin(al)]), atol=1e-15)
    for k in range(2):
        np.testing.assert_allclose((pp[k] - pm[k]) / (2 * h), p[k + 1], atol=1e-8)


@pytest.mark.parametrize("seed", SEEDS)
def test_curvature_against_three_point_circle(seed):
    rng = np.random.default_rng(seed)
    psi_min, a, b = random_law(rng)
    L = 0.12
    al = rng.uniform(0, np.pi, 20)
    kappa = rc.profile_curvature(L, psi_min, a, b, al)
    h = 2e-4
    p0, p1, p2 = (rc.profile_point(L, psi_min, a, b, x)[0].T for x in (al - h, al, al + h))
    u, w = p1 - p0, p2 - p1
    cross = u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]  # > 0: turning left (convex, ccw curve)
    sides = np.linalg.norm(u, axis=1) * np.linalg.norm(w, axis=1) * np.linalg.norm(p2 - p0, axis=1)
    kappa3 = 2 * cross / sides  # signed 1 / circumradius
    np.testing.assert_allclose(kappa, kappa3, rtol=1e-5, atol=1e-4)


def test_eq19_form_is_quarter_turn():
    psi_min, a, b = 0.7, (0.05, 0.01), (0.02,)
    al = np.linspace(-3, 3, 41)
    np.testing.assert_allclose(rc.profile_radius_eq19(0.1, psi_min, a, b, al),
                               rc.profile_radius(0.1, psi_min, a, b, al + np.pi / 2)[0],
                               atol=1e-15)  # fmt: skip


# --- stationary points, extremes, monotonicity --------------------------------------------
def test_stationary_points_first_harmonic():
    z = rc.psi_stationary_points(np.radians(40))
    np.testing.assert_allclose(z, [0, np.pi / 2, np.pi], atol=1e-12)


def test_stationary_points_against_brentq():
    psi_min, a, b = NON_MONOTONE
    z = rc.psi_stationary_points(psi_min, a, b)

    def d1(x):
        return (psi_ref(x + 1e-6, psi_min, a, b) - psi_ref(x - 1e-6, psi_min, a, b)) / 2e-6

    g = np.linspace(1.1e-3, np.pi - 1.3e-3, 20001)  # no node on pi/2
    s = np.sign(d1(g))
    roots = [brentq(d1, g[i], g[i + 1], xtol=1e-14) for i in np.flatnonzero(s[:-1] * s[1:] < 0)]
    expected = np.concatenate([[0.0], roots, [np.pi]])
    np.testing.assert_allclose(z, expected, atol=1e-8)
    assert z.size == 7  # 4 extra extremes: the law swings back and forth twice per half
    np.testing.assert_allclose(rc.psi_law(psi_min, a, b, z)[1], 0.0, atol=1e-12)


@pytest.mark.parametrize("seed", SEEDS)
def test_extremes_against_brute_force(seed):
    rng = np.random.default_rng(seed)
    psi_min = rng.uniform(0.2, 1.3)
    a = tuple(rng.uniform(-0.6, 0.6, 3))
    b = tuple(rng.uniform(-0.1, 0.1, 2))
    lo, alo, hi, ahi = rc.psi_extremes(psi_min, a, b)
    g = np.linspace(0, np.pi, 400001)
    p = psi_ref(g, psi_min, a, b)
    assert lo == pytest.approx(p.min(), abs=1e-9)
    assert hi == pytest.approx(p.max(), abs=1e-9)
    assert psi_ref(alo, psi_min, a, b) == pytest.approx(lo, abs=1e-14)
    assert lo + hi == pytest.approx(np.pi, abs=1e-12)  # eq. 10


def test_monotone_detection():
    assert rc.psi_is_monotone(np.radians(40))
    assert rc.psi_is_monotone(np.radians(40), (-(np.pi / 2 - np.radians(40)) / 8,))
    assert not rc.psi_is_monotone(*NON_MONOTONE)
    psi_min, a, b = NON_MONOTONE
    g = np.linspace(0, np.pi, 2_000_001)
    tv = np.sum(np.abs(np.diff(psi_ref(g, psi_min, a, b))))
    assert rc.psi_total_variation(psi_min, a, b) == pytest.approx(tv, rel=1e-10)


# --- torques and work ---------------------------------------------------------------------
def test_blade_torque_levels():
    """Ends of the two lines of eq. 29 as read: M_p from M1 to -M2, M_c from -M1 to M2."""
    pm, m1, m2 = 0.6, 100.0, 40.0
    psi = np.array([pm, np.pi - pm, np.pi - pm, pm])
    got = rc.blade_torque(m1, m2, pm, psi, np.array([1, 1, -1, -1]))
    np.testing.assert_allclose(got, [m1, -m2, -m1, m2], atol=1e-12)
    assert rc.blade_torque(m1, m2, np.pi / 2, 1.0, 1) == pytest.approx((m1 - m2) / 2)


def test_stroke_direction():
    al = np.array([0.0, 0.3, np.pi / 2, 2.0, np.pi])
    np.testing.assert_array_equal(rc.stroke_direction(0.7, (), (), al), [-1, -1, 1, 1, -1])
    np.testing.assert_array_equal(rc.stroke_direction(np.pi / 2, (), (), al), 0.0)
    # dwell law psi' ~ -sin^3 2 alpha: flat at 0, the stroke is read from psi'''
    a3 = (-(np.pi / 2 - 0.7) / 8,)
    np.testing.assert_array_equal(rc.stroke_direction(0.7, a3, (), al), [-1, -1, 1, 1, -1])


@pytest.mark.parametrize("seed", SEEDS)
def test_work_monotone_laws(seed):
    rng = np.random.default_rng(seed)
    psi_min, a, b = random_law(rng, n=1, scale=0.06)
    g = np.linspace(1e-6, np.pi / 2 - 1e-6, 100001)
    d = np.diff(psi_ref(g, psi_min, a, b))
    assert np.all(d < 0), "test law must be monotone on (0, pi/2)"
    m1, m2 = rng.uniform(50, 150), rng.uniform(-50, 50)
    A = rc.indicator_work(psi_min, a, b, m1, m2)
    assert A == pytest.approx((m1 - m2) * (np.pi - 2 * psi_min), rel=1e-12)
    assert rc.mean_shaft_torque(psi_min, a, b, m1, m2) == pytest.approx(A / np.pi, rel=1e-14)


def test_work_non_monotone_against_brute_force():
    psi_min, a, b = NON_MONOTONE
    m1, m2 = 100.0, 40.0
    A = float(rc.indicator_work(psi_min, a, b, m1, m2))
    # brute force: trapezoid on 2e6 intervals of M(psi, sign psi') psi', all written here
    g = np.linspace(0, np.pi, 2_000_001)
    h = 1e-6
    psi = psi_ref(g, psi_min, a, b)
    dpsi = (psi_ref(g + h, psi_min, a, b) - psi_ref(g - h, psi_min, a, b)) / (2 * h)
    f = torque_ref(psi, dpsi, m1, m2, psi_min) * dpsi
    brute = np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(g))
    assert A == pytest.approx(brute, rel=1e-6)
    # the back-and-forth swings add (M1 - M2) times the extra travel
    tv = np.sum(np.abs(np.diff(psi)))
    assert A == pytest.approx((m1 - m2) * tv / 2, rel=1e-9)
    closed = (m1 - m2) * (np.pi - 2 * psi_min)
    assert A > closed * 1.4


def test_work_broadcasts_over_torques():
    m1 = np.array([[100.0], [80.0]])
    m2 = np.array([40.0, 0.0, -20.0])
    A = rc.indicator_work(0.7, (0.03,), (), m1, m2)
    assert A.shape == (2, 3)
    np.testing.assert_allclose(A, (m1 - m2) * (np.pi - 1.4), rtol=1e-12)


def test_shaft_torque_by_virtual_work():
    psi_min, a, b = 0.6, (0.04,), (0.01,)
    m1, m2 = 100.0, 40.0
    al = np.linspace(0, np.pi, 200001)
    t = rc.shaft_torque(psi_min, a, b, m1, m2, al)
    psi, dpsi = psi_ref(al, psi_min, a, b), rc.psi_law(psi_min, a, b, al)[1]
    mb = torque_ref(psi, dpsi, m1, m2, psi_min)
    dphi = rc.blade_angles(psi_min, a, b, al)[1]
    inner = np.abs(dpsi) > 1e-9
    np.testing.assert_allclose(t[inner], (mb * dphi[0] - mb * dphi[1])[inner], atol=1e-10)
    mean = np.sum(0.5 * (t[1:] + t[:-1]) * np.diff(al)) / np.pi
    assert mean == pytest.approx(float(rc.mean_shaft_torque(psi_min, a, b, m1, m2)), rel=1e-8)


# --- parameters and errors ----------------------------------------------------------------
def test_dataclass_stores_tuples_and_is_frozen():
    p = rc.RhomboidCam(0.12, np.radians(40), [0.1], np.array([0.01, 0.0]))
    assert p.a == (0.1,) and p.b == (0.01, 0.0)
    assert isinstance(p.link_length, float)
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.psi_min = 0.5


@pytest.mark.parametrize(
    ("kwargs", "name", "text"),
    [
        ({"link_length": 0.0}, "link_length", "mm"),
        ({"link_length": -0.1}, "link_length", "mm"),
        ({"link_length": float("nan")}, "link_length", "link_length"),
        ({"psi_min": 0.0}, "psi_min", "deg"),
        ({"psi_min": np.pi / 2}, "psi_min", "90 deg"),
        ({"psi_min": -0.2}, "psi_min", "deg"),
        ({"psi_min": 2.0}, "psi_min", "114.6 deg"),
        ({"psi_min": float("inf")}, "psi_min", "deg"),
        ({"a": (2.0,)}, "a", "psi = -"),
        ({"b": (1.0,)}, "b", "psi = -"),
        ({"a": (0.1,) * 21}, "a", "at most 20"),
        ({"b": (0.0, float("nan"))}, "b", "finite"),
        ({"a": ((0.1, 0.2), (0.3, 0.4))}, "a", "flat"),
        ({"a": ("x",)}, "a", "numbers"),
    ],
)
def test_parameter_errors(kwargs, name, text):
    args = {"link_length": 0.12, "psi_min": np.radians(40), **kwargs}
    with pytest.raises(ParameterError) as info:
        rc.RhomboidCam(**args)
    assert info.value.name == name
    assert str(info.value).startswith(f"{name} = ")
    assert text in str(info.value)


def test_law_error_reports_the_extreme():
    with pytest.raises(ParameterError) as info:
        rc.RhomboidCam(0.12, np.radians(40), (2.0,))
    psi_min, a = np.radians(40), (2.0,)
    g = np.linspace(0, np.pi, 200001)
    lowest = np.degrees(psi_ref(g, psi_min, a).min())
    assert f"psi = {lowest:.4g} deg" in str(info.value)


# --- study --------------------------------------------------------------------------------
def _cfg(**drive):
    d = {"type": "rhomboid_cam", "link_length": 0.12, "psi_min": np.radians(40), "a": [], "b": []}
    d.update(drive)
    return {
        "title": "",
        "drive": d,
        "machine": {},
        "loads": {"torque_high": 100.0, "torque_low": 40.0},
        "run": {"points": 181},
    }


def test_study_summary_paper_example():
    res = evaluate(_cfg())
    s = res.summary
    h = np.pi / 2 - np.radians(40)  # a_1 of eq. 16
    expected = {
        "psi_min_deg": 40.0,
        "psi_max_deg": 140.0,
        "profile_radius_min_mm": 120 * np.cos(np.radians(70)),
        "profile_radius_max_mm": 120 * np.cos(np.radians(20)),
        "indicator_work_J": 60.0 * np.radians(100),
        "indicator_work_closed_form_J": 60.0 * np.radians(100),
        "mean_shaft_torque_Nm": 60.0 * np.radians(100) / np.pi,
        "blade_accel_coeff_max": 4 * h / 2,  # |psi''|/2 = 2 a_1 at alpha = 0
        "blade_speed_coeff_max": 1 + h,  # 1 + |psi'|/2, |psi'| <= 2 a_1
        "blade_speed_coeff_min": 1 - h,
        "blade_jerk_coeff_max": 8 * h / 2,
        "a1_rad": h,
        "b1_rad": 0.0,
        "psi_lowest_deg": 40.0,
        "psi_highest_deg": 140.0,
        "psi_travel_per_period_deg": 200.0,
    }
    for key, value in expected.items():
        assert s[key] == pytest.approx(value, rel=1e-6, abs=1e-9), key
    assert s["psi_monotone"] is True
    assert s["highest_harmonic"] == 1
    # waist of the cam at alpha = 0 is concave: rho'' > 0 at the minimum radius
    assert s["profile_convex"] is False
    json.dumps(s)
    for key in res.headline:
        assert key in s


def test_study_columns():
    res = evaluate(_cfg(a=[0.02], b=[0.01]))
    cols = res.columns
    assert list(cols)[0] == "alpha_deg"
    assert all(v.shape == (181,) for v in cols.values())
    assert set(cols) == set(res.column_docs)
    np.testing.assert_allclose(cols["alpha_deg"], np.linspace(0, 180, 181))
    al = np.radians(cols["alpha_deg"])
    psi = psi_ref(al, np.radians(40), (0.02,), (0.01,))
    np.testing.assert_allclose(cols["psi_deg"], np.degrees(psi), atol=1e-10)
    np.testing.assert_allclose(cols["rho_mm"], 120 * np.cos(psi / 2), atol=1e-10)
    np.testing.assert_allclose(cols["rho_b_mm"], 120 * np.sin(psi / 2), atol=1e-10)
    np.testing.assert_allclose(np.hypot(cols["x_mm"], cols["y_mm"]), cols["rho_mm"], atol=1e-10)
    np.testing.assert_allclose(cols["phi1_deg"] - cols["phi2_deg"], cols["psi_deg"], atol=1e-10)
    np.testing.assert_allclose(cols["phi1_speed_coeff"], 1 + cols["dpsi"] / 2, atol=1e-14)
    np.testing.assert_allclose(cols["dA_dalpha_J_per_rad"],
                               cols["blade_torque_Nm"] * cols["dpsi"], atol=1e-12)  # fmt: skip


def test_study_motion_is_both_blade_pairs_on_the_column_grid():
    res = evaluate(_cfg(a=[0.02], b=[0.01]))
    mo, cols = res.motion, res.columns
    assert mo is not None and mo.members == ("blade pair 1", "blade pair 2")
    np.testing.assert_allclose(np.degrees(mo.theta), cols["alpha_deg"], rtol=0, atol=1e-12)
    al = np.radians(cols["alpha_deg"])
    psi = psi_ref(al, np.radians(40), (0.02,), (0.01,))
    np.testing.assert_allclose(mo.q[0], al + psi / 2, atol=1e-12)  # eq. 21
    np.testing.assert_allclose(mo.q[1], al - psi / 2, atol=1e-12)
    np.testing.assert_allclose(mo.dq[0], cols["phi1_speed_coeff"], atol=1e-14)
    np.testing.assert_allclose(mo.d2q[1], cols["phi2_accel_per_rad"], atol=1e-14)
    np.testing.assert_allclose(mo.d3q[0], cols["phi1_jerk_per_rad2"], atol=1e-14)


def test_study_non_monotone():
    s = evaluate(_cfg(a=[0.4])).summary
    assert s["psi_monotone"] is False
    assert s["indicator_work_J"] > 1.4 * s["indicator_work_closed_form_J"]
    assert s["psi_travel_per_period_deg"] > 200.0


def test_study_errors_name_the_config_key():
    with pytest.raises(ParameterError, match=r"^drive\.psi_min = "):
        evaluate(_cfg(psi_min=np.radians(95)))
    with pytest.raises(ParameterError, match=r"^drive\.a = "):
        evaluate(_cfg(a=[2.0]))
    with pytest.raises(ParameterError, match=r"^drive\.link_length = "):
        evaluate(_cfg(link_length=0.0))


@pytest.mark.slow
@pytest.mark.parametrize("drive", [{}, {"a": [0.4]}, {"a": [0.05], "b": [0.02]}])
def test_study_plot_writes_pngs(tmp_path, drive):
    paths = evaluate(_cfg(**drive)).write_figures(tmp_path)
    # fig01-fig04 of the drive, fig05, fig07, fig08 of the engine (fig06, p-V, needs pressures),
    # fig09 the converter's forces
    assert [p.name[:5] for p in paths] == ["fig01", "fig02", "fig03", "fig04", "fig05", "fig07",
                                           "fig08", "fig09"]  # fmt: skip
    for p in paths:
        assert p.suffix == ".png" and p.parent == tmp_path
        assert p.stat().st_size > 10_000
        assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


# --- one source of defaults -----------------------------------------------------------------
def _schema_defaults(model, **required):
    """Every field of a config section parsed through the schema (SI), defaults filled."""
    return model(**required).model_dump()


@pytest.mark.parametrize(
    "holder, section",
    [
        ("drive", "drive"),
        ("machine", "machine"),
        ("gas", "loads"),
    ],
)
def test_dataclass_defaults_equal_the_schema(holder, section):
    cls = {"drive": rc.RhomboidCam, "machine": rb.RotaryBlade, "gas": rb.IsothermalGas}[holder]
    parsed = {
        "drive": lambda: _schema_defaults(
            schema.RhomboidDrive, type="rhomboid_cam", link_length="120 mm", psi_min="40 deg"
        ),
        "machine": lambda: _schema_defaults(schema.RotaryBladeMachine),
        "loads": lambda: _schema_defaults(schema.RhomboidLoads),
    }[section]()
    checked = 0
    for f in dataclasses.fields(cls):
        if f.default is dataclasses.MISSING:
            continue
        assert f.name in parsed, f"{cls.__name__}.{f.name} has no schema field"
        want = parsed[f.name]
        got = f.default
        if isinstance(want, list):
            want, got = tuple(want), tuple(got)
        assert got == want, f"{cls.__name__}.{f.name} = {got!r}, schema: {want!r}"
        checked += 1
    if holder != "gas":  # IsothermalGas has no defaults; the others must have been compared
        assert checked >= 2
