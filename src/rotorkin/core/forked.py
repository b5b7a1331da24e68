"""Work done by forked processes: the fork, the result sent back, exceptions that travel.

A forked child inherits the caller's modules and arrays, so its work needs no pickling
on the way in; only its result (or the exception it raised) comes back, pickled, over
a pipe. :func:`ahead` runs one call that way while the caller goes on, e.g. a check
that takes a few tenths of a second beside a computation that does not need it yet.
The figures' drawing processes (:mod:`rotorkin.render.figures`) use the same parts.

Only POSIX systems fork; elsewhere, and in a process whose other threads could hold a
lock the child needs, :func:`ahead` returns None and the caller calls the function
itself.
"""

from __future__ import annotations

import contextlib
import os
import pickle
import signal
import sys
import threading
import warnings
from collections.abc import Callable

__all__ = ["fork", "fork_safe", "take_signals", "flush_streams", "send_and_end", "read_all",
           "portable", "rebuilt", "Ahead", "ahead"]  # fmt: skip

#: The signals held while forking (the child takes them once its own code runs).
HELD = {signal.SIGTERM} if hasattr(signal, "pthread_sigmask") else set()


#: File descriptors this process keeps to itself: a child of :func:`ahead` closes its copies
#: at once (the write end of a pipe another child reads to its end, e.g.).
PRIVATE: set[int] = set()


def fork() -> int:
    """``os.fork()`` with SIGTERM held in the child until :func:`take_signals`.

    A SIGTERM reaching a child inside the interpreter's after-fork hooks would raise
    there and print a traceback; held, it is raised in the child's own code, which ends
    the child quietly (a failure sent back, or none wanted).
    """
    if HELD:
        previous = signal.pthread_sigmask(signal.SIG_BLOCK, HELD)
    try:
        with warnings.catch_warnings():  # rotorkin's idle threads hold no lock
            warnings.simplefilter("ignore", DeprecationWarning)
            pid = os.fork()
    except BaseException:
        if HELD:
            signal.pthread_sigmask(signal.SIG_SETMASK, previous)
        raise
    if HELD and pid != 0:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)
    return pid


def take_signals() -> None:  # pragma: no cover - runs in a forked child
    """In a child of :func:`fork`: receive the held signals (a pending one raises now)."""
    if HELD:
        signal.pthread_sigmask(signal.SIG_UNBLOCK, HELD)


def fork_safe() -> bool:
    """Whether this process may fork: no threads but its own and rotorkin's idle pool."""
    main = threading.main_thread()
    return threading.current_thread() is main and all(
        t is main or t.name.startswith("rotorkin") for t in threading.enumerate()
    )


def flush_streams() -> None:
    """Flush stdout and stderr (a child would otherwise write their buffers once more)."""
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(BaseException):
            stream.flush()


def send_and_end(out_w: int, result, code: int) -> None:  # pragma: no cover - in a child
    """A forked process's end: ``result`` pickled into ``out_w`` (unless None), its streams
    flushed, ``os._exit(code)`` (1 where the result cannot be sent)."""
    try:
        if result is not None:
            view = memoryview(pickle.dumps(result))
            while view:
                view = view[os.write(out_w, view) :]
    except BaseException:  # noqa: BLE001 - a child never returns into the caller's code
        code = 1
    finally:
        flush_streams()
        os._exit(code)


def read_all(fd: int) -> bytes:
    """Everything a child writes into its pipe, until it closes it."""
    chunks = []
    while chunk := os.read(fd, 1 << 16):
        chunks.append(chunk)
    return b"".join(chunks)


def portable(exc: BaseException):
    """What a child sends back of ``exc``: the exception, or what rebuilds it, or its text.

    An exception that pickles is sent as it is; one whose constructor takes other
    arguments than it keeps (:class:`rotorkin.core.errors.ParameterError`) as its class's
    module and name, its arguments and attributes, rebuilt by :func:`rebuilt` (the
    class is in the parent too: it forked); any other as ``(class name, message)``.
    """
    try:
        back = pickle.loads(pickle.dumps(exc))
        if type(back) is type(exc) and str(back) == str(exc):
            return exc
    except Exception:  # noqa: BLE001 - any failure: try the parts
        pass
    cls = type(exc)
    try:
        parts = ("class", cls.__module__, cls.__qualname__, exc.args, dict(vars(exc)))
        pickle.loads(pickle.dumps(parts))
        if "<locals>" not in cls.__qualname__:
            return parts
    except Exception:  # noqa: BLE001 - the text only
        pass
    return (cls.__name__, str(exc))


def rebuilt(failure) -> BaseException | tuple[str, str]:
    """The exception a child sent back (:func:`portable`), or its ``(name, message)``."""
    if isinstance(failure, BaseException):
        return failure
    if len(failure) == 5 and failure[0] == "class":
        _, module, qualname, args, attrs = failure
        cls = sys.modules.get(module)
        for part in qualname.split("."):
            cls = getattr(cls, part, None)
        if isinstance(cls, type) and issubclass(cls, BaseException):
            exc = cls.__new__(cls)
            BaseException.__init__(exc, *args)
            exc.__dict__.update(attrs)
            return exc
        return (qualname, str(args[0]) if args else "")
    return tuple(failure)


class Ahead:
    """One call running in a forked process (:func:`ahead`): wait for it, or end it."""

    def __init__(self, pid: int, out_r: int):
        self.pid, self._out_r, self._outcome = pid, out_r, None

    def done(self) -> bool:
        """Whether the call has ended (its outcome is ready; never waits)."""
        if self._outcome is None:
            import select

            if not select.select([self._out_r], [], [], 0)[0]:
                return False
            self._finish()
        return True

    def result(self):
        """The call's return value; its exception raised here. Waits for the child."""
        if self._outcome is None:
            self._finish()
        kind, payload = self._outcome
        if kind == "ok":
            return payload
        failure = rebuilt(payload)
        if isinstance(failure, BaseException):
            raise failure
        name, message = failure
        raise RuntimeError(f"{name}: {message}")

    def cancel(self) -> None:
        """End the child if it still runs (SIGTERM) and forget its outcome."""
        if self._outcome is None:
            with contextlib.suppress(OSError):
                os.kill(self.pid, signal.SIGTERM)
            self._finish()

    def _finish(self) -> None:
        data = read_all(self._out_r)
        os.close(self._out_r)
        try:
            status = os.waitpid(self.pid, 0)[1]
        except ChildProcessError:  # pragma: no cover - reaped elsewhere
            status = 0
        try:
            self._outcome = pickle.loads(data)
        except Exception:  # noqa: BLE001 - a child that died without a result
            code = os.waitstatus_to_exitcode(status) if status else 1
            self._outcome = ("error", ("ChildProcessError", f"the process ended with code {code}"))


def ahead(fn: Callable, *args) -> Ahead | None:
    """Run ``fn(*args)`` in a forked process now; None where this process cannot fork.

    The child inherits everything (nothing is pickled on the way in); its return value
    comes back pickled, an exception rebuilt (:func:`portable`). Call
    :meth:`Ahead.result` for the outcome, :meth:`Ahead.cancel` when it is no longer
    wanted: a child is never left behind unless the caller dies first.
    """
    if not hasattr(os, "fork") or not fork_safe():
        return None
    flush_streams()
    out_r, out_w = os.pipe()
    try:
        pid = fork()
    except OSError:
        os.close(out_r)
        os.close(out_w)
        return None
    if pid == 0:  # pragma: no cover - runs in the forked process
        os.close(out_r)
        _run(fn, args, out_w)
    os.close(out_w)
    return Ahead(pid, out_r)


def _run(fn, args, out_w: int) -> None:  # pragma: no cover - runs in a forked child
    """The child of :func:`ahead`: the call's outcome sent back, then the child ends."""
    result, code = None, 1
    try:
        # a cancelled call's outcome is not wanted: SIGTERM ends the child at once
        if HELD:
            signal.signal(signal.SIGTERM, signal.SIG_DFL)
        take_signals()
        for fd in PRIVATE:
            with contextlib.suppress(OSError):
                os.close(fd)
        try:
            result, code = ("ok", fn(*args)), 0
        except BaseException as exc:  # noqa: BLE001 - everything goes back to the caller
            result, code = ("error", portable(exc)), 0
    except BaseException:  # noqa: BLE001 - a child never returns into the caller's code
        result, code = None, 1
    send_and_end(out_w, result, code)
