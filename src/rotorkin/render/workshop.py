"""Workshop details of CAD parts: keyed shaft bores, ISO 286 fits, named STEP assemblies.

Shared by every drive's CAD (planar cams, discs, impellers, gears, and any part a
drive writes itself). Lengths in m inside, mm in the tables (as the standards
print them) and in the files.

* **Parallel keys**: :data:`KEYWAYS`, DIN 6885-1:1968 (drive-type parallel keys,
  keyways, deep pattern; the same cross-sections as ISO/R 773): for a shaft of
  diameter ``d`` over ``d_over`` up to ``d_to`` the key ``b x h``, the shaft keyseat
  depth ``t1`` and the hub keyway depth ``t2``; the hub keyway's bottom is
  ``d + t2`` from the far side of the bore, i.e. ``d/2 + t2`` from the axis along
  the key's centre line. Hub keyway width: ISO JS9 (normal fit; symmetric, so the
  model carries the nominal ``b``), depth tolerance ``+0.1 mm`` (``d <= 22 mm``),
  ``+0.2 mm`` (to 130 mm) or ``+0.3 mm``, modelled at the nominal depth.
* **Fits**: the ISO 286 tables and limits of :mod:`rotorkin.analysis.fits`
  (re-exported here: :data:`IT`, :data:`SHAFT_DEVIATIONS`, :func:`fit_limits`,
  :func:`running_gap`); holes of position H (``EI = 0``). A bore is modelled at the
  middle of its hole zone (``H7``: ``d + IT7/2``), the usual basis of a CAM program;
  a running gap at half the mean diametral clearance of a running fit
  (:func:`running_gap`).
* **Hub wall**: :func:`hub_wall` measures the smallest wall between a bore with its
  keyway and a part's outline; rotorkin asks for :func:`wall_needed`, ``max(1 mm,
  d/4)`` beyond the keyway's bottom (a keyed steel hub of about 1.7 d outer
  diameter, at the lean end of common practice), and :func:`largest_bore` finds the
  largest bore that leaves it (stated in the error when a bore does not fit).
* **STEP** (:mod:`rotorkin.render.step`, re-exported here): :func:`write_step` writes
  named solids as one product each, or as one assembly of placed components, with the
  title in the header (``FILE_DESCRIPTION``), units mm; :func:`read_step` reads names,
  placed solids and the header back.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.analysis.fits import IT, SHAFT_DEVIATIONS, fit_limits, running_gap
from rotorkin.cams import edges as ce
from rotorkin.cams.planar import Curve
from rotorkin.core.angles import fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.render.step import read_step, write_step

__all__ = [
    "Settings",
    "settings",
    "part_hub",
    "pair_gap",
    "configured",
    "with_hub",
    "key_angle",
    "floor_mm",
    "KEYWAYS",
    "Key",
    "keyway_for",
    "IT",
    "SHAFT_DEVIATIONS",
    "BORE_FITS",
    "RUNNING_FITS",
    "fit_limits",
    "running_gap",
    "Hub",
    "make_hub",
    "hub_wall",
    "wall_needed",
    "largest_bore",
    "round_bore",
    "write_step",
    "read_step",
]

_MM = 1e-3

#: DIN 6885-1 parallel keys: (d over, d up to, b, h, t1, t2) [mm].
KEYWAYS = (
    (6, 8, 2, 2, 1.2, 1.0), (8, 10, 3, 3, 1.8, 1.4), (10, 12, 4, 4, 2.5, 1.8),
    (12, 17, 5, 5, 3.0, 2.3), (17, 22, 6, 6, 3.5, 2.8), (22, 30, 8, 7, 4.0, 3.3),
    (30, 38, 10, 8, 5.0, 3.3), (38, 44, 12, 8, 5.0, 3.3), (44, 50, 14, 9, 5.5, 3.8),
    (50, 58, 16, 10, 6.0, 4.3), (58, 65, 18, 11, 7.0, 4.4), (65, 75, 20, 12, 7.5, 4.9),
    (75, 85, 22, 14, 9.0, 5.4), (85, 95, 25, 14, 9.0, 5.4), (95, 110, 28, 16, 10.0, 6.4),
    (110, 130, 32, 18, 11.0, 7.4), (130, 150, 36, 20, 12.0, 8.4),
    (150, 170, 40, 22, 13.0, 9.4), (170, 200, 45, 25, 15.0, 10.4),
    (200, 230, 50, 28, 17.0, 11.4),
)  # fmt: skip
#: Smallest and largest bore with a keyway from :data:`KEYWAYS` [m].
KEYWAY_RANGE = (KEYWAYS[0][0] * _MM, KEYWAYS[-1][1] * _MM)

#: Fits of a hub on its shaft (``export.bore_fit``): what each is for.
BORE_FITS = {
    "H7/g6": "sliding fit: slides on by hand, locates accurately (ISO 286 hole basis)",
    "H7/h6": "locational clearance fit: snug, assembled by hand",
    "H7/k6": "locational transition fit: pressed on lightly, for keyed hubs under shock",
}
#: Fits that set the running gaps (``export.running_fit``): what each is for.
RUNNING_FITS = {
    "H8/f7": "close running fit: accurate running at moderate speed",
    "H9/d9": "free running fit: larger gaps, high speeds or temperatures",
    "H7/g6": "sliding fit: the smallest gap that still runs",
}


@dataclass(frozen=True)
class Key:
    """One row of :data:`KEYWAYS`, in m: key ``b x h``, depths ``t1`` (shaft), ``t2`` (hub)."""

    b: float
    h: float
    t1: float
    t2: float

    @property
    def t2_tolerance(self) -> float:
        """Upper tolerance of the hub keyway depth [m] (DIN 6885-1: +0.1 mm for bores up to
        22 mm, +0.2 mm up to 130 mm, +0.3 mm above)."""
        return (0.1 if self.b <= 6 * _MM else 0.2 if self.b <= 32 * _MM else 0.3) * _MM


def keyway_for(bore: float) -> Key | None:
    """The DIN 6885-1 key of a shaft of diameter ``bore`` [m]; None outside 6..230 mm."""
    d = float(bore) / _MM
    for lo, hi, b, h, t1, t2 in KEYWAYS:
        if (lo < d or (lo == KEYWAYS[0][0] and d >= lo)) and d <= hi + 1e-9:
            return Key(b * _MM, h * _MM, t1 * _MM, t2 * _MM)
    return None


def round_bore(d: float) -> float:
    """A bore [m] rounded down to a shaft size: whole mm to 20 mm, even mm to 50 mm, 5 mm to
    150 mm, 10 mm above (rotorkin's rounding of a default bore; at least 1 mm)."""
    mm = float(d) / _MM
    step = 1.0 if mm <= 20 else 2.0 if mm <= 50 else 5.0 if mm <= 150 else 10.0
    return max(1.0, np.floor(mm / step + 1e-9) * step) * _MM


# --- hubs -----------------------------------------------------------------------------------
@dataclass(frozen=True)
class Hub:
    """A shaft bore with its keyway, in a part's frame.

    Attributes
    ----------
    bore : float
        Nominal diameter ``d`` [m] (the shaft's).
    diameter : float
        Diameter as modelled: the middle of the hole's zone of ``fit`` [m].
    fit : str
        ``"H7/g6"``, ...
    key : Key or None
        The DIN 6885-1 key (None: a plain bore).
    angle : float
        Direction of the keyway from the bore's centre [rad].
    centre : tuple of float
        Centre of the bore [m].
    """

    bore: float
    diameter: float
    fit: str
    key: Key | None
    angle: float = 0.0
    centre: tuple[float, float] = (0.0, 0.0)

    def edges(self) -> tuple:
        """The bore's closed contour, counter-clockwise: circle, or arc + three keyway lines."""
        r = 0.5 * self.diameter
        if self.key is None:
            return (ce.Arc(self.centre, r, self.angle, self.angle + 2.0 * np.pi),)
        b, top = 0.5 * self.key.b, 0.5 * self.bore + self.key.t2
        y = float(np.sqrt(r * r - b * b))
        phi = float(np.arctan2(b, y))  # corner angle from the key's centre line
        local = (
            ce.Arc((0.0, 0.0), r, 0.5 * np.pi + phi, 2.5 * np.pi - phi),
            ce.Line((b, y), (b, top)),
            ce.Line((b, top), (-b, top)),
            ce.Line((-b, top), (-b, y)),
        )
        return ce.moved(local, self.angle - 0.5 * np.pi, self.centre)

    def contour(self, tolerance: float) -> Curve:
        """The bore as a :class:`Curve` on layer ``BORE`` (exact edges + polygon)."""
        e = self.edges()
        return Curve("bore", "BORE", ce.chain_polygon(e, tolerance), True, None, e)

    def describe(self) -> str:
        """One line for a drawing: bore, fit, keyway and the clearance range of the fit."""
        (_, es_h), (ei_s, es_s) = fit_limits(self.fit, self.bore)
        d, hole, shaft = self.bore / _MM, *self.fit.split("/")
        text = (f"bore {d:g} {hole} (+0/+{es_h / _MM:.3f}) for a {d:g} {shaft} shaft, clearance "
                f"{-es_s / _MM:.3f} .. {(es_h - ei_s) / _MM:.3f} mm")  # fmt: skip
        if self.key is not None:
            k = self.key
            text += (f"; keyway {k.b / _MM:g} JS9 x d + {k.t2 / _MM:g} (+{k.t2_tolerance / _MM:g}) "
                     f"for a DIN 6885-1 key {k.b / _MM:g} x {k.h / _MM:g}")  # fmt: skip
        return text


def make_hub(bore: float, fit: str, keyway: bool, angle: float = 0.0, centre=(0.0, 0.0)) -> Hub:
    """A :class:`Hub` of nominal ``bore`` [m], drawn at the middle of the hole zone of ``fit``."""
    (ei, es), _ = fit_limits(fit, bore)
    key = keyway_for(bore) if keyway else None
    c = (float(centre[0]), float(centre[1]))
    return Hub(float(bore), float(bore) + 0.5 * (ei + es), fit, key, float(angle), c)


def wall_needed(bore: float) -> float:
    """Smallest hub wall beyond the keyway's bottom (or the bore): ``max(1 mm, d/4)`` [m]."""
    return max(1.0 * _MM, 0.25 * float(bore))


def hub_wall(outline, hub: Hub) -> float:
    """Smallest distance from the outline's points to the bore and its keyway [m].

    Parameters
    ----------
    outline : ndarray, shape (n, 2)
        Points of the part's outer contour [m] (a polygon within the export tolerance).
    hub : Hub

    Returns
    -------
    float
        Negative when a point lies inside the bore or keyway.
    """
    p = np.asarray(outline, dtype=float) - np.asarray(hub.centre)
    c, s = np.cos(hub.angle - 0.5 * np.pi), np.sin(hub.angle - 0.5 * np.pi)
    x, y = c * p[:, 0] + s * p[:, 1], -s * p[:, 0] + c * p[:, 1]  # keyway along +y
    dist = np.hypot(x, y) - 0.5 * hub.diameter
    if hub.key is not None:
        b, top = 0.5 * hub.key.b, 0.5 * hub.bore + hub.key.t2
        dx, dy = np.abs(x) - b, np.maximum(y - top, -y)
        box = np.hypot(np.maximum(dx, 0.0), np.maximum(dy, 0.0)) + np.minimum(np.maximum(dx, dy), 0)
        dist = np.minimum(dist, box)
    return float(np.min(dist))


def largest_bore(outline, fit: str, keyway: bool, angle: float = 0.0, centre=(0.0, 0.0),
                 resolution: float = 1e-5) -> float:  # fmt: skip
    """Largest nominal bore [m] whose hub wall (:func:`hub_wall`) is :func:`wall_needed`.

    Bisection to ``resolution``, rounded down to it; 0 when not even 1 mm fits (or, with
    a keyway, when no bore of the DIN 6885-1 range fits).
    """
    lo_d = KEYWAY_RANGE[0] if keyway else 1.0 * _MM
    hi_d = min(2.0 * float(np.min(np.hypot(*(np.asarray(outline) - centre).T))),
               KEYWAY_RANGE[1] if keyway else 0.5)  # fmt: skip

    def fits(d):
        return hub_wall(outline, make_hub(d, fit, keyway, angle, centre)) >= wall_needed(d)

    if hi_d <= lo_d or not fits(lo_d):
        return 0.0
    if fits(hi_d):
        return float(np.floor(hi_d / resolution) * resolution)
    while hi_d - lo_d > resolution:
        mid = 0.5 * (lo_d + hi_d)
        lo_d, hi_d = (mid, hi_d) if fits(mid) else (lo_d, mid)
    return float(np.floor(lo_d / resolution + 1e-9) * resolution)


# --- config ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class Settings:
    """The workshop keys of a config's ``[export]`` section (SI; None: derived).

    ``check_only``: the checks that every command makes (``DriveSpec.check_cam``) rather
    than an export: a bore the config sets is checked, a default bore that finds no room
    is left out instead of refused (only ``rotorkin export`` needs it).
    """

    bore: float | None = None
    sleeve_bore: float | None = None
    keyway: bool = True
    bore_fit: str = "H7/g6"
    running_fit: str = "H8/f7"
    running_clearance: float | None = None
    check_only: bool = False


def settings(cfg: dict, check_only: bool = False) -> Settings:
    """:class:`Settings` from a validated config (absent keys take the schema's defaults)."""
    e = cfg.get("export") or {}
    names = ("bore", "sleeve_bore", "keyway", "bore_fit", "running_fit", "running_clearance")
    return Settings(**{k: e[k] for k in names if k in e}, check_only=bool(check_only))


def configured(cfg: dict) -> bool:
    """Whether the config sets a bore or a running gap (``[export]``): only then do the checks
    of every command (``check_only``) build the parts to check them."""
    e = cfg.get("export") or {}
    return any(e.get(k) is not None for k in ("bore", "sleeve_bore", "running_clearance"))


def floor_mm(x: float) -> str:
    """A length [m] rounded down to 0.01 mm, as people read it: ``'35.61 mm'``."""
    return f"{np.floor(float(x) * 1e5 + 1e-6) / 100:g} mm"


def part_hub(s: Settings, outline, what: str, bore: float | None, key: str = "export.bore",
             angle: float = 0.0, centre=(0.0, 0.0)) -> Hub | None:  # fmt: skip
    """The checked bore of one part, or its default (the largest that fits, rounded down).

    None (no bore) when ``bore`` is 0, or when a default finds no room and ``s.check_only``.

    Parameters
    ----------
    s : Settings
    outline : ndarray, shape (n, 2)
        The part's outer contour [m] (its polygon within the export tolerance).
    what : str
        The part, for messages (``"impeller_1"``).
    bore : float or None
        The configured bore [m] (``s.bore``, or a hollow shaft's); None: the default;
        0: no bore.
    key : str
        Config key of the bore (for messages).
    angle : float
        Direction of the keyway [rad].
    centre : tuple of float
        Centre of the bore [m].

    Raises
    ------
    ParameterError
        Named by ``key``: a bore outside the keyway table, or one that leaves less
        than :func:`wall_needed` (the message states the largest that fits); a part too
        small for any bore.
    """
    d, short = bore, key.rsplit(".", 1)[-1]
    if d == 0.0:
        return None
    if s.keyway and d is not None and not KEYWAY_RANGE[0] <= d <= KEYWAY_RANGE[1]:
        raise ParameterError(key, fmt_mm(d), f"6 mm <= {short} <= 230 mm for a DIN 6885-1 "
                             "keyway (or export.keyway = false)")  # fmt: skip
    d_max = largest_bore(outline, s.bore_fit, s.keyway, angle, centre)
    rule = f"a wall of max(1 mm, {short}/4) beyond the " + ("keyway" if s.keyway else "bore")
    if d_max <= 0.0:
        if d is None and s.check_only:
            return None
        least = "6 mm with a keyway" if s.keyway else "1 mm"
        raise ParameterError(key, "(default)" if d is None else fmt_mm(d),
                             f"{what} has no room for a bore of {least} and {rule}; "
                             f'{key} = "0 mm" exports it without a bore')  # fmt: skip
    if d is None:
        d = max(round_bore(d_max), KEYWAY_RANGE[0] if s.keyway else 0.0)
    elif d > d_max + 1e-12:
        raise ParameterError(key, fmt_mm(d), f"{short} <= {floor_mm(d_max)}, the largest that "
                             f"leaves {what} {rule}")  # fmt: skip
    return make_hub(d, s.bore_fit, s.keyway, angle, centre)


def with_hub(part, hub: Hub | None, tolerance: float, notes: tuple[str, ...] = ()):
    """``part`` (a plain plate) with ``hub`` cut through it: hole, ``bore`` curve, notes."""
    from dataclasses import replace

    if hub is None:
        return replace(part, notes=(*part.notes, "no bore (export.bore = 0 mm)", *notes))
    bore = hub.contour(tolerance)
    return replace(part, holes=(*part.holes, bore), curves=(*part.curves, bore), hub=hub,
                   notes=(*part.notes, hub.describe(), *notes))  # fmt: skip


def key_angle(outline, centre=(0.0, 0.0)) -> float:
    """Direction [rad] of the outline's point farthest from ``centre``: the thickest wall,
    where a keyway goes (the first of equal maxima, radii compared to 1 nm)."""
    p = np.asarray(outline, dtype=float) - np.asarray(centre, dtype=float)
    i = int(np.argmax(np.round(np.hypot(p[:, 0], p[:, 1]), 9)))
    return float(np.arctan2(p[i, 1], p[i, 0]))


def pair_gap(s: Settings, size: float, given: float = 0.0) -> float:
    """Radial running gap of a pair of ``size`` [m] (a diameter): ``given`` when > 0, else
    ``export.running_clearance``, else :func:`running_gap` of ``export.running_fit`` (sizes
    past 500 mm take the 400..500 mm row of ISO 286)."""
    if given > 0.0:
        return float(given)
    if s.running_clearance is not None:
        return float(s.running_clearance)
    return running_gap(s.running_fit, min(float(size), 0.5))
