"""Curve accuracy end to end through the command (not part of `make bench`).

Usage: ``python -m bench.curve_end_to_end FRAMES NOISE full|poly SEED_FROM SEED_TO [-v] [ARGS]``

``-v`` prints every seed; further ARGS go to ``curverecon reconstruct`` (e.g. ``--curve-bundle
off`` for the answer without the curve bundle).  The summary line adds the wall time of each
reconstruction (median and max; wall clock and the process's CPU time, which depends less on
other load on the machine).

For each seed: ``curverecon simulate --with-curve`` (NOISE px on every point, NOISE degrees on the
tangents), then ``curverecon reconstruct``; the written ``curve3d`` is compared with the
simulator's truth curve (frame 0 camera coordinates): the symmetric mean distance between the two
polylines over the true curve's length, best over the mirror image z -> -z.  ``poly`` removes A, B
and the tangents from the input, so they come from the polylines.
"""

from __future__ import annotations

import contextlib
import io
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from curverecon.cli import main


def _mean_distance(a: np.ndarray, b: np.ndarray) -> float:
    """Mean distance from the points of ``a`` to the polyline ``b`` (point to segment)."""
    seg0, seg = b[:-1], np.diff(b, axis=0)
    len2 = np.maximum((seg * seg).sum(1), 1e-300)
    t = np.clip(((a[:, None, :] - seg0[None]) * seg[None]).sum(2) / len2, 0.0, 1.0)
    foot = seg0[None] + t[..., None] * seg[None]
    return float(np.linalg.norm(a[:, None, :] - foot, axis=2).min(1).mean())


def _feet(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """For each point of ``a`` its nearest point on the polyline ``b``."""
    seg0, seg = b[:-1], np.diff(b, axis=0)
    len2 = np.maximum((seg * seg).sum(1), 1e-300)
    t = np.clip(((a[:, None, :] - seg0[None]) * seg[None]).sum(2) / len2, 0.0, 1.0)
    foot = seg0[None] + t[..., None] * seg[None]
    k = np.linalg.norm(a[:, None, :] - foot, axis=2).argmin(1)
    return foot[np.arange(a.shape[0]), k]


def curve_error_up_to_rotation(
    recovered: np.ndarray, truth: np.ndarray, iterations: int = 10
) -> float:
    """:func:`curve_error` after the rotation about the recovered curve's first point (A) that
    best lays it on the true curve (iterated closest points, Kabsch): the curve's shape
    without frame 0's tilt, which only frame 0's own view measures.  A diagnostic beside the
    error in frame 0's coordinates, which is what the output gives."""
    best = np.inf
    for q in (truth, truth * [1.0, 1.0, -1.0]):
        r = recovered.copy()
        a = r[0]
        for _ in range(iterations):
            feet = _feet(r, q)
            u, _, vt = np.linalg.svd((r - a).T @ (feet - a))
            d = np.sign(np.linalg.det(vt.T @ u.T))
            rot = vt.T @ np.diag([1.0, 1.0, d]) @ u.T
            r = a + (r - a) @ rot.T
        best = min(best, curve_error(r, q))
    return best


def curve_error(recovered: np.ndarray, truth: np.ndarray) -> float:
    """Symmetric mean distance / true length, best over the mirror image (depth sign)."""
    length = float(np.linalg.norm(np.diff(truth, axis=0), axis=1).sum())
    errors = []
    for q in (truth, truth * [1.0, 1.0, -1.0]):
        errors.append(0.5 * (_mean_distance(recovered, q) + _mean_distance(q, recovered)))
    return min(errors) / length


def run(
    frames: int,
    noise: float,
    polyline_only: bool,
    seeds: range,
    extra: tuple[str, ...] = (),
    verbose: bool = False,
) -> np.ndarray:
    """Relative curve errors, one per seed (inf where the command refused the scene).

    ``extra``: more arguments for ``curverecon reconstruct`` (e.g. ``--curve-bundle off``);
    ``verbose``: print each seed's error and the reconstruction's wall time.
    """
    out = []
    times = []
    cpu = []
    with tempfile.TemporaryDirectory() as tmp:
        scene, truth, result = (str(Path(tmp) / n) for n in ("s.json", "t.json", "r.json"))
        for seed in seeds:
            args = ["simulate", "-o", scene, "--truth", truth, "--frames", str(frames)]
            args += ["--point-noise", str(noise), "--tangent-noise", str(noise)]
            assert main([*args, "--seed", str(seed), "--with-curve"]) == 0
            if polyline_only:
                doc = json.loads(Path(scene).read_text())
                for frame in doc["frames"]:
                    for key in ("A", "B", "tangent_A", "tangent_B"):
                        frame.pop(key)
                Path(scene).write_text(json.dumps(doc))
            start, start_cpu = time.perf_counter(), time.process_time()
            with contextlib.redirect_stderr(io.StringIO()):
                status = main(["reconstruct", scene, "-o", result, *extra])
            times.append(time.perf_counter() - start)
            cpu.append(time.process_time() - start_cpu)
            if status != 0:
                out.append(np.inf)
            else:
                rec = np.array(json.loads(Path(result).read_text())["curve3d"])
                truth_curve = np.array(json.loads(Path(truth).read_text())["curve3d"])
                out.append(curve_error(rec, truth_curve))
            if verbose:
                print(
                    f"seed {seed}: {100 * out[-1]:.3f}% in {times[-1]:.1f} s (cpu {cpu[-1]:.1f} s)",
                    flush=True,
                )
    run.last_times = np.array(times)  # type: ignore[attr-defined]
    run.last_cpu = np.array(cpu)  # type: ignore[attr-defined]
    return np.array(out)


if __name__ == "__main__":
    n_frames, sigma, kind, lo, hi = sys.argv[1:6]
    rest = sys.argv[6:]
    verbose = "-v" in rest
    extra = tuple(a for a in rest if a != "-v")
    err = run(int(n_frames), float(sigma), kind == "poly", range(int(lo), int(hi)), extra, verbose)
    t = run.last_times  # type: ignore[attr-defined]
    cpu = run.last_cpu  # type: ignore[attr-defined]
    print(
        f"frames={n_frames} noise={sigma} input={kind} scenes={len(err)} "
        f"median={100 * np.median(err):.3f}% p90={100 * np.quantile(err, 0.9):.3f}% "
        f"max={100 * err.max():.2f}% within1%={np.mean(err < 0.01):.2f} "
        f"within3%={np.mean(err < 0.03):.2f} "
        f"time/scene median={np.median(t):.1f}s max={t.max():.1f}s "
        f"(cpu median={np.median(cpu):.1f}s max={cpu.max():.1f}s)"
        + (f" ({' '.join(extra)})" if extra else "")
    )
