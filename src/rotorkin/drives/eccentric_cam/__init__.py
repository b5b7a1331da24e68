"""The eccentric_cam drive: its kinematics API (re-exported here) and all built on it.

``SPEC`` (:mod:`.spec`) is what the registry lists.
"""

import sys

from rotorkin.drives.eccentric_cam.kinematics import *  # noqa: F403
from rotorkin.drives.eccentric_cam.kinematics import __all__ as _api

# a function of the API may share a submodule's name: the submodule keeps it
kinematics = sys.modules[f"{__name__}.kinematics"]

from rotorkin.drives.eccentric_cam.spec import SPEC  # noqa: E402

__all__ = [*(n for n in _api if n != "kinematics"), "SPEC"]
