"""Rotary-blade engine: two blade pairs on one axis, working chambers between the blades.

The machine of Zhuravlev, Donchenko, Sherstyukov (2012): a Stirling-type engine
with external heat supply whose two blade pairs turn about one axis at the angles
``phi_1`` and ``phi_2``. This module needs only their motion (a
:class:`rotorkin.core.motion.Motion` of the two pairs against the output-shaft
angle, from whichever drive produces it) and plain numbers; it knows no drive. The
paper gives no geometry of the working space; the model here is ours.

Geometry (not in the paper):

* The working space is an annulus between the hub (``inner_radius`` ``R_i``) and
  the casing (``outer_radius`` ``R_o``), ``axial_width`` ``w`` long.
* Each pair carries ``B = blades_per_pair`` radial blades, evenly spaced: pair 1
  at ``phi_1 + 2 pi m / B``, pair 2 at ``phi_2 + 2 pi m / B``, ``m = 0 .. B-1``;
  a blade is a sector of angular thickness ``t`` (``blade_thickness``) centred on
  its axis. The paper's engine has ``B = 2`` (4 blades, 4 chambers).
* Counter-clockwise from the blade of pair 2 at ``phi_2`` the ``2B`` chambers are
  numbered ``j = 0 .. 2B-1``: even chambers lie between ``phi_2 + 2 pi m/B`` and
  ``phi_1 + 2 pi m/B``, odd chambers between ``phi_1 + 2 pi m/B`` and
  ``phi_2 + 2 pi (m+1)/B``. With ``psi = phi_1 - phi_2`` their angles are

      even:  gamma_j = psi - t,          odd:  gamma_j = 2 pi / B - psi - t

  (for ``B = 2``: ``psi - t`` and ``pi - psi - t``, alternating), and both must
  stay positive over the whole motion (:func:`check_swing`).
* Volume of a sector chamber: ``V_j = gamma_j (R_o^2 - R_i^2) w / 2``, so with
  ``k = (R_o^2 - R_i^2) w / 2`` [m^3/rad] and the chamber sign ``s_j = +1`` (even),
  ``-1`` (odd): ``dV_j/dphi_1 = s_j k``, ``dV_j/dphi_2 = -s_j k`` and
  ``d^n V_j / d theta^n = s_j k (phi_1^(n) - phi_2^(n))``, exactly.

Pressure models:

* given member torques: a drive's own load model may give the torques ``(M_1, M_2)``
  on the pairs directly; :func:`rotorkin.analysis.torque.shaft_torque_from_members`
  turns them into the shaft torque.
* ``isothermal`` (ideal Stirling cycle, ours): each chamber holds a fixed gas mass
  ``m_j``; while it *expands* (``dV_j > 0``) the gas is at the hot temperature
  ``T_h``, while it is *compressed* (``dV_j < 0``) at the cold temperature
  ``T_c``; the change of temperature at the turning points is isochoric (an ideal
  regenerator). ``p_j = m_j R T / V_j`` with ``m_j R = p_charge V_max,j / T_c``:
  the charge pressure is the pressure at the chamber's largest volume, cold. No
  heater, regenerator or cooler, no gas exchange: an upper bound, kept for comparison.
* ``schmidt`` and ``adiabatic`` (an alpha-type Stirling engine, ours): the engine's
  chambers are the *expansion (hot) spaces*; an identical second blade set on the
  same drive, lagging by ``phase_angle`` of a chamber's volume cycle, gives the
  *compression (cold) spaces*; hot chamber ``j`` and cold chamber ``j`` are joined
  through a heater, a regenerator and a cooler (one Stirling circuit per chamber
  pair, :mod:`rotorkin.machines.rotary_blade_stirling`). Two chambers of one set
  cannot form a pair: their volumes are equal or complementary. Each circuit is solved by
  :mod:`rotorkin.analysis.stirling` (Urieli and Berchowitz 1984: Schmidt or ideal
  adiabatic analysis); the gas of a circuit fills it to ``charge_pressure`` at its
  largest total volume, all at the cooler's temperature.

All functions broadcast: member positions ``q`` have shape ``(2, ...)``, chamber
arrays shape ``(2B, ...)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.analysis.torque import member_torques
from rotorkin.core.angles import fmt_deg, fmt_mm
from rotorkin.core.errors import ParameterError

__all__ = [
    "IsothermalGas",
    "RotaryBlade",
    "chamber_angles",
    "chamber_figures",
    "chamber_offsets",
    "chamber_signs",
    "chamber_strokes",
    "chamber_volume_derivative",
    "chamber_volumes",
    "CHECKS",
    "GAS_CHECKS",
    "SWING_CHECKS",
    "blade_thickness_max",
    "check_swing",
    "class_volume_range",
    "displacement_per_rev",
    "gas_charge",
    "gas_member_torques",
    "gas_violation",
    "isothermal_cycle_work",
    "isothermal_pressure",
    "isothermal_stroke_work",
    "sector_constant",
    "volume_gradient",
    "swing_violation",
    "violation",
    "volume_range",
]

_TWO_PI = 2.0 * np.pi


#: Parameters of :class:`RotaryBlade` in the order :func:`violation` checks them.
CHECKS = (
    "blades_per_pair",
    "outer_radius",
    "inner_radius",
    "axial_width",
    "blade_thickness",
    "inertia_shaft",
    "inertia_blade_pair_1",
    "inertia_blade_pair_2",
)
#: Parameters of :class:`IsothermalGas` in the order :func:`gas_violation` checks them.
GAS_CHECKS = ("charge_pressure", "hot_temperature", "cold_temperature")
#: What :func:`swing_violation` reports, in order.
SWING_CHECKS = ("blade_thickness", "blades_per_pair")


def _first_violation(bad) -> np.ndarray:
    """Per element, ``i + 1`` of the first true mask in ``bad`` (0: none is true)."""
    bad = np.broadcast_arrays(*[np.asarray(b, dtype=bool) for b in bad])
    out = np.zeros(bad[0].shape, dtype=np.int16)
    for i, b in enumerate(bad):
        out[(out == 0) & b] = i + 1
    return out


def violation(blade_thickness, inner_radius, outer_radius, axial_width, blades_per_pair=2,
              inertia_shaft=0.0, inertia_blade_pair_1=0.01, inertia_blade_pair_2=0.01):  # fmt: skip
    """Which parameter of each design is out of its admissible range.

    Parameters
    ----------
    blade_thickness : array_like
        ``t`` [rad]; admissible ``0 <= t < pi / B``.
    inner_radius, outer_radius : array_like
        ``R_i``, ``R_o`` [m]; ``0 <= R_i < R_o``, ``R_o > 0``.
    axial_width : array_like
        ``w`` [m], > 0.
    blades_per_pair : array_like of int
        ``B >= 1``.
    inertia_shaft, inertia_blade_pair_1, inertia_blade_pair_2 : array_like
        [kg m^2], >= 0.

    Returns
    -------
    ndarray of int16
        Broadcast shape of the inputs: 0 where the design is admissible, else
        ``i + 1`` for the first violated parameter ``CHECKS[i]`` (in the order of
        :data:`CHECKS`).
    """
    with np.errstate(invalid="ignore"):
        B = np.asarray(blades_per_pair)
        Bf = np.where(B >= 1, B, 1).astype(float)
        ro, ri = np.asarray(outer_radius, dtype=float), np.asarray(inner_radius, dtype=float)
        w, t = np.asarray(axial_width, dtype=float), np.asarray(blade_thickness, dtype=float)
        bad = [
            ~((B >= 1) & (B == np.floor(B))),
            ~(np.isfinite(ro) & (ro > 0.0)),
            ~(np.isfinite(ri) & (ri >= 0.0) & (ri < ro)),
            ~(np.isfinite(w) & (w > 0.0)),
            ~(np.isfinite(t) & (t >= 0.0) & (t < np.pi / Bf)),
        ]
        for j in (inertia_shaft, inertia_blade_pair_1, inertia_blade_pair_2):
            j = np.asarray(j, dtype=float)
            bad.append(~(np.isfinite(j) & (j >= 0.0)))
    return _first_violation(bad)


def _value(x, where):
    """Element ``where`` (a flat index) of the broadcast parameter ``x``."""
    return np.broadcast_to(np.asarray(x), where[1]).flat[where[0]]


def _number(x):
    """A parameter as float (scalar) or float array (many designs)."""
    a = np.asarray(x, dtype=float)
    return float(a) if a.ndim == 0 else a


# --- parameters ---------------------------------------------------------------------------
@dataclass(frozen=True)
class RotaryBlade:
    """Geometry and inertias of the rotary-blade engine.

    A thin holder of the parameters, validated by :func:`violation`; each field
    may also be an array (many designs, broadcast together) for the functions
    that treat the chambers by kind (:func:`sector_constant`,
    :func:`blade_thickness_max`, :func:`class_volume_range`,
    :func:`displacement_per_rev`).

    Attributes
    ----------
    blade_thickness : float
        Angular thickness ``t`` of one blade [rad], ``0 <= t < pi / B``; the drive's
        swing of ``psi`` narrows it further (:func:`check_swing`).
    inner_radius : float
        Hub radius ``R_i`` of the working space [m], ``0 <= R_i < R_o``.
    outer_radius : float
        Casing radius ``R_o`` [m], > 0.
    axial_width : float
        Axial width ``w`` of the working space [m], > 0.
    blades_per_pair : int
        ``B`` blades on each pair, ``>= 1`` (the paper: 2).
    inertia_shaft : float
        Inertia of the output shaft with the cam carrier [kg m^2], >= 0.
    inertia_blade_pair_1, inertia_blade_pair_2 : float
        Inertias of the blade pairs with their hubs and arms [kg m^2], >= 0 (default
        0.01, as the config schema).
    """

    blade_thickness: float
    inner_radius: float
    outer_radius: float
    axial_width: float
    blades_per_pair: int = 2
    inertia_shaft: float = 0.01
    inertia_blade_pair_1: float = 0.005
    inertia_blade_pair_2: float = 0.005

    def __post_init__(self):
        B = self.blades_per_pair
        if isinstance(B, bool) or not np.issubdtype(np.asarray(B).dtype, np.integer):
            raise ParameterError("blades_per_pair", repr(B), "an integer >= 1")
        fields = {name: getattr(self, name) for name in CHECKS}
        code = violation(**fields)
        if np.any(code):
            k = int(np.flatnonzero(code)[0])
            name = CHECKS[code.flat[k] - 1]
            at = (k, code.shape)
            raise _machine_error(name, {n: _value(v, at) for n, v in fields.items()})
        B = np.asarray(B)
        object.__setattr__(self, "blades_per_pair", int(B) if B.ndim == 0 else B)
        for name in CHECKS[1:]:
            object.__setattr__(self, name, _number(getattr(self, name)))

    @property
    def chambers(self) -> int:
        """Number of working chambers, ``2B``."""
        return 2 * self.blades_per_pair

    @property
    def member_inertias(self) -> tuple[float, float]:
        """``(J_1, J_2)`` of the blade pairs [kg m^2]."""
        return (self.inertia_blade_pair_1, self.inertia_blade_pair_2)


@dataclass(frozen=True)
class IsothermalGas:
    """Loads of the isothermal (ideal Stirling) pressure model.

    A thin holder validated by :func:`gas_violation`; the fields may be arrays.

    Attributes
    ----------
    charge_pressure : float
        Pressure of each chamber at its largest volume, cold [Pa], > 0.
    hot_temperature : float
        Gas temperature while a chamber expands [K], > 0.
    cold_temperature : float
        Gas temperature while a chamber is compressed [K], > 0. ``T_h > T_c`` makes
        an engine; ``T_h < T_c`` gives negative work (the cycle run as a heat pump).
    """

    charge_pressure: float
    hot_temperature: float
    cold_temperature: float

    def __post_init__(self):
        fields = {name: getattr(self, name) for name in GAS_CHECKS}
        code = gas_violation(**fields)
        if np.any(code):
            k = int(np.flatnonzero(code)[0])
            name = GAS_CHECKS[code.flat[k] - 1]
            v = float(_value(fields[name], (k, code.shape)))
            if name == "charge_pressure":
                raise ParameterError(name, f"{v / 1e5:g} bar", "charge_pressure > 0 bar")
            raise ParameterError(name, f"{v:g} K", f"{name} > 0 K")
        for name in GAS_CHECKS:
            object.__setattr__(self, name, _number(getattr(self, name)))


def gas_violation(charge_pressure, hot_temperature, cold_temperature) -> np.ndarray:
    """Which parameter of each isothermal-gas load is out of range (all must be finite, > 0).

    Returns
    -------
    ndarray of int16
        Broadcast shape: 0 where admissible, else ``i + 1`` for the first violated
        parameter ``GAS_CHECKS[i]``.
    """
    with np.errstate(invalid="ignore"):
        values = [np.asarray(x, dtype=float) for x in (charge_pressure, hot_temperature,
                                                         cold_temperature)]  # fmt: skip
        return _first_violation([~(np.isfinite(x) & (x > 0.0)) for x in values])


def _machine_error(name, v) -> ParameterError:
    """The :class:`ParameterError` of one design whose ``name`` :func:`violation` flags."""
    B = int(v["blades_per_pair"]) if float(v["blades_per_pair"]).is_integer() else None
    if name == "blades_per_pair":
        return ParameterError(name, repr(v[name]), "an integer >= 1")
    if name == "outer_radius":
        return ParameterError(name, fmt_mm(v[name]), "outer_radius > 0 mm")
    if name == "inner_radius":
        return ParameterError(
            name,
            fmt_mm(v[name]),
            f"0 mm <= inner_radius < outer_radius = {fmt_mm(v['outer_radius'])}",
        )
    if name == "axial_width":
        return ParameterError(name, fmt_mm(v[name]), "axial_width > 0 mm")
    if name == "blade_thickness":
        return ParameterError(
            name,
            fmt_deg(v[name]),
            f"0 deg <= blade_thickness < {fmt_deg(np.pi / B)} "
            f"(the {2 * B} blades must fit around the rotor)",
        )
    return ParameterError(name, f"{float(v[name]):g} kg*m^2", f"{name} >= 0 kg*m^2")


def blade_thickness_max(blades_per_pair, psi_lo, psi_hi):
    """Thickest blade that fits a swing of ``psi``: ``min(psi_lo, 2 pi/B - psi_hi)`` [rad].

    The chamber angles ``psi - t`` and ``2 pi/B - psi - t`` stay > 0 for
    ``psi_lo <= psi <= psi_hi`` exactly when ``t`` is below this. All arguments
    broadcast.
    """
    B = np.asarray(blades_per_pair, dtype=float)
    return np.minimum(psi_lo, _TWO_PI / B - np.asarray(psi_hi, dtype=float))


def swing_violation(blades_per_pair, blade_thickness, psi_lo, psi_hi) -> np.ndarray:
    """Whether the blades collide in a swing of ``psi``, and which parameter to change.

    Returns
    -------
    ndarray of int16
        0 where ``t < blade_thickness_max``; else 1 (``SWING_CHECKS[0]``,
        ``blade_thickness``) where thinner blades would fit, 2 (``blades_per_pair``)
        where none would. All arguments broadcast.
    """
    t_max = blade_thickness_max(blades_per_pair, psi_lo, psi_hi)
    with np.errstate(invalid="ignore"):
        bad = ~(np.asarray(blade_thickness, dtype=float) < t_max)
    return _first_violation([bad & (t_max > 0.0), bad])


def check_swing(machine: RotaryBlade, psi_lo: float, psi_hi: float) -> None:
    """Refuse blades that collide somewhere in the drive's swing of ``psi``.

    The chamber angles ``psi - t`` and ``2 pi/B - psi - t`` must stay > 0 for
    ``psi_lo <= psi <= psi_hi``, i.e. ``t < t_max = min(psi_lo, 2 pi/B - psi_hi)``.
    For a swing symmetric about pi/2 (``psi_hi = pi - psi_lo``) and ``B = 2`` that
    is ``t < psi_lo``.

    Raises
    ------
    ParameterError
        Named ``blade_thickness`` with ``t_max`` when thinner blades would fit, else
        ``blades_per_pair`` with the largest ``B`` that fits.
    """
    B, t = machine.blades_per_pair, machine.blade_thickness
    code = int(swing_violation(B, t, psi_lo, psi_hi))
    if code == 0:
        return
    t_max = float(blade_thickness_max(B, psi_lo, psi_hi))
    swing = f"psi from {fmt_deg(psi_lo)} to {fmt_deg(psi_hi)}"
    if SWING_CHECKS[code - 1] == "blade_thickness":
        raise ParameterError(
            "blade_thickness",
            fmt_deg(t),
            f"0 deg <= blade_thickness < {fmt_deg(t_max)}: the chamber angles psi - "
            f"blade_thickness and {fmt_deg(_TWO_PI / B)} - psi - blade_thickness must stay "
            f"> 0 for {swing} (thicker blades of the two pairs collide)",
        )
    b_max = int(np.ceil(_TWO_PI / (float(psi_hi) + t))) - 1
    raise ParameterError(
        "blades_per_pair",
        str(B),
        f"1 <= blades_per_pair <= {b_max}: 360 deg / blades_per_pair - psi - blade_thickness "
        f"must stay > 0 for {swing} (blade_thickness = {fmt_deg(t)})",
    )


# --- chambers -----------------------------------------------------------------------------
def sector_constant(machine: RotaryBlade) -> float:
    """``k = (R_o^2 - R_i^2) w / 2``: volume of the annulus per radian [m^3/rad]."""
    return 0.5 * (machine.outer_radius**2 - machine.inner_radius**2) * machine.axial_width


def chamber_signs(machine: RotaryBlade) -> np.ndarray:
    """``s_j = +1, -1, +1, ...``: how chamber ``j``'s angle follows ``psi``, shape ``(2B,)``."""
    return np.tile([1.0, -1.0], machine.blades_per_pair)


def chamber_offsets(machine: RotaryBlade) -> np.ndarray:
    """Constant part of the chamber angles: ``-t`` (even), ``2 pi/B - t`` (odd) [rad].

    Shape ``(2B,)``, or ``(2B, ...)`` when ``t`` is an array of designs (one ``B``).
    """
    B, t = machine.blades_per_pair, np.asarray(machine.blade_thickness, dtype=float)
    return np.concatenate([np.stack(np.broadcast_arrays(-t, _TWO_PI / B - t))] * int(B))


def _expand(vec, ndim):
    """``vec`` (2B, ...) with unit axes appended to broadcast against ``ndim``-d angles."""
    vec = np.asarray(vec)
    return vec.reshape(vec.shape + (1,) * (ndim - (vec.ndim - 1)))


def chamber_angles(machine: RotaryBlade, q) -> np.ndarray:
    """Angular widths ``gamma_j`` of the chambers [rad].

    Parameters
    ----------
    q : array_like, shape (2, ...)
        ``(phi_1, phi_2)`` [rad].

    Returns
    -------
    ndarray, shape (2B, ...)
        ``psi - t`` (even ``j``), ``2 pi/B - psi - t`` (odd ``j``), ``psi = phi_1 - phi_2``.
    """
    q = np.asarray(q, dtype=float)
    psi = q[0] - q[1]
    return _expand(chamber_signs(machine), psi.ndim) * psi + _expand(
        chamber_offsets(machine), psi.ndim
    )


def chamber_volumes(machine: RotaryBlade, q) -> np.ndarray:
    """Chamber volumes ``V_j = k gamma_j`` [m^3], shape ``(2B, ...)``; ``q`` shape ``(2, ...)``."""
    return sector_constant(machine) * chamber_angles(machine, q)


def chamber_volume_derivative(machine: RotaryBlade, dq) -> np.ndarray:
    """Exact ``d^n V_j / d theta^n = s_j k (phi_1^(n) - phi_2^(n))`` for any order ``n >= 1``.

    Parameters
    ----------
    dq : array_like, shape (2, ...)
        The n-th derivatives of ``(phi_1, phi_2)`` with respect to the input angle
        (``Motion.dq``, ``d2q`` or ``d3q``) [rad/rad^n].

    Returns
    -------
    ndarray, shape (2B, ...)
        [m^3/rad^n].
    """
    dq = np.asarray(dq, dtype=float)
    dpsi = dq[0] - dq[1]
    return sector_constant(machine) * _expand(chamber_signs(machine), dpsi.ndim) * dpsi


def volume_gradient(machine: RotaryBlade, ndim: int = 0) -> np.ndarray:
    """``dV_j/dq_i``: ``+s_j k`` for pair 1, ``-s_j k`` for pair 2 [m^3/rad].

    Parameters
    ----------
    ndim : int
        Trailing unit axes to append, to broadcast against pressures of shape
        ``(2B, *shape)`` with ``len(shape) = ndim``.

    Returns
    -------
    ndarray, shape (2, 2B) + (1,) * ndim
        For a machine of column fields ``(m, 1)`` (many designs) the columns' shape
        takes the first of the trailing axes: ``(2, 2B, m, 1) + (1,) * (ndim - 2)``.
    """
    k = np.asarray(sector_constant(machine), dtype=float)
    signs = chamber_signs(machine)
    g = signs.reshape(signs.shape + (1,) * k.ndim) * k
    return np.stack([g, -g]).reshape((2, signs.size) + k.shape + (1,) * (ndim - k.ndim))


def class_volume_range(machine: RotaryBlade, psi_lo, psi_hi):
    """Smallest and largest volume of the even and the odd chambers over a swing of ``psi``.

    ``V = k gamma`` with the chamber angles ``psi - t`` (even, smallest at
    ``psi_lo``) and ``2 pi/B - psi - t`` (odd, smallest at ``psi_hi``) [m^3]. The
    machine's fields and the swing may be arrays (many designs), broadcast together.

    Returns
    -------
    (v_min, v_max) : ndarray, shape (2, ...)
        Even chambers first, then odd.
    """
    k, t = sector_constant(machine), machine.blade_thickness
    odd = _TWO_PI / np.asarray(machine.blades_per_pair, dtype=float)
    v_lo = np.stack(np.broadcast_arrays(k * (psi_lo - t), k * (-psi_lo + (odd - t))))
    v_hi = np.stack(np.broadcast_arrays(k * (psi_hi - t), k * (-psi_hi + (odd - t))))
    return np.minimum(v_lo, v_hi), np.maximum(v_lo, v_hi)


def chamber_figures(machine: RotaryBlade, psi_lo, psi_hi) -> dict:
    """Volume figures of the working chambers over a swing of ``psi``, over all chambers.

    From :func:`class_volume_range`; arrays of designs broadcast.

    Returns
    -------
    dict of ndarray
        ``volume_max``, ``volume_min`` [m^3] (largest and smallest volume of any
        chamber), ``swept_volume`` [m^3] (largest ``V_max - V_min`` of a chamber),
        ``compression_ratio`` (smallest ``V_max / V_min`` of a chamber).
    """
    v_min, v_max = class_volume_range(machine, psi_lo, psi_hi)
    return {
        "volume_max": np.max(v_max, axis=0),
        "volume_min": np.min(v_min, axis=0),
        "swept_volume": np.max(v_max - v_min, axis=0),
        "compression_ratio": np.min(v_max / v_min, axis=0),
    }


def volume_range(machine: RotaryBlade, psi_lo: float, psi_hi: float):
    """Smallest and largest volume of each chamber over a swing of ``psi`` [m^3].

    Even chambers are smallest at ``psi_lo``, odd ones at ``psi_hi``
    (:func:`class_volume_range`, repeated around the rotor).

    Returns
    -------
    (v_min, v_max) : ndarray, shape (2B,)
    """
    B = machine.blades_per_pair
    return tuple(np.tile(v, B) for v in class_volume_range(machine, psi_lo, psi_hi))


def displacement_per_rev(machine: RotaryBlade, psi_travel_per_rev) -> np.ndarray:
    """Swept volume per output-shaft revolution [m^3].

    The volume every chamber takes in while it expands, summed over the chambers:
    ``sum_j integral max(dV_j, 0) = B k TV``, where ``TV`` is the total travel
    ``integral |d psi|`` of ``psi`` per revolution. For a ``psi`` that swings
    monotonically between ``psi_min`` and ``psi_max`` twice per revolution,
    ``TV = 4 (psi_max - psi_min)`` and this is ``2B x 2 x (V_max - V_min)``.

    Parameters
    ----------
    psi_travel_per_rev : array_like
        ``TV`` [rad].
    """
    return machine.blades_per_pair * sector_constant(machine) * np.asarray(psi_travel_per_rev)


def chamber_strokes(machine: RotaryBlade, psi_stroke) -> np.ndarray:
    """Stroke of each chamber: +1 expanding, -1 compressed, 0 at rest; shape ``(2B, ...)``.

    ``psi_stroke`` is +1 while ``psi`` rises and -1 while it falls (the sign of
    ``d psi / d theta``, from the drive); even chambers expand with ``psi``, odd ones
    against it.
    """
    s = np.asarray(psi_stroke, dtype=float)
    return _expand(chamber_signs(machine), s.ndim) * s


# --- pressures and torques ----------------------------------------------------------------
def gas_charge(gas: IsothermalGas, volume_max) -> np.ndarray:
    """``m_j R = p_charge V_max,j / T_c`` [J/K]: the gas of each chamber (isothermal model).

    The gas constant drops out of every result; only the product ``m R`` matters.
    """
    return gas.charge_pressure * np.asarray(volume_max, dtype=float) / gas.cold_temperature


def isothermal_pressure(gas: IsothermalGas, charge, volume, stroke) -> np.ndarray:
    """Chamber pressures of the isothermal model, ``p_j = m_j R T / V_j`` [Pa].

    ``T = T_h`` where the chamber expands (``stroke > 0``, ``dV_j > 0``), else
    ``T_c`` (compression, and at rest).

    Parameters
    ----------
    charge : array_like, shape (2B,)
        ``m_j R`` from :func:`gas_charge` [J/K].
    volume : array_like, shape (2B, ...)
        [m^3].
    stroke : array_like, shape (2B, ...)
        :func:`chamber_strokes`.
    """
    volume = np.asarray(volume, dtype=float)
    T = np.where(np.asarray(stroke) > 0.0, gas.hot_temperature, gas.cold_temperature)
    return _expand(charge, volume.ndim - 1) * T / volume


def isothermal_stroke_work(charge, temperature, volume_start, volume_end) -> np.ndarray:
    """Work of the gas over an isothermal stroke, ``m R T ln(V_end / V_start)`` [J].

    Positive in expansion: the gas does work on the blades.
    """
    return (
        np.asarray(charge)
        * np.asarray(temperature)
        * np.log(np.asarray(volume_end) / np.asarray(volume_start))
    )


def gas_member_torques(machine: RotaryBlade, pressure) -> np.ndarray:
    """Torques of the chamber pressures on the blade pairs, ``M_i = sum_j p_j dV_j/dq_i`` [N m].

    ``M_1 = k (sum_even p_j - sum_odd p_j)`` and ``M_2 = -M_1``; positive in the
    sense of increasing ``phi_i``.

    Parameters
    ----------
    pressure : array_like, shape (2B, ...)
        Absolute pressures [Pa] (a uniform pressure gives no torque).

    Returns
    -------
    ndarray, shape (2, ...)
    """
    pressure = np.asarray(pressure, dtype=float)
    return member_torques(pressure, volume_gradient(machine, pressure.ndim - 1))


def isothermal_cycle_work(gas: IsothermalGas, charge, volume_at_turns) -> np.ndarray:
    """Work of each chamber over a chain of monotone strokes, isothermal model [J].

    ``W_j = sum_strokes m_j R T ln(V_end / V_start)`` with ``T = T_h`` on the strokes
    where the volume grows and ``T_c`` where it shrinks; the isochoric steps at the
    turning points do no work. For one compression from ``V_max`` to ``V_min`` and
    one expansion back this is ``m_j R (T_h - T_c) ln(V_max / V_min)``.

    Parameters
    ----------
    charge : array_like, shape (2B,)
        ``m_j R`` [J/K].
    volume_at_turns : array_like, shape (2B, n)
        Volumes at the turning points (and the ends) of the motion, in order [m^3].

    Returns
    -------
    ndarray, shape (2B,)
    """
    v = np.asarray(volume_at_turns, dtype=float)
    va, vb = v[:, :-1], v[:, 1:]
    T = np.where(vb > va, gas.hot_temperature, gas.cold_temperature)
    return np.sum(isothermal_stroke_work(np.asarray(charge)[:, None], T, va, vb), axis=1)
