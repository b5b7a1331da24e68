"""The fused fast path of the wobble-cam kinematics against the reference formulas.

The reference is written out here, independently of the fast kernel: the
projected angle ``E(u) = u + atan2`` of the plate radius rotated by ``-u``
(``rotorkin.core.angles.angle_near``), its derivatives from
``D = (1 + c^2)/2 - (1 - c^2)/2 cos 2u`` as in the paper note, and the chain
rule (Faa di Bruno) through the spin law, on whole arrays with broadcasting.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.core import fused as fused_core
from rotorkin.core.errors import ParameterError
from rotorkin.drives.wobble_cam import chambers as wobble_chambers
from rotorkin.drives.wobble_cam import fast as wobble_kernel
from rotorkin.drives.wobble_cam import kinematics as wc

TOL = 1e-12


def ref_projected(u, phi):
    """E, E', E'', E''' of E(u) = atan2(sin u, cos(phi) cos u) on the branch through u."""
    c = np.cos(phi)
    su, cu = np.sin(u), np.cos(u)
    y, x = su, c * cu
    e0 = u + np.arctan2(y * np.cos(u) - x * np.sin(u), x * np.cos(u) + y * np.sin(u))
    d0 = 0.5 * (1 + c * c) - 0.5 * (1 - c * c) * np.cos(2 * u)
    d1 = (1 - c * c) * np.sin(2 * u)
    d2 = 2 * (1 - c * c) * np.cos(2 * u)
    return e0, c / d0, -c * d1 / d0**2, -c * d2 / d0**2 + 2 * c * d1**2 / d0**3


def ref_rotors(theta, spin, phi, alpha):
    """(4, 2, ...) reference: Phi_k = theta + E(varphi -+ alpha/2), chain rule to order 3."""
    theta = np.asarray(theta, dtype=float)
    v, g1, g2, g3 = (np.asarray(s, dtype=float) for s in spin)
    out = []
    for s in (-1.0, 1.0):
        e0, e1, e2, e3 = ref_projected(v + s * 0.5 * np.asarray(alpha), phi)
        out.append(
            [
                theta + e0,
                1 + e1 * g1,
                e2 * g1**2 + e1 * g2,
                e3 * g1**3 + 3 * e2 * g1 * g2 + e1 * g3,
            ]
        )
    shape = np.broadcast_shapes(*(np.shape(a) for k in out for a in k))
    return np.stack(
        [np.stack([np.broadcast_to(out[k][i], shape) for k in (0, 1)]) for i in range(4)]
    )


def linear(n, theta):
    theta = np.asarray(theta, dtype=float)
    return n * theta, n + 0 * theta, 0 * theta, 0 * theta


def corrected(theta, n=-2.0, a=0.15, k=3.0, b=0.7):
    theta = np.asarray(theta, dtype=float)
    s, c = np.sin(k * theta + b), np.cos(k * theta + b)
    return n * theta + a * s, n + a * k * c, -a * k * k * s, -a * k**3 * c


def close(fast, ref):
    """|fast - ref| <= 1e-12 * max(1, max |ref|), per derivative order."""
    fast, ref = np.asarray(fast), np.asarray(ref)
    assert fast.shape == ref.shape
    for i in range(fast.shape[0]):
        scale = max(1.0, float(np.max(np.abs(ref[i]), initial=0.0)))
        np.testing.assert_allclose(fast[i], ref[i], rtol=0, atol=TOL * scale, err_msg=f"order {i}")


SHAPES = [(), (257,), (3, 4, 5)]


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("seed", range(3))
def test_linear_law_equals_reference(shape, seed):
    rng = np.random.default_rng(seed)
    alpha = rng.uniform(np.pi / 4 + 0.05, 3 * np.pi / 4 - 0.05)
    phi = rng.uniform(0.02, float(wc.max_plate_tilt(alpha)) - 0.01)
    n = float(rng.choice([-3.0, -2.0, -1.5, -0.5, 1.0, 2.5]))
    theta = rng.uniform(-8, 8, shape)
    p = wc.WobbleCam(phi, alpha, n)
    fast = np.stack(wc.rotor_angles(p, theta))
    assert fast.shape == (4, 2, *shape)
    close(fast, ref_rotors(theta, linear(n, theta), phi, alpha))
    # the same through the 4-array form of the spin law
    close(np.stack(wc.rotor_angles_from_spin(phi, alpha, linear(n, theta), theta)), fast)


@pytest.mark.parametrize("shape", SHAPES)
def test_corrected_spin_law_equals_reference(shape):
    rng = np.random.default_rng(11)
    theta = rng.uniform(-5, 5, shape)
    phi, alpha = 0.7, 1.3
    fast = np.stack(wc.rotor_angles_from_spin(phi, alpha, corrected(theta), theta))
    close(fast, ref_rotors(theta, corrected(theta), phi, alpha))
    # and through WobbleCam's spin_a / spin_b: varphi = -2 theta + 0.1 cos 2 theta + 0.05 sin theta
    p = wc.WobbleCam(phi, alpha, -2.0, spin_a=(0.0, 0.1), spin_b=(0.05,))
    spin = (
        -2 * theta + 0.1 * np.cos(2 * theta) + 0.05 * np.sin(theta),
        -2 - 0.2 * np.sin(2 * theta) + 0.05 * np.cos(theta),
        -0.4 * np.cos(2 * theta) - 0.05 * np.sin(theta),
        0.8 * np.sin(2 * theta) - 0.05 * np.cos(theta),
    )
    close(np.stack(wc.rotor_angles(p, theta)), ref_rotors(theta, spin, phi, alpha))


def test_broadcast_design_arrays_equal_reference():
    """Tilt and roller axis angle per design (rows) against shaft angles (columns)."""
    rng = np.random.default_rng(5)
    theta = np.linspace(0, 2 * np.pi, 301)
    alpha = rng.uniform(1.0, 2.1, (40, 1))
    phi = rng.uniform(0.05, 0.9, (40, 1))
    fast = np.stack(wc.rotor_angles_from_spin(phi, alpha, corrected(theta), theta))
    assert fast.shape == (4, 2, 40, 301)
    close(fast, ref_rotors(theta, corrected(theta), phi, alpha))
    # full-shape design arrays take the plain-slice path, not the nditer one
    t2, p2, a2 = (np.ascontiguousarray(np.broadcast_to(x, (40, 301))) for x in (theta, phi, alpha))
    fast_full = np.stack(wc.rotor_angles_from_spin(p2, a2, corrected(t2), t2))
    np.testing.assert_array_equal(fast_full, fast)
    rot, cham = wobble_kernel.rotor_kinematics(phi, alpha, -1.5, theta, chamber=(0.1, 6))
    close(rot, ref_rotors(theta, linear(-1.5, theta), phi, alpha))
    slider = rot[0, 1] - rot[0, 0]
    close(cham, np.stack(wc.chamber_angles(0.1, slider, pistons=6)))


@pytest.mark.parametrize("shape", SHAPES)
def test_kinematics_chambers_equal_reference(shape):
    p = wc.WobbleCam(np.radians(45), np.radians(90), -2.0)
    beta = wc.piston_layout(p, 10.0).piston_width
    theta = np.random.default_rng(3).uniform(0, 2 * np.pi, shape)
    k = wc.kinematics(p, theta, beta)
    ref = ref_rotors(theta, linear(-2.0, theta), p.plate_tilt, p.roller_axis_angle)
    close(np.stack([k.q, k.dq, k.d2q, k.d3q]), ref)
    # eq. 19 and 18 written out: delta_A = alpha' - 2 gamma - beta, delta_B = pi/2 + 2 gamma - ...
    slider = ref[0, 1] - ref[0, 0]
    gamma = np.pi / 8
    close(
        np.stack([k.chamber_a, k.chamber_b]),
        np.stack([slider - 2 * gamma - beta, np.pi / 2 + 2 * gamma - slider - beta]),
    )
    np.testing.assert_array_equal(k.slider, k.q[1] - k.q[0])
    assert k.chamber_a.shape == np.shape(theta)


def test_bitwise_independent_of_shape_blocks_threads_and_strides():
    """Each value depends on its own point only: shape, block cuts, threads, strides."""
    p = wc.WobbleCam(0.6, 1.4, -1.5)
    size = 8 * wobble_kernel.BLOCK + 1234  # several blocks, a ragged last one, 2 threads used
    theta = np.random.default_rng(9).uniform(-6, 6, size)
    one = wc.kinematics(p, theta, 0.2, threads=1)
    two = wc.kinematics(p, theta, 0.2, threads=2)
    for name in ("q", "dq", "d2q", "d3q", "chamber_a", "chamber_b"):
        np.testing.assert_array_equal(getattr(two, name), getattr(one, name), err_msg=name)
    q1 = np.stack(wc.rotor_angles(p, theta, threads=1))
    # a 3-d view, Fortran order, reversed strides, one point at a time
    t3 = theta[: 6 * 7 * 11].reshape(6, 7, 11)
    q3 = np.stack(wc.rotor_angles(p, np.asfortranarray(t3)))
    np.testing.assert_array_equal(q3.reshape(4, 2, -1), q1[..., : t3.size])
    rev = np.stack(wc.rotor_angles(p, theta[::-3]))
    np.testing.assert_array_equal(rev, q1[..., ::-3])
    for i in (0, 1, 4097, size - 1):
        np.testing.assert_array_equal(np.stack(wc.rotor_angles(p, theta[i])), q1[..., i])


def test_zero_tilt_and_empty_input():
    """phi = 0: E(u) = u, no division warning (filterwarnings = error); empty arrays."""
    theta = np.linspace(-3, 3, 11)
    rot, _ = wobble_kernel.rotor_kinematics(0.0, 1.2, -2.0, theta)
    np.testing.assert_allclose(rot[0, 0], theta - 2 * theta - 0.6, atol=1e-15)
    np.testing.assert_allclose(rot[1], -1.0, atol=1e-15)
    np.testing.assert_allclose(rot[2:], 0.0, atol=1e-15)
    rot, cham = wobble_kernel.rotor_kinematics(0.5, 1.5, -2.0, np.empty((0, 3)), chamber=(0.1, 4))
    assert rot.shape == (4, 2, 0, 3) and cham.shape == (2, 0, 3)


def test_thread_count_checked(monkeypatch):
    p = wc.WobbleCam(0.6)
    monkeypatch.setenv(wobble_kernel.THREADS_ENV, "two")
    with pytest.raises(ParameterError, match="ROTORKIN_THREADS"):
        wc.rotor_angles(p, np.zeros(3))
    monkeypatch.setenv(wobble_kernel.THREADS_ENV, "2")
    assert wobble_kernel.default_threads() == 2
    monkeypatch.delenv(wobble_kernel.THREADS_ENV)
    assert wobble_kernel.default_threads() == 1
    with pytest.raises(ParameterError, match="threads"):
        wc.rotor_angles(p, np.zeros(3), threads=0)
    with pytest.raises(ValueError, match="4 arrays"):
        wobble_kernel.rotor_kinematics(0.5, 1.5, (0.0, 1.0), 0.0)


def test_pool_recreated_after_fork(monkeypatch):
    """A pool inherited through fork() has no threads: a new one is made for the new pid."""
    p = wc.WobbleCam(0.6)
    theta = np.linspace(0, 1, 10 * wobble_kernel.BLOCK)
    ref = np.stack(wc.rotor_angles(p, theta, threads=1))
    wc.rotor_angles(p, theta, threads=2)
    size, _ = fused_core._POOL_KEY  # the thread pool the kernels share
    monkeypatch.setattr(fused_core, "_POOL_KEY", (size, -1))
    np.testing.assert_array_equal(np.stack(wc.rotor_angles(p, theta, threads=2)), ref)
    assert fused_core._POOL_KEY[1] > 0


def test_split_modules_export_everything():
    """wobble_cam re-exports the chamber module's names: no caller has to change."""
    for name in wobble_chambers.__all__:
        assert getattr(wc, name) is getattr(wobble_chambers, name), name
        assert name in wc.__all__, name


def test_spin_angles_at_the_poles_of_tan():
    """sin 2 varphi, cos 2 varphi come from tan varphi: varphi at (and next to) pi/2 + k pi."""
    n = -2.0
    poles = (np.pi / 2 + np.arange(-4, 4) * np.pi) / n
    quarter = (np.pi / 4 + np.arange(-4, 4) * np.pi / 2) / n
    base = np.concatenate([poles, quarter, [0.0]])
    theta = np.concatenate([base, np.nextafter(base, 9.0), np.nextafter(base, -9.0)])
    for phi, alpha in ((0.3, 1.2), (np.radians(45), np.pi / 2), (1.1, 1.9)):
        fast = np.stack(wc.rotor_angles_from_spin(phi, alpha, n, theta))
        close(fast, ref_rotors(theta, linear(n, theta), phi, alpha))
        assert np.all(np.isfinite(fast))


def test_results_into_given_arrays():
    theta = np.linspace(0, 6, 5000).reshape(50, 100)
    new = wobble_kernel.rotor_kinematics(0.7, 1.5, -2.0, theta, chamber=(0.2, 4))
    out = (np.full((4, 2, 50, 100), np.nan), np.full((2, 50, 100), np.nan))
    got = wobble_kernel.rotor_kinematics(0.7, 1.5, -2.0, theta, chamber=(0.2, 4), out=out)
    assert got[0] is out[0] and got[1] is out[1]
    np.testing.assert_array_equal(out[0], new[0])
    np.testing.assert_array_equal(out[1], new[1])
    with pytest.raises(ValueError, match=r"out\[0\]"):
        wobble_kernel.rotor_kinematics(0.7, 1.5, -2.0, theta, out=(np.empty((4, 2, 100, 50)), None))
    with pytest.raises(ValueError, match=r"out\[1\]"):
        bad = np.empty((2, 50, 100), dtype=np.float32)
        wobble_kernel.rotor_kinematics(0.7, 1.5, -2.0, theta, chamber=(0.2, 4), out=(out[0], bad))
