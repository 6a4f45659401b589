"""The regions (kind, sigma) the separatrix cuts the sphere of G into, and the four arcs (s1, s3) bounding them."""

from __future__ import annotations

from typing import Any, NamedTuple

from ._model import KINDS

__all__ = ["ARCS", "REGIONS", "Arc", "Region", "check_arc", "check_region", "next_arc", "region_arcs"]


Arc = tuple[int, int]


class Region(NamedTuple):
    """A region of the sphere of G cut by the separatrix: the kind of motion (``'max'``: rotation about the axis
    of A1, ``'min'``: about A3) and its sense ``sigma`` (+1/-1). A pair: equal to, and as a dict key the same
    as, the tuple ``(kind, sigma)`` (the public functions take and show regions as such tuples)."""

    kind: str
    sigma: int

    def __repr__(self) -> str:
        return repr((self.kind, self.sigma))

    @property
    def about_a1(self) -> bool:
        """Whether its motions rotate about the axis of A1 (the kind ``'max'``)."""
        return self.kind == "max"

    @property
    def h_sign(self) -> int:
        """The sign of the energy offset h = T - G^2/(2 A2) inside it: -1 about A1, +1 about A3."""
        return -1 if self.about_a1 else 1

    @classmethod
    def beside(cls, arc: Arc, h: float) -> Region:
        """The region next to ``arc`` on the side of energy offset ``h`` (< 0: about A1, with sigma = s1)."""
        return cls("max", arc[0]) if h < 0.0 else cls("min", arc[1])


#: The four arcs (s1, s3) of the separatrix: signs of g1 and g3 on them.
ARCS: tuple[Arc, ...] = ((1, 1), (1, -1), (-1, 1), (-1, -1))
#: The four regions (kind, sigma) the separatrix cuts the sphere into.
REGIONS: tuple[Region, ...] = (Region("max", 1), Region("max", -1), Region("min", 1), Region("min", -1))


def check_arc(arc: Any) -> Arc:
    try:
        s1, s3 = arc
    except (TypeError, ValueError):
        raise ValueError(f"arc must be a pair (s1, s3) of signs +1/-1, got {arc!r}") from None
    if s1 not in (1, -1) or s3 not in (1, -1):
        raise ValueError(f"arc must be a pair (s1, s3) of signs +1/-1, got {arc!r}")
    return int(s1), int(s3)


def check_region(region: Any, name: str = "region") -> Region:
    try:
        kind, sigma = region
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair (kind, sigma), e.g. ('min', 1), got {region!r}") from None
    if not isinstance(kind, str) or kind not in KINDS:
        raise ValueError(f"{name}: kind must be 'max' (rotation about the axis of A1) or 'min' (about A3), "
                         f"got {kind!r}")
    if sigma not in (1, -1):
        raise ValueError(f"{name}: sigma must be +1 or -1, got {sigma!r}")
    return Region(str(kind), int(sigma))


def region_arcs(region: Region) -> tuple[Arc, Arc]:
    """The two arcs bounding a region, in the order the motion runs along them (from ``+e2`` first)."""
    r = check_region(region)
    sigma = r.sigma
    if r.about_a1:
        return ((sigma, sigma), (sigma, -sigma))
    return ((sigma, sigma), (-sigma, sigma))


def next_arc(arc: Arc, h: float) -> Arc:
    """The arc followed after ``arc`` by a motion with energy offset ``h`` at the saddle where ``arc`` ends."""
    s1, s3 = arc
    return (s1, -s3) if h < 0.0 else (-s1, s3)
