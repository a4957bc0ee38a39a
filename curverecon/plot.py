"""Figure of a reconstruction: the recovered curve in 3-D and its reprojection into the frames.

Conventions: ``curve3d`` is (K, 3) in frame 0's camera coordinates (pixels, A at z = 0); the pose
of frame i maps curve coordinates to camera coordinates, ``X_cam = R_i X_curve + t_i``, so a
point of frame 0's camera maps to frame i by ``X_i = R_i R_0^T (X_0 - t_0) + t_i``. Orthographic
projection keeps (x, y). Image panels are drawn with y pointing down (pixel convention).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

#: Most frames drawn as reprojection panels (evenly chosen, frame 0 always included).
MAX_PANELS = 12


def reproject(curve3d: np.ndarray, rotations: np.ndarray, translations: np.ndarray) -> np.ndarray:
    """Image points (N, K, 2) of a frame-0 camera-coordinate curve (K, 3) in every frame."""
    rot = np.asarray(rotations, dtype=float)
    tr = np.asarray(translations, dtype=float)
    x = np.asarray(curve3d, dtype=float)
    m = np.einsum("nij,kj->nik", rot, rot[0])  # R_i R_0^T
    cam = np.einsum("nij,kj->nki", m, x - tr[0]) + tr[:, None, :]
    return cam[..., :2]


def feature_polyline(
    a3: np.ndarray, b3: np.ndarray, tangent_a3: np.ndarray, tangent_b3: np.ndarray
) -> np.ndarray:
    """(4, 3) polyline of one frame's traceable features: tangent stub at A, A, B, stub at B.

    Used to plot a reconstruction whose input has no polylines.  The stubs are a quarter of |AB|
    long and point into the curve (input units, the frame's camera coordinates).
    """
    a3, b3 = np.asarray(a3, float), np.asarray(b3, float)
    length = 0.25 * float(np.linalg.norm(b3 - a3))

    def stub(t: np.ndarray) -> np.ndarray:
        t = np.asarray(t, float)
        return length * t / np.linalg.norm(t)

    return np.array([a3 + stub(tangent_a3), a3, b3, b3 + stub(tangent_b3)])


def _panel_frames(n: int) -> list[int]:
    if n <= MAX_PANELS:
        return list(range(n))
    return sorted({int(round(v)) for v in np.linspace(0, n - 1, MAX_PANELS)})


def plot_reconstruction(
    path: str,
    polylines: Sequence[np.ndarray] | None,
    curve3d: np.ndarray,
    rotations: np.ndarray,
    translations: np.ndarray,
    *,
    features_only: bool = False,
) -> None:
    """Write a PNG: the curve in 3-D (left) and, per frame, its reprojection over the polyline.

    path: output PNG file. polylines: the observed (M_i, 2) polylines per frame, or None (then
    only the reprojection is drawn). curve3d: (K, 3) in frame 0's camera coordinates.
    features_only: ``curve3d`` is not a recovered curve but the traceable features
    (see :func:`feature_polyline`): A and B are its second and third points, and the panels say so.
    rotations (N, 3, 3), translations (N, 3): poses, ``X_cam = R_i X_curve + t_i``.
    At most ``MAX_PANELS`` frames are drawn. Uses the Agg backend (no display needed).
    Raises ``CurveReconError`` for inconsistent shapes or an unwritable path.
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure

    from curverecon.curve.polyline import distance_to_polyline
    from curverecon.errors import CurveReconError

    x = np.asarray(curve3d, dtype=float)
    rot = np.asarray(rotations, dtype=float)
    tr = np.asarray(translations, dtype=float)
    if x.ndim != 2 or x.shape[1] != 3 or len(x) < 2:
        raise CurveReconError(f"curve3d: expected shape (K, 3) with K >= 2, got {x.shape}")
    if rot.ndim != 3 or rot.shape[1:] != (3, 3) or tr.shape != (len(rot), 3) or len(rot) == 0:
        raise CurveReconError("rotations/translations: expected shapes (N, 3, 3) and (N, 3)")
    if polylines is not None and len(polylines) != len(rot):
        raise CurveReconError(f"got {len(polylines)} polylines for {len(rot)} poses")
    n = len(rot)
    frames = _panel_frames(n)
    proj = reproject(x, rot, tr)

    ncols = min(4, len(frames))
    nrows = int(np.ceil(len(frames) / ncols))
    height = max(4.2, 2.6 * nrows + 0.6)
    fig = Figure(figsize=(4.0 + 2.6 * ncols, height), dpi=100)
    gs = fig.add_gridspec(nrows, ncols + 2, width_ratios=[1.6, 0.1] + [1.0] * ncols)

    ax3 = fig.add_subplot(gs[:, 0], projection="3d")
    ia, ib = (1, 2) if features_only else (0, len(x) - 1)
    ax3.plot(x[:, 0], x[:, 1], x[:, 2], color="C0", lw=1.8)
    ax3.scatter(*x[ia], color="C2", s=30, label="A")
    ax3.scatter(*x[ib], color="C3", s=30, label="B")
    span = float(np.ptp(x, axis=0).max()) or 1.0
    centre = 0.5 * (x.min(axis=0) + x.max(axis=0))
    for setlim, c in zip((ax3.set_xlim, ax3.set_ylim, ax3.set_zlim), centre, strict=True):
        setlim(c - 0.55 * span, c + 0.55 * span)
    ax3.invert_yaxis()  # image y points down
    ax3.set_xlabel("x")
    ax3.set_ylabel("y")
    ax3.set_zlabel("z (depth)")
    what = (
        "A, B and end tangents\n(no polylines in the input)" if features_only else "recovered curve"
    )
    ax3.set_title(f"{what}\n(frame 0 camera coordinates)", fontsize=9)
    ax3.legend(loc="upper left", fontsize=7)
    ax3.tick_params(labelsize=6)

    for slot, i in enumerate(frames):
        ax = fig.add_subplot(gs[slot // ncols, 2 + slot % ncols])
        title = f"frame {i}"
        if polylines is not None:
            p = np.asarray(polylines[i], dtype=float)
            if p.ndim == 2 and p.shape[1] == 2 and len(p) >= 2 and np.all(np.isfinite(p)):
                ax.plot(p[:, 0], p[:, 1], color="0.6", lw=3.0, label="observed")
                resid = np.median(distance_to_polyline(proj[i], p)[0])
                title += f"  (median off {resid:.1f} px)"
        ax.plot(proj[i, :, 0], proj[i, :, 1], color="C1", lw=1.0, label="reprojected")
        ax.plot(*proj[i, ia], "o", color="C2", ms=3)
        ax.plot(*proj[i, ib], "o", color="C3", ms=3)
        ax.set_aspect("equal", adjustable="datalim")
        ax.invert_yaxis()
        ax.set_title(title, fontsize=8)
        ax.tick_params(labelsize=6)
        if slot == 0:
            ax.legend(fontsize=6, loc="best")
    fig.suptitle(
        f"Reconstruction: {n} frame{'s' if n != 1 else ''}"
        + (f" (showing {len(frames)})" if len(frames) < n else ""),
        fontsize=10,
    )
    fig.subplots_adjust(
        left=0.02, right=0.98, top=1.0 - 0.75 / height, bottom=0.3 / height, wspace=0.35, hspace=0.4
    )
    try:
        fig.savefig(path)
    except OSError as exc:
        raise CurveReconError(f"cannot write plot {path}: {exc.strerror or exc}") from None
    finally:
        plt.close("all")


def plot_reconstruction_file(path: str, rec, obs) -> None:
    """Draw a :class:`curverecon.model.reconstruction.Reconstruction` of ``obs`` to a PNG file:
    its ``curve3d`` over every frame's polyline, or, without polylines, the features that were
    reconstructed (A, B and the end tangents)."""
    curve3d = rec.curve3d
    features_only = curve3d is None
    if features_only:
        curve3d = feature_polyline(*(v[0] for v in rec.points_3d()))
    plot_reconstruction(
        path,
        obs.curves,
        curve3d,
        rec.rotations(),
        rec.translations(),
        features_only=features_only,
    )


def plot_configuration_file(path: str, rec, obs) -> None:
    """Draw a reconstruction of a configuration beyond the paper's own (``RigidObservations``)
    to a PNG file: every frame's traceable points in 3-D relative to A (each frame's camera
    axes, A at the origin, frame 0 darkest: the body turning as the camera saw it) with the
    recovered curve of frame 0 if any, and per frame the observed points (and polyline) beside
    the reconstructed points' projections (x, y).

    Raises ``CurveReconError`` when the reconstruction has no per-frame points or the path is
    not writable."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure

    from curverecon.errors import CurveReconError

    names = list(obs.configuration.points)
    if rec.points3 is None or len(rec.points3) != obs.n_frames:
        raise CurveReconError("the reconstruction has no per-frame points to plot")
    p3 = np.array(
        [[rec.points3[i].get(k, [np.nan] * 3) for k in names] for i in range(obs.n_frames)]
    )
    frames = _panel_frames(obs.n_frames)
    ncols = min(4, len(frames))
    nrows = int(np.ceil(len(frames) / ncols))
    height = max(4.2, 2.6 * nrows + 0.6)
    fig = Figure(figsize=(4.0 + 2.6 * ncols, height), dpi=100)
    gs = fig.add_gridspec(nrows, ncols + 2, width_ratios=[1.6, 0.1] + [1.0] * ncols)
    ax3 = fig.add_subplot(gs[:, 0], projection="3d")
    shade = np.linspace(1.0, 0.25, obs.n_frames)
    rel = p3 - p3[:, :1]
    for i in range(obs.n_frames):
        ax3.plot(*rel[i].T, "-o", color=(0.1, 0.3, 0.7, shade[i]), ms=3, lw=0.8)
    shown = rel.reshape(-1, 3)
    if rec.curve3d is not None:
        c = np.asarray(rec.curve3d, float) - p3[0, 0]
        ax3.plot(*c.T, color="C1", lw=1.8, label="curve (frame 0)")
        ax3.legend(loc="upper left", fontsize=7)
        shown = np.concatenate([shown, c])
    shown = shown[np.all(np.isfinite(shown), axis=1)]
    if len(shown):
        span = float(np.ptp(shown, axis=0).max()) or 1.0
        centre = 0.5 * (shown.min(axis=0) + shown.max(axis=0))
        for setlim, m in zip((ax3.set_xlim, ax3.set_ylim, ax3.set_zlim), centre, strict=True):
            setlim(m - 0.55 * span, m + 0.55 * span)
    ax3.invert_yaxis()  # image y points down
    ax3.set_xlabel("x")
    ax3.set_ylabel("y")
    ax3.set_zlabel("z (depth)")
    motion = (rec.configuration or {}).get("motion", obs.configuration.motion)
    ax3.set_title(f"{', '.join(names)} in every frame, A at 0\n(motion {motion})", fontsize=9)
    ax3.tick_params(labelsize=6)
    for slot, i in enumerate(frames):
        ax = fig.add_subplot(gs[slot // ncols, 2 + slot % ncols])
        if obs.curves is not None:
            ax.plot(*obs.curves[i].T, color="0.6", lw=3.0, label="observed curve")
        ax.plot(*obs.points[i].T, "x", color="k", ms=5, label="observed")
        ax.plot(*p3[i, :, :2].T, "o", mfc="none", color="C3", ms=6, label="reconstructed")
        for k, name in enumerate(names):
            ax.annotate(
                name, obs.points[i, k], fontsize=6, xytext=(3, 3), textcoords="offset points"
            )
        ax.set_aspect("equal", adjustable="datalim")
        ax.invert_yaxis()
        ax.set_title(f"frame {i} (t = {obs.times[i]:g})", fontsize=8)
        ax.tick_params(labelsize=6)
        if slot == 0:
            ax.legend(fontsize=6, loc="best")
    fig.suptitle(f"Reconstruction: {obs.n_frames} frames, motion {motion}", fontsize=10)
    fig.subplots_adjust(left=0.02, right=0.98, top=1.0 - 0.75 / height, bottom=0.3 / height)
    try:
        fig.savefig(path)
    except OSError as exc:
        raise CurveReconError(f"cannot write plot {path}: {exc.strerror or exc}") from None
    finally:
        plt.close("all")


def camera_views(obs) -> list[tuple[str, object, np.ndarray, np.ndarray]]:
    """The cameras of a perspective or stereo ``RigidObservations``: (label, Camera, R, t) with
    the camera's coordinates ``R X + t`` of a point X in the frame's camera(-0) coordinates."""
    from curverecon.errors import CurveReconError

    cfg = obs.configuration
    if cfg.projection == "perspective":
        return [("camera", cfg.camera, np.eye(3), np.zeros(3))]
    if cfg.projection == "stereo":
        rig = cfg.rig
        return [
            ("camera 0", rig.camera0, np.eye(3), np.zeros(3)),
            ("camera 1", rig.camera1, np.asarray(rig.R, float), np.asarray(rig.t, float)),
        ]
    raise CurveReconError(f'no camera to draw for projection "{cfg.projection}"')


def camera_reprojection(rec, obs) -> list[dict]:
    """Per frame, what the figure draws over each view: ``{"curve": [(K, 2) or None per view],
    "points": [(P, 2) or None per view]}`` in pixels.

    The curve: ``rec.curve3d`` (frame 0's camera(-0) coordinates) moved to frame f by
    ``rec.frame_poses`` (X_f = R_f X_0 + T_f), then into each camera and projected; without
    frame poses only frame 0 has it.  The points: ``rec.points3[f]`` (frame f's camera(-0)
    coordinates, the configuration's point order) projected.
    """
    views = camera_views(obs)
    names = list(obs.configuration.points)
    curve = None if rec.curve3d is None else np.asarray(rec.curve3d, float)
    poses = None if rec.frame_poses is None else np.asarray(rec.frame_poses, float)
    out = []
    for f in range(obs.n_frames):
        xf = None
        if curve is not None and (poses is not None or f == 0):
            xf = curve if poses is None else curve @ poses[f, :, :3].T + poses[f, :, 3]
        pf = None
        if rec.points3 is not None and f < len(rec.points3):
            pf = np.array([rec.points3[f].get(k, [np.nan] * 3) for k in names], dtype=float)
        out.append(
            {
                "curve": [
                    None if xf is None else cam.project(xf @ r.T + t) for _, cam, r, t in views
                ],
                "points": [
                    None if pf is None else cam.project(pf @ r.T + t) for _, cam, r, t in views
                ],
            }
        )
    return out


def camera_frustums(rec, obs, depth: float) -> list[dict]:
    """Every frame's camera(s) in frame 0's camera(-0) coordinates: ``{"frame", "label",
    "centre" (3,), "axes" (3, 3) rows x, y, z, "corners" (4, 3)}``.  Camera k of frame f has
    its centre at R_f^T (C_k - T_f) with C_k = -R_k^T t_k (C_f = -R_f^T T_f for camera 0);
    the corners are the image's corners (the image taken as twice the principal point) at
    ``depth`` along the optical axis.  Without frame poses only frame 0 is drawn."""
    views = camera_views(obs)
    poses = None if rec.frame_poses is None else np.asarray(rec.frame_poses, float)
    frames = range(obs.n_frames) if poses is not None else range(1)
    out = []
    for f in frames:
        rf = np.eye(3) if poses is None else poses[f, :, :3]
        tf = np.zeros(3) if poses is None else poses[f, :, 3]
        for label, cam, r, t in views:
            cx, cy = (float(v) for v in cam.principal_point)
            px = np.array([[0.0, 0.0], [2 * cx, 0.0], [2 * cx, 2 * cy], [0.0, 2 * cy]])
            local = np.vstack([np.zeros(3), depth * cam.rays(px)])
            in_f = (local - t) @ r  # camera k's coordinates -> frame f's camera(-0)
            in_0 = (in_f - tf) @ rf
            axes = (r.T @ np.eye(3)).T @ rf  # rows: camera k's axes in frame 0's coordinates
            out.append(
                {"frame": f, "label": label, "centre": in_0[0], "axes": axes, "corners": in_0[1:]}
            )
    return out


#: Most frames drawn as image panels of a stereo figure (two panels each).
MAX_STEREO_FRAMES = 6


def _scene_depth(rec, obs) -> float:
    """A frustum's drawn depth: a quarter of the scene's median depth in frame 0."""
    pts = [] if rec.curve3d is None else [np.asarray(rec.curve3d, float)]
    if rec.points3:
        pts.append(np.array(list(rec.points3[0].values()), dtype=float).reshape(-1, 3))
    z = np.concatenate([p[:, 2] for p in pts]) if pts else np.array([1.0])
    z = z[np.isfinite(z) & (z > 0)]
    return 0.25 * float(np.median(z)) if len(z) else 0.25


def _draw_frustums(ax3, rec, obs) -> np.ndarray:
    """Every camera as a frustum in the 3-D panel; returns the drawn points (for the limits)."""
    frustums = camera_frustums(rec, obs, _scene_depth(rec, obs))
    shown = []
    n = max(1, obs.n_frames - 1)
    for fr in frustums:
        c, k = fr["centre"], fr["corners"]
        colour = (0.2, 0.2, 0.2) if fr["label"] != "camera 1" else (0.6, 0.1, 0.5)
        alpha = 1.0 - 0.7 * fr["frame"] / n
        for corner in k:
            ax3.plot(*np.column_stack([c, corner]), color=colour, lw=0.6, alpha=alpha)
        ring = np.vstack([k, k[:1]])
        ax3.plot(*ring.T, color=colour, lw=0.8, alpha=alpha)
        ax3.plot(*np.column_stack([c, c + 0.6 * (k.mean(axis=0) - c)]), color="C0", lw=0.6)
        if fr["frame"] == 0:
            ax3.text(*c, f" {fr['label']}, frame 0", fontsize=6, color=colour)
        shown.append(np.vstack([c, k]))
    for label, colour in _frustum_legend(obs):
        ax3.plot([], [], color=colour, lw=0.8, label=label)
    return np.concatenate(shown)


def _frustum_legend(obs) -> list[tuple[str, tuple]]:
    """Legend entries of the frustums: (label, colour) per camera of the rig."""
    fade = "frame 0 dark, later frames fainter" if obs.n_frames > 1 else "frame 0"
    if obs.configuration.projection == "stereo":
        return [(f"camera 0 ({fade})", (0.2, 0.2, 0.2)), ("camera 1", (0.6, 0.1, 0.5))]
    return [(f"camera ({fade})", (0.2, 0.2, 0.2))]


def _camera_3d_panel(ax3, rec, obs) -> None:
    """The curve (frame 0), frame 0's points and every frame's camera(s); equal axes."""
    shown = [_draw_frustums(ax3, rec, obs)]
    if rec.curve3d is not None:
        c = np.asarray(rec.curve3d, float)
        ax3.plot(*c.T, color="C1", lw=1.8, label="curve (frame 0)")
        shown.append(c)
    if rec.points3:
        p = np.array(list(rec.points3[0].values()), dtype=float).reshape(-1, 3)
        ax3.scatter(*p.T, color="C3", s=12, label="points (frame 0)")
        for name, x in zip(rec.points3[0], p, strict=False):
            ax3.text(*x, f" {name}", fontsize=7, color="C3")
        shown.append(p)
    allp = np.concatenate(shown)
    allp = allp[np.all(np.isfinite(allp), axis=1)]
    span = float(np.ptp(allp, axis=0).max()) or 1.0
    centre = 0.5 * (allp.min(axis=0) + allp.max(axis=0))
    for setlim, m in zip((ax3.set_xlim, ax3.set_ylim, ax3.set_zlim), centre, strict=True):
        setlim(m - 0.55 * span, m + 0.55 * span)
    ax3.set_box_aspect((1, 1, 1))
    ax3.invert_yaxis()  # image y points down
    ax3.set_xlabel("x")
    ax3.set_ylabel("y")
    ax3.set_zlabel("z (depth)")
    ax3.set_title("curve and cameras\n(frame 0 camera coordinates)", fontsize=9)
    ax3.legend(loc="upper left", fontsize=7)
    ax3.tick_params(labelsize=6)


def _observed(obs, f: int, view: int):
    """(polyline or None, points (P, 2)) camera ``view`` saw in frame f."""
    src = obs if view == 0 else obs.view1
    curve = None if src.curves is None else np.asarray(src.curves[f], float)
    return curve, np.asarray(src.points[f], float)


def _image_frame(ax, camera, data: list) -> None:
    """The image's border (dashed; its size taken as twice the principal point, seen where the
    curve comes near it) and limits on what is drawn (the fit is judged there), y down."""
    w, h = (2.0 * float(v) for v in camera.principal_point)
    ax.plot([0, w, w, 0, 0], [0, 0, h, h, 0], ls="--", lw=0.6, color="0.7")
    pts = np.concatenate([np.asarray(d, float).reshape(-1, 2) for d in data])
    pts = pts[np.all(np.isfinite(pts), axis=1)]
    if len(pts):  # a square view about what is drawn: equal axes without matplotlib's warning
        mid = 0.5 * (pts.min(axis=0) + pts.max(axis=0))
        half = 0.54 * float(np.max(pts.max(axis=0) - pts.min(axis=0))) + 1.0
        ax.set_xlim(mid[0] - half, mid[0] + half)
        ax.set_ylim(mid[1] + half, mid[1] - half)
    else:
        ax.invert_yaxis()
    ax.set_aspect("equal", adjustable="box")


def _image_panel(ax, obs, f, view, label, drawn) -> None:
    """Frame ``f`` as camera ``view`` saw it (the whole image) with the answer reprojected."""
    from curverecon.curve.polyline import distance_to_polyline

    poly, pts = _observed(obs, f, view)
    title = f"frame {f}, {label}"
    if poly is not None:
        ax.plot(*poly.T, color="0.6", lw=3.0, label="observed")
    ax.plot(*pts.T, "x", color="k", ms=5, label="observed points")
    curve, points = drawn["curve"][view], drawn["points"][view]
    if curve is not None:
        ax.plot(*curve.T, color="C1", lw=1.0, label="reprojected")
        if poly is not None and len(poly) >= 2:
            off = np.median(distance_to_polyline(curve, poly)[0])
            title += f"\n(median off {off:.2f} px)"
    if points is not None:
        ax.plot(*points.T, "o", mfc="none", color="C3", ms=6, label="reprojected points")
    drawn_xy = [pts] + [d for d in (poly, curve, points) if d is not None]
    _image_frame(ax, camera_views(obs)[view][1], drawn_xy)
    ax.set_title(title, fontsize=8)
    ax.tick_params(labelsize=6)


#: The 3-D panel gets an enlarged view of the curve when the curve spans less than this fraction
#: of what that panel shows (a body a tenth of its distance across is a few pixels wide there).
ZOOM_BELOW = 0.3


def _curve_points(rec) -> np.ndarray:
    """The answer's 3-D curve and frame 0's named points (finite rows only), (M, 3)."""
    shown = [np.zeros((0, 3))]
    if rec.curve3d is not None:
        shown.append(np.asarray(rec.curve3d, float).reshape(-1, 3))
    if rec.points3:
        shown.append(np.array(list(rec.points3[0].values()), dtype=float).reshape(-1, 3))
    allp = np.concatenate(shown)
    return allp[np.all(np.isfinite(allp), axis=1)]


def _needs_zoom(rec, obs) -> bool:
    """Whether the curve spans less than ``ZOOM_BELOW`` of the 3-D panel's extent (the curve and
    every camera drawn, as :func:`_camera_3d_panel` frames them)."""
    pts = _curve_points(rec)
    if len(pts) < 3:  # A and B alone: two dots, nothing to enlarge
        return False
    frustums = camera_frustums(rec, obs, _scene_depth(rec, obs))
    allp = np.concatenate([pts] + [np.vstack([f["centre"], f["corners"]]) for f in frustums])
    allp = allp[np.all(np.isfinite(allp), axis=1)]
    return float(np.ptp(pts, axis=0).max()) < ZOOM_BELOW * float(np.ptp(allp, axis=0).max())


def _curve_zoom_panel(ax3, rec) -> None:
    """The curve and frame 0's named points alone, enlarged; equal axes, y down."""
    if rec.curve3d is not None:
        ax3.plot(*np.asarray(rec.curve3d, float).T, color="C1", lw=1.8)
    if rec.points3:
        for name, x in rec.points3[0].items():
            ax3.scatter(*np.asarray(x, float), color="C3", s=12)
            ax3.text(*np.asarray(x, float), f" {name}", fontsize=7, color="C3")
    pts = _curve_points(rec)
    span = float(np.ptp(pts, axis=0).max()) or 1.0
    centre = 0.5 * (pts.min(axis=0) + pts.max(axis=0))
    for setlim, m in zip((ax3.set_xlim, ax3.set_ylim, ax3.set_zlim), centre, strict=True):
        setlim(m - 0.55 * span, m + 0.55 * span)
    ax3.set_box_aspect((1, 1, 1))
    ax3.invert_yaxis()
    ax3.set_xlabel("x")
    ax3.set_ylabel("y")
    ax3.set_zlabel("z (depth)")
    ax3.set_title("the curve enlarged (same coordinates)", fontsize=9)
    ax3.tick_params(labelsize=6)


def plot_camera_file(path: str, rec, obs) -> None:
    """Draw a perspective or stereo reconstruction to a PNG file: per frame (a few, evenly
    chosen) and per camera the observed polyline and points with the answer's reprojection
    (:func:`camera_reprojection`), and a 3-D panel with the curve and every frame's camera(s)
    as frustums (:func:`camera_frustums`), equal axes.

    ``rec``: a Reconstruction with ``frame_poses``, ``curve3d`` and ``points3`` where it has
    them; ``obs``: the ``RigidObservations`` it answers.  Raises ``CurveReconError`` for a
    projection without cameras or an unwritable path."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure

    from curverecon.errors import CurveReconError

    views = camera_views(obs)
    drawn = camera_reprojection(rec, obs)
    frames = _panel_frames(obs.n_frames)
    if len(views) > 1 and len(frames) > MAX_STEREO_FRAMES:
        frames = sorted({int(round(v)) for v in np.linspace(0, obs.n_frames - 1, 6)})
    panels = [(f, v) for f in frames for v in range(len(views))]
    ncols = min(4, len(panels)) if len(views) == 1 else 2 * min(2, len(frames))
    nrows = int(np.ceil(len(panels) / ncols))
    height = max(4.2, 2.8 * nrows + 0.6)
    fig = Figure(figsize=(4.5 + 2.6 * ncols, height), dpi=100)
    gs = fig.add_gridspec(nrows, ncols + 2, width_ratios=[1.8, 0.1] + [1.0] * ncols)
    if _needs_zoom(rec, obs):  # the overview above, the curve enlarged below
        left = gs[:, 0].subgridspec(2, 1, height_ratios=[1.5, 1.0], hspace=0.25)
        _camera_3d_panel(fig.add_subplot(left[0], projection="3d"), rec, obs)
        _curve_zoom_panel(fig.add_subplot(left[1], projection="3d"), rec)
    else:
        _camera_3d_panel(fig.add_subplot(gs[:, 0], projection="3d"), rec, obs)
    for slot, (f, v) in enumerate(panels):
        ax = fig.add_subplot(gs[slot // ncols, 2 + slot % ncols])
        _image_panel(ax, obs, f, v, views[v][0], drawn[f])
        if slot == 0:
            ax.legend(fontsize=6, loc="best")
    cfg = obs.configuration
    motion = (rec.configuration or {}).get("motion", cfg.motion)  # auto: the chosen model
    fig.suptitle(
        f"Reconstruction ({cfg.projection}, motion {motion}): {obs.n_frames} frame"
        + ("s" if obs.n_frames != 1 else "")
        + (f" (showing {len(frames)})" if len(frames) < obs.n_frames else ""),
        fontsize=10,
    )
    fig.subplots_adjust(
        left=0.02, right=0.98, top=1.0 - 0.8 / height, bottom=0.3 / height, wspace=0.35, hspace=0.5
    )
    try:
        fig.savefig(path)
    except OSError as exc:
        raise CurveReconError(f"cannot write plot {path}: {exc.strerror or exc}") from None
    finally:
        plt.close("all")
