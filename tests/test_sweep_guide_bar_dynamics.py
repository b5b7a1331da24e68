"""The vane pump's flow extremes, torques, inertia, flywheel and time peaks in the sweep kernel.

With ideal ports the guide-bar drive's kernel evaluates these keys over designs x input
angles. Each is checked against the study run design by design
(``rotorkin.drives.evaluate``, on the same 20 001 angles), and against closed forms: the
impellers' speed ratio extremes (the drive's closed form, JHIT 2012 eq. 3) times the
shaft speed, and a shaft alone carrying the inertia.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.core.batch import DEFAULT_SAMPLES, Designs
from rotorkin.drives import evaluate
from rotorkin.drives.guide_bar import sweep as kernel
from rotorkin.io.config import load_config, validate_config
from rotorkin.sweep.engine import coverage
from sweep_equality import (
    assert_equal_to_study,
    assert_kernel_is_study,
    assert_refused_as_study,
)

#: The keys the kernel took over from the study run design by design.
DYNAMIC = (
    "flow_max_l_per_min", "flow_min_l_per_min", "flow_ripple", "shaft_torque_min_Nm",
    "shaft_torque_max_Nm", "torque_ripple", "shaft_torque_with_inertia_min_Nm",
    "shaft_torque_with_inertia_max_Nm", "torque_ripple_with_inertia",
    "equivalent_inertia_mean_kgm2", "energy_fluctuation_J", "speed_fluctuation_without_flywheel",
    "speed_fluctuation", "flywheel_inertia_kgm2", "impeller1_speed_peak_rad_per_s",
    "impeller1_accel_peak_rad_per_s2", "impeller1_jerk_peak_rad_per_s3",
    "impeller2_speed_peak_rad_per_s", "impeller2_accel_peak_rad_per_s2",
    "impeller2_jerk_peak_rad_per_s3", "shaft_speed_mean_rpm",
)  # fmt: skip


def _base(sets=()):
    cfg, raw, _ = load_config(example="guide-bar-pump", sets=list(sets))
    return cfg, raw


def _sample(n: int, seed: int) -> dict:
    """Designs over the drive (both drivers, two gear ratios i12), the pump and its loads."""
    rng = np.random.default_rng(seed)
    return {
        "drive.lambda": rng.uniform(0.2, 0.8, n),
        "drive.gear_ratio": rng.choice([1.0, 2.0, 3.0], n),
        "drive.input_gear_ratio": rng.choice([1.0, 2.0], n),
        "drive.phase": np.radians(rng.uniform(90.0, 270.0, n)),
        "drive.driver": rng.choice(["crank", "guide"], n),
        "machine.vanes_per_impeller": rng.choice([1, 2], n),
        "machine.hub_radius": rng.uniform(0.01, 0.04, n),
        "machine.casing_radius": rng.uniform(0.05, 0.12, n),
        "machine.axial_width": rng.uniform(0.01, 0.08, n),
        "machine.inertia_shaft": rng.uniform(0.0, 0.01, n),
        "machine.inertia_impeller_1": np.where(
            rng.random(n) < 0.2, 0.0, rng.uniform(0.0, 0.01, n)
        ),  # fmt: skip
        "machine.inertia_impeller_2": rng.uniform(0.0, 0.01, n),
        "machine.speed_fluctuation": rng.uniform(0.005, 0.2, n),
        "loads.suction_pressure": rng.uniform(0.5e5, 2e5, n),
        "loads.discharge_pressure": rng.uniform(3e5, 20e5, n),
    }


def test_the_kernel_vectorises_the_dynamics_with_ideal_ports():
    cfg, _ = _base()
    summary = evaluate(cfg).summary
    assert set(DYNAMIC) <= {k for k, v in summary.items() if isinstance(v, (int, float))}
    fast, slow, why = coverage("guide_bar", cfg, list(_sample(1, 0)), list(DYNAMIC))
    assert (sorted(fast), slow, why) == (sorted(DYNAMIC), [], None)
    # a sealing land traps the chambers' fluid: the study evaluates those designs
    land, _ = _base(["machine.vane_angle=50deg", "machine.port_land=4deg"])
    fast, slow, _ = coverage("guide_bar", land, ["drive.lambda"], list(DYNAMIC))
    assert (fast, sorted(slow)) == ([], sorted(DYNAMIC))


@pytest.mark.parametrize("seed", [5, 6])
def test_kernel_equals_the_study_design_by_design(seed):
    cfg, _ = _base()
    n = 14
    p, ok = assert_kernel_is_study(cfg, _sample(n, seed), DYNAMIC)
    # every group of periods and chambers, and both drivers, ran
    assert set(p["drive.input_gear_ratio"][ok]) == {1.0, 2.0}
    assert set(p["machine.vanes_per_impeller"][ok]) == {1, 2}
    assert set(p["drive.driver"][ok]) == {"crank", "guide"}


def test_a_speed_profile_of_the_base_config_goes_through_the_kernel():
    _, raw = _base()
    raw["run"]["speed"] = ["1200 rpm", "1500 rpm", "1400 rpm"]
    cfg = validate_config(raw)
    n = 3
    table = {"drive.lambda": np.array([0.3, 0.5, 0.7]),
             "drive.input_gear_ratio": np.array([1.0, 2.0, 2.0])}  # fmt: skip
    p = Designs(cfg, table, n)
    got = kernel.metrics(p, DYNAMIC, DEFAULT_SAMPLES, 1)
    assert assert_equal_to_study(p, got, DYNAMIC) == n


def test_time_peaks_are_the_speed_ratio_extremes_times_the_speed():
    """At a constant speed w an impeller's peak angular speed is w times the largest
    |q'| of the drive's closed form (``impeller_speed_ratio_input_*``), to the sampling
    error of 20 001 angles; the mean shaft speed is w."""
    cfg, _ = _base()
    n = 6
    rng = np.random.default_rng(8)
    table = {"drive.lambda": rng.uniform(0.2, 0.8, n),
             "drive.driver": rng.choice(["crank", "guide"], n)}  # fmt: skip
    names = [*DYNAMIC, "impeller_speed_ratio_input_max", "impeller_speed_ratio_input_min"]
    got = kernel.metrics(Designs(cfg, table, n), names, DEFAULT_SAMPLES, 1)
    w = cfg["run"]["speed"]
    exact = w * np.maximum(np.abs(got["impeller_speed_ratio_input_max"]),
                           np.abs(got["impeller_speed_ratio_input_min"]))  # fmt: skip
    for k in (1, 2):
        peak = got[f"impeller{k}_speed_peak_rad_per_s"]
        np.testing.assert_allclose(peak, exact, rtol=1e-6)
        assert np.all(peak <= exact * (1.0 + 1e-12))  # samples never pass the extreme
    np.testing.assert_allclose(got["shaft_speed_mean_rpm"], w * 30.0 / np.pi, rtol=1e-12)


def test_a_shaft_alone_carrying_the_inertia():
    """Impellers without inertia at a constant speed: J_eq is the shaft's; the torque with
    inertia is the torque; the flywheel is what C_s asks for beyond the shaft."""
    cfg, _ = _base(["machine.inertia_impeller_1=0 kg*m^2", "machine.inertia_impeller_2=0 kg*m^2"])
    n = 5
    rng = np.random.default_rng(4)
    js, cs = rng.uniform(1e-4, 0.01, n), rng.uniform(0.01, 0.2, n)
    table = {"drive.lambda": rng.uniform(0.2, 0.8, n), "machine.inertia_shaft": js,
             "machine.speed_fluctuation": cs}  # fmt: skip
    got = kernel.metrics(Designs(cfg, table, n), DYNAMIC, 4001, 1)
    np.testing.assert_allclose(got["equivalent_inertia_mean_kgm2"], js, rtol=1e-14)
    for a, b in (("shaft_torque_with_inertia_min_Nm", "shaft_torque_min_Nm"),
                 ("shaft_torque_with_inertia_max_Nm", "shaft_torque_max_Nm"),
                 ("torque_ripple_with_inertia", "torque_ripple")):  # fmt: skip
        np.testing.assert_array_equal(got[a], got[b])
    w = cfg["run"]["speed"]
    np.testing.assert_allclose(got["flywheel_inertia_kgm2"],
                               np.maximum(got["energy_fluctuation_J"] / (cs * w**2) - js, 0.0),
                               rtol=1e-12)  # fmt: skip


def test_refused_designs_keep_the_studys_reason():
    cfg, _ = _base()
    table = {"machine.inertia_impeller_1": np.array([-1e-3, 0.01, 0.02]),
             "drive.lambda": np.array([0.5, 0.5, 1.5])}  # fmt: skip
    assert_refused_as_study(cfg, table, DYNAMIC, "guide_bar", "machine.inertia_impeller_1")
