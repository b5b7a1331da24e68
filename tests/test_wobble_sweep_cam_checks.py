"""The spherical cam's and the rails' rules across a wobble-cam sweep.

The sphere radius is swept by the kernel; the cam shell, its grooves and rollers and the
rail rollers outside the shell are sized against it. A design whose cam ``run`` and
``export`` refuse is refused by the sweep with the same key, design by design, and the
vectorised rules are those the cam applies to one design.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.core.batch import Designs
from rotorkin.core.errors import ParameterError
from rotorkin.drives.wobble_cam import cam as cs
from rotorkin.drives.wobble_cam import forces as fo
from rotorkin.io.config import load_config
from rotorkin.sweep.engine import evaluate_designs, reason_keys
from sweep_equality import assert_reasons_of_study


def _designs(seed: int, n: int, sets=(), cam=True):
    cfg, _, _ = load_config(example="wobble-cam-engine", sets=list(sets))
    if not cam:
        cfg.pop("cam")
    rng = np.random.default_rng(seed)
    table = {
        "drive.sphere_radius": rng.uniform(0.0, 0.1, n),
        "drive.plate_tilt": np.radians(rng.uniform(20.0, 70.0, n)),
        "machine.compression_ratio": rng.uniform(0.5, 12.0, n),
    }
    return Designs(cfg, table, n)


@pytest.mark.parametrize(
    "seed, sets, cam, named",
    [
        (0, (), True, {"drive.rail_radius", "cam.shell_thickness", "ok"}),
        (1, ("cam.shell_thickness=30mm",), True, {"cam.groove_depth", "cam.shell_thickness"}),
        (2, (), False, {"drive.rail_radius", "ok"}),  # no [cam]: its rules are not export's
    ],
)
def test_a_cam_or_rail_that_does_not_fit_is_refused_with_the_studys_key(seed, sets, cam, named):
    p = _designs(seed, 40, sets, cam)
    res = evaluate_designs(p, ["chamber_swing_deg", "displacement_cm3_per_rev"], threads=1)
    assert_reasons_of_study(p, res["reason"], "wobble_cam")
    assert named <= {reason_keys("wobble_cam")[r] for r in res["reason"]}
    assert np.all(np.isnan(res["metrics"]["chamber_swing_deg"][res["reason"] != 0]))


def test_the_cli_sweep_marks_a_sphere_past_the_rails(tmp_path, capsys):
    import xarray as xr

    from rotorkin.cli import main

    out = tmp_path / "s"
    assert main(["sweep", "--vary", "drive.sphere_radius=50mm:80mm:4", "-o", str(out)]) == 0
    with xr.open_dataset(out / "sweep.nc") as ds:
        reason = ds["reason"].values
    # 50 and 60 mm fit inside the default 80 mm rails; 70 and 80 mm do not
    # (rail_radius > sphere_radius + shell_thickness/2 + rail_roller_radius = r + 12 mm)
    named = [reason_keys("wobble_cam")[r] for r in reason]
    assert named == ["ok", "ok", "drive.rail_radius", "drive.rail_radius"]


def _one_by_one(r, **cam):
    """The code of each design from the cam of that design alone (0: it builds)."""
    out = np.zeros(np.shape(r), dtype=int)
    for i, ri in np.ndenumerate(r):
        try:
            cs.SphericalCam(float(ri), **{k: float(np.broadcast_to(v, np.shape(r))[i])
                                          for k, v in cam.items()})  # fmt: skip
        except ParameterError as exc:
            out[i] = cs.CAM_CHECKED.index(exc.name) + 1
    return out


def test_the_vectorised_cam_rules_broadcast_as_one_design_each():
    rng = np.random.default_rng(3)
    r = rng.uniform(-0.01, 0.1, (6, 7))
    cam = {
        "shell_thickness": rng.uniform(0.0, 0.03, (6, 1)),
        "groove_depth": rng.uniform(0.004, 0.02, (1, 7)),
        "roller_radius": rng.uniform(0.0, 0.01, (6, 7)),
        "roller_end_gap": rng.uniform(0.0, 0.004, (6, 7)),
    }
    code = cs.cam_violation(r, **cam)
    assert code.shape == (6, 7)
    np.testing.assert_array_equal(code, _one_by_one(r, **cam))
    assert len(set(code.ravel())) >= 4  # admissible designs and three different rules


def test_an_admissible_cam_holds_its_geometry():
    # the rules as geometry: roller inside the shell's bore, groove reaching the roller
    # centres with a floor left, the roller's rim below the groove bottom
    rng = np.random.default_rng(4)
    r = rng.uniform(0.02, 0.1, 400)
    t = rng.uniform(0.002, 0.04, 400)
    d = rng.uniform(0.3, 1.1, 400) * t
    rho = rng.uniform(0.001, 0.01, 400)
    ok = cs.cam_violation(r, rho, t, d) == 0
    assert 50 < ok.sum() < 400
    for i in np.flatnonzero(ok)[:40]:
        cam = cs.SphericalCam(r[i], rho[i], t[i], d[i])
        assert cam.inner_radius > cam.roller_radius
        assert cam.inner_radius < cam.sphere_radius < cam.bottom_radius < cam.outer_radius
        inner, outer = cam.roller_span
        assert cam.inner_radius <= inner + 1e-12 < outer
        assert np.hypot(outer, cam.roller_radius) <= cam.bottom_radius - cam.roller_end_gap + 1e-12


def test_the_rail_rule_is_the_force_parameters_rule():
    cfg, _, _ = load_config(example="wobble-cam-engine")
    drive, cam = cs.from_config(cfg)
    least = cam.outer_radius + 0.006
    assert not fo.rail_violation(least + 1e-6, cam.outer_radius, 0.006)
    assert fo.rail_violation(np.array([least, least - 1e-3]), cam.outer_radius, 0.006).all()
    cfg["drive"]["rail_radius"] = least
    with pytest.raises(ParameterError, match="^drive.rail_radius"):
        fo.force_params(cfg, cam)


def test_a_wall_the_other_grooves_cut_away_everywhere_guides_no_roller():
    # a 10.5 mm sphere at 51 deg: the channels of the other branches cut one wall of a
    # groove over the whole turn; that roller is never between both walls
    from rotorkin.drives import evaluate
    from rotorkin.drives.wobble_cam import cam_walls

    sets = ["drive.sphere_radius=10.5mm", "drive.plate_tilt=51deg"]
    cfg, _, _ = load_config(example="wobble-cam-engine", sets=sets)
    drive, cam = cs.from_config(cfg)
    gaps = cam_walls.wall_gaps(drive, cam)
    whole = [g for g in gaps if g.end - g.start == g.period]
    assert whole
    theta = np.linspace(0.0, 2.0 * np.pi, 97)
    for g in whole:
        assert g.contains(theta).all()
        assert not cs.guided(drive, cam, theta)[g.roller].any()
    res = evaluate(cfg)
    assert res.summary["groove_crossing_fraction"] == 1.0
    assert any(w.startswith("cam.roller_radius = 4 mm undercuts") for w in res.warnings)


def test_a_cam_whose_roller_cannot_be_that_long_names_roller_length():
    with pytest.raises(ParameterError, match="^roller_length = 20 mm") as err:
        cs.SphericalCam(0.06, roller_length=0.02)
    assert "the largest that fits" in str(err.value)
