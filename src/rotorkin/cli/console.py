"""What the commands print and where: consoles, ``--quiet`` / ``--verbose``, progress.

* :func:`out_console` prints tables on stdout. On a terminal they fit its width;
  into a pipe or a file they are never cut or wrapped (a wide console), so that
  no digit is lost to an ellipsis.
* :func:`stages` shows a spinner with the running step and its elapsed time on
  stderr while a command works (only on a terminal, never with ``--quiet``);
  with ``--verbose`` each finished step is written to stderr with its time.
* ``--quiet`` and ``--verbose`` are options of every command; their callbacks
  record them here (:data:`STATE`), reset by :func:`rotorkin.cli.main` at each call.
"""

from __future__ import annotations

import contextlib
import sys
import time

import typer

__all__ = ["one_line", "require", "STATE", "reset", "quiet_callback", "verbose_callback",
           "out_console", "err_console", "stdout_is_terminal", "stages", "note"]  # fmt: skip

#: Characters that end a line for Python's ``str.splitlines`` (and for terminals).
_LINE_BREAKS = "\n\r\x0b\x0c\x1c\x1d\x1e\x85\u2028\u2029"


def one_line(text: str) -> str:
    """A message on one line: line breaks a user typed are shown escaped (``\\n``)."""
    return "".join(c.encode("unicode_escape").decode() if c in _LINE_BREAKS else c for c in text)


def require(*modules: str) -> None:
    """Stop before any work when an optional module is not installed.

    Raises the ``ModuleNotFoundError`` that :func:`rotorkin.cli.main` turns into one
    line naming the extra to install (exit 2).
    """
    import importlib.util

    for module in modules:
        if importlib.util.find_spec(module) is None:
            raise ModuleNotFoundError(f"No module named {module!r}", name=module)


#: Width of the console when stdout is not a terminal: no table is cut or wrapped.
WIDE = 100_000


class _State:
    """``--quiet`` / ``--verbose`` of the running command."""

    quiet: bool = False
    verbose: bool = False


#: The running command's verbosity.
STATE = _State()


def reset() -> None:
    """Forget the flags of a previous command (one process may run several)."""
    STATE.quiet = STATE.verbose = False


def quiet_callback(value: bool) -> bool:
    """``--quiet``: record it; refuse it beside ``--verbose``."""
    if value:
        if STATE.verbose:
            raise typer.BadParameter("give either --quiet or --verbose, not both")
        STATE.quiet = True
    return value


def verbose_callback(value: bool) -> bool:
    """``--verbose``: record it; refuse it beside ``--quiet``."""
    if value:
        if STATE.quiet:
            raise typer.BadParameter("give either --quiet or --verbose, not both")
        STATE.verbose = True
    return value


def stdout_is_terminal() -> bool:
    """True when stdout is a terminal (then tables fit its width and show 6 digits)."""
    try:
        return sys.stdout.isatty()
    except (AttributeError, ValueError):  # closed or replaced by an object without it
        return False


def out_console():
    """A rich console on stdout: the terminal's width, or never cut when not a terminal."""
    from rich.console import Console

    if stdout_is_terminal():
        return Console(markup=False, highlight=False)
    return Console(markup=False, highlight=False, width=WIDE, no_color=True)


def err_console():
    """A rich console on stderr (progress bars and spinners)."""
    from rich.console import Console

    return Console(stderr=True, markup=False, highlight=False)


def note(message: str) -> None:
    """A line on stderr with ``--verbose`` (what was done, how long it took)."""
    if STATE.verbose:
        print(f"rotorkin: {message}", file=sys.stderr, flush=True)


class _Steps:
    """Callable ``step(label)``: the previous step ends, ``label`` begins."""

    def __init__(self, bar):
        self.bar = bar
        self.task = None
        self.label = None
        self.t0 = self.t_step = time.perf_counter()

    def __call__(self, label: str) -> None:
        self._end()
        self.label, self.t_step = label, time.perf_counter()
        if self.bar is not None:
            if self.task is None:
                self.task = self.bar.add_task(label, total=None)
            else:
                self.bar.update(self.task, description=label)

    def _end(self) -> None:
        if self.label is not None:
            note(f"{self.label}: {time.perf_counter() - self.t_step:.2f} s")
            self.label = None


@contextlib.contextmanager
def stages(command: str):
    """Steps of a command that may take more than a second, shown while they run.

    Yields ``step(label)``; call it as each step begins. On a terminal (and not
    ``--quiet``) stderr shows a spinner, the step and the elapsed time, cleared
    at the end; with ``--verbose`` every finished step and the total are written
    to stderr with their times.
    """
    bar = None
    if not STATE.quiet:
        console = err_console()
        if console.is_terminal:
            from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

            bar = Progress(SpinnerColumn(), TextColumn("{task.description}"),
                           TimeElapsedColumn(), console=console, transient=True)  # fmt: skip
    from rotorkin.cli.lazy import running

    loaded, running.load_seconds = running.load_seconds, 0.0
    if loaded:
        note(f"importing the library behind {running.command}: {loaded:.2f} s")
    steps = _Steps(bar)
    steps.t0 -= loaded  # "in all" counts the imports too
    if bar is not None:
        bar.start()
    try:
        yield steps
        steps._end()
        note(f"{command}: {time.perf_counter() - steps.t0:.2f} s in all")
    finally:
        if bar is not None:
            bar.stop()
