"""The stereo row's curve: ``python -m bench.stereo_curve [--scenes N] [--seed S] [--frames F]``.

Scenes: ``curverecon.simulate.simulate_camera_configuration("stereo", "free", "AB", F, seed,
noise_px=0.5, with_curve=True)`` (its own 3-D construction: a Bezier curve of chord 100-300
1000 units in front of camera 0, camera 1 a quarter of that to the right, turned towards the
body, 150 polyline points per view).  The answer is ``reconstruct_rigid`` (what ``curverecon
reconstruct`` writes); the oracle is ``stereo_curve3d`` on the true frame poses; the
placement oracle is the true curve placed in frame 0 by frame 0's polylines alone (the least an
answer in frame 0's coordinates pays: under free motion no other frame places the shape there).
Errors against the truth's ``curve3d`` (frame 0's camera-0 coordinates): ``error`` is
bench/persp_curve.py's ``curve_error`` (symmetric mean distance / true length), ``max_error``
the largest distance of a returned point from the true curve / true length; ``coverage`` the
share of returned points whose distance from the true curve is within three of their
``curve3d_normal_std``.

Keys: ``config_stereo_free_curve_within_1pct_rate`` (target >= 0.95; 20 frames, 0.5 px),
``..._oracle_within_1pct_rate``, the medians of the errors, the coverage, seconds per scene.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from bench.common import Task, chunks, run_tasks  # noqa: E402

SIGMA_PX = 0.5
FRAMES = 20


def _distances(points: np.ndarray, curve: np.ndarray) -> np.ndarray:
    """Distance of each point from the polyline ``curve`` (point to segment)."""
    seg0, seg = curve[:-1], np.diff(curve, axis=0)
    len2 = np.maximum((seg * seg).sum(1), 1e-300)
    t = np.clip(((points[:, None, :] - seg0[None]) * seg[None]).sum(2) / len2, 0.0, 1.0)
    foot = seg0[None] + t[..., None] * seg[None]
    return np.linalg.norm(points[:, None, :] - foot, axis=2).min(1)


def _dense(truth_curve: np.ndarray, per_segment: int = 8) -> np.ndarray:
    """The true polyline with points between its samples (a finer reference)."""
    u = np.linspace(0.0, 1.0, per_segment, endpoint=False)
    a, d = truth_curve[:-1], np.diff(truth_curve, axis=0)
    fine = (a[:, None, :] + u[None, :, None] * d[:, None, :]).reshape(-1, 3)
    return np.vstack([fine, truth_curve[-1:]])


def measure(curve: np.ndarray, std: np.ndarray | None, truth_curve: np.ndarray) -> dict:
    """``error``, ``max_error`` (over the true length) and ``coverage`` (module docstring)."""
    from bench.persp_curve import curve_error

    length = float(np.linalg.norm(np.diff(truth_curve, axis=0), axis=1).sum())
    d = _distances(curve, _dense(truth_curve))
    out = {"error": curve_error(curve, truth_curve), "max_error": float(d.max() / length)}
    out["coverage"] = None if std is None else float(np.mean(d <= 3.0 * std))
    return out


def scene_row(seed: int, frames: int = FRAMES, sigma: float = SIGMA_PX) -> dict:
    """One scene: the answer's and the oracle's errors, the answer's time."""
    from curverecon.curve.stereo import stereo_curve3d
    from curverecon.io import observations_from_dict
    from curverecon.options import ReconstructOptions
    from curverecon.rigid import reconstruct_rigid
    from curverecon.simulate import simulate_camera_configuration

    doc, truth = simulate_camera_configuration(
        "stereo", "free", "AB", frames, seed, noise_px=sigma, with_curve=True
    )
    obs = observations_from_dict(doc)
    truth_curve = np.asarray(truth["curve3d"])
    row: dict = {"seed": seed, "frames": frames}
    t0 = time.perf_counter()
    try:
        rec = reconstruct_rigid(obs, ReconstructOptions(point_sigma=sigma))
        row["seconds"] = time.perf_counter() - t0
        row.update(measure(rec.curve3d, rec.curve3d_normal_std, truth_curve))
    except Exception as exc:  # noqa: BLE001 (a failure is counted, not raised)
        row.update(error=None, failed=str(exc))
    poses = np.array(
        [np.column_stack([f["frame_pose"]["R"], f["frame_pose"]["T"]]) for f in truth["frames"]]
    )
    cfg = obs.configuration
    o_curve, o_std = stereo_curve3d(cfg.rig, obs.curves, obs.view1.curves, poses, sigma)
    row.update({f"oracle_{k}": v for k, v in measure(o_curve, o_std, truth_curve).items()})
    row.update({f"placed_{k}": v for k, v in placement_oracle(obs, truth_curve, sigma).items()})
    return row


def placement_oracle(obs, truth_curve: np.ndarray, sigma: float) -> dict:
    """The true curve placed in frame 0 by frame 0's two polylines alone (from the truth,
    ``curve.stereo_place``): with free motion nothing else places the shape in frame 0, so
    this is what any answer in frame 0's coordinates pays at least."""
    from curverecon.curve.stereo_place import place_shape

    views = (np.asarray(obs.curves[0], float), np.asarray(obs.view1.curves[0], float))
    start = np.column_stack([np.eye(3), np.zeros(3)])
    pose, std = place_shape(obs.configuration.rig, truth_curve, start, views, sigma)
    return measure(truth_curve @ pose[:, :3].T + pose[:, 3], std, truth_curve)


def _rate(rows: list[dict], key: str) -> float:
    return float(np.mean([r.get(key) is not None and r[key] < 0.01 for r in rows]))


def _median(rows: list[dict], key: str) -> float | None:
    vals = [r[key] for r in rows if r.get(key) is not None]
    return float(np.median(vals)) if vals else None


def _rows(seeds: range, frames: int) -> list[dict]:
    return [dict(scene_row(s, frames), index=s) for s in seeds]


def run(seed: int = 0, scenes: int = 20, frames: int = FRAMES, workers: int = 1) -> dict:
    """The keys of the module docstring over scenes ``seed`` .. ``seed + scenes - 1``, on
    ``workers`` processes."""
    seeds = [range(seed + r.start, seed + r.stop) for r in chunks(scenes, 5)]
    tasks = [Task(_rows, (s, frames), len(s), "stereo") for s in seeds]
    rows = run_tasks(tasks, workers, "stereo curve").get("stereo", [])
    name = "config_stereo_free_curve"
    return {
        f"{name}_within_1pct_rate": _rate(rows, "error"),
        f"{name}_oracle_within_1pct_rate": _rate(rows, "oracle_error"),
        f"{name}_error_median": _median(rows, "error"),
        f"{name}_oracle_error_median": _median(rows, "oracle_error"),
        f"{name}_placement_oracle_within_1pct_rate": _rate(rows, "placed_error"),
        f"{name}_placement_oracle_error_median": _median(rows, "placed_error"),
        f"{name}_max_error_median": _median(rows, "max_error"),
        f"{name}_oracle_max_error_median": _median(rows, "oracle_max_error"),
        f"{name}_std_coverage_3sigma_median": _median(rows, "coverage"),
        f"{name}_oracle_std_coverage_3sigma_median": _median(rows, "oracle_coverage"),
        f"{name}_seconds_median": _median(rows, "seconds"),
        f"{name}_frames": frames,
        f"{name}_scenes": len(rows),
    }


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--scenes", type=int, default=20)
    ap.add_argument("--frames", type=int, default=FRAMES)
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args(argv)
    print(json.dumps(run(args.seed, args.scenes, args.frames, args.workers), indent=1))


if __name__ == "__main__":
    main()
