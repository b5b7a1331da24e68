"""The wobble-cam sweep kernel's engine dynamics and pair forces (ideal cycle): the study's
numbers design by design, the columns of designs equal to each design alone, the balance
of power through the drive."""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.analysis import engine_cycle as ec
from rotorkin.analysis.timing import shaft_speed
from rotorkin.core.errors import ParameterError
from rotorkin.drives.wobble_cam import cam as cs
from rotorkin.drives.wobble_cam import engine as eng
from rotorkin.drives.wobble_cam import forces as fo
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.drives.wobble_cam import sweep as kernel
from rotorkin.drives.wobble_cam import sweep_forces as swf
from rotorkin.io.config import load_config
from rotorkin.machines import twin_rotor as tr
from rotorkin.sweep.engine import coverage, evaluate_designs
from sweep_equality import assert_kernel_is_study

NAMES = list(swf.DYNAMIC + swf.FORCES)


def _cfg(*sets):
    return load_config(example="wobble-cam-engine", sets=["loads.model=ideal", *sets])[0]


def test_the_keys_are_computed_by_the_kernel_with_the_ideal_cycle_only():
    cfg = _cfg()
    fast, slow, why = coverage("wobble_cam", cfg, ["drive.plate_tilt"], NAMES)
    assert (fast, slow, why) == (NAMES, [], None)
    assert len(NAMES) == 47  # 12 dynamics, 7 peaks in time, 10 of the pairs, 20 of the drive's
    # the fuel-air cycle's pressures come from its integrated tables: the study computes them
    fuel = load_config(example="wobble-cam-engine")[0]
    fast, slow, why = coverage("wobble_cam", fuel, ["drive.plate_tilt"], NAMES)
    assert fast == [] and slow == NAMES and "not vectorized" in why
    # on request only: a default sweep stays the closed forms
    assert not set(NAMES) & set(kernel.metric_names(cfg))


@pytest.mark.parametrize(
    "sets",
    [
        (),
        ("drive.output=both", "machine.section=circular", "machine.clearance_volume=3cm^3",
         'run.speed=["2500 rpm", "3500 rpm", "2800 rpm"]'),
        ("machine.pistons_per_rotor=6", "drive.roller_axis_angle=80deg", "drive.spin_ratio=-1"),
        ("drive.spin_a=[0.04]", "drive.output=cam", "machine.inertia_shaft=0.01kg*m^2"),
    ],
)  # fmt: skip
def test_kernel_equals_the_study_design_by_design(sets):
    cfg = _cfg(*sets)
    rng = np.random.default_rng(len(sets))
    n = 5
    six = "machine.pistons_per_rotor=6" in sets
    table = {
        "drive.plate_tilt": np.radians(rng.uniform(28, 36, n) if six else rng.uniform(38, 52, n)),
        "machine.compression_ratio": rng.uniform(40, 60, n) if six else rng.uniform(9, 16, n),
        "drive.sphere_radius": rng.uniform(0.055, 0.07, n),
        "loads.heat_per_cycle": rng.uniform(300, 1500, n),
        "loads.polytropic_exponent": rng.uniform(1.25, 1.4, n),
    }
    assert_kernel_is_study(cfg, table, NAMES)


def test_a_cam_that_does_not_fit_leaves_the_forces_out_as_the_study_does():
    # a 6 mm sphere cannot hold the default 12 mm shell; without a [cam] section the engine
    # is analysed all the same, its pair forces left out
    cfg = _cfg()
    del cfg["cam"]
    table = {"drive.sphere_radius": np.array([0.006, 0.06])}
    with pytest.raises(ParameterError):
        cs.SphericalCam(0.006)
    p, ok = assert_kernel_is_study(cfg, table, NAMES)
    assert ok.all()
    got = evaluate_designs(p, NAMES, threads=1)["metrics"]
    assert np.isnan(got["groove_roller_force_max_N"][0])
    assert np.isfinite(got["torque_ripple"][0])  # the engine's dynamics stand without the cam
    assert np.isfinite(got["groove_roller_force_max_N"][1])


def _columns(tilts, eps):
    """A drive, machine and cycle of columns of designs (d, 1) and the same designs alone."""
    cfg = _cfg()
    m = {k: cfg["machine"][k] for k in ("section", "inner_radius", "outer_radius", "axial_width",
                                         "mean_radius", "section_diameter", "clearance_volume",
                                         "inertia_shaft", "inertia_rotor_1", "inertia_rotor_2",
                                         "speed_fluctuation")}  # fmt: skip
    col = lambda v: np.asarray(v, dtype=float)[:, None]  # noqa: E731
    drive = wc.WobbleCam(col(tilts), np.pi / 2, -2.0, 0.06, 4)
    machine = tr.TwinRotor(compression_ratio=col(eps), pistons_per_rotor=4,
                           **{k: np.full((len(tilts), 1), v) for k, v in m.items()})  # fmt: skip
    alone = [(wc.WobbleCam(t, np.pi / 2, -2.0, 0.06, 4),
              tr.TwinRotor(compression_ratio=e, pistons_per_rotor=4, **m))
             for t, e in zip(tilts, eps, strict=True)]  # fmt: skip
    return cfg, drive, machine, alone


def test_columns_of_designs_equal_each_design_alone():
    tilts, eps = np.radians([40.0, 45.0, 50.0]), [10.0, 12.0, 14.0]
    cfg, drive, machine, alone = _columns(tilts, eps)
    cycle = ec.IdealCycle()
    theta = np.linspace(0.0, 2.0 * np.pi, 1441)
    omega = shaft_speed(theta, cfg["run"]["speed"], 2.0 * np.pi)
    state = eng.engine_state(drive, machine, cycle, theta)
    assert state.pressure.shape == (8, 3, theta.size)
    dyn = eng.dynamics_summary(machine, state, theta, omega, 300.0)
    _, cam = cs.from_config(cfg)
    fp = fo.force_params(cfg, cam)
    f = fo.solve(drive, cam, fp, theta, state.member_torque, machine.member_inertias, *omega[:2])
    assert f.groove_force.shape == (4, 3, theta.size)
    assert f.plate_bearing.shape == (2, 3, 3, theta.size)
    for i, (d1, m1) in enumerate(alone):
        s1 = eng.engine_state(d1, m1, cycle, theta)
        np.testing.assert_array_equal(state.pressure[:, i], s1.pressure)
        np.testing.assert_array_equal(state.member_torque[:, i], s1.member_torque)
        one = eng.dynamics_summary(m1, s1, theta, omega, 300.0)
        for k in eng.DYNAMICS_KEYS:
            np.testing.assert_allclose(dyn[k][i], one[k], rtol=1e-14, err_msg=k)
        f1 = fo.solve(d1, cam, fp, theta, s1.member_torque, m1.member_inertias, *omega[:2])
        for name in ("groove_force", "rail_force", "groove_radius"):
            np.testing.assert_array_equal(getattr(f, name)[:, i], getattr(f1, name), name)
        for name in ("torque_total", "gearbox_torque", "mesh_force"):
            np.testing.assert_array_equal(getattr(f, name)[i], getattr(f1, name), name)
        np.testing.assert_array_equal(f.plate_bearing[:, :, i], f1.plate_bearing)
        np.testing.assert_array_equal(f.cam_bearing[:, :, i], f1.cam_bearing)


def test_the_drive_passes_the_rotors_power_to_its_outputs():
    # without friction the outputs' power is the rotors' (gas less inertia) less the plate's
    tilts, eps = np.radians([38.0, 47.0]), [9.0, 15.0]
    cfg, drive, machine, _ = _columns(tilts, eps)
    theta = np.linspace(0.0, 2.0 * np.pi, 2001)
    omega = shaft_speed(theta, 400.0, 2.0 * np.pi)
    state = eng.engine_state(drive, machine, ec.IdealCycle(), theta)
    _, cam = cs.from_config(cfg)
    fp = fo.force_params(cfg, cam)
    f = fo.solve(drive, cam, fp, theta, state.member_torque, machine.member_inertias, *omega[:2])
    q, dq, d2q, _ = wc.rotor_angles(drive, theta)
    j = np.stack(machine.member_inertias)
    rotors = np.sum((state.member_torque - j * d2q * omega[0] ** 2) * dq, axis=0)
    np.testing.assert_allclose(f.torque_total, rotors - f.plate_power,
                               rtol=1e-10, atol=1e-9 * np.max(np.abs(rotors)))  # fmt: skip


def test_a_refused_design_in_a_column_is_refused_as_it_would_be_alone():
    col = np.radians([[40.0], [80.0]])
    with pytest.raises(ParameterError) as many:
        wc.WobbleCam(col, np.pi / 2, -2.0, 0.06, 4)
    with pytest.raises(ParameterError) as one:
        wc.WobbleCam(np.radians(80.0), np.pi / 2, -2.0, 0.06, 4)
    assert str(many.value) == str(one.value) and many.value.name == "plate_tilt"
    with pytest.raises(ParameterError) as many:
        tr.TwinRotor(compression_ratio=np.array([[10.0], [0.5]]))
    assert many.value.name == "compression_ratio" and "0.5" in str(many.value)
    with pytest.raises(ParameterError) as many:
        wc.piston_layout(wc.WobbleCam(np.radians([[45.0], [45.0]])), np.array([[10.0], [2.0]]))
    assert many.value.name == "compression_ratio" and str(many.value).startswith(
        "compression_ratio = 2 "
    )


def test_pistons_as_manufactured_keep_their_width_and_set_the_ratio():
    nominal = wc.piston_layout(wc.WobbleCam(np.radians(45.0)), 10.0)
    same = wc.piston_layout(wc.WobbleCam(np.radians(45.0)), 10.0, nominal.piston_width)
    assert same.piston_width == nominal.piston_width
    np.testing.assert_allclose(same.compression_ratio, 10.0, rtol=1e-12)
    # a steeper plate swings the rails further: the same pistons compress more
    tilts = np.radians([[45.0], [47.0]])
    held = wc.piston_layout(wc.WobbleCam(tilts), 10.0, nominal.piston_width)
    np.testing.assert_array_equal(held.piston_width, nominal.piston_width)
    kind = held.design_kind[1, 0].lower()
    lo, hi = (getattr(held, f"chamber_{kind}_{end}")[1, 0] for end in ("min", "max"))
    assert held.compression_ratio[1, 0] == hi / lo > 10.0
