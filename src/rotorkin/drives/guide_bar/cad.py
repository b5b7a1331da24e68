"""CAD of the drive's planar parts, with their profile checks (``rotorkin export``)."""

from __future__ import annotations

from rotorkin.drives.guide_bar import cam as impeller
from rotorkin.drives.guide_bar.study import drive_params, pump_params
from rotorkin.render import workshop as ws
from rotorkin.render.cad import check_tolerance

__all__ = ["cad_parts", "check_cam"]


def cad_parts(cfg: dict, with_parts: bool = True):
    """The impellers (``Part``) and no profile checks (the drive has no cam).

    ``parts`` is empty when ``with_parts`` is false (the checks only: a bore the config
    sets is checked, a default that finds no room is left to ``rotorkin export``).
    Raises :class:`ParameterError` named by config key (``export.tolerance``,
    ``export.bore``, ``export.sleeve_bore``, drive and machine keys).
    """
    params = drive_params(cfg)
    pump = pump_params(cfg, params)
    tol = check_tolerance(cfg, float(pump.hub_radius))
    if not (with_parts or ws.configured(cfg)):
        return [], []
    parts = impeller.impeller_parts(params, pump, cfg, tol, check_only=not with_parts)
    return (parts if with_parts else []), []


def check_cam(cfg: dict) -> None:
    """The profile and part checks of ``rotorkin export``, without building the parts.

    ``rotorkin run`` makes them too (through :func:`rotorkin.drives.evaluate`), so a
    config that export would refuse is refused by every command, in the same line.
    """
    cad_parts(cfg, with_parts=False)
