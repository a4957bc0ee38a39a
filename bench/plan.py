"""What runs first when the budget cannot hold everything, and what everything would cost.

The benchmark submits the required counts (``Config``) in priority order and stops starting
expensive scenes at a deadline (the budget minus a reserve for the report), so the wall time
stays within the budget whatever the machine's speed; the report then prints, per experiment,
the required and the run count, the measured per-scene times and the CPU time all the required
counts would need.  Nothing is cut silently.

Priority (in this order):

0. the cheap parts of every accuracy scene (CRLB, refinement from the truth, linearisation);
   these ignore the deadline (a few hundredths of a second per scene);
1. the default pipeline at the headline cell (1 px, 1 deg, 20 frames), all required scenes;
2. a floor of every other group (16 scenes per cell, 40 per robustness fraction, 96 noise-free
   6-frame scenes, 40 at 4 and 5 frames, 32 per linearisation frame count), interleaved;
3. the rest of every group, merged by weighted fair queuing: robustness and the first
   ``stability_target_scenes`` noise-free 6-frame scenes weigh 3, the others 1.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from bench.config import Config


def split(total: int, keys: tuple[int, ...]) -> dict[int, int]:
    """``total`` split as evenly as possible over ``keys`` (earlier keys get the remainder)."""
    base, rem = divmod(total, len(keys))
    return {k: base + (1 if i < rem else 0) for i, k in enumerate(keys)}


def stability_counts(cfg: Config) -> tuple[dict[int, int], dict[int, int]]:
    """Required noise-free scenes per frame count, and how many of them are in tier 2."""
    req = split(cfg.stability_scenes, cfg.stability_frames)
    nt = cfg.stability_target_frames
    first = {nt: min(req[nt], cfg.stability_target_scenes)} if nt in req else {}
    return req, first


def measured_seconds(results: dict[str, list[dict[str, Any]]]) -> dict[str, float]:
    """Mean per-scene seconds by kind of work, from the records of the run."""
    acc: dict[str, list[float]] = {}

    def put(key: str, value: float) -> None:
        acc.setdefault(key, []).append(value)

    for label, recs in results.items():
        kind = label.split("|")[0]
        for r in recs:
            if kind == "accd" and "default_s" in r:
                put(f"default_{r['n_frames']}_frames", r["default_s"])
            elif kind == "acc":
                put(f"cheap_{r['n_frames']}_frames", r["truth_start_s"] + r.get("linear_s", 0.0))
            elif kind == "rob":
                put(f"robustness_{label.split('|')[1]}", r["seconds"])
            elif kind == "stab":
                put(f"noise_free_{r['n_frames']}_frames", r["seconds"])
            elif kind == "lin":
                put(f"linear_noise_free_{r['n_frames']}_frames", r["seconds"])
    order = ("cheap", "default", "robustness", "noise", "linear")

    def key(name: str) -> tuple[int, float]:
        kind = next(i for i, o in enumerate(order) if name.startswith(o))
        nums = [float(t) for t in name.split("_") if t.replace(".", "", 1).isdigit()]
        return kind, nums[0] if nums else 0.0

    return {k: float(np.mean(acc[k])) for k in sorted(acc, key=key)}


def required_cpu_seconds(cfg: Config, per_scene: dict[str, float]) -> float | None:
    """CPU-seconds all the required counts would need at the measured per-scene times."""
    total = 0.0
    try:
        for _ in cfg.noise_levels:
            for n in cfg.frame_counts:
                total += cfg.accuracy_scenes * per_scene.get(f"cheap_{n}_frames", 0.0)
                total += cfg.accuracy_default_scenes * per_scene[f"default_{n}_frames"]
        for f in cfg.outlier_fractions:
            total += cfg.robustness_scenes * per_scene[f"robustness_{f}"]
        req, _ = stability_counts(cfg)
        for n, k in req.items():
            total += k * per_scene[f"noise_free_{n}_frames"]
        for n, k in split(cfg.stability_linear_scenes, cfg.stability_linear_frames).items():
            total += k * per_scene.get(f"linear_noise_free_{n}_frames", 0.0)
    except KeyError:
        return None
    return total
