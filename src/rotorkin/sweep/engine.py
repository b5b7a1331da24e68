"""Evaluating batches of designs: the kernels, the scalar fallback, chunks, the result Dataset.

A sweep is a grid of designs (the outer product of the swept values, flattened
in C order: the last ``--vary`` key varies fastest). It is cut into chunks of
consecutive designs; :func:`compute_chunk` evaluates one chunk (the unit of
work of the local loop, of a dask task and of a committed file), and
:func:`to_dataset` shapes the flat results into an :class:`xarray.Dataset`.
"""

from __future__ import annotations

import importlib
import json
import warnings
from dataclasses import dataclass, field

import numpy as np

from rotorkin.errors import ParameterError, RotorkinError
from rotorkin.sweep._common import DEFAULT_SAMPLES, Designs, reason_keys, sample_grid

__all__ = [
    "KERNELS",
    "SweepSpec",
    "SweepFallbackWarning",
    "kernel_of",
    "evaluate_designs",
    "compute_chunk",
    "chunk_bounds",
    "to_dataset",
    "metric_units",
]

#: drive.type -> kernel module under rotorkin.sweep
KERNELS = {
    "wobble_cam": "kernels_wobble",
    "eccentric_cam": "kernels_eccentric",
    "guide_bar": "kernels_guide_bar",
    "rhomboid_cam": "kernels_rhomboid",
}


class SweepFallbackWarning(UserWarning):
    """Some metrics or keys are not vectorized: evaluated design by design by the scalar study."""


def kernel_of(drive_type: str):
    """The kernel module of a drive type."""
    return importlib.import_module(f"rotorkin.sweep.{KERNELS[drive_type]}")


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
        from rotorkin import __version__

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
    kern = kernel_of(drive_type)
    why = kern.unsupported(cfg)
    if why is None:
        outside = sorted(set(keys) - kern.KEYS)
        if outside:
            why = f"the kernel does not vary {', '.join(outside)}"
    if why is not None:
        return [], list(metrics), why
    names = set(kern.metric_names(cfg))
    fast = [m for m in metrics if m in names]
    slow = [m for m in metrics if m not in names]
    return fast, slow, (f"{len(slow)} metric(s) are not vectorized ({', '.join(slow[:4])}"
                        f"{', ...' if len(slow) > 4 else ''})" if slow else None)  # fmt: skip


def warn_fallback(why: str | None, designs: int) -> None:
    """Warn once per sweep that the scalar study runs design by design."""
    if why:
        warnings.warn(
            f"{why}: those are evaluated design by design with rotorkin.studies.evaluate "
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
        Summary keys wanted.
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
        (n,) int16 codes into :func:`rotorkin.sweep._common.reason_keys`;
        with ``curves``: ``"curves"`` name -> (n, curves) and ``"angle"`` [rad].
    """
    drive_type = p.cfg["drive"]["type"]
    kern = kernel_of(drive_type)
    keys = reason_keys(drive_type)
    code = {k: i for i, k in enumerate(keys)}
    fast, slow, why = coverage(drive_type, p.cfg, p.table, metrics)
    n = p.n
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
    if slow or not kernel_ok:
        scalar_curves = curve_out if curves and not kernel_ok else None
        for i in np.flatnonzero(reason == 0):
            _fallback(p, int(i), slow, out, reason, code, scalar_curves)
    result = {"metrics": out, "reason": reason}
    if curves:
        period = np.asarray(kern.period(p), dtype=float)
        result["curves"] = curve_out
        result["angle"] = sample_grid(period[:, None] if period.ndim else period, curves)
    return result


def _fallback(p, i, names, out, reason, code, curve_out) -> None:
    """One design through :func:`rotorkin.studies.evaluate` (the scalar study)."""
    from rotorkin.studies import evaluate

    try:
        res = evaluate(p.config(i))
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
_UNITS = (
    ("_mm_per_rad3", "mm/rad^3"), ("_mm_per_rad2", "mm/rad^2"), ("_mm_per_rad", "mm/rad"),
    ("_per_rad2", "1/rad^2"), ("_per_rad", "1/rad"), ("_per_m", "1/m"), ("_deg", "deg"),
    ("_mm", "mm"), ("_cm3_per_rev", "cm^3/rev"), ("_cm3_per_rad", "cm^3/rad"), ("_cm3", "cm^3"),
    ("_cm2", "cm^2"), ("_Nm", "N*m"), ("_J_per_rev", "J/rev"), ("_J", "J"), ("_bar", "bar"),
    ("_kW", "kW"), ("_W", "W"), ("_l_per_min", "l/min"), ("_percent", "%"), ("_rad", "rad"),
    ("_kgm2", "kg*m^2"), ("_K", "K"),
)  # fmt: skip


def metric_units(name: str) -> str:
    """Unit of a summary key from its suffix ("1" when dimensionless)."""
    return next((u for suffix, u in _UNITS if name.endswith(suffix)), "1")


def to_dataset(spec: SweepSpec, flat: dict):
    """Shape flat results (every design in order) into an :class:`xarray.Dataset`.

    Parameters
    ----------
    spec : SweepSpec
    flat : dict
        ``"metrics"`` name -> (size,), ``"reason"`` (size,), and with curves
        ``"curves"`` name -> (size, points) and ``"angle"`` (points,) or (size, points).
    """
    import xarray as xr

    from rotorkin import __version__

    kern = kernel_of(spec.drive_type)
    dims = tuple(v.key for v in spec.varies)
    shape = spec.shape
    coords = {}
    for v in spec.varies:
        coords[v.key] = xr.Variable(v.key, v.display_values(), attrs={
            "units": v.field.unit or "1", "long_name": f"config key {v.key}",
            "spec": v.text})  # fmt: skip
    data = {}
    for m in spec.metrics:
        data[m] = xr.Variable(dims, flat["metrics"][m].reshape(shape),
                              attrs={"units": metric_units(m)})  # fmt: skip
    reasons = reason_keys(spec.drive_type)
    data["reason"] = xr.Variable(dims, flat["reason"].reshape(shape).astype(np.int16), attrs={
        "long_name": "why a design is inadmissible: 0 ok, else the config key whose admissible "
                     "range it violates (flag_meanings); its metrics are NaN",
        "flag_values": np.arange(len(reasons), dtype=np.int16),
        "flag_meanings": " ".join(reasons)})  # fmt: skip
    if spec.keep_curves:
        angle_name, angle_doc = kern.ANGLE
        angle = np.degrees(np.asarray(flat["angle"], dtype=float))
        if angle.ndim == 1:
            coords[angle_name] = xr.Variable(
                "point", angle, attrs={"units": "deg", "long_name": angle_doc}
            )
        else:
            coords[angle_name] = xr.Variable(
                (*dims, "point"),
                angle.reshape(*shape, -1),
                attrs={"units": "deg", "long_name": angle_doc},
            )
        for c, values in flat["curves"].items():
            data[c] = xr.Variable((*dims, "point"), values.reshape(*shape, -1),
                                  attrs={"units": metric_units(c)})  # fmt: skip
    inadmissible = int(np.count_nonzero(flat["reason"]))
    attrs = {
        "title": f"rotorkin sweep of {spec.name}",
        "drive_type": spec.drive_type,
        "rotorkin_version": __version__,
        "designs": spec.size,
        "inadmissible_designs": inadmissible,
        "samples_per_period": spec.samples,
        "spec": json.dumps(spec.manifest(), sort_keys=True),
        "conventions": "coordinates in the units of their 'units' attribute; metrics are the "
                       "summary keys of rotorkin run (unit = suffix); integers and booleans "
                       "stored as float64 (1 = true); NaN where reason != 0",
    }  # fmt: skip
    return xr.Dataset(data, coords=coords, attrs=attrs)


def check_spec_values(spec: SweepSpec) -> None:
    """Refuse a swept value that is inadmissible on its own (the other keys at their base).

    A range "crossing an admissible limit" is refused here with one line; designs
    inadmissible only in combination with other swept values become NaN with a
    reason instead. Each swept value is checked by the kernel's admissibility
    rules, then one design is run through the scalar study to check the base.
    """
    from rotorkin.studies import evaluate
    from rotorkin.sweep.spec import display

    drive_type = spec.drive_type
    kern = kernel_of(drive_type)
    code = {k: i for i, k in enumerate(reason_keys(drive_type))}
    kernel_ok = kern.unsupported(spec.base_cfg) is None
    for v in spec.varies:
        p = Designs(spec.base_cfg, {v.key: v.array()}, len(v), spec.extra)
        if kernel_ok and v.key in kern.KEYS:
            bad = np.flatnonzero(kern.reasons(p, code))
        else:
            bad = []
            for i in range(p.n):
                try:
                    evaluate(p.config(i))
                except ParameterError:
                    bad.append(i)
                    break
        if len(bad):
            i = int(bad[0])
            where = f"--vary {v.key}={v.text} at {display(v.field, v.values[i])}"
            try:
                evaluate(p.config(i))
            except ParameterError as exc:
                raise RotorkinError(f"{where} crosses an admissible limit: {exc}") from None
            raise RotorkinError(f"{where} crosses an admissible limit of {v.key}")
    # one design through the scalar study: the keys the kernels do not check (inertias ...)
    first = {spec.varies[0].key: spec.varies[0].array()[:1]} if spec.varies else {}
    try:
        evaluate(Designs(spec.base_cfg, first, 1).config(0))
    except ParameterError as exc:
        raise RotorkinError(f"the base config is not admissible: {exc}") from None
