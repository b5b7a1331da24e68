"""Sweep kernel of the rotary-blade engine on the rhomboid lever-cam converter, by broadcasting.

The summary keys of :mod:`rotorkin.drives.rhomboid_cam.study` for arrays of designs
with the first-harmonic law (eq. 16, ``drive.a = drive.b = []``; higher
harmonics move the stationary points of ``psi`` per design, and such configs
fall back to the scalar study): ``psi`` extremes (0 and 90 deg), the cam
profile radii, the indicator work (eq. 26-28, Gauss-Legendre on the two
monotone halves, as the study), the blade-pair and engine-volume quantities in
closed form, and, sampled on ``samples`` shaft angles per design, the peaks of
the blade speed, acceleration and jerk coefficients and the pitch-curve
curvature (:func:`~rotorkin.drives.rhomboid_cam.kinematics.law_peaks` over a
design x angle array). Under the linear torque model (eq. 29), also sampled: the
engine's work, power, shaft torques with and without the inertias, equivalent
inertia, energy fluctuation and flywheel
(:func:`~rotorkin.drives.rhomboid_cam.summary.dynamics_summary`) and the blade
pairs' peaks in time (:func:`~rotorkin.studies.helpers.time_peaks`), from the
study's own :func:`~rotorkin.drives.rhomboid_cam.engine.machine_state` on
columns of designs (one call per block and number of blades); and the converter's
forces (:func:`~rotorkin.drives.rhomboid_cam.forces.machine_pairs` on the same
columns), its pairs' contact stresses, bearing loads, friction and efficiency
(:func:`rotorkin.analysis.pairs.summary`). Under the Stirling
models (adiabatic, schmidt) the same keys and the models' own (heat in and out, gas
mass, pressures, efficiencies): the circuits of up to :data:`STIRLING_BLOCK` designs
of one number of blades and one gas solved in one run
(:func:`~rotorkin.machines.rotary_blade_stirling.stirling_solution` on columns;
each design's cycle is the one it has alone).

Every formula is the drive's (:mod:`rotorkin.drives.rhomboid_cam.kinematics`) or the
machine's (:mod:`rotorkin.machines.rotary_blade`), called with arrays of parameters:
the kernel only gathers the designs' values; the summary keys and curves are built by
:mod:`rotorkin.drives.rhomboid_cam.summary`, as in the study.
"""

from __future__ import annotations

import functools

import numpy as np

from rotorkin.analysis import pairs as ap
from rotorkin.analysis.timing import shaft_speed
from rotorkin.core.batch import distinct, flag, full, run_blocks, sample_grid
from rotorkin.drives.rhomboid_cam import engine
from rotorkin.drives.rhomboid_cam import forces as rf
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.drives.rhomboid_cam import summary as rs
from rotorkin.drives.rhomboid_cam.schema import RotaryBladeMachine, with_defaults
from rotorkin.machines import rotary_blade as rb
from rotorkin.machines import rotary_blade_stirling as rbs
from rotorkin.studies.helpers import time_peaks

__all__ = ["DRIVE", "KEYS", "CURVES", "ANGLE", "unsupported", "metric_names", "reasons",
           "metrics", "curves", "period"]  # fmt: skip

DRIVE = "rhomboid_cam"

KEYS = frozenset(
    {
        "drive.link_length",
        "drive.psi_min",
        "loads.torque_high",
        "loads.torque_low",
        "machine.blade_thickness",
        "machine.blades_per_pair",
        "machine.inner_radius",
        "machine.outer_radius",
        "machine.axial_width",
        "machine.inertia_shaft",
        "machine.inertia_blade_pair_1",
        "machine.inertia_blade_pair_2",
        "machine.speed_fluctuation",
        *(f"loads.{k}" for k in rbs.STIRLING_CHECKS if k != "pressure_model"),
    }
)

_METRICS = rs.LAW_KEYS + rs.GEOMETRY_KEYS

CURVES = rs.CURVE_KEYS
ANGLE = ("alpha_deg", "Output-shaft angle alpha: polar angle of diagonal OA, from +x.")

_MACHINE = ("blade_thickness", "inner_radius", "outer_radius", "axial_width", "blades_per_pair")
_INERTIAS = ("inertia_shaft", "inertia_blade_pair_1", "inertia_blade_pair_2")
#: Keys of the engine's dynamics, its pairs' contact, bearing and friction and the
#: converter's forces (linear torque model and Stirling models; sampled).
_DYNAMIC = rs.DYNAMICS_KEYS + rs.TIME_KEYS + ap.NUMBER_KEYS + rf.SUMMARY_KEYS
#: Keys of the Stirling models (adiabatic, schmidt): their circuits' cycle per design.
_STIRLING = tuple(k for k in rbs.NUMBER_KEYS if k != "indicated_work_J") + (
    "pressure_max_bar", "pressure_min_bar")  # fmt: skip
#: The loads' fields of the Stirling models the kernel reads per design.
_GAS = ("charge_pressure", "hot_temperature", "cold_temperature", "phase_angle",
        "regenerator_effectiveness")  # fmt: skip
_DEAD = ("heater_volume", "regenerator_volume", "cooler_volume")
#: Designs per solve of a Stirling model's circuits (the ideal adiabatic cycle's cost is
#: numpy's per-call overhead up to a few hundred designs; ~0.4 MB per design and circuit).
STIRLING_BLOCK = 128


def unsupported(cfg: dict) -> str | None:
    """Why the kernel cannot evaluate designs on this base config (None: it can)."""
    d = cfg["drive"]
    if d.get("a") or d.get("b"):
        return "drive.a / drive.b hold higher harmonics (their stationary points vary per design)"
    return None


def _model(cfg: dict) -> str:
    """The base config's pressure model (``linear``: the paper's torque model, eq. 29)."""
    return (cfg.get("loads") or {}).get("pressure_model") or "linear"


def _linear(cfg: dict) -> bool:
    """The base config's loads follow the linear torque model (eq. 29)."""
    return _model(cfg) == "linear"


def _stirling(cfg: dict) -> bool:
    """The base config's loads are a Stirling model (adiabatic or schmidt)."""
    return _model(cfg) in ("adiabatic", "schmidt")


def metric_names(cfg: dict) -> tuple[str, ...]:
    """Summary keys the kernel computes (the dynamics under the linear torque model and
    the Stirling models, and the Stirling models' cycle)."""
    if _stirling(cfg):
        return _METRICS + _DYNAMIC + _STIRLING
    return _METRICS + (_DYNAMIC if _linear(cfg) else ())


def period(p) -> float:
    """Period of psi in the output-shaft angle [rad] (:func:`~.kinematics.period`: pi)."""
    return rc.period(p)


def reasons(p, code: dict) -> np.ndarray:
    """Reason code per design (0: admissible), in the order of the study's checks.

    The drive's :func:`~rotorkin.drives.rhomboid_cam.kinematics.violation`; under the
    linear torque model, a law leaving ``psi_min <= psi <= psi_max`` (eq. 2,
    :func:`~rotorkin.drives.rhomboid_cam.kinematics.psi_range_violation`) flagged
    ``drive.a`` (``drive.b`` when ``a`` is empty) as the study refuses it; the machine's
    :func:`~rotorkin.machines.rotary_blade.violation` and, for the drive's swing of
    ``psi``, :func:`~rotorkin.machines.rotary_blade.swing_violation`.
    """
    r = np.zeros(p.n, dtype=np.int16)
    with np.errstate(all="ignore"):
        pm = p.float("drive.psi_min")
        _report(r, rc.violation(p.float("drive.link_length"), pm), rc.CHECKS, "drive", code)
        a, b = tuple(p["drive.a"] or ()), tuple(p["drive.b"] or ())
        if p["loads.pressure_model"] in (None, "linear"):
            key = "drive.a" if a else "drive.b"
            flag(r, rc.psi_range_violation(pm, a, b), code[key])
        m = {k: p[f"machine.{k}"] for k in _MACHINE}
        _report(r, rb.violation(**m, **{k: _value(p, f"machine.{k}") for k in _INERTIAS}),
                rb.CHECKS, "machine", code)  # fmt: skip
        cs = np.asarray(_value(p, "machine.speed_fluctuation"), dtype=float)
        flag(r, ~((cs > 0.0) & (cs < 1.0)), code.get("machine.speed_fluctuation", code["other"]))
        lo, _, hi, _ = rc.psi_extremes(pm)
        swing = rb.swing_violation(m["blades_per_pair"], m["blade_thickness"], lo, hi)
        _report(r, swing, rb.SWING_CHECKS, "machine", code)
    return r


def _report(r, violation, names, section, code) -> None:
    """Flag the designs whose ``violation`` code points at ``names[i - 1]``."""
    for i, name in enumerate(names, start=1):
        key = f"{section}.{name}"
        if key in code:
            flag(r, violation == i, code[key])


def _value(p, key: str):
    """``p[key]`` as floats, the schema's default where the base config leaves it out."""
    if p[key] is None:
        return float(RotaryBladeMachine().model_dump()[key.split(".", 1)[1]])
    return p.float(key)


def _machine(p) -> rb.RotaryBlade:
    """The designs' machines, one holder of arrays (admissible designs only)."""
    m = {k: p.float(f"machine.{k}") for k in _MACHINE}
    m["blades_per_pair"] = np.asarray(m["blades_per_pair"]).astype(np.int64)
    return rb.RotaryBlade(**m)


def metrics(p, names, samples: int, threads: int | None = None) -> dict:
    """Summary metrics of admissible designs ``p``, arrays (n,)."""
    names = set(names)
    n = p.n
    L, pm = p.float("drive.link_length"), p.float("drive.psi_min")
    m1, m2 = p.float("loads.torque_high"), p.float("loads.torque_low")
    val = rs.law_summary(L, full(pm, n), (), (), full(m1, n), full(m2, n))
    lo, _, hi, _ = rc.psi_extremes(pm)
    revs = 2.0 * np.pi / period(p)  # periods per output-shaft revolution
    travel = revs * rc.psi_total_variation(pm)
    val.update(rs.engine_geometry_summary(_machine(p), lo, hi, travel))
    if _stirling(p.cfg):  # the hot and the cold set: twice one set's displacement
        val["displacement_cm3_per_rev"] = 2.0 * val["displacement_cm3_per_rev"]
    if names & set(rs.PEAK_KEYS):
        val.update(_sampled(L, pm, n, samples, threads))
    if names & set(_DYNAMIC + _STIRLING):
        val.update(_dynamics(p, samples, threads))
    return {name: full(val[name], n) for name in names}


def _dynamics(p, samples: int, threads) -> dict:
    """The :data:`_DYNAMIC` keys on ``samples`` shaft angles per design, and under a
    Stirling model its :data:`_STIRLING` keys.

    Designs of one number of blades (it sets the number of chambers) and one gas at a
    time; the study's :func:`~rotorkin.drives.rhomboid_cam.engine.machine_state` and
    :func:`~rotorkin.drives.rhomboid_cam.summary.dynamics_summary` on (block, 1)
    columns; a Stirling model's circuits by
    :func:`~rotorkin.machines.rotary_blade_stirling.stirling_solution` on the block's
    columns (every design's cycle as it is alone).
    """
    n = p.n
    stirling = _stirling(p.cfg)
    keys = _DYNAMIC + (_STIRLING if stirling else ())
    alpha = sample_grid(rc.period(p), samples)
    omega = shaft_speed(alpha, p.cfg["run"]["speed"], rc.period(p))
    cfg = with_defaults(p.cfg)  # the pairs' keys, the same for every design
    contact = (
        rf.check_roller(cfg["cam"]["roller_radius"]),
        float(cfg["contact"]["bearing_radius"]),
    )
    model = ap.ContactModel.from_config(cfg)
    cols = {k: full(p.float(k), n) for k in ("drive.link_length", "drive.psi_min",
                                             "loads.torque_high", "loads.torque_low")}  # fmt: skip
    for k in (*_MACHINE[:4], *_INERTIAS, "speed_fluctuation"):
        cols[k] = full(_value(p, f"machine.{k}"), n)
    blades = full(np.asarray(p["machine.blades_per_pair"]), n, dtype=np.int64)
    gases = np.array([None])
    gas_of = np.zeros(n, dtype=np.int64)
    if stirling:
        for k in _GAS + tuple(k for k in _DEAD if p[f"loads.{k}"] is not None):
            cols[k] = full(p.float(f"loads.{k}"), n)
        gas = full(np.asarray(p["loads.gas"], dtype=object), n, dtype=object)
        gases, gas_of = np.unique(gas.astype(str), return_inverse=True)
    # the stationary points of the first-harmonic law: the same for every psi_min
    turning = len(rc.psi_stationary_points(float(cols["drive.psi_min"][0]), (), ())) - 1
    out = {k: np.empty(n) for k in keys}
    kinds = np.stack([blades, gas_of.reshape(-1)], axis=-1)
    for count, g in np.unique(kinds, axis=0):
        rows = np.flatnonzero((blades == count) & (gas_of.reshape(-1) == g))
        count, gas = int(count), str(gases[g])
        # a Stirling model's circuits for many designs per solve (its cost is nearly that
        # of one design up to a few hundred); the fine grid's state in smaller blocks
        step = STIRLING_BLOCK if stirling else rows.size
        for first in range(0, rows.size, step):
            part = rows[first : first + step]
            sol = None
            if stirling:
                sol = _circuits(p, *_design({k: v[part, None] for k, v in cols.items()}, count),
                                gas, turning)  # fmt: skip

            def fn(lo, hi, part=part, sol=sol, count=count):
                c = {k: v[part[lo:hi], None] for k, v in cols.items()}
                params, machine, c = _design(c, count)
                high, low = c["loads.torque_high"], c["loads.torque_low"]
                if sol is not None:
                    block = rbs.select(sol, slice(lo, hi))
                    loads = engine.Loads(_model(p.cfg), high, low, block.loads, None, block)
                    work = np.sum(block.cycle.work, axis=0)
                else:
                    loads = engine.Loads("linear", high, low)
                    work = rc.indicator_work(c["drive.psi_min"][:, 0], (), (), high[:, 0],
                                             low[:, 0])  # fmt: skip
                st = engine.machine_state(params, machine, loads, alpha)
                val, _ = rs.dynamics_summary(machine, alpha, st.motion, st.members, st.torque,
                                             omega, c["speed_fluctuation"][:, 0], work)  # fmt: skip
                val.update(time_peaks(st.motion, omega, rs.SLUGS))
                drive = engine.drive_torque(machine, st, omega)
                found, fo = rf.machine_pairs(params, machine, alpha, st.members, drive, *contact)
                val.update(ap.summary(found, alpha, val["indicated_work_J"], model, omega[0],
                                      batch=True))  # fmt: skip
                val.update(rf.force_summary(fo))
                if sol is not None:
                    numbers = rbs.stirling_numbers(block, 2.0 * np.pi / rc.period(params))
                    val.update({k: v for k, v in numbers.items() if k != "indicated_work_J"})
                    val["pressure_max_bar"] = np.max(st.pressure, axis=(0, -1)) * 1e-5
                    val["pressure_min_bar"] = np.min(st.pressure, axis=(0, -1)) * 1e-5
                return {k: np.broadcast_to(val[k], (hi - lo,)) for k in keys}

            res = run_blocks(fn, part.size, samples, threads)
            for k in keys:
                out[k][part] = res[k]
    return out


def _design(c: dict, count: int):
    """The drive's parameters and the machine of columns ``c`` (``(m, 1)`` arrays)."""
    params = rc.RhomboidCam(c["drive.link_length"], c["drive.psi_min"])
    machine = rb.RotaryBlade(**{k: c[k] for k in (*_MACHINE[:4], *_INERTIAS)},
                             blades_per_pair=count)  # fmt: skip
    return params, machine, c


def _circuits(p, params, machine, c, gas, turning):
    """The Stirling circuits of a block of designs (columns ``c``; one gas)."""
    dead = {k: c[k][:, 0] if k in c else None for k in _DEAD}
    loads = rbs.StirlingColumns(**{k: c[k][:, 0] for k in _GAS}, **dead,
                                pressure_model=_model(p.cfg), gas=gas)  # fmt: skip
    lo, _, hi, _ = rc.psi_extremes(c["drive.psi_min"])
    v_min, v_max = rb.class_volume_range(machine, lo, hi)
    swept = np.max(v_max - v_min, axis=0)[:, 0]
    motion = functools.partial(rc.motion, params)
    return rbs.stirling_solution(machine, loads, motion, rc.period(params), turning // 2, swept)


def _sampled(L, psi_min, n: int, samples, threads) -> dict:
    """The :data:`~.summary.PEAK_KEYS` on ``samples`` shaft angles per design (n,), in
    blocks, once per distinct (link length, minimum rhomboid angle)."""
    (L, psi_min), which = distinct((L, psi_min), n)
    alpha = sample_grid(np.pi, samples)

    def fn(lo, hi):
        return rc.law_peaks(L[lo:hi, None], psi_min[lo:hi, None], (), (), alpha)

    peaks = rs.peak_summary(run_blocks(fn, L.size, samples, threads))
    return {k: np.asarray(v)[which] for k, v in peaks.items()}


def curves(p, points: int):
    """The :data:`CURVES` of admissible designs over a period: angle (points,), dict (n, points)."""
    alpha = sample_grid(np.pi, points)
    L = full(p.float("drive.link_length"), p.n)[:, None]
    pm = full(p.float("drive.psi_min"), p.n)[:, None]
    return alpha, rs.law_curves(L, pm, (), (), alpha)
