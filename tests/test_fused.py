"""Compiled loops (numba) against the numpy fallback, and both against independent formulas.

Each drive's fused kinematics runs the same point formulas either as numpy operations on
blocks or compiled into loops (:mod:`rotorkin.core.fused`). Here, for random designs and
angles (hypothesis), the two paths agree to 1e-14 relative to each value, and both
agree with the drives' sin/cos closed forms written independently of the half-angle
rearrangement (within 1e-12 of each derivative's size). The choice of the path (option,
``$ROTORKIN_KERNEL``, automatic by size) and its errors are checked, and the studies and
sweeps are run through both paths.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rotorkin.core import fused
from rotorkin.core.errors import ParameterError
from rotorkin.core.motion import compose
from rotorkin.drives.eccentric_cam import kinematics as ec
from rotorkin.drives.eccentric_cam import kinematics_fused as ec_fused
from rotorkin.drives.guide_bar import kinematics as gb
from rotorkin.drives.guide_bar import kinematics_fused as gb_fused
from rotorkin.drives.noncircular_gears import kinematics as ng
from rotorkin.drives.noncircular_gears import kinematics_fused as ng_fused
from rotorkin.drives.rhomboid_cam import kinematics as rc
from rotorkin.drives.rhomboid_cam import kinematics_fused as rc_fused
from rotorkin.drives.wobble_cam import fast as wc_fast
from rotorkin.drives.wobble_cam import kinematics as wc
from rotorkin.drives.wobble_cam import kinematics_fused as wc_fused
from rotorkin.drives.wobble_cam.fast import rotor_kinematics

SETTINGS = settings(max_examples=25, deadline=None)
FUSED_RTOL = 1e-14
REF_TOL = 1e-12


def same(a, b):
    """Compiled vs numpy: ``|a - b| <= 1e-14 |b|`` per value (zeros must match exactly)."""
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape
    np.testing.assert_allclose(a, b, rtol=FUSED_RTOL, atol=0.0)


def close(got, ref, scales=None):
    """Against an independent formula: within 1e-12 of each derivative order's largest size.

    ``scales``: the size of each order's terms where they may cancel (default: the values').
    """
    got, ref = np.asarray(got), np.asarray(ref)
    assert got.shape == ref.shape
    for i in range(got.shape[0]):
        scale = max(1e-300, float(np.max(np.abs(ref[i]), initial=0.0)))
        if scales is not None:
            scale = max(scale, float(np.max(scales[i])))
        np.testing.assert_allclose(got[i], ref[i], rtol=0, atol=REF_TOL * scale, err_msg=str(i))


def both(fn):
    """``fn(kernel)`` on the numpy path and the compiled path, compared; the numpy result."""
    a, b = fn("numpy"), fn("numba")
    same(b, a)
    return a


shapes = st.sampled_from([(), (1,), (37,), (3, 5), (2, 3, 4)])


def angles(draw, shape, lo=-40.0, hi=40.0):
    """Angles of ``shape`` from a drawn seed (uniform in [lo, hi))."""
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    return rng.uniform(lo, hi, shape)


# --------------------------------------------------------------------------------------------
# wobble cam
# --------------------------------------------------------------------------------------------
def wobble_reference(tilt, alpha, n, theta):
    """Phi_k = theta + E(n theta -+ alpha/2), E from projected_angle (sin/cos, atan2)."""
    out = []
    for s in (-1.0, 1.0):
        e = wc.projected_angle(tilt, n * theta + s * 0.5 * alpha)
        q = compose(e, (n * theta, n, 0.0, 0.0))
        out.append((theta + q[0], 1.0 + q[1], q[2], q[3]))
    shape = np.broadcast_shapes(*(np.shape(v) for k in out for v in k))
    return np.stack([np.stack([np.broadcast_to(out[r][i], shape) for r in (0, 1)])
                     for i in range(4)])  # fmt: skip


@st.composite
def wobble_inputs(draw):
    shape = draw(shapes)
    tilt = draw(st.floats(0.05, 1.3))
    alpha = draw(st.floats(0.3, 2.8))
    n = draw(st.sampled_from([-2.0, -1.5, -0.5, 1.0]))
    return tilt, alpha, n, angles(draw, shape)


@SETTINGS
@given(wobble_inputs())
def test_wobble_compiled_equals_numpy_and_reference(args):
    tilt, alpha, n, theta = args
    rot = both(lambda k: rotor_kinematics(tilt, alpha, n, theta, kernel=k)[0])
    close(rot, wobble_reference(tilt, alpha, n, theta))
    ch = both(lambda k: rotor_kinematics(tilt, alpha, n, theta, chamber=(0.2, 4), kernel=k)[1])
    close(ch, np.stack(wc.chamber_angles(0.2, rot[0, 1] - rot[0, 0], pistons=4)))


def test_wobble_corrected_spin_law_and_designs_per_point():
    """Any spin law (four arrays) and tilt, roller axis angle, width varying per point."""
    rng = np.random.default_rng(3)
    theta = rng.uniform(-7, 7, (40, 1)) + np.zeros((40, 9))
    law = (-2 * theta + 0.1 * np.sin(3 * theta), -2 + 0.3 * np.cos(3 * theta),
           -0.9 * np.sin(3 * theta), -2.7 * np.cos(3 * theta))  # fmt: skip
    tilt, alpha, width = (
        rng.uniform(0.2, 1.2, 9),
        rng.uniform(1, 2, (40, 1)),
        rng.uniform(0, 0.3, 9),
    )
    rot = both(lambda k: rotor_kinematics(tilt, alpha, law, theta, kernel=k)[0])
    ch = both(lambda k: rotor_kinematics(tilt, alpha, law, theta, chamber=(width, 4), kernel=k)[1])
    for r, s in enumerate((-1.0, 1.0)):
        e = wc.projected_angle(tilt, law[0] + s * 0.5 * alpha)
        q = compose(e, law)
        close(rot[:, r], np.stack([theta + q[0], 1.0 + q[1], q[2], q[3]]))
    close(ch, np.stack(wc.chamber_angles(width, rot[0, 1] - rot[0, 0], pistons=4)))


def test_wobble_extremes_refuse_mismatched_designs():
    theta = np.linspace(0.0, 1.0, 5)
    with pytest.raises(ValueError, match=r"plate_tilt \(3\) and roller_axis_angle \(2\)"):
        wc_fast.rotor_extremes(np.full(3, 0.5), np.full(2, 1.5), -2.0, theta)
    with pytest.raises(ValueError, match=r"theta \(0\) at least one angle"):
        wc_fast.rotor_extremes(0.5, 1.5, -2.0, np.array([]))


def _bits(values: dict) -> dict:
    return {k: np.asarray(v).view(np.int64) for k, v in values.items()}


@pytest.mark.parametrize("law", ["linear", "corrected"])
@pytest.mark.parametrize(("designs", "angles"), [(1, 360), (7, 360), (400, 360), (70, 5000)])
def test_wobble_extremes_equal_the_reduced_curves(law, designs, angles):
    """A sweep's per-design peaks, reduced as they are evaluated (compiled), equal the
    curves' reductions (numpy) bit for bit, NaN designs included, and the independent
    sin/cos forms to 1e-12; 400 designs at 360 angles span two tiles of designs, 70
    designs at 5000 angles two tiles of designs by three of angles."""
    rng = np.random.default_rng(designs)
    theta = np.linspace(0.0, 2.0 * np.pi, angles, endpoint=False)
    spin = -2.0 if law == "linear" else wc.spin_angle(-2.0, (0.01,), (0.02,), theta)
    tilt, alpha = rng.uniform(0.3, 1.2, designs), rng.uniform(1.0, 2.5, designs)
    if designs > 1:
        tilt[designs // 2] = np.nan  # a design the sweep could not evaluate
    for a in (alpha, alpha[0]):  # per design, or one roller axis angle for all
        got = wc_fast.rotor_extremes(tilt, a, spin, theta, kernel="numba")
        ref = wc_fast.rotor_extremes(tilt, a, spin, theta, kernel="numpy")
        assert list(got) == list(wc_fast.EXTREMES)
        for key, bits in _bits(ref).items():
            np.testing.assert_array_equal(_bits(got)[key], bits, err_msg=key)
    law4 = (spin * theta, spin, 0.0, 0.0) if law == "linear" else spin
    rot = []
    for s in (-1.0, 1.0):  # Phi_k = theta + E(varphi -+ alpha/2), E by sin/cos and atan2
        e = wc.projected_angle(tilt[:, None], law4[0] + s * 0.5 * alpha[:, None])
        q = compose(e, law4)
        rot.append(np.stack(np.broadcast_arrays(theta + q[0], 1.0 + q[1], q[2], q[3])))
    rot = np.stack(rot, axis=1)  # (4, 2, designs, angles)
    with np.errstate(invalid="ignore"):
        ref = {"acc": np.abs(rot[2]).max(axis=(0, 2)), "jerk": np.abs(rot[3]).max(axis=(0, 2)),
               "r_min": rot[1].min(axis=(0, 2)), "r_max": rot[1].max(axis=(0, 2)),
               "s_min": (rot[0, 1] - rot[0, 0]).min(axis=1),
               "s_max": (rot[0, 1] - rot[0, 0]).max(axis=1)}  # fmt: skip
    got = wc_fast.rotor_extremes(tilt, alpha, spin, theta, kernel="numba")
    for key, value in ref.items():
        assert np.array_equal(np.isnan(got[key]), np.isnan(value)), key
        ok = ~np.isnan(value)
        scale = np.max(np.abs(value[ok]))
        np.testing.assert_allclose(got[key][ok], value[ok], rtol=0, atol=REF_TOL * scale,
                                   err_msg=key)  # fmt: skip


# --------------------------------------------------------------------------------------------
# eccentric cam
# --------------------------------------------------------------------------------------------
@st.composite
def eccentric_inputs(draw):
    shape = draw(shapes)
    e = draw(st.floats(0.001, 0.05))
    rc_ = draw(st.one_of(st.just(np.inf), st.floats(1.02, 20.0).map(lambda k: k * e)))
    return rc_, e, angles(draw, shape)


@SETTINGS
@given(eccentric_inputs())
def test_eccentric_compiled_equals_numpy_and_reference(args):
    rc_, e, beta = args
    got = both(lambda k: ec_fused.travels_fused(rc_, e, beta, kernel=k))
    h = ec.harmonic_travel(e, beta)
    a = ec.additional_travel(rc_, e, beta)
    close(got, np.stack([np.stack([ai + hi, ai - hi]) for ai, hi in zip(a, h, strict=True)]))


# --------------------------------------------------------------------------------------------
# guide bar
# --------------------------------------------------------------------------------------------
def guide_reference(lam, u, i12, phase, driver, theta):
    """``f(x_k)/(u i12^n)`` from the sin/cos forms (guide_angle, crank_angle via angle_near)."""
    t = np.asarray(theta, dtype=float) / i12 + 0.0 * np.asarray(lam)  # the designs' shape
    x = np.stack(np.broadcast_arrays(t, t + phase))
    f = gb.driven_angle(lam, driver, x)
    return np.stack([fn / (u * i12**n) for n, fn in enumerate(f)])


@st.composite
def guide_inputs(draw):
    shape = draw(shapes)
    lam = draw(st.floats(0.05, 0.95))
    u = draw(st.floats(0.5, 4.0))
    i12 = draw(st.floats(0.5, 3.0))
    phase = draw(st.floats(0.2, 6.0))
    driver = draw(st.sampled_from(["crank", "guide"]))
    return lam, u, i12, phase, driver, angles(draw, shape)


@SETTINGS
@given(guide_inputs())
def test_guide_bar_compiled_equals_numpy_and_reference(args):
    lam, u, i12, phase, driver, theta = args
    flag = driver == "guide"
    got = both(lambda k: gb_fused.impellers_fused(lam, u, i12, phase, flag, theta, kernel=k))
    close(got, guide_reference(lam, u, i12, phase, driver, theta))
    rates = both(
        lambda k: gb_fused.impellers_fused(lam, u, i12, phase, flag, theta, angles=False, kernel=k)
    )
    np.testing.assert_array_equal(rates, got[1:])


def test_guide_bar_drivers_per_design():
    """An array of drivers (both kinds in one call) picks each design's law."""
    rng = np.random.default_rng(5)
    lam = rng.uniform(0.1, 0.9, (6, 1))
    driver = np.array(["crank", "guide", "guide", "crank", "guide", "crank"]).reshape(6, 1)
    theta = rng.uniform(-10, 10, 300)
    params = gb.GuideBar(lam, 2.0, 1.5, 2.5, driver)
    for kernel in ("numpy", "numba"):
        with pytest.MonkeyPatch.context() as mp:
            mp.setenv(fused.KERNEL_ENV, kernel)
            got = np.stack(gb.impeller_angles(params, theta))
        close(got, guide_reference(lam, 2.0, 1.5, 2.5, driver, theta))


# --------------------------------------------------------------------------------------------
# non-circular gears
# --------------------------------------------------------------------------------------------
@st.composite
def noncircular_inputs(draw):
    shape = draw(shapes)
    n = draw(st.integers(1, 4))
    m = draw(st.integers(1, 4))
    limit = float(ng.eccentricity_limit(n, m))
    e = draw(st.floats(0.0, 0.95)) * min(limit, 0.6)
    phase = draw(st.one_of(st.none(), st.floats(0.1, 3.0)))
    return ng.NoncircularGears(n, m, e, 0.1, phase), angles(draw, shape)


@SETTINGS
@given(noncircular_inputs())
def test_noncircular_compiled_equals_numpy_and_reference(args):
    params, theta = args

    def motion(kernel):
        with pytest.MonkeyPatch.context() as mp:
            mp.setenv(fused.KERNEL_ENV, kernel)
            mo = ng.motion(params, theta)
        return np.stack([mo.q, mo.dq, mo.d2q, mo.d3q])

    got = both(motion)
    sigma = ng._phase(params)
    one = ng.driven_angle(params, theta)
    two = ng.driven_angle(params, theta + sigma)
    offset = ng.driven_angle(params, sigma)[0]
    ref = np.stack([np.stack(np.broadcast_arrays(a, b))
                    for a, b in zip(one, (two[0] - offset, *two[1:]), strict=True)])  # fmt: skip
    close(got, ref)


# --------------------------------------------------------------------------------------------
# rhomboid cam
# --------------------------------------------------------------------------------------------
def psi_reference(psi_min, a, b, alpha):
    """eq. 13-15 term by term with cos/sin of each harmonic's own argument."""
    a1, b1 = rc.first_harmonic(psi_min, a, b)
    terms = [(1, a1, b1)] + [(2 * j + 3, ak, bk) for j, (ak, bk) in
                             enumerate(zip(np.pad(a, (0, max(0, len(b) - len(a)))),
                                           np.pad(b, (0, max(0, len(a) - len(b)))),
                                           strict=True))]  # fmt: skip
    out = [np.pi / 2 + 0.0 * alpha, 0.0 * alpha, 0.0 * alpha, 0.0 * alpha]
    for k, ak, bk in terms:
        w = 2.0 * k
        c, s = np.cos(w * alpha), np.sin(w * alpha)
        for order in range(4):
            # d^n/dx^n (a cos wx + b sin wx): rotate (a, b) by n quarter turns, times w^n
            ca, cb = [(ak, bk), (bk, -ak), (-ak, -bk), (-bk, ak)][order]
            out[order] = out[order] + w**order * (ca * c + cb * s)
    return np.stack(np.broadcast_arrays(*out))


@st.composite
def rhomboid_inputs(draw):
    shape = draw(shapes)
    psi_min = draw(st.floats(0.3, 1.5))
    a = draw(st.lists(st.floats(-0.05, 0.05), max_size=4))
    b = draw(st.lists(st.floats(-0.05, 0.05), max_size=3))
    return psi_min, tuple(a), tuple(b), angles(draw, shape, -10.0, 10.0)


@SETTINGS
@given(rhomboid_inputs())
def test_rhomboid_compiled_equals_numpy_and_reference(args):
    psi_min, a, b, alpha = args
    _, ak, bk = rc._higher(a, b)
    a1, b1 = rc.first_harmonic(psi_min, a, b)
    psi = both(lambda k: rc_fused.law_fused(a1, b1, ak, bk, alpha, kernel=k))
    # the harmonics' terms may cancel: tolerance from their sizes (sum |coefficient| (2k)^n)
    scales = [rc._scale(psi_min, a, b, order) for order in range(4)]
    close(psi, psi_reference(psi_min, a, b, alpha), scales)
    blades = both(lambda k: rc_fused.law_fused(a1, b1, ak, bk, alpha, blades=True, kernel=k))
    half = 0.5 * psi
    base = np.stack(np.broadcast_arrays(alpha, 1.0, 0.0, 0.0, psi[0]))[:4]
    close(blades[:, 0], base + half, scales)
    close(blades[:, 1], base - half, scales)


# --------------------------------------------------------------------------------------------
# many blocks, threads, strides: the same numbers
# --------------------------------------------------------------------------------------------
def test_large_inputs_over_blocks_and_threads_equal_the_numpy_path():
    """Several blocks with a ragged end, 1 and 2 threads, a strided view: same values."""
    size = 2 * fused.COMPILED_BLOCK + 3 * fused.BLOCK + 77  # 2 threads: 2 ragged ranges
    assert size >= fused.MIN_PARALLEL
    theta = np.random.default_rng(11).uniform(-9, 9, 2 * size)[::2]  # a strided view
    calls = [
        lambda k, t: rotor_kinematics(0.6, 1.4, -1.5, theta, chamber=(0.2, 4), kernel=k, threads=t)[
            0
        ],  # fmt: skip
        lambda k, t: ec_fused.travels_fused(0.08, 0.04, theta, kernel=k, threads=t),
        lambda k, t: gb_fused.impellers_fused(
            0.5, 2.0, 2.0, np.pi, False, theta, kernel=k, threads=t
        ),  # fmt: skip
        lambda k, t: rc_fused.law_fused(
            0.4, 0.0, np.array([0.02]), np.array([0.01]), theta, blades=True, kernel=k, threads=t
        ),  # fmt: skip
        lambda k, t: ng_fused.motion_fused(
            2, 2, 0.2, 0.4, 0.6, 0.5, 0.7, 0.1, theta, kernel=k, threads=t
        ),  # fmt: skip
    ]
    for call in calls:
        ref = call("numpy", 1)
        for kernel in ("numpy", "numba"):
            for threads in (1, 2):
                same(call(kernel, threads), ref)


# --------------------------------------------------------------------------------------------
# choosing the path
# --------------------------------------------------------------------------------------------
def test_kernel_choice_from_option_and_environment(monkeypatch):
    monkeypatch.delenv(fused.KERNEL_ENV, raising=False)
    assert fused.kernel_choice() == "auto"
    monkeypatch.setenv(fused.KERNEL_ENV, "numpy")
    assert fused.kernel_choice() == "numpy"
    assert not fused.use_compiled(10**7)
    assert fused.kernel_choice("numba") == "numba"  # the option wins over the environment
    monkeypatch.setenv(fused.KERNEL_ENV, "fortran")
    with pytest.raises(ParameterError, match=r"ROTORKIN_KERNEL.*'fortran'.*'auto', 'numpy'"):
        fused.kernel_choice()
    with pytest.raises(ParameterError, match=r"kernel.*'gpu'"):
        ec_fused.travels_fused(0.08, 0.04, np.zeros(3), kernel="gpu")


AUTO_SCRIPT = """
import sys
import numpy as np
from rotorkin.core import fused
from rotorkin.drives.eccentric_cam import kinematics as ec
ec.travels(0.08, 0.04, np.linspace(0, 6, fused.AUTO_MIN_POINTS - 1))
print("numba" in sys.modules)
ec.travels(0.08, 0.04, np.linspace(0, 6, fused.AUTO_MIN_POINTS))
print("numba" in sys.modules, fused.use_compiled(10))
"""


def test_auto_imports_numba_for_large_inputs_only():
    """``auto``: a small evaluation alone leaves numba unloaded; a large one loads it, and
    from then on every evaluation runs the compiled loops."""
    import os
    import subprocess
    import sys

    env = {k: v for k, v in os.environ.items() if k != fused.KERNEL_ENV}
    out = subprocess.run([sys.executable, "-c", AUTO_SCRIPT], env=env, capture_output=True,
                         text=True, check=True).stdout.split()  # fmt: skip
    assert out == ["False", "True", "True"]


PREFER_SCRIPT = """
import sys
from rotorkin.core import fused
print(fused.prefer_compiled(fused.AUTO_MIN_POINTS - 1), "numba" in sys.modules)
print(fused.prefer_compiled(fused.AUTO_MIN_POINTS), "numba" in sys.modules, fused.use_compiled(8))
"""


@pytest.mark.parametrize("choice", ["auto", "numpy"])
def test_a_large_batch_loads_the_compiled_loops_up_front(choice):
    """``prefer_compiled``: a batch of evaluations large in all (a sweep's blocks) loads
    numba before its first evaluation with ``auto``, never with ``numpy``."""
    import os
    import subprocess
    import sys

    env = {**os.environ, fused.KERNEL_ENV: choice}
    out = subprocess.run([sys.executable, "-c", PREFER_SCRIPT], env=env, capture_output=True,
                         text=True, check=True).stdout.split()  # fmt: skip
    if choice == "auto":
        assert out == ["False", "False", "True", "True", "True"]
    else:
        assert out == ["False", "False", "False", "False", "False"]


def test_auto_and_forced_paths_call_the_compiled_loops(monkeypatch):
    monkeypatch.delenv(fused.KERNEL_ENV, raising=False)
    assert fused.numba_available()
    calls = []
    loop = ec_fused._travel_loop
    monkeypatch.setattr(ec_fused, "_travel_loop", lambda *a: calls.append(1) or loop(*a))
    ec.travels(0.08, 0.04, np.linspace(0, 6, fused.AUTO_MIN_POINTS))
    assert calls
    calls.clear()
    monkeypatch.setenv(fused.KERNEL_ENV, "numpy")
    ec.travels(0.08, 0.04, np.linspace(0, 6, fused.AUTO_MIN_POINTS))
    assert not calls
    monkeypatch.setenv(fused.KERNEL_ENV, "numba")
    ec.travels(0.08, 0.04, np.linspace(0, 6, 5))
    assert calls


def test_without_numba_auto_falls_back_and_numba_is_refused(monkeypatch):
    """numba missing (simulated): ``auto`` gives the numpy path's values, ``numba`` one line."""
    theta = np.linspace(0, 6, fused.AUTO_MIN_POINTS + 10)
    ref = ec_fused.travels_fused(0.08, 0.04, theta, kernel="numpy")
    monkeypatch.setattr(fused, "_NUMBA", False)
    monkeypatch.delenv(fused.KERNEL_ENV, raising=False)
    assert not fused.numba_available()
    np.testing.assert_array_equal(ec_fused.travels_fused(0.08, 0.04, theta), ref)
    with pytest.raises(ParameterError, match=r"kernel = 'numba'.*numba installed"):
        ec_fused.travels_fused(0.08, 0.04, theta, kernel="numba")


def test_formulas_run_as_plain_python_on_numbers():
    """The point formulas are ordinary functions: on floats they give the numpy values."""
    t = 0.37
    got = ec_fused.travel_point(t, 0.08, 0.04)
    ref = ec_fused.travel_point(np.array([t]), 0.08, 0.04)
    np.testing.assert_array_equal(np.array(got), np.array(ref)[:, 0])
    assert wc_fused.spin_trig(0.0, 1.0, 0.0, 2.0, 0.0) == (0.0, 1.0, 0.0, 1.0)
    assert fused.at(3.0, 5) == 3.0 and fused.at(np.arange(4.0), 2) == 2.0
    assert fused.select(True, 1.0, 2.0) == 1.0


def test_out_arrays_are_checked_and_written():
    theta = np.linspace(0, 3, 50)
    out = np.full((4, 2, 50), np.nan)
    got = ec_fused.travels_fused(0.08, 0.04, theta, out=out)
    assert np.shares_memory(got, out) and np.all(np.isfinite(out))
    with pytest.raises(ValueError, match="out"):
        ec_fused.travels_fused(0.08, 0.04, theta, out=np.empty((4, 2, 49)))
    res = ng_fused.motion_fused(2, 2, 0.2, 0.4, 0.6, 0.5, 0.7, 0.1, theta, out=np.empty((4, 2, 50)))
    assert res.shape == (4, 2, 50)
