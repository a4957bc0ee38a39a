"""Correspondence between two views of a flat (planar) curve (paper, section 5 and section 2).

Perspective, three traceable points A, B, C of the curve and the tangents at A and B (section 5):
D is where the tangents meet, E = AB x DC. For a query X' on view 0's curve, Y' = A'B' x D'X';
the double quotient (cross-ratio) of A, B, E, Y on line AB is the same in both views
(equations (15)-(17)), which fixes Y'' on A''B''; X'' is where D''Y'' meets view 1's curve.

Orthographic, two traceable points (section 2's table, first row, after Lee): D from the tangents,
Y' = A'B' x D'X' as above, and Y'' divides A''B'' in the same ratio as Y' divides A'B' (Thales:
parallel projection keeps ratios along a line); X'' is where D''Y'' meets view 1's curve.

Ambiguity (the line D''Y'' may meet the curve several times) is resolved by continuity: the map
from view 0's curve to view 1's curve keeps the order from A to B, so the correspondence of
relative arc positions is monotone. It is traced at samples along view 0's curve (every crossing
of D''Y'' a candidate) by dynamic programming (monotone, least jumping, from A to B), and each
query takes the crossing of its own line D''Y'' nearest to that path. Without a path, the j-th
crossing (in curve order) of D'X' in view 0 maps to the j-th of D''Y'' in view 1.

Noisy polylines (estimated noise > 0.05 px) are smoothed before intersecting; crossings are
refined on the local cubic through the neighbouring vertices. The construction is inherently
ill-conditioned near A and B, where D'X' is nearly the tangent and meets the curve at a grazing
angle (noise-free this costs nothing measurable; with 0.5 px noise the error there reaches tens of
pixels while the median stays ~0.3 px).

Coordinates are image pixels; points are handled in homogeneous form so points at infinity (E or
Y when lines are parallel in the image) need no special case.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from curverecon.curve import polyline as pl

FORMAT_IN = "curverecon.flat-views/1"
FORMAT_OUT = "curverecon.matches/1"
PROJECTIONS = ("perspective", "orthographic")

#: |sin| of the angle between the two tangent lines below which they count as parallel (no D).
MAX_COORDINATE = 1e12
"""Image coordinates beyond this are refused: no image is that large, and the construction's
products of coordinates would overflow (found by tests/test_fuzz.py with values near 1e300)."""

MIN_TANGENT_SIN = 1e-3
#: Samples along view 0's curve used to trace the continuity path (ambiguous crossings).
CONTINUITY_SAMPLES = 150
#: Estimated polyline noise (pixels) above which curves are smoothed before intersecting.
NOISE_TO_SMOOTH = 0.05
#: |sin| of the angle at the corners of a triangle of A, B, C, D below which it is degenerate.
MIN_TRIANGLE_SIN = 1e-3


def _error(message: str) -> Exception:
    from curverecon.errors import CurveReconError

    return CurveReconError(message)


@dataclass
class FlatView:
    """One view of the flat curve (image pixels). ``C`` is None for orthographic input."""

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray | None
    tangent_A: np.ndarray
    tangent_B: np.ndarray
    curve: np.ndarray


def _point(value: object, what: str) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise _error(f"{what}: must be [x, y] numbers") from None
    if arr.shape != (2,):
        raise _error(f"{what}: must be [x, y], got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise _error(f"{what}: contains NaN or infinite values")
    return arr


def parse_view(view: Mapping[str, object] | FlatView, projection: str, index: int) -> FlatView:
    """Validate one view (a JSON-like mapping or a :class:`FlatView`) and return a FlatView.

    The curve is reversed if its first point is nearer B than A (it must run from A to B).
    Missing tangents are estimated from the curve with
    :func:`curverecon.curve.polyline.end_tangents`.
    """
    name = f"view {index}"
    if isinstance(view, FlatView):
        view = {
            "A": view.A,
            "B": view.B,
            "C": view.C,
            "tangent_A": view.tangent_A,
            "tangent_B": view.tangent_B,
            "curve": view.curve,
        }
    if not isinstance(view, Mapping):
        raise _error(f"{name}: must be an object")
    for key in ("A", "B", "curve"):
        if view.get(key) is None:
            raise _error(f"{name}: missing {key!r}")
    a = _point(view["A"], f"{name} A")
    b = _point(view["B"], f"{name} B")
    c = None
    if projection == "perspective":
        if view.get("C") is None:
            raise _error(f"{name}: perspective input needs a third traceable point 'C'")
        c = _point(view["C"], f"{name} C")
    curve = pl.as_polyline(view["curve"], name=f"{name} curve")
    if np.hypot(*(curve[0] - b)) < np.hypot(*(curve[0] - a)):
        curve = curve[::-1].copy()
    if view.get("tangent_A") is None or view.get("tangent_B") is None:
        ta_est, tb_est = pl.end_tangents(curve)
    ta = (
        _point(view["tangent_A"], f"{name} tangent_A")
        if view.get("tangent_A") is not None
        else ta_est
    )
    tb = (
        _point(view["tangent_B"], f"{name} tangent_B")
        if view.get("tangent_B") is not None
        else tb_est
    )
    for p, what in ((a, "A"), (b, "B"), (c, "C"), (curve, "curve")):
        if p is not None and np.max(np.abs(p)) > MAX_COORDINATE:
            raise _error(f"{name} {what}: coordinates beyond {MAX_COORDINATE:.0e} (not an image)")
    for t, what in ((ta, "tangent_A"), (tb, "tangent_B")):
        if not np.max(np.abs(t)) > 0:
            raise _error(f"{name} {what}: zero vector")
    # a direction of any length: one of extreme length scaled to unit length (a 1e308-long
    # one would overflow); others kept as given, so that results do not move by rounding
    ta, tb = (_unit_if_extreme(t) for t in (ta, tb))
    if not np.hypot(*(b - a)) > 0:
        raise _error(f"{name}: A and B coincide")
    return FlatView(A=a, B=b, C=c, tangent_A=ta, tangent_B=tb, curve=curve)


def _unit_if_extreme(t: np.ndarray) -> np.ndarray:
    m = float(np.max(np.abs(t)))
    if 1.0 / MAX_COORDINATE <= m <= MAX_COORDINATE:
        return t
    t = t / m
    return t / np.hypot(*t)


def _h(p: np.ndarray) -> np.ndarray:
    return np.array([p[0], p[1], 1.0])


def _line(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Homogeneous line through two homogeneous points."""
    return np.cross(p, q)


def _sin_between(u: np.ndarray, v: np.ndarray) -> float:
    return float(abs(u[0] * v[1] - u[1] * v[0]) / (np.hypot(*u) * np.hypot(*v)))


def _collinear_sin(p: np.ndarray, q: np.ndarray, r: np.ndarray) -> float:
    """Smallest |sin| of the corner angles of the triangle of three homogeneous points.

    A point at infinity (w = 0) stands for a direction; the measure then is the |sin| of the angle
    between that direction and the line through the other two points.
    """
    pts = [p, q, r]
    fin = [abs(x[2]) > 1e-12 * max(1.0, float(np.abs(x[:2]).max())) for x in pts]
    eu = [x[:2] / x[2] if f else x[:2] for x, f in zip(pts, fin, strict=True)]
    sins = []
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        if fin[i] and fin[j] and fin[k]:
            u, v = eu[j] - eu[i], eu[k] - eu[i]
            if not (np.hypot(*u) > 0 and np.hypot(*v) > 0):
                return 0.0
            sins.append(_sin_between(u, v))
        elif not fin[i] and fin[j] and fin[k]:
            u = eu[k] - eu[j]
            if not np.hypot(*u) > 0:
                return 0.0
            return _sin_between(eu[i], u)
    return min(sins) if sins else 0.0


@dataclass
class _Frame:
    """Homogeneous construction points of one view."""

    A: np.ndarray
    B: np.ndarray
    D: np.ndarray
    E: np.ndarray | None  # perspective only


def _construct(view: FlatView, projection: str, index: int) -> _Frame:
    name = f"view {index}"
    if _sin_between(view.tangent_A, view.tangent_B) < MIN_TANGENT_SIN:
        raise _error(f"{name}: the tangents at A and B are parallel, so there is no point D")
    a, b = _h(view.A), _h(view.B)
    la = _line(a, _h(view.A + view.tangent_A))
    lb = _line(b, _h(view.B + view.tangent_B))
    d = np.cross(la, lb)
    d = d / d[2]  # finite: tangents are not parallel
    if _collinear_sin(a, b, d) < MIN_TRIANGLE_SIN:
        raise _error(
            f"{name}: A, B and the tangents' meeting point D are collinear (degenerate "
            "configuration: a tangent lies along AB or the curve's plane is seen edge-on)"
        )
    e = None
    if projection == "perspective":
        assert view.C is not None
        c = _h(view.C)
        if _collinear_sin(a, b, c) < MIN_TRIANGLE_SIN:
            raise _error(f"{name}: C lies on the line AB (degenerate configuration)")
        if _collinear_sin(a, c, d) < MIN_TRIANGLE_SIN or _collinear_sin(b, c, d) < MIN_TRIANGLE_SIN:
            raise _error(f"{name}: C lies on a tangent line through D (degenerate configuration)")
        e = np.cross(_line(a, b), _line(d, c))
    return _Frame(A=a, B=b, D=d, E=e)


def _coords_on_ab(fr: _Frame, y: np.ndarray) -> np.ndarray:
    """(alpha, beta) with y ~ alpha * A + beta * B (A, B normalised to w = 1)."""
    m = np.column_stack([fr.A, fr.B])
    coef, *_ = np.linalg.lstsq(m, y, rcond=None)
    return coef


def _refine_crossing(
    curve: np.ndarray, s: np.ndarray, line: np.ndarray, arc: float
) -> tuple[float, np.ndarray] | None:
    """Crossing of a line with the cubic through the 4 polyline points around arc position arc.

    The chord polyline cuts the corners of a curved, sparsely sampled curve; the local cubic
    (x(s), y(s) through the neighbouring vertices, chord-length parameter) removes most of that
    error, which matters where the line meets the curve at a grazing angle (near A and B, where
    D'X' is close to the tangent). Returns None where no root lies on the segment.
    """
    m = len(curve)
    if m < 4:
        return None
    j = int(np.clip(np.searchsorted(s, arc, side="right") - 1, 0, m - 2))
    lo = int(np.clip(j - 1, 0, m - 4))
    idx = np.arange(lo, lo + 4)
    ss = s[idx]
    scale = ss[-1] - ss[0]
    if not scale > 0:
        return None
    u = (ss - ss[0]) / scale
    v = np.vander(u, 4)
    try:
        cx = np.linalg.solve(v, curve[idx, 0])
        cy = np.linalg.solve(v, curve[idx, 1])
    except np.linalg.LinAlgError:
        return None
    poly = line[0] * cx + line[1] * cy
    poly[-1] += line[2]
    roots = np.roots(poly) if np.any(poly[:-1]) else np.zeros(0)
    a, b = (s[j] - ss[0]) / scale, (s[j + 1] - ss[0]) / scale
    tol = 1e-9
    real = [r.real for r in roots if abs(r.imag) < 1e-9 and a - tol <= r.real <= b + tol]
    if len(real) != 1:
        return None
    r = real[0]
    pt = np.array([np.polyval(cx, r), np.polyval(cy, r)])
    return float(ss[0] + r * scale), pt


def _line_polyline_crossings(
    line: np.ndarray, curve: np.ndarray, extend: float, touch_tol: float
) -> tuple[np.ndarray, np.ndarray]:
    """Where a homogeneous image line meets a polyline: (arc positions, points), in curve order.

    Sign changes of the distance to the line give the crossings; a local minimum of the
    distance below ``touch_tol`` pixels away from any crossing counts as a touch (the line is
    tangent to the curve there, which a projective or affine map preserves).
    """
    n = line[:2]
    nn = float(np.hypot(*n))
    if not nn > 0:
        return np.zeros(0), np.zeros((0, 2))
    direction = np.array([-n[1], n[0]]) / nn
    origin = -line[2] * n / nn**2  # the foot of the image origin on the line
    u, arc, _ = pl.segment_line_crossings(curve, origin, direction, extend=extend)
    pts = origin[None, :] + u[:, None] * direction[None, :]
    s = pl.arc_length(curve)
    for k in range(len(arc)):
        refined = _refine_crossing(curve, s, line, float(arc[k]))
        if refined is not None:
            arc[k], pts[k] = refined
    hs = (curve @ n + line[2]) / nn
    h = np.abs(hs)
    interior = np.arange(1, len(curve) - 1)
    is_min = (h[interior] <= h[interior - 1]) & (h[interior] <= h[interior + 1])
    # A touch has no sign change on either side (the vertex next to a crossing is also a local
    # minimum of the distance; it is not a touch).
    same_side = (hs[interior - 1] * hs[interior] > 0) & (hs[interior + 1] * hs[interior] > 0)
    touch = interior[is_min & same_side & (h[interior] < touch_tol)]
    if len(touch):
        far = np.array([np.all(np.abs(arc - s[j]) > 3.0 * touch_tol) for j in touch], dtype=bool)
        touch = touch[far]
        # Foot of the vertex on the line.
        feet = curve[touch] - ((curve[touch] @ n + line[2]) / nn**2)[:, None] * n[None, :]
        arc = np.concatenate([arc, s[touch]])
        pts = np.vstack([pts, feet])
    order = np.argsort(arc)
    return arc[order], pts[order]


def match_flat(
    views: Sequence[Mapping[str, object] | FlatView],
    projection: str,
    query: Sequence[Sequence[float]] | np.ndarray,
) -> list[np.ndarray | None]:
    """Match query points on view 0's curve to view 1's curve (paper section 5 / Lee).

    views: two views, each a mapping with keys "A", "B", "C" (perspective only), "tangent_A",
        "tangent_B" (optional: estimated from the curve when missing) and "curve" (polyline from A
        to B), all in image pixels; or :class:`FlatView` objects.
    projection: "perspective" (needs C) or "orthographic".
    query: (Q, 2) points on view 0's curve (pixels).

    Returns a list of Q entries: the matching point (2,) on view 1's curve, or None where the
    query is off view 0's curve (farther than max(2 px, 4 sigma, 0.5 % of the curve length), sigma
    the estimated polyline noise), the construction degenerates for that point (X' at D'), or
    the line D''Y'' misses view 1's curve.
    Raises ``CurveReconError`` for bad input: wrong number of views, unknown projection, missing
    keys, short or degenerate polylines, parallel tangents (no D), C on line AB, A, B, D collinear.
    """
    if projection not in PROJECTIONS:
        raise _error(f"projection must be one of {PROJECTIONS}, got {projection!r}")
    if len(views) != 2:
        raise _error(f"expected exactly 2 views, got {len(views)}")
    v0, v1 = (parse_view(v, projection, i) for i, v in enumerate(views))
    f0, f1 = (_construct(v, projection, i) for i, v in enumerate((v0, v1)))
    try:
        q = np.asarray(query, dtype=float)
    except (TypeError, ValueError):
        raise _error("query: must be a list of [x, y] points") from None
    if q.size == 0:
        return []
    if q.ndim != 2 or q.shape[1] != 2:
        raise _error(f"query: expected a list of [x, y] points, got shape {q.shape}")

    sigma0 = pl.noise_level(v0.curve)
    sigma1 = pl.noise_level(v1.curve)
    # Noisy polylines are smoothed before lines are intersected with them (local quadratic
    # regression over +-(1 % + 2 % per pixel of noise) of the curve length): at 0.5 px noise this
    # halves the median match error; clean polylines are used as given.
    curve0, curve1 = v0.curve, v1.curve
    if sigma0 > NOISE_TO_SMOOTH:
        curve0 = pl.smooth(curve0, (0.01 + 0.02 * sigma0) * float(pl.arc_length(curve0)[-1]))
    if sigma1 > NOISE_TO_SMOOTH:
        curve1 = pl.smooth(curve1, (0.01 + 0.02 * sigma1) * float(pl.arc_length(curve1)[-1]))
    len0 = float(pl.arc_length(curve0)[-1])
    len1 = float(pl.arc_length(curve1)[-1])
    tol = max(2.0, 4.0 * sigma0, 0.005 * len0)
    finite_q = np.where(np.isfinite(q), q, 0.0)
    dist = pl.distance_to_polyline(finite_q, v0.curve)[0]
    foot_arc = pl.distance_to_polyline(finite_q, curve0)[1]
    extend0 = max(1.0, 2.0 * sigma0, 0.002 * len0)
    extend1 = max(1.0, 2.0 * sigma1, 0.002 * len1)
    touch0 = max(0.5, 2.0 * sigma0)
    touch1 = max(0.5, 2.0 * sigma1)
    if projection == "perspective":
        e0 = _coords_on_ab(f0, f0.E)
        e1 = _coords_on_ab(f1, f1.E)

    def lines_through(x0_xy: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
        """(D'X' in view 0, D''Y'' in view 1) for a point X' of view 0, None if degenerate."""
        l0 = _line(f0.D, _h(x0_xy))
        if np.hypot(*l0[:2]) < 1e-9 * max(1.0, float(np.hypot(*x0_xy))):
            return None  # X' coincides with D'
        # Y' = A'B' x D'X' and its coordinates on A'B'.
        ya, yb = _coords_on_ab(f0, np.cross(_line(f0.A, f0.B), l0))
        if projection == "perspective":
            # Equal double quotients (15)-(17): (A E / A Y) : (B E / B Y) in both views.
            # In coordinates y ~ a A + b B the double quotient is (e_b * y_a) / (e_a * y_b).
            (ea0, eb0), (ea1, eb1) = e0, e1
            y1 = (eb0 * ya * ea1) * f1.A + (ea0 * yb * eb1) * f1.B
        else:
            # Thales: same affine ratio along AB (homogeneous coordinates keep w = 1 for A, B).
            y1 = ya * f1.A + yb * f1.B
        l1 = _line(f1.D, y1)
        if not (np.linalg.norm(y1) > 0 and np.hypot(*l1[:2]) > 0):
            return None
        return l0, l1

    # Continuity: the map from view 0's curve to view 1's curve is monotone in arc length (the
    # curve's order from A to B is kept). Trace it at samples along view 0's curve (all
    # crossings of D''Y'' are candidates) and pick the monotone, least-jumping path.
    path_a, path_b = _continuity_path(
        curve0, curve1, lines_through, extend1, touch1, n_samples=CONTINUITY_SAMPLES
    )

    out: list[np.ndarray | None] = []
    for k in range(len(q)):
        if not (np.all(np.isfinite(q[k])) and dist[k] <= tol):
            out.append(None)
            continue
        lines = lines_through(q[k])
        if lines is None:
            out.append(None)
            continue
        l0, l1 = lines
        arcs1, pts1 = _line_polyline_crossings(l1, curve1, extend1, touch1)
        if len(arcs1) == 0:
            out.append(None)
            continue
        rel0 = foot_arc[k] / len0
        if len(path_a) >= 2:
            # The crossing nearest to the continuity path at the query's arc position.
            target = float(np.interp(rel0, path_a, path_b))
            out.append(pts1[int(np.argmin(np.abs(arcs1 / len1 - target)))])
            continue
        # Fallback (no path): the query is the j-th crossing of D'X' with view 0's curve in
        # curve order; take the j-th crossing in view 1 when the counts agree.
        arcs0, _ = _line_polyline_crossings(l0, curve0, extend0, touch0)
        j = int(np.argmin(np.abs(arcs0 - foot_arc[k]))) if len(arcs0) else None
        if j is not None and len(arcs0) == len(arcs1):
            out.append(pts1[j])
        else:
            rel = rel0 if j is None else arcs0[j] / len0
            out.append(pts1[int(np.argmin(np.abs(arcs1 / len1 - rel)))])
    return out


def _continuity_path(
    curve0: np.ndarray,
    curve1: np.ndarray,
    lines_through,
    extend1: float,
    touch1: float,
    *,
    n_samples: int,
) -> tuple[np.ndarray, np.ndarray]:
    """Monotone correspondence of relative arc positions, view 0 -> view 1, by dynamic programming.

    Samples X' along view 0's curve; each crossing of D''Y'' with view 1's curve is a candidate
    (relative arc b). The path starts at (0, 0) (A) and ends at (1, 1) (B); a step from (a, b)
    to (a', b') costs ``(db - da)^2 / da`` (a jump in b over a short stretch of a is expensive)
    plus a large cost for going backwards; a sample may be skipped at a fixed cost (no candidate
    or only wrong ones). Returns the chosen (a, b) positions, end points included.
    """
    len0 = float(pl.arc_length(curve0)[-1])
    len1 = float(pl.arc_length(curve1)[-1])
    pts0, arcs0 = pl.resample(curve0, n_samples + 2)
    items_a, items_b = [0.0], [np.array([0.0])]
    for x0, a0 in zip(pts0[1:-1], arcs0[1:-1], strict=True):
        lines = lines_through(x0)
        if lines is None:
            continue
        arcs1, _ = _line_polyline_crossings(lines[1], curve1, extend1, touch1)
        if len(arcs1):
            items_a.append(a0 / len0)
            items_b.append(np.clip(arcs1 / len1, -0.05, 1.05))
    items_a.append(1.0)
    items_b.append(np.array([1.0]))
    back_tol = 2.0 / len1 + 0.002  # small backward steps: noise at grazing crossings
    skip_cost = 0.5
    # States: (item, candidate). cost[s], prev[s]; all previous states are reachable (skips).
    state_item = [0]
    state_b = [0.0]
    state_cost = [0.0]
    state_prev = [-1]
    for j in range(1, len(items_a)):
        si = np.asarray(state_item)
        sb = np.asarray(state_b)
        sc = np.asarray(state_cost)
        ia = np.asarray(items_a)[si]
        da = max(items_a[j] - 0.0, 0.0) - ia
        da = np.maximum(da, 1e-9)
        skipped = (j - 1 - si) * skip_cost
        for b in items_b[j]:
            db = b - sb
            step = (db - da) ** 2 / da + 1e3 * np.maximum(0.0, -db - back_tol)
            total = sc + skipped + step
            best = int(np.argmin(total))
            state_item.append(j)
            state_b.append(float(b))
            state_cost.append(float(total[best]))
            state_prev.append(best)
    # The end state is the last one appended (item len - 1, b = 1).
    s = len(state_item) - 1
    path = []
    while s >= 0:
        path.append((items_a[state_item[s]], state_b[s]))
        s = state_prev[s]
    path.reverse()
    pa = np.array([p[0] for p in path])
    pb = np.array([p[1] for p in path])
    return pa, pb


def run_match_flat(in_path: str, out_path: str) -> None:
    """Read ``curverecon.flat-views/1`` from in_path, write ``curverecon.matches/1`` to out_path.

    Raises ``CurveReconError`` (one-line message) for unreadable or invalid input.
    """
    from curverecon.io import format_hint, read_json, write_json

    doc = read_json(in_path)  # unreadable, malformed, too deeply nested, NaN: one-line errors
    if not isinstance(doc, dict):
        raise _error(f"{in_path}: expected a JSON object")
    if doc.get("format") != FORMAT_IN:
        fmt = doc.get("format")
        raise _error(f"{in_path}: format must be {FORMAT_IN!r}, got {fmt!r}{format_hint(fmt)}")
    projection = doc.get("projection")
    views = doc.get("views")
    if not isinstance(views, list):
        raise _error(f"{in_path}: 'views' must be a list of two views")
    query = doc.get("query")
    if not isinstance(query, list):
        raise _error(f"{in_path}: 'query' must be a list of [x, y] points")
    matches = match_flat(views, projection, query)  # type: ignore[arg-type]
    result = {
        "format": FORMAT_OUT,
        "matches": [None if m is None else [float(m[0]), float(m[1])] for m in matches],
    }
    write_json(out_path, result)
