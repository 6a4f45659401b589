"""Vectorised stability maps over parameter grids (the family (2.3), verdicts of (2.5))."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from ..core.validate import positive
from ._family import (
    SINGULAR_TOL,
    Scratch,
    broadcast_shape,
    check_fits,
    check_omega_sign,
    family_arrays,
    family_constants,
    family_momentum,
    family_side,
    float_arrays,
    lean,
)
from ._model import Satellite
from ._secondvar import (
    VERDICTS,
    a_matrix,
    entry_constants,
    hessian_entries,
    restricted_conditions,
    second_variation_side,
    verdicts,
)

__all__ = ["StabilityMap", "exact_boundaries", "normalized_stability_map", "stability_map"]

_MAP_ORDER = ("theta0", "R0", "k2", "k3", "M", "A1", "A2", "A3", "mu")


@dataclass(frozen=True)
class StabilityMap:
    """Verdicts over a grid.  All arrays have the grid's shape (``minors``: plus a trailing axis of 5); they
    may be read-only broadcast views (copy before writing).

    ``code``: 0 stable, 1 unstable (odd degree), 2 undecided, -1 invalid (no motion of the family,
    singular chart, k2 ill-conditioned (abs(sin(theta0 + kappa0)) <= 1e-6 with k3 given), a non-physical
    body, or one that does not fit inside its orbit, ``R0^2 <= (A1 + A2 + A3) / (2 M)``);
    :attr:`verdict` gives the strings.  ``minors`` (the five leading minors of the constrained second
    variation, see :class:`Stability`), ``r1, r2, r3`` (the restricted-problem quantities) and
    ``restricted_stable`` (their conjunction) are computed on first access.

    See Also
    --------
    stability_map : the function that returns it.
    Stability : the same quantities for one motion.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.5).

    Examples
    --------
    A 2 x 2 grid over theta0 (rows) and k2 (columns); each point is what :func:`stability` says of it:

    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> mp = gyrostat.stability_map(sat, 1.0, [0.0, 0.3], k2=[0.0, 0.02])
    >>> mp.code
    array([[1, 0],
           [1, 0]], dtype=int8)
    >>> m = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=0.02)
    >>> gyrostat.stability(m.satellite, m).verdict, str(mp.verdict[1, 1])
    ('stable', 'stable')
    """

    params: dict[str, np.ndarray]
    kappa0: np.ndarray
    omega0: np.ndarray
    k2: np.ndarray
    k3: np.ndarray
    s1: np.ndarray
    s2: np.ndarray
    s3: np.ndarray
    degree: np.ndarray
    code: np.ndarray
    #: what the lazy minors recompute a11 and a11 a22 - a12^2 from: the side parameters, omega_sign, rtol
    _parts: dict[str, Any] = field(repr=False, compare=False)

    @cached_property
    def minors(self) -> np.ndarray:
        """The leading minors ``s1, s2, s2 a11, s2 (a11 a22 - a12^2), s2 s3`` (NaN at invalid points)."""
        s2 = self.s2
        with np.errstate(all="ignore"):  # a11 and a11 a22 - a12^2 do not involve k2: per theta0 on a grid
            _, d = _side(self._parts["side"], self._parts["omega_sign"], self._parts["rtol"])
        out = np.empty((*self.shape, 5))
        out[..., 0] = self.s1
        out[..., 1] = s2
        with np.errstate(over="ignore", invalid="ignore"):
            np.multiply(s2, d["a11"], out=out[..., 2])
            np.multiply(s2, d["C"], out=out[..., 3])
            np.multiply(s2, self.s3, out=out[..., 4])
        out[self.code == -1] = np.nan
        return out

    @cached_property
    def _restricted(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        P = self.params
        r1, r2, r3 = restricted_conditions(P["A1"], P["A2"], P["A3"], P["theta0"], self.k2, self.omega0)
        return np.broadcast_to(r1, self.shape), np.broadcast_to(r2, self.shape), np.broadcast_to(r3, self.shape)

    @property
    def r1(self) -> np.ndarray:
        """``A1 - A2 sin^2 theta0 - A3 cos^2 theta0`` (see :func:`~rigidbody.gyrostat.restricted_conditions`).

        Examples
        --------
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
        >>> mp = gyrostat.stability_map(sat, 1.0, [0.0, 0.3], k2=[0.0, 0.02])
        >>> print(f"{mp.r1[0, 0]:.12f}")  # A1 - A3 at theta0 = 0
        0.004000000000
        """
        return self._restricted[0]

    @property
    def r2(self) -> np.ndarray:
        """``A2 - A3 + k2 / (4 omega0 cos^3 theta0)``.

        Examples
        --------
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
        >>> mp = gyrostat.stability_map(sat, 1.0, [0.0, 0.3], k2=[0.0, 0.02])
        >>> print(f"{mp.r2[0, 0]:.12f}")  # A2 - A3 at theta0 = 0, k2 = 0
        0.002000000000
        """
        return self._restricted[1]

    @property
    def r3(self) -> np.ndarray:
        """``r1 (A2 - A1 + k2 / (omega0 cos theta0)) + 3 (A1 - A2)(A2 - A3) sin^2 theta0``.

        Examples
        --------
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
        >>> mp = gyrostat.stability_map(sat, 1.0, [0.0, 0.3], k2=[0.0, 0.02])
        >>> print(f"{mp.r3[0, 0]:.6e}")  # (A1 - A3)(A2 - A1) at theta0 = 0, k2 = 0
        -8.000000e-06
        """
        return self._restricted[2]

    @property
    def verdict(self) -> np.ndarray:
        """Verdict strings ('stable', 'unstable', 'undecided', 'invalid').

        Examples
        --------
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
        >>> mp = gyrostat.stability_map(sat, 1.0, [0.0, 0.3], k2=[0.0, 0.02])
        >>> mp.verdict
        array([['unstable', 'stable'],
               ['unstable', 'stable']], dtype='<U9')
        """
        names = np.array([VERDICTS[0], VERDICTS[1], VERDICTS[2], VERDICTS[-1]])
        return names[np.where(self.code < 0, 3, self.code)]

    @property
    def theta0(self) -> np.ndarray:
        """The tilt theta0 at each point of the map (broadcast to its shape).

        Examples
        --------
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
        >>> mp = gyrostat.stability_map(sat, 1.0, [0.0, 0.3], k2=[0.0, 0.02])
        >>> mp.theta0
        array([[0. , 0. ],
               [0.3, 0.3]])
        """
        return self.params["theta0"]

    @property
    def restricted_stable(self) -> np.ndarray:
        """Where all three restricted-problem inequalities hold (:attr:`r1`, :attr:`r2`, :attr:`r3` > 0).

        Examples
        --------
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
        >>> mp = gyrostat.stability_map(sat, 1.0, [0.0, 0.3], k2=[0.0, 0.02])
        >>> mp.restricted_stable
        array([[False,  True],
               [False,  True]])
        """
        return (self.r1 > 0) & (self.r2 > 0) & (self.r3 > 0)

    @property
    def shape(self) -> tuple[int, ...]:
        """The shape of the grid.

        Examples
        --------
        >>> from rigidbody import gyrostat
        >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
        >>> mp = gyrostat.stability_map(sat, 1.0, [0.0, 0.3], k2=[0.0, 0.02])
        >>> mp.shape
        (2, 2)
        """
        return self.code.shape


def stability_map(
    sat: Satellite,
    R0: Any,
    theta0: Any,
    k2: Any = None,
    k3: Any = None,
    *,
    omega_sign: int = 1,
    grid: bool = True,
    rtol: float = 1e-12,
    **overrides: Any,
) -> StabilityMap:
    """Verdicts for the motions (2.3) over arrays of parameters, in one vectorised call.

    Parameters
    ----------
    sat : Satellite
        Supplies M, A1, A2, A3, mu unless overridden.
    R0, theta0 : float or array_like
    k2, k3 : float or array_like
        Exactly one (the other is computed from (2.4)).
    omega_sign : {+1, -1}
    grid : bool
        If True (default), the 1-D arrays among the parameters are combined into an outer grid
        (``indexing='ij'``, axes in the order theta0, R0, k2, k3, M, A1, A2, A3, mu); if False the
        arrays are broadcast against each other as given.
    rtol : float
        Zero-eigenvalue threshold of the equilibrated second variation (see
        :func:`rigidbody.core.quadform.inertia`).
    **overrides : float or array_like
        Any of ``M, A1, A2, A3, mu`` to vary the body (e.g. ``A1=np.linspace(...)``).

    Returns
    -------
    StabilityMap

    See Also
    --------
    stability : one motion, with its second variation.
    normalized_stability_map : the map in the plane (theta0, k2 / (omega0 Abar)).
    exact_boundaries : the boundaries of the verdicts as curves k2(theta0).
    rigidbody.plotting.stability_map_plot : draws the verdicts.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eqs. (2.3)-(2.5).

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> mp = gyrostat.stability_map(sat, 1.0, np.linspace(-1.2, 1.2, 5), k2=np.linspace(-0.05, 0.05, 4))
    >>> mp.code.shape
    (5, 4)

    At :math:`\theta_0 = 0`, :math:`k_2 = 0` the degree of instability is odd, as the end of section 2 says
    when :math:`s_2 < 0 < s_3`:

    >>> mp = gyrostat.stability_map(sat, 1.0, 0.0, k2=0.0)
    >>> str(mp.verdict), int(mp.degree), bool(mp.s2 < 0 < mp.s3)
    ('unstable', 1, True)
    """
    if not isinstance(sat, Satellite):
        raise TypeError(f"sat must be a Satellite; got {type(sat).__name__}")
    bad = set(overrides) - {"M", "A1", "A2", "A3", "mu"}
    if bad:
        raise TypeError(f"unknown parameter(s) {sorted(bad)}; overridable: M, A1, A2, A3, mu")
    if (k2 is None) == (k3 is None):
        raise TypeError("give exactly one of k2 and k3")
    omega_sign = check_omega_sign(omega_sign)
    vals: dict[str, Any] = {
        "theta0": theta0, "R0": R0, "k2": k2, "k3": k3,
        "M": overrides.get("M", sat.M), "A1": overrides.get("A1", sat.A1), "A2": overrides.get("A2", sat.A2),
        "A3": overrides.get("A3", sat.A3), "mu": overrides.get("mu", sat.mu),
    }
    arrs = float_arrays(vals)
    if grid:
        axes = [n for n in _MAP_ORDER if n in arrs and arrs[n].ndim == 1 and arrs[n].size != 1]
        if any(arrs[n].ndim > 1 for n in arrs):
            raise ValueError("with grid=True pass 1-D arrays (or use grid=False and broadcastable arrays)")
        # sparse: the per-theta0 work runs on the 1-D axes, broadcasting does the rest
        mesh = np.meshgrid(*[arrs[n] for n in axes], indexing="ij", sparse=True) if axes else []
        for n, m in zip(axes, mesh):
            arrs[n] = m
    shape = broadcast_shape(arrs)
    kname = "k2" if "k2" in arrs else "k3"
    return _evaluate(arrs, shape, kname, omega_sign, rtol)


#: points per block of the evaluation: its temporaries stay in the CPU cache (2**14 doubles = 128 kB)
_BLOCK = 1 << 14

_SIDE_NAMES = ("M", "A1", "A2", "A3", "mu", "R0", "theta0")


def _physical(M: Any, A1: Any, A2: Any, A3: Any, mu: Any, R0: Any) -> Any:
    """A body (positive masses, triangle inequalities) that fits inside its orbit (_family.check_fits)."""
    with np.errstate(all="ignore"):
        return (
            (M > 0) & (A1 > 0) & (A2 > 0) & (A3 > 0) & (mu > 0) & (R0 > 0)
            & (A1 <= (A2 + A3) * (1 + 1e-12)) & (A2 <= (A1 + A3) * (1 + 1e-12)) & (A3 <= (A1 + A2) * (1 + 1e-12))
            & (R0**2 > (A1 + A2 + A3) / (2 * M))
        )


def _side(p: dict[str, np.ndarray], omega_sign: int, rtol: float, const: tuple[dict, dict] | None = None,
          work: Scratch | None = None) -> tuple[dict, dict]:
    fc, ec = (None, None) if const is None else const
    f = family_side(p["M"], p["A1"], p["A2"], p["A3"], p["mu"], p["R0"], p["theta0"], omega_sign, const=fc, work=work)
    return f, second_variation_side(f, p["M"], p["A1"], p["A2"], p["A3"], p["mu"], p["R0"], rtol=rtol, const=ec,
                                    work=work)


def _evaluate(arrs: dict[str, np.ndarray], shape: tuple[int, ...], kname: str, omega_sign: int,
              rtol: float) -> StabilityMap:
    """stability_map on broadcastable parameter arrays, block by block along the longest axis.

    Per block: the k2-free part of the family (2.4) and of the second variation on the shape of the
    parameters other than k2 / k3 (once per theta0 on a (theta0, k2) grid), then the few operations that
    involve k2 on the block.  The factors that involve only the body, mu and R0 are computed once; every
    block writes its intermediate quantities into the work arrays of the previous one (a :class:`Scratch`)
    and its results straight into the map's arrays.
    """
    nd = len(shape)
    pad = {n: a.reshape((1,) * (nd - a.ndim) + a.shape) for n, a in arrs.items()}
    side_shape = np.broadcast_shapes(*(pad[n].shape for n in _SIDE_NAMES))
    ax = int(np.argmax(shape)) if nd else 0
    n_ax = shape[ax] if nd else 1
    per = math.prod(shape) // max(n_ax, 1)
    step = max(1, _BLOCK // max(per, 1))
    side_cut = nd > 0 and side_shape[ax] == n_ax  # the side quantities vary along the blocked axis
    body = [pad[n] for n in ("M", "A1", "A2", "A3", "mu", "R0")]
    physical_all = _physical(*body) if all(b.size == 1 for b in body) else None  # once for a fixed body
    # (1-element factors as 0-d arrays: the padded theta0 has all nd axes, so the shapes of the results stay)
    const = (lean(family_constants(*body)), lean(entry_constants(*body)))
    work = Scratch()

    kfull = "k3" if kname == "k2" else "k2"  # the computed component; the given one is returned as a view
    full = {n: np.empty(shape) for n in (kfull, "s2", "s3")}
    degree = np.empty(shape, dtype=np.int64)
    code = np.empty(shape, dtype=np.int8)
    side = {n: np.empty(side_shape) for n in ("kappa0", "omega0", "s1")}

    def cut(a: Any, sl: slice) -> Any:
        if nd == 0 or not isinstance(a, np.ndarray) or a.ndim == 0 or a.shape[ax] != n_ax or n_ax == 1:
            return a
        return a[(slice(None),) * ax + (sl,)]

    def side_part(p: dict[str, np.ndarray], sl: slice) -> tuple[dict, dict, np.ndarray]:
        # kappa0, omega0 and s1 = W_g1g1 straight into the map's arrays
        outs = {"kappa0": cut(side["kappa0"], sl), "omega0": cut(side["omega0"], sl), "g1g1": cut(side["s1"], sl)}
        for n, a in outs.items():
            work.put(n, a)
        fc, ec = const
        if physical_all is None:  # the body varies: its factors too
            fc, ec = {k: cut(v, sl) for k, v in fc.items()}, {k: cut(v, sl) for k, v in ec.items()}
        f, d = _side(p, omega_sign, rtol, (fc, ec), work)
        for n, a in (("kappa0", f["kappa0"]), ("omega0", f["omega0"]), ("g1g1", d["g1g1"])):
            if a is not outs[n]:  # (a work array of another shape: copy)
                outs[n][...] = a
        if physical_all is None:
            valid = d["valid"] & _physical(*(p[n] for n in ("M", "A1", "A2", "A3", "mu", "R0")))
        else:
            valid = d["valid"] if physical_all else np.zeros_like(d["valid"])
        return f, d, valid

    if not side_cut:  # the side quantities do not vary along the blocked axis: compute them once
        with np.errstate(all="ignore"):
            shared = side_part(pad, slice(None))
    any_bad = False
    for i0 in range(0, n_ax, step):
        sl = slice(i0, i0 + step)
        p = {n: cut(pad[n], sl) for n in pad}
        blk: Any = (slice(None),) * ax + (sl,) if nd else ...  # (a 0-d map: its one element as a 0-d view)
        out: dict[str, np.ndarray] = {"s2": full["s2"][blk], "s3": full["s3"][blk], "n_neg": degree[blk],
                                      "code": code[blk]}
        with np.errstate(all="ignore"):
            f, d, valid = side_part(p, sl) if side_cut else shared
            if kname == "k2":
                k2 = p["k2"]
                # k3 by the first relation (2.4) (NaN where cos(theta0 + kappa0) = 0, see below):
                # k2 sin(theta0 + kappa0) / cos(..) + rest / (cos(..) omega0)
                icp = f["icp"]
                t = work.at(icp.shape)["_t0"]
                kc = np.multiply(k2, np.multiply(f["sin_tk"], icp, out=t), out=full[kfull][blk])
                x = np.multiply(f["rest"], icp, out=t)
                x /= f["omega0"]
                kc += x
            else:
                # k2 from k3 divides by sin(theta0 + kappa0): ill-conditioned near theta0 = 0, pi
                k2, _, _ = family_momentum(f, k3=p["k3"])
                full[kfull][blk] = k2
                valid = valid & (np.abs(f["sin_tk"]) > SINGULAR_TOL)
            # (a k2 or k3 that is not finite makes s2, s3 non-finite: verdicts() marks the point invalid)
            v = verdicts(d, k2, valid, rtol=rtol, out=out, work=work)
            if not v["valid"].all():  # invalid points: NaN quantities, degree -1
                any_bad = True
                bad = ~v["valid"]
                if kname == "k2":
                    full[kfull][blk][bad & (f["cos_tk"] == 0)] = np.nan
                full["s2"][blk][bad] = np.nan
                full["s3"][blk][bad] = np.nan
                degree[blk][bad] = -1

    def b(x: np.ndarray) -> np.ndarray:
        return np.broadcast_to(x, shape)

    s1 = b(side["s1"])
    if any_bad:
        s1 = np.where(code == -1, np.nan, s1)
    P = {n: np.broadcast_to(v, shape) for n, v in arrs.items()}
    ks = {kname: P[kname], kfull: full[kfull]}
    parts = {"side": {n: pad[n] for n in _SIDE_NAMES}, "omega_sign": omega_sign, "rtol": rtol}
    return StabilityMap(
        params=P, kappa0=b(side["kappa0"]), omega0=b(side["omega0"]), k2=ks["k2"], k3=ks["k3"],
        s1=s1, s2=full["s2"], s3=full["s3"], degree=degree, code=code, _parts=parts,
    )


def exact_boundaries(sat: Satellite, R0: float, theta0: Any, *, omega_sign: int = 1) -> dict[str, np.ndarray]:
    r"""The curves s2 = 0, s3 = 0 (exact) and r2 = 0, r3 = 0 (restricted) as k2(theta0).

    For fixed theta0 the motion's kappa0 and omega0 do not depend on k2, and k2 enters only W_b1b1
    (as ``omega0 k2 / cos(theta0 + kappa0)``) and W_b3b3 (as ``omega0 k2 / cos^3(theta0 + kappa0)``), so
    s2 and s3 = det a are *linear* in k2 and each boundary is one explicit curve.  ``s1`` and ``r1``
    do not depend on k2: their zeros are vertical lines, returned as ``s1`` and ``r1`` arrays over
    theta0 for the caller to locate sign changes (``theta_r1``: the closed-form roots of r1).

    Parameters
    ----------
    sat : Satellite
        The body (its ``k2``, ``k3`` are not used).
    R0 : float
        Orbit radius.
    theta0 : array_like
        Tilts (radians) at which the curves are evaluated.
    omega_sign : {+1, -1}
        Sign of omega0.

    Returns
    -------
    dict with keys ``theta0, s1, k2_s2, k2_s3, r1, k2_r2, k2_r3, theta_r1, omega0`` (NaN where undefined).

    See Also
    --------
    normalized_stability_map : the map with these curves in normalised units.
    restricted_conditions : the restricted quantities r1, r2, r3.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.5) and the restricted conditions after it.

    Examples
    --------
    s3 changes sign across the curve ``k2_s3`` at :math:`\theta_0 = 0.3`; the restricted curve
    :math:`r_2 = 0` is :math:`k_2 = -4\omega_0\cos^3\theta_0(A_2 - A_3)`, at :math:`\theta_0 = 0` with
    :math:`\omega_0 = \sqrt{1.009}` (see :func:`stationary_motion`):

    >>> import math
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> b = gyrostat.exact_boundaries(sat, 1.0, [0.0, 0.3])
    >>> for dk in (-1e-4, 1e-4):
    ...     m = gyrostat.stationary_motion(sat, 1.0, 0.3, k2=b["k2_s3"][1] + dk)
    ...     print(math.copysign(1.0, gyrostat.stability(m.satellite, m).s3))
    -1.0
    1.0
    >>> print(f"{b['k2_r2'][0]:.12f} {-4 * math.sqrt(1.009) * 0.002:.12f}")
    -0.008035919362 -0.008035919362
    """
    if not isinstance(sat, Satellite):
        raise TypeError(f"sat must be a Satellite; got {type(sat).__name__}")
    R0 = positive(R0, "R0")
    check_fits(sat, R0)
    omega_sign = check_omega_sign(omega_sign)
    th = np.asarray(theta0, dtype=float)
    f = family_arrays(sat.M, sat.A1, sat.A2, sat.A3, sat.mu, R0, th, k2=0.0, omega_sign=omega_sign)
    e = hessian_entries(sat.M, sat.A1, sat.A2, sat.A3, sat.mu, R0, th, f["kappa0"], f["omega0"], 0.0, f["S0"])
    a = a_matrix(e, th, f["kappa0"])
    om, cp = f["omega0"], f["cos_tk"]
    with np.errstate(divide="ignore", invalid="ignore"):
        s1 = e["g1g1"]
        s2_0 = e["g1g1"] * e["b1b1"] - e["b1g1"] ** 2
        k2_s2 = -s2_0 * cp / (s1 * om)
        C33 = a[..., 0, 0] * a[..., 1, 1] - a[..., 0, 1] ** 2
        k2_s3 = -np.linalg.det(a) * cp**3 / (om * C33)
        A1, A2, A3 = sat.A1, sat.A2, sat.A3
        ct, st2 = np.cos(th), np.sin(th) ** 2
        r1 = A1 - A2 * st2 - A3 * ct**2
        k2_r2 = -4 * om * ct**3 * (A2 - A3)
        k2_r3 = om * ct * (A1 - A2 - 3 * (A1 - A2) * (A2 - A3) * st2 / r1)
        x = (A1 - A3) / (A2 - A3) if A2 != A3 else np.nan
    roots = np.array([])
    if np.isfinite(x) and 0 <= x <= 1:
        t = np.arcsin(np.sqrt(x))
        roots = np.array([-np.pi + t, -t, t, np.pi - t])
    return {"theta0": th, "s1": s1, "k2_s2": k2_s2, "k2_s3": k2_s3, "r1": r1, "k2_r2": k2_r2,
            "k2_r3": k2_r3, "theta_r1": roots, "omega0": om}


def normalized_stability_map(
    sat: Satellite, R0: float, theta0: Any, u: Any, *, omega_sign: int = 1, rtol: float = 1e-12
) -> tuple[StabilityMap, dict[str, np.ndarray]]:
    """Verdicts on the grid ``theta0 x u`` with ``u = k2 / (omega0 Abar)`` (the plane of the paper-style maps).

    omega0 depends on theta0 (not on k2), so ``k2 = u omega0(theta0) Abar`` column by column.

    Parameters
    ----------
    sat : Satellite
        The body.
    R0 : float
        Orbit radius.
    theta0, u : array_like
        The axes of the grid: tilts (radians) and normalised gyrostatic components.
    omega_sign : {+1, -1}
        Sign of omega0.
    rtol : float
        Zero-eigenvalue threshold (see :func:`stability_map`).

    Returns
    -------
    (StabilityMap, boundaries)
        The map has shape ``(len(theta0), len(u))``; ``boundaries`` is :func:`exact_boundaries` with the
        k2-curves divided by ``omega0 Abar`` (keys ``u_s2, u_s3, u_r2, u_r3`` added).

    See Also
    --------
    rigidbody.plotting.normalized_map_plot : computes and draws it.

    References
    ----------
    :ref:`S. Ya. Stepanov, PMM 32 (1968) <ref-stepanov-1968>`, eq. (2.5) and the restricted conditions after it.

    Examples
    --------
    >>> import numpy as np
    >>> from rigidbody import gyrostat
    >>> sat = gyrostat.Satellite(M=1.0, A1=0.012, A2=0.010, A3=0.008)
    >>> mp, b = gyrostat.normalized_stability_map(sat, 1.0, np.linspace(-1.0, 1.0, 5), [-3.0, -1.0, 1.0, 3.0])
    >>> mp.shape
    (5, 4)
    >>> print(np.round(mp.k2[2] / (mp.omega0[2] * sat.Abar), 12))  # u, recovered from the map's k2
    [-3. -1.  1.  3.]
    """
    if not isinstance(sat, Satellite):
        raise TypeError(f"sat must be a Satellite; got {type(sat).__name__}")
    R0 = positive(R0, "R0")
    check_fits(sat, R0)
    omega_sign = check_omega_sign(omega_sign)
    th = np.asarray(theta0, dtype=float).ravel()
    uu = np.asarray(u, dtype=float).ravel()
    om = family_arrays(sat.M, sat.A1, sat.A2, sat.A3, sat.mu, R0, th, k2=0.0, omega_sign=omega_sign)["omega0"]
    k2 = uu[None, :] * (om * sat.Abar)[:, None]
    mp = stability_map(sat, R0, th[:, None], k2=k2, omega_sign=omega_sign, grid=False, rtol=rtol)
    b = exact_boundaries(sat, R0, th, omega_sign=omega_sign)
    for key in ("s2", "s3", "r2", "r3"):
        b[f"u_{key}"] = b[f"k2_{key}"] / (b["omega0"] * sat.Abar)
    return mp, b
