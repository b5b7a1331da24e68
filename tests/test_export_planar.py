"""CAD export of the planar parts, checked by re-reading the files with other libraries.

The model curves are rebuilt here from the paper's equations (eq. 3 of the
rhomboid cam, the disc and impeller geometry) with finite-difference normals;
areas come from quadrature (Steiner's formula for the offset) or closed form.
The bare geometry: ``export.bore = 0 mm`` (no bore) and ``export.running_clearance =
0 mm`` (the nominal profiles); bores, keyways and gaps are tested in
``test_cad_workshop.py``.
"""

import sys

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.spatial import cKDTree

from rotorkin.core.errors import ParameterError, RotorkinError
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.io.config import load_config
from rotorkin.io.export import export

ezdxf = pytest.importorskip("ezdxf")
trimesh = pytest.importorskip("trimesh")

TOL_MM = 0.01  # the default export.tolerance


BARE = ("export.bore=0 mm", "export.running_clearance=0 mm")


def _cfg(example, *sets):
    return load_config(None, example, [*BARE, *sets])


def _rhomboid_curves(cfg, n=300_000):
    """Dense exact pitch curve and actual profile [mm] of a rhomboid config (eq. 3, FD normal)."""
    d = cfg["drive"]
    L, law = d["link_length"], (d["psi_min"], tuple(d["a"]), tuple(d["b"]))
    r = cfg["cam"]["roller_radius"]

    def pitch(t):
        rho = L * np.cos(0.5 * rc.psi_law(*law, t)[0])
        return np.stack([rho * np.cos(t), rho * np.sin(t)])

    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    h = 1e-6
    tan = (pitch(t + h) - pitch(t - h)) / (2 * h)
    nrm = np.stack([tan[1], -tan[0]]) / np.hypot(*tan)
    p = pitch(t)
    return p.T * 1e3, (p - r * nrm).T * 1e3


def _areas_mm2(cfg):
    """Pitch area 1/2 int rho^2, perimeter int |p'|, and the profile's by Steiner [mm^2]."""
    d = cfg["drive"]
    L, law = d["link_length"], (d["psi_min"], tuple(d["a"]), tuple(d["b"]))
    r = cfg["cam"]["roller_radius"]

    def rho(t):
        return L * np.cos(0.5 * rc.psi_law(*law, t)[0])

    def speed(t, h=1e-6):
        dr = (rho(t + h) - rho(t - h)) / (2 * h)
        return np.hypot(rho(t), dr)

    area = quad(lambda t: 0.5 * rho(t) ** 2, 0, 2 * np.pi, limit=200, epsabs=1e-14)[0]
    perim = quad(speed, 0, 2 * np.pi, limit=200, epsabs=1e-12)[0]
    return area * 1e6, (area - r * perim + np.pi * r * r) * 1e6


def _distance(tree, dense, pts):
    """Distance of pts from the dense closed polyline (nearest vertex, then its two segments)."""
    _, i = tree.query(pts)
    n = len(dense)
    best = np.full(len(pts), np.inf)
    for a, b in ((i - 1) % n, i), (i, (i + 1) % n):
        A, B = dense[a], dense[b]
        ab = B - A
        s = np.clip(np.sum((pts - A) * ab, axis=1) / np.sum(ab * ab, axis=1), 0.0, 1.0)
        best = np.minimum(best, np.hypot(*(pts - A - s[:, None] * ab).T))
    return best


def _check_polyline(vertices, dense):
    """Every vertex on the model curve; the chords' quarter and middle points within TOL_MM."""
    tree = cKDTree(dense)
    v = np.asarray(vertices)
    assert _distance(tree, dense, v).max() < 1e-6
    w = np.roll(v, -1, axis=0)
    dev = np.max([_distance(tree, dense, v + f * (w - v)) for f in (0.25, 0.5, 0.75)], axis=0)
    assert dev.max() <= TOL_MM
    assert dev.max() > 0.2 * TOL_MM  # not wastefully fine
    return dev


def test_rhomboid_dxf(tmp_path):
    cfg, _, name = _cfg("rhomboid-engine")
    files = export(cfg, "dxf", tmp_path / "cad", name)
    assert [f.name for f in files] == ["rhomboid-engine_rhomboid_cam.dxf"]
    doc = ezdxf.readfile(files[0])
    auditor = doc.audit()
    assert not auditor.has_errors and not auditor.has_fixes
    assert doc.header["$INSUNITS"] == 4  # mm
    msp = doc.modelspace()
    polys = {e.dxf.layer: e for e in msp.query("LWPOLYLINE")}
    assert {"PITCH", "LINKAGE"} <= set(polys)
    pitch_dense, prof_dense = _rhomboid_curves(cfg)
    e = polys["PITCH"]
    assert e.closed
    pts = np.array([(x, y) for x, y, *_ in e.get_points()])
    assert len(pts) > 100
    _check_polyline(pts, pitch_dense)
    # the profile to cut: B-spline pieces within the tolerance, joined end to end
    splines = list(msp.query("SPLINE[layer=='PROFILE']"))
    assert len(splines) >= 8 and not msp.query("LWPOLYLINE[layer=='PROFILE']")
    tools = [s.construction_tool() for s in splines]
    ends = np.array([[tuple(t.point(t.max_t))[:2], tuple(u.point(u.knots()[0]))[:2]]
                     for t, u in zip(tools, tools[1:] + tools[:1], strict=True)])  # fmt: skip
    assert np.abs(ends[:, 0] - ends[:, 1]).max() < 1e-9
    q = np.concatenate([np.array(list(t.approximate(500)))[:, :2] for t in tools])
    assert _distance(cKDTree(prof_dense), prof_dense, q).max() <= TOL_MM
    circles = list(msp.query("CIRCLE"))
    assert len(circles) == 4 and all(c.dxf.layer == "ROLLER" for c in circles)
    r_mm = cfg["cam"]["roller_radius"] * 1e3
    for c in circles:
        assert c.dxf.radius == pytest.approx(r_mm)
        # every roller centre lies on the pitch curve
        assert cKDTree(pitch_dense).query([c.dxf.center.x, c.dxf.center.y])[0] < 1e-3


def test_rhomboid_stl_volume(tmp_path):
    cfg, _, name = _cfg("rhomboid-engine")
    (path,) = export(cfg, "stl", tmp_path, name)
    mesh = trimesh.load(path)
    assert mesh.is_watertight and mesh.is_volume
    _, prof_area = _areas_mm2(cfg)
    t_mm = cfg["cam"]["thickness"] * 1e3
    assert mesh.volume == pytest.approx(prof_area * t_mm, rel=1e-2)
    assert mesh.volume == pytest.approx(prof_area * t_mm, rel=1e-4)  # in fact much closer
    assert mesh.bounds[0][2] == pytest.approx(0.0) and mesh.bounds[1][2] == pytest.approx(t_mm)


@pytest.mark.parametrize("follower", ["knife_edge", "roller"])
def test_eccentric_dxf_stl_csv(tmp_path, follower):
    cfg, _, name = _cfg("eccentric-reactor", f"drive.follower={follower}",
                        "drive.roller_radius=12 mm")  # fmt: skip
    R, e = 80.0, 40.0
    files = export(cfg, "all", tmp_path, name) if _has_bd() else None
    if files is None:
        files = [f for fmt in ("dxf", "stl", "csv") for f in export(cfg, fmt, tmp_path, name)]
    names = {f.name for f in files}
    assert {f"{name}_disc_left.dxf", f"{name}_disc_right.dxf", f"{name}_disc_left.stl"} <= names
    for side, cx in (("left", e), ("right", -e)):
        doc = ezdxf.readfile(tmp_path / f"{name}_disc_{side}.dxf")
        assert not doc.audit().has_errors
        circ = {c.dxf.layer: c for c in doc.modelspace().query("CIRCLE")}
        assert circ["PROFILE"].dxf.radius == pytest.approx(R)
        assert (circ["PROFILE"].dxf.center.x, circ["PROFILE"].dxf.center.y) == pytest.approx(
            (cx, 0.0)
        )
        pitch = R + (12.0 if follower == "roller" else 0.0)
        assert circ["PITCH"].dxf.radius == pytest.approx(pitch)
        if follower == "roller":
            roller = circ["ROLLER"]
            # the roller touches the disc at beta = 0: centre on the axis at Rc from the disc
            assert roller.dxf.radius == pytest.approx(12.0)
            assert abs(roller.dxf.center.x - cx) == pytest.approx(pitch)
        mesh = trimesh.load(tmp_path / f"{name}_disc_{side}.stl")
        assert mesh.is_watertight
        assert mesh.volume == pytest.approx(np.pi * R * R * 20.0, rel=1e-3)
        prof = np.loadtxt(tmp_path / f"{name}_disc_{side}_profile.csv", delimiter=",", skiprows=1)
        rr = np.hypot(prof[:, 0] - cx, prof[:, 1])
        np.testing.assert_allclose(rr, R, atol=1e-6)
        mid = 0.5 * (prof + np.roll(prof, -1, axis=0))
        assert np.max(R - np.hypot(mid[:, 0] - cx, mid[:, 1])) <= TOL_MM


def test_impeller_stl_and_dxf(tmp_path):
    """Without gaps: each impeller is its vanes over the width and its hub over half of it."""
    cfg, _, name = _cfg("guide-bar-pump")
    m = cfg["machine"]
    rh, rcas, w = m["hub_radius"] * 1e3, m["casing_radius"] * 1e3, m["axial_width"] * 1e3
    z = m["vanes_per_impeller"]
    gamma = np.arctan(2.0)  # the drive's gamma_0 for lambda = 0.5, u = 2 (63.43 deg)
    volume = np.pi * rh * rh * w / 2 + z * gamma * 0.5 * (rcas**2 - rh**2) * w
    for f in ("stl", "dxf"):
        export(cfg, f, tmp_path, name)
    for k in (1, 2):
        mesh = trimesh.load(tmp_path / f"{name}_impeller_{k}.stl")
        assert mesh.is_watertight
        assert mesh.volume == pytest.approx(volume, rel=1e-4)
        doc = ezdxf.readfile(tmp_path / f"{name}_impeller_{k}.dxf")
        assert not doc.audit().has_errors
        (poly,) = doc.modelspace().query("LWPOLYLINE[layer=='PROFILE']")
        pts = np.array([(x, y) for x, y, *_ in poly.get_points()])
        rad = np.hypot(pts[:, 0], pts[:, 1])
        on = np.isclose(rad, rh, atol=1e-6) | np.isclose(rad, rcas, atol=1e-6)
        assert on.all()
        # vane tips: the angular extent on the casing is z * gamma
        ang = np.arctan2(pts[:, 1], pts[:, 0])
        tips = rad > 0.5 * (rh + rcas)
        seg = np.diff(np.unwrap(np.append(ang, ang[0])))
        both = tips & np.roll(tips, -1)
        assert np.sum(np.abs(seg[both])) == pytest.approx(z * gamma, rel=1e-9)


def _has_bd():
    try:
        import build123d  # noqa: F401
    except ImportError:
        return False
    return True


@pytest.mark.cad
def test_rhomboid_step(tmp_path):
    bd = pytest.importorskip("build123d", reason="STEP export needs the [cad] extra (build123d)")
    cfg, _, name = _cfg("rhomboid-engine")
    assembly, path = export(cfg, "step", tmp_path, name)
    assert assembly.name == f"{name}_assembly.step"
    shape = bd.import_step(str(path))
    solids = shape.solids()
    assert len(solids) == 1 and solids[0].is_valid
    _, prof_area = _areas_mm2(cfg)
    assert solids[0].volume == pytest.approx(prof_area * 20.0, rel=1e-2)
    assert solids[0].volume == pytest.approx(prof_area * 20.0, rel=1e-4)


@pytest.mark.cad
def test_eccentric_and_impeller_step(tmp_path):
    bd = pytest.importorskip("build123d", reason="STEP export needs the [cad] extra (build123d)")
    cfg, _, name = _cfg("eccentric-reactor")
    for path in export(cfg, "step", tmp_path, name):
        s = bd.import_step(str(path)).solids()
        assert len(s) == (2 if path.stem.endswith("assembly") else 1) and s[0].is_valid
        assert s[0].volume == pytest.approx(np.pi * 80.0**2 * 20.0, rel=1e-9)
    cfg, _, name = _cfg("guide-bar-pump")
    for path in export(cfg, "step", tmp_path, name):
        s = bd.import_step(str(path)).solids()
        assert len(s) == (2 if path.stem.endswith("assembly") else 1) and s[0].is_valid
        vanes = 2 * np.arctan(2.0) * 0.5 * (80.0**2 - 30.0**2) * 40.0
        assert s[0].volume == pytest.approx(np.pi * 30.0**2 * 20.0 + vanes, rel=1e-9)


def test_csv_every_curve(tmp_path):
    cfg, _, name = _cfg("rhomboid-engine")
    files = export(cfg, "csv", tmp_path, name)
    stems = sorted(f.stem.removeprefix(f"{name}_rhomboid_cam_") for f in files)
    assert stems == ["pitch", "profile", "rhombus", "roller_A", "roller_B", "roller_C", "roller_D"]
    files = export(load_config(None, "rhomboid-engine", [])[0], "csv", tmp_path / "b", name)
    assert f"{name}_rhomboid_cam_bore.csv" in [f.name for f in files]  # with its bore
    pitch_dense, prof_dense = _rhomboid_curves(cfg)
    for stem, dense in (("pitch", pitch_dense), ("profile", prof_dense)):
        path = tmp_path / f"{name}_rhomboid_cam_{stem}.csv"
        assert path.read_text().splitlines()[0] == "x_mm,y_mm"
        pts = np.loadtxt(path, delimiter=",", skiprows=1)
        assert _distance(cKDTree(dense), dense, pts).max() < 1e-6


def test_failures_leave_nothing(tmp_path):
    cfg, _, name = _cfg("rhomboid-engine", "cam.roller_radius=60 mm")
    out = tmp_path / "cad"
    with pytest.raises(ParameterError, match="cam.roller_radius.*alpha = 59.71 deg"):
        export(cfg, "dxf", out, name)
    with pytest.raises(ParameterError, match="^fmt = "):
        export(_cfg("rhomboid-engine")[0], "iges", out, name)
    cfg, _, name = _cfg("rhomboid-engine", "cam.thickness=0 mm")
    with pytest.raises(ParameterError, match="cam.thickness"):
        export(cfg, "stl", out, name)
    assert list(tmp_path.iterdir()) == []


def test_tolerance_controls_the_vertex_count(tmp_path):
    coarse = export(_cfg("rhomboid-engine", "export.tolerance=0.1 mm")[0], "csv", tmp_path / "a",
                    "x")  # fmt: skip
    fine = export(_cfg("rhomboid-engine")[0], "csv", tmp_path / "b", "x")
    n = [len(np.loadtxt(f[0], delimiter=",", skiprows=1)) for f in (coarse, fine)]
    # chord length ~ sqrt(8 R tol): ten times the tolerance, about sqrt(10) fewer vertices
    assert 2.0 < n[1] / n[0] < 5.0


def test_wobble_goes_to_cad_wobble(tmp_path):
    pytest.importorskip("rotorkin.drives.wobble_cam.cad")
    cfg, _, name = _cfg("wobble-cam-engine", "cam.roller_radius=4 mm")
    files = export(cfg, "csv", tmp_path, name)
    assert files and all(f.parent == tmp_path and f.suffix == ".csv" for f in files)


def test_step_without_build123d_is_one_clear_error(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "build123d", None)  # import build123d -> ImportError
    cfg, _, name = _cfg("eccentric-reactor")
    with pytest.raises(RotorkinError, match=r'pip install "rotorkin\[cad\]"') as info:
        export(cfg, "step", tmp_path / "cad", name)
    assert "\n" not in str(info.value)
    assert list(tmp_path.iterdir()) == []
