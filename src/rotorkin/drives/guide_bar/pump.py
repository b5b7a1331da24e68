"""The differential vane pump on this drive: what the pump needs from the drive (JHIT 2012).

The pump (:mod:`rotorkin.machines.vane_pump`) is built from the impellers'
motion and plain numbers. This module gives it those numbers:

* the smallest and largest relative angle ``r = q_2 - q_1`` over a period,
  taken at the two equal-speed points of the drive
  (:func:`~rotorkin.drives.guide_bar.kinematics.equal_speed_angles`), where ``r`` is
  stationary (closed form, no sampling);
* the default vane angle, the drive's theoretical vane angle gamma_0 (section 3,
  eq. 5, 6; :func:`~rotorkin.drives.guide_bar.kinematics.vane_angle`).
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.angles import fmt_deg
from rotorkin.core.errors import ParameterError
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar.schema import VanePumpMachine
from rotorkin.machines import vane_pump as vp

__all__ = ["relative_angle_extremes", "vane_pump", "displacement"]

#: The machine section's defaults (SI), the one source of the pump's defaults.
_MACHINE = VanePumpMachine().model_dump()


def relative_angle_extremes(params: gb.GuideBar) -> tuple[float, float]:
    """Smallest and largest relative angle ``r = q_2 - q_1`` over a period [rad].

    ``r`` is stationary exactly at the two equal-speed points of the drive
    (driving angles ``-Sigma/2`` and ``pi - Sigma/2`` of mechanism 1), so its
    extremes are its values there (closed form, no sampling).

    Parameters
    ----------
    params : GuideBar

    Returns
    -------
    (r_min, r_max) : tuple of float
        [rad]; ``r_max - r_min = 2 pi/u - 2 gamma_0``.
    """
    t = np.array(gb.equal_speed_angles(params.phase), dtype=float)
    q = gb.impeller_angles(params, t * float(params.input_gear_ratio))[0]
    r = q[1] - q[0]
    return float(np.min(r)), float(np.max(r))


def vane_pump(
    params: gb.GuideBar,
    vanes_per_impeller: int = _MACHINE["vanes_per_impeller"],
    vane_angle: float | None = _MACHINE["vane_angle"],
    hub_radius: float = _MACHINE["hub_radius"],
    casing_radius: float = _MACHINE["casing_radius"],
    axial_width: float = _MACHINE["axial_width"],
) -> vp.VanePump:
    """The pump on this drive; ``vane_angle = None`` takes the drive's gamma_0 [rad].

    Parameters
    ----------
    params : GuideBar
        The drive (already validated).
    vanes_per_impeller, vane_angle, hub_radius, casing_radius, axial_width
        As :class:`rotorkin.machines.vane_pump.VanePump` ([-], [rad], [m], [m], [m]).

    Raises
    ------
    ParameterError
        Named by field, as the pump's; with the default vane angle, a
        ``vanes_per_impeller`` too large for gamma_0 names ``vanes_per_impeller``.
    """
    r_min, r_max = relative_angle_extremes(params)
    geometry = {
        "vanes_per_impeller": vanes_per_impeller,
        "hub_radius": hub_radius,
        "casing_radius": casing_radius,
        "axial_width": axial_width,
    }
    if vane_angle is not None:
        return vp.VanePump(r_min, r_max, vane_angle, **geometry)
    g0 = float(gb.vane_angle(params.lam, params.gear_ratio, params.phase, params.driver))
    try:
        return vp.VanePump(r_min, r_max, g0, **geometry)
    except ParameterError as exc:
        if exc.name != "vane_angle":
            raise
    swing = r_max - r_min
    gmax = float(vp.vane_angle_max(vanes_per_impeller, swing))
    z_max = int(np.floor(2.0 * np.pi / (2.0 * g0 + swing) * (1.0 + 1e-12)))
    raise ParameterError(
        "vanes_per_impeller",
        str(vanes_per_impeller),
        f"1 <= vanes_per_impeller <= {z_max} with the default vane_angle = gamma_0 "
        f"= {fmt_deg(g0)} (Z (2 vane_angle + swing {fmt_deg(swing)}) <= 360 deg); "
        f"or give vane_angle <= {fmt_deg(gmax)}",
    )


def displacement(params: gb.GuideBar, pump: vp.VanePump) -> dict:
    """Volume discharged, per period, per input-gear turn and per impeller revolution [m^3].

    Per period ``2 pi i12``: :func:`rotorkin.machines.vane_pump.displacement`. Per
    input turn: that over ``i12``. An impeller advances ``2 pi/u`` per period, so
    per impeller revolution: ``u`` times it.

    Returns
    -------
    dict
        ``"per_period"``, ``"per_input_turn"``, ``"per_impeller_rev"`` [m^3].
    """
    per_period = vp.displacement(pump)
    return {
        "per_period": per_period,
        "per_input_turn": per_period / float(params.input_gear_ratio),
        "per_impeller_rev": per_period * float(params.gear_ratio),
    }
