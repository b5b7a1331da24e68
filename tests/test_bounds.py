"""Every numeric key of every drive has an admissible range, and inside it every number is finite.

A value outside its range is refused in one line naming the key (``rotorkin run`` exits 2
and writes nothing); a value just inside is run with finite summary values; and values
sampled anywhere in the documented ranges (one key at a time, the example's other values)
either are refused in one line by a check that depends on other keys, or give a summary
whose non-finite numbers are all named by the result's warnings.
"""

from __future__ import annotations

import copy
import json
import math

import annotated_types as at
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from pydantic import BaseModel

from rotorkin import drives
from rotorkin.cli import main
from rotorkin.core.errors import RotorkinError
from rotorkin.io.config import load_config

EXAMPLES = {
    "wobble_cam": "wobble-cam-engine",
    "eccentric_cam": "eccentric-reactor",
    "guide_bar": "guide-bar-pump",
    "rhomboid_cam": "rhomboid-engine",
}

# (example, --set, the key the one-line error names)
REFUSED = [
    # wobble cam
    ("wobble-cam-engine", "drive.spin_ratio=1e-10", "drive.spin_ratio"),
    ("wobble-cam-engine", "drive.spin_ratio=0.3", "drive.spin_ratio"),
    ("wobble-cam-engine", "drive.spin_ratio=1e300", "drive.spin_ratio"),
    ("wobble-cam-engine", "drive.spin_ratio=20.5", "drive.spin_ratio"),
    ("wobble-cam-engine", "drive.plate_tilt=1e-9 rad", "drive.plate_tilt"),
    ("wobble-cam-engine", "drive.plate_tilt=0.49 deg", "drive.plate_tilt"),
    ("wobble-cam-engine", "drive.sphere_radius=0.9 mm", "drive.sphere_radius"),
    ("wobble-cam-engine", "drive.sphere_radius=1 km", "drive.sphere_radius"),
    ("wobble-cam-engine", "drive.spin_a=[0, 10.5]", "drive.spin_a.1"),
    ("wobble-cam-engine", "machine.compression_ratio=1e308", "machine.compression_ratio"),
    ("wobble-cam-engine", "drive.roller_axis_angle=0.5 deg", "drive.roller_axis_angle"),
    ("wobble-cam-engine", "machine.compression_ratio=1", "machine.compression_ratio"),
    ("wobble-cam-engine", "machine.pistons_per_rotor=26", "machine.pistons_per_rotor"),
    ("wobble-cam-engine", "machine.pistons_per_rotor=0", "machine.pistons_per_rotor"),
    ("wobble-cam-engine", "machine.axial_width=1 km", "machine.axial_width"),
    ("wobble-cam-engine", "machine.inner_radius=-1 mm", "machine.inner_radius"),
    ("wobble-cam-engine", "machine.inner_radius=80 mm", "machine.inner_radius"),
    ("wobble-cam-engine", "machine.clearance_volume=2 m^3", "machine.clearance_volume"),
    ("wobble-cam-engine", "machine.inertia_rotor_1=1e6 kg*m^2", "machine.inertia_rotor_1"),
    ("wobble-cam-engine", "machine.speed_fluctuation=1", "machine.speed_fluctuation"),
    ("wobble-cam-engine", "machine.speed_fluctuation=0.00009", "machine.speed_fluctuation"),
    ("wobble-cam-engine", "loads.polytropic_exponent=1.7", "loads.polytropic_exponent"),
    ("wobble-cam-engine", "loads.polytropic_exponent=1", "loads.polytropic_exponent"),
    ("wobble-cam-engine", "loads.ambient_pressure=2000 bar", "loads.ambient_pressure"),
    ("wobble-cam-engine", "loads.heat_per_cycle=2 MJ", "loads.heat_per_cycle"),
    ("wobble-cam-engine", "cam.groove_depth=20 mm", "cam.groove_depth"),
    ("wobble-cam-engine", "cam.roller_radius=0 mm", "cam.roller_radius"),
    # eccentric cams
    ("eccentric-reactor", "machine.device_length=1 mm", "machine.device_length"),
    ("eccentric-reactor", "machine.device_length=79.9 mm", "machine.device_length"),
    ("eccentric-reactor", "machine.bore=1 km", "machine.bore"),
    ("eccentric-reactor", "machine.initial_pressure=0 bar", "machine.initial_pressure"),
    ("eccentric-reactor", "machine.polytropic_exponent=0.5", "machine.polytropic_exponent"),
    ("eccentric-reactor", "machine.bulk_modulus=1 Pa", "machine.bulk_modulus"),
    ("eccentric-reactor", "machine.piston_mass=-1 kg", "machine.piston_mass"),
    ("eccentric-reactor", "drive.disc_radius=0 mm", "drive.disc_radius"),
    ("eccentric-reactor", "drive.eccentricity=80 mm", "drive.eccentricity"),
    ("eccentric-reactor", "cam.thickness=161 mm", "cam.thickness"),
    # guide bar
    ("guide-bar-pump", "drive.lambda=1e-300", "drive.lambda"),
    ("guide-bar-pump", "drive.lambda=0.999999999", "drive.lambda"),
    ("guide-bar-pump", "drive.gear_ratio=1e300", "drive.gear_ratio"),
    ("guide-bar-pump", "drive.input_gear_ratio=0.05", "drive.input_gear_ratio"),
    ("guide-bar-pump", "drive.phase=720 deg", "drive.phase"),
    ("guide-bar-pump", "machine.vanes_per_impeller=25", "machine.vanes_per_impeller"),
    ("guide-bar-pump", "machine.hub_radius=80 mm", "machine.hub_radius"),
    ("guide-bar-pump", "loads.impeller_torque_1=-1 N*m", "loads.impeller_torque_1"),
    ("guide-bar-pump", "loads.discharge_pressure=1e9 Pa", "loads.discharge_pressure"),
    # rhomboid cam
    ("rhomboid-engine", "cam.roller_radius=100 mm", "cam.roller_radius"),
    ("rhomboid-engine", "cam.thickness=1 m", "cam.thickness"),
    ("rhomboid-engine", "cam.thickness=0 mm", "cam.thickness"),
    ("rhomboid-engine", "drive.psi_min=90 deg", "drive.psi_min"),
    ("rhomboid-engine", "drive.link_length=0.5 mm", "drive.link_length"),
    ("rhomboid-engine", "machine.blades_per_pair=13", "machine.blades_per_pair"),
    ("rhomboid-engine", "machine.outer_radius=20 m", "machine.outer_radius"),
    ("rhomboid-engine", "loads.hot_temperature=0 K", "loads.hot_temperature"),
    ("rhomboid-engine", "loads.torque_high=2e6 N*m", "loads.torque_high"),
    # every drive: the shaft speed (rotorkin.analysis.timing)
    ("guide-bar-pump", "run.speed=1e300 rpm", "run.speed"),
    ("guide-bar-pump", "run.speed=1e-300 rpm", "run.speed"),
    ("wobble-cam-engine", "run.speed=100001 rpm", "run.speed"),
    ("eccentric-reactor", "run.speed=0.009 rpm", "run.speed"),
    ("rhomboid-engine", 'run.speed=["1000 rpm", "1e6 rpm", "1000 rpm"]', "run.speed"),
]  # fmt: skip

# (example, --set): the boundary value, or just inside it
INSIDE = [
    ("wobble-cam-engine", "drive.spin_ratio=0.5"),
    ("wobble-cam-engine", "drive.plate_tilt=0.5 deg"),
    ("wobble-cam-engine", "drive.spin_ratio=-20"),
    ("wobble-cam-engine", ("machine.compression_ratio=1e6", "loads.model=ideal")),
    ("wobble-cam-engine", "loads.polytropic_exponent=1.6666"),
    ("wobble-cam-engine", "loads.ambient_pressure=100 bar"),
    ("wobble-cam-engine", "machine.speed_fluctuation=0.999"),
    ("wobble-cam-engine", "cam.roller_radius=5 mm"),
    ("eccentric-reactor", "machine.device_length=80 mm"),
    ("eccentric-reactor", "machine.polytropic_exponent=1.6666"),
    ("eccentric-reactor", "cam.thickness=160 mm"),
    ("guide-bar-pump", "drive.lambda=0.99"),
    ("guide-bar-pump", "drive.lambda=0.01"),
    ("guide-bar-pump", ("drive.lambda=0.99", "drive.driver=guide")),
    ("guide-bar-pump", ("drive.lambda=0.99", "drive.gear_ratio=10", "drive.input_gear_ratio=0.1")),
    ("wobble-cam-engine", ("machine.pistons_per_rotor=2", "drive.roller_axis_angle=1 deg")),
    ("eccentric-reactor", ("machine.device_length=80 mm", "machine.fluid=liquid")),
    ("guide-bar-pump", "drive.gear_ratio=10"),
    ("rhomboid-engine", "loads.torque_high=1e6 N*m"),
    ("guide-bar-pump", "run.speed=100000 rpm"),
    ("wobble-cam-engine", "run.speed=0.01 rpm"),
    ("eccentric-reactor", "run.speed=0.01 rpm"),
    ("rhomboid-engine", "run.speed=100000 rpm"),
]  # fmt: skip


def test_the_batch_admissibility_has_the_same_bounds():
    from rotorkin.drives.wobble_cam import kinematics as wc

    tilt = np.radians([0.49, 0.5, 45.0, 45.0, 45.0, 45.0])
    spin = np.array([-2.0, -2.0, 1e-10, 20.0, -20.5, 0.5])
    code = wc.violation(tilt, np.pi / 2, spin, 0.06).tolist()
    k_tilt, k_spin = (1 + wc.CHECKED.index(k) for k in ("plate_tilt", "spin_ratio"))
    assert code == [k_tilt, 0, k_spin, 0, k_spin, 0]


def _run(capsys, tmp_path, example, sets):
    out = tmp_path / "run"
    args = ["run", "-e", example, "-q", "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    code = main(args)
    return code, capsys.readouterr().err, out


@pytest.mark.parametrize(("example", "setting", "key"), REFUSED)
def test_out_of_range_is_refused_in_one_line(capsys, tmp_path, example, setting, key):
    code, err, out = _run(capsys, tmp_path, example, [setting])
    assert code == 2, err
    assert err.count("\n") == 1 and err.startswith(f"rotorkin: error: {key} = "), err
    assert "is not admissible" in err
    assert not out.exists()


@pytest.mark.slow
@pytest.mark.parametrize(("example", "setting"), INSIDE)
def test_just_inside_runs_with_finite_summary(capsys, tmp_path, example, setting):
    sets = [setting] if isinstance(setting, str) else list(setting)
    code, err, out = _run(capsys, tmp_path, example, sets)
    assert code == 0, err
    summary = json.loads((out / "summary.json").read_text())
    warned = [line for line in err.splitlines() if line.startswith("rotorkin: warning")]
    for key in summary.get("undefined", []):
        assert any(key in line for line in warned), (key, err)
    for key, value in summary.items():
        if isinstance(value, float):
            assert math.isfinite(value), key


# --- every key of every drive, sampled in its documented range -----------------------------
_SKIPPED_SECTIONS = ("run", "export")  # shared sections (rotorkin.core.schema)


def _bounds(field):
    lo = hi = None
    lo_open = hi_open = False
    for m in field.metadata:
        if isinstance(m, at.Ge):
            lo = float(m.ge)
        elif isinstance(m, at.Gt):
            lo, lo_open = float(m.gt), True
        elif isinstance(m, at.Le):
            hi = float(m.le)
        elif isinstance(m, at.Lt):
            hi, hi_open = float(m.lt), True
    return lo, lo_open, hi, hi_open


def numeric_keys(model: type[BaseModel]):
    """``[(section, key, field)]`` of every numeric key of a drive's config model."""
    out = []
    for section, sfield in model.model_fields.items():
        sub = sfield.annotation
        if section in _SKIPPED_SECTIONS or not (
            isinstance(sub, type) and issubclass(sub, BaseModel)
        ):
            continue  # fmt: skip
        for name, field in sub.model_fields.items():
            key = field.alias or name
            if field.annotation in (float, int) or "float" in str(field.annotation):
                out.append((section, key, field))
    return out


def test_every_numeric_key_has_a_documented_range():
    for spec in (drives.get(t) for t in EXAMPLES):
        for section, key, field in numeric_keys(spec.config_model):
            lo, _, hi, _ = _bounds(field)
            if "list" in str(field.annotation):
                assert any(getattr(m, "max_length", None) for m in field.metadata), key
                continue
            if key != "thickness":  # 0 < thickness <= the part's diameter: the cam check
                assert lo is not None, f"{spec.name}: {section}.{key} has no lower bound"
                assert hi is not None, f"{spec.name}: {section}.{key} has no upper bound"
            assert "<" in (field.description or ""), f"{spec.name}: {section}.{key}"


def _value(field):
    """Strategy of an admissible value of ``field`` (SI)."""
    annotation = str(field.annotation)
    if "list" in annotation:
        (inner,) = field.annotation.__args__
        meta = [m for f in inner.__metadata__ for m in getattr(f, "metadata", [f])]
        lo, _, hi, _ = _bounds(type("F", (), {"metadata": meta})())
        return st.lists(st.floats(lo, hi), max_size=3)
    lo, lo_open, hi, hi_open = _bounds(field)
    if lo is None and hi is None:  # cam.thickness: 0 < thickness <= the part's diameter
        lo, lo_open, hi = 0.0, True, 0.2
    if field.annotation is int:
        return st.integers(int(math.ceil(lo + lo_open)), int(hi - hi_open))
    return st.floats(lo, hi, exclude_min=lo_open, exclude_max=hi_open)


def _cases():
    cases = []
    for drive_type, example in EXAMPLES.items():
        spec = drives.get(drive_type)
        for section, key, field in numeric_keys(spec.config_model):
            cases.append((drive_type, example, section, key, field))
    return cases


_CASES = _cases()
_BASE = {}


def _base(example):
    if example not in _BASE:
        cfg = load_config(None, example, ["run.points=73"])[0]
        _BASE[example] = cfg
    return copy.deepcopy(_BASE[example])


@settings(max_examples=160, deadline=None, suppress_health_check=list(HealthCheck))
@given(st.data())
def test_sampled_in_range_is_refused_in_one_line_or_finite(data):
    drive_type, example, section, key, field = data.draw(st.sampled_from(_CASES), label="key")
    value = data.draw(_value(field), label=f"{section}.{key}")
    cfg = _base(example)
    cfg.setdefault(section, {})[key] = value
    spec = drives.get(drive_type)
    try:
        result = spec.study(cfg)
    except RotorkinError as exc:  # a range that depends on other keys
        assert "\n" not in str(exc) and "is not admissible" in str(exc), str(exc)
        return
    for name, v in result.summary.items():
        if isinstance(v, (float, np.floating)) and not np.isfinite(v):
            assert any(name in w for w in result.warnings), (section, key, value, name, v)
