"""Impeller outlines of the differential vane pump (the guide-bar drive has no cam).

The pump of :mod:`rotorkin.machines.vane_pump`: two coaxial impellers, each a
hub of radius ``R_h`` carrying ``Z`` radial vanes of angular width ``gamma``
that reach the casing radius ``R_c``, over the axial width ``w``. Derived here:
the outline of one impeller in its cross-section, a closed curve made of
casing arcs (the vane tips), radial flanks and hub arcs between the vanes,
counter-clockwise (:func:`impeller_outline`, :func:`impeller_area`: the nominal
section). The workshop parts (:func:`impeller_parts`) are those of any drive carrying
the pump (:mod:`rotorkin.vane.impellers`): drawn at ``theta = 0`` in the pump frame,
their hubs nested axially, bored and keyed, with the running gaps cut.
"""

from __future__ import annotations

import numpy as np

from rotorkin.cams import planar
from rotorkin.cams.planar import Part
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.machines import vane_pump as vp
from rotorkin.vane import impellers

__all__ = ["impeller_outline", "impeller_area", "impeller_parts"]


def impeller_outline(vane_angle, hub_radius, casing_radius, vane_centres, tolerance):
    """Closed outline of an impeller with vanes centred at ``vane_centres`` [rad].

    Parameters
    ----------
    vane_angle : float
        Angular width gamma of a vane [rad], ``0 < gamma < 2 pi / Z``.
    hub_radius, casing_radius : float
        [m].
    vane_centres : array_like, shape (Z,)
        Angles of the vane centre lines [rad], equally spaced ``2 pi / Z``.
    tolerance : float
        Chordal tolerance of the arcs [m].

    Returns
    -------
    ndarray, shape (n, 2)
        Vertices [m], counter-clockwise, not closed (the last joins the first).
    """
    c = np.sort(np.asarray(vane_centres, dtype=float).reshape(-1))
    z = c.size
    g = float(vane_angle)
    pitch = 2.0 * np.pi / z
    pieces = []
    for m in range(z):
        tip = planar.arc_points((0.0, 0.0), casing_radius, c[m] - 0.5 * g, c[m] + 0.5 * g,
                                tolerance)  # fmt: skip
        hub = planar.arc_points((0.0, 0.0), hub_radius, c[m] + 0.5 * g,
                                c[m] + pitch - 0.5 * g, tolerance)  # fmt: skip
        pieces += [tip, hub]
    return np.concatenate(pieces)


def impeller_area(vanes, vane_angle, hub_radius, casing_radius):
    """Exact area of the outline: ``pi R_h^2 + Z gamma (R_c^2 - R_h^2) / 2`` [m^2]."""
    rh, rc = float(hub_radius), float(casing_radius)
    return np.pi * rh * rh + int(vanes) * float(vane_angle) * 0.5 * (rc * rc - rh * rh)


def impeller_parts(params: gb.GuideBar, pump: vp.VanePump, cfg: dict, tolerance,
                   check_only: bool = False) -> list[Part]:  # fmt: skip
    """Both impellers as workshop :class:`~rotorkin.cams.planar.Part` s at ``theta = 0``.

    :func:`rotorkin.vane.impellers.impeller_parts` on the drive's motion at ``theta = 0``.
    """
    return impellers.impeller_parts(pump, gb.motion(params, 0.0), cfg, tolerance, check_only)
