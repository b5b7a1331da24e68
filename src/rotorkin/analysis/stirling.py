"""Stirling cycle of one circuit: Schmidt (ideal isothermal) and ideal adiabatic analyses.

A circuit is five cells in series (I. Urieli, D. M. Berchowitz, *Stirling Cycle
Engine Analysis*, Adam Hilger, Bristol, 1984; the same notation in Urieli's Ohio
University course notes *Stirling Cycle Machine Analysis*):

    compression space c (V_c(theta), cold) - cooler k (V_k, T_k)
    - regenerator r (V_r, linear temperature profile, T_r = (T_h - T_k) / ln(T_h / T_k))
    - heater h (V_h, T_h) - expansion space e (V_e(theta), hot)

holding a fixed mass ``M`` of an ideal gas (gas constant ``R``, ratio of heats
``gamma``) at one pressure ``p(theta)`` (no pressure drop). Only ``M R`` [J/K] enters
the pressure, the work and the heats; ``R`` alone converts to masses.

* **Schmidt analysis** (ideal isothermal; book, "ideal isothermal analysis"): the
  working spaces stay at ``T_k`` and ``T_h``,

      p = M R / (V_c/T_k + V_k/T_k + V_r/T_r + V_h/T_h + V_e/T_h),

  ``W_c = loop integral p dV_c``, ``W_e = loop integral p dV_e``; the heat enters the
  expansion space (``Q_in = W_e``) and leaves the compression space
  (``Q_out = -W_c``): the efficiency is Carnot's, ``1 - T_k/T_h``, for an ideal
  regenerator. :func:`schmidt_sinusoidal` is the closed form for sinusoidal
  volumes (book and notes, "Schmidt analysis": the phase angle ``alpha``, the
  parameters ``s``, ``b``, ``beta``).
* **Ideal adiabatic analysis** (book, "ideal adiabatic analysis"): the working
  spaces are adiabatic, the heat exchangers isothermal; gas crossing an interface
  carries the temperature of the cell it leaves (conditional temperatures
  ``T_ck``, ``T_he``). Seven ODEs in the cycle angle (``T_c``, ``T_e``, ``Q_k``,
  ``Q_r``, ``Q_h``, ``W_c``, ``W_e``) integrated by fixed-step RK4 over repeated
  cycles until the working-space temperatures are periodic
  (:func:`adiabatic_cycle`).
* **Regenerator effectiveness** ``eps < 1`` (Urieli's *simple* analysis): the
  regenerator passes only ``eps`` of its heat per cycle, ``Q_r,max - Q_r,min``; the
  rest, ``(1 - eps)(Q_r,max - Q_r,min)``, is added to the heater's load and to the
  cooler's (the work is unchanged).

Volumes are sampled on a uniform grid over one cycle, ends included, along the last
axis; leading axes are designs (any shape, broadcast). SI units throughout.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = [
    "GASES",
    "CycleResult",
    "adiabatic_cycle",
    "charge_gas",
    "gas_properties",
    "periodic_pressure",
    "regenerator_temperature",
    "schmidt_cycle",
    "schmidt_gas_for_mean_pressure",
    "schmidt_pressure",
    "schmidt_sinusoidal",
]

#: Gas constant R [J/(kg K)] and ratio of specific heats gamma of the working gases
#: (Urieli's ``gas.m`` values: air 287, 1.4; helium 2078.6, 5/3; hydrogen 4157.2, 1.4).
GASES = {
    "air": (287.0, 1.4),
    "helium": (2078.6, 5.0 / 3.0),
    "hydrogen": (4157.2, 1.4),
}
#: Default tolerance of the periodic steady state of the ideal adiabatic cycle [K].
PERIODIC_TOLERANCE = 1e-6


def gas_properties(name: str) -> tuple[float, float]:
    """``(R [J/(kg K)], gamma)`` of ``"air"``, ``"helium"`` or ``"hydrogen"``."""
    return GASES[name]


def regenerator_temperature(hot_temperature, cold_temperature):
    """Effective gas temperature of a regenerator with a linear profile [K].

    ``T_r = (T_h - T_k) / ln(T_h / T_k)``, the log mean that makes ``V_r / T_r`` the
    integral of ``dV / T(x)`` along the matrix; ``T_k`` where ``T_h = T_k``.
    """
    th = np.asarray(hot_temperature, dtype=float)
    tk = np.asarray(cold_temperature, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        tr = (th - tk) / np.log(th / tk)
    return np.where(np.isclose(th, tk, rtol=1e-12, atol=0.0), 0.5 * (th + tk), tr)


def charge_gas(pressure, total_volume, temperature):
    """``M R = p V / T`` [J/K]: the gas of a circuit filled to ``p`` at ``V``, all at ``T``.

    For a charge pressure at the largest total volume, cold: ``V`` the largest
    ``V_c + V_k + V_r + V_h + V_e`` and ``T = T_k``.
    """
    return np.asarray(pressure, dtype=float) * np.asarray(total_volume) / np.asarray(temperature)


def _dead(vk, vr, vh, tk, th):
    """``V_k/T_k + V_r/T_r + V_h/T_h`` [m^3/K] and ``T_r``, with a trailing axis."""
    tr = regenerator_temperature(th, tk)
    e = np.expand_dims
    return e(vk / tk + vr / tr + vh / th, -1), e(np.asarray(tr, dtype=float), -1)


def schmidt_pressure(gas, vc, ve, vk, vr, vh, tk, th):
    """Schmidt pressure ``p = M R / (V_c/T_k + V_k/T_k + V_r/T_r + V_h/T_h + V_e/T_h)`` [Pa].

    Parameters
    ----------
    gas : array_like, shape (...)
        ``M R`` [J/K].
    vc, ve : array_like, shape (..., n)
        Compression and expansion space volumes [m^3].
    vk, vr, vh, tk, th : array_like, shape (...)
        Cooler, regenerator, heater volumes [m^3]; cooler and heater temperatures [K].
    """
    vk, vr, vh, tk, th = (np.asarray(x, dtype=float) for x in (vk, vr, vh, tk, th))
    dead, _ = _dead(vk, vr, vh, tk, th)
    e = np.expand_dims
    return e(np.asarray(gas, dtype=float), -1) / (
        np.asarray(vc) / e(tk, -1) + dead + np.asarray(ve) / e(th, -1)
    )


def schmidt_gas_for_mean_pressure(p_mean, vc, ve, vk, vr, vh, tk, th):
    """``M R`` [J/K] that gives the cycle-mean Schmidt pressure ``p_mean``.

    Urieli's way of fixing the gas of a given engine (the mean pressure is what is
    known): ``p_mean = M R mean(1/S)`` with ``S`` the denominator of
    :func:`schmidt_pressure`, averaged over the uniform samples (last one dropped:
    it repeats the first).
    """
    one = schmidt_pressure(1.0, vc, ve, vk, vr, vh, tk, th)
    return np.asarray(p_mean, dtype=float) / np.mean(one[..., :-1], axis=-1)


def _trapezoid_cumulative(f, h):
    """Cumulative trapezoid of ``f`` along the last axis, step ``h``, starting at 0."""
    inc = 0.5 * (f[..., 1:] + f[..., :-1]) * np.expand_dims(h, -1)
    return np.concatenate([np.zeros(inc.shape[:-1] + (1,)), np.cumsum(inc, axis=-1)], axis=-1)


@dataclass(frozen=True)
class CycleResult:
    """One periodic cycle of a circuit (every array: designs first, angle samples last).

    Attributes
    ----------
    theta : ndarray, shape (n,)
        Cycle angles of the samples, ``0 .. period`` [rad].
    pressure, tc, te : ndarray, shape (..., n)
        Pressure [Pa]; compression and expansion space gas temperatures [K].
    qk, qr, qh, wc, we : ndarray, shape (..., n)
        Heat into the cooler, regenerator, heater gas and work of the compression and
        expansion spaces since ``theta = 0`` [J] (the ideal cycle, before the
        regenerator-effectiveness correction). Schmidt: the heat crosses the isothermal
        working spaces, so ``qk = wc`` and ``qh = we`` (the compression and expansion
        spaces' heat stands for the cooler's and the heater's).
    flow_ck, flow_kr, flow_rh, flow_he : ndarray, shape (..., n)
        Mass flows across the interfaces, ``+`` towards the expansion space [kg/rad].
    work, work_compression, work_expansion : ndarray, shape (...)
        ``W = W_c + W_e`` per cycle [J].
    heat_in, heat_out : ndarray, shape (...)
        Heat supplied to the gas by the heater and rejected by the cooler per cycle,
        both ``>= 0`` for an engine, with the effectiveness correction [J].
    regenerator_heat : ndarray, shape (...)
        ``Q_r,max - Q_r,min``: heat the regenerator takes and gives back per cycle [J].
    heat_cooler, heat_regenerator, heat_heater : ndarray, shape (...)
        Net ``Q_k`` (< 0 in an engine), ``Q_r`` (0 at steady state), ``Q_h`` per cycle,
        without the effectiveness correction [J].
    efficiency : ndarray, shape (...)
        ``W / heat_in``.
    residual : ndarray, shape (...)
        ``|T_c(end) - T_c(0)| + |T_e(end) - T_e(0)|`` [K] (0 for Schmidt).
    iterations : int
        Cycles integrated (1 for Schmidt).
    """

    theta: np.ndarray
    pressure: np.ndarray
    tc: np.ndarray
    te: np.ndarray
    qk: np.ndarray
    qr: np.ndarray
    qh: np.ndarray
    wc: np.ndarray
    we: np.ndarray
    flow_ck: np.ndarray
    flow_kr: np.ndarray
    flow_rh: np.ndarray
    flow_he: np.ndarray
    work: np.ndarray
    work_compression: np.ndarray
    work_expansion: np.ndarray
    heat_in: np.ndarray
    heat_out: np.ndarray
    regenerator_heat: np.ndarray
    heat_cooler: np.ndarray
    heat_regenerator: np.ndarray
    heat_heater: np.ndarray
    efficiency: np.ndarray
    residual: np.ndarray
    iterations: int


def _heat_flows(p, dp, gack, gahe, vk, vr, vh, tk, th, tck, the, gamma):
    """Flows ``m' R`` across k-r, r-h and the heat rates of k, r, h (Urieli's energy balance).

    ``dQ = V dp c_v/R - c_p (T_in m'_in - T_out m'_out)`` per heat exchanger, with
    masses in ``m R`` units so that ``c_v/R = 1/(gamma - 1)``, ``c_p/R = gamma/(gamma - 1)``.
    """
    gakr = gack - vk * dp / tk
    garh = gahe + vh * dp / th
    k1, k2 = 1.0 / (gamma - 1.0), gamma / (gamma - 1.0)
    dqk = vk * dp * k1 - k2 * (tck * gack - tk * gakr)
    dqr = vr * dp * k1 - k2 * (tk * gakr - th * garh)
    dqh = vh * dp * k1 - k2 * (th * garh - the * gahe)
    return gakr, garh, dqk, dqr, dqh


def _finish(theta, p, tc, te, q, w, flows, r_gas, eps, residual, iterations) -> CycleResult:
    qk, qr, qh = q
    wc, we = w
    amp = np.max(qr, axis=-1) - np.min(qr, axis=-1)
    loss = (1.0 - np.asarray(eps, dtype=float)) * amp
    heat_in = qh[..., -1] + loss
    heat_out = -(qk[..., -1] - loss)
    work = wc[..., -1] + we[..., -1]
    with np.errstate(divide="ignore", invalid="ignore"):
        efficiency = work / heat_in
    rg = np.expand_dims(np.asarray(r_gas, dtype=float), -1)
    return CycleResult(
        theta, p, tc, te, qk, qr, qh, wc, we, *(f / rg for f in flows), work,
        wc[..., -1], we[..., -1], heat_in, heat_out, amp, qk[..., -1], qr[..., -1],
        qh[..., -1], efficiency, residual, iterations,
    )  # fmt: skip


def schmidt_cycle(gas, vc, ve, dvc, dve, vk, vr, vh, tk, th, gamma=1.4, r_gas=287.0,
                  period=2.0 * np.pi, regenerator_effectiveness=1.0) -> CycleResult:  # fmt: skip
    """Schmidt (ideal isothermal) cycle of circuits with any sampled volume laws.

    ``p`` from :func:`schmidt_pressure`; ``W_c``, ``W_e`` the loop integrals of
    ``p dV/dtheta`` by the trapezoid rule on the periodic samples (spectrally accurate
    for smooth laws); ``Q_in = W_e``, ``Q_out = -W_c``. The regenerator's heat follows
    from its energy balance with the mass flows of the isothermal cells (mass
    conservation, ``dp/dtheta = -p^2 (dV_c/T_k + dV_e/T_h) / (M R)``), so that
    ``eps < 1`` adds ``(1 - eps)(Q_r,max - Q_r,min)`` to both heat flows.

    Parameters
    ----------
    gas : array_like, shape (...)
        ``M R`` [J/K].
    vc, ve, dvc, dve : array_like, shape (..., n)
        Volumes [m^3] and ``dV/dtheta`` [m^3/rad] on ``n`` uniform samples of one
        cycle, ends included.
    vk, vr, vh, tk, th, gamma, r_gas, regenerator_effectiveness : array_like, shape (...)
        Dead volumes [m^3], cooler and heater temperatures [K], ratio of heats, gas
        constant [J/(kg K)], effectiveness ``0 <= eps <= 1``.
    period : float
        Cycle angle [rad].
    """
    vk, vr, vh, tk, th, gamma = (np.asarray(x, dtype=float) for x in (vk, vr, vh, tk, th, gamma))
    vc, ve, dvc, dve = (np.asarray(x, dtype=float) for x in (vc, ve, dvc, dve))
    n = vc.shape[-1]
    theta = np.linspace(0.0, period, n)
    h = period / (n - 1)
    p = schmidt_pressure(gas, vc, ve, vk, vr, vh, tk, th)
    e = np.expand_dims
    tk_, th_, vk_, vr_, vh_, g_ = (e(x, -1) for x in (tk, th, vk, vr, vh, gamma))
    dp = -(p**2) * (dvc / tk_ + dve / th_) / e(np.asarray(gas, dtype=float), -1)
    gack = -(p * dvc + vc * dp) / tk_
    gahe = (p * dve + ve * dp) / th_
    gakr, garh, _, dqr, _ = _heat_flows(p, dp, gack, gahe, vk_, vr_, vh_, tk_, th_, tk_, th_, g_)
    wc = _trapezoid_cumulative(p * dvc, h)
    we = _trapezoid_cumulative(p * dve, h)
    qr = _trapezoid_cumulative(dqr, h)
    tc, te = np.broadcast_to(tk_, p.shape), np.broadcast_to(th_, p.shape)
    zero = np.zeros(p.shape[:-1])
    return _finish(theta, p, tc, te, (wc, qr, we), (wc, we), (gack, gakr, garh, gahe), r_gas,
                   regenerator_effectiveness, zero, 1)  # fmt: skip


def schmidt_sinusoidal(gas, v_swept_c, v_swept_e, v_clear_c, v_clear_e, vk, vr, vh, tk, th,
                       alpha) -> dict:  # fmt: skip
    """Closed-form Schmidt analysis of sinusoidal volumes (Urieli and Berchowitz, Schmidt analysis).

    ``V_c = V_clc + V_swc (1 + cos theta) / 2``,
    ``V_e = V_cle + V_swe (1 + cos(theta + alpha)) / 2`` (the expansion space leads by
    ``alpha``):

        s = (V_swc/2 + V_clc + V_k)/T_k + V_r/T_r + (V_swe/2 + V_cle + V_h)/T_h
        b = sqrt((V_swe/T_h)^2 + 2 (V_swe/T_h)(V_swc/T_k) cos alpha + (V_swc/T_k)^2) / (2 s)
        beta = atan2(V_swe sin alpha / T_h, V_swe cos alpha / T_h + V_swc / T_k)
        p = M R / (s (1 + b cos(theta + beta))),    p_mean = M R / (s sqrt(1 - b^2))
        W_c = pi V_swc p_mean sin(beta) (sqrt(1 - b^2) - 1) / b
        W_e = pi V_swe p_mean sin(beta - alpha) (sqrt(1 - b^2) - 1) / b

    Returns
    -------
    dict
        ``s``, ``b``, ``beta``, ``p_mean``, ``p_max``, ``p_min``, ``work_compression``,
        ``work_expansion``, ``work``, ``efficiency`` (``W / W_e``); arrays broadcast.
    """
    a = [np.asarray(x, dtype=float) for x in (gas, v_swept_c, v_swept_e, v_clear_c, v_clear_e,
                                              vk, vr, vh, tk, th, alpha)]  # fmt: skip
    mr, vswc, vswe, vclc, vcle, vk, vr, vh, tk, th, alpha = a
    tr = regenerator_temperature(th, tk)
    s = (0.5 * vswc + vclc + vk) / tk + vr / tr + (0.5 * vswe + vcle + vh) / th
    xe, xc = vswe / th, vswc / tk
    b = np.sqrt(xe**2 + 2.0 * xe * xc * np.cos(alpha) + xc**2) / (2.0 * s)
    beta = np.arctan2(xe * np.sin(alpha), xe * np.cos(alpha) + xc)
    root = np.sqrt(1.0 - b**2)
    p_mean = mr / (s * root)
    wc = np.pi * vswc * p_mean * np.sin(beta) * (root - 1.0) / b
    we = np.pi * vswe * p_mean * np.sin(beta - alpha) * (root - 1.0) / b
    return {
        "s": s, "b": b, "beta": beta, "p_mean": p_mean, "p_max": mr / (s * (1.0 - b)),
        "p_min": mr / (s * (1.0 + b)), "work_compression": wc, "work_expansion": we,
        "work": wc + we, "efficiency": (wc + we) / we,
    }  # fmt: skip


# --- ideal adiabatic -----------------------------------------------------------------------
#: The four choices of conditional temperatures (T_ck from c, T_he from h): c-side, e-side.
_FROM_C = np.array([True, True, False, False])
_FROM_H = np.array([False, True, False, True])


def _adiabatic_rates(tc, te, vc, ve, dvc, dve, k):
    """Derivatives of the ideal adiabatic model at one angle, every design at once.

    The conditional temperatures depend on the flow directions, which depend on
    ``dp`` through them: of the four combinations the one whose flows agree with its
    own choice is taken (the least disagreeing flow where none agrees fully).
    """
    gas, vk, vr, vh, tk, th, g, vot = k
    p = gas / (vc / tc + vot + ve / te)
    shape = (4,) + np.broadcast_shapes(np.shape(p), np.shape(tk))
    fc = _FROM_C.reshape((4,) + (1,) * (len(shape) - 1))
    fh = _FROM_H.reshape((4,) + (1,) * (len(shape) - 1))
    tck = np.where(fc, tc, tk)
    the = np.where(fh, th, te)
    dp = -g * p * (dvc / tck + dve / the) / (vc / tck + g * vot + ve / the)
    dmc = (p * dvc + vc * dp / g) / tck
    dme = (p * dve + ve * dp / g) / the
    bad = np.where((-dmc > 0.0) == fc, 0.0, np.abs(dmc)) + np.where((dme > 0.0) == fh, 0.0,
                                                                     np.abs(dme))  # fmt: skip
    pick = np.argmin(bad, axis=0)[None]
    tck, the, dp, dmc, dme = (np.take_along_axis(np.broadcast_to(x, shape), pick, 0)[0]
                              for x in (tck, the, dp, dmc, dme))  # fmt: skip
    dtc = tc * (dp / p + dvc / vc - dmc * tc / (p * vc))
    dte = te * (dp / p + dve / ve - dme * te / (p * ve))
    gakr, garh, dqk, dqr, dqh = _heat_flows(p, dp, -dmc, dme, vk, vr, vh, tk, th, tck, the, g)
    rates = (dtc, dte, dqk, dqr, dqh, p * dvc, p * dve)
    return rates, p, (-dmc, gakr, garh, dme)


def _adiabatic_run(x0, vc, ve, dvc, dve, k, h, record):
    """One cycle of RK4 from ``(T_c, T_e) = x0``; the samples hold the half steps."""
    tc, te = x0
    steps = (vc.shape[-1] - 1) // 2
    acc = [np.zeros(np.broadcast_shapes(np.shape(tc), vc.shape[:-1])) for _ in range(5)]
    out = []

    def at(i):
        return vc[..., i], ve[..., i], dvc[..., i], dve[..., i]

    for i in range(steps):
        k1, p0, fl = _adiabatic_rates(tc, te, *at(2 * i), k)
        if record:  # the designs themselves (not their bumped copies beside them)
            out.append(tuple(x[0] for x in (p0, tc, te, *acc, *fl)))
        k2, _, _ = _adiabatic_rates(tc + 0.5 * h * k1[0], te + 0.5 * h * k1[1], *at(2 * i + 1), k)
        k3, _, _ = _adiabatic_rates(tc + 0.5 * h * k2[0], te + 0.5 * h * k2[1], *at(2 * i + 1), k)
        k4, _, _ = _adiabatic_rates(tc + h * k3[0], te + h * k3[1], *at(2 * i + 2), k)
        inc = [
            h / 6.0 * (a + 2.0 * b + 2.0 * c + d) for a, b, c, d in zip(k1, k2, k3, k4, strict=True)
        ]
        tc, te = tc + inc[0], te + inc[1]
        acc = [a + d for a, d in zip(acc, inc[2:], strict=True)]
    if record:
        _, p0, fl = _adiabatic_rates(tc, te, *at(2 * steps), k)
        out.append(tuple(x[0] for x in (p0, tc, te, *acc, *fl)))
    return (tc, te), out


def adiabatic_cycle(gas, vc, ve, dvc, dve, vk, vr, vh, tk, th, gamma=1.4, r_gas=287.0,
                    period=2.0 * np.pi, regenerator_effectiveness=1.0,
                    tolerance=PERIODIC_TOLERANCE, max_iterations=40) -> CycleResult:  # fmt: skip
    """Ideal adiabatic cycle (Urieli and Berchowitz) at periodic steady state.

    Per angle: ``p = M R / (V_c/T_c + V_k/T_k + V_r/T_r + V_h/T_h + V_e/T_e)``, and::

        dp = -gamma p (dV_c/T_ck + dV_e/T_he) / (V_c/T_ck + gamma (V_k/T_k + V_r/T_r + V_h/T_h)
             + V_e/T_he)
        dm_c = (p dV_c + V_c dp/gamma) / (R T_ck),   dm_e = (p dV_e + V_e dp/gamma) / (R T_he)
        dT_c = T_c (dp/p + dV_c/V_c - dm_c/m_c),     dT_e = T_e (dp/p + dV_e/V_e - dm_e/m_e)
        m'_ck = -dm_c,  m'_kr = m'_ck - dm_k,  m'_he = dm_e,  m'_rh = m'_he + dm_h
        dQ_k = V_k dp c_v/R - c_p (T_ck m'_ck - T_k m'_kr)     (and Q_r, Q_h alike)
        dW_c = p dV_c,  dW_e = p dV_e

    with ``T_ck = T_c`` when gas leaves the compression space (``m'_ck > 0``), else
    ``T_k``; ``T_he = T_h`` when gas enters the expansion space (``m'_he > 0``), else
    ``T_e``. The seven rates are integrated by RK4 with the step of two samples (the
    odd samples are the half steps, so no volume is interpolated). The start
    temperatures are found by Newton's method on the cycle map ``(T_c, T_e)(0) ->
    (T_c, T_e)(period)``, its Jacobian by finite differences of 1e-3 K run as two
    extra designs beside the design itself, until ``|T_c(end) - T_c(0)| +
    |T_e(end) - T_e(0)| <= tolerance`` for every design; the last cycle is returned.
    The energy balance ``W = Q_k + Q_r + Q_h`` holds per cycle to the RK4 error
    (about 1e-6 relative with 720 steps).

    Parameters
    ----------
    gas : array_like, shape (...)
        ``M R`` [J/K].
    vc, ve, dvc, dve : array_like, shape (..., 2 N + 1)
        Volumes [m^3] and ``dV/dtheta`` [m^3/rad] on uniform samples over one cycle,
        ends included; ``N`` RK4 steps. Working-space volumes must stay > 0.
    vk, vr, vh, tk, th, gamma, r_gas, regenerator_effectiveness : array_like, shape (...)
        As in :func:`schmidt_cycle`.
    period : float
        Cycle angle [rad].
    tolerance : float
        Periodicity of the working-space temperatures [K].
    max_iterations : int
        Most Newton cycles; a RuntimeError beyond.
    """
    vc, ve, dvc, dve = (np.asarray(x, dtype=float) for x in (vc, ve, dvc, dve))
    if vc.shape[-1] % 2 == 0 or vc.shape[-1] < 3:
        raise ValueError("adiabatic_cycle needs 2 N + 1 samples (odd, >= 3)")
    steps = (vc.shape[-1] - 1) // 2
    h = period / steps
    vk, vr, vh, tk, th, g = (np.asarray(x, dtype=float) for x in (vk, vr, vh, tk, th, gamma))
    dead, _ = _dead(vk, vr, vh, tk, th)
    shape = np.broadcast_shapes(vc.shape[:-1], np.shape(gas), vk.shape, tk.shape, th.shape,
                                g.shape)  # fmt: skip
    size = math.prod(shape)
    # every design on one flat axis, beside {itself, +dT_c, +dT_e}: the Jacobian of the
    # cycle map in one run; a design leaves the run once periodic, so that its cycle is
    # the one it has alone (the others' iterations do not move it)
    k3 = tuple(np.broadcast_to(np.asarray(x, dtype=float), shape).reshape(1, size)
               for x in (gas, vk, vr, vh, tk, th, g, dead[..., 0]))  # fmt: skip
    v3 = tuple(np.broadcast_to(x, shape + x.shape[-1:]).reshape(1, size, -1)
               for x in (vc, ve, dvc, dve))  # fmt: skip
    delta = 1e-3
    x = np.stack([k3[4][0], k3[5][0]])  # (2, size): start at T_k, T_h
    bump = np.zeros((2, 3, 1))
    bump[0, 1], bump[1, 2] = delta, delta
    cols = np.empty((12, size, steps + 1))
    residual = np.empty(size)
    active = np.arange(size)
    cycles = 0
    for _ in range(max_iterations):
        cycles += 1
        start = x[:, None] + bump
        end, rec = _adiabatic_run((start[0], start[1]), *(v[:, active] for v in v3),
                                  tuple(k[:, active] for k in k3), h, True)  # fmt: skip
        f = np.stack(end) - start  # (2, 3, active)
        res = np.abs(f[0, 0]) + np.abs(f[1, 0])
        done = res <= tolerance
        if done.any():
            rows = active[done]
            residual[rows] = res[done]
            for j in range(12):
                cols[j][rows] = np.stack([r[j][done] for r in rec], axis=-1)
            keep = ~done
            active, x, f, start, end = (active[keep], x[:, keep], f[..., keep],
                                        start[..., keep], [e[:, keep] for e in end])  # fmt: skip
        if active.size == 0:
            break
        jac = (f[:, 1:] - f[:, :1]) / delta  # (2 eqs, 2 vars, active)
        det = jac[0, 0] * jac[1, 1] - jac[0, 1] * jac[1, 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            dx0 = -(jac[1, 1] * f[0, 0] - jac[0, 1] * f[1, 0]) / det
            dx1 = -(-jac[1, 0] * f[0, 0] + jac[0, 0] * f[1, 0]) / det
        newton = np.stack([x[0] + dx0, x[1] + dx1])
        plain = np.stack([end[0][0], end[1][0]])
        ok = np.isfinite(newton) & (newton > 0.0)
        x = np.where(ok & np.isfinite(det), newton, plain)
    else:
        raise RuntimeError(
            f"ideal adiabatic cycle not periodic to {tolerance:g} K after "
            f"{max_iterations} cycles (residual {np.max(res):.3g} K)"
        )
    cols = cols.reshape((12, *shape, steps + 1))
    residual = residual.reshape(shape)
    p, tc, te, qk, qr, qh, wc, we, *flows = cols
    theta = np.linspace(0.0, period, steps + 1)
    return _finish(theta, p, tc, te, (qk, qr, qh), (wc, we), flows, r_gas,
                   regenerator_effectiveness, residual, cycles)  # fmt: skip


def periodic_pressure(result: CycleResult, theta, period: float):
    """The cycle's pressure at any angles ``theta`` [Pa]: a periodic cubic spline.

    Returns
    -------
    ndarray, shape ``(..., *theta.shape)``
        Designs first.
    """
    from scipy.interpolate import CubicSpline

    p = np.array(result.pressure, dtype=float)
    p[..., -1] = p[..., 0]  # periodic to the tolerance of the cycle: closed exactly
    spline = CubicSpline(result.theta, p, axis=-1, bc_type="periodic")
    return spline(np.mod(np.asarray(theta, dtype=float), period))
