"""The outlier keys: ``python -m bench --only outliers`` (or ``python -m bench.outliers``).

``success_rate_10pct_outliers`` and ``success_rate_30pct_outliers``: the default pipeline,
without the truth, on the headline cell's scenes (20 frames, 1 px point noise, 1 degree tangent
noise, chord 100-300 px) where 10 % or 30 % of the frames are outliers whose two tangent
directions are replaced by independent uniformly random directions (the simulator's
``outlier_model="random"``).  Success as everywhere in the bench: worst angle
error of alpha, beta, phi below ``bench.common.SUCCESS_DEG`` (5 degrees).  The per-scene work
is ``bench.robustness.run_scenes`` (the main sections' robustness rows use the other model, 15-40
degree errors, under ``report.json["robustness"]``); scenes come from spawn keys
(``outliers_random``, fraction index, scene index) of the bench's seed, on ``WORKERS``
processes.

``python -m bench.outliers [--seed N] [--scenes K] [--workers W] [--quick]`` prints the keys as
JSON (a held-out seed: ``--seed``), without touching the report.
"""

from __future__ import annotations

import json
import os
import sys
import time

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from typing import Any  # noqa: E402

from bench import robustness  # noqa: E402
from bench.common import SUCCESS_DEG, Task, chunks, run_tasks  # noqa: E402
from bench.config import Config  # noqa: E402

FRACTIONS = ((0.1, "10pct"), (0.3, "30pct"))
"""Outlier fractions and their key names."""
SCENES = 50
"""Scenes per fraction: at about 3.3 s and 7.5 s a scene (10 % and 30 %, one core) 50 take
about 4.5 minutes on two processes, what ``make bench`` has left under 30 minutes (with the
main sections' budget cut to 620 s, ``bench.config``).  Success rates to about 2 % standard
error near 98 %, 4 % near 90 %."""
WORKERS = 2
CHUNK = 5
"""Scenes per pool task."""


def run(
    quick: bool = False,
    seed: int | None = None,
    scenes: int | None = None,
    workers: int = WORKERS,
) -> dict:
    """The section's report keys (``--only outliers``): ``scenes`` per fraction (default
    ``SCENES``) of ``seed`` (default the bench's) on ``workers`` processes."""
    cfg = Config()
    seed = cfg.seed if seed is None else seed
    n = (2 if quick else SCENES) if scenes is None else scenes
    tasks = [
        Task(
            robustness.run_scenes,
            (
                seed,
                fid,
                frac,
                cfg.headline_noise,
                cfg.headline_frames,
                r,
                cfg.chord,
                float("inf"),
                "random",
                "outliers_random",
            ),
            len(r),
            f"{frac}",
        )
        for fid, (frac, _) in enumerate(FRACTIONS)
        for r in chunks(n, CHUNK)
    ]
    results = run_tasks(tasks, workers, "outlier scenes (random tangents)", progress=False)
    out: dict[str, Any] = {"outliers_seed": seed}
    for frac, name in FRACTIONS:
        records = results.get(f"{frac}", [])
        row = robustness.summarise_records(records, frac)
        out[f"success_rate_{name}_outliers"] = row["success_rate"]
        out[f"outliers_random_{name}"] = row
        out[f"outliers_random_{name}_failed_scenes"] = [
            r["index"] for r in records if not r["worst_deg"] < SUCCESS_DEG
        ]
    return out


if __name__ == "__main__":
    args = sys.argv[1:]
    s = int(args[args.index("--seed") + 1]) if "--seed" in args else None
    k = int(args[args.index("--scenes") + 1]) if "--scenes" in args else None
    t0 = time.time()
    w = int(args[args.index("--workers") + 1]) if "--workers" in args else WORKERS
    result = run("--quick" in args, s, k, w)
    result["outliers_section_seconds"] = round(time.time() - t0, 1)
    print(json.dumps(result, indent=1))
