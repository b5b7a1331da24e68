"""Swept tools of the spherical cam: grooves and shaft slots, as meshes' sections and B-reps.

A groove is the region swept by its cross-section in the normal plane of the centre-line,
the plane spanned by the radial direction ``e_r`` and the wall normal ``n``: between the
walls ``lambda e_r +- h n`` (``h = rho + c/2``, :attr:`SphericalCam.groove_half_width`)
and from just inside the inner surface out to the groove bottom at
``R_b = R_i + groove_depth`` (the sphere R_b for the STL; flat across for the STEP, as a
flat end mill leaves it). A shaft slot is the region swept by the roller shaft (a
cylinder of radius ``r_s`` on the same radial line) plus its clearance: the same sweep
with a narrower section, from the groove bottom out through ``R_o``. Where the
figure-eight crosses itself the two branches overlap and the groove is cut through.

A closed swept tube that crosses itself is not a valid solid (neither for manifold3d
nor for OpenCascade), so every groove is split into open pieces between its
self-crossings (:func:`groove_pieces`: 2 pieces for a figure-eight); the pieces share
their end sections and are united. Each B-rep piece is lofted through polygonal sections
(exact at the sections, B-spline between; 0.001 um from the walls measured in the
example); sweeps (``BRepOffsetAPI_MakePipeShell`` in Frenet, corrected-Frenet or
auxiliary-spine mode) fail to make a solid of these pieces.
"""

from __future__ import annotations

import numpy as np

from rotorkin.drives.wobble_cam import cam as sph
from rotorkin.render.cad import build123d_module

__all__ = [
    "groove_pieces",
    "section_uv",
    "tool_floor",
    "sections",
    "piece_samples",
    "groove_bottom",
    "cutting_tools",
    "solid_volume",
]

_MM = 1e3
#: Where the pieces of a groove are cut between consecutive self-crossings (fraction of
#: the way): off the lobe tips, where the sharpest bend of the wall meets the cut.
CUT = 0.42


def groove_pieces(drive) -> list[tuple[int, float, float]]:
    """Open pieces ``(roller, theta_start, theta_end)`` [rad] covering every distinct groove.

    Cut :data:`CUT` of the way between consecutive self-crossing parameters, so that no
    piece holds both branches of a crossing (2 pieces for a figure-eight, cut before its
    lobe tips; 2 halves for a groove that does not cross itself); ends are shared,
    ``theta_end > theta_start``.
    """
    period = sph.groove_period(drive)
    crossings = sph.groove_crossings(drive)
    out = []
    for i in sph.distinct_grooves(drive):
        own = np.sort([x for c in crossings if c.rollers == (i, i) for x in c.theta])
        if len(own):
            cuts = np.sort((own + CUT * np.diff(np.append(own, own[0] + period))) % period)
        else:
            cuts = np.array([0.0, 0.5 * period])
        ends = np.append(cuts[1:], cuts[0] + period)
        out.extend((i, float(a), float(b)) for a, b in zip(cuts, ends, strict=True))
    return out


def section_uv(cam, lam_lo: float, tol: float):
    """Groove cross-section in (lambda, mu) coordinates of the plane (e_r, n), CCW [m].

    From ``lam_lo`` to the groove bottom arc of radius R_b, ``mu`` between ``-+h``.
    """
    rb, h = cam.bottom_radius, cam.groove_half_width
    beta = np.arcsin(h / rb)
    k = max(2, int(np.ceil(beta / np.arccos(1.0 - tol / rb))))
    a = np.linspace(-beta, beta, k + 1)
    arc = np.stack([rb * np.cos(a), rb * np.sin(a)], 1)
    return np.vstack([[lam_lo, -h], arc, [lam_lo, h]])


def tool_floor(drive, cam) -> float:
    """Radius a little inside R_i where the tool starts, still free of wall cusps [m]."""
    kmax = sph.sharpest_bend(drive)[0]
    regular = cam.groove_half_width * np.sqrt(1.0 + (drive.sphere_radius * kmax) ** 2)
    return max(cam.inner_radius - 0.05 * cam.shell_thickness, 0.5 * (cam.inner_radius + regular))


def sections(drive, roller, theta, uv):
    """3D sections at theta: (len(theta), len(uv), 3) [m]."""
    e_r, _, n = sph.groove_frame(drive, theta)
    e_r, n = e_r[roller].T, n[roller].T  # (m, 3)
    return e_r[:, None, :] * uv[None, :, :1] + n[:, None, :] * uv[None, :, 1:]


def piece_samples(drive, roller, t0, t1, uv, tol):
    """Section parameters on [t0, t1] such that every vertex path is within tol."""
    n = max(8, int(np.ceil(64 * (t1 - t0) / np.pi)))
    while True:
        theta = np.linspace(t0, t1, n + 1)
        s = sections(drive, roller, theta, uv)
        mid = sections(drive, roller, 0.5 * (theta[1:] + theta[:-1]), uv)
        e = s[1:] - s[:-1]
        e /= np.linalg.norm(e, axis=2, keepdims=True)
        w = mid - s[:-1]
        sag = float(np.max(np.linalg.norm(w - np.sum(w * e, 2, keepdims=True) * e, axis=2)))
        if sag <= tol:
            return theta, s, sag
        n = int(np.ceil(n * np.sqrt(sag / tol) * 1.1))


def groove_bottom(cam) -> float:
    """Distance of the flat groove bottom from the centre along the roller axis [m]: R_b.

    The tool is flat across (as a flat end mill of the groove's width leaves it): the
    bottom stands at ``R_b`` on the centre-line and reaches ``sqrt(R_b^2 + h^2)`` at the
    walls (0.13 mm deeper in the example).
    """
    return cam.bottom_radius


def cutting_tools(drive, cam, tol: float, slot_half_width: float) -> list:
    """Lofted tools cutting the grooves and the shaft slots, one per groove piece [mm].

    Each piece of :func:`groove_pieces` is lofted through sections in the normal plane
    (``e_r``, ``n``) of the centre-line: the groove ``mu in [-h, h]`` from the piece's
    floor just inside ``R_i`` to its flat bottom at ``R_b``, and on it the shaft slot
    ``mu in [-w, w]`` (``w = slot_half_width``) out beyond ``R_o``. The sections are those
    of :func:`piece_samples` within ``tol/2`` (the walls ``lambda e_r +- h n`` are exact at
    the sections, the loft's B-splines follow them between). Piece k of K gets its floor,
    bottom and top shifted by the fraction ``(k + 1)/(K + 1)`` of 0.05 R_i, 0.1 mm and
    1 mm: where two pieces cross, equal levels would touch tangentially, which
    OpenCascade's booleans miss.

    Returns
    -------
    list of build123d Solid
    """
    bd = build123d_module()
    pieces = groove_pieces(drive)
    low = tool_floor(drive, cam)
    h, w = cam.groove_half_width, float(slot_half_width)
    ri, ro, rb = cam.inner_radius, cam.outer_radius, groove_bottom(cam)
    out = []
    for k, (roller, t0, t1) in enumerate(pieces):
        f = (k + 1.0) / (len(pieces) + 1.0)
        lo, st, hi = ri - f * (ri - low), rb + f * 1e-4, ro + 0.5e-3 + f * 1e-3
        sec = np.array([[lo, -h], [st, -h], [st, -w], [hi, -w], [hi, w], [st, w], [st, h], [lo, h]])
        theta, _, _ = piece_samples(drive, roller, t0, t1, sec, 0.5 * tol)
        wires = [
            bd.Wire.make_polygon([bd.Vector(*c) for c in corners], close=True)
            for corners in sections(drive, roller, theta, sec) * _MM
        ]
        out.append(bd.Solid.make_loft(wires, ruled=False))
    return out


def solid_volume(solid) -> float:
    """Volume of a build123d solid by adaptive integration (relative error 1e-9) [its units^3].

    ``Shape.volume`` uses a fixed Gauss rule that is off by up to ~5 % on the trimmed
    B-spline faces of the grooves.
    """
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(solid.wrapped, props, 1e-9, True)
    return float(props.Mass())
