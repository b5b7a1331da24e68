"""CAD of the drive's planar parts, with their profile checks (``rotorkin export``)."""

from __future__ import annotations

from rotorkin.render.cad import check_tolerance

__all__ = ["cad_parts"]


def cad_parts(cfg: dict, with_parts: bool = True):
    """Planar parts (``Part``) and profile checks ``[(label, ProfileCheck)]`` of a config.

    ``parts`` is empty when ``with_parts`` is false (checks only). Raises
    :class:`ParameterError` named by config key (``cam.roller_radius``,
    ``cam.thickness``, ``export.tolerance``, drive and machine keys).
    """
    from rotorkin.drives.guide_bar import cam as impeller
    from rotorkin.drives.guide_bar.schema import VanePumpMachine
    from rotorkin.drives.guide_bar.study import drive_params
    from rotorkin.machines import vane_pump as vp
    from rotorkin.studies.helpers import build_params

    params = drive_params(cfg)
    m = {**VanePumpMachine().model_dump(), **(cfg.get("machine") or {})}
    keys = ("vanes_per_impeller", "vane_angle", "hub_radius", "casing_radius", "axial_width")
    pump = build_params(vp.VanePump, "machine", {"drive": params, **{k: m[k] for k in keys}})
    tol = check_tolerance(cfg, float(pump.hub_radius))
    return (impeller.impeller_parts(pump, tol) if with_parts else []), []
