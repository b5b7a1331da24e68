"""The eccentric-cam reactor's torques, flywheel, contact and force keys in the sweep kernel.

Each key the kernel computes over designs x shaft angles is checked against the
study run design by design (``rotorkin.drives.evaluate``, which samples the same
20 001 angles), and the inertia keys of a flat follower against their closed forms.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from rotorkin.analysis import pairs as pairs_mod
from rotorkin.core.batch import DEFAULT_SAMPLES, Designs
from rotorkin.drives import evaluate
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.drives.eccentric_cam import sweep as kernel
from rotorkin.drives.eccentric_cam.forces import forces_summary
from rotorkin.drives.eccentric_cam.reactor import opposed_piston, reactor_summary
from rotorkin.io.config import load_config, validate_config
from rotorkin.sweep.engine import coverage, evaluate_designs
from sweep_equality import assert_equal_to_study, assert_reasons_of_study

#: The keys this kernel took over from the study run design by design.
DYNAMIC = (
    "back_pressure_bar", "piston_force_peak_N", "indicated_work_J", "mean_torque_Nm",
    "shaft_torque_min_Nm", "shaft_torque_max_Nm", "shaft_torque_peak_Nm",
    "shaft_torque_with_inertia_peak_Nm", "inertia_torque_peak_Nm",
    "equivalent_inertia_mean_kgm2", "energy_fluctuation_J", "speed_fluctuation_without_flywheel",
    "speed_fluctuation", "flywheel_inertia_kgm2",
    "piston_left_speed_peak_m_per_s", "piston_left_accel_peak_m_per_s2",
    "piston_left_jerk_peak_m_per_s3", "piston_right_speed_peak_m_per_s",
    "piston_right_accel_peak_m_per_s2", "piston_right_jerk_peak_m_per_s3",
    "shaft_speed_mean_rpm", "peak_contact_force_N", "peak_contact_stress_MPa",
    "peak_contact_stress_at_deg", "contact_safety_factor", "peak_bearing_load_N",
    "friction_loss_J_per_rev", "friction_loss_W", "mechanical_efficiency",
    "work_through_drive_J", "follower_force_peak_N", "follower_force_min_N", "follower_lift_off",
    "side_thrust_peak_N", "guide_tilting_moment_peak_Nm", "shaft_radial_load_peak_N",
)  # fmt: skip
#: Integrals of a conservative fluid's torque: zero up to round-off of the torque's size.
ROUND_OFF = {"indicated_work_J": "shaft_torque_peak_Nm", "mean_torque_Nm": "shaft_torque_peak_Nm"}


def _base(sets=()):
    cfg, raw, _ = load_config(example="eccentric-reactor", sets=list(sets))
    return cfg, raw


def _sample(n: int, seed: int) -> dict:
    """Designs over the drive, the reactor, its inertias, the speed and the contact keys."""
    rng = np.random.default_rng(seed)
    return {
        "drive.eccentricity": rng.uniform(0.004, 0.07, n),
        "drive.follower": rng.choice(["knife_edge", "flat", "roller"], n),
        "drive.roller_radius": rng.uniform(0.004, 0.03, n),
        "drive.tip_radius": np.where(rng.random(n) < 0.25, 0.0, rng.uniform(5e-4, 5e-3, n)),
        "machine.fluid": rng.choice(["gas", "liquid"], n),
        "machine.initial_pressure": rng.uniform(0.5e5, 20e5, n),
        "machine.back_pressure": rng.uniform(0.0, 2e5, n),
        "machine.piston_mass": rng.uniform(0.0, 3.0, n),
        "machine.inertia_shaft": rng.uniform(0.0, 0.1, n),
        "machine.speed_fluctuation": rng.uniform(0.005, 0.2, n),
        "run.speed": rng.uniform(5.0, 400.0, n),
        "contact.youngs_modulus": rng.uniform(70e9, 300e9, n),
        "contact.poisson_ratio": rng.uniform(0.2, 0.35, n),
        "contact.roller_width": rng.uniform(0.005, 0.03, n),
        "contact.allowable_stress": rng.uniform(0.5e9, 2.5e9, n),
        "contact.friction_sliding": rng.uniform(0.0, 0.15, n),
        "contact.friction_rolling": rng.uniform(0.0, 0.01, n),
        "contact.friction_bearing": rng.uniform(0.0, 0.01, n),
        "contact.bearing_radius": rng.uniform(0.005, 0.04, n),
    }


def test_the_kernel_vectorises_every_force_and_torque_key_of_the_study():
    cfg, _ = _base()
    summary = evaluate(cfg).summary
    numeric = {k for k, v in summary.items() if isinstance(v, (bool, int, float))}
    assert set(DYNAMIC) <= numeric
    assert set(DYNAMIC) <= set(kernel.metric_names(cfg))
    fast, slow, why = coverage("eccentric_cam", cfg, list(_sample(1, 0)), list(DYNAMIC))
    assert (sorted(fast), slow, why) == (sorted(DYNAMIC), [], None)


@pytest.mark.parametrize("seed", [11, 12])
def test_kernel_equals_the_study_design_by_design(seed):
    cfg, _ = _base()
    n = 24
    p = Designs(cfg, _sample(n, seed), n)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no design may fall back to the study
        res = evaluate_designs(p, DYNAMIC, threads=2)
    assert np.all(res["reason"] == 0)
    assert assert_equal_to_study(p, res["metrics"], DYNAMIC, ROUND_OFF) == n
    # every follower and an edge without a tip were in the sample
    followers = set(p["drive.follower"])
    assert followers == {"knife_edge", "flat", "roller"}
    edge = (p["drive.follower"] == "knife_edge") & (p["drive.tip_radius"] == 0.0)
    assert edge.any() and np.all(np.isnan(res["metrics"]["peak_contact_stress_MPa"][edge]))
    assert np.all(np.isfinite(res["metrics"]["peak_contact_stress_MPa"][~edge]))


@pytest.mark.parametrize(
    "sets",
    [
        ["drive.follower=roller", "drive.roller_radius=12mm", "machine.fluid=liquid"],
        ["drive.tip_radius=0mm"],  # a sharp edge: no contact stress keys at all
        ["drive.follower=flat", "machine.back_pressure=1bar"],
        ["run.speed=1500rpm"],  # the speed of the base, not swept
    ],
)
def test_kernel_equals_the_study_on_other_bases(sets):
    cfg, _ = _base(sets)
    n = 6
    rng = np.random.default_rng(5)
    table = {"drive.eccentricity": rng.uniform(0.004, 0.07, n),
             "run.speed": rng.uniform(5.0, 400.0, n),
             "contact.friction_sliding": rng.uniform(0.0, 0.15, n)}  # fmt: skip
    if any(s.startswith("run.speed") for s in sets):
        del table["run.speed"]
    p = Designs(cfg, table, n)
    got = kernel.metrics(p, DYNAMIC, DEFAULT_SAMPLES, 1)
    assert assert_equal_to_study(p, got, DYNAMIC, ROUND_OFF) == n


@pytest.mark.parametrize(
    "swept",
    [
        {"machine.bore": (0.03, 0.07), "machine.polytropic_exponent": (1.0, 1.4)},
        {"run.speed": (5.0, 400.0)},
    ],
    ids=["machine", "speed"],
)
def test_kernel_equals_the_study_where_no_drive_value_varies(swept):
    """Every design on the base's discs: the drive's curves still carry the design axis."""
    cfg, _ = _base()
    n = 5
    rng = np.random.default_rng(8)
    p = Designs(cfg, {k: rng.uniform(*lims, n) for k, lims in swept.items()}, n)
    got = kernel.metrics(p, DYNAMIC, DEFAULT_SAMPLES, 1)
    assert assert_equal_to_study(p, got, DYNAMIC, ROUND_OFF) == n


def test_a_speed_profile_of_the_base_config_goes_through_the_kernel():
    _, raw = _base()
    raw["run"]["speed"] = ["500 rpm", "700 rpm", "650 rpm", "450 rpm"]
    cfg = validate_config(raw)
    n = 4
    p = Designs(cfg, {"drive.eccentricity": np.linspace(0.01, 0.06, n)}, n)
    got = kernel.metrics(p, DYNAMIC, DEFAULT_SAMPLES, 1)
    assert assert_equal_to_study(p, got, DYNAMIC, ROUND_OFF) == n
    # an accelerating shaft: the inertia torque differs from that at constant speed
    assert np.all(got["shaft_speed_mean_rpm"] != 500.0)


def test_flat_follower_inertia_keys_match_their_closed_forms():
    """Flat faces move harmonically, z = e cos(beta), z' = -e cos(beta): at the speed w
    the two pistons' inertia torque is m e^2 w^2 sin(2 beta), the mean equivalent inertia
    J + m e^2, a piston's peak speed, acceleration and jerk e w, e w^2, e w^3, and its
    side thrust zero."""
    cfg, _ = _base(["drive.follower=flat"])
    n = 9
    rng = np.random.default_rng(7)
    e, m = rng.uniform(0.005, 0.07, n), rng.uniform(0.1, 3.0, n)
    w, js = rng.uniform(5.0, 400.0, n), rng.uniform(0.0, 0.1, n)
    table = {"drive.eccentricity": e, "machine.piston_mass": m, "run.speed": w,
             "machine.inertia_shaft": js}  # fmt: skip
    got = kernel.metrics(Designs(cfg, table, n), DYNAMIC, DEFAULT_SAMPLES, 1)
    close = {"rtol": 1e-9, "atol": 0.0}
    np.testing.assert_allclose(got["inertia_torque_peak_Nm"], m * e**2 * w**2, **close)
    np.testing.assert_allclose(got["equivalent_inertia_mean_kgm2"], js + m * e**2, **close)
    for side in ("left", "right"):
        np.testing.assert_allclose(got[f"piston_{side}_speed_peak_m_per_s"], e * w, **close)
        np.testing.assert_allclose(got[f"piston_{side}_accel_peak_m_per_s2"], e * w**2, **close)
        np.testing.assert_allclose(got[f"piston_{side}_jerk_peak_m_per_s3"], e * w**3, **close)
    np.testing.assert_allclose(got["shaft_speed_mean_rpm"], w * 30.0 / np.pi, **close)
    assert np.all(got["side_thrust_peak_N"] == 0.0)
    # the flat face keeps the volume: the fluid does no work on the shaft
    assert np.all(got["shaft_torque_peak_Nm"] <= 1e-9 * got["piston_force_peak_N"])


def test_refused_designs_keep_the_studys_reason():
    cfg, _ = _base()
    n = 5
    table = {
        # too eccentric for the disc; a reactor shorter than the stroke; three good ones
        "drive.eccentricity": np.array([0.079, 0.08, 0.04, 0.02, 0.03]),
        "machine.device_length": np.array([1.0, 1.0, 0.05, 0.5, 1.0]),
        "run.speed": np.array([10.0, 20.0, 30.0, 40.0, 50.0]),
    }
    p = Designs(cfg, table, n)
    res = evaluate_designs(p, DYNAMIC, threads=1)
    assert_reasons_of_study(p, res["reason"], "eccentric_cam")
    refused = res["reason"] != 0
    assert refused.tolist() == [False, True, True, False, False]
    for name in DYNAMIC:
        assert np.all(np.isnan(res["metrics"][name][refused]))
    assert assert_equal_to_study(p, res["metrics"], DYNAMIC, ROUND_OFF) == 3


def _design(follower="roller"):
    drive = ec.EccentricCam(0.08, 0.03, follower, 0.01)
    reactor = opposed_piston(drive, device_length=1.0, bore=0.05, fluid="gas",
                             initial_pressure=3e5, polytropic_exponent=1.2,
                             bulk_modulus=1.5e9, back_pressure=1e5)  # fmt: skip
    return drive, reactor


def test_summaries_of_one_design_are_floats_and_of_designs_arrays():
    beta = np.linspace(0.0, 2.0 * np.pi, 2001)
    drive, reactor = _design()
    model = pairs_mod.ContactModel()
    one_r = reactor_summary(drive, reactor, (0.03, (0.5, 0.5)), 60.0, 0.02, beta)
    one_f = forces_summary(drive, reactor, (0.03, (0.5, 0.5)), 60.0, beta, model, 0.01, 0.0)
    assert all(type(v) in (float, bool, str) for v in {**one_r, **one_f}.values())
    assert isinstance(one_f["peak_contact_stress_pair"], str)
    for d in (1, 3):
        col = np.full((d, 1), 1.0)
        drive_d = ec.EccentricCam(0.08 * col, 0.03 * col, "roller", 0.01 * col)
        reactor_d = opposed_piston(drive_d, device_length=col, bore=0.05 * col, fluid="gas",
                                   initial_pressure=3e5 * col, polytropic_exponent=1.2 * col,
                                   bulk_modulus=1.5e9 * col, back_pressure=1e5 * col)  # fmt: skip
        inertia = (0.03 * col, np.stack([0.5 * col, 0.5 * col]))
        model_d = pairs_mod.ContactModel(210e9 * col, 0.3 * col, 0.01 * col, 1.5e9 * col,
                                         {k: model.coefficient(k) * col
                                          for k in pairs_mod.KINDS})  # fmt: skip
        many_r = reactor_summary(drive_d, reactor_d, inertia, 60.0 * col, np.full(d, 0.02), beta)
        many_f = forces_summary(drive_d, reactor_d, inertia, 60.0 * col, beta, model_d,
                                0.01 * col, 0.0)  # fmt: skip
        for key, value in {**one_r, **one_f}.items():
            got = {**many_r, **many_f}[key]
            assert np.shape(got) == (d,), key
            if not isinstance(value, str):
                np.testing.assert_allclose(got, value, rtol=1e-12, atol=0.0, err_msg=key)
            else:
                assert set(got) == {value}, key
