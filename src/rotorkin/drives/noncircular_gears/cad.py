"""CAD of the gears: both pitch curves as plates (``rotorkin export``: DXF, STEP, STL).

The pitch curves are what a gear shop needs to generate the teeth (hobbing with a
non-circular generator or wire cutting of a tooth profile laid on the curve); the
plates are the pitch curves extruded to ``drive.face_width``. Tooth design stays
with the shop. Both gear pairs are alike; pair 2 sits ``drive.phase`` further on
the shaft.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from rotorkin.cams import edges, planar
from rotorkin.cams.planar import Curve, Part, Placement
from rotorkin.core.angles import fmt_mm
from rotorkin.drives.noncircular_gears import kinematics as ng
from rotorkin.drives.noncircular_gears.study import drive_params
from rotorkin.drives.noncircular_gears.study import law as law_of
from rotorkin.render import workshop as ws
from rotorkin.render.cad import check_tolerance
from rotorkin.vane.impellers import PUMP_SPACING, machine_type, pump_parts

__all__ = ["cad_parts", "check_cam"]


def _curve(params, which):
    def f(t):
        x, y = ng.pitch_curve(params, which, np.asarray(t, dtype=float))
        return np.stack([x, y])

    return f


def cad_parts(cfg: dict, with_parts: bool = True):
    """The driving and the driven gear's pitch-curve plates, and no profile checks.

    Each plate's outline is its pitch curve as clamped cubic B-spline pieces within
    ``export.tolerance`` (:func:`rotorkin.cams.edges.fit_closed`); each is bored on its
    axis with a keyway towards its largest radius. In the assembly the driving gear
    sits at the origin and the driven gear at ``(a, 0)`` turned half a turn (their pitch
    curves touch on the line of centres at ``theta = 0``,
    :func:`~rotorkin.drives.noncircular_gears.kinematics.pitch_curve`); backlash belongs
    to the teeth, so the pitch curves carry no running gap. With ``machine.type =
    "vane_pump"`` the pump's impellers follow, beside the gears on the driven axis. The
    pitch curves' convexity is checked when the gears are built (a concave stretch is
    refused, naming ``drive.eccentricity``).
    """
    params = drive_params(cfg)
    r_min = float(np.min(ng.pitch_radius(params, "driven", np.linspace(0, 2 * np.pi, 721))))
    tol = check_tolerance(cfg, r_min)
    if not (with_parts or ws.configured(cfg)):
        return [], []
    width = float(cfg["drive"].get("face_width", 0.02))
    s = ws.settings(cfg, check_only=not with_parts)
    a = float(params.centre_distance)
    parts = []
    for which, lobes in (("driving", params.lobes), ("driven", params.rotor_lobes)):
        curve = _curve(params, which)
        t = planar.resample_closed(curve, 0.0, 2.0 * np.pi, tol)
        pieces = edges.fit_closed(curve, 2.0 * np.pi, tol)[0]
        outline = Curve("pitch", "PITCH", curve(t).T.copy(), True, None, pieces)
        r = ng.pitch_radius(params, which, t)
        part = Part(
            name=f"{which}_gear",
            outline=outline,
            thickness=width,
            curves=(outline,),
            title=f"{which} gear pitch curve, {lobes} lobe(s), radius {fmt_mm(np.min(r))} to "
            f"{fmt_mm(np.max(r))}, centre at the origin",
            placement=Placement() if which == "driving" else Placement(a, 0.0, np.pi),
            notes=("pitch curve only: teeth and backlash by the gear shop",),
        )  # fmt: skip
        hub = ws.part_hub(s, outline.points, part.name, s.bore,
                          angle=ws.key_angle(outline.points))  # fmt: skip
        parts.append(ws.with_hub(part, hub, tol))
    if machine_type(cfg) == "vane_pump":
        pump = pump_parts(cfg, law_of(cfg), tol, width + PUMP_SPACING, not with_parts)
        parts += [replace(p, placement=replace(p.placement, x=a)) for p in pump]
    return (parts if with_parts else []), []


def check_cam(cfg: dict) -> None:
    """What ``rotorkin export`` checks, without building the plates."""
    cad_parts(cfg, with_parts=False)
