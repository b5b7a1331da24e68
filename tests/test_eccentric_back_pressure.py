"""Back pressure behind the pistons of the opposed-piston reactor on the eccentric discs."""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin import drives
from rotorkin.cli import main
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.drives.eccentric_cam.reactor import reactor_state
from rotorkin.drives.eccentric_cam.study import drive_params, machine_params
from rotorkin.io.config import load_config
from rotorkin.machines import opposed_piston as op

PB = 1.0e5


def _state(*sets):
    cfg = load_config(None, "eccentric-reactor", list(sets))[0]
    params = drive_params(cfg)
    reactor = machine_params(params, {**cfg["machine"]})
    beta = np.linspace(0.0, 2.0 * np.pi, 181)
    return params, reactor, reactor_state(params, reactor, (0.0, (0.0, 0.0)), 60.0, beta), beta


def test_torque_with_back_pressure_by_hand():
    params, vac_reactor, vac, beta = _state()
    _, reactor, st, _ = _state("machine.back_pressure=1 bar")
    assert vac_reactor.back_pressure == 0.0 and reactor.back_pressure == PB
    area = reactor.area
    dz = ec.motion(params, beta).dq  # piston velocity coefficients dz/dbeta, dz'/dbeta
    # each piston: F = (p - p_b) dV/dq = -(p - p_b) A; the torque T = sum F_i dq_i/dbeta
    np.testing.assert_allclose(st["F"], vac["F"] + PB * area, rtol=1e-12, atol=1e-9)
    expected = vac["shaft"] + PB * area * (dz[0] + dz[1])
    np.testing.assert_allclose(st["shaft"], expected, rtol=1e-12, atol=1e-9)
    # over a turn the back pressure does no work
    assert np.trapezoid(st["shaft"] - vac["shaft"], beta) == pytest.approx(0.0, abs=1e-9)


def test_default_is_vacuum_and_summary_reports_it():
    cfg = load_config(None, "eccentric-reactor", ["run.points=73"])[0]
    s = drives.get("eccentric_cam").study(cfg).summary
    assert s["back_pressure_bar"] == 0.0
    cfg = load_config(None, "eccentric-reactor", ["run.points=73", "machine.back_pressure=1 bar"])
    assert drives.get("eccentric_cam").study(cfg[0]).summary["back_pressure_bar"] == 1.0


def test_negative_back_pressure_is_refused():
    with pytest.raises(Exception, match="back_pressure"):
        op.OpposedPiston(back_pressure=-1.0)


def test_negative_back_pressure_exits_2(capsys, tmp_path):
    out = tmp_path / "o"
    args = ["run", "-e", "eccentric-reactor", "--set", "machine.back_pressure=-1 bar"]
    assert main([*args, "--out", str(out), "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "machine.back_pressure" in err
