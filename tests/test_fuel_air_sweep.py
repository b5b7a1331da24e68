"""The fuel-air cycle at sweep speed: the sweep kernel against the one-design study, and the
compiled integrator against the numpy one.

Independent checks: every cycle metric of random designs from the wobble-cam sweep kernel
(blocks of designs on threads, compiled or numpy) against the study of each design alone
(:func:`rotorkin.drives.evaluate`, its own kinematics and turning points); the compiled
Runge-Kutta loop against the numpy operations on arrays of chambers; the gas tables against
linear interpolation (:func:`numpy.interp`) of their 1 K nodes, and those nodes against
Cantera's GRI-Mech 3.0 mixture.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin import drives
from rotorkin.analysis import combustion as cb
from rotorkin.analysis import gas as gs
from rotorkin.core import fused
from rotorkin.core.batch import Designs
from rotorkin.drives.wobble_cam import sweep_cycle
from rotorkin.io.config import load_config
from rotorkin.sweep import evaluate_designs

EXAMPLE = "wobble-cam-engine"
#: The cycle's metrics (the machine's other metrics are closed forms, tested elsewhere).
CYCLE = ("trapped_mass_mg", "compression_end_pressure_bar", "peak_pressure_bar",
         "peak_pressure_angle_deg", "peak_temperature_K", "indicated_work_J",
         "fuel_energy_J_per_rev", "heat_added_J_per_rev", "heat_to_walls_J_per_rev",
         "indicated_efficiency", "imep_bar", "indicated_work_per_cycle_a_J",
         "indicated_work_per_cycle_b_J", "mean_torque_Nm", "indicated_power_kW",
         "otto_efficiency")  # fmt: skip
#: Base loads: the example's (NASA gas), and constant gamma with another burn and walls.
BASES = {
    "nasa": [],
    "constant": ["loads.gas_properties=constant", "loads.burn_start=-25 deg",
                 "loads.burn_duration=70 deg", "loads.wall_temperature=520 K"],
}  # fmt: skip


def _designs(count: int, seed: int) -> list[list[str]]:
    """Random designs (seeded): tilt, roller axis angle, compression ratio, clearance, width."""
    rng = np.random.default_rng(seed)
    return [[f"drive.plate_tilt={rng.uniform(22, 50):.6f} deg",
             f"drive.roller_axis_angle={rng.uniform(80, 100):.6f} deg",
             f"machine.compression_ratio={rng.uniform(7, 15):.6f}",
             f"machine.clearance_volume={rng.uniform(0, 3):.6f} cm^3",
             f"machine.axial_width={rng.uniform(25, 50):.6f} mm"]
            for _ in range(count)]  # fmt: skip


KEYS = ("drive.plate_tilt", "drive.roller_axis_angle", "machine.compression_ratio",
        "machine.clearance_volume", "machine.axial_width")  # fmt: skip


@pytest.mark.parametrize("base", list(BASES))
def test_the_sweeps_cycle_equals_the_study_of_each_design(base, monkeypatch):
    """Seeded random designs with Woschni walls and a Wiebe burn: the sweep kernel, compiled
    and numpy, in blocks of 2 designs on 2 threads, equals the study of each design (numpy
    path) to 1e-9 in every cycle metric."""
    sets = _designs(5, seed=11 if base == "nasa" else 12)
    monkeypatch.setenv(fused.KERNEL_ENV, "numpy")
    cfgs = [load_config(example=EXAMPLE, sets=[*BASES[base], *s])[0] for s in sets]
    studies = [drives.evaluate(cfg).summary for cfg in cfgs]
    base_cfg = load_config(example=EXAMPLE, sets=BASES[base])[0]
    table = {k: np.array([c[k.split(".")[0]][k.split(".")[1]] for c in cfgs]) for k in KEYS}
    monkeypatch.setattr(sweep_cycle, "CYCLE_BLOCK", {"numba": 2, "numpy": 2})
    for kernel in ("numba", "numpy"):
        monkeypatch.setenv(fused.KERNEL_ENV, kernel)
        res = evaluate_designs(Designs(base_cfg, table, len(cfgs)), CYCLE, samples=361,
                               threads=2)  # fmt: skip
        assert np.all(res["reason"] == 0)
        for i, s in enumerate(studies):
            for key in CYCLE:
                assert res["metrics"][key][i] == pytest.approx(s[key], rel=1e-9, abs=1e-12), (
                    kernel, i, key)  # fmt: skip
    # the designs differ: the comparison is not of one design with itself
    assert np.ptp([s["indicated_work_J"] for s in studies]) > 0.1 * studies[0]["indicated_work_J"]


def test_blocks_mixing_spin_ratios_pistons_and_sections_equal_the_study(monkeypatch):
    """Designs of different spin ratios, piston counts and sections in the same blocks (of 3):
    each equals its own study to 1e-9."""
    cases = [(-2, 4, "rectangular"), (-1, 4, "circular"), (-2, 6, "rectangular"),
             (2, 4, "circular"), (-3, 6, "rectangular"), (-2, 4, "circular")]  # fmt: skip
    cfgs = [load_config(example=EXAMPLE, sets=[f"drive.spin_ratio={n}",
                                               f"machine.pistons_per_rotor={z}",
                                               f"machine.section={sec}",
                                               "drive.plate_tilt=30 deg"])[0]
            for n, z, sec in cases]  # fmt: skip
    studies = [drives.evaluate(cfg).summary for cfg in cfgs]
    keys = ("drive.spin_ratio", "machine.pistons_per_rotor", "machine.section")
    table = {k: np.array([c[k.split(".")[0]][k.split(".")[1]] for c in cfgs]) for k in keys}
    monkeypatch.setattr(sweep_cycle, "CYCLE_BLOCK", {"numba": 3, "numpy": 3})
    res = evaluate_designs(Designs(cfgs[0], table, len(cfgs)), CYCLE, samples=361, threads=2)
    assert np.all(res["reason"] == 0)
    for i, s in enumerate(studies):
        for key in CYCLE:
            assert res["metrics"][key][i] == pytest.approx(s[key], rel=1e-9, abs=1e-12), (i, key)


def _chambers(n: int, seed: int, thin: bool = False):
    """Random piston-like chambers on the cycle grid, their charge and walls."""
    rng = np.random.default_rng(seed)
    x = np.linspace(-np.pi, np.pi, 4 * 90 + 1)
    vc = rng.uniform(3e-6, 9e-6, (n, 1))
    vs = rng.uniform(30e-6, 90e-6, (n, 1))
    skew = rng.uniform(-0.2, 0.2, (n, 1))
    v = vc + vs / 2 * (1 - np.cos(x + skew * np.sin(x)))
    dv = vs / 2 * np.sin(x + skew * np.sin(x)) * (1 + skew * np.cos(x))
    area = (2e-3 + rng.uniform(5, 20, (n, 1)) * v) * (1e4 if thin else 1.0)
    diameter = np.full(n, 1e-9) if thin else rng.uniform(0.02, 0.06, n)
    walls = cb.Walls(area=area, diameter=diameter, wall_speed=rng.uniform(5, 15, n),
                     seconds=np.full((n, x.size), 1e-4), temperature=450.0)  # fmt: skip
    return x, v, dv, walls


@pytest.mark.parametrize("props", ["constant", "nasa"])
def test_the_compiled_cycle_equals_the_numpy_cycle(props):
    """Same operations in the same order per chamber: equal to 1e-14 relative (the only
    possible difference: numpy's vectorised exp/log against libm's, each within an ulp;
    a relative error of 1e-16 per step stays under 1e-14 over the 360 steps)."""
    gas = gs.ConstantGas(1.33) if props == "constant" else gs.NasaGas(residual_fraction=0.07)
    x, v, dv, walls = _chambers(13, seed=3)  # 13: one group of 8 chambers and a partial one
    mass = 1e5 * v[:, 0] / (gas.gas_constant(0.0) * 320.0)
    heat = cb.heat_of_charge(cb.Charge(), mass)
    burn = cb.Wiebe(np.radians(-15.0), np.radians(55.0), 5.0, 2.0)
    out = {k: cb.closed_cycle(x, v, dv, mass=mass, heat=heat, gas=gas, temperature=320.0,
                              burn=burn, walls=walls, kernel=k)
           for k in ("numpy", "numba")}  # fmt: skip
    for key in ("T", "p", "p_left", "dp", "work", "heat_wall", "energy_rise"):
        a, b = out["numpy"][key], out["numba"][key]
        scale = np.max(np.abs(a), axis=-1, keepdims=True) if a.ndim > 1 else np.abs(a)
        assert np.all(np.abs(a - b) <= 1e-14 * scale), key
    # and the cycle is one: work + heat to the walls + energy rise = heat released
    r = out["numba"]
    balance = r["work"] + r["heat_wall"] + r["energy_rise"] - r["heat_released"]
    assert np.all(np.abs(balance) < 1e-5 * r["heat_released"])


def test_a_chamber_without_a_cycle_gives_nan_on_both_paths():
    """Walls that take the heat faster than a step (a hydraulic diameter of 1 nm and 1e4 times
    the area): both paths give non-finite pressures (what the study refuses) at the same
    nodes."""
    gas = gs.NasaGas()
    x, v, dv, walls = _chambers(3, seed=5, thin=True)
    mass = 1e5 * v[:, 0] / (gas.gas_constant(0.0) * 320.0)
    with np.errstate(all="ignore"):
        out = [cb.closed_cycle(x, v, dv, mass=mass, heat=100.0 * mass / mass.max(), gas=gas,
                               temperature=320.0, burn=cb.Wiebe(), walls=walls, kernel=k)["p"]
               for k in ("numpy", "numba")]  # fmt: skip
    assert not np.all(np.isfinite(out[0]))
    np.testing.assert_array_equal(np.isfinite(out[0]), np.isfinite(out[1]))


@pytest.mark.parametrize(("phi", "hc"), [(1.0, 1.87), (0.7, 2.0), (1.3, 1.0)])
def test_the_gas_nodes_are_canteras(phi, hc):
    """rotorkin's NASA polynomials against Cantera's GRI-Mech 3.0 mixture (the same data,
    evaluated by another code): the coefficients and molar masses, then c_v and R of air
    and of the burnt gas on every node from 200 to 5000 K (both ranges of the polynomials,
    and below Cantera's 300 K bound for N2 and Ar), and the sensible energy against
    Cantera's internal energy (the trapezoid rule on a 1 K grid: 1e-7 of its span)."""
    import cantera as ct

    sol = ct.Solution("gri30.yaml", transport_model=None)
    for name, (molar_mass, t_mid, low, high) in gs.NASA7.items():
        coeffs = sol.species(name).thermo.coeffs
        assert coeffs[0] == t_mid and tuple(coeffs[8:13]) == low and tuple(coeffs[1:6]) == high
        assert sol.molecular_weights[sol.species_index(name)] == pytest.approx(
            molar_mass, rel=1e-15
        )
    for comp in (gs.AIR, gs.burnt_composition(phi, hc)):
        t, r, cv, u = gs._tables(tuple(sorted(comp.items())))
        states = ct.SolutionArray(sol, len(t))
        states.TPX = t, 1.0e5, comp
        np.testing.assert_allclose(cv, states.cv_mass, rtol=1e-13)
        assert r == pytest.approx(ct.gas_constant / states.mean_molecular_weight[0], rel=1e-14)
        exact = states.int_energy_mass - np.interp(298.15, t, states.int_energy_mass)
        np.testing.assert_allclose(u, exact, rtol=0, atol=1e-7 * np.ptp(exact))


@pytest.mark.parametrize("residual", [0.0, 0.05, 0.3])
def test_the_gas_tables_are_linear_interpolation_of_their_nodes(residual):
    """The tables (one index per temperature) against numpy.interp of the 1 K nodes,
    inside the range, between the nodes, beyond both ends and at NaN."""
    gas = gs.NasaGas(residual_fraction=residual)
    tab = gas.tables()
    t = np.concatenate([np.random.default_rng(1).uniform(150.0, 5100.0, 2000),
                        [200.0, 200.5, 4999.5, 5000.0, 100.0, 9000.0]])  # fmt: skip
    cvu, cvb, du = tab.lookup(t)
    np.testing.assert_allclose(cvu, gas.cv(t, 0.0), rtol=1e-13)
    np.testing.assert_allclose(cvb, gas.cv(t, 1.0), rtol=1e-13)
    scale = np.max(np.abs(gas.burnt_minus_unburnt(t)))
    np.testing.assert_allclose(du, gas.burnt_minus_unburnt(t), rtol=0, atol=1e-13 * scale)
    assert tab.r_unburnt == pytest.approx(gas.gas_constant(0.0), rel=1e-15)
    assert tab.r_burnt == pytest.approx(gas.gas_constant(1.0), rel=1e-15)
    assert all(np.isnan(v) for v in tab.lookup(np.array([np.nan])))
    const = gs.ConstantGas(1.3).tables()
    cv = const.lookup(np.array([1.0, 300.0, 1e5]))
    assert np.all(cv[0] == gs.ConstantGas(1.3).cv(300.0, 0.0)) and np.all(cv[2] == 0.0)
