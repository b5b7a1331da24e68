"""Study of the wobble-plate + spherical-cam twin-rotor engine (Chen Hu et al. 2015).

Config keys (SI, defaults filled by :mod:`rotorkin.io.config`):
``drive.plate_tilt``, ``drive.roller_axis_angle``, ``drive.spin_ratio``,
``drive.sphere_radius``; ``machine.*`` (:class:`rotorkin.machines.twin_rotor.TwinRotor`:
compression ratio, pistons per rotor, cylinder section, clearance, inertias, speed
fluctuation); ``loads.*`` (the fuel-air cycle, :mod:`rotorkin.machines.fuel_air`, or with
``model = "ideal"`` :class:`rotorkin.analysis.engine_cycle.IdealCycle`: ambient pressure,
polytropic exponent, heat per cycle); ``run.points``, ``run.speed``.
Keys missing from a hand-built cfg take the dataclasses' defaults (= the config's).
"""

from __future__ import annotations

import functools
import sys
from dataclasses import fields
from pathlib import Path

import numpy as np

from rotorkin.analysis import engine_cycle as ec
from rotorkin.analysis import pairs as pr
from rotorkin.analysis.timing import mean_speed, shaft_speed
from rotorkin.core.errors import ParameterError
from rotorkin.drives.wobble_cam import cam as cs
from rotorkin.drives.wobble_cam import engine as eng
from rotorkin.drives.wobble_cam import figures as figures_wobble_cam
from rotorkin.drives.wobble_cam import figures_cam as figures_spherical_cam
from rotorkin.drives.wobble_cam import forces as fo
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.machines import fuel_air as fa
from rotorkin.machines import twin_rotor as tr
from rotorkin.render.figures import draw
from rotorkin.studies import StudyResult
from rotorkin.studies.helpers import angle_grid, build_params, time_domain, undefined_warnings
from rotorkin.vane import RotaryLaw
from rotorkin.vane.law import turning_points

__all__ = ["evaluate", "models", "law", "HEADLINE"]

#: Summary keys printed by the command line, in order, with what each means (one line).
HEADLINE = {
    "slider_angle_max_deg": "largest angle between the slider groups, alpha'_max (eq. 15)",
    "slider_angle_min_deg": "smallest angle between the slider groups, alpha'_min",
    "chamber_angle_max_deg": "chamber angle delta at bottom dead centre (eq. 22)",
    "chamber_angle_min_deg": "chamber angle delta at top dead centre (eq. 22)",
    "chamber_swing_deg": "swing of the chamber angle over a turn (Fig. 10)",
    "piston_width_deg": "angular width beta of a piston for the compression ratio (eq. 21)",
    "volume_cycles_per_rev": "volume cycles of one chamber per shaft turn",
    "power_strokes_per_rev": "power strokes of the engine per shaft turn",
    "max_plate_tilt_deg": "largest admissible plate tilt, eq. 20 (Fig. 13)",
    "displacement_cm3_per_rev": "swept volume of all chambers per shaft turn",
    "compression_ratio_geometric": "V_max / V_min of a chamber, with clearance",
    "peak_pressure_bar": "highest chamber pressure of the cycle",
    "imep_bar": "indicated mean effective pressure: work per turn over displacement",
    "indicated_efficiency": "indicated work over the fuel's energy (ideal cycle: the heat)",
    "indicated_work_J": "indicated work of all chambers per shaft turn",
    "mean_torque_Nm": "mean gas torque on the shaft (+ drives the shaft)",
    "torque_ripple": "(max - min) / mean of the gas torque on the shaft",
    "indicated_power_kW": "indicated power at the run speed",
    "flywheel_inertia_kgm2": "flywheel for the chosen coefficient of speed fluctuation",
    "cam_shell_torque_share": "share of the output torque taken at the cam shell (drive.output)",
    "cam_shell_natural_torque_share": "share the grooves hand the cam shell (gearbox idle)",
    "groove_roller_force_max_N": "largest normal force of a roller on its groove wall, at speed",
    "groove_contact_stress_max_MPa": "largest Hertz pressure of a roller on its groove wall",
    "rail_roller_force_max_N": "largest force of a roller on its rotor's slider rail",
    "plate_bearing_load_max_N": "largest load of a wobble-plate bearing on the inclined crank",
    "cam_bearing_load_max_N": "largest radial load of a cam-shell bearing (the grooves' couple)",
    "bevel_mesh_force_max_N": "largest normal tooth force of a bevel mesh of the gearbox",
    "peak_contact_stress_MPa": "largest Hertz pressure of any contact over the turn",
    "contact_safety_factor": "allowable contact pressure over the largest",
    "mechanical_efficiency": "output over indicated work, friction of every pair counted",
}

#: Samples per shaft turn used for the peaks of the rotor derivatives (independent of run.points).
_PEAK_SAMPLES = 20_001
#: Default shaft speed when a hand-built cfg has none: 3000 rpm [rad/s] (the config's default).
_DEFAULT_SPEED = 3000.0 * np.pi / 30.0


def _deg(x) -> float:
    return float(np.degrees(x))


def _layout(params, machine):
    try:
        return eng.piston_layout(params, machine)
    except ParameterError as exc:
        raise ParameterError("machine.compression_ratio", exc.value, exc.admissible) from None


def _section(cfg, name, cls):
    """The cfg section's values for the fields of ``cls`` (missing ones: the defaults)."""
    section = cfg.get(name, {}) or {}
    return {f.name: section[f.name] for f in fields(cls) if f.name in section}


def _summary(params, layout) -> dict:
    amax, amin = (
        float(v) for v in wc.slider_angle_extremes(params.plate_tilt, params.roller_axis_angle)
    )
    design_min, design_max = (
        (layout.chamber_a_min, layout.chamber_a_max)
        if layout.design_kind == "A"
        else (layout.chamber_b_min, layout.chamber_b_max)
    )
    # peaks of the rotor kinematic coefficients on a fine grid (closed-form values, sampled)
    fine = np.linspace(0.0, wc.period(params), _PEAK_SAMPLES)
    _, d1, d2, d3 = wc.rotor_angles(params, fine)
    c, n = np.cos(params.plate_tilt), params.spin_ratio
    if params.spin_a or params.spin_b:  # a corrected spin law: sampled extremes
        ratios = (float(np.min(d1)), float(np.max(d1)))
    else:  # dPhi/dtheta = 1 + n c / D with c^2 <= D <= 1: extremes 1 + n c and 1 + n / c
        ratios = sorted((1.0 + n * c, 1.0 + n / c))
    return {
        "slider_angle_max_deg": _deg(amax),
        "slider_angle_min_deg": _deg(amin),
        "chamber_angle_max_deg": _deg(design_max),
        "chamber_angle_min_deg": _deg(design_min),
        "chamber_swing_deg": _deg(amax - amin),
        "piston_width_deg": _deg(layout.piston_width),
        "volume_cycles_per_rev": wc.volume_cycles_per_rev(params),
        "power_strokes_per_rev": wc.power_strokes_per_rev(params),
        "max_plate_tilt_deg": _deg(
            wc.max_plate_tilt(params.roller_axis_angle, params.pistons_per_rotor)
        ),
        "piston_offset_gamma_deg": _deg(wc.piston_offset(params.pistons_per_rotor)),
        "chambers": wc.chamber_count(params.pistons_per_rotor),
        "compression_ratio": float(layout.compression_ratio),
        "min_compression_ratio": float(wc.min_compression_ratio(params)),
        "design_chamber_kind": layout.design_kind,
        "chamber_a_angle_min_deg": _deg(layout.chamber_a_min),
        "chamber_a_angle_max_deg": _deg(layout.chamber_a_max),
        "chamber_b_angle_min_deg": _deg(layout.chamber_b_min),
        "chamber_b_angle_max_deg": _deg(layout.chamber_b_max),
        "compression_ratio_a": float(layout.compression_ratio_a),
        "compression_ratio_b": float(layout.compression_ratio_b),
        "volume_cycles_per_rev_all_chambers": wc.chamber_count(params.pistons_per_rotor)
        * wc.volume_cycles_per_rev(params),
        "rotor_mean_speed_ratio": float(1.0 + n),
        "rotor_speed_ratio_min": float(ratios[0]),
        "rotor_speed_ratio_max": float(ratios[1]),
        "rotor_accel_peak_per_rad": float(np.max(np.abs(d2))),
        "rotor_jerk_peak_per_rad2": float(np.max(np.abs(d3))),
    }


_DOCS = {
    "theta_deg": "Output-shaft angle theta, positive from +z towards +y about x.",
    "rotor1_angle_deg": "Rotor 1 angle Phi_1 in the yz plane from +z towards +y (rail of group 1).",
    "rotor2_angle_deg": "Rotor 2 angle Phi_2 in the yz plane from +z towards +y (rail of group 2).",
    "rotor1_speed_ratio": "dPhi_1/dtheta, rotor 1 speed over shaft speed.",
    "rotor2_speed_ratio": "dPhi_2/dtheta, rotor 2 speed over shaft speed.",
    "rotor1_accel_per_rad": "d2Phi_1/dtheta2, rotor 1 angular acceleration per shaft speed^2.",
    "rotor2_accel_per_rad": "d2Phi_2/dtheta2, rotor 2 angular acceleration per shaft speed^2.",
    "rotor1_jerk_per_rad2": "d3Phi_1/dtheta3, rotor 1 angular jerk over shaft speed cubed.",
    "rotor2_jerk_per_rad2": "d3Phi_2/dtheta3, rotor 2 angular jerk over shaft speed cubed.",
    "slider_angle_deg": "Slider (rail) angle alpha' = Phi_2 - Phi_1 (eq. 15).",
    "chamber_a_angle_deg": "Chamber kind A angle delta_A = alpha' - 2 gamma - beta (eq. 19).",
    "chamber_b_angle_deg": "Chamber kind B, delta_B = 2 pi/N + 2 gamma - alpha' - beta (eq. 18).",
    "roller1_x_mm": "Roller 1 (group 1, c = -alpha/2) centre x in the fixed frame (eq. 8).",
    "roller1_y_mm": "Roller 1 centre y in the fixed frame (eq. 8).",
    "roller1_z_mm": "Roller 1 centre z in the fixed frame (eq. 8).",
    "groove1_x_mm": "Groove centre-line point of roller 1, x4 in the cam frame (eq. 11).",
    "groove1_y_mm": "Groove centre-line point of roller 1, y4 in the cam frame (eq. 11).",
    "groove1_z_mm": "Groove centre-line point of roller 1, z4 in the cam frame (eq. 11).",
}


def _columns(params, layout, points) -> dict:
    theta = angle_grid(wc.period(params), points)
    q, d1, d2, d3 = wc.rotor_angles(params, theta)
    slider = q[1] - q[0]
    da, db = wc.chamber_angles(layout.piston_width, slider, pistons=params.pistons_per_rotor)
    roller = wc.roller_positions(params, theta)[0] * 1e3
    groove = wc.groove_points(params, theta)[0] * 1e3
    cols = {"theta_deg": np.degrees(theta)}
    for k in (0, 1):
        cols[f"rotor{k + 1}_angle_deg"] = np.degrees(q[k])
    for k in (0, 1):
        cols[f"rotor{k + 1}_speed_ratio"] = d1[k]
    for k in (0, 1):
        cols[f"rotor{k + 1}_accel_per_rad"] = d2[k]
    for k in (0, 1):
        cols[f"rotor{k + 1}_jerk_per_rad2"] = d3[k]
    cols["slider_angle_deg"] = np.degrees(slider)
    cols["chamber_a_angle_deg"] = np.degrees(da)
    cols["chamber_b_angle_deg"] = np.degrees(db)
    for i, ax in enumerate("xyz"):
        cols[f"roller1_{ax}_mm"] = roller[i]
    for i, ax in enumerate("xyz"):
        cols[f"groove1_{ax}_mm"] = groove[i]
    return cols


# --------------------------------------------------------------------------------------------
# the engine: volumes, pressures, torques, inertia
# --------------------------------------------------------------------------------------------
def _engine_summary(params, machine, cycle, layout, speed) -> dict:
    """Volumes, cycle, torques and flywheel; closed forms where they exist, else a fine grid."""
    v_min, v_max = eng.volume_limits(machine, layout)
    eps_a, eps_b = eng.compression_ratio_geometric(machine, layout)
    design = 0 if layout.design_kind == "A" else 1
    swept = eng.swept_volume(machine, layout)
    disp = eng.displacement_per_rev(params, machine, layout)
    per_rev = eng.cycles_per_rev(params)
    cyc = tr.cycle_summary(machine, cycle, v_min, v_max, per_rev, disp)
    work_rev = cyc["indicated_work_J"]
    if isinstance(cycle, ec.IdealCycle):
        work_cycle = ec.indicated_work(cycle, v_max[:2], v_min[:2])  # kinds A, B
        otto = float(ec.otto_efficiency((eps_a, eps_b)[design], cycle.polytropic_exponent))
    else:
        work_cycle = (cycle.work_of_kind(0), cycle.work_of_kind(1))
        otto = float(ec.otto_efficiency((eps_a, eps_b)[design], 1.4))
    fine = np.linspace(0.0, wc.period(params), _PEAK_SAMPLES)
    state = eng.engine_state(params, machine, cycle, fine)
    omega = shaft_speed(fine, speed, wc.period(params))
    omega_mean = wc.period(params) / np.trapezoid(1.0 / omega[0], fine)  # time average
    dynamics = eng.dynamics_summary(machine, state, fine, omega, omega_mean)
    mm3 = 1e6
    return {
        "pistons_per_rotor": int(machine.pistons_per_rotor),
        "section": machine.section,
        "annulus_volume_cm3": tr.annulus_volume(machine) * mm3,
        "clearance_volume_cm3": float(machine.clearance_volume) * mm3,
        "chamber_volume_max_cm3": float(np.max(v_max)) * mm3,
        "chamber_volume_min_cm3": float(np.min(v_min)) * mm3,
        "chamber_a_volume_min_cm3": float(v_min[0]) * mm3,
        "chamber_a_volume_max_cm3": float(v_max[0]) * mm3,
        "chamber_b_volume_min_cm3": float(v_min[1]) * mm3,
        "chamber_b_volume_max_cm3": float(v_max[1]) * mm3,
        "swept_volume_cm3": swept * mm3,
        "displacement_cm3_per_rev": disp * mm3,
        "equivalent_capacity_cm3": eng.swept_volume_per_rev(params, machine, layout) * mm3,
        "intake_strokes_per_rev": int(round(machine.chambers * eng.cycles_per_rev(params))),
        "chambers_in_power_stroke": machine.pistons_per_rotor // 2,
        "compression_ratio_geometric": (eps_a, eps_b)[design],
        "compression_ratio_geometric_a": eps_a,
        "compression_ratio_geometric_b": eps_b,
        **{k: v for k, v in cyc.items() if k not in ("otto_efficiency",)},
        "indicated_work_per_cycle_a_J": float(work_cycle[0]),
        "indicated_work_per_cycle_b_J": float(work_cycle[1]),
        "otto_efficiency": otto,
        "mean_torque_Nm": work_rev / wc.period(params),
        **{k: float(dynamics[k]) for k in eng.DYNAMICS_KEYS[:7]},
        "indicated_power_kW": work_rev * omega_mean / wc.period(params) / 1e3,
        **{k: float(dynamics[k]) for k in eng.DYNAMICS_KEYS[7:]},
    }


def _engine_columns(params, machine, cycle, speed, theta):
    state = eng.engine_state(params, machine, cycle, theta)
    ch = state.chambers
    omega = shaft_speed(theta, speed, wc.period(params))
    t_in, net, j_eq, ke = eng.dynamics(machine, state, omega[0], omega[1])
    cols, docs = {}, {}

    def add(name, values, doc):
        cols[name] = np.asarray(values, dtype=float)
        docs[name] = doc

    for j, kind in ((0, "a"), (1, "b")):
        add(
            f"chamber_{kind}_volume_cm3",
            ch.volume[j] * 1e6,
            f"Volume of every kind-{kind.upper()} chamber (chambers {j + 1}, {j + 3}, ...), "
            "K delta + V_c.",
        )
    for j, kind in ((0, "a"), (1, "b")):
        add(
            f"chamber_{kind}_dvolume_cm3_per_rad",
            ch.dvolume[j] * 1e6,
            f"dV/dtheta of a kind-{kind.upper()} chamber (exact).",
        )
    for j in range(machine.chambers):
        add(
            f"chamber{j + 1}_stroke",
            state.stroke[j],
            f"Stroke of chamber {j + 1}: 0 intake, 1 compression, 2 power, 3 exhaust.",
        )
    for j in range(machine.chambers):
        kind = "AB"[j % 2]
        add(
            f"chamber{j + 1}_pressure_bar",
            state.pressure[j] / 1e5,
            f"Absolute pressure of chamber {j + 1} (kind {kind}), ideal four-stroke cycle.",
        )
    add(
        "chambers_in_power_stroke",
        np.sum(state.stroke == ec.POWER, axis=0),
        "Number of chambers on the power stroke.",
    )
    for i in (0, 1):
        add(
            f"rotor{i + 1}_gas_torque_Nm",
            state.member_torque[i],
            f"Gas torque on rotor {i + 1}, sum_j p_j dV_j/dPhi_{i + 1}, positive along +Phi.",
        )
    add(
        "shaft_torque_Nm",
        state.shaft_torque,
        "Gas torque on the shaft by virtual work, sum_i M_i dPhi_i/dtheta, without inertia; "
        "positive when it drives the shaft.",
    )
    add(
        "inertia_torque_Nm",
        t_in,
        "Torque the shaft spends on accelerating shaft and rotors at the run speed.",
    )
    add(
        "shaft_torque_with_inertia_Nm",
        net,
        "Shaft torque with inertia: gas torque minus inertia torque (what reaches the load).",
    )
    add(
        "equivalent_inertia_kgm2",
        j_eq,
        "J_eq = J_shaft + J_1 Phi_1'^2 + J_2 Phi_2'^2, inertia seen at the shaft.",
    )
    add("kinetic_energy_J", ke, "Kinetic energy of shaft and rotors, 1/2 J_eq omega^2.")
    tcols, tdocs, tsummary, _ = time_domain(
        ch.motion, speed, ("rotor1", "rotor2"), wc.period(params)
    )
    for name, values in tcols.items():
        add(name, values, tdocs[name][0].upper() + tdocs[name][1:] + ".")
    return cols, docs, tsummary


def _drive(cfg: dict, pistons) -> wc.WobbleCam:
    """The drive's parameters for ``pistons`` per rotor (eq. 20 limits the tilt with them)."""
    d = cfg["drive"]
    return build_params(
        wc.WobbleCam,
        "drive",
        {
            "plate_tilt": d["plate_tilt"],
            "roller_axis_angle": d["roller_axis_angle"],
            "spin_ratio": d["spin_ratio"],
            "sphere_radius": d["sphere_radius"],
            "pistons_per_rotor": pistons,
            "spin_a": tuple(d.get("spin_a", ())),
            "spin_b": tuple(d.get("spin_b", ())),
        },
        aliases={"pistons_per_rotor": "machine.pistons_per_rotor"},
    )


def models(cfg: dict) -> tuple[wc.WobbleCam, tr.TwinRotor, object]:
    """Drive, machine and cycle from a validated config (SI); errors name the keys.

    The cycle is the ideal one (``loads.model = "ideal"``) or the fuel-air cycle integrated
    over the drive's strokes (:func:`rotorkin.machines.fuel_air.charge_cycle`).
    """
    machine = build_params(tr.TwinRotor, "machine", _section(cfg, "machine", tr.TwinRotor))
    params = _drive(cfg, machine.pistons_per_rotor)
    cycle = fa.loads_of(cfg.get("loads") or {})
    if isinstance(cycle, fa.FuelAirLoads):
        cycle = charge_cycle(
            params, machine, cycle, (cfg.get("run") or {}).get("speed", _DEFAULT_SPEED)
        )
    return params, machine, cycle


def charge_cycle(params, machine, loads, speed) -> fa.ChargeCycle:
    """The fuel-air cycle of the engine's chambers on this drive, over one turn."""
    layout = _layout(params, machine)
    per = wc.period(params)
    points = turning_points(RotaryLaw(functools.partial(wc.motion, params), per))
    return fa.charge_cycle(
        machine, loads, lambda t: eng.chambers(params, machine, t, layout),
        lambda t: eng.chamber_stroke_count(params, t), points, per, mean_speed(speed, per),
    )  # fmt: skip


def pairs_of(cfg: dict):
    """``f(theta, drive_torque, motion) -> list[Pair]`` for a machine that is not the engine.

    The torques the drive puts on the rotors stand for the machine's and the rotors'
    inertia together (``M = -D``, no rotor inertia left); the plate's own inertia is taken
    at the run speed.
    """
    drive, cam, fp = fo.from_config(cfg)
    model = pr.ContactModel.from_config(cfg)
    speed = (cfg.get("run") or {}).get("speed", _DEFAULT_SPEED)

    def f(theta, drive_torque, motion):
        omega, omega_dot, _ = shaft_speed(theta, speed, wc.period(drive))
        forces = fo.solve(drive, cam, fp, theta, -np.asarray(drive_torque), (0.0, 0.0), omega,
                          omega_dot)  # fmt: skip
        return fo.pairs(forces, cam, fp, model)

    return f


def law(cfg: dict) -> RotaryLaw:
    """The rotors' motion for any vane machine on this drive (:mod:`rotorkin.vane`).

    The drive's admissible tilt depends on the pistons per rotor (eq. 20); a machine
    without pistons takes the paper's 4.
    """
    params = _drive(cfg, (cfg.get("machine") or {}).get("pistons_per_rotor", 4))
    return RotaryLaw(functools.partial(wc.motion, params), wc.period(params))


def evaluate(cfg: dict) -> StudyResult:
    """Run the twin-rotor engine study on a validated config (SI values).

    Parameters
    ----------
    cfg : dict
        ``cfg["drive"]``: ``plate_tilt`` [rad], ``roller_axis_angle`` [rad],
        ``spin_ratio`` [-], ``sphere_radius`` [m]; ``cfg["machine"]``: the fields of
        :class:`~rotorkin.machines.twin_rotor.TwinRotor`; ``cfg["loads"]``: the
        fields of :class:`~rotorkin.analysis.engine_cycle.IdealCycle`;
        ``cfg["run"]``: ``points``, ``speed`` [rad/s or list].

    Returns
    -------
    StudyResult
        Summary keys: see :data:`HEADLINE` and the docs pages
        ``docs/drives/wobble_cam.md`` and ``docs/machines/twin_rotor.md``.
    """
    params, machine, cycle = models(cfg)
    layout = _layout(params, machine)
    run = cfg.get("run", {})
    speed = run.get("speed", _DEFAULT_SPEED)
    summary = _summary(params, layout)
    summary.update(_engine_summary(params, machine, cycle, layout, speed))
    theta = angle_grid(wc.period(params), run.get("points", 721))
    columns = _columns(params, layout, len(theta))
    docs = dict(_DOCS)
    engine_cols, engine_docs, time_summary = _engine_columns(params, machine, cycle, speed, theta)
    columns.update(engine_cols)
    docs.update(engine_docs)
    summary.update(time_summary)
    force_warnings = ()
    try:
        _, scam = cs.from_config(cfg)
    except ParameterError as exc:  # a shell that does not fit this sphere: no pair forces
        scam = None
        force_warnings = (f"{exc.name} = {exc.value}: {exc.admissible}; the pair forces "
                          "(grooves, rails, bearings, gearbox) are not computed",)  # fmt: skip
    if scam is not None:
        fp = fo.force_params(cfg, scam)
        model = pr.ContactModel.from_config(cfg)
        fine = np.linspace(0.0, wc.period(params), _PEAK_SAMPLES)
        f_fine = _forces(params, scam, fp, machine, cycle, speed, fine)
        p_fine = fo.pairs(f_fine, scam, fp, model)
        omega = shaft_speed(fine, speed, wc.period(params))[0]
        summary.update(pr.summary(p_fine, fine, summary["indicated_work_J"], model, omega))
        summary.update(fo.summary(f_fine, p_fine, model, cs.guided(params, scam, fine)))
        f_cols = _forces(params, scam, fp, machine, cycle, speed, theta)
        p_cols = fo.pairs(f_cols, scam, fp, model)
        gas = eng.engine_state(params, machine, cycle, theta).shaft_torque
        for c, d in (pr.columns(p_cols, model, gas), fo.columns(f_cols)):
            columns.update(c)
            docs.update(d)
    summary = {k: v.item() if isinstance(v, np.generic) else v for k, v in summary.items()}

    def plot(outdir: Path) -> list[Path]:
        outdir = Path(outdir)
        tasks = figures_wobble_cam.figure_tasks(params, layout, outdir, machine=machine,
                                                cycle=cycle, speed=speed)  # fmt: skip
        if scam is not None:
            tasks.append(functools.partial(figures_wobble_cam.fig_forces, f_cols, p_cols, fp,
                                           model, outdir))  # fmt: skip
        if "cam" in cfg:  # the cam's own figure, when its roller fits the grooves
            tasks.append(functools.partial(_cam_figure, cfg, outdir))
        # longest first (measured): the cam, the forces, the four strokes, Fig. 9, Fig. 8
        n = len(tasks)
        return draw(tasks, slowest=(n - 1, n - 2, 7, 1, 0, 6, 3, 5, 4, 2))

    return StudyResult(
        drive_type="wobble_cam",
        title="Twin-rotor engine, wobble plate + spherical cam",
        summary=summary,
        columns=columns,
        column_docs=docs,
        headline={k: v for k, v in HEADLINE.items() if k in summary},
        write_figures=plot,
        motion=wc.motion(params, theta),
        warnings=(*_warnings(cycle, summary), *_cam_warnings(cfg), *force_warnings),
    )


def _cam_figure(cfg: dict, outdir: Path) -> list[Path]:
    """The spherical cam's figure, or a warning line when its roller does not fit."""
    try:
        return figures_spherical_cam.plot_spherical_cam(cfg, outdir)
    except ParameterError as exc:
        print(f"rotorkin: warning: spherical cam figure not drawn: {exc}", file=sys.stderr)
        return []


def _forces(params, scam, fp, machine, cycle, speed, theta) -> fo.Forces:
    """Pair forces at the angles, from the gas torques on the rotors and the run speed."""
    state = eng.engine_state(params, machine, cycle, theta)
    omega, omega_dot, _ = shaft_speed(theta, speed, wc.period(params))
    return fo.solve(params, scam, fp, theta, state.member_torque, machine.member_inertias,
                    omega, omega_dot)  # fmt: skip


def _cam_warnings(cfg: dict) -> tuple[str, ...]:
    """A roller that ``rotorkin export`` would refuse, said in one line (the motion stands).

    The grooves' undercut limit depends on the plate tilt; the default 4 mm roller fits
    near the paper's 45 deg only, so the analysis of other tilts is not refused for it.
    """
    if "cam" not in cfg:
        return ()
    try:
        cs.check_roller_radius(*cs.from_config(cfg))
    except ParameterError as exc:
        key = exc.name if "." in exc.name else f"cam.{exc.name}"
        return (f"{key} = {exc.value} undercuts the grooves: {exc.admissible}; "
                "rotorkin export will refuse this cam",)  # fmt: skip
    return ()


def _warnings(cycle, summary: dict) -> tuple[str, ...]:
    """Inputs that leave summary numbers without meaning, one line each."""
    out = []
    if getattr(cycle, "heat_per_cycle", None) == 0.0:
        out.append(
            "loads.heat_per_cycle = 0: no heat is added, so the indicated work, mean torque "
            "and power are those of a motored engine (about 0)"
        )
    because = {"indicated_efficiency": "no heat is added (loads.heat_per_cycle = 0)"}
    return (*out, *undefined_warnings(summary, because))
