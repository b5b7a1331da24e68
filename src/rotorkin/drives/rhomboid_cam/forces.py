"""Forces in the pairs of the rhomboid lever-cam converter, at speed.

Zhuravlev et al. 2012 (``papers/rhomboid_cam.md``) give the kinematics only; the
force model here is ours.

The mechanism as modelled
-------------------------
* The **output shaft** carries a cross of radial guides along the diagonals of the
  rhombus (OA at ``alpha``, OB at ``alpha + pi/2``, ...). In each guide slides a
  **vertex block** that carries the **vertex pin**; on the pin turn the two **links**
  meeting at that vertex and the **roller**, which rolls on the outside of the fixed
  disc cam (:mod:`rotorkin.drives.rhomboid_cam.cam`).
* Each **link** (side ``2l``: AB, BC, CD, DA) is a straight bar pinned at both vertices
  and, at its midpoint, to a **blade arm**: pair 1's arm (a bar through O, pivoted on
  the shaft axis) holds the midpoints of AB and CD, pair 2's those of BC and DA.
* Each **blade-pair hub** turns on the output shaft.

Frames and signs
----------------
* Fixed plane x, y about the shaft axis O, angles counter-clockwise from +x (as the
  kinematics). At vertex ``k`` (A, B, C, D at ``alpha + k pi/2``): ``e_k`` the unit
  vector from O along the diagonal, ``t_k`` that vector turned by +90 deg (the
  shaft's direction of rotation there).
* ``D_i = J_i qdd_i - M_i`` is the torque the drive must put on blade pair ``i``
  (counter-clockwise positive, ``qdd_i = q_i'' w^2 + q_i' w_dot``): the machine's
  torque ``M_i`` and the pair's inertia at the run speed.
* **Roller k on the cam**: ``N_k >= 0``, the force of the cam on the roller along the
  pitch curve's outward normal ``n_k = (rho e_k - rho' t_k) / sqrt(rho^2 + rho'^2)``
  (at the roller's polar angle). The cam can only push: the load is carried by the
  outer surface of the cam, by A and C when the blades' loads try to open psi
  (``rho_A`` shrinks) and by B and D when they try to close it.
* **Guide k**: ``G_k`` (signed), the force of the shaft's guide on vertex block ``k``
  along ``t_k``: > 0 when the guide flank behind the block pushes it forward (the shaft
  drives the rhombus), < 0 when the block pushes the flank ahead of it (the rhombus
  drives the shaft). The torque the rhombus gives the shaft is ``-sum_k rho_k G_k``.
* **Arm force** on link ``j``: the force of the blade arm on the link at its midpoint,
  normal to the arm: ``-(D_1/2l) u_1`` on AB, ``+(D_1/2l) u_1`` on CD,
  ``+(D_2/2l) u_2`` on BC, ``-(D_2/2l) u_2`` on DA, ``u_i = e(phi_i + pi/2)``.
* **Link end forces**: the force of the vertex pin on the link at each end; the link's
  **tension** (> 0 pulls the pins together) is given for its two halves (vertex to
  midpoint), which differ by the arm force's component along the link; its bending
  moment is largest at the midpoint, ``l`` times half the arm force's normal component.

Statics (quasi-static in the links, rollers and blocks; the blade pairs' inertia is in
``D_i``)
----------------------------------------------------------------------------------------
The rigid rhombus held by the cam, the guides and both blade arms at once is
over-constrained (its statics have ten redundant unknowns); we close them with
four stated assumptions:

1. **Half-turn symmetry**: the forces at C, D (links CD, DA) are those at A, B (links
   AB, BC) turned by pi. Each blade pair's load is a pure couple (its blades are
   evenly spaced), so its hub and the shaft's bearings carry no radial force from
   the drive.
2. **Blade arms carry torque only**: the arm force at a link's midpoint is normal to
   the arm, ``D_i / (2l)`` at each of its two pins; a radial force in an arm would be
   a self-equilibrated preload of the closed linkage.
3. **No preload between the rollers**: of the two roller pairs (A, C and B, D) only the
   one that resists the blades' load touches the cam with a force; the other rolls
   on it unloaded. (All four rollers stay on the cam: the rhombus holds them by form
   closure, eq. 7/10; a preload would add a self-equilibrated set of forces.)
4. **Equally stiff guides in a stiff carrier**: the guide forces are proportional to
   their radii, ``G_k = g rho_k`` (the rhombus turning by a small angle relative to the
   shaft loads each guide in proportion to its radius).

With these, the equilibrium of vertex blocks A and B (four equations) gives the link
tensions ``S_AB``, ``S_BC``, the loaded roller force and ``g`` at every angle (a 4 x 4
system per angle, solved by elimination, vectorised). Power check: the rollers do no
work on the fixed cam (rolling) and the guides are normal to the blocks' sliding, so
the shaft torque ``-sum rho_k G_k`` equals ``-sum_i D_i q_i'``, the virtual-work torque
with the blade pairs' inertia.

Neglected: the masses of links, rollers, blocks and arms (no config keys; the
centrifugal force of a 50 g roller at 100 mm and 1500 rpm is about 120 N, a tenth of
the example's peak roller force) and friction in the statics (friction is first
order, :mod:`rotorkin.analysis.pairs`).

Slip of each pair per rad of shaft (see :mod:`rotorkin.analysis.pairs`): roller on the
cam, the rolling speed ``|dp/dalpha| |1 - r kappa|`` of the contact point (pitch curve
point ``p``, curvature ``kappa``, roller radius ``r``); roller on its pin,
``R_b |sqrt(rho^2 + rho'^2)/r - 1|`` (the roller spins at the centre's speed over
``r``, the pin turns with the shaft); block in its guide, ``|rho_k'|``; link on a
vertex pin, ``R_b |psi'|/2`` (links AB, CD turn at ``phi_2'``, BC, DA at ``phi_1'``);
arm on a link, ``R_b |psi'|``; blade-pair hub on the shaft, ``R_b |psi'|/2``, with
``R_b`` = ``contact.bearing_radius``.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from rotorkin.analysis.pairs import Pair
from rotorkin.core.angles import fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.drives.rhomboid_cam import cam
from rotorkin.drives.rhomboid_cam import kinematics as rc

__all__ = ["LINKS", "Forces", "check_roller", "solve", "pairs", "blade_hub_force",
           "machine_pairs", "force_summary", "SUMMARY_KEYS"]  # fmt: skip

#: The links of the rhombus, each from its first vertex to its second.
LINKS = ("AB", "BC", "CD", "DA")
#: The keys of :func:`force_summary`.
SUMMARY_KEYS = ("peak_roller_force_N", "peak_guide_force_N", "peak_link_force_N",
                "peak_link_bending_Nm", "peak_arm_force_N", "roller_pair_BD_share")  # fmt: skip
#: Blade pair holding each link's midpoint.
_ARM_OF_LINK = (1, 2, 1, 2)


class Forces(NamedTuple):
    """The forces of :func:`solve` over ``n`` shaft angles (frames: module docstring).

    Attributes
    ----------
    roller : ndarray, shape (4, n)
        ``N_k`` [N], rollers A, B, C, D, >= 0.
    guide : ndarray, shape (4, n)
        ``G_k`` [N], signed along ``t_k``.
    normal : ndarray, shape (4, 2, n)
        Outward unit normals of the cam at the rollers, fixed frame (x, y).
    link_end : ndarray, shape (4, 2, 2, n)
        Link ``j`` (:data:`LINKS`), end (0: first vertex, 1: second), force of the pin
        on the link (x, y) [N].
    arm : ndarray, shape (4, 2, n)
        Force of the blade arm on link ``j`` at its midpoint (x, y) [N].
    tension : ndarray, shape (4, 2, n)
        Tension of link ``j``'s first and second half [N] (> 0 tension).
    bending : ndarray, shape (4, n)
        Bending moment of link ``j`` at its midpoint [N m] (>= 0).
    loaded : ndarray of int, shape (n,)
        0 where A and C carry the load, 1 where B and D do.
    shaft_torque : ndarray, shape (n,)
        Torque the rhombus gives the shaft through the guides, ``-sum rho_k G_k`` [N m].
    """

    roller: np.ndarray
    guide: np.ndarray
    normal: np.ndarray
    link_end: np.ndarray
    arm: np.ndarray
    tension: np.ndarray
    bending: np.ndarray
    loaded: np.ndarray
    shaft_torque: np.ndarray


def _e(angle):
    return np.stack([np.cos(angle), np.sin(angle)])


def _to_fixed(v, alpha, axis):
    """Shaft-frame components ``(along e_A, along e_B)`` on ``axis`` of ``v`` -> fixed x, y."""
    v = np.moveaxis(v, axis, 0)
    shape = (2,) + (1,) * (v.ndim - 2) + alpha.shape
    ea, eb = _e(alpha).reshape(shape), _e(alpha + 0.5 * np.pi).reshape(shape)
    return np.moveaxis(v[0][None] * ea + v[1][None] * eb, 0, axis)


def _rollers(alpha, ndim: int):
    """:func:`~.cam.roller_alphas` ``(4, n)``, as ``(4, 1, n)`` against designs ``(m, n)``."""
    ak = cam.roller_alphas(alpha)
    return ak.reshape((4,) + (1,) * (ndim - alpha.ndim) + alpha.shape)


def solve(params: rc.RhomboidCam, alpha, drive_torque) -> Forces:
    """Forces in every pair at the shaft angles ``alpha`` (module docstring).

    Parameters
    ----------
    params : RhomboidCam
        One design; or designs, ``link_length`` and ``psi_min`` columns ``(m, 1)`` of
        the first-harmonic law: every result then has a designs axis before the angles'
        (``roller`` ``(4, m, n)``, ``loaded`` ``(m, n)``, ...).
    alpha : array_like, shape (n,)
        Output-shaft angles [rad].
    drive_torque : array_like, shape (2, n) or (2, m, n)
        ``D_i``, the torque the drive puts on blade pair ``i`` [N m] (counter-clockwise).

    Returns
    -------
    Forces
    """
    alpha = np.asarray(alpha, dtype=float)
    L = np.asarray(params.link_length, dtype=float)  # 2l
    law = (params.psi_min, params.a, params.b)
    psi = rc.psi_law(*law, alpha)[0]
    D = np.broadcast_to(np.asarray(drive_torque, dtype=float), (2,) + psi.shape)
    c, s = np.cos(0.5 * psi), np.sin(0.5 * psi)
    rho, drho = rc.profile_radius(L, *law, _rollers(alpha, psi.ndim))[:2]  # (4, [m,] n)
    h = np.hypot(rho, drho)
    # shaft frame (e_A, e_B): normals at A (e_r = e_A, e_t = e_B) and B (e_r = e_B, e_t = -e_A)
    n_a = np.stack([rho[0], -drho[0]]) / h[0]
    n_b = np.stack([drho[1], rho[1]]) / h[1]
    u_ab, u_bc = np.stack([-c, s]), np.stack([-c, -s])  # link directions A -> B, B -> C
    u1, u2 = np.stack([-s, c]), np.stack([s, c])  # e(phi_i + pi/2) in the shaft frame
    f_ab = -(D[0] / L) * u1  # arm force on link AB (D_1 / 2l at each of arm 1's two pins)
    f_bc = (D[1] / L) * u2  # arm force on link BC
    # vertex blocks A and B in equilibrium (t_A = e_B, t_B = -e_A):
    #   A: f_ab/2 + S1 u_ab - f_bc/2 + S2 u_bc + N_A n_A + g rho_A t_A = 0
    #   B: f_ab/2 - S1 u_ab + f_bc/2 + S2 u_bc + N_B n_B + g rho_B t_B = 0
    # with N_A = 0 or N_B = 0. In P = S1 + S2, Q = S1 - S2 the four rows read
    #   -c P + N_A n_A,x = r1    s Q + rho_A g + N_A n_A,y = r2
    #   -s P + N_B n_B,y = r4    c Q - rho_B g + N_B n_B,x = r3
    # (r: the arm forces' rows): with A loaded the e_B row of B gives P, the e_A row of A
    # gives N_A; with B loaded the e_A row of A gives P, the e_B row of B gives N_B; then
    # Q and g from the other two rows (determinant s rho_B + c rho_A > 0: 0 < psi < pi).
    r1, r2 = -0.5 * (f_ab - f_bc)
    r3, r4 = -0.5 * (f_ab + f_bc)
    p_a = -r4 / s
    n_on_a = (r1 + c * p_a) / n_a[0]
    use_b = n_on_a < 0.0  # the cam can only push: then B and D carry the load
    p_b = -r1 / c
    n_on_b = (r4 + s * p_b) / n_b[1]
    p_sum = np.where(use_b, p_b, p_a)
    n_load = np.where(use_b, n_on_b, n_on_a)
    row2 = np.where(use_b, r2, r2 - n_a[1] * n_on_a)
    row3 = np.where(use_b, r3 - n_b[0] * n_on_b, r3)
    det = s * rho[1] + c * rho[0]
    q_diff = (rho[1] * row2 + rho[0] * row3) / det
    g = (c * row2 - s * row3) / det
    s1, s2 = 0.5 * (p_sum + q_diff), 0.5 * (p_sum - q_diff)
    n_load = np.maximum(n_load, 0.0)  # -0.0 and rounding at the switch
    na = np.where(use_b, 0.0, n_load)
    nb = np.where(use_b, n_load, 0.0)
    roller = np.stack([na, nb, na, nb])
    guide = g * rho
    # link end forces (shaft frame), then the half-turn images
    end_ab = np.stack([-0.5 * f_ab - s1 * u_ab, -0.5 * f_ab + s1 * u_ab])
    end_bc = np.stack([-0.5 * f_bc - s2 * u_bc, -0.5 * f_bc + s2 * u_bc])
    link_end = np.stack([end_ab, end_bc, -end_ab, -end_bc])  # (4, 2, 2, n)
    arm = np.stack([f_ab, f_bc, -f_ab, -f_bc])
    along_ab = np.sum(f_ab * u_ab, axis=0)
    along_bc = np.sum(f_bc * u_bc, axis=0)
    t_ab = np.stack([s1 + 0.5 * along_ab, s1 - 0.5 * along_ab])
    t_bc = np.stack([s2 + 0.5 * along_bc, s2 - 0.5 * along_bc])
    tension = np.stack([t_ab, t_bc, t_ab, t_bc])
    half_len = 0.5 * L
    b_ab = half_len * 0.5 * np.abs(f_ab[0] * u_ab[1] - f_ab[1] * u_ab[0])
    b_bc = half_len * 0.5 * np.abs(f_bc[0] * u_bc[1] - f_bc[1] * u_bc[0])
    normal = np.stack([n_a, n_b, -n_a, -n_b])
    return Forces(
        roller=roller,
        guide=guide,
        normal=_to_fixed(normal, alpha, 1),
        link_end=_to_fixed(link_end, alpha, 2),
        arm=_to_fixed(arm, alpha, 1),
        tension=tension,
        bending=np.stack([b_ab, b_bc, b_ab, b_bc]),
        loaded=use_b.astype(np.int8),
        shaft_torque=-np.sum(rho * guide, axis=0),
    )


def blade_hub_force(member_torque, blades_per_pair, inner_radius, outer_radius):
    """Radial force on each blade-pair hub from the machine [N], shape of ``member_torque``.

    Zero for two or more evenly spaced blades per pair (their forces make a couple); a
    single blade carries its pressure force ``|M_i| / r_c`` at the centre of pressure
    of a flat radial blade, ``r_c = (inner_radius + outer_radius) / 2``.
    """
    m = np.abs(np.asarray(member_torque, dtype=float))
    if int(blades_per_pair) >= 2:
        return np.zeros_like(m)
    return m / (0.5 * (np.asarray(inner_radius, dtype=float) + outer_radius))


#: The smallest roller radius the forces take [m]: a roller spins at its rolling speed
#: over its radius, and a radius near 0 leaves the spin and the pin's friction without
#: meaning (1 um; a denormal radius overflowed them).
ROLLER_RADIUS_MIN = 1e-6


def check_roller(roller_radius, name="cam.roller_radius") -> float:
    """The roller radius [m] the forces need: >= 1 um (a roller's contact stress and spin)."""
    r = float(roller_radius)
    if not (np.isfinite(r) and r >= ROLLER_RADIUS_MIN):
        raise ParameterError(
            name,
            fmt_mm(r),
            "roller_radius >= 0.001 mm for the contact forces (a roller's Hertz stress and "
            "spin need its radius)",
        )
    return r


def pairs(params: rc.RhomboidCam, alpha, drive_torque, roller_radius, bearing_radius,
          hub_force=None, forces: Forces | None = None) -> list[Pair]:  # fmt: skip
    """Every load-carrying pair of the converter over ``alpha`` (:class:`Pair` list).

    Parameters
    ----------
    params : RhomboidCam
    alpha : ndarray, shape (n,)
        [rad].
    drive_torque : ndarray, shape (2, n)
        ``D_i`` [N m].
    roller_radius, bearing_radius : float
        [m]; ``roller_radius > 0``.
    hub_force : ndarray, shape (2, n), optional
        Radial force on the blade-pair hubs (:func:`blade_hub_force`); zero by default.
    forces : Forces, optional
        :func:`solve` of the same inputs, when already computed.

    Returns
    -------
    list of Pair
        Rollers on the cam (4, rolling), rollers on their pins (4), blocks in their guides
        (4, sliding), links on the vertex pins (8), blade arms on the links (4), blade-pair
        hubs on the shaft (2).
    """
    alpha = np.asarray(alpha, dtype=float)
    r = check_roller(roller_radius)
    rb = float(bearing_radius)
    f = solve(params, alpha, drive_torque) if forces is None else forces
    L, law = params.link_length, (params.psi_min, params.a, params.b)
    dpsi = rc.psi_law(*law, alpha)[1]
    ak = _rollers(alpha, np.ndim(dpsi))
    radius = rc.profile_radius(L, *law, ak)
    rho, drho = radius[:2]
    speed = np.hypot(rho, drho)  # roller centre's speed per rad of shaft
    kappa = rc.polar_curvature(*radius[:3])
    r_cam = cam.radius_of_curvature(kappa) - r  # cam surface, + convex
    out = []
    for k, v in enumerate(cam.ROLLERS):
        out.append(Pair(
            f"roller {v} on the cam", f"roller_{v.lower()}_cam", "rolling", f.roller[k],
            speed[k] * np.abs(1.0 - r * kappa[k]), ("line", r, r_cam[k]),
            f"cam on roller {v} along the cam's outward normal (the cam only pushes); A and C "
            "carry the load while the blades' loads open psi, B and D while they close it",
        ))  # fmt: skip
    for k, v in enumerate(cam.ROLLERS):
        out.append(Pair(
            f"roller {v} on its pin", f"roller_{v.lower()}_pin", "bearing", f.roller[k],
            rb * np.abs(speed[k] / r - 1.0), None,
            f"the cam force on roller {v}, carried by the vertex pin",
        ))  # fmt: skip
    for k, v in enumerate(cam.ROLLERS):
        out.append(Pair(
            f"vertex {v} in its guide", f"guide_{v.lower()}", "sliding", f.guide[k],
            np.abs(drho[k]), None,
            f"shaft's guide on vertex block {v}, normal to the diagonal O{v}: the flank behind "
            "the block while the shaft drives, the flank ahead while the rhombus drives",
        ))  # fmt: skip
    for j, name in enumerate(LINKS):
        for end in (0, 1):
            v = name[end]
            out.append(Pair(
                f"link {name} on pin {v}", f"link_{name.lower()}_pin_{v.lower()}", "bearing",
                np.hypot(*f.link_end[j, end]), rb * 0.5 * np.abs(dpsi), None,
                f"pin {v} on link {name} (x, y in the fixed frame)",
            ))  # fmt: skip
    for j, name in enumerate(LINKS):
        i = _ARM_OF_LINK[j]
        out.append(Pair(
            f"blade arm {i} on link {name}", f"arm{i}_link_{name.lower()}", "bearing",
            np.hypot(*f.arm[j]), rb * np.abs(dpsi), None,
            f"blade arm {i} on the midpoint of link {name}, normal to the arm: D_{i} / 2l",
        ))  # fmt: skip
    hub = np.zeros((2,) + alpha.shape) if hub_force is None else np.asarray(hub_force)
    for i in (0, 1):
        out.append(Pair(
            f"blade pair {i + 1} hub on the shaft", f"blade_pair_{i + 1}_hub", "bearing",
            hub[i], rb * 0.5 * np.abs(dpsi), None,
            "radial force of the machine on the blade pair (a couple, zero, with two or more "
            "blades per pair)",
        ))  # fmt: skip
    return out


def machine_pairs(params, machine, alpha, member_torque, drive_torque, roller_radius,
                  bearing_radius) -> tuple[list[Pair], Forces]:  # fmt: skip
    """The converter's pairs (:func:`pairs`) and forces (:func:`solve`) in a machine.

    ``member_torque``: the machine's torques on the blade pairs ``M_i`` (the hubs' load,
    :func:`blade_hub_force`), ``drive_torque`` the drive's ``D_i``; one design, or
    designs as :func:`solve` takes them (``params``, ``machine`` of ``(m, 1)`` columns).
    """
    fo = solve(params, alpha, drive_torque)
    hub = blade_hub_force(member_torque, machine.blades_per_pair, machine.inner_radius,
                          machine.outer_radius)  # fmt: skip
    return pairs(params, alpha, drive_torque, roller_radius, bearing_radius, hub, forces=fo), fo


def force_summary(fo: Forces) -> dict:
    """The converter's own summary keys (``docs/drives/rhomboid_cam.md``) from :func:`solve`.

    Each the peak (or share) over the rollers, links and angles: a 0-d array of one
    design, an array ``(m,)`` of designs.
    """
    values = (
        np.max(fo.roller, axis=(0, -1)),
        np.max(np.abs(fo.guide), axis=(0, -1)),
        np.max(np.abs(fo.tension), axis=(0, 1, -1)),
        np.max(fo.bending, axis=(0, -1)),
        np.max(np.hypot(fo.arm[:, 0], fo.arm[:, 1]), axis=(0, -1)),
        np.mean(fo.loaded[..., :-1], axis=-1),
    )
    return dict(zip(SUMMARY_KEYS, values, strict=True))
