"""``--motion auto``: every motion model the points allow, chosen by nested likelihood-ratio
tests where the models nest and by BIC between the rest, both with a robust chi2.

Candidates: two points without tangents: uniform-rotation, fixed-axis, force-field; two points
with tangents: those and free motion through the paper's pipeline; three points or more: all
four; under a pinhole or a stereo pair also rotation-free, and only the models the points
determine (``model.configuration.motion_determined``).  Each is fitted (``rigid.estimate``);
chi2_f is each frame's chi2 at the fit, T the outlier test's threshold for a frame of that
model (``OutlierOptions.false_alarm``), k the number of free parameters (global plus every
frame's own, the gauge's fixed ones not counted), n the number of measurements.

One pinhole camera with fewer than four points and a polyline in every frame: free motion is
the ordinary camera's curve bundle (``curve.pinhole``), whose free poses fit A and B (and C)
exactly in every frame; on the points it is the saturated model (chi2 0, as many parameters as
measurements).  Its tests against the rigid models are then each model's goodness of fit, and it
is chosen only when every model it contains is rejected; its bundle runs only then.

Nesting (``NESTS_IN``): rotation-free is a uniform rotation of rate zero, a uniform rotation a
fixed axis whose angles grow with t, and every model a free motion; the force field (free
rotations, the mass centre on a parabola) and the axis models (translations free) do not nest
in one another.  A fixed axis is also fitted from the uniform rotation's optimum (its angles
w (t_f - t_0)), so that its fit is never worse than the model it contains.

Choice:

1. Every nested pair (simple s in complex c, both fitted): the robust likelihood ratio
   D = sum_f [min(chi2_f(s), T_s) - min(chi2_f(c), T_s)] against chi2 with df = k_c - k_s
   degrees of freedom (less the per-frame parameters of frames both models leave out: they
   contribute nothing).  D's tail probability below ``LEVEL`` rejects s: c explains the data
   significantly better.
2. A model with a sub-model that no test rejected is dominated: the simpler one explains the
   data as well (a uniform rotation *is* a fixed-axis motion; when the data cannot tell them
   apart the simpler answer is not wrong, and it is better determined).
3. Among the models neither rejected nor dominated (models that do not nest, e.g. the uniform
   rotation and the force field), the lowest BIC = sum_f min(chi2_f, T) + k ln(n) wins; the
   truncation is GRIC's robust rho, so an outlier frame costs the same under every model.

BIC alone charged every per-frame parameter ln(n) (4.8 at 20 frames of three points): a fixed
axis with 18 angles more than a uniform rotation had to lower chi2 by 86, and scenes whose
angles stray 5-10 degrees from uniform were read as uniform rotations (``bench.persp_auto``).

``motion_scores``: every candidate's BIC, robust chi2 and k (null and the reason when it could
not be fitted) and every nested test (statistic, df, p).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.stats import chi2 as chi2_dist

from curverecon.errors import CurveReconError
from curverecon.model.configuration import RigidObservations, min_frames
from curverecon.model.reconstruction import Reconstruction
from curverecon.options import ReconstructOptions

NESTS_IN = {
    "rotation-free": ("uniform-rotation", "fixed-axis", "free"),
    "uniform-rotation": ("fixed-axis", "free"),
    "fixed-axis": ("free",),
    "force-field": ("free",),
}
"""Every model and the models it is a special case of (see the module docstring)."""

LEVEL = 0.01
"""A simpler model is rejected for a model it nests in when the likelihood ratio's tail
probability is below this (a true simpler model is lost in about one test in a hundred).
Chosen on ``python -m bench.persp_auto --detail`` (seed 0): the fixed-axis scenes (A, B, C)
nearest a uniform rotation have p 9e-3 and 1.3e-3 for it, read as uniform at 5e-3 and 1e-3.
Its cost, seen on 300 scenes: an orthographic uniform rotation (bench.configurations seed
2026, scene 13; p 6.7e-4) and a perspective rotation-free scene (seed 1, scene 9; p 9.9e-3)
read as the larger model."""

CRITERION = "likelihood-ratio tests where nested, BIC between the rest"


@dataclass
class Candidate:
    """One fitted motion model as ``auto`` scores it.

    Attributes:
        frame_chi2: (N,) every frame's chi2 at the fit (inf for a frame the model has no fit
            of, the paper's outlier frames).
        threshold: T, the outlier test's chi2 threshold for one frame of this model.
        k: free parameters (global and per frame).
        n_local: free parameters of one frame.
        n_measurements: measurements in all frames.
        make: the model's Reconstruction (built only for the chosen model).
        state: the fit's state over every frame (rigid rows), a start for a model it nests in.
    """

    frame_chi2: np.ndarray
    threshold: float
    k: int
    n_local: int
    n_measurements: int
    make: Callable[[], Reconstruction]
    state: object = None

    @property
    def robust_chi2(self) -> float:
        """sum_f min(chi2_f, T)."""
        return float(np.sum(np.minimum(self.frame_chi2, self.threshold)))

    @property
    def bic(self) -> float:
        """sum_f min(chi2_f, T) + k ln(n)."""
        return self.robust_chi2 + self.k * math.log(self.n_measurements)


def candidates(n_points: int, tangents: bool, projection: str = "orthographic") -> list[str]:
    """The motion models ``auto`` fits for these points (see the module docstring); under a
    pinhole or a stereo pair also rotation-free, and only the models the points determine."""
    if projection != "orthographic":
        from curverecon.model.configuration import motion_determined

        models = ["rotation-free", "uniform-rotation", "fixed-axis", "force-field", "free"]
        return [m for m in models if motion_determined(m, n_points, tangents, projection) is None]
    out = ["uniform-rotation", "fixed-axis", "force-field"]
    if n_points >= 3 or tangents:
        out.append("free")
    return out


def robust_bic(frame_chi2: np.ndarray, threshold: float, k: int, n_meas: int) -> float:
    """sum min(chi2_f, threshold) + k ln(n_meas)."""
    return float(np.sum(np.minimum(frame_chi2, threshold)) + k * math.log(n_meas))


def likelihood_ratio(simple: Candidate, complex_: Candidate) -> tuple[float, int]:
    """(D, df) of a nested pair (module docstring, step 1): both truncated at the simpler
    model's threshold (the larger: its frames have more degrees of freedom)."""
    t = simple.threshold
    both_out = (simple.frame_chi2 >= t) & (complex_.frame_chi2 >= t)
    stat = np.sum(np.minimum(simple.frame_chi2, t) - np.minimum(complex_.frame_chi2, t))
    df = complex_.k - simple.k - (complex_.n_local - simple.n_local) * int(np.sum(both_out))
    return float(stat), max(int(df), 1)


def choose(cands: dict[str, Candidate], level: float = LEVEL) -> tuple[str, list[dict]]:
    """(the chosen motion, every nested test as a dict) among fitted candidates (module
    docstring, steps 1-3)."""
    tests, rejected = [], set()
    for simple, supers in NESTS_IN.items():
        for complex_ in supers:
            if simple not in cands or complex_ not in cands:
                continue
            stat, df = likelihood_ratio(cands[simple], cands[complex_])
            p = float(chi2_dist.sf(stat, df))
            tests.append(
                {"simple": simple, "complex": complex_, "statistic": stat, "df": df, "p": p}
            )
            if p < level:
                rejected.add(simple)
    kept = [m for m in cands if m not in rejected] or list(cands)
    dominated = {c for s in kept for c in NESTS_IN.get(s, ())}
    left = [m for m in kept if m not in dominated] or kept
    return min(left, key=lambda m: cands[m].bic), tests


def _fitted(obs: RigidObservations, layout, fit, inliers, options) -> Candidate:
    """The Candidate of a rigid row's fit (every frame's chi2 at its state over every frame)."""
    from curverecon.rigid import answer, rigid_data
    from curverecon.rigid.estimate import frame_dof
    from curverecon.rigid.measurements import fixed_globals, fixed_locals
    from curverecon.rigid.refinement import refine

    data = rigid_data(obs, options)
    state = fit.full_state or fit.state
    full = refine(layout, state, data, max_iter=0, covariance=False)
    n = data.n_frames
    fixed = np.count_nonzero(fixed_locals(layout, n)) + np.count_nonzero(fixed_globals(layout))
    return Candidate(
        frame_chi2=np.asarray(full.frame_chi2, float),
        threshold=float(chi2_dist.isf(options.outliers.false_alarm, frame_dof(layout))),
        k=int(layout.n_global + n * layout.n_local - fixed),
        n_local=layout.n_local,
        n_measurements=n * layout.n_measurements,
        make=lambda: answer(obs, layout, fit, inliers, options),
        state=state,
    )


def _score_rigid(obs: RigidObservations, motion: str, options: ReconstructOptions) -> Candidate:
    from curverecon.rigid import fit_motion

    layout, fit, inliers = fit_motion(obs, motion, options)
    return _fitted(obs, layout, fit, inliers, options)


def _score_paper(obs: RigidObservations, motion: str, options: ReconstructOptions) -> Candidate:
    """Free motion of A and B with tangents: the paper's pipeline, scored alike (4 shape
    parameters, 5 per frame, one degree of freedom per frame)."""
    from curverecon.model.observations import Observations
    from curverecon.pipeline import reconstruct

    paper = Observations(obs.points[:, 0], obs.points[:, 1], obs.tangents[:, 0], obs.tangents[:, 1])
    rec = reconstruct(paper, options=options)
    n = obs.n_frames
    return Candidate(
        frame_chi2=np.where(rec.inliers, rec.frame_chi2, np.inf),
        threshold=float(chi2_dist.isf(options.outliers.false_alarm, 1)),
        k=4 + 5 * n,
        n_local=5,
        n_measurements=6 * n,
        make=lambda: rec,
    )


def fixed_axis_from_uniform(
    obs: RigidObservations, uniform: Candidate, options: ReconstructOptions
) -> Candidate:
    """The fixed axis fitted from a uniform rotation's optimum (angles w (t_f - t_0)): the
    axis rows' polish, the outlier test and the refusals of ``rigid.estimate``.  Raises
    CurveReconError when the fit is degenerate."""
    from curverecon.rigid import rigid_data
    from curverecon.rigid.estimate import axis_polish, check_degenerate, frame_dof, outlier_frames
    from curverecon.rigid.model import Layout

    cfg = obs.configuration
    layout = Layout("fixed-axis", tuple(cfg.points), bool(cfg.tangents), cfg.projection)
    data = rigid_data(obs, options)
    start = uniform.state.copy()
    start.angles = start.rate * (data.times - data.times[0])
    start.rate = None
    threshold = float(chi2_dist.isf(options.outliers.false_alarm, frame_dof(layout)))
    got = axis_polish(layout, data, start, threshold)
    if got is None:
        raise CurveReconError("motion fixed-axis: no fit from the uniform rotation's optimum")
    need = min_frames("fixed-axis", obs.n_points, cfg.projection, bool(cfg.tangents))
    inliers, fit = outlier_frames(layout, data, got[0], need, options.outliers, got[1])
    check_degenerate(layout, fit, data.subset(np.flatnonzero(inliers)))
    return _fitted(obs, layout, fit, inliers, options)


def _nested_start(obs: RigidObservations, cands: dict, admitted: set, options) -> None:
    """The fixed axis from the uniform rotation's optimum (when the points and frames admit a
    fixed axis), kept when its robust chi2 is below the fixed axis's own search's or that
    search failed."""
    if "uniform-rotation" not in cands or "fixed-axis" not in admitted:
        return
    try:
        got = fixed_axis_from_uniform(
            obs.with_motion("fixed-axis"), cands["uniform-rotation"], options
        )
    except CurveReconError:
        return
    own = cands.get("fixed-axis")
    if own is None or got.robust_chi2 < own.robust_chi2:
        cands["fixed-axis"] = got


def _ordinary_camera(obs: RigidObservations, cands: dict, options: ReconstructOptions) -> None:
    """Free motion through the ordinary camera's curve bundle (module docstring) when the
    points alone do not determine it and every frame has a polyline: the saturated model on
    the points (every frame's chi2 0, k = the number of measurements)."""
    from curverecon.curve.pinhole import MIN_FRAMES

    cfg = obs.configuration
    if "free" in cands or cfg.projection != "perspective" or obs.curves is None:
        return
    if obs.n_points >= 4 or obs.n_frames < MIN_FRAMES or not cands:
        return
    n_meas = next(iter(cands.values())).n_measurements

    def make() -> Reconstruction:
        from curverecon.curve.pinhole import reconstruct_perspective_curve

        return reconstruct_perspective_curve(obs.with_motion("free"), options)

    cands["free"] = Candidate(
        frame_chi2=np.zeros(obs.n_frames),
        threshold=float("inf"),
        k=n_meas,
        n_local=n_meas // obs.n_frames,
        n_measurements=n_meas,
        make=make,
    )


def _admit(obs: RigidObservations, motion: str, options: ReconstructOptions) -> RigidObservations:
    """The observations under ``motion``; CurveReconError when the frames or the points
    cannot determine it."""
    cfg = obs.configuration
    need = min_frames(motion, obs.n_points, cfg.projection, cfg.tangents)
    if obs.n_frames < need:
        raise CurveReconError(f"needs at least {need} frames")
    cand = obs.with_motion(motion)
    cand.require_reconstructable(options.point_sigma, options.tangent_sigma_deg)
    return cand


def reconstruct_auto(obs: RigidObservations, options: ReconstructOptions) -> Reconstruction:
    """The chosen model's reconstruction with every candidate's score and every nested test."""
    cfg = obs.configuration
    scores: dict = {}
    cands: dict[str, Candidate] = {}
    admitted: set[str] = set()
    for motion in candidates(obs.n_points, cfg.tangents, cfg.projection):
        try:
            cand = _admit(obs, motion, options)
            admitted.add(motion)
            paper = motion == "free" and obs.n_points == 2 and cfg.projection == "orthographic"
            cands[motion] = (_score_paper if paper else _score_rigid)(cand, motion, options)
        except CurveReconError as exc:
            scores[motion] = {"bic": None, "reason": str(exc)}
    _nested_start(obs, cands, admitted, options)
    _ordinary_camera(obs, cands, options)
    if not cands:
        reasons = "; ".join(f"{m}: {s['reason']}" for m, s in scores.items())
        raise CurveReconError(f"motion auto: no model could be fitted ({reasons})")
    for motion, c in cands.items():
        scores[motion] = {"bic": c.bic, "robust_chi2": c.robust_chi2, "k": c.k}
    chosen, tests = choose(cands)
    rec = cands[chosen].make()
    rec.motion_scores = {"criterion": CRITERION, "chosen": chosen, "scores": scores}
    rec.motion_scores["tests"] = tests
    rec.configuration = {**cfg.to_json_dict(), "motion": chosen}
    return rec
