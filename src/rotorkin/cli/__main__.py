"""``python -m rotorkin.cli``: the same as the ``rotorkin`` command."""

import sys

from rotorkin.cli import main

sys.exit(main())
