"""Property tests of the rhomboid drive's physics (hypothesis).

Relations tested, exact in the model (the paper's eq. 9, 10, 13, 15, 21):

* Broadcasting: every function gives, for parameter arrays against angle arrays of
  any shape (0-d, 1-d, 3-d, and ``(n, 1)`` parameters against ``(m,)`` angles), the
  element-wise results of scalar calls.
* Period: ``psi(alpha + pi) = psi(alpha)`` (only harmonics ``cos 2k alpha``,
  ``sin 2k alpha``), and the blade pairs advance by exactly half a turn per period,
  ``phi_i(alpha + pi) = phi_i(alpha) + pi``.
* Odd harmonics only (k = 1, 3, 5, ...): a quarter turn changes the sign of every
  term, ``cos 2k(alpha + pi/2) = -cos 2k alpha``, so
  ``psi(alpha + pi/2) = pi - psi(alpha)`` (half-period antisymmetry about pi/2,
  eq. 10) and ``psi^(n)(alpha + pi/2) = -psi^(n)(alpha)`` for n = 1, 2, 3.
* The two blade pairs (``phi_1,2 = alpha +- psi/2``, eq. 21): after a quarter turn
  they trade places, ``phi_1(alpha + pi/2) = phi_2(alpha) + pi`` and
  ``phi_2(alpha + pi/2) = phi_1(alpha)``, with the same relations for every
  derivative (without the ``+ pi``); their mean turns uniformly,
  ``phi_1 + phi_2 = 2 alpha``.
* Mirror: ``psi(-alpha; a, b) = psi(alpha; a, -b)`` (cosines even, sines odd; eq. 15
  flips ``b_1`` with the ``b_k``).

The independent model is eq. 13 summed term by term with ``a_1``, ``b_1`` solved from
eq. 15 here.
"""

from __future__ import annotations

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.machines import rotary_blade as rb

PROPS = settings(max_examples=40, deadline=None)


def same(x, y):
    """Equal to rounding (array and scalar calls may sum in another order, a few ulps)."""
    np.testing.assert_allclose(x, y, rtol=1e-13, atol=1e-13)


psi_mins = st.floats(0.05, np.pi / 2 - 0.05)
lengths = st.floats(0.02, 0.5)
coeffs = st.lists(st.floats(-0.08, 0.08), max_size=3).map(tuple)
angles = st.floats(-10.0, 10.0)
shapes = st.sampled_from([(), (5,), (2, 3, 4)])


def psi_series(psi_min, a, b, alpha):
    """Eq. 13 term by term; ``a_1``, ``b_1`` from eq. 15 (independent of the library)."""
    alpha = np.asarray(alpha, dtype=float)
    a1 = np.pi / 2 - psi_min - sum(a)
    b1 = -sum((2 * i + 3) * bk for i, bk in enumerate(b))
    out = np.pi / 2 + a1 * np.cos(2 * alpha) + b1 * np.sin(2 * alpha)
    for i, ak in enumerate(a):
        out = out + ak * np.cos(2 * (2 * i + 3) * alpha)
    for i, bk in enumerate(b):
        out = out + bk * np.sin(2 * (2 * i + 3) * alpha)
    return out


def _angle_array(draw, shape):
    return draw(hnp.arrays(float, shape, elements=angles))


# --- broadcasting -------------------------------------------------------------------------
@PROPS
@given(st.data(), shapes, psi_mins, lengths, coeffs, coeffs)
def test_angle_arrays_of_any_shape_equal_scalar_calls(data, shape, pm, L, a, b):
    alpha = _angle_array(data.draw, shape)
    psi = rc.psi_law(pm, a, b, alpha)
    rho = rc.profile_radius(L, pm, a, b, alpha)
    phi = rc.blade_angles(pm, a, b, alpha)
    verts = rc.rhombus_vertices(L, pm, a, b, alpha)
    assert all(x.shape == shape for x in psi + rho)
    assert all(x.shape == (2, *shape) for x in phi)
    assert verts.shape == (4, 2, *shape)
    flat = np.asarray(alpha).reshape(-1)
    for i, al in enumerate(flat):
        idx = np.unravel_index(i, shape) if shape else ()
        one = rc.psi_law(pm, a, b, float(al))
        for n in range(4):
            same(psi[n][idx], one[n])
        same(rho[0][idx], rc.profile_radius(L, pm, a, b, float(al))[0])
        same(phi[1][(slice(None), *idx)], rc.blade_angles(pm, a, b, al)[1])
    np.testing.assert_allclose(psi[0], psi_series(pm, a, b, alpha), rtol=0, atol=1e-12)


@PROPS
@given(
    hnp.arrays(float, st.integers(1, 6), elements=psi_mins),
    hnp.arrays(float, st.integers(1, 7), elements=angles),
    lengths,
)
def test_parameter_arrays_against_angle_arrays(pms, alpha, L):
    """``psi_min`` and ``link_length`` shape (n, 1) against ``alpha`` (m,): (n, m)."""
    Ls = L * (1.0 + np.arange(pms.size))[:, None]
    pm = pms[:, None]
    psi = rc.psi_law(pm, (), (), alpha)
    rho = rc.profile_radius(Ls, pm, (), (), alpha)
    kappa = rc.profile_curvature(Ls, pm, (), (), alpha)
    torque = rc.shaft_torque(pm, (), (), 100.0, 40.0, alpha)
    stroke = rc.stroke_direction(pm, (), (), alpha)
    for x in (*psi, *rho, kappa, torque, stroke):
        assert x.shape == (pms.size, alpha.size)
    for i in range(pms.size):
        for j in range(alpha.size):
            args = (float(pm[i, 0]), (), (), float(alpha[j]))
            same(psi[1][i, j], rc.psi_law(*args)[1])
            same(rho[2][i, j], rc.profile_radius(float(Ls[i, 0]), *args)[2])
            same(kappa[i, j], rc.profile_curvature(float(Ls[i, 0]), *args))
            same(torque[i, j], rc.shaft_torque(args[0], (), (), 100.0, 40.0, args[3]))
            assert stroke[i, j] == rc.stroke_direction(*args)
    np.testing.assert_allclose(psi[0], psi_series(pm, (), (), alpha), rtol=0, atol=1e-12)


@PROPS
@given(st.data(), shapes, psi_mins)
def test_machine_chambers_follow_the_blade_pairs_for_any_shape(data, shape, pm):
    alpha = _angle_array(data.draw, shape)
    m = rb.RotaryBlade(0.05, 0.03, 0.09, 0.05, 2)
    q = rc.motion(rc.RhomboidCam(0.12, pm), alpha).q
    v = rb.chamber_volumes(m, q)
    assert v.shape == (4, *shape)
    psi = rc.psi_law(pm, (), (), alpha)[0]
    k = 0.5 * (0.09**2 - 0.03**2) * 0.05
    # even chambers: psi - t, odd: pi - psi - t (B = 2), sector volume k per radian
    np.testing.assert_allclose(v[0], k * (psi - 0.05), rtol=1e-12, atol=1e-16)
    np.testing.assert_allclose(v[3], k * (np.pi - psi - 0.05), rtol=1e-12, atol=1e-16)


# --- periodicity ----------------------------------------------------------------------------
@PROPS
@given(psi_mins, coeffs, coeffs, hnp.arrays(float, 6, elements=angles))
def test_period_pi(pm, a, b, alpha):
    assert rc.period(rc.RhomboidCam(0.1, pm)) == np.pi
    now, later = rc.psi_law(pm, a, b, alpha), rc.psi_law(pm, a, b, alpha + np.pi)
    scale = 1.0 + sum(abs(x) for x in a + b) * 14**3
    for n in range(4):
        np.testing.assert_allclose(later[n], now[n], rtol=0, atol=1e-11 * scale)
    phi, phi_later = rc.blade_angles(pm, a, b, alpha), rc.blade_angles(pm, a, b, alpha + np.pi)
    np.testing.assert_allclose(phi_later[0], phi[0] + np.pi, rtol=0, atol=1e-11)
    for n in (1, 2, 3):
        np.testing.assert_allclose(phi_later[n], phi[n], rtol=0, atol=1e-11 * scale)


# --- symmetry -------------------------------------------------------------------------------
@PROPS
@given(psi_mins, coeffs, coeffs, hnp.arrays(float, 6, elements=angles))
def test_quarter_turn_antisymmetry_of_the_odd_harmonic_law(pm, a, b, alpha):
    now, quarter = rc.psi_law(pm, a, b, alpha), rc.psi_law(pm, a, b, alpha + np.pi / 2)
    scale = 1.0 + sum(abs(x) for x in a + b) * 14**3
    np.testing.assert_allclose(quarter[0], np.pi - now[0], rtol=0, atol=1e-11)  # eq. 10
    for n in (1, 2, 3):
        np.testing.assert_allclose(quarter[n], -now[n], rtol=0, atol=1e-11 * scale)
    # the pitch curve: rho(alpha + pi/2) = 2l sin(psi(alpha)/2), the form of eq. 19
    np.testing.assert_allclose(
        rc.profile_radius(0.1, pm, a, b, alpha + np.pi / 2)[0],
        rc.profile_radius_eq19(0.1, pm, a, b, alpha),
        rtol=0,
        atol=1e-12,
    )


@PROPS
@given(psi_mins, coeffs, coeffs, hnp.arrays(float, 6, elements=angles))
def test_blade_pairs_trade_places_after_a_quarter_turn(pm, a, b, alpha):
    phi = rc.blade_angles(pm, a, b, alpha)
    quarter = rc.blade_angles(pm, a, b, alpha + np.pi / 2)
    np.testing.assert_allclose(quarter[0][0], phi[0][1] + np.pi, rtol=0, atol=1e-11)
    np.testing.assert_allclose(quarter[0][1], phi[0][0], rtol=0, atol=1e-11)
    scale = 1.0 + sum(abs(x) for x in a + b) * 14**3
    for n in (1, 2, 3):
        np.testing.assert_allclose(quarter[n][0], phi[n][1], rtol=0, atol=1e-11 * scale)
        np.testing.assert_allclose(quarter[n][1], phi[n][0], rtol=0, atol=1e-11 * scale)
    # the mean of the two pairs turns with the shaft
    np.testing.assert_allclose(phi[0][0] + phi[0][1], 2 * alpha, rtol=0, atol=1e-12)
    np.testing.assert_allclose(phi[1][0] + phi[1][1], 2.0, rtol=0, atol=1e-12)


@PROPS
@given(psi_mins, coeffs, coeffs, hnp.arrays(float, 6, elements=angles))
def test_mirror_flips_the_sine_coefficients(pm, a, b, alpha):
    minus_b = tuple(-x for x in b)
    np.testing.assert_allclose(
        rc.psi_law(pm, a, b, -alpha)[0], rc.psi_law(pm, a, minus_b, alpha)[0], atol=1e-12
    )
    np.testing.assert_allclose(
        rc.psi_law(pm, a, b, -alpha)[1], -rc.psi_law(pm, a, minus_b, alpha)[1], atol=1e-10
    )


@PROPS
@given(psi_mins, lengths, coeffs, coeffs, hnp.arrays(float, 4, elements=angles))
def test_all_four_rollers_on_the_pitch_curve(pm, L, a, b, alpha):
    """Vertex k of the rhombus lies at polar angle alpha + k pi/2 on rho (eq. 3, 10)."""
    rho = [rc.profile_radius(L, pm, a, b, alpha + k * np.pi / 2)[0] for k in range(4)]
    assume(all(np.all(r > 0.0) for r in rho))  # a law whose pitch curve passes the axis is no cam
    verts = rc.rhombus_vertices(L, pm, a, b, alpha)
    for k in range(4):
        r = np.hypot(*verts[k])
        np.testing.assert_allclose(r, rho[k], rtol=1e-12, atol=1e-15)
