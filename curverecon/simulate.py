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


# ---------------------------------------------------------------- the Section 2 table's rows
CONFIG_MOTIONS = ("free", "uniform-rotation", "fixed-axis", "force-field")
"""Motion models ``simulate_configuration`` draws (the contract's, less "rotation-free", which
shows no depth, and "auto", which is a choice of the reconstruction)."""

MIN_AXIS_TILT_DEG = 35.0
"""A rotation axis is drawn at least this far from the viewing direction (well-conditioned: an
axis along the view turns the body in the image plane and shows no depth)."""

MIN_AXIS_TO_CHORD_DEG = 20.0
"""AB at least this far from the rotation axis (a chord along the axis hardly moves)."""

SWEEP_DEG = (180.0, 300.0)
"""Total rotation over a sequence (uniform in this range, at most 60 degrees a frame): angles
spread, and with equal time steps below the rate's alias (180 degrees a step)."""

MIN_DISTANCE_STD = 0.05
"""Some image distance between the points varies over the frames with a standard deviation of at
least this fraction of c (a rotation out of the image plane that shows depth well above the
noise; ``model.configuration.in_plane_motion`` refuses sequences that show none)."""

MIN_POINT_OFFSET = 0.15
"""A further point C is at least this fraction of c from the line AB (else A, B, C are nearly
collinear and the third point adds little)."""


def simulate_configuration(
    motion: str,
    points: str = "AB",
    frames: int = 20,
    seed: int = 0,
    noise_px: float = 0.0,
    tangent_noise_deg: float | None = None,
    with_curve: bool = False,
    curve_noise_px: float | None = None,
    times: np.ndarray | None = None,
    *,
    family: str = "bezier",
    chord: tuple[float, float] = (100.0, 300.0),
    outlier_fraction: float = 0.0,
    n_curve_points: int = 150,
) -> tuple[dict, dict]:
    """A scene of a row of the seed's Section 2 table: its observations document and its truth.

    The 3-D construction: a random curve of ``family`` (``curve_families``) with A, B its ends
    and every further point (C, D, ...) a marked point on the curve (at arc parameter s in
    [0.25, 0.75], at least ``MIN_POINT_OFFSET`` c from line AB); the body moves rigidly by
    ``motion`` and is projected orthographically (x, y kept):

    - ``free``: a random rotation per frame (``Rotation.random``);
    - ``fixed-axis``: Rot(n, theta_f) R0, n at least ``MIN_AXIS_TILT_DEG`` from the viewing
      direction, the angles increasing with random steps over a total sweep in ``SWEEP_DEG``;
    - ``uniform-rotation``: the same with theta_f = w (t_f - t_0), w > 0 in degrees per unit t;
    - ``force-field``: the mass centre (the centroid of the curve, a homogeneous wire) on a
      parabola x_G(t) = g0 + g1 t + g2 t^2 / 2 in the image plane, the rotation smooth and free
      (rotation vector w1 (t - t0) + w2 (t - t0)^2 / 2).

    Every frame shows AB and every A-to-point vector at least ``MIN_FORESHORTENING`` of its
    length, and some image distance between the points varies by ``MIN_DISTANCE_STD`` (the
    whole motion is redrawn otherwise; free motion redraws single frames).

    Args:
        motion: one of ``CONFIG_MOTIONS``.
        points: the traceable point names, "AB" then further capital letters ("ABC").
        frames: number of frames; times: (frames,) increasing times (default 0, 1, 2, ...).
        seed: the random stream's seed (everything comes from it).
        noise_px: Gaussian noise on every image coordinate of the points (input units).
        tangent_noise_deg: None writes no tangents; else the tangents at A and B with this
            Gaussian noise on their angles (degrees).
        with_curve: also write every frame's projected polyline (A' to B', ``n_curve_points``),
            with noise ``curve_noise_px`` per coordinate (default ``noise_px``).
        family: the curve family; chord: range of c = |AB| (input units, uniform).
        outlier_fraction: fraction of frames (rounded) whose points (and tangents) are replaced
            by uniformly random ones within c of the true A'; the truth lists them.
    Returns:
        (the ``curverecon.observations/1`` document, the ``curverecon.truth/1`` document):
        the truth has per frame ``points3`` (camera coordinates, A at z = 0), ``rotation``
        (X_f - A_f = R_f (X_0 - A_0)), A3, B3 and unit tangents; ``motion_parameters``
        (``axis`` in frame 0's camera coordinates, ``angle_deg`` per frame, ``rate_deg`` per
        unit of t, ``acceleration``, ``velocity``, ``position`` of the mass centre's image,
        ``mass_centre`` relative to A); c, alpha, beta, phi; the ``body`` (points and curve in
        frame 0's camera coordinates, relative to A) and ``curve3d`` (frame 0, A at z = 0).
    Raises:
        CurveReconError: an unknown motion, bad point names, too few frames or a configuration
            orthographic projection cannot determine.
    """
    from curverecon.errors import CurveReconError
    from curverecon.model.configuration import Configuration, motion_determined

    names = _point_names(points)
    if motion not in CONFIG_MOTIONS:
        raise CurveReconError(f'unknown motion "{motion}" (choose {", ".join(CONFIG_MOTIONS)})')
    reason = motion_determined(motion, len(names), tangent_noise_deg is not None)
    if reason is not None:
        raise CurveReconError(reason)
    t = _scene_times(times, frames)
    rng = np.random.default_rng(seed)
    if family == "bezier":
        curve = bezier_curve(random_curve(rng, chord))
    else:
        curve = draw_curve(rng, family, chord)
    body = _scene_body(rng, curve, names, n_curve_points)
    rots, centre, params = _scene_motion(rng, motion, t, body, tangent_noise_deg is not None)
    cam = np.einsum("nij,pj->npi", rots, body["points"])  # (N, P, 3) relative to A
    shift = np.zeros((len(t), 3))
    shift[:, :2] = rng.uniform(-200.0, 200.0, size=(len(t), 2))
    if centre is not None:  # A's image from the mass centre's path
        shift[:, :2] = centre - np.einsum("nij,j->ni", rots, body["centre"])[:, :2]
    pts3 = cam + shift[:, None, :]
    cfg = Configuration("orthographic", motion, names, tangent_noise_deg is not None)
    noise = (noise_px, tangent_noise_deg, noise_px if curve_noise_px is None else curve_noise_px)
    doc, inliers = _scene_document(
        rng, cfg, t, pts3, rots, body, noise, with_curve, outlier_fraction
    )
    truth = _scene_truth(cfg, t, pts3, rots, body, params, inliers, noise, seed, family)
    return doc, truth


def _point_names(points: str) -> tuple[str, ...]:
    """("A", "B", "C", ...) from "ABC"; anything else is a one-line error."""
    from curverecon.errors import CurveReconError

    names = tuple(points)
    if names[:2] != ("A", "B") or len(set(names)) != len(names) or not points.isalpha():
        raise CurveReconError(
            f'points "{points}" must be "AB" followed by further distinct letters (e.g. "ABC")'
        )
    if len(names) > 8:
        raise CurveReconError("at most 8 points (A, B and six more)")
    return names


def _scene_times(times: np.ndarray | None, frames: int) -> np.ndarray:
    from curverecon.errors import CurveReconError

    if times is None:
        if frames < 2:
            raise CurveReconError("a scene needs at least 2 frames")
        return np.arange(float(frames))
    t = np.asarray(times, dtype=float)
    if t.ndim != 1 or len(t) < 2 or not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
        raise CurveReconError("times must be at least 2 finite, increasing numbers")
    return t


def _scene_body(rng: np.random.Generator, curve, names: tuple[str, ...], n_curve: int) -> dict:
    """The rigid body in the curve's own coordinates (A = 0): the named points, the end
    tangents (unit, into the curve), the sampled curve and its centroid (a homogeneous wire)."""
    a, b, ta, tb = curve.ends()
    c = float(np.linalg.norm(b - a))
    e = (b - a) / c
    marks = [0.0, 1.0]
    for _ in names[2:]:
        best, best_off = 0.5, -1.0
        for _ in range(200):
            s = float(rng.uniform(0.25, 0.75))
            p = curve.points(np.array([s]))[0]
            off = float(np.linalg.norm(p - (p @ e) * e))
            if min(abs(s - m) for m in marks) >= 0.08 and off > best_off:
                best, best_off = s, off
            if best_off >= MIN_POINT_OFFSET * c:
                break
        marks.append(best)
    s = np.linspace(0.0, 1.0, 2001)
    speed = np.linalg.norm(curve.derivative(s), axis=1)
    weight = speed * np.gradient(s)
    dense = curve.points(s)
    return {
        "names": names,
        "s": marks,
        "points": curve.points(np.array(marks)),
        "ta": _unit(ta),
        "tb": _unit(tb),
        "curve": curve.points(np.linspace(0.0, 1.0, n_curve)),
        "centre": weight @ dense / weight.sum(),
        "shape": shape_from_geometry(a, b, ta, tb),
    }


def _frame_ok(m: np.ndarray, body: dict, tangents: bool) -> bool:
    """A view ``m`` shows every A-to-point vector at least MIN_FORESHORTENING of its length
    (and, with tangents, the ends as ``observable_view`` asks)."""
    pts = body["points"]
    if tangents and not observable_view(m, pts[1], body["ta"], body["tb"]):
        return False
    img = np.linalg.norm((pts[1:] @ m.T)[:, :2], axis=1)
    return bool(np.all(img >= MIN_FORESHORTENING * np.linalg.norm(pts[1:], axis=1)))


def _shows_depth(rots: np.ndarray, body: dict) -> bool:
    """Some image distance between two of the points has a standard deviation over the frames
    of at least ``MIN_DISTANCE_STD`` c."""
    img = np.einsum("nij,pj->npi", rots, body["points"])[..., :2]
    p = img.shape[1]
    spread = max(
        float(np.std(np.linalg.norm(img[:, j] - img[:, i], axis=1)))
        for i in range(p)
        for j in range(i + 1, p)
    )
    return spread >= MIN_DISTANCE_STD * float(body["shape"][0])


def _tilted_axis(rng: np.random.Generator) -> np.ndarray:
    """A unit axis at least MIN_AXIS_TILT_DEG from the viewing direction (camera z)."""
    while True:
        n = _unit(rng.normal(size=3))
        if abs(n[2]) <= np.cos(np.radians(MIN_AXIS_TILT_DEG)):
            return n


def _rot(rotvec: np.ndarray) -> np.ndarray:
    """Rotation matrices (..., 3, 3) of rotation vectors (..., 3) (radians)."""
    return Rotation.from_rotvec(rotvec).as_matrix()


def _scene_motion(
    rng: np.random.Generator,
    motion: str,
    t: np.ndarray,
    body: dict,
    tangents: bool,
    sweep: tuple[float, float] = SWEEP_DEG,
) -> tuple[np.ndarray, np.ndarray | None, dict]:
    """(N, 3, 3) body-to-camera rotations, the mass centre's image path (N, 2) for the force
    field (else None) and the true motion parameters; redrawn until every frame is observable.
    ``sweep``: the range of the total turn (degrees) of the force field's rotation."""
    from curverecon.errors import CurveReconError

    for _ in range(2000):
        if motion == "free":
            rots = []
            while len(rots) < len(t):
                m = Rotation.random(random_state=rng).as_matrix()
                if _frame_ok(m, body, tangents):
                    rots.append(m)
            if _shows_depth(np.array(rots), body):
                return np.array(rots), None, {}
            continue
        r0 = Rotation.random(random_state=rng).as_matrix()
        if motion == "force-field":
            rel, centre, params = _force_field_motion(rng, t, r0 @ body["centre"], sweep)
        else:
            rel, params = _axis_motion(rng, motion, t, r0 @ body["points"][1], sweep)
            centre = None
        if rel is None:
            continue
        rots = rel @ r0
        if all(_frame_ok(m, body, tangents) for m in rots) and _shows_depth(rots, body):
            return rots, centre, params
    raise CurveReconError(  # pragma: no cover - a few draws suffice in practice
        f"could not draw an observable {motion} motion over {len(t)} frames"
    )


def _axis_motion(
    rng: np.random.Generator,
    motion: str,
    t: np.ndarray,
    chord0: np.ndarray,
    sweep_range: tuple[float, float] = SWEEP_DEG,
) -> tuple[np.ndarray | None, dict]:
    """Rotations relative to frame 0 about one axis (fixed axis: increasing random angles;
    uniform rotation: a constant rate; a total sweep uniform in ``sweep_range`` degrees, at most
    60 a frame), or None when the axis is too close to the chord."""
    n = _tilted_axis(rng)
    cosang = abs(n @ chord0) / np.linalg.norm(chord0)
    if cosang > np.cos(np.radians(MIN_AXIS_TO_CHORD_DEG)):
        return None, {}
    sweep = min(rng.uniform(*sweep_range), 60.0 * (len(t) - 1))
    if motion == "uniform-rotation":
        rate = sweep / (t[-1] - t[0])
        angles = rate * (t - t[0])
        params = {"axis": n.tolist(), "rate_deg": float(rate), "angle_deg": angles.tolist()}
    else:
        steps = rng.uniform(0.5, 1.5, size=len(t) - 1)
        angles = np.concatenate([[0.0], np.cumsum(steps / steps.sum() * sweep)])
        params = {"axis": n.tolist(), "angle_deg": angles.tolist()}
    return _rot(np.outer(np.radians(angles), n)), params


def _force_field_motion(
    rng: np.random.Generator,
    t: np.ndarray,
    centre0: np.ndarray,
    sweep_range: tuple[float, float] = SWEEP_DEG,
) -> tuple[np.ndarray, np.ndarray, dict]:
    """A smooth free rotation (rotation vector w1 tau + w2 tau^2 / 2, tau = t - t0, w1 at least
    MIN_AXIS_TILT_DEG from the view, |w1| (t_N - t_0) uniform in ``sweep_range`` degrees, at
    most 60 a frame) and the mass centre's image on a parabola in t."""
    span = t[-1] - t[0]
    tau = t - t[0]
    sweep = np.radians(min(rng.uniform(*sweep_range), 60.0 * (len(t) - 1)))
    w1 = _tilted_axis(rng) * sweep / span
    w2 = _unit(rng.normal(size=3)) * rng.uniform(0.0, 0.5) * sweep / span**2
    rel = _rot(np.outer(tau, w1) + np.outer(tau**2 / 2, w2))
    acc = _unit(rng.normal(size=2)) * rng.uniform(200.0, 400.0) * 2 / span**2
    vel = rng.uniform(-100.0, 100.0, size=2) / span - acc * span / 2
    pos = rng.uniform(-50.0, 50.0, size=2)
    path = pos + np.outer(tau, vel) + np.outer(tau**2, acc) / 2
    # the same parabola in absolute t: x_G(t) = g0 + g1 t + g2 t^2 / 2
    g1 = vel - acc * t[0]
    g0 = pos - vel * t[0] + acc * t[0] ** 2 / 2
    params = {
        "acceleration": acc.tolist(),
        "velocity": g1.tolist(),
        "position": g0.tolist(),
        "mass_centre": np.asarray(centre0, float).tolist(),
    }
    return rel, path, params


def _scene_document(rng, cfg, t, pts3, rots, body, noise, with_curve, outlier_fraction):
    """The observations document (noisy points, tangents, polylines, outlier frames) and the
    inlier mask.  ``noise``: (point px, tangent deg or None, curve px)."""
    point_sigma, tangent_sigma, curve_sigma = noise
    n, p = pts3.shape[:2]
    img = pts3[:, :, :2] + rng.normal(scale=point_sigma, size=(n, p, 2))
    ang = None
    if tangent_sigma is not None:
        tan3 = np.stack([rots @ body["ta"], rots @ body["tb"]], axis=1)
        ang = np.arctan2(tan3[..., 1], tan3[..., 0])
        ang = ang + rng.normal(scale=np.radians(tangent_sigma), size=(n, 2))
    inliers = np.ones(n, dtype=bool)
    n_out = int(round(outlier_fraction * n))
    c = float(body["shape"][0])
    for i in rng.choice(n, size=n_out, replace=False) if n_out else []:
        inliers[i] = False
        img[i] = pts3[i, 0, :2] + rng.uniform(-c, c, size=(p, 2))
        if ang is not None:
            ang[i] = rng.uniform(-np.pi, np.pi, size=2)
    frames = []
    for i in range(n):
        frame = {"t": float(t[i]), "A": img[i, 0].tolist(), "B": img[i, 1].tolist()}
        if p > 2:
            frame["points"] = {k: img[i, j].tolist() for j, k in enumerate(cfg.points) if j >= 2}
        if ang is not None:
            frame["tangent_A"] = [float(np.cos(ang[i, 0])), float(np.sin(ang[i, 0]))]
            frame["tangent_B"] = [float(np.cos(ang[i, 1])), float(np.sin(ang[i, 1]))]
        if with_curve:
            cam = body["curve"] @ rots[i].T + pts3[i, 0]
            noisy = cam[:, :2] + rng.normal(scale=curve_sigma, size=(len(cam), 2))
            frame["curve"] = np.round(noisy, 6).tolist()
        frames.append(frame)
    doc = {
        "format": "curverecon.observations/1",
        "projection": cfg.projection,
        "motion": cfg.motion,
        "frames": frames,
    }
    return doc, inliers


def _scene_truth(cfg, t, pts3, rots, body, params, inliers, noise, seed, family) -> dict:
    """The ``curverecon.truth/1`` document of a configuration scene (see
    ``simulate_configuration``)."""
    c, alpha, beta, phi = body["shape"]
    rel = rots @ rots[0].T
    frames = []
    for i in range(len(t)):
        frames.append(
            {
                "t": float(t[i]),
                "points3": {k: pts3[i, j].tolist() for j, k in enumerate(cfg.points)},
                "A3": pts3[i, 0].tolist(),
                "B3": pts3[i, 1].tolist(),
                "tangent_A3": (rots[i] @ body["ta"]).tolist(),
                "tangent_B3": (rots[i] @ body["tb"]).tolist(),
                "rotation": rel[i].tolist(),
                "inlier": bool(inliers[i]),
            }
        )
    r0 = rots[0]
    return {
        "format": "curverecon.truth/1",
        "configuration": cfg.to_json_dict(),
        "seed": int(seed),
        "family": family,
        "c": float(c),
        "alpha_deg": float(np.degrees(alpha)),
        "beta_deg": float(np.degrees(beta)),
        "phi_deg": float(np.degrees(phi)),
        "times": [float(v) for v in t],
        "frames": frames,
        "motion_parameters": params,
        "body": {
            "points": {
                k: (r0 @ x).tolist() for k, x in zip(cfg.points, body["points"], strict=True)
            },
            "curve_s": dict(zip(cfg.points, body["s"], strict=True)),
            "mass_centre": (r0 @ body["centre"]).tolist(),
        },
        "curve3d": (body["curve"] @ r0.T + pts3[0, 0]).tolist(),
        "point_noise": float(noise[0]),
        "tangent_noise_deg": None if noise[1] is None else float(noise[1]),
        "curve_noise": float(noise[2]),
        "outlier_frames": [int(i) for i in np.flatnonzero(~inliers)],
    }


# ---------------------------------------------------------- the perspective and stereo rows
CAMERA_MOTIONS = (*CONFIG_MOTIONS, "rotation-free")
"""Motion models of the perspective and stereo scenes (a pinhole sees depth without rotation)."""

DEFAULT_DISTANCE = 1000.0
"""Depth of the body's centre in frame 0 (input units; with the default chord 100-300 the body
spans a tenth to a third of its distance, so perspective is strong)."""

DEFAULT_FOCAL_PX = 800.0
DEFAULT_PRINCIPAL_POINT = (320.0, 240.0)
"""The default camera of ``simulate --projection perspective|stereo``: 640 x 480 pixels."""

STEREO_BASELINE = 0.25
"""Camera 1 of the default stereo rig: this fraction of the distance to the right of camera 0,
turned to look at the body's centre (X1 = R X0 + t, units of the scene)."""

LATERAL_MOVE = 0.12
DEPTH_MOVE = 0.08
"""Per-frame translation of the body's centre: lateral uniform within this fraction of the
distance, depth within this fraction (both ways)."""

FORCE_FIELD_TURN_DEG = (720.0, 1080.0)
"""Total turn (degrees, uniform in this range, at most 60 a frame) of a perspective or stereo
force-field scene: with A and B under a pinhole the row is determined in practice only when the
body turns about two full turns or more (c's Cramer-Rao bound at 1 px, 30 frames: 8 c at
360 degrees, 4 % at 720, 3 % at 1080; ``bench/persp_force_field_bound.py``, docs/accuracy.md);
the other motions keep ``SWEEP_DEG``."""


def default_camera(distance: float = DEFAULT_DISTANCE):
    """The default pinhole camera with its focal length scaled by ``distance`` /
    DEFAULT_DISTANCE (the image keeps its size when the scene moves away)."""
    from curverecon.solvers.camera import Camera

    return Camera(DEFAULT_FOCAL_PX * distance / DEFAULT_DISTANCE, DEFAULT_PRINCIPAL_POINT)


def default_rig(distance: float = DEFAULT_DISTANCE):
    """Two default cameras; camera 1 at (b, 0, 0), b = STEREO_BASELINE distance, looking at
    (0, 0, distance): its rows x1, y1, z1 in camera 0's coordinates, t = -R (b, 0, 0)."""
    from curverecon.solvers.camera import StereoRig

    b = STEREO_BASELINE * distance
    z1 = _unit(np.array([-b, 0.0, distance]))
    x1 = _unit(np.array([distance, 0.0, b]))
    rot = np.array([x1, np.cross(z1, x1), z1])
    cam = default_camera(distance)
    return StereoRig(cam, cam, rot, -rot @ np.array([b, 0.0, 0.0]))


def simulate_camera_configuration(
    projection: str,
    motion: str,
    points: str = "AB",
    frames: int = 20,
    seed: int = 0,
    noise_px: float = 0.0,
    tangent_noise_deg: float | None = None,
    with_curve: bool = False,
    curve_noise_px: float | None = None,
    times: np.ndarray | None = None,
    *,
    family: str = "bezier",
    chord: tuple[float, float] = (100.0, 300.0),
    outlier_fraction: float = 0.0,
    n_curve_points: int = 150,
    distance: float = DEFAULT_DISTANCE,
    camera=None,
    rig=None,
    move: tuple[float, float] = (LATERAL_MOVE, DEPTH_MOVE),
    turn_deg: tuple[float, float] | None = None,
) -> tuple[dict, dict]:
    """A perspective or stereo scene of a Section 2 row: its observations and its truth.

    The same 3-D construction as :func:`simulate_configuration` (the body, its rotations) with
    depth: the body's centre (the wire's centroid) at (0, 0, ``distance``) in frame 0 and moved
    per frame by ``move`` = (lateral, depth) fractions of the distance (default
    ``LATERAL_MOVE``, ``DEPTH_MOVE``; ``force-field``: the mass
    centre on a 3-D parabola G(t) = g0 + g1 t + g2 t^2 / 2 of that reach; ``rotation-free``:
    R_f = R_0), projected through ``camera`` (default :func:`default_camera`) or both cameras of
    ``rig`` (default :func:`default_rig`; X1 = R X0 + t).  Units of the truth (CONTRACT.md,
    "Configurations"): perspective lengths in units of A's depth in frame 0 (A3 z = 1 there),
    stereo lengths in the scene's units (those of the rig's t).  The truth has per frame
    ``points3`` (camera coordinates with depth; camera 0's for stereo), A3, B3, the unit
    tangents, ``rotation`` (R_f = rot_f rot_0^T) and ``frame_pose`` {"R", "T"} with
    X_f = R X_0 + T; ``curve3d`` in frame 0's camera coordinates; ``motion_parameters`` as the
    orthographic rows' (the force field's ``acceleration``, ``velocity``, ``position`` as 3-D
    vectors of the mass centre in camera coordinates, ``mass_centre`` relative to A in frame 0).
    ``turn_deg`` (lo, hi): the range of the body's total turn over the sequence in degrees (at
    most 60 a frame; default ``FORCE_FIELD_TURN_DEG`` for the force field, else ``SWEEP_DEG``).

    Raises CurveReconError for an unknown projection or motion, bad names, too few frames, a
    bad turn range.
    """
    from curverecon.errors import CurveReconError
    from curverecon.model.configuration import Configuration

    if projection not in ("perspective", "stereo"):
        raise CurveReconError(f'projection "{projection}": choose perspective or stereo')
    if motion not in CAMERA_MOTIONS:
        raise CurveReconError(f'unknown motion "{motion}" (choose {", ".join(CAMERA_MOTIONS)})')
    if not (np.isfinite(distance) and distance > 0):
        raise CurveReconError("the distance must be a positive number")
    names = _point_names(points)
    t = _scene_times(times, frames)
    sweep = _turn_range(motion, turn_deg)
    rng = np.random.default_rng(seed)
    curve = bezier_curve(random_curve(rng, chord)) if family == "bezier" else None
    if curve is None:
        curve = draw_curve(rng, family, chord)
    body = _scene_body(rng, curve, names, n_curve_points)
    tangents = tangent_noise_deg is not None
    if motion == "rotation-free":
        r0 = Rotation.random(random_state=rng).as_matrix()
        while not _frame_ok(r0, body, tangents):
            r0 = Rotation.random(random_state=rng).as_matrix()
        rots, params = np.array([r0] * len(t)), {}
    else:
        rots, _, params = _scene_motion(rng, motion, t, body, tangents, sweep)
    centre, path_params = _centre_path(rng, motion, t, distance, move)
    if motion == "force-field":
        params = {k: v for k, v in params.items() if k == "mass_centre"}
    a3 = centre - np.einsum("nij,j->ni", rots, body["centre"])  # A in every frame
    pts3 = np.einsum("nij,pj->npi", rots, body["points"]) + a3[:, None, :]
    if projection == "perspective":
        camera = camera if camera is not None else default_camera(distance)
        cfg = Configuration("perspective", motion, names, tangents, camera=camera)
        scale = 1.0 / float(pts3[0, 0, 2])
    else:
        rig = rig if rig is not None else default_rig(distance)
        cfg = Configuration("stereo", motion, names, tangents, rig=rig)
        scale = 1.0
    if motion == "force-field":
        params.update({k: (np.asarray(v) * scale).tolist() for k, v in path_params.items()})
        params["mass_centre"] = (rots[0] @ body["centre"] * scale).tolist()
    noise = (noise_px, tangent_noise_deg, noise_px if curve_noise_px is None else curve_noise_px)
    geometry = (t, pts3, rots, body)
    doc, inliers = _camera_document(rng, cfg, geometry, noise, with_curve, outlier_fraction)
    truth = _camera_truth(cfg, geometry, scale, params, inliers, noise, (seed, family))
    return doc, truth


def _turn_range(motion: str, turn_deg) -> tuple[float, float]:
    """The camera scene's range of total turns in degrees (``simulate_camera_configuration``)."""
    from curverecon.errors import CurveReconError

    if turn_deg is None:
        return FORCE_FIELD_TURN_DEG if motion == "force-field" else SWEEP_DEG
    lo, hi = (float(v) for v in turn_deg)
    if not (np.isfinite(lo) and np.isfinite(hi) and 0 < lo <= hi):
        raise CurveReconError("the turn range needs 0 < MIN <= MAX degrees")
    return lo, hi


def _centre_path(rng: np.random.Generator, motion: str, t: np.ndarray, distance: float, move):
    """(N, 3) the body's centre in every frame's camera coordinates and, for the force field,
    its parabola's g0, g1, g2 (``position``, ``velocity``, ``acceleration``, absolute t)."""
    n = len(t)
    home = np.array([0.0, 0.0, distance])
    if motion != "force-field":
        step = np.column_stack(
            [
                rng.uniform(-1.0, 1.0, size=(n, 2)) * move[0],
                rng.uniform(-1.0, 1.0, size=n) * move[1],
            ]
        )
        step[0] = 0.0
        return home + distance * step, {}
    span = t[-1] - t[0]
    tau = (t - t[0]) / span  # 0 .. 1
    reach = distance * np.array([move[0], move[0], move[1]])
    acc = rng.uniform(2.0, 4.0, size=3) * rng.choice([-1.0, 1.0], size=3) * reach
    vel = rng.uniform(-1.0, 1.0, size=3) * reach - acc / 2
    path = home + np.outer(tau, vel) + np.outer(tau**2, acc) / 2
    g2 = acc / span**2
    g1 = vel / span - g2 * t[0]
    g0 = home - g1 * t[0] - g2 * t[0] ** 2 / 2
    return path, {"position": g0, "velocity": g1, "acceleration": g2}


def _camera_views(cfg, pts3: np.ndarray) -> list[tuple]:
    """[(camera, points in that camera's coordinates (N, P, 3), R of that camera)] per view."""
    if cfg.rig is None:
        return [(cfg.camera, pts3, np.eye(3), np.zeros(3))]
    r, tr = np.asarray(cfg.rig.R, float), np.asarray(cfg.rig.t, float)
    return [
        (cfg.rig.camera0, pts3, np.eye(3), np.zeros(3)),
        (cfg.rig.camera1, pts3 @ r.T + tr, r, tr),
    ]


def _image_angles(camera, x: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Image angle (radians) of the direction d (..., 3) at the point x (..., 3): the derivative
    of the pinhole projection, (d_x z - x_x d_z, d_y z - x_y d_z)."""
    u = d[..., 0] * x[..., 2] - x[..., 0] * d[..., 2]
    v = d[..., 1] * x[..., 2] - x[..., 1] * d[..., 2]
    return np.arctan2(v, u)


def _camera_document(rng, cfg, geometry, noise, with_curve, outlier_fraction):
    """The observations document of a camera scene (pixels; stereo frames with two views) and
    the inlier mask; outlier frames (never frame 0, the reference of the units) get random
    points within c' of A' in every view."""
    t, pts3, rots, body = geometry
    point_sigma, tangent_sigma, curve_sigma = noise
    n, p = pts3.shape[:2]
    inliers = np.ones(n, dtype=bool)
    n_out = int(round(outlier_fraction * n))
    out_idx = rng.choice(np.arange(1, n), size=n_out, replace=False) if n_out else []
    inliers[list(out_idx)] = False
    views = []
    for camera, x, r, tr in _camera_views(cfg, pts3):
        img = camera.project(x) + rng.normal(scale=point_sigma, size=(n, p, 2))
        ang = None
        if tangent_sigma is not None:
            dirs = np.stack([rots @ body["ta"], rots @ body["tb"]], axis=1) @ r.T
            ang = _image_angles(camera, x[:, :2], dirs)
            ang = ang + rng.normal(scale=np.radians(tangent_sigma), size=(n, 2))
        c_img = float(np.median(np.linalg.norm(img[:, 1] - img[:, 0], axis=1)))
        for i in out_idx:
            img[i] = img[i, 0] + rng.uniform(-c_img, c_img, size=(p, 2))
            if ang is not None:
                ang[i] = rng.uniform(-np.pi, np.pi, size=2)
        view_frames = []
        for i in range(n):
            frame = {"A": img[i, 0].tolist(), "B": img[i, 1].tolist()}
            if p > 2:
                frame["points"] = {k: img[i, j].tolist() for j, k in enumerate(cfg.points) if j > 1}
            if ang is not None:
                frame["tangent_A"] = [float(np.cos(ang[i, 0])), float(np.sin(ang[i, 0]))]
                frame["tangent_B"] = [float(np.cos(ang[i, 1])), float(np.sin(ang[i, 1]))]
            if with_curve:
                cam3 = (body["curve"] @ rots[i].T + pts3[i, 0]) @ r.T + tr
                noisy = camera.project(cam3) + rng.normal(scale=curve_sigma, size=(len(cam3), 2))
                frame["curve"] = np.round(noisy, 6).tolist()
            view_frames.append(frame)
        views.append(view_frames)
    if len(views) == 1:
        frames = [{"t": float(t[i]), **views[0][i]} for i in range(n)]
    else:
        frames = [{"t": float(t[i]), "views": [views[0][i], views[1][i]]} for i in range(n)]
    doc = {"format": "curverecon.observations/1", **_camera_keys(cfg), "frames": frames}
    return doc, inliers


def _camera_keys(cfg) -> dict:
    """projection, camera(s) and motion of a camera document."""
    out = cfg.to_json_dict()
    keep = {k: out[k] for k in ("projection", "camera", "cameras") if k in out}
    return {**keep, "motion": cfg.motion}


def _camera_truth(cfg, geometry, scale, params, inliers, noise, tag) -> dict:
    """The ``curverecon.truth/1`` document of a camera scene (see
    ``simulate_camera_configuration``)."""
    t, pts3, rots, body = geometry
    c, alpha, beta, phi = body["shape"]
    rel = rots @ rots[0].T
    p3 = pts3 * scale
    frames = []
    for i in range(len(t)):
        trans = p3[i, 0] - rel[i] @ p3[0, 0]
        frames.append(
            {
                "t": float(t[i]),
                "points3": {k: p3[i, j].tolist() for j, k in enumerate(cfg.points)},
                "A3": p3[i, 0].tolist(),
                "B3": p3[i, 1].tolist(),
                "tangent_A3": (rots[i] @ body["ta"]).tolist(),
                "tangent_B3": (rots[i] @ body["tb"]).tolist(),
                "rotation": rel[i].tolist(),
                "frame_pose": {"R": rel[i].tolist(), "T": trans.tolist()},
                "inlier": bool(inliers[i]),
            }
        )
    r0 = rots[0]
    return {
        "format": "curverecon.truth/1",
        "configuration": cfg.to_json_dict(),
        "seed": int(tag[0]),
        "family": tag[1],
        "scale": float(scale),
        "c": float(c * scale),
        "alpha_deg": float(np.degrees(alpha)),
        "beta_deg": float(np.degrees(beta)),
        "phi_deg": float(np.degrees(phi)),
        "times": [float(v) for v in t],
        "frames": frames,
        "motion_parameters": params,
        "body": {
            "points": {
                k: (r0 @ x * scale).tolist()
                for k, x in zip(cfg.points, body["points"], strict=True)
            },
            "curve_s": dict(zip(cfg.points, body["s"], strict=True)),
            "mass_centre": (r0 @ body["centre"] * scale).tolist(),
        },
        "curve3d": ((body["curve"] @ r0.T) * scale + p3[0, 0]).tolist(),
        "point_noise": float(noise[0]),
        "tangent_noise_deg": None if noise[1] is None else float(noise[1]),
        "curve_noise": float(noise[2]),
        "outlier_frames": [int(i) for i in np.flatnonzero(~inliers)],
    }
