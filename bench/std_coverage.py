"""The curve bundle's shape std on more scenes than the bench's (not part of
``make bench``).

``python -m bench.std_coverage scan SEED_FROM SEED_TO``: the scenes of the bundle section's
``std_coverage_3sigma`` (``bench.bundle``: 1 px on every image point, 1 degree on the tangents,
12 frames, end points, tangents and polylines, every family of
``curverecon.curve_families.FAMILIES``) for every seed in the range; prints each scene's
|error| / std of (c, alpha, beta, phi), then the fraction of (scene, parameter) pairs below 3,
the RMS of |error| / std per parameter (1 for an honest std) and the CPU time.  The bench itself
uses seeds 1200-1203.

``python -m bench.std_coverage draws FAMILY SEED COUNT``: one geometry (the scene of that seed
without its noise) seen again under COUNT independent noise draws of the same model: the mean
error (bias) and the spread of the errors over the draws, both in units of the median reported
std, and the fraction of draws beyond 3 std; draws whose bundle the never-worse test refused
are left out of the bias and spread (their std is the widened end-point one).

``python -m bench.std_coverage curve SEED_FROM SEED_TO``: the bundle section's never_worse case
itself (``bench.bundle``, on 2 workers) for every family and seed in the range; prints the
fraction of ``curve3d`` points within 3 ``curve3d_normal_std`` of the true curve (the bench's
``curve3d_normal_std_coverage_3sigma``) and their RMS |distance| / std, the shape's
``std_coverage_3sigma``, and the scenes with the most points beyond.  Scenes whose run without
the bundle is refused count (they have no pair for the never-worse rate only), as in the bench.

Findings at commit 720ca49 (helper scripts beside this module for the parts that need the
bundle's internals):

- Coverage of |error| / std < 3: bench seeds 1200-1203 0.979 (2 of 96: bezier 1201 c 3.53,
  random 1202 beta 3.92), 1204-1207 0.990 (1 of 96), so 1200-1207 0.984 (3 of 192); tuning
  seeds 5000-5009 0.996 (1 of 240); held-out seeds 9100-9119 0.985 (7 of 480, 2 of them on a
  refused bundle); 912 single-draw pairs together 0.988.  RMS of |error| / std per parameter
  1.0-1.3 (c highest on every set).
- The two bench pairs are not bias or a wrong minimum: the bundle started from the true poses
  and curve ends at the same cost and error (3.41 and 3.95 std), the noise-free optimum's
  shape is the truth to 0.05 std (no spline or penalty bias), and 100 noise draws of each
  geometry give bias 0.24 / 0.03 std and a spread of 0.97 / 0.99 std for those parameters.
- The covariance itself is right for the estimator it linearises: the linear response to the
  noise at the noise-free optimum has a std of 0.96-1.01 times the reported one, the penalty
  (0.1) changes the std by under 0.4 %, the sandwich with the rows the final fit adds (reverse
  term, robust ends) by under 4 %.
- The excess is the estimator's nonlinear part: over 100 draws the actual error minus the linear
  response has a std of 0.2-0.6 std, is nearly uncorrelated with the linear part and
  heavy-tailed (kurtosis of phi 3.7 and 5.9 against the linear part's 2.3-2.9); every draw of
  random 1202 beyond 3 std is beyond it through that part (the linear part stays below 2.8).
  Part of it is nearby local minima: LM from the truth and from the pipeline's start end 0.3-0.6
  std apart on the same data, and on the bench draw of random 1202 the cost falls by 2.7 along
  the straight line to the truth-started minimum except for bumps of 0.1-0.3 from the reverse
  term (distances of curve samples to the jagged noisy polyline: kinks where the nearest
  segment changes).  12 geometries (seeds 5000-5001, every family) x 12 draws: spread / std
  (RMS over the geometries) 1.06, 0.78, 1.00, 0.95 at 12 control points, 1.16, 1.87, 1.48, 1.05
  at 21 (the std does not follow the freer ends), 1.03, 0.86, 0.95, 0.97 at 8 with more bias
  (RMS bias 0.34-0.48 std against 0.23-0.39, noise floor 0.29).
- One accepted wrong minimum in 576 draws (fourier 5000, draw 11: cost 2134 against 1805 from
  the truth, c and beta 3.6 and 4.3 std off): the end-point answer had alternatives, so the
  curve decided, and frame 9 fitted at 1.47 sigma RMS, just under the restart level (1.53).

From commit b728435 on:

- The never-worse gate now also applies where the end-point answer has equally good
  alternatives, from the least chi2 of the answer and its alternatives
  (``CurveOptions.never_worse_alternatives``; before, the curve alone decided there).  At 1 px,
  12 frames those alternatives are mostly nearby minima of a loosely fixed end-point fit, a
  few std apart.  Seeds 1200-1207: 2 of 192 pairs above 3 (was 3; random 1205 refused,
  its beta 3.06 std off before); held-out 9100-9119: 8 of 480 both ways (9101 bezier and 9112
  fourier refused, c of 9112 2.8 -> 0.33 of the widened std), RMS per parameter 1.171, 1.063,
  1.051, 1.009 -> 1.142, 1.038, 1.050, 1.005.
- Two tries at the reverse term's kinks, neither kept (seeds 1200-1207, 48 scenes): the
  reverse term measured from each polyline smoothed by a cubic Savitzky-Golay filter in the
  joint fit (C1-smooth in effect: the vertex angles become the curve's own): 15 points, 4
  pairs above 3; 7 points, 4 above, ``curve3d`` within 3 normal std 0.963 and RMS 1.39 (against
  2, 0.968, 1.29 with the raw polyline); no reverse term in the final polish (the estimator
  the covariance linearises): 3 above, 0.918 and RMS 2.69 (the reverse term keeps stretches
  that no polyline point is near in place).  The excess is not the kinks' alone.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import sys  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402

import numpy as np  # noqa: E402

from curverecon.curve_families import FAMILIES  # noqa: E402
from curverecon.model.observations import Observations  # noqa: E402
from curverecon.pipeline import reconstruct  # noqa: E402
from curverecon.simulate import make_scene  # noqa: E402

FRAMES = 12


def shape_error(shape: np.ndarray, truth: np.ndarray) -> np.ndarray:
    """(c, alpha, beta, phi) error, phi wrapped to (-pi, pi]."""
    err = np.asarray(shape, float) - np.asarray(truth, float)
    err[3] = (err[3] + np.pi) % (2.0 * np.pi) - np.pi
    return err


def noisy(obs: Observations, rng: np.random.Generator, sigma: float = 1.0, deg: float = 1.0):
    """Noise-free observations with ``sigma`` px on every image point and ``deg`` degrees on the
    tangents (the simulator's noise model)."""

    def turned(t: np.ndarray) -> np.ndarray:
        ang = np.arctan2(t[:, 1], t[:, 0]) + rng.normal(scale=np.radians(deg), size=len(t))
        return np.column_stack([np.cos(ang), np.sin(ang)])

    return Observations(
        obs.a + rng.normal(scale=sigma, size=obs.a.shape),
        obs.b + rng.normal(scale=sigma, size=obs.b.shape),
        turned(obs.tangent_a),
        turned(obs.tangent_b),
        [c + rng.normal(scale=sigma, size=c.shape) for c in obs.curves],
    )


def scan(seeds: range) -> np.ndarray:
    """|error| / std per (scene, parameter), one row per scene (seed-major, then family)."""
    rows = []
    for seed in seeds:
        for family in FAMILIES:
            sc = make_scene(
                np.random.default_rng(seed), FRAMES, 1.0, 1.0, with_curve=True, curve_family=family
            )
            rec = reconstruct(sc.observations)
            z = np.abs(shape_error(rec.shape, sc.truth.shape)) / rec.std
            info = rec.curve_bundle or {}
            mark = "  <- above 3" if z.max() >= 3.0 else ""
            print(
                f"{seed} {family:10s} |error|/std {np.round(z, 2)} "
                f"accepted {info.get('accepted')}{mark}",
                flush=True,
            )
            rows.append(z)
    return np.array(rows)


def curve_scan(seeds: range) -> dict:
    """The never_worse case of ``bench.bundle`` on every family and seed: the ``curve3d`` and
    shape coverage over the scenes whose run with polylines answered (a refused run without
    the bundle no longer leaves a scene out, as in the bench)."""
    from multiprocessing import get_context

    from bench.bundle import WORKERS, case

    tasks = [("never_worse", family, seed) for seed in seeds for family in FAMILIES]
    with get_context("fork").Pool(WORKERS) as pool:
        rows = [r for r in pool.map(case, tasks, chunksize=1) if "error" not in r]
    zn = np.array([v for r in rows for v in r.get("curve_zn", [])])
    z = np.array([v for r in rows for v in r["z_with"]])
    worst = sorted(
        (
            (float(np.mean(np.array(r.get("curve_zn", [0.0])) >= 3.0)), r["family"], r["seed"])
            for r in rows
        ),
        reverse=True,
    )
    return {
        "scenes": len(rows),
        "refused_with": len(tasks) - len(rows),
        "refused_without": sum("off_refused" in r for r in rows),
        "curve_coverage": float(np.mean(zn < 3.0)),
        "curve_z_rms": float(np.sqrt(np.mean(zn * zn))),
        "shape_coverage": float(np.mean(z < 3.0)),
        "worst": [w for w in worst[:5] if w[0] > 0.0],
    }


def draws(family: str, seed: int, count: int) -> dict:
    """Bias and spread over ``count`` noise draws of one geometry (units of the median std)."""
    sc = make_scene(
        np.random.default_rng(seed), FRAMES, 0.0, 0.0, with_curve=True, curve_family=family
    )
    rng = np.random.default_rng(777)
    err, std, accepted = [], [], []
    for _ in range(count):
        rec = reconstruct(noisy(sc.observations, rng))
        err.append(shape_error(rec.shape, sc.truth.shape))
        std.append(rec.std)
        accepted.append(bool((rec.curve_bundle or {}).get("accepted", True)))
    err, std, ok = np.array(err), np.array(std), np.array(accepted)
    med = np.median(std[ok], axis=0)
    return {
        "accepted": int(ok.sum()),
        "bias": err[ok].mean(axis=0) / med,
        "spread": err[ok].std(axis=0, ddof=1) / med,
        "above_3": np.mean(np.abs(err[ok]) / std[ok] >= 3.0, axis=0),
    }


if __name__ == "__main__":
    warnings.filterwarnings("ignore")
    t0 = time.process_time()
    if sys.argv[1:2] == ["scan"]:
        z = scan(range(int(sys.argv[2]), int(sys.argv[3])))
        print(
            f"pairs {z.size}: |error|/std < 3 {np.mean(z < 3.0):.4f} ({int((z >= 3.0).sum())} "
            f"above); RMS per parameter {np.round(np.sqrt(np.mean(z * z, axis=0)), 3)}; "
            f"cpu {time.process_time() - t0:.0f} s"
        )
    elif sys.argv[1:2] == ["curve"]:
        out = curve_scan(range(int(sys.argv[2]), int(sys.argv[3])))
        print(
            f"scenes {out['scenes']} ({out['refused_with']} refused with polylines, left out; "
            f"{out['refused_without']} refused without, kept): curve3d within 3 "
            f"normal std {out['curve_coverage']:.4f} (RMS z {out['curve_z_rms']:.3f}); shape "
            f"|error|/std < 3 {out['shape_coverage']:.4f}"
        )
        for frac, family, seed in out["worst"]:
            print(f"  {family} {seed}: {100 * frac:.1f} % of its points beyond 3 std")
    elif sys.argv[1:2] == ["draws"]:
        out = draws(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]))
        print(f"accepted {out['accepted']} of {sys.argv[4]} draws")
        print(f"bias / std    {np.round(out['bias'], 2)} (+- {1 / np.sqrt(out['accepted']):.2f})")
        print(f"spread / std  {np.round(out['spread'], 2)}")
        print(f"beyond 3 std  {np.round(out['above_3'], 3)}")
        print(f"cpu {time.process_time() - t0:.0f} s")
    else:
        sys.exit(__doc__)
