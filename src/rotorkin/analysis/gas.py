"""Caloric properties of an engine's gas: unburnt charge and burnt products, over temperature.

A single-zone engine model needs, for the mixture of unburnt charge and burnt gas
(burnt mass fraction ``x``), the gas constant ``R(x)``, the specific heat at constant
volume ``c_v(T, x)`` and the sensible internal energy ``u(T, x)`` (zero at 298.15 K):

* :class:`ConstantGas` -- one ratio of specific heats ``gamma`` for both
  (``c_v = R / (gamma - 1)``); the ideal-gas cycles' assumption.
* :class:`NasaGas` -- the species' NASA 7-coefficient polynomials (GRI-Mech 3.0
  thermodynamic data, :data:`NASA7`, the values Cantera's ``gri30.yaml`` holds; the
  tests check the tables against Cantera's, the ``thermo`` extra) for

  - the unburnt charge: dry air (molar O2 20.95 %, N2 78.09 %, Ar 0.93 %, 0.03 % CO2
    counted as Ar) and the residual burnt gas; the fuel vapour (about 6 % of the mass
    at stoichiometry) is not counted, it changes ``c_v`` by about 1 % at most;
  - the burnt gas: the complete products of a fuel ``C H_y`` (``y`` the fuel's
    hydrogen-to-carbon ratio, gasoline 1.87) with that air at the equivalence ratio
    ``phi``: CO2, H2O, N2, Ar and the excess O2 (``phi < 1``); frozen, no dissociation
    (which lowers the real peak temperatures above about 2500 K; Heywood ch. 4.9).
    Richer mixtures take the stoichiometric products (what burns is limited by the
    air, :mod:`rotorkin.analysis.combustion`).

  Tabulated once per composition on a 1 K grid from 200 K to 5000 K and
  interpolated linearly (``c_v``) and by the trapezoid integral of that table
  (``u``), so that ``du = c_v dT`` holds on the tables exactly.

Both give :class:`GasTables`: ``c_v`` of the unburnt and of the burnt gas and
``u_b - u_u`` on one uniform grid, read with one index per temperature (what the
single-zone cycle needs at every Runge-Kutta stage).

J. B. Heywood, *Internal Combustion Engine Fundamentals*, 2nd ed., 2018, ch. 4.
G. P. Smith et al., GRI-Mech 3.0, http://combustion.berkeley.edu/gri-mech/ (thermodynamic
data of the species).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

__all__ = [
    "ConstantGas",
    "NasaGas",
    "R_UNIVERSAL",
    "R_AIR",
    "NASA7",
    "burnt_composition",
    "GasTables",
    "table_index",
]

#: Universal gas constant [J/(mol K)] (Boltzmann times Avogadro, exact in SI since 2019).
R_UNIVERSAL = 8.31446261815324
#: Gas constant of dry air [J/(kg K)] (molar mass 28.965 g/mol).
R_AIR = R_UNIVERSAL / 28.965e-3
#: Dry air, molar fractions (the 0.03 % CO2 counted as argon).
AIR = {"O2": 0.2095, "N2": 0.7809, "AR": 0.0096}
_T_LO, _T_HI = 200.0, 5000.0
_T_REF = 298.15


@dataclass(frozen=True)
class GasTables:
    """The caloric properties a single-zone cycle needs, as tables on one uniform grid.

    Piecewise linear in ``T`` between the nodes ``T_j = lo + j / inv_step`` and constant
    beyond the ends (as :func:`numpy.interp`); the value at ``T`` is
    ``values[:, j] + f slopes[:, j]``, ``j, f`` from :func:`table_index`.

    Attributes
    ----------
    lo : float
        Temperature of the first node [K].
    inv_step : float
        Nodes per kelvin [1/K].
    values : ndarray (3, J)
        ``c_v`` of the unburnt charge and of the burnt gas [J/(kg K)] and ``u_b - u_u``
        [J/kg] at the nodes.
    slopes : ndarray (3, J)
        Their differences to the next node (0 at the last).
    r_unburnt, r_burnt : float
        Gas constants [J/(kg K)].
    """

    lo: float
    inv_step: float
    values: np.ndarray
    slopes: np.ndarray
    r_unburnt: float
    r_burnt: float

    @classmethod
    def of(cls, lo, inv_step, cv_unburnt, cv_burnt, du, r_unburnt, r_burnt) -> GasTables:
        """Tables from the node values (the slopes follow)."""
        values = np.ascontiguousarray(np.stack([cv_unburnt, cv_burnt, du]), dtype=float)
        slopes = np.zeros_like(values)
        slopes[:, :-1] = np.diff(values, axis=1)
        return cls(float(lo), float(inv_step), values, slopes, float(r_unburnt), float(r_burnt))

    def lookup(self, t):
        """``(c_v unburnt, c_v burnt, u_b - u_u)`` at temperatures ``t`` (arrays)."""
        j, f = table_index(self.lo, self.inv_step, self.values.shape[1], t)
        v, d = self.values, self.slopes
        return tuple(v[k].take(j) + f * d[k].take(j) for k in range(3))


def table_index(lo, inv_step, nodes, t):
    """Node ``j`` (``0 <= j <= nodes - 2``) and fraction ``f`` (in [0, 1]) of ``t`` (arrays).

    ``s = (t - lo) inv_step`` clipped to ``[0, nodes - 1]``, ``j = min(floor(s), nodes - 2)``,
    ``f = s - j``; a NaN temperature gives ``j = 0`` and ``f = NaN``.
    """
    s = np.minimum(np.maximum((np.asarray(t, dtype=float) - lo) * inv_step, 0.0), nodes - 1.0)
    with np.errstate(invalid="ignore"):
        j = s.astype(np.intp)
    j = np.minimum(np.maximum(j, 0), nodes - 2)
    return j, s - j


@dataclass(frozen=True)
class ConstantGas:
    """Ideal gas of one ratio of specific heats, unburnt and burnt alike.

    Parameters
    ----------
    gamma : float
        ``c_p / c_v`` [-], ``> 1``.
    r : float
        Gas constant [J/(kg K)] (air by default).
    """

    gamma: float = 1.3
    r: float = R_AIR

    @property
    def label(self) -> str:
        return f"constant gamma = {self.gamma:g}"

    def gas_constant(self, x):
        """``R`` [J/(kg K)] at burnt fraction ``x``."""
        return self.r + 0.0 * np.asarray(x, dtype=float)

    def cv(self, t, x):
        """``c_v`` [J/(kg K)]."""
        return self.r / (self.gamma - 1.0) + 0.0 * (np.asarray(t) + np.asarray(x))

    def energy(self, t, x):
        """Sensible internal energy ``u`` [J/kg], zero at 298.15 K."""
        return self.r / (self.gamma - 1.0) * (np.asarray(t, dtype=float) - _T_REF) + 0.0 * x

    def burnt_minus_unburnt(self, t):
        """``u_b(T) - u_u(T)`` [J/kg]: zero for one gas."""
        return 0.0 * np.asarray(t, dtype=float)

    def temperature_after(self, energy, x):
        """The temperature whose energy is ``energy`` at burnt fraction ``x`` [K]."""
        return _T_REF + np.asarray(energy, dtype=float) * (self.gamma - 1.0) / self.r

    def tables(self) -> GasTables:
        """:class:`GasTables` of the gas: constant ``c_v``, no energy of reaction."""
        cv = np.full(2, self.r / (self.gamma - 1.0))
        return GasTables.of(0.0, 1.0, cv, cv, np.zeros(2), self.r, self.r)


def burnt_composition(equivalence_ratio: float, hc_ratio: float) -> dict:
    """Molar amounts of the complete products of ``C H_y`` with air per mole of fuel carbon.

    ``C H_y + (a_s / phi) (O2 + 3.727 N2 + 0.0458 Ar) -> CO2 + y/2 H2O + ...``,
    ``a_s = 1 + y / 4``; ``phi`` taken at most 1 (stoichiometric products).
    """
    phi = min(float(equivalence_ratio), 1.0)
    a_s = 1.0 + hc_ratio / 4.0
    o2 = a_s / phi
    return {
        "CO2": 1.0,
        "H2O": hc_ratio / 2.0,
        "O2": o2 - a_s,
        "N2": o2 * AIR["N2"] / AIR["O2"],
        "AR": o2 * AIR["AR"] / AIR["O2"],
    }


#: NASA 7-coefficient polynomials of the species of air and of the burnt gas (GRI-Mech
#: 3.0): ``species -> (molar mass [g/mol], T_mid [K], low, high)``, ``low`` for
#: ``T <= T_mid``; ``c_p / R = a0 + a1 T + a2 T^2 + a3 T^3 + a4 T^4`` (``a5``, ``a6``,
#: the enthalpy and entropy constants, are not needed for sensible energies). Molar
#: masses from the atomic weights C 12.011, H 1.008, N 14.007, O 15.999, Ar 39.95.
NASA7 = {
    "O2": (31.998, 1000.0,
           (3.78245636, -0.00299673416, 9.84730201e-06, -9.68129509e-09, 3.24372837e-12),
           (3.28253784, 0.00148308754, -7.57966669e-07, 2.09470555e-10, -2.16717794e-14)),
    "N2": (28.014, 1000.0,
           (3.298677, 0.0014082404, -3.963222e-06, 5.641515e-09, -2.444854e-12),
           (2.92664, 0.0014879768, -5.68476e-07, 1.0097038e-10, -6.753351e-15)),
    "AR": (39.95, 1000.0, (2.5, 0.0, 0.0, 0.0, 0.0), (2.5, 0.0, 0.0, 0.0, 0.0)),
    "CO2": (44.009, 1000.0,
            (2.35677352, 0.00898459677, -7.12356269e-06, 2.45919022e-09, -1.43699548e-13),
            (3.85746029, 0.00441437026, -2.21481404e-06, 5.23490188e-10, -4.72084164e-14)),
    "H2O": (18.015, 1000.0,
            (4.19864056, -0.0020364341, 6.52040211e-06, -5.48797062e-09, 1.77197817e-12),
            (3.03399249, 0.00217691804, -1.64072518e-07, -9.7041987e-11, 1.68200992e-14)),
}  # fmt: skip


def _cp_over_r(species: str, t) -> np.ndarray:
    """``c_p / R`` of one species at temperatures ``t`` [K] (:data:`NASA7`)."""
    _, t_mid, low, high = NASA7[species]
    t = np.asarray(t, dtype=float)
    a = np.where(t <= t_mid, np.asarray(low)[:, None], np.asarray(high)[:, None])
    return a[0] + t * (a[1] + t * (a[2] + t * (a[3] + t * a[4])))


@lru_cache(maxsize=32)
def _tables(composition: tuple) -> tuple:
    """``(T, R, c_v(T), u(T))`` of an ideal-gas mixture given as ((species, moles), ...).

    ``c_p`` of the mixture is the mole-weighted sum of the species' (:data:`NASA7`),
    ``c_v = c_p - R`` per mole, divided by the mean molar mass per kilogram.
    """
    t = np.arange(_T_LO, _T_HI + 0.5, 1.0)
    names = [name for name, _ in composition]
    moles = np.array([n for _, n in composition], dtype=float)
    x = moles / moles.sum()
    molar_mass = float(np.dot(x, [NASA7[name][0] for name in names])) * 1e-3  # kg/mol
    cp_r = sum(xk * _cp_over_r(name, t) for name, xk in zip(names, x, strict=True))
    cv = R_UNIVERSAL * (cp_r - 1.0) / molar_mass
    u = np.concatenate([[0.0], np.cumsum(0.5 * (cv[1:] + cv[:-1]) * np.diff(t))])
    u = u - np.interp(_T_REF, t, u)
    return t, R_UNIVERSAL / molar_mass, cv, u


class NasaGas:
    """Unburnt charge and burnt products from the species' NASA polynomials (:data:`NASA7`).

    Parameters
    ----------
    equivalence_ratio : float
        Of the fresh mixture [-].
    hc_ratio : float
        Hydrogen-to-carbon atom ratio of the fuel [-] (gasoline 1.87).
    residual_fraction : float
        Mass fraction of burnt gas in the unburnt charge [-].
    """

    def __init__(self, equivalence_ratio=1.0, hc_ratio=1.87, residual_fraction=0.0):
        burnt = burnt_composition(equivalence_ratio, hc_ratio)
        self._b = _tables(tuple(sorted(burnt.items())))
        self._a = _tables(tuple(sorted(AIR.items())))
        self.residual_fraction = float(residual_fraction)
        self._mixture = None
        self.label = "NASA polynomials (GRI-Mech 3.0 data)"

    def _unburnt(self, table_index, t):
        a, b, xr = self._a, self._b, self.residual_fraction
        return (1.0 - xr) * np.interp(t, a[0], a[table_index]) + xr * np.interp(
            t, b[0], b[table_index]
        )

    def gas_constant(self, x):
        x = np.asarray(x, dtype=float)
        ru = (1.0 - self.residual_fraction) * self._a[1] + self.residual_fraction * self._b[1]
        return (1.0 - x) * ru + x * self._b[1]

    def cv(self, t, x):
        x = np.asarray(x, dtype=float)
        return (1.0 - x) * self._unburnt(2, t) + x * np.interp(t, self._b[0], self._b[2])

    def energy(self, t, x):
        x = np.asarray(x, dtype=float)
        return (1.0 - x) * self._unburnt(3, t) + x * np.interp(t, self._b[0], self._b[3])

    def burnt_minus_unburnt(self, t):
        return np.interp(t, self._b[0], self._b[3]) - self._unburnt(3, t)

    def tables(self) -> GasTables:
        """:class:`GasTables` of the gas on its 1 K grid (computed once per composition)."""
        if self._mixture is None:
            a, b, xr = self._a, self._b, self.residual_fraction
            t = a[0]
            cv_u = (1.0 - xr) * a[2] + xr * b[2]
            u_u = (1.0 - xr) * a[3] + xr * b[3]
            r_u = (1.0 - xr) * a[1] + xr * b[1]
            self._mixture = GasTables.of(t[0], 1.0 / (t[1] - t[0]), cv_u, b[2], b[3] - u_u, r_u,
                                         b[1])  # fmt: skip
        return self._mixture

    def temperature_after(self, energy, x):
        """Inverse of :meth:`energy` in ``T`` (monotone), on the 1 K grid."""
        t = self._b[0]
        energy, x = np.broadcast_arrays(np.asarray(energy, float), np.asarray(x, float))
        out = np.empty(energy.shape)
        for idx in np.ndindex(energy.shape):  # a few chambers, once per cycle
            out[idx] = np.interp(energy[idx], self.energy(t, x[idx]), t)
        return out
