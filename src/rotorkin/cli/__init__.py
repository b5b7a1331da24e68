"""The ``rotorkin`` command: thin; parses, calls the library, prints, sets the exit code.

Exit codes: 0 success, 2 bad input (one line on stderr, no traceback, no
output files), 3 the machine failed us (disk full, no permission: one line saying
what to do, no output files), 1 an internal error (one line; ``ROTORKIN_DEBUG=1``
shows the traceback).
"""

from __future__ import annotations

import contextlib
import errno
import os
import signal
import sys
import threading
import warnings
from typing import Annotated

import typer

from rotorkin import __version__
from rotorkin.cli import console
from rotorkin.cli.console import one_line as _one_line
from rotorkin.cli.lazy import COMMANDS, LazyGroup, running
from rotorkin.core.errors import RotorkinError
from rotorkin.core.memory import tune_allocator

__all__ = ["app", "main", "console_main", "COMMANDS", "EXTRAS", "ENVIRONMENT_ERROR"]

app = typer.Typer(
    name="rotorkin",
    cls=LazyGroup,
    help="Design the drives of rotary variable-volume machines: kinematics, volumes, torques.",
    add_completion=True,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,
)


def _version(value: bool):
    if value:
        typer.echo(f"rotorkin {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[
        bool, typer.Option("--version", callback=_version, is_eager=True, help="Print the version.")
    ] = False,
):
    """rotorkin: exact kinematics, volumes and torques of the drives of rotary machines."""


#: The optional extra that provides a module (its top-level name) the core install lacks.
EXTRAS = {
    "plotly": "report",
    "ezdxf": "cad",
    "trimesh": "cad",
    "manifold3d": "cad",
    "build123d": "cad",
    "OCP": "cad",
    "dask": "dask",
    "distributed": "dask",
    "cantera": "thermo",
    "pymoo": "optimize",
    "numba": "fast",
    "xarray": "xarray",
    "pandas": "xarray",
}


def _missing_extra(exc: ModuleNotFoundError) -> str | None:
    """One line naming the extra (and its pip command) that provides the missing module."""
    module = (exc.name or "").split(".")[0]
    extra = EXTRAS.get(module)
    if extra is None:
        return None
    command = f"rotorkin {running.command}" if running.command else "this command"
    return (f'{command} needs the {extra} extra: pip install "rotorkin[{extra}]" '
            f"({module} is not installed)")  # fmt: skip


class Terminated(BaseException):
    """SIGTERM, raised where the program stands so that every ``finally`` cleans up."""


def _raise_terminated(signum, frame):
    raise Terminated


def _on_sigterm():
    """Turn SIGTERM into :class:`Terminated` (main thread only); the previous handler."""
    if threading.current_thread() is not threading.main_thread():
        return None
    return signal.signal(signal.SIGTERM, _raise_terminated)


#: Exit code of a failure of the machine rather than the input (disk full, no permission).
ENVIRONMENT_ERROR = 3

_WHAT_TO_DO = {
    errno.ENOSPC: "the disk is full: free some space or write elsewhere with --out",
    errno.EDQUOT: "the disk quota is used up: free some space or write elsewhere with --out",
    errno.EACCES: "permission denied: write elsewhere with --out, or fix the folder's permissions",
    errno.EPERM: "operation not permitted: write elsewhere with --out",
    errno.EROFS: "the file system is read-only: write elsewhere with --out",
    errno.ENOMEM: "out of memory: ask for fewer points, designs or samples",
}


def _environment_message(exc: OSError) -> str:
    """One line: what failed and what to do; nothing was left behind."""
    what = _WHAT_TO_DO.get(exc.errno, "the system refused; check the output folder and retry")
    where = f" ({exc.filename})" if getattr(exc, "filename", None) else ""
    return _one_line(f"cannot finish: {exc.strerror or exc}{where}; {what}; no output was written")


def main(argv: list[str] | None = None) -> int:
    """Entry point of the console script; returns the exit code."""
    # figures are files here: matplotlib draws off screen unless the user chose a backend
    os.environ.setdefault("MPLBACKEND", "Agg")
    tune_allocator()  # array temporaries from the heap, not fresh pages (rotorkin.core.memory)
    previous = _on_sigterm()
    args = sys.argv[1:] if argv is None else list(argv)
    if not args:
        args = ["--help"]
    console.reset()
    running.command, running.load_seconds = None, 0.0
    try:
        # numpy's floating-point warnings are not for the user (LazyGroup.invoke silences
        # numpy's own): every number that could be non-finite is checked before it is shown
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            app(args=args, prog_name="rotorkin", standalone_mode=False)
    except RotorkinError as exc:
        print(f"rotorkin: error: {_one_line(str(exc))}", file=sys.stderr)
        return 2
    except typer.Exit as exc:
        return exc.exit_code
    except typer.Abort:
        print("rotorkin: aborted", file=sys.stderr)
        return 130
    except Terminated:
        print(
            "rotorkin: terminated; no output was finished (a sweep keeps its committed "
            "chunks and resumes from them)",
            file=sys.stderr,
        )
        return 143
    except KeyboardInterrupt:
        print("rotorkin: interrupted; no output was finished", file=sys.stderr)
        return 130
    except BrokenPipeError:  # the reader of our output went away (e.g. "| head"): say nothing
        with contextlib.suppress(OSError):
            sys.stderr.close()
        return ENVIRONMENT_ERROR
    except ModuleNotFoundError as exc:  # an optional extra that is not installed: exit 2
        message = _missing_extra(exc)
        if message is None:
            return _internal_error(exc)
        print(f"rotorkin: error: {message}", file=sys.stderr)
        return 2
    except OSError as exc:  # the machine, not the input: disk full, permission, ...
        print(f"rotorkin: {_environment_message(exc)}", file=sys.stderr)
        return ENVIRONMENT_ERROR
    except Exception as exc:
        if hasattr(exc, "format_message") and hasattr(exc, "exit_code"):  # a usage error
            print(f"rotorkin: error: {_one_line(exc.format_message())}", file=sys.stderr)
            return 2
        return _internal_error(exc)
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)
    return 0


def console_main() -> None:
    """The ``rotorkin`` console script: :func:`main`, then leave at once.

    Once the command has returned, its files are closed and the exit handlers run
    (logging, a dask cluster's, temporary folders'); what is left is tearing the
    interpreter down object by object, 0.2-0.4 s after a run or a sweep that loaded
    numpy, matplotlib and the compiled loops, for nothing: the process ends instead.
    ``ROTORKIN_DEBUG=1`` leaves the normal way.
    """

    code = main()
    if os.environ.get("ROTORKIN_DEBUG"):
        sys.exit(code)
    import atexit

    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):
            stream.flush()
    os._exit(code)


def _internal_error(exc: BaseException) -> int:
    """An internal error: one line; the traceback with ``--verbose`` or ``ROTORKIN_DEBUG=1``."""
    if os.environ.get("ROTORKIN_DEBUG"):
        raise exc
    if console.STATE.verbose:
        import traceback

        traceback.print_exception(exc, file=sys.stderr)
    print(
        f"rotorkin: internal error: {type(exc).__name__}: {_one_line(str(exc))} "
        "(run with --verbose or set ROTORKIN_DEBUG=1 for the traceback, and please report it)",
        file=sys.stderr,
    )
    return 1
