"""The reconstruction pipeline: start, maximum-likelihood refinement, outlier frames, answer.

``reconstruct(obs, method="auto")``: robust global start (``start.robust_start``; the
linearisation seeds it too when it is determined) -> ML refinement over all frames -> outlier test
(studentised per-frame chi2, chi2 / (1 - leverage); when the fit's chi2 is implausible, trimmed
refits first, ``_trimmed_inliers``; then the worst frame above the threshold is dropped and the
fit redone until none is left) -> with few frames, single frames tried on their other branch of
(10) with a joint refit (``_flip_ambiguous_frames``: nearby local minima with tau near 0 or phi
near 0 or 180 degrees; pairs and triples of frames on nearly noise-free data; nothing once the
fit is exact)
-> every other shape that fits about equally well by chi2 ("alternatives", e.g. with 4-5
frames; the other candidates of the search, refined in one batch) -> with
``estimator="marginal"`` (the default) each of those fits taken to the optimum of the marginal
likelihood (every frame's pose integrated out, ``curverecon.refine.marginal``) and the highest optimum
kept, which removes most of the maximum likelihood's bias at realistic noise -> normalised
answer (alpha, beta in [0, 90] deg, phi in [0, 180] deg, tau in (-90, 90] deg), the shape's
standard deviations from the covariance, and the alternatives.

``method="linear"``: the paper's linearisation alone (``linear.solve_linear``), poses from the
shape (``pose.poses_from_shape``), no refinement.

Library units: lengths in input units, angles in radians; files use degrees.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.stats import chi2 as chi2_dist

from curverecon.errors import CurveReconError
from curverecon.generated import measurement_model
from curverecon.model.observations import Observations, wrap_line_angle
from curverecon.model.pose import normalise, rotations, translations
from curverecon.refine.marginal import KAPPA_MIN, refine_marginal
from curverecon.refine.ml import (
    RefineResult,
    frame_leverages,
    optimise_poses,
    refine,
    refine_batch,
    standardised_residuals,
)
from curverecon.robust.search import (
    EXACT_COST,
    NEAR_EXACT_CHI2,
    branch_alternatives,
    robust_start,
    shape_distance,
    switch_branches,
)
from curverecon.solvers.pose import poses_from_shape

OUTLIER_P = 2e-4
"""False-alarm probability per frame of the outlier test (chi2 with one degree of freedom)."""

MIXTURE_DCHI2 = 40.0
"""A frame's other branch joins the marginal likelihood's mixture if its chi2 is within this
many noise scales (kappa, the chi2 per degree of freedom) of the frame's fit."""

ALTERNATIVE_DCHI2 = 4.0
"""Shapes whose chi2 is within this of the best count as fitting equally well."""

LINEAR_SEED_GAP = 1e-3
"""The linearisation seeds the search only if its two smallest singular values differ this much."""

BRANCH_DCHI2 = 4.0
"""A frame whose other branch of (10) fits within this chi2 of its pose is reported ambiguous."""

FLIP_DCHI2 = 4.0
"""Frames whose other branch fits within this chi2 (shape fixed) are tried on it (joint refit)."""

FLIP_MAX_FRAMES = 12
"""... only with at most this many inlier frames (with more, the others pin the shape and the
per-frame branch switching of the search suffices; the joint refits would cost time)."""

FLIP_COMBO_MAX = 64
"""Nearly noise-free fits (``start.NEAR_EXACT_CHI2``): at most this many pairs and triples of
frames switched together (``_flip_ambiguous_frames``, one batched refinement)."""

METHODS = ("auto", "linear")

ESTIMATORS = ("marginal", "ml")
"""Final shape estimate of ``method="auto"``: the marginal likelihood (poses integrated out,
``marginal.refine_marginal``; the default) or plain maximum likelihood (``refine.refine``)."""

CAUCHY_K = 4.0
"""Scale (in standard deviations, per frame) of the robust reweighting before the outlier test."""

TRIM_STEPS = 2
"""Concentration steps of ``_trimmed_inliers``."""

LEVERAGE_FLOOR = 0.05
"""Least 1 - leverage used by ``_studentised`` (a frame that alone fixes a shape direction)."""

MEDIAN_CHI2_1 = 0.4549364231195724
"""Median of chi2 with one degree of freedom."""


@dataclass
class Alternative:
    """Another shape that fits the data about as well as the answer."""

    shape: np.ndarray
    poses: np.ndarray
    chi2: float
    std: np.ndarray | None = None


@dataclass
class Reconstruction:
    """The answer.

    Attributes:
        shape: (4,) c (input units), alpha, beta, phi (radians), normalised.
        poses: (N, 5) delta, tau, theta, tx, ty per frame (radians, input units).
        std: (4,) standard deviations of c, alpha, beta, phi from the covariance, or None.
        inliers: (N,) False for frames found not to fit (excluded from the shape estimate).
        alternatives: other shapes fitting equally well (best first).
        warnings: human-readable warnings (also printed by the command line).
        method: "auto" or "linear".
        chi2: sum of squared standardised residuals over the inlier frames (None for linear).
        frame_chi2: (N,) per-frame chi2 (None for linear).
        branch_alternatives: (N, 5) per frame the best pose on another branch of (10) (other
            sign of tau or another delta) for the same shape, or None.
        branch_alternative_chi2: (N,) its chi2 (inf if none).  Frames where it is within
            ``BRANCH_DCHI2`` of ``frame_chi2`` are ambiguous from the end points and tangents
            alone (``ambiguous_frames``); a curve reconstruction may tell them apart.
        estimator: "marginal" or "ml", the estimate the shape is (None for linear); "ml" also
            where the marginal step does not apply (noise-free data, fewer than 5 frames).
    """

    shape: np.ndarray
    poses: np.ndarray
    std: np.ndarray | None
    inliers: np.ndarray
    alternatives: list[Alternative] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    method: str = "auto"
    chi2: float | None = None
    frame_chi2: np.ndarray | None = None
    branch_alternatives: np.ndarray | None = None
    branch_alternative_chi2: np.ndarray | None = None
    estimator: str | None = None

    @property
    def c(self) -> float:
        return float(self.shape[0])

    @property
    def alpha(self) -> float:
        return float(self.shape[1])

    @property
    def beta(self) -> float:
        return float(self.shape[2])

    @property
    def phi(self) -> float:
        return float(self.shape[3])

    def rotations(self) -> np.ndarray:
        """(N, 3, 3) curve-to-camera rotations R_z(theta) R_y(tau) R_x(delta)."""
        return rotations(self.poses)

    def translations(self) -> np.ndarray:
        """(N, 3) translations (tx, ty, 0): A at z = 0."""
        return translations(self.poses)

    def points_3d(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(A3, B3, tangent_A3, tangent_B3), each (N, 3), camera coordinates, A at z = 0."""
        out = measurement_model.points_3d(*self.shape, *self.poses.T)
        return tuple(np.asarray(v, float) for v in out)

    def ambiguous_frames(self) -> list[int]:
        """Frames whose pose another branch of (10) fits about as well (see the attributes)."""
        if self.branch_alternative_chi2 is None or self.frame_chi2 is None:
            return []
        amb = self.branch_alternative_chi2 - self.frame_chi2 < BRANCH_DCHI2
        return [int(i) for i in np.flatnonzero(amb)]

    def outlier_frames(self) -> list[int]:
        return [int(i) for i in np.flatnonzero(~self.inliers)]

    def to_json_dict(self) -> dict:
        """The ``curverecon.reconstruction/1`` document (degrees; extra keys beyond the contract:
        per-frame theta_deg, tx, ty, inlier, chi2; top-level method, std, chi2, outlier_frames,
        alternatives, warnings)."""
        a3, b3, ta3, tb3 = self.points_3d()
        frames = []
        for i in range(len(self.poses)):
            d, t, th, tx, ty = self.poses[i]
            frame = {
                "delta_deg": math.degrees(d),
                "tau_deg": math.degrees(t),
                "A3": a3[i].tolist(),
                "B3": b3[i].tolist(),
                "tangent_A3": ta3[i].tolist(),
                "tangent_B3": tb3[i].tolist(),
                "theta_deg": math.degrees(th),
                "inlier": bool(self.inliers[i]),
            }
            if self.frame_chi2 is not None:
                frame["chi2"] = float(self.frame_chi2[i])
            if self.branch_alternatives is not None:
                ad, at = self.branch_alternatives[i, :2]
                frame["branch_alternative"] = {
                    "delta_deg": math.degrees(ad),
                    "tau_deg": math.degrees(at),
                    "chi2": float(self.branch_alternative_chi2[i]),
                }
            frames.append(frame)
        out = {"format": "curverecon.reconstruction/1", **_shape_dict(self.shape)}
        out["frames"] = frames
        out["method"] = self.method
        out["estimator"] = self.estimator
        out["std"] = None if self.std is None else _shape_dict(self.std)
        out["chi2"] = self.chi2
        out["outlier_frames"] = self.outlier_frames()
        out["ambiguous_frames"] = self.ambiguous_frames()
        out["alternatives"] = [
            {
                **_shape_dict(alt.shape),
                "chi2": alt.chi2,
                "std": None if alt.std is None else _shape_dict(alt.std),
            }
            for alt in self.alternatives
        ]
        out["warnings"] = list(self.warnings)
        return out


def _alternatives_warning(
    shape: np.ndarray, std: np.ndarray | None, alternatives: list[Alternative]
) -> str:
    """One line saying how many shapes fit about equally well and whether they really differ.

    Alternatives within two standard deviations (of the best fit's covariance) in every parameter
    are local optima of the same answer; farther ones mean the frames do not determine the shape.
    """
    n = len(alternatives) + 1
    if std is not None and all(
        np.all(np.abs(alt.shape - shape) <= 2.0 * std) for alt in alternatives
    ):
        return (
            f"{n} local optima fit the data about equally well but agree within two standard "
            "deviations; the best is returned, the others are listed in alternatives"
        )
    return (
        f"{n} distinct shapes fit the data about equally well (these frames do not determine the "
        "shape uniquely; more frames or more varied motion would); the best is returned, the "
        "others are listed in alternatives"
    )


def _shape_dict(shape: np.ndarray) -> dict:
    c, a, b, p = (float(v) for v in shape)
    return {
        "c": c,
        "alpha_deg": math.degrees(a),
        "beta_deg": math.degrees(b),
        "phi_deg": math.degrees(p),
    }


def reconstruct(
    obs: Observations,
    method: str = "auto",
    point_sigma: float = 1.0,
    tangent_sigma_deg: float = 1.0,
    estimator: str = "marginal",
) -> Reconstruction:
    """Recover c, alpha, beta, phi and every frame's pose.

    Args:
        obs: observations (at least 4 frames, not all related by in-plane similarity).
        method: "auto" (robust start, ML refinement, outlier test) or "linear" (the paper's
            linearisation alone; needs ``linear.min_frames()`` frames).
        point_sigma: standard deviation of the image point coordinates (input units).
        tangent_sigma_deg: standard deviation of the tangent directions (degrees).
        estimator: "marginal" (default): after the maximum-likelihood fit, the shape that
            maximises the likelihood with every frame's pose integrated out (less biased: the
            ML chord c comes out long at realistic noise, see ``curverecon.refine.marginal``); "ml":
            the maximum-likelihood fit itself.  Noise-free data and 4 frames give the same
            answer either way.
    Raises:
        CurveReconError: bad input, too few frames, degenerate motion.
    """
    if method not in METHODS:
        raise CurveReconError(f'unknown method "{method}" (choose {" or ".join(METHODS)})')
    if estimator not in ESTIMATORS:
        raise CurveReconError(f'unknown estimator "{estimator}" (choose {" or ".join(ESTIMATORS)})')
    if not (point_sigma > 0 and tangent_sigma_deg > 0):
        raise CurveReconError("point and tangent standard deviations must be positive")
    obs.require_reconstructable()
    if method == "linear":
        return _reconstruct_linear(obs)
    return _reconstruct_auto(
        obs, float(point_sigma), math.radians(tangent_sigma_deg), estimator == "marginal"
    )


def _reconstruct_linear(obs: Observations) -> Reconstruction:
    from curverecon.solvers.linear import solve_linear

    lin = solve_linear(obs)
    poses, _ = poses_from_shape(obs, lin.shape)
    shape, poses = normalise(lin.shape, poses)
    warnings = []
    if lin.fit_residual > 1e-6:
        warnings.append(
            f"the linearisation's null vector fits the shape only to {lin.fit_residual:.1e} "
            "(noisy data: the linear method is not reliable; use --method auto)"
        )
    return Reconstruction(
        shape, poses, None, np.ones(obs.n_frames, bool), [], warnings, "linear", None, None
    )


def _linear_seed(obs: Observations) -> list[np.ndarray]:
    """The linearisation's shape as an extra start, when it is determined (enough frames)."""
    try:
        from curverecon.solvers.linear import frame_matrix, min_frames, solve_linear

        if obs.n_frames < max(min_frames(), 45):
            return []
        # only when the null space is clearly one-dimensional (near noise-free data): at
        # realistic noise the linearisation is unusable (NOTES item 5) and costs time
        m, _ = frame_matrix(obs)
        with np.errstate(all="ignore"):
            sv = np.linalg.svd(m / np.linalg.norm(m, axis=0), compute_uv=False)
        if not (np.all(np.isfinite(sv)) and sv[-1] < LINEAR_SEED_GAP * sv[-2]):
            return []
        lin = solve_linear(obs)
    except (ImportError, CurveReconError, ValueError, np.linalg.LinAlgError):
        return []
    return [lin.shape] if np.all(np.isfinite(lin.shape)) else []


def _trimmed_inliers(
    obs: Observations, fit: RefineResult, ps: float, ts: float, w8: np.ndarray, max_out: int
) -> tuple[np.ndarray, RefineResult]:
    """Outlier frames by trimmed refits (least trimmed squares' concentration steps).

    When the best fit's chi2 is implausible, outlier frames have pulled the shape, every frame's
    misfit has grown, and the median-scaled threshold hides them (masking).  So: refit the shape
    on all but the ``max_out`` frames of largest studentised chi2; test every frame against that
    fit, the left-out ones by their deleted residual (their pose fitted to the trimmed shape,
    chi2 / (1 + h), h = tr(S_kept^-1 S_i)) and the others by chi2 / (1 - l); flag those above
    the threshold; repeat from the new shape (``TRIM_STEPS``).  Returns the inliers (at least
    N - ``max_out``) and the fit on them; all frames and ``fit`` itself when none is flagged.
    """
    n = obs.n_frames
    meas = obs.measurements()
    shape, poses = fit.shape, np.array(fit.poses)
    flagged = np.zeros(n, bool)
    base = float(chi2_dist.isf(OUTLIER_P, 1))
    for step in range(TRIM_STEPS):
        st = _studentised(obs, refine(obs, shape, poses, ps, ts, max_iter=0, covariance=False), w8)
        keep = np.zeros(n, bool)
        keep[np.argsort(st, kind="stable")[: n - max_out]] = True
        tf = refine(obs.subset(keep), shape, poses[keep], ps, ts, covariance=False)
        if step == 0:  # the kept frames searched again: the outliers may have moved the basin
            try:
                cands = robust_start(obs.subset(keep), ps, ts)
            except CurveReconError:  # e.g. the kept frames alone are degenerate: keep tf
                cands = []
            if cands and cands[0].result.chi2 < tf.chi2:
                tf = cands[0].result
        poses[keep] = tf.poses
        poses = switch_branches(obs, tf.shape, poses, w8)
        poses[keep] = tf.poses
        r = standardised_residuals(tf.shape, poses, meas, w8)
        chi2 = np.sum(r * r, axis=1)
        lev = frame_leverages(tf.shape, poses, meas, w8, among=keep)
        t2 = np.where(keep, chi2 / np.maximum(1.0 - lev, LEVERAGE_FLOOR), chi2 / (1.0 + lev))
        scale = max(1.0, float(np.median(t2)) / MEDIAN_CHI2_1)
        over = t2 > base * scale
        worst = np.argsort(-t2, kind="stable")[:max_out]
        flagged = np.zeros(n, bool)
        flagged[worst[over[worst]]] = True
        shape = tf.shape
    if not flagged.any():  # nothing found: the fit stays as it was
        return np.ones(n, bool), fit
    inl = ~flagged
    return inl, refine(obs.subset(inl), shape, poses[inl], ps, ts, covariance=False)


def _studentised(obs: Observations, fit: RefineResult, w8: np.ndarray) -> np.ndarray:
    """(N,) per-frame chi2 / (1 - leverage) (``refine.frame_leverages``): what the outlier test
    compares with its threshold, so that a frame that pins the shape cannot hide its misfit."""
    lev = frame_leverages(fit.shape, fit.poses, obs.measurements(), w8)
    return fit.frame_chi2 / np.maximum(1.0 - lev, LEVERAGE_FLOOR)


def _threshold(frame_chi2: np.ndarray) -> float:
    """Per-frame chi2 threshold: chi2(1) quantile, scaled up if the noise looks larger."""
    base = float(chi2_dist.isf(OUTLIER_P, 1))
    scale = max(1.0, float(np.median(frame_chi2)) / MEDIAN_CHI2_1)
    return base * scale


def _flip_ambiguous_frames(
    obs: Observations, fit: RefineResult, ps: float, ts: float, w8: np.ndarray, rounds: int = 2
) -> RefineResult:
    """Refit with single frames moved to their other branch of (10) where that lowers chi2.

    A frame whose other branch (other sign of tau / other delta) fits about as well for the
    current shape (within ``FLIP_DCHI2``) can hold the joint fit in a nearby local minimum: e.g.
    a frame with c' close to c (tau near 0), or phi near 0 or 180 degrees where a single frame's
    mirror image fits almost as well.  Each such frame is switched in turn (one batched
    refinement, one start per frame) and the best refit is kept if it lowers chi2.

    Nearly noise-free data (chi2 below ``start.NEAR_EXACT_CHI2`` per degree of freedom, not exact):
    when no single switch helps, pairs and triples of those frames are switched together (at
    most ``FLIP_COMBO_MAX`` starts, one batch): several frames near tau = 0 can sit on their
    other branch at once, a local minimum a hair above the exact fit.  Skipped once the fit is
    exact (``start.EXACT_COST``: no refit can beat it by the required margin).
    """
    dof = max(obs.n_frames - 4, 1)
    for _ in range(rounds):
        if fit.chi2 <= EXACT_COST:  # an exact fit: no refit can lower chi2 by the margin below
            return fit
        alt, alt_chi2 = branch_alternatives(obs, fit.shape, fit.poses, w8)
        frames = np.flatnonzero(alt_chi2 - fit.frame_chi2 < FLIP_DCHI2)
        if frames.size == 0:
            return fit
        combos = [(int(i),) for i in frames]
        g, p, chi2 = _refit_switched(obs, fit, alt, combos, ps, ts)
        k = int(np.argmin(chi2))
        if not chi2[k] < fit.chi2 - 1e-9 * (1.0 + fit.chi2) and fit.chi2 < NEAR_EXACT_CHI2 * dof:
            combos = [c for m in (2, 3) for c in itertools.combinations(frames.tolist(), m)][
                :FLIP_COMBO_MAX
            ]
            if combos:
                g, p, chi2 = _refit_switched(obs, fit, alt, combos, ps, ts)
                k = int(np.argmin(chi2))
        if not chi2[k] < fit.chi2 - 1e-9 * (1.0 + fit.chi2):
            return fit
        fit = refine(obs, g[k], p[k], ps, ts, covariance=True)
    return fit


def _refit_switched(
    obs: Observations,
    fit: RefineResult,
    alt: np.ndarray,
    combos: list[tuple[int, ...]],
    ps: float,
    ts: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Joint refits (one batch) with the frames of each combination on their other branch."""
    poses = np.repeat(fit.poses[None], len(combos), axis=0)
    for j, c in enumerate(combos):
        poses[j, list(c)] = alt[list(c)]
    shapes = np.repeat(fit.shape[None], len(combos), axis=0)
    g, p, _, chi2, _, _ = refine_batch(obs, shapes, poses, ps, ts, max_iter=60)
    return g, p, chi2


def _second_branches(
    obs: Observations, fit: RefineResult, w8: np.ndarray, kappa: float
) -> np.ndarray:
    """(N, 5) each frame's pose on its other branch of (10) for the fit's shape, the second
    component of the marginal likelihood's mixture (``marginal.refine_marginal``), or NaN
    where there is none or it fits worse by more than ``MIXTURE_DCHI2`` noise scales (its
    weight would be below exp(-20))."""
    alt, alt_chi2 = branch_alternatives(obs, fit.shape, fit.poses, w8)
    keep = np.isfinite(alt_chi2) & (alt_chi2 - fit.frame_chi2 < MIXTURE_DCHI2 * kappa)
    return np.where(keep[:, None], alt, np.nan)


def _reconstruct_auto(
    obs: Observations, ps: float, ts: float, marginal: bool = True
) -> Reconstruction:
    n = obs.n_frames
    cands = robust_start(obs, ps, ts, extra_shapes=_linear_seed(obs))
    if not cands:
        raise CurveReconError("no shape fits the data (the search found no candidate)")
    best = cands[0].result
    warnings: list[str] = []

    # Robust fit (frame-level Cauchy reweighting) so that outlier frames stand out; with an
    # implausible chi2, trimmed refits; then the outlier test on the unweighted, studentised
    # per-frame chi2: drop the worst frame above the threshold, refit, repeat.
    fit = best
    w8 = np.array([1 / ps] * 4 + [1 / ts] * 2)
    st = _studentised(obs, fit, w8)
    robust_rounds = 3 if np.max(st) > _threshold(st) else 0
    for _ in range(robust_rounds):
        scale2 = CAUCHY_K**2 * max(1.0, float(np.median(st)) / MEDIAN_CHI2_1)
        weights = 1.0 / (1.0 + st / scale2)
        poses_sw = switch_branches(obs, fit.shape, fit.poses, w8, rescue=True)
        fit = refine(obs, fit.shape, poses_sw, ps, ts, covariance=False, frame_weights=weights)
        st = _studentised(obs, fit, w8)
    inliers = np.ones(n, dtype=bool)
    max_out = max(0, (n - 5) // 2)
    dof = max(n - 4, 1)
    if max_out > 0 and best.chi2 > dof + 5.0 * math.sqrt(2.0 * dof) + 10.0:
        inliers, fit = _trimmed_inliers(obs, fit, ps, ts, w8, max_out)
    rescued = 0
    while True:
        idx = np.flatnonzero(inliers)
        st = _studentised(obs.subset(inliers), fit, w8)
        j = int(np.argmax(st))
        thr = _threshold(st)
        if st[j] <= thr or (~inliers).sum() >= max_out:
            break
        # a frame on a wrong pose (a minimum of its own that no branch of (10) led out of)
        # is not an outlier: its pose re-solved from a grid of starts first, and kept if
        # that brings it under the threshold (``start.switch_branches(..., rescue=True)``)
        one = obs.subset(np.array([idx[j]]))
        pj = switch_branches(one, fit.shape, fit.poses[j : j + 1], w8, rescue=True)
        if rescued < n and not np.array_equal(pj, fit.poses[j : j + 1]):
            rj = standardised_residuals(fit.shape, pj, one.measurements(), w8)
            chi2_j = float(np.sum(rj * rj))
            if chi2_j < fit.frame_chi2[j] and chi2_j <= thr:
                poses = np.array(fit.poses)
                poses[j] = pj[0]
                fit = refine(obs.subset(inliers), fit.shape, poses, ps, ts, covariance=False)
                rescued += 1
                continue
        inliers[idx[j]] = False
        keep = np.arange(idx.size) != j
        fit = refine(obs.subset(inliers), fit.shape, fit.poses[keep], ps, ts, covariance=False)
    final = refine(obs.subset(inliers), fit.shape, fit.poses, ps, ts, covariance=True)
    if inliers.sum() <= FLIP_MAX_FRAMES:
        final = _flip_ambiguous_frames(obs.subset(inliers), final, ps, ts, w8)
    if not final.converged:
        warnings.append(
            "the maximum-likelihood refinement stopped at its iteration limit (slow creep along "
            "c; the answer is near, not exactly at, the optimum)"
        )
    # Alternatives: other refined candidates that fit the inlier frames about as well as the
    # ML fit (all refined in one batch; the covariance only for those kept).
    sub = obs.subset(inliers)
    ml_chi2 = final.chi2
    fits = [(normalise(final.shape, final.poses)[0], final)]  # (normalised shape, fit)
    pending = [
        cand.result
        for cand in cands[1:]
        if cand.robust_cost - cands[0].robust_cost <= 4 * ALTERNATIVE_DCHI2
        and shape_distance(cand.result.shape, fits[0][0]) >= 0.02
    ]
    if pending:
        g_alt, p_alt, _, _, _, _ = refine_batch(
            sub,
            np.array([r.shape for r in pending]),
            np.array([r.poses[inliers] for r in pending]),
            ps,
            ts,
        )
    for k, r in enumerate(pending):
        if any(shape_distance(r.shape, f[0]) < 0.02 for f in fits):
            continue
        alt = refine(sub, g_alt[k], p_alt[k], ps, ts, max_iter=0, covariance=True)
        if alt.chi2 - ml_chi2 > ALTERNATIVE_DCHI2:
            continue
        alt_shape = normalise(alt.shape, alt.poses)[0]
        if any(shape_distance(alt_shape, f[0]) < 0.02 for f in fits):
            continue
        fits.append((alt_shape, alt))

    # The answer.  Maximum likelihood: the best fit.  Marginal: every fit that is about as
    # good by chi2 is taken to its basin's marginal optimum (one noise scale for all), and the
    # highest of those optima is the answer.  (At 1 px, 1 deg and 20 frames the lowest chi2 is
    # sometimes a spurious basin, c off by 10-30 standard deviations, while F prefers the basin
    # of the truth by 20-80; see curverecon.refine.marginal.  Comparing F at the optima rather than
    # at the fits' ML points matters where the ML points sit on either side of a fold: F at
    # the ML point of the truth's basin was 2 higher on one headline scene, its optimum 2
    # lower.  On the bench's 200 headline scenes: alpha's RMSE/CRLB 1.26 -> 1.09, phi's 1.25
    # -> 1.23, with 3 answers changed, at the same time per scene: ``python -m bench.headline``.
    # Each frame whose other branch of (10) fits about as well enters F as a mixture of both,
    # ``_second_branches``: phi's 1.23 -> 1.12, see curverecon.refine.marginal.)
    estimator = "ml"
    chosen = 0
    if marginal:
        meas_in = sub.measurements()
        kappa = ml_chi2 / max(sub.n_frames - 4, 1)
        mixture = sub.n_frames >= 5 and kappa >= KAPPA_MIN  # where the marginal step applies
        mgs = [
            refine_marginal(
                meas_in,
                f.shape,
                f.poses,
                ps,
                ts,
                ml_chi2,
                _second_branches(sub, f, w8, kappa) if mixture else None,
            )
            for _, f in fits
        ]
        if all(m is not None for m in mgs):
            chosen = int(np.argmin([m.value for m in mgs]))
        r0 = fits[chosen][1]
        mg = mgs[chosen]
        if mg is not None:
            # every frame on its best branch of (10) for the answer's shape (the mixture put it
            # on its branch of the larger weight, which can differ where the two fit alike)
            mg.poses = switch_branches(sub, mg.shape, mg.poses, w8)
            final = refine(sub, mg.shape, mg.poses, ps, ts, max_iter=0, covariance=True)
            estimator = "marginal"
        else:
            final = r0

    # Poses of outlier frames: best pose for the final shape (shape held fixed).
    poses = np.array(poses_from_shape(obs, final.shape)[0])
    poses[inliers] = final.poses
    meas = obs.measurements()
    poses, resid = optimise_poses(final.shape, poses, meas, w8, 10)
    frame_chi2 = np.sum(resid * resid, axis=1)
    frame_chi2[inliers] = final.frame_chi2
    shape, poses = normalise(final.shape, poses)
    alt_poses, alt_chi2 = branch_alternatives(obs, shape, poses, w8)
    std = final.std
    if std is None or not np.all(np.isfinite(std)):
        std = None
        warnings.append("the shape is not determined by these frames (singular information matrix)")
    elif std[0] > 0.5 * shape[0] or np.any(std[1:] > math.radians(30.0)):
        warnings.append(
            "the shape is poorly determined by these frames (standard deviation "
            f"c {std[0]:.3g}, angles {', '.join(f'{math.degrees(s):.1f}' for s in std[1:])} deg)"
        )
    outliers = np.flatnonzero(~inliers)
    if outliers.size:
        warnings.append(
            f"{outliers.size} frame(s) do not fit and were left out of the shape estimate: "
            + ", ".join(str(int(i)) for i in outliers)
        )
    alternatives: list[Alternative] = []
    for k, (alt_shape, alt) in enumerate(fits):
        if k == chosen:
            continue
        other_poses = np.array(poses_from_shape(obs, alt_shape)[0])
        other_poses[inliers] = normalise(alt.shape, alt.poses)[1]
        alternatives.append(Alternative(alt_shape, other_poses, alt.chi2, alt.std))
    if alternatives:
        warnings.append(_alternatives_warning(shape, std, alternatives))
    rec = Reconstruction(
        shape,
        poses,
        std,
        inliers,
        alternatives,
        warnings,
        "auto",
        final.chi2,
        frame_chi2,
        alt_poses,
        alt_chi2,
        estimator,
    )
    return rec


def angle_residuals_deg(rec: Reconstruction, obs: Observations) -> np.ndarray:
    """(N, 2) tangent-angle residuals of a reconstruction (degrees), for diagnostics."""
    pred = measurement_model.predict(*rec.shape, *rec.poses.T)
    return np.degrees(wrap_line_angle(pred[:, 4:6] - obs.measurements()[:, 4:6]))


CURVE_FLIP_DCHI2 = 4.0
"""Frames whose other branch of (10) fits within this chi2 of their pose are tried on it by the
curve (``resolve_branches_with_curves``); farther branches are excluded by the end points and
tangents alone."""

CURVE_FLIP_GAIN = 0.03
"""A branch switch is kept only if it lowers the total curve reprojection by this fraction."""

CURVE_FLIP_MAX_SWITCHES = 6
"""At most this many single-frame switches (greedy rounds) per reconstruction."""


def resolve_branches_with_curves(
    rec: Reconstruction, curves: list[np.ndarray], reconstruct_curve
) -> tuple[Reconstruction, object]:
    """Use the frames' polylines to choose the pose branch of ambiguous frames.

    The end points and tangents alone fit two branches of (10) about equally well in some frames
    (other branch within ``CURVE_FLIP_DCHI2``, ``Reconstruction.ambiguous_frames``).  The whole
    curve tells them apart: a frame on the wrong branch makes the recovered 3-D curve reproject
    badly onto the polylines.  Greedy search: in each round every ambiguous frame is tried on
    its other branch and the single switch that lowers the total reprojection distance (sum of
    ``frame_residual`` over the inlier frames) most is kept, if it lowers it by at least
    ``CURVE_FLIP_GAIN``; repeat until no switch helps.

    The total is used, not the switched frame's own residual, because the curve is built along
    frame 0's lines of sight: frame 0 always reprojects well, and when frame 0 itself is on the
    wrong branch it is the *other* frames that reproject badly (switching frame 0 repairs them).
    The curve stays in frame 0's camera coordinates (with frame 0's chosen pose).  The shape is
    kept.

    Args:
        rec: an "auto" reconstruction with branch alternatives.
        curves: the frames' polylines (A' to B').
        reconstruct_curve: ``curverecon.curve.section4.reconstruct_curve`` (its result has
            ``frame_residual``, the per-frame median reprojection distance).
    Returns:
        (reconstruction, curve result) - the input reconstruction if nothing changed.
    """
    res = reconstruct_curve(curves, rec.rotations(), rec.translations())
    fr = getattr(res, "frame_residual", None)
    if (
        fr is None
        or rec.branch_alternatives is None
        or rec.branch_alternative_chi2 is None
        or rec.frame_chi2 is None
    ):
        return rec, res
    dchi2 = rec.branch_alternative_chi2 - rec.frame_chi2
    cand = [int(i) for i in np.flatnonzero(np.isfinite(dchi2) & (dchi2 < CURVE_FLIP_DCHI2))]
    if not cand:
        return rec, res
    inl = np.asarray(rec.inliers, bool)

    def total(r) -> float:
        f = np.asarray(getattr(r, "frame_residual", None), float)
        return float(np.sum(f[inl])) if f.shape == inl.shape else np.inf

    search = _coarse(reconstruct_curve)
    switched = np.zeros(len(rec.poses), bool)
    best_total = (
        total(res) if search is reconstruct_curve else total(search(curves, *_rt(rec.poses)))
    )
    for _ in range(CURVE_FLIP_MAX_SWITCHES):
        round_best = None
        for i in cand:
            trial = switched.copy()
            trial[i] = ~trial[i]
            poses = np.where(trial[:, None], rec.branch_alternatives, rec.poses)
            t = total(search(curves, *_rt(poses)))
            if round_best is None or t < round_best[0]:
                round_best = (t, i)
        t, i = round_best
        if not t < (1.0 - CURVE_FLIP_GAIN) * best_total:
            break
        switched[i] = ~switched[i]
        best_total = t
    take = [int(i) for i in np.flatnonzero(switched)]
    if not take:
        return rec, res
    poses = np.array(rec.poses)
    poses[take] = rec.branch_alternatives[take]
    alt = np.array(rec.branch_alternatives)
    alt[take] = rec.poses[take]
    fchi2 = np.array(rec.frame_chi2)
    achi2 = np.array(rec.branch_alternative_chi2)
    fchi2[take], achi2[take] = rec.branch_alternative_chi2[take], rec.frame_chi2[take]
    warnings = list(rec.warnings) + [
        f"frames {take}: pose branch chosen by the curve (their end points and tangents fit "
        "two branches about equally well)"
    ]
    new = Reconstruction(
        rec.shape,
        poses,
        rec.std,
        rec.inliers,
        rec.alternatives,
        warnings,
        rec.method,
        rec.chi2,
        fchi2,
        alt,
        achi2,
    )
    return new, reconstruct_curve(curves, new.rotations(), new.translations())


CURVE_SEARCH_SAMPLES = 60
"""Curve samples per trial reconstruction during the branch search (the final curve uses the
default sampling)."""


def _rt(poses: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return rotations(poses), translations(poses)


def _coarse(reconstruct_curve):
    """A cheaper variant of ``reconstruct_curve`` for the branch search (fewer samples, no
    smoothing, fixed dummy end tangents so that the coplanarity check - irrelevant to
    ``frame_residual`` - does not estimate them from every polyline) when it accepts those
    keywords; otherwise the callable itself."""
    import functools
    import inspect

    try:
        params = inspect.signature(reconstruct_curve).parameters
    except (TypeError, ValueError):
        return reconstruct_curve
    if {"n_samples", "smooth", "tangents"} <= set(params):
        dummy = (np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]))
        return functools.partial(
            reconstruct_curve, n_samples=CURVE_SEARCH_SAMPLES, smooth=False, tangents=dummy
        )
    return reconstruct_curve


CURVE_REFIT_DCHI2 = 4.0
"""A joint refit with one frame started on its mirrored branch (other sign of tau) is a
candidate for ``refit_branches_with_curves`` if its chi2 is within this of the answer's."""

CURVE_REFIT_GAIN = 0.2
"""... and kept only if it lowers the total curve reprojection by this fraction (a larger margin
than ``CURVE_FLIP_GAIN``: the refit moves the maximum-likelihood answer itself, and small gains
in the curve's consistency did not mean a better curve in the seeded studies)."""

CURVE_REFIT_ROUNDS = 1
"""At most this many accepted refits (greedy rounds; a second round changed nothing in the
seeded studies and costs a batched refinement)."""


def refit_branches_with_curves(
    rec: Reconstruction,
    obs: Observations,
    reconstruct_curve,
    point_sigma: float = 1.0,
    tangent_sigma_deg: float = 1.0,
    curve=None,
) -> tuple[Reconstruction, object]:
    """Among about equally good maximum-likelihood optima, take the one the curve fits best.

    First the other shapes that fit about equally well (``rec.alternatives``; they usually
    differ from the answer in the pose branch of several frames at once): if one makes the
    recovered curve reproject much better (total ``frame_residual`` lower by
    ``CURVE_REFIT_GAIN``), it is refitted and becomes the answer (the old answer becomes an
    alternative).  Then joint refits with single frames started on the other sign of tau:

    ``resolve_branches_with_curves`` switches frames with the shape held fixed.  With noisy end
    points and tangents the maximum-likelihood fit can also have a nearby local optimum in which
    one frame (often frame 0, whose pose fixes the coordinates of ``curve3d``) has the other sign
    of tau and the shape and the other poses move a little: its chi2 is about as low, but with the
    shape held fixed that branch fits badly, so it is not among the branch alternatives.  Here
    every frame in turn is started on the other sign of tau (delta from (10) and (11) for the
    current shape) and the shape and all poses are refitted jointly (one batched refinement);
    refits whose chi2 is within ``CURVE_REFIT_DCHI2`` of the answer's are scored by the total
    curve reprojection distance (sum of ``frame_residual``), and the best is kept if it lowers
    that total by at least ``CURVE_REFIT_GAIN``.  Up to ``CURVE_REFIT_ROUNDS`` rounds.

    Only for "auto" reconstructions without outlier frames (otherwise returned unchanged).
    ``curve``: the curve result for ``rec`` if already computed (saves one reconstruction).

    Returns:
        (reconstruction, curve result) - the input reconstruction if nothing changed.
    """
    from curverecon.generated import frame_equations

    res = curve
    if res is None:
        res = reconstruct_curve(obs.curves, rec.rotations(), rec.translations())
    if rec.method != "auto" or rec.chi2 is None or not np.all(rec.inliers):
        return rec, res
    ps, ts = float(point_sigma), math.radians(tangent_sigma_deg)
    w8 = np.array([1 / ps] * 4 + [1 / ts] * 2)
    search = _coarse(reconstruct_curve)
    n = obs.n_frames

    def total(poses: np.ndarray) -> float:
        f = np.asarray(getattr(search(obs.curves, *_rt(poses)), "frame_residual", None), float)
        return float(np.sum(f)) if f.shape == (n,) else np.inf

    shape, poses = rec.shape, np.array(rec.poses)
    best_total = total(poses)
    fit = None
    alternatives = list(rec.alternatives)
    # The other shapes that fit about equally well (``rec.alternatives``, each with its own pose
    # branches in many frames at once - out of reach of single-frame switches): the curve picks.
    scored_alts = [(total(a.poses), j) for j, a in enumerate(alternatives)]
    if scored_alts and min(scored_alts)[0] < (1.0 - CURVE_REFIT_GAIN) * best_total:
        j = min(scored_alts)[1]
        trial = refine(obs, alternatives[j].shape, alternatives[j].poses, ps, ts, covariance=True)
        trial_shape, trial_poses = normalise(trial.shape, trial.poses)
        t = total(trial_poses)
        if t < (1.0 - CURVE_REFIT_GAIN) * best_total:
            alternatives[j] = Alternative(rec.shape, rec.poses, float(rec.chi2), rec.std)
            fit, shape, poses, best_total = trial, trial_shape, trial_poses, t
    for _ in range(CURVE_REFIT_ROUNDS):
        c, alpha, beta, phi = (float(v) for v in shape)
        with np.errstate(all="ignore"):
            cos_d, sin_d = frame_equations.pose_from_shape(
                c, np.tan(alpha), np.tan(beta), phi, obs.cp, obs.dp, obs.ep, -np.sin(poses[:, 1])
            )
        delta = np.arctan2(np.broadcast_to(sin_d, (n,)), np.broadcast_to(cos_d, (n,)))
        frames = np.flatnonzero(np.isfinite(delta))
        if frames.size == 0:
            break
        starts = np.repeat(poses[None], frames.size, axis=0)
        starts[np.arange(frames.size), frames, 0] = delta[frames]
        starts[np.arange(frames.size), frames, 1] = -poses[frames, 1]
        shapes = np.repeat(np.asarray(shape, float)[None], frames.size, axis=0)
        g, p, _, chi2, _, _ = refine_batch(obs, shapes, starts, ps, ts, max_iter=60)
        cands = [k for k in range(frames.size) if chi2[k] < rec.chi2 + CURVE_REFIT_DCHI2]
        scored = [(total(p[k]), k) for k in cands]
        if not scored:
            break
        t, k = min(scored)
        if not t < (1.0 - CURVE_REFIT_GAIN) * best_total:
            break
        trial = refine(obs, g[k], p[k], ps, ts, covariance=True)
        trial_shape, trial_poses = normalise(trial.shape, trial.poses)
        t = total(trial_poses)  # the full refinement may move on: check again
        if not (
            t < (1.0 - CURVE_REFIT_GAIN) * best_total and trial.chi2 < rec.chi2 + CURVE_REFIT_DCHI2
        ):
            break
        fit, shape, poses, best_total = trial, trial_shape, trial_poses, t
    if fit is None:
        return rec, res
    alt_poses, alt_chi2 = branch_alternatives(obs, shape, poses, w8)
    std = fit.std if fit.std is not None and np.all(np.isfinite(fit.std)) else rec.std
    warnings = list(rec.warnings) + [
        "the curve chose between nearby maximum-likelihood optima (pose branches refitted "
        f"jointly; chi2 {rec.chi2:.2f} -> {fit.chi2:.2f})"
    ]
    new = Reconstruction(
        shape,
        poses,
        std,
        rec.inliers,
        alternatives,
        warnings,
        rec.method,
        fit.chi2,
        fit.frame_chi2,
        alt_poses,
        alt_chi2,
    )
    return new, reconstruct_curve(obs.curves, new.rotations(), new.translations())
