"""Curve accuracy end to end through the command (issue 4's figures; not part of `make bench`).

Usage: ``python -m bench.curve_end_to_end FRAMES NOISE full|poly SEED_FROM SEED_TO``

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


def curve_error(recovered: np.ndarray, truth: np.ndarray) -> float:
    """Symmetric mean distance / true length, best over the mirror image (depth sign)."""
    length = float(np.linalg.norm(np.diff(truth, axis=0), axis=1).sum())
    errors = []
    for q in (truth, truth * [1.0, 1.0, -1.0]):
        errors.append(0.5 * (_mean_distance(recovered, q) + _mean_distance(q, recovered)))
    return min(errors) / length


def run(frames: int, noise: float, polyline_only: bool, seeds: range) -> np.ndarray:
    """Relative curve errors, one per seed (inf where the command refused the scene)."""
    out = []
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
            with contextlib.redirect_stderr(io.StringIO()):
                status = main(["reconstruct", scene, "-o", result])
            if status != 0:
                out.append(np.inf)
                continue
            rec = np.array(json.loads(Path(result).read_text())["curve3d"])
            out.append(curve_error(rec, np.array(json.loads(Path(truth).read_text())["curve3d"])))
    return np.array(out)


if __name__ == "__main__":
    n_frames, sigma, kind, lo, hi = sys.argv[1:6]
    err = run(int(n_frames), float(sigma), kind == "poly", range(int(lo), int(hi)))
    print(
        f"frames={n_frames} noise={sigma} input={kind} scenes={len(err)} "
        f"median={100 * np.median(err):.3f}% p90={100 * np.quantile(err, 0.9):.3f}% "
        f"max={100 * err.max():.2f}% within1%={np.mean(err < 0.01):.2f} "
        f"within3%={np.mean(err < 0.03):.2f}"
    )
