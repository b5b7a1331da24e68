"""Fused evaluation of closed forms: compiled loops (numba) when installed, numpy otherwise.

The kinematics of a drive are closed forms: a few transcendental calls per point
(``tan``, ``arctan``, ``sqrt``) and a few dozen multiplications and additions.
numpy evaluates the transcendental calls as fast as anything can (vectorised
loops), but each arithmetic operation is a separate pass over memory. This
module lets a drive evaluate them in *blocks* of :data:`BLOCK` points that stay
in the cache, with the arithmetic of a block either

* as numpy operations on the block (always available, the fallback), or
* fused into one compiled loop per stage (numba, the optional ``fast`` extra):
  the point's formula, written once as a plain Python function of numbers and
  marked with :func:`formula`, is compiled into the loop; the same function
  called on numpy arrays is the fallback, so both paths run the same
  operations in the same order.

The transcendental calls stay numpy calls on the block in both paths.

Which path runs (:func:`use_compiled`): ``kernel="numpy"`` or ``"numba"``
where a function takes it, else ``$ROTORKIN_KERNEL`` (``auto``, ``numpy`` or
``numba``), else ``auto``: numba when it is installed, for evaluations of at least
:data:`AUTO_MIN_POINTS` points and, once numba has been loaded, for all (a small
evaluation alone does not import numba: importing it and loading compiled code takes
a few tenths of a second, more than it saves on a few thousand points). Compiled
loops are cached on disk by numba (``__pycache__`` beside the source, else the
user's cache folder). numba checks the cache against the loop's own source file only:
keep a drive's formulas in the file of its loops, and after changing :func:`at` or
:func:`select` here delete the cached ``*.nbi``/``*.nbc`` files.

Threads: the blocks of large evaluations may be shared among a pool of threads
(:func:`split`, ``threads=`` or ``$ROTORKIN_THREADS``, default 1): numpy
releases the GIL in its loops and the compiled loops run without it. Each value
depends only on its own point, so results do not depend on the thread count.
"""

from __future__ import annotations

import math
import os
import threading
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from rotorkin.core.errors import ParameterError

__all__ = [
    "AUTO_MIN_POINTS",
    "BLOCK",
    "COMPILED_BLOCK",
    "KERNELS",
    "KERNEL_ENV",
    "MIN_PARALLEL",
    "THREADS_ENV",
    "at",
    "chunks",
    "compiled_loop",
    "default_threads",
    "evaluate",
    "formula",
    "kernel_choice",
    "numba_available",
    "prefer_compiled",
    "prepare",
    "shared_pool",
    "select",
    "split",
    "use_compiled",
]

#: Points per block: a block's scratch arrays (64 KiB each) stay in the L2 cache.
BLOCK = 8192
#: Environment variable choosing the kernels: ``auto`` (default), ``numpy`` or ``numba``.
KERNEL_ENV = "ROTORKIN_KERNEL"
#: The admissible choices of kernels.
KERNELS = ("auto", "numpy", "numba")
#: With ``auto``: fewest points of one evaluation for which the compiled loops are used.
#: Importing numba and loading the compiled code takes about 0.5 s, numpy about 0.1 us a
#: point: one study's evaluations (up to ~1e5 points) stay numpy, a sweep's blocks of
#: designs (360 angles x 1000 designs and more) load the compiled loops.
AUTO_MIN_POINTS = 1 << 17
#: Environment variable giving the default thread count (default 1).
THREADS_ENV = "ROTORKIN_THREADS"
#: Points per block of the compiled loops: a block's Python work (a few numpy calls and
#: compiled loops, ~15 us) is then a few per cent of its time, which keeps two threads
#: from waiting on each other for the interpreter's lock (with 8192-point blocks two
#: threads ran 1.0-1.6x as fast as one on this project's 2-core machine, with 32768
#: 1.5-1.8x, and one thread 5-10 % faster).
COMPILED_BLOCK = 4 * BLOCK
#: Fewest points for which the thread pool is used.
MIN_PARALLEL = 8 * BLOCK

_FORMULAS: list = []
_NUMBA = None  # the numba module once imported and set up; False when it cannot be imported
_NUMBA_LOCK = threading.RLock()
_POOL: ThreadPoolExecutor | None = None
_POOL_KEY = (0, 0)  # (threads, pid): a pool inherited through fork() has no threads
_POOL_LOCK = threading.Lock()


# --------------------------------------------------------------------------------------------
# the formulas and their helpers (plain Python on numbers or arrays; compiled inside loops)
# --------------------------------------------------------------------------------------------
def formula(fn):
    """Mark ``fn`` as a point formula: plain Python on numbers (or arrays).

    Called on numpy arrays it is the numpy path; compiled loops call it on
    numbers, inlined into the loop's own code. It may only use arithmetic,
    :func:`at`, :func:`select` and other formulas. Returns ``fn`` itself.
    """
    _FORMULAS.append(fn)
    if _NUMBA:
        _register(_NUMBA, fn)
    return fn


def _register(numba, fn) -> None:
    """Teach numba a formula (inlined into the loops that call it)."""
    numba.extending.register_jitable(inline="always")(fn)


def at(x, i):
    """``x[i]`` for an array (a block of per-point values), ``x`` for a number."""
    return x[i] if np.ndim(x) else x


def select(flag, a, b):
    """``a`` where ``flag`` else ``b`` (``numpy.where`` on arrays, a branch on numbers)."""
    return np.where(flag, a, b)


def _setup_numba():
    """Import numba and teach it :func:`at`, :func:`select` and the formulas (once)."""
    global _NUMBA
    with _NUMBA_LOCK:
        if _NUMBA is not None:
            return _NUMBA
        try:
            import numba
            import numba.extending
            from numba import types
        except ImportError:
            _NUMBA = False
            return _NUMBA

        @numba.extending.overload(at, inline="always")
        def _at(x, i):
            if isinstance(x, types.Array) and x.ndim == 0:
                return lambda x, i: x[()]
            if isinstance(x, types.Array):
                return lambda x, i: x[i]
            return lambda x, i: x

        @numba.extending.overload(select)
        def _select(flag, a, b):
            def impl(flag, a, b):
                return a if flag else b

            return impl

        for fn in _FORMULAS:
            _register(numba, fn)
        _NUMBA = numba
        return _NUMBA


def numba_available() -> bool:
    """Whether numba can be imported (the ``fast`` extra is installed)."""
    return bool(_setup_numba())


class _Loop:
    """A loop compiled by numba on first call (nogil, numpy's division semantics, cached)."""

    def __init__(self, fn):
        self.py = fn
        self._compiled = None
        self.__doc__ = fn.__doc__
        self.__name__ = fn.__name__

    def __call__(self, *args):
        if self._compiled is None:
            numba = _setup_numba()
            if not numba:
                raise ParameterError(KERNEL_ENV, "'numba'", "numba installed (the fast extra)")
            with _NUMBA_LOCK:
                if self._compiled is None:
                    self._compiled = numba.njit(
                        nogil=True, error_model="numpy", fastmath=False, cache=True
                    )(self.py)
        return self._compiled(*args)


def compiled_loop(fn):
    """Decorator: ``fn`` (a loop over points calling formulas) compiled by numba on first call.

    The compiled loop releases the GIL; division by zero gives inf/nan as in numpy
    (no exception); no fast-math (the operations are those of the source, in order).
    """
    return _Loop(fn)


# --------------------------------------------------------------------------------------------
# choosing the path
# --------------------------------------------------------------------------------------------
def kernel_choice(kernel=None) -> str:
    """``kernel`` if given, else ``$ROTORKIN_KERNEL``, else ``"auto"``; checked.

    Raises
    ------
    ParameterError
        named ``kernel`` (or ``ROTORKIN_KERNEL``) for any other value.
    """
    name = "kernel"
    if kernel is None:
        kernel, name = os.environ.get(KERNEL_ENV, "").strip() or "auto", KERNEL_ENV
    if kernel not in KERNELS:
        raise ParameterError(name, repr(kernel), "one of " + ", ".join(map(repr, KERNELS)))
    return kernel


def use_compiled(points: int, kernel=None) -> bool:
    """Whether an evaluation of ``points`` points runs the compiled loops.

    ``numpy``: never; ``numba``: always (a :class:`ParameterError` when numba is not
    installed); ``auto``: when numba is installed and either ``points >= AUTO_MIN_POINTS``
    or numba is already loaded (by an earlier evaluation).
    """
    choice = kernel_choice(kernel)
    if choice == "numpy":
        return False
    if choice == "numba":
        if not numba_available():
            raise ParameterError(
                "kernel", "'numba'", "numba installed (pip install 'rotorkin[fast]')"
            )
        return True
    if _NUMBA:
        return True
    return points >= AUTO_MIN_POINTS and numba_available()


def prefer_compiled(points: int, kernel=None) -> bool:
    """Before a batch of evaluations of ``points`` points in all: whether they run compiled.

    With ``auto`` and ``points >= AUTO_MIN_POINTS`` numba is loaded now (when installed),
    so that every evaluation of the batch runs the compiled loops, however small each one
    is (a sweep evaluates its designs in blocks); otherwise as :func:`use_compiled`.
    """
    if kernel_choice(kernel) == "auto" and points >= AUTO_MIN_POINTS:
        return numba_available()
    return use_compiled(points, kernel)


# --------------------------------------------------------------------------------------------
# blocks and threads
# --------------------------------------------------------------------------------------------
def default_threads() -> int:
    """Threads used when ``threads=None``: ``$ROTORKIN_THREADS``, else 1.

    Raises
    ------
    ParameterError
        named ``ROTORKIN_THREADS`` when it is not an integer >= 1.
    """
    text = os.environ.get(THREADS_ENV, "").strip()
    if not text:
        return 1
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise ParameterError(THREADS_ENV, repr(text), "an integer >= 1 (threads per evaluation)")
    return value


def shared_pool(size: int) -> ThreadPoolExecutor:
    """A shared pool with at least ``size`` threads (created on first use)."""
    global _POOL, _POOL_KEY
    with _POOL_LOCK:
        if _POOL is None or _POOL_KEY[0] < size or _POOL_KEY[1] != os.getpid():
            old, forked = _POOL, _POOL_KEY[1] != os.getpid()
            _POOL = ThreadPoolExecutor(max_workers=size, thread_name_prefix="rotorkin")
            _POOL_KEY = (size, os.getpid())
            if old is not None and not forked:
                old.shutdown(wait=False)
        return _POOL


def split(run, size: int, threads=None) -> None:
    """Call ``run(lo, hi)`` over the flat points ``0:size``, on threads for large sizes.

    Parameters
    ----------
    run : callable
        ``run(lo, hi)`` evaluates the points ``lo:hi`` (block by block).
    size : int
        Number of points.
    threads : int, optional
        Threads (default :func:`default_threads`); sizes under :data:`MIN_PARALLEL`
        always run on the calling thread. Ranges are whole blocks.

    Raises
    ------
    ParameterError
        named ``threads`` when it is not an integer >= 1.
    """
    nthreads = default_threads() if threads is None else int(threads)
    if nthreads < 1:
        raise ParameterError("threads", repr(threads), "an integer >= 1")
    nthreads = min(nthreads, max(1, size // (MIN_PARALLEL // 2)))
    if nthreads == 1 or size < MIN_PARALLEL:
        run(0, size)
        return
    step = -(-size // nthreads)
    step = -(-step // BLOCK) * BLOCK
    cuts = [(lo, min(size, lo + step)) for lo in range(0, size, step)]
    # the calling thread takes the first range: one thread fewer to wake and to share with
    pool = shared_pool(len(cuts) - 1)
    futures = [pool.submit(run, lo, hi) for lo, hi in cuts[1:]]
    try:
        run(*cuts[0])
    finally:
        done = [f.exception() for f in futures]  # every range ended before returning
    for exc in done:
        if exc is not None:
            raise exc


def prepare(inputs: dict):
    """Split the inputs of an evaluation into numbers and arrays, and find its shape.

    Parameters
    ----------
    inputs : dict of str -> array_like
        Every input of the closed form that may vary per point (floats).

    Returns
    -------
    shape : tuple
        Broadcast shape of the inputs.
    scalars : dict of str -> float
        The inputs with one element.
    arrays : dict of str -> ndarray
        The others: flat when ``flat``.
    flat : bool
        Every array has the full shape and is C-contiguous: blocks are slices
        (else :func:`chunks` broadcasts them with a buffered iterator).
    """
    inputs = {k: np.asarray(v, dtype=float) for k, v in inputs.items()}
    shapes = {a.shape for a in inputs.values()} - {()}
    shape = shapes.pop() if len(shapes) == 1 else np.broadcast_shapes(*shapes, ())
    scalars = {k: float(a.reshape(-1)[0]) for k, a in inputs.items() if a.size == 1}
    arrays = {k: a for k, a in inputs.items() if a.size > 1}
    flat = all(a.shape == shape and a.flags.c_contiguous for a in arrays.values())
    if flat:
        arrays = {k: a.reshape(-1) for k, a in arrays.items()}
    return shape, scalars, arrays, flat


def chunks(arrays: dict, flat: bool, lo: int, hi: int, block: int = BLOCK):
    """``(start, stop, {name: block of the input})`` over the flat points ``lo:hi``.

    ``flat`` (see :func:`prepare`): a block is a slice of each array; otherwise a
    buffered C-order :class:`numpy.nditer` broadcasts them (never materialised at
    the full size). With no arrays, one chunk ``(lo, hi, {})``.
    """
    names = list(arrays)
    if not names:
        yield lo, hi, {}
        return
    if flat:
        for start in range(lo, hi, block):
            stop = min(hi, start + block)
            yield start, stop, {name: arrays[name][start:stop] for name in names}
        return
    it = np.nditer(
        [arrays[name] for name in names],
        flags=["external_loop", "buffered", "ranged", "zerosize_ok"],
        op_flags=[["readonly", "contig"]] * len(names),
        buffersize=block,
        order="C",
    )
    it.iterrange = (lo, hi)
    while not it.finished:
        start = it.iterindex
        chunk = it.value if len(names) > 1 else (it.value,)
        yield start, start + chunk[0].shape[0], dict(zip(names, chunk, strict=True))
        it.iternext()


def evaluate(
    inputs: dict, outputs: int, block, *, threads=None, kernel=None, out=None, constants=None
):
    """Evaluate a closed form with ``outputs`` values per point, block by block.

    Parameters
    ----------
    inputs : dict of str -> array_like
        The inputs that may vary per point (broadcast together).
    outputs : int
        Values per point.
    block : callable
        ``block(x, o, compiled)``: fill ``o`` (``outputs``, m) from ``x`` (name ->
        number or block of m values) with the numpy path or, when ``compiled``,
        the compiled loops.
    threads : int, optional
        Threads sharing the blocks (:func:`split`).
    kernel : {"auto", "numpy", "numba"}, optional
        :func:`use_compiled`.
    out : ndarray, optional
        ``(outputs, *shape)`` float64, C-contiguous, to write into.
    constants : (callable, tuple of str), optional
        ``(fn, names)``: ``fn(inputs)`` returns a dict of values derived from the inputs
        ``names`` (arrays of their own shapes, e.g. designs ``(m, 1)``), computed once
        per call and then broadcast block by block like the inputs.

    Returns
    -------
    ndarray, shape (outputs, ...)
        ``...`` the broadcast shape of the inputs.
    """
    if constants is not None:  # once per call, on the inputs' own shapes (not per point)
        derive, _ = constants
        inputs = {k: np.asarray(v, dtype=float) for k, v in inputs.items()}
        inputs.update(derive(inputs))
    shape, scalars, arrays, flat = prepare(inputs)
    size = math.prod(shape)
    if out is None:
        out = np.empty((outputs, *shape))
    elif not (
        isinstance(out, np.ndarray)
        and out.dtype == np.float64
        and out.shape == (outputs, *shape)
        and out.flags.c_contiguous
        and out.flags.writeable
    ):
        want = (outputs, *shape)
        raise ValueError(f"out: expected a writeable C-contiguous float64 array {want}")
    if size == 0:
        return out
    compiled = use_compiled(size, kernel)
    flat_out = out.reshape(outputs, size)

    step = COMPILED_BLOCK if compiled else BLOCK

    def run(lo, hi):
        for start, stop, chunk in chunks(arrays, flat, lo, hi, step):
            block({**scalars, **chunk}, flat_out[:, start:stop], compiled)

    split(run, size, threads)
    return out
