"""Opposed-piston reactor on the double eccentric cams: volume, pressure, forces, energy.

Independent model: the two piston faces placed on a common reactor axis from their
contact geometry (intersection of each follower axis with its disc, by root finding), the
enclosed volume as bore area times the distance between them; the fluid laws written out
here; work by Gauss quadrature and by closed-form integrals of p dV.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest
from numpy.polynomial.legendre import leggauss
from scipy.optimize import brentq

from rotorkin.analysis import torque as tq
from rotorkin.core.errors import ParameterError
from rotorkin.drives import evaluate
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.drives.eccentric_cam.reactor import opposed_piston, reactor_state
from rotorkin.machines import opposed_piston as op


# --------------------------------------------------------------------------------------------
# independent model
# --------------------------------------------------------------------------------------------
def _contact_x(rc, e, beta, sign):
    """Farthest point of the follower axis (y = 0) on the circle of radius rc about the disc
    centre sign * e (cos beta, sin beta), found by root finding; rc = inf: the disc's support."""
    cx, cy = sign * e * np.cos(beta), sign * e * np.sin(beta)
    if np.isinf(rc):
        return cx  # flat face: tangent plate at cx + R, measured from its mid position
    x = brentq(lambda x: (x - cx) ** 2 + cy**2 - rc**2, cx, cx + rc + 1e-12, xtol=1e-15)
    return x - rc


def _face_gap(drive, length, beta):
    """Distance between the inner faces on a common axis X: left face at -L/2 + z (moving
    towards +X, the centre), right face at +L/2 - z'."""
    rc = drive.contact_radius
    e = drive.eccentricity
    out = []
    for b in np.atleast_1d(beta):
        left = -0.5 * length + _contact_x(rc, e, b, +1.0)
        right = 0.5 * length - _contact_x(rc, e, b, -1.0)
        out.append(right - left)
    return np.array(out)


def _volume(reactor, beta):
    return np.pi * reactor.bore**2 / 4 * _face_gap(reactor.drive, reactor.device_length, beta)


def _p_gas(p0, v0, n, v):
    return p0 * (v0 / v) ** n


def _p_liquid(p0, v0, k, v):
    """Integrate dp = -K dV/V from V0: p0 - K ln(V/V0)."""
    return p0 - k * np.log(v / v0)


def _int_p_dv(reactor, v1):
    """Closed-form integral of p dV from V0 to v1."""
    p0, v0 = reactor.initial_pressure, reactor.volume_initial
    if reactor.fluid == "gas":
        n = reactor.polytropic_exponent
        if n == 1.0:
            return p0 * v0 * np.log(v1 / v0)
        return p0 * v0**n * (v1 ** (1 - n) - v0 ** (1 - n)) / (1 - n)
    k = reactor.bulk_modulus
    # int (p0 - K ln(V/V0)) dV = p0 V - K (V ln(V/V0) - V)
    return p0 * (v1 - v0) - k * (v1 * np.log(v1 / v0) - v1 + v0)


def _reactor(
    follower="knife_edge",
    R=0.08,
    e=0.04,
    r=0.0,
    L=1.0,
    bore=0.05,
    fluid="liquid",
    p0=1e5,
    n=1.0,
    K=1.5e9,
):
    drive = ec.EccentricCam(R, e, follower, r)
    machine = opposed_piston(
        drive,
        device_length=L,
        bore=bore,
        fluid=fluid,
        initial_pressure=p0,
        polytropic_exponent=n,
        bulk_modulus=K,
    )
    return _Rx(drive, machine)


@dataclass(frozen=True)
class _Rx:
    """The drive and the reactor on it."""

    drive: ec.EccentricCam
    machine: op.OpposedPiston

    def __getattr__(self, name):
        return getattr(self.machine, name)


def _V(rx, beta):
    return op.enclosed_volume(rx.machine, ec.motion(rx.drive, beta))


def _P(rx, beta):
    return op.pressure(rx.machine, ec.motion(rx.drive, beta))


def _dVdq(rx, beta):
    return op.volume_derivatives_dq(rx.machine, ec.motion(rx.drive, beta))


CASES = [
    dict(),
    dict(fluid="gas", n=1.4, p0=8e5),
    dict(fluid="gas", n=1.0, follower="roller", r=0.015, R=0.05, e=0.03, L=0.2, bore=0.03),
    dict(fluid="liquid", follower="roller", r=0.01, e=0.01, K=2.2e9, p0=5e5, L=0.3),
    dict(follower="flat"),
]


# --------------------------------------------------------------------------------------------
# geometry and fluid
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("case", CASES)
def test_volume_against_face_positions(case):
    rx = _reactor(**case)
    beta = np.random.default_rng(5).uniform(0, 2 * np.pi, 60)
    v = _V(rx, beta)[0]
    assert v.shape == (1, 60)
    np.testing.assert_allclose(v[0], _volume(rx, beta), rtol=1e-12)
    # the volume only grows from V0 (the paper: Delta <= 0, the pressure can only drop)
    assert np.all(v >= rx.volume_initial * (1 - 1e-15))
    vmin, vmax = op.volume_extremes(rx.machine)
    grid = np.linspace(0, 2 * np.pi, 3601)  # contains 0 and 90 deg
    vg = _volume(rx, grid)
    assert vmin == pytest.approx(vg.min(), rel=1e-12)
    assert vmax == pytest.approx(vg.max(), rel=1e-12)


def test_flat_follower_keeps_volume_and_pressure_constant():
    """Eq. 7, 8: Delta = 0, so V = V0 and p = p0 at every angle; no fluid torque."""
    for fluid in ("gas", "liquid"):
        rx = _reactor(follower="flat", fluid=fluid, n=1.3)
        beta = np.linspace(0, 2 * np.pi, 37)
        v, dv, d2v, d3v = _V(rx, beta)
        np.testing.assert_allclose(v, rx.volume_initial, rtol=1e-15)
        assert np.all(dv == 0) and np.all(d2v == 0) and np.all(d3v == 0)
        p, dp = _P(rx, beta)
        np.testing.assert_allclose(p, 1e5, rtol=1e-14)
        assert np.all(dp == 0)
        st = reactor_state(rx.drive, rx.machine, (0.0, (0.5, 0.5)), 60.0, beta)
        assert np.all(st["shaft"] == 0)
    s = evaluate(_cfg(follower="flat")).summary
    assert s["pressure_ripple_bar"] == 0.0 and s["volume_change_cm3"] == 0.0
    assert s["compression_ratio_geometric"] == 1.0 and s["shaft_torque_peak_Nm"] == 0.0
    assert s["cavitation"] is False


@pytest.mark.parametrize("case", CASES[:4])
def test_volume_derivatives_against_finite_differences(case):
    rx = _reactor(**case)
    beta = np.linspace(0.05, 6.2, 31)
    h = 1e-4
    v = [_V(rx, beta + k * h)[0] for k in (-1, 0, 1)]
    d = _V(rx, beta)
    scale = rx.area * rx.drive.eccentricity
    np.testing.assert_allclose(d[1], (v[2] - v[0]) / (2 * h), atol=1e-8 * scale)
    np.testing.assert_allclose(d[2], (v[2] - 2 * v[1] + v[0]) / h**2, atol=1e-5 * scale)
    h = 2e-3
    d1 = [_V(rx, beta + k * h)[1] for k in (-1, 0, 1)]
    np.testing.assert_allclose(d[3], (d1[2] - 2 * d1[1] + d1[0]) / h**2, atol=1e-5 * scale)
    # dV/dq: moving one piston face by dz towards the centre shrinks V by A dz
    dvdq = _dVdq(rx, beta)
    assert dvdq.shape == (2, 1, 31)
    np.testing.assert_allclose(dvdq, -np.pi * rx.bore**2 / 4)


@pytest.mark.parametrize("case", CASES[:4])
def test_pressure_laws(case):
    rx = _reactor(**case)
    beta = np.linspace(0, 2 * np.pi, 73)
    v = _volume(rx, beta)
    p, dp = _P(rx, beta)
    if rx.fluid == "gas":
        want = _p_gas(rx.initial_pressure, rx.volume_initial, rx.polytropic_exponent, v)
    else:
        want = _p_liquid(rx.initial_pressure, rx.volume_initial, rx.bulk_modulus, v)
    np.testing.assert_allclose(p[0], want, rtol=1e-9, atol=1e-9 * rx.initial_pressure)
    # dp/dbeta against finite differences
    h = 1e-5
    fd = (_P(rx, beta + h)[0] - _P(rx, beta - h)[0]) / (2 * h)
    np.testing.assert_allclose(dp, fd, rtol=1e-6, atol=1e-6 * np.max(np.abs(fd)) + 1e-9)
    # liquid: the bulk modulus is -V dp/dV (numerically on the pressure law)
    if rx.fluid == "liquid":
        v0 = rx.volume_initial
        vv = v0 * np.linspace(1.0, 1.03, 7)
        dv = 1e-6 * v0
        k = (
            -vv
            * (
                op.pressure_from_volume(rx.machine, vv + dv)
                - op.pressure_from_volume(rx.machine, vv - dv)
            )
            / (2 * dv)
        )
        np.testing.assert_allclose(k, rx.bulk_modulus, rtol=1e-6)


# --------------------------------------------------------------------------------------------
# energy
# --------------------------------------------------------------------------------------------
def _drive_torque(rx, beta):
    """Fluid torque on the shaft through the drive: piston forces times dq/dbeta."""
    p, _ = _P(rx, beta)
    forces = tq.member_torques(p, _dVdq(rx, beta))
    return tq.shaft_torque_from_members(forces, ec.piston_travels(rx.drive, beta)[1])


def _gauss(f, a, b, pieces=16, n=30):
    x, w = leggauss(n)
    edges = np.linspace(a, b, pieces + 1)
    total = 0.0
    for lo, hi in zip(edges[:-1], edges[1:], strict=True):
        t = 0.5 * (hi - lo) * x + 0.5 * (hi + lo)
        total += 0.5 * (hi - lo) * float(np.sum(w * f(t)))
    return total


@pytest.mark.parametrize("case", CASES[:4])
def test_stroke_work_through_the_drive_equals_integral_of_p_dv(case):
    """int_0^{90 deg} F_i q_i' dbeta = int_{V0}^{Vmax} p dV (closed form), to 1e-10; over a
    turn the fluid spring returns everything: oint p dV = 0."""
    rx = _reactor(**case)
    work = _gauss(lambda b: _drive_torque(rx, b), 0.0, np.pi / 2)
    vmax = _volume(rx, np.pi / 2)[0]
    want = _int_p_dv(rx, vmax)
    assert work == pytest.approx(want, rel=1e-10)
    full = _gauss(lambda b: _drive_torque(rx, b), 0.0, 2 * np.pi, pieces=64)
    scale = _gauss(lambda b: np.abs(_drive_torque(rx, b)), 0.0, 2 * np.pi, pieces=64)
    assert abs(full) < 1e-12 * scale
    s = evaluate(_cfg_from(rx)).summary
    assert abs(s["indicated_work_J"]) < 1e-9 * scale
    assert abs(s["mean_torque_Nm"]) < 1e-9 * scale


def test_instantaneous_power_balance_with_speed_profile():
    """Motor power = -p dV/dt + d(KE)/dt; dV/dt from the face-position model, KE differenced."""
    rx = _reactor(fluid="gas", p0=5e5, n=1.3)
    js, m = 0.02, 0.7
    speed = [60.0, 66.0, 63.0, 58.0]
    beta = np.linspace(0.03, 2 * np.pi - 0.03, 83)
    st = reactor_state(rx.drive, rx.machine, (js, (m, m)), speed, beta)
    omega = st["omega"]
    h = 1e-6
    dvdt = (_volume(rx, beta + h) - _volume(rx, beta - h)) / (2 * h) * omega
    fluid_power = st["p"][0] * dvdt

    def ke(b):
        w = reactor_state(rx.drive, rx.machine, (js, (m, m)), speed, b)["omega"]
        dq = ec.piston_travels(rx.drive, b)[1]
        return 0.5 * (js + m * dq[0] ** 2 + m * dq[1] ** 2) * w**2

    dke_dt = (ke(beta + 1e-5) - ke(beta - 1e-5)) / 2e-5 * omega
    motor = -st["net"] * omega
    np.testing.assert_allclose(
        motor, -fluid_power + dke_dt, rtol=1e-6, atol=1e-7 * np.max(np.abs(motor))
    )


def test_piston_forces_push_the_pistons_out():
    rx = _reactor(fluid="gas", p0=3e5)
    beta = np.linspace(0, 2 * np.pi, 9)
    st = reactor_state(rx.drive, rx.machine, (0.0, (0.0, 0.0)), 10.0, beta)
    np.testing.assert_allclose(st["F"], -np.stack([st["p"][0]] * 2) * np.pi * 0.05**2 / 4)


# --------------------------------------------------------------------------------------------
# study
# --------------------------------------------------------------------------------------------
def _cfg(machine=None, speed=600 * np.pi / 30, **drive):
    d = {
        "type": "eccentric_cam",
        "disc_radius": 0.08,
        "eccentricity": 0.04,
        "follower": "knife_edge",
        "roller_radius": 0.0,
    }
    d.update(drive)
    m = {
        "device_length": 1.0,
        "bore": 0.05,
        "fluid": "liquid",
        "initial_pressure": 1e5,
        "polytropic_exponent": 1.0,
        "bulk_modulus": 1.5e9,
        "piston_mass": 0.5,
        "inertia_shaft": 0.032,
        "speed_fluctuation": 0.02,
    }
    m.update(machine or {})
    return {"drive": d, "machine": m, "loads": {}, "run": {"points": 361, "speed": speed}}


def _cfg_from(rx):
    dr = rx.drive
    return _cfg(
        machine={
            "device_length": rx.device_length,
            "bore": rx.bore,
            "fluid": rx.fluid,
            "initial_pressure": rx.initial_pressure,
            "polytropic_exponent": rx.polytropic_exponent,
            "bulk_modulus": rx.bulk_modulus,
        },
        disc_radius=dr.disc_radius,
        eccentricity=dr.eccentricity,
        follower=dr.follower,
        roller_radius=dr.roller_radius,
    )


def test_summary_values_are_plain_python():
    s = evaluate(_cfg()).summary
    bad = {k: type(v) for k, v in s.items() if type(v) not in (float, int, str, bool)}
    assert not bad


def test_study_summary_of_the_paper_reactor_by_hand():
    """R 80 mm, e 40 mm, knife edge (paper), bore 50 mm, L 1000 mm, liquid K 1.5 GPa, 1 bar,
    600 rpm. Delta_min = 2 (sqrt(80^2 - 40^2) - 80) mm = -21.436 mm (paper: -21.4 mm)."""
    s = evaluate(_cfg()).summary
    a = np.pi * 25.0**2  # mm^2
    dmin = 2 * (np.sqrt(80.0**2 - 40.0**2) - 80.0)  # mm
    assert dmin == pytest.approx(-21.4, abs=0.05)
    v0, vmax = a * 1000.0 / 1e3, a * (1000.0 - dmin) / 1e3  # cm^3
    assert s["enclosed_volume_min_cm3"] == pytest.approx(v0, rel=1e-12)
    assert s["enclosed_volume_max_cm3"] == pytest.approx(vmax, rel=1e-12)
    assert s["chamber_volume_max_cm3"] == s["enclosed_volume_max_cm3"]
    assert s["compression_ratio_geometric"] == pytest.approx(vmax / v0, rel=1e-12)
    drop = 1.5e9 * np.log(vmax / v0) / 1e5  # bar
    assert s["pressure_ripple_bar"] == pytest.approx(drop, rel=1e-12)
    assert s["pressure_min_bar"] == pytest.approx(1.0 - drop, rel=1e-12)
    assert s["pressure_ripple_relative"] == pytest.approx(drop, rel=1e-12)  # p0 = 1 bar
    assert s["cavitation"] is True  # a 2 % volume growth tears a liquid at 1 bar
    w = 600 * np.pi / 30
    # z''(0) = -e (1 + lambda) is the largest |z''| (drive test): a = 0.06 m * w^2
    assert s["piston_left_accel_peak_m_per_s2"] == pytest.approx(0.06 * w**2, rel=1e-12)
    assert s["piston_right_accel_peak_m_per_s2"] == pytest.approx(0.06 * w**2, rel=1e-12)
    assert s["piston_force_peak_N"] == pytest.approx((drop - 1.0) * 1e5 * a * 1e-6, rel=1e-4)
    for key in (
        "shaft_torque_peak_Nm",
        "flywheel_inertia_kgm2",
        "energy_fluctuation_J",
        "piston_left_speed_peak_m_per_s",
        "shaft_speed_mean_rpm",
    ):
        assert isinstance(s[key], float) and np.isfinite(s[key]), key
    assert s["shaft_speed_mean_rpm"] == pytest.approx(600.0)


def test_flywheel_of_a_flat_follower_by_hand():
    """Flat follower: no fluid torque; z = e cos b, z' = -e cos b so J_eq = J_s + 2 m e^2 sin^2 b.
    KE = 1/2 J_eq w^2 swings by m e^2 w^2 = Delta E; J_flywheel = Delta E/(C_s w^2) - mean J_eq
    = m e^2 / C_s - (J_s + m e^2)."""
    js, m, e, cs = 0.001, 2.0, 0.04, 0.05
    s = evaluate(
        _cfg(
            machine={"inertia_shaft": js, "piston_mass": m, "speed_fluctuation": cs},
            follower="flat",
        )
    ).summary
    w = 600 * np.pi / 30
    assert s["energy_fluctuation_J"] == pytest.approx(m * e**2 * w**2, rel=1e-7)
    assert s["equivalent_inertia_mean_kgm2"] == pytest.approx(js + m * e**2, rel=1e-9)
    assert s["flywheel_inertia_kgm2"] == pytest.approx(m * e**2 / cs - js - m * e**2, rel=1e-6)
    assert s["speed_fluctuation_without_flywheel"] == pytest.approx(
        m * e**2 / (js + m * e**2), rel=1e-6
    )


def test_study_columns():
    res = evaluate(
        _cfg(
            machine={"fluid": "gas", "polytropic_exponent": 1.4, "initial_pressure": 4e5},
            follower="roller",
            roller_radius=0.01,
        )
    )
    c = res.columns
    for key in (
        "volume_cm3",
        "dvolume_cm3_per_rad",
        "pressure_bar",
        "piston_left_force_N",
        "shaft_torque_Nm",
        "inertia_torque_Nm",
        "shaft_torque_with_inertia_Nm",
        "piston_left_speed_m_per_s",
        "piston_right_accel_m_per_s2",
        "shaft_speed_rpm",
    ):
        assert key in c and c[key].shape == (361,) and key in res.column_docs
    np.testing.assert_allclose(
        c["shaft_torque_with_inertia_Nm"], c["shaft_torque_Nm"] - c["inertia_torque_Nm"]
    )
    # virtual work: F_L z' + F_R z'' = p dV/dbeta
    via = (
        c["piston_left_force_N"] * c["z_left_velocity_mm_per_rad"]
        + c["piston_right_force_N"] * c["z_right_velocity_mm_per_rad"]
    ) / 1e3
    np.testing.assert_allclose(c["shaft_torque_Nm"], via, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(
        c["shaft_torque_Nm"],
        c["pressure_bar"] * 1e5 * c["dvolume_cm3_per_rad"] * 1e-6,
        rtol=1e-9,
        atol=1e-12,
    )
    # gas: p V^n constant along the turn
    pvn = c["pressure_bar"] * c["volume_cm3"] ** 1.4
    np.testing.assert_allclose(pvn, pvn[0], rtol=1e-12)
    assert res.summary["cavitation"] is False


def test_shapes_0d_1d_3d():
    rx = _reactor(fluid="gas")
    b3 = np.random.default_rng(2).uniform(0, 7, (3, 2, 4))
    v3 = _V(rx, b3)
    p3, dp3 = _P(rx, b3)
    assert v3[0].shape == p3.shape == dp3.shape == (1, 3, 2, 4)
    v1 = _V(rx, b3.ravel())
    np.testing.assert_array_equal(v3[1].reshape(1, -1), v1[1])
    p0, _ = _P(rx, b3[2, 1, 3])
    assert p0.shape == (1,) and p0[0] == p3[0, 2, 1, 3]
    assert _dVdq(rx, b3).shape == (2, 1, 3, 2, 4)


@pytest.mark.parametrize(
    ("machine", "key", "text"),
    [
        ({"bore": 0.0}, "machine.bore", "bore > 0 mm"),
        ({"device_length": -0.1}, "machine.device_length", "device_length > 0 mm"),
        ({"fluid": "water"}, "machine.fluid", "'gas', 'liquid'"),
        ({"initial_pressure": 0.0}, "machine.initial_pressure", "> 0 bar"),
        ({"polytropic_exponent": 0.0}, "machine.polytropic_exponent", "> 0"),
        ({"bulk_modulus": -1.0}, "machine.bulk_modulus", "> 0 GPa"),
        ({"piston_mass": -0.1}, "machine.piston_mass", ">= 0 kg"),
        ({"inertia_shaft": -0.1}, "machine.inertia_shaft", ">= 0"),
        ({"speed_fluctuation": 1.5}, "machine.speed_fluctuation", "< 1"),
    ],
)
def test_bad_inputs_name_the_key(machine, key, text):
    with pytest.raises(ParameterError) as err:
        evaluate(_cfg(machine=machine))
    assert str(err.value).startswith(key + " = ")
    assert text in str(err.value)


@pytest.mark.slow
def test_plot_writes_reactor_figures(tmp_path):
    res = evaluate(_cfg(machine={"fluid": "gas"}, follower="roller", roller_radius=0.012))
    paths = res.write_figures(tmp_path)
    names = {p.name for p in paths}
    assert {
        "reactor_volume_pressure.png",
        "reactor_torque.png",
        "reactor_ripple_vs_lambda.png",
    } <= names
    for p in paths:
        assert p.stat().st_size > 10_000 and p.read_bytes()[:4] == b"\x89PNG"
