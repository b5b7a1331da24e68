"""Single-zone chamber model (rotorkin.analysis.combustion): Otto limit, energy balance, parts."""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.analysis import combustion as cb

VC, VS = 8e-6, 64e-6


def volume(x):
    x = np.asarray(x, dtype=float)
    return VC + VS / 2 * (1 - np.cos(x)), VS / 2 * np.sin(x)


@pytest.mark.parametrize("gamma", [1.3, 1.35, 1.4])
def test_instant_burn_without_walls_is_the_ideal_otto_cycle(gamma):
    """Heywood sec. 5.3: W = Q (1 - r^(1 - gamma)); peak p = p_i r^gamma + (gamma - 1) Q / V_c."""
    ch = cb.Charge(gamma=gamma)
    q = 120.0
    r = cb.closed_cycle(volume, np.linspace(-np.pi, np.pi, 2001), q, None, ch, 1e-4)
    ratio = (VC + VS) / VC
    assert r["work"] == pytest.approx(q * (1 - ratio ** (1 - gamma)), rel=1e-9)
    peak = 1e5 * ratio**gamma + (gamma - 1) * q / VC
    assert np.max(r["p"]) == pytest.approx(peak, rel=1e-9)
    assert r["heat_wall"] == 0.0


def test_energy_balance_with_a_wiebe_burn_and_woschni_walls():
    """Work = heat released - heat to the walls - the gas's energy rise, per closed cycle."""
    ch = cb.Charge()
    x = np.linspace(-np.pi, np.pi, 4001)
    mass = cb.trapped_mass(ch, VC + VS)
    q = cb.heat_of_charge(ch, VC + VS)
    wall = (lambda xi: 0.01 + 0 * np.asarray(xi), 0.04, 10.0, 450.0, 1 / 314.16)
    r = cb.closed_cycle(volume, x, q, cb.Wiebe(), ch, mass, wall)
    cv = cb.R_AIR / (ch.gamma - 1)
    rise = mass * cv * (r["T"][-1] - r["T"][0])
    assert r["heat_released"] - r["heat_wall"] - rise - r["work"] == pytest.approx(0, abs=1e-6 * q)
    assert 0 < r["heat_wall"] < q and 0 < r["work"] < q * (1 - (9.0) ** (1 - ch.gamma))
    assert 30e5 < np.max(r["p"]) < 120e5  # a spark-ignition engine's peak pressure


def test_heat_of_the_charge_by_hand():
    # 72 cm^3 of air at 1 bar, 300 K: 8.362e-5 kg; 5 % residuals: 7.944e-5 kg of air,
    # 5.404e-6 kg of gasoline at phi = 1, 0.98 x 44 MJ/kg: 233.03 J
    q = cb.heat_of_charge(cb.Charge(), 72e-6)
    assert q == pytest.approx(0.98 * 44e6 * 0.95 * 1e5 * 72e-6 / (287 * 300) / 14.7, rel=1e-12)
    assert q == pytest.approx(233.03, abs=0.01)
    rich = cb.heat_of_charge(cb.Charge(equivalence_ratio=1.2), 72e-6)
    assert rich == pytest.approx(q)  # the air limits what burns


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
    ch = cb.Charge()
    x = np.linspace(-np.pi, np.pi, 801)
    heats = np.array([50.0, 100.0, 200.0])
    many = cb.closed_cycle(volume, x, heats, cb.Wiebe(), ch, 1e-4)
    for i, q in enumerate(heats):
        one = cb.closed_cycle(volume, x, q, cb.Wiebe(), ch, 1e-4)
        assert many["work"][i] == pytest.approx(one["work"], rel=1e-14)
        assert many["p"][i] == pytest.approx(one["p"], rel=1e-14)
