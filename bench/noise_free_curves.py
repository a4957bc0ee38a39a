"""Noise-free curve survey: ``curve3d`` error per curve family.

``python -m bench.noise_free_curves FRAMES SEED0 COUNT [family,family,...]`` (pin it to one
core: ``taskset -c 0``).  Not a ``make bench`` section: the scenes behind the figures of
``CurveOptions.exact_start_control_points`` and ``exact_unfold``.

Scenes: ``make_scene(default_rng(seed), FRAMES, with_curve=True, curve_family=F)`` for seeds
SEED0 .. SEED0 + COUNT - 1, end points, tangents and polylines given, no noise.  Per family one
line: the largest and median mean distance of the ``curve3d`` points from the true curve
(sampled at 20,000 points, point to segment; that yardstick's own floor is about 1e-9 of the
length) over its length (the truth or its mirror image, the better), how many exceed 1e-6 and
which, the worst c and angle errors, and the median and largest CPU seconds of a reconstruction.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import sys  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402

import numpy as np  # noqa: E402


def distance_to(points: np.ndarray, curve: np.ndarray) -> np.ndarray:
    """Distance of each point from the polyline ``curve`` (point to segment)."""
    seg0, seg = curve[:-1], np.diff(curve, axis=0)
    len2 = (seg * seg).sum(1)
    out = np.empty(len(points))
    for i, p in enumerate(points):
        t = np.clip(((p - seg0) * seg).sum(1) / len2, 0.0, 1.0)
        out[i] = np.linalg.norm(seg0 + t[:, None] * seg - p, axis=1).min()
    return out


def survey(frames: int, seed0: int, count: int, families) -> list[str]:
    """One line per family (see the module docstring)."""
    from curverecon.pipeline import reconstruct
    from curverecon.simulate import make_scene

    lines = []
    for fam in families:
        rows = []
        for seed in range(seed0, seed0 + count):
            kw = {"with_curve": True, "curve_family": fam}
            sc = make_scene(np.random.default_rng(seed), frames, **kw)
            dense = make_scene(
                np.random.default_rng(seed), frames, n_curve_points=20000, **kw
            ).curve_3d
            t0 = time.process_time()
            rec = reconstruct(sc.observations)
            cpu = time.process_time() - t0
            length = float(np.linalg.norm(np.diff(dense, axis=0), axis=1).sum())
            err = min(
                float(distance_to(rec.curve3d, q).mean()) for q in (dense, dense * [1, 1, -1.0])
            )
            c_rel = abs(rec.c - sc.truth.c) / sc.truth.c
            ang = float(np.degrees(np.abs(rec.shape[1:] - sc.truth.shape[1:])).max())
            rows.append((err / length, seed, c_rel, ang, cpu))
        e = np.array([r[0] for r in rows])
        fails = [(r[1], float(f"{r[0]:.1e}")) for r in rows if r[0] > 1e-6]
        cpu = [r[4] for r in rows]
        lines.append(
            f"{fam:10s} frames={frames} n={len(rows)} max={e.max():.2e} "
            f"med={np.median(e):.2e} n>1e-6={len(fails)} c_rel={max(r[2] for r in rows):.1e} "
            f"angle_deg={max(r[3] for r in rows):.1e} cpu_med={np.median(cpu):.2f}s "
            f"cpu_max={max(cpu):.2f}s fails={fails}"
        )
        print(lines[-1], flush=True)
    return lines


if __name__ == "__main__":
    from curverecon.curve_families import FAMILIES

    warnings.filterwarnings("ignore")
    args = sys.argv[1:]
    fams = args[3].split(",") if len(args) > 3 else FAMILIES
    survey(int(args[0]), int(args[1]), int(args[2]), fams)
