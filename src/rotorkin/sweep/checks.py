"""The design checks of ``rotorkin run`` across a sweep: each check's margin per design.

Every check that ``run`` prints (:mod:`rotorkin.studies.checks`) becomes a variable of
the sweep, ``check_<what>_margin[_<unit>]``, positive where the design passes, in the
unit of the check (``limit - value`` for an upper limit, ``value - limit`` for a lower
one); NaN where the design is inadmissible or the check was not computed.

* The drive's own checks (:func:`rotorkin.drives.design_checks`: a roller against the
  undercut of its cam, a profile's pressure angle, ...) depend on the geometry only, not
  on the speed or the loads: they are computed once per distinct geometry of the grid
  (the swept keys outside :data:`NOT_GEOMETRY`), a few milliseconds each. A design that
  a check refuses outright (as ``run`` and ``export`` would) is inadmissible, with the
  check's config key as its ``reason``. A grid of more than :data:`MAX_GEOMETRIES`
  distinct geometries does not record them (said by ``rotorkin sweep`` and in the
  Dataset's ``design_checks`` attribute): sweep fewer drive and cam values, or check a chosen
  design with ``rotorkin run``.
* The plausibility limits (:data:`rotorkin.studies.limits.LIMITS`) measured by the swept
  metrics: the worst of those metrics against the limit (the ``violations`` bits say
  the same as a yes/no).
"""

from __future__ import annotations

import math
import re
import warnings

import numpy as np

from rotorkin import drives
from rotorkin.core.errors import ConfigError, ParameterError
from rotorkin.studies.checks import LIMIT_NAMES
from rotorkin.studies.limits import LIMITS, limit_value

__all__ = [
    "PREFIX",
    "NOT_GEOMETRY",
    "MAX_GEOMETRIES",
    "metric_name",
    "is_check",
    "limit_metric",
    "check_metrics",
    "geometries",
    "skipped",
    "note",
    "fill_drive_checks",
    "fill_limit_checks",
]

#: Prefix of a check's variable.
PREFIX = "check_"
#: Config sections whose keys do not move the drive's own checks.
NOT_GEOMETRY = ("run", "loads", "contact")
#: Most distinct geometries whose drive checks a sweep computes (1-20 ms each).
MAX_GEOMETRIES = 2048

_UNITS = {"mm": "_mm", "deg": "_deg", "bar": "_bar", "MPa": "_MPa", "K": "_K"}


def _slug(text: str) -> str:
    return re.sub(r"[^a-z0-9]+", "_", text.lower()).strip("_")


def metric_name(name: str, unit: str) -> str:
    """The sweep variable of a check named ``name`` measured in ``unit``."""
    return f"{PREFIX}{_slug(name)}_margin{_UNITS.get(unit, '')}"


def is_check(metric: str) -> bool:
    """Whether a sweep variable is a check's margin."""
    return metric.startswith(PREFIX)


def limit_metric(key: str) -> str:
    """The variable of a plausibility limit (config key of :data:`LIMITS`)."""
    return metric_name(LIMIT_NAMES[key], LIMITS[key][2])


def _matching(key: str, metrics) -> list[str]:
    pattern = LIMITS[key][0]
    return [m for m in metrics if not is_check(m) and re.search(pattern, m)]


def _base_checks(cfg: dict) -> list:
    try:
        return list(drives.design_checks(cfg))
    except (ParameterError, ConfigError):
        return []


def geometries(varies) -> int:
    """Distinct geometries of a grid: the product of the swept values outside
    :data:`NOT_GEOMETRY`."""
    return math.prod(len(v) for v in varies if v.key.split(".")[0] not in NOT_GEOMETRY)


def skipped(cfg: dict, varies) -> str | None:
    """Why the drive's checks are not recorded for this grid, or None."""
    n = geometries(varies)
    if n <= MAX_GEOMETRIES or not _base_checks(cfg):
        return None
    return (f"the drive's design checks are not recorded: {n} distinct geometries (at most "
            f"{MAX_GEOMETRIES}); sweep fewer drive and cam values, or check a design with "
            "rotorkin run")  # fmt: skip


def note(cfg: dict, varies, metrics) -> str:
    """What a sweep's Dataset says of its checks (its ``design_checks`` attribute)."""
    why = skipped(cfg, varies)
    if why is not None:
        return why
    if any(is_check(m) for m in metrics):
        return "recorded as the check_* variables (margins)"
    return "none: the drive has no design checks and no swept metric measures a limit"


def check_metrics(cfg: dict, varies, metrics) -> tuple[str, ...]:
    """The check variables of a sweep of ``cfg`` over ``varies`` with ``metrics``.

    The drive's checks of the base design (unless :func:`skipped`: the Dataset's
    ``design_checks`` attribute says so, ``rotorkin sweep`` prints it), then one per
    plausibility limit that a swept metric measures.
    """
    out = []
    if skipped(cfg, varies) is None:
        out += [metric_name(c.name, c.unit) for c in _base_checks(cfg)]
    out += [limit_metric(key) for key in LIMITS if _matching(key, metrics)]
    return tuple(dict.fromkeys(out))


def fill_drive_checks(p, names, out: dict, reason: np.ndarray, code: dict) -> None:
    """The drive's check margins of the admissible designs of ``p``, once per geometry.

    ``out[name]`` (n,) arrays are filled for the ``names`` that are drive checks; a
    geometry a check refuses gets that check's key in ``reason`` (the other metrics of
    those designs are set NaN by the caller).
    """
    limits_vars = {limit_metric(k) for k in LIMITS}
    wanted = [m for m in names if m not in limits_vars]
    if not wanted:
        return
    todo = np.flatnonzero(reason == 0)
    if todo.size == 0:
        return
    members = _geometries(p, todo)
    for idx in members:
        try:
            found = drives.design_checks(p.config(int(idx[0])))
        except (ParameterError, ConfigError) as exc:
            reason[idx] = code.get(getattr(exc, "name", ""), code["other"])
            continue
        for c in found:
            name = metric_name(c.name, c.unit)
            if name in out:
                out[name][idx] = c.margin


def _geometries(p, todo: np.ndarray) -> list[np.ndarray]:
    """The designs ``todo`` grouped by their geometry (equal values of every swept key
    outside :data:`NOT_GEOMETRY`), vectorised: each key's values as integer codes, the
    codes combined into one, the designs sorted by it."""
    keys = [k for k in p.table if k.split(".")[0] not in NOT_GEOMETRY]
    if not keys:
        return [todo]
    codes, sizes = [], []
    for k in keys:
        values, inverse = np.unique(np.asarray(p.table[k])[todo], return_inverse=True)
        codes.append(inverse.reshape(-1))
        sizes.append(len(values))
    combined = np.ravel_multi_index(codes, sizes)
    order = np.argsort(combined, kind="stable")
    starts = np.flatnonzero(np.diff(combined[order], prepend=-1))
    return np.split(todo[order], starts[1:])


def fill_limit_checks(p, names, out: dict) -> None:
    """The plausibility limits' margins from the swept metrics in ``out`` (worst of each)."""
    for key in LIMITS:
        name = limit_metric(key)
        if name not in names:
            continue
        scale = LIMITS[key][3]
        table = p.table.get(key)
        limit = (limit_value(p.cfg, key) if table is None else np.asarray(table, float)) * scale
        measured = [np.asarray(out[m], dtype=float) for m in _matching(key, out)]
        with warnings.catch_warnings(), np.errstate(invalid="ignore"):
            warnings.simplefilter("ignore", RuntimeWarning)
            worst = np.nanmax(np.vstack(measured), axis=0) if measured else np.nan
        out[name][:] = limit - worst
