"""CAD export of the wobble-cam drive's spherical cam: STL, STEP, CSV and DXF, in mm.

The solid is the shell ``R_i <= |p| <= R_o`` (``R_i, R_o = r -+ shell_thickness/2``)
minus the 4 grooves (:mod:`rotorkin.drives.wobble_cam.cam`). A groove is the region swept by
its cross-section in the normal plane of the centre-line, the plane spanned by the
radial direction ``e_r`` and the wall normal ``n``: between the walls
``lambda e_r +- rho n`` and from just inside the inner surface out to the groove bottom,
the sphere ``R_b = R_i + groove_depth``. Where the figure-eight crosses itself the two
branches overlap and the groove is cut through.

A closed swept tube that crosses itself is not a valid solid (neither for manifold3d
nor for OpenCascade), so every groove is split into open pieces at the middles
between its self-crossings (2 pieces for a figure-eight, cut at the lobe tips); the
pieces share their end sections and are united.

* STL (trimesh + manifold3d): the shells are icospheres refined until their chordal
  deviation is within ``export.tolerance`` (default 0.01 mm); the groove pieces are
  triangulated sweeps whose sections are spaced so that every vertex path stays within
  half the tolerance, and the groove-bottom arc too (a facet of the doubly curved
  groove bottom deviates by about the sum).
* STEP (build123d, optional ``[cad]`` extra): exact spheres; each piece is lofted
  through rectangular sections at the same parameters (the walls exact at the
  sections, B-spline between); the pieces of a groove are fused, cut to the layer
  ``R_i..R_b`` (exact spherical bottom) and subtracted from the shell. Sweeps
  (``BRepOffsetAPI_MakePipeShell`` in Frenet, corrected-Frenet or auxiliary-spine mode)
  failed to make a solid of these pieces, hence the loft.
* CSV: one point list per curve (``x_mm,y_mm,z_mm``, closed curves, first point not
  repeated), plus ``<name>_crossings.csv``.
* DXF (ezdxf): the same curves as closed 3D polylines on layers ``CENTRELINE``,
  ``WALL_INNER_SURFACE`` and ``WALL_GROOVE_BOTTOM``.

Curves are sampled uniformly in the shaft angle until the chordal deviation at the
middle of every segment is within the tolerance.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from rotorkin.core.angles import fmt_mm
from rotorkin.core.errors import ParameterError, RotorkinError
from rotorkin.drives.wobble_cam import cam as sph
from rotorkin.render.cad import build123d_module

__all__ = [
    "export_wobble",
    "setup",
    "closed_polyline",
    "groove_curves",
    "groove_pieces",
    "cam_mesh",
    "cam_step_solid",
    "solid_volume",
    "FORMATS",
]

#: Formats handled by :func:`export_wobble`.
FORMATS = ("stl", "step", "csv", "dxf")
#: Default chordal tolerance [m] (config ``export.tolerance``).
DEFAULT_TOLERANCE = 1e-5
#: Finest tolerance accepted [m]: the STL of the example is then 37 MB (0.01 mm: 10 MB).
_MIN_TOLERANCE = 2e-6
_MM = 1e3
_LAYERS = {
    "centreline": ("CENTRELINE", 1),
    "inner": ("WALL_INNER_SURFACE", 5),
    "bottom": ("WALL_GROOVE_BOTTOM", 3),
}


def setup(cfg: dict):
    """Drive, cam and tolerance of a validated config; checks the roller radius.

    Returns
    -------
    (WobbleCam, SphericalCam, float)
        The tolerance [m].
    """
    drive, cam = sph.from_config(cfg)
    tol = float((cfg.get("export") or {}).get("tolerance", DEFAULT_TOLERANCE))
    if not (np.isfinite(tol) and _MIN_TOLERANCE <= tol <= 0.1 * cam.roller_radius):
        raise ParameterError(
            "export.tolerance",
            fmt_mm(tol),
            f"{fmt_mm(_MIN_TOLERANCE)} <= tolerance <= {fmt_mm(0.1 * cam.roller_radius)} (finer "
            "makes STL files beyond 50 MB; coarser than a tenth of the roller radius loses the "
            "groove's shape)",
        )
    try:
        sph.check_roller_radius(drive, cam)
    except ParameterError as exc:
        raise ParameterError(sph.config_key(exc.name), exc.value, exc.admissible) from None
    return drive, cam, tol


# --------------------------------------------------------------------------------------------
# curves
# --------------------------------------------------------------------------------------------
def _segment_sag(p, mid):
    """Distance of ``mid`` (n, 3) from the segments ``p[k] -> p[k+1]`` (closed, n segments)."""
    q = np.roll(p, -1, axis=0)
    e = q - p
    e /= np.linalg.norm(e, axis=1, keepdims=True)
    w = mid - p
    return np.linalg.norm(w - np.sum(w * e, axis=1, keepdims=True) * e, axis=1)


def closed_polyline(fun, period: float, tol: float, start: int = 64):
    """Sample a closed curve uniformly in its parameter within a chordal tolerance.

    Parameters
    ----------
    fun : callable
        ``theta (n,) -> points (n, 3)`` [m], periodic with ``period``.
    period : float
        [rad].
    tol : float
        Largest distance of the curve's segment middles from the chords [m].

    Returns
    -------
    (theta, points, sag) : ndarray (n,), ndarray (n, 3), float
        ``sag`` is the deviation reached [m].
    """
    n = int(start)
    while True:
        theta = np.linspace(0.0, period, n, endpoint=False)
        p = fun(theta)
        sag = float(np.max(_segment_sag(p, fun(theta + 0.5 * period / n))))
        if sag <= tol:
            return theta, p, sag
        n = int(np.ceil(n * np.sqrt(sag / tol) * 1.1))


def groove_curves(drive, cam, tol: float) -> dict:
    """Centre-lines and wall edges of the distinct grooves as closed polylines [m].

    Keys ``groove<k>_centreline`` (on r), ``groove<k>_wall<L|R>_inner`` (the wall's
    edge on the shell's inner surface R_i) and ``groove<k>_wall<L|R>_bottom`` (its
    edge on the groove bottom R_b); k is the roller (``1``, ``1p``, ``2``, ``2p`` for
    rollers 1, 1', 2, 2'), L the ``+n`` wall (left of the roller's travel seen from
    outside). Values: ``(kind, points (n, 3), sag)`` with kind ``centreline``, ``inner``
    or ``bottom``.
    """
    period = sph.groove_period(drive)
    out = {}
    for i in sph.distinct_grooves(drive):
        fns = {
            f"groove{sph.ROLLER_SLUGS[i]}_centreline": (
                "centreline",
                lambda t, i=i: sph.groove_derivatives(drive, t)[0][i].T,
            )
        }
        for kind, rad in (("inner", cam.inner_radius), ("bottom", cam.bottom_radius)):
            for s, side in enumerate("LR"):
                fns[f"groove{sph.ROLLER_SLUGS[i]}_wall{side}_{kind}"] = (
                    kind,
                    lambda t, i=i, s=s, rad=rad: sph.groove_walls(drive, cam, t, rad)[i, s].T,
                )
        for key, (kind, fun) in fns.items():
            _, pts, sag = closed_polyline(fun, period, tol)
            out[key] = (kind, pts, sag)
    return out


def _write_csv(path: Path, pts) -> None:
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["x_mm", "y_mm", "z_mm"])
        w.writerows([f"{v:.6f}" for v in row] for row in pts * _MM)


def _write_crossings(path: Path, drive, cam) -> None:
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(
            [
                "roller_a",
                "roller_b",
                "theta_a_deg",
                "theta_b_deg",
                "x_mm",
                "y_mm",
                "z_mm",
                "crossing_angle_deg",
                "unguided_length_mm",
            ]
        )
        for c in sph.groove_crossings(drive):
            w.writerow(
                [sph.ROLLER_NAMES[c.rollers[0]], sph.ROLLER_NAMES[c.rollers[1]]]
                + [f"{np.degrees(x):.6f}" for x in c.theta]
                + [f"{x * _MM:.6f}" for x in c.point]
                + [f"{np.degrees(c.angle):.6f}", f"{c.gap_length(cam.roller_radius) * _MM:.6f}"]
            )


def _export_dxf(path: Path, curves: dict) -> None:
    import ezdxf  # the [cad] extra, imported when a DXF is written

    doc = ezdxf.new("R2010", setup=True)
    doc.units = ezdxf.units.MM
    for layer, colour in _LAYERS.values():
        doc.layers.add(layer, color=colour)
    msp = doc.modelspace()
    for kind, pts, _ in curves.values():
        msp.add_polyline3d(
            [tuple(p) for p in pts * _MM], close=True, dxfattribs={"layer": _LAYERS[kind][0]}
        )
    doc.saveas(path)


# --------------------------------------------------------------------------------------------
# groove pieces (shared by STL and STEP)
# --------------------------------------------------------------------------------------------
def groove_pieces(drive) -> list[tuple[int, float, float]]:
    """Open pieces ``(roller, theta_start, theta_end)`` [rad] covering every distinct groove.

    Cut at the middles between consecutive self-crossing parameters, so that no piece
    holds both branches of a crossing (2 pieces for a figure-eight, cut at its lobe
    tips; 2 halves for a groove that does not cross itself); ends are shared,
    ``theta_end > theta_start``.
    """
    period = sph.groove_period(drive)
    crossings = sph.groove_crossings(drive)
    out = []
    for i in sph.distinct_grooves(drive):
        own = np.sort([x for c in crossings if c.rollers == (i, i) for x in c.theta])
        if len(own):
            cuts = np.sort(0.5 * (own + np.append(own[1:], own[0] + period)) % period)
        else:
            cuts = np.array([0.0, 0.5 * period])
        ends = np.append(cuts[1:], cuts[0] + period)
        out.extend((i, float(a), float(b)) for a, b in zip(cuts, ends, strict=True))
    return out


def _section_uv(cam, lam_lo: float, tol: float):
    """Groove cross-section in (lambda, mu) coordinates of the plane (e_r, n), CCW [m]."""
    rb, rho = cam.bottom_radius, cam.roller_radius
    beta = np.arcsin(rho / rb)
    k = max(2, int(np.ceil(beta / np.arccos(1.0 - tol / rb))))
    a = np.linspace(-beta, beta, k + 1)
    arc = np.stack([rb * np.cos(a), rb * np.sin(a)], 1)
    return np.vstack([[lam_lo, -rho], arc, [lam_lo, rho]])


def _tool_floor(drive, cam) -> float:
    """Radius a little inside R_i where the tool starts, still free of wall cusps [m]."""
    kmax = sph.sharpest_bend(drive)[0]
    regular = cam.roller_radius * np.sqrt(1.0 + (drive.sphere_radius * kmax) ** 2)
    return max(cam.inner_radius - 0.05 * cam.shell_thickness, 0.5 * (cam.inner_radius + regular))


def _sections(drive, roller, theta, uv):
    """3D sections at theta: (len(theta), len(uv), 3) [m]."""
    e_r, _, n = sph.groove_frame(drive, theta)
    e_r, n = e_r[roller].T, n[roller].T  # (m, 3)
    return e_r[:, None, :] * uv[None, :, :1] + n[:, None, :] * uv[None, :, 1:]


def _piece_samples(drive, roller, t0, t1, uv, tol):
    """Section parameters on [t0, t1] such that every vertex path is within tol."""
    n = max(8, int(np.ceil(64 * (t1 - t0) / np.pi)))
    while True:
        theta = np.linspace(t0, t1, n + 1)
        s = _sections(drive, roller, theta, uv)
        mid = _sections(drive, roller, 0.5 * (theta[1:] + theta[:-1]), uv)
        e = s[1:] - s[:-1]
        e /= np.linalg.norm(e, axis=2, keepdims=True)
        w = mid - s[:-1]
        sag = float(np.max(np.linalg.norm(w - np.sum(w * e, 2, keepdims=True) * e, axis=2)))
        if sag <= tol:
            return theta, s, sag
        n = int(np.ceil(n * np.sqrt(sag / tol) * 1.1))


# --------------------------------------------------------------------------------------------
# STL
# --------------------------------------------------------------------------------------------
def _sphere_mesh(radius: float, tol: float):
    """Icosphere with vertices on the sphere, refined until within tol; (mesh, deviation)."""
    import trimesh  # the [cad] extra, imported when a mesh is built

    for sub in range(1, 9):
        m = trimesh.creation.icosphere(subdivisions=sub, radius=radius)
        dev = radius - float(np.min(np.abs(np.sum(m.face_normals * m.triangles[:, 0], 1))))
        if dev <= tol or sub == 8:
            return m, dev
    raise AssertionError  # pragma: no cover


def _piece_mesh(sections):
    """Closed triangle mesh of swept sections (m, k, 3), ends capped, outward normals."""
    import trimesh

    m, k, _ = sections.shape
    idx = np.arange(m * k).reshape(m, k)
    a, b = idx[:-1], np.roll(idx[:-1], -1, axis=1)
    c, d = np.roll(idx[1:], -1, axis=1), idx[1:]
    side = np.concatenate(
        [np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)]
    )
    fan = np.arange(1, k - 1)
    cap0 = np.stack([np.zeros_like(fan), fan + 1, fan], 1)
    cap1 = np.stack([np.zeros_like(fan), fan, fan + 1], 1) + (m - 1) * k
    mesh = trimesh.Trimesh(sections.reshape(-1, 3), np.vstack([side, cap0, cap1]), process=False)
    if mesh.volume < 0:
        mesh.invert()
    return mesh


def cam_mesh(drive, cam, tol: float):
    """The cam shell with its grooves cut, as a watertight trimesh in mm.

    The groove bottom is curved both ways (the arc of the section, the sweep), so each
    direction gets half the tolerance: the middle of a groove-bottom facet deviates by
    at most about the sum of the two sags.

    Returns
    -------
    (trimesh.Trimesh, dict)
        The mesh [mm] and build facts: ``deviation_mm`` (largest deviation by
        construction: the spheres' facets; sweep sag plus arc sag on the groove bottom),
        ``pieces``, ``sections``, ``faces``.
    """
    import trimesh

    outer, dev_o = _sphere_mesh(cam.outer_radius, tol)
    inner, dev_i = _sphere_mesh(cam.inner_radius, tol)
    floor = _tool_floor(drive, cam)
    uv = _section_uv(cam, np.sqrt(floor**2 - cam.roller_radius**2), 0.5 * tol)
    beta = np.arcsin(cam.roller_radius / cam.bottom_radius)
    dev_arc = cam.bottom_radius * (1.0 - np.cos(beta / (len(uv) - 3)))
    tools, devs, count = [], [dev_o, dev_i], 0
    for roller, t0, t1 in groove_pieces(drive):
        _, s, sag = _piece_samples(drive, roller, t0, t1, uv, 0.5 * tol)
        tools.append(_piece_mesh(s))
        devs.append(sag + dev_arc)
        count += len(s)
    mesh = trimesh.boolean.difference([outer, inner, *tools], engine="manifold")
    mesh.apply_scale(_MM)
    facts = {
        "deviation_mm": max(devs) * _MM,
        "pieces": len(tools),
        "sections": count,
        "faces": len(mesh.faces),
    }
    return mesh, facts


# --------------------------------------------------------------------------------------------
# STEP
# --------------------------------------------------------------------------------------------
def cam_step_solid(drive, cam, tol: float):
    """The cam shell with its grooves cut, as one build123d Solid in mm.

    Each groove piece (:func:`groove_pieces`) is lofted (smooth B-spline faces)
    through rectangular sections in the normal planes of the centre-line, the sections
    of :func:`cam_mesh` without the bottom arc, at the same parameters: the walls
    ``lambda e_r +- rho n`` exactly at the sections. Every piece reaches from its
    own floor just inside ``R_i`` to its own top between ``R_b`` and ``R_o``: where two
    pieces cross, their floors and tops would otherwise touch tangentially, which
    OpenCascade's booleans miss. The pieces of a groove are fused, cut to the layer
    ``R_i <= |p| <= R_b`` (exact spherical bottom) and subtracted from the shell.
    Sweeps (``BRepOffsetAPI_MakePipeShell``: Frenet, corrected Frenet, auxiliary
    spine) fail to build a solid of these pieces, hence the loft.

    Returns
    -------
    build123d.Solid
    """
    bd = build123d_module()
    s = _MM
    pieces = groove_pieces(drive)
    low = _tool_floor(drive, cam)
    margin = cam.inner_radius - low
    rho = cam.roller_radius
    tools: dict[int, list] = {}
    for k, (roller, t0, t1) in enumerate(pieces):
        frac = (k + 1.0) / (len(pieces) + 1.0)
        floor = cam.inner_radius - frac * margin
        top = cam.bottom_radius + frac * (cam.outer_radius - cam.bottom_radius)
        lam = np.sqrt(floor**2 - rho**2)
        rect = np.array([[lam, -rho], [top, -rho], [top, rho], [lam, rho]])
        uv = _section_uv(cam, lam, 0.5 * tol)
        theta, _, _ = _piece_samples(drive, roller, t0, t1, uv, 0.5 * tol)
        wires = [
            bd.Wire.make_polygon([bd.Vector(*c) for c in corners], close=True)
            for corners in _sections(drive, roller, theta, rect) * s
        ]
        tools.setdefault(roller, []).append(bd.Solid.make_loft(wires, ruled=False))
    axis = bd.Plane.YZ  # sphere poles on the cam axis, away from every groove
    ri, rb, ro = (
        bd.Solid.make_sphere(x * s, axis)
        for x in (cam.inner_radius, cam.bottom_radius, cam.outer_radius)
    )
    layer = rb - ri
    cuts = []
    for parts in tools.values():
        tool = parts[0].fuse(*parts[1:]) if len(parts) > 1 else parts[0]
        cuts.append(tool & layer)
    result = (ro - ri).cut(*cuts)
    solids = result.solids()
    if len(solids) != 1:  # pragma: no cover - a failed boolean
        raise RotorkinError(
            f"the STEP cam came out as {len(solids)} solids, not 1; report this config as a bug"
        )
    return solids[0]


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


# --------------------------------------------------------------------------------------------
# entry point
# --------------------------------------------------------------------------------------------
def export_wobble(cfg: dict, fmt: str, stage_dir, name: str) -> list[Path]:
    """Write the spherical cam of a wobble-cam config in one CAD format.

    Parameters
    ----------
    cfg : dict
        Validated config (SI): ``drive``, ``machine.pistons_per_rotor``, ``cam``
        (``roller_radius``, ``shell_thickness``, ``groove_depth``), ``export.tolerance``.
    fmt : str
        ``"stl"``, ``"step"``, ``"csv"`` or ``"dxf"``.
    stage_dir : path-like
        Existing folder to write into (the caller moves the files into place).
    name : str
        Stem of the file names.

    Returns
    -------
    list of Path
        Files written: ``<name>.stl`` / ``<name>.step`` / ``<name>.dxf``, or one
        ``<name>_<curve>.csv`` per curve plus ``<name>_crossings.csv``.

    Raises
    ------
    ParameterError
        Named by config key (e.g. ``cam.roller_radius`` where the roller undercuts).
    RotorkinError
        STEP without build123d.
    """
    if fmt not in FORMATS:
        raise ParameterError("fmt", repr(fmt), " | ".join(FORMATS))
    stage = Path(stage_dir)
    if fmt == "step":
        build123d_module()
    drive, cam, tol = setup(cfg)
    if fmt == "csv":
        written = []
        for key, (_, pts, _) in groove_curves(drive, cam, tol).items():
            path = stage / f"{name}_{key}.csv"
            _write_csv(path, pts)
            written.append(path)
        path = stage / f"{name}_crossings.csv"
        _write_crossings(path, drive, cam)
        return [*written, path]
    if fmt == "dxf":
        path = stage / f"{name}.dxf"
        _export_dxf(path, groove_curves(drive, cam, tol))
        return [path]
    if fmt == "stl":
        mesh, _ = cam_mesh(drive, cam, tol)
        if not mesh.is_watertight:  # pragma: no cover - a failed boolean
            raise RotorkinError("the cam mesh is not watertight; report this config as a bug")
        path = stage / f"{name}.stl"
        mesh.export(path)
        return [path]
    solid = cam_step_solid(drive, cam, tol)
    if not solid.is_valid:  # pragma: no cover
        raise RotorkinError("the cam solid is not valid; report this config as a bug")
    bd = build123d_module()
    path = stage / f"{name}.step"
    bd.export_step(solid, str(path))
    return [path]


def _fmt(value, digits=4) -> str:
    return f"{value:.{digits}g}" if isinstance(value, float) else str(value)


def check_rows(cfg: dict) -> list[tuple[str, str]]:
    """(check, value) rows of the spherical cam's grooves (:mod:`.cam`)."""
    drive, cam = sph.from_config(cfg)
    crossings = sph.groove_crossings(drive)
    s = sph.summary(drive, cam)
    peaks = sph.pressure_angle_peaks(drive, cam, crossings=crossings)

    def at(key):
        mu, theta, roller = (float(x) for x in peaks[key])
        who = f"roller {sph.ROLLER_NAMES[int(roller)]}" if roller >= 0 else "no roller guided"
        return f"{_fmt(np.degrees(mu))} at theta = {_fmt(np.degrees(theta))} deg ({who})"

    kmax, th_k, roller_k = sph.sharpest_bend(drive)
    label = "wobble cam"
    rows = [
        (f"{label}: roller radius mm", _fmt(cam.roller_radius * 1e3)),
        (
            f"{label}: groove min radius of curvature (tangent plane) mm",
            f"{_fmt(1e3 / kmax)} at theta = {_fmt(float(np.degrees(th_k)))} deg "
            f"(roller {sph.ROLLER_NAMES[roller_k]})",
        ),
        (f"{label}: largest roller radius free of undercut mm",
         _fmt(float(s["cam_roller_radius_limit_mm"]))),
        (f"{label}: max pressure angle, one roller away from the crossings deg", at("guided")),
        (f"{label}: max pressure angle, best-placed roller deg", at("best")),
        (f"{label}: max pressure angle, best-placed roller between both walls deg",
         at("best_guided")),
        (f"{label}: max pressure angle in the fixed frame, away from the crossings deg",
         at("fixed_guided")),
    ]  # fmt: skip
    if crossings:
        worst = min(crossings, key=lambda c: c.angle)
        rows.append(
            (
                f"{label}: groove crossings (cut through)",
                f"{s['cam_self_crossings']} self, {s['cam_crossings_between_grooves']} between "
                f"grooves; min angle {_fmt(float(np.degrees(worst.angle)))} deg, unguided "
                f"{_fmt(float(s['cam_unguided_length_max_mm']))} mm",
            )
        )
    rows.append((f"{label}: closest approach of two grooves mm",
                 _fmt(float(s["cam_groove_separation_mm"]))))  # fmt: skip
    return rows


def check_cam(cfg: dict) -> None:
    """The cam's proportions, checked as ``rotorkin export`` checks them.

    :func:`rotorkin.drives.wobble_cam.cam.from_config`: ``cam.roller_radius``,
    ``cam.shell_thickness`` and ``cam.groove_depth`` against the sphere radius and each
    other. (The roller's undercut limit depends on the plate tilt, and the default roller
    fits only near the paper's 45 deg; ``rotorkin export`` checks it.)
    """
    sph.from_config(cfg)
