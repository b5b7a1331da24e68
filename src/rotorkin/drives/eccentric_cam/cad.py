"""CAD of the drive's planar parts, with their profile checks (``rotorkin export``)."""

from __future__ import annotations

from rotorkin.drives.eccentric_cam import cam as eccentric
from rotorkin.drives.eccentric_cam.study import drive_params
from rotorkin.render.cad import check_thickness, check_tolerance

__all__ = ["cad_parts", "check_cam"]


def cad_parts(cfg: dict, with_parts: bool = True):
    """Planar parts (``Part``) and profile checks ``[(label, ProfileCheck)]`` of a config.

    ``parts`` is empty when ``with_parts`` is false (checks only). Raises
    :class:`ParameterError` named by config key (``cam.roller_radius``,
    ``cam.thickness``, ``export.tolerance``, drive and machine keys).
    """
    params = drive_params(cfg)
    thickness = check_thickness(cfg, 2.0 * float(params.disc_radius), "the disc's diameter")
    tol = check_tolerance(cfg, float(params.disc_radius))
    check = eccentric.profile_check(params)
    parts = eccentric.cam_parts(params, thickness, tol) if with_parts else []
    return parts, [("eccentric discs", check)]


def check_cam(cfg: dict) -> None:
    """The profile and part checks of ``rotorkin export``, without building the parts.

    ``rotorkin run`` makes them too (through :func:`rotorkin.drives.evaluate`), so a
    config that export would refuse is refused by every command, in the same line.
    """
    cad_parts(cfg, with_parts=False)
