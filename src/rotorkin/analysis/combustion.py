"""Single-zone closed-cycle model of a chamber: charge, Wiebe burn, Woschni heat transfer.

The heat an engine chamber releases comes from the charge it traps (J. B. Heywood,
*Internal Combustion Engine Fundamentals*, 2nd ed. 2018, ch. 4 and 9):

* **Charge** at the closure of the intake (the chamber's largest volume ``V_ivc``):
  fresh air ``m_a = (1 - x_r) p_i V_ivc / (R T_i)`` with the residual-gas fraction
  ``x_r``; fuel ``m_f = phi m_a / AFR_s``; the heat released
  ``Q = eta_c m_f LHV`` (lean and stoichiometric mixtures, ``phi <= 1``; richer ones
  burn only the fuel the air can oxidise: ``min(phi, 1)``).
* **Burn**: the Wiebe function ``x_b = 1 - exp(-a ((theta - theta_0)/dtheta)^(m + 1))``,
  ``a = 5``, ``m = 2`` by default; the start ``theta_0`` is counted from the dead centre.
* **Heat transfer** to the walls (Woschni 1967, the correlation of Heywood eq. 12.19):
  ``h = 3.26 D^-0.2 p^0.8 T^-0.55 w^0.8`` [W/m^2 K, D in m, p in kPa, T in K, w in m/s]
  with the chamber's hydraulic diameter ``D`` for the bore and the mean gas speed
  ``w = C_1 S`` (``C_1 = 2.28``, ``S`` the mean speed of the chamber's moving walls);
  ``dQ_w/dt = h A (T - T_w)``.
* **Gas**: an ideal gas of constant ratio of specific heats ``gamma``.

The pressure follows from the first law over the shaft angle,
``dp/dtheta = (gamma - 1)/V (dQ_b/dtheta - dQ_w/dtheta) - gamma p/V dV/dtheta``,
integrated by the classical Runge-Kutta method on a fixed grid of the angle, for many
chambers (designs) at once (arrays). With no heat transfer and an instant burn at the
dead centre it is the ideal Otto cycle (:mod:`rotorkin.analysis.engine_cycle`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Charge", "Wiebe", "heat_of_charge", "wiebe", "woschni", "closed_cycle"]

#: Gas constant of air [J/(kg K)].
R_AIR = 287.0


@dataclass(frozen=True)
class Charge:
    """The trapped charge and its fuel (gasoline by default).

    Attributes
    ----------
    intake_pressure, intake_temperature : float
        At the closure of the intake [Pa, K].
    residual_fraction : float
        Mass fraction of burnt gas left from the last cycle [-].
    equivalence_ratio : float
        Fuel-air ratio over the stoichiometric one [-].
    stoichiometric_afr : float
        Air-fuel mass ratio of the stoichiometric mixture (gasoline 14.7) [-].
    lower_heating_value : float
        Of the fuel (gasoline 44 MJ/kg) [J/kg].
    combustion_efficiency : float
        Fraction of the fuel's energy released (0.98) [-].
    gamma : float
        Ratio of specific heats of the gas [-].
    """

    intake_pressure: float = 1.0e5
    intake_temperature: float = 300.0
    residual_fraction: float = 0.05
    equivalence_ratio: float = 1.0
    stoichiometric_afr: float = 14.7
    lower_heating_value: float = 44.0e6
    combustion_efficiency: float = 0.98
    gamma: float = 1.35


def trapped_mass(charge: Charge, volume_ivc):
    """Mass of gas in the chamber at the intake's closure [kg] (air, fuel and residuals)."""
    air = (1.0 - charge.residual_fraction) * charge.intake_pressure * np.asarray(volume_ivc)
    air = air / (R_AIR * charge.intake_temperature)
    return (
        air
        / (1.0 - charge.residual_fraction)
        * (
            1.0
            + (1.0 - charge.residual_fraction)
            * charge.equivalence_ratio
            / charge.stoichiometric_afr
        )
    )


def heat_of_charge(charge: Charge, volume_ivc):
    """Heat the trapped charge releases [J]: ``eta_c min(phi, 1) m_a / AFR_s LHV``."""
    air = (1.0 - charge.residual_fraction) * charge.intake_pressure * np.asarray(volume_ivc)
    air = air / (R_AIR * charge.intake_temperature)
    fuel_burnt = min(charge.equivalence_ratio, 1.0) * air / charge.stoichiometric_afr
    return charge.combustion_efficiency * fuel_burnt * charge.lower_heating_value


@dataclass(frozen=True)
class Wiebe:
    """Burn law: start after the dead centre and duration [rad of the chamber's cycle]."""

    start: float = -np.radians(10.0)
    duration: float = np.radians(50.0)
    a: float = 5.0
    m: float = 2.0


def wiebe(burn: Wiebe, x):
    """Burnt fraction and its derivative at ``x`` [rad, from the dead centre]."""
    x = np.asarray(x, dtype=float)
    u = np.clip((x - burn.start) / burn.duration, 0.0, None)
    e = np.exp(-burn.a * u ** (burn.m + 1.0))
    fraction = 1.0 - e
    rate = np.where(u > 0, burn.a * (burn.m + 1.0) * u**burn.m * e / burn.duration, 0.0)
    return fraction, rate


def woschni(pressure, temperature, diameter, gas_speed):
    """Woschni's heat-transfer coefficient [W/(m^2 K)], Heywood eq. 12.19 (SI in, kPa inside)."""
    p_kpa = np.asarray(pressure) / 1e3
    return (
        3.26
        * np.asarray(diameter) ** -0.2
        * p_kpa**0.8
        * np.asarray(temperature) ** -0.55
        * (np.asarray(gas_speed) ** 0.8)
    )


def closed_cycle(volume, x, heat, burn: Wiebe | None, charge: Charge, mass, wall=None):
    """Pressure over the closed part of a chamber's cycle, from intake closure to exhaust opening.

    Parameters
    ----------
    volume : callable
        ``volume(x) -> (V, dV/dx)`` [m^3, m^3/rad] on the grid ``x`` (any leading design
        shape broadcast with it).
    x : ndarray, shape (n,)
        The cycle's angle from intake closure (the largest volume) through the dead centre
        (``x = 0``, smallest volume) to exhaust opening, increasing [rad].
    heat : float or ndarray
        Heat released by the charge [J].
    burn : Wiebe or None
        None: all the heat at once at ``x = 0`` (the ideal Otto cycle's isochoric heating).
    charge : Charge
        Intake state and ``gamma``.
    mass : float or ndarray
        Trapped mass [kg] (for the temperature).
    wall : tuple, optional
        ``(area(x) [m^2], diameter [m], gas_speed [m/s], wall_temperature [K],
        seconds_per_rad [s])``; None: adiabatic.

    Returns
    -------
    dict of ndarray
        ``p`` [Pa], ``T`` [K], ``work`` [J] (``int p dV``), ``heat_wall`` [J] (to the
        walls, positive out), ``heat_released`` [J].
    """
    g = charge.gamma
    x = np.asarray(x, dtype=float)
    v0, _ = volume(x[0])
    heat = np.asarray(heat, dtype=float)
    mass = np.asarray(mass, dtype=float)
    shape = np.broadcast_shapes(np.shape(v0), heat.shape, mass.shape)  # one value per chamber
    p = np.full(shape, float(charge.intake_pressure))

    def rates(xi, p):
        v, dv = volume(xi)
        temperature = p * v / (mass * R_AIR)
        q_burn = heat * wiebe(burn, xi)[1] if burn is not None else 0.0 * p
        if wall is None:
            q_wall = 0.0 * p
        else:
            area, diameter, speed, t_wall, seconds = wall
            h = woschni(p, temperature, diameter, speed)
            q_wall = h * area(xi) * (temperature - t_wall) * seconds
        dp = (g - 1.0) / v * (q_burn - q_wall) - g * p / v * dv
        return dp, p * dv, q_wall

    out_p = [p]
    work = 0.0 * p
    lost = 0.0 * p
    done_instant = burn is not None
    for k in range(len(x) - 1):  # the grid of one cycle (a few thousand steps), designs in arrays
        a, b = x[k], x[k + 1]
        if not done_instant and a < 0.0 <= b:  # isochoric heating at the dead centre
            # integrate to 0, add the heat at constant volume, continue
            p, work, lost = _rk4(rates, a, 0.0, p, work, lost)
            v, _ = volume(0.0)
            p = p + (g - 1.0) * heat / v
            done_instant = True
            p, work, lost = _rk4(rates, 0.0, b, p, work, lost)
        else:
            p, work, lost = _rk4(rates, a, b, p, work, lost)
        out_p.append(p)
    pressure = np.stack(out_p, axis=-1) if np.ndim(p) else np.array(out_p)
    v_all, _ = volume(x)
    return {
        "p": pressure,
        "T": pressure * v_all / (np.expand_dims(mass, -1) * R_AIR),
        "work": work,
        "heat_wall": lost,
        "heat_released": heat if burn is None else heat * wiebe(burn, x[-1])[0],
    }


def _rk4(rates, a, b, p, work, lost):
    """One classical Runge-Kutta step of (p, work = int p dV, heat lost) from ``a`` to ``b``."""
    h = b - a
    if h == 0.0:
        return p, work, lost
    k1 = rates(a, p)
    k2 = rates(a + h / 2, p + h / 2 * k1[0])
    k3 = rates(a + h / 2, p + h / 2 * k2[0])
    k4 = rates(b, p + h * k3[0])
    step = [h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]) for i in range(3)]
    return p + step[0], work + step[1], lost + step[2]
