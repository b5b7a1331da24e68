"""Forces in the pairs of the double eccentric discs, and the inclined-disc adjuster."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from rotorkin.analysis import torque as tq
from rotorkin.cli import main
from rotorkin.drives import evaluate
from rotorkin.drives.eccentric_cam import forces as fz
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.drives.eccentric_cam.reactor import opposed_piston, reactor_state

FOLLOWERS = (("knife_edge", 0.0), ("roller", 0.015), ("flat", 0.0))


def _cfg(machine=None, run=None, **drive):
    d = {"type": "eccentric_cam", "disc_radius": 0.08, "eccentricity": 0.04,
         "follower": "knife_edge", "roller_radius": 0.0}  # fmt: skip
    d.update(drive)
    m = {"device_length": 1.0, "inertia_shaft": 0.0, "piston_mass": 0.5}
    m.update(machine or {})
    return {"drive": d, "machine": m, "loads": {}, "run": {"points": 361, **(run or {})}}


def _random_case(rng, follower, r):
    R = rng.uniform(0.03, 0.2)
    e = rng.uniform(0.1, 0.8) * R
    params = ec.EccentricCam(R, e, follower, r * R / 0.08 if follower == "roller" else 0.0)
    reactor = opposed_piston(params, device_length=2.0, bore=rng.uniform(0.02, 0.1),
                             fluid="gas", initial_pressure=rng.uniform(0.5e5, 20e5),
                             polytropic_exponent=1.3, bulk_modulus=1.5e9)  # fmt: skip
    masses = (rng.uniform(0.1, 3.0), rng.uniform(0.1, 3.0))
    return params, reactor, masses


# --------------------------------------------------------------------------------------------
# power balance: the contact forces' torque on the shaft is the virtual-work torque
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize(("follower", "r"), FOLLOWERS)
@pytest.mark.parametrize("speed", [62.8, [40.0, 90.0, 60.0]])
def test_contact_torque_equals_the_virtual_work_torque(follower, r, speed):
    rng = np.random.default_rng(7)
    for _ in range(4):
        params, reactor, masses = _random_case(rng, follower, r)
        beta = np.linspace(0.0, 2.0 * np.pi, 1001)
        st = reactor_state(params, reactor, (0.0, masses), speed, beta)
        state = fz.contact_state(params, beta, st["F"], masses, st["omega"], st["omega_dot"])
        m = ec.motion(params, beta)
        pistons = tq.inertia_torque(0.0, masses, m.dq, m.d2q, st["omega"], st["omega_dot"])
        want = st["shaft"] - pistons
        scale = np.max(np.abs(want))
        assert np.max(np.abs(state.shaft_torque - want)) <= 1e-9 * scale
        # power: N n . (disc surface velocity at C) summed = - shaft torque (per rad)
        C, n = state.point, state.n
        v_disc = np.stack([-C[:, 1], C[:, 0]], axis=1)
        power = np.sum(state.normal[:, None] * n * v_disc, axis=(0, 1))
        assert np.max(np.abs(power + state.shaft_torque)) <= 1e-9 * scale


def test_study_columns_balance_with_the_shaft_torque():
    for follower, r in FOLLOWERS:
        res = evaluate(_cfg(follower=follower, roller_radius=r))
        c = res.columns
        want = c["shaft_torque_with_inertia_Nm"]  # inertia_shaft = 0: the pistons' only
        assert np.allclose(
            c["contact_shaft_torque_Nm"], want, rtol=0, atol=1e-9 * np.abs(want).max()
        )


# --------------------------------------------------------------------------------------------
# an independent statics model: Newton-Euler per link, one linear system
# --------------------------------------------------------------------------------------------
def _newton_euler(R, e, follower, r, beta, M, masses, qdd):
    """Pair forces at one angle from the equilibrium of every link.

    Links: piston 1, piston 2 (x, y, moment), roller 1, 2 (x, y, moment; massless,
    their mass counted in the piston's), shaft with both discs (x, y, moment).
    Unknowns: N1, N2 (contact, along the normal), G1, G2 (guide on piston, y),
    K1, K2 (guide moment on piston), P1x, P1y, P2x, P2y (piston on roller),
    Bx, By (frame on shaft), T (motor on shaft).
    """
    rc = R + r if follower == "roller" else R
    geo = []
    for sign in (1.0, -1.0):
        c = sign * e * np.array([np.cos(beta), np.sin(beta)])
        if follower == "flat":
            n = np.array([1.0, 0.0])
            C = c + R * n
            P = None
        else:
            P = np.array([c[0] + np.sqrt(rc**2 - c[1] ** 2), 0.0])  # on the axis, pitch circle
            n = (P - c) / np.linalg.norm(P - c)
            C = c + R * n
        geo.append((c, n, C, P))
    names = ["N1", "N2", "G1", "G2", "K1", "K2", "P1x", "P1y", "P2x", "P2y", "Bx", "By", "T"]
    col = {nm: i for i, nm in enumerate(names)}
    rows, rhs = [], []

    def eq(coeffs, value):
        row = np.zeros(len(names))
        for nm, v in coeffs.items():
            row[col[nm]] += v
        rows.append(row)
        rhs.append(value)

    for k in range(2):
        c, n, C, P = geo[k]
        N, G, K = f"N{k + 1}", f"G{k + 1}", f"K{k + 1}"
        px, py = f"P{k + 1}x", f"P{k + 1}y"
        inertia = masses[k] * qdd[k]
        if follower == "roller":
            # roller: N n + (Px, Py) = 0; moment about its centre: N (C - P) x n = 0
            eq({N: n[0], px: 1.0}, 0.0)
            eq({N: n[1], py: 1.0}, 0.0)
            arm = C - P
            eq({N: arm[0] * n[1] - arm[1] * n[0]}, 0.0)
            # piston: -(Px, Py) at P (on the axis), guide, machine force
            eq({px: -1.0}, inertia - M[k])
            eq({py: -1.0, G: 1.0}, 0.0)
            eq({K: 1.0}, 0.0)  # the pin force passes through the axis
        else:
            eq({N: n[0]}, inertia - M[k])
            eq({N: n[1], G: 1.0}, 0.0)
            eq({N: -C[1] * n[0], K: 1.0}, 0.0)  # moment about the axis point level with C
            eq({px: 1.0}, 0.0)
            eq({py: 1.0}, 0.0)
            eq({px: 0.0}, 0.0)
    # shaft with both discs: -N n at C, bearing B, motor T
    eq({"N1": -geo[0][1][0], "N2": -geo[1][1][0], "Bx": 1.0}, 0.0)
    eq({"N1": -geo[0][1][1], "N2": -geo[1][1][1], "By": 1.0}, 0.0)
    mz = {}
    for k in range(2):
        _, n, C, _ = geo[k]
        mz[f"N{k + 1}"] = -(C[0] * n[1] - C[1] * n[0])
    eq({**mz, "T": 1.0}, 0.0)
    A, b = np.array(rows), np.array(rhs)
    x = np.linalg.lstsq(A, b, rcond=None)[0]
    assert np.allclose(A @ x, b, atol=1e-9 * max(1.0, np.abs(b).max()))
    assert np.linalg.matrix_rank(A) == len(names)
    return dict(zip(names, x, strict=True)), geo


@pytest.mark.parametrize(("follower", "r"), FOLLOWERS)
def test_forces_equal_an_independent_newton_euler_model(follower, r):
    rng = np.random.default_rng(11)
    for _ in range(5):
        params, reactor, masses = _random_case(rng, follower, r)
        beta = rng.uniform(0.0, 2.0 * np.pi, 7)
        omega, omega_dot = rng.uniform(10.0, 200.0), rng.uniform(-500.0, 500.0)
        st = reactor_state(params, reactor, (0.0, masses), omega, beta)
        state = fz.contact_state(params, beta, st["F"], masses, omega, omega_dot)
        m = ec.motion(params, beta)
        qdd = m.d2q * omega**2 + m.dq * omega_dot
        R, e, rr = (
            float(params.disc_radius),
            float(params.eccentricity),
            float(params.roller_radius),
        )
        for j, b in enumerate(beta):
            sol, geo = _newton_euler(R, e, follower, rr, b, st["F"][:, j], masses, qdd[:, j])
            scale = max(abs(sol["N1"]), abs(sol["N2"]))
            for k in range(2):
                if geo[k][3] is not None:  # the pitch point is where the kinematics put it
                    rc = float(params.contact_radius)
                    assert geo[k][3][0] == pytest.approx(rc + m.q[k, j], rel=1e-12)
                assert state.normal[k, j] == pytest.approx(sol[f"N{k + 1}"], abs=1e-9 * scale)
                assert state.side_thrust[k, j] == pytest.approx(-sol[f"G{k + 1}"], abs=1e-9 * scale)
                assert state.tilting_moment[k, j] == pytest.approx(
                    -sol[f"K{k + 1}"], abs=1e-9 * scale * R
                )
                if follower == "roller":
                    pin = np.hypot(sol[f"P{k + 1}x"], sol[f"P{k + 1}y"])
                    assert abs(state.normal[k, j]) == pytest.approx(pin, abs=1e-9 * scale)
            assert state.shaft_load[0, j] == pytest.approx(-sol["Bx"], abs=1e-9 * scale)
            assert state.shaft_load[1, j] == pytest.approx(-sol["By"], abs=1e-9 * scale)
            assert state.shaft_torque[j] == pytest.approx(-sol["T"], abs=1e-9 * scale * R)


# --------------------------------------------------------------------------------------------
# signs and walls on cases worked by hand
# --------------------------------------------------------------------------------------------
def _gas_only(params, beta, p=1e5, bore=0.05):
    A = np.pi * bore**2 / 4.0
    F = np.full((2, np.size(beta)), -p * A)
    return A * p, fz.contact_state(params, beta, F, (0.0, 0.0), 50.0, 0.0)


def test_knife_edge_side_thrust_wall_at_90_deg():
    # lambda = 0.5: at 90 deg the left disc centre is at (0, e), the tip at (sqrt(R^2-e^2), 0):
    # the normal leans to -y by 30 deg; the left piston presses its -y wall, the right its +y
    params = ec.EccentricCam(0.08, 0.04)
    pA, s = _gas_only(params, np.array([0.0, 0.5 * np.pi]))
    assert s.normal[:, 0] == pytest.approx([pA, pA], rel=1e-12)  # on the axis at 0 deg
    assert s.side_thrust[:, 0] == pytest.approx([0.0, 0.0], abs=1e-9)
    assert s.normal[:, 1] == pytest.approx([pA * 2 / np.sqrt(3)] * 2, rel=1e-12)
    assert s.side_thrust[0, 1] == pytest.approx(-pA / np.sqrt(3), rel=1e-12)
    assert s.side_thrust[1, 1] == pytest.approx(+pA / np.sqrt(3), rel=1e-12)
    # the disc surface under the tip slides at |C| along the tangent at 0 deg: R + e
    assert s.slip[0, 0] == pytest.approx(0.12, rel=1e-12)


def test_flat_face_pushes_along_the_axis_off_it():
    params = ec.EccentricCam(0.08, 0.04, "flat")
    pA, s = _gas_only(params, np.array([0.5 * np.pi]))
    assert s.side_thrust[:, 0] == pytest.approx([0.0, 0.0], abs=1e-12)
    assert s.normal[:, 0] == pytest.approx([pA, pA], rel=1e-12)
    # left contact at y = +e: the force along +x there turns the piston clockwise (-z)
    assert s.tilting_moment[:, 0] == pytest.approx([-0.04 * pA, 0.04 * pA], rel=1e-12)
    assert s.slip[:, 0] == pytest.approx([0.08, 0.08], rel=1e-12)  # R + e cos 90 deg


def test_roller_pin_turns_with_the_rolling_speed():
    params = ec.EccentricCam(0.08, 0.04, "roller", 0.02)
    _, s = _gas_only(params, np.array([0.0]))
    # at 0 deg: disc surface at C = (e + R, 0) moves at R + e along y, the roller rolls on it
    assert s.slip[0, 0] == pytest.approx(0.12, rel=1e-12)
    assert s.spin[0, 0] == pytest.approx(0.12 / 0.02, rel=1e-12)
    prs = fz.pairs(params, s, 0.01)
    kinds = {p.slug: p.kind for p in prs}
    assert kinds == {"left_roller": "rolling", "left_guide": "sliding",
                     "left_roller_pin": "bearing", "left_disc_shaft": "bearing",
                     "right_roller": "rolling", "right_guide": "sliding",
                     "right_roller_pin": "bearing", "right_disc_shaft": "bearing"}  # fmt: skip
    assert prs[0].geometry == ("line", 0.08, 0.02)


def test_follower_lifts_off_at_high_speed():
    slow = evaluate(_cfg(run={"speed": 62.83})).summary
    fast = evaluate(_cfg(run={"speed": 314.16})).summary
    assert not slow["follower_lift_off"] and slow["follower_force_min_N"] > 0.0
    assert fast["follower_lift_off"] and fast["follower_force_min_N"] < 0.0


def test_study_summary_keys_and_stress():
    s = evaluate(_cfg()).summary
    for key in ("peak_contact_force_N", "peak_bearing_load_N", "friction_loss_W",
                "mechanical_efficiency", "side_thrust_peak_N", "follower_force_peak_N",
                "shaft_radial_load_peak_N", "work_through_drive_J"):  # fmt: skip
        assert np.isfinite(s[key]), key
    assert "peak_contact_stress_MPa" not in s  # a sharp knife edge: no contact stress
    tipped = evaluate(_cfg(tip_radius=0.002)).summary
    assert tipped["peak_contact_stress_MPa"] > 0.0 and tipped["contact_safety_factor"] > 0.0
    flat = evaluate(_cfg(follower="flat")).summary
    assert flat["side_thrust_peak_N"] == pytest.approx(0.0, abs=1e-9)
    assert flat["guide_tilting_moment_peak_Nm"] > 0.0
    assert 0.0 < flat["mechanical_efficiency"] < 1.0


# --------------------------------------------------------------------------------------------
# the adjuster: inclined discs slid along the shaft
# --------------------------------------------------------------------------------------------
def test_adjuster_eccentricity_and_slide():
    a = np.radians(20.0)
    assert ec.adjuster_eccentricity(a, 0.1) == pytest.approx(0.1 * np.tan(a), rel=1e-15)
    assert ec.adjuster_slide(a, ec.adjuster_eccentricity(a, 0.1)) == pytest.approx(0.1)
    assert ec.section_semi_axes(0.08, a)[0] == pytest.approx(0.08 / np.cos(a))


@pytest.mark.parametrize(("follower", "r"), FOLLOWERS)
def test_section_law_without_inclination_is_the_paper_law(follower, r):
    beta = np.linspace(0.0, 2.0 * np.pi, 3601)
    params = ec.EccentricCam(0.08, 0.04, follower, r)
    got = ec.section_travels(0.08, 0.04, 0.0, follower, r, beta)
    assert np.max(np.abs(got - ec.piston_travels(params, beta)[0])) < 1e-15


def test_study_without_inclination_is_unchanged():
    base = evaluate(_cfg())
    off = evaluate(_cfg(inclination=0.0))
    assert off.summary == base.summary
    assert off.columns.keys() == base.columns.keys()
    assert all(np.array_equal(off.columns[k], base.columns[k]) for k in base.columns)
    assert not any(k.startswith("section_") for k in base.summary)


def _brute_rho(R, alpha, s, beta, sign, follower):
    """Follower point from the 3-D cylinder itself (no ellipse): axis through o'' with
    direction (sin a cos b', sin a sin b', cos a), b' = beta (left) or beta + pi (right)."""
    bb = beta + (0.0 if sign > 0 else np.pi)
    d = np.array([np.sin(alpha) * np.cos(bb), np.sin(alpha) * np.sin(bb), np.cos(alpha)])

    def dist2(p):
        return p @ p - (p @ d) ** 2

    if follower == "knife_edge":
        f = lambda x: dist2(np.array([x, 0.0, s])) - R**2  # noqa: E731
        return brentq(f, 0.0, 10.0 * R, xtol=1e-15)
    # flat face: largest x over the section points, parametrised by the angle around the axis
    w1 = np.cross(d, [0.0, 0.0, 1.0])
    w1 /= np.linalg.norm(w1)
    w2 = np.cross(d, w1)

    def x_of(phi):
        rim = R * (np.cos(phi) * w1 + np.sin(phi) * w2)
        t = (s - rim[2]) / d[2]
        return -(t * d + rim)[0]

    grid = np.linspace(0.0, 2.0 * np.pi, 721)
    k = int(np.argmin([x_of(p) for p in grid]))
    res = minimize_scalar(x_of, bounds=(grid[k] - 0.01, grid[k] + 0.01), method="bounded",
                          options={"xatol": 1e-13})  # fmt: skip
    return -res.fun


@pytest.mark.parametrize("follower", ["knife_edge", "flat"])
def test_section_law_against_the_cylinder_in_three_dimensions(follower):
    R, alpha, s = 0.08, np.radians(17.0), 0.12
    e = s * np.tan(alpha)
    beta = np.radians([0.0, 33.0, 90.0, 147.0, 180.0, 251.0])
    got = ec.section_travels(R, e, alpha, follower, 0.0, beta)
    for k, sign in enumerate((1.0, -1.0)):
        rho0 = _brute_rho(R, alpha, s, 0.0, 1.0, follower)  # top: z = +e
        for j, b in enumerate(beta):
            z = _brute_rho(R, alpha, s, b, sign, follower) - (rho0 - e)
            assert got[k, j] == pytest.approx(z, abs=1e-8 * R)


def test_inclined_flat_face_no_longer_keeps_the_gap():
    R, alpha = 0.08, np.radians(20.0)
    z = ec.section_travels(R, 0.04, alpha, "flat", 0.0, np.array([0.0, 0.5 * np.pi]))
    assert z[0, 0] + z[1, 0] == pytest.approx(0.0, abs=1e-15)
    assert z[0, 1] + z[1, 1] == pytest.approx(2 * R * (1 - 1 / np.cos(alpha)), rel=1e-12)


def test_roller_on_the_section_rolls_on_its_parallel_curve():
    R, e, alpha, r = 0.08, 0.04, np.radians(25.0), 0.015
    a, b = ec.section_semi_axes(R, alpha)
    beta = np.linspace(0.0, 2.0 * np.pi, 91)
    z = ec.section_travels(R, e, alpha, "roller", r, beta)
    t = np.linspace(0.0, 2.0 * np.pi, 200001)
    for k, sign in enumerate((1.0, -1.0)):
        for j, bt in enumerate(beta):
            centre = np.array([a + r + z[k, j], 0.0])
            u = np.array([np.cos(bt), np.sin(bt)])
            v = np.array([-u[1], u[0]])
            pts = sign * e * u[:, None] + a * np.cos(t) * u[:, None] + b * np.sin(t) * v[:, None]
            dist = np.min(np.hypot(*(pts - centre[:, None])))
            assert dist == pytest.approx(r, abs=1e-8)


def test_study_with_the_adjuster():
    alpha = np.radians(20.0)
    slide = 0.04 / np.tan(alpha)
    s = evaluate(_cfg(eccentricity=None, inclination=alpha, slide=slide)).summary
    base = evaluate(_cfg()).summary
    assert s["gap_change_min_mm"] == pytest.approx(base["gap_change_min_mm"], rel=1e-9)
    assert s["slide_mm"] == pytest.approx(slide * 1e3)
    assert s["section_major_axis_mm"] == pytest.approx(160.0 / np.cos(alpha))
    assert 1.0 < s["section_travel_difference_max_mm"] < 10.0
    both = evaluate(_cfg(inclination=alpha)).summary  # e given: the slide derived
    assert both["slide_mm"] == pytest.approx(slide * 1e3)


# --------------------------------------------------------------------------------------------
# refusals: one line, exit 2
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("sets", "fragment"),
    [
        (["drive.slide=100 mm"], "drive.slide"),
        (["drive.inclination=20 deg", "drive.slide=300 mm"], "drive.slide"),
        (["drive.inclination=20 deg", "drive.slide=50 mm"], "drive.eccentricity"),
        (["drive.inclination=90 deg"], "inclination"),
        (["drive.inclination=-5 deg"], "inclination"),
        (["drive.tip_radius=-1 mm"], "tip_radius"),
    ],
)
def test_bad_adjuster_inputs_are_refused(sets, fragment, tmp_path, capsys):
    args = ["run", "-e", "eccentric-reactor", "-q", "--out", str(tmp_path / "o")]
    for item in sets:
        args += ["--set", item]
    code = main(args)
    _, err = capsys.readouterr()
    assert code == 2
    assert err.strip().count("\n") == 0 and fragment in err


def test_missing_eccentricity_without_the_adjuster_is_refused(tmp_path, capsys):
    cfg = tmp_path / "c.toml"
    cfg.write_text('[drive]\ntype = "eccentric_cam"\ndisc_radius = "80 mm"\n')
    code = main(["run", str(cfg), "-q", "--out", str(tmp_path / "o")])
    _, err = capsys.readouterr()
    assert code == 2 and "drive.eccentricity" in err and err.strip().count("\n") == 0


@pytest.mark.parametrize(("follower", "r"), FOLLOWERS)
def test_largest_travel_change_is_the_semi_axes_difference(follower, r):
    # the section contains the paper's circle and touches it at the minor axis' ends: there
    # the follower stands where the circle would put it, and the travels (from mid stroke)
    # differ by the shift a - R of the mid position, the largest difference over the turn
    rng = np.random.default_rng(3)
    for _ in range(3):
        R, alpha = rng.uniform(0.04, 0.12), np.radians(rng.uniform(3.0, 35.0))
        e = rng.uniform(0.1, 0.7) * R
        rr = r * R / 0.08
        beta = np.linspace(0.0, 2.0 * np.pi, 40001)
        d = (
            ec.section_travels(R, e, alpha, follower, rr, beta)
            - ec.piston_travels(ec.EccentricCam(R, e, follower, rr), beta)[0]
        )
        assert np.max(d) <= 1e-15
        assert np.min(d) == pytest.approx(R * (1.0 - 1.0 / np.cos(alpha)), rel=1e-6)
