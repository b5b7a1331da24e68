"""The opposed-piston reactor driven by the double eccentric discs: the two joined.

:mod:`rotorkin.machines.opposed_piston` computes the reactor from the pistons'
:class:`~rotorkin.core.motion.Motion` and plain numbers; this module supplies
them from the drive (:mod:`rotorkin.drives.eccentric_cam.kinematics`): the
travels ``(z, z')`` of eq. 1, 3 and the smallest gap change of eq. 5 (at
``beta = 90 deg``).
"""

from __future__ import annotations

from rotorkin.analysis import torque as tq
from rotorkin.analysis.timing import shaft_speed
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.machines import opposed_piston as op

__all__ = ["opposed_piston", "reactor_state"]


def opposed_piston(params: ec.EccentricCam, **machine) -> op.OpposedPiston:
    """The reactor on the drive ``params``: the machine's fields ``machine`` (SI) and the
    drive's smallest gap change ``Delta_min = 2 (sqrt(Rc^2 - e^2) - Rc)`` (eq. 5).

    Parameters
    ----------
    params : EccentricCam
    **machine
        :class:`~rotorkin.machines.opposed_piston.OpposedPiston` fields other than
        ``gap_change_min`` (``device_length`` [m], ``bore`` [m], ``fluid``,
        ``initial_pressure`` [Pa], ``polytropic_exponent``, ``bulk_modulus`` [Pa]).

    Returns
    -------
    OpposedPiston
    """
    return op.OpposedPiston(**machine, gap_change_min=ec.gap_change_extreme(params)[0])


def reactor_state(params: ec.EccentricCam, reactor: op.OpposedPiston, inertia, speed,
                  beta) -> dict:  # fmt: skip
    """Volume, pressure, piston forces and shaft torques at the shaft angles ``beta``.

    Parameters
    ----------
    params : EccentricCam
    reactor : OpposedPiston
    inertia : (float, (float, float))
        ``J_shaft`` [kg*m^2] and the piston masses [kg].
    speed : float or sequence of float
        ``run.speed`` [rad/s].
    beta : ndarray, shape (n,)
        Shaft angles [rad].

    Returns
    -------
    dict of ndarray
        ``V``, ``dV``, ``p`` (1, n); ``F`` (2, n); ``shaft``, ``inertia``, ``net``,
        ``J_eq``, ``omega``, ``omega_dot`` (n,).
    """
    m = ec.motion(params, beta)
    V, dV, _, _ = op.enclosed_volume(reactor, m)
    p, _ = op.pressure(reactor, m)
    F = tq.member_torques(p, op.volume_derivatives_dq(reactor, m))
    shaft = tq.shaft_torque_from_members(F, m.dq)
    omega, omega_dot, _ = shaft_speed(beta, speed, ec.period(params))
    js, masses = inertia
    t_in = tq.inertia_torque(js, masses, m.dq, m.d2q, omega, omega_dot)
    return {
        "V": V,
        "dV": dV,
        "p": p,
        "F": F,
        "shaft": shaft,
        "inertia": t_in,
        "net": shaft - t_in,
        "J_eq": tq.equivalent_inertia(js, masses, m.dq),
        "omega": omega,
        "omega_dot": omega_dot,
    }
