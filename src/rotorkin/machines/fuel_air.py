"""The fuel-air cycle of a twin-rotor engine's chambers on any drive.

Each chamber runs the four strokes between the turning points of the rotors'
relative angle: intake (volume rising), compression, power, exhaust. Intake closes
and the exhaust opens at the largest volume (ideal timing at the dead centres); the
closed part in between, compression and power, is the single-zone model of
:mod:`rotorkin.analysis.combustion`: the charge trapped at intake closure, a Wiebe
burn, Woschni heat transfer to walls whose area follows the chamber, and the gas's
properties (:mod:`rotorkin.analysis.gas`). Intake is at the intake pressure, exhaust
at the ambient pressure (the pumping loop ``(p_i - p_a) (V_max - V_min)`` per cycle).

The chamber's *cycle angle* ``x`` runs 180 deg per stroke, 0 at the dead centre of
smallest volume, linear in the shaft angle within each stroke: a drive's strokes may
take unequal shaft angles and the burn is timed in the cycle, like a crank angle.

Which closed parts exist: every turning point starts the compression of the chambers
of one kind (A or B) at their largest volume; each of these ``n`` parts (``n``
turning points per period of the drive) is integrated once, over its own two strokes
of the drive's law, with all parts in arrays. A chamber's pressure at a shaft angle is
read from its part's table by cubic Hermite interpolation on the integration grid.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from rotorkin.analysis import combustion as cb
from rotorkin.analysis import engine_cycle as ec
from rotorkin.analysis import gas as gs
from rotorkin.core.errors import ParameterError
from rotorkin.machines import twin_rotor as tr

__all__ = [
    "FuelAirLoads",
    "ChargeCycle",
    "charge_cycle",
    "loads_of",
    "walls_of",
    "summarize",
    "compression_limit",
    "IDEAL_ONLY",
]

#: Steps of the integration per stroke (0.5 deg of cycle angle), at least; a short burn gets
#: more, so that :data:`STEPS_PER_BURN` steps cover it (up to :data:`STEPS_MAX`).
STEPS_PER_STROKE = 360
STEPS_PER_BURN = 30
STEPS_MAX = 20_000
#: Highest temperature the compression alone may reach [K]: above it the single-zone model
#: (and its gas tables, which end at 5000 K) no longer describe a charge.
COMPRESSION_TEMPERATURE_MAX = 4000.0
#: The [loads] keys the ideal cycle reads and the fuel-air cycle does not.
IDEAL_ONLY = ("polytropic_exponent", "heat_per_cycle")


@dataclass(frozen=True)
class FuelAirLoads:
    """Fuel-air cycle inputs (SI; config section ``[loads]`` with ``model = "fuel_air"``).

    Defaults: a naturally aspirated spark-ignition engine on gasoline (Heywood
    table D.4 for the fuel; ch. 9.2.1 for the Wiebe constants ``a = 5``, ``m = 2``).
    """

    ambient_pressure: float = 1.0e5
    intake_pressure: float = 1.0e5
    intake_temperature: float = 320.0
    residual_fraction: float = 0.05
    equivalence_ratio: float = 1.0
    fuel_heating_value: float = 44.0e6
    stoichiometric_afr: float = 14.6
    fuel_hc_ratio: float = 1.87
    combustion_efficiency: float = 0.97
    burn_start: float = float(np.radians(-10.0))
    burn_duration: float = float(np.radians(50.0))
    wiebe_a: float = 5.0
    wiebe_m: float = 2.0
    heat_transfer: str = "woschni"
    wall_temperature: float = 450.0
    gas_properties: str = "auto"
    specific_heat_ratio: float = 1.3

    def __post_init__(self):
        if self.burn_start + self.burn_duration > np.pi:
            raise ParameterError(
                "burn_duration",
                f"{np.degrees(self.burn_duration):.4g} deg",
                f"burn_start + burn_duration <= 180 deg (the exhaust opens there); "
                f"burn_start is {np.degrees(self.burn_start):.4g} deg",
            )

    def charge(self) -> cb.Charge:
        return cb.Charge(self.intake_pressure, self.intake_temperature, self.residual_fraction,
                         self.equivalence_ratio, self.stoichiometric_afr,
                         self.fuel_heating_value, self.combustion_efficiency)  # fmt: skip

    def burn(self) -> cb.Wiebe:
        return cb.Wiebe(self.burn_start, self.burn_duration, self.wiebe_a, self.wiebe_m)

    def gas(self):
        """The species' NASA polynomials (``nasa``, ``auto``) or one gamma (``constant``)."""
        if self.gas_properties in ("nasa", "auto"):
            return gs.NasaGas(self.equivalence_ratio, self.fuel_hc_ratio, self.residual_fraction)
        return gs.ConstantGas(self.specific_heat_ratio)


def loads_of(section: dict):
    """The cycle of a ``[loads]`` section: :class:`FuelAirLoads` or the ideal cycle."""
    cls = ec.IdealCycle if section.get("model", "fuel_air") == "ideal" else FuelAirLoads
    names = {f.name for f in fields(cls)}
    try:
        return cls(**{k: v for k, v in section.items() if k in names})
    except ParameterError as exc:
        key = exc.name if "." in exc.name else f"loads.{exc.name}"
        raise ParameterError(key, exc.value, exc.admissible) from None


@dataclass(frozen=True)
class ChargeCycle:
    """The closed parts of a drive's period, integrated; the chambers' pressures from them.

    Arrays have one row per turning point ``i`` (the part whose compression starts there).
    """

    loads: FuelAirLoads
    gas_label: str
    turning: np.ndarray  # (n,) in [0, period)
    period: float
    kind: np.ndarray  # (n,) chamber kind compressed from turning point i (0: A, 1: B)
    multiplicity: np.ndarray  # (n,) chambers that start compression at turning point i
    x: np.ndarray  # (K+1,) cycle angle of the nodes [rad]
    p: np.ndarray  # (n, K+1)
    p_left: np.ndarray
    dp: np.ndarray  # dp/dx
    temperature: np.ndarray  # (n, K+1)
    v_max: np.ndarray  # (n,)
    v_min: np.ndarray
    mass: np.ndarray
    fuel: np.ndarray  # fuel energy per cycle [J]
    heat: np.ndarray  # heat released per cycle [J]
    heat_wall: np.ndarray
    work_closed: np.ndarray  # int p dV over the closed part [J]
    energy_rise: np.ndarray

    @property
    def work(self) -> np.ndarray:
        """Indicated work of each part's cycle with its pumping loop [J]."""
        pumping = (self.loads.intake_pressure - self.loads.ambient_pressure) * (
            self.v_max - self.v_min
        )
        return self.work_closed + pumping

    def per_period(self, values) -> float:
        """Sum over the chambers' cycles in one period of the drive."""
        return float(np.sum(self.multiplicity * np.asarray(values)))

    def work_per_rev(self) -> float:
        """Indicated work of all chambers per shaft turn [J]."""
        return self.per_period(self.work) * 2.0 * np.pi / self.period

    def pressures(self, theta, stroke) -> np.ndarray:
        """Pressures [Pa] of chambers in ``stroke`` (2N, ...) at shaft angles ``theta`` (...)."""
        theta = np.asarray(theta, dtype=float)
        stroke = np.asarray(stroke)
        n, per = len(self.turning), self.period
        t = self.turning
        local = np.mod(theta, per)
        k = np.searchsorted(t, local, side="right") - 1
        nxt = np.where(k + 1 < n, t[np.minimum(k + 1, n - 1)], t[0] + per)
        k = np.where(nxt - local <= 1e-9, k + 1, k) % n  # on a turning point, within rounding
        closed = (stroke == ec.COMPRESSION) | (stroke == ec.POWER)
        f = np.where(stroke == ec.POWER, 1, 0)
        i = np.mod(k - f, n)
        start = t[np.mod(i + f, n)]
        end = t[np.mod(i + f + 1, n)] + np.where(np.mod(i + f + 1, n) <= np.mod(i + f, n), per,
                                                 0.0)  # fmt: skip
        gone = np.mod(local - start, per)
        gone = np.where(gone > per - 1e-9, 0.0, gone)
        x = np.where(f == 1, 0.0, -np.pi) + np.pi * np.clip(gone / (end - start), 0.0, 1.0)
        p_closed = cb.hermite(self.x, self.p, self.dp, i, x, left=self.p_left)
        outside = np.where(stroke == ec.INTAKE, self.loads.intake_pressure,
                           self.loads.ambient_pressure)  # fmt: skip
        return np.where(closed, p_closed, outside)

    def summary(self, displacement_per_rev: float) -> dict:
        """Per-turn numbers of the cycle (keys as the study prints them)."""
        res = {"x": self.x, "p": self.p, "p_left": self.p_left, "T": self.temperature,
               "work": self.work_closed, "fuel": self.fuel, "heat_released": self.heat,
               "heat_wall": self.heat_wall, "mass": self.mass}  # fmt: skip
        out = summarize(
            self.loads,
            self.gas_label,
            res,
            self.v_max,
            self.v_min,
            self.multiplicity,
            2.0 * np.pi / self.period,
            displacement_per_rev,
        )
        return {k: v if isinstance(v, str) else float(v) for k, v in out.items()}

    def work_of_kind(self, kind: int) -> float:
        """Indicated work of one cycle of a chamber of ``kind`` (the mean over its parts) [J]."""
        pick = (self.kind == kind) & (self.multiplicity > 0)
        return float(np.mean(self.work[pick])) if np.any(pick) else float("nan")


def walls_of(section, inner_radius, outer_radius, axial_width, mean_radius, section_diameter,
             clearance_volume, volume_per_radian, volume, seconds, swing_rate,
             temperature):  # fmt: skip
    """Woschni's inputs of vane chambers on the integration grid (designs in arrays).

    The wetted area from the chamber angle ``delta = (V - V_c) / K``: the two piston faces
    and, over ``delta``, the side faces and the inner and outer walls (rectangular) or the
    torus wall (circular); the hydraulic diameter of the section; the pistons' mean speed
    at the section's mean radius, ``swing_rate`` the mean relative angular speed [rad/s].
    Section sizes broadcast against the leading (design) shape of ``volume``.
    """
    ex = lambda v: np.expand_dims(np.asarray(v, dtype=float), -1)  # noqa: E731
    rect = ex(np.asarray(section) == "rectangular")
    ri, ro, w = ex(inner_radius), ex(outer_radius), ex(axial_width)
    rm, d = ex(mean_radius), ex(section_diameter)
    delta = (volume - ex(clearance_volume)) / ex(volume_per_radian)
    area = np.where(rect, 2.0 * (ro - ri) * w + delta * (ro**2 - ri**2 + (ro + ri) * w),
                    2.0 * np.pi * d**2 / 4.0 + delta * rm * np.pi * d)  # fmt: skip
    diameter = np.where(rect, 2.0 * (ro - ri) * w / ((ro - ri) + w), d)[..., 0]
    radius = np.where(rect, 0.5 * (ri + ro), rm)[..., 0]
    return cb.Walls(area=area, diameter=diameter, wall_speed=radius * swing_rate,
                    seconds=seconds, temperature=temperature)  # fmt: skip


def _thin_section(machine, wall) -> ParameterError:
    """The refusal of a chamber whose walls take the heat faster than the cycle can follow.

    A section a few micrometres thin has a hydraulic diameter so small that Woschni's
    coefficient (which grows as ``D^-0.2`` and with the wetted area over the volume)
    empties the charge's heat within one integration step: no cycle exists there.
    """
    d = float(np.min(wall.diameter)) if wall is not None else float("nan")
    if machine.section == "circular":
        key, value = "machine.section_diameter", machine.section_diameter
    elif machine.outer_radius - machine.inner_radius <= machine.axial_width:
        key, value = "machine.outer_radius", machine.outer_radius
    else:
        key, value = "machine.axial_width", machine.axial_width
    return ParameterError(key, f"{value * 1e3:.6g} mm",
                          f"a chamber section whose walls leave a gas cycle: the hydraulic "
                          f"diameter {d * 1e3:.3g} mm is so small that the heat transfer to "
                          "the walls has no solution (loads.heat_transfer = none leaves the "
                          "walls out)")  # fmt: skip


def steps_per_stroke(loads: FuelAirLoads) -> int:
    """Runge-Kutta steps per stroke: 0.5 deg, or finer so that a short burn gets its steps."""
    return int(
        min(STEPS_MAX, max(STEPS_PER_STROKE, np.ceil(STEPS_PER_BURN * np.pi / loads.burn_duration)))
    )


def compression_limit(loads: FuelAirLoads) -> float:
    """Largest geometric compression ratio the cycle admits (compression below 4000 K)."""
    # adiabatic compression with gamma <= 1.4: T = T_i r^(gamma - 1) <= T_i r^0.4
    return (COMPRESSION_TEMPERATURE_MAX / loads.intake_temperature) ** (1.0 / 0.4)


def summarize(loads: FuelAirLoads, gas_label: str, res: dict, v_max, v_min, weight, turns,
              displacement) -> dict:  # fmt: skip
    """Per-turn numbers from integrated closed parts (designs in leading dimensions).

    ``res``: :func:`rotorkin.analysis.combustion.closed_cycle` of the parts (last axis
    of its per-part arrays: the parts); ``weight``: cycles of each part per period (0: the
    part does not occur); ``turns``: turns per period.
    """
    used = np.asarray(weight) > 0
    pumping = (loads.intake_pressure - loads.ambient_pressure) * (v_max - v_min)
    per = lambda v: np.sum(np.where(used, weight * v, 0.0), axis=-1) * turns  # noqa: E731
    work, fuel = per(res["work"] + pumping), per(res["fuel"])
    zero = int(np.argmin(np.abs(res["x"])))
    p = np.where(used[..., None], res["p"], -np.inf)
    peak_at = np.argmax(np.max(p, axis=-2), axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        return {
            "gas_properties": gas_label,
            "trapped_mass_mg": np.max(np.where(used, res["mass"], 0.0), axis=-1) * 1e6,
            "compression_end_pressure_bar": np.max(
                np.where(used, res["p_left"][..., zero], 0.0), axis=-1) / 1e5,
            "peak_pressure_bar": np.max(p, axis=(-2, -1)) / 1e5,
            "peak_pressure_angle_deg": np.degrees(res["x"][peak_at]),
            "peak_temperature_K": np.max(np.where(used[..., None], res["T"], 0.0),
                                         axis=(-2, -1)),
            "indicated_work_J": work,
            "fuel_energy_J_per_rev": fuel,
            "heat_added_J_per_rev": per(res["heat_released"]),
            "heat_to_walls_J_per_rev": per(res["heat_wall"]),
            "indicated_efficiency": np.where(fuel > 0, work / fuel, np.nan),
            "otto_efficiency": np.max(np.where(used, 1.0 - (v_max / v_min) ** -0.4, 0.0),
                                      axis=-1),
            "imep_bar": np.where(displacement > 0, work / displacement, np.nan) / 1e5,
        }  # fmt: skip


def _check_compression(machine, loads: FuelAirLoads, ratio: float) -> None:
    """Refuse a compression that heats the charge past what the cycle model describes."""
    most = compression_limit(loads)
    if ratio > most:
        raise ParameterError(
            "machine.compression_ratio",
            f"{machine.compression_ratio:g}",
            f"compression_ratio <= {most:.4g} for the fuel-air cycle (compression alone would "
            f"heat the charge from {loads.intake_temperature:g} K past "
            f"{COMPRESSION_TEMPERATURE_MAX:g} K); loads.model = 'ideal' for the drive alone",
        )


def charge_cycle(machine, loads: FuelAirLoads, chambers_at, counter, turning, period: float,
                 omega: float, steps: int | None = None) -> ChargeCycle:  # fmt: skip
    """Integrate the closed parts of one period of the drive.

    Parameters
    ----------
    machine : TwinRotor
    loads : FuelAirLoads
    chambers_at : callable
        ``theta (any shape) -> Chambers`` of the machine on its drive (volumes ``(2N, ...)``
        and ``dV/dtheta``).
    counter : callable
        ``theta ->`` chamber 1's stroke counter (integers at the turning points).
    turning : ndarray
        The turning points of the relative angle in ``[0, period)`` [rad].
    period : float
        Of the drive's law [rad].
    omega : float
        Mean shaft speed [rad/s] (the time base of the burn's walls).
    steps : int, optional
        Runge-Kutta steps per stroke (default: :data:`STEPS_PER_STROKE`, more for a short
        burn).
    """
    if steps is None:
        steps = int(
            min(
                STEPS_MAX,
                max(STEPS_PER_STROKE, np.ceil(STEPS_PER_BURN * np.pi / loads.burn_duration)),
            )
        )
    t = np.sort(np.asarray(turning, dtype=float))
    n = len(t)
    t1 = np.concatenate([t, t + period, t + 2 * period])
    a, b, c = t1[:n], t1[1 : n + 1], t1[2 : n + 2]
    half = np.linspace(-np.pi, np.pi, 4 * steps + 1)
    neg = half < 0.0
    theta = np.where(neg, a[:, None] + (half + np.pi) / np.pi * (b - a)[:, None],
                     b[:, None] + half / np.pi * (c - b)[:, None])  # fmt: skip
    dtheta = np.where(neg, ((b - a) / np.pi)[:, None], ((c - b) / np.pi)[:, None])
    ch = chambers_at(theta)
    starting = tr.strokes(machine, counter(t)) == ec.COMPRESSION  # (2N, n)
    kinds = tr.chamber_kinds(machine)
    mult = np.sum(starting, axis=0)
    kind = np.where(mult > 0, np.argmax(starting, axis=0) % 2, 0)
    first = np.where(kinds[:, None] == kind[None, :], 1, 0)
    row = np.argmax(first, axis=0)  # a chamber of that kind
    volume = ch.volume[row, np.arange(n)]
    dvolume = ch.dvolume[row, np.arange(n)] * dtheta
    gas = loads.gas()
    charge = loads.charge()
    v_max, v_min = volume[:, 0], volume[:, 2 * steps]
    _check_compression(machine, loads, float(np.max(v_max / v_min)))
    mass = cb.trapped_mass(charge, v_max, gas.gas_constant(0.0))
    heat = cb.heat_of_charge(charge, mass)
    wall = None
    if loads.heat_transfer == "woschni":
        delta_swing = (v_max - v_min) / tr.volume_per_radian(machine)
        swing_rate = delta_swing * omega / (0.5 * (c - a))  # mean relative speed [rad/s]
        m = machine
        wall = walls_of(m.section, m.inner_radius, m.outer_radius, m.axial_width, m.mean_radius,
                         m.section_diameter, m.clearance_volume, tr.volume_per_radian(m), volume,
                         dtheta / omega, swing_rate, loads.wall_temperature)  # fmt: skip
    res = cb.closed_cycle(half, volume, dvolume, mass=mass, heat=heat, gas=gas,
                          temperature=loads.intake_temperature, burn=loads.burn(),
                          walls=wall)  # fmt: skip
    if not np.all(np.isfinite(res["p"])):
        raise _thin_section(machine, wall)
    return ChargeCycle(
        loads=loads,
        gas_label=gas.label,
        turning=t,
        period=float(period),
        kind=kind,
        multiplicity=mult,
        x=res["x"],
        p=res["p"],
        p_left=res["p_left"],
        dp=res["dp"],
        temperature=res["T"],
        v_max=v_max,
        v_min=v_min,
        mass=mass,
        fuel=cb.fuel_energy(charge, mass),
        heat=res["heat_released"],
        heat_wall=res["heat_wall"],
        work_closed=res["work"],
        energy_rise=res["energy_rise"],
    )
