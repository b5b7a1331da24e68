"""Study of a vane machine on non-circular gears: the gears' own numbers, then the machine's.

Config keys (SI): ``drive.lobes``, ``drive.rotor_lobes``, ``drive.eccentricity``,
``drive.centre_distance``, ``drive.phase`` (None: pi / lobes), ``drive.face_width``;
``[machine]`` and ``[loads]`` of ``machine.type`` (:mod:`rotorkin.machines.schema`;
a twin-rotor engine by default), ``run.points``, ``run.speed``. The machine runs
through :func:`rotorkin.vane.evaluate`; the gears add their transmission ratio,
pitch radii and curvature to the summary, the pitch radii at every angle to
``motion.csv`` and a figure of the pitch curves.
"""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np

from rotorkin.drives.noncircular_gears import figures, forces
from rotorkin.drives.noncircular_gears import kinematics as ng
from rotorkin.studies import StudyResult
from rotorkin.studies.helpers import build_params
from rotorkin.vane import RotaryLaw
from rotorkin.vane import evaluate as evaluate_machine

__all__ = ["evaluate", "drive_params", "law", "HEADLINE"]

#: The gears' summary keys printed by the command line (the machine's follow).
HEADLINE = {
    "transmission_ratio_min": "slowest rotor speed over the shaft's (closed form)",
    "transmission_ratio_max": "fastest rotor speed over the shaft's (closed form)",
    "eccentricity_limit": "largest eccentricity with both pitch curves convex",
}

_FIELDS = ("lobes", "rotor_lobes", "eccentricity", "centre_distance", "phase")


def drive_params(cfg: dict) -> ng.NoncircularGears:
    """The gears from a validated config (SI); errors name the config keys."""
    d = cfg["drive"]
    return build_params(ng.NoncircularGears, "drive", {k: d[k] for k in _FIELDS if k in d})


def law(cfg: dict) -> RotaryLaw:
    """The rotors' motion for any vane machine (:mod:`rotorkin.vane`)."""
    params = drive_params(cfg)
    lo, hi = ng.equal_speed_angles(params)
    period = ng.period(params)
    turning = tuple(sorted(float(np.mod(t, period)) for t in (lo, hi)))
    return RotaryLaw(functools.partial(ng.motion, params), period, turning=turning)


def _summary(params: ng.NoncircularGears) -> dict:
    rmin, rmax = (float(v) for v in ng.ratio_extremes(params))
    radii = {}
    for which in ng.WHICH:
        angle = np.linspace(0.0, 2.0 * np.pi, 4001)
        r = ng.pitch_radius(params, which, angle)
        radii[f"{which}_pitch_radius_min_mm"] = float(np.min(r)) * 1e3
        radii[f"{which}_pitch_radius_max_mm"] = float(np.max(r)) * 1e3
        k = ng.curvature(params, which, angle)
        radii[f"{which}_curvature_radius_min_mm"] = float(1.0 / np.max(k)) * 1e3
    return {
        "lobes": int(params.lobes),
        "rotor_lobes": int(params.rotor_lobes),
        "rotor_turns_per_shaft_turn": params.lobes / params.rotor_lobes,
        "pitch_parameter_mm": float(ng.pitch_parameter(params)) * 1e3,
        "transmission_ratio_min": rmin,
        "transmission_ratio_max": rmax,
        "eccentricity_limit": float(ng.eccentricity_limit(params.lobes, params.rotor_lobes)),
        "phase_deg": float(np.degrees(ng._phase(params))),
        **radii,
    }


def _columns(params: ng.NoncircularGears, theta):
    cols, docs = {}, {}
    for k, offset in ((0, 0.0), (1, float(ng._phase(params)))):
        key = f"driving_gear{k + 1}_pitch_radius_mm"
        cols[key] = ng.pitch_radius(params, "driving", theta + offset) * 1e3
        docs[key] = (f"Radius of driving gear {k + 1} at its contact with driven gear {k + 1} "
                     "(on the line of centres).")  # fmt: skip
    return cols, docs


def evaluate(cfg: dict) -> StudyResult:
    """Run ``machine.type`` on the non-circular gears of ``cfg`` (validated, SI)."""
    params = drive_params(cfg)
    kind = cfg["machine"]["type"]
    return evaluate_machine(
        cfg,
        law(cfg),
        drive_type="noncircular_gears",
        title=f"{kind.replace('_', ' ')} on non-circular gears ({params.lobes}:"
        f"{params.rotor_lobes} lobes, e = {params.eccentricity:g})",
        drive_summary=_summary(params),
        drive_headline=HEADLINE,
        drive_columns=functools.partial(_columns, params),
        drive_figures=lambda outdir: figures.plot_pitch_curves(params, Path(outdir)),
        drive_pairs=functools.partial(
            _pairs,
            params,
            cfg["drive"].get("pressure_angle", np.radians(20.0)),
            cfg["drive"].get("face_width", 0.02),
            (cfg.get("contact") or {}).get("bearing_radius", 0.01),
        ),
    )


def _pairs(params, pressure_angle, face_width, bearing_radius, theta, drive_torque, motion):
    return forces.pairs(params, theta, drive_torque, motion, pressure_angle, face_width,
                        bearing_radius)  # fmt: skip
