"""Options of every stage, with their defaults (as PoseLib's ``RansacOptions`` / ``BundleOptions``).

The tuned numbers of the pipeline's decisions live here, passed down from
:func:`curverecon.reconstruct` (``ReconstructOptions``) to the stage that uses it.  (The
numerical settings inside a method, e.g. the Levenberg-Marquardt switch to Newton or the curve
bundle's spline, are still constants of its module.)  Each default's comment says what it trades
and what chose it.  "headline" is the bench cell of ``python -m bench.headline`` (1 px, 1 degree,
20 frames, 200 scenes); "noise-free" the bench's 10,000 noise-free scenes of 4-6 frames;
"robustness" its outlier-frame scenes; "scaling" its long sequences (bench/REPORT.md).

Units: chi2 values are sums of squared standardised residuals (dimensionless); angles in
radians unless a name says ``_deg``; lengths in input units (pixels).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from curverecon.solvers.homotopy import HomotopyOptions


@dataclass
class SearchOptions:
    """The global search over the shape (``robust/search.py``), which makes the hypotheses."""

    candidates: int = 16
    """Grid minima refined briefly with 12 or more frames.  More costs time about linearly.
    The figure that chose 16 is not recorded; the headline cell (100 % success) runs on it."""

    candidates_few: int = 48
    """... with 5 to 11 frames, where the cost has more shallow minima (the 6-frame cell, 61 %
    success, is where the search misses most)."""

    candidates_minimal: int = 16
    """... with 4 frames: every start fits exactly, the candidates are the exact shapes found."""

    restarts: int = 32
    """Random restarts per centre with 12 or more frames and a plausible chi2 (headline)."""

    restarts_few: int = 96
    """... with fewer than 12 frames (6- and 10-frame cells)."""

    restarts_implausible: int = 96
    """... when the best chi2 is implausibly high (outlier frames, a missed minimum) or nearly
    but not exactly zero (``near_exact_chi2``; noise-free cells)."""

    near_exact_chi2: float = 0.05
    """chi2 per degree of freedom below which a fit that is not exact counts as nearly
    noise-free (search harder).  Noise-free 6-frame rate."""

    exact_cost: float = 1e-9
    """A (robust) chi2 at or below this is an exact fit: nothing can beat it by the relative 1e-9
    margin the searches require, so restarts and branch flips are skipped (time only)."""

    exact_reduced_cost: float = 1e-20
    """A pose-free cost at or below this counts as an exact fit in the exact stage."""

    exact_stage_starts: int = 12
    """Grid minima searched first for an exact fit (noise-free: saves the rest of the search)."""

    exact_stage_min_frames: int = 5
    """... from this many frames on (with 4 frames every start fits exactly)."""

    screen_iterations: int = 15
    """Gauss-Newton iterations that screen the random restarts of plausible noisy data; the
    ``restart_finalists`` best are then refined to convergence (time per headline scene)."""

    screen_ftol: float = 1e-6
    """Relative predicted decrease at which a screening iteration counts as converged."""

    restart_finalists: int = 8
    """Screened restarts refined to convergence (headline: 0.143 s per reconstruction)."""

    rescue_chi2: float = 9.0
    """A frame whose chi2 is still above this after the branches of (10) is re-solved from a
    grid of starts before it can be called an outlier (scaling: 12 -> 2 false outliers on the
    4,642-frame scene)."""

    rescue_deltas: int = 12
    """Values of delta in that grid (every 30 degrees), each with both signs of tau."""

    rescue_before_fit_frames: int = 1000
    """From this many frames on, the rescue also runs on the start poses of each refinement on
    a larger subset (``robust_start``'s ladder and all frames), before the fit rather than only
    after it: the frames it moves otherwise pull the fit along a creep, and the refit after the
    rescue costs a few more iterations on all frames (100,000 frames, held-out seed 1002: the
    fit on all frames took 21 iterations, the refit after the rescue 6 more)."""

    max_search_frames: int = 40
    """The search runs on this many evenly spread frames; the candidates are refined on all
    (its cost grows with the frame count; scaling)."""

    medium_frames: int = 400
    """Above this many frames the candidates are screened on this many spread frames first
    (with the one-trial marginal line search, scaling's 10,000 frames: 24.1 s -> 9.0 s)."""

    medium_keep_cost: float = 16.0
    """... keeping those within this robust cost of the best (four times the alternatives'
    window, ``BranchOptions.alternative_dchi2``)."""

    medium_merge_distance: float = 0.02
    """... and merging those within this ``shape_distance`` of a better one (one basin: the
    same threshold that makes two fits one alternative, ``robust.alternatives``)."""

    ladder_factor: int = 10
    """Above ``medium_frames`` the kept candidates are refined on ever larger spread subsets,
    each this many times the last (as long as it is at most half of all frames), before all
    frames: each rung starts a few of its own standard deviations from its optimum.  (30,000
    frames: from the 400-frame fit the refinement on all frames took 34 iterations, with 4,000
    frames in between 9 (with the Newton switch of long sequences, ``refine.ml``); 100,000
    frames with rungs of 4,000 and 40,000: 6 and 7.)"""

    linear_seed_gap: float = 1e-3
    """The linearisation seeds the search (from 45 frames) only if its two smallest singular
    values differ this much (nearly noise-free data; at realistic noise it is unusable)."""

    def __post_init__(self) -> None:
        if self.exact_stage_starts < 1:
            raise ValueError(
                "SearchOptions.exact_stage_starts must be at least 1, got "
                f"{self.exact_stage_starts}"
            )


@dataclass
class OutlierOptions:
    """The outlier-frame test (``robust/outliers.py``)."""

    false_alarm: float = 2e-4
    """False-alarm probability per frame (chi2, one degree of freedom).  Lower flags fewer
    outliers (robustness: 53.5 % of 10 % outliers flagged); higher flags good frames of long
    sequences (scaling: 2 of 4,642 flagged, as 2e-4 predicts).  Where the test starts from
    LO-RANSAC's consensus set, a frame left out also needs a chi2 below ``take_back_chi2`` to
    come back: set that to inf for this rate alone to decide."""

    cauchy_k: float = 4.0
    """Scale (standard deviations per frame) of the robust reweighting before the test."""

    trim_steps: int = 2
    """Concentration steps of the trimmed refits when the fit's chi2 is implausible (the
    trimmed refits took robustness at 30 % outliers from 33 to 49 % success, commit 2a48dc8)."""

    batch_frames: int = 1000
    """From this many frames on, every frame above the threshold is dropped in one round
    (then one refit, and the test again), and the robust reweighting runs only when the fit's
    chi2 is implausible: one frame's pull on the shape is ~4/N, and one at a time cost a
    refit on all frames per frame flagged (30,000 frames: 8 flagged, as ``false_alarm``
    predicts).  Below, the frames go one at a time (robustness, headline: unchanged)."""

    leverage_floor: float = 0.05
    """Least 1 - leverage in the studentised chi2 (a frame that alone fixes a shape direction)."""

    take_back_chi2: float = 9.0
    """Starting from a consensus set (``robust.outliers.consensus_start``: LO-RANSAC's frames
    below ``FrameSampleOptions.truncate``), a frame left out is taken back only when its chi2
    at the shape refitted without it is below this too, not only below the test's threshold
    (chi2(1) at ``false_alarm``, 13.8 and more): random-tangent outlier frames whose chi2
    fell between the two were taken back and pulled the answer.  Scene 4 of seed 4242 (30 %):
    samples' shape 2.3 degrees off, answer 5.4 with the frame taken back, 3.2 without.  30 %,
    scenes 0-29, with ``chord_weight`` 1: seed 4242 (tuned on) 29 of 30 against 27; seed 5151
    26 of 30 both.  It holds whatever ``false_alarm`` is (a frame above it stays out even at
    a false-alarm rate of 1e-300); inf leaves the decision to ``false_alarm``."""


@dataclass
class BranchOptions:
    """Pose branches of (10) and equally good optima (``robust/branches.py``, the pipeline)."""

    ambiguous_dchi2: float = 4.0
    """A frame whose other branch fits within this chi2 of its pose is reported ambiguous."""

    flip_dchi2: float = 4.0
    """Frames whose other branch fits within this chi2 (shape fixed) are tried on it."""

    flip_max_frames: int = 12
    """... only with at most this many inlier frames (with more, the others pin the shape)."""

    alternative_dchi2: float = 4.0
    """Shapes whose chi2 is within this of the best count as fitting equally well."""

    mixture_dchi2: float = 40.0
    """A frame's other branch joins the marginal likelihood's mixture if its chi2 is within
    this many noise scales of the frame's fit (headline phi RMSE/CRLB 1.23 -> 1.12)."""


@dataclass
class CurveOptions:
    """The curve stages (``curve/``): branch choice by the curve, section 4, the bundle."""

    bundle: bool = True
    """Fit the poses and one 3-D curve to every frame's polyline (``curve/bundle.py``)."""

    traced_tangents_retry: bool = True
    """Input whose tangents were estimated from its polylines (``"tangents_from_curve": true``,
    ``curverecon trace``): reconstruct also with the adaptive end-tangent fit as a start only
    (``Observations.ends_given`` false: the polylines alone fix the shape) and keep the answer
    whose curve fits the polylines closer (mean frame RMS).  Tangents of hooked or end-on ends
    are off by tens of degrees; trusted as measurements they left the bundle in a wrong
    minimum on bench seeds 8 and 1002 (frame RMS 0.3-4 px, curve errors 3.8 % and 12.9 %;
    from the polylines alone 0.13 % and 0.15 %), while on seed 1003 the polylines alone went
    wrong and the tangents did not (RMS up to 3.5 px against 0.24 px): neither start is always
    right, the fit to the images decides.  Costs a second reconstruction."""

    flip_dchi2: float = 4.0
    """Frames whose other branch fits within this chi2 of their pose are tried on it by the
    curve; farther branches are excluded by the end points and tangents alone."""

    flip_gain: float = 0.03
    """A branch switch is kept only if it lowers the total curve reprojection by this fraction."""

    flip_max_switches: int = 6
    """At most this many single-frame switches (greedy rounds) per reconstruction."""

    search_samples: int = 60
    """Curve samples per trial reconstruction in the branch search (time only)."""

    curve_search_max_frames: int = 20
    """With the curve bundle, sequences of more frames choose the pose branches by the curve
    and build the bundle's start curve (section 4) on this many frames spread over the
    sequence, not on all: section 4 scores every frame's crossings in every frame (O(N^2)) and
    the branch search runs it once per candidate switch, hours at 1,000 frames.  The joint
    refits from the other sign of tau (``refit_*``: one refinement of all N frames per frame)
    are left out there.  The bundle then fits every frame and searches every frame's pose
    against the curve itself.  20: the
    bench's 8- to 20-frame scenes keep the full search (their answers unchanged); at 40 frames
    (1 px, seeds 7-9, helix, clothoid, random, sharp-ends) the search on 20 frames gave the
    full search's answers (curve errors 0.15, 0.18, 0.18 %; sharp-ends 0.16 against 0.18 %)
    in half the time (1.5-3.2 s against 3.4-7.2 s)."""

    bundle_max_frames: int = 200
    """From this many frames on (end points and tangents given), no joint fit of the poses
    and the curve: the end-point answer stays and the curve alone is fitted to the polylines of
    ``curve_search_max_frames`` frames spread over the sequence, every pose fixed - the answer
    the never-worse test (``never_worse_dchi2``) falls back to.  With this many frames the end
    points fix the shape more tightly than the curve model's bias: at 1,000 frames (bench seed
    1400, 1 px) the joint fit took 2 minutes and the never-worse test then refused its shape
    (outside the end points' 99 % region; seed 1401, random curve: 89 s, refused with
    end_point_dchi2 85), leaving this answer; this path took 1.8 s (curve
    0.41 % of its length off; with 50 or 100 frames fitted 0.43, 0.39 %: the end-point poses
    bound it, not the number of frames).  At 100 frames the joint fit's shape was still taken
    in 2 of 3 scenes (seeds 1400-1402, 9 s each)."""

    bundle_start_from_search: bool = True
    """With the curve bundle on given end points and tangents, its start curve is the branch
    search's own section-4 curve of the chosen poses (``search_samples`` samples, unsmoothed),
    not a full reconstruction (200 samples, smoothed) made for it: the bundle first fits its
    own coarse spline to it.  The full reconstruction (on polylines whose 200-sample crossings
    nothing has computed yet: about 0.027 s a scene at 20 frames, a tenth of the curve stage)
    is made only where a fit with every pose fixed runs (a refused bundle, exact end points),
    whose local minima need the better start: random 1205 (1 px, 12 frames, refused) fitted
    from the coarse curve left a polyline RSS of 2,380 against 1,859, and the gate's polyline
    test (``never_worse_f_test``) then took the bundle's shape, 3.2 degrees off.  Time ratio
    at 20 frames (1 px; seeds 1400, 2000, 2100): 2.53 -> 2.43, 2.17 -> 2.04, 2.24 -> 2.05; on the
    bench's 12-frame scenes (curve_05 1100-1107, 3000-3007, never_worse 1200-1207,
    2100-2107) every count and rate the same.  Not for polylines only: nothing checks the
    bundle's answer there (no end-point answer, no gate), and from the coarse curve clothoid
    1302 (0.5 px, 12 frames) reached a minimum of higher cost (1,877.8 against 1,859.2), phi
    3.3 degrees off against 0.16."""

    refit_dchi2: float = 4.0
    """A joint refit with one frame on its mirrored branch is a candidate if its chi2 is within
    this of the answer's."""

    refit_gain: float = 0.2
    """... and kept only if it lowers the total curve reprojection by this fraction (a larger
    margin than ``flip_gain``: it moves the maximum-likelihood answer itself)."""

    refit_rounds: int = 1
    """At most this many accepted refits (a second round changed nothing; costs a batch)."""

    refit_same_tol: float = 1e-4
    """Joint refits (from different frames' mirrored starts) whose shape and pose parameters
    all agree within this (radians, pixels) reached one optimum, and only the first is scored
    by the curve (each score is a section-4 reconstruction of the whole curve, about 10 ms at
    20 frames).  On bench seeds 1400 and 1401 (20 frames, 1 px, every family) the refits
    within 1e-2 of another agreed within 2e-5 (chi2 within 1e-9: the refinement's tolerance),
    and 5 of 12 scenes had such repeats (up to 6 of 11 candidates); no two refits fell between
    2e-5 and 1e-2.  0: every candidate scored."""

    frame0_branch_dchi2: float = 9.0
    """Frame 0's pose fixes the coordinates of ``curve3d``; when its other pose branch of (10)
    fits frame 0's end points and tangents within this chi2 of its own (3 std of the frame's one
    degree of freedom), the curve bundle also starts from that branch (the start curve turned
    with frame 0) and keeps the lower cost; 0 never.  Bezier seed 1300, 1 px, 12 frames: the
    end points preferred frame 0's wrong branch by 6.2, section 4's reprojection kept it, and
    ``curve3d`` came out 2.6 % of its length off (a tilt of the whole curve, 8 std across the
    curve); the bundle from the other branch reached a lower cost (end-point chi2 46.7 against
    59.1, polylines 11.62 against 11.96) and 0.19 %."""

    frame0_branch_same_deg: float = 5.0
    """The bundle from frame 0's other branch (``frame0_branch_dchi2``) stops after its coarse
    stage when that stage ended within this angle (degrees, every frame's rotation relative to
    frame 0) of the first start's coarse stage: the pose search of the coarse stage brought
    frame 0 back to the first start's branch, and the rest of the run retraced the first
    start's to the same minimum, give or take the cost's rough floor (1 px, 20 frames, seeds
    1400, 2000, 1401, 1402, 2001: 6 of the 7 second starts within 1.3 degrees, their final
    costs 2.0 below to 146 above the first start's; the seventh at 144 degrees, another basin;
    held out, seeds 1403-1407, 2002-2005: 17 of 20 within 1.7 degrees, final costs 3.8 below
    to 0.7 above, the other 3 at 18.6-121 degrees, each run to its end); 0 never stops.  The
    rest of a second start took about a third of the curve bundle's time where it ran."""

    frame0_branch_first_iter: int = 3
    """The bundle from frame 0's other branch (``frame0_branch_dchi2``) searches every frame's
    pose after this many coarse LM iterations (and as many of the coarse fit with uneven frames
    down-weighted), not after the full coarse fit, and stops as soon as the poses are the first
    start's again (``frame0_branch_same_deg``, tested after each pose search as well as at the
    end of the coarse stage); 0: the search after the full coarse fit.  That run starts with
    only frame 0's pose flipped (the curve and the other frames as the first start's in world
    terms); where it returns to the first branch, the coarse LM spent up to 30 iterations
    dragging the curve and every pose towards frame 0 (fourier seed 1400, 1 px, 20 frames:
    relative poses 145 -> 116 degrees from the first start's) before a pose search that brought
    every frame back within a degree.  Seeds 1300-1307, 1400-1402, 2000-2001, every family,
    1 px, 12 and 20 frames (45 second starts, 36 stopped): the same stops plus one (bezier seed
    1307, 12 frames: it had run on to the first start's minimum, the same curve), that run's
    time 7.5 -> 4.6 s in all (a stopped run's median 0.10 -> 0.044 s); bezier seed 1300 at 12
    frames still found 95 degrees away (cost 1737.3 against 1737.2, curve 0.18 % off against
    0.20 %); fourier seed 1306 at 12 frames reached the first start's minimum instead of a
    higher one (the flat start it called for not needed, the same curve).  Held out, seeds
    1403-1407, 2002-2005, 2100 at 20 frames (18 second starts): the same 15 stops, 1.95 ->
    1.19 s; sharp-ends seed 2005's run to the end won by a cost of 0.01 (the rough floor)
    where it had lost by 1.6, a curve 0.52 % off instead of 3.8 %.  Capping also the LM
    after the first pose search (a second search before the test) saved a little more at 20
    frames but lost 3 of the stops at 12 frames (runs sent to higher minima instead)."""

    bundle_extra_starts: int = 3
    """When the curve bundle still leaves some frame fitting clearly worse than the others
    (``bundle.UNEVEN_RATIO``) after its start from the end-point answer and from frame 0's
    polyline, it starts again from this many other frames' polylines at depth 0 (spread over
    the sequence, ``bundle.extra_start_frames``) and keeps the lowest cost.  Trace bench seed 0:
    both default starts ended in the same wrong minimum (frame RMS up to 2.4 px, 10.7 % of the
    length off) while the starts from frames 8 and 12 reached the noise level (0.1 %).  Each
    start costs one bundle run (2-5 s at 16 frames), only on scenes that do not fit evenly."""

    bundle_smooth_weight: float = 0.1
    """Weight of the bundle's fourth-difference penalty on the control points (relative to one
    polyline point's residual; ``bundle.SMOOTH_WEIGHT``).  It only fixes the spline's
    parametrisation (sliding control points along the curve), which the images leave free; it
    is zero for cubics but not for the curves fitted, so a heavy weight pulls the curve towards
    a cubic - a bias of the end tangents that the covariance, counting the penalty as
    information, does not show.  At 2.0 (the former weight) the shape's |error| / std had an RMS of
    1.17-1.33 per parameter on accepted scenes (1 px, 1 degree, 12 frames, seeds 5000-5004 of
    every family; chi2 per polyline point 0.86-1.05, residuals white along the polylines: not
    the noise model) and 20 noise draws of one scene (random family, seed 5502) showed a
    beta bias of 2.1 std and phi 1.6 std with the spread equal to the std; at 0.1 the biases
    fell to 0.06 and 0.17 std (at 20 control points instead of 12: likewise), the RMS to
    0.92-1.17, the 3-sigma coverage there 0.967 -> 1.0."""

    bundle_order_tol: float = 8.0
    """A fitted curve counts as folded over itself (forward, back and forward again along one
    stretch) when in most frames some polyline point's nearest foot steps back along the
    projected curve (against the polyline's order, A' to B') by more than this many sigma of
    arc length, or a stretch that long gets no foot (``bundle._folded``); the bundle then
    refits from the curve's points at the feet in a polyline's order with every foot in the
    polylines' order (``bundle._Problem._ordered_feet``) and keeps that fit whatever its cost;
    0 never.  With the nearest feet the strands of a fold share the polyline points and fit
    the noise better than any single curve (a lower cost), so no restart rule finds the single
    curve: random seed 1206 (1 px, 12 frames) folded near B even started from the true curve
    and poses (3-D length 1.42 times the true one, ``curve3d`` up to 4.6 px and 12 std off over
    18 % of its points, while the 12-point spline fits the true curve within 0.006 px);
    refitted: 1.005, at most 1.9 std.  The noise moves a foot along the curve by about a sigma
    (true curve, noisy polylines: at most 3.7 px at 1 px), a fold's strands by tens of pixels.
    Bench never_worse scenes, seeds 1200-1207 (tuning): 3 of 48 refitted, all folds (length
    ratio 1.42, 1.10, 1.02 -> 1.005, 1.008, 1.007), the rest unchanged; curve3d 3-sigma coverage
    0.9676 -> 0.9717, |d| / std RMS 1.293 -> 1.214; held-out seeds 2100-2111: no accepted
    bundle folded, figures unchanged (0.9649, 1.230; their misses are refused scenes such as
    random 2108, whose fixed-pose curve is stretched in depth by the end-point answer's poses,
    no fold).  Keeping every foot within 4 sigma in
    order in every fit instead (no fold test) also moved the shapes of unfolded curves (Bezier
    1202: c 0.4 -> 3.0 std)."""

    never_worse_dchi2: float = 13.28
    """The curve bundle's answer replaces the end-point answer only if its end-point chi2 is
    within this of the end-point answer's, in units of the end-point fit's variance factor
    (chi2 / dof): the 99 % quantile of chi2 with 4 degrees of freedom (the shape), so the
    answer stays inside the end points' 99 % confidence region (never worse beyond noise).
    Refused, the end-point answer's std is scaled by sqrt(dchi2 / never_worse_dchi2): the two
    answers disagree, and the bundle's shape is then just inside the scaled 99 % region."""

    never_worse_f_test: bool = True
    """Refused by ``never_worse_dchi2`` (a known noise level), the bundle's shape is still kept
    when ``end_point_dchi2`` is within 4 F(4, N - 4) at the same probability (99 %;
    ``bundle.never_worse_limit``: 28.0 at 12 frames, 19.1 at 20, 13.4 at 1,000) and the
    polylines reject the end-point answer's poses (``never_worse_polyline_level``).  The
    variance factor comes from the end-point fit's own N - 4 degrees of freedom, so with an
    estimated noise level the end points' 99 % region reaches the F limit: between the two the
    end points do not say whether the shape is inside it, and the polylines decide.  Helix seed
    1105 (0.5 px, 0.5 degree, 12 frames): the bundle reached the truth's minimum (curve 0.040 %
    of its length off; started at the truth 0.038 %) but s2 was 0.16 where the noise gives
    0.25 (a chi2_8 draw; a third of them fall below 0.7 of their mean), dchi2 16.2 (the
    truth-start bundle's 15.3): refused, the curve fitted on the end-point poses stayed 20
    times the polylines' noise from them and was 2.5 % off.  Bench seeds 1100-1107 (0.5 px, 12
    frames, every family): 3 refusals in the band, all kept (2.50 -> 0.04 %, 0.29 -> 0.09 %,
    0.51 -> 0.26 %); held out 3000-3007: 3, all kept (2.28 -> 0.03, 0.30 -> 0.17, 1.06 ->
    0.13 %).  The F limit alone (no polyline test) also took random 1205 (1 px; dchi2 16.6),
    whose fixed-pose curve fits the polylines at their noise (F test tail 0.013): its beta went
    3.5 std of the end-point answer off (1.24 kept).  Off: ``never_worse_dchi2`` alone."""

    never_worse_polyline_level: float = 0.999
    """The polylines reject the end-point answer's poses (``never_worse_f_test``) when the
    curve fitted on them with its ends pinned leaves more polyline residual than the bundle
    beyond this level of the nested-model F test (``bundle.polylines_reject_fixed_poses``,
    5 N + 4 parameters more in the bundle).  0.999 rather than the gate's 0.99: it overrides the
    end points' known-variance verdict, so the polylines must be decisive; the 6 scenes kept
    on bench seeds 1100-1107, 3000-3007 had tails below 1e-190, random 1205 (refused) 0.013."""

    never_worse_alternatives: bool = True
    """Where the end-point answer has equally good ``alternatives`` the gate still applies, from
    the least chi2 among the answer and its alternatives (``bundle.gate_reference_chi2``: the
    end points' likelihood-ratio 99 % region, the union of the regions about every hypothesis);
    off, the gate is skipped there and the curve alone decides (as before; commit 4bb75e5: a
    traced 8-frame scene went to c = 1265 against 127 with the gate).  At 1 px, 12 frames the
    alternatives are mostly nearby minima of a loosely determined end-point fit, a few std
    apart, not rival hypotheses: bench seed 1205 (random family) had three, the bundle's shape
    17 chi2 units (variance factor 0.34) from the best of them, beta 3.5 std of the end-point
    answer off (1.24 without polylines): skipping the gate took it."""

    refused_std_disagreement: bool = True
    """Refused by that test, the std of the end-point answer kept also includes (in
    quadrature, per parameter) its difference from the bundle's shape.  The refusals at 1 px
    came where the end-point answer itself was off (tuning seeds 6000-6011, 12 frames:
    helix 6007 alpha, beta, phi 1.9-3.0 degrees off, bundle 0.2-0.3; sharp-ends 6001 10-18
    degrees off, bundle 2-3.6; dchi2 13.8 and 16.2, just over the limit), the Birge scaling
    alone left |error| / std at 2.3-3.2 and 5.8-19."""

    restart_coarse_cost_ratio: float = 1.05
    """The bundle from frame 0's other branch (``frame0_branch_dchi2``) stops after its coarse
    stage when its cost there exceeds the first run's at the same stage by this factor: it is
    no rival then.  Measured (1 px; seeds 1200-1207 at 12 frames, 1400-1403 at 20 frames): of
    the second starts that went on to the end, every one that won or came within 2 of the
    first run's final cost was at 0.13-1.008 times its coarse cost; those at 1.3-51 times ended
    20 to 132,820 above it."""

    rival_minima_std: bool = True
    """With given end points: where another start of the curve bundle (frame 0's other pose
    branch, a restart from a frame's polyline) ended in another minimum, the answer's std
    (shape and ``curve3d``) include, in quadrature, the gap to that minimum weighted by its
    probability ``1 / (1 + exp(dcost / 2))`` (the two minima as the only hypotheses, cost a
    chi2): the RMS error of the answer when the data cannot tell the two apart.  Sharp-ends
    seed 9105, 1 px, 12 frames: frame 0's two branches at costs 1883.2 and 1884.5, curves 11 px
    apart at the middle for a std across the curve of 1.1 px; seed 1102 at 0.5 px: 1787.8
    and 1789.9, the lower one the farther from the truth (8.0 against 5.4 px).  A minimum
    20 above adds under 5e-5 of the gap squared."""

    rival_warning_probability: float = 0.01
    """A warning names that rival minimum (``rival_minima_std``) from this probability on."""

    variance_floor: float = 1e-30
    """Least variance factor of that test (noise-free end points: float rounding, about 1e-28;
    a positive floor only avoids dividing by zero)."""

    flag_rms_sigma: float = 3.0
    """A frame whose polyline stays more than flag_rms_sigma * sigma + flag_rms_px (RMS) from
    the fitted curve while end points are given is flagged: its polyline contradicts them
    (3 sigma: a frame fitting at the noise level stays below it)."""

    flag_rms_px: float = 1.0
    """... plus this (pixels: tracing and curve-model errors of a frame that does fit)."""

    max_flagged_fraction: float = 0.34
    """At most this fraction of the frames can have their polylines flagged as contradicting
    the end points; with more, the end points themselves are the doubtful data."""

    max_control_points: int = 75
    """Most control points of the curve when the information criterion asks for more (knot
    spans halved from 12: 21, 39, 75; noise-free sharp-ended curves reach 1e-7 of their length
    at 75; time grows with it)."""

    exact_start_control_points: int = 21
    """With exact end points the curve fitted with the poses fixed starts from this many control
    points (then 39, 75 while the information criterion improves; at most
    ``max_control_points``).  From 12 (the bundle's default) the stiff first fit folded or
    stuck where the curve bends more than 12 control points follow, and the knots grown from
    there kept it.  Noise-free, 10 scenes per family at 4, 8 and 20 frames, scenes whose
    curve3d mean distance exceeds 1e-6 of the length (``python -m bench.noise_free_curves
    FRAMES SEED0 10``): tuning seeds 7000-7009: 12 (with ``exact_unfold``) 5 of the 150 scenes
    run, up to 2.1e-3; 21: none of 180; held-out seeds 8000-8009 at 21: 3 of 180 (one a wrong
    shape at 4 frames, as before; fourier 8008, 20 frames, 4.9e-5; fourier 8009, 8 frames,
    1.1e-6), before this change 13 of 180 (tuning seeds: 20 of 180)."""

    exact_unfold: int = 2
    """... and at each number of control points up to this many refits from the fitted curve's
    points in a polyline's order when the spline has folded (run forward, back and forward
    again over one stretch: invisible in every image, a local minimum the Gauss-Newton steps do
    not leave), each kept if it lowers the cost; from the second number of control points on
    the feet of every polyline point are searched in the polyline's order (a crossing of the
    projected curve with itself otherwise held the fit: random, seed 7007, 8 frames, 6.3e-6 of
    the length before, 2.7e-7 after).  0: neither (the noisy paths never use them)."""

    exact_restart_control_points: int = 12
    """With exact end points, a curve fit that stays stuck (some frame's RMS distance from its
    polyline above ``exact_restart_rms`` of the polyline's length) is run again from this many
    control points (the bundle's default) and the fit with the lower polyline misfit kept
    (the sum over frames of the squared RMS distances).  Noise-free data fit to float rounding:
    a fit well above it sits in a local minimum of its start, and another number of starting
    control points leaves it (fourier, seed 8008, 20 frames: from 21 the fit stuck at 9.8e-4
    px RMS at 75 control points, 4.9e-5 of the length in 3-D; from 12, 2.6e-7).  0: never;
    scenes under the limit are unchanged (no second fit).  Noise-free survey (``python -m
    bench.noise_free_curves FRAMES SEED0 10``), scenes over 1e-6 of the length, before -> after:
    seeds 8000-8009 (fourier 8008 the scene this was built on), 20 frames 1 -> 0 (1 restart),
    8 frames 1 -> 1 (fourier 8009, 1.1e-6, under the limit; 2 restarts), 4 frames 1 -> 1 (bezier
    8007, a wrong shape from the end points; 3 restarts); held-out seeds 9000-9009, 20 frames
    2 -> 0 (bezier 9000 4.7e-5, sharp-ends 9004 5.6e-6; 2 restarts), 8 frames 0 -> 0 (none);
    tuning seeds 7000-7009 at 4, 8, 20 frames: no restart, none over 1e-6 (unchanged)."""

    exact_restart_rms: float = 1e-6
    """... the limit: the noise-free target (curve3d within 1e-6 of the curve's length) as a
    fraction of each polyline's length in the image.  Fits that reach the target sat 5e-8 to
    7e-7 below it (fourier 8000, 8001, 8009, helix 8000, random 8001), the stuck fourier 8008
    at 6e-6 to 1.2e-5 (its frames' lengths 84-159 px)."""

    exact_variance_factor: float = 1e-16
    """An end-point fit whose variance factor (chi2 / dof) is below this is exact (noise-free
    end points fit to 1e-8 of their sigma): the bundle is skipped, the exact answer kept and
    the curve alone fitted with the poses fixed (its variance factor is about 1e-28 there)."""

    fixed_pose_reverse_factor: float = 0.05
    """... and this fraction of the reverse term's weight (curve samples to the polyline): the
    term's pull towards the polyline's chords biased noise-free curves by about 1e-6 of their
    length at 0.25 (helix, seed 1, 8 frames: 1.0e-6; at 0.05: 6.9e-8), while the fixed poses
    leave a hidden detour little room."""

    fixed_pose_abs_tol: float = 1e-7
    """... its Gauss-Newton stops when the cost (units of sigma squared) falls by less than this
    per residual: a noise-free cost falls towards zero by a large fraction in every iteration,
    and below this a further fall moves the curve by about sigma * 3e-4 RMS (2e-5 px at the
    0.05 px floor; the noise-free target is 1e-6 of a 100-300 px curve)."""

    fixed_pose_resolution: float = 1e-8
    """... and its control points stop growing once every frame's RMS distance is below this
    fraction of the polyline's length (noise-free: a Bezier curve fits to rounding at once)."""

    fixed_pose_smooth_weight: float = 2.0
    """The difference penalty's weight when the curve alone is fitted with every pose fixed
    (the end-point answer kept: refused by the never-worse test, long sequences).  The shape
    is then the end-point answer's, so the penalty's pull on the end tangents does not reach
    it, while the poses' own errors would bend a freer curve: 2.0 (the bundle's former
    weight) kept; at ``bundle_smooth_weight`` (0.1) a 40-frame helix (seed 7, 1 px, poses
    fixed) went 3.6 % of its length off, from under 2 %."""

    fixed_pose_smooth_factor: float = 1e-3
    """With exact end points the curve fitted with the poses fixed keeps this fraction of
    ``fixed_pose_smooth_weight``: with the poses fixed only the spline's parametrisation is
    undetermined, which a trace of the penalty fixes, and the full penalty biased noise-free
    helices by 2e-4 px."""


METHODS = ("auto", "linear")
ESTIMATORS = ("marginal", "ml")


@dataclass(frozen=True)
class MinimalOptions:
    """The minimal solver's input checks, its polish, and the tracker's options.  (What counts
    as real and inside the bounds: ``solvers.minimal.REAL_TOLERANCE``, ``BOUND_TOLERANCE``.)"""

    homotopy: HomotopyOptions = field(default_factory=HomotopyOptions)
    polish_iterations: int = 6
    """Newton iterations on the tracked (unsquared) system for each real solution; the tracker
    ends every path with up to 3 already, so this is a margin (it stops at 1e-15 relative)."""
    duplicate_frames: float = 1e-9
    """Two frames whose observables (c', d', e') agree to this (relative) are one view."""
    tangent_along_chord_deg: float = 1e-6
    """A tangent within this angle of A'B' makes d' or e' zero: the frame says nothing."""


@dataclass(frozen=True)
class FrameSampleOptions:
    """LO-RANSAC over four-frame samples (``robust/frame_samples.py``), run when the search's
    answer has outlier frames.  Tuned on the robustness scenes of seeds 777 and 779 (not the
    bench's): 30 % outliers, 20 frames, 1 px / 1 degree: 10 of 12 and 15 of 20 succeed against
    7 of 12 and 9 of 20 without (``make bench`` measures it on its own scenes)."""

    enabled: bool = True
    min_frames: int = 7
    """Fewer frames: not run.  The outlier test flags at most (N - 5) // 2 frames, none below 7,
    so a sample's shape would be refitted on all frames anyway; and four frames are the
    minimal solver's alone (``robust.four_frames``)."""
    max_frames: int = 200
    """More frames: not run.  Each sample scores every frame, and with hundreds of frames one
    frame's pull on the shape is small enough for the outlier test alone (``OutlierOptions``)."""
    truncate: float = 9.0
    """Per-frame chi2 at which a frame counts as not explained, in the samples' score, their
    local optimisation and the robust cost that accepts their answer: three standard deviations
    of a frame's one degree of freedom (six measurements, five pose parameters; an inlier frame
    passes it with probability 0.997).  At 25 (five standard deviations, the search's
    ``robust_cost``) outlier frames whose 15-40 degree tangent errors a wrong shape half absorbs
    made that shape's cost the lower one.  30 % outliers, 20 frames, 1 px / 1 degree, with the
    ``fixed_shape`` score: 27 of 30 scenes succeed against 24 of 30 at 25 (seed 4242, tuned on;
    16 gave 26 of 30) and 25 of 30 against 22 of 30 (seed 5151, held out); 10 % outliers: 30 of
    30 both (seed 5151)."""
    trigger_p_value: float = 1e-3
    """Run also when no frame is flagged but the answer's chi2 is this improbable for the noise
    (``robust.outliers.chi2_tail``, n - 4 degrees of freedom).  Outlier frames whose tangent
    errors a wrong shape half absorbs leave no frame flagged: on scene 7 of seed 5151 (30 %
    outliers) the answer was 8.8 degrees off with chi2 44.3 on 16 degrees of freedom (p 2e-4),
    below the outlier test's 54.3 (``implausible_chi2``, five standard deviations plus 10).
    With it that scene is 2.7 degrees off.  Held out (seed 6262, 40 scenes each at 10 % and
    30 % outliers): the same successes as with the rule before it (flagged frames only).
    Clean 20-frame, 1 px / 1 degree scenes (seed 6161, 300): none below 1e-3 (smallest
    0.0017), 2.7 % below 1e-2, so the samples' seconds are not spent on clean data."""
    min_samples: int = 10
    """Samples drawn at least (PoseLib's ``min_iterations``)."""
    max_samples: int = 30
    """Samples drawn at most: each costs a minimal solve (about 0.17 s).  At 30 % outlier frames
    a sample is all inliers with probability 0.24, so 20 samples miss all of them with
    probability 0.004; but a clean sample of noisy frames gives a shape from which the local
    optimisation reaches the truth's basin only some of the time (bench-seed scene 22, 30 %:
    2 clean samples of 20, the better one 2.2 degrees off but explaining 11 frames, never
    refined; the answer 57 degrees off), and the adaptive limit (``success_prob``,
    ``dyn_num_trials_mult``: about 70 samples at 13 of 20 frames explained) is cut here in
    every 30 % scene.  With 30 (and the local optimisation's ``chord_prior``, ``anneal_steps``,
    ``search_answer_start``): bench seed 45 of 50 (90 %) against 44 with 20 (scene 22
    gained), 10 % 49 of 50 as before; held out, seed 7373: 27 of 30 (27 with 20, 25 with the
    defaults before the three); tuning seeds 5151 27 of 30 (27 with 20, 28 before), 4242 29
    (28 with 20, 29 before: 23 lost, 29 gained).  CPU time a scene (``time.process_time``, side
    by side), bench seed 30 %: 2.24 s (defaults before the three) -> 2.31 (20 samples) -> 2.86
    (30); 10 %: 1.45 -> 1.52.
    (Under the first scores, seeds 777 and 779, 30 gave the same successes as 20.)"""
    success_prob: float = 0.999
    """Probability that some sample was all inliers when the loop stops (adaptive stopping)."""
    dyn_num_trials_mult: float = 2.0
    """Safety factor on the adaptive number of samples (noisy samples give imprecise shapes)."""
    score: str = "fixed_shape"
    """How a sample's shape is scored on all frames: "fixed_shape", the robust cost of
    ``fixed_shape_fit`` (every frame's pose at its best branch, all six residuals: the measure
    the pipeline then accepts the samples' answer by, about 1.8 ms at 20 frames), or "tangent",
    the tangent misfit of the poses solved from the end points alone (about 0.5 ms).  The
    tangent score ranked wrong shapes above the truth: on 30 % outlier scenes of seed 4242
    (scenes 7, 8, 13, 24) the truth refined on the inlier frames scored 246-304 against 183-242
    for shapes 22-160 degrees off, whose robust cost was higher.  (Scored with it, at the
    truncation 25 of then, 24 of 30 scenes of seed 4242 succeeded both ways.)"""
    seed: int = 0
    """Seed of the sampler: the same input gives the same output."""
    final_refinements: int = 4
    """After the loop, this many more of the best-scoring sample shapes, each distinct from every
    shape refined before (``distinct_deg``), are refined too and the best of all refined shapes
    is kept (``robust.ransac.RansacOptions.final_refinements``): a sample near the truth can
    score below a wrong one until it is polished.  Each costs one local optimisation (a few
    hundredths of a second, against 0.17 s a minimal solve).  Random-tangent outliers, 30 %,
    20 frames, 1 px / 1 degree (scripts on ``bench.common.make``'s
    ``outliers_random`` scenes), with ``chord_weight`` 1 and ``OutlierOptions.take_back_chi2``
    9: seed 5151 (tuned on), scenes 0-29, 27 of 30 against 25 of 30 with 0 and ``lo_rounds``
    1 (scenes 2 and 8 gained, none lost; the same mean time, 2.7 s of CPU a scene); seed
    4242 (tuned on): 29 of 30 both."""
    distinct_deg: float = 3.0
    """Sample shapes within this in every angle (and this many radians' fraction of c) count as
    one for the final refinements (the noise of a four-frame sample's shape is a few degrees)."""
    chord_weight: float = 0.5
    """Weight of the chord-length term (``robust.frame_samples.chord_cost``: what each frame's
    |A'B'| says of c, AB's direction uniform on the sphere as the marginal likelihood assumes)
    in the samples' score and in the comparison that accepts their answer (0: the truncated
    chi2 alone).  The end points stay right in random-tangent outlier frames, so they tell
    wrong shapes whose c is too long for the chords seen: on scene 0 of seed 4242 (30 %) the
    samples' best by the truncated chi2 alone was 63 degrees off, c 161.8 against the true
    148.0 and a longest chord of 147.2; its truncated chi2 was 9 below the truth's, its chord
    term 24 above.  Random-tangent outliers, 30 %, 20 frames, 1 px / 1 degree, scenes 0-29
    (scripts on the bench's scenes of other seeds), with the other present defaults:
    weight 0 / 0.5 / 1: seed 4242 (tuned on) 27 / 29 / 29 of 30, seed 5151 (tuned on) 27 /
    28 / 27.  Weight 1 lost scene 27 of 5151: the samples' near-truth shape (2 degrees) had a
    c 4.7 % long (116.4 against 111.2, the c of a 14-frame fit is loose), and the chord term
    (11.6 higher) outweighed its truncated chi2 (3.2 lower) in favour of a shape 48 degrees
    off whose c happened to be right; 0.5 loses it too.  (The local optimisation's fit,
    ``refine_hypothesis`` on the inlier frames, does not see the term; ``chord_prior`` adds it
    there as a prior on c.)"""
    chord_prior: bool = True
    """The local optimisation (``FrameSampleEstimator.refine_model``) ends by moving c to the
    minimum of the fit's chi2 plus the score's chord term (``chord_weight`` times
    ``robust.frame_samples.chord_cost``; ``chord_prior_step``), the other parameters
    following c along the fit's covariance, and keeps that shape if it scores lower: the fit on
    a sample's consensus set alone ignores what every frame's |A'B'| says of c, and a near-truth
    shape whose c came out a few per cent long lost to a wrong one by its chord term alone
    (bench-seed scene 8 at 30 %: c 3.9 % long, 2.0 degrees off, score 144.9 against 144.0 for a
    shape 83 degrees off; with the prior 0.5 degrees).  Alone it gained nothing overall
    (random-tangent outliers, 30 %, 20 frames, 1 px / 1 degree; scripts on the bench's
    scenes, the bench seed 50 scenes, the others 0-29): bench seed 44 -> 43 of 50 (8 gained;
    34 and 46 lost, at 1.4 and 4.9 degrees before, 5.2 and 6.3 after), seeds 7373, 5151, 4242
    unchanged (25, 28, 29 of 30); the annealing below takes 34 and 46 back.  5151/27, where a
    c 4.7 % long was thought to lose the truth, is ambiguous under the score even so: a shape
    30 degrees off scores 141.6 against 146.1 for the truth refined on its inlier frames."""
    search_answer_start: bool = True
    """The search's answer joins the samples' shapes as a hypothesis of the loop (scored and,
    if best so far, polished by the same local optimisation on the frames it explains), not
    only as the answer the samples' shape must beat.  Seed 7373, scene 17 (30 %): no sample's
    shape within 5 degrees, the search's answer 8.3 degrees off; polished, 2.0 degrees."""
    anneal_steps: int = 2
    """Fits at a raised threshold that start the local optimisation (before the ``lo_rounds``
    at ``truncate``; 0: none): on the frames below ``anneal_start`` times the truncation,
    then lower multiples, falling geometrically towards 1 (Lebeda, Matas and Chum, "Fixing the
    locally optimized RANSAC", 2012: the iterated least squares of LO at a threshold that
    shrinks to the final one).  A sample's shape a few degrees off misses good frames by a
    little and takes in outliers that happen to fit; at the truncation alone the local
    optimisation stays with that consensus set.  Bench-seed scene 46 (30 %): the samples'
    best 5.9 degrees off, score 179.7, the truth refined on its inlier frames 161.8, which the
    annealed optimisation reaches (1.0 degrees).  One setting tried (4 and 2 times the
    truncation), not tuned.  With ``chord_prior`` and ``search_answer_start``, against the
    defaults before them (same scenes and scripts as ``chord_prior``): bench seed 44 of 50 both (the
    same six failures), 10 % 49 of 50 both (scene 3, where the samples do not run); held out,
    seed 7373: 25 -> 27 of 30 (17 and 28 gained); tuning seeds 5151: 28 -> 27 (20 lost: a shape
    10.4 degrees off that the loop before them did not find scores 153.9 against the truth's 155.6),
    4242: 29 -> 28 (29 gained; 23 lost, 4.9 -> 5.1 degrees, the truth refined on its inlier
    frames itself 3.2 degrees off).  CPU time a scene (``time.process_time``, the same
    conditions, run side by side): 2.24 -> 2.31 s at 30 %, 1.45 -> 1.51 s at 10 %.  These are
    the figures with 20 samples; the present ``max_samples`` (30): see there."""
    anneal_start: float = 4.0
    """The first of those thresholds, in multiples of ``truncate`` (a chi2: twice the residual
    of the truncation)."""
    lo_rounds: int = 3
    """Fits of the local optimisation, each on the frames the last shape explains, until that
    set stops changing (a shape refined on a sample's consensus explains other frames)."""
    consensus_start: bool = True
    """When the samples' shape is taken, the outlier test starts from the frames it explains
    (per-frame chi2 below ``truncate``: LO-RANSAC's consensus set; a frame left out is taken
    back if it fits the shape refitted without it, ``robust.outliers.consensus_start``), not
    from a reweighted fit of all frames, which the outliers pulled again: on scene 91 of the
    bench's random-tangent 10 % scenes (``bench.outliers``) the samples' shape was 1.6 degrees
    off, the answer refitted from it on all frames 5.8.  Random-tangent outliers, 20 frames,
    1 px / 1 degree (scripts calling ``bench.robustness.run_scenes``): bench seed
    20260521 (diagnosed on), 10 %: 99 of 100 succeed against 98; 30 %, scenes 0-39: 31 of 40
    both (scenes 12 and 19 gained, 8 and 31 lost).  Held-out seed 9001 (the same scripts):
    10 %, scenes 0-29: 29 of 30 both; 30 %, scenes 0-19: 17 of 20 both (the same three fail).
    The 30 % figure is bounded by scenes the truncated cost cannot tell from the truth and by
    missed basins (README).  The 15-40 degree model, 30 %, seed 4242 scenes 0-19: 15 of 20
    against 14 (scene 13 gained, none lost)."""


@dataclass(frozen=True)
class FewFrameSampleOptions:
    """Hypotheses from a few four-frame samples next to the search's, with few frames
    (``robust.frame_samples.few_frame_hypotheses``): every real minimal solution of each sample
    is scored on all frames, the best refined on all frames, and the candidates join the
    search's (the lowest robust cost wins).  On exact data every sample's solutions contain the
    truth (the minimal solver lists it in 99.97 % of scenes), which fits all frames exactly:
    the search alone missed it in 1.4 % of the bench's noise-free 6-frame scenes.  Run only when
    the search's best fit is not exact (``SearchOptions.exact_cost``): nothing could beat it."""

    enabled: bool = True
    min_frames: int = 5
    """Fewer frames: four frames are the minimal solver's alone (``robust.four_frames``)."""
    max_frames: int = 11
    """More frames: not run.  Where the search counts frames as few (``SearchOptions``'
    ``candidates_few``, below 12 frames) its cost has many shallow minima and the samples
    pay; a sample costs a fixed 0.2-0.5 s (a minimal solve, 0.16 s unloaded, and the
    refinements), which the 20-frame reconstruction (0.2 s at most,
    ``reconstruct_seconds_20_frames``) cannot carry, and noisy data always runs it.  Noise-free
    scenes of the stability generator (seed 4242, 300 each) the search alone got wrong: 1 at 8
    frames, 3 at 10; with the samples all 4 give the truth to 1e-9."""
    samples: int = 1
    """Samples (spread over the frames, ``robust.frame_samples.spread_samples``), each a
    minimal solve (about 0.16 s).  Exact data: one sample lists the truth with probability
    0.9997 (``minimal_truth_listed_rate``).  Noisy 6-frame, 1 px scenes (accuracy generator,
    seeds 1 and 2, not the bench's, 30 scenes each): successes 42 of 60 without samples, 43
    with one, 44 with two, where one sample took the mean time per scene from 0.99 s to
    1.81 s (20 of those scenes, on and off interleaved on one core of the loaded shared
    machine) and two about twice the extra."""
    refine_per_sample: int = 3
    """Of each sample's solutions, this many with the lowest chi2 on all frames (shape fixed,
    every frame at its best pose) are refined on all frames.  Exact data: the truth's chi2 is
    zero, always the first."""
    precise_p_value: float = 1e-2
    """Beyond ``max_frames``: run when the search's best fit is not exact but its chi2 is
    improbably low for the noise given (lower tail probability, n - 4 degrees of freedom): the
    data are far more precise than ``point_sigma`` / ``tangent_sigma_deg`` say, so the exact
    fit that a sample's minimal solutions contain is within reach, and a near-exact wrong basin
    must not stand.  Noise-free scenes of the stability generator at the default sigmas, the
    truth missed (error above 1e-6) without / with: seed 4242 (tuned on, 300 each) 16 / 2 at
    15 frames and 12 / 1 at 20 frames; seed 5353 (held out, 200) 5 / 1 at 20 frames.  The
    wrong basins' chi2 was 0.02-4.4 on 16 degrees of freedom, so 1e-3 left half of them
    (scene 62: 4.37, tail 0.002).  Noisy 20-frame scenes (1 px / 1 degree, seed 6161) ran the
    sample in 12 of 300 (0.2-0.5 s each)."""
    precise_chi2_ratio: float = 0.5
    """... and only when that chi2 is also below this fraction of its degrees of freedom.  The
    tail probability alone fired on long noisy sequences: choosing each frame's better pose
    branch makes the chi2 a few per cent low (chi2 / dof 0.961 at 10,000 frames, 1 px, seed 2:
    2.7 standard deviations), and the sample then took the reconstruction from 2.2 s to 8.2 s.
    The noise-free wrong basins above had chi2 / dof 0.001-0.27; up to 20 frames the tail
    probability 1e-2 is the tighter rule (chi2 / dof below 0.36), so the figures above stand."""


@dataclass(frozen=True)
class LabelOptions:
    """Which end is A in each frame, where the input does not say (``robust/labels.py``;
    ``"ends_identified": false``)."""

    starts: int = 16
    """Grid minima polished by the label search (a few compass and LM steps)."""
    candidates: int = 6
    """Distinct polished shapes scored by their maximum-likelihood chi2 (``frame_labels``)."""
    distinct: float = 0.02
    """``robust.search.shape_distance`` below which two polished shapes are one."""
    truncate_chi2: float = 25.0
    """A frame's chi2 counts at most this in a candidate's score (outlier frames)."""
    plausible_score: float = 2.0
    """The candidates are scored in the pose-free cost's order until one scores at most this
    per frame (each frame has one degree of freedom beyond its pose: chi2 about 1 a frame,
    plus the undecided frames' penalty, up to ``undecided_dchi2`` each; on 20-frame scenes
    the truth scored 0.7-2.4 a frame, wrong candidates 3-10; bench seed, 60 scenes of 20
    frames, with every candidate refined again: at 2.5 success 90.0 % and time ratio 1.76,
    at 2.0 93.3 % and 1.96, at 1.5 93.3 % and 2.14, never stopping 93.3 % and 2.53: a first
    candidate scoring 2.1 a frame stopped the scoring where the truth's basin, later in the
    order, scores 1.7)."""
    final_rounds: int = 2
    """Every candidate refined again from its own shape and labels, while its score falls (a
    frame labelled wrong at the first refinement's shape turns an outlier of the pipeline and
    costs it an LO-RANSAC run; 20 frames, 1 px, bench seed: a candidate 0.06 from the truth
    scored 65.8 after one refinement, 30.1 after three, where the truth scores 29.7; the best
    candidate alone refined again: success 88.3 %, time ratio 1.94; every candidate: 90.0 %,
    1.76, with ``plausible_score`` 2.5)."""
    refine_iterations: int = 15
    """Maximum-likelihood iterations of each candidate before it is scored."""
    grid_frames_factor: int = 2
    """The grid of ``GridSpec.for_frames`` for this many times the frames (every frame is
    costed in both labellings: a grid as coarse as the search's for twice the frames)."""
    curve_grid: tuple[int, int, int, int] = (8, 24, 24, 25)
    """With polylines, the pose-free cost's grid at least this fine in (gamma, alpha, beta,
    phi): the truth's basin is narrow where every frame may take either labelling (held-out
    curve scenes of seed 7, 16 frames, 0.5 px: the label search ended within 0.02 of the truth
    in 25 of 48 with the grid for 32 frames, (5, 16, 16, 17), in 38 with this one, 40 with
    (10, 28, 28, 29) at 1.6 times its cost).  Without polylines the finer grid cost its time
    in every run (20 frames, 1 px: time ratio 2.3 against 1.9) for one scene of 60 right up
    to the warned naming."""
    compass_iterations: int = 10
    """Compass steps of the pose-free cost from each grid minimum."""
    undecided_dchi2: float = 4.0
    """A frame whose two labellings' chi2 differ by less is undecided (warned about)."""
    switch_dchi2: float = 4.0
    """At the answer, a frame is relabelled (and the pipeline run again) when its other
    labelling fits better by this: a frame that fits both about equally barely moves the
    answer, and a rerun costs a whole reconstruction (12 scenes of 20 frames: 3 reruns at 1.0,
    2 at 4.0)."""
    max_rounds: int = 2
    """Pipeline reruns after a frame's labelling changed at the answer."""
    polyline_check: bool = True
    """With polylines, judge the labels by the curve's fit to them (``curve.labels``)."""
    polyline_dchi2: float = 25.0
    """Frames whose two labellings' chi2 differ by less are judged by their polylines too
    (every frame where the tangents were fitted to the polylines, and frame 0)."""
    polyline_ratio: float = 0.6
    """A polyline decides a frame's labelling where one direction's fit RMS is below this
    fraction of the other's."""
    unsettled_fit: float = 2.0
    """With polylines, where the quick curve fits the polylines (mean over frames of the closer
    direction's RMS) worse than this many times their noise, the labels are judged again at
    the pipeline's end-point answer before its first full run (held-out curve scenes of seed
    7, 0.5 px polylines: 1.4-3.4 px in the six scenes whose first full run met frames labelled
    wrong, 1.6-5.3 s against 0.2-0.5 s consistent, at most 1.2 px in the other 42; time
    ratio 1.89 against 4.70, docs/accuracy.md)."""


@dataclass
class ReconstructOptions:
    """Everything :func:`curverecon.reconstruct` can be told.

    Attributes:
        method: "auto" (search, refinement, outliers, curve) or "linear" (the paper's
            linearisation alone; at least ``solvers.linear.min_frames()`` frames).
        estimator: "marginal" (poses integrated out; less biased at realistic noise) or "ml".
        point_sigma: image point noise (input units).
        tangent_sigma_deg: tangent direction noise (degrees).
        progress: show a progress bar on stderr (the command: when stderr is a terminal and
            not ``--quiet``).
    """

    method: str = "auto"
    estimator: str = "marginal"
    marginal_max_frames: int = 20_000
    """From this many inlier frames on, the answer is the maximum-likelihood fit even with
    ``estimator="marginal"`` (and a warning says so).  There the marginal likelihood's objective
    is resolved only to the jumps of the frames near a fold of (10) (``refine.marginal``), not to
    the scale of its own correction: on ``make_scene`` 1 px / 1 deg scenes its answer at 30,000
    frames was the maximum-likelihood one (c 14.4 standard deviations off both ways, seed 2), at
    100,000 frames it moved c from 27.1 to -25.2 standard deviations (seed 2) and from 36.5 to
    6.4 (seed 1002), and took 15 to 20 of the 29 to 36 seconds.  At 10,000 frames it still
    moved c from 9.7 to -5.9 (seed 2)."""
    point_sigma: float = 1.0
    tangent_sigma_deg: float = 1.0
    progress: bool = False
    search: SearchOptions = field(default_factory=SearchOptions)
    outliers: OutlierOptions = field(default_factory=OutlierOptions)
    branches: BranchOptions = field(default_factory=BranchOptions)
    curve: CurveOptions = field(default_factory=CurveOptions)
    minimal: MinimalOptions = field(default_factory=MinimalOptions)
    frame_samples: FrameSampleOptions = field(default_factory=FrameSampleOptions)
    few_frame_samples: FewFrameSampleOptions = field(default_factory=FewFrameSampleOptions)
    labels: LabelOptions = field(default_factory=LabelOptions)
