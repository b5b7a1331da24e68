"""Flow losses of the differential vane pump: laminar leakage through the vane clearances and
the compression loss at the switch-over (rotorkin.machines.vane_pump, the guide-bar study)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorkin import drives
from rotorkin.cli import main
from rotorkin.core.errors import ParameterError
from rotorkin.io.config import load_config
from rotorkin.machines import pump_flow as pf
from rotorkin.machines import vane_pump as vp

PS, PD = 1.0e5, 6.0e5
MU = 0.03
PUMP = vp.VanePump(0.0, 1.0, 0.5, 2, 0.030, 0.080, 0.040)


def _study(*sets):
    cfg = load_config(None, "guide-bar-pump", ["run.points=73", *sets])[0]
    return drives.get("guide_bar").study(cfg)


def test_zero_clearances_deliver_the_ideal_flow():
    result = _study()
    cols, s = result.columns, result.summary
    assert np.array_equal(cols["flow_delivered_l_per_min"], cols["flow_l_per_min"])
    assert not np.any(cols["leakage_l_per_min"])
    assert s["leakage_l_per_min"] == 0.0
    # the only loss left is the compression of the chambers at the switch to the outlet
    expected = s["flow_mean_l_per_min"] - s["compression_loss_l_per_min"]
    assert s["flow_delivered_mean_l_per_min"] == pytest.approx(expected, rel=1e-12, abs=1e-12)
    eta = expected / s["flow_mean_l_per_min"]
    assert s["volumetric_efficiency"] == pytest.approx(eta, rel=1e-12)


def test_leakage_by_hand():
    h_t, h_s, h_h = 20e-6, 10e-6, 5e-6
    gaps = pf.Gaps(h_t, h_s, h_h, MU)
    leak = pf.leakage_flow(PUMP, gaps, vp.PortPressures(PS, PD))
    dp, n, g = PD - PS, 4, 0.5
    tip = 0.040 * h_t**3 * dp / (12 * MU * g * 0.080)
    hub = 0.040 * h_h**3 * dp / (12 * MU * g * 0.030)
    side = 2 * h_s**3 * dp * math.log(0.080 / 0.030) / (12 * MU * g)
    assert leak["tip"] == pytest.approx(n * tip, rel=1e-12)
    assert leak["hub"] == pytest.approx(n * hub, rel=1e-12)
    assert leak["side"] == pytest.approx(n * side, rel=1e-12)
    assert leak["total"] == pytest.approx(n * (tip + hub + side), rel=1e-12)
    # the side land as thin plane strips of length gamma rho (Poiseuille on each strip)
    rho = np.linspace(0.030, 0.080, 200_001)
    strips = pf.gap_flow(1.0, h_s, g * rho, dp, MU)
    assert 2 * np.trapezoid(strips, rho) == pytest.approx(side, rel=1e-9)


def test_compression_loss_by_hand():
    gaps = pf.Gaps(bulk_modulus=1.5e9)
    k = 0.5 * (0.080**2 - 0.030**2) * 0.040
    phi_max = PUMP.chamber_angle_range[1]
    expected = 4 * k * phi_max * (PD - PS) / 1.5e9
    loss = pf.compression_loss(PUMP, gaps, vp.PortPressures(PS, PD))
    assert loss == pytest.approx(expected, rel=1e-12)


def test_volumetric_loss_grows_as_the_cube_of_the_clearance():
    base = _study().summary
    losses = []
    for h in (0.01, 0.02, 0.04):
        s = _study(f"machine.tip_clearance={h} mm", f"machine.side_clearance={h} mm",
                   f"machine.hub_clearance={h} mm").summary  # fmt: skip
        losses.append(base["volumetric_efficiency"] - s["volumetric_efficiency"])
        assert s["leakage_l_per_min"] == pytest.approx(
            s["leakage_tip_l_per_min"] + s["leakage_side_l_per_min"] + s["leakage_hub_l_per_min"]
        )
    assert losses[1] / losses[0] == pytest.approx(8.0, rel=1e-9)
    assert losses[2] / losses[1] == pytest.approx(8.0, rel=1e-9)


def test_gaps_refuse_bad_values():
    with pytest.raises(ParameterError, match="tip_clearance"):
        pf.Gaps(tip_clearance=-1e-6)
    with pytest.raises(ParameterError, match="fluid_viscosity"):
        pf.Gaps(fluid_viscosity=0.0)
    with pytest.raises(ParameterError, match="bulk_modulus"):
        pf.Gaps(bulk_modulus=float("nan"))


@pytest.mark.parametrize(
    "setting, key",
    [
        ("machine.tip_clearance=-1 mm", "machine.tip_clearance"),
        ("machine.side_clearance=2 mm", "machine.side_clearance"),
        ("machine.hub_clearance=-0.1 mm", "machine.hub_clearance"),
        ("loads.fluid_viscosity=0", "loads.fluid_viscosity"),
        ("loads.bulk_modulus=0 GPa", "loads.bulk_modulus"),
    ],
)
def test_out_of_range_is_refused_in_one_line(capsys, tmp_path, setting, key):
    out = tmp_path / "out"
    assert main(["run", "-e", "guide-bar-pump", "--set", setting, "--out", str(out), "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and key in err
    assert not out.exists()
