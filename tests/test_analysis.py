"""Generic analysis: shaft speed profiles, torque by virtual work, inertia, flywheel sizing."""

import numpy as np
import pytest

from rotorkin.analysis.flywheel import (
    energy_fluctuation,
    flywheel_inertia,
    speed_fluctuation_coefficient,
)
from rotorkin.analysis.timing import shaft_speed
from rotorkin.analysis.torque import (
    cycle_integral,
    equivalent_inertia,
    gas_torque,
    inertia_torque,
    kinetic_energy,
    member_torques,
    shaft_torque_from_members,
    torque_ripple,
)
from rotorkin.core.errors import ParameterError
from rotorkin.core.motion import compose, time_derivatives


def _members(theta, a=0.3, b=0.2):
    """Two members q1 = theta + a sin 2theta, q2 = -theta + b cos 3theta and 3 derivatives."""
    s2, c2, s3, c3 = np.sin(2 * theta), np.cos(2 * theta), np.sin(3 * theta), np.cos(3 * theta)
    q = np.stack([theta + a * s2, -theta + b * c3])
    dq = np.stack([1 + 2 * a * c2, -1 - 3 * b * s3])
    d2q = np.stack([-4 * a * s2, -9 * b * c3])
    d3q = np.stack([-8 * a * c2, 27 * b * s3])
    return q, dq, d2q, d3q


def test_constant_speed_has_no_derivatives():
    theta = np.linspace(0, 2 * np.pi, 7)
    w, wd, wdd = shaft_speed(theta, 314.0, 2 * np.pi)
    assert np.all(w == 314.0) and np.all(wd == 0) and np.all(wdd == 0)


def test_speed_profile_interpolates_and_its_time_derivatives_follow_the_chain_rule():
    period = 2 * np.pi
    nodes = np.arange(8) * period / 8
    samples = 300 + 20 * np.sin(nodes) + 5 * np.cos(2 * nodes)
    w_nodes = shaft_speed(nodes, samples, period)[0]
    np.testing.assert_allclose(w_nodes, samples, rtol=1e-13)
    theta = np.linspace(0.1, 6.0, 50)
    h = 1e-5
    w, wd, wdd = shaft_speed(theta, samples, period)
    wp, wm = shaft_speed(theta + h, samples, period)[0], shaft_speed(theta - h, samples, period)[0]
    np.testing.assert_allclose(wd, w * (wp - wm) / (2 * h), rtol=1e-6, atol=1e-6)
    wdp = shaft_speed(theta + h, samples, period)[1]
    wdm = shaft_speed(theta - h, samples, period)[1]
    np.testing.assert_allclose(wdd, w * (wdp - wdm) / (2 * h), rtol=1e-5, atol=1e-3)
    # periodic: the profile repeats after one period
    np.testing.assert_allclose(shaft_speed(theta + period, samples, period)[0], w, rtol=1e-12)


@pytest.mark.parametrize("speed", [0.0, -5.0, [300.0, 300.0], [300.0, np.nan, 300.0]])
def test_bad_speeds_are_refused(speed):
    with pytest.raises(ParameterError, match="run.speed"):
        shaft_speed(np.zeros(3), speed, 2 * np.pi)


def test_time_derivatives_match_finite_differences_in_time():
    """q(theta(t)) with theta(t) = w0 t + c t^2 + d t^3: exact omega, omega_dot, omega_ddot."""
    w0, c, d = 50.0, 30.0, 40.0
    t = np.linspace(0.01, 0.2, 25)
    theta = w0 * t + c * t**2 + d * t**3
    omega, omega_dot, omega_ddot = w0 + 2 * c * t + 3 * d * t**2, 2 * c + 6 * d * t, 6 * d
    _, dq, d2q, d3q = _members(theta)
    v, a, j = time_derivatives(dq, d2q, d3q, omega, omega_dot, omega_ddot)
    h = 1e-5

    def q_of(tt):
        return _members(w0 * tt + c * tt**2 + d * tt**3)[0]

    np.testing.assert_allclose(v, (q_of(t + h) - q_of(t - h)) / (2 * h), rtol=1e-5)
    np.testing.assert_allclose(
        a, (q_of(t + h) - 2 * q_of(t) + q_of(t - h)) / h**2, rtol=1e-4, atol=1e-2
    )
    h3 = 1e-4
    fd3 = (q_of(t + 2 * h3) - 2 * q_of(t + h3) + 2 * q_of(t - h3) - q_of(t - 2 * h3)) / (2 * h3**3)
    np.testing.assert_allclose(j, fd3, rtol=1e-3, atol=20)


def test_compose_is_the_chain_rule_to_third_order():
    x = np.linspace(-1, 1, 9)
    g = (np.sin(x), np.cos(x), -np.sin(x), -np.cos(x))
    u = g[0]
    f = (np.exp(2 * u), 2 * np.exp(2 * u), 4 * np.exp(2 * u), 8 * np.exp(2 * u))
    h = compose(f, g)
    # independent: h = exp(2 sin x); derivatives by hand
    e = np.exp(2 * np.sin(x))
    c, s = np.cos(x), np.sin(x)
    np.testing.assert_allclose(h[1], 2 * c * e)
    np.testing.assert_allclose(h[2], (4 * c**2 - 2 * s) * e)
    np.testing.assert_allclose(h[3], (8 * c**3 - 12 * s * c - 2 * c) * e)


def test_inertia_torque_is_the_rate_of_kinetic_energy():
    """d(KE)/dtheta = T_inertia, with KE = 1/2 J_eq(theta) omega(theta)^2 (independent path)."""
    period = 2 * np.pi
    samples = 200 + 15 * np.sin(np.arange(12) * period / 12)
    js, jm = 0.05, [0.02, 0.03]
    theta = np.linspace(0.2, 6.0, 40)
    h = 1e-5

    def ke(th):
        w = shaft_speed(th, samples, period)[0]
        return kinetic_energy(js, jm, _members(th)[1], w)

    w, wd, _ = shaft_speed(theta, samples, period)
    _, dq, d2q, _ = _members(theta)
    torque = inertia_torque(js, jm, dq, d2q, w, wd)
    np.testing.assert_allclose(torque, (ke(theta + h) - ke(theta - h)) / (2 * h), rtol=1e-6)
    assert equivalent_inertia(js, jm, dq).shape == theta.shape


def test_gas_torque_equals_member_torques_through_the_drive():
    """Chambers V1 = k (q2 - q1) + V0 and V2 = -k (q2 - q1) + V0: two routes, one torque."""
    theta = np.linspace(0, 2 * np.pi, 101)
    q, dq, _, _ = _members(theta)
    k, v0 = 2e-5, 1e-4
    rel, drel = q[1] - q[0], dq[1] - dq[0]
    volume = np.stack([v0 + k * rel, v0 - k * rel])
    dvolume = np.stack([k * drel, -k * drel])
    pressure = 1e5 * (1 + volume / v0)
    dv_dq = np.array([[-k, k], [k, -k]])[:, :, None] * np.ones_like(theta)
    via_members = shaft_torque_from_members(member_torques(pressure, dv_dq), dq)
    np.testing.assert_allclose(via_members, gas_torque(pressure, dvolume), rtol=1e-12)


def test_cycle_integral_and_ripple():
    theta = np.linspace(0, 2 * np.pi, 2001)
    torque = 10 + 4 * np.sin(3 * theta)
    assert cycle_integral(torque, theta) == pytest.approx(20 * np.pi, rel=1e-12)
    assert torque_ripple(torque) == pytest.approx(0.8, rel=1e-6)
    assert np.isnan(torque_ripple(np.sin(theta)))


def test_flywheel_hand_checked_square_torque():
    """T = 200 N m on the first half turn, 0 on the second: mean 100 N m, the energy rises by
    100 N m * pi rad and falls back, so Delta E = 100 pi J = 314.159 J. At 100 rad/s and
    C_s = 0.02 the flywheel needs J = Delta E / (C_s omega^2) = 314.159 / 200 = 1.5708 kg m^2."""
    theta = np.linspace(0, 2 * np.pi, 200_001)
    torque = np.where(theta < np.pi, 200.0, 0.0)
    delta_e = energy_fluctuation(torque, theta)
    assert delta_e == pytest.approx(100 * np.pi, rel=1e-4)
    assert flywheel_inertia(delta_e, 100.0, 0.02) == pytest.approx(1.5708, rel=1e-4)
    assert flywheel_inertia(delta_e, 100.0, 0.02, inertia_present=1.0) == pytest.approx(
        0.5708, rel=1e-3
    )
    assert flywheel_inertia(delta_e, 100.0, 0.02, inertia_present=5.0) == 0.0
    assert speed_fluctuation_coefficient(delta_e, 1.5708, 100.0) == pytest.approx(0.02, rel=1e-4)


def test_flywheel_sinusoidal_torque():
    """T = T0 + A sin(n theta): E = -(A/n) cos(n theta) + c, so Delta E = 2 A / n."""
    theta = np.linspace(0, 2 * np.pi, 4001)
    torque = np.stack([50 + 100 * np.sin(2 * theta), 50 + 30 * np.sin(4 * theta)])
    np.testing.assert_allclose(energy_fluctuation(torque, theta), [100.0, 15.0], rtol=1e-5)


@pytest.mark.parametrize("coefficient", [0.0, 1.0, -0.1])
def test_flywheel_coefficient_must_be_a_fraction(coefficient):
    with pytest.raises(ParameterError, match="machine.speed_fluctuation"):
        flywheel_inertia(1.0, 100.0, coefficient)


def test_shaft_torque_summary_of_known_curves():
    """A torque 2 + sin(theta) and, with inertia, 2 + sin(theta) - 0.5 sin(2 theta), over
    a turn: ripple and extremes from their closed forms, for a column of two designs."""
    from rotorkin.analysis.torque import SHAFT_TORQUE_KEYS, shaft_torque_summary

    theta = np.linspace(0.0, 2.0 * np.pi, 100_001)
    scale = np.array([[1.0], [3.0]])
    torque = scale * (2.0 + np.sin(theta))
    net = scale * (2.0 + np.sin(theta) - 0.5 * np.sin(2.0 * theta))
    s = shaft_torque_summary(torque, net)
    assert tuple(s) == SHAFT_TORQUE_KEYS
    # net' = cos t - cos 2t = 0 where cos t = 1 or -1/2: the largest at t = 2 pi / 3;
    # net(-t) = 4 - net(t), so the smallest is 4 less the largest
    hi = 2.0 + np.sin(2 * np.pi / 3) - 0.5 * np.sin(4 * np.pi / 3)
    np.testing.assert_allclose(s["shaft_torque_max_Nm"], scale[:, 0] * 3.0, rtol=1e-9)
    np.testing.assert_allclose(s["shaft_torque_min_Nm"], scale[:, 0] * 1.0, rtol=1e-9)
    np.testing.assert_allclose(s["torque_ripple"], [1.0, 1.0], rtol=1e-9)
    np.testing.assert_allclose(s["shaft_torque_with_inertia_max_Nm"], scale[:, 0] * hi, rtol=1e-9)
    np.testing.assert_allclose(s["shaft_torque_with_inertia_min_Nm"], scale[:, 0] * (4.0 - hi),
                               rtol=1e-9)  # fmt: skip
    np.testing.assert_allclose(s["torque_ripple_with_inertia"], [(2 * hi - 4.0) / 2.0] * 2,
                               rtol=1e-9)  # fmt: skip
