"""The fuel-air cycle of twin-rotor engines on any drive (rotorkin.machines.fuel_air).

Independent checks: the air-standard Otto cycle (Heywood sec. 5.3) as the limit of a
short burn without walls and of constant gamma; the torque integrated over the turn
against the integrated cycle work; scaling with displacement and speed; the first law
per cycle.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin import drives
from rotorkin.io.config import load_config

GEARS = "elliptic-gear-engine"


def _run(example=GEARS, *sets, points=721):
    cfg, _, _ = load_config(example=example, sets=[f"run.points={points}", *sets])
    return drives.evaluate(cfg)


@pytest.mark.parametrize("example", [GEARS, "wobble-cam-engine", "tabulated-engine"])
def test_a_short_burn_without_walls_at_constant_gamma_is_the_otto_cycle(example):
    """Burn 0.5 deg (of the cycle angle) centred on the dead centre, adiabatic, gamma 1.35:
    indicated efficiency = 1 - r^(1 - gamma) to 1e-4 (the burn's width), with the heat the
    charge releases."""
    s = _run(example, "loads.heat_transfer=none", "loads.gas_properties=constant",
             "loads.specific_heat_ratio=1.35", "loads.burn_start=-0.25 deg",
             "loads.burn_duration=0.5 deg", "loads.wiebe_a=20").summary  # fmt: skip
    r = s["compression_ratio_geometric"]
    otto = 1 - r ** (1 - 1.35)
    released = s["heat_added_J_per_rev"]
    assert s["indicated_work_J"] / released == pytest.approx(otto, rel=1e-4)
    assert s["heat_to_walls_J_per_rev"] == 0.0


def test_mean_torque_integrated_over_the_turn_is_the_cycle_work():
    """The torque column (pressures read from the integrated tables, p dV/dtheta) against
    the Runge-Kutta work of the cycles: to the trapezoid rule on 3601 angles."""
    res = _run(GEARS, points=3601)
    angle = np.radians(res.columns["theta_deg"])
    torque = res.columns["shaft_torque_Nm"]
    mean = np.trapezoid(torque, angle) / (angle[-1] - angle[0])
    assert mean * 2 * np.pi == pytest.approx(res.summary["indicated_work_J"], rel=1e-4)


def test_the_first_law_holds_per_cycle():
    """Work = heat released - heat to the walls - the gas's energy rise, every closed part."""
    from rotorkin.drives.wobble_cam import study

    cfg, _, _ = load_config(example="wobble-cam-engine")
    _, _, cycle = study.models(cfg)
    balance = cycle.heat - cycle.heat_wall - cycle.energy_rise - cycle.work_closed
    assert np.max(np.abs(balance)) < 1e-6 * np.max(cycle.heat)
    assert np.all(cycle.heat_wall > 0) and np.all(cycle.work_closed > 0)


def test_work_scales_with_displacement_and_power_with_speed():
    base = _run(GEARS).summary
    wide = _run(GEARS, "machine.axial_width=80 mm").summary  # twice the chambers' volume
    assert wide["displacement_cm3_per_rev"] == pytest.approx(
        2 * base["displacement_cm3_per_rev"], rel=1e-12)  # fmt: skip
    # a larger chamber loses a smaller share of its heat: a little more than twice the work
    assert 2.0 < wide["indicated_work_J"] / base["indicated_work_J"] < 2.2
    adiabatic = [_run(GEARS, "loads.heat_transfer=none", *s).summary["indicated_work_J"]
                 for s in ([], ["machine.axial_width=80 mm"])]  # fmt: skip
    assert adiabatic[1] == pytest.approx(2 * adiabatic[0], rel=1e-9)  # no walls: exactly
    fast = _run(GEARS, "run.speed=6000 rpm").summary
    assert 2.0 < fast["indicated_power_kW"] / base["indicated_power_kW"] < 2.2
    # supercharging: the trapped charge, and so the work, grows with the intake pressure
    boost = _run(GEARS, "loads.intake_pressure=1.5 bar").summary
    assert 1.4 < boost["indicated_work_J"] / base["indicated_work_J"] < 1.6


def test_a_spark_ignition_engine_has_a_spark_ignition_engines_numbers():
    """Heywood ch. 1 and 9: SI engines at wide-open throttle reach 8.5-13.5 bar IMEP, peak
    pressures 40-70 bar about 10-25 deg after top centre, indicated efficiencies 0.3-0.45 at
    compression ratio 10, and lose 10-30 % of the fuel's energy to the walls."""
    s = _run(GEARS).summary
    assert 8.5 < s["imep_bar"] < 14.0
    assert 40 < s["peak_pressure_bar"] < 70
    assert 5 < s["peak_pressure_angle_deg"] < 25
    assert 0.3 < s["indicated_efficiency"] < 0.45
    assert 0.1 < s["heat_to_walls_J_per_rev"] / s["fuel_energy_J_per_rev"] < 0.3
    assert 2200 < s["peak_temperature_K"] < 3000
    assert s["indicated_efficiency"] < s["otto_efficiency"]


def test_the_ideal_model_stays_selectable_and_is_the_closed_form():
    s = _run(GEARS, "loads.model=ideal", "loads.heat_per_cycle=90 J").summary
    r = s["compression_ratio_geometric"]
    assert s["indicated_efficiency"] == pytest.approx(1 - r ** (1 - 1.35), rel=1e-12)
    assert "fuel_energy_J_per_rev" not in s


def test_nasa_and_constant_gas_differ_as_they_should():
    """Temperature-dependent c_v (larger when hot) lowers the peak temperature and the
    efficiency below the constant-gamma 1.35 cycle's (Heywood fig. 5-9)."""
    nasa = _run(GEARS, "loads.gas_properties=nasa").summary
    const = _run(GEARS, "loads.gas_properties=constant", "loads.specific_heat_ratio=1.35").summary
    assert nasa["peak_temperature_K"] < const["peak_temperature_K"]
    assert nasa["indicated_efficiency"] < const["indicated_efficiency"]
    assert nasa["gas_properties"].startswith("NASA")
    assert const["gas_properties"] == "constant gamma = 1.35"


def test_a_burn_past_the_exhaust_opening_is_refused_naming_the_key():
    from rotorkin.core.errors import ParameterError

    with pytest.raises(ParameterError) as err:
        _run(GEARS, "loads.burn_start=150 deg", "loads.burn_duration=60 deg")
    assert err.value.name == "loads.burn_duration"


def test_a_highly_charged_high_compression_engine_passes_the_pressure_limit():
    s = _run(GEARS, "loads.intake_pressure=4 bar", "machine.compression_ratio=16").summary
    assert s["peak_pressure_bar"] > 250
    assert "limits.peak_pressure" in s["limits_passed"]


def test_the_sweep_integrates_every_design_as_the_study_does_and_power_follows_displacement():
    """Plate tilt x compression ratio: the batch kernel's fuel-air cycle equals the study's
    per design (to 1e-12), and the power grows with the displacement."""
    from rotorkin.sweep import run_sweep

    raw = load_config(None, "wobble-cam-engine")[1]
    ds = run_sweep(raw, {"drive.plate_tilt": "20deg,35deg,50deg",
                         "machine.compression_ratio": "8,12"}, progress=False)  # fmt: skip
    for tilt in (20.0, 50.0):
        d = ds.sel({"drive.plate_tilt": tilt, "machine.compression_ratio": 12.0})
        cfg, _, _ = load_config(example="wobble-cam-engine",
                                sets=[f"drive.plate_tilt={tilt} deg",
                                      "machine.compression_ratio=12"])  # fmt: skip
        s = drives.evaluate(cfg).summary
        for key in ("indicated_work_J", "peak_pressure_bar", "peak_temperature_K", "imep_bar",
                    "heat_to_walls_J_per_rev", "fuel_energy_J_per_rev", "indicated_power_kW",
                    "peak_pressure_angle_deg", "indicated_work_per_cycle_b_J"):  # fmt: skip
            assert float(d[key]) == pytest.approx(s[key], rel=1e-12), key
    power = ds["indicated_power_kW"].sel({"machine.compression_ratio": 12.0}).values
    disp = ds["displacement_cm3_per_rev"].sel({"machine.compression_ratio": 12.0}).values
    assert np.all(np.diff(disp) > 0) and np.all(np.diff(power) > 0)
    assert power[-1] / power[0] == pytest.approx(disp[-1] / disp[0], rel=0.15)
    assert np.all(ds["peak_pressure_bar"].values < 100)


def test_a_section_too_thin_for_any_cycle_is_refused_naming_its_key(capsys, tmp_path):
    from rotorkin.cli import main

    code = main(["run", "-e", "elliptic-gear-engine", "--set",
                 'machine.outer_radius="40.001 mm"', "--out", str(tmp_path / "o")])  # fmt: skip
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1
    assert "machine.outer_radius = 40.001 mm" in err[0] and "hydraulic diameter" in err[0]
    assert not (tmp_path / "o").exists()
