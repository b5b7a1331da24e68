"""Differential vane pump on the guide-bar drive: chambers, flow, torques, energy, inertia.

The independent model in this file places the 2 Z vanes of the two impellers in the casing
(angles of their centre lines from the drive's impeller angles and a mounting offset found
here by numeric search), sorts them round the casing and measures the gaps: chamber volumes,
displacement, flow and work follow from those sampled volumes alone, by finite differences,
sums of volume decreases and quadrature.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest
from numpy.polynomial.legendre import leggauss
from scipy.optimize import brentq, minimize_scalar

from rotorkin.analysis import torque as tq
from rotorkin.core.errors import ParameterError
from rotorkin.drives import evaluate
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar import pump as gb_pump
from rotorkin.drives.guide_bar.study import pump_state
from rotorkin.machines import vane_pump as vp

PS, PD = 1.0e5, 6.0e5


# --------------------------------------------------------------------------------------------
# the independent geometric model
# --------------------------------------------------------------------------------------------
class Geometry:
    """Vanes in the casing -> sorted gaps -> chamber volumes; nothing from vane_pump."""

    def __init__(self, drive, z, gamma, rh, rc, w):
        self.drive, self.z, self.gamma = drive, z, gamma
        self.k = 0.5 * (rc * rc - rh * rh) * w
        per = gb.period(drive)

        def rel(t):
            q = gb.impeller_angles(drive, np.asarray(t))[0]
            return q[1] - q[0]

        # extremes of the relative angle by dense sampling + bounded refinement
        grid = np.linspace(0.0, per, 4001)
        r = rel(grid)
        ext = []
        for sgn, i in ((1.0, int(np.argmin(r))), (-1.0, int(np.argmax(r)))):
            lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
            res = minimize_scalar(
                lambda t, s=sgn: s * rel(t),
                bounds=(lo, hi),
                method="bounded",
                options={"xatol": 1e-12},
            )
            ext.append(float(rel(res.x)))
        self.r_min, self.r_max = ext
        # impeller 2's vanes sit pi/Z ahead of impeller 1's at mid-swing
        self.offset = np.pi / z - 0.5 * (self.r_min + self.r_max)

    def vanes(self, theta, dq=(0.0, 0.0)):
        """Vane centre lines, shape (2 Z, n), optionally with the members nudged by dq."""
        q = gb.impeller_angles(self.drive, np.atleast_1d(theta))[0]
        m = 2 * np.pi * np.arange(self.z)[:, None] / self.z
        one = q[0][None] + dq[0] + m
        two = q[1][None] + dq[1] + self.offset + m
        return np.concatenate([one, two])

    def volumes(self, theta, dq=(0.0, 0.0)):
        """Chamber volumes sorted round the casing from the first vane of impeller 1, (2 Z, n)."""
        v = self.vanes(theta, dq)
        rel = np.mod(v - v[0], 2 * np.pi)  # vane angles from vane 0 of impeller 1
        order = np.argsort(rel, axis=0)
        srt = np.take_along_axis(rel, order, axis=0)
        gaps = np.diff(np.concatenate([srt, np.full((1, srt.shape[1]), 2 * np.pi)]), axis=0)
        return self.k * (gaps - self.gamma)


@dataclass(frozen=True)
class Case:
    """A drive and the pump on it; the pump's fields read through."""

    drive: gb.GuideBar
    pump: vp.VanePump

    def __getattr__(self, name):
        return getattr(self.pump, name)


def _pump(
    driver="crank", lam=0.5, u=2.0, i12=2.0, phase=np.pi, z=2, gamma=None, rh=0.03, rc=0.08, w=0.04
):
    drive = gb.GuideBar(lam, u, i12, phase, driver)
    return Case(drive, gb_pump.vane_pump(drive, z, gamma, rh, rc, w))


def _m(p, theta):
    """The impellers' motion of case ``p`` at ``theta``."""
    return gb.motion(p.drive, theta)


def _geometry(p):
    return Geometry(
        p.drive, p.vanes_per_impeller, p.vane_angle, p.hub_radius, p.casing_radius, p.axial_width
    )


CASES = [
    dict(),
    dict(driver="guide"),
    dict(driver="crank", lam=0.3, u=3.0, i12=1.0, phase=np.radians(150.0), z=3),
    dict(driver="guide", lam=0.7, u=2.0, i12=1.5, phase=np.radians(220.0), z=2, gamma=0.6),
    dict(driver="crank", lam=0.4, u=2.0, i12=1.0, phase=np.pi, z=1, rh=0.02, rc=0.05, w=0.01),
]


def _equal_speed_thetas(drive):
    """Input angles in (0, period) where both impellers turn equally fast (root finding)."""
    per = gb.period(drive)

    def f(t):
        dq = gb.impeller_angles(drive, np.asarray(t))[1]
        return float(dq[1] - dq[0])

    grid = np.linspace(0.0, per, 2001) + 0.000123456 * per  # off any symmetric point
    vals = np.array([f(t) for t in grid])
    roots = [
        brentq(f, grid[i], grid[i + 1], xtol=1e-15)
        for i in range(grid.size - 1)
        if vals[i] * vals[i + 1] < 0
    ]
    return np.sort(np.mod(roots, per))


# --------------------------------------------------------------------------------------------
# geometry
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("case", CASES)
def test_volumes_against_vane_gaps(case):
    """V_j(theta) equal the gaps between sorted vanes minus a vane width, to 1e-12 relative."""
    p = _pump(**case)
    g = _geometry(p)
    theta = np.random.default_rng(7).uniform(0, gb.period(p.drive), 300)
    want = g.volumes(theta)
    got, _ = vp.chamber_volumes(p.pump, _m(p, theta))
    # the module numbers chambers A1, B1, A2, ... from vane 1 of impeller 1: the same order
    scale = g.k * 2 * np.pi
    np.testing.assert_allclose(got, want, atol=1e-9 * scale, rtol=0)
    assert np.all(want > -1e-12 * scale), "a chamber went negative"
    # the chambers fill the annulus: sum V = k (2 pi - 2 Z gamma)
    total = g.k * (2 * np.pi - 2 * p.vanes_per_impeller * p.vane_angle)
    np.testing.assert_allclose(got.sum(axis=0), total, rtol=1e-12)


def test_vane_angles_alternate_at_mid_swing():
    """At mid-swing of the relative angle the vanes are evenly spaced pi/Z (the layout)."""
    p = _pump(z=3, u=3.0, lam=0.4, i12=1.0)
    g = _geometry(p)
    # where q2 - q1 = r_mid: between the two equal-speed points
    ta, tb = _equal_speed_thetas(p.drive)[:2]
    mid = 0.5 * (g.r_min + g.r_max)
    t = brentq(
        lambda s: float(np.subtract(*gb.impeller_angles(p.drive, s)[0][::-1])) - mid,
        ta,
        tb,
        xtol=1e-15,
    )
    v = np.sort(np.mod(vp.vane_angles(p.pump, _m(p, t)).ravel(), 2 * np.pi))
    gaps = np.diff(np.append(v, v[0] + 2 * np.pi))
    np.testing.assert_allclose(gaps, np.pi / 3, atol=1e-9)


@pytest.mark.parametrize("case", CASES[:4])
def test_chamber_angle_range_and_vane_angle_max(case):
    p = _pump(**case)
    g = _geometry(p)
    lo, hi = p.chamber_angle_range
    sw = g.r_max - g.r_min
    assert hi - lo == pytest.approx(sw, abs=1e-9)
    assert lo == pytest.approx(np.pi / p.vanes_per_impeller - sw / 2 - p.vane_angle, abs=1e-9)
    th = np.linspace(0, gb.period(p.drive), 20001)
    v = g.volumes(th) / g.k
    assert v.min() == pytest.approx(lo, abs=1e-7) and v.max() == pytest.approx(hi, abs=1e-7)
    assert p.pump.vane_angle_max == pytest.approx(np.pi / p.vanes_per_impeller - sw / 2, abs=1e-9)


def test_theoretical_vane_angle_closes_the_chambers_when_z_equals_u():
    """Z = u and gamma = gamma_0 (eq. 5/6): the smallest chamber is exactly empty."""
    for driver, g0 in (("crank", 2 * np.arccos(0.5 / np.sqrt(1.25)) / 2), ("guide", np.pi / 3)):
        p = _pump(driver=driver)
        assert p.vane_angle == pytest.approx(g0, abs=1e-14)  # eq. 5, eq. 6 at lambda 0.5, u 2
        assert p.chamber_angle_range[0] == 0.0
        th = _equal_speed_thetas(p.drive)
        assert np.min(_geometry(p).volumes(th)) == pytest.approx(0.0, abs=1e-12)


def test_chamber_derivatives_against_finite_differences():
    p = _pump(driver="guide", lam=0.6, u=3.0, i12=1.3, phase=2.0, z=2)
    th = np.linspace(0.1, 7.0, 41)
    h = 1e-4
    phi = [vp.chamber_angles(p.pump, _m(p, th + k * h))[0] for k in (-2, -1, 0, 1, 2)]
    d = vp.chamber_angles(p.pump, _m(p, th))
    np.testing.assert_allclose(d[1], (phi[3] - phi[1]) / (2 * h), atol=1e-8)
    np.testing.assert_allclose(d[2], (phi[3] - 2 * phi[2] + phi[1]) / h**2, atol=1e-6)
    h = 2e-3  # third differences: truncation h^2 f^(5) vs round-off eps/h^3
    dphi = [vp.chamber_angles(p.pump, _m(p, th + k * h))[1] for k in (-1, 0, 1)]
    np.testing.assert_allclose(d[3], (dphi[2] - 2 * dphi[1] + dphi[0]) / h**2, atol=1e-5)
    v, dv = vp.chamber_volumes(p.pump, _m(p, th))
    np.testing.assert_allclose(dv, p.volume_per_angle * d[1], rtol=1e-14)


def test_volume_derivatives_dq_against_nudged_members():
    """dV_j/dq_i by moving one impeller alone in the geometric model."""
    p = _pump(z=3, u=3.0, lam=0.3, i12=1.0, phase=2.5)
    g = _geometry(p)
    th = np.linspace(0.2, 5.0, 9)
    h = 1e-6
    got = vp.volume_derivatives_dq(p.pump, _m(p, th))
    assert got.shape == (2, 6, 9)
    for i in (0, 1):
        e = np.zeros(2)
        e[i] = h
        fd = (g.volumes(th, e) - g.volumes(th, -e)) / (2 * h)
        np.testing.assert_allclose(got[i], fd, atol=1e-8 * g.k)


def test_shapes_0d_1d_3d():
    p = _pump(z=3, u=3.0)
    th3 = np.random.default_rng(3).uniform(0, 12, (2, 3, 4))
    V3, dV3 = vp.chamber_volumes(p.pump, _m(p, th3))
    assert V3.shape == dV3.shape == (6, 2, 3, 4)
    V1, dV1 = vp.chamber_volumes(p.pump, _m(p, th3.ravel()))
    np.testing.assert_allclose(V3.reshape(6, -1), V1, rtol=0, atol=0)
    V0, _ = vp.chamber_volumes(p.pump, _m(p, th3[1, 2, 3]))
    assert V0.shape == (6,)
    np.testing.assert_allclose(V0, V3[:, 1, 2, 3], rtol=0, atol=0)
    assert vp.vane_angles(p.pump, _m(p, th3)).shape == (2, 3, 2, 3, 4)
    assert vp.volume_derivatives_dq(p.pump, _m(p, th3)).shape == (2, 6, 2, 3, 4)
    assert vp.flow_rate(p.pump, _m(p, th3), 100.0).shape == (2, 3, 4)
    assert vp.chamber_pressures(vp.PortPressures(PS, PD), dV3).shape == (6, 2, 3, 4)


def test_periodicity():
    p = _pump(driver="guide", i12=1.7, phase=2.2)
    th = np.linspace(0, 5, 11)
    a = vp.chamber_volumes(p.pump, _m(p, th))
    b = vp.chamber_volumes(p.pump, _m(p, th + gb.period(p.drive)))
    np.testing.assert_allclose(a[0], b[0], atol=1e-15)
    np.testing.assert_allclose(a[1], b[1], atol=1e-15)


# --------------------------------------------------------------------------------------------
# displacement and flow, from the sampled geometry
# --------------------------------------------------------------------------------------------
def _numeric_displacement(g, drive, n=400_001):
    th = np.linspace(0, gb.period(drive), n)
    dv = np.diff(g.volumes(th), axis=1)
    return float(-np.sum(np.minimum(dv, 0.0)))


@pytest.mark.parametrize("case", CASES)
def test_displacement_against_summed_volume_decreases(case):
    p = _pump(**case)
    g = _geometry(p)
    per_period = _numeric_displacement(g, p.drive)
    d = gb_pump.displacement(p.drive, p.pump)
    assert d["per_period"] == pytest.approx(per_period, rel=1e-8)
    assert d["per_input_turn"] == pytest.approx(per_period / p.drive.input_gear_ratio, rel=1e-8)
    # an impeller advances 2 pi / u per period: u periods per impeller revolution
    assert d["per_impeller_rev"] == pytest.approx(per_period * p.drive.gear_ratio, rel=1e-8)


def _numeric_flow(g, drive, omega, n=200_001):
    """Q = omega sum max(-dV/dtheta, 0) by central differences of the sampled volumes."""
    per = gb.period(drive)
    th = np.linspace(0, per, n)
    h = 1e-6
    dv = (g.volumes(th + h) - g.volumes(th - h)) / (2 * h)
    return th, omega * np.sum(np.maximum(-dv, 0.0), axis=0)


@pytest.mark.parametrize("case", CASES[:4])
def test_flow_and_flow_ripple_against_sampled_geometry(case):
    p = _pump(**case)
    g = _geometry(p)
    omega = 157.08
    th, q = _numeric_flow(g, p.drive, omega)
    np.testing.assert_allclose(
        vp.flow_rate(p.pump, _m(p, th[::100]), omega), q[::100], atol=1e-7 * np.max(q)
    )
    mean = np.trapezoid(q, th) / th[-1]
    ripple = (q.max() - q.min()) / mean
    got = vp.flow_ripple(vp.flow_rate(p.pump, _m(p, th), omega))
    assert got == pytest.approx(ripple, rel=1e-6)
    # the mean flow is the displacement per unit time
    assert mean == pytest.approx(_numeric_displacement(g, p.drive) * omega / th[-1], rel=1e-6)


def test_flow_ripple_of_the_example_by_hand():
    """Crank-driven, lambda 0.5, u 2, i12 2, Sigma 180 deg, constant speed.

    Q ~ |g'(t + pi) - g'(t)| with g'(x) = (1 + l cos x)/(1 + 2 l cos x + l^2) (eq. 1 times u).
    Largest at t = 0: g'(pi) - g'(0) = 1/(1 - l) - 1/(1 + l) = 2 l/(1 - l^2) = 4/3; zero at the
    equal-speed points. Over a turn of t, g(t + pi) - g(t) swings up and down by u s =
    2 pi - 4 a (s the relative swing, a = u gamma_0/2 = arccos(l/sqrt(1 + l^2)), eq. 5), so
    the mean of |.| is 2 (2 pi - 4 a)/(2 pi). Ripple = (4/3)/mean.
    """
    g0 = np.arccos(0.5 / np.sqrt(1.25))  # u gamma_0 / 2 from eq. 5, u = 2
    swing_driving = 2 * (np.pi / 2 - g0) * 2  # relative swing times u (driving-angle units)
    mean = 2 * swing_driving / (2 * np.pi)
    want = (4 / 3) / mean
    s = evaluate(_cfg()).summary
    assert s["flow_ripple"] == pytest.approx(want, rel=1e-7)


# --------------------------------------------------------------------------------------------
# torques and energy
# --------------------------------------------------------------------------------------------
def _gauss_integral(f, edges, n=40):
    x, w = leggauss(n)
    total = 0.0
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        t = 0.5 * (b - a) * x + 0.5 * (a + b)
        total += 0.5 * (b - a) * float(np.sum(w * f(t)))
    return total


@pytest.mark.parametrize("case", CASES)
def test_cycle_work_through_the_drive_equals_sum_of_p_dv(case):
    """oint M_i q_i' dtheta (drive, Gauss quadrature on the smooth pieces) = sum_j oint p dV_j.

    Independent right-hand side: each chamber takes in (V_max - V_min) at p_s and delivers it
    at p_d, with V_max, V_min of the geometric model at the equal-speed points.
    """
    p = _pump(**case)
    ports = vp.PortPressures(PS, PD)
    g = _geometry(p)
    roots = _equal_speed_thetas(p.drive)
    per = gb.period(p.drive)
    edges = np.concatenate([[0.0], roots, [per]])

    def torque(t):
        _, dv = vp.chamber_volumes(p.pump, _m(p, t))
        m = tq.member_torques(
            vp.chamber_pressures(ports, dv), vp.volume_derivatives_dq(p.pump, _m(p, t))
        )
        return tq.shaft_torque_from_members(m, gb.impeller_angles(p.drive, t)[1])

    work = _gauss_integral(torque, edges)
    v = g.volumes(roots)
    strokes = np.max(v, axis=1) - np.min(v, axis=1)
    want = np.sum((PS - PD) * strokes)
    assert work == pytest.approx(want, rel=1e-9)
    # and the study reports it (per input turn and per period), with the mean torque
    s = evaluate(_cfg_from(p, ports)).summary
    assert s["indicated_work_per_period_J"] == pytest.approx(want, rel=1e-9)
    assert s["indicated_work_J"] == pytest.approx(want / p.drive.input_gear_ratio, rel=1e-9)
    assert s["mean_torque_Nm"] == pytest.approx(want / per, rel=1e-9)
    assert s["mean_torque_Nm"] < 0  # a pump takes torque from the shaft


def test_instantaneous_power_balance_with_speed_profile():
    """Motor power = -sum p dV/dt + d(KE)/dt, with a varying shaft speed.

    dV/dt from the geometric volumes (central differences in theta times omega); KE =
    1/2 J_eq omega^2 differenced along theta (d/dt = omega d/dtheta).
    """
    p = _pump(driver="guide", lam=0.4, u=2.0, i12=1.0, phase=2.6, z=2)
    ports = vp.PortPressures(PS, PD)
    g = _geometry(p)
    js, jm = 0.002, (0.004, 0.007)
    speed = [150.0, 170.0, 160.0, 140.0, 155.0]
    th = np.linspace(0.05, gb.period(p.drive) - 0.05, 97)
    st = pump_state(p.drive, p.pump, ports, (js, jm), speed, th)
    omega = st["omega"]
    h = 1e-6
    dvdt = (g.volumes(th + h) - g.volumes(th - h)) / (2 * h) * omega
    pressure = np.where(dvdt < 0, PD, PS)
    fluid_power = np.sum(pressure * dvdt, axis=0)  # power the fluid gives the mechanism

    def ke(t):
        w = pump_state(p.drive, p.pump, ports, (js, jm), speed, t)["omega"]
        dq = gb.impeller_angles(p.drive, t)[1]
        return 0.5 * (js + jm[0] * dq[0] ** 2 + jm[1] * dq[1] ** 2) * w**2

    dke_dt = (ke(th + 1e-5) - ke(th - 1e-5)) / 2e-5 * omega
    motor_power = -st["net"] * omega
    np.testing.assert_allclose(
        motor_power, -fluid_power + dke_dt, rtol=1e-6, atol=1e-6 * np.max(np.abs(motor_power))
    )


def test_member_torques_are_pressure_difference_times_area_moment():
    """Impeller torques: +-Z k (p_d - p_s), opposite on the two impellers (hand-derived)."""
    p = _pump()
    ports = vp.PortPressures(PS, PD)
    th = np.array([0.3, 2.0, 4.0, 6.0, 9.0, 12.0])
    st = pump_state(p.drive, p.pump, ports, (0.0, (0.0, 0.0)), 100.0, th)
    np.testing.assert_allclose(np.abs(st["M"]), 2 * p.volume_per_angle * (PD - PS), rtol=1e-14)
    np.testing.assert_allclose(st["M"][0], -st["M"][1], rtol=1e-14)
    # the chamber that shrinks is at the discharge pressure
    assert np.all((st["p"] == PD) == (st["dV"] < 0))


def test_flywheel_from_independent_energy_integration():
    """No inertia anywhere: Delta E of the fluid torque alone (geometry, cumulative sum)."""
    cfg = _cfg(
        machine={
            "inertia_shaft": 0.0,
            "inertia_impeller_1": 0.0,
            "inertia_impeller_2": 0.0,
            "speed_fluctuation": 0.05,
        }
    )
    s = evaluate(cfg).summary
    p = _pump()
    g = _geometry(p)
    omega = 1500 * np.pi / 30
    th, q = _numeric_flow(g, p.drive, 1.0)
    torque = -(PD - PS) * q
    e = np.concatenate([[0], np.cumsum(0.5 * (torque[1:] + torque[:-1]) * np.diff(th))])
    e -= th * e[-1] / th[-1]
    delta_e = e.max() - e.min()
    assert s["energy_fluctuation_J"] == pytest.approx(delta_e, rel=1e-6)
    assert s["flywheel_inertia_kgm2"] == pytest.approx(delta_e / (0.05 * omega**2), rel=1e-6)
    assert s["speed_fluctuation_without_flywheel"] is None or np.isnan(
        s["speed_fluctuation_without_flywheel"]
    )


# --------------------------------------------------------------------------------------------
# study
# --------------------------------------------------------------------------------------------
def _cfg(machine=None, loads=None, **drive):
    d = {
        "type": "guide_bar",
        "lambda": 0.5,
        "gear_ratio": 2.0,
        "input_gear_ratio": 2.0,
        "phase": np.pi,
        "driver": "crank",
    }
    d.update(drive)
    m = {
        "vanes_per_impeller": 2,
        "vane_angle": None,
        "hub_radius": 0.03,
        "casing_radius": 0.08,
        "axial_width": 0.04,
        "inertia_shaft": 0.001,
        "inertia_impeller_1": 0.005,
        "inertia_impeller_2": 0.005,
        "speed_fluctuation": 0.02,
    }
    m.update(machine or {})
    lo = {
        "impeller_torque_1": 10.0,
        "impeller_torque_2": 10.0,
        "suction_pressure": PS,
        "discharge_pressure": PD,
    }
    lo.update(loads or {})
    return {
        "drive": d,
        "machine": m,
        "loads": lo,
        "run": {"points": 361, "speed": 1500 * np.pi / 30},
    }


def _cfg_from(p, ports):
    dr = p.drive
    return _cfg(
        machine={
            "vanes_per_impeller": p.vanes_per_impeller,
            "vane_angle": p.vane_angle,
            "hub_radius": p.hub_radius,
            "casing_radius": p.casing_radius,
            "axial_width": p.axial_width,
        },
        loads={
            "suction_pressure": ports.suction_pressure,
            "discharge_pressure": ports.discharge_pressure,
        },
        **{"lambda": dr.lam},
        gear_ratio=dr.gear_ratio,
        input_gear_ratio=dr.input_gear_ratio,
        phase=dr.phase,
        driver=dr.driver,
    )


def test_summary_values_are_plain_python():
    s = evaluate(_cfg()).summary
    bad = {k: type(v) for k, v in s.items() if type(v) not in (float, int, str, bool)}
    assert not bad


def test_study_summary_of_the_example_by_hand():
    """The example pump: k = (80^2 - 30^2) mm^2 * 40 mm / 2 = 110 cm^3/rad; swing
    s = pi - 2 gamma_0 (u = 2), gamma_0 from eq. 5; 2 Z = 4 chambers, i12 = 2."""
    s = evaluate(_cfg()).summary
    k = 0.5 * (80**2 - 30**2) * 40 / 1000  # cm^3 per rad
    g0 = 2 * np.arccos(0.5 / np.sqrt(1.25)) / 2
    sw = np.pi - 2 * g0
    assert s["chamber_volume_max_cm3"] == pytest.approx(k * sw, rel=1e-12)
    assert s["chamber_volume_min_cm3"] == 0.0
    assert s["displacement_per_period_cm3"] == pytest.approx(4 * k * sw, rel=1e-12)
    assert s["displacement_cm3_per_rev"] == pytest.approx(2 * k * sw, rel=1e-12)
    assert s["displacement_per_impeller_rev_cm3"] == pytest.approx(8 * k * sw, rel=1e-12)
    assert s["flow_mean_l_per_min"] == pytest.approx(2 * k * sw * 1500 / 1000, rel=1e-9)
    assert s["hydraulic_power_W"] == pytest.approx(5e5 * 2 * k * sw * 1e-6 * 25, rel=1e-9)
    assert s["mean_torque_Nm"] == pytest.approx(-5e5 * 2 * k * sw * 1e-6 / (2 * np.pi), rel=1e-9)
    # the paper's constant-torque keys are still there
    assert s["input_torque_mean_Nm"] == pytest.approx(5.0)
    for key in (
        "flow_ripple",
        "torque_ripple",
        "flywheel_inertia_kgm2",
        "energy_fluctuation_J",
        "speed_fluctuation_without_flywheel",
        "impeller1_accel_peak_rad_per_s2",
    ):
        assert isinstance(s[key], float) and np.isfinite(s[key]), key
    # fluid torque ~ -|r'|: ripple (max - min)/|mean| = flow ripple at constant speed
    assert s["torque_ripple"] == pytest.approx(s["flow_ripple"], rel=1e-9)


def test_study_columns():
    res = evaluate(_cfg(machine={"vanes_per_impeller": 3, "vane_angle": 0.3}, gear_ratio=3.0))
    c = res.columns
    for key in (
        "chamber_a_volume_cm3",
        "chamber_b_volume_cm3",
        "chamber_a_pressure_bar",
        "flow_l_per_min",
        "impeller1_torque_Nm",
        "shaft_torque_Nm",
        "shaft_torque_with_inertia_Nm",
        "impeller1_speed_rad_per_s",
        "impeller2_accel_rad_per_s2",
        "shaft_speed_rpm",
    ):
        assert key in c and c[key].shape == (361,)
        assert key in res.column_docs
    np.testing.assert_allclose(
        c["shaft_torque_with_inertia_Nm"], c["shaft_torque_Nm"] - c["inertia_torque_Nm"]
    )
    # virtual work: shaft torque = sum_i M_i q_i'
    via = c["impeller1_torque_Nm"] * c["impeller1_speed_ratio"] + (
        c["impeller2_torque_Nm"] * c["impeller2_speed_ratio"]
    )
    np.testing.assert_allclose(c["shaft_torque_Nm"], via, rtol=1e-12, atol=1e-12)
    # flow in L/min = omega * 3 chambers * max(-dV, 0)
    omega = 1500 * np.pi / 30
    dv = np.stack([c["chamber_a_dvolume_cm3_per_rad"], c["chamber_b_dvolume_cm3_per_rad"]])
    np.testing.assert_allclose(
        c["flow_l_per_min"], 3 * omega * np.sum(np.maximum(-dv, 0), 0) * 60 / 1000
    )


@pytest.mark.parametrize(
    ("machine", "loads", "key", "text"),
    [
        ({"hub_radius": 0.08}, {}, "machine.hub_radius", "casing_radius = 80 mm"),
        ({"hub_radius": 0.0}, {}, "machine.hub_radius", "> 0"),
        ({"axial_width": 0.0}, {}, "machine.axial_width", "> 0"),
        ({"vanes_per_impeller": 0}, {}, "machine.vanes_per_impeller", "integer >= 1"),
        ({"vanes_per_impeller": 3}, {}, "machine.vanes_per_impeller", "<= 2"),
        ({"vanes_per_impeller": 7, "vane_angle": 0.01}, {}, "machine.vanes_per_impeller", "<= 6"),
        ({"vane_angle": np.radians(64.0)}, {}, "machine.vane_angle", "63.43 deg"),
        ({"vane_angle": 0.0}, {}, "machine.vane_angle", "0 deg < vane_angle"),
        ({"inertia_impeller_1": -1.0}, {}, "machine.inertia_impeller_1", ">= 0"),
        ({"speed_fluctuation": 0.0}, {}, "machine.speed_fluctuation", "0 < speed_fluctuation"),
        ({}, {"suction_pressure": 0.0}, "loads.suction_pressure", "> 0 bar"),
        ({}, {"discharge_pressure": -1.0}, "loads.discharge_pressure", "> 0 bar"),
    ],
)
def test_bad_inputs_name_the_key(machine, loads, key, text):
    with pytest.raises(ParameterError) as err:
        evaluate(_cfg(machine=machine, loads=loads))
    assert str(err.value).startswith(key + " = ")
    assert text in str(err.value)


def test_non_integer_vane_count_refused():
    drive = gb.GuideBar(0.5, 2.0)
    for z in (1.5, True, "2"):
        with pytest.raises(ParameterError, match="vanes_per_impeller"):
            gb_pump.vane_pump(drive, z)


def test_motor_when_discharge_below_suction():
    """p_d < p_s: the fluid drives the shaft (positive mean torque)."""
    s = evaluate(_cfg(loads={"suction_pressure": 6e5, "discharge_pressure": 1e5})).summary
    assert s["mean_torque_Nm"] > 0


def test_equal_port_pressures_give_no_fluid_torque():
    s = evaluate(_cfg(loads={"discharge_pressure": PS})).summary
    assert s["mean_torque_Nm"] == 0.0
    assert np.isnan(s["torque_ripple"])
    assert s["shaft_torque_min_Nm"] == 0.0 and s["shaft_torque_max_Nm"] == 0.0


@pytest.mark.slow
def test_plot_writes_pump_figures(tmp_path):
    res = evaluate(
        _cfg(
            machine={"vanes_per_impeller": 3},
            gear_ratio=3.0,
            driver="guide",
            phase=np.radians(150.0),
        )
    )
    paths = res.write_figures(tmp_path)
    names = {p.name for p in paths}
    assert {"pump_sections.png", "pump_chambers.png", "pump_flow.png", "pump_torque.png"} <= names
    for p in paths:
        assert p.stat().st_size > 10_000 and p.read_bytes()[:4] == b"\x89PNG"
