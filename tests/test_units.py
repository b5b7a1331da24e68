"""Units at the boundary: a number times a unit expression, read without evaluating anything.

Expected values are written out by hand (1 deg = pi/180 rad, 1 rpm = 2 pi/60 rad/s,
a cycle per second = 2 pi rad/s, 0 degC = 273.15 K), not taken from pint.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rotorkin.core.units import KINDS, MAX_TEXT, parse_quantity

TWO_PI = 2.0 * math.pi


@pytest.mark.parametrize(
    ("text", "kind", "si"),
    [
        ("45 deg", "angle", math.pi / 4),
        ("0.8 rad", "angle", 0.8),
        ("1 turn", "angle", TWO_PI),
        ("3000 rpm", "speed", 3000 * TWO_PI / 60),
        ("50 Hz", "speed", 50 * TWO_PI),
        ("3000 1/min", "speed", 3000 * TWO_PI / 60),
        ("314 rad/s", "speed", 314.0),
        ("360 deg/s", "speed", TWO_PI),
        ("80 mm", "length", 0.08),
        ("1 inch", "length", 0.0254),
        ("12 N*m", "torque", 12.0),
        ("12 N m", "torque", 12.0),
        ("0.02 kg*m^2", "inertia", 0.02),
        ("0.02 kg*m**2", "inertia", 0.02),
        ("2 cm^3", "volume", 2e-6),
        ("1 bar", "pressure", 1e5),
        ("1.5 GPa", "modulus", 1.5e9),
        ("90 J", "energy", 90.0),
        ("0.5 kg", "mass", 0.5),
        ("25 degC", "temperature", 298.15),
        ("600 K", "temperature", 600.0),
        ("-1.5e-3 m", "length", -1.5e-3),
        ("  7 mm  ", "length", 7e-3),
    ],
)  # fmt: skip
def test_reads_a_number_times_a_unit(text, kind, si):
    value, reason = parse_quantity(text, kind)
    assert reason == ""
    assert value == pytest.approx(si, rel=1e-12)


@pytest.mark.parametrize(
    ("text", "kind", "words"),
    [
        ("9**9**9 deg", "angle", "cannot be read"),
        ("10**400 deg", "angle", "cannot be read"),
        ("1 deg / 0", "angle", "cannot be read"),
        ("(1 deg", "angle", "no number"),
        ("1 deg deg", "angle", "twice"),
        ("3000 rpm rpm", "speed", "twice"),
        ("deg", "angle", "no number"),
        ("45", "angle", "no unit"),
        ("45 m", "angle", "wrong unit"),
        ("5 m/m", "angle", "twice"),
        ("1 deg^9", "angle", "power"),
        ("1e999 deg", "angle", "finite"),
        ("1 furlongz", "length", "unknown unit"),
        ("1 mm; rm -rf", "length", "character"),
        ("-300 degC", "temperature", "absolute zero"),
        ("0 K", "temperature", "absolute zero"),
        ("1" * 70 + " mm", "length", f"longer than {MAX_TEXT}"),
        ("$", "length", "no number"),
        ("", "length", "no number"),
    ],
)  # fmt: skip
def test_refuses_what_is_not_a_quantity(text, kind, words):
    value, reason = parse_quantity(text, kind)
    assert math.isnan(value) and words in reason


def test_bare_numbers_and_other_types_are_refused():
    assert "has no unit" in parse_quantity(45, "angle")[1]
    assert "needs an angle" in parse_quantity(True, "angle")[1]
    assert "needs an angle" in parse_quantity([1], "angle")[1]


@settings(max_examples=300, deadline=None)
@given(text=st.text(max_size=80), kind=st.sampled_from(sorted(KINDS)))
def test_any_text_gives_a_finite_value_or_a_reason(text, kind):
    value, reason = parse_quantity(text, kind)
    assert (reason == "" and math.isfinite(value)) or (reason and math.isnan(value))


@settings(max_examples=200, deadline=None)
@given(
    number=st.floats(-1e6, 1e6, allow_nan=False),
    unit=st.sampled_from(["mm", "m", "cm", "inch"]),
    sep=st.sampled_from(["", " ", "  "]),
)
def test_lengths_round_trip(number, unit, sep):
    text = f"{number!r}{sep}{unit}"
    value, reason = parse_quantity(text, "length")
    scale = {"mm": 1e-3, "m": 1.0, "cm": 1e-2, "inch": 0.0254}[unit]
    assert reason == "" and value == pytest.approx(number * scale, rel=1e-12, abs=1e-300)


# -- the table of common units against pint ----------------------------------------------

from rotorkin.core import units as U  # noqa: E402


@pytest.mark.parametrize("name", sorted(U._NAMES))
def test_table_reads_each_name_as_pint_does(name):
    prefix, canonical = U._NAMES[name]
    found = U._registry().parse_unit_name(name)
    assert found and found[0] == (prefix, canonical, "")


_COMPOSITES = ["N*m", "kN*m", "N m", "kg*m^2", "kg m**2", "g*cm^2", "rad/s", "deg/s", "1/min",
               "1/s", "J/kg", "MJ/kg", "kJ/kg", "cm^3", "mm^3", "m^3", "L", "N/mm^2", "kN/m^2",
               "W*s", "kW*h", "J*s/rad", "m/s", "revolution/min", "turn/s", "kg/m^3", "lb*in^2",
               "Pa*s", "N*mm", "mm^2*kg", "bar/K", "degC/s", "degC^2", "kdegC", "s^-1",
               "min^-1", "Hz", "rad*s^-1", "m/mm"]  # fmt: skip


@pytest.mark.parametrize("kind", sorted(U.KINDS))
@pytest.mark.parametrize("text", sorted(U._NAMES) + _COMPOSITES)
def test_table_converts_as_pint_does(text, kind):
    """Every unit the table reads, alone and in products, converts to the same SI value
    (or is refused for the same kind) as pint's registry."""
    factors = U._unit_factors(text)
    if isinstance(factors, str):
        pytest.fail(f"{text!r}: {factors}")
    table = U._table_conversion(factors, kind)
    pint_way = U._pint_conversion(factors, kind)
    if table is None:  # outside the table: pint alone decides
        assert text in ("degC/s", "degC^2", "kdegC") or any(
            c[1] not in U._BASE for _, c, _ in factors
        )
        return
    if isinstance(pint_way, str):
        assert table == pint_way
    else:
        assert not isinstance(table, str), (text, kind, pint_way)
        assert table == pytest.approx(pint_way, rel=1e-14, abs=1e-12)


def test_common_units_need_no_pint():
    """Reading the examples' configurations imports no pint (its registry costs ~0.3 s)."""
    import subprocess
    import sys

    code = (
        "import sys\n"
        "from rotorkin.io.config import example_names, load_config, example_path\n"
        "for n in example_names(): load_config(example_path(n))\n"
        "assert 'pint' not in sys.modules, 'pint imported'\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
