"""The kinematics of each drive as a benchmark case: the library and its yardsticks.

A :class:`Case` knows, for one drive and design, how to build at ``size`` angles

* ``lib``: the library's kinematics, 1 thread, writing into preallocated arrays (as
  the floor does), kernel as installed (``auto``: compiled loops when numba is);
* ``lib_numpy``: the same with ``kernel="numpy"`` (the fallback);
* ``lib_2t``: ``lib`` on 2 threads;
* ``lib_alloc``: the public call, which allocates its results;
* ``floor``: **floor (b')** -- exactly the transcendental calls the drive's closed form
  makes (numpy, on arrays of the same size, arguments precomputed and realistic)
  plus writing the outputs: the calls write into rows of the output array, the
  other rows are filled (``ndarray.fill``), so the floor stores exactly the bytes
  the library stores and computes nothing else;
* ``floor_2t``: the floor on 2 threads (each half of the points);
* ``floor_alloc``: the floor allocating its output array on each call, as ``lib_alloc``;
* ``scalar``: the per-point baseline (:mod:`scalar_ports`), on at most ``cap`` points;

and checks that the library, its numpy fallback and the scalar port agree.
"""

from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
import scalar_ports

from rotorkin.core.errors import ParameterError
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.drives.eccentric_cam.kinematics_fused import travels_fused
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar.kinematics_fused import atan_argument as gb_atan_argument
from rotorkin.drives.guide_bar.kinematics_fused import half_angle_trig as gb_trig
from rotorkin.drives.guide_bar.kinematics_fused import impellers_fused
from rotorkin.drives.noncircular_gears import kinematics as ng
from rotorkin.drives.noncircular_gears.kinematics_fused import atan_argument as ng_atan_argument
from rotorkin.drives.noncircular_gears.kinematics_fused import half_angle_trig as ng_trig
from rotorkin.drives.noncircular_gears.kinematics_fused import motion_fused
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.drives.rhomboid_cam.kinematics_fused import law_fused
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.drives.wobble_cam.fast import rotor_kinematics
from rotorkin.drives.wobble_cam.kinematics_fused import spin_trig

_POOL = ThreadPoolExecutor(2, thread_name_prefix="bench")


def _halves(fn, size):
    """``fn(lo, hi)`` on 2 threads, one half of the points each."""
    mid = size // 2

    def run():
        for f in [_POOL.submit(fn, 0, mid), _POOL.submit(fn, mid, size)]:
            f.result()

    return run


def floor_methods(calls, outputs, size):
    """``floor``, ``floor_2t``, ``floor_alloc`` from the transcendental ``calls``.

    ``calls``: list of ``(ufunc, argument array of length size)``; call ``r`` writes
    output row ``r``, the remaining rows up to ``outputs`` are filled.
    """
    out = np.zeros((outputs, size))

    def part(o, lo, hi):
        for r, (f, x) in enumerate(calls):
            f(x[lo:hi], out=o[r, lo:hi])
        for r in range(len(calls), outputs):
            o[r, lo:hi].fill(1.0)

    def alloc():
        part(np.empty((outputs, size)), 0, size)

    return {
        "floor": lambda: part(out, 0, size),
        "floor_2t": _halves(lambda lo, hi: part(out, lo, hi), size),
        "floor_alloc": alloc,
    }


@dataclass(frozen=True)
class Case:
    """One drive's kinematics as a benchmark (see the module)."""

    name: str
    title: str
    design: dict
    outputs: int
    #: the transcendental calls of the closed form per point (floor b')
    transcendentals: str
    build: object  # build(size, seed) -> (theta, methods without scalar)
    scalar: object  # scalar(theta) -> rows
    library: object  # library(theta, kernel) -> rows (allocating, for the checks)

    def methods(self, size: int, cap: int, seed: int = 0):
        """Every method at ``size`` points; ``scalar`` runs on at most ``cap`` of them."""
        theta, fns = self.build(size, seed)
        sub = theta[: min(size, cap)]
        fns["scalar"] = lambda: self.scalar(sub)
        return fns, len(sub)

    def agreement(self, points: int = 2000) -> dict:
        """Largest differences (relative to each row's largest magnitude) on ``points`` angles."""
        theta = np.random.default_rng(1).uniform(-2 * np.pi, 2 * np.pi, points)
        lib = self.library(theta, "auto")
        scale = np.maximum(1e-300, np.max(np.abs(lib), axis=1))[:, None]
        out = {
            "numpy_vs_library": float(np.max(np.abs(self.library(theta, "numpy") - lib) / scale)),
            "scalar_vs_library": float(np.max(np.abs(self.scalar(theta) - lib) / scale)),
        }
        try:
            fused = self.library(theta, "numba")
        except ParameterError:  # numba not installed
            return out
        out["numba_vs_numpy"] = float(np.max(np.abs(fused - self.library(theta, "numpy")) / scale))
        return out


def _theta(size, seed):
    return np.random.default_rng(1000 + seed + size).uniform(0.0, 2.0 * np.pi, size)


# --------------------------------------------------------------------------------------------
# wobble cam: paper Table 1
# --------------------------------------------------------------------------------------------
_W = {"tilt": math.radians(45.0), "alpha": math.radians(90.0), "n": -2.0, "eps": 10.0, "N": 4}
_W_PARAMS = wc.WobbleCam(_W["tilt"], _W["alpha"], _W["n"], 0.05, _W["N"])
_W_WIDTH = float(wc.piston_layout(_W_PARAMS, _W["eps"]).piston_width)


def _wobble_build(size, seed):
    theta = _theta(size, seed)
    v = _W["n"] * theta
    c = math.cos(_W["tilt"])
    g = (1.0 + c) / (1.0 - c)
    ca, sa = math.cos(_W["alpha"]), math.sin(_W["alpha"])
    s1, c1, s2, c2 = spin_trig(np.tan(v), ca, sa, 2 * ca, 2 * sa)
    calls = [(np.tan, v), (np.arctan, s1 / (g - c1)), (np.arctan, s2 / (g - c2))]
    rot, cham = np.zeros((4, 2, size)), np.zeros((2, size))
    args = (_W["tilt"], _W["alpha"], _W["n"], theta)
    kw = {"chamber": (_W_WIDTH, _W["N"]), "out": (rot, cham)}
    return theta, {
        "lib": lambda: rotor_kinematics(*args, threads=1, **kw),
        "lib_numpy": lambda: rotor_kinematics(*args, threads=1, kernel="numpy", **kw),
        "lib_2t": lambda: rotor_kinematics(*args, threads=2, **kw),
        "lib_alloc": lambda: wc.kinematics(_W_PARAMS, theta, _W_WIDTH, threads=1),
        **floor_methods(calls, 10, size),
    }


def _wobble_library(theta, kernel):
    rot, cham = rotor_kinematics(
        _W["tilt"], _W["alpha"], _W["n"], theta, chamber=(_W_WIDTH, _W["N"]), kernel=kernel
    )
    return np.concatenate([rot.reshape(8, -1), cham])


def _wobble_scalar(theta):
    return scalar_ports.wobble(theta, _W["tilt"], _W["alpha"], _W["n"], _W_WIDTH, _W["N"])


# --------------------------------------------------------------------------------------------
# eccentric cam: the example (R = 80 mm, e = 40 mm, knife edge)
# --------------------------------------------------------------------------------------------
_E = {"rc": 0.080, "e": 0.040}


def _eccentric_build(size, seed):
    beta = _theta(size, seed)
    calls = [(np.tan, 0.5 * beta), (np.sqrt, _E["rc"] ** 2 - (_E["e"] * np.sin(beta)) ** 2)]
    out = np.zeros((4, 2, size))
    args = (_E["rc"], _E["e"], beta)
    return beta, {
        "lib": lambda: travels_fused(*args, threads=1, out=out),
        "lib_numpy": lambda: travels_fused(*args, threads=1, kernel="numpy", out=out),
        "lib_2t": lambda: travels_fused(*args, threads=2, out=out),
        "lib_alloc": lambda: ec.travels(*args),
        **floor_methods(calls, 8, size),
    }


def _eccentric_library(beta, kernel):
    return travels_fused(_E["rc"], _E["e"], beta, kernel=kernel).reshape(8, -1)


def _eccentric_scalar(beta):
    return scalar_ports.eccentric(beta, _E["rc"], _E["e"])


# --------------------------------------------------------------------------------------------
# guide bar: the paper's crank-driven drive (lambda 0.5, u 2, i12 2, Sigma 180 deg)
# --------------------------------------------------------------------------------------------
_G = {"lam": 0.5, "u": 2.0, "i12": 2.0, "phase": math.pi}
_G_PARAMS = gb.GuideBar(_G["lam"], _G["u"], _G["i12"], _G["phase"], "crank")


def _guide_build(size, seed):
    theta = _theta(size, seed)
    x1 = theta / _G["i12"]
    x2 = x1 + _G["phase"]
    t1, t2 = np.tan(0.5 * x1), np.tan(0.5 * x2)
    r1 = gb_atan_argument(*gb_trig(t1), _G["lam"], False)
    r2 = gb_atan_argument(*gb_trig(t2), _G["lam"], False)
    calls = [(np.tan, 0.5 * x1), (np.tan, 0.5 * x2), (np.arctan, r1), (np.arctan, r2)]
    out = np.zeros((4, 2, size))
    args = (_G["lam"], _G["u"], _G["i12"], _G["phase"], False, theta)
    return theta, {
        "lib": lambda: impellers_fused(*args, threads=1, out=out),
        "lib_numpy": lambda: impellers_fused(*args, threads=1, kernel="numpy", out=out),
        "lib_2t": lambda: impellers_fused(*args, threads=2, out=out),
        "lib_alloc": lambda: gb.impeller_angles(_G_PARAMS, theta),
        **floor_methods(calls, 8, size),
    }


def _guide_library(theta, kernel):
    args = (_G["lam"], _G["u"], _G["i12"], _G["phase"], False, theta)
    return impellers_fused(*args, kernel=kernel).reshape(8, -1)


def _guide_scalar(theta):
    return scalar_ports.guide_bar(theta, _G["lam"], _G["u"], _G["i12"], _G["phase"])


# --------------------------------------------------------------------------------------------
# non-circular gears: the example (2 lobes, 2 rotor lobes, e 0.2, phase 90 deg)
# --------------------------------------------------------------------------------------------
_N_PARAMS = ng.NoncircularGears(2, 2, 0.2, 0.12, math.radians(90.0))


def _noncircular_design():
    n, m, e, _, pa, beta, root = (float(v) for v in ng._design(_N_PARAMS))
    sigma = float(ng._phase(_N_PARAMS))
    offset = float(ng.driven_angle(_N_PARAMS, sigma)[0])
    return n, m, e, pa, beta, root, sigma, offset


def _noncircular_build(size, seed):
    theta = _theta(size, seed)
    n, m, e, pa, beta, root, sigma, offset = _noncircular_design()
    h1, h2 = 0.5 * (n * theta), 0.5 * (n * (theta + sigma))
    r1 = ng_atan_argument(*ng_trig(np.tan(h1)), e, beta, root)
    r2 = ng_atan_argument(*ng_trig(np.tan(h2)), e, beta, root)
    calls = [(np.tan, h1), (np.tan, h2), (np.arctan, r1), (np.arctan, r2)]
    out = np.zeros((4, 2, size))
    args = (n, m, e, pa, beta, root, sigma, offset, theta)
    return theta, {
        "lib": lambda: motion_fused(*args, threads=1, out=out),
        "lib_numpy": lambda: motion_fused(*args, threads=1, kernel="numpy", out=out),
        "lib_2t": lambda: motion_fused(*args, threads=2, out=out),
        "lib_alloc": lambda: ng.motion(_N_PARAMS, theta),
        **floor_methods(calls, 8, size),
    }


def _noncircular_library(theta, kernel):
    return motion_fused(*_noncircular_design(), theta, kernel=kernel).reshape(8, -1)


def _noncircular_scalar(theta):
    return scalar_ports.noncircular(theta, *_noncircular_design())


# --------------------------------------------------------------------------------------------
# rhomboid cam: the example's first-harmonic law (psi_min 40 deg)
# --------------------------------------------------------------------------------------------
_R_PSI_MIN = math.radians(40.0)


def _rhomboid_law():
    a1, b1 = rc.first_harmonic(_R_PSI_MIN)
    return float(a1), float(b1), np.zeros(0), np.zeros(0)


def _rhomboid_build(size, seed):
    alpha = _theta(size, seed)
    law = _rhomboid_law()
    out = np.zeros((4, 2, size))
    return alpha, {
        "lib": lambda: law_fused(*law, alpha, blades=True, threads=1, out=out),
        "lib_numpy": lambda: law_fused(
            *law, alpha, blades=True, threads=1, kernel="numpy", out=out
        ),  # fmt: skip
        "lib_2t": lambda: law_fused(*law, alpha, blades=True, threads=2, out=out),
        "lib_alloc": lambda: rc.blade_angles(_R_PSI_MIN, (), (), alpha),
        **floor_methods([(np.tan, alpha)], 8, size),
    }


def _rhomboid_library(alpha, kernel):
    return law_fused(*_rhomboid_law(), alpha, blades=True, kernel=kernel).reshape(8, -1)


def _rhomboid_scalar(alpha):
    a1, b1, _, _ = _rhomboid_law()
    return scalar_ports.rhomboid(alpha, a1, b1)


CASES = {
    c.name: c
    for c in (
        Case("wobble_cam", "wobble cam: both rotor angles, 3 derivatives each, 2 chamber angles",
             {"plate_tilt_deg": 45.0, "roller_axis_angle_deg": 90.0, "spin_ratio": -2.0,
              "compression_ratio": 10.0, "pistons_per_rotor": 4,
              "piston_width_deg": math.degrees(_W_WIDTH)},
             10, "tan, 2 arctan", _wobble_build, _wobble_scalar, _wobble_library),
        Case("eccentric_cam", "eccentric cam: both piston travels, 3 derivatives each",
             {"contact_radius_mm": 80.0, "eccentricity_mm": 40.0, "follower": "knife_edge"},
             8, "tan, sqrt", _eccentric_build, _eccentric_scalar, _eccentric_library),
        Case("guide_bar", "guide bar (crank-driven): both impeller angles, 3 derivatives each",
             dict(_G, driver="crank"), 8, "2 tan, 2 arctan", _guide_build, _guide_scalar,
             _guide_library),
        Case("noncircular_gears", "non-circular gears: both rotor angles, 3 derivatives each",
             {"lobes": 2, "rotor_lobes": 2, "eccentricity": 0.2, "phase_deg": 90.0},
             8, "2 tan, 2 arctan", _noncircular_build, _noncircular_scalar,
             _noncircular_library),
        Case("rhomboid_cam", "rhomboid cam: both blade-pair angles, 3 derivatives each",
             {"psi_min_deg": 40.0, "harmonics": "first only"}, 8, "tan", _rhomboid_build,
             _rhomboid_scalar, _rhomboid_library),
    )
}  # fmt: skip
