"""Tests of the double eccentric-cam drive against independent geometric models."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from rotorkin.core.errors import ParameterError
from rotorkin.core.motion import Motion
from rotorkin.drives import evaluate
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.drives.eccentric_cam import schema
from rotorkin.drives.eccentric_cam.study import drive_params
from rotorkin.machines import opposed_piston as op
from rotorkin.studies.helpers import build_params


# --------------------------------------------------------------------------------------------
# independent models (plane geometry in the frame of one follower: x along its axis,
# towards the reactor centre, origin on the shaft axis)
# --------------------------------------------------------------------------------------------
def _disc_centre(e, beta, side):
    """Disc centre seen from the follower: left +e(cos, sin), right -e(cos, sin)."""
    sign = 1.0 if side == "left" else -1.0
    return sign * e * np.cos(beta), sign * e * np.sin(beta)


def _knife_edge_travel(R, e, beta, side):
    """Intersection of the follower axis (y = 0) with the disc circle, by root finding."""
    cx, cy = _disc_centre(e, beta, side)

    def on_circle(x):
        return (x - cx) ** 2 + cy**2 - R**2

    # the contact is the intersection farther along +x: between the centre's foot and cx + R
    x = brentq(on_circle, cx, cx + R + 1e-12, xtol=1e-15, rtol=1e-15)
    return x - R


def _flat_travel(R, e, beta, side):
    """Support function of the disc in +x: max over the circle's points of x, minus R."""
    cx, cy = _disc_centre(e, beta, side)
    grid = np.linspace(-np.pi, np.pi, 721)
    phi0 = grid[np.argmax(cx + R * np.cos(grid))]
    res = minimize_scalar(
        lambda p: -(cx + R * np.cos(p)),
        bounds=(phi0 - 0.01, phi0 + 0.01),
        method="bounded",
        options={"xatol": 1e-12},
    )
    return -res.fun - R


def _roller_travel(R, e, r, beta, side):
    """Roller centre on the follower axis at the lowest position that clears the disc.

    The clearance is the smallest distance from the roller centre to the disc's boundary
    points (found by minimisation), which must equal r; the centre is found by root finding.
    """
    cx, cy = _disc_centre(e, beta, side)
    grid = np.linspace(-np.pi, np.pi, 361)

    def clearance(x):
        d = np.hypot(x - (cx + R * np.cos(grid)), -(cy + R * np.sin(grid)))
        p0 = grid[np.argmin(d)]
        res = minimize_scalar(
            lambda p: np.hypot(x - (cx + R * np.cos(p)), cy + R * np.sin(p)),
            bounds=(p0 - 0.02, p0 + 0.02),
            method="bounded",
            options={"xatol": 1e-13},
        )
        return res.fun - r

    x = brentq(clearance, cx + np.sqrt(max(R**2 - cy**2, 0.0)), cx + R + r + 1e-9, xtol=1e-14)
    return x - (R + r)


def _independent(params, beta, side):
    R, e = params.disc_radius, params.eccentricity
    if params.follower == "knife_edge":
        return _knife_edge_travel(R, e, beta, side)
    if params.follower == "flat":
        return _flat_travel(R, e, beta, side)
    return _roller_travel(R, e, params.roller_radius, beta, side)


def _random_params(rng, follower):
    R = rng.uniform(0.02, 0.2)
    e = rng.uniform(0.05, 0.95) * R
    r = rng.uniform(0.05, 0.6) * R if follower == "roller" else 0.0
    return ec.EccentricCam(R, e, follower, r)


# --------------------------------------------------------------------------------------------
# closed forms against the models
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("follower", ["knife_edge", "roller"])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_travels_against_intersection_models(seed, follower):
    rng = np.random.default_rng(seed)
    p = _random_params(rng, follower)
    beta = rng.uniform(-2 * np.pi, 4 * np.pi, 25)
    q = ec.piston_travels(p, beta)[0]
    tol = 1e-11 if follower == "knife_edge" else 1e-9
    for k, side in enumerate(("left", "right")):
        want = np.array([_independent(p, b, side) for b in beta])
        np.testing.assert_allclose(q[k], want, rtol=0, atol=tol * p.disc_radius / 0.1 + 1e-12)


@pytest.mark.parametrize("seed", [4, 5])
def test_flat_travel_is_support_function(seed):
    rng = np.random.default_rng(seed)
    p = _random_params(rng, "flat")
    beta = rng.uniform(0, 2 * np.pi, 25)
    q = ec.piston_travels(p, beta)[0]
    for k, side in enumerate(("left", "right")):
        want = np.array([_flat_travel(p.disc_radius, p.eccentricity, b, side) for b in beta])
        np.testing.assert_allclose(q[k], want, rtol=0, atol=1e-11)
    np.testing.assert_array_equal(ec.gap_change(p, beta)[0], 0.0)


def test_knife_edge_matches_paper_equations_1_to_6():
    """Eq. 1-6 as printed (with (1/lambda)^2 for the OCR's (1 - lambda)^2)."""
    R, e = 0.08, 0.04
    lam = e / R
    p = ec.EccentricCam(R, e)
    b = np.linspace(0, 2 * np.pi, 37)
    z = np.sqrt(R**2 - e**2 * np.sin(b) ** 2) + e * np.cos(b) - R  # eq. 1
    x = np.sqrt((1 / lam) ** 2 - np.sin(b) ** 2) - 1 / lam + np.cos(b)  # eq. 2
    zr = np.sqrt(R**2 - e**2 * np.sin(b) ** 2) - R - e * np.cos(b)  # eq. 3
    xr = np.sqrt((1 / lam) ** 2 - np.sin(b) ** 2) - 1 / lam - np.cos(b)  # eq. 4
    D = 2 * R * (np.sqrt(1 - lam**2 * np.sin(b) ** 2) - 1)  # eq. 5
    q = ec.piston_travels(p, b)[0]
    d = ec.decomposition(p, b)
    np.testing.assert_allclose(q[0], z, atol=1e-15)
    np.testing.assert_allclose(q[1], zr, atol=1e-15)
    np.testing.assert_allclose(d["x"], x, atol=1e-13)
    np.testing.assert_allclose(d["x_right"], xr, atol=1e-13)
    np.testing.assert_allclose(ec.gap_change(p, b)[0], D, atol=1e-15)
    np.testing.assert_allclose(d["delta"], D / e, atol=1e-13)
    # eq. 6 as printed: delta = (2/lambda)(sqrt(1 - lambda^2 sin^2 beta) - 1)
    eq6 = (2.0 / lam) * (np.sqrt(1.0 - lam**2 * np.sin(b) ** 2) - 1.0)
    np.testing.assert_allclose(d["delta"], eq6, atol=1e-13)
    np.testing.assert_allclose(d["xi"], np.cos(b), atol=1e-15)
    np.testing.assert_allclose(d["mu"], x - np.cos(b), atol=1e-13)


@pytest.mark.parametrize("follower", ec.FOLLOWERS)
def test_derivatives_against_finite_differences(follower):
    rng = np.random.default_rng(11)
    p = _random_params(rng, follower)
    beta = rng.uniform(0, 2 * np.pi, 40)
    h = 1e-4
    f = [ec.piston_travels(p, beta + s * h) for s in (-1, 1)]
    scale = p.eccentricity
    for n in range(3):  # derivative n+1 from central differences of derivative n
        fd = (f[1][n] - f[0][n]) / (2 * h)
        exact = ec.piston_travels(p, beta)[n + 1]
        np.testing.assert_allclose(fd, exact, rtol=0, atol=2e-7 * scale * 10**n)
    g = [ec.gap_change(p, beta + s * h) for s in (-1, 1)]
    for n in range(3):
        fd = (g[1][n] - g[0][n]) / (2 * h)
        np.testing.assert_allclose(fd, ec.gap_change(p, beta)[n + 1], atol=2e-7 * scale * 10**n)


def test_third_derivative_richardson_tight():
    p = ec.EccentricCam(0.08, 0.06, "roller", 0.01)
    beta = np.linspace(0.1, 6.2, 23)

    def d2(b):
        return ec.piston_travels(p, b)[2]

    def cd(h):
        return (d2(beta + h) - d2(beta - h)) / (2 * h)

    rich = (4 * cd(1e-3) - cd(2e-3)) / 3
    np.testing.assert_allclose(rich, ec.piston_travels(p, beta)[3], rtol=0, atol=1e-10)


def test_pressure_angle_against_contact_normal():
    rng = np.random.default_rng(7)
    for follower in ("knife_edge", "roller"):
        p = _random_params(rng, follower)
        for b in rng.uniform(0, 2 * np.pi, 10):
            z = _independent(p, b, "left")
            cx, cy = _disc_centre(p.eccentricity, b, "left")
            # follower point (contact or roller centre) on the axis at x = z + Rc
            px = z + p.contact_radius
            normal = np.array([px - cx, 0.0 - cy])  # from the disc centre through the point
            want = np.arctan2(-normal[1], normal[0])
            assert ec.pressure_angle(p, b) == pytest.approx(want, abs=1e-9)
        assert ec.pressure_angle_max(p) == pytest.approx(
            np.arcsin(p.eccentricity / p.contact_radius)
        )
    flat = ec.EccentricCam(0.08, 0.04, "flat")
    assert ec.pressure_angle_max(flat) == 0.0
    np.testing.assert_array_equal(ec.pressure_angle(flat, np.linspace(0, 6, 7)), 0.0)


# --------------------------------------------------------------------------------------------
# stated properties (paper section 2)
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("follower", ["knife_edge", "roller"])
def test_gap_change_properties(follower):
    rng = np.random.default_rng(21)
    p = _random_params(rng, follower)
    b = np.linspace(0, 2 * np.pi, 3601)
    D = ec.gap_change(p, b)[0]
    assert np.all(D <= 0.0)
    a = rng.uniform(0, np.pi, 50)
    half = np.pi / 2
    np.testing.assert_allclose(ec.gap_change(p, half + a)[0], ec.gap_change(p, half - a)[0],
                               atol=1e-16)  # fmt: skip
    np.testing.assert_allclose(ec.gap_change(p, a + np.pi)[0], ec.gap_change(p, a)[0], atol=1e-16)
    assert b[np.argmin(D[: len(b) // 2 + 1])] == pytest.approx(half)
    k = np.arange(-3, 4) * np.pi
    np.testing.assert_allclose(ec.gap_change(p, k)[0], 0.0, atol=1e-16)
    dmin, bmin = ec.gap_change_extreme(p)
    assert dmin == pytest.approx(D.min(), rel=1e-12)
    assert bmin == pytest.approx(half)
    # x'(beta) = x(180 deg - beta)
    dec, dec_m = ec.decomposition(p, a), ec.decomposition(p, np.pi - a)
    np.testing.assert_allclose(dec["x_right"], dec_m["x"], atol=1e-14)


def test_gap_change_grows_with_lambda():
    R = 0.08
    b = np.linspace(0.05, np.pi - 0.05, 50)
    lams = np.linspace(0.05, 0.95, 19)
    mags = np.array([np.abs(ec.gap_change(ec.EccentricCam(R, lam * R), b)[0]) for lam in lams])
    assert np.all(np.diff(mags, axis=0) > 0)
    deltas = np.array([np.abs(ec.decomposition(ec.EccentricCam(R, lam * R), b)["delta"])
                       for lam in lams])  # fmt: skip
    assert np.all(np.diff(deltas, axis=0) > 0)


def test_roller_between_flat_and_knife_edge():
    R, e = 0.08, 0.05
    b = np.linspace(0.01, 2 * np.pi - 0.01, 400)
    b = b[np.abs(np.sin(b)) > 1e-3]
    knife = ec.gap_change(ec.EccentricCam(R, e), b)[0]
    flat = ec.gap_change(ec.EccentricCam(R, e, "flat"), b)[0]
    prev = knife
    for r in (0.005, 0.02, 0.08):
        roller = ec.gap_change(ec.EccentricCam(R, e, "roller", r), b)[0]
        assert np.all(flat > roller) and np.all(roller > prev)
        prev = roller


def test_stroke_and_period():
    rng = np.random.default_rng(3)
    for follower in ec.FOLLOWERS:
        p = _random_params(rng, follower)
        b = np.linspace(0, 2 * np.pi, 20001)
        z = ec.piston_travels(p, b)[0]
        for k in (0, 1):
            assert z[k].max() - z[k].min() == pytest.approx(ec.piston_stroke(p), rel=1e-9)
            assert z[k].max() == pytest.approx(p.eccentricity, rel=1e-12)
        assert ec.period(p) == pytest.approx(2 * np.pi)
        a = rng.uniform(0, 2 * np.pi, 20)
        for x, y in zip(ec.piston_travels(p, a), ec.piston_travels(p, a + ec.period(p)),
                        strict=True):  # fmt: skip
            np.testing.assert_allclose(x, y, atol=1e-15)


def test_shapes_0d_1d_3d():
    p = ec.EccentricCam(0.08, 0.03, "roller", 0.01)
    rng = np.random.default_rng(0)
    b3 = rng.uniform(0, 7, (2, 3, 4))
    m3 = ec.motion(p, b3)
    assert isinstance(m3, Motion)
    assert m3.q.shape == (2, 2, 3, 4) and m3.d3q.shape == (2, 2, 3, 4)
    assert m3.members == ("left piston", "right piston") and m3.unit == "m"
    m1 = ec.motion(p, b3.ravel())
    for a3, a1 in zip((m3.q, m3.dq, m3.d2q, m3.d3q), (m1.q, m1.dq, m1.d2q, m1.d3q), strict=True):
        np.testing.assert_array_equal(a3.reshape(2, -1), a1)
    m0 = ec.motion(p, b3[1, 2, 3])
    assert m0.q.shape == (2,)
    np.testing.assert_array_equal(m0.dq, m3.dq[:, 1, 2, 3])
    for key, val in ec.decomposition(p, b3).items():
        assert val.shape == b3.shape, key
    assert ec.gap_change(p, 0.3)[0].shape == ()
    assert ec.pressure_angle(p, b3).shape == b3.shape


# --------------------------------------------------------------------------------------------
# parameters
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("kwargs", "name", "text"),
    [
        ({"disc_radius": 0.0, "eccentricity": 0.01}, "disc_radius", "disc_radius > 0"),
        ({"disc_radius": -0.1, "eccentricity": 0.01}, "disc_radius", "disc_radius > 0"),
        ({"disc_radius": 0.08, "eccentricity": 0.0}, "eccentricity", "0 mm < eccentricity"),
        ({"disc_radius": 0.08, "eccentricity": 0.08}, "eccentricity",
         "eccentricity must be below disc_radius"),
        ({"disc_radius": 0.08, "eccentricity": 0.1}, "eccentricity",
         "eccentricity must be below disc_radius"),
        ({"disc_radius": 0.08, "eccentricity": 0.04, "follower": "mushroom"}, "follower",
         "knife_edge"),
        ({"disc_radius": 0.08, "eccentricity": 0.04, "roller_radius": -0.01}, "roller_radius",
         ">= 0"),
        ({"disc_radius": 0.08, "eccentricity": 0.04, "follower": "roller"}, "roller_radius",
         "follower = 'roller'"),
    ],
)  # fmt: skip
def test_parameter_errors(kwargs, name, text):
    with pytest.raises(ParameterError) as info:
        ec.EccentricCam(**kwargs)
    assert info.value.name == name
    assert name in str(info.value) and text in str(info.value)
    with pytest.raises(ParameterError) as info:
        build_params(ec.EccentricCam, "drive", kwargs)
    assert f"drive.{name}" in str(info.value)


def test_params_defaults_and_properties():
    p = ec.EccentricCam(0.08, 0.04)
    assert p.follower == "knife_edge" and p.lam == pytest.approx(0.5)
    assert p.contact_radius == pytest.approx(0.08)
    assert ec.EccentricCam(0.08, 0.04, "roller", 0.01).contact_radius == pytest.approx(0.09)
    assert np.isinf(ec.EccentricCam(0.08, 0.04, "flat").contact_radius)


# --------------------------------------------------------------------------------------------
# study
# --------------------------------------------------------------------------------------------
def _cfg(**drive):
    d = {"type": "eccentric_cam", "disc_radius": 0.08, "eccentricity": 0.04,
         "follower": "knife_edge", "roller_radius": 0.0}  # fmt: skip
    d.update(drive)
    return {"drive": d, "machine": {"device_length": 1.0}, "loads": {}, "run": {"points": 361}}


REQUIRED = ("gap_change_min_mm", "gap_change_min_ratio", "gap_change_to_length", "piston_stroke_mm")


@pytest.mark.parametrize(("follower", "r"), [("knife_edge", 0.0), ("roller", 0.012), ("flat", 0.0)])
def test_study_summary(follower, r):
    R, e, L = 0.08, 0.04, 1.0
    res = evaluate(_cfg(follower=follower, roller_radius=r))
    s = res.summary
    for key in REQUIRED + ("lambda", "gap_change_min_angle_deg", "piston_velocity_peak_mm_per_rad",
                           "piston_accel_peak_mm_per_rad2", "pressure_angle_max_deg"):  # fmt: skip
        assert key in s
        assert isinstance(s[key], (float, int, str))
    Rc = {"knife_edge": R, "roller": R + r, "flat": np.inf}[follower]
    want = 0.0 if follower == "flat" else 2 * (np.sqrt(Rc**2 - e**2) - Rc)
    assert s["gap_change_min_mm"] == pytest.approx(want * 1e3, abs=1e-12)
    assert s["gap_change_min_ratio"] == pytest.approx(want / e, abs=1e-12)
    assert s["gap_change_to_length"] == pytest.approx(abs(want) / L, abs=1e-15)
    assert s["piston_stroke_mm"] == pytest.approx(80.0)
    assert s["lambda"] == pytest.approx(0.5)
    assert s["gap_change_min_angle_deg"] == pytest.approx(90.0)
    # peaks against the travel written out here, differentiated numerically on a fine grid
    b = np.linspace(0, 2 * np.pi, 200001)
    if follower == "flat":
        z = e * np.cos(b)
    else:
        z = np.sqrt(Rc**2 - e**2 * np.sin(b) ** 2) + e * np.cos(b) - Rc
    dz = np.gradient(z, b)
    d2z = np.gradient(dz, b)
    assert s["piston_velocity_peak_mm_per_rad"] == pytest.approx(np.abs(dz).max() * 1e3, rel=1e-6)
    assert s["piston_accel_peak_mm_per_rad2"] == pytest.approx(np.abs(d2z[5:-5]).max() * 1e3,
                                                               rel=1e-5)  # fmt: skip
    want_pa = 0.0 if follower == "flat" else np.degrees(np.arcsin(e / Rc))
    assert s["pressure_angle_max_deg"] == pytest.approx(want_pa, abs=1e-12)
    assert set(res.headline) <= set(s)
    assert list(res.columns)[0] == "beta_deg"
    assert all(np.shape(v) == (361,) for v in res.columns.values())
    assert res.columns["beta_deg"][-1] == pytest.approx(360.0)
    np.testing.assert_allclose(res.columns["gap_change_mm"],
                               res.columns["z_left_mm"] + res.columns["z_right_mm"])  # fmt: skip


def test_study_knife_edge_accel_peak_closed_form():
    """z''(0) = -e (1 + lambda) is the largest |z''| for lambda = 0.5 (derived by hand)."""
    s = evaluate(_cfg()).summary
    assert s["piston_accel_peak_mm_per_rad2"] == pytest.approx(40.0 * 1.5, rel=1e-12)


def test_study_errors_name_config_keys():
    with pytest.raises(ParameterError, match=r"drive\.eccentricity"):
        evaluate(_cfg(eccentricity=0.09))
    with pytest.raises(ParameterError, match=r"drive\.roller_radius"):
        evaluate(_cfg(follower="roller"))
    cfg = _cfg()
    cfg["machine"]["device_length"] = 0.0
    with pytest.raises(ParameterError, match=r"machine\.device_length"):
        evaluate(cfg)


@pytest.mark.slow
def test_study_plot_writes_pngs(tmp_path):
    res = evaluate(_cfg(follower="roller", roller_radius=0.01))
    paths = res.write_figures(tmp_path)
    assert len(paths) == 8  # 4 of the drive (paper) + 3 of the reactor + the forces
    for p in paths:
        assert p.exists() and p.suffix == ".png" and p.stat().st_size > 1000
        assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


# --------------------------------------------------------------------------------------------
# one source of defaults: the schema
# --------------------------------------------------------------------------------------------
def _schema_defaults() -> dict:
    """Every default of the [drive], [machine] and [cam] sections, parsed by the schema (SI)."""
    required = {"type": "eccentric_cam", "disc_radius": "80 mm", "eccentricity": "40 mm"}
    drive = schema.EccentricDrive.model_validate(required).model_dump()
    out = {k: v for k, v in drive.items() if k not in required}
    out.update(schema.EccentricMachine().model_dump())
    out.update(schema.DiscCamSection().model_dump())
    return out


#: Dataclass fields that are not config keys (derived from the drive by the reactor module).
_NOT_IN_SCHEMA = {"gap_change_min", "piston_stroke"}


def _default_mismatches(classes, want) -> list:
    """(class, field, dataclass default, schema default) for every defaulted field that
    differs from the schema or has no schema key."""
    out = []
    for cls in classes:
        for f in dataclasses.fields(cls):
            if f.default is dataclasses.MISSING or f.name in _NOT_IN_SCHEMA:
                continue
            if f.name not in want or f.default != want[f.name]:
                out.append((cls.__name__, f.name, f.default, want.get(f.name)))
    return out


def test_dataclass_defaults_equal_the_schema_defaults():
    want = _schema_defaults()
    assert _default_mismatches((ec.EccentricCam, op.OpposedPiston), want) == []
    # every defaulted field was compared: follower, roller_radius and seven reactor fields
    compared = [
        f.name
        for cls in (ec.EccentricCam, op.OpposedPiston)
        for f in dataclasses.fields(cls)
        if f.default is not dataclasses.MISSING and f.name not in _NOT_IN_SCHEMA
    ]
    assert len(compared) == 9 and set(compared) <= set(want)


def test_default_comparison_reports_a_mismatch():
    @dataclasses.dataclass(frozen=True)
    class Wrong:
        bore: float = 0.04  # schema: 50 mm
        fluid: str = "gas"
        unknown: float = 1.0  # no schema key

    got = _default_mismatches((Wrong,), _schema_defaults())
    assert got == [("Wrong", "bore", 0.04, 0.05), ("Wrong", "unknown", 1.0, None)]


def test_drive_params_without_optional_keys_take_the_schema_defaults():
    want = _schema_defaults()
    p = drive_params({"drive": {"disc_radius": 0.08, "eccentricity": 0.04}})
    assert p.follower == want["follower"] and p.roller_radius == want["roller_radius"]


def test_study_keeps_the_pistons_motion_on_the_column_grid():
    res = evaluate(_cfg())
    m = res.motion
    assert isinstance(m, Motion)
    assert m.members == ("left piston", "right piston") and m.unit == "m"
    np.testing.assert_allclose(np.degrees(m.theta), res.columns["beta_deg"], rtol=0, atol=1e-12)
    assert m.theta[-1] - m.theta[0] == pytest.approx(2 * np.pi, rel=1e-15)
    np.testing.assert_array_equal(m.q[0] * 1e3, res.columns["z_left_mm"])
    np.testing.assert_array_equal(m.q[1] * 1e3, res.columns["z_right_mm"])
    np.testing.assert_array_equal(m.dq[0] * 1e3, res.columns["z_left_velocity_mm_per_rad"])
