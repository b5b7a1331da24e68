"""Sweep kernel of the wobble-cam twin-rotor engine: many designs at once, by broadcasting.

The same quantities as :mod:`rotorkin.drives.wobble_cam.study` (summary keys of the
same names), computed for arrays of designs:

* closed forms per design (eq. 17, 20, 21-23 of Chen Hu et al. 2015; the
  machine's volumes and ideal cycle): slider and chamber angle extremes,
  piston width, eq. 20 tilt limit, compression ratios, volumes, displacement,
  pressures, work;
* sampled peaks: the acceleration and jerk coefficients of both rotors are
  evaluated on ``samples`` shaft angles per design (a design x angle array, in
  blocks) and reduced to their peaks, as the study does on its 20001-point grid,
  by the library's own fused kinematics
  (:func:`rotorkin.drives.wobble_cam.fast.rotor_extremes`: the closed forms of
  :func:`~rotorkin.drives.wobble_cam.fast.rotor_kinematics` for designs x angles,
  reduced as they are evaluated): the same functions as the study, for either spin law.
* on request (:data:`SAMPLED_METRICS`, ``--metrics``; the sweep benchmark's
  workload): every kinematic curve per design and sampled angle -- both rotor
  angles and their three derivatives, the slider angle, the chamber angles of
  both kinds and their volumes -- reduced to extremes and peaks. The closed
  forms above give the same extremes exactly; the sampled ones agree with them
  to the sampling error (tested), and equal the extremes of the study's columns
  when the grids are the same.

The closed forms are the drive's and the machine's broadcasting functions
(:mod:`rotorkin.drives.wobble_cam.kinematics`, :mod:`rotorkin.drives.wobble_cam.chambers`,
:mod:`rotorkin.machines.twin_rotor`) called with arrays of designs; admissibility is
their vectorised ``violation`` functions.
"""

from __future__ import annotations

import contextlib
from dataclasses import fields

import numpy as np

from rotorkin.analysis import engine_cycle as ec
from rotorkin.analysis.timing import shaft_speed
from rotorkin.core.batch import (
    Designs,
    block_progress,
    distinct,
    flag,
    full,
    run_blocks,
    sample_grid,
)
from rotorkin.drives.wobble_cam import cam as cs
from rotorkin.drives.wobble_cam import chambers as wch
from rotorkin.drives.wobble_cam import forces as fo
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.drives.wobble_cam import sweep_forces as swf
from rotorkin.drives.wobble_cam.fast import rotor_extremes
from rotorkin.drives.wobble_cam.sweep_cycle import fuel_air_cycle
from rotorkin.machines import fuel_air as fa
from rotorkin.machines import twin_rotor as tr

__all__ = ["DRIVE", "KEYS", "CURVES", "ANGLE", "SAMPLED_METRICS", "optional_metrics",
           "unsupported", "metric_names", "reasons", "metrics", "curves", "period"]  # fmt: skip

DRIVE = "wobble_cam"

#: Config keys the kernel reads per design (any other swept key: scalar fallback).
KEYS = frozenset(
    {
        "drive.plate_tilt",
        "drive.roller_axis_angle",
        "drive.spin_ratio",
        "drive.sphere_radius",
        "machine.compression_ratio",
        "machine.pistons_per_rotor",
        "machine.section",
        "machine.inner_radius",
        "machine.outer_radius",
        "machine.axial_width",
        "machine.mean_radius",
        "machine.section_diameter",
        "machine.clearance_volume",
        "loads.ambient_pressure",
        "loads.polytropic_exponent",
        "loads.heat_per_cycle",
    }
)

_DRIVE_METRICS = (
    "slider_angle_max_deg",
    "slider_angle_min_deg",
    "chamber_angle_max_deg",
    "chamber_angle_min_deg",
    "chamber_swing_deg",
    "piston_width_deg",
    "volume_cycles_per_rev",
    "power_strokes_per_rev",
    "max_plate_tilt_deg",
    "piston_offset_gamma_deg",
    "chambers",
    "compression_ratio",
    "min_compression_ratio",
    "chamber_a_angle_min_deg",
    "chamber_a_angle_max_deg",
    "chamber_b_angle_min_deg",
    "chamber_b_angle_max_deg",
    "compression_ratio_a",
    "compression_ratio_b",
    "volume_cycles_per_rev_all_chambers",
    "rotor_mean_speed_ratio",
    "rotor_speed_ratio_min",
    "rotor_speed_ratio_max",
    "rotor_accel_peak_per_rad",
    "rotor_jerk_peak_per_rad2",
)
_MACHINE_METRICS = (
    "pistons_per_rotor",
    "annulus_volume_cm3",
    "clearance_volume_cm3",
    "chamber_volume_max_cm3",
    "chamber_volume_min_cm3",
    "chamber_a_volume_min_cm3",
    "chamber_a_volume_max_cm3",
    "chamber_b_volume_min_cm3",
    "chamber_b_volume_max_cm3",
    "swept_volume_cm3",
    "displacement_cm3_per_rev",
    "equivalent_capacity_cm3",
    "intake_strokes_per_rev",
    "chambers_in_power_stroke",
    "compression_ratio_geometric",
    "compression_ratio_geometric_a",
    "compression_ratio_geometric_b",
    "compression_end_pressure_bar",
    "peak_pressure_bar",
    "indicated_work_per_cycle_a_J",
    "indicated_work_per_cycle_b_J",
    "indicated_work_J",
    "heat_added_J_per_rev",
    "indicated_efficiency",
    "otto_efficiency",
    "imep_bar",
    "mean_torque_Nm",
    "indicated_power_kW",
)

#: Extremes reduced from every curve evaluated on the sampled grid (opt-in: not in the
#: default metrics; the closed forms give the exact values of the first ten).
SAMPLED_METRICS = (
    "sampled_slider_angle_min_deg",
    "sampled_slider_angle_max_deg",
    "sampled_chamber_a_angle_min_deg",
    "sampled_chamber_a_angle_max_deg",
    "sampled_chamber_b_angle_min_deg",
    "sampled_chamber_b_angle_max_deg",
    "sampled_chamber_a_volume_min_cm3",
    "sampled_chamber_a_volume_max_cm3",
    "sampled_chamber_b_volume_min_cm3",
    "sampled_chamber_b_volume_max_cm3",
    "sampled_rotor_speed_ratio_min",
    "sampled_rotor_speed_ratio_max",
)


def optional_metrics(cfg: dict) -> tuple[str, ...]:
    """Metrics the kernel computes on request only (``--metrics``), not by default: the
    sampled extremes and, with the ideal cycle, the engine's dynamics and the pairs' forces
    (:mod:`rotorkin.drives.wobble_cam.sweep_forces`, 20 001 angles per design)."""
    if _fuel_air(cfg):
        return SAMPLED_METRICS
    return SAMPLED_METRICS + swf.DYNAMIC + swf.FORCES


#: Curves over one period (``keep_curves``): the study's columns of the same names.
CURVES = (
    "rotor1_angle_deg",
    "rotor2_angle_deg",
    "rotor1_speed_ratio",
    "rotor2_speed_ratio",
    "rotor1_accel_per_rad",
    "rotor2_accel_per_rad",
    "rotor1_jerk_per_rad2",
    "rotor2_jerk_per_rad2",
    "slider_angle_deg",
    "chamber_a_angle_deg",
    "chamber_b_angle_deg",
)
#: The angle of the curves: column name and its doc.
ANGLE = ("theta_deg", "Output-shaft angle theta, positive from +z towards +y about x.")


def unsupported(cfg: dict) -> str | None:
    """Why the kernel cannot evaluate designs on this base config (None: it can)."""
    d = cfg["drive"]
    if _fuel_air(cfg) and (d.get("spin_a") or d.get("spin_b")):
        return "the fuel-air cycle on a corrected spin law (its strokes vary per design)"
    return None


def _fuel_air(cfg: dict) -> bool:
    return (cfg.get("loads") or {}).get("model", "fuel_air") != "ideal"


#: Metrics of the fuel-air cycle only.
_FUEL_AIR_METRICS = ("trapped_mass_mg", "peak_pressure_angle_deg", "peak_temperature_K",
                     "fuel_energy_J_per_rev", "heat_to_walls_J_per_rev")  # fmt: skip


def metric_names(cfg: dict) -> tuple[str, ...]:
    """Summary keys the kernel computes for this base config."""
    if _fuel_air(cfg):
        return _DRIVE_METRICS + _MACHINE_METRICS + _FUEL_AIR_METRICS
    return _DRIVE_METRICS + _MACHINE_METRICS


def period(p) -> float:
    """Period of the motion: one shaft turn [rad]."""
    return 2.0 * np.pi


# --------------------------------------------------------------------------------------------
# admissibility: the checks of TwinRotor, WobbleCam, piston_layout and IdealCycle, in order
# --------------------------------------------------------------------------------------------
def _machine_args(p) -> dict:
    """The machine fields of the designs (arrays or base scalars), SI."""
    args = {
        f: p.float(f"machine.{f}") for f in tr.CHECKED if f not in ("section", "pistons_per_rotor")
    }
    args["pistons_per_rotor"] = np.asarray(p["machine.pistons_per_rotor"])
    args["section"] = np.asarray(p["machine.section"])
    return args


def reasons(p, code: dict) -> np.ndarray:
    """Reason code per design: 0 if admissible, else the code of the key the study would name.

    The machine's and the drive's own vectorised checks
    (:func:`rotorkin.machines.twin_rotor.violation`,
    :func:`rotorkin.drives.wobble_cam.kinematics.violation`), with a ``[cam]`` section the
    spherical cam's (:func:`rotorkin.drives.wobble_cam.cam.cam_violation`: every command
    refuses what ``export`` would, before the study), then
    :func:`rotorkin.drives.wobble_cam.chambers.compression_ratio_violation`, the cycle's,
    and last the rail rollers against the cam shell
    (:func:`rotorkin.drives.wobble_cam.forces.rail_violation`, where the cam fits: the pair
    forces), in the order the study meets them.
    """
    r = np.zeros(p.n, dtype=np.int16)
    with np.errstate(all="ignore"):
        m = _machine_args(p)
        tilt, alpha = p.float("drive.plate_tilt"), p.float("drive.roller_axis_angle")
        d = p.cfg["drive"]

        def machine():
            first = tr.violation(**m)
            for i, name in enumerate(tr.CHECKED, start=1):
                if f"machine.{name}" in code:
                    flag(r, first == i, code[f"machine.{name}"])

        def drive():
            first = wc.violation(tilt, alpha, p.float("drive.spin_ratio"),
                                 p.float("drive.sphere_radius"), m["pistons_per_rotor"],
                                 d.get("spin_a") or (), d.get("spin_b") or ())  # fmt: skip
            for i, name in enumerate(wc.CHECKED, start=1):
                key = f"drive.{name}"
                key = "machine.pistons_per_rotor" if name == "pistons_per_rotor" else key
                flag(r, first == i, code.get(key, code["other"]))

        shell = _cam_args(p)
        cam_code = cs.cam_violation(p.float("drive.sphere_radius"), **shell)
        if "cam" in p.cfg:  # the cam's checks come first, with the drive's (as export's)
            drive()
            for i, name in enumerate(cs.CAM_CHECKED, start=1):
                flag(r, cam_code == i, code.get(cs.config_key(name), code["other"]))
            machine()
        else:
            machine()
            drive()
        npist = m["pistons_per_rotor"]
        n_f = np.where((npist >= 2) & (npist % 2 == 0), npist, 4).astype(float)
        gaps = wc.chamber_gaps(tilt, alpha, n_f)
        bad = wc.compression_ratio_violation(
            gaps, m["compression_ratio"], p.extra.get("piston_width")
        )
        flag(r, bad, code["machine.compression_ratio"])
        if _fuel_air(p.cfg):  # the fuel-air cycle's compression limit (geometric ratio)
            beta = p.extra.get("piston_width")
            beta = wch.piston_width(gaps, m["compression_ratio"]) if beta is None else beta
            kvol, vc = _section(p), p.float("machine.clearance_volume")
            ratio = np.maximum(*((kvol * (g[1] - beta) + vc) / (kvol * (g[0] - beta) + vc)
                                 for g in gaps))  # fmt: skip
            limit = fa.compression_limit(fa.loads_of(p.cfg.get("loads") or {}))
            flag(r, ratio > limit, code["machine.compression_ratio"])
        # IdealCycle
        bad = ec.cycle_violation(*(p.float(f"loads.{key}") for key in ec.CYCLE_CHECKS))
        for i, key in enumerate(ec.CYCLE_CHECKS, start=1):
            flag(r, bad == i, code[f"loads.{key}"])
        # the pair forces of a cam that fits: its rail rollers must clear the shell
        outer = p.float("drive.sphere_radius") + 0.5 * shell["shell_thickness"]
        rail = fo.rail_violation(_drive_value(p, "rail_radius"), outer,
                                 _drive_value(p, "rail_roller_radius"))  # fmt: skip
        flag(r, (cam_code == 0) & rail, code.get("drive.rail_radius", code["other"]))
    return r


def _cam_args(p) -> dict:
    """The spherical cam's fields of the base config (defaults where it has none)."""
    c = p.cfg.get("cam") or {}
    defaults = {f.name: f.default for f in fields(cs.SphericalCam)}
    return {k: defaults[k] if c.get(k) is None else c[k] for k in cs.CAM_KEYS}


def _drive_value(p, key: str):
    """A force parameter ``drive.<key>`` of the designs, or its default."""
    if f"drive.{key}" in p.cfg["drive"] or p.varies(f"drive.{key}"):
        return p.float(f"drive.{key}")
    return getattr(fo.ForceParams, key)


# --------------------------------------------------------------------------------------------
# metrics
# --------------------------------------------------------------------------------------------
def metrics(p, names, samples: int, threads: int | None = None) -> dict:
    """Summary metrics of admissible designs ``p``, arrays (n,), for the requested ``names``."""
    names = set(names)
    n = p.n
    deg = np.degrees
    out = {}
    tilt, alpha = p.float("drive.plate_tilt"), p.float("drive.roller_axis_angle")
    npist = np.asarray(p["machine.pistons_per_rotor"]).astype(int)
    n_f = npist.astype(float)
    spin = p.float("drive.spin_ratio")
    eps = p.float("machine.compression_ratio")
    amax, amin = wc.slider_angle_extremes(tilt, alpha)
    ga, gb = wc.chamber_gaps(tilt, alpha, n_f)
    kind_a = wc.design_kind_a((ga, gb))
    fixed = "piston_width" in p.extra  # tolerance analysis: pistons as manufactured
    beta = p.extra["piston_width"] if fixed else wch.piston_width((ga, gb), eps)
    a_lo, a_hi, b_lo, b_hi = ga[0] - beta, ga[1] - beta, gb[0] - beta, gb[1] - beta
    d_lo, d_hi = np.where(kind_a, a_lo, b_lo), np.where(kind_a, a_hi, b_hi)
    cycles = wc.volume_cycles(spin)  # volume cycles per rev, an integer
    chambers = 2.0 * n_f
    c = np.cos(tilt)
    val = {
        "slider_angle_max_deg": deg(amax),
        "slider_angle_min_deg": deg(amin),
        "chamber_angle_max_deg": deg(d_hi),
        "chamber_angle_min_deg": deg(d_lo),
        "chamber_swing_deg": deg(amax - amin),
        "piston_width_deg": deg(beta),
        "volume_cycles_per_rev": cycles,
        "power_strokes_per_rev": wc.power_strokes(spin, n_f),
        "max_plate_tilt_deg": deg(wc.max_plate_tilt(alpha, n_f)),
        "piston_offset_gamma_deg": deg(wc.piston_offset(n_f)),
        "chambers": chambers,
        "compression_ratio": d_hi / d_lo if fixed else eps,
        "min_compression_ratio": wc.zero_width_ratio((ga, gb)),
        "chamber_a_angle_min_deg": deg(a_lo),
        "chamber_a_angle_max_deg": deg(a_hi),
        "chamber_b_angle_min_deg": deg(b_lo),
        "chamber_b_angle_max_deg": deg(b_hi),
        "compression_ratio_a": a_hi / a_lo,
        "compression_ratio_b": b_hi / b_lo,
        "volume_cycles_per_rev_all_chambers": chambers * cycles,
        "rotor_mean_speed_ratio": 1.0 + spin,
    }
    val["rotor_speed_ratio_min"] = np.minimum(1.0 + spin * c, 1.0 + spin / c)
    val["rotor_speed_ratio_max"] = np.maximum(1.0 + spin * c, 1.0 + spin / c)
    sampled = {"rotor_accel_peak_per_rad", "rotor_jerk_peak_per_rad2"}
    spin_a, spin_b = p.cfg["drive"].get("spin_a") or [], p.cfg["drive"].get("spin_b") or []
    if spin_a or spin_b:
        sampled |= {"rotor_speed_ratio_min", "rotor_speed_ratio_max"}
    cycle = bool(names & set(_MACHINE_METRICS)) and _fuel_air(p.cfg)
    # progress: the fuel-air cycle's blocks when it runs (most of the time), else these
    with block_progress(None) if cycle else contextlib.nullcontext():
        if names & set(SAMPLED_METRICS):  # every curve; the peaks come out of the same pass
            val.update(_sampled_full(p, tilt, alpha, spin, n_f, beta, samples, threads))
        elif names & sampled:
            val.update(_sampled(p, tilt, alpha, spin, samples, threads))
    dynamic = names & set(swf.DYNAMIC + swf.FORCES)
    if names & set(_MACHINE_METRICS) or dynamic:
        val.update(_machine(p, n_f, cycles, ga, gb, beta, kind_a, a_lo, a_hi, b_lo, b_hi,
                            threads))  # fmt: skip
    if dynamic:
        val.update(swf.dynamics(p, names, samples, threads, val["indicated_work_J"], _cam_args(p),
                                p.extra.get("piston_width")))  # fmt: skip
    for name in names:
        out[name] = full(val[name], n)
    return out


def _machine(p, n_f, cycles, ga, gb, beta, kind_a, a_lo, a_hi, b_lo, b_hi, threads=None) -> dict:
    """Volumes and the ideal cycle (:mod:`rotorkin.machines.twin_rotor`, closed forms)."""
    k = _section(p)
    vc = p.float("machine.clearance_volume")
    va_min, va_max, vb_min, vb_max = (tr.chamber_volume(k, d, vc) for d in (a_lo, a_hi, b_lo, b_hi))
    eps_a, eps_b = va_max / va_min, vb_max / vb_min
    chambers = 2.0 * n_f
    per_rev = cycles / 2.0  # four-stroke cycles per rev
    swept = tr.chamber_volume(k, a_hi - a_lo)  # K swing (eq. 23)
    disp = tr.displacement(swept, chambers, per_rev)
    cycle = ec.IdealCycle(*(p.float(f"loads.{key}") for key in ec.CYCLE_CHECKS))
    q = cycle.heat_per_cycle
    end_a, end_b = (ec.compression_end_pressure(cycle, va_max, va_min),
                    ec.compression_end_pressure(cycle, vb_max, vb_min))  # fmt: skip
    peak_a, peak_b = (
        ec.peak_pressure(cycle, va_max, va_min),
        ec.peak_pressure(cycle, vb_max, vb_min),
    )
    work_a, work_b = (
        ec.indicated_work(cycle, va_max, va_min),
        ec.indicated_work(cycle, vb_max, vb_min),
    )
    work = (work_a + work_b) * (chambers / 2.0) * per_rev
    heat = q * chambers * per_rev
    eps_design = np.where(kind_a, eps_a, eps_b)
    with np.errstate(divide="ignore", invalid="ignore"):
        eff = np.where(heat > 0, work / np.where(heat > 0, heat, 1.0), np.nan)
        imep = np.where(disp > 0, work / np.where(disp > 0, disp, 1.0), np.nan) / 1e5
    omega_mean = _omega_mean(p)
    mm3 = 1e6
    out = {
        "pistons_per_rotor": n_f,
        "annulus_volume_cm3": 2.0 * np.pi * k * mm3,
        "clearance_volume_cm3": vc * mm3,
        "chamber_volume_max_cm3": np.maximum(va_max, vb_max) * mm3,
        "chamber_volume_min_cm3": np.minimum(va_min, vb_min) * mm3,
        "chamber_a_volume_min_cm3": va_min * mm3,
        "chamber_a_volume_max_cm3": va_max * mm3,
        "chamber_b_volume_min_cm3": vb_min * mm3,
        "chamber_b_volume_max_cm3": vb_max * mm3,
        "swept_volume_cm3": swept * mm3,
        "displacement_cm3_per_rev": disp * mm3,
        "equivalent_capacity_cm3": 2.0 * disp * mm3,
        "intake_strokes_per_rev": np.round(chambers * per_rev),
        "chambers_in_power_stroke": np.floor(n_f / 2.0),
        "compression_ratio_geometric": eps_design,
        "compression_ratio_geometric_a": eps_a,
        "compression_ratio_geometric_b": eps_b,
        "compression_end_pressure_bar": np.maximum(end_a, end_b) / 1e5,
        "peak_pressure_bar": np.maximum(peak_a, peak_b) / 1e5,
        "indicated_work_per_cycle_a_J": work_a,
        "indicated_work_per_cycle_b_J": work_b,
        "indicated_work_J": work,
        "heat_added_J_per_rev": heat,
        "indicated_efficiency": eff,
        "otto_efficiency": ec.otto_efficiency(eps_design, cycle.polytropic_exponent),
        "imep_bar": imep,
        "mean_torque_Nm": work / (2.0 * np.pi),
        "indicated_power_kW": work * omega_mean / (2.0 * np.pi) / 1e3,
    }
    if _fuel_air(p.cfg):  # the cycle's keys from the integrated fuel-air cycle instead
        out.update(fuel_air_cycle(p, n_f, per_rev, kind_a, beta, k, vc, (va_min, va_max),
                                   (vb_min, vb_max), disp, omega_mean, threads))  # fmt: skip
    return out


def _section(p):
    """Chamber volume per radian of chamber angle, ``V = K delta + V_c`` [m^3/rad]."""
    keys = ("inner_radius", "outer_radius", "axial_width", "mean_radius", "section_diameter")
    return tr.section_volume_per_radian(
        p["machine.section"], *(p.float(f"machine.{k}") for k in keys)
    )


def _omega_mean(p) -> float:
    """Time-averaged shaft speed over a turn, as the study computes it [rad/s]."""
    fine = np.linspace(0.0, 2.0 * np.pi, 20_001)
    speed = p.cfg.get("run", {}).get("speed", 3000.0 * np.pi / 30.0)
    omega = shaft_speed(fine, speed, 2.0 * np.pi)
    return 2.0 * np.pi / np.trapezoid(1.0 / omega[0], fine)


# --------------------------------------------------------------------------------------------
# sampled peaks of the rotor coefficients
# --------------------------------------------------------------------------------------------
def _spin_tables(p, n_spin: float, theta):
    """The spin law and its three derivatives on the grid (:func:`~.kinematics.spin_angle`)."""
    d = p.cfg["drive"]
    return wc.spin_angle(n_spin, d.get("spin_a") or (), d.get("spin_b") or (), theta)


def _sampled(p, tilt, alpha, spin, samples: int, threads) -> dict:
    """Peaks of |Phi''|, |Phi'''| (and extremes of Phi' for a corrected spin law) per design."""
    out = _rotor_extremes(p, tilt, alpha, spin, samples, threads)
    val = {"rotor_accel_peak_per_rad": out["acc"], "rotor_jerk_peak_per_rad2": out["jerk"]}
    if not _linear(p):
        val["rotor_speed_ratio_min"] = out["r_min"]
        val["rotor_speed_ratio_max"] = out["r_max"]
    return val


def _linear(p) -> bool:
    """Whether the spin law is ``varphi = n theta`` (no correction)."""
    return not (p.cfg["drive"].get("spin_a") or p.cfg["drive"].get("spin_b"))


def _rotor_extremes(p, tilt, alpha, spin, samples: int, threads) -> dict:
    """:func:`~rotorkin.drives.wobble_cam.fast.rotor_extremes` per design (n,), evaluated
    once per distinct (spin ratio, plate tilt, roller axis angle): the only values the
    rotors' motion depends on; blocks of designs on ``threads``."""
    (spin, tilt, alpha), which = distinct((spin, tilt, alpha), p.n)
    theta = sample_grid(2.0 * np.pi, samples)
    out = {}
    for n_spin in np.unique(spin):  # one table per spin ratio (usually one)
        rows = np.flatnonzero(spin == n_spin)
        law = float(n_spin) if _linear(p) else _spin_tables(p, float(n_spin), theta)
        block = _extremes_block(theta, law, tilt[rows], alpha[rows])
        res = run_blocks(block, rows.size, samples, threads)
        for key, values in res.items():
            out.setdefault(key, np.empty(spin.size))[rows] = values
    return {key: values[which] for key, values in out.items()}


def _extremes_block(theta, law, tilt, alpha):
    """Block evaluator: :func:`~rotorkin.drives.wobble_cam.fast.rotor_extremes` of the
    designs ``lo:hi`` (``law``: the spin ratio n, or the spin law's 4 tables on ``theta``)."""
    return lambda lo, hi: rotor_extremes(tilt[lo:hi], alpha[lo:hi], law, theta)


# --------------------------------------------------------------------------------------------
# every curve on the sampled grid, reduced (SAMPLED_METRICS)
# --------------------------------------------------------------------------------------------
def _sampled_full(p, tilt, alpha, spin, n_f, beta, samples: int, threads) -> dict:
    """Every kinematic curve of each design on ``samples`` angles, reduced to extremes and peaks.

    Per design and angle: both rotor angles ``Phi_k`` and ``Phi_k'``, ``Phi_k''``,
    ``Phi_k'''`` and the slider angle ``s = Phi_2 - Phi_1``, reduced (once per distinct
    rotor motion, :func:`_rotor_extremes`). The chamber angles of both kinds (eq. 18-19),
    ``delta_A = s - lo_a`` and ``delta_B = hi_b - s``, and their volumes ``K delta + V_c``
    (``K > 0``) are monotone in ``s`` in every rounded step, so their extremes are those
    of the slider angle carried through the same steps: equal, bit for bit, to the
    extremes of the curves. Returns the peaks of :func:`_sampled` (the same evaluation)
    and :data:`SAMPLED_METRICS`.
    """
    kvol, vc = _section(p), p.float("machine.clearance_volume")
    lo, hi = wc.slider_angle_limits(n_f)
    lo_a, hi_b = lo + beta, hi - beta  # delta_A = s - lo_a, delta_B = hi_b - s (eq. 18-19)
    out = _rotor_extremes(p, tilt, alpha, spin, samples, threads)
    s_min, s_max = out["s_min"], out["s_max"]
    a_min, a_max = s_min - lo_a, s_max - lo_a
    b_min, b_max = hi_b - s_max, hi_b - s_min
    deg, mm3 = np.degrees, 1e6
    val = {
        "rotor_accel_peak_per_rad": out["acc"],
        "rotor_jerk_peak_per_rad2": out["jerk"],
        "sampled_slider_angle_min_deg": deg(s_min),
        "sampled_slider_angle_max_deg": deg(s_max),
        "sampled_chamber_a_angle_min_deg": deg(a_min),
        "sampled_chamber_a_angle_max_deg": deg(a_max),
        "sampled_chamber_b_angle_min_deg": deg(b_min),
        "sampled_chamber_b_angle_max_deg": deg(b_max),
        "sampled_chamber_a_volume_min_cm3": (a_min * kvol + vc) * mm3,
        "sampled_chamber_a_volume_max_cm3": (a_max * kvol + vc) * mm3,
        "sampled_chamber_b_volume_min_cm3": (b_min * kvol + vc) * mm3,
        "sampled_chamber_b_volume_max_cm3": (b_max * kvol + vc) * mm3,
        "sampled_rotor_speed_ratio_min": out["r_min"],
        "sampled_rotor_speed_ratio_max": out["r_max"],
    }
    if not _linear(p):
        val["rotor_speed_ratio_min"] = out["r_min"]
        val["rotor_speed_ratio_max"] = out["r_max"]
    return val


# --------------------------------------------------------------------------------------------
# curves
# --------------------------------------------------------------------------------------------
def curves(p, points: int):
    """The :data:`CURVES` of admissible designs over one turn: angle (points,), dict (n, points).

    The same drive functions as the study's columns, broadcast over a design axis.
    """
    theta = sample_grid(2.0 * np.pi, points)
    n_spin = full(p.float("drive.spin_ratio"), p.n)
    out = {name: np.empty((p.n, points)) for name in CURVES}
    eps = full(p.float("machine.compression_ratio"), p.n)
    npist = full(np.asarray(p["machine.pistons_per_rotor"]), p.n, dtype=float)
    tilt = full(p.float("drive.plate_tilt"), p.n)
    alpha = full(p.float("drive.roller_axis_angle"), p.n)
    for ns in np.unique(n_spin):
        rows = np.flatnonzero(n_spin == ns)
        spin = _spin_tables(p, float(ns), theta)
        t_, a_, nf = tilt[rows, None], alpha[rows, None], npist[rows, None]
        q, d1, d2, d3 = wc.rotor_angles_from_spin(t_, a_, spin, theta)
        beta = p.extra.get("piston_width")
        if beta is None:
            beta = wch.piston_width(wc.chamber_gaps(t_, a_, nf), eps[rows, None])
        slider = q[1] - q[0]
        delta_a, delta_b = wc.chamber_angles(beta, slider, pistons=nf)
        values = {
            "slider_angle_deg": np.degrees(slider),
            "chamber_a_angle_deg": np.degrees(delta_a),
            "chamber_b_angle_deg": np.degrees(delta_b),
        }
        for k in (0, 1):
            values[f"rotor{k + 1}_angle_deg"] = np.degrees(q[k])
            values[f"rotor{k + 1}_speed_ratio"] = d1[k]
            values[f"rotor{k + 1}_accel_per_rad"] = d2[k]
            values[f"rotor{k + 1}_jerk_per_rad2"] = d3[k]
        for name in CURVES:
            out[name][rows] = values[name]
    return theta, out


def tolerance_hold(cfg: dict) -> tuple[dict, dict]:
    """Hold the piston width beta at its nominal value in a tolerance analysis.

    The pistons are manufactured at the width the nominal design needs for its
    compression ratio; a deviation of the plate tilt then changes the compression
    ratio instead of the piston width.
    """
    beta = metrics(Designs(cfg, {}, 1), ["piston_width_deg"], 3)["piston_width_deg"][0]
    return cfg, {"piston_width": float(np.radians(beta))}
