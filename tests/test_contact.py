"""Hertz contact: closed forms, the elliptic contact against numeric integrals, broadcasting.

The expected values are written with other algebra than the module's: the
line and circle contacts in Roark's form (diameters ``D``, ``K_D`` and the
compliance sum ``C_E``, Roark's *Formulas for Stress and Strain*, bodies in
contact), the elliptic contact through quadrature of the defining integrals
of the surface displacement (Johnson, *Contact Mechanics*, ch. 3 and sec. 4.2) and of
the pressure over the ellipse, never through the module's elliptic integrals.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate, optimize
from scipy.special import ellipe, ellipk

from rotorkin.analysis.contact import (
    STEEL,
    LineContact,
    Material,
    PointContact,
    effective_modulus,
    effective_radius,
    line_contact,
    point_contact,
    safety_factor,
)
from rotorkin.core.errors import ParameterError

E_STEEL, NU_STEEL = 210e9, 0.3
# Roark's compliance sum C_E = (1 - nu1^2) / E1 + (1 - nu2^2) / E2, two steels
C_E = 2.0 * (1.0 - NU_STEEL**2) / E_STEEL
REL = 1e-9


def close(actual, expected, rel=REL):
    np.testing.assert_allclose(actual, expected, rtol=rel, atol=0.0)


# --------------------------------------------------------------------------- materials


def test_steel_and_effective_modulus():
    assert STEEL == Material(210e9, 0.3)
    # two steels: E* = E / (2 (1 - nu^2)) = 210e9 / 1.82 = 115.384615384...e9
    close(effective_modulus(STEEL, STEEL), 115.38461538461538e9)
    aluminium = Material(70e9, 0.33)
    # E* = E1 E2 / (E2 (1 - nu1^2) + E1 (1 - nu2^2))
    expected = 210e9 * 70e9 / (70e9 * (1 - 0.09) + 210e9 * (1 - 0.1089))
    close(effective_modulus(STEEL, aluminium), expected)
    close(effective_modulus(aluminium, STEEL), expected)


@pytest.mark.parametrize(
    ("key", "kwargs"),
    [
        ("contact.youngs_modulus", {"youngs_modulus": 0.0, "poisson_ratio": 0.3}),
        ("contact.youngs_modulus", {"youngs_modulus": -210e9, "poisson_ratio": 0.3}),
        ("contact.youngs_modulus", {"youngs_modulus": math.inf, "poisson_ratio": 0.3}),
        ("contact.youngs_modulus", {"youngs_modulus": math.nan, "poisson_ratio": 0.3}),
        ("contact.youngs_modulus", {"youngs_modulus": "210e9", "poisson_ratio": 0.3}),
        ("contact.youngs_modulus", {"youngs_modulus": None, "poisson_ratio": 0.3}),
        ("contact.youngs_modulus", {"youngs_modulus": True, "poisson_ratio": 0.3}),
        ("contact.poisson_ratio", {"youngs_modulus": 210e9, "poisson_ratio": -0.1}),
        ("contact.poisson_ratio", {"youngs_modulus": 210e9, "poisson_ratio": 0.5}),
        ("contact.poisson_ratio", {"youngs_modulus": 210e9, "poisson_ratio": 0.7}),
        ("contact.poisson_ratio", {"youngs_modulus": 210e9, "poisson_ratio": math.nan}),
        ("contact.poisson_ratio", {"youngs_modulus": 210e9, "poisson_ratio": "0.3"}),
        ("contact.poisson_ratio", {"youngs_modulus": 210e9, "poisson_ratio": [0.3]}),
    ],
)
def test_material_refusals_are_one_line_parameter_errors(key, kwargs):
    with pytest.raises(ParameterError) as info:
        Material(**kwargs)
    assert info.value.name == key
    text = str(info.value)
    assert text.startswith(key + " = ")
    assert "\n" not in text


def test_material_limits_accepted():
    Material(1e-3, 0.0)
    Material(1e12, 0.4999)
    Material(np.float64(200e9), np.float64(0.29))


# --------------------------------------------------------------------------- radii


@pytest.mark.parametrize(
    ("r1", "r2", "expected"),
    [
        (10.0, 40.0, 8.0),  # two convex: 1/10 + 1/40 = 5/40
        (10.0, math.inf, 10.0),  # on a flat
        (10.0, -math.inf, 10.0),
        (10.0, -40.0, 40.0 / 3.0),  # in a concave one: 1/10 - 1/40 = 3/40
        (-40.0, 10.0, 40.0 / 3.0),
        (math.inf, math.inf, math.inf),  # two flats
    ],
)
def test_effective_radius(r1, r2, expected):
    assert effective_radius(r1, r2) == pytest.approx(expected, rel=1e-15)


@pytest.mark.parametrize(
    ("r1", "r2"),
    [
        (10.0, -10.0),  # conformal: equal and opposite curvatures
        (10.0, -5.0),  # the concave body tighter than the convex one: no point contact
        (-10.0, -20.0),  # two concave
        (-10.0, math.inf),  # concave on a flat
        (0.0, 10.0),  # an edge
        (math.nan, 10.0),
    ],
)
def test_effective_radius_marks_no_hertz_geometry_nan(r1, r2):
    assert math.isnan(effective_radius(r1, r2))
    assert math.isnan(effective_radius(r2, r1))


# --------------------------------------------------------------------------- line contact


def roark_line(force, length, d1, d2):
    """Half-width and peak pressure from diameters (Roark: width 1.60 sqrt(p K_D C_E)).

    ``d2`` signed: negative for the concave cylinder (Roark's K_D = D1 D2 / (D1 + D2)),
    ``inf`` for a plane (K_D = D1).
    """
    p = force / length
    k_d = d1 if math.isinf(d2) else d1 * d2 / (d1 + d2)
    half_width = math.sqrt(2.0 * p * k_d * C_E / math.pi)  # 1.60 / 2 = sqrt(2 / pi)
    peak = math.sqrt(2.0 * p / (math.pi * k_d * C_E))  # 0.798 = sqrt(2 / pi)
    return half_width, peak


def test_two_cylinders_closed_form():
    # roller r = 15 mm on a convex cam flank of 60 mm, 2 kN over 20 mm
    out = line_contact(2000.0, 0.02, 0.015, 0.060)
    assert isinstance(out, LineContact)
    b, p0 = roark_line(2000.0, 0.02, 0.030, 0.120)
    # by hand: p = 1e5 N/m, K_D = 0.024 m, C_E = 8.6667e-12 1/Pa
    # b = sqrt(2e5 * 0.024 * 8.6667e-12 / pi) = 1.15072548e-4 m, p0 = 5.53233403e8 Pa
    close(out.b, b)
    close(out.p_max, p0)
    close(out.b, 1.1507254783503185e-4)
    close(out.p_max, 5.532334030530376e8)
    # Johnson eq. 4.43 ff, in the module's own variables, once
    e_star = effective_modulus(STEEL, STEEL)
    close(out.b, math.sqrt(4 * 2000.0 * 0.012 / (math.pi * 0.02 * e_star)))
    close(out.p_max, 2 * 2000.0 / (math.pi * out.b * 0.02))


def test_cylinder_on_plane_closed_form():
    out = line_contact(1500.0, 0.012, 0.010, np.inf)
    b, p0 = roark_line(1500.0, 0.012, 0.020, math.inf)
    close(out.b, b)
    close(out.p_max, p0)
    same = line_contact(1500.0, 0.012, np.inf, 0.010)
    close(same.b, b)


def test_cylinder_in_concave_cylinder_closed_form():
    # roller of 10 mm radius in a groove flank of 25 mm concave radius
    out = line_contact(800.0, 0.008, 0.010, -0.025)
    b, p0 = roark_line(800.0, 0.008, 0.020, -0.050)
    close(out.b, b)
    close(out.p_max, p0)
    # conformity widens the contact against the same roller on a plane
    assert out.b > line_contact(800.0, 0.008, 0.010, np.inf).b


def test_line_pressure_integrates_to_the_load():
    force, length = 2000.0, 0.02
    out = line_contact(force, length, 0.015, 0.060)
    b, p0 = float(out.b), float(out.p_max)
    load, _ = integrate.quad(lambda x: p0 * math.sqrt(1.0 - (x / b) ** 2), -b, b)
    assert load == pytest.approx(force / length, rel=1e-8)


def test_subsurface_shear_maximum_found_numerically():
    out = line_contact(2000.0, 0.02, 0.015, 0.060)
    b, p0 = float(out.b), float(out.p_max)

    def tau(z):
        # stresses on the plane of symmetry under the Hertz line pressure (Johnson sec. 4.3)
        root = math.sqrt(b * b + z * z)
        sigma_x = -p0 / b * ((b * b + 2 * z * z) / root - 2 * z)
        sigma_z = -p0 * b / root
        return 0.5 * (sigma_x - sigma_z)

    best = optimize.minimize_scalar(
        lambda z: -tau(z), bounds=(0.0, 3 * b), method="bounded", options={"xatol": 1e-12 * b}
    )
    assert out.depth == pytest.approx(best.x, rel=1e-6)
    assert out.tau_max == pytest.approx(tau(best.x), rel=1e-9)
    # Johnson's rounded figures: 0.300 p0 at 0.786 b
    assert out.tau_max / p0 == pytest.approx(0.300, abs=5e-4)
    assert out.depth / b == pytest.approx(0.786, abs=5e-4)


def test_line_contact_zero_force_is_zero_contact():
    out = line_contact(0.0, 0.02, 0.015, 0.060)
    assert out.b == 0.0 and out.p_max == 0.0 and out.tau_max == 0.0 and out.depth == 0.0


@pytest.mark.parametrize("force", [-1.0, np.array([10.0, -1e-9])])
def test_negative_force_is_a_programming_error(force):
    with pytest.raises(ValueError, match="force"):
        line_contact(force, 0.01, 0.01, 0.02)
    with pytest.raises(ValueError, match="force"):
        point_contact(force, 0.01, 0.01, 0.02, 0.02)


@pytest.mark.parametrize("length", [0.0, -0.01])
def test_length_must_be_positive(length):
    with pytest.raises(ValueError, match="length"):
        line_contact(100.0, length, 0.01, 0.02)


def test_materials_enter_line_contact():
    aluminium = Material(70e9, 0.33)
    out = line_contact(1000.0, 0.01, 0.01, np.inf, STEEL, aluminium)
    compliance = (1 - 0.09) / 210e9 + (1 - 0.33**2) / 70e9
    close(out.b, math.sqrt(2.0 * 1e5 * 0.02 * compliance / math.pi))


# --------------------------------------------------------------------------- circle


def roark_sphere(force, k_d):
    """Radius, peak pressure and approach: a = 0.721 (P K_D C_E)^(1/3), y = 1.04 (...)^(1/3)."""
    a = (3.0 / 8.0 * force * k_d * C_E) ** (1 / 3)  # 0.721 = (3/8)^(1/3)
    peak = 1.5 * force / (math.pi * a * a)
    approach = (9.0 / 8.0 * force**2 * C_E**2 / k_d) ** (1 / 3)  # 1.04 = (9/8)^(1/3)
    return a, peak, approach


def test_sphere_on_plane_closed_form():
    out = point_contact(50.0, 0.005, 0.005, np.inf, np.inf)
    assert isinstance(out, PointContact)
    a, p0, delta = roark_sphere(50.0, 0.010)
    # by hand: a = (3/8 * 50 * 0.01 * 8.6667e-12)^(1/3) = 1.17566734e-4 m,
    # p0 = 75 / (pi a^2) = 1.72719941e9 Pa, delta = a^2 / R = 2.76438741e-6 m
    for value in (out.a, out.b):
        close(value, a)
        close(value, 1.1756673438603794e-4)
    close(out.p_max, p0)
    close(out.p_max, 1.7271994080655212e9)
    close(out.approach, delta)
    close(out.approach, 2.764387406839438e-6)


def test_sphere_on_sphere_and_in_a_socket_closed_form():
    out = point_contact(120.0, 0.006, 0.006, 0.010, 0.010)
    a, p0, delta = roark_sphere(120.0, 0.012 * 0.020 / 0.032)
    close(out.a, a)
    close(out.b, a)
    close(out.p_max, p0)
    close(out.approach, delta)
    socket = point_contact(120.0, 0.006, 0.006, -0.010, -0.010)
    a, p0, delta = roark_sphere(120.0, 0.012 * 0.020 / (0.020 - 0.012))
    close(socket.a, a)
    close(socket.p_max, p0)
    close(socket.approach, delta)


# --------------------------------------------------------------------------- ellipse


def displacement_integrals(a, b):
    """I0, Ix, Iy of the surface displacement of p0 sqrt(1 - x^2/a^2 - y^2/b^2), by quadrature.

    u(x, y) = p0 a b / (2 E*) int_0^inf (1 - x^2/(a^2+w) - y^2/(b^2+w)) dw / sqrt(D(w) w),
    D(w) = (a^2+w)(b^2+w), summed over both bodies (Johnson sec. 4.2); with w = t^2,
    dw / sqrt(w) = 2 dt.
    """
    lo, hi = sorted((a, b))

    def quad(f):
        parts = [(0.0, lo), (lo, hi), (hi, 10 * hi), (10 * hi, np.inf)]
        return sum(
            integrate.quad(f, s, e, epsabs=0.0, epsrel=1e-12, limit=200)[0] for s, e in parts
        )

    def root(t):
        return math.sqrt((a * a + t * t) * (b * b + t * t))

    i0 = quad(lambda t: 2.0 / root(t))
    ix = quad(lambda t: 2.0 / ((a * a + t * t) * root(t)))
    iy = quad(lambda t: 2.0 / ((b * b + t * t) * root(t)))
    return i0, ix, iy


def crowned_roller(ratio):
    """Radii with Ry / Rx = ratio: roller 10 mm on a 40 mm cam, crown chosen for the ratio."""
    rx = 0.010 * 0.040 / 0.050
    ry = ratio * rx
    return 0.010, ry, 0.040, np.inf, rx, ry


@pytest.mark.parametrize("ratio", [1.0 / 250.0, 1.0 / 3.0, 1.7, 12.0, 250.0, 1e4])
def test_elliptic_contact_meets_the_compatibility_conditions(ratio):
    force = 400.0
    if ratio < 1:
        # the long axis along x this time: crown across, a wide roller lengthways
        rx1, ry1, rx2, ry2 = 0.008 / ratio, 0.008, np.inf, np.inf
        rx, ry = rx1, ry1
    else:
        rx1, ry1, rx2, ry2, rx, ry = crowned_roller(ratio)
    out = point_contact(force, rx1, ry1, rx2, ry2)
    a, b, p0 = float(out.a), float(out.b), float(out.p_max)
    assert (a > b) == (rx > ry)
    e_star = effective_modulus(STEEL, STEEL)
    i0, ix, iy = displacement_integrals(a, b)
    scale = p0 * a * b / (2.0 * e_star)
    # the displacement fills the gap x^2 / (2 Rx) + y^2 / (2 Ry) inside the ellipse
    assert scale * ix == pytest.approx(1.0 / (2.0 * rx), rel=1e-8)
    assert scale * iy == pytest.approx(1.0 / (2.0 * ry), rel=1e-8)
    assert scale * i0 == pytest.approx(float(out.approach), rel=1e-8)


def test_elongated_ellipse_pressure_integrates_to_the_force():
    force = 400.0
    out = point_contact(force, *crowned_roller(250.0)[:4])
    a, b, p0 = float(out.a), float(out.b), float(out.p_max)
    assert b / a > 20.0  # strongly elongated along the roller's axis

    # x = a u, y = b v over the unit disc
    def inner(u):
        half = math.sqrt(max(1.0 - u * u, 0.0))
        return integrate.quad(
            lambda v: math.sqrt(max(1.0 - u * u - v * v, 0.0)), -half, half, epsabs=1e-13
        )[0]

    unit, _ = integrate.quad(inner, -1.0, 1.0, epsabs=1e-13)
    assert p0 * a * b * unit == pytest.approx(force, rel=1e-7)


def test_equal_curvature_limit_is_the_sphere():
    sphere = point_contact(200.0, 0.008, 0.008, 0.030, 0.030)
    e_star = effective_modulus(STEEL, STEEL)
    radius = 1.0 / (1.0 / 0.008 + 1.0 / 0.030)
    a = (3.0 * 200.0 * radius / (4.0 * e_star)) ** (1 / 3)
    close(sphere.a, a)
    close(sphere.b, a)
    close(sphere.p_max, 3.0 * 200.0 / (2.0 * math.pi * a * a))
    close(sphere.approach, a * a / radius)
    # continuous into the ellipse: a relative difference of 1e-8 in a radius
    near = point_contact(200.0, 0.008, 0.008 * (1 + 1e-8), 0.030, 0.030)
    for name in ("a", "b", "p_max", "approach"):
        assert getattr(near, name) == pytest.approx(getattr(sphere, name), rel=1e-7)


@pytest.mark.parametrize("ratio", [1.1, 2.0, 10.0, 300.0, 1e4, 1e6])
def test_axis_ratio_solves_the_textbook_equation(ratio):
    # Johnson: Ry / Rx = (E(e) / q^2 - K(e)) / (K(e) - E(e)), q = minor / major, m = 1 - q^2
    out = point_contact(100.0, *crowned_roller(ratio)[:4])
    q = float(out.a / out.b)
    m = 1.0 - q * q
    k, e = ellipk(m), ellipe(m)
    assert (e / (q * q) - k) / (k - e) == pytest.approx(ratio, rel=1e-7)


@pytest.mark.parametrize("ratio", [1.0, 1.5, 3.0, 10.0, 30.0])
def test_hamrock_brewe_approximations_agree(ratio):
    # Hamrock & Brewe 1983, fitted for 1 <= k <= 10: k = 1.0339 (Ry/Rx)^0.6360,
    # E = 1.0003 + 0.5968 Rx/Ry, F = 1.5277 + 0.6023 ln(Ry/Rx); a few percent
    force = 300.0
    rx1, ry1, rx2, ry2, rx, ry = crowned_roller(ratio)
    out = point_contact(force, rx1, ry1, rx2, ry2)
    k_hb = 1.0339 * ratio**0.6360
    e_hb = 1.0003 + 0.5968 / ratio
    f_hb = 1.5277 + 0.6023 * math.log(ratio)
    e_prime = 2.0 * effective_modulus(STEEL, STEEL)
    radius = rx * ry / (rx + ry)
    d_y = 2.0 * (6.0 * k_hb**2 * e_hb * force * radius / (math.pi * e_prime)) ** (1 / 3)
    d_x = 2.0 * (6.0 * e_hb * force * radius / (math.pi * k_hb * e_prime)) ** (1 / 3)
    p_hb = 6.0 * force / (math.pi * d_x * d_y)
    delta_hb = f_hb * (9.0 / (2.0 * e_hb * radius) * (force / (math.pi * k_hb * e_prime)) ** 2) ** (
        1 / 3
    )
    assert float(out.b / out.a) == pytest.approx(k_hb, rel=0.035)
    assert float(out.a) == pytest.approx(d_x / 2.0, rel=0.03)
    assert float(out.b) == pytest.approx(d_y / 2.0, rel=0.03)
    assert float(out.p_max) == pytest.approx(p_hb, rel=0.03)
    # the approach compounds the three fits (k 3.4 % high and F 2.7 % low at k = 1)
    assert float(out.approach) == pytest.approx(delta_hb, rel=0.06)


def test_point_contact_zero_force():
    out = point_contact(0.0, 0.01, 0.5, 0.04, np.inf)
    assert out.a == 0.0 and out.b == 0.0 and out.p_max == 0.0 and out.approach == 0.0


# --------------------------------------------------------------------------- markers


def test_no_hertz_geometry_gives_nan_results():
    # concave groove tighter than the roller, conformal, two flats
    for r1, r2 in [(0.010, -0.008), (0.010, -0.010), (np.inf, np.inf)]:
        out = line_contact(100.0, 0.01, r1, r2)
        assert all(np.isnan(value) for value in out)
    # point contact: either direction without a Hertz contact
    for radii in [
        (0.010, 0.010, -0.008, -0.008),
        (0.010, 0.5, -0.008, np.inf),
        (0.010, 0.5, 0.04, -0.4),
        (0.010, np.inf, 0.04, np.inf),  # a line contact
    ]:
        out = point_contact(100.0, *radii)
        assert all(np.isnan(value) for value in out)


def test_nan_marks_only_the_bad_points():
    cam = np.array([0.04, -0.008, 0.10, -0.05, np.inf])  # cam radii along a profile
    out = line_contact(500.0, 0.01, 0.01, cam)
    assert np.isnan(out.p_max).tolist() == [False, True, False, False, False]
    # a concave flank loads the roller less than a convex one
    assert out.p_max[3] < out.p_max[4] < out.p_max[2] < out.p_max[0]
    zero = line_contact(0.0, 0.01, 0.01, cam)
    assert np.isnan(zero.p_max).tolist() == [False, True, False, False, False]


# --------------------------------------------------------------------------- broadcasting


def test_line_contact_broadcasts_like_scalar_calls():
    force = np.linspace(100.0, 1200.0, 12).reshape(3, 4)
    cam = np.array([0.03, 0.05, -0.02, np.inf])
    length = np.array([[0.008], [0.010], [0.012]])
    out = line_contact(force, length, 0.01, cam)
    for value in out:
        assert value.shape == (3, 4)
    for i in range(3):
        for j in range(4):
            single = line_contact(force[i, j], length[i, 0], 0.01, cam[j])
            for got, want in zip(out, single, strict=True):
                assert got[i, j] == pytest.approx(float(want), rel=1e-14)
    assert isinstance(line_contact(100.0, 0.01, 0.01, 0.02).p_max, float)
    assert line_contact(np.full(5, 100.0), 0.01, 0.01, 0.02).p_max.shape == (5,)


def test_point_contact_broadcasts_like_scalar_calls():
    ratio = np.array([1.0, 1.3, 4.0, 50.0, 2e3])
    force = np.linspace(50.0, 600.0, 12).reshape(3, 4, 1)
    rx1, ry1, rx2, ry2, _, _ = crowned_roller(ratio)
    out = point_contact(force, rx1, ry1, rx2, ry2)
    for value in out:
        assert value.shape == (3, 4, 5)
    for i, j, k in [(0, 0, 0), (1, 2, 3), (2, 3, 4), (2, 1, 1), (0, 3, 2)]:
        single = point_contact(force[i, j, 0], rx1, ry1[k], rx2, ry2)
        for got, want in zip(out, single, strict=True):
            assert got[i, j, k] == pytest.approx(float(want), rel=1e-12)
    shapes = [(), (5,), (3, 4)]
    for shape in shapes:
        out = point_contact(np.full(shape, 100.0), 0.01, 0.3, 0.04, np.inf)
        assert np.shape(out.p_max) == shape


def test_effective_radius_and_safety_factor_broadcast():
    r1 = np.full((3, 4), 0.01)
    r2 = np.array([0.01, -0.005, np.inf, -0.02])
    radius = effective_radius(r1, r2)
    assert radius.shape == (3, 4)
    np.testing.assert_allclose(radius[0], [0.005, np.nan, 0.01, 0.02], rtol=1e-15)
    p = np.array([[0.0, 1e9, 2e9, np.nan, 5e8]])
    factor = safety_factor(p, 1.5e9)
    assert factor.shape == (1, 5)
    assert factor[0, 0] == np.inf
    np.testing.assert_allclose(factor[0, 1:3], [1.5, 0.75], rtol=1e-15)
    assert math.isnan(factor[0, 3])
    assert safety_factor(1e9, np.array([[1e9], [2e9]])).shape == (2, 1)
    assert safety_factor(1e9, 2e9) == 2.0
