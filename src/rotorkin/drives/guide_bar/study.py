"""Study of the differential vane pump driven by two rotating guide bars + gears (JHIT 2012).

Config keys (SI, defaults filled by :mod:`rotorkin.io.config`; a key missing from
``cfg`` takes the schema's default):
``drive.lambda``, ``drive.gear_ratio``, ``drive.input_gear_ratio``,
``drive.phase``, ``drive.driver``; ``machine.vanes_per_impeller``,
``machine.vane_angle``, ``machine.hub_radius``, ``machine.casing_radius``,
``machine.axial_width``, ``machine.inertia_shaft``, ``machine.inertia_impeller_1``,
``machine.inertia_impeller_2``, ``machine.speed_fluctuation``;
``loads.impeller_torque_1``, ``loads.impeller_torque_2`` (the paper's constant
torques, ``input_torque_*`` keys), ``loads.suction_pressure``,
``loads.discharge_pressure`` (the pump, :mod:`rotorkin.machines.vane_pump`);
``run.points``, ``run.speed``; for the forces in the pairs (:mod:`.forces`)
``drive.crank_length``, ``drive.input_pitch_radius``, ``drive.output_pitch_radius``,
``drive.face_width``, ``drive.pressure_angle`` and the ``[contact]`` section.

Torque sign of the pump keys (``shaft_torque_*``, ``mean_torque_Nm``,
``indicated_work_J``): positive when the machine drives the input shaft, so a
pump's are negative (the motor supplies their opposite). The paper's
``input_torque_*`` keys keep the paper's sense: the torque input gear 1 needs
against the resisting torques M7, M8.
"""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np

from rotorkin.analysis import pairs as pr
from rotorkin.core.errors import ParameterError
from rotorkin.core.schema import RunSection
from rotorkin.drives.guide_bar import figures as figures_guide_bar
from rotorkin.drives.guide_bar import forces as gb_forces
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar import pump as gb_pump
from rotorkin.drives.guide_bar import summary as closed_forms
from rotorkin.drives.guide_bar.pump import pump_state
from rotorkin.drives.guide_bar.schema import GuideBarLoads, VanePumpMachine
from rotorkin.machines import pump_flow as pf
from rotorkin.machines import vane_pump as vp
from rotorkin.studies import StudyResult
from rotorkin.studies.helpers import angle_grid, build_params, time_domain, undefined_warnings
from rotorkin.vane import RotaryLaw

__all__ = ["evaluate", "drive_params", "pump_params", "gap_params", "land_params", "pump_state",
           "pair_forces", "HEADLINE"]  # fmt: skip

#: Summary keys printed by the command line, in order, with what each means (one line).
HEADLINE = {
    "driver": "which member of gear 1 drives: crank or guide bar",
    "vane_angle_deg": "vane angle gamma_0 of an impeller (section 3)",
    "relative_angle_swing_deg": "swing of the angle between the two impellers",
    "impeller_speed_ratio_min": "slowest impeller speed over the driving member's",
    "impeller_speed_ratio_max": "fastest impeller speed over the driving member's",
    "input_torque_min_Nm": "paper eq. 7, constant M7, M8: least torque gear 1 needs",
    "input_torque_max_Nm": "paper eq. 7, constant M7, M8: most torque gear 1 needs",
    "input_torque_mean_Nm": "paper eq. 7, constant M7, M8: mean torque gear 1 needs",
    "displacement_cm3_per_rev": "volume delivered per input-shaft turn",
    "flow_mean_l_per_min": "mean delivered flow at the run speed",
    "flow_ripple": "(max - min) / mean of the delivered flow",
    "flow_delivered_mean_l_per_min": "mean flow less leakage and compression loss",
    "volumetric_efficiency": "delivered over geometric mean flow",
    "flow_delivered_ripple": "(max - min) / mean of the flow delivered, losses included",
    "trapped_pressure_peak_bar": "highest pressure of a chamber closed by the ports' land",
    "trapped_pressure_min_bar": "lowest pressure of a chamber closed by the ports' land",
    "mean_torque_Nm": "ideal ports: mean torque on the shaft (- : the motor drives)",
    "torque_ripple": "ideal ports: (max - min) / |mean| of the shaft torque",
    "flywheel_inertia_kgm2": "flywheel for the chosen coefficient of speed fluctuation",
    "peak_slider_force_N": "largest force of a guide bar on its slider block, at speed",
    "peak_input_mesh1_tangential_force_N": "largest tangential force of gear 1 on gear 2",
    "peak_impeller_mesh1_tangential_force_N": "largest tangential force of gear 6 on gear 7",
    "load_reversals_per_period": "times an impeller's load reverses (slot wall, tooth flank)",
    "peak_contact_stress_MPa": "largest Hertz pressure of a gear mesh (pitch point)",
    "contact_safety_factor": "allowable contact pressure over the largest",
    "peak_bearing_load_N": "largest load of a pin or bearing",
    "friction_loss_W": "power lost to friction in the pairs at the run speed",
    "mechanical_efficiency": "hydraulic work over shaft work, friction in the pairs included",
}

#: Samples per period used for extremes and peaks (independent of run.points).
_PEAK_SAMPLES = 20_001


def _deg(x) -> float:
    return float(np.degrees(x))


def _summary(params: gb.GuideBar, m7: float, m8: float) -> dict:
    fine = np.linspace(0.0, gb.period(params), _PEAK_SAMPLES)
    d1, d2, d3 = gb.impeller_rates(params, fine)
    torque = m7 * d1[0] + m8 * d1[1]
    sampled = {
        "input_torque_min_Nm": float(np.min(torque)),
        "input_torque_max_Nm": float(np.max(torque)),
        "impeller_accel_peak_per_rad": float(np.max(np.abs(d2))),
        "impeller_jerk_peak_per_rad2": float(np.max(np.abs(d3))),
    }
    return closed_forms.drive_summary(params, m7, m8, sampled)


_DOCS = {
    "theta_deg": "Input gear 1 angle theta; the driving members turn at theta / i12.",
    "driving_angle_1_deg": "Driving angle x_1 = theta / i12 of mechanism 1 (crank or guide bar), "
    "from the line guide pivot -> crank pivot.",
    "driving_angle_2_deg": "Driving angle x_2 = Sigma + theta / i12 of mechanism 2.",
    "impeller1_angle_deg": "Impeller 1 angle q_1 = f(x_1)/u, positive in its mean sense of "
    "turning.",
    "impeller2_angle_deg": "Impeller 2 angle q_2 = f(x_2)/u, positive in its mean sense of "
    "turning.",
    "relative_angle_deg": "Angle between the impellers q_2 - q_1; a chamber angle is this plus a "
    "constant of the vane layout.",
    "impeller1_speed_ratio": "dq_1/dtheta, impeller 1 speed over input gear speed (eq. 1 or 3 "
    "over i12).",
    "impeller2_speed_ratio": "dq_2/dtheta, impeller 2 speed over input gear speed.",
    "impeller1_accel_per_rad": "d2q_1/dtheta2, impeller 1 acceleration over input speed squared.",
    "impeller2_accel_per_rad": "d2q_2/dtheta2, impeller 2 acceleration over input speed squared.",
    "impeller1_jerk_per_rad2": "d3q_1/dtheta3, impeller 1 jerk over input speed cubed.",
    "impeller2_jerk_per_rad2": "d3q_2/dtheta3, impeller 2 jerk over input speed cubed.",
    "input_torque_Nm": "Torque M1 on input gear 1 by virtual work, M7 dq_1/dtheta + "
    "M8 dq_2/dtheta (eq. 7, 8).",
}


def _columns(params: gb.GuideBar, m7: float, m8: float, points: int) -> dict:
    theta = angle_grid(gb.period(params), points)
    x = gb.driving_angles(params, theta)
    q, d1, d2, d3 = gb.impeller_angles(params, theta)
    cols = {"theta_deg": np.degrees(theta)}
    for k in (0, 1):
        cols[f"driving_angle_{k + 1}_deg"] = np.degrees(x[k])
    for k in (0, 1):
        cols[f"impeller{k + 1}_angle_deg"] = np.degrees(q[k])
    cols["relative_angle_deg"] = np.degrees(q[1] - q[0])
    for name, arr in (("speed_ratio", d1), ("accel_per_rad", d2), ("jerk_per_rad2", d3)):
        for k in (0, 1):
            cols[f"impeller{k + 1}_{name}"] = arr[k]
    cols["input_torque_Nm"] = m7 * d1[0] + m8 * d1[1]
    return cols


# --------------------------------------------------------------------------------------------
# the pump
# --------------------------------------------------------------------------------------------
_M3_TO_L_PER_MIN = 60.0e3

_PUMP_DOCS = {
    "chamber_a_volume_cm3": "Volume of each chamber A (from a vane of impeller 1 to the next "
    "vane of impeller 2; chambers 1, 3, ...).",
    "chamber_b_volume_cm3": "Volume of each chamber B (from a vane of impeller 2 to the next "
    "vane of impeller 1; chambers 2, 4, ...).",
    "chamber_a_dvolume_cm3_per_rad": "dV/dtheta of a chamber A; negative while it discharges.",
    "chamber_b_dvolume_cm3_per_rad": "dV/dtheta of a chamber B; negative while it discharges.",
    "chamber_a_pressure_bar": "Pressure in a chamber A, ideal ports: discharge while it "
    "shrinks, suction while it grows.",
    "chamber_b_pressure_bar": "Pressure in a chamber B, ideal ports.",
    "flow_l_per_min": "Delivered flow, sum over the shrinking chambers of -dV/dt at the shaft "
    "speed.",
    "leakage_l_per_min": "Laminar leakage through the clearances of all vanes, "
    "2 Z (G_tip + G_side + G_hub) (p_d - p_s) (docs/machines/vane_pump.md).",
    "flow_delivered_l_per_min": "Flow to the outlet: flow_l_per_min outside the ports' closed "
    "windows (0 inside, machine.port_land), less leakage_l_per_min.",
    "impeller1_torque_Nm": "Torque of the chamber pressures on impeller 1, sum p_j dV_j/dq_1, "
    "positive in its sense of rotation.",
    "impeller2_torque_Nm": "Torque of the chamber pressures on impeller 2, sum p_j dV_j/dq_2.",
    "shaft_torque_Nm": "Torque of the fluid on input gear 1 by virtual work, sum M_i dq_i/dtheta; "
    "positive when it drives the shaft (a pump's is negative).",
    "inertia_torque_Nm": "Torque the input shaft spends on the inertia of shaft and impellers, "
    "d(KE)/dtheta.",
    "shaft_torque_with_inertia_Nm": "shaft_torque_Nm minus inertia_torque_Nm: the net torque the "
    "machine puts on the input shaft (the motor supplies its opposite).",
    "equivalent_inertia_kgm2": "Inertia seen at the input shaft, "
    "J_shaft + sum J_i (dq_i/dtheta)^2.",
}


def _nonnegative(key: str, value: float, unit: str) -> float:
    v = float(value)
    if not (np.isfinite(v) and v >= 0.0):
        raise ParameterError(key, f"{v:g} {unit}", f"{key.split('.')[-1]} >= 0 {unit}")
    return v


def _defaults(cfg: dict):
    """Machine, loads and run sections with the schema's defaults for missing keys."""
    machine = {**VanePumpMachine().model_dump(), **(cfg.get("machine") or {})}
    loads = {**GuideBarLoads().model_dump(), **(cfg.get("loads") or {})}
    run = {**RunSection().model_dump(), **(cfg.get("run") or {})}
    return machine, loads, run


def _inertias(machine: dict) -> tuple[float, tuple[float, float]]:
    js = _nonnegative("machine.inertia_shaft", machine["inertia_shaft"], "kg*m^2")
    j1 = _nonnegative("machine.inertia_impeller_1", machine["inertia_impeller_1"], "kg*m^2")
    j2 = _nonnegative("machine.inertia_impeller_2", machine["inertia_impeller_2"], "kg*m^2")
    return js, (j1, j2)


def gap_params(machine: dict, loads: dict) -> pf.Gaps:
    """The vane clearances (machine section) and the fluid (loads section), SI."""
    values = {k: machine[k] for k in pf.GAP_FIELDS[:3]}
    values |= {k: loads[k] for k in pf.GAP_FIELDS[3:]}
    aliases = {k: f"loads.{k}" for k in pf.GAP_FIELDS[3:]}
    return build_params(pf.Gaps, "machine", values, aliases)


def land_params(params: gb.GuideBar, pump: vp.VanePump, ports: vp.PortPressures,
                gaps: pf.Gaps, land: float = 0.0) -> pf.LandWindows:  # fmt: skip
    """The ports' closed windows at the equal-speed points (``machine.port_land`` [rad]).

    The machine's :func:`rotorkin.machines.pump_flow.land_windows` at this drive's
    turning points in closed form (:func:`rotorkin.drives.guide_bar.pump.turning_angles`);
    errors name ``machine.port_land``.
    """
    values = {"pump": pump, "ports": ports, "gaps": gaps,
              "motion_of": functools.partial(gb.motion, params),
              "turning": gb_pump.turning_angles(params), "period": gb.period(params),
              "land": land}  # fmt: skip
    return build_params(pf.land_windows, "machine", values)


def _pump_summary(drive, pump, ports, inertia, speed, coefficient, gaps=None,
                  windows=None) -> dict:  # fmt: skip
    period = gb.period(drive)
    gaps = gaps or pf.Gaps()
    windows = windows or land_params(drive, pump, ports, gaps)
    fine = np.linspace(0.0, period, _PEAK_SAMPLES)
    st = pump_state(drive, pump, ports, inertia, speed, fine, windows)
    # time-averaged flow: volume per period over the time of a period
    dt = 1.0 / st["omega"]
    t_period = float(np.trapezoid(dt, fine))
    flow_mean = vp.displacement(pump) / t_period
    dyn = closed_forms.dynamics_summary(drive, st, inertia, fine, coefficient)
    flow = pf.pump_flow(pump, ports, gaps, windows, flow_mean, t_period, st["dV"], fine,
                        st["omega"])  # fmt: skip
    out = {
        **closed_forms.pump_summary(drive, pump),
        "flow_mean_l_per_min": flow_mean * _M3_TO_L_PER_MIN,
        **{k: dyn[k] for k in closed_forms.FLOW_KEYS},
        **pf.flow_keys(flow, ports, windows.land),
        **closed_forms.work_summary(drive, pump, ports, flow_mean),
        **{k: dyn[k] for k in closed_forms.TORQUE_KEYS},
    }
    out.update(time_domain(st["motion"], speed, closed_forms.SLUGS, period)[2])
    return out


def _pump_columns(drive, pump, ports, inertia, speed, theta, gaps=None,
                  windows=None) -> tuple[dict, dict]:  # fmt: skip
    gaps = gaps or pf.Gaps()
    windows = windows or land_params(drive, pump, ports, gaps)
    st = pump_state(drive, pump, ports, inertia, speed, theta, windows)
    leak = pf.leakage_flow(pump, gaps, ports)["total"]
    closed = pf.closed_windows(theta, windows.turning, windows.period, windows.land)[0]
    cols = {}
    for j, tag in ((0, "a"), (1, "b")):
        cols[f"chamber_{tag}_volume_cm3"] = st["V"][j] * 1e6
        cols[f"chamber_{tag}_dvolume_cm3_per_rad"] = st["dV"][j] * 1e6
        cols[f"chamber_{tag}_pressure_bar"] = st["p"][j] / 1e5
    cols["flow_l_per_min"] = st["flow"] * _M3_TO_L_PER_MIN
    cols["leakage_l_per_min"] = np.full(np.shape(st["flow"]), leak * _M3_TO_L_PER_MIN)
    cols["flow_delivered_l_per_min"] = (
        pf.delivered_flow(st["dV"], closed, st["omega"], leak) * _M3_TO_L_PER_MIN
    )
    cols["impeller1_torque_Nm"] = st["M"][0]
    cols["impeller2_torque_Nm"] = st["M"][1]
    cols["shaft_torque_Nm"] = st["shaft"]
    cols["inertia_torque_Nm"] = st["inertia"]
    cols["shaft_torque_with_inertia_Nm"] = st["net"]
    cols["equivalent_inertia_kgm2"] = st["J_eq"]
    tcols, tdocs, _, _ = time_domain(gb.motion(drive, theta), speed,
                                     ("impeller1", "impeller2"), gb.period(drive))  # fmt: skip
    cols.update(tcols)
    return cols, {**_PUMP_DOCS, **tdocs}


def pair_forces(cfg: dict, params: gb.GuideBar, state: dict, theta, inertia):
    """Forces in the pairs at the input angles ``theta``, from a :func:`pump_state` on them.

    The impellers' load is the pump's torque (ideal ports) and their inertia at the run
    speed (:func:`rotorkin.drives.guide_bar.forces.drive_torques`).

    Returns
    -------
    (Forces, list of Pair)
    """
    size = gb_forces.gearing(cfg["drive"])
    D = gb_forces.drive_torques(params, theta, state["M"], inertia[1], state["omega"],
                                state["omega_dot"])  # fmt: skip
    forces = gb_forces.solve(params, size, theta, D)
    return forces, gb_forces.pairs(params, size, forces, gb_forces.bearing_radius(cfg))


def _forces_summary(cfg, params, pump, ports, inertia, speed, work_per_turn,
                    windows=None) -> dict:  # fmt: skip
    fine = np.linspace(0.0, gb.period(params), _PEAK_SAMPLES)
    st = pump_state(params, pump, ports, inertia, speed, fine, windows)
    forces, pairs = pair_forces(cfg, params, st, fine, inertia)
    model = pr.ContactModel.from_config(cfg)
    out = pr.summary(pairs, fine, work_per_turn, model, st["omega"])
    out.update(gb_forces.own_summary(forces, st["omega"]))
    return out


def _forces_columns(cfg, params, pump, ports, inertia, speed, theta,
                    windows=None) -> tuple[dict, dict]:  # fmt: skip
    st = pump_state(params, pump, ports, inertia, speed, theta, windows)
    forces, pairs = pair_forces(cfg, params, st, theta, inertia)
    cols, docs = pr.columns(pairs, pr.ContactModel.from_config(cfg), st["shaft"])
    cols.update(gb_forces.signed_columns(forces))
    return cols, {**docs, **gb_forces.SIGNED_DOCS}


def drive_params(cfg: dict) -> gb.GuideBar:
    """The drive's parameters from a validated config (SI); errors name the config keys."""
    d = cfg["drive"]
    keys = {"lam": "lambda", "gear_ratio": "gear_ratio", "input_gear_ratio": "input_gear_ratio",
            "phase": "phase", "driver": "driver"}  # fmt: skip
    # a key missing from cfg takes the dataclass default, which is the schema's
    values = {field: d[key] for field, key in keys.items() if key in d}
    return build_params(gb.GuideBar, "drive", values, aliases={"lam": "lambda"})


def pump_params(cfg: dict, params: gb.GuideBar | None = None) -> vp.VanePump:
    """The pump from a validated config (SI; missing machine keys take the schema's defaults).

    Errors name the config keys (``machine.vane_angle``, ...).
    """
    params = drive_params(cfg) if params is None else params
    machine = _defaults(cfg)[0]
    keys = ("vanes_per_impeller", "vane_angle", "hub_radius", "casing_radius", "axial_width")
    return build_params(
        gb_pump.vane_pump, "machine", {"params": params, **{k: machine[k] for k in keys}}
    )


def pairs_of(cfg: dict):
    """``f(theta, drive_torque, motion) -> list[Pair]`` for a machine that is not the pump."""
    params = drive_params(cfg)
    size = gb_forces.gearing(cfg["drive"])
    radius = gb_forces.bearing_radius(cfg)

    def f(theta, drive_torque, motion):
        return gb_forces.pairs(params, size, gb_forces.solve(params, size, theta, drive_torque),
                               radius)  # fmt: skip

    return f


def law(cfg: dict) -> RotaryLaw:
    """The two members' motion for any vane machine on this drive (:mod:`rotorkin.vane`)."""
    params = drive_params(cfg)
    return RotaryLaw(functools.partial(gb.motion, params), gb.period(params))


def evaluate(cfg: dict) -> StudyResult:
    """Run the guide-bar pump study on a validated config (SI values).

    Parameters
    ----------
    cfg : dict
        ``cfg["drive"]``: ``lambda``, ``gear_ratio``, ``input_gear_ratio``,
        ``phase`` [rad], ``driver``; ``cfg["machine"]``: the pump geometry and
        inertias; ``cfg["loads"]``: ``impeller_torque_1``, ``impeller_torque_2``
        [N*m], ``suction_pressure``, ``discharge_pressure`` [Pa];
        ``cfg["run"]``: ``points``, ``speed`` [rad/s]. Missing machine, loads
        and run keys take the schema's defaults.

    Returns
    -------
    StudyResult
        Summary keys: see :data:`HEADLINE`, ``docs/drives/guide_bar.md`` and
        ``docs/machines/vane_pump.md``.
    """
    params = drive_params(cfg)
    machine, loads, run = _defaults(cfg)
    m7 = float(loads["impeller_torque_1"])
    m8 = float(loads["impeller_torque_2"])
    pump = pump_params(cfg, params)
    ports = build_params(
        vp.PortPressures,
        "loads",
        {
            "suction_pressure": loads["suction_pressure"],
            "discharge_pressure": loads["discharge_pressure"],
        },
    )
    gaps = gap_params(machine, loads)
    windows = land_params(params, pump, ports, gaps, float(machine["port_land"]))
    inertia = _inertias(machine)
    speed = run["speed"]
    summary = _summary(params, m7, m8)
    summary.update(_pump_summary(params, pump, ports, inertia, speed,
                                 float(machine["speed_fluctuation"]), gaps,
                                 windows))  # fmt: skip
    columns = _columns(params, m7, m8, run["points"])
    theta = angle_grid(gb.period(params), run["points"])
    pump_cols, pump_docs = _pump_columns(params, pump, ports, inertia, speed, theta, gaps,
                                         windows)  # fmt: skip
    columns.update(pump_cols)
    summary.update(_forces_summary(cfg, params, pump, ports, inertia, speed,
                                   summary["indicated_work_J"], windows))  # fmt: skip
    force_cols, force_docs = _forces_columns(cfg, params, pump, ports, inertia, speed, theta,
                                             windows)  # fmt: skip
    columns.update(force_cols)

    def plot(outdir: Path) -> list[Path]:
        grid = angle_grid(gb.period(params), 1441)
        state = pump_state(params, pump, ports, inertia, speed, grid, windows)
        pairs = pair_forces(cfg, params, state, grid, inertia)[1]
        return figures_guide_bar.plot_all(
            params, m7, m8, Path(outdir), pump=pump, ports=ports, theta=grid, state=state,
            summary=summary, pairs=pairs, contact=pr.ContactModel.from_config(cfg),
        )  # fmt: skip

    return StudyResult(
        drive_type="guide_bar",
        title="Differential vane pump, rotating guide-bar + gear drive",
        summary=summary,
        columns=columns,
        column_docs={**_DOCS, **pump_docs, **force_docs},
        headline=HEADLINE,
        write_figures=plot,
        motion=gb.motion(params, theta),
        warnings=_warnings(cfg, summary, gaps),
    )


def _warnings(cfg: dict, summary: dict, gaps: pf.Gaps | None = None) -> tuple[str, ...]:
    """Inputs that leave summary numbers without meaning, one line each."""
    loads = cfg.get("loads", {})
    out = []
    floor = pf.VAPOUR_PRESSURE if gaps is None else gaps.vapour_pressure
    cavitation = pf.cavitation_warning(summary["trapped_pressure_min_bar"] * 1e5, floor)
    if cavitation:
        out.append(cavitation)
    if loads.get("discharge_pressure") == loads.get("suction_pressure"):
        out.append(
            "loads.discharge_pressure = loads.suction_pressure: the pump lifts nothing, so its "
            "mean torque, work and hydraulic power are 0"
        )
    because = {
        "input_torque_fluctuation_ratio": "the input torque of eq. 7 is 0 everywhere "
        "(loads.impeller_torque_1 = loads.impeller_torque_2 = 0)",
    }
    return (*out, *undefined_warnings(summary, because))
