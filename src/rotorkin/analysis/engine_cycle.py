"""Ideal four-stroke cycle of one chamber: pressures, stroke works, efficiency.

The air-standard cycle with polytropic compression and expansion (e.g.
Heywood, *Internal Combustion Engine Fundamentals*, ch. 5, the constant-volume
fuel-air cycle simplified to an ideal gas):

* intake (stroke 0): the volume rises from ``V_min`` to ``V_max`` at the ambient
  pressure ``p_a``;
* compression (stroke 1): ``p = p_a (V_max / V)^k``, ``k`` the polytropic exponent;
* heat ``Q`` added at the minimum volume, at constant volume: with the gas's
  ``c_v = R / (k - 1)`` (the simplification: the same k for the caloric
  relation as for the polytropes) ``Q = V_min Delta p / (k - 1)``, so
  ``Delta p = (k - 1) Q / V_min`` and the peak pressure is
  ``p_3 = p_a r^k + (k - 1) Q / V_min``, ``r = V_max / V_min``;
* power (stroke 2): ``p = p_3 (V_min / V)^k``;
* blow-down to ``p_a`` at the maximum volume (constant volume), then exhaust
  (stroke 3) at ``p_a``.

Intake and exhaust works cancel, so the indicated work of a cycle is
``W = Q (1 - r^(1 - k))``: the Otto efficiency with the polytropic exponent.
The functions are plain and broadcast over any shape; which stroke a chamber
is in at an angle is the machine's business (it knows where its volume
extremes are), given here as a stroke counter (:func:`stroke_from_count`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.core.errors import ParameterError

__all__ = [
    "INTAKE",
    "COMPRESSION",
    "POWER",
    "EXHAUST",
    "STROKE_NAMES",
    "IdealCycle",
    "stroke_from_count",
    "compression_end_pressure",
    "peak_pressure",
    "expansion_end_pressure",
    "cycle_pressure",
    "stroke_works",
    "indicated_work",
    "otto_efficiency",
    "mean_effective_pressure",
    "cycle_violation",
    "CYCLE_CHECKS",
]

INTAKE, COMPRESSION, POWER, EXHAUST = 0, 1, 2, 3
#: Names of the strokes by index.
STROKE_NAMES = ("intake", "compression", "power", "exhaust")


@dataclass(frozen=True)
class IdealCycle:
    """Loads of the ideal four-stroke cycle (SI; config section ``[loads]``).

    Parameters
    ----------
    ambient_pressure : float, optional
        Intake and exhaust pressure ``p_a`` [Pa] (default 1 bar).
    polytropic_exponent : float, optional
        ``k`` of ``p V^k = const`` on compression and expansion, also used as the
        ratio of specific heats for the heat addition, ``k > 1`` [-] (default 1.35).
    heat_per_cycle : float, optional
        Heat ``Q`` added at minimum volume, per chamber and four-stroke cycle,
        ``Q >= 0`` [J] (default 0: a gas spring, no net work).
    """

    ambient_pressure: float = 1.0e5
    polytropic_exponent: float = 1.35
    heat_per_cycle: float = 90.0

    def __post_init__(self):
        code = cycle_violation(self.ambient_pressure, self.polytropic_exponent, self.heat_per_cycle)
        if np.any(code):
            first = int(np.ravel(code)[np.flatnonzero(np.ravel(code))[0]])
            name = CYCLE_CHECKS[first - 1]
            value = np.ravel(np.broadcast_to(np.asarray(getattr(self, name), float), code.shape))[
                np.flatnonzero(np.ravel(code) == first)[0]
            ]
            raise ParameterError(name, *_CYCLE_TEXT[name](float(value)))


#: The parameters :func:`cycle_violation` checks, in order (its codes 1, 2, 3).
CYCLE_CHECKS = ("ambient_pressure", "polytropic_exponent", "heat_per_cycle")
_CYCLE_TEXT = {
    "ambient_pressure": lambda v: (f"{v / 1e5:.4g} bar", "ambient_pressure > 0"),
    "polytropic_exponent": lambda v: (
        f"{v:g}",
        "polytropic_exponent > 1 (it is also the ratio of specific heats of the "
        "constant-volume heat addition, Delta p = (k - 1) Q / V_min)",
    ),
    "heat_per_cycle": lambda v: (f"{v:g} J", "heat_per_cycle >= 0 J"),
}


def cycle_violation(ambient_pressure, polytropic_exponent, heat_per_cycle):
    """Admissibility of ideal cycles, broadcast over arrays of them.

    Returns
    -------
    ndarray of int8
        0 where admissible, else ``1 + i`` for the first violated parameter
        ``CYCLE_CHECKS[i]``: ``p_a > 0``, ``k > 1``, ``Q >= 0``, each finite.
    """
    pa, k, q = (np.asarray(v, dtype=float) for v in (ambient_pressure, polytropic_exponent,
                                                       heat_per_cycle))  # fmt: skip
    bad = (
        ~(np.isfinite(pa) & (pa > 0.0)),
        ~(np.isfinite(k) & (k > 1.0)),
        ~(np.isfinite(q) & (q >= 0.0)),
    )
    code = np.zeros(np.broadcast(pa, k, q).shape, dtype=np.int8)
    for i, b in enumerate(bad, start=1):
        code = np.where((code == 0) & b, np.int8(i), code)
    return code


def stroke_from_count(count):
    """Stroke index from a stroke counter: ``floor(count) mod 4``.

    ``count`` counts strokes since the start of an intake stroke (0 at the start
    of intake, 1 at the start of compression, ...). A counter within ``1e-11`` (relative) of
    an integer is taken as that integer, so at a volume extreme the stroke that
    starts there is returned, whatever the round-off.

    Parameters
    ----------
    count : array_like
        Stroke counter [-].

    Returns
    -------
    ndarray of int
        :data:`INTAKE`, :data:`COMPRESSION`, :data:`POWER` or :data:`EXHAUST`.
    """
    count = np.asarray(count, dtype=float)
    near = np.round(count)
    snapped = np.where(np.abs(count - near) <= 1e-11 * np.maximum(1.0, np.abs(count)), near, count)
    return np.mod(np.floor(snapped), 4).astype(int)


def compression_end_pressure(cycle: IdealCycle, v_max, v_min):
    """Pressure at the end of compression, before the heat, ``p_a (V_max/V_min)^k`` [Pa]."""
    r = np.asarray(v_max, dtype=float) / np.asarray(v_min, dtype=float)
    return cycle.ambient_pressure * r**cycle.polytropic_exponent


def peak_pressure(cycle: IdealCycle, v_max, v_min):
    """Pressure after the constant-volume heat addition, ``p_a r^k + (k-1) Q / V_min`` [Pa]."""
    k = cycle.polytropic_exponent
    return compression_end_pressure(cycle, v_max, v_min) + (k - 1.0) * cycle.heat_per_cycle / (
        np.asarray(v_min, dtype=float)
    )


def expansion_end_pressure(cycle: IdealCycle, v_max, v_min):
    """Pressure at the end of the power stroke, before blow-down, ``p_3 r^-k`` [Pa]."""
    r = np.asarray(v_max, dtype=float) / np.asarray(v_min, dtype=float)
    return peak_pressure(cycle, v_max, v_min) * r ** (-cycle.polytropic_exponent)


def cycle_pressure(cycle: IdealCycle, stroke, volume, v_max, v_min):
    """Chamber pressure from its stroke and volume [Pa].

    Parameters
    ----------
    cycle : IdealCycle
    stroke : array_like of int
        Stroke index (:func:`stroke_from_count`).
    volume : array_like
        Chamber volume V [m^3].
    v_max, v_min : array_like
        The chamber's largest and smallest volume [m^3] (broadcast with ``volume``).

    Returns
    -------
    ndarray
        ``p_a`` on intake and exhaust, ``p_a (V_max/V)^k`` on compression,
        ``p_3 (V_min/V)^k`` on the power stroke.
    """
    stroke = np.asarray(stroke)
    v = np.asarray(volume, dtype=float)
    v_max, v_min = np.asarray(v_max, dtype=float), np.asarray(v_min, dtype=float)
    k, pa = cycle.polytropic_exponent, cycle.ambient_pressure
    comp = pa * (v_max / v) ** k
    power = peak_pressure(cycle, v_max, v_min) * (v_min / v) ** k
    out = np.where(stroke == COMPRESSION, comp, np.where(stroke == POWER, power, pa))
    return np.broadcast_to(out, np.broadcast_shapes(stroke.shape, v.shape, out.shape)).copy()


def stroke_works(cycle: IdealCycle, v_max, v_min):
    """Work the gas does on the pistons during each stroke, closed forms [J].

    ``W_intake = p_a (V_max - V_min)``,
    ``W_compression = -p_a V_max (r^(k-1) - 1) / (k - 1)``,
    ``W_power = p_3 V_min (1 - r^(1-k)) / (k - 1)``,
    ``W_exhaust = -p_a (V_max - V_min)``.

    Returns
    -------
    ndarray, shape (4, ...)
        Indexed by stroke (:data:`INTAKE` ...).
    """
    v_max, v_min = np.broadcast_arrays(
        np.asarray(v_max, dtype=float), np.asarray(v_min, dtype=float)
    )
    k, pa = cycle.polytropic_exponent, cycle.ambient_pressure
    r = v_max / v_min
    swept = v_max - v_min
    comp = -pa * v_max * (r ** (k - 1.0) - 1.0) / (k - 1.0)
    power = peak_pressure(cycle, v_max, v_min) * v_min * (1.0 - r ** (1.0 - k)) / (k - 1.0)
    return np.stack([pa * swept, comp, power, -pa * swept])


def indicated_work(cycle: IdealCycle, v_max, v_min):
    """Indicated work of one four-stroke cycle, ``Q (1 - r^(1-k))`` [J] (the strokes' sum)."""
    r = np.asarray(v_max, dtype=float) / np.asarray(v_min, dtype=float)
    return cycle.heat_per_cycle * otto_efficiency(r, cycle.polytropic_exponent)


def otto_efficiency(ratio, exponent):
    """Otto efficiency ``1 - r^(1-k)`` of a compression ratio r and exponent k [-]."""
    return 1.0 - np.asarray(ratio, dtype=float) ** (1.0 - np.asarray(exponent, dtype=float))


def mean_effective_pressure(work, swept_volume):
    """Mean effective pressure, work per cycle over swept volume [Pa]."""
    return np.asarray(work, dtype=float) / np.asarray(swept_volume, dtype=float)
