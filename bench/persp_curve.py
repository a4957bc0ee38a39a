"""The ordinary camera beyond the Section 2 table: free motion, A, B and polylines, one pinhole.

Scenes (:func:`make_scene`, an independent 3-D construction): a curve of
``curverecon.curve_families`` (bezier, helix, clothoid, fourier, random in turn), a random
rotation per frame (``Rotation.random``), its middle at ``distance`` in front of a calibrated
camera (focal length ``FOCAL_PX`` times ``distance / DISTANCE``, so that the curve keeps its
image size whatever its distance) with a random sideways shift, the curve scaled so that its
depth varies over each frame by ``distance / ratio`` on average (ratio 5: a fifth of its
distance); polylines of 120 points, A' and B' with Gaussian noise ``sigma`` px per coordinate;
no tangents (the ordinary camera traces A and B and the curve).

Keys (``run``):
- ``config_persp_free_curve_curve_within_1pct_rate`` (target >= 0.95): scenes at 20 frames,
  0.5 px, ratio 5, whose ``curve3d`` lies within 1 % of the curve's length of the truth (mean
  symmetric distance / length, in frame 0's camera coordinates with A's depth 1, no mirror
  allowed); ``..._curve_or_alternative_within_1pct_rate``: the same for the answer's curve or,
  where the answer lists the mirror image as an alternative (``curve_bundle.mirror_curve3d``,
  the depth order undecided), that one; ``..._oracle_within_1pct_rate``: the same for the
  pinhole bundle started at the truth.
- the sweep over the ratio distance / depth variation (``SWEEP_RATIOS``): the rate, the rate up
  to the mirror image, the rate of the answer or its listed alternative, how often the mirror
  is listed, the median relative std of the scale (|AB| in units of A's depth), the
  median chi2 gap to the mirror image; plotted in bench/persp_curve_vs_distance.png.

``python -m bench.persp_curve [--scenes N] [--seed S]`` prints the keys.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402
from dataclasses import dataclass  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
from scipy.spatial.transform import Rotation  # noqa: E402

from curverecon.curve import pinhole  # noqa: E402
from curverecon.curve_families import draw_curve  # noqa: E402
from curverecon.errors import CurveReconError  # noqa: E402
from curverecon.model.configuration import Configuration, RigidObservations  # noqa: E402
from curverecon.options import ReconstructOptions  # noqa: E402
from curverecon.solvers.camera import Camera  # noqa: E402

FOCAL_PX = 800.0
PRINCIPAL_POINT = (640.0, 480.0)
DISTANCE = 10.0
"""The curve's distance at which the focal length is ``FOCAL_PX`` (lengths: any unit)."""
FAMILIES = ("bezier", "helix", "clothoid", "fourier", "random")
SWEEP_RATIOS = (5.0, 10.0, 20.0, 50.0, 200.0)
POLYLINE_POINTS = 120
PLOT = Path(__file__).with_name("persp_curve_vs_distance.png")


@dataclass
class PerspScene:
    """A perspective scene with its truth: ``curve0`` (M, 3) in frame 0's camera coordinates
    (A first), ``rot``/``trans`` frame 0 -> frame f (X_f = rot X_0 + trans)."""

    obs: RigidObservations
    curve0: np.ndarray
    rot: np.ndarray
    trans: np.ndarray
    sigma: float


def _body_curve(rng: np.random.Generator, family: str) -> np.ndarray:
    """(M, 3) points of a curve of ``family`` from A to B (unit-ish chord)."""
    s = np.linspace(0.0, 1.0, POLYLINE_POINTS)
    if family == "bezier":
        from curverecon.curve_families import bezier_curve

        ctrl = rng.normal(size=(4, 3))
        return bezier_curve(ctrl).points(s)
    return draw_curve(rng, family, (0.8, 1.2)).points(s)


def make_scene(
    seed: int,
    n_frames: int = 20,
    sigma: float = 0.5,
    ratio: float = 5.0,
    family: str | None = None,
    length_ab: float | None = None,
) -> PerspScene:
    """A random perspective scene (see the module docstring); ``ratio``: the curve's distance
    over its mean depth variation in a frame."""
    rng = np.random.default_rng([seed, int(ratio * 100), n_frames])
    family = family or FAMILIES[seed % len(FAMILIES)]
    body = _body_curve(rng, family)
    body = body - 0.5 * (body.min(0) + body.max(0))
    rots = Rotation.random(n_frames, random_state=rng).as_matrix()
    depth_range = np.mean([np.ptp(body @ r[2]) for r in rots])
    distance = DISTANCE
    body = body * (distance / ratio / depth_range)
    focal = FOCAL_PX * ratio / 5.0
    shift = rng.uniform(-0.15, 0.15, size=(n_frames, 2)) * distance * 5.0 / ratio
    centre = np.column_stack([shift, distance * (1.0 + rng.uniform(-0.25, 0.25, n_frames) / ratio)])
    cam_pts = np.einsum("fij,mj->fmi", rots, body) + centre[:, None, :]
    camera = Camera(focal, PRINCIPAL_POINT)
    pix = camera.project(cam_pts)
    noisy = pix + rng.normal(scale=sigma, size=pix.shape)
    points = np.stack([noisy[:, 0], noisy[:, -1]], axis=1)
    curves = [noisy[f, 1:-1] for f in range(n_frames)]
    curves = [np.vstack([points[f, 0], c, points[f, 1]]) for f, c in enumerate(curves)]
    cfg = Configuration("perspective", "free", ("A", "B"), False, camera, None, length_ab)
    obs = RigidObservations(cfg, np.arange(n_frames, dtype=float), points, None, curves)
    rel = np.einsum("fij,kj->fik", rots, rots[0])
    trans = centre - np.einsum("fij,j->fi", rel, centre[0])
    unit = cam_pts[0, 0, 2] if length_ab is None else length_ab / np.linalg.norm(body[-1] - body[0])
    return PerspScene(obs, cam_pts[0] / unit, rel, trans / unit, sigma)


def curve_error(recovered: np.ndarray, truth: np.ndarray) -> float:
    """Symmetric mean distance between two polylines over the true length (no mirror)."""
    from bench.curve_end_to_end import _mean_distance

    length = float(np.linalg.norm(np.diff(truth, axis=0), axis=1).sum())
    return 0.5 * (_mean_distance(recovered, truth) + _mean_distance(truth, recovered)) / length


def mirrored(curve: np.ndarray) -> np.ndarray:
    """The curve's depth reversed about A's depth (the orthographic answer's other image)."""
    out = curve.copy()
    out[:, 2] = 2.0 * curve[0, 2] - curve[:, 2]
    return out


def oracle_fit(scene: PerspScene) -> pinhole.PinholeFit:
    """The pinhole bundle started at the truth (curve, rotations, translations)."""
    obs = scene.obs
    data = pinhole._prepare(
        obs.configuration.camera, obs.curves, obs.point("A"), obs.point("B"), scene.sigma, 1.0
    )
    ctrl = pinhole.fit_spline(scene.curve0, pinhole.CONTROL_POINTS)
    free = np.ones(3 * pinhole.CONTROL_POINTS + 6 * obs.n_frames, bool)
    free[2] = False
    free[3 * pinhole.CONTROL_POINTS : 3 * pinhole.CONTROL_POINTS + 6] = False
    return pinhole.bundle(data, ctrl, scene.rot.copy(), scene.trans.copy(), free)


def scene_row(seed: int, ratio: float, n_frames: int = 20, sigma: float = 0.5) -> dict:
    """One scene: the answer's curve error (and up to the mirror, and the answer or its
    listed alternative), its scale's relative std, the mirror gap, the oracle's error, the
    answer's and the oracle's chi2, the time."""
    sc = make_scene(seed, n_frames, sigma, ratio)
    opts = ReconstructOptions(point_sigma=sigma)
    t0 = time.perf_counter()
    try:
        rec = pinhole.reconstruct_perspective_curve(sc.obs, opts)
    except CurveReconError as exc:
        return {"seed": seed, "ratio": ratio, "error": None, "failed": str(exc)}
    seconds = time.perf_counter() - t0
    err = curve_error(rec.curve3d, sc.curve0)
    err_m = min(err, curve_error(mirrored(rec.curve3d), sc.curve0))
    listed = rec.curve_bundle.get("mirror_curve3d")
    err_alt = err if listed is None else min(err, curve_error(np.asarray(listed), sc.curve0))
    oracle = oracle_fit(sc)
    o_curve, _, _ = pinhole.curve_points_and_std(oracle)
    c_std = None if rec.std is None else float(rec.std[0] / rec.shape[0])
    return {
        "seed": seed,
        "ratio": ratio,
        "error": err,
        "error_up_to_mirror": err_m,
        "error_or_alternative": err_alt,
        "alternative_listed": listed is not None,
        "oracle_error": curve_error(o_curve, sc.curve0),
        "chi2": rec.chi2,
        "oracle_chi2": oracle.cost,
        "scale_relative_std": c_std,
        "mirror_dchi2": rec.curve_bundle["mirror_dchi2"],
        "seconds": seconds,
    }


def _rate(rows: list[dict], key: str) -> float:
    vals = [r.get(key) for r in rows]
    return float(np.mean([v is not None and v < 0.01 for v in vals]))


def _median(rows: list[dict], key: str) -> float | None:
    vals = [r[key] for r in rows if r.get(key) is not None]
    return float(np.median(vals)) if vals else None


def run(seed: int = 0, scenes: int = 20, sweep_scenes: int | None = None, workers: int = 1) -> dict:
    """The keys of the module docstring: ``scenes`` scenes at ratio 5, ``sweep_scenes``
    (default ``scenes // 2``) at every other ratio of the sweep, on ``workers`` processes;
    writes the PNG plot."""
    sweep_scenes = sweep_scenes or max(scenes // 2, 1)
    jobs = [
        (seed + i, ratio)
        for ratio in SWEEP_RATIOS
        for i in range(scenes if ratio == 5.0 else sweep_scenes)
    ]
    if workers > 1:
        import multiprocessing

        with multiprocessing.get_context("fork").Pool(workers) as pool:
            done = pool.starmap(scene_row, jobs)
    else:
        done = [scene_row(*job) for job in jobs]
    rows = {
        ratio: [r for r, (_, q) in zip(done, jobs, strict=True) if q == ratio]
        for ratio in SWEEP_RATIOS
    }
    main = rows[5.0]
    out = {
        "config_persp_free_curve_curve_within_1pct_rate": _rate(main, "error"),
        "config_persp_free_curve_curve_or_alternative_within_1pct_rate": _rate(
            main, "error_or_alternative"
        ),
        "config_persp_free_curve_oracle_within_1pct_rate": _rate(main, "oracle_error"),
        "config_persp_free_curve_curve_error_median": _median(main, "error"),
        "config_persp_free_curve_seconds_median": _median(main, "seconds"),
        "config_persp_free_curve_scenes": len(main),
        "config_persp_free_curve_vs_distance": [
            {
                "distance_over_depth_variation": ratio,
                "curve_within_1pct_rate": _rate(rows[ratio], "error"),
                "curve_within_1pct_rate_up_to_mirror": _rate(rows[ratio], "error_up_to_mirror"),
                "curve_or_alternative_within_1pct_rate": _rate(rows[ratio], "error_or_alternative"),
                "alternative_listed_rate": float(
                    np.mean([bool(r.get("alternative_listed")) for r in rows[ratio]])
                ),
                "oracle_within_1pct_rate": _rate(rows[ratio], "oracle_error"),
                "scale_relative_std_median": _median(rows[ratio], "scale_relative_std"),
                "mirror_dchi2_median": _median(rows[ratio], "mirror_dchi2"),
                "scenes": len(rows[ratio]),
            }
            for ratio in SWEEP_RATIOS
        ],
    }
    _plot(out["config_persp_free_curve_vs_distance"])
    return out


def _plot(sweep: list[dict]) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    x = [s["distance_over_depth_variation"] for s in sweep]
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(10, 4))
    ax0.plot(x, [s["curve_within_1pct_rate"] for s in sweep], "o-", label="curve within 1 %")
    ax0.plot(
        x,
        [s["curve_within_1pct_rate_up_to_mirror"] for s in sweep],
        "s--",
        label="within 1 % up to the mirror image",
    )
    ax0.plot(
        x,
        [s["curve_or_alternative_within_1pct_rate"] for s in sweep],
        "d-.",
        label="answer or its listed mirror within 1 %",
    )
    ax0.plot(x, [s["oracle_within_1pct_rate"] for s in sweep], "^:", label="oracle (from truth)")
    ax0.axhline(0.95, color="grey", lw=0.8)
    ax0.set_xscale("log")
    ax0.set_xlabel("distance / depth variation of the curve")
    ax0.set_ylabel("rate (20 frames, 0.5 px)")
    ax0.legend(fontsize=8)
    ax1.plot(x, [s["mirror_dchi2_median"] or np.nan for s in sweep], "o-", label="mirror chi2 gap")
    ax1.plot(
        x,
        [100 * (s["scale_relative_std_median"] or np.nan) for s in sweep],
        "s-",
        label="scale std (%)",
    )
    ax1.axhline(pinhole.MIRROR_DCHI2, color="grey", lw=0.8)
    ax1.set_xscale("log")
    ax1.set_yscale("log")
    ax1.set_xlabel("distance / depth variation of the curve")
    ax1.legend(fontsize=8)
    fig.suptitle("Perspective, free motion, A, B and polylines (same image size at every distance)")
    fig.tight_layout()
    fig.savefig(PLOT, dpi=90)
    plt.close(fig)


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--scenes", type=int, default=20)
    ap.add_argument("--sweep-scenes", type=int, default=None)
    args = ap.parse_args(argv)
    print(json.dumps(run(args.seed, args.scenes, args.sweep_scenes), indent=1))


if __name__ == "__main__":
    main()
