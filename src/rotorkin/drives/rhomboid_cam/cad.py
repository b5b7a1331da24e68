"""CAD of the drive's planar parts, with their profile checks (``rotorkin export``)."""

from __future__ import annotations

import numpy as np

from rotorkin.drives.rhomboid_cam import cam as rhomboid
from rotorkin.drives.rhomboid_cam.study import drive_params
from rotorkin.render.cad import check_thickness, check_tolerance

__all__ = ["cad_parts", "check_cam"]


def cad_parts(cfg: dict, with_parts: bool = True):
    """Planar parts (``Part``) and profile checks ``[(label, ProfileCheck)]`` of a config.

    ``parts`` is empty when ``with_parts`` is false (checks only). Raises
    :class:`ParameterError` named by config key (``cam.roller_radius``,
    ``cam.thickness``, ``export.tolerance``, drive and machine keys).
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
    parts = [rhomboid.cam_part(params, r, thickness, tol)] if with_parts else []
    return parts, [("rhomboid cam", check)]


def check_cam(cfg: dict) -> None:
    """The profile and part checks of ``rotorkin export``, without building the parts.

    ``rotorkin run`` makes them too (through :func:`rotorkin.drives.evaluate`), so a
    config that export would refuse is refused by every command, in the same line.
    """
    cad_parts(cfg, with_parts=False)
