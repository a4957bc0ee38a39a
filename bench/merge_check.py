"""Merging same-basin candidates of long sequences (``SearchOptions.medium_merge_distance``):
the answer and the time with it (0.02, the default) and without it (0: nothing merged).

``python -m bench.merge_check FRAMES SEED_FROM SEED_TO`` prints per scene (``make_scene``, 1 px,
1 degree) the time and the worst angle error against the truth for both, and the totals.
"""

from __future__ import annotations

import sys
import time

import numpy as np

from curverecon.options import ReconstructOptions, SearchOptions
from curverecon.pipeline import reconstruct
from curverecon.simulate import make_scene


def main(argv: list[str]) -> None:
    n, lo, hi = (int(a) for a in argv)
    totals = {"off": [0.0, 0.0], "on": [0.0, 0.0]}
    for seed in range(lo, hi):
        sc = make_scene(np.random.default_rng(seed), n, point_sigma=1.0, tangent_sigma_deg=1.0)
        row = []
        for name, d in (("off", 0.0), ("on", 0.02)):
            opts = ReconstructOptions(search=SearchOptions(medium_merge_distance=d))
            t = time.perf_counter()
            rec = reconstruct(sc.observations, options=opts)
            dt = time.perf_counter() - t
            err = float(np.max(np.abs(np.degrees(rec.shape[1:] - sc.truth.shape[1:]))))
            totals[name][0] += dt
            totals[name][1] += err
            row.append(f"{name} {dt:5.1f}s worst angle error {err:.3f} deg, c {rec.c:.3f}")
        print(seed, " | ".join(row), flush=True)
    k = hi - lo
    for name, (t, e) in totals.items():
        print(f"{name}: {t:.1f} s in all, mean worst angle error {e / k:.4f} deg")


if __name__ == "__main__":
    main(sys.argv[1:])
