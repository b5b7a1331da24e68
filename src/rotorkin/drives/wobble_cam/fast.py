"""Fast path of the wobble-cam kinematics: one fused pass over blocks of points.

The closed form of :func:`rotorkin.drives.wobble_cam.kinematics.rotor_angles_from_spin`,
rearranged so that each point costs three transcendental calls and about 55
in-place multiplications and additions (``u_k = varphi + s_k alpha/2``,
``s_1 = -1``, ``s_2 = +1``, ``c = cos(phi)``, ``k = 1 - c^2``):

* ``sin 2varphi = 2 t/(1 + t^2)`` and ``cos 2varphi = 2/(1 + t^2) - 1`` from one
  ``t = tan varphi`` (cheaper than a sine and a cosine; ``|t| < 2e16`` for any
  double, so ``t^2`` never overflows and both stay accurate to a few ulp);
* ``S_k = sin 2u_k`` and ``C_k = cos 2u_k`` of *both* rotors from them and the
  constants ``cos alpha``, ``sin alpha`` (angle sums, ``2u_k = 2 varphi -+ alpha``);
* ``E(u) = u + atan(S / (g - C))``, ``g = (1 + c)/(1 - c)``: the ``atan2`` of
  :func:`rotorkin.core.angles.angle_near` with reference ``u`` (the projected plate
  radius rotated by ``-u`` is ``((1 - c) sin u cos u, sin^2 u + c cos^2 u)``;
  divide by ``(1 - c)/2``). Its denominator ``g - C > 0``, so one ``atan`` per
  rotor gives the continuous branch;
* ``D = sin^2 u + c^2 cos^2 u = (1 + c^2)/2 - k/2 C`` (the paper note's
  eq. 14 squared projection length): ``E' = c/D``, ``E'' = -c k S/D^2``,
  ``E''' = 2 c k/D^2 (k S^2/D - C)``;
* ``Phi_k = theta + E(u_k)`` and the chain rule (Faa di Bruno) through the spin
  law; for the linear law ``varphi = n theta`` it reduces to
  ``Phi' = 1 + n E'``, ``Phi'' = n^2 E''``, ``Phi''' = n^3 E'''``;
* the chamber angles of eq. 18-19, ``delta_A = alpha' - 2 gamma - beta`` and
  ``delta_B = 2 pi/N + 2 gamma - alpha' - beta``, ``alpha' = Phi_2 - Phi_1``.

The points are walked in blocks of :data:`BLOCK`: slices when every array input
has the full shape, else a buffered C-order :class:`numpy.nditer` broadcasts
them (inputs of different shapes are never materialised at the full size). The
scratch arrays of a block stay in the L2 cache and every result is written
once, straight into the output. With ``threads > 1`` (or ``$ROTORKIN_THREADS``)
the blocks of large inputs are shared among a thread pool: numpy releases the
GIL inside its loops. Every value depends on its own point only, so the
results are the same, bit for bit, whatever the shape, the strides, the block
boundaries or the thread count.

Two paths evaluate a block's arithmetic (:mod:`rotorkin.core.fused`): the numpy
operations of :func:`_block` (always available), or the compiled loops of
:mod:`rotorkin.drives.wobble_cam.kinematics_fused` (numba, the ``fast`` extra), which
fuse them into two passes around the same numpy ``tan`` and ``arctan`` calls.
``kernel="numpy"``/``"numba"`` or ``$ROTORKIN_KERNEL`` chooses; by default the
compiled loops run when numba is installed and there are at least
:data:`rotorkin.core.fused.AUTO_MIN_POINTS` points. Both give the same numbers.
"""

from __future__ import annotations

import math

import numpy as np

from rotorkin.core.fused import (
    BLOCK,
    COMPILED_BLOCK,
    THREADS_ENV,
    chunks,
    default_threads,
    split,
    use_compiled,
)
from rotorkin.drives.wobble_cam import kinematics_fused as fused

__all__ = [
    "BLOCK",
    "EXTREMES",
    "THREADS_ENV",
    "default_threads",
    "rotor_extremes",
    "rotor_kinematics",
]

#: Inputs from which the constants of the formulas follow (:func:`_coefficients`).
_DESIGN = ("tilt", "half", "width")
_SCRATCH = 14


def rotor_kinematics(
    plate_tilt, roller_axis_angle, spin, theta, *, chamber=None, threads=None, out=None, kernel=None
):
    """Rotor angles, their three derivatives and (optionally) the chamber angles, fused.

    Parameters
    ----------
    plate_tilt, roller_axis_angle : float or array_like
        phi and alpha [rad], ``0 <= phi < pi/2``; broadcast with ``theta``.
    spin : float or sequence of 4 array_like
        The spin law: a number ``n`` for the linear law ``varphi = n theta``
        (the paper's ``n = -2``), or ``varphi, varphi', varphi'', varphi'''``
        at ``theta`` [rad, -, 1/rad, 1/rad^2].
    theta : array_like, shape (...)
        Shaft angle [rad].
    chamber : (piston_width, pistons), optional
        beta [rad] (float or array_like, broadcast) and N (pistons per rotor):
        also return the chamber angles of both kinds (eq. 18-19).
    threads : int, optional
        Threads sharing the blocks (default :func:`default_threads`); arrays
        under ``8 BLOCK`` points always run on the calling thread.
    out : (ndarray, ndarray or None), optional
        Arrays to write the results into (float64, C-contiguous, the shapes
        below), e.g. to reuse them block after block; new arrays by default.
    kernel : {"auto", "numpy", "numba"}, optional
        The block arithmetic: numpy operations or compiled loops (default
        ``$ROTORKIN_KERNEL``, else ``"auto"``: :func:`rotorkin.core.fused.use_compiled`).

    Returns
    -------
    rotor : ndarray, shape (4, 2, ...)
        ``Phi, dPhi/dtheta, d2Phi/dtheta2, d3Phi/dtheta3`` (axis 0) of rotor 1
        and rotor 2 (axis 1) [rad, -, 1/rad, 1/rad^2].
    chambers : ndarray, shape (2, ...), or None
        ``delta_A, delta_B`` [rad] when ``chamber`` is given.
    """
    inputs = {"theta": np.asarray(theta, dtype=float)}
    if isinstance(spin, (float, int, np.number)) or np.ndim(spin) == 0:
        n = float(spin)
    else:
        n = None
        parts = [np.asarray(s, dtype=float) for s in spin]
        if len(parts) != 4:
            raise ValueError(f"spin: expected a number or 4 arrays, got {len(parts)} arrays")
        inputs.update(zip(("v", "g1", "g2", "g3"), parts, strict=True))
    inputs["tilt"] = np.asarray(plate_tilt, dtype=float)
    inputs["half"] = 0.5 * np.asarray(roller_axis_angle, dtype=float)
    pistons = None
    if chamber is not None:
        inputs["width"] = np.asarray(chamber[0], dtype=float)
        pistons = float(chamber[1])
    shapes = {a.shape for a in inputs.values()} - {()}
    shape = shapes.pop() if len(shapes) == 1 else np.broadcast_shapes(*shapes, ())
    size = math.prod(shape)
    if out is None:
        rotor = np.empty((4, 2, *shape))
        cham = np.empty((2, *shape)) if chamber is not None else None
    else:
        rotor, cham = out
        _check_out(rotor, (4, 2, *shape), "out[0]")
        if chamber is not None:
            _check_out(cham, (2, *shape), "out[1]")
        else:
            cham = None
    if size == 0:
        return rotor, cham
    scalars = {k: float(a.reshape(-1)[0]) for k, a in inputs.items() if a.size == 1}
    arrays = {k: a for k, a in inputs.items() if a.size > 1}
    # the design's constants, once per call: math on numbers, numpy on the design arrays'
    # own shapes (e.g. designs (m, 1)), then broadcast block by block like any input
    fixed = _coefficients({k: v for k, v in scalars.items() if k in _DESIGN}, n, pistons)
    design = {k: arrays.pop(k) for k in _DESIGN if k in arrays}
    if design:
        arrays.update(_coefficients(design, n, pistons))
    scalars.update(fixed)
    flat_r = rotor.reshape(4, 2, size)
    flat_c = cham.reshape(2, size) if cham is not None else None
    if all(a.shape == shape and a.flags.c_contiguous for a in arrays.values()):
        arrays = {k: a.reshape(-1) for k, a in arrays.items()}  # plain slices, no nditer
        flat = True
    else:
        flat = False
    job = (arrays, flat, scalars, n, pistons, flat_r, flat_c, use_compiled(size, kernel))
    split(lambda lo, hi: _run(job, lo, hi), size, threads)
    return rotor, cham


def _check_out(array, shape, name):
    ok = isinstance(array, np.ndarray) and array.dtype == np.float64
    if not (ok and array.shape == shape and array.flags.c_contiguous and array.flags.writeable):
        got = f"{getattr(array, 'dtype', type(array).__name__)} {np.shape(array)}"
        raise ValueError(
            f"{name}: expected a writeable C-contiguous float64 array {shape}, got {got}"
        )


def _run(job, lo, hi):
    """Evaluate the flat points ``lo:hi`` block by block."""
    arrays, flat, scalars, n, pistons, flat_r, flat_c, compiled = job
    block_size = COMPILED_BLOCK if compiled else BLOCK
    work = np.empty((6 if compiled else _SCRATCH, min(block_size, hi - lo)))
    block = _block_compiled if compiled else _block
    if not arrays:  # a single point
        block(scalars, scalars, n, flat_r, flat_c, work[:, :1], 0)
        return
    for start, stop, chunk in chunks(arrays, flat, lo, hi, block_size):
        x = k = {**scalars, **chunk}  # inputs and the design's constants
        if compiled:
            _block_compiled(x, k, n, flat_r, flat_c, work[:, : stop - start], start)
        else:
            cham = flat_c[:, start:stop] if flat_c is not None else None
            _block(x, k, n, flat_r[:, :, start:stop], cham, work[:, : stop - start], 0)


def _block_compiled(x, k, n, o, dch, w, lo):
    """One block by the compiled loops: ``o[:, :, lo:lo + m]``, ``dch[:, lo:lo + m]``.

    ``o`` (4, 2, size) and ``dch`` (2, size) are the whole flat outputs; the loops
    write at ``lo + i``. Same operations as :func:`_block`.
    """
    tv, vt, e1, e2 = w[0], w[1], w[2], w[3]
    th = x["theta"]
    if n is not None:
        np.multiply(th, n, out=tv)
    else:
        np.copyto(tv, x["v"])
        np.add(x["v"], th, out=vt)
    np.tan(tv, out=tv)
    trig = (k["ca"], k["sa"], k["ca2"], k["sa2"])
    fused.atan_arguments(tv, *trig, k["gamma"], e1, e2)
    np.arctan(w[2:4], out=w[2:4])  # e1, e2 in one call
    m = tv.shape[0]
    outs = [o[i, r, lo : lo + m] for i in range(4) for r in range(2)]
    chambers = dch is not None
    ka, kb = (k["ka"], k["kb"]) if chambers else (0.0, 0.0)
    cham = (dch[0, lo : lo + m], dch[1, lo : lo + m]) if chambers else (w[4], w[5])
    common = (k["h"], k["a0"], k["b0"], k["k"])
    if n is not None:
        fused.linear_outputs(
            tv, th, 1.0 + n, e1, e2, *trig, *common, k["nc"], k["a2"], k["a3"], ka, kb,
            *outs, chambers, *cham,
        )  # fmt: skip
    else:
        fused.general_outputs(
            tv, vt, e1, e2, *trig, *common, k["c"], k["mck"], k["ck2"], x["g1"], x["g2"],
            x["g3"], ka, kb, *outs, chambers, *cham,
        )  # fmt: skip


def _coefficients(x, n, pistons):
    """Constants of the formulas from the tilt, half angle and piston width in ``x``.

    Floats for scalar inputs (once per call), block arrays for array inputs
    (once per block); inputs missing from ``x`` are skipped.
    """
    out = {}
    if "tilt" in x:
        tilt = x["tilt"]
        if isinstance(tilt, float):
            c = math.cos(tilt)
            gamma = (1.0 + c) / (1.0 - c) if c != 1.0 else math.inf
        else:
            c = np.cos(tilt)
            with np.errstate(divide="ignore"):  # phi = 0: gamma = inf, atan term 0
                gamma = (1.0 + c) / (1.0 - c)
        k = 1.0 - c * c
        ck = c * k
        out.update(c=c, k=k, gamma=gamma, a0=0.5 * (1.0 + c * c), b0=0.5 * k, mck=-ck, ck2=2 * ck)
        if n is not None:
            out.update(nc=n * c, a2=-(n * n) * ck, a3=2.0 * n**3 * ck)
    if "half" in x:
        h = x["half"]
        trig = math if isinstance(h, float) else np
        ca, sa = trig.cos(2.0 * h), trig.sin(2.0 * h)
        out.update(h=h, mh=-h, ca=ca, sa=sa, ca2=2.0 * ca, sa2=2.0 * sa)
    if pistons is not None and "width" in x:
        g2 = 2.0 * (0.25 * np.pi - 0.5 * np.pi / pistons)
        out.update(ka=-g2 - x["width"], kb=2.0 * np.pi / pistons + g2 - x["width"])
    return out


def _block(x, k, n, o, dch, w, lo=0):
    """One block: fill ``o`` (4, 2, m) and ``dch`` (2, m) from inputs ``x``, constants ``k``.

    In terms of ``S = sin 2u``, ``C = cos 2u``, ``D = (1 + c^2)/2 - k/2 C``:
    ``E = u + atan(S / (gamma - C))``, ``gamma = (1 + c)/(1 - c)``;
    ``E' = c/D``, ``E'' = -c k S/D^2``, ``E''' = 2 c k/D^2 (k S^2/D - C)``.
    """
    tv, vt, s2v, c2v, t1, t2, t3, t4, s, c, a, b, e1, e2 = w
    th = x["theta"]
    if n is not None:
        np.multiply(th, n, out=tv)
        np.multiply(th, 1.0 + n, out=vt)  # theta + varphi
    else:
        np.copyto(tv, x["v"])  # contiguous: one tan loop whatever the strides
        np.add(x["v"], th, out=vt)
    # sin 2 varphi = 2 t/(1 + t^2), cos 2 varphi = 2/(1 + t^2) - 1, t = tan varphi: one
    # call instead of sin and cos (|t| < 2e16 for any double, t^2 does not overflow)
    np.tan(tv, out=tv)
    np.multiply(tv, tv, out=c2v)
    np.add(c2v, 1.0, out=c2v)
    np.divide(1.0, c2v, out=c2v)  # cos^2 varphi
    np.multiply(tv, c2v, out=s2v)  # sin 2 varphi / 2
    np.multiply(c2v, 2.0, out=c2v)
    np.subtract(c2v, 1.0, out=c2v)  # cos 2 varphi
    # sin 2u, cos 2u of both rotors, 2u = 2 varphi -+ alpha (angle sums)
    np.multiply(s2v, k["ca2"], out=t1)
    np.multiply(c2v, k["sa"], out=t2)
    np.multiply(c2v, k["ca"], out=t3)
    np.multiply(s2v, k["sa2"], out=t4)
    if n is None:
        g1, g2, g3 = x["g1"], x["g2"], x["g3"]
        g1s, g1c, g12 = g1 * g1, g1 * g1 * g1, 3.0 * g1 * g2
    for rot, plus in ((0, False), (1, True)):
        if plus:
            np.add(t1, t2, out=s)
            np.subtract(t3, t4, out=c)
        else:
            np.subtract(t1, t2, out=s)
            np.add(t3, t4, out=c)
        o0, o1, o2, o3 = o[0, rot], o[1, rot], o[2, rot], o[3, rot]
        # Phi = theta + u + atan(S / (gamma - C))
        np.subtract(k["gamma"], c, out=a)
        np.divide(s, a, out=b)
        np.arctan(b, out=b)
        np.add(vt, k["h"] if plus else k["mh"], out=o0)
        np.add(o0, b, out=o0)
        # 1/D
        np.multiply(c, k["b0"], out=a)
        np.subtract(k["a0"], a, out=a)
        np.divide(1.0, a, out=a)
        np.multiply(s, a, out=b)  # S/D
        if n is not None:
            np.multiply(a, k["nc"], out=o1)
            np.add(o1, 1.0, out=o1)
            np.multiply(b, a, out=o2)  # S/D^2
            _third(b, s, a, c, k, o3, k["a3"])
            np.multiply(o2, k["a2"], out=o2)
        else:
            np.multiply(a, k["c"], out=e1)  # E'
            np.multiply(b, a, out=e2)
            np.multiply(e2, k["mck"], out=e2)  # E''
            _third(b, s, a, c, k, s, k["ck2"])  # E''' (in s)
            np.multiply(e1, g1, out=o1)
            np.add(o1, 1.0, out=o1)
            np.multiply(e2, g1s, out=o2)
            np.multiply(e1, g2, out=a)
            np.add(o2, a, out=o2)
            np.multiply(s, g1c, out=o3)
            np.multiply(e2, g12, out=a)
            np.add(o3, a, out=o3)
            np.multiply(e1, g3, out=a)
            np.add(o3, a, out=o3)
    if dch is not None:
        np.subtract(o[0, 1], o[0, 0], out=a)
        np.add(a, k["ka"], out=dch[0])
        np.subtract(k["kb"], a, out=dch[1])


def _third(b, s, a, c, k, out, factor):
    """Set ``out = factor / D^2 (k S^2/D - C)`` from ``b = S/D`` (spent) and ``a = 1/D``."""
    np.multiply(b, s, out=b)
    np.multiply(b, k["k"], out=b)
    np.subtract(b, c, out=b)
    np.multiply(a, a, out=out)
    np.multiply(out, b, out=out)
    np.multiply(out, factor, out=out)


#: Keys of :func:`rotor_extremes`, in the rows of its compiled loop.
EXTREMES = ("acc", "jerk", "r_min", "r_max", "s_min", "s_max")
#: Where each of them starts before the first angle (a maximum at -inf, a minimum at +inf).
_START = np.array([-np.inf, -np.inf, np.inf, -np.inf, np.inf, -np.inf])[:, None]
#: Fewest designs of a tile of :func:`rotor_extremes` (its compiled loops run over them).
_MIN_DESIGNS = 64


def rotor_extremes(plate_tilt, roller_axis_angle, spin, theta, *, kernel=None) -> dict:
    """Per design, over both rotors and the angles: the peaks a sweep keeps of the curves.

    Parameters
    ----------
    plate_tilt, roller_axis_angle : array_like, shape (m,)
        phi and alpha of each design [rad] (numbers: one design).
    spin : float or sequence of 4 array_like
        As :func:`rotor_kinematics`; the tables on ``theta``.
    theta : array_like, shape (A,)
        Shaft angles [rad], the same for every design.
    kernel : {"auto", "numpy", "numba"}, optional
        :func:`rotorkin.core.fused.use_compiled`.

    Returns
    -------
    dict of str -> ndarray, shape (m,)
        ``acc`` = max ``|Phi_k''|``, ``jerk`` = max ``|Phi_k'''|``, ``r_min``, ``r_max`` =
        the extremes of ``Phi_k'`` (both rotors, every angle), ``s_min``, ``s_max`` = the
        extremes of the slider angle ``Phi_2 - Phi_1``; NaN where a curve has a NaN.

    Notes
    -----
    The values are those of :func:`rotor_kinematics` on designs ``(m, 1)`` against
    ``theta``, reduced with numpy (the numpy path does exactly that), bit for bit. The
    compiled path stores no curve: the angles' ``tan`` is taken once for all designs
    (it does not depend on the design); on tiles of designs x angles, one compiled loop
    writes the arctangents' arguments, one numpy ``arctan`` takes them, and one compiled
    loop evaluates every point and folds it into its design's running extremes. Both
    loops run over designs innermost, so that they vectorise, the updates of the
    extremes too (elementwise, with numpy's rule for NaN).
    """
    tilt = np.atleast_1d(np.asarray(plate_tilt, dtype=float)).reshape(-1)
    alpha = np.atleast_1d(np.asarray(roller_axis_angle, dtype=float)).reshape(-1)
    th = np.atleast_1d(np.asarray(theta, dtype=float)).reshape(-1)
    m = max(tilt.size, alpha.size)
    if {tilt.size, alpha.size} - {1, m} or th.size == 0:
        raise ValueError(
            f"rotor_extremes: plate_tilt ({tilt.size}) and roller_axis_angle ({alpha.size}) "
            f"need one value or one per design, theta ({th.size}) at least one angle"
        )
    if not use_compiled(m * th.size, kernel):
        rot, _ = rotor_kinematics(tilt[:, None], alpha[:, None], spin, th, threads=1,
                                  kernel=kernel)  # fmt: skip
        q, d1, d2, d3 = rot
        s = np.subtract(q[1], q[0], out=q[1])
        return {"acc": np.abs(d2).max(axis=(0, 2)), "jerk": np.abs(d3).max(axis=(0, 2)),
                "r_min": d1.min(axis=(0, 2)), "r_max": d1.max(axis=(0, 2)),
                "s_min": s.min(axis=1), "s_max": s.max(axis=1)}  # fmt: skip
    linear = isinstance(spin, (float, int, np.number)) or np.ndim(spin) == 0
    if linear:
        n = float(spin)
        tv = np.multiply(th, n)
        vt = th * (1.0 + n)
        u = (th, th, th)  # not read
    else:
        n = None
        v, *u = (np.broadcast_to(np.asarray(s, dtype=float), th.shape) for s in spin)
        tv = np.array(v)
        vt = np.add(v, th)
    np.tan(tv, out=tv)
    # per design, as rotor_kinematics: a one-element input is a number (math), else numpy
    design = {"tilt": tilt, "half": 0.5 * alpha}
    k = _coefficients({key: float(a[0]) if a.size == 1 else a for key, a in design.items()},
                      n, None)  # fmt: skip
    slope = (k["nc"], k["a2"], k["a3"]) if linear else (k["c"], k["mck"], k["ck2"])
    names = ("ca", "sa", "ca2", "sa2", "gamma", "h", "a0", "b0", "k")
    per = {key: k[key] for key in names}
    per.update(zip(("c1", "c2", "c3"), slope, strict=True))
    out = np.empty((len(EXTREMES), m))
    # tiles of designs x angles: a few hundred designs (the inner loops run over them, and
    # vectorise) by as many angles as make 2 MiB of arctangents; each design's running
    # extremes are folded over its angles' tiles
    points = 4 * COMPILED_BLOCK
    designs = min(m, max(_MIN_DESIGNS, points // th.size))
    angles = max(1, points // designs)
    r = np.empty(2 * designs * min(angles, th.size))
    acc = np.empty((len(EXTREMES), designs))
    for lo in range(0, m, designs):
        hi = min(m, lo + designs)
        x = {key: a if np.ndim(a) == 0 else a[lo:hi] for key, a in per.items()}
        run = acc if hi - lo == designs else np.empty((len(EXTREMES), hi - lo))
        run[:] = _START
        for a0 in range(0, th.size, angles):
            a1 = min(th.size, a0 + angles)
            e = r[: 2 * (a1 - a0) * (hi - lo)].reshape(2, a1 - a0, hi - lo)  # C-contiguous
            tj = tv[a0:a1]
            fused.atan_arguments_grid(tj, x["ca"], x["sa"], x["ca2"], x["sa2"], x["gamma"], *e)
            np.arctan(e, out=e)
            fused.extremes_grid(
                tj, vt[a0:a1], e[0], e[1], x["ca"], x["sa"], x["ca2"], x["sa2"], x["h"],
                x["a0"], x["b0"], x["k"], x["c1"], x["c2"], x["c3"],
                *(v[a0:a1] for v in u), linear, run,
            )  # fmt: skip
        out[:, lo:hi] = run
    return dict(zip(EXTREMES, out, strict=True))
