"""Ideal four-stroke cycle: closed forms against quadrature, ODEs and ideal-gas bookkeeping.

The independent models here: scipy quadrature of p(V) written out per stroke,
the polytrope integrated as an ODE (dp/dV = -k p / V), and the heat addition
computed with an explicit gas mass and temperatures (c_v = R/(k-1)).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate

from rotorkin.analysis import engine_cycle as ec
from rotorkin.core.errors import ParameterError


def random_cycle(rng):
    return ec.IdealCycle(
        ambient_pressure=rng.uniform(0.5e5, 3e5),
        polytropic_exponent=rng.uniform(1.05, 1.67),
        heat_per_cycle=rng.uniform(0.0, 500.0),
    )


def random_volumes(rng):
    v_min = rng.uniform(1e-6, 5e-5)
    return v_min * rng.uniform(2.0, 25.0), v_min


def p_of_v(cycle, stroke, v, v_max, v_min):
    """The cycle written out stroke by stroke (independent of the module)."""
    pa, k, q = cycle.ambient_pressure, cycle.polytropic_exponent, cycle.heat_per_cycle
    if stroke in (0, 3):
        return pa + 0.0 * v
    if stroke == 1:
        return pa * (v_max / v) ** k
    p2 = pa * (v_max / v_min) ** k
    # heat at constant volume with an explicit gas: m R T2 = p2 V_min, Q = m c_v (T3 - T2)
    r_gas = 287.0
    m = 1e-4  # any mass: it cancels
    t2 = p2 * v_min / (m * r_gas)
    t3 = t2 + q / (m * r_gas / (k - 1.0))
    p3 = m * r_gas * t3 / v_min
    return p3 * (v_min / v) ** k


@pytest.mark.parametrize("seed", range(6))
def test_stroke_works_against_quadrature(seed):
    rng = np.random.default_rng(seed)
    cycle = random_cycle(rng)
    v_max, v_min = random_volumes(rng)
    works = ec.stroke_works(cycle, v_max, v_min)
    assert works.shape == (4,)
    limits = [(v_min, v_max), (v_max, v_min), (v_min, v_max), (v_max, v_min)]
    for s, (a, b) in enumerate(limits):
        w, _ = integrate.quad(
            lambda v, s=s: p_of_v(cycle, s, v, v_max, v_min),
            a,
            b,
            epsabs=0,
            epsrel=1e-13,
            limit=200,
        )
        assert works[s] == pytest.approx(w, rel=1e-10, abs=1e-12)
    total = ec.indicated_work(cycle, v_max, v_min)
    assert total == pytest.approx(works.sum(), rel=1e-10, abs=1e-10)
    # efficiency: Otto with the polytropic exponent
    r = v_max / v_min
    assert total == pytest.approx(
        cycle.heat_per_cycle * (1.0 - r ** (1.0 - cycle.polytropic_exponent)), rel=1e-12, abs=1e-12
    )


@pytest.mark.parametrize("seed", range(4))
def test_pressures_against_ode_and_gas_bookkeeping(seed):
    rng = np.random.default_rng(100 + seed)
    cycle = random_cycle(rng)
    k = cycle.polytropic_exponent
    v_max, v_min = random_volumes(rng)
    # compression: integrate dp/dV = -k p / V from (V_max, p_a)
    v = np.linspace(v_max, v_min, 40)
    sol = integrate.solve_ivp(
        lambda vv, p: -k * p / vv,
        (v_max, v_min),
        [cycle.ambient_pressure],
        t_eval=v,
        rtol=1e-12,
        atol=1e-6,
    )
    np.testing.assert_allclose(
        ec.cycle_pressure(cycle, ec.COMPRESSION, v, v_max, v_min), sol.y[0], rtol=1e-9
    )
    assert float(ec.compression_end_pressure(cycle, v_max, v_min)) == pytest.approx(
        sol.y[0][-1], rel=1e-9
    )
    p3 = p_of_v(cycle, 2, v_min, v_max, v_min)
    assert float(ec.peak_pressure(cycle, v_max, v_min)) == pytest.approx(p3, rel=1e-12)
    # expansion from (V_min, p_3)
    v = np.linspace(v_min, v_max, 40)
    sol = integrate.solve_ivp(
        lambda vv, p: -k * p / vv, (v_min, v_max), [p3], t_eval=v, rtol=1e-12, atol=1e-6
    )
    np.testing.assert_allclose(
        ec.cycle_pressure(cycle, ec.POWER, v, v_max, v_min), sol.y[0], rtol=1e-9
    )
    assert float(ec.expansion_end_pressure(cycle, v_max, v_min)) == pytest.approx(
        sol.y[0][-1], rel=1e-9
    )
    for s in (ec.INTAKE, ec.EXHAUST):
        np.testing.assert_array_equal(
            ec.cycle_pressure(cycle, s, v, v_max, v_min), cycle.ambient_pressure
        )


def test_jumps_at_the_volume_extremes():
    """Continuous at BDC of intake and TDC of exhaust; jumps by (k-1)Q/V_min at the firing TDC
    and by p_4 - p_a at the blow-down."""
    cycle = ec.IdealCycle(1e5, 1.4, 100.0)
    v_max, v_min = 50e-6, 5e-6
    p = lambda s, v: float(ec.cycle_pressure(cycle, s, v, v_max, v_min))  # noqa: E731
    assert p(ec.INTAKE, v_max) == p(ec.COMPRESSION, v_max) == pytest.approx(1e5, rel=1e-15)
    assert p(ec.EXHAUST, v_min) == p(ec.INTAKE, v_min)
    assert p(ec.POWER, v_min) - p(ec.COMPRESSION, v_min) == pytest.approx(0.4 * 100.0 / 5e-6)
    assert p(ec.POWER, v_max) - p(ec.EXHAUST, v_max) == pytest.approx(
        float(ec.expansion_end_pressure(cycle, v_max, v_min)) - 1e5
    )


def test_no_heat_is_a_gas_spring():
    cycle = ec.IdealCycle(1e5, 1.3, 0.0)
    assert float(ec.indicated_work(cycle, 40e-6, 4e-6)) == 0.0
    assert float(ec.stroke_works(cycle, 40e-6, 4e-6).sum()) == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize(
    ("ratio", "k", "expected"),
    [(10.0, 1.4, 0.601892829), (8.0, 1.35, 0.517032), (1.0, 1.4, 0.0)],
)
def test_otto_efficiency_hand_values(ratio, k, expected):
    """Hand values of 1 - r^(1-k): 1 - 10^-0.4 = 60.19 %, 1 - 8^-0.35 = 51.70 % (1e-6)."""
    assert float(ec.otto_efficiency(ratio, k)) == pytest.approx(expected, abs=1e-6)


def test_mean_effective_pressure():
    assert float(ec.mean_effective_pressure(50.0, 65e-6)) == pytest.approx(50.0 / 65e-6)


def test_stroke_from_count():
    c = np.array(
        [0.0, 0.5, 1.0 - 1e-13, 1.0, 2.999, 3.0, 4.0, 5.5, -0.5, -1.0, 7.0 - 1e-14, 2.0 - 1e-9]
    )
    np.testing.assert_array_equal(ec.stroke_from_count(c), [0, 0, 1, 1, 2, 3, 0, 1, 3, 3, 3, 1])
    assert ec.stroke_from_count(2.5).shape == ()
    assert ec.STROKE_NAMES[ec.POWER] == "power"


def test_shapes_broadcast():
    cycle = ec.IdealCycle(1e5, 1.35, 80.0)
    rng = np.random.default_rng(2)
    v3 = rng.uniform(5e-6, 50e-6, (2, 3, 4))
    s3 = rng.integers(0, 4, (2, 3, 4))
    p3 = ec.cycle_pressure(cycle, s3, v3, 50e-6, 5e-6)
    p1 = ec.cycle_pressure(cycle, s3.ravel(), v3.ravel(), 50e-6, 5e-6)
    assert p3.shape == (2, 3, 4)
    np.testing.assert_array_equal(p3.ravel(), p1)
    assert float(ec.cycle_pressure(cycle, s3.ravel()[3], v3.ravel()[3], 50e-6, 5e-6)) == p1[3]
    # scalar stroke, array volumes; per-chamber limits of shape (n, 1)
    p = ec.cycle_pressure(cycle, 1, np.full((3, 5), 2e-5), np.array([[4e-5], [5e-5], [6e-5]]), 5e-6)
    assert p.shape == (3, 5) and np.all(np.diff(p[:, 0]) > 0)
    w = ec.stroke_works(cycle, np.array([4e-5, 5e-5]), 5e-6)
    assert w.shape == (4, 2)


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"ambient_pressure": 0.0}, "ambient_pressure"),
        ({"ambient_pressure": -1e5}, "ambient_pressure"),
        ({"ambient_pressure": float("nan")}, "ambient_pressure"),
        ({"polytropic_exponent": 1.0}, "polytropic_exponent"),
        ({"polytropic_exponent": 0.9}, "polytropic_exponent"),
        ({"polytropic_exponent": float("inf")}, "polytropic_exponent"),
        ({"heat_per_cycle": -1.0}, "heat_per_cycle"),
        ({"heat_per_cycle": float("nan")}, "heat_per_cycle"),
    ],
)
def test_parameter_errors(kwargs, name):
    with pytest.raises(ParameterError, match=name) as info:
        ec.IdealCycle(**kwargs)
    assert info.value.name == name


def test_cycles_broadcast_and_their_admissibility_is_the_constructors():
    rng = np.random.default_rng(7)
    pa = rng.choice([-1.0, 0.0, 1e5, 2e5], size=50)
    k = rng.choice([0.9, 1.0, 1.3, 1.4], size=50)
    q = rng.choice([-5.0, 0.0, 90.0], size=50)
    codes = ec.cycle_violation(pa, k, q)
    for i in range(50):
        try:
            ec.IdealCycle(pa[i], k[i], q[i])
            named = 0
        except ParameterError as exc:
            named = 1 + ec.CYCLE_CHECKS.index(exc.name)
        assert codes[i] == named
    ok = codes == 0
    many = ec.IdealCycle(pa[ok], k[ok], q[ok])
    peaks = ec.peak_pressure(many, 6e-5, 6e-6)
    cycles = zip(pa[ok], k[ok], q[ok], strict=True)
    one_by_one = [ec.peak_pressure(ec.IdealCycle(*v), 6e-5, 6e-6) for v in cycles]
    np.testing.assert_allclose(peaks, one_by_one, rtol=1e-15)
