"""Design commands: solve for a key that brings a metric to a target; multi-objective search.

:func:`solve` finds one config key's value at which one summary metric hits a
target (a scan of the key's admissible range, then Brent's method);
:func:`rotorkin.design.optimize.optimize` searches several keys for the Pareto set
of several metrics (NSGA-II of the optional ``pymoo``, imported when a search
runs), a population at a time through the sweep kernels. Both evaluate designs
with :func:`rotorkin.sweep.evaluate_designs`, so a design the drive refuses is
never a candidate. See ``docs/design.md``.
"""

from __future__ import annotations

from rotorkin.design.optimize import OptimizeResult
from rotorkin.design.problem import OptimizeSpec
from rotorkin.design.solve import End, OutOfReach, SolveResult, solve

__all__ = [
    "solve",
    "SolveResult",
    "End",
    "OutOfReach",
    "OptimizeSpec",
    "OptimizeResult",
]
