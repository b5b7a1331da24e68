"""The guide-bar drive's pair forces, contact stresses and friction in the sweep kernel.

With ideal ports the kernel solves both mechanisms' statics for columns of designs at
once (one input gear ratio, number of vanes and driver per block), then the pairs' Hertz
stresses, bearing loads and friction and the drive's own peaks. Each design is checked
against the study run on its own (``rotorkin.drives.evaluate``, the same 20 001 angles),
and the forces of a column of designs against what must hold whatever the algebra: a
massless drive passes on the power it takes (virtual work), and the forces of a column
are those of each design alone.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.analysis import pairs as ap
from rotorkin.analysis.timing import shaft_speed
from rotorkin.drives.guide_bar import forces as gbf
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar import pump as gb_pump
from rotorkin.io.config import load_config
from rotorkin.machines import vane_pump as vp
from rotorkin.sweep.engine import coverage
from sweep_equality import assert_kernel_is_study
from test_sweep_guide_bar_dynamics import _sample  # designs over drive, pump and loads

#: The pairs' keys and the drive's own, as the study gives them.
FORCES = ap.NUMBER_KEYS + gbf.SUMMARY_KEYS


def _base(sets=()):
    cfg, _, _ = load_config(example="guide-bar-pump", sets=list(sets))
    return cfg


def test_the_forces_are_vectorised_with_ideal_ports():
    cfg = _base()
    fast, slow, why = coverage("guide_bar", cfg, ["drive.lambda", "drive.driver"], list(FORCES))
    assert (sorted(fast), slow, why) == (sorted(FORCES), [], None)
    # a sealing land traps the chambers' fluid: the study evaluates those designs
    land = _base(["machine.vane_angle=50deg", "machine.port_land=4deg"])
    fast, slow, _ = coverage("guide_bar", land, ["drive.lambda"], list(FORCES))
    assert (fast, sorted(slow)) == ([], sorted(FORCES))


@pytest.mark.parametrize("seed", [5, 7])
def test_kernel_equals_the_study_design_by_design(seed):
    p, ok = assert_kernel_is_study(_base(), _sample(12, seed), FORCES)
    assert set(p["drive.driver"][ok]) == {"crank", "guide"}
    assert set(p["drive.input_gear_ratio"][ok]) == {1.0, 2.0}


def _columns(seed: int, driver: str, m: int = 4):
    cfg = _base()
    rng = np.random.default_rng(seed)
    col = lambda lo, hi: rng.uniform(lo, hi, (m, 1))  # noqa: E731
    params = gb.GuideBar(col(0.2, 0.8), col(1.0, 3.0), 1.0, np.radians(col(90.0, 270.0)), driver)
    pump = gb_pump.vane_pump(params, 1, None, col(0.01, 0.03), col(0.06, 0.1), col(0.02, 0.05))
    ports = vp.PortPressures(col(0.5e5, 2e5), col(3e5, 20e5))
    inertia = (col(0.0, 0.01), (col(0.0, 0.01), col(0.0, 0.01)))
    theta = np.linspace(0.0, gb.input_period(1.0), 1441)
    omega = shaft_speed(theta, 150.0, gb.input_period(1.0))
    st = gb_pump.pump_state(params, pump, ports, inertia, 150.0, theta, omega=omega)
    torque = gbf.drive_torques(params, theta, st["M"], inertia[1], st["omega"], st["omega_dot"])
    return cfg, params, theta, torque, gbf.solve(params, gbf.gearing(cfg["drive"]), theta, torque)


@pytest.mark.parametrize("driver", ["crank", "guide"])
def test_a_massless_drive_passes_on_the_power_it_takes(driver):
    # the input gear's torque balances the torques the drive puts on the impellers at
    # their speed ratios (virtual work), a different path from the statics
    _, params, theta, torque, fo = _columns(3, driver)
    assert fo.shaft_torque.shape == (4, theta.size)
    dq = gb.impeller_rates(params, theta)[0]
    delivered = -np.sum(torque * dq, axis=0)
    scale = np.max(np.abs(torque), axis=(0, -1))[:, None]
    assert np.max(np.abs(fo.shaft_torque - delivered) / scale) < 1e-10


@pytest.mark.parametrize("driver", ["crank", "guide"])
def test_a_column_of_designs_is_each_design_alone(driver):
    cfg, params, theta, torque, fo = _columns(9, driver)
    size = gbf.gearing(cfg["drive"])
    together = gbf.own_summary(fo, 150.0)
    for i in range(4):
        one = gb.GuideBar(*(float(np.asarray(v)[i, 0]) if np.ndim(v) else v
                            for v in (params.lam, params.gear_ratio, params.input_gear_ratio,
                                      params.phase)), driver)  # fmt: skip
        alone = gbf.solve(one, size, theta, torque[:, i])
        for name in ("slider", "drive_torque", "crank_bearing", "guide_bearing",
                     "impeller_bearing", "input_bearing", "shaft_torque"):  # fmt: skip
            got = np.take(getattr(fo, name), i, axis=getattr(fo, name).ndim - 2)
            np.testing.assert_array_equal(got, getattr(alone, name), err_msg=name)
        summary = gbf.own_summary(alone, 150.0)
        for key in gbf.SUMMARY_KEYS:
            assert together[key][i] == summary[key], key


def test_load_reversals_skip_the_angles_without_load():
    # a load that is zero between two of its signs does not reverse twice
    sign = np.array([[0, 1, 0, -1, -1, 0, 1, 1], [1, 1, 1, 0, 0, 1, 1, 1]])
    np.testing.assert_array_equal(gbf._sign_changes(sign), [2, 0])
