"""The ``rotorkin export`` command: every example in every format, checks printed, bad input."""

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from rotorkin.cli import main
from rotorkin.drives.rhomboid_cam import kinematics as rc

PLANAR = ["rhomboid-engine", "eccentric-reactor", "guide-bar-pump"]
EXPECTED = {  # files of each planar example (stems after "<name>_")
    "rhomboid-engine": ["rhomboid_cam"],
    "eccentric-reactor": ["disc_left", "disc_right"],
    "guide-bar-pump": ["impeller_1", "impeller_2"],
}


def _files(folder):
    """Names of the files written in ``folder`` (not the hidden manifest of the output helper)."""
    return sorted(p.name for p in Path(folder).iterdir() if not p.name.startswith("."))


def _run(capsys, *args):
    code = main(["export", *args])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("example", PLANAR)
@pytest.mark.parametrize("fmt", ["dxf", "stl", "csv"])
def test_every_planar_example_every_format(tmp_path, capsys, example, fmt):
    out_dir = tmp_path / "cad"
    code, out, err = _run(capsys, "-e", example, "--format", fmt, "--out", str(out_dir))
    assert code == 0, err
    names = _files(out_dir)
    if fmt == "csv":
        for stem in EXPECTED[example]:
            assert any(n.startswith(f"{example}_{stem}_") and n.endswith(".csv") for n in names)
    else:
        assert names == sorted(f"{example}_{s}.{fmt}" for s in EXPECTED[example])
    for n in names:
        assert n in out  # every file is listed
        assert (out_dir / n).stat().st_size > 0
    assert [p.name for p in tmp_path.iterdir()] == ["cad"]  # no staging folder left


@pytest.mark.cad
@pytest.mark.parametrize("example", PLANAR)
def test_every_planar_example_step(tmp_path, capsys, example):
    pytest.importorskip("build123d", reason="STEP export needs the [cad] extra (build123d)")
    code, out, err = _run(capsys, "-e", example, "-f", "step", "-o", str(tmp_path))
    assert code == 0, err
    names = _files(tmp_path)
    parts = [*EXPECTED[example], "assembly"]  # one file per part and the assembly of them all
    assert names == sorted(f"{example}_{s}.step" for s in parts)
    assert all(n in out for n in names)


def test_default_out_folder(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, _ = _run(capsys, "-e", "eccentric-reactor", "-q")
    assert code == 0 and out == ""
    made = _files(tmp_path / "rotorkin-out" / "eccentric-reactor" / "cad")
    assert made == ["eccentric-reactor_disc_left.dxf", "eccentric-reactor_disc_right.dxf"]


def test_checks_printed(tmp_path, capsys):
    code, out, _ = _run(capsys, "-e", "rhomboid-engine", "-f", "csv", "-o", str(tmp_path))
    assert code == 0
    # independent: tan mu = -tan(psi/2) psi'/2 on a dense grid (first-harmonic law, eq. 16)
    a = np.linspace(0, np.pi, 200_001)
    a1 = np.pi / 2 - np.radians(40)
    psi, dpsi = np.pi / 2 + a1 * np.cos(2 * a), -2 * a1 * np.sin(2 * a)
    mu = np.degrees(np.max(np.abs(np.arctan(np.tan(psi / 2) * dpsi / 2))))
    assert f"{mu:.4g}" in out and "max pressure angle" in out
    r_min = 1e3 / np.max(rc.profile_curvature(0.12, np.radians(40), (), (), a))
    assert f"{r_min:.4g}" in out and "min convex radius" in out
    code, out, _ = _run(capsys, "-e", "eccentric-reactor", "-f", "csv", "-o", str(tmp_path))
    line = next(ln for ln in out.splitlines() if "max pressure angle" in ln)
    assert "30 at 90 deg" in line  # arcsin(e/R) = arcsin(0.5)


@pytest.mark.parametrize(
    "args,needle",
    [
        (["-e", "rhomboid-engine", "-f", "iges"], "--format"),
        (["-e", "rhomboid-engine", "-s", "cam.roller_radius=60 mm"], "cam.roller_radius"),
        (["-e", "rhomboid-engine", "-s", "cam.thickness=-1 mm"], "cam.thickness"),
        (["-e", "eccentric-reactor", "-s", "drive.eccentricity=90 mm"], "drive.eccentricity"),
        (["-e", "no-such-example"], "no-such-example"),
    ],
)
def test_bad_input_one_line_exit_2_nothing_written(tmp_path, capsys, args, needle):
    code, out, err = _run(capsys, *args, "-o", str(tmp_path / "cad"))
    assert code == 2
    assert err.count("\n") == 1 and needle in err and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []


def test_undercut_message_names_the_angle(tmp_path, capsys):
    code, _, err = _run(capsys, "-e", "rhomboid-engine", "-s", "cam.roller_radius=60 mm",
                        "-o", str(tmp_path))  # fmt: skip
    assert code == 2
    # the smallest convex radius of curvature of the pitch curve, found independently
    a = np.linspace(0, np.pi / 2, 400_001)
    k = rc.profile_curvature(0.12, np.radians(40), (), (), a)
    assert f"at alpha = {np.degrees(a[np.argmax(k)]):.4g} deg" in err
    assert f"smallest convex radius of curvature is {1e3 / k.max():.4g} mm" in err
    # the admissible range is set by the waist: rho_min = 2l cos(psi_max / 2), psi_max = 140 deg
    waist = 120 * np.cos(np.radians(70))
    assert f"roller_radius < {np.floor(waist * 100) / 100:.4g} mm" in err


def _limit(err: str) -> float:
    return float(err.split("roller_radius < ")[1].split(" mm")[0])


def test_roller_limit_is_stated_and_right(tmp_path, capsys):
    """The stated largest roller radius: one a hair below passes, one digit above fails."""
    code, _, err = _run(capsys, "-e", "rhomboid-engine", "-s", "cam.roller_radius=50 mm",
                        "-o", str(tmp_path / "a"))  # fmt: skip
    assert code == 2 and err.count("\n") == 1 and "overlaps another flank" in err
    limit = _limit(err)
    assert limit == pytest.approx(120 * np.cos(np.radians(70)), abs=0.01)  # the waist
    below = f"cam.roller_radius={limit * (1 - 1e-4):.6f} mm"
    code, _, err = _run(capsys, "-e", "rhomboid-engine", "-s", below, "-f", "csv",
                        "-o", str(tmp_path / "b"))  # fmt: skip
    assert code == 2 and "export.bore = (default)" in err  # a cam that leaves no room for a bore
    code, _, err = _run(capsys, "-e", "rhomboid-engine", "-s", below, "-s", "export.bore=0 mm",
                        "-f", "csv", "-o", str(tmp_path / "b"))  # fmt: skip
    assert code == 0, err
    above = f"cam.roller_radius={limit + 0.01:.6f} mm"  # the limit is rounded down to 0.01 mm
    code, _, err = _run(capsys, "-e", "rhomboid-engine", "-s", above, "-f", "csv",
                        "-o", str(tmp_path / "c"))  # fmt: skip
    assert code == 2 and _limit(err) == limit
    assert not (tmp_path / "c").exists()


@pytest.mark.parametrize(
    "example,diameter",
    [
        # the cam's outer diameter: 2 (rho_max - r), rho_max = 2l cos(psi_min / 2)
        ("rhomboid-engine", 2 * (120 * np.cos(np.radians(20)) - 10)),
        ("eccentric-reactor", 160.0),  # the disc's diameter 2R
    ],
)
def test_thickness_has_an_upper_bound(tmp_path, capsys, example, diameter):
    code, _, err = _run(capsys, "-e", example, "-s", 'cam.thickness="1e9 mm"', "-f", "stl",
                        "-o", str(tmp_path / "a"))  # fmt: skip
    assert code == 2 and err.count("\n") == 1
    assert "cam.thickness = 1e+09 mm" in err and f"thickness <= {diameter:.4g} mm" in err
    assert not (tmp_path / "a").exists()
    import trimesh

    ok = f"cam.thickness={diameter * (1 - 1e-4):.6f} mm"
    code, _, err = _run(capsys, "-e", example, "-s", ok, "-f", "stl", "-o", str(tmp_path / "b"))
    assert code == 0, err
    mesh = trimesh.load(sorted((tmp_path / "b").glob("*.stl"))[0])
    assert np.ptp(mesh.vertices[:, 2]) == pytest.approx(diameter * (1 - 1e-4), rel=1e-6)
    code, _, err = _run(capsys, "-e", example, "-s", f"cam.thickness={diameter + 0.1:.6f} mm",
                        "-f", "stl", "-o", str(tmp_path / "c"))  # fmt: skip
    assert code == 2 and "cam.thickness" in err


@pytest.mark.slow
def test_subprocess(tmp_path):
    res = subprocess.run(
        [sys.executable, "-m", "rotorkin.cli", "export", "-e", "guide-bar-pump", "-f", "dxf",
         "-o", str(tmp_path)],
        capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert res.returncode == 0, res.stderr
    assert _files(tmp_path) == [
        "guide-bar-pump_impeller_1.dxf",
        "guide-bar-pump_impeller_2.dxf",
    ]
    bad = subprocess.run(
        [sys.executable, "-m", "rotorkin.cli", "export", "-e", "guide-bar-pump", "-f", "obj",
         "-o", str(tmp_path / "x")],
        capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1
    assert not (tmp_path / "x").exists()


WOBBLE = ["-e", "wobble-cam-engine", "-s", "cam.roller_radius=4 mm"]


@pytest.mark.parametrize("fmt", ["dxf", "csv"])
def test_wobble_example(tmp_path, capsys, fmt):
    pytest.importorskip("rotorkin.drives.wobble_cam.cad")
    code, out, err = _run(capsys, *WOBBLE, "-f", fmt, "-o", str(tmp_path))
    assert code == 0, err
    names = _files(tmp_path)
    assert names and all(n.endswith(f".{fmt}") and n in out for n in names)


@pytest.mark.slow
@pytest.mark.parametrize("fmt", ["stl", "step"])
def test_wobble_example_solids(tmp_path, capsys, fmt):
    pytest.importorskip("rotorkin.drives.wobble_cam.cad")
    if fmt == "step":
        pytest.importorskip("build123d", reason="STEP export needs the [cad] extra (build123d)")
    code, out, err = _run(capsys, *WOBBLE, "-f", fmt, "-o", str(tmp_path))
    assert code == 0, err
    assert [Path(n).suffix for n in _files(tmp_path)] == [f".{fmt}"]


def test_wobble_checks_table(tmp_path, capsys, monkeypatch):
    """Readable rows; the pressure angle away from the crossings, where, and the best roller."""
    from rotorkin.drives.wobble_cam import cam as sph
    from rotorkin.io.config import load_config

    monkeypatch.setenv("COLUMNS", "200")  # rich: one line per row
    code, out, err = _run(capsys, "-e", "wobble-cam-engine", "-f", "csv", "-o", str(tmp_path))
    assert code == 0, err
    assert "cam_" not in out  # no raw summary keys
    table = " ".join(out.split())
    row = next(ln for ln in out.splitlines() if "one roller away from the crossings" in ln)
    assert "90 at theta = 22.5 deg (roller 2)" in row
    drive, cam = sph.from_config(load_config(None, "wobble-cam-engine", [])[0])
    # the best-placed roller, on a grid of its own (not the command's 2881 samples)
    theta = np.radians(np.arange(0.0, 360.0, 0.0625))
    mu = np.degrees(sph.pressure_angle(drive, theta))
    best = mu.min(axis=0)
    assert f"{best.max():.4g} at theta = {np.degrees(theta[np.argmax(best)]):.4g} deg" in table
    assert "best-placed roller" in table and "away from the crossings" in table
    # one roller reaches 90 deg at theta = 22.5 deg: roller 2 at its lobe tip, 45 deg of
    # shaft angle from its own crossings (67.5 deg, 157.5 deg), i.e. between both walls
    crossings = sph.groove_crossings(drive)
    own = [np.degrees(c.theta) for c in crossings if c.rollers == (2, 2)][0]
    assert np.allclose(np.sort(own), [67.5, 157.5])
    assert "90 at theta = 22.5 deg (roller 2)" in table
    assert "4 self, 0 between grooves; min angle 45 deg, unguided" in table
    # one wall or the other is missing over about 2 h (cot a + 1/sin a) r / R_i of the path
    # (straight branches crossing at a = 45 deg; h = 4 mm + 31.5 um / 2, r = 60, R_i = 54 mm)
    length = float(re.search(r"unguided ([0-9.]+) mm", table).group(1))
    assert length == pytest.approx(2 * 4.01575 * (1 + np.sqrt(2)) * 60 / 54, rel=0.06)
