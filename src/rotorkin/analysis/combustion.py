"""Single-zone closed-cycle model of an engine chamber: charge, Wiebe burn, Woschni walls.

The heat a chamber releases comes from the charge it traps (J. B. Heywood,
*Internal Combustion Engine Fundamentals*, 2nd ed. 2018, ch. 4, 9 and 12):

* **Charge** at the closure of the intake (the chamber's largest volume ``V_ivc``, at
  the intake pressure ``p_i`` and temperature ``T_i``): ``m = p_i V_ivc / (R T_i)``, of
  which the fraction ``x_r`` is residual burnt gas; the fresh part is air and fuel,
  ``m_a = (1 - x_r) m / (1 + phi / AFR_s)``, ``m_f = phi m_a / AFR_s``. The heat
  released is ``Q = eta_c min(phi, 1) m_a / AFR_s LHV``: a rich mixture burns only the
  fuel its air can oxidise.
* **Burn**: the Wiebe function ``x_b = 1 - exp(-a ((x - x_0) / dx)^(m + 1))``
  (Heywood eq. 9.23), ``a = 5``, ``m = 2`` by default; ``x`` is the chamber's cycle
  angle, 180 deg per stroke, 0 at the dead centre of smallest volume, like a piston
  engine's crank angle.
* **Walls**: Woschni's correlation (Heywood eq. 12.19),
  ``h = 3.26 B^-0.2 p^0.8 T^-0.55 w^0.8`` [W/(m^2 K); B m, p kPa, T K, w m/s], the
  characteristic gas speed ``w = C_1 S_p + C_2 V_d T_r / (p_r V_r) (p - p_m)`` with
  ``C_1 = 2.28``, ``C_2 = 3.24e-3 m/(s K)`` from the start of the burn on (0 before),
  ``p_m`` the motored pressure (isentropic from intake closure ``r``), ``S_p`` the mean
  speed of the chamber's moving walls, ``B`` the hydraulic diameter of its section;
  ``dQ_w/dt = h A (T - T_w)``.
* **Gas**: ideal, of constant or temperature-dependent properties
  (:mod:`rotorkin.analysis.gas`).

The first law for the mixture of unburnt and burnt gas (sensible energies, the
apparent heat release ``Q dx_b``):

    m c_v(T, x_b) dT/dx = Q dx_b/dx - dQ_w/dx - p dV/dx - m (u_b - u_u)(T) dx_b/dx,
    p = m R(x_b) T / V,

integrated from intake closure (``x = -180 deg``) to exhaust opening (``+180 deg``) by
the classical Runge-Kutta method on a fixed grid (the volumes given on the half
steps). Without walls, with an instant burn at the dead centre and a constant ``gamma``
it is the ideal Otto cycle.

Two paths run the same formulas in the same order (:mod:`rotorkin.core.fused` chooses,
``kernel=`` or ``$ROTORKIN_KERNEL``): numpy operations on arrays of all chambers
(designs) at once, step by step, or -- with a Wiebe burn and numba installed -- one
compiled loop over the chambers, a few side by side, each through all its steps
(:data:`INTERLEAVE`). The gas comes from its uniform tables
(:class:`~rotorkin.analysis.gas.GasTables`: one index per temperature for ``c_v`` of
both gases and ``u_b - u_u``); Woschni's coefficient is evaluated as
``3.26 B^-0.2 (m R w / (1e3 V))^0.8 T^0.25`` (the same value: ``p = m R T / V``), whose
first factor before the burn depends on the volume only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.analysis.gas import ConstantGas
from rotorkin.core.fused import compiled_loop, formula, select, use_compiled

__all__ = [
    "Charge",
    "Wiebe",
    "Walls",
    "trapped_mass",
    "fresh_air",
    "fuel_energy",
    "heat_of_charge",
    "wiebe",
    "woschni",
    "closed_cycle",
    "hermite",
    "WOSCHNI_C1",
    "WOSCHNI_C2",
]

#: Woschni's constants of the gas speed during compression, combustion and expansion.
WOSCHNI_C1, WOSCHNI_C2 = 2.28, 3.24e-3


@dataclass(frozen=True)
class Charge:
    """The trapped charge and its fuel (gasoline by default; Heywood table D.4).

    Attributes
    ----------
    intake_pressure, intake_temperature : float
        At the closure of the intake [Pa, K].
    residual_fraction : float
        Mass fraction of burnt gas left from the last cycle [-].
    equivalence_ratio : float
        Fuel-air ratio over the stoichiometric one [-].
    stoichiometric_afr : float
        Air-fuel mass ratio of the stoichiometric mixture (gasoline 14.6) [-].
    lower_heating_value : float
        Of the fuel (gasoline 44 MJ/kg) [J/kg].
    combustion_efficiency : float
        Fraction of the fuel's energy released (0.97) [-].
    """

    intake_pressure: float = 1.0e5
    intake_temperature: float = 320.0
    residual_fraction: float = 0.05
    equivalence_ratio: float = 1.0
    stoichiometric_afr: float = 14.6
    lower_heating_value: float = 44.0e6
    combustion_efficiency: float = 0.97


def trapped_mass(charge: Charge, volume_ivc, gas_constant):
    """Mass of gas in the chamber at intake closure, ``p_i V / (R T_i)`` [kg]."""
    return (
        charge.intake_pressure * np.asarray(volume_ivc, dtype=float)
        / (gas_constant * charge.intake_temperature)
    )  # fmt: skip


def fresh_air(charge: Charge, mass):
    """Air in the trapped ``mass`` [kg]: ``(1 - x_r) m / (1 + phi / AFR_s)``."""
    return (
        (1.0 - charge.residual_fraction) * np.asarray(mass, dtype=float)
        / (1.0 + charge.equivalence_ratio / charge.stoichiometric_afr)
    )  # fmt: skip


def fuel_energy(charge: Charge, mass):
    """Chemical energy of the fuel in the trapped ``mass``, ``m_f LHV`` [J]."""
    air = fresh_air(charge, mass)
    return charge.equivalence_ratio * air / charge.stoichiometric_afr * charge.lower_heating_value


def heat_of_charge(charge: Charge, mass):
    """Heat the trapped charge releases, ``eta_c min(phi, 1) m_a / AFR_s LHV`` [J]."""
    air = fresh_air(charge, mass)
    burnt = min(charge.equivalence_ratio, 1.0) * air / charge.stoichiometric_afr
    return charge.combustion_efficiency * burnt * charge.lower_heating_value


@dataclass(frozen=True)
class Wiebe:
    """Burn law: start and duration [rad of the chamber's cycle angle], shape ``a``, ``m``."""

    start: float = -np.radians(10.0)
    duration: float = np.radians(50.0)
    a: float = 5.0
    m: float = 2.0


def wiebe(burn: Wiebe, x):
    """Burnt fraction and its derivative at ``x`` [rad of the cycle angle]."""
    x = np.asarray(x, dtype=float)
    u = np.clip((x - burn.start) / burn.duration, 0.0, None)
    e = np.exp(-burn.a * u ** (burn.m + 1.0))
    fraction = 1.0 - e
    rate = np.where(u > 0, burn.a * (burn.m + 1.0) * u**burn.m * e / burn.duration, 0.0)
    return fraction, rate


def woschni(pressure, temperature, diameter, gas_speed):
    """Woschni's heat-transfer coefficient [W/(m^2 K)], Heywood eq. 12.19 (SI in)."""
    p_kpa = np.asarray(pressure) / 1e3
    return (
        3.26
        * np.asarray(diameter) ** -0.2
        * p_kpa**0.8
        * np.asarray(temperature) ** -0.55
        * np.asarray(gas_speed) ** 0.8
    )


@dataclass(frozen=True)
class Walls:
    """What the wall heat transfer needs, on the integration grid (half steps).

    Attributes
    ----------
    area : ndarray (..., 2K+1)
        Wetted wall area of the chamber [m^2].
    diameter : ndarray (...)
        Hydraulic diameter of its section [m].
    wall_speed : ndarray (...)
        Mean speed of its moving walls ``S_p`` [m/s].
    seconds : ndarray (..., 2K+1)
        Time per radian of the cycle angle ``dt/dx`` [s].
    temperature : float
        Wall temperature [K].
    """

    area: np.ndarray
    diameter: np.ndarray
    wall_speed: np.ndarray
    seconds: np.ndarray
    temperature: float


def closed_cycle(x, volume, dvolume, *, mass, heat, gas=None, temperature=None,
                 burn: Wiebe | None = None, walls: Walls | None = None,
                 kernel=None) -> dict:  # fmt: skip
    """Temperature and pressure of chambers from intake closure to exhaust opening.

    Parameters
    ----------
    x : ndarray, shape (2K+1,)
        Uniform grid of the cycle angle, nodes at the even indices and the half steps
        between them (the Runge-Kutta stages); ``x = 0`` (the dead centre) a node when
        ``burn`` is None [rad].
    volume, dvolume : ndarray, shape (..., 2K+1)
        ``V`` and ``dV/dx`` of each chamber on ``x`` [m^3, m^3/rad].
    mass : float or ndarray (...)
        Trapped mass [kg].
    heat : float or ndarray (...)
        Heat the charge releases [J].
    gas : ConstantGas or NasaGas, optional
        Properties (default constant ``gamma = 1.3``), through their
        :class:`~rotorkin.analysis.gas.GasTables`.
    temperature : float or ndarray, optional
        At intake closure [K]; default from the ideal gas law at ``x[0]`` with 1 bar.
    burn : Wiebe or None
        None: all the heat at once at ``x = 0``, at constant volume.
    walls : Walls or None
        None: adiabatic.
    kernel : {"auto", "numpy", "numba"}, optional
        With a Wiebe burn, the chambers' integration as numpy operations on arrays of
        chambers or as one compiled loop per chamber
        (:func:`rotorkin.core.fused.use_compiled`; the same formulas, in the same order).

    Returns
    -------
    dict
        At the nodes (..., K+1): ``x``, ``T``, ``p``, ``dp`` (``dp/dx``, the right-hand
        limit at an instant burn), ``p_left`` (the left-hand limit of ``p`` there),
        ``burnt``; per chamber: ``work`` (``int p dV``), ``heat_wall`` (to the walls),
        ``heat_released``, ``energy_rise`` (the gas's sensible energy, end - start) [J].
    """
    gas = ConstantGas() if gas is None else gas
    x = np.asarray(x, dtype=float)
    volume, dvolume = np.asarray(volume, float), np.asarray(dvolume, float)
    mass = np.asarray(mass, dtype=float)
    heat = np.asarray(heat, dtype=float)
    shape = np.broadcast_shapes(volume.shape[:-1], mass.shape, heat.shape)
    n_half = x.size
    if n_half < 3 or n_half % 2 == 0:
        raise ValueError("x needs 2K+1 points, K >= 1")
    h = x[2] - x[0]
    volume = np.broadcast_to(volume, shape + (n_half,))
    dvolume = np.broadcast_to(dvolume, shape + (n_half,))
    t0 = (1.0e5 * volume[..., 0] / (mass * gas.gas_constant(0.0)) if temperature is None
          else np.broadcast_to(np.asarray(temperature, float), shape))  # fmt: skip
    t0 = np.broadcast_to(t0, shape).astype(float)
    zero = n_half
    if burn is None:
        at = np.flatnonzero(np.isclose(x[::2], 0.0, rtol=0.0, atol=1e-9 * abs(h)))
        zero = int(at[0]) if at.size else n_half  # no dead centre on the grid: motored
        fraction = np.where(np.arange(n_half) >= 2 * zero, 1.0, 0.0)
        rate = np.zeros(n_half)
    else:
        fraction, rate = wiebe(burn, x)
    tables = gas.tables()
    r_half = np.broadcast_to(gas.gas_constant(fraction), (n_half,)).astype(float)
    nodes = slice(0, None, 2)
    dr = (gas.gas_constant(1.0) - gas.gas_constant(0.0)) * rate[nodes]
    wall = _wall_constants(gas, walls, burn, x, shape, mass, t0, volume)
    chambers = int(np.prod(shape))
    if burn is not None and use_compiled(chambers * n_half, kernel):
        args = (h, volume, dvolume, r_half, fraction, rate, dr, mass, heat, t0, walls, wall)
        temp, pressure, dp, work, lost = _compiled_cycle(*args, tables, shape)
        p_left = pressure.copy()  # a Wiebe burn: no jump, the limits from both sides agree
    else:
        args = (h, volume, dvolume, r_half, fraction, rate, zero, mass, heat, t0, gas, walls)
        temp, temp_left, slopes, work, lost = _numpy_cycle(*args, wall, tables, shape)
        m = mass[..., None] if np.ndim(mass) else mass
        r_gas = r_half[nodes]
        v_nodes = volume[..., nodes]
        pressure = m * r_gas * temp / v_nodes
        # dp/dx = m/V (R dT/dx + T dR/dx) - p dV/dx / V at the nodes
        dp = (m * (r_gas * slopes + temp * dr) - pressure * dvolume[..., nodes]) / v_nodes
        p_left = m * r_gas * temp_left / volume[..., nodes]
    xb = fraction[nodes]
    energy0 = gas.energy(t0, 0.0)
    energy1 = gas.energy(temp[..., -1], xb[-1])
    return {
        "x": x[nodes],
        "T": temp,
        "p": pressure,
        "p_left": p_left,
        "dp": dp,
        "burnt": xb,
        "work": work,
        "heat_wall": lost,
        "heat_released": heat * xb[-1],
        "energy_rise": mass * (energy1 - energy0),
    }


def _wall_constants(gas, walls, burn, x, shape, mass, t0, volume):
    """Per chamber: Woschni's constant factors and the motored state from intake closure."""
    if walls is None:
        return None
    r0 = gas.gas_constant(0.0)
    gamma_m = 1.0 + r0 / gas.cv(t0, 0.0)
    v0 = volume[..., 0]
    p0 = mass * r0 * t0 / v0
    v_d = np.max(volume, -1) - np.min(volume, -1)
    full = lambda a: np.broadcast_to(np.asarray(a, dtype=float), shape)  # noqa: E731
    return {
        "p0": full(p0),
        "v0": full(v0),
        "gamma": full(gamma_m),
        "c1sp": full(WOSCHNI_C1 * np.asarray(walls.wall_speed, dtype=float)),
        "c2k": full(WOSCHNI_C2 * v_d * t0 / (p0 * v0)),
        "cd": full(3.26 * np.asarray(walls.diameter, dtype=float) ** -0.2),
        "started": x >= (burn.start if burn is not None else 0.0),
    }


@formula
def _motored(p0, v0, v, gamma):
    """Pressure of the motored charge, ``p_0 (V_0 / V)^gamma`` [Pa]."""
    return p0 * np.exp(gamma * np.log(v0 / v))


@formula
def _pressure(mass, r, t, v):
    """``p = m R T / V`` [Pa]."""
    return mass * r * t / v


@formula
def _gas_speed(p, motored, started, c1sp, c2k):
    """Woschni's gas speed ``w = C_1 S_p + C_2 V_d T_r / (p_r V_r) (p - p_m)`` [m/s]."""
    excess = p - motored
    return c1sp + select(started, c2k * select(excess > 0.0, excess, 0.0), 0.0)


@formula
def _wall_factor(mass, r, speed, v):
    """``(p w / 1e3)^0.8 T^-0.8 = (m R w / (1e3 V))^0.8`` of Woschni's coefficient."""
    return np.exp(0.8 * np.log(mass * r * speed / (1e3 * v)))


@formula
def _wall_heat(t, factor, cd, area, seconds, t_wall):
    """Heat to the walls per radian of cycle angle [J/rad] (numbers or arrays).

    Woschni's coefficient ``3.26 B^-0.2 (p/1e3)^0.8 T^-0.55 w^0.8`` (:func:`woschni`)
    as ``cd factor T^0.25``, ``cd = 3.26 B^-0.2``, ``factor`` from :func:`_wall_factor`
    (before the burn it depends on the volume only: the compiled loop takes it once per
    grid point), ``T^0.25`` two square roots.
    """
    coeff = cd * factor * np.sqrt(np.sqrt(t))
    return coeff * area * (t - t_wall) * seconds


@formula
def _stage(t, p, dv, xb, dxb, mass, heat, cvu, cvb, du, q_wall):
    """``dT/dx`` and ``p dV/dx`` of one chamber at one grid point (numbers or arrays).

    ``cvu, cvb, du``: the gas tables at ``t``; ``q_wall``: :func:`_wall_heat`.
    """
    cv = (1.0 - xb) * cvu + xb * cvb
    return (heat * dxb - q_wall - p * dv - mass * (du * dxb)) / (mass * cv), p * dv


def _numpy_cycle(h, volume, dvolume, r_half, fraction, rate, zero, mass, heat, t0, gas, walls,
                 wall, tables, shape):  # fmt: skip
    """The classical Runge-Kutta steps as numpy operations on arrays of chambers."""
    n_half = r_half.size
    zeros = np.zeros(shape)
    if walls is not None:  # the motored pressure on the whole grid at once
        ex = lambda a: np.asarray(a)[..., None]  # noqa: E731
        motored = _motored(ex(wall["p0"]), ex(wall["v0"]), volume, ex(wall["gamma"]))

    def rates(i, t):
        cvu, cvb, du = tables.lookup(t)
        v = volume[..., i]
        p = _pressure(mass, r_half[i], t, v)
        q_wall = 0.0 * t
        if walls is not None:
            speed = _gas_speed(p, motored[..., i], bool(wall["started"][i]), wall["c1sp"],
                               wall["c2k"])  # fmt: skip
            factor = _wall_factor(mass, r_half[i], speed, v)
            q_wall = _wall_heat(t, factor, wall["cd"], walls.area[..., i], walls.seconds[..., i],
                                walls.temperature)  # fmt: skip
        dt, pdv = _stage(t, p, dvolume[..., i], fraction[i], rate[i], mass, heat, cvu, cvb, du,
                         q_wall)  # fmt: skip
        return dt, pdv, q_wall

    t = t0
    work, lost = zeros, zeros
    temps, left, slopes = [t], [t], []
    for k in range(0, n_half - 1, 2):  # the cycle's steps, chambers in arrays
        if k == 2 * zero:  # all the heat at the dead centre
            before = gas.energy(t, 0.0)
            t = gas.temperature_after(before + heat / mass, 1.0)
            temps[-1] = t
        k1 = rates(k, t)
        slopes.append(k1[0])  # dT/dx at the node (after an instant burn there)
        k2 = rates(k + 1, t + h / 2 * k1[0])
        k3 = rates(k + 1, t + h / 2 * k2[0])
        k4 = rates(k + 2, t + h * k3[0])
        steps = [h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]) for j in range(3)]
        t, work, lost = t + steps[0], work + steps[1], lost + steps[2]
        temps.append(t)
        left.append(t)
    slopes.append(rates(n_half - 1, t)[0])  # the last node
    stack = lambda a: np.stack([np.broadcast_to(v, shape) for v in a], axis=-1)  # noqa: E731
    work, lost = (np.broadcast_to(a, shape) + 0.0 for a in (work, lost))
    return stack(temps), stack(left), stack(slopes), work, lost


def _compiled_cycle(h, volume, dvolume, r_half, fraction, rate, dr, mass, heat, t0, walls, wall,
                    tables, shape):  # fmt: skip
    """The same steps as one compiled loop per chamber (numba), chambers flattened."""
    n_half = r_half.size
    n = int(np.prod(shape))
    flat = lambda a: np.ascontiguousarray(np.broadcast_to(a, shape).reshape(n))  # noqa: E731
    grid = lambda a: np.ascontiguousarray(np.broadcast_to(a, shape + (n_half,)).reshape(n, -1))  # noqa: E731
    if walls is None:
        lazy = np.zeros((n, n_half))  # never read (calloc: never touched either)
        area, seconds, per = lazy, lazy, [np.zeros(n)] * 6
        started, t_wall = np.zeros(n_half, dtype=np.bool_), 0.0
    else:
        area, seconds = grid(walls.area), grid(walls.seconds)
        per = [flat(wall[k]) for k in ("p0", "v0", "gamma", "c1sp", "c2k", "cd")]
        started, t_wall = wall["started"], float(walls.temperature)
    k = (n_half - 1) // 2
    temp, pressure, dp = np.empty((n, k + 1)), np.empty((n, k + 1)), np.empty((n, k + 1))
    work, lost = np.empty(n), np.empty(n)
    _cycle_loop(float(h), grid(volume), grid(dvolume), r_half, fraction, rate, dr, flat(mass),
                flat(heat), flat(t0), walls is not None, started, area, seconds, *per, t_wall,
                tables.lo, tables.inv_step, tables.values, tables.slopes, temp, pressure, dp,
                work, lost)  # fmt: skip
    out = (temp, pressure, dp)
    return (*(a.reshape(shape + (k + 1,)) for a in out), work.reshape(shape),
            lost.reshape(shape))  # fmt: skip


@formula
def _lookup(lo, inv_step, values, slopes, t):
    """The gas tables at one temperature (a number; NaN propagates), as :func:`table_index`."""
    nodes = values.shape[1]
    top = nodes - 1.0
    s = (t - lo) * inv_step
    s = select(s < 0.0, 0.0, select(s > top, top, s))
    j = min(int(select(s == s, s, 0.0)), nodes - 2)
    f = s - j
    return (values[0, j] + f * slopes[0, j], values[1, j] + f * slopes[1, j],
            values[2, j] + f * slopes[2, j])  # fmt: skip


#: Chambers integrated side by side in the compiled loop (independent work for the CPU to
#: overlap while one chamber waits for its exponential).
INTERLEAVE = 8


@compiled_loop
def _cycle_loop(h, volume, dvolume, r_half, fraction, rate, dr, mass, heat, t0, walls, started,
                area, seconds, p0, v0, gamma, c1sp, c2k, cd, t_wall, lo, inv_step, values,
                slopes, temp, pressure, dp, work, lost):  # fmt: skip
    """Runge-Kutta steps of each chamber; ``T``, ``p``, ``dp/dx`` at the nodes, work, heat lost.

    The steps of :func:`_numpy_cycle` (a Wiebe burn), :data:`INTERLEAVE` chambers at a time,
    each with the same operations in the same order.
    """
    n, n_half = volume.shape
    g = INTERLEAVE
    state = np.zeros((7, g))  # T, the stage's T, the Runge-Kutta sums (3), work, heat lost
    t_, ts_, st_, sw_, sq_, ws_, qs_ = (state[0], state[1], state[2], state[3], state[4],
                                        state[5], state[6])  # fmt: skip
    # per grid point of the step (start, middle, end): the motored pressure (after the burn's
    # start) and Woschni's factor (before it, where it does not depend on the temperature)
    motored, factor = np.zeros((3, g)), np.zeros((3, g))
    for c0 in range(0, n, g):
        cnt = min(g, n - c0)
        for j in range(cnt):
            t_[j], ws_[j], qs_[j] = t0[c0 + j], 0.0, 0.0
        node = 0
        for k in range(0, n_half, 2):
            last = k == n_half - 1
            if walls:
                for j in range(cnt):
                    c = c0 + j
                    for at in range(3):
                        i = k + at
                        if (at == 0 and k > 0) or i >= n_half:
                            continue
                        if started[i]:
                            motored[at, j] = _motored(p0[c], v0[c], volume[c, i], gamma[c])
                        else:
                            factor[at, j] = _wall_factor(mass[c], r_half[i], c1sp[c],
                                                         volume[c, i])  # fmt: skip
            for stage in range(4):
                i = k + (stage + 1) // 2
                at = (stage + 1) // 2
                for j in range(cnt):
                    c = c0 + j
                    m, q, t = mass[c], heat[c], t_[j]
                    ts = t if stage == 0 else ts_[j]
                    v = volume[c, i]
                    p = _pressure(m, r_half[i], ts, v)
                    q_wall = 0.0
                    if walls:
                        f = factor[at, j]
                        if started[i]:
                            speed = _gas_speed(p, motored[at, j], True, c1sp[c], c2k[c])
                            f = _wall_factor(m, r_half[i], speed, v)
                        q_wall = _wall_heat(ts, f, cd[c], area[c, i], seconds[c, i], t_wall)
                    cvu, cvb, du = _lookup(lo, inv_step, values, slopes, ts)
                    dt, pdv = _stage(ts, p, dvolume[c, i], fraction[i], rate[i], m, q, cvu, cvb,
                                     du, q_wall)  # fmt: skip
                    if stage == 0:  # the node
                        temp[c, node] = t
                        pressure[c, node] = p
                        dp[c, node] = (m * (r_half[i] * dt + t * dr[node])
                                       - p * dvolume[c, i]) / v  # fmt: skip
                        st_[j], sw_[j], sq_[j] = dt, pdv, q_wall
                        ts_[j] = t + h / 2 * dt
                    elif stage < 3:
                        st_[j], sw_[j] = st_[j] + 2 * dt, sw_[j] + 2 * pdv
                        sq_[j] = sq_[j] + 2 * q_wall
                        ts_[j] = t + (h / 2 if stage == 1 else h) * dt
                    else:
                        t_[j] = t + h / 6 * (st_[j] + dt)
                        ws_[j] = ws_[j] + h / 6 * (sw_[j] + pdv)
                        qs_[j] = qs_[j] + h / 6 * (sq_[j] + q_wall)
                if last:
                    break
            node += 1
            if walls:  # the step's end is the next one's start
                for j in range(cnt):
                    motored[0, j], factor[0, j] = motored[2, j], factor[2, j]
        for j in range(cnt):
            work[c0 + j], lost[c0 + j] = ws_[j], qs_[j]


def hermite(x_nodes, values, slopes, rows, xq, left=None):
    """Cubic Hermite interpolation in tables on one uniform grid.

    Parameters
    ----------
    x_nodes : ndarray (K+1,)
        Uniform, increasing.
    values, slopes : ndarray (R, K+1)
        Function and derivative at the nodes, one row per table.
    rows : ndarray of int (...)
        The table of each query.
    xq : ndarray (...)
        Query points (broadcast with ``rows``).
    left : ndarray (R, K+1), optional
        The left-hand limits of ``values`` at the nodes (a jump); an interval's right end
        takes those.
    """
    x0, h = x_nodes[0], x_nodes[1] - x_nodes[0]
    k = x_nodes.size - 1
    rows, xq = np.broadcast_arrays(np.asarray(rows), np.asarray(xq, dtype=float))
    s = (xq - x0) / h
    i = np.clip(np.floor(s).astype(int), 0, k - 1)
    u = s - i
    flat_a, flat_b = rows * (k + 1) + i, rows * (k + 1) + i + 1
    v, d = np.ravel(values), np.ravel(slopes)
    ya, yb = v[flat_a], (v if left is None else np.ravel(left))[flat_b]
    da, db = d[flat_a] * h, d[flat_b] * h
    h00, h10 = 2 * u**3 - 3 * u**2 + 1, u**3 - 2 * u**2 + u
    h01, h11 = -2 * u**3 + 3 * u**2, u**3 - u**2
    return h00 * ya + h10 * da + h01 * yb + h11 * db
