"""The regions (kind, sigma) the separatrix cuts the sphere of G into, and the four arcs (s1, s3) bounding them."""

from __future__ import annotations

from typing import Any

from ._model import KINDS

__all__ = ["ARCS", "REGIONS", "Arc", "Region", "check_arc", "check_region", "next_arc", "region_arcs"]


#: The four arcs (s1, s3) of the separatrix: signs of g1 and g3 on them.
ARCS: tuple[tuple[int, int], ...] = ((1, 1), (1, -1), (-1, 1), (-1, -1))
#: The four regions (kind, sigma) the separatrix cuts the sphere into.
REGIONS: tuple[tuple[str, int], ...] = (("max", 1), ("max", -1), ("min", 1), ("min", -1))

Region = tuple[str, int]
Arc = tuple[int, int]


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
    return str(kind), int(sigma)


def region_arcs(region: Region) -> tuple[Arc, Arc]:
    """The two arcs bounding a region, in the order the motion runs along them (from ``+e2`` first)."""
    kind, sigma = check_region(region)
    if kind == "max":
        return ((sigma, sigma), (sigma, -sigma))
    return ((sigma, sigma), (-sigma, sigma))


def next_arc(arc: Arc, h: float) -> Arc:
    """The arc followed after ``arc`` by a motion with energy offset ``h`` at the saddle where ``arc`` ends."""
    s1, s3 = arc
    return (s1, -s3) if h < 0.0 else (-s1, s3)
