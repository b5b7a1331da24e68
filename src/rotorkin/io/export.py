"""CAD export of any drive: the dispatcher behind ``rotorkin export``.

A drive gives planar parts with their profile checks (``DriveSpec.cad_parts``:
cam plates, discs, impellers; a roller that does not fit is a
:class:`ParameterError` on ``cam.roller_radius`` stating the largest one that
does) written here as DXF, STL, STEP and CSV, or writes its own files
(``DriveSpec.cad_write``: a spherical cam).

Files are written into a temporary folder beside ``outdir`` and moved into it
with ``os.replace`` only when all of them are written: a failure leaves nothing.
File names: ``<name>_<part>.dxf|stl|step`` and ``<name>_<part>_<curve>.csv``; STEP
adds ``<name>_assembly.step``, every part placed as in the machine at ``theta = 0``
(one product per part, named after it; the config's title in the header).
"""

from __future__ import annotations

from pathlib import Path

from rotorkin import drives
from rotorkin.core.errors import ConfigError, ParameterError
from rotorkin.io.output import staged_output
from rotorkin.render import cad as cp
from rotorkin.render.cad import DEFAULT_TOLERANCE

__all__ = ["FORMATS", "DEFAULT_TOLERANCE", "export", "planar_parts", "profile_checks",
           "workshop_rows"]  # fmt: skip

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


def workshop_rows(cfg: dict) -> list[tuple[str, str]]:
    """(item, value) rows of the parts' bores, keyways and running gaps (planar drives)."""
    if drives.spec_of(cfg).cad_parts is None:
        return []
    rows = []
    for part in planar_parts(cfg)[0]:
        hub = part.hub
        if hub is not None:
            hole, shaft = hub.fit.split("/")
            d = hub.bore * 1e3
            drawn = f"drawn {hub.diameter * 1e3:.4f}"
            rows.append(
                (f"{part.name}: bore mm", f"{d:g} {hole} on a {d:g} {shaft} shaft ({drawn})")
            )
            if hub.key is not None:
                k = {f: getattr(hub.key, f) * 1e3 for f in ("b", "h", "t2")}
                rows.append((f"{part.name}: keyway mm",
                             f"{k['b']:g} JS9 x d + {k['t2']:g}, key {k['b']:g} x {k['h']:g} "
                             "(DIN 6885-1)"))  # fmt: skip
        rows += [(f"{part.name}: gap {what} mm", f"{gap * 1e3:.4g}") for what, gap in part.gaps]
    return rows


def _check_format(fmt: str) -> list[str]:
    if fmt == "all":
        return list(FORMATS)
    if fmt not in FORMATS:
        raise ParameterError("fmt", repr(fmt), "one of " + ", ".join(FORMATS) + ", all")
    return [fmt]


def _tasks(parts, fmts) -> list[tuple[str, object]]:
    """The units of work of an export, in order: ``(format, part)`` and the assembly."""
    out = [(f, p) for f in fmts for p in parts]
    return out + ([("assembly", None)] if "step" in fmts else [])


def _write_planar(parts, fmts, stage: Path, name: str, title: str, progress) -> None:
    solids = {}
    tasks = _tasks(parts, fmts)
    for i, (fmt, part) in enumerate(tasks):
        if progress is not None:
            progress(f"{fmt} {part.name}" if part is not None else "step assembly", i, len(tasks))
        if part is None:
            cp.write_assembly(parts, stage / f"{name}_assembly.step", name, title,
                              [solids[p.name] for p in parts])  # fmt: skip
            continue
        stem = f"{name}_{part.name}"
        if fmt == "dxf":
            cp.write_dxf(part, stage / f"{stem}.dxf", name)
        elif fmt == "stl":
            cp.write_stl(part, stage / f"{stem}.stl")
        elif fmt == "step":
            solids[part.name] = cp.part_solid(part)
            cp.write_step(part, stage / f"{stem}.step", title, solids[part.name])
        else:
            cp.write_csv(part, stage, stem)
    if progress is not None:
        progress("done", len(tasks), len(tasks))


def _write_own(spec, cfg: dict, fmts, stage, name: str, progress) -> None:
    """A drive that writes its own files: one step per format, or one per part where the
    drive reports its parts (``progress(label, done, total)`` counts them as they come)."""
    if progress is None:
        for f in fmts:
            spec.cad_write(cfg, f, stage, name)
        return
    done = 0
    for i, f in enumerate(fmts):
        left = len(fmts) - i - 1
        steps = [1]

        def step(label, k, n, base=done, left=left, steps=steps):
            steps[0] = max(n, 1)
            progress(label, base + k, base + n + left)

        progress(f, done, done + 1 + left)
        spec.cad_write(cfg, f, stage, name, progress=step)
        done += steps[0]
    progress("done", done, done)


def export(cfg: dict, fmt: str, outdir, name: str, progress=None) -> list[Path]:
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
    progress : callable, optional
        ``progress(label, done, total)``, called before each part in each format (and
        the STEP assembly) and once at the end with ``done == total``.

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
    title = str(cfg.get("title") or name)
    with staged_output(outdir, "export-" + "-".join(fmts)) as (stage, written):
        if parts is None:
            _write_own(spec, cfg, fmts, stage, name, progress)
        else:
            _write_planar(parts, fmts, stage, name, title, progress)
    return written
