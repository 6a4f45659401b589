"""``Solution.to_xarray``: an integration result as an ``xarray.Dataset`` (xarray is imported only here).

A single run gives the dimensions ``(time,)`` for scalar fields and ``(component, time)`` for vector fields;
a batch run (``sol.batch_shape != ()``) puts its batch dimensions first. The time dimension is named by
``sol.time_name`` (``'t'`` or ``'tau'``) and carries the times as its coordinate. ``status`` and ``message``
are variables over the batch dimensions (0-d for a single run), so a single run, a batch and a sweep
(:func:`rigidbody.sweep.sweep`) end up in the same kind of object.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np


def _xarray() -> Any:
    try:
        import xarray
    except ImportError as exc:
        raise ImportError('Solution.to_xarray needs xarray, an optional dependency: pip install "rigidbody[sweep]"'
                          ) from exc
    return xarray


def _batch_dims(batch_shape: tuple[int, ...], batch_dims: Any) -> tuple[tuple[str, ...], dict[str, Any]]:
    nb = len(batch_shape)
    if batch_dims is None:
        return tuple(f"batch_{i}" for i in range(nb)), {}
    coords: dict[str, Any] = {}
    if isinstance(batch_dims, Mapping):
        names = tuple(batch_dims)
        for (name, values), size in zip(batch_dims.items(), batch_shape):
            if values is not None:
                v = np.asarray(values)
                if v.shape != (size,):
                    raise ValueError(f"batch_dims[{name!r}] must have the {size} values of its batch axis, got "
                                     f"shape {v.shape}")
                coords[name] = v
    elif isinstance(batch_dims, Sequence) and not isinstance(batch_dims, str):
        names = tuple(batch_dims)
    else:
        raise TypeError(f"batch_dims must be a sequence of names or a mapping of names to coordinates, got "
                        f"{type(batch_dims).__name__}")
    if len(names) != nb or not all(isinstance(n, str) for n in names):
        raise ValueError(f"batch_dims must name the {nb} batch axes of shape {batch_shape}, got {names!r}")
    return names, coords


def solution_to_xarray(sol: Any, batch_dims: Any = None) -> Any:
    """The :class:`~rigidbody.core.ode.Solution` ``sol`` as an ``xarray.Dataset``.

    Parameters
    ----------
    sol : Solution
        A single run or a batch (``sol.batch_shape``).
    batch_dims : sequence of str or mapping of str to array_like, optional
        Names of the batch dimensions (default ``batch_0, batch_1, ...``); a mapping also gives their
        coordinates (``{"k2_0": k2_values}``; ``None`` for none).

    Returns
    -------
    xarray.Dataset
        One variable per field; vector fields get a dimension ``component`` (size 3) or
        ``<field>_component`` (other sizes, e.g. a quaternion's 4), before the time; ``status`` and
        ``message`` over the batch dimensions; for a single run ``attrs['event']`` (the terminal event's
        name, ``''`` if none), for a batch a variable ``event``.
    """
    xr = _xarray()
    batch_shape = tuple(getattr(sol, "batch_shape", ()) or ())
    nb = len(batch_shape)
    bdims, coords = _batch_dims(batch_shape, batch_dims)
    tname = sol.time_name
    time = np.asarray(sol.time)
    data: dict[str, Any] = {}
    for name in sol.fields:
        a = np.asarray(getattr(sol, name))
        if a.shape[:nb] != batch_shape or a.shape[-1:] != time.shape:
            raise ValueError(f"field {name!r} has shape {a.shape}, not batch {batch_shape} + (..., {time.size})")
        if a.ndim == nb + 1:
            dims = (*bdims, tname)
        elif a.ndim == nb + 2:
            dims = (*bdims, "component" if a.shape[nb] == 3 else f"{name}_component", tname)
        else:
            raise ValueError(f"field {name!r} has shape {a.shape}: expected scalar or vector samples")
        data[name] = (dims, a)
    status = np.asarray(sol.status, dtype=np.int64)
    message = np.empty(batch_shape, dtype=object)
    message[...] = sol.message if nb == 0 else np.asarray(sol.message, dtype=object)
    data["status"] = (bdims, status)
    data["message"] = (bdims, message)
    attrs: dict[str, Any] = {"time_name": tname}
    if nb == 0:
        attrs["event"] = sol.event or ""
    else:
        flat = np.asarray(sol.event, dtype=object).ravel()
        event = np.empty(flat.size, dtype=object)
        event[:] = [e or "" for e in flat]
        data["event"] = (bdims, event.reshape(batch_shape))
    coords[tname] = time
    return xr.Dataset(data, coords=coords, attrs=attrs)
