"""Planar cam geometry: curvature, offsets, pressure angles, undercut and clearance checks.

Every reference is computed here independently: finite differences of point
positions, circumscribed circles of dense polygons, explicit rotations.
"""

import numpy as np
import pytest

from rotorkin.cams import planar
from rotorkin.core.errors import ParameterError
from rotorkin.drives.eccentric_cam import cam as eccentric
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.drives.rhomboid_cam import cam as rhomboid
from rotorkin.drives.rhomboid_cam import kinematics as rc

L = 0.12
LAWS = [
    (np.radians(40.0), (), ()),  # the example: first harmonic
    (np.radians(50.0), (0.08,), (0.03,)),  # first + third harmonic
    (np.radians(60.0), (-0.05, 0.02), (0.0, 0.01)),
]


def _pitch_xy(t, law):
    """Pitch point from eq. 3 written out here: rho = 2l cos(psi/2) at polar angle t."""
    psi = rc.psi_law(*law, t)[0]
    rho = L * np.cos(0.5 * psi)
    return np.stack([rho * np.cos(t), rho * np.sin(t)])


def _fd(fun, t, h=1e-4):
    """First and second central differences of fun(t) -> (2, ...)."""
    f0, fp, fm = fun(t), fun(t + h), fun(t - h)
    return (fp - fm) / (2 * h), (fp - 2 * f0 + fm) / h**2


def _circumradius(pts):
    """Signed radius of the circle through consecutive points of a CCW closed polygon."""
    a, b, c = np.roll(pts, 1, axis=1), pts, np.roll(pts, -1, axis=1)
    ab, bc, ca = b - a, c - b, a - c
    cross = ab[0] * bc[1] - ab[1] * bc[0]
    la, lb, lc = np.hypot(*ab), np.hypot(*bc), np.hypot(*ca)
    return la * lb * lc / (2.0 * cross)


# --- generic geometry ------------------------------------------------------------------------
def test_curvature_and_offset_of_a_circle():
    t = np.linspace(0, 2 * np.pi, 9)
    R = 0.05
    p = R * np.stack([np.cos(t), np.sin(t)])
    dp = R * np.stack([-np.sin(t), np.cos(t)])
    d2p = -p
    np.testing.assert_allclose(planar.signed_curvature(dp, d2p), 1 / R)
    q = planar.offset_curve(p, dp, -0.01)
    np.testing.assert_allclose(np.hypot(*q), 0.04)
    np.testing.assert_allclose(planar.offset_radius(dp, d2p, -0.01), 0.04)
    np.testing.assert_allclose(planar.outward_normal(dp), p / R, atol=1e-15)


def test_pressure_angle_generic():
    n = np.array([[1.0, 1.0, -1.0, 0.0], [0.0, 1.0, 0.0, 1.0]])
    v = np.array([[1.0, 1.0, 1.0, 1.0], [0.0, 0.0, 0.0, 0.0]])
    np.testing.assert_allclose(planar.pressure_angle(n, v), [0.0, np.pi / 4, 0.0, np.pi / 2])


@pytest.mark.parametrize("law", LAWS)
def test_pitch_curvature_against_finite_differences(law):
    t = np.linspace(0.0, 2 * np.pi, 181)
    d1, d2 = _fd(lambda x: _pitch_xy(x, law), t)
    kappa_fd = (d1[0] * d2[1] - d1[1] * d2[0]) / np.hypot(*d1) ** 3
    radius = rhomboid.pitch_radius_of_curvature(L, *law, t)
    np.testing.assert_allclose(1.0 / radius, kappa_fd, rtol=1e-5, atol=1e-4)
    p, dp, d2p = rhomboid.pitch_curve(L, *law, t)
    np.testing.assert_allclose(planar.signed_curvature(dp, d2p), kappa_fd, rtol=1e-5, atol=1e-4)


@pytest.mark.parametrize("law", LAWS)
def test_actual_profile_is_at_roller_distance(law):
    """Each profile point is r from its roller centre, along the finite-difference normal."""
    r = 0.008
    t = np.linspace(0.0, 2 * np.pi, 97)
    p = _pitch_xy(t, law)
    d1, _ = _fd(lambda x: _pitch_xy(x, law), t)
    n = np.stack([d1[1], -d1[0]]) / np.hypot(*d1)
    q = rhomboid.actual_profile(L, *law, r, t)
    np.testing.assert_allclose(q, p - r * n, atol=1e-9)


def test_resample_closed_meets_the_tolerance():
    def ellipse(t):
        return np.stack([0.08 * np.cos(t), 0.03 * np.sin(t)])

    tol = 1e-5
    t = planar.resample_closed(ellipse, 0.0, 2 * np.pi, tol)
    tn = np.append(t, 2 * np.pi)
    f = np.linspace(0, 1, 41)[1:-1, None]
    arc = ellipse(tn[:-1] + f * np.diff(tn))  # (2, 39, n)
    a, b = ellipse(tn[:-1]), ellipse(tn[1:])
    # distance of the dense arc points from the chord line
    ab = (b - a)[:, None]
    rel = arc - a[:, None]
    dev = np.abs(ab[0] * rel[1] - ab[1] * rel[0]) / np.hypot(*ab)
    assert dev.max() <= tol
    assert dev.max() > 0.2 * tol  # not wastefully fine
    np.testing.assert_allclose(
        planar.polygon_area(ellipse(t).T), np.pi * 0.08 * 0.03, rtol=1e-3
    )  # polygon inside the ellipse


def test_arc_points_sagitta():
    pts = planar.arc_points((0.0, 0.0), 0.05, 0.0, 1.0, 1e-5)
    a = np.arctan2(pts[:, 1], pts[:, 0])
    step = np.diff(a).max()
    assert 0.05 * (1 - np.cos(step / 2)) <= 1e-5 + 1e-15


def test_undercut_intervals_locate_the_sign_change():
    t = np.linspace(0, np.pi, 1001)[:-1]
    kappa = 1.0 / (0.05 + 0.02 * np.cos(2 * t))  # radius 0.03 .. 0.07
    iv = planar.undercut_intervals(t, kappa, -0.04)  # cusp where radius < 0.04
    # independent: 0.05 + 0.02 cos 2t = 0.04 at t = acos(-0.5)/2 = pi/3
    assert iv.shape == (1, 2)
    np.testing.assert_allclose(iv[0], [np.pi / 3, 2 * np.pi / 3], atol=1e-5)
    assert planar.undercut_intervals(t, kappa, -0.02).size == 0


# --- the rhomboid cam --------------------------------------------------------------------------
def _roller_xy(alpha, law):
    """Roller centres A..D from the rhombus geometry (eq. 3, 4), written out here."""
    psi = rc.psi_law(*law, alpha)[0]
    ra, rb = L * np.cos(psi / 2), L * np.sin(psi / 2)
    e = lambda t: np.stack([np.cos(t), np.sin(t)])  # noqa: E731
    A, B = ra * e(alpha), rb * e(alpha + np.pi / 2)
    return np.stack([A, B, -A, -B])


@pytest.mark.parametrize("law", LAWS)
def test_pressure_angles_against_finite_difference_geometry(law):
    alpha = np.linspace(0.0, np.pi, 73)
    h = 1e-5
    mu = rhomboid.pressure_angles(L, *law, alpha)
    assert mu.shape == (4, alpha.size)

    def rel(a):  # roller centres in the frame of the output shaft (rotated by -alpha)
        v = _roller_xy(a, law)
        c, s = np.cos(a), np.sin(a)
        return np.stack([c * v[:, 0] + s * v[:, 1], -s * v[:, 0] + c * v[:, 1]], axis=1)

    dv = (rel(alpha + h) - rel(alpha - h)) / (2 * h)  # velocity relative to the shaft
    c, s = np.cos(alpha), np.sin(alpha)
    vel = np.stack([c * dv[:, 0] - s * dv[:, 1], s * dv[:, 0] + c * dv[:, 1]], axis=1)
    pos = _roller_xy(alpha, law)
    # relative to the shaft each roller moves along its diagonal
    cross = pos[:, 0] * vel[:, 1] - pos[:, 1] * vel[:, 0]
    assert np.max(np.abs(cross)) < 1e-6 * L * L
    # contact normal: perpendicular to the pitch curve at the roller (finite differences)
    for k in range(4):
        tangent = _fd(lambda t: _pitch_xy(t, law), alpha + k * np.pi / 2)[0]
        assert np.allclose(_pitch_xy(alpha + k * np.pi / 2, law), pos[k], atol=1e-12)
        normal = np.stack([tangent[1], -tangent[0]])
        speed = np.hypot(*vel[k])
        ok = speed > 1e-4 * L
        cosang = np.abs(np.sum(normal * vel[k], axis=0)) / (np.hypot(*normal) * speed + 1e-300)
        ang = np.arccos(np.clip(cosang, 0, 1))
        np.testing.assert_allclose(np.abs(mu[k][ok]), ang[ok], atol=2e-6)
        outward = np.sum(pos[k] * vel[k], axis=0) > 0
        assert np.all((mu[k][ok] > 0) == outward[ok])


@pytest.mark.parametrize("shape", [(), (5,), (2, 3, 4)])
def test_pressure_angles_broadcast(shape):
    rng = np.random.default_rng(3)
    alpha = rng.uniform(-4, 4, size=shape)
    mu = rhomboid.pressure_angles(L, *LAWS[1], alpha)
    assert mu.shape == (4, *shape)
    flat = rhomboid.pressure_angles(L, *LAWS[1], np.ravel(alpha))
    np.testing.assert_allclose(mu.reshape(4, -1), flat, atol=1e-15)


def _dense_extremes(law, r):
    """Min convex radius and max |pressure angle| from a dense polygon (independent)."""
    t = np.linspace(0.0, 2 * np.pi, 200_001)[:-1]
    pts = _pitch_xy(t, law)
    R = _circumradius(pts)
    conv = R > 0
    i = np.argmin(np.where(conv, R, np.inf))
    d1 = _fd(lambda x: _pitch_xy(x, law), t)[0]
    normal = np.stack([d1[1], -d1[0]])
    radial = pts
    mu = np.arccos(np.abs(np.sum(normal * radial, 0)) / np.hypot(*normal) / np.hypot(*radial))
    j = np.argmax(mu)
    return R[i], t[i] % np.pi, mu[j], t[j] % np.pi


@pytest.mark.parametrize("law", LAWS)
def test_profile_check_extremes_against_dense_polygon(law):
    chk = rhomboid.profile_check(L, *law, 0.005)
    r_min, a_min, mu_max, a_mu = _dense_extremes(law, 0.005)
    np.testing.assert_allclose(chk.min_convex_radius, r_min, rtol=1e-6)
    # the same convex minimum may occur at several symmetric angles: compare the radius there
    at = rhomboid.pitch_radius_of_curvature(L, *law, chk.min_convex_radius_alpha)
    np.testing.assert_allclose(at, r_min, rtol=1e-6)
    np.testing.assert_allclose(chk.max_pressure_angle, mu_max, atol=1e-7)
    np.testing.assert_allclose(
        np.abs(rhomboid.pressure_angles(L, *law, chk.max_pressure_angle_alpha)[0]),
        mu_max,
        atol=1e-7,
    )
    assert not chk.undercut and chk.ok
    assert 0.0 <= chk.min_convex_radius_alpha < np.pi


@pytest.mark.parametrize("law", LAWS[:2])
def test_undercut_trips_at_the_right_angle(law):
    r_min, a_min, _, _ = _dense_extremes(law, 0.0)
    below = rhomboid.profile_check(L, *law, r_min * (1 - 1e-5))
    assert not below.undercut
    r = r_min * (1 + 1e-5)
    chk = rhomboid.profile_check(L, *law, r)
    assert chk.undercut and not chk.ok
    with pytest.raises(ParameterError) as info:
        rhomboid.check_profile(L, *law, r)
    err = info.value
    assert err.name == "roller_radius"
    # the named angle is one where the dense polygon has its smallest convex radius
    named = float(str(err).split("at alpha = ")[1].split(" deg")[0])
    R_named = 1 / rc.profile_curvature(L, *law, np.radians(named))
    np.testing.assert_allclose(R_named, r_min, rtol=1e-4)
    # the cusp really is there: the offset polygon runs backwards around that angle
    a0 = np.radians(named)
    t = np.linspace(a0 - 0.5, a0 + 0.5, 20001)
    big = r_min * 1.05
    q = rhomboid.actual_profile(L, *law, big, t)
    back = np.sum(np.diff(q, axis=1) * np.diff(_pitch_xy(t, law), axis=1), axis=0) < 0
    assert back.any() and not back[0] and not back[-1]
    tm = 0.5 * (t[1:] + t[:-1])
    lo, hi = tm[back].min() % np.pi, tm[back].max() % np.pi
    iv = rhomboid.profile_check(L, *law, big).extra["undercut_intervals"]
    assert np.any((np.abs(iv[:, 0] - lo) < 1e-3) & (np.abs(iv[:, 1] - hi) < 1e-3))


def test_check_profile_other_errors():
    law = LAWS[0]
    with pytest.raises(ParameterError, match="^roller_radius = "):
        rhomboid.check_profile(L, *law, -0.001)
    chk = rhomboid.check_profile(L, *law, 0.0)  # a knife edge
    assert chk.extra["roller_gap"] == L
    # a roller wider than the waist of the cam (rho(0) = 41 mm) reaches across it:
    r = 0.045
    assert rhomboid.profile_check(L, *law, r).min_clearance < 0.0
    t = np.linspace(0, 2 * np.pi, 4001)
    prof = rhomboid.actual_profile(L, *law, r, t)
    far = np.abs(np.angle(np.exp(1j * t))) > np.pi / 2  # the other side of the cam
    centre = _roller_xy(0.0, law)[0]
    assert np.min(np.hypot(*(prof[:, far] - centre[:, None]))) < r  # independent: overlap
    with pytest.raises(ParameterError, match="overlaps another flank"):
        rhomboid.check_profile(L, *law, r)


def test_profile_check_never_raises():
    for args in [(-0.1, 0.7, (), (), 0.01), (0.12, 0.7, (5.0,), (), 0.01),
                 (0.12, float("nan"), (), (), 0.01), (0.12, 0.7, (), (), 1.0)]:  # fmt: skip
        chk = rhomboid.profile_check(*args)
        assert isinstance(chk, planar.ProfileCheck)
        assert not chk.ok


def test_facing_clearance_convex_and_overlap():
    # a disc cam with a roller anywhere on it: no other flank faces the roller
    t = 2 * np.pi * np.arange(360) / 360
    p = 0.05 * np.stack([np.cos(t), np.sin(t)])
    gap, j = planar.facing_clearance(1.2 * p[:, :180], p, p / 0.05, 0.01, np.arange(180))
    assert np.all(np.isinf(gap)) and np.all(j == -1)
    # a profile with a narrow notch that a big roller cannot enter: its centre, placed on the
    # notch bottom's pitch point, overlaps the notch flanks
    rho = 0.05 - 0.02 * np.exp(-((np.angle(np.exp(1j * t)) / 0.12) ** 2))
    prof = rho * np.stack([np.cos(t), np.sin(t)])
    d = np.gradient(prof, axis=1)
    n = np.stack([d[1], -d[0]]) / np.hypot(*d)
    r = 0.012
    centres = prof + r * n
    gap, j = planar.facing_clearance(centres, prof, n, r, np.arange(360))
    # independent: the deepest overlap of any roller disc with the profile samples
    dist = np.hypot(*(centres[:, :, None] - prof[:, None, :])) - r
    assert dist.min() < -1e-3
    np.testing.assert_allclose(gap.min(), dist.min(), rtol=1e-9)


def test_rhomboid_example_clearance_and_gap():
    chk = rhomboid.profile_check(L, *LAWS[0], 0.01)
    assert chk.min_clearance > 0.0
    np.testing.assert_allclose(chk.extra["roller_gap"], L - 0.02)
    # the actual profile's nearest point to O: rho_min - r (at the waist, alpha = 0)
    np.testing.assert_allclose(chk.profile_min_radius, L * np.cos(np.radians(70)) - 0.01,
                               rtol=1e-9)  # fmt: skip


# --- the eccentric discs -------------------------------------------------------------------------
@pytest.mark.parametrize("follower,r", [("knife_edge", 0.0), ("roller", 0.01), ("flat", 0.0)])
def test_eccentric_pressure_angles_by_geometry(follower, r):
    params = ec.EccentricCam(0.08, 0.04, follower, r)
    beta = np.linspace(0, 2 * np.pi, 37)
    mu = eccentric.pressure_angles(params, beta)
    centre = eccentric.disc_centres(params, beta)  # (2, 2, n)
    foll = eccentric.follower_points(params, beta)
    for k in (0, 1):
        # independent: the follower point's distance from the disc centre is the contact radius
        if follower != "flat":
            np.testing.assert_allclose(np.hypot(*(foll[k] - centre[k])), params.contact_radius)
            normal = foll[k] - centre[k]
            expected = np.arctan2(normal[1], normal[0])  # the follower moves along x
            np.testing.assert_allclose(np.abs(mu[k]), np.abs(expected), atol=1e-12)
            # the follower's velocity (finite differences) is along its axis
            h = 1e-6
            v = (eccentric.follower_points(params, beta + h)[k]
                 - eccentric.follower_points(params, beta - h)[k])  # fmt: skip
            assert np.all(np.abs(v[1]) < 1e-12)
        else:
            assert np.all(mu[k] == 0.0)
    np.testing.assert_allclose(mu[1], -mu[0])
    chk = eccentric.profile_check(params)
    assert chk.ok
    if follower != "flat":
        np.testing.assert_allclose(chk.max_pressure_angle, np.max(np.abs(mu)), atol=1e-12)


@pytest.mark.parametrize("law", LAWS)
def test_roller_radius_limit(law):
    """The largest roller that passes check_profile; the message states it (rounded down)."""
    limit, reason = rhomboid.roller_radius_limit(L, *law)
    chk0 = rhomboid.profile_check(L, *law, 0.0)
    if reason == "clearance":
        # independent: the rollers at the waist (rho_min) meet at the centre when r = rho_min
        t = np.linspace(0, np.pi, 200_001)
        rho_min = np.min(np.hypot(*_pitch_xy(t, law)))
        assert limit == pytest.approx(rho_min, rel=1e-5)
    else:
        assert reason == "undercut" and limit == chk0.min_convex_radius
    assert limit <= chk0.min_convex_radius and limit <= L / 2
    rhomboid.check_profile(L, *law, limit * (1 - 1e-6))  # passes
    with pytest.raises(ParameterError) as info:
        rhomboid.check_profile(L, *law, limit * (1 + 1e-6))
    stated = float(str(info.value).split("roller_radius < ")[1].split(" mm")[0])
    assert limit * 1e3 - 0.01 < stated <= limit * 1e3
    with pytest.raises(ParameterError) as info:  # any failing roller states the same range
        rhomboid.check_profile(L, *law, 0.059)
    assert f"roller_radius < {stated:.4g} mm" in str(info.value)
