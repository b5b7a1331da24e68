"""Tests of the non-circular gear drive against independent numerical models.

* Rolling: the two pitch curves taken as plane curves (points only), placed in mesh, the
  driven angle found by equal rolled arc lengths (quadrature + root finding); the contact
  must then lie on the line of centres, the curves must touch tangentially, and the angle
  must be the closed form's.
* The closure root, the continuous closed form and its inverse against quadrature and
  root finding on the defining integrals.
* Derivatives against central differences of the level below.
* Convexity against the curvature of the pitch curves by finite differences of points.
* Broadcasting and periodicity.

Designs are drawn from seeded generators, so every run sees the same ones.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from rotorkin.core.errors import ParameterError
from rotorkin.core.motion import Motion
from rotorkin.drives.noncircular_gears import kinematics as ncg

G = ncg.NoncircularGears


def _random_design(rng, lobes=(1, 5), rotor_lobes=(1, 5), fill=0.95):
    """An admissible design: lobes, eccentricity up to ``fill`` of the convexity limit."""
    n = int(rng.integers(*lobes))
    m = int(rng.integers(*rotor_lobes))
    e_max = min(float(ncg.eccentricity_limit(n, m)), 0.9)
    return G(
        lobes=n,
        rotor_lobes=m,
        eccentricity=float(rng.uniform(0.02, fill) * e_max),
        centre_distance=float(rng.uniform(0.01, 2.0)),
        phase=float(rng.uniform(-3.0, 3.0)),
    )


def _designs(seed, count, **kw):
    rng = np.random.default_rng(seed)
    return [_random_design(rng, **kw) for _ in range(count)]


def _hypot(g, which, angle):
    return float(np.hypot(*ncg.pitch_curve(g, which, angle)))


def _tangent(g, which, angle, h=1e-4):
    """d(x, y)/d(angle) of a pitch curve's points, 4th-order central difference."""

    def P(v):
        return np.array(ncg.pitch_curve(g, which, v), dtype=float)

    return (-P(angle + 2 * h) + 8 * P(angle + h) - 8 * P(angle - h) + P(angle - 2 * h)) / (12 * h)


def _second(g, which, angle, h=1e-3):
    """d2(x, y)/d(angle)^2 of a pitch curve's points, 4th-order central difference."""

    def P(v):
        return np.array(ncg.pitch_curve(g, which, v), dtype=float)

    return (
        -P(angle + 2 * h) + 16 * P(angle + h) - 30 * P(angle) + 16 * P(angle - h) - P(angle - 2 * h)
    ) / (12 * h * h)


def _fd_curvature(g, which, angle):
    d1, d2 = _tangent(g, which, angle, h=1e-3), _second(g, which, angle)
    return (d1[0] * d2[1] - d1[1] * d2[0]) / np.hypot(*d1) ** 3


def _arc(g, which, angle):
    """Arc length of a pitch curve from polar angle 0 to ``angle`` (signed)."""
    return quad(
        lambda v: np.hypot(*_tangent(g, which, v)), 0.0, angle, epsabs=1e-15, epsrel=1e-13,
        limit=200,
    )[0]  # fmt: skip


def _rot(angle, v):
    c, s = np.cos(angle), np.sin(angle)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def _placed(g, which, angle, turned):
    """A curve point (own polar angle ``angle``) and tangent in the plane of the mesh.

    Driving centre at the origin, turning counter-clockwise by ``turned``; driven centre at
    (a, 0), turning clockwise by ``turned``. Own angles run against each gear's sense of
    rotation, so the driving curve is mirrored and the driven one rotated by pi.
    """
    P = np.array(ncg.pitch_curve(g, which, angle), dtype=float)
    T = _tangent(g, which, angle)
    if which == "driving":
        mirror = np.array([1.0, -1.0])
        return _rot(turned, P * mirror), _rot(turned, T * mirror)
    a = g.centre_distance
    return np.array([a, 0.0]) + _rot(np.pi - turned, P), _rot(np.pi - turned, T)


# --------------------------------------------------------------------------------------------
# an independent rolling model
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("seed", range(6))
def test_rolling_without_slip_matches_closed_form(seed):
    rng = np.random.default_rng(100 + seed)
    g = _random_design(rng)
    a = g.centre_distance
    radii = [_hypot(g, "driven", v) for v in np.linspace(0.0, 2 * np.pi, 721)]
    r_min = 0.9 * min(radii)
    for phi1 in (*rng.uniform(-4.0, 4.0, 2), 2 * np.pi / g.lobes + 0.3):
        s1 = _arc(g, "driving", phi1)
        bound = 1.1 * abs(s1) / r_min  # arc >= r_min * angle
        lo, hi = (0.0, bound) if s1 > 0 else (-bound, 0.0)
        phi2 = brentq(lambda v, s1=s1: _arc(g, "driven", v) - s1, lo, hi, xtol=1e-14, rtol=1e-15)
        assert phi2 == pytest.approx(float(ncg.driven_angle(g, phi1)[0]), abs=1e-9)
        # (a) both contact points on the line of centres, at the same point: r1 + r2 = a
        P1, T1 = _placed(g, "driving", phi1, phi1)
        P2, T2 = _placed(g, "driven", phi2, phi2)
        assert abs(P1[1]) < 1e-12 * a and abs(P2[1]) < 1e-12 * a
        assert P1[0] == pytest.approx(P2[0], abs=1e-11 * a)
        assert _hypot(g, "driving", phi1) + _hypot(g, "driven", phi2) == pytest.approx(a, rel=1e-12)
        # the curves touch: parallel tangents
        cross = (T1[0] * T2[1] - T1[1] * T2[0]) / (np.hypot(*T1) * np.hypot(*T2))
        assert abs(cross) < 1e-9


@pytest.mark.parametrize("seed", range(4))
def test_closure_by_quadrature(seed):
    for g in _designs(200 + seed, 5):
        n, m, a = g.lobes, g.rotor_lobes, g.centre_distance
        lobe = 2 * np.pi / n

        def rate(v, g=g, a=a):
            r1 = _hypot(g, "driving", v)
            return r1 / (a - r1)

        turned = quad(rate, 0.0, lobe, epsabs=1e-14, epsrel=1e-13, limit=200)[0]
        assert turned == pytest.approx(2 * np.pi / m, rel=1e-11)
        assert float(ncg.driven_angle(g, lobe)[0]) == pytest.approx(2 * np.pi / m, rel=1e-13)
        # the driven pitch curve closes lobe by lobe and is mirror symmetric
        v = np.linspace(-7.0, 7.0, 29)
        r = ncg.pitch_radius(g, "driven", v)
        np.testing.assert_allclose(ncg.pitch_radius(g, "driven", v + 2 * np.pi / m), r, rtol=1e-13)
        np.testing.assert_allclose(ncg.pitch_radius(g, "driven", -v), r, rtol=1e-13)
        phi2 = ncg.driven_angle(g, v)[0]
        np.testing.assert_allclose(
            ncg.pitch_radius(g, "driven", phi2), a - ncg.pitch_radius(g, "driving", v), rtol=1e-12
        )


def _p_by_root(n, m, e, a):
    """The closure root found by bracketing: ``p/sqrt((a - p)^2 - (a e)^2) = n/m``."""
    f = lambda p: p / np.sqrt((a - p) ** 2 - (a * e) ** 2) - n / m  # noqa: E731
    return brentq(f, 1e-15 * a, a * (1 - e) * (1 - 1e-15), xtol=1e-16 * a, rtol=1e-15)


@pytest.mark.parametrize("seed", range(3))
def test_pitch_parameter_is_the_closure_root(seed):
    for g in _designs(300 + seed, 8):
        n, m, e, a = g.lobes, g.rotor_lobes, g.eccentricity, g.centre_distance
        p = float(ncg.pitch_parameter(g))
        assert p == pytest.approx(_p_by_root(n, m, e, a), rel=1e-12)
        assert a - p / (1 - e) > 0  # a positive driven radius everywhere


@pytest.mark.parametrize("n", [1, 2, 3, 5])
def test_pitch_parameter_equal_lobes(n):
    e = np.linspace(0.0, 0.99 * float(ncg.eccentricity_limit(n, n)), 7)
    g = G(lobes=n, rotor_lobes=n, eccentricity=e, centre_distance=0.37)
    np.testing.assert_allclose(ncg.pitch_parameter(g), 0.37 * (1 - e**2) / 2, rtol=1e-14)


@pytest.mark.parametrize("seed", range(3))
def test_closed_form_is_the_integral_on_many_turns(seed):
    """phi2 = (p/n) int_0^t dv/(B - C cos v), t = n phi1, beyond (-pi, pi) too."""
    for g in _designs(400 + seed, 4):
        n, e, a = g.lobes, g.eccentricity, g.centre_distance
        p = float(ncg.pitch_parameter(g))
        B, C = a - p, a * e
        for phi1 in np.linspace(-11.0, 13.0, 9):
            t = n * phi1
            num = quad(lambda v, B=B, C=C: 1.0 / (B - C * np.cos(v)), 0.0, t, limit=400,
                       epsabs=1e-14, epsrel=1e-13)[0]  # fmt: skip
            assert float(ncg.driven_angle(g, phi1)[0]) == pytest.approx(p / n * num, rel=1e-11)


@pytest.mark.parametrize("seed", range(3))
def test_continuous_and_inverse(seed):
    for g in _designs(500 + seed, 4):
        x = np.linspace(-40.0, 40.0, 80001)
        phi2, R = ncg.driven_angle(g, x)[:2]
        step = np.diff(phi2)
        lo, hi = ncg.ratio_extremes(g)
        dx = x[1] - x[0]
        assert np.all(step > 0.999 * lo * dx) and np.all(step < 1.001 * hi * dx)  # no jumps
        np.testing.assert_allclose(ncg.driving_angle(g, phi2), x, rtol=0, atol=1e-12)
        # the inverse found by root finding on the closed form
        for y in (-5.3, 0.4, 2.9, 8.1):
            c, w = y * g.rotor_lobes / g.lobes, 2 * np.pi / g.lobes + 1.0  # |phi2 - k phi1| < pi/m
            root = brentq(lambda v, y=y, g=g: float(ncg.driven_angle(g, v)[0]) - y, c - w, c + w,
                          xtol=1e-15)  # fmt: skip
            assert float(ncg.driving_angle(g, y)) == pytest.approx(root, abs=1e-12)
        # odd in phi1
        np.testing.assert_allclose(ncg.driven_angle(g, -x[::97])[0], -phi2[::97], atol=1e-12)


# --------------------------------------------------------------------------------------------
# derivatives
# --------------------------------------------------------------------------------------------
def _check_levels(levels, fd_levels, h):
    """``levels[j]`` against the central difference of ``fd_levels[j - 1]``."""
    for j in (1, 2, 3):
        fd = (fd_levels[+1][j - 1] - fd_levels[-1][j - 1]) / (2 * h)
        scale = np.max(np.abs(levels[j])) + 1e-300
        np.testing.assert_allclose(levels[j], fd, rtol=0, atol=1e-6 * scale)


@pytest.mark.parametrize("seed", range(4))
def test_driven_angle_and_ratio_derivatives(seed):
    h = 1e-4
    x = np.linspace(-7.0, 7.0, 301)
    for g in _designs(600 + seed, 4):
        _check_levels(
            ncg.driven_angle(g, x),
            {s: ncg.driven_angle(g, x + s * h) for s in (-1, 1)},
            h,
        )
        R = ncg.ratio(g, x)
        np.testing.assert_array_equal(R[:3], ncg.driven_angle(g, x)[1:])
        _check_levels(R, {s: ncg.ratio(g, x + s * h) for s in (-1, 1)}, h)


@pytest.mark.parametrize("seed", range(4))
def test_motion_derivatives(seed):
    h = 1e-4
    theta = np.linspace(-7.0, 7.0, 301)
    for g in _designs(700 + seed, 4):
        mo = ncg.motion(g, theta)
        levels = (mo.q, mo.dq, mo.d2q, mo.d3q)
        shifted = {}
        for s in (-1, 1):
            ms = ncg.motion(g, theta + s * h)
            shifted[s] = (ms.q, ms.dq, ms.d2q, ms.d3q)
        _check_levels(levels, shifted, h)


# --------------------------------------------------------------------------------------------
# closed forms
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("seed", range(3))
def test_ratio_extremes(seed):
    for g in _designs(800 + seed, 6):
        lo, hi = ncg.ratio_extremes(g)
        R = ncg.ratio(g, np.linspace(0.0, 2 * np.pi, 100001))[0]
        assert float(lo) == pytest.approx(R.min(), rel=1e-12)
        assert float(hi) == pytest.approx(R.max(), rel=1e-12)
        n, m, e, a = g.lobes, g.rotor_lobes, g.eccentricity, g.centre_distance
        p = _p_by_root(n, m, e, a)
        assert float(lo) == pytest.approx(p / (a - p + a * e), rel=1e-12)
        assert float(hi) == pytest.approx(p / (a - p - a * e), rel=1e-12)


def test_ratio_extremes_equal_lobes():
    e = np.linspace(0.0, 0.33, 12)
    lo, hi = ncg.ratio_extremes(G(lobes=2, rotor_lobes=2, eccentricity=e))
    np.testing.assert_allclose(hi, (1 + e) / (1 - e), rtol=1e-14)
    np.testing.assert_allclose(lo, (1 - e) / (1 + e), rtol=1e-14)


@pytest.mark.parametrize("m", [1, 2, 3])
def test_one_lobe_is_an_ellipse_about_a_focus(m):
    a, e = 0.23, 0.3
    g = G(lobes=1, rotor_lobes=m, eccentricity=e, centre_distance=a)
    A = float(ncg.pitch_parameter(g)) / (1 - e**2)  # semi-major axis
    if m == 1:
        assert A == pytest.approx(a / 2, rel=1e-14)
    x, y = ncg.pitch_curve(g, "driving", np.linspace(0.0, 2 * np.pi, 37))
    other = (2 * A * e, 0.0)  # the far focus; the gear turns about the one at the origin
    np.testing.assert_allclose(np.hypot(x, y) + np.hypot(x - other[0], y - other[1]), 2 * A,
                               rtol=1e-14)  # fmt: skip


@pytest.mark.parametrize("seed", range(3))
def test_relative_angle_extremes_against_sampling(seed):
    for g in _designs(900 + seed, 5):
        rel = ncg.motion(g, np.linspace(0.0, ncg.period(g), 200001)).relative[0]
        lo, hi = ncg.relative_angle_extremes(g)
        assert float(lo) == pytest.approx(rel.min(), abs=1e-9)
        assert float(hi) == pytest.approx(rel.max(), abs=1e-9)
        for th in ncg.equal_speed_angles(g):
            dq = ncg.motion(g, th).dq
            assert float(dq[0]) == pytest.approx(float(dq[1]), rel=1e-13)


def test_default_phase_gives_the_largest_swing():
    for n, m, e in [(2, 2, 0.3), (1, 2, 0.5), (3, 1, 0.1), (2, 3, 0.15)]:
        g = G(lobes=n, rotor_lobes=m, eccentricity=e)
        assert g.phase is None
        lo, hi = ncg.relative_angle_extremes(g)
        sig = np.linspace(0.0, 2 * np.pi / n, 721)
        los, his = ncg.relative_angle_extremes(G(lobes=n, rotor_lobes=m, eccentricity=e, phase=sig))
        assert float(hi - lo) == pytest.approx(np.max(his - los), rel=1e-12)
        assert float(hi - lo) > 0
        explicit = G(lobes=n, rotor_lobes=m, eccentricity=e, phase=np.pi / n)
        np.testing.assert_array_equal(ncg.motion(g, sig).q, ncg.motion(explicit, sig).q)


# --------------------------------------------------------------------------------------------
# convexity and admissibility
# --------------------------------------------------------------------------------------------
def _refused(**fields):
    with pytest.raises(ParameterError) as info:
        G(**fields)
    text = str(info.value)
    assert "\n" not in text
    return info.value, text


@pytest.mark.parametrize(
    ("n", "m", "limit"),
    [
        (2, 2, 1 / 3),
        (3, 3, 1 / 8),
        (4, 4, 1 / 15),
        (4, 1, 1 / 15),
        (5, 2, 1 / 24),
        (1, 2, 1 / np.sqrt(3)),  # the driven curve binds where m > n
        (1, 4, 1 / np.sqrt(15)),
        (2, 3, 1 / np.sqrt(29)),
        (3, 5, 1 / np.sqrt(208)),
    ],
)
def test_convexity_limit(n, m, limit):
    assert float(ncg.eccentricity_limit(n, m)) == pytest.approx(limit, rel=1e-14)
    which = "driving" if m <= n else "driven"
    other = "driven" if m <= n else "driving"
    below, above = limit * (1 - 1e-9), limit * (1 + 1e-9)
    g = G(lobes=n, rotor_lobes=m, eccentricity=below)
    assert ncg.concave_intervals(g, "driving") == []
    assert ncg.concave_intervals(g, "driven") == []
    err, text = _refused(lobes=n, rotor_lobes=m, eccentricity=above)
    assert err.name == "drive.eccentricity"
    assert text.startswith(f"drive.eccentricity = {above:g} is not admissible: 0 <= eccentricity")
    assert which in text
    bad = G.unchecked(lobes=n, rotor_lobes=m, eccentricity=above)
    assert len(ncg.concave_intervals(bad, which)) == (n if which == "driving" else m)
    if m != n:
        assert ncg.concave_intervals(bad, other) == []
    # independent: the sign of the curvature of the points, where concavity first appears
    worst = np.pi / n if which == "driving" else 0.0
    for e, sign in ((limit * (1 - 1e-3), 1), (limit * (1 + 1e-3), -1)):
        k = _fd_curvature(G.unchecked(lobes=n, rotor_lobes=m, eccentricity=e), which, worst)
        assert np.sign(k) == sign


def test_message_example():
    err, text = _refused(lobes=4, rotor_lobes=4, eccentricity=0.2)
    assert text == (
        "drive.eccentricity = 0.2 is not admissible: 0 <= eccentricity <= 0.06666 (a 4-lobed "
        "driving pitch curve is convex only for e <= 1/(n^2-1); external gears need convex "
        "pitch curves)"
    )


@pytest.mark.parametrize(
    ("n", "m", "e"),
    [(3, 3, 0.2), (2, 2, 0.5), (4, 2, 0.1), (1, 2, 0.7), (2, 3, 0.3), (3, 5, 0.1), (1, 3, 0.5)],
)
@pytest.mark.parametrize("which", ["driving", "driven"])
def test_concave_intervals_against_sampled_and_points(n, m, e, which):
    g = G.unchecked(lobes=n, rotor_lobes=m, eccentricity=e, centre_distance=0.2)
    exact = ncg.concave_intervals(g, which)
    sampled = ncg.concave_intervals(g, which, samples=200000)
    assert len(exact) == len(sampled)
    np.testing.assert_allclose(np.array(exact).reshape(-1), np.array(sampled).reshape(-1),
                               atol=1e-8)  # fmt: skip
    refused = int(ncg.violation(n, m, e, 0.2)) != 0
    assert refused
    # the curvature of the points, independent of the closed forms
    v = np.linspace(0.0, 2 * np.pi, 97)
    kfd = np.array([_fd_curvature(g, which, x) for x in v])
    np.testing.assert_allclose(ncg.curvature(g, which, v), kfd, rtol=1e-7, atol=1e-7 / 0.2)
    for lo, hi in exact:
        mid = 0.5 * (lo + hi)
        assert _fd_curvature(g, which, mid) < 0
        assert _fd_curvature(g, which, lo - 0.01) > 0 and _fd_curvature(g, which, hi + 0.01) > 0


@pytest.mark.parametrize("seed", range(2))
def test_curvature_of_admissible_designs(seed):
    for g in _designs(1000 + seed, 5, fill=1.0):
        for which in ncg.WHICH:
            v = np.linspace(-3.0, 3.0, 41)
            k = ncg.curvature(g, which, v)
            kfd = np.array([_fd_curvature(g, which, x) for x in v])
            np.testing.assert_allclose(k, kfd, rtol=1e-7, atol=1e-9 / g.centre_distance)
            assert np.all(k > 0)
            assert ncg.concave_intervals(g, which) == []
            assert ncg.concave_intervals(g, which, samples=4096) == []


@pytest.mark.parametrize(
    ("fields", "name", "value"),
    [
        ({"lobes": 0}, "drive.lobes", "0"),
        ({"lobes": 2.5}, "drive.lobes", "2.5"),
        ({"lobes": 13}, "drive.lobes", "13"),
        ({"rotor_lobes": -1}, "drive.rotor_lobes", "-1"),
        ({"eccentricity": -0.1}, "drive.eccentricity", "-0.1"),
        ({"eccentricity": 1.0, "lobes": 1, "rotor_lobes": 1}, "drive.eccentricity", "1"),
        ({"eccentricity": np.nan}, "drive.eccentricity", "nan"),
        ({"centre_distance": 0.0005}, "drive.centre_distance", "0.0005 m"),
        ({"centre_distance": 11.0}, "drive.centre_distance", "11 m"),
        ({"phase": np.inf}, "drive.phase", "inf rad"),
        ({"lobes": "two"}, "drive.lobes", "'two'"),
    ],
)
def test_refused_fields(fields, name, value):
    err, text = _refused(**fields)
    assert err.name == name
    assert text.startswith(f"{name} = {value} is not admissible: ")


def test_violation_is_vectorised_and_matches_the_dataclass():
    n = np.array([1, 2, 2, 4, 0, 3, 1, 2])[:, None]
    e = np.array([0.0, 0.1, 0.3, 0.34, 0.6, 1.2])
    code = ncg.violation(n, 2, e, np.array([[0.1]] * 7 + [[0.0001]]), None)
    assert code.shape == (8, 6)
    for i in range(8):
        for j in range(6):
            k = int(code[i, j])
            a = 0.1 if i < 7 else 0.0001
            if k == 0:
                G(lobes=int(n[i, 0]), rotor_lobes=2, eccentricity=float(e[j]), centre_distance=a)
            else:
                err, _ = _refused(lobes=int(n[i, 0]), rotor_lobes=2, eccentricity=float(e[j]),
                                  centre_distance=a)  # fmt: skip
                assert err.name == "drive." + ncg.CHECKS[k - 1]
    assert set(np.unique(code)) >= {0, 1, 3, 4, 7, 8}


def test_which_is_checked():
    with pytest.raises(ParameterError, match="which"):
        ncg.pitch_radius(G(), "rotor", 0.0)


# --------------------------------------------------------------------------------------------
# broadcasting and periodicity
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("shape", [(), (5,), (3, 4)])
def test_theta_shapes(shape):
    g = G(lobes=3, rotor_lobes=2, eccentricity=0.1, centre_distance=0.2)
    theta = np.random.default_rng(1).uniform(-9, 9, shape)
    mo = ncg.motion(g, theta)
    assert isinstance(mo, Motion)
    assert mo.members == ("rotor 1", "rotor 2") and mo.unit == "rad"
    assert mo.theta.shape == shape
    for arr in (mo.q, mo.dq, mo.d2q, mo.d3q):
        assert arr.shape == (2, *shape)
    for f in (ncg.driven_angle, ncg.ratio):
        assert all(np.shape(v) == shape for v in f(g, theta))
    for which in ncg.WHICH:
        assert np.shape(ncg.pitch_radius(g, which, theta)) == shape
        assert np.shape(ncg.curvature(g, which, theta)) == shape
        assert all(np.shape(v) == shape for v in ncg.pitch_curve(g, which, theta))
    flat = theta.reshape(-1)
    for i, t in enumerate(flat):
        one = ncg.motion(g, float(t))
        for arr, ref in zip((mo.q, mo.dq, mo.d2q, mo.d3q), (one.q, one.dq, one.d2q, one.d3q),
                            strict=True):  # fmt: skip
            np.testing.assert_array_equal(arr.reshape(2, -1)[:, i], ref)


def test_parameter_arrays():
    rng = np.random.default_rng(7)
    designs = _designs(1100, 6)
    fields = ("lobes", "rotor_lobes", "eccentricity", "centre_distance", "phase")
    arrays = {f: np.array([getattr(d, f) for d in designs])[:, None] for f in fields}
    batch = G(**arrays)
    theta = rng.uniform(-8.0, 8.0, 4)
    mo = ncg.motion(batch, theta)
    assert mo.q.shape == (2, 6, 4) and mo.theta.shape == (6, 4)
    phi = ncg.driven_angle(batch, theta)
    lo, hi = ncg.relative_angle_extremes(batch)
    rlo, rhi = ncg.ratio_extremes(batch)
    assert lo.shape == (6, 1) and rlo.shape == (6, 1)
    assert np.shape(ncg.period(batch)) == (6, 1)
    np.testing.assert_array_equal(ncg.violation(*arrays.values()), 0)
    for i, d in enumerate(designs):
        one = ncg.motion(d, theta)
        np.testing.assert_allclose(mo.q[:, i], one.q, rtol=1e-15, atol=1e-15)
        np.testing.assert_allclose(mo.d3q[:, i], one.d3q, rtol=1e-15, atol=1e-15)
        np.testing.assert_allclose(phi[2][i], ncg.driven_angle(d, theta)[2], rtol=1e-15)
        assert float(lo[i, 0]) == pytest.approx(float(ncg.relative_angle_extremes(d)[0]), rel=1e-15)
        assert float(hi[i, 0]) == pytest.approx(float(ncg.relative_angle_extremes(d)[1]), rel=1e-15)
        assert float(rhi[i, 0]) == float(ncg.ratio_extremes(d)[1])
        assert float(ncg.pitch_parameter(batch)[i, 0]) == float(ncg.pitch_parameter(d))
        assert float(ncg.period(batch)[i, 0]) == ncg.period(d)
        for which in ncg.WHICH:
            np.testing.assert_allclose(
                ncg.curvature(batch, which, theta)[i], ncg.curvature(d, which, theta), rtol=1e-15
            )


def test_default_phase_with_parameter_arrays():
    n = np.array([1, 2, 3, 4])
    batch = G(lobes=n, rotor_lobes=3, eccentricity=0.02)
    theta = np.linspace(-1.0, 1.0, 5)[:, None]
    mo = ncg.motion(batch, theta)
    assert mo.q.shape == (2, 5, 4)
    for i, k in enumerate(n):
        one = ncg.motion(G(lobes=int(k), rotor_lobes=3, eccentricity=0.02), theta[:, 0])
        np.testing.assert_allclose(mo.q[:, :, i], one.q, rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(ncg.equal_speed_angles(batch)[1], np.pi / (2 * n), rtol=1e-15)


@pytest.mark.parametrize("seed", range(3))
def test_periodicity(seed):
    theta = np.linspace(-5.0, 5.0, 41)
    for g in _designs(1200 + seed, 4):
        n, m = g.lobes, g.rotor_lobes
        T = ncg.period(g)
        assert T == pytest.approx(2 * np.pi / n)
        now, later = ncg.motion(g, theta), ncg.motion(g, theta + T)
        np.testing.assert_allclose(later.q - now.q, 2 * np.pi / m, rtol=1e-12)
        for a, b in ((now.dq, later.dq), (now.d2q, later.d2q), (now.d3q, later.d3q)):
            np.testing.assert_allclose(b, a, rtol=1e-11, atol=1e-11 * np.abs(a).max())
        np.testing.assert_allclose(later.relative[0], now.relative[0], atol=1e-12)
        turn = ncg.motion(g, theta + 2 * np.pi)
        np.testing.assert_allclose(turn.q - now.q, 2 * np.pi * n / m, rtol=1e-12)
        # q increases with theta, rotor 2 is rotor 1 shifted by the phase
        assert np.all(now.dq > 0)
        s = g.phase
        np.testing.assert_allclose(now.q[1], ncg.motion(g, theta + s).q[0] - ncg.motion(g, s).q[0],
                                   atol=1e-13)  # fmt: skip
        np.testing.assert_array_equal(ncg.motion(g, 0.0).q, 0.0)
