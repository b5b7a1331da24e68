"""A design's config out of a batch of designs: a deep copy of the base, its values set."""

from __future__ import annotations

import copy

import numpy as np

from rotorkin.core.batch import Designs, _copied
from rotorkin.io.config import load_config


def _containers(value, found):
    """Every dict and list inside ``value`` (by identity)."""
    if isinstance(value, dict | list):
        found.append(value)
        for v in value.values() if isinstance(value, dict) else value:
            _containers(v, found)
    return found


def test_copy_equals_deepcopy_and_shares_no_container():
    cfg, _, _ = load_config(example="wobble-cam-engine", sets=[])
    cfg["extra"] = {"table": [[1.0, 2.0], [3.0, {"k": (4, [5])}]], "array": np.arange(3.0)}
    got, want = _copied(cfg), copy.deepcopy(cfg)
    assert got.keys() == want.keys()
    assert np.array_equal(got.pop("extra")["array"], want.pop("extra")["array"])
    cfg_extra = cfg.pop("extra")
    assert got == want == cfg
    mine = {id(c) for c in _containers(cfg, [])}
    assert mine.isdisjoint(id(c) for c in _containers(got, []))
    # the array is copied too: writing the copy leaves the base alone
    copied = _copied({"a": cfg_extra["array"]})["a"]
    copied[0] = 99.0
    assert cfg_extra["array"][0] == 0.0


def test_a_design_config_has_its_values_and_leaves_the_base_alone():
    cfg, _, _ = load_config(example="wobble-cam-engine", sets=[])
    base = copy.deepcopy(cfg)
    table = {
        "drive.plate_tilt": np.radians([30.0, 40.0]),
        "machine.compression_ratio": np.array([9.0, 12.0]),
    }
    designs = Designs(cfg, table, 2)
    one = designs.config(1)
    assert one["drive"]["plate_tilt"] == np.radians(40.0)
    assert one["machine"]["compression_ratio"] == 12.0
    assert type(one["machine"]["compression_ratio"]) is float
    one["drive"]["spin_ratio"] = 5.0
    assert cfg == base
