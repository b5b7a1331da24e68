"""The wobble-cam engine as one STEP assembly of named parts, placed at a shaft angle.

Parts are built once in their bodies' frames (:mod:`rotorkin.drives.wobble_cam.cad_parts`)
and placed by the bodies' rotations at theta
(:func:`rotorkin.drives.wobble_cam.cad_layout.body_rotations`); the assembly is
written by :func:`rotorkin.render.workshop.write_step` in mm: every part is a product
named as below, the top product is named after the export, the file header carries the
config's title.

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
from rotorkin.render import workshop as ws

__all__ = ["Part", "build_parts", "placed_parts", "write_assembly"]


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


def build_parts(layout: Layout, tol: float, progress=None) -> list[Part]:
    """Every part of the assembly, each in its body's frame [mm].

    ``progress(label, done, total)`` (optional) is called before each group of parts.
    """
    groups = (
        ("cam", lambda: [Part(n, "cam", s) for n, s in cp.cam_parts(layout, tol)]),
        ("z_shaft", lambda: [Part("z_shaft", "z_shaft", cp.z_shaft(layout))]),
        ("plate", lambda: [Part(n, "plate", s) for n, s in cp.plate_parts(layout)]),
        ("rotor_1", lambda: [Part(n, "rotor_1", s) for n, s in cp.rotor_parts(layout, 1)]),
        ("rotor_2", lambda: [Part(n, "rotor_2", s) for n, s in cp.rotor_parts(layout, 2)]),
        ("casing", lambda: [Part("casing", "casing", cp.casing(layout))]),
    )
    out = []
    for i, (label, build) in enumerate(groups):
        if progress is not None:
            progress(f"step {label}", i, len(groups) + 1)
        out += build()
    return out


def placed_parts(parts: list[Part], layout: Layout, theta: float = 0.0) -> list:
    """``[(name, Solid)]`` of the parts placed at the shaft angle theta [rad] (fixed frame)."""
    rot = body_rotations(layout, np.asarray(float(theta)))
    return [(p.name, cp.placed(p.solid, rot[p.body])) for p in parts]


def write_assembly(
    parts: list[Part], layout: Layout, path, name: str, title: str = "", theta: float = 0.0
):
    """Write the parts placed at theta as one STEP assembly (AP214, mm).

    The assembly product is ``name``, each component and its product carries the part's
    name, the header the title (:func:`rotorkin.render.workshop.write_step`).
    """
    rot = body_rotations(layout, np.asarray(float(theta)))
    items = [(p.name, cp.placed(p.solid, rot[p.body]), (0.0, 0.0, 0.0, 0.0)) for p in parts]
    return ws.write_step(path, items, name, title, assembly=True)
