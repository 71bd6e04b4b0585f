"""Which axis-aligned boxes overlap, without comparing every pair: sort and sweep.

The boxes are sorted by their lower x bound; a sweep keeps the boxes whose x interval is still
open and compares each new box with those only, all at once with numpy. The work is linear in
the boxes plus the pairs that overlap along x, so a scene of 1,000 bodies spread out costs
about 1,000 small array operations where a pair loop made 1,000,000 (and a scene where every
body overlaps every other is reported by the first overlap of each, not by every pair).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np


def first_overlaps(lo: np.ndarray, hi: np.ndarray, wanted: Sequence[bool],
                   allowed: Callable[[int, int], bool], margin: float = 0.0) -> dict[int, tuple[int, float]]:
    """For every box `i` with `wanted[i]`: (the lowest index `j` of a box it overlaps by more than
    `margin` on every axis with `allowed(i, j)`, the overlap's smallest extent). `lo`, `hi`: (n, 3)."""
    n = len(lo)
    found: dict[int, tuple[int, float]] = {}
    if n < 2:
        return found
    order = np.argsort(lo[:, 0], kind="stable")
    active = np.empty(0, dtype=np.int64)
    for i in order:
        i = int(i)
        if active.size:
            active = active[hi[active, 0] > lo[i, 0] + margin]  # closed for i and for every later box
            if active.size:
                depth = np.minimum(hi[active], hi[i]) - np.maximum(lo[active], lo[i])
                hits = np.flatnonzero(np.all(depth > margin, axis=1))
                if hits.size:
                    _record(found, i, active[hits], depth[hits].min(axis=1), wanted, allowed)
        active = np.append(active, i)
    return found


def _record(found: dict, i: int, others: np.ndarray, extents: np.ndarray, wanted, allowed) -> None:
    """Keep, for `i` and for each of `others`, the overlapping box of the lowest index."""
    if wanted[i]:
        for k in np.argsort(others, kind="stable"):
            j = int(others[k])
            if j >= found.get(i, (1 << 62, 0.0))[0]:
                break
            if allowed(i, j):
                found[i] = (j, float(extents[k]))
                break
    for j, extent in zip(others.tolist(), extents.tolist()):
        if wanted[j] and i < found.get(j, (1 << 62, 0.0))[0] and allowed(j, i):
            found[j] = (i, float(extent))
