"""The engine's dynamics and the drive's pair forces in the wobble-cam sweep kernel.

With the ideal cycle, on ``samples`` shaft angles per design (designs as (block, 1) columns
against the angles, in blocks on threads): the study's own functions, called on columns of
designs --

* :func:`rotorkin.drives.wobble_cam.engine.engine_state` (chamber volumes, strokes,
  pressures, the gas torques on the rotors and the shaft) and
  :func:`~rotorkin.drives.wobble_cam.engine.dynamics_summary` (torque extremes and ripple,
  equivalent inertia, energy fluctuation, flywheel); the rotors' peaks in time
  (:func:`rotorkin.studies.helpers.time_peaks`) on the run's ``run.points`` angles, as the
  study's columns;
* where the spherical cam fits the sphere: the forces in every pair
  (:func:`rotorkin.drives.wobble_cam.forces.solve`), the pairs' contact stresses, bearing
  loads, friction and mechanical efficiency (:func:`rotorkin.analysis.pairs.summary`) and
  the drive's own peaks (:func:`rotorkin.drives.wobble_cam.forces.summary`). Which rollers
  run between both walls of their groove (the crossings' keys) is found per geometry
  (plate tilt, roller axis angle, sphere radius: :func:`rotorkin.drives.wobble_cam.cam.guided`,
  a search along the walls), once for all the designs that share it.

Designs of one spin ratio and one number of pistons per block.
"""

from __future__ import annotations

import numpy as np

from rotorkin.analysis import engine_cycle as ec
from rotorkin.analysis import pairs as pr
from rotorkin.analysis.timing import shaft_speed
from rotorkin.core.batch import full, run_blocks, sample_grid
from rotorkin.drives.wobble_cam import cam as cs
from rotorkin.drives.wobble_cam import engine as eng
from rotorkin.drives.wobble_cam import forces as fo
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.machines import twin_rotor as tr
from rotorkin.studies.helpers import angle_grid, time_peak_keys, time_peaks

__all__ = ["DYNAMIC", "FORCES", "dynamics"]

_SLUGS = ("rotor1", "rotor2")
#: The engine's dynamics: torques, inertia and flywheel; the rotors' peaks in time.
DYNAMIC = eng.DYNAMICS_KEYS + time_peak_keys(_SLUGS)
#: The pairs' forces, contact stresses, friction and the drive's own peaks.
FORCES = pr.NUMBER_KEYS + fo.SUMMARY_KEYS
#: The machine's fields besides the compression ratio and the pistons.
_MACHINE = ("section", "inner_radius", "outer_radius", "axial_width", "mean_radius",
            "section_diameter", "clearance_volume", "inertia_shaft", "inertia_rotor_1",
            "inertia_rotor_2", "speed_fluctuation")  # fmt: skip


def dynamics(p, names, samples: int, threads, work, cam_args: dict, width=None) -> dict:
    """:data:`DYNAMIC` and, if ``names`` asks for any, :data:`FORCES` of the designs ``p``.

    ``work``: the designs' indicated work per turn [J] (the pairs' efficiency);
    ``cam_args``: the spherical cam's fields (:data:`rotorkin.drives.wobble_cam.cam.CAM_KEYS`);
    ``width``: the pistons' width as manufactured (a tolerance analysis), else None.
    Designs whose cam does not fit have no forces (NaN), as the study leaves them out.
    """
    n = p.n
    forces = bool(set(names) & set(FORCES))
    keys = DYNAMIC + (FORCES if forces else ())
    cols = {
        "tilt": p.float("drive.plate_tilt"),
        "alpha": p.float("drive.roller_axis_angle"),
        "radius": p.float("drive.sphere_radius"),
        "compression_ratio": p.float("machine.compression_ratio"),
        "work": work,
        **{key: p.float(f"loads.{key}") for key in ec.CYCLE_CHECKS},
        **{f: p.float(f"machine.{f}") for f in _MACHINE if f != "section"},
    }
    if width is not None:
        cols["width"] = width
    cols = {k: full(v, n) for k, v in cols.items()}
    cols["section"] = full(np.asarray(p["machine.section"]), n, dtype=str)
    spin = full(p.float("drive.spin_ratio"), n)
    pistons = full(np.asarray(p["machine.pistons_per_rotor"]), n, dtype=np.int64)
    fits = cs.cam_violation(cols["radius"], **cam_args) == 0
    theta = sample_grid(2.0 * np.pi, samples)
    run = p.cfg.get("run") or {}
    speed = run.get("speed", 3000.0 * np.pi / 30.0)
    omega = shaft_speed(theta, speed, 2.0 * np.pi)
    omega_mean = 2.0 * np.pi / np.trapezoid(1.0 / omega[0], theta)  # time average
    grid = angle_grid(2.0 * np.pi, run.get("points", 721))  # the study's columns
    ctx = {"theta": theta, "omega": omega, "omega_mean": omega_mean, "grid": grid,
           "grid_omega": shaft_speed(grid, speed, 2.0 * np.pi), "cfg": p.cfg,
           "cam_args": cam_args}  # fmt: skip
    if forces and fits.any():  # the force parameters and contact model: one for the sweep
        cam = cs.SphericalCam(float(cols["radius"][np.argmax(fits)]), **cam_args)
        ctx |= {"cam": cam, "fp": fo.force_params(p.cfg, cam),
                "model": pr.ContactModel.from_config(p.cfg)}  # fmt: skip
    out = {k: np.full(n, np.nan) for k in keys}
    kinds = np.stack([spin, pistons.astype(float), fits.astype(float)], axis=-1)
    for n_spin, count, fit in np.unique(kinds, axis=0):
        rows = np.flatnonzero((spin == n_spin) & (pistons == count) & (fits == bool(fit)))
        want = keys if fit else DYNAMIC

        def fn(lo, hi, rows=rows, n_spin=float(n_spin), count=int(count), want=want):
            c = {k: v[rows[lo:hi], None] for k, v in cols.items()}
            val = _block(c, n_spin, count, want, ctx)
            return {k: np.broadcast_to(val[k], (hi - lo,)) for k in want}

        res = run_blocks(fn, rows.size, samples * (4 if fit and forces else 1), threads)
        for k in want:
            out[k][rows] = res[k]
    return out


def _block(c: dict, n_spin: float, pistons: int, want, ctx: dict) -> dict:
    """The keys ``want`` of one block of designs (columns ``c`` of shape (block, 1))."""
    d = ctx["cfg"]["drive"]
    spin_a, spin_b = tuple(d.get("spin_a") or ()), tuple(d.get("spin_b") or ())
    drive = wc.WobbleCam(c["tilt"], c["alpha"], n_spin, c["radius"], pistons, spin_a, spin_b)
    machine = tr.TwinRotor(compression_ratio=c["compression_ratio"], pistons_per_rotor=pistons,
                           **{f: c[f] for f in _MACHINE})  # fmt: skip
    cycle = ec.IdealCycle(*(c[key] for key in ec.CYCLE_CHECKS))
    layout = wc.piston_layout(drive, c["compression_ratio"], c.get("width"))
    theta, omega = ctx["theta"], ctx["omega"]
    state = eng.engine_state(drive, machine, cycle, theta, layout)
    val = eng.dynamics_summary(machine, state, theta, omega, ctx["omega_mean"])
    val |= time_peaks(wc.motion(drive, ctx["grid"]), ctx["grid_omega"], _SLUGS)
    if set(want) & set(FORCES):
        cam, fp, model = ctx["cam"], ctx["fp"], ctx["model"]  # what solve and pairs read of
        # the cam (roller radius, groove depth) does not depend on the sphere radius
        f = fo.solve(drive, cam, fp, theta, state.member_torque, machine.member_inertias,
                     omega[0], omega[1])  # fmt: skip
        found = fo.pairs(f, cam, fp, model)
        val |= pr.summary(found, theta, c["work"][:, 0], model, omega[0], batch=True)
        val |= fo.summary(f, found, model, _guided(c, n_spin, pistons, spin_a, spin_b, ctx))
    return val


def _guided(c: dict, n_spin, pistons, spin_a, spin_b, ctx) -> np.ndarray:
    """Rollers between both walls of their groove, (4, block, angles): once per geometry."""
    geometry = np.concatenate([c["tilt"], c["alpha"], c["radius"]], axis=1)
    shapes, which = np.unique(geometry, axis=0, return_inverse=True)
    found = []
    for tilt, alpha, radius in shapes:
        drive = wc.WobbleCam(float(tilt), float(alpha), n_spin, float(radius), pistons, spin_a,
                             spin_b)  # fmt: skip
        cam = cs.SphericalCam(float(radius), **ctx["cam_args"])
        found.append(cs.guided(drive, cam, ctx["theta"]))
    return np.stack(found, axis=1)[:, which.reshape(-1)]
