"""Multi-objective search over config keys: NSGA-II (pymoo) on the sweep kernels.

>>> from rotorkin.io.config import load_config
>>> _, raw, _ = load_config()  # the default example
>>> spec = build_spec(raw, ["machine.axial_width=20mm:60mm", "drive.plate_tilt=30deg:50deg"],
...                   ["max:displacement_cm3_per_rev", "min:rotor_accel_peak_per_rad"],
...                   population=16, generations=5, seed=1)
>>> res = optimize(spec)
>>> res.size > 0
True

Each generation's designs (a population of ``KEY`` values drawn by NSGA-II) are
evaluated in **one** call of :func:`rotorkin.sweep.evaluate_designs` on a list of
designs (:class:`rotorkin.sweep.Designs`): the drive's sweep kernel where it has
one for the keys and metrics, the scalar study design by design otherwise.

Objectives are summary metrics to maximise or minimise; constraints bound
metrics (``METRIC<=VALUE``, ``METRIC>=VALUE``). A design the drive refuses
(sweep reason code != 0) or whose objective is undefined violates a constraint
of its own (``admissible``): NSGA-II ranks it by its violation, never by objective
values it does not have. Constraint ``k`` is ``g_k = (metric - VALUE) / |VALUE|``
(``VALUE - metric`` for ``>=``; divided by 1 when VALUE is 0), admissible
designs with ``g_k <= 0`` are feasible.

Resumption: with a ``store`` folder, every generation's designs and metrics are
committed to ``store/HASH/gen_NNNNNN.npz`` (written under a temporary name and
renamed) as they finish. A rerun of the same problem (same config, keys, ranges,
objectives, constraints, population, seed and samples: the ``HASH``; the number
of generations may grow) with ``resume=True`` replays the stored generations --
NSGA-II's own random generator, seeded, draws the same designs again, and their
stored metrics are taken instead of evaluated, checked design by design -- and
continues from the last finished one: its front equals that of an uninterrupted
run.
"""

from __future__ import annotations

import contextlib
import json
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from rotorkin import __version__
from rotorkin.core.errors import ConfigError, ParameterError, RotorkinError
from rotorkin.core.units import metric_units
from rotorkin.design.keys import with_values as _with_values
from rotorkin.design.problem import (
    OptimizeSpec,
    build_spec,
    evaluate_population,
    objectives_and_constraints,
)
from rotorkin.sweep.result import SweepResult, Variable
from rotorkin.sweep.store import open_folder

__all__ = [
    "OptimizeResult",
    "GenerationStore",
    "build_spec",
    "optimize",
    "write_front",
]


def _pymoo():
    """pymoo's NSGA-II and Problem, imported on first use; one line when it is missing."""
    try:
        from pymoo.algorithms.moo.nsga2 import NSGA2
        from pymoo.config import Config
        from pymoo.core.problem import Problem
    except ImportError:
        raise ConfigError("rotorkin optimize needs pymoo: pip install 'rotorkin[optimize]' "
                          "(or pip install 'pymoo>=0.6')") from None  # fmt: skip
    Config.warnings["not_compiled"] = False  # nothing on stdout
    return NSGA2, Problem


class GenerationStore:
    """The evaluated generations of one search in ``folder`` (one ``.npz`` file each).

    Parameters
    ----------
    root : Path
        ``OUT/.optimize``; the search's files go to ``root/HASH[:16]``.
    spec : OptimizeSpec
    """

    def __init__(self, root, spec: OptimizeSpec):
        self.folder = Path(root) / spec.key()[:16]
        self.manifest = {"hash": spec.key(), "spec": spec.manifest()}

    def open(self, resume: bool) -> dict:
        """Prepare the folder; the stored generations (all dropped unless ``resume``)."""
        open_folder(self.folder, self.folder.parent.parent)
        path = self.folder / "manifest.json"
        old = None
        with contextlib.suppress(OSError, ValueError):
            old = json.loads(path.read_text()).get("hash")
        if old != self.manifest["hash"] or not resume:
            for f in self.folder.glob("gen_*.npz"):
                f.unlink()
            self._write_text(path, json.dumps(self.manifest, indent=1))
        return self.read()

    def read(self) -> dict:
        """Generation index -> its record (``X``, ``values``, ``reason``, ``violations``)."""
        out = {}
        for f in sorted(self.folder.glob("gen_*.npz")):
            try:
                index = int(f.stem.split("_")[1])
                with np.load(f, allow_pickle=False) as data:
                    out[index] = {k: np.array(data[k]) for k in data.files}
            except (ValueError, OSError, KeyError):
                continue
        return out

    def commit(self, index: int, record: dict) -> None:
        """Write generation ``index`` atomically."""
        final = self.folder / f"gen_{index:06d}.npz"
        tmp = self.folder / f".gen_{index:06d}.npz.tmp-{os.getpid()}"
        with open(tmp, "wb") as fh:
            np.savez(fh, **record)
        os.replace(tmp, final)

    def drop_from(self, index: int) -> None:
        """Remove generations ``>= index`` (they no longer follow from the stored ones)."""
        for f in self.folder.glob("gen_*.npz"):
            with contextlib.suppress(ValueError):
                if int(f.stem.split("_")[1]) >= index:
                    f.unlink()

    def _write_text(self, path: Path, text: str) -> None:
        tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
        tmp.write_text(text)
        os.replace(tmp, path)


# --------------------------------------------------------------------------------------------
# the search
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class OptimizeResult:
    """The Pareto set of a search and every design it evaluated.

    Attributes
    ----------
    spec : OptimizeSpec
    X : ndarray, shape (m, keys)
        The Pareto designs' key values [SI], sorted by the first objective's metric.
    values : ndarray, shape (m, metrics)
        Their metrics (``spec.metrics``), in the metrics' units.
    violations : ndarray, shape (m,)
        Plausibility limits each passes (bit mask, :mod:`rotorkin.studies.limits`).
    history : tuple of dict
        Every generation's record (``X``, ``values``, ``reason``, ``violations``).
    replayed : int
        Generations taken from the store instead of evaluated.
    """

    spec: OptimizeSpec
    X: np.ndarray
    values: np.ndarray
    violations: np.ndarray
    history: tuple = field(repr=False)
    replayed: int = 0

    @property
    def size(self) -> int:
        """Designs on the front."""
        return int(self.X.shape[0])

    @property
    def evaluations(self) -> int:
        """Designs evaluated over all generations (replayed ones included)."""
        return int(sum(h["X"].shape[0] for h in self.history))

    def column(self, metric: str) -> np.ndarray:
        """One metric over the front."""
        return self.values[:, list(self.spec.metrics).index(metric)]

    def display(self, j: int) -> np.ndarray:
        """Key ``j`` over the front in the unit people read (mm, deg, ...)."""
        return self.X[:, j] * self.spec.variables[j].info.factor

    def config(self, index: int) -> tuple[dict, dict]:
        """The config of front design ``index`` as written, and validated (SI)."""
        if not 0 <= index < self.size:
            raise ParameterError("--report", index, f"0 <= index <= {self.size - 1} (the "
                                 f"front's designs, column 'index' of pareto.csv)")  # fmt: skip
        infos = [v.info for v in self.spec.variables]
        return _with_values(self.spec.base_raw, infos, self.X[index])

    def to_dataset(self):
        """The front as an :class:`xarray.Dataset` over dimension ``design`` (the ``xarray``
        extra; :meth:`to_result` holds the same variables as numpy arrays)."""
        return self.to_result().to_dataset("OptimizeResult.to_dataset")

    def to_result(self) -> SweepResult:
        """The front as a :class:`~rotorkin.sweep.result.SweepResult` over dimension ``design``."""
        spec = self.spec
        data = {}
        for j, v in enumerate(spec.variables):
            data[v.key] = Variable("design", self.display(j), {
                "units": v.info.unit or "1", "long_name": f"config key {v.key}",
                "searched": f"{v.info.show(v.low)} ... {v.info.show(v.high)}"})  # fmt: skip
        roles = {o.metric: f"objective: {o.sense}" for o in spec.objectives}
        for c in spec.constraints:
            roles[c.metric] = (roles.get(c.metric, "") + f"; constraint: {c.metric} {c.op} "
                               f"{c.value:.12g}").lstrip("; ")  # fmt: skip
        for i, m in enumerate(spec.metrics):
            data[m] = Variable("design", self.values[:, i],
                               {"units": metric_units(m), "role": roles[m]})  # fmt: skip
        data["violations"] = Variable("design", self.violations.astype(np.int16), {
            "long_name": "plausibility limits the design passes (bit mask; 0 none)"})  # fmt: skip
        attrs = {
            "title": f"rotorkin optimize of {spec.name}: Pareto set",
            "drive_type": spec.base_cfg["drive"]["type"],
            "rotorkin_version": __version__,
            "algorithm": "NSGA-II (pymoo)",
            "population": spec.population,
            "generations": len(self.history),
            "seed": spec.seed,
            "evaluations": self.evaluations,
            "objectives": " ".join(o.text for o in spec.objectives),
            "constraints": " ".join(c.text for c in spec.constraints),
            "spec": json.dumps(spec.manifest(), sort_keys=True),
        }
        return SweepResult(data, {"design": Variable("design", np.arange(self.size))}, attrs)

    def csv_text(self) -> str:
        """The front as CSV: index, the keys (unit in brackets), objectives, constraints."""
        spec = self.spec
        head = ["index"] + [f"{v.key} [{v.info.unit}]" if v.info.unit else v.key
                            for v in spec.variables] + list(spec.metrics)  # fmt: skip
        lines = [",".join(head)]
        for i in range(self.size):
            row = [str(i)] + [f"{self.display(j)[i]:.12g}" for j in range(len(spec.variables))]
            row += [f"{v:.12g}" for v in self.values[i]]
            lines.append(",".join(row))
        return "\n".join(lines) + "\n"


def optimize(spec: OptimizeSpec, *, store=None, resume: bool = False, on_generation=None,
             on_status=None) -> OptimizeResult:  # fmt: skip
    """Run NSGA-II on ``spec``; the Pareto set of its last population.

    Parameters
    ----------
    spec : OptimizeSpec
        From :func:`build_spec`.
    store : path, optional
        Folder of the generations (``OUT/.optimize``): each is committed as it
        finishes, so that an interrupted search can resume.
    resume : bool
        Continue from the generations in ``store`` (a search of the same spec), else
        start afresh.
    on_generation : callable, optional
        ``on_generation(index, evaluated)`` after each generation (``evaluated``: False
        when it was replayed from the store); may raise to stop the search.
    on_status : callable, optional
        ``on_status(message)`` for one-line notes (resumption).

    Raises
    ------
    RotorkinError
        No design of the last population is admissible and satisfies the constraints.
    """
    NSGA2, Problem = _pymoo()
    lo = np.array([v.low for v in spec.variables])
    hi = np.array([v.high for v in spec.variables])
    n_g = 1 + len(spec.constraints)

    class _Problem(Problem):
        def __init__(self):
            super().__init__(n_var=lo.size, n_obj=len(spec.objectives), n_ieq_constr=n_g,
                             xl=lo, xu=hi)  # fmt: skip

        def _evaluate(self, X, out, *args, **kwargs):
            # the generation's record, evaluated (or replayed) before: its rows for X
            rec = self.record
            rows = _rows(rec["X"], np.asarray(X, dtype=float))
            out["F"], out["G"] = objectives_and_constraints(spec, rec["values"][rows],
                                                            rec["reason"][rows])  # fmt: skip

    problem = _Problem()
    gens = GenerationStore(store, spec) if store is not None else None
    stored = gens.open(resume) if gens is not None else {}
    if on_status and resume:
        on_status(f"resuming: {len(stored)} generation(s) stored, replaying them" if stored else
                  "nothing stored to resume in this folder for these arguments: starting "
                  "afresh")  # fmt: skip
    history, replayed = [], 0
    algorithm = NSGA2(pop_size=spec.population)
    algorithm.setup(problem, termination=("n_gen", spec.generations), seed=spec.seed,
                    verbose=False)  # fmt: skip
    while algorithm.has_next():
        index = len(history)
        pop = algorithm.ask()
        X = np.asarray(pop.get("X"), dtype=float).reshape(-1, lo.size)
        old = stored.get(index)
        if old is not None and old["X"].shape == X.shape and np.array_equal(old["X"], X):
            record, fresh = old, False
            replayed += 1
        else:
            if old is not None and gens is not None:  # the stored run went another way
                gens.drop_from(index)
                stored = {}
                if on_status:
                    on_status(f"generation {index} differs from the stored one: evaluating "
                              "from there")  # fmt: skip
            record = {"X": X, **evaluate_population(spec, X)}
            fresh = True
            if gens is not None:
                gens.commit(index, record)
        problem.record = record
        algorithm.evaluator.eval(problem, pop)
        algorithm.tell(infills=pop)
        history.append(record)
        if on_generation is not None:
            on_generation(index, fresh)
    return _front(spec, algorithm.opt, history, replayed)


def _rows(table: np.ndarray, X: np.ndarray) -> np.ndarray:
    """Row of ``table`` holding each row of ``X`` (the last such)."""
    if table.shape == X.shape and np.array_equal(table, X):
        return np.arange(X.shape[0])
    table = np.ascontiguousarray(table, dtype=float)
    where = {row.tobytes(): i for i, row in enumerate(table)}  # later rows win
    return np.array([where[row.tobytes()] for row in np.ascontiguousarray(X, dtype=float)],
                    dtype=int)  # fmt: skip


def _front(spec: OptimizeSpec, opt, history, replayed) -> OptimizeResult:
    """The feasible non-dominated designs of the last population, sorted by objective 1."""
    X = np.asarray(opt.get("X"), dtype=float).reshape(-1, len(spec.variables))
    cv = np.asarray(opt.get("CV"), dtype=float).reshape(-1)
    X = X[cv <= 0.0]
    if X.shape[0] == 0:
        raise RotorkinError(
            "no design of the last generation is admissible and meets every --constraint: "
            "widen the --vary ranges, relax the constraints, or run more --generations"
        )
    # the designs' records, looked up from the generations (exact values, no re-evaluation)
    allx = np.concatenate([h["X"] for h in history])
    allv = np.concatenate([h["values"] for h in history])
    allf = np.concatenate([h["violations"] for h in history])
    idx = _rows(allx, X)
    values, flags = allv[idx], allf[idx]
    order = np.argsort(values[:, 0], kind="stable")
    return OptimizeResult(spec, X[order], values[order], flags[order], tuple(history), replayed)


def refused_share(result: OptimizeResult) -> float:
    """Share of the evaluated designs the drive refused."""
    reasons = np.concatenate([h["reason"] for h in result.history])
    return float(np.count_nonzero(reasons)) / max(reasons.size, 1)


def write_front(result: OptimizeResult, folder) -> list[str]:
    """Write ``pareto.nc``, ``pareto.csv``, ``pareto.png`` and ``README.txt`` into ``folder``.

    ``folder`` is a staging folder (:func:`rotorkin.io.output.staged_output`): the
    files are written as they are and moved into place by the caller. Returns their names.
    """
    from rotorkin.design.figures import plot_front
    from rotorkin.sweep.store import write_dataset

    folder = Path(folder)
    ds = result.to_result()
    write_dataset(ds, folder / "pareto.nc")
    (folder / "pareto.csv").write_text(result.csv_text())
    plot_front(result, folder / "pareto.png")
    names = ["pareto.nc", "pareto.csv", "pareto.png", "README.txt"]
    (folder / "README.txt").write_text(_readme(result, ds, names))
    return names


def _readme(result: OptimizeResult, ds, names) -> str:
    spec = result.spec
    lines = [
        ds.attrs["title"],
        "",
        f"NSGA-II (pymoo): population {spec.population}, {len(result.history)} generations, "
        f"seed {spec.seed}, {result.evaluations} designs evaluated "
        f"({100 * refused_share(result):.3g} % refused by the drive)",
        "objectives: " + ", ".join(o.text for o in spec.objectives),
        "constraints: " + (", ".join(c.text for c in spec.constraints) or "none"),
        "",
        "variables (pareto.nc, read with xarray.open_dataset(path); pareto.csv the same):",
    ]
    width = max(len(str(k)) for k in ds.data_vars)
    for name, var in ds.data_vars.items():
        lines.append(f"  {str(name).ljust(width)}  [{var.attrs.get('units', '1')}]  "
                     f"{var.attrs.get('role', var.attrs.get('long_name', ''))}")  # fmt: skip
    lines += ["", "files:"] + [f"  {n}" for n in names]
    lines += [
        "",
        "the state of the search (every generation's designs) is kept in .optimize/: "
        "the same command with --resume continues it; --report INDEX writes the "
        "outputs of rotorkin run for design INDEX (column 'index' of pareto.csv)",
    ]
    return "\n".join(lines) + "\n"
