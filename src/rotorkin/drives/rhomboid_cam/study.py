"""Study of the rotary-blade engine with the rhomboid lever-cam converter (Zhuravlev et al. 2012).

Config keys (SI, defaults filled by :mod:`rotorkin.io.config`; keys missing from a
hand-built ``cfg`` take the same defaults):

* ``drive.link_length`` [m], ``drive.psi_min`` [rad], ``drive.a``, ``drive.b``
  (higher harmonics a3, a5, ... and b3, b5, ... [rad]);
* ``machine.*``: the rotary-blade engine (:class:`rotorkin.machines.rotary_blade.RotaryBlade`)
  and ``machine.speed_fluctuation`` for the flywheel;
* ``loads.torque_high``, ``loads.torque_low`` [N m] (the paper's linear model, eq. 29),
  ``loads.pressure_model`` (``"linear"``, ``"adiabatic"``, ``"schmidt"`` or
  ``"isothermal"``), ``loads.charge_pressure`` [Pa], ``loads.hot_temperature``,
  ``loads.cold_temperature`` [K] and, for the Stirling models (a cold blade set lagging
  the engine's, :mod:`rotorkin.machines.rotary_blade`), ``loads.gas``,
  ``loads.phase_angle``, the heat exchangers' volumes and
  ``loads.regenerator_effectiveness``;
* ``run.points``, ``run.speed`` [rad/s] (constant or a profile over one period, pi);
* ``cam.roller_radius`` [m] and ``contact.*`` for the forces in the converter's pairs
  (:mod:`rotorkin.drives.rhomboid_cam.forces`).

The linear torque model (eq. 29) is defined for ``psi_min <= psi <= psi_max`` (eq. 2)
only: a law whose higher harmonics take psi outside is refused with it. The gas
models run such a law (its torques follow the chamber volumes over the law's own swing,
which the blades must fit); the summary keys of the paper's linear model are then
left undefined.

The drive's outputs (psi law, cam, the paper's indicator work per *half* turn
``indicator_work_J``) are kept as they were; the machine adds chamber volumes,
pressures, member and shaft torques, inertia and flywheel, with work per output-shaft
*revolution* in ``indicated_work_J``.
"""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np

from rotorkin.analysis import pairs as ap
from rotorkin.analysis import torque as at
from rotorkin.core.errors import ParameterError
from rotorkin.core.schema import ContactSection
from rotorkin.drives.rhomboid_cam import engine
from rotorkin.drives.rhomboid_cam import figures as figures_rhomboid_cam
from rotorkin.drives.rhomboid_cam import forces as rf
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.drives.rhomboid_cam import summary as rs
from rotorkin.drives.rhomboid_cam.engine import Loads, State, machine_state
from rotorkin.drives.rhomboid_cam.schema import with_defaults
from rotorkin.machines import rotary_blade as rb
from rotorkin.machines import rotary_blade_stirling as rbs
from rotorkin.render.figures import draw
from rotorkin.studies import StudyResult
from rotorkin.studies.helpers import angle_grid, build_params, time_domain, undefined_warnings
from rotorkin.vane import RotaryLaw

__all__ = [
    "evaluate",
    "drive_params",
    "HEADLINE",
    "Loads",
    "State",
    "machine_state",
    "indicated_work_per_period",
]

#: Summary keys printed by the command line, in order, with what each means (one line).
HEADLINE = {
    "psi_min_deg": "smallest angle psi between the blade axes",
    "psi_max_deg": "largest angle psi between the blade axes, pi - psi_min",
    "profile_radius_min_mm": "smallest radius of the cam pitch curve",
    "profile_radius_max_mm": "largest radius of the cam pitch curve",
    "indicator_work_J": "paper's linear torque model (eq. 31): work per period (half turn)",
    "mean_shaft_torque_Nm": "paper's linear torque model: mean output-shaft torque",
    "blade_accel_coeff_max": "max |d2 phi_1 / d alpha2| of a blade pair",
    "psi_monotone": "true if psi rises and falls once per period",
    "pressure_model": "model of the machine keys below: linear, adiabatic, schmidt, isothermal",
    "compression_ratio_geometric": "V_max / V_min of a chamber",
    "displacement_cm3_per_rev": "swept volume of all chambers per output turn",
    "indicated_work_J": "pressure model above: work per output-shaft turn",
    "mean_torque_Nm": "pressure model above: mean output-shaft torque",
    "torque_ripple": "pressure model above: (max - min) / mean shaft torque",
    "flywheel_inertia_kgm2": "flywheel for the chosen coefficient of speed fluctuation",
    "peak_contact_force_N": "largest roller force on the cam, at the run speed",
    "peak_contact_stress_MPa": "largest Hertz pressure of a roller on the cam",
    "contact_safety_factor": "contact.allowable_stress over the largest Hertz pressure",
    "peak_bearing_load_N": "largest load on a pin or bearing of the linkage",
    "peak_link_force_N": "largest axial force (tension or compression) in a rhombus link",
    "peak_guide_force_N": "largest force of a vertex block on the shaft's guide",
    "friction_loss_W": "power lost to friction in the converter at the run speed",
    "mechanical_efficiency": "work delivered over indicated work, converter friction included",
}

#: Samples per period used for the peaks of the kinematic coefficients (independent of run.points).
_PEAK_SAMPLES = 20_001


def _deg(x) -> float:
    return float(np.degrees(x))


def _plain(value):
    """A summary value as a plain Python bool, int or float (for ``summary.json``)."""
    value = np.asarray(value).item()
    return value if isinstance(value, bool | int) else float(value)


def _summary(params, m1, m2) -> dict:
    law = (params.psi_min, params.a, params.b)
    L = params.link_length
    fine = np.linspace(0.0, rc.period(params), _PEAK_SAMPLES)
    s = rs.law_summary(L, *law, m1, m2)
    s.update(rs.peak_summary(rc.law_peaks(L, *law, fine)))
    return {k: _plain(s[k]) for k in rs.LAW_KEYS}


_DOCS = {
    "alpha_deg": "Output-shaft angle alpha: polar angle of diagonal OA, from +x counter-clockwise.",
    "psi_deg": "Angle between the blade axes psi = phi_1 - phi_2 (eq. 13).",
    "dpsi": "dpsi/dalpha (eq. 14).",
    "d2psi_per_rad": "d2psi/dalpha2.",
    "d3psi_per_rad2": "d3psi/dalpha3.",
    "phi1_deg": "Blade pair 1 angle phi_1 = alpha + psi/2 from +x (eq. 21).",
    "phi2_deg": "Blade pair 2 angle phi_2 = alpha - psi/2 from +x (eq. 21).",
    "phi1_speed_coeff": "dphi_1/dalpha = 1 + psi'/2, blade pair 1 speed over shaft speed (eq. 22).",
    "phi2_speed_coeff": "dphi_2/dalpha = 1 - psi'/2, blade pair 2 speed over shaft speed (eq. 22).",
    "phi1_accel_per_rad": "d2phi_1/dalpha2 = psi''/2.",
    "phi2_accel_per_rad": "d2phi_2/dalpha2 = -psi''/2.",
    "phi1_jerk_per_rad2": "d3phi_1/dalpha3 = psi'''/2.",
    "phi2_jerk_per_rad2": "d3phi_2/dalpha3 = -psi'''/2.",
    "rho_mm": "Cam pitch-curve polar radius rho = OA = 2l cos(psi/2) at polar angle alpha (eq. 3).",
    "drho_mm_per_rad": "drho/dalpha.",
    "x_mm": "Pitch-curve point x = rho cos(alpha) (roller A centre).",
    "y_mm": "Pitch-curve point y = rho sin(alpha) (roller A centre).",
    "rho_b_mm": "Half-diagonal OB = 2l sin(psi/2) (eq. 4), = rho at alpha + 90 deg (eq. 10).",
    "curvature_per_m": "Signed curvature of the pitch curve at A (negative where concave).",
    "stroke": "+1 expansion (psi rising, M_p), -1 compression (psi falling, M_c).",
    "blade_torque_Nm": "Torque M_1 on blade pair 1 from the linear model of eq. 29 (M_2 = -M_1).",
    "dA_dalpha_J_per_rad": "Work rate M_1 psi' = torque driving the output shaft (eq. 24).",
}


def _columns(params, m1, m2, points) -> dict:
    law = (params.psi_min, params.a, params.b)
    L = params.link_length
    alpha = angle_grid(rc.period(params), points)
    psi, d1 = rc.psi_law(*law, alpha)[:2]
    _, p1, p2, p3 = rc.blade_angles(*law, alpha)
    drho = rc.profile_radius(L, *law, alpha)[1]
    xy = rc.profile_point(L, *law, alpha)[0]
    stroke = rc.stroke_direction(*law, alpha)
    torque = rc.blade_torque(m1, m2, params.psi_min, psi, stroke)
    law_cols = rs.law_curves(L, *law, alpha)
    cols = {"alpha_deg": np.degrees(alpha)}
    cols.update({k: law_cols[k] for k in rs.CURVE_KEYS[:6]})
    for name, arr in (("speed_coeff", p1), ("accel_per_rad", p2), ("jerk_per_rad2", p3)):
        for k in (0, 1):
            cols[f"phi{k + 1}_{name}"] = arr[k]
    cols["rho_mm"] = law_cols["rho_mm"]
    cols["drho_mm_per_rad"] = drho * 1e3
    cols["x_mm"] = xy[0] * 1e3
    cols["y_mm"] = xy[1] * 1e3
    cols["rho_b_mm"] = rc.profile_radius_eq19(L, *law, alpha) * 1e3
    cols["curvature_per_m"] = law_cols["curvature_per_m"]
    cols["stroke"] = stroke
    cols["blade_torque_Nm"] = torque
    cols["dA_dalpha_J_per_rad"] = torque * d1
    return cols


# --- the machine --------------------------------------------------------------------------
def indicated_work_per_period(params, machine, loads: Loads, nodes: int = 64) -> float:
    """Work of the loads on the output shaft over one period ``0 <= alpha <= pi`` [J].

    ``integral_0^pi T d alpha`` with ``T`` from :func:`machine_state`, split at the
    stationary points of ``psi`` (where the stroke, and so the model, switches) and
    integrated by Gauss-Legendre on each smooth piece (exact to rounding for the
    linear model, ~1e-15 relative for the isothermal one). The Stirling models give the
    work of their solved cycles, ``sum W_c + W_e`` over the circuits.
    """
    if loads.stirling is not None:
        return float(np.sum(loads.stirling.cycle.work))
    law = (params.psi_min, params.a, params.b)
    z = rc.psi_stationary_points(*law)
    x, w = np.polynomial.legendre.leggauss(int(nodes))
    half = 0.5 * (z[1:] - z[:-1])[:, None]
    al = 0.5 * (z[1:] + z[:-1])[:, None] + half * x
    s = np.sign(np.diff(rc.psi_law(*law, z)[0]))[:, None] * np.ones_like(al)
    return float(np.sum(machine_state(params, machine, loads, al, s).torque * w * half))


def _inertia_torque(machine, mo, omega):
    """Torque the shaft spends on the inertia of shaft and blade pairs [N m]."""
    J = machine.member_inertias
    return at.inertia_torque(machine.inertia_shaft, J, mo.dq, mo.d2q, omega[0], omega[1])


def _cm3(v) -> float:
    return float(v) * 1e6


def _machine_setup(cfg, params):
    m = cfg.get("machine", {})
    keys = ("blade_thickness", "inner_radius", "outer_radius", "axial_width", "blades_per_pair",
            "inertia_shaft", "inertia_blade_pair_1", "inertia_blade_pair_2")  # fmt: skip
    machine = build_params(rb.RotaryBlade, "machine", {k: m[k] for k in keys})
    lo, _, hi, _ = rc.psi_extremes(params.psi_min, params.a, params.b)
    try:  # the blades must fit the drive's swing of psi
        rb.check_swing(machine, lo, hi)
    except ParameterError as exc:
        raise ParameterError(f"machine.{exc.name}", exc.value, exc.admissible) from None
    ld = cfg["loads"]
    v_min, v_max = rb.volume_range(machine, lo, hi)
    model = ld["pressure_model"]
    if model in ("adiabatic", "schmidt"):
        keys = [f for f in rbs.STIRLING_CHECKS if f in ld]
        gas = build_params(rbs.StirlingLoads, "loads", {k: ld[k] for k in keys})
        turning = len(rc.psi_stationary_points(params.psi_min, params.a, params.b)) - 1
        sol = rbs.stirling_solution(machine, gas, functools.partial(rc.motion, params),
                                   rc.period(params), turning // 2,
                                   float(np.max(v_max - v_min)))  # fmt: skip
        loads = Loads(model, ld["torque_high"], ld["torque_low"], gas, None, sol)
    elif model == "isothermal":
        gas = build_params(
            rb.IsothermalGas,
            "loads",
            {k: ld[k] for k in ("charge_pressure", "hot_temperature", "cold_temperature")},
        )
        loads = Loads("isothermal", ld["torque_high"], ld["torque_low"], gas,
                      rb.gas_charge(gas, v_max))  # fmt: skip
    else:
        loads = Loads("linear", float(ld["torque_high"]), float(ld["torque_low"]))
    return machine, loads, (lo, hi, v_min, v_max)


def _pairs(params, machine, forces_cfg, alpha, st, drive_torque):
    """The converter's pairs and forces at ``alpha`` (:func:`~.forces.machine_pairs`)."""
    return rf.machine_pairs(params, machine, alpha, st.members, drive_torque,
                            forces_cfg["roller_radius"], forces_cfg["bearing_radius"])  # fmt: skip


def _force_columns(fo, alpha) -> tuple[dict, dict]:
    cols, docs = {}, {}
    for j, name in enumerate(rf.LINKS):
        t = fo.tension[j]
        key = f"link_{name.lower()}_axial_N"
        cols[key] = np.where(np.abs(t[0]) >= np.abs(t[1]), t[0], t[1])
        docs[key] = (f"Axial force of link {name} (tension +), in its more loaded half (the "
                     "halves differ by the blade arm's force along the link).")  # fmt: skip
    for k, v in enumerate("ABCD"):
        key = f"guide_{v.lower()}_tangential_N"
        cols[key] = fo.guide[k]
        docs[key] = (f"Force of the shaft's guide on vertex block {v}, along the shaft's "
                     "rotation (+: the shaft drives the rhombus, -: the rhombus drives "
                     "it).")  # fmt: skip
    cols["roller_pair_loaded"] = fo.loaded.astype(float)
    docs["roller_pair_loaded"] = "0: rollers A and C carry the load, 1: rollers B and D."
    cols["converter_shaft_torque_Nm"] = fo.shaft_torque
    docs["converter_shaft_torque_Nm"] = (
        "Torque the guides put on the output shaft, -sum rho_k G_k: the machine's torque less "
        "the blade pairs' inertia torque (shaft_torque_Nm less their part of inertia_torque_Nm)."
    )
    return cols, docs


def _machine_summary(params, machine, loads, extremes, speed, coefficient,
                     forces_cfg) -> tuple[dict, dict]:  # fmt: skip
    """Engine summary on a fine grid over one period, and the curves the figures draw."""
    law = (params.psi_min, params.a, params.b)
    lo, hi, _, _ = extremes
    period = rc.period(params)
    alpha = np.linspace(0.0, period, _PEAK_SAMPLES)
    st = machine_state(params, machine, loads, alpha)
    mo = st.motion
    _, _, td_summary, omega = time_domain(mo, speed, _SLUGS, period)
    work_period = indicated_work_per_period(params, machine, loads)
    revs = 2.0 * np.pi / period  # periods per output-shaft revolution
    dyn, curves = rs.dynamics_summary(machine, alpha, mo, st.members, st.torque, omega,
                                      coefficient, work_period)  # fmt: skip
    work_rev = float(dyn["indicated_work_J"])
    drive_torque = engine.drive_torque(machine, st, omega)
    pairs, fo = _pairs(params, machine, forces_cfg, alpha, st, drive_torque)
    force_summary = {
        **ap.summary(pairs, alpha, work_rev, forces_cfg["model"], omega[0]),
        **{k: float(v) for k, v in rf.force_summary(fo).items()},
    }
    geometry = rs.engine_geometry_summary(machine, lo, hi, revs * rc.psi_total_variation(*law))
    s = {
        "pressure_model": loads.model,
        **{k: _plain(v) for k, v in geometry.items()},
        **{k: float(v) for k, v in dyn.items()},
    }
    if loads.stirling is not None:
        s.update(rbs.stirling_summary(loads.stirling, revs))
        s["displacement_cm3_per_rev"] = 2.0 * s["displacement_cm3_per_rev"]  # both sets
        s["indicated_work_J"] = work_rev
        s["pressure_max_bar"] = float(np.max(st.pressure)) * 1e-5
        s["pressure_min_bar"] = float(np.min(st.pressure)) * 1e-5
    if loads.model == "isothermal":
        z = rc.psi_stationary_points(*law)
        v_turns = rb.chamber_volumes(machine, rc.blade_angles(*law, z)[0])
        closed = rb.isothermal_cycle_work(loads.gas, loads.charge, v_turns)
        s["isothermal_work_closed_form_per_rev_J"] = float(revs * np.sum(closed))
        s["gas_charge_J_per_K"] = float(np.sum(loads.charge))
        s["pressure_max_bar"] = float(np.max(st.pressure)) * 1e-5
        s["pressure_min_bar"] = float(np.min(st.pressure)) * 1e-5
        s["charge_pressure_bar"] = loads.gas.charge_pressure * 1e-5
        s["hot_temperature_K"] = loads.gas.hot_temperature
        s["cold_temperature_K"] = loads.gas.cold_temperature
    s.update(td_summary)
    s.update(force_summary)
    return s, {"alpha": alpha, "forces": fo, "pairs": pairs, "contact": forces_cfg["model"],
               "state": st, "inertia_torque": curves["inertia_torque"],
               "steady": curves["steady"], "equivalent_inertia": curves["equivalent_inertia"],
               "omega_mean": float(curves["omega_mean"]), "work_rev": work_rev,
               "energy_fluctuation": s["energy_fluctuation_J"],
               "flywheel": s["flywheel_inertia_kgm2"]}  # fmt: skip


_SLUGS = rs.SLUGS


def _machine_columns(params, machine, loads, points, speed, forces_cfg):
    period = rc.period(params)
    alpha = angle_grid(period, points)
    st = machine_state(params, machine, loads, alpha)
    mo = st.motion
    cols, docs, _, omega = time_domain(mo, speed, _SLUGS, period)
    J = machine.member_inertias
    t_inertia = _inertia_torque(machine, mo, omega)
    out, out_docs = {}, {}
    for j in range(machine.chambers):
        kind = "psi - t" if j % 2 == 0 else "2 pi/B - psi - t"
        c = f"chamber{j + 1}"
        out[f"{c}_volume_cm3"] = st.volume[j] * 1e6
        out_docs[f"{c}_volume_cm3"] = f"Volume of chamber {j + 1} (angle {kind})."
        out[f"{c}_dvolume_cm3_per_rad"] = st.dvolume[j] * 1e6
        out_docs[f"{c}_dvolume_cm3_per_rad"] = f"dV/dalpha of chamber {j + 1} (exact)."
        if st.pressure is not None:
            out[f"{c}_pressure_bar"] = st.pressure[j] * 1e-5
            out_docs[f"{c}_pressure_bar"] = (
                f"Absolute gas pressure in chamber {j + 1}, isothermal model "
                "(hot while it expands, cold while it is compressed)."
                if loads.stirling is None
                else f"Absolute gas pressure in circuit {j + 1} (hot chamber {j + 1}, cold "
                f"chamber {j + 1} and their heat exchangers), {loads.model} model."
            )
        if st.cold_volume is not None:
            out[f"cold_{c}_volume_cm3"] = st.cold_volume[j] * 1e6
            out_docs[f"cold_{c}_volume_cm3"] = (
                f"Volume of chamber {j + 1} of the cold blade set (the engine's chamber "
                f"{j + 1} {np.degrees(loads.stirling.lag):.6g} deg of shaft angle earlier)."
            )
    for i in (0, 1):
        key = f"blade_pair_{i + 1}_torque_Nm"
        out[key] = st.members[i]
        out_docs[key] = (
            f"Torque of the loads ({loads.model} model) on blade pair {i + 1}, "
            f"positive counter-clockwise (increasing phi_{i + 1})."
        )
    out["shaft_torque_Nm"] = st.torque
    out_docs["shaft_torque_Nm"] = (
        "Torque of the loads on the output shaft by virtual work, sum M_i phi_i' "
        "(positive: drives the shaft), without inertia."
    )
    out["inertia_torque_Nm"] = t_inertia
    out_docs["inertia_torque_Nm"] = (
        "Torque the shaft spends on the inertia of shaft and blade pairs at the shaft speed "
        "of shaft_speed_rpm (positive: the shaft gives energy to them)."
    )
    out["shaft_torque_with_inertia_Nm"] = st.torque - t_inertia
    out_docs["shaft_torque_with_inertia_Nm"] = (
        "shaft_torque_Nm - inertia_torque_Nm: torque left to drive the load."
    )
    out["equivalent_inertia_kgm2"] = at.equivalent_inertia(machine.inertia_shaft, J, mo.dq)
    out_docs["equivalent_inertia_kgm2"] = "J_eq = J_shaft + J_1 phi_1'^2 + J_2 phi_2'^2."
    drive_torque = engine.drive_torque(machine, st, omega)
    for i in (0, 1):
        key = f"blade_pair_{i + 1}_drive_torque_Nm"
        out[key] = drive_torque[i]
        out_docs[key] = (
            f"Torque the converter must put on blade pair {i + 1} at the run speed, "
            f"D = J qdd - M (counter-clockwise +): what its pairs carry."
        )
    pairs, fo = _pairs(params, machine, forces_cfg, alpha, st, drive_torque)
    pcols, pdocs = ap.columns(pairs, forces_cfg["model"], st.torque)
    fcols, fdocs = _force_columns(fo, alpha)
    out.update(pcols)
    out_docs.update(pdocs)
    out.update(fcols)
    out_docs.update(fdocs)
    out.update(cols)
    out_docs.update(docs)
    return out, out_docs


def drive_params(cfg: dict) -> rc.RhomboidCam:
    """The drive's parameters from a validated config (SI); errors name the config keys."""
    d = cfg["drive"]
    params = build_params(
        rc.RhomboidCam,
        "drive",
        {
            "link_length": d["link_length"],
            "psi_min": d["psi_min"],
            "a": tuple(d.get("a", ())),
            "b": tuple(d.get("b", ())),
        },
    )
    return params


def pairs_of(cfg: dict):
    """``f(alpha, drive_torque, motion) -> list[Pair]`` for a machine that is not its own."""
    params = drive_params(cfg)
    roller = rf.check_roller(float((cfg.get("cam") or {}).get("roller_radius", 0.01)))
    radius = float({**ContactSection().model_dump(), **(cfg.get("contact") or {})}
                   ["bearing_radius"])  # fmt: skip

    def f(alpha, drive_torque, motion):
        return rf.pairs(params, alpha, drive_torque, roller, radius)

    return f


def law(cfg: dict) -> RotaryLaw:
    """The two members' motion for any vane machine on this drive (:mod:`rotorkin.vane`)."""
    params = drive_params(cfg)
    return RotaryLaw(functools.partial(rc.motion, params), rc.period(params))


def evaluate(cfg: dict) -> StudyResult:
    """Run the rotary-blade engine study on a validated config (SI values).

    Parameters
    ----------
    cfg : dict
        ``cfg["drive"]``: ``link_length`` [m], ``psi_min`` [rad], ``a``, ``b``
        (lists [rad]); ``cfg["machine"]``, ``cfg["loads"]``, ``cfg["run"]`` as in the
        module docstring (missing keys take the config defaults).

    Returns
    -------
    StudyResult
        Summary keys: see :data:`HEADLINE`, ``docs/drives/rhomboid_cam.md`` and
        ``docs/machines/rotary_blade.md``.
    """
    cfg = with_defaults(cfg)
    params = drive_params(cfg)
    outside = check_linear_range(cfg, params)
    forces_cfg = {
        "roller_radius": rf.check_roller(cfg["cam"]["roller_radius"]),
        "bearing_radius": float(cfg["contact"]["bearing_radius"]),
        "model": ap.ContactModel.from_config(cfg),
    }
    m1 = float(cfg["loads"]["torque_high"])
    m2 = float(cfg["loads"]["torque_low"])
    machine, loads, extremes = _machine_setup(cfg, params)
    speed = cfg["run"]["speed"]
    summary = _summary(params, m1, m2)
    if outside:
        summary.update({k: float("nan") for k in _LINEAR_KEYS})
    msum, curves = _machine_summary(
        params, machine, loads, extremes, speed, cfg["machine"]["speed_fluctuation"], forces_cfg
    )
    summary.update(msum)
    columns = _columns(params, m1, m2, cfg["run"]["points"])
    docs = dict(_DOCS)
    mcols, mdocs = _machine_columns(params, machine, loads, cfg["run"]["points"], speed,
                                    forces_cfg)  # fmt: skip
    columns.update(mcols)
    docs.update(mdocs)

    state = functools.partial(machine_state, params, machine, loads)  # pickles (drawn ahead)

    def plot(outdir: Path) -> list[Path]:
        outdir = Path(outdir)
        return draw([
            *figures_rhomboid_cam.figure_tasks(params, m1, m2, outdir),
            *figures_rhomboid_cam.machine_tasks(params, machine, loads, state, curves, summary,
                                                outdir),
        ])  # fmt: skip

    return StudyResult(
        drive_type="rhomboid_cam",
        title=f"Rotary-blade engine ({loads.model} loads), rhomboid lever-cam converter",
        summary=summary,
        columns=columns,
        column_docs=docs,
        headline=HEADLINE,
        write_figures=plot,
        motion=rc.motion(params, angle_grid(rc.period(params), cfg["run"]["points"])),
        warnings=_warnings(loads, summary, outside),
    )


#: Summary keys of the paper's linear torque model, undefined where psi leaves its range.
_LINEAR_KEYS = ("indicator_work_J", "indicator_work_closed_form_J", "mean_shaft_torque_Nm")


def check_linear_range(cfg: dict, params) -> str:
    """Refuse a law leaving ``psi_min <= psi <= psi_max`` under the linear torque model (eq. 2).

    Raises :class:`ParameterError` named ``drive.a`` (or ``drive.b``) for the linear model.
    For the isothermal model returns the config key of the harmonics when the law leaves
    the range (the linear model's keys are then undefined), else ``""``.
    """
    law = (params.psi_min, params.a, params.b)
    if not rc.psi_range_violation(*law):
        return ""
    key = "drive.a" if params.a else "drive.b"
    if cfg["loads"]["pressure_model"] == "linear":
        try:
            rc.check_psi_range(*law)
        except ParameterError as exc:
            raise ParameterError(key, exc.value, exc.admissible) from None
    return key


def _warnings(loads, summary: dict, outside: str = "") -> tuple[str, ...]:
    """Inputs that leave summary numbers without meaning, one line each."""
    out = []
    because = {}
    if outside:
        because = {
            k: f"{outside} takes psi outside psi_min ... psi_max, where the paper's linear "
            "torque model (eq. 29) is defined; the gas model's keys stand"
            for k in _LINEAR_KEYS
        }
    if loads.model == "linear" and loads.torque_high == loads.torque_low:
        out.append(
            "loads.torque_high = loads.torque_low: the linear blade model does no work, so the "
            "indicated work and mean torque are 0"
        )
    return (*out, *undefined_warnings(summary, because))
