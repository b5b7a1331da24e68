"""CAD of the drive's planar parts, with their profile checks (``rotorkin export``)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from rotorkin.cams.planar import Placement
from rotorkin.drives.eccentric_cam import cam as eccentric
from rotorkin.drives.eccentric_cam.study import drive_params
from rotorkin.render import workshop as ws
from rotorkin.render.cad import check_thickness, check_tolerance

__all__ = ["cad_parts", "check_cam"]


def cad_parts(cfg: dict, with_parts: bool = True):
    """Planar parts (``Part``) and profile checks ``[(label, ProfileCheck)]`` of a config.

    Both discs, bored on the shaft axis with a keyway towards the disc's centre (its
    thickest wall; the shaft carries two keyseats half a turn apart), side by side on
    the shaft in the assembly (left from z = 0, right from z = thickness). The follower
    is held on its disc (force closure), so the disc keeps its nominal radius: no
    running gap. ``parts`` is empty when ``with_parts`` is false (checks only). Raises
    :class:`ParameterError` named by config key (``cam.roller_radius``,
    ``cam.thickness``, ``export.tolerance``, ``export.bore``, drive and machine keys).
    """
    params = drive_params(cfg)
    thickness = check_thickness(cfg, 2.0 * float(params.disc_radius), "the disc's diameter")
    tol = check_tolerance(cfg, float(params.disc_radius))
    check = eccentric.profile_check(params)
    if not (with_parts or ws.configured(cfg)):
        return [], [("eccentric discs", check)]
    s = ws.settings(cfg, check_only=not with_parts)
    parts = []
    for k, part in enumerate(eccentric.cam_parts(params, thickness, tol)):
        cx = part.outline.circle[0]
        angle = 0.0 if cx >= 0.0 else np.pi
        hub = ws.part_hub(s, part.outline.points, part.name, s.bore, angle=angle)
        part = ws.with_hub(part, hub, tol, ("force-closed follower: the disc at its nominal "
                                            "radius, no running gap",))  # fmt: skip
        parts.append(replace(part, placement=Placement(z=k * float(thickness))))
    return (parts if with_parts else []), [("eccentric discs", check)]


def check_cam(cfg: dict) -> None:
    """The profile and part checks of ``rotorkin export``, without building the parts.

    ``rotorkin run`` makes them too (through :func:`rotorkin.drives.evaluate`), so a
    config that export would refuse is refused by every command, in the same line.
    """
    cad_parts(cfg, with_parts=False)
