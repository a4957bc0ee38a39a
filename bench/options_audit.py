"""Which options earn their place: every option set to its neutral value on a fixed scene suite.

``python -m bench.options_audit [--jobs N] [--out DIR] [--only NAME ...] [--max-seconds S]``

The suite (``suite()``, about 45 seeded scenes) spans what ``make bench`` reports: few frames
(4, 5, 6, 8; noise-free and 1 px), the headline cell (20 frames, 1 px, 1 degree), outlier frames
(gross and random-tangent, 10 % and 30 %), long sequences (1,000 and 10,000 frames), curves with
polylines (every family, 12 and 20 frames), polylines only, noise-free curves, the linear seed
(50 noise-free frames) and a traced rendered sequence.

1. Defaults: every scene is reconstructed once; its reconstruction JSON and figures are kept,
   and every read of an option field is logged (``__getattribute__`` of each options class,
   reads made by ``dataclasses.replace`` left out: copying is not using).
2. Each option that some scene reads is set to its neutral value (``NEUTRAL``: off, zero
   restarts, the loosest sensible tolerance) on every instance (the patched
   ``__getattribute__`` returns it), and only the scenes that read it run again, cheapest
   first.  A scene's outcome is "identical" (the same JSON), "output" (another JSON, no figure
   moved) or a list of the figures that moved: success (worst angle below 5 degrees), the
   outlier flags, the shape error (0.01 degree or 1 % of the relative c error), the std
   (1 %), curve3d's error (1 % and 1e-5 of the length), an exception, and the time (total over
   the scenes run, beyond 1.5x either way).  An option stops at its first scene whose figures
   moved.

Writes DIR/defaults.json (the reconstruction JSON of every scene at defaults), DIR/reads.json
and DIR/audit.json (per option: neutral value, scenes read, verdict, the figures that moved).
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import hashlib
import io
import json
import math
import multiprocessing
import sys
import time
import warnings
from pathlib import Path
from typing import Any

import numpy as np

INF = math.inf
NEVER = 10**9

# (class, field) -> neutral value.  Fields missing here are not options of their own:
# ReconstructOptions' containers, its API arguments, MinimalOptions.homotopy (the tracker's).
NEUTRAL: dict[tuple[str, str], Any] = {
    ("SearchOptions", "candidates"): 1,
    ("SearchOptions", "candidates_few"): 1,
    ("SearchOptions", "candidates_minimal"): 1,
    ("SearchOptions", "restarts"): 0,
    ("SearchOptions", "restarts_few"): 0,
    ("SearchOptions", "restarts_implausible"): 0,
    ("SearchOptions", "near_exact_chi2"): 0.0,
    ("SearchOptions", "exact_cost"): 0.0,
    ("SearchOptions", "exact_reduced_cost"): 0.0,
    ("SearchOptions", "exact_stage_starts"): 0,
    ("SearchOptions", "exact_stage_min_frames"): NEVER,
    ("SearchOptions", "screen_iterations"): 100,
    ("SearchOptions", "screen_ftol"): 1e-3,
    ("SearchOptions", "restart_finalists"): 1,
    ("SearchOptions", "rescue_chi2"): INF,
    ("SearchOptions", "rescue_deltas"): 1,
    ("SearchOptions", "rescue_before_fit_frames"): NEVER,
    ("SearchOptions", "max_search_frames"): NEVER,
    ("SearchOptions", "medium_frames"): NEVER,
    ("SearchOptions", "medium_keep_cost"): INF,
    ("SearchOptions", "medium_merge_distance"): 0.0,
    ("SearchOptions", "ladder_factor"): NEVER,
    ("SearchOptions", "linear_seed_gap"): INF,
    ("OutlierOptions", "false_alarm"): 1e-300,
    ("OutlierOptions", "cauchy_k"): 1e6,
    ("OutlierOptions", "trim_steps"): 0,
    ("OutlierOptions", "batch_frames"): NEVER,
    ("OutlierOptions", "leverage_floor"): 1e-9,
    ("OutlierOptions", "take_back_chi2"): INF,
    ("BranchOptions", "ambiguous_dchi2"): 0.0,
    ("BranchOptions", "flip_dchi2"): 0.0,
    ("BranchOptions", "flip_max_frames"): 0,
    ("BranchOptions", "alternative_dchi2"): 0.0,
    ("BranchOptions", "mixture_dchi2"): 0.0,
    ("CurveOptions", "bundle"): False,
    ("CurveOptions", "traced_tangents_retry"): False,
    ("CurveOptions", "flip_dchi2"): 0.0,
    ("CurveOptions", "flip_gain"): 1.0,
    ("CurveOptions", "flip_max_switches"): 0,
    ("CurveOptions", "search_samples"): 200,
    ("CurveOptions", "curve_search_max_frames"): NEVER,
    ("CurveOptions", "bundle_max_frames"): NEVER,
    ("CurveOptions", "bundle_start_from_search"): False,
    ("CurveOptions", "refit_with_bundle"): False,
    ("CurveOptions", "refit_dchi2"): 0.0,
    ("CurveOptions", "refit_gain"): 1.0,
    ("CurveOptions", "refit_rounds"): 0,
    ("CurveOptions", "refit_same_tol"): 0.0,
    ("CurveOptions", "bundle_max_control_points"): 12,
    ("CurveOptions", "bundle_misfit_z"): INF,
    ("CurveOptions", "polylines_only_control_points"): (),
    ("CurveOptions", "frame0_branch_dchi2"): 0.0,
    ("CurveOptions", "frame0_branch_same_deg"): 0.0,
    ("CurveOptions", "frame0_branch_first_iter"): 0,
    ("CurveOptions", "bundle_extra_starts"): 0,
    ("CurveOptions", "bundle_smooth_weight"): 0.0,
    ("CurveOptions", "bundle_order_tol"): 0.0,
    ("CurveOptions", "never_worse_dchi2"): INF,
    ("CurveOptions", "never_worse_f_test"): False,
    ("CurveOptions", "never_worse_polyline_level"): 0.0,
    ("CurveOptions", "never_worse_alternatives"): False,
    ("CurveOptions", "refused_std_disagreement"): False,
    ("CurveOptions", "restart_coarse_cost_ratio"): INF,
    ("CurveOptions", "rival_minima_std"): False,
    ("CurveOptions", "rival_warning_probability"): 2.0,
    ("CurveOptions", "variance_floor"): 1e-300,
    ("CurveOptions", "flag_rms_sigma"): INF,
    ("CurveOptions", "flag_rms_px"): 0.0,
    ("CurveOptions", "max_flagged_fraction"): 1.0,
    ("CurveOptions", "max_control_points"): 12,
    ("CurveOptions", "exact_start_control_points"): 12,
    ("CurveOptions", "exact_unfold"): 0,
    ("CurveOptions", "exact_restart_control_points"): 0,
    ("CurveOptions", "exact_restart_rms"): INF,
    ("CurveOptions", "exact_variance_factor"): 0.0,
    ("CurveOptions", "fixed_pose_reverse_factor"): 1.0,
    ("CurveOptions", "fixed_pose_abs_tol"): 1e-4,
    ("CurveOptions", "fixed_pose_resolution"): 1e-4,
    ("CurveOptions", "fixed_pose_smooth_weight"): 0.1,
    ("CurveOptions", "fixed_pose_smooth_factor"): 1.0,
    ("MinimalOptions", "polish_iterations"): 0,
    ("MinimalOptions", "duplicate_frames"): 0.0,
    ("MinimalOptions", "tangent_along_chord_deg"): 0.0,
    ("FrameSampleOptions", "enabled"): False,
    ("FrameSampleOptions", "min_frames"): 5,
    ("FrameSampleOptions", "max_frames"): NEVER,
    ("FrameSampleOptions", "truncate"): 25.0,
    ("FrameSampleOptions", "trigger_p_value"): 0.0,
    ("FrameSampleOptions", "min_samples"): 0,
    ("FrameSampleOptions", "max_samples"): 1000,
    ("FrameSampleOptions", "success_prob"): 0.9,
    ("FrameSampleOptions", "dyn_num_trials_mult"): 1.0,
    ("FrameSampleOptions", "score"): "tangent",
    ("FrameSampleOptions", "seed"): 1,
    ("FrameSampleOptions", "final_refinements"): 0,
    ("FrameSampleOptions", "distinct_deg"): 0.0,
    ("FrameSampleOptions", "chord_weight"): 0.0,
    ("FrameSampleOptions", "chord_prior"): False,
    ("FrameSampleOptions", "search_answer_start"): False,
    ("FrameSampleOptions", "anneal_steps"): 0,
    ("FrameSampleOptions", "anneal_start"): 1.0,
    ("FrameSampleOptions", "lo_rounds"): 1,
    ("FrameSampleOptions", "consensus_start"): False,
    ("FewFrameSampleOptions", "enabled"): False,
    ("FewFrameSampleOptions", "min_frames"): 4,
    ("FewFrameSampleOptions", "max_frames"): NEVER,
    ("FewFrameSampleOptions", "samples"): 0,
    ("FewFrameSampleOptions", "refine_per_sample"): 1,
    ("FewFrameSampleOptions", "precise_p_value"): 0.0,
    ("FewFrameSampleOptions", "precise_chi2_ratio"): INF,
    ("ReconstructOptions", "marginal_max_frames"): NEVER,
    ("TraceOptions", "dark_curve"): False,
    ("TraceOptions", "low_fraction"): 0.0,
    ("TraceOptions", "centre_iterations"): 0,
    ("TraceOptions", "max_shift"): INF,
    ("TraceOptions", "junction_radius_widths"): 0.0,
    ("TraceOptions", "spur_widths"): 0.0,
    ("TraceOptions", "max_gap_widths"): 0.0,
    ("TraceOptions", "max_gap_angle_deg"): 180.0,
    ("TraceOptions", "min_length"): 0.0,
    ("TraceOptions", "border_margin"): 0.0,
    ("TraceOptions", "end_search_widths"): 0.0,
    ("TraceOptions", "ambiguity_ratio"): 1.0,
}
"""The neutral value of every option: off, none, the simplest choice, the loosest tolerance.
TraceOptions' width, high_sigmas, low_sigmas, end_direction_widths and tangent_fit_length
are scales of the input with no neutral value (measured on the trace bench, kept)."""

# The full branch search on every frame of a 1,000-frame curve takes hours (section 4 is
# O(N^2) per candidate switch, ``CurveOptions.curve_search_max_frames``): only shorter scenes.
SCENE_CAP_FRAMES = {("CurveOptions", "curve_search_max_frames"): 200}


def option_classes() -> dict[str, type]:
    from curverecon.options import (
        BranchOptions,
        CurveOptions,
        FewFrameSampleOptions,
        FrameSampleOptions,
        MinimalOptions,
        OutlierOptions,
        ReconstructOptions,
        SearchOptions,
    )
    from curverecon.robust.ransac import RansacOptions
    from curverecon.solvers.homotopy import HomotopyOptions
    from curverecon.trace.options import TraceOptions

    classes = [
        SearchOptions,
        OutlierOptions,
        BranchOptions,
        CurveOptions,
        MinimalOptions,
        FrameSampleOptions,
        FewFrameSampleOptions,
        ReconstructOptions,
        TraceOptions,
        RansacOptions,
        HomotopyOptions,
    ]
    return {c.__name__: c for c in classes}


READS: set[tuple[str, str]] = set()
OVERRIDE: dict[tuple[str, str], Any] = {}


def _copying(frame: Any) -> bool:
    name = frame.f_code.co_filename
    return name.endswith("dataclasses.py") or name.startswith("<")


def install() -> None:
    """Log every read of an option field and return ``OVERRIDE``'s value where one is set."""
    for cname, cls in option_classes().items():
        names = frozenset(f.name for f in dataclasses.fields(cls))

        def getattribute(self, name, _names=names, _c=cname):
            if name in _names:
                key = (_c, name)
                if not _copying(sys._getframe(1)):
                    READS.add(key)
                if key in OVERRIDE:
                    return OVERRIDE[key]
            return object.__getattribute__(self, name)

        cls.__getattribute__ = getattribute


# ---------------------------------------------------------------------------------------------
# the scene suite


def _sim(seed, group, key, frames, noise, **kw):
    from bench.common import make

    return make(seed, group, key, frames, point_sigma=noise, tangent_sigma_deg=noise, **kw)


def _curve_scene(seed, frames, noise, family):
    from curverecon.simulate import make_scene

    sc = make_scene(
        np.random.default_rng(seed), frames, noise, noise, with_curve=True, curve_family=family
    )
    return sc


def suite() -> list[dict[str, Any]]:
    """The scenes: name, a builder of (observations, truth dict), the noise given."""
    s: list[dict[str, Any]] = []

    def add(name, build, noise=1.0, base=None):
        s.append({"name": name, "build": build, "noise": noise, "base": base or {}})

    for frames in (4, 5, 6, 8):
        for noise, k in ((0.0, 0), (1.0, 1)):
            add(f"few{frames}_n{noise:g}", ("sim", 2026, "accuracy", (frames, k), frames, noise))
    add("few6_n1_b", ("sim", 2026, "accuracy", (6, 2), 6, 1.0))
    add("few10_n1", ("sim", 2026, "accuracy", (10, 1), 10, 1.0))
    for k in range(4):
        add(f"headline20_{k}", ("sim", 2026, "accuracy", (20, k), 20, 1.0))
    add("nf15", ("sim", 2026, "stability", (15, 0), 15, 0.0))
    add("linear50_nf", ("sim", 2026, "stability", (50, 0), 50, 0.0))
    for frac, ks in ((0.1, (0, 1)), (0.3, (0, 1))):
        for k in ks:
            add(
                f"gross{int(frac * 100)}_{k}",
                ("sim", 20260521, "robustness", (int(frac * 100), k), 20, 1.0, frac, "gross"),
            )
    for frac, ks in ((0.1, (0, 1)), (0.3, (0, 1, 2))):
        for k in ks:
            add(
                f"random{int(frac * 100)}_{k}",
                ("sim", 20260521, "outliers_random", (int(frac * 100), k), 20, 1.0, frac, "random"),
            )
    add("long1000", ("plain", 2, 1000, 1.0))
    for i, fam in enumerate(("bezier", "helix", "clothoid", "fourier", "sharp-ends", "random")):
        add(f"curve20_{fam}", ("curve", 1400 + i, 20, 0.5, fam, True), 0.5)
    for i, fam in enumerate(("bezier", "helix", "random")):
        add(f"curve12_{fam}", ("curve", 1200 + i, 12, 1.0, fam, True), 1.0)
    add("curve12_05_clothoid", ("curve", 1102, 12, 0.5, "clothoid", True), 0.5)
    for i, fam in enumerate(("fourier", "helix")):
        add(f"curve8_nf_{fam}", ("curve", 7000 + i, 8, 0.0, fam, True), 0.0)
    for i, fam in enumerate(("bezier", "clothoid")):
        add(f"polyonly12_{fam}", ("curve", 1300 + i, 12, 0.5, fam, False), 0.5)
    # the never-worse gate's refusals and bands (docstrings of CurveOptions.never_worse_*)
    add("curve12_random_1205", ("curve", 1205, 12, 1.0, "random", True), 1.0)
    add("curve12_05_helix_1105", ("curve", 1105, 12, 0.5, "helix", True), 0.5)
    add("curve12_sharp_6001", ("curve", 6001, 12, 1.0, "sharp-ends", True), 1.0)
    # the bench's runs without the bundle (bench.bundle's never-worse pairs)
    off = {("CurveOptions", "bundle"): False}
    add("nobundle12_bezier", ("curve", 1200, 12, 1.0, "bezier", True), 1.0, off)
    add("nobundle12_random_1205", ("curve", 1205, 12, 1.0, "random", True), 1.0, off)
    add("curve1000_bezier", ("curve", 1400, 1000, 1.0, "bezier", True), 1.0)
    add("traced_bezier", ("trace", 0), 1.0)
    add("traced_helix", ("trace", 1), 1.0)
    add("long10000", ("plain", 2, 10_000, 1.0))
    return s


_TRACE_CACHE: dict[int, Any] = {}


def _traced(seed: int):
    from curverecon.io import OBSERVATIONS_FORMAT, observations_from_dict
    from curverecon.trace.ends import assign_ends, frame_record
    from curverecon.trace.frame import trace_image
    from curverecon.trace.options import TraceOptions
    from curverecon.trace.render import render_frame, tumbling_scene
    from curverecon.trace.topology import TraceFailure

    rng = np.random.default_rng(seed)
    scene = tumbling_scene(rng, 16, family=("bezier", "helix", "wave")[seed % 3])
    o = TraceOptions()
    curves, index, first = [], [], None
    for k, truth in enumerate(scene.observations.curves):
        img = render_frame(truth, rng) / 255.0
        try:
            curves.append(trace_image(img, o).curve)
        except TraceFailure:
            continue
        first = k if first is None else first
        index.append(k)
    assignment = assign_ends(curves, o.ambiguity_ratio, index, fit_length=o.tangent_fit_length)
    oriented = [c[::-1] if f else c for c, f in zip(curves, assignment.flip, strict=True)]
    frames = [frame_record(c, o.tangent_fit_length) for c in oriented]
    doc = {"format": OBSERVATIONS_FORMAT, "frames": frames, "tangents_from_curve": True}
    t = scene.truth
    local = (scene.curve_3d - t.A3[0]) @ t.rotations[0]
    true_curve = local @ t.rotations[first].T + t.A3[first]
    a_first = np.hypot(*(oriented[0][0] - scene.observations.curves[first][0]))
    b_first = np.hypot(*(oriented[0][0] - scene.observations.curves[first][-1]))
    if b_first < a_first:
        true_curve = true_curve - [0.0, 0.0, true_curve[-1, 2]]
    truth = {"curve": true_curve, "n_traced": len(curves)}
    return observations_from_dict(doc), truth


def build(spec: tuple, trace_options_changed: bool) -> tuple[Any, dict[str, Any]]:
    """Observations and what the figures compare with."""
    from bench.common import true_poses

    kind = spec[0]
    if kind == "sim":
        _, seed, group, key, frames, noise, *rest = spec
        kw = {}
        if rest:
            kw = {"outlier_fraction": rest[0], "outlier_model": rest[1]}
        sc = _sim(seed, group, key, frames, noise, **kw)
        shape, _ = true_poses(sc)
        return sc.observations, {"shape": shape, "inliers": sc.truth.inliers}
    if kind == "plain":
        from curverecon.simulate import make_scene

        _, seed, frames, noise = spec
        sc = make_scene(np.random.default_rng(seed), frames, noise, noise)
        return sc.observations, {"shape": true_poses(sc)[0], "inliers": sc.truth.inliers}
    if kind == "curve":
        from bench.bundle import obs_without

        _, seed, frames, noise, fam, ends = spec
        sc = _curve_scene(seed, frames, noise, fam)
        obs = sc.observations if ends else obs_without(sc.observations, True, False)
        return obs, {"shape": true_poses(sc)[0], "curve": sc.curve_3d}
    seed = spec[1]
    if trace_options_changed or seed not in _TRACE_CACHE:
        got = _traced(seed)
        if trace_options_changed:
            return got
        _TRACE_CACHE[seed] = got
    return _TRACE_CACHE[seed]


def figures(rec: Any, truth: dict[str, Any]) -> dict[str, Any]:
    from bench.common import shape_errors, worst_angle_deg
    from bench.curve_end_to_end import curve_error

    out: dict[str, Any] = {}
    if "shape" in truth:
        err = shape_errors(np.asarray(rec.shape, float), truth["shape"])
        out["worst_deg"] = worst_angle_deg(err)
        out["c_rel"] = abs(float(err[0]))
        out["success"] = out["worst_deg"] < 5.0
    out["flags"] = [int(i) for i in rec.outlier_frames()]
    out["std"] = None if rec.std is None else [float(v) for v in rec.std]
    if "curve" in truth and rec.curve3d is not None:
        out["curve_err"] = float(curve_error(np.asarray(rec.curve3d), truth["curve"]))
    return out


def run_scene(scene: dict[str, Any], trace_changed: bool) -> dict[str, Any]:
    from curverecon.pipeline import reconstruct

    obs, truth = build(scene["build"], trace_changed)
    audited = dict(OVERRIDE)
    OVERRIDE.update(scene["base"])
    OVERRIDE.update(audited)
    noise = max(scene["noise"], 1e-9) if scene["noise"] > 0 else None
    t0 = time.process_time()
    out: dict[str, Any] = {}
    try:
        with warnings.catch_warnings(), contextlib.redirect_stderr(io.StringIO()):
            warnings.simplefilter("ignore")
            if noise is None:
                rec = reconstruct(obs)
            else:
                rec = reconstruct(obs, point_sigma=noise, tangent_sigma_deg=noise)
        doc = rec.to_json_dict()
        text = json.dumps(doc, sort_keys=True, default=float)
        out["hash"] = hashlib.sha256(text.encode()).hexdigest()
        out["doc"] = doc
        out["figures"] = figures(rec, truth)
    except Exception as exc:  # a refusal is an outcome like any other
        out["exception"] = f"{type(exc).__name__}: {str(exc)[:200]}"
        out["hash"] = "exception:" + out["exception"]
    out["seconds"] = time.process_time() - t0
    OVERRIDE.clear()
    OVERRIDE.update(audited)
    return out


def _rel_moved(a: float, b: float, rel: float, floor: float) -> bool:
    if a == b:
        return False
    if not (math.isfinite(a) and math.isfinite(b)):
        return True
    return abs(a - b) > max(rel * max(abs(a), abs(b)), floor)


def moved(base: dict[str, Any], new: dict[str, Any]) -> list[str]:
    """The figures that differ between two outcomes of one scene."""
    if base["hash"] == new["hash"]:
        return []
    if ("exception" in base) != ("exception" in new):
        return ["exception"]
    if "exception" in base:
        return ["exception"]
    a, b = base["figures"], new["figures"]
    out = []
    if a.get("success") != b.get("success"):
        out.append("success")
    if a["flags"] != b["flags"]:
        out.append("outlier flags")
    if "worst_deg" in a:
        if _rel_moved(a["worst_deg"], b["worst_deg"], 0.0, 0.01):
            out.append("shape error")
        elif _rel_moved(a["c_rel"], b["c_rel"], 0.01, 1e-9):
            out.append("shape error")
    if (a["std"] is None) != (b["std"] is None):
        out.append("std")
    elif a["std"] is not None and any(
        _rel_moved(x, y, 0.01, 1e-12) for x, y in zip(a["std"], b["std"], strict=True)
    ):
        out.append("std")
    if ("curve_err" in a) != ("curve_err" in b):
        out.append("curve3d error")
    elif "curve_err" in a and _rel_moved(a["curve_err"], b["curve_err"], 0.01, 1e-5):
        out.append("curve3d error")
    return out or ["output"]


def _describe(base: dict[str, Any], new: dict[str, Any]) -> str:
    if "exception" in new or "exception" in base:
        return f"{base.get('exception', 'ok')} -> {new.get('exception', 'ok')}"
    a, b = base["figures"], new["figures"]
    parts = []
    if "worst_deg" in a:
        parts.append(f"worst {a['worst_deg']:.3g} -> {b['worst_deg']:.3g} deg")
    if a["flags"] != b["flags"]:
        parts.append(f"flags {a['flags']} -> {b['flags']}")
    if "curve_err" in a and "curve_err" in b:
        parts.append(f"curve {100 * a['curve_err']:.3g} -> {100 * b['curve_err']:.3g} %")
    if a["std"] and b["std"]:
        r = [y / x if x > 0 else INF for x, y in zip(a["std"], b["std"], strict=True)]
        parts.append(f"std x{min(r):.3g} to x{max(r):.3g}")
    return "; ".join(parts)


# ---------------------------------------------------------------------------------------------
# the two passes


def defaults_pass(scenes: list[dict[str, Any]]) -> dict[str, Any]:
    out = {}
    for sc in scenes:
        READS.clear()
        res = run_scene(sc, False)
        res["reads"] = sorted(f"{c}.{n}" for c, n in READS)
        out[sc["name"]] = res
        print(f"defaults {sc['name']}: {res['seconds']:.1f} s", file=sys.stderr, flush=True)
    return out


def audit_option(task: tuple) -> dict[str, Any]:
    key, value, scene_names, base, max_seconds = task
    install()
    scenes = {s["name"]: s for s in suite()}
    OVERRIDE.clear()
    OVERRIDE[key] = value
    trace_changed = key[0] == "TraceOptions"
    rows, spent, spent_base, verdict = [], 0.0, 0.0, "identical"
    for name in scene_names:
        if spent > max_seconds:
            verdict = verdict + " (partial)" if "partial" not in verdict else verdict
            break
        new = run_scene(scenes[name], trace_changed)
        spent += new["seconds"]
        spent_base += base[name]["seconds"]
        what = moved(base[name], new)
        row = {"scene": name, "moved": what, "seconds": [base[name]["seconds"], new["seconds"]]}
        if what and what != ["output"]:
            row["detail"] = _describe(base[name], new)
        rows.append(row)
        if what == ["output"] and verdict == "identical":
            verdict = "output"
        if what and what != ["output"]:
            verdict = "figure"
            break
    ratio = spent / spent_base if spent_base > 0 else 1.0
    if verdict in ("identical", "output") and (ratio > 1.5 or ratio < 1 / 1.5) and spent > 1.0:
        verdict = "time"
    return {
        "option": f"{key[0]}.{key[1]}",
        "neutral": repr(value),
        "verdict": verdict,
        "time_ratio": round(ratio, 2),
        "scenes": rows,
    }


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(prog="python -m bench.options_audit")
    p.add_argument("--out", default="bench/options_audit_out")
    p.add_argument("--jobs", type=int, default=1)
    p.add_argument("--only", nargs="*", default=None, help="Class.field names")
    p.add_argument("--max-seconds", type=float, default=300.0)
    p.add_argument("--reuse-defaults", action="store_true")
    p.add_argument("--resume", action="store_true", help="keep the options audit.json has")
    p.add_argument("--table", action="store_true", help="print audit.json as a markdown table")
    args = p.parse_args(argv)
    out = Path(args.out)
    if args.table:
        print(markdown(json.loads((out / "audit.json").read_text())), end="")
        return
    out.mkdir(parents=True, exist_ok=True)
    install()
    scenes = suite()
    dpath = out / "defaults.json"
    if args.reuse_defaults and dpath.exists():
        base = json.loads(dpath.read_text())
    else:
        base = defaults_pass(scenes)
        dpath.write_text(json.dumps(base, default=float))
    reads: dict[str, list[str]] = {}
    for name, res in base.items():
        for r in res["reads"]:
            reads.setdefault(r, []).append(name)
    (out / "reads.json").write_text(json.dumps(reads, indent=1))
    order = _interleaved(base)
    frames_of = {s["name"]: _frames(s["build"]) for s in scenes}
    slim = {n: {k: v for k, v in r.items() if k != "doc"} for n, r in base.items()}
    tasks, results = [], []
    apath = out / "audit.json"
    if args.resume and apath.exists():
        results = [r for r in json.loads(apath.read_text()) if r["verdict"] != "unread"]
    done = {r["option"] for r in results}
    # the stages cheapest to audit first; the search and the curve (most scenes read them) last
    rank = {"SearchOptions": 1, "CurveOptions": 2}
    for key, value in sorted(NEUTRAL.items(), key=lambda kv: rank.get(kv[0][0], 0)):
        name = f"{key[0]}.{key[1]}"
        if (args.only is not None and name not in args.only) or name in done:
            continue
        read_on = [n for n in order if n in set(reads.get(name, ()))]
        cap = SCENE_CAP_FRAMES.get(key)
        if cap is not None:
            read_on = [n for n in read_on if frames_of[n] < cap]
        if not read_on:
            results.append({"option": name, "neutral": repr(value), "verdict": "unread"})
            continue
        tasks.append((key, value, read_on, slim, args.max_seconds))
    # one option a process: caches filled under another option's value must not answer
    with multiprocessing.Pool(args.jobs, initializer=_warm_up, maxtasksperchild=1) as pool:
        for res in pool.imap_unordered(audit_option, tasks):
            res["read_on"] = len(reads.get(res["option"], ()))
            results.append(res)
            print(json.dumps(res), flush=True)
            apath.write_text(json.dumps(results, indent=1))
    apath.write_text(json.dumps(results, indent=1))


def _default(name: str) -> str:
    cname, field = name.split(".")
    for f in dataclasses.fields(option_classes()[cname]):
        if f.name == field:
            if f.default is not dataclasses.MISSING:
                return repr(f.default)
            return repr(f.default_factory())  # type: ignore[misc]
    return "(removed)"


def _moved_text(r: dict[str, Any]) -> str:
    rows = r.get("scenes", [])
    hit = [x for x in rows if x["moved"] and x["moved"] != ["output"]]
    if hit:
        x = hit[0]
        return f"{x['scene']}: {', '.join(x['moved'])} ({x.get('detail', '')})"
    out = [x["scene"] for x in rows if x["moved"] == ["output"]]
    if out:
        return f"output only ({', '.join(out[:3])}{' ...' if len(out) > 3 else ''})"
    return ""


VERDICTS = {
    "unread": "unread",
    "identical": "identical",
    "output": "output, no figure",
    "figure": "figure",
    "time": "time",
}


def markdown(results: list[dict[str, Any]]) -> str:
    """The measurement table (docs/options-audit.md): one row per option."""
    lines = [
        "| option | default | neutral | scenes read | run | verdict | what moved (first scene) |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in sorted(results, key=lambda r: r["option"]):
        verdict = r["verdict"]
        base = verdict.replace(" (partial)", "")
        partial = " (partial)" if "partial" in verdict else ""
        ratio = r.get("time_ratio")
        what = _moved_text(r) or r.get("note", "")
        if ratio is not None and (ratio > 1.5 or ratio < 1 / 1.5):
            what = f"{what}; time x{ratio}".lstrip("; ")
        lines.append(
            f"| `{r['option']}` | `{r.get('default') or _default(r['option'])}` | "
            f"`{r['neutral']}` | "
            f"{r.get('read_on', 0)} | {len(r.get('scenes', []))} | "
            f"{VERDICTS.get(base, base)}{partial} | {what} |"
        )
    return "\n".join(lines) + "\n"


def _warm_up() -> None:
    """One scene at defaults before a worker's first option: its first-use costs (imports,
    numba's cache loads) must not count as the option's time."""
    install()
    run_scene(next(s for s in suite() if s["name"] == "few6_n1"), False)


STAGES = {
    "TraceOptions": "trace (`trace/`)",
    "SearchOptions": "1 hypotheses: the global search (`robust/search.py`)",
    "FewFrameSampleOptions": "1 hypotheses: few-frame samples (`robust/frame_samples.py`)",
    "MinimalOptions": "the minimal solver (`solvers/minimal.py`)",
    "OutlierOptions": "3 outlier frames (`robust/outliers.py`)",
    "FrameSampleOptions": "3 outlier frames: LO-RANSAC over four-frame samples",
    "BranchOptions": "pose branches, 4 equally good fits, 5 the final estimate",
    "ReconstructOptions": "5 the final estimate (`pipeline.py`)",
    "CurveOptions": "6 the curve (`curve/`)",
}


def stage_list(results: list[dict[str, Any]], gone: set[str]) -> str:
    """The options that stay, grouped by stage, each with the figure its neutral value moved."""
    lines = []
    for cname, title in STAGES.items():
        rows = [r for r in results if r["option"].startswith(cname + ".")]
        rows = [r for r in rows if r["option"] not in gone]
        if not rows:
            continue
        lines.append(f"- **{title}**")
        for r in sorted(rows, key=lambda r: r["option"]):
            field = r["option"].split(".")[1]
            what = _moved_text(r) or r.get("note") or r["verdict"]
            if r["verdict"].startswith("identical"):
                run = len(r.get("scenes", []))
                what = f"identical on {run} of {r.get('read_on', run)} scenes that read it"
            lines.append(f"  - `{field}` = `{_default(r['option'])}`: {what}")
    return "\n".join(lines) + "\n"


def _interleaved(base: dict[str, Any]) -> list[str]:
    """Scene names, one of each kind in turn (each kind cheapest first): an option whose
    neutral value moves a figure meets a scene of every kind early."""
    kinds: dict[str, list[str]] = {}
    for name in sorted(base, key=lambda n: base[n]["seconds"]):
        kinds.setdefault(name.split("_")[0].rstrip("0123456789"), []).append(name)
    out = []
    while any(kinds.values()):
        for names in kinds.values():
            if names:
                out.append(names.pop(0))
    return out


def _frames(spec: tuple) -> int:
    if spec[0] == "sim":
        return spec[4]
    if spec[0] in ("plain", "curve"):
        return spec[2]
    return 16


if __name__ == "__main__":
    main()
