"""Every published number and statement of the guide-bar vane pump paper (JHIT 44(9), 2012).

Paper: "Kinematic and mechanical characteristics of the drive system of a differential
vane pump", J. Harbin Institute of Technology 44(9), 2012, sections 2-4, eq. 1-7, Fig. 3, 5,
9-11. Note: /work/shared/papers/guide_bar_pump.md.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.drives import evaluate
from rotorkin.drives.guide_bar import kinematics as gb

LAM, U, I12, SIGMA = 0.5, 2.0, 2.0, np.pi  # Fig. 3, 5, 10, 11: lambda 0.5, u 2, i12 2, 180 deg


def _cfg(driver):
    return {
        "drive": {"type": "guide_bar", "lambda": LAM, "gear_ratio": U, "input_gear_ratio": I12,
                  "phase": SIGMA, "driver": driver},
        "machine": {},
        "loads": {"impeller_torque_1": 10.0, "impeller_torque_2": 10.0},
        "run": {"points": 721},
    }  # fmt: skip


def test_vane_angle_crank_driven_example():
    """Eq. 5 with lambda = 0.5, u = 2: gamma_0 = 63.43 deg (crank-driven).

    Printed to 2 decimals: tolerance half a unit of the last digit, 0.005 deg. Checked through
    eq. 5 itself, the geometric vane angle, the paper's general-Sigma formula and the study.
    """
    assert np.degrees(gb.vane_angle_half_turn(LAM, U, "crank")) == pytest.approx(63.43, abs=0.005)
    assert np.degrees(gb.vane_angle(LAM, U, SIGMA, "crank")) == pytest.approx(63.43, abs=0.005)
    assert np.degrees(gb.vane_angle_paper(LAM, U, SIGMA, "crank")) == pytest.approx(
        63.43, abs=0.005
    )
    assert evaluate(_cfg("crank")).summary["vane_angle_deg"] == pytest.approx(63.43, abs=0.005)


def test_vane_angle_guide_driven_example():
    """Eq. 6 with lambda = 0.5, u = 2: gamma_0 = 60.00 deg (guide-driven); tolerance 0.005 deg."""
    assert np.degrees(gb.vane_angle_half_turn(LAM, U, "guide")) == pytest.approx(60.0, abs=0.005)
    assert np.degrees(gb.vane_angle(LAM, U, SIGMA, "guide")) == pytest.approx(60.0, abs=0.005)
    assert np.degrees(gb.vane_angle_paper(LAM, U, SIGMA, "guide")) == pytest.approx(60.0, abs=0.005)
    s = evaluate(_cfg("guide")).summary
    assert s["vane_angle_deg"] == pytest.approx(60.0, abs=0.005)
    assert s["vane_angle_other_driver_deg"] == pytest.approx(63.43, abs=0.005)


def test_eq5_eq6_residuals_vanish():
    """Eq. 5: arccos(lambda / sqrt(1 + lambda^2)) - u gamma_0 / 2 = 0; eq. 6: arccos(lambda) - ...

    Residuals of the equations as printed, at our gamma_0: round-off tolerance 1e-12.
    """
    lam = np.linspace(0.02, 0.98, 49)
    for u in (2.0, 3.0):
        gc = gb.vane_angle(lam, u, SIGMA, "crank")
        gg = gb.vane_angle(lam, u, SIGMA, "guide")
        np.testing.assert_allclose(np.arccos(lam / np.sqrt(1 + lam**2)) - u * gc / 2, 0, atol=1e-12)
        np.testing.assert_allclose(np.arccos(lam) - u * gg / 2, 0, atol=1e-12)


def test_fig9_crank_driven_needs_larger_vane_angle():
    """Fig. 9 (Sigma = 180 deg, u = 2, 3): at equal lambda curves 1, 3 (crank) lie above 2, 4."""
    lam = np.linspace(0.01, 0.99, 99)
    for u in (2.0, 3.0):
        assert np.all(gb.vane_angle(lam, u, SIGMA, "crank") > gb.vane_angle(lam, u, SIGMA, "guide"))
        # and the vane angle falls as lambda grows (the curves of Fig. 9 are monotonic)
        assert np.all(np.diff(gb.vane_angle(lam, u, SIGMA, "crank")) < 0)
        assert np.all(np.diff(gb.vane_angle(lam, u, SIGMA, "guide")) < 0)


def test_fig3_fig5_equal_ordinates_at_180_deg():
    """Fig. 3, 5 (Sigma = 180 deg): both crossings of the speed curves have the same ordinate.

    Exact statement: tolerance round-off.
    """
    for driver in gb.DRIVERS:
        s = evaluate(_cfg(driver)).summary
        assert s["equal_speed_ratio_1"] == pytest.approx(s["equal_speed_ratio_2"], abs=1e-14)
        assert s["equal_speed_driving_angle_1_deg"] == pytest.approx(90.0)
        assert s["equal_speed_driving_angle_2_deg"] == pytest.approx(270.0)


def test_fig3_vs_fig5_crank_driven_fluctuates_more():
    """Section 2.2: the crank-driven impeller speeds fluctuate more than the guide-driven ones.

    At lambda = 0.5, u = 2: crank 1/3 ... 1, guide 1/4 ... 3/4 (closed forms of eq. 1, 3).
    """
    c = evaluate(_cfg("crank")).summary
    g = evaluate(_cfg("guide")).summary
    assert c["impeller_speed_ratio_min"] == pytest.approx(1 / 3, rel=1e-12)
    assert c["impeller_speed_ratio_max"] == pytest.approx(1.0, rel=1e-12)
    assert g["impeller_speed_ratio_min"] == pytest.approx(0.25, rel=1e-12)
    assert g["impeller_speed_ratio_max"] == pytest.approx(0.75, rel=1e-12)
    assert (c["impeller_speed_ratio_max"] - c["impeller_speed_ratio_min"]) > (
        g["impeller_speed_ratio_max"] - g["impeller_speed_ratio_min"]
    )


def test_eq1_eq2_eq3_as_printed():
    """Eq. 1, 2 (crank) and eq. 3, 4 (guide, its zero at our y = pi) against our motion."""
    theta = np.linspace(0, 4 * np.pi, 97)
    phi = theta / I12
    pc = gb.GuideBar(LAM, U, I12, SIGMA, "crank")
    dq = gb.impeller_angles(pc, theta)[1] * I12  # per crank speed
    np.testing.assert_allclose(dq[0], gb.speed_ratio_eq1(LAM, U, phi), rtol=1e-13)
    np.testing.assert_allclose(dq[1], gb.speed_ratio_eq1(LAM, U, SIGMA + phi), rtol=1e-13)
    pg = gb.GuideBar(LAM, U, I12, SIGMA, "guide")
    dq = gb.impeller_angles(pg, theta)[1] * I12
    np.testing.assert_allclose(dq[0], gb.speed_ratio_eq3(LAM, U, phi - np.pi), rtol=1e-12)
    np.testing.assert_allclose(dq[1], gb.speed_ratio_eq3(LAM, U, SIGMA + phi - np.pi), rtol=1e-12)


def test_eq7_input_torque_and_fig10_fig11():
    """Eq. 7 and Fig. 10, 11 (u = 2, i12 = 2).

    The fluctuation grows with lambda and is far smaller guide-driven.

    M7 = M8 = 10 N*m (the paper gives no values). Checked against eq. 7 as printed (round-off
    tolerance); the crank-driven extremes at lambda = 0.5 follow by hand from eq. 7:
    M1 = (M / (u i12)) (2 / (1 + l^2)) = 4 N*m at x = 90 deg and (M / (u i12)) (2 / (1 - l^2))
    = 6.667 N*m at x = 0 (summary sampled on 20001 points: tolerance 1e-6 N*m).
    """
    s = evaluate(_cfg("crank")).summary
    assert s["input_torque_min_Nm"] == pytest.approx(2.5 * 2 / (1 + LAM**2), abs=1e-6)
    assert s["input_torque_max_Nm"] == pytest.approx(2.5 * 2 / (1 - LAM**2), abs=1e-6)
    theta = np.linspace(0, 4 * np.pi, 721)
    pc = gb.GuideBar(LAM, U, I12, SIGMA, "crank")
    np.testing.assert_allclose(
        gb.input_torque(pc, 10.0, 10.0, theta),
        gb.input_torque_eq7(LAM, U, I12, 10.0, 10.0, theta / I12, SIGMA + theta / I12),
        rtol=1e-13,
    )
    fluct = {}
    for driver in gb.DRIVERS:
        fluct[driver] = []
        for lam in (0.3, 0.5, 0.7):
            p = gb.GuideBar(lam, U, I12, SIGMA, driver)
            M = gb.input_torque(p, 10.0, 10.0, theta)
            fluct[driver].append(M.max() - M.min())
    assert np.all(np.diff(fluct["crank"]) > 0)
    assert np.all(np.array(fluct["guide"]) < 0.1 * np.array(fluct["crank"]))


def test_speed_ratio_averages_one_over_u():
    """Note on eq. 3: over a turn the ratio averages 1/u (either zero convention)."""
    x = np.linspace(0, 2 * np.pi, 100001)
    for f in (gb.speed_ratio_eq1, gb.speed_ratio_eq3):
        assert np.trapezoid(f(LAM, U, x), x) / (2 * np.pi) == pytest.approx(1 / U, rel=1e-12)
