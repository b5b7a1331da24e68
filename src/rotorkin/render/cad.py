"""CAD writers for planar parts (:class:`rotorkin.cams.planar.Part`): DXF, STL, STEP, CSV, in mm.

* DXF (ezdxf, R2010, ``$INSUNITS = 4`` mm, ``$MEASUREMENT = 1`` metric): every
  closed curve as a closed LWPOLYLINE whose vertices lie on the model curve and
  whose chords stay within ``export.tolerance`` of it; exact circles as CIRCLE
  entities; layers ``PROFILE`` (the outline to cut), ``PITCH`` (roller-centre
  curve, dashed), ``ROLLER``, ``LINKAGE``, ``CASING``, ``AXIS`` (centre marks).
* STL (manifold3d extrusion, written by trimesh, binary): the outline polygon
  extruded from z = 0 to the part's thickness; one watertight solid per part.
* STEP (build123d, the optional ``[cad]`` extra, imported lazily): the same
  prism as the STL (planar side faces on the outline polygon), with an exact
  cylinder for a circular outline; one valid solid per part. (A periodic
  spline through the vertices gives a smoother side face, but OpenCascade
  then integrates its volume 0.7 % off: the polygon keeps the file checkable.)
* CSV: one file per curve, columns ``x_mm,y_mm``, one row per vertex (a closed
  curve's first vertex is not repeated).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorkin.core.angles import fmt_mm
from rotorkin.core.errors import ParameterError, RotorkinError

__all__ = [
    "DEFAULT_TOLERANCE",
    "write_dxf",
    "write_stl",
    "write_step",
    "write_csv",
    "part_mesh",
    "part_solid",
    "build123d_module",
    "positive_key",
    "check_tolerance",
    "check_thickness",
]

_MM = 1e3
#: DXF layer -> (ACI colour, linetype).
LAYERS = {
    "PROFILE": (7, "CONTINUOUS"),
    "PITCH": (1, "DASHED"),
    "ROLLER": (3, "CONTINUOUS"),
    "LINKAGE": (8, "CONTINUOUS"),
    "CASING": (5, "DASHED"),
    "AXIS": (4, "CENTER"),
}


def write_dxf(part, path, name: str = "") -> Path:
    """Write the drawing of ``part`` to a DXF file in mm; returns the path.

    The file's ``$PROJECTNAME`` holds ``name`` and a TEXT on layer ``NOTES``
    (below the drawing) the part's title.
    """
    import ezdxf
    from ezdxf import units

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
        attribs = {"layer": c.layer}
        if c.circle is not None:
            cx, cy, r = (v * _MM for v in c.circle)
            msp.add_circle((cx, cy), r, dxfattribs=attribs)
        else:
            pts = [(float(x), float(y)) for x, y in np.asarray(c.points) * _MM]
            msp.add_lwpolyline(pts, format="xy", close=c.closed, dxfattribs=attribs)
    if part.title:
        lo = np.min(np.concatenate([np.asarray(c.points) for c in part.curves]), axis=0) * _MM
        size = max(1.0, 0.02 * float(np.ptp(np.asarray(part.outline.points)[:, 0]) * _MM))
        msp.add_text(
            part.title,
            height=size,
            dxfattribs={"layer": "NOTES", "insert": (lo[0], lo[1] - 3 * size)},
        )
    path = Path(path)
    doc.saveas(path)
    return path


def part_mesh(part):
    """The part's outline extruded to its thickness, as a watertight ``trimesh.Trimesh`` [mm].

    The polygon is extruded by manifold3d (a robust triangulation of any simple
    polygon); z runs from 0 to the thickness.
    """
    import manifold3d
    import trimesh

    pts = np.asarray(part.outline.points, dtype=float) * _MM
    if _signed_area(pts) < 0.0:
        pts = pts[::-1]
    solid = manifold3d.CrossSection([pts]).extrude(float(part.thickness) * _MM)
    m = solid.to_mesh()
    mesh = trimesh.Trimesh(
        vertices=np.asarray(m.vert_properties)[:, :3], faces=np.asarray(m.tri_verts), process=True
    )
    if not mesh.is_watertight:  # pragma: no cover - manifold3d output is manifold by design
        raise RotorkinError(f"the mesh of {part.name} is not watertight; please report this")
    return mesh


def write_stl(part, path) -> Path:
    """Write the extruded part as a binary STL in mm; returns the path."""
    path = Path(path)
    part_mesh(part).export(path, file_type="stl")
    return path


def build123d_module():
    """build123d (the optional ``[cad]`` extra), or one clear error naming the install."""
    try:
        import build123d
    except ImportError:
        raise RotorkinError(
            'STEP export needs build123d, an optional extra: pip install "rotorkin[cad]"'
        ) from None
    return build123d


def part_solid(part):
    """The extruded part as one build123d ``Solid`` [mm] (raises without build123d).

    A circular outline gives an exact cylinder, any other a prism on its polygon.
    """
    bd = build123d_module()
    t = float(part.thickness) * _MM
    o = part.outline
    if o.circle is not None:
        cx, cy, r = (v * _MM for v in o.circle)
        return bd.Solid.make_cylinder(r, t, bd.Plane.XY.move(bd.Location((cx, cy, 0.0))))
    pts = np.asarray(o.points, dtype=float) * _MM
    if _signed_area(pts) < 0.0:
        pts = pts[::-1]
    vecs = [bd.Vector(float(x), float(y), 0.0) for x, y in pts]
    wire = bd.Wire.make_polygon(vecs, close=True)
    return bd.Solid.extrude(bd.Face(wire), bd.Vector(0.0, 0.0, t))


def write_step(part, path) -> Path:
    """Write the extruded part as STEP (AP214, mm); returns the path."""
    bd = build123d_module()
    solid = part_solid(part)
    if not solid.is_valid:  # pragma: no cover
        raise RotorkinError(f"the solid of {part.name} is not valid; please report this")
    path = Path(path)
    bd.export_step(solid, str(path))
    return path


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
