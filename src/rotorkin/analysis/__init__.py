"""Generic analysis on any drive: time domain, torque by virtual work, inertia and flywheel."""
