"""Vane machines on any rotary drive.

A rotary two-member drive (two coaxial members turned by one shaft) gives a
:class:`~rotorkin.vane.law.RotaryLaw`; any of the vane machines (twin-rotor
engine, differential vane pump, rotary-blade engine) then runs on it:
:func:`~rotorkin.vane.study.evaluate`. The drives' packages use this layer; it
names no drive.
"""

from rotorkin.vane.law import RotaryLaw
from rotorkin.vane.machines import MACHINES
from rotorkin.vane.study import evaluate

__all__ = ["RotaryLaw", "MACHINES", "evaluate"]
