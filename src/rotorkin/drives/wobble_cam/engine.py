"""The twin-rotor engine driven by the wobble cam: the drive's numbers fed to the machine.

:mod:`rotorkin.machines.twin_rotor` computes chambers, strokes, pressures and
torques from the rotors' :class:`rotorkin.core.motion.Motion` and plain numbers.
This module supplies those numbers from a
:class:`rotorkin.drives.wobble_cam.kinematics.WobbleCam`: the rotor motion
(eq. 13-15), the piston width and chamber angle extremes for the machine's
compression ratio (eq. 17, 21-22), the four-stroke cycles per shaft turn and
chamber 1's stroke counter from the spin law.

Four-stroke timing: with ``n`` the spin ratio, the slider angle has period
``pi/|n|`` in theta and is even, so all volume extremes fall at
``theta = m pi/(2|n|)``: kind A is largest (BDC) at even m, kind B at odd m.
Every stroke lasts ``pi/(2|n|)`` of shaft angle (45 deg at n = -2). Chamber 1
starts its compression stroke at theta = 0, chamber 2 its intake (paper
section 1.2: 2 chambers on the power stroke at every instant at N = 4).
"""

from __future__ import annotations

import numpy as np

from rotorkin.analysis import engine_cycle as ec
from rotorkin.analysis.flywheel import energy_fluctuation, flywheel_inertia
from rotorkin.analysis.torque import (
    SHAFT_TORQUE_KEYS,
    equivalent_inertia,
    inertia_torque,
    kinetic_energy,
    shaft_torque_summary,
)
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.machines import twin_rotor as tr

__all__ = [
    "piston_layout",
    "cycles_per_rev",
    "chamber_stroke_count",
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
    "dynamics",
    "DYNAMICS_KEYS",
    "dynamics_summary",
]


def _check(drive: wc.WobbleCam, machine: tr.TwinRotor):
    if drive.pistons_per_rotor != machine.pistons_per_rotor:
        raise ValueError(
            f"the drive has {drive.pistons_per_rotor} pistons per rotor, the machine "
            f"{machine.pistons_per_rotor}: build both from the same pistons_per_rotor"
        )


def _extremes(layout: wc.PistonLayout):
    """Chamber angle extremes ``(delta_A, delta_B)``: (minima, maxima) [rad]."""
    return (
        (layout.chamber_a_min, layout.chamber_b_min),
        (layout.chamber_a_max, layout.chamber_b_max),
    )


def piston_layout(drive: wc.WobbleCam, machine: tr.TwinRotor) -> wc.PistonLayout:
    """Piston width and chamber angle extremes for the machine's compression ratio.

    :func:`rotorkin.drives.wobble_cam.kinematics.piston_layout` (eq. 21-22 generalised to N);
    raises ParameterError named ``compression_ratio`` if eps is too small.
    """
    _check(drive, machine)
    return wc.piston_layout(drive, machine.compression_ratio)


def cycles_per_rev(drive: wc.WobbleCam) -> float:
    """Four-stroke cycles of each chamber per shaft turn, ``2|n| / 2 = |n|``."""
    return wc.volume_cycles_per_rev(drive) / 2.0


def chamber_stroke_count(drive: wc.WobbleCam, theta):
    """Stroke counter of chamber 1, ``c_0 = 2 sign(n) varphi(theta)/pi + 1`` [-].

    ``floor(c_0) mod 4`` is chamber 1's stroke; its integers fall on the volume
    extremes. The chambers follow the plate spin ``varphi`` (the slider angle is
    a function of it), so with a corrected spin law ``|n| theta`` reads
    ``sign(n) varphi(theta)``.

    Parameters
    ----------
    drive : WobbleCam
    theta : array_like
        Shaft angle [rad].
    """
    theta = np.asarray(theta, dtype=float)
    turned = np.sign(float(drive.spin_ratio)) * wc.spin_law(drive, theta)[0]
    return 2.0 * turned / np.pi + 1.0


def chamber_volumes_from_rotors(machine: tr.TwinRotor, layout: wc.PistonLayout, q1, q2):
    """Chamber volumes from the rotor angles [m^3], shape (2N, ...).

    :func:`rotorkin.machines.twin_rotor.chamber_volumes_from_rotors` with the
    layout's piston width.
    """
    return tr.chamber_volumes_from_rotors(machine, layout.piston_width, q1, q2)


def chambers(drive: wc.WobbleCam, machine: tr.TwinRotor, theta, layout=None) -> tr.Chambers:
    """Volumes of all chambers and their exact derivatives over the shaft angle theta [rad].

    :func:`rotorkin.machines.twin_rotor.chambers` with the rotors' motion
    (:func:`rotorkin.drives.wobble_cam.kinematics.motion`).
    """
    _check(drive, machine)
    layout = piston_layout(drive, machine) if layout is None else layout
    return tr.chambers(machine, wc.motion(drive, theta), layout.piston_width)


def volume_limits(machine: tr.TwinRotor, layout: wc.PistonLayout):
    """Smallest and largest volume of every chamber [m^3], two arrays of shape (2N,)."""
    return tr.volume_limits(machine, *_extremes(layout))


def swept_volume(machine: tr.TwinRotor, layout: wc.PistonLayout) -> float:
    """Volume swept by one chamber in one stroke, ``K (alpha'_max - alpha'_min)`` [m^3] (eq. 23)."""
    return tr.swept_volume(machine, layout.swing)


def compression_ratio_geometric(machine: tr.TwinRotor, layout: wc.PistonLayout):
    """``V_max / V_min`` of chamber kind A and B, with the clearance volume.

    It equals the angular ratio (config ``compression_ratio``) when ``V_c = 0``.
    """
    return tr.compression_ratio_geometric(machine, *_extremes(layout))


def displacement_per_rev(drive: wc.WobbleCam, machine: tr.TwinRotor, layout) -> float:
    """Engine displacement per shaft turn, ``V_s x 2N x |n|`` [m^3] (16 V_s at N = 4, n = -2).

    :func:`rotorkin.machines.twin_rotor.displacement_per_rev`.
    """
    _check(drive, machine)
    return tr.displacement_per_rev(machine, layout.swing, cycles_per_rev(drive))


def swept_volume_per_rev(drive: wc.WobbleCam, machine: tr.TwinRotor, layout) -> float:
    """Volume swept per shaft turn by all volume cycles, ``V_s x 2N x 2|n|`` [m^3]."""
    _check(drive, machine)
    return tr.swept_volume_per_rev(machine, layout.swing, cycles_per_rev(drive))


def stroke_counter(drive: wc.WobbleCam, machine: tr.TwinRotor, theta):
    """Stroke counter ``c_j = 2|n| theta/pi + 1 - b_j + 2 m_j`` of chamber ``j = 2 m_j + b_j``.

    ``floor(c_j) mod 4`` is the chamber's stroke; see :func:`chamber_stroke_count`
    and :func:`rotorkin.machines.twin_rotor.stroke_counter`.

    Returns
    -------
    ndarray, shape (2N, ...)
    """
    return tr.stroke_counter(machine, chamber_stroke_count(drive, theta))


def strokes(drive: wc.WobbleCam, machine: tr.TwinRotor, theta):
    """Stroke of every chamber at every shaft angle, shape (2N, ...) of int.

    0 intake, 1 compression, 2 power, 3 exhaust
    (:data:`rotorkin.analysis.engine_cycle.STROKE_NAMES`).
    """
    return tr.strokes(machine, chamber_stroke_count(drive, theta))


def chamber_pressures(cycle: ec.IdealCycle, machine: tr.TwinRotor, layout, stroke, volume):
    """Pressures of all chambers from their strokes and volumes [Pa], shape (2N, ...)."""
    return tr.chamber_pressures(cycle, machine, *_extremes(layout), stroke, volume)


def engine_state(drive: wc.WobbleCam, machine: tr.TwinRotor, cycle: ec.IdealCycle, theta,
                 layout=None):  # fmt: skip
    """Volumes, strokes, pressures, member torques and shaft gas torque at ``theta`` [rad].

    :func:`rotorkin.machines.twin_rotor.engine_state` with the rotors' motion,
    the piston layout (default: :func:`piston_layout`) and chamber 1's stroke counter.
    Columns of designs: drive and machine holding arrays of shape (d, 1) against ``theta``
    (n,) give every curve of shape (..., d, n).
    """
    _check(drive, machine)
    layout = piston_layout(drive, machine) if layout is None else layout
    theta = np.asarray(theta, dtype=float)
    return tr.engine_state(
        machine,
        cycle,
        wc.motion(drive, theta),
        layout.piston_width,
        *_extremes(layout),
        chamber_stroke_count(drive, theta),
    )


def indicated_work_per_rev(drive, machine: tr.TwinRotor, cycle: ec.IdealCycle, layout) -> float:
    """Indicated work of all chambers per shaft turn, closed form [J].

    ``sum_j |n| Q (1 - eps_geo,j^(1-k))``: each chamber runs ``|n|`` four-stroke
    cycles per turn (:func:`rotorkin.analysis.engine_cycle.indicated_work`).
    """
    return tr.indicated_work_per_rev(machine, cycle, *_extremes(layout), cycles_per_rev(drive))


def dynamics(machine: tr.TwinRotor, state: tr.EngineState, omega, omega_dot):
    """Inertia torque, net shaft torque, ``J_eq`` and kinetic energy at the given speed.

    ``omega``, ``omega_dot`` [rad/s, rad/s^2] at the state's angles; the net torque is the
    gas torque less the torque that accelerates shaft and rotors.
    """
    dq, d2q = state.chambers.motion.dq, state.chambers.motion.d2q
    j_s, j_m = machine.inertia_shaft, machine.member_inertias
    t_in = inertia_torque(j_s, j_m, dq, d2q, omega, omega_dot)
    return (
        t_in,
        state.shaft_torque - t_in,
        equivalent_inertia(j_s, j_m, dq),
        kinetic_energy(j_s, j_m, dq, omega),
    )


#: The keys of :func:`dynamics_summary`, in order.
DYNAMICS_KEYS = (
    *SHAFT_TORQUE_KEYS,
    "rotor_gas_torque_peak_Nm",
    "equivalent_inertia_mean_kgm2",
    "energy_fluctuation_J",
    "speed_fluctuation_without_flywheel",
    "speed_fluctuation",
    "flywheel_inertia_kgm2",
)


def dynamics_summary(machine: tr.TwinRotor, state: tr.EngineState, theta, omega, omega_mean):
    """Torque extremes and ripple, equivalent inertia, energy fluctuation and flywheel.

    Parameters
    ----------
    machine : TwinRotor
    state : EngineState
        Over one turn ``theta`` (ends included), e.g. :func:`engine_state`.
    theta : ndarray, shape (n,)
        Shaft angles [rad].
    omega : tuple of ndarray
        ``(omega, omega_dot)`` at ``theta`` [rad/s, rad/s^2] (the run's speed profile).
    omega_mean : float
        Time-averaged shaft speed [rad/s]; the flywheel is sized at this constant speed
        (net torque ``T_gas - T_inertia(omega_mean)``).

    Returns
    -------
    dict
        :data:`DYNAMICS_KEYS`: arrays of the designs for columns of designs (machine fields
        of shape (d, 1), the state's angles last), else 0-d values.
    """
    _, net, j_eq, _ = dynamics(machine, state, omega[0], omega[1])
    _, net_const, _, _ = dynamics(machine, state, omega_mean, 0.0)
    d_e = energy_fluctuation(net_const, theta)
    j_mean = np.mean(j_eq[..., :-1], axis=-1)
    c_s = np.asarray(machine.speed_fluctuation, dtype=float)
    c_s = c_s[..., 0] if c_s.ndim else c_s  # a column of designs: (d, 1) -> (d,)
    torque = state.shaft_torque
    held = j_mean * omega_mean**2
    with np.errstate(divide="ignore", invalid="ignore"):
        unbound = np.where(held > 0, d_e / np.where(held > 0, held, 1.0), np.nan)
    return {
        **shaft_torque_summary(torque, net),
        "rotor_gas_torque_peak_Nm": np.max(np.abs(state.member_torque), axis=(0, -1)),
        "equivalent_inertia_mean_kgm2": j_mean,
        "energy_fluctuation_J": d_e,
        "speed_fluctuation_without_flywheel": unbound,
        "speed_fluctuation": c_s,
        "flywheel_inertia_kgm2": flywheel_inertia(d_e, omega_mean, c_s, j_mean),
    }
