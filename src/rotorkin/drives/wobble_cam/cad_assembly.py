"""The wobble-cam engine as one STEP assembly of named parts, placed at a shaft angle.

Parts are built once in their bodies' frames (:mod:`rotorkin.drives.wobble_cam.cad_parts`)
and placed by the bodies' rotations at theta
(:func:`rotorkin.drives.wobble_cam.cad_layout.body_rotations`); the assembly is a
build123d ``Compound(children=..., label=title)`` written with ``export_step`` in mm:
every part is a product named as below, the top product and the file header carry
the config's title.

Part names: ``cam_half_1`` (``x >= 0``), ``cam_half_2``, ``cam_lobe_<groove>_<half>`` (the
lobes freed by the shaft slots), ``z_shaft``, ``plate``, ``roller_shaft_<k>``,
``roller_<k>``, ``rail_roller_<k>`` (``k`` in ``1, 1p, 2, 2p`` for rollers 1, 1', 2, 2'),
``rotor_1``, ``rotor_2``, ``rail_<k>``, ``casing``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.drives.wobble_cam import cad_parts as cp
from rotorkin.drives.wobble_cam.cad_layout import Layout, body_rotations
from rotorkin.render.cad import build123d_module

__all__ = ["Part", "build_parts", "placed_parts", "assembly", "write_assembly"]


@dataclass(frozen=True)
class Part:
    """A part of the assembly in its body's frame.

    Attributes
    ----------
    name : str
        Product name in the STEP file.
    body : str
        The rigid body that carries it (:data:`rotorkin.drives.wobble_cam.cad_layout.BODIES`).
    solid : build123d.Solid
        In the body's frame [mm].
    """

    name: str
    body: str
    solid: object


def build_parts(layout: Layout, tol: float) -> list[Part]:
    """Every part of the assembly, each in its body's frame [mm]."""
    out = [Part(n, "cam", s) for n, s in cp.cam_parts(layout, tol)]
    out.append(Part("z_shaft", "z_shaft", cp.z_shaft(layout)))
    out += [Part(n, "plate", s) for n, s in cp.plate_parts(layout)]
    for k in (1, 2):
        out += [Part(n, f"rotor_{k}", s) for n, s in cp.rotor_parts(layout, k)]
    out.append(Part("casing", "casing", cp.casing(layout)))
    return out


def placed_parts(parts: list[Part], layout: Layout, theta: float = 0.0) -> list:
    """``[(name, Solid)]`` of the parts placed at the shaft angle theta [rad] (fixed frame)."""
    rot = body_rotations(layout, np.asarray(float(theta)))
    return [(p.name, cp.placed(p.solid, rot[p.body])) for p in parts]


def assembly(parts: list[Part], layout: Layout, title: str, theta: float = 0.0):
    """The parts placed at theta as a labelled build123d Compound (the STEP assembly)."""
    bd = build123d_module()
    children = []
    for name, solid in placed_parts(parts, layout, theta):
        solid.label = name
        children.append(solid)
    return bd.Compound(children=children, label=title)


def write_assembly(compound, path) -> None:
    """Write the assembly as STEP (AP214, mm) with its product names and title."""
    bd = build123d_module()
    bd.export_step(compound, str(path), unit=bd.Unit.MM)
