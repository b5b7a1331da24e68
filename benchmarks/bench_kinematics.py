"""Throughput of the wobble-cam kinematics (issue 6, item 4, first bullet).

At 1e3 ... 1e7 shaft angles, the library's kinematics -- both rotor angles with
their three exact derivatives and the chamber angles of both kinds,
:func:`rotorkin.drives.wobble_cam.kinematics.kinematics` -- against

(a) ``per_point``: the paper's method ported point by point, as a MATLAB script
    usually is: a Python loop that builds ``A_theta``, ``A_phi``, ``A_varphi``
    (eq. 2-4), takes the three 3x3 products ``A_theta A_phi A_varphi [r1|3 r2|3]``
    (eq. 5, 12-13), the rotor angles from the yz projections (eq. 14), the slider
    angle from eq. 15 (arccos), the chamber angles from eq. 19/22 and the three
    derivatives from their closed forms, all with scalar ``math`` functions.
    Timed on at most ``--cap`` points and extrapolated per point beyond;
(b) ``floor``: numpy evaluating only the transcendental functions the closed form
    needs, on arrays of the same size, into preallocated outputs: ``sin`` and
    ``cos`` of ``2 varphi`` and one ``arctan`` per rotor (``floor_atan2``, with
    ``arctan2`` instead, is the probe quoted in the issue). The library gets
    ``sin 2varphi`` and ``cos 2varphi`` from one ``tan varphi``, so it can run under
    (b); ``floor_tan`` (b') times the calls it does make (``tan``, 2 ``arctan``):
    the library's time over (b') is its overhead beyond the transcendentals.

Also timed: the library on 2 threads, the library writing into preallocated
arrays (``out=``, as the floor does: fresh memory costs page faults, very
expensive in a VM that returns freed memory to its host), the two-call path of the study
(``rotor_angles`` then ``chamber_angles``) and ``before``, the 0.1.0 code
(``compose`` chain rule, ``angle_near``, broadcast copies). All methods of one
size are timed round-robin (``_common.interleaved``), so the ratios are measured
side by side under the same load. Results: a table on stdout and
``benchmarks/results/kinematics.json``.

Run from the repository root::

    python benchmarks/bench_kinematics.py
    python benchmarks/bench_kinematics.py --sizes 1e3,1e4,1e5 --out /tmp/k.json   # quick
"""

from __future__ import annotations

import argparse
import gc
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import interleaved, load, machine, peak_rss, write_json  # noqa: E402

from rotorkin.core.motion import compose  # noqa: E402
from rotorkin.drives.wobble_cam import kinematics as wc  # noqa: E402
from rotorkin.drives.wobble_cam.fast import rotor_kinematics  # noqa: E402

#: Paper Table 1: phi = 45 deg, alpha = 90 deg, varphi = -2 theta, eps = 10, N = 4.
TILT, ALPHA, SPIN, EPS, PISTONS = math.radians(45.0), math.radians(90.0), -2.0, 10.0, 4
TARGET_FLOOR, TARGET_PER_POINT = 2.0, 120.0
DEFAULT_OUT = Path(__file__).resolve().parent / "results" / "kinematics.json"
COMMAND = "python benchmarks/bench_kinematics.py"


# --------------------------------------------------------------------------------------------
# (a) the paper's method, point by point
# --------------------------------------------------------------------------------------------
def per_point(theta, n, phi, alpha, beta, pistons):
    """Rows: Phi_1, Phi_2 (wrapped), Phi', Phi'', Phi''' (rotors 1, 2 each), delta_A, delta_B."""
    out = np.empty((10, len(theta)))
    h = 0.5 * alpha
    r3 = np.array([[0.0, 0.0], [-math.sin(h), math.sin(h)], [math.cos(h), math.cos(h)]])  # eq. 12
    gamma = math.pi / 4.0 - math.pi / (2.0 * pistons)
    for i in range(len(theta)):
        th = float(theta[i])
        vp = n * th
        ct, st = math.cos(th), math.sin(th)
        cp, sp = math.cos(phi), math.sin(phi)
        cv, sv = math.cos(vp), math.sin(vp)
        a_theta = np.array([[1.0, 0.0, 0.0], [0.0, ct, st], [0.0, -st, ct]])  # eq. 4
        a_phi = np.array([[cp, 0.0, sp], [0.0, 1.0, 0.0], [-sp, 0.0, cp]])  # eq. 3
        a_varphi = np.array([[1.0, 0.0, 0.0], [0.0, cv, sv], [0.0, -sv, cv]])  # eq. 2
        r0 = a_theta @ a_phi @ a_varphi @ r3  # eq. 5, 13
        out[0, i] = math.atan2(r0[1, 0], r0[2, 0])  # eq. 14: yz projection, from z to y
        out[1, i] = math.atan2(r0[1, 1], r0[2, 1])
        sm, cm = math.sin(vp - h), math.cos(vp - h)
        sq, cq = math.sin(vp + h), math.cos(vp + h)
        c2 = cp * cp
        num = sm * sq + c2 * cm * cq
        den = math.sqrt((sm * sm + c2 * cm * cm) * (sq * sq + c2 * cq * cq))
        slider = math.acos(num / den)  # eq. 15
        k = 1.0 - c2
        for j, (s, c) in enumerate(((sm, cm), (sq, cq))):
            d = s * s + c2 * c * c
            s2, cos2 = 2.0 * s * c, c * c - s * s
            out[2 + j, i] = 1.0 + n * cp / d
            out[4 + j, i] = -n * n * cp * k * s2 / (d * d)
            out[6 + j, i] = n**3 * 2.0 * cp * k / (d * d) * (k * s2 * s2 / d - cos2)
        out[8, i] = slider - 2.0 * gamma - beta  # eq. 19
        out[9, i] = 2.0 * math.pi / pistons + 2.0 * gamma - slider - beta  # eq. 18
    return out


# --------------------------------------------------------------------------------------------
# (b) the floor, and the 0.1.0 implementation
# --------------------------------------------------------------------------------------------
def floor_fns(theta):
    """The transcendental calls alone, on arrays of ``theta``'s size, into preallocated outputs.

    ``floor``: ``sin`` and ``cos`` of ``2 varphi`` and one ``arctan`` per rotor;
    ``floor_atan2``: ``arctan2`` instead; ``floor_tan``: one ``tan varphi`` instead of
    the sine and cosine, as the library does. The three share their arrays.
    """
    x = 2.0 * SPIN * theta
    v = SPIN * theta
    g = (1 + math.cos(TILT)) / (1 - math.cos(TILT))
    nums = [np.sin(x - ALPHA), np.sin(x + ALPHA)]  # realistic atan arguments: S / (g - C)
    dens = [g - np.cos(x - ALPHA), g - np.cos(x + ALPHA)]
    ratios = [nums[0] / dens[0], nums[1] / dens[1]]
    outs = [np.empty_like(theta) for _ in range(4)]

    def floor():
        np.sin(x, out=outs[0])
        np.cos(x, out=outs[1])
        np.arctan(ratios[0], out=outs[2])
        np.arctan(ratios[1], out=outs[3])

    def floor_atan2():
        np.sin(x, out=outs[0])
        np.cos(x, out=outs[1])
        np.arctan2(nums[0], dens[0], out=outs[2])
        np.arctan2(nums[1], dens[1], out=outs[3])

    def floor_tan():
        np.tan(v, out=outs[0])
        np.arctan(ratios[0], out=outs[2])
        np.arctan(ratios[1], out=outs[3])

    return {"floor": floor, "floor_atan2": floor_atan2, "floor_tan": floor_tan}


def before(params, theta, beta):
    """rotorkin 0.1.0: compose() chain rule, angle_near, broadcast copies; then chamber_angles."""
    theta = np.asarray(theta, dtype=float)
    spin = wc.spin_law(params, theta)
    half = 0.5 * params.roller_axis_angle
    sign = np.array([-1.0, 1.0]).reshape((2,) + (1,) * theta.ndim)
    u = spin[0] + sign * half
    h = compose(wc.projected_angle(params.plate_tilt, u), (u, spin[1], spin[2], spin[3]))
    full = (2, *theta.shape)
    q = tuple(np.broadcast_to(x, full).copy() for x in (theta + h[0], 1.0 + h[1], h[2], h[3]))
    return q, wc.chamber_angles(beta, q[0][1] - q[0][0], pistons=params.pistons_per_rotor)


def _as_rows(rotor, da, db):
    return np.concatenate([np.asarray(rotor).reshape(8, -1), da[None], db[None]])


def agreement(params, beta, points=2000):
    """Largest differences between the methods on ``points`` angles (angles wrapped for (a))."""
    theta = np.random.default_rng(1).uniform(-2 * np.pi, 2 * np.pi, points)
    k1 = wc.kinematics(params, theta, beta, threads=1)
    lib = _as_rows((k1.q, k1.dq, k1.d2q, k1.d3q), k1.chamber_a, k1.chamber_b)
    k2 = wc.kinematics(params, np.tile(theta, 64), beta, threads=2)  # large enough for 2 threads
    two = _as_rows((k2.q, k2.dq, k2.d2q, k2.d3q), k2.chamber_a, k2.chamber_b)[:, :points]
    q = wc.rotor_angles(params, theta)
    split = _as_rows(q, *wc.chamber_angles(beta, q[0][1] - q[0][0], pistons=PISTONS))
    qb, (da, db) = before(params, theta, beta)
    old = _as_rows(qb, da, db)
    pp = per_point(theta, SPIN, TILT, ALPHA, beta, PISTONS)
    wrapped = np.angle(np.exp(1j * (pp[:2] - lib[:2])))
    scale = np.maximum(1.0, np.max(np.abs(lib), axis=1))[:, None]
    return {
        "points": points,
        "library_2threads_vs_1thread_max_abs": float(np.max(np.abs(two - lib))),
        "rotor_angles_path_vs_library_max_rel": float(np.max(np.abs(split - lib) / scale)),
        "before_vs_library_max_rel": float(np.max(np.abs(old - lib) / scale)),
        "per_point_vs_library_max_rel": float(
            max(np.max(np.abs(wrapped)), np.max(np.abs(pp[2:] - lib[2:]) / scale[2:]))
        ),
    }


# --------------------------------------------------------------------------------------------
# the run
# --------------------------------------------------------------------------------------------
def measure(params, beta, size, cap, cap_before, rounds, budget):
    """Best times [s] of every method at ``size`` points, timed round-robin."""
    theta = np.random.default_rng(size).uniform(0.0, 2.0 * np.pi, size)
    sub = theta[: min(size, cap)]
    out = (np.zeros((4, 2, size)), np.zeros((2, size)))  # touched once, like the floor's
    fns = {
        "per_point": lambda: per_point(sub, SPIN, TILT, ALPHA, beta, PISTONS),
        **floor_fns(theta),
        "library": lambda: wc.kinematics(params, theta, beta, threads=1),
        "library_2threads": lambda: wc.kinematics(params, theta, beta, threads=2),
        "library_out": lambda: rotor_kinematics(
            TILT, ALPHA, SPIN, theta, chamber=(beta, PISTONS), threads=1, out=out
        ),
        "rotor_angles_path": lambda: wc.chamber_angles(
            beta, np.subtract(*wc.rotor_angles(params, theta, threads=1)[0][::-1]), pistons=PISTONS
        ),
    }
    if size <= cap_before:
        fns["before"] = lambda: before(params, theta, beta)
    load0 = load()
    stats = {}
    best = interleaved(fns, rounds, budget, stats)
    per_point_ns = best.pop("per_point") / len(sub) * 1e9
    ns = {name: t / size * 1e9 for name, t in best.items()}
    ns["per_point"] = per_point_ns
    times = {name: ns[name] * size * 1e-9 for name in ns}
    lib, lib2, fl = ns["library"], ns["library_2threads"], ns["floor"]
    ratios = {
        "library_over_floor": lib / fl,
        "per_point_over_library": per_point_ns / lib,
        "library_2threads_over_floor": lib2 / fl,
        "per_point_over_library_2threads": per_point_ns / lib2,
        "floor_atan2_over_floor": ns["floor_atan2"] / fl,
        "library_over_floor_tan": lib / ns["floor_tan"],
        "library_out_over_floor": ns["library_out"] / fl,
        "rotor_angles_path_over_library": ns["rotor_angles_path"] / lib,
    }
    if "before" in ns:
        ratios["before_over_library"] = ns["before"] / lib
    return {
        "points": size,
        "per_point_timed_on": len(sub),
        "per_point_extrapolated": len(sub) < size,
        "rounds": stats["rounds"],
        "seconds": times,
        "ns_per_point": ns,
        "ratios": ratios,
        "load_before": load0,
        "load_after": load(),
    }


COLUMNS = (
    # header, width, format, getter
    ("points", 8, ".0e", lambda row: row["points"]),
    ("(a) ns", 8, ".0f", lambda row: row["ns_per_point"]["per_point"]),
    ("(b) ns", 7, ".1f", lambda row: row["ns_per_point"]["floor"]),
    ("(b') ns", 7, ".1f", lambda row: row["ns_per_point"]["floor_tan"]),
    ("lib ns", 7, ".1f", lambda row: row["ns_per_point"]["library"]),
    ("out ns", 7, ".1f", lambda row: row["ns_per_point"]["library_out"]),
    ("lib2 ns", 7, ".1f", lambda row: row["ns_per_point"]["library_2threads"]),
    ("0.1.0", 7, ".1f", lambda row: row["ns_per_point"].get("before", math.nan)),
    ("lib/(b)", 7, ".2f", lambda row: row["ratios"]["library_over_floor"]),
    ("out/(b)", 7, ".2f", lambda row: row["ratios"]["library_out_over_floor"]),
    ("(a)/lib", 7, ".0f", lambda row: row["ratios"]["per_point_over_library"]),
    ("lib2/(b)", 8, ".2f", lambda row: row["ratios"]["library_2threads_over_floor"]),
    ("(a)/lib2", 8, ".0f", lambda row: row["ratios"]["per_point_over_library_2threads"]),
)


def _fmt_row(row):
    cells = [f"{get(row):>{w}{fmt}}" for _, w, fmt, get in COLUMNS]
    star = "*" if row["per_point_extrapolated"] else " "
    cells[1] += star
    load_text = f"{row['load_before'][0]:.1f}/{row['load_after'][0]:.1f}"
    return " ".join(cells) + "  " + load_text


HEADER = " ".join(f"{h:>{w}}" for h, w, _, _ in COLUMNS) + "   load\n" + "-" * 104


def markdown(result) -> str:
    """A result file as the markdown table of ``docs/performance.md`` (the columns above)."""
    lines = ["| " + " | ".join(h for h, *_ in COLUMNS) + " | load |"]
    lines.append("|" + "---:|" * (len(COLUMNS) + 1))
    for row in result["rows"]:
        cells = [f"{get(row):{fmt}}" for _, _, fmt, get in COLUMNS]
        cells[0] = f"1e{round(math.log10(row['points']))}"
        cells[1] += "*" if row["per_point_extrapolated"] else ""
        cells = [c.replace("nan", "-") for c in cells]
        load_text = f"{row['load_before'][0]:.1f}-{row['load_after'][0]:.1f}"
        lines.append("| " + " | ".join(cells) + f" | {load_text} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", default="1e3,1e4,1e5,1e6,1e7", help="comma-separated point counts")
    ap.add_argument("--cap", type=float, default=1e5, help="most points timed for (a)")
    ap.add_argument("--cap-before", type=float, default=1e6, help="most points for the 0.1.0 code")
    ap.add_argument("--budget", type=float, default=30.0, help="seconds of timing per size")
    ap.add_argument("--rounds", type=int, default=50, help="most rounds per size")
    ap.add_argument("--out", type=Path, default=DEFAULT_OUT, help="JSON result file")
    ap.add_argument("--markdown", type=Path, help="only print this result file as a markdown table")
    args = ap.parse_args(argv)
    if args.markdown is not None:
        print(markdown(json.loads(args.markdown.read_text())))
        return 0
    sizes = [int(float(s)) for s in args.sizes.split(",") if s.strip()]
    params = wc.WobbleCam(TILT, ALPHA, SPIN, 0.05, PISTONS)
    beta = wc.piston_layout(params, EPS).piston_width
    t_start = time.perf_counter()
    info = machine()
    print(
        f"wobble-cam kinematics throughput; numpy {info['numpy']}, {info['cores']} cores "
        f"({info['cpu']}), load {info['load_average']}"
    )
    print("(a) per-point port of the paper; (b) floor: sin, cos, 2 arctan; (b'): tan, 2 arctan")
    print("(the calls the library makes); lib: library, 1 thread; out: the same writing into")
    print("preallocated arrays, as the floor does; lib2: 2 threads; 0.1.0: the code before;")
    print("* = (a) extrapolated from --cap points; times in ns per point\n")
    agree = agreement(params, beta)
    print("agreement:", ", ".join(f"{k} {v:.2g}" for k, v in agree.items() if k != "points"))
    print(HEADER)
    rows = []
    for size in sizes:
        rounds = args.rounds
        row = measure(params, beta, size, int(args.cap), int(args.cap_before), rounds, args.budget)
        rows.append(row)
        print(_fmt_row(row), flush=True)
        gc.collect()
    at = {row["points"]: row for row in rows}.get(10**6)
    targets = {
        "library_over_floor_max": TARGET_FLOOR,
        "per_point_over_library_min": TARGET_PER_POINT,
    }
    if at is not None:
        r = at["ratios"]
        targets["at_1e6"] = {
            "library_over_floor": r["library_over_floor"],
            "per_point_over_library": r["per_point_over_library"],
            "met_1_thread": bool(
                r["library_over_floor"] <= TARGET_FLOOR
                and r["per_point_over_library"] >= TARGET_PER_POINT
            ),
            "met_2_threads": bool(
                r["library_2threads_over_floor"] <= TARGET_FLOOR
                and r["per_point_over_library_2threads"] >= TARGET_PER_POINT
            ),
        }
        met = [
            "met" if targets["at_1e6"][k] else "NOT met" for k in ("met_1_thread", "met_2_threads")
        ]
        print(
            f"\ntargets at 1e6 points: lib/(b) <= {TARGET_FLOOR}, (a)/lib >= {TARGET_PER_POINT}: "
            f"1 thread {met[0]}, 2 threads {met[1]}"
        )
    result = {
        "benchmark": "wobble-cam kinematics throughput (issue 6, item 4)",
        "command": " ".join([COMMAND, *(sys.argv[1:] if argv is None else argv)]),
        "machine": info,
        "design": {
            "plate_tilt_deg": 45.0,
            "roller_axis_angle_deg": 90.0,
            "spin_ratio": SPIN,
            "compression_ratio": EPS,
            "pistons_per_rotor": PISTONS,
            "piston_width_deg": math.degrees(beta),
        },
        "outputs_per_point": "Phi_1, Phi_2, 3 derivatives each, delta_A, delta_B (10 values)",
        "methods": {
            "per_point": "(a) the paper's method ported point by point (Python loop, 3x3 products)",
            "floor": "(b) sin, cos of 2 varphi and one arctan per rotor, preallocated outputs",
            "floor_atan2": "(b) with arctan2 instead of arctan (the issue's probe)",
            "floor_tan": "(b') the calls the library makes: tan varphi and one arctan per rotor",
            "library": "rotorkin.drives.wobble_cam.kinematics.kinematics, 1 thread",
            "library_2threads": "the same on 2 threads",
            "library_out": "the library, 1 thread, writing into preallocated arrays (out=)",
            "rotor_angles_path": "rotor_angles then chamber_angles (the study's two calls)",
            "before": "rotorkin 0.1.0 rotor_angles (compose, angle_near) + chamber_angles",
        },
        "agreement": agree,
        "targets": targets,
        "rows": rows,
        "peak_rss_bytes": peak_rss(),
        "wall_seconds": time.perf_counter() - t_start,
    }
    path = write_json(args.out, result)
    print(f"peak RSS {peak_rss() / 2**20:.0f} MiB; wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
