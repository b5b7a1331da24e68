"""Sweep kernel of the opposed-piston reactor on double eccentric discs, by broadcasting.

The summary keys of :mod:`rotorkin.drives.eccentric_cam.study` for arrays of designs:
the gap change at 90 deg (eq. 5, 6; the contact radius ``Rc = R``, ``R + r`` or
infinite for a flat face), the stroke, the pressure angle, the reactor's volume
extremes and pressures (closed forms), and the peaks of the piston velocity,
acceleration and jerk coefficients sampled on ``samples`` shaft angles (the
drive's :func:`~rotorkin.drives.eccentric_cam.kinematics.harmonic_travel` and
:func:`~rotorkin.drives.eccentric_cam.kinematics.additional_travel`, broadcast over a
design x angle array).

The torques, inertia and flywheel keys, the pistons' peaks in time, and the contact,
bearing, friction and efficiency keys come from the study's own functions
(:func:`~rotorkin.drives.eccentric_cam.reactor.reactor_summary`,
:func:`~rotorkin.drives.eccentric_cam.forces.forces_summary`) called with the designs
as columns ``(d, 1)`` against the ``samples`` shaft angles, in blocks of designs and
once per follower (each follower has its own pairs). With the default ``samples``
(20 001, the study's grid) every key equals the study's, the angle of the peak contact
stress included.
"""

from __future__ import annotations

import numpy as np

from rotorkin.analysis import pairs as ap
from rotorkin.analysis.pairs import KINDS, ContactModel
from rotorkin.analysis.timing import SPEED_MAX, SPEED_MIN
from rotorkin.core.batch import distinct, flag, full, run_blocks, sample_grid
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.drives.eccentric_cam.curves import drive_curves
from rotorkin.drives.eccentric_cam.forces import forces_summary
from rotorkin.drives.eccentric_cam.reactor import (
    closed_forms,
    opposed_piston,
    reactor_state,
    reactor_summary,
)
from rotorkin.machines import opposed_piston as op
from rotorkin.studies.helpers import time_peaks

__all__ = ["DRIVE", "KEYS", "CURVES", "ANGLE", "unsupported", "metric_names", "reasons",
           "metrics", "curves", "period"]  # fmt: skip

DRIVE = "eccentric_cam"

KEYS = frozenset(
    {
        "drive.disc_radius",
        "drive.eccentricity",
        "drive.follower",
        "drive.roller_radius",
        "machine.device_length",
        "machine.bore",
        "machine.fluid",
        "machine.initial_pressure",
        "machine.polytropic_exponent",
        "machine.bulk_modulus",
        "machine.back_pressure",
        "machine.piston_mass",
        "machine.inertia_shaft",
        "machine.speed_fluctuation",
        "drive.tip_radius",
        "run.speed",
        "contact.youngs_modulus",
        "contact.poisson_ratio",
        "contact.allowable_stress",
        "contact.roller_width",
        "contact.bearing_radius",
        *(f"contact.friction_{kind}" for kind in KINDS),
    }
)

_METRICS = (
    "lambda",
    "lambda_contact",
    "gap_change_min_mm",
    "gap_change_min_ratio",
    "gap_change_min_angle_deg",
    "gap_change_to_length",
    "gap_change_to_length_percent",
    "gap_change_min_knife_edge_mm",
    "piston_stroke_mm",
    "piston_velocity_peak_mm_per_rad",
    "piston_accel_peak_mm_per_rad2",
    "piston_jerk_peak_mm_per_rad3",
    "pressure_angle_max_deg",
    "device_length_mm",
    "bore_mm",
    "piston_area_cm2",
    "enclosed_volume_min_cm3",
    "enclosed_volume_max_cm3",
    "chamber_volume_min_cm3",
    "chamber_volume_max_cm3",
    "volume_change_cm3",
    "volume_change_relative",
    "compression_ratio_geometric",
    "initial_pressure_bar",
    "pressure_max_bar",
    "pressure_min_bar",
    "pressure_ripple_bar",
    "pressure_ripple_relative",
    "cavitation",
)

#: Keys of the reactor's torques, inertia and flywheel (:func:`reactor_summary`).
_REACTOR = (
    "back_pressure_bar",
    "piston_force_peak_N",
    "indicated_work_J",
    "mean_torque_Nm",
    "shaft_torque_min_Nm",
    "shaft_torque_max_Nm",
    "shaft_torque_peak_Nm",
    "shaft_torque_with_inertia_peak_Nm",
    "inertia_torque_peak_Nm",
    "equivalent_inertia_mean_kgm2",
    "energy_fluctuation_J",
    "speed_fluctuation_without_flywheel",
    "speed_fluctuation",
    "flywheel_inertia_kgm2",
)
#: The pistons' peaks in time and the mean shaft speed (the study's ``time_domain``).
_SLUGS = ("piston_left", "piston_right")
_TIME = (
    *(f"{s}_{what}_peak_{u}" for s in _SLUGS
      for what, u in (("speed", "m_per_s"), ("accel", "m_per_s2"), ("jerk", "m_per_s3"))),
    "shaft_speed_mean_rpm",
)  # fmt: skip
#: Contact, bearing, friction, efficiency and the drive's own force keys (:func:`forces_summary`).
_FORCES = (
    *ap.NUMBER_KEYS,
    "work_through_drive_J",
    "follower_force_peak_N",
    "follower_force_min_N",
    "follower_lift_off",
    "side_thrust_peak_N",
    "guide_tilting_moment_peak_Nm",
    "shaft_radial_load_peak_N",
)
_DYNAMIC = frozenset(_REACTOR + _TIME + _FORCES)

CURVES = (
    "z_left_mm",
    "z_right_mm",
    "gap_change_mm",
    "x_left",
    "x_right",
    "xi",
    "mu",
    "delta",
    "z_left_velocity_mm_per_rad",
    "z_right_velocity_mm_per_rad",
    "z_left_accel_mm_per_rad2",
    "z_right_accel_mm_per_rad2",
    "z_left_jerk_mm_per_rad3",
    "z_right_jerk_mm_per_rad3",
    "pressure_angle_left_deg",
)
ANGLE = ("beta_deg", "Shaft angle beta; 0 puts the left piston at its top (+e).")


def unsupported(cfg: dict) -> str | None:
    """Why the kernel cannot evaluate designs on this base config (None: it can)."""
    if cfg["drive"].get("eccentricity") is None:
        return "the eccentricity is set by the adjuster (drive.slide), not drive.eccentricity"
    return None


def metric_names(cfg: dict) -> tuple[str, ...]:
    """Summary keys the kernel computes."""
    return _METRICS + _REACTOR + _TIME + _FORCES


def period(p) -> float:
    """Period of the pistons' motion: one shaft turn [rad]."""
    return 2.0 * np.pi


def _drive(p, column: bool = False) -> ec.EccentricCam:
    """The drives of the designs ``p``: fields (n,), or (n, 1) with ``column``."""

    def col(v):
        v = np.asarray(v)
        return v[:, None] if column and v.ndim else v

    return ec.EccentricCam(
        col(p.float("drive.disc_radius")),
        col(p.float("drive.eccentricity")),
        col(p["drive.follower"]),
        col(p.float("drive.roller_radius")),
    )


_MACHINE = ("device_length", "bore", "fluid", "initial_pressure", "polytropic_exponent",
            "bulk_modulus", "back_pressure")  # fmt: skip


def _machine_values(p) -> dict:
    return {k: p[f"machine.{k}"] if k == "fluid" else p.float(f"machine.{k}") for k in _MACHINE}


def reasons(p, code: dict) -> np.ndarray:
    """Reason code per design (0: admissible), in the order of the study's checks.

    The drive's :func:`~rotorkin.drives.eccentric_cam.kinematics.invalid_parameter`,
    then the reactor's :func:`~rotorkin.machines.opposed_piston.invalid_parameter`.
    """
    r = np.zeros(p.n, dtype=np.int16)
    drive = ec.invalid_parameter(
        p.float("drive.disc_radius"),
        p.float("drive.eccentricity"),
        p["drive.follower"],
        p.float("drive.roller_radius"),
    )
    machine = op.invalid_parameter(
        **_machine_values(p),
        gap_change_min=0.0,
        piston_stroke=2.0 * p.float("drive.eccentricity"),
    )
    for section, bad in (("drive", drive), ("machine", machine)):
        for name in np.unique(bad[bad != ""]):
            flag(r, bad == name, code.get(f"{section}.{name}", code["other"]))
    for key, bad in _dynamic_refusals(p):
        flag(r, bad, code.get(key, code["other"]))
    return r


def _dynamic_refusals(p):
    """What the study refuses after the drive and the reactor, in its order: the inertias,
    the shaft speed, the wanted speed fluctuation, the contact materials."""
    with np.errstate(invalid="ignore"):
        for key in ("machine.inertia_shaft", "machine.piston_mass"):
            v = np.asarray(p.float(key))
            yield key, ~(np.isfinite(v) & (v >= 0.0))
        speed = p["run.speed"]
        if np.ndim(speed) == 0 or p.varies("run.speed"):  # a profile is checked with the base
            w = np.asarray(speed, dtype=float)
            slack = 1e-12  # as analysis.timing.shaft_speed
            yield "run.speed", ~((w >= SPEED_MIN * (1 - slack)) & (w <= SPEED_MAX * (1 + slack)))
        c = np.asarray(p.float("machine.speed_fluctuation"))
        yield "machine.speed_fluctuation", ~((c > 0.0) & (c < 1.0))
        e = np.asarray(p.float("contact.youngs_modulus"))
        yield "contact.youngs_modulus", ~(np.isfinite(e) & (e > 0.0))
        nu = np.asarray(p.float("contact.poisson_ratio"))
        yield "contact.poisson_ratio", ~((nu >= 0.0) & (nu < 0.5))


def metrics(p, names, samples: int, threads: int | None = None) -> dict:
    """Summary metrics of admissible designs ``p``, arrays (n,)."""
    names = set(names)
    n = p.n
    drive = _drive(p)
    rx = opposed_piston(drive, **_machine_values(p))
    val = closed_forms(drive, rx)
    val["cavitation"] = val["cavitation"].astype(float)
    peaks = {"piston_velocity_peak_mm_per_rad", "piston_accel_peak_mm_per_rad2",
             "piston_jerk_peak_mm_per_rad3"}  # fmt: skip
    if names & peaks:
        val.update(_peaks(drive.contact_radius, drive.eccentricity, n, samples, threads))
    if names & _DYNAMIC:
        val.update(_dynamic(p, sorted(names & _DYNAMIC), samples, threads))
    return {name: full(val[name], n) for name in names}


def _dynamic(p, names, samples, threads) -> dict:
    """The :data:`_DYNAMIC` keys ``names``, arrays (n,): one pass per follower."""
    follower = p["drive.follower"]
    if not p.varies("drive.follower"):
        return _dynamic_follower(p, str(follower), names, samples, threads)
    out = {name: np.full(p.n, np.nan) for name in names}
    for kind in np.unique(follower):
        at = np.flatnonzero(follower == kind)
        part = _dynamic_follower(p.take(at), str(kind), names, samples, threads)
        for name in names:
            out[name][at] = part[name]
    return out


def _dynamic_follower(p, follower: str, names, samples, threads) -> dict:
    """The :data:`_DYNAMIC` keys ``names`` of designs ``p`` with one ``follower``."""
    n = p.n
    beta = sample_grid(2.0 * np.pi, samples)
    keys = ("drive.disc_radius", "drive.eccentricity", "drive.roller_radius", "drive.tip_radius",
            "machine.piston_mass", "machine.inertia_shaft", "machine.speed_fluctuation",
            "contact.youngs_modulus", "contact.poisson_ratio", "contact.roller_width",
            "contact.allowable_stress", "contact.bearing_radius",
            *(f"contact.friction_{kind}" for kind in KINDS))  # fmt: skip
    values = {k: 0.0 if p[k] is None else p.float(k) for k in keys}  # no tip: an edge
    machine = _machine_values(p)
    speed = p.float("run.speed") if p.varies("run.speed") else p["run.speed"]

    def fn(lo, hi):
        def col(v):  # a varying value as a column (d, 1) against the angles
            return v[lo:hi, None] if np.ndim(v) else v

        v = {k: col(x) for k, x in values.items()}
        # the disc as columns (d, 1) even where no drive value varies: every curve then
        # carries the design axis, as the machine's values do (members first: (2, d, m))
        rd, e = (
            np.broadcast_to(v[k], (hi - lo, 1)) for k in ("drive.disc_radius", "drive.eccentricity")
        )
        drive = ec.EccentricCam(rd, e, follower, v["drive.roller_radius"])
        reactor = opposed_piston(drive, **{k: col(x) for k, x in machine.items()})
        mass = v["machine.piston_mass"]
        inertia = (v["machine.inertia_shaft"], np.stack([mass, mass]) if np.ndim(mass) else
                   (mass, mass))  # fmt: skip
        w = col(speed) if p.varies("run.speed") else speed
        coefficient = values["machine.speed_fluctuation"]
        coefficient = coefficient[lo:hi] if np.ndim(coefficient) else coefficient
        model = ContactModel(v["contact.youngs_modulus"], v["contact.poisson_ratio"],
                             v["contact.roller_width"], v["contact.allowable_stress"],
                             {kind: v[f"contact.friction_{kind}"] for kind in KINDS})  # fmt: skip
        st = reactor_state(drive, reactor, inertia, w, beta)
        out = reactor_summary(drive, reactor, inertia, w, coefficient, beta, state=st)
        out.update(forces_summary(drive, reactor, inertia, w, beta, model,
                                  v["contact.bearing_radius"], v["drive.tip_radius"],
                                  state=st))  # fmt: skip
        out.update(time_peaks(st["motion"], (st["omega"], st["omega_dot"], st["omega_ddot"]),
                              _SLUGS))  # fmt: skip
        return {name: np.broadcast_to(np.asarray(out.get(name, np.nan), dtype=float), (hi - lo,))
                for name in names}  # fmt: skip

    return run_blocks(fn, n, samples, threads)


def _peaks(rc, e, n: int, samples, threads) -> dict:
    """The travel's sampled peaks per design (n,), once per distinct (contact radius,
    eccentricity): the only values the piston's travel depends on."""
    (rc, e), which = distinct((rc, e), n)
    beta = sample_grid(2.0 * np.pi, samples)

    def fn(lo, hi):
        peaks = ec.travel_peaks(rc[lo:hi, None], e[lo:hi, None], beta)
        return dict(zip(("v", "a", "j"), peaks, strict=True))

    res = run_blocks(fn, e.size, samples, threads)
    return {
        "piston_velocity_peak_mm_per_rad": res["v"][which] * 1e3,
        "piston_accel_peak_mm_per_rad2": res["a"][which] * 1e3,
        "piston_jerk_peak_mm_per_rad3": res["j"][which] * 1e3,
    }


def curves(p, points: int):
    """The :data:`CURVES` of admissible designs over one turn: angle (points,), dict (n, points)."""
    beta = sample_grid(2.0 * np.pi, points)
    out = drive_curves(_drive(p, column=True), beta)
    return beta, {k: np.array(np.broadcast_to(v, (p.n, points))) for k, v in out.items()}
