"""Opposed-piston reactor: enclosed volume, pressure and forces from the pistons' motion.

Two pistons in one tube of bore ``b`` face each other; a drive moves them with
travels ``z`` (left) and ``z'`` (right) from their balanced positions, positive
towards the reactor centre (a :class:`~rotorkin.core.motion.Motion` of the two
pistons, the travels and their derivatives over the shaft angle ``beta``). The
drive this machine was built for (Zhu Ruilin, Zhu Guolin, Engineering Sciences
(China) 14(10), 2012) is a pair of discs on one shaft; the paper stops at the
gap change ``Delta = z + z'`` (its eq. 5), states that ``Delta <= 0``, "the
inner faces move apart, the pressure can only drop", and gives no bore and no
fluid. The volume, pressure, force and torque models below are derived here
and need only the travels.

One chamber: the tube between the inner faces of the two pistons. The distance
between the faces is ``L - (z + z') = L - Delta`` with ``L``
(``device_length``) the distance in the balanced position (``Delta = 0``), and

    V(beta) = A (L - Delta(beta)),   A = pi b^2 / 4,   V0 = A L

With ``Delta <= 0`` (``gap_change_min <= Delta <= 0``) the enclosed volume only
grows from ``V0`` (largest where ``Delta = gap_change_min``), so the pressure
only drops. ``dV/dz = dV/dz' = -A``; travels with ``z + z' = 0`` keep ``V = V0``.

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

Forces: the absolute chamber pressure ``p`` acts on each inner face, the back
pressure ``p_b`` (``back_pressure``, default 0: vacuum behind the pistons, the
model of the published numbers) on each outer face, so the net force on a piston
is ``(p - p_b) A`` and the shaft torque ``sum_i (p - p_b) dV/dq_i dq_i/dbeta =
(p - p_b) dV/dbeta``: the back pressure adds ``-p_b dV/dbeta`` to the vacuum
torque, zero over a turn (:func:`net_pressure`).

Every parameter may be a float or an array; arrays broadcast against each other
and against the angles of the motion (parameters of shape ``(n, 1)`` against
angles ``(m,)``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.core.angles import fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.core.motion import Motion

__all__ = [
    "FLUIDS",
    "OpposedPiston",
    "invalid_parameter",
    "piston_area",
    "enclosed_volume",
    "volume_derivatives_dq",
    "pressure_from_volume",
    "pressure",
    "net_pressure",
    "volume_extremes",
]

#: Admissible working fluids.
FLUIDS = ("gas", "liquid")

#: Admissible range of each field, for the error message.
_ADMISSIBLE = {
    "device_length": "device_length > 0 mm",
    "bore": "bore > 0 mm",
    "fluid": "one of " + ", ".join(map(repr, FLUIDS)),
    "initial_pressure": "initial_pressure > 0 bar (absolute)",
    "polytropic_exponent": "polytropic_exponent > 0 (1 isothermal, 1.4 adiabatic air)",
    "bulk_modulus": "bulk_modulus > 0 GPa",
    "gap_change_min": "gap_change_min <= 0 mm",
    "back_pressure": "back_pressure >= 0 bar (absolute)",
}


def _shown(name: str, value) -> str:
    if name == "fluid":
        return repr(str(value))
    v = float(value)
    if name in ("initial_pressure", "back_pressure"):
        return f"{v / 1e5:.4g} bar"
    if name == "bulk_modulus":
        return f"{v / 1e9:.4g} GPa"
    if name == "polytropic_exponent":
        return f"{v:g}"
    return fmt_mm(v)


def invalid_parameter(
    device_length, bore, fluid, initial_pressure, polytropic_exponent, bulk_modulus,
    gap_change_min, piston_stroke=0.0, back_pressure=0.0,
):  # fmt: skip
    """The first violated parameter of each design, ``""`` where all are admissible.

    Checked in the order of :class:`OpposedPiston`'s fields: ``device_length``,
    ``bore``, ``initial_pressure``, ``polytropic_exponent``, ``bulk_modulus``
    finite and ``> 0``; ``fluid`` one of :data:`FLUIDS`; ``gap_change_min``
    finite and ``<= 0``; ``device_length >= piston_stroke`` [m] (each piston
    travels up to half its stroke inwards: a shorter reactor lets it reach the
    middle, where the other piston stands). Broadcasts.

    Returns
    -------
    ndarray of str
        A field name of :class:`OpposedPiston` per design, or ``""``.
    """

    def positive(x):
        x = np.asarray(x, dtype=float)
        with np.errstate(invalid="ignore"):
            return ~(np.isfinite(x) & (x > 0.0))

    dmin = np.asarray(gap_change_min, dtype=float)
    pb = np.asarray(back_pressure, dtype=float)
    with np.errstate(invalid="ignore"):
        checks = (
            (
                "device_length",
                positive(device_length)
                | (np.asarray(device_length, dtype=float) < np.asarray(piston_stroke, dtype=float)),
            ),
            ("bore", positive(bore)),
            ("fluid", ~np.isin(np.asarray(fluid), FLUIDS)),
            ("initial_pressure", positive(initial_pressure)),
            ("polytropic_exponent", positive(polytropic_exponent)),
            ("bulk_modulus", positive(bulk_modulus)),
            ("gap_change_min", ~(np.isfinite(dmin) & (dmin <= 0.0))),
            ("back_pressure", ~(np.isfinite(pb) & (pb >= 0.0))),
        )
    shape = np.broadcast_shapes(*(bad.shape for _, bad in checks))
    out = np.full(shape, "", dtype=f"<U{max(len(n) for n, _ in checks)}")
    for name, bad in reversed(checks):
        out[np.broadcast_to(bad, shape)] = name
    return out


@dataclass(frozen=True)
class OpposedPiston:
    """Geometry and fluid of the opposed-piston reactor (SI); floats or broadcasting arrays.

    Parameters
    ----------
    device_length : float, optional
        ``L``, distance between the inner faces in the balanced position
        (``z = z' = 0``) [m], ``L > 0`` (default 1000 mm, the paper's).
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
    gap_change_min : float, optional
        Smallest (most negative) gap change ``Delta = z + z'`` of the drive over
        a period [m], ``<= 0`` (default 0: travels that keep the gap). Only
        :func:`volume_extremes` uses it.
    piston_stroke : float, optional
        Stroke of each piston [m] (``2 e``), ``device_length >= piston_stroke``
        (default 0: no bound).
    back_pressure : float, optional
        ``p_b``, absolute pressure on the outer faces of the pistons [Pa], ``>= 0``
        (default 0: vacuum, the published model; 1 bar for pistons open to the air).

    Raises
    ------
    ParameterError
        Naming the first violated field (:func:`invalid_parameter`).
    """

    device_length: float = 1.0
    bore: float = 0.05
    fluid: str = "gas"
    initial_pressure: float = 1.0e5
    polytropic_exponent: float = 1.0
    bulk_modulus: float = 1.5e9
    gap_change_min: float = 0.0
    piston_stroke: float = 0.0
    back_pressure: float = 0.0

    def __post_init__(self):
        names = ("device_length", "bore", "fluid", "initial_pressure", "polytropic_exponent",
                 "bulk_modulus", "gap_change_min", "piston_stroke", "back_pressure")  # fmt: skip
        bad = invalid_parameter(*(getattr(self, n) for n in names))
        if not bad.any():
            return
        first = np.flatnonzero(np.ravel(bad) != "")[0]
        name = str(np.ravel(bad)[first])
        mask = bad == name
        value, m = np.broadcast_arrays(np.asarray(getattr(self, name)), mask)
        shown = value[m].flat[0] if value.ndim else value[()]
        admissible = _ADMISSIBLE[name]
        stroke = float(np.max(self.piston_stroke))
        if name == "device_length" and np.isfinite(shown) and shown > 0.0:
            admissible = (
                f"device_length >= {fmt_mm(stroke)}, the piston stroke 2 e (each piston moves "
                "up to e inwards: a shorter reactor lets it reach the other piston's place)"
            )
        raise ParameterError(name, _shown(name, shown), admissible)

    @property
    def area(self):
        """Piston area ``A = pi b^2/4`` [m^2]."""
        return np.asarray(piston_area(self.bore))[()]

    @property
    def volume_initial(self):
        """``V0 = A L``, the enclosed volume in the balanced position [m^3]."""
        return np.asarray(self.area * np.asarray(self.device_length, dtype=float))[()]


def piston_area(bore):
    """``A = pi b^2 / 4`` [m^2] of a bore ``b`` [m]."""
    return 0.25 * np.pi * np.asarray(bore, dtype=float) ** 2


def enclosed_volume(reactor: OpposedPiston, motion: Motion):
    """Enclosed volume ``V = A (L - (z + z'))`` and its derivatives with respect to beta.

    Parameters
    ----------
    reactor : OpposedPiston
    motion : Motion
        Travels ``q = (z, z')`` [m] of the two pistons, positive towards the
        reactor centre, and their derivatives over the shaft angle, shape (2, ...).

    Returns
    -------
    tuple of 4 ndarray, shape (1, ...)
        ``V`` [m^3] and ``dV/dbeta``, ``d2V/dbeta2``, ``d3V/dbeta3`` [m^3/rad^n],
        one chamber on the leading axis (``dV = -A d(z + z')``, exact).
    """
    A, L = reactor.area, np.asarray(reactor.device_length, dtype=float)
    d = [v[0] + v[1] for v in (motion.q, motion.dq, motion.d2q, motion.d3q)]
    return (A * (L - d[0]))[None], *((-A * v)[None] for v in d[1:])


def volume_derivatives_dq(reactor: OpposedPiston, motion: Motion):
    """``dV/dq_i`` for the pistons ``q = (z, z')``: ``-A`` each [m^2], shape (2, 1, ...)."""
    shape = np.broadcast_shapes(np.shape(motion.q)[1:], np.shape(reactor.area))
    return np.broadcast_to(-reactor.area, (2, 1, *shape)).copy()


def pressure_from_volume(reactor: OpposedPiston, volume):
    """Pressure of the enclosed fluid at the volume ``V`` [Pa] (module docstring).

    ``gas``: ``p0 (V0/V)^n``; ``liquid``: ``p0 - K ln(V/V0)``. Broadcasts.
    """
    v = np.asarray(volume, dtype=float)
    p0, v0 = np.asarray(reactor.initial_pressure, dtype=float), reactor.volume_initial
    gas = np.asarray(reactor.fluid) == "gas"
    n = np.asarray(reactor.polytropic_exponent, dtype=float)
    K = np.asarray(reactor.bulk_modulus, dtype=float)
    if gas.ndim == 0:
        return p0 * (v0 / v) ** n if gas else p0 - K * np.log(v / v0)
    with np.errstate(all="ignore"):
        return np.where(gas, p0 * (v0 / v) ** n, p0 - K * np.log(v / v0))


def pressure(reactor: OpposedPiston, motion: Motion):
    """Chamber pressure and ``dp/dbeta`` over the shaft angle, shape (1, ...).

    ``dp/dbeta = (dp/dV) dV/dbeta`` with ``dp/dV = -n p/V`` (gas) or ``-K/V``
    (liquid).

    Returns
    -------
    (p, dp) : tuple of ndarray, shape (1, ...)
        [Pa], [Pa/rad].
    """
    v, dv, _, _ = enclosed_volume(reactor, motion)
    p = pressure_from_volume(reactor, v)
    gas = np.asarray(reactor.fluid) == "gas"
    n = np.asarray(reactor.polytropic_exponent, dtype=float)
    K = np.asarray(reactor.bulk_modulus, dtype=float)
    slope = np.where(gas, -n * p / v, -K / v)
    return p, slope * dv


def net_pressure(reactor: OpposedPiston, pressure):
    """``p - p_b``: the pressure that loads the pistons, chamber less back pressure [Pa].

    Times ``dV/dq_i`` it gives the piston forces, times ``dV/dbeta`` the shaft torque
    (module docstring). Broadcasts.
    """
    return np.asarray(pressure, dtype=float) - np.asarray(reactor.back_pressure, dtype=float)


def volume_extremes(reactor: OpposedPiston):
    """Smallest and largest enclosed volume over a period [m^3] (closed form).

    ``V_min = A L`` where ``Delta = 0``; ``V_max = A (L - gap_change_min)``.
    """
    A, L = reactor.area, np.asarray(reactor.device_length, dtype=float)
    dmin = np.asarray(reactor.gap_change_min, dtype=float)
    return np.asarray(A * L)[()], np.asarray(A * (L - dmin))[()]
