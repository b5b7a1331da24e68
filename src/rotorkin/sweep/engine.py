"""Evaluating batches of designs: the kernels, the scalar fallback, chunks, the result.

A sweep is a grid of designs (the outer product of the swept values, flattened
in C order: the last ``--vary`` key varies fastest). It is cut into chunks of
consecutive designs; :func:`compute_chunk` evaluates one chunk (the unit of
work of the local loop, of a dask task and of a committed file), and
:func:`to_result` shapes the flat results into a :class:`~rotorkin.sweep.result.SweepResult`
(the variables of the sweep's Dataset as numpy arrays) and :func:`to_dataset` into an
:class:`xarray.Dataset`.
"""

from __future__ import annotations

import json
import warnings
from dataclasses import dataclass, field

import numpy as np

from rotorkin import __version__, drives
from rotorkin.core.batch import DEFAULT_SAMPLES, Designs, sample_grid
from rotorkin.core.errors import ParameterError, RotorkinError, shown
from rotorkin.core.fused import prefer_compiled
from rotorkin.core.units import metric_units
from rotorkin.io.config import glossary
from rotorkin.studies import limits
from rotorkin.sweep import checks as sweep_checks
from rotorkin.sweep.result import SweepResult, Variable
from rotorkin.sweep.spec import display

__all__ = [
    "SweepSpec",
    "SweepFallbackWarning",
    "kernel_of",
    "reason_keys",
    "check_spec_values",
    "check_grid_values",
    "check_study",
    "evaluate_designs",
    "compute_chunk",
    "chunk_bounds",
    "to_result",
    "to_dataset",
    "metric_units",
]


class SweepFallbackWarning(UserWarning):
    """Some metrics or keys are not vectorized: evaluated design by design by the scalar study."""


class _NoBatch:
    """Stands for the batch module of a drive that has none: every design goes through its study."""

    KEYS = frozenset()
    CURVES = ()
    ANGLE = ("theta_deg", "input angle")

    @staticmethod
    def unsupported(cfg):
        return "the drive has no batch evaluation"

    @staticmethod
    def metric_names(cfg):
        return ()

    @staticmethod
    def period(p):
        return 2.0 * np.pi


def kernel_of(drive_type: str, cfg: dict | None = None):
    """The batch module of a drive type (``DriveSpec.batch``; a stand-in when it has none).

    With ``cfg``, the batch module of the spec that evaluates it
    (:func:`rotorkin.drives.spec_of`): none for a drive carrying another machine.
    """
    spec = drives.get(drive_type) if cfg is None else drives.spec_of(cfg)
    return spec.batch or _NoBatch


def reason_keys(drive_type: str) -> list[str]:
    """The reason table of a drive: ``"ok"``, every config key of the drive, ``"other"``.

    The ``reason`` variable of a sweep holds indices into this list: the config
    key whose admissible range the design violates (the one the scalar study
    would name in its error).
    """
    return ["ok", *(key for _, key, _, _ in glossary(drive_type)), "other"]


@dataclass(frozen=True)
class SweepSpec:
    """Everything that defines a sweep's numbers (and nothing about where it runs).

    Attributes
    ----------
    name : str
        Run name (example name or config file stem).
    base_raw, base_cfg : dict
        The base config as written and validated (SI).
    varies : tuple of Vary
        The swept keys, in order (the last one varies fastest).
    metrics : tuple of str
        Summary keys in the result.
    samples : int
        Shaft angles per period for the sampled peaks.
    keep_curves : bool
        Also keep the kernel's curves over ``points`` angles per design.
    points : int
        Angles per period of the curves (``run.points``).
    chunk_size : int
        Designs per chunk.
    """

    name: str
    base_raw: dict
    base_cfg: dict
    varies: tuple
    metrics: tuple
    samples: int = DEFAULT_SAMPLES
    keep_curves: bool = False
    points: int = 721
    chunk_size: int = 4096
    extra: dict = field(default_factory=dict)

    @property
    def drive_type(self) -> str:
        return self.base_cfg["drive"]["type"]

    @property
    def shape(self) -> tuple:
        return tuple(len(v) for v in self.varies)

    @property
    def size(self) -> int:
        return int(np.prod(self.shape, dtype=np.int64))

    @property
    def n_chunks(self) -> int:
        return -(-self.size // self.chunk_size)

    def manifest(self) -> dict:
        """A JSON-able description; two specs with equal manifests give equal numbers."""

        return {
            "format": "rotorkin-sweep-1",
            "rotorkin_version": __version__,
            "name": self.name,
            "drive_type": self.drive_type,
            "base_raw": self.base_raw,
            "vary": [
                {"key": v.key, "text": v.text, "values": list(v.values)} for v in self.varies
            ],  # fmt: skip
            "metrics": list(self.metrics),
            "samples": self.samples,
            "keep_curves": self.keep_curves,
            "points": self.points,
            "chunk_size": self.chunk_size,
            "designs": self.size,
            "chunks": self.n_chunks,
        }

    def designs(self, start: int, stop: int) -> Designs:
        """The designs ``start <= i < stop`` of the flattened grid."""
        idx = np.unravel_index(np.arange(start, stop), self.shape) if self.varies else ()
        table = {v.key: v.array()[i] for v, i in zip(self.varies, idx, strict=True)}
        return Designs(self.base_cfg, table, stop - start, self.extra)


def chunk_bounds(spec: SweepSpec, index: int) -> tuple[int, int]:
    """First and one-past-last design of chunk ``index``."""
    start = index * spec.chunk_size
    return start, min(start + spec.chunk_size, spec.size)


def coverage(drive_type: str, cfg: dict, keys, metrics) -> tuple[list, list, str | None]:
    """Split ``metrics`` into kernel-computed and fallback ones; the reason of any fallback.

    Returns
    -------
    (kernel_metrics, fallback_metrics, why)
        ``why`` is None when nothing falls back.
    """
    kern = kernel_of(drive_type, cfg)
    metrics = [m for m in metrics if not sweep_checks.is_check(m)]
    why = kern.unsupported(cfg)
    if why is None:
        outside = sorted(set(keys) - kern.KEYS)
        if outside:
            why = f"the kernel does not vary {', '.join(outside)}"
    if why is not None:
        return [], list(metrics), why
    names = set(kern.metric_names(cfg)) | set(optional_metrics(kern, cfg))
    fast = [m for m in metrics if m in names]
    slow = [m for m in metrics if m not in names]
    return fast, slow, (f"{len(slow)} metric(s) are not vectorized ({', '.join(slow[:4])}"
                        f"{', ...' if len(slow) > 4 else ''})" if slow else None)  # fmt: skip


def optional_metrics(kern, cfg: dict) -> tuple[str, ...]:
    """The metrics a kernel computes on request only, for this base config.

    A kernel's ``optional_metrics(cfg)`` when it has one (they depend on the config), else
    its ``OPTIONAL_METRICS``.
    """
    if hasattr(kern, "optional_metrics"):
        return tuple(kern.optional_metrics(cfg))
    return tuple(getattr(kern, "OPTIONAL_METRICS", ()))


def warn_fallback(why: str | None, designs: int) -> None:
    """Warn once per sweep that the scalar study runs design by design."""
    if why:
        warnings.warn(
            f"{why}: those are evaluated design by design with rotorkin.drives.evaluate "
            f"({designs} designs; slow, about 30-100 ms each)",
            SweepFallbackWarning,
            stacklevel=3,
        )


def evaluate_designs(p: Designs, metrics, samples: int = DEFAULT_SAMPLES, threads=None,
                     curves: int = 0) -> dict:  # fmt: skip
    """Metrics (and curves) of the designs ``p``: kernels first, scalar study where needed.

    Parameters
    ----------
    p : Designs
    metrics : sequence of str
        Summary keys wanted, and check variables (:mod:`rotorkin.sweep.checks`).
    samples : int
        Angles per period of the sampled peaks.
    threads : int, optional
        Threads of the kernels (default: all cores).
    curves : int
        Keep the kernel's curves over this many angles (0: none).

    Returns
    -------
    dict
        ``"metrics"``: name -> (n,) float64, NaN where inadmissible; ``"reason"``:
        (n,) int16 codes into :func:`rotorkin.core.batch.reason_keys`;
        with ``curves``: ``"curves"`` name -> (n, curves) and ``"angle"`` [rad].
    """
    drive_type = p.cfg["drive"]["type"]
    kern = kernel_of(drive_type, p.cfg)
    keys = reason_keys(drive_type)
    code = {k: i for i, k in enumerate(keys)}
    checks = [m for m in metrics if sweep_checks.is_check(m)]
    fast, slow, why = coverage(drive_type, p.cfg, p.table, metrics)
    n = p.n
    prefer_compiled(n * samples)  # a sweep's kernels evaluate its designs in blocks
    out = {m: np.full(n, np.nan) for m in metrics}
    curve_out = {c: np.full((n, curves), np.nan) for c in kern.CURVES} if curves else {}
    kernel_ok = kern.unsupported(p.cfg) is None and set(p.table) <= kern.KEYS
    if kernel_ok:
        reason = kern.reasons(p, code)
        ok = reason == 0
        sub = p.take(ok) if not np.all(ok) else p
        if sub.n and fast:
            with np.errstate(all="ignore"):
                values = kern.metrics(sub, fast, samples, threads)
            for m in fast:
                out[m][ok] = values[m]
        if curves and sub.n:
            with np.errstate(all="ignore"):
                _, cv = kern.curves(sub, curves)
            for c in kern.CURVES:
                curve_out[c][ok] = cv[c]
    else:
        reason = np.zeros(n, dtype=np.int16)
    if checks:  # the drive's checks, once per geometry; what they refuse is inadmissible
        sweep_checks.fill_drive_checks(p, checks, out, reason, code)
    # plausibility limits: from the metrics at hand (every design), or from the whole
    # summary of the scalar study (the designs that went through it)
    flags = limits.violation_codes(out, p.cfg, n, {k: v for k, v in p.table.items()
                                                   if k in limits.LIMITS})  # fmt: skip
    if slow or not kernel_ok:
        scalar_curves = curve_out if curves and not kernel_ok else None
        for i in np.flatnonzero(reason == 0):
            _fallback(p, int(i), slow, out, reason, code, scalar_curves, flags)
    if checks:
        sweep_checks.fill_limit_checks(p, checks, out)
    refused = reason != 0
    flags[refused] = 0
    for m in out:
        out[m][refused] = np.nan
    for c in curve_out:
        curve_out[c][refused] = np.nan
    result = {"metrics": out, "reason": reason, "violations": flags}
    if curves:
        period = np.asarray(kern.period(p), dtype=float)
        result["curves"] = curve_out
        result["angle"] = sample_grid(period[:, None] if period.ndim else period, curves)
    return result


def _fallback(p, i, names, out, reason, code, curve_out, flags=None) -> None:
    """One design through :func:`rotorkin.drives.evaluate` (the scalar study)."""

    try:
        res = drives.evaluate(p.config(i))
    except ParameterError as exc:
        reason[i] = code.get(exc.name, code["other"])
        for m in out:
            out[m][i] = np.nan
        if curve_out:
            for c in curve_out:
                curve_out[c][i] = np.nan
        return
    for m in names:
        value = res.summary.get(m, np.nan)
        out[m][i] = float(value) if isinstance(value, (int, float, np.number)) else np.nan
    if flags is not None:
        for key in filter(None, res.summary.get("limits_passed", "").split(", ")):
            flags[i] |= limits.BITS.get(key, 0)
    if curve_out:
        for c in curve_out:
            curve_out[c][i] = res.columns[c]


def compute_chunk(spec: SweepSpec, start: int, stop: int, threads=None) -> dict:
    """Evaluate the designs ``start <= i < stop`` of a sweep (a dask task, a committed file).

    Returns
    -------
    dict
        ``"start"``, ``"stop"``, ``"design"`` (int64 indices), ``"reason"``,
        ``"metrics"`` and, with curves, ``"curves"`` and ``"angle"``.
    """
    p = spec.designs(start, stop)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SweepFallbackWarning)
        res = evaluate_designs(p, spec.metrics, spec.samples, threads,
                               spec.points if spec.keep_curves else 0)  # fmt: skip
    res["start"], res["stop"] = start, stop
    res["design"] = np.arange(start, stop, dtype=np.int64)
    return res


# --------------------------------------------------------------------------------------------
# the result
# --------------------------------------------------------------------------------------------
def to_result(spec: SweepSpec, flat: dict) -> SweepResult:
    """Shape flat results (every design in order) into a :class:`SweepResult` (views, no copy).

    Parameters
    ----------
    spec : SweepSpec
    flat : dict
        ``"metrics"`` name -> (size,), ``"reason"`` (size,), and with curves
        ``"curves"`` name -> (size, points) and ``"angle"`` (points,) or (size, points).

    Returns
    -------
    SweepResult
        The variables, coordinates and attributes of the sweep's Dataset
        (:func:`to_dataset`).
    """
    kern = kernel_of(spec.drive_type, spec.base_cfg)
    dims = tuple(v.key for v in spec.varies)
    shape = spec.shape
    coords = {}
    for v in spec.varies:
        coords[v.key] = Variable(v.key, v.display_values(), {
            "units": v.field.unit or "1", "long_name": f"config key {v.key}",
            "spec": v.text})  # fmt: skip
    data = {}
    for m in spec.metrics:
        attrs = {"units": metric_units(m)}
        if sweep_checks.is_check(m):
            attrs["long_name"] = ("margin of a design check of rotorkin run: positive where the "
                                  "design passes, negative where it fails")  # fmt: skip
        data[m] = Variable(dims, flat["metrics"][m].reshape(shape), attrs)
    reasons = reason_keys(spec.drive_type)
    reason = np.asarray(flat["reason"]).astype(np.int16, copy=False)
    data["reason"] = Variable(dims, reason.reshape(shape), {
        "long_name": "why a design is inadmissible: 0 ok, else the config key whose admissible "
                     "range it violates (flag_meanings); its metrics are NaN",
        "flag_values": np.arange(len(reasons), dtype=np.int16),
        "flag_meanings": " ".join(reasons)})  # fmt: skip
    violations = flat.get("violations")
    if violations is None:
        violations = np.zeros(spec.size, dtype=np.int16)
    violations = np.asarray(violations).astype(np.int16, copy=False)
    data["violations"] = Variable(dims, violations.reshape(shape), {
        "long_name": "plausibility limits the design passes: a bit mask, 0 none (flag_masks, "
                     "flag_meanings: the config keys of the limits)",
        "flag_masks": np.array(list(limits.BITS.values()), dtype=np.int16),
        "flag_meanings": " ".join(limits.BITS),
        "comment": "checked on the swept metrics that measure a limit (peak_pressure_bar, "
                   "pressure_max_bar, *pressure_angle*max_deg, *contact_stress*_MPa, "
                   "*temperature*_K); a design evaluated by the scalar study is checked on its "
                   "whole summary and motion"})  # fmt: skip
    if spec.keep_curves:
        angle_name, angle_doc = kern.ANGLE
        angle = np.degrees(np.asarray(flat["angle"], dtype=float))
        if angle.ndim > 1:
            angle_dims, angle = (*dims, "point"), angle.reshape(*shape, -1)
        else:
            angle_dims = ("point",)
        coords[angle_name] = Variable(angle_dims, angle, {"units": "deg", "long_name": angle_doc})
        for c, values in flat["curves"].items():
            data[c] = Variable((*dims, "point"), values.reshape(*shape, -1),
                               {"units": metric_units(c)})  # fmt: skip
    inadmissible = int(np.count_nonzero(reason))
    attrs = {
        "title": f"rotorkin sweep of {spec.name}",
        "drive_type": spec.drive_type,
        "rotorkin_version": __version__,
        "designs": spec.size,
        "inadmissible_designs": inadmissible,
        "implausible_designs": int(np.count_nonzero(violations)),
        "samples_per_period": spec.samples,
        "design_checks": sweep_checks.note(spec.base_cfg, spec.varies, spec.metrics),
        "spec": json.dumps(spec.manifest(), sort_keys=True),
        "conventions": "coordinates in the units of their 'units' attribute; metrics are the "
                       "summary keys of rotorkin run (unit = suffix); integers and booleans "
                       "stored as float64 (1 = true); NaN where reason != 0",
    }  # fmt: skip
    return SweepResult(data, coords, attrs)


def to_dataset(spec: SweepSpec, flat: dict):
    """Shape flat results into an :class:`xarray.Dataset` (:func:`to_result`; the ``xarray``
    extra)."""
    return to_result(spec, flat).to_dataset()


#: Designs per block of the admissibility scan of :func:`check_spec_values`.
_CHECK_BLOCK = 1 << 18
#: Combinations of the other swept keys tried per value when the scalar study checks it.
_CHECK_SCALAR_TRIES = 64


def designs_at(spec: SweepSpec, index) -> Designs:
    """The designs at the flat grid indices ``index`` (any order)."""
    index = np.asarray(index, dtype=np.int64)
    idx = np.unravel_index(index, spec.shape) if spec.varies else ()
    table = {v.key: v.array()[i] for v, i in zip(spec.varies, idx, strict=True)}
    return Designs(spec.base_cfg, table, index.size, spec.extra)


def _slice_indices(shape: tuple, axis: int, j: int, start: int, stop: int) -> np.ndarray:
    """Flat indices ``start:stop`` (C order) of the sub-grid where dimension ``axis`` is ``j``."""
    sub = shape[:axis] + shape[axis + 1 :]
    rest = np.unravel_index(np.arange(start, stop, dtype=np.int64), sub) if sub else ()
    full_idx = (*rest[:axis], np.full(stop - start, j, dtype=np.int64), *rest[axis:])
    return np.ravel_multi_index(full_idx, shape)


def check_spec_values(spec: SweepSpec) -> None:
    """Refuse a swept value that crosses its key's own admissible limit (one line).

    A swept value is refused when every design of the grid that holds it is
    inadmissible *because of that key* (the key the scalar study would name):
    e.g. a plate tilt beyond the eq. 20 limit at every swept roller-axis angle,
    or a compression ratio below the zero-width-piston ratio at every swept plate
    tilt. A value inadmissible only in combination with other values (the other
    swept keys or the base config), e.g. a plate tilt at which the base
    compression ratio needs a negative piston width, is not refused: those
    designs come out NaN with the violated key in ``reason``.

    Kernel-evaluated sweeps are checked over the whole grid (vectorized, in
    blocks, a spread sample first so that the usual grid needs one block); other
    keys through the scalar study, at up to :data:`_CHECK_SCALAR_TRIES`
    combinations of the other swept keys per value. Finally one admissible design
    goes through the scalar study, to check the keys the kernels do not read.

    Raises
    ------
    RotorkinError
        One line naming the ``--vary`` item, the value and the study's message.
    """
    cfg = check_grid_values(spec)
    if cfg is not None:
        check_study(cfg)


def check_grid_values(spec: SweepSpec) -> dict | None:
    """:func:`check_spec_values` but its last check: the config of the design left for it.

    The design to run through the scalar study (:func:`check_study`), or None when the
    checks made already ran every design they tried through it.
    """
    if not spec.varies:
        return None
    kern = kernel_of(spec.drive_type, spec.base_cfg)
    code = {k: i for i, k in enumerate(reason_keys(spec.drive_type))}
    keys = [v.key for v in spec.varies]
    if kern.unsupported(spec.base_cfg) is None and set(keys) <= kern.KEYS:
        admissible = _check_grid(spec, kern, code)
        if admissible is None:
            admissible = _first_admissible(spec, kern, code)
        if admissible is None:
            _refuse_all(spec)
    else:
        if _check_scalar(spec) is False:
            _refuse_all(spec)
        admissible = None
    return None if admissible is None else designs_at(spec, [admissible]).config(0)


def check_study(cfg: dict) -> None:
    """One admissible design of a sweep through the scalar study: the keys no kernel reads.

    Raises
    ------
    RotorkinError
        One line: the base config is not admissible, and the study's message.
    """
    try:
        with warnings.catch_warnings():  # the study's own warnings are not the sweep's
            warnings.simplefilter("ignore")
            drives.evaluate(cfg)
    except ParameterError as exc:
        raise RotorkinError(f"the base config is not admissible: {exc}") from None


def _refuse(spec: SweepSpec, axis: int, j: int, flat: int):
    """Raise the one-line error of value ``j`` of swept key ``axis`` (design ``flat``)."""

    v = spec.varies[axis]
    where = f"--vary {v.key}={shown(v.text)[1:-1]} at {display(v.field, v.values[j])}"
    try:
        drives.evaluate(designs_at(spec, [flat]).config(0))
    except ParameterError as exc:
        raise RotorkinError(f"{where} crosses an admissible limit: {exc}") from None
    raise RotorkinError(f"{where} crosses an admissible limit of {v.key}")


def _check_grid(spec: SweepSpec, kern, code: dict) -> int | None:
    """Kernel admissibility over the grid; refuse own-limit values; an admissible design or None."""
    shape, size = spec.shape, spec.size
    own = [code.get(v.key, -1) for v in spec.varies]
    # pending[k][j]: every design checked so far that holds value j of key k names key k
    pending = [np.ones(n, dtype=bool) for n in shape]
    admissible = None

    def scan(index):
        nonlocal admissible
        r = kern.reasons(designs_at(spec, index), code)
        ok = np.flatnonzero(r == 0)
        if admissible is None and ok.size:
            admissible = int(index[ok[0]])
        idx = np.unravel_index(index, shape)
        for k, i in enumerate(idx):
            cleared = np.unique(i[r != own[k]])
            pending[k][cleared] = False

    # 1. a spread sample: every value of every key with a few pseudo-random partners
    rng = np.random.default_rng(0)
    sample = [np.arange(min(size, _CHECK_BLOCK), dtype=np.int64)]
    for k, n in enumerate(shape):
        reps = 4
        multi = [rng.integers(0, m, size=n * reps) for m in shape]
        multi[k] = np.repeat(np.arange(n), reps)
        sample.append(np.ravel_multi_index(multi, shape))
    scan(np.unique(np.concatenate(sample)))
    # 2. the values still suspect: their whole slice of the grid, block by block
    for k, n in enumerate(shape):
        per = size // n
        for j in np.flatnonzero(pending[k]):
            for lo in range(0, per, _CHECK_BLOCK):
                scan(_slice_indices(shape, k, int(j), lo, min(lo + _CHECK_BLOCK, per)))
                if not pending[k][j]:
                    break
            else:
                _refuse(spec, k, int(j), int(_slice_indices(shape, k, int(j), 0, 1)[0]))
    return admissible


def _first_admissible(spec: SweepSpec, kern, code: dict) -> int | None:
    """The first admissible design of the whole grid (block by block), or None."""
    for lo in range(0, spec.size, _CHECK_BLOCK):
        index = np.arange(lo, min(lo + _CHECK_BLOCK, spec.size), dtype=np.int64)
        ok = np.flatnonzero(kern.reasons(designs_at(spec, index), code) == 0)
        if ok.size:
            return int(index[ok[0]])
    return None


def _refuse_all(spec: SweepSpec):
    """No design of the grid is admissible: one line with the first design's reason."""
    try:
        drives.evaluate(designs_at(spec, [0]).config(0))
    except ParameterError as exc:
        raise RotorkinError(f"no design of the sweep is admissible: {exc}") from None
    raise RotorkinError("no design of the sweep is admissible")


def _check_scalar(spec: SweepSpec) -> bool | None:
    """The same rule through the scalar study (keys the kernel does not vary).

    The designs tried went through the whole study, so there is no separate base
    check afterwards. Returns False when every design of the grid was tried and
    none is admissible, True when one is, None when the tries did not cover the
    grid and found none.
    """
    found, tried = False, set()

    shape = spec.shape
    for k, v in enumerate(spec.varies):
        per = spec.size // len(v)
        for j in range(len(v)):
            tries = min(per, _CHECK_SCALAR_TRIES)
            flats = _slice_indices(shape, k, j, 0, tries)
            own_only = True
            for flat in flats:
                tried.add(int(flat))
                try:
                    drives.evaluate(designs_at(spec, [flat]).config(0))
                    found = True
                except ParameterError as exc:
                    if exc.name == v.key:
                        continue
                own_only = False
                break
            if own_only and tries == per:
                _refuse(spec, k, j, int(flats[0]))
    if found:
        return True
    return False if len(tried) == spec.size else None
