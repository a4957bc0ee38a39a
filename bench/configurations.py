"""The orthographic Section 2 rows: ``python -m bench --only configurations``.

Rows (key names): ``ortho_uniform_rotation`` (A, B), ``ortho_fixed_axis`` (A, B),
``ortho_free_3pt`` (A, B, C), ``ortho_force_field`` (A, B); scenes from
``bench.rigid_scenes`` (an independent 3-D construction), each seeded by a SeedSequence of
(bench seed, kind, row, scene).  Keys per row ``config_<row>_...``:

- ``noise_free_max_error``: the largest error of any point of any frame (points3, relative to
  the chord c) of ``reconstruct_rigid`` on noise-free scenes of ``UNIQUE_FRAMES`` frames (up to
  the symmetries: the mirror, and for a planar body each frame's depth reversal);
- ``rmse_over_crlb``: over ``ACCURACY_SCENES`` scenes (20 frames, 30 for the force field, 1 px),
  the root mean square over scenes of each shape and motion parameter's error divided by its
  Cramer-Rao bound (the Fisher information at the truth), the worst parameter; with
  ``_oracle`` the same for the maximum likelihood started at the truth;
- ``std_coverage_3sigma``: the fraction of (scene, parameter) whose error is within three of the
  answer's standard deviations;
- ``success_rate_20pct_outliers``: a fifth of the frames with random points (``OUTLIER_SCENES``);
  success as for the paper's row, by the answer's accuracy: c within 5 % of the truth (a frame of
  random points that happens to fit within the noise is no error); ``_oracle`` the same for
  maximum likelihood on the good frames alone started at the truth; beside it
  ``outlier_frames_flagged_rate`` (outlier frames flagged) and ``good_frames_flagged_rate``;
- ``curve_within_1pct_rate``: with 0.5 px polylines (and points), 20 frames: curve3d's
  symmetric mean distance from the true curve within 1 % of its length (the curve bench's
  measure, ``bench.curve_end_to_end.curve_error``);
- ``config_motion_auto_correct_rate``: ``--motion auto`` on scenes of each motion with A, B, C
  (20 frames, 1 px): the chosen model is the scene's.

The minimal solvers' keys come from ``bench.config_minimal.run(seed, scenes)`` where it exists.
``python -m bench.configurations [--seed N] [--quick] [--kinds K ...] [--rows R ...]
[--noise PX]`` prints the keys as JSON (a held-out seed, a part of the section, the accuracy
scenes at another noise), without touching the report.  The axis rows add
``rmse_over_crlb_tilt5`` (with ``_oracle``: scenes whose axis is at least 5 degrees out of the
image plane) and ``chi2_at_oracle_rate`` (the estimate fits no worse than the oracle).
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402

import numpy as np  # noqa: E402

from bench.common import Task, chunks, run_tasks  # noqa: E402
from bench.rigid_scenes import RigidScene, make_rigid_scene  # noqa: E402

ROWS = {
    "ortho_uniform_rotation": ("uniform-rotation", "AB"),
    "ortho_fixed_axis": ("fixed-axis", "AB"),
    "ortho_free_3pt": ("free", "ABC"),
    "ortho_force_field": ("force-field", "AB"),
}
UNIQUE_FRAMES = {"uniform-rotation": 8, "fixed-axis": 8, "free": 6, "force-field": 14}
"""Frames of the noise-free scenes: a few above the least count, where the answer is unique up
to its symmetries."""
ACCURACY_SCENES = 200
NOISE_FREE_SCENES = 30
OUTLIER_SCENES = 40
CURVE_SCENES = 20
AUTO_SCENES = 15
MINIMAL_SCENES = 1000
"""Noise-free scenes per row of the minimal solvers' keys (``bench.config_minimal``)."""
PERSP_FIXED_AXIS_SCENES = 200
"""The perspective fixed-axis solver takes about 0.8 s a scene (84 homotopy paths, three
charts): 1,000 scenes would take a quarter of the bench's budget (``python -m
bench.config_minimal_persp --rows persp_fixed_axis_3pt --scenes 1000`` runs them)."""
CHUNK = 5
WORKERS = 2
DEFAULT_SEED = 2026
KINDS = ("noise_free", "accuracy", "outliers", "curve", "auto")


def scene_seed(seed: int, kind: str, row: int, index: int) -> int:
    return int(np.random.SeedSequence([seed, KINDS.index(kind), row, index]).generate_state(1)[0])


def observations(scene: RigidScene, motion: str):
    """The scene as ``RigidObservations`` under ``motion``."""
    from curverecon.model.configuration import Configuration, RigidObservations

    tan = None
    if scene.angles is not None:
        tan = np.stack([np.cos(scene.angles), np.sin(scene.angles)], axis=-1)
    cfg = Configuration("orthographic", motion, scene.names, tan is not None)
    return RigidObservations(cfg, scene.times, scene.points, tan, scene.curves)


def _points3(rec, names) -> np.ndarray:
    return np.array([[p[n] for n in names] for p in rec.points3])


def points_error(scene: RigidScene, rec) -> float:
    """Largest point error over every frame relative to c, up to the mirror and (a planar body
    under free rotations: A, B, C or A, B and the mass centre) each frame's depth reversal."""
    est = _points3(rec, scene.names)
    truth = scene.points3
    c = float(np.linalg.norm(truth[0, 1] - truth[0, 0]))
    flip = np.array([1.0, 1.0, -1.0])
    best = np.inf
    for mirror in (1.0, -1.0):
        t = truth * (flip if mirror < 0 else 1.0)
        err = np.abs(est - t).max(axis=(1, 2))
        planar = len(scene.names) <= 3 and scene.angles is None
        if planar and scene.motion in ("free", "force-field"):
            err = np.minimum(err, np.abs(est - t * flip).max(axis=(1, 2)))
        best = min(best, float(err.max()))
    return best / c


def _truth_state(scene: RigidScene, layout, data):
    from curverecon.rigid.geometry import state_from_geometry
    from curverecon.rigid.measurements import RigidData

    exact = RigidData(scene.times, scene.points3[:, :, :2], scene.angles, 1.0, 1.0)
    state = state_from_geometry(layout, exact, scene.points3, scene.rotations)
    if scene.angles is not None:
        from curverecon.rigid.model import axis_angles

        state.directions = np.array([axis_angles(u) for u in scene.tangents3])
    return state


def parameter_vector(layout, state, times, mirror: bool | None = None) -> np.ndarray:
    """The shape and motion parameters compared with the truth (normalised state; ``mirror``
    as ``rigid.model.normalise``)."""
    from curverecon.rigid.model import normalise

    s = normalise(layout, state, times, mirror)
    parts = [s.body.ravel()]
    if s.directions is not None:
        parts.append(s.directions.ravel())
    if s.axis is not None:
        parts.append(s.axis)
    if s.rate is not None:
        parts.append([s.rate])
    if s.parabola is not None:
        parts.append(s.parabola.ravel())
    return np.concatenate(parts)


def axis_reversed(layout, v: np.ndarray) -> np.ndarray:
    """A fixed-axis parameter vector with the axis reversed, n -> -n (kappa -> pi - kappa,
    lam -> lam + pi), the angles negated (not in the vector): the same rotations.  The
    normalisation's sign (a non-negative angle sum) flips with noise when the angles sum to
    about zero (a tilt series about its middle), and that flip is no error."""
    out = np.array(v, float)
    k = layout.global_names().index("axis_kappa")
    out[k], out[k + 1] = np.pi - out[k], out[k + 1] + np.pi
    return out


def _wrap_diff(layout, d: np.ndarray) -> np.ndarray:
    """Angle parameters' differences wrapped to (-pi, pi]."""
    names = layout.global_names()
    out = np.array(d, float)
    for i, name in enumerate(names):
        if name.endswith(("azimuth", "lam", "kappa", "polar")):
            out[i] = np.angle(np.exp(1j * out[i]))
    return out


def accuracy_scenes(seed: int, row: int, indices: range, noise: float = 1.0) -> list[dict]:
    """Per scene: errors / CRLB of the answer and of the oracle, the 3-sigma coverage, both
    fits' chi2 over every frame; ``noise`` the points' noise (pixels)."""
    from curverecon.rigid import fit_motion, reconstruct_rigid, rigid_data  # noqa: F401
    from curverecon.rigid.measurements import RigidData
    from curverecon.rigid.model import Layout
    from curverecon.rigid.refinement import fisher_information, refine

    motion, names = list(ROWS.values())[row]
    frames = 30 if motion == "force-field" else 20
    out = []
    for i in indices:
        sc = make_rigid_scene(motion, names, frames, scene_seed(seed, "accuracy", row, i), noise)
        layout = Layout(motion, tuple(names), False)
        data = RigidData(sc.times, sc.points, None, noise, 1.0)
        truth = _truth_state(sc, layout, data)
        crlb = np.sqrt(np.diag(np.linalg.inv(fisher_information(layout, truth, data))))
        # the truth in both mirror images: where B lies near A's depth the estimate's mirror
        # choice may differ from the truth's, and the mirror is no error; a fixed axis also
        # with the opposite axis sign (Rot(n, a) = Rot(-n, -a): the same motion)
        tvs = [parameter_vector(layout, truth, sc.times, m) for m in (False, True)]
        tvs += [axis_reversed(layout, t) for t in tvs if layout.motion == "fixed-axis"]

        def closest(v, tvs=tvs, crlb=crlb, layout=layout):
            ds = [_wrap_diff(layout, v - t) for t in tvs]
            return min(ds, key=lambda e: float(np.sum((e / crlb) ** 2)))

        oracle = refine(layout, truth, data, covariance=False, max_iter=200)
        z_oracle = closest(parameter_vector(layout, oracle.state, sc.times)) / crlb
        rec = {"index": i}
        if sc.axis is not None:  # the axis's angle out of the image plane (degrees)
            rec["axis_tilt_deg"] = float(np.degrees(np.arcsin(min(abs(sc.axis[2]), 1.0))))
        try:
            lay, fit, inl = fit_motion(observations(sc, motion), motion, _options(noise))
            est = fit.full_state or fit.state
            rec["chi2"] = refine(layout, est, data, covariance=False, max_iter=0).chi2
            rec["chi2_oracle"] = oracle.chi2
            d = closest(parameter_vector(layout, est, sc.times))
            rec["z"] = (d / crlb).tolist()
            sd = (
                np.sqrt(np.diag(fit.covariance)) if fit.covariance is not None else np.zeros_like(d)
            )
            rec["covered"] = (np.abs(d) <= 3 * sd).tolist()
            rec["outliers_flagged"] = int(np.count_nonzero(~inl))
        except Exception as exc:  # noqa: BLE001 (a failure is counted, not raised)
            rec["error"] = str(exc)
        rec["z_oracle"] = z_oracle.tolist()
        out.append(rec)
    return out


def _options(point_sigma: float = 1.0):
    from curverecon.options import ReconstructOptions

    return ReconstructOptions(point_sigma=point_sigma)


def noise_free_scenes(seed: int, row: int, indices: range) -> list[dict]:
    from curverecon.rigid import reconstruct_rigid

    motion, names = list(ROWS.values())[row]
    out = []
    for i in indices:
        sc = make_rigid_scene(
            motion, names, UNIQUE_FRAMES[motion], scene_seed(seed, "noise_free", row, i), 0.0
        )
        try:
            # noise-free: the stated noise small, so the input check does not read a slow turn
            # as no turn at all
            rec = reconstruct_rigid(observations(sc, motion), _options(1e-6))
            out.append({"index": i, "error": points_error(sc, rec)})
        except Exception as exc:  # noqa: BLE001
            out.append({"index": i, "error": float("inf"), "message": str(exc)})
    return out


def outlier_scenes(seed: int, row: int, indices: range) -> list[dict]:
    from curverecon.rigid import reconstruct_rigid

    motion, names = list(ROWS.values())[row]
    frames = 30 if motion == "force-field" else 20
    out = []
    for i in indices:
        sc = make_rigid_scene(
            motion, names, frames, scene_seed(seed, "outliers", row, i), outlier_fraction=0.2
        )
        c = float(np.linalg.norm(sc.points3[0, 1] - sc.points3[0, 0]))
        rec_out = {"index": i, "success": False, "flagged": 0.0, "good_flagged": 0.0}
        rec_out["oracle_success"] = _outlier_oracle(sc, motion, names, c)
        try:
            rec = reconstruct_rigid(observations(sc, motion))
            flagged = ~np.asarray(rec.inliers)
            rec_out["success"] = bool(abs(rec.c - c) <= 0.05 * c)
            rec_out["flagged"] = float(np.mean(flagged[sc.outliers]))
            rec_out["good_flagged"] = float(np.mean(flagged[~sc.outliers]))
        except Exception:  # noqa: BLE001
            pass
        out.append(rec_out)
    return out


def _outlier_oracle(sc: RigidScene, motion: str, names: str, c: float) -> bool:
    """Maximum likelihood on the good frames alone (the outlier frames known), started at the
    truth: c within 5 % of the truth (what the outliers' success asks of the estimate)."""
    from curverecon.rigid.measurements import RigidData
    from curverecon.rigid.model import Layout, body_vectors, with_frames
    from curverecon.rigid.refinement import refine

    layout = Layout(motion, tuple(names), False)
    good = np.flatnonzero(~sc.outliers)
    data = RigidData(sc.times, sc.points, None, 1.0, 1.0)
    truth = with_frames(_truth_state(sc, layout, data), good)
    fit = refine(layout, truth, data.subset(good), covariance=False, max_iter=200)
    q = body_vectors(layout, fit.state)
    return bool(abs(float(np.linalg.norm(q[1] - q[0])) - c) <= 0.05 * c)


def curve_error(scene: RigidScene, curve3d: np.ndarray) -> float:
    """The curve bench's error (``bench.curve_end_to_end.curve_error``): symmetric mean distance
    between curve3d and the true curve over the true length, best over the mirror image."""
    from bench.curve_end_to_end import curve_error as symmetric_error

    return float(symmetric_error(np.asarray(curve3d, float), scene.curve3d))


def curve_scenes(seed: int, row: int, indices: range) -> list[dict]:
    from curverecon.rigid import reconstruct_rigid

    motion, names = list(ROWS.values())[row]
    out = []
    for i in indices:
        sc = make_rigid_scene(
            motion, names, 20, scene_seed(seed, "curve", row, i), 0.5, with_curve=True
        )
        try:
            rec = reconstruct_rigid(observations(sc, motion))
            err = curve_error(sc, rec.curve3d) if rec.curve3d is not None else float("inf")
        except Exception:  # noqa: BLE001
            err = float("inf")
        out.append({"index": i, "error": err})
    return out


def auto_scenes(seed: int, row: int, indices: range) -> list[dict]:
    from curverecon.rigid import reconstruct_rigid

    motion = list(ROWS.values())[row][0]
    out = []
    for i in indices:
        sc = make_rigid_scene(motion, "ABC", 20, scene_seed(seed, "auto", row, i))
        try:
            chosen = reconstruct_rigid(observations(sc, "auto")).configuration["motion"]
        except Exception as exc:  # noqa: BLE001
            chosen = f"error: {exc}"
        out.append({"index": i, "chosen": chosen, "truth": motion})
    return out


TILT_DEG = 5.0
"""Scenes whose axis lies at least this far out of the image plane: nearer, B's depth is
barely determined (the image ellipse's minor axis about 5 px at a chord of 100 px) and the
likelihood has distant minima that fit better than the truth's."""


def _axis_keys(key: str, ok: list[dict]) -> dict:
    """The axis rows' diagnostic keys: ``rmse_over_crlb_tilt5`` (and its ``_oracle``) over the
    scenes whose axis is at least ``TILT_DEG`` out of the image plane; ``chi2_at_oracle_rate``
    the fraction of scenes whose estimate fits every frame no worse than the oracle (chi2 at
    most 0.5 above it: the search found the likelihood's best basin known)."""
    if "axis_tilt_deg" not in ok[0]:
        return {}
    tilted = [r for r in ok if r["axis_tilt_deg"] >= TILT_DEG]
    z = np.array([r["z"] for r in tilted])
    zo = np.array([r["z_oracle"] for r in tilted])
    return {
        f"config_{key}_rmse_over_crlb_tilt5": round(float(np.sqrt(np.mean(z**2, 0)).max()), 3),
        f"config_{key}_rmse_over_crlb_tilt5_oracle": round(
            float(np.sqrt(np.mean(zo**2, 0)).max()), 3
        ),
        f"config_{key}_tilt5_scenes": len(tilted),
        f"config_{key}_chi2_at_oracle_rate": round(
            float(np.mean([r["chi2"] <= r["chi2_oracle"] + 0.5 for r in ok])), 3
        ),
    }


def _summarise(groups: dict[str, list[dict]]) -> dict:
    out: dict = {}
    for row, key in enumerate(ROWS):
        acc = groups.get(f"accuracy|{row}", [])
        ok = [r for r in acc if "z" in r]
        if ok:
            out.update(_axis_keys(key, ok))
            z = np.array([r["z"] for r in ok])
            out[f"config_{key}_rmse_over_crlb"] = round(float(np.sqrt(np.mean(z**2, 0)).max()), 3)
            out[f"config_{key}_rmse_over_crlb_median_param"] = round(
                float(np.median(np.sqrt(np.mean(z**2, 0)))), 3
            )
            out[f"config_{key}_std_coverage_3sigma"] = round(
                float(np.mean([r["covered"] for r in ok])), 4
            )
        if acc:
            zo = np.array([r["z_oracle"] for r in acc])
            out[f"config_{key}_rmse_over_crlb_oracle"] = round(
                float(np.sqrt(np.mean(zo**2, 0)).max()), 3
            )
            out[f"config_{key}_accuracy_scenes"] = len(acc)
            out[f"config_{key}_accuracy_failures"] = len(acc) - len(ok)
        nf = groups.get(f"noise_free|{row}", [])
        if nf:
            out[f"config_{key}_noise_free_max_error"] = float(max(r["error"] for r in nf))
            out[f"config_{key}_noise_free_scenes"] = len(nf)
        ol = groups.get(f"outliers|{row}", [])
        if ol:
            out[f"config_{key}_success_rate_20pct_outliers"] = round(
                float(np.mean([r["success"] for r in ol])), 3
            )
            out[f"config_{key}_success_rate_20pct_outliers_oracle"] = round(
                float(np.mean([r["oracle_success"] for r in ol])), 3
            )
            out[f"config_{key}_outlier_frames_flagged_rate"] = round(
                float(np.mean([r["flagged"] for r in ol])), 3
            )
            out[f"config_{key}_good_frames_flagged_rate"] = round(
                float(np.mean([r["good_flagged"] for r in ol])), 3
            )
        cv = groups.get(f"curve|{row}", [])
        if cv:
            out[f"config_{key}_curve_within_1pct_rate"] = round(
                float(np.mean([r["error"] <= 0.01 for r in cv])), 3
            )
    auto = [r for row in range(len(ROWS)) for r in groups.get(f"auto|{row}", [])]
    if auto:
        out["config_motion_auto_correct_rate"] = round(
            float(np.mean([r["chosen"] == r["truth"] for r in auto])), 3
        )
        out["config_motion_auto_scenes"] = len(auto)
    return out


def run(
    quick: bool = False,
    seed: int | None = None,
    workers: int = WORKERS,
    kinds: tuple[str, ...] = KINDS,
    noise: float = 1.0,
    rows: tuple[str, ...] = tuple(ROWS),
) -> dict:
    """The section's report keys for ``seed`` (default ``DEFAULT_SEED``); ``kinds`` a subset
    of ``KINDS`` and ``rows`` of ``ROWS`` (the minimal solvers' keys only with all of both;
    ``auto`` scenes of every motion whatever ``rows``), ``noise`` the accuracy scenes' point
    noise (pixels)."""
    seed = DEFAULT_SEED if seed is None else seed
    t0 = time.time()
    warnings.filterwarnings("ignore", category=RuntimeWarning)
    counts = {
        "accuracy": (accuracy_scenes, 4 if quick else ACCURACY_SCENES),
        "noise_free": (noise_free_scenes, 2 if quick else NOISE_FREE_SCENES),
        "outliers": (outlier_scenes, 2 if quick else OUTLIER_SCENES),
        "curve": (curve_scenes, 1 if quick else CURVE_SCENES),
        "auto": (auto_scenes, 1 if quick else AUTO_SCENES),
    }
    tasks = [
        Task(fn, (seed, row, r) + ((noise,) if kind == "accuracy" else ()), len(r), f"{kind}|{row}")
        for kind, (fn, n) in counts.items()
        if kind in kinds
        for row in range(len(ROWS))
        if kind == "auto" or list(ROWS)[row] in rows
        for r in chunks(n, CHUNK)
    ]
    groups = run_tasks(tasks, workers, "configurations", progress=True)
    out = _summarise(groups)
    if set(kinds) == set(KINDS) and set(rows) == set(ROWS):
        out.update(_minimal(seed, quick))
    out["config_seed"] = seed
    out["config_seconds"] = round(time.time() - t0, 1)
    return out


def _minimal(seed: int, quick: bool) -> dict:
    """The minimal solvers' keys: the orthographic rows (``bench.config_minimal``) and the
    perspective and stereo rows (``bench.config_minimal_persp``; the perspective fixed axis on
    ``PERSP_FIXED_AXIS_SCENES`` scenes)."""
    from bench import config_minimal, config_minimal_persp

    n = 20 if quick else MINIMAL_SCENES
    out = config_minimal.run(seed, n)
    fast = tuple(r for r in config_minimal_persp.ROWS if r != "persp_fixed_axis_3pt")
    out.update(config_minimal_persp.run(seed, n, fast))
    slow = 10 if quick else PERSP_FIXED_AXIS_SCENES
    out.update(config_minimal_persp.run_row("persp_fixed_axis_3pt", seed, slow))
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.configurations")
    parser.add_argument("--seed", type=int, default=None)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--workers", type=int, default=WORKERS)
    parser.add_argument("--kinds", nargs="+", choices=KINDS, default=list(KINDS))
    parser.add_argument("--noise", type=float, default=1.0, help="accuracy scenes' noise (px)")
    parser.add_argument("--rows", nargs="+", choices=list(ROWS), default=list(ROWS))
    args = parser.parse_args(argv)
    out = run(args.quick, args.seed, args.workers, tuple(args.kinds), args.noise, tuple(args.rows))
    print(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
