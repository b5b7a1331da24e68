"""CAD export of the spherical cam: files re-read with other libraries, against geometry here.

Reference geometry: the grooves from the paper's rotation matrices written out
(tests/test_cams_spherical.py's ``Explicit``), the shell volume in closed form, the
groove volume by the tube formula on the sphere (area of a band of angular half-width
b around a closed curve of angular length L: 2 L sin b) integrated over the radius.
"""

from __future__ import annotations

import csv
import sys
import time

import numpy as np
import pytest

from rotorkin.core.errors import ParameterError, RotorkinError
from rotorkin.drives.wobble_cam import cad as cw
from rotorkin.io.config import load_config
from test_cams_spherical import Explicit

SETS = ['cam.roller_radius="4 mm"']
#: Half the groove width: the 4 mm roller plus half the ISO 286 H8/f7 running clearance at
#: 8 mm (IT8 = 22 um, IT7 = 15 um, es(f) = -13 um: mean clearance 11 + 13 + 7.5 = 31.5 um).
HALF = 0.004 + 0.5 * 31.5e-6


@pytest.fixture(scope="module")
def cfg():
    return load_config(None, "wobble-cam-engine", SETS)[0]


@pytest.fixture(scope="module")
def geom(cfg):
    return cw.setup(cfg)


@pytest.fixture(scope="module")
def stl(cfg, tmp_path_factory):
    import trimesh

    out = tmp_path_factory.mktemp("stl")
    t0 = time.perf_counter()
    paths = cw.export_wobble(cfg, "stl", out, "cam")
    seconds = time.perf_counter() - t0
    return trimesh.load(paths[0]), paths[0], seconds


def _expected_volume_mm3(drive, cam):
    """Shell minus 4 grooves, each counted once where its figure-eight overlaps itself."""
    ex = Explicit()
    t = np.linspace(0, np.pi, 200001)
    ri, rb, ro, rho = cam.inner_radius, cam.bottom_radius, cam.outer_radius, HALF
    shell = 4 / 3 * np.pi * (ro**3 - ri**3)
    grooves = 0.0
    h = 1e-6
    for i in range(4):
        u = ex.groove(t, i)
        u /= np.linalg.norm(u, axis=1, keepdims=True)
        length = np.sum(np.linalg.norm(np.diff(u, axis=0), axis=1))  # angular length [rad]
        # integral over R of 2 L sin(b) R^2 with sin b = rho / R
        band = rho * length * (rb**2 - ri**2)
        # the figure-eight crosses itself once, at u = +-pi/2: theta = (c - u)/2 ...
        c = (-np.pi / 4, 3 * np.pi / 4, np.pi / 4, 5 * np.pi / 4)[i]
        t1, t2 = (c + np.pi / 2) / 2 % np.pi, (c - np.pi / 2) / 2 % np.pi
        assert np.linalg.norm(ex.groove(t1, i) - ex.groove(t2, i)) < 1e-12
        ta = ex.groove(t1 + h, i) - ex.groove(t1 - h, i)
        tb = ex.groove(t2 + h, i) - ex.groove(t2 - h, i)
        sin = np.linalg.norm(np.cross(ta, tb)) / np.linalg.norm(ta) / np.linalg.norm(tb)
        overlap = (2 * rho) ** 2 / sin * (rb - ri)  # parallelogram of the two crossing bands
        grooves += band - overlap
    return (shell - grooves) * 1e9


def test_stl_watertight_volume_and_size(stl, geom):
    mesh, path, seconds = stl
    drive, cam, _ = geom
    assert mesh.is_watertight and mesh.is_volume
    assert mesh.volume == pytest.approx(_expected_volume_mm3(drive, cam), rel=1e-3)
    assert path.stat().st_size < 50e6
    # in mm: the outer sphere's radius
    assert np.max(np.linalg.norm(mesh.vertices, axis=1)) == pytest.approx(66.0, abs=1e-4)
    print(f"STL {path.stat().st_size / 1e6:.1f} MB, {len(mesh.faces)} faces, {seconds:.1f} s")


def test_stl_surface_within_tolerance(stl, geom):
    """Face centres and edge middles lie on the exact surfaces (spheres, ruled walls)."""
    from scipy.spatial import cKDTree

    mesh, _, _ = stl
    drive, cam, tol = geom
    ex = Explicit()
    pts = np.vstack([mesh.triangles_center, mesh.vertices[mesh.edges_unique].mean(axis=1)])
    p = pts * 1e-3
    rad = np.linalg.norm(p, axis=1)
    d_sphere = np.min(
        np.abs(rad[:, None] - [cam.inner_radius, cam.bottom_radius, cam.outer_radius]),
        axis=1,
    )
    # wall points: their distance from the nearest roller axis (the radial line through
    # the groove centre-line) is rho. Nearest axis: coarse sample, then Newton on the angle.
    wall = d_sphere > 0.5 * tol
    q = p[wall] / rad[wall, None]
    n = 2000
    t = np.linspace(0, np.pi, n, endpoint=False)
    axes = np.vstack([ex.groove(t, i) for i in range(4)])
    _, k = cKDTree(axes / np.linalg.norm(axes, axis=1, keepdims=True)).query(q)
    roller, th = k // n, t[k % n]

    def unit(theta):
        g = np.empty((len(theta), 3))
        for i in range(4):
            g[roller == i] = ex.groove(theta[roller == i], i)
        return g / np.linalg.norm(g, axis=1, keepdims=True)

    h = 1e-4
    for _ in range(5):
        a, b, c = unit(th - h), unit(th), unit(th + h)
        f1 = np.sum(q * (c - a), axis=1) / (2 * h)
        f2 = np.sum(q * (c - 2 * b + a), axis=1) / h**2
        th = th - f1 / f2
    angle = np.arctan2(np.linalg.norm(np.cross(q, unit(th)), axis=1), np.sum(q * unit(th), 1))
    dev = d_sphere.copy()
    dev[wall] = np.minimum(d_sphere[wall], np.abs(rad[wall] * np.sin(angle) - HALF))
    assert dev.max() <= tol
    print(f"STL largest deviation at face centres / edge middles: {dev.max() * 1e3:.4f} mm")


def _read_csv(path):
    with path.open() as fh:
        rows = list(csv.reader(fh))
    return rows[0], np.array(rows[1:], dtype=float)


def test_csv_curves_within_tolerance(cfg, geom, tmp_path):
    from scipy.spatial import cKDTree

    drive, cam, tol = geom
    paths = cw.export_wobble(cfg, "csv", tmp_path, "cam")
    names = {p.name for p in paths}
    assert len(paths) == 4 * 5 + 1 and "cam_crossings.csv" in names
    ex = Explicit()
    t = np.linspace(0, np.pi, 60000, endpoint=False)
    h = 1e-6
    for i, slug in enumerate(("1", "1p", "2", "2p")):
        g = ex.groove(t, i)
        e = g / np.linalg.norm(g, axis=1, keepdims=True)
        tan = ex.groove(t + h, i) - ex.groove(t - h, i)
        nrm = np.cross(e, tan / np.linalg.norm(tan, axis=1, keepdims=True))
        models = {"centreline": g}
        for kind, rad in (("inner", cam.inner_radius), ("bottom", cam.bottom_radius)):
            lam = np.sqrt(rad**2 - HALF**2)
            models[f"wallL_{kind}"] = lam * e + HALF * nrm
            models[f"wallR_{kind}"] = lam * e - HALF * nrm
        for key, model in models.items():
            header, pts = _read_csv(tmp_path / f"cam_groove{slug}_{key}.csv")
            assert header == ["x_mm", "y_mm", "z_mm"]
            pts = pts * 1e-3
            # the points lie on the model curve
            d, _ = cKDTree(model).query(pts)
            assert d.max() < 5e-6
            # the model lies within the tolerance of the closed polyline
            a, b = pts, np.roll(pts, -1, axis=0)
            _, k = cKDTree(0.5 * (a + b)).query(model, k=4)
            best = np.full(len(model), np.inf)
            for j in range(4):
                pa, pb = a[k[:, j]], b[k[:, j]]
                s = np.clip(np.sum((model - pa) * (pb - pa), 1) / np.sum((pb - pa) ** 2, 1), 0, 1)
                dist = np.linalg.norm(model - (pa + s[:, None] * (pb - pa)), axis=1)
                best = np.minimum(best, dist)
            assert best.max() <= 1.001 * tol
    with (tmp_path / "cam_crossings.csv").open() as fh:
        rows = list(csv.reader(fh))
    assert rows[0][:4] == ["roller_a", "roller_b", "theta_a_deg", "theta_b_deg"]
    assert [r[:2] for r in rows[1:]] == [["1", "1"], ["1'", "1'"], ["2", "2"], ["2'", "2'"]]
    values = np.array([r[2:] for r in rows[1:]], dtype=float)
    # the figure-eight of a roller at c crosses itself where u = -2 theta + c = +-90 deg
    assert np.allclose(values[:, 0], [22.5, 22.5, 67.5, 67.5])
    assert np.allclose(values[:, 1], [112.5, 112.5, 157.5, 157.5])
    assert np.allclose(values[:, 5], 45.0)


def test_dxf_audit_layers_and_points(cfg, tmp_path):
    import ezdxf

    (path,) = cw.export_wobble(cfg, "dxf", tmp_path, "cam")
    csvs = cw.export_wobble(cfg, "csv", tmp_path, "cam")
    doc = ezdxf.readfile(path)
    auditor = doc.audit()
    assert not auditor.has_errors and not auditor.has_fixes
    lines = list(doc.modelspace().query("POLYLINE"))
    assert len(lines) == 20
    layers = {e.dxf.layer for e in lines}
    assert layers == {"CENTRELINE", "WALL_INNER_SURFACE", "WALL_GROOVE_BOTTOM"}
    assert all(e.is_3d_polyline and e.is_closed for e in lines)
    by_layer = {layer: sum(e.dxf.layer == layer for e in lines) for layer in layers}
    assert by_layer == {"CENTRELINE": 4, "WALL_INNER_SURFACE": 8, "WALL_GROOVE_BOTTOM": 8}
    curves = [_read_csv(p)[1] for p in csvs if "crossings" not in p.name]
    for e in lines:  # each polyline is one CSV curve, in mm (CSV written to 1e-6 mm)
        pts = np.array([v.dxf.location for v in e.vertices])
        same = [c for c in curves if c.shape == pts.shape and np.allclose(c, pts, atol=1e-6)]
        assert len(same) == 1


def test_errors_write_nothing(tmp_path):
    cfg = load_config(None, "wobble-cam-engine", ['cam.roller_radius="6 mm"'])[0]  # undercuts
    with pytest.raises(ParameterError, match=r"^cam\.roller_radius = 6 mm"):
        cw.export_wobble(cfg, "stl", tmp_path, "cam")
    cfg = load_config(None, "wobble-cam-engine", SETS)[0]
    cfg["export"]["tolerance"] = 0.0  # the config refuses it; the library checks it too
    with pytest.raises(ParameterError, match=r"^export\.tolerance"):
        cw.export_wobble(cfg, "csv", tmp_path, "cam")
    with pytest.raises(ParameterError, match=r"^fmt = 'iges'"):
        cw.export_wobble(cfg, "iges", tmp_path, "cam")
    assert list(tmp_path.iterdir()) == []


def test_step_without_build123d(cfg, tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "build123d", None)
    with pytest.raises(RotorkinError, match=r'pip install "rotorkin\[cad\]"'):
        cw.export_wobble(cfg, "step", tmp_path, "cam")
    assert list(tmp_path.iterdir()) == []
