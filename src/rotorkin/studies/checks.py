"""Design checks with their margins: what a design must pass to be built, and how far it is.

A :class:`Check` compares one measured value of a design with its limit: a cam's
roller radius with the largest radius free of undercut, a peak pressure with
``limits.peak_pressure``, the clearance between a roller and the cam with 0. The
same checks are printed by ``rotorkin run`` and ``rotorkin export``, listed in the
report and used by ``rotorkin limits`` (a design is admissible when every check
passes); a drive adds its own (``DriveSpec.checks``) to the shared ones here:

* :func:`limit_checks`: every plausibility limit of :mod:`rotorkin.studies.limits`
  that the study's results measure (the worst result of each);
* :func:`profile_checks`: the checks of a planar cam's profile
  (:class:`rotorkin.cams.planar.ProfileCheck`).

The margin is positive when the check passes, in the unit of the value
(``limit - value`` for an upper limit, ``value - limit`` for a lower one).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rotorkin.studies.limits import LIMITS, limit_value, worst_result

__all__ = [
    "Check",
    "LIMIT_NAMES",
    "limit_checks",
    "profile_checks",
    "failed",
    "failure_line",
    "rows",
]


@dataclass(frozen=True)
class Check:
    """One check of a design.

    Attributes
    ----------
    name : str
        What is checked, for people (``"cam plate 1: roller radius against undercut"``).
    key : str
        The config key that moves the limit or the value most directly (the one to change).
    value, limit : float
        The measured value and its limit, in ``unit``.
    unit : str
        ``"mm"``, ``"deg"``, ``"bar"``, ``"MPa"``, ``"K"`` or ``""``.
    upper : bool
        True: the value must not exceed the limit; False: it must not fall below it.
    where : str
        Where the worst value occurs (a shaft angle, a part), or ``""``.
    """

    name: str
    key: str
    value: float
    limit: float
    unit: str
    upper: bool = True
    where: str = ""

    @property
    def margin(self) -> float:
        """How far the value is inside its limit (negative: past it), in ``unit``."""
        return self.limit - self.value if self.upper else self.value - self.limit

    @property
    def passed(self) -> bool:
        """True when the value is within its limit (a NaN value does not pass)."""
        return bool(self.margin >= 0.0)


def _fmt(value: float) -> str:
    if not math.isfinite(value):
        return "n/a"
    return f"{value:.4g}" if abs(value) < 1e4 else f"{value:.3g}"


def rows(checks) -> list[tuple[str, str, str, str, str]]:
    """Table rows ``(check, value, limit, margin, status)`` of ``checks``, units written."""
    out = []
    for c in checks:
        unit = f" {c.unit}" if c.unit else ""
        sense = "<=" if c.upper else ">="
        where = f" ({c.where})" if c.where else ""
        out.append((f"{c.name}{where}", f"{_fmt(c.value)}{unit}", f"{sense} {_fmt(c.limit)}{unit}",
                    f"{_fmt(c.margin)}{unit}", "ok" if c.passed else "FAILS"))  # fmt: skip
    return out


def failed(checks) -> list[Check]:
    """The checks of ``checks`` that do not pass."""
    return [c for c in checks if not c.passed]


def failure_line(c: Check) -> str:
    """One line saying why ``c`` fails, led by its config key (a refusal's own line when the
    check carries one in ``where``)."""
    if c.where.startswith(f"{c.key} = "):
        return f"{c.where} ({c.name})"
    unit = f" {c.unit}" if c.unit else ""
    sense = "<=" if c.upper else ">="
    where = f": {c.where}" if c.where else ""
    return (f"{c.key}: {c.name} fails ({c.value:.6g}{unit}, admissible {sense} "
            f"{c.limit:.6g}{unit}){where}")  # fmt: skip


def _number(value) -> float | None:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.number)):
        return None
    value = float(value)
    return value if math.isfinite(value) else None


#: What each plausibility limit's check is called.
LIMIT_NAMES = {
    "limits.peak_pressure": "peak gas pressure",
    "limits.peak_temperature": "peak gas temperature",
    "limits.pressure_angle": "peak pressure angle",
    "contact.allowable_stress": "peak contact stress",
}


def limit_checks(summary: dict, cfg: dict, columns: dict | None = None) -> list[Check]:
    """One :class:`Check` per plausibility limit the results measure (the worst result).

    A limit none of the study's results measures (no pressure in a drive without a
    machine, no contact stress without forces) gives no check.
    """
    out = []
    for key, (_, _, unit, scale) in LIMITS.items():
        worst = worst_result(key, summary, columns)
        if worst is not None:
            limit = limit_value(cfg, key) * scale
            out.append(Check(LIMIT_NAMES[key], key, worst[1], limit, unit, True, worst[0]))
    return out


def profile_checks(label: str, check, pressure_angle_limit: float) -> list[Check]:
    """The checks of one planar cam profile (:class:`rotorkin.cams.planar.ProfileCheck`).

    * the roller radius against the smallest convex radius of curvature of the pitch
      curve (a larger roller undercuts the profile);
    * the actual profile's nearest point to the axis (> 0);
    * the smallest clearance between the roller and the rest of the cam (>= 0);
    * the largest pressure angle against ``pressure_angle_limit`` [rad].

    The roller-to-cam clearance is checked where another flank faces a roller.
    """
    deg = math.degrees
    at = f"at {deg(check.min_convex_radius_alpha):.4g} deg"
    out = [
        Check(f"{label}: roller radius against undercut", "cam.roller_radius",
              check.roller_radius * 1e3, check.min_convex_radius * 1e3, "mm", True,
              f"pitch curve's sharpest convex bend {at}"),
        Check(f"{label}: actual profile clear of the axis", "cam.roller_radius",
              check.profile_min_radius * 1e3, 0.0, "mm", False),
        Check(f"{label}: pressure angle", "limits.pressure_angle",
              deg(check.max_pressure_angle), deg(pressure_angle_limit), "deg", True,
              f"at {deg(check.max_pressure_angle_alpha):.4g} deg"),
    ]  # fmt: skip
    if math.isfinite(check.min_clearance):
        where = f"roller at {deg(check.min_clearance_alpha):.4g} deg"
        out.append(Check(f"{label}: roller-to-cam clearance", "cam.roller_radius",
                         check.min_clearance * 1e3, 0.0, "mm", False, where))  # fmt: skip
    return out
