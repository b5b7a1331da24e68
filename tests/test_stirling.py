"""Stirling circuit analyses (rotorkin.analysis.stirling) against independent models.

The independent models: Urieli and Berchowitz's closed-form Schmidt analysis of sinusoidal
volumes (written out again here from the derivation 1/p = s + C cos(theta + beta)); Carnot's
efficiency; the first law per cycle (W = Q_k + Q_r + Q_h); the isothermal limit of the ideal
adiabatic model (gamma -> 1: no temperature change under compression, so the working spaces
stay at T_k and T_h and the cycle is Schmidt's); RK4 step halving.

No printed result of Urieli's GPU-3 worked example could be reached here (its volumes come
from the rhombic drive, not sinusoids), so the ideal adiabatic model is tested against those
limits and balances, with GPU-3's inputs (helium, 4.13 MPa mean, T_h 977 K, T_k 288 K, swept
120.82 / 114.13 cm^3, clearance 30.52 / 28.68 cm^3, heater 70.88, regenerator 50.55, cooler
13.8 cm^3) on sinusoidal volumes 90 deg apart as a realistic case.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.analysis import stirling as st

GPU3 = {
    "vswc": 114.13e-6, "vswe": 120.82e-6, "vclc": 28.68e-6, "vcle": 30.52e-6,
    "vk": 13.8e-6, "vr": 50.55e-6, "vh": 70.88e-6, "tk": 288.0, "th": 977.0,
    "alpha": np.pi / 2, "p_mean": 4.13e6,
}  # fmt: skip
R_HE, G_HE = st.GASES["helium"]


def sinusoidal(vswc, vswe, vclc, vcle, alpha, samples):
    """Test-only volume law: V_c = V_clc + V_swc (1 + cos t)/2, V_e leads by alpha."""
    t = np.linspace(0.0, 2 * np.pi, samples)
    e = np.expand_dims
    vswc, vswe, vclc, vcle, alpha = (e(np.asarray(x, dtype=float), -1)
                                     for x in (vswc, vswe, vclc, vcle, alpha))  # fmt: skip
    vc = vclc + 0.5 * vswc * (1 + np.cos(t))
    ve = vcle + 0.5 * vswe * (1 + np.cos(t + alpha))
    return vc, ve, -0.5 * vswc * np.sin(t), -0.5 * vswe * np.sin(t + alpha)


def closed_form(mr, d):
    """Schmidt closed form, derived independently: 1/p = (s + C cos(t + beta)) / (M R)."""
    tr = (d["th"] - d["tk"]) / np.log(d["th"] / d["tk"])
    s = (
        (d["vswc"] / 2 + d["vclc"] + d["vk"]) / d["tk"]
        + d["vr"] / tr
        + (d["vswe"] / 2 + d["vcle"] + d["vh"]) / d["th"]
    )
    a_, b_ = d["vswc"] / (2 * d["tk"]), d["vswe"] / (2 * d["th"])
    cb = a_ + b_ * np.cos(d["alpha"])  # C cos(beta)
    sb = b_ * np.sin(d["alpha"])  # C sin(beta)
    c = np.hypot(cb, sb)
    beta = np.arctan2(sb, cb)
    k = c / s
    root = np.sqrt(1 - k**2)
    # W_c = loop of p dV_c = (M R / s) (V_swc/2) sin(beta) (2 pi / k)(1 / root - 1)
    wc = mr / s * d["vswc"] / 2 * np.sin(beta) * 2 * np.pi / k * (1 - 1 / root)
    we = mr / s * d["vswe"] / 2 * np.sin(beta - d["alpha"]) * 2 * np.pi / k * (1 - 1 / root)
    return {"p_mean": mr / (s * root), "p_max": mr / (s - c), "p_min": mr / (s + c), "wc": wc,
            "we": we}  # fmt: skip


def _args(d, samples):
    v = sinusoidal(d["vswc"], d["vswe"], d["vclc"], d["vcle"], d["alpha"], samples)
    return (*v, d["vk"], d["vr"], d["vh"], d["tk"], d["th"])


def _gas(d, samples=721):
    vc, ve, _, _, *rest = _args(d, samples)
    return st.schmidt_gas_for_mean_pressure(d["p_mean"], vc, ve, *rest)


# --- Schmidt --------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "change",
    [{}, {"alpha": np.radians(120)}, {"vk": 0.0, "vr": 0.0, "vh": 0.0},
     {"th": 600.0, "vswc": 60e-6}, {"alpha": np.radians(30), "vcle": 1e-6}],
)  # fmt: skip
def test_schmidt_numeric_equals_the_closed_form(change):
    """Trapezoid loop integrals on 721 periodic samples vs the closed form: 1e-9 relative
    (the trapezoid rule on a smooth periodic integrand converges geometrically)."""
    d = {**GPU3, **change}
    mr = _gas(d)
    res = st.schmidt_cycle(mr, *_args(d, 721), G_HE, R_HE)
    ref = closed_form(mr, d)
    book = st.schmidt_sinusoidal(mr, d["vswc"], d["vswe"], d["vclc"], d["vcle"], d["vk"],
                                 d["vr"], d["vh"], d["tk"], d["th"], d["alpha"])  # fmt: skip
    assert np.mean(res.pressure[:-1]) == pytest.approx(d["p_mean"], rel=1e-12)
    assert ref["p_mean"] == pytest.approx(d["p_mean"], rel=1e-9)
    assert res.work_compression == pytest.approx(ref["wc"], rel=1e-9)
    assert res.work_expansion == pytest.approx(ref["we"], rel=1e-9)
    fine = st.schmidt_cycle(mr, *_args(d, 200_001), G_HE, R_HE)
    assert np.max(fine.pressure) == pytest.approx(ref["p_max"], rel=1e-9)
    assert np.min(fine.pressure) == pytest.approx(ref["p_min"], rel=1e-9)
    for key, value in (("work_compression", ref["wc"]), ("work_expansion", ref["we"]),
                       ("p_mean", ref["p_mean"]), ("p_max", ref["p_max"]),
                       ("p_min", ref["p_min"])):  # fmt: skip
        assert book[key] == pytest.approx(value, rel=1e-12), key
    assert book["work"] > 0


def test_schmidt_is_carnot_with_an_ideal_regenerator_and_balances_energy():
    d = GPU3
    mr = _gas(d)
    res = st.schmidt_cycle(mr, *_args(d, 721), G_HE, R_HE)
    carnot = 1 - d["tk"] / d["th"]
    assert res.efficiency == pytest.approx(carnot, rel=1e-12)
    assert res.heat_in == pytest.approx(res.work_expansion, rel=1e-15)
    assert res.heat_out == pytest.approx(-res.work_compression, rel=1e-15)
    assert res.heat_in - res.heat_out == pytest.approx(res.work, rel=1e-12)
    # the regenerator's net heat over a cycle is 0 (its gas returns to its state)
    assert abs(res.heat_regenerator) < 1e-9 * res.regenerator_heat
    assert res.regenerator_heat > res.heat_in  # the regenerator carries the most heat
    # an imperfect regenerator: the same work, (1 - eps) of its heat on both heat flows
    worse = st.schmidt_cycle(mr, *_args(d, 721), G_HE, R_HE, regenerator_effectiveness=0.9)
    loss = 0.1 * res.regenerator_heat
    assert worse.work == pytest.approx(res.work, rel=1e-15)
    assert worse.heat_in == pytest.approx(res.heat_in + loss, rel=1e-12)
    assert worse.heat_out == pytest.approx(res.heat_out + loss, rel=1e-12)
    assert worse.efficiency < carnot


def test_regenerator_temperature_is_the_log_mean():
    assert st.regenerator_temperature(977.0, 288.0) == pytest.approx(689 / np.log(977 / 288))
    assert st.regenerator_temperature(300.0, 300.0) == 300.0
    # V_r / T_r is the integral of dV / T(x) along a linear profile
    x = np.linspace(0, 1, 100_001)
    inv = np.trapezoid(1 / (288 + (977 - 288) * x), x)
    assert 1 / st.regenerator_temperature(977.0, 288.0) == pytest.approx(inv, rel=1e-9)


# --- ideal adiabatic ------------------------------------------------------------------------
@pytest.fixture(scope="module")
def gpu3_adiabatic():
    d = GPU3
    mr = _gas(d)
    return mr, st.adiabatic_cycle(mr, *_args(d, 1441), G_HE, R_HE)


def test_adiabatic_is_periodic_balances_energy_and_stays_below_carnot(gpu3_adiabatic):
    _, res = gpu3_adiabatic
    assert res.residual <= st.PERIODIC_TOLERANCE
    assert abs(res.tc[-1] - res.tc[0]) + abs(res.te[-1] - res.te[0]) <= 1e-6
    # first law per cycle: W = Q_k + Q_r + Q_h, to the RK4 error (measured ~1e-11)
    total = res.heat_cooler + res.heat_regenerator + res.heat_heater
    assert total == pytest.approx(res.work, rel=1e-8)
    assert abs(res.heat_regenerator) < 1e-8 * res.regenerator_heat
    assert res.work == pytest.approx(res.work_compression + res.work_expansion, rel=1e-15)
    assert 0 < res.efficiency < 1 - GPU3["tk"] / GPU3["th"]
    assert res.heat_cooler < 0 < res.heat_heater
    # the gas in the working spaces leaves the heat exchangers' temperatures
    assert np.min(res.te) < GPU3["th"] and np.max(res.tc) > GPU3["tk"]
    # mass conservation: what leaves the compression space over a cycle comes back
    h = 2 * np.pi / (res.theta.size - 1)
    for f in (res.flow_ck, res.flow_kr, res.flow_rh, res.flow_he):
        assert abs(np.sum(f[:-1]) * h) < 1e-6 * np.sum(np.abs(f[:-1])) * h


def test_adiabatic_rk4_converges_with_the_step():
    """Halving the step changes the work by far less than it did before (RK4 with the
    conditional temperatures switching): 360 -> 720 -> 1440 steps."""
    d = GPU3
    mr = _gas(d)
    w = [float(st.adiabatic_cycle(mr, *_args(d, 2 * n + 1), G_HE, R_HE).work)
         for n in (360, 720, 1440)]  # fmt: skip
    assert abs(w[2] - w[1]) <= abs(w[1] - w[0]) and abs(w[2] - w[1]) < 1e-6 * w[2]


def test_adiabatic_tends_to_schmidt_as_gamma_tends_to_one():
    """gamma -> 1: no temperature change under compression, so T_c = T_k, T_e = T_h."""
    for d in (GPU3, {**GPU3, "vk": 0.0, "vr": 0.0, "vh": 0.0}):
        mr = _gas(d)
        schmidt = st.schmidt_cycle(mr, *_args(d, 721), G_HE, R_HE)
        errs = []
        for g in (1.01, 1.001):
            res = st.adiabatic_cycle(mr, *_args(d, 721), g, R_HE)
            errs.append(abs(res.work / schmidt.work - 1))
            assert np.max(np.abs(res.tc - d["tk"])) < 300 * (g - 1)
            assert np.max(np.abs(res.pressure / schmidt.pressure[..., ::2] - 1)) < 5 * (g - 1)
        assert errs[1] < 0.2 * errs[0] and errs[1] < 1e-3  # first order in gamma - 1


def test_adiabatic_effectiveness_correction(gpu3_adiabatic):
    mr, ideal = gpu3_adiabatic
    worse = st.adiabatic_cycle(mr, *_args(GPU3, 1441), G_HE, R_HE,
                               regenerator_effectiveness=0.95)  # fmt: skip
    loss = 0.05 * ideal.regenerator_heat
    assert worse.work == pytest.approx(ideal.work, rel=1e-12)
    assert worse.heat_in == pytest.approx(ideal.heat_in + loss, rel=1e-12)
    assert worse.heat_out == pytest.approx(ideal.heat_out + loss, rel=1e-12)
    assert worse.efficiency < ideal.efficiency


def test_work_scales_with_the_gas_charge():
    """Ideal gas: p, W and Q are proportional to M R, temperatures unchanged."""
    d = GPU3
    mr = _gas(d)
    a = st.adiabatic_cycle(mr, *_args(d, 721), G_HE, R_HE)
    b = st.adiabatic_cycle(2.5 * mr, *_args(d, 721), G_HE, R_HE)
    assert b.work == pytest.approx(2.5 * a.work, rel=1e-9)
    assert b.heat_in == pytest.approx(2.5 * a.heat_in, rel=1e-9)
    np.testing.assert_allclose(b.te, a.te, rtol=1e-9)


def test_a_batch_of_designs_equals_the_designs_one_by_one():
    """Designs along leading axes (2, 3) vs one at a time: the same to the periodicity
    tolerance (a batch iterates until its slowest design is periodic): 1e-8 relative."""
    rng = np.random.default_rng(7)
    th = rng.uniform(600, 1000, (2, 3))
    alpha = rng.uniform(np.radians(60), np.radians(120), (2, 3))
    vh = rng.uniform(0, 80e-6, (2, 3))
    d = {**GPU3, "th": th, "alpha": alpha, "vh": vh}
    vc, ve, dvc, dve = np.broadcast_arrays(*sinusoidal(d["vswc"], d["vswe"], d["vclc"],
                                                       d["vcle"], alpha, 721))  # fmt: skip
    args = (d["vk"], d["vr"], vh, d["tk"], th)
    mr = st.schmidt_gas_for_mean_pressure(4e6, vc, ve, *args)
    for solve in (st.adiabatic_cycle, st.schmidt_cycle):
        batch = solve(mr, vc, ve, dvc, dve, *args, G_HE, R_HE)
        assert batch.work.shape == (2, 3) and batch.pressure.shape[:2] == (2, 3)
        for i in np.ndindex(2, 3):
            one = solve(mr[i], vc[i], ve[i], dvc[i], dve[i], d["vk"], d["vr"], vh[i], d["tk"],
                        th[i], G_HE, R_HE)  # fmt: skip
            for key in ("work", "heat_in", "heat_out", "regenerator_heat", "efficiency"):
                assert getattr(batch, key)[i] == pytest.approx(getattr(one, key), rel=1e-8), key
            np.testing.assert_allclose(batch.pressure[i], one.pressure, rtol=1e-8)


def test_periodic_pressure_interpolates_the_cycle(gpu3_adiabatic):
    _, res = gpu3_adiabatic
    p = st.periodic_pressure(res, res.theta, 2 * np.pi)
    np.testing.assert_allclose(p[:-1], res.pressure[:-1], rtol=1e-14)
    mid = 0.5 * (res.theta[1:] + res.theta[:-1])
    np.testing.assert_allclose(st.periodic_pressure(res, mid + 2 * np.pi, 2 * np.pi),
                               st.periodic_pressure(res, mid, 2 * np.pi), rtol=1e-13)  # fmt: skip
    assert st.periodic_pressure(res, np.zeros((3, 4)), 2 * np.pi).shape == (3, 4)


def test_adiabatic_needs_an_odd_number_of_samples():
    with pytest.raises(ValueError, match="2 N"):
        st.adiabatic_cycle(1.0, *_args(GPU3, 720), G_HE, R_HE)


def test_charge_gas_and_gases():
    assert st.charge_gas(2e5, 1e-3, 300.0) == pytest.approx(2e5 * 1e-3 / 300)
    assert st.gas_properties("helium") == (2078.6, 5 / 3)
    assert set(st.GASES) == {"air", "helium", "hydrogen"}
