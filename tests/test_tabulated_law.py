"""Tabulated drive law: Fourier series, its fit to tables and CSV files, and the refusals."""

from __future__ import annotations

import numpy as np
import pytest

from rotorkin.core.errors import ParameterError
from rotorkin.drives.tabulated import law as tl
from rotorkin.drives.wobble_cam import kinematics as wc

TWO_PI = 2.0 * np.pi

# q_i = c_i theta + sum_k A cos(k theta) + B sin(k theta): (c, [(k, A, B), ...])
ANALYTIC = (
    (1.5, [(1, 0.30, -0.20), (2, 0.05, 0.10), (5, -0.01, 0.02)]),
    (-0.5, [(1, -0.10, 0.25), (3, 0.04, 0.0), (7, 0.0, -0.005)]),
)


def analytic(theta):
    """Exact (4, 2, ...) angles and derivatives 1..3 of the law ANALYTIC."""
    theta = np.asarray(theta, dtype=float)
    out = np.zeros((4, 2) + theta.shape)
    for i, (c, terms) in enumerate(ANALYTIC):
        out[0, i] = c * theta + 0.4 * (i + 1)
        out[1, i] = c
        for k, a, b in terms:
            x = k * theta
            cs, sn = np.cos(x), np.sin(x)
            out[0, i] += a * cs + b * sn
            out[1, i] += k * (-a * sn + b * cs)
            out[2, i] += -(k**2) * (a * cs + b * sn)
            out[3, i] += k**3 * (a * sn - b * cs)
    return out


def stacked(m):
    return np.stack([m.q, m.dq, m.d2q, m.d3q])


def wobble():
    return wc.WobbleCam(plate_tilt=np.radians(45.0), roller_axis_angle=np.radians(90.0))


def assert_one_line(exc: ParameterError, *parts: str):
    text = str(exc)
    assert "\n" not in text
    assert exc.name == "drive.table"
    assert text.startswith("drive.table = ")
    for part in parts:
        assert part in text, text


# --------------------------------------------------------------------------------------------
# tables
# --------------------------------------------------------------------------------------------
def test_analytic_table_reproduces_angles_and_derivatives():
    theta = np.linspace(0.0, TWO_PI, 721)
    q = analytic(theta)[0]
    law = tl.from_table(theta, *q)
    assert law.period == pytest.approx(TWO_PI, rel=1e-15)
    np.testing.assert_allclose(law.mean_ratio, [1.5, -0.5], rtol=1e-12)
    x = np.random.default_rng(7).uniform(-3.0, 3.0 + TWO_PI, 2000)
    exact = analytic(x)
    got = stacked(law(x))
    for order in range(4):
        scale = np.abs(exact[order]).max()
        assert np.abs(got[order] - exact[order]).max() <= 1e-9 * scale, order
    # exact at the samples
    np.testing.assert_allclose(law(theta).q, q, rtol=0, atol=1e-13)


def test_error_estimate_bounds_the_true_error():
    theta = np.linspace(0.0, TWO_PI, 721)
    q = analytic(theta)[0]
    law = tl.from_table(theta, *q)
    est = tl.fit_error(theta, *q)
    assert est.method == "fit from every 2nd sample"
    x = np.random.default_rng(8).uniform(0.0, TWO_PI, 3000)
    err = np.abs(stacked(law(x)) - analytic(x)).max(axis=2)
    for order in range(4):
        assert np.all(err[order] <= est[order]), order
        assert np.all(est[order] < 1e-9 * np.abs(analytic(x)[order]).max()), order


def bumpy(t):
    """(4, 2, ...) exact values of a law with a geometric spectrum (ratio 0.64 per harmonic).

    ``g(t) = 1 / (1.1 - cos t)``, a narrow peak at t = 0;
    q1 = 2 t + 0.3 g(t - 2.5), q2 = 0.7 cos 2t + 0.2 g(t - 1).
    """

    def g(u):
        c, s = np.cos(u), np.sin(u)
        d = 1.1 - c
        return np.stack(
            [
                1.0 / d,
                -s / d**2,
                -c / d**2 + 2.0 * s**2 / d**3,
                s / d**2 + 6.0 * s * c / d**3 - 6.0 * s**3 / d**4,
            ]
        )

    g1, g2 = 0.3 * g(t - 2.5), 0.2 * g(t - 1.0)
    c2, s2 = np.cos(2.0 * t), np.sin(2.0 * t)
    q1 = g1 + np.stack([2.0 * t, 2.0 + 0.0 * t, 0.0 * t, 0.0 * t])
    q2 = g2 + 0.7 * np.stack([c2, -2.0 * s2, -4.0 * c2, 8.0 * s2])
    return np.stack([q1, q2], axis=1)


def test_bumpy_law_derivatives():
    """The closed forms of ``bumpy`` against central differences."""
    t = np.linspace(0.0, TWO_PI, 401)
    h = 1e-5
    for order in range(1, 4):
        fd = (bumpy(t + h)[order - 1] - bumpy(t - h)[order - 1]) / (2.0 * h)
        assert np.abs(fd - bumpy(t)[order]).max() < 1e-6 * np.abs(bumpy(t)[order]).max()


@pytest.mark.parametrize("rows", [25, 33, 49, 65, 97])
def test_error_estimate_bounds_an_under_resolved_fit(rows):
    """On coarse tables the error is far above roundoff: the bound is tested for real."""
    theta = np.linspace(0.0, TWO_PI, rows)
    q = bumpy(theta)[0]
    law = tl.from_table(theta, *q)
    est = tl.fit_error(theta, *q)
    x = np.random.default_rng(rows).uniform(0.0, TWO_PI, 4000)
    err = np.abs(stacked(law(x)) - bumpy(x)).max(axis=2)
    assert err[0].max() > 1e-10
    assert np.all(err <= est.array)
    assert np.all(est.array < 1e5 * err)  # an over-estimate, not a useless one


def test_error_estimate_on_a_prime_number_of_intervals():
    theta = np.linspace(0.0, TWO_PI, 42)  # 41 intervals
    q = analytic(theta)[0]
    est = tl.fit_error(theta, *q)
    assert est.method == "fit from half the harmonics"
    law = tl.from_table(theta, *q)
    x = np.linspace(0.0, TWO_PI, 1001)
    err = np.abs(stacked(law(x)) - analytic(x)).max(axis=2)
    assert np.all(err <= est.array)


def test_one_quarter_turn_period():
    theta = np.linspace(0.0, TWO_PI / 4.0, 181)

    def exact(t):
        return np.stack([0.5 * t + 0.2 * np.sin(4.0 * t), -t + 0.1 * np.cos(8.0 * t + 1.0)])

    law = tl.from_table(theta, *exact(theta))
    assert law.turn_divisions == 4
    assert law.period == pytest.approx(TWO_PI / 4.0, rel=1e-15)
    x = np.linspace(-1.0, 7.0, 999)
    np.testing.assert_allclose(law(x).q, exact(x), rtol=0, atol=1e-12)
    m = law(x)
    np.testing.assert_allclose(m.dq[0], 0.5 + 0.8 * np.cos(4.0 * x), atol=1e-11)


def test_span_of_100_deg_refused():
    theta = np.radians(np.linspace(0.0, 100.0, 101))
    with pytest.raises(ParameterError) as info:
        tl.from_table(theta, theta, 2.0 * theta)
    assert_one_line(info.value, "span of 100 deg", "360 deg / k", "both end points included")


def test_table_without_its_end_point_refused():
    theta = np.radians(np.arange(0.0, 360.0, 1.0))  # 0..359 deg
    with pytest.raises(ParameterError) as info:
        tl.from_table(theta, theta, np.sin(theta))
    assert_one_line(info.value, "span of 359 deg")


def test_wobble_cam_rotors():
    params = wobble()
    theta = np.linspace(0.0, TWO_PI, 721)
    law = tl.from_table(theta, *wc.motion(params, theta).q)
    np.testing.assert_allclose(law.mean_ratio, [-1.0, -1.0], rtol=1e-12)
    x = np.random.default_rng(3).uniform(0.0, TWO_PI, 5000)
    got = stacked(law(x, members=("rotor 1", "rotor 2")))
    ref = stacked(wc.motion(params, x))
    # measured (relative to the largest value of each order): q 2.5e-16, dq 5e-14,
    # d2q 2e-12, d3q 2e-11; tolerances leave a margin of about 50
    for order, tol in enumerate((1e-9, 1e-11, 1e-10, 1e-9)):
        scale = np.abs(ref[order]).max()
        assert np.abs(got[order] - ref[order]).max() <= tol * scale, order
    est = tl.fit_error(theta, *wc.motion(params, theta).q)
    err = np.abs(got - ref).max(axis=2)
    assert np.all(err <= est.array)


def test_wobble_cam_relative_angle_extremes():
    params = wobble()
    theta = np.linspace(0.0, TWO_PI, 721)
    law = tl.from_table(theta, *wc.motion(params, theta).q)
    x = np.linspace(0.0, TWO_PI, 20001)
    rel = law(x).relative[0]
    found = []
    for pick in (np.argmax, np.argmin):
        t = x[pick(rel)]
        for _ in range(6):  # Newton on the slope of the relative angle
            _, d1, d2, _ = law(t).relative
            t = t - d1 / d2
        found.append(float(law(t).relative[0]))
    hi, lo = wc.slider_angle_extremes(params.plate_tilt, params.roller_axis_angle)
    assert found[0] == pytest.approx(float(hi), abs=1e-9)
    assert found[1] == pytest.approx(float(lo), abs=1e-9)


def test_low_pass_fit_is_the_least_squares_fit():
    rng = np.random.default_rng(11)
    theta = np.linspace(0.0, TWO_PI, 361)
    clean = analytic(theta)[0]
    noisy = clean + 1e-3 * rng.standard_normal(clean.shape)
    law = tl.from_table(theta, *noisy, harmonics=8)
    assert law.harmonics == 8
    # least squares of a trend and 8 harmonics over the distinct rows
    t = theta[:-1]
    k = np.arange(1, 9)
    design = np.column_stack([np.ones_like(t), t, np.cos(np.outer(t, k)), np.sin(np.outer(t, k))])
    for i in range(2):
        coef = np.linalg.lstsq(design, noisy[i, :-1], rcond=None)[0]
        assert law.offset[i] == pytest.approx(coef[0], abs=1e-12)
        assert law.mean_ratio[i] == pytest.approx(coef[1], abs=1e-12)
        np.testing.assert_allclose(law.cos[i], coef[2:10], atol=1e-12)
        np.testing.assert_allclose(law.sin[i], coef[10:], atol=1e-12)
    # the filter takes out most of the noise
    x = np.linspace(0.0, TWO_PI, 777)
    assert np.abs(law(x).q - analytic(x)[0]).max() < 5e-4
    est = tl.fit_error(theta, *noisy, harmonics=8)
    assert np.all(est.q > 1e-3)  # the noise counts as error of the angles


def test_start_away_from_zero():
    theta = np.linspace(np.radians(3600.0), np.radians(3960.0), 361)
    q = analytic(theta)[0]
    law = tl.from_table(theta, *q)
    x = np.random.default_rng(2).uniform(0.0, 70.0, 500)
    np.testing.assert_allclose(stacked(law(x)), analytic(x), rtol=0, atol=1e-9 * 50)


def test_harmonics_out_of_range_refused():
    theta = np.linspace(0.0, TWO_PI, 21)
    q = analytic(theta)[0]
    for bad in (0, 11, 2.5, "three", True):
        with pytest.raises(ParameterError) as info:
            tl.from_table(theta, *q, harmonics=bad)
        assert "\n" not in str(info.value)
        assert info.value.name == "drive.harmonics"


# --------------------------------------------------------------------------------------------
# bad tables
# --------------------------------------------------------------------------------------------
def _good(rows=73):
    theta = np.linspace(0.0, TWO_PI, rows)
    return [theta, *analytic(theta)[0]]


def _with(index, row, value, rows=73):
    cols = _good(rows)
    cols[index] = cols[index].copy()
    cols[index][row] = value
    return cols


def _kinked():
    theta, q1, q2 = _good(721)
    largest = np.abs(np.diff(q1)).max() / (theta[1] - theta[0])
    # a slope jump of 3 % of the largest slope across the ends, smooth inside
    return [theta, q1 + 0.03 * largest * theta**2 / (2.0 * TWO_PI), q2]


def _wrapped():
    theta, q1, q2 = _good(721)
    return [theta, np.mod(q1 + np.pi, TWO_PI) - np.pi, q2]


BAD_TABLES = {
    "too few rows": (lambda: _good(7), ["7 rows", "at least 8 rows"]),
    "NaN": (lambda: _with(1, 5, np.nan), ["row 6", "q1 = nan", "finite"]),
    "inf": (lambda: _with(0, 9, np.inf), ["row 10", "theta = inf"]),
    "decreasing row": (
        lambda: _with(0, 4, 0.01),
        ["row 5", "theta = 0.572958 deg after 15 deg", "strictly increasing"],
    ),
    "wrong span": (
        lambda: [np.linspace(0.0, 1.7, 50), np.zeros(50), np.zeros(50)],
        ["span of 97.4", "360 deg / k"],
    ),
    "kinked joint": (_kinked, ["q1", "slope jumps", "2.95 % of its largest slope", "periodic"]),
    "non-uniform": (lambda: _with(0, 30, _good()[0][30] + 1e-4), ["row 31", "uniform steps"]),
    "wrapped angles": (_wrapped, ["q1", "not wrapped", "numpy.unwrap"]),
    "theta squared": (
        lambda: [np.linspace(0.0, TWO_PI, 361), np.linspace(0.0, TWO_PI, 361) ** 2, np.zeros(361)],
        ["q1", "100 % of its largest slope"],
    ),
    "unequal columns": (lambda: [*_good()[:2], np.zeros(5)], ["equal length"]),
    "too many rows": (
        lambda: [np.linspace(0.0, TWO_PI, 100_002), np.zeros(100_002), np.zeros(100_002)],
        ["100002 rows", "at most 100001"],
    ),
}


@pytest.mark.parametrize("case", list(BAD_TABLES))
def test_bad_table_refused_in_one_line(case):
    make, parts = BAD_TABLES[case]
    with pytest.raises(ParameterError) as info:
        tl.from_table(*make())
    assert_one_line(info.value, *parts)


def test_kink_check_accepts_smooth_tables_and_small_kinks():
    """Coarse smooth tables, narrow features, measured noise and a kink under 1 % all pass."""
    rng = np.random.default_rng(5)
    for rows in (8, 9, 12, 17, 33, 65):
        theta = np.linspace(0.0, TWO_PI, rows)
        tl.from_table(theta, 2.0 * theta + np.exp(np.sin(theta)), 0.5 * np.cos(theta))
        tl.from_table(theta, *analytic(theta)[0])
    theta, q1, q2 = _good(721)
    tl.from_table(theta, q1 + 1e-3 * rng.standard_normal(721), q2)
    largest = np.abs(np.diff(q1)).max() / (theta[1] - theta[0])
    tl.from_table(theta, q1 + 0.005 * largest * theta**2 / (2.0 * TWO_PI), q2)
    for rows in (49, 97, 721):  # a narrow smooth peak right at the ends
        theta = np.linspace(0.0, TWO_PI, rows)
        tl.from_table(theta, *bumpy(theta + 2.5)[0])
    for tilt in (20.0, 45.0, 60.0):
        params = wc.WobbleCam(np.radians(tilt))
        for rows in (61, 181, 721):
            theta = np.linspace(0.0, TWO_PI, rows)
            tl.from_table(theta, *wc.motion(params, theta).q)


# --------------------------------------------------------------------------------------------
# CSV
# --------------------------------------------------------------------------------------------
def _write_motion_csv(path, theta, q):
    """Like rotorkin's motion.csv: degrees, unit suffixes, more columns than read."""
    columns = {
        "theta_deg": np.degrees(theta),
        "rotor1_angle_deg": np.degrees(q[0]),
        "rotor2_angle_deg": np.degrees(q[1]),
        "slider_angle_deg": np.degrees(q[1] - q[0]),
    }
    data = np.column_stack(list(columns.values()))
    np.savetxt(path, data, delimiter=",", header=",".join(columns), comments="", fmt="%.12g")


def test_csv_round_trip_in_degrees(tmp_path):
    params = wobble()
    theta = np.linspace(0.0, TWO_PI, 721)
    q = wc.motion(params, theta).q
    path = tmp_path / "motion.csv"
    _write_motion_csv(path, theta, q)
    names = ["theta_deg", "rotor1_angle_deg", "rotor2_angle_deg"]
    th, q1, q2 = tl.read_table(path, columns=names)
    np.testing.assert_allclose(th, theta, rtol=1e-11, atol=1e-13)
    np.testing.assert_allclose(np.stack([q1, q2]), q, rtol=1e-11)
    law = tl.from_csv(path, columns=names)
    x = np.random.default_rng(4).uniform(0.0, TWO_PI, 1000)
    ref = wc.motion(params, x)
    # 12 significant digits in the file
    assert np.abs(law(x).q - ref.q).max() < 1e-9 * np.abs(ref.q).max()
    assert np.abs(law(x).dq - ref.dq).max() < 1e-7 * np.abs(ref.dq).max()


def test_csv_header_styles(tmp_path):
    theta = np.linspace(0.0, TWO_PI, 37)
    q = analytic(theta)[0]
    lines = ["# exported by a motion study", "shaft angle (deg); rotor A [rad]; rotor B [degrees]"]
    lines += [
        f"{float(np.degrees(t))!r}; {float(a)!r}; {float(np.degrees(b))!r}"
        for t, a, b in zip(theta, q[0], q[1], strict=True)
    ]
    lines.insert(10, "# a comment between rows")
    lines.insert(12, "")
    path = tmp_path / "study.csv"
    path.write_text("\ufeff" + "\n".join(lines) + "\n")
    th, q1, q2 = tl.read_table(path)
    np.testing.assert_allclose(th, theta, rtol=1e-14, atol=1e-15)
    np.testing.assert_allclose(np.stack([q1, q2]), q, rtol=1e-14)
    tab = tmp_path / "tab.csv"
    tab.write_text(
        "theta [rad]\tq1_rad\tq2 (rad)\n"
        + "".join(
            f"{float(t)!r}\t{float(a)!r}\t{float(b)!r}\n" for t, a, b in zip(theta, *q, strict=True)
        )
    )
    np.testing.assert_array_equal(np.stack(tl.read_table(tab)), np.stack([theta, *q]))


def _csv(tmp_path, text, name="table.csv"):
    path = tmp_path / name
    path.write_text(text)
    return path


GOOD_ROWS = "".join(f"{t:g},{t:g},{2 * t:g}\n" for t in range(0, 361, 30))

BAD_CSV = {
    "unknown column": (
        "theta_deg,rotor1_angle_deg,rotor2_angle_deg\n" + GOOD_ROWS,
        ["theta_deg", "rotor1_angle_deg", "rotor3_angle_deg"],
        ["column 'rotor3_angle_deg'", "one of the columns theta_deg, rotor1_angle_deg"],
    ),
    "missing unit": (
        "theta [deg],q1,q2 [deg]\n" + GOOD_ROWS,
        None,
        ["column 'q1' without a unit", "'theta [deg]'", "'theta_deg'"],
    ),
    "unknown unit": ("theta [deg],q1 [mm],q2 [deg]\n" + GOOD_ROWS, None, ["'q1 [mm]'"]),
    "non-number cell": (
        "# header next\ntheta [deg],q1 [deg],q2 [deg]\n0,0,0\n30,abc,60\n" + GOOD_ROWS,
        None,
        ["'table.csv' line 4 column 'q1 [deg]': 'abc'", "a finite number"],
    ),
    "NaN cell": ("theta_deg,a_deg,b_deg\n0,0,nan\n" + GOOD_ROWS, None, ["line 2", "'nan'"]),
    "short row": ("theta_deg,a_deg,b_deg\n0,0\n" + GOOD_ROWS, None, ["line 2 (2 cells)"]),
    "no header": ("# only comments\n\n", None, ["no header"]),
    "two columns": ("theta_deg,a_deg\n0,1\n", None, ["at least three columns"]),
    "decreasing row": (
        "theta_deg,a_deg,b_deg\n" + GOOD_ROWS.replace("60,60,120", "20,60,120"),
        None,
        ["'table.csv' row 3", "strictly increasing"],
    ),
}


@pytest.mark.parametrize("case", list(BAD_CSV))
def test_bad_csv_refused_in_one_line(tmp_path, case):
    text, columns, parts = BAD_CSV[case]
    with pytest.raises(ParameterError) as info:
        tl.from_csv(_csv(tmp_path, text), columns=columns)
    assert_one_line(info.value, *parts)


def test_csv_files_that_cannot_be_read(tmp_path):
    for path, part in (
        (tmp_path / "missing.csv", "'missing.csv'"),
        (tmp_path, "a regular file"),
    ):
        with pytest.raises(ParameterError) as info:
            tl.read_table(path)
        assert_one_line(info.value, part)
    binary = tmp_path / "binary.csv"
    binary.write_bytes(b"theta_deg,a_deg,b_deg\n\xff\xfe\n")
    with pytest.raises(ParameterError) as info:
        tl.read_table(binary)
    assert_one_line(info.value, "UTF-8")
    big = tmp_path / "big.csv"
    with open(big, "wb") as f:
        f.truncate(tl.MAX_FILE_BYTES + 1)
    with pytest.raises(ParameterError) as info:
        tl.read_table(big)
    assert_one_line(info.value, "at most 16 MiB")


def test_long_column_list_is_cut(tmp_path):
    names = [f"column_number_{i}_deg" for i in range(60)]
    path = _csv(tmp_path, ",".join(names) + "\n" + "0," * 59 + "0\n")
    with pytest.raises(ParameterError) as info:
        tl.read_table(path, columns=["x_deg", "y_deg", "z_deg"])
    assert_one_line(info.value, "(60 columns)")
    assert len(str(info.value)) < 300


# --------------------------------------------------------------------------------------------
# Fourier input
# --------------------------------------------------------------------------------------------
def _fourier():
    return tl.from_fourier(
        TWO_PI / 2.0,
        [1.0, -1.0],
        [0.1, 0.2],
        [0.2, -0.05, 0.01],
        [0.1, 0.02, 0.0],
        [0.3],
        [-0.1],
    )


def test_fourier_derivatives_against_finite_differences():
    law = _fourier()
    assert law.harmonics == 3
    x = np.linspace(-4.0, 9.0, 301)
    h = 1e-4
    m = law(x)
    ahead, behind = law(x + h), law(x - h)
    pairs = ((m.dq, "q"), (m.d2q, "dq"), (m.d3q, "d2q"))
    for got, lower in pairs:
        fd = (getattr(ahead, lower) - getattr(behind, lower)) / (2.0 * h)
        assert np.abs(got - fd).max() < 1e-6 * np.abs(got).max(), lower
    # the series itself, written out
    w = 2.0
    q1 = 0.1 + x + 0.2 * np.cos(w * x) + 0.1 * np.sin(w * x) - 0.05 * np.cos(2 * w * x)
    q1 += 0.02 * np.sin(2 * w * x) + 0.01 * np.cos(3 * w * x)
    q2 = 0.2 - x + 0.3 * np.cos(w * x) - 0.1 * np.sin(w * x)
    np.testing.assert_allclose(m.q, np.stack([q1, q2]), atol=1e-14)
    assert m.members == ("member 1", "member 2") and m.unit == "rad"


@pytest.mark.parametrize("shape", [(), (5,), (3, 4)])
def test_theta_shapes_broadcast(shape):
    law = _fourier()
    theta = np.random.default_rng(1).uniform(-5.0, 5.0, shape)
    m = law(theta)
    flat = law(np.ravel(theta))
    for name in ("q", "dq", "d2q", "d3q"):
        got = getattr(m, name)
        assert got.shape == (2,) + np.shape(theta)
        np.testing.assert_array_equal(got.reshape(2, -1), getattr(flat, name))
    assert m.theta.shape == np.shape(theta)


def test_chunked_evaluation_agrees(monkeypatch):
    rng = np.random.default_rng(9)
    a1, b1, a2, b2 = (rng.standard_normal(1000) / np.arange(1, 1001) ** 3 for _ in range(4))
    law = tl.from_fourier(TWO_PI, [1.0, 0.5], [0.0, 0.0], a1, b1, a2, b2)
    theta = rng.uniform(0.0, TWO_PI, (7, 301))
    whole = stacked(law(theta))
    monkeypatch.setattr(tl, "_CHUNK_BYTES", 8 * 1000 * 13)  # 13 angles per chunk
    np.testing.assert_allclose(stacked(law(theta)), whole, rtol=1e-13, atol=1e-13)


def test_periodic_part_repeats_far_from_the_origin():
    law = _fourier()
    x = np.linspace(0.0, 3.0, 11)
    far = law(x + 1000.0 * law.period)
    near = law(x)
    advance = (1000.0 * law.period * law.mean_ratio)[:, None] * np.ones(x.size)
    np.testing.assert_allclose(far.q - near.q, advance, rtol=1e-12)
    np.testing.assert_allclose(far.d3q, near.d3q, atol=1e-9)


BAD_FOURIER = {
    "period": (dict(period=np.radians(100.0)), "drive.period", "360 deg / k"),
    "mean ratio": (dict(mean_ratio=[1.0]), "drive.mean_ratio", "two numbers"),
    "offset": (dict(offset=[0.0, np.nan]), "drive.offset", "finite"),
    "lengths": (dict(b1=[0.1]), "drive.b1", "as many as drive.a1 (3)"),
    "too many": (dict(a2=np.zeros(1001), b2=np.zeros(1001)), "drive.a2", "at most 1000"),
    "not numbers": (dict(a1=["x", 1.0, 2.0]), "drive.a1", "numbers"),
    "not finite": (dict(b2=[np.inf]), "drive.b2", "finite"),
}


@pytest.mark.parametrize("case", list(BAD_FOURIER))
def test_bad_fourier_refused(case):
    change, name, part = BAD_FOURIER[case]
    args = dict(
        period=TWO_PI,
        mean_ratio=[1.0, -1.0],
        offset=[0.0, 0.0],
        a1=[0.1, 0.2, 0.3],
        b1=[0.0, 0.0, 0.0],
        a2=[0.1],
        b2=[0.1],
    )
    args.update(change)
    with pytest.raises(ParameterError) as info:
        tl.from_fourier(**args)
    assert info.value.name == name
    assert "\n" not in str(info.value)
    assert part in str(info.value)
