"""Layout of the wobble-cam engine's parts for the CAD assembly: sizes and motions (SI).

Every size is a config key or derived from them (``[cam]``, ``[cad]``, ``[drive]``,
``[machine]``); see ``docs/cams.md`` ("Workshop assembly"). The parts are rigid bodies
turning about axes through the plate centre O, so a placement is a rotation matrix:

* cam shell ``A_x(psi)``, ``psi = -theta`` (cam frame x4y4z4, eq. 9);
* Z-shaft ``A_x(theta)`` (shaft frame x1y1z1, eq. 4);
* plate with its roller shafts and rollers ``A_x(theta) A_y(phi) A_x(varphi)`` (plate
  frame x3y3z3, eq. 5: roller c along ``(0, sin c, cos c)``);
* rotor k with its rails ``A_x(Phi_k)`` (rotor frame: the rail of roller 1 or 2 in the
  half-plane ``y = 0, z > 0``, of roller 1' or 2' in ``y = 0, z < 0``);
* casing: fixed.

``A_x(t) = [[1, 0, 0], [0, cos t, sin t], [0, -sin t, cos t]]`` and
``A_y(t) = [[cos t, 0, sin t], [0, 1, 0], [-sin t, 0, cos t]]`` are the paper's matrices
(eq. 2-4), used as active rotations of the body frames.

Along the cam axis x: the plate and the cam shell at O; the rails around the shell, their
arms running out to +x, to the spokes of rotor 2 (slab a) and rotor 1 (slab b); rotor 1's
near disc, the cylinder (``machine.axial_width``), rotor 2's far disc. Rotor 2's sleeve
runs inside rotor 1's, both around the Z-shaft; the casing encloses everything.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, fields

import numpy as np

from rotorkin.analysis.fits import fit_clearance
from rotorkin.core.angles import fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.drives.wobble_cam import cam as sph
from rotorkin.drives.wobble_cam import engine as eng
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.machines import twin_rotor as tr
from rotorkin.studies.helpers import build_params

__all__ = ["Layout", "layout_from_config", "rot_x", "rot_y", "body_rotations", "BODIES"]

#: Rigid bodies of the assembly, each with the parts it carries (part name stems).
BODIES = ("cam", "z_shaft", "plate", "rotor_1", "rotor_2", "casing")


def rot_x(t):
    """``A_x(t)`` of shape (..., 3, 3): takes z to ``(0, sin t, cos t)`` (eq. 2, 4, 9)."""
    t = np.asarray(t, dtype=float)
    c, s = np.cos(t), np.sin(t)
    o, z = np.ones_like(t), np.zeros_like(t)
    return np.stack(
        [np.stack([o, z, z], -1), np.stack([z, c, s], -1), np.stack([z, -s, c], -1)], -2
    )


def rot_y(t):
    """``A_y(t)`` of shape (..., 3, 3) (eq. 3)."""
    t = np.asarray(t, dtype=float)
    c, s = np.cos(t), np.sin(t)
    o, z = np.ones_like(t), np.zeros_like(t)
    return np.stack(
        [np.stack([c, z, s], -1), np.stack([z, o, z], -1), np.stack([-s, z, c], -1)], -2
    )


@dataclass(frozen=True)
class Layout:
    """Sizes of the assembly's parts [m, rad] (see the module text and ``docs/cams.md``).

    Attributes are grouped by part: ``shaft_*`` the Z-shaft (journal radius, crank
    half-length, journal start ``x_j``); ``plate_*`` the plate (disc radius and half
    thickness, hub radius and half-length, bore); ``rshaft_*`` the roller shafts (radius,
    inner and outer end); ``roller_bore``, ``rail_roller_*``; ``cam_*`` the cam's bores, slots
    and assembly windows; ``rail_*`` the rails (radii, polar angles from +x, half-widths,
    arm); ``slab_*``, ``sleeve_*``, ``disc``, ``cyl_*`` the rotors; ``case_*`` the casing.
    """

    drive: wc.WobbleCam
    cam: sph.SphericalCam
    machine: tr.TwinRotor
    piston_width: float
    piston_offset: float
    wall: float
    gap: float
    shaft_radius: float
    crank_half: float
    journal_start: float
    journal_end: tuple
    plate_radius: float
    plate_half: float
    hub_radius: float
    hub_half: float
    plate_bore: float
    rshaft_radius: float
    rshaft_inner: float
    rshaft_outer: float
    roller_bore: float
    rail_roller_radius: float
    rail_roller_length: float
    rail_radius: float
    cam_bore: float
    slot_half_width: float
    window_radius: float
    window_floor: float
    rail_inner: float
    rail_outer: float
    rail_angles: tuple
    rail_end_angle: float
    rail_channel: float
    rail_half_width: float
    arm_z: tuple
    slab_a: tuple
    slab_b: tuple
    sleeve_2: tuple
    sleeve_1: tuple
    disc: float
    cyl_x: tuple
    cyl_r: tuple
    case_x: tuple
    case_step: float
    case_radius: float


def _num(section: dict, key: str, default: float) -> float:
    value = section.get(key)
    return float(default if value is None else value)


def _machine(cfg: dict) -> tr.TwinRotor:
    section = cfg.get("machine") or {}
    names = {f.name for f in fields(tr.TwinRotor)}
    return build_params(tr.TwinRotor, "machine", {k: v for k, v in section.items() if k in names})


def _need(ok: bool, key: str, value: float, admissible: str) -> None:
    if not ok:
        raise ParameterError(key, fmt_mm(value), admissible)


def layout_from_config(cfg: dict, parts: tuple | None = None) -> Layout:
    """The layout of a validated wobble-cam config (SI); errors name the config key.

    ``parts``: the config's ``(drive, cam)`` if built already
    (:func:`rotorkin.drives.wobble_cam.cam.from_config`).

    Raises
    ------
    ParameterError
        A size that does not fit, named by its key with the admissible range:
        ``cam.bore_diameter``, ``cam.slot_clearance``, ``cad.roller_shaft_diameter``,
        ``cad.plate_radius``, ``cad.plate_thickness``, ``drive.plate_bearing_span`` (the
        plate hub and the Z-shaft's crank must fit in the shell), ``drive.rail_radius`` (the
        rails must clear the shell), ``machine.compression_ratio``, and those of
        :func:`rotorkin.drives.wobble_cam.cam.from_config`.
    """
    drive, cam = parts or sph.from_config(cfg)
    machine = _machine(cfg)
    try:
        layout = eng.piston_layout(drive, machine)
    except ParameterError as exc:
        raise ParameterError("machine.compression_ratio", exc.value, exc.admissible) from None
    d, c, k = cfg["drive"], cfg.get("cam") or {}, cfg.get("cad") or {}
    r, ri, ro, rb = cam.sphere_radius, cam.inner_radius, cam.outer_radius, cam.bottom_radius
    rho, h, phi = cam.roller_radius, cam.groove_half_width, drive.plate_tilt
    gap = _num(k, "gap", 0.001)
    wall = _num(k, "wall_thickness", 0.1 * r)
    # Z-shaft, plate hub and disc
    rz = 0.5 * _num(k, "shaft_diameter", 0.25 * r)
    rs = 0.5 * _num(k, "roller_shaft_diameter", rho)
    _need(rs <= rho - 0.25e-3, "cad.roller_shaft_diameter", 2 * rs,
          f"roller_shaft_diameter <= {fmt_mm(2 * rho - 0.5e-3)} (the roller's bore must leave "
          "a wall of 0.25 mm)")  # fmt: skip
    half_t = 0.5 * _num(k, "plate_thickness", 5.0 * rs)
    rp = _num(k, "plate_radius", 0.8 * ri)
    hub = rz + gap + 0.5 * wall
    hub_half = 0.5 * float(d.get("plate_bearing_span", 0.04)) + 0.5 * wall
    crank_half = hub_half + gap + rz
    xj = crank_half / np.cos(phi)
    reach = xj + rz  # the web's end sphere at (x_j, 0, 0)
    _need(reach <= ri - gap, "drive.plate_bearing_span", 2 * (hub_half - 0.5 * wall),
          f"plate_bearing_span <= "
          f"{fmt_mm(2 * ((ri - gap - rz) * np.cos(phi) - gap - rz - 0.5 * wall))}"
          " here: the plate hub (span + wall_thickness) and the Z-shaft's crank webs must fit "
          f"inside the shell's inner radius {fmt_mm(ri)} at this plate tilt")  # fmt: skip
    _need(half_t >= rs + 0.5e-3 and half_t <= hub_half, "cad.plate_thickness", 2 * half_t,
          f"{fmt_mm(2 * rs + 1e-3)} <= plate_thickness <= {fmt_mm(2 * hub_half)} (around the "
          "roller shafts' holes, within the hub)")  # fmt: skip
    corner = float(np.hypot(rp, half_t))
    rp_max = np.sqrt((ri - gap) ** 2 - half_t**2)
    _need(rp >= hub + 4.0 * rs and corner <= ri - gap, "cad.plate_radius", rp,
          f"{fmt_mm(hub + 4 * rs)} <= plate_radius <= {fmt_mm(rp_max)} (room for the roller "
          "shafts' holes; the disc turns inside the shell)")  # fmt: skip
    # cam: bores on the axis, shaft slots, assembly windows
    bore = 0.5 * _num(c, "bore_diameter", 2.0 * (rz + gap))
    polar = _groove_polar_min(drive)
    bore_max = ri * np.sin(polar - np.arcsin(h / ri)) - gap
    _need(rz < bore <= bore_max, "cam.bore_diameter", 2 * bore,
          f"{fmt_mm(2 * rz)} < bore_diameter <= {fmt_mm(2 * bore_max)} (around the Z-shaft, "
          "clear of the grooves)")  # fmt: skip
    slot = rs + 0.5 * _num(c, "slot_clearance", 0.001)
    _need(slot < h, "cam.slot_clearance", 2 * (slot - rs),
          f"0 mm <= slot_clearance < {fmt_mm(2 * (h - rs))} (the shaft slot must be narrower "
          "than the groove, 2 roller_radius + running_clearance)")  # fmt: skip
    # rails and their rollers
    rr = float(d.get("rail_roller_radius", 0.006))
    rl = _num(k, "rail_roller_length", 2.0 * rr)
    rail_r = float(d.get("rail_radius", 0.08))
    rail_in = rail_r - 0.5 * rl - gap
    _need(rail_in - gap >= ro + gap, "drive.rail_radius", rail_r,
          f"rail_radius >= {fmt_mm(ro + 3 * gap + 0.5 * rl)} (the rail and its roller, "
          "cad.rail_roller_length long, outside the cam shell)")  # fmt: skip
    rail_out = rail_r + 0.5 * rl + gap + wall
    margin = np.arcsin(min(1.0, (rr + gap) / (rail_r - 0.5 * rl)))
    b0, b1 = 0.5 * np.pi - phi - margin, 0.5 * np.pi + phi + margin
    channel = rr + 0.5 * float(fit_clearance(sph.RUNNING_FIT, 2.0 * rr))
    half_w = channel + wall
    z1 = rail_in * np.sin(b0)
    b_end = float(np.arcsin(max(z1 - wall, 0.0) / rail_in))
    _need(np.hypot(rail_in * np.cos(b0), z1 - wall) >= ro + gap and b0 > 0.0,
          "drive.rail_radius", rail_r,
          "a larger rail_radius: the rails' arms must clear the cam shell")  # fmt: skip
    # along +x: the drive, the spokes' slabs, the cylinder
    sweep_x = (rail_r + 0.5 * rl) * np.cos(0.5 * np.pi - phi) + rr * np.sin(0.5 * np.pi - phi)
    xa = max(ro, sweep_x, rail_out * np.cos(b_end)) + gap
    xb = xa + wall + gap
    s2 = (rz + gap, rz + gap + 0.5 * wall)
    s1 = (s2[1] + gap, s2[1] + gap + 0.5 * wall)
    _need(z1 - wall > s1[1] + gap, "drive.rail_radius", rail_r,
          "a larger rail_radius: the rotors' spokes need room between their sleeves and the "
          "rails' arms")  # fmt: skip
    inner, outer, width = _annulus(machine)
    x0 = xb + wall + gap + wall
    cyl = (x0, x0 + width)
    far = cyl[1] + wall
    x_left = -(max(ro, sweep_x, rail_out * np.cos(np.pi - b1)) + gap)
    case_r = float(np.hypot(rail_out, half_w)) + gap
    case = (x_left, far + gap)
    return Layout(
        drive=drive, cam=cam, machine=machine, piston_width=layout.piston_width,
        piston_offset=float(wc.piston_offset(drive.pistons_per_rotor)), wall=wall, gap=gap,
        shaft_radius=rz, crank_half=crank_half, journal_start=float(xj),
        journal_end=(case[0] - 2.0 * wall, case[1] + 2.0 * wall), plate_radius=rp,
        plate_half=half_t, hub_radius=hub, hub_half=hub_half, plate_bore=rz + gap,
        rshaft_radius=rs, rshaft_inner=rp - 3.0 * rs,
        rshaft_outer=rail_r + 0.5 * rl + 0.5 * gap,
        roller_bore=rs + 0.5 * float(fit_clearance(sph.RUNNING_FIT, 2.0 * rs)),
        rail_roller_radius=rr, rail_roller_length=rl, rail_radius=rail_r, cam_bore=bore,
        slot_half_width=slot, window_radius=h + 0.5e-3,
        window_floor=0.5 * (rb + cam.roller_outer_end),
        rail_inner=rail_in, rail_outer=rail_out, rail_angles=(float(b0), float(b1)),
        rail_end_angle=b_end, rail_channel=channel, rail_half_width=half_w,
        arm_z=(float(z1 - wall), float(z1)), slab_a=(xa, xa + wall), slab_b=(xb, xb + wall),
        sleeve_2=s2, sleeve_1=s1, disc=wall, cyl_x=cyl, cyl_r=(inner, outer), case_x=case,
        case_step=x0 - wall - gap, case_radius=case_r,
    )  # fmt: skip


def _annulus(machine: tr.TwinRotor):
    """Inner and outer radius and axial width of the cylinder's envelope [m]."""
    if machine.section == "circular":
        half = 0.5 * machine.section_diameter
        return machine.mean_radius - half, machine.mean_radius + half, 2.0 * half
    return machine.inner_radius, machine.outer_radius, machine.axial_width


def _groove_polar_min(drive, samples: int = 4096) -> float:
    """Smallest angle between a groove centre-line point and the cam axis (+-x) [rad].

    Remembered per drive (the last 512): a sweep checks every design of one drive with
    its own machine and cam sizes.
    """
    try:
        return _groove_polar_min_remembered(drive, samples)
    except TypeError:  # a drive holding arrays cannot be a key
        return _groove_polar_min_of(drive, samples)


@functools.lru_cache(maxsize=512)
def _groove_polar_min_remembered(drive, samples: int) -> float:
    return _groove_polar_min_of(drive, samples)


def _groove_polar_min_of(drive, samples: int) -> float:
    theta = np.linspace(0.0, sph.groove_period(drive), samples, endpoint=False)
    g = sph.groove_derivatives(drive, theta)[0]
    cos = np.abs(g[:, 0]) / np.linalg.norm(g, axis=1)
    return float(np.arccos(np.max(cos)))


def body_rotations(layout: Layout, theta) -> dict:
    """Rotation of every body at the shaft angles theta: ``name -> (..., 3, 3)``.

    Body coordinates to fixed coordinates, ``p_fixed = R p_body``; the names of
    :data:`BODIES`.
    """
    theta = np.asarray(theta, dtype=float)
    drive = layout.drive
    spin = wc.spin_law(drive, theta)[0]
    phi_k = wc.rotor_angles(drive, theta)[0]
    shaft = rot_x(theta)
    eye = np.broadcast_to(np.eye(3), theta.shape + (3, 3))
    return {
        "cam": rot_x(wc.cam_angle(theta)),
        "z_shaft": shaft,
        "plate": shaft @ rot_y(np.broadcast_to(drive.plate_tilt, theta.shape)) @ rot_x(spin),
        "rotor_1": rot_x(phi_k[0]),
        "rotor_2": rot_x(phi_k[1]),
        "casing": eye.copy(),
    }
