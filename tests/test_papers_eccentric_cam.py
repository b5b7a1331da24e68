"""Every published number of Zhu Ruilin & Zhu Guolin (2012), double eccentric cams.

Paper: "Analysis of the motions of the double eccentric cams used in a process
intensification equipment", Engineering Sciences (China) 14(10), 2012, section 2
(the worked example after eq. 6) and Fig. 6-8. Note: /work/shared/papers/eccentric_pistons.md.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.drives import evaluate
from rotorkin.drives.eccentric_cam import kinematics as ec

R, LAM, L = 0.080, 0.5, 1.000  # paper: R = 80 mm, lambda = 0.5, device length 1000 mm
E = LAM * R  # e = lambda R = 40 mm (paper)


def _cfg():
    return {
        "drive": {"type": "eccentric_cam", "disc_radius": R, "eccentricity": E,
                  "follower": "knife_edge", "roller_radius": 0.0},
        "machine": {"device_length": L},
        "loads": {},
        "run": {"points": 721},
    }  # fmt: skip


def test_eccentricity_of_the_example():
    """Paper: e = lambda R = 40 mm (exact arithmetic)."""
    assert ec.EccentricCam(R, E).eccentricity * 1e3 == pytest.approx(40.0, abs=1e-12)


def test_delta_ratio_at_90_deg():
    """Eq. 6 example: delta = -0.5359 at beta = 90 deg.

    The paper prints 4 decimals, so the tolerance is half a unit of the last digit (5e-5).
    """
    p = ec.EccentricCam(R, E)
    delta = float(ec.decomposition(p, np.pi / 2)["delta"])
    assert delta == pytest.approx(-0.5359, abs=5e-5)
    assert f"{delta:.4f}" == "-0.5359"
    # eq. 6 as printed, at 90 deg: (2/lambda)(sqrt(1 - lambda^2) - 1)
    assert (2.0 / LAM) * (np.sqrt(1.0 - LAM**2) - 1.0) == pytest.approx(-0.5359, abs=5e-5)


def test_gap_change_at_90_deg():
    """Eq. 5 example: Delta = delta e = -0.5359 x 40 = -21.4 mm.

    Printed with 3 significant digits: tolerance half a unit of the last digit, 0.05 mm.
    """
    p = ec.EccentricCam(R, E)
    assert float(ec.gap_change(p, np.pi / 2)[0]) * 1e3 == pytest.approx(-21.4, abs=0.05)
    s = evaluate(_cfg()).summary
    assert s["gap_change_min_mm"] == pytest.approx(-21.4, abs=0.05)
    assert s["gap_change_min_ratio"] == pytest.approx(-0.5359, abs=5e-5)
    assert s["gap_change_min_angle_deg"] == pytest.approx(90.0)


def test_gap_change_to_device_length():
    """Delta/L = 2.14 % for L = 1000 mm (printed 21.4/2000 = 2.14 %: an OCR misprint).

    21.4/2000 would be 1.07 %; the paper's 2.14 % is 21.4/1000. Tolerance half a unit of the
    printed last digit: 0.005 % (5e-5 as a fraction).
    """
    s = evaluate(_cfg()).summary
    assert s["gap_change_to_length"] == pytest.approx(0.0214, abs=5e-5)
    assert s["gap_change_to_length_percent"] == pytest.approx(2.14, abs=0.005)
    assert abs(s["gap_change_to_length"] - 21.4 / 2000) > 0.01  # the misprint would be far off


def test_section2_statements():
    """Statements after eq. 5: Delta < 0, symmetric about 90 deg, largest at 90 deg,
    period 180 deg, zero at k 180 deg, larger for larger lambda (Fig. 7); x' = x(180 - beta).

    Exact statements: tolerances are round-off only.
    """
    p = ec.EccentricCam(R, E)
    b = np.linspace(0.0, 2 * np.pi, 7201)
    D = ec.gap_change(p, b)[0]
    assert np.all(D <= 0)
    assert np.degrees(b[np.argmin(D[:3601])]) == pytest.approx(90.0)
    np.testing.assert_allclose(ec.gap_change(p, b + np.pi)[0], D, atol=1e-16)
    np.testing.assert_allclose(ec.gap_change(p, np.pi - b)[0], D, atol=1e-16)
    np.testing.assert_allclose(ec.gap_change(p, np.arange(5) * np.pi)[0], 0.0, atol=1e-16)
    small = ec.decomposition(ec.EccentricCam(R, 0.3 * R), np.pi / 2)["delta"]
    large = ec.decomposition(ec.EccentricCam(R, 0.7 * R), np.pi / 2)["delta"]
    assert abs(large) > abs(float(ec.decomposition(p, np.pi / 2)["delta"])) > abs(small)
    d = ec.decomposition(p, b)
    np.testing.assert_allclose(ec.decomposition(p, np.pi - b)["x"], d["x_right"], atol=1e-14)


def test_fig6_decomposition_and_fig8_range():
    """Fig. 6: x = xi + mu with xi = cos beta; Fig. 8: x runs from +1 to -1, x + x' = delta."""
    p = ec.EccentricCam(R, E)
    b = np.linspace(0, 2 * np.pi, 721)
    d = ec.decomposition(p, b)
    np.testing.assert_allclose(d["x"], d["xi"] + d["mu"], atol=1e-15)
    np.testing.assert_allclose(d["x"] + d["x_right"], d["delta"], atol=1e-15)
    assert d["x"].max() == pytest.approx(1.0) and d["x"].min() == pytest.approx(-1.0)


def test_flat_follower_is_harmonic():
    """Eq. 7, 8: with a flat contact plate z = e cos beta, z' = -e cos beta, Delta = 0."""
    p = ec.EccentricCam(R, E, "flat")
    b = np.linspace(0, 2 * np.pi, 361)
    z = ec.piston_travels(p, b)[0]
    np.testing.assert_allclose(z[0], E * np.cos(b), atol=1e-16)
    np.testing.assert_allclose(z[1], -E * np.cos(b), atol=1e-16)
    assert evaluate({**_cfg(), "drive": {**_cfg()["drive"], "follower": "flat"}}).summary[
        "gap_change_min_mm"
    ] == pytest.approx(0.0, abs=1e-15)


def test_section3_half_gap_is_lag_behind_tangent():
    """Section 3: a point-contact piston lags a flat one by Delta/2 = sqrt(R^2 - e^2 sin^2) - R."""
    b = np.linspace(0, 2 * np.pi, 181)
    knife = ec.piston_travels(ec.EccentricCam(R, E), b)[0]
    flat = ec.piston_travels(ec.EccentricCam(R, E, "flat"), b)[0]
    half = np.sqrt(R**2 - E**2 * np.sin(b) ** 2) - R
    np.testing.assert_allclose(knife - flat, np.stack([half, half]), atol=1e-16)
