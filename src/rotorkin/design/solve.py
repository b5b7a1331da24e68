"""Solve for one config key so that one summary metric hits a target value.

>>> from rotorkin.io.config import load_config
>>> _, raw, _ = load_config()  # the default example
>>> res = solve(raw, "machine.axial_width", "displacement_cm3_per_rev", 800.0)
>>> round(res.value * 1e3, 6)                                 # [mm]
30.651958

The search runs over the key's admissible range: the schema field's bounds
(``ge``/``gt``/``le``/``lt``), narrowed where the drive refuses a design (a design
the drive refuses is not a candidate). It has three steps:

1. a coarse scan of the range (evenly and geometrically spaced values, and the
   config's current value), evaluated in one call of
   :func:`rotorkin.sweep.evaluate_designs` -- the drive's sweep kernel where it has
   one for the key and the metric, else the scalar study design by design;
2. the ends of the admissible stretches located by bisection on the drive's
   reason codes (to a relative 1e-12 with a kernel, 1e-6 without), and the
   metric evaluated there;
3. in the stretch and sign change of ``metric - target`` nearest the current
   value, :func:`scipy.optimize.brentq` to a relative ``rtol`` (default 1e-12).

The key's value is written into a copy of the config in the unit people read
(17 significant digits, e.g. ``"35.412548... mm"``); the metric reached is that of
the scalar study (:func:`rotorkin.drives.evaluate`) at the value as written, so the
residual is that of the config one would run. A target beyond what the scan saw
raises :class:`OutOfReach` naming the range the metric covers.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from rotorkin import drives
from rotorkin.core.batch import DEFAULT_SAMPLES, Designs
from rotorkin.core.errors import ConfigError, ParameterError, RotorkinError
from rotorkin.core.units import metric_units
from rotorkin.design.keys import (
    KeyInfo,
    check_metric,
    key_info,
    numeric_metrics,
    parse_key_value,
    value_text,
    with_values,
)
from rotorkin.io.config import validate_config
from rotorkin.sweep.engine import coverage, evaluate_designs, reason_keys

__all__ = ["End", "SolveResult", "OutOfReach", "solve", "SCAN_KERNEL", "SCAN_SCALAR"]

#: Values per spacing (even, geometric) of the coarse scan with a sweep kernel.
SCAN_KERNEL = 129
#: ... and through the scalar study (about 0.03-0.3 s per design).
SCAN_SCALAR = 12
#: Relative width (of the range) to which the ends of the admissible stretches are located.
EDGE_RTOL_KERNEL, EDGE_RTOL_SCALAR = 1e-12, 1e-6
#: A bound missing from the schema: the search goes this factor beyond the current value.
UNBOUNDED_FACTOR = 1e6


class OutOfReach(RotorkinError):
    """No admissible value of the key brings the metric to the target.

    Attributes
    ----------
    metric : str
    target : float
    covers : (float, float)
        Least and greatest metric value the scan saw (NaN when no design was admissible).
    """

    def __init__(self, message: str, metric: str, target: float, covers: tuple):
        super().__init__(message)
        self.metric, self.target, self.covers = metric, target, covers


@dataclass(frozen=True)
class End:
    """One end of the admissible stretch of the key that holds the solution.

    Attributes
    ----------
    value : float
        The last admissible value found [SI].
    source : str
        ``"schema"`` (the field's bound), ``"drive"`` (beyond it the drive refuses),
        ``"range"`` (the ``within`` range asked for), ``"search"`` (the schema has no
        bound: the search stopped ``1e6`` times beyond the current value) or
        ``"metric"`` (beyond it the metric is undefined).
    detail : str
        One line: the bound, or the drive's message just beyond the end.
    """

    value: float
    source: str
    detail: str


@dataclass(frozen=True)
class SolveResult:
    """What :func:`solve` found.

    Attributes
    ----------
    key, metric : str
    target : float
        In the metric's unit (its name's suffix).
    value : float
        The key's value [SI], as read back from :attr:`value_text`.
    value_text : str or float
        The value written into :attr:`raw` (``"35.41 mm"``; a bare number when
        dimensionless).
    reached : float
        The metric at :attr:`value` (the scalar study's summary when it has the metric).
    residual : float
        ``reached - target``.
    lower, upper : End
        The ends of the admissible stretch that holds the solution.
    roots_seen : int
        Sign changes of ``metric - target`` (and exact hits) the scan saw over the
        whole admissible range; the one nearest :attr:`start` was solved.
    start : float or None
        The config's value of the key [SI] (None when unset).
    evaluations : int
        Designs evaluated.
    kernel : bool
        Evaluated by the drive's sweep kernel (else the scalar study).
    info : KeyInfo
    raw : dict
        The config as written with the key set (write it with
        :func:`rotorkin.io.output.to_toml`).
    warnings : tuple of str
        The study's warnings at the solution (as ``rotorkin run`` prints them): a
        plausibility limit passed, a number without meaning.
    """

    key: str
    metric: str
    target: float
    value: float
    value_text: str | float
    reached: float
    residual: float
    lower: End
    upper: End
    roots_seen: int
    start: float | None
    evaluations: int
    kernel: bool
    info: KeyInfo = field(repr=False)
    raw: dict = field(repr=False, compare=False)
    warnings: tuple = ()

    @property
    def unit(self) -> str:
        """Unit of :attr:`value_text` (``""`` when dimensionless)."""
        return self.info.unit

    @property
    def metric_unit(self) -> str:
        """Unit of the metric, from its name's suffix (``"1"`` when dimensionless)."""
        return metric_units(self.metric)

    @property
    def relative_residual(self) -> float:
        """``|residual| / |target|`` (the residual itself when the target is 0)."""
        return abs(self.residual) / abs(self.target) if self.target else abs(self.residual)

    def to_dict(self) -> dict:
        """A JSON-able record (values in the units people read)."""
        f = self.info.factor
        return {
            "key": self.key,
            "unit": self.unit,
            "value": self.value * f,
            "start": None if self.start is None else self.start * f,
            "metric": self.metric,
            "metric_unit": self.metric_unit,
            "target": self.target,
            "reached": self.reached,
            "residual": self.residual,
            "relative_residual": self.relative_residual,
            "lower_end": {
                "value": self.lower.value * f,
                "source": self.lower.source,
                "detail": self.lower.detail,
            },  # fmt: skip
            "upper_end": {
                "value": self.upper.value * f,
                "source": self.upper.source,
                "detail": self.upper.detail,
            },  # fmt: skip
            "roots_seen": self.roots_seen,
            "evaluations": self.evaluations,
            "evaluated_by": "sweep kernel" if self.kernel else "scalar study",
            "warnings": list(self.warnings),
        }


class _Batch:
    """Designs that differ in one key, evaluated in one call of the sweep machinery."""

    def __init__(self, cfg: dict, info: KeyInfo, metric: str, samples: int):
        self.cfg, self.info, self.metric, self.samples = cfg, info, metric, samples
        fast, _, why = coverage(cfg["drive"]["type"], cfg, [info.key], [metric])
        self.kernel = why is None and fast == [metric]
        self.count = 0

    def __call__(self, x, metric: bool = True):
        """``(values, reason)`` of the designs at ``x`` [SI]; values NaN where refused."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        names = [self.metric] if metric else []
        try:
            res = _evaluate(Designs(self.cfg, {self.info.key: x}, x.size), names, self.samples)
        except RotorkinError:
            raise
        except Exception:  # the study fails on some design: find it, the others stand
            if x.size > 1:
                parts = [self(xi, metric) for xi in x]
                return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])
            self.count += 1
            return np.full(1, np.nan), np.full(1, len(reason_keys(self.drive_type)) - 1, np.int16)
        self.count += x.size
        values = res["metrics"][self.metric] if metric else np.full(x.size, np.nan)
        return values, res["reason"]

    @property
    def drive_type(self) -> str:
        return self.cfg["drive"]["type"]

    def refusal(self, x: float, code: int) -> str:
        """The drive's one-line refusal of the design at ``x`` (its study's message)."""
        cfg = Designs(self.cfg, {self.info.key: np.array([x])}, 1).config(0)
        try:
            with np.errstate(all="ignore"), warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                drives.evaluate(cfg)
        except ParameterError as exc:
            return str(exc)
        except Exception as exc:  # not a refusal: the study cannot evaluate the design
            return (f"the study fails at {self.info.key} = {self.info.show(x)} "
                    f"({type(exc).__name__}: {exc})")  # fmt: skip
        keys = reason_keys(self.drive_type)
        return f"the drive refuses {self.info.key} = {self.info.show(x)} ({keys[int(code)]})"


def _evaluate(p: Designs, names, samples: int) -> dict:
    """:func:`rotorkin.sweep.evaluate_designs`, numpy's floating-point warnings silenced
    (a value that is not finite is checked where it is used)."""
    with np.errstate(all="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return evaluate_designs(p, names, samples)


def _search_range(info: KeyInfo, within) -> tuple[End, End]:
    """The ends of the search [SI] before the drive is asked: schema, ``within`` or search."""
    x0 = info.current
    ends = []
    for side, bound, is_open in (("low", info.low, info.low_open),
                                 ("high", info.high, info.high_open)):  # fmt: skip
        sign = -1.0 if side == "low" else 1.0
        if within is not None:
            value = float(within[0 if side == "low" else 1])
            ends.append(End(value, "range", f"the range asked for ({info.show(value)})"))
            continue
        if bound is not None:
            rel = "<" if is_open else "<="
            what = f"{info.show(bound)} {rel} {info.key}" if side == "low" else \
                f"{info.key} {rel} {info.show(bound)}"  # fmt: skip
            ends.append(End(bound, "schema", f"the schema's bound {what}"))
            continue
        if x0 is None or x0 == 0.0:
            raise ConfigError(f"{info.key} has no {side} bound in the schema and no current "
                              "value to search from: give the range (--within LO:HI)")  # fmt: skip
        # keep the current value's sign: factor 1e6 beyond it on either side
        outward = (sign > 0) == (x0 > 0)
        value = x0 * (UNBOUNDED_FACTOR if outward else 1.0 / UNBOUNDED_FACTOR)
        ends.append(End(value, "search", f"no {side} bound in the schema: searched to "
                                         f"{info.show(value)}"))  # fmt: skip
    lo, hi = ends
    if not lo.value < hi.value:
        raise ConfigError(f"--within: the range of {info.key} is empty ({info.show(lo.value)} "
                          f"... {info.show(hi.value)})")  # fmt: skip
    return lo, hi


def _inner(info: KeyInfo, lo: End, hi: End) -> tuple[float, float]:
    """The first and last values to evaluate: open schema bounds moved inside by 1e-12."""
    a, b = lo.value, hi.value
    step = 1e-12 * max(b - a, abs(a), abs(b))
    if lo.source == "schema" and info.low_open:
        a = a + step
    if hi.source == "schema" and info.high_open:
        b = b - step
    return a, b


def _grid(a: float, b: float, n: int, x0: float | None) -> np.ndarray:
    """Evenly and geometrically spaced values over ``[a, b]`` (and ``x0``), sorted, unique."""
    parts = [np.linspace(a, b, n)]
    if a >= 0.0 or b <= 0.0:
        lo, hi = (a, b) if a >= 0.0 else (-b, -a)
        lo = max(lo, hi * 1e-9)
        if 0.0 < lo < hi:
            g = np.geomspace(lo, hi, n)
            parts.append(g if a >= 0.0 else -g[::-1])
    if x0 is not None and a <= x0 <= b:
        parts.append(np.array([x0]))
    grid = np.unique(np.concatenate(parts))
    return grid[(grid >= a) & (grid <= b)]


def _edge(batch: _Batch, inside: float, outside: float, rtol: float, floor: float):
    """Bisect between an admissible and a refused value: ``(inside, outside, code)``.

    Stops when the two are ``rtol`` apart relative to their size (at least ``floor``);
    halves geometrically while they differ by more than a factor 2 (same sign).
    """
    code = None
    for _ in range(400):
        if abs(outside - inside) <= rtol * max(abs(inside), abs(outside), floor):
            break
        same = inside * outside > 0.0
        ratio = inside / outside if same else 1.0
        mid = (math.copysign(math.sqrt(inside * outside), inside)
               if same and not 0.5 <= ratio <= 2.0 else 0.5 * (inside + outside))  # fmt: skip
        if mid in (inside, outside):
            break
        _, reason = batch(mid, metric=False)
        if reason[0] == 0:
            inside = mid
        else:
            outside, code = mid, int(reason[0])
    if code is None:
        code = int(batch(outside, metric=False)[1][0])
    return inside, outside, code


@dataclass
class _Scan:
    """The evaluated values of the key, sorted, with their metric and admissibility."""

    x: np.ndarray
    f: np.ndarray
    ok: np.ndarray  # admissible and the metric defined
    refused: dict  # x of a refused value -> (code, x of the nearest admissible value)


def _scan(batch: _Batch, a: float, b: float, n: int, rtol_edge: float) -> _Scan:
    grid = _grid(a, b, n, batch.info.current)
    f, reason = batch(grid)
    adm = reason == 0
    extra_in, refused = [], {}
    floor = 1e-9 * (b - a)
    for i in np.flatnonzero(adm[:-1] != adm[1:]):
        inside, outside = (grid[i], grid[i + 1]) if adm[i] else (grid[i + 1], grid[i])
        inside, outside, code = _edge(batch, inside, outside, rtol_edge, floor)
        extra_in.append(inside)
        refused[outside] = (code, inside)
    x = [grid, np.array(list(refused), dtype=float)]
    fv = [f, np.full(len(refused), np.nan)]
    okv = [adm & np.isfinite(f), np.zeros(len(refused), dtype=bool)]
    if extra_in:
        fe, re = batch(np.array(extra_in))
        x.append(np.array(extra_in))
        fv.append(fe)
        okv.append((re == 0) & np.isfinite(fe))
    x, fv, okv = np.concatenate(x), np.concatenate(fv), np.concatenate(okv)
    order = np.argsort(x, kind="stable")
    return _Scan(x[order], fv[order], okv[order], refused)


def _stretch_end(batch: _Batch, scan: _Scan, i: int, step: int, range_end: End) -> End:
    """The end of the admissible stretch through ``scan.x[i]`` in direction ``step``."""
    j = i
    while 0 <= j + step < scan.x.size and scan.ok[j + step]:
        j += step
    k = j + step
    if not 0 <= k < scan.x.size:
        return End(scan.x[j], range_end.source, range_end.detail)
    xk = scan.x[k]
    if xk in scan.refused:
        code, _ = scan.refused[xk]
        return End(scan.x[j], "drive", batch.refusal(xk, code))
    if np.isnan(scan.f[k]):
        # a refused grid value whose edge was not refined (it sits beside another refused one)
        # or an admissible design without the metric
        _, reason = batch(xk, metric=False)
        if reason[0] != 0:
            return End(scan.x[j], "drive", batch.refusal(xk, int(reason[0])))
        return End(scan.x[j], "metric", f"{batch.metric} is undefined at {batch.info.key} = "
                                        f"{batch.info.show(xk)}")  # fmt: skip
    return End(scan.x[j], "drive", f"{batch.info.key} = {batch.info.show(xk)}")


def _roots(scan: _Scan, target: float) -> list[tuple[int, int]]:
    """Brackets ``(i, j)`` of consecutive admissible values with a sign change (or a hit)."""
    d = np.where(scan.ok, scan.f - target, np.nan)
    hits = np.flatnonzero(d == 0.0)
    sign = np.sign(d)
    cross = np.flatnonzero(sign[:-1] * sign[1:] < 0.0)  # NaN (refused) compares False
    pairs = [(int(i), int(i)) for i in hits] + [(int(i), int(i) + 1) for i in cross]
    return sorted(pairs)


def _fmt(value: float) -> str:
    return f"{value:.6g}"


def solve(raw: dict, key: str, metric: str, target: float, *, within=None, scan=None,
          rtol: float = 1e-12, samples: int = DEFAULT_SAMPLES) -> SolveResult:  # fmt: skip
    """Find the value of ``key`` at which ``metric`` equals ``target``.

    Parameters
    ----------
    raw : dict
        The config as written (``raw`` of :func:`rotorkin.io.config.load_config`).
    key : str
        A continuous config key (``"machine.casing_radius"``): a number or a quantity.
    metric : str
        A numeric summary key of the study (``rotorkin run``'s ``summary.json``) or a
        sweep metric of the drive (``"flow_mean_l_per_min"``).
    target : float
        In the metric's unit (its name's suffix: l/min, cm^3/rev, deg, ...).
    within : (float or str, float or str), optional
        Search only this range of the key: SI floats, or values as written
        (``"30 mm"``), inside the schema's bounds.
    scan : int, optional
        Values per spacing of the coarse scan (default :data:`SCAN_KERNEL` with a
        kernel, :data:`SCAN_SCALAR` without).
    rtol : float
        Relative tolerance of the key (:func:`scipy.optimize.brentq`), >= 1e-15.
    samples : int
        Shaft angles per period of the sampled peaks (as ``rotorkin run``).

    Returns
    -------
    SolveResult

    Raises
    ------
    ConfigError
        Unknown or non-continuous key, unknown metric, bad target or range (one line).
    OutOfReach
        No sign change of ``metric - target`` over the admissible range (one line
        naming the range the metric covers).
    """
    from scipy.optimize import brentq

    cfg = validate_config(raw)
    info = key_info(raw, cfg, key, "--for")
    check_metric(metric, numeric_metrics(cfg), f"--target {metric}={target}")
    target = float(target)
    if not math.isfinite(target):
        raise ConfigError(f"--target {metric} = {target} is not admissible: a finite number")
    if not 1e-15 <= rtol < 1.0:
        raise ParameterError("rtol", rtol, "1e-15 <= rtol < 1")
    if within is not None:
        within = tuple(parse_key_value(info, v, "--within") if isinstance(v, str) else float(v)
                       for v in within)  # fmt: skip
        if len(within) != 2:
            raise ConfigError("--within is not admissible: write it as LO:HI")
        for v in within:
            if not info.inside(v):
                raise ConfigError(f"--within: {info.key} = {info.show(v)} is not "
                                  f"admissible: {info.admissible()}")  # fmt: skip
    batch = _Batch(cfg, info, metric, int(samples))
    n = int(scan) if scan is not None else (SCAN_KERNEL if batch.kernel else SCAN_SCALAR)
    if n < 2:
        raise ParameterError("scan", n, "scan >= 2")
    lo, hi = _search_range(info, within)
    a, b = _inner(info, lo, hi)
    sc = _scan(batch, a, b, n, EDGE_RTOL_KERNEL if batch.kernel else EDGE_RTOL_SCALAR)
    brackets = _roots(sc, target)
    if not brackets:
        raise _out_of_reach(info, metric, target, sc, a, b)
    x0 = info.current if info.current is not None else 0.5 * (a + b)

    def distance(br):
        xa, xb = sc.x[br[0]], sc.x[br[1]]
        return 0.0 if xa <= x0 <= xb else min(abs(x0 - xa), abs(x0 - xb))

    i, j = min(brackets, key=distance)
    if i == j:
        root = float(sc.x[i])
    else:

        def residual(x):
            value, reason = batch(x)
            if reason[0] != 0:
                raise ParameterError(key, info.show(x), "refused by the drive inside the "
                                     "admissible stretch the scan saw; narrow the search "
                                     "with --within")  # fmt: skip
            return float(value[0]) - target

        xa, xb = float(sc.x[i]), float(sc.x[j])
        xtol = 1e-15 * max(abs(a), abs(b), b - a)
        root = float(brentq(residual, xa, xb, xtol=xtol, rtol=rtol, maxiter=500))
    lower = _stretch_end(batch, sc, i, -1, lo)
    upper = _stretch_end(batch, sc, j, +1, hi)
    solved_raw, solved_cfg = with_values(raw, [info], [root])
    section, _, name = key.partition(".")
    value = float(solved_cfg[section][name])
    reached, notes = _reached(batch, solved_cfg, value)
    span = np.nanmax(np.abs(sc.f[sc.ok])) if np.any(sc.ok) else abs(target)
    if not abs(reached - target) <= 1e-8 * max(abs(target), span):
        raise _jump(batch, info, metric, target, value)
    return SolveResult(key, metric, target, value, value_text(info, root), reached,
                       reached - target, lower, upper, len(brackets), info.current,
                       batch.count, batch.kernel, info, solved_raw, notes)  # fmt: skip


def _reached(batch: _Batch, cfg: dict, value: float) -> tuple[float, tuple]:
    """The metric of the solved config (the scalar study's, or the kernel's sweep metric)
    and the study's warnings (plausibility limits passed, numbers without meaning)."""
    try:
        with np.errstate(all="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            result = drives.evaluate(cfg)
    except ParameterError as exc:
        raise ParameterError(batch.info.key, batch.info.show(value),
                             f"it brings {batch.metric} to the target but the drive refuses "
                             f"it: {exc}") from None  # fmt: skip
    batch.count += 1
    notes = tuple(result.warnings)
    if batch.metric in result.summary:
        return float(result.summary[batch.metric]), notes
    f, _ = batch(value)
    return float(f[0]), notes


def _out_of_reach(info: KeyInfo, metric: str, target: float, sc: _Scan, a: float, b: float):
    unit = metric_units(metric)
    unit = "" if unit == "1" else f" {unit}"
    if not np.any(sc.ok):
        return OutOfReach(f"--target {metric} = {_fmt(target)}{unit} is out of reach: the drive "
                          f"refuses every {info.key} from {info.show(a)} to {info.show(b)} the "
                          f"scan tried (or {metric} is undefined there)", metric, target,
                          (math.nan, math.nan))  # fmt: skip
    x = sc.x[sc.ok]
    low, high = float(np.min(sc.f[sc.ok])), float(np.max(sc.f[sc.ok]))
    return OutOfReach(f"--target {metric} = {_fmt(target)}{unit} is out of reach: over the "
                      f"admissible {info.key} from {info.show(x[0])} to {info.show(x[-1])} it "
                      f"covers {_fmt(low)} ... {_fmt(high)}{unit}", metric, target,
                      (low, high))  # fmt: skip


def _jump(batch: _Batch, info: KeyInfo, metric: str, target: float, x: float):
    """The metric jumps across the target at ``x``: no value of the key gives it."""
    h = 1e-9 * max(abs(x), 1e-300)
    f, _ = batch(np.array([x - h, x + h]))
    unit = metric_units(metric)
    unit = "" if unit == "1" else f" {unit}"
    return OutOfReach(f"--target {metric} = {_fmt(target)}{unit} is out of reach: {metric} jumps "
                      f"across it at {info.key} = {info.show(x)} (from {_fmt(f[0])} to "
                      f"{_fmt(f[1])}{unit})", metric, target,
                      (float(f[0]), float(f[1])))  # fmt: skip
