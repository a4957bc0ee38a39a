"""The headline accuracy cell alone, quickly: ``python -m bench.headline [options]``.

Runs the default pipeline (no truth) on scenes ``--from`` .. ``--to`` of the benchmark's
headline cell (1 px, 1 deg, 20 frames, chord 100-300 px; the same scenes as ``make bench``, by
the same seeds) and prints RMSE / CRLB per parameter, the success rate, the median time per
scene, and the scenes that contribute most to the squared error.  ``--save FILE`` writes the
per-scene errors (JSON) and ``--compare FILE`` prints, scene by scene, where two runs differ by
more than a fifth of a standard deviation (CRLB) in any parameter.

It exists to measure a change to the pipeline in a minute or two instead of the full bench's
15; the figures it prints are the bench's definitions (``bench.accuracy.summarise_method``).

``--basin SCENE`` looks at one scene instead: the pipeline's answer and the marginal optimum
reached from the truth (maximum likelihood from the true shape and poses, then
``marginal.refine_marginal``), their errors in CRLB standard deviations, and F (the marginal
likelihood's objective, lower is better) of both with the same noise scale.  Where the answer's F
is the lower one, the data prefer the answer's basin: no search can do better by F.
"""

from __future__ import annotations

import argparse
import json
import math
import multiprocessing as mp
import time
from typing import Any

import numpy as np

from bench.accuracy import summarise_method
from bench.common import PARAMETERS, make, shape_errors, true_poses
from bench.config import full
from curverecon.errors import CurveReconError
from curverecon.pipeline import reconstruct
from curverecon.refine.ml import crlb_covariance
from curverecon.simulate import Scene


def _cell_scene(i: int, cell: int, noise: float, n_frames: int) -> Scene:
    """Scene ``i`` of an accuracy cell, as ``make bench`` makes it (``bench.accuracy``); the
    cells are numbered noise-major (``bench.__main__.build_tasks``: 1 px, 20 frames is 13)."""
    cfg = full()
    return make(
        cfg.seed,
        "accuracy",
        (cell, i),
        n_frames,
        point_sigma=noise,
        tangent_sigma_deg=noise,
        chord=cfg.chord,
    )


def _scene(args: tuple[int, str, int, float, int]) -> dict[str, Any]:
    i, estimator, cell, noise, n_frames = args
    scene = _cell_scene(i, cell, noise, n_frames)
    shape, poses = true_poses(scene)
    cov = crlb_covariance(shape, poses, noise, math.radians(noise))
    var = np.clip(np.diag(cov), 0.0, None) / np.array([shape[0] ** 2, 1.0, 1.0, 1.0])
    rec: dict[str, Any] = {"index": i, "crlb_var": var.tolist(), "default": None}
    t0 = time.perf_counter()
    try:
        r = reconstruct(
            scene.observations, point_sigma=noise, tangent_sigma_deg=noise, estimator=estimator
        )
        rec["default"] = shape_errors(r.shape, shape).tolist()
    except CurveReconError as exc:
        rec["exception"] = str(exc)
    rec["default_s"] = time.perf_counter() - t0
    return rec


def _basin(i: int, cell: int, noise: float, n_frames: int) -> None:
    """Print the ``--basin`` comparison for scene ``i`` (module docstring)."""
    from curverecon.model.pose import normalise
    from curverecon.refine.marginal import marginal_value, refine_marginal
    from curverecon.refine.ml import crlb, refine

    scene = _cell_scene(i, cell, noise, n_frames)
    ts = math.radians(noise)
    obs, meas = scene.observations, scene.observations.measurements()
    shape, poses = true_poses(scene)
    sd = crlb(shape, poses, noise, ts) / np.array([shape[0], 1.0, 1.0, 1.0])
    ml = reconstruct(obs, point_sigma=noise, tangent_sigma_deg=noise, estimator="ml")
    rec = reconstruct(obs, point_sigma=noise, tangent_sigma_deg=noise)
    from_truth = refine(obs, shape, poses, noise, ts, covariance=False)
    opt = refine_marginal(meas, from_truth.shape, from_truth.poses, noise, ts, from_truth.chi2)
    rows = [("answer", rec.shape, rec.poses)]
    if opt is not None:
        rows.append(("optimum from the truth", normalise(opt.shape, opt.poses)[0], opt.poses))
    print(f"scene {i} of cell {cell}: kappa from the ML chi2 {ml.chi2:.2f}")
    for name, g, p in rows:
        z = shape_errors(g, shape) / sd
        f = marginal_value(meas, g, p, noise, ts, ml.chi2)
        print(
            f"  {name}: errors in CRLB standard deviations "
            + ", ".join(f"{q} {v:+.1f}" for q, v in zip(PARAMETERS, z, strict=True))
            + f"; F {f:.2f}"
        )


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench.headline", description=__doc__)
    ap.add_argument("--from", dest="lo", type=int, default=0)
    ap.add_argument("--to", dest="hi", type=int, default=200)
    ap.add_argument("--estimator", default="marginal", choices=("marginal", "ml"))
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--noise", type=float, default=1.0, choices=full().noise_levels)
    ap.add_argument("--frames", type=int, default=20, choices=full().frame_counts)
    ap.add_argument("--save", help="write the per-scene records (JSON)")
    ap.add_argument("--compare", help="records of an earlier run (JSON) to compare with")
    ap.add_argument("--basin", type=int, metavar="SCENE", help="one scene's basins (docstring)")
    a = ap.parse_args(argv)
    if not 0 <= a.lo < a.hi:
        ap.error("--from and --to must satisfy 0 <= FROM < TO")
    if a.workers < 1:
        ap.error("--workers must be at least 1")
    if a.basin is not None and a.basin < 0:
        ap.error("--basin takes a scene index (0 or more)")
    cfg = full()
    cell = cfg.noise_levels.index(a.noise) * len(cfg.frame_counts) + cfg.frame_counts.index(
        a.frames
    )
    if a.basin is not None:
        _basin(a.basin, cell, a.noise, a.frames)
        return 0
    jobs = [(i, a.estimator, cell, a.noise, a.frames) for i in range(a.lo, a.hi)]
    t0 = time.perf_counter()
    if a.workers > 1:
        with mp.get_context("fork").Pool(a.workers) as pool:
            records = pool.map(_scene, jobs, chunksize=1)
    else:
        records = [_scene(j) for j in jobs]
    wall = time.perf_counter() - t0
    s = summarise_method(records, "default")
    times = [r["default_s"] for r in records]
    print(
        f"cell {cell} ({a.noise} px, {a.frames} frames), scenes {a.lo}-{a.hi - 1}, "
        f"estimator {a.estimator}: wall {wall:.1f} s on {a.workers} workers"
    )
    print("RMSE/CRLB " + ", ".join(f"{p} {s['ratio'][p]:.3f}" for p in PARAMETERS))
    print(
        f"success {s['success_rate']:.3f}; median time per scene {np.median(times):.3f} s "
        f"(mean {np.mean(times):.3f}); exceptions {s['n_exceptions']}"
    )
    ok = [r for r in records if r["default"] is not None]
    err = np.array([r["default"] for r in ok])
    sd = np.sqrt(np.array([r["crlb_var"] for r in ok]))
    z = err / sd
    share = err**2 / np.sum(err**2, axis=0)
    worst = np.argsort(-np.max(share[:, 1:], axis=1))[:5]
    for k in worst:
        print(
            f"  scene {ok[k]['index']}: errors in CRLB standard deviations "
            + ", ".join(f"{p} {v:+.1f}" for p, v in zip(PARAMETERS, z[k], strict=True))
            + f"; share of the angles' squared error {np.max(share[k, 1:]):.2f}"
        )
    if a.save:
        with open(a.save, "w") as fh:
            json.dump(records, fh)
    if a.compare:
        with open(a.compare) as fh:
            old = {r["index"]: r for r in json.load(fh)}
        moved = 0
        for r in records:
            o = old.get(r["index"])
            if o is None or o["default"] is None or r["default"] is None:
                continue
            d = (np.array(r["default"]) - np.array(o["default"])) / np.sqrt(r["crlb_var"])
            if np.max(np.abs(d)) > 0.2:
                moved += 1
                zo = np.array(o["default"]) / np.sqrt(r["crlb_var"])
                zn = np.array(r["default"]) / np.sqrt(r["crlb_var"])
                print(
                    f"  scene {r['index']}: old "
                    + " ".join(f"{v:+.1f}" for v in zo)
                    + "  new "
                    + " ".join(f"{v:+.1f}" for v in zn)
                )
        print(f"{moved} scenes moved by more than 0.2 standard deviations")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
