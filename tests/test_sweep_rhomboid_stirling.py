"""The rotary-blade Stirling engine's cycle, torques and flywheel in the sweep kernel.

Under the Stirling models (``loads.pressure_model`` adiabatic or schmidt: a hot and a
lagging cold blade set joined by heater, regenerator and cooler, Urieli and Berchowitz
1984) the rhomboid drive's kernel solves the circuits of many designs in one run of the
cycle. Each design is checked against the study run on its own
(``rotorkin.drives.evaluate``), and against what the models must give by themselves:
the Schmidt cycle with an ideal regenerator runs at the Carnot efficiency, and the
work from the shaft torque over the fine grid is the heat in less the heat out of the
integrated cycle (two different paths).
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.analysis import stirling as sa
from rotorkin.core.batch import Designs
from rotorkin.drives.rhomboid_cam import sweep as kernel
from rotorkin.io.config import load_config
from rotorkin.sweep.engine import coverage, evaluate_designs
from sweep_equality import assert_kernel_is_study, assert_refused_as_study

#: The Stirling model's own keys, beside the dynamics of the linear model's test.
STIRLING = (
    "phase_angle_deg", "cold_set_lag_deg", "circuits", "heater_volume_cm3",
    "regenerator_volume_cm3", "cooler_volume_cm3", "regenerator_effectiveness",
    "charge_pressure_bar", "gas_mass_g", "heat_in_J_per_rev", "heat_out_J_per_rev",
    "regenerator_heat_J_per_rev", "indicated_efficiency", "carnot_efficiency",
    "peak_pressure_bar", "mean_pressure_bar", "hot_temperature_K", "cold_temperature_K",
    "periodic_residual_K", "pressure_max_bar", "pressure_min_bar",
)  # fmt: skip
DYNAMIC = (
    "indicated_work_J", "indicated_power_kW", "mean_torque_Nm", "torque_ripple",
    "shaft_torque_max_Nm", "shaft_torque_min_Nm", "flywheel_inertia_kgm2",
    "energy_fluctuation_J", "blade_pair_torque_peak_Nm", "displacement_cm3_per_rev",
)  # fmt: skip


def _base(model: str, sets=()):
    cfg, raw, _ = load_config(example="rhomboid-engine",
                              sets=[f"loads.pressure_model={model}", *sets])  # fmt: skip
    return cfg


def _sample(n: int, seed: int, dead: bool) -> dict:
    """Designs over the law, the machine, the gas and its heat exchangers."""
    rng = np.random.default_rng(seed)
    table = {
        "drive.psi_min": np.radians(rng.uniform(30.0, 60.0, n)),
        "drive.link_length": rng.uniform(0.05, 0.3, n),
        "machine.blades_per_pair": rng.choice([1, 2], n),
        "machine.blade_thickness": np.radians(rng.uniform(2.0, 9.0, n)),
        "machine.outer_radius": rng.uniform(0.06, 0.2, n),
        "machine.inertia_blade_pair_1": rng.uniform(0.0, 0.02, n),
        "loads.charge_pressure": rng.uniform(2e5, 40e5, n),
        "loads.hot_temperature": rng.uniform(500.0, 1000.0, n),
        "loads.cold_temperature": rng.uniform(280.0, 400.0, n),
        "loads.gas": rng.choice(["air", "helium", "hydrogen"], n).astype(object),
        "loads.phase_angle": np.radians(rng.uniform(45.0, 135.0, n)),
        "loads.regenerator_effectiveness": rng.uniform(0.8, 1.0, n),
    }
    if dead:  # given volumes; else each design's default fractions of its swept volume
        table["loads.heater_volume"] = rng.uniform(0.0, 50e-6, n)
        table["loads.cooler_volume"] = rng.uniform(0.0, 50e-6, n)
    return table


@pytest.mark.parametrize("model", ["adiabatic", "schmidt"])
def test_the_kernel_vectorises_the_stirling_models(model):
    cfg = _base(model)
    names = list(DYNAMIC + STIRLING)
    assert set(names) <= set(kernel.metric_names(cfg))
    fast, slow, why = coverage("rhomboid_cam", cfg, list(_sample(1, 0, True)), names)
    assert (sorted(fast), slow, why) == (sorted(names), [], None)


@pytest.mark.parametrize(
    ("model", "n", "dead"), [("schmidt", 10, True), ("schmidt", 6, False), ("adiabatic", 5, True)]
)
def test_every_design_is_the_study_run_alone(model, n, dead):
    # the adiabatic cycle: each design leaves the batch's Newton run once its own cycle is
    # periodic, so its numbers are those it has alone (to the last bit here)
    assert_kernel_is_study(_base(model), _sample(n, 7 + n, dead), list(DYNAMIC + STIRLING))


def test_schmidt_with_an_ideal_regenerator_runs_at_the_carnot_efficiency():
    table = _sample(16, 3, True)
    table["loads.regenerator_effectiveness"] = np.ones(16)
    p = Designs(_base("schmidt"), table, 16)
    res = evaluate_designs(p, ["indicated_efficiency", "carnot_efficiency"], threads=1)
    ok = res["reason"] == 0
    assert ok.sum() >= 8
    m = res["metrics"]
    carnot = 1.0 - table["loads.cold_temperature"] / table["loads.hot_temperature"]
    np.testing.assert_allclose(m["carnot_efficiency"][ok], carnot[ok], rtol=1e-12)
    np.testing.assert_allclose(m["indicated_efficiency"][ok], carnot[ok], rtol=1e-9)


@pytest.mark.parametrize("model", ["adiabatic", "schmidt"])
def test_the_shaft_work_is_the_cycle_heat_in_less_heat_out(model):
    # the work from the gas torque on the shaft (20 001 angles, both blade sets) against
    # the heat balance of the integrated circuits (their own grid and integrator)
    n = 6 if model == "adiabatic" else 12
    p = Designs(_base(model), _sample(n, 11, True), n)
    names = ["indicated_work_J", "heat_in_J_per_rev", "heat_out_J_per_rev"]
    res = evaluate_designs(p, names, threads=1)
    ok = res["reason"] == 0
    assert ok.sum() >= n // 2
    m = {k: v[ok] for k, v in res["metrics"].items()}
    balance = m["heat_in_J_per_rev"] - m["heat_out_J_per_rev"]
    np.testing.assert_allclose(m["indicated_work_J"], balance, rtol=2e-4)


def test_a_design_whose_blades_do_not_fit_the_swing_is_refused_as_the_study_refuses_it():
    table = {"machine.blade_thickness": np.radians([40.0, 5.0]),
             "loads.charge_pressure": np.array([10e5, 12e5])}  # fmt: skip
    assert_refused_as_study(_base("schmidt"), table, list(STIRLING), "rhomboid_cam",
                            "machine.blade_thickness")  # fmt: skip


def test_the_adiabatic_cycle_of_many_designs_is_each_design_alone():
    rng = np.random.default_rng(5)
    n, steps = 7, 90
    theta = np.linspace(0.0, 2.0 * np.pi, 2 * steps + 1)
    lead = rng.uniform(0.5, 2.0, n)[:, None]
    swept = rng.uniform(50e-6, 200e-6, n)[:, None]
    vc = 20e-6 + swept * (1.0 + np.cos(theta)) / 2.0
    ve = 20e-6 + swept * (1.0 + np.cos(theta + lead)) / 2.0
    dvc = -swept * np.sin(theta) / 2.0
    dve = -swept * np.sin(theta + lead) / 2.0
    gas = rng.uniform(0.05, 2.0, n)
    vk, vr, vh = (rng.uniform(5e-6, 50e-6, n) for _ in range(3))
    tk, th = rng.uniform(280.0, 400.0, n), rng.uniform(500.0, 1000.0, n)
    many = sa.adiabatic_cycle(gas, vc, ve, dvc, dve, vk, vr, vh, tk, th)
    for i in range(n):
        one = sa.adiabatic_cycle(gas[i], vc[i], ve[i], dvc[i], dve[i], vk[i], vr[i], vh[i],
                                 tk[i], th[i])  # fmt: skip
        for name in ("pressure", "tc", "te", "work", "heat_in", "residual"):
            np.testing.assert_array_equal(getattr(many, name)[i], getattr(one, name),
                                          err_msg=name)  # fmt: skip
