"""Scenes of the orthographic Section 2 rows, built by an independent 3-D construction.

A random smooth curve (``curverecon.curve_families``) is a rigid body: A and B its ends, C a
marked point on it (s = 0.45), the mass centre G the mean of the curve's points (a uniform wire).
The body is moved in world = camera coordinates by its motion model with scipy's rotations and
projected orthographically (keep x, y).  Nothing here uses the rigid stage's parametrisation,
its generated model or its solvers, so the tests and the bench compare the estimate with
geometry it never saw.

Motions: ``uniform-rotation`` Rot(n, w t) R0 (n at least 30 degrees from the viewing axis,
w 8-20 degrees per unit of t); ``fixed-axis`` Rot(n, theta_f) R0 (theta_f uniform in +-90
degrees); ``free`` a random rotation per frame; ``force-field`` a random rotation per frame and
the mass centre on x_G(t) = g0 + g1 t + g2 t^2 / 2 (3-D; its image is what the row sees).  Times
t_f = f (unit spacing).  Lengths in input units (pixels), angles in radians.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.spatial.transform import Rotation

from curverecon.curve_families import draw_curve


@dataclass
class RigidScene:
    """Measurements and truth of one scene.

    times (N,); points (N, P, 2) noisy images in ``names`` order; angles (N, 2) noisy tangent
    image angles at A and B (radians) or None; curves: per frame an (M, 2) polyline from A to B
    or None.  Truth: points3 (N, P, 3) camera coordinates with A at z = 0; rotations (N, 3, 3)
    relative to frame 0; axis (3,) or None; rate (radians per unit of t) or None; angles (N,)
    or None; parabola (3, 2) of the mass centre's image or None; tangents3 (2, 3) unit
    directions at A and B (into the curve) in frame 0; curve3d (M, 3) in frame 0's camera
    coordinates (A at z = 0; 4,001 points, dense enough to measure 1e-6 of the length);
    outliers (N,) True for frames whose points were replaced.
    """

    motion: str
    names: tuple[str, ...]
    times: np.ndarray
    points: np.ndarray
    angles: np.ndarray | None
    curves: list[np.ndarray] | None
    points3: np.ndarray
    rotations: np.ndarray
    axis: np.ndarray | None
    rate: float | None
    frame_angles: np.ndarray | None
    parabola: np.ndarray | None
    tangents3: np.ndarray
    curve3d: np.ndarray
    curve_length: float
    outliers: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))


def _axis(rng: np.random.Generator) -> np.ndarray:
    while True:
        n = rng.normal(size=3)
        n /= np.linalg.norm(n)
        if abs(n[2]) <= np.cos(np.radians(30.0)):
            return n


def _world_rotations(motion: str, n_frames: int, rng: np.random.Generator):
    """(rotations (N, 3, 3) body to camera, axis, rate, angles relative to frame 0)."""
    r0 = Rotation.random(random_state=int(rng.integers(2**31)))
    t = np.arange(n_frames, dtype=float)
    if motion == "uniform-rotation":
        n, w = _axis(rng), np.radians(rng.uniform(8.0, 20.0)) * rng.choice([-1.0, 1.0])
        rel = Rotation.from_rotvec(np.outer(w * t, n))
        return (rel * r0).as_matrix(), n, float(w), w * t
    if motion == "fixed-axis":
        n = _axis(rng)
        ang = np.concatenate([[0.0], np.radians(rng.uniform(-90.0, 90.0, n_frames - 1))])
        rel = Rotation.from_rotvec(np.outer(ang, n))
        return (rel * r0).as_matrix(), n, None, ang
    rots = Rotation.random(n_frames, random_state=int(rng.integers(2**31))).as_matrix()
    return rots, None, None, None


def make_rigid_scene(
    motion: str,
    names: str = "AB",
    frames: int = 20,
    seed: int = 0,
    noise_px: float = 1.0,
    tangents: bool = False,
    tangent_noise_deg: float = 1.0,
    with_curve: bool = False,
    curve_noise_px: float = 0.5,
    outlier_fraction: float = 0.0,
    chord: tuple[float, float] = (80.0, 160.0),
    curve_points: int = 201,
) -> RigidScene:
    """One scene (see the module docstring); ``seed`` fixes everything; ``curve_points``
    points per polyline."""
    rng = np.random.default_rng(seed)
    curve = draw_curve(rng, ("helix", "clothoid", "fourier", "random")[seed % 4], chord)
    samples = curve.points(np.linspace(0.0, 1.0, 201))
    polyline = curve.points(np.linspace(0.0, 1.0, curve_points))
    a_, b_, ta, tb = curve.ends()
    c_ = curve.points(np.array([0.45]))[0]
    body = {"A": a_, "B": b_, "C": c_}
    g = samples.mean(axis=0)  # the mass centre of a uniform wire
    rots, axis, rate, angles = _world_rotations(motion, frames, rng)
    t = np.arange(frames, dtype=float)
    if motion == "force-field":
        g3 = np.array([rng.uniform(-40, 40), rng.uniform(-40, 40), 0.0])
        v3 = rng.uniform(-8.0, 8.0, 3)
        acc = np.array([rng.uniform(-1.0, 1.0), rng.uniform(0.5, 2.0), rng.uniform(-1, 1)])
        centre = g3 + np.outer(t, v3) + 0.5 * np.outer(t * t, acc)
        parabola = np.array([g3[:2], v3[:2], acc[:2]])
    else:
        centre = np.column_stack([rng.uniform(-50, 50, (frames, 2)), rng.normal(0, 20, frames)])
        parabola = None

    def place(x: np.ndarray) -> np.ndarray:  # body points (K, 3) -> (N, K, 3) camera
        return np.einsum("fij,kj->fki", rots, x - g) + centre[:, None, :]

    pts3 = place(np.array([body[k] for k in names]))
    a_depth = pts3[:, :1, 2:3].copy()
    pts3[:, :, 2:] -= a_depth
    obs = pts3[:, :, :2] + rng.normal(0.0, noise_px, (frames, len(names), 2))
    dirs = np.einsum("fij,kj->fki", rots, np.array([ta, tb]))
    ang = None
    if tangents:
        ang = np.arctan2(dirs[:, :, 1], dirs[:, :, 0])
        ang = ang + np.radians(tangent_noise_deg) * rng.normal(size=ang.shape)
    curves = None
    if with_curve:
        img = place(polyline)[:, :, :2]
        curves = [c + rng.normal(0.0, curve_noise_px, c.shape) for c in img]
    outliers = np.zeros(frames, bool)
    k = int(round(outlier_fraction * frames))
    if k:
        bad = rng.choice(np.arange(1, frames), size=k, replace=False)
        outliers[bad] = True
        lo, hi = obs.reshape(-1, 2).min(axis=0) - 50, obs.reshape(-1, 2).max(axis=0) + 50
        obs[bad] = rng.uniform(lo, hi, (k, len(names), 2))
    rel = np.einsum("fij,kj->fik", rots, rots[0])
    dense = curve.points(np.linspace(0.0, 1.0, 4001))
    c3 = np.einsum("ij,kj->ki", rots[0], dense - a_)
    c3[:, :2] += pts3[0, 0, :2]
    length = float(np.sum(np.linalg.norm(np.diff(dense, axis=0), axis=1)))
    unit = dirs[0] / np.linalg.norm(dirs[0], axis=1)[:, None]
    return RigidScene(
        motion, tuple(names), t, obs, ang, curves, pts3, rel, axis, rate, angles, parabola,
        unit, c3, length, outliers,
    )  # fmt: skip
