"""The rotary-blade engine's work, torques, inertia, flywheel and time peaks in the sweep kernel.

Under the linear torque model (Zhuravlev et al. 2012, eq. 29) the rhomboid drive's
kernel evaluates these keys over designs x shaft angles. Each is checked against the
study run design by design (``rotorkin.drives.evaluate``, on the same 20 001 angles),
and against closed forms: the law's own speed, acceleration and jerk coefficients
(computed by another path, :func:`~rotorkin.drives.rhomboid_cam.kinematics.law_peaks`)
times the shaft speed's powers, and a shaft alone carrying the inertia.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.core.batch import DEFAULT_SAMPLES, Designs
from rotorkin.drives import evaluate
from rotorkin.drives.rhomboid_cam import sweep as kernel
from rotorkin.io.config import load_config, validate_config
from rotorkin.sweep.engine import coverage
from sweep_equality import (
    assert_equal_to_study,
    assert_kernel_is_study,
    assert_refused_as_study,
)

#: The keys the kernel took over from the study run design by design.
DYNAMIC = (
    "indicated_work_J", "indicated_work_per_period_J", "indicated_power_kW", "mean_torque_Nm",
    "torque_ripple", "torque_ripple_with_inertia", "shaft_torque_max_Nm", "shaft_torque_min_Nm",
    "shaft_torque_with_inertia_max_Nm", "shaft_torque_with_inertia_min_Nm",
    "inertia_torque_peak_Nm", "blade_pair_torque_peak_Nm", "equivalent_inertia_mean_kgm2",
    "equivalent_inertia_min_kgm2", "equivalent_inertia_max_kgm2", "energy_fluctuation_J",
    "speed_fluctuation_without_flywheel", "speed_fluctuation", "flywheel_inertia_kgm2",
    "blade_pair_1_speed_peak_rad_per_s", "blade_pair_1_accel_peak_rad_per_s2",
    "blade_pair_1_jerk_peak_rad_per_s3", "blade_pair_2_speed_peak_rad_per_s",
    "blade_pair_2_accel_peak_rad_per_s2", "blade_pair_2_jerk_peak_rad_per_s3",
    "shaft_speed_mean_rpm",
)  # fmt: skip


def _base(sets=()):
    cfg, raw, _ = load_config(example="rhomboid-engine", sets=list(sets))
    return cfg, raw


def _sample(n: int, seed: int) -> dict:
    """Designs over the law, the loads, the blades and every inertia."""
    rng = np.random.default_rng(seed)
    return {
        "drive.link_length": rng.uniform(0.05, 0.3, n),
        "drive.psi_min": np.radians(rng.uniform(25.0, 60.0, n)),
        "loads.torque_high": rng.uniform(20.0, 400.0, n),
        "loads.torque_low": rng.uniform(0.0, 100.0, n),
        "machine.blades_per_pair": rng.choice([1, 2], n),
        "machine.blade_thickness": np.radians(rng.uniform(2.0, 9.0, n)),
        "machine.inner_radius": rng.uniform(0.01, 0.05, n),
        "machine.outer_radius": rng.uniform(0.06, 0.2, n),
        "machine.axial_width": rng.uniform(0.01, 0.1, n),
        "machine.inertia_shaft": rng.uniform(0.0, 0.05, n),
        "machine.inertia_blade_pair_1": np.where(
            rng.random(n) < 0.2, 0.0, rng.uniform(0.0, 0.02, n)
        ),  # fmt: skip
        "machine.inertia_blade_pair_2": rng.uniform(0.0, 0.02, n),
        "machine.speed_fluctuation": rng.uniform(0.005, 0.2, n),
    }


def test_the_kernel_vectorises_the_dynamics_of_the_linear_model():
    cfg, _ = _base()
    summary = evaluate(cfg).summary
    assert set(DYNAMIC) <= {k for k, v in summary.items() if isinstance(v, (int, float))}
    fast, slow, why = coverage("rhomboid_cam", cfg, list(_sample(1, 0)), list(DYNAMIC))
    assert (sorted(fast), slow, why) == (sorted(DYNAMIC), [], None)
    # a gas model's torques come from its pressures: the study evaluates those designs
    gas, _ = _base(["loads.pressure_model=isothermal"])
    fast, slow, _ = coverage("rhomboid_cam", gas, ["drive.psi_min"], list(DYNAMIC))
    assert (fast, sorted(slow)) == ([], sorted(DYNAMIC))


@pytest.mark.parametrize("seed", [3, 4])
def test_kernel_equals_the_study_design_by_design(seed):
    cfg, _ = _base()
    n = 12
    p, ok = assert_kernel_is_study(cfg, _sample(n, seed), DYNAMIC)
    assert set(p["machine.blades_per_pair"][ok]) == {1, 2}  # every group of chambers ran


def test_a_speed_profile_of_the_base_config_goes_through_the_kernel():
    _, raw = _base()
    raw["run"]["speed"] = ["1200 rpm", "1500 rpm", "1400 rpm"]
    cfg = validate_config(raw)
    n = 3
    p = Designs(cfg, {"drive.psi_min": np.radians([30.0, 40.0, 50.0])}, n)
    got = kernel.metrics(p, DYNAMIC, DEFAULT_SAMPLES, 1)
    assert assert_equal_to_study(p, got, DYNAMIC) == n
    # an accelerating shaft: its inertia torque is not that of a constant speed
    assert np.all(got["inertia_torque_peak_Nm"] > 0.0)


def test_time_peaks_are_the_law_coefficients_times_the_speed():
    """At a constant speed w a blade pair's angular speed, acceleration and jerk are its
    law's coefficients (``law_peaks``, another path through the drive) times w, w^2, w^3;
    the mean shaft speed is w."""
    cfg, _ = _base()
    n = 7
    rng = np.random.default_rng(9)
    table = {"drive.psi_min": np.radians(rng.uniform(25.0, 60.0, n)),
             "drive.link_length": rng.uniform(0.05, 0.3, n)}  # fmt: skip
    names = [*DYNAMIC, "blade_speed_coeff_max", "blade_speed_coeff_min",
             "blade_accel_coeff_max", "blade_jerk_coeff_max"]  # fmt: skip
    got = kernel.metrics(Designs(cfg, table, n), names, 4001, 1)
    w = cfg["run"]["speed"]
    speed = np.maximum(np.abs(got["blade_speed_coeff_max"]), np.abs(got["blade_speed_coeff_min"]))
    close = {"rtol": 1e-12, "atol": 0.0}
    for pair in (1, 2):
        np.testing.assert_allclose(got[f"blade_pair_{pair}_speed_peak_rad_per_s"], w * speed,
                                   **close)  # fmt: skip
        np.testing.assert_allclose(got[f"blade_pair_{pair}_accel_peak_rad_per_s2"],
                                   w**2 * got["blade_accel_coeff_max"], **close)  # fmt: skip
        np.testing.assert_allclose(got[f"blade_pair_{pair}_jerk_peak_rad_per_s3"],
                                   w**3 * got["blade_jerk_coeff_max"], **close)  # fmt: skip
    np.testing.assert_allclose(got["shaft_speed_mean_rpm"], w * 30.0 / np.pi, **close)


def test_a_shaft_alone_carrying_the_inertia():
    """Blade pairs without inertia at a constant speed: J_eq is the shaft's, constant; the
    shaft spends no torque on inertia; the work per revolution is the law's indicator work
    of both periods, and the flywheel is what C_s asks for beyond the shaft."""
    cfg, _ = _base(
        ["machine.inertia_blade_pair_1=0 kg*m^2", "machine.inertia_blade_pair_2=0 kg*m^2"]
    )
    n = 6
    rng = np.random.default_rng(2)
    js = rng.uniform(0.001, 0.05, n)
    cs = rng.uniform(0.01, 0.2, n)
    table = {"drive.psi_min": np.radians(rng.uniform(25.0, 60.0, n)),
             "machine.inertia_shaft": js, "machine.speed_fluctuation": cs}  # fmt: skip
    got = kernel.metrics(Designs(cfg, table, n), [*DYNAMIC, "indicator_work_J"], 2001, 1)
    for key in ("equivalent_inertia_mean_kgm2", "equivalent_inertia_min_kgm2",
                "equivalent_inertia_max_kgm2"):  # fmt: skip
        np.testing.assert_allclose(got[key], js, rtol=1e-15)  # a mean of equal values
    assert np.all(got["inertia_torque_peak_Nm"] == 0.0)
    np.testing.assert_array_equal(got["torque_ripple_with_inertia"], got["torque_ripple"])
    np.testing.assert_allclose(got["indicated_work_J"], 2.0 * got["indicator_work_J"], rtol=1e-15)
    w = cfg["run"]["speed"]
    np.testing.assert_allclose(got["speed_fluctuation_without_flywheel"],
                               got["energy_fluctuation_J"] / (js * w**2), rtol=1e-13)  # fmt: skip
    np.testing.assert_allclose(got["flywheel_inertia_kgm2"],
                               np.maximum(got["energy_fluctuation_J"] / (cs * w**2) - js, 0.0),
                               rtol=1e-13)  # fmt: skip


def test_refused_designs_keep_the_studys_reason():
    cfg, _ = _base()
    table = {"machine.inertia_blade_pair_2": np.array([-1e-3, 0.01, 0.02]),
             "drive.psi_min": np.radians([40.0, 40.0, 95.0])}  # fmt: skip
    assert_refused_as_study(cfg, table, DYNAMIC, "rhomboid_cam", "machine.inertia_blade_pair_2")
