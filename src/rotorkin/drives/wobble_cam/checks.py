"""The spherical cam's checks with their margins (:mod:`rotorkin.studies.checks`).

The cam's proportions (roller radius, shell thickness, groove depth against the sphere
radius and each other) are refused outright, as ``rotorkin export`` refuses them
(:func:`rotorkin.drives.wobble_cam.cam.from_config`). The roller's undercut limit
depends on the plate tilt (the grooves bend harder as the plate tilts further), so the
analysis of a tilt whose grooves the default roller undercuts is not refused: the check
below fails, ``run`` says so and ``export`` refuses that cam.
"""

from __future__ import annotations

import numpy as np

from rotorkin.drives.wobble_cam import cam as cs
from rotorkin.studies.checks import Check

__all__ = ["checks"]


def checks(cfg: dict, parts: tuple | None = None) -> list[Check]:
    """The cam's checks: the roller radius against the grooves' undercut limit.

    The walls' offset ``h = rho + c/2`` (running clearance ``c``) must stay below
    ``R_i / sqrt(1 + (r kappa_g)^2)`` at the sharpest bend of any groove
    (:func:`rotorkin.drives.wobble_cam.cam.check_roller_radius`): the roller radius below
    that less ``c/2``; a larger roller makes a cusp in the inner groove wall. Raises
    :class:`ParameterError` for proportions that no tilt admits (named by config key).
    ``parts``: the config's ``(drive, cam)`` if built already (``cam.from_config``).
    """
    if "cam" not in cfg:
        return []
    drive, cam = parts or cs.from_config(cfg)
    kmax, theta, roller = cs.sharpest_bend(drive)
    # the walls' offset h = rho + c/2 must stay below the limit: rho below it less c/2
    walls = cam.inner_radius / np.sqrt(1.0 + (drive.sphere_radius * kmax) ** 2)
    limit = walls - 0.5 * cam.running_clearance
    where = (f"sharpest groove bend at theta = {np.degrees(theta):.4g} deg, "
             f"roller {cs.ROLLER_NAMES[roller]}")  # fmt: skip
    return [Check("wobble cam: roller radius against undercut", "cam.roller_radius",
                  cam.roller_radius * 1e3, float(limit) * 1e3, "mm", True, where)]  # fmt: skip
