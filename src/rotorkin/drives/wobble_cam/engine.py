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


def engine_state(drive: wc.WobbleCam, machine: tr.TwinRotor, cycle: ec.IdealCycle, theta):
    """Volumes, strokes, pressures, member torques and shaft gas torque at ``theta`` [rad].

    :func:`rotorkin.machines.twin_rotor.engine_state` with the rotors' motion,
    the piston layout and chamber 1's stroke counter.
    """
    _check(drive, machine)
    layout = piston_layout(drive, machine)
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
