"""Writing a run's results: summary.json, motion.csv, config.toml, README.txt and figures.

Everything is written into a staging folder first and moved into place only
when all of it has been written, so a failure never leaves a half-written
output behind.
"""

from __future__ import annotations

import contextlib
import errno
import json
import math
import os
import shutil
import tempfile
from pathlib import Path

import numpy as np

from rotorkin.core.errors import ConfigError

__all__ = [
    "write_outputs",
    "staged_output",
    "output_lock",
    "check_out",
    "out_error",
    "to_toml",
]


def write_outputs(result, outdir: Path, raw_config: dict, meta: dict) -> list[Path]:
    """Write every output file of a study into ``outdir``, atomically per file.

    Parameters
    ----------
    result : rotorkin.studies.StudyResult
    outdir : Path
        Created if missing; files of the same names are replaced.
    raw_config : dict
        The config as written (after ``--set``), saved as ``config.toml``.
    meta : dict
        Extra flat entries for ``summary.json`` (name, version).

    Returns
    -------
    list of Path
        The files written, in ``outdir``.
    """
    with staged_output(outdir) as (stage, written):
        summary = {**meta, **result.summary}
        (stage / "summary.json").write_text(json.dumps(_jsonable(summary), indent=2) + "\n")
        _write_csv(stage / "motion.csv", result.columns)
        (stage / "config.toml").write_text(to_toml(raw_config))
        if result.checks:
            write_checks(stage / "checks.csv", result.checks)
        figures = result.write_figures(stage)
        (stage / "README.txt").write_text(_readme(result, [Path(f).name for f in figures]))
    return written


@contextlib.contextmanager
def output_lock(outdir):
    """Hold the lock of an output folder for the block: one writer at a time.

    The lock is ``.<name>.lock`` beside ``outdir`` (``fcntl.flock``, released by the
    system when the process dies). A second writer of the same folder is refused in
    one line naming the first one's process id.
    """
    import fcntl

    outdir = Path(outdir)
    parent = outdir.parent if str(outdir.parent) else Path(".")
    path = parent / f".{outdir.name}.lock"
    try:
        fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
    except OSError as exc:
        out_error(outdir, exc)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            holder = os.pread(fd, 32, 0).decode(errors="replace").strip() or "?"
            raise ConfigError(
                f"--out = {str(outdir)!r} is being written by another rotorkin (process "
                f"{holder}): wait until it ends, or choose another --out"
            ) from None
        os.ftruncate(fd, 0)
        os.pwrite(fd, str(os.getpid()).encode(), 0)
        try:
            yield path
        finally:
            with contextlib.suppress(OSError):
                path.unlink()
    finally:
        os.close(fd)


#: errno values that say the --out path itself is wrong (bad input), not the machine.
_PATH_ERRORS = {errno.ENOTDIR, errno.EEXIST, errno.ENAMETOOLONG, errno.EINVAL, errno.EISDIR}


def out_error(outdir, exc: OSError):
    """Raise for a folder that cannot be written: bad input (exit 2) or the machine (exit 3).

    A path through a file, or too long, is the user's: one :class:`ConfigError`
    line. No permission, a read-only or full disk is the machine's: the
    :class:`OSError` goes on (the command line says what to do, exit 3).
    """
    if exc.errno in _PATH_ERRORS:
        raise ConfigError(f"--out = {str(outdir)!r} cannot be written: {exc.strerror}") from None
    raise exc


def check_out(outdir) -> None:
    """Refuse an output folder that is a file or lies under one, before any work is done."""
    outdir = Path(outdir)
    if "\0" in str(outdir):
        raise ConfigError("--out is not admissible: a folder name cannot hold a NUL character")
    if outdir.exists() and not outdir.is_dir():
        raise ConfigError(f"--out = {str(outdir)!r} is not admissible: it is a file, not a folder")
    for up in outdir.parents:
        if up.exists():
            if not up.is_dir():
                raise ConfigError(
                    f"--out = {str(outdir)!r} is not admissible: {str(up)!r} is a file"
                )
            break


def _make_parents(parent: Path) -> list[Path]:
    """Create ``parent`` and its missing ancestors; return the ones created (deepest last)."""
    missing = []
    p = parent
    while not p.exists() and p != p.parent:
        missing.append(p)
        p = p.parent
    for d in reversed(missing):
        d.mkdir()
    return list(reversed(missing))


def _remove_empty(folders: list[Path]) -> None:
    """Remove the folders a failed output created, deepest first, if still empty."""
    for d in reversed(folders):
        with contextlib.suppress(OSError):
            d.rmdir()


@contextlib.contextmanager
def staged_output(outdir, kind: str = "run"):
    """A staging folder beside ``outdir`` whose files move into ``outdir`` at the end.

    Yields ``(stage, written)``: write every output file into ``stage``; when the
    block ends without an error they are moved into ``outdir`` (created if missing)
    with ``os.replace``, in name order, and ``written`` receives their final paths.
    On an error (or SIGTERM, which the command line turns into an exception)
    nothing reaches ``outdir``, and folders created for it are removed again. The
    staging folder is always removed; one left by a killed run (SIGKILL) is removed
    by the next output into the same folder. One writer at a time
    (:func:`output_lock`).

    Files that an earlier output of the same ``kind`` (``"run"``, ``"export"``, ...)
    wrote into ``outdir`` and this one does not write again are removed, so that a
    figure of the last run never sits beside the summary of this one. They are known
    from a hidden manifest, ``outdir/.rotorkin-<kind>.files``; files rotorkin did not
    write are never touched.

    Raises
    ------
    ConfigError
        ``outdir`` is a file, it or its parent cannot be created, or another
        rotorkin is writing it.
    """
    outdir = Path(outdir)
    check_out(outdir)
    parent = outdir.parent if outdir.parent != Path("") else Path(".")
    try:
        created = _make_parents(parent)
    except OSError as exc:
        out_error(outdir, exc)
    ok = False
    try:
        with output_lock(outdir):
            for stale in parent.glob(f".{glob_escape(outdir.name)}.tmp-*"):
                shutil.rmtree(stale, ignore_errors=True)  # a killed run's staging folder
            try:
                stage = Path(tempfile.mkdtemp(prefix=f".{outdir.name}.tmp-", dir=parent))
            except OSError as exc:
                out_error(outdir, exc)
            written: list[Path] = []
            try:
                yield stage, written
                try:
                    outdir.mkdir(parents=True, exist_ok=True)
                except OSError as exc:
                    out_error(outdir, exc)
                manifest = outdir / f".rotorkin-{kind}.files"
                earlier = _read_manifest(manifest)
                for item in sorted(stage.iterdir()):
                    os.replace(item, outdir / item.name)
                    written.append(outdir / item.name)
                names = [p.name for p in written]
                for name in sorted(set(earlier) - set(names)):
                    with contextlib.suppress(OSError):
                        (outdir / name).unlink()
                tmp = stage / manifest.name
                tmp.write_text("\n".join(names) + "\n")
                os.replace(tmp, manifest)
                ok = True
            finally:
                shutil.rmtree(stage, ignore_errors=True)
    finally:
        if not ok and not outdir.exists():
            _remove_empty(created)


def glob_escape(name: str) -> str:
    """``name`` with the glob characters ``*?[`` taken literally."""
    return "".join(f"[{c}]" if c in "*?[" else c for c in name)


def _read_manifest(path: Path) -> list[str]:
    """Names listed in a manifest; only plain names (no folders), so nothing outside is hit."""
    try:
        lines = path.read_text().splitlines()
    except OSError:
        return []
    return [n for n in lines if n and n == Path(n).name and not n.startswith(".")]


def _jsonable(summary: dict) -> dict:
    """JSON values; a value that is not finite is left out and named under ``undefined``.

    (Why it has no value is one of the run's warnings.)
    """
    out, undefined = {}, []
    for key, value in summary.items():
        if isinstance(value, np.generic):
            value = value.item()
        if isinstance(value, float) and not math.isfinite(value):
            undefined.append(key)
            continue
        out[key] = value
    if undefined:
        out["undefined"] = undefined
    return out


def _write_csv(path: Path, columns: dict) -> None:
    names = list(columns)
    data = np.column_stack([np.asarray(columns[n], dtype=float) for n in names])
    np.savetxt(path, data, delimiter=",", header=",".join(names), comments="", fmt="%.12g")


def write_checks(path: Path, checks) -> Path:
    """Write a design's checks (:class:`rotorkin.studies.checks.Check`) as CSV; the path.

    Columns: ``check, key, value, limit, unit, sense, margin, passed, where`` (``sense``
    ``<=`` for an upper limit, ``>=`` for a lower one; ``margin`` > 0 when it passes).
    """
    import csv

    with Path(path).open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["check", "key", "value", "limit", "unit", "sense", "margin", "passed",
                    "where"])  # fmt: skip
        for c in checks:
            w.writerow([c.name, c.key, f"{c.value:.12g}", f"{c.limit:.12g}", c.unit,
                        "<=" if c.upper else ">=", f"{c.margin:.12g}",
                        "true" if c.passed else "false", c.where])  # fmt: skip
    return Path(path)


def _readme(result, figures: list[str]) -> str:
    lines = [
        f"rotorkin results: {result.title}",
        "",
        "summary.json  flat metrics; the unit is the key's suffix (_deg, _mm, _Nm, _J ...)",
        "motion.csv    one row per input angle over one period, ends included; columns:",
    ]
    width = max(len(n) for n in result.columns)
    lines += [f"  {n.ljust(width)}  {result.column_docs[n]}" for n in result.columns]
    lines += ["config.toml   the configuration as run (after --set overrides)"]
    if result.checks:
        lines += ["checks.csv    the design's checks: value, limit, margin (> 0: passes), where"]
    lines += ["figures:"]
    lines += [f"  {f}" for f in figures]
    return "\n".join(lines) + "\n"


def to_toml(data: dict) -> str:
    """A small TOML writer for configs: nested tables of scalars, strings and lists."""
    top = [(k, v) for k, v in data.items() if not isinstance(v, dict)]
    tables = [(k, v) for k, v in data.items() if isinstance(v, dict)]
    lines = [f"{k} = {_toml_value(v)}" for k, v in top]
    for name, table in tables:
        lines += ["", f"[{name}]"]
        lines += [f"{k} = {_toml_value(v)}" for k, v in table.items() if not isinstance(v, dict)]
    return "\n".join(lines).lstrip("\n") + "\n"


def _toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    return json.dumps(str(value))
