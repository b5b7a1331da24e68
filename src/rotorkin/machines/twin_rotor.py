"""Twin-rotor vane-piston engine: two coaxial rotors in one annular cylinder.

Each rotor carries N vane pistons; the pistons of the two rotors alternate
round the annulus and the 2N sectors between them are the chambers. This
module computes everything that follows from the rotors' motion and plain
numbers (piston width, pistons per rotor, chamber angle extremes, volume
cycles per shaft turn): volumes, four-stroke timing, pressures and gas
torques. The drive that moves the rotors supplies their
:class:`rotorkin.core.motion.Motion` ``q = (Phi_1, Phi_2)`` over the shaft
angle, the piston width and the extremes of the chamber angles, and chamber 1's
stroke counter. The machine follows Chen Hu et al. (2015, eq. 18-23); the
cylinder section, the clearance volume, the four-stroke timing, pressures,
torques and inertias are ours.

Geometry and conventions:

* Each rotor has 2 rails pi apart; rotor 1's pistons are centred at
  ``Phi_1 + gamma + 2 pi m/N``, rotor 2's at ``Phi_2 - gamma + 2 pi m/N``,
  ``m = 0 .. N-1``, ``gamma = pi/4 - pi/(2N)`` (:func:`piston_offset`); each
  piston is ``beta`` wide [rad].
* Chambers ``j = 0 .. 2N-1`` in the sense of increasing ``Phi``, starting at
  rotor 1's piston ``m = 0``: chamber ``2m`` (kind A) lies between rotor-1 piston m
  and rotor-2 piston m, chamber ``2m+1`` (kind B) between rotor-2 piston m and
  rotor-1 piston m+1. People count from 1: chamber 1 is ``j = 0``.
  ``delta_A = (Phi_2 - Phi_1) - 2 gamma - beta``,
  ``delta_B = 2 pi/N + 2 gamma - beta - (Phi_2 - Phi_1)``: all chambers of one kind
  have the same volume at every instant.
* Volume ``V_j = K delta_j + V_c`` with ``K = (R_o^2 - R_i^2) w / 2`` (rectangular
  annulus) or ``K = R_m pi d^2/4`` (circular torus, Pappus) [m^3/rad] and the
  clearance volume ``V_c`` of each chamber (a recess in the housing, say).
  ``dV_j/dPhi_1 = -s_j K``, ``dV_j/dPhi_2 = +s_j K``, ``s_j = +1`` (A), ``-1`` (B).
* Four-stroke timing: the drive gives the stroke counter ``c_0`` of chamber 1
  (strokes since the start of its intake; its integers fall on the volume
  extremes of kind A). Chamber ``j = 2m + b`` counts ``c_j = c_0 - b + 2m``
  (mod 4): neighbours of the two kinds are one stroke apart, and in each kind
  the chambers alternate by two strokes, so of the N chambers of the
  expanding kind N/2 are on the power stroke at every instant.
* Sign: a torque on the shaft is positive when it drives the shaft (engine
  output positive), see :mod:`rotorkin.analysis.torque`.

Every function broadcasts: theta of shape ``(...)`` gives chamber arrays of shape
``(2N, ...)`` and member arrays of shape ``(2, ...)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.analysis import engine_cycle as ec
from rotorkin.analysis.torque import member_torques, shaft_torque_from_members
from rotorkin.core.angles import fmt_mm
from rotorkin.core.batch import number, refuse_first
from rotorkin.core.errors import ParameterError
from rotorkin.core.motion import Motion

__all__ = [
    "TwinRotor",
    "Chambers",
    "EngineState",
    "CHECKED",
    "SECTIONS",
    "check_pistons",
    "first_violation",
    "violation",
    "section_volume_per_radian",
    "piston_offset",
    "chamber_count",
    "chamber_volume",
    "displacement",
    "volume_per_radian",
    "annulus_volume",
    "chamber_kinds",
    "volume_gradient",
    "chamber_volumes_from_rotors",
    "chambers",
    "volume_limits",
    "swept_volume",
    "compression_ratio_geometric",
    "displacement_per_rev",
    "swept_volume_per_rev",
    "stroke_counter",
    "strokes",
    "chamber_pressures",
    "engine_state",
    "indicated_work_per_rev",
]


def check_pistons(pistons):
    """ParameterError named ``pistons_per_rotor`` unless N is an even integer >= 2."""
    ok = isinstance(pistons, (int, np.integer)) and not isinstance(pistons, bool)
    if not (ok and pistons >= 2 and pistons % 2 == 0):
        raise ParameterError(
            "pistons_per_rotor",
            repr(pistons),
            "an even integer >= 2 (each rotor has 2 rails 180 deg apart, so its pistons must "
            "repeat every 180 deg for eq. 18-19 and the period of one shaft turn)",
        )


def piston_offset(pistons=4):
    """Angle gamma between a piston's centre line and the nearest rail [rad] (eq. 18-19).

    With 2 rails per rotor (pi apart) and N pistons (2 pi/N apart): eq. 18 gives
    ``alpha'_1 + alpha'_2 = pi`` and ``delta_A + delta_B + 2 beta = 2 pi/N``; eq. 19,
    ``alpha' = delta + beta + 2 gamma``, written for both chamber kinds then
    gives ``gamma = pi/4 - pi/(2N)`` (pi/8 at the paper's N = 4; 0 at N = 2).
    Broadcasts over ``pistons``.
    """
    return np.pi / 4.0 - np.pi / (2.0 * np.asarray(pistons, dtype=float))


def chamber_count(pistons=4) -> int:
    """Chambers between two rotors of N pistons each: ``2 N`` (8 in the paper)."""
    return 2 * int(pistons)


#: Fields of :class:`TwinRotor` that :func:`violation` checks, in the order it checks them.
CHECKED = (
    "compression_ratio",
    "pistons_per_rotor",
    "section",
    "outer_radius",
    "inner_radius",
    "axial_width",
    "mean_radius",
    "section_diameter",
    "clearance_volume",
    "inertia_shaft",
    "inertia_rotor_1",
    "inertia_rotor_2",
    "speed_fluctuation",
)
SECTIONS = ("rectangular", "circular")


def first_violation(checks, shape=()) -> np.ndarray:
    """Code per element: 0 where no check fails, else 1 + the index of the first failing one.

    Parameters
    ----------
    checks : sequence of array_like of bool
        ``True`` where the check fails; broadcast together (and with ``shape``).
    """
    checks = [np.asarray(c, dtype=bool) for c in checks]
    shape = np.broadcast_shapes(shape, *(c.shape for c in checks))
    code = np.zeros(shape, dtype=np.int16)
    for i, bad in enumerate(checks):
        code[(code == 0) & bad] = i + 1
    return code


def violation(
    compression_ratio,
    pistons_per_rotor,
    section,
    inner_radius,
    outer_radius,
    axial_width,
    mean_radius,
    section_diameter,
    clearance_volume,
    inertia_shaft=0.0,
    inertia_rotor_1=0.0,
    inertia_rotor_2=0.0,
    speed_fluctuation=0.02,
) -> np.ndarray:
    """Which field of the twin-rotor machine is not admissible, per design.

    Every argument is a float (``section`` a string) or an array; they broadcast
    together. Lengths [m], volume [m^3], inertias [kg m^2].

    Returns
    -------
    ndarray of int16
        0 where admissible, else ``1 + CHECKED.index(field)`` of the first field
        (in the order of :data:`CHECKED`) that is out of range: compression_ratio > 1;
        pistons_per_rotor even and >= 2; section rectangular or circular;
        rectangular: outer_radius > 0, 0 < inner_radius < outer_radius,
        axial_width > 0; circular: mean_radius > 0,
        0 < section_diameter < 2 mean_radius; clearance_volume >= 0; inertias >= 0;
        0 < speed_fluctuation < 1.
    """
    with np.errstate(invalid="ignore"):
        eps = np.asarray(compression_ratio, dtype=float)
        n = np.asarray(pistons_per_rotor, dtype=float)
        sec = np.asarray(section)
        rect = sec == "rectangular"
        known = rect | (sec == "circular")
        ri, ro = np.asarray(inner_radius, dtype=float), np.asarray(outer_radius, dtype=float)
        w = np.asarray(axial_width, dtype=float)
        rm, d = np.asarray(mean_radius, dtype=float), np.asarray(section_diameter, dtype=float)
        vc = np.asarray(clearance_volume, dtype=float)
        cs = np.asarray(speed_fluctuation, dtype=float)
        inertias = [np.asarray(j, dtype=float) for j in (inertia_shaft, inertia_rotor_1,
                                                         inertia_rotor_2)]  # fmt: skip
        return first_violation(
            [
                ~(np.isfinite(eps) & (eps > 1.0)),
                ~((n >= 2) & (n % 2 == 0)),
                ~known,
                rect & ~(np.isfinite(ro) & (ro > 0.0)),
                rect & ~(np.isfinite(ri) & (ri > 0.0) & (ri < ro)),
                rect & ~(np.isfinite(w) & (w > 0.0)),
                ~rect & ~(np.isfinite(rm) & (rm > 0.0)),
                ~rect & ~(np.isfinite(d) & (d > 0.0) & (d < 2.0 * rm)),
                ~(np.isfinite(vc) & (vc >= 0.0)),
                *(~(np.isfinite(j) & (j >= 0.0)) for j in inertias),
                ~(np.isfinite(cs) & (cs > 0.0) & (cs < 1.0)),
            ]
        )


def _shown(name, value) -> str:
    """A field's value as the error message shows it."""
    if name in ("outer_radius", "inner_radius", "axial_width", "mean_radius", "section_diameter"):
        return fmt_mm(float(value))
    if name == "clearance_volume":
        return f"{float(value) * 1e6:.4g} cm^3"
    if name.startswith("inertia"):
        return f"{float(value):g} kg*m^2"
    if name == "section":
        return repr(value)
    return f"{float(value):g}"


def _admissible(machine, name) -> str:
    """The admissible range of a field of ``machine``, as the error message states it."""
    fixed = {
        "compression_ratio": "compression_ratio > 1 (and above the ratio of zero-width "
        "pistons, eq. 21)",
        "section": '"rectangular" or "circular"',
        "outer_radius": "outer_radius > 0 mm",
        "axial_width": "axial_width > 0 mm",
        "mean_radius": "mean_radius > 0 mm",
        "clearance_volume": "clearance >= 0",
        "speed_fluctuation": "0 < speed_fluctuation < 1",
    }
    if name in fixed:
        return fixed[name]
    if name == "inner_radius":
        return (
            f"0 mm < inner_radius < outer_radius = {fmt_mm(float(machine.outer_radius))} "
            "(rectangular annulus)"
        )
    if name == "section_diameter":
        return (
            f"0 mm < section_diameter < 2 mean_radius = {fmt_mm(2.0 * float(machine.mean_radius))}"
            " (the torus section must not reach the axis)"
        )
    return f"{name} >= 0"


@dataclass(frozen=True)
class TwinRotor:
    """Geometry and inertias of the twin-rotor engine (SI; config section ``[machine]``).

    Parameters
    ----------
    compression_ratio : float, optional
        Angular ratio ``eps = delta_max/delta_min`` of the tighter chamber kind; it
        sets the piston width (eq. 21-22). Table 1: 10 (default).
    pistons_per_rotor : int, optional
        N, even, >= 2 (paper: 4).
    section : {"rectangular", "circular"}, optional
        Cylinder section: rectangular annulus or circular torus.
    inner_radius, outer_radius, axial_width : float, optional
        Rectangular annulus ``R_i < R_o`` and its axial width w [m].
    mean_radius, section_diameter : float, optional
        Circular torus: radius ``R_m`` of the section centre and diameter d,
        ``d/2 < R_m`` [m].
    clearance_volume : float, optional
        ``V_c`` added to every chamber, >= 0 [m^3] (default 0, as in the paper).
    inertia_shaft : float, optional
        Output shaft with everything turning at its speed [kg m^2] (members
        whose kinetic energy is ``1/2 J omega^2`` with a constant J).
    inertia_rotor_1, inertia_rotor_2 : float, optional
        Rotors with their pistons and rails [kg m^2].
    speed_fluctuation : float, optional
        Wanted coefficient of speed fluctuation for the flywheel, in (0, 1).
    """

    compression_ratio: float = 10.0
    pistons_per_rotor: int = 4
    section: str = "rectangular"
    inner_radius: float = 0.04
    outer_radius: float = 0.08
    axial_width: float = 0.04
    mean_radius: float = 0.06
    section_diameter: float = 0.04
    clearance_volume: float = 0.0
    inertia_shaft: float = 0.004
    inertia_rotor_1: float = 0.008
    inertia_rotor_2: float = 0.008
    speed_fluctuation: float = 0.02

    def __post_init__(self):
        try:
            code = violation(**{f: getattr(self, f) for f in CHECKED})
        except (TypeError, ValueError):  # a value that is no number at all
            check_pistons(self.pistons_per_rotor)
            raise
        if np.ndim(code):  # columns of designs (one number of pistons): each one admissible
            check_pistons(self.pistons_per_rotor)
            refuse_first(self, code)
            return
        code = int(code)
        if code:
            name = CHECKED[code - 1]
            if name == "pistons_per_rotor":
                check_pistons(self.pistons_per_rotor)  # raises, with the reason
            raise ParameterError(name, _shown(name, getattr(self, name)), _admissible(self, name))
        check_pistons(self.pistons_per_rotor)  # an int, not only an integral value

    @property
    def chambers(self) -> int:
        """Number of chambers, 2N."""
        return chamber_count(self.pistons_per_rotor)

    @property
    def member_inertias(self) -> tuple[float, float]:
        """``(inertia_rotor_1, inertia_rotor_2)`` [kg m^2] (arrays for columns of designs)."""
        return number(self.inertia_rotor_1), number(self.inertia_rotor_2)


@dataclass(frozen=True)
class Chambers:
    """Chamber volumes over the shaft angle.

    Attributes
    ----------
    theta : ndarray, shape (...)
        Shaft angle [rad].
    volume : ndarray, shape (2N, ...)
        ``V_j`` [m^3].
    dvolume, d2volume : ndarray, shape (2N, ...)
        ``dV_j/dtheta`` [m^3/rad], ``d2V_j/dtheta2`` [m^3/rad^2] (exact).
    dvolume_dq : ndarray, shape (2, 2N)
        ``dV_j/dPhi_i`` [m^3/rad] (constant).
    motion : Motion
        The rotors' motion (``q = (Phi_1, Phi_2)``).
    piston_width : float
        beta [rad].
    """

    theta: np.ndarray
    volume: np.ndarray
    dvolume: np.ndarray
    d2volume: np.ndarray
    dvolume_dq: np.ndarray
    motion: Motion
    piston_width: float


@dataclass(frozen=True)
class EngineState:
    """Chambers, strokes, pressures and gas torques over the shaft angle.

    Attributes
    ----------
    chambers : Chambers
    stroke : ndarray of int, shape (2N, ...)
        Stroke of each chamber (:data:`rotorkin.analysis.engine_cycle.INTAKE` ...).
    pressure : ndarray, shape (2N, ...)
        Absolute chamber pressures [Pa].
    member_torque : ndarray, shape (2, ...)
        Gas torques on rotor 1 and 2, ``M_i = sum_j p_j dV_j/dPhi_i`` [N m].
    shaft_torque : ndarray, shape (...)
        Gas torque on the shaft by virtual work, ``sum_i M_i Phi_i'`` [N m],
        positive when it drives the shaft.
    """

    chambers: Chambers
    stroke: np.ndarray
    pressure: np.ndarray
    member_torque: np.ndarray
    shaft_torque: np.ndarray


# --------------------------------------------------------------------------------------------
# geometry
# --------------------------------------------------------------------------------------------
def section_volume_per_radian(
    section, inner_radius, outer_radius, axial_width, mean_radius, section_diameter
):
    """Volume of the cylinder per radian of chamber angle, K [m^3/rad].

    Rectangular annulus: ``(R_o^2 - R_i^2) w / 2``; circular torus (Pappus):
    ``R_m pi d^2 / 4``. Every argument may be an array (they broadcast).

    Parameters
    ----------
    section : str or array_like of str
        ``"rectangular"`` or ``"circular"``.
    inner_radius, outer_radius, axial_width : float or array_like
        ``R_i``, ``R_o``, ``w`` of the rectangular annulus [m].
    mean_radius, section_diameter : float or array_like
        ``R_m``, ``d`` of the circular torus [m].
    """
    ro, ri = np.asarray(outer_radius, dtype=float), np.asarray(inner_radius, dtype=float)
    rect = 0.5 * (ro * ro - ri * ri) * axial_width
    circ = mean_radius * np.pi * np.asarray(section_diameter, dtype=float) ** 2 / 4.0
    out = np.where(np.asarray(section) == "rectangular", rect, circ)
    return out[()] if out.ndim == 0 else out


def chamber_volume(volume_per_radian, chamber_angle, clearance_volume=0.0):
    """Volume of a chamber from its angle, ``V = K delta + V_c`` [m^3].

    Parameters
    ----------
    volume_per_radian : float or array_like
        K [m^3/rad] (:func:`section_volume_per_radian`).
    chamber_angle : float or array_like
        delta [rad].
    clearance_volume : float or array_like, optional
        V_c [m^3]. All three broadcast together.
    """
    return volume_per_radian * chamber_angle + clearance_volume


def displacement(swept_volume, chambers, cycles_per_rev):
    """Volume the intake strokes draw in per shaft turn, ``V_s x 2N x cycles`` [m^3].

    Parameters
    ----------
    swept_volume : float or array_like
        Volume swept by one chamber in one stroke [m^3].
    chambers : int or array_like
        2N.
    cycles_per_rev : float or array_like
        Four-stroke cycles of each chamber per shaft turn [-].
    """
    return swept_volume * chambers * cycles_per_rev


def volume_per_radian(machine: TwinRotor) -> float:
    """Volume of the cylinder per radian of chamber angle, K [m^3/rad].

    :func:`section_volume_per_radian` of the machine's fields (an array for columns of
    designs).
    """
    return number(
        section_volume_per_radian(
            machine.section,
            machine.inner_radius,
            machine.outer_radius,
            machine.axial_width,
            machine.mean_radius,
            machine.section_diameter,
        )
    )


def annulus_volume(machine: TwinRotor) -> float:
    """Volume of the whole annular cylinder, ``2 pi K`` [m^3] (no clearance)."""
    return 2.0 * np.pi * volume_per_radian(machine)


def chamber_kinds(machine: TwinRotor) -> np.ndarray:
    """Kind of each chamber, 0 = A, 1 = B; shape (2N,): ``[0, 1, 0, 1, ...]``."""
    return np.arange(machine.chambers) % 2


def _signs(machine, ndim=0):
    """``s_j = +1`` (A), ``-1`` (B), shaped (2N, 1, ...) for ``ndim`` trailing axes."""
    return (1.0 - 2.0 * chamber_kinds(machine)).reshape((-1,) + (1,) * ndim)


def _per_chamber(machine, pair, ndim=0):
    """Chamber-kind values ``(A, B)`` spread over the 2N chambers, shape (2N, 1, ...).

    ``A`` and ``B`` may be columns of designs broadcasting against the ``ndim`` trailing
    axes (e.g. (designs, 1) with ``ndim = 2``).
    """
    a, b = pair
    kinds = chamber_kinds(machine).reshape((-1,) + (1,) * ndim)
    return np.where(kinds == 0, a, b)


def volume_gradient(machine: TwinRotor, ndim: int = 0) -> np.ndarray:
    """``dV_j/dPhi_i`` [m^3/rad], shape (2, 2N): row 0 rotor 1 (``-s_j K``), row 1 rotor 2.

    With ``ndim`` trailing unit axes, shape (2, 2N, 1, ...), K broadcast into them (columns
    of designs: (2, 2N, designs, 1) with ``ndim = 2``).
    """
    k = volume_per_radian(machine)
    s = _signs(machine, ndim)
    return np.stack(np.broadcast_arrays(-k * s, k * s))


def _offsets(machine, piston_width, ndim=0):
    """``delta_j = s_j (Phi_2 - Phi_1) + o_j``: the constant o_j, shaped (2N, 1, ...)."""
    n = machine.pistons_per_rotor
    g2 = 2.0 * float(piston_offset(n))
    beta = piston_width
    return _per_chamber(machine, (-g2 - beta, 2.0 * np.pi / n + g2 - beta), ndim)


def chamber_volumes_from_rotors(machine: TwinRotor, piston_width, q1, q2):
    """Chamber volumes from the rotor angles, ``V_j = K delta_j + V_c`` [m^3].

    Parameters
    ----------
    machine : TwinRotor
    piston_width : float
        beta [rad].
    q1, q2 : array_like
        ``Phi_1``, ``Phi_2`` [rad] (broadcast together).

    Returns
    -------
    ndarray, shape (2N, ...)
    """
    rel = np.asarray(q2, dtype=float) - np.asarray(q1, dtype=float)
    delta = _signs(machine, rel.ndim) * rel + _offsets(machine, piston_width, rel.ndim)
    return chamber_volume(volume_per_radian(machine), delta, machine.clearance_volume)


def chambers(machine: TwinRotor, motion: Motion, piston_width) -> Chambers:
    """Volumes of all chambers and their exact derivatives over the shaft angle.

    ``dV_j/dtheta = s_j K (Phi_2' - Phi_1')``, ``d2V_j/dtheta2 = s_j K (Phi_2'' - Phi_1'')``.

    Parameters
    ----------
    machine : TwinRotor
    motion : Motion
        Rotor 1 and rotor 2 over the shaft angle [rad].
    piston_width : float
        beta [rad].
    """
    m = motion
    theta = np.asarray(m.theta, dtype=float)
    k = volume_per_radian(machine)
    nd = np.ndim(m.dq[0])  # the angles' axes, and the designs' for columns of designs
    s = _signs(machine, nd)
    return Chambers(
        theta=theta,
        volume=chamber_volumes_from_rotors(machine, piston_width, m.q[0], m.q[1]),
        dvolume=k * s * (m.dq[1] - m.dq[0]),
        d2volume=k * s * (m.d2q[1] - m.d2q[0]),
        dvolume_dq=volume_gradient(machine, 0 if np.ndim(k) == 0 else nd),
        motion=m,
        piston_width=piston_width,
    )


def volume_limits(machine: TwinRotor, angle_min, angle_max, ndim: int = 0):
    """Smallest and largest volume of every chamber [m^3].

    Parameters
    ----------
    machine : TwinRotor
    angle_min, angle_max : pair of float
        Smallest and largest chamber angle of kind A and of kind B,
        ``(delta_A, delta_B)`` [rad].
    ndim : int, optional
        Trailing unit axes of the result (2 for columns of designs against the angles).

    Returns
    -------
    (v_min, v_max) : tuple of ndarray, shape (2N,) (with ``ndim``: (2N, 1, ...))
    """
    k, vc = volume_per_radian(machine), machine.clearance_volume
    lo = _per_chamber(machine, angle_min, ndim)
    hi = _per_chamber(machine, angle_max, ndim)
    return chamber_volume(k, lo, vc), chamber_volume(k, hi, vc)


def swept_volume(machine: TwinRotor, swing) -> float:
    """Volume swept by one chamber in one stroke, ``K swing`` [m^3] (eq. 23).

    ``swing = delta_max - delta_min`` [rad], the same for both kinds.
    """
    return volume_per_radian(machine) * swing


def compression_ratio_geometric(machine: TwinRotor, angle_min, angle_max):
    """``V_max / V_min`` of chamber kind A and B, with the clearance volume.

    With ``V_s`` the swept volume and ``V_0 = K delta_min`` the smallest volume
    of the sector itself, ``eps_geo = (V_s + V_0 + V_c) / (V_0 + V_c)``; it equals
    the angular ratio ``delta_max / delta_min`` when ``V_c = 0``.

    Returns
    -------
    (eps_a, eps_b) : tuple of float
    """
    v_min, v_max = volume_limits(machine, angle_min, angle_max)
    return float(v_max[0] / v_min[0]), float(v_max[1] / v_min[1])


def displacement_per_rev(machine: TwinRotor, swing, cycles_per_rev) -> float:
    """Engine displacement per shaft turn, four-stroke convention [m^3].

    The volume the intake strokes draw in per shaft turn: swept volume per
    chamber times the intake strokes per turn of all chambers,
    ``V_s x 2N x cycles_per_rev`` (16 V_s at N = 4 and 2 four-stroke cycles per
    turn). A conventional four-stroke piston engine of capacity ``V_d`` draws
    ``V_d / 2`` per turn: the capacity equivalent to this engine is twice this
    value, :func:`swept_volume_per_rev`.

    Parameters
    ----------
    machine : TwinRotor
    swing : float
        ``delta_max - delta_min`` [rad].
    cycles_per_rev : float
        Four-stroke cycles of each chamber per shaft turn [-].
    """
    return displacement(swept_volume(machine, swing), machine.chambers, cycles_per_rev)


def swept_volume_per_rev(machine: TwinRotor, swing, cycles_per_rev) -> float:
    """Volume swept per shaft turn by all volume cycles of all chambers [m^3].

    ``V_s x 2N x 2 cycles_per_rev``: every expansion counted, intake and power
    alike; the capacity of the equivalent conventional four-stroke engine
    (twice :func:`displacement_per_rev`).
    """
    return 2.0 * displacement_per_rev(machine, swing, cycles_per_rev)


# --------------------------------------------------------------------------------------------
# four-stroke timing, pressures, torques
# --------------------------------------------------------------------------------------------
def stroke_counter(machine: TwinRotor, count):
    """Stroke counters ``c_j = c_0 - b_j + 2 m_j`` of the chambers ``j = 2 m_j + b_j``.

    Parameters
    ----------
    machine : TwinRotor
    count : array_like, shape (...)
        Stroke counter ``c_0`` of chamber 1 (strokes since the start of its
        intake; integers on the volume extremes) [-].

    Returns
    -------
    ndarray, shape (2N, ...)
        ``floor(c_j) mod 4`` is the stroke of chamber j.
    """
    count = np.asarray(count, dtype=float)
    j = np.arange(machine.chambers).reshape((-1,) + (1,) * count.ndim)
    b, m = j % 2, j // 2
    return count - b + 2.0 * m


def strokes(machine: TwinRotor, count):
    """Stroke of every chamber, shape (2N, ...) of int, from chamber 1's counter.

    0 intake, 1 compression, 2 power, 3 exhaust
    (:data:`rotorkin.analysis.engine_cycle.STROKE_NAMES`); at a volume extreme,
    the stroke that starts there.
    """
    return ec.stroke_from_count(stroke_counter(machine, count))


def chamber_pressures(cycle, machine: TwinRotor, angle_min, angle_max, stroke, volume, theta=None):
    """Pressures of all chambers from their strokes and volumes [Pa], shape (2N, ...).

    ``angle_min``, ``angle_max``: chamber angle extremes ``(delta_A, delta_B)`` [rad].
    The ideal cycle's pressures depend on the stroke and the volume only; a fuel-air
    cycle (:class:`rotorkin.machines.fuel_air.ChargeCycle`) reads its integrated
    tables at the shaft angles ``theta``.
    """
    if not isinstance(cycle, ec.IdealCycle):
        return cycle.pressures(theta, stroke)
    v_min, v_max = volume_limits(machine, angle_min, angle_max, np.ndim(volume) - 1)
    return ec.cycle_pressure(cycle, stroke, volume, v_max, v_min)


def engine_state(
    machine: TwinRotor,
    cycle: ec.IdealCycle,
    motion: Motion,
    piston_width,
    angle_min,
    angle_max,
    count,
) -> EngineState:
    """Volumes, strokes, pressures, member torques and shaft gas torque.

    Member torques by ``M_i = sum_j p_j dV_j/dPhi_i``
    (:func:`rotorkin.analysis.torque.member_torques`); the shaft torque by
    virtual work ``sum_i M_i dPhi_i/dtheta``
    (:func:`rotorkin.analysis.torque.shaft_torque_from_members`). Since
    ``dV_j/dPhi_1 = -dV_j/dPhi_2``, ``M_1 = -M_2``: the gas pushes the rotors
    apart, and the shaft torque is ``M_2 (Phi_2' - Phi_1') = sum_j p_j dV_j/dtheta``.

    Parameters
    ----------
    machine : TwinRotor
    cycle : IdealCycle
    motion : Motion
        The rotors over the shaft angle theta [rad].
    piston_width : float
        beta [rad].
    angle_min, angle_max : pair of float
        Chamber angle extremes ``(delta_A, delta_B)`` [rad].
    count : array_like
        Chamber 1's stroke counter at theta (:func:`stroke_counter`) [-].
    """
    ch = chambers(machine, motion, piston_width)
    count = np.asarray(count, dtype=float)
    count = count.reshape((1,) * (np.ndim(motion.q[0]) - count.ndim) + count.shape)
    stroke = strokes(machine, count)
    p = chamber_pressures(cycle, machine, angle_min, angle_max, stroke, ch.volume, ch.theta)
    grad = ch.dvolume_dq.reshape(ch.dvolume_dq.shape + (1,) * (p.ndim + 1 - ch.dvolume_dq.ndim))
    members = member_torques(p, grad)
    return EngineState(
        chambers=ch,
        stroke=stroke,
        pressure=p,
        member_torque=members,
        shaft_torque=shaft_torque_from_members(members, ch.motion.dq),
    )


def indicated_work_per_rev(
    machine: TwinRotor, cycle: ec.IdealCycle, angle_min, angle_max, cycles_per_rev
) -> float:
    """Indicated work of all chambers per shaft turn, closed form [J].

    ``sum_j cycles_per_rev Q (1 - eps_geo,j^(1-k))``
    (:func:`rotorkin.analysis.engine_cycle.indicated_work`).
    """
    if not isinstance(cycle, ec.IdealCycle):  # a fuel-air cycle sums its integrated parts
        return cycle.work_per_rev()
    v_min, v_max = volume_limits(machine, angle_min, angle_max)
    return float(np.sum(ec.indicated_work(cycle, v_max, v_min)) * cycles_per_rev)


def cycle_summary(machine: TwinRotor, cycle, v_min, v_max, cycles_per_rev, displacement) -> dict:
    """The cycle's per-turn numbers: work, heat, efficiency, mean effective and peak pressure.

    ``cycle``: the ideal cycle (closed forms) or a fuel-air cycle integrated on the drive
    (:class:`rotorkin.machines.fuel_air.ChargeCycle`, which sums its own parts).
    """
    if not isinstance(cycle, ec.IdealCycle):
        return cycle.summary(displacement)
    work = float(np.sum(ec.indicated_work(cycle, v_max, v_min)) * cycles_per_rev)
    heat = cycle.heat_per_cycle * machine.chambers * cycles_per_rev
    return {
        "compression_end_pressure_bar": float(
            np.max(ec.compression_end_pressure(cycle, v_max, v_min))) / 1e5,
        "peak_pressure_bar": float(np.max(ec.peak_pressure(cycle, v_max, v_min))) / 1e5,
        "indicated_work_J": work,
        "heat_added_J_per_rev": float(heat),
        "indicated_efficiency": work / heat if heat > 0 else float("nan"),
        "otto_efficiency": float(np.max(ec.otto_efficiency(v_max / v_min,
                                                           cycle.polytropic_exponent))),
        "imep_bar": work / displacement / 1e5 if displacement > 0 else float("nan"),
    }  # fmt: skip
