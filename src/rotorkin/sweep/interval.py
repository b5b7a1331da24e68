"""The admissible interval of one config key, every other key held: ``rotorkin limits``.

A design is admissible when the study accepts it (every refusal of the drive and the
machine: ranges, a drive's geometric limits, the compression
ratio its chamber gaps allow), every check of the drive passes (cam undercut, profile
clearance: :func:`rotorkin.drives.design_checks`) and, when asked, no plausibility
limit is passed (``[limits]``, ``contact.allowable_stress``: results of the study at the
run speed and loads, so each sample is then a full study). All of them
together, not one equation: the interval is where they all hold.

The key's schema range is scanned in one vectorised sweep (the drive's batch kernel:
the refusals of every design at once), the drive's checks are made at each
admissible sample, and each end of the interval that contains the config's value is
refined by bisection between the last admissible and the first refused sample, to
``rtol`` of the key's range. At each end the binding constraint is named: the one-line
refusal of the first design beyond it, the checks it fails, or the schema's bound.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass

import numpy as np

from rotorkin import drives
from rotorkin.core.errors import ConfigError, ParameterError
from rotorkin.io.config import validate_config
from rotorkin.studies.checks import failed, failure_line
from rotorkin.studies.limits import LIMITS
from rotorkin.sweep.spec import DISPLAY_UNITS, bounds_of, field_of

__all__ = ["Interval", "admissible_interval", "DEFAULT_POINTS", "DEFAULT_POINTS_WITH_LIMITS"]

#: Samples of the scan of the key's range (the vectorised scan; with the plausibility
#: limits every sample is a study: :data:`DEFAULT_POINTS_WITH_LIMITS`).
DEFAULT_POINTS = 201
DEFAULT_POINTS_WITH_LIMITS = 41
#: Bisection stops when the bracket is below this fraction of the scanned range.
RTOL = 1e-10


@dataclass(frozen=True)
class Interval:
    """The admissible interval of one key.

    Attributes
    ----------
    key : str
        The config key.
    unit : str
        Unit of ``lo``, ``hi``, ``value`` (deg, mm, ..., "" for a number).
    value : float
        The config's value of the key.
    lo, hi : float
        Ends of the admissible interval that contains ``value`` (nan if ``value`` is
        not admissible: then ``intervals`` still lists what the scan found).
    lo_binds, hi_binds : str
        What binds at each end (a refusal line, failed checks, or the schema's bound).
    intervals : tuple of (float, float)
        Every admissible stretch the scan found, refined.
    value_admissible : bool
        Whether the config's own value is admissible.
    value_reason : str
        Why not ("" when it is).
    points : int
        Samples of the scan.
    values : tuple of int
        An integer key: every admissible value scanned (empty for other keys).
    """

    key: str
    unit: str
    value: float
    lo: float
    hi: float
    lo_binds: str
    hi_binds: str
    intervals: tuple
    value_admissible: bool
    value_reason: str
    points: int
    values: tuple = ()


def _set(raw: dict, key: str, text) -> dict:
    out = copy.deepcopy(raw)
    section, name = key.split(".", 1)
    out.setdefault(section, {})[name] = text
    return out


def _text(field, value: float):
    """The value as the config writes it (with its unit; ints as ints)."""
    if field.kind == "int":
        return int(round(value))
    if field.dimensional:
        unit, factor = DISPLAY_UNITS[field.kind]
        return f"{value * factor:.17g} {unit}"
    return float(value)


class _Judge:
    """Whether a value of the key is admissible, and why not (the scalar study's word)."""

    def __init__(self, raw: dict, key: str, field, with_limits: bool):
        self.raw, self.key, self.field, self.with_limits = raw, key, field, with_limits

    def config(self, value: float) -> dict:
        return validate_config(_set(self.raw, self.key, _text(self.field, value)))

    def reason(self, value: float, full: bool = True) -> str:
        """ "" when admissible; else one line: the refusal, or the checks that fail."""
        try:
            cfg = self.config(value)
            checks = drives.design_checks(cfg)
            if not full:
                bad = failed(checks)
                return "; ".join(failure_line(c) for c in bad)
            result = drives.evaluate(cfg)
        except (ParameterError, ConfigError) as exc:
            return str(exc)
        bad = [c for c in failed(result.checks) if self.with_limits or c.key not in LIMITS]
        return "; ".join(failure_line(c) for c in bad)


def _scan(raw: dict, key: str, values: np.ndarray, judge: _Judge) -> np.ndarray:
    """Admissible flags of the sampled values.

    Without the plausibility limits: one sweep (the drive's vectorised refusals), then
    the drive's checks at the admissible samples (a few ms each). With them: the study
    of every sample (the limits need its results: pressures, contact stresses).
    """
    if judge.with_limits:
        return np.array([judge.reason(float(v)) == "" for v in values])
    from rotorkin.sweep import build_spec, compute, resolve_metrics

    metrics = list(resolve_metrics(validate_config(raw))[:1])
    texts = [_text(judge.field, v) for v in values]
    # no refusal of values past the key's own limit: they are what the scan looks for
    spec = build_spec(raw, {key: texts}, metrics=metrics, check=False, design_checks=False)
    ok = np.asarray(compute(spec, progress=False)["reason"].values == 0).reshape(-1)
    for i in np.flatnonzero(ok):
        ok[i] = judge.reason(values[i], full=False) == ""
    return ok


def _ok(judge: _Judge, value: float, cache: dict) -> bool:
    if value not in cache:
        cache[value] = _fast_ok(judge, value)
    return cache[value]


def _fast_ok(judge: _Judge, value: float) -> bool:
    """One design through the same sweep path as the scan (reasons, limits, checks)."""
    return bool(_scan(judge.raw, judge.key, np.array([value]), judge)[0])


def _refine(judge, good: float, bad: float, span: float) -> tuple[float, float]:
    """Bisect between an admissible and a refused value; the admissible end and the refused."""
    cache: dict = {}
    while abs(bad - good) > RTOL * span:
        mid = 0.5 * (good + bad)
        if mid in (good, bad):
            break
        if _ok(judge, mid, cache):
            good = mid
        else:
            bad = mid
    return good, bad


def admissible_interval(raw: dict, key: str, *, points: int | None = None,
                        lo: float | None = None, hi: float | None = None,
                        with_limits: bool = False) -> Interval:  # fmt: skip
    """The admissible interval of ``key`` with every other key of ``raw`` held.

    Parameters
    ----------
    raw : dict
        The config as written (TOML mapping, units in strings).
    key : str
        A numeric config key (``drive.plate_tilt``, ``machine.casing_radius`` ...).
    points : int, optional
        Samples of the scan (>= 3); a stretch narrower than the sample step may be missed.
        Default :data:`DEFAULT_POINTS` (with the limits :data:`DEFAULT_POINTS_WITH_LIMITS`).
    lo, hi : float, optional
        Scan range [SI]; default the schema's bounds of the key (an unbounded side:
        1000 times the config's value, or 1e6 for 0).
    with_limits : bool
        Count the plausibility limits (``[limits]``, ``contact.allowable_stress``) among the
        constraints: every sample is then a full study (slower).

    Raises
    ------
    ParameterError
        ``--key`` unknown or not numeric, ``--points`` below 3, an empty range.
    """
    base = validate_config(raw)
    spec = drives.spec_of(base)
    kind, machine = base["drive"]["type"], base.get("machine", {}).get("type")
    field = field_of(kind, key, machine)
    if field is None or field.kind not in (*DISPLAY_UNITS, "float", "int"):
        raise ParameterError("--key", repr(key),
                             f"a numeric config key of drive.type = {spec.name} "
                             "(rotorkin keys lists them)")  # fmt: skip
    if points is None:
        points = DEFAULT_POINTS_WITH_LIMITS if with_limits else DEFAULT_POINTS
    if points < 3:
        raise ParameterError("--points", str(points), "an integer >= 3")
    section, name = key.split(".", 1)
    value = float(base.get(section, {}).get(name))
    b_lo, b_hi, lo_open, hi_open = bounds_of(kind, key, machine)
    far = 1e3 * abs(value) if value else 1e6
    s_lo = (b_lo if math.isfinite(b_lo) else -far) if lo is None else float(lo)
    s_hi = (b_hi if math.isfinite(b_hi) else far) if hi is None else float(hi)
    span = s_hi - s_lo
    if not span > 0.0:
        raise ParameterError("--range", f"{s_lo:g}:{s_hi:g}", "lo < hi")
    if field.kind == "int":
        values = np.arange(math.ceil(s_lo), math.floor(s_hi) + 1, dtype=float)
    else:
        # strict schema bounds are never sampled: step in from them by a tiny fraction
        a = s_lo + (RTOL * span if lo_open and lo is None else 0.0)
        b = s_hi - (RTOL * span if hi_open and hi is None else 0.0)
        log = a > 0.0 and b / a > 1e3  # decades of range: sample them evenly
        values = np.geomspace(a, b, points) if log else np.linspace(a, b, points)
        values = np.unique(np.append(values, value if s_lo <= value <= s_hi else []))
    judge = _Judge(raw, key, field, with_limits)
    ok = _scan(raw, key, values, judge)
    stretches = []
    i = 0
    while i < len(values):
        if not ok[i]:
            i += 1
            continue
        j = i
        while j + 1 < len(values) and ok[j + 1]:
            j += 1
        lo_end, lo_why = _end(judge, values, ok, i, -1, span, field)
        hi_end, hi_why = _end(judge, values, ok, j, +1, span, field)
        stretches.append((lo_end, hi_end, lo_why, hi_why))
        i = j + 1
    unit, factor = DISPLAY_UNITS[field.kind] if field.dimensional else ("", 1.0)
    own = next((s for s in stretches if s[0] <= value <= s[1]), None)
    reason = "" if own is not None else judge.reason(value) or "outside the scanned range"
    return Interval(
        key=key, unit=unit, value=value * factor,
        lo=own[0] * factor if own else math.nan, hi=own[1] * factor if own else math.nan,
        lo_binds=own[2] if own else "", hi_binds=own[3] if own else "",
        intervals=tuple((s[0] * factor, s[1] * factor) for s in stretches),
        value_admissible=own is not None, value_reason=reason, points=len(values),
        values=tuple(int(v) for v in values[ok]) if field.kind == "int" else (),
    )  # fmt: skip


def _end(judge, values, ok, i, step, span, field) -> tuple[float, str]:
    """The refined end of an admissible stretch at sample ``i`` toward ``step``; what binds."""
    k = i + step
    if k < 0 or k >= len(values):  # the scan's end: the schema's bound (or the range asked)
        return float(values[i]), "the key's range in the schema (or the range scanned)"
    if field.kind == "int":
        return float(values[i]), judge.reason(float(values[k])) or "refused"
    good, bad = _refine(judge, float(values[i]), float(values[k]), span)
    return good, judge.reason(bad) or "refused"
