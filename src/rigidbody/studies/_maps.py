r"""A study over the outer product of a grid in this process, into NumPy arrays (:class:`StudyMap`).

The light counterpart of :func:`rigidbody.sweep.sweep`: the same layout (a dimension per grid name, a
variable per output, ``status`` and ``message`` per point) without the optional dependencies. The readers
(:func:`grid_values`, :func:`fitted_order`, the plotting helpers) take a :class:`StudyMap` or a sweep's
``xarray.Dataset`` alike.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

__all__ = ["Field", "StudyMap", "as_study_map", "evaluate", "fitted_order", "grid_values"]

#: the per-point variables every map has besides the function's outputs
_OWN = ("status", "message")


class Field(NamedTuple):
    """A variable or coordinate of a :class:`StudyMap`: its dimension names and its values (what the readers
    use of an ``xarray.DataArray``).

    See Also
    --------
    StudyMap : whose variables and coordinates these are.
    grid_values : a variable's values in a chosen order of its dimensions.

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody.studies import Field
    >>> f = Field(dims=("eps",), values=np.array([0.01, 0.02]))
    >>> f.dims, f.values.shape
    (('eps',), (2,))
    """

    dims: tuple[str, ...]
    values: np.ndarray


@dataclass(frozen=True)
class StudyMap:
    """Outputs of a study over the outer product of a grid, as NumPy arrays.

    Attributes
    ----------
    coords : dict of str to numpy.ndarray
        The grid: names (the dimensions, in order) to their 1-D values.
    data : dict of str to numpy.ndarray
        The outputs, each of shape ``shape`` (or ``shape + (...)`` for an array output), NaN where a point
        failed; ``status`` (int, 0 ok) and ``message`` (str, '' where ok) per point.

    See Also
    --------
    evaluate : which makes one.
    as_study_map : a sweep's dataset as one.

    Examples
    --------
    The grid and outputs of a toy study ``error = c eps²``:

    >>> from rigidbody import studies
    >>> m = studies.evaluate(lambda eps, c: {"error": c * eps**2}, {"eps": [0.01, 0.02, 0.04], "c": [1.0, 3.0]})
    >>> list(m.coords), m.data["error"].shape
    (['eps', 'c'], (3, 2))
    """

    coords: dict[str, np.ndarray]
    data: dict[str, np.ndarray]

    @property
    def dims(self) -> tuple[str, ...]:
        """The grid names, in order.

        Examples
        --------
        >>> from rigidbody import studies
        >>> m = studies.evaluate(lambda eps, c: {"error": c * eps**2}, {"eps": [0.01, 0.02, 0.04], "c": [1.0, 3.0]})
        >>> m.dims
        ('eps', 'c')
        """
        return tuple(self.coords)

    @property
    def shape(self) -> tuple[int, ...]:
        """The grid's shape.

        Examples
        --------
        >>> from rigidbody import studies
        >>> m = studies.evaluate(lambda eps, c: {"error": c * eps**2}, {"eps": [0.01, 0.02, 0.04], "c": [1.0, 3.0]})
        >>> m.shape, m.data["error"].shape
        ((3, 2), (3, 2))
        """
        return tuple(v.size for v in self.coords.values())

    def __getitem__(self, name: str) -> Field:
        """A coordinate (its own dimension) or a variable (the grid's dimensions, then ``<name>_dim_0, ...``)."""
        if name in self.coords:
            return Field((name,), self.coords[name])
        if name in self.data:
            v = self.data[name]
            return Field(self.dims + tuple(f"{name}_dim_{i}" for i in range(v.ndim - len(self.dims))), v)
        raise KeyError(f"{name!r} is neither a grid name {self.dims} nor an output {tuple(self.data)}")

    def __contains__(self, name: object) -> bool:
        return name in self.coords or name in self.data

    def __repr__(self) -> str:
        grid = ", ".join(f"{k}: {v.size}" for k, v in self.coords.items())
        failed = f"; {int(np.count_nonzero(self.data['status']))} failed" if "status" in self.data else ""
        return f"StudyMap({grid}; outputs {[k for k in self.data if k not in _OWN]}{failed})"

    def to_xarray(self) -> Any:
        """The map as the ``xarray.Dataset`` a sweep of the same function gives (needs xarray).

        Returns
        -------
        xarray.Dataset

        Examples
        --------
        >>> from rigidbody import studies
        >>> m = studies.evaluate(lambda eps, c: {"error": c * eps**2}, {"eps": [0.01, 0.02, 0.04], "c": [1.0, 3.0]})
        >>> ds = m.to_xarray()
        >>> dict(ds.sizes), sorted(ds.data_vars)
        ({'eps': 3, 'c': 2}, ['error', 'message', 'status'])
        >>> print(f"{float(ds['error'].sel(eps=0.04, c=3.0)):.6f} {3.0 * 0.04**2:.6f}")
        0.004800 0.004800
        """
        import xarray as xr

        data = {k: (self[k].dims, v.astype(str) if k == "message" else v) for k, v in self.data.items()}
        return xr.Dataset(data, coords=self.coords)


def _grid(grid: Any) -> dict[str, np.ndarray]:
    if not isinstance(grid, Mapping) or not grid:
        raise TypeError(f"grid must be a non-empty mapping of parameter names to 1-D arrays, got {grid!r}")
    out = {}
    for name, values in grid.items():
        if not isinstance(name, str) or not name.isidentifier() or name in _OWN:
            raise ValueError(f"grid names must be Python identifiers other than {_OWN}, got {name!r}")
        a = np.asarray(values)
        if a.ndim != 1 or a.size == 0 or a.dtype.kind not in "biuf":
            raise ValueError(f"grid[{name!r}] must be a non-empty 1-D array of numbers, got {values!r}")
        out[name] = a
    return out


def evaluate(func: Callable[..., Mapping[str, Any]], grid: Mapping[str, Any]) -> StudyMap:
    """``func`` over the outer product of ``grid`` in this process: one call with all the points as arrays.

    For a function that takes arrays of points, as the studies of :mod:`rigidbody.studies` do (each
    integrates its points as batches): ``evaluate(spin_end, grid)`` holds the numbers of
    ``rigidbody.sweep.sweep(spin_end, grid)`` and needs no optional dependency (no workers, no store, no
    Dask: for those, sweep).

    Parameters
    ----------
    func : callable
        ``func(**arrays) -> {output name: array}``, called once with each grid name as a 1-D array over
        all points (C order: the last name varies fastest); each output has a leading axis over the points,
        and optionally ``'status'`` (integers >= 0, 0 ok) and ``'message'`` (strings) per point.
    grid : mapping of str to 1-D array_like
        Parameter names to their values.

    Returns
    -------
    StudyMap
        Outputs NaN where ``status`` is not 0 (as in a sweep).

    See Also
    --------
    rigidbody.sweep.sweep : the same map with workers, a store or Dask.
    grid_values, fitted_order : readers of the map.

    Examples
    --------
    A toy study ``error = c eps²`` over a 3 x 2 grid:

    >>> from rigidbody import studies
    >>> m = studies.evaluate(lambda eps, c: {"error": c * eps**2}, {"eps": [0.01, 0.02, 0.04], "c": [1.0, 3.0]})
    >>> m
    StudyMap(eps: 3, c: 2; outputs ['error']; 0 failed)
    >>> print(f"{m.data['error'][2, 1]:.6f}")
    0.004800
    """
    if not callable(func):
        raise TypeError(f"func must be callable, got {type(func).__name__}")
    coords = _grid(grid)
    shape = tuple(v.size for v in coords.values())
    n = math.prod(shape)
    mesh = np.meshgrid(*coords.values(), indexing="ij")
    out = func(**{k: m.reshape(-1) for k, m in zip(coords, mesh)})
    if not isinstance(out, Mapping):
        raise TypeError(f"{func!r} must return a mapping of output names to arrays, got {type(out).__name__}")
    status = np.asarray(out.get("status", np.zeros(n, dtype=int)))
    message = np.asarray(out.get("message", np.full(n, "", dtype=object)), dtype=object)
    if status.shape != (n,) or status.dtype.kind not in "biu" or message.shape != (n,):
        raise ValueError(f"{func!r} must return 'status' (integers) and 'message' with one entry per point ({n})")
    data: dict[str, np.ndarray] = {}
    for k, v in out.items():
        if k in _OWN:
            continue
        a = np.array(v, dtype=float)
        if a.ndim == 0 or a.shape[0] != n:
            raise ValueError(f"output {k!r} of {func!r} must have a leading axis over the {n} points, has {a.shape}")
        a[status != 0] = np.nan  # a point that did not succeed has no results
        data[k] = a.reshape(shape + a.shape[1:])
    data["status"] = status.astype(int).reshape(shape)
    data["message"] = message.reshape(shape)
    return StudyMap(coords, data)


def as_study_map(ds: Any) -> StudyMap:
    """A map as a :class:`StudyMap`: the map itself, or the NumPy arrays of a sweep's ``xarray.Dataset``.

    Parameters
    ----------
    ds : StudyMap or xarray.Dataset
        The grid's dimensions are those of ``status`` (of the first variable if there is none); each variable
        has them first.

    Returns
    -------
    StudyMap

    See Also
    --------
    evaluate : which returns a map.
    rigidbody.sweep.sweep : which returns a dataset.

    Examples
    --------
    A map is returned as it is:

    >>> from rigidbody import studies
    >>> m = studies.evaluate(lambda eps, c: {"error": c * eps**2}, {"eps": [0.01, 0.02, 0.04], "c": [1.0, 3.0]})
    >>> studies.as_study_map(m) is m
    True
    """
    if isinstance(ds, StudyMap):
        return ds
    names = list(ds.data_vars)
    if not names:
        raise ValueError("the Dataset has no variables")
    dims = tuple(ds["status" if "status" in names else names[0]].dims)
    data = {}
    for k in names:
        data[k] = grid_values(ds, k, dims + tuple(d for d in ds[k].dims if d not in dims))
        if k == "message":
            data[k] = data[k].astype(object)
    return StudyMap({d: np.asarray(ds[d].values) for d in dims}, data)


def grid_values(ds: Any, name: str, dims: tuple[str, ...] | None = None) -> np.ndarray:
    """A variable or coordinate of a map as a NumPy array, its axes in the order ``dims``.

    Parameters
    ----------
    ds : StudyMap or xarray.Dataset
        A map from :func:`evaluate` or from :func:`rigidbody.sweep.sweep`.
    name : str
    dims : tuple of str, optional
        All of the variable's dimensions, in the wanted order (default: as stored).

    Returns
    -------
    numpy.ndarray

    See Also
    --------
    fitted_order : a fit along one axis.

    Examples
    --------
    The toy study ``error = c eps²`` with its axes swapped to ``(c, eps)``: the row ``c = 3`` is
    ``3 eps²``:

    >>> from rigidbody import studies
    >>> m = studies.evaluate(lambda eps, c: {"error": c * eps**2}, {"eps": [0.01, 0.02, 0.04], "c": [1.0, 3.0]})
    >>> studies.grid_values(m, "error", ("c", "eps"))[1]
    array([0.0003, 0.0012, 0.0048])
    """
    f = ds[name]
    values, own = np.asarray(f.values), tuple(f.dims)
    if dims is None:
        return values
    if sorted(dims) != sorted(own):
        raise ValueError(f"{name!r} has the dimensions {own}, not {tuple(dims)}")
    return np.transpose(values, [own.index(d) for d in dims])


def fitted_order(ds: Any, var: str = "error", over: str = "eps") -> Any:
    r"""The exponent :math:`p` of ``var ~ C over**p``: least squares in log-log along the ``over`` axis.

    Parameters
    ----------
    ds : StudyMap or xarray.Dataset
        A study's map (points that failed, NaN, are left out of each fit).
    var, over : str
        The variable and the grid dimension.

    Returns
    -------
    numpy.ndarray or xarray.DataArray
        One exponent for each point of the other dimensions (NaN where fewer than two points are left): an
        array for a :class:`StudyMap`, a DataArray for a Dataset.

    See Also
    --------
    averaging_error_lagrange, averaging_error_euler_poinsot : studies whose order it measures.

    Examples
    --------
    ``error = c eps²`` has the exponent 2 for every ``c``:

    >>> from rigidbody import studies
    >>> m = studies.evaluate(lambda eps, c: {"error": c * eps**2}, {"eps": [0.01, 0.02, 0.04], "c": [1.0, 3.0]})
    >>> print(" ".join(f"{p:.6f}" for p in studies.fitted_order(m)))
    2.000000 2.000000
    """
    x = np.log(grid_values(ds, over))

    def fit(y: np.ndarray) -> float:
        ok = np.isfinite(y) & (y > 0)
        if ok.sum() < 2:
            return math.nan
        return float(np.polyfit(x[ok], np.log(y[ok]), 1)[0])

    if isinstance(ds, StudyMap):
        others = tuple(d for d in ds[var].dims if d != over)
        y = grid_values(ds, var, (*others, over))
        return np.array([fit(row) for row in y.reshape(-1, x.size)]).reshape(y.shape[:-1])
    import xarray as xr

    return xr.apply_ufunc(fit, ds[var], input_core_dims=[[over]], vectorize=True)
