"""Tests of the wobble-plate + spherical-cam drive against independent numeric models.

The independent models are written here from the paper's frame definitions
(eq. 2-5, 9) as explicit rotation matrices, plus explicit piston placement and
scipy optimisation / root finding; nothing is copied from the code's output.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import optimize

from rotorkin.core.errors import ParameterError
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.drives.wobble_cam import study as study

D = np.pi / 180.0
GAMMA = np.pi / 8.0


# --------------------------------------------------------------------------------------------
# independent model: rotation matrices of the paper, written out per angle
# --------------------------------------------------------------------------------------------
def a_x(t):
    """Paper eq. 2/4/9 form, shape (..., 3, 3)."""
    t = np.asarray(t, dtype=float)
    c, s = np.cos(t), np.sin(t)
    one, zero = np.ones_like(t), np.zeros_like(t)
    return np.stack(
        [np.stack([one, zero, zero], -1), np.stack([zero, c, s], -1), np.stack([zero, -s, c], -1)],
        -2,
    )


def a_y(t):
    """Paper eq. 3 form, shape (..., 3, 3)."""
    t = np.asarray(t, dtype=float)
    c, s = np.cos(t), np.sin(t)
    one, zero = np.ones_like(t), np.zeros_like(t)
    return np.stack(
        [np.stack([c, zero, s], -1), np.stack([zero, one, zero], -1), np.stack([-s, zero, c], -1)],
        -2,
    )


def fixed_point(theta, varphi, phi, c, r=1.0):
    """r|0 = A_theta A_phi A_varphi r|3 with r|3 = r [0, sin c, cos c]; shape (..., 3)."""
    theta, varphi, c = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (theta, varphi, c))
    )
    a = a_x(theta) @ a_y(np.full_like(theta, phi)) @ a_x(varphi)
    r3 = r * np.stack([np.zeros_like(c), np.sin(c), np.cos(c)], -1)
    return np.einsum("...ij,...j->...i", a, r3)


def cam_point(theta, psi, varphi, phi, c, r=1.0):
    """r|4 = A_psi^T r|0; shape (..., 3)."""
    p0 = fixed_point(theta, varphi, phi, c, r)
    return np.einsum("...ji,...j->...i", a_x(psi), p0)


def wrap(x):
    return np.angle(np.exp(1j * np.asarray(x)))


def random_params(rng):
    alpha = rng.uniform(np.pi / 4 + 0.02, 3 * np.pi / 4 - 0.02)
    lim = float(wc.max_plate_tilt(alpha))
    phi = rng.uniform(0.03, lim - 0.01)
    n = float(rng.choice([-3.0, -2.0, -1.5, -1.0, -0.5, 0.5, 1.0, 2.0]))
    return wc.WobbleCam(phi, alpha, n, rng.uniform(0.01, 0.2))


def d5(f, x, h):
    """Five-point central difference (error O(h^4))."""
    return (-f(x + 2 * h) + 8 * f(x + h) - 8 * f(x - h) + f(x - 2 * h)) / (12 * h)


def table1():
    return wc.WobbleCam(45 * D, 90 * D, -2.0, 0.05)


# --------------------------------------------------------------------------------------------
# rotor angles
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("seed", range(6))
def test_rotor_angles_match_rotation_matrices(seed):
    """Phi_k = yz-projection angle (from +z towards +y) of group k's roller shaft."""
    rng = np.random.default_rng(seed)
    p = random_params(rng)
    theta = rng.uniform(-10, 10, 200)
    q = wc.rotor_angles(p, theta)[0]
    varphi = p.spin_ratio * theta
    for k, c in enumerate((-p.roller_axis_angle / 2, p.roller_axis_angle / 2)):
        v = fixed_point(theta, varphi, p.plate_tilt, c)
        np.testing.assert_allclose(wrap(q[k] - np.arctan2(v[..., 1], v[..., 2])), 0, atol=1e-9)
        # the opposite roller of the same group lies on the same rail, pi away
        w = fixed_point(theta, varphi, p.plate_tilt, c + np.pi)
        np.testing.assert_allclose(
            wrap(q[k] + np.pi - np.arctan2(w[..., 1], w[..., 2])), 0, atol=1e-9
        )


@pytest.mark.parametrize("seed", range(4))
def test_rotor_angles_continuous_and_periodic(seed):
    rng = np.random.default_rng(100 + seed)
    p = random_params(rng)
    theta = np.linspace(-2 * np.pi, 2 * np.pi, 40001)
    q, d1 = wc.rotor_angles(p, theta)[:2]
    step = theta[1] - theta[0]
    assert np.max(np.abs(np.diff(q, axis=1))) < 1.01 * step * np.max(np.abs(d1))
    t0 = rng.uniform(-5, 5, 50)
    a = wc.rotor_angles(p, t0)
    b = wc.rotor_angles(p, t0 + wc.period(p))
    # each rotor gains 2 pi (1 + n), a multiple of pi: 2 rails, 4 pistons map onto themselves
    np.testing.assert_allclose(b[0] - a[0], 2 * np.pi * (1 + p.spin_ratio), atol=1e-9)
    assert abs((1 + p.spin_ratio) * 2 - round((1 + p.spin_ratio) * 2)) < 1e-12
    for i in (1, 2, 3):
        np.testing.assert_allclose(b[i], a[i], atol=1e-9 * max(1.0, np.max(np.abs(a[i]))))


@pytest.mark.parametrize("seed", range(4))
def test_rotor_derivatives_finite_differences(seed):
    rng = np.random.default_rng(200 + seed)
    p = random_params(rng)
    theta = rng.uniform(-4, 4, 100)
    h = 1e-3
    ders = wc.rotor_angles(p, theta)
    for i in (0, 1, 2):
        fd = d5(lambda t, i=i: wc.rotor_angles(p, t)[i], theta, h)
        scale = max(1.0, np.max(np.abs(ders[i + 1])))
        np.testing.assert_allclose(ders[i + 1], fd, rtol=0, atol=2e-7 * scale)


@pytest.mark.parametrize("seed", range(4))
def test_general_spin_law_chain_rule(seed):
    """Spin law with a periodic correction: varphi = n theta + a sin(k theta + b)."""
    rng = np.random.default_rng(300 + seed)
    phi, alpha = rng.uniform(0.1, 1.0), rng.uniform(1.0, 2.0)
    n, a, k, b = -2.0, rng.uniform(-0.3, 0.3), float(rng.integers(1, 5)), rng.uniform(0, 6)

    def spin(t):
        s, c = np.sin(k * t + b), np.cos(k * t + b)
        return n * t + a * s, n + a * k * c, -a * k**2 * s, -a * k**3 * c

    theta = rng.uniform(-4, 4, 80)
    ders = wc.rotor_angles_from_spin(phi, alpha, spin(theta), theta)
    for i in (0, 1, 2):
        fd = d5(lambda t, i=i: wc.rotor_angles_from_spin(phi, alpha, spin(t), t)[i], theta, 1e-3)
        scale = max(1.0, np.max(np.abs(ders[i + 1])))
        np.testing.assert_allclose(ders[i + 1], fd, rtol=0, atol=2e-7 * scale)
    # position still equals the rotation-matrix projection
    v = fixed_point(theta, spin(theta)[0], phi, -alpha / 2)
    np.testing.assert_allclose(wrap(ders[0][0] - np.arctan2(v[..., 1], v[..., 2])), 0, atol=1e-9)


def test_projected_angle_derivatives_and_branch():
    rng = np.random.default_rng(7)
    phi = rng.uniform(0.05, 1.4, 200)
    u = rng.uniform(-20, 20, 200)
    e = wc.projected_angle(phi, u)
    for i in (0, 1, 2):
        fd = d5(lambda x, i=i: wc.projected_angle(phi, x)[i], u, 1e-3)
        scale = np.maximum(1.0, np.abs(e[i + 1]))
        assert np.all(np.abs(e[i + 1] - fd) < 1e-6 * scale)
    # the atan2 of the definition, modulo 2 pi; and E(u + pi) = E(u) + pi, E odd
    np.testing.assert_allclose(
        wrap(e[0] - np.arctan2(np.sin(u), np.cos(phi) * np.cos(u))), 0, atol=1e-12
    )
    np.testing.assert_allclose(wc.projected_angle(phi, u + np.pi)[0], e[0] + np.pi, atol=1e-12)
    np.testing.assert_allclose(wc.projected_angle(phi, -u)[0], -e[0], atol=1e-12)
    # no tilt: the projection is the plate angle itself
    np.testing.assert_allclose(wc.projected_angle(0.0, u)[0], u, atol=1e-12)


def test_speed_ratio_extremes_in_summary_match_samples():
    cfg = _cfg()
    s = study.evaluate(cfg).summary
    theta = np.linspace(0, 2 * np.pi, 200001)
    d1 = wc.rotor_angles(table1(), theta)[1]
    assert s["rotor_speed_ratio_min"] == pytest.approx(d1.min(), abs=1e-8)
    assert s["rotor_speed_ratio_max"] == pytest.approx(d1.max(), abs=1e-8)
    assert s["rotor_mean_speed_ratio"] == pytest.approx(np.trapezoid(d1[0], theta) / (2 * np.pi))


def test_mirror_symmetry_of_the_rotors():
    """E is odd, so Phi_2(-theta) = -Phi_1(theta) for the linear spin law."""
    rng = np.random.default_rng(11)
    for _ in range(3):
        p = random_params(rng)
        t = rng.uniform(-6, 6, 100)
        a, b = wc.rotor_angles(p, t), wc.rotor_angles(p, -t)
        np.testing.assert_allclose(b[0][1], -a[0][0], atol=1e-12)
        np.testing.assert_allclose(b[1][1], a[1][0], atol=1e-12)


# --------------------------------------------------------------------------------------------
# slider angle, extremes, plate tilt limit
# --------------------------------------------------------------------------------------------
def eq15_printed(varphi, phi, alpha):
    """Eq. 15 as printed (with the paper's phi/varphi read as spin/tilt)."""
    m, p = varphi - alpha / 2, varphi + alpha / 2
    c2 = np.cos(phi) ** 2
    num = np.sin(m) * np.sin(p) + c2 * np.cos(m) * np.cos(p)
    den = np.sqrt((np.sin(m) ** 2 + c2 * np.cos(m) ** 2) * (np.sin(p) ** 2 + c2 * np.cos(p) ** 2))
    return np.arccos(num / den)


@pytest.mark.parametrize("seed", range(4))
def test_slider_angle_against_eq15_and_matrices(seed):
    rng = np.random.default_rng(400 + seed)
    phi, alpha = rng.uniform(0.02, 1.4), rng.uniform(0.1, np.pi - 0.1)
    varphi = rng.uniform(-10, 10, 300)
    got = wc.slider_angle(phi, alpha, varphi)
    np.testing.assert_allclose(got, eq15_printed(varphi, phi, alpha), atol=1e-9)
    # explicit projections at an arbitrary theta: alpha' does not depend on theta
    theta = rng.uniform(-10, 10, 300)
    r1 = fixed_point(theta, varphi, phi, -alpha / 2)
    r2 = fixed_point(theta, varphi, phi, alpha / 2)
    cross = r1[..., 2] * r2[..., 1] - r1[..., 1] * r2[..., 2]  # from r1 towards r2, z->y sense
    dot = r1[..., 1] * r2[..., 1] + r1[..., 2] * r2[..., 2]
    np.testing.assert_allclose(got, np.arctan2(cross, dot), atol=1e-9)
    # period pi in varphi, values in (0, pi)
    np.testing.assert_allclose(wc.slider_angle(phi, alpha, varphi + np.pi), got, atol=1e-12)
    assert np.all((got > 0) & (got < np.pi))


@pytest.mark.parametrize("seed", range(5))
def test_slider_extremes_by_optimisation(seed):
    rng = np.random.default_rng(500 + seed)
    phi, alpha = rng.uniform(0.05, 1.4), rng.uniform(0.2, np.pi - 0.2)
    amax, amin = wc.slider_angle_extremes(phi, alpha)
    grid = np.linspace(0, np.pi, 2001)
    vals = eq15_printed(grid, phi, alpha)
    i, j = np.argmax(vals), np.argmin(vals)
    top = optimize.minimize_scalar(
        lambda v: -eq15_printed(v, phi, alpha),
        bracket=(grid[i] - 0.01, grid[i], grid[i] + 0.01),
        tol=1e-12,
    )
    bot = optimize.minimize_scalar(
        lambda v: eq15_printed(v, phi, alpha),
        bracket=(grid[j] - 0.01, grid[j], grid[j] + 0.01),
        tol=1e-12,
    )
    assert amax == pytest.approx(-top.fun, abs=1e-10)
    assert amin == pytest.approx(bot.fun, abs=1e-10)
    assert wrap(2 * top.x) == pytest.approx(0.0, abs=1e-4)  # varphi = 0 (mod pi)
    assert wrap(2 * bot.x) == pytest.approx(np.pi, abs=1e-4) or wrap(2 * bot.x) == pytest.approx(
        -np.pi, abs=1e-4
    )  # varphi = pi/2 (mod pi)
    # d alpha'/d varphi vanishes exactly where sin(2 varphi) sin(alpha) = 0
    v = rng.uniform(0.05, np.pi / 2 - 0.05, 50)
    fd = d5(lambda x: wc.slider_angle(phi, alpha, x), v, 1e-4)
    assert np.all(fd < 0)  # strictly falling between 0 and pi/2


@pytest.mark.parametrize("alpha_deg", [50.0, 63.0, 80.0, 90.0, 101.0, 120.0, 130.0])
def test_max_plate_tilt_by_root_finding(alpha_deg):
    alpha = alpha_deg * D
    f_max = optimize.brentq(
        lambda p: eq15_printed(0.0, p, alpha) - 3 * np.pi / 4, 1e-9, np.pi / 2 - 1e-9, xtol=1e-14
    )
    f_min = optimize.brentq(
        lambda p: eq15_printed(np.pi / 2, p, alpha) - np.pi / 4, 1e-9, np.pi / 2 - 1e-9, xtol=1e-14
    )
    assert float(wc.max_plate_tilt(alpha)) == pytest.approx(min(f_max, f_min), abs=1e-9)


def test_max_plate_tilt_outside_range_is_nan():
    assert np.isnan(wc.max_plate_tilt(40 * D))
    assert np.isnan(wc.max_plate_tilt(140 * D))


# --------------------------------------------------------------------------------------------
# chambers and pistons
# --------------------------------------------------------------------------------------------
def explicit_chambers(phi1, phi2, beta):
    """Place the 8 pistons and measure the 8 gaps between neighbours, minus the width."""
    pist = np.concatenate(
        [
            phi1[..., None] + GAMMA + np.arange(4) * np.pi / 2,
            phi2[..., None] - GAMMA + np.arange(4) * np.pi / 2,
        ],
        -1,
    )
    pist = np.sort(np.mod(pist, 2 * np.pi), -1)
    gaps = np.diff(np.concatenate([pist, pist[..., :1] + 2 * np.pi], -1), axis=-1)
    return np.sort(gaps - beta, -1)


@pytest.mark.parametrize("seed", range(4))
def test_chamber_angles_against_explicit_pistons(seed):
    rng = np.random.default_rng(600 + seed)
    p = random_params(rng)
    beta = rng.uniform(0.0, 0.1)
    theta = rng.uniform(-5, 5, 100)
    q = wc.rotor_angles(p, theta)[0]
    da, db = wc.chamber_angles(beta, q[1] - q[0])
    ours = np.sort(
        np.concatenate([np.repeat(da[:, None], 4, 1), np.repeat(db[:, None], 4, 1)], 1), 1
    )
    np.testing.assert_allclose(ours, explicit_chambers(q[0], q[1], beta), atol=1e-9)
    np.testing.assert_allclose(da + db + 2 * beta, np.pi / 2, atol=1e-12)  # eq. 18


@pytest.mark.parametrize("seed", range(6))
def test_piston_layout_against_dense_simulation(seed):
    rng = np.random.default_rng(700 + seed)
    p = random_params(rng)
    eps_lo = wc.min_compression_ratio(p)
    eps = eps_lo * rng.uniform(1.05, 5.0)
    lay = wc.piston_layout(p, eps)
    assert lay.piston_width > 0
    theta = np.linspace(0, np.pi, 20001)
    q = wc.rotor_angles(p, theta)[0]
    ch = explicit_chambers(q[0], q[1], lay.piston_width)
    # the tightest chamber reaches ratio eps; no chamber goes below the design minimum
    lo = ch.min()
    da, db = wc.chamber_angles(lay.piston_width, q[1] - q[0])
    kinds = {"A": da, "B": db}
    tight = kinds[lay.design_kind]
    other = kinds["B" if lay.design_kind == "A" else "A"]
    assert tight.min() == pytest.approx(lo, abs=1e-9)
    assert tight.max() / tight.min() == pytest.approx(eps, rel=1e-6)
    assert other.max() / other.min() <= eps * (1 + 1e-9)
    other_ratio = lay.compression_ratio_b if lay.design_kind == "A" else lay.compression_ratio_a
    assert other.max() / other.min() == pytest.approx(other_ratio, rel=1e-6)
    # eq. 23: both kinds swing by alpha'_max - alpha'_min
    amax, amin = wc.slider_angle_extremes(p.plate_tilt, p.roller_axis_angle)
    for k in (da, db):
        assert k.max() - k.min() == pytest.approx(amax - amin, abs=1e-7)
    assert lay.swing == pytest.approx(amax - amin, abs=1e-12)


@pytest.mark.parametrize("seed", range(5))
def test_piston_layout_reduces_to_eq21_22_at_90deg(seed):
    rng = np.random.default_rng(800 + seed)
    phi = rng.uniform(0.05, float(wc.max_plate_tilt(np.pi / 2)) - 0.01)
    p = wc.WobbleCam(phi, np.pi / 2)
    eps = wc.min_compression_ratio(p) * rng.uniform(1.01, 5.0)
    lay = wc.piston_layout(p, eps)
    amin = eq15_printed(np.pi / 2, phi, np.pi / 2)
    amax = eq15_printed(0.0, phi, np.pi / 2)
    beta21 = (eps + 1) / (eps - 1) * amin - np.pi * (eps + 3) / (4 * (eps - 1))
    assert lay.piston_width == pytest.approx(beta21, abs=1e-12)
    for a_, d_ in ((amin, lay.chamber_a_min), (amax, lay.chamber_a_max)):
        assert d_ == pytest.approx(a_ - (eps + 1) / (eps - 1) * amin + np.pi / (eps - 1), abs=1e-12)
    # both kinds identical at 90 deg
    assert lay.chamber_b_min == pytest.approx(lay.chamber_a_min, abs=1e-12)
    assert lay.compression_ratio_b == pytest.approx(eps, rel=1e-10)


def test_compression_ratio_bounds():
    p = table1()
    lo = wc.min_compression_ratio(p)
    # zero-width pistons: the gaps between centre lines alone give the ratio
    gmin, gmax = (
        eq15_printed(np.pi / 2, 45 * D, np.pi / 2) - 2 * GAMMA,
        eq15_printed(0.0, 45 * D, np.pi / 2) - 2 * GAMMA,
    )
    assert lo == pytest.approx(gmax / gmin, rel=1e-12)
    assert wc.piston_layout(p, lo * (1 + 1e-6)).piston_width == pytest.approx(0.0, abs=1e-6)
    for bad in (lo, lo * 0.9, 1.0, 0.5, float("nan"), float("inf")):
        with pytest.raises(ParameterError, match="compression_ratio"):
            wc.piston_layout(p, bad)


# --------------------------------------------------------------------------------------------
# roller trajectories and grooves
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("seed", range(4))
def test_roller_positions_and_grooves_against_matrices(seed):
    rng = np.random.default_rng(900 + seed)
    p = random_params(rng)
    theta = rng.uniform(-7, 7, 60)
    r = wc.roller_positions(p, theta)
    g = wc.groove_points(p, theta)
    a = p.roller_axis_angle
    for k, c in enumerate((-a / 2, np.pi - a / 2, a / 2, np.pi + a / 2)):
        ref = fixed_point(theta, p.spin_ratio * theta, p.plate_tilt, c, p.sphere_radius)
        np.testing.assert_allclose(np.moveaxis(r[k], 0, -1), ref, atol=1e-12)
        ref4 = cam_point(theta, -theta, p.spin_ratio * theta, p.plate_tilt, c, p.sphere_radius)
        np.testing.assert_allclose(np.moveaxis(g[k], 0, -1), ref4, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(r, axis=1), p.sphere_radius, rtol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(g, axis=1), p.sphere_radius, rtol=1e-12)


def test_groove_closes_after_half_a_turn():
    p = table1()
    theta = np.linspace(0, 2 * np.pi, 97)
    g = wc.groove_points(p, theta)
    np.testing.assert_allclose(wc.groove_points(p, theta + np.pi), g, atol=1e-12)
    for frac in (0.25, 0.5, 0.75):
        assert np.max(np.abs(wc.groove_points(p, theta + frac * np.pi) - g)) > 1e-3
    # the fixed-frame trajectory needs the full turn
    r = wc.roller_positions(p, theta)
    np.testing.assert_allclose(wc.roller_positions(p, theta + 2 * np.pi), r, atol=1e-12)
    assert np.max(np.abs(wc.roller_positions(p, theta + np.pi) - r)) > 1e-3


# --------------------------------------------------------------------------------------------
# shapes, motion, counts
# --------------------------------------------------------------------------------------------
def test_shapes_0d_1d_3d_agree():
    p = wc.WobbleCam(0.6, 1.4, -1.5, 0.04)
    t3 = np.random.default_rng(1).uniform(-4, 4, (2, 3, 4))
    t1 = t3.ravel()
    funcs = {
        "rotor": lambda t: np.stack(wc.rotor_angles(p, t)),
        "roller": lambda t: wc.roller_positions(p, t),
        "groove": lambda t: wc.groove_points(p, t),
        "slider": lambda t: wc.slider_angle(p.plate_tilt, p.roller_axis_angle, t),
        "proj": lambda t: np.stack(wc.projected_angle(p.plate_tilt, t)),
        "spin": lambda t: np.stack(wc.spin_law(p, t)),
        "cam": wc.cam_angle,
    }
    for name, f in funcs.items():
        v3, v1 = f(t3), f(t1)
        assert v3.shape[v3.ndim - 3 :] == (2, 3, 4), name
        np.testing.assert_array_equal(v3.reshape(v1.shape), v1, err_msg=name)
        v0 = f(np.float64(t1[5]))
        np.testing.assert_array_equal(v0, v1[..., 5], err_msg=name)
    m = wc.motion(p, t3)
    assert m.q.shape == m.dq.shape == m.d2q.shape == m.d3q.shape == (2, 2, 3, 4)
    assert m.members == ("rotor 1", "rotor 2") and m.unit == "rad"
    assert wc.motion(p, 0.3).q.shape == (2,)
    np.testing.assert_allclose(m.relative[0], wc.slider_angle(0.6, 1.4, p.spin_ratio * t3))


@pytest.mark.parametrize("n", [-2.0, -1.5, -1.0, 0.5, 1.0, 3.0])
def test_volume_cycles_counted(n):
    p = wc.WobbleCam(0.7, np.pi / 2, n)
    theta = np.linspace(0, 2 * np.pi, 40000, endpoint=False)
    s = wc.slider_angle(p.plate_tilt, p.roller_axis_angle, wc.spin_law(p, theta)[0])
    minima = np.sum((s < np.roll(s, 1)) & (s < np.roll(s, -1)))
    assert minima == wc.volume_cycles_per_rev(p) == round(2 * abs(n))
    assert wc.power_strokes_per_rev(p) == 8 * minima // 2


# --------------------------------------------------------------------------------------------
# validation
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"plate_tilt": 0.5, "roller_axis_angle": 40 * D}, "roller_axis_angle"),
        ({"plate_tilt": 0.5, "roller_axis_angle": 135 * D}, "roller_axis_angle"),
        ({"plate_tilt": 0.5, "roller_axis_angle": float("nan")}, "roller_axis_angle"),
        ({"plate_tilt": 0.0}, "plate_tilt"),
        ({"plate_tilt": -0.1}, "plate_tilt"),
        ({"plate_tilt": 66 * D}, "plate_tilt"),
        ({"plate_tilt": float("nan")}, "plate_tilt"),
        ({"plate_tilt": 60 * D, "roller_axis_angle": 60 * D}, "plate_tilt"),
        ({"plate_tilt": 0.5, "spin_ratio": 0.0}, "spin_ratio"),
        ({"plate_tilt": 0.5, "spin_ratio": -2.2}, "spin_ratio"),
        ({"plate_tilt": 0.5, "spin_ratio": float("inf")}, "spin_ratio"),
        ({"plate_tilt": 0.5, "spin_ratio": float("nan")}, "spin_ratio"),
        ({"plate_tilt": 0.5, "sphere_radius": 0.0}, "sphere_radius"),
        ({"plate_tilt": 0.5, "sphere_radius": -0.01}, "sphere_radius"),
        ({"plate_tilt": 0.5, "sphere_radius": float("nan")}, "sphere_radius"),
    ],
)
def test_parameter_errors(kwargs, name):
    with pytest.raises(ParameterError, match=name) as info:
        wc.WobbleCam(**kwargs)
    assert info.value.name == name


def test_plate_tilt_message_gives_limit_and_equation():
    with pytest.raises(ParameterError) as info:
        wc.WobbleCam(70 * D)
    msg = str(info.value)
    assert "65.53 deg" in msg and "eq. 20" in msg and "70 deg" in msg
    with pytest.raises(ParameterError, match="eq. 20"):
        wc.WobbleCam(60 * D, 60 * D)


def test_valid_edges_accepted():
    wc.WobbleCam(65.5 * D)
    wc.WobbleCam(0.2, 46 * D, 0.5, 1e-4)
    wc.WobbleCam(0.2, 134 * D, -7.5)


# --------------------------------------------------------------------------------------------
# study and figures
# --------------------------------------------------------------------------------------------
def _cfg(**drive):
    d = {
        "type": "wobble_cam",
        "plate_tilt": 45 * D,
        "roller_axis_angle": 90 * D,
        "spin_ratio": -2.0,
        "sphere_radius": 0.05,
    }
    d.update(drive)
    return {"drive": d, "machine": {"compression_ratio": 10.0}, "run": {"points": 721}, "loads": {}}


def test_study_summary_and_columns():
    res = study.evaluate(_cfg())
    s, c = res.summary, res.columns
    # independent expectations: eq. 15 printed, explicit pistons, Table 1 inputs
    amax = np.degrees(eq15_printed(0.0, 45 * D, 90 * D))
    amin = np.degrees(eq15_printed(np.pi / 2, 45 * D, 90 * D))
    assert s["slider_angle_max_deg"] == pytest.approx(amax, abs=1e-9)
    assert s["slider_angle_min_deg"] == pytest.approx(amin, abs=1e-9)
    assert s["chamber_swing_deg"] == pytest.approx(amax - amin, abs=1e-9)
    beta = (11 * amin - 180 * 13 / 4) / 9  # eq. 21 in degrees
    assert s["piston_width_deg"] == pytest.approx(beta, abs=1e-9)
    assert s["chamber_angle_min_deg"] == pytest.approx(amin - 45 - beta, abs=1e-9)
    assert s["chamber_angle_max_deg"] == pytest.approx(amax - 45 - beta, abs=1e-9)
    assert s["chamber_angle_max_deg"] / s["chamber_angle_min_deg"] == pytest.approx(10.0)
    assert s["volume_cycles_per_rev"] == 4 and s["power_strokes_per_rev"] == 16
    assert s["chambers"] == 8 and s["piston_offset_gamma_deg"] == pytest.approx(22.5)
    assert s["max_plate_tilt_deg"] == pytest.approx(np.degrees(np.arccos(np.tan(np.pi / 8))))
    assert s["compression_ratio_a"] == pytest.approx(10.0)
    assert s["compression_ratio_b"] == pytest.approx(10.0)
    for k in res.headline:
        assert k in s
    assert set(res.headline) >= {
        "slider_angle_max_deg",
        "slider_angle_min_deg",
        "chamber_angle_max_deg",
        "chamber_angle_min_deg",
        "chamber_swing_deg",
        "piston_width_deg",
        "volume_cycles_per_rev",
        "power_strokes_per_rev",
        "max_plate_tilt_deg",
    }
    for v in s.values():
        assert isinstance(v, (int, float, str)) and not isinstance(v, np.generic)
    # columns: grid, consistency with the summary, derivative peaks
    assert all(np.shape(v) == (721,) for v in c.values())
    assert list(c)[0] == "theta_deg"
    assert c["theta_deg"][0] == 0.0 and c["theta_deg"][-1] == pytest.approx(360.0)
    assert c["slider_angle_deg"].max() == pytest.approx(amax, abs=1e-9)  # varphi = 0 on grid
    assert c["chamber_a_angle_deg"].min() == pytest.approx(amin - 45 - beta, abs=1e-9)
    np.testing.assert_allclose(
        c["rotor2_angle_deg"] - c["rotor1_angle_deg"], c["slider_angle_deg"], atol=1e-9
    )
    np.testing.assert_allclose(
        np.hypot(np.hypot(c["roller1_x_mm"], c["roller1_y_mm"]), c["roller1_z_mm"]), 50.0
    )
    np.testing.assert_allclose(c["roller1_x_mm"], c["groove1_x_mm"], atol=1e-12)
    peak = max(np.abs(c["rotor1_accel_per_rad"]).max(), np.abs(c["rotor2_accel_per_rad"]).max())
    assert s["rotor_accel_peak_per_rad"] == pytest.approx(peak, rel=2e-3)
    assert s["rotor_accel_peak_per_rad"] >= peak - 1e-12
    assert set(res.column_docs) == set(c)


def test_study_error_names():
    with pytest.raises(ParameterError, match=r"drive\.plate_tilt") as info:
        study.evaluate(_cfg(plate_tilt=70 * D))
    assert "65.53" in str(info.value)
    with pytest.raises(ParameterError, match=r"drive\.spin_ratio"):
        study.evaluate(_cfg(spin_ratio=0.3))
    cfg = _cfg()
    cfg["machine"]["compression_ratio"] = 2.0
    with pytest.raises(ParameterError, match=r"machine\.compression_ratio") as info:
        study.evaluate(cfg)
    assert info.value.name == "machine.compression_ratio"


def test_study_off_90deg_reports_both_kinds():
    res = study.evaluate(_cfg(roller_axis_angle=70 * D))
    s = res.summary
    assert s["chamber_swing_deg"] == pytest.approx(
        s["chamber_a_angle_max_deg"] - s["chamber_a_angle_min_deg"]
    )
    ratios = sorted([s["compression_ratio_a"], s["compression_ratio_b"]])
    assert ratios[1] == pytest.approx(10.0) and ratios[0] < 9.0
    assert s["chamber_angle_max_deg"] / s["chamber_angle_min_deg"] == pytest.approx(10.0)


@pytest.mark.slow
def test_plot_writes_pngs(tmp_path):
    for cfg in (_cfg(), _cfg(roller_axis_angle=70 * D, spin_ratio=-1.5)):
        paths = study.evaluate(cfg).write_figures(tmp_path)
        names = {p.name for p in paths}
        assert {
            "fig08_roller_trajectory.png",
            "fig09_groove_centreline.png",
            "fig10_chamber_angle.png",
            "fig_rotor_kinematics.png",
        } <= names
        for p in paths:
            assert p.exists() and p.stat().st_size > 10_000
            assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


# --------------------------------------------------------------------------------------------
# N pistons per rotor: eq. 18-22 generalised
# --------------------------------------------------------------------------------------------
def explicit_chambers_n(phi1, phi2, beta, n_p, gamma):
    """Place 2N pistons (N per rotor, 2 pi/N apart) and measure the 2N gaps minus the width."""
    k = np.arange(n_p) * 2 * np.pi / n_p
    pist = np.concatenate([phi1[..., None] + gamma + k, phi2[..., None] - gamma + k], -1)
    pist = np.sort(np.mod(pist, 2 * np.pi), -1)
    gaps = np.diff(np.concatenate([pist, pist[..., :1] + 2 * np.pi], -1), axis=-1)
    return np.sort(gaps - beta, -1)


def random_params_n(rng, n_p):
    lo, hi = np.pi / 2 - np.pi / n_p, np.pi / 2 + np.pi / n_p
    alpha = rng.uniform(lo + 0.02, hi - 0.02) if n_p > 2 else rng.uniform(0.2, np.pi - 0.2)
    lim = min(float(wc.max_plate_tilt(alpha, n_p)), 1.45)
    phi = rng.uniform(0.03, lim - 0.01)
    n = float(rng.choice([-3.0, -2.0, -1.5, -1.0, 1.0, 2.0]))
    return wc.WobbleCam(phi, alpha, n, 0.05, n_p)


@pytest.mark.parametrize("n_p", [2, 4, 6, 8, 12])
def test_piston_offset_from_eq18_19(n_p):
    """gamma = pi/4 - pi/(2N): the only offset for which eq. 19 holds for both kinds, i.e. kind B
    at the complementary slider angle pi - alpha' (eq. 18) is kind A at alpha'."""
    g = float(wc.piston_offset(n_p))
    assert g == pytest.approx(np.pi / 4 - np.pi / (2 * n_p), abs=1e-15)
    rng = np.random.default_rng(n_p)
    s, beta = rng.uniform(0.5, 2.5, 50), rng.uniform(0, 0.2)
    da, db = wc.chamber_angles(beta, s, pistons=n_p)
    np.testing.assert_allclose(db, wc.chamber_angles(beta, np.pi - s, pistons=n_p)[0], atol=1e-14)
    np.testing.assert_allclose(da + db + 2 * beta, 2 * np.pi / n_p, atol=1e-14)  # eq. 18
    lo, hi = wc.slider_angle_limits(n_p)
    assert (lo, hi) == pytest.approx((2 * g, 2 * np.pi / n_p + 2 * g))
    assert wc.chamber_count(n_p) == 2 * n_p
    if n_p == 4:
        assert g == wc.PISTON_OFFSET and (lo, hi) == pytest.approx((np.pi / 4, 3 * np.pi / 4))


@pytest.mark.parametrize("seed", range(6))
def test_chamber_angles_n_against_explicit_pistons(seed):
    rng = np.random.default_rng(1000 + seed)
    n_p = int(rng.choice([2, 4, 6, 8]))
    p = random_params_n(rng, n_p)
    beta = rng.uniform(0.0, 0.05)
    theta = rng.uniform(-5, 5, 100)
    q = wc.rotor_angles(p, theta)[0]
    da, db = wc.chamber_angles(beta, q[1] - q[0], pistons=n_p)
    ours = np.sort(
        np.concatenate([np.repeat(da[:, None], n_p, 1), np.repeat(db[:, None], n_p, 1)], 1), 1
    )
    g = np.pi / 4 - np.pi / (2 * n_p)
    np.testing.assert_allclose(ours, explicit_chambers_n(q[0], q[1], beta, n_p, g), atol=1e-9)


@pytest.mark.parametrize("n_p", [2, 6, 8])
@pytest.mark.parametrize("alpha_frac", [0.15, 0.4, 0.5, 0.7, 0.9])
def test_max_plate_tilt_n_by_root_finding(n_p, alpha_frac):
    """Eq. 20 with N: alpha'_max <= pi/2 + pi/N, alpha'_min >= pi/2 - pi/N, solved on eq. 15."""
    lo, hi = np.pi / 2 - np.pi / n_p, np.pi / 2 + np.pi / n_p
    alpha = lo + alpha_frac * (hi - lo)
    got = float(wc.max_plate_tilt(alpha, n_p))
    if n_p == 2:
        assert got == pytest.approx(np.pi / 2, abs=1e-12)  # no limit before the geometric one
        return
    f_max = optimize.brentq(
        lambda p: eq15_printed(0.0, p, alpha) - hi, 1e-9, np.pi / 2 - 1e-9, xtol=1e-14
    )
    f_min = optimize.brentq(
        lambda p: eq15_printed(np.pi / 2, p, alpha) - lo, 1e-9, np.pi / 2 - 1e-9, xtol=1e-14
    )
    assert got == pytest.approx(min(f_max, f_min), abs=1e-9)
    # at the limit the centre lines of two neighbouring pistons just touch (zero-width pistons)
    p = wc.WobbleCam(got - 1e-12, alpha, -2.0, 0.05, n_p)
    q = wc.rotor_angles(p, np.linspace(0, np.pi, 20001))[0]
    gaps = explicit_chambers_n(q[0], q[1], 0.0, n_p, np.pi / 4 - np.pi / (2 * n_p))
    assert gaps.min() == pytest.approx(0.0, abs=1e-6)


@pytest.mark.parametrize("seed", range(6))
def test_piston_layout_n_against_dense_simulation(seed):
    rng = np.random.default_rng(1100 + seed)
    n_p = int(rng.choice([2, 6, 8]))
    p = random_params_n(rng, n_p)
    eps = wc.min_compression_ratio(p) * rng.uniform(1.05, 5.0)
    lay = wc.piston_layout(p, eps)
    assert lay.piston_width > 0
    q = wc.rotor_angles(p, np.linspace(0, np.pi, 20001))[0]
    g = np.pi / 4 - np.pi / (2 * n_p)
    ch = explicit_chambers_n(q[0], q[1], lay.piston_width, n_p, g)
    da, db = wc.chamber_angles(lay.piston_width, q[1] - q[0], pistons=n_p)
    tight = {"A": da, "B": db}[lay.design_kind]
    assert tight.min() == pytest.approx(ch.min(), abs=1e-9)
    assert tight.max() / tight.min() == pytest.approx(eps, rel=1e-6)


@pytest.mark.parametrize("n_p", [2, 4, 6, 8])
def test_eq21_generalised_at_90deg(n_p):
    """beta = (eps+1)/(eps-1) alpha'_min - (pi + (eps-1)(pi/2 - pi/N))/(eps-1); N = 4 is eq. 21."""
    lim = float(wc.max_plate_tilt(np.pi / 2, n_p))
    phi = min(0.7 * lim, 1.2)
    p = wc.WobbleCam(phi, np.pi / 2, -2.0, 0.05, n_p)
    eps = wc.min_compression_ratio(p) * 2.0
    amin = eq15_printed(np.pi / 2, phi, np.pi / 2)
    beta = (eps + 1) / (eps - 1) * amin - (np.pi + (eps - 1) * (np.pi / 2 - np.pi / n_p)) / (
        eps - 1
    )
    assert wc.piston_layout(p, eps).piston_width == pytest.approx(beta, abs=1e-12)


@pytest.mark.parametrize("n_p", [2, 4, 6])
def test_power_strokes_with_n(n_p):
    p = wc.WobbleCam(0.3, np.pi / 2, -2.0, 0.05, n_p)
    assert wc.power_strokes_per_rev(p) == 2 * n_p * 4 // 2


@pytest.mark.parametrize("bad", [3, 0, -2, 1, 4.0, True, "4"])
def test_pistons_per_rotor_errors(bad):
    with pytest.raises(ParameterError, match="pistons_per_rotor") as info:
        wc.WobbleCam(0.5, pistons_per_rotor=bad)
    assert info.value.name == "pistons_per_rotor" and "even" in str(info.value)


def test_roller_axis_and_tilt_ranges_follow_n():
    with pytest.raises(ParameterError, match="roller_axis_angle") as info:
        wc.WobbleCam(0.3, 55 * D, pistons_per_rotor=6)
    assert "60 deg" in str(info.value) and "120 deg" in str(info.value)
    wc.WobbleCam(0.3, 65 * D, pistons_per_rotor=6)
    wc.WobbleCam(80 * D, 10 * D, pistons_per_rotor=2)  # N = 2: any tilt below 90 deg
    with pytest.raises(ParameterError, match="plate_tilt") as info:
        wc.WobbleCam(56 * D, pistons_per_rotor=6)
    assert "54.74 deg" in str(info.value) and "6 pistons per rotor" in str(info.value)
    # default N = 4 is unchanged
    assert wc.WobbleCam(0.5).pistons_per_rotor == 4
    s = np.linspace(1.0, 2.0, 5)
    np.testing.assert_array_equal(wc.chamber_angles(0.1, s), wc.chamber_angles(0.1, s, pistons=4))
    assert float(wc.max_plate_tilt(1.2)) == float(wc.max_plate_tilt(1.2, 4))


def test_spin_correction_derivatives_match_finite_differences():
    """Corrected spin law varphi = n theta + sum a_k cos k theta + b_k sin k theta: exact
    derivatives against central differences (h = 1e-4: error ~ h^2 |f'''''| ~ 1e-7)."""
    p = wc.WobbleCam(np.radians(45.0), spin_a=(0.0, 0.0, 0.0, 0.1), spin_b=(0.02, 0.0, 0.05))
    t = np.random.default_rng(7).uniform(0.0, 2.0 * np.pi, 50)
    h = 1e-4
    f = [wc.spin_law(p, t + k * h)[0] for k in (-2, -1, 0, 1, 2)]
    v, d1, d2, d3 = wc.spin_law(p, t)
    manual = -2.0 * t + 0.1 * np.cos(4 * t) + 0.02 * np.sin(t) + 0.05 * np.sin(3 * t)
    np.testing.assert_allclose(v, manual, rtol=0, atol=1e-14)
    np.testing.assert_allclose(d1, (f[3] - f[1]) / (2 * h), rtol=0, atol=5e-8)
    np.testing.assert_allclose(d2, (f[3] - 2 * f[2] + f[1]) / h**2, rtol=0, atol=1e-5)
    g = [wc.spin_law(p, t + k * 2e-3)[0] for k in (-2, -1, 1, 2)]  # larger step: roundoff/h^3
    d3_fd = (g[3] - 2 * g[2] + 2 * g[1] - g[0]) / (2 * 2e-3**3)
    np.testing.assert_allclose(d3, d3_fd, rtol=0, atol=2e-4)
    # the rotor angles under the corrected law are those of the linear-law formula at varphi
    q = wc.rotor_angles(p, t)[0]
    q_ref = wc.rotor_angles_from_spin(
        p.plate_tilt, p.roller_axis_angle, (v, v * 0 + 1, v * 0, v * 0), t
    )[0]
    np.testing.assert_allclose(q, q_ref, rtol=0, atol=1e-12)


def test_spin_correction_that_reverses_the_spin_is_refused():
    with pytest.raises(ParameterError, match="spin_a"):
        wc.WobbleCam(np.radians(45.0), spin_a=(0.0, 0.0, 0.0, 1.0))  # 4 * 1.0 > |n| = 2


@pytest.mark.parametrize(
    ("kwargs", "name", "admissible"),
    [
        # coefficients that are not numbers: named, whatever the law would do
        ({"spin_b": (0.0, float("nan"))}, "spin_b", "finite coefficients"),
        ({"spin_a": (float("inf"),), "spin_b": (0.1,)}, "spin_a", "finite coefficients"),
        # a field before the law in the order of checking is named first
        ({"spin_a": (float("nan"),), "plate_tilt": 70 * D}, "plate_tilt", "eq. 20"),
        ({"spin_a": (0.0, 0.0, 0.0, 1.0), "spin_ratio": 0.3}, "spin_ratio", "multiple of 0.5"),
        ({"spin_a": (0.0, 0.0, 0.0, 1.0)}, "spin_a", "monotone"),
    ],
)
def test_spin_correction_errors_in_order(kwargs, name, admissible):
    kwargs = {"plate_tilt": 45 * D, **kwargs}
    with pytest.raises(ParameterError) as info:
        wc.WobbleCam(**kwargs)
    assert info.value.name == name and admissible in str(info.value), str(info.value)


# --------------------------------------------------------------------------------------------
# one source of defaults: the schema
# --------------------------------------------------------------------------------------------
def _schema_defaults() -> dict:
    """Every section of a minimal wobble_cam config, parsed through the schema (SI)."""
    from rotorkin.core.schema import validate_model
    from rotorkin.drives.wobble_cam.schema import WobbleConfig

    return validate_model(WobbleConfig, {"drive": {"type": "wobble_cam", "plate_tilt": "45 deg"}})


def _dataclass_defaults(cls) -> dict:
    from dataclasses import MISSING, fields

    out = {}
    for f in fields(cls):
        if f.default is not MISSING:
            out[f.name] = f.default
        elif f.default_factory is not MISSING:
            out[f.name] = f.default_factory()
    return out


def test_every_dataclass_default_is_the_schema_default():
    """WobbleCam, TwinRotor, SphericalCam and IdealCycle defaults equal the config's (SI)."""
    from rotorkin.analysis.engine_cycle import IdealCycle
    from rotorkin.drives.wobble_cam.cam import SphericalCam
    from rotorkin.machines.twin_rotor import TwinRotor

    cfg = _schema_defaults()
    # the study builds WobbleCam.pistons_per_rotor from machine.pistons_per_rotor
    sections = {
        wc.WobbleCam: {**cfg["drive"], "pistons_per_rotor": cfg["machine"]["pistons_per_rotor"]},
        TwinRotor: cfg["machine"],
        SphericalCam: cfg["cam"],
        IdealCycle: cfg["loads"],
    }
    mismatched = []
    for cls, section in sections.items():
        for name, ours in _dataclass_defaults(cls).items():
            assert name in section, f"{cls.__name__}.{name} has no config key"
            theirs = section[name]
            if ours is None or theirs is None:  # a size derived from the others
                same = ours is None and theirs is None
            elif isinstance(ours, (tuple, list)):
                same = tuple(ours) == tuple(theirs)
            elif isinstance(ours, str):
                same = ours == theirs
            else:
                same = float(ours) == pytest.approx(float(theirs), rel=1e-15, abs=0.0)
            if not same:
                mismatched.append(f"{cls.__name__}.{name} = {ours!r}, schema {theirs!r}")
    assert not mismatched, "; ".join(mismatched)


def test_study_keeps_the_rotor_motion_on_the_column_grid():
    """StudyResult.motion: rotor 1 and rotor 2 over one turn, on the angles of the columns."""
    res = study.evaluate(_cfg())
    m = res.motion
    assert m.members == ("rotor 1", "rotor 2") and m.unit == "rad"
    theta = np.radians(res.columns["theta_deg"])
    np.testing.assert_allclose(m.theta, theta, rtol=0, atol=1e-12)
    assert m.theta[0] == 0.0 and m.theta[-1] == pytest.approx(2 * np.pi, abs=1e-12)
    for k in (0, 1):
        np.testing.assert_allclose(np.degrees(m.q[k]), res.columns[f"rotor{k + 1}_angle_deg"])
        np.testing.assert_allclose(m.dq[k], res.columns[f"rotor{k + 1}_speed_ratio"])
        np.testing.assert_allclose(m.d2q[k], res.columns[f"rotor{k + 1}_accel_per_rad"])


def test_batch_peaks_of_a_corrected_spin_law_are_the_studys():
    """The batch module evaluates a corrected spin law with the study's own functions."""
    from rotorkin.core.batch import Designs
    from rotorkin.drives.wobble_cam import sweep
    from rotorkin.io.config import load_config

    sets = ["drive.spin_a=[0.05, 0.02]", "drive.spin_b=[0.01]", "drive.plate_tilt=50 deg"]
    cfg = load_config(None, "wobble-cam-engine", sets)[0]
    names = ["rotor_accel_peak_per_rad", "rotor_jerk_peak_per_rad2"]
    names += ["rotor_speed_ratio_min", "rotor_speed_ratio_max"]
    got = sweep.metrics(Designs(cfg, {"drive.plate_tilt": np.radians([50.0])}, 1), names, 20001)
    want = study.evaluate(cfg).summary
    for k in names:
        assert got[k][0] == pytest.approx(want[k], rel=1e-12), k
