"""CAD writers for planar parts (:class:`rotorkin.cams.planar.Part`): DXF, STL, STEP, CSV, in mm.

* DXF (ezdxf, R2010, ``$INSUNITS = 4`` mm, ``$MEASUREMENT = 1`` metric, ``$EXTMIN`` /
  ``$EXTMAX`` set to the drawing's extents): a cut contour made of lines and arcs
  (impeller, bore with keyway) as one closed LWPOLYLINE with bulges (exact arcs); one
  with B-spline edges (a cam's profile, a gear's pitch curve) as SPLINE entities
  carrying the same control points and knots as the STEP file, joined by LINE/ARC
  entities; exact circles as CIRCLE; reference curves (pitch curve, linkage) as
  LWPOLYLINEs whose chords stay within ``export.tolerance`` of the model curve.
  Layers ``PROFILE`` (the outline to cut), ``BORE`` (the shaft bore and keyway, cut
  too), ``RELIEF`` (a recess turned over part of the width, its extent in the notes),
  ``PITCH`` (dashed), ``ROLLER``, ``LINKAGE``, ``CASING``, ``AXIS``, ``NOTES`` (title,
  fits, gaps).
* STL (manifold3d extrusion of each slab's polygons, holes cut, the cuts subtracted,
  written by trimesh, binary): one watertight solid per part.
* STEP (build123d / OpenCascade, the optional ``[cad]`` extra, imported lazily): each
  slab's face bounded by the exact edges (``Geom_BSplineCurve`` pieces, circles,
  lines), extruded, the slabs fused, the cuts subtracted: one valid solid per part,
  named after it (:func:`rotorkin.render.workshop.write_step`).
* CSV: one file per curve, columns ``x_mm,y_mm``, one row per vertex (a closed
  curve's first vertex is not repeated).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin.cams import edges as ce
from rotorkin.core.angles import fmt_mm
from rotorkin.core.errors import ParameterError, RotorkinError
from rotorkin.render import workshop

__all__ = [
    "DEFAULT_TOLERANCE",
    "write_dxf",
    "write_stl",
    "write_step",
    "write_assembly",
    "write_csv",
    "part_mesh",
    "part_solid",
    "curve_edges",
    "build123d_module",
    "positive_key",
    "check_tolerance",
    "check_thickness",
]

_MM = 1e3
#: DXF layer -> (ACI colour, linetype).
LAYERS = {
    "PROFILE": (7, "CONTINUOUS"),
    "BORE": (6, "CONTINUOUS"),
    "PITCH": (1, "DASHED"),
    "ROLLER": (3, "CONTINUOUS"),
    "LINKAGE": (8, "CONTINUOUS"),
    "CASING": (5, "DASHED"),
    "RELIEF": (2, "DASHED"),
    "AXIS": (4, "CENTER"),
}


def curve_edges(curve) -> tuple:
    """The exact edges of a closed curve: its ``edges``, its circle, or its polygon's sides."""
    if curve.edges:
        return tuple(curve.edges)
    if curve.circle is not None:
        cx, cy, r = curve.circle
        return (ce.Arc((cx, cy), r, 0.0, 2.0 * np.pi),)
    p = np.asarray(curve.points, dtype=float)
    q = np.roll(p, -1, axis=0)
    return tuple(ce.Line(tuple(a), tuple(b)) for a, b in zip(p, q, strict=True))


# --- DXF --------------------------------------------------------------------------------------
def _full(e) -> bool:
    return isinstance(e, ce.Arc) and abs(abs(e.a1 - e.a0) - 2.0 * np.pi) < 1e-12


def _add_contour(msp, edges, attribs) -> None:
    """One closed contour of exact edges (module docstring)."""
    if len(edges) == 1 and _full(edges[0]):
        e = edges[0]
        msp.add_circle(tuple(v * _MM for v in e.centre), e.radius * _MM, dxfattribs=attribs)
        return
    if not any(isinstance(e, ce.Spline) for e in edges):
        pts = [(e.start[0] * _MM, e.start[1] * _MM,
                np.tan(0.25 * (e.a1 - e.a0)) if isinstance(e, ce.Arc) else 0.0)
               for e in edges]  # fmt: skip
        msp.add_lwpolyline(pts, format="xyb", close=True, dxfattribs=attribs)
        return
    for e in edges:
        if isinstance(e, ce.Line):
            msp.add_line(tuple(v * _MM for v in e.start), tuple(v * _MM for v in e.end),
                         dxfattribs=attribs)  # fmt: skip
        elif isinstance(e, ce.Arc):
            a0, a1 = sorted((np.degrees(e.a0), np.degrees(e.a1)))
            msp.add_arc(tuple(v * _MM for v in e.centre), e.radius * _MM, a0, a1,
                        dxfattribs=attribs)  # fmt: skip
        else:
            msp.add_open_spline([(float(x), float(y)) for x, y in np.asarray(e.poles) * _MM],
                                degree=3, knots=[float(k) for k in e.knots],
                                dxfattribs=attribs)  # fmt: skip


def write_dxf(part, path, name: str = "") -> Path:
    """Write the drawing of ``part`` to a DXF file in mm; returns the path.

    The file's ``$PROJECTNAME`` holds ``name``; TEXT lines on layer ``NOTES`` (below
    the drawing) the part's title and notes; ``$EXTMIN`` / ``$EXTMAX`` its extents.
    """
    import ezdxf
    from ezdxf import bbox, units, zoom

    doc = ezdxf.new("R2010", setup=True)
    doc.units = units.MM
    doc.header["$MEASUREMENT"] = 1
    if name:
        doc.header["$PROJECTNAME"] = name
    for layer, (colour, linetype) in LAYERS.items():
        doc.layers.add(layer, color=colour, linetype=linetype)
    doc.layers.add("NOTES", color=7)
    msp = doc.modelspace()
    for c in part.curves:
        if c.layer not in doc.layers:
            doc.layers.add(c.layer, color=7)
        attribs = {"layer": c.layer}
        if c.edges or c.circle is not None:
            _add_contour(msp, curve_edges(c), attribs)
        else:
            pts = [(float(x), float(y)) for x, y in np.asarray(c.points) * _MM]
            msp.add_lwpolyline(pts, format="xy", close=c.closed, dxfattribs=attribs)
    lines = [part.title, *part.notes] if part.title else list(part.notes)
    if lines:
        lo = np.min(np.concatenate([np.asarray(c.points) for c in part.curves]), axis=0) * _MM
        size = max(1.0, 0.02 * float(np.ptp(np.asarray(part.outline.points)[:, 0]) * _MM))
        for i, text in enumerate(lines):
            at = (lo[0], lo[1] - (3 + 2 * i) * size)
            msp.add_text(text, height=size, dxfattribs={"layer": "NOTES", "insert": at})
    box = bbox.extents(msp, fast=False)
    msp.dxf.extmin, msp.dxf.extmax = box.extmin, box.extmax  # saved into $EXTMIN, $EXTMAX
    doc.header["$EXTMIN"], doc.header["$EXTMAX"] = box.extmin, box.extmax
    zoom.center(msp, box.center, box.size)
    path = Path(path)
    doc.saveas(path)
    return path


# --- STL --------------------------------------------------------------------------------------
def _ccw(pts):
    pts = np.asarray(pts, dtype=float)
    return pts if _signed_area(pts) >= 0.0 else pts[::-1]


def _z_range(part, slab) -> tuple[float, float]:
    """The z range [m] a slab of ``part.cuts`` is extruded over: through an end face it reaches."""
    lo = min(s.z0 for s in part.solid_slabs())
    hi = max(s.z1 for s in part.solid_slabs())
    pad = hi - lo
    return (
        slab.z0 - pad if slab.z0 <= lo else slab.z0,
        slab.z1 + pad if slab.z1 >= hi else slab.z1,
    )


def _around(curve):
    """A circle's polygon with its sides tangent to it (so that a cut removes all of the disc),
    any other curve's points."""
    if curve.circle is None:
        return curve.points
    cx, cy, r = curve.circle
    p = np.asarray(curve.points, dtype=float) - (cx, cy)
    return p / np.cos(np.pi / len(p)) + (cx, cy)


def part_mesh(part):
    """The part's slabs extruded and joined, less its cuts: a watertight ``trimesh.Trimesh`` [mm].

    Each slab's outlines (counter-clockwise) and holes (clockwise) are extruded by
    manifold3d (a robust triangulation of any polygon with holes); z as in the part.
    """
    import manifold3d
    import trimesh

    def prism(slab, z0, z1, cut=False):
        polys = [_ccw(_around(c) if cut else c.points) * _MM for c in slab.outlines]
        polys += [_ccw(c.points)[::-1] * _MM for c in slab.holes]
        piece = manifold3d.CrossSection(polys).extrude((z1 - z0) * _MM)
        return piece.translate((0.0, 0.0, z0 * _MM))

    solid = None
    for slab in part.solid_slabs():
        piece = prism(slab, slab.z0, slab.z1)
        solid = piece if solid is None else solid + piece
    for slab in part.cuts:
        solid = solid - prism(slab, *_z_range(part, slab), cut=True)
    m = solid.to_mesh()
    mesh = trimesh.Trimesh(
        vertices=np.asarray(m.vert_properties)[:, :3], faces=np.asarray(m.tri_verts), process=False
    )
    if not mesh.is_watertight:  # pragma: no cover - manifold3d output is manifold by design
        raise RotorkinError(f"the mesh of {part.name} is not watertight; please report this")
    return mesh


def write_stl(part, path) -> Path:
    """Write the part's solid as a binary STL in mm; returns the path."""
    path = Path(path)
    part_mesh(part).export(path, file_type="stl")
    return path


# --- STEP -------------------------------------------------------------------------------------
def build123d_module():
    """build123d (the optional ``[cad]`` extra), or one clear error naming the install."""
    try:
        import build123d
    except ImportError:
        raise RotorkinError(
            'STEP export needs build123d, an optional extra: pip install "rotorkin[cad]"'
        ) from None
    return build123d


def _occ_edge(e):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
    from OCP.collections import Array1_double, Array1_gp_Pnt, Array1_int
    from OCP.GC import GC_MakeArcOfCircle, GC_MakeCircle
    from OCP.Geom import Geom_BSplineCurve
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

    def pnt(p):
        return gp_Pnt(float(p[0]) * _MM, float(p[1]) * _MM, 0.0)

    if isinstance(e, ce.Line):
        return BRepBuilderAPI_MakeEdge(pnt(e.start), pnt(e.end)).Edge()
    if isinstance(e, ce.Arc):
        if _full(e):
            axis = gp_Ax2(pnt(e.centre), gp_Dir(0, 0, 1))
            return BRepBuilderAPI_MakeEdge(GC_MakeCircle(axis, e.radius * _MM).Value()).Edge()
        mid = e.evaluate(0.5)
        arc = GC_MakeArcOfCircle(pnt(e.start), pnt(mid), pnt(e.end)).Value()
        return BRepBuilderAPI_MakeEdge(arc).Edge()
    poles = np.asarray(e.poles, dtype=float)
    knots, mults = np.unique(np.asarray(e.knots, dtype=float), return_counts=True)
    P = Array1_gp_Pnt(1, len(poles))
    for i, p in enumerate(poles, 1):
        P.SetValue(i, pnt(p))
    K, M = Array1_double(1, len(knots)), Array1_int(1, len(knots))
    for i, (k, m) in enumerate(zip(knots, mults, strict=True), 1):
        K.SetValue(i, float(k))
        M.SetValue(i, int(m))
    return BRepBuilderAPI_MakeEdge(Geom_BSplineCurve(P, K, M, 3)).Edge()


def _wire(curve):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeWire

    mk = BRepBuilderAPI_MakeWire()
    for e in curve_edges(curve):
        mk.Add(_occ_edge(e))
    if not mk.IsDone():  # pragma: no cover - the chains are closed by construction
        raise RotorkinError(f"the contour {curve.name} does not close; please report this")
    return mk.Wire()


def _slab_solids(slab, bd, z0=None, z1=None):
    z0, z1 = (slab.z0 if z0 is None else z0), (slab.z1 if z1 is None else z1)
    t = (z1 - z0) * _MM
    out = []
    holes = [bd.Wire(_wire(h)) for h in slab.holes]
    for outline in slab.outlines:
        outer = bd.Wire(_wire(outline))
        inner = [w for w, h in zip(holes, slab.holes, strict=True)
                 if _inside(np.asarray(h.points)[0], np.asarray(outline.points))]  # fmt: skip
        face = bd.Face(outer, inner)
        solid = bd.Solid.extrude(face, bd.Vector(0.0, 0.0, t))
        out.append(solid.moved(bd.Location((0.0, 0.0, z0 * _MM))) if z0 else solid)
    return out


def _inside(p, poly) -> bool:
    """Whether the point ``p`` lies inside the closed polygon (even-odd rule)."""
    x, y = poly[:, 0], poly[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = (y > p[1]) != (yn > p[1])
    with np.errstate(divide="ignore", invalid="ignore"):
        xi = x + (p[1] - y) * (xn - x) / (yn - y)
    return bool(np.count_nonzero(cross & (p[0] < xi)) % 2)


def part_solid(part):
    """The part as one build123d ``Solid`` [mm] (raises without build123d).

    Each slab's face is bounded by the exact edges of its contours (B-spline
    pieces, arcs, lines, full circles) and extruded; the slabs are fused (coplanar
    faces merged) and the cuts subtracted.
    """
    bd = build123d_module()
    solids = [s for slab in part.solid_slabs() for s in _slab_solids(slab, bd)]
    solid = solids[0] if len(solids) == 1 else solids[0].fuse(*solids[1:]).clean()
    tools = [s for slab in part.cuts for s in _slab_solids(slab, bd, *_z_range(part, slab))]
    if tools:
        solid = solid.cut(*tools).clean()
    found = solid.solids()
    if len(found) != 1 or not found[0].is_valid:  # pragma: no cover - a failed boolean
        raise RotorkinError(f"the solid of {part.name} is not one valid solid; please report this")
    return found[0]


def write_step(part, path, title: str = "", solid=None) -> Path:
    """Write the part as its own STEP file (AP214, mm), one product named after it.

    ``solid`` is :func:`part_solid` of the part when already built. Returns the path.
    """
    solid = part_solid(part) if solid is None else solid
    return workshop.write_step(path, [(part.name, solid, (0.0, 0.0, 0.0, 0.0))], part.name,
                               title, assembly=False)  # fmt: skip


def write_assembly(parts, path, name: str, title: str = "", solids=None) -> Path:
    """Write every part, placed as in its machine (``Part.placement``), as one STEP assembly.

    The assembly product is ``name``; each component and its product carries the part's
    name. ``solids`` are the parts' solids when already built.
    """
    solids = [part_solid(p) for p in parts] if solids is None else solids
    items = [(p.name, s, p.placement.as_tuple()) for p, s in zip(parts, solids, strict=True)]
    return workshop.write_step(path, items, name, title, assembly=True)


# --- CSV --------------------------------------------------------------------------------------
def write_csv(part, folder, stem: str) -> list[Path]:
    """Write one ``<stem>_<curve>.csv`` per curve of ``part`` (``x_mm,y_mm``); returns the paths."""
    out = []
    for c in part.curves:
        path = Path(folder) / f"{stem}_{c.name}.csv"
        np.savetxt(path, np.asarray(c.points) * _MM, delimiter=",", header="x_mm,y_mm",
                   comments="", fmt="%.9f")  # fmt: skip
        out.append(path)
    return out


def _signed_area(pts) -> float:
    x, y = pts[:, 0], pts[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


# --- checks of config values ------------------------------------------------------------------
#: Default chordal tolerance [m] (``export.tolerance``).
DEFAULT_TOLERANCE = 1e-5


def positive_key(cfg: dict, section: str, key: str, default: float) -> float:
    """A positive length ``cfg[section][key]`` [m] (``default`` when absent)."""
    v = float((cfg.get(section) or {}).get(key, default))
    if not (np.isfinite(v) and v > 0.0):
        raise ParameterError(f"{section}.{key}", fmt_mm(v), f"{key} > 0 mm")
    return v


def check_tolerance(cfg: dict, scale: float) -> float:
    """``export.tolerance`` [m], checked against the part's size ``scale`` [m]."""
    tol = positive_key(cfg, "export", "tolerance", DEFAULT_TOLERANCE)
    if not (1e-8 <= tol <= 0.01 * scale):
        raise ParameterError(
            "export.tolerance",
            fmt_mm(tol),
            f"0.00001 mm <= tolerance <= {fmt_mm(0.01 * scale)} (1 % of the part's size)",
        )
    return tol


def check_thickness(cfg: dict, diameter: float, what: str) -> float:
    """``cam.thickness`` [m], checked: ``0 < thickness <= diameter`` (the part's outer diameter)."""
    t = positive_key(cfg, "cam", "thickness", 0.02)
    if not t <= diameter:
        raise ParameterError(
            "cam.thickness",
            fmt_mm(t),
            f"0 mm < thickness <= {fmt_mm(diameter)} ({what}: a plate thicker than it is wide "
            "is no cam plate)",
        )
    return t
