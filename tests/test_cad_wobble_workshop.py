"""The wobble-cam engine's STEP assembly, re-read with OpenCascade and checked here.

Reference models of this file, independent of the library: the roller centres and
grooves from the paper's rotation matrices written out (``test_cams_spherical.Explicit``);
the rotors' angles as the roller shafts' projections on the yz plane (their definition,
eq. 13-14); the ISO 286 H8/f7 clearances from the tables' values written here; the
walls of the exported grooves found by casting rays on the re-read solids.
"""

from __future__ import annotations

import itertools
import re
import time

import numpy as np
import pytest

from rotorkin.cli import main
from rotorkin.drives.wobble_cam import cad as cw
from rotorkin.drives.wobble_cam import cam as sph
from rotorkin.io.config import load_config
from test_cams_spherical import PHI, Explicit, _rot_x, _rot_y

pytestmark = pytest.mark.cad

SLUGS = ("1", "1p", "2", "2p")
#: Diametral mean clearances of ISO 286 H8/f7 [m]: at 8 mm (6-10: IT8 22, IT7 15, es -13 um),
#: at 4 mm (3-6: IT8 18, IT7 12, es -10 um), at 12 mm (10-18: IT8 27, IT7 18, es -16 um).
FIT_8, FIT_4, FIT_12 = 31.5e-6, 25e-6, 38.5e-6
#: Sizes of the example (config and documented defaults) [m].
R, RI, RO, RB, RHO = 0.06, 0.054, 0.066, 0.062, 0.004
HALF = RHO + 0.5 * FIT_8
#: The largest roller that fits: from R_i to its rim 0.5 mm inside the groove bottom.
LONGEST = np.sqrt((RB - 0.0005) ** 2 - RHO**2) - RI


def _ocp():
    pytest.importorskip("build123d", reason="STEP export needs the [cad] extra (build123d)")


def read_step(path):
    """``{product name: TopoDS_Shape (placed)}``, the header's text and the length unit."""
    from OCP.collections import Sequence_TDF_Label
    from OCP.STEPCAFControl import STEPCAFControl_Reader
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDataStd import TDataStd_Name
    from OCP.TDF import TDF_Label
    from OCP.TDocStd import TDocStd_Document
    from OCP.XCAFDoc import XCAFDoc_DocumentTool

    doc = TDocStd_Document(TCollection_ExtendedString("step"))
    reader = STEPCAFControl_Reader()
    reader.SetNameMode(True)
    reader.ReadFile(str(path))
    reader.Transfer(doc)
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())

    def name(label):
        attr = TDataStd_Name()
        return (
            attr.Get().ToExtString() if label.FindAttribute(TDataStd_Name.GetID_s(), attr) else None
        )

    roots = Sequence_TDF_Label()
    tool.GetFreeShapes(roots)
    assert roots.Length() == 1
    top = roots.Value(1)
    comps = Sequence_TDF_Label()
    tool.GetComponents_s(top, comps)
    parts = {}
    for i in range(1, comps.Length() + 1):
        ref = TDF_Label()
        tool.GetReferredShape_s(comps.Value(i), ref)
        assert name(ref) not in parts
        parts[name(ref)] = tool.GetShape_s(comps.Value(i))
    text = path.read_text(errors="replace")
    return name(top), parts, text


def _solids(shape):
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer

    out, ex = [], TopExp_Explorer(shape, TopAbs_SOLID)
    while ex.More():
        out.append(ex.Current())
        ex.Next()
    return out


def _volume(shape) -> float:
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props, 1e-7, True)
    return float(props.Mass())


def _centre(shape) -> np.ndarray:
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props, 1e-7, True)
    c = props.CentreOfMass()
    return np.array([c.X(), c.Y(), c.Z()])


@pytest.fixture(scope="module")
def cfg():
    return load_config(None, "wobble-cam-engine", [])[0]


@pytest.fixture(scope="module")
def step(cfg, tmp_path_factory):
    """The example's assembly written once (timed) and read back with OCP."""
    _ocp()
    out = tmp_path_factory.mktemp("step")
    from rotorkin.io.export import export

    calls = []
    t0 = time.perf_counter()
    (path,) = export(cfg, "step", out, "engine", progress=lambda *a: calls.append(a))
    seconds = time.perf_counter() - t0
    title, parts, text = read_step(path)
    print(f"STEP assembly: {len(parts)} parts, {path.stat().st_size / 1e6:.1f} MB, {seconds:.1f} s")
    _PROGRESS[:] = calls
    return title, parts, text, seconds


_PROGRESS: list = []


def test_the_export_reports_progress_per_group_of_parts(step):
    """One step per group of parts (cam, Z-shaft, plate, rotors, casing, the file), counted
    up to its total, the total reached at the end."""
    labels = [c[0] for c in _PROGRESS]
    for group in ("cam", "z_shaft", "plate", "rotor_1", "rotor_2", "casing", "file"):
        assert f"step {group}" in labels
    done = [c[1] for c in _PROGRESS]
    assert done == sorted(done)
    assert all(0 <= d <= t for _, d, t in _PROGRESS)
    assert _PROGRESS[-1][1] == _PROGRESS[-1][2] > 1


# --------------------------------------------------------------------------------------------
# names, solids, units, title
# --------------------------------------------------------------------------------------------
def test_every_part_a_named_valid_solid_in_mm(cfg, step):
    from OCP.BRepCheck import BRepCheck_Analyzer

    title, parts, text, seconds = step
    assert title == "engine"  # the assembly product: the export's name
    assert cfg["title"][:40] in " ".join(text.split("FILE_SCHEMA")[0].split())
    assert re.search(r"SI_UNIT\(\.MILLI\.,\.METRE\.\)", text)
    fixed = {"cam_half_1", "cam_half_2", "z_shaft", "plate", "rotor_1", "rotor_2", "casing"}
    per_roller = {
        f"{p}_{s}" for p in ("roller", "roller_shaft", "rail_roller", "rail") for s in SLUGS
    }
    lobes = {f"cam_lobe_{s}_{h}" for s in SLUGS for h in (1, 2)}
    assert set(parts) == fixed | per_roller | lobes
    assert len(lobes) == cw.freed_regions(sph.from_config(cfg)[0])  # the slots free 8 lobes
    for name, shape in parts.items():
        solids = _solids(shape)
        assert len(solids) == 1, name
        assert BRepCheck_Analyzer(solids[0]).IsValid(), name
        assert _volume(solids[0]) > 0.0, name
    assert seconds < 120.0  # the export's time is reported (see docs/cams.md), not tested here


# --------------------------------------------------------------------------------------------
# placed at theta = 0
# --------------------------------------------------------------------------------------------
def test_parts_placed_at_theta_zero(cfg, step):
    """Rollers on their shafts' axes (the paper's eq. 8 at theta = 0), lobes by their grooves."""
    _, parts, _, _ = step
    ex = Explicit()
    cam = sph.from_config(cfg)[1]
    for k, slug in enumerate(SLUGS):
        axis = ex.fixed(0.0, k)[..., 0] / R
        c = _centre(parts[f"roller_{slug}"]) * 1e-3
        assert np.linalg.norm(np.cross(c, axis)) < 1e-9
        assert np.dot(c, axis) == pytest.approx(0.5 * (RI + RI + LONGEST), abs=1e-9)
        c = _centre(parts[f"rail_roller_{slug}"]) * 1e-3
        assert np.dot(c, axis) == pytest.approx(0.08, abs=1e-9)  # drive.rail_radius
        assert np.linalg.norm(np.cross(c, axis)) < 1e-9
    assert cam.roller_length == pytest.approx(LONGEST, rel=1e-12)
    # each lobe lies in the cam half of its sign of x, next to its own groove
    t = np.linspace(0, np.pi, 2000)
    for name in (n for n in parts if n.startswith("cam_lobe_")):
        _, _, slug, half = name.split("_")
        c = _centre(parts[name])
        assert np.sign(c[0]) == (1 if half == "1" else -1)
        g = ex.groove(t, SLUGS.index(slug))
        assert np.min(np.linalg.norm(g * 1e3 - c, axis=1)) < 15.0


# --------------------------------------------------------------------------------------------
# sizes: bores, groove width, roller and rail fits
# --------------------------------------------------------------------------------------------
def _cylinders(shape):
    """``(radius [mm], axis direction, location)`` of every cylindrical face."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_Cylinder
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    out, ex = [], TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        s = BRepAdaptor_Surface(TopoDS.Face(ex.Current()))
        if s.GetType() == GeomAbs_Cylinder:
            c = s.Cylinder()
            d, p = c.Axis().Direction(), c.Axis().Location()
            out.append(
                (c.Radius(), np.array([d.X(), d.Y(), d.Z()]), np.array([p.X(), p.Y(), p.Z()]))
            )
        ex.Next()
    return out


def test_bores_and_fits_at_their_sizes(cfg, step):
    _, parts, _, _ = step
    # the cam's bores on its axis: the Z-shaft (15 mm) plus 2 x cad.gap (1 mm)
    for half in ("cam_half_1", "cam_half_2"):
        on_axis = [c for c in _cylinders(parts[half])
                   if abs(abs(c[1][0]) - 1) < 1e-9 and np.hypot(*c[2][1:]) < 1e-6]  # fmt: skip
        assert on_axis and all(c[0] == pytest.approx(8.5, abs=1e-6) for c in on_axis)
    journals = [c[0] for c in _cylinders(parts["z_shaft"]) if abs(abs(c[1][0]) - 1) < 1e-9]
    assert journals and np.allclose(journals, 7.5, atol=1e-6)
    ex = Explicit()
    for k, slug in enumerate(SLUGS):
        axis = ex.fixed(0.0, k)[..., 0] / R
        radii = sorted(c[0] for c in _cylinders(parts[f"roller_{slug}"]))
        assert all(
            abs(abs(np.dot(c[1], axis)) - 1) < 1e-9 for c in _cylinders(parts[f"roller_{slug}"])
        )
        # bore: the 4 mm shaft plus its H8/f7 clearance; outside: the 8 mm roller
        assert radii[0] == pytest.approx(2.0 + 0.5 * FIT_4 * 1e3, abs=1e-9)
        assert radii[-1] == pytest.approx(4.0, abs=1e-9)
        shaft = [c[0] for c in _cylinders(parts[f"roller_shaft_{slug}"])]
        assert np.allclose(shaft, 2.0, atol=1e-9)
        rr = sorted(c[0] for c in _cylinders(parts[f"rail_roller_{slug}"]))
        assert rr[-1] == pytest.approx(6.0, abs=1e-9)


def _planes(shape):
    """``(normal, offset [mm])`` of every planar face."""
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.GeomAbs import GeomAbs_Plane
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    out, ex = [], TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        s = BRepAdaptor_Surface(TopoDS.Face(ex.Current()))
        if s.GetType() == GeomAbs_Plane:
            pl = s.Plane()
            n, p = pl.Axis().Direction(), pl.Location()
            n = np.array([n.X(), n.Y(), n.Z()])
            out.append((n, float(np.dot(n, [p.X(), p.Y(), p.Z()]))))
        ex.Next()
    return out


def test_rails_fit_their_rollers(cfg, step):
    """The rail's walls stand 6 mm + half the 12 mm roller's H8/f7 clearance off its plane."""
    _, parts, _, _ = step
    phi_1 = np.arctan2(*Explicit().fixed(0.0, 0)[1:3, 0])  # rotor 1's angle at theta = 0
    normal = np.array([0.0, np.cos(phi_1), -np.sin(phi_1)])  # of rotor 1's meridian plane
    offsets = sorted(abs(o) for n, o in _planes(parts["rail_1"]) if abs(abs(n @ normal) - 1) < 1e-9)
    assert offsets[0] == pytest.approx(6.0 + 0.5 * FIT_12 * 1e3, abs=1e-9)


# --------------------------------------------------------------------------------------------
# the grooves' walls by ray casting, against guided()
# --------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def rays(cfg, step):
    """Distances to the walls along +-n from the roller axes, over one groove period."""
    from OCP.BRep import BRep_Builder
    from OCP.gp import gp_Dir, gp_Lin, gp_Pnt
    from OCP.IntCurvesFace import IntCurvesFace_ShapeIntersector
    from OCP.TopoDS import TopoDS_Compound

    _, parts, _, _ = step
    comp, builder = TopoDS_Compound(), BRep_Builder()
    builder.MakeCompound(comp)
    for name, shape in parts.items():
        if name.startswith("cam_"):
            builder.Add(comp, shape)
    inter = IntCurvesFace_ShapeIntersector()
    inter.Load(comp, 1e-7)
    ex = Explicit()
    theta = (np.arange(720) + 0.5) * np.pi / 720  # every 0.25 deg
    # the roller's ends and middle; the middle of the slot's layer, R_b..R_o
    lam = np.array([RI, 0.5 * (RI + RI + LONGEST), RI + LONGEST, 0.5 * (RB + RO)]) * 1e3
    dist = np.full((4, 2, len(lam), len(theta)), np.inf)
    for k in range(4):
        g = ex.groove(theta, k)
        e = g / np.linalg.norm(g, axis=1, keepdims=True)
        tan = ex.d(ex.groove, theta, k)
        n = np.cross(e, tan / np.linalg.norm(tan, axis=1, keepdims=True))
        for j in range(len(theta)):
            for s, sign in enumerate((1.0, -1.0)):
                d = gp_Dir(*(sign * n[j]))
                for m, lm in enumerate(lam):
                    inter.Perform(gp_Lin(gp_Pnt(*(lm * e[j])), d), 0.0, 30.0)
                    if inter.NbPnt():
                        dist[k, s, m, j] = min(
                            inter.WParameter(i) for i in range(1, inter.NbPnt() + 1)
                        )
    return theta, dist


def test_rollers_run_between_their_walls_with_the_clearance(rays):
    """Where a wall is there it stands rho + c/2 off the roller axis, to within 1 um."""
    _, dist = rays
    dist = dist[:, :, :3]
    present = np.abs(dist - HALF * 1e3) < 0.01
    assert present.mean() > 0.8
    dev = np.abs(dist[present] - HALF * 1e3)
    assert dev.max() < 1e-3  # mm: the loft between its exact sections
    assert np.all(dist[present] - RHO * 1e3 > 0.5 * FIT_8 * 1e3 - 1e-3)  # running clearance
    print(f"groove walls: largest deviation from rho + c/2 over {present.sum()} rays: "
          f"{dev.max() * 1e3:.3f} um")  # fmt: skip


def test_guided_agrees_with_ray_casting_on_the_solid(cfg, rays):
    """The share of a groove period with both walls along the contact line, per roller."""
    theta, dist = rays
    drive, cam = sph.from_config(cfg)
    walls = np.all(
        np.abs(dist[:, :, :3] - HALF * 1e3) < 0.01, axis=2
    )  # (4, 2, n): all 3 points on a wall
    both = walls.all(axis=1)
    got = sph.guided(drive, cam, theta)
    for k in range(4):
        flips = np.flatnonzero(np.diff(both[k]))
        assert len(flips) == 4  # 2 crossings passed per groove period, a gap around each
        near = np.zeros(len(theta), bool)
        for f in flips:
            near[max(f - 1, 0) : f + 3] = True
        assert np.array_equal(got[k][~near], both[k][~near])
        # the fractions agree to within the sampling (one sample per end of a gap)
        assert abs(got[k].mean() - both[k].mean()) <= 4.5 / len(theta)
    print(f"both walls: ray casting {both.mean():.4f}, guided() {got.mean():.4f} of the turn")


def test_slots_are_the_shafts_swept_region_with_its_clearance(rays):
    """Outside the groove bottom the shaft (4 mm) passes a slot 4 mm + 1 mm wide.

    Away from the crossings' assembly windows (radius h + 0.5 mm around each crossing
    point) the slot's sides stand r_s + slot_clearance/2 = 2.5 mm off the shaft's axis.
    """
    theta, dist = rays
    ex = Explicit()
    crossings = [ex.groove(t, k) for k, t in ((0, np.pi / 8), (1, np.pi / 8), (2, 3 * np.pi / 8),
                                              (3, 3 * np.pi / 8))]  # fmt: skip
    slot = dist[:, :, 3]
    for k in range(4):
        g = ex.groove(theta, k)
        away = np.min([np.linalg.norm(g - c, axis=1) for c in crossings], axis=0) > 0.012
        assert np.allclose(slot[k][:, away], 2.5, atol=1e-3)
        assert np.all(slot[k][:, ~away] >= 2.5 - 1e-3)


def test_iso_286_close_running_fit_from_the_tables():
    """H8/f7 clearances against ISO 286-2's tables (hole H8: 0..IT8, shaft f7: es-IT7..es)."""
    from rotorkin.analysis.fits import fit_clearance

    # diameter [mm]: (smallest, largest) clearance [um]; 10 mm still in the range 6..10
    table = {2: (6, 30), 8: (13, 50), 10: (13, 50), 10.5: (16, 61), 25: (20, 74),
             50: (25, 89), 100: (36, 125), 400: (62, 208)}  # fmt: skip
    for d, (lo, hi) in table.items():
        assert fit_clearance("H8/f7", d * 1e-3, "min") == pytest.approx(lo * 1e-6, abs=1e-12)
        assert fit_clearance("H8/f7", d * 1e-3, "max") == pytest.approx(hi * 1e-6, abs=1e-12)
        mean = fit_clearance("H8/f7", d * 1e-3)
        assert mean == pytest.approx(0.5 * (lo + hi) * 1e-6, abs=1e-12)
    assert fit_clearance("H8/f7", np.array([0.008, 0.004, 0.012])) == pytest.approx(
        [FIT_8, FIT_4, FIT_12], abs=1e-12
    )


# --------------------------------------------------------------------------------------------
# refusals
# --------------------------------------------------------------------------------------------
def test_roller_too_long_refused_in_one_line(tmp_path, capsys):
    code = main(["export", "-e", "wobble-cam-engine", "--set", 'cam.roller_length="9 mm"',
                 "-f", "step", "-o", str(tmp_path / "out")])  # fmt: skip
    err = capsys.readouterr().err.strip().removeprefix("rotorkin: error: ")
    assert code == 2 and "\n" not in err
    assert err.startswith("cam.roller_length = 9 mm is not admissible")
    largest = float(re.search(r"roller_length <= ([0-9.]+) mm", err).group(1))
    assert largest == pytest.approx(LONGEST * 1e3, abs=1e-3)
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    ("key", "value"),
    [("cam.bore_diameter", '"80 mm"'), ("cam.slot_clearance", '"5 mm"'),
     ("cad.roller_shaft_diameter", '"8 mm"'), ("cad.plate_radius", '"53.5 mm"'),
     ("cam.running_clearance", '"2.5 mm"'), ("cam.roller_end_gap", '"7.9 mm"'),
     ("drive.plate_bearing_span", '"45 mm"')],
)  # fmt: skip
def test_sizes_that_do_not_fit_refused_in_one_line(tmp_path, capsys, key, value):
    """export refuses them; run refuses the cam's own sizes alike and flags the assembly's:
    a warning with export's line, a failed check."""
    code = main(["export", "-e", "wobble-cam-engine", "--set", f"{key}={value}", "-f", "step",
                 "-o", str(tmp_path / "out")])  # fmt: skip
    err = capsys.readouterr().err.strip().removeprefix("rotorkin: error: ")
    assert code == 2 and "\n" not in err and err.startswith(f"{key} = ")
    assert not (tmp_path / "out").exists()
    code = main(["run", "-e", "wobble-cam-engine", "--set", f"{key}={value}",
                 "-o", str(tmp_path / "run")])  # fmt: skip
    err_run = capsys.readouterr().err
    if key in ("cam.running_clearance", "cam.roller_end_gap"):  # the cam itself: refused
        assert code == 2 and err_run.strip().removeprefix("rotorkin: error: ") == err
        return
    assert code == 0 and f"rotorkin: warning: {err} (wobble cam: STEP assembly" in err_run
    checks = (tmp_path / "run" / "checks.csv").read_text()
    assert "wobble cam: STEP assembly parts that do not fit" in checks and key in checks


# --------------------------------------------------------------------------------------------
# no interference at a set of shaft angles
# --------------------------------------------------------------------------------------------
def _body(name: str) -> str:
    if name.startswith("cam_"):
        return "cam"
    if name in ("plate", "z_shaft", "casing", "rotor_1", "rotor_2"):
        return name
    if name.startswith("rail_roller") or name.startswith("roller"):
        return "plate"
    return "rotor_1" if name in ("rail_1", "rail_1p") else "rotor_2"


def _rotations(theta: float) -> dict:
    """Every body's rotation at theta, from the paper's matrices written out here."""
    ex = Explicit()
    phi = [np.arctan2(*ex.fixed(theta, k)[1:3, 0]) for k in (0, 2)]  # shafts' projections
    return {
        "cam": _rot_x(-theta),  # psi = -theta (eq. 9)
        "z_shaft": _rot_x(theta),
        "plate": _rot_x(theta) @ _rot_y(PHI) @ _rot_x(-2.0 * theta),  # eq. 5, varphi = -2 theta
        "rotor_1": _rot_x(phi[0]),
        "rotor_2": _rot_x(phi[1]),
        "casing": np.eye(3),
    }


def _moved(shape, rot):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.gp import gp_Trsf

    trsf = gp_Trsf()
    trsf.SetValues(*rot[0], 0.0, *rot[1], 0.0, *rot[2], 0.0)
    return BRepBuilderAPI_Transform(shape, trsf, True).Shape()


def _box(shape):
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib

    box = Bnd_Box()
    BRepBndLib.Add_s(shape, box)
    lo, hi = box.CornerMin(), box.CornerMax()
    return np.array([[lo.X(), lo.Y(), lo.Z()], [hi.X(), hi.Y(), hi.Z()]])


def _common_volume(a, b) -> float:
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common

    op = BRepAlgoAPI_Common(a, b)
    assert op.IsDone()
    return _volume(op.Shape())


#: Tessellation deflection [mm] and the margin added to the farthest tessellation vertex.
_DEFLECTION, _MARGIN = 0.02, 0.2


def _mesh_points(shape) -> np.ndarray:
    """Vertices of a tessellation of the shape within _DEFLECTION [mm], (n, 3)."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepMesh import BRepMesh_IncrementalMesh
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopLoc import TopLoc_Location
    from OCP.TopoDS import TopoDS

    BRepMesh_IncrementalMesh(shape, _DEFLECTION, False, 0.1, True)
    out, ex = [], TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        loc = TopLoc_Location()
        tri = BRep_Tool.Triangulation_s(TopoDS.Face(ex.Current()), loc)
        trsf = loc.Transformation()
        for i in range(1, tri.NbNodes() + 1):
            p = tri.Node(i).Transformed(trsf)
            out.append((p.X(), p.Y(), p.Z()))
        ex.Next()
    return np.array(out)


def _reach(shape, axis=False):
    """Smallest and largest distance of a part from O (or from the x axis) [mm]."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeVertex
    from OCP.BRepClass3d import BRepClass3d_SolidClassifier
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.gp import gp_Pnt
    from OCP.TopAbs import TopAbs_IN

    pts = _mesh_points(shape)
    if axis:
        probe = BRepBuilderAPI_MakeEdge(gp_Pnt(-1e3, 0, 0), gp_Pnt(1e3, 0, 0)).Edge()
        far = np.max(np.hypot(pts[:, 1], pts[:, 2])) + _MARGIN
    else:
        probe = BRepBuilderAPI_MakeVertex(gp_Pnt(0, 0, 0)).Vertex()
        far = np.max(np.linalg.norm(pts, axis=1)) + _MARGIN
    near = BRepExtrema_DistShapeShape(probe, shape).Value()
    inside = BRepClass3d_SolidClassifier(shape, gp_Pnt(0, 0, 0), 1e-7).State() == TopAbs_IN
    return (
        (0.0 if inside else near),
        far,
        np.array([pts[:, 0].min(), pts[:, 0].max()])
        + [
            -_MARGIN,
            _MARGIN,
        ],
    )


def _quadrants(shape) -> list:
    """The shape cut into its 4 quadrants about the x axis (y, z signs): smaller faces."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
    from OCP.gp import gp_Pnt

    out = []
    for sy, sz in itertools.product((-1, 1), (-1, 1)):
        lo = gp_Pnt(-200, min(0, 200 * sy), min(0, 200 * sz))
        box = BRepPrimAPI_MakeBox(lo, gp_Pnt(200, max(0, 200 * sy), max(0, 200 * sz))).Shape()
        out += _solids(BRepAlgoAPI_Common(shape, box).Shape())
    return out


@pytest.mark.slow
def test_no_interference_over_the_turn(step):
    """Boolean common volume 0 between every two parts that can meet, over the turn.

    Parts of one body are checked once (and the casing, a body of revolution, once against
    every part turning about x); two bodies turning about x (cam shell, Z-shaft, rotors)
    whose (x, distance from x) shadows do not overlap, or two parts whose distances from O
    (kept by every rotation about O) do not overlap, can never meet. The rest are checked
    at 72 shaft angles, every 5 deg from 2.5 deg (the crossings at 22.5 deg + k 45 deg
    among them); the cam against the plate's parts at the 36 of the first 180 deg, after
    which their relative motion repeats (the groove period), the cam's halves cut in
    quadrants for speed.
    """
    _, parts, _, _ = step
    names = sorted(parts)
    solids = {n: _solids(parts[n])[0] for n in names}
    about_x = {"cam", "z_shaft", "rotor_1", "rotor_2", "casing"}
    reach = {n: _reach(solids[n]) for n in names}
    shadow = {n: _reach(solids[n], axis=True) for n in names if _body(n) in about_x}
    checked, moving = 0, []
    t0 = time.perf_counter()
    for a, b in itertools.combinations(names, 2):
        ba, bb = _body(a), _body(b)
        (na, fa, _), (nb, fb, _) = reach[a], reach[b]
        apart = na > fb or nb > fa
        if ba in about_x and bb in about_x:
            (ra, sa, xa), (rb, sb, xb) = shadow[a], shadow[b]
            apart |= ra > sb or rb > sa or xa[0] > xb[1] or xb[0] > xa[1]
        if apart:
            continue
        if ba == bb or "casing" in (ba, bb) and {ba, bb} <= about_x:  # fixed relative shape
            assert _common_volume(solids[a], solids[b]) < 1e-6, (a, b)
            checked += 1
        else:
            moving.append((a, b))
    rest = time.perf_counter() - t0
    pieces = {n: [solids[n]] for n in names}
    for half in ("cam_half_1", "cam_half_2"):
        pieces[half] = _quadrants(solids[half])
    t0 = time.perf_counter()
    base = _rotations(0.0)
    worst = 0.0
    for theta in np.radians(np.arange(2.5, 360.0, 5.0)):
        rot = _rotations(theta)
        pairs = [(a, b) for a, b in moving
                 if theta < np.pi or {_body(a), _body(b)} != {"cam", "plate"}]  # fmt: skip
        placed = {}
        for n in {x for pair in pairs for x in pair}:
            turn = rot[_body(n)] @ base[_body(n)].T
            placed[n] = [(p, _box(p)) for p in (_moved(q, turn) for q in pieces[n])]
        for a, b in pairs:
            for (pa, (lo_a, hi_a)), (pb, (lo_b, hi_b)) in itertools.product(placed[a], placed[b]):
                if np.any(lo_a > hi_b) or np.any(lo_b > hi_a):
                    continue
                v = _common_volume(pa, pb)
                worst = max(worst, v)
                assert v < 1e-6, (a, b, np.degrees(theta), v)
                checked += 1
    print(f"interference: {checked} booleans, {len(moving)} moving pairs, at rest "
          f"{rest:.1f} s, over the turn {time.perf_counter() - t0:.1f} s, largest "
          f"{worst:.2e} mm^3")  # fmt: skip
