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
columns of designs (one call per block and number of blades).

Every formula is the drive's (:mod:`rotorkin.drives.rhomboid_cam.kinematics`) or the
machine's (:mod:`rotorkin.machines.rotary_blade`), called with arrays of parameters:
the kernel only gathers the designs' values; the summary keys and curves are built by
:mod:`rotorkin.drives.rhomboid_cam.summary`, as in the study.
"""

from __future__ import annotations

import numpy as np

from rotorkin.analysis.timing import shaft_speed
from rotorkin.core.batch import flag, full, run_blocks, sample_grid
from rotorkin.drives.rhomboid_cam import engine
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.drives.rhomboid_cam import summary as rs
from rotorkin.drives.rhomboid_cam.schema import RotaryBladeMachine
from rotorkin.machines import rotary_blade as rb
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
    }
)

_METRICS = rs.LAW_KEYS + rs.GEOMETRY_KEYS

CURVES = rs.CURVE_KEYS
ANGLE = ("alpha_deg", "Output-shaft angle alpha: polar angle of diagonal OA, from +x.")

_MACHINE = ("blade_thickness", "inner_radius", "outer_radius", "axial_width", "blades_per_pair")
_INERTIAS = ("inertia_shaft", "inertia_blade_pair_1", "inertia_blade_pair_2")
#: Keys of the engine's dynamics (linear torque model only; sampled).
_DYNAMIC = rs.DYNAMICS_KEYS + rs.TIME_KEYS


def unsupported(cfg: dict) -> str | None:
    """Why the kernel cannot evaluate designs on this base config (None: it can)."""
    d = cfg["drive"]
    if d.get("a") or d.get("b"):
        return "drive.a / drive.b hold higher harmonics (their stationary points vary per design)"
    return None


def _linear(cfg: dict) -> bool:
    """The base config's loads follow the linear torque model (eq. 29)."""
    return (cfg.get("loads") or {}).get("pressure_model", "linear") in (None, "linear")


def metric_names(cfg: dict) -> tuple[str, ...]:
    """Summary keys the kernel computes (the dynamics under the linear torque model)."""
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
    if names & set(rs.PEAK_KEYS):
        val.update(_sampled(full(L, n), full(pm, n), samples, threads))
    if names & set(_DYNAMIC):
        val.update(_dynamics(p, samples, threads))
    return {name: full(val[name], n) for name in names}


def _dynamics(p, samples: int, threads) -> dict:
    """The :data:`_DYNAMIC` keys on ``samples`` shaft angles per design (linear model).

    Designs of one number of blades at a time (it sets the number of chambers); the
    study's :func:`~rotorkin.drives.rhomboid_cam.engine.machine_state` and
    :func:`~rotorkin.drives.rhomboid_cam.summary.dynamics_summary` on (block, 1) columns.
    """
    n = p.n
    alpha = sample_grid(rc.period(p), samples)
    omega = shaft_speed(alpha, p.cfg["run"]["speed"], rc.period(p))
    cols = {k: full(p.float(k), n) for k in ("drive.link_length", "drive.psi_min",
                                             "loads.torque_high", "loads.torque_low")}  # fmt: skip
    for k in (*_MACHINE[:4], *_INERTIAS, "speed_fluctuation"):
        cols[k] = full(_value(p, f"machine.{k}"), n)
    blades = full(np.asarray(p["machine.blades_per_pair"]), n, dtype=np.int64)
    out = {k: np.empty(n) for k in _DYNAMIC}
    for count in np.unique(blades):
        rows = np.flatnonzero(blades == count)

        def fn(lo, hi, rows=rows, count=int(count)):
            c = {k: v[rows[lo:hi], None] for k, v in cols.items()}
            params = rc.RhomboidCam(c["drive.link_length"], c["drive.psi_min"])
            machine = rb.RotaryBlade(**{k: c[k] for k in (*_MACHINE[:4], *_INERTIAS)},
                                     blades_per_pair=count)  # fmt: skip
            high, low = c["loads.torque_high"], c["loads.torque_low"]
            st = engine.machine_state(params, machine, engine.Loads("linear", high, low), alpha)
            work = rc.indicator_work(c["drive.psi_min"][:, 0], (), (), high[:, 0], low[:, 0])
            val, _ = rs.dynamics_summary(machine, alpha, st.motion, st.members, st.torque,
                                         omega, c["speed_fluctuation"][:, 0], work)  # fmt: skip
            val.update(time_peaks(st.motion, omega, rs.SLUGS))
            return {k: np.broadcast_to(val[k], (hi - lo,)) for k in _DYNAMIC}

        res = run_blocks(fn, rows.size, samples, threads)
        for k in _DYNAMIC:
            out[k][rows] = res[k]
    return out


def _sampled(L, psi_min, samples, threads) -> dict:
    """The :data:`~.summary.PEAK_KEYS` on ``samples`` shaft angles per design, in blocks."""
    alpha = sample_grid(np.pi, samples)

    def fn(lo, hi):
        return rc.law_peaks(L[lo:hi, None], psi_min[lo:hi, None], (), (), alpha)

    return rs.peak_summary(run_blocks(fn, L.size, samples, threads))


def curves(p, points: int):
    """The :data:`CURVES` of admissible designs over a period: angle (points,), dict (n, points)."""
    alpha = sample_grid(np.pi, points)
    L = full(p.float("drive.link_length"), p.n)[:, None]
    pm = full(p.float("drive.psi_min"), p.n)[:, None]
    return alpha, rs.law_curves(L, pm, (), (), alpha)
