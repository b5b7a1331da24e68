"""The command group that imports a command's module only when that command runs.

``rotorkin --help`` lists every command from :data:`COMMANDS` (name, module,
one-line help) without importing any of them: the library behind them (drives,
scipy, matplotlib, pint) takes about a second to import, the list a few
milliseconds. Each module has ``register(app)``, which adds its commands to a
typer app; the first time a command is asked for, its module is imported and
registered on an app of its own, and the command is taken from there.
"""

from __future__ import annotations

import gc
import importlib
import time

import typer
from typer.core import TyperGroup

__all__ = ["COMMANDS", "LazyGroup", "running"]

#: Every command: name -> (module with ``register(app)``, the first line of its help).
#: ``tests/test_cli_format.py`` checks each line against the command's own docstring.
COMMANDS = {
    "run": ("rotorkin.cli.run",
            "Evaluate a drive over one period; write summary.json, motion.csv and figures."),
    "examples": ("rotorkin.cli.run",
                 "List the built-in examples (run one with: rotorkin run --example NAME)."),
    "keys": ("rotorkin.cli.run",
             "List every config key with its default and meaning (the glossary)."),
    "export": ("rotorkin.cli.export",
               "Write CAD files of the cam(s): DXF profiles, STL/STEP solids, CSV point lists "
               "(mm)."),
    "synthesize": ("rotorkin.cli.synthesize",
                   "Synthesize a design for an objective; compare it with the config's (the "
                   "paper's)."),
    "report": ("rotorkin.cli.report",
               "Write report.html: summary vs the paper, checks, animated mechanism, plots "
               "(offline)."),
    "sweep": ("rotorkin.cli.sweep",
              "Sweep config keys over ranges or lists; write sweep.nc (netCDF) and figures."),
    "tolerance": ("rotorkin.cli.sweep",
                  "Monte-Carlo tolerance analysis; write tolerance.json, tolerance.nc, "
                  "histograms."),
    "compare": ("rotorkin.cli.compare",
                "Run the config's vane machine on several drives sized to the same "
                "displacement."),
    "limits": ("rotorkin.cli.limits",
               "Print the admissible interval of one key, every other key held, and what "
               "binds."),
    "solve": ("rotorkin.cli.solve",
              "Find the value of one config key at which one metric hits a target."),
    "optimize": ("rotorkin.cli.optimize",
                 "Multi-objective search (NSGA-II): the Pareto set of metrics over config keys."),
}  # fmt: skip


class _Running:
    """The command being resolved or run (for the missing-extra message and --verbose)."""

    command: str | None = None
    #: Seconds its module took to import (the library behind it).
    load_seconds: float = 0.0


#: The command being run (None before one is chosen).
running = _Running()


def _load(name: str):
    """The click command ``name``, from its module registered on an app of its own."""
    # importing the library creates few cycles: no garbage collection meanwhile (its
    # passes over the growing heap take a tenth of the import)
    enabled = gc.isenabled()
    gc.disable()
    try:
        module = importlib.import_module(COMMANDS[name][0])
    finally:
        if enabled:
            gc.enable()
    app = typer.Typer(add_completion=False, pretty_exceptions_enable=False,
                      rich_markup_mode=None)  # fmt: skip
    module.register(app)
    group = typer.main.get_group(app)
    return group.commands[name]


class LazyGroup(TyperGroup):
    """A typer group whose commands are imported on first use (see the module's text)."""

    def list_commands(self, ctx) -> list[str]:
        return [*(n for n in self.commands if n not in COMMANDS), *COMMANDS]

    def invoke(self, ctx):
        # numpy's floating-point warnings are not for the user: every number that could be
        # non-finite is checked before it is written or printed (numpy imported here, not
        # for --help)
        import numpy as np

        with np.errstate(all="ignore"):
            return super().invoke(ctx)

    def get_command(self, ctx, cmd_name: str):
        if cmd_name not in self.commands and cmd_name in COMMANDS:
            running.command = cmd_name
            t0 = time.perf_counter()
            self.commands[cmd_name] = _load(cmd_name)
            running.load_seconds = time.perf_counter() - t0
        return self.commands.get(cmd_name)

    def format_commands(self, ctx, formatter) -> None:
        """The list of commands from :data:`COMMANDS`, nothing imported."""
        with formatter.section("Commands"):
            formatter.write_dl([(name, help_) for name, (_, help_) in COMMANDS.items()])

    def shell_complete(self, ctx, incomplete: str):
        """Command names from :data:`COMMANDS` (nothing imported), then the group's options."""
        try:
            from typer.core import CompletionItem  # typer with click inside
        except ImportError:  # pragma: no cover - typer on an installed click
            from click.shell_completion import CompletionItem

        items = [CompletionItem(name, help=help_) for name, (_, help_) in COMMANDS.items()
                 if name.startswith(incomplete)]  # fmt: skip
        names = {item.value for item in items}
        # the group's options (a typer on an installed click also lists commands: once here)
        base = super(TyperGroup, self).shell_complete(ctx, incomplete)
        return items + [item for item in base if item.value not in names]
