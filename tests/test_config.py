"""Config reading: units at the boundary, --set overrides, one-line errors."""

import math

import pytest

from rotorkin.core.errors import ConfigError
from rotorkin.core.units import to_si
from rotorkin.drives import REGISTRY
from rotorkin.io.config import (
    apply_sets,
    example_names,
    glossary,
    load_config,
    parse_set,
    validate_config,
)
from rotorkin.io.output import to_toml

EXAMPLES = [
    "eccentric-reactor",
    "elliptic-gear-engine",
    "guide-bar-pump",
    "rhomboid-engine",
    "tabulated-engine",
    "wobble-cam-engine",
]


def test_examples_are_shipped_one_per_drive_type():
    assert example_names() == EXAMPLES
    kinds = {load_config(example=name)[0]["drive"]["type"] for name in EXAMPLES}
    assert kinds == set(REGISTRY)


@pytest.mark.parametrize(
    ("text", "kind", "expected"),
    [
        ("45 deg", "angle", math.pi / 4),
        ("0.8 rad", "angle", 0.8),
        ("80 mm", "length", 0.08),
        ("0.5 m", "length", 0.5),
        ("3000 rpm", "speed", 100 * math.pi),
        ("12 N*m", "torque", 12.0),
        ("1.2 kN*m", "torque", 1200.0),
    ],
)
def test_units_are_converted_to_si(text, kind, expected):
    assert to_si("k", text, kind) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize(
    ("value", "words"),
    [
        (45, "has no unit"),
        ("45", "has no unit"),
        ("45 mm", "wrong unit"),
        ("fourty-five degrees", "has no number"),
        ("inf deg", "has no number"),
        ("1e400 deg", "finite"),
        (True, "not admissible"),
    ],
)
def test_bad_dimensional_values_name_the_key(value, words):
    with pytest.raises(ConfigError) as info:
        to_si("drive.plate_tilt", value, "angle")
    message = str(info.value)
    assert message.startswith("drive.plate_tilt = ")
    assert words in message
    assert "\n" not in message


def test_default_config_is_the_wobble_cam_engine():
    cfg, raw, name = load_config()
    assert name == "wobble-cam-engine"
    assert cfg["drive"]["type"] == "wobble_cam"
    assert cfg["drive"]["plate_tilt"] == pytest.approx(math.radians(45))
    assert cfg["machine"]["compression_ratio"] == 10
    assert raw["drive"]["plate_tilt"] == "45 deg"


@pytest.mark.parametrize(
    ("item", "parts", "value"),
    [
        ('drive.plate_tilt="30 deg"', ["drive", "plate_tilt"], "30 deg"),
        ("drive.plate_tilt=30 deg", ["drive", "plate_tilt"], "30 deg"),
        ("drive.a=[0.05]", ["drive", "a"], [0.05]),
        ("machine.compression_ratio=8", ["machine", "compression_ratio"], 8),
        ("drive.follower=flat", ["drive", "follower"], "flat"),
    ],
)
def test_set_values_are_toml_when_they_parse(item, parts, value):
    assert parse_set(item) == (parts, value)


def test_set_overrides_and_validates():
    cfg, raw, _ = load_config(sets=['drive.plate_tilt="30 deg"', "machine.compression_ratio=8"])
    assert cfg["drive"]["plate_tilt"] == pytest.approx(math.radians(30))
    assert cfg["machine"]["compression_ratio"] == 8
    assert raw["drive"]["plate_tilt"] == "30 deg"


@pytest.mark.parametrize("item", ["plate_tilt=3", "drive.=3", "novalue"])
def test_malformed_set_is_refused(item):
    with pytest.raises(ConfigError, match="--set"):
        apply_sets({}, [item])


@pytest.mark.parametrize(
    ("sets", "starts"),
    [
        (["drive.plate_tilt=45"], "drive.plate_tilt = 45 has no unit"),
        (["drive.colour=1"], "unknown key drive.colour"),
        (["nonsense.key=1"], "unknown key nonsense"),
        (
            ['machine.compression_ratio="ten"'],
            "machine.compression_ratio = 'ten' is not admissible",
        ),
        (["machine.compression_ratio=nan"], "machine.compression_ratio = nan is not admissible"),
        (["run.points=true"], "run.points = True is not admissible"),
        (["run.points=2"], "run.points = 2 is not admissible"),
        (['drive.type="cam"'], "drive.type = 'cam' is not admissible"),
    ],
)
def test_bad_keys_and_types_give_one_line(sets, starts):
    with pytest.raises(ConfigError) as info:
        load_config(sets=sets)
    message = str(info.value)
    assert message.startswith(starts), message
    assert "\n" not in message


def test_missing_required_key_says_which_unit():
    with pytest.raises(ConfigError) as info:
        validate_config({"drive": {"type": "wobble_cam"}})
    message = str(info.value)
    assert message.startswith("missing required key drive.plate_tilt")
    assert '"45 deg"' in message


def test_missing_drive_section():
    with pytest.raises(ConfigError, match=r"missing section \[drive\]"):
        validate_config({"machine": {}})


def test_guide_bar_lambda_key_and_literals():
    cfg, _, _ = load_config(example="guide-bar-pump", sets=['drive.driver="guide"'])
    assert cfg["drive"]["lambda"] == 0.5
    assert cfg["drive"]["driver"] == "guide"
    with pytest.raises(ConfigError, match="drive.driver = 'gear' is not admissible"):
        load_config(example="guide-bar-pump", sets=['drive.driver="gear"'])


def test_unreadable_files(tmp_path):
    with pytest.raises(ConfigError, match="does not exist"):
        load_config(tmp_path / "nope.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[drive\ntype = 1")
    with pytest.raises(ConfigError, match="not valid TOML"):
        load_config(bad)
    with pytest.raises(ConfigError, match="is a directory"):
        load_config(tmp_path)
    with pytest.raises(ConfigError, match="--example = 'nope' is not admissible"):
        load_config(example="nope")
    with pytest.raises(ConfigError, match="not both"):
        load_config(bad, example="wobble-cam-engine")


def test_written_config_reads_back_to_the_same_values(tmp_path):
    for name in EXAMPLES:
        cfg, raw, _ = load_config(example=name)
        path = tmp_path / f"{name}.toml"
        path.write_text(to_toml(raw))
        assert load_config(path)[0] == cfg


def test_every_key_is_documented():
    rows = glossary()
    assert len(rows) > 20
    for kind, key, _default, doc in rows:
        assert doc and len(doc) > 10, (kind, key)
