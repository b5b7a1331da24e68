"""CAD of the gears: both pitch curves as plates (``rotorkin export``: DXF, STEP, STL).

The pitch curves are what a gear shop needs to generate the teeth (hobbing with a
non-circular generator or wire cutting of a tooth profile laid on the curve); the
plates are the pitch curves extruded to ``drive.face_width``. Tooth design stays
with the shop. Both gear pairs are alike; pair 2 sits ``drive.phase`` further on
the shaft.
"""

from __future__ import annotations

import numpy as np

from rotorkin.cams import planar
from rotorkin.cams.planar import Curve, Part
from rotorkin.core.angles import fmt_mm
from rotorkin.drives.noncircular_gears import kinematics as ng
from rotorkin.drives.noncircular_gears.study import drive_params
from rotorkin.render.cad import check_tolerance

__all__ = ["cad_parts", "check_cam"]


def _curve(params, which):
    def f(t):
        x, y = ng.pitch_curve(params, which, np.asarray(t, dtype=float))
        return np.stack([x, y])

    return f


def cad_parts(cfg: dict, with_parts: bool = True):
    """The driving and the driven gear's pitch-curve plates, and no profile checks.

    The pitch curves' convexity is checked when the gears are built (a concave
    stretch is refused, naming ``drive.eccentricity``).
    """
    params = drive_params(cfg)
    r_min = float(np.min(ng.pitch_radius(params, "driven", np.linspace(0, 2 * np.pi, 721))))
    tol = check_tolerance(cfg, r_min)
    if not with_parts:
        return [], []
    width = float(cfg["drive"].get("face_width", 0.02))
    parts = []
    for which, lobes in (("driving", params.lobes), ("driven", params.rotor_lobes)):
        curve = _curve(params, which)
        t = planar.resample_closed(curve, 0.0, 2.0 * np.pi, tol)
        pts = curve(t).T
        outline = Curve("pitch", "PITCH", pts)
        r = ng.pitch_radius(params, which, t)
        parts.append(Part(
            name=f"{which}_gear",
            outline=outline,
            thickness=width,
            curves=(outline,),
            title=f"{which} gear pitch curve, {lobes} lobe(s), radius {fmt_mm(np.min(r))} to "
            f"{fmt_mm(np.max(r))}, centre at the origin",
        ))  # fmt: skip
    return parts, []


def check_cam(cfg: dict) -> None:
    """What ``rotorkin export`` checks, without building the plates."""
    cad_parts(cfg, with_parts=False)
