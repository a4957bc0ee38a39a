"""Synthetic scenes with the truth beside them: an INDEPENDENT 3-D construction.

Nothing here uses the generated modules or the (delta, tau) parametrisation: a random cubic
Bezier curve (or, with ``curve_family``, a helix, clothoid, Fourier, sharp-ended or random
Frenet curve from ``curverecon.curve_families``) with A, B its end points is moved by random
rotations (scipy Rotation.random) and translations, projected orthographically (keep x, y),
and the image tangents are the projected derivatives at the ends.  The true c, alpha, beta,
phi follow from the 3-D curve by the CONTRACT's geometric definitions (S, T, the angle between
AS and BT), so tests compare the solver with geometry it never saw.

Sampling choices (so the frames are observable at all): alpha and beta of the curve lie in
[10, 80] degrees; a frame is redrawn while c'/c < 0.3 (AB nearly along the line of sight) or
a projected tangent is within 3 degrees of perpendicular to A'B' (d' or e' nearly infinite).
Lengths in input units (pixels), angles in radians in the API, degrees in files.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from curverecon.curve_families import bezier_curve, draw_curve
from curverecon.model.observations import Observations

MIN_FORESHORTENING = 0.3
MIN_TANGENT_TO_NORMAL_DEG = 3.0
OUTLIER_MODELS = ("gross", "random")
"""``make_scene``'s outlier models: "gross", a 15-40 degree error on one or both tangent angles
of an outlier frame (the default, the original stream); "random", both tangent directions of an
outlier frame replaced by independent uniformly random directions in the image plane (the
robustness model of a tracker that lost the curve)."""


@dataclass
class Truth:
    """The true shape (radians, input units) and per-frame 3-D geometry (camera coordinates).

    A3 has z = 0 in every frame (depth is known only up to a shift); rotations map the curve's
    world coordinates to the camera; tangent directions are unit vectors from A into the curve
    and from B into the curve.
    """

    c: float
    alpha: float
    beta: float
    phi: float
    A3: np.ndarray
    B3: np.ndarray
    tangent_A3: np.ndarray
    tangent_B3: np.ndarray
    rotations: np.ndarray
    inliers: np.ndarray

    @property
    def shape(self) -> np.ndarray:
        """(4,) c, alpha, beta, phi."""
        return np.array([self.c, self.alpha, self.beta, self.phi])


@dataclass
class Scene:
    """A synthetic scene: noisy observations, the truth, the 3-D curve in frame-0 camera coords."""

    observations: Observations
    truth: Truth
    curve_3d: np.ndarray | None = None
    point_sigma: float = 0.0
    tangent_sigma_deg: float = 0.0


def shape_from_geometry(
    a: np.ndarray, b: np.ndarray, tangent_a: np.ndarray, tangent_b: np.ndarray
) -> tuple[float, float, float, float]:
    """c, alpha, beta, phi (radians) of a curve from its end points and end tangents in 3-D.

    CONTRACT definitions: alpha (beta) is the acute angle between line AB and the tangent line at
    B (A); S is where the tangent line at B meets the plane through A perpendicular to AB, T where
    the tangent line at A meets the plane through B perpendicular to AB; phi is the angle between
    the vectors AS and BT, in [0, pi].
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    ta, tb = np.asarray(tangent_a, float), np.asarray(tangent_b, float)
    ab = b - a
    c = float(np.linalg.norm(ab))
    e = ab / c
    alpha = float(np.arccos(min(1.0, abs(tb @ e) / np.linalg.norm(tb))))
    beta = float(np.arccos(min(1.0, abs(ta @ e) / np.linalg.norm(ta))))
    s = b + (-(ab @ e) / (tb @ e)) * tb  # (S - A) . e = 0
    t = a + ((ab @ e) / (ta @ e)) * ta  # (T - B) . e = 0
    u, v = s - a, t - b
    cosphi = (u @ v) / (np.linalg.norm(u) * np.linalg.norm(v))
    return c, alpha, beta, float(np.arccos(np.clip(cosphi, -1.0, 1.0)))


def random_curve(rng: np.random.Generator, chord: tuple[float, float]) -> np.ndarray:
    """(4, 3) control points of a random cubic Bezier curve with alpha, beta in [10, 80] deg."""
    while True:
        p0 = np.zeros(3)
        p3 = rng.normal(size=3)
        p3 /= np.linalg.norm(p3)
        p1 = p0 + rng.uniform(0.2, 0.7) * _unit(rng.normal(size=3) + 0.3 * p3)
        p2 = p3 + rng.uniform(0.2, 0.7) * _unit(rng.normal(size=3) - 0.3 * p3)
        ctrl = np.array([p0, p1, p2, p3])
        _, alpha, beta, _ = shape_from_geometry(p0, p3, p1 - p0, p3 - p2)
        lo, hi = np.radians(10.0), np.radians(80.0)
        if lo <= alpha <= hi and lo <= beta <= hi:
            return ctrl * rng.uniform(*chord)


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def observable_view(
    m: np.ndarray,
    ab: np.ndarray,
    ta: np.ndarray,
    tb: np.ndarray,
    min_foreshortening: float = MIN_FORESHORTENING,
) -> bool:
    """A view (rotation matrix ``m``) shows AB at least ``min_foreshortening`` of its length
    and neither end tangent (``ta``, ``tb``) within MIN_TANGENT_TO_NORMAL_DEG of the normal of
    A'B' (the simulator's rule; the renderer of ``curverecon.trace.render`` uses it too)."""
    ch = (m @ ab)[:2]
    if np.linalg.norm(ch) < min_foreshortening * np.linalg.norm(ab):
        return False
    lim = np.sin(np.radians(MIN_TANGENT_TO_NORMAL_DEG))
    for t in (ta, tb):
        pt = (m @ t)[:2]
        n = np.linalg.norm(pt)
        if n == 0 or abs(pt @ ch) / (n * np.linalg.norm(ch)) < lim:
            return False
    return True


def make_scene(
    rng: np.random.Generator,
    n_frames: int,
    point_sigma: float = 0.0,
    tangent_sigma_deg: float = 0.0,
    chord: tuple[float, float] = (100.0, 300.0),
    outlier_fraction: float = 0.0,
    with_curve: bool = False,
    n_curve_points: int = 150,
    curve_family: str = "bezier",
    outlier_model: str = "gross",
) -> Scene:
    """A random smooth curve seen in ``n_frames`` orthographic frames under random free motion.

    Args:
        rng: NumPy random generator (all randomness comes from it).
        n_frames: number of frames.
        point_sigma: standard deviation of the Gaussian noise on each image coordinate (px),
            also applied to the polyline points.
        tangent_sigma_deg: standard deviation of the Gaussian noise on the tangent angles (deg).
        chord: range of the 3-D chord length c = |AB| (input units, uniform).
        outlier_fraction: fraction of frames (rounded to a whole number) whose tangents are
            wrong, as ``outlier_model`` says; ``truth.inliers`` marks them False.
        with_curve: also produce each frame's projected polyline (A' to B') and the 3-D curve in
            frame 0's camera coordinates (A at z = 0).
        curve_family: one of ``curve_families.FAMILIES``; "bezier" (the default) draws the
            same scenes as before the families existed (same random stream).
        outlier_model: one of ``OUTLIER_MODELS``: "gross" (the default and the original
            stream), a gross error of 15-40 degrees on the tangent angle at A, at B or at both
            (tracking errors); "random", both tangent directions replaced by independent
            directions uniform on the circle (a tracker that lost the curve).
    """
    if outlier_model not in OUTLIER_MODELS:
        raise ValueError(f"outlier_model must be one of {OUTLIER_MODELS}, not {outlier_model!r}")
    if curve_family == "bezier":
        ctrl = random_curve(rng, chord)
        curve = bezier_curve(ctrl)
    else:
        curve = draw_curve(rng, curve_family, chord)
    a, b, ta, tb = curve.ends()  # tangents from A into the curve, from B into the curve
    c, alpha, beta, phi = shape_from_geometry(a, b, ta, tb)
    rots = []
    while len(rots) < n_frames:
        r = Rotation.random(random_state=rng)
        if observable_view(r.as_matrix(), b - a, ta, tb):
            rots.append(r.as_matrix())
    rot = np.array(rots)
    shift = rng.uniform(-200.0, 200.0, size=(n_frames, 2))
    a_img = shift
    ab3 = np.einsum("nij,j->ni", rot, b - a)
    a3 = np.column_stack([a_img, np.zeros(n_frames)])
    b3 = a3 + ab3
    ta3 = np.einsum("nij,j->ni", rot, _unit(ta))
    tb3 = np.einsum("nij,j->ni", rot, _unit(tb))

    obs_a = a3[:, :2] + rng.normal(scale=point_sigma, size=(n_frames, 2))
    obs_b = b3[:, :2] + rng.normal(scale=point_sigma, size=(n_frames, 2))
    ang_a = np.arctan2(ta3[:, 1], ta3[:, 0])
    ang_b = np.arctan2(tb3[:, 1], tb3[:, 0])
    sig = np.radians(tangent_sigma_deg)
    ang_a = ang_a + rng.normal(scale=sig, size=n_frames)
    ang_b = ang_b + rng.normal(scale=sig, size=n_frames)
    inliers = np.ones(n_frames, dtype=bool)
    n_out = int(round(outlier_fraction * n_frames))
    if n_out:
        idx = rng.choice(n_frames, size=n_out, replace=False)
        inliers[idx] = False
        for i in idx:
            if outlier_model == "random":
                ang_a[i], ang_b[i] = rng.uniform(-np.pi, np.pi, size=2)
                continue
            which = rng.integers(0, 3)  # 0: A, 1: B, 2: both
            err = rng.choice([-1.0, 1.0], size=2) * np.radians(rng.uniform(15.0, 40.0, size=2))
            if which in (0, 2):
                ang_a[i] += err[0]
            if which in (1, 2):
                ang_b[i] += err[1]
    obs_ta = np.column_stack([np.cos(ang_a), np.sin(ang_a)])
    obs_tb = np.column_stack([np.cos(ang_b), np.sin(ang_b)])

    curves = None
    curve_3d = None
    if with_curve:
        s = np.linspace(0.0, 1.0, n_curve_points)
        pts = curve.points(s) - a
        curves = []
        for i in range(n_frames):
            cam = pts @ rot[i].T + a3[i]
            curves.append(cam[:, :2] + rng.normal(scale=point_sigma, size=(n_curve_points, 2)))
        curve_3d = pts @ rot[0].T + a3[0]

    obs = Observations(obs_a, obs_b, obs_ta, obs_tb, curves)
    truth = Truth(c, alpha, beta, phi, a3, b3, ta3, tb3, rot, inliers)
    return Scene(obs, truth, curve_3d, point_sigma, tangent_sigma_deg)


def truth_to_dict(scene: Scene, seed: int | None = None) -> dict:
    """The ``curverecon.truth/1`` document of a scene (degrees; camera coordinates, A at z=0)."""
    t = scene.truth
    frames = [
        {
            "A3": t.A3[i].tolist(),
            "B3": t.B3[i].tolist(),
            "tangent_A3": t.tangent_A3[i].tolist(),
            "tangent_B3": t.tangent_B3[i].tolist(),
            "rotation": t.rotations[i].tolist(),
            "inlier": bool(t.inliers[i]),
        }
        for i in range(len(t.A3))
    ]
    out = {
        "format": "curverecon.truth/1",
        "c": t.c,
        "alpha_deg": float(np.degrees(t.alpha)),
        "beta_deg": float(np.degrees(t.beta)),
        "phi_deg": float(np.degrees(t.phi)),
        "frames": frames,
        "point_noise": scene.point_sigma,
        "tangent_noise_deg": scene.tangent_sigma_deg,
        "outlier_frames": [int(i) for i in np.flatnonzero(~t.inliers)],
    }
    if seed is not None:
        out["seed"] = int(seed)
    if scene.curve_3d is not None:
        out["curve3d"] = scene.curve_3d.tolist()
    return out
