"""CAD of the drive's planar parts, with their profile checks (``rotorkin export``)."""

from __future__ import annotations

import numpy as np

from rotorkin.drives.rhomboid_cam import cam as rhomboid
from rotorkin.drives.rhomboid_cam.study import drive_params
from rotorkin.drives.rhomboid_cam.study import law as law_of
from rotorkin.render import workshop as ws
from rotorkin.render.cad import check_thickness, check_tolerance
from rotorkin.vane.impellers import PUMP_SPACING, machine_type, pump_parts

__all__ = ["cad_parts", "check_cam"]


def cad_parts(cfg: dict, with_parts: bool = True):
    """Planar parts (``Part``) and profile checks ``[(label, ProfileCheck)]`` of a config.

    The cam plate, its profile offset by the roller radius and the running gap
    (:func:`rotorkin.render.workshop.pair_gap` at the cam's outer diameter), bored and
    keyed on the axis (the fixed cam sits on the housing's stationary spigot; the key
    also sets its angle), the keyway towards the profile's farthest point. With
    ``machine.type = "vane_pump"`` the pump's impellers follow, beside the cam.
    ``parts`` is empty when ``with_parts`` is false (checks only). Raises
    :class:`ParameterError` named by config key (``cam.roller_radius``,
    ``cam.thickness``, ``export.tolerance``, ``export.bore``, drive and machine keys).
    """
    params = drive_params(cfg)
    cam = cfg.get("cam") or {}
    r = float(cam.get("roller_radius", 0.01))
    law = (params.psi_min, params.a, params.b)
    check = rhomboid.check_profile(params.link_length, *law, r, name="cam.roller_radius")
    q = rhomboid.actual_profile(params.link_length, *law, r, np.linspace(0.0, np.pi, 4097))
    diameter = 2.0 * float(np.max(np.hypot(q[0], q[1])))
    thickness = check_thickness(cfg, diameter, "the cam's outer diameter")
    tol = check_tolerance(cfg, check.extra["pitch_radius_min"])
    if not (with_parts or ws.configured(cfg)):
        return [], [("rhomboid cam", check)]
    s = ws.settings(cfg, check_only=not with_parts)
    gap = ws.pair_gap(s, diameter)
    part = rhomboid.cam_part(params, r, thickness, tol, gap)
    outline = part.outline.points
    hub = ws.part_hub(s, outline, part.name, s.bore, angle=ws.key_angle(outline))
    parts = [ws.with_hub(part, hub, tol)]
    if machine_type(cfg) == "vane_pump":
        parts += pump_parts(cfg, law_of(cfg), tol, thickness + PUMP_SPACING, not with_parts)
    return (parts if with_parts else []), [("rhomboid cam", check)]


def check_cam(cfg: dict) -> None:
    """The profile and part checks of ``rotorkin export``, without building the parts.

    ``rotorkin run`` makes them too (through :func:`rotorkin.drives.evaluate`), so a
    config that export would refuse is refused by every command, in the same line.
    """
    cad_parts(cfg, with_parts=False)
