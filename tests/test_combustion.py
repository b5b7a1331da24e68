"""Single-zone chamber model (rotorkin.analysis.combustion, rotorkin.analysis.gas).

Independent checks: the ideal Otto cycle's closed forms (Heywood sec. 5.3), the
first law per cycle, the isentropic relation, hand calculations, a published table
of air's specific heat.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.analysis import combustion as cb
from rotorkin.analysis import gas as gs

VC, VS = 8e-6, 64e-6


def grid(steps):
    x = np.linspace(-np.pi, np.pi, 2 * steps + 1)
    return x, VC + VS / 2 * (1 - np.cos(x)), VS / 2 * np.sin(x)


@pytest.mark.parametrize("gamma", [1.3, 1.35, 1.4])
def test_instant_burn_without_walls_is_the_ideal_otto_cycle(gamma):
    """Heywood sec. 5.3: W = Q (1 - r^(1 - gamma)); peak p = p_i r^gamma + (gamma - 1) Q / V_c."""
    gas = gs.ConstantGas(gamma=gamma)
    q, mass = 120.0, 1e5 * (VC + VS) / (gas.r * 300.0)
    x, v, dv = grid(2000)
    r = cb.closed_cycle(x, v, dv, mass=mass, heat=q, gas=gas, temperature=300.0)
    ratio = (VC + VS) / VC
    assert r["work"] == pytest.approx(q * (1 - ratio ** (1 - gamma)), rel=1e-9)
    peak = 1e5 * ratio**gamma + (gamma - 1) * q / VC
    assert np.max(r["p"]) == pytest.approx(peak, rel=1e-9)
    tdc = np.flatnonzero(r["x"] == 0.0)[0]
    assert r["p_left"][tdc] == pytest.approx(1e5 * ratio**gamma, rel=1e-9)
    assert r["p"][tdc] == pytest.approx(peak, rel=1e-9)
    assert r["heat_wall"] == 0.0


def test_compression_is_isentropic_with_temperature_dependent_properties():
    """No burn, no walls: s(T, v) is constant, int c_v/T dT = R ln(V_1/V_2) (independent check)."""
    gas = gs.NasaGas(residual_fraction=0.0)
    x, v, dv = grid(1000)
    half = slice(0, 1001)  # intake closure to the dead centre
    r = cb.closed_cycle(x[half], v[..., half], dv[..., half], mass=1e-4, heat=0.0, gas=gas,
                        temperature=300.0)  # fmt: skip
    t_end = r["T"][-1]
    fine = np.linspace(300.0, t_end, 200_001)
    integral = np.trapezoid(gas.cv(fine, 0.0) / fine, fine)
    assert integral == pytest.approx(gas.gas_constant(0.0) * np.log((VC + VS) / VC), rel=1e-7)


@pytest.mark.parametrize("props", ["constant", "nasa"])
def test_energy_balance_with_a_wiebe_burn_and_woschni_walls(props):
    """Work = heat released - heat to the walls - the gas's sensible energy rise, per closed
    cycle, to the Runge-Kutta integrator's error on 720 steps (1e-6 of the heat)."""
    ch = cb.Charge()
    gas = gs.ConstantGas(1.3) if props == "constant" else gs.NasaGas(residual_fraction=0.05)
    x, v, dv = grid(360)
    mass = cb.trapped_mass(ch, VC + VS, gas.gas_constant(0.0))
    q = cb.heat_of_charge(ch, mass)
    walls = cb.Walls(area=0.005 + 0 * x, diameter=0.04, wall_speed=10.0,
                     seconds=np.full(x.shape, 1 / 314.16), temperature=450.0)  # fmt: skip
    r = cb.closed_cycle(x, v, dv, mass=mass, heat=q, gas=gas, temperature=ch.intake_temperature,
                        burn=cb.Wiebe(), walls=walls)  # fmt: skip
    balance = r["heat_released"] - r["heat_wall"] - r["energy_rise"] - r["work"]
    assert balance == pytest.approx(0, abs=1e-6 * q)
    assert 0 < r["heat_wall"] < 0.3 * q
    assert 0 < r["work"] < q * (1 - 9.0 ** (1 - 1.4))
    assert 30e5 < np.max(r["p"]) < 120e5  # a spark-ignition engine's peak pressure


def test_nasa_specific_heat_of_air_against_a_published_table():
    """Incropera & DeWitt, *Fundamentals of Heat and Mass Transfer*, table A.4 (air at
    1 atm): c_p = 1.007 kJ/(kg K) at 300 K, 1.051 at 600 K, 1.141 at 1000 K; to 1 %."""
    gas = gs.NasaGas(residual_fraction=0.0)
    t = np.array([300.0, 600.0, 1000.0])
    cp = gas.cv(t, 0.0) + gas.gas_constant(0.0)
    assert cp / 1e3 == pytest.approx([1.007, 1.051, 1.141], rel=0.01)
    assert gas.gas_constant(0.0) == pytest.approx(287.0, rel=2e-3)


def test_nasa_and_constant_gamma_agree_where_the_temperature_barely_changes():
    """A compression from 300 K by a ratio of 1.5 (to about 350 K): air's gamma varies by
    0.1 %; the constant-gamma model at the mean gamma gives the same end pressure to 0.05 %."""
    nasa = gs.NasaGas(residual_fraction=0.0)
    r = nasa.gas_constant(0.0)
    x = np.linspace(1.0, 2.0, 401)  # no dead centre: motored
    v, dv = 1e-4 * (2.0 - 0.5 * x), np.full(x.shape, -0.5e-4)  # 1.5e-4 to 1e-4 m^3
    mass = 1e5 * 1.5e-4 / (r * 300.0)
    hot = cb.closed_cycle(x, v, dv, mass=mass, heat=0.0, gas=nasa, temperature=300.0)
    g = float(1 + r / nasa.cv(325.0, 0.0))
    const = cb.closed_cycle(x, v, dv, mass=mass, heat=0.0, gas=gs.ConstantGas(g, r),
                            temperature=300.0)  # fmt: skip
    assert hot["p"][-1] == pytest.approx(const["p"][-1], rel=5e-4)
    assert const["p"][-1] == pytest.approx(1e5 * 1.5**g, rel=1e-9)


def test_the_charge_by_hand():
    # 72 cm^3 at 1 bar, 320 K: m = 1e5 * 72e-6 / (287.05 * 320); 5 % residuals; phi = 1
    ch = cb.Charge()
    m = cb.trapped_mass(ch, 72e-6, 287.05)
    assert m == pytest.approx(7.2 / (287.05 * 320), rel=1e-12)
    air = 0.95 * m / (1 + 1 / 14.6)
    assert cb.fresh_air(ch, m) == pytest.approx(air, rel=1e-12)
    assert cb.heat_of_charge(ch, m) == pytest.approx(0.97 * air / 14.6 * 44e6, rel=1e-12)
    rich = cb.Charge(equivalence_ratio=1.2)
    air_rich = 0.95 * m / (1 + 1.2 / 14.6)
    assert cb.heat_of_charge(rich, m) == pytest.approx(0.97 * air_rich / 14.6 * 44e6, rel=1e-12)
    assert cb.fuel_energy(rich, m) == pytest.approx(1.2 * air_rich / 14.6 * 44e6, rel=1e-12)


def test_wiebe_fraction_and_rate():
    burn = cb.Wiebe(start=-0.1, duration=0.9, a=5.0, m=2.0)
    x = np.linspace(-0.5, 1.5, 20001)
    f, rate = cb.wiebe(burn, x)
    assert f[0] == 0.0 and f[-1] == pytest.approx(1 - np.exp(-5.0 * (1.6 / 0.9) ** 3))
    assert np.trapezoid(rate, x) == pytest.approx(f[-1] - f[0], rel=1e-6)
    h = 1e-6
    fd = (cb.wiebe(burn, x[5000:5010] + h)[0] - cb.wiebe(burn, x[5000:5010] - h)[0]) / (2 * h)
    assert fd == pytest.approx(rate[5000:5010], rel=1e-6)


def test_woschni_by_hand():
    # 50 bar = 5000 kPa, 2000 K, D = 0.04 m, w = 20 m/s
    h = cb.woschni(50e5, 2000.0, 0.04, 20.0)
    assert h == pytest.approx(3.26 * 0.04**-0.2 * 5000**0.8 * 2000**-0.55 * 20**0.8, rel=1e-12)


def test_many_chambers_at_once_equal_one_by_one():
    x, v, dv = grid(200)
    heats = np.array([50.0, 100.0, 200.0])
    many = cb.closed_cycle(x, v, dv, mass=1e-4, heat=heats, temperature=320.0, burn=cb.Wiebe())
    for i, q in enumerate(heats):
        one = cb.closed_cycle(x, v, dv, mass=1e-4, heat=q, temperature=320.0, burn=cb.Wiebe())
        assert many["work"][i] == pytest.approx(one["work"], rel=1e-14)
        assert np.allclose(many["p"][i], one["p"], rtol=1e-14)


def test_hermite_is_exact_for_cubics_and_converges():
    nodes = np.linspace(-1.0, 2.0, 31)
    f = lambda t: 2 * t**3 - t**2 + 0.5  # noqa: E731
    df = lambda t: 6 * t**2 - 2 * t  # noqa: E731
    q = np.linspace(-1.0, 2.0, 1001)
    rows = np.zeros(q.shape, dtype=int)
    got = cb.hermite(nodes, f(nodes)[None], df(nodes)[None], rows, q)
    assert got == pytest.approx(f(q), abs=1e-12)
    # the pressure table of a cycle: interpolated at the half steps against the integration
    x, v, dv = grid(400)
    r = cb.closed_cycle(x, v, dv, mass=1e-4, heat=80.0, temperature=320.0, burn=cb.Wiebe())
    fine = cb.closed_cycle(np.linspace(-np.pi, np.pi, 3201), *grid(1600)[1:], mass=1e-4,
                           heat=80.0, temperature=320.0, burn=cb.Wiebe())  # fmt: skip
    mid = cb.hermite(r["x"], r["p"][None], r["dp"][None], 0, fine["x"])
    assert mid == pytest.approx(fine["p"], rel=1e-6)
