"""Double eccentric cams: lambda, or the follower, for a tolerated gap change.

Zhu & Zhu 2012 (``papers/eccentric_pistons.md``): with point contact the gap
between the two pistons changes by ``Delta = 2 (sqrt(Rc^2 - e^2 sin^2 beta) - Rc)``
(eq. 5; ``Rc = R`` for a knife edge, ``R + r`` for a roller of radius r), most
at ``beta = 90 deg``: ``|Delta|_max = 2 (Rc - sqrt(Rc^2 - e^2))``; a flat-faced
follower gives ``Delta = 0`` (eq. 7, 8). Inverting the peak (derived here):

* keep the disc (contact radius Rc), change the eccentricity:
  ``e = sqrt(d (2 Rc - d))``, ``d = |Delta|_max / 2``;
* keep the eccentricity e (the stroke 2e), change the contact radius:
  ``Rc = (e^2 + d^2) / (2 d)``, i.e. ``lambda_c = e/Rc = 2q/(1 + q^2)``, ``q = d/e < 1``
  (``lambda = sin t`` gives ``|Delta|/(2e) = tan(t/2)``);
* keep both, fit a roller: ``r = Rc - R`` with that Rc (if positive);
* a flat follower: zero gap change for every lambda.

The synthesized design keeps the eccentricity (the stroke the process needs)
and the follower kind and sets the disc radius (option "stroke"); a target of
zero gives the flat follower.
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.angles import fmt_mm
from rotorkin.core.errors import ParameterError
from rotorkin.core.schema import validate_model
from rotorkin.drives.eccentric_cam import figures_synthesis, schema, study
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.synthesis import (
    SynthesisResult,
    parse_fraction,
    parse_quantity_arg,
    synthesized_raw_config,
)

__all__ = [
    "gap_change_peak",
    "eccentricity_for_gap_change",
    "contact_radius_for_gap_change",
    "design_options",
    "DEFAULT_GAP_SHARE",
    "default_gap_change",
    "synthesize",
]


def gap_change_peak(contact_radius, eccentricity):
    """Largest gap change magnitude ``2 (Rc - sqrt(Rc^2 - e^2))`` [m] (eq. 5 at 90 deg).

    Minus twice :func:`~rotorkin.drives.eccentric_cam.kinematics.additional_travel` at
    90 deg; 0 for ``Rc = inf``. Broadcasts.
    """
    return -2.0 * ec.additional_travel(contact_radius, eccentricity, 0.5 * np.pi)[0]


def eccentricity_for_gap_change(gap, contact_radius):
    """Eccentricity giving the peak gap change ``gap`` with contact radius Rc [m].

    ``e = sqrt(d (2 Rc - d))``, ``d = gap/2``; NaN unless ``0 < gap < 2 Rc``.
    """
    d = 0.5 * np.asarray(gap, dtype=float)
    Rc = np.asarray(contact_radius, dtype=float)
    ok = (d > 0.0) & (d < Rc)
    return np.where(ok, np.sqrt(np.where(ok, d * (2.0 * Rc - d), 1.0)), np.nan)


def contact_radius_for_gap_change(gap, eccentricity):
    """Contact radius Rc (disc, or disc + roller) for the peak gap change ``gap`` at eccentricity e.

    Returns Rc [m].

    ``Rc = (e^2 + d^2)/(2 d)``, ``d = gap/2``; NaN unless ``0 < gap < 2 e``
    (larger gaps need ``lambda_c = e/Rc >= 1``).
    """
    d = 0.5 * np.asarray(gap, dtype=float)
    e = np.asarray(eccentricity, dtype=float)
    ok = (d > 0.0) & (d < e)
    dd = np.where(ok, d, 1.0)
    return np.where(ok, (e * e + dd * dd) / (2.0 * dd), np.nan)


def design_options(params: ec.EccentricCam, gap: float) -> list[dict]:
    """Every way to reach the peak gap change ``gap`` [m] from the design ``params``.

    Returns
    -------
    list of dict
        One per option, with keys ``option``, ``follower``, ``disc_radius``,
        ``eccentricity``, ``roller_radius`` [m], ``lambda`` (e/R), ``feasible`` (bool) and
        ``why`` (text, when not feasible).
    """
    R, e = float(params.disc_radius), float(params.eccentricity)
    follower = "knife_edge" if params.follower == "flat" else params.follower
    r = float(params.roller_radius) if follower == "roller" else 0.0
    out = []

    def add(option, fol, disc, ecc, roller, why=""):
        ok = bool(np.isfinite(disc) and np.isfinite(ecc) and 0.0 < ecc < disc and not why)
        out.append(
            {
                "option": option,
                "follower": fol,
                "disc_radius": float(disc),
                "eccentricity": float(ecc),
                "roller_radius": float(roller),
                "lambda": float(ecc / disc) if ok else float("nan"),
                "feasible": ok,
                "why": why if not ok else "",
            }
        )

    if gap == 0.0:
        add("flat", "flat", R, e, 0.0)
        return out
    Rc = float(contact_radius_for_gap_change(gap, e))
    add(
        "stroke",
        follower,
        Rc - r,
        e,
        r,
        "" if np.isfinite(Rc) and Rc - r > e else f"needs gap < 2 e = {fmt_mm(2 * e)}",
    )
    e_new = float(eccentricity_for_gap_change(gap, R + r))
    add("disc", follower, R, e_new, r, "" if np.isfinite(e_new) else "gap too large for the disc")
    roller = Rc - R if np.isfinite(Rc) else np.nan
    add(
        "roller",
        "roller",
        R,
        e,
        roller,
        "" if np.isfinite(roller) and roller > 0.0 else "needs a smaller gap than the knife edge",
    )
    add("flat", "flat", R, e, 0.0, "gives zero gap change, below the target")
    out[-1]["feasible"] = True  # within any tolerance
    return out


#: Without a ``target``: this fraction of the design's own peak gap change is tolerated.
DEFAULT_GAP_SHARE = 0.5


def default_gap_change(params: ec.EccentricCam) -> float:
    """The tolerated peak gap change when none is given: half the design's own [m].

    The example (R = 80 mm, e = 40 mm, knife edge): 10.72 mm (1.072 % of L = 1 m), half
    its 21.44 mm; always reachable by keeping the eccentricity (it is below ``2 e``).
    A flat follower's own gap change is zero, and so is the default (the flat follower).
    """
    return DEFAULT_GAP_SHARE * abs(
        float(gap_change_peak(params.contact_radius, params.eccentricity))
    )


def _parse_gap(target, length):
    try:
        ratio = parse_fraction(target, "target")
        gap = ratio * length
    except ParameterError:
        gap = parse_quantity_arg(target, "length", "target")
    if not (np.isfinite(gap) and gap >= 0.0):
        raise ParameterError("target", repr(target), "a gap change |Delta| >= 0")
    return abs(gap)


def _format_length(x: float) -> str:
    return f"{x * 1e3!r} mm"


def synthesize(cfg, raw, objective, target, harmonics, options=None):
    """Design for the ``target`` peak gap change (objective ``gap_change``); see the module doc.

    Without a target, half the design's own peak gap change (:func:`default_gap_change`).
    """
    if harmonics is not None:
        raise ParameterError("harmonics", str(harmonics), "not used by the eccentric_cam drive")
    d = cfg["drive"]
    base = study.drive_params(cfg)
    length = float(cfg["machine"]["device_length"])
    gap = default_gap_change(base) if target is None else _parse_gap(target, length)
    options = design_options(base, gap)
    chosen = options[0]
    if not chosen["feasible"]:
        hi = 2.0 * float(base.eccentricity)
        raise ParameterError(
            "target",
            f"{fmt_mm(gap)} (|Delta|/L = {gap / length:.4g})",
            f"0 <= |Delta| < {fmt_mm(hi)} (|Delta|/L < {hi / length:.4g}) at the eccentricity "
            f"{fmt_mm(base.eccentricity)}; with the disc kept instead: {options[1]['why'] or 'ok'}",
        )
    updates = {
        "drive": {
            "follower": chosen["follower"],
            "disc_radius": _format_length(chosen["disc_radius"]),
            "eccentricity": _format_length(chosen["eccentricity"]),
        }
    }
    if chosen["follower"] == "roller":
        updates["drive"]["roller_radius"] = _format_length(chosen["roller_radius"])
    new_raw = synthesized_raw_config(raw, updates, objective)
    res0 = study.evaluate(cfg)
    res1 = study.evaluate(validate_model(schema.EccentricConfig, new_raw))
    gap_run = abs(float(res1.summary["gap_change_min_mm"])) * 1e-3
    rel_err = abs(gap_run - gap) / gap if gap > 0 else abs(gap_run)
    keys = (
        ("follower", "follower"),
        ("lambda", "lambda = e/R"),
        ("gap_change_min_mm", "gap change min [mm]"),
        ("gap_change_to_length_percent", "|gap change|/L [%]"),
        ("piston_stroke_mm", "piston stroke [mm]"),
        ("pressure_angle_max_deg", "pressure angle max [deg]"),
        ("pressure_ripple_relative", "pressure ripple"),
        ("piston_accel_peak_mm_per_rad2", "piston accel peak [mm/rad2]"),
    )
    rows = [("disc radius [mm]", d["disc_radius"] * 1e3, chosen["disc_radius"] * 1e3)]
    rows += [(label, res0.summary[k], res1.summary[k]) for k, label in keys]
    rows += [
        ("target |gap change| [mm]", "", gap * 1e3),
        ("round trip relative error", "", rel_err),
    ]
    metrics = {
        "target_gap_change_mm": gap * 1e3,
        "target_given": target is not None,
        "target_gap_change_to_length": gap / length,
        "round_trip_relative_error": rel_err,
    }
    for k, _ in keys:
        metrics[f"baseline_{k}"] = res0.summary[k]
        metrics[f"synthesized_{k}"] = res1.summary[k]
    for opt in options:
        for k in ("follower", "disc_radius", "eccentricity", "roller_radius", "lambda", "feasible"):
            v = opt[k]
            key = f"option_{opt['option']}_{k}" + ("_mm" if k.endswith(("radius", "ity")) else "")
            metrics[key] = v * 1e3 if key.endswith("_mm") else v
    notes = []
    if target is None:
        notes.append(
            f"no target given: |Delta| = {gap * 1e3:.6g} mm, half the design's own peak gap "
            f"change {abs(float(res0.summary['gap_change_min_mm'])):.6g} mm"
        )
    notes.append(
        f"options for |Delta| = {gap * 1e3:.6g} mm (|Delta|/L = {100 * gap / length:.6g} %):"
    )
    text = {
        "stroke": "keep eccentricity (stroke), set disc_radius",
        "disc": "keep disc_radius, set eccentricity (stroke changes)",
        "roller": "keep disc and eccentricity, roller follower",
        "flat": "flat follower: zero gap change for any lambda (eq. 7, 8)",
    }
    for opt in options:
        if opt["option"] == "flat":
            notes.append(f"  flat: {text['flat']}")
            continue
        state = (
            f"R = {opt['disc_radius'] * 1e3:.6g} mm, e = {opt['eccentricity'] * 1e3:.6g} mm, "
            f"r = {opt['roller_radius'] * 1e3:.6g} mm, lambda = {opt['lambda']:.6g}"
            if opt["feasible"]
            else f"not possible: {opt['why']}"
        )
        notes.append(f"  {opt['option']}: {text[opt['option']]}: {state}")
    new_params = ec.EccentricCam(
        chosen["disc_radius"],
        chosen["eccentricity"],
        chosen["follower"],
        chosen["roller_radius"] if chosen["follower"] == "roller" else 0.0,
    )

    def plot(outdir):
        feasible = [
            ec.EccentricCam(
                o["disc_radius"],
                o["eccentricity"],
                o["follower"],
                o["roller_radius"] if o["follower"] == "roller" else 0.0,
            )
            for o in options
            if o["feasible"] and o["option"] != "flat"
        ]
        return figures_synthesis.plot_eccentric(base, new_params, feasible, gap, length, outdir)

    return SynthesisResult(
        drive_type="eccentric_cam",
        objective=objective,
        title=f"eccentric cams: design for a peak gap change of {gap * 1e3:.6g} mm "
        f"({100 * gap / length:.4g} % of L)",
        rows=tuple(rows),
        parameters={
            "option": chosen["option"],
            "follower": chosen["follower"],
            "disc_radius_mm": chosen["disc_radius"] * 1e3,
            "eccentricity_mm": chosen["eccentricity"] * 1e3,
            "roller_radius_mm": chosen["roller_radius"] * 1e3,
            "lambda": chosen["lambda"],
        },
        metrics=metrics,
        updates=updates,
        notes=tuple(notes),
        plot=plot,
    )
