"""The vane pump's two impellers as workshop parts, on any drive that carries the pump.

The pump of :mod:`rotorkin.machines.vane_pump`: two coaxial impellers, each a hub
of radius ``R_h`` carrying ``Z`` vanes of angular width ``gamma`` that reach the
casing radius ``R_c``, over the axial width ``w``; each impeller drawn at ``theta
= 0`` in the pump frame, its vanes at :func:`rotorkin.machines.vane_pump.vane_angles`.
Derived here (the paper gives no pump design):

* **Nested hubs.** Both impellers' vanes span the whole working width, so their hubs
  cannot: they are stacked axially inside ``R_h``. Impeller 2 sits on a hollow shaft
  (bore ``export.sleeve_bore``) entering from the drive side ``z = 0``; its hub fills
  ``c_s <= z <= w/2 - c_h/2``. Impeller 1 sits on the inner shaft (bore ``export.bore``),
  which passes through the hollow shaft; its hub fills ``w/2 + c_h/2 <= z <= w - c_s``.
  Each impeller is its whole section (hub and vanes) extruded over ``c_s <= z <= w - c_s``
  with a relief turned down to ``R_h + c_h`` over the other impeller's hub: the vane root
  runs on the other hub with the gap ``c_h`` of the leakage model
  (``machine.hub_clearance``), and the hubs face each other across ``c_h``. The two
  solids have no common volume.
* **Running gaps.** Vane tips at ``R_c - c_t`` (``machine.tip_clearance``), vanes short
  of the end covers by ``c_s`` (``machine.side_clearance``); a gap of the machine
  section that is 0 (the flow model's "no leakage") takes the export's running gap at
  the casing diameter (:func:`rotorkin.render.workshop.pair_gap`). Where the vanes of
  the two impellers come closer than ``c_h`` (the drive's widest vane closes the
  chambers completely, ``phi_min = 0``), each flank is moved into its vane by
  ``c_h/2``, parallel to the radius, so two vanes never come closer than ``c_h``.
* **Keyways** on each bore, at the centre line of the impeller's first vane.

Every edge is exact: arcs (hub, vane tips, bore) and lines (flanks, keyway).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from rotorkin.cams import edges as ce
from rotorkin.cams.planar import Curve, Part, Slab, circle_curve
from rotorkin.core.angles import fmt_deg, fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.machines import vane_pump as vp
from rotorkin.render import workshop as ws

__all__ = ["PUMP_SPACING", "Gaps", "pump_gaps", "flank_offset", "impeller_edges",
           "impeller_parts", "machine_type", "pump_parts"]  # fmt: skip

#: Axial space [m] between a drive's own parts and the pump beside them in the assembly.
PUMP_SPACING = 0.01


class Gaps(NamedTuple):
    """Running gaps of the pump's CAD [m]: vane tip to casing, vane root to the other hub
    (and hub to hub), vane side to end cover, and how far each flank moves into its vane."""

    tip: float
    hub: float
    side: float
    flank: float


def flank_offset(pump: vp.VanePump, gap: float) -> float:
    """How far each vane flank moves into its vane [m]: ``gap/2`` when two vanes come within
    ``gap`` of each other at the hub over a period (``R_h sin phi_min < gap``), else 0."""
    phi_min = float(pump.chamber_angle_range[0])
    close = phi_min < 0.5 * np.pi and float(pump.hub_radius) * np.sin(phi_min) < gap
    return 0.5 * float(gap) if close else 0.0


def pump_gaps(pump: vp.VanePump, cfg: dict) -> Gaps:
    """The gaps ``(tip, hub, side, flank offset)`` [m] of a config (module docstring)."""
    s, m = ws.settings(cfg), cfg.get("machine") or {}
    size = 2.0 * float(pump.casing_radius)
    tip, hub, side = (ws.pair_gap(s, size, float(m.get(k, 0.0)))
                      for k in ("tip_clearance", "hub_clearance", "side_clearance"))  # fmt: skip
    return Gaps(tip, hub, side, flank_offset(pump, hub))


def _corner(half: float, offset: float, r: float) -> float:
    """Polar angle of a flank moved in by ``offset`` at radius ``r``, from the vane centre."""
    return half - float(np.arcsin(offset / r))


def impeller_edges(centres, half: float, offset: float, r_hub: float, r_out: float) -> tuple:
    """Closed contour of a hub of radius ``r_hub`` with its vanes (counter-clockwise)."""
    c = np.sort(np.asarray(centres, dtype=float).ravel())
    th, to = _corner(half, offset, r_hub), _corner(half, offset, r_out)
    out = []
    for i, a in enumerate(c):
        nxt = c[(i + 1) % c.size] + (2.0 * np.pi if i + 1 == c.size else 0.0)
        out += [
            ce.Line((r_hub * np.cos(a - th), r_hub * np.sin(a - th)),
                    (r_out * np.cos(a - to), r_out * np.sin(a - to))),
            ce.Arc((0.0, 0.0), r_out, a - to, a + to),
            ce.Line((r_out * np.cos(a + to), r_out * np.sin(a + to)),
                    (r_hub * np.cos(a + th), r_hub * np.sin(a + th))),
            ce.Arc((0.0, 0.0), r_hub, a + th, nxt - th),
        ]  # fmt: skip
    return tuple(out)


def _hubs(s: ws.Settings, outlines, centres, tol):
    """The bores of impeller 1 (inner shaft) and 2 (hollow shaft): (hub_1, hub_2).

    ``export.bore = 0``: no bores, but for a ``sleeve_bore`` that is set.
    """
    if s.bore == 0.0:
        sleeve = 0.0 if s.sleeve_bore is None else s.sleeve_bore
        return None, ws.part_hub(s, outlines[1], "impeller_2", sleeve, "export.sleeve_bore",
                                 float(centres[1][0]))  # fmt: skip
    hub2 = ws.part_hub(s, outlines[1], "impeller_2", s.sleeve_bore, "export.sleeve_bore",
                       float(centres[1][0]))  # fmt: skip
    if hub2 is None:  # checks only, and no room for the default hollow shaft
        return ws.part_hub(s, outlines[0], "impeller_1", s.bore, "export.bore",
                           float(centres[0][0])), None  # fmt: skip
    sleeve = hub2.bore
    t1 = hub2.key.t1 if hub2.key is not None else 0.0
    wall = max(1e-3, 0.1 * sleeve)
    inner_max = sleeve - 2.0 * (t1 + wall)
    what = (f"a hollow shaft of {fmt_mm(sleeve)} (export.sleeve_bore) a wall of max(1 mm, "
            "sleeve_bore/10) under its keyseat")  # fmt: skip
    if s.bore is not None and s.bore > inner_max + 1e-12:
        most = ws.floor_mm(inner_max)
        raise ParameterError("export.bore", fmt_mm(s.bore),
                             f"bore <= {most}, the largest that leaves {what}")  # fmt: skip
    bore = s.bore
    low = ws.KEYWAY_RANGE[0] if s.keyway else 1e-3
    if bore is None:
        bore = ws.round_bore(inner_max)
        if bore < low and s.check_only:
            return None, hub2
        if bore < low:
            room = ws.largest_bore(outlines[1], s.bore_fit, s.keyway)
            raise ParameterError(
                "export.sleeve_bore", fmt_mm(sleeve),
                f"sleeve_bore >= {fmt_mm(low + 2.0 * (t1 + wall))}, a hollow shaft round a "
                f"shaft of {fmt_mm(low)} (impeller 2 has room for {ws.floor_mm(room)})",
            )  # fmt: skip
    hub1 = ws.part_hub(s, outlines[0], "impeller_1", bore, "export.bore", float(centres[0][0]))
    return hub1, hub2


def impeller_parts(pump: vp.VanePump, motion0, cfg: dict, tolerance: float,
                   check_only: bool = False) -> list[Part]:  # fmt: skip
    """Both impellers as :class:`~rotorkin.cams.planar.Part` s with bores, keyways and gaps.

    Parameters
    ----------
    pump : VanePump
    motion0 : rotorkin.core.motion.Motion
        The impellers' motion at ``theta = 0``.
    cfg : dict
        Validated config (SI): ``[export]`` (bores, fits, gaps) and ``[machine]`` gaps.
    tolerance : float
        Chordal tolerance of the polygons (STL, CSV) [m].
    check_only : bool
        For the checks of every command (:class:`rotorkin.render.workshop.Settings`).

    Curves: ``profile`` (PROFILE: the hub with its vanes), ``bore`` (BORE), ``relief``
    (RELIEF: the circle ``R_h + c_h`` the vane roots are turned down to over the other
    impeller's hub, a cut of the part), ``casing`` (CASING, reference). Raises
    :class:`ParameterError` named ``export.bore`` / ``export.sleeve_bore`` when a bore does
    not fit.
    """
    g = pump_gaps(pump, cfg)
    rh, rc, w = float(pump.hub_radius), float(pump.casing_radius), float(pump.axial_width)
    half = 0.5 * float(pump.vane_angle)
    if g.tip >= rc - rh - g.hub or 2.0 * g.side + g.hub >= w:
        raise ParameterError("export.running_clearance", fmt_mm(max(g.tip, g.side, g.hub)),
                             "gaps that leave the vanes some length and width")  # fmt: skip
    if _corner(half, g.flank, rh) <= 0.0:
        raise ParameterError("export.running_clearance", fmt_mm(2.0 * g.flank),
                             f"gap < {fmt_mm(2.0 * rh * np.sin(half))}, the vane's width at "
                             "the hub")  # fmt: skip
    s = ws.settings(cfg, check_only)
    centres = vp.vane_angles(pump, motion0).reshape(2, -1)
    r_out = rc - g.tip
    full = [impeller_edges(centres[k], half, g.flank, rh, r_out) for k in (0, 1)]
    outlines = [ce.chain_polygon(e, tolerance) for e in full]
    hubs = _hubs(s, outlines, centres, tolerance)
    mid_lo, mid_hi = 0.5 * w - 0.5 * g.hub, 0.5 * w + 0.5 * g.hub
    # the relief round the vane roots, over the other impeller's hub: impeller 1 (far from
    # the drive) keeps its hub from mid_hi on, impeller 2 (near) up to mid_lo
    reliefs = ((g.side, mid_hi), (mid_lo, w - g.side))
    casing = circle_curve("casing", "CASING", (0.0, 0.0), rc, tolerance)
    relief = circle_curve("relief", "RELIEF", (0.0, 0.0), rh + g.hub, tolerance)
    parts = []
    for k in (0, 1):
        profile = Curve("profile", "PROFILE", outlines[k], True, None, full[k])
        holes = () if hubs[k] is None else (hubs[k].contour(tolerance),)
        v0, v1 = reliefs[k]
        h0, h1 = (v1, w - g.side) if k == 0 else (g.side, v0)
        shaft = "the inner shaft" if k == 0 else "a hollow shaft around the inner shaft"
        notes = (
            f"on {shaft}: " + ("no bore" if hubs[k] is None else hubs[k].describe()),
            f"hub z = {fmt_mm(h0)} .. {fmt_mm(h1)}; vanes z = {fmt_mm(g.side)} .. "
            f"{fmt_mm(w - g.side)}, relieved to r = {fmt_mm(rh + g.hub)} (RELIEF) over z = "
            f"{fmt_mm(v0)} .. {fmt_mm(v1)}, round the other impeller's hub",
            f"running gaps: vane tip {fmt_mm(g.tip)} to the casing R = {fmt_mm(rc)}, vane root "
            f"and hub faces {fmt_mm(g.hub)}, vane sides {fmt_mm(g.side)}, flanks moved in "
            f"{fmt_mm(g.flank)}",
        )
        parts.append(Part(
            name=f"impeller_{k + 1}",
            outline=profile,
            thickness=w - 2.0 * g.side,
            curves=(profile, *holes, relief, casing),
            title=f"impeller {k + 1}: hub {fmt_mm(rh)}, {pump.vanes_per_impeller} vanes of "
            f"{fmt_deg(pump.vane_angle)} to {fmt_mm(r_out)}, drawn at theta = 0 in the pump frame",
            holes=holes,
            slabs=(Slab(g.side, w - g.side, (profile,), holes, "impeller"),),
            cuts=(Slab(v0, v1, (relief,), (), "relief"),),
            hub=hubs[k],
            notes=notes,
            gaps=(("vane tip to casing", g.tip), ("vane root to hub, hub to hub", g.hub),
                  ("vane side to end cover", g.side), ("each flank moved in", g.flank)),
        ))  # fmt: skip
    return parts


def machine_type(cfg: dict) -> str:
    """``machine.type`` of a validated config ("" when it has none)."""
    return str((cfg.get("machine") or {}).get("type") or "")


def pump_parts(cfg: dict, law, tolerance: float, z: float = 0.0,
               check_only: bool = False) -> list[Part]:  # fmt: skip
    """The impellers of the vane pump a drive carries (``machine.type = "vane_pump"``).

    The pump is mounted on the drive's law as :func:`rotorkin.vane.machines.setup` mounts
    it; its parts are placed ``z`` [m] along the axis (beside the drive's own parts).
    """
    from dataclasses import replace

    from rotorkin.cams.planar import Placement
    from rotorkin.vane.machines import setup

    pump = setup("vane_pump", cfg, law).model
    parts = impeller_parts(pump, law.motion(0.0), cfg, tolerance, check_only)
    return [replace(p, placement=Placement(z=float(z))) for p in parts]
