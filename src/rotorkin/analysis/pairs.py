"""The load-carrying pairs of a drive: forces, contact stress, friction and efficiency.

A drive's kinetostatics (``rotorkin/drives/<name>/forces.py``) gives, at every
shaft angle, one :class:`Pair` per kinematic pair that carries load: the normal
force, how fast the pair slips or rolls, and, for a contact, the radii that set
its Hertz stress. This module turns a list of pairs into what every drive reports
(:func:`summary`, :func:`columns`), one way for all drives:

* **Contact stress**: Hertz (:mod:`rotorkin.analysis.contact`), line contact of a
  roller of ``contact.roller_width`` (``("line", r1, r2)``) or point contact
  (``("point", rx1, ry1, rx2, ry2)``); the largest over the turn, where, and the
  safety factor ``contact.allowable_stress / p_max``.
* **Friction** (first order in the coefficients: friction does not change the
  normal forces): the power lost in a pair is ``c N |s| omega`` with the pair's
  coefficient ``c`` (``contact.friction_<kind>``) and its slip ``s`` [m per rad of
  shaft]: the sliding speed of a sliding pair; the rolling speed of a rolling pair
  (``c`` a rolling-resistance coefficient); the pitch-line speed times the cosine
  of the pressure angle of a gear mesh (``c`` the fraction of the transmitted power a
  mesh loses); the journal radius times the relative turning speed of a bearing.
  The friction torque on the shaft is ``sum c N |s|`` (it always resists), the
  work lost per turn its integral.
* **Efficiency**: an engine (work on the shaft ``W > 0``) delivers
  ``(W - W_loss) / W``; a pump or compressor (``W < 0``) needs ``|W| + W_loss`` for
  ``|W|``: ``|W| / (|W| + W_loss)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorkin.analysis import contact as hz

__all__ = ["KINDS", "NUMBER_KEYS", "Pair", "ContactModel", "stress", "friction_torque", "summary",
           "columns"]  # fmt: skip

#: The kinds of pair, each with its friction coefficient ``contact.friction_<kind>``.
KINDS = ("rolling", "sliding", "mesh", "bearing")


@dataclass(frozen=True)
class Pair:
    """One load-carrying pair over the shaft angles.

    Attributes
    ----------
    name : str
        For people: ``"roller 1 on its groove"``.
    slug : str
        Column stem: ``"roller1_groove"``.
    kind : str
        One of :data:`KINDS`.
    force : ndarray, shape (...)
        Magnitude of the normal force the pair carries [N], at the shaft angles.
    slip : ndarray, shape (...)
        Sliding, rolling, pitch-line or journal speed per unit shaft speed [m/rad]
        (see the module text); its sign does not matter.
    geometry : tuple, optional
        Hertz geometry: ``("line", r1, r2)`` (a roller of ``contact.roller_width``;
        signed radii of curvature, + convex, - concave, ``inf`` flat), ``("line", r1, r2,
        width)`` (a contact of its own width, e.g. a gear's face width) or
        ``("point", rx1, ry1, rx2, ry2)``; radii broadcast with ``force``. None: no
        contact stress (bearings, pins).
    where : str
        Frame, direction and sign convention of the force (one sentence).
    """

    name: str
    slug: str
    kind: str
    force: np.ndarray
    slip: np.ndarray
    geometry: tuple | None = None
    where: str = ""

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"pair kind {self.kind!r} is not one of {KINDS}")


@dataclass(frozen=True)
class ContactModel:
    """Materials, roller width, friction coefficients and limits (the ``[contact]`` section)."""

    youngs_modulus: float = 210e9
    poisson_ratio: float = 0.3
    roller_width: float = 0.010
    allowable_stress: float = 1.5e9
    friction: dict | None = None  # kind -> coefficient
    efficiency_min: float = 0.9

    @classmethod
    def from_config(cls, cfg: dict) -> ContactModel:
        """From a validated config's ``[contact]`` section (SI); defaults where missing."""
        c = cfg.get("contact") or {}
        defaults = {"rolling": 0.002, "sliding": 0.08, "mesh": 0.01, "bearing": 0.0015}
        friction = {k: float(c.get(f"friction_{k}", v)) for k, v in defaults.items()}
        return cls(float(c.get("youngs_modulus", 210e9)), float(c.get("poisson_ratio", 0.3)),
                   float(c.get("roller_width", 0.010)),
                   float(c.get("allowable_stress", 1.5e9)), friction,
                   float(c.get("efficiency_min", 0.9)))  # fmt: skip

    def coefficient(self, kind: str):
        """Friction coefficient of the pairs of ``kind``: a float, or an array of designs."""
        c = (self.friction or {}).get(kind, 0.0)
        return float(c) if np.ndim(c) == 0 else np.asarray(c, dtype=float)


def stress(pair: Pair, model: ContactModel) -> np.ndarray | None:
    """Peak Hertz pressure of a contact pair at every angle [Pa]; None without geometry."""
    if pair.geometry is None:
        return None
    force = np.abs(np.asarray(pair.force, dtype=float))
    shape, *radii = pair.geometry
    m = hz.Material(model.youngs_modulus, model.poisson_ratio)
    if shape == "line":  # ("line", r1, r2) with the roller width, or ("line", r1, r2, width)
        width = radii[2] if len(radii) > 2 else model.roller_width
        return hz.line_contact(force, width, radii[0], radii[1], m, m).p_max
    return hz.point_contact(force, *radii, m, m).p_max


def friction_torque(pairs, model: ContactModel) -> np.ndarray:
    """Torque friction takes from the shaft, ``sum c N |s|`` [N m] (always resisting)."""
    return sum(model.coefficient(p.kind) * np.abs(p.force) * np.abs(p.slip) for p in pairs)


#: The numeric keys of :func:`summary` (with contact pairs that have a geometry, and
#: bearings); the names of the peaks' pairs are text.
NUMBER_KEYS = (
    "peak_contact_force_N",
    "peak_contact_stress_MPa",
    "peak_contact_stress_at_deg",
    "contact_safety_factor",
    "peak_bearing_load_N",
    "friction_loss_J_per_rev",
    "friction_loss_W",
    "mechanical_efficiency",
)


def summary(pairs, theta, work_per_turn, model: ContactModel, omega, batch: bool = False) -> dict:
    """The contact, bearing, friction and efficiency keys of a study's summary.

    Parameters
    ----------
    pairs : list of Pair
        Over ``theta``.
    theta : ndarray, shape (n,)
        Shaft angles of one turn (or of the drive's span), ends included [rad].
    work_per_turn : float or ndarray
        Work of the machine on the shaft per turn, friction aside [J] (+ engine).
    model : ContactModel
        Its values floats or, with ``batch``, arrays of shape ``(designs, 1)``.
    omega : ndarray, shape (n,) or (..., n)
        Shaft speed at ``theta`` [rad/s].
    batch : bool, optional
        False (one design): floats, each peak over all the values of a pair. True
        (many designs): forces, slips and ``omega`` of shape ``(..., n)``, every key an
        array ``(...)`` of the designs, each peak over the last axis (the angles).
    """
    theta = np.asarray(theta, dtype=float)
    span = float(theta[-1] - theta[0])
    axis = -1 if batch else None
    out = {}
    contacts = [p for p in pairs if p.kind != "bearing"]
    bearings = [p for p in pairs if p.kind == "bearing"]
    if contacts:
        peak = np.stack(np.broadcast_arrays(*(np.max(np.abs(p.force), axis=axis)
                                              for p in contacts)))  # fmt: skip
        k = _first_peak(peak)
        out["peak_contact_force_N"] = _pick(peak, k)
        out["peak_contact_force_pair"] = np.asarray([p.name for p in contacts])[k]
    stressed = [(p, stress(p, model)) for p in contacts if p.geometry is not None]
    if stressed:
        curves = np.stack(np.broadcast_arrays(*(s for _, s in stressed)))
        if batch:
            peaks = np.fmax.reduce(curves, axis=-1)  # NaN only where every angle is NaN
        else:
            peaks = np.array([np.nanmax(s) for _, s in stressed])
        k = _first_peak(peaks)
        top = _pick(peaks, k)
        s = _pick(curves, k)
        out["peak_contact_stress_MPa"] = top / 1e6
        out["peak_contact_stress_pair"] = np.asarray([p.name for p, _ in stressed])[k]
        if batch:
            at = np.argmax(s == top[..., None], axis=-1)  # the first angle of the peak
            out["peak_contact_stress_at_deg"] = np.where(np.isnan(top), np.nan,
                                                         np.degrees(theta[at]))  # fmt: skip
        else:
            out["peak_contact_stress_at_deg"] = np.degrees(theta[int(np.nanargmax(s))])
        allowable = np.asarray(model.allowable_stress, dtype=float)
        if batch and allowable.ndim:
            allowable = allowable[..., 0]  # (designs, 1) against the angles
        with np.errstate(divide="ignore", invalid="ignore"):
            safety = np.where(top > 0, allowable / top, np.inf)
        out["contact_safety_factor"] = np.where(np.isnan(top), np.nan, safety) if batch else safety
    if bearings:
        out["peak_bearing_load_N"] = np.max(np.stack(np.broadcast_arrays(
            *(np.max(np.abs(p.force), axis=axis) for p in bearings))), axis=0)  # fmt: skip
    loss_torque = friction_torque(pairs, model) if pairs else np.zeros_like(theta)
    loss_span = np.trapezoid(loss_torque, theta, axis=-1)
    loss_turn = loss_span * 2.0 * np.pi / span
    seconds = np.trapezoid(1.0 / np.asarray(omega, dtype=float), theta, axis=-1)
    out["friction_loss_J_per_rev"] = loss_turn
    out["friction_loss_W"] = loss_span / seconds
    w = np.asarray(work_per_turn, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        out["mechanical_efficiency"] = np.where(
            w > 0.0, (w - loss_turn) / w, np.where(w < 0.0, -w / (-w + loss_turn), np.nan)
        )
    if batch:
        return out
    return {k: v.item() if np.ndim(v) == 0 and hasattr(v, "item") else v for k, v in out.items()}


#: Peaks of two pairs closer than this (relative) are a tie: the first pair is named.
PEAK_TIE = 1e-9


def _first_peak(values):
    """Index along the first axis of the largest of ``values`` (>= 0), per design.

    Pairs that mirror each other (a drive's symmetric rollers) peak at the same value but
    for rounding, which would name one or the other at random from one platform or model
    input to the next: the first pair within :data:`PEAK_TIE` of the largest is named.
    A design with a NaN peak names its first NaN pair (as ``argmax``).
    """
    top = np.max(values, axis=0)
    with np.errstate(invalid="ignore"):
        k = np.argmax(values >= top * (1.0 - PEAK_TIE), axis=0)
    return np.where(np.isnan(top), np.argmax(values, axis=0), k)


def _pick(values, k):
    """``values[k]`` along the first axis, per design: ``k`` indexes the leading axes of
    the rest (one design: ``k`` a scalar)."""
    k = np.asarray(k)
    index = k.reshape((1,) + k.shape + (1,) * (values.ndim - 1 - k.ndim))
    return np.take_along_axis(values, index, axis=0)[0]


def columns(pairs, model: ContactModel, shaft_torque) -> tuple[dict, dict]:
    """motion.csv columns: each pair's force (and contact stress), the friction torque."""
    cols, docs = {}, {}
    for p in pairs:
        cols[f"{p.slug}_force_N"] = np.abs(np.asarray(p.force, dtype=float))
        docs[f"{p.slug}_force_N"] = f"Normal force of {p.name} ({p.kind}). {p.where}".strip()
        s = stress(p, model)
        if s is not None:
            cols[f"{p.slug}_contact_stress_MPa"] = s / 1e6
            docs[f"{p.slug}_contact_stress_MPa"] = f"Peak Hertz pressure of {p.name}."
    loss = friction_torque(pairs, model) if pairs else np.zeros_like(shaft_torque)
    cols["friction_torque_Nm"] = np.asarray(loss, dtype=float)
    docs["friction_torque_Nm"] = ("Torque friction takes from the shaft, sum of c N |slip| over "
                                  "the pairs (first order in the coefficients).")  # fmt: skip
    cols["shaft_torque_with_friction_Nm"] = np.asarray(shaft_torque, dtype=float) - loss
    docs["shaft_torque_with_friction_Nm"] = "shaft_torque_Nm less the friction torque."
    return cols, docs
