"""Sweep kernel of the differential vane pump on the guide-bar + gear drive, by broadcasting.

The summary keys of :mod:`rotorkin.drives.guide_bar.study` for arrays of designs:
vane angle gamma_0 (both drivers), relative-angle swing, speed-ratio range,
equal-speed points, the pump's chamber angles, volumes and displacement
(closed forms), and, sampled on ``samples`` input angles per design (a design x
angle array in blocks), the input torque ``M7 q_1' + M8 q_2'`` (eq. 7, 8) and
the peaks of the impellers' acceleration and jerk coefficients. The crank-
and guide-driven derivatives are those of
:func:`~rotorkin.drives.guide_bar.kinematics.guide_angle` and
:func:`~rotorkin.drives.guide_bar.kinematics.crank_angle`, written without the angle
itself (no arctangent per sample).
"""

from __future__ import annotations

import numpy as np

from rotorkin.core.batch import Designs, flag, full, run_blocks, sample_grid
from rotorkin.drives.guide_bar import kinematics as gb

__all__ = ["DRIVE", "KEYS", "CURVES", "ANGLE", "unsupported", "metric_names", "reasons",
           "metrics", "curves", "period"]  # fmt: skip

DRIVE = "guide_bar"

KEYS = frozenset(
    {
        "drive.lambda",
        "drive.gear_ratio",
        "drive.input_gear_ratio",
        "drive.phase",
        "drive.driver",
        "machine.vanes_per_impeller",
        "machine.vane_angle",
        "machine.hub_radius",
        "machine.casing_radius",
        "machine.axial_width",
        "loads.impeller_torque_1",
        "loads.impeller_torque_2",
        "loads.suction_pressure",
        "loads.discharge_pressure",
    }
)

_METRICS = (
    "lambda",
    "gear_ratio",
    "input_gear_ratio",
    "phase_deg",
    "vane_angle_deg",
    "vane_angle_crank_driven_deg",
    "vane_angle_guide_driven_deg",
    "vane_angle_other_driver_deg",
    "relative_angle_swing_deg",
    "impeller_speed_ratio_min",
    "impeller_speed_ratio_max",
    "impeller_speed_ratio_mean",
    "equal_speed_driving_angle_1_deg",
    "equal_speed_driving_angle_2_deg",
    "equal_speed_input_angle_1_deg",
    "equal_speed_input_angle_2_deg",
    "equal_speed_ratio_1",
    "equal_speed_ratio_2",
    "input_torque_min_Nm",
    "input_torque_max_Nm",
    "input_torque_mean_Nm",
    "input_torque_fluctuation_Nm",
    "input_torque_fluctuation_ratio",
    "impeller_speed_ratio_input_min",
    "impeller_speed_ratio_input_max",
    "impeller_accel_peak_per_rad",
    "impeller_jerk_peak_per_rad2",
    "vanes_per_impeller",
    "chambers",
    "pump_vane_angle_deg",
    "pump_vane_angle_max_deg",
    "chamber_angle_min_deg",
    "chamber_angle_max_deg",
    "chamber_volume_min_cm3",
    "chamber_volume_max_cm3",
    "displacement_cm3_per_rev",
    "displacement_per_period_cm3",
    "displacement_per_impeller_rev_cm3",
    "pressure_rise_bar",
    "indicated_work_J",
    "indicated_work_per_period_J",
    "mean_torque_Nm",
)
_FLOW = ("flow_mean_l_per_min", "hydraulic_power_W")

CURVES = (
    "impeller1_angle_deg",
    "impeller2_angle_deg",
    "relative_angle_deg",
    "impeller1_speed_ratio",
    "impeller2_speed_ratio",
    "impeller1_accel_per_rad",
    "impeller2_accel_per_rad",
    "impeller1_jerk_per_rad2",
    "impeller2_jerk_per_rad2",
    "input_torque_Nm",
)
ANGLE = ("theta_deg", "Input gear 1 angle theta; the driving members turn at theta / i12.")


def unsupported(cfg: dict) -> str | None:
    """Why the kernel cannot evaluate designs on this base config (None: it can)."""
    return None


def metric_names(cfg: dict) -> tuple[str, ...]:
    """Summary keys the kernel computes (the mean flow only at a constant shaft speed)."""
    speed = cfg.get("run", {}).get("speed")
    return _METRICS + (_FLOW if not isinstance(speed, list) else ())


def period(p):
    """Period of the speeds: ``2 pi i12`` [rad] (an array when i12 varies)."""
    return 2.0 * np.pi * p.float("drive.input_gear_ratio")


def _vane_angles(lam, u, phase):
    """gamma_0 crank- and guide-driven (:func:`~.kinematics.vane_angle`)."""
    a = 0.5 * np.mod(np.asarray(phase, dtype=float), 2.0 * np.pi)
    g1, g2 = gb.guide_angle(lam, a)[0], gb.guide_angle(lam, np.pi - a)[0]
    h1, h2 = gb.crank_angle(lam, a)[0], gb.crank_angle(lam, np.pi - a)[0]
    return (g1 + g2) / u, (2.0 * np.pi - h1 - h2) / u


def _drive(p):
    lam, u = p.float("drive.lambda"), p.float("drive.gear_ratio")
    phase = p.float("drive.phase")
    crank = np.asarray(p["drive.driver"]) == "crank"
    g_crank, g_guide = _vane_angles(lam, u, phase)
    g0 = np.where(crank, g_crank, g_guide)
    swing = 2.0 * np.pi / u - 2.0 * g0
    return lam, u, phase, crank, g_crank, g_guide, g0, swing


def reasons(p, code: dict) -> np.ndarray:
    """Reason code per design (0: admissible), in the order of the study's checks."""
    r = np.zeros(p.n, dtype=np.int16)
    with np.errstate(all="ignore"):
        lam = p.float("drive.lambda")
        flag(r, ~(np.isfinite(lam) & (lam > 0.0) & (lam < 1.0)), code["drive.lambda"])
        u = p.float("drive.gear_ratio")
        flag(r, ~(np.isfinite(u) & (u > 0.0)), code["drive.gear_ratio"])
        i12 = p.float("drive.input_gear_ratio")
        flag(r, ~(np.isfinite(i12) & (i12 > 0.0)), code["drive.input_gear_ratio"])
        ph = p.float("drive.phase")
        turns = ph / (2.0 * np.pi)
        flag(r, ~np.isfinite(ph) | (np.abs(turns - np.round(turns)) < 1e-9), code["drive.phase"])
        rh, rc = p.float("machine.hub_radius"), p.float("machine.casing_radius")
        flag(r, ~(np.isfinite(rh) & (rh > 0.0)), code["machine.hub_radius"])
        flag(r, ~(np.isfinite(rc) & (rc > rh)), code["machine.casing_radius"])
        w = p.float("machine.axial_width")
        flag(r, ~(np.isfinite(w) & (w > 0.0)), code["machine.axial_width"])
        z = np.asarray(p["machine.vanes_per_impeller"])
        flag(r, ~(z >= 1), code["machine.vanes_per_impeller"])
        ok = r == 0
        safe = p.take(ok) if not np.all(ok) else p
        bad = np.zeros(p.n, dtype=np.int16)
        if safe.n:
            bad[ok] = _pump_reasons(safe, code)
        r[ok] = bad[ok]
        for key in ("suction_pressure", "discharge_pressure"):
            v = p.float(f"loads.{key}")
            flag(r, ~(np.isfinite(v) & (v > 0.0)), code[f"loads.{key}"])
    return r


def _pump_reasons(p, code) -> np.ndarray:
    """The vane checks of :class:`rotorkin.machines.vane_pump.VanePump` (admissible drives)."""
    r = np.zeros(p.n, dtype=np.int16)
    _, _, _, _, _, _, g0, swing = _drive(p)
    z = np.asarray(p["machine.vanes_per_impeller"]).astype(float)
    z_fit = np.floor(2.0 * np.pi / swing * (1.0 + 1e-12))
    flag(r, z > z_fit, code["machine.vanes_per_impeller"])
    gmax = np.pi / z - 0.5 * swing
    vane = p["machine.vane_angle"]
    if vane is None:
        flag(r, g0 > gmax + 1e-12, code["machine.vanes_per_impeller"])
        g = g0
    else:
        g = np.asarray(vane, dtype=float)
    flag(r, ~(np.isfinite(g) & (g > 0.0) & (g <= gmax + 1e-12)), code["machine.vane_angle"])
    return r


def metrics(p, names, samples: int, threads: int | None = None) -> dict:
    """Summary metrics of admissible designs ``p``, arrays (n,)."""
    names = set(names)
    n = p.n
    deg = np.degrees
    lam, u, phase, crank, g_crank, g_guide, g0, swing = _drive(p)
    i12 = p.float("drive.input_gear_ratio")
    t = np.mod(np.stack(np.broadcast_arrays(*gb.equal_speed_angles(phase))), 2.0 * np.pi)
    t_a, t_b = np.minimum(t[0], t[1]), np.maximum(t[0], t[1])
    ratio = {k: np.where(crank, _crank_rates(lam, tt)[0], _guide_rates(lam, tt)[0]) / u
             for k, tt in (("a", t_a), ("b", t_b))}  # fmt: skip
    rmin = np.where(crank, 1.0 / ((1.0 + lam) * u), (1.0 - lam) / u)
    rmax = np.where(crank, 1.0 / ((1.0 - lam) * u), (1.0 + lam) / u)
    m7, m8 = p.float("loads.impeller_torque_1"), p.float("loads.impeller_torque_2")
    mean = (m7 + m8) / (u * i12)
    # the pump
    z = np.asarray(p["machine.vanes_per_impeller"]).astype(float)
    vane = p["machine.vane_angle"]
    gamma = g0 if vane is None else np.asarray(vane, dtype=float)
    rh, rc = p.float("machine.hub_radius"), p.float("machine.casing_radius")
    k = 0.5 * (rc * rc - rh * rh) * p.float("machine.axial_width")
    lo = np.pi / z - 0.5 * swing - gamma
    lo = np.where(np.abs(lo) < 1e-12, 0.0, lo)
    per_period = 2.0 * z * k * swing
    dp = p.float("loads.discharge_pressure") - p.float("loads.suction_pressure")
    work_period = -dp * per_period
    val = {
        "lambda": lam,
        "gear_ratio": u,
        "input_gear_ratio": i12,
        "phase_deg": deg(phase),
        "vane_angle_deg": deg(g0),
        "vane_angle_crank_driven_deg": deg(g_crank),
        "vane_angle_guide_driven_deg": deg(g_guide),
        "vane_angle_other_driver_deg": deg(np.where(crank, g_guide, g_crank)),
        "relative_angle_swing_deg": deg(swing),
        "impeller_speed_ratio_min": rmin,
        "impeller_speed_ratio_max": rmax,
        "impeller_speed_ratio_mean": 1.0 / u,
        "equal_speed_driving_angle_1_deg": deg(t_a),
        "equal_speed_driving_angle_2_deg": deg(t_b),
        "equal_speed_input_angle_1_deg": deg(t_a * i12),
        "equal_speed_input_angle_2_deg": deg(t_b * i12),
        "equal_speed_ratio_1": ratio["a"],
        "equal_speed_ratio_2": ratio["b"],
        "input_torque_mean_Nm": mean,
        "impeller_speed_ratio_input_min": rmin / i12,
        "impeller_speed_ratio_input_max": rmax / i12,
        "vanes_per_impeller": z,
        "chambers": 2.0 * z,
        "pump_vane_angle_deg": deg(gamma),
        "pump_vane_angle_max_deg": deg(np.pi / z - 0.5 * swing),
        "chamber_angle_min_deg": deg(lo),
        "chamber_angle_max_deg": deg(lo + swing),
        "chamber_volume_min_cm3": k * lo * 1e6,
        "chamber_volume_max_cm3": k * (lo + swing) * 1e6,
        "displacement_cm3_per_rev": per_period / i12 * 1e6,
        "displacement_per_period_cm3": per_period * 1e6,
        "displacement_per_impeller_rev_cm3": per_period * u * 1e6,
        "pressure_rise_bar": dp / 1e5,
        "indicated_work_J": work_period / i12,
        "indicated_work_per_period_J": work_period,
        "mean_torque_Nm": work_period / (2.0 * np.pi * i12),
    }
    speed = p.cfg.get("run", {}).get("speed")
    if not isinstance(speed, list):
        flow = per_period / (2.0 * np.pi * i12 / float(speed))  # volume per period / its time
        val["flow_mean_l_per_min"] = flow * 60.0e3
        val["hydraulic_power_W"] = dp * flow
    sampled = {"input_torque_min_Nm", "input_torque_max_Nm", "input_torque_fluctuation_Nm",
               "input_torque_fluctuation_ratio", "impeller_accel_peak_per_rad",
               "impeller_jerk_peak_per_rad2"}  # fmt: skip
    if names & sampled:
        s = _sampled(p, samples, threads)
        val.update(s)
        fl = s["input_torque_max_Nm"] - s["input_torque_min_Nm"]
        val["input_torque_fluctuation_Nm"] = fl
        with np.errstate(divide="ignore", invalid="ignore"):
            val["input_torque_fluctuation_ratio"] = np.where(mean != 0.0, fl / np.abs(mean),
                                                             np.nan)  # fmt: skip
    return {name: full(val[name], n) for name in names}


def _crank_rates(lam, x):
    """``g', g'', g'''`` of a crank-driven mechanism (as :func:`guide_bar.guide_angle`)."""
    c, s = np.cos(x), np.sin(x)
    D = 1.0 + 2.0 * lam * c + lam * lam
    K = lam * (1.0 - lam * lam)
    return (1.0 + lam * c) / D, K * s / D**2, K * (D * c + 4.0 * lam * s * s) / D**3


def _guide_rates(lam, y):
    """``h', h'', h'''`` of a guide-driven mechanism (as :func:`guide_bar.crank_angle`)."""
    c, s = np.cos(y), np.sin(y)
    W = np.sqrt(1.0 - (lam * s) ** 2)
    K = lam * (1.0 - lam * lam)
    return 1.0 + lam * c / W, -K * s / W**3, -K * c * (1.0 + 2.0 * (lam * s) ** 2) / W**5


def _sampled(p, samples, threads) -> dict:
    n = p.n
    cols = {k: full(p.float(k), n) for k in ("drive.lambda", "drive.gear_ratio",
            "drive.input_gear_ratio", "drive.phase", "loads.impeller_torque_1",
            "loads.impeller_torque_2")}  # fmt: skip
    crank = full(np.asarray(p["drive.driver"]) == "crank", n, dtype=bool)
    shared_grid = not p.varies("drive.input_gear_ratio")
    grid = (
        sample_grid(2.0 * np.pi * p.float("drive.input_gear_ratio"), samples)
        if shared_grid
        else None
    )

    def fn(lo, hi):
        lam, u, i12, ph, m7, m8 = (cols[k][lo:hi, None] for k in cols)
        theta = grid if shared_grid else sample_grid(2.0 * np.pi * i12, samples)
        x1 = theta / i12
        rates = []
        for x in (x1, x1 + ph):
            cr, gu = _crank_rates(lam, x), _guide_rates(lam, x)
            rates.append([np.where(crank[lo:hi, None], a, b) for a, b in zip(cr, gu, strict=True)])
        d1 = [r[0] / (u * i12) for r in rates]
        torque = m7 * d1[0] + m8 * d1[1]
        acc = [np.abs(r[1] / (u * i12**2)).max(axis=1) for r in rates]
        jerk = [np.abs(r[2] / (u * i12**3)).max(axis=1) for r in rates]
        return {
            "input_torque_min_Nm": torque.min(axis=1),
            "input_torque_max_Nm": torque.max(axis=1),
            "impeller_accel_peak_per_rad": np.maximum(*acc),
            "impeller_jerk_peak_per_rad2": np.maximum(*jerk),
        }

    return run_blocks(fn, n, samples, threads)


def curves(p, points: int):
    """The :data:`CURVES` of admissible designs over one period: angle, dict (n, points).

    The angle is (points,) or, when ``drive.input_gear_ratio`` varies, (n, points).
    """
    n = p.n
    i12 = full(p.float("drive.input_gear_ratio"), n)[:, None]
    lam, u, ph = (full(p.float(k), n)[:, None] for k in ("drive.lambda", "drive.gear_ratio",
                                                         "drive.phase"))  # fmt: skip
    crank = full(np.asarray(p["drive.driver"]) == "crank", n, dtype=bool)[:, None]
    if p.varies("drive.input_gear_ratio"):
        theta = sample_grid(2.0 * np.pi * i12, points)
    else:
        theta = sample_grid(2.0 * np.pi * float(i12[0, 0]) if n else 2.0 * np.pi, points)
    x = np.stack([theta / i12, theta / i12 + ph])
    f = [np.where(crank, a, b) for a, b in zip(gb.guide_angle(lam, x), gb.crank_angle(lam, x),
                                               strict=True)]  # fmt: skip
    d = [fn / (u * i12**k) for k, fn in enumerate(f)]
    m7 = p.float("loads.impeller_torque_1")
    m8 = p.float("loads.impeller_torque_2")
    m7, m8 = (full(m, n)[:, None] for m in (m7, m8))
    out = {
        "impeller1_angle_deg": np.degrees(d[0][0]),
        "impeller2_angle_deg": np.degrees(d[0][1]),
        "relative_angle_deg": np.degrees(d[0][1] - d[0][0]),
        "input_torque_Nm": m7 * d[1][0] + m8 * d[1][1],
    }
    for k, name in ((1, "speed_ratio"), (2, "accel_per_rad"), (3, "jerk_per_rad2")):
        out[f"impeller1_{name}"] = d[k][0]
        out[f"impeller2_{name}"] = d[k][1]
    return theta, out


def tolerance_hold(cfg: dict) -> tuple[dict, dict]:
    """Hold the vane angle at its nominal value (the drive's gamma_0) in a tolerance analysis."""
    if cfg["machine"].get("vane_angle") is None:
        g0 = metrics(Designs(cfg, {}, 1), ["vane_angle_deg"], 3)["vane_angle_deg"][0]
        cfg["machine"]["vane_angle"] = float(np.radians(g0))
    return cfg, {}
