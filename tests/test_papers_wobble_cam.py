"""Published numbers and statements of Chen Hu et al. (2015), wobble plate + spherical cam.

Source: /work/shared/papers/wobble_cam.md (note) and original/000_6ae3d194aa17d620.txt.
Table 1: eps = 10, phi = 45 deg, alpha = 90 deg, spin law varphi = -2 theta, cam psi = -theta.

Tolerances: the note gives values computed from the paper's equations rounded to
0.01 deg, so those are checked to 0.005 deg (half the last digit). The paper's
own text only says "about 39 deg" (Fig. 10) and "about 65 deg" (Fig. 13), read
off plots: those are checked to 0.5 deg and 1 deg.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.analysis.engine_cycle import POWER
from rotorkin.drives.wobble_cam import engine as eng
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.drives.wobble_cam import study as study
from rotorkin.machines import twin_rotor as tr

D = np.pi / 180.0
HALF_LAST_DIGIT_DEG = 0.005


def table1():
    return wc.WobbleCam(plate_tilt=45 * D, roller_axis_angle=90 * D, spin_ratio=-2.0)


def table1_cfg():
    return {
        "drive": {
            "type": "wobble_cam",
            "plate_tilt": 45 * D,
            "roller_axis_angle": 90 * D,
            "spin_ratio": -2.0,
            "sphere_radius": 0.05,
        },
        "machine": {"compression_ratio": 10.0},
        "run": {"points": 721},
        "loads": {},
    }


def deg(x):
    return float(np.degrees(x))


# --------------------------------------------------------------------------------------------
# Table 1 numbers
# --------------------------------------------------------------------------------------------
def test_slider_angle_extremes_table1():
    """Eq. 15 + 17 at Table 1: alpha'_max = 109.47 deg, alpha'_min = 70.53 deg (note; 0.005 deg)."""
    amax, amin = wc.slider_angle_extremes(45 * D, 90 * D)
    assert deg(amax) == pytest.approx(109.47, abs=HALF_LAST_DIGIT_DEG)
    assert deg(amin) == pytest.approx(70.53, abs=HALF_LAST_DIGIT_DEG)
    # the same extremes as the maximum / minimum of eq. 15 over one shaft turn
    theta = np.linspace(0, 2 * np.pi, 14401)
    s = np.degrees(np.subtract(*wc.rotor_angles(table1(), theta)[0][::-1]))
    assert s.max() == pytest.approx(109.47, abs=HALF_LAST_DIGIT_DEG)
    assert s.min() == pytest.approx(70.53, abs=HALF_LAST_DIGIT_DEG)


def test_chamber_swing_table1():
    """Fig. 10 / eq. 23: swing 38.94 deg from eq. 15 (0.005 deg); the paper says "about 39 deg"
    (section 4.2.3, read off Fig. 10: 0.5 deg)."""
    lay = wc.piston_layout(table1(), 10.0)
    assert deg(lay.swing) == pytest.approx(38.94, abs=HALF_LAST_DIGIT_DEG)
    assert deg(lay.swing) == pytest.approx(39.0, abs=0.5)
    theta = np.linspace(0, 2 * np.pi, 14401)
    q = wc.rotor_angles(table1(), theta)[0]
    da, db = wc.chamber_angles(lay.piston_width, q[1] - q[0])
    for k in (da, db):
        assert deg(k.max() - k.min()) == pytest.approx(38.94, abs=HALF_LAST_DIGIT_DEG)


def test_piston_width_and_chamber_extremes_table1():
    """Eq. 21-22, Table 1: beta = 21.20, delta_min = 4.33, delta_max = 43.27 deg (note; 0.005 deg).

    Also checks eq. 21 and 22 as printed give the same numbers from alpha'_min.
    """
    lay = wc.piston_layout(table1(), 10.0)
    assert deg(lay.piston_width) == pytest.approx(21.20, abs=HALF_LAST_DIGIT_DEG)
    assert deg(lay.chamber_a_min) == pytest.approx(4.33, abs=HALF_LAST_DIGIT_DEG)
    assert deg(lay.chamber_a_max) == pytest.approx(43.27, abs=HALF_LAST_DIGIT_DEG)
    assert deg(lay.chamber_b_min) == pytest.approx(4.33, abs=HALF_LAST_DIGIT_DEG)
    assert deg(lay.chamber_b_max) == pytest.approx(43.27, abs=HALF_LAST_DIGIT_DEG)
    eps, amax, amin = 10.0, 109.47 * D, 70.53 * D  # the note's rounded values
    beta21 = (eps + 1) / (eps - 1) * amin - np.pi * (eps + 3) / (4 * (eps - 1))
    delta22 = lambda a: a - (eps + 1) / (eps - 1) * amin + np.pi / (eps - 1)  # noqa: E731
    assert deg(beta21) == pytest.approx(21.20, abs=0.01)  # rounded inputs: 0.01 deg
    assert deg(delta22(amin)) == pytest.approx(4.33, abs=0.01)
    assert deg(delta22(amax)) == pytest.approx(43.27, abs=0.01)


def test_gamma_is_22_5_deg():
    """Eq. 18 + 19 give gamma = 22.5 deg (section 2.2.2; exact)."""
    assert deg(wc.PISTON_OFFSET) == pytest.approx(22.5, abs=1e-12)


def test_volume_cycles_and_power_strokes():
    """Section 1.2: 4 volume cycles per chamber per turn, 8 chambers, 32 in all, 16 power strokes
    (integers, exact). Counted here on the chamber-angle curve over one turn."""
    p = table1()
    lay = wc.piston_layout(p, 10.0)
    theta = np.linspace(0, 2 * np.pi, 36000, endpoint=False)
    q = wc.rotor_angles(p, theta)[0]
    da, _ = wc.chamber_angles(lay.piston_width, q[1] - q[0])
    minima = int(np.sum((da < np.roll(da, 1)) & (da < np.roll(da, -1))))
    assert minima == wc.volume_cycles_per_rev(p) == 4
    assert wc.CHAMBERS * minima == 32
    assert wc.power_strokes_per_rev(p) == 16
    s = study.evaluate(table1_cfg()).summary
    assert s["volume_cycles_per_rev"] == 4
    assert s["volume_cycles_per_rev_all_chambers"] == 32
    assert s["power_strokes_per_rev"] == 16


def test_two_chambers_in_power_stroke_at_every_instant():
    """Section 1.2: "at every instant 2 working chambers are in the power stroke".

    Exactly 4 of the 8 chambers expand at any instant (delta_A + delta_B is constant,
    eq. 18); in a four-stroke cycle every other expansion is a power stroke, so 2.
    Checked away from the turning points (exact integer count).
    """
    p = table1()
    theta = np.linspace(0.01, 2 * np.pi, 5000)
    h = 1e-5
    k = np.arange(4)[:, None]

    def gaps(t):
        """The 8 gaps between the labelled pistons, in their order around the cylinder."""
        q = wc.rotor_angles(p, t)[0]
        p1 = q[0] + np.pi / 8 + k * np.pi / 2  # rotor 1 pistons
        p2 = q[1] - np.pi / 8 + k * np.pi / 2  # rotor 2 pistons
        return np.concatenate(
            [p2 - p1, np.roll(p1, -1, axis=0) + np.where(k == 3, 2 * np.pi, 0) - p2]
        )

    g0 = gaps(theta)
    assert np.all(g0 > 0) and np.allclose(g0.sum(axis=0), 2 * np.pi)
    rate = (gaps(theta + h) - gaps(theta - h)) / (2 * h)
    moving = np.all(np.abs(rate) > 1e-4, axis=0)  # away from the turning points
    expanding = np.sum(rate[:, moving] > 0, axis=0)
    assert moving.mean() > 0.95
    assert np.all(expanding == 4)  # 4 expand: 2 power strokes + 2 intake strokes


def test_max_plate_tilt():
    """Eq. 20 / Fig. 13: largest plate tilt "about 65 deg" (paper, read off Fig. 13: 1 deg);
    65.53 deg solving eq. 15 (note: 0.005 deg). At it alpha'_max = 135 deg, alpha'_min = 45 deg."""
    lim = wc.max_plate_tilt(90 * D)
    assert deg(lim) == pytest.approx(65.53, abs=HALF_LAST_DIGIT_DEG)
    assert deg(lim) == pytest.approx(65.0, abs=1.0)
    amax, amin = wc.slider_angle_extremes(lim, 90 * D)
    assert deg(amax) == pytest.approx(135.0, abs=1e-9)
    assert deg(amin) == pytest.approx(45.0, abs=1e-9)
    assert study.evaluate(table1_cfg()).summary["max_plate_tilt_deg"] == pytest.approx(
        65.53, abs=HALF_LAST_DIGIT_DEG
    )


def test_study_headline_table1():
    """All headline numbers of the study at Table 1 (note's values, 0.005 deg)."""
    s = study.evaluate(table1_cfg()).summary
    expected = {
        "slider_angle_max_deg": 109.47,
        "slider_angle_min_deg": 70.53,
        "chamber_angle_max_deg": 43.27,
        "chamber_angle_min_deg": 4.33,
        "chamber_swing_deg": 38.94,
        "piston_width_deg": 21.20,
        "max_plate_tilt_deg": 65.53,
    }
    for k, v in expected.items():
        assert s[k] == pytest.approx(v, abs=HALF_LAST_DIGIT_DEG), k


# --------------------------------------------------------------------------------------------
# equations as printed (with the note's misprint corrections)
# --------------------------------------------------------------------------------------------
def test_eq8_and_eq11_as_printed():
    """Eq. 8 (roller in the fixed frame) and eq. 11 (groove in the cam frame), with
    cos(phi) cos(varphi) for the OCR's "cos phi cos phi" (exact up to rounding, 1e-12 m)."""
    p = table1()
    rng = np.random.default_rng(3)
    theta = rng.uniform(0, 2 * np.pi, 50)
    v = -2 * theta + (-45 * D)  # roller 1: varphi + c, c = -alpha/2
    ph, r = 45 * D, p.sphere_radius
    eq8 = r * np.array(
        [
            np.sin(ph) * np.cos(v),
            np.cos(theta) * np.sin(v) + np.sin(theta) * np.cos(ph) * np.cos(v),
            -np.sin(theta) * np.sin(v) + np.cos(theta) * np.cos(ph) * np.cos(v),
        ]
    )
    np.testing.assert_allclose(wc.roller_positions(p, theta)[0], eq8, atol=1e-12)
    tp = theta - (-theta)
    eq11 = r * np.array(
        [
            np.sin(ph) * np.cos(v),
            np.sin(v) * np.cos(tp) + np.cos(ph) * np.cos(v) * np.sin(tp),
            np.cos(ph) * np.cos(v) * np.cos(tp) - np.sin(v) * np.sin(tp),
        ]
    )
    np.testing.assert_allclose(wc.groove_points(p, theta)[0], eq11, atol=1e-12)


def test_eq18_slider_angles_sum_to_pi():
    """Eq. 18: alpha'_1 + alpha'_2 = pi (the text's "90 deg - alpha'_1" is a misprint).

    alpha'_1: rail of rotor 1 to rail of rotor 2; alpha'_2: rail of rotor 2 to the
    other rail of rotor 1, measured from the 4 roller projections (exact, 1e-12)."""
    rng = np.random.default_rng(5)
    for _ in range(5):
        alpha = rng.uniform(50 * D, 130 * D)
        p = wc.WobbleCam(rng.uniform(0.1, float(wc.max_plate_tilt(alpha)) - 0.01), alpha)
        theta = rng.uniform(0, 2 * np.pi, 40)
        r = wc.roller_positions(p, theta)
        ang = np.arctan2(r[:, 1], r[:, 2])  # rollers: 1 (c=-a/2), 1' (pi-a/2), 2 (a/2), 2' (pi+a/2)
        a1 = np.mod(ang[2] - ang[0], 2 * np.pi)
        a2 = np.mod(ang[1] - ang[2], 2 * np.pi)
        np.testing.assert_allclose(a1 + a2, np.pi, atol=1e-12)


def test_groove_runs_twice_per_turn():
    """Section 4.2.2: the roller reaches 4 extreme positions per turn, the groove has 2, so the
    roller runs its groove twice per shaft turn (exact counts; extremes of x along the shaft)."""
    p = table1()
    theta = np.linspace(0, 2 * np.pi, 8000, endpoint=False)
    x = wc.roller_positions(p, theta)[0, 0]
    n_ext = np.sum((x > np.roll(x, 1)) & (x > np.roll(x, -1))) + np.sum(
        (x < np.roll(x, 1)) & (x < np.roll(x, -1))
    )
    assert n_ext == 4
    half = theta[theta < np.pi]
    g = wc.groove_points(p, half)[0, 0]
    n_groove = np.sum((g > np.roll(g, 1)) & (g > np.roll(g, -1))) + np.sum(
        (g < np.roll(g, 1)) & (g < np.roll(g, -1))
    )
    assert n_groove == 2
    np.testing.assert_allclose(
        wc.groove_points(p, half + np.pi), wc.groove_points(p, half), atol=1e-12
    )


def test_rotors_turn_with_the_cam_on_average():
    """Section 1.2 / note: with varphi = -2 theta both rotors turn on average at -1 times the
    shaft speed, like the cam (psi = -theta) (exact, 1e-12)."""
    p = table1()
    q0 = wc.rotor_angles(p, np.array([0.0, 2 * np.pi]))[0]
    np.testing.assert_allclose(q0[:, 1] - q0[:, 0], -2 * np.pi, atol=1e-12)
    assert float(wc.cam_angle(2 * np.pi)) == pytest.approx(-2 * np.pi)


# --------------------------------------------------------------------------------------------
# trend statements of Fig. 11-13 and the conclusions
# --------------------------------------------------------------------------------------------
def test_fig11_swing_largest_at_90deg():
    """Fig. 11 / conclusion 3: at fixed phi, the swing first rises then falls with alpha and is
    largest at alpha = pi/2 (sweep 1..179 deg, 0.01 deg step)."""
    alpha = np.arange(1.0, 179.0, 0.01) * D
    for phi in (20 * D, 45 * D, 60 * D):
        amax, amin = wc.slider_angle_extremes(phi, alpha)
        swing = amax - amin
        k = np.argmax(swing)
        assert deg(alpha[k]) == pytest.approx(90.0, abs=0.011)
        assert np.all(np.diff(swing[: k + 1]) > 0) and np.all(np.diff(swing[k:]) < 0)


def test_fig11_groups_a_and_b_same_amplitude_but_not_coincident():
    """Fig. 11: alpha and pi - alpha give the same amplitude, period and trend but
    different curves (except at the extremes); the two neighbouring chambers follow
    different laws unless alpha = pi/2, the more so the farther from pi/2."""
    phi = 35 * D  # admissible (eq. 20) for all alpha of the sweep
    v = np.linspace(0, np.pi, 721)
    spread = []
    for a_deg in (60.0, 70.0, 80.0, 90.0):
        a = a_deg * D
        s1, s2 = wc.slider_angle(phi, a, v), wc.slider_angle(phi, np.pi - a, v)
        assert s1.max() - s1.min() == pytest.approx(s2.max() - s2.min(), abs=1e-12)
        p = wc.WobbleCam(phi, a)
        lay = wc.piston_layout(p, 10.0)
        spread.append(abs(lay.chamber_b_min - lay.chamber_a_min))
        if a_deg != 90.0:
            assert np.max(np.abs(s1 - s2)) > 1e-2
            assert abs(lay.compression_ratio_a - lay.compression_ratio_b) > 0.5
        else:
            np.testing.assert_allclose(s1, s2, atol=1e-12)
            assert spread[-1] == pytest.approx(0.0, abs=1e-12)
    assert np.all(np.diff(spread) < 0)  # differences grow as alpha leaves 90 deg


def test_fig12_extremes_rise_with_alpha():
    """Fig. 12 / conclusion 3: alpha'_max and alpha'_min both rise with alpha (sweep)."""
    alpha = np.linspace(1 * D, 179 * D, 5000)
    for phi in (20 * D, 45 * D, 60 * D):
        amax, amin = wc.slider_angle_extremes(phi, alpha)
        assert np.all(np.diff(amax) > 0) and np.all(np.diff(amin) > 0)
        assert np.all(amax > amin)


def test_fig13_extremes_spread_faster_and_faster_with_phi():
    """Fig. 13: with growing phi, alpha'_max rises and alpha'_min falls, faster and faster
    (alpha'_max convex, alpha'_min concave), so the swing grows; sweep 0.1..65.5 deg."""
    phi = np.linspace(0.1 * D, 65.5 * D, 4000)
    for a in (60 * D, 90 * D, 120 * D):
        amax, amin = wc.slider_angle_extremes(phi, a)
        assert np.all(np.diff(amax) > 0) and np.all(np.diff(amin) < 0)
        assert np.all(np.diff(amax, 2) > 0) and np.all(np.diff(amin, 2) < 0)
        assert np.all(np.diff(amax - amin) > 0)


# --------------------------------------------------------------------------------------------
# the engine statements of section 1.2 through the four-stroke assignment of the machine
# --------------------------------------------------------------------------------------------
def test_sixteen_power_strokes_and_two_chambers_firing_through_the_machine():
    """Section 1.2: "each output-shaft turn ... 16 power strokes"; "at every instant 2 working
    chambers are in the power stroke". Counted on the machine's four-stroke assignment over one
    turn (exact integers), sampled inside every stroke interval (0.1 deg steps)."""
    p, m = table1(), tr.TwinRotor()
    theta = np.arange(0.05, 360.0, 0.1) * D
    s = eng.strokes(p, m, theta)
    assert s.shape == (8, theta.size)
    assert np.all(np.sum(s == POWER, axis=0) == 2)
    starts = np.sum((s == POWER) & (np.roll(s, 1, axis=1) != POWER))
    assert starts == 16
    summary = study.evaluate(table1_cfg()).summary
    assert summary["chambers_in_power_stroke"] == 2
    assert summary["intake_strokes_per_rev"] == 16


def test_table1_compression_ratio_is_the_geometric_one_without_clearance():
    """Table 1: eps = 10 with the paper's pure annular-sector chamber (no clearance volume):
    V_max/V_min = 10 for both chamber kinds (exact up to rounding, 1e-12)."""
    s = study.evaluate(table1_cfg()).summary
    assert s["compression_ratio_geometric"] == pytest.approx(10.0, rel=1e-12)
    assert s["compression_ratio_geometric_b"] == pytest.approx(10.0, rel=1e-12)
    assert s["chamber_volume_max_cm3"] / s["chamber_volume_min_cm3"] == pytest.approx(10.0)
