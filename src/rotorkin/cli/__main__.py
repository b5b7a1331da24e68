"""``python -m rotorkin.cli``: the same as the ``rotorkin`` command."""

from rotorkin.cli import console_main

console_main()
