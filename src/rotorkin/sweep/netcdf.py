"""A netCDF-3 writer (64-bit offset format) that streams each variable from its array in blocks.

The classic netCDF format (Unidata, "The NetCDF Classic Format Specification";
CDF-2 is its 64-bit offset variant) is a header followed by the data::

    file      = "CDF" VERSION numrecs dim_list gatt_list var_list  data
    dim_list  = ABSENT | NC_DIMENSION nelems {name length}
    gatt_list = ABSENT | NC_ATTRIBUTE nelems {name nc_type nelems values}
    var_list  = ABSENT | NC_VARIABLE nelems {name ndims {dimid} vatt_list nc_type vsize begin}

every integer big-endian (``begin`` 64 bits in CDF-2, 32 in CDF-1), every name and
value list padded with zero bytes to a multiple of 4, and each variable's values
big-endian at ``begin``, in C order. Only fixed-size (non-record) variables are
written here. Each variable is converted to big-endian in blocks of
:data:`BLOCK_BYTES`, so writing a result takes no copy of it; the file is written
under a temporary name and renamed into place, so it exists only when complete.

The encoding follows what :meth:`xarray.Dataset.to_netcdf` writes for the same
data (scipy engine, ``NETCDF3_64BIT``), so that :func:`xarray.open_dataset`
reads back an identical Dataset: floats carry ``_FillValue = NaN``; 64-bit
integers are stored as 32-bit ones (refused beyond their range); booleans as
bytes; strings as characters along an extra dimension ``stringN`` with
``_Encoding = "utf-8"``; the non-dimension coordinates are named in the
``coordinates`` attribute of the variables that carry their dimensions.
"""

from __future__ import annotations

import os
import struct
from collections.abc import Mapping
from pathlib import Path

import numpy as np

__all__ = ["write_netcdf3", "BLOCK_BYTES"]

#: Bytes of one block of a variable converted to big-endian and written.
BLOCK_BYTES = 1 << 20

_ABSENT = b"\x00" * 8
_NC_DIMENSION, _NC_VARIABLE, _NC_ATTRIBUTE = 10, 11, 12
#: nc_type and big-endian dtype of the numpy kinds stored as they are
_TYPES = {
    np.dtype(np.int8): (1, ">i1"),
    np.dtype(np.int16): (3, ">i2"),
    np.dtype(np.int32): (4, ">i4"),
    np.dtype(np.float32): (5, ">f4"),
    np.dtype(np.float64): (6, ">f8"),
}
_NC_CHAR = 2
_INT32 = np.iinfo(np.int32)


def _pad(data: bytes) -> bytes:
    return data + b"\x00" * (-len(data) % 4)


def _name(text: str) -> bytes:
    raw = str(text).encode("utf-8")
    return struct.pack(">i", len(raw)) + _pad(raw)


def _int32(values: np.ndarray, what: str) -> np.ndarray:
    if values.size and (values.min() < _INT32.min or values.max() > _INT32.max):
        raise ValueError(f"{what}: integers beyond the 32-bit range of netCDF-3")
    return values.astype(np.int32)


def _attr_values(value, what: str) -> tuple[int, int, bytes]:
    """(nc_type, nelems, padded big-endian bytes) of one attribute value."""
    if isinstance(value, str | bytes | np.str_ | np.bytes_):
        raw = value.encode("utf-8") if isinstance(value, str) else bytes(value)
        raw = raw or b"\x00"  # an empty text as scipy writes it: one NUL character
        return _NC_CHAR, len(raw), _pad(raw)
    arr = np.asarray(value)
    if arr.dtype.kind in "US":
        raise ValueError(f"{what}: a list of strings is not a netCDF-3 attribute")
    if arr.dtype == bool:
        arr = arr.astype(np.int8)
    elif arr.dtype.kind in "iu" and arr.dtype not in _TYPES:
        arr = _int32(arr.astype(np.int64), what)
    nc_type, big = _TYPES[arr.dtype]
    arr = arr.reshape(-1)
    return nc_type, arr.size, _pad(arr.astype(big).tobytes())


def _attrs(attrs: Mapping) -> bytes:
    if not attrs:
        return _ABSENT
    out = [struct.pack(">ii", _NC_ATTRIBUTE, len(attrs))]
    for key, value in attrs.items():
        nc_type, n, data = _attr_values(value, f"attribute {key}")
        out.append(_name(key) + struct.pack(">ii", nc_type, n) + data)
    return b"".join(out)


class _Plan:
    """One variable as stored: dims, attrs, nc_type, big-endian dtype, its flat source."""

    def __init__(self, name, dims, data, attrs, dim_sizes):
        data = np.asarray(data)
        self.name, self.attrs = name, dict(attrs)
        self.dims = tuple(dims)
        if data.ndim != len(self.dims):
            raise ValueError(f"variable {name}: {data.ndim} axes for dims {self.dims}")
        for d, n in zip(self.dims, data.shape, strict=True):
            if dim_sizes.setdefault(d, n) != n:
                raise ValueError(f"variable {name}: dimension {d} has {n}, not {dim_sizes[d]}")
        if data.dtype.kind in "OUS":  # strings: characters along a stringN dimension
            raw = [str(s).encode("utf-8") if not isinstance(s, bytes) else s
                   for s in data.reshape(-1)]  # fmt: skip
            width = max([len(r) for r in raw] + [1])
            chars = np.array(raw, dtype=f"S{width}").view("S1").reshape(*data.shape, width)
            string_dim = f"string{width}"
            dim_sizes.setdefault(string_dim, width)
            self.dims += (string_dim,)
            self.attrs["_Encoding"] = "utf-8"
            self.nc_type, self.big, self.source = _NC_CHAR, "S1", chars.reshape(-1)
            self.itemsize = 1
            return
        if data.dtype == bool:
            data = data.astype(np.int8)
        elif data.dtype.kind in "iu" and data.dtype not in _TYPES:
            data = _int32(data.astype(np.int64, copy=False), f"variable {name}")
        self.nc_type, self.big = _TYPES[data.dtype]
        if data.dtype.kind == "f" and "_FillValue" not in self.attrs:
            self.attrs["_FillValue"] = np.array(np.nan, dtype=data.dtype)
        self.itemsize = data.dtype.itemsize
        self.source = data.reshape(-1)  # a view of a C-contiguous array: no copy

    @property
    def nbytes(self) -> int:
        return self.source.size * self.itemsize

    @property
    def vsize(self) -> int:
        return self.nbytes + (-self.nbytes % 4)


def _plans(variables: Mapping, coords) -> tuple[dict, list, list]:
    dim_sizes: dict = {}
    plans = [_Plan(name, v.dims, v.data, v.attrs, dim_sizes) for name, v in variables.items()]
    # non-dimension coordinates: named by the variables that carry all their dimensions
    extra = [c for c in coords if tuple(variables[c].dims) != (c,)]
    named = set()
    for p in plans:
        if p.name in coords:
            continue
        here = [c for c in extra if set(variables[c].dims) <= set(variables[p.name].dims)]
        if here:
            fill = p.attrs.pop("_FillValue", None)
            p.attrs["coordinates"] = " ".join(here)
            if fill is not None:
                p.attrs["_FillValue"] = fill
            named.update(here)
    return dim_sizes, plans, [c for c in extra if c not in named]


def _header(dim_sizes: dict, plans: list, attrs: Mapping, begins: list[int]) -> bytes:
    dim_id = {d: i for i, d in enumerate(dim_sizes)}
    out = [b"CDF\x02", struct.pack(">i", 0)]
    if dim_sizes:
        out.append(struct.pack(">ii", _NC_DIMENSION, len(dim_sizes)))
        out += [_name(d) + struct.pack(">i", n) for d, n in dim_sizes.items()]
    else:
        out.append(_ABSENT)
    out.append(_attrs(attrs))
    if plans:
        out.append(struct.pack(">ii", _NC_VARIABLE, len(plans)))
        for p, begin in zip(plans, begins, strict=True):
            out.append(_name(p.name) + struct.pack(">i", len(p.dims)))
            out.append(b"".join(struct.pack(">i", dim_id[d]) for d in p.dims))
            out.append(_attrs(p.attrs))
            out.append(struct.pack(">iiq", p.nc_type, min(p.vsize, 2**32 - 1), begin))
    else:
        out.append(_ABSENT)
    return b"".join(out)


def write_netcdf3(path, variables: Mapping, attrs: Mapping, coords=()) -> Path:
    """Write variables and attributes as a netCDF-3 file (64-bit offsets), atomically.

    Parameters
    ----------
    path : path
        The file; written as ``.NAME.tmp-PID`` beside it and renamed when complete
        (nothing is left behind when the write fails or is interrupted).
    variables : mapping
        Name -> object with ``dims`` (tuple of str), ``data`` (numpy array of that
        many axes) and ``attrs`` (mapping), in the order to store them.
    attrs : mapping
        Global attributes (str, int, float or arrays of numbers).
    coords : sequence of str
        The names among ``variables`` that are coordinates.

    Returns
    -------
    Path
    """
    path = Path(path)
    dim_sizes, plans, loose = _plans(variables, tuple(coords))
    attrs = dict(attrs)
    if loose:
        attrs["coordinates"] = " ".join(loose)
    # a header with placeholder offsets has the final length: the data begin after it
    begins = [0] * len(plans)
    start = len(_header(dim_sizes, plans, attrs, begins))
    for i, p in enumerate(plans):
        begins[i] = start
        start += p.vsize
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    try:
        with open(tmp, "wb") as f:
            f.write(_header(dim_sizes, plans, attrs, begins))
            for p in plans:
                step = max(1, BLOCK_BYTES // p.itemsize)
                src = p.source
                for lo in range(0, src.size, step):
                    f.write(np.ascontiguousarray(src[lo : lo + step], dtype=p.big).data)
                f.write(b"\x00" * (p.vsize - p.nbytes))
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    return path
