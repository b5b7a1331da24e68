"""The three vane machines on any rotary law: setup (with the fit check), state, closed forms.

Each machine is built from the ``[machine]`` and ``[loads]`` sections
(:mod:`rotorkin.machines.schema`) and a :class:`~rotorkin.vane.law.RotaryLaw`. It
*mounts* its vanes on member 2 so that at mid-swing of the relative angle its two
chamber kinds are alike (a twin-rotor engine's rails 90 deg apart, a pump's vanes
``pi/Z`` apart, a blade pair ``pi/B`` from the other): both kinds then reach the
same smallest volume, the best a designer can do with a given swing. A drive whose
relative angle already swings about that middle keeps its own mounting (a shift of
0): its machine's numbers are then those of its own study.

Compatibility: what cannot fit is refused in one line naming the machine key:
pistons, vanes or blades that would collide over the drive's swing, or a
four-stroke engine on a drive that does not swing the rotors a multiple of two
times per turn.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from rotorkin.analysis.timing import mean_speed
from rotorkin.analysis.torque import member_torques, shaft_torque_from_members
from rotorkin.core.angles import fmt_deg
from rotorkin.core.errors import ParameterError
from rotorkin.machines import fuel_air as fa
from rotorkin.machines import pump_flow as pf
from rotorkin.machines import rotary_blade as rb
from rotorkin.machines import rotary_blade_stirling as rs
from rotorkin.machines import twin_rotor as tr
from rotorkin.machines import vane_pump as vp
from rotorkin.machines.schema import (
    EngineLoads,
    PumpPorts,
    RotaryBladeSection,
    StirlingGas,
    TwinRotorMachine,
    VanePumpSection,
)
from rotorkin.studies.helpers import build_params
from rotorkin.vane.law import RotaryLaw, mounted, relative_extremes, stroke_counter, turning_points
from rotorkin.vane.law import strokes_per_turn as _strokes_per_turn

__all__ = ["Setup", "State", "MACHINES", "setup", "state", "summary"]

_TWO_PI = 2.0 * np.pi
#: Shaft speed when the config gives none: 3000 rpm [rad/s].
DEFAULT_SPEED = 3000.0 * np.pi / 30.0


@dataclass(frozen=True)
class Setup:
    """A machine mounted on a law: everything that does not depend on the shaft angle."""

    kind: str
    law: RotaryLaw
    model: object  # TwinRotor | VanePump | RotaryBlade
    loads: object  # IdealCycle | PortPressures | IsothermalGas | StirlingLoads
    turning: np.ndarray  # turning points of r in [0, period)
    r_lo: float
    r_hi: float
    shift: float  # member 2's vanes mounted this much from its zero [rad]
    strokes_per_turn: float
    extra: dict  # the machine's own closed-form numbers


@dataclass(frozen=True)
class State:
    """The machine at a set of shaft angles."""

    motion: object  # mounted Motion
    volume: np.ndarray  # (C, ...) [m^3]
    dvolume: np.ndarray  # (C, ...) dV/dtheta [m^3/rad]
    pressure: np.ndarray  # (C, ...) [Pa]
    members: np.ndarray  # (2, ...) torques on the members [N m]
    shaft: np.ndarray  # (...) torque on the shaft, + drives it [N m]


#: machine.type -> (machine section, loads section, inertia keys of the two members).
MACHINES = {
    "twin_rotor": (TwinRotorMachine, EngineLoads, ("inertia_rotor_1", "inertia_rotor_2")),
    "vane_pump": (VanePumpSection, PumpPorts, ("inertia_impeller_1", "inertia_impeller_2")),
    "rotary_blade": (
        RotaryBladeSection,
        StirlingGas,
        ("inertia_blade_pair_1", "inertia_blade_pair_2"),
    ),
}


def _fields(cls, section: dict) -> dict:
    return {f.name: section[f.name] for f in fields(cls) if f.name in section}


def inertias(kind: str, machine: dict) -> tuple[float, tuple[float, float]]:
    """``J_shaft`` and the two members' inertias of a machine section [kg m^2]."""
    k1, k2 = MACHINES[kind][2]
    return float(machine["inertia_shaft"]), (float(machine[k1]), float(machine[k2]))


def setup(kind: str, cfg: dict, law: RotaryLaw) -> Setup:
    """Build, mount and check the machine ``kind`` of ``cfg`` on ``law``.

    Raises
    ------
    ParameterError
        Named by the machine key that does not fit the drive.
    """
    machine, loads = cfg.get("machine", {}), cfg.get("loads", {})
    points = turning_points(law)
    if len(points) == 0:
        raise ParameterError(
            "machine.type",
            kind,
            "a drive that swings its two members against each other; this one turns them "
            "together (their relative angle never turns back)",
        )
    lo, hi = relative_extremes(law, points)
    swing, mid = hi - lo, 0.5 * (lo + hi)
    per_turn = _strokes_per_turn(law, points)
    speed = (cfg.get("run") or {}).get("speed", DEFAULT_SPEED)
    return _SETUPS[kind](machine, loads, law, points, lo, hi, swing, mid, per_turn, speed)


def _twin_rotor(machine, loads, law, points, lo, hi, swing, mid, per_turn, speed) -> Setup:
    model = build_params(tr.TwinRotor, "machine", _fields(tr.TwinRotor, machine))
    cycle = fa.loads_of(loads)
    n = model.pistons_per_rotor
    per_span = int(round(per_turn * law.span / _TWO_PI))
    if per_span % 4:
        raise ParameterError(
            "machine.type",
            "twin_rotor",
            "a four-stroke engine needs a drive that swings the rotors an even number of times "
            f"per shaft turn (or per period of the drive); this one swings them {per_span / 2:g} "
            "time(s)",
        )
    pitch = _TWO_PI / n
    g_lo, g_hi = 0.5 * pitch - 0.5 * swing, 0.5 * pitch + 0.5 * swing  # piston gaps, centred
    if g_lo <= 0.0:
        most = 2 * int(np.floor(np.pi / swing - 1e-12)) if swing > 0 else 24
        raise ParameterError(
            "machine.pistons_per_rotor",
            str(n),
            f"pistons_per_rotor < 360 deg / swing, at most {max(most, 0)} here: the drive swings "
            f"the rotors by {fmt_deg(swing)} and the pistons must stay apart",
        )
    eps = float(model.compression_ratio)
    beta = (eps * g_lo - g_hi) / (eps - 1.0)
    if beta < 0.0:
        raise ParameterError(
            "machine.compression_ratio",
            f"{eps:g}",
            f"compression_ratio > {g_hi / g_lo:.4g}, the ratio of zero-width pistons for "
            f"{n} pistons per rotor over the drive's swing of {fmt_deg(swing)}",
        )
    amin, amax = (g_lo - beta, g_lo - beta), (g_hi - beta, g_hi - beta)
    shift = 0.5 * np.pi - mid
    if isinstance(cycle, fa.FuelAirLoads):  # the closed parts of the law's period, integrated
        cycle = fa.charge_cycle(
            model, cycle, lambda t: tr.chambers(model, mounted(law.motion(t), shift), beta),
            lambda t: stroke_counter(law, t, points), points, law.period,
            mean_speed(speed, law.period),
        )  # fmt: skip
    extra = {"piston_width": beta, "angle_min": amin, "angle_max": amax, "cycle": cycle}
    return Setup("twin_rotor", law, model, cycle, points, lo, hi, shift, per_turn,
                 extra)  # fmt: skip


def _vane_pump(machine, loads, law, points, lo, hi, swing, mid, per_turn, speed) -> Setup:
    z = int(machine.get("vanes_per_impeller", 2))
    widest = float(vp.vane_angle_max(z, swing))
    if widest <= 0.0:
        raise ParameterError(
            "machine.vanes_per_impeller",
            str(z),
            f"vanes_per_impeller < 360 deg / swing = {_TWO_PI / swing:.4g}: the drive swings the "
            f"impellers by {fmt_deg(swing)} and the vanes must stay apart",
        )
    gamma = machine.get("vane_angle")
    values = {k: machine[k] for k in ("hub_radius", "casing_radius", "axial_width") if k in machine}
    pump = build_params(
        vp.VanePump,
        "machine",
        {
            "relative_angle_min": lo,
            "relative_angle_max": hi,
            "vane_angle": widest if gamma is None else gamma,
            "vanes_per_impeller": z,
            **values,
        },
    )
    ports = build_params(vp.PortPressures, "loads", _fields(vp.PortPressures, loads))
    gaps = _pump_gaps(machine, loads)
    values = {
        "pump": pump,
        "ports": ports,
        "gaps": gaps,
        "motion_of": law.motion,
        "turning": points,
        "period": law.period,
        "land": machine.get("port_land", 0.0),
    }
    windows = build_params(pf.land_windows, "machine", values)  # fmt: skip
    return Setup("vane_pump", law, pump, ports, points, lo, hi, 0.0, per_turn,
                 {"gaps": gaps, "windows": windows})  # fmt: skip


def _pump_gaps(machine: dict, loads: dict) -> pf.Gaps:
    """The vanes' clearances (machine section) and the fluid (loads section), SI."""
    values = {k: machine[k] for k in pf.GAP_FIELDS[:3] if k in machine}
    values |= {k: loads[k] for k in pf.GAP_FIELDS[3:] if k in loads}
    aliases = {k: f"loads.{k}" for k in pf.GAP_FIELDS[3:]}
    return build_params(pf.Gaps, "machine", values, aliases)


_L_PER_MIN = 60.0e3  # [l/min] per [m^3/s]
_PUMP_COLUMN_DOCS = {
    "flow_l_per_min": "Geometric flow, sum over the shrinking chambers of -dV/dt at the run "
    "speed (ideal ports).",
    "leakage_l_per_min": "Laminar leakage through the clearances of all vanes, "
    "2 Z (G_tip + G_side + G_hub) (p_d - p_s) (docs/machines/vane_pump.md).",
    "flow_delivered_l_per_min": "Flow to the outlet: flow_l_per_min outside the ports' closed "
    "windows (0 inside, machine.port_land), less leakage_l_per_min.",
}


def pump_flow(s: Setup, theta, st: State, omega) -> tuple[dict, dict, dict]:
    """A pump's flow at the run speed: summary keys, columns and their docs.

    The machine's :func:`rotorkin.machines.vane_pump.pump_flow` on the state sampled
    over whole spans of the law: geometric mean flow (the displacement per turn over
    the time of a turn), its ripple and extremes, leakage, compression and land
    losses, the delivered flow and its ripple, volumetric efficiency, trapped
    pressures (:func:`rotorkin.machines.vane_pump.flow_keys`: the same keys on every
    drive).

    Parameters
    ----------
    s : Setup
        A vane pump.
    theta : ndarray, shape (n,)
        Shaft angles over whole spans of the law, ends included [rad].
    st : State
        The pump at ``theta``.
    omega : ndarray, shape (n,)
        Shaft speed at ``theta`` [rad/s].
    """
    theta, omega = np.asarray(theta, dtype=float), np.asarray(omega, dtype=float)
    pump, ports, extra = s.model, s.loads, s.extra
    cycles = s.strokes_per_turn / 2.0
    disp_rev = float(vp.displacement(pump)) * cycles
    dt = 1.0 / omega
    span = float(theta[-1] - theta[0])
    t_turn = float(np.trapezoid(dt, theta)) * _TWO_PI / span
    flow_mean = disp_rev / t_turn
    geometric = np.sum(np.maximum(-st.dvolume, 0.0), axis=0) * omega
    t_period = t_turn * float(s.law.period) / _TWO_PI
    flow = pf.pump_flow(pump, ports, extra["gaps"], extra["windows"], flow_mean, t_period,
                        st.dvolume, theta, omega)  # fmt: skip
    dp = float(ports.discharge_pressure) - float(ports.suction_pressure)
    keys = {
        "flow_mean_l_per_min": flow_mean * _L_PER_MIN,
        "flow_max_l_per_min": float(np.max(geometric)) * _L_PER_MIN,
        "flow_min_l_per_min": float(np.min(geometric)) * _L_PER_MIN,
        "flow_ripple": float(vp.flow_ripple(geometric, dt)),
        "hydraulic_power_W": dp * flow_mean,
        **pf.flow_keys(flow, ports, extra["windows"].land),
    }
    leak = np.full(theta.shape, flow["leakage"]["total"])
    columns = {
        "flow_l_per_min": geometric * _L_PER_MIN,
        "leakage_l_per_min": leak * _L_PER_MIN,
        "flow_delivered_l_per_min": flow["delivered"] * _L_PER_MIN,
    }
    return keys, columns, dict(_PUMP_COLUMN_DOCS)


def pump_warnings(s: Setup, summary: dict) -> tuple[str, ...]:
    """A pump's trapped chamber below the cavitation floor (``loads.vapour_pressure``)."""
    line = pf.cavitation_warning(s.extra["windows"].pressure_min,
                                 s.extra["gaps"].vapour_pressure)  # fmt: skip
    return (line,) if line else ()


def _rotary_blade(machine, loads, law, points, lo, hi, swing, mid, per_turn, speed) -> Setup:
    keys = ("blade_thickness", "inner_radius", "outer_radius", "axial_width", "blades_per_pair",
            "inertia_shaft", "inertia_blade_pair_1", "inertia_blade_pair_2")  # fmt: skip
    model = build_params(rb.RotaryBlade, "machine", {k: machine[k] for k in keys if k in machine})
    kind = loads.get("pressure_model", "adiabatic")
    if kind not in rs.PRESSURE_MODELS:
        raise ParameterError("loads.pressure_model", repr(kind),
                             "adiabatic, schmidt or isothermal (the drive's own models run in "
                             "its own study)")  # fmt: skip
    if kind == "isothermal":
        gas = build_params(rb.IsothermalGas, "loads", _fields(rb.IsothermalGas, loads))
    else:
        gas = build_params(rs.StirlingLoads, "loads", _fields(rs.StirlingLoads, loads))
    centre = np.pi / model.blades_per_pair
    psi_lo, psi_hi = centre - 0.5 * swing, centre + 0.5 * swing
    try:  # the blades must fit the drive's swing
        rb.check_swing(model, psi_lo, psi_hi)
    except ParameterError as exc:
        raise ParameterError(f"machine.{exc.name}", exc.value, exc.admissible) from None
    v_min, v_max = rb.volume_range(model, psi_lo, psi_hi)
    # psi = q1 - q2 runs from its centre pi/B where r = q2 - q1 is at mid-swing
    shift = -(mid + centre)
    extra = {"psi": (psi_lo, psi_hi), "v_min": v_min, "v_max": v_max, "stirling": None}
    if kind == "isothermal":
        extra["charge"] = rb.gas_charge(gas, v_max)
    else:
        extra["stirling"] = _stirling(model, gas, law, shift, points, v_max - v_min)
    return Setup("rotary_blade", law, model, gas, points, lo, hi, shift, per_turn, extra)


def _stirling(model, gas, law, shift, points, swept) -> rs.StirlingSolution:
    """The circuits of the rotary-blade Stirling engine over one period of the law."""

    def motion(theta):
        return mounted(law.motion(theta), shift)

    return rs.stirling_solution(model, gas, motion, law.period, len(points) // 2,
                                float(np.max(swept)))  # fmt: skip


def _rotary_blade_state(s: Setup, motion) -> State:
    """Both blade sets of the Stirling models: volumes and pressures hot set first."""
    sol = s.extra["stirling"]
    cold = mounted(s.law.motion(np.asarray(motion.theta) - sol.lag), s.shift)
    st = rs.stirling_state(s.model, sol, motion, cold)
    two = (np.concatenate([st["volume_hot"], st["volume_cold"]]),
           np.concatenate([st["dvolume_hot"], st["dvolume_cold"]]),
           np.concatenate([st["pressure"], st["pressure"]]))  # fmt: skip
    return State(motion, *two, st["members"], st["shaft"])


_SETUPS = {"twin_rotor": _twin_rotor, "vane_pump": _vane_pump, "rotary_blade": _rotary_blade}


def state(s: Setup, theta) -> State:
    """Volumes, pressures and torques at the shaft angles ``theta`` (any shape)."""
    theta = np.asarray(theta, dtype=float)
    motion = mounted(s.law.motion(theta), s.shift)
    if s.kind == "twin_rotor":
        count = stroke_counter(s.law, theta, s.turning)
        e = s.extra
        st = tr.engine_state(s.model, e["cycle"], motion, e["piston_width"], e["angle_min"],
                             e["angle_max"], count)  # fmt: skip
        return State(motion, st.chambers.volume, st.chambers.dvolume, st.pressure,
                     st.member_torque, st.shaft_torque)  # fmt: skip
    if s.kind == "vane_pump":
        volume, dvolume = vp.chamber_volumes(s.model, motion)
        pressure = pf.port_pressures(s.loads, s.extra["windows"], volume, dvolume, theta)
        members = member_torques(pressure, vp.volume_derivatives_dq(s.model, motion))
        return State(motion, volume, dvolume, pressure, members,
                     shaft_torque_from_members(members, motion.dq))  # fmt: skip
    if s.extra["stirling"] is not None:
        return _rotary_blade_state(s, motion)
    volume = rb.chamber_volumes(s.model, motion.q)
    dvolume = rb.chamber_volume_derivative(s.model, motion.dq)
    dpsi, d2psi = motion.dq[0] - motion.dq[1], motion.d2q[0] - motion.d2q[1]
    direction = np.where(dpsi != 0.0, np.sign(dpsi), np.sign(d2psi))
    strokes = rb.chamber_strokes(s.model, direction)
    pressure = rb.isothermal_pressure(s.loads, s.extra["charge"], volume, strokes)
    members = rb.gas_member_torques(s.model, pressure)
    return State(motion, volume, dvolume, pressure, members,
                 shaft_torque_from_members(members, motion.dq))  # fmt: skip


def summary(s: Setup) -> dict:
    """Closed-form numbers of the machine: volumes, displacement, work per shaft turn.

    ``indicated_work_J`` is the work the machine does on the shaft per turn (a
    pump's is negative); ``displacement_cm3_per_rev`` the volume swept by all
    chambers' strokes of one kind (intake / suction / expansion) per turn.
    """
    cycles = s.strokes_per_turn / 2.0  # volume cycles of each chamber per turn
    swing = s.r_hi - s.r_lo
    out = {
        "machine": s.kind,
        "relative_angle_min_deg": float(np.degrees(s.r_lo)),
        "relative_angle_max_deg": float(np.degrees(s.r_hi)),
        "relative_swing_deg": float(np.degrees(swing)),
        "volume_cycles_per_rev": cycles,
        "vane_mounting_deg": float(np.degrees(s.shift)),
    }
    if s.kind == "twin_rotor":
        e, m = s.extra, s.model
        four = cycles / 2.0  # four-stroke cycles of each chamber per turn
        v_min, v_max = tr.volume_limits(m, e["angle_min"], e["angle_max"])
        eps = tr.compression_ratio_geometric(m, e["angle_min"], e["angle_max"])
        disp = tr.displacement_per_rev(m, swing, four)
        out.update({
            "pistons_per_rotor": int(m.pistons_per_rotor),
            "piston_width_deg": float(np.degrees(e["piston_width"])),
            "chamber_angle_min_deg": float(np.degrees(e["angle_min"][0])),
            "chamber_angle_max_deg": float(np.degrees(e["angle_max"][0])),
            "power_strokes_per_rev": float(m.chambers * four),
            "chamber_volume_min_cm3": float(np.min(v_min)) * 1e6,
            "chamber_volume_max_cm3": float(np.max(v_max)) * 1e6,
            "displacement_cm3_per_rev": float(disp) * 1e6,
            "compression_ratio_geometric": float(min(eps)),
        })  # fmt: skip
        out.update(tr.cycle_summary(m, e["cycle"], v_min, v_max, four, disp))
    elif s.kind == "vane_pump":
        pump, ports = s.model, s.loads
        disp = float(vp.displacement(pump)) * cycles  # per period of one swing, per turn
        lo, hi = pump.chamber_angle_range
        out.update({
            "vanes_per_impeller": int(pump.vanes_per_impeller),
            "vane_angle_deg": float(np.degrees(pump.vane_angle)),
            "chamber_angle_min_deg": float(np.degrees(lo)),
            "chamber_angle_max_deg": float(np.degrees(hi)),
            "displacement_cm3_per_rev": disp * 1e6,
            "pressure_rise_bar": (ports.discharge_pressure - ports.suction_pressure) / 1e5,
            "indicated_work_J": -(ports.discharge_pressure - ports.suction_pressure) * disp,
            "port_land_deg": float(np.degrees(s.extra["windows"].land)),
            "trapped_pressure_peak_bar": s.extra["windows"].pressure_peak / 1e5,
            "trapped_pressure_min_bar": s.extra["windows"].pressure_min / 1e5,
        })  # fmt: skip
    else:
        m, gas, e = s.model, s.loads, s.extra
        psi_lo, psi_hi = e["psi"]
        periods = _TWO_PI / s.law.period
        disp = float(rb.displacement_per_rev(m, s.strokes_per_turn * (psi_hi - psi_lo)))
        out.update({
            "blades_per_pair": int(m.blades_per_pair),
            "psi_min_deg": float(np.degrees(psi_lo)),
            "psi_max_deg": float(np.degrees(psi_hi)),
            "chamber_volume_min_cm3": float(np.min(e["v_min"])) * 1e6,
            "chamber_volume_max_cm3": float(np.max(e["v_max"])) * 1e6,
            "displacement_cm3_per_rev": disp * 1e6,
            "compression_ratio_geometric": float(np.min(e["v_max"] / e["v_min"])),
        })  # fmt: skip
        if e["stirling"] is not None:  # both sets' expansion strokes
            out["displacement_cm3_per_rev"] = 2.0 * disp * 1e6
            out.update(rs.stirling_summary(e["stirling"], periods))
        else:
            ends = np.concatenate([[0.0], np.asarray(s.turning, dtype=float), [s.law.period]])
            ends = np.unique(ends)
            v_turns = rb.chamber_volumes(m, mounted(s.law.motion(ends), s.shift).q)
            per_period = float(np.sum(rb.isothermal_cycle_work(gas, e["charge"], v_turns)))
            out.update({
                "indicated_work_J": per_period * periods,
                "hot_temperature_K": gas.hot_temperature,
                "cold_temperature_K": gas.cold_temperature,
            })  # fmt: skip
    return out
