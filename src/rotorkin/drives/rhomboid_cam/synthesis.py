"""Rhomboid lever-cam converter: the law psi(alpha) that optimises an objective.

Zhuravlev, Donchenko, Sherstyukov 2012 (``papers/rhomboid_cam.md``). The law of
the angle between the blade axes is the odd-harmonic series of eq. 13,

    psi(alpha) = pi/2 + sum_{k = 1, 3, 5, ...} (a_k cos 2k alpha + b_k sin 2k alpha),

whose first harmonic follows from the end conditions (eq. 15):
``a_1 = pi/2 - psi_min - (a_3 + a_5 + ...)``, ``b_1 = -(3 b_3 + 5 b_5 + ...)``
(:func:`rotorkin.drives.rhomboid_cam.kinematics.first_harmonic`). The free variables are
the higher harmonics ``x = (a_3, a_5, ..., b_3, b_5, ...)`` (``N`` of each,
``--harmonics N``, default 2: the 3rd and 5th). The paper's law (eq. 16) is
``x = 0``; the paper concludes it is the best. It is not, for the objectives
below - at the price of others (the table of ``rotorkin synthesize`` shows both).

Objectives (smaller is better; all on a grid of ``alpha`` over one period):

* ``min_accel``: peak blade angular acceleration coefficient
  ``max |d2 phi_i / d alpha2| = max |psi''| / 2`` (eq. 22 differentiated);
* ``dwell_min`` / ``dwell_max``: minus the share of the period during which
  ``|psi - psi_min|`` (or ``|psi - psi_max|``) stays below
  :data:`~rotorkin.synthesis.DWELL_TOLERANCE` times the swing ``pi - 2 psi_min``
  (2 deg for the example's 100 deg). By eq. 10, ``psi(alpha + pi/2) = pi - psi(alpha)``,
  so every law dwells exactly as long near psi_max as near psi_min: the two
  objectives have the same optimum;
* ``min_pressure_angle``: the peak pressure angle of the rollers on the cam
  (:func:`rotorkin.drives.rhomboid_cam.cam.pressure_angles`).

Constraints (all designs, baseline included):

* eq. 15 (built in) and ``0 < psi < pi``;
* the law monotone between its extremes (``psi' <= 0`` on ``[0, pi/2]``, the rest
  by eq. 10): then ``psi_min <= psi <= psi_max``, the blades fit and the
  compression ratio and the indicator work ``A = Delta M Delta psi`` (eq. 34)
  stay those of the paper's design;
* no undercut: the smallest convex radius of curvature of the pitch curve
  at least ``cam.roller_radius`` (x 1.01);
* the peak pressure angle at most ``max(45 deg, the paper's law's peak)`` (or
  ``--max-pressure-angle``), less 0.01 deg on the design grid.

Method: :func:`scipy.optimize.differential_evolution` (seeded, vectorized over
the population, the paper's law in the first population) on a grid of
``alpha``, polished by SLSQP (epigraph form for the peak objectives); the result
is then checked on a 10x finer grid by the drive's own functions.
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.angles import fmt_deg
from rotorkin.core.errors import ParameterError
from rotorkin.core.schema import validate_model
from rotorkin.drives.rhomboid_cam import cam, figures_synthesis, study
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.drives.rhomboid_cam.schema import RhomboidConfig
from rotorkin.synthesis import (
    DWELL_TOLERANCE,
    SynthesisResult,
    dwell_fraction,
    synthesized_raw_config,
)

__all__ = [
    "OBJECTIVES",
    "PRESSURE_ANGLE_LIMIT",
    "Law",
    "objective_values",
    "constraint_values",
    "optimize_law",
    "law_report",
    "synthesize",
]

#: The rhomboid cam's objectives (as in :data:`rotorkin.synthesis.OBJECTIVES`).
OBJECTIVES = ("min_accel", "dwell_min", "dwell_max", "min_pressure_angle")
#: Default bound on the peak pressure angle [rad] (raised to the paper's law's peak if higher).
PRESSURE_ANGLE_LIMIT = np.radians(45.0)
#: Safety factor on the roller radius in the undercut constraint.
_UNDERCUT_FACTOR = 1.01
#: Relative margin of the monotonicity constraint (of the paper's law's psi').
_MONO_MARGIN = 1e-4
#: Margin of the pressure-angle constraint on the design grid [rad] (0.01 deg).
_PA_MARGIN = np.radians(0.01)
#: Samples per period of the design grid (a multiple of 4, see _pressure_batch).
_GRID = 720


class Law:
    """Batched evaluation of laws ``psi(alpha)`` for many harmonic vectors at once.

    Parameters
    ----------
    psi_min : float
        [rad].
    harmonics : int
        N: higher harmonics 3, 5, ..., 2N + 1 in a and in b.
    alpha : array_like, shape (G,)
        Output-shaft angles [rad].

    Notes
    -----
    ``psi^(n)(alpha) = base_n + x @ D_n`` is affine in ``x`` for every derivative
    order n: ``D_n`` holds, for ``a_k``, the kth basis function minus the first
    (eq. 15 takes ``a_k`` off ``a_1``) and, for ``b_k``, the kth minus k times the first.
    """

    def __init__(self, psi_min: float, harmonics: int, alpha):
        self.psi_min = float(psi_min)
        self.n = int(harmonics)
        self.alpha = np.asarray(alpha, dtype=float)
        k = np.concatenate(([1.0], 2.0 * np.arange(1, self.n + 1) + 1.0))
        w = 2.0 * k
        arg = w[:, None] * self.alpha
        a1 = 0.5 * np.pi - self.psi_min
        self.base, self.D = [], []
        for order in range(4):
            c = w[:, None] ** order * np.cos(arg + 0.5 * np.pi * order)
            s = w[:, None] ** order * np.sin(arg + 0.5 * np.pi * order)
            self.base.append(a1 * c[0] + (0.5 * np.pi if order == 0 else 0.0))
            self.D.append(np.concatenate([c[1:] - c[0], s[1:] - k[1:, None] * s[0]]))

    def split(self, x):
        """``(a, b)`` tuples of floats from one harmonic vector x."""
        x = np.asarray(x, dtype=float)
        return tuple(x[: self.n].tolist()), tuple(x[self.n :].tolist())

    def psi(self, x, order=0):
        """``d^order psi / d alpha^order``, shape ``(S, G)`` for x of shape ``(S, 2N)`` [rad]."""
        return self.base[order] + np.atleast_2d(x) @ self.D[order]


def _curvature(L, psi, d1, d2):
    """Signed curvature of the pitch curve ``rho = L cos(psi/2)`` [1/m], the drive's formula."""
    return rc.polar_curvature(*rc.radius_from_psi(L, (psi, d1, d2, 0.0))[:3])


def _pressure_batch(law: Law, L: float, x):
    """Peak pressure angle of each law, ``max arctan(|rho'|/rho)`` over the pitch curve [rad].

    The pressure angle of :func:`rotorkin.drives.rhomboid_cam.cam.pressure_angles` is
    ``arctan(rho'/rho)`` at the four rollers ``alpha + k pi/2``; on a grid of one
    period whose size is a multiple of 4 the rollers visit the same samples as the
    pitch curve itself, so the peak is that of ``|rho'|/rho = |tan(psi/2) psi'|/2``
    over the grid (batched over laws; the final check uses the cams module itself).
    """
    x = np.atleast_2d(x)
    rho, drho = rc.radius_from_psi(L, (law.psi(x), law.psi(x, 1), 0.0, 0.0))[:2]
    return np.arctan(np.max(np.abs(drho) / rho, axis=-1))


def objective_values(law: Law, objective: str, x, L: float = 1.0):
    """Objective of each harmonic vector (smaller is better), shape ``(S,)``.

    ``min_accel``: ``max |psi''|/2``; ``dwell_min``/``dwell_max``: minus the dwell
    fraction; ``min_pressure_angle``: the peak pressure angle [rad].
    """
    if objective == "min_accel":
        return 0.5 * np.max(np.abs(law.psi(x, 2)), axis=-1)
    if objective in ("dwell_min", "dwell_max"):
        extreme = law.psi_min if objective == "dwell_min" else np.pi - law.psi_min
        tol = DWELL_TOLERANCE * (np.pi - 2.0 * law.psi_min)
        return -dwell_fraction(law.psi(x), extreme, tol)
    if objective == "min_pressure_angle":
        return _pressure_batch(law, L, x)
    raise ParameterError("objective", repr(objective), "one of " + ", ".join(OBJECTIVES))


def constraint_values(law: Law, x, L, roller_radius, pa_limit, quarter):
    """Constraint margins (>= 0 when satisfied), shape ``(3, S)``.

    Rows: monotone (``min(-psi' - margin)`` on the quarter period, in rad),
    undercut (``1 - 1.01 r kappa_max``), pressure angle (``limit - 0.01 deg - peak``
    [rad]; 0 when ``pa_limit`` is NaN: no bound).
    """
    x = np.atleast_2d(x)
    d1q = quarter.psi(x, 1)
    margin = _MONO_MARGIN * (0.5 * np.pi - law.psi_min) * 2.0 * np.sin(2.0 * quarter.alpha)
    mono = np.min(-d1q - margin, axis=-1)
    kappa = _curvature(L, law.psi(x), law.psi(x, 1), law.psi(x, 2))
    under = 1.0 - _UNDERCUT_FACTOR * roller_radius * np.max(kappa, axis=-1)
    if np.isfinite(pa_limit):
        press = pa_limit - _PA_MARGIN - _pressure_batch(law, L, x)
    else:
        press = np.zeros(x.shape[0])
    return np.stack([mono, under, press])


def optimize_law(
    link_length,
    psi_min,
    roller_radius,
    objective: str,
    harmonics: int = 2,
    pa_limit=None,
    seed: int = 1,
    maxiter: int = 100,
    popsize: int = 15,
):
    """The harmonics ``x = (a3, a5, ..., b3, b5, ...)`` that minimise ``objective`` [rad].

    Parameters
    ----------
    link_length, psi_min, roller_radius : float
        ``2l`` [m], psi_min [rad], cam roller radius [m].
    objective : str
        One of :data:`OBJECTIVES`.
    harmonics : int, optional
        N (default 2: 3rd and 5th).
    pa_limit : float, optional
        Bound on the peak pressure angle [rad]; default
        ``max(PRESSURE_ANGLE_LIMIT, paper's law's peak)``; NaN disables it.
    seed, maxiter, popsize : int, optional
        Differential evolution's seed and budget.

    Returns
    -------
    (x, info) : ndarray, dict
        The optimum and ``{"objective": value, "baseline": value, "pa_limit": rad,
        "constraints": (3,) margins, "evaluations": int}``.
    """
    from scipy.optimize import NonlinearConstraint, differential_evolution, minimize

    L, r = float(link_length), float(roller_radius)
    n = int(harmonics)
    alpha = np.arange(_GRID) * np.pi / _GRID
    law = Law(psi_min, n, alpha)
    quarter = Law(psi_min, n, np.linspace(0.0, 0.5 * np.pi, _GRID // 2 + 1)[1:-1])
    x0 = np.zeros(2 * n)
    if pa_limit is None:
        base_pa = float(_pressure_batch(law, L, x0)[0])
        pa_limit = max(PRESSURE_ANGLE_LIMIT, base_pa)

    def f(xs):  # DE vectorized: xs has shape (2N, S)
        return objective_values(law, objective, xs.T, L)

    def g(xs):
        return constraint_values(law, xs.T, L, r, pa_limit, quarter)

    span = 0.5 * np.pi - float(psi_min)
    bounds = [(-span, span)] * n + [(-span / 3.0, span / 3.0)] * n
    de = differential_evolution(
        f,
        bounds,
        constraints=NonlinearConstraint(g, 0.0, np.inf),
        seed=seed,
        maxiter=maxiter,
        popsize=popsize,
        tol=1e-10,
        x0=x0,
        polish=False,
        vectorized=True,
        updating="deferred",
    )
    best = de.x
    evals = int(de.nfev)

    # polish by SLSQP: the peak objectives in epigraph form (minimise t >= every sample)
    def cons_x(x):
        return _vector_constraints(law, quarter, x, L, r, pa_limit)

    samples = _peak_samples(law, objective, L)
    if samples is not None:
        z0 = np.append(best, f(best[:, None])[0])
        res = minimize(
            lambda z: z[-1],
            z0,
            method="SLSQP",
            constraints=[
                {"type": "ineq", "fun": lambda z: cons_x(z[:-1])},
                {"type": "ineq", "fun": lambda z: z[-1] - samples(z[:-1])},
            ],
            options={"maxiter": 200, "ftol": 1e-12},
        )
        cand = res.x[:-1]
    else:
        res = minimize(
            lambda z: f(z[:, None])[0],
            best,
            method="SLSQP",
            constraints=[{"type": "ineq", "fun": cons_x}],
            options={"maxiter": 100, "ftol": 1e-12},
        )
        cand = res.x
    evals += int(res.nfev)
    if np.all(g(cand[:, None]) >= 0.0) and f(cand[:, None])[0] < f(best[:, None])[0]:
        best = cand
    clean = np.where(np.abs(best) < 1e-10, 0.0, best)  # optimiser noise, e.g. b of a symmetric law
    if np.all(g(clean[:, None]) >= 0.0) and f(clean[:, None])[0] <= f(best[:, None])[0] + 1e-9:
        best = clean
    info = {
        "objective": float(f(best[:, None])[0]),
        "baseline": float(f(x0[:, None])[0]),
        "pa_limit": float(pa_limit),
        "constraints": g(best[:, None])[:, 0],
        "evaluations": evals,
    }
    return best, info


def _peak_samples(law, objective, L):
    """For a peak objective, the function of x whose largest sample is the objective."""
    if objective == "min_accel":
        return lambda x: np.concatenate([0.5 * law.psi(x, 2)[0], -0.5 * law.psi(x, 2)[0]])
    if objective == "min_pressure_angle":
        return lambda x: _pressure_samples(law, x)
    return None


def _pressure_samples(law, x):
    """``arctan(|rho'|/rho)`` of one law over the grid [rad]."""
    t = np.abs(np.tan(0.5 * law.psi(x)) * law.psi(x, 1))[0] * 0.5
    return np.arctan(t)


def _vector_constraints(law, quarter, x, L, r, pa_limit):
    """Every sampled constraint of one design (SLSQP): monotone, undercut, pressure angle."""
    x = np.atleast_2d(x)
    margin = _MONO_MARGIN * (0.5 * np.pi - law.psi_min) * 2.0 * np.sin(2.0 * quarter.alpha)
    mono = (-quarter.psi(x, 1) - margin)[0]
    kappa = _curvature(L, law.psi(x), law.psi(x, 1), law.psi(x, 2))[0]
    under = 1.0 - _UNDERCUT_FACTOR * r * kappa
    parts = [mono, under]
    if np.isfinite(pa_limit):
        parts.append(pa_limit - _PA_MARGIN - _pressure_samples(law, x))
    return np.concatenate(parts)


# --------------------------------------------------------------------------------------------
# checks on a fine grid and the command's entry point
# --------------------------------------------------------------------------------------------
_FINE = 20_000


def law_report(link_length, psi_min, a, b, roller_radius) -> dict:
    """Objectives and checks of one law, computed independently of the optimiser [SI].

    The drive's own functions on 20000 samples per period and the cams module's
    :func:`rotorkin.drives.rhomboid_cam.cam.profile_check`.

    Returns
    -------
    dict
        ``accel_peak`` (``max |psi''|/2``), ``jerk_peak``, ``speed_coeff_min``/``max``,
        ``dwell_min``/``dwell_max`` (fractions), ``pressure_angle_peak`` [rad],
        ``min_convex_radius``, ``min_concave_radius``, ``min_clearance`` [m],
        ``undercut``, ``monotone`` (bool), ``psi_lowest``, ``psi_highest`` [rad].
    """
    alpha = np.arange(_FINE) * np.pi / _FINE
    psi = rc.psi_law(psi_min, a, b, alpha)[0]
    peaks = rc.law_peaks(link_length, psi_min, a, b, alpha)
    tol = DWELL_TOLERANCE * (np.pi - 2.0 * psi_min)
    chk = cam.profile_check(link_length, psi_min, a, b, roller_radius)
    lo, _, hi, _ = rc.psi_extremes(psi_min, a, b)
    return {
        "accel_peak": float(peaks["accel_coeff_max"]),
        "jerk_peak": float(peaks["jerk_coeff_max"]),
        "speed_coeff_min": float(peaks["speed_coeff_min"]),
        "speed_coeff_max": float(peaks["speed_coeff_max"]),
        "dwell_min": float(dwell_fraction(psi, psi_min, tol)),
        "dwell_max": float(dwell_fraction(psi, np.pi - psi_min, tol)),
        "pressure_angle_peak": float(chk.max_pressure_angle),
        "min_convex_radius": float(chk.min_convex_radius),
        "min_concave_radius": float(chk.min_concave_radius),
        "min_clearance": float(chk.min_clearance),
        "undercut": bool(chk.undercut),
        "monotone": bool(rc.psi_is_monotone(psi_min, a, b)),
        "psi_lowest": lo,
        "psi_highest": hi,
    }


#: objective -> (law_report key, sign: +1 smaller is better, -1 larger is better, label)
_MEASURE = {
    "min_accel": ("accel_peak", 1.0, "peak blade accel |d2phi/dalpha2| [1/rad]"),
    "dwell_min": ("dwell_min", -1.0, "dwell near psi_min [% of period]"),
    "dwell_max": ("dwell_max", -1.0, "dwell near psi_max [% of period]"),
    "min_pressure_angle": ("pressure_angle_peak", 1.0, "peak pressure angle [deg]"),
}


def _shown(key, value):
    if key.startswith("dwell"):
        return 100.0 * value
    if key in ("pressure_angle_peak", "psi_lowest", "psi_highest"):
        return float(np.degrees(value))
    if key.startswith("min_c"):
        return value * 1e3
    return value


def synthesize(cfg, raw, objective, target, harmonics, options=None):
    """Optimal harmonics for ``objective``, beside the first-harmonic law (eq. 16).

    See :func:`rotorkin.synthesis.synthesize`; ``options`` may hold
    ``max_pressure_angle`` [rad].
    """
    if target is not None:
        raise ParameterError(
            "target",
            repr(target),
            f"no target for {objective}: the rhomboid cam's objectives are optimised "
            "(min_accel, dwell_min, dwell_max, min_pressure_angle)",
        )
    n = 2 if harmonics is None else int(harmonics)
    if n > rc.MAX_HARMONICS:
        raise ParameterError("harmonics", str(n), f"1 <= harmonics <= {rc.MAX_HARMONICS}")
    d = cfg["drive"]
    L, pmin, r = float(d["link_length"]), float(d["psi_min"]), float(cfg["cam"]["roller_radius"])
    base_cfg = validate_model(
        RhomboidConfig, synthesized_raw_config(raw, {"drive": {"a": [], "b": []}})
    )
    res0 = study.evaluate(base_cfg)  # validates the design with the paper's law
    rep0 = law_report(L, pmin, (), (), r)
    if rep0["undercut"]:
        raise ParameterError(
            "cam.roller_radius",
            f"{r * 1e3:.4g} mm",
            f"roller_radius < {rep0['min_convex_radius'] * 1e3:.4g} mm: even the first-harmonic "
            "law undercuts the cam with this roller",
        )
    limit = (options or {}).get("max_pressure_angle")
    if limit is not None and not limit > rep0["pressure_angle_peak"] - np.radians(1.0):
        raise ParameterError(
            "max_pressure_angle",
            fmt_deg(limit),
            f"> {fmt_deg(rep0['pressure_angle_peak'] - np.radians(1.0))} (the first-harmonic law "
            f"reaches {fmt_deg(rep0['pressure_angle_peak'])}; a bound far below it leaves no "
            "admissible law)",
        )
    x, info = optimize_law(L, pmin, r, objective, n, pa_limit=limit)
    a, b = tuple(x[:n].tolist()), tuple(x[n:].tolist())
    updates = {"drive": {"a": list(a), "b": list(b)}}
    res1 = study.evaluate(
        validate_model(RhomboidConfig, synthesized_raw_config(raw, updates, objective))
    )
    rep1 = law_report(L, pmin, a, b, r)
    key, sign, label = _MEASURE[objective]
    better = sign * rep1[key] < sign * rep0[key]
    feasible = (
        rep1["monotone"]
        and not rep1["undercut"]
        and rep1["min_convex_radius"] >= r
        and rep1["pressure_angle_peak"] <= info["pa_limit"]
    )
    rows = [(f"objective: {label}", _shown(key, rep0[key]), _shown(key, rep1[key]))]
    rows.append(("harmonics a3, a5, ... [rad]", "-", ", ".join(f"{v:.5g}" for v in a)))
    rows.append(("harmonics b3, b5, ... [rad]", "-", ", ".join(f"{v:.5g}" for v in b)))
    shown = (
        ("accel_peak", "peak blade accel [1/rad]"),
        ("jerk_peak", "peak blade jerk [1/rad2]"),
        ("speed_coeff_min", "blade speed coeff min"),
        ("speed_coeff_max", "blade speed coeff max"),
        ("dwell_min", "dwell near psi_min [%]"),
        ("pressure_angle_peak", "peak pressure angle [deg]"),
        ("min_convex_radius", "min convex radius of curvature [mm]"),
        ("min_concave_radius", "min concave radius of curvature [mm]"),
        ("min_clearance", "min roller clearance [mm]"),
        ("psi_lowest", "psi lowest [deg]"),
        ("psi_highest", "psi highest [deg]"),
        ("monotone", "check: psi monotone"),
        ("undercut", "check: undercut"),
    )
    rows += [(lab, _shown(k, rep0[k]), _shown(k, rep1[k])) for k, lab in shown if k != key]
    rows.append(("check: pressure angle bound [deg]", "", float(np.degrees(info["pa_limit"]))))
    rows.append(("check: roller radius [mm]", "", r * 1e3))
    for k, lab in (
        ("indicator_work_J", "indicator work per half turn [J]"),
        ("torque_ripple", "torque ripple"),
        ("flywheel_inertia_kgm2", "flywheel inertia [kg m2]"),
    ):
        rows.append((lab, res0.summary[k], res1.summary[k]))
    rows.append(("strictly better, constraints met", "", bool(better and feasible)))
    metrics = {"objective_key": key, "better": bool(better), "constraints_met": bool(feasible)}
    metrics.update({f"baseline_{k}": v for k, v in rep0.items()})
    metrics.update({f"synthesized_{k}": v for k, v in rep1.items()})
    metrics.update(
        {
            "pressure_angle_limit_deg": float(np.degrees(info["pa_limit"])),
            "roller_radius_mm": r * 1e3,
            "optimizer_evaluations": info["evaluations"],
            "baseline_indicator_work_J": res0.summary["indicator_work_J"],
            "synthesized_indicator_work_J": res1.summary["indicator_work_J"],
        }
    )
    notes = []
    if objective in ("dwell_min", "dwell_max"):
        notes.append(
            "by eq. 10 (psi(alpha + 90 deg) = 180 deg - psi(alpha)) every law dwells as long near "
            "psi_max as near psi_min: dwell_min and dwell_max have the same optimum"
        )
    if d.get("a") or d.get("b"):
        notes.append("the config's own harmonics a, b were replaced (baseline: eq. 16)")
    if not (better and feasible):
        notes.append("no admissible law better than the first-harmonic law was found")

    def plot(outdir):
        return figures_synthesis.plot_rhomboid(
            outdir, L, pmin, a, b, r, objective, info["pa_limit"]
        )

    alpha = np.linspace(0.0, np.pi, 721)
    table = {"alpha_deg": np.degrees(alpha)}
    for tag, (aa, bb) in (("baseline", ((), ())), ("synthesized", (a, b))):
        psi, d1, d2, _ = rc.psi_law(pmin, aa, bb, alpha)
        table[f"psi_{tag}_deg"] = np.degrees(psi)
        table[f"blade_accel_{tag}_per_rad"] = 0.5 * d2
        table[f"rho_{tag}_mm"] = rc.profile_radius(L, pmin, aa, bb, alpha)[0] * 1e3
    return SynthesisResult(
        drive_type="rhomboid_cam",
        objective=objective,
        title=f"rhomboid cam: harmonics 3..{2 * n + 1} for {objective} (psi_min = "
        f"{fmt_deg(pmin)}), against the first-harmonic law (eq. 16)",
        rows=tuple(rows),
        parameters={"a": list(a), "b": list(b), "harmonics": n, "psi_min_deg": np.degrees(pmin)},
        metrics=metrics,
        updates=updates,
        notes=tuple(notes),
        plot=plot,
        tables={"law.csv": table},
    )
