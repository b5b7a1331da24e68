"""``rotorkin run`` imports only the drive it runs; figures drawn in parallel match serial."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from rotorkin import drives

SRC = str(Path(__file__).resolve().parents[1] / "src")


def _python(code: str, **env) -> subprocess.CompletedProcess:
    """Run ``code`` in a fresh interpreter with this checkout first on the path."""
    environ = {**os.environ, "PYTHONPATH": SRC + os.pathsep + os.environ.get("PYTHONPATH", ""),
               "MPLBACKEND": "Agg", **env}  # fmt: skip
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=environ, timeout=300)  # fmt: skip


def _drive_packages(modules) -> set[str]:
    """The drive packages among imported module names."""
    parts = [m.split(".") for m in modules if m.startswith("rotorkin.drives.")]
    return {p[2] for p in parts if not p[2].startswith("_")}


def test_listing_drives_and_examples_imports_none():
    done = _python(
        "import json, sys\n"
        "from rotorkin import drives\n"
        "from rotorkin.io.config import example_names\n"
        "names, examples = drives.names(), example_names()\n"
        "print(json.dumps([names, examples, 'wobble_cam' in drives.REGISTRY, list(sys.modules)]))\n"
    )
    assert done.returncode == 0, done.stderr
    names, examples, contained, modules = json.loads(done.stdout)
    assert names == list(drives.BUILTIN)
    assert contained
    assert _drive_packages(modules) == set()
    # nor the machines, studies and units behind the drives (pint, scipy)
    assert not {"rotorkin.vane", "rotorkin.studies.limits", "pint", "scipy"} & set(modules)
    # the same examples as the specs list once every drive is imported
    assert examples == sorted(e for s in drives.REGISTRY.values() for e in s.examples)


@pytest.mark.parametrize("kind", list(drives.BUILTIN))
def test_run_imports_only_the_running_drive_and_no_costly_library(kind, tmp_path):
    example = drives.REGISTRY[kind].examples[0]
    done = _python(
        "import json, sys\n"
        "from rotorkin.cli import main\n"
        f"code = main(['run', '-e', {example!r}, '-o', {str(tmp_path / 'out')!r}, '-q', "
        "'--no-figures'])\n"
        "print(json.dumps([code, list(sys.modules)]))\n"
    )
    assert done.returncode == 0, done.stderr
    code, modules = json.loads(done.stdout.splitlines()[-1])
    assert code == 0
    assert _drive_packages(modules) == {kind}
    assert (tmp_path / "out" / "summary.json").is_file()
    # what one design does not need (0.1-0.5 s each to import): the units of its config
    # from the table, no optimiser, no compiled loops for one study's evaluations, no
    # k-d tree (the spherical cam's groove searches run on a grid in numpy)
    costly = ("pint", "numba", "scipy.optimize", "scipy.spatial", "dask", "xarray")
    assert [m for m in costly if m in modules] == []


def test_registry_keeps_order_and_loads_on_access():
    registry = drives.Registry(("tabulated", "wobble_cam"))
    assert list(registry) == ["tabulated", "wobble_cam"] and len(registry) == 2
    spec = registry["tabulated"]
    assert spec.name == "tabulated" and registry.loaded("tabulated")
    assert registry.package("tabulated") is None
    assert registry.package("nothing") is None
    del registry["wobble_cam"]
    assert list(registry) == ["tabulated"]
    with pytest.raises(KeyError):
        registry["wobble_cam"]


def test_drive_package_as_attribute():
    assert drives.tabulated.SPEC is drives.REGISTRY["tabulated"]
    with pytest.raises(AttributeError):
        drives.no_such_drive  # noqa: B018


# --- figures drawn by several processes ------------------------------------------------------
def _square_figure(outdir: Path, name: str, size: tuple, value: float) -> Path:
    """A small figure whose content depends on ``value`` (what the parent can check)."""
    from rotorkin.render.figures import pyplot, save

    fig, ax = pyplot().subplots(figsize=size)
    ax.plot([0.0, 1.0], [0.0, value])
    return save(fig, outdir / name, layout=(0.6, 0.5, 0.2, 0.3))


def _tasks(outdir: Path) -> list:
    import functools

    return [functools.partial(_square_figure, outdir, f"f{i}.png", (2 + i % 3, 2), float(i))
            for i in range(7)]  # fmt: skip


def _png_size(path: Path) -> tuple[int, int]:
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")


@pytest.fixture
def forking(monkeypatch):
    """Fork even if an earlier test left threads running in this process (the tasks here
    take no lock those threads could hold)."""
    from rotorkin.core import forked

    monkeypatch.setattr(forked, "fork_safe", lambda: True)


def test_parallel_draw_writes_the_files_of_the_serial_one(tmp_path, forking):
    from rotorkin.render.figures import draw

    serial, parallel = tmp_path / "serial", tmp_path / "parallel"
    serial.mkdir()
    parallel.mkdir()
    one = draw(_tasks(serial), workers=1)
    two = draw(_tasks(parallel), workers=3, slowest=(6, 6, 99))
    assert [p.name for p in one] == [p.name for p in two] == [f"f{i}.png" for i in range(7)]
    assert all(p.parent == parallel for p in two)
    for a, b in zip(one, two, strict=True):
        # 2..4 inches wide, 2 high, at 120 dpi
        assert _png_size(a) == _png_size(b) == (120 * (2 + int(a.stem[1:]) % 3), 240)
        assert a.read_bytes() == b.read_bytes()


class _Odd(Exception):
    """An exception that cannot be rebuilt from its arguments (pickling fails)."""

    def __init__(self, a, b):
        super().__init__(f"{a}/{b}")


def _fails_in_child(parent: int, how: str):
    from rotorkin.core.errors import ParameterError

    if os.getpid() == parent:
        import time

        time.sleep(0.5)  # the child takes the failing task first
        return []
    if how == "parameter":
        raise ParameterError("cam.roller_radius", "9 mm", "roller_radius <= 5 mm")
    if how == "odd":
        raise _Odd(1, 2)
    if how == "local":

        class Local(Exception):
            pass

        raise Local("nowhere to rebuild it")
    os._exit(3)


@pytest.mark.parametrize(
    ("how", "kind", "text"),
    [
        ("parameter", "ParameterError", "cam.roller_radius = 9 mm is not admissible"),
        ("odd", "_Odd", "1/2"),
        ("local", "FigureError", "a figure could not be drawn: Local: nowhere to rebuild it"),
        ("exit", "FigureError", "ended with code 3"),
    ],
)
def test_a_failure_in_a_worker_is_raised_in_the_caller(how, kind, text, forking):
    import functools

    from rotorkin.render.figures import draw

    task = functools.partial(_fails_in_child, os.getpid(), how)
    with pytest.raises(Exception) as info:  # noqa: PT011 - the class is checked below
        draw([task, task, task], workers=2)
    assert type(info.value).__name__ == kind
    assert text in str(info.value)
    if how == "parameter":  # rebuilt with what the command line reads
        assert info.value.name == "cam.roller_radius"
        assert info.value.admissible == "roller_radius <= 5 mm"
    assert "\n" not in str(info.value)


def test_workers_from_the_environment(monkeypatch, forking):
    from rotorkin.core.errors import ParameterError
    from rotorkin.render.figures import WORKERS_ENV, figure_workers, recording

    monkeypatch.setenv(WORKERS_ENV, "1")
    assert figure_workers() == 1
    monkeypatch.setenv(WORKERS_ENV, "3")
    assert figure_workers() == 3
    with recording():  # the recorded figures must stay in this process
        assert figure_workers() == 1
    for bad in ("0", "two", "-1"):
        monkeypatch.setenv(WORKERS_ENV, bad)
        with pytest.raises(ParameterError, match=WORKERS_ENV):
            figure_workers()


def _run_cli(tmp_path, example: str, workers: str, prelude: str = ""):
    out = tmp_path / f"out-{workers}"
    code = (
        "import sys\n" + prelude + "from rotorkin.cli import main\n"
        f"sys.exit(main(['run', '-e', {example!r}, '-o', {str(out)!r}, '-q']))\n"
    )
    return out, _python(code, ROTORKIN_FIGURE_WORKERS=workers)


def test_run_draws_the_same_figures_in_one_process_or_two(tmp_path):
    outs = {}
    for workers in ("1", "2"):
        out, done = _run_cli(tmp_path, "eccentric-reactor", workers)
        assert done.returncode == 0, done.stderr
        outs[workers] = out
    names = sorted(p.name for p in outs["1"].glob("*.png"))
    assert len(names) >= 8
    assert names == sorted(p.name for p in outs["2"].glob("*.png"))
    for name in names:
        assert _png_size(outs["1"] / name) == _png_size(outs["2"] / name)
        assert (outs["1"] / name).read_bytes() == (outs["2"] / name).read_bytes()
    assert (outs["1"] / "README.txt").read_text() == (outs["2"] / "README.txt").read_text()


def test_run_with_a_failing_figure_worker_writes_nothing(tmp_path):
    prelude = (
        "import os\n"
        "from rotorkin.core.errors import ParameterError\n"
        "from rotorkin.drives.eccentric_cam import figures\n"
        "PARENT = os.getpid()\n"
        "def fail(*args, **kwargs):\n"
        "    if os.getpid() != PARENT:\n"
        "        raise ParameterError('run.points', '7', 'points >= 9')\n"
        "    import time; time.sleep(1.0)\n"
        "figures.fig_pistons = fail\n"
        "figures.fig_decomposition = fail\n"
    )
    out, done = _run_cli(tmp_path, "eccentric-reactor", "2", prelude)
    assert done.returncode == 2, done.stderr
    lines = done.stderr.strip().splitlines()
    assert lines == ["rotorkin: error: run.points = 7 is not admissible: points >= 9"]
    assert not out.exists()
    assert [p.name for p in tmp_path.iterdir()] == []  # no staging folder left either


def test_a_worker_does_not_repeat_what_the_caller_had_not_yet_written():
    done = _python(
        "import sys\n"
        "from rotorkin.render.figures import draw\n"
        "print('before the figures')\n"  # stdout is a pipe: held in the buffer
        "draw([lambda: None] * 4, workers=2)\n"
        "print('after the figures')\n",
        PYTHONUNBUFFERED="",  # buffered, as when a user pipes the output
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["before the figures", "after the figures"]


def test_no_fork_while_another_thread_runs():
    import threading

    from rotorkin.render.figures import figure_workers

    stop = threading.Event()
    for name, expected in (("someone-else", 1), ("rotorkin_0", 2)):
        thread = threading.Thread(target=stop.wait, name=name)
        thread.start()
        try:
            # rotorkin's own pool threads (left idle by earlier tests) do not count
            others = [t for t in threading.enumerate()
                      if t is not threading.main_thread() and t is not thread
                      and not t.name.startswith("rotorkin")]  # fmt: skip
            if not others:  # only then is the answer the thread's alone
                assert figure_workers(2) == expected
            else:
                assert figure_workers(2) == 1
        finally:
            stop.set()
            thread.join()
            stop.clear()


def test_log_axes_in_plain_numbers_on_the_ticks_matplotlib_labels():
    """plain_log_labels: the same labelled ticks as matplotlib's own formatter, written
    as plain numbers (no mathtext to parse)."""
    import numpy as np

    from rotorkin.render.figures import plain_log_labels, pyplot

    plt = pyplot()
    labels = []
    for plain in (False, True):
        fig, ax = plt.subplots()
        ax.plot(np.linspace(7.0, 72.0, 50), np.geomspace(1.0, 57.0, 50))
        ax.set_xscale("log")
        ax.set_yscale("log")
        if plain:
            plain_log_labels(ax)
        fig.canvas.draw()
        labels.append([[(t.get_position(), t.get_text()) for t in
                         (*axis.get_majorticklabels(), *axis.get_minorticklabels())]
                        for axis in (ax.xaxis, ax.yaxis)])  # fmt: skip
        plt.close(fig)
    mathtext, plain = labels
    for before, after in zip(mathtext, plain, strict=True):
        shown = [(pos, text) for pos, text in after if text]
        assert [pos for pos, _ in shown] == [pos for pos, text in before if text]
        assert shown and all("$" not in text for _, text in shown)
        for pos, text in shown:
            value = max(pos)  # (x, 0) or (0, y)
            assert float(text) == pytest.approx(value, rel=1e-5)
    assert {text for _, text in plain[0] if text} >= {"10", "20"}


_AHEAD_SCRIPT = """
import functools, json, os, sys, time
from pathlib import Path
from rotorkin.render import figures

def square(outdir, name, value):
    fig, ax = figures.pyplot().subplots(figsize=(2.5, 2))
    ax.plot([0.0, 1.0], [0.0, value])
    return figures.save(fig, Path(outdir) / name, layout=(0.6, 0.5, 0.2, 0.3))

def gated(outdir, name):  # drawn once the caller has gone on (it makes the file "go")
    for _ in range(3000):
        if (Path(outdir) / "go").exists():
            return square(outdir, name, 1.0)
        time.sleep(0.01)
    raise RuntimeError("the caller waited for the drawing")

def tasks(outdir, local=False):
    if local:  # a closure over a local: cannot travel by pickle
        return [lambda i=i: square(outdir, f"f{i}.png", float(i)) for i in range(5)]
    return [functools.partial(square, outdir, f"f{i}.png", float(i)) for i in range(5)]

style = {"lines.linewidth": 4.0}
out = {}
cases = (("ahead", False, "2", style), ("plain", False, "1", None),  # before any style here
         ("direct", False, "2", style), ("local", True, "2", style),
         ("serial", False, "1", style))
for name, local, workers, rc in cases:
    os.environ[figures.WORKERS_ENV] = workers
    d = Path(name)
    d.mkdir()
    with figures.drawing_ahead(rc):
        helper = figures._HELPER is not None
        if name == "direct":  # drawn here without draw (the block's style all the same)
            paths = [task() for task in tasks(d)]
        else:
            paths = figures.draw(tasks(d, local))
    out[name] = {"helper": helper, "paths": [p.name for p in paths],
                 "pyplot_here": "matplotlib.pyplot" in sys.modules}
    try:
        os.waitpid(-1, os.WNOHANG)
        out[name]["children_left"] = True
    except ChildProcessError:
        out[name]["children_left"] = False
os.environ[figures.WORKERS_ENV] = "2"
with figures.drawing_ahead(style), figures.recording() as record:  # kept in this process
    figures.draw(tasks(Path("ahead")))
out["recorded"] = len(record)
with figures.drawing_ahead(style):  # a block without a draw ends its process
    pid = figures._HELPER.pid if figures._HELPER else None
try:
    os.waitpid(-1, os.WNOHANG)
    out["unused_left"] = True
except ChildProcessError:
    out["unused_left"] = False
out["unused_pid"] = pid
d = Path("soon")
d.mkdir()
with figures.drawing_ahead(style):  # the caller goes on while the drawing process draws
    drawing = figures.draw_soon([functools.partial(gated, d, "g.png"), *tasks(d)])
    (d / "go").touch()
    out["soon"] = [p.name for p in drawing.paths()]
d = Path("abandoned")
d.mkdir()
try:
    with figures.drawing_ahead(style):  # an error before the wait: the drawing ends too
        drawing = figures.draw_soon([functools.partial(gated, d, "g.png")])
        raise KeyError("between")
except KeyError:
    pass
try:
    os.waitpid(-1, os.WNOHANG)
    out["abandoned_left"] = True
except ChildProcessError:
    out["abandoned_left"] = False
print(json.dumps(out))
"""


def test_figures_drawn_ahead_are_the_files_drawn_here(tmp_path):
    """Inside drawing_ahead the process forked before the work draws the tasks: this
    process never imports pyplot, the files are those one process draws with the block's
    style; tasks that do not pickle are drawn here; draw_soon returns while they are
    drawn; no process is left behind, even by a drawing nobody waited for."""
    done = subprocess.run([sys.executable, "-c", _AHEAD_SCRIPT], capture_output=True,
                          text=True, cwd=tmp_path, timeout=300,
                          env={**os.environ, "PYTHONPATH": SRC, "MPLBACKEND": "Agg"})  # fmt: skip
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout.splitlines()[-1])
    names = [f"f{i}.png" for i in range(5)]
    assert out["ahead"] == {"helper": True, "paths": names, "pyplot_here": False,
                            "children_left": False}  # fmt: skip
    assert out["local"]["helper"] and out["local"]["pyplot_here"]  # drawn here
    assert out["serial"]["helper"] is False and out["serial"]["paths"] == names
    assert out["unused_pid"] is not None and out["unused_left"] is False
    assert out["recorded"] == 5
    assert out["soon"] == ["g.png", *names]
    assert out["abandoned_left"] is False
    assert not (tmp_path / "abandoned" / "g.png").exists()
    for name in names:
        ahead = (tmp_path / "ahead" / name).read_bytes()
        assert ahead == (tmp_path / "serial" / name).read_bytes()
        assert ahead == (tmp_path / "local" / name).read_bytes()
        assert ahead == (tmp_path / "direct" / name).read_bytes()
        # the style reached the drawing process (without it, another picture)
        assert ahead != (tmp_path / "plain" / name).read_bytes()
