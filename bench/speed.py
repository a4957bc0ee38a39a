"""Speed: derivation, generated functions against sympy.lambdify, analytic against
finite-difference refinement, full reconstruction time against the number of frames.

Everything here runs in the main process while no worker is busy (so the timings see one idle
core, as far as the shared machine allows).  Timings are wall-clock (``time.perf_counter``);
per-call times are the best of three repeats, each long enough to be measured well.
"""

from __future__ import annotations

import math
import subprocess
import sys
import tempfile
import time
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from bench.common import make, true_poses
from curverecon.model.observations import Observations
from curverecon.pipeline import reconstruct
from curverecon.refine.ml import refine, standardised_residuals

REPO_ROOT = Path(__file__).resolve().parent.parent


# ------------------------------------------------------------------------------ derivation
def derive_seconds() -> dict[str, Any]:
    """Time ``python -m derivations --out <tmp> --docs <tmp>`` in a subprocess (wall clock)."""
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [
            sys.executable,
            "-m",
            "derivations",
            "--out",
            str(Path(tmp) / "generated"),
            "--docs",
            str(Path(tmp) / "docs"),
        ]
        start = time.perf_counter()
        proc = subprocess.run(cmd, cwd=REPO_ROOT, capture_output=True, text=True)
        seconds = time.perf_counter() - start
    return {
        "seconds": seconds,
        "returncode": proc.returncode,
        "command": "python -m derivations --out <tmp> --docs <tmp>",
        "stdout_tail": proc.stdout.strip().splitlines()[-6:],
        "stderr_tail": proc.stderr.strip().splitlines()[-3:],
    }


# ------------------------------------------------------------------------------ timing helper
def per_call_seconds(fn: Callable[[], object], min_seconds: float) -> float:
    """Best of three per-call times, each repeat running at least ``min_seconds / 3``."""
    fn()
    n = 1
    while True:
        start = time.perf_counter()
        for _ in range(n):
            fn()
        dt = time.perf_counter() - start
        if dt >= min_seconds / 3 or n >= 1 << 20:
            break
        n *= 2 if dt <= 0 else max(2, min(16, int(math.ceil(min_seconds / 3 / dt))))
    best = dt / n
    for _ in range(2):
        start = time.perf_counter()
        for _ in range(n):
            fn()
        best = min(best, (time.perf_counter() - start) / n)
    return best


# ------------------------------------------------------------------------------ kernels
_FRAME_ARGS = {"delta", "tau", "theta", "tx", "ty", "cp", "dp", "ep", "sin_tau"}


def _arg_values(names: list[str], n: int, rng: np.random.Generator) -> list[Any]:
    """Plausible values: shape scalars, frame arrays of length n (finite outputs)."""
    scalars = {
        "c": 150.0,
        "alpha": 0.6,
        "beta": 0.9,
        "phi": 1.1,
        "tan_alpha": math.tan(0.6),
        "tan_beta": math.tan(0.9),
    }
    frames = {
        "delta": lambda: rng.uniform(-np.pi, np.pi, n),
        "tau": lambda: rng.uniform(-1.2, 1.2, n),
        "theta": lambda: rng.uniform(-np.pi, np.pi, n),
        "tx": lambda: rng.uniform(-200, 200, n),
        "ty": lambda: rng.uniform(-200, 200, n),
        "cp": lambda: rng.uniform(50, 140, n),
        "dp": lambda: rng.uniform(-100, 100, n),
        "ep": lambda: rng.uniform(-100, 100, n),
        "sin_tau": lambda: rng.uniform(-0.9, 0.9, n),
    }
    out = []
    for name in names:
        if name in frames:
            out.append(frames[name]())
        elif name in scalars:
            out.append(scalars[name])
        else:
            out.append(rng.uniform(0.5, 1.5))
    return out


def _flatten(outputs: dict[str, Any]) -> tuple[list[Any], list[tuple[int, ...]]]:
    """Scalar expressions of every output in order, and each output's trailing shape."""
    import sympy as sp

    exprs: list[Any] = []
    shapes: list[tuple[int, ...]] = []
    for value in outputs.values():
        if isinstance(value, sp.MatrixBase):
            shapes.append(tuple(value.shape))
            exprs.extend(value[i, j] for i in range(value.rows) for j in range(value.cols))
        elif isinstance(value, (tuple, list)):
            shapes.append((len(value),))
            exprs.extend(value)
        else:
            shapes.append(())
            exprs.append(value)
    return exprs, shapes


def _assembler(raw: Callable[..., list[Any]], shapes: list[tuple[int, ...]]) -> Callable[..., Any]:
    """Wrap a lambdified flat function so it returns the generated function's array layout."""

    def call(*args: Any) -> Any:
        vals = raw(*args)
        n = np.broadcast_shapes(*(np.shape(a) for a in args))
        outs = []
        k = 0
        for shp in shapes:
            size = int(np.prod(shp)) if shp else 1
            if not shp:
                arr = np.empty(n)
                arr[...] = vals[k]
            else:
                arr = np.empty((*n, size))
                for j in range(size):
                    arr[..., j] = vals[k + j]
                arr = arr.reshape(*n, *shp)
            outs.append(arr)
            k += size
        return outs[0] if len(outs) == 1 else tuple(outs)

    return call


def _max_rel_diff(a: Any, b: Any) -> float:
    a = a if isinstance(a, tuple) else (a,)
    b = b if isinstance(b, tuple) else (b,)
    worst = 0.0
    for x, y in zip(a, b, strict=True):
        x, y = np.asarray(x, float), np.asarray(y, float)
        worst = max(worst, float(np.max(np.abs(x - y) / (1.0 + np.abs(y)))))
    return worst


def kernels(frame_counts: tuple[int, ...], min_seconds: float, seed: int) -> list[dict[str, Any]]:
    """Per-call time of every generated function against sympy.lambdify of its expressions.

    The expressions are the derivation's own (``derivations.measurement`` and
    ``derivations.section3`` ``generated_functions()``); lambdify (numpy printer, plain and with
    ``cse=True``) output is assembled into the same array layout the generated function returns,
    and the two results are compared.
    """
    import sympy as sp
    from curverecon.generated import frame_equations, measurement_model

    from derivations import measurement, section3

    rows = []
    rng = np.random.default_rng(seed)
    for source, module in ((measurement, measurement_model), (section3, frame_equations)):
        for spec in source.generated_functions():
            gen = getattr(module, spec.name)
            exprs, shapes = _flatten(spec.outputs)
            names = [a.name for a in spec.args]
            t0 = time.perf_counter()
            lam = _assembler(sp.lambdify(spec.args, exprs, modules="numpy"), shapes)
            t_lambdify = time.perf_counter() - t0
            t0 = time.perf_counter()
            lam_cse = _assembler(sp.lambdify(spec.args, exprs, modules="numpy", cse=True), shapes)
            t_lambdify_cse = time.perf_counter() - t0
            for n in frame_counts:
                args = _arg_values(names, n, rng)
                with np.errstate(all="ignore"):
                    diff = _max_rel_diff(gen(*args), lam(*args))
                    t_gen = per_call_seconds(lambda g=gen, a=args: g(*a), min_seconds)
                    t_lam = per_call_seconds(lambda f=lam, a=args: f(*a), min_seconds)
                    t_cse = per_call_seconds(lambda f=lam_cse, a=args: f(*a), min_seconds)
                rows.append(
                    {
                        "module": module.__name__.rsplit(".", 1)[-1],
                        "function": spec.name,
                        "n_frames": n,
                        "generated_s": t_gen,
                        "lambdify_s": t_lam,
                        "lambdify_cse_s": t_cse,
                        "speedup": t_lam / t_gen,
                        "speedup_vs_cse": t_cse / t_gen,
                        "max_rel_diff": diff,
                        "lambdify_build_s": t_lambdify,
                        "lambdify_cse_build_s": t_lambdify_cse,
                        "n_expressions": len(exprs),
                    }
                )
    return rows


# ------------------------------------------------------------------------------ refinement
def _fd_solve(
    obs: Observations,
    shape: np.ndarray,
    poses: np.ndarray,
    ps: float,
    ts: float,
    method: str,
) -> tuple[float, float, int]:
    """scipy least_squares with a dense 2-point finite-difference Jacobian: (s, chi2, nfev)."""
    from scipy.optimize import least_squares

    meas = obs.measurements()
    w8 = np.array([1.0 / ps] * 4 + [1.0 / ts] * 2)
    n = len(poses)

    def fun(x: np.ndarray) -> np.ndarray:
        return standardised_residuals(x[:4], x[4:].reshape(n, 5), meas, w8).ravel()

    x0 = np.concatenate([shape, np.ravel(poses)])
    kwargs: dict[str, Any] = {"jac": "2-point", "method": method}
    kwargs.update(ftol=1e-10, xtol=1e-10, gtol=1e-10)
    if method == "trf":
        kwargs["tr_solver"] = "exact"
    start = time.perf_counter()
    sol = least_squares(fun, x0, **kwargs)
    seconds = time.perf_counter() - start
    return seconds, float(2.0 * sol.cost), int(sol.nfev)


SAME_COST_CHI2 = 0.01
"""Two fits reach the same cost when their chi2 differ by less than this (chi2 units; the
statistical spread of chi2 is sqrt(2 x degrees of freedom), about 6 at 20 frames)."""


def _time_to_cost(
    obs: Observations, shape: np.ndarray, poses: np.ndarray, ts: float, target: float
) -> tuple[int, float]:
    """Fewest iterations after which ``refine`` (from the same start) has chi2 <= target, and
    the time of that truncated refinement (``refine(..., max_iter=k)``: the same iterates)."""
    k = 1
    while refine(obs, shape, poses, 1.0, ts, max_iter=k, covariance=False).chi2 > target:
        k += 1
    return k, per_call_seconds(
        lambda: refine(obs, shape, poses, 1.0, ts, max_iter=k, covariance=False), 0.2
    )


def refinement_vs_fd(
    problems: tuple[tuple[int, tuple[str, ...], int], ...], seed: int
) -> list[dict[str, Any]]:
    """Generated-Jacobian refinement (``refine.refine``) against scipy finite differences.

    ``problems``: (frames, scipy methods, number of problems).  Same problems (1 px, 1 degree,
    started at the truth), same residual function (``refine.standardised_residuals``); scipy's
    ``least_squares`` with ``jac="2-point"`` (dense; "trf" with the exact solver, "lm" MINPACK).
    Reports the times, the speedups and the relative difference of the final chi2.  Where
    scipy stops at a clearly higher chi2 (more than ``SAME_COST_CHI2`` above), the generated
    refinement is also timed up to the iteration where it first reaches scipy's final chi2
    (``speedup_equal_cost_<method>``): the speedup at equal quality.
    """
    rows = []
    for n, methods, n_problems in problems:
        for k in range(n_problems):
            scene = make(seed, "speed", (1, n, k), n, point_sigma=1.0, tangent_sigma_deg=1.0)
            shape, poses = true_poses(scene)
            obs = scene.observations
            ts = math.radians(1.0)
            refine(obs, shape, poses, 1.0, ts, covariance=False)  # warm-up
            t_gen = per_call_seconds(
                lambda o=obs, s=shape, p=poses, t=ts: refine(o, s, p, 1.0, t, covariance=False),
                0.2,
            )
            res = refine(obs, shape, poses, 1.0, ts, covariance=False)
            row: dict[str, Any] = {
                "n_frames": n,
                "problem": k,
                "generated_s": t_gen,
                "generated_chi2": res.chi2,
                "generated_iterations": res.iterations,
                "generated_converged": res.converged,
            }
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                for method in methods:
                    sec, chi2, nfev = _fd_solve(obs, shape, poses, 1.0, ts, method)
                    row[f"fd_{method}_s"] = sec
                    row[f"fd_{method}_chi2"] = chi2
                    row[f"fd_{method}_nfev"] = nfev
                    row[f"speedup_{method}"] = sec / t_gen
                    row[f"chi2_rel_diff_{method}"] = (chi2 - res.chi2) / max(res.chi2, 1e-300)
                    if chi2 > res.chi2 + SAME_COST_CHI2:
                        # scipy stopped at a higher cost (another local minimum, or short of
                        # it): time the generated refinement up to the iteration where it first
                        # reaches scipy's final cost, so both deliver the same quality
                        k, t_k = _time_to_cost(obs, shape, poses, ts, chi2 + SAME_COST_CHI2)
                        row[f"generated_equal_cost_{method}_iterations"] = k
                        row[f"generated_equal_cost_{method}_s"] = t_k
                        row[f"speedup_equal_cost_{method}"] = sec / t_k
            rows.append(row)
    return rows


# ------------------------------------------------------------------------------ reconstruction
def reconstruct_times(n_frames: int, repeats: int, seed: int) -> dict[str, Any]:
    """Median wall time of ``reconstruct`` on ``repeats`` scenes (1 px, 1 degree)."""
    times = []
    for k in range(repeats):
        scene = make(
            seed, "speed", (2, n_frames, k), n_frames, point_sigma=1.0, tangent_sigma_deg=1.0
        )
        start = time.perf_counter()
        reconstruct(scene.observations)
        times.append(time.perf_counter() - start)
    return {
        "n_frames": n_frames,
        "repeats": repeats,
        "median_s": float(np.median(times)),
        "min_s": float(np.min(times)),
        "max_s": float(np.max(times)),
    }


def refine_times(n_frames: int, repeats: int, seed: int) -> dict[str, Any]:
    """Median wall time of ``refine`` (with covariance) from the truth on a noisy scene."""
    scene = make(seed, "speed", (3, n_frames), n_frames, point_sigma=1.0, tangent_sigma_deg=1.0)
    shape, poses = true_poses(scene)
    times = []
    iters = 0
    for _ in range(repeats):
        start = time.perf_counter()
        res = refine(scene.observations, shape, poses, 1.0, math.radians(1.0))
        times.append(time.perf_counter() - start)
        iters = res.iterations
        converged = res.converged
    return {
        "n_frames": n_frames,
        "repeats": repeats,
        "median_s": float(np.median(times)),
        "iterations": iters,
        "converged": converged,
    }


def scaling(frame_counts: tuple[int, ...], budget_s: float, seed: int) -> list[dict[str, Any]]:
    """One ``reconstruct`` per frame count (small ones repeated), stopping before the budget.

    A frame count is skipped (and every larger one) when the time predicted from the previous
    two points (power law, exponent at least 1) would take the total past ``budget_s``.
    """
    done: list[dict[str, Any]] = []
    skipped: list[dict[str, Any]] = []
    spent = 0.0
    for n in frame_counts:
        predicted = None
        if done:
            n1, t1 = done[-1]["n_frames"], done[-1]["median_s"]
            p = 1.0
            if len(done) >= 2:
                n0, t0 = done[-2]["n_frames"], done[-2]["median_s"]
                p = max(1.0, math.log(t1 / t0) / math.log(n1 / n0))
            predicted = t1 * (n / n1) ** p
        if skipped or (predicted is not None and spent + predicted > budget_s):
            skipped.append({"n_frames": n, "skipped": True, "predicted_s": predicted})
            continue
        repeats = 3 if (predicted or 0.0) < 1.0 else 1
        r = reconstruct_times(n, repeats, seed)
        spent += r["median_s"] * repeats
        done.append(r)
    return done + skipped
