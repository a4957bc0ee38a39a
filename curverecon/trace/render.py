"""Rendered image sequences with the truth beside them (tests, the bench, ``simulate --images``).

A 3-D curve (a family below) tumbles smoothly: frame k+1's rotation is frame k's followed by a
rotation of ``step_deg`` about an axis that drifts slowly, and the curve drifts across the
image.  Each frame is projected orthographically (keep x, y) and drawn as a bright line: the
projected curve convolved with a 2-D Gaussian point-spread function of ``line_sigma`` pixels
(a Gaussian profile across the line, and half the line's brightness at each end), then
integrated over each pixel, optionally blurred further, on a background with a linear gradient,
with Gaussian noise, clipped and rounded to 8 bits.

Pixel convention (the trace contract): x = column, y = row, the centre of the top-left pixel at
(0, 0).  The true projected curve of a frame is ``Scene.observations.curves[k]`` (dense, from A
to B).  The truth uses the simulator's geometry (``curverecon.simulate.shape_from_geometry``):
nothing here uses the tracer.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import gaussian_filter
from scipy.spatial.transform import Rotation

from curverecon.errors import CurveReconError
from curverecon.model.observations import Observations
from curverecon.simulate import (
    Scene,
    Truth,
    observable_view,
    random_curve,
    shape_from_geometry,
)

FAMILIES = ("bezier", "helix", "wave", "loop")
"""Curve families: a random cubic Bezier (``simulate.random_curve``), a stretch of a helix, a
random quintic Bezier (more turns), and a curl whose projection usually crosses itself."""

SUPERSAMPLE = 4
"""Sub-pixels per pixel along each axis for the pixel integration."""


@dataclass
class RenderOptions:
    """How frames are drawn (grey levels of an 8-bit image; lengths in pixels)."""

    size: int = 384
    line_sigma: float = 1.2  # the rendered sequences: a Gaussian profile of about 1.2 px
    amplitude: float = 160.0  # line brightness above the background
    noise: float = 8.0  # standard deviation of the added noise
    background: float = 40.0  # mean background level
    gradient: float = 60.0  # background rise across the image (grey levels, random direction)
    blur: float = 0.0  # extra Gaussian blur of the whole frame (px)
    dark: bool = False  # draw a dark line on a bright background


def _bezier(ctrl: np.ndarray, s: np.ndarray) -> np.ndarray:
    from math import comb

    n = len(ctrl) - 1
    s = s[:, None]
    return sum(comb(n, k) * (1 - s) ** (n - k) * s**k * ctrl[k] for k in range(n + 1))


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def curve_points(rng: np.random.Generator, family: str, n: int = 2000) -> np.ndarray:
    """(n, 3) points of a random curve of ``family``, chord |AB| = 1, A first, alpha and beta
    in [10, 80] degrees (as the simulator's curves)."""
    s = np.linspace(0.0, 1.0, n)
    lo, hi = np.radians(10.0), np.radians(80.0)
    for _ in range(1000):
        if family == "bezier":
            pts = _bezier(random_curve(rng, (1.0, 1.0)), s)
        elif family == "helix":
            turns = rng.uniform(0.4, 0.8)
            pitch = rng.uniform(0.3, 1.0)
            t = 2 * np.pi * turns * s
            pts = np.column_stack([np.cos(t), np.sin(t), pitch * t])
        elif family == "wave":
            ctrl = np.column_stack([np.linspace(0, 1, 6), np.zeros(6), np.zeros(6)])
            ctrl[1:-1] += rng.normal(scale=0.35, size=(4, 3))
            pts = _bezier(ctrl, s)
        elif family == "loop":  # a prolate trochoid: one loop, with a little pitch
            th = np.pi * (2 * s - 1)
            d = rng.uniform(0.55, 0.9)
            pts = np.column_stack(
                [0.4 * th - d * np.sin(th), -d * np.cos(th), rng.uniform(0.05, 0.2) * th]
            )
        else:
            raise CurveReconError(f"unknown curve family {family!r} (one of {', '.join(FAMILIES)})")
        pts = pts - pts[0]
        pts = pts / np.linalg.norm(pts[-1])
        pts = pts @ Rotation.random(random_state=rng).as_matrix().T
        _, alpha, beta, _ = shape_from_geometry(pts[0], pts[-1], pts[5] - pts[0], pts[-6] - pts[-1])
        if lo <= alpha <= hi and lo <= beta <= hi:
            return pts
    raise CurveReconError(f"no {family} curve with alpha, beta in [10, 80] degrees")


def _observable(m: np.ndarray, pts: np.ndarray, min_foreshortening: float) -> bool:
    """The simulator's rule (``simulate.observable_view``) for a sampled 3-D curve ``pts``."""
    return observable_view(
        m, pts[-1] - pts[0], pts[5] - pts[0], pts[-6] - pts[-1], min_foreshortening
    )


def tumbling_scene(
    rng: np.random.Generator,
    n_frames: int,
    *,
    family: str = "bezier",
    size: int = 384,
    chord: tuple[float, float] = (0.35, 0.5),
    step_deg: float = 25.0,
    min_foreshortening: float = 0.3,
    independent: bool = False,
) -> Scene:
    """A curve of ``family`` tumbling through ``n_frames`` frames of ``size`` pixels.

    ``chord``: the 3-D chord |AB| as a fraction of ``size`` (uniform).  Each step turns the curve
    by ``step_deg`` about an axis that drifts by about 20 degrees a frame; a step that would show
    AB foreshortened below ``min_foreshortening`` (or an end tangent along the normal of A'B') is
    drawn again.  The curve's bounding box is kept inside the image (a margin of 6 % each side),
    its centre drifting smoothly.  The scene's polylines (1,000 points a frame) are the true
    projected curves in pixels; ``curve_3d`` is frame 0's, A at z = 0.  ``independent``: every
    frame in its own random orientation (drawn until observable), nothing linking one frame's
    pose to the next (images taken apart in time; ``step_deg`` unused).
    """
    pts = curve_points(rng, family) * rng.uniform(*chord) * size
    pts = pts - pts[0]
    rots = []
    axis = _unit(rng.normal(size=3))
    r = Rotation.random(random_state=rng).as_matrix()
    while not _observable(r, pts, min_foreshortening):
        r = Rotation.random(random_state=rng).as_matrix()
    rots.append(r)
    while len(rots) < n_frames:
        for _ in range(0 if independent else 200):
            ax = _unit(axis + 0.35 * rng.normal(size=3))
            cand = Rotation.from_rotvec(np.radians(step_deg) * ax).as_matrix() @ rots[-1]
            if _observable(cand, pts, min_foreshortening):
                axis = ax
                break
        else:
            cand = Rotation.random(random_state=rng).as_matrix()
            while not _observable(cand, pts, min_foreshortening):
                cand = Rotation.random(random_state=rng).as_matrix()
        rots.append(cand)
    rot = np.array(rots)
    margin = 0.06 * size
    centre = np.array([size / 2.0, size / 2.0]) + rng.uniform(-0.05, 0.05, 2) * size
    drift = rng.normal(scale=0.01 * size, size=2)
    dense = pts[:: max(1, len(pts) // 1000)]
    if not np.allclose(dense[-1], pts[-1]):
        dense = np.vstack([dense, pts[-1]])
    curves, a3 = [], []
    for i in range(n_frames):
        cam = dense @ rot[i].T
        lo, hi = cam[:, :2].min(0), cam[:, :2].max(0)
        half = (hi - lo) / 2.0
        room = np.maximum(size / 2.0 - margin - half, 0.0)
        c = np.clip(centre + i * drift, size / 2.0 - room, size / 2.0 + room)
        shift = c - (lo + hi) / 2.0
        a3.append([shift[0], shift[1], 0.0])
        curves.append(cam[:, :2] + shift)
    a3 = np.array(a3)
    ab3 = np.einsum("nij,j->ni", rot, pts[-1] - pts[0])
    b3 = a3 + ab3
    ta, tb = pts[5] - pts[0], pts[-6] - pts[-1]
    ta3 = np.einsum("nij,j->ni", rot, _unit(ta))
    tb3 = np.einsum("nij,j->ni", rot, _unit(tb))
    c, alpha, beta, phi = shape_from_geometry(pts[0], pts[-1], ta, tb)
    ang_a = np.arctan2(ta3[:, 1], ta3[:, 0])
    ang_b = np.arctan2(tb3[:, 1], tb3[:, 0])
    obs = Observations(
        a3[:, :2].copy(),
        b3[:, :2].copy(),
        np.column_stack([np.cos(ang_a), np.sin(ang_a)]),
        np.column_stack([np.cos(ang_b), np.sin(ang_b)]),
        curves,
    )
    truth = Truth(c, alpha, beta, phi, a3, b3, ta3, tb3, rot, np.ones(n_frames, bool))
    curve_3d = dense @ rot[0].T + a3[0]
    return Scene(obs, truth, curve_3d)


def render_frame(
    curve: np.ndarray, rng: np.random.Generator, options: RenderOptions | None = None
) -> np.ndarray:
    """An 8-bit (size, size) image of the polyline ``curve`` (pixels, x = column, y = row).

    The line is the curve convolved with an isotropic Gaussian of ``line_sigma`` (peak
    ``amplitude`` across a straight stretch), integrated over each pixel's area by
    ``SUPERSAMPLE`` x ``SUPERSAMPLE`` sub-pixels; where the curve crosses itself the brightness
    is capped at ``amplitude`` (a wire, not two glowing threads).
    """
    o = options or RenderOptions()
    f = SUPERSAMPLE
    curve = np.asarray(curve, float)
    seg = np.hypot(*np.diff(curve, axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    h = 0.05  # pixels between splatted points
    t = np.linspace(0.0, s[-1], max(2, int(np.ceil(s[-1] / h)) + 1))
    px = np.interp(t, s, curve[:, 0])
    py = np.interp(t, s, curve[:, 1])
    step = t[1] - t[0]
    # only the window around the curve is drawn (the line is zero beyond 5 sigma)
    pad = int(np.ceil(5 * o.line_sigma)) + 2
    c0 = int(np.clip(np.floor(px.min()) - pad, 0, o.size))
    c1 = int(np.clip(np.ceil(px.max()) + pad + 1, c0, o.size))
    r0 = int(np.clip(np.floor(py.min()) - pad, 0, o.size))
    r1 = int(np.clip(np.ceil(py.max()) + pad + 1, r0, o.size))
    nx, ny = (c1 - c0) * f, (r1 - r0) * f
    # sub-pixel grid: sub-pixel m has its centre at pixel coordinate (m + 0.5) / f - 0.5
    gx, gy = (px - c0 + 0.5) * f - 0.5, (py - r0 + 0.5) * f - 0.5
    x0, y0 = np.floor(gx).astype(int), np.floor(gy).astype(int)
    fx, fy = gx - x0, gy - y0
    acc = np.zeros((ny + 2, nx + 2))
    w = step * f  # line density per sub-pixel length
    for dx, dy, wt in (
        (0, 0, (1 - fx) * (1 - fy)),
        (1, 0, fx * (1 - fy)),
        (0, 1, (1 - fx) * fy),
        (1, 1, fx * fy),
    ):
        xi, yi = x0 + dx + 1, y0 + dy + 1
        ok = (xi >= 0) & (xi < nx + 2) & (yi >= 0) & (yi < ny + 2)
        np.add.at(acc, (yi[ok], xi[ok]), w * wt[ok])
    sig = o.line_sigma * f
    window = gaussian_filter(acc, sig, mode="constant")[1:-1, 1:-1] * np.sqrt(2 * np.pi) * sig
    window = np.minimum(window, 1.0)
    line = np.zeros((o.size, o.size))
    if nx and ny:
        line[r0:r1, c0:c1] = window.reshape(ny // f, f, nx // f, f).mean(axis=(1, 3))
    if o.blur > 0:
        line = gaussian_filter(line, o.blur)
    yy, xx = np.mgrid[0 : o.size, 0 : o.size] / max(o.size - 1, 1) - 0.5
    ang = rng.uniform(0, 2 * np.pi)
    bg = o.background + o.gradient * (np.cos(ang) * xx + np.sin(ang) * yy)
    if o.dark:
        img = bg + o.amplitude - o.amplitude * line
    else:
        img = bg + o.amplitude * line
    img = img + rng.normal(scale=o.noise, size=img.shape)
    return np.clip(np.rint(img), 0, 255).astype(np.uint8)


def render_scene(
    scene: Scene, rng: np.random.Generator, options: RenderOptions | None = None
) -> list[np.ndarray]:
    """Every frame of a scene with polylines drawn by :func:`render_frame`."""
    if scene.observations.curves is None:
        raise CurveReconError("the scene has no polylines to draw")
    return [render_frame(c, rng, options) for c in scene.observations.curves]


def write_images(frames: list[np.ndarray], folder: str) -> list[str]:
    """PNG files ``frame_0000.png``, ... in ``folder`` (created); returns their paths."""
    from pathlib import Path

    import imageio.v3 as iio

    out = Path(folder)
    try:
        out.mkdir(parents=True, exist_ok=True)
        paths = []
        for i, img in enumerate(frames):
            p = out / f"frame_{i:04d}.png"
            iio.imwrite(p, img)
            paths.append(str(p))
    except OSError as exc:
        raise CurveReconError(f"cannot write images to {folder}: {exc.strerror or exc}") from exc
    return paths
