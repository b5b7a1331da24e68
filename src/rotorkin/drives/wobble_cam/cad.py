"""CAD export of the wobble-cam drive: the spherical cam as STL, CSV and DXF, the engine as STEP.

The cam is the shell ``R_i <= |p| <= R_o`` (``R_i, R_o = r -+ shell_thickness/2``)
minus the 4 grooves (:mod:`rotorkin.drives.wobble_cam.cam`). A groove is the region swept by
its cross-section in the normal plane of the centre-line, the plane spanned by the
radial direction ``e_r`` and the wall normal ``n``: between the walls
``lambda e_r +- h n`` (``h = rho + c/2``, the roller radius plus half the running
clearance) and from just inside the inner surface out to the groove bottom at
``R_b = R_i + groove_depth``. Where the figure-eight crosses itself the two branches
overlap and the groove is cut through. The pieces of the sweeps:
:mod:`rotorkin.drives.wobble_cam.cad_grooves`.

* STL (trimesh + manifold3d): the closed shell with its blind grooves; the shells are
  icospheres refined until their chordal deviation is within ``export.tolerance``
  (default 0.01 mm); the groove pieces are triangulated sweeps whose sections are spaced
  so that every vertex path stays within half the tolerance, and the groove-bottom arc
  (the sphere R_b) too (a facet of the doubly curved groove bottom deviates by about the
  sum).
* STEP (build123d, optional ``[cad]`` extra): the engine as one assembly of named parts
  at theta = 0 (:mod:`rotorkin.drives.wobble_cam.cad_assembly`): the cam in two halves
  with bores, shaft slots and assembly windows, the lobes the slots free, the plate and
  its shafts and rollers, the rails, the rotors, the Z-shaft and a casing.
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
from rotorkin.drives.wobble_cam import checks as cam_checks
from rotorkin.drives.wobble_cam.cad_grooves import (
    groove_pieces,
    piece_samples,
    section_uv,
    solid_volume,
    tool_floor,
)
from rotorkin.drives.wobble_cam.cad_layout import layout_from_config
from rotorkin.drives.wobble_cam.cam_walls import unguided_stretches
from rotorkin.render.cad import build123d_module
from rotorkin.studies.checks import Check

__all__ = [
    "export_wobble",
    "setup",
    "closed_polyline",
    "groove_curves",
    "groove_pieces",
    "cam_mesh",
    "solid_volume",
    "freed_regions",
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
        stretches = unguided_stretches(drive, sph.wall_gaps(drive, cam))
        for c in sph.groove_crossings(drive):
            w.writerow(
                [sph.ROLLER_NAMES[c.rollers[0]], sph.ROLLER_NAMES[c.rollers[1]]]
                + [f"{np.degrees(x):.6f}" for x in c.theta]
                + [f"{x * _MM:.6f}" for x in c.point]
                + [f"{np.degrees(c.angle):.6f}", f"{_unguided(c, stretches) * _MM:.6f}"]
            )


def _unguided(crossing, stretches) -> float:
    """Longest path of either branch's roller with a wall missing at the crossing [m]."""
    out = 0.0
    for roller, theta in zip(crossing.rollers, crossing.theta, strict=True):
        for k, lo, hi, length in stretches:
            if k == roller and (theta - lo) % crossing.period <= hi - lo:
                out = max(out, length)
    return out


def _export_dxf(path: Path, curves: dict) -> None:
    import ezdxf  # the [cad] extra; imported where it is used

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
# STL
# --------------------------------------------------------------------------------------------
def _sphere_mesh(radius: float, tol: float):
    """Icosphere with vertices on the sphere, refined until within tol; (mesh, deviation)."""
    import trimesh  # the [cad] extra; imported where it is used

    for sub in range(1, 9):
        m = trimesh.creation.icosphere(subdivisions=sub, radius=radius)
        dev = radius - float(np.min(np.abs(np.sum(m.face_normals * m.triangles[:, 0], 1))))
        if dev <= tol or sub == 8:
            return m, dev
    raise AssertionError  # pragma: no cover


def _piece_mesh(sections):
    """Closed triangle mesh of swept sections (m, k, 3), ends capped, outward normals."""
    import trimesh  # the [cad] extra; imported where it is used

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


def _signed_volume(mesh) -> float:
    """Enclosed volume of a triangle mesh by its tetrahedra from the origin [its units^3]."""
    t = mesh.triangles
    return float(np.einsum("ij,ij->", t[:, 0], np.cross(t[:, 1], t[:, 2])) / 6.0)


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
    import trimesh  # the [cad] extra; imported where it is used

    outer, dev_o = _sphere_mesh(cam.outer_radius, tol)
    inner, dev_i = _sphere_mesh(cam.inner_radius, tol)
    floor = tool_floor(drive, cam)
    h = cam.groove_half_width
    uv = section_uv(cam, np.sqrt(floor**2 - h**2), 0.5 * tol)
    beta = np.arcsin(h / cam.bottom_radius)
    dev_arc = cam.bottom_radius * (1.0 - np.cos(beta / (len(uv) - 3)))
    tools, devs, count = [], [dev_o, dev_i], 0
    for roller, t0, t1 in groove_pieces(drive):
        _, s, sag = piece_samples(drive, roller, t0, t1, uv, 0.5 * tol)
        tools.append(_piece_mesh(s))
        devs.append(sag + dev_arc)
        count += len(s)
    mesh = trimesh.boolean.difference([outer, inner, *tools], engine="manifold")
    # a sliver the boolean may leave where two pieces' shared end sections meet a wall
    parts = mesh.split(only_watertight=False)
    keep = [m for m in parts if abs(_signed_volume(m)) > 1e-9 * abs(_signed_volume(mesh))]
    if len(keep) < len(parts):
        mesh = trimesh.util.concatenate(keep)
    mesh.apply_scale(_MM)
    facts = {
        "deviation_mm": max(devs) * _MM,
        "pieces": len(tools),
        "sections": count,
        "faces": len(mesh.faces),
    }
    return mesh, facts


# --------------------------------------------------------------------------------------------
# entry point
# --------------------------------------------------------------------------------------------
def export_wobble(cfg: dict, fmt: str, stage_dir, name: str, progress=None) -> list[Path]:
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
    progress : callable, optional
        ``progress(label, done, total)`` before each group of parts of the STEP assembly.

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
    layout = layout_from_config(cfg)
    from rotorkin.drives.wobble_cam.cad_assembly import build_parts, write_assembly

    parts = build_parts(layout, tol, progress)
    title = str(cfg.get("title") or name)
    path = stage / f"{name}.step"
    if progress is not None:
        progress("step file", 6, 7)
    write_assembly(parts, layout, path, name, title)
    return [path]


def _fmt(value, digits=4) -> str:
    return f"{value:.{digits}g}" if isinstance(value, float) else str(value)


def check_rows(cfg: dict) -> list[tuple[str, str]]:
    """(check, value) rows of the spherical cam's grooves (:mod:`.cam`)."""
    drive, cam = sph.from_config(cfg)
    crossings = sph.groove_crossings(drive)
    s = sph.summary(drive, cam)
    peaks = sph.pressure_angle_peaks(drive, cam)

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
    rows += [
        (f"{label}: groove width mm (roller + running clearance)",
         f"{_fmt(s['cam_groove_width_mm'], 6)} ({_fmt(2e3 * cam.roller_radius)} + "
         f"{_fmt(s['cam_running_clearance_mm'])})"),
        (f"{label}: both walls along a roller's contact lines, share of the turn",
         f"{100.0 * s['cam_both_walls_fraction']:.2f} %"),
        (f"{label}: regions freed by the shaft slots (no part turning with the cam holds them)",
         str(freed_regions(drive))),
    ]  # fmt: skip
    return rows


def freed_regions(drive) -> int:
    """Pieces of the shell a through slot along every groove cuts off the main body.

    The grooves' centre-lines split the sphere into ``F = E - V + 1 + C`` regions (Euler on
    the sphere): V crossings, E arcs between the passes (2 per crossing; a groove that
    crosses nothing is a closed arc of its own), C connected sets of grooves. A slot
    through the shell along every groove makes each region a piece of its own; all but
    one are freed (8 lobes for the paper's 4 figure-eights).
    """
    crossings = sph.groove_crossings(drive)
    rollers = sph.distinct_grooves(drive)
    parent = {i: i for i in rollers}

    def root(i):
        while parent[i] != i:
            i = parent[i]
        return i

    for c in crossings:
        parent[root(c.rollers[0])] = root(c.rollers[1])
    passes = {i: 0 for i in rollers}
    for c in crossings:
        for i in c.rollers:
            passes[i] += 1
    v = len(crossings)
    e = sum(max(p, 1) for p in passes.values())
    loops = sum(1 for p in passes.values() if p == 0)  # closed arcs with no vertex
    comps = len({root(i) for i in rollers})
    return e - (v + loops) + 1 + comps - 1


#: Name of the check of the STEP assembly's sizes.
ASSEMBLY_CHECK = "wobble cam: STEP assembly parts that do not fit"


def checks(cfg: dict) -> list:
    """The cam's checks with their margins (:func:`rotorkin.drives.wobble_cam.checks.checks`)
    and the sizes of the STEP assembly (:func:`cad_layout.layout_from_config`).

    A bore, slot, shaft, plate or bearing span that does not fit makes
    :data:`ASSEMBLY_CHECK` fail (value 1 against 0; ``where`` holds the line ``export``
    refuses it with, naming the key and what is admissible): every command flags what
    ``export --format step`` refuses.
    """
    if "cam" not in cfg:
        return []
    parts = sph.from_config(cfg)  # the drive and the cam, built and validated once
    found = cam_checks.checks(cfg, parts)
    try:
        layout_from_config(cfg, parts)
        bad, key, where = 0.0, "cam.bore_diameter", ""
    except ParameterError as exc:
        bad, key, where = 1.0, exc.name, str(exc)
    found.append(Check(ASSEMBLY_CHECK, key, bad, 0.0, "", True, where))
    return found


def check_cam(cfg: dict) -> None:
    """The cam's proportions, checked as ``rotorkin export`` checks them.

    :func:`rotorkin.drives.wobble_cam.cam.from_config`: ``cam.roller_radius``,
    ``cam.shell_thickness`` and ``cam.groove_depth`` against the sphere radius and each
    other. (The roller's undercut limit depends on the plate tilt, and the default roller
    fits only near the paper's 45 deg; ``rotorkin export`` checks it.)
    """
    sph.from_config(cfg)
