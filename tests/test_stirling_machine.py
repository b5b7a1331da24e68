"""The rotary-blade engine as an alpha-type Stirling engine (hot blade set + lagging cold set).

Independent checks: the Schmidt pressure written out here from the two sets' volumes;
the cold set's volumes as the hot set's at theta - lag; the shaft torque as
sum p (dV_hot + dV_cold)/dtheta integrated over a turn against the cycle's work; Carnot;
linearity of the ideal gas in the charge; the drive's own study against rotorkin.vane.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin import drives
from rotorkin.core.errors import ConfigError, ParameterError
from rotorkin.io.config import load_config, validate_config
from rotorkin.vane import evaluate as evaluate_vane
from rotorkin.vane import machines as vm

WOBBLE = {"type": "wobble_cam", "plate_tilt": "45 deg", "roller_axis_angle": "90 deg",
          "spin_ratio": -2}  # fmt: skip
RHOMBOID = {"type": "rhomboid_cam", "link_length": "120 mm", "psi_min": "40 deg"}
BLADES = {"type": "rotary_blade", "blades_per_pair": 2, "blade_thickness": "10 deg"}


def _cfg(drive=WOBBLE, **loads):
    return validate_config({"drive": dict(drive), "machine": dict(BLADES), "loads": loads,
                            "run": {"points": 361}})  # fmt: skip


def _setup(cfg):
    law = drives.get(cfg["drive"]["type"]).law(cfg)
    return vm.setup("rotary_blade", cfg, law)


@pytest.mark.parametrize("model", ["adiabatic", "schmidt"])
def test_efficiency_work_and_torque(model):
    res = drives.evaluate(_cfg(pressure_model=model))
    s = res.summary
    carnot = 1 - 330 / 900
    assert s["carnot_efficiency"] == pytest.approx(carnot, rel=1e-15)
    if model == "schmidt":
        assert s["indicated_efficiency"] == pytest.approx(carnot, rel=1e-12)
    else:
        assert 0 < s["indicated_efficiency"] < carnot
    assert s["heat_in_J_per_rev"] - s["heat_out_J_per_rev"] == pytest.approx(
        s["indicated_work_J"], rel=1e-7
    )
    assert s["regenerator_heat_J_per_rev"] > s["heat_in_J_per_rev"]
    assert s["indicated_power_kW"] == pytest.approx(s["indicated_work_J"] * 50 * 1e-3, rel=1e-9)
    # the shaft torque of both sets integrated over a turn is the cycles' work
    theta = np.radians(res.columns["theta_deg"])
    integrated = np.trapezoid(res.columns["shaft_torque_Nm"], theta)
    assert integrated == pytest.approx(s["indicated_work_J"], rel=1e-4)
    assert s["mean_pressure_bar"] > 2.0 and s["peak_pressure_bar"] > s["mean_pressure_bar"]
    assert s["pressure_model"] == model and s["gas"] == "air" and s["circuits"] == 4


def test_both_sets_the_schmidt_pressure_and_the_shaft_torque():
    setup = _setup(_cfg(pressure_model="schmidt", phase_angle="75 deg", gas="helium",
                        heater_volume="20 cm^3"))  # fmt: skip
    sol = setup.extra["stirling"]
    theta = np.linspace(0.0, 2 * np.pi, 1001)
    st = vm.state(setup, theta)
    c = setup.model.chambers
    hot, cold = st.volume[:c], st.volume[c:]
    # the cold set is the hot set lag earlier, the lag 75 deg of a volume cycle
    earlier = vm.state(setup, theta - sol.lag)
    np.testing.assert_allclose(cold, earlier.volume[:c], rtol=1e-12)
    cycle = 2 * np.pi / (setup.strokes_per_turn / 2)
    assert sol.lag == pytest.approx(np.radians(75) / (2 * np.pi) * cycle, rel=1e-12)
    # Schmidt pressure from the two volumes and the dead volumes, written out here
    vk, vr, vh = sol.dead
    swing = setup.r_hi - setup.r_lo  # a chamber sweeps k x the swing, k = 180 cm^3/rad
    assert vh == pytest.approx(20e-6) and vr == pytest.approx(0.4 * 0.18e-3 * swing, rel=1e-12)
    assert vk == pytest.approx(0.2 * 0.18e-3 * swing, rel=1e-12)
    tr = (900 - 330) / np.log(900 / 330)
    p = sol.gas[:, None] / (cold / 330 + vk / 330 + vr / tr + vh / 900 + hot / 900)
    np.testing.assert_allclose(st.pressure[:c], p, rtol=1e-12)
    np.testing.assert_array_equal(st.pressure[c:], st.pressure[:c])  # one gas per circuit
    # gas: charged to 2 bar at the largest total volume, cold
    total = np.max(hot + cold, axis=1) + vk + vr + vh
    np.testing.assert_allclose(sol.gas, 2e5 * total / 330, rtol=1e-6)
    # torque on the shaft: both sets; on the members: the hot set by virtual work
    np.testing.assert_allclose(st.shaft, np.sum(st.pressure * st.dvolume, axis=0), rtol=1e-12,
                               atol=1e-9 * np.max(np.abs(st.shaft)))  # fmt: skip
    hot_shaft = np.sum(st.members * st.motion.dq, axis=0)
    np.testing.assert_allclose(hot_shaft, np.sum(st.pressure[:c] * st.dvolume[:c], axis=0),
                               atol=1e-9 * np.max(np.abs(hot_shaft)))  # fmt: skip


def test_work_grows_linearly_with_the_charge_pressure():
    w = [drives.evaluate(_cfg(pressure_model="adiabatic", charge_pressure=f"{p} bar")).summary
         for p in (2, 5)]  # fmt: skip
    assert w[1]["indicated_work_J"] == pytest.approx(2.5 * w[0]["indicated_work_J"], rel=1e-8)
    assert w[1]["indicated_efficiency"] == pytest.approx(w[0]["indicated_efficiency"], rel=1e-8)


def test_a_worse_regenerator_costs_heat_not_work():
    a = drives.evaluate(_cfg(pressure_model="adiabatic")).summary
    b = drives.evaluate(_cfg(pressure_model="adiabatic", regenerator_effectiveness=0.9)).summary
    assert b["indicated_work_J"] == pytest.approx(a["indicated_work_J"], rel=1e-12)
    assert b["heat_in_J_per_rev"] == pytest.approx(
        a["heat_in_J_per_rev"] + 0.1 * a["regenerator_heat_J_per_rev"], rel=1e-12
    )
    assert b["indicated_efficiency"] < a["indicated_efficiency"]


def test_displacement_counts_both_sets_and_the_isothermal_model_is_kept():
    iso = drives.evaluate(_cfg(pressure_model="isothermal")).summary
    adi = drives.evaluate(_cfg()).summary  # the default model
    assert adi["pressure_model"] == "adiabatic"
    assert adi["displacement_cm3_per_rev"] == pytest.approx(2 * iso["displacement_cm3_per_rev"])
    assert "heat_in_J_per_rev" not in iso
    assert adi["indicated_work_J"] < iso["indicated_work_J"]  # the upper bound stays above


@pytest.mark.parametrize(
    ("key", "value", "text"),
    [("regenerator_effectiveness", 1.5, "= 1.5 is not admissible: 0 <= eps <= 1"),
     ("gas", "argon", "helium"),
     ("phase_angle", "400 deg", "= 400 deg is not admissible: 0 deg <= phase_angle <= 360 deg"),
     ("cooler_volume", "-1 cm^3", "= -1 cm^3 is not admissible: 0 <= V <= 1 m^3")],
)  # fmt: skip
def test_bad_config_is_refused_in_one_line_naming_the_key(key, value, text):
    with pytest.raises(ConfigError) as err:
        _cfg(**{key: value})
    assert f"loads.{key}" in str(err.value) and "\n" not in str(err.value)
    assert text in str(err.value)


@pytest.mark.parametrize(
    ("key", "value"),
    [("regenerator_effectiveness", 1.5), ("gas", "argon"), ("phase_angle", -0.1),
     ("heater_volume", -1e-6), ("pressure_model", "linear")],
)  # fmt: skip
def test_bad_values_past_the_schema_name_the_key(key, value):
    """A hand-built config (no schema) meets the parameter holder: the same one line."""
    cfg = _cfg()
    cfg = {**cfg, "loads": {**cfg["loads"], key: value}}
    with pytest.raises(ParameterError) as err:
        _setup(cfg)
    assert err.value.name == f"loads.{key}" and "\n" not in str(err.value)


def test_drive_study_refuses_a_bad_effectiveness_too():
    cfg, _, _ = load_config(example="rhomboid-engine", sets=["loads.pressure_model=adiabatic"])
    cfg = {**cfg, "loads": {**cfg["loads"], "regenerator_effectiveness": 1.5}}
    with pytest.raises(ParameterError, match=r"^loads\.regenerator_effectiveness = 1\.5 "):
        drives.evaluate(cfg)


@pytest.mark.parametrize("model", ["adiabatic", "schmidt"])
def test_the_drives_own_study_equals_the_generic_layer(model):
    """rhomboid-engine: the drive's study and rotorkin.vane solve the same circuits."""
    cfg, _, _ = load_config(example="rhomboid-engine", sets=[f"loads.pressure_model={model}"])
    own = drives.evaluate(cfg)
    law = drives.get("rhomboid_cam").law(cfg)
    generic = evaluate_vane(cfg, law, drive_type="rhomboid_cam", title="generic")
    keys = ("displacement_cm3_per_rev", "compression_ratio_geometric", "indicated_work_J",
            "mean_torque_Nm", "heat_in_J_per_rev", "heat_out_J_per_rev",
            "regenerator_heat_J_per_rev", "indicated_efficiency", "carnot_efficiency",
            "peak_pressure_bar", "mean_pressure_bar", "gas_mass_g", "indicated_power_kW",
            "cold_set_lag_deg")  # fmt: skip
    for key in keys:
        assert generic.summary[key] == pytest.approx(own.summary[key], rel=1e-9), key
    # sampled on other grids (the drive: its period; the generic layer: a turn): 1e-6
    for key in ("pressure_max_bar", "flywheel_inertia_kgm2"):
        assert generic.summary[key] == pytest.approx(own.summary[key], rel=1e-6), key
    assert own.summary["pressure_model"] == model
    # the drive's columns: both sets' chambers, the circuit pressures
    cols = own.columns
    assert {"chamber1_pressure_bar", "cold_chamber1_volume_cm3"} <= set(cols)
    al = np.radians(cols["alpha_deg"])
    integrated = np.trapezoid(cols["shaft_torque_Nm"], al) * 2
    assert integrated == pytest.approx(own.summary["indicated_work_J"], rel=1e-3)


def test_the_drive_keeps_the_papers_linear_model():
    cfg, _, _ = load_config(example="rhomboid-engine")
    s = drives.evaluate(cfg).summary
    assert s["pressure_model"] == "linear"
    assert s["indicated_work_J"] == pytest.approx(2 * 60 * (np.pi - 2 * np.radians(40)),
                                                  rel=1e-12)  # fmt: skip
    assert "heat_in_J_per_rev" not in s
