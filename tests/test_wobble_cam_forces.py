"""Kinetostatics of the wobble-cam drive: power balance, an independent Newton-Euler model,
the torque split between the Z-shaft and the cam shell, walls and signs, refusals."""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.analysis import pairs as pr
from rotorkin.cli import main
from rotorkin.drives.wobble_cam import cam as cs
from rotorkin.drives.wobble_cam import forces as fo
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.drives.wobble_cam import study

D = np.pi / 180.0


def _random_case(seed, output="both", inertia=True):
    rng = np.random.default_rng(seed)
    alpha = rng.uniform(75, 105) * D
    tilt = rng.uniform(15.0, 0.9 * np.degrees(wc.max_plate_tilt(alpha, 4))) * D
    n = float(rng.choice([-2.0, -1.5, -1.0, 1.0, 2.0, -3.0]))
    spin_a = tuple(rng.uniform(-0.02, 0.02, 2)) if seed % 2 else ()
    r = rng.uniform(0.04, 0.1)
    drive = wc.WobbleCam(tilt, alpha, n, r, spin_a=spin_a)
    scam = cs.SphericalCam(r, 0.003, 0.012, 0.008)
    fp = fo.ForceParams(
        output=output,
        cam_torque_share=rng.uniform(0, 1),
        bevel_ratio=rng.uniform(1, 4),
        bevel_pitch_radius=rng.uniform(0.02, 0.08),
        bevel_pressure_angle=rng.uniform(14, 25) * D,
        rail_radius=r + rng.uniform(0.02, 0.05),
        plate_bearing_span=rng.uniform(0.02, 0.06),
        cam_bearing_span=rng.uniform(0.05, 0.2),
        plate_inertia_axial=rng.uniform(0.001, 0.005) if inertia else 0.0,
        plate_inertia_transverse=rng.uniform(0.0005, 0.003) if inertia else 0.0,
    )
    theta = rng.uniform(0, 2 * np.pi, 13)
    moments = rng.normal(0, 200, (2, theta.size))
    jr = rng.uniform(0.001, 0.02, 2)
    omega = rng.uniform(50, 400, theta.size)
    omega_dot = rng.normal(0, 500, theta.size)
    return drive, scam, fp, theta, moments, jr, omega, omega_dot


def _need(drive, theta, moments, jr, omega, omega_dot):
    _, dq, d2q, _ = wc.rotor_angles(drive, theta)
    return jr[:, None] * (d2q * omega**2 + dq * omega_dot) - moments, dq


# --------------------------------------------------------------------------------------------
# power balance
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("seed", range(8))
def test_power_balance_at_every_angle(seed):
    """Outputs' power = rotors' power less the plate's inertia power, at every angle."""
    drive, scam, fp, theta, m, jr, w, wd = _random_case(seed)
    f = fo.solve(drive, scam, fp, theta, m, jr, w, wd)
    need, dq = _need(drive, theta, m, jr, w, wd)
    expected = -np.sum(need * dq, axis=0) - f.plate_power
    scale = np.max(np.abs(need))
    np.testing.assert_allclose(f.torque_total, expected, rtol=0, atol=1e-9 * scale)
    # the outputs together deliver the total, each output turning at the shaft speed
    np.testing.assert_allclose(
        f.output_shaft + f.output_cam, f.torque_total, rtol=0, atol=1e-9 * scale
    )
    # rails: force x velocity of the rollers on the rotors is the rotors' demand
    group = [0, 0, 1, 1]
    e = wc.roller_positions(drive, theta) / drive.sphere_radius
    rho = fp.rail_radius * np.hypot(e[:, 1], e[:, 2])
    np.testing.assert_allclose(
        np.sum(f.rail_force * rho * dq[group], axis=0),
        np.sum(need * dq, axis=0),
        rtol=0,
        atol=1e-9 * scale,
    )
    # the gearbox is lossless: what it takes from one output it gives to the other
    np.testing.assert_allclose(f.output_cam - f.torque_cam_grooves, f.gearbox_torque)
    np.testing.assert_allclose(
        f.output_shaft - f.torque_shaft_plate, -f.gearbox_torque, atol=1e-9 * scale
    )


@pytest.mark.parametrize("seed", range(4))
def test_plate_inertia_power_is_the_rate_of_its_kinetic_energy(seed):
    """P_plate = dKE/dt, KE = 1/2 omega^2 (J_a (cos phi + varphi')^2 + J_t sin^2 phi)."""
    drive, scam, fp, theta, m, jr, w, wd = _random_case(2 * seed + 1)  # corrected spin law
    f = fo.solve(drive, scam, fp, theta, m, jr, w, wd)
    _, v1, v2, _ = wc.spin_law(drive, theta)
    c, s = np.cos(drive.plate_tilt), np.sin(drive.plate_tilt)
    ja, jt = fp.plate_inertia_axial, fp.plate_inertia_transverse
    j_eq = ja * (c + v1) ** 2 + jt * s**2
    power = w * wd * j_eq + w**3 * ja * (c + v1) * v2
    np.testing.assert_allclose(f.plate_power * w, power, rtol=1e-9, atol=1e-9 * np.max(power))


def test_without_friction_the_efficiency_is_one_and_friction_loses_work():
    cfg = _cfg()
    cfg["contact"] = {k: 0.0 for k in ("friction_rolling", "friction_sliding")}
    cfg["contact"].update(friction_mesh=0.0, friction_bearing=0.0)
    s = study.evaluate(cfg).summary
    assert s["mechanical_efficiency"] == pytest.approx(1.0, abs=1e-12)
    assert s["friction_loss_W"] == 0.0
    s = study.evaluate(_cfg()).summary
    assert 0.0 < s["mechanical_efficiency"] < 1.0


# --------------------------------------------------------------------------------------------
# independent Newton-Euler model
# --------------------------------------------------------------------------------------------
def _a(x):
    c, s = np.cos(x), np.sin(x)
    return np.array([[1, 0, 0], [0, c, s], [0, -s, c]])


def _da(x):
    c, s = np.cos(x), np.sin(x)
    return np.array([[0, 0, 0], [0, -s, c], [0, -c, -s]])


def _dda(x):
    c, s = np.cos(x), np.sin(x)
    return np.array([[0, 0, 0], [0, -c, -s], [0, s, -c]])


def _unskew(m):
    return np.array([m[2, 1], m[0, 2], m[1, 0]])


def _newton_euler(drive, fp, th, moments, jr, w, wd):
    """Unknowns: N(4), F(4), f_b(3), m_b(3), spin and rotor compliance (3), G_s, G_c, T_s, T_c.

    Equations: plate (6) and m_b . x2 = 0, rotors (2), Z-shaft (1), cam (1), lossless gearbox
    (1), output split (1), equal-stiffness compatibility of the 8 contacts (8).
    """
    ph, r, big_r = drive.plate_tilt, drive.sphere_radius, fp.rail_radius
    v, v1, v2, _ = (float(x) for x in wc.spin_law(drive, th))
    a_ph = np.array([[np.cos(ph), 0, np.sin(ph)], [0, 1, 0], [-np.sin(ph), 0, np.cos(ph)]])
    rot = _a(th) @ a_ph @ _a(v)
    d1 = _da(th) @ a_ph @ _a(v) + _a(th) @ a_ph @ _da(v) * v1
    d2 = (
        _dda(th) @ a_ph @ _a(v)
        + 2 * _da(th) @ a_ph @ _da(v) * v1
        + _a(th) @ a_ph @ (_dda(v) * v1**2 + _da(v) * v2)
    )
    rdot, rddot = w * d1, w**2 * d2 + wd * d1
    omega = _unskew(rdot @ rot.T)
    alpha = _unskew(rddot @ rot.T + rdot @ rdot.T)
    inertia = rot @ np.diag([fp.plate_inertia_axial, *[fp.plate_inertia_transverse] * 2]) @ rot.T
    dh = inertia @ alpha + np.cross(omega, inertia @ omega)
    x2 = rot @ np.array([1.0, 0, 0])
    xh, axis = np.array([1.0, 0, 0]), np.array([-1.0, 0, 0])
    q, dq, d2q, _ = (np.asarray(x)[:, 0] for x in wc.rotor_angles(drive, np.array([th])))
    need = jr * (d2q * w**2 + dq * wd) - moments
    cam_w = w * xh  # the cam turns about +x at the shaft speed
    e, n, ephi = [], [], []
    for c in wc.roller_offsets(drive.roller_axis_angle):
        b = np.array([0.0, np.sin(c), np.cos(c)])
        ej = rot @ b
        vrel = w * r * (d1 @ b) - np.cross(cam_w, r * ej)
        t = vrel / np.linalg.norm(vrel)
        e.append(ej)
        n.append(np.cross(ej, t))
        erho = np.array([0.0, ej[1], ej[2]]) / np.hypot(ej[1], ej[2])
        ephi.append(np.cross(axis, erho))
    a = np.zeros((21, 21))
    b = np.zeros(21)
    iN, iF, ifb, imb, idl, ieps, igs, igc, its, itc = 0, 4, 8, 11, 14, 15, 17, 18, 19, 20
    for j in range(4):
        a[0:3, iN + j] = n[j]
        a[0:3, iF + j] = -ephi[j]
        a[3:6, iN + j] = np.cross(r * e[j], n[j])
        a[3:6, iF + j] = -np.cross(big_r * e[j], ephi[j])
    a[0:3, ifb : ifb + 3] = np.eye(3)
    a[3:6, imb : imb + 3] = np.eye(3)
    b[3:6] = dh
    a[6, imb : imb + 3] = x2
    for j in range(4):  # rotors: moment about the axis of the rollers' forces on the rails
        a[7 + j // 2, iF + j] = np.cross(big_r * e[j], ephi[j]) @ axis
    b[7:9] = need
    a[9, imb : imb + 3] = xh  # Z-shaft: -m_b about -x, the gearbox, the load
    a[9, igs], a[9, its] = 1.0, -1.0
    for j in range(4):  # cam shell about +x
        a[10, iN + j] = -np.cross(r * e[j], n[j]) @ xh
    a[10, igc], a[10, itc] = 1.0, -1.0
    a[11, igs], a[11, igc] = 1.0, 1.0
    share = fp.share
    a[12, itc], a[12, its] = 1.0 - share, -share
    for j in range(4):
        a[13 + j, iN + j] = 1.0
        a[13 + j, idl] = -np.cross(r * e[j], n[j]) @ x2
        a[17 + j, iF + j] = 1.0
        a[17 + j, ieps + j // 2] = -np.cross(big_r * e[j], ephi[j]) @ axis
    x = np.linalg.solve(a, b)
    return {
        "N": x[iN : iN + 4],
        "F": x[iF : iF + 4],
        "f_b": x[ifb : ifb + 3],
        "m_b": x[imb : imb + 3],
        "T_s": x[its],
        "T_c": x[itc],
        "G_c": x[igc],
    }


@pytest.mark.parametrize("output", fo.OUTPUTS)
@pytest.mark.parametrize("seed", range(6))
def test_production_forces_match_a_newton_euler_model(seed, output):
    drive, scam, fp, theta, m, jr, w, wd = _random_case(seed, output)
    f = fo.solve(drive, scam, fp, theta, m, jr, w, wd)
    for k, th in enumerate(theta):
        ref = _newton_euler(drive, fp, th, m[:, k], jr, w[k], wd[k])
        scale = max(np.max(np.abs(ref["N"])), np.max(np.abs(ref["F"])), 1.0)
        tol = dict(rtol=0, atol=1e-9 * scale)
        np.testing.assert_allclose(f.groove_force[:, k], ref["N"], **tol)
        np.testing.assert_allclose(f.rail_force[:, k], ref["F"], **tol)
        np.testing.assert_allclose(f.plate_bearing_force[:, k], ref["f_b"], **tol)
        tol_m = dict(rtol=0, atol=1e-9 * scale * drive.sphere_radius)
        np.testing.assert_allclose(f.plate_bearing_moment[:, k], ref["m_b"], **tol_m)
        np.testing.assert_allclose(f.output_shaft[k], ref["T_s"], **tol_m)
        np.testing.assert_allclose(f.output_cam[k], ref["T_c"], **tol_m)
        np.testing.assert_allclose(f.gearbox_torque[k], ref["G_c"], **tol_m)
        mesh = abs(ref["G_c"]) / (2 * fp.bevel_pitch_radius * np.cos(fp.bevel_pressure_angle))
        np.testing.assert_allclose(f.mesh_force[k], mesh, rtol=1e-9, atol=1e-9 * scale)


@pytest.mark.parametrize("seed", range(6))
def test_cam_shell_torque_is_that_of_the_differential(seed):
    """The plate is a differential: T_C = -sum D_k (Phi_k' - 1)/2 whatever the groove sharing."""
    drive, scam, fp, theta, m, jr, w, wd = _random_case(seed, inertia=False)
    need, dq = _need(drive, theta, m, jr, w, wd)
    expected = -0.5 * np.sum(need * (dq - 1.0), axis=0)
    for guided in (None, cs.guided(drive, scam, theta)):
        f = fo.solve(drive, scam, fp, theta, m, jr, w, wd, guided=guided)
        ok = ~f.unguided
        scale = np.max(np.abs(need))
        np.testing.assert_allclose(f.torque_cam_grooves, expected, rtol=0, atol=1e-9 * scale)
        np.testing.assert_allclose(
            f.torque_shaft_plate, -0.5 * np.sum(need * (dq + 1.0), axis=0), atol=1e-9 * scale
        )
        assert np.all(f.groove_force[~f.guided & ok[None]] == 0.0)


# --------------------------------------------------------------------------------------------
# split between the outputs
# --------------------------------------------------------------------------------------------
def _cfg(**drive):
    d = {"type": "wobble_cam", "plate_tilt": 45 * D, "roller_axis_angle": 90 * D}
    d.update(spin_ratio=-2.0, sphere_radius=0.06)
    d.update(drive)
    return {
        "drive": d,
        "machine": {"compression_ratio": 10.0},
        "loads": {"heat_per_cycle": 90.0},
        "run": {"points": 361, "speed": 2000 * np.pi / 30},
    }


def test_cam_shell_share_zero_when_only_the_shaft_is_loaded_and_split_sums():
    res = study.evaluate(_cfg(output="shaft"))
    s, c = res.summary, res.columns
    assert s["cam_shell_torque_share"] == 0.0 and s["cam_shell_torque_mean_Nm"] == 0.0
    assert np.all(c["cam_output_torque_Nm"] == 0.0)
    np.testing.assert_allclose(c["shaft_output_torque_Nm"] + c["cam_output_torque_Nm"],
                               c["plate_torque_on_shaft_Nm"] + c["groove_torque_on_cam_Nm"],
                               atol=1e-9)  # fmt: skip
    # the gearbox then carries all of the grooves' torque on the cam shell
    np.testing.assert_allclose(c["gearbox_torque_Nm"], -c["groove_torque_on_cam_Nm"], atol=1e-9)
    res = study.evaluate(_cfg(output="cam"))
    assert res.summary["cam_shell_torque_share"] == pytest.approx(1.0, abs=1e-12)
    assert np.all(res.columns["shaft_output_torque_Nm"] == 0.0)
    res = study.evaluate(_cfg(output="both", cam_torque_share=0.3))
    s, c = res.summary, res.columns
    assert s["cam_shell_torque_share"] == pytest.approx(0.3, abs=1e-12)
    assert s["shaft_output_torque_mean_Nm"] + s["cam_shell_torque_mean_Nm"] == pytest.approx(
        s["output_torque_mean_Nm"], rel=1e-12
    )
    # at a constant speed the outputs deliver the indicated work (inertia does no net work)
    assert s["output_torque_mean_Nm"] * 2 * np.pi == pytest.approx(s["indicated_work_J"], rel=1e-4)


def test_equal_split_leaves_the_gas_torque_out_of_the_gearbox():
    """Gas torques on the rotors are equal and opposite: the grooves hand the cam shell half
    of the total, and with a 50/50 output split and no rotor inertia the gearbox idles."""
    cfg = _cfg(output="both", cam_torque_share=0.5)
    cfg["machine"].update(inertia_rotor_1=0.0, inertia_rotor_2=0.0)
    res = study.evaluate(cfg)
    s, c = res.summary, res.columns
    assert s["cam_shell_natural_torque_share"] == pytest.approx(0.5, abs=1e-9)
    scale = np.max(np.abs(c["shaft_output_torque_Nm"]))
    assert np.max(np.abs(c["gearbox_torque_Nm"])) < 1e-9 * scale
    assert s["bevel_mesh_force_max_N"] < 1e-9 * scale


# --------------------------------------------------------------------------------------------
# signs and walls
# --------------------------------------------------------------------------------------------
def test_gas_pushing_a_rotor_forward_is_met_by_its_rail_and_the_loaded_wall():
    """Rotor 1 pushed forward by the gas (M_1 > 0, no inertia): each of its rollers puts a
    negative F on its rail (the rail drives the roller forward along +e_Phi); the groove
    force points from the loaded wall (cam.groove_walls) to the roller centre."""
    drive = wc.WobbleCam(45 * D)
    scam = cs.SphericalCam(0.06)
    fp = fo.ForceParams(plate_inertia_axial=0.0, plate_inertia_transverse=0.0)
    theta = np.linspace(0.0, 2 * np.pi, 97)
    m = np.stack([np.full_like(theta, 100.0), np.zeros_like(theta)])
    f = fo.solve(drive, scam, fp, theta, m)
    assert np.all(f.rail_force[:2] < 0) and np.all(f.rail_force[2:] == 0)
    walls = cs.groove_walls(drive, scam, theta)  # (4, 2, 3, n), wall 0 at +n
    g = cs.groove_derivatives(drive, theta)[0]
    _, _, n = cs.groove_frame(drive, theta)
    loaded = np.where(f.groove_force > 0, 1, 0)  # N > 0: the -n wall (index 1)
    for j in range(4):
        w = np.take_along_axis(walls[j], loaded[j][None, None, :], axis=0)[0]
        push = f.groove_force[j] * np.sum(n[j] * (g[j] - w), axis=0)
        assert np.all(push[np.abs(f.groove_force[j]) > 1e-9] > 0)
    # motion.csv names that wall (+1 the +n wall, -1 the -n wall), and none where the force
    # is a zero's rounding (it passes through zero at two of these angles, ~1e-13 N)
    cols = fo.columns(f)[0]
    for j, slug in enumerate(("1", "1p", "2", "2p")):
        rounding = np.abs(f.groove_force[j]) < 1e-9 * np.max(np.abs(f.groove_force[j]))
        expected = np.where(rounding, 0.0, np.where(loaded[j] == 1, -1.0, 1.0))
        np.testing.assert_array_equal(cols[f"groove{slug}_loaded_wall"], expected)
    assert np.any(np.abs(f.groove_force[0]) < 1e-9)
    # opposite rollers: equal and opposite groove forces, equal rail forces
    np.testing.assert_allclose(f.groove_force[1], -f.groove_force[0], atol=1e-9)
    np.testing.assert_allclose(f.rail_force[1], f.rail_force[0])
    # a couple only: no net force on the plate bearings
    assert np.max(np.abs(f.plate_bearing_force)) < 1e-9 * np.max(np.abs(f.groove_force))
    # the shaft delivers M_1 Phi_1' when it alone is loaded
    dq = wc.rotor_angles(drive, theta)[1]
    np.testing.assert_allclose(f.output_shaft, 100.0 * dq[0], atol=1e-9)


def test_the_wall_radius_is_convex_inside_the_bend():
    """The loaded wall inside the centre-line's bend is convex (1/kappa - rho), outside concave."""
    drive = wc.WobbleCam(45 * D)
    scam = cs.SphericalCam(0.06, 0.004)
    theta = np.linspace(0.01, 2 * np.pi, 101)
    f = fo.solve(drive, scam, fo.ForceParams(), theta, np.ones((2, theta.size)) * [[50.0], [-30]])
    kappa = cs.geodesic_curvature(drive, theta)
    side = -np.sign(f.groove_force)  # +1: the +n wall, towards which kappa > 0 bends
    inside = side * kappa > 0
    rad = np.abs(1.0 / kappa)
    np.testing.assert_allclose(f.groove_radius[inside], (rad - 0.004)[inside], rtol=1e-9)
    out = (side * kappa < 0) & np.isfinite(rad)
    np.testing.assert_allclose(f.groove_radius[out], -(rad + 0.004)[out], rtol=1e-9)


def test_rail_roller_stays_in_its_rotor_plane():
    """The outer roller's velocity relative to its rotor has no e_Phi part (pure rolling)."""
    drive, *_ = _random_case(3)
    theta = np.linspace(0, 2 * np.pi, 50)
    h = 1e-6
    e = wc.roller_positions(drive, theta) / drive.sphere_radius
    de = (wc.roller_positions(drive, theta + h) - wc.roller_positions(drive, theta - h)) / (
        2 * h * drive.sphere_radius
    )
    dq = wc.rotor_angles(drive, theta)[1][[0, 0, 1, 1]]
    x_cross_e = np.stack([0 * e[:, 0], -e[:, 2], e[:, 1]], axis=1)
    rel = de + dq[:, None] * x_cross_e
    ephi = np.stack([0 * e[:, 0], e[:, 2], -e[:, 1]], axis=1) / np.hypot(e[:, 1], e[:, 2])[:, None]
    assert np.max(np.abs(np.sum(rel * ephi, axis=1))) < 1e-7


# --------------------------------------------------------------------------------------------
# study, summary keys, refusals
# --------------------------------------------------------------------------------------------
def test_study_keys_columns_and_pairs():
    res = study.evaluate(_cfg())
    s, c = res.summary, res.columns
    for k in ("cam_shell_torque_share", "groove_roller_force_max_N",
              "groove_contact_stress_max_MPa", "plate_bearing_load_max_N",
              "bevel_mesh_force_max_N", "peak_contact_stress_MPa", "contact_safety_factor",
              "peak_bearing_load_N", "mechanical_efficiency", "friction_loss_W"):  # fmt: skip
        assert k in s and np.isfinite(s[k]), k
    assert all(np.shape(v) == (361,) for v in c.values())
    assert set(res.column_docs) == set(c)
    for slug in ("groove1", "groove1p", "groove2", "groove2p", "rail1", "rail2p"):
        assert f"{slug}_force_N" in c and f"{slug}_contact_stress_MPa" in c
    assert s["peak_bearing_load_N"] >= s["plate_bearing_load_max_N"]
    assert s["groove_roller_force_max_N"] == pytest.approx(np.max(c["groove1_force_N"]), rel=0.05)


def test_defaults_are_the_schema_defaults():
    from rotorkin.drives.wobble_cam.schema import WobbleConfig

    cfg = WobbleConfig.model_validate({"drive": {"type": "wobble_cam", "plate_tilt": "40 deg"}})
    d = cfg.model_dump()["drive"]
    ours = fo.ForceParams()
    for name in fo.ForceParams.__dataclass_fields__:
        if name == "bearing_radius":
            continue
        theirs = d[name]
        mine = getattr(ours, name)
        assert mine == theirs if isinstance(mine, str) else mine == pytest.approx(theirs)


@pytest.mark.parametrize(
    ("setting", "key"),
    [
        ("drive.output=middle", "drive.output"),
        ("drive.cam_torque_share=1.5", "drive.cam_torque_share"),
        ("drive.bevel_ratio=0.5", "drive.bevel_ratio"),
        ("drive.bevel_pressure_angle=50 deg", "drive.bevel_pressure_angle"),
        ("drive.rail_radius=60 mm", "drive.rail_radius"),
        ("drive.plate_bearing_span=0 mm", "drive.plate_bearing_span"),
    ],
)
def test_bad_force_inputs_are_refused_in_one_line(setting, key, tmp_path, capsys):
    out = tmp_path / "out"
    code = main(["run", "-e", "wobble-cam-engine", "-q", "--set", setting, "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 2, err
    assert err.count("\n") == 1 and key in err, err
    assert not out.exists()


def test_pair_kinds_and_stress_geometry():
    drive = wc.WobbleCam(45 * D)
    scam = cs.SphericalCam(0.06, 0.004, 0.012, 0.007)
    fp = fo.ForceParams()
    theta = np.linspace(0, 2 * np.pi, 31)
    f = fo.solve(drive, scam, fp, theta, np.full((2, 31), 80.0))
    plist = fo.pairs(f, scam, fp, pr.ContactModel(roller_width=0.010))
    kinds = {p.slug: p.kind for p in plist}
    assert kinds["groove1"] == "rolling" and kinds["bevel_mesh_cam"] == "mesh"
    assert kinds["plate_bearing_a"] == "bearing"
    groove = next(p for p in plist if p.slug == "groove1")
    assert groove.geometry[3] == 0.007  # the wall is only the groove's depth deep
