"""From the ridge mask to one ordered chain of pixels: skeleton, crossings, spurs and gaps.

Conventions: the mask is indexed [row, column]; chains are (M, 2) float arrays of pixel centres
(x, y) = (column, row), ordered from one free end of the line to the other.

Method: the mask is thinned to a one-pixel skeleton (``skimage.morphology.skeletonize``).  A
skeleton pixel is a junction when the skeleton leaves a ring of radius 2 around it in three or
more places (a thin line leaves it in two, whatever its staircase).  Discs around junctions are
cut out (the Hessian sees two lines there, so the centre is unreliable) and what is left falls
into segments, each a simple path.  The walk starts at a free end and, arriving at a crossing,
leaves by the unused segment that continues its direction best (a smooth curve goes straight
through its own crossing).  Short side branches (spurs) are ignored.  Pieces of a broken line
are joined end to end across small gaps when their ends point at each other.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy import ndimage
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import dijkstra

from curverecon.trace.options import TraceOptions

_RING = np.array(
    [(-2, -2), (-2, -1), (-2, 0), (-2, 1), (-2, 2), (-1, 2), (0, 2), (1, 2), (2, 2), (2, 1)]
    + [(2, 0), (2, -1), (2, -2), (1, -2), (0, -2), (-1, -2)]
)
"""The 16 pixels at Chebyshev distance 2 around a pixel, in circular order (row, column)."""


class TraceFailure(Exception):
    """A frame that cannot be traced; the message is the reason written to frames_skipped."""


@dataclass
class Chain:
    """An ordered chain of pixel centres (x, y) and what was found on the way."""

    points: np.ndarray
    crossings: int = 0
    gaps: list[float] = field(default_factory=list)
    untraced_length: float = 0.0


@dataclass
class _Segment:
    pts: np.ndarray  # (M, 2) x, y in order
    ends: list[int]  # junction cluster at each end (0: free end)


def _order_path(rc: np.ndarray) -> np.ndarray:
    """Pixels (row, col) of a thin connected set in path order: the two ends are the pair
    farthest apart along the set (two sweeps of Dijkstra over 8-neighbour steps)."""
    n = len(rc)
    if n <= 2:
        return rc
    index = {(int(r), int(c)): i for i, (r, c) in enumerate(rc)}
    rows, cols, w = [], [], []
    for i, (r, c) in enumerate(rc):
        for dr in (-1, 0, 1):
            for dc in (-1, 0, 1):
                j = index.get((int(r) + dr, int(c) + dc))
                if j is not None and j > i:
                    rows.append(i)
                    cols.append(j)
                    w.append(1.4142135 if dr and dc else 1.0)
    g = coo_matrix((w, (rows, cols)), shape=(n, n)).tocsr()
    d0 = dijkstra(g, directed=False, indices=0)
    d0[~np.isfinite(d0)] = -1
    u = int(np.argmax(d0))
    du, pred = dijkstra(g, directed=False, indices=u, return_predecessors=True)
    du[~np.isfinite(du)] = -1
    v = int(np.argmax(du))
    path = [v]
    while path[-1] != u:
        path.append(int(pred[path[-1]]))
    return rc[path[::-1]]


def _junctions(skel: np.ndarray) -> np.ndarray:
    """Boolean image of junction pixels: the skeleton crosses the radius-2 ring 3+ times."""
    nb = ndimage.convolve(skel.astype(np.uint8), np.ones((3, 3), np.uint8), mode="constant")
    cand = np.argwhere(skel & (nb >= 4))
    out = np.zeros_like(skel)
    h, w = skel.shape
    for r, c in cand:
        rr, cc = r + _RING[:, 0], c + _RING[:, 1]
        inside = (rr >= 0) & (rr < h) & (cc >= 0) & (cc < w)
        ring = np.zeros(len(_RING), bool)
        ring[inside] = skel[rr[inside], cc[inside]]
        runs = int(np.sum(ring & ~np.roll(ring, 1)))
        if runs >= 3:
            out[r, c] = True
    return out


def _direction(pts: np.ndarray, k: int) -> np.ndarray:
    """Unit direction from pts[0] into the chain, over its first k points."""
    q = pts[min(k, len(pts) - 1)] - pts[0]
    n = float(np.hypot(*q))
    return q / n if n > 0 else np.array([1.0, 0.0])


def _walk_component(comp: np.ndarray, options: TraceOptions) -> Chain:
    """One skeleton component (boolean image) as a chain from a free end to the other."""
    w = options.width
    rad = options.junction_radius_widths * w
    junction = _junctions(comp)
    if not junction.any():
        pts = _order_path(np.argwhere(comp))[:, ::-1].astype(float)
        return Chain(pts)
    yy, xx = np.mgrid[-int(rad) - 1 : int(rad) + 2, -int(rad) - 1 : int(rad) + 2]
    disc = (xx**2 + yy**2) <= rad**2
    cut = ndimage.binary_dilation(junction, structure=disc)
    clusters, _ = ndimage.label(ndimage.binary_dilation(cut, iterations=2))
    segs_img, n_seg = ndimage.label(comp & ~cut, structure=np.ones((3, 3)))
    spur = options.spur_widths * w
    segments: list[_Segment] = []
    for lab, sl in enumerate(ndimage.find_objects(segs_img), start=1):
        rc = np.argwhere(segs_img[sl] == lab) + [sl[0].start, sl[1].start]
        rc = _order_path(rc)
        ends = [int(clusters[tuple(rc[0])]), int(clusters[tuple(rc[-1])])]
        length = float(np.hypot(*np.diff(rc, axis=0).T).sum()) if len(rc) > 1 else 0.0
        if length < spur and 0 in ends:
            continue  # a spur (or a crumb at a free end)
        if length < 2 and ends[0] == ends[1]:
            continue
        segments.append(_Segment(rc[:, ::-1].astype(float), ends))
    # a junction left with one segment end (its other branches were spurs, e.g. the fork
    # that thinning leaves at a blunt end) is no junction: that end is free
    attached: dict[int, int] = {}
    for s in segments:
        for node in s.ends:
            attached[node] = attached.get(node, 0) + 1
    for s in segments:
        lone = [e for e in (0, 1) if s.ends[e] != 0 and attached.get(s.ends[e], 0) == 1]
        for e in lone:  # grow the segment back through the cut disc, along its longest arm
            rc = s.pts[:, ::-1].astype(int)
            extra = np.argwhere(comp & (clusters == s.ends[e]))
            path = _order_path(np.vstack([rc, extra]))
            keep_end = rc[-1 if e == 0 else 0]
            if np.abs(path[0] - keep_end).sum() < np.abs(path[-1] - keep_end).sum():
                path = path[::-1]
            if e == 1:
                path = path[::-1]
            s.pts = path[:, ::-1].astype(float)
            s.ends[e] = 0
    free = [(i, e) for i, s in enumerate(segments) for e in (0, 1) if s.ends[e] == 0]
    if len(free) == 0:
        raise TraceFailure("the line has no free ends (closed, or its ends are not visible)")
    if len(free) > 2:
        raise TraceFailure(f"the line branches ({len(free)} free ends)")
    if len(free) == 1:
        raise TraceFailure("the line has one free end only (it ends in a loop or a blob)")
    k = max(3, int(round(2 * w)))
    used = [False] * len(segments)
    i, e = free[0]
    pieces = []
    crossings = 0
    while True:
        used[i] = True
        pts = segments[i].pts if e == 0 else segments[i].pts[::-1]
        pieces.append(pts)
        node = segments[i].ends[1 - e]
        if node == 0:
            break
        d_in = -_direction(pts[::-1], k)
        best, best_dot = None, -np.inf
        for j, s in enumerate(segments):
            if used[j]:
                continue
            for ej in (0, 1):
                if s.ends[ej] == node:
                    q = s.pts if ej == 0 else s.pts[::-1]
                    dot = float(d_in @ _direction(q, k))
                    if dot > best_dot:
                        best, best_dot = (j, ej), dot
        if best is None:
            raise TraceFailure("the line ends at a junction (a branch the walk cannot leave)")
        crossings += 1
        i, e = best
    untraced = sum(
        float(np.hypot(*np.diff(s.pts, axis=0).T).sum())
        for s, u in zip(segments, used, strict=True)
        if not u
    )
    return Chain(np.vstack(pieces), crossings=crossings // 2, untraced_length=untraced)


def trace_chain(mask: np.ndarray, options: TraceOptions) -> Chain:
    """The line in a ridge mask as one ordered chain (see the module docstring).

    Raises :class:`TraceFailure` when no line, a branching line, a closed line or pieces that
    cannot be joined are found.
    """
    from skimage.morphology import skeletonize

    if not mask.any():
        raise TraceFailure("no line found (no ridge above the noise)")
    skel = skeletonize(mask)
    lab, n = ndimage.label(skel, structure=np.ones((3, 3)))
    sizes = np.bincount(lab.ravel(), minlength=n + 1)[1:]
    w = options.width
    keep = [i + 1 for i in np.argsort(-sizes) if sizes[i] >= options.spur_widths * w]
    if not keep:
        raise TraceFailure("no line found (only specks)")
    chains = []
    objects = ndimage.find_objects(lab)
    for label in keep:
        sl = objects[label - 1]
        pad = (
            slice(max(sl[0].start - 3, 0), sl[0].stop + 3),
            slice(max(sl[1].start - 3, 0), sl[1].stop + 3),
        )
        sub = lab[pad] == label
        ch = _walk_component(sub, options)
        ch.points = ch.points + [pad[1].start, pad[0].start]
        chains.append(ch)
    return _join(chains, options)


def _join(chains: list[Chain], options: TraceOptions) -> Chain:
    """Join pieces end to end (largest first) across gaps that their ends point across."""
    w = options.width
    max_gap = options.max_gap_widths * w
    cos_lim = np.cos(np.radians(options.max_gap_angle_deg))
    k = max(3, int(round(2 * w)))
    chains = sorted(chains, key=lambda c: -len(c.points))
    main = chains[0]
    rest = chains[1:]
    gaps: list[float] = list(main.gaps)
    crossings = main.crossings
    untraced = main.untraced_length
    pts = main.points
    while rest:
        best = None
        for j, ch in enumerate(rest):
            for at_end in (False, True):  # join to the start or the end of pts
                for rev in (False, True):
                    q = ch.points[::-1] if rev else ch.points
                    if at_end:
                        p_end, d_end = pts[-1], -_direction(pts[::-1], k)
                        q_end, d_q = q[0], _direction(q, k)
                    else:
                        p_end, d_end = pts[0], -_direction(pts, k)
                        q_end, d_q = q[-1], _direction(q[::-1], k)
                    gap = q_end - p_end
                    dist = float(np.hypot(*gap))
                    if dist > max_gap:
                        continue
                    u = gap / dist if dist > 0 else d_end
                    if d_end @ u < cos_lim or d_q @ u < cos_lim:
                        continue
                    if best is None or dist < best[0]:
                        best = (dist, j, at_end, q)
        if best is None:
            break
        dist, j, at_end, q = best
        pts = np.vstack([pts, q]) if at_end else np.vstack([q, pts])
        gaps.append(dist)
        crossings += rest[j].crossings
        untraced += rest[j].untraced_length
        rest.pop(j)
    left = sum(float(np.hypot(*np.diff(c.points, axis=0).T).sum()) for c in rest)
    total = float(np.hypot(*np.diff(pts, axis=0).T).sum())
    if left > 0.1 * total:
        raise TraceFailure(
            f"the line is broken into {len(rest) + 1} pieces that cannot be joined "
            f"({left:.0f} px of {left + total:.0f} px left over)"
        )
    return Chain(pts, crossings=crossings, gaps=gaps, untraced_length=untraced + left)
