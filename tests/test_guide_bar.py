"""Tests of the guide-bar + gear drive against independent geometric models."""

from __future__ import annotations

import dataclasses
import inspect

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from rotorkin.core.errors import ParameterError
from rotorkin.core.motion import Motion
from rotorkin.drives import evaluate
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar import pump as gb_pump
from rotorkin.drives.guide_bar.schema import GuideBarDrive, GuideBarLoads, VanePumpMachine
from rotorkin.machines import vane_pump as vp
from rotorkin.studies.helpers import build_params


# --------------------------------------------------------------------------------------------
# an independent model: a guide-bar mechanism placed anywhere in the plane, with real lengths
# --------------------------------------------------------------------------------------------
class Linkage:
    """Guide pivot C, crank pivot A = C + d (cos psi0, sin psi0), crank length a.

    Angles are measured from the line C -> A (psi0 in the plane).
    """

    def __init__(self, lam, a=0.137, psi0=0.7, C=(0.31, -0.52)):
        self.a, self.d, self.psi0 = a, lam * a, psi0
        self.C = np.array(C, dtype=float)
        self.A = self.C + self.d * np.array([np.cos(psi0), np.sin(psi0)])

    def pin(self, crank):
        w = self.psi0 + crank
        return self.A + self.a * np.array([np.cos(w), np.sin(w)])

    @staticmethod
    def _cross(u, v):
        return u[0] * v[1] - u[1] * v[0]

    def _dir(self, ang):
        w = self.psi0 + ang
        return np.array([np.cos(w), np.sin(w)])

    def guide_from_crank(self, x):
        """Guide angle whose ray from C passes through the crank pin (root finding)."""
        B = self.pin(x) - self.C
        return brentq(lambda p: self._cross(self._dir(p), B), x - np.pi / 2, x + np.pi / 2,
                      xtol=1e-15, rtol=1e-15)  # fmt: skip

    def crank_from_guide(self, y):
        """Crank angle whose pin lies on the guide's ray from C (root finding)."""
        u = self._dir(y)
        return brentq(lambda c: self._cross(u, self.pin(c) - self.C), y - np.pi / 2,
                      y + np.pi / 2, xtol=1e-15, rtol=1e-15)  # fmt: skip

    def guide_speed(self, x):
        """omega_guide / omega_crank by velocity analysis.

        v_B = omega_crank k x AB; omega_guide = (CB x v_B) / |CB|^2.
        """
        B = self.pin(x)
        CB, AB = B - self.C, B - self.A
        vB = np.array([-AB[1], AB[0]])
        return self._cross(CB, vB) / (CB @ CB)

    def crank_speed(self, y):
        """omega_crank / omega_guide (the inverse ratio at the matching crank angle)."""
        return 1.0 / self.guide_speed(self.crank_from_guide(y))

    def driven(self, driver, x):
        return self.guide_from_crank(x) if driver == "crank" else self.crank_from_guide(x)

    def speed(self, driver, x):
        return self.guide_speed(x) if driver == "crank" else self.crank_speed(x)


def _random_bar(rng, driver=None):
    return gb.GuideBar(
        lam=rng.uniform(0.05, 0.95),
        gear_ratio=rng.uniform(0.5, 4.0),
        input_gear_ratio=rng.uniform(0.5, 3.0),
        phase=rng.uniform(0.2, 6.0),
        driver=driver or rng.choice(gb.DRIVERS),
    )


# --------------------------------------------------------------------------------------------
# one mechanism
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_guide_angle_against_linkage(seed):
    rng = np.random.default_rng(seed)
    lam = rng.uniform(0.05, 0.95)
    link = Linkage(lam, a=rng.uniform(0.05, 0.5), psi0=rng.uniform(-3, 3), C=rng.normal(size=2))
    x = rng.uniform(-8, 8, 30)
    g, g1, _, _ = gb.guide_angle(lam, x)
    want = np.array([link.guide_from_crank(v) for v in x])
    np.testing.assert_allclose(g, want, rtol=0, atol=1e-12)
    np.testing.assert_allclose(g1, [link.guide_speed(v) for v in x], rtol=1e-12)


@pytest.mark.parametrize("seed", [4, 5, 6])
def test_crank_angle_against_linkage(seed):
    rng = np.random.default_rng(seed)
    lam = rng.uniform(0.05, 0.95)
    link = Linkage(lam, a=rng.uniform(0.05, 0.5), psi0=rng.uniform(-3, 3), C=rng.normal(size=2))
    y = rng.uniform(-8, 8, 30)
    h, h1, _, _ = gb.crank_angle(lam, y)
    np.testing.assert_allclose(h, [link.crank_from_guide(v) for v in y], rtol=0, atol=1e-12)
    np.testing.assert_allclose(h1, [link.crank_speed(v) for v in y], rtol=1e-11)


def test_crank_angle_is_inverse_of_guide_angle():
    rng = np.random.default_rng(8)
    lam = rng.uniform(0.05, 0.95, (5, 1))
    y = rng.uniform(-10, 10, (1, 40))
    back = gb.guide_angle(lam, gb.crank_angle(lam, y)[0])[0]
    np.testing.assert_allclose(back, np.broadcast_to(y, back.shape), atol=1e-12)
    # derivatives of inverse functions: h' g'(h) = 1
    h = gb.crank_angle(lam, y)
    np.testing.assert_allclose(h[1] * gb.guide_angle(lam, h[0])[1], 1.0, rtol=1e-13)


def test_zeros_and_continuity():
    lam = 0.8
    for f in (gb.guide_angle, gb.crank_angle):
        np.testing.assert_allclose(f(lam, np.arange(-4, 5) * np.pi)[0], np.arange(-4, 5) * np.pi,
                                   atol=1e-13)  # fmt: skip
        x = np.linspace(-20, 20, 400001)
        v = f(lam, x)[0]
        assert np.max(np.abs(np.diff(v))) < 10 * (x[1] - x[0])  # no 2 pi jumps
        np.testing.assert_allclose(f(lam, x + 2 * np.pi)[0], v + 2 * np.pi, atol=1e-12)


@pytest.mark.parametrize("fn", [gb.guide_angle, gb.crank_angle])
def test_mechanism_derivatives_against_finite_differences(fn):
    rng = np.random.default_rng(12)
    lam = rng.uniform(0.05, 0.95, 30)
    x = rng.uniform(-7, 7, 30)
    h = 1e-4
    lo, hi = fn(lam, x - h), fn(lam, x + h)
    exact = fn(lam, x)
    for n in range(3):
        fd = (hi[n] - lo[n]) / (2 * h)
        scale = 1.0 + np.abs(exact[n + 1])
        np.testing.assert_array_less(np.abs(fd - exact[n + 1]) / scale, 2e-5 * (1 + 30 * n))


def test_third_derivatives_richardson_tight():
    lam, x = 0.6, np.linspace(-3.1, 3.1, 31)
    for fn in (gb.guide_angle, gb.crank_angle):

        def cd(h, fn=fn):
            return (fn(lam, x + h)[2] - fn(lam, x - h)[2]) / (2 * h)

        rich = (4 * cd(5e-4) - cd(1e-3)) / 3
        np.testing.assert_allclose(rich, fn(lam, x)[3], rtol=0, atol=1e-9)


def test_paper_speed_ratios_eq1_eq3():
    """Eq. 1 is g'/u; eq. 3 (paper's zero) is our h' at y + pi, over u."""
    rng = np.random.default_rng(13)
    lam, u = rng.uniform(0.05, 0.95, (6, 1)), rng.uniform(0.5, 4, (6, 1))
    x = rng.uniform(-7, 7, (1, 50))
    np.testing.assert_allclose(gb.speed_ratio_eq1(lam, u, x), gb.guide_angle(lam, x)[1] / u,
                               rtol=1e-14)  # fmt: skip
    np.testing.assert_allclose(gb.speed_ratio_eq3(lam, u, x),
                               gb.crank_angle(lam, x + np.pi)[1] / u, rtol=1e-12)  # fmt: skip
    # and *not* at y itself (the zero of the paper differs from ours)
    assert np.max(np.abs(gb.speed_ratio_eq3(lam, u, x) - gb.crank_angle(lam, x)[1] / u)) > 0.01


def test_speed_ratio_range_and_mean():
    rng = np.random.default_rng(14)
    x = np.linspace(0, 2 * np.pi, 200001)
    for _ in range(5):
        lam, u = rng.uniform(0.05, 0.95), rng.uniform(0.5, 4)
        for driver in gb.DRIVERS:
            r = gb.driven_angle(lam, driver, x)[1] / u
            lo, hi = gb.speed_ratio_range(lam, u, driver)
            assert r.min() == pytest.approx(lo, rel=1e-9)
            assert r.max() == pytest.approx(hi, rel=1e-9)
            # mean over a turn (trapezoid on a periodic function: spectrally accurate)
            assert np.trapezoid(r, x) / (2 * np.pi) == pytest.approx(1 / u, rel=1e-12)
        # crank-driven fluctuates more than guide-driven (Fig. 3 vs 5)
        c = gb.speed_ratio_range(lam, u, "crank")
        g = gb.speed_ratio_range(lam, u, "guide")
        assert c[1] - c[0] > g[1] - g[0]


# --------------------------------------------------------------------------------------------
# the pair of mechanisms, the impellers
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("seed", [21, 22, 23, 24])
def test_impeller_angles_against_linkage(seed):
    rng = np.random.default_rng(seed)
    p = _random_bar(rng)
    link = Linkage(p.lam, psi0=rng.uniform(-3, 3))
    theta = rng.uniform(-10, 10, 20)
    q, dq, _, _ = gb.impeller_angles(p, theta)
    sig = (0.0, p.phase)
    for k in (0, 1):
        xk = sig[k] + theta / p.input_gear_ratio
        want = np.array([link.driven(p.driver, v) for v in xk]) / p.gear_ratio
        np.testing.assert_allclose(q[k], want, rtol=0, atol=1e-12)
        wspeed = np.array([link.speed(p.driver, v) for v in xk])
        np.testing.assert_allclose(dq[k], wspeed / (p.gear_ratio * p.input_gear_ratio),
                                   rtol=1e-11)  # fmt: skip


@pytest.mark.parametrize("seed", [31, 32])
def test_impeller_derivatives_against_finite_differences(seed):
    rng = np.random.default_rng(seed)
    for driver in gb.DRIVERS:
        p = _random_bar(rng, driver)
        theta = rng.uniform(-10, 10, 40)
        h = 1e-4 * p.input_gear_ratio
        lo, hi = gb.impeller_angles(p, theta - h), gb.impeller_angles(p, theta + h)
        exact = gb.impeller_angles(p, theta)
        for n in range(3):
            fd = (hi[n] - lo[n]) / (2 * h)
            scale = np.max(np.abs(exact[n + 1])) + 1e-300
            np.testing.assert_allclose(fd, exact[n + 1], rtol=0, atol=3e-6 * scale * (1 + 5 * n))


def test_period_and_advance():
    rng = np.random.default_rng(33)
    for driver in gb.DRIVERS:
        p = _random_bar(rng, driver)
        T = gb.period(p)
        assert T == pytest.approx(2 * np.pi * p.input_gear_ratio)
        theta = rng.uniform(-5, 5, 30)
        a, b = gb.impeller_angles(p, theta), gb.impeller_angles(p, theta + T)
        np.testing.assert_allclose(b[0], a[0] + 2 * np.pi / p.gear_ratio, atol=1e-12)
        for n in (1, 2, 3):
            np.testing.assert_allclose(b[n], a[n], atol=1e-12)


def test_shapes_0d_1d_3d():
    p = gb.GuideBar(0.4, 2.5, 1.5, 2.0, "guide")
    rng = np.random.default_rng(0)
    t3 = rng.uniform(-9, 9, (3, 2, 4))
    m3 = gb.motion(p, t3)
    assert isinstance(m3, Motion)
    assert m3.q.shape == (2, 3, 2, 4) and m3.members == ("impeller 1", "impeller 2")
    assert m3.unit == "rad"
    m1 = gb.motion(p, t3.ravel())
    for a3, a1 in zip((m3.q, m3.dq, m3.d2q, m3.d3q), (m1.q, m1.dq, m1.d2q, m1.d3q), strict=True):
        np.testing.assert_array_equal(a3.reshape(2, -1), a1)
    m0 = gb.motion(p, t3[2, 1, 3])
    assert m0.q.shape == (2,)
    np.testing.assert_array_equal(m0.d2q, m3.d2q[:, 2, 1, 3])
    assert gb.input_torque(p, 3.0, 4.0, t3).shape == t3.shape
    # loads broadcasting with theta
    m7 = rng.uniform(1, 5, (3, 1, 1))
    M = gb.input_torque(p, m7, 2.0, t3)
    np.testing.assert_allclose(M, m7 * m3.dq[0] + 2.0 * m3.dq[1])
    assert gb.vane_angle(np.full((2, 3), 0.5), 2.0, np.pi, "crank").shape == (2, 3)


# --------------------------------------------------------------------------------------------
# equal-speed points and vane angle: numeric model (sample, root-find, integrate)
# --------------------------------------------------------------------------------------------
def _numeric_vane_angle(lam, u, phase, driver):
    """Equal-speed points of both impellers by root finding; the slower's turn by quadrature."""
    link = Linkage(lam)

    def w(k, t):
        return link.speed(driver, t + (0.0, phase)[k]) / u

    def diff(t):
        return w(0, t) - w(1, t)

    grid = np.linspace(0.0, 2 * np.pi, 721) + 1e-3
    vals = np.array([diff(t) for t in grid])
    roots = [brentq(diff, grid[i], grid[i + 1], xtol=1e-14)
             for i in range(len(grid) - 1) if vals[i] * vals[i + 1] < 0]  # fmt: skip
    assert len(roots) == 2
    t0, t1 = roots
    turns = [quad(lambda t, k=k: w(k, t), t0, t1, epsabs=1e-13, epsrel=1e-13)[0] for k in (0, 1)]
    mid = 0.5 * (t0 + t1)
    slower = 0 if w(0, mid) < w(1, mid) else 1
    return turns[slower], turns[1 - slower], np.array(roots)


PHASES_DEG = [20.0, 75.0, 120.0, 180.0, 230.0, 300.0, 345.0, -100.0, 500.0]


@pytest.mark.parametrize("driver", gb.DRIVERS)
@pytest.mark.parametrize("phase_deg", PHASES_DEG)
def test_vane_angle_against_numeric_model(driver, phase_deg):
    rng = np.random.default_rng(int(phase_deg) % 97 + (driver == "guide"))
    lam, u = rng.uniform(0.1, 0.9), rng.uniform(1.0, 3.0)
    phase = np.radians(phase_deg)
    slow, fast, roots = _numeric_vane_angle(lam, u, phase, driver)
    g0 = float(gb.vane_angle(lam, u, phase, driver))
    assert g0 == pytest.approx(slow, abs=1e-9)
    assert fast == pytest.approx(2 * np.pi / u - g0, abs=1e-9)
    # the paper's general-Sigma formulas agree with the geometry at every phase
    assert float(gb.vane_angle_paper(lam, u, phase, driver)) == pytest.approx(slow, abs=1e-9)
    # equal-speed driving angles -Sigma/2 and pi - Sigma/2 (mod 2 pi)
    want = np.sort(np.mod(np.array(gb.equal_speed_angles(phase)) - 1e-3, 2 * np.pi) + 1e-3)
    np.testing.assert_allclose(np.sort(roots), want, atol=1e-9)
    # the angle between the impellers swings by 2 pi/u - 2 gamma_0
    p = gb.GuideBar(lam, u, 1.3, phase, driver)
    q = gb.impeller_angles(p, np.linspace(0, gb.period(p), 20001))[0]
    rel = q[1] - q[0]
    assert rel.max() - rel.min() == pytest.approx(gb.relative_angle_swing(p), abs=1e-7)
    assert gb.relative_angle_swing(p) == pytest.approx(fast - slow, abs=1e-9)


def test_vane_angle_half_turn_is_eq5_eq6():
    lam = np.linspace(0.01, 0.99, 99)
    for u in (1.0, 2.0, 3.0):
        c = gb.vane_angle_half_turn(lam, u, "crank")
        g = gb.vane_angle_half_turn(lam, u, "guide")
        np.testing.assert_allclose(np.arccos(lam / np.sqrt(1 + lam**2)) - u * c / 2, 0, atol=1e-14)
        np.testing.assert_allclose(np.arccos(lam) - u * g / 2, 0, atol=1e-14)
        np.testing.assert_allclose(gb.vane_angle(lam, u, np.pi, "crank"), c, atol=1e-13)
        np.testing.assert_allclose(gb.vane_angle(lam, u, np.pi, "guide"), g, atol=1e-13)
        # round trip through lambda_for_vane_angle
        np.testing.assert_allclose(gb.lambda_for_vane_angle(c, u, "crank"), lam, rtol=1e-11)
        np.testing.assert_allclose(gb.lambda_for_vane_angle(g, u, "guide"), lam, rtol=1e-11)
    assert np.isnan(gb.lambda_for_vane_angle(np.radians(100.0), 2.0, "crank"))
    assert np.isnan(gb.lambda_for_vane_angle(np.radians(40.0), 2.0, "crank"))  # would need >1


# --------------------------------------------------------------------------------------------
# torque
# --------------------------------------------------------------------------------------------
def test_input_torque_is_eq7_for_crank_driven():
    rng = np.random.default_rng(41)
    for _ in range(4):
        p = _random_bar(rng, "crank")
        theta = rng.uniform(-10, 10, 50)
        m7, m8 = rng.uniform(-20, 20, 2)
        phi = theta / p.input_gear_ratio
        want = gb.input_torque_eq7(p.lam, p.gear_ratio, p.input_gear_ratio, m7, m8, phi,
                                   p.phase + phi)  # fmt: skip
        np.testing.assert_allclose(gb.input_torque(p, m7, m8, theta), want, rtol=1e-13,
                                   atol=1e-13)  # fmt: skip


def test_input_torque_power_balance_with_finite_differences():
    """M1 dtheta = M7 dq_1 + M8 dq_2 with q from the independent linkage, by differences."""
    rng = np.random.default_rng(42)
    for driver in gb.DRIVERS:
        p = _random_bar(rng, driver)
        link = Linkage(p.lam)
        m7, m8 = 7.0, -3.0
        h = 1e-5
        for theta in rng.uniform(0, 10, 8):
            dq = []
            for s in (0.0, p.phase):
                x = s + np.array([theta - h, theta + h]) / p.input_gear_ratio
                qk = [link.driven(driver, v) / p.gear_ratio for v in x]
                dq.append((qk[1] - qk[0]) / (2 * h))
            want = m7 * dq[0] + m8 * dq[1]
            assert float(gb.input_torque(p, m7, m8, theta)) == pytest.approx(want, abs=1e-8)


def _fluctuation(lam, driver, m7, m8, phase=np.pi):
    p = gb.GuideBar(lam, 2.0, 2.0, phase, driver)
    M = gb.input_torque(p, m7, m8, np.linspace(0, gb.period(p), 4001))
    return M.max() - M.min()


@pytest.mark.parametrize(("m7", "m8"), [(10.0, 10.0), (10.0, 5.0), (3.0, 12.0)])
def test_torque_fluctuation_sweeps(m7, m8):
    """Fig. 10, 11 (u = 2, i12 = 2, Sigma = 180 deg).

    The fluctuation grows with lambda and is smaller guide-driven.
    """
    lams = np.linspace(0.05, 0.95, 19)
    crank = np.array([_fluctuation(lam, "crank", m7, m8) for lam in lams])
    guide = np.array([_fluctuation(lam, "guide", m7, m8) for lam in lams])
    assert np.all(np.diff(crank) > 0)
    assert np.all(guide < crank)
    if m7 == m8:
        # derived here: h'(y) + h'(y + pi) = 2, the guide-driven input torque is constant
        np.testing.assert_allclose(guide, 0.0, atol=1e-12)
    else:
        assert np.all(np.diff(guide) > 0)


def test_torque_mean_is_loads_over_ratios():
    rng = np.random.default_rng(43)
    for driver in gb.DRIVERS:
        p = _random_bar(rng, driver)
        th = np.linspace(0, gb.period(p), 40001)
        M = gb.input_torque(p, 4.0, 9.0, th)
        mean = np.trapezoid(M, th) / gb.period(p)
        assert mean == pytest.approx(13.0 / (p.gear_ratio * p.input_gear_ratio), rel=1e-10)


# --------------------------------------------------------------------------------------------
# parameters
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("kwargs", "name", "text"),
    [
        ({"lam": 1.0}, "lam", "oscillating guide bar"),
        ({"lam": 1.7}, "lam", "oscillating guide bar"),
        ({"lam": 0.0}, "lam", "0 < lambda < 1"),
        ({"lam": -0.2}, "lam", "0 < lambda < 1"),
        ({"gear_ratio": 0.0}, "gear_ratio", "u > 0"),
        ({"gear_ratio": -2.0}, "gear_ratio", "u > 0"),
        ({"input_gear_ratio": 0.0}, "input_gear_ratio", "i12 > 0"),
        ({"phase": 0.0}, "phase", "not a multiple of 360 deg"),
        ({"phase": 2 * np.pi}, "phase", "not a multiple of 360 deg"),
        ({"phase": -4 * np.pi}, "phase", "not a multiple of 360 deg"),
        ({"driver": "slider"}, "driver", "'crank', 'guide'"),
    ],
)
def test_parameter_errors(kwargs, name, text):
    args = {"lam": 0.5, "gear_ratio": 2.0, "input_gear_ratio": 2.0, "phase": np.pi,
            "driver": "crank"}  # fmt: skip
    args.update(kwargs)
    with pytest.raises(ParameterError) as info:
        gb.GuideBar(**args)
    assert info.value.name == name
    assert name in str(info.value) and text in str(info.value)
    with pytest.raises(ParameterError) as info:
        build_params(gb.GuideBar, "drive", args, aliases={"lam": "lambda"})
    assert f"drive.{'lambda' if name == 'lam' else name}" in str(info.value)


def test_defaults():
    p = gb.GuideBar(0.5, 2.0)
    assert p.input_gear_ratio == 2.0 and p.phase == pytest.approx(np.pi) and p.driver == "crank"


# --------------------------------------------------------------------------------------------
# study
# --------------------------------------------------------------------------------------------
def _cfg(machine=None, **drive):
    d = {"type": "guide_bar", "lambda": 0.5, "gear_ratio": 2.0, "input_gear_ratio": 2.0,
         "phase": np.pi, "driver": "crank"}  # fmt: skip
    d.update(drive)
    return {
        "drive": d,
        "machine": dict(machine or {}),
        "loads": {"impeller_torque_1": 10.0, "impeller_torque_2": 6.0},
        "run": {"points": 361},
    }


REQUIRED = (
    "vane_angle_deg",
    "impeller_speed_ratio_min",
    "impeller_speed_ratio_max",
    "input_torque_min_Nm",
    "input_torque_max_Nm",
)


@pytest.mark.parametrize(
    ("driver", "lam", "u", "i12", "phase_deg"),
    [("crank", 0.5, 2.0, 2.0, 180.0), ("guide", 0.5, 2.0, 2.0, 180.0),
     ("crank", 0.7, 3.0, 1.5, 110.0), ("guide", 0.3, 1.5, 0.8, 250.0)],
)  # fmt: skip
def test_study_summary(driver, lam, u, i12, phase_deg):
    phase = np.radians(phase_deg)
    # with the default vane angle gamma_0 at most floor(u) vanes per impeller fit (pump)
    res = evaluate(_cfg(driver=driver, **{"lambda": lam}, gear_ratio=u, input_gear_ratio=i12,
                        phase=phase, machine={"vanes_per_impeller": int(u)}))  # fmt: skip
    s = res.summary
    for key in REQUIRED + ("vane_angle_other_driver_deg", "equal_speed_driving_angle_1_deg",
                           "input_torque_mean_Nm", "input_torque_fluctuation_ratio",
                           "impeller_accel_peak_per_rad"):  # fmt: skip
        assert key in s and isinstance(s[key], (float, int, str))
    slow, _, roots = _numeric_vane_angle(lam, u, phase, driver)
    assert s["vane_angle_deg"] == pytest.approx(np.degrees(slow), abs=1e-7)
    other = "guide" if driver == "crank" else "crank"
    assert s["vane_angle_other_driver_deg"] == pytest.approx(
        np.degrees(_numeric_vane_angle(lam, u, phase, other)[0]), abs=1e-7
    )
    assert [s["equal_speed_driving_angle_1_deg"], s["equal_speed_driving_angle_2_deg"]] == (
        pytest.approx(np.degrees(np.sort(np.mod(roots, 2 * np.pi))), abs=1e-7)
    )
    # speed ratios (over the driving member) and torques from the independent linkage
    link = Linkage(lam)
    t = np.linspace(0, 2 * np.pi, 2001)
    w = np.array([[link.speed(driver, v + s_) / u for v in t] for s_ in (0.0, phase)])
    assert s["impeller_speed_ratio_min"] == pytest.approx(w.min(), rel=1e-5)
    assert s["impeller_speed_ratio_max"] == pytest.approx(w.max(), rel=1e-5)
    M = (10.0 * w[0] + 6.0 * w[1]) / i12
    assert s["input_torque_min_Nm"] == pytest.approx(M.min(), rel=1e-5)
    assert s["input_torque_max_Nm"] == pytest.approx(M.max(), rel=1e-5)
    assert s["input_torque_mean_Nm"] == pytest.approx(16.0 / (u * i12), rel=1e-12)
    assert set(res.headline) <= set(s)
    cols = res.columns
    assert list(cols)[0] == "theta_deg" and cols["theta_deg"][-1] == pytest.approx(360 * i12)
    assert all(np.shape(v) == (361,) for v in cols.values())
    rel = cols["impeller2_angle_deg"] - cols["impeller1_angle_deg"]
    np.testing.assert_allclose(cols["relative_angle_deg"], rel)


def test_study_zero_loads_fluctuation_ratio_is_nan():
    cfg = _cfg()
    cfg["loads"] = {"impeller_torque_1": 0.0, "impeller_torque_2": 0.0}
    s = evaluate(cfg).summary
    assert s["input_torque_min_Nm"] == 0.0 and s["input_torque_max_Nm"] == 0.0
    assert np.isnan(s["input_torque_fluctuation_ratio"])


def test_study_errors_name_config_keys():
    with pytest.raises(ParameterError, match=r"drive\.lambda = 1\.2.*oscillating guide bar"):
        evaluate(_cfg(**{"lambda": 1.2}))
    with pytest.raises(ParameterError, match=r"drive\.phase"):
        evaluate(_cfg(phase=0.0))


@pytest.mark.slow
def test_study_plot_writes_pngs(tmp_path):
    cfg = _cfg(driver="guide", phase=np.radians(120.0))
    cfg["loads"] = {"impeller_torque_1": 0.0, "impeller_torque_2": 0.0}
    paths = evaluate(cfg).write_figures(tmp_path)
    assert len(paths) == 11  # 6 of the drive (paper) + 4 of the pump + the forces
    for p in paths:
        assert p.exists() and p.suffix == ".png" and p.stat().st_size > 1000
        assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_fig9_ordering_reverses_at_small_phase():
    """Derived here: Fig. 9's "crank-driven needs the larger vane angle" holds near Sigma = 180 deg
    only; at Sigma = 60 deg (lambda 0.5, u 2) the guide-driven vane angle is the larger one.
    Both sides from the numeric model."""
    crank = _numeric_vane_angle(0.5, 2.0, np.radians(60.0), "crank")[0]
    guide = _numeric_vane_angle(0.5, 2.0, np.radians(60.0), "guide")[0]
    assert guide > crank + 1e-3
    assert float(gb.vane_angle(0.5, 2.0, np.radians(60.0), "guide")) > float(
        gb.vane_angle(0.5, 2.0, np.radians(60.0), "crank")
    )
    crank = _numeric_vane_angle(0.5, 2.0, np.pi, "crank")[0]
    guide = _numeric_vane_angle(0.5, 2.0, np.pi, "guide")[0]
    assert crank > guide + 1e-3


# --------------------------------------------------------------------------------------------
# one source of defaults: the schema
# --------------------------------------------------------------------------------------------
def _schema_defaults():
    """Every section's defaults parsed through the schema (SI), by field name."""
    drive = GuideBarDrive(type="guide_bar", **{"lambda": 0.5}, gear_ratio=2.0)
    required = {"type", "lam", "gear_ratio"}  # given above, no default to compare
    return {
        "drive": {k: v for k, v in drive.model_dump().items() if k not in required},
        "machine": VanePumpMachine().model_dump(),
        "loads": GuideBarLoads().model_dump(),
    }


def _dataclass_defaults(cls):
    return {
        f.name: f.default for f in dataclasses.fields(cls) if f.default is not dataclasses.MISSING
    }


def test_every_dataclass_default_is_the_schema_default():
    """GuideBar ~ [drive], VanePump and vane_pump() ~ [machine], PortPressures ~ [loads]."""
    schema = _schema_defaults()
    pump_fn = {
        name: par.default
        for name, par in inspect.signature(gb_pump.vane_pump).parameters.items()
        if par.default is not inspect.Parameter.empty
    }
    pairs = (
        ("drive", _dataclass_defaults(gb.GuideBar)),
        ("machine", _dataclass_defaults(vp.VanePump)),
        ("loads", _dataclass_defaults(vp.PortPressures)),
        ("machine", pump_fn),
    )
    compared = []
    for section, defaults in pairs:
        for name, value in defaults.items():
            assert name in schema[section], f"{name}: no field of that name in [{section}]"
            want = schema[section][name]
            assert value == want and (value is None) == (want is None), (
                f"{name}: dataclass default {value!r} != schema [{section}] default {want!r}"
            )
            compared.append(name)
    # every default is compared; the schema's defaults of these sections are all covered
    assert {"input_gear_ratio", "phase", "driver"} <= set(compared)
    assert {"vanes_per_impeller", "hub_radius", "casing_radius", "axial_width"} <= set(compared)
    assert {"suction_pressure", "discharge_pressure", "vane_angle"} <= set(compared)


def test_the_defaults_check_fails_on_a_mismatch():
    """The comparison above is not vacuous: a changed default is caught."""

    @dataclasses.dataclass(frozen=True)
    class Shifted:
        lam: float
        gear_ratio: float
        input_gear_ratio: float = 2.0
        phase: float = np.pi / 2.0
        driver: str = "crank"

    schema = _schema_defaults()["drive"]
    bad = {k: v for k, v in _dataclass_defaults(Shifted).items() if schema[k] != v}
    assert bad == {"phase": np.pi / 2.0}


def test_study_keeps_the_impellers_motion_on_the_column_grid():
    """StudyResult.motion: both impellers over one period, on the grid of the columns."""
    res = evaluate(_cfg(driver="guide", input_gear_ratio=1.5, phase=2.0))
    m, c = res.motion, res.columns
    assert isinstance(m, Motion) and m.members == ("impeller 1", "impeller 2")
    np.testing.assert_allclose(np.degrees(m.theta), c["theta_deg"], rtol=1e-15, atol=0)
    assert m.theta[0] == 0.0 and m.theta[-1] == pytest.approx(2 * np.pi * 1.5, rel=1e-15)
    for k in (1, 2):
        np.testing.assert_array_equal(np.degrees(m.q[k - 1]), c[f"impeller{k}_angle_deg"])
        np.testing.assert_array_equal(m.dq[k - 1], c[f"impeller{k}_speed_ratio"])
        np.testing.assert_array_equal(m.d3q[k - 1], c[f"impeller{k}_jerk_per_rad2"])
