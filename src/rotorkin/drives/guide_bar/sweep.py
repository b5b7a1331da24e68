"""Sweep kernel of the differential vane pump on the guide-bar + gear drive, by broadcasting.

The summary keys of :mod:`rotorkin.drives.guide_bar.study` for arrays of designs, from
the same functions: the closed forms of :mod:`rotorkin.drives.guide_bar.summary`
(vane angle gamma_0 of both drivers, relative-angle swing, speed-ratio range,
equal-speed points, the pump's chamber angles, volumes and displacement) and,
sampled on ``samples`` input angles per design (a design x angle array in blocks),
the input torque ``M7 q_1' + M8 q_2'`` (eq. 7, 8) and the peaks of the impellers'
acceleration and jerk coefficients from
:func:`~rotorkin.drives.guide_bar.kinematics.impeller_rates` (no arctangent per
sample), the drive's parameters held as (block, 1) columns of a
:class:`~rotorkin.drives.guide_bar.kinematics.GuideBar`. With ideal ports (no
sealing land, ``machine.port_land = 0``), also sampled: the geometric flow's
extremes and ripple, the shaft torques with and without the inertias, the
equivalent inertia, energy fluctuation and flywheel
(:func:`~rotorkin.drives.guide_bar.summary.dynamics_summary`) and the impellers'
peaks in time (:func:`~rotorkin.studies.helpers.time_peaks`), from the study's own
:func:`~rotorkin.drives.guide_bar.pump.pump_state` on columns of designs (one call
per block, gear ratio i12 and number of vanes). Admissibility: :func:`reasons`, from
the same vectorised checks as the dataclasses.
"""

from __future__ import annotations

import numpy as np

from rotorkin.analysis import pairs as ap
from rotorkin.analysis.timing import shaft_speed
from rotorkin.core.batch import Designs, distinct, flag, full, run_blocks, sample_grid
from rotorkin.drives.guide_bar import forces as gb_forces
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar import pump as gb_pump
from rotorkin.drives.guide_bar import summary as closed_forms
from rotorkin.drives.guide_bar.schema import VanePumpMachine
from rotorkin.machines import vane_pump as vp
from rotorkin.studies.helpers import time_peaks

__all__ = ["DRIVE", "KEYS", "CURVES", "ANGLE", "unsupported", "metric_names", "reasons",
           "metrics", "curves", "period"]  # fmt: skip

DRIVE = "guide_bar"

KEYS = frozenset(
    {
        "drive.lambda",
        "drive.gear_ratio",
        "drive.input_gear_ratio",
        "drive.phase",
        "drive.driver",
        "machine.vanes_per_impeller",
        "machine.vane_angle",
        "machine.hub_radius",
        "machine.casing_radius",
        "machine.axial_width",
        "machine.inertia_shaft",
        "machine.inertia_impeller_1",
        "machine.inertia_impeller_2",
        "machine.speed_fluctuation",
        "loads.impeller_torque_1",
        "loads.impeller_torque_2",
        "loads.suction_pressure",
        "loads.discharge_pressure",
    }
)

_METRICS = (
    "lambda",
    "gear_ratio",
    "input_gear_ratio",
    "phase_deg",
    "vane_angle_deg",
    "vane_angle_crank_driven_deg",
    "vane_angle_guide_driven_deg",
    "vane_angle_other_driver_deg",
    "relative_angle_swing_deg",
    "impeller_speed_ratio_min",
    "impeller_speed_ratio_max",
    "impeller_speed_ratio_mean",
    "equal_speed_driving_angle_1_deg",
    "equal_speed_driving_angle_2_deg",
    "equal_speed_input_angle_1_deg",
    "equal_speed_input_angle_2_deg",
    "equal_speed_ratio_1",
    "equal_speed_ratio_2",
    "input_torque_min_Nm",
    "input_torque_max_Nm",
    "input_torque_mean_Nm",
    "input_torque_fluctuation_Nm",
    "input_torque_fluctuation_ratio",
    "impeller_speed_ratio_input_min",
    "impeller_speed_ratio_input_max",
    "impeller_accel_peak_per_rad",
    "impeller_jerk_peak_per_rad2",
    "vanes_per_impeller",
    "chambers",
    "pump_vane_angle_deg",
    "pump_vane_angle_max_deg",
    "chamber_angle_min_deg",
    "chamber_angle_max_deg",
    "chamber_volume_min_cm3",
    "chamber_volume_max_cm3",
    "displacement_cm3_per_rev",
    "displacement_per_period_cm3",
    "displacement_per_impeller_rev_cm3",
    "pressure_rise_bar",
    "indicated_work_J",
    "indicated_work_per_period_J",
    "mean_torque_Nm",
)
_FLOW = ("flow_mean_l_per_min", "hydraulic_power_W")
_INERTIAS = ("inertia_shaft", "inertia_impeller_1", "inertia_impeller_2")
#: Keys of the pump's dynamics (ideal ports; sampled).
_DYNAMIC = closed_forms.FLOW_KEYS + closed_forms.TORQUE_KEYS + closed_forms.TIME_KEYS
#: Keys of the pairs' forces, stresses and friction and the drive's own peaks (ideal
#: ports; sampled with the dynamics).
_FORCES = ap.NUMBER_KEYS + gb_forces.SUMMARY_KEYS

CURVES = (
    "impeller1_angle_deg",
    "impeller2_angle_deg",
    "relative_angle_deg",
    "impeller1_speed_ratio",
    "impeller2_speed_ratio",
    "impeller1_accel_per_rad",
    "impeller2_accel_per_rad",
    "impeller1_jerk_per_rad2",
    "impeller2_jerk_per_rad2",
    "input_torque_Nm",
)
ANGLE = ("theta_deg", "Input gear 1 angle theta; the driving members turn at theta / i12.")


def unsupported(cfg: dict) -> str | None:
    """Why the kernel cannot evaluate designs on this base config (None: it can)."""
    return None


def metric_names(cfg: dict) -> tuple[str, ...]:
    """Summary keys the kernel computes (the mean flow only at a constant shaft speed, the
    dynamics with ideal ports)."""
    speed = cfg.get("run", {}).get("speed")
    ideal = not (cfg.get("machine") or {}).get("port_land")
    return (_METRICS + (_FLOW if not isinstance(speed, list) else ())
            + (_DYNAMIC + _FORCES if ideal else ()))  # fmt: skip


def _value(p, key: str):
    """``p[key]`` as floats, the schema's default where the base config leaves it out."""
    if p[key] is None:
        return float(VanePumpMachine().model_dump()[key.split(".", 1)[1]])
    return p.float(key)


def period(p):
    """Period of the speeds: ``2 pi i12`` [rad] (an array when i12 varies)."""
    return gb.input_period(p.float("drive.input_gear_ratio"))


def _column(p, key: str, n: int | None, dtype=float):
    """``p[key]`` as given (``n`` None), or as a fresh column of shape (n, 1)."""
    value = p[key]
    if n is None:
        return value.astype(dtype) if isinstance(value, np.ndarray) else value
    return full(value, n, dtype=dtype)[:, None]


def _drive(p, n: int | None = None) -> gb.GuideBar:
    """The designs' drive: scalars and (n,) arrays as given, or (n, 1) columns with ``n``."""
    return gb.GuideBar(
        *(_column(p, f"drive.{k}", n) for k in ("lambda", "gear_ratio", "input_gear_ratio",
                                                 "phase")),
        _column(p, "drive.driver", n, dtype=str),
    )  # fmt: skip


def _machine(p) -> dict:
    """The designs' pump fields (scalars or (n,) arrays); ``vane_angle`` None: the default."""
    m = {k: p[f"machine.{k}"] for k in ("vanes_per_impeller", "vane_angle", "hub_radius",
                                        "casing_radius", "axial_width")}  # fmt: skip
    if m["vane_angle"] is not None:
        m["vane_angle"] = np.asarray(m["vane_angle"], dtype=float)
    return m


def _config_key(section: str, field: str) -> str:
    return f"{section}.{'lambda' if field == 'lam' else field}"


def reasons(p, code: dict) -> np.ndarray:
    """Reason code per design (0: admissible), in the order of the study's checks.

    The drive's (:func:`~rotorkin.drives.guide_bar.kinematics.inadmissible`), the
    pump's (:func:`~rotorkin.drives.guide_bar.pump.inadmissible`), the ports'
    (:func:`~rotorkin.machines.vane_pump.ports_inadmissible`).
    """
    r = np.zeros(p.n, dtype=np.int16)

    def mark(codes, fields, section, where=slice(None)):
        codes = np.broadcast_to(codes, r[where].shape)
        sub = r[where]
        for k, field in enumerate(fields):
            flag(sub, codes == k + 1, code.get(_config_key(section, field), code["other"]))
        r[where] = sub

    drive = [p.float(f"drive.{k}") for k in ("lambda", "gear_ratio", "input_gear_ratio", "phase")]
    mark(gb.inadmissible(*drive, p["drive.driver"]), gb.FIELDS, "drive")
    ok = r == 0
    if ok.any():
        safe = p.take(ok) if not ok.all() else p
        pump = gb_pump.inadmissible(_drive(safe), **_machine(safe))
        mark(pump, gb_pump.CHECKS, "machine", ok)
    ports = vp.ports_inadmissible(p.float("loads.suction_pressure"),
                                  p.float("loads.discharge_pressure"))  # fmt: skip
    mark(ports, vp.PORT_FIELDS, "loads")
    for k in _INERTIAS:  # the study's order: the inertias, then the wanted C_s
        flag(
            r,
            ~(np.asarray(_value(p, f"machine.{k}")) >= 0.0),
            code.get(f"machine.{k}", code["other"]),
        )
    cs = np.asarray(_value(p, "machine.speed_fluctuation"), dtype=float)
    flag(r, ~((cs > 0.0) & (cs < 1.0)), code.get("machine.speed_fluctuation", code["other"]))
    return r


_SAMPLED = frozenset({"input_torque_min_Nm", "input_torque_max_Nm", "input_torque_fluctuation_Nm",
                      "input_torque_fluctuation_ratio", "impeller_accel_peak_per_rad",
                      "impeller_jerk_peak_per_rad2"})  # fmt: skip


def metrics(p, names, samples: int, threads: int | None = None) -> dict:
    """Summary metrics of admissible designs ``p``, arrays (n,) (:mod:`.summary`)."""
    names = set(names)
    params = _drive(p)
    m7, m8 = p.float("loads.impeller_torque_1"), p.float("loads.impeller_torque_2")
    sampled = _sampled(p, samples, threads) if names & _SAMPLED else None
    val = closed_forms.drive_summary(params, m7, m8, sampled)
    pump = gb_pump.vane_pump(params, **_machine(p))
    ports = vp.PortPressures(p.float("loads.suction_pressure"), p.float("loads.discharge_pressure"))
    val |= closed_forms.pump_summary(params, pump)
    speed = p.cfg.get("run", {}).get("speed")
    flow = None
    if not isinstance(speed, list):
        flow = vp.displacement(pump) / (gb.period(params) / float(speed))  # volume / its time
        val["flow_mean_l_per_min"] = flow * 60.0e3
    val |= closed_forms.work_summary(params, pump, ports, flow)
    if names & set(_DYNAMIC + _FORCES):
        work = full(val["indicated_work_J"], p.n) if names & set(_FORCES) else None
        val |= _dynamics(p, samples, threads, work)
    return {name: full(val[name], p.n) for name in names}


def _dynamics(p, samples: int, threads, work=None) -> dict:
    """The :data:`_DYNAMIC` keys on ``samples`` input angles per design (ideal ports), and
    given the designs' indicated work per turn ``work``, the :data:`_FORCES` keys.

    Designs of one input gear ratio (it sets the period), one number of vanes (the
    number of chambers) and one driver at a time; the study's
    :func:`~rotorkin.drives.guide_bar.pump.pump_state`,
    :func:`~rotorkin.drives.guide_bar.summary.dynamics_summary` and the pairs' forces
    (:func:`~rotorkin.drives.guide_bar.forces.solve`,
    :func:`~rotorkin.drives.guide_bar.forces.pairs`,
    :func:`rotorkin.analysis.pairs.summary`) on (block, 1) columns.
    """
    n = p.n
    keys = _DYNAMIC + (_FORCES if work is not None else ())
    cols = {k: full(p.float(k), n) for k in ("drive.lambda", "drive.gear_ratio",
            "drive.input_gear_ratio", "drive.phase", "loads.suction_pressure",
            "loads.discharge_pressure")}  # fmt: skip
    for k in ("hub_radius", "casing_radius", "axial_width", *_INERTIAS, "speed_fluctuation"):
        cols[k] = full(_value(p, f"machine.{k}"), n)
    if p["machine.vane_angle"] is not None:
        cols["vane_angle"] = full(p.float("machine.vane_angle"), n)
    if work is not None:
        cols["work"] = work
        # the gears' and contacts' keys: the same for every design
        size = gb_forces.gearing(p.cfg["drive"])
        model = ap.ContactModel.from_config(p.cfg)
        bearing = gb_forces.bearing_radius(p.cfg)
    driver = full(np.asarray(p["drive.driver"]), n, dtype=str)
    drivers, driver_of = np.unique(driver, return_inverse=True)
    vanes = full(np.asarray(p["machine.vanes_per_impeller"]), n, dtype=np.int64)
    i12 = cols["drive.input_gear_ratio"]
    speed = p.cfg["run"]["speed"]
    out = {k: np.empty(n) for k in keys}
    kinds = np.stack([i12, vanes.astype(float), driver_of.reshape(-1).astype(float)], axis=-1)
    for ratio, count, which in np.unique(kinds, axis=0):
        rows = np.flatnonzero((i12 == ratio) & (vanes == count)
                              & (driver_of.reshape(-1) == which))  # fmt: skip
        theta = sample_grid(gb.input_period(ratio), samples)
        omega = shaft_speed(theta, speed, gb.input_period(ratio))

        def fn(lo, hi, rows=rows, count=int(count), theta=theta, omega=omega,
               driver=str(drivers[int(which)])):  # fmt: skip
            c = {k: v[rows[lo:hi], None] for k, v in cols.items()}
            params = gb.GuideBar(c["drive.lambda"], c["drive.gear_ratio"],
                                 c["drive.input_gear_ratio"], c["drive.phase"], driver)  # fmt: skip
            pump = gb_pump.vane_pump(params, count, c.get("vane_angle"), c["hub_radius"],
                                     c["casing_radius"], c["axial_width"])  # fmt: skip
            ports = vp.PortPressures(c["loads.suction_pressure"], c["loads.discharge_pressure"])
            inertia = (c["inertia_shaft"], (c["inertia_impeller_1"], c["inertia_impeller_2"]))
            st = gb_pump.pump_state(params, pump, ports, inertia, speed, theta, omega=omega)
            val = closed_forms.dynamics_summary(params, st, inertia, theta,
                                                c["speed_fluctuation"][:, 0])  # fmt: skip
            val |= time_peaks(st["motion"], omega, closed_forms.SLUGS)
            if work is not None:
                torque = gb_forces.drive_torques(params, theta, st["M"], inertia[1],
                                                 st["omega"], st["omega_dot"])  # fmt: skip
                forces = gb_forces.solve(params, size, theta, torque)
                found = gb_forces.pairs(params, size, forces, bearing)
                val |= ap.summary(found, theta, c["work"][:, 0], model, st["omega"], batch=True)
                val |= gb_forces.own_summary(forces, st["omega"])
            return {k: np.broadcast_to(val[k], (hi - lo,)) for k in keys}

        res = run_blocks(fn, rows.size, samples, threads)
        for k in keys:
            out[k][rows] = res[k]
    return out


def _sampled(p, samples, threads) -> dict:
    """The sampled peaks per design (n,), once per distinct drive and impeller torques."""
    n = p.n
    keys = ("drive.lambda", "drive.gear_ratio", "drive.input_gear_ratio", "drive.phase",
            "loads.impeller_torque_1", "loads.impeller_torque_2")  # fmt: skip
    # one driver for all designs: one formula evaluated; else both, picked per design
    varies = p.varies("drive.driver")
    drivers = np.unique(np.asarray(p["drive.driver"]))
    code = np.searchsorted(drivers, p["drive.driver"]).astype(float) if varies else 0.0
    columns, which = distinct([p.float(k) for k in keys] + [code], n)
    cols = dict(zip(keys, columns[:-1], strict=True))
    driver = drivers[columns[-1].astype(int)] if varies else p["drive.driver"]
    shared_grid = not p.varies("drive.input_gear_ratio")
    grid = sample_grid(period(p), samples) if shared_grid else None

    def fn(lo, hi):
        lam, u, i12, ph, m7, m8 = (cols[k][lo:hi, None] for k in keys)
        params = gb.GuideBar(lam, u, i12, ph, driver[lo:hi, None] if varies else driver)
        theta = grid if shared_grid else sample_grid(gb.period(params), samples)
        d1, d2, d3 = gb.impeller_rates(params, theta)  # (2, block, samples)
        torque = m7 * d1[0] + m8 * d1[1]
        return {
            "input_torque_min_Nm": torque.min(axis=1),
            "input_torque_max_Nm": torque.max(axis=1),
            "impeller_accel_peak_per_rad": np.abs(d2).max(axis=2).max(axis=0),
            "impeller_jerk_peak_per_rad2": np.abs(d3).max(axis=2).max(axis=0),
        }

    res = run_blocks(fn, columns[0].size, samples, threads)
    return {k: v[which] for k, v in res.items()}


def curves(p, points: int):
    """The :data:`CURVES` of admissible designs over one period: angle, dict (n, points).

    The angle is (points,) or, when ``drive.input_gear_ratio`` varies, (n, points).
    """
    n = p.n
    params = _drive(p, n)
    if p.varies("drive.input_gear_ratio"):
        theta = sample_grid(gb.period(params), points)
    else:
        theta = sample_grid(gb.period(params)[0, 0] if n else 2.0 * np.pi, points)
    d = gb.impeller_angles(params, theta)
    m7, m8 = (_column(p, k, n) for k in ("loads.impeller_torque_1", "loads.impeller_torque_2"))
    out = {
        "impeller1_angle_deg": np.degrees(d[0][0]),
        "impeller2_angle_deg": np.degrees(d[0][1]),
        "relative_angle_deg": np.degrees(d[0][1] - d[0][0]),
        "input_torque_Nm": m7 * d[1][0] + m8 * d[1][1],
    }
    for k, name in ((1, "speed_ratio"), (2, "accel_per_rad"), (3, "jerk_per_rad2")):
        out[f"impeller1_{name}"] = d[k][0]
        out[f"impeller2_{name}"] = d[k][1]
    return theta, out


def tolerance_hold(cfg: dict) -> tuple[dict, dict]:
    """Hold the vane angle at its nominal value (the drive's gamma_0) in a tolerance analysis."""
    if cfg["machine"].get("vane_angle") is None:
        g0 = metrics(Designs(cfg, {}, 1), ["vane_angle_deg"], 3)["vane_angle_deg"][0]
        cfg["machine"]["vane_angle"] = float(np.radians(g0))
    return cfg, {}
