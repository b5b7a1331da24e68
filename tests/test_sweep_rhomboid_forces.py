"""The rhomboid converter's forces, contact stresses and friction in the sweep kernel.

The kernel of the rotary-blade engine solves the converter's statics (the rhombus's
vertex blocks in equilibrium, the loaded roller pair chosen by the sign of the cam's
push) for columns of designs at once, then the pairs' Hertz stresses, bearing loads
and friction. Each design is checked against the study run on its own
(``rotorkin.drives.evaluate``), under the linear torque model and a Stirling model, and
the solved forces against what must hold whatever the algebra: a massless converter
passes on the power it takes (virtual work), and the forces of a column of designs are
those of each design alone.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.analysis import pairs as ap
from rotorkin.analysis.timing import shaft_speed
from rotorkin.drives.rhomboid_cam import engine
from rotorkin.drives.rhomboid_cam import forces as rf
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.io.config import load_config
from rotorkin.machines import rotary_blade as rb
from rotorkin.sweep.engine import coverage
from sweep_equality import assert_kernel_is_study
from test_sweep_rhomboid_dynamics import _sample  # designs over law, loads, blades, inertias

#: The pairs' keys and the converter's own, as the study gives them.
FORCES = ap.NUMBER_KEYS + rf.SUMMARY_KEYS


def _base(sets=()):
    cfg, _, _ = load_config(example="rhomboid-engine", sets=list(sets))
    return cfg


def test_the_forces_are_vectorised_under_every_pressure_model_with_a_kernel():
    for sets in ((), ("loads.pressure_model=schmidt",), ("loads.pressure_model=adiabatic",)):
        cfg = _base(sets)
        fast, slow, why = coverage("rhomboid_cam", cfg, ["drive.psi_min"], list(FORCES))
        assert (sorted(fast), slow, why) == (sorted(FORCES), [], None), sets


@pytest.mark.parametrize("seed", [5, 6])
def test_kernel_equals_the_study_design_by_design(seed):
    p, ok = assert_kernel_is_study(_base(), _sample(10, seed), FORCES)
    assert set(p["machine.blades_per_pair"][ok]) == {1, 2}  # a single blade loads the hubs


def test_kernel_equals_the_study_under_a_stirling_model():
    table = {k: v[:4] for k, v in _sample(4, 7).items() if not k.startswith("loads.")}
    assert_kernel_is_study(_base(["loads.pressure_model=schmidt"]), table, FORCES)


def _columns(seed: int, m: int = 5):
    rng = np.random.default_rng(seed)
    col = lambda lo, hi: rng.uniform(lo, hi, (m, 1))  # noqa: E731
    params = rc.RhomboidCam(col(0.08, 0.3), np.radians(col(25.0, 60.0)))
    machine = rb.RotaryBlade(np.radians(col(2.0, 8.0)), col(0.01, 0.04), col(0.07, 0.2),
                             col(0.02, 0.08), blades_per_pair=1, inertia_shaft=col(0.0, 0.1),
                             inertia_blade_pair_1=col(0.0, 0.02),
                             inertia_blade_pair_2=col(0.0, 0.02))  # fmt: skip
    loads = engine.Loads("linear", col(50.0, 300.0), col(0.0, 50.0))
    alpha = np.linspace(0.0, np.pi, 721)
    st = engine.machine_state(params, machine, loads, alpha)
    omega = shaft_speed(alpha, 150.0, np.pi)
    return params, machine, alpha, st, engine.drive_torque(machine, st, omega)


def test_a_massless_converter_passes_on_the_power_it_takes():
    # the torque the guides put on the shaft balances the drive torques on the blade
    # pairs at their speed ratios (virtual work), a different path from the statics
    params, _, alpha, st, drive = _columns(11)
    fo = rf.solve(params, alpha, drive)
    assert fo.shaft_torque.shape == (5, alpha.size)
    delivered = -np.sum(drive * st.motion.dq, axis=0)
    scale = np.max(np.abs(drive), axis=(0, -1), keepdims=True)[0]
    assert np.max(np.abs(fo.shaft_torque - delivered) / scale) < 1e-10
    # the cam only pushes, one roller pair at a time
    assert np.all(fo.roller >= 0.0)
    assert np.all((fo.roller[0] == 0.0) | (fo.roller[1] == 0.0))


def test_a_column_of_designs_gives_each_design_its_own_forces():
    params, machine, alpha, st, drive = _columns(12)
    found, fo = rf.machine_pairs(params, machine, alpha, st.members, drive, 0.01, 0.008)
    peaks = rf.force_summary(fo)
    for i in range(5):
        one = rc.RhomboidCam(float(params.link_length[i, 0]), float(params.psi_min[i, 0]))
        mine = rb.RotaryBlade(*(float(getattr(machine, k)[i, 0]) for k in
                                ("blade_thickness", "inner_radius", "outer_radius",
                                 "axial_width")), blades_per_pair=1)  # fmt: skip
        pairs_i, fo_i = rf.machine_pairs(one, mine, alpha, st.members[:, i], drive[:, i], 0.01,
                                         0.008)  # fmt: skip
        for field in fo_i._fields:
            got = np.take(getattr(fo, field), i, axis=getattr(fo, field).ndim - 2)
            np.testing.assert_allclose(got, getattr(fo_i, field), rtol=1e-12, atol=1e-9,
                                       err_msg=field)  # fmt: skip
        for a, b in zip(found, pairs_i, strict=True):
            assert a.name == b.name
            np.testing.assert_allclose(np.broadcast_to(a.force, fo.loaded.shape)[i], b.force,
                                       rtol=1e-12, atol=1e-9)  # fmt: skip
        for key, value in rf.force_summary(fo_i).items():
            assert peaks[key][i] == pytest.approx(float(value), rel=1e-12), key
