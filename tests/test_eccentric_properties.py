"""Property tests of the double eccentric-disc drive and the reactor on it (hypothesis).

Exact statements tested (``A(beta) = sqrt(Rc^2 - e^2 sin^2 beta) - Rc``, the additional
part, ``Rc`` the contact radius: R, R + r, or infinite for a flat face, where A = 0):

* ``z(beta) = A(beta) + e cos beta`` and ``z'(beta) = A(beta) - e cos beta`` (eq. 1, 3);
* periodicity: ``z``, ``z'`` have period 2 pi (the drive's period); the gap change
  ``Delta = z + z' = 2 A`` has period pi;
* evenness: ``z(-beta) = z(beta)``, ``z'(-beta) = z'(beta)``, ``Delta(-beta) = Delta(beta)``;
  their first and third derivatives are odd, the second even;
* half turn: ``z'(beta) = z(beta + pi)`` (the right disc is the left one half a turn on);
* about 90 deg: ``Delta(pi - beta) = Delta(beta)`` (symmetric), ``z(pi - beta) = z'(beta)``,
  and the difference ``z - z' = 2 e cos beta`` is odd about 90 deg:
  ``(z - z')(pi - beta) = -(z - z')(beta)``.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq

from rotorkin.core.batch import Designs
from rotorkin.core.errors import ParameterError
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.drives.eccentric_cam import reactor as rx
from rotorkin.drives.eccentric_cam import sweep as batch
from rotorkin.drives.eccentric_cam.study import evaluate
from rotorkin.io.config import load_config
from rotorkin.machines import opposed_piston as op
from rotorkin.sweep.engine import reason_keys

SETTINGS = settings(max_examples=40, deadline=None)

radii = st.floats(0.01, 0.5)
ratios = st.floats(0.02, 0.98)
followers = st.sampled_from(ec.FOLLOWERS)
roller_shares = st.floats(0.05, 1.0)
angles = st.floats(-20.0, 20.0)


@st.composite
def drives(draw):
    """An admissible drive: R, e = lambda R, a follower and (for a roller) r > 0."""
    R, lam, follower = draw(radii), draw(ratios), draw(followers)
    r = draw(roller_shares) * R if follower == "roller" else 0.0
    return ec.EccentricCam(R, lam * R, follower, r)


def _close(a, b, scale):
    np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * scale)


def _same(a, b, scale=None):
    """Equal up to the last bits: NumPy evaluates sin, cos, sqrt of arrays with SIMD code
    that may differ by an ulp from the scalar path."""
    b = np.asarray(b, dtype=float)
    scale = np.max(np.abs(b)) if scale is None else scale
    np.testing.assert_allclose(a, b, rtol=1e-14, atol=1e-14 * scale)


# --------------------------------------------------------------------------------------------
# against an independent model
# --------------------------------------------------------------------------------------------
def _intersection_travel(p, beta, side):
    """Follower point on its axis (y = 0), by root finding on the circle of radius Rc about
    the disc centre +-e (cos beta, sin beta); a flat face: the disc's support in +x."""
    sign = 1.0 if side == 0 else -1.0
    cx, cy = sign * p.eccentricity * np.cos(beta), sign * p.eccentricity * np.sin(beta)
    rc = float(p.contact_radius)
    if not np.isfinite(rc):
        return cx
    x = brentq(lambda x: (x - cx) ** 2 + cy**2 - rc**2, cx, cx + 1.01 * rc, xtol=1e-15, rtol=1e-15)
    return x - rc


@SETTINGS
@given(drives(), angles)
def test_travels_equal_the_intersection_of_axis_and_pitch_circle(p, beta):
    z = ec.piston_travels(p, beta)[0]
    for side in (0, 1):
        _close(z[side], _intersection_travel(p, beta, side), p.disc_radius)


# --------------------------------------------------------------------------------------------
# broadcasting
# --------------------------------------------------------------------------------------------
@SETTINGS
@given(
    st.lists(drives(), min_size=1, max_size=4),
    st.sampled_from([(), (5,), (2, 3, 2)]),
    st.integers(0, 2**32 - 1),
)
def test_parameter_arrays_against_angle_arrays_equal_scalar_calls(designs, shape, seed):
    """Parameters (n, 1, ...) against angles of shape () / (m,) / (a, b, c)."""
    beta = np.random.default_rng(seed).uniform(-7.0, 7.0, shape)
    n = len(designs)
    lead = (n,) + (1,) * len(shape)

    def field(name):
        return np.array([getattr(d, name) for d in designs]).reshape(lead)

    arr = ec.EccentricCam(*(field(k) for k in ("disc_radius", "eccentricity", "follower",
                                                "roller_radius")))  # fmt: skip
    q = ec.piston_travels(arr, beta)
    m = ec.motion(arr, beta)
    gap = ec.gap_change(arr, beta)
    mu = ec.pressure_angle(arr, beta)
    dec = ec.decomposition(arr, beta)
    assert q[0].shape == (2, n, *shape) and m.q.shape == (2, n, *shape)
    assert gap[0].shape == (n, *shape) and mu.shape == (n, *shape)
    assert np.shape(ec.gap_change_extreme(arr)[0]) == lead
    e = max(d.eccentricity for d in designs)
    for i, d in enumerate(designs):
        one = ec.piston_travels(d, beta)
        for k in range(4):
            _same(q[k][:, i], one[k], e)
            _same(gap[k][i], ec.gap_change(d, beta)[k], e)
        _same(m.q[:, i], one[0], e)
        _same(mu[i], ec.pressure_angle(d, beta), 1.0)
        for key, v in ec.decomposition(d, beta).items():
            _same(dec[key][i], v, 1.0)
        _same(ec.gap_change_extreme(arr)[0].reshape(n)[i], ec.gap_change_extreme(d)[0], e)
        _same(ec.pressure_angle_max(arr).reshape(n)[i], ec.pressure_angle_max(d), 1.0)
        _same(ec.piston_stroke(arr).reshape(n)[i], ec.piston_stroke(d), e)


@SETTINGS
@given(
    st.lists(drives(), min_size=1, max_size=3),
    st.lists(st.sampled_from(op.FLUIDS), min_size=3, max_size=3),
    st.integers(0, 2**32 - 1),
)
def test_reactor_of_parameter_arrays_equals_scalar_reactors(designs, fluids, seed):
    rng = np.random.default_rng(seed)
    n = len(designs)
    beta = rng.uniform(0.0, 2 * np.pi, 7)
    machine = {
        # at least the piston stroke 2 e (the reactor's admissible lengths)
        "device_length": 2.0 * np.array([d.eccentricity for d in designs])
        + rng.uniform(0.0, 2.0, n),
        "bore": rng.uniform(0.01, 0.1, n),
        "fluid": np.array(fluids[:n]),
        "initial_pressure": rng.uniform(1e5, 1e6, n),
        "polytropic_exponent": rng.uniform(1.0, 1.4, n),
        "bulk_modulus": rng.uniform(1e9, 2e9, n),
    }

    def col(v):
        return np.asarray(v)[:, None]

    names = ("disc_radius", "eccentricity", "follower", "roller_radius")
    arr = ec.EccentricCam(*(col([getattr(d, k) for d in designs]) for k in names))
    reactor = rx.opposed_piston(arr, **{k: col(v) for k, v in machine.items()})
    m = ec.motion(arr, beta)
    v = op.enclosed_volume(reactor, m)
    p = op.pressure(reactor, m)
    ext = op.volume_extremes(reactor)
    forms = rx.closed_forms(arr, reactor)
    for i, d in enumerate(designs):
        one = rx.opposed_piston(d, **{k: val[i] for k, val in machine.items()})
        mi = ec.motion(d, beta)
        for k in range(4):
            _same(v[k][0, i], op.enclosed_volume(one, mi)[k][0], np.max(np.abs(v[0])))
        pi = op.pressure(one, mi)
        _same(p[0][0, i], pi[0][0])
        _same(p[1][0, i], pi[1][0], np.max(np.abs(p[0])))
        _same(ext[0][i, 0], op.volume_extremes(one)[0])
        _same(ext[1][i, 0], op.volume_extremes(one)[1])
        for key, val in rx.closed_forms(d, one).items():
            got = np.broadcast_to(forms[key], (n, 1))[i, 0]
            if key == "cavitation":
                assert got == val
            else:
                _same(got, val, max(abs(float(val)), 1e-300))


# --------------------------------------------------------------------------------------------
# periodicity and symmetry
# --------------------------------------------------------------------------------------------
@SETTINGS
@given(drives(), angles)
def test_periods(p, beta):
    assert ec.period(p) == 2 * np.pi
    z, zt = ec.piston_travels(p, beta), ec.piston_travels(p, beta + ec.period(p))
    d, dh = ec.gap_change(p, beta), ec.gap_change(p, beta + np.pi)
    e = p.eccentricity
    for k in range(4):
        _close(zt[k], z[k], 100 * e)
        _close(dh[k], d[k], 100 * e)


@SETTINGS
@given(drives(), angles)
def test_evenness_and_oddness(p, beta):
    """z, z', Delta even in beta; their 1st and 3rd derivatives odd, the 2nd even."""
    z, zm = ec.piston_travels(p, beta), ec.piston_travels(p, -beta)
    d, dm = ec.gap_change(p, beta), ec.gap_change(p, -beta)
    e = p.eccentricity
    for k, sign in enumerate((1.0, -1.0, 1.0, -1.0)):
        _close(zm[k], sign * z[k], 10 * e)
        _close(dm[k], sign * d[k], 10 * e)


@SETTINGS
@given(drives(), angles)
def test_half_turn_and_quarter_turn_relations(p, beta):
    e = p.eccentricity
    z = ec.piston_travels(p, beta)[0]
    # the right piston is the left one half a turn later
    _close(z[1], ec.piston_travels(p, beta + np.pi)[0][0], 10 * e)
    # about 90 deg: Delta symmetric, z(pi - beta) = z'(beta), z - z' odd
    zr = ec.piston_travels(p, np.pi - beta)[0]
    _close(ec.gap_change(p, np.pi - beta)[0], ec.gap_change(p, beta)[0], 10 * e)
    _close(zr[0], z[1], 10 * e)
    _close(zr[0] - zr[1], -(z[0] - z[1]), 10 * e)
    # the difference is the harmonic part alone, the sum twice the additional part
    _close(z[0] - z[1], 2 * e * np.cos(beta), 10 * e)
    _close(z[0] + z[1], 2 * ec.additional_travel(p.contact_radius, e, beta)[0], 10 * e)


@SETTINGS
@given(drives())
def test_gap_change_extreme_is_the_minimum_over_a_turn(p):
    beta = np.linspace(0.0, 2 * np.pi, 2001)
    dmin, at = ec.gap_change_extreme(p)
    gap = ec.gap_change(p, beta)[0]
    assert dmin <= gap.min() + 1e-15 * p.disc_radius
    _close(dmin, ec.gap_change(p, at)[0], p.disc_radius)
    # closed form of eq. 5 at 90 deg, by plain geometry: the follower point where the
    # disc centre stands e off the axis
    rc = p.contact_radius
    want = 0.0 if not np.isfinite(rc) else 2 * (np.sqrt(rc**2 - p.eccentricity**2) - rc)
    _close(dmin, want, p.disc_radius)


# --------------------------------------------------------------------------------------------
# admissibility written once
# --------------------------------------------------------------------------------------------
values = st.floats(-0.1, 0.3) | st.sampled_from([0.0, np.nan, np.inf])
any_follower = st.sampled_from([*ec.FOLLOWERS, "wheel"])


@SETTINGS
@given(st.lists(st.tuples(values, values, any_follower, values), min_size=1, max_size=6))
def test_one_admissibility_for_one_design_and_many(rows):
    R, e, f, r = (np.array(c) for c in zip(*rows, strict=True))
    bad = ec.invalid_parameter(R, e, f, r)
    for i, row in enumerate(rows):
        assert bad[i] == ec.invalid_parameter(*row)
        if bad[i]:
            with pytest.raises(ParameterError) as err:
                ec.EccentricCam(*row)
            assert err.value.name == bad[i]
        else:
            ec.EccentricCam(*row)
    if bad.any():
        with pytest.raises(ParameterError) as err:
            ec.EccentricCam(R, e, f, r)
        assert err.value.name == bad[bad != ""][0]


@pytest.fixture(scope="module")
def example():
    cfg, _, _ = load_config(None, "eccentric-reactor", [])
    return cfg


def test_batch_reasons_name_what_the_study_names(example):
    rng = np.random.default_rng(7)
    n = 40
    table = {
        "drive.disc_radius": rng.choice([0.08, -0.01, 0.05], n),
        "drive.eccentricity": rng.choice([0.04, 0.07, 0.0], n),
        "drive.follower": rng.choice(np.array(ec.FOLLOWERS), n),
        "drive.roller_radius": rng.choice([0.0, 0.01, -0.01], n),
        "machine.bore": rng.choice([0.05, 0.0], n),
        "machine.bulk_modulus": rng.choice([1.5e9, -1.0], n),
    }
    keys = reason_keys("eccentric_cam")
    code = {k: i for i, k in enumerate(keys)}
    got = batch.reasons(Designs(example, table, n), code)
    for i in range(n):
        cfg = {s: dict(v) if isinstance(v, dict) else v for s, v in example.items()}
        for key, col in table.items():
            section, name = key.split(".")
            cfg[section][name] = col[i].item()
        try:
            evaluate(cfg)
            want = "ok"
        except ParameterError as exc:
            want = exc.name
        assert keys[got[i]] == want, (i, cfg["drive"], cfg["machine"])
    assert len(set(got.tolist())) >= 4  # several reasons were exercised
