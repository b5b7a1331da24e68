"""Forces in the pairs of the guide-bar + gear drive, at speed (derived here; the paper has none).

The paper (section 4) balances torques by virtual work only. Here every load-carrying
pair of both mechanisms gets its force at every input angle, from the torque the drive
must put on each impeller,

    D_k = J_k qdd_k - M_k,   qdd_k = q_k'' omega^2 + q_k' omega_dot,

with ``M_k`` the torque of the pump on impeller k along ``+q_k`` (the study's chamber
pressures, ideal ports) and ``J_k`` the impeller's inertia.

Layout (ours; the paper draws none to scale): the two mechanisms lie in parallel planes
and share the frame line, each gear pair's line of centres lies on it. Mechanism k's
**frame**: guide pivot C at the origin, x from C to the crank pivot A = (lambda a, 0),
z along the axes so that the driving member turns about +z (counter-clockwise seen from
+z); y = z x x. Gear 2 (9) sits on the driving member's pivot (A crank-driven, C
guide-driven), input gear 1 beyond it on the frame line, at ``r1 + r2`` away from the
other pivot; gear 6 (11) sits on the driven member's pivot, impeller gear 7 (8) and the
impellers' axis beyond it, ``r6 + r7`` away from the other pivot. Pitch radii: ``r1``
(``drive.input_pitch_radius``), ``r2 = i12 r1``, ``r6`` (``drive.output_pitch_radius``),
``r7 = u r6``. Gear 1 and the impellers turn clockwise (external meshes), the
mechanisms' members counter-clockwise; every torque below is along the member's own
sense of turning (+q, +theta), every vector in the mechanism frame.

Angles in the frame: crank angle ``phi_c`` and guide-bar angle ``phi_g`` from the x axis
(:mod:`~rotorkin.drives.guide_bar.kinematics`: crank-driven ``phi_c = x``,
``phi_g = g(x)``; guide-driven ``phi_g = y``, ``phi_c = h(y)``). Crank pin (slider block) at
``P = s (cos phi_g, sin phi_g)``, ``s = a sqrt(1 + 2 lambda cos phi_c + lambda^2)`` from C;
``e_g = (cos phi_g, sin phi_g)`` along the guide, ``n_g = (-sin phi_g, cos phi_g)`` across
it, pointing where the guide bar moves.

Equilibrium (the links' own inertia neglected, see below), with ``L = -D/u`` the torque
impeller gear 7 puts on gear 6 and ``c = cos(phi_c - phi_g) > 0``:

* ``N``: force of the guide bar on the slider block along ``n_g`` (signed). The block is
  pinned to the crank and carries no moment, so the guide's force passes through the pin
  and the pin carries ``N`` too: the block pushes the crank with ``+N n_g`` at P and the
  guide bar with ``-N n_g``. ``N > 0``: the slot's *trailing* wall (behind the block in
  the sense of turning) carries the load, the guide bar pushes the block forward;
  ``N < 0``: the *leading* wall, the block pushes the guide bar forward.
* crank-driven (guide bar driven): moments on the guide bar about C, ``-N s + L = 0``:
  ``N = L / s``; on the crank about A, ``T + N a c = 0``: ``T = -N a c``;
* guide-driven (crank driven): on the crank about A, ``N a c + L = 0``:
  ``N = -L / (a c)``; on the guide bar about C, ``T - N s = 0``: ``T = N s``;
  ``T`` the torque gear 2 (9) puts on the driving member, ``T = D f'/u`` by virtual work.
* meshes, involute spur gears of pressure angle alpha, one tooth pair in contact: the
  tangential force on the driven gear of the pair is ``F_t = torque / pitch radius``
  (input mesh: ``T / r2`` on gear 2; impeller mesh: ``D / r7`` on gear 7), the radial
  force ``|F_t| tan alpha`` pushes the two gears apart, the tooth normal force is
  ``|F_t| / cos alpha``. ``F_t > 0``: the flank ahead of the driving tooth (in the sense
  of turning) carries the load, the usual drive flank; ``F_t < 0`` (the impeller
  overruns the drive, e.g. while it decelerates): the back flank.
* bearings: the frame's force on each link is minus the sum of the other forces on it
  (crank + its gear at A, guide bar + its gear at C, gear 1 on its shaft, impeller k on
  its own; both mechanisms' forces add on gear 1, their frames being the same).
* the torque of the drive on the input shaft ``-(T_1 + T_2) / i12`` is the study's
  ``shaft_torque - inertia_torque + J_shaft omega_dot`` (tested).

Neglected: the links' own inertia (crank, block, guide bar and gears 2, 6, assumed
balanced about their pivots; a driven member's rotary inertia ``J`` acts on the impeller
as ``u^2 J`` and may be added to ``machine.inertia_impeller_*``: the pivot, slider and
input loads are then exact, the impeller mesh's slightly high; the driving members turn
uniformly at a constant run speed), the block's mass, gravity, the chamber pressures'
radial force on the impellers (the pump's vanes are symmetric), friction in the force
balance (first order: :mod:`rotorkin.analysis.pairs`), and the teeth's contact ratio
(one tooth pair carries the whole mesh force: the Hertz pressure at the pitch point is
an upper bound of the mesh's).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.analysis.pairs import Pair
from rotorkin.core.errors import ParameterError
from rotorkin.core.schema import ContactSection
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar.schema import (
    DRIVE_LENGTH_MAX,
    DRIVE_LENGTH_MIN,
    FACE_WIDTH_MAX,
    FACE_WIDTH_MIN,
    PRESSURE_ANGLE_MAX,
    PRESSURE_ANGLE_MIN,
)

__all__ = ["GEARING_FIELDS", "Gearing", "Forces", "gearing", "drive_torques", "solve", "pairs",
           "own_summary", "signed_columns"]  # fmt: skip

#: Fields of :class:`Gearing` in the order they are checked (their config keys: ``drive.<f>``).
GEARING_FIELDS = ("crank_length", "input_pitch_radius", "output_pitch_radius", "face_width",
                  "pressure_angle")  # fmt: skip
_BOUNDS = {
    "crank_length": (DRIVE_LENGTH_MIN, DRIVE_LENGTH_MAX, "1 mm <= a <= 1 m"),
    "input_pitch_radius": (DRIVE_LENGTH_MIN, DRIVE_LENGTH_MAX, "1 mm <= r1 <= 1 m"),
    "output_pitch_radius": (DRIVE_LENGTH_MIN, DRIVE_LENGTH_MAX, "1 mm <= r6 <= 1 m"),
    "face_width": (FACE_WIDTH_MIN, FACE_WIDTH_MAX, "1 mm <= b <= 500 mm"),
    "pressure_angle": (PRESSURE_ANGLE_MIN, PRESSURE_ANGLE_MAX,
                       "10 deg <= pressure_angle <= 35 deg"),
}  # fmt: skip


@dataclass(frozen=True)
class Gearing:
    """Sizes of the drive for its forces (SI): the schema's defaults.

    Parameters
    ----------
    crank_length : float
        ``a`` [m]; the frame is ``lambda a``.
    input_pitch_radius : float
        ``r1`` of input gear 1 [m]; gears 2, 9 have ``i12 r1``.
    output_pitch_radius : float
        ``r6`` of gears 6, 11 on the driven members [m]; gears 7, 8 have ``u r6``.
    face_width : float
        Face width of the gears [m] (Hertz pressure of the meshes).
    pressure_angle : float
        alpha [rad].

    Raises
    ------
    ParameterError
        Named by the field, with its value and the admissible range.
    """

    crank_length: float = 0.040
    input_pitch_radius: float = 0.025
    output_pitch_radius: float = 0.030
    face_width: float = 0.020
    pressure_angle: float = np.radians(20.0)

    def __post_init__(self):
        for field in GEARING_FIELDS:
            v = float(getattr(self, field))
            lo, hi, text = _BOUNDS[field]
            # a hair of slack: a value typed at the bound survives unit conversion
            if not (np.isfinite(v) and lo * (1 - 1e-12) <= v <= hi * (1 + 1e-12)):
                shown = f"{np.degrees(v):g} deg" if field == "pressure_angle" else f"{v:g} m"
                raise ParameterError(field, shown, text)


def gearing(drive: dict) -> Gearing:
    """:class:`Gearing` from a validated config's ``drive`` section (SI; defaults if missing).

    Raises
    ------
    ParameterError
        Named by the config key (``drive.pressure_angle``, ...).
    """
    values = {f: float(drive[f]) for f in GEARING_FIELDS if f in drive}
    try:
        return Gearing(**values)
    except ParameterError as exc:
        raise ParameterError(f"drive.{exc.name}", exc.value, exc.admissible) from None


def bearing_radius(cfg: dict) -> float:
    """The bearings' journal radius of a validated config (``contact.bearing_radius``)."""
    return float({**ContactSection().model_dump(), **(cfg.get("contact") or {})}["bearing_radius"])


def drive_torques(params: gb.GuideBar, theta, member_torques, inertias, omega, omega_dot=0.0):
    """Torque the drive must put on each impeller, ``D_k = J_k qdd_k - M_k`` [N*m], shape (2, n).

    Parameters
    ----------
    params : GuideBar
    theta : ndarray, shape (n,)
        Input angles [rad].
    member_torques : array_like, shape (2, n)
        ``M_k``: torque of the pump on impeller k along ``+q_k`` [N*m].
    inertias : (float, float)
        ``J_1``, ``J_2`` [kg*m^2]; with parameters of designs ``(m, 1)``, columns of
        that shape (every array then ``(2, m, n)``).
    omega, omega_dot : float or ndarray, shape (n,)
        Input speed and acceleration [rad/s, rad/s^2].
    """
    dq, d2q, _ = gb.impeller_rates(params, theta)
    j = np.stack(np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in inertias)))
    j = j.reshape(j.shape + (1,) * (d2q.ndim - j.ndim))  # (2, 1) or columns (2, m, 1)
    w, wd = np.asarray(omega, dtype=float), np.asarray(omega_dot, dtype=float)
    return j * (d2q * w**2 + dq * wd) - np.asarray(member_torques, dtype=float)


@dataclass(frozen=True)
class Forces:
    """Signed forces and torques of both mechanisms over the input angles (module text).

    Arrays of shape (2, n) are per mechanism k; vectors (2, 2, n) are (k, x/y, n) in the
    mechanism frame; ``input_bearing`` is (x/y, n).

    Attributes
    ----------
    crank_angle, guide_angle : ndarray (2, n)
        ``phi_c``, ``phi_g`` [rad].
    crank_rate, guide_rate : ndarray (2, n)
        Their derivatives w.r.t. theta [-].
    pin_distance : ndarray (2, n)
        ``s = |CP|`` [m].
    pin_slip : ndarray (2, n)
        ``ds/dtheta`` [m/rad]: the block's speed along the guide per unit input speed.
    slider : ndarray (2, n)
        ``N`` [N], + the trailing wall of the slot carries the load.
    drive_torque : ndarray (2, n)
        ``T`` [N*m], gear 2 (9) on the driving member, + along its turning.
    impeller_torque : ndarray (2, n)
        ``D`` [N*m], gear 6 (11) on the impeller through gear 7 (8).
    input_mesh : ndarray (2, n)
        Tangential force of gear 1 on gear 2 (9), ``T / r2`` [N], + drive flank.
    impeller_mesh : ndarray (2, n)
        Tangential force of gear 6 (11) on gear 7 (8), ``D / r7`` [N], + drive flank.
    crank_bearing, guide_bearing, impeller_bearing : ndarray (2, 2, n)
        Frame on crank at A, on guide bar at C, on impeller k at its axis [N].
    input_bearing : ndarray (2, n)
        Frame on gear 1 [N].
    pin_force : ndarray (2, 2, n)
        Slider block on the crank at P, ``N n_g`` [N].
    shaft_torque : ndarray (n,)
        Torque of the drive on input gear 1 along its turning, ``-(T_1 + T_2)/i12`` [N*m]
        (positive when it drives the shaft).
    """

    crank_angle: np.ndarray
    guide_angle: np.ndarray
    crank_rate: np.ndarray
    guide_rate: np.ndarray
    pin_distance: np.ndarray
    pin_slip: np.ndarray
    slider: np.ndarray
    drive_torque: np.ndarray
    impeller_torque: np.ndarray
    input_mesh: np.ndarray
    impeller_mesh: np.ndarray
    crank_bearing: np.ndarray
    guide_bearing: np.ndarray
    impeller_bearing: np.ndarray
    input_bearing: np.ndarray
    pin_force: np.ndarray
    shaft_torque: np.ndarray


def _mesh_force(tangential, normal_out, tan_alpha):
    """Force on a gear at its pitch point [N], (2, 2, ...): ``F_t t - |F_t| tan(alpha) e``.

    ``normal_out`` is the unit vector from the gear's axis to its mate's, shape (2, ...)
    with the parameters' shape (it broadcasts with ``tangential``'s after padding);
    ``t = z x normal_out`` (the gear's counter-clockwise tangent); the radial part pushes the
    gear away from its mate.
    """
    e = np.asarray(normal_out, dtype=float)
    e = e.reshape(e.shape + (1,) * (tangential.ndim - e.ndim))  # aligned with the angles
    t = np.stack([-e[1], e[0]])
    ft = tangential[:, None]
    return ft * t[None] - np.abs(ft) * tan_alpha * e[None]


def solve(params: gb.GuideBar, size: Gearing, theta, impeller_torques) -> Forces:
    """Forces in every pair of both mechanisms (module text), vectorised over the angles.

    Parameters
    ----------
    params : GuideBar
        Scalar parameters, or columns of designs ``(m, 1)`` (``driver`` a string or an
        array of them); every array of the result then has the designs' axis before the
        angles'.
    size : Gearing
    theta : array_like, shape (n,)
        Input angles [rad].
    impeller_torques : array_like, shape (2, n) or (2, m, n)
        ``D_k`` (:func:`drive_torques`) [N*m].

    Returns
    -------
    Forces
    """
    theta = np.asarray(theta, dtype=float)
    lam, u, i12 = (np.asarray(v, dtype=float) for v in (params.lam, params.gear_ratio,
                                                        params.input_gear_ratio))  # fmt: skip
    a = float(size.crank_length)
    r1, r6 = float(size.input_pitch_radius), float(size.output_pitch_radius)
    r2, r7 = i12 * r1, u * r6
    ta = np.tan(float(size.pressure_angle))

    x = gb.driving_angles(params, theta)
    D = np.broadcast_to(np.asarray(impeller_torques, dtype=float), x.shape)
    f, f1, _, _ = gb.driven_angle(lam, params.driver, x)
    crank_driven = np.asarray(params.driver) == "crank"
    phi_c, phi_g = np.where(crank_driven, x, f), np.where(crank_driven, f, x)
    uniform = np.broadcast_to(1.0 / i12, f1.shape)
    rate_c = np.where(crank_driven, uniform, f1 / i12)
    rate_g = np.where(crank_driven, f1 / i12, uniform)
    root = np.sqrt(1.0 + 2.0 * lam * np.cos(phi_c) + lam * lam)
    s = a * root
    ds = -a * lam * np.sin(phi_c) / root * rate_c
    c = np.cos(phi_c - phi_g)
    n_g = np.stack([-np.sin(phi_g), np.cos(phi_g)], axis=1)  # (2, 2, ...)

    L = -D / u  # gear 7 on gear 6, along the driven member's turning
    with np.errstate(divide="ignore", invalid="ignore"):  # the other driver's branch
        N = np.where(crank_driven, L / s, -L / (a * c))
    T = np.where(crank_driven, -N * a * c, N * s)
    pin = N[:, None] * n_g  # block on crank

    # the frame line points from the driven member's pivot to the driving member's: +x
    # crank-driven (C -> A), -x guide-driven; gear 1 lies along it, the impellers against it
    along = np.where(crank_driven, 1.0, -1.0)
    e_in = np.stack([along, np.zeros_like(along)])
    f_in = _mesh_force(T / r2, e_in, ta)  # gear 1 on gear 2 (9), at the driving pivot
    f_out = _mesh_force(L / r6, -e_in, ta)  # gear 7 on gear 6, at the driven pivot
    # crank-driven: crank + gear 2, guide bar + gear 6; guide-driven: guide bar + gear 2,
    # crank + gear 6
    crank_bearing = -(pin + np.where(crank_driven, f_in, f_out))
    guide_bearing = -(-pin + np.where(crank_driven, f_out, f_in))
    return Forces(
        crank_angle=phi_c,
        guide_angle=phi_g,
        crank_rate=rate_c,
        guide_rate=rate_g,
        pin_distance=s,
        pin_slip=ds,
        slider=N,
        drive_torque=T,
        impeller_torque=D,
        input_mesh=T / r2,
        impeller_mesh=D / r7,
        crank_bearing=crank_bearing,
        guide_bearing=guide_bearing,
        impeller_bearing=f_out,  # the impeller's axis holds gear 7 against gear 6's push
        input_bearing=f_in[0] + f_in[1],  # gear 1 takes -f_in from each; its axis the opposite
        pin_force=pin,
        shaft_torque=-(T[0] + T[1]) / i12,
    )


def pairs(params: gb.GuideBar, size: Gearing, forces: Forces, bearing_radius: float) -> list:
    """The load-carrying pairs (:class:`~rotorkin.analysis.pairs.Pair`) of both mechanisms.

    Per mechanism k: slider block on guide bar (sliding; a block on a flat guide, no Hertz
    stress), crank pin, crank bearing A, guide-bar pivot C (bearings), the input mesh gear 1
    with gear 2 (9) and the impeller mesh gear 6 (11) with gear 7 (8) (meshes, tooth normal
    force, Hertz line contact of the involutes at the pitch point, radii ``r sin alpha``,
    over the face width), impeller k's bearing; and input gear 1's bearing.
    Slips per unit input speed: the block's ``|ds/dtheta|``; a bearing's journal radius
    times the relative turning speed; a mesh's pitch-line speed times ``cos alpha``.
    """
    i12, u = np.asarray(params.input_gear_ratio, float), np.asarray(params.gear_ratio, float)
    alpha = float(size.pressure_angle)
    r1, r6 = float(size.input_pitch_radius), float(size.output_pitch_radius)
    r2, r7 = i12 * r1, u * r6
    rb = float(bearing_radius)
    F = forces
    ca = np.cos(alpha)
    drivers = set(np.unique(np.asarray(params.driver)))
    if len(drivers) != 1:
        raise ValueError("the pairs of designs with different drivers: one driver at a time")
    crank_driven = drivers == {"crank"}
    gear_in, gear_out = ("crank", "guide bar") if crank_driven else ("guide bar", "crank")
    n = F.shaft_torque.shape
    driven_rate = F.guide_rate if crank_driven else F.crank_rate
    out = []
    for k in (0, 1):
        m = k + 1
        g2, g6, g7 = (2, 6, 7) if k == 0 else (9, 11, 8)
        out += [
            Pair(f"slider {m} on guide bar {m}", f"slider{m}_guide", "sliding",
                 np.abs(F.slider[k]), np.abs(F.pin_slip[k]), None,
                 f"mechanism {m} frame: force of the guide bar on the block across the guide "
                 "(n_g); the trailing wall of the slot carries it when the guide bar drives, "
                 f"the leading wall when the block drives (slider{m}_normal_N)"),
            Pair(f"crank pin {m}", f"crank_pin{m}", "bearing", np.abs(F.slider[k]),
                 rb * np.abs(F.guide_rate[k] - F.crank_rate[k]), None,
                 f"mechanism {m}: the block on its crank pin, across the guide bar"),
            Pair(f"crank bearing {m} (A)", f"crank{m}_bearing", "bearing",
                 np.hypot(*F.crank_bearing[k]), rb * np.abs(F.crank_rate[k]), None,
                 f"mechanism {m}: frame on the crank and gear {g2 if crank_driven else g6} at "
                 "the crank pivot A"),
            Pair(f"guide-bar pivot {m} (C)", f"guide{m}_pivot", "bearing",
                 np.hypot(*F.guide_bearing[k]), rb * np.abs(F.guide_rate[k]), None,
                 f"mechanism {m}: frame on the guide bar and gear "
                 f"{g6 if crank_driven else g2} at the guide pivot C"),
            Pair(f"input mesh gear 1 / gear {g2}", f"input_mesh{m}", "mesh",
                 np.abs(F.input_mesh[k]) / ca, np.full(n, r1 * ca),
                 ("line", r1 * np.sin(alpha), r2 * np.sin(alpha), float(size.face_width)),
                 f"tooth normal force, gear 1 on gear {g2} of the {gear_in}; tangential part "
                 f"input_mesh{m}_tangential_N (+: drive flank)"),
            Pair(f"impeller mesh gear {g6} / gear {g7}", f"impeller_mesh{m}", "mesh",
                 np.abs(F.impeller_mesh[k]) / ca, r6 * np.abs(driven_rate[k]) * ca,
                 ("line", r6 * np.sin(alpha), r7 * np.sin(alpha), float(size.face_width)),
                 f"tooth normal force, gear {g6} of the {gear_out} on impeller gear {g7}; "
                 f"tangential part impeller_mesh{m}_tangential_N (+: drive flank)"),
            Pair(f"impeller {m} bearing", f"impeller{m}_bearing", "bearing",
                 np.hypot(*F.impeller_bearing[k]), rb * np.abs(driven_rate[k]) / u, None,
                 f"frame on impeller {m} (the impeller mesh's force; the chamber pressures' "
                 "radial force neglected)"),
        ]  # fmt: skip
    out.append(
        Pair(
            "input gear 1 bearing",
            "input_bearing",
            "bearing",
            np.hypot(*F.input_bearing),
            np.full(n, rb),
            None,
            "frame on input gear 1: both input meshes' forces (the mechanisms share the frame "
            "line)",
        )  # fmt: skip
    )
    return out


#: Keys of :func:`own_summary`, in its order.
SUMMARY_KEYS = (
    "load_reversals_per_period",
    "peak_slider_force_N",
    "peak_slider_speed_m_per_s",
    "peak_input_mesh1_tangential_force_N",
    "peak_input_mesh2_tangential_force_N",
    "peak_impeller_mesh1_tangential_force_N",
    "peak_impeller_mesh2_tangential_force_N",
    "peak_crank_bearing_load_N",
    "peak_guide_pivot_load_N",
    "peak_input_bearing_load_N",
)


def own_summary(forces: Forces, omega) -> dict:
    """The drive's own peaks: slider force and speed, mesh tangential forces, pivot loads, and
    how often per period the load on an impeller's mesh (and on its slot's walls) reverses.

    Floats for one design; arrays ``(m,)`` for forces of designs ``(m, 1)`` (:func:`solve`).
    """
    w = np.asarray(omega, dtype=float)

    def peak(values, axis=(0, -1)):
        return np.max(values, axis=axis)

    # over the samples of a period; where the load is 0 no wall is chosen
    reversals = np.max(_sign_changes(np.sign(forces.impeller_torque)), axis=0)
    out = {
        "load_reversals_per_period": reversals,
        "peak_slider_force_N": peak(np.abs(forces.slider)),
        "peak_slider_speed_m_per_s": peak(np.abs(forces.pin_slip) * w),
    }
    for k in (0, 1):
        out[f"peak_input_mesh{k + 1}_tangential_force_N"] = peak(np.abs(forces.input_mesh[k]),
                                                                 -1)  # fmt: skip
    for k in (0, 1):
        out[f"peak_impeller_mesh{k + 1}_tangential_force_N"] = peak(
            np.abs(forces.impeller_mesh[k]), -1)  # fmt: skip
    for key, vec in (("crank_bearing", forces.crank_bearing),
                     ("guide_pivot", forces.guide_bearing)):  # fmt: skip
        out[f"peak_{key}_load_N"] = peak(np.hypot(vec[:, 0], vec[:, 1]))
    out["peak_input_bearing_load_N"] = peak(np.hypot(*forces.input_bearing), -1)
    return {k: v.item() if np.ndim(v) == 0 else v for k, v in out.items()}


def _sign_changes(sign):
    """Changes of sign along the last axis, zeros skipped (the sign before them carries on)."""
    at = np.arange(sign.shape[-1])
    last = np.maximum.accumulate(np.where(sign != 0, at, 0), axis=-1)
    held = np.take_along_axis(sign, last, axis=-1)
    return np.sum((held[..., 1:] != held[..., :-1]) & (held[..., :-1] != 0), axis=-1)


#: Docs of :func:`signed_columns`.
SIGNED_DOCS = {
    **{f"slider{m}_normal_N": f"Force of guide bar {m} on its slider block across the guide "
       "(n_g, the guide's sense of turning) [N]: + the slot's trailing wall carries it (the guide "
       "bar drives), - the leading wall (the block drives)." for m in (1, 2)},
    **{f"input_mesh{m}_tangential_N": f"Tangential force of input gear 1 on gear {g} [N], + on "
       "the drive flank (gear 1 drives)." for m, g in ((1, 2), (2, 9))},
    **{f"impeller_mesh{m}_tangential_N": f"Tangential force of gear {g} on impeller gear {i} [N], "
       "+ on the drive flank, - on the back flank (the impeller overruns)."
       for m, g, i in ((1, 6, 7), (2, 11, 8))},
}  # fmt: skip


def signed_columns(forces: Forces) -> dict:
    """motion.csv columns with the signs the magnitudes lose (:data:`SIGNED_DOCS`)."""
    cols = {}
    for k in (0, 1):
        cols[f"slider{k + 1}_normal_N"] = forces.slider[k]
    for k in (0, 1):
        cols[f"input_mesh{k + 1}_tangential_N"] = forces.input_mesh[k]
    for k in (0, 1):
        cols[f"impeller_mesh{k + 1}_tangential_N"] = forces.impeller_mesh[k]
    return cols
