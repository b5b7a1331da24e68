"""Any vane machine on any rotary drive (rotorkin.vane): energy balance, the papers' pairings,
compatibility refusals, the turning points and stroke counter against independent models."""

from __future__ import annotations

import copy

import numpy as np
import pytest

from rotorkin import drives
from rotorkin.core.errors import ConfigError, ParameterError
from rotorkin.core.motion import Motion
from rotorkin.io.config import load_config, validate_config
from rotorkin.vane import RotaryLaw
from rotorkin.vane import law as vl

#: A config of each rotary drive (its own keys only).
DRIVES = {
    "wobble_cam": {"type": "wobble_cam", "plate_tilt": "45 deg", "roller_axis_angle": "90 deg",
                   "spin_ratio": -2},
    "guide_bar": {"type": "guide_bar", "lambda": 0.5, "gear_ratio": 2, "input_gear_ratio": 0.5,
                  "phase": "180 deg"},
    "rhomboid_cam": {"type": "rhomboid_cam", "link_length": "120 mm", "psi_min": "40 deg"},
    "noncircular_gears": {"type": "noncircular_gears", "lobes": 2, "rotor_lobes": 2,
                          "eccentricity": 0.15},
    # q1 = theta, q2 = theta + 90 deg + 0.3 rad sin(2 theta): two swings per turn
    "tabulated": {"type": "tabulated", "period": "180 deg", "mean_ratio": [1, 1],
                  "offset": ["0 deg", "90 deg"], "b2": [0.3]},
}  # fmt: skip
#: A machine section of each vane machine that fits all three drives.
MACHINES = {
    "twin_rotor": {"type": "twin_rotor", "pistons_per_rotor": 2, "compression_ratio": 8},
    "vane_pump": {"type": "vane_pump", "vanes_per_impeller": 2},
    "rotary_blade": {"type": "rotary_blade", "blades_per_pair": 2, "blade_thickness": "10 deg"},
}
#: The pump's flow keys (rotorkin.machines.vane_pump.flow_keys) that both paths report.
PUMP_FLOW_KEYS = ("flow_max_l_per_min", "flow_min_l_per_min", "hydraulic_power_W",
                  "leakage_l_per_min", "leakage_tip_l_per_min", "leakage_side_l_per_min",
                  "leakage_hub_l_per_min", "compression_loss_l_per_min", "land_loss_l_per_min",
                  "flow_delivered_mean_l_per_min", "flow_delivered_max_l_per_min",
                  "flow_delivered_min_l_per_min", "flow_delivered_ripple",
                  "volumetric_efficiency", "hydraulic_power_delivered_W", "port_land_deg",
                  "trapped_pressure_peak_bar", "trapped_pressure_min_bar")  # fmt: skip
#: Each drive's own machine: evaluated by the drive's study, not by rotorkin.vane.
OWN = {"wobble_cam": "twin_rotor", "guide_bar": "vane_pump", "rhomboid_cam": "rotary_blade"}


def _cfg(drive: str, machine: str, **run) -> dict:
    raw = {"drive": dict(DRIVES[drive]), "machine": dict(MACHINES[machine]),
           "run": {"points": 361, **run}}  # fmt: skip
    if machine == "rotary_blade" and drive == "rhomboid_cam":
        raw["loads"] = {"pressure_model": "isothermal"}
    return validate_config(raw)


@pytest.mark.parametrize("machine", list(MACHINES))
@pytest.mark.parametrize("drive", list(DRIVES))
def test_every_machine_runs_on_every_rotary_drive_with_the_energy_balance(drive, machine):
    cfg = _cfg(drive, machine)
    result = drives.evaluate(cfg)
    s = result.summary
    # mean torque x 2 pi = work per turn: the closed-form work against the integrated torque
    work = s["indicated_work_J"]
    angle = np.radians(next(iter(result.columns.values())))  # the shaft angle, first column
    integrated = float(np.trapezoid(result.columns["shaft_torque_Nm"], angle))
    span = angle[-1] - angle[0]
    assert integrated / span * 2 * np.pi == pytest.approx(work, rel=2e-3, abs=1e-6)
    assert s["mean_torque_Nm"] * 2 * np.pi == pytest.approx(work, rel=1e-12)
    assert s["displacement_cm3_per_rev"] > 0
    assert np.isfinite(s["flywheel_inertia_kgm2"]) and s["flywheel_inertia_kgm2"] >= 0
    assert all(np.all(np.isfinite(v)) for v in result.columns.values())
    if machine == "vane_pump":
        assert work < 0  # the shaft drives a pump
    else:
        assert work > 0  # an engine drives the shaft


def _law_of(cfg):
    return drives.get(cfg["drive"]["type"]).law(cfg)


@pytest.mark.parametrize(
    ("example", "sets", "keys"),
    [
        ("wobble-cam-engine", [], ("displacement_cm3_per_rev", "compression_ratio_geometric",
                                   "indicated_work_J", "mean_torque_Nm", "flywheel_inertia_kgm2",
                                   "peak_pressure_bar", "piston_width_deg", "torque_ripple",
                                   "indicated_power_kW")),
        ("guide-bar-pump", [], ("displacement_cm3_per_rev", "vane_angle_deg", "indicated_work_J",
                                "mean_torque_Nm", "flywheel_inertia_kgm2", "flow_mean_l_per_min",
                                "flow_ripple", "torque_ripple", *PUMP_FLOW_KEYS)),
        # a land needs a dead volume (vanes narrower than gamma_0); its ends off the 1 deg grid of
        # the columns (a sample on an end is open or closed by the rounding of the turning points)
        ("guide-bar-pump", ["machine.vane_angle=60 deg", "machine.port_land=10.3 deg",
                            "machine.tip_clearance=0.02 mm", "machine.side_clearance=0.01 mm",
                            "machine.hub_clearance=0.005 mm", "run.speed=900 rpm"],
         ("displacement_cm3_per_rev", "indicated_work_J", "flow_mean_l_per_min", "flow_ripple",
          "torque_ripple", *PUMP_FLOW_KEYS)),
        ("rhomboid-engine", ["loads.pressure_model=isothermal"],
         ("displacement_cm3_per_rev", "compression_ratio_geometric", "indicated_work_J",
          "mean_torque_Nm", "pressure_max_bar")),
        ("rhomboid-engine", ["loads.pressure_model=adiabatic"],
         ("displacement_cm3_per_rev", "compression_ratio_geometric", "indicated_work_J",
          "mean_torque_Nm", "heat_in_J_per_rev", "indicated_efficiency", "peak_pressure_bar")),
    ],
)  # fmt: skip
def test_the_papers_pairings_through_the_generic_layer_equal_the_drives_own_studies(
    example, sets, keys
):
    """The drive's own study and rotorkin.vane compute the same machine: same numbers."""
    from rotorkin.vane import evaluate

    cfg, _, _ = load_config(example=example, sets=sets)
    own = drives.evaluate(cfg)
    generic = evaluate(cfg, _law_of(cfg), drive_type=cfg["drive"]["type"], title="generic")
    for key in keys:
        assert generic.summary[key] == pytest.approx(own.summary[key], rel=1e-9), key
    # the flywheel is integrated on another grid by the rhomboid study: 1e-6
    assert generic.summary["flywheel_inertia_kgm2"] == pytest.approx(
        own.summary["flywheel_inertia_kgm2"], rel=1e-6
    )
    assert generic.summary["vane_mounting_deg"] == pytest.approx(0.0, abs=1e-9)
    if "port_land_deg" in keys:  # the pump's curves over the same angles: the same samples
        cols = ("flow_l_per_min", "leakage_l_per_min", "flow_delivered_l_per_min",
                "chamber_a_pressure_bar", "chamber_b_pressure_bar", "shaft_torque_Nm")  # fmt: skip
        for col in cols:
            scale = np.max(np.abs(own.columns[col])) or 1.0
            np.testing.assert_allclose(generic.columns[col], own.columns[col], rtol=1e-9,
                                       atol=1e-12 * scale, err_msg=col)  # fmt: skip


def test_own_machine_named_explicitly_is_the_drives_own_study():
    cfg, raw, _ = load_config(example="wobble-cam-engine")
    raw = copy.deepcopy(raw)
    raw["machine"]["type"] = "twin_rotor"
    again = drives.evaluate(validate_config(raw))
    assert again.summary == drives.evaluate(cfg).summary


@pytest.mark.parametrize(
    ("drive", "machine", "sets", "name"),
    [
        ("rhomboid_cam", "twin_rotor", {"pistons_per_rotor": 4}, "machine.pistons_per_rotor"),
        ("wobble_cam", "twin_rotor", {"compression_ratio": 1.2}, "machine.compression_ratio"),
        ("wobble_cam", "vane_pump", {"vanes_per_impeller": 10}, "machine.vanes_per_impeller"),
        ("wobble_cam", "vane_pump", {"vane_angle": "80 deg"}, "machine.vane_angle"),
        ("rhomboid_cam", "rotary_blade", {"blade_thickness": "45 deg"},
         "machine.blade_thickness"),
        ("guide_bar", "twin_rotor", {}, "machine.type"),
    ],
)  # fmt: skip
def test_what_cannot_fit_is_refused_in_one_line_naming_the_key(drive, machine, sets, name):
    raw = {"drive": dict(DRIVES[drive]), "machine": {**MACHINES[machine], **sets}}
    if drive == "guide_bar" and name == "machine.type":
        raw["drive"]["input_gear_ratio"] = 2  # one swing per two turns: no four-stroke cycle
    if drive == "rhomboid_cam" and machine == "rotary_blade":
        raw["loads"] = {"pressure_model": "isothermal"}
    with pytest.raises(ParameterError) as err:
        drives.evaluate(validate_config(raw))
    assert err.value.name == name
    assert "\n" not in str(err.value)


def test_a_drive_that_carries_one_machine_only_refuses_another():
    raw = {"drive": {"type": "eccentric_cam"}, "machine": {"type": "twin_rotor"}}
    with pytest.raises(ConfigError, match="carries machine.type = 'opposed_piston' only"):
        validate_config(raw)


def test_keys_of_another_machine_are_refused():
    raw = {"drive": dict(DRIVES["wobble_cam"]), "machine": {"type": "vane_pump",
                                                            "compression_ratio": 8}}  # fmt: skip
    with pytest.raises(ConfigError, match="unknown key machine.compression_ratio"):
        validate_config(raw)


# --- the law: turning points and stroke counter against independent models ---------------------
def _sine_law(k: int, amp: float, phase: float = 0.3):
    """q1 = theta, q2 = theta + pi/2 + amp sin(k theta + phase): turning points in closed form."""

    def motion(theta):
        t = np.asarray(theta, dtype=float)
        s, c = np.sin(k * t + phase), np.cos(k * t + phase)
        z, one = np.zeros_like(t), np.ones_like(t)
        q = np.stack([t, t + np.pi / 2 + amp * s])
        return Motion(t, q, np.stack([one, one + amp * k * c]), np.stack([z, -amp * k * k * s]),
                      np.stack([z, -amp * k**3 * c]))  # fmt: skip

    return RotaryLaw(motion, 2 * np.pi / k)


@pytest.mark.parametrize("k", [1, 2, 3, 5])
def test_turning_points_are_the_roots_of_the_relative_speed(k):
    law = _sine_law(k, 0.2)
    pts = vl.turning_points(law)
    # r' = amp k cos(k t + phase) = 0 at k t + phase = pi/2 + m pi
    exact = np.sort(np.mod((np.pi / 2 + np.arange(-2, 4) * np.pi - 0.3) / k, 2 * np.pi / k))
    exact = np.unique(np.round(exact, 14))
    assert pts.size == 2
    assert pts == pytest.approx(exact[:2] if exact.size >= 2 else exact, abs=1e-12)
    lo, hi = vl.relative_extremes(law)
    assert (lo, hi) == pytest.approx((np.pi / 2 - 0.2, np.pi / 2 + 0.2), abs=1e-14)
    assert vl.strokes_per_turn(law) == pytest.approx(2 * k)


def test_stroke_counter_is_one_at_the_largest_relative_angle_and_counts_turning_points():
    law = _sine_law(2, 0.2, phase=0.0)  # r largest at theta = pi/4
    pts = vl.turning_points(law)
    c = vl.stroke_counter(law, pts)
    assert c[0] == 1.0 and np.all(np.diff(c) == 1.0)
    theta = np.linspace(0, 4 * np.pi, 2001)
    c = vl.stroke_counter(law, theta)
    assert np.all(np.diff(c) > 0)
    assert c[-1] - c[0] == pytest.approx(2 * 2 * 2)  # 4 turning points per turn, 2 turns


def test_a_law_without_relative_motion_is_refused():
    def motion(theta):
        t = np.asarray(theta, dtype=float)
        z, one = np.zeros_like(t), np.ones_like(t)
        return Motion(t, np.stack([t, t + 1.0]), np.stack([one, one]), np.stack([z, z]),
                      np.stack([z, z]))  # fmt: skip

    from rotorkin.vane import machines

    cfg = validate_config({"drive": dict(DRIVES["wobble_cam"]), "machine": MACHINES["vane_pump"]})
    with pytest.raises(ParameterError, match="swings its two members"):
        machines.setup("vane_pump", cfg, RotaryLaw(motion, 2 * np.pi))


def test_periods_must_divide_a_turn_or_be_whole_turns():
    law = _sine_law(1, 0.1)
    RotaryLaw(law.motion, 4 * np.pi)
    with pytest.raises(ValueError):
        RotaryLaw(law.motion, 2.0)


@pytest.mark.parametrize("drive", ["noncircular_gears", "tabulated", "wobble_cam"])
def test_drive_torques_on_the_members_balance_the_shaft_at_constant_speed(drive):
    """At a constant speed the torques the drive puts on the members, times their speed
    ratios, are the shaft's net torque with the sign turned: power through the drive."""
    from rotorkin.vane import evaluate

    cfg = _cfg(drive, "twin_rotor" if drive != "wobble_cam" else "vane_pump")
    r = evaluate(cfg, _law_of(cfg), drive_type=drive, title="t")
    c = r.columns
    through = c["member1_drive_torque_Nm"] * c["member1_speed_ratio"] + (
        c["member2_drive_torque_Nm"] * c["member2_speed_ratio"]
    )
    scale = np.max(np.abs(c["shaft_torque_with_inertia_Nm"]))
    assert -through == pytest.approx(c["shaft_torque_with_inertia_Nm"], abs=1e-9 * scale)
    assert r.summary["drive_torque_peak_Nm"] == pytest.approx(
        np.max(np.abs([c["member1_drive_torque_Nm"], c["member2_drive_torque_Nm"]])), rel=1e-3
    )


@pytest.mark.parametrize(
    ("drive", "machine"),
    [("wobble_cam", "vane_pump"), ("guide_bar", "rotary_blade"), ("rhomboid_cam", "twin_rotor"),
     ("noncircular_gears", "vane_pump")],
)  # fmt: skip
def test_a_machine_on_another_drive_loads_the_drives_pairs(drive, machine):
    cfg = _cfg(drive, machine)
    s = drives.evaluate(cfg).summary
    for key in ("peak_contact_force_N", "peak_bearing_load_N", "friction_loss_W",
                "mechanical_efficiency"):  # fmt: skip
        assert key in s and np.isfinite(s[key]) and s[key] >= 0, key
    assert 0.0 < s["mechanical_efficiency"] < 1.0
    off = {f"friction_{k}": 0.0 for k in ("rolling", "sliding", "mesh", "bearing")}
    idle = {**cfg, "contact": {**cfg["contact"], **off}}
    assert drives.evaluate(idle).summary["mechanical_efficiency"] == pytest.approx(1.0)
