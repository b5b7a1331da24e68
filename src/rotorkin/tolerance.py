"""Tolerance analysis: Monte-Carlo over manufacturing tolerances of config keys, seeded.

``--tol drive.plate_tilt=0.1deg`` draws the plate tilt uniformly in
``nominal +- 0.1 deg``; ``--tol drive.plate_tilt=0.1deg:normal`` draws it from a
normal distribution of standard deviation 0.1 deg (``:uniform`` is the default
and may be written). Every sample is a design evaluated by the drive's sweep
kernel (broadcast over the samples, no loop), and each metric's distribution
is summarised by its nominal value, mean, standard deviation (``ddof = 1``),
extremes and percentiles 1, 5, 50, 95, 99 (``numpy.percentile``, linear).

Sampling, exactly (so that a run can be reproduced elsewhere):
``rng = numpy.random.default_rng(seed)``; for each ``--tol`` in the order given,
``delta = rng.uniform(-w, w, size=N)`` or ``rng.normal(0.0, w, size=N)`` with the
width ``w`` in SI units (rad, m, ...); the sample is ``nominal + delta``.

The manufactured parts keep their nominal size: a tolerance perturbs the
drive, not the design rules that size the parts from it: each drive says which
parts it holds (``DriveSpec.tolerance_hold``; e.g. a piston width sized for the
nominal compression ratio stays that width, and drive errors show as a spread of
the actual compression ratio). Samples that are not
admissible (e.g. pistons that would collide) get NaN and a reason, are counted
and left out of the statistics.
"""

from __future__ import annotations

import copy
import warnings
from dataclasses import dataclass

import numpy as np

from rotorkin.core.batch import DEFAULT_SAMPLES
from rotorkin.core.errors import ConfigError, ParameterError, RotorkinError, shown
from rotorkin.core.extras import xarray_module
from rotorkin.core.units import parse_quantity
from rotorkin.drives import evaluate, spec_of
from rotorkin.io.config import validate_config
from rotorkin.sweep import MAX_SAMPLES, MAX_WORK, Designs, evaluate_designs, resolve_metrics
from rotorkin.sweep.engine import (
    SweepFallbackWarning,
    coverage,
    metric_units,
    reason_keys,
    warn_fallback,
)
from rotorkin.sweep.result import SweepResult, Variable
from rotorkin.sweep.spec import DISPLAY_UNITS, Field, _check_key, parse_item

__all__ = ["Tolerance", "parse_tol", "draw", "run_tolerance", "tolerance_result", "summarize",
           "PERCENTILES"]  # fmt: skip

#: Percentiles reported for every metric.
PERCENTILES = (1, 5, 50, 95, 99)
_CHUNK = 65_536
_DISTRIBUTIONS = ("uniform", "normal")

#: Most Monte-Carlo samples of one analysis.
MAX_TOLERANCE_SAMPLES = 10_000_000


@dataclass(frozen=True)
class Tolerance:
    """One toleranced key: ``width`` is the half-width (uniform) or sigma (normal), SI."""

    key: str
    text: str
    distribution: str
    width: float
    field: Field

    def describe(self) -> str:
        """``'drive.plate_tilt +- 0.1 deg (uniform)'`` or ``'... sigma 0.1 deg (normal)'``."""
        unit, factor = DISPLAY_UNITS.get(self.field.kind, ("", 1.0))
        amount = f"{self.width * factor:.6g}{(' ' + unit) if unit else ''}"
        if self.distribution == "uniform":
            return f"{self.key} +- {amount} (uniform)"
        return f"{self.key} sigma {amount} (normal)"


def parse_tol(item: str, base_raw: dict) -> Tolerance:
    """Parse ``KEY=WIDTH[:uniform|:normal]`` (WIDTH with its unit for a dimensional key)."""
    key, spec = parse_item(item, "--tol")
    option = f"--tol {key}={shown(spec)[1:-1]}"
    _, field = _check_key(base_raw, key, "--tol")
    if field.kind in ("choice", "int"):
        raise ConfigError(f"{option} is not admissible: {key} is not a continuous quantity")
    text, _, dist = spec.partition(":")
    dist = dist.strip() or "uniform"
    if dist not in _DISTRIBUTIONS:
        raise ConfigError(f"{option} is not admissible: the distribution is uniform (default) "
                          "or normal, e.g. 0.1deg:normal")  # fmt: skip
    text = text.strip()
    if not text:
        raise ConfigError(f"{option} is not admissible: give the width, e.g. {key}=0.1deg")
    if field.dimensional:
        if field.kind == "temperature" and any(u in text for u in ("degC", "degF", "°")):
            raise ConfigError(f"{option} is not admissible: give a temperature difference in K")
        width, reason = parse_quantity(text, field.kind)
        if reason:
            raise ConfigError(f"{option}: {key} = {shown(text)} {reason}")
    else:
        try:
            width = float(text)
        except ValueError:
            raise ConfigError(f"{option} is not admissible: the width {shown(text)} must be a "
                              "number") from None  # fmt: skip
    if not (np.isfinite(width) and width > 0.0):
        raise ConfigError(f"{option} is not admissible: the width must be > 0")
    return Tolerance(key, spec, dist, float(width), field)


def draw(tols, samples: int, seed: int) -> dict:
    """The deltas of every key [SI], in the documented order: key -> (samples,)."""
    rng = np.random.default_rng(seed)
    out = {}
    for t in tols:
        if t.distribution == "uniform":
            out[t.key] = rng.uniform(-t.width, t.width, size=samples)
        else:
            out[t.key] = rng.normal(0.0, t.width, size=samples)
    return out


def _held(cfg: dict) -> tuple[dict, dict]:
    """The config and extras that keep the manufactured parts at their nominal size."""

    hold = spec_of(cfg).tolerance_hold
    return hold(copy.deepcopy(cfg)) if hold else (copy.deepcopy(cfg), {})


def run_tolerance(base_cfg_raw: dict, tols, *, samples: int = 10_000, seed: int = 0,
                  metrics=None, angles=None, threads=None):  # fmt: skip
    """Monte-Carlo tolerance analysis; returns an :class:`xarray.Dataset` over ``sample``.

    :func:`tolerance_result` as a Dataset (the ``xarray`` extra; without it a
    ``ModuleNotFoundError`` naming ``pip install "rotorkin[xarray]"`` before any work).
    """
    what = "rotorkin.tolerance.run_tolerance"
    xarray_module(what)
    return tolerance_result(base_cfg_raw, tols, samples=samples, seed=seed, metrics=metrics,
                            angles=angles, threads=threads).to_dataset(what)  # fmt: skip


def tolerance_result(base_cfg_raw: dict, tols, *, samples: int = 10_000, seed: int = 0,
                     metrics=None, angles=None, threads=None) -> SweepResult:  # fmt: skip
    """Monte-Carlo tolerance analysis; a :class:`~rotorkin.sweep.result.SweepResult` over
    ``sample`` (numpy arrays, no xarray needed).

    Parameters
    ----------
    base_cfg_raw : dict
        The nominal design, as written (units in strings).
    tols : sequence of str or Tolerance
        ``"KEY=WIDTH[:uniform|:normal]"`` items.
    samples : int
        Monte-Carlo samples N.
    seed : int
        Seed of ``numpy.random.default_rng``.
    metrics : None, "all" or list of str
        As :func:`rotorkin.sweep.resolve_metrics`.
    angles : int, optional
        Shaft angles per period of the sampled peaks (default 20001).

    Returns
    -------
    SweepResult
        Per sample: the toleranced keys (display units), every metric, ``reason``;
        attributes ``nominal:<metric>``, ``seed``, ``tolerances``.
    """
    cfg = validate_config(base_cfg_raw)
    tols = [t if isinstance(t, Tolerance) else parse_tol(t, base_cfg_raw) for t in tols]
    if not tols:
        raise ConfigError("give at least one --tol KEY=WIDTH, e.g. --tol drive.plate_tilt=0.1deg")
    keys = [t.key for t in tols]
    dup = next((k for k in keys if keys.count(k) > 1), None)
    if dup:
        raise ConfigError(f"--tol {shown(dup)[1:-1]} is not admissible: the key is given twice")
    if not 2 <= int(samples) <= MAX_TOLERANCE_SAMPLES:
        raise ParameterError("samples", samples, f"2 <= samples <= {MAX_TOLERANCE_SAMPLES}")
    if not 0 <= int(seed) < 2**63:
        raise ParameterError("seed", seed, "0 <= seed < 2**63")
    if angles is not None and not 3 <= int(angles) <= MAX_SAMPLES:
        raise ParameterError("angles", angles, f"3 <= angles <= {MAX_SAMPLES}")
    if int(samples) * (DEFAULT_SAMPLES if angles is None else int(angles)) > MAX_WORK:
        raise ParameterError("samples", samples, f"samples x angles <= {MAX_WORK:.0e}")
    names = resolve_metrics(cfg, metrics)
    angles = DEFAULT_SAMPLES if angles is None else int(angles)
    try:
        evaluate(cfg)
    except ParameterError as exc:
        raise RotorkinError(f"the nominal design is not admissible: {exc}") from None
    held, extra = _held(cfg)
    nominal_run = evaluate_designs(Designs(held, {}, 1, extra), names, angles, threads)
    deltas = draw(tols, int(samples), int(seed))
    table = {}
    for t in tols:
        section, _, name = t.key.partition(".")
        table[t.key] = held[section][name] + deltas[t.key]
    _, _, why = coverage(cfg["drive"]["type"], held, keys, names)
    warn_fallback(why, int(samples))
    n = int(samples)
    values = {m: np.empty(n) for m in names}
    reason = np.empty(n, dtype=np.int16)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SweepFallbackWarning)
        for lo in range(0, n, _CHUNK):
            hi = min(lo + _CHUNK, n)
            p = Designs(held, {k: v[lo:hi] for k, v in table.items()}, hi - lo, extra)
            res = evaluate_designs(p, names, angles, threads)
            reason[lo:hi] = res["reason"]
            for m in names:
                values[m][lo:hi] = res["metrics"][m]
    if np.all(reason != 0):
        codes = reason_keys(cfg["drive"]["type"])
        worst = codes[int(np.bincount(reason).argmax())]
        raise RotorkinError(
            f"every one of the {n} samples is inadmissible (most often by {worst}): the "
            "tolerances reach past an admissible limit from the nominal design; narrow them"
        )
    data = {}
    for t in tols:
        unit, factor = DISPLAY_UNITS.get(t.field.kind, ("1", 1.0))
        data[t.key] = Variable("sample", table[t.key] * factor,
                               {"units": unit, "tolerance": t.describe()})  # fmt: skip
    for m in names:
        data[m] = Variable("sample", values[m], {
            "units": metric_units(m), "nominal": float(nominal_run["metrics"][m][0])})  # fmt: skip
    codes = reason_keys(cfg["drive"]["type"])
    data["reason"] = Variable(
        "sample",
        reason,
        {
            "flag_values": np.arange(len(codes), dtype=np.int16),
            "flag_meanings": " ".join(codes),
            "long_name": "0 admissible, else the config key whose limit the sample violates",
        },
    )
    held_note = ("piston width held at nominal" if "piston_width" in extra
                 else "vane angle held at nominal gamma_0" if held != cfg else "")  # fmt: skip
    return SweepResult(data, {"sample": Variable("sample", np.arange(n, dtype=np.int32))}, {
        "drive_type": cfg["drive"]["type"],
        "seed": int(seed),
        "samples": n,
        "angles_per_period": angles,
        "tolerances": "; ".join(t.describe() for t in tols),
        "held_at_nominal": held_note,
        "sampling": "rng = numpy.random.default_rng(seed); per --tol in order: "
                    "rng.uniform(-w, w, N) or rng.normal(0, w, N), w in SI units",
    })  # fmt: skip


def summarize(ds) -> dict:
    """Statistics of every metric of a tolerance Dataset over its admissible samples.

    Returns
    -------
    dict
        metric -> ``{"nominal", "mean", "std", "min", "max", "p1", "p5", "p50", "p95",
        "p99", "admissible", "inadmissible"}`` (None where there is no admissible sample).
    """
    ok = ds["reason"].values == 0
    out = {}
    for m, var in ds.data_vars.items():
        if "nominal" not in var.attrs:
            continue
        v = var.values[ok]
        v = v[np.isfinite(v)]
        row = {"nominal": float(var.attrs["nominal"])}
        if v.size:
            row.update(mean=float(np.mean(v)), std=float(np.std(v, ddof=1)) if v.size > 1
                       else 0.0, min=float(np.min(v)), max=float(np.max(v)))  # fmt: skip
            for q, value in zip(PERCENTILES, np.percentile(v, PERCENTILES), strict=True):
                row[f"p{q}"] = float(value)
        else:
            row.update({k: None for k in ("mean", "std", "min", "max")})
            row.update({f"p{q}": None for q in PERCENTILES})
        row["admissible"] = int(v.size)
        row["inadmissible"] = int(np.count_nonzero(~ok))
        out[m] = row
    return out
