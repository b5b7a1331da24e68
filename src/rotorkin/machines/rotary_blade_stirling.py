"""The rotary-blade engine as a Stirling engine: a lagging cold blade set, heat exchangers.

The engine's chambers (:mod:`rotorkin.machines.rotary_blade`) are the expansion (hot)
spaces; an identical second blade set on the same drive, lagging by ``phase_angle`` of a
chamber's volume cycle, gives the compression (cold) spaces. Hot chamber ``j`` and cold
chamber ``j`` are joined through a heater, a regenerator and a cooler: one Stirling
circuit per chamber pair, solved by :mod:`rotorkin.analysis.stirling` (I. Urieli and
D. M. Berchowitz, *Stirling Cycle Engine Analysis*, 1984: Schmidt or ideal adiabatic).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from rotorkin.analysis import stirling as sa
from rotorkin.core.angles import fmt_deg
from rotorkin.core.errors import ParameterError
from rotorkin.machines.rotary_blade import (
    _TWO_PI,
    IsothermalGas,
    RotaryBlade,
    chamber_volume_derivative,
    chamber_volumes,
    gas_member_torques,
)

__all__ = [
    "PRESSURE_MODELS",
    "DEAD_VOLUME_FRACTIONS",
    "STIRLING_CHECKS",
    "STIRLING_STEPS",
    "StirlingLoads",
    "StirlingColumns",
    "dead_volumes",
    "cold_set_lag",
    "StirlingSolution",
    "stirling_solution",
    "select",
    "stirling_state",
    "stirling_summary",
    "stirling_numbers",
    "NUMBER_KEYS",
]


# --- Stirling engine: a second blade set for the cold spaces ------------------------------
#: Chamber pressure models of :class:`StirlingLoads` (``isothermal``: :class:`IsothermalGas`).
PRESSURE_MODELS = ("adiabatic", "schmidt", "isothermal")
#: Dead volumes of a circuit when not given, as fractions of a chamber's swept volume
#: (0.9 in all; the GPU-3 engine of Urieli and Berchowitz has 0.59, 0.42, 0.11 = 1.12).
DEAD_VOLUME_FRACTIONS = {"heater_volume": 0.3, "regenerator_volume": 0.4, "cooler_volume": 0.2}
#: Parameters of :class:`StirlingLoads` in the order their check names them.
STIRLING_CHECKS = ("charge_pressure", "hot_temperature", "cold_temperature", "pressure_model",
                   "gas", "phase_angle", "heater_volume", "regenerator_volume",
                   "cooler_volume", "regenerator_effectiveness")  # fmt: skip
#: RK4 steps of the ideal adiabatic cycle per period of the drive's law.
STIRLING_STEPS = 720


@dataclass(frozen=True)
class StirlingLoads:
    """Loads of the Stirling models (``schmidt``, ``adiabatic``): one design, scalars.

    Attributes
    ----------
    charge_pressure : float
        Pressure of a circuit's gas at the circuit's largest total volume, all at the
        cooler's temperature [Pa], > 0.
    hot_temperature, cold_temperature : float
        Heater and cooler gas temperatures ``T_h``, ``T_k`` [K], > 0.
    pressure_model : str
        ``"adiabatic"`` (ideal adiabatic) or ``"schmidt"`` (isothermal spaces).
    gas : str
        ``"air"``, ``"helium"`` or ``"hydrogen"`` (:data:`rotorkin.analysis.stirling.GASES`).
    phase_angle : float
        Lag of the cold set behind the hot set, as a fraction of ``2 pi`` of a chamber's
        volume cycle [rad], ``0 <= phase_angle <= 2 pi`` (default pi/2).
    heater_volume, regenerator_volume, cooler_volume : float or None
        Volumes of each circuit's heat exchangers [m^3], >= 0; None: the fraction
        :data:`DEAD_VOLUME_FRACTIONS` of a chamber's swept volume.
    regenerator_effectiveness : float
        ``0 <= eps <= 1``; ``(1 - eps)`` of the regenerator's heat per cycle loads the
        heater and the cooler (default 1, the ideal regenerator).
    """

    charge_pressure: float
    hot_temperature: float
    cold_temperature: float
    pressure_model: str = "adiabatic"
    gas: str = "air"
    phase_angle: float = 0.5 * np.pi
    heater_volume: float | None = None
    regenerator_volume: float | None = None
    cooler_volume: float | None = None
    regenerator_effectiveness: float = 1.0

    def __post_init__(self):
        IsothermalGas(self.charge_pressure, self.hot_temperature, self.cold_temperature)
        if self.pressure_model not in ("adiabatic", "schmidt"):
            raise ParameterError(
                "pressure_model", repr(self.pressure_model), "'adiabatic' or 'schmidt'"
            )
        if self.gas not in sa.GASES:
            raise ParameterError("gas", repr(self.gas), "one of " + ", ".join(sa.GASES))
        phase = float(self.phase_angle)
        if not (np.isfinite(phase) and 0.0 <= phase <= _TWO_PI):
            raise ParameterError("phase_angle", fmt_deg(phase),
                                 "0 deg <= phase_angle <= 360 deg")  # fmt: skip
        for name in ("heater_volume", "regenerator_volume", "cooler_volume"):
            v = getattr(self, name)
            if v is not None and not (np.isfinite(float(v)) and float(v) >= 0.0):
                raise ParameterError(name, f"{float(v) * 1e6:g} cm^3", f"{name} >= 0 cm^3")
        eps = float(self.regenerator_effectiveness)
        if not (np.isfinite(eps) and 0.0 <= eps <= 1.0):
            raise ParameterError("regenerator_effectiveness", f"{eps:g}",
                                 "0 <= regenerator_effectiveness <= 1")  # fmt: skip
        for name in STIRLING_CHECKS:
            v = getattr(self, name)
            if v is not None and name not in ("pressure_model", "gas"):
                object.__setattr__(self, name, float(v))


@dataclass(frozen=True)
class StirlingColumns:
    """The loads of :class:`StirlingLoads` for many designs at once: arrays ``(m,)``.

    The same fields (floats or arrays of designs; a dead volume None takes its default
    fraction of each design's swept volume), one pressure model and one gas for all.
    Not checked here: the caller has checked every design as :class:`StirlingLoads`
    does (a sweep's kernel, whose config schema bounds every field).
    """

    charge_pressure: np.ndarray
    hot_temperature: np.ndarray
    cold_temperature: np.ndarray
    pressure_model: str = "adiabatic"
    gas: str = "air"
    phase_angle: np.ndarray | float = 0.5 * np.pi
    heater_volume: np.ndarray | float | None = None
    regenerator_volume: np.ndarray | float | None = None
    cooler_volume: np.ndarray | float | None = None
    regenerator_effectiveness: np.ndarray | float = 1.0


def dead_volumes(loads: StirlingLoads, swept_volume) -> tuple:
    """``(V_k, V_r, V_h)`` of a circuit [m^3]: the loads' or the default fractions.

    ``swept_volume`` and the loads' volumes: floats, or arrays of designs (see
    :func:`stirling_solution`).
    """
    out = []
    swept = np.asarray(swept_volume, dtype=float)
    for name in ("cooler_volume", "regenerator_volume", "heater_volume"):
        v = getattr(loads, name)
        out.append(DEAD_VOLUME_FRACTIONS[name] * swept if v is None else v)
    return tuple(_plain(v) for v in out)


def _plain(v):
    """A 0-d array as a float; arrays of designs as they are."""
    return float(v) if np.ndim(v) == 0 else v


def cold_set_lag(phase_angle, period: float, cycles_per_period: int):
    """Shaft angle by which the cold set lags the hot set [rad].

    ``phase_angle`` of a chamber's volume cycle, whose length in shaft angle is
    ``period / cycles_per_period`` (exact for a law that sweeps each chamber once up
    and once down per cycle). A float, or an array for an array of phase angles.
    """
    lag = np.asarray(phase_angle, dtype=float) * float(period)
    return _plain(lag / (_TWO_PI * max(int(cycles_per_period), 1)))


@dataclass(frozen=True)
class StirlingSolution:
    """The periodic cycle of every circuit of a rotary-blade Stirling engine.

    Attributes
    ----------
    loads : StirlingLoads
    lag : float
        Shaft angle of the cold set behind the hot one [rad] (:func:`cold_set_lag`).
    period : float
        Cycle of the circuits in shaft angle, the period of the drive's law [rad].
    gas : ndarray, shape (2B,)
        ``M R`` of each circuit [J/K].
    dead : tuple of float
        ``(V_k, V_r, V_h)`` of each circuit [m^3].
    r_gas, gamma : float
        Gas constant [J/(kg K)] and ratio of heats.
    cycle : CycleResult
        :mod:`rotorkin.analysis.stirling`'s result, designs = circuits.
    """

    loads: StirlingLoads
    lag: float
    period: float
    gas: np.ndarray
    dead: tuple
    r_gas: float
    gamma: float
    cycle: object


def select(sol: StirlingSolution, rows) -> StirlingSolution:
    """The solution of some of its designs (a solution of :class:`StirlingColumns`).

    ``rows``: a slice or indices of the designs (the axis after the circuits').
    """
    pick = lambda v: v if v is None or np.ndim(v) == 0 else np.asarray(v)[rows]  # noqa: E731
    loads = dataclasses.replace(sol.loads, **{
        f.name: pick(getattr(sol.loads, f.name)) for f in dataclasses.fields(sol.loads)
        if f.name not in ("pressure_model", "gas")})  # fmt: skip
    cycle = dataclasses.replace(sol.cycle, **{
        f.name: getattr(sol.cycle, f.name)[:, rows] for f in dataclasses.fields(sol.cycle)
        if np.ndim(getattr(sol.cycle, f.name)) >= 2})  # fmt: skip
    return dataclasses.replace(sol, loads=loads, lag=pick(sol.lag), gas=sol.gas[:, rows],
                               dead=tuple(pick(v) for v in sol.dead), cycle=cycle)  # fmt: skip


def _largest(x) -> np.ndarray:
    """Largest value of periodic samples along the last axis, refined by a parabola."""
    x = np.asarray(x, dtype=float)[..., :-1]
    i = np.argmax(x, axis=-1)
    n = x.shape[-1]
    take = lambda k: np.take_along_axis(x, ((i + k) % n)[..., None], -1)[..., 0]  # noqa: E731
    a, b, c = take(-1), take(0), take(1)
    den = a - 2.0 * b + c
    with np.errstate(divide="ignore", invalid="ignore"):
        top = b - 0.125 * (c - a) ** 2 / den
    return np.where(den < 0.0, np.maximum(top, b), b)


def stirling_solution(machine: RotaryBlade, loads: StirlingLoads, motion, period: float,
                      cycles_per_period: int, swept_volume: float,
                      steps: int = STIRLING_STEPS) -> StirlingSolution:  # fmt: skip
    """Solve the ``2B`` circuits of the engine over one period of the drive's law.

    One design, or columns of designs: the machine's fields and the drive's parameters
    behind ``motion`` as ``(m, 1)`` columns and the loads' numbers as ``(m,)`` arrays
    (:class:`StirlingColumns`); the circuits then come first, ``(2B, m)``, and every
    design's cycle is the one it has alone.

    Parameters
    ----------
    machine : RotaryBlade
    loads : StirlingLoads or StirlingColumns
    motion : callable
        ``motion(theta) -> Motion`` of the blade pairs (as mounted), any shape of theta.
    period : float
        Period of the law in shaft angle [rad].
    cycles_per_period : int
        Volume cycles of a chamber per period (for the lag).
    swept_volume : float or ndarray (m,)
        A chamber's swept volume [m^3] (for the default dead volumes).
    steps : int
        RK4 steps per period (the volumes are sampled at ``2 steps + 1`` angles).
    """
    lag = cold_set_lag(loads.phase_angle, period, cycles_per_period)
    theta = np.linspace(0.0, period, 2 * steps + 1)
    hot, cold = motion(theta), motion(theta - (lag if np.ndim(lag) == 0 else lag[:, None]))
    ve, vc = chamber_volumes(machine, hot.q), chamber_volumes(machine, cold.q)
    dve = chamber_volume_derivative(machine, hot.dq)
    dvc = chamber_volume_derivative(machine, cold.dq)
    vk, vr, vh = dead_volumes(loads, swept_volume)
    tk, th = loads.cold_temperature, loads.hot_temperature
    r_gas, gamma = sa.gas_properties(loads.gas)
    gas = sa.charge_gas(loads.charge_pressure, _largest(vc + ve) + vk + vr + vh, tk)
    solve = sa.adiabatic_cycle if loads.pressure_model == "adiabatic" else sa.schmidt_cycle
    cycle = solve(gas, vc, ve, dvc, dve, vk, vr, vh, tk, th, gamma, r_gas, period,
                  loads.regenerator_effectiveness)  # fmt: skip
    return StirlingSolution(loads, lag, float(period), gas, (vk, vr, vh), r_gas, gamma, cycle)


def stirling_state(machine: RotaryBlade, sol: StirlingSolution, hot, cold) -> dict:
    """Volumes, pressures and torques of both blade sets at a set of shaft angles.

    Parameters
    ----------
    hot, cold : Motion
        The blade pairs of the hot set at ``theta`` and of the cold set (the same law
        at ``theta - lag``).

    Returns
    -------
    dict of ndarray
        ``volume_hot``, ``volume_cold``, ``dvolume_hot``, ``dvolume_cold`` (2B, ...);
        ``pressure`` (2B, ...) of each circuit [Pa] (Schmidt: exact at ``theta``;
        adiabatic: the cycle's periodic cubic spline); ``members`` (2, ...), the gas
        torques on the hot set's blade pairs [N m]; ``shaft`` (...), the torque of
        both sets on the shaft, ``sum_j p_j (dV_hot,j + dV_cold,j)/dtheta`` [N m].
    """
    ve, vc = chamber_volumes(machine, hot.q), chamber_volumes(machine, cold.q)
    dve = chamber_volume_derivative(machine, hot.dq)
    dvc = chamber_volume_derivative(machine, cold.dq)
    loads = sol.loads
    if loads.pressure_model == "schmidt":
        vk, vr, vh = sol.dead
        if np.ndim(sol.gas) == 1:  # one design: the circuits against any shape of angles
            flat = (ve.shape[0], -1)
            p = sa.schmidt_pressure(sol.gas, vc.reshape(flat), ve.reshape(flat), vk, vr, vh,
                                    loads.cold_temperature, loads.hot_temperature)  # fmt: skip
            p = p.reshape(ve.shape)
        else:  # (2B, m) circuits of designs against (2B, m, n) volumes
            p = sa.schmidt_pressure(sol.gas, vc, ve, vk, vr, vh, loads.cold_temperature,
                                    loads.hot_temperature)  # fmt: skip
    else:
        p = sa.periodic_pressure(sol.cycle, hot.theta, sol.period)
    return {
        "volume_hot": ve, "volume_cold": vc, "dvolume_hot": dve, "dvolume_cold": dvc,
        "pressure": p, "members": gas_member_torques(machine, p),
        "shaft": np.sum(p * (dve + dvc), axis=0),
    }  # fmt: skip


#: Numeric keys of :func:`stirling_summary` (:func:`stirling_numbers`), in its order.
NUMBER_KEYS = ("phase_angle_deg", "cold_set_lag_deg", "circuits", "heater_volume_cm3",
               "regenerator_volume_cm3", "cooler_volume_cm3", "regenerator_effectiveness",
               "charge_pressure_bar", "gas_mass_g", "indicated_work_J", "heat_in_J_per_rev",
               "heat_out_J_per_rev", "regenerator_heat_J_per_rev", "indicated_efficiency",
               "carnot_efficiency", "peak_pressure_bar", "mean_pressure_bar",
               "hot_temperature_K", "cold_temperature_K", "periodic_residual_K")  # fmt: skip


def stirling_numbers(sol: StirlingSolution, periods_per_rev: float) -> dict:
    """The numbers of :func:`stirling_summary` (:data:`NUMBER_KEYS`), summed over the circuits.

    Floats for one design; arrays ``(m,)`` for a solution of columns of designs
    (the circuits on the first axis).
    """
    c, ld = sol.cycle, sol.loads
    k = float(periods_per_rev)
    work, heat_in = np.sum(c.work, axis=0) * k, np.sum(c.heat_in, axis=0) * k
    vk, vr, vh = sol.dead
    angles = (0, -1)  # circuits and samples
    with np.errstate(divide="ignore", invalid="ignore"):
        efficiency = np.where(heat_in > 0.0, work / heat_in, np.nan)
    out = {
        "phase_angle_deg": np.degrees(ld.phase_angle),
        "cold_set_lag_deg": np.degrees(sol.lag),
        "circuits": np.shape(sol.gas)[0],
        "heater_volume_cm3": vh * 1e6,
        "regenerator_volume_cm3": vr * 1e6,
        "cooler_volume_cm3": vk * 1e6,
        "regenerator_effectiveness": ld.regenerator_effectiveness,
        "charge_pressure_bar": ld.charge_pressure * 1e-5,
        "gas_mass_g": np.sum(sol.gas, axis=0) / sol.r_gas * 1e3,
        "indicated_work_J": work,
        "heat_in_J_per_rev": heat_in,
        "heat_out_J_per_rev": np.sum(c.heat_out, axis=0) * k,
        "regenerator_heat_J_per_rev": np.sum(c.regenerator_heat, axis=0) * k,
        "indicated_efficiency": efficiency,
        "carnot_efficiency": 1.0 - ld.cold_temperature / ld.hot_temperature,
        "peak_pressure_bar": np.max(c.pressure, axis=angles) * 1e-5,
        "mean_pressure_bar": np.mean(c.pressure[..., :-1], axis=angles) * 1e-5,
        "hot_temperature_K": ld.hot_temperature,
        "cold_temperature_K": ld.cold_temperature,
        "periodic_residual_K": np.max(c.residual, axis=0),
    }
    return {key: out[key] for key in NUMBER_KEYS}


def stirling_summary(sol: StirlingSolution, periods_per_rev: float) -> dict:
    """Per-revolution numbers of the Stirling models of one design, summed over the circuits.

    Returns
    -------
    dict
        ``indicated_work_J``, ``heat_in_J_per_rev``, ``heat_out_J_per_rev``,
        ``regenerator_heat_J_per_rev``, ``indicated_efficiency``,
        ``carnot_efficiency``, ``peak_pressure_bar``, ``mean_pressure_bar``,
        ``gas_mass_g``, the loads and the dead volumes, ``periodic_residual_K``
        (:func:`stirling_numbers`), the model and the gas.
    """
    numbers = stirling_numbers(sol, periods_per_rev)
    numbers = {k: int(v) if k == "circuits" else float(v) for k, v in numbers.items()}
    return {"pressure_model": sol.loads.pressure_model, "gas": sol.loads.gas, **numbers}
