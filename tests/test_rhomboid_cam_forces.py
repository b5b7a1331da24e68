"""Forces in the rhomboid lever-cam converter, against models written here.

* power: the torque the guides give the shaft equals the virtual-work torque with the
  blade pairs' inertia, at every angle (production and through the study's columns);
* an independent Newton-Euler model: every body of the linkage (four links, four vertex
  blocks, two blade arms, the shaft) with its own unknown pair forces, in the fixed
  frame, no symmetry built in, closed by the model's stated assumptions as equations,
  solved as one 39 x 39 system per angle;
* signs and which surface carries the load on cases worked by hand;
* refusals: the linear torque model outside psi_min ... psi_max, a roller of radius 0.
"""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest

from rotorkin.analysis import pairs as ap
from rotorkin.cli import main
from rotorkin.core.batch import Designs
from rotorkin.core.errors import ParameterError
from rotorkin.drives import evaluate as drive_evaluate
from rotorkin.drives.rhomboid_cam import cam
from rotorkin.drives.rhomboid_cam import forces as rf
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.drives.rhomboid_cam import sweep as batch
from rotorkin.drives.rhomboid_cam.study import drive_params, evaluate
from rotorkin.io.config import load_config
from rotorkin.sweep.engine import evaluate_designs, reason_keys

RNG = np.random.default_rng(20240611)


def _cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def _random_design(rng):
    while True:
        a = tuple(rng.uniform(-0.12, 0.12, rng.integers(0, 3)))
        b = tuple(rng.uniform(-0.04, 0.04, rng.integers(0, 2)))
        psi_min = np.radians(rng.uniform(25.0, 80.0))
        try:
            p = rc.RhomboidCam(rng.uniform(0.03, 0.4), psi_min, a, b)
        except ParameterError:
            continue
        return p


# --- the independent model ------------------------------------------------------------------
def newton_euler(params, alpha, d1, d2, loaded):
    """All pair forces at one angle from the equilibrium of every body (fixed frame).

    Unknowns (39): pin force on link j at its ends (16), arm force on link j (8), cam
    normal forces N_k (4), guide forces G_k (4), blade pivot reactions (4), shaft torque
    and bearing reaction (3). Equations: links (12), vertex blocks (8), blade arms (6),
    shaft (3), and the model's closure: arm forces normal to the arms (4), guide forces
    proportional to the radii (3), the unloaded roller pair free (2), the loaded pair
    equal (1). ``loaded`` = 0: A, C carry; 1: B, D.
    """
    L = params.link_length
    law = (params.psi_min, params.a, params.b)
    V = rc.rhombus_vertices(L, *law, alpha)  # (4, 2)
    M = 0.5 * (V + np.roll(V, -1, axis=0))  # midpoints of AB, BC, CD, DA
    ak = alpha + 0.5 * np.pi * np.arange(4)
    dp = cam.pitch_curve(L, *law, ak)[1]  # (2, 4)
    normal = np.stack([dp[1], -dp[0]]) / np.hypot(dp[0], dp[1])  # tangent turned by -90 deg
    radial = V / np.linalg.norm(V, axis=1, keepdims=True)
    tang = np.stack([-radial[:, 1], radial[:, 0]], axis=1)
    rho = np.linalg.norm(V, axis=1)
    n_unk = 39
    iF = lambda j, e: 4 * j + 2 * e  # noqa: E731
    iP = lambda j: 16 + 2 * j  # noqa: E731
    iN = lambda k: 24 + k  # noqa: E731
    iG = lambda k: 28 + k  # noqa: E731
    iR = lambda i: 32 + 2 * i  # noqa: E731
    iT, iS = 36, 37
    rows, rhs = [], []

    def eq(coeffs, value=0.0):
        row = np.zeros(n_unk)
        for idx, c in coeffs:
            row[idx] += c
        rows.append(row)
        rhs.append(value)

    links = [(0, 1), (1, 2), (2, 3), (3, 0)]
    for j, (v1, v2) in enumerate(links):
        for ax in (0, 1):  # forces
            eq([(iF(j, 0) + ax, 1), (iF(j, 1) + ax, 1), (iP(j) + ax, 1)])
        eq([(iF(j, 0), -V[v1][1]), (iF(j, 0) + 1, V[v1][0]),  # moment about O
            (iF(j, 1), -V[v2][1]), (iF(j, 1) + 1, V[v2][0]),
            (iP(j), -M[j][1]), (iP(j) + 1, M[j][0])])  # fmt: skip
    for k in range(4):  # vertex block k: links meeting there push back
        ends = [(j, e) for j, lk in enumerate(links) for e in (0, 1) if lk[e] == k]
        for ax in (0, 1):
            eq([(iF(j, e) + ax, -1) for j, e in ends]
               + [(iN(k), normal[ax, k]), (iG(k), tang[k, ax])])  # fmt: skip
    for i, (d, held) in enumerate(((d1, (0, 2)), (d2, (1, 3)))):  # blade arm i
        for ax in (0, 1):
            eq([(iP(j) + ax, -1) for j in held] + [(iR(i) + ax, 1)])
        # the links' forces on the arm (-P_j at M_j) give it the drive's torque D_i
        eq([c for j in held for c in ((iP(j), M[j][1]), (iP(j) + 1, -M[j][0]))], d)
    for ax in (0, 1):  # shaft: the blocks push back on the guides
        eq([(iG(k), -tang[k, ax]) for k in range(4)] + [(iS + ax, 1)])
    eq([(iG(k), -rho[k]) for k in range(4)] + [(iT, 1)])
    for j in range(4):  # arm forces normal to the arms
        eq([(iP(j), M[j][0]), (iP(j) + 1, M[j][1])])
    for k in (1, 2, 3):  # G_k / rho_k equal
        eq([(iG(0), rho[k]), (iG(k), -rho[0])])
    free = (1, 3) if loaded == 0 else (0, 2)
    eq([(iN(free[0]), 1)])
    eq([(iN(free[1]), 1)])
    carry = (0, 2) if loaded == 0 else (1, 3)
    eq([(iN(carry[0]), 1), (iN(carry[1]), -1)])
    A = np.array(rows)
    assert A.shape == (n_unk, n_unk)
    assert np.linalg.matrix_rank(A) == n_unk
    x = np.linalg.solve(A, np.array(rhs))
    return {
        "link_end": x[:16].reshape(4, 2, 2),
        "arm": x[16:24].reshape(4, 2),
        "N": x[24:28],
        "G": x[28:32],
        "pivot": x[32:36].reshape(2, 2),
        "T": x[36],
        "bearing": x[37:39],
    }


def newton_euler_min_preload(params, alpha, d1, d2):
    """:func:`newton_euler` with the roller pair whose force comes out >= 0."""
    sol = newton_euler(params, alpha, d1, d2, 0)
    if sol["N"][0] >= 0.0:
        return sol, 0
    return newton_euler(params, alpha, d1, d2, 1), 1


@pytest.mark.parametrize("seed", range(12))
def test_independent_newton_euler(seed):
    rng = np.random.default_rng(seed)
    p = _random_design(rng)
    alpha = rng.uniform(-np.pi, 3 * np.pi, 6)
    D = rng.normal(0.0, 200.0, (2, 6))
    f = rf.solve(p, alpha, D)
    for m in range(alpha.size):
        ref, loaded = newton_euler_min_preload(p, alpha[m], D[0, m], D[1, m])
        scale = max(np.max(np.abs(ref["N"])), np.max(np.abs(ref["link_end"])), 1.0)
        assert f.loaded[m] == loaded
        assert np.min(ref["N"]) >= -1e-9 * scale
        np.testing.assert_allclose(f.roller[:, m], ref["N"], rtol=0, atol=1e-9 * scale)
        np.testing.assert_allclose(f.guide[:, m], ref["G"], rtol=0, atol=1e-9 * scale)
        np.testing.assert_allclose(f.link_end[..., m], ref["link_end"], rtol=0, atol=1e-9 * scale)
        np.testing.assert_allclose(f.arm[..., m], ref["arm"], rtol=0, atol=1e-9 * scale)
        # the shaft holds the torque the guides put on it; no radial load anywhere
        assert f.shaft_torque[m] == pytest.approx(-ref["T"], abs=1e-9 * scale * p.link_length)
        assert np.max(np.abs(ref["pivot"])) < 1e-9 * scale
        assert np.max(np.abs(ref["bearing"])) < 1e-9 * scale
        # link tensions from the independent end forces
        V = rc.rhombus_vertices(p.link_length, p.psi_min, p.a, p.b, alpha[m])
        for j in range(4):
            u = (V[(j + 1) % 4] - V[j]) / p.link_length
            t0, t1 = -ref["link_end"][j, 0] @ u, ref["link_end"][j, 1] @ u
            np.testing.assert_allclose(f.tension[j, :, m], [t0, t1], atol=1e-9 * scale)


def test_independent_model_can_disagree():
    """The comparison is not vacuous: another roller pair or arm load changes the answer."""
    p = rc.RhomboidCam(0.12, np.radians(40))
    ref, loaded = newton_euler_min_preload(p, 0.3, 50.0, -80.0)
    other = newton_euler(p, 0.3, 50.0, -80.0, 1 - loaded)
    assert np.min(other["N"]) < 0.0  # the other pair would have to pull on the cam
    f = rf.solve(p, np.array([0.3]), np.array([[50.0], [-81.0]]))
    assert abs(f.roller[:, 0] - ref["N"]).max() > 1e-3


# --- power ---------------------------------------------------------------------------------
@pytest.mark.parametrize("seed", range(6))
def test_power_balance_every_angle(seed):
    rng = np.random.default_rng(100 + seed)
    p = _random_design(rng)
    alpha = np.linspace(0.0, 2 * np.pi, 997)
    D = rng.normal(0.0, 150.0, (2, 1)) * (1.0 + np.sin(np.arange(2)[:, None] + 3 * alpha))
    f = rf.solve(p, alpha, D)
    mo = rc.motion(p, alpha)
    virtual = -np.sum(D * mo.dq, axis=0)  # sum (M_i - J_i qdd_i) q_i'
    np.testing.assert_allclose(f.shaft_torque, virtual, rtol=0,
                               atol=1e-9 * np.max(np.abs(virtual)))  # fmt: skip
    # the cam's forces do no work: each roller force is normal to its centre's path
    dp = cam.pitch_curve(p.link_length, p.psi_min, p.a, p.b, cam.roller_alphas(alpha))[1]
    dp = np.moveaxis(dp, 0, 1)  # (4, 2, n) as the normals
    assert np.max(np.abs(np.sum(f.normal * dp, axis=1))) < 1e-12 * p.link_length


def _cfg(**kw):
    cfg = {
        "title": "",
        "drive": {"type": "rhomboid_cam", "link_length": 0.12, "psi_min": np.radians(40),
                  "a": [], "b": []},
        "machine": {},
        "loads": {"torque_high": 100.0, "torque_low": 40.0},
        "run": {"points": 181},
    }  # fmt: skip
    for key, value in kw.items():
        section, _, name = key.partition("__")
        cfg.setdefault(section, {})[name] = value
    return cfg


@pytest.mark.parametrize("drive", [{}, {"drive__a": [0.05], "drive__b": [0.02]}])
@pytest.mark.parametrize("model", ["linear", "isothermal"])
def test_power_balance_through_the_study(drive, model):
    res = evaluate(_cfg(loads__pressure_model=model, **drive))
    cols = res.columns
    # the machine's torque less the blade pairs' inertia (constant speed: no shaft term)
    want = cols["shaft_torque_Nm"] - cols["inertia_torque_Nm"]
    np.testing.assert_allclose(cols["converter_shaft_torque_Nm"], want, rtol=0,
                               atol=1e-9 * np.max(np.abs(want)))  # fmt: skip
    al = np.radians(cols["alpha_deg"])
    params = drive_params(_cfg(**drive))
    mo = rc.motion(params, al)
    rho = rc.profile_radius(params.link_length, params.psi_min, params.a, params.b,
                            cam.roller_alphas(al))[0]  # fmt: skip
    guides = sum(cols[f"guide_{v}_tangential_N"] * rho[i] for i, v in enumerate("abcd"))
    np.testing.assert_allclose(-guides, want, rtol=0, atol=1e-9 * np.max(np.abs(want)))
    D = np.stack([cols[f"blade_pair_{i}_drive_torque_Nm"] for i in (1, 2)])
    np.testing.assert_allclose(-np.sum(D * mo.dq, axis=0), want, rtol=0,
                               atol=1e-9 * np.max(np.abs(want)))  # fmt: skip


# --- signs and hand cases --------------------------------------------------------------------
def test_opening_load_presses_a_and_c_by_hand():
    """Blade pair 1 pushed forward, pair 2 back (the gas opening psi), no speed: at alpha = 0
    (psi = psi_max, rho' = 0) the rhombus pushes A and C on the cam radially with
    ``N = M / (2l sin(psi_max/2))`` (virtual work on psi); B and D are free."""
    p = rc.RhomboidCam(0.12, np.radians(40))
    M = 100.0
    f = rf.solve(p, np.array([0.0]), np.array([[-M], [M]]))  # D = -M_machine
    n_hand = M / (0.12 * np.sin(np.radians(70)))
    np.testing.assert_allclose(f.roller[:, 0], [n_hand, 0, n_hand, 0], rtol=1e-12)
    np.testing.assert_allclose(f.guide[:, 0], 0.0, atol=1e-9)  # no torque at the dead centre
    np.testing.assert_allclose(f.normal[0, :, 0], [1.0, 0.0], atol=1e-15)  # radial at A
    assert f.loaded[0] == 0
    # closing load: B and D carry it, with rho_B in place of rho_A
    g = rf.solve(p, np.array([0.0]), np.array([[M], [-M]]))
    n_b = M / (0.12 * np.cos(np.radians(70)))
    np.testing.assert_allclose(g.roller[:, 0], [0, n_b, 0, n_b], rtol=1e-12)
    assert g.loaded[0] == 1


def test_compression_stroke_shaft_drives_through_the_trailing_flank():
    """While psi falls (0 < alpha < 90 deg) under an opening gas load the shaft does the work:
    the guides push the blocks forward (G > 0), the shaft torque is negative."""
    p = rc.RhomboidCam(0.12, np.radians(40))
    al = np.radians([20.0, 45.0, 70.0])
    f = rf.solve(p, al, np.array([[-100.0] * 3, [100.0] * 3]))
    assert np.all(f.guide > 0.0) and np.all(f.shaft_torque < 0.0)
    assert np.all(f.roller[[0, 2]] > 0.0) and np.all(f.roller[[1, 3]] == 0.0)
    # expansion (psi rising) under the same load: the rhombus drives the shaft
    f = rf.solve(p, al + np.pi / 2, np.array([[-100.0] * 3, [100.0] * 3]))
    assert np.all(f.guide < 0.0) and np.all(f.shaft_torque > 0.0)


def test_pure_common_torque_goes_through_the_guides_as_tension():
    """Both blade pairs driven alike (no load on psi), square rhombus-like alpha = 45 deg of
    the first-harmonic law (psi = 90 deg): no roller force; the guides carry the torque."""
    p = rc.RhomboidCam(0.12, np.radians(40))
    al = np.array([np.pi / 4])
    f = rf.solve(p, al, np.array([[60.0], [60.0]]))
    rho = rc.profile_radius(0.12, p.psi_min, (), (), al + np.arange(4)[:, None] * np.pi / 2)[0]
    mu = cam.pressure_angles(0.12, p.psi_min, (), (), al)[:, 0]
    assert abs(mu[0]) > 0.1  # the cam is inclined here, yet carries nothing
    np.testing.assert_allclose(f.roller, 0.0, atol=1e-9)
    np.testing.assert_allclose(f.guide[:, 0], 120.0 / np.sum(rho[:, 0] ** 2) * rho[:, 0],
                               rtol=1e-12)  # fmt: skip


def test_arm_forces_are_torque_over_two_l():
    p = _random_design(np.random.default_rng(7))
    al = np.linspace(0, np.pi, 11)
    D = np.stack([np.full(11, 30.0), np.full(11, -45.0)])
    f = rf.solve(p, al, D)
    mag = np.hypot(f.arm[:, 0], f.arm[:, 1])
    np.testing.assert_allclose(mag[[0, 2]], 30.0 / p.link_length, rtol=1e-12)
    np.testing.assert_allclose(mag[[1, 3]], 45.0 / p.link_length, rtol=1e-12)


# --- the study, pairs and keys ---------------------------------------------------------------
def test_study_pairs_keys_and_columns():
    res = evaluate(_cfg())
    s, cols = res.summary, res.columns
    json.dumps(s)
    for key in ("peak_contact_force_N", "peak_contact_stress_MPa", "contact_safety_factor",
                "peak_bearing_load_N", "friction_loss_W", "mechanical_efficiency",
                "peak_roller_force_N", "peak_link_force_N", "peak_guide_force_N",
                "peak_link_bending_Nm", "peak_arm_force_N", "roller_pair_BD_share"):  # fmt: skip
        assert np.isfinite(s[key]), key
    assert s["peak_contact_force_N"] == pytest.approx(s["peak_roller_force_N"])
    assert s["peak_contact_stress_pair"].startswith("roller ")
    assert 0.0 < s["mechanical_efficiency"] < 1.0
    assert 0.0 < s["roller_pair_BD_share"] < 1.0
    for v in "abcd":
        assert f"roller_{v}_cam_force_N" in cols and f"roller_{v}_cam_contact_stress_MPa" in cols
        assert f"guide_{v}_force_N" in cols and f"roller_{v}_pin_force_N" in cols
    assert set(cols) == set(res.column_docs)
    assert all(np.shape(v) == (181,) for v in cols.values())
    for key in ("peak_contact_force_N", "peak_link_force_N", "mechanical_efficiency"):
        assert key in res.headline
    # rollers' Hertz pressure: line contact of the roller on the cam's actual profile
    al = np.radians(cols["alpha_deg"])
    r = 0.01
    rp = cam.pitch_radius_of_curvature(0.12, np.radians(40), (), (), al)
    model = ap.ContactModel.from_config({})
    from rotorkin.analysis import contact as hz

    m = hz.Material(model.youngs_modulus, model.poisson_ratio)
    want = hz.line_contact(cols["roller_a_cam_force_N"], model.roller_width, r, rp - r, m, m).p_max
    np.testing.assert_allclose(cols["roller_a_cam_contact_stress_MPa"], want / 1e6, rtol=1e-9)


def test_inertia_dominates_at_speed_and_vanishes_at_rest():
    fast = evaluate(_cfg()).summary
    slow = evaluate(_cfg(run__speed=2e-3)).summary
    assert fast["peak_roller_force_N"] > 1.5 * slow["peak_roller_force_N"]
    # at rest: only the linear model's torques, at most M1 = 100 N m on a pair
    assert slow["peak_arm_force_N"] == pytest.approx(100.0 / 0.12, rel=1e-6)


def test_single_blade_loads_its_hub():
    res = evaluate(_cfg(machine__blades_per_pair=1))
    cols = res.columns
    r_c = 0.5 * (0.03 + 0.09)  # machine defaults: 30 and 90 mm
    want = np.abs(cols["blade_pair_1_torque_Nm"]) / r_c
    np.testing.assert_allclose(cols["blade_pair_1_hub_force_N"], want, rtol=1e-12)
    two = evaluate(_cfg()).columns
    assert np.all(two["blade_pair_1_hub_force_N"] == 0.0)


# --- psi within psi_min ... psi_max for the linear torque model (eq. 2) ----------------------
def test_linear_model_refuses_a_law_leaving_the_range():
    with pytest.raises(ParameterError) as info:
        evaluate(_cfg(drive__a=[1.0]))
    msg = str(info.value)
    assert msg == (
        "drive.a = [1.0] is not admissible: psi must stay within psi_min = 40 deg ... "
        "psi_max = 140 deg for the linear torque model (eq. 2); this law reaches "
        "29.0 deg ... 151.0 deg"
    )
    with pytest.raises(ParameterError, match=r"^drive\.b = \[0\.3\] .*eq\. 2"):
        evaluate(_cfg(drive__b=[0.3]))
    # monotone and non-monotone laws inside the range still run
    assert evaluate(_cfg(drive__a=[0.4])).summary["psi_monotone"] is False
    assert rc.psi_range_violation(np.radians(40), (0.4,)) is False
    assert rc.psi_range_violation(np.radians(70), (0.4,)) is True


def test_isothermal_model_runs_the_law_and_leaves_linear_keys_undefined():
    res = evaluate(_cfg(drive__a=[1.0], loads__pressure_model="isothermal"))
    s = res.summary
    assert np.isnan(s["indicator_work_J"]) and np.isnan(s["mean_shaft_torque_Nm"])
    assert np.isfinite(s["indicated_work_J"]) and np.isfinite(s["peak_roller_force_N"])
    assert s["psi_lowest_deg"] == pytest.approx(29.0179, abs=1e-3)
    assert any(w.startswith("indicator_work_J is not defined: drive.a takes psi outside")
               for w in res.warnings)  # fmt: skip


def test_cli_refuses_in_one_line(capsys, tmp_path):
    code = main(["run", "-e", "rhomboid-engine", "--set", "drive.a=[1.0]", "-q", "--out",
                 str(tmp_path / "out")])  # fmt: skip
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert len(err.splitlines()) == 1
    assert "drive.a = [1.0] is not admissible: psi must stay within psi_min = 40 deg" in err
    assert "this law reaches 29.0 deg ... 151.0 deg" in err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("radius, shown", [("0 mm", "0 mm"), ("1e-300 m", "1e-297 mm")])
def test_cli_refuses_roller_radius_zero(capsys, tmp_path, radius, shown):
    """0, and a radius so small that the roller's spin overflows, are refused."""
    code = main(["run", "-e", "rhomboid-engine", "--set", f"cam.roller_radius={radius}", "-q",
                 "--out", str(tmp_path / "out")])  # fmt: skip
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1
    assert err.endswith(
        f"cam.roller_radius = {shown} is not admissible: roller_radius >= 0.001 mm for the "
        "contact forces (a roller's Hertz stress and spin need its radius)"
    )
    assert not (tmp_path / "out").exists()


def test_sweep_flags_the_range_like_the_study():
    cfg = load_config(None, "rhomboid-engine", ["drive.a=[0.4]"])[0]
    code = {k: i for i, k in enumerate(reason_keys("rhomboid_cam"))}
    pm = np.radians([40.0, 60.0, 75.0, 85.0])
    p = Designs(cfg, {"drive.psi_min": pm}, 4)
    r = batch.reasons(p, code)  # the kernel's check, called on such a base config
    np.testing.assert_array_equal(r, [0, 0, code["drive.a"], code["drive.a"]])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        out = evaluate_designs(p, ["indicator_work_J"], samples=101)  # the scalar fallback
    np.testing.assert_array_equal(out["reason"], r)
    assert np.all(np.isfinite(out["metrics"]["indicator_work_J"][:2]))
    # the isothermal model runs them
    iso = load_config(None, "rhomboid-engine",
                      ["drive.a=[0.4]", "loads.pressure_model=isothermal"])[0]  # fmt: skip
    assert not np.any(batch.reasons(Designs(iso, {"drive.psi_min": pm}, 4), code))
    # first-harmonic designs never leave the range
    base = load_config(None, "rhomboid-engine", [])[0]
    assert not np.any(batch.reasons(Designs(base, {"drive.psi_min": pm}, 4), code))


def test_sweep_and_study_agree_on_one_design():
    cfg = load_config(None, "rhomboid-engine", ["drive.a=[1.0]"])[0]
    with pytest.raises(ParameterError, match=r"^drive\.a = "):
        drive_evaluate(cfg)
