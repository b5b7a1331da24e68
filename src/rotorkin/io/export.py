"""CAD export of any drive: the dispatcher behind ``rotorkin export``.

* ``rhomboid_cam``: the cam plate (:mod:`rotorkin.cams.rhomboid`), after the
  profile check (a roller that does not fit is a :class:`ParameterError` on
  ``cam.roller_radius`` stating the largest one that does and naming the angle);
* ``eccentric_cam``: the two discs (:mod:`rotorkin.cams.eccentric`);
* ``guide_bar``: the two impellers of the vane pump (:mod:`rotorkin.cams.impeller`);
* ``wobble_cam``: the spherical cam, by :func:`rotorkin.io.cad_wobble.export_wobble`.

Files are written into a temporary folder beside ``outdir`` and moved into it
with ``os.replace`` only when all of them are written: a failure leaves nothing.
File names: ``<name>_<part>.dxf|stl|step`` and ``<name>_<part>_<curve>.csv``
(the wobble cam: see :mod:`rotorkin.io.cad_wobble`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin._angles import fmt_mm
from rotorkin.errors import ConfigError, ParameterError
from rotorkin.io.output import staged_output

__all__ = ["FORMATS", "DEFAULT_TOLERANCE", "export", "planar_parts", "profile_checks"]

#: Formats of :func:`export` (``all`` writes every one).
FORMATS = ("dxf", "stl", "step", "csv")
#: Default chordal tolerance [m] (``export.tolerance``).
DEFAULT_TOLERANCE = 1e-5


def _positive(cfg: dict, section: str, key: str, default: float) -> float:
    v = float((cfg.get(section) or {}).get(key, default))
    if not (np.isfinite(v) and v > 0.0):
        raise ParameterError(f"{section}.{key}", fmt_mm(v), f"{key} > 0 mm")
    return v


def _tolerance(cfg: dict, scale: float) -> float:
    tol = _positive(cfg, "export", "tolerance", DEFAULT_TOLERANCE)
    if not (1e-8 <= tol <= 0.01 * scale):
        raise ParameterError(
            "export.tolerance",
            fmt_mm(tol),
            f"0.00001 mm <= tolerance <= {fmt_mm(0.01 * scale)} (1 % of the part's size)",
        )
    return tol


def _thickness(cfg: dict, diameter: float, what: str) -> float:
    """``cam.thickness`` [m], checked: ``0 < thickness <= diameter`` (the part's outer diameter)."""
    t = _positive(cfg, "cam", "thickness", 0.02)
    if not t <= diameter:
        raise ParameterError(
            "cam.thickness",
            fmt_mm(t),
            f"0 mm < thickness <= {fmt_mm(diameter)} ({what}: a plate thicker than it is wide "
            "is no cam plate)",
        )
    return t


def _rhomboid(cfg: dict, with_parts: bool = True):
    from rotorkin.cams import rhomboid
    from rotorkin.studies.rhomboid_cam import drive_params

    params = drive_params(cfg)
    cam = cfg.get("cam") or {}
    r = float(cam.get("roller_radius", 0.01))
    law = (params.psi_min, params.a, params.b)
    check = rhomboid.check_profile(params.link_length, *law, r)
    q = rhomboid.actual_profile(np.linspace(0.0, np.pi, 4097), params.link_length, *law, r)
    diameter = 2.0 * float(np.max(np.hypot(q[0], q[1])))
    thickness = _thickness(cfg, diameter, "the cam's outer diameter")
    tol = _tolerance(cfg, check.extra["pitch_radius_min"])
    parts = [rhomboid.cam_part(params, r, thickness, tol)] if with_parts else []
    return parts, [("rhomboid cam", check)]


def _eccentric(cfg: dict, with_parts: bool = True):
    from rotorkin.cams import eccentric
    from rotorkin.studies.eccentric_cam import drive_params

    params = drive_params(cfg)
    thickness = _thickness(cfg, 2.0 * float(params.disc_radius), "the disc's diameter")
    tol = _tolerance(cfg, float(params.disc_radius))
    check = eccentric.profile_check(params)
    parts = eccentric.cam_parts(params, thickness, tol) if with_parts else []
    return parts, [("eccentric discs", check)]


def _guide_bar(cfg: dict, with_parts: bool = True):
    from rotorkin.cams import impeller
    from rotorkin.io.config import VanePumpMachine
    from rotorkin.machines import vane_pump as vp
    from rotorkin.studies._common import build_params
    from rotorkin.studies.guide_bar import drive_params

    params = drive_params(cfg)
    m = {**VanePumpMachine().model_dump(), **(cfg.get("machine") or {})}
    keys = ("vanes_per_impeller", "vane_angle", "hub_radius", "casing_radius", "axial_width")
    pump = build_params(vp.VanePump, "machine", {"drive": params, **{k: m[k] for k in keys}})
    tol = _tolerance(cfg, float(pump.hub_radius))
    return (impeller.impeller_parts(pump, tol) if with_parts else []), []


_PLANAR = {"rhomboid_cam": _rhomboid, "eccentric_cam": _eccentric, "guide_bar": _guide_bar}


def planar_parts(cfg: dict, with_parts: bool = True):
    """Planar parts and profile checks of a validated config (not for the wobble cam).

    Returns
    -------
    (parts, checks) : list of Part, list of (str, ProfileCheck)
        ``parts`` is empty when ``with_parts`` is false (checks only).

    Raises
    ------
    ParameterError
        Named by config key: bad drive or machine values, ``cam.roller_radius``
        undercutting the cam, ``cam.thickness`` (``0 < thickness <=`` the part's outer
        diameter) or ``export.tolerance`` out of range.
    """
    kind = cfg["drive"]["type"]
    if kind not in _PLANAR:
        raise ConfigError(f"drive.type = {kind!r} has no planar parts")
    return _PLANAR[kind](cfg, with_parts)


def profile_checks(cfg: dict) -> list[tuple[str, object]]:
    """The profile checks of a config's cams: ``[(label, ProfileCheck)]`` (planar drives).

    Empty for the guide-bar pump (no cam) and the wobble cam (see
    :mod:`rotorkin.cams.spherical`). Raises like :func:`planar_parts`.
    """
    if cfg["drive"]["type"] not in _PLANAR:
        return []
    return planar_parts(cfg, with_parts=False)[1]


def _check_format(fmt: str) -> list[str]:
    if fmt == "all":
        return list(FORMATS)
    if fmt not in FORMATS:
        raise ParameterError("--format", repr(fmt), "one of " + ", ".join(FORMATS) + ", all")
    return [fmt]


def _write_planar(parts, fmt: str, stage: Path, name: str) -> list[Path]:
    from rotorkin.io import cad_planar as cp

    out = []
    for part in parts:
        stem = f"{name}_{part.name}"
        if fmt == "dxf":
            out.append(cp.write_dxf(part, stage / f"{stem}.dxf", name))
        elif fmt == "stl":
            out.append(cp.write_stl(part, stage / f"{stem}.stl"))
        elif fmt == "step":
            out.append(cp.write_step(part, stage / f"{stem}.step"))
        else:
            out += cp.write_csv(part, stage, stem)
    return out


def export(cfg: dict, fmt: str, outdir, name: str) -> list[Path]:
    """Write the CAD files of a validated config (SI) in one format (or ``"all"``).

    Parameters
    ----------
    cfg : dict
        From :func:`rotorkin.io.config.load_config`.
    fmt : {"dxf", "stl", "step", "csv", "all"}
    outdir : path-like
        Folder to write into (created; files of the same names are replaced).
    name : str
        Stem of the file names (the config's name).

    Returns
    -------
    list of Path
        The files written, in ``outdir``.

    Raises
    ------
    ParameterError, ConfigError, RotorkinError
        Bad format, bad values (named by config key), an unwritable ``outdir``,
        STEP without build123d. Nothing is written then.
    """
    fmts = _check_format(fmt)
    kind = cfg["drive"]["type"]
    if "step" in fmts:
        from rotorkin.io.cad_planar import _bd

        _bd()
    parts = planar_parts(cfg)[0] if kind in _PLANAR else None
    with staged_output(outdir, "export-" + "-".join(fmts)) as (stage, written):
        for f in fmts:
            if parts is None:
                from rotorkin.io.cad_wobble import export_wobble

                export_wobble(cfg, f, stage, name)
            else:
                _write_planar(parts, f, stage, name)
    return written
