"""Machines built on the drives: chambers, volumes, pressures and torques."""
