"""Design checks with margins in every command, and the admissible interval of one key.

Independent references: the scalar study (``rotorkin.drives.evaluate``, which refuses
in one line what the drive does not admit) at values a hair inside and outside each
end found by the vectorised scan and bisection; a scan of the study at evenly spaced
values; the spherical cam's undercut limit recomputed from its closed form.
"""

from __future__ import annotations

import csv
import math
import re

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rotorkin.cli import main
from rotorkin.core.errors import ConfigError, ParameterError
from rotorkin.drives import design_checks, evaluate
from rotorkin.drives.wobble_cam import cad as wcad
from rotorkin.drives.wobble_cam import cam as cs
from rotorkin.drives.wobble_cam.cad_layout import layout_from_config
from rotorkin.io.config import load_config, validate_config
from rotorkin.studies.checks import Check, failed, rows
from rotorkin.studies.limits import LIMITS
from rotorkin.sweep.interval import admissible_interval

# a plate bearing span that fits the shell at every tilt here (the default 40 mm binds the
# assembly above about 46 deg: see the test of the default below)
TILT_AT_75 = ['drive.roller_axis_angle="75 deg"', 'drive.plate_bearing_span="20 mm"']


def _admissible(raw: dict, key: str, text, with_limits: bool = False) -> bool:
    """The scalar study's verdict: no refusal, every check passed."""
    section, name = key.split(".")
    cfg_raw = {**raw, section: {**raw[section], name: text}}
    try:
        result = evaluate(validate_config(cfg_raw))
    except (ParameterError, ConfigError):
        return False
    bad = [c for c in failed(result.checks) if with_limits or c.key not in LIMITS]
    return not bad


# --- checks ---------------------------------------------------------------------------------
def test_a_check_margin_is_positive_inside_and_negative_outside():
    up = Check("x", "k", 3.0, 5.0, "mm")
    low = Check("y", "k", 3.0, 5.0, "mm", upper=False)
    assert (up.margin, up.passed) == (2.0, True)
    assert (low.margin, low.passed) == (-2.0, False)
    assert not Check("z", "k", math.nan, 1.0, "").passed  # no value: it does not pass
    assert rows([up])[0] == ("x", "3 mm", "<= 5 mm", "2 mm", "ok")
    assert rows([low])[0][-1] == "FAILS"


def test_the_wobble_cam_check_is_the_closed_form_undercut_limit():
    cfg, _, _ = load_config(None, "wobble-cam-engine", [])
    drive, cam = cs.from_config(cfg)
    kmax, _, _ = cs.sharpest_bend(drive)
    walls = cam.inner_radius / math.sqrt(1.0 + (drive.sphere_radius * kmax) ** 2)
    # the roller stands half the running clearance (ISO 286 H8/f7 at 8 mm: 31.5 um) inside
    limit = walls - 0.5 * 31.5e-6
    check, assembly = design_checks(cfg)
    assert check.key == "cam.roller_radius"
    assert check.limit == pytest.approx(limit * 1e3, rel=1e-12)
    assert check.value == pytest.approx(4.0, rel=1e-12)
    # the same limit as the refusal of export (check_roller_radius returns the walls')
    assert cs.check_roller_radius(drive, cam) == pytest.approx(walls, rel=1e-12)
    assert assembly.passed and assembly.value == 0.0  # the example's assembly fits


_CAM = st.tuples(
    st.floats(20.0, 56.0),  # plate tilt [deg]
    st.floats(1.0, 9.0),  # roller radius [mm]
    st.floats(4.0, 30.0),  # shell thickness [mm]
    st.floats(2.0, 30.0),  # groove depth [mm]
)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(_CAM)
def test_run_refuses_or_flags_every_cam_that_export_refuses(values):
    tilt, rho, shell, depth = values
    sets = [f'drive.plate_tilt="{tilt} deg"', f'cam.roller_radius="{rho} mm"',
            f'cam.shell_thickness="{shell} mm"', f'cam.groove_depth="{depth} mm"',
            'export.tolerance="0.05 mm"']  # fmt: skip
    try:
        cfg, _, _ = load_config(None, "wobble-cam-engine", sets)
    except (ParameterError, ConfigError):
        return  # refused by the schema: every command refuses it alike
    try:
        wcad.setup(cfg)  # the cam in every format
        layout_from_config(cfg)  # and the sizes of the STEP assembly
        export_refuses = False
    except ParameterError:
        export_refuses = True
    try:
        checks = design_checks(cfg)
        run_refuses, run_flags = False, bool(failed(checks))
    except ParameterError:
        run_refuses, run_flags = True, False
    if export_refuses:
        assert run_refuses or run_flags
    else:
        assert not run_refuses and not run_flags


def test_run_writes_and_prints_the_checks(tmp_path, capsys):
    out = tmp_path / "w35"
    assert main(["run", "-e", "wobble-cam-engine", "--set", 'drive.plate_tilt="35 deg"',
                 "--out", str(out)]) == 0  # fmt: skip
    text = capsys.readouterr()
    assert "checks" in text.out and "FAILS" in text.out
    with (out / "checks.csv").open() as fh:
        table = {r["check"]: r for r in csv.DictReader(fh)}
    roller = table["wobble cam: roller radius against undercut"]
    assert roller["passed"] == "false" and roller["key"] == "cam.roller_radius"
    # the margin is the limit less the value; the limit is the refusal's of export
    assert float(roller["margin"]) == pytest.approx(
        float(roller["limit"]) - float(roller["value"]), rel=1e-9
    )
    cfg, _, _ = load_config(None, "wobble-cam-engine", ['drive.plate_tilt="35 deg"'])
    with pytest.raises(ParameterError) as info:
        wcad.setup(cfg)
    refused = float(re.search(r"roller_radius < ([0-9.]+) mm", str(info.value)).group(1))
    assert float(roller["limit"]) == pytest.approx(refused, abs=1e-3)
    # the walls' limit 2.6045 mm less half the running clearance (31.5 um)
    assert float(roller["limit"]) == pytest.approx(2.6045 - 0.01575, abs=1e-4)


@pytest.mark.parametrize("example", ["rhomboid-engine", "eccentric-reactor"])
def test_planar_cam_checks_come_from_the_profile_export_checks(example):
    cfg, _, _ = load_config(None, example, [])
    checks = design_checks(cfg)
    undercut = [c for c in checks if c.name.endswith("roller radius against undercut")]
    assert undercut and all(c.passed for c in checks)
    from rotorkin.io.export import profile_checks

    (label, pc), *_ = profile_checks(cfg)
    assert undercut[0].limit == pytest.approx(pc.min_convex_radius * 1e3, rel=1e-12)
    assert undercut[0].value == pytest.approx(pc.roller_radius * 1e3, rel=1e-12)


# --- the admissible interval ----------------------------------------------------------------
@pytest.fixture(scope="module")
def tilt_interval():
    _, raw, _ = load_config(None, "wobble-cam-engine", TILT_AT_75)
    return raw, admissible_interval(raw, "drive.plate_tilt")


def test_tilt_interval_ends_against_the_study_a_hair_either_side(tilt_interval):
    raw, r = tilt_interval
    assert r.value_admissible and r.unit == "deg"
    eps = 1e-6  # deg
    for end in (r.lo, r.hi):
        inside = end + eps if end == r.lo else end - eps
        outside = end - eps if end == r.lo else end + eps
        assert _admissible(raw, "drive.plate_tilt", f"{inside!r} deg")
        assert not _admissible(raw, "drive.plate_tilt", f"{outside!r} deg")
    # the compression ratio binds above (at roller axis angle 75 deg, below eq. 20's limit)
    assert "machine.compression_ratio" in r.hi_binds
    assert r.hi < 57.33  # eq. 20 alone would allow up to 57.33 deg
    assert "cam.roller_radius" in r.lo_binds


def test_tilt_interval_against_a_scan_of_the_study(tilt_interval):
    raw, r = tilt_interval
    for tilt in map(float, np.linspace(30.0, 56.0, 14)):
        expected = r.lo <= tilt <= r.hi
        assert _admissible(raw, "drive.plate_tilt", f"{tilt!r} deg") == expected, tilt


def test_the_lower_end_is_where_the_undercut_limit_meets_the_roller(tilt_interval):
    _, r = tilt_interval
    cfg, _, _ = load_config(
        None, "wobble-cam-engine", [*TILT_AT_75, f'drive.plate_tilt="{r.lo!r} deg"']
    )
    check = design_checks(cfg)[0]
    assert check.limit == pytest.approx(check.value, abs=1e-6)  # mm


def test_the_default_plate_bearings_bind_the_tilt_where_they_stop_fitting(capsys):
    """With the default 40 mm plate bearing span the hub leaves the shell above about 46 deg:
    the interval's upper end is where the assembly's own limit of the span reaches 40 mm."""
    _, raw, _ = load_config(None, "wobble-cam-engine", [])
    r = admissible_interval(raw, "drive.plate_tilt")
    assert "drive.plate_bearing_span" in r.hi_binds
    cfg, _, _ = load_config(None, "wobble-cam-engine", [f'drive.plate_tilt="{r.hi + 1e-3!r} deg"'])
    where = design_checks(cfg)[1].where
    span = float(re.search(r"plate_bearing_span <= ([0-9.]+) mm", where).group(1))
    assert span == pytest.approx(40.0, abs=0.01)


def test_casing_radius_with_the_contact_limit(capsys):
    _, raw, _ = load_config(None, "guide-bar-pump", [])
    r = admissible_interval(raw, "machine.casing_radius", with_limits=True, points=21)
    assert r.value_admissible
    # below: the hub (30 mm) binds; above: the contact stress reaches its allowable
    assert r.lo == pytest.approx(30.0, abs=1e-6) and "hub_radius" in r.lo_binds
    assert "contact.allowable_stress" in r.hi_binds
    cfg, _, _ = load_config(None, "guide-bar-pump", [f'machine.casing_radius="{r.hi!r} mm"'])
    stress = evaluate(cfg).summary["peak_contact_stress_MPa"]
    assert stress == pytest.approx(1500.0, rel=1e-6)


def test_an_integer_key_lists_its_admissible_values():
    _, raw, _ = load_config(None, "wobble-cam-engine", [])
    r = admissible_interval(raw, "machine.pistons_per_rotor")
    assert r.value == 4 and r.value_admissible
    assert 2 in r.values and 4 in r.values and 3 not in r.values
    for n in range(2, 25):
        ok = any(a <= n <= b for a, b in r.intervals)
        assert _admissible(raw, "machine.pistons_per_rotor", n) == ok, n


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--key", "drive.nonsense"], "--key"),
        (["--key", "drive.type"], "--key"),
        (["--key", "drive.plate_tilt", "--points", "2"], "--points"),
        ([], "--key"),
    ],
)
def test_bad_limits_requests_are_one_line_exit_2(capsys, args, words):
    assert main(["limits", "-e", "wobble-cam-engine", *args]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and words in err[0]


def test_limits_command_prints_the_interval_and_what_binds(capsys):
    sets = [a for item in TILT_AT_75 for a in ("--set", item)]
    assert main(["limits", "-e", "wobble-cam-engine", *sets,
                 "--key", "drive.plate_tilt", "--points", "41"]) == 0  # fmt: skip
    out = capsys.readouterr().out
    assert "admissible from 41.19" in out and "to 51.8" in out
    assert "machine.compression_ratio" in out


def test_the_report_lists_the_same_checks(tmp_path):
    assert main(["report", "-e", "rhomboid-engine", "--out", str(tmp_path)]) == 0
    html = (tmp_path / "report.html").read_text()
    cfg, _, _ = load_config(None, "rhomboid-engine", [])
    for c in design_checks(cfg):
        assert c.name in html
    assert "margin" in html
