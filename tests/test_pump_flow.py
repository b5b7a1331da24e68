"""Flow of the differential vane pump on any drive: leakage, sealing land, trapped pressure,
delivered flow and its ripple, volumetric efficiency (rotorkin.machines.vane_pump, the vane path
rotorkin.vane and the guide-bar study).

Independent models: the plane Poiseuille gap flow written out by hand, a numeric integration
of the closed chamber's continuity equation dp/dtheta = -(K/V) dV/dtheta (scipy solve_ivp), the
volumes of the chambers from the relative angle written out here, and a law of constant
relative speed whose delivered flow is a square wave with a closed-form ripple.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rotorkin import drives
from rotorkin.cli import main
from rotorkin.core.errors import ParameterError
from rotorkin.core.motion import Motion
from rotorkin.io.config import load_config, validate_config
from rotorkin.machines import pump_flow as pf
from rotorkin.machines import vane_pump as vp
from rotorkin.vane import RotaryLaw

PS, PD, K, MU = 1.0e5, 6.0e5, 1.5e9, 0.03
RH, RC, W = 0.030, 0.080, 0.040
KV = 0.5 * (RC**2 - RH**2) * W  # chamber volume per radian [m^3/rad]

#: q1 = theta, q2 = theta + 90 deg + 0.3 rad sin(2 theta): two swings per turn (tabulated drive)
TABULATED = {"type": "tabulated", "period": "180 deg", "mean_ratio": [1, 1],
             "offset": ["0 deg", "90 deg"], "b2": [0.3]}  # fmt: skip
WOBBLE = {"type": "wobble_cam", "plate_tilt": "45 deg", "roller_axis_angle": "90 deg",
          "spin_ratio": -2}  # fmt: skip


def _vane(drive: dict, points: int = 361, loads: dict | None = None, **machine):
    """A vane pump (Z = 2) on ``drive`` through the vane path."""
    raw = {"drive": dict(drive), "machine": {"type": "vane_pump", "vanes_per_impeller": 2,
                                             **machine}, "run": {"points": points}}  # fmt: skip
    if loads:
        raw["loads"] = loads
    return drives.evaluate(validate_config(raw))


# --- a sine law and a law of constant relative speed, as the machine sees them ---------------
def _sine_motion(amp=0.3, k=2, phase=0.3):
    def motion(theta):
        t = np.asarray(theta, dtype=float)
        s, c = np.sin(k * t + phase), np.cos(k * t + phase)
        z, one = np.zeros_like(t), np.ones_like(t)
        return Motion(t, np.stack([t, t + np.pi / 2 + amp * s]), np.stack([one, one + amp * k * c]),
                      np.stack([z, -amp * k * k * s]), np.stack([z, -amp * k**3 * c]))  # fmt: skip

    # r' = amp k cos(k t + phase) = 0 at k t + phase = pi/2, 3 pi/2
    turning = np.sort(np.mod((np.array([0.5, 1.5]) * np.pi - phase) / k, 2 * np.pi / k))
    return motion, turning, 2 * np.pi / k


def _triangle_motion(slope=0.2):
    """r = pi/2 + slope tri(theta): |r'| = slope everywhere but at the turning points."""

    def motion(theta):
        t = np.asarray(theta, dtype=float)
        u = np.mod(t + np.pi / 2, 2 * np.pi) - np.pi / 2  # [-pi/2, 3pi/2)
        tri = np.pi / 2 - np.abs(u - np.pi / 2)
        dtri = np.where(u < np.pi / 2, 1.0, -1.0)
        z, one = np.zeros_like(t), np.ones_like(t)
        return Motion(t, np.stack([t, t + np.pi / 2 + slope * tri]),
                      np.stack([one, one + slope * dtri]), np.stack([z, z]),
                      np.stack([z, z]))  # fmt: skip

    return motion, np.array([0.5 * np.pi, 1.5 * np.pi]), 2 * np.pi


def _pump(lo, hi, gamma):
    return vp.VanePump(lo, hi, gamma, 2, RH, RC, W)


# --- ideal limit ------------------------------------------------------------------------------
def test_zero_clearances_and_no_land_give_the_ideal_flow_exactly():
    motion, turning, period = _sine_motion()
    pump = _pump(np.pi / 2 - 0.3, np.pi / 2 + 0.3, 0.5)
    ports = vp.PortPressures(PS, PD)
    gaps = pf.Gaps()
    windows = pf.land_windows(pump, ports, gaps, motion, turning, period, 0.0)
    theta = np.linspace(0.0, 2 * np.pi, 4001)
    m = motion(theta)
    volume, dvolume = vp.chamber_volumes(pump, m)
    omega = 157.0
    closed = pf.closed_windows(theta, turning, period, 0.0)[0]
    assert not closed.any()
    ideal = vp.flow_rate(pump, m, omega)
    leak = pf.leakage_flow(pump, gaps, ports)["total"]
    assert leak == 0.0
    assert np.array_equal(pf.delivered_flow(dvolume, closed, omega, leak), ideal)
    assert np.array_equal(pf.port_pressures(ports, windows, volume, dvolume, theta),
                          vp.chamber_pressures(ports, dvolume))  # fmt: skip
    # nothing trapped: the extremes are the ports', no volume lost to a land
    assert (windows.pressure_peak, windows.pressure_min) == (PD, PS)
    assert windows.lost_volume == 0.0
    # the compression loss is today's closed form (2 Z V_max dp / K), to rounding
    assert windows.compression_volume == pytest.approx(
        pf.compression_loss(pump, gaps, ports), rel=1e-12
    )


@pytest.mark.parametrize("drive", [TABULATED, WOBBLE])
def test_the_vane_path_delivers_the_ideal_flow_with_default_clearances(drive):
    r = _vane(drive)
    c, s = r.columns, r.summary
    assert np.array_equal(c["flow_delivered_l_per_min"], c["flow_l_per_min"])
    assert not np.any(c["leakage_l_per_min"])
    assert s["leakage_l_per_min"] == 0.0 and s["land_loss_l_per_min"] == 0.0
    assert s["port_land_deg"] == 0.0
    assert (s["trapped_pressure_peak_bar"], s["trapped_pressure_min_bar"]) == (6.0, 1.0)
    expected = s["flow_mean_l_per_min"] - s["compression_loss_l_per_min"]
    assert s["flow_delivered_mean_l_per_min"] == pytest.approx(expected, rel=1e-12)
    assert s["volumetric_efficiency"] == pytest.approx(expected / s["flow_mean_l_per_min"],
                                                       rel=1e-12)  # fmt: skip
    assert s["flow_delivered_ripple"] == pytest.approx(s["flow_ripple"], rel=1e-12)
    assert s["hydraulic_power_W"] == pytest.approx(5e5 * s["flow_mean_l_per_min"] / 6e4,
                                                   rel=1e-12)  # fmt: skip


# --- leakage ------------------------------------------------------------------------------------
def test_leakage_on_any_drive_against_the_plane_gap_flow_by_hand():
    h_t, h_s, h_h = 20e-6, 10e-6, 5e-6
    r = _vane(TABULATED, tip_clearance=f"{h_t * 1e3} mm", side_clearance=f"{h_s * 1e3} mm",
              hub_clearance=f"{h_h * 1e3} mm")  # fmt: skip
    s, c = r.summary, r.columns
    g = math.radians(s["vane_angle_deg"])
    dp = PD - PS
    # Q = b h^3 dp / (12 mu L) per vane, 2 Z = 4 vanes; the side face a sector: L = gamma rho
    tip = W * h_t**3 * dp / (12 * MU * g * RC)
    hub = W * h_h**3 * dp / (12 * MU * g * RH)
    side = 2 * h_s**3 * dp * math.log(RC / RH) / (12 * MU * g)
    to_l_min = 6e4
    assert s["leakage_tip_l_per_min"] == pytest.approx(4 * tip * to_l_min, rel=1e-12)
    assert s["leakage_hub_l_per_min"] == pytest.approx(4 * hub * to_l_min, rel=1e-12)
    assert s["leakage_side_l_per_min"] == pytest.approx(4 * side * to_l_min, rel=1e-12)
    total = 4 * (tip + hub + side) * to_l_min
    assert s["leakage_l_per_min"] == pytest.approx(total, rel=1e-12)
    assert c["flow_delivered_l_per_min"] == pytest.approx(c["flow_l_per_min"] - total, rel=1e-12)
    expected = s["flow_mean_l_per_min"] - total - s["compression_loss_l_per_min"]
    assert s["flow_delivered_mean_l_per_min"] == pytest.approx(expected, rel=1e-12)


def test_volumetric_efficiency_falls_as_the_cube_of_the_clearance_and_with_the_viscosity():
    base = _vane(WOBBLE, points=73).summary["volumetric_efficiency"]
    loss = []
    for h in ("0.01 mm", "0.02 mm", "0.04 mm"):
        s = _vane(WOBBLE, points=73, tip_clearance=h, side_clearance=h, hub_clearance=h).summary
        loss.append(base - s["volumetric_efficiency"])
    assert loss[0] > 0
    assert loss[1] / loss[0] == pytest.approx(8.0, rel=1e-9)  # h^3
    assert loss[2] / loss[1] == pytest.approx(8.0, rel=1e-9)
    etas = []
    for mu in (0.1, 0.03, 0.01):  # thinner oil: more leakage, in proportion to 1/mu
        s = _vane(WOBBLE, points=73, tip_clearance="0.02 mm",
                  loads={"fluid_viscosity": mu}).summary  # fmt: skip
        etas.append(s["volumetric_efficiency"])
    assert etas[0] > etas[1] > etas[2]
    assert (base - etas[2]) / (base - etas[0]) == pytest.approx(10.0, rel=1e-9)


# --- trapped pressure ---------------------------------------------------------------------------
def _chamber_a_volume(theta, lo, hi, gamma, motion):
    """V_A = k (r - r_mid + pi/Z - gamma), written out from the relative angle (Z = 2)."""
    q = motion(theta).q
    return KV * ((q[1] - q[0]) - 0.5 * (lo + hi) + np.pi / 2 - gamma)


def _chamber_a_dvolume(theta, motion):
    dq = motion(theta).dq
    return KV * (dq[1] - dq[0])


@pytest.mark.parametrize("land_deg", [4.0, 20.0, 60.0])
def test_trapped_pressure_against_a_numeric_integration_of_the_continuity_equation(land_deg):
    amp = 0.3
    motion, turning, period = _sine_motion(amp)
    lo, hi, gamma = np.pi / 2 - amp, np.pi / 2 + amp, 1.2  # a dead volume: phi_min = 0.0708 rad
    pump = _pump(lo, hi, gamma)
    ports, gaps = vp.PortPressures(PS, PD), pf.Gaps(bulk_modulus=K)
    land = math.radians(land_deg)
    windows = pf.land_windows(pump, ports, gaps, motion, turning, period, land)

    def rhs(t, p):  # dp/dtheta = -(K/V) dV/dtheta, chamber A closed
        return -K / _chamber_a_volume(t, lo, hi, gamma, motion) * _chamber_a_dvolume(t, motion)

    for i, t_turn in enumerate(turning):
        a, b = t_turn - land / 2, t_turn + land / 2
        # chamber A at its smallest volume: closed full of discharge fluid, else suction fluid
        small = _chamber_a_dvolume(a, motion) < 0
        p0 = PD if small else PS
        assert windows.is_min[i, 0] == small
        grid = np.linspace(a, b, 41)[1:-1]  # inside the window (open at its ends)
        sol = solve_ivp(rhs, (a, b), [p0], dense_output=True, rtol=1e-12, atol=1e-6,
                        method="DOP853")  # fmt: skip
        numeric = sol.sol(np.concatenate([grid, [t_turn, b]]))[0]
        fine = sol.sol(np.linspace(a, b, 2001))[0]
        m = motion(grid)
        volume, dvolume = vp.chamber_volumes(pump, m)
        p = pf.port_pressures(ports, windows, volume, dvolume, grid)
        scale = abs(numeric - p0).max()
        assert p[0] == pytest.approx(numeric[:-2], abs=1e-9 * scale + 1e-6)
        assert windows.pressure_turn[i, 0] == pytest.approx(numeric[-2], abs=1e-9 * scale + 1e-6)
        assert windows.pressure_open[i, 0] == pytest.approx(numeric[-1], abs=1e-9 * scale + 1e-6)
        # the chamber's extreme is at the turning point: above p_d when closed full of discharge
        if small:
            assert numeric[-2] >= np.max(fine) - 1e-9 * scale
            assert numeric[-2] > PD
        else:
            assert numeric[-2] <= np.min(fine) + 1e-9 * scale
            assert numeric[-2] < PS
    every = np.stack([windows.pressure_close, windows.pressure_turn, windows.pressure_open])
    assert windows.pressure_peak == np.max(every) and windows.pressure_min == np.min(every)
    # the compression loss: the chambers opening to the outlet, V_o (p_d - p_o) / K by hand
    opening = ~windows.is_min
    by_hand = np.sum(windows.volume_open[opening] * (PD - windows.pressure_open[opening])) / K
    assert windows.compression_volume == pytest.approx(by_hand, rel=1e-12)


def test_trapped_pressure_broadcasts_at_0d_1d_3d():
    rng = np.random.default_rng(7)
    for shape in ((), (5,), (2, 3, 4)):
        v = rng.uniform(1e-6, 2e-6, shape)
        v0 = rng.uniform(1e-6, 2e-6, shape)
        p = pf.trapped_pressure(v, v0, PS, K)
        assert np.shape(p) == shape
        assert p == pytest.approx(PS - K * np.log(v / v0), rel=1e-14)


def test_land_on_the_vane_path_agrees_with_the_machine_and_warns_of_cavitation():
    r = _vane(TABULATED, vane_angle="60 deg", port_land="8 deg")
    s = r.summary
    assert s["port_land_deg"] == pytest.approx(8.0)
    assert s["trapped_pressure_peak_bar"] > 6.0
    assert s["trapped_pressure_min_bar"] < 1.0
    assert s["land_loss_l_per_min"] > 0
    pressure = np.stack([r.columns["chamber_a_pressure_bar"], r.columns["chamber_b_pressure_bar"]])
    # the sampled chamber pressures stay inside the closed-form extremes of the windows
    assert pressure.max() <= s["trapped_pressure_peak_bar"] * (1 + 1e-12)
    assert pressure.min() >= s["trapped_pressure_min_bar"] * (1 + 1e-12) - 1e-12
    # the chamber closed at 1 bar and expanded by the land falls below the 0.1 bar floor: warned
    assert s["trapped_pressure_min_bar"] < 0.1
    assert any("loads.vapour_pressure" in w for w in r.warnings)
    # the same chamber closed at 60 bar falls by the same K ln(V_max / V_c): not below the floor
    quiet = _vane(TABULATED, vane_angle="60 deg", port_land="8 deg",
                  loads={"suction_pressure": "60 bar", "discharge_pressure": "65 bar"})  # fmt: skip
    drop = 1.0 - s["trapped_pressure_min_bar"]
    assert quiet.summary["trapped_pressure_min_bar"] == pytest.approx(60.0 - drop, rel=1e-9)
    assert quiet.summary["trapped_pressure_min_bar"] > 0.1
    assert not any("vapour_pressure" in w for w in quiet.warnings)


# --- flow ripple of a law of constant relative speed ------------------------------------------
@pytest.mark.parametrize(("land_deg", "h_tip"), [(0.0, 0.0), (20.0, 0.0), (20.0, 40e-6)])
def test_ripple_of_a_constant_relative_speed_against_the_sampled_curve(land_deg, h_tip):
    slope = 0.2
    motion, turning, period = _triangle_motion(slope)
    lo, hi, gamma = np.pi / 2 - slope * np.pi / 2, np.pi / 2 + slope * np.pi / 2, 1.0
    pump = _pump(lo, hi, gamma)
    ports, gaps = vp.PortPressures(PS, PD), pf.Gaps(tip_clearance=h_tip, bulk_modulus=K)
    land = math.radians(land_deg)
    windows = pf.land_windows(pump, ports, gaps, motion, turning, period, land)
    omega = 100.0
    theta = np.linspace(0.0, 2 * np.pi, 36_001)  # 0.01 deg: the windows' ends are samples
    dvolume = vp.chamber_volumes(pump, motion(theta))[1]
    t_period = period / omega
    q = omega * 2 * KV * slope  # Z k |r'| omega: constant
    flow_mean = vp.displacement(pump) / t_period
    assert flow_mean == pytest.approx(q, rel=1e-12)
    flow = pf.pump_flow(pump, ports, gaps, windows, flow_mean, t_period, dvolume, theta,
                        np.full_like(theta, omega))  # fmt: skip
    leak = flow["leakage"]["total"]
    closed_share = 2 * land / period  # two windows per period
    mean = q * (1 - closed_share) - leak
    # closed form: a square wave between q - Q_L (open) and -Q_L (closed)
    assert flow["delivered_mean"] + flow["compression"] == pytest.approx(mean, rel=1e-12)
    assert flow["land_loss"] == pytest.approx(q * closed_share, rel=1e-12)
    ripple = (q if land > 0 else 0.0) / mean
    assert flow["delivered_ripple"] == pytest.approx(ripple, rel=1e-4, abs=1e-12)
    curve = flow["delivered"]
    assert curve.max() == pytest.approx(q - leak, rel=1e-12)
    assert curve.min() == pytest.approx(-leak if land > 0 else q - leak, rel=1e-12, abs=1e-20)
    # the sampled time mean of the curve: the trapezoid over the steps, to 1e-4
    assert np.trapezoid(curve, theta) / period == pytest.approx(mean, rel=1e-4)
    # the law is symmetric about its turning points: a chamber opens at the pressure it closed at
    # (to the rounding of V_o / V_c, 1e-16, times K)
    assert windows.pressure_open == pytest.approx(windows.pressure_close, abs=1e-14 * K)
    if land > 0:
        v_open = windows.volume_open[~windows.is_min]
        assert windows.compression_volume == pytest.approx(np.sum(v_open) * (PD - PS) / K,
                                                           rel=1e-12)  # fmt: skip


# --- the guide-bar study's own pump agrees ----------------------------------------------------
def test_guide_bar_study_with_a_land_uses_the_machines_flow():
    sets = ["run.points=145", "machine.vane_angle=60 deg", "machine.port_land=10 deg",
            "machine.tip_clearance=0.02 mm"]  # fmt: skip
    r = drives.evaluate(load_config(None, "guide-bar-pump", sets)[0])
    s, c = r.summary, r.columns
    expected = (s["flow_mean_l_per_min"] - s["land_loss_l_per_min"] - s["leakage_l_per_min"]
                - s["compression_loss_l_per_min"])  # fmt: skip
    assert s["flow_delivered_mean_l_per_min"] == pytest.approx(expected, rel=1e-12)
    assert s["trapped_pressure_peak_bar"] > 6.0 > 1.0 > s["trapped_pressure_min_bar"]
    # the delivered curve is zero (less the leakage) in the windows round the equal-speed points
    assert np.isclose(c["flow_delivered_l_per_min"], -s["leakage_l_per_min"]).sum() > 0
    assert np.all(c["flow_delivered_l_per_min"] <= c["flow_l_per_min"] - s["leakage_l_per_min"]
                  + 1e-9)  # fmt: skip


# --- bad input ------------------------------------------------------------------------------------
def test_bad_values_are_refused_naming_the_field():
    motion, turning, period = _sine_motion()
    pump = _pump(np.pi / 2 - 0.3, np.pi / 2 + 0.3, 0.5)
    ports, gaps = vp.PortPressures(PS, PD), pf.Gaps()
    stroke = period / 2
    for land in (-0.01, stroke, 10.0, float("nan")):
        with pytest.raises(ParameterError) as err:
            pf.land_windows(pump, ports, gaps, motion, turning, period, land)
        assert err.value.name == "port_land"
    closing = _pump(np.pi / 2 - 0.3, np.pi / 2 + 0.3, float(vp.vane_angle_max(2, 0.6)))
    with pytest.raises(ParameterError, match="close completely") as err:
        pf.land_windows(closing, ports, gaps, motion, turning, period, 0.01)
    assert err.value.name == "port_land"
    pf.land_windows(closing, ports, gaps, motion, turning, period, 0.0)  # no land: fine
    with pytest.raises(ParameterError, match="tip_clearance"):
        pf.Gaps(tip_clearance=-1e-6)
    with pytest.raises(ParameterError, match="vapour_pressure"):
        pf.Gaps(vapour_pressure=-1.0)


@pytest.mark.parametrize(
    ("drive", "machine", "key"),
    [
        (TABULATED, {"vane_angle": "60 deg", "port_land": "200 deg"}, "machine.port_land"),
        (TABULATED, {"port_land": "5 deg"}, "machine.port_land"),  # widest vanes: no dead volume
        (WOBBLE, {"port_land": "1 deg"}, "machine.port_land"),
    ],
)
def test_a_land_that_does_not_fit_the_drive_is_refused_naming_the_key(drive, machine, key):
    raw = {"drive": dict(drive), "machine": {"type": "vane_pump", **machine}}
    with pytest.raises(ParameterError) as err:
        drives.evaluate(validate_config(raw))
    assert err.value.name == key
    assert "\n" not in str(err.value)


@pytest.mark.parametrize(
    ("setting", "key"),
    [
        ("machine.port_land=-1 deg", "machine.port_land"),
        ("machine.port_land=400 deg", "machine.port_land"),
        ("machine.tip_clearance=-0.01 mm", "machine.tip_clearance"),
        ("loads.vapour_pressure=-1 bar", "loads.vapour_pressure"),
    ],
)
def test_out_of_range_is_refused_in_one_line(capsys, tmp_path, setting, key):
    out = tmp_path / "out"
    args = ["run", "-e", "guide-bar-pump", "--set", setting, "--set", "machine.vane_angle=60 deg",
            "--out", str(out), "-q"]  # fmt: skip
    assert main(args) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and err.startswith(f"rotorkin: error: {key} = ")
    assert not out.exists()


def test_the_law_is_a_rotary_law():
    """The test laws are laws the vane path accepts (the turning points found numerically)."""
    from rotorkin.vane.law import turning_points

    motion, turning, period = _sine_motion()
    assert turning_points(RotaryLaw(motion, period)) == pytest.approx(turning, abs=1e-12)
