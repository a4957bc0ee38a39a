"""Sizing the run to the budget: a pilot measures per-scene cost, the plan chooses counts.

The required counts (``Config``) are kept whenever the estimate says they fit.  Otherwise the
default-pipeline work is lowered, never silently: the plan records, per experiment, the required
and the planned count and why; the report prints both.

Priority (what is kept first):
0. the cheap parts of every accuracy scene (CRLB, refinement from the truth, linearisation);
1. the default pipeline at the headline cell;
2. the robustness runs and the first noise-free scenes at the target's frame count (6);
3. the default pipeline at the other cells, the rest of the noise-free stability runs.
Floors keep every table non-empty.  During the run a deadline stops the default pipeline (and
stability/robustness scenes) once the budget is used up, so the wall time stays bounded even
when the estimate was too low; the report counts what actually ran.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from bench.config import Config

ROBUSTNESS_COST_FACTOR = 1.5
"""Outlier frames make the pipeline refit (one refit per flagged frame)."""
NOISE_FREE_COST_FACTOR = 1.0

FLOOR_DEFAULT_CELL = 10
FLOOR_HEADLINE = 40
FLOOR_ROBUSTNESS = 30
FLOOR_STABILITY = 50
FLOOR_STABILITY_LINEAR = 100


@dataclass
class Plan:
    """Counts to run, with the required ones and the estimates behind them."""

    accuracy_default: dict[tuple[float, int], int]
    robustness: dict[float, int]
    stability: dict[int, int]
    stability_linear: dict[int, int]
    estimate_cpu_s: float
    available_cpu_s: float
    scales: list[float]
    stability_first: dict[int, int]
    per_scene_s: dict[str, float] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    def to_dict(self, cfg: Config) -> dict[str, Any]:
        """JSON form: required and planned counts side by side."""
        req_stab = split(cfg.stability_scenes, cfg.stability_frames)
        req_lin = split(cfg.stability_linear_scenes, cfg.stability_linear_frames)
        return {
            "available_cpu_seconds": self.available_cpu_s,
            "estimated_cpu_seconds": self.estimate_cpu_s,
            "scales": self.scales,
            "stability_first": self.stability_first,
            "per_scene_seconds": self.per_scene_s,
            "accuracy_default": [
                {
                    "noise": k[0],
                    "n_frames": k[1],
                    "required": cfg.accuracy_default_scenes,
                    "planned": v,
                }
                for k, v in sorted(self.accuracy_default.items())
            ],
            "robustness": [
                {"fraction": k, "required": cfg.robustness_scenes, "planned": v}
                for k, v in sorted(self.robustness.items())
            ],
            "stability": [
                {"n_frames": k, "required": req_stab[k], "planned": v}
                for k, v in sorted(self.stability.items())
            ],
            "stability_linear": [
                {"n_frames": k, "required": req_lin[k], "planned": v}
                for k, v in sorted(self.stability_linear.items())
            ],
            "notes": self.notes,
        }


def split(total: int, keys: tuple[int, ...]) -> dict[int, int]:
    """``total`` split as evenly as possible over ``keys`` (earlier keys get the remainder)."""
    base, rem = divmod(total, len(keys))
    return {k: base + (1 if i < rem else 0) for i, k in enumerate(keys)}


def per_scene_costs(pilot: dict[int, list[dict[str, Any]]]) -> dict[str, Any]:
    """Mean per-scene seconds from the pilot records (keyed by frame count)."""
    out: dict[str, Any] = {"default": {}, "cheap": {}, "linear": None}
    lin = []
    for n, recs in sorted(pilot.items()):
        d = [r["default_s"] for r in recs if "default_s" in r]
        out["default"][n] = float(np.mean(d)) if d else math.nan
        out["cheap"][n] = float(np.mean([r["total_s"] - r.get("default_s", 0.0) for r in recs]))
        lin += [r["linear_s"] for r in recs if "linear_s" in r]
    out["linear"] = float(np.mean(lin)) if lin else 0.06
    return out


def _interp(table: dict[int, float], n: int) -> float:
    """Per-scene cost at n frames: the pilot's value, else log-log interpolation."""
    if n in table and math.isfinite(table[n]):
        return table[n]
    keys = sorted(k for k, v in table.items() if math.isfinite(v))
    if not keys:
        return 1.0
    xs = np.log(keys)
    ys = np.log([table[k] for k in keys])
    return float(np.exp(np.interp(math.log(n), xs, ys)))


def make_plan(cfg: Config, costs: dict[str, Any], available_cpu_s: float, full: bool) -> Plan:
    """Counts that fit ``available_cpu_s`` CPU-seconds (all required counts when ``full``).

    Tiers, each scaled uniformly to what the tiers before it left: (1) the headline cell's default
    pipeline; (2) robustness and the first ``stability_target_scenes`` noise-free scenes at the
    target's frame count; (3) the other cells, the rest of the stability runs, the linearisation's
    stability.
    """
    t_def = {n: _interp(costs["default"], n) for n in {*cfg.frame_counts, *cfg.stability_frames}}
    t_cheap = {n: _interp(costs["cheap"], n) for n in cfg.frame_counts}
    t_lin = costs["linear"]
    hn, hf = cfg.headline_noise, cfg.headline_frames
    cells = [(s, n) for s in cfg.noise_levels for n in cfg.frame_counts]
    req_stab = split(cfg.stability_scenes, cfg.stability_frames)
    req_lin = split(cfg.stability_linear_scenes, cfg.stability_linear_frames)
    nt = cfg.stability_target_frames
    first = min(req_stab.get(nt, 0), cfg.stability_target_scenes)

    cost0 = sum(cfg.accuracy_scenes * t_cheap[n] for _, n in cells)
    tiers: list[dict[tuple, tuple[int, float, int]]] = [
        {("acc", hn, hf): (cfg.accuracy_default_scenes, t_def[hf], FLOOR_HEADLINE)},
        {},
        {},
    ]
    for f in cfg.outlier_fractions:
        tiers[1][("rob", f)] = (
            cfg.robustness_scenes,
            ROBUSTNESS_COST_FACTOR * t_def[hf],
            FLOOR_ROBUSTNESS,
        )
    if first:
        tiers[1][("stab1", nt)] = (first, NOISE_FREE_COST_FACTOR * t_def[nt], FLOOR_STABILITY)
    for s, n in cells:
        if (s, n) != (hn, hf):
            tiers[2][("acc", s, n)] = (cfg.accuracy_default_scenes, t_def[n], FLOOR_DEFAULT_CELL)
    for n, k in req_stab.items():
        rest = k - (first if n == nt else 0)
        floor = 0 if n == nt else FLOOR_STABILITY
        tiers[2][("stab", n)] = (rest, NOISE_FREE_COST_FACTOR * t_def[n], floor)
    for n, k in req_lin.items():
        tiers[2][("lin", n)] = (k, t_lin, FLOOR_STABILITY_LINEAR)

    scales = []
    left = available_cpu_s - cost0
    for tier in tiers:
        sc = 1.0 if full else _solve_scale(tier, left)
        scales.append(sc)
        left -= _tier_cost(tier, sc)
    counts: dict[tuple, int] = {}
    for tier, sc in zip(tiers, scales, strict=True):
        counts.update({key: _count(req, sc, floor) for key, (req, _, floor) in tier.items()})
    estimate = cost0 + sum(_tier_cost(t, sc) for t, sc in zip(tiers, scales, strict=True))
    notes = []
    if min(scales) < 1.0:
        need = cost0 + sum(_tier_cost(t, 1.0) for t in tiers)
        notes.append(
            f"the required counts need about {need:.0f} CPU-s by the pilot's per-scene times, "
            f"{available_cpu_s:.0f} CPU-s were available: default-pipeline counts scaled by "
            f"{scales[0]:.2f} (headline cell), {scales[1]:.2f} (robustness, first "
            f"{first} noise-free {nt}-frame scenes) and {scales[2]:.2f} (other cells, the rest "
            "of the stability runs)"
        )
    stab = {n: counts[("stab", n)] for n in cfg.stability_frames}
    if first:
        stab[nt] += counts[("stab1", nt)]
    return Plan(
        accuracy_default={(s, n): counts[("acc", s, n)] for s, n in cells},
        robustness={f: counts[("rob", f)] for f in cfg.outlier_fractions},
        stability=stab,
        stability_linear={n: counts[("lin", n)] for n in cfg.stability_linear_frames},
        estimate_cpu_s=estimate,
        available_cpu_s=available_cpu_s,
        scales=scales,
        stability_first={nt: counts[("stab1", nt)]} if first else {},
        per_scene_s={
            **{f"default_{n}_frames": v for n, v in sorted(t_def.items())},
            **{f"cheap_parts_{n}_frames": v for n, v in sorted(t_cheap.items())},
            "linear": t_lin,
        },
        notes=notes,
    )


def _tier_cost(tier: dict, scale: float) -> float:
    return sum(_count(req, scale, floor) * t for req, t, floor in tier.values())


def _count(required: int, scale: float, floor: int) -> int:
    return int(min(required, max(min(floor, required), math.floor(required * scale))))


def _solve_scale(tier: dict, budget: float) -> float:
    """Largest scale in [0, 1] whose tier cost (with floors) fits ``budget`` (bisection)."""

    if _tier_cost(tier, 1.0) <= budget:
        return 1.0
    lo, hi = 0.0, 1.0
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if _tier_cost(tier, mid) <= budget:
            lo = mid
        else:
            hi = mid
    return lo
