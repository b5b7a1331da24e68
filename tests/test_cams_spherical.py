"""Spherical cam of the wobble drive: every result against geometry built here.

The reference geometry is computed with the paper's rotation matrices (eq. 2-5, 9-10)
written out explicitly, derivatives by central finite differences, curvature from the
circle through three close points, crossings by brute-force distance search.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.core.errors import ParameterError
from rotorkin.drives.wobble_cam import cam as sph
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.io.config import load_config

PHI, ALPHA, R = np.radians(45.0), np.radians(90.0), 0.06


def _rot_x(a):
    """Paper's A_theta form (eq. 2, 4, 9), stacked over a's shape: (..., 3, 3)."""
    a = np.asarray(a, dtype=float)
    c, s, z, o = np.cos(a), np.sin(a), np.zeros_like(a), np.ones_like(a)
    return np.stack(
        [np.stack([o, z, z], -1), np.stack([z, c, s], -1), np.stack([z, -s, c], -1)], -2
    )


def _rot_y(a):
    """Paper's A_phi (eq. 3)."""
    a = np.asarray(a, dtype=float)
    c, s, z, o = np.cos(a), np.sin(a), np.zeros_like(a), np.ones_like(a)
    return np.stack(
        [np.stack([c, z, s], -1), np.stack([z, o, z], -1), np.stack([-s, z, c], -1)], -2
    )


def _spin(theta, n=-2.0, a=(), b=()):
    v = n * theta
    for k, x in enumerate(a, 1):
        v = v + x * np.cos(k * theta)
    for k, x in enumerate(b, 1):
        v = v + x * np.sin(k * theta)
    return v


class Explicit:
    """Roller centres and grooves from the explicit matrices (independent of the library)."""

    def __init__(self, phi=PHI, alpha=ALPHA, n=-2.0, r=R, a=(), b=()):
        self.phi, self.alpha, self.n, self.r, self.a, self.b = phi, alpha, n, r, a, b

    def r3(self, roller):
        c = (-self.alpha / 2, np.pi - self.alpha / 2, self.alpha / 2, np.pi + self.alpha / 2)
        c = c[roller]
        return self.r * np.array([0.0, np.sin(c), np.cos(c)])

    def shaft(self, theta, roller):
        """Roller centre in the shaft frame x1y1z1: A_phi A_varphi r|3, (..., 3)."""
        v = _spin(np.asarray(theta, float), self.n, self.a, self.b)
        return _rot_y(self.phi) @ _rot_x(v) @ self.r3(roller)

    def fixed(self, theta, roller):
        return _rot_x(theta) @ self.shaft(theta, roller)[..., None]

    def groove(self, theta, roller):
        """Cam frame: A_psi^T r|0 with psi = -theta (eq. 10), shape (..., 3)."""
        theta = np.asarray(theta, float)
        p0 = _rot_x(theta) @ self.shaft(theta, roller)[..., None]
        return (np.swapaxes(_rot_x(-theta), -1, -2) @ p0)[..., 0]

    def d(self, fun, theta, roller, h=1e-5):
        return (fun(theta + h, roller) - fun(theta - h, roller)) / (2 * h)


@pytest.fixture(scope="module")
def example():
    cfg, _, _ = load_config(None, "wobble-cam-engine", ['cam.roller_radius="4 mm"'])
    return sph.from_config(cfg)


# --------------------------------------------------------------------------------------------
def test_cam_validation_names_the_key():
    cam = sph.SphericalCam(0.06)
    assert (cam.inner_radius, cam.outer_radius, cam.bottom_radius) == pytest.approx(
        (0.054, 0.066, 0.062)
    )
    cases = [
        ({"shell_thickness": 0.13}, "cam.shell_thickness"),
        ({"shell_thickness": 0.0}, "cam.shell_thickness"),
        ({"groove_depth": 0.012}, "cam.groove_depth"),  # through the shell
        ({"groove_depth": 0.005}, "cam.groove_depth"),  # does not reach the roller centres
        ({"roller_radius": 0.0}, "cam.roller_radius"),
        ({"roller_radius": 0.055}, "cam.roller_radius"),
        ({"roller_radius": float("nan")}, "cam.roller_radius"),
    ]
    for kwargs, key in cases:
        with pytest.raises(ParameterError) as err:
            sph.SphericalCam(0.06, **kwargs)
        # the dataclass names its field; from_config names the config key
        assert err.value.name == key.split(".")[1] and "mm" in str(err.value)
        assert sph.config_key(err.value.name) == key
    with pytest.raises(ParameterError, match="^sphere_radius"):
        sph.SphericalCam(-1.0)


def test_from_config_and_errors(example):
    drive, cam = example
    assert drive.plate_tilt == pytest.approx(PHI) and cam.roller_radius == pytest.approx(0.004)
    cfg, _, _ = load_config(None, "wobble-cam-engine", ['cam.groove_depth="13 mm"'])
    with pytest.raises(ParameterError, match=r"^cam\.groove_depth = 13 mm"):
        sph.from_config(cfg)
    cfg, _, _ = load_config(None, "wobble-cam-engine", ['drive.plate_tilt="70 deg"'])
    with pytest.raises(ParameterError, match=r"^drive\.plate_tilt"):
        sph.from_config(cfg)


@pytest.mark.parametrize("spin", [((), ()), ((0.05, 0.02), (0.0, 0.03))])
def test_groove_and_derivatives_against_matrices(spin):
    a, b = spin
    drive = wc.WobbleCam(PHI, ALPHA, -2.0, R, spin_a=a, spin_b=b)
    ex = Explicit(a=a, b=b)
    theta = np.random.default_rng(1).uniform(0, 2 * np.pi, 50)
    g, d1, d2 = sph.groove_derivatives(drive, theta)
    h = 1e-4
    for i in range(4):
        ref = ex.groove(theta, i)
        assert np.allclose(g[i].T, ref, atol=1e-15)
        fd1 = (ex.groove(theta + h, i) - ex.groove(theta - h, i)) / (2 * h)
        fd2 = (ex.groove(theta + h, i) - 2 * ref + ex.groove(theta - h, i)) / h**2
        assert np.allclose(d1[i].T, fd1, atol=1e-9)
        assert np.allclose(d2[i].T, fd2, atol=1e-6)


def test_shapes_broadcast(example):
    drive, cam = example
    for shape in [(), (7,), (2, 3, 4)]:
        theta = np.random.default_rng(2).uniform(0, 6, shape)
        assert sph.groove_derivatives(drive, theta)[0].shape == (4, 3, *shape)
        assert sph.groove_walls(drive, cam, theta).shape == (4, 2, 3, *shape)
        for f in (sph.pressure_angle, sph.geodesic_curvature, sph.curvature_radius):
            assert f(drive, theta).shape == (4, *shape)


def test_walls_are_the_envelope_of_the_roller(example):
    """Wall points: at rho from the roller axis there, and no axis of the groove is closer."""
    from scipy.optimize import minimize_scalar

    drive, cam = example
    ex = Explicit()
    # half the groove: the 4 mm roller plus half the ISO 286 H8/f7 clearance at 8 mm
    # (IT8 = 22 um, IT7 = 15 um, es = -13 um: mean clearance 11 + 13 + 7.5 = 31.5 um)
    half = cam.roller_radius + 0.5 * 31.5e-6
    theta = np.radians([5.0, 40.0, 61.0, 100.0, 140.0])  # away from the crossings
    for rad in (cam.inner_radius, drive.sphere_radius, cam.bottom_radius):
        w = sph.groove_walls(drive, cam, theta, rad)
        assert np.allclose(np.linalg.norm(w, axis=2), rad, atol=1e-15)
        for i in range(4):
            for side in range(2):
                for k, th in enumerate(theta):
                    p = w[i, side, :, k]

                    def axis_distance(t, p=p, i=i):
                        e = ex.groove(t, i)
                        e = e / np.linalg.norm(e)
                        return np.linalg.norm(p - np.dot(p, e) * e)

                    best = minimize_scalar(
                        axis_distance,
                        bounds=(th - 0.3, th + 0.3),
                        method="bounded",
                        options={"xatol": 1e-12},
                    )
                    assert best.fun == pytest.approx(half, abs=1e-10)
                    assert best.x == pytest.approx(th, abs=1e-6)


@pytest.mark.parametrize("frame", ["shaft", "fixed"])
def test_pressure_angle_against_matrices(example, frame):
    drive, _ = example
    ex = Explicit()
    theta = np.linspace(0.0, 2 * np.pi, 181)
    mu = sph.pressure_angle(drive, theta, frame)
    h = 1e-5
    for i in range(4):
        g = ex.groove(theta, i)
        t = (ex.groove(theta + h, i) - ex.groove(theta - h, i)) / (2 * h)
        n = np.cross(g, t)
        n /= np.linalg.norm(n, axis=1, keepdims=True)
        if frame == "shaft":  # velocity relative to the Z-shaft, turned into the cam frame
            v1 = (ex.shaft(theta + h, i) - ex.shaft(theta - h, i)) / (2 * h)
            v0 = (_rot_x(theta) @ v1[..., None])[..., 0]
        else:
            v0 = (ex.fixed(theta + h, i) - ex.fixed(theta - h, i))[..., 0] / (2 * h)
        v = (np.swapaxes(_rot_x(-theta), -1, -2) @ v0[..., None])[..., 0]
        v /= np.linalg.norm(v, axis=1, keepdims=True)
        cos_ref = np.abs(np.sum(n * v, axis=1))
        assert np.allclose(np.cos(mu[i]), cos_ref, atol=1e-8)
        # relative to the cam the roller moves along the groove: always 90 deg to n
        assert np.max(np.abs(np.sum(n * t, axis=1))) < 1e-12 * np.max(np.abs(t))
    # lobe tip of roller 2 (u = -2 theta + alpha/2 = 0): spin and cam motion both along the
    # groove, so no wall force can drive the spin
    assert sph.pressure_angle(drive, np.radians(22.5))[2] == pytest.approx(np.pi / 2, abs=1e-9)


def test_geodesic_curvature_from_three_points(example):
    drive, _ = example
    ex = Explicit()
    theta = np.linspace(0.01, np.pi, 157)
    kg = sph.geodesic_curvature(drive, theta)
    h = 1e-3
    for i in range(4):
        a, b, c = ex.groove(theta - h, i), ex.groove(theta, i), ex.groove(theta + h, i)
        ab, bc, ca = (np.linalg.norm(x, axis=1) for x in (b - a, c - b, a - c))
        area2 = np.linalg.norm(np.cross(b - a, c - a), axis=1)
        kappa = 2 * area2 / (ab * bc * ca)  # circumscribed circle of three points
        kg_ref = np.sqrt(np.maximum(kappa**2 - 1 / R**2, 0.0))  # normal curvature 1/r
        assert np.allclose(np.abs(kg[i]), kg_ref, rtol=2e-4, atol=0.02)
        # sign: +n side (n = e_r x t) holds the centre of curvature when kappa_g > 0
        n = np.cross(b, c - a)
        side = np.sum((a + c - 2 * b) * n, axis=1)
        big = np.abs(kg[i]) > 1.0
        assert np.all(np.sign(side[big]) == np.sign(kg[i][big]))
    assert np.allclose(sph.curvature_radius(drive, theta), 1 / np.abs(kg))


def test_undercut_limit_is_where_the_inner_wall_reverses(example):
    """Below the limit the inner wall at R_i runs with the groove; above it, backwards."""
    drive, cam = example
    ex = Explicit()
    kmax, th, i = sph.sharpest_bend(drive)
    # independent: the largest |kappa_g| by three-point circles over a dense grid
    grid = np.linspace(0, np.pi, 20001)
    k3 = np.abs(sph.geodesic_curvature(drive, grid))
    assert kmax == pytest.approx(k3.max(), rel=1e-6)
    assert np.degrees(th) % 90 == pytest.approx(22.5, abs=1e-6)  # a lobe tip: u = 0 mod pi
    limit = float(sph.roller_radius_limit(drive, th, cam.inner_radius)[i])
    assert limit == pytest.approx(cam.inner_radius / np.hypot(1.0, R * kmax))
    h = 1e-5

    def wall(t, rho):
        g = ex.groove(t, i)
        tan = (ex.groove(t + h, i) - ex.groove(t - h, i)) / (2 * h)
        e = g / np.linalg.norm(g)
        n = np.cross(e, tan / np.linalg.norm(tan))
        inner = np.sign(sph.geodesic_curvature(drive, th)[i])
        return np.sqrt(cam.inner_radius**2 - rho**2) * e + inner * rho * n

    step = 1e-4
    along = ex.groove(th + step, i) - ex.groove(th - step, i)
    for factor, sign in ((0.98, 1.0), (1.02, -1.0)):
        dw = wall(th + step, factor * limit) - wall(th - step, factor * limit)
        assert np.sign(np.dot(dw, along)) == sign


def test_check_roller_radius(example):
    drive, cam = example
    assert sph.check_roller_radius(drive, cam) > cam.roller_radius
    big = sph.SphericalCam(drive.sphere_radius, roller_radius=0.006)  # over the limit
    with pytest.raises(ParameterError) as err:
        sph.check_roller_radius(drive, big)
    msg = str(err.value)
    # the walls' undercut limit 5.045 mm, less half the running clearance of a 12 mm roller
    # (ISO 286 H8/f7 over 10 up to 18 mm: 27/2 + 16 + 18/2 = 38.5 um)
    assert msg.startswith("roller_radius = 6 mm is not admissible: roller_radius < 5.026 mm")
    assert "theta = 22.5 deg" in msg and "roller 2" in msg


def _brute_crossings(ex, i, j, period, n=2500, near=5e-4):
    """Clusters of close approach of groove i and j (j may equal i), by full distance tables."""
    from scipy.spatial.distance import cdist

    t = np.linspace(0, period, n, endpoint=False)
    d = cdist(ex.groove(t, i), ex.groove(t, j))
    if i == j:
        gap = np.abs(t[:, None] - t[None, :])
        d[np.minimum(gap, period - gap) < 0.1] = np.inf
        d[np.tril_indices(n)] = np.inf
    a, b = np.nonzero(d < near)
    if len(a) == 0:
        return []
    order = np.argsort(a)
    a, b = a[order], b[order]
    clusters, start = [], 0
    for k in range(1, len(a) + 1):
        if k == len(a) or a[k] - a[k - 1] > 3:
            m = start + int(np.argmin(d[a[start:k], b[start:k]]))
            clusters.append((t[a[m]], t[b[m]], d[a[m], b[m]]))
            start = k
    return clusters


def test_crossings_example(example):
    drive, cam = example
    ex = Explicit()
    found = sph.groove_crossings(drive)
    period = sph.groove_period(drive)
    assert period == pytest.approx(np.pi)
    brute = {(i, j): _brute_crossings(ex, i, j, period) for i in range(4) for j in range(i, 4)}
    assert sum(len(v) for v in brute.values()) == len(found) == 4
    h = 1e-6
    for c in found:
        i, j = c.rollers
        assert i == j and len(brute[(i, j)]) == 1
        for k, who in enumerate((i, j)):
            assert np.linalg.norm(ex.groove(c.theta[k], who) - c.point) < 1e-9
        ta = ex.groove(c.theta[0] + h, i) - ex.groove(c.theta[0] - h, i)
        tb = ex.groove(c.theta[1] + h, j) - ex.groove(c.theta[1] - h, j)
        cos = abs(ta @ tb) / np.linalg.norm(ta) / np.linalg.norm(tb)
        assert c.angle == pytest.approx(np.arccos(cos), abs=1e-7)
        tb0, tb1, _ = brute[(i, j)][0]
        assert min(abs(tb0 - c.theta[0]), abs(tb1 - c.theta[0])) < 2e-3
        assert c.gap_length(cam.roller_radius) == pytest.approx(
            2 * cam.roller_radius / np.sin(c.angle)
        )
        assert np.allclose(c.shaft_angles(0), c.theta[0] + np.array([0.0, np.pi]))
    assert sph.distinct_grooves(drive) == [0, 1, 2, 3]


def test_crossings_between_grooves_and_shared_grooves():
    drive = wc.WobbleCam(PHI, ALPHA, -1.0, R)
    ex = Explicit(n=-1.0)
    period = sph.groove_period(drive)
    assert period == pytest.approx(2 * np.pi)
    # roller c + pi runs in roller c's groove half a turn later
    t = np.linspace(0, 2 * np.pi, 50)
    assert np.allclose(ex.groove(t + np.pi, 0), ex.groove(t, 1), atol=1e-15)
    assert sph.distinct_grooves(drive) == [0, 2]
    found = sph.groove_crossings(drive)
    brute = _brute_crossings(ex, 0, 2, period) + _brute_crossings(ex, 0, 0, period)
    brute += _brute_crossings(ex, 2, 2, period)
    assert len(found) == len(brute) == 2
    for c in found:
        assert c.rollers == (0, 2)
        for k, who in enumerate(c.rollers):
            assert np.linalg.norm(ex.groove(c.theta[k], who) - c.point) < 1e-9
    assert sph.groove_separation(drive)[0] < 1e-12
    # half-integer spin, alpha = 90 deg: a shift by pi turns the plate by 90 deg, one groove
    half = wc.WobbleCam(PHI, ALPHA, -0.5, R)
    assert sph.groove_period(half) == pytest.approx(4 * np.pi)
    assert sph.distinct_grooves(half) == [0]


def test_separation_against_brute_force(example):
    from scipy.spatial.distance import cdist

    drive, _ = example
    ex = Explicit()
    t = np.linspace(0, np.pi, 3000, endpoint=False)
    d = min(
        cdist(ex.groove(t, i), ex.groove(t, j)).min() for i in range(4) for j in range(i + 1, 4)
    )
    sep, rollers, _ = sph.groove_separation(drive)
    assert sep <= d + 1e-12 and sep == pytest.approx(d, abs=2e-5)
    assert rollers[0] != rollers[1]


@pytest.mark.parametrize("tilt, axis", [(30.0, 60.0), (60.0, 100.0), (40.0, 70.0)])
def test_separation_of_grooves_running_side_by_side(tilt, axis):
    """Grooves that never cross, closest where they run parallel: Newton from the
    closest samples lands on the closest approach a dense search finds (not on a
    farther point where Gauss-Newton's singular step throws it)."""
    from scipy.spatial.distance import cdist

    phi, alpha = np.radians(tilt), np.radians(axis)
    drive = wc.WobbleCam(phi, alpha, -2.0, R)
    ex = Explicit(phi=phi, alpha=alpha)
    t = np.linspace(0, 2 * np.pi, 6000, endpoint=False)
    d = min(
        cdist(ex.groove(t, i), ex.groove(t, j)).min() for i in range(4) for j in range(i + 1, 4)
    )
    sep, rollers, theta = sph.groove_separation(drive)
    assert d > 0.02  # no crossing
    assert sep <= d + 1e-12 and sep == pytest.approx(d, abs=2e-6)
    # the two points found are that far apart on the explicit grooves
    gap = np.linalg.norm(ex.groove(theta[0], rollers[0]) - ex.groove(theta[1], rollers[1]))
    assert gap == pytest.approx(sep, rel=1e-12)


def test_summary(example):
    drive, cam = example
    s = sph.summary(drive, cam)
    assert s["cam_pressure_angle_best_roller_max_deg"] <= s["cam_pressure_angle_max_deg"]
    assert s["cam_roller_radius_limit_mm"] < s["cam_curvature_radius_min_mm"]
    assert s["cam_self_crossings"] == 4 and s["cam_crossings_between_grooves"] == 0
    assert s["cam_groove_width_mm"] == pytest.approx(8.0315)  # 8 mm H8/f7: 31.5 um more
    assert s["cam_running_clearance_mm"] == pytest.approx(0.0315)
    assert all(isinstance(v, (int, float)) for v in s.values())
    # the shape's keys (what the cam's figure shows) are the summary's, measured alone
    shape = sph.shape_summary(drive, cam)
    assert len(shape) == 6 and shape == {k: s[k] for k in shape}
    kmax = np.max(np.abs(sph.geodesic_curvature(drive, np.linspace(0, 2 * np.pi, 20001))))
    assert shape["cam_curvature_radius_min_mm"] == pytest.approx(1e3 / kmax, rel=1e-6)


def test_argument_errors(example):
    drive, cam = example
    with pytest.raises(ParameterError, match="frame"):
        sph.pressure_angle(drive, 0.0, frame="cam")
    with pytest.raises(ParameterError, match="radius"):
        sph.groove_walls(drive, cam, 0.0, radius=0.003)
    with pytest.raises(ParameterError, match="^sphere_radius"):
        sph.groove_walls(drive, sph.SphericalCam(0.07), 0.0)


def test_figure(example, tmp_path):
    import matplotlib.image as mpimg

    from rotorkin.drives.wobble_cam.figures_cam import plot_spherical_cam

    drive, cam = example
    (path,) = plot_spherical_cam(drive, tmp_path, cam=cam, points=361)
    assert path.name == "fig_spherical_cam.png"
    img = mpimg.imread(path)
    assert img.shape[0] > 1000 and img.shape[1] > 1400
    with pytest.raises(TypeError):
        plot_spherical_cam(drive, tmp_path)


def _brute_walls(ex, cam, roller, theta, count=4000, own=0.2):
    """Walls (+n, -n) of ``roller`` present along its contact lines: a dense search here.

    A contact point ``q = lambda e_r +- h n`` is cut away where it lies within ``h`` of a
    groove axis (the radial line through a centre-line point) other than its own branch
    near theta: a k-d tree on the axes' unit vectors, sampled every period/count.
    """
    from scipy.spatial import cKDTree

    period = np.pi
    t = np.linspace(0.0, period, count, endpoint=False)
    axes = np.vstack([ex.groove(t, i) for i in range(4)])
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    tree = cKDTree(axes)
    owner, at = np.repeat(np.arange(4), count), np.tile(t, 4)
    g = ex.groove(theta, roller)
    e = g / np.linalg.norm(g, axis=1, keepdims=True)
    tan = ex.d(ex.groove, theta, roller)
    n = np.cross(e, tan / np.linalg.norm(tan, axis=1, keepdims=True))
    h = cam.groove_half_width
    lo, hi = cam.roller_span
    out = np.ones((2, len(theta)), bool)
    for k, side in enumerate((1.0, -1.0)):
        for lam in np.linspace(lo, hi, 5):
            q = lam * e + side * h * n
            rad = np.linalg.norm(q, axis=1)
            chord = 2.0 * np.sin(0.5 * np.arcsin(h / rad))
            for j, hits in enumerate(tree.query_ball_point(q / rad[:, None], chord)):
                d = (at[hits] - theta[j] + 0.5 * period) % period - 0.5 * period
                if np.any((owner[hits] != roller) | (np.abs(d) > own)):
                    out[k, j] = False
    return out


def test_guided_against_a_dense_search_of_the_other_channels(example):
    """Both walls along the contact lines: guided() against a brute-force channel test."""
    drive, cam = example
    ex = Explicit()
    crossings = sph.groove_crossings(drive)
    step = np.radians(0.02)
    for c in crossings:
        for k in (0, 1):
            i, t0 = c.rollers[k], c.theta[k]
            theta = t0 + np.arange(-450, 451) * step  # +-9 deg
            want = _brute_walls(ex, cam, i, theta)
            got = sph.guided(drive, cam, theta)[i]
            both = want.all(axis=0)
            assert not both[450] and both[0] and both[-1]
            # the two agree except within one sample of where a wall begins or ends
            edge = np.zeros_like(both)
            for w in want:
                flips = np.flatnonzero(np.diff(w))
                for f in flips:
                    edge[max(f - 1, 0) : f + 3] = True
            assert np.array_equal(got[~edge], both[~edge])
            # one wall or the other is missing over about 2 h (cot a + 1/sin a) r/lambda_in
            speed = np.linalg.norm(ex.d(ex.groove, theta[~both], i), axis=1)
            length = np.sum(speed) * step
            a = c.angle
            flat = 2 * cam.groove_half_width * (1 / np.tan(a) + 1 / np.sin(a))
            assert length == pytest.approx(flat * R / cam.roller_span[0], rel=0.1)
    # every roller is guided while more than 10 deg of shaft angle from its crossings
    theta = np.linspace(0.0, 2 * np.pi, 7201)
    far = np.ones((4, len(theta)), bool)
    for c in crossings:
        for k in (0, 1):
            for t0 in c.shaft_angles(k):
                d = (theta - t0 + np.pi) % (2 * np.pi) - np.pi
                far[c.rollers[k]] &= np.abs(d) > np.radians(10)
    assert sph.guided(drive, cam, theta)[far].all()


def test_pressure_angle_peaks(example):
    drive, cam = example
    peaks = sph.pressure_angle_peaks(drive, cam)
    s = sph.summary(drive, cam)
    deg = np.degrees
    assert deg(peaks["any"][0]) == pytest.approx(s["cam_pressure_angle_max_deg"])
    assert deg(peaks["best"][0]) == pytest.approx(s["cam_pressure_angle_best_roller_max_deg"])
    assert deg(peaks["guided"][0]) == pytest.approx(s["cam_pressure_angle_guided_max_deg"])
    # each value is the roller's own pressure angle at the shaft angle named
    for key in ("any", "guided", "best", "best_guided"):
        mu, th, roller = peaks[key]
        assert sph.pressure_angle(drive, th)[roller] == pytest.approx(mu, abs=1e-12)
    # the best-placed roller: of the 4, the smallest at that angle
    mu, th, roller = peaks["best"]
    assert mu == pytest.approx(sph.pressure_angle(drive, th).min(), abs=1e-12)
    # the guided peaks are of rollers between both walls
    for key in ("guided", "fixed_guided", "best_guided"):
        _, th, roller = peaks[key]
        assert sph.guided(drive, cam, th)[roller]
    # leaving rollers out cannot lower the best roller's worst angle, nor raise the peak
    assert peaks["best_guided"][0] >= peaks["best"][0] - 1e-12
    assert peaks["guided"][0] <= peaks["any"][0] + 1e-12
    # the example: 30.36 deg with every roller, but at theta = 22.5 deg rollers 1, 1' are at
    # their crossings and 2, 2' at their lobe tips (90 deg): no roller guides the plate well
    assert deg(peaks["best"][0]) == pytest.approx(30.36, abs=0.01)
    assert deg(peaks["best_guided"][0]) == pytest.approx(90.0, abs=1e-6)
    assert deg(peaks["best_guided"][1]) % 45.0 == pytest.approx(22.5)


def _near_others_listed(ch, roller):
    """The samples near another branch, every axis sample measured against every sample
    one by one (no grid): the reference of the search in ``near_others``."""
    from rotorkin.drives.wobble_cam.cam_walls import SCAN

    i, shift = ch.curve[roller]
    own = ch.axes[ch.owner == i]
    reach = 2.0 * np.sin(np.arcsin(min(1.0, 1.05 * ch.h / ch.lam_in))) + 2 * ch.pad
    out = np.zeros(SCAN, dtype=bool)
    for j, p in enumerate(np.roll(own, -shift, axis=0)):
        hits = np.flatnonzero(np.linalg.norm(p - ch.axes, axis=1) <= reach)
        gap = np.abs(ch.arc[i][hits % SCAN] - ch.arc[i][(j + shift) % SCAN])
        gap = np.minimum(gap, ch.length[i] - gap)
        out[j] = bool(np.any((ch.owner[hits] != i) | (gap > 2.5 * ch.h)))
    return out


def _tilted(example, tilt):
    """The example's drive at another plate tilt [deg], and its cam."""
    drive, cam = example
    return wc.WobbleCam(
        plate_tilt=np.radians(tilt),
        roller_axis_angle=drive.roller_axis_angle,
        spin_ratio=drive.spin_ratio,
        sphere_radius=drive.sphere_radius,
        pistons_per_rotor=drive.pistons_per_rotor,
    ), cam


@pytest.mark.parametrize("tilt", [45.0, 30.0, 60.0])
def test_near_others_counts_what_the_neighbour_lists_find(example, tilt):
    """The grid's search (all within reach less the own stretch of groove) flags the
    same samples as measuring every axis sample."""
    from rotorkin.drives.wobble_cam import cam_walls

    drive, cam = _tilted(example, tilt)
    ch = cam_walls._Channels(drive, cam)
    for roller in range(4):
        want = _near_others_listed(ch, roller)
        got = ch.near_others(roller)
        assert want.any()
        assert np.array_equal(got, want)


@pytest.mark.parametrize("tilt", [45.0, 30.0])
def test_wall_gaps_search_batched_equals_one_step_at_a_time(example, tilt, monkeypatch):
    """The gaps' ends bisected several steps a search equal the steps taken one by one
    (one search each), bit for bit: the same midpoints, the same brackets."""
    from rotorkin.drives.wobble_cam import cam_walls

    drive, cam = _tilted(example, tilt)
    batched = cam_walls.wall_gaps(drive, cam)
    monkeypatch.setattr(cam_walls, "_LEVELS", 1)
    one_by_one = cam_walls.wall_gaps(drive, cam)
    assert batched and batched == one_by_one
    # and the scan's search is the wall test of every sample alone: each gap's ends
    # bracket a change of the wall, a step of the scan inside and outside it
    ch = cam_walls._Channels(drive, cam)
    step = ch.period / cam_walls.SCAN
    for g in batched:
        ends = np.array([g.start, g.end])
        inside = cam_walls._missing(ch, cam, g.roller, ends + [step / 4, -step / 4], g.wall)
        outside = cam_walls._missing(ch, cam, g.roller, ends + [-step / 4, step / 4], g.wall)
        assert inside.all() and not outside.any()
