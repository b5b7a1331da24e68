"""Any vane machine on any rotary drive: the study of a machine moved by a :class:`RotaryLaw`.

:func:`evaluate` runs ``[machine] type`` (twin_rotor, vane_pump, rotary_blade) on
the law a drive gives (:attr:`rotorkin.drives.DriveSpec.law`) and returns a
:class:`~rotorkin.studies.StudyResult` like every drive's own study: summary
(the drive's motion, the machine's closed forms, torques and flywheel at the run
speed), ``motion.csv`` columns over one shaft turn, figures.

Dynamics at the run speed (constant or a profile over one period of the law):
the gas or port torque on the shaft by virtual work ``T = sum_i M_i q_i'``, the
inertia torque of shaft and members, the energy fluctuation of the net torque at
the time-mean speed and the flywheel for ``machine.speed_fluctuation``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin.analysis import flywheel as fw
from rotorkin.analysis import torque as tq
from rotorkin.analysis.pairs import ContactModel
from rotorkin.analysis.pairs import columns as pair_columns
from rotorkin.analysis.pairs import summary as pair_summary
from rotorkin.analysis.timing import shaft_speed
from rotorkin.studies import StudyResult
from rotorkin.studies.helpers import angle_grid, time_domain, undefined_warnings
from rotorkin.vane import figures
from rotorkin.vane import machines as vm
from rotorkin.vane.law import RotaryLaw

__all__ = ["evaluate", "HEADLINES", "dynamics", "DWELL_FRACTION"]

_TWO_PI = 2.0 * np.pi
#: Samples per shaft turn for the sampled extremes, integrals and flywheel.
_FINE = 20_001
#: A chamber "dwells" at its dead centre while its volume is within this fraction of the
#: swept volume from its smallest volume.
DWELL_FRACTION = 0.01

_COMMON = {
    "relative_swing_deg": "swing of the angle between the two members",
    "volume_cycles_per_rev": "volume cycles of each chamber per shaft turn",
    "member_speed_ratio_min": "slowest member speed over the shaft's",
    "member_speed_ratio_max": "fastest member speed over the shaft's",
    "member_accel_peak_per_rad": "peak member acceleration over shaft speed squared",
    "member_jerk_peak_per_rad2": "peak member jerk over shaft speed cubed",
    "tdc_dwell_deg": "shaft angle a chamber stays within 1 % of the stroke of its dead centre",
    "drive_torque_peak_Nm": "largest torque the drive puts on a member (machine and inertia)",
    "displacement_cm3_per_rev": "volume swept by all chambers per shaft turn",
}
_TAIL = {
    "indicated_work_J": "work of the machine on the shaft per turn (- : the shaft drives it)",
    "mean_torque_Nm": "mean torque on the shaft (+ drives the shaft)",
    "torque_ripple": "(max - min) / |mean| of the shaft torque",
    "indicated_power_kW": "power at the run speed (- : absorbed)",
    "flywheel_inertia_kgm2": "flywheel for the chosen coefficient of speed fluctuation",
}
#: The printed summary keys of each machine.
HEADLINES = {
    "twin_rotor": {
        **_COMMON,
        "power_strokes_per_rev": "power strokes of the engine per shaft turn",
        "piston_width_deg": "angular width of a piston for the compression ratio",
        "compression_ratio_geometric": "V_max / V_min of a chamber, with clearance",
        "peak_pressure_bar": "highest chamber pressure of the cycle",
        "imep_bar": "indicated mean effective pressure: work per turn over displacement",
        "indicated_efficiency": "indicated work over the fuel's energy (ideal cycle: the heat)",
        **_TAIL,
    },
    "vane_pump": {
        **_COMMON,
        "vane_angle_deg": "angular width of a vane",
        "flow_mean_l_per_min": "mean delivered flow at the run speed",
        "flow_ripple": "(max - min) / mean of the geometric flow (ideal ports)",
        "flow_delivered_mean_l_per_min": "mean flow less leakage, land and compression losses",
        "volumetric_efficiency": "delivered over geometric mean flow",
        "flow_delivered_ripple": "(max - min) / mean of the flow delivered, losses included",
        "trapped_pressure_peak_bar": "highest pressure of a chamber closed by the ports' land",
        "trapped_pressure_min_bar": "lowest pressure of a chamber closed by the ports' land",
        **_TAIL,
    },
    "rotary_blade": {
        **_COMMON,
        "compression_ratio_geometric": "V_max / V_min of a chamber",
        "pressure_max_bar": "highest gas pressure of the cycle (loads.pressure_model)",
        "indicated_efficiency": "indicated work over the heater's heat (Stirling models)",
        "carnot_efficiency": "1 - T_cold / T_hot, the bound of the efficiency",
        "heat_in_J_per_rev": "heat taken in by the hot spaces and the heater per turn",
        **_TAIL,
    },
}
_SLUGS = ("member1", "member2")
#: The printed keys of a drive's load-carrying pairs (:mod:`rotorkin.analysis.pairs`).
CONTACT_HEADLINE = {
    "peak_contact_force_N": "largest normal force in a contact (mesh, roller, slider)",
    "peak_contact_stress_MPa": "largest Hertz pressure in a contact",
    "contact_safety_factor": "contact.allowable_stress over the largest Hertz pressure",
    "peak_bearing_load_N": "largest load on a bearing",
    "friction_loss_W": "power lost to friction at the run speed (first order)",
    "mechanical_efficiency": "work delivered over work put in, friction included",
}


def dynamics(st: vm.State, theta, speed, period, inertia) -> dict:
    """Torques, inertia and flywheel of a machine state sampled over one shaft turn.

    Parameters
    ----------
    st : State
        The machine at ``theta``.
    theta : ndarray, shape (n,)
        ``0 .. 2 pi``, ends included [rad].
    speed : float or list
        ``run.speed`` [rad/s], a profile over one ``period``.
    period : float
        Period of the law [rad].
    inertia : (float, (float, float))
        ``J_shaft`` and the members' inertias [kg m^2].
    """
    js, jm = inertia
    dq, d2q = st.motion.dq, st.motion.d2q
    omega, omega_dot, _ = shaft_speed(theta, speed, period)
    jm_arr = np.asarray(jm, dtype=float)[:, None] if np.ndim(dq) > 1 else np.asarray(jm)
    t_in = tq.inertia_torque(js, jm, dq, d2q, omega, omega_dot)
    span = theta[-1] - theta[0]
    omega_mean = span / float(np.trapezoid(1.0 / omega, theta))  # time average
    steady = st.shaft - tq.inertia_torque(js, jm, dq, d2q, omega_mean, 0.0)
    j_eq = tq.equivalent_inertia(js, jm, dq)
    member_accel = d2q * omega**2 + dq * omega_dot  # [rad/s^2]
    return {
        "omega": omega,
        "omega_mean": omega_mean,
        # what the drive must put on each member: its inertia less the machine's torque
        "drive_torque": jm_arr * member_accel - st.members,
        "inertia_torque": t_in,
        "net": st.shaft - t_in,
        "steady": steady,
        "J_eq": j_eq,
        "energy_fluctuation": float(fw.energy_fluctuation(steady, theta)),
        "J_mean": float(np.mean(j_eq[:-1])),
    }


def _ratio(num, den) -> float:
    return float(num / den) if den > 0 else float("nan")


def _dwell(setup: vm.Setup, r) -> float:
    """Shaft angle per dead centre within DWELL_FRACTION of the stroke of the smallest r [deg]."""
    near = (r - setup.r_lo) <= DWELL_FRACTION * (setup.r_hi - setup.r_lo)
    minima = setup.strokes_per_turn / 2.0  # per turn
    return float(np.degrees(_TWO_PI * np.mean(near[:-1]) / minima)) if minima else float("nan")


def _summary(setup: vm.Setup, cfg: dict, theta, st, dyn) -> dict:
    out = vm.summary(setup)
    mo = st.motion
    r = mo.q[1] - mo.q[0] - setup.shift  # as the drive gives it
    coefficient = float(cfg.get("machine", {}).get("speed_fluctuation", 0.02))
    work = out["indicated_work_J"]
    d_e, j_mean, w = dyn["energy_fluctuation"], dyn["J_mean"], dyn["omega_mean"]
    out.update({
        "member_speed_ratio_min": float(np.min(mo.dq)),
        "member_speed_ratio_max": float(np.max(mo.dq)),
        "member_accel_peak_per_rad": float(np.max(np.abs(mo.d2q))),
        "member_jerk_peak_per_rad2": float(np.max(np.abs(mo.d3q))),
        "tdc_dwell_deg": _dwell(setup, r),
        "mean_torque_Nm": work / _TWO_PI,
        "mean_torque_integrated_Nm": float(np.trapezoid(st.shaft, theta)) / setup.law.span,
        "torque_ripple": float(tq.torque_ripple(st.shaft)),
        "torque_ripple_with_inertia": float(tq.torque_ripple(dyn["net"])),
        "shaft_torque_max_Nm": float(np.max(st.shaft)),
        "shaft_torque_min_Nm": float(np.min(st.shaft)),
        "member_torque_peak_Nm": float(np.max(np.abs(st.members))),
        "drive_torque_peak_Nm": float(np.max(np.abs(dyn["drive_torque"]))),
        "indicated_power_kW": work * w / _TWO_PI / 1e3,
        "equivalent_inertia_mean_kgm2": j_mean,
        "energy_fluctuation_J": d_e,
        "speed_fluctuation_without_flywheel": _ratio(d_e, j_mean * w**2),
        "speed_fluctuation": coefficient,
        "flywheel_inertia_kgm2": float(fw.flywheel_inertia(d_e, w, coefficient, j_mean)),
    })  # fmt: skip
    if setup.kind == "vane_pump":
        out.update(vm.pump_flow(setup, theta, st, dyn["omega"])[0])
    if setup.kind == "rotary_blade":
        out["pressure_max_bar"] = float(np.max(st.pressure)) / 1e5
        out["pressure_min_bar"] = float(np.min(st.pressure)) / 1e5
    return out


def _columns(setup: vm.Setup, st: vm.State, dyn: dict, theta, members) -> tuple[dict, dict]:
    mo = st.motion
    cols = {"theta_deg": np.degrees(theta)}
    docs = {"theta_deg": "Shaft angle theta."}
    for k in (0, 1):
        cols[f"member{k + 1}_angle_deg"] = np.degrees(mo.q[k])
        docs[f"member{k + 1}_angle_deg"] = (
            f"Angle of {members[k]} (member {k + 1})"
            + (", with the vanes' mounting offset" if k == 1 else "") + "."
        )  # fmt: skip
    cols["relative_angle_deg"] = np.degrees(mo.q[1] - mo.q[0])
    docs["relative_angle_deg"] = "Angle of member 2 less member 1's, as mounted."
    for name, arr, what in (("speed_ratio", mo.dq, "speed over the shaft's"),
                            ("accel_per_rad", mo.d2q, "acceleration over shaft speed squared"),
                            ("jerk_per_rad2", mo.d3q, "jerk over shaft speed cubed")):  # fmt: skip
        for k in (0, 1):
            cols[f"member{k + 1}_{name}"] = arr[k]
            docs[f"member{k + 1}_{name}"] = f"{members[k]}: {what} (exact derivative)."
    for j, tag in ((0, "a"), (1, "b")):
        cols[f"chamber_{tag}_volume_cm3"] = st.volume[j] * 1e6
        docs[f"chamber_{tag}_volume_cm3"] = f"Volume of chamber {j + 1} (kind {tag.upper()})."
        cols[f"chamber_{tag}_dvolume_cm3_per_rad"] = st.dvolume[j] * 1e6
        docs[f"chamber_{tag}_dvolume_cm3_per_rad"] = f"dV/dtheta of chamber {j + 1} (exact)."
        cols[f"chamber_{tag}_pressure_bar"] = st.pressure[j] / 1e5
        docs[f"chamber_{tag}_pressure_bar"] = f"Absolute pressure in chamber {j + 1}."
    for k in (0, 1):
        cols[f"member{k + 1}_torque_Nm"] = st.members[k]
        docs[f"member{k + 1}_torque_Nm"] = (
            f"Torque of the chamber pressures on {members[k]}, sum p_j dV_j/dq_{k + 1}."
        )
    for k in (0, 1):
        cols[f"member{k + 1}_drive_torque_Nm"] = dyn["drive_torque"][k]
        docs[f"member{k + 1}_drive_torque_Nm"] = (
            f"Torque the drive must put on {members[k]} at the run speed: its inertia less "
            "the machine's torque (what the drive's pairs carry)."
        )
    for key, values, doc in (
        ("shaft_torque_Nm", st.shaft,
         "Torque of the machine on the shaft by virtual work, sum M_i q_i'; + drives the shaft."),
        ("inertia_torque_Nm", dyn["inertia_torque"],
         "Torque the shaft spends on the inertia of shaft and members at the run speed."),
        ("shaft_torque_with_inertia_Nm", dyn["net"], "shaft_torque_Nm - inertia_torque_Nm."),
        ("equivalent_inertia_kgm2", dyn["J_eq"], "J_shaft + J_1 q_1'^2 + J_2 q_2'^2."),
    ):  # fmt: skip
        cols[key], docs[key] = values, doc
    return cols, docs


def evaluate(
    cfg: dict,
    law: RotaryLaw,
    *,
    drive_type: str,
    title: str,
    drive_summary: dict | None = None,
    drive_headline: dict | None = None,
    drive_columns=None,
    drive_figures=None,
    drive_pairs=None,
    warnings: tuple = (),
) -> StudyResult:
    """Run ``cfg["machine"]["type"]`` on ``law`` (a validated SI config).

    Parameters
    ----------
    cfg : dict
        ``machine`` and ``loads`` sections of the machine type
        (:mod:`rotorkin.machines.schema`), ``run``.
    law : RotaryLaw
        The drive's two members.
    drive_type, title : str
        For the result.
    drive_summary, drive_headline : dict, optional
        The drive's own summary keys and printed keys (put first).
    drive_columns : callable, optional
        ``drive_columns(theta) -> (columns, docs)``: the drive's own columns.
    drive_figures : callable, optional
        ``drive_figures(outdir) -> list[Path]``: the drive's own figures.
    drive_pairs : callable, optional
        ``drive_pairs(theta, drive_torque, motion) -> list[Pair]``: the drive's
        load-carrying pairs (:mod:`rotorkin.analysis.pairs`) from the torque it must
        put on each member (machine and inertia at the run speed, shape (2, n)).
    warnings : tuple of str
        The drive's warnings.
    """
    kind = cfg["machine"]["type"]
    setup = vm.setup(kind, cfg, law)
    run = cfg.get("run", {})
    speed = run.get("speed", 3000.0 * np.pi / 30.0)
    inertia = vm.inertias(kind, cfg["machine"])
    fine = np.linspace(0.0, law.span, _FINE)
    st_fine = vm.state(setup, fine)
    dyn_fine = dynamics(st_fine, fine, speed, law.period, inertia)
    summary = {**(drive_summary or {}), **_summary(setup, cfg, fine, st_fine, dyn_fine)}
    model = ContactModel.from_config(cfg)
    if drive_pairs is not None:
        found = drive_pairs(fine, dyn_fine["drive_torque"], st_fine.motion)
        summary.update(pair_summary(found, fine, summary["indicated_work_J"], model,
                                    dyn_fine["omega"]))  # fmt: skip
    _, _, peaks, _ = time_domain(st_fine.motion, speed, _SLUGS, law.period)
    summary.update(peaks)
    summary = {k: v.item() if isinstance(v, np.generic) else v for k, v in summary.items()}

    theta = angle_grid(law.span, run.get("points", 721))
    st = vm.state(setup, theta)
    dyn = dynamics(st, theta, speed, law.period, inertia)
    members = st.motion.members
    columns, docs = _columns(setup, st, dyn, theta, members)
    if kind == "vane_pump":
        extra, extra_docs = vm.pump_flow(setup, theta, st, dyn["omega"])[1:]
        columns.update(extra)
        docs.update(extra_docs)
    if drive_columns is not None:
        extra, extra_docs = drive_columns(theta)
        columns.update(extra)
        docs.update(extra_docs)
    if drive_pairs is not None:
        extra, extra_docs = pair_columns(drive_pairs(theta, dyn["drive_torque"], st.motion),
                                         model, st.shaft)  # fmt: skip
        columns.update(extra)
        docs.update(extra_docs)
    tcols, tdocs, _, _ = time_domain(st.motion, speed, _SLUGS, law.period)
    columns.update(tcols)
    docs.update({k: v[0].upper() + v[1:] + "." for k, v in tdocs.items()})

    def plot(outdir: Path) -> list[Path]:
        paths = list(drive_figures(Path(outdir))) if drive_figures is not None else []
        grid = np.linspace(0.0, law.span, 1441)
        return paths + figures.plot_machine(setup, vm.state(setup, grid), grid, Path(outdir),
                                            title)  # fmt: skip

    headline = {**(drive_headline or {}), **HEADLINES[kind]}
    if drive_pairs is not None:
        headline.update({k: v for k, v in CONTACT_HEADLINE.items() if k in summary})
    return StudyResult(
        drive_type=drive_type,
        title=title,
        summary=summary,
        columns=columns,
        column_docs=docs,
        headline=headline,
        write_figures=plot,
        motion=law.motion(angle_grid(law.period, run.get("points", 721))),
        warnings=(*warnings, *_warnings(setup, summary)),
    )


#: Per machine: the model input that leaves a summary value undefined.
_BECAUSE = {
    "twin_rotor": {"indicated_efficiency": "no heat is added (loads.heat_per_cycle = 0)"},
    "vane_pump": {"volumetric_efficiency": "the geometric flow is 0 (no displacement)"},
    "rotary_blade": {
        "indicated_efficiency": "the gas takes in no heat (loads.hot_temperature is not above "
        "loads.cold_temperature)"
    },
}


def _warnings(setup: vm.Setup, summary: dict) -> tuple[str, ...]:
    out = []
    if setup.kind == "twin_rotor" and getattr(setup.loads, "heat_per_cycle", None) == 0.0:
        out.append("loads.heat_per_cycle = 0: no heat is added, so the indicated work, mean "
                   "torque and power are those of a motored engine (about 0)")  # fmt: skip
    if setup.kind == "vane_pump":
        out.extend(vm.pump_warnings(setup, summary))
    if setup.kind == "vane_pump" and setup.loads.discharge_pressure == setup.loads.suction_pressure:
        out.append("loads.discharge_pressure = loads.suction_pressure: the pump lifts nothing, so "
                   "its mean torque, work and hydraulic power are 0")  # fmt: skip
    if setup.kind == "rotary_blade" and setup.loads.hot_temperature == setup.loads.cold_temperature:
        out.append("loads.hot_temperature = loads.cold_temperature: the gas does no net work, so "
                   "the mean torque and power are 0")  # fmt: skip
    return (*out, *undefined_warnings(summary, _BECAUSE[setup.kind]))
