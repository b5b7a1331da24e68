"""Physical bounds shared by the drives' config schemas.

Every numeric key of a drive's schema carries its admissible range (``ge``/``le``/
``gt``/``lt``, stated in its description); the ones shared by all drives live here.
"""

from __future__ import annotations

from pydantic import Field

__all__ = [
    "INERTIA_MAX",
    "LENGTH_MAX",
    "PRESSURE_MIN",
    "PRESSURE_MAX",
    "TORQUE_MAX",
    "TEMPERATURE_MIN",
    "TEMPERATURE_MAX",
    "SPEED_FLUCTUATION_MIN",
    "speed_fluctuation",
    "gear_pressure_angle",
]

#: Largest inertia of any member [kg*m^2] (a ship engine's flywheel is about 1e4).
INERTIA_MAX = 1e5
#: Largest length of any part [m].
LENGTH_MAX = 10.0
#: Smallest and largest absolute pressure [Pa] (0.01 bar, 1000 bar).
PRESSURE_MIN, PRESSURE_MAX = 1e3, 1e8
#: Smallest and largest gas temperature [K].
TEMPERATURE_MIN, TEMPERATURE_MAX = 1.0, 5000.0
#: Largest magnitude of a load torque [N*m].
TORQUE_MAX = 1e6

#: Smallest wanted coefficient of speed fluctuation [-]: the flywheel's inertia grows as
#: 1 / C_s (generator sets ask for about 0.003).
SPEED_FLUCTUATION_MIN = 1e-4


def speed_fluctuation():
    """A fresh field of ``machine.speed_fluctuation``: 0.02, ``0.0001 <= C_s < 1``."""
    return Field(
        0.02,
        ge=SPEED_FLUCTUATION_MIN,
        lt=1.0,
        description="wanted coefficient of speed fluctuation, for the flywheel (0.0001 <= C_s < 1)",
    )


def gear_pressure_angle(what: str = "pressure angle of the gear teeth"):
    """A fresh gear pressure-angle field: 20 deg, ``10 deg <= alpha <= 35 deg``."""
    return Field(
        "20 deg",
        ge=0.17453292519943295,
        le=0.6108652381980153,
        description=f"{what} (10 deg <= pressure_angle <= 35 deg)",
    )
