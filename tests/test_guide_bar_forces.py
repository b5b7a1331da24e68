"""Forces in the pairs of the guide-bar + gear drive: power balance, an independent
Newton-Euler model, signs by hand, the study's keys and columns, refusals."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from rotorkin.analysis import pairs as pr
from rotorkin.analysis import torque as tq
from rotorkin.cli import main
from rotorkin.core.errors import ParameterError
from rotorkin.drives import evaluate
from rotorkin.drives.guide_bar import forces as fo
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar import study
from rotorkin.io.config import load_config

RNG = np.random.default_rng(20120904)


def _random_design(rng, driver):
    params = gb.GuideBar(
        lam=rng.uniform(0.05, 0.95),
        gear_ratio=rng.uniform(0.3, 5.0),
        input_gear_ratio=rng.uniform(0.3, 5.0),
        phase=rng.uniform(0.2, 6.0),
        driver=driver,
    )
    size = fo.Gearing(
        crank_length=rng.uniform(0.01, 0.2),
        input_pitch_radius=rng.uniform(0.01, 0.2),
        output_pitch_radius=rng.uniform(0.01, 0.2),
        face_width=rng.uniform(0.005, 0.05),
        pressure_angle=np.radians(rng.uniform(10.0, 35.0)),
    )
    return params, size


# --------------------------------------------------------------------------------------------
# an independent model: Newton-Euler of gear 1 and of crank, block, guide bar and impeller of
# both mechanisms, all pair forces unknown, one linear system per angle and per choice of the
# loaded flank of each mesh (the choice whose tooth forces all push is the answer)
# --------------------------------------------------------------------------------------------
def _cross(r, f):
    return r[0] * f[1] - r[1] * f[0]


def _unit(v):
    return v / np.hypot(v[0], v[1])


def _linkage(params, size, theta):
    """Positions of both mechanisms by plain geometry (no kinematics module)."""
    lam, a = params.lam, size.crank_length
    out = []
    for sigma in (0.0, params.phase):
        x = sigma + theta / params.input_gear_ratio
        C = np.zeros((2, theta.size))
        A = np.array([[lam * a], [0.0]]) * np.ones(theta.size)
        if params.driver == "crank":
            P = A + a * np.array([np.cos(x), np.sin(x)])
            e = _unit(P)
        else:  # the pin where the circle about A meets the guide line through C
            e = np.array([np.cos(x), np.sin(x)])
            s = lam * a * np.cos(x) + np.sqrt(a * a - (lam * a * np.sin(x)) ** 2)
            P = s * e
        drive_pivot, driven_pivot = (A, C) if params.driver == "crank" else (C, A)
        out.append({"A": A, "C": C, "P": P, "n": np.array([-e[1], e[0]]),
                    "drive": drive_pivot, "driven": driven_pivot})  # fmt: skip
    return out


def _line_of_action(axis_b, axis_a, r_b, alpha, flank):
    """Pitch point on gear b and the direction of gear a's push on it (flank +1 or -1)."""
    e = _unit(axis_a - axis_b)
    t = np.array([-e[1], e[0]])
    return axis_b + r_b * e, flank * np.cos(alpha) * t - np.sin(alpha) * e


def _newton_euler(params, size, theta, M, J, qdd, j_shaft, omega_dot, flanks):
    """Pair forces at every angle for one choice of flanks, shape (n, 27)."""
    n = theta.size
    i12, u = params.input_gear_ratio, params.gear_ratio
    r1, r6, alpha = size.input_pitch_radius, size.output_pitch_radius, size.pressure_angle
    r2, r7 = i12 * r1, u * r6
    mech = _linkage(params, size, theta)
    # gear 1: beyond mechanism 1's driving pivot on the frame line (both mechanisms share it)
    m0 = mech[0]
    O1 = m0["drive"] + (r1 + r2) * _unit(m0["drive"] - m0["driven"])
    K = np.zeros((n, 27, 27))
    rhs = np.zeros((n, 27))
    # unknowns: 0-1 F_O1, 2 T1; per mechanism base b = 3 + 12 k: b+0,1 F_A; b+2,3 F_P (block on
    # crank); b+4 N (guide on block along n); b+5 M_s; b+6,7 F_C; b+8 f_in; b+9 f_out;
    # b+10,11 F_O (frame on impeller)
    row = 0
    g1_rows = (0, 1, 2)  # gear 1: forces x, y; moment about O1 in its sense of turning (-z)
    K[:, 0, 0] = K[:, 1, 1] = 1.0
    K[:, 2, 2] = 1.0
    rhs[:, 2] = j_shaft * omega_dot
    row = 3
    for k, m in enumerate(mech):
        b = 3 + 12 * k
        P, nvec = m["P"], m["n"]
        pin_in, d_in = _line_of_action(m["drive"], O1, r2, alpha, flanks[2 * k])
        O = m["driven"] + (r6 + r7) * _unit(m["driven"] - m["drive"])
        pin_out, d_out = _line_of_action(O, m["driven"], r7, alpha, flanks[2 * k + 1])
        # gear 1 gets -f_in d_in
        for i in (0, 1):
            K[:, g1_rows[i], b + 8] = -d_in[i]
        K[:, 2, b + 8] = _cross(pin_in - O1, d_in)  # -(moment about +z of -f d)
        crank_gear = "in" if params.driver == "crank" else "out"
        # crank: F_A + F_P + gear force = 0; moments about A
        cr, gu = row, row + 3
        for i in (0, 1):
            K[:, cr + i, b + i] = 1.0
            K[:, cr + i, b + 2 + i] = 1.0
        K[:, cr + 2, b + 2] = -(P - m["A"])[1]
        K[:, cr + 2, b + 3] = (P - m["A"])[0]
        # block: -F_P + N n = 0; moment M_s = 0
        bl = row + 6
        for i in (0, 1):
            K[:, bl + i, b + 2 + i] = -1.0
            K[:, bl + i, b + 4] = nvec[i]
        K[:, bl + 2, b + 5] = 1.0
        # guide bar: F_C - N n + gear force = 0; moments about C: P x (-N n) - M_s + ...
        for i in (0, 1):
            K[:, gu + i, b + 6 + i] = 1.0
            K[:, gu + i, b + 4] = -nvec[i]
        K[:, gu + 2, b + 4] = -_cross(P - m["C"], nvec)
        K[:, gu + 2, b + 5] = -1.0
        # the gears on crank and guide bar: gear 2 gets +f_in d_in, gear 6 gets -f_out d_out
        for where, col, point, d, sign in (("in", b + 8, pin_in, d_in, 1.0),
                                           ("out", b + 9, pin_out, d_out, -1.0)):  # fmt: skip
            link = cr if where == crank_gear else gu
            pivot = m["A"] if where == crank_gear else m["C"]
            for i in (0, 1):
                K[:, link + i, col] = sign * d[i]
            K[:, link + 2, col] = sign * _cross(point - pivot, d)
        # impeller: F_O + f_out d_out = 0; moment about O (-z is +q): J qdd = M + torque
        im = row + 9
        for i in (0, 1):
            K[:, im + i, b + 10 + i] = 1.0
            K[:, im + i, b + 9] = d_out[i]
        K[:, im + 2, b + 9] = -_cross(pin_out - O, d_out)
        rhs[:, im + 2] = J[k] * qdd[k] - M[k]
        row += 12
    assert row == 27
    return np.linalg.solve(K, rhs[..., None])[..., 0]


def _independent(params, size, theta, M, J, qdd, j_shaft=0.0, omega_dot=0.0):
    """The Newton-Euler solution whose four mesh forces all push (normal forces >= 0)."""
    best = np.full((theta.size, 27), np.nan)
    for flanks in itertools.product((1.0, -1.0), repeat=4):
        x = _newton_euler(params, size, theta, M, J, qdd, j_shaft, omega_dot, flanks)
        ok = np.all(x[:, [11, 12, 23, 24]] >= -1e-9, axis=1)
        best[ok] = x[ok]
    assert np.all(np.isfinite(best))
    return best


@pytest.mark.parametrize("driver", ["crank", "guide"])
@pytest.mark.parametrize("seed", range(4))
def test_forces_equal_an_independent_newton_euler_model(driver, seed):
    rng = np.random.default_rng(seed)
    params, size = _random_design(rng, driver)
    theta = rng.uniform(0.0, 4.0 * np.pi, 40)
    M = rng.normal(0.0, 50.0, (2, theta.size))  # either sign: both flanks of every mesh
    J = rng.uniform(0.0, 0.02, 2)
    qdd = rng.normal(0.0, 3000.0, (2, theta.size))
    j_shaft, omega_dot = 0.003, rng.normal(0.0, 200.0, theta.size)

    F = fo.solve(params, size, theta, J[:, None] * qdd - M)
    x = _independent(params, size, theta, M, J, qdd, j_shaft, omega_dot)
    ca = np.cos(size.pressure_angle)
    scale = np.max(np.abs(x))
    close = dict(rtol=0.0, atol=1e-9 * scale)
    np.testing.assert_allclose(x[:, 0:2].T, F.input_bearing, **close)
    np.testing.assert_allclose(x[:, 2], j_shaft * omega_dot - F.shaft_torque, **close)
    for k in (0, 1):
        b = 3 + 12 * k
        np.testing.assert_allclose(x[:, b : b + 2].T, F.crank_bearing[k], **close)
        np.testing.assert_allclose(x[:, b + 2 : b + 4].T, F.pin_force[k], **close)
        np.testing.assert_allclose(x[:, b + 4], F.slider[k], **close)
        np.testing.assert_allclose(x[:, b + 5], 0.0, **close)  # the block carries no moment
        np.testing.assert_allclose(x[:, b + 6 : b + 8].T, F.guide_bearing[k], **close)
        np.testing.assert_allclose(x[:, b + 8], np.abs(F.input_mesh[k]) / ca, **close)
        np.testing.assert_allclose(x[:, b + 9], np.abs(F.impeller_mesh[k]) / ca, **close)
        np.testing.assert_allclose(x[:, b + 10 : b + 12].T, F.impeller_bearing[k], **close)
    # the pairs carry these magnitudes
    names = {p.slug: p for p in fo.pairs(params, size, F, 0.01)}
    np.testing.assert_allclose(names["slider1_guide"].force, np.abs(x[:, 7]), **close)
    np.testing.assert_allclose(names["guide2_pivot"].force, np.hypot(*x[:, 21:23].T), **close)
    np.testing.assert_allclose(names["input_bearing"].force, np.hypot(*x[:, 0:2].T), **close)


# --------------------------------------------------------------------------------------------
# power balance
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("driver", ["crank", "guide"])
@pytest.mark.parametrize("seed", range(3))
def test_power_balance_at_every_angle(driver, seed):
    """Frictionless: the input meshes' power is the shaft's and equals the power the impeller
    meshes deliver; the block moves the crank pin and the guide bar equally across the guide."""
    rng = np.random.default_rng(100 + seed)
    params, size = _random_design(rng, driver)
    theta = np.linspace(0.0, gb.period(params), 501)
    D = rng.normal(0.0, 80.0, (2, theta.size))
    F = fo.solve(params, size, theta, D)
    dq = gb.impeller_rates(params, theta)[0]
    i12, u = params.input_gear_ratio, params.gear_ratio
    r2, r7 = i12 * size.input_pitch_radius, u * size.output_pitch_radius
    into = F.input_mesh * r2 / i12  # tangential force x pitch-line speed, per unit shaft speed
    out = F.impeller_mesh * r7 * dq
    scale = np.max(np.abs(into))
    np.testing.assert_allclose(into, out, rtol=0.0, atol=1e-12 * scale)
    np.testing.assert_allclose(-into.sum(axis=0), F.shaft_torque, rtol=0.0, atol=1e-12 * scale)
    np.testing.assert_allclose(F.shaft_torque, -(D * dq).sum(axis=0), rtol=1e-9, atol=0.0)
    # slider: power of the block on the crank (N n . v_P, crank) = on the guide bar (N n . v)
    a, lam = size.crank_length, params.lam
    v_crank = a * F.crank_rate * np.cos(F.crank_angle - F.guide_angle)  # across the guide
    v_guide = F.pin_distance * F.guide_rate
    np.testing.assert_allclose(v_crank, v_guide, rtol=1e-12)
    # the block's power into the driven member: -N n on the guide bar, +N n on the crank
    sign = -1.0 if driver == "crank" else 1.0
    np.testing.assert_allclose(sign * F.slider * v_crank, into, rtol=0.0, atol=1e-12 * scale)
    # the block's sliding speed is the pin distance's derivative
    s = a * np.sqrt(1.0 + 2.0 * lam * np.cos(F.crank_angle) + lam * lam)
    np.testing.assert_allclose(F.pin_distance, s, rtol=1e-12)
    pc, rate = F.crank_angle, F.crank_rate
    P = np.stack([lam * a + a * np.cos(pc), a * np.sin(pc)])
    v = a * rate * np.stack([-np.sin(pc), np.cos(pc)])
    ds = np.sum(P * v, axis=0) / s  # the pin's velocity along the guide
    np.testing.assert_allclose(F.pin_slip, ds, rtol=0.0, atol=1e-12 * np.max(np.abs(ds)))


def _cfg(sets=()):
    return load_config(example="guide-bar-pump", sets=list(sets))[0]


@pytest.mark.parametrize(
    "sets",
    [
        (),
        ("drive.driver=guide", "drive.phase=150 deg"),
        ('run.speed=["1200 rpm", "1500 rpm", "1800 rpm", "1500 rpm"]',),
    ],
)
def test_shaft_torque_from_the_meshes_is_the_studys(sets):
    """The meshes' moments about gear 1 give the study's virtual-work torque, inertia of
    the impellers at speed included (the shaft's own inertia is not carried by a pair)."""
    cfg = _cfg(sets)
    params = study.drive_params(cfg)
    pump = study.pump_params(cfg, params)
    res = evaluate(cfg)
    theta = np.radians(res.columns["theta_deg"])
    machine = cfg["machine"]
    inertia = (machine["inertia_shaft"],
               (machine["inertia_impeller_1"], machine["inertia_impeller_2"]))  # fmt: skip
    from rotorkin.machines import vane_pump as vp

    ports = vp.PortPressures(cfg["loads"]["suction_pressure"], cfg["loads"]["discharge_pressure"])
    st = study.pump_state(params, pump, ports, inertia, cfg["run"]["speed"], theta)
    F, pairs = study.pair_forces(cfg, params, st, theta, inertia)
    expected = st["shaft"] - (st["inertia"] - inertia[0] * st["omega_dot"])
    np.testing.assert_allclose(F.shaft_torque, expected, rtol=1e-9, atol=1e-9 * np.max(
        np.abs(expected)))  # fmt: skip
    # the same from the independent members' inertia torque
    dq, d2q, _ = gb.impeller_rates(params, theta)
    members = tq.inertia_torque(0.0, inertia[1], dq, d2q, st["omega"], st["omega_dot"])
    np.testing.assert_allclose(F.shaft_torque, st["shaft"] - members, rtol=1e-9,
                               atol=1e-9 * np.max(np.abs(expected)))  # fmt: skip
    # and the study's columns are these pairs
    for p in pairs:
        np.testing.assert_allclose(res.columns[f"{p.slug}_force_N"], p.force, rtol=1e-12)


# --------------------------------------------------------------------------------------------
# signs and which wall carries the load, by hand
# --------------------------------------------------------------------------------------------
def test_crank_driven_pump_loads_the_leading_wall_and_the_drive_flanks():
    """A constant resisting torque M (D = -M > 0): the crank's block pushes the guide bar
    forward with the slot's leading wall; every mesh loads its drive flank. At x = 0 the pin is
    at (a(1 + lambda), 0): N = -D/(u a (1 + lambda)), and the guide pivot carries the block's
    push and gear 7's reaction, both along +y, plus the mesh's separating force along -x."""
    params = gb.GuideBar(0.4, 2.5, 1.5, np.pi, "crank")
    size = fo.Gearing(0.05, 0.02, 0.03, 0.02, np.radians(20.0))
    theta = np.linspace(0.0, gb.period(params), 721)
    D = np.full((2, theta.size), 30.0)
    F = fo.solve(params, size, theta, D)
    assert np.all(F.slider < 0.0)
    assert np.all(F.input_mesh > 0.0) and np.all(F.impeller_mesh > 0.0)
    a, u = size.crank_length, params.gear_ratio
    s = a * 1.4
    assert F.slider[0, 0] == pytest.approx(-30.0 / (u * s), rel=1e-12)
    r6 = size.output_pitch_radius
    ft = 30.0 / (u * r6)
    np.testing.assert_allclose(F.guide_bearing[0, :, 0],
                               [-ft * np.tan(size.pressure_angle), -(30.0 / (u * s) + ft)],
                               rtol=1e-12)  # fmt: skip
    # the crank: T = D g'/u; at x = 0, g' = 1/(1 + lambda)
    assert F.drive_torque[0, 0] == pytest.approx(30.0 / (u * 1.4), rel=1e-12)
    # mechanism 2 at x = pi: pin at a(lambda - 1) on the -x side, s = a (1 - lambda)
    assert F.pin_distance[1, 0] == pytest.approx(a * 0.6, rel=1e-12)
    assert F.slider[1, 0] == pytest.approx(-30.0 / (u * a * 0.6), rel=1e-12)


def test_guide_driven_pump_loads_the_trailing_wall():
    """Guide-driven, the guide bar pushes the block (and the crank) forward: N > 0; the pin
    force is N = D/(u a W) with W = sqrt(1 - lambda^2 sin^2 y), a W being the crank's arm."""
    params = gb.GuideBar(0.6, 2.0, 2.0, np.pi, "guide")
    size = fo.Gearing()
    theta = np.linspace(0.0, gb.period(params), 361)
    D = np.full((2, theta.size), 12.0)
    F = fo.solve(params, size, theta, D)
    assert np.all(F.slider > 0.0)
    y = gb.driving_angles(params, theta)
    W = np.sqrt(1.0 - (0.6 * np.sin(y)) ** 2)
    np.testing.assert_allclose(F.slider, 12.0 / (2.0 * size.crank_length * W), rtol=1e-12)


def test_an_impeller_that_overruns_its_drive_loads_the_back_flank():
    """No pump torque, only the impellers' inertia: the mesh to gear 7 pulls back (back flank)
    while the impeller decelerates, pushes while it accelerates."""
    params = gb.GuideBar(0.5, 2.0, 2.0, np.pi, "crank")
    theta = np.linspace(0.01, gb.period(params) - 0.01, 400)
    d2q = gb.impeller_rates(params, theta)[1]
    omega = 150.0
    D = fo.drive_torques(params, theta, np.zeros((2, theta.size)), (0.01, 0.01), omega)
    F = fo.solve(params, fo.Gearing(), theta, D)
    moving = np.abs(d2q) > 1e-6
    assert np.array_equal(np.sign(F.impeller_mesh[moving]), np.sign(d2q[moving]))
    assert np.any(F.impeller_mesh < 0.0) and np.any(F.impeller_mesh > 0.0)


def test_mesh_stress_is_the_spur_gear_formula():
    """Hertz at the pitch point: p = sqrt(F_n E* (1/rho_1 + 1/rho_2) / (pi b)),
    rho = r sin(alpha), E* = E / (2 (1 - nu^2)) for two steel gears."""
    params = gb.GuideBar(0.5, 2.0, 2.0, np.pi, "crank")
    size = fo.Gearing(0.04, 0.025, 0.03, 0.02, np.radians(20.0))
    theta = np.linspace(0.0, gb.period(params), 50)
    F = fo.solve(params, size, theta, np.full((2, 50), 40.0))
    mesh = {p.slug: p for p in fo.pairs(params, size, F, 0.01)}["impeller_mesh1"]
    model = pr.ContactModel()
    rho1, rho2 = 0.03 * np.sin(size.pressure_angle), 0.06 * np.sin(size.pressure_angle)
    e_star = 210e9 / (2.0 * (1.0 - 0.09))
    fn = np.abs(F.impeller_mesh[0]) / np.cos(size.pressure_angle)
    expected = np.sqrt(fn * e_star * (1.0 / rho1 + 1.0 / rho2) / (np.pi * 0.02))
    np.testing.assert_allclose(pr.stress(mesh, model), expected, rtol=1e-9)


# --------------------------------------------------------------------------------------------
# the study
# --------------------------------------------------------------------------------------------
def test_the_example_reports_forces_and_efficiency():
    res = evaluate(_cfg())
    s = res.summary
    for key in ("peak_contact_force_N", "peak_contact_stress_MPa", "contact_safety_factor",
                "peak_bearing_load_N", "friction_loss_W", "mechanical_efficiency",
                "peak_slider_force_N", "peak_input_mesh1_tangential_force_N",
                "peak_impeller_mesh2_tangential_force_N", "peak_guide_pivot_load_N"):  # fmt: skip
        assert np.isfinite(s[key]) and s[key] > 0.0, key
    assert s["peak_contact_stress_pair"].startswith(("input mesh", "impeller mesh"))
    assert 0.5 < s["mechanical_efficiency"] < 1.0
    # the pump's work is negative: efficiency = |W| / (|W| + loss)
    w = -s["indicated_work_J"]
    assert s["mechanical_efficiency"] == pytest.approx(w / (w + s["friction_loss_J_per_rev"]))
    # crank-driven: the block drives its guide bar, pressing on the slot's leading wall, while
    # the impeller resists (D > 0); the slower impeller is pushed by the discharge chamber
    # behind it and then holds its guide bar back: the trailing wall, the meshes' back flanks
    c = res.columns
    params = study.drive_params(_cfg())
    D = c["impeller_mesh1_tangential_N"] * params.gear_ratio * 0.03
    assert np.all(np.sign(c["slider1_normal_N"]) == -np.sign(D))
    assert np.all(np.sign(c["input_mesh1_tangential_N"]) == np.sign(D))
    assert np.any(D < 0.0) and np.any(D > 0.0)
    assert "forces.png" not in s  # figures are written on demand
    for k in study.HEADLINE:
        assert k in s, k


def test_forces_figure_is_written(tmp_path):
    paths = evaluate(_cfg()).write_figures(tmp_path)
    fig = tmp_path / "forces.png"
    assert fig in paths and fig.stat().st_size > 10_000


def test_friction_free_contact_loses_nothing():
    sets = [f"contact.friction_{k}=0" for k in ("rolling", "sliding", "mesh", "bearing")]
    s = evaluate(_cfg(sets)).summary
    assert s["friction_loss_W"] == 0.0 and s["mechanical_efficiency"] == 1.0


# --------------------------------------------------------------------------------------------
# refusals
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("setting", "key"),
    [
        ("drive.pressure_angle=40 deg", "drive.pressure_angle"),
        ("drive.pressure_angle=5 deg", "drive.pressure_angle"),
        ("drive.crank_length=0 mm", "drive.crank_length"),
        ("drive.input_pitch_radius=2 m", "drive.input_pitch_radius"),
        ("drive.output_pitch_radius=-3 mm", "drive.output_pitch_radius"),
        ("drive.face_width=0.5 mm", "drive.face_width"),
    ],
)
def test_bad_drive_sizes_exit_2_with_one_line(setting, key, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["run", "-e", "guide-bar-pump", "--set", setting, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and key in err[0] and "Traceback" not in err[0]
    assert not out.exists()


@pytest.mark.parametrize(
    ("field", "value"),
    [("pressure_angle", np.radians(36.0)), ("crank_length", np.nan), ("face_width", 0.0)],
)
def test_gearing_refuses_by_name(field, value):
    with pytest.raises(ParameterError, match=f"drive.{field}"):
        fo.gearing({field: value})
    with pytest.raises(ParameterError, match=field):
        fo.Gearing(**{field: value})


def test_load_reversals_are_counted():
    params = gb.GuideBar(0.5, 2.0, 2.0, np.pi, "crank")
    theta = np.linspace(0.0, gb.period(params), 9)
    D = np.array([[1.0, 2.0, 0.0, -1.0, -2.0, 3.0, 0.0, 1.0, 1.0], np.ones(9)])
    F = fo.solve(params, fo.Gearing(), theta, D)
    assert fo.own_summary(F, 100.0)["load_reversals_per_period"] == 2
    F = fo.solve(params, fo.Gearing(), theta, np.ones((2, 9)))
    assert fo.own_summary(F, 100.0)["load_reversals_per_period"] == 0


def test_gearing_defaults_are_the_schemas():
    from rotorkin.drives.guide_bar.schema import GuideBarDrive

    drive = GuideBarDrive.model_validate({"type": "guide_bar", "lambda": 0.5, "gear_ratio": 2})
    assert fo.gearing(drive.model_dump()) == fo.Gearing()
