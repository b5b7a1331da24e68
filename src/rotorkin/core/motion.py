"""Motion of the two working members of a drive, and the chain rule to order 3.

Kinematic coefficients (derivatives with respect to the input angle ``theta``)
are the currency of rotorkin: time rates follow as ``q' omega``,
``q'' omega^2 + q' omega_dot`` and ``q''' omega^3 + 3 q'' omega omega_dot + q' omega_ddot``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Motion", "compose", "time_derivatives"]


@dataclass(frozen=True)
class Motion:
    """Positions of two working members and their exact derivatives.

    Attributes
    ----------
    theta : ndarray, shape (...)
        Input-shaft angle [rad].
    q : ndarray, shape (2, ...)
        Member positions, ``q[0]`` and ``q[1]`` [rad for rotating members,
        m for pistons].
    dq, d2q, d3q : ndarray, shape (2, ...)
        First, second and third derivatives of ``q`` with respect to ``theta``
        [unit of q per rad^n].
    members : tuple of str
        Names of the two members, e.g. ``("rotor 1", "rotor 2")``.
    unit : str
        ``"rad"`` or ``"m"``: the unit of ``q``.
    """

    theta: np.ndarray
    q: np.ndarray
    dq: np.ndarray
    d2q: np.ndarray
    d3q: np.ndarray
    members: tuple[str, str] = ("member 1", "member 2")
    unit: str = "rad"

    @property
    def relative(self):
        """``q[1] - q[0]`` and its three derivatives, as a tuple of 4 arrays."""
        return tuple(a[1] - a[0] for a in (self.q, self.dq, self.d2q, self.d3q))

    def in_time(self, omega, omega_dot=0.0, omega_ddot=0.0):
        """Velocity, acceleration and jerk of both members in time.

        Parameters
        ----------
        omega : float or array_like
            Input-shaft speed [rad/s].
        omega_dot, omega_ddot : float or array_like, optional
            Its first and second time derivatives [rad/s^2, rad/s^3].

        Returns
        -------
        (v, a, j) : tuple of ndarray, shape (2, ...)
            [unit/s, unit/s^2, unit/s^3].
        """
        return time_derivatives(self.dq, self.d2q, self.d3q, omega, omega_dot, omega_ddot)


def time_derivatives(d1, d2, d3, omega, omega_dot=0.0, omega_ddot=0.0):
    """Time derivatives of ``q(theta(t))`` from its kinematic coefficients.

    ``v = q' w``, ``a = q'' w^2 + q' w_dot``,
    ``j = q''' w^3 + 3 q'' w w_dot + q' w_ddot``.
    """
    w, wd, wdd = (np.asarray(v, dtype=float) for v in (omega, omega_dot, omega_ddot))
    v = d1 * w
    a = d2 * w**2 + d1 * wd
    j = d3 * w**3 + 3.0 * d2 * w * wd + d1 * wdd
    return v, a, j


def compose(f, g):
    """Derivatives of ``f(g(theta))`` up to order 3 (Faa di Bruno).

    Parameters
    ----------
    f : sequence of 4 arrays
        ``f(u), f'(u), f''(u), f'''(u)`` evaluated at ``u = g(theta)``.
    g : sequence of 4 arrays
        ``g, g', g'', g'''`` with respect to ``theta``.

    Returns
    -------
    tuple of 4 ndarrays
        ``h, h', h'', h'''`` of ``h = f o g``.
    """
    f0, f1, f2, f3 = f
    _, g1, g2, g3 = g
    g1_2 = g1 * g1  # not g1**3: numpy's pow takes ~40 ns a value where g1 is near 0
    return (
        f0,
        f1 * g1,
        f2 * g1_2 + f1 * g2,
        f3 * (g1_2 * g1) + 3.0 * f2 * g1 * g2 + f1 * g3,
    )
