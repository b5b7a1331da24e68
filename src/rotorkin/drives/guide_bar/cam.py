"""Impeller outlines of the differential vane pump (the guide-bar drive has no cam).

The pump of :mod:`rotorkin.machines.vane_pump`: two coaxial impellers, each a
hub of radius ``R_h`` carrying ``Z`` radial vanes of angular width ``gamma``
that reach the casing radius ``R_c``, over the axial width ``w``. Derived here:
the outline of one impeller in its cross-section, a closed curve made of
casing arcs (the vane tips), radial flanks and hub arcs between the vanes,
counter-clockwise. Each impeller is drawn at ``theta = 0`` in the pump frame, its
vanes at the angles of :func:`rotorkin.machines.vane_pump.vane_angles`, so the
two drawings overlaid show the pump assembled. The vane tips are drawn on the
casing radius itself; running clearance and seals are left to the designer.
"""

from __future__ import annotations

import numpy as np

from rotorkin.cams import planar
from rotorkin.cams.planar import Curve, Part
from rotorkin.core.angles import fmt_deg, fmt_mm
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.machines import vane_pump as vp

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


def impeller_parts(params: gb.GuideBar, pump: vp.VanePump, tolerance) -> list[Part]:
    """Both impellers as :class:`~rotorkin.cams.planar.Part` s, extruded to ``axial_width``.

    Curves: ``profile`` (PROFILE) and, for reference, the ``casing`` circle (CASING).
    """
    v = vp.vane_angles(pump, gb.motion(params, 0.0))  # (2, Z)
    rh, rc = float(pump.hub_radius), float(pump.casing_radius)
    casing = planar.circle_curve("casing", "CASING", (0.0, 0.0), rc, tolerance)
    parts = []
    for k in (0, 1):
        pts = impeller_outline(pump.vane_angle, rh, rc, v[k], tolerance)
        outline = Curve("profile", "PROFILE", pts)
        parts.append(
            Part(
                name=f"impeller_{k + 1}",
                outline=outline,
                thickness=float(pump.axial_width),
                curves=(outline, casing),
                title=f"impeller {k + 1}: hub {fmt_mm(rh)}, {pump.vanes_per_impeller} vanes of "
                f"{fmt_deg(pump.vane_angle)} to {fmt_mm(rc)}, drawn at theta = 0",
            )
        )
    return parts
