"""The fuel-air cycle of the wobble-cam sweep kernel: every design's two closed parts.

Designs in blocks of :data:`CYCLE_BLOCK` (on threads, :func:`rotorkin.core.batch.run_blocks`):
the chamber volumes of a block from the drive's fused kinematics
(:func:`rotorkin.drives.wobble_cam.fast.rotor_kinematics`), its walls
(:func:`rotorkin.machines.fuel_air.walls_of`) and the single-zone cycle
(:func:`rotorkin.analysis.combustion.closed_cycle`), reduced to the block's metrics
(:func:`rotorkin.machines.fuel_air.summarize`) before the next block: the memory grows
with the designs' results, not with designs x steps.
"""

from __future__ import annotations

import math
import threading

import numpy as np

from rotorkin.analysis import combustion as cb
from rotorkin.core.batch import BLOCK_ELEMENTS, full, run_blocks
from rotorkin.core.fused import use_compiled
from rotorkin.drives.wobble_cam.fast import rotor_kinematics
from rotorkin.machines import fuel_air as fa

__all__ = ["CYCLE_BLOCK", "fuel_air_cycle"]


#: Designs per block of the fuel-air cycle (its working set, ~0.15 MB per design, stays
#: small): compiled, and as numpy operations (on longer arrays, fewer calls).
CYCLE_BLOCK = {"numba": 256, "numpy": 1024}
#: Designs per call of the kinematics within a block.
_KINEMATICS_BLOCK = 256
_SCRATCH = threading.local()


def fuel_air_cycle(p, n_f, per_rev, kind_a, beta, kvol, vc, vol_a, vol_b, disp, omega,
                    threads=None) -> dict:  # fmt: skip
    """The fuel-air cycle of every design: its two closed parts (kinds A and B) integrated.

    With the linear spin law the turning points are equally spaced, ``pi / (2|n|)``
    apart: chamber 1 (kind A) compresses from ``theta = 0`` on, chamber 2 (kind B) one
    stroke later; every chamber of a kind runs that part (the study's
    :func:`rotorkin.machines.fuel_air.charge_cycle`, which finds the parts of any law).
    The designs run in blocks of :data:`CYCLE_BLOCK` (on ``threads``): volumes, walls and
    the integration of a block, reduced to its metrics before the next.
    """
    loads = fa.loads_of(p.cfg.get("loads") or {})
    n = p.n
    per = {
        "tilt": p.float("drive.plate_tilt"),
        "alpha": p.float("drive.roller_axis_angle"),
        "spin": p.float("drive.spin_ratio"),
        "beta": beta, "kvol": kvol, "vc": vc, "n_f": n_f, "per_rev": per_rev, "disp": disp,
        "eps": np.where(kind_a, vol_a[1] / vol_a[0], vol_b[1] / vol_b[0]),
    }  # fmt: skip
    woschni = loads.heat_transfer == "woschni"
    if woschni:
        for k in ("inner_radius", "outer_radius", "axial_width", "mean_radius",
                  "section_diameter"):  # fmt: skip
            per[k] = p.float(f"machine.{k}")
        per["rect"] = np.asarray(p["machine.section"]) == "rectangular"
    per = {k: full(v, n) for k, v in per.items()}
    gas = loads.gas()
    steps = fa.steps_per_stroke(loads)
    block = CYCLE_BLOCK["numba" if use_compiled(n * 2 * (4 * steps + 1)) else "numpy"]

    def fn(lo, hi):
        return _cycle_block(loads, gas, steps, {k: v[lo:hi] for k, v in per.items()}, omega)

    return run_blocks(fn, n, BLOCK_ELEMENTS // block, threads)


def _scratch(shape) -> tuple:
    """This thread's arrays for the kinematics of ``shape`` (memory reused call after call)."""
    size = math.prod(shape)
    buf = getattr(_SCRATCH, "kinematics", None)
    if buf is None or buf.size < 10 * size:
        buf = _SCRATCH.kinematics = np.empty(10 * size)
    return buf[: 8 * size].reshape(4, 2, *shape), buf[8 * size : 10 * size].reshape(2, *shape)


def _volumes(d, half, stroke, volume, dvolume) -> None:
    """Chamber volumes and ``dV/dx`` of both closed parts on the grid ``half`` (in place)."""
    groups = np.unique(np.stack([d["spin"], d["n_f"]], axis=-1), axis=0)
    for n_spin, pistons in groups:
        rows = (slice(None) if len(groups) == 1
                else np.flatnonzero((d["spin"] == n_spin) & (d["n_f"] == pistons)))  # fmt: skip
        col = lambda v, rows=rows: v[rows, None, None]  # noqa: E731
        # kind A from theta = 0, kind B one stroke later
        theta = ((half + np.pi) / np.pi + np.arange(2.0)[:, None]) * col(stroke)
        rot, ch = rotor_kinematics(col(d["tilt"]), col(d["alpha"]), float(n_spin), theta,
                                   chamber=(col(d["beta"]), float(pistons)), threads=1,
                                   out=_scratch(theta.shape))  # fmt: skip
        kv = col(d["kvol"])
        volume[rows, 0] = kv[:, 0] * ch[0][:, 0] + col(d["vc"])[:, 0]
        volume[rows, 1] = kv[:, 0] * ch[1][:, 1] + col(d["vc"])[:, 0]
        dvolume[rows] = kv * (rot[1, 1] - rot[1, 0]) * (col(stroke) / np.pi)
        dvolume[rows, 1] *= -1.0  # delta_A = s - lo_a, delta_B = hi_b - s


def _cycle_block(loads, gas, steps, d, omega) -> dict:
    """The fuel-air cycle's metrics of one block of designs (arrays ``d`` of the block)."""
    m = d["tilt"].size
    half = np.linspace(-np.pi, np.pi, 4 * steps + 1)
    stroke = np.pi / (2.0 * np.abs(d["spin"]))  # shaft angle per stroke
    volume, dvolume = np.empty((m, 2, half.size)), np.empty((m, 2, half.size))
    for lo in range(0, m, _KINEMATICS_BLOCK):
        part = slice(lo, min(m, lo + _KINEMATICS_BLOCK))
        _volumes({k: v[part] for k, v in d.items()}, half, stroke[part], volume[part],
                 dvolume[part])  # fmt: skip
    charge = loads.charge()
    v_max, v_min = volume[..., 0], volume[..., 2 * steps]
    mass = cb.trapped_mass(charge, v_max, gas.gas_constant(0.0))
    heat = cb.heat_of_charge(charge, mass)
    wall = None
    if loads.heat_transfer == "woschni":
        keys = ("inner_radius", "outer_radius", "axial_width", "mean_radius", "section_diameter")
        sizes = [d[k][:, None] for k in keys]
        section = np.where(d["rect"], "rectangular", "circular")[:, None]
        kv = d["kvol"][:, None]
        rate = (v_max - v_min) / kv * omega / stroke[:, None]
        wall = fa.walls_of(section, *sizes, d["vc"][:, None], kv, volume,
                           np.broadcast_to((stroke / np.pi / omega)[:, None, None], volume.shape),
                           rate, loads.wall_temperature)  # fmt: skip
    with np.errstate(all="ignore"):
        res = cb.closed_cycle(half, volume, dvolume, mass=mass, heat=heat, gas=gas,
                              temperature=loads.intake_temperature, burn=loads.burn(),
                              walls=wall)  # fmt: skip
    res = {**res, "fuel": cb.fuel_energy(charge, mass), "mass": mass}
    weight = np.broadcast_to((d["n_f"] * d["per_rev"])[:, None], (m, 2))  # cycles per turn
    out = fa.summarize(loads, gas.label, res, v_max, v_min, weight, 1.0, d["disp"])
    pumping = (loads.intake_pressure - loads.ambient_pressure) * (v_max - v_min)
    work = res["work"] + pumping
    out.update({
        "indicated_work_per_cycle_a_J": work[:, 0],
        "indicated_work_per_cycle_b_J": work[:, 1],
        "otto_efficiency": 1.0 - d["eps"]**-0.4,
        "mean_torque_Nm": out["indicated_work_J"] / (2.0 * np.pi),
        "indicated_power_kW": out["indicated_work_J"] * omega / (2.0 * np.pi) / 1e3,
    })  # fmt: skip
    del out["gas_properties"]
    return out
