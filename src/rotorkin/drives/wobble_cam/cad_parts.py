"""Solids of the wobble-cam engine's parts, each in its own body's frame, in mm (build123d).

Sizes from :class:`rotorkin.drives.wobble_cam.cad_layout.Layout`; frames as there (cam
frame, shaft frame, plate frame, rotor frames, the fixed frame for the casing). Exact
cylinders, spheres and planar faces; the cam's grooves and slots are lofted
(:mod:`rotorkin.drives.wobble_cam.cad_grooves`).

* cam: the shell ``R_i..R_o`` minus the grooves (``2 rho + c`` wide, ``R_i..R_b``), the
  shaft slots (the roller shaft's swept region, ``2 r_s + slot_clearance`` wide, from
  inside the groove bottom out through ``R_o``), one assembly window at each crossing (a
  radial hole of the groove's width from just inside ``R_b`` out: the roller goes in
  through it onto its shaft) and the bore on the axis; split on the plane ``x = 0`` into
  ``cam_half_1`` (``x >= 0``) and ``cam_half_2``. A through slot along a closed lobe of the
  figure-eight frees the lobe's inside: each such island is a part of its own,
  ``cam_lobe_<groove>_<half>``.
* plate: hub on the crank (bore with a gap for the bearings), disc with 4 radial holes.
* roller shafts, rollers (bore: ISO 286 H8/f7 on the shaft), rail rollers.
* Z-shaft: journals on x from ``x_j`` out, the crank along the plate axis, straight webs
  with spheres at their joints.
* rails: a U channel in the rotor's meridian plane around the rail roller's arc, closed
  at its +x end, with an arm along x to the rotor's spoke.
* rotors: sleeve, disc, spokes and pistons (annular sectors of the piston width);
  rotor 1 also the hub under the cylinder.
* casing: a body of revolution around everything, with bores for the Z-shaft.
"""

from __future__ import annotations

import copy

import numpy as np

from rotorkin.core.errors import RotorkinError
from rotorkin.drives.wobble_cam import cam as sph
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.drives.wobble_cam.cad_grooves import cutting_tools
from rotorkin.drives.wobble_cam.cad_layout import Layout, rot_x, rot_y
from rotorkin.render.cad import build123d_module

__all__ = ["cam_parts", "plate_parts", "z_shaft", "rotor_parts", "casing", "placed"]

_MM = 1e3


def placed(solid, rotation):
    """``solid`` turned by the 3x3 rotation matrix (body to fixed coordinates)."""
    bd = build123d_module()
    from OCP.gp import gp_Trsf
    from OCP.TopLoc import TopLoc_Location

    m = np.asarray(rotation, dtype=float)
    trsf = gp_Trsf()
    trsf.SetValues(*m[0], 0.0, *m[1], 0.0, *m[2], 0.0)
    return solid.moved(bd.Location(TopLoc_Location(trsf)))


def _cyl(r, a, b, axis=(1.0, 0.0, 0.0)):
    """Cylinder of radius r along the unit ``axis`` from ``a`` to ``b`` (distances) [m -> mm]."""
    bd = build123d_module()
    u = np.asarray(axis, dtype=float)
    plane = bd.Plane(origin=tuple(a * _MM * u), z_dir=tuple(u))
    return bd.Solid.make_cylinder(r * _MM, (b - a) * _MM, plane)


def _ring(r0, r1, a, b, axis=(1.0, 0.0, 0.0)):
    return _cyl(r1, a, b, axis) - _cyl(r0, a - 1e-3, b + 1e-3, axis)


def _sector_x(r0, r1, x0, x1, centre, width):
    """Annular sector about x: radii r0..r1, x0..x1, angles ``centre -+ width/2`` (z to y)."""
    bd = build123d_module()
    pts = [(x0, 0.0, r0), (x1, 0.0, r0), (x1, 0.0, r1), (x0, 0.0, r1)]
    face = bd.Face(bd.Wire.make_polygon([bd.Vector(*(np.array(p) * _MM)) for p in pts], True))
    solid = bd.Solid.revolve(face, float(np.degrees(width)), bd.Axis.X)
    # revolving about +x takes z towards -y: the sector spans the angles -width..0
    return placed(solid, rot_x(centre + 0.5 * width))


def _box_centre(solid) -> np.ndarray:
    """Centre of a solid's bounding box [its units] (no volume integration)."""
    return np.array(tuple(solid.bounding_box().center()))


def _box(x, y, z):
    """Box over the ranges x, y, z [m -> mm]."""
    bd = build123d_module()
    lo = [v[0] * _MM for v in (x, y, z)]
    size = [(v[1] - v[0]) * _MM for v in (x, y, z)]
    return bd.Solid.make_box(*size, bd.Plane(origin=tuple(lo)))


def _sector_y(r0, r1, a0, a1, half):
    """Sector in the xz plane (radii r0..r1, polar a0..a1 from +x towards +z), y in +-half."""
    bd = build123d_module()

    def p(r, a):
        return bd.Vector(r * np.cos(a) * _MM, -half * _MM, r * np.sin(a) * _MM)

    am = 0.5 * (a0 + a1)
    wire = bd.Wire(
        [
            bd.Edge.make_line(p(r0, a0), p(r1, a0)),
            bd.Edge.make_three_point_arc(p(r1, a0), p(r1, am), p(r1, a1)),
            bd.Edge.make_line(p(r1, a1), p(r0, a1)),
            bd.Edge.make_three_point_arc(p(r0, a1), p(r0, am), p(r0, a0)),
        ]
    )
    return bd.Solid.extrude(bd.Face(wire), bd.Vector(0.0, 2.0 * half * _MM, 0.0))


def _solid(shape, what):
    """The one valid solid of a boolean's result (OpenCascade's shape healing if needed)."""
    bd = build123d_module()
    solids = shape.solids()
    if len(solids) == 1 and not solids[0].is_valid:
        from OCP.ShapeFix import ShapeFix_Shape

        fix = ShapeFix_Shape(solids[0].wrapped)
        fix.Perform()
        solids = bd.Shape.cast(fix.Shape()).solids()
    if len(solids) != 1 or not solids[0].is_valid:  # pragma: no cover - a failed boolean
        raise RotorkinError(
            f"the {what} came out as {len(solids)} solids or not valid; report this config as a bug"
        )
    return solids[0]


# --------------------------------------------------------------------------------------------
# cam shell (cam frame)
# --------------------------------------------------------------------------------------------
def cam_parts(layout: Layout, tol: float) -> list:
    """The cam's halves and freed lobes: ``[(name, Solid)]`` in the cam frame [mm].

    One boolean cuts the grooves with their shaft slots (:func:`cutting_tools`), the
    assembly windows and the bore from the shell; the plane ``x = 0`` splits it.
    """
    bd = build123d_module()
    drive, cam = layout.drive, layout.cam
    ri, ro = cam.inner_radius, cam.outer_radius
    tools = cutting_tools(drive, cam, tol, layout.slot_half_width)
    centres = [c.point / np.linalg.norm(c.point) for c in sph.groove_crossings(drive)]
    windows = [_cyl(layout.window_radius, layout.window_floor, ro + 2e-3, u) for u in centres]
    bore = _cyl(layout.cam_bore, -ro - 2e-3, ro + 2e-3)
    axis = bd.Plane.YZ  # sphere poles on the cam axis, inside the bores
    shell = bd.Solid.make_sphere(ro * _MM, axis) - bd.Solid.make_sphere(ri * _MM, axis)
    body = shell.cut(*tools, *windows, bore)
    big = 2.0 * ro + 0.01
    out = []
    for k, xs in ((1, (0.0, big)), (2, (-big, 0.0))):
        side = (body & _box(xs, (-big, big), (-big, big))).solids()
        solids = sorted(side, key=lambda s: -s.bounding_box().diagonal)
        out.append((f"cam_half_{k}", solids[0]))
        out.extend(_lobe_names(drive, solids[1:], k))
    return out


def _lobe_names(drive, solids, half: int) -> list:
    """Name each freed island by the groove whose centre-line runs nearest its centre."""
    theta = np.linspace(0.0, sph.groove_period(drive), 2048, endpoint=False)
    g = sph.groove_derivatives(drive, theta)[0]
    rollers = sph.distinct_grooves(drive)
    out, used = [], {}
    for s in solids:
        c = _box_centre(s)
        c /= np.linalg.norm(c)
        dots = [np.max(np.einsum("j,jn->n", c, g[i]) / drive.sphere_radius) for i in rollers]
        slug = sph.ROLLER_SLUGS[rollers[int(np.argmax(dots))]]
        name = f"cam_lobe_{slug}_{half}"
        used[name] = used.get(name, 0) + 1
        out.append((name if used[name] == 1 else f"{name}_{used[name]}", s))
    return out


# --------------------------------------------------------------------------------------------
# plate, roller shafts, rollers (plate frame)
# --------------------------------------------------------------------------------------------
def _roller_axes(layout: Layout):
    c = wc.roller_offsets(layout.drive.roller_axis_angle)
    return [(0.0, float(np.sin(a)), float(np.cos(a))) for a in c]


def plate_parts(layout: Layout) -> list:
    """Plate, roller shafts, rollers and rail rollers: ``[(name, Solid)]`` in the plate frame."""
    L = layout
    lo, hi = L.cam.roller_span
    hub = _cyl(L.hub_radius, -L.hub_half, L.hub_half)
    disc = _cyl(L.plate_radius, -L.plate_half, L.plate_half)
    holes = [_cyl(L.rshaft_radius, L.rshaft_inner, L.plate_radius + 1e-3, u)
             for u in _roller_axes(L)]  # fmt: skip
    plate = (hub + disc).cut(_cyl(L.plate_bore, -L.hub_half - 1e-3, L.hub_half + 1e-3), *holes)
    out = [("plate", _solid(plate, "plate"))]
    rr, rl, rad = L.rail_roller_radius, L.rail_roller_length, L.rail_radius
    for slug, u in zip(sph.ROLLER_SLUGS, _roller_axes(L), strict=True):
        out.append(
            (f"roller_shaft_{slug}", _cyl(L.rshaft_radius, L.rshaft_inner, L.rshaft_outer, u))
        )
        out.append((f"roller_{slug}", _ring(L.roller_bore, L.cam.roller_radius, lo, hi, u)))
        out.append((f"rail_roller_{slug}",
                    _ring(L.roller_bore, rr, rad - 0.5 * rl, rad + 0.5 * rl, u)))  # fmt: skip
    return out


# --------------------------------------------------------------------------------------------
# Z-shaft (shaft frame)
# --------------------------------------------------------------------------------------------
def z_shaft(layout: Layout):
    """The Z-shaft in the shaft frame [mm]: journals, crank along the plate axis, webs."""
    bd = build123d_module()
    L = layout
    r = L.shaft_radius
    axis = rot_y(L.drive.plate_tilt)[:, 0]  # the plate axis x2 in the shaft frame
    parts = [
        _cyl(r, L.journal_start, L.journal_end[1]),
        _cyl(r, L.journal_end[0], -L.journal_start),
        _cyl(r, -L.crank_half, L.crank_half, axis),
    ]
    for s in (1.0, -1.0):
        a = s * L.crank_half * axis
        b = np.array([s * L.journal_start, 0.0, 0.0])
        length = float(np.linalg.norm(b - a))
        parts.append(_cyl(r, 0.0, length, (b - a) / length).moved(bd.Location(tuple(a * _MM))))
        parts += [bd.Solid.make_sphere(r * _MM).moved(bd.Location(tuple(p * _MM))) for p in (a, b)]
    return _solid(parts[0].fuse(*parts[1:]), "Z-shaft")


# --------------------------------------------------------------------------------------------
# rails and rotors (rotor frames)
# --------------------------------------------------------------------------------------------
def _rail(layout: Layout, slab: float):
    L = layout
    b0, b1 = L.rail_angles
    outer = _sector_y(L.rail_inner, L.rail_outer, L.rail_end_angle, b1, L.rail_half_width)
    x_arm = L.rail_inner * np.cos(b0)
    arm = _box((x_arm, slab), (-L.rail_half_width, L.rail_half_width), L.arm_z)
    channel = _sector_y(L.rail_inner - 1e-3, L.rail_outer - L.wall, b0, b1 + np.radians(1.0),
                        L.rail_channel)  # fmt: skip
    return _solid((outer + arm) - channel, "rail")


def rotor_parts(layout: Layout, rotor: int) -> list:
    """Rotor ``rotor`` (1 or 2) and its two rails: ``[(name, Solid)]`` in its rotor frame."""
    L = layout
    x0, x1 = L.cyl_x
    r1, r2 = L.cyl_r
    g, w = L.gap, L.wall
    n = L.drive.pistons_per_rotor
    beta, gamma = L.piston_width, L.piston_offset
    if rotor == 1:
        slab, (s_in, s_out) = L.slab_b, L.sleeve_1
        # overlaps of 0.2 to 0.3 mm join the pieces; none of their faces coincide
        body = [
            _ring(s_in, s_out, slab[0], x0 - 0.5 * w),
            _ring(s_in, r2 - g, x0 - w, x0),
            _ring(s_in, r1, x0 - 0.3e-3, x1 - g),
        ]
        pistons = [_sector_x(r1 - 0.2e-3, r2 - g, x0 - 0.2e-3, x1 - g,
                             gamma + 2 * np.pi * k / n, beta) for k in range(n)]  # fmt: skip
    else:
        slab, (s_in, s_out) = L.slab_a, L.sleeve_2
        body = [_ring(s_in, s_out, slab[0], x1 + 0.5 * w), _ring(s_in, r2 - g, x1, x1 + w)]
        pistons = [_sector_x(r1 + g, r2 - g, x0 + g, x1 + 0.2e-3,
                             -gamma + 2 * np.pi * k / n, beta) for k in range(n)]  # fmt: skip
    hw = L.rail_half_width
    spoke = _box(slab, (-hw, hw), (s_out - 0.5e-3, L.arm_z[1]))
    body += [spoke, placed(spoke, rot_x(np.pi)), *pistons]
    out = [(f"rotor_{rotor}", _solid(body[0].fuse(*body[1:]), f"rotor {rotor}"))]
    rail = _rail(L, slab[0])
    slugs = ("1", "1p") if rotor == 1 else ("2", "2p")
    twin = placed(copy.deepcopy(rail), rot_x(np.pi))  # a part of its own in the STEP file
    out += [(f"rail_{slugs[0]}", rail), (f"rail_{slugs[1]}", twin)]
    return out


# --------------------------------------------------------------------------------------------
# casing (fixed frame)
# --------------------------------------------------------------------------------------------
def casing(layout: Layout):
    """The casing, a body of revolution about x [mm]: the drive's bay, the cylinder, ends."""
    bd = build123d_module()
    L = layout
    xl, xr = L.case_x
    w, rb = L.wall, L.shaft_radius + L.gap
    out_r = L.case_radius + w
    prof = [
        (xl - w, rb), (xl - w, out_r), (xr + w, out_r), (xr + w, rb), (xr, rb), (xr, L.cyl_r[1]),
        (L.case_step, L.cyl_r[1]), (L.case_step, L.case_radius), (xl, L.case_radius), (xl, rb),
    ]  # fmt: skip
    face = bd.Face(
        bd.Wire.make_polygon([bd.Vector(x * _MM, 0.0, z * _MM) for x, z in prof], close=True)
    )
    return bd.Solid.revolve(face, 360.0, bd.Axis.X)
