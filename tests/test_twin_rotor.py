"""Twin-rotor engine on the wobble-cam drive: volumes, four-stroke timing, pressures, torques.

Independent models written here: rotor angles from the paper's rotation matrices
(eq. 2-5), explicit piston faces placed around the cylinder, chamber volumes by
numeric integration over the section (scipy quad / dblquad), the polytropes as
ODEs, the work per stroke by quadrature, the shaft angle in time by an ODE of the
speed profile, kinetic energy from finite differences of the rotor angles in time.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy import integrate, optimize

from rotorkin.analysis import engine_cycle as ec
from rotorkin.analysis.timing import shaft_speed
from rotorkin.analysis.torque import equivalent_inertia, inertia_torque, kinetic_energy
from rotorkin.cli import main
from rotorkin.core.errors import ConfigError, ParameterError
from rotorkin.drives.wobble_cam import engine as eng
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.drives.wobble_cam import study as study
from rotorkin.io.config import load_config
from rotorkin.machines import fuel_air as fa
from rotorkin.machines import twin_rotor as tr

D = np.pi / 180.0


# --------------------------------------------------------------------------------------------
# independent models
# --------------------------------------------------------------------------------------------
def a_x(t):
    c, s = np.cos(t), np.sin(t)
    one, zero = np.ones_like(t), np.zeros_like(t)
    return np.stack(
        [np.stack([one, zero, zero], -1), np.stack([zero, c, s], -1), np.stack([zero, -s, c], -1)],
        -2,
    )


def a_y(t):
    c, s = np.cos(t), np.sin(t)
    one, zero = np.ones_like(t), np.zeros_like(t)
    return np.stack(
        [np.stack([c, zero, s], -1), np.stack([zero, one, zero], -1), np.stack([-s, zero, c], -1)],
        -2,
    )


def rotor_angles_matrices(drive, theta):
    """Angles (wrapped) of the two roller shafts projected on yz, from +z towards +y."""
    theta = np.asarray(theta, dtype=float)
    a = a_x(theta) @ a_y(np.full_like(theta, drive.plate_tilt)) @ a_x(drive.spin_ratio * theta)
    out = []
    for c in (-drive.roller_axis_angle / 2, drive.roller_axis_angle / 2):
        r3 = np.array([0.0, np.sin(c), np.cos(c)])
        v = np.einsum("...ij,j->...i", a, r3)
        out.append(np.arctan2(v[..., 1], v[..., 2]))
    return out


def gamma_from_eq18_19(n_pistons):
    """gamma solving eq. 18-19 for both chamber kinds: pi - alpha' - 2 gamma - beta (eq. 19 with
    alpha'_2 = pi - alpha') = 2 pi/N + 2 gamma - alpha' - beta (pistons 2 pi/N apart)."""
    return optimize.brentq(lambda g: (np.pi - 2 * g) - (2 * np.pi / n_pistons + 2 * g), -1, 1)


def explicit_chamber_angles(q1, q2, n_pistons, beta):
    """Chamber angles between explicitly placed piston faces, chambers in the module's order."""
    g = gamma_from_eq18_19(n_pistons)
    out = []
    for m in range(n_pistons):
        c1 = q1 + g + 2 * np.pi * m / n_pistons
        c2 = q2 - g + 2 * np.pi * m / n_pistons
        c1_next = q1 + g + 2 * np.pi * (m + 1) / n_pistons
        out.append(np.mod((c2 - beta / 2) - (c1 + beta / 2), 2 * np.pi))
        out.append(np.mod((c1_next - beta / 2) - (c2 + beta / 2), 2 * np.pi))
    return np.stack(out)


def section_volume_per_radian(machine):
    """int r dA over the section, by scipy quadrature."""
    if machine.section == "rectangular":
        val, _ = integrate.quad(lambda r: r, machine.inner_radius, machine.outer_radius)
        return val * machine.axial_width
    rm, h = machine.mean_radius, machine.section_diameter / 2
    val, _ = integrate.dblquad(
        lambda r, z: r,
        -h,
        h,
        lambda z: rm - np.sqrt(max(h * h - z * z, 0.0)),
        lambda z: rm + np.sqrt(max(h * h - z * z, 0.0)),
        epsabs=0,
        epsrel=1e-12,
    )
    return val


def explicit_volumes(drive, machine, layout, theta, k=None):
    """Volumes of the explicit model; k = int r dA (computed here unless given)."""
    q1, q2 = rotor_angles_matrices(drive, theta)
    delta = explicit_chamber_angles(q1, q2, machine.pistons_per_rotor, layout.piston_width)
    k = section_volume_per_radian(machine) if k is None else k
    return k * delta + machine.clearance_volume


def p_of_v(cycle, stroke, v, v_max, v_min):
    pa, k, q = cycle.ambient_pressure, cycle.polytropic_exponent, cycle.heat_per_cycle
    if stroke in (ec.INTAKE, ec.EXHAUST):
        return pa + 0.0 * v
    if stroke == ec.COMPRESSION:
        return pa * (v_max / v) ** k
    return (pa * (v_max / v_min) ** k + (k - 1) * q / v_min) * (v_min / v) ** k


def random_engine(rng, n_pistons=None, spin=None):
    n_p = int(rng.choice([2, 4, 6, 8])) if n_pistons is None else n_pistons
    lo, hi = np.pi / 2 - np.pi / n_p, np.pi / 2 + np.pi / n_p
    alpha = rng.uniform(lo + 0.03, hi - 0.03) if n_p > 2 else rng.uniform(0.3, np.pi - 0.3)
    lim = float(wc.max_plate_tilt(alpha, n_p))
    phi = rng.uniform(0.1, min(lim, 1.4) - 0.02)
    n = float(rng.choice([-3.0, -2.0, -1.5, -1.0, 1.0, 2.0])) if spin is None else spin
    drive = wc.WobbleCam(phi, alpha, n, 0.05, n_p)
    eps = wc.min_compression_ratio(drive) * rng.uniform(1.1, 4.0)
    common = dict(
        compression_ratio=eps,
        pistons_per_rotor=n_p,
        clearance_volume=rng.choice([0.0, rng.uniform(0, 5e-6)]),
        inertia_shaft=rng.uniform(0, 0.01),
        inertia_rotor_1=rng.uniform(0, 0.02),
        inertia_rotor_2=rng.uniform(0, 0.02),
    )
    if rng.uniform() < 0.5:
        ri = rng.uniform(0.02, 0.06)
        machine = tr.TwinRotor(
            section="rectangular",
            inner_radius=ri,
            outer_radius=ri + rng.uniform(0.01, 0.05),
            axial_width=rng.uniform(0.01, 0.06),
            **common,
        )
    else:
        rm = rng.uniform(0.03, 0.1)
        machine = tr.TwinRotor(
            section="circular",
            mean_radius=rm,
            section_diameter=rng.uniform(0.1, 1.8) * rm,
            **common,
        )
    cycle = ec.IdealCycle(rng.uniform(0.8e5, 2e5), rng.uniform(1.1, 1.5), rng.uniform(10, 200))
    return drive, machine, cycle


def table1_engine(**machine):
    drive = wc.WobbleCam(45 * D, 90 * D, -2.0, 0.06)
    kw = dict(inner_radius=0.04, outer_radius=0.08, axial_width=0.04)
    kw.update(machine)
    return drive, tr.TwinRotor(**kw), ec.IdealCycle(1e5, 1.35, 90.0)


def eq15(varphi, phi, alpha):
    m, p = varphi - alpha / 2, varphi + alpha / 2
    c2 = np.cos(phi) ** 2
    num = np.sin(m) * np.sin(p) + c2 * np.cos(m) * np.cos(p)
    den = np.sqrt((np.sin(m) ** 2 + c2 * np.cos(m) ** 2) * (np.sin(p) ** 2 + c2 * np.cos(p) ** 2))
    return np.arccos(num / den)


def d5(f, x, h):
    return (-f(x + 2 * h) + 8 * f(x + h) - 8 * f(x - h) + f(x - 2 * h)) / (12 * h)


# --------------------------------------------------------------------------------------------
# volumes
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("seed", range(8))
def test_volumes_against_explicit_pistons_and_section_integral(seed):
    rng = np.random.default_rng(seed)
    drive, machine, _ = random_engine(rng)
    layout = eng.piston_layout(drive, machine)
    theta = rng.uniform(-6, 6, 120)
    got = eng.chambers(drive, machine, theta).volume
    assert got.shape == (2 * machine.pistons_per_rotor, 120)
    np.testing.assert_allclose(
        got, explicit_volumes(drive, machine, layout, theta), rtol=1e-9, atol=1e-15
    )
    # eq. 19 holds for both kinds: alpha' = delta_A + beta + 2 gamma and the complementary
    # slider angle alpha'_2 = pi - alpha' (rotor 2's rail to rotor 1's other rail) = delta_B + ...
    q1, q2 = rotor_angles_matrices(drive, theta)
    delta = explicit_chamber_angles(q1, q2, machine.pistons_per_rotor, layout.piston_width)
    g = gamma_from_eq18_19(machine.pistons_per_rotor)
    slider = np.mod(q2 - q1, 2 * np.pi)
    slider2 = np.mod(q1 + np.pi - q2, 2 * np.pi)
    np.testing.assert_allclose(delta[0] + layout.piston_width + 2 * g, slider, atol=1e-9)
    np.testing.assert_allclose(delta[1] + layout.piston_width + 2 * g, slider2, atol=1e-9)
    assert float(wc.piston_offset(machine.pistons_per_rotor)) == pytest.approx(g, abs=1e-13)


@pytest.mark.parametrize("seed", range(5))
def test_volume_bookkeeping_chambers_plus_pistons_fill_the_annulus(seed):
    """sum_j (V_j - V_c) + 2N pistons of width beta = the annulus volume, at every angle."""
    rng = np.random.default_rng(50 + seed)
    drive, machine, _ = random_engine(rng)
    ch = eng.chambers(drive, machine, rng.uniform(-5, 5, (3, 40)))
    k = section_volume_per_radian(machine)
    n_p = machine.pistons_per_rotor
    total = np.sum(ch.volume - machine.clearance_volume, axis=0) + 2 * n_p * ch.piston_width * k
    np.testing.assert_allclose(total, 2 * np.pi * k, rtol=1e-12)
    assert tr.annulus_volume(machine) == pytest.approx(2 * np.pi * k, rel=1e-10)
    assert np.all(ch.volume > machine.clearance_volume)  # no interference anywhere


@pytest.mark.parametrize("seed", range(5))
def test_volume_derivatives_by_finite_differences(seed):
    rng = np.random.default_rng(100 + seed)
    drive, machine, _ = random_engine(rng)
    layout = eng.piston_layout(drive, machine)
    theta = rng.uniform(-4, 4, 60)
    ch = eng.chambers(drive, machine, theta, layout)
    scale = np.max(np.abs(ch.dvolume))
    fd = d5(lambda t: eng.chambers(drive, machine, t, layout).volume, theta, 1e-3)
    np.testing.assert_allclose(ch.dvolume, fd, rtol=0, atol=1e-7 * scale)
    fd2 = d5(lambda t: eng.chambers(drive, machine, t, layout).dvolume, theta, 1e-3)
    np.testing.assert_allclose(ch.d2volume, fd2, rtol=0, atol=1e-6 * np.max(np.abs(ch.d2volume)))
    # dV_j/dq_i: vary one rotor at a time
    q1, q2 = ch.motion.q
    h = 1e-4
    for i in (0, 1):
        dq = np.array([h, 0.0]) if i == 0 else np.array([0.0, h])
        vp = eng.chamber_volumes_from_rotors(machine, layout, q1 + dq[0], q2 + dq[1])
        vm = eng.chamber_volumes_from_rotors(machine, layout, q1 - dq[0], q2 - dq[1])
        fdq = (vp - vm) / (2 * h)
        np.testing.assert_allclose(
            np.broadcast_to(ch.dvolume_dq[i][:, None], fdq.shape), fdq, rtol=1e-8, atol=1e-16
        )


def test_torus_volume_is_pappus_and_rectangle_the_sector_formula():
    m = tr.TwinRotor(section="circular", mean_radius=0.06, section_diameter=0.04)
    assert tr.volume_per_radian(m) == pytest.approx(section_volume_per_radian(m), rel=1e-10)
    assert tr.volume_per_radian(m) == pytest.approx(0.06 * np.pi * 0.04**2 / 4, rel=1e-14)
    r = tr.TwinRotor()
    assert tr.volume_per_radian(r) == pytest.approx(0.5 * (0.08**2 - 0.04**2) * 0.04, rel=1e-14)


def test_compression_ratio_with_clearance_textbook_relation():
    """eps_geo = (V_s + V_0 + V_c) / (V_0 + V_c), V_0 = K delta_min; = 10 at Table 1 without V_c."""
    drive, machine, _ = table1_engine()
    layout = eng.piston_layout(drive, machine)
    assert eng.compression_ratio_geometric(machine, layout) == pytest.approx(
        (10.0, 10.0), rel=1e-12
    )
    k = 0.5 * (0.08**2 - 0.04**2) * 0.04
    amax, amin = eq15(0.0, 45 * D, 90 * D), eq15(np.pi / 2, 45 * D, 90 * D)
    beta = (11 * amin - np.pi * 13 / 4) / 9  # eq. 21
    v0 = k * (amin - np.pi / 4 - beta)
    vs = k * (amax - amin)
    assert eng.swept_volume(machine, layout) == pytest.approx(vs, rel=1e-12)
    for vc in (1e-6, 3.3e-6, 2e-5):
        _, m, _ = table1_engine(clearance_volume=vc)
        got = eng.compression_ratio_geometric(m, eng.piston_layout(drive, m))
        assert got == pytest.approx(((vs + v0 + vc) / (v0 + vc),) * 2, rel=1e-12)
        assert got[0] < 10.0
    # with clearance, the dense-sampled explicit volumes give the same ratio
    _, m, _ = table1_engine(clearance_volume=2e-6)
    v = explicit_volumes(drive, m, eng.piston_layout(drive, m), np.linspace(0, np.pi, 4001))
    assert v[0].max() / v[0].min() == pytest.approx(
        eng.compression_ratio_geometric(m, eng.piston_layout(drive, m))[0], rel=1e-9
    )


@pytest.mark.parametrize("seed", range(4))
def test_volume_limits_off_90_deg(seed):
    """alpha != 90 deg: the kinds differ; the limits equal dense-sampled extremes."""
    rng = np.random.default_rng(150 + seed)
    drive, machine, _ = random_engine(rng, n_pistons=int(rng.choice([4, 6])), spin=-2.0)
    layout = eng.piston_layout(drive, machine)
    v = explicit_volumes(drive, machine, layout, np.linspace(0, np.pi / 2, 2001))
    v_min, v_max = eng.volume_limits(machine, layout)
    np.testing.assert_allclose(v.min(axis=1), v_min, rtol=1e-9)
    np.testing.assert_allclose(v.max(axis=1), v_max, rtol=1e-9)


# --------------------------------------------------------------------------------------------
# four-stroke timing
# --------------------------------------------------------------------------------------------
def _intervals(drive, turns=1.0):
    """Stroke boundaries theta = m pi / (2|n|) over the given turns, and interval midpoints."""
    h = np.pi / (2 * abs(drive.spin_ratio))
    edges = np.arange(0, round(turns * 2 * np.pi / h) + 1) * h
    return edges, 0.5 * (edges[1:] + edges[:-1]), h


@pytest.mark.parametrize("seed", range(6))
def test_strokes_follow_the_volume(seed):
    """Each chamber runs intake -> compression -> power -> exhaust; strokes change only at the
    volume extremes; intake and power expand, compression and exhaust compress; N/2 chambers
    are on the power stroke at every instant; 2N |n| power strokes per turn."""
    rng = np.random.default_rng(200 + seed)
    drive, machine, _ = random_engine(rng)
    layout = eng.piston_layout(drive, machine)
    edges, mids, h = _intervals(drive, turns=2.0)
    # sample inside each interval (away from the ends)
    frac = np.linspace(0.02, 0.98, 9)
    theta = (edges[:-1, None] + frac * h).ravel()
    s = eng.strokes(drive, machine, theta).reshape(machine.chambers, len(mids), len(frac))
    assert np.all(s == s[..., :1])  # constant inside an interval
    s = s[..., 0]
    assert np.all(np.mod(np.diff(s, axis=1), 4) == 1)  # in order, one stroke per interval
    # sign of the volume change from the explicit model
    dv = explicit_volumes(drive, machine, layout, mids + 1e-4) - explicit_volumes(
        drive, machine, layout, mids - 1e-4
    )
    expanding = (s == ec.INTAKE) | (s == ec.POWER)
    assert np.all(dv[expanding] > 0) and np.all(dv[~expanding] < 0)
    assert np.all(np.sum(s == ec.POWER, axis=0) == machine.pistons_per_rotor // 2)
    starts = np.sum((s == ec.POWER)[:, : len(mids) // 2])  # one turn
    assert starts == 2 * machine.pistons_per_rotor * abs(drive.spin_ratio)
    assert starts == wc.power_strokes_per_rev(drive)
    # at a boundary, the stroke that starts there
    at = eng.strokes(drive, machine, edges[1:-1])
    np.testing.assert_array_equal(at, s[:, 1:])


def test_table1_timing_chamber1_and_fixed_ports():
    """Chamber 1 starts compression at theta = 0 and fires at 45 deg; at Table 1 the firing
    TDCs of all chambers fall on 2 fixed housing positions 180 deg apart (spark plugs), the
    intake TDCs on the 2 others: the timing is realizable with ports fixed in the housing."""
    drive, machine, _ = table1_engine()
    layout = eng.piston_layout(drive, machine)
    assert int(eng.strokes(drive, machine, 0.0)[0]) == ec.COMPRESSION
    assert int(eng.strokes(drive, machine, 45 * D)[0]) == ec.POWER
    edges, _, h = _intervals(drive, turns=2.0)
    edges = edges[:-1]  # events in [0, 4 pi)
    before = eng.strokes(drive, machine, edges - 1e-6)
    after = eng.strokes(drive, machine, edges + 1e-6)
    q1, q2 = rotor_angles_matrices(drive, edges)
    g, beta = gamma_from_eq18_19(4), layout.piston_width
    pos = {ec.POWER: [], ec.INTAKE: []}
    for j in range(8):
        m, b = divmod(j, 2)
        c1 = q1 + g + m * np.pi / 2
        c2 = q2 - g + m * np.pi / 2
        lo = c1 + beta / 2 if b == 0 else c2 + beta / 2
        width = explicit_chamber_angles(q1, q2, 4, beta)[j]
        centre = np.mod(lo + width / 2, 2 * np.pi)
        for stroke in pos:
            fired = (after[j] == stroke) & (before[j] != stroke)
            pos[stroke].extend(np.degrees(centre[fired]))
    for stroke, values in pos.items():
        values = np.round(np.mod(values, 360.0), 6) % 360.0
        distinct = np.unique(values)
        assert len(values) == 32 and len(distinct) == 2, (stroke, distinct)
        assert distinct[1] - distinct[0] == pytest.approx(180.0, abs=1e-6)
    assert not set(np.unique(np.round(pos[ec.POWER], 6) % 360)) & set(
        np.unique(np.round(pos[ec.INTAKE], 6) % 360)
    )


# --------------------------------------------------------------------------------------------
# pressures, torques, energy
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("seed", range(4))
def test_pressure_of_chamber_against_ode_through_a_cycle(seed):
    """March chamber 1 through its four strokes: dp/dtheta = -k p V'/V on compression and
    power (solve_ivp on the explicit volumes), p_a on intake/exhaust, heat at TDC."""
    rng = np.random.default_rng(300 + seed)
    drive, machine, cycle = random_engine(rng, spin=float(rng.choice([-2.0, -1.0, 2.0])))
    layout = eng.piston_layout(drive, machine)
    k = cycle.polytropic_exponent
    edges, _, h = _intervals(drive, turns=2.0)

    k_section = section_volume_per_radian(machine)

    def vol(t):
        return explicit_volumes(drive, machine, layout, np.atleast_1d(t), k_section)[0]

    v_lo = vol(np.pi / (2 * abs(drive.spin_ratio)))[0]  # chamber 1 (kind A): TDC
    state = eng.strokes(drive, machine, edges[:-1] + 0.5 * h)[0]
    p_start_power = np.nan
    for a, s in zip(edges[:-1], state, strict=True):
        t = np.linspace(a + 1e-9, a + h - 1e-9, 7)
        got = eng.engine_state(drive, machine, cycle, t).pressure[0]
        if s in (ec.INTAKE, ec.EXHAUST):
            np.testing.assert_allclose(got, cycle.ambient_pressure, rtol=1e-15)
            continue
        if s == ec.COMPRESSION:
            p_start = cycle.ambient_pressure
        else:
            p_start = p_start_power

        def rhs(tt, p):
            dv = (vol(tt + 1e-6) - vol(tt - 1e-6)) / 2e-6
            return -k * p / vol(tt) * dv

        sol = integrate.solve_ivp(
            rhs, (a, a + h), [p_start], t_eval=np.append(t, a + h), rtol=1e-11, atol=1e-3
        )
        np.testing.assert_allclose(got, sol.y[0][:-1], rtol=1e-6)
        if s == ec.COMPRESSION:  # heat at constant volume at TDC: Q = V dp / (k - 1)
            p_start_power = sol.y[0][-1] + (k - 1) * cycle.heat_per_cycle / v_lo


@pytest.mark.parametrize("seed", range(8))
def test_energy_shaft_torque_integral_equals_sum_of_pdv(seed):
    """int_0^2pi T_shaft dtheta (member torques times Phi_i', Gauss-Legendre per stroke) equals
    the sum over chambers and strokes of int p dV (quadrature on p(V) with the explicit
    volumes' extremes), to 1e-9."""
    rng = np.random.default_rng(400 + seed)
    drive, machine, cycle = random_engine(rng)
    layout = eng.piston_layout(drive, machine)
    edges, mids, h = _intervals(drive, turns=1.0)
    x, w = np.polynomial.legendre.leggauss(40)
    nodes = edges[:-1, None] + 0.5 * h * (x + 1.0)
    st = eng.engine_state(drive, machine, cycle, nodes)
    torque_integral = float(np.sum(st.shaft_torque * w) * 0.5 * h)
    # independent: chamber extremes from the explicit model at the exact extreme angles
    v_bdc_a = explicit_volumes(drive, machine, layout, np.array([0.0]))[:, 0]
    v_tdc_a = explicit_volumes(drive, machine, layout, np.array([h]))[:, 0]
    v_max = np.maximum(v_bdc_a, v_tdc_a)
    v_min = np.minimum(v_bdc_a, v_tdc_a)
    strokes = eng.strokes(drive, machine, mids)
    total = 0.0
    for j in range(machine.chambers):
        for s in strokes[j]:
            a, b = (v_min[j], v_max[j]) if s in (ec.INTAKE, ec.POWER) else (v_max[j], v_min[j])
            val, _ = integrate.quad(
                lambda v, s=s, j=j: p_of_v(cycle, s, v, v_max[j], v_min[j]),
                a,
                b,
                epsabs=0,
                epsrel=1e-13,
            )
            total += val
    assert torque_integral == pytest.approx(total, rel=1e-9)
    closed = eng.indicated_work_per_rev(drive, machine, cycle, layout)
    assert closed == pytest.approx(total, rel=1e-9)
    # the virtual-work torque equals sum_j p_j dV_j/dtheta
    np.testing.assert_allclose(
        st.shaft_torque,
        np.sum(st.pressure * st.chambers.dvolume, axis=0),
        rtol=1e-10,
        atol=1e-10 * np.max(np.abs(st.shaft_torque)),
    )
    np.testing.assert_allclose(st.member_torque[0], -st.member_torque[1], rtol=1e-14)


def test_efficiency_is_otto_with_the_geometric_ratio():
    for vc in (0.0, 2e-6):
        drive, machine, cycle = table1_engine(clearance_volume=vc)
        layout = eng.piston_layout(drive, machine)
        eps = eng.compression_ratio_geometric(machine, layout)[0]
        work = eng.indicated_work_per_rev(drive, machine, cycle, layout)
        heat = 16 * cycle.heat_per_cycle  # 16 power strokes per turn, paper section 1.2
        assert work / heat == pytest.approx(1 - eps ** (1 - 1.35), rel=1e-12)


@pytest.mark.parametrize("seed", range(4))
def test_instantaneous_power_balance_with_a_speed_profile(seed):
    """omega (T_gas - T_inertia) = sum_j p_j dV_j/dt - dKE/dt, where theta(t) comes from an ODE
    of the speed profile, dV/dt and dKE/dt are 5-point differences along the time grid and KE
    is 1/2 (J_s omega^2 + sum J_i (dPhi_i/dt)^2) with dPhi_i/dt also by differences in time."""
    rng = np.random.default_rng(500 + seed)
    drive, machine, cycle = random_engine(rng, spin=float(rng.choice([-2.0, -1.0, 1.0])))
    layout = eng.piston_layout(drive, machine)
    samples = 300.0 + rng.uniform(-30, 30, 7)
    omega_of = lambda th: shaft_speed(th, samples, 2 * np.pi)[0]  # noqa: E731
    dt = 1e-5
    for theta_c in rng.uniform(0.05, 6.2, 5):
        steps = np.arange(-4, 5) * dt
        sol = integrate.solve_ivp(
            lambda t, y: omega_of(y),
            (0, 4 * dt),
            [theta_c],
            t_eval=steps[4:],
            rtol=1e-13,
            atol=1e-15,
        )
        solb = integrate.solve_ivp(
            lambda t, y: omega_of(y),
            (0, -4 * dt),
            [theta_c],
            t_eval=steps[4::-1],
            rtol=1e-13,
            atol=1e-15,
        )
        th = np.concatenate([solb.y[0][::-1][:-1], sol.y[0]])  # theta at t = -4dt .. 4dt
        q1, q2 = (np.unwrap(q) for q in rotor_angles_matrices(drive, th))

        def ddt(f, i):  # 5-point central difference at index i (f over the 9 times)
            return (-f[i + 2] + 8 * f[i + 1] - 8 * f[i - 1] + f[i - 2]) / (12 * dt)

        rotor_speed = [np.array([ddt(q, i) for i in range(2, 7)]) for q in (q1, q2)]
        ke = 0.5 * (
            machine.inertia_shaft * omega_of(th[2:7]) ** 2
            + machine.inertia_rotor_1 * rotor_speed[0] ** 2
            + machine.inertia_rotor_2 * rotor_speed[1] ** 2
        )
        dke = (-ke[4] + 8 * ke[3] - 8 * ke[1] + ke[0]) / (12 * dt)
        vols = explicit_volumes(drive, machine, layout, th)
        dvdt = ddt(vols.T, 4)
        st = eng.engine_state(drive, machine, cycle, theta_c)
        w, wd = (float(x) for x in shaft_speed(theta_c, samples, 2 * np.pi)[:2])
        m = st.chambers.motion
        t_in = inertia_torque(machine.inertia_shaft, machine.member_inertias, m.dq, m.d2q, w, wd)
        lhs = w * (float(st.shaft_torque) - float(t_in))
        rhs = float(np.sum(st.pressure * dvdt)) - dke
        scale = w * (abs(float(st.shaft_torque)) + abs(float(t_in))) + 1.0
        assert lhs == pytest.approx(rhs, abs=2e-6 * scale)
        # and the kinetic energy itself
        ke_code = kinetic_energy(machine.inertia_shaft, machine.member_inertias, m.dq, w)
        assert float(ke_code) == pytest.approx(ke[2], rel=1e-6)


def test_flywheel_against_independent_energy_integral():
    cfg, _, _ = load_config(example="wobble-cam-engine", sets=["loads.model=ideal"])
    s = study.evaluate(cfg).summary
    drive, machine, cycle = table1_engine(
        inertia_shaft=0.004, inertia_rotor_1=0.008, inertia_rotor_2=0.008
    )
    theta = np.linspace(0, 2 * np.pi, 200_001)
    st = eng.engine_state(drive, machine, cycle, theta)
    w = 3000 * np.pi / 30
    dq, d2q = st.chambers.motion.dq, st.chambers.motion.d2q
    # inertia torque written out: d/dtheta of 1/2 J_eq w^2 at constant w
    t_in = w**2 * (0.008 * dq[0] * d2q[0] + 0.008 * dq[1] * d2q[1])
    net = st.shaft_torque - t_in
    e = integrate.cumulative_trapezoid(
        net - np.trapezoid(net, theta) / (2 * np.pi), theta, initial=0
    )
    d_e = e.max() - e.min()
    assert s["energy_fluctuation_J"] == pytest.approx(d_e, rel=1e-5)
    j_mean = np.mean(equivalent_inertia(0.004, (0.008, 0.008), dq)[:-1])
    assert s["equivalent_inertia_mean_kgm2"] == pytest.approx(j_mean, rel=1e-6)
    assert s["speed_fluctuation_without_flywheel"] == pytest.approx(d_e / (j_mean * w**2), rel=1e-5)
    assert s["flywheel_inertia_kgm2"] == pytest.approx(d_e / (0.02 * w**2) - j_mean, rel=1e-5)


# --------------------------------------------------------------------------------------------
# shapes
# --------------------------------------------------------------------------------------------
def test_shapes_0d_1d_3d_agree():
    drive, machine, cycle = random_engine(np.random.default_rng(9), n_pistons=6, spin=-2.0)
    t3 = np.random.default_rng(1).uniform(-4, 4, (2, 3, 4))
    t1 = t3.ravel()
    s3, s1 = (
        eng.engine_state(drive, machine, cycle, t3),
        eng.engine_state(drive, machine, cycle, t1),
    )
    s0 = eng.engine_state(drive, machine, cycle, np.float64(t1[5]))
    for name in ("volume", "dvolume", "d2volume"):
        a3, a1 = getattr(s3.chambers, name), getattr(s1.chambers, name)
        assert a3.shape == (12, 2, 3, 4)
        np.testing.assert_array_equal(a3.reshape(a1.shape), a1)
        np.testing.assert_array_equal(getattr(s0.chambers, name), a1[:, 5])
    for name, lead in (("stroke", 12), ("pressure", 12), ("member_torque", 2)):
        a3, a1 = getattr(s3, name), getattr(s1, name)
        assert a3.shape == (lead, 2, 3, 4)
        np.testing.assert_array_equal(a3.reshape(a1.shape), a1)
        np.testing.assert_array_equal(getattr(s0, name), a1[:, 5])
    assert s3.shaft_torque.shape == (2, 3, 4) and s0.shaft_torque.shape == ()
    np.testing.assert_array_equal(s3.shaft_torque.ravel(), s1.shaft_torque)
    assert tr.volume_gradient(machine).shape == (2, 12)
    assert tr.chamber_volumes_from_rotors(machine, s0.chambers.piston_width, 0.1, 1.2).shape == (
        12,
    )


# --------------------------------------------------------------------------------------------
# validation
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"pistons_per_rotor": 3}, "pistons_per_rotor"),
        ({"pistons_per_rotor": 0}, "pistons_per_rotor"),
        ({"pistons_per_rotor": 4.0}, "pistons_per_rotor"),
        ({"pistons_per_rotor": True}, "pistons_per_rotor"),
        ({"compression_ratio": 1.0}, "compression_ratio"),
        ({"compression_ratio": float("nan")}, "compression_ratio"),
        ({"section": "oval"}, "section"),
        ({"inner_radius": 0.08}, "inner_radius"),
        ({"inner_radius": 0.09}, "inner_radius"),
        ({"inner_radius": 0.0}, "inner_radius"),
        ({"outer_radius": -0.01}, "outer_radius"),
        ({"axial_width": 0.0}, "axial_width"),
        ({"axial_width": float("inf")}, "axial_width"),
        ({"section": "circular", "mean_radius": 0.0}, "mean_radius"),
        ({"section": "circular", "section_diameter": 0.12}, "section_diameter"),
        ({"section": "circular", "section_diameter": 0.0}, "section_diameter"),
        ({"clearance_volume": -1e-7}, "clearance_volume"),
        ({"inertia_shaft": -1.0}, "inertia_shaft"),
        ({"inertia_rotor_2": float("nan")}, "inertia_rotor_2"),
        ({"speed_fluctuation": 0.0}, "speed_fluctuation"),
        ({"speed_fluctuation": 1.0}, "speed_fluctuation"),
    ],
)
def test_parameter_errors(kwargs, name):
    with pytest.raises(ParameterError, match=name) as info:
        tr.TwinRotor(**kwargs)
    assert info.value.name == name


def test_pistons_message_says_why():
    with pytest.raises(ParameterError) as info:
        tr.TwinRotor(pistons_per_rotor=5)
    assert "even" in str(info.value) and "180 deg" in str(info.value)


def test_drive_and_machine_must_agree_on_pistons():
    with pytest.raises(ValueError, match="pistons"):
        eng.chambers(wc.WobbleCam(0.5), tr.TwinRotor(pistons_per_rotor=6), 0.0)


def test_inactive_section_sizes_are_not_checked():
    tr.TwinRotor(section="circular", inner_radius=0.1, outer_radius=0.05)
    tr.TwinRotor(section="rectangular", section_diameter=1.0)


# --------------------------------------------------------------------------------------------
# study, CLI, figures
# --------------------------------------------------------------------------------------------
def example_cfg(**sets):
    """The example engine with the ideal cycle (the closed forms these tests check)."""
    sets = {"loads.model": '"ideal"', **sets}
    cfg, _, _ = load_config(example="wobble-cam-engine", sets=[f"{k}={v}" for k, v in sets.items()])
    return cfg


def test_study_example_summary_against_hand_numbers():
    """The example (Table 1 + our 40/80 x 40 mm annulus, Q = 90 J, 3000 rpm), from eq. 15/21."""
    s = study.evaluate(example_cfg()).summary
    k = 0.5 * (0.08**2 - 0.04**2) * 0.04
    amax, amin = eq15(0.0, 45 * D, 90 * D), eq15(np.pi / 2, 45 * D, 90 * D)
    beta = (11 * amin - np.pi * 13 / 4) / 9
    v_min, v_max = k * (amin - np.pi / 4 - beta), k * (amax - np.pi / 4 - beta)
    swept = v_max - v_min
    assert s["chamber_volume_min_cm3"] == pytest.approx(v_min * 1e6, rel=1e-10)
    assert s["chamber_volume_max_cm3"] == pytest.approx(v_max * 1e6, rel=1e-10)
    assert s["swept_volume_cm3"] == pytest.approx(swept * 1e6, rel=1e-10)
    # 16 intake strokes per turn (as many as the paper's 16 power strokes)
    assert s["intake_strokes_per_rev"] == 16
    assert s["displacement_cm3_per_rev"] == pytest.approx(16 * swept * 1e6, rel=1e-10)
    assert s["equivalent_capacity_cm3"] == pytest.approx(32 * swept * 1e6, rel=1e-10)
    assert s["compression_ratio_geometric"] == pytest.approx(10.0, rel=1e-12)
    p3 = 1e5 * 10**1.35 + 0.35 * 90 / v_min
    assert s["peak_pressure_bar"] == pytest.approx(p3 / 1e5, rel=1e-10)
    assert 50 < s["peak_pressure_bar"] < 80
    assert s["compression_end_pressure_bar"] == pytest.approx(10**1.35, rel=1e-10)
    work = 16 * 90 * (1 - 10**-0.35)
    assert s["indicated_work_J"] == pytest.approx(work, rel=1e-10)
    assert s["indicated_efficiency"] == pytest.approx(1 - 10**-0.35, rel=1e-10)
    assert s["mean_torque_Nm"] == pytest.approx(work / (2 * np.pi), rel=1e-10)
    assert s["indicated_power_kW"] == pytest.approx(work * 50 / 1e3, rel=1e-10)
    assert s["imep_bar"] == pytest.approx(work / (16 * swept) / 1e5, rel=1e-10)
    assert s["chambers_in_power_stroke"] == 2 and s["pistons_per_rotor"] == 4
    assert s["shaft_speed_mean_rpm"] == pytest.approx(3000.0)
    # rotor speed peak: |dPhi/dtheta| up to 1 + 2/cos(45 deg) - 1 = 1.828 times the shaft speed
    assert s["rotor1_speed_peak_rad_per_s"] == pytest.approx(
        (2 / np.cos(45 * D) - 1) * 100 * np.pi, rel=1e-6
    )
    for key in ("flywheel_inertia_kgm2", "energy_fluctuation_J", "torque_ripple"):
        assert s[key] > 0
    for v in s.values():
        assert isinstance(v, (int, float, str)) and not isinstance(v, np.generic)
    json.dumps(s)


def test_study_columns_are_consistent():
    res = study.evaluate(example_cfg())
    c = res.columns
    assert set(res.column_docs) == set(c)
    assert all(np.shape(v) == (721,) for v in c.values())
    p = np.stack([c[f"chamber{j}_pressure_bar"] for j in range(1, 9)]) * 1e5
    dv = np.stack([c["chamber_a_dvolume_cm3_per_rad"], c["chamber_b_dvolume_cm3_per_rad"]] * 4)
    np.testing.assert_allclose(
        c["shaft_torque_Nm"], np.sum(p * dv * 1e-6, axis=0), rtol=1e-9, atol=1e-9
    )
    np.testing.assert_allclose(c["rotor1_gas_torque_Nm"], -c["rotor2_gas_torque_Nm"])
    np.testing.assert_allclose(
        c["shaft_torque_with_inertia_Nm"], c["shaft_torque_Nm"] - c["inertia_torque_Nm"]
    )
    np.testing.assert_array_equal(c["chambers_in_power_stroke"], 2)
    strokes = np.stack([c[f"chamber{j}_stroke"] for j in range(1, 9)])
    assert all(set(np.unique(row)) == {0, 1, 2, 3} for row in strokes)
    np.testing.assert_array_equal(np.sum(strokes == 2, axis=0), c["chambers_in_power_stroke"])
    # every chamber spends a quarter of the 4-stroke cycle (4 volume cycles a turn) in each stroke
    for k in range(4):
        np.testing.assert_allclose(np.mean(strokes[:, :-1] == k, axis=1), 0.25, atol=0.01)
    # the torque's mean over the turn (sampled) matches the closed-form indicated work
    s = res.summary
    mean = np.trapezoid(c["shaft_torque_Nm"], np.radians(c["theta_deg"])) / (2 * np.pi)
    assert mean == pytest.approx(s["mean_torque_Nm"], rel=1e-3)  # trapezoid over kinks, 0.5 deg
    span = c["shaft_torque_Nm"].max() - c["shaft_torque_Nm"].min()
    assert s["torque_ripple"] == pytest.approx(span / s["mean_torque_Nm"], rel=1e-3)
    assert c["chamber_a_volume_cm3"].max() == pytest.approx(s["chamber_a_volume_max_cm3"])
    assert "rotor2_jerk_rad_per_s3" in c and "shaft_speed_rpm" in c


def test_study_with_clearance_pistons_and_speed_profile():
    cfg = example_cfg(
        **{
            "machine.clearance_volume": '"2 cm^3"',
            "machine.pistons_per_rotor": 6,
            "drive.plate_tilt": '"40 deg"',
            "run.speed": '["2800 rpm", "3200 rpm", "3000 rpm", "2900 rpm"]',
        }
    )
    res = study.evaluate(cfg)
    s = res.summary
    assert s["chambers"] == 12 and s["power_strokes_per_rev"] == 24
    assert s["chambers_in_power_stroke"] == 3
    assert s["piston_offset_gamma_deg"] == pytest.approx(45 - 15)
    eps = s["compression_ratio_geometric"]
    v0, vc = s["chamber_volume_min_cm3"] - 2.0, 2.0
    assert eps == pytest.approx((s["swept_volume_cm3"] + v0 + vc) / (v0 + vc), rel=1e-10)
    assert s["indicated_efficiency"] == pytest.approx(1 - eps**-0.35, rel=1e-10)
    per_chamber = [k for k in res.columns if k.startswith("chamber") and k[7].isdigit()]
    assert len(per_chamber) == 2 * 12 and "chamber12_stroke" in res.columns


def test_study_n2_admits_large_tilt_and_n6_refuses_with_its_limit():
    s = study.evaluate(
        example_cfg(**{"machine.pistons_per_rotor": 2, "drive.plate_tilt": '"70 deg"'})
    ).summary
    assert s["max_plate_tilt_deg"] == pytest.approx(90.0)
    with pytest.raises(ParameterError, match=r"drive\.plate_tilt") as info:
        study.evaluate(
            example_cfg(**{"machine.pistons_per_rotor": 6, "drive.plate_tilt": '"56 deg"'})
        )
    lim = np.degrees(np.arccos(np.tan(np.pi / 4 - np.pi / 12)))  # 54.74 deg
    assert f"{lim:.2f} deg" in str(info.value) and "6 pistons per rotor" in str(info.value)


@pytest.mark.parametrize(
    ("key", "value"),
    [
        ("machine.pistons_per_rotor", "3"),
        ("machine.inner_radius", '"90 mm"'),
        ("machine.axial_width", '"0 mm"'),
        ("machine.clearance_volume", '"-1 cm^3"'),
        ("machine.speed_fluctuation", "0"),
        ("machine.compression_ratio", "2"),
        ("loads.polytropic_exponent", "1.0"),
        ("loads.ambient_pressure", '"0 bar"'),
        ("loads.heat_per_cycle", '"-5 J"'),
    ],
)
def test_study_errors_name_the_key(key, value):
    with pytest.raises((ParameterError, ConfigError)) as info:  # the schema's bounds or the study's
        study.evaluate(example_cfg(**{key: value}))
    assert str(info.value).startswith(f"{key} = ")


def test_study_circular_section_errors():
    with pytest.raises(ParameterError) as info:
        study.evaluate(
            example_cfg(**{"machine.section": '"circular"', "machine.section_diameter": '"130 mm"'})
        )
    assert info.value.name == "machine.section_diameter"
    s = study.evaluate(example_cfg(**{"machine.section": '"circular"'})).summary
    k = 0.06 * np.pi * 0.04**2 / 4
    assert s["annulus_volume_cm3"] == pytest.approx(2 * np.pi * k * 1e6, rel=1e-12)


@pytest.mark.parametrize(
    ("setting", "words"),
    [
        ("machine.inner_radius=90 mm", "machine.inner_radius"),
        ("machine.pistons_per_rotor=3", "even"),
        ("machine.clearance_volume=-1 cm^3", "machine.clearance_volume"),
    ],
)
def test_cli_bad_machine_input_exits_2(setting, words, tmp_path, capsys):
    assert main(["run", "--set", setting, "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and words in err[0]


def test_no_heat_no_inertia_gives_nan_not_a_crash():
    cfg = example_cfg(
        **{
            "loads.heat_per_cycle": '"0 J"',
            "machine.inertia_shaft": '"0 kg*m^2"',
            "machine.inertia_rotor_1": '"0 kg*m^2"',
            "machine.inertia_rotor_2": '"0 kg*m^2"',
        }
    )
    s = study.evaluate(cfg).summary
    assert s["indicated_work_J"] == 0.0 and s["mean_torque_Nm"] == 0.0
    assert np.isnan(s["indicated_efficiency"]) and np.isnan(s["torque_ripple"])
    assert np.isnan(s["speed_fluctuation_without_flywheel"])
    assert s["energy_fluctuation_J"] > 0  # the gas spring still stores energy


@pytest.mark.slow
def test_plot_writes_engine_figures(tmp_path):
    paths = study.evaluate(
        example_cfg(**{"machine.pistons_per_rotor": 6, "drive.plate_tilt": '"40 deg"'})
    ).write_figures(tmp_path)
    names = {p.name for p in paths}
    assert {
        "fig_chamber_volumes.png",
        "fig_pv_diagram.png",
        "fig_shaft_torque.png",
        "fig_four_stroke.png",
        "fig10_chamber_angle.png",
    } <= names
    for p in paths:
        assert p.stat().st_size > 10_000 and p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_every_config_key_reaches_a_dataclass_field():
    """No [machine] or [loads] key of a wobble_cam config is silently ignored by the study."""
    from dataclasses import fields

    from rotorkin.drives.wobble_cam.schema import WobbleConfig

    machine_keys = set(WobbleConfig.model_fields["machine"].annotation.model_fields)
    loads_keys = set(WobbleConfig.model_fields["loads"].annotation.model_fields)
    # machine.type chooses the machine; every other key is a field of it
    assert machine_keys == {f.name for f in fields(tr.TwinRotor)} | {"type"}
    both = {f.name for f in fields(ec.IdealCycle)} | {f.name for f in fields(fa.FuelAirLoads)}
    assert loads_keys == both | {"model"}
    # and the dataclass defaults are the config's defaults
    cfg, _, _ = load_config(example="wobble-cam-engine")
    defaults = tr.TwinRotor()
    base = WobbleConfig.model_validate({"drive": {"type": "wobble_cam", "plate_tilt": "45 deg"}})
    for f in fields(tr.TwinRotor):
        ours, theirs = getattr(defaults, f.name), getattr(base.machine, f.name)
        if isinstance(ours, str):
            assert theirs == ours, f.name
        else:
            assert theirs == pytest.approx(ours, rel=1e-12), f.name
    for f in fields(ec.IdealCycle):
        assert getattr(base.loads, f.name) == pytest.approx(getattr(ec.IdealCycle(), f.name))
    assert cfg["machine"]["pistons_per_rotor"] == 4
