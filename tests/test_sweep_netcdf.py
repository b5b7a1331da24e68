"""The netCDF-3 writer of sweep results: read back by scipy's reader and by xarray, streamed.

Every variable, dimension, dtype and attribute written by
:func:`rotorkin.sweep.netcdf.write_netcdf3` is read back with two independent
readers (:class:`scipy.io.netcdf_file` and :func:`xarray.open_dataset`) and
compared with the in-memory result, and with the file xarray's own writer makes
of the same Dataset.
"""

from __future__ import annotations

import os
import tracemalloc
import warnings

import numpy as np
import pytest
import xarray as xr
from scipy.io import netcdf_file

from rotorkin.io.config import load_config
from rotorkin.sweep import SweepFallbackWarning, build_spec, compute, execute
from rotorkin.sweep import netcdf as nc
from rotorkin.sweep.result import SweepResult, Variable
from rotorkin.sweep.store import write_dataset


def _text(value):
    return value.decode() if isinstance(value, bytes) else value


def _scipy_equal(path, result: SweepResult) -> None:
    """Every variable and attribute of ``result`` as scipy reads it from ``path``."""
    with netcdf_file(path, "r", mmap=False) as f:
        assert f.version_byte == 2  # the 64-bit offset format
        attrs = {k: _text(v) for k, v in f._attributes.items()}
        assert attrs.keys() == result.attrs.keys()
        for k, v in result.attrs.items():
            np.testing.assert_array_equal(attrs[k], v, err_msg=k)
        assert set(f.variables) == set(result.variables)
        for name, var in result.variables.items():
            got = f.variables[name]
            data = var.data
            if data.dtype == object:  # strings: characters along a stringN dimension
                assert got.dimensions[:-1] == var.dims and got.typecode() == "c"
                assert got.dimensions[-1] == f"string{got.data.shape[-1]}"
                words = [b"".join(row).decode() for row in got.data.reshape(-1, got.shape[-1])]
                assert words == [str(s) for s in data.reshape(-1)]
                assert _text(got._attributes["_Encoding"]) == "utf-8"
                continue
            assert got.dimensions == var.dims, name
            expected = data.astype(np.int32) if data.dtype == np.int64 else data
            assert got.data.dtype.newbyteorder("=") == expected.dtype, name
            assert got.data.shape == expected.shape, name
            np.testing.assert_array_equal(got.data, expected, err_msg=name)
            attrs = {k: _text(v) for k, v in got._attributes.items()}
            if data.dtype.kind == "f":
                assert np.isnan(attrs.pop("_FillValue")), name
            attrs.pop("coordinates", None)
            assert attrs.keys() == var.attrs.keys(), name
            for k, v in var.attrs.items():
                np.testing.assert_array_equal(attrs[k], v, err_msg=f"{name}:{k}")
                if isinstance(v, np.ndarray):
                    assert np.asarray(attrs[k]).dtype.newbyteorder("=") == v.dtype


@pytest.fixture(scope="module")
def sweep(tmp_path_factory):
    """A 3-d sweep (float, choice and int keys) with curves, written by compute(store=...)."""
    _, raw, _ = load_config()
    spec = build_spec(raw, {"drive.plate_tilt": "30deg:40deg:3",
                            "machine.section": "rectangular,circular",
                            "machine.pistons_per_rotor": "2,4"},
                      keep_curves=True, samples=361)  # fmt: skip
    folder = tmp_path_factory.mktemp("sweep")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SweepFallbackWarning)
        result = compute(spec, store=folder, progress=False)
    return spec, result, folder / "sweep.nc"


def test_a_sweep_reads_back_with_scipy(sweep):
    spec, result, path = sweep
    assert result["drive.plate_tilt"].values.tolist() == [30.0, 35.0, 40.0]
    assert result["reason"].dtype == np.int16 and result["reason"].shape == spec.shape
    assert result["theta_deg"].dims == ("point",)
    assert result["slider_angle_deg"].shape == (*spec.shape, spec.points)
    _scipy_equal(path, result)
    with netcdf_file(path, "r", mmap=False) as f:  # xarray's convention for the 1-d angle
        assert f.variables["slider_angle_deg"]._attributes["coordinates"] == b"theta_deg"
        assert "coordinates" not in f.variables["reason"]._attributes


def test_a_sweep_reads_back_with_xarray_as_the_same_dataset(sweep, tmp_path):
    spec, result, path = sweep
    ds = result.to_dataset()
    with xr.open_dataset(path) as back:
        back = back.load()
    assert back.identical(ds)
    assert back["machine.pistons_per_rotor"].dtype == np.int32
    assert back["reason"].dtype == np.int16 and back["violations"].dtype == np.int16
    assert back["reason"].attrs["flag_values"].dtype.newbyteorder("=") == np.int16
    # xarray's own writer makes the same file but for the order of the variables
    ref = tmp_path / "ref.nc"
    ds.to_netcdf(ref, engine="scipy", format="NETCDF3_64BIT")
    assert os.path.getsize(ref) == os.path.getsize(path)
    with netcdf_file(ref, mmap=False) as a, netcdf_file(path, mmap=False) as b:
        assert a.dimensions == b.dimensions and a._attributes == b._attributes
        for name, va in a.variables.items():
            vb = b.variables[name]
            assert (va.dimensions, va.typecode()) == (vb.dimensions, vb.typecode())
            assert va._attributes.keys() == vb._attributes.keys()
            np.testing.assert_array_equal(va.data, vb.data)


def test_execute_returns_the_dataset_of_the_file(sweep, tmp_path):
    spec, result, _ = sweep
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SweepFallbackWarning)
        ds = execute(spec, store=tmp_path, progress=False)
    assert ds.identical(result.to_dataset())
    with xr.open_dataset(tmp_path / "sweep.nc") as back:
        assert back.load().identical(ds)


def _odd() -> SweepResult:
    """0-d, 1-d and 3-d variables of every stored kind, a 3-d non-dimension coordinate."""
    rng = np.random.default_rng(1)
    shape = (3, 5, 7)
    dims = ("a.key", "b", "c")
    data = {
        "scalar": Variable((), np.float64(2.5), {"units": "mm"}),
        "f8": Variable(dims, rng.normal(size=shape), {"units": "deg", "long_name": "x é y"}),
        "f4": Variable(dims, rng.normal(size=shape).astype(np.float32), {"units": ""}),
        "i2": Variable(
            dims,
            rng.integers(-300, 300, size=shape).astype(np.int16),
            {"flag_values": np.arange(3, dtype=np.int16), "flag_meanings": "ok x other"},
        ),
        "i4": Variable("c", np.arange(7, dtype=np.int32) * 100_000, {"scale": 1.5}),
        "i1": Variable("b", np.array([1, 0, 1, 1, 0], dtype=np.int8), {"n": 3}),
        "odd_i2": Variable("c", np.arange(7, dtype=np.int16), {}),
        "nan": Variable("b", np.array([np.nan, 1.0, np.inf, -np.inf, -0.0]), {}),
    }
    coords = {
        "a.key": Variable("a.key", np.array([1.0, 2.0, 4.0]), {"units": "mm", "spec": ""}),
        "b": Variable("b", np.array(["x", "crank", "", "guide", "é"], dtype=object), {}),
        "c": Variable("c", np.arange(7, dtype=np.int64), {}),
        "angle": Variable(dims, rng.uniform(size=shape), {"units": "deg"}),
    }
    attrs = {"title": "odd", "designs": 105, "ratio": 0.25, "empty": "",
             "masks": np.array([1, 2, 4], dtype=np.int16),
             "pair": np.array([1.5, 2.5])}  # fmt: skip
    return SweepResult(data, coords, attrs)


@pytest.mark.parametrize("block", [nc.BLOCK_BYTES, 24, 2])
def test_every_kind_and_shape_reads_back(block, tmp_path, monkeypatch):
    """0-d/1-d/3-d, float64/float32/int8/int16/int32/int64, strings, char and numeric
    attributes; blocks smaller than a row and than an item's padding."""
    monkeypatch.setattr(nc, "BLOCK_BYTES", block)
    result = _odd()
    path = result.to_netcdf(tmp_path / "odd.nc")
    _scipy_equal(path, result)
    ds = result.to_dataset()
    with xr.open_dataset(path) as back:
        back = back.load()
    expected = ds.assign_coords(c=ds["c"].astype(np.int32))  # netCDF-3 has no int64
    assert back.identical(expected)
    assert back["angle"].dims == ("a.key", "b", "c") and "angle" in back.coords
    ref = tmp_path / "ref.nc"
    ds.to_netcdf(ref, engine="scipy", format="NETCDF3_64BIT")
    assert os.path.getsize(ref) == os.path.getsize(path)


def test_write_dataset_takes_an_xarray_dataset_too(tmp_path):
    ds = _odd().to_dataset()
    write_dataset(ds, tmp_path / "x.nc")
    with xr.open_dataset(tmp_path / "x.nc") as back:
        assert back.load().identical(ds.assign_coords(c=ds["c"].astype(np.int32)))


def test_integers_beyond_32_bits_are_refused(tmp_path):
    bad = SweepResult({"v": Variable("n", np.array([2**40]), {})}, {}, {})
    with pytest.raises(ValueError, match="32-bit"):
        bad.to_netcdf(tmp_path / "bad.nc")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("interrupt", [KeyboardInterrupt, OSError])
def test_an_interrupted_write_leaves_no_file(interrupt, tmp_path, monkeypatch):
    """Interrupted after the header and some blocks: no file, no temporary file, and a
    file written before stays as it was."""
    result = _odd()
    path = tmp_path / "sweep.nc"
    path.write_bytes(b"previous")
    real, calls = np.ascontiguousarray, []

    def failing(*args, **kwargs):
        calls.append(1)
        if len(calls) == 4:
            raise interrupt("stop")
        return real(*args, **kwargs)

    monkeypatch.setattr(nc.np, "ascontiguousarray", failing)
    with pytest.raises(interrupt):
        result.to_netcdf(path)
    assert len(calls) == 4
    assert path.read_bytes() == b"previous"
    assert [p.name for p in tmp_path.iterdir()] == ["sweep.nc"]
    path.unlink()
    with pytest.raises(interrupt):
        calls.clear()
        result.to_netcdf(path)
    assert list(tmp_path.iterdir()) == []


def test_the_write_streams_without_a_copy(tmp_path):
    """Writing 48 MB of results allocates a few blocks, not a copy of them."""
    n = 2_000_000
    result = SweepResult(
        {f"m{i}": Variable("design", np.full(n, float(i)), {"units": "1"}) for i in range(3)},
        {"design": Variable("design", np.arange(n, dtype=np.int32), {})},
        {"designs": n},
    )
    tracemalloc.start()
    try:
        result.to_netcdf(tmp_path / "big.nc")
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 4 * nc.BLOCK_BYTES, peak
    assert result.nbytes == 3 * 8 * n + 4 * n
    with netcdf_file(tmp_path / "big.nc", mmap=True) as f:
        assert float(f.variables["m2"][n - 1]) == 2.0
        assert int(f.variables["design"][n - 1]) == n - 1
        del f


def test_an_angle_per_design_reads_back(tmp_path):
    """A swept gear ratio changes the period: the angle coordinate is (designs..., point)."""
    _, raw, _ = load_config(None, "guide-bar-pump", ["run.points=37"])
    spec = build_spec(raw, {"drive.input_gear_ratio": "1,2", "drive.lambda": "0.3,0.5,0.7"},
                      keep_curves=True, samples=181)  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SweepFallbackWarning)
        result = compute(spec, store=tmp_path, progress=False)
    angle = result["theta_deg"]
    assert angle.dims == ("drive.input_gear_ratio", "drive.lambda", "point")
    # one input turn per output period: the angle's last point grows with the gear ratio
    assert angle.values[1, 0, -1] > angle.values[0, 0, -1]
    _scipy_equal(tmp_path / "sweep.nc", result)
    with xr.open_dataset(tmp_path / "sweep.nc") as back:
        assert back.load().identical(result.to_dataset())
