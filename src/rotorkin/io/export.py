"""CAD export of any drive: the dispatcher behind ``rotorkin export``.

A drive gives planar parts with their profile checks (``DriveSpec.cad_parts``:
cam plates, discs, impellers; a roller that does not fit is a
:class:`ParameterError` on ``cam.roller_radius`` stating the largest one that
does) written here as DXF, STL, STEP and CSV, or writes its own files
(``DriveSpec.cad_write``: a spherical cam).

Files are written into a temporary folder beside ``outdir`` and moved into it
with ``os.replace`` only when all of them are written: a failure leaves nothing.
File names: ``<name>_<part>.dxf|stl|step`` and ``<name>_<part>_<curve>.csv``.
"""

from __future__ import annotations

from pathlib import Path

from rotorkin import drives
from rotorkin.core.errors import ConfigError, ParameterError
from rotorkin.io.output import staged_output
from rotorkin.render import cad as cp
from rotorkin.render.cad import DEFAULT_TOLERANCE

__all__ = ["FORMATS", "DEFAULT_TOLERANCE", "export", "planar_parts", "profile_checks"]

#: Formats of :func:`export` (``all`` writes every one).
FORMATS = ("dxf", "stl", "step", "csv")


def planar_parts(cfg: dict, with_parts: bool = True):
    """Planar parts and profile checks of a validated config (``DriveSpec.cad_parts``).

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
    spec = drives.spec_of(cfg)
    if spec.cad_parts is None:
        raise ConfigError(f"drive.type = {spec.name!r} has no planar parts")
    return spec.cad_parts(cfg, with_parts)


def profile_checks(cfg: dict) -> list[tuple[str, object]]:
    """The profile checks of a config's cams: ``[(label, ProfileCheck)]`` (planar drives).

    Empty for a drive without planar parts. Raises like :func:`planar_parts`.
    """
    if drives.spec_of(cfg).cad_parts is None:
        return []
    return planar_parts(cfg, with_parts=False)[1]


def _check_format(fmt: str) -> list[str]:
    if fmt == "all":
        return list(FORMATS)
    if fmt not in FORMATS:
        raise ParameterError("fmt", repr(fmt), "one of " + ", ".join(FORMATS) + ", all")
    return [fmt]


def _write_planar(parts, fmt: str, stage: Path, name: str) -> list[Path]:

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
    spec = drives.spec_of(cfg)
    if spec.cad_parts is None and spec.cad_write is None:
        raise ConfigError(f"drive.type = {spec.name!r} has no parts to export")
    if "step" in fmts:
        cp.build123d_module()
    parts = planar_parts(cfg)[0] if spec.cad_parts is not None else None
    with staged_output(outdir, "export-" + "-".join(fmts)) as (stage, written):
        for f in fmts:
            if parts is None:
                spec.cad_write(cfg, f, stage, name)
            else:
                _write_planar(parts, f, stage, name)
    return written
