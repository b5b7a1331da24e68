"""Design-space sweeps: config keys over ranges or lists -> an xarray Dataset of summary metrics.

>>> from rotorkin.io.config import load_config
>>> _, raw, _ = load_config()  # the default example
>>> ds = run_sweep(raw, {"drive.plate_tilt": "20deg:55deg:36",
...                      "drive.roller_axis_angle": "80deg,90deg,100deg"}, progress=False)
>>> ds["chamber_swing_deg"].sel({"drive.roller_axis_angle": 90.0}).max().item() > 60
True

Every design of the grid (the outer product of the swept values) is evaluated
by the drive's kernel (``kernels_<drive>.py``): broadcasting over a design axis
and, for the sampled peaks, a design x shaft-angle array in blocks, with no
Python loop over designs. Chunks of designs keep the memory bounded, can be
committed to disk as they finish (``store=``; resumable after a kill) and can
run on dask.distributed (``client=``). See ``docs/sweeps.md``.

:func:`run_sweep` and :func:`execute` return an :class:`xarray.Dataset` (the
``xarray`` extra); :func:`compute` returns the same variables as a
:class:`SweepResult` of numpy arrays and writes ``sweep.nc`` without xarray
(the command line, on the core install).
"""

from __future__ import annotations

import contextlib
import math
import sys
import time
from collections.abc import Mapping

import numpy as np

from rotorkin.core import forked
from rotorkin.core.batch import DEFAULT_SAMPLES, Designs, block_progress
from rotorkin.core.errors import ConfigError, ParameterError, shown
from rotorkin.core.extras import xarray_module
from rotorkin.core.memory import release_memory
from rotorkin.drives import evaluate, spec_of
from rotorkin.io.config import validate_config
from rotorkin.sweep.checks import check_metrics
from rotorkin.sweep.engine import (
    SweepFallbackWarning,
    SweepSpec,
    check_grid_values,
    check_spec_values,
    check_study,
    chunk_bounds,
    compute_chunk,
    coverage,
    evaluate_designs,
    kernel_of,
    optional_metrics,
    reason_keys,
    to_result,
    warn_fallback,
)
from rotorkin.sweep.result import SweepResult
from rotorkin.sweep.spec import Vary, parse_vary
from rotorkin.sweep.store import ChunkStore

__all__ = [
    "run_sweep",
    "build_spec",
    "execute",
    "compute",
    "CheckAhead",
    "SweepResult",
    "parse_vary",
    "resolve_metrics",
    "evaluate_designs",
    "Designs",
    "Vary",
    "SweepSpec",
    "SweepFallbackWarning",
    "DEFAULT_SAMPLES",
    "reason_keys",
    "reason_text",
    "result_bytes",
    "MAX_DESIGNS",
    "MAX_SAMPLES",
    "MAX_WORK",
    "MAX_RESULT_BYTES",
]

#: Default memory budget of one chunk's results [bytes].
MEMORY_BUDGET = 32 * 2**20
#: Largest chunk (designs), so that progress and resumption stay fine-grained.
MAX_CHUNK = 65_536
#: Most designs in one sweep (the grid's size); beyond, split the sweep.
MAX_DESIGNS = 20_000_000
#: Most shaft angles per period of the sampled peaks.
MAX_SAMPLES = 1_000_001
#: Most design x angle evaluations of one sweep (1e6 x 360 take about 15 s on 2 cores).
MAX_WORK = 2e10
#: Most memory the whole result may take (metrics, reasons and, with curves, the curves),
#: as estimated before anything runs [bytes]: the result is assembled in memory.
MAX_RESULT_BYTES = 8 * 2**30


def reason_text(ds, code: int) -> str:
    """The meaning of a ``reason`` code of a sweep Dataset (``"ok"`` or a config key)."""
    return ds["reason"].attrs["flag_meanings"].split()[int(code)]


def resolve_metrics(cfg: dict, metrics=None) -> tuple[str, ...]:
    """The summary keys a sweep computes.

    ``None``: those the drive's batch module computes by default (the fast path),
    or the drive's headline keys when it has none;
    ``"all"``: those, the batch module's optional ones (e.g. the
    ``sampled_*`` extremes of every curve) and every numeric summary key of
    :func:`rotorkin.drives.evaluate` (the others through the scalar study); or a
    list of names (or one comma-separated string).
    """
    kern = kernel_of(cfg["drive"]["type"], cfg)
    if metrics is None:
        return tuple(kern.metric_names(cfg)) or tuple(spec_of(cfg).headline)
    known = _all_metrics(cfg)
    if isinstance(metrics, str) and metrics == "all":
        return known
    names = [m.strip() for m in (metrics.split(",") if isinstance(metrics, str) else metrics)]
    unknown = [m for m in names if m not in known]
    if unknown or not names:
        raise ParameterError("metrics", repr(",".join(names)),
                             f"unknown metric {unknown[0] if unknown else '(none)'}; known: all, "
                             + ", ".join(known))  # fmt: skip
    return tuple(dict.fromkeys(names))


def _all_metrics(cfg: dict) -> tuple[str, ...]:
    """Numeric summary keys of the study (from the kernel list and one scalar run)."""

    kern = kernel_of(cfg["drive"]["type"], cfg)
    names = [*kern.metric_names(cfg), *optional_metrics(kern, cfg)]
    try:
        summary = evaluate(cfg).summary
    except ParameterError:
        return tuple(names)
    for k, v in summary.items():
        if isinstance(v, (bool, int, float, np.number)) and k not in names:
            names.append(k)
    return tuple(names)


def _varies(base_raw: dict, vary) -> tuple[Vary, ...]:
    if isinstance(vary, Mapping):
        items = []
        for key, spec in vary.items():
            if not isinstance(spec, str):
                spec = ",".join(str(s) for s in spec)
            items.append(f"{key}={spec}")
    else:
        items = list(vary or [])
    out = tuple(parse_vary(item, base_raw) for item in items)
    keys = [v.key for v in out]
    dup = next((k for k in keys if keys.count(k) > 1), None)
    if dup:
        raise ConfigError(f"--vary {shown(dup)[1:-1]} is not admissible: the key is given twice")
    return out


def _chunk_size(n_metrics: int, curves: int, points: int, size: int, budget: int) -> int:
    per_design = 8 * (n_metrics + 2) * 3 + 8 * points * curves * 3
    return int(max(1, min(MAX_CHUNK, budget // per_design, max(size, 1))))


def result_bytes(size: int, n_metrics: int, n_curves: int = 0, points: int = 0) -> int:
    """Estimated memory of a sweep's result [bytes]: float64 metrics and curves, the reasons
    and violations (int16)."""
    return size * (8 * n_metrics + 4 + 8 * n_curves * points) + (8 * points if n_curves else 0)


def _check_size(varies, size: int, n_metrics: int, n_curves: int, points: int) -> None:
    """Refuse a grid beyond :data:`MAX_DESIGNS` or a result beyond :data:`MAX_RESULT_BYTES`."""
    dims = " x ".join(f"{v.key}[{len(v)}]" for v in varies)
    if size > MAX_DESIGNS:
        raise ConfigError(f"--vary: {dims} = {size:.4g} designs is not admissible: at most "
                          f"{MAX_DESIGNS:.0e} designs per sweep; split it")  # fmt: skip
    need = result_bytes(size, n_metrics, n_curves, points)
    if need > MAX_RESULT_BYTES:
        what = f"{n_metrics} metrics" + (f" and {n_curves} curves x {points} points (--curves)"
                                         if n_curves else "")  # fmt: skip
        raise ConfigError(f"--vary: {dims} = {size} designs is not admissible: its result ("
                          f"{what} per design) would take {need / 2**30:.3g} GiB in memory, "
                          f"at most {MAX_RESULT_BYTES / 2**30:.3g} GiB; fewer designs"
                          + (", fewer run.points or no --curves" if n_curves else
                             " or --metrics") )  # fmt: skip


def build_spec(base_cfg_raw: dict, vary, *, keep_curves=False, chunk_size=None, metrics=None,
               samples=None, memory_budget=MEMORY_BUDGET, name="sweep", extra=None,
               check=True, design_checks=True) -> SweepSpec:  # fmt: skip
    """Validate a sweep and return its :class:`SweepSpec` (arguments of :func:`run_sweep`).

    With ``design_checks`` (default) the checks of ``rotorkin run`` are recorded as
    variables (:mod:`rotorkin.sweep.checks`) and what they refuse is inadmissible.
    """

    cfg = validate_config(base_cfg_raw)
    varies = _varies(base_cfg_raw, vary)
    names = resolve_metrics(cfg, metrics)
    samples = DEFAULT_SAMPLES if samples is None else int(samples)
    if not 3 <= samples <= MAX_SAMPLES:
        raise ParameterError("samples", samples, f"3 <= samples <= {MAX_SAMPLES}")
    points = int(cfg["run"]["points"])
    size = math.prod(len(v) for v in varies)
    n_curves = len(kernel_of(cfg["drive"]["type"], cfg).CURVES) if keep_curves else 0
    _check_size(varies, size, len(names), n_curves, points)
    if design_checks:
        names = names + check_metrics(cfg, varies, names)
        _check_size(varies, size, len(names), n_curves, points)
    if size * samples > MAX_WORK:
        raise ParameterError(
            "samples",
            samples,
            f"designs x samples <= {MAX_WORK:.0e} ({size} designs here: samples <= "
            f"{int(MAX_WORK // size)}); fewer designs or samples",
        )
    if chunk_size is None:
        chunk_size = _chunk_size(len(names), n_curves, points, size, memory_budget)
    elif int(chunk_size) < 1:
        raise ParameterError("chunk_size", chunk_size, "chunk_size >= 1")
    spec = SweepSpec(name, base_cfg_raw, cfg, varies, names, samples, bool(keep_curves), points,
                     int(chunk_size), dict(extra or {}))  # fmt: skip
    if check:
        check_spec_values(spec)
    return spec


class CheckAhead:
    """:func:`check_spec_values` of a spec built with ``check=False``, its last check ahead.

    The checks over the grid run when it is made (one line for a refused value); the
    last, one admissible design through the scalar study (a few tenths of a second, the
    keys no kernel reads), runs in a forked process beside the sweep, where this system
    forks (else here, at once). Give :meth:`confirm` to :func:`compute` (it waits for
    the check before anything is written) and :meth:`cancel` it when the sweep ends
    otherwise; as a context manager it cancels on leaving.

    Raises
    ------
    RotorkinError
        From the constructor or :meth:`confirm`: what :func:`check_spec_values` raises.
    """

    def __init__(self, spec: SweepSpec):
        self._job = None
        cfg = check_grid_values(spec)
        if cfg is not None:
            self._job = forked.ahead(check_study, cfg)
            if self._job is None:
                check_study(cfg)

    def confirm(self) -> None:
        """Wait for the study's check; its one-line error raised here (then no more)."""
        job, self._job = self._job, None
        if job is not None:
            job.result()

    def cancel(self) -> None:
        """End the study's check if it still runs."""
        job, self._job = self._job, None
        if job is not None:
            job.cancel()

    def __enter__(self) -> CheckAhead:
        return self

    def __exit__(self, *exc) -> None:
        self.cancel()


def run_sweep(base_cfg_raw: dict, vary, *, keep_curves: bool = False, chunk_size=None,
              store=None, client=None, progress: bool = True, metrics=None, samples=None,
              threads=None, memory_budget: int = MEMORY_BUDGET, name: str = "sweep",
              keep_chunks: bool = False, on_status=None):  # fmt: skip
    """Evaluate a grid of designs; return an :class:`xarray.Dataset`.

    Parameters
    ----------
    base_cfg_raw : dict
        The base config as written (TOML mapping, units in strings), e.g. the
        ``raw`` of :func:`rotorkin.io.config.load_config`.
    vary : dict or list
        Config key -> values: ``"START:STOP:N"``, ``"v1,v2,..."`` or a list of
        values as in a config (``["30 deg", "45 deg"]``); or a list of
        ``"KEY=SPEC"`` strings. One dimension per key, in order.
    keep_curves : bool
        Also keep the kernel's curves over ``run.points`` angles (dimension ``point``).
    chunk_size : int, optional
        Designs per chunk; default from ``memory_budget``.
    store : path, optional
        Sweep folder: chunks are committed to ``store/.chunks`` as they finish,
        the result is written to ``store/sweep.nc``; a killed sweep restarted
        with the same arguments computes only the missing chunks.
    client : distributed.Client, optional
        Run the chunks on this dask cluster instead of locally.
    progress : bool
        A rich progress bar on stderr when it is a terminal.
    metrics : None, "all" or list of str
        See :func:`resolve_metrics`.
    samples : int, optional
        Shaft angles per period for the sampled peaks (default 20001, as the
        studies, so that a sweep equals the designs run one by one).
    threads : int, optional
        Kernel threads of the local run (default: all cores).
    memory_budget : int
        Bytes of results per chunk, for the default chunk size.
    name : str
        Run name (in the Dataset's attributes).
    keep_chunks : bool
        Keep ``store/.chunks`` after writing ``sweep.nc``.
    on_status : callable, optional
        ``on_status(message)`` for one-line notes (resumption).

    Returns
    -------
    xarray.Dataset
        One dimension per swept key (coordinates in deg, mm, ... with a
        ``units`` attribute), every metric (summary key names) and ``reason``
        (0 admissible, else the index of the violated key in its
        ``flag_meanings``; metrics NaN); with curves, a ``point`` dimension.
    """
    xarray_module("rotorkin.sweep.run_sweep")
    spec = build_spec(base_cfg_raw, vary, keep_curves=keep_curves, chunk_size=chunk_size,
                      metrics=metrics, samples=samples, memory_budget=memory_budget,
                      name=name)  # fmt: skip
    _, _, why = coverage(spec.drive_type, spec.base_cfg, [v.key for v in spec.varies],
                         spec.metrics)  # fmt: skip
    warn_fallback(why, spec.size)
    return execute(spec, store=store, client=client, progress=progress, threads=threads,
                   keep_chunks=keep_chunks, on_status=on_status)  # fmt: skip


def execute(spec: SweepSpec, *, store=None, client=None, progress=True, threads=None,
            keep_chunks=False, on_status=None):  # fmt: skip
    """Run a validated spec (locally or on ``client``); an :class:`xarray.Dataset`.

    As :func:`compute`, whose :class:`SweepResult` it turns into a Dataset (the
    ``xarray`` extra: without it, ``ModuleNotFoundError`` naming
    ``pip install "rotorkin[xarray]"`` before any work).
    """
    xarray_module("rotorkin.sweep.execute")
    return compute(spec, store=store, client=client, progress=progress, threads=threads,
                   keep_chunks=keep_chunks, on_status=on_status).to_dataset()  # fmt: skip


def compute(spec: SweepSpec, *, store=None, client=None, progress=True, threads=None,
            keep_chunks=False, on_status=None, confirm=None,
            on_result=None) -> SweepResult:  # fmt: skip
    """Run a validated spec (locally or on ``client``), optionally through a chunk store.

    Returns the :class:`SweepResult` (numpy arrays; no xarray needed). With
    ``store``, the chunks are committed to ``store/.chunks`` as they finish and the
    result is written to ``store/sweep.nc`` (streamed, atomically). ``confirm()``, if
    given, is called once before anything is written into ``store`` (before the result
    is returned without one): an exception it raises ends the sweep there
    (:meth:`CheckAhead.confirm`). ``on_result(result)``, if given, is called with the
    assembled result before ``sweep.nc`` is written (to start work on it meanwhile).
    """
    from pathlib import Path

    chunks = ChunkStore.of_spec(Path(store) / ".chunks", spec.manifest()) if store else None
    # a new store is made once confirmed: a sweep refused then leaves no folder behind;
    # an existing one (chunks to resume, or to replace) is opened now, confirmed first
    opened = chunks is None or confirm is None or chunks.folder.exists()

    def confirmed() -> None:
        nonlocal confirm, opened
        if confirm is not None:
            check, confirm = confirm, None
            check()
        if not opened:
            opened = True
            chunks.open()

    if store is not None:
        for stale in Path(store).glob(".sweep.nc.tmp-*"):  # a killed run's half-written result
            stale.unlink(missing_ok=True)
    if chunks is not None and opened:
        confirmed()
        done = chunks.open()
    else:
        done = set()
    if chunks and done and on_status:
        on_status(f"resuming: {len(done)} of {spec.n_chunks} chunks already committed, "
                  f"computing {spec.n_chunks - len(done)}")  # fmt: skip
    todo = [(i, *chunk_bounds(spec, i)) for i in range(spec.n_chunks) if i not in done]
    # every chunk computed now is placed as it arrives (and committed, with a store); only
    # the chunks of an earlier run are read back from the store at the end
    flat = _empty(spec)

    with _Progress(progress, spec.size, done_designs=spec.size - sum(b - a for _, a, b in todo)) \
            as bar:  # fmt: skip

        def take(index, res):
            if chunks:
                confirmed()
                chunks.commit(index, res)
            _place(flat, res)
            bar.finish_chunk(res["stop"] - res["start"])

        if client is not None:
            from rotorkin.sweep.dask import run_chunks

            run_chunks(client, spec, todo, take)
        else:
            for index, start, stop in todo:
                with bar.within(stop - start):  # advanced block by block inside the chunk
                    res = compute_chunk(spec, start, stop, threads)
                take(index, res)
    confirmed()
    if chunks:
        release_memory()  # the chunks' freed work arrays, back before earlier chunks are read
        _assemble(flat, spec, chunks, done)
    if not np.all(flat["count"] == 1):
        bad = np.flatnonzero(flat["count"] != 1)
        raise RuntimeError(f"{bad.size} designs lost or duplicated in the sweep chunks")
    flat.pop("count", None)
    result = to_result(spec, flat)
    if on_result is not None:
        on_result(result)
    if chunks:
        result.to_netcdf(Path(store) / "sweep.nc")
        if not keep_chunks:
            chunks.remove()
    return result


def _empty(spec: SweepSpec) -> dict:
    # not filled: every design is placed once (``count``, checked), the pages are touched then
    flat = {
        "metrics": {m: np.empty(spec.size) for m in spec.metrics},
        "reason": np.zeros(spec.size, dtype=np.int16),
        "violations": np.zeros(spec.size, dtype=np.int16),
        "count": np.zeros(spec.size, dtype=np.int8),
    }
    if spec.keep_curves:
        kern = kernel_of(spec.drive_type, spec.base_cfg)
        flat["curves"] = {c: np.empty((spec.size, spec.points)) for c in kern.CURVES}
        flat["angle"] = None
    return flat


def _place(flat: dict, res: dict) -> None:
    idx = res["design"]
    for m, values in res["metrics"].items():
        flat["metrics"][m][idx] = values
    flat["reason"][idx] = res["reason"]
    if "violations" in res:
        flat["violations"][idx] = res["violations"]
    flat["count"][idx] += 1
    if "curves" in res:
        for c, values in res["curves"].items():
            flat["curves"][c][idx] = values
        angle = np.asarray(res["angle"])
        if angle.ndim == 1:
            flat["angle"] = angle
        else:
            if flat["angle"] is None or np.ndim(flat["angle"]) == 1:
                flat["angle"] = np.full((len(flat["reason"]), angle.shape[-1]), np.nan)
            flat["angle"][idx] = angle


def _assemble(flat: dict, spec: SweepSpec, chunks, earlier) -> None:
    """Place the chunks committed by an earlier run (``earlier``) into ``flat``, read from
    the store (the caller checks that each design appears exactly once)."""
    missing = sorted(set(range(spec.n_chunks)) - chunks.committed())
    if missing:
        raise RuntimeError(f"sweep chunks missing after the run: {missing[:5]}")
    for i in sorted(earlier):
        _place(flat, chunks.read(i))
        release_memory()  # the chunk's buffer: not kept in the heap beside the result


#: Seconds between two moves of the progress bar within a chunk.
_PROGRESS_EVERY = 0.1


class _Progress:
    """A rich progress bar over designs on stderr (only on a terminal and when wanted)."""

    def __init__(self, wanted: bool, total: int, done_designs: int = 0):
        self.bar = None
        self._chunk_left = None  # designs of the running chunk not shown yet
        self.total, self.done = total, done_designs
        self.wanted = bool(wanted) and sys.stderr.isatty()
        self.t0 = time.perf_counter()

    def __enter__(self):
        if self.wanted:
            from rich.console import Console
            from rich.progress import (
                BarColumn,
                MofNCompleteColumn,
                Progress,
                TextColumn,
                TimeElapsedColumn,  # fmt: skip
                TimeRemainingColumn,
            )

            self.bar = Progress(TextColumn("sweep"), BarColumn(), MofNCompleteColumn(),
                                TextColumn("designs"), TimeElapsedColumn(), TimeRemainingColumn(),
                                console=Console(stderr=True, markup=False),
                                transient=True)  # fmt: skip
            self.bar.start()
            self.task = self.bar.add_task("sweep", total=self.total, completed=self.done)
        return self

    def advance(self, n: int) -> None:
        if self.bar is not None:
            self.bar.advance(self.task, n)

    @contextlib.contextmanager
    def within(self, designs: int):
        """Advance block by block while a chunk of ``designs`` is computed (local runs).

        The kernels report their finished blocks
        (:func:`rotorkin.core.batch.block_progress`); the bar is moved at most
        every :data:`_PROGRESS_EVERY` seconds, and by at most ``designs`` before
        :meth:`finish_chunk` adds the rest.
        """
        self._chunk_left = designs
        if self.bar is None:
            yield
            return
        pending, last = 0, time.perf_counter()

        def done(n):
            nonlocal pending, last
            n = min(n, self._chunk_left - pending)
            pending += n
            now = time.perf_counter()
            if pending and now - last >= _PROGRESS_EVERY:
                self.bar.advance(self.task, pending)
                self._chunk_left -= pending
                pending, last = 0, now

        with block_progress(done):
            yield

    def finish_chunk(self, designs: int) -> None:
        """A chunk of ``designs`` is committed: show what its blocks have not shown yet."""
        left = self._chunk_left
        self.advance(designs if left is None else left)
        self._chunk_left = None

    def __exit__(self, *exc):
        if self.bar is not None:
            self.bar.stop()
        return False
