"""Every stated result of Zhuravlev, Donchenko, Sherstyukov (2012), rhomboid lever-cam converter.

Source: ``papers/rhomboid_cam.md`` (OCR ``original/004_9d85cab5121ee64f.txt``).
The paper publishes no numerical tables: its results are identities (eq. 3-34)
and one closed form (eq. 31, 34). Each test cites the equation and its tolerance.
Tolerances: identities evaluated in double precision are held to 1e-12 (a few
hundred ulps of the quantities, which are O(1) rad or O(0.1) m); quadratures
written here with scipy are held to their own accuracy.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from rotorkin.drives.rhomboid_cam import kinematics as rc

PSI_MIN = np.radians(40.0)
L = 0.12  # 2l [m]
ALPHA = np.linspace(-np.pi, np.pi, 257)


def laws(seed=3, count=4):
    """Admissible laws with 1st, 3rd and 5th harmonics (small, so 0 < psi < pi)."""
    rng = np.random.default_rng(seed)
    out = [(PSI_MIN, (), ())]
    for _ in range(count):
        out.append(
            (
                rng.uniform(0.3, 1.3),
                tuple(rng.uniform(-0.1, 0.1, 2)),
                tuple(rng.uniform(-0.03, 0.03, 2)),
            )
        )
    return out


@pytest.mark.parametrize("law", laws())
def test_eq3_eq4_half_diagonals(law):
    """Eq. 3 rho_A = 2l cos(psi/2) and eq. 4 rho_B = 2l sin(psi/2) (the OCR prints cos in eq. 4;
    sin is what eq. 7 requires). Built here from the blade arm points l e(phi_1), l e(phi_2):
    A is their vector sum (O, arm 1, A, arm 2 form a rhombus of side l). Tol 1e-12 m."""
    psi = rc.psi_law(*law, ALPHA)[0]
    phi1, phi2 = ALPHA + psi / 2, ALPHA - psi / 2  # eq. 21
    l = L / 2
    A = l * np.stack([np.cos(phi1) + np.cos(phi2), np.sin(phi1) + np.sin(phi2)])
    v = rc.rhombus_vertices(L, *law, ALPHA)
    np.testing.assert_allclose(v[0], A, atol=1e-12)
    np.testing.assert_allclose(np.hypot(*v[0]), L * np.cos(psi / 2), atol=1e-12)
    np.testing.assert_allclose(np.hypot(*v[1]), L * np.sin(psi / 2), atol=1e-12)
    np.testing.assert_allclose(
        rc.profile_radius(L, *law, ALPHA)[0], L * np.cos(psi / 2), atol=1e-15
    )


@pytest.mark.parametrize("law", laws())
def test_eq5_eq6_end_conditions(law):
    """Eq. 5: psi = psi_max = pi - psi_min at alpha = 0, psi_min at +-pi/2; eq. 6: psi' = 0 there.
    Tol 1e-12 rad (sin(k pi) rounding)."""
    psi_min = law[0]
    p = rc.psi_law(*law, np.array([0.0, np.pi / 2, -np.pi / 2]))
    np.testing.assert_allclose(p[0], [np.pi - psi_min, psi_min, psi_min], atol=1e-12)
    np.testing.assert_allclose(p[1], 0.0, atol=1e-12)


@pytest.mark.parametrize("law", laws())
def test_eq7_diagonals(law):
    """Eq. 7: rho_A^2 + rho_B^2 = 4 l^2 = (2l)^2. Tol 1e-14 m^2."""
    v = rc.rhombus_vertices(L, *law, ALPHA)
    np.testing.assert_allclose(np.sum(v[0] ** 2, 0) + np.sum(v[1] ** 2, 0), L**2, atol=1e-14)


@pytest.mark.parametrize("law", laws())
def test_eq8_eq10(law):
    """Eq. 8: cos psi(alpha + pi/2) = -cos psi(alpha); eq. 10: psi(alpha + pi/2) = pi - psi(alpha).
    Tol 1e-12."""
    p0 = rc.psi_law(*law, ALPHA)[0]
    p1 = rc.psi_law(*law, ALPHA + np.pi / 2)[0]
    np.testing.assert_allclose(np.cos(p1), -np.cos(p0), atol=1e-12)
    np.testing.assert_allclose(p1, np.pi - p0, atol=1e-12)
    # consequence used for the cam: vertex B lies on the curve, OB = rho(alpha + pi/2)
    v = rc.rhombus_vertices(L, *law, ALPHA)
    rho_b = rc.profile_radius(L, *law, ALPHA + np.pi / 2)[0]
    np.testing.assert_allclose(np.hypot(*v[1]), rho_b, atol=1e-12)


@pytest.mark.parametrize("law", laws())
def test_eq11_eq12_no_even_harmonics(law):
    """Eq. 11-12: a_0 = pi/2 and every even harmonic (cos/sin 4 alpha, 8 alpha, ...) vanishes.
    Discrete Fourier transform of psi over one period pi (exact for these trigonometric
    polynomials, 256 samples > twice the highest order). Tol 1e-12."""
    n = 256
    al = np.arange(n) * np.pi / n
    c = np.fft.rfft(rc.psi_law(*law, al)[0]) / n  # bin j: frequency 2 j in alpha
    assert c[0].real == pytest.approx(np.pi / 2, abs=1e-12)
    np.testing.assert_allclose(np.abs(c[2::2]), 0.0, atol=1e-12)
    assert np.abs(c[1]) > 1e-3  # the first harmonic is there


@pytest.mark.parametrize("law", laws())
def test_eq15_coefficient_sums(law):
    """Eq. 15: a_1 + a_3 + a_5 + ... = pi/2 - psi_min, b_1 + 3 b_3 + 5 b_5 + ... = 0.
    The first harmonic is read back from the law itself by a DFT, not from the code's a_1.
    Tol 1e-12."""
    psi_min, a, b = law
    n = 256
    al = np.arange(n) * np.pi / n
    c = 2 * np.fft.rfft(rc.psi_law(*law, al)[0]) / n
    a1, b1 = c[1].real, -c[1].imag
    assert a1 + sum(a) == pytest.approx(np.pi / 2 - psi_min, abs=1e-12)
    assert b1 + 3 * (b[0] if b else 0) + 5 * (b[1] if len(b) > 1 else 0) == pytest.approx(
        0.0, abs=1e-12
    )
    # and the higher harmonics are the ones given: a_3 = Re c[3], b_3 = -Im c[3]
    if a:
        assert c[3].real == pytest.approx(a[0], abs=1e-12)
        assert -c[3].imag == pytest.approx(b[0], abs=1e-12)


def test_eq16_first_harmonic_law():
    """Eq. 16: psi = pi/2 + (pi/2 - psi_min) cos 2 alpha (the patented profile, eq. 1).
    Tol 1e-14 rad (1e-13 for the derivatives, scaled by 4 and 8)."""
    p = rc.psi_law(PSI_MIN, (), (), ALPHA)
    h = np.pi / 2 - PSI_MIN
    np.testing.assert_allclose(p[0], np.pi / 2 + h * np.cos(2 * ALPHA), atol=1e-14)
    np.testing.assert_allclose(p[1], -2 * h * np.sin(2 * ALPHA), atol=1e-14)
    np.testing.assert_allclose(p[2], -4 * h * np.cos(2 * ALPHA), atol=1e-13)
    np.testing.assert_allclose(p[3], 8 * h * np.sin(2 * ALPHA), atol=1e-13)


@pytest.mark.parametrize("a3, b3", [(0.1, 0.0), (-0.1, 0.05), (0.05, -0.03), (-0.2, 0.02)])
def test_eq17_eq18(a3, b3):
    """Eq. 18 (eq. 17 with eq. 15: a_1 = pi/2 - psi_min - a_3, b_1 = -3 b_3), as printed.
    Tol 1e-14 rad."""
    al = ALPHA
    eq18 = (
        np.pi / 2
        + (np.pi / 2 - PSI_MIN - a3) * np.cos(2 * al)
        + a3 * np.cos(6 * al)
        - 3 * b3 * np.sin(2 * al)
        + b3 * np.sin(6 * al)
    )
    np.testing.assert_allclose(rc.psi_law(PSI_MIN, (a3,), (b3,), al)[0], eq18, atol=1e-14)
    # "substituting alpha + pi/2 ... confirms condition (10) and restrictions (5), (6)"
    p = rc.psi_law(PSI_MIN, (a3,), (b3,), np.array([0.0, np.pi / 2]))
    np.testing.assert_allclose(p[0], [np.pi - PSI_MIN, PSI_MIN], atol=1e-14)
    np.testing.assert_allclose(p[1], 0.0, atol=1e-14)


@pytest.mark.parametrize("a3, b3", [(0.1, 0.0), (-0.1, 0.05)])
def test_eq19_profile(a3, b3):
    """Eq. 19 as printed, rho = 2l sin(pi/4 + (pi/4 - psi_min/2 - a3/2) cos 2a + a3/2 cos 6a
    - 3 b3/2 sin 2a + b3/2 sin 6a): the sin form. It is our (eq. 3, cos) cam turned by a
    quarter turn: rho_19(alpha) = rho_3(alpha + pi/2), i.e. every point of the eq. 19 curve is a
    point of the eq. 3 curve rotated by -90 deg. Tol 1e-15 m."""
    al = ALPHA
    arg = (
        np.pi / 4
        + (np.pi / 4 - PSI_MIN / 2 - a3 / 2) * np.cos(2 * al)
        + a3 / 2 * np.cos(6 * al)
        - 3 * b3 / 2 * np.sin(2 * al)
        + b3 / 2 * np.sin(6 * al)
    )
    eq19 = L * np.sin(arg)
    law = (PSI_MIN, (a3,), (b3,))
    np.testing.assert_allclose(rc.profile_radius_eq19(L, *law, al), eq19, atol=1e-15)
    np.testing.assert_allclose(rc.profile_radius(L, *law, al + np.pi / 2)[0], eq19, atol=1e-15)
    p3 = rc.profile_point(L, *law, al + np.pi / 2)[0]
    turned = np.stack([p3[1], -p3[0]])  # rotation by -90 deg
    p19 = eq19 * np.stack([np.cos(al), np.sin(al)])
    np.testing.assert_allclose(turned, p19, atol=1e-15)


def test_eq8_constant_law_is_a_circle():
    """After eq. 8: a constant law can only be psi = pi/2; the rhombus is a square and the cam a
    circle of radius 2l sqrt(2)/2. The plain functions accept psi_min = pi/2. Tol 1e-15."""
    pm = np.pi / 2
    p = rc.psi_law(pm, (), (), ALPHA)
    np.testing.assert_allclose(p[0], np.pi / 2, atol=1e-15)
    for d in p[1:]:
        np.testing.assert_allclose(d, 0.0, atol=1e-15)
    np.testing.assert_allclose(
        rc.profile_radius(L, pm, (), (), ALPHA)[0], L * np.sqrt(2) / 2, atol=1e-15
    )
    v = rc.rhombus_vertices(L, pm, (), (), ALPHA)
    np.testing.assert_allclose(np.hypot(*v[1]), L * np.sqrt(2) / 2, atol=1e-15)  # square
    assert float(rc.indicator_work(pm, (), (), 100.0, 40.0)) == 0.0


@pytest.mark.parametrize("law", laws())
def test_eq21_eq22_blade_angles(law):
    """Eq. 21 phi_1 - phi_2 = psi, phi_1 + phi_2 = 2 alpha (constants taken zero); eq. 22
    d phi_1 = (1 + psi'/2) d alpha, d phi_2 = (1 - psi'/2) d alpha. Tol 1e-14."""
    phi, d1, d2, _ = rc.blade_angles(*law, ALPHA)
    p = rc.psi_law(*law, ALPHA)
    np.testing.assert_allclose(phi[0] - phi[1], p[0], atol=1e-14)
    np.testing.assert_allclose(phi[0] + phi[1], 2 * ALPHA, atol=1e-14)
    np.testing.assert_allclose(d1[0], 1 + p[1] / 2, atol=1e-14)
    np.testing.assert_allclose(d1[1], 1 - p[1] / 2, atol=1e-14)
    np.testing.assert_allclose(d2[0], p[2] / 2, atol=1e-14)


@pytest.mark.parametrize("law", laws())
def test_eq20_eq24_work_rate(law):
    """Eq. 20/23: dA = M_1 dphi_1 + M_2 dphi_2; with M_2 = -M_1, eq. 24: dA = M_1 psi' d alpha.
    Any M_1: the blade torque model's value at each alpha. Tol 1e-12 N m."""
    m1, m2 = 100.0, 40.0
    al = ALPHA
    dphi = rc.blade_angles(*law, al)[1]
    psi, dpsi = rc.psi_law(*law, al)[:2]
    M1 = rc.blade_torque(m1, m2, law[0], psi, rc.stroke_direction(*law, al))
    eq23 = M1 * dphi[0] + (-M1) * dphi[1]
    np.testing.assert_allclose(eq23, M1 * dpsi, atol=1e-12)
    np.testing.assert_allclose(rc.shaft_torque(*law, m1, m2, al), eq23, atol=1e-12)


@pytest.mark.parametrize("m1, m2", [(100.0, 40.0), (250.0, -30.0), (10.0, 10.0)])
def test_eq31_first_harmonic_work(m1, m2):
    """Eq. 31: for the harmonic law (16), A = Delta M Delta psi with Delta M = M1 - M2,
    Delta psi = psi_max - psi_min. Also eq. 27-28 integrated over psi here with scipy.quad.
    Tol 1e-12 relative (Gauss-Legendre on the monotone pieces is exact to rounding)."""
    dpsi = np.pi - 2 * PSI_MIN
    A = float(rc.indicator_work(PSI_MIN, (), (), m1, m2))
    assert A == pytest.approx((m1 - m2) * dpsi, rel=1e-12, abs=1e-12)
    a, b = (m1 - m2) / 2, (m1 + m2) / 2
    x = lambda p: (p - np.pi / 2) / (np.pi / 2 - PSI_MIN)  # noqa: E731
    comp = quad(lambda p: -a - b * x(p), np.pi - PSI_MIN, PSI_MIN)[0]
    expa = quad(lambda p: a - b * x(p), PSI_MIN, np.pi - PSI_MIN)[0]
    assert A == pytest.approx(comp + expa, rel=1e-12, abs=1e-12)
    assert float(rc.mean_shaft_torque(PSI_MIN, (), (), m1, m2)) == pytest.approx(A / np.pi)


@pytest.mark.parametrize("a3, b3", [(0.1, 0.0), (-0.1, 0.05), (0.05, -0.03), (-0.109, 0.0)])
def test_eq34_first_and_third_harmonic_work(a3, b3):
    """Eq. 34: for the 1st + 3rd harmonic law (18), A = Delta M Delta psi again - true here
    because these laws are monotone between their extremes (checked on a dense grid).
    Tol 1e-12 relative."""
    g = np.linspace(1e-6, np.pi / 2 - 1e-6, 100001)
    assert np.all(np.diff(rc.psi_law(PSI_MIN, (a3,), (b3,), g)[0]) < 0)
    A = float(rc.indicator_work(PSI_MIN, (a3,), (b3,), 100.0, 40.0))
    assert A == pytest.approx(60.0 * (np.pi - 2 * PSI_MIN), rel=1e-12)


def test_eq34_claim_fails_for_non_monotone_laws():
    """The paper concludes that A does not depend on the profile. With eq. 29 switching
    between M_c and M_p on the sign of psi', a law that swings back and forth between its
    extremes does more work: A = (M1 - M2) x (total travel of psi)/2. Independent check:
    adaptive scipy.quad over alpha of M_1 psi' with psi of eq. 18 written out here
    (a3 = 0.4, b3 = 0). Tol 1e-9 relative."""
    a3, m1, m2 = 0.4, 100.0, 40.0
    a1 = np.pi / 2 - PSI_MIN - a3
    a, b = (m1 - m2) / 2, (m1 + m2) / 2

    def integrand(al):
        psi = np.pi / 2 + a1 * np.cos(2 * al) + a3 * np.cos(6 * al)
        d = -2 * a1 * np.sin(2 * al) - 6 * a3 * np.sin(6 * al)
        x = (psi - np.pi / 2) / (np.pi / 2 - PSI_MIN)
        return (a - b * x if d > 0 else -a - b * x) * d

    ref = quad(integrand, 0.0, np.pi, limit=1000, epsabs=1e-12, epsrel=1e-12)[0]
    A = float(rc.indicator_work(PSI_MIN, (a3,), (), m1, m2))
    assert A == pytest.approx(ref, rel=1e-9)
    assert A > 1.4 * (m1 - m2) * (np.pi - 2 * PSI_MIN)


@pytest.mark.parametrize("a3, b3", [(0.0, 0.0), (0.1, 0.0), (-0.1, 0.05), (-0.109, 0.0)])
def test_eq31_eq34_through_the_engine(a3, b3):
    """Eq. 31/34 again, now through the rotary-blade engine (study path): member torques
    (M_1, -M_1) on the blade pairs (eq. 24), shaft torque by virtual work sum M_i phi_i',
    integrated over the half turn; the per-revolution work is twice the paper's A.
    Tol 1e-12 relative (Gauss-Legendre on the monotone pieces)."""
    from rotorkin.drives import evaluate

    cfg = {
        "drive": {"type": "rhomboid_cam", "link_length": L, "psi_min": PSI_MIN,
                  "a": [a3], "b": [b3]},
        "machine": {}, "loads": {"torque_high": 100.0, "torque_low": 40.0}, "run": {"points": 91},
    }  # fmt: skip
    s = evaluate(cfg).summary
    A = 60.0 * (np.pi - 2 * PSI_MIN)
    assert s["indicator_work_J"] == pytest.approx(A, rel=1e-12)
    assert s["indicated_work_per_period_J"] == pytest.approx(A, rel=1e-12)
    assert s["indicated_work_J"] == pytest.approx(2 * A, rel=1e-12)
    assert s["mean_torque_Nm"] == pytest.approx(A / np.pi, rel=1e-12)
