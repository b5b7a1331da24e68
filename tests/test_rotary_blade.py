"""Rotary-blade engine on the rhomboid lever-cam drive, against independent models written here.

The independent models: chamber volumes from the blade positions sorted around the rotor
and the shoelace area of a fine polygon of each annular sector; member torques by
finite-difference virtual work on those volumes; the isothermal work by the closed form
m R T ln(V_end / V_start) per stroke, with the turning points found here by brentq on the
term-by-term Fourier series; the paper's eq. 31/34 for the linear model; the kinetic energy
differentiated along a time grid built here.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.optimize import brentq

from rotorkin.analysis import torque as at
from rotorkin.core.errors import ParameterError
from rotorkin.drives import evaluate
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.drives.rhomboid_cam import study as study
from rotorkin.machines import rotary_blade as rb

TWO_PI = 2.0 * np.pi
PSI_MIN = np.radians(40.0)
T_BLADE = np.radians(10.0)
RI, RO, W = 0.03, 0.09, 0.05
K = 0.5 * (RO**2 - RI**2) * W  # 1.8e-4 m^3/rad, written out for the expected values


def machine(**kw):
    args = {
        "blade_thickness": T_BLADE,
        "inner_radius": RI,
        "outer_radius": RO,
        "axial_width": W,
        "blades_per_pair": 2,
        "inertia_shaft": 0.01,
        "inertia_blade_pair_1": 0.005,
        "inertia_blade_pair_2": 0.005,
    }
    args.update(kw)
    return rb.RotaryBlade(**args)


def gas(p=2e5, th=900.0, tc=330.0):
    return rb.IsothermalGas(p, th, tc)


def cfg(model="linear", drive=None, machine_keys=None, loads=None, run=None):
    d = {"type": "rhomboid_cam", "link_length": 0.12, "psi_min": PSI_MIN, "a": [], "b": []}
    d.update(drive or {})
    m = {
        "blades_per_pair": 2,
        "blade_thickness": T_BLADE,
        "inner_radius": RI,
        "outer_radius": RO,
        "axial_width": W,
        "inertia_shaft": 0.01,
        "inertia_blade_pair_1": 0.005,
        "inertia_blade_pair_2": 0.005,
        "speed_fluctuation": 0.02,
    }
    m.update(machine_keys or {})
    ld = {
        "torque_high": 100.0,
        "torque_low": 40.0,
        "pressure_model": model,
        "charge_pressure": 2e5,
        "hot_temperature": 900.0,
        "cold_temperature": 330.0,
    }
    ld.update(loads or {})
    r = {"points": 361, "speed": 1500 * np.pi / 30}
    r.update(run or {})
    return {"title": "", "drive": d, "machine": m, "loads": ld, "run": r}


# --- independent models -------------------------------------------------------------------
def psi_ref(alpha, psi_min, a=(), b=(), order=0):
    """Eq. 13 summed term by term (a_1, b_1 from eq. 15), or its derivative of ``order``."""
    alpha = np.asarray(alpha, dtype=float)
    a1 = np.pi / 2 - psi_min - sum(a)
    b1 = -sum((2 * i + 3) * bk for i, bk in enumerate(b))
    terms = [(1, a1, b1)] + [(2 * i + 3, ak, 0.0) for i, ak in enumerate(a)]
    terms += [(2 * i + 3, 0.0, bk) for i, bk in enumerate(b)]
    out = np.full(alpha.shape, np.pi / 2 if order == 0 else 0.0)
    for k, ak, bk in terms:
        w = 2 * k
        # d^n/dx^n of cos(w x) = w^n cos(w x + n pi/2), of sin(w x) = w^n sin(w x + n pi/2)
        ph = order * np.pi / 2
        out = out + w**order * (ak * np.cos(w * alpha + ph) + bk * np.sin(w * alpha + ph))
    return out


def _polygon_area(gamma, n):
    t = np.linspace(0.0, gamma, n)
    x = np.concatenate([RO * np.cos(t), RI * np.cos(t[::-1])])
    y = np.concatenate([RO * np.sin(t), RI * np.sin(t[::-1])])
    cross = x * np.roll(y, -1) - y * np.roll(x, -1)  # per edge first: no cancellation
    return 0.5 * abs(np.sum(cross))


def sector_volume(gamma):
    """Annular sector of angle gamma, R_i..R_o, width W: shoelace area of fine polygons
    (chords for arcs, error ~ (gamma/n)^2), Richardson-extrapolated from n and 2n edges."""
    a1, a2 = _polygon_area(gamma, 50_001), _polygon_area(gamma, 100_001)
    return (4 * a2 - a1) / 3 * W


def chambers_ref(phi1, phi2, B, t):
    """Blades of both pairs sorted counter-clockwise from pair 2's first blade; the chamber
    between two neighbours spans their angular distance less one blade thickness."""
    blades = [((phi2 + TWO_PI * m / B - phi2) % TWO_PI, 2) for m in range(B)]
    blades += [((phi1 + TWO_PI * m / B - phi2) % TWO_PI, 1) for m in range(B)]
    blades.sort()
    angles = [blades[i + 1][0] - blades[i][0] for i in range(2 * B - 1)]
    angles.append(TWO_PI - blades[-1][0])
    return [p for _, p in blades], [sector_volume(g - t) for g in angles]


def turning_points(psi_min, a, b):
    """0, the roots of psi' in (0, pi) (brentq on the series' derivative) and pi."""
    g = np.linspace(1e-7, np.pi - 1e-7, 40001)
    d = psi_ref(g, psi_min, a, b, 1)
    i = np.flatnonzero(np.sign(d[:-1]) * np.sign(d[1:]) < 0)
    roots = [brentq(lambda x: psi_ref(x, psi_min, a, b, 1), g[j], g[j + 1], xtol=1e-15) for j in i]
    return np.array([0.0, *roots, np.pi])


def gauss_pieces(f, nodes, n=80):
    """integral of f over [nodes[0], nodes[-1]] by n-point Gauss-Legendre on each piece."""
    x, w = np.polynomial.legendre.leggauss(n)
    total = 0.0
    for lo, hi in zip(nodes[:-1], nodes[1:], strict=True):
        half = 0.5 * (hi - lo)
        total += float(np.sum(f(0.5 * (hi + lo) + half * x) * w) * half)
    return total


def isothermal_work_ref(psi_min, a, b, B, t, p_charge, th, tc):
    """Work per half turn of all chambers: m R T ln(V_end/V_start) per stroke, written here."""
    z = turning_points(psi_min, a, b)
    psi = psi_ref(z, psi_min, a, b)
    even = K * (psi - t)  # chambers psi - t and 2 pi/B - psi - t (checked against geometry)
    odd = K * (TWO_PI / B - psi - t)
    total = 0.0
    for v in (even, odd):
        g = np.linspace(0, np.pi, 20001)
        pg = psi_ref(g, psi_min, a, b)
        vmax = K * max(np.max(pg) - t, 0) if v is even else K * (TWO_PI / B - np.min(pg) - t)
        mR = p_charge * vmax / tc
        for v0, v1 in zip(v[:-1], v[1:], strict=True):
            total += B * mR * (th if v1 > v0 else tc) * np.log(v1 / v0)
    return total


MONOTONE = [((), ()), ((0.1,), (0.0,)), ((-0.1,), (0.05,)), ((0.05,), (-0.03,)), ((-0.109,), ())]


# --- geometry -----------------------------------------------------------------------------
@pytest.mark.parametrize(("B", "psi_min", "t"), [(2, PSI_MIN, T_BLADE), (2, 0.5, 0.0),
                                                (3, np.radians(75), np.radians(6)),
                                                (1, 0.4, 0.3)])  # fmt: skip
def test_volumes_against_sorted_blades_and_polygon_areas(B, psi_min, t):
    rng = np.random.default_rng(B)
    m = machine(blades_per_pair=B, blade_thickness=t)
    params = rc.RhomboidCam(0.12, psi_min, (0.03,), (0.01,))
    al = rng.uniform(-4, 4, 6)
    q = rc.motion(params, al).q
    v = rb.chamber_volumes(m, q)
    assert v.shape == (2 * B, 6)
    for n in range(al.size):
        pairs, ref = chambers_ref(q[0, n], q[1, n], B, t)
        assert pairs == [2, 1] * B  # blades alternate: pair 2, pair 1, ...
        np.testing.assert_allclose(v[:, n], ref, rtol=1e-10)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_volume_derivatives_by_finite_differences(seed):
    rng = np.random.default_rng(seed)
    params = rc.RhomboidCam(0.12, rng.uniform(0.5, 1.0), (rng.uniform(-0.05, 0.05),), ())
    m = machine(blades_per_pair=int(rng.integers(1, 3)), blade_thickness=0.2)
    al = rng.uniform(-4, 4, 20)
    h = 1e-5
    mo, mp, mm = (rc.motion(params, x) for x in (al, al + h, al - h))
    for k, (d_now, lo, hi) in enumerate(
        ((mo.dq, mm.q, mp.q), (mo.d2q, mm.dq, mp.dq), (mo.d3q, mm.d2q, mp.d2q))
    ):
        f = rb.chamber_volumes if k == 0 else rb.chamber_volume_derivative
        fd = (f(m, hi) - f(m, lo)) / (2 * h)
        np.testing.assert_allclose(rb.chamber_volume_derivative(m, d_now), fd, atol=1e-9 * 10**k)


def test_volume_gradient_by_virtual_displacement_of_each_pair():
    """dV_j/dq_i against central differences of the geometric volumes (V is linear in q)."""
    m = machine(blades_per_pair=2)
    q = np.array([1.3, 0.1])
    h = 1e-2
    grad = rb.volume_gradient(m)
    for i in range(2):
        e = np.zeros(2)
        e[i] = h
        vp = chambers_ref(*(q + e), 2, T_BLADE)[1]
        vm = chambers_ref(*(q - e), 2, T_BLADE)[1]
        np.testing.assert_allclose(grad[i], (np.array(vp) - np.array(vm)) / (2 * h), rtol=1e-8)


def test_member_torques_by_virtual_work_and_shaft_torque():
    rng = np.random.default_rng(7)
    m = machine(blades_per_pair=3, blade_thickness=0.05)
    params = rc.RhomboidCam(0.12, np.radians(75), (), ())
    al = rng.uniform(0, np.pi, 5)
    mo = rc.motion(params, al)
    p = rng.uniform(1e5, 3e6, (6, al.size))
    M = rb.gas_member_torques(m, p)
    h = 1e-2
    for n in range(al.size):
        for i in range(2):
            e = np.zeros(2)
            e[i] = h
            vp = np.array(chambers_ref(*(mo.q[:, n] + e), 3, 0.05)[1])
            vm = np.array(chambers_ref(*(mo.q[:, n] - e), 3, 0.05)[1])
            assert M[i, n] == pytest.approx(np.dot(p[:, n], (vp - vm) / (2 * h)), rel=1e-7)
    # virtual work on the shaft: sum M_i q_i' = sum p_j dV_j/dtheta
    T = at.shaft_torque_from_members(M, mo.dq)
    np.testing.assert_allclose(T, at.gas_torque(p, rb.chamber_volume_derivative(m, mo.dq)),
                               rtol=1e-12, atol=1e-9)  # fmt: skip
    # a uniform pressure gives no torque
    np.testing.assert_allclose(rb.gas_member_torques(m, np.full(6, 5e5)), 0.0, atol=1e-9)


def test_shapes_0d_1d_3d():
    m = machine()
    params = rc.RhomboidCam(0.12, PSI_MIN, (0.02,), ())
    al3 = np.random.default_rng(1).uniform(0, 3, (2, 3, 4))
    mo3 = rc.motion(params, al3)
    v3 = rb.chamber_volumes(m, mo3.q)
    dv3 = rb.chamber_volume_derivative(m, mo3.dq)
    st3 = rb.chamber_strokes(m, rc.stroke_direction(PSI_MIN, (0.02,), (), al3))
    g = gas()
    charge = rb.gas_charge(g, np.full(4, 4e-4))
    p3 = rb.isothermal_pressure(g, charge, v3, st3)
    M3 = rb.gas_member_torques(m, p3)
    assert v3.shape == dv3.shape == p3.shape == (4, 2, 3, 4) and M3.shape == (2, 2, 3, 4)
    flat = al3.reshape(-1)
    mo1 = rc.motion(params, flat)
    v1 = rb.chamber_volumes(m, mo1.q)
    st1 = rb.chamber_strokes(m, rc.stroke_direction(PSI_MIN, (0.02,), (), flat))
    p1 = rb.isothermal_pressure(g, charge, v1, st1)
    np.testing.assert_array_equal(v3.reshape(4, -1), v1)
    np.testing.assert_array_equal(p3.reshape(4, -1), p1)
    np.testing.assert_array_equal(M3.reshape(2, -1), rb.gas_member_torques(m, p1))
    mo0 = rc.motion(params, al3[1, 2, 3])
    v0 = rb.chamber_volumes(m, mo0.q)
    assert v0.shape == (4,)
    np.testing.assert_array_equal(v0, v3[:, 1, 2, 3])
    assert rb.gas_member_torques(m, p3[:, 1, 2, 3]).shape == (2,)
    st = study.machine_state(params, m, study.Loads("isothermal", 0, 0, g, charge), al3)
    assert st.torque.shape == (2, 3, 4) and st.pressure.shape == (4, 2, 3, 4)


def test_volume_range_and_displacement():
    m = machine()
    vmin, vmax = rb.volume_range(m, PSI_MIN, np.pi - PSI_MIN)
    np.testing.assert_allclose(vmin, K * np.radians(30.0), rtol=1e-14)
    np.testing.assert_allclose(vmax, K * np.radians(130.0), rtol=1e-14)
    # monotone law: psi travels 4 (psi_max - psi_min) per revolution; 4 chambers x 2 strokes
    travel = 4 * (np.pi - 2 * PSI_MIN)
    assert rb.displacement_per_rev(m, travel) == pytest.approx(8 * (vmax[0] - vmin[0]), rel=1e-14)


# --- pressure model and work --------------------------------------------------------------
def test_isothermal_pressure_hot_in_expansion_cold_in_compression():
    g = gas(1e6, 900.0, 300.0)
    charge = rb.gas_charge(g, np.array([4e-4, 4e-4]))  # m R at 10 bar, 4e-4 m^3, 300 K
    np.testing.assert_allclose(charge, 1e6 * 4e-4 / 300.0)
    v = np.array([[4e-4, 1e-4], [4e-4, 1e-4]])
    p = rb.isothermal_pressure(g, charge, v, np.array([[-1, -1], [1, 1]]))
    np.testing.assert_allclose(p, [[1e6, 4e6], [3e6, 12e6]], rtol=1e-14)
    w = rb.isothermal_stroke_work(charge[0], 900.0, 1e-4, 4e-4)
    assert w == pytest.approx(1e6 * 4e-4 * 3 * np.log(4), rel=1e-14)


@pytest.mark.parametrize(("a", "b"), MONOTONE)
def test_isothermal_energy_balance_monotone_laws(a, b):
    """integral_0^pi T d alpha (T through member torques x phi_i') = sum over chambers of
    m R (T_h - T_c) ln(V_max/V_min), one cycle per chamber per half turn. GL on the monotone
    halves [0, pi/2], [pi/2, pi] (written here). Tol 1e-11 relative."""
    c = cfg("isothermal", drive={"a": list(a), "b": list(b)})
    res = evaluate(c)
    m = machine()
    params = rc.RhomboidCam(0.12, PSI_MIN, a, b)
    g = gas()
    charge = rb.gas_charge(g, np.full(4, K * (np.pi - PSI_MIN - T_BLADE)))
    loads = study.Loads("isothermal", 0.0, 0.0, g, charge)
    work = gauss_pieces(lambda x: study.machine_state(params, m, loads, x).torque,
                        [0.0, np.pi / 2, np.pi])  # fmt: skip
    vmax, vmin = K * (np.pi - PSI_MIN - T_BLADE), K * (PSI_MIN - T_BLADE)
    closed = 4 * (2e5 * vmax / 330.0) * (900.0 - 330.0) * np.log(vmax / vmin)
    assert work == pytest.approx(closed, rel=1e-11)
    s = res.summary
    assert s["indicated_work_per_period_J"] == pytest.approx(closed, rel=1e-11)
    assert s["indicated_work_J"] == pytest.approx(2 * closed, rel=1e-11)
    assert s["isothermal_work_closed_form_per_rev_J"] == pytest.approx(2 * closed, rel=1e-12)
    assert s["mean_torque_Nm"] == pytest.approx(2 * closed / TWO_PI, rel=1e-11)


@pytest.mark.parametrize(("B", "psi_min", "a", "b", "t"), [
    (2, PSI_MIN, (0.4,), (), T_BLADE),  # psi swings back and forth: 3 strokes each way
    (3, np.radians(75), (0.02,), (0.01,), np.radians(6)),
    (1, 0.5, (), (0.02,), 0.2),
])  # fmt: skip
def test_isothermal_energy_balance_any_law(B, psi_min, a, b, t):
    """The same for laws with extra turning points and B != 2: the chain of isothermal strokes
    between turning points found here by brentq. Tol 1e-10 relative."""
    c = cfg("isothermal", drive={"psi_min": psi_min, "a": list(a), "b": list(b)},
            machine_keys={"blades_per_pair": B, "blade_thickness": t})  # fmt: skip
    s = evaluate(c).summary
    ref = isothermal_work_ref(psi_min, a, b, B, t, 2e5, 900.0, 330.0)
    assert s["indicated_work_per_period_J"] == pytest.approx(ref, rel=1e-10)
    assert s["isothermal_work_closed_form_per_rev_J"] == pytest.approx(2 * ref, rel=1e-10)
    # and through machine_state integrated here over the pieces between the turning points
    m = machine(blades_per_pair=B, blade_thickness=t)
    params = rc.RhomboidCam(0.12, psi_min, a, b)
    lo, _, hi, _ = rc.psi_extremes(psi_min, a, b)
    charge = rb.gas_charge(gas(), rb.volume_range(m, lo, hi)[1])
    loads = study.Loads("isothermal", 0.0, 0.0, gas(), charge)
    work = gauss_pieces(lambda x: study.machine_state(params, m, loads, x).torque,
                        turning_points(psi_min, a, b))  # fmt: skip
    assert work == pytest.approx(ref, rel=1e-10)


def test_isothermal_pv_loop_area_from_columns():
    """The closed integral of p dV over the p-V loop of chamber 1 (trapezoid on the csv columns,
    isochoric steps add nothing), against m R (T_h - T_c) ln(V_max/V_min). Tol 1e-6 (grid)."""
    res = evaluate(cfg("isothermal", run={"points": 40001}))
    v = res.columns["chamber1_volume_cm3"] * 1e-6
    p = res.columns["chamber1_pressure_bar"] * 1e5
    loop = np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(v))
    vmax, vmin = K * np.radians(130), K * np.radians(30)
    assert loop == pytest.approx(2e5 * vmax / 330 * 570 * np.log(vmax / vmin), rel=1e-6)


@pytest.mark.parametrize(("a", "b"), MONOTONE)
def test_linear_model_work_is_delta_m_delta_psi(a, b):
    """Paper eq. 31 (first harmonic) and eq. 34 (1st + 3rd harmonic, monotone laws): work per
    half turn A = (M1 - M2)(psi_max - psi_min), here through the machine path (member torques
    (M_1, -M_1) times phi_i') and the study. Tol 1e-12 relative."""
    res = evaluate(cfg("linear", drive={"a": list(a), "b": list(b)}))
    s = res.summary
    A = 60.0 * (np.pi - 2 * PSI_MIN)
    assert s["indicator_work_J"] == pytest.approx(A, rel=1e-12)  # the drive's key, per half turn
    assert s["indicated_work_per_period_J"] == pytest.approx(A, rel=1e-12)
    assert s["indicated_work_J"] == pytest.approx(2 * A, rel=1e-12)
    assert s["mean_torque_Nm"] == pytest.approx(A / np.pi, rel=1e-12)
    assert s["mean_torque_Nm"] == pytest.approx(s["mean_shaft_torque_Nm"], rel=1e-12)
    params = rc.RhomboidCam(0.12, PSI_MIN, a, b)
    loads = study.Loads("linear", 100.0, 40.0)
    work = gauss_pieces(lambda x: study.machine_state(params, machine(), loads, x).torque,
                        [0.0, np.pi / 2, np.pi])  # fmt: skip
    assert work == pytest.approx(A, rel=1e-12)


def test_linear_model_member_torques():
    params = rc.RhomboidCam(0.12, PSI_MIN, (0.05,), ())
    al = np.linspace(0.01, 3.1, 50)
    st = study.machine_state(params, machine(), study.Loads("linear", 100.0, 40.0), al)
    psi, dpsi = psi_ref(al, PSI_MIN, (0.05,)), psi_ref(al, PSI_MIN, (0.05,), order=1)
    x = (psi - np.pi / 2) / (np.pi / 2 - PSI_MIN)
    m1 = np.where(dpsi > 0, 30.0 - 70.0 * x, -30.0 - 70.0 * x)  # eq. 29 as read
    np.testing.assert_allclose(st.members[0], m1, atol=1e-12)
    np.testing.assert_allclose(st.members[1], -m1, atol=1e-12)
    np.testing.assert_allclose(st.torque, m1 * dpsi, atol=1e-10)
    assert st.pressure is None


# --- time domain, inertia, flywheel -------------------------------------------------------
def test_instantaneous_power_balance_with_speed_profile():
    """omega x (shaft torque with inertia) = sum_j p_j dV_j/dt - d/dt(kinetic energy), with a
    speed profile; KE = 1/2 (J_s omega^2 + J_1 phi_1dot^2 + J_2 phi_2dot^2) from the csv's
    blade speeds, differentiated along the time grid t = integral d alpha / omega. Tol 1e-6 of
    the power scale (second-order differences on 40001 points)."""
    speed = list(150.0 + 12.0 * np.sin(np.arange(9) * TWO_PI / 9) + 4.0 * np.cos(np.arange(9)))
    res = evaluate(cfg("isothermal", run={"points": 40001, "speed": speed},
                       machine_keys={"inertia_blade_pair_2": 0.008}))  # fmt: skip
    c = res.columns
    al = np.radians(c["alpha_deg"])
    w = c["shaft_speed_rpm"] * np.pi / 30
    p_gas = sum(c[f"chamber{j}_pressure_bar"] * 1e5 * c[f"chamber{j}_dvolume_cm3_per_rad"] * 1e-6
                for j in range(1, 5)) * w  # fmt: skip
    ke = 0.5 * (0.01 * w**2 + 0.005 * c["blade_pair_1_speed_rad_per_s"] ** 2
                + 0.008 * c["blade_pair_2_speed_rad_per_s"] ** 2)  # fmt: skip
    t = np.concatenate([[0.0], np.cumsum(0.5 * (1 / w[1:] + 1 / w[:-1]) * np.diff(al))])
    dke = np.gradient(ke, t, edge_order=2)
    p_net = w * c["shaft_torque_with_inertia_Nm"]
    scale = np.max(np.abs(p_gas))
    np.testing.assert_allclose(p_net[1:-1], (p_gas - dke)[1:-1], atol=1e-6 * scale)
    # and the gas power is the shaft torque without inertia times omega
    np.testing.assert_allclose(w * c["shaft_torque_Nm"], p_gas, atol=1e-9 * scale)


def test_flywheel_and_time_domain_first_harmonic():
    """Linear model, first-harmonic law, constant speed, J_1 = J_2 = J: written here,
    psi' = -2h sin 2a, psi'' = -4h cos 2a (h = pi/2 - psi_min); inertia torque
    J psi' psi''/2 omega^2 (peak 2 h^2 J omega^2); J_eq mean = J_s + 2J (1 + h^2/2);
    Delta E by a 200001-point trapezoid here. Tol 1e-7 relative (the study uses 20001)."""
    w = 1500 * np.pi / 30
    s = evaluate(cfg("linear")).summary
    h = np.pi / 2 - PSI_MIN
    J, Js = 0.005, 0.01
    al = np.linspace(0, np.pi, 200001)
    d1, d2 = -2 * h * np.sin(2 * al), -4 * h * np.cos(2 * al)
    psi = np.pi / 2 + h * np.cos(2 * al)
    x = (psi - np.pi / 2) / h
    m1 = np.where(d1 > 0, 30.0 - 70.0 * x, -30.0 - 70.0 * x)
    steady = m1 * d1 - J * d1 * d2 / 2 * w**2
    e = np.concatenate([[0], np.cumsum(0.5 * (steady[1:] + steady[:-1]) * np.diff(al))])
    e -= e[-1] * al / np.pi
    d_e = e.max() - e.min()
    j_mean = Js + 2 * J * (1 + h**2 / 2)
    assert s["inertia_torque_peak_Nm"] == pytest.approx(2 * h**2 * J * w**2, rel=1e-12)
    assert s["equivalent_inertia_mean_kgm2"] == pytest.approx(j_mean, rel=1e-9)
    assert s["energy_fluctuation_J"] == pytest.approx(d_e, rel=1e-7)
    assert s["speed_fluctuation_without_flywheel"] == pytest.approx(d_e / (j_mean * w**2), 1e-7)
    assert s["flywheel_inertia_kgm2"] == pytest.approx(d_e / (0.02 * w**2) - j_mean, rel=1e-7)
    # time-domain peaks: |phi'| <= 1 + h, |phi''| = 2h, |phi'''| = 4h, at constant speed
    assert s["blade_pair_1_speed_peak_rad_per_s"] == pytest.approx((1 + h) * w, rel=1e-12)
    assert s["blade_pair_2_accel_peak_rad_per_s2"] == pytest.approx(2 * h * w**2, rel=1e-12)
    assert s["blade_pair_1_jerk_peak_rad_per_s3"] == pytest.approx(4 * h * w**3, rel=1e-12)
    assert s["shaft_speed_mean_rpm"] == pytest.approx(1500.0, rel=1e-14)
    # torque ripple of the loads' torque M_1 psi' over the period
    gas_t = m1 * d1
    ripple = (gas_t.max() - gas_t.min()) / (60.0 * (np.pi - 2 * PSI_MIN) / np.pi)
    assert s["torque_ripple"] == pytest.approx(ripple, rel=1e-6)


def test_zero_inertia_gives_infinite_speed_fluctuation():
    s = evaluate(cfg(machine_keys={"inertia_shaft": 0.0, "inertia_blade_pair_1": 0.0,
                                   "inertia_blade_pair_2": 0.0})).summary  # fmt: skip
    assert s["speed_fluctuation_without_flywheel"] == float("inf")
    assert s["inertia_torque_peak_Nm"] == 0.0
    assert s["flywheel_inertia_kgm2"] > 0.0


# --- study --------------------------------------------------------------------------------
def test_study_summary_example_geometry():
    res = evaluate(cfg("isothermal"))
    s = res.summary
    vmax, vmin = K * np.radians(130), K * np.radians(30)
    expected = {
        "chamber_volume_max_cm3": vmax * 1e6,
        "chamber_volume_min_cm3": vmin * 1e6,
        "chamber_swept_volume_cm3": (vmax - vmin) * 1e6,
        "compression_ratio_geometric": 13 / 3,
        "displacement_cm3_per_rev": 8 * (vmax - vmin) * 1e6,
        "sector_volume_cm3_per_rad": K * 1e6,
        "blade_thickness_max_deg": 40.0,
        "pressure_max_bar": 2.0 * 13 / 3 * 900 / 330,
        "pressure_min_bar": 2.0,
        "gas_charge_J_per_K": 4 * 2e5 * vmax / 330,
        "indicated_power_kW": 2 * 4 * 2e5 * vmax / 330 * 570 * np.log(13 / 3) * 25 * 1e-3,
    }
    for key, value in expected.items():
        assert s[key] == pytest.approx(value, rel=1e-12), key
    assert s["chambers"] == 4 and s["blades_per_pair"] == 2
    assert s["pressure_model"] == "isothermal"
    json.dumps(s)
    for key in res.headline:
        assert key in s
    assert set(res.columns) == set(res.column_docs)
    cols = res.columns
    assert all(v.shape == (361,) for v in cols.values())
    al = np.radians(cols["alpha_deg"])
    psi = psi_ref(al, PSI_MIN)
    np.testing.assert_allclose(cols["chamber1_volume_cm3"], K * (psi - T_BLADE) * 1e6, rtol=1e-12)
    np.testing.assert_allclose(cols["chamber2_volume_cm3"], K * (np.pi - psi - T_BLADE) * 1e6,
                               rtol=1e-12)  # fmt: skip
    np.testing.assert_allclose(cols["chamber3_volume_cm3"], cols["chamber1_volume_cm3"])
    np.testing.assert_allclose(cols["shaft_torque_with_inertia_Nm"],
                               cols["shaft_torque_Nm"] - cols["inertia_torque_Nm"])  # fmt: skip


def test_study_keeps_the_drive_outputs():
    """Every key of the drive-only study is still there with the paper's values."""
    s = evaluate(cfg("isothermal")).summary
    assert s["indicator_work_J"] == pytest.approx(60.0 * (np.pi - 2 * PSI_MIN), rel=1e-12)
    assert s["psi_min_deg"] == pytest.approx(40.0)
    assert s["profile_radius_min_mm"] == pytest.approx(120 * np.cos(np.radians(70)), rel=1e-12)


def test_study_fills_missing_machine_and_loads_keys():
    c = {"drive": cfg()["drive"], "machine": {}, "loads": {}, "run": {"points": 181}}
    s = evaluate(c).summary
    assert s["pressure_model"] == "linear"
    assert s["chamber_volume_max_cm3"] == pytest.approx(K * np.radians(130) * 1e6, rel=1e-12)
    assert s["shaft_speed_mean_rpm"] == pytest.approx(3000.0)


@pytest.mark.slow
@pytest.mark.parametrize(("model", "count"), [("linear", 8), ("isothermal", 9)])
def test_plots(tmp_path, model, count):
    paths = evaluate(cfg(model)).write_figures(tmp_path)
    assert len(paths) == count
    assert ("fig06_pv_diagram.png" in [p.name for p in paths]) == (model == "isothermal")
    for p in paths:
        assert p.stat().st_size > 10_000
        assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.slow
def test_plots_other_blade_counts(tmp_path):
    for B, psi_min, t in ((3, np.radians(75), 0.1), (1, PSI_MIN, 0.1)):
        c = cfg("isothermal", drive={"psi_min": psi_min},
                machine_keys={"blades_per_pair": B, "blade_thickness": t})  # fmt: skip
        out = tmp_path / str(B)
        out.mkdir()
        assert len(evaluate(c).write_figures(out)) == 9  # with the forces


# --- bad input ----------------------------------------------------------------------------
@pytest.mark.parametrize(("kwargs", "name", "text"), [
    ({"inner_radius": 0.09}, "inner_radius", "< outer_radius = 90 mm"),
    ({"inner_radius": -0.01}, "inner_radius", "0 mm <="),
    ({"outer_radius": 0.0}, "outer_radius", "> 0 mm"),
    ({"axial_width": 0.0}, "axial_width", "> 0 mm"),
    ({"axial_width": float("nan")}, "axial_width", "> 0 mm"),
    ({"blade_thickness": -0.01}, "blade_thickness", "0 deg <="),
    ({"blade_thickness": np.pi / 2}, "blade_thickness", "< 90 deg"),
    ({"blades_per_pair": 0}, "blades_per_pair", ">= 1"),
    ({"blades_per_pair": 2.0}, "blades_per_pair", "integer"),
    ({"inertia_shaft": -1.0}, "inertia_shaft", ">= 0"),
    ({"inertia_blade_pair_2": float("inf")}, "inertia_blade_pair_2", ">= 0"),
])  # fmt: skip
def test_machine_errors(kwargs, name, text):
    with pytest.raises(ParameterError) as info:
        machine(**kwargs)
    assert info.value.name == name
    assert str(info.value).startswith(f"{name} = ") and text in str(info.value)


@pytest.mark.parametrize(("kwargs", "name"), [
    ({"charge_pressure": 0.0}, "charge_pressure"),
    ({"hot_temperature": -5.0}, "hot_temperature"),
    ({"cold_temperature": float("nan")}, "cold_temperature"),
])  # fmt: skip
def test_gas_errors(kwargs, name):
    args = {"charge_pressure": 1e6, "hot_temperature": 900.0, "cold_temperature": 300.0, **kwargs}
    with pytest.raises(ParameterError) as info:
        rb.IsothermalGas(**args)
    assert info.value.name == name


def test_swing_errors_name_the_admissible_maximum():
    m = machine(blade_thickness=np.radians(45))
    with pytest.raises(ParameterError) as info:
        rb.check_swing(m, PSI_MIN, np.pi - PSI_MIN)
    assert info.value.name == "blade_thickness"
    assert "< 40 deg" in str(info.value)
    # B = 3: the odd chambers 120 deg - psi - t close before psi_max = 140 deg
    with pytest.raises(ParameterError) as info:
        rb.check_swing(machine(blades_per_pair=3), PSI_MIN, np.pi - PSI_MIN)
    assert info.value.name == "blades_per_pair" and "<= 2" in str(info.value)
    # psi from 75 to 105 deg, B = 3: t < min(75, 120 - 105) = 15 deg
    with pytest.raises(ParameterError) as info:
        rb.check_swing(machine(blades_per_pair=3, blade_thickness=np.radians(16)),
                       np.radians(75), np.radians(105))  # fmt: skip
    assert info.value.name == "blade_thickness" and "< 15 deg" in str(info.value)
    rb.check_swing(machine(blades_per_pair=3, blade_thickness=np.radians(14.9)),
                   np.radians(75), np.radians(105))  # fmt: skip


@pytest.mark.parametrize(("model", "section", "key", "value"), [
    ("linear", "machine", "inner_radius", 0.1),
    ("linear", "machine", "outer_radius", -0.1),
    ("linear", "machine", "axial_width", 0.0),
    ("linear", "machine", "blade_thickness", np.radians(40)),
    ("linear", "machine", "blades_per_pair", 3),
    ("linear", "machine", "inertia_blade_pair_1", -0.1),
    ("linear", "machine", "speed_fluctuation", 1.5),
    ("isothermal", "loads", "charge_pressure", -1.0),
    ("isothermal", "loads", "hot_temperature", 0.0),
    ("isothermal", "loads", "cold_temperature", -3.0),
    ("linear", "run", "speed", [100.0, -1.0, 100.0]),
])  # fmt: skip
def test_study_errors_name_the_config_key(model, section, key, value):
    c = cfg(model)
    c[section][key] = value
    with pytest.raises(ParameterError, match=rf"^{section}\.{key} = "):
        evaluate(c)
