"""A multi-objective search's problem: keys and ranges, objectives, constraints, evaluation.

``--vary KEY=LO:HI`` (values with units, inside the key's schema bounds),
``--objective max:METRIC`` / ``min:METRIC`` and ``--constraint METRIC<=VALUE`` /
``METRIC>=VALUE`` are parsed and checked here, each bad item refused in one line;
:func:`evaluate_population` evaluates a population (a list of designs, not a grid)
in one call of :func:`rotorkin.sweep.evaluate_designs`, and
:func:`objectives_and_constraints` turns the metrics into NSGA-II's ``F`` and ``G``.
"""

from __future__ import annotations

import hashlib
import json
import math
import warnings
from dataclasses import dataclass

import numpy as np

from rotorkin import __version__
from rotorkin.core.batch import DEFAULT_SAMPLES, Designs
from rotorkin.core.errors import ConfigError, ParameterError, shown
from rotorkin.design.keys import KeyInfo, check_metric, key_info, numeric_metrics, parse_key_value
from rotorkin.io.config import validate_config
from rotorkin.sweep.engine import evaluate_designs

__all__ = [
    "Variable",
    "Objective",
    "Constraint",
    "OptimizeSpec",
    "parse_variable",
    "parse_objective",
    "parse_constraint",
    "build_spec",
    "evaluate_population",
    "objectives_and_constraints",
    "MAX_POPULATION",
    "MAX_GENERATIONS",
]

#: Largest population and most generations of one search.
MAX_POPULATION, MAX_GENERATIONS = 100_000, 100_000


@dataclass(frozen=True)
class Variable:
    """A key searched over ``[low, high]`` [SI]."""

    info: KeyInfo
    low: float
    high: float

    @property
    def key(self) -> str:
        return self.info.key


@dataclass(frozen=True)
class Objective:
    """``sense`` (``"max"`` or ``"min"``) of a metric."""

    sense: str
    metric: str

    @property
    def text(self) -> str:
        return f"{self.sense}:{self.metric}"


@dataclass(frozen=True)
class Constraint:
    """``metric <= value`` or ``metric >= value`` (``op``), in the metric's unit."""

    metric: str
    op: str
    value: float

    @property
    def text(self) -> str:
        return f"{self.metric}{self.op}{self.value:.17g}"

    def g(self, values: np.ndarray) -> np.ndarray:
        """Normalised violation: <= 0 where satisfied; 1 where the metric is undefined."""
        scale = abs(self.value) if self.value != 0.0 else 1.0
        g = (values - self.value) / scale if self.op == "<=" else (self.value - values) / scale
        return np.where(np.isfinite(g), g, 1.0)


def parse_variable(text: str, raw: dict, cfg: dict) -> Variable:
    """``"KEY=LO:HI"`` (values with units, as in a config) -> :class:`Variable`."""
    key, eq, rng = str(text).partition("=")
    parts = rng.split(":")
    if not eq or len(parts) != 2 or not all(p.strip() for p in parts):
        raise ConfigError(f"--vary {shown(text)} is not admissible: write it as KEY=LO:HI with "
                          "units, e.g. machine.casing_radius=40mm:100mm")  # fmt: skip
    info = key_info(raw, cfg, key.strip(), "--vary")
    low, high = (parse_key_value(info, p, f"--vary {info.key}") for p in parts)
    if not low < high:
        raise ConfigError(f"--vary {shown(text)} is not admissible: LO < HI")
    return Variable(info, low, high)


def parse_objective(text: str) -> Objective:
    """``"max:METRIC"`` or ``"min:METRIC"`` -> :class:`Objective` (the metric unchecked)."""
    sense, colon, metric = str(text).partition(":")
    if not colon or sense.strip() not in ("max", "min") or not metric.strip():
        raise ConfigError(f"--objective {shown(text)} is not admissible: write it as max:METRIC "
                          "or min:METRIC, e.g. max:flow_mean_l_per_min")  # fmt: skip
    return Objective(sense.strip(), metric.strip())


def parse_constraint(text: str) -> Constraint:
    """``"METRIC<=VALUE"`` or ``"METRIC>=VALUE"`` -> :class:`Constraint` (the metric unchecked)."""
    text = str(text)
    for op in ("<=", ">="):
        metric, found, value = text.partition(op)
        if found:
            break
    else:
        metric = value = ""
    try:
        number = float(value)
    except ValueError:
        number = math.nan
    if not metric.strip() or not math.isfinite(number):
        raise ConfigError(f"--constraint {shown(text)} is not admissible: write it as "
                          "METRIC<=VALUE or METRIC>=VALUE, VALUE a finite number in the "
                          "metric's unit, e.g. input_torque_max_Nm<=40")  # fmt: skip
    return Constraint(metric.strip(), op, number)


@dataclass(frozen=True)
class OptimizeSpec:
    """A validated search: what defines its numbers (:meth:`manifest`).

    Attributes
    ----------
    name : str
    base_raw, base_cfg : dict
        The base config as written and validated (SI).
    variables : tuple of Variable
    objectives : tuple of Objective
    constraints : tuple of Constraint
    population, generations, seed, samples : int
    """

    name: str
    base_raw: dict
    base_cfg: dict
    variables: tuple
    objectives: tuple
    constraints: tuple
    population: int
    generations: int
    seed: int
    samples: int = DEFAULT_SAMPLES

    @property
    def metrics(self) -> tuple[str, ...]:
        """Metrics evaluated: the objectives', then the constraints' (each once)."""
        names = [o.metric for o in self.objectives] + [c.metric for c in self.constraints]
        return tuple(dict.fromkeys(names))

    def manifest(self) -> dict:
        """JSON-able; equal manifests give equal generations (their count aside)."""
        try:
            from pymoo import __version__ as pymoo_version
        except ImportError:
            pymoo_version = None
        return {
            "format": "rotorkin-optimize-1",
            "rotorkin_version": __version__,
            "pymoo_version": pymoo_version,
            "name": self.name,
            "base_raw": self.base_raw,
            "vary": [{"key": v.key, "low": v.low, "high": v.high} for v in self.variables],
            "objectives": [o.text for o in self.objectives],
            "constraints": [c.text for c in self.constraints],
            "population": self.population,
            "seed": self.seed,
            "samples": self.samples,
        }

    def key(self) -> str:
        """SHA-256 of the manifest (its first 16 hex digits name the state folder)."""
        text = json.dumps(self.manifest(), sort_keys=True, separators=(",", ":"))
        return hashlib.sha256(text.encode()).hexdigest()


def _count(value, name: str, low: int, high: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or \
            not low <= int(value) <= high:  # fmt: skip
        raise ParameterError(name, value, f"{low} <= {name} <= {high}")
    return int(value)


def build_spec(raw: dict, vary, objectives, constraints=(), *, population: int = 40,
               generations: int = 30, seed: int = 0, samples: int = DEFAULT_SAMPLES,
               name: str = "optimize") -> OptimizeSpec:  # fmt: skip
    """Validate a search; every bad item refused in one line before anything runs.

    Parameters
    ----------
    raw : dict
        The base config as written.
    vary : sequence of str or Variable
        ``"KEY=LO:HI"`` with units (``"machine.casing_radius=40mm:100mm"``).
    objectives : sequence of str or Objective
        ``"max:METRIC"``, ``"min:METRIC"``.
    constraints : sequence of str or Constraint
        ``"METRIC<=VALUE"``, ``"METRIC>=VALUE"`` (VALUE in the metric's unit).
    population, generations, seed : int
        NSGA-II's population size, number of generations and random seed.
    samples : int
        Shaft angles per period of the sampled peaks.
    """
    cfg = validate_config(raw)
    variables = tuple(v if isinstance(v, Variable) else parse_variable(v, raw, cfg)
                      for v in vary or ())  # fmt: skip
    if not variables:
        raise ConfigError("give at least one --vary KEY=LO:HI")
    keys = [v.key for v in variables]
    dup = next((k for k in keys if keys.count(k) > 1), None)
    if dup:
        raise ConfigError(f"--vary {dup} is not admissible: the key is given twice")
    objs = tuple(o if isinstance(o, Objective) else parse_objective(o) for o in objectives or ())
    cons = tuple(c if isinstance(c, Constraint) else parse_constraint(c)
                 for c in constraints or ())  # fmt: skip
    if not objs:
        raise ConfigError("give at least one --objective max:METRIC or min:METRIC")
    known = numeric_metrics(cfg)
    for o in objs:
        check_metric(o.metric, known, f"--objective {o.text}")
    for c in cons:
        check_metric(c.metric, known, f"--constraint {c.metric}{c.op}{c.value:g}")
    names = [o.metric for o in objs]
    dup = next((m for m in names if names.count(m) > 1), None)
    if dup:
        raise ConfigError(f"--objective {dup} is not admissible: the metric is given twice")
    return OptimizeSpec(name, raw, cfg, variables, objs, cons,
                        _count(population, "population", 2, MAX_POPULATION),
                        _count(generations, "generations", 1, MAX_GENERATIONS),
                        _count(seed, "seed", 0, 2**32 - 1),
                        _count(samples, "samples", 3, 1_000_001))  # fmt: skip


# --------------------------------------------------------------------------------------------
# evaluation and the stored generations
# --------------------------------------------------------------------------------------------
def evaluate_population(spec: OptimizeSpec, X: np.ndarray) -> dict:
    """The metrics of the designs ``X`` (n, keys) [SI] in one call of the sweep machinery.

    Returns
    -------
    dict
        ``"values"`` (n, metrics) float (NaN where refused or undefined), ``"reason"``
        (n,) int16 (0 admissible), ``"violations"`` (n,) int16 (plausibility limits).
    """
    X = np.asarray(X, dtype=float).reshape(-1, len(spec.variables))
    if X.shape[0] == 0:
        return {"values": np.zeros((0, len(spec.metrics))), "reason": np.zeros(0, np.int16),
                "violations": np.zeros(0, np.int16)}  # fmt: skip
    p = Designs(spec.base_cfg, {v.key: X[:, j] for j, v in enumerate(spec.variables)}, X.shape[0])
    with np.errstate(all="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = evaluate_designs(p, list(spec.metrics), spec.samples)
    values = np.column_stack([res["metrics"][m] for m in spec.metrics])
    return {"values": values, "reason": np.asarray(res["reason"], dtype=np.int16),
            "violations": np.asarray(res["violations"], dtype=np.int16)}  # fmt: skip


def objectives_and_constraints(spec: OptimizeSpec, values, reason) -> tuple:
    """NSGA-II's ``F`` (minimised) and ``G`` (<= 0 feasible) from the metrics.

    ``G[:, 0]`` is the admissibility constraint: +1 where the drive refuses the
    design or an objective is undefined, -1 else; ``G[:, 1 + k]`` constraint ``k``
    (0 for a refused design). ``F`` is 0 for those designs: never compared.
    """
    col = {m: i for i, m in enumerate(spec.metrics)}
    F = np.column_stack([values[:, col[o.metric]] * (-1.0 if o.sense == "max" else 1.0)
                         for o in spec.objectives])  # fmt: skip
    bad = (np.asarray(reason) != 0) | ~np.all(np.isfinite(F), axis=1)
    F[bad] = 0.0
    G = [np.where(bad, 1.0, -1.0)]
    G += [np.where(bad, 0.0, c.g(values[:, col[c.metric]])) for c in spec.constraints]
    return F, np.column_stack(G)
