"""The shared pair bookkeeping: contact stress, friction, efficiency (rotorkin.analysis.pairs)."""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.analysis import pairs as pp
from rotorkin.core.schema import ContactSection

THETA = np.linspace(0.0, 2 * np.pi, 2001)


def _model(**kw):
    return pp.ContactModel.from_config({"contact": {**ContactSection().model_dump(), **kw}})


def test_defaults_of_the_model_are_the_config_section():
    m = _model()
    assert (m.youngs_modulus, m.poisson_ratio, m.roller_width) == (210e9, 0.3, 0.01)
    assert m.coefficient("sliding") == 0.08 and m.coefficient("bearing") == 0.0015


def test_line_contact_stress_of_a_roller_against_the_closed_form():
    force = 1000.0 * (1.5 + np.sin(THETA))
    pair = pp.Pair("roller", "roller", "rolling", force, np.ones_like(THETA),
                   ("line", 0.005, 0.05))  # fmt: skip
    s = pp.stress(pair, _model(roller_width=0.012))
    e_star = 210e9 / (2 * (1 - 0.3**2))
    r = 1 / (1 / 0.005 + 1 / 0.05)
    assert s == pytest.approx(np.sqrt(force * e_star / (np.pi * 0.012 * r)), rel=1e-12)
    wide = pp.Pair("gear", "gear", "mesh", force, np.ones_like(THETA), ("line", 0.005, 0.05, 0.048))
    assert pp.stress(wide, _model()) == pytest.approx(s * 0.5, rel=1e-12)  # 4 x the width


def test_friction_loss_efficiency_of_an_engine_and_a_pump():
    # a sliding pair with N = 100 N, slip 0.02 m/rad: 2 N*m of friction torque all round
    pair = pp.Pair("slider", "slider", "sliding", np.full_like(THETA, 100.0),
                   np.full_like(THETA, -0.02))  # fmt: skip
    model = _model(friction_sliding=0.5)
    omega = np.full_like(THETA, 100.0)
    loss = 0.5 * 100.0 * 0.02 * 2 * np.pi  # J per turn
    engine = pp.summary([pair], THETA, 100.0, model, omega)
    assert engine["friction_loss_J_per_rev"] == pytest.approx(loss, rel=1e-12)
    assert engine["friction_loss_W"] == pytest.approx(0.5 * 100.0 * 0.02 * 100.0, rel=1e-12)
    assert engine["mechanical_efficiency"] == pytest.approx((100.0 - loss) / 100.0, rel=1e-12)
    pump = pp.summary([pair], THETA, -100.0, model, omega)
    assert pump["mechanical_efficiency"] == pytest.approx(100.0 / (100.0 + loss), rel=1e-12)
    cols, docs = pp.columns([pair], model, np.full_like(THETA, 7.0))
    assert cols["shaft_torque_with_friction_Nm"] == pytest.approx(np.full_like(THETA, 6.0))
    assert set(cols) == set(docs)


def test_peaks_name_their_pair_and_bearings_apart():
    a = pp.Pair("roller a", "a", "rolling", 10 + 0 * THETA, THETA * 0, ("line", 0.01, np.inf))
    b = pp.Pair("roller b", "b", "rolling", 20 + np.cos(THETA), THETA * 0, ("line", 0.01, np.inf))
    c = pp.Pair("pin", "c", "bearing", 500 + 0 * THETA, THETA * 0)
    s = pp.summary([a, b, c], THETA, 1.0, _model(), np.ones_like(THETA))
    assert (
        s["peak_contact_force_N"] == pytest.approx(21.0)
        and s["peak_contact_force_pair"] == "roller b"
    )
    assert s["peak_contact_stress_pair"] == "roller b" and s["peak_contact_stress_at_deg"] == 0.0
    assert s["peak_bearing_load_N"] == 500.0
    assert s["contact_safety_factor"] == pytest.approx(1.5e9 / (s["peak_contact_stress_MPa"] * 1e6))


@pytest.mark.parametrize("rounding", [-1e-13, 0.0, 1e-13, 5e-10])
def test_mirrored_pairs_peaking_together_name_the_first(rounding):
    """Two pairs whose peaks differ by rounding (a symmetric drive) name the first pair and
    its own peak angle, whichever rounding made larger; a second pair larger by more than
    the tie (1e-9; stress goes as the root of force) is named; the same one design and
    batch (a NaN design names its NaN)."""
    first = 100.0 * (1.5 + np.sin(THETA))
    second = 100.0 * (1.5 + np.sin(THETA - np.pi)) * (1.0 + rounding)
    pairs = [
        pp.Pair("roller 1", "r1", "rolling", first, 0 * THETA, ("line", 0.01, np.inf)),
        pp.Pair("roller 2", "r2", "rolling", second, 0 * THETA, ("line", 0.01, np.inf)),
    ]
    s = pp.summary(pairs, THETA, 1.0, _model(), np.ones_like(THETA))
    assert s["peak_contact_force_pair"] == s["peak_contact_stress_pair"] == "roller 1"
    assert s["peak_contact_stress_at_deg"] == pytest.approx(90.0, abs=0.2)
    bigger = [pairs[0], pp.Pair("roller 2", "r2", "rolling", second * (1 + 1e-8), 0 * THETA,
                                ("line", 0.01, np.inf))]  # fmt: skip
    s = pp.summary(bigger, THETA, 1.0, _model(), np.ones_like(THETA))
    assert s["peak_contact_force_pair"] == s["peak_contact_stress_pair"] == "roller 2"
    assert s["peak_contact_stress_at_deg"] == pytest.approx(270.0, abs=0.2)
    # batch: designs (3, n): tied, second larger, second NaN everywhere
    f1 = np.stack([first, first, first])
    f2 = np.stack([second, second * (1 + 1e-8), np.full_like(second, np.nan)])
    batch = [
        pp.Pair("roller 1", "r1", "rolling", f1, 0 * f1, ("line", 0.01, np.inf)),
        pp.Pair("roller 2", "r2", "rolling", f2, 0 * f2, ("line", 0.01, np.inf)),
    ]
    model = pp.ContactModel(**{**vars(_model()), "allowable_stress": np.full((3, 1), 1.5e9)})
    b = pp.summary(batch, THETA, np.ones((3, 1)), model, np.ones((3, THETA.size)), batch=True)
    assert list(b["peak_contact_force_pair"]) == ["roller 1", "roller 2", "roller 2"]


def test_unknown_kind_is_a_programming_error():
    with pytest.raises(ValueError):
        pp.Pair("x", "x", "magic", THETA, THETA)
