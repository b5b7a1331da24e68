"""Forces of the non-circular gears: power balance, an independent free-body model, bearings."""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin import drives
from rotorkin.drives.noncircular_gears import forces
from rotorkin.drives.noncircular_gears import kinematics as ng
from rotorkin.io.config import load_config

RNG = np.random.default_rng(7)
DESIGNS = [(2, 2, 0.2), (1, 1, 0.3), (2, 1, 0.1), (3, 3, 0.1)]


@pytest.mark.parametrize(("n", "m", "e"), DESIGNS)
def test_shaft_torque_of_the_mesh_forces_is_the_virtual_work_torque(n, m, e):
    params = ng.NoncircularGears(lobes=n, rotor_lobes=m, eccentricity=e, centre_distance=0.12)
    theta = RNG.uniform(0, 2 * np.pi, 200)
    torque = RNG.normal(0.0, 300.0, (2, 200))
    f = forces.mesh_forces(params, theta, torque, np.radians(20.0))
    dq = ng.motion(params, theta).dq
    # the moment of each tangential force about the shaft = D_i q_i' (power balance, no friction)
    assert np.sum(f["ft"] * f["r1"], axis=0) == pytest.approx(np.sum(torque * dq, axis=0),
                                                              rel=1e-12)  # fmt: skip


@pytest.mark.parametrize(("n", "m", "e"), DESIGNS)
def test_free_body_of_each_gear_solved_as_a_linear_system(n, m, e):
    """Unknowns: the force components (fx, fy) on the driven gear at the pitch point and the
    torque T on the driving gear; equations: the force along the line of action (its direction
    fixed by the pressure angle), moment equilibrium of the driven gear about its axis, and of
    the driving gear about the shaft (the reaction, Newton's third law)."""
    params = ng.NoncircularGears(lobes=n, rotor_lobes=m, eccentricity=e, centre_distance=0.12)
    a0 = np.radians(20.0)
    for _ in range(30):
        t, d = RNG.uniform(0, 2 * np.pi), RNG.normal(0.0, 500.0)
        f = forces.mesh_forces(params, np.array([t]), np.array([[d], [0.0]]), a0)
        r1 = float(ng.pitch_radius(params, "driving", t))
        r2 = 0.12 - r1
        h = 1e-6  # the tangent's inclination from the curve's points, not from the closed form
        x = [np.array(ng.pitch_curve(params, "driving", t + s)) for s in (-h, h)]
        tangent = (x[1] - x[0]) / (2 * h)
        radial = np.array([np.cos(t), np.sin(t)])
        nu = abs(np.arcsin(np.dot(tangent, radial) / np.linalg.norm(tangent)))
        alpha = a0 + nu
        # frame: x along the line of centres (shaft -> rotors' axis), pitch point at (r1, 0)
        direction = np.array([-np.sin(alpha), np.sign(d) * np.cos(alpha)])
        # [fx, fy, T]: fx*dir_y - fy*dir_x = 0; moment about the rotor axis (r2 arm): fy*r2 = d;
        # driving gear: T = fy * r1 (the reaction -f acts at r1 from the shaft)
        mat = np.array([[direction[1], -direction[0], 0.0], [0.0, r2, 0.0], [0.0, -r1, 1.0]])
        fx, fy, torque = np.linalg.solve(mat, [0.0, d, 0.0])
        assert np.hypot(fx, fy) == pytest.approx(f["fn"][0, 0], rel=1e-8)
        assert torque == pytest.approx(f["ft"][0, 0] * f["r1"][0, 0], rel=1e-12)


def test_example_prints_forces_stress_bearings_and_efficiency():
    cfg, _, _ = load_config(example="elliptic-gear-engine")
    r = drives.evaluate(cfg)
    s = r.summary
    for key in ("peak_contact_force_N", "peak_contact_stress_MPa", "contact_safety_factor",
                "peak_bearing_load_N", "friction_loss_W", "mechanical_efficiency"):  # fmt: skip
        assert key in s and key in r.headline and np.isfinite(s[key]), key
    assert 0.5 < s["mechanical_efficiency"] < 1.0
    # the friction loss is the mesh fraction of the power the meshes carry, plus the bearings
    cols = r.columns
    assert "mesh1_force_N" in cols and "shaft_torque_with_friction_Nm" in cols
    # no friction: efficiency 1
    cfg0 = {**cfg, "contact": {**cfg["contact"], "friction_mesh": 0.0, "friction_bearing": 0.0}}
    assert drives.evaluate(cfg0).summary["mechanical_efficiency"] == pytest.approx(1.0)
