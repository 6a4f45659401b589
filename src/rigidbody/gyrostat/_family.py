"""Closed-form evaluation of the family (2.3)-(2.4), vectorised, and the checks shared by its callers."""

from __future__ import annotations

import collections
import functools
import math
from typing import Any

import numpy as np

from ._model import Satellite

#: below this |cos| or |sin| a denominator of the family or of its chart is called near-singular
SINGULAR_TOL = 1e-6


def wrap_angle(theta: Any) -> Any:
    """Reduce an angle to (-pi, pi]; angles already there are returned unchanged (bit for bit).

    (Reducing every angle as ``(theta + pi) mod 2 pi - pi`` rounds it to the ulp of pi: theta0 = 1e-12
    came back as 1.00009e-12.)
    """
    t = np.asarray(theta, dtype=float)
    w = np.remainder(t + np.pi, 2 * np.pi) - np.pi
    w = np.where(w == -np.pi, np.pi, w)
    return np.where((t > -np.pi) & (t <= np.pi), t, w)


def check_omega_sign(omega_sign: Any) -> int:
    """``omega_sign`` must be the integer +1 or -1 (it multiplies omega0: any other value rescales it)."""
    if isinstance(omega_sign, (bool, np.bool_)) or omega_sign not in (1, -1):
        raise ValueError(f"omega_sign must be +1 or -1; got {omega_sign!r}")
    return int(omega_sign)


def float_arrays(vals: dict[str, Any]) -> dict[str, np.ndarray]:
    """The map parameters as float arrays (``TypeError`` naming the parameter otherwise); None is dropped."""
    out = {}
    for name, v in vals.items():
        if v is None:
            continue
        try:
            out[name] = np.asarray(v, dtype=float)
        except (TypeError, ValueError):
            raise TypeError(f"{name} must be a real number or an array of real numbers; got {v!r}") from None
    return out


def broadcast_shape(arrs: dict[str, np.ndarray]) -> tuple[int, ...]:
    """Common shape of the map parameters (``ValueError`` listing their shapes if they do not broadcast)."""
    try:
        return np.broadcast(*arrs.values()).shape
    except ValueError:
        shapes = ", ".join(f"{n} {a.shape}" for n, a in arrs.items() if a.ndim)
        raise ValueError(f"the parameter arrays do not broadcast together: {shapes}") from None


def check_fits(sat: Satellite, R0: float) -> None:
    """Reject an orbit radius the body does not fit into.

    The mean square distance of the mass from G is ``(A1 + A2 + A3) / (2 M)``.  If ``R0`` does not exceed
    its square root, some mass lies at least ``R0`` from G, where the second-order (MacCullagh) potential U
    of section 2 no longer describes any real body (its expansion about G diverges at O).
    """
    r2 = (sat.A1 + sat.A2 + sat.A3) / (2.0 * sat.M)
    if not R0 * R0 > r2:
        raise ValueError(
            f"R0 = {R0!r} must exceed the rms radius sqrt((A1 + A2 + A3)/(2 M)) = {math.sqrt(r2):.6g} of the body: "
            "otherwise the body does not fit inside its orbit (some mass lies at least R0 from G) and the "
            "second-order potential U of section 2 does not apply"
        )


class Arrays(dict[str, Any]):
    """Work arrays of one shape and dtype by name, created on first use and kept if ``keep``, else new on
    each request."""

    def __init__(self, shape: tuple[int, ...], dtype: Any, keep: bool) -> None:
        super().__init__()
        self.shape, self.dtype, self.keep = shape, dtype, keep

    def __missing__(self, name: str) -> np.ndarray:
        a = np.empty(self.shape, self.dtype)
        if self.keep:
            self[name] = a
        return a


#: the "arrays" of a single point without a scratch: None for every name (the ufunc returns a numpy scalar)
_NO_ARRAYS: dict[str, Any] = collections.defaultdict(type(None))
#: the dtypes the users of a Scratch name (float, bool, np.int8), by their numpy dtype
_DTYPES = {np.dtype(t): t for t in (float, bool, np.int8)}


class Scratch:
    """Named work arrays for the ``out=`` of ufuncs, kept from call to call.

    A map is evaluated in blocks of the same shape: with a ``Scratch`` every block writes its quantities into
    the arrays of the previous one instead of allocating (and page-faulting) fresh ones.  ``at(shape, dtype)``
    gives the arrays of that shape and dtype by name (``dtype`` one of float, bool, np.int8).
    ``Scratch(keep=False)`` allocates on every request (a single evaluation), and gives None for the shape
    (): each ufunc then returns a numpy scalar, and :meth:`ops` gives operators on numpy scalars, much
    quicker than ufunc calls (one point, as in ``stability``).  The code that uses a scratch therefore always
    takes the result an operation returns, and writes into a variable in place only through :func:`own`.
    The arrays a function returns live in the scratch: the next evaluation with the same scratch overwrites
    them.  Names starting with ``_t`` are temporaries that a function does not return (each function may
    reuse them; it calls no other user of the scratch while it holds them).
    """

    def __init__(self, keep: bool = True) -> None:
        self._keep = keep
        self._sets: dict[tuple[tuple[int, ...], Any], Any] = {}

    def at(self, shape: tuple[int, ...], dtype: Any = float) -> Any:
        if not self._keep:  # (nothing to keep: no growing cache of shapes)
            return _NO_ARRAYS if shape == () else Arrays(shape, dtype, False)
        key = (shape, dtype)
        a = self._sets.get(key)
        if a is None:
            a = self._sets[key] = Arrays(shape, dtype, True)
        return a

    def ops(self, shape: tuple[int, ...]) -> Any:
        """The ufuncs for quantities of this shape: NumPy's, or :class:`ScalarOps` for one point without a
        scratch (where the results are numpy scalars)."""
        return ScalarOps if not self._keep and shape == () else np

    def put(self, name: str, a: np.ndarray) -> None:
        """Let ``name`` (at the shape and dtype of ``a``) be written into ``a`` (an output array, or a view of one)."""
        self.at(a.shape, _DTYPES[a.dtype])[name] = a


#: the scratch of the evaluations without one (it keeps no arrays)
FRESH = Scratch(keep=False)


class ScalarOps:
    """The ufuncs the users of a :class:`Scratch` call, as Python operators on numpy scalars (``out`` is None):
    a ufunc call on a numpy scalar costs about 1 us, an operator a tenth of that; the IEEE operations are the
    same."""

    tan, arctan, sqrt, copysign = np.tan, np.arctan, np.sqrt, np.copysign

    @staticmethod
    def multiply(a: Any, b: Any, out: None = None) -> Any:
        return a * b

    @staticmethod
    def divide(a: Any, b: Any, out: None = None) -> Any:
        return a / b

    @staticmethod
    def add(a: Any, b: Any, out: None = None, dtype: Any = None) -> Any:
        return a + b if dtype is None else dtype(a) + dtype(b)

    @staticmethod
    def subtract(a: Any, b: Any, out: None = None) -> Any:
        return a - b

    @staticmethod
    def abs(a: Any, out: None = None) -> Any:
        return abs(a)

    @staticmethod
    def greater(a: Any, b: Any, out: None = None) -> Any:
        return a > b

    @staticmethod
    def less(a: Any, b: Any, out: None = None) -> Any:
        return a < b

    @staticmethod
    def not_equal(a: Any, b: Any, out: None = None) -> Any:
        return a != b

    @staticmethod
    def logical_xor(a: Any, b: Any, out: None = None) -> Any:
        return a ^ b

    @staticmethod
    def logical_not(a: Any, out: None = None) -> Any:
        return ~a


def own(x: Any) -> np.ndarray | None:
    """``x`` as the ``out=`` of an operation on itself if it is an array (a scalar is replaced instead)."""
    return x if isinstance(x, np.ndarray) else None


def common_shape(*vals: Any) -> tuple[int, ...]:
    """``np.broadcast_shapes`` of the arrays among ``vals`` (floats have no shape), quick when they share one."""
    shapes = {v.shape for v in vals if isinstance(v, np.ndarray)}
    if len(shapes) == 1:
        return shapes.pop()
    return np.broadcast_shapes(*shapes) if shapes else ()


def lean(c: dict[str, Any]) -> dict[str, Any]:
    """Factors with one element as 0-d arrays (an operation with a 0-d array skips both the broadcast of a
    1-element array and the conversion of a Python float; the arithmetic is the same).  Only for factors that
    multiply arrays of at least their own number of dimensions, so that the shape of the result stays."""
    return {k: fixed(v) if np.size(v) == 1 else v for k, v in c.items()}


def fixed(x: Any) -> np.ndarray:
    """``x`` (one number) as a read-only 0-d float array: the quickest scalar operand of a ufunc."""
    a = np.array(np.asarray(x, dtype=float).reshape(()))
    a.flags.writeable = False
    return a


#: scalar operands of the ufunc calls below
ZERO, HALF, ONE, TWO = fixed(0.0), fixed(0.5), fixed(1.0), fixed(2.0)


def sin_cos(theta: Any, work: Scratch | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``sin theta, cos theta, cos 2 theta`` to a couple of ulp (relative), from tangents.

    ``np.sin`` and ``np.cos`` of float64 arrays cost several times ``np.tan`` (no SIMD loops), and a map
    evaluates them at every point.  With ``T = tan theta`` (an ulp even next to pi/2):
    ``abs(cos theta) = 1 / sqrt(1 + T^2)``, ``sin theta = T cos theta``.  The sign of the cosine is that of
    ``T tan(theta/2)`` (``tan theta = 2 u / (1 - u^2)`` with ``u = tan(theta/2)``, and ``cos theta`` has the sign
    of ``1 - u^2``); ``cos 2 theta`` likewise from ``X = tan 2 theta``, with the sign of ``X T``.  Not as
    ``cos^2 - sin^2``: that has an absolute error of an ulp, so no correct digit at theta = pi/4, where the
    stable W_g2g2 needs it.  At theta = 0 the product of the tangents is +0 (positive sign).  ``work``: see
    :class:`Scratch`.
    """
    th = np.asarray(theta, dtype=float)
    w = FRESH if work is None else work
    wf, xp = w.at(th.shape), w.ops(th.shape)
    T = xp.tan(th, out=wf["_t0"])
    X = xp.multiply(th, TWO, out=wf["_t1"])
    X = xp.tan(X, out=own(X))
    ct = xp.multiply(T, T, out=wf["cos_t"])
    ct += ONE
    ct = xp.sqrt(ct, out=own(ct))
    ct = xp.divide(ONE, ct, out=own(ct))
    # cos > 0 for abs(theta) <= fl(pi/2) < pi/2 (a NaN takes the general route too)
    if th.size and not (np.maximum.reduce(th, axis=None) <= 0.5 * np.pi
                        and np.minimum.reduce(th, axis=None) >= -0.5 * np.pi):
        u = xp.multiply(th, HALF, out=wf["_t2"])
        u = xp.tan(u, out=own(u))
        u *= T
        ct = xp.copysign(ct, u, out=own(ct))
    st = xp.multiply(T, ct, out=wf["sin_t"])
    c2t = xp.multiply(X, X, out=wf["cos_2t"])
    c2t += ONE
    c2t = xp.sqrt(c2t, out=own(c2t))
    c2t = xp.divide(ONE, c2t, out=own(c2t))
    X *= T
    c2t = xp.copysign(c2t, X, out=own(c2t))
    return st, ct, c2t


def family_constants(M: Any, A1: Any, A2: Any, A3: Any, mu: Any, R0: Any) -> dict[str, Any]:
    """The factors of :func:`family_side` that involve only the body, mu and R0 (once per map, not per point)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        M, A1, A2, A3, mu, R0 = (np.asarray(v, dtype=float) for v in (M, A1, A2, A3, mu, R0))
        n0 = mu / R0**3
        MR2 = M * R0**2
        return {
            "n0": n0, "MR2": MR2, "A2": A2, "A3": A3, "A2-A3": A2 - A3, "3n0": 3 * n0,
            "n2:st2": 4.5 / MR2 * (A2 - A3) * -n0,  # n2 = n2:st2 sin^2 theta0 + n2:1
            "n2:1": n0 * (1 - 4.5 / MR2 * (2 * A3 - A1 - A2) / 3),
            "tk:stct": 3 * n0 * (A2 - A3) / MR2,  # tan kappa0 = tk:stct sin theta0 cos theta0 / n2
        }


@functools.lru_cache(maxsize=32)
def _scalar_constants(fn: Any, *body: float) -> dict[str, Any]:
    return {k: np.float64(v) for k, v in fn(*body).items()}


def constants(fn: Any, M: Any, A1: Any, A2: Any, A3: Any, mu: Any, R0: Any) -> dict[str, Any]:
    """``fn(M, A1, A2, A3, mu, R0)`` (:func:`family_constants` or ``_secondvar.entry_constants``), remembered as
    numpy scalars for a body of Python floats (the scalar API evaluates one body point after point)."""
    body = (M, A1, A2, A3, mu, R0)
    if all(type(v) is float for v in body):
        return _scalar_constants(fn, *body)
    return fn(*body)


def family_side(M: Any, A1: Any, A2: Any, A3: Any, mu: Any, R0: Any, theta0: Any,
                omega_sign: Any = 1, *, const: dict[str, Any] | None = None,
                work: Scratch | None = None) -> dict[str, np.ndarray]:
    """The part of the closed-form solution of (2.4) that does not involve the gyrostatic momentum.

    Returns arrays (broadcast over the inputs): ``n0 = mu / R0^3``, ``n2`` (the right-hand side of the second
    relation (2.4), omega0^2 cos^2 kappa0), ``exists`` (n2 > 0), ``kappa0``, ``omega0``, the sines and cosines
    ``sin_t, cos_t, cos_2t`` of theta0 and 2 theta0 (:func:`sin_cos`), ``sin_k, cos_k`` of kappa0 and
    ``sin_tk, cos_tk`` of theta0 + kappa0, ``S0`` and ``rest`` (the terms of the first relation
    (2.4) free of k2, k3); and the products the second variation needs (see ``gyrostat._secondvar._entries``).

    ``tan kappa0 = 3/2 (A2 - A3) mu R0^-3 sin 2 theta0 / (M R0^2 n2)`` (third relation divided by the second,
    kappa0 in (-pi/2, pi/2)), so ``cos kappa0 = 1 / sqrt(1 + tan^2)``, ``sin kappa0 = tan kappa0 cos kappa0``
    and the angle theta0 + kappa0 by the addition formulas.

    ``const``: :func:`family_constants` of the body (computed here if not given); ``work``: see :class:`Scratch`
    (a map passes both, once for all its blocks).  The quantities of theta0 alone keep its shape.
    """
    c = constants(family_constants, M, A1, A2, A3, mu, R0) if const is None else const
    w = FRESH if work is None else work
    with np.errstate(divide="ignore", invalid="ignore"):
        th = np.asarray(theta0, dtype=float)
        sgn = omega_sign if isinstance(omega_sign, int) else np.asarray(omega_sign, dtype=float)
        ts = th.shape
        s = common_shape(th, sgn, *c.values())
        st, ct, c2t = sin_cos(th, w)
        wf, wb, wt = w.at(s), w.at(s, bool), w.at(ts)
        xp = w.ops(s)
        mul = xp.multiply
        st2, stct = mul(st, st, out=wt["st2"]), mul(st, ct, out=wt["stct"])
        n2 = mul(c["n2:st2"], st2, out=wf["n2"])
        n2 += c["n2:1"]
        exists = xp.greater(n2, ZERO, out=wb["exists"])
        n2p = n2 if exists.all() else np.where(exists, n2, np.nan)
        tk = mul(c["tk:stct"], stct, out=wf["tk"])
        tk /= n2p
        kap = xp.arctan(tk, out=wf["kappa0"])
        sec2 = mul(tk, tk, out=wf["_t0"])
        sec2 += ONE
        ck = xp.sqrt(sec2, out=wf["cos_k"])
        ck = xp.divide(ONE, ck, out=own(ck))
        sk = mul(tk, ck, out=wf["sin_k"])
        om2 = mul(n2p, sec2, out=wf["om2"])
        om = xp.sqrt(om2, out=wf["omega0"])
        if not (isinstance(sgn, int) and sgn == 1) and np.any(sgn != 1):
            om *= sgn
        t = wf["_t1"]
        sp = mul(st, ck, out=wf["sin_tk"])
        sp += mul(ct, sk, out=t)
        cp = mul(ct, ck, out=wf["cos_tk"])
        cp -= mul(st, sk, out=t)
        cp2 = mul(cp, cp, out=wf["cp2"])
        # gravity moment about y1, exact form 3/2 mu R0^-3 (A2 - A3) sin 2 theta0, and the centrifugal term:
        # rest = (A2 - A3) (omega0^2 sin(theta0 + kappa0) cos(theta0 + kappa0) + 3 n0 sin theta0 cos theta0)
        rest = mul(sp, cp, out=wf["rest"])
        rest *= om2
        rest += mul(c["3n0"], stct, out=t)
        rest *= c["A2-A3"]
        ck2 = mul(ck, ck, out=wf["ck2"])
        S0 = mul(c["MR2"], ck2, out=wf["S0"])  # M R0^2 cos^2 kappa0 + A2 cos^2(theta0 + kappa0) + A3 sin^2(..)
        S0 += mul(c["A2"], cp2, out=t)
        x = mul(sp, sp, out=t)
        x *= c["A3"]
        S0 += x
        ct2 = mul(ct, ct, out=wt["ct2"])
        icp = xp.divide(ONE, cp, out=wf["icp"])
    return {"n0": c["n0"], "n2": n2, "exists": exists, "theta0": th, "kappa0": kap, "omega0": om, "sin_t": st,
            "cos_t": ct, "cos_2t": c2t, "sin_k": sk, "cos_k": ck, "sin_tk": sp, "cos_tk": cp, "S0": S0,
            "rest": rest,
            # the same under the short names of the bundle that gyrostat._secondvar._entries reads
            "st": st, "ct": ct, "c2t": c2t, "sk": sk, "ck": ck, "tk": tk, "sp": sp, "cp": cp, "om": om, "om2": om2,
            "S": S0, "st2": st2, "stct": stct, "ct2": ct2, "icp": icp, "ck2": ck2, "cp2": cp2}


def family_momentum(f: dict[str, np.ndarray], k2: Any = None, k3: Any = None
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The gyrostatic component missing from ``k2``/``k3`` by the first relation (2.4), for :func:`family_side`
    output ``f``; returns ``(k2, k3, ok)`` with ``ok`` False where the denominator cos(theta0 + kappa0) (k2
    given) or sin(theta0 + kappa0) (k3 given) vanishes (NaN there)."""
    if (k2 is None) == (k3 is None):
        raise TypeError("give exactly one of k2 and k3")
    om, sp, cp, rest = f["omega0"], f["sin_tk"], f["cos_tk"], f["rest"]
    with np.errstate(divide="ignore", invalid="ignore"):
        if k3 is None:
            k2v = np.asarray(k2, dtype=float)
            ok = cp != 0
            k3v = np.where(ok, (om * k2v * sp + rest) / (om * np.where(ok, cp, 1.0)), np.nan)
        else:
            k3v = np.asarray(k3, dtype=float)
            ok = sp != 0
            k2v = np.where(ok, (om * k3v * cp - rest) / (om * np.where(ok, sp, 1.0)), np.nan)
    return k2v, k3v, ok


def family_arrays(
    M: Any, A1: Any, A2: Any, A3: Any, mu: Any, R0: Any, theta0: Any,
    k2: Any = None, k3: Any = None, omega_sign: Any = 1,
) -> dict[str, np.ndarray]:
    """Vectorised closed-form solution of (2.4); all inputs broadcast.

    Returns a dict of arrays: ``n2`` (the right-hand side of the second relation (2.4), omega0^2
    cos^2 kappa0), ``kappa0``, ``omega0``, ``k2``, ``k3``, ``S0``, ``k``, ``lambda0``, and ``exists``
    (False where n2 <= 0 or the required denominator vanishes).  No warnings are emitted here.

    Derivation: dividing the third relation of (2.4) by the second gives
    ``tan kappa0 = 3/2 (A2 - A3) mu R0^-3 sin 2 theta0 / (M R0^2 n2)`` (kappa0 in (-pi/2, pi/2)),
    then ``omega0 = omega_sign sqrt(n2) / cos kappa0``; the first relation is linear in (k2, k3)
    (:func:`family_side`, :func:`family_momentum`).
    """
    if (k2 is None) == (k3 is None):
        raise TypeError("give exactly one of k2 and k3")
    f = family_side(M, A1, A2, A3, mu, R0, theta0, omega_sign)
    k2v, k3v, ok = family_momentum(f, k2, k3)
    om, sp, cp = f["omega0"], f["sin_tk"], f["cos_tk"]
    shape = np.broadcast_shapes(om.shape, k2v.shape, k3v.shape)

    def full(x: np.ndarray) -> np.ndarray:
        return np.array(np.broadcast_to(x, shape))

    lam = np.asarray(M, dtype=float) * np.asarray(R0, dtype=float) ** 2 * f["om2"] * f["sin_k"]  # M R0^2 om0^2 sin ka0
    return {
        "theta0": full(f["theta0"]), "n2": full(f["n2"]), "kappa0": full(f["kappa0"]), "omega0": full(om),
        "k2": full(k2v), "k3": full(k3v), "S0": full(f["S0"]), "k": om * f["S0"] + k2v * cp + k3v * sp,
        "lambda0": full(lam), "exists": f["exists"] & ok, "sin_tk": full(sp), "cos_tk": full(cp),
        "sin_t": full(f["sin_t"]), "cos_t": full(f["cos_t"]),
    }
