"""Study of the opposed-piston reactor driven by double eccentric discs (Zhu & Zhu 2012).

Config keys (SI, defaults filled by :mod:`rotorkin.io.config`; a key missing from
``cfg`` takes the schema's default):
``drive.disc_radius``, ``drive.eccentricity``, ``drive.follower``,
``drive.roller_radius``; ``machine.device_length``, ``machine.bore``,
``machine.fluid``, ``machine.initial_pressure``, ``machine.polytropic_exponent``,
``machine.bulk_modulus``, ``machine.piston_mass``, ``machine.inertia_shaft``,
``machine.speed_fluctuation`` (the reactor, :mod:`rotorkin.machines.opposed_piston`);
``run.points``, ``run.speed``.

Torque sign (``shaft_torque_*``, ``mean_torque_Nm``): positive when the machine
drives the shaft. Piston forces are positive towards the reactor centre (the
sense of the travels ``z``, ``z'``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin.analysis import pairs as pairs_mod
from rotorkin.core.angles import fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.core.schema import ContactSection, RunSection
from rotorkin.drives.eccentric_cam import figures as figures_eccentric_cam
from rotorkin.drives.eccentric_cam import forces as fz
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.drives.eccentric_cam.curves import drive_curves
from rotorkin.drives.eccentric_cam.forces import forces_summary
from rotorkin.drives.eccentric_cam.reactor import (
    closed_forms,
    opposed_piston,
    reactor_state,
    reactor_summary,
)
from rotorkin.drives.eccentric_cam.schema import EccentricMachine
from rotorkin.machines import opposed_piston as op
from rotorkin.studies import StudyResult
from rotorkin.studies.helpers import angle_grid, build_params, time_domain, undefined_warnings

__all__ = [
    "evaluate",
    "drive_params",
    "machine_params",
    "sections",
    "adjuster",
    "reactor_state",
    "HEADLINE",
]

#: Summary keys printed by the command line, in order, with what each means (one line).
HEADLINE = {
    "follower": "piston follower: knife_edge, flat or roller",
    "lambda": "eccentricity over disc radius, e/R",
    "gap_change_min_mm": "most negative change Delta of the piston gap (Fig. 8)",
    "gap_change_min_ratio": "Delta / e there (Fig. 7)",
    "gap_change_to_length_percent": "|Delta| / device length there",
    "piston_stroke_mm": "travel of one piston over a turn",
    "pressure_angle_max_deg": "largest pressure angle between disc and piston",
    "fluid": "working fluid model: gas (polytropic) or liquid (bulk modulus)",
    "chamber_volume_max_cm3": "largest volume enclosed between the pistons",
    "pressure_min_bar": "lowest pressure of the enclosed fluid",
    "pressure_ripple_bar": "max - min of the enclosed fluid's pressure",
    "cavitation": "true if the liquid's pressure would fall to zero (it would boil)",
    "piston_left_accel_peak_m_per_s2": "peak acceleration of the left piston",
    "shaft_torque_peak_Nm": "peak torque of the fluid on the shaft, without inertia",
    "flywheel_inertia_kgm2": "flywheel for the chosen coefficient of speed fluctuation",
    "peak_contact_force_N": "largest normal force of a disc on its follower, at the run speed",
    "peak_contact_stress_MPa": "largest Hertz pressure of a disc on its follower",
    "contact_safety_factor": "contact.allowable_stress over that pressure",
    "peak_bearing_load_N": "largest load of a disc on the shaft bearings (or a roller pin)",
    "follower_force_min_N": "smallest push of a disc on its follower (< 0: it would lift off)",
    "side_thrust_peak_N": "largest side thrust of a piston on its guide",
    "friction_loss_W": "power friction takes from the shaft at the run speed",
    "mechanical_efficiency": "work through the drive over it plus the friction loss",
    "section_travel_difference_max_mm": "adjuster: largest travel change, exact elliptic "
    "section against the paper's circle",
}

#: Samples per shaft turn used for the peaks of the piston derivatives (independent of run.points).
_PEAK_SAMPLES = 20_001


def _summary(params: ec.EccentricCam, reactor: op.OpposedPiston) -> dict:
    fine = np.linspace(0.0, ec.period(params), _PEAK_SAMPLES)
    v, a, j = ec.travel_peaks(params.contact_radius, params.eccentricity, fine)
    out = {"follower": params.follower, "fluid": reactor.fluid}
    out.update(closed_forms(params, reactor))
    out["piston_velocity_peak_mm_per_rad"] = v * 1e3
    out["piston_accel_peak_mm_per_rad2"] = a * 1e3
    out["piston_jerk_peak_mm_per_rad3"] = j * 1e3
    return out


_DOCS = {
    "beta_deg": "Shaft angle beta; 0 puts the left piston at its top (+e), the right at its "
    "bottom.",
    "z_left_mm": "Left piston travel z from mid position, positive towards the reactor centre "
    "(eq. 1).",
    "z_right_mm": "Right piston travel z' from mid position, positive towards the reactor centre "
    "(eq. 3).",
    "gap_change_mm": "Gap change Delta = z + z' (eq. 5); negative: the inner faces stand apart.",
    "x_left": "Dimensionless left travel x = z/e = xi + mu (eq. 2).",
    "x_right": "Dimensionless right travel x' = z'/e = mu - xi (eq. 4).",
    "xi": "Harmonic part xi = cos beta of x (Fig. 6).",
    "mu": "Additional part mu of x, the same for both pistons (Fig. 6).",
    "delta": "Dimensionless gap change delta = Delta/e = x + x' (eq. 6).",
    "z_left_velocity_mm_per_rad": "dz/dbeta, left piston velocity over shaft speed.",
    "z_right_velocity_mm_per_rad": "dz'/dbeta, right piston velocity over shaft speed.",
    "z_left_accel_mm_per_rad2": "d2z/dbeta2, left piston acceleration over shaft speed squared.",
    "z_right_accel_mm_per_rad2": "d2z'/dbeta2, right piston acceleration over shaft speed squared.",
    "z_left_jerk_mm_per_rad3": "d3z/dbeta3, left piston jerk over shaft speed cubed.",
    "z_right_jerk_mm_per_rad3": "d3z'/dbeta3, right piston jerk over shaft speed cubed.",
    "pressure_angle_left_deg": "Angle between the left contact normal and the piston axis "
    "(0 for a flat face).",
}


def _columns(params: ec.EccentricCam, points: int) -> dict:
    beta = angle_grid(ec.period(params), points)
    return {"beta_deg": np.degrees(beta), **drive_curves(params, beta)}


# --------------------------------------------------------------------------------------------
# the reactor
# --------------------------------------------------------------------------------------------
_SLUGS = ("piston_left", "piston_right")

_REACTOR_DOCS = {
    "volume_cm3": "Enclosed volume V = A (L - Delta) between the inner faces of the pistons.",
    "dvolume_cm3_per_rad": "dV/dbeta, exact (-A dDelta/dbeta).",
    "pressure_bar": "Absolute pressure of the enclosed fluid (gas: p0 (V0/V)^n; liquid: "
    "p0 - K ln(V/V0)); below 0: the liquid would cavitate.",
    "piston_left_force_N": "Force of the fluid on the left piston, -p A, positive towards the "
    "reactor centre.",
    "piston_right_force_N": "Force of the fluid on the right piston, -p A, positive towards the "
    "reactor centre.",
    "shaft_torque_Nm": "Torque of the fluid on the shaft by virtual work, sum F_i dq_i/dbeta = "
    "p dV/dbeta; positive when it drives the shaft.",
    "inertia_torque_Nm": "Torque the shaft spends on the inertia of shaft and pistons, "
    "d(KE)/dbeta.",
    "shaft_torque_with_inertia_Nm": "shaft_torque_Nm minus inertia_torque_Nm: the net torque of "
    "the machine on the shaft (the motor supplies its opposite).",
    "equivalent_inertia_kgm2": "Inertia seen at the shaft, J_shaft + m (z'^2 + z''^2) with "
    "z' = dz/dbeta [m/rad].",
}


def sections(cfg: dict):
    """Machine and run sections with the schema's defaults for missing keys."""
    machine = {**EccentricMachine().model_dump(), **(cfg.get("machine") or {})}
    run = {**RunSection().model_dump(), **(cfg.get("run") or {})}
    return machine, run


def _inertias(machine: dict) -> tuple[float, tuple[float, float]]:
    js = float(machine["inertia_shaft"])
    if not (np.isfinite(js) and js >= 0.0):
        raise ParameterError("machine.inertia_shaft", f"{js:g} kg*m^2", "inertia_shaft >= 0")
    m = float(machine["piston_mass"])
    if not (np.isfinite(m) and m >= 0.0):
        raise ParameterError("machine.piston_mass", f"{m:g} kg", "piston_mass >= 0 kg")
    return js, (m, m)


def _reactor_summary(drive: ec.EccentricCam, reactor: op.OpposedPiston, inertia, speed,
                     coefficient) -> dict:  # fmt: skip
    fine = np.linspace(0.0, ec.period(drive), _PEAK_SAMPLES)
    out = reactor_summary(drive, reactor, inertia, speed, coefficient, fine)
    out.update(time_domain(ec.motion(drive, fine), speed, _SLUGS, ec.period(drive))[2])
    return out


def _reactor_columns(drive, reactor, inertia, speed, beta) -> tuple[dict, dict]:
    st = reactor_state(drive, reactor, inertia, speed, beta)
    cols = {
        "volume_cm3": st["V"][0] * 1e6,
        "dvolume_cm3_per_rad": st["dV"][0] * 1e6,
        "pressure_bar": st["p"][0] / 1e5,
        "piston_left_force_N": st["F"][0],
        "piston_right_force_N": st["F"][1],
        "shaft_torque_Nm": st["shaft"],
        "inertia_torque_Nm": st["inertia"],
        "shaft_torque_with_inertia_Nm": st["net"],
        "equivalent_inertia_kgm2": st["J_eq"],
    }
    tcols, tdocs, _, _ = time_domain(ec.motion(drive, beta), speed, _SLUGS,
                                     ec.period(drive))  # fmt: skip
    cols.update(tcols)
    return cols, {**_REACTOR_DOCS, **tdocs}


def adjuster(cfg: dict) -> tuple[float, float | None]:
    """The adjuster's inclination [rad] (0: off) and slide [m] (None: not given), checked.

    Refused (one line naming the key): a slide without an inclination, an
    inclination outside ``0 <= alpha < 90 deg``, a slide and an eccentricity that
    disagree (``e = s tan(alpha)``), neither eccentricity nor slide.
    """
    d = cfg["drive"]
    alpha = float(d.get("inclination") or 0.0)
    slide = d.get("slide")
    e = d.get("eccentricity")
    if not (np.isfinite(alpha) and 0.0 <= alpha < 0.5 * np.pi):
        raise ParameterError("drive.inclination", f"{np.degrees(alpha):g} deg",
                             "0 deg <= inclination < 90 deg")  # fmt: skip
    if slide is not None:
        slide = float(slide)
        if alpha == 0.0:
            raise ParameterError("drive.slide", fmt_mm(slide), "a slide needs drive.inclination "
                                 "> 0 deg (e = slide tan(inclination))")  # fmt: skip
        if not (np.isfinite(slide) and slide > 0.0):
            raise ParameterError("drive.slide", fmt_mm(slide), "slide > 0 mm")
        set_e = float(ec.adjuster_eccentricity(alpha, slide))
        if e is not None and not np.isclose(float(e), set_e, rtol=1e-9, atol=0.0):
            raise ParameterError(
                "drive.slide",
                fmt_mm(slide),
                f"slide tan(inclination) = {fmt_mm(set_e)} must equal "
                f"drive.eccentricity = {fmt_mm(float(e))}; give one of the two",
            )
    elif e is None:
        raise ParameterError(
            "drive.eccentricity",
            "missing",
            "an eccentricity, or drive.inclination > 0 deg with drive.slide",
        )
    return alpha, slide


def _forces(params, reactor, inertia, speed, beta, cfg):
    """Reactor state, contact state and pairs at the angles ``beta``."""
    st = reactor_state(params, reactor, inertia, speed, beta)
    state = fz.contact_state(params, beta, st["F"], inertia[1], st["omega"], st["omega_dot"])
    contact = {**ContactSection().model_dump(), **(cfg.get("contact") or {})}
    tip = float(cfg["drive"].get("tip_radius") or 0.0)
    return st, state, fz.pairs(params, state, float(contact["bearing_radius"]), tip)


def _forces_summary(params, reactor, inertia, speed, cfg) -> dict:
    fine = np.linspace(0.0, ec.period(params), _PEAK_SAMPLES)
    contact = {**ContactSection().model_dump(), **(cfg.get("contact") or {})}
    tip = float(cfg["drive"].get("tip_radius") or 0.0)
    return forces_summary(params, reactor, inertia, speed, fine,
                          pairs_mod.ContactModel.from_config(cfg),
                          float(contact["bearing_radius"]), tip)  # fmt: skip


_FORCE_DOCS = {
    "follower_normal_left_N": "Push N of the left disc on its follower along the contact "
    "normal (signed: < 0 means the follower would lift off).",
    "follower_normal_right_N": "Push N of the right disc on its follower (signed).",
    "side_thrust_left_N": "Side thrust N n_y of the left piston on its guide along y of its "
    "follower frame (> 0: the +y wall).",
    "side_thrust_right_N": "Side thrust of the right piston on its guide (signed, as the left).",
    "shaft_radial_load_N": "Magnitude of the sum of both discs' loads on the shaft.",
    "contact_shaft_torque_Nm": "Torque of the contact forces on the shaft (with the pistons' "
    "inertia), positive in the sense of rotation.",
}


def _forces_columns(params, reactor, inertia, speed, beta, cfg) -> tuple[dict, dict]:
    st, state, prs = _forces(params, reactor, inertia, speed, beta, cfg)
    cols, docs = pairs_mod.columns(prs, pairs_mod.ContactModel.from_config(cfg), st["shaft"])
    cols.update({
        "follower_normal_left_N": state.normal[0],
        "follower_normal_right_N": state.normal[1],
        "side_thrust_left_N": state.side_thrust[0],
        "side_thrust_right_N": state.side_thrust[1],
        "shaft_radial_load_N": np.hypot(*state.shaft_load),
        "contact_shaft_torque_Nm": state.shaft_torque,
    })  # fmt: skip
    return cols, {**docs, **_FORCE_DOCS}


def _adjuster_summary(params, cfg) -> dict:
    """Keys of the inclined-disc adjuster (none when it is off)."""
    alpha, slide = adjuster(cfg)
    if alpha == 0.0:
        return {}
    fine = np.linspace(0.0, ec.period(params), _PEAK_SAMPLES)
    exact = ec.section_travels(params.disc_radius, params.eccentricity, alpha, params.follower,
                               params.roller_radius, fine)  # fmt: skip
    circle = ec.piston_travels(params, fine)[0]
    a, _ = ec.section_semi_axes(params.disc_radius, alpha)
    s = float(ec.adjuster_slide(alpha, params.eccentricity)) if slide is None else slide
    return {
        "inclination_deg": float(np.degrees(alpha)),
        "slide_mm": s * 1e3,
        "section_major_axis_mm": 2e3 * float(a),
        "section_minor_axis_mm": 2e3 * float(params.disc_radius),
        "section_travel_difference_max_mm": float(np.max(np.abs(exact - circle))) * 1e3,
        "section_gap_change_min_mm": float(np.min(exact[0] + exact[1])) * 1e3,
    }


_ADJUSTER_DOCS = {
    "z_left_section_mm": "Left piston travel on the disc's exact (elliptic) section in the "
    "piston plane (adjuster).",
    "z_right_section_mm": "Right piston travel on the exact section (adjuster).",
    "gap_change_section_mm": "Gap change z + z' on the exact section (adjuster).",
}


def _adjuster_columns(params, cfg, beta) -> dict:
    alpha, _ = adjuster(cfg)
    if alpha == 0.0:
        return {}
    z = ec.section_travels(params.disc_radius, params.eccentricity, alpha, params.follower,
                           params.roller_radius, beta)  # fmt: skip
    return {"z_left_section_mm": z[0] * 1e3, "z_right_section_mm": z[1] * 1e3,
            "gap_change_section_mm": (z[0] + z[1]) * 1e3}  # fmt: skip


def drive_params(cfg: dict) -> ec.EccentricCam:
    """The drive's parameters from a validated config (SI); errors name the config keys.

    The eccentricity is ``drive.eccentricity`` or, with the adjuster,
    ``drive.slide * tan(drive.inclination)`` (:func:`adjuster`).
    """
    d = dict(cfg["drive"])
    alpha, slide = adjuster(cfg)
    if slide is not None:
        e = float(ec.adjuster_eccentricity(alpha, slide))
        if not e < float(d["disc_radius"]):
            raise ParameterError("drive.slide", fmt_mm(slide),
                                 f"slide tan(inclination) = {fmt_mm(e)} below disc_radius = "
                                 f"{fmt_mm(float(d['disc_radius']))}")  # fmt: skip
        d["eccentricity"] = e
    keys = ("disc_radius", "eccentricity", "follower", "roller_radius")
    return build_params(ec.EccentricCam, "drive", {k: d[k] for k in keys if k in d})


def machine_params(params: ec.EccentricCam, machine: dict) -> op.OpposedPiston:
    """The reactor on the drive ``params`` from the machine section (SI, defaults filled);
    errors name the config keys."""
    keys = ("device_length", "bore", "fluid", "initial_pressure", "polytropic_exponent",
            "bulk_modulus", "back_pressure")  # fmt: skip
    return build_params(
        lambda **kw: opposed_piston(params, **kw), "machine", {k: machine[k] for k in keys}
    )


_UNDEFINED = {
    "mechanical_efficiency": "no work passes through the drive (no pressure and no piston "
    "mass: machine.initial_pressure, machine.piston_mass)",
}


def evaluate(cfg: dict) -> StudyResult:
    """Run the eccentric-cam reactor study on a validated config (SI values).

    Parameters
    ----------
    cfg : dict
        ``cfg["drive"]``: ``disc_radius`` [m], ``eccentricity`` [m], ``follower``,
        ``roller_radius`` [m]; ``cfg["machine"]``: ``device_length``, ``bore`` [m],
        ``fluid``, ``initial_pressure`` [Pa], ``polytropic_exponent``,
        ``bulk_modulus`` [Pa], ``piston_mass`` [kg], ``inertia_shaft`` [kg*m^2],
        ``speed_fluctuation``; ``cfg["run"]``: ``points``, ``speed`` [rad/s].
        Missing machine and run keys take the schema's defaults.

    Returns
    -------
    StudyResult
        Summary keys: see :data:`HEADLINE`, ``docs/drives/eccentric_cam.md`` and
        ``docs/machines/opposed_piston.md``.
    """
    params = drive_params(cfg)
    machine, run = sections(cfg)
    reactor = machine_params(params, machine)
    inertia = _inertias(machine)
    speed = run["speed"]
    summary = _summary(params, reactor)
    summary.update(
        _reactor_summary(params, reactor, inertia, speed, float(machine["speed_fluctuation"]))
    )
    summary.update(_forces_summary(params, reactor, inertia, speed, cfg))
    summary.update(_adjuster_summary(params, cfg))
    summary = {k: v.item() if isinstance(v, np.generic) else v for k, v in summary.items()}
    columns = _columns(params, run["points"])
    beta = angle_grid(ec.period(params), run["points"])
    more, more_docs = _reactor_columns(params, reactor, inertia, speed, beta)
    columns.update(more)
    columns.update(_adjuster_columns(params, cfg, beta))
    fcols, fdocs = _forces_columns(params, reactor, inertia, speed, beta, cfg)
    columns.update(fcols)

    def plot(outdir: Path) -> list[Path]:
        grid = angle_grid(ec.period(params), 1441)
        state = reactor_state(params, reactor, inertia, speed, grid)
        fcols = _forces_columns(params, reactor, inertia, speed, grid, cfg)[0]
        return figures_eccentric_cam.plot_all(
            params,
            Path(outdir),
            reactor=reactor,
            beta=grid,
            state=state,
            summary=summary,
            forces=fcols,
        )

    return StudyResult(
        drive_type="eccentric_cam",
        title="Opposed-piston reactor, double eccentric cams",
        summary=summary,
        columns=columns,
        column_docs={**_DOCS, **more_docs, **_ADJUSTER_DOCS, **fdocs},
        headline={k: v for k, v in HEADLINE.items() if k in summary},
        write_figures=plot,
        motion=ec.motion(params, beta),
        warnings=undefined_warnings(summary, _UNDEFINED),
    )
