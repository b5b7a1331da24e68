"""Opposed-piston reactor on the double eccentric-cam drive: enclosed volume, pressure, forces.

Source of the drive: Zhu Ruilin, Zhu Guolin, "Analysis of the motions of the
double eccentric cams used in a process intensification equipment", Engineering
Sciences (China) 14(10), 2012 (:mod:`rotorkin.drives.eccentric_cam.kinematics`). The paper
stops at the gap change ``Delta``; it states that ``Delta <= 0``, "the inner
faces move apart, the pressure can only drop", and gives no bore and no fluid.
The volume, pressure, force and torque models below are derived here.

One chamber: the tube of bore ``b`` between the inner faces of the two pistons.
The drive's travels ``z`` (left) and ``z'`` (right) are positive towards the
reactor centre, so the distance between the faces is ``L - (z + z') = L -
Delta`` with ``L`` (``device_length``) the distance in the balanced position
(``beta = 0``, where ``Delta = 0``), and

    V(beta) = A (L - Delta(beta)),   A = pi b^2 / 4,   V0 = A L = V(0)

``Delta <= 0`` gives ``V >= V0``: the enclosed volume only grows from its value at
``beta = 0`` (largest at 90 deg and 270 deg), so the pressure only drops - the
paper's statement. ``dV/dz = dV/dz' = -A``; the flat follower keeps ``V = V0``.

Pressure models (closed system, the fluid is neither added nor removed):

* ``gas``: polytropic, ``p = p0 (V0/V)^n``.
* ``liquid``: constant bulk modulus ``K = -V dp/dV`` integrated exactly,
  ``p = p0 - K ln(V/V0)`` (chosen over the linearized ``p0 - K (V - V0)/V0``,
  which differs by ``K (dV/V0)^2/2``: 1 % of the drop at a 2 % volume change).

Either way ``p`` is a function of ``V`` only, so the fluid is a conservative
spring: over a turn ``oint p dV = 0`` and the mean shaft torque is zero. A
liquid under a pressure drop larger than ``p0`` would be in tension: the model
then gives a negative absolute pressure, which in practice means cavitation
(flagged by the study, not modelled).

Forces: the absolute chamber pressure acts on each inner face (the outer faces
are taken at zero pressure; an ambient pressure ``p_a`` there would add
``+p_a A`` to each piston force and ``-p_a dV/dbeta`` to the shaft torque, zero
over a turn).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.core.angles import fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.drives.eccentric_cam import kinematics as ec

__all__ = [
    "FLUIDS",
    "OpposedPiston",
    "piston_area",
    "enclosed_volume",
    "volume_derivatives_dq",
    "pressure_from_volume",
    "pressure",
    "volume_extremes",
]

#: Admissible working fluids.
FLUIDS = ("gas", "liquid")


@dataclass(frozen=True)
class OpposedPiston:
    """Geometry and fluid of the opposed-piston reactor (SI).

    Parameters
    ----------
    drive : rotorkin.drives.eccentric_cam.kinematics.EccentricCam
        The drive (already validated).
    device_length : float, optional
        ``L``, distance between the inner faces at ``beta = 0`` [m], ``L > 0``
        (default 1000 mm, the paper's).
    bore : float, optional
        Piston and tube bore ``b`` [m], ``b > 0`` (default 50 mm).
    fluid : {"gas", "liquid"}, optional
        Pressure model (default ``"liquid"``).
    initial_pressure : float, optional
        ``p0``, absolute pressure at ``V0`` [Pa], ``> 0`` (default 1 bar).
    polytropic_exponent : float, optional
        ``n > 0`` of the gas (default 1, isothermal).
    bulk_modulus : float, optional
        ``K > 0`` of the liquid [Pa] (default 1.5 GPa; water is about 2.2 GPa,
        vegetable oils and methanol about 1-1.8 GPa).
    """

    drive: ec.EccentricCam
    device_length: float = 1.0
    bore: float = 0.05
    fluid: str = "liquid"
    initial_pressure: float = 1.0e5
    polytropic_exponent: float = 1.0
    bulk_modulus: float = 1.5e9

    def __post_init__(self):
        L = float(self.device_length)
        if not (np.isfinite(L) and L > 0.0):
            raise ParameterError("device_length", fmt_mm(L), "device_length > 0 mm")
        b = float(self.bore)
        if not (np.isfinite(b) and b > 0.0):
            raise ParameterError("bore", fmt_mm(b), "bore > 0 mm")
        if self.fluid not in FLUIDS:
            raise ParameterError(
                "fluid", repr(self.fluid), "one of " + ", ".join(map(repr, FLUIDS))
            )
        p0 = float(self.initial_pressure)
        if not (np.isfinite(p0) and p0 > 0.0):
            raise ParameterError(
                "initial_pressure", f"{p0 / 1e5:.4g} bar", "initial_pressure > 0 bar (absolute)"
            )
        n = float(self.polytropic_exponent)
        if not (np.isfinite(n) and n > 0.0):
            raise ParameterError(
                "polytropic_exponent",
                f"{n:g}",
                "polytropic_exponent > 0 (1 isothermal, 1.4 adiabatic air)",
            )
        K = float(self.bulk_modulus)
        if not (np.isfinite(K) and K > 0.0):
            raise ParameterError("bulk_modulus", f"{K / 1e9:.4g} GPa", "bulk_modulus > 0 GPa")

    @property
    def area(self) -> float:
        """Piston area ``A = pi b^2/4`` [m^2]."""
        return float(piston_area(self.bore))

    @property
    def volume_initial(self) -> float:
        """``V0 = A L``, the enclosed volume at ``beta = 0`` and its smallest [m^3]."""
        return self.area * float(self.device_length)


def piston_area(bore):
    """``A = pi b^2 / 4`` [m^2] of a bore ``b`` [m]."""
    return 0.25 * np.pi * np.asarray(bore, dtype=float) ** 2


def enclosed_volume(reactor: OpposedPiston, beta):
    """Enclosed volume ``V = A (L - Delta)`` and its derivatives with respect to beta.

    Parameters
    ----------
    reactor : OpposedPiston
    beta : array_like
        Shaft angle [rad].

    Returns
    -------
    tuple of 4 ndarray, shape (1, ...)
        ``V`` [m^3] and ``dV/dbeta``, ``d2V/dbeta2``, ``d3V/dbeta3`` [m^3/rad^n],
        one chamber on the leading axis (``dV = -A dDelta``, exact).
    """
    A, L = reactor.area, float(reactor.device_length)
    d = ec.gap_change(reactor.drive, beta)
    return (A * (L - d[0]))[None], *((-A * v)[None] for v in d[1:])


def volume_derivatives_dq(reactor: OpposedPiston, beta):
    """``dV/dq_i`` for the pistons ``q = (z, z')``: ``-A`` each [m^2], shape (2, 1, ...)."""
    beta = np.asarray(beta, dtype=float)
    return np.full((2, 1, *beta.shape), -reactor.area)


def pressure_from_volume(reactor: OpposedPiston, volume):
    """Pressure of the enclosed fluid at the volume ``V`` [Pa] (module docstring).

    ``gas``: ``p0 (V0/V)^n``; ``liquid``: ``p0 - K ln(V/V0)``. Broadcasts.
    """
    v = np.asarray(volume, dtype=float)
    p0, v0 = float(reactor.initial_pressure), reactor.volume_initial
    if reactor.fluid == "gas":
        return p0 * (v0 / v) ** float(reactor.polytropic_exponent)
    return p0 - float(reactor.bulk_modulus) * np.log(v / v0)


def pressure(reactor: OpposedPiston, beta):
    """Chamber pressure and ``dp/dbeta`` over the shaft angle, shape (1, ...).

    ``dp/dbeta = (dp/dV) dV/dbeta`` with ``dp/dV = -n p/V`` (gas) or ``-K/V``
    (liquid).

    Returns
    -------
    (p, dp) : tuple of ndarray, shape (1, ...)
        [Pa], [Pa/rad].
    """
    v, dv, _, _ = enclosed_volume(reactor, beta)
    p = pressure_from_volume(reactor, v)
    if reactor.fluid == "gas":
        slope = -float(reactor.polytropic_exponent) * p / v
    else:
        slope = -float(reactor.bulk_modulus) / v
    return p, slope * dv


def volume_extremes(reactor: OpposedPiston) -> tuple[float, float]:
    """Smallest and largest enclosed volume over a turn [m^3] (closed form).

    ``V_min = A L`` at ``beta = 0`` (``Delta = 0``); ``V_max = A (L - Delta_min)`` at
    90 deg, ``Delta_min`` from :func:`rotorkin.drives.eccentric_cam.kinematics.gap_change_extreme`.
    """
    A, L = reactor.area, float(reactor.device_length)
    dmin = ec.gap_change_extreme(reactor.drive)[0]
    return A * L, A * (L - dmin)
