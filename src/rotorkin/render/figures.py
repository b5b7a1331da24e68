"""Helpers of the matplotlib figures, and the recipe of a paper's sweep figure.

matplotlib is imported when a figure is drawn, never at import time, and its
backend is left to the caller: the command line selects Agg; a notebook keeps
its own.

:func:`draw` draws a run's figures, given as tasks (callables that write one or
more files and return their paths), on the cores of the machine: the process
forks workers that inherit the study's arrays and each draw a share of the
figures, the figures being independent of each other
(``$ROTORKIN_FIGURE_WORKERS``; ``1`` draws them in this process, one after the
other, as where ``fork`` is unavailable). Inside :func:`drawing_ahead` the drawing
process is forked before the study starts and imports pyplot on another core while
the study computes; the study's figure tasks travel to it by pickle.
"""

from __future__ import annotations

import contextlib
import gc
import os
import pickle
import signal
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from rotorkin.core import forked

__all__ = [
    "draw",
    "draw_soon",
    "Drawing",
    "drawing_ahead",
    "figure_workers",
    "FigureError",
    "WORKERS_ENV",
    "recording",
    "DPI",
    "BASELINE",
    "SYNTHESIZED",
    "pyplot",
    "png_bytes",
    "save",
    "save_in",
    "fixed_layout",
    "axes3d",
    "RUN_STYLE",
    "degree_axis",
    "plain_log_labels",
    "Recipe",
]

#: Resolution of the PNG figures [dots per inch].
DPI = 120


@dataclass
class _Helper:
    """The drawing process forked by :func:`drawing_ahead`: its pid and its two pipes."""

    pid: int
    tasks_w: int  # this process writes the pickled tasks, then closes it
    out_r: int  # the helper writes its result, then ends


#: The drawing process of the current :func:`drawing_ahead` block, until a draw takes it.
_HELPER: _Helper | None = None

#: The matplotlib settings of the current :func:`drawing_ahead` block, applied once.
_STYLE: dict | None = None

#: Drawing processes given their tasks by :func:`draw_soon`, not yet waited for.
_HANDED: list[_Helper] = []


@contextlib.contextmanager
def drawing_ahead(style: dict | None = None):
    """Fork the process that draws the block's figures now, before the study computes.

    The forked process imports ``matplotlib.pyplot`` and applies ``style`` (rcParams) on
    another core while this one computes; the first :func:`draw` in the block sends it
    its tasks by pickle. It forks the other workers and draws with them; this process
    waits for the paths. Tasks that do not pickle are drawn as without the block (this
    process imports pyplot and forks after the study). Without ``fork``, with one worker
    (:func:`figure_workers`) or where threads run, no process is forked ahead. A drawing
    process that no draw took is ended (SIGTERM) when the block ends.

    Parameters
    ----------
    style : dict, optional
        rcParams for the block's figures (:data:`RUN_STYLE` for a run), in whichever
        process draws them.
    """
    global _HELPER, _STYLE
    started = _HELPER is None and figure_workers() > 1
    previous = _STYLE
    _STYLE = dict(style) if style else None
    if started:
        _HELPER = _fork_helper(_STYLE)
    try:
        yield
    finally:
        _STYLE = previous
        if started:
            helper, _HELPER = _HELPER, None
            if helper is not None:  # no draw took it: not worth waiting for its imports
                _end_helper(helper, kill=True)
            while _HANDED:  # a drawing started and not waited for (an error came between)
                _end_helper(_HANDED.pop(), kill=True)


def _fork_helper(style: dict | None) -> _Helper | None:
    """Fork the drawing process of :func:`drawing_ahead` (None where the fork fails)."""
    forked.flush_streams()  # the child would write their buffers again
    tasks_r, tasks_w = os.pipe()
    out_r, out_w = os.pipe()
    try:
        pid = forked.fork()
    except OSError:
        for fd in (tasks_r, tasks_w, out_r, out_w):
            os.close(fd)
        return None
    if pid == 0:  # pragma: no cover - runs in the forked process
        os.close(tasks_w)
        os.close(out_r)
        _helper(tasks_r, out_w, style)
    os.close(tasks_r)
    os.close(out_w)
    forked.PRIVATE.add(tasks_w)  # the helper reads its tasks until every copy is closed
    return _Helper(pid, tasks_w, out_r)


def _helper(tasks_r: int, out_w: int, style: dict | None) -> None:  # pragma: no cover
    """The drawing process: pyplot imported, then the tasks drawn, the result sent back.

    It reads ``(tasks, workers, slowest)`` pickled until this end of the pipe closes;
    nothing read (the block ended without a draw, or the caller died): it ends at once.
    Its result is :func:`_child`'s, with ``"gone"`` for tasks it could not unpickle.
    """
    result, code = None, 1
    try:
        # until the tasks come there is nothing to clean up: a SIGTERM ends it at once
        handler = signal.signal(signal.SIGTERM, signal.SIG_DFL) if forked.HELD else None
        forked.take_signals()
        try:
            gc.disable()  # nothing to collect while importing (a third faster)
            import matplotlib.pyplot  # noqa: F401 - imported for its use by the tasks

            if style:
                matplotlib.rcParams.update(style)
        except BaseException:  # noqa: BLE001 - the caller draws, and reports the failure
            os._exit(3)
        finally:
            gc.enable()
        import select

        if not select.select([tasks_r], [], [], 0)[0]:  # idle until the study is done
            with contextlib.suppress(Exception):
                _warm_up()
        data = forked.read_all(tasks_r)
        os.close(tasks_r)
        if not data:
            os._exit(0)
        if forked.HELD:
            signal.signal(signal.SIGTERM, handler)  # workers of its own to end from now on
        try:
            tasks, workers, slowest = pickle.loads(data)
        except BaseException:  # noqa: BLE001 - the caller draws them itself
            result, code = ("gone", None), 0
        else:
            del data
            try:
                result, code = ("ok", draw(tasks, workers, slowest)), 0
            except BaseException as exc:  # noqa: BLE001 - everything goes to the caller
                result = ("error", forked.portable(exc))
    except BaseException:  # noqa: BLE001 - the process never returns into the caller's code
        result, code = None, 1
    forked.send_and_end(out_w, result, code)


def _warm_up() -> None:
    """Draw a small figure of every kind of element once, and forget it.

    The first figure a process draws loads the fonts, builds the text layout's caches and
    imports the 3D axes (0.05-0.1 s); the drawing process does it while it waits for the
    study's tasks, and the workers it forks inherit it.
    """
    plt = pyplot()
    fig = plt.figure(figsize=(3.0, 2.0), dpi=DPI)
    try:
        ax = fig.add_subplot(1, 2, 1)
        ax.plot([1.0, 2.0], [1.0, 3.0], "o-", label="a")
        ax.set_yscale("log")
        plain_log_labels(ax, "y")
        ax.set_title("title")
        ax.set_xlabel("x [deg]")
        ax.legend(loc="upper right", fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
        ax.annotate("a", (1.0, 1.0), textcoords="offset points", xytext=(6, 6), fontsize=8)
        space = axes3d(fig, 1, 2, 2, title="3d")
        space.plot([0.0, 1.0], [0.0, 1.0], [0.0, 1.0])
        fig.suptitle("suptitle")
        fig.canvas.draw()
    finally:
        plt.close(fig)


def _send(helper: _Helper, tasks: list, workers, slowest) -> None:
    """Hand the tasks to :func:`drawing_ahead`'s process (nothing, if they do not pickle:
    it then ends without a result and they are drawn here)."""
    try:
        try:
            payload = pickle.dumps((tasks, workers, tuple(slowest)), protocol=5)
        except Exception:  # noqa: BLE001 - tasks that do not pickle are drawn here
            payload = b""
        view = memoryview(payload)
        with contextlib.suppress(BrokenPipeError):  # a helper that ended: drawn here
            while view:
                view = view[os.write(helper.tasks_w, view) :]
        os.close(helper.tasks_w)
        forked.PRIVATE.discard(helper.tasks_w)
        helper.tasks_w = -1
    except BaseException:
        _end_helper(helper, kill=True)
        raise


def _collect(helper: _Helper) -> list[Path] | None:
    """The paths :func:`drawing_ahead`'s process drew; None: draw the tasks here."""
    try:
        data = forked.read_all(helper.out_r)
    except BaseException:
        _end_helper(helper, kill=True)
        raise
    status = _end_helper(helper, kill=False)
    if not data:  # nothing sent, or the helper ended without a result
        return None
    kind, payload = _result(data, status)
    if kind == "ok":
        return payload
    if kind == "error":
        raise _rebuilt(payload)
    return None


def _end_helper(helper: _Helper, kill: bool) -> int:
    """Close the pipes to the drawing process, end it if ``kill``; its wait status."""
    forked.PRIVATE.discard(helper.tasks_w)
    for fd in (helper.tasks_w, helper.out_r):
        if fd >= 0:
            with contextlib.suppress(OSError):
                os.close(fd)
    helper.tasks_w = helper.out_r = -1
    if kill:
        with contextlib.suppress(OSError):
            os.kill(helper.pid, signal.SIGTERM)
    try:
        return os.waitpid(helper.pid, 0)[1]
    except ChildProcessError:
        return 0


def _apply_style() -> None:
    """The :func:`drawing_ahead` block's rcParams in this process, once."""
    global _STYLE
    if _STYLE:
        import matplotlib

        matplotlib.rcParams.update(_STYLE)
        _STYLE = None


def pyplot():
    """``matplotlib.pyplot``, imported on first use (no garbage collection meanwhile), with
    the :func:`drawing_ahead` block's style applied (figures drawn here, not by draw)."""
    plt = sys.modules.get("matplotlib.pyplot")
    if plt is None:
        enabled = gc.isenabled()
        gc.disable()
        try:
            import matplotlib.pyplot as plt
        finally:
            if enabled:
                gc.enable()
    _apply_style()
    return plt


#: Figures kept open by :func:`recording` (None: figures are closed once written).
_RECORDED: list | None = None


@contextlib.contextmanager
def recording():
    """Collect every figure written inside the block as ``(path, Figure)``, still open.

    For tests and notebooks that look at what a figure plots (its lines' data)
    rather than at the PNG; the figures are closed when the block ends.
    """
    global _RECORDED
    previous, _RECORDED = _RECORDED, []
    record = _RECORDED
    try:
        yield record
    finally:
        _RECORDED = previous
        for _, fig in record:
            pyplot().close(fig)


def _done(fig, path: Path) -> None:
    """Close a written figure, or keep it for :func:`recording`."""
    if _RECORDED is None:
        pyplot().close(fig)
    else:
        _RECORDED.append((Path(path), fig))


#: zlib level of the PNG files (1: fastest).
PNG_COMPRESS_LEVEL = 1


def _write(fig, path, dpi: int) -> None:
    """``fig.savefig(path, dpi=dpi)``; a PNG written by :func:`png_bytes`.

    matplotlib renders the figure into an RGBA buffer (``format="rgba"``); the PNG is
    encoded here: RGB where every pixel is opaque (a quarter less to compress), rows
    unfiltered, zlib at :data:`PNG_COMPRESS_LEVEL`. Pillow's encoder tries every row
    filter on every row: twice the time for files ~15 % larger on these flat-coloured
    plots. Where the figure is drawn at another resolution than it is written at, or
    the buffer is not its size (a ``savefig.bbox = tight`` in a matplotlibrc),
    matplotlib writes the PNG itself.
    """
    if Path(path).suffix.lower() != ".png" or fig.dpi != dpi:
        fig.savefig(path, dpi=dpi, **_png_options(path))
        return
    import io

    import numpy as np

    buf = io.BytesIO()
    fig.savefig(buf, format="rgba", dpi=dpi)
    width, height = fig.canvas.get_width_height(physical=True)
    raw = buf.getbuffer()
    if len(raw) != width * height * 4:
        fig.savefig(path, dpi=dpi, **_png_options(path))
        return
    rgba = np.frombuffer(raw, dtype=np.uint8).reshape(height, width, 4)
    Path(path).write_bytes(png_bytes(rgba, software=f"matplotlib {_mpl_version()}"))


def _png_options(path) -> dict:
    """``savefig``'s options of a file matplotlib writes: a PNG at our zlib level."""
    if Path(path).suffix.lower() == ".png":
        return {"pil_kwargs": {"compress_level": PNG_COMPRESS_LEVEL}}
    return {}


def _mpl_version() -> str:
    import matplotlib

    return matplotlib.__version__


def png_bytes(rgba, software: str = "") -> bytes:
    """A PNG file of an 8-bit RGBA image ``(height, width, 4)``, as bytes.

    Colour type 2 (RGB) where every alpha is 255, else 6 (RGBA); every row unfiltered
    (filter type 0), the image data in one zlib stream at :data:`PNG_COMPRESS_LEVEL`,
    a ``Software`` text chunk if given.
    """
    import struct
    import zlib

    import numpy as np

    rgba = np.asarray(rgba, dtype=np.uint8)
    height, width = rgba.shape[:2]
    pixels, colour = (rgba[..., :3], 2) if bool(np.all(rgba[..., 3] == 255)) else (rgba, 6)
    rows = np.zeros((height, 1 + width * pixels.shape[2]), dtype=np.uint8)
    rows[:, 1:] = pixels.reshape(height, -1)

    def chunk(kind: bytes, data: bytes) -> bytes:
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    head = struct.pack(">IIBBBBB", width, height, 8, colour, 0, 0, 0)
    text = chunk(b"tEXt", b"Software\0" + software.encode("latin-1")) if software else b""
    return b"".join([
        b"\x89PNG\r\n\x1a\n", chunk(b"IHDR", head), text,
        chunk(b"IDAT", zlib.compress(rows.data, PNG_COMPRESS_LEVEL)), chunk(b"IEND", b""),
    ])  # fmt: skip


def _laid_out(fig) -> None:
    """Forget the inert layout engine ``tight_layout`` leaves behind.

    matplotlib keeps a placeholder engine after ``fig.tight_layout()``, and
    ``savefig`` then draws the whole figure once more before drawing it for the file
    (about a third of a figure's time); the placeholder lays nothing out, so the file
    is the same without it.
    """
    import matplotlib
    from matplotlib.layout_engine import PlaceHolderLayoutEngine

    if isinstance(fig.get_layout_engine(), PlaceHolderLayoutEngine) and not (
        matplotlib.rcParams["figure.autolayout"]
        or matplotlib.rcParams["figure.constrained_layout.use"]
    ):
        fig.set_layout_engine(None)


#: matplotlib settings of the figures of ``rotorkin run`` (set by the command line):
#: drawn at the resolution they are written at, so their text is laid out once, and
#: the titles of 2D axes at their top edge (no run figure puts tick labels on top), so
#: matplotlib need not measure the axes to place them; :func:`axes3d` keeps the
#: automatic place for 3D axes, whose box the title would overlap.
RUN_STYLE = {"figure.dpi": DPI, "axes.titley": 1.0}


def axes3d(fig, *args, title: str = "", **kwargs):
    """``fig.add_subplot(*args, projection="3d", **kwargs)`` with ``title`` placed by matplotlib.

    matplotlib moves the title of a 3D axes above its box, whatever ``axes.titley``.
    """
    import matplotlib

    with matplotlib.rc_context({"axes.titley": None}):
        ax = fig.add_subplot(*args, projection="3d", **kwargs)
        if title:
            ax.set_title(title)
    return ax


def fixed_layout(fig, left, bottom, right, top, wspace=0.0, hspace=0.0) -> None:
    """Place ``fig``'s grid of subplots with constant margins and gaps [inch].

    The layout of a run's figures is known: their text is the same from one design to
    the next but for the numbers of the tick labels. Margins given in inches (the
    space the labels take, measured once with ``tight_layout`` and some room to spare)
    place them without measuring every label at each draw, which takes about a third
    of a figure's time.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        Its axes on one grid (``plt.subplots``, ``fig.add_subplot(rows, cols, k)``).
    left, bottom, right, top : float
        Space from the figure's edges to the grid [inch].
    wspace, hspace : float
        Space between neighbouring columns and rows [inch].
    """
    width, height = fig.get_size_inches()
    rows, cols = 1, 1
    for ax in fig.axes:
        spec = ax.get_subplotspec()
        if spec is not None:
            rows, cols = spec.get_gridspec().get_geometry()
            break
    inner_w = width - left - right
    inner_h = height - bottom - top
    cell_w = (inner_w - (cols - 1) * wspace) / cols
    cell_h = (inner_h - (rows - 1) * hspace) / rows
    fig.subplots_adjust(
        left=left / width,
        right=1.0 - right / width,
        bottom=bottom / height,
        top=1.0 - top / height,
        wspace=wspace / cell_w if cols > 1 else None,
        hspace=hspace / cell_h if rows > 1 else None,
    )


def save(fig, path: Path, dpi: int = DPI, rect=None, layout=None) -> Path:
    """Lay out, write and close ``fig``.

    ``layout``: margins and gaps for :func:`fixed_layout` [inch], ``(left, bottom,
    right, top[, wspace[, hspace]])``; without it ``tight_layout`` (within ``rect`` of
    the figure, when given).
    """
    if layout is not None:
        fixed_layout(fig, *layout)
    elif rect is None:
        fig.tight_layout()
    else:
        fig.tight_layout(rect=rect)
    _laid_out(fig)
    _write(fig, path, dpi)
    _done(fig, path)
    return Path(path)


@dataclass(frozen=True)
class Recipe:
    """A sweep behind one or more of a paper's figures.

    ``sets`` are ``--set`` overrides of the config, ``vary`` the ``--vary`` items,
    ``figures`` the PNG names drawn from its dataset, ``note`` what the recipe
    changes in the config and why, ``metrics`` the summary keys it needs and
    ``plot(ds, outdir, recipe, cfg) -> list[Path]`` draws the figures from the
    sweep's dataset and its validated base config.
    """

    key: str
    sets: tuple
    vary: tuple
    curves: bool
    figures: tuple
    note: str = ""
    metrics: tuple = field(default=())
    plot: Callable | None = field(default=None, compare=False, repr=False)


#: Line styles of a baseline design and a synthesized one drawn side by side.
BASELINE = {"color": "0.45", "lw": 1.6, "label": "baseline (paper)"}
SYNTHESIZED = {"color": "C3", "lw": 1.8, "label": "synthesized"}


def save_in(fig, outdir, name: str, dpi: int = DPI) -> Path:
    """Write and close ``fig`` as ``outdir/name`` (its layout as it is); return the path."""
    path = Path(outdir) / name
    _laid_out(fig)
    _write(fig, path, dpi)
    _done(fig, path)
    return path


#: Environment variable giving the number of processes that draw a run's figures.
WORKERS_ENV = "ROTORKIN_FIGURE_WORKERS"

#: Most processes drawing figures by default (a run has about ten figures).
MAX_WORKERS = 4

#: True in a process forked by :func:`draw` (its own figures are drawn serially).
_IN_WORKER = False


class FigureError(Exception):
    """A figure task that failed in a worker, when its exception cannot travel as it is."""


def figure_workers(workers: int | None = None) -> int:
    """Processes that draw figures: ``workers``, else ``$ROTORKIN_FIGURE_WORKERS``, else cores.

    Cores are those this process may run on, at most :data:`MAX_WORKERS`; 1 where
    ``fork`` is unavailable, inside a worker, while :func:`recording` and where threads
    other than rotorkin's own run.

    Raises
    ------
    rotorkin.core.errors.ParameterError
        ``$ROTORKIN_FIGURE_WORKERS`` is not an integer >= 1.
    """
    if workers is None:
        text = os.environ.get(WORKERS_ENV, "").strip()
        if text:
            try:
                workers = int(text)
            except ValueError:
                workers = 0
            if workers < 1:
                from rotorkin.core.errors import ParameterError

                raise ParameterError(WORKERS_ENV, repr(text), "an integer >= 1 (processes)")
        else:
            try:
                cores = len(os.sched_getaffinity(0))
            except AttributeError:  # pragma: no cover - no affinity on this system
                cores = os.cpu_count() or 1
            workers = min(cores, MAX_WORKERS)
    if not hasattr(os, "fork") or _IN_WORKER or _RECORDED is not None or not forked.fork_safe():
        return 1
    return max(1, int(workers))


def _flat(done) -> list[Path]:
    """A task's return value (a path, a list of paths or None) as a list of paths."""
    if done is None:
        return []
    if isinstance(done, (str, os.PathLike)):
        return [Path(done)]
    return [Path(p) for p in done]


def draw(
    tasks: Sequence[Callable], workers: int | None = None, slowest: Sequence[int] = ()
) -> list[Path]:
    """Run figure tasks; the paths they wrote, in the order of ``tasks``.

    Parameters
    ----------
    tasks : sequence of callable
        Each ``task()`` draws and writes one or more figures and returns the path (or
        list of paths) written; tasks are independent of each other.
    workers : int, optional
        Processes drawing (:func:`figure_workers`); 1 draws in this process, in order.
    slowest : sequence of int
        Indices of the tasks that take longest, handed out first by more than one
        worker (so that no worker starts a long one when the others are done).

    Notes
    -----
    With more than one worker this process forks ``workers - 1`` children and draws
    too; each process takes the next task not yet taken (figures differ in cost), so
    the tasks need not be picklable: the children inherit them. A task that fails
    fails the whole call with its exception (rebuilt here, or :class:`FigureError`
    with its one-line message), after every child has ended; the files already
    written are left to the caller's staging folder. A SIGTERM ends the children.
    """
    return draw_soon(tasks, workers, slowest).paths()


class Drawing:
    """Figure tasks being drawn (:func:`draw_soon`); :meth:`paths` waits for them."""

    def __init__(self, tasks: list, workers, slowest, helper: _Helper | None):
        self.tasks, self.workers, self.slowest = tasks, workers, tuple(slowest)
        self._helper = helper

    def paths(self) -> list[Path]:
        """The paths written, in the order of the tasks (as :func:`draw` returns them).

        Call it once. A drawing whose process ended with its :func:`drawing_ahead` block
        is drawn here.
        """
        helper, self._helper = self._helper, None
        if helper is not None and helper in _HANDED:
            _HANDED.remove(helper)
            done = _collect(helper)
            if done is not None:
                return done
        return _draw_here(self.tasks, self.workers, self.slowest)


def draw_soon(
    tasks: Sequence[Callable], workers: int | None = None, slowest: Sequence[int] = ()
) -> Drawing:
    """:func:`draw`, returning at once where :func:`drawing_ahead`'s process draws them.

    The caller goes on with other work (writing its data files) while that process
    draws, then calls :meth:`Drawing.paths`. Without that process the tasks are drawn
    when :meth:`Drawing.paths` is called. A drawing not waited for when the
    :func:`drawing_ahead` block ends is ended with it (SIGTERM).
    """
    global _HELPER
    tasks = list(tasks)
    helper, _HELPER = _HELPER, None
    if helper is not None:
        # figures recorded, or asked for in this process (one worker): not drawn there
        if tasks and _RECORDED is None and (workers is None or workers > 1):
            _send(helper, tasks, workers, slowest)
            _HANDED.append(helper)
            return Drawing(tasks, workers, slowest, helper)
        _end_helper(helper, kill=True)
    return Drawing(tasks, workers, slowest, None)


def _draw_here(tasks: list, workers: int | None, slowest: Sequence[int]) -> list[Path]:
    """:func:`draw` in this process (and the workers it forks)."""
    _apply_style()
    workers = min(figure_workers(workers), len(tasks))
    # the objects that exist now (the study's, the libraries') are left out of the garbage
    # collector's passes while drawing: the passes take less time, and a forked worker does
    # not copy every page they would touch (that doubled its start-up)
    gc.freeze()
    try:
        if workers <= 1 or len(tasks) > 255:
            return [p for task in tasks for p in _flat(task())]
        return _draw_forked(tasks, workers, slowest)
    finally:
        gc.unfreeze()


def _draw_forked(tasks: list, workers: int, slowest: Sequence[int]) -> list[Path]:
    """:func:`draw` with ``workers - 1`` forked children besides this process."""
    pyplot()  # imported once, before the fork, for every worker
    forked.flush_streams()  # a child would write their buffers once more
    queue_r, queue_w = os.pipe()
    first = [i for i in dict.fromkeys(slowest) if 0 <= i < len(tasks)]
    order = first + [i for i in range(len(tasks)) if i not in first]
    os.write(queue_w, bytes(order))  # one byte per task: the next one to take
    os.close(queue_w)
    children = []
    try:
        for _ in range(workers - 1):
            out_r, out_w = os.pipe()
            pid = forked.fork()
            if pid == 0:  # pragma: no cover - runs in the child (its coverage is not collected)
                os.close(out_r)
                _child(tasks, queue_r, out_w)
            os.close(out_w)
            children.append((pid, out_r))
        done: dict[int, list[Path]] = dict(_take(tasks, queue_r))
        failure = None
        while children:
            pid, out_r = children[0]
            data = forked.read_all(out_r)
            os.close(out_r)
            children[0] = (pid, None)
            _, status = os.waitpid(pid, 0)
            children.pop(0)
            kind, payload = _result(data, status)
            if kind == "ok":
                done.update(payload)
            elif failure is None:
                failure = payload
        if failure is not None:
            raise _rebuilt(failure)
        return [p for i in range(len(tasks)) for p in done.get(i, [])]
    finally:
        os.close(queue_r)
        for pid, out_r in children:  # an error or a signal here: end the children
            with contextlib.suppress(OSError):
                os.kill(pid, signal.SIGTERM)
            if out_r is not None:
                os.close(out_r)
            with contextlib.suppress(OSError):
                os.waitpid(pid, 0)


def _take(tasks, queue_r) -> list[tuple[int, list[Path]]]:
    """Draw the tasks this process takes from the queue until it is empty."""
    out = []
    while True:
        token = os.read(queue_r, 1)
        if not token:
            return out
        i = token[0]
        out.append((i, _flat(tasks[i]())))


def _child(tasks, queue_r, out_w) -> None:  # pragma: no cover - runs in a forked child
    """A forked worker: draw tasks from the queue, send back the paths or the error, exit."""
    global _IN_WORKER
    _IN_WORKER = True
    try:
        forked.take_signals()
        result, code = ("ok", _take(tasks, queue_r)), 0
    except BaseException as exc:  # noqa: BLE001 - everything goes back to the parent
        try:
            result, code = ("error", forked.portable(exc)), 1
        except BaseException:  # noqa: BLE001 - a child never returns into the caller's code
            result, code = None, 1
    forked.send_and_end(out_w, result, code)


def _rebuilt(failure) -> BaseException:
    """The exception a worker sent back (:func:`rotorkin.core.forked.portable`)."""
    failure = forked.rebuilt(failure)
    if isinstance(failure, BaseException):
        return failure
    name, message = failure
    return FigureError(f"a figure could not be drawn: {name}: {message}")


def _result(data: bytes, status: int):
    """A child's result: ``("ok", [(i, paths)])`` or ``("error", exception or text)``."""
    try:
        return pickle.loads(data)
    except Exception:  # noqa: BLE001 - a child that died without a result
        code = os.waitstatus_to_exitcode(status)
        return ("error", ("FigureError", f"the process drawing figures ended with code {code}"))


def plain_log_labels(ax, axes: str = "xy") -> None:
    """Label the log-scaled ``axes`` ("x", "y" or "xy") of ``ax`` in plain numbers.

    matplotlib labels log axes with mathtext (``$10^{1}$``, ``$2\\times10^{1}$``), whose
    parser costs a figure 0.1-0.2 s to build; these labels read ``10``, ``20``, ``1e-16``,
    on the ticks matplotlib's own formatter labels (call after ``set_xscale("log")``).
    """
    from matplotlib.ticker import Formatter

    class PlainLog(Formatter):
        def __init__(self, inner):
            self.inner = inner

        def set_axis(self, axis):
            super().set_axis(axis)
            self.inner.set_axis(axis)

        def set_locs(self, locs):
            super().set_locs(locs)
            self.inner.set_locs(locs)

        def __call__(self, x, pos=None):
            return f"{x:g}" if self.inner(x, pos) else ""

    for name in axes:
        axis = ax.xaxis if name == "x" else ax.yaxis
        if axis.get_scale() != "log":
            continue
        axis.set_major_formatter(PlainLog(axis.get_major_formatter()))
        axis.set_minor_formatter(PlainLog(axis.get_minor_formatter()))


def degree_axis(ax, end: float, step: float, label: str | None) -> None:
    """An x axis of angles from 0 to ``end`` [deg] with ticks every ``step``, and a grid."""
    import numpy as np

    ax.set_xlim(0.0, end)
    ax.set_xticks(np.arange(0.0, end + 1e-9, step))
    if label:
        ax.set_xlabel(label)
    ax.grid(True, alpha=0.4)
