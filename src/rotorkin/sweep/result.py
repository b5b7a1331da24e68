"""The light result of a sweep: the flat arrays, shaped as views, with their dims and attributes.

:class:`SweepResult` holds exactly what the :class:`xarray.Dataset` of a sweep
holds (variables with dims and attributes, coordinates, global attributes) as
numpy arrays, without xarray: the command line writes it (netCDF with
:mod:`rotorkin.sweep.netcdf`, figures, README) on the core install, and
:meth:`SweepResult.to_dataset` builds the Dataset (no copy of the arrays) when
the Python API asks for one (the ``xarray`` extra).

For the figures it offers the small part of xarray's interface they use:
``result[name].values``, ``.dims``, ``.attrs``, ``.isel({dim: i})`` and
``.sel({dim: value})`` (exact coordinate values).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from rotorkin.core.extras import xarray_module

__all__ = ["Variable", "SweepResult"]


class Variable:
    """One variable: ``dims``, ``data`` (numpy, often a view of a flat result), ``attrs``."""

    __slots__ = ("dims", "data", "attrs", "_owner")

    def __init__(self, dims, data, attrs=None, owner=None):
        self.dims = (dims,) if isinstance(dims, str) else tuple(dims)
        self.data = np.asarray(data)
        self.attrs = dict(attrs or {})
        self._owner = owner
        if self.data.ndim != len(self.dims):
            raise ValueError(f"{self.data.ndim} axes for dims {self.dims}")

    @property
    def values(self) -> np.ndarray:
        return self.data

    @property
    def dtype(self):
        return self.data.dtype

    @property
    def shape(self) -> tuple:
        return self.data.shape

    @property
    def sizes(self) -> dict:
        return dict(zip(self.dims, self.data.shape, strict=True))

    def __len__(self) -> int:
        return len(self.data)

    def __getitem__(self, index):
        return self.data[index]

    def item(self):
        return self.data.item()

    def isel(self, indexers: Mapping) -> Variable:
        """The variable at integer positions (or slices) along some of its dims."""
        index = tuple(indexers.get(d, slice(None)) for d in self.dims)
        dims = tuple(d for d in self.dims if not isinstance(indexers.get(d), int | np.integer))
        return Variable(dims, self.data[index], self.attrs, self._owner)

    def sel(self, indexers: Mapping) -> Variable:
        """The variable at coordinate values (exact) along some of its dims."""
        if self._owner is None:
            raise KeyError("no coordinates to select by")
        return self.isel(self._owner.positions(indexers))


class SweepResult:
    """Variables, coordinates and attributes of a sweep, as numpy arrays.

    Parameters
    ----------
    data_vars, coords : mapping
        Name -> :class:`Variable` (or ``(dims, data, attrs)``), in the Dataset's order.
    attrs : mapping
        Global attributes.
    """

    def __init__(self, data_vars: Mapping, coords: Mapping, attrs: Mapping):
        def make(v):
            if isinstance(v, Variable):
                return Variable(v.dims, v.data, v.attrs, self)
            return Variable(*v, owner=self)

        self.data_vars = {k: make(v) for k, v in data_vars.items()}
        self.coords = {k: make(v) for k, v in coords.items()}
        self.attrs = dict(attrs)

    @property
    def variables(self) -> dict:
        """Every variable: data variables, then coordinates."""
        return {**self.data_vars, **self.coords}

    @property
    def sizes(self) -> dict:
        out = {}
        for v in self.variables.values():
            out.update(v.sizes)
        return out

    dims = sizes

    @property
    def nbytes(self) -> int:
        """Bytes of the arrays held (views of one array counted once)."""
        seen, total = set(), 0
        for v in self.variables.values():
            base = v.data if v.data.base is None else v.data.base
            if id(base) not in seen:
                seen.add(id(base))
                total += base.nbytes
        return total

    def __getitem__(self, name: str) -> Variable:
        if name in self.data_vars:
            return self.data_vars[name]
        return self.coords[name]

    def __contains__(self, name) -> bool:
        return name in self.data_vars or name in self.coords

    def __iter__(self):
        return iter(self.data_vars)

    def positions(self, indexers: Mapping) -> dict:
        """Coordinate values -> integer positions (exact match)."""
        out = {}
        for dim, value in indexers.items():
            hits = np.flatnonzero(self.coords[dim].data == value)
            if not hits.size:
                raise KeyError(f"{value!r} is not a value of {dim}")
            out[dim] = int(hits[0])
        return out

    def isel(self, indexers: Mapping) -> SweepResult:
        """The result at integer positions along some dims (views, no copy)."""
        return SweepResult({k: v.isel(indexers) for k, v in self.data_vars.items()},
                           {k: v.isel(indexers) for k, v in self.coords.items()},
                           self.attrs)  # fmt: skip

    def to_dataset(self, what: str = "rotorkin.sweep.execute"):
        """The :class:`xarray.Dataset` of the same variables (the arrays are shared, not copied).

        Raises ``ModuleNotFoundError`` naming ``pip install "rotorkin[xarray]"`` without xarray.
        """
        xr = xarray_module(what)

        def var(v):
            return xr.Variable(v.dims, v.data, attrs=dict(v.attrs))

        return xr.Dataset({k: var(v) for k, v in self.data_vars.items()},
                          coords={k: var(v) for k, v in self.coords.items()},
                          attrs=dict(self.attrs))  # fmt: skip

    def to_netcdf(self, path):
        """Write netCDF-3 (64-bit offsets), streamed in blocks, atomically; the path."""
        from rotorkin.sweep.netcdf import write_netcdf3

        return write_netcdf3(path, self.variables, self.attrs, tuple(self.coords))
