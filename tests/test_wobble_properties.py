"""Property tests of the wobble-cam drive: broadcasting, periodicity, alpha <-> pi - alpha.

Independent models: scalar calls (for the broadcast results), the explicit roller
position of eq. 7-8 projected on the yz plane (for the rotor angles), the
dataclass constructors (for the vectorised admissibility) and a shift of the
shaft angle (for the symmetry of the roller-axis angle).

Symmetry of the roller axis angle: with ``alpha* = pi - alpha`` (60 deg <-> 120 deg)
and the linear spin law ``varphi = n theta``, the rollers of group 1 at ``alpha*``
sit where those of group 2 at ``alpha`` sit a quarter spin turn later (minus a
half turn of the plate), so the two rotors exchange their roles:

    Phi_1*(theta) = Phi_2(theta + pi/(2n)) - pi/(2n) - pi
    Phi_2*(theta) = Phi_1(theta + pi/(2n)) - pi/(2n)

and every derivative of Phi_1* (Phi_2*) is that of Phi_2 (Phi_1) at
``theta + pi/(2n)``. The slider angle mirrors: ``alpha'*(varphi) = pi - alpha'(varphi + pi/2)``,
so chamber kinds A and B exchange their laws (``delta_A* = delta_B`` a quarter spin
turn later, at equal piston width).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from rotorkin.core.errors import ParameterError
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.machines import twin_rotor as tr

D = np.pi / 180.0
FAST = settings(max_examples=40, deadline=None)

tilts = st.floats(2.0 * D, 60.0 * D)
alphas = st.floats(70.0 * D, 110.0 * D)
spins = st.sampled_from([-2.0, -1.5, -1.0, -0.5, 0.5, 1.0, 2.0, 3.0])
angles = st.floats(-4.0 * np.pi, 4.0 * np.pi)
theta_arrays = hnp.arrays(
    float,
    hnp.array_shapes(min_dims=0, max_dims=3, max_side=4),
    elements=st.floats(-4.0 * np.pi, 4.0 * np.pi),
)


def _drive(tilt, alpha, n, pistons=4):
    """A drive with a tilt admissible at alpha (capped below the eq. 20 limit)."""
    lim = float(wc.max_plate_tilt(alpha, pistons))
    return wc.WobbleCam(min(tilt, 0.95 * lim), alpha, n, 0.06, pistons)


def _close(a, b, tol=1e-11):
    np.testing.assert_allclose(a, b, rtol=tol, atol=tol)


# --------------------------------------------------------------------------------------------
# broadcasting
# --------------------------------------------------------------------------------------------
@FAST
@given(tilts, alphas, spins, theta_arrays)
def test_motion_of_any_shape_equals_scalar_calls(tilt, alpha, n, theta):
    """motion(params, theta) of a 0-d, 1-d, ... 3-d theta: shape (2, *theta.shape), elementwise."""
    p = _drive(tilt, alpha, n)
    m = wc.motion(p, theta)
    for arr in (m.q, m.dq, m.d2q, m.d3q):
        assert arr.shape == (2, *np.shape(theta))
    flat = np.ravel(theta)
    for i, t in enumerate(flat):
        s = wc.motion(p, float(t))
        for arr, ref in ((m.q, s.q), (m.dq, s.dq), (m.d2q, s.d2q), (m.d3q, s.d3q)):
            _close(arr.reshape(2, -1)[:, i], ref)


@FAST
@given(
    st.lists(st.tuples(tilts, alphas), min_size=1, max_size=5),
    hnp.arrays(float, st.integers(1, 6), elements=angles),
    spins,
)
def test_parameter_arrays_broadcast_against_angle_arrays(designs, theta, n):
    """Parameters of shape (k, 1) against angles (m,) give (2, k, m), equal to per-design calls."""
    ps = [_drive(t, a, n) for t, a in designs]
    tilt = np.array([p.plate_tilt for p in ps])[:, None]
    alpha = np.array([p.roller_axis_angle for p in ps])[:, None]
    q, d1, d2, d3 = wc.rotor_angles_from_spin(tilt, alpha, n, theta)
    assert q.shape == (2, len(ps), theta.size)
    slider = wc.slider_angle(tilt, alpha, n * theta)
    assert slider.shape == (len(ps), theta.size)
    for i, p in enumerate(ps):
        ref = wc.rotor_angles(p, theta)
        for got, want in zip((q, d1, d2, d3), ref, strict=True):
            _close(got[:, i], want)
        _close(slider[i], ref[0][1] - ref[0][0])


@FAST
@given(
    st.lists(
        st.tuples(tilts, alphas, st.sampled_from([2, 4, 6, 8]), st.floats(1.5, 40.0)),
        min_size=1,
        max_size=6,
    )
)
def test_closed_forms_broadcast_over_designs(designs):
    """Tilt limit, gaps, zero-width ratio and piston width of arrays = the dataclass path."""
    rows = []
    for tilt, alpha, n_p, eps in designs:
        lo, hi = (float(x) for x in wc.roller_axis_angle_limits(n_p))
        a = min(max(alpha, lo + 1e-3), hi - 1e-3)
        p = _drive(tilt, a, -2.0, n_p)
        rows.append((p, max(eps, 1.01 * wc.min_compression_ratio(p))))
    tilt = np.array([p.plate_tilt for p, _ in rows])
    alpha = np.array([p.roller_axis_angle for p, _ in rows])
    n_p = np.array([p.pistons_per_rotor for p, _ in rows])
    eps = np.array([e for _, e in rows])
    gaps = wc.chamber_gaps(tilt, alpha, n_p)
    beta = wc.piston_width(gaps, eps)
    lim = wc.max_plate_tilt(alpha, n_p)
    ratio = wc.zero_width_ratio(gaps)
    for i, (p, e) in enumerate(rows):
        layout = wc.piston_layout(p, e)
        assert beta[i] == pytest.approx(layout.piston_width, rel=1e-13, abs=1e-15)
        assert lim[i] == pytest.approx(float(wc.max_plate_tilt(p.roller_axis_angle, n_p[i])))
        assert ratio[i] == pytest.approx(wc.min_compression_ratio(p), rel=1e-13)
    # the chamber angles of arrays: extremes of kind A at the slider extremes
    amax, amin = wc.slider_angle_extremes(tilt, alpha)
    da, db = wc.chamber_angles(beta, np.stack([amin, amax]), pistons=n_p)
    for i, (p, e) in enumerate(rows):
        layout = wc.piston_layout(p, e)
        _close(da[:, i], [layout.chamber_a_min, layout.chamber_a_max])
        _close(db[:, i], [layout.chamber_b_max, layout.chamber_b_min])


@FAST
@given(
    st.floats(-0.2, 1.6),
    st.floats(20.0 * D, 160.0 * D),
    st.sampled_from([-2.0, -0.7, 0.0, 0.5, 1.25, np.nan]),
    st.sampled_from([0.06, 0.0, -0.01]),
    st.sampled_from([4, 2, 6, 3, 0]),
)
def test_vectorised_admissibility_names_what_the_constructor_names(tilt, alpha, n, r, n_p):
    """violation() of one design is 0 iff WobbleCam accepts it, else the field it names."""
    code = wc.violation(
        np.array([tilt, tilt]), np.array([alpha, alpha]), n, r, np.array([n_p, n_p])
    )
    assert code.shape == (2,) and code[0] == code[1]
    try:
        wc.WobbleCam(tilt, alpha, n, r, n_p)
    except ParameterError as exc:
        assert code[0] > 0 and wc.CHECKED[code[0] - 1] == exc.name
    else:
        assert code[0] == 0


@FAST
@given(
    st.floats(0.5, 30.0),
    st.sampled_from([4, 3, 6]),
    st.sampled_from(["rectangular", "circular"]),
    st.floats(-0.01, 0.1),
    st.floats(-0.01, 0.1),
    st.floats(-1e-6, 1e-5),
    st.floats(-0.1, 1.1),
)
def test_machine_admissibility_names_what_the_constructor_names(eps, n_p, section, ri, d, vc, cs):
    """twin_rotor.violation() of one design is 0 iff TwinRotor accepts it, else that field."""
    kw = dict(
        compression_ratio=eps,
        pistons_per_rotor=n_p,
        section=section,
        inner_radius=ri,
        section_diameter=d,
        clearance_volume=vc,
        speed_fluctuation=cs,
    )
    fields = {f: getattr(tr.TwinRotor, f, None) for f in tr.CHECKED}
    full = {f: v for f, v in fields.items() if v is not None} | kw
    code = int(tr.violation(**full))
    try:
        tr.TwinRotor(**kw)
    except ParameterError as exc:
        assert code > 0 and tr.CHECKED[code - 1] == exc.name
    else:
        assert code == 0


# --------------------------------------------------------------------------------------------
# independent geometry and periodicity
# --------------------------------------------------------------------------------------------
@FAST
@given(tilts, alphas, spins, hnp.arrays(float, st.integers(1, 8), elements=angles))
def test_rotor_angle_is_the_projected_roller_direction(tilt, alpha, n, theta):
    """Phi_k = atan2(y, z) of roller k's centre in the fixed frame (eq. 7-8), modulo 2 pi."""
    p = _drive(tilt, alpha, n)
    q = wc.motion(p, theta).q
    r = wc.roller_positions(p, theta)  # (4, 3, m); rollers 0 (group 1) and 2 (group 2)
    for k, roller in ((0, 0), (1, 2)):
        direct = np.arctan2(r[roller, 1], r[roller, 2])
        diff = np.angle(np.exp(1j * (q[k] - direct)))
        _close(diff, 0.0, 1e-10)


@FAST
@given(
    tilts,
    alphas,
    spins,
    hnp.arrays(float, st.integers(1, 6), elements=angles),
    st.lists(st.floats(-0.05, 0.05), max_size=3),
    st.lists(st.floats(-0.05, 0.05), max_size=3),
)
def test_motion_repeats_after_one_period(tilt, alpha, n, theta, sa, sb):
    """Phi_k(theta + 2 pi) = Phi_k(theta) + 2 pi (1 + n); every derivative is 2 pi periodic."""
    base = _drive(tilt, alpha, n)
    p = wc.WobbleCam(base.plate_tilt, alpha, n, 0.06, 4, tuple(sa), tuple(sb))
    T = wc.period(p)
    a, b = wc.motion(p, theta), wc.motion(p, theta + T)
    _close(b.q - a.q, 2.0 * np.pi * (1.0 + n) * np.ones_like(a.q), 1e-9)
    for x, y in ((a.dq, b.dq), (a.d2q, b.d2q), (a.d3q, b.d3q)):
        _close(y, x, 1e-8)


# --------------------------------------------------------------------------------------------
# symmetry alpha <-> pi - alpha
# --------------------------------------------------------------------------------------------
@FAST
@given(st.floats(1.0 * D, 44.0 * D), spins, hnp.arrays(float, st.integers(1, 6), elements=angles))
def test_roller_axis_angles_60_and_120_deg_exchange_the_rotors(tilt, n, theta):
    """At alpha = 60 and 120 deg the rotors swap roles a quarter spin turn apart (module doc)."""
    p60 = wc.WobbleCam(tilt, 60.0 * D, n, 0.06, 4)
    p120 = wc.WobbleCam(tilt, 120.0 * D, n, 0.06, 4)
    shift = np.pi / (2.0 * n)
    m120 = wc.motion(p120, theta)
    m60 = wc.motion(p60, theta + shift)
    _close(m120.q[0], m60.q[1] - shift - np.pi, 1e-10)
    _close(m120.q[1], m60.q[0] - shift, 1e-10)
    for a, b in ((m120.dq, m60.dq), (m120.d2q, m60.d2q), (m120.d3q, m60.d3q)):
        _close(a[0], b[1], 1e-9)
        _close(a[1], b[0], 1e-9)


@FAST
@given(st.floats(1.0 * D, 44.0 * D), hnp.arrays(float, st.integers(1, 6), elements=angles))
def test_slider_angle_mirrors_and_chamber_kinds_swap(tilt, varphi):
    """alpha'(120 deg; varphi) = pi - alpha'(60 deg; varphi + pi/2); delta_A and delta_B swap."""
    s120 = wc.slider_angle(tilt, 120.0 * D, varphi)
    s60 = wc.slider_angle(tilt, 60.0 * D, varphi + 0.5 * np.pi)
    _close(s120, np.pi - s60, 1e-10)
    beta = 0.1
    a120, b120 = wc.chamber_angles(beta, s120)
    a60, b60 = wc.chamber_angles(beta, s60)
    _close(a120, b60, 1e-10)
    _close(b120, a60, 1e-10)


@FAST
@given(
    st.sampled_from([-2.0, -0.5, 0.5, 1.0]),
    st.lists(st.floats(-1.5, 1.5), min_size=1, max_size=3),
    st.lists(st.floats(-1.5, 1.5), max_size=2),
)
def test_spin_correction_check_of_arrays_is_the_constructors(n, sa, sb):
    """A non-monotone spin correction: violation() of an array of spin ratios names spin_a
    exactly where the constructor refuses; the lowest rate is that of the sampled law."""
    ns = np.array([n, -n, 2.0 * n])
    code = wc.violation(45 * D, np.pi / 2, ns, 0.06, 4, tuple(sa), tuple(sb))
    grid = np.linspace(0.0, 2.0 * np.pi, 4097)
    for i, ni in enumerate(ns):
        rate = wc.spin_angle(ni, sa, sb, grid)[1] * np.sign(ni)
        assert float(wc.slowest_spin(ni, sa, sb)) == pytest.approx(rate.min(), abs=1e-12)
        try:
            wc.WobbleCam(45 * D, np.pi / 2, float(ni), 0.06, 4, tuple(sa), tuple(sb))
        except ParameterError as exc:
            assert exc.name == "spin_a" and wc.CHECKED[code[i] - 1] == "spin_a"
        else:
            assert code[i] == 0


@FAST
@given(
    hnp.arrays(float, st.integers(1, 3), elements=st.sampled_from([-2.0, -1.0, 0.5, 1.5])),
    st.lists(st.floats(-0.05, 0.05), max_size=3),  # sum k |a_k| < 0.5: monotone
    hnp.arrays(float, st.integers(1, 5), elements=angles),
)
def test_spin_angle_broadcasts_spin_ratio_arrays(ns, sa, theta):
    """spin_angle of ratios (k, 1) against angles (m,) equals the dataclass law per ratio."""
    got = wc.spin_angle(ns[:, None], sa, (), theta)
    for i, n in enumerate(ns):
        ref = wc.spin_law(wc.WobbleCam(45 * D, np.pi / 2, float(n), 0.06, 4, tuple(sa)), theta)
        for g, r in zip(got, ref, strict=True):
            _close(g[i], r)
