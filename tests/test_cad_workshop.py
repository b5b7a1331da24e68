"""Workshop CAD of the planar parts: bores, keyways, fits, running gaps, exact edges, assembly.

Every file is re-read with other code than the writer's (OpenCascade's readers through
OCP and build123d, ezdxf) and measured against independent models: the DIN 6885-1 and
ISO 286 values written out below from the standards' tables, the rhomboid cam's pitch
curve from eq. 3 offset with finite-difference normals, areas by Steiner's formula and
quadrature, the impellers' vanes by integration over their angular width.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.spatial import cKDTree

from rotorkin.cli import main
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar.study import drive_params
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.io.config import load_config
from rotorkin.io.export import export, planar_parts
from rotorkin.render import workshop as ws

bd = pytest.importorskip("build123d", reason="STEP export needs the [cad] extra (build123d)")
ezdxf = pytest.importorskip("ezdxf")
pytestmark = pytest.mark.cad

TOL_MM = 0.01  # the default export.tolerance
# ISO 286-2, written out here: IT grades and shaft deviations [um] for the sizes used.
H8F7_160 = (63.0, -43.0, 40.0)  # 120..180 mm: IT8, es of f, IT7
H8F7_200 = (72.0, -50.0, 46.0)  # 180..250 mm
IT7 = {18: 18.0, 30: 21.0, 50: 25.0, 80: 30.0}  # IT7 of the ranges up to 18, 30, 50, 80 mm
# DIN 6885-1, written out here: bore range -> (b, h, t1, t2) [mm].
DIN = {(17, 22): (6, 6, 3.5, 2.8), (22, 30): (8, 7, 4.0, 3.3), (30, 38): (10, 8, 5.0, 3.3),
       (38, 44): (12, 8, 5.0, 3.3), (44, 50): (14, 9, 5.5, 3.8), (50, 58): (16, 10, 6.0, 4.3),
       (58, 65): (18, 11, 7.0, 4.4)}  # fmt: skip


def _it7(d):
    return next(v for top, v in sorted(IT7.items()) if d <= top)


def _din(d):
    return next(v for (lo, hi), v in DIN.items() if lo < d <= hi)


def _gap(it8, es, it7):
    """Half the mean diametral clearance of H8/f7 [mm]."""
    return ((0.0 + it8) - (es + es - it7)) / 4.0 / 1000.0


def _cfg(example, *sets):
    return load_config(None, example, list(sets))


# --- files, written once -------------------------------------------------------------------
@pytest.fixture(scope="module")
def rhomboid(tmp_path_factory):
    out = tmp_path_factory.mktemp("rhomboid")
    cfg, _, name = _cfg("rhomboid-engine", "export.bore=30 mm")
    export(cfg, "step", out, name)
    export(cfg, "dxf", out, name)
    return cfg, out, name


@pytest.fixture(scope="module")
def pump(tmp_path_factory):
    out = tmp_path_factory.mktemp("pump")
    cfg, _, name = _cfg("guide-bar-pump", "export.bore=20 mm", "export.sleeve_bore=38 mm")
    for fmt in ("step", "dxf", "stl"):
        export(cfg, fmt, out, name)
    return cfg, out, name


@pytest.fixture(scope="module")
def gears(tmp_path_factory):
    out = tmp_path_factory.mktemp("gears")
    cfg, _, name = _cfg("elliptic-gear-engine")
    export(cfg, "all", out, name)
    return cfg, out, name


def _read_solids(path):
    """Solids of a STEP file read by OpenCascade's plain reader (no names), in mm."""
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer

    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_ReturnStatus.IFSelect_RetDone
    reader.TransferRoots()
    shape = reader.OneShape()
    out, exp = [], TopExp_Explorer(shape, TopAbs_SOLID)
    while exp.More():
        out.append(exp.Current())
        exp.Next()
    return out


def _valid(shape) -> bool:
    from OCP.BRepCheck import BRepCheck_Analyzer

    return BRepCheck_Analyzer(shape).IsValid()


def _volume(shape) -> float:
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    return float(props.Mass())


def _labelled(path):
    """{label: build123d shape} of the top level of an imported STEP file."""
    imp = bd.import_step(str(path))
    kids = list(imp.children) or [imp]
    return imp.label, {k.label: k for k in kids}


# --- the tables ----------------------------------------------------------------------------
@pytest.mark.parametrize("d,row", [(20, (17, 22)), (22, (17, 22)), (22.01, (22, 30)),
                                   (30, (22, 30)), (38, (30, 38)), (50, (44, 50))])  # fmt: skip
def test_keyway_table_rows(d, row):
    k = ws.keyway_for(d * 1e-3)
    assert (k.b * 1e3, k.h * 1e3, k.t1 * 1e3, k.t2 * 1e3) == pytest.approx(DIN[row])
    assert ws.keyway_for(5.9e-3) is None and ws.keyway_for(231e-3) is None


def test_iso286_limits():
    (EI, ES), (ei, es) = ws.fit_limits("H7/g6", 0.020)  # 18..30 mm: IT7 21, IT6 13, g -7
    assert (EI, ES, ei, es) == pytest.approx((0.0, 21e-6, -20e-6, -7e-6), abs=1e-12)
    (EI, ES), (ei, es) = ws.fit_limits("H8/f7", 0.160)
    assert (ES, ei, es) == pytest.approx((63e-6, -83e-6, -43e-6), abs=1e-12)
    (_, _), (ei, es) = ws.fit_limits("H7/k6", 0.040)  # 30..50: k ei +2, IT6 16
    assert (ei, es) == pytest.approx((2e-6, 18e-6), abs=1e-12)
    assert ws.running_gap("H8/f7", 0.160) == pytest.approx(_gap(*H8F7_160) * 1e-3, abs=1e-12)


# --- STEP: solids, names, title, units, volumes --------------------------------------------
def test_every_step_part_is_one_valid_named_solid(rhomboid, pump, gears):
    for cfg, out, name in (rhomboid, pump, gears):
        parts = [p.name for p in planar_parts(cfg)[0]]
        for part in parts:
            path = out / f"{name}_{part}.step"
            solids = _read_solids(path)
            assert len(solids) == 1 and _valid(solids[0])
            label, _ = _labelled(path)
            assert label == part
            head = ws.read_step(path)[1]
            assert head["description"] == cfg["title"] and head["unit"] == "MILLI"
        path = out / f"{name}_assembly.step"
        solids = _read_solids(path)
        assert len(solids) == len(parts) and all(_valid(s) for s in solids)
        label, kids = _labelled(path)
        assert label == name and sorted(kids) == sorted(parts)
        head = path.read_text().split("ENDSEC;")[0].replace("\n", "")  # line ends are void
        assert re.search(r"FILE_DESCRIPTION\(\(\s*'" + re.escape(cfg["title"]) + "'", head)


def test_a_title_beyond_ascii_is_encoded_for_step(tmp_path):
    title = "Pompe à palettes 摆盘 'JHIT' 2012"
    box = bd.Solid.make_box(10, 20, 5)
    path = ws.write_step(tmp_path / "t.step", [("box_1", box, (0.0, 0.0, 0.0, 0.0))], "t",
                         title, assembly=False)  # fmt: skip
    raw = path.read_bytes()
    assert raw.isascii()  # ISO 10303-21: \X2\ hex for what is not ASCII
    head = raw.decode().split("ENDSEC;")[0].replace("\n", "")
    assert f"\\X2\\{ord('à'):04X}\\X0\\" in head
    assert f"\\X2\\{ord('摆'):04X}{ord('盘'):04X}\\X0\\" in head
    assert ws.read_step(path)[1]["description"] == title
    (solid,) = _read_solids(path)
    assert _volume(solid) == pytest.approx(1000.0)


def _rhomboid_exact(cfg, n=400_000):
    """Dense exact actual profile [mm] (eq. 3 offset by r + gap, FD normals) and its area."""
    d = cfg["drive"]
    L, law = d["link_length"], (d["psi_min"], tuple(d["a"]), tuple(d["b"]))
    off = cfg["cam"]["roller_radius"] + _gap(*H8F7_200) * 1e-3

    def rho(t):
        return L * np.cos(0.5 * rc.psi_law(*law, t)[0])

    def pitch(t):
        return rho(t) * np.stack([np.cos(t), np.sin(t)])

    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    h = 1e-6
    tan = (pitch(t + h) - pitch(t - h)) / (2 * h)
    nrm = np.stack([tan[1], -tan[0]]) / np.hypot(*tan)

    def speed(t):
        dr = (rho(t + h) - rho(t - h)) / (2 * h)
        return np.hypot(rho(t), dr)

    area = quad(lambda t: 0.5 * rho(t) ** 2, 0, 2 * np.pi, limit=200, epsabs=1e-14)[0]
    perim = quad(speed, 0, 2 * np.pi, limit=200, epsabs=1e-12)[0]
    return (pitch(t) - off * nrm).T * 1e3, (area - off * perim + np.pi * off * off) * 1e6


def _bore_area(d, fit_it7):
    """Area [mm^2] of a bore drawn at d + IT7/2 with its DIN keyway (quadrature)."""
    b, _, _, t2 = _din(d)
    r = 0.5 * (d + fit_it7 / 2000.0)  # drawn at the middle of H7
    top = 0.5 * d + t2
    return np.pi * r * r + quad(lambda x: top - np.sqrt(r * r - x * x), -b / 2, b / 2)[0]


def test_rhomboid_volume_is_area_times_thickness(rhomboid):
    cfg, out, name = rhomboid
    (solid,) = _read_solids(out / f"{name}_rhomboid_cam.step")
    _, area = _rhomboid_exact(cfg)
    exact = (area - _bore_area(30, IT7[30])) * 20.0
    assert _volume(solid) == pytest.approx(exact, rel=1e-5)


def _vane_area(r1, r2, gamma, delta):
    """Area of a vane between radii r1, r2 whose flanks are moved in by delta [mm^2]."""
    return quad(lambda r: r * (gamma - 2.0 * np.arcsin(delta / r)), r1, r2, epsabs=1e-12)[0]


def test_impeller_volumes(pump):
    cfg, out, name = pump
    c = _gap(*H8F7_160)  # every pump gap: machine gaps 0 in the example
    rh, rcas, w, z, gamma = 30.0, 80.0, 40.0, 2, np.arctan(2.0)  # gamma_0(lambda=0.5, u=2)
    delta = c / 2  # the vanes close completely (phi_min = 0): each flank moves in c/2
    hub = np.pi * rh * rh + z * _vane_area(rh, rcas - c, gamma, delta)
    vanes = z * _vane_area(rh + c, rcas - c, gamma, delta)
    label, kids = _labelled(out / f"{name}_assembly.step")
    for k, d in ((1, 20), (2, 38)):
        h_hub = w / 2 - c / 2 - c  # from the side gap to the middle less half the hub gap
        h_vanes = w - 2 * c - h_hub
        exact = (hub - _bore_area(d, _it7(d))) * h_hub + vanes * h_vanes
        (solid,) = _read_solids(out / f"{name}_impeller_{k}.step")
        assert _volume(solid) == pytest.approx(exact, rel=1e-6)
        assert _volume(kids[f"impeller_{k}"].wrapped) == pytest.approx(exact, rel=1e-6)
        import trimesh

        mesh = trimesh.load(out / f"{name}_impeller_{k}.stl")
        assert mesh.is_watertight and mesh.volume == pytest.approx(exact, rel=2e-4)


# --- bores and keyways measured on the solids ----------------------------------------------
def _bore_face_measures(shape):
    """(bore radius, keyway width, axis-to-keyway-bottom, bore centre) of the first planar face
    with an inner wire holding a circular arc [mm]."""
    solid = bd.Solid(shape) if not isinstance(shape, bd.Shape) else shape
    for face in solid.faces().filter_by(bd.GeomType.PLANE):
        for wire in face.inner_wires():
            arcs = [e for e in wire.edges() if e.geom_type == bd.GeomType.CIRCLE]
            lines = [e for e in wire.edges() if e.geom_type == bd.GeomType.LINE]
            if len(arcs) != 1 or len(lines) != 3:
                continue
            centre = arcs[0].arc_center
            dirs = [(e.end_point() - e.start_point()).normalized() for e in lines]
            sides = [i for i in range(3) if abs(dirs[i].dot(dirs[(i + 1) % 3])) < 1e-9
                     and abs(dirs[i].dot(dirs[(i + 2) % 3])) < 1e-9]  # fmt: skip
            (top,) = sides
            a, b = (lines[i] for i in range(3) if i != top)
            width = abs((a.start_point() - b.start_point()).dot(dirs[top]))
            p, q = lines[top].start_point(), lines[top].end_point()
            depth = ((centre - p).cross(q - p)).length / (q - p).length
            return arcs[0].radius, width, depth, centre
    raise AssertionError("no bore face found")


@pytest.mark.parametrize("which", ["rhomboid_cam", "impeller_1", "impeller_2", "driving_gear"])
def test_bore_and_keyway_measured_on_the_solid(rhomboid, pump, gears, which):
    cfg, out, name = {"rhomboid_cam": rhomboid, "driving_gear": gears}.get(which, pump)
    (solid,) = _read_solids(out / f"{name}_{which}.step")
    d = {"rhomboid_cam": 30, "impeller_1": 20, "impeller_2": 38}.get(which)
    if d is None:  # the gears' default bore: read it from the key, check it against its row
        d = planar_parts(cfg)[0][0].hub.bore * 1e3
    radius, width, depth, centre = _bore_face_measures(solid)
    b, _, _, t2 = _din(d)
    assert radius == pytest.approx(0.5 * (d + _it7(d) / 2000.0), abs=1e-7)  # middle of H7
    assert width == pytest.approx(b, abs=1e-7)
    assert depth == pytest.approx(0.5 * d + t2, abs=1e-7)  # d + t2 from the far side of the bore
    assert np.hypot(centre.X, centre.Y) < 1e-7  # on the part's axis


def test_default_bore_is_the_largest_that_fits_rounded_down():
    cfg, _, _ = _cfg("eccentric-reactor")  # R = 80, e = 40: the wall is thinnest opposite e
    parts = planar_parts(cfg)[0]
    # R - e >= (d + IT7/2)/2 + d/4 away from the keyway: d <= 53.3 mm, rounded to 5 mm -> 50
    assert [p.hub.bore for p in parts] == [pytest.approx(0.050)] * 2
    assert [p.hub.angle for p in parts] == pytest.approx([0.0, np.pi])  # towards each centre


# --- nested hubs, running gaps ---------------------------------------------------------------
def _common_and_distance(a, b):
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape

    common = BRepAlgoAPI_Common(a, b)
    common.Build()
    dist = BRepExtrema_DistShapeShape(a, b)
    return _volume(common.Shape()), dist.Value()


def test_impellers_have_no_common_volume_and_run_on_their_gap(pump):
    cfg, out, name = pump
    solids = _read_solids(out / f"{name}_assembly.step")
    assert len(solids) == 2
    common, distance = _common_and_distance(*solids)
    assert common == 0.0
    assert distance == pytest.approx(_gap(*H8F7_160), abs=1e-7)  # hub faces / vane roots
    # vane tips short of the casing by the gap: the largest circle on each solid
    for s in solids:
        radii = [e.radius for e in bd.Solid(s).edges() if e.geom_type == bd.GeomType.CIRCLE]
        assert max(radii) == pytest.approx(80.0 - _gap(*H8F7_160), abs=1e-9)


def _flanks(dxf_path):
    """Straight edges (flanks) of the PROFILE polyline of an impeller drawing [mm], (n, 2, 2)."""
    doc = ezdxf.readfile(dxf_path)
    (poly,) = doc.modelspace().query("LWPOLYLINE[layer=='PROFILE']")
    pts = np.array([(x, y, b) for x, y, _, _, b in poly.get_points("xyseb")])
    nxt = np.roll(pts, -1, axis=0)
    keep = pts[:, 2] == 0.0
    return np.stack([pts[keep, :2], nxt[keep, :2]], axis=1)


def _seg_dist(p, a, b):
    ab = b - a
    s = np.clip(np.sum((p - a) * ab, -1) / np.sum(ab * ab, -1), 0.0, 1.0)
    return np.linalg.norm(p - a - s[..., None] * ab, axis=-1)


def test_vanes_never_come_closer_than_the_gap(pump):
    cfg, out, name = pump
    f1, f2 = (_flanks(out / f"{name}_impeller_{k}.dxf") for k in (1, 2))
    theta = np.linspace(0.0, 2 * np.pi, 7201)
    q = gb.motion(drive_params(cfg), theta).q
    turn = q - q[:, :1]  # turned from theta = 0, where the drawings are

    def at(f, ang):  # (T, n, 2, 2)
        c, s = np.cos(ang)[:, None, None], np.sin(ang)[:, None, None]
        x, y = f[None, ..., 0], f[None, ..., 1]
        return np.stack([c * x - s * y, s * x + c * y], -1)

    a, b = at(f1, turn[0])[:, :, None], at(f2, turn[1])[:, None, :]  # (T, n1, n2, 2, 2)
    d = np.minimum.reduce([_seg_dist(a[..., 0, :], b[..., 0, :], b[..., 1, :]),
                           _seg_dist(a[..., 1, :], b[..., 0, :], b[..., 1, :]),
                           _seg_dist(b[..., 0, :], a[..., 0, :], a[..., 1, :]),
                           _seg_dist(b[..., 1, :], a[..., 0, :], a[..., 1, :])])  # fmt: skip
    c = _gap(*H8F7_160)
    assert d.min() >= c * (1 - 1e-6)
    assert d.min() <= c * 1.01  # they do close up to the gap


def test_pump_on_another_drive_nests_too(tmp_path):
    path = tmp_path / "pump.toml"
    path.write_text(
        "[drive]\ntype = 'noncircular_gears'\nlobes = 2\nrotor_lobes = 2\neccentricity = 0.2\n"
        "centre_distance = '120 mm'\n[machine]\ntype = 'vane_pump'\nhub_radius = '25 mm'\n"
        "casing_radius = '60 mm'\naxial_width = '30 mm'\n"
    )
    cfg, _, name = load_config(path)
    files = export(cfg, "step", tmp_path / "cad", name)
    solids = _read_solids(tmp_path / "cad" / f"{name}_assembly.step")
    names = sorted(_labelled(tmp_path / "cad" / f"{name}_assembly.step")[1])
    assert names == ["driven_gear", "driving_gear", "impeller_1", "impeller_2"] and files
    for i in range(4):
        for j in range(i + 1, 4):
            assert _common_and_distance(solids[i], solids[j])[0] == 0.0


# --- exact edges ---------------------------------------------------------------------------
def _edge_points(shape, kind="BSPLINE", n=200):
    from OCP.BRepAdaptor import BRepAdaptor_Curve

    pts = []
    for e in bd.Solid(shape).edges():
        if e.geom_type != getattr(bd.GeomType, kind):
            continue
        c = BRepAdaptor_Curve(e.wrapped)
        for u in np.linspace(c.FirstParameter(), c.LastParameter(), n):
            p = c.Value(float(u))
            pts.append((p.X(), p.Y(), p.Z()))
    return np.array(pts)


def test_rhomboid_spline_edges_follow_the_model_within_the_tolerance(rhomboid):
    cfg, out, name = rhomboid
    (solid,) = _read_solids(out / f"{name}_rhomboid_cam.step")
    faces = bd.Solid(solid).faces()
    assert len(faces) < 20  # 8 spline pieces, 2 caps, bore and keyway: no polygon facets
    pts = _edge_points(solid)
    dense, _ = _rhomboid_exact(cfg)
    dist, _ = cKDTree(dense).query(pts[:, :2])
    assert len(pts) >= 16 * 200 and dist.max() <= TOL_MM
    # the DXF's splines: the same curves
    doc = ezdxf.readfile(out / f"{name}_rhomboid_cam.dxf")
    splines = doc.modelspace().query("SPLINE[layer=='PROFILE']")
    assert len(splines) >= 8
    q = np.concatenate([np.array(list(s.construction_tool().approximate(200)))[:, :2]
                        for s in splines])  # fmt: skip
    assert cKDTree(dense).query(q)[0].max() <= TOL_MM


def test_gear_spline_edges_follow_the_pitch_curve(gears):
    cfg, out, name = gears
    a, e, n = 120.0, 0.2, 2
    p = a * (1 - e * e) / 2  # closure for n = m (Litvin): r1 = p / (1 - e cos(n phi))
    (solid,) = _read_solids(out / f"{name}_driving_gear.step")
    pts = _edge_points(solid)
    phi = np.arctan2(pts[:, 1], pts[:, 0])
    r = np.hypot(pts[:, 0], pts[:, 1])
    assert len(pts) and np.max(np.abs(r - p / (1 - e * np.cos(n * phi)))) <= TOL_MM


# --- DXF extents ---------------------------------------------------------------------------
def test_dxf_extents_enclose_every_entity(rhomboid, pump, gears):
    from ezdxf import bbox

    for _, out, _ in (rhomboid, pump, gears):
        for path in sorted(out.glob("*.dxf")):
            doc = ezdxf.readfile(path)
            lo, hi = np.array(doc.header["$EXTMIN"]), np.array(doc.header["$EXTMAX"])
            assert np.all(hi[:2] - lo[:2] > 1.0) and np.all(np.abs(lo) < 1e4)  # not the 1e20
            box = bbox.extents(doc.modelspace(), fast=False)
            assert np.allclose(lo, box.extmin, atol=1e-6) and np.allclose(hi, box.extmax, atol=1e-6)
            for ent in doc.modelspace():
                if ent.dxftype() == "TEXT":
                    pts = [ent.dxf.insert]
                else:
                    pts = list(ezdxf.path.make_path(ent).flattening(0.001))
                pts = np.array([tuple(v)[:2] for v in pts])
                assert np.all(pts >= lo[:2] - 1e-6) and np.all(pts <= hi[:2] + 1e-6), path.name


# --- refused input ---------------------------------------------------------------------------
def _run(capsys, *args):
    code = main(["export", *args])
    out, err = capsys.readouterr()
    return code, out, err


def test_a_bore_too_large_is_refused_in_one_line_with_the_largest_that_fits(tmp_path, capsys):
    code, _, err = _run(capsys, "-e", "rhomboid-engine", "-s", "export.bore=60 mm", "-f", "dxf",
                        "-o", str(tmp_path / "a"))  # fmt: skip
    assert code == 2 and err.count("\n") == 1 and "Traceback" not in err
    assert "export.bore = 60 mm" in err and "rhomboid_cam" in err
    most = float(err.split("bore <= ")[1].split(" mm")[0])
    assert not (tmp_path / "a").exists()
    code, _, err = _run(capsys, "-e", "rhomboid-engine", "-s", f"export.bore={most} mm",
                        "-f", "dxf", "-o", str(tmp_path / "b"))  # fmt: skip
    assert code == 0, err
    code, _, err = _run(capsys, "-e", "rhomboid-engine", "-s", f"export.bore={most + 0.01} mm",
                        "-f", "dxf", "-o", str(tmp_path / "c"))  # fmt: skip
    assert code == 2 and f"bore <= {most:g} mm" in err


@pytest.mark.parametrize("sets,needle", [
    (["export.sleeve_bore=55 mm"], "export.sleeve_bore = 55 mm"),
    (["export.sleeve_bore=30 mm", "export.bore=20 mm"], "export.bore = 20 mm"),
    (["export.bore=5 mm"], "6 mm <= bore <= 230 mm"),
])  # fmt: skip
def test_pump_bores_refused(tmp_path, capsys, sets, needle):
    args = [a for s in sets for a in ("-s", s)]
    code, _, err = _run(capsys, "-e", "guide-bar-pump", *args, "-f", "dxf", "-o", str(tmp_path))
    assert code == 2 and err.count("\n") == 1 and needle in err
    assert list(tmp_path.iterdir()) == []


# --- progress --------------------------------------------------------------------------------
def test_progress_per_part_and_the_cli_bar(tmp_path, capsys, monkeypatch):
    cfg, _, name = _cfg("eccentric-reactor")
    calls = []
    export(cfg, "all", tmp_path / "a", name, progress=lambda *a: calls.append(a))
    labels = [c[0] for c in calls]
    assert labels[-1] == "done" and calls[-1][1] == calls[-1][2] == 9  # 4 formats x 2 + assembly
    assert labels[:2] == ["dxf disc_left", "dxf disc_right"] and "step assembly" in labels
    monkeypatch.setenv("TTY_COMPATIBLE", "1")
    code, out, err = _run(capsys, "-e", "eccentric-reactor", "-f", "stl", "-o", str(tmp_path / "b"))
    assert code == 0 and "stl disc_right" in err  # the bar, on stderr
    code, out, err = _run(capsys, "-e", "eccentric-reactor", "-f", "stl", "-q",
                          "-o", str(tmp_path / "c"))  # fmt: skip
    assert code == 0 and out == "" and err == ""
