"""Time of the pipeline after the hypotheses (stages 2-5), stage by stage, against the frame count.

The hypotheses stage (``robust.search``, being replaced) is stood in for: its search runs on
400 evenly spread frames only (``--start search``, the default) or the truth is perturbed by
about 2 % (``--start truth``); its best shape then goes through what follows on all frames:

- ``refine``: the refinement on all frames from that shape (``refine.start.refine_hypothesis``);
- ``outliers``: the outlier-frame test and refits (``robust.outliers``);
- ``covariance``: the fit on the inliers with its covariance (and the branch flips, few frames);
- ``alternatives``: the equally good fits (``robust.alternatives``);
- ``final``: the final estimate (``refine.answer``: marginal likelihood, poses, warnings).

Scenes: ``simulate.make_scene`` (seed 2 unless ``--seed``), 1 px, 1 degree.  Each size runs in
its own process (``--case``) so that its peak memory (``ru_maxrss``) is its own.  Prints JSON:
seconds per stage, the answer's error against the truth in its own standard deviations.

    python -m bench.stages [--sizes 1000,10000,30000,100000] [--seed 2] [--start search|truth]
    python -m bench.stages --case 10000 [--profile FILE]   # one size, in this process
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

STUB_FRAMES = 400
"""Frames the stand-in for the hypotheses stage searches on."""


class _Timer:
    """The pipeline's progress hook, recording when each stage starts."""

    def __init__(self) -> None:
        self.marks: list[tuple[str, float, float]] = []

    def step(self, name: str) -> None:
        self.marks.append((name, time.perf_counter(), time.process_time()))

    def close(self) -> None:
        self.step("end")


def numerics(obs, rec, ps: float, ts: float) -> dict:
    """Accuracy of the large sums at the answer (inlier frames): the shape's information matrix
    S = sum_i (U_i - W_i V_i^-1 W_i^T) as the pipeline computes it (``refine.ml``'s batched
    float64 Schur complement) against an independent one (each frame's Householder QR of its
    [J_pose | J_shape], rows sorted by norm, summed in extended precision), and chi2's float64
    sum against ``math.fsum``."""
    import math

    import numpy as np
    from curverecon.generated import measurement_model

    from curverecon.refine.ml import schur_covariance, schur_information, standardised_residuals

    w8 = np.array([1 / ps] * 4 + [1 / ts] * 2)
    sub = obs.subset(rec.inliers)
    poses = rec.poses[rec.inliers]
    _, jg, jl = measurement_model.predict_with_jacobians(*rec.shape, *poses.T)
    jg, jl = jg * w8[None, :, None], jl * w8[None, :, None]
    s64 = schur_information(jg, jl)
    a = np.concatenate([jl, jg], axis=2)
    order = np.argsort(-np.linalg.norm(a, axis=2), axis=1)
    a = np.take_along_axis(a, order[:, :, None], axis=1)
    tail = np.linalg.qr(a, mode="r")[:, 5, 5:].astype(np.longdouble)
    s_ref = np.einsum("ni,nj->ij", tail, tail)
    rel = float(np.max(np.abs(s64 - s_ref)) / np.max(np.abs(s_ref)))
    cov = schur_covariance(jg, jl)
    std64 = np.sqrt(np.diag(cov))
    std_ref = np.sqrt(np.diag(np.linalg.inv(s_ref.astype(float))))
    r = standardised_residuals(rec.shape, poses, sub.measurements(), w8)
    sq = (r * r).ravel()
    chi2_ref = math.fsum(sq.tolist())
    return {
        "schur_rel_error": float(f"{rel:.2g}"),
        "std_rel_error": float(f"{np.max(np.abs(std64 / std_ref - 1)):.2g}"),
        "chi2_rel_error": float(f"{abs(float(np.sum(sq)) - chi2_ref) / chi2_ref:.2g}"),
    }


def run_case(
    n: int, seed: int, start: str, profile: str | None = None, check: bool = False
) -> dict:
    import numpy as np

    from curverecon.model.pose import normalise
    from curverecon.options import ReconstructOptions
    from curverecon.pipeline import answer_from_hypotheses
    from curverecon.refine.start import refine_hypothesis
    from curverecon.robust.search import Candidate, robust_cost, robust_start
    from curverecon.simulate import make_scene

    opts = ReconstructOptions()
    ps, ts = opts.point_sigma, np.radians(opts.tangent_sigma_deg)
    sc = make_scene(np.random.default_rng(seed), n, point_sigma=1.0, tangent_sigma_deg=1.0)
    obs = sc.observations
    timer = _Timer()
    timer.step("hypotheses_stub")
    if start == "truth":
        g0 = sc.truth.shape * (1.0 + 0.02 * np.random.default_rng(seed + 1).normal(size=4))
    else:
        sub = np.unique(np.linspace(0, n - 1, min(n, STUB_FRAMES)).round().astype(int))
        g0 = robust_start(obs.subset(sub), ps, ts, options=opts.search)[0].result.shape
    prof = None
    if profile:
        import cProfile

        prof = cProfile.Profile()
        prof.enable()
    timer.step("refine")
    fit = refine_hypothesis(obs, g0, ps, ts, options=opts.search)
    rec = answer_from_hypotheses(
        obs, [Candidate(fit, robust_cost(fit.frame_chi2), 0.0)], opts, timer
    )
    timer.close()
    if prof is not None:
        prof.disable()
        prof.dump_stats(profile)
    names = {
        "maximum likelihood": "outliers_covariance",
        "alternatives": "alternatives",
        "final estimate": "final",
    }
    seconds, cpu = {}, {}
    for (name, t, c), (_, t_next, c_next) in zip(timer.marks, timer.marks[1:], strict=False):
        seconds[names.get(name, name)] = t_next - t
        cpu[names.get(name, name)] = c_next - c
    seconds["stages_2_to_5"] = timer.marks[-1][1] - timer.marks[1][1]
    cpu["stages_2_to_5"] = timer.marks[-1][2] - timer.marks[1][2]
    truth, _ = normalise(sc.truth.shape, np.zeros((1, 5)))
    err = np.asarray(rec.shape) - truth
    err[1:] = (err[1:] + np.pi) % (2 * np.pi) - np.pi
    z = err / rec.std if rec.std is not None else err * np.nan
    out = numerics(obs, rec, ps, ts) if check else {}
    return {
        **out,
        "frames": n,
        "seconds": {k: round(v, 3) for k, v in seconds.items()},
        "cpu_seconds": {k: round(v, 3) for k, v in cpu.items()},
        "shape": [round(float(v), 6) for v in rec.shape],
        "truth": [round(float(v), 6) for v in truth],
        "error_in_std": [round(float(v), 2) for v in z],
        "outliers": int((~rec.inliers).sum()),
        "estimator": rec.estimator,
        "peak_mb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0, 1),
    }


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(prog="python -m bench.stages")
    ap.add_argument("--sizes", default="1000,10000,30000,100000")
    ap.add_argument("--seed", type=int, default=2)
    ap.add_argument("--start", choices=("search", "truth"), default="search")
    ap.add_argument("--case", type=int)
    ap.add_argument("--profile")
    ap.add_argument("--numerics", action="store_true", help="check the large sums' accuracy")
    a = ap.parse_args(argv)
    if a.case is not None:
        print(json.dumps(run_case(a.case, a.seed, a.start, a.profile, a.numerics)))
        return
    for n in (int(v) for v in a.sizes.split(",")):
        cmd = [sys.executable, "-m", "bench.stages", "--case", str(n), "--seed", str(a.seed)]
        cmd += ["--start", a.start] + (["--numerics"] if a.numerics else [])
        proc = subprocess.run(cmd, capture_output=True, text=True, check=True)
        print(proc.stdout.strip().splitlines()[-1], flush=True)


if __name__ == "__main__":
    main()
