"""Summaries of the raw records, the targets, the plots, ``REPORT.md`` and ``report.json``."""

from __future__ import annotations

import json
import math
import time
from pathlib import Path
from typing import Any

import numpy as np

from bench import accuracy, plan, robustness, stability
from bench.common import GROUPS, PARAMETERS, SUCCESS_DEG
from bench.config import Config
from bench.speed import SAME_COST_CHI2

STABILITY_PNG = "stability_histogram.png"
SCALING_PNG = "scaling.png"
ACCURACY_PNG = "accuracy_vs_frames.png"


# ------------------------------------------------------------------------------ summaries


def pooled_rate(rows: list[dict], key: str) -> float | None:
    """A rate over several stability rows pooled by their scene counts (None without scenes)."""
    n = sum(r.get("n", 0) for r in rows if r.get(key) is not None)
    if not n:
        return None
    return float(sum(r[key] * r["n"] for r in rows if r.get(key) is not None) / n)


def summarise(
    cfg: Config,
    results: dict[str, list[dict[str, Any]]],
    t_speed: float,
    t_experiments: float,
    available_cpu_s: float,
) -> dict[str, Any]:
    """Everything the report needs from the raw per-scene records."""
    cells: dict[tuple[float, int], list[dict[str, Any]]] = {}
    for noise in cfg.noise_levels:
        for n in cfg.frame_counts:
            cells[(noise, n)] = results.get(f"acc|{noise}|{n}", []) + results.get(
                f"accd|{noise}|{n}", []
            )
    acc_rows = accuracy.summarise(cells)
    head = cells[(cfg.headline_noise, cfg.headline_frames)]
    rob = [robustness.summarise_baseline(head)]
    for f in cfg.outlier_fractions:
        rob.append(robustness.summarise_records(results.get(f"rob|{f}", []), f))
    stab: dict[str, Any] = {"default": [], "linear": []}
    hist: dict[str, dict[int, list[float]]] = {"default": {}, "linear": {}}
    for n in cfg.stability_frames:
        recs = results.get(f"stab|{n}", [])
        stab["default"].append(
            {"n_frames": n, **stability.summarise_records(recs, cfg.failure_threshold)}
        )
        hist["default"][n] = [r["log10_error"] for r in recs]
    for n in cfg.stability_linear_frames:
        recs = results.get(f"lin|{n}", [])
        stab["linear"].append(
            {"n_frames": n, **stability.summarise_records(recs, cfg.failure_threshold)}
        )
        hist["linear"][n] = [r["log10_error"] for r in recs]
    all_default = [r for n in cfg.stability_frames for r in results.get(f"stab|{n}", [])]
    stab["default_all"] = stability.summarise_records(all_default, cfg.failure_threshold)
    stab["default_all"]["failure_rate_four_frames_listed"] = stability.failure_rate_listed_at_four(
        all_default, cfg.failure_threshold
    )
    req_stab, first = plan.stability_counts(cfg)
    req_lin = plan.split(cfg.stability_linear_scenes, cfg.stability_linear_frames)
    per_scene = plan.measured_seconds(results)
    counts = {
        "accuracy_default": [
            {
                "noise": k[0],
                "n_frames": k[1],
                "required": cfg.accuracy_default_scenes,
                "run": sum("default_s" in r for r in v),
            }
            for k, v in cells.items()
        ],
        "accuracy_cheap_parts": {
            "required": cfg.accuracy_scenes,
            "run_min": min(sum("truth_start_s" in r for r in v) for v in cells.values()),
        },
        "robustness": [
            {
                "fraction": f,
                "required": cfg.robustness_scenes,
                "run": len(results.get(f"rob|{f}", [])),
            }
            for f in cfg.outlier_fractions
        ],
        "stability": [
            {
                "n_frames": n,
                "required": req_stab[n],
                "priority": first.get(n, 0),
                "run": len(results.get(f"stab|{n}", [])),
            }
            for n in cfg.stability_frames
        ],
        "stability_linear": [
            {"n_frames": n, "required": req_lin[n], "run": len(results.get(f"lin|{n}", []))}
            for n in cfg.stability_linear_frames
        ],
        "per_scene_seconds": per_scene,
        "required_cpu_seconds": plan.required_cpu_seconds(cfg, per_scene),
        "available_cpu_seconds": available_cpu_s if math.isfinite(available_cpu_s) else None,
    }
    truth_conv = [r.get("truth_start_converged", True) for v in cells.values() for r in v]
    return {
        "accuracy": acc_rows,
        "robustness": rob,
        "stability": stab,
        "_histograms": hist,
        "counts": counts,
        "truth_start_not_converged_rate": float(1.0 - np.mean(truth_conv)) if truth_conv else None,
        "section_seconds": {"speed": t_speed, "scene_experiments": t_experiments},
    }


def _acc_row(sections: dict[str, Any], noise: float, n: int) -> dict[str, Any] | None:
    for row in sections["accuracy"]:
        if row["noise"] == noise and row["n_frames"] == n:
            return row
    return None


def headline(cfg: Config, sections: dict[str, Any]) -> dict[str, Any]:
    """The report.json headline keys and the targets (measured, PASS/MISS)."""
    sp = sections["speed"]
    row = _acc_row(sections, cfg.headline_noise, cfg.headline_frames)
    d = row["default"] if row else None
    ratio = d["ratio_worst"] if d and d.get("ratio") else None
    ratio_angle = d["ratio_worst_angle"] if d and d.get("ratio") else None
    success = d["success_rate"] if d else None
    stab_all = sections["stability"]["default_all"]
    stab6 = next((s for s in sections["stability"]["default"] if s["n_frames"] == 6), None)
    fd = sp["refine_vs_fd"]
    speedups = fair_speedups(fd)
    speedup = float(min(speedups)) if speedups else None
    same_cost = all(_same_cost(r, k) for r in fd for k in r if k.startswith("chi2_rel_diff_"))
    to_convergence = [r[f"speedup_{m}"] for r in fd for m in _fd_methods(r)]
    rec20 = sp["reconstruct_20"]["median_s"]
    ref1000 = sp["refine_1000"]["median_s"]
    ref_conv = bool(sp["refine_1000"].get("converged", True))
    out = {
        "derive_seconds": sp["derive"]["seconds"] if "derive" in sp else None,
        "rmse_over_crlb": ratio,
        "rmse_over_crlb_worst_angle": ratio_angle,
        "rmse_over_crlb_by_parameter": d["ratio"] if d and d.get("ratio") else None,
        "headline_scenes": d["n"] if d else 0,
        "success_rate_no_truth": success,
        # with exactly four frames the answer is the list of every real solution
        # (``alternatives``, with a warning that four frames cannot choose), so a four-frame
        # scene fails when the truth is not listed; from five frames on the answer itself must
        # be the truth.  The first-answer-only rate stays beside it.
        "noise_free_failure_rate": stab_all.get("failure_rate_four_frames_listed"),
        "noise_free_failure_rate_first_answer": stab_all.get("failure_rate"),
        # the target's key: over the 4-, 5- and 6-frame scenes together (truth among the
        # answer and its alternatives to the threshold), weighted by their numbers
        "noise_free_truth_not_listed_rate": pooled_rate(
            sections["stability"]["default"], "failure_rate_truth_not_listed"
        ),
        **{
            f"noise_free_truth_not_listed_rate_{s['n_frames']}_frames_stability": s.get(
                "failure_rate_truth_not_listed"
            )
            for s in sections["stability"]["default"]
        },
        **{
            f"noise_free_failure_rate_{s['n_frames']}_frames": s.get("failure_rate")
            for s in sections["stability"]["default"]
            if s["n_frames"] > 4
        },
        "refine_speedup_vs_finite_differences": speedup,
        "refine_same_cost_as_finite_differences": same_cost,
        "refine_speedup_to_convergence_min": float(min(to_convergence)) if to_convergence else None,
        "reconstruct_seconds_20_frames": rec20,
        "refine_seconds_1000_frames": ref1000,
        "refine_1000_frames_converged": ref_conv,
        "headline_worse_fit_than_truth_start_rate": d.get("worse_fit_than_truth_start_rate")
        if d
        else None,
        "headline_better_fit_than_truth_start_rate": d.get("better_fit_than_truth_start_rate")
        if d
        else None,
        # per cell (noise|frames): [default-only failures, of them in a basin of lower chi2]
        "default_only_failures_lower_chi2_by_cell": {
            f"{row['noise']:g}|{row['n_frames']}": [
                row["default"]["default_only_failures"],
                row["default"]["default_only_failures_lower_chi2"],
            ]
            for row in sections["accuracy"]
            if row["default"] and row["default"].get("default_only_failures") is not None
        },
        # success of the default, of the lower-chi2 basin of the default's and the truth's
        # (bench.accuracy: what a chi2 minimiser shown both would take) and of refinement from
        # the truth, per cell (noise|frames), in per cent
        "success_default_chi2_choice_truth_start_by_cell": {
            f"{row['noise']:g}|{row['n_frames']}": [
                round(100.0 * row["default"]["success_rate"], 1),
                round(100.0 * row["default"]["chi2_choice_success_rate"], 1),
                round(100.0 * row["truth_start"]["success_rate"], 1),
            ]
            for row in sections["accuracy"]
            if row["default"]
            and row.get("truth_start")
            and row["default"].get("chi2_choice_success_rate") is not None
        },
        # ... and of them polished to the very minimum the truth's refinement reaches
        "default_only_failures_same_minimum_by_cell": {
            f"{row['noise']:g}|{row['n_frames']}": row["default"].get(
                "default_only_failures_same_minimum"
            )
            for row in sections["accuracy"]
            if row["default"] and row["default"].get("default_only_failures") is not None
        },
    }

    def verdict(ok: bool | None) -> str:
        return "n/a" if ok is None else ("PASS" if ok else "MISS")

    rate9 = stab6.get("rate_below_1e-9") if stab6 and stab6.get("n") else None
    targets = [
        {
            "target": "noise-free, 6 frames: relative error <= 1e-9 in >= 99 % of scenes",
            "measured": None if rate9 is None else f"{100 * rate9:.1f} % (n = {stab6['n']})",
            "verdict": verdict(None if rate9 is None else rate9 >= 0.99),
        },
        {
            "target": "1 px + 1 deg, 20 frames: RMSE of each angle <= 1.2 x CRLB (default)",
            "measured": None
            if ratio_angle is None
            else f"{ratio_angle:.2f} x (worst angle, n = {d['n']})",
            "verdict": verdict(None if ratio_angle is None else ratio_angle <= 1.2),
        },
        {
            "target": "1 px + 1 deg, 20 frames: success >= 95 % without the truth",
            "measured": None if success is None else f"{100 * success:.1f} % (n = {d['n']})",
            "verdict": verdict(None if success is None else success >= 0.95),
        },
        {
            "target": "one full 20-frame reconstruction < 0.2 s",
            "measured": f"{rec20:.3f} s (median of {sp['reconstruct_20']['repeats']})",
            "verdict": verdict(rec20 < 0.2),
        },
        {
            "target": "refinement of 1000 frames < 1 s",
            "measured": f"{ref1000:.3f} s ({sp['refine_1000']['iterations']} iterations"
            + (
                ""
                if ref_conv
                else ", stopped at the iteration limit without converging: counted as a miss"
            )
            + ")",
            "verdict": verdict(ref1000 < 1.0 and ref_conv),
        },
        {
            "target": "generated-Jacobian refinement >= 20 x faster than finite differences",
            "measured": None
            if speedup is None
            else f"{speedup:.0f} x (slowest case, at equal quality)"
            + ("" if same_cost else "; where scipy stopped at a higher cost, timed to that cost"),
            "verdict": verdict(None if speedup is None else speedup >= 20),
        },
    ]
    return {"headline": out, "targets": targets}


def _same_cost(row: dict[str, Any], key: str) -> bool:
    return abs(row[key]) * row["generated_chi2"] < SAME_COST_CHI2


def _equal_cost_cell(row: dict[str, Any], method: str) -> str:
    """The report's 'at equal cost' cell: where scipy stopped at a higher cost, the generated
    refinement's time and iterations to that cost and the speedup then; else the same run."""
    if f"speedup_equal_cost_{method}" in row:
        return (
            f"{row[f'generated_equal_cost_{method}_s']:.4f} s, "
            f"{row[f'generated_equal_cost_{method}_iterations']} iterations: "
            f"{row[f'speedup_equal_cost_{method}']:.0f} x"
        )
    if _same_cost(row, f"chi2_rel_diff_{method}"):
        return "same cost"
    return "scipy lower"


def _fd_methods(row: dict[str, Any]) -> list[str]:
    """The scipy methods timed on one refinement problem (``speedup_<method>`` keys)."""
    return [m for m in ("lm", "trf") if f"speedup_{m}" in row]


def fair_speedups(fd: list[dict[str, Any]]) -> list[float]:
    """Per problem and scipy method, the speedup at equal quality: to convergence where both
    reach the same cost; to scipy's final cost where scipy stops higher
    (``speedup_equal_cost_<method>``); none where scipy ends lower (then the target fails)."""
    out = []
    for r in fd:
        for method in _fd_methods(r):
            if _same_cost(r, f"chi2_rel_diff_{method}"):
                out.append(r[f"speedup_{method}"])
            elif f"speedup_equal_cost_{method}" in r:
                out.append(r[f"speedup_equal_cost_{method}"])
            else:
                out.append(0.0)  # scipy found the lower cost: no equal-quality time
    return out


# ------------------------------------------------------------------------------ plots
def _plots(out: Path, cfg: Config, sections: dict[str, Any]) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import (
        FormatStrFormatter,
        LogLocator,
        NullFormatter,
        ScalarFormatter,
    )

    paths = []
    # stability histogram
    hist = sections["_histograms"]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=False)
    bins = np.arange(-17.5, 1.01, 0.5)
    for ax, key, title in (
        (axes[0], "default", "default pipeline (no truth)"),
        (axes[1], "linear", "linearisation alone"),
    ):
        any_data = False
        for n, vals in sorted(hist[key].items()):
            v = np.array(vals, float)
            if not v.size:
                continue
            any_data = True
            v = np.where(np.isfinite(v), np.clip(v, -17.0, 0.9), 0.9)
            ax.hist(v, bins=bins, histtype="step", linewidth=1.6, label=f"{n} frames (n={v.size})")
        ax.axvline(-9, color="0.4", linestyle=":", linewidth=1)
        ax.axvline(math.log10(cfg.failure_threshold), color="tab:red", linestyle="--", linewidth=1)
        ax.text(
            math.log10(cfg.failure_threshold) + 0.2,
            0.95,
            "failure\n> 1e-6",
            color="tab:red",
            transform=ax.get_xaxis_transform(),
            va="top",
            fontsize=8,
        )
        if not any_data:
            ax.text(0.5, 0.5, "no scenes ran", transform=ax.transAxes, ha="center")
        ax.set_xlim(bins[0], bins[-1])
        ax.set_yscale("log")
        ax.set_ylim(0.7, None)
        ax.set_title(f"noise-free scenes: {title}", fontsize=10)
        ax.set_xlabel("log10 error (max of |dc|/c and angle errors in rad)")
        ax.set_ylabel("scenes (log scale)")
        if any_data:
            ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    p = out / STABILITY_PNG
    fig.savefig(p, dpi=110)
    plt.close(fig)
    paths.append(p)

    # scaling
    sc = [r for r in sections["speed"]["scaling"] if not r.get("skipped")]
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    if sc:
        n = np.array([r["n_frames"] for r in sc], float)
        t = np.array([r["median_s"] for r in sc], float)
        ax.loglog(n, t, "o-", label="reconstruct (default pipeline)")
        ref = t[-1] * n / n[-1]
        ax.loglog(n, ref, ":", color="0.5", label="proportional to N (through the last point)")
        if len(n) >= 3:
            slope = np.polyfit(np.log(n[-3:]), np.log(t[-3:]), 1)[0]
            ax.text(
                0.03,
                0.95,
                f"slope of the last 3 points: {slope:.2f}",
                transform=ax.transAxes,
                va="top",
                fontsize=9,
            )
    r1000 = sections["speed"]["refine_1000"]
    ax.loglog(
        [r1000["n_frames"]],
        [r1000["median_s"]],
        "s",
        color="tab:green",
        label="refine from the truth (1000 frames)",
    )
    ax.axhline(0.2, color="tab:red", linestyle="--", linewidth=0.8)
    ax.text(
        ax.get_xlim()[0] * 1.1 if sc else 10,
        0.21,
        "0.2 s (target at 20 frames)",
        color="tab:red",
        fontsize=8,
    )
    ax.yaxis.set_major_formatter(ScalarFormatter())
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("frames N")
    ax.set_ylabel("wall time (s)")
    ax.set_title("reconstruction time against the number of frames", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    p = out / SCALING_PNG
    fig.savefig(p, dpi=110)
    plt.close(fig)
    paths.append(p)

    # accuracy vs frames (worst angle ratio)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, method in zip(axes, ("default", "truth_start"), strict=True):
        for noise in cfg.noise_levels:
            xs, ys = [], []
            for n in cfg.frame_counts:
                row = _acc_row(sections, noise, n)
                m = row[method] if row else None
                if m and m.get("ratio"):
                    xs.append(n)
                    ys.append(m["ratio_worst_angle"])
            if xs:
                ax.plot(xs, ys, "o-", label=f"{noise:g} px, {noise:g} deg")
        ax.axhline(1.0, color="0.5", linewidth=0.8, label="the bound")
        ax.axhline(1.2, color="tab:red", linestyle="--", linewidth=0.8, label="target 1.2 x")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xticks(cfg.frame_counts)
        ax.set_xticklabels([str(n) for n in cfg.frame_counts])
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.yaxis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
        ax.yaxis.set_major_formatter(FormatStrFormatter("%g"))
        ax.yaxis.set_minor_formatter(NullFormatter())
        lo, hi = ax.get_ylim()
        if hi / lo < 10:
            ax.yaxis.set_minor_formatter(FormatStrFormatter("%g"))
        ax.set_xlabel("frames")
        ax.set_ylabel("RMSE / CRLB (worst angle)")
        ax.set_title(accuracy.METHOD_TITLES[method], fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    p = out / ACCURACY_PNG
    fig.savefig(p, dpi=110)
    plt.close(fig)
    paths.append(p)
    return paths


# ------------------------------------------------------------------------------ markdown
def _f(v: Any, fmt: str = ".2f") -> str:
    if v is None:
        return "–"
    if isinstance(v, float) and not math.isfinite(v):
        return "inf"
    return format(v, fmt)


def _pct(v: float | None) -> str:
    return "–" if v is None else f"{100 * v:.1f} %"


def _ratio_cells(m: dict[str, Any] | None) -> list[str]:
    if not m or not m.get("ratio"):
        return ["–"] * 4
    return [_f(m["ratio"][p]) for p in PARAMETERS]


def _markdown(cfg: Config, sections: dict[str, Any], command: str, started: str) -> str:
    mach = sections["machine"]
    sp = sections["speed"]
    lines: list[str] = []
    add = lines.append
    add("# curverecon benchmark report")
    add("")
    add(
        "Measured in one run: accuracy of the shape (c, alpha, beta, phi) against the Cramér–Rao "
        "bound of the same measurement model, robustness (success without the truth, outlier "
        "frames), numerical stability on noise-free scenes, and speed (derivation, generated code "
        "against `sympy.lambdify`, analytic against finite-difference refinement, reconstruction "
        "time against the number of frames).  Scenes come from `curverecon.simulate.make_scene` "
        f"(random cubic curves, chord {cfg.chord[0]:g}–{cfg.chord[1]:g} px, random free motion, "
        "orthographic); the noise level sigma means sigma px on every image coordinate and sigma "
        "degrees on every tangent angle."
    )
    add("")
    make = " (`make bench`)" if cfg.name == "full" else ""
    add(f"- command: `{command}`{make}, configuration `{cfg.name}`, started {started}")
    add(
        f"- wall time {sections['wall_seconds']:.0f} s (budget {cfg.budget_s:.0f} s) on "
        f"{cfg.workers} worker processes; speed section {sections['section_seconds']['speed']:.0f}"
        f" s, scene experiments {sections['section_seconds']['scene_experiments']:.0f} s"
    )
    add(
        f"- machine: {mach['cores']} cores ({mach['cpu'] or 'unknown CPU'}), {mach['platform']}, "
        f"Python {mach['python']}, NumPy {mach['numpy']}, SciPy {mach['scipy']}, "
        f"SymPy {mach['sympy']}; one BLAS thread per process"
    )
    add(
        f"- seed {cfg.seed}: every scene has its own generator "
        "`SeedSequence(seed, spawn_key=(experiment, cell, index))`, so results do not depend on "
        "scheduling (timings do vary, and on a shared machine they are noisy)"
    )
    add("- raw numbers: `report.json` beside this file")
    add("")
    add("## Targets")
    add("")
    add("| target | measured | verdict |")
    add("|---|---|---|")
    for t in sections["targets"]:
        add(f"| {t['target']} | {t['measured'] or '–'} | **{t['verdict']}** |")
    add("")

    # accuracy
    add("## Accuracy against the Cramér–Rao bound")
    add("")
    add(
        "RMSE over the scenes divided by the root of the mean CRLB variance over the same scenes "
        "(`sqrt(mean err^2) / sqrt(mean crlb_var)`; c relative to the true c, angles in radians; "
        "the CRLB is `refine.crlb_covariance` at the true parameters, poses eliminated as nuisance "
        "parameters).  Angles compared after normalisation (alpha, beta in [0, 90], phi in "
        "[0, 180], mirror folded).  1.00 is the bound; the RMSE includes every scene, failures "
        f"too (success: worst angle error below {SUCCESS_DEG:g} degrees)."
    )
    add("")
    add(
        f"### Default pipeline, {cfg.headline_noise:g} px / {cfg.headline_noise:g} deg, "
        "by frame count"
    )
    add("")
    add(
        "| frames | scenes | c | alpha | beta | phi | success | worst ratio, successes only "
        "| worse fit than from the truth | better fit than from the truth | frames dropped "
        "| s / scene |"
    )
    add("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for n in cfg.frame_counts:
        row = _acc_row(sections, cfg.headline_noise, n)
        d = row["default"] if row else None
        if not d:
            add(f"| {n} | 0 | – | – | – | – | – | – | – | – | – | – |")
            continue
        rs = d.get("ratio_successes")
        add(
            f"| {n} | {d['n']} | "
            + " | ".join(_ratio_cells(d))
            + f" | {_pct(d['success_rate'])} | {_f(max(rs.values()) if rs else None)} | "
            + f"{_pct(d.get('worse_fit_than_truth_start_rate'))} | "
            + f"{_pct(d.get('better_fit_than_truth_start_rate'))} | "
            + f"{_pct(d.get('frames_dropped_rate'))} | {_f(d['seconds_mean'], '.3f')} |"
        )
    add("")
    add(
        "'worse fit than from the truth': the pipeline kept every frame and the chi2 minimum "
        "of its answer's basin (the answer polished by maximum likelihood) is more than 1 above "
        "that of the refinement started at the truth on the same scene (its global search "
        "missed that minimum, or the marginal likelihood preferred a basin with higher chi2); "
        "'better fit than from the truth': the same more than 1 below it (the refinement from "
        "the truth keeps every frame on the truth's pose branch, and at this noise a frame's "
        "other branch of (10) often fits better: that refinement, and the bound computed at the "
        "truth, know which branch is right, an estimator without the truth does not); "
        "'frames dropped': it left out at least one frame as an outlier (there are none in "
        "these scenes)."
    )
    add("")
    add(f"![RMSE/CRLB against frames]({ACCURACY_PNG})")
    add("")
    add("### Full grid")
    add("")
    lin_min = accuracy.linear_min_frames()
    add(
        f"The linearisation needs at least {lin_min} frames (`linear.min_frames()`: a "
        "one-dimensional null space of the grouped frame matrix); below that it is not "
        "determined and marked so.  The refinement from the truth uses the true shape and poses "
        "as its start (the best a local method can do); the default pipeline never sees the truth. "
        "The default pipeline's answer is the marginal-likelihood estimate (every frame's pose "
        "integrated out, `refine/marginal.py`); the refinement from the truth is maximum "
        "likelihood, and in a few cells 'marginal likelihood from the truth' takes that fit on to "
        "the marginal estimate, so the two estimators compare on the same scenes and start. "
        "Maximum likelihood has five pose parameters per frame for six measurements; at these "
        "noise levels its c comes out long, and that bias does not shrink with more frames while "
        "the bound does."
    )
    add("")
    add("| noise | frames | method | scenes | c | alpha | beta | phi | success |")
    add("|---|---|---|---|---|---|---|---|---|")
    for row in sections["accuracy"]:
        for m in accuracy.METHODS:
            s = row[m]
            if m == "truth_marginal" and not s:
                continue
            title = accuracy.METHOD_TITLES[m]
            if m == "linear" and row["n_frames"] < lin_min:
                add(
                    f"| {row['noise']:g} | {row['n_frames']} | {title} | – | not determined "
                    f"(< {lin_min} frames) | | | | |"
                )
                continue
            if not s:
                add(f"| {row['noise']:g} | {row['n_frames']} | {title} | 0 | – | – | – | – | – |")
                continue
            add(
                f"| {row['noise']:g} | {row['n_frames']} | {title} | {s['n']} | "
                + " | ".join(_ratio_cells(s))
                + f" | {_pct(s.get('success_rate'))} |"
            )
    add("")
    basin_rows = [
        (row, row["default"])
        for row in sections["accuracy"]
        if row["n_frames"] >= 6
        and row["default"]
        and row["default"].get("default_only_failures") is not None
    ]
    if basin_rows:
        add(
            "Where the default fails and refinement from the truth does not (cells with 6 "
            "frames or more; the refinement from the truth run again on the same scene as the "
            "default): the chi2 of the answer's basin (the answer polished by maximum "
            "likelihood) against that of the refinement from the truth.  'lower': the answer's "
            "basin fits the data better than the truth's, so no estimator that minimises chi2 "
            "without the truth would choose the truth's basin (the refinement from the truth "
            "keeps every frame on the truth's pose branch).  'same minimum': both polish to "
            "the same chi2 (to 1e-6), so the answer (the marginal-likelihood estimate) left the "
            "maximum-likelihood minimum that the truth's refinement finds.  'success, chi2 "
            "choice': every scene scored on the basin that a chi2 minimiser shown both would "
            "take (the truth's where it fits at least as well, else the default's answer); "
            "the default's gap to it is a better fit it missed, the rest of the gap to "
            "refinement from the truth is the truth's pose branches."
        )
        add("")
        add(
            "| noise | frames | scenes diagnosed | default fails, truth start succeeds "
            "| ... lower chi2 | ... same minimum | success: default / chi2 choice / truth start |"
        )
        add("|---|---|---|---|---|---|---|")
        for row, d in basin_rows:
            choice = d.get("chi2_choice_success_rate")
            ts = (row.get("truth_start") or {}).get("success_rate")
            add(
                f"| {row['noise']:g} | {row['n_frames']} | {d['basin_diagnosed_scenes']} | "
                f"{d['default_only_failures']} | {d['default_only_failures_lower_chi2']} | "
                f"{d.get('default_only_failures_same_minimum')} | "
                f"{_pct(d.get('success_rate'))} / {_pct(choice)} / {_pct(ts)} |"
            )
        add("")
    add(
        "Reading the ratios at 4-6 frames: there the bound of some scenes is very large (nearly "
        "degenerate motion), the mean CRLB variance is dominated by them, and the errors of an "
        "angle are bounded (it lives in [0, 90] or [0, 180]), so a ratio below 1 there does not "
        "mean the estimator beats the bound; from 10 frames on the bound is informative."
    )
    add("")
    if sections.get("truth_start_not_converged_rate"):
        add(
            "Refinement from the truth stopped at its iteration limit without meeting a "
            f"convergence test in {_pct(sections['truth_start_not_converged_rate'])} of the "
            "accuracy scenes."
        )
        add("")

    # robustness
    add("## Robustness")
    add("")
    add(
        f"Default pipeline without the truth, {cfg.headline_noise:g} px / {cfg.headline_noise:g} "
        f"deg, {cfg.headline_frames} frames.  Outlier frames (simulator's `outlier_fraction`) "
        "carry tangent errors of 15–40 degrees; flagged = left out by the pipeline "
        "(`Reconstruction.inliers` False).  The 0 % row is the headline accuracy cell.  "
        "'Detectable at the true shape': the outlier frames whose chi2 with the shape held at "
        "the truth (each frame's pose at its best branch of (10)) exceeds the pipeline's outlier "
        "threshold; a frame's five pose parameters absorb the rest of its error, so flagging by "
        "misfit at that threshold cannot reach more than this without knowing the shape."
    )
    add("")
    add(
        "| outlier frames | scenes | success | median worst angle (deg) | outlier frames flagged |"
        " detectable at the true shape | scenes with all flagged | false flags / scene "
        "| s / scene |"
    )
    add("|---|---|---|---|---|---|---|---|---|")
    for r in sections["robustness"]:
        add(
            f"| {100 * r['fraction']:.0f} % | {r['n']} | {_pct(r['success_rate'])} | "
            f"{_f(r['median_worst_deg'])} | {_pct(r['outliers_flagged_rate'])} | "
            f"{_pct(r.get('outliers_detectable_rate'))} | "
            f"{_pct(r['scenes_all_outliers_flagged'])} | {_f(r['false_flags_per_scene'])} | "
            f"{_f(r['seconds_mean'], '.3f')} |"
        )
    add("")

    # stability
    st = sections["stability"]
    add("## Numerical stability (noise-free scenes)")
    add("")
    add(
        "Error of a scene: the largest of |dc|/c and the angle errors (radians).  Failure: error "
        f"above {cfg.failure_threshold:g}.  'Truth not listed': neither the answer nor any listed "
        "alternative is within that (with 4 frames a noise-free scene can have several exact "
        "solutions)."
    )
    add("")
    add(f"![stability histogram]({STABILITY_PNG})")
    add("")
    add(
        "| method | frames | scenes | failure rate | truth not listed | <= 1e-9 | median log10 | "
        "s / scene |"
    )
    add("|---|---|---|---|---|---|---|---|")
    for key, title in (("default", "default pipeline"), ("linear", "linearisation alone")):
        for r in st[key]:
            if not r.get("n"):
                add(f"| {title} | {r['n_frames']} | 0 | – | – | – | – | – |")
                continue
            add(
                f"| {title} | {r['n_frames']} | {r['n']} | {_pct(r['failure_rate'])} | "
                f"{_pct(r['failure_rate_truth_not_listed'])} | {_pct(r['rate_below_1e-9'])} | "
                f"{_f(r['median_log10'], '.1f')} | {_f(r['seconds_mean'], '.3f')} |"
            )
    a = st["default_all"]
    add("")
    add(
        f"Default pipeline over all {a.get('n', 0)} noise-free scenes: failure rate "
        f"{_pct(a.get('failure_rate_four_frames_listed'))} (`noise_free_failure_rate`: a "
        "four-frame scene fails when the truth is not among the listed solutions, since four "
        "frames cannot choose; a scene of five or more frames when the answer is not the truth); "
        f"counting the first answer only at four frames too: {_pct(a.get('failure_rate'))}."
    )
    add("")

    # speed
    add("## Speed")
    add("")
    if "derive" in sp:
        dv = sp["derive"]
        add(
            f"Derivation (`{dv['command']}`, subprocess, wall clock): **{dv['seconds']:.1f} s** "
            f"(exit status {dv['returncode']})."
        )
        add("")
    add("### Generated functions against `sympy.lambdify` of the same expressions")
    add("")
    add(
        "Expressions from `derivations.measurement` / `derivations.section3` "
        "(`generated_functions()`), lambdified with the NumPy printer, plain and with "
        "`cse=True`, output assembled into the generated function's array layout; per-call time, "
        "best of three.  'max diff' is the largest |generated - lambdify| / (1 + |lambdify|)."
    )
    add("")
    add(
        "| module | function | N | generated | lambdify | speedup | lambdify cse | speedup | "
        "max diff |"
    )
    add("|---|---|---|---|---|---|---|---|---|")
    for r in sp["kernels"]:
        add(
            f"| {r['module']} | {r['function']} | {r['n_frames']} | "
            f"{_us(r['generated_s'])} | {_us(r['lambdify_s'])} | {r['speedup']:.1f} x | "
            f"{_us(r['lambdify_cse_s'])} | {r['speedup_vs_cse']:.1f} x | "
            f"{r['max_rel_diff']:.0e} |"
        )
    add("")
    add("### Refinement: generated Jacobian against finite differences")
    add("")
    add(
        "Same problems (1 px / 1 deg, started at the truth) and the same residual function; "
        "`refine.refine` (analytic Jacobian from `measurement_model.predict_with_jacobians`, "
        "Schur complement) against `scipy.optimize.least_squares(jac='2-point')` on the dense "
        "problem (`trf` with the exact solver, `lm` = MINPACK).  chi2 difference: "
        "(chi2_scipy - chi2_generated) / chi2_generated (negative: scipy found a lower cost); "
        f"the two count as reaching the same cost when the chi2 differ by less than "
        f"{SAME_COST_CHI2:g}."
    )
    add("")
    add(
        "| frames | problem | generated (s) | iterations | scipy method | scipy (s) | speedup | "
        "chi2 difference | at equal cost |"
    )
    add("|---|---|---|---|---|---|---|---|---|")
    for r in sp["refine_vs_fd"]:
        for method in _fd_methods(r):
            add(
                f"| {r['n_frames']} | {r['problem']} | {r['generated_s']:.4f} | "
                f"{r['generated_iterations']}{'' if r['generated_converged'] else ' (limit)'} | "
                f"{method} | {r[f'fd_{method}_s']:.3f} | {r[f'speedup_{method}']:.0f} x | "
                f"{r[f'chi2_rel_diff_{method}']:.1e} | {_equal_cost_cell(r, method)} |"
            )
    add("")
    add("### Reconstruction and refinement time")
    add("")
    r20, r1k = sp["reconstruct_20"], sp["refine_1000"]
    add(
        f"- full reconstruction, 20 frames (1 px / 1 deg): median {r20['median_s']:.3f} s over "
        f"{r20['repeats']} scenes (min {r20['min_s']:.3f}, max {r20['max_s']:.3f})"
    )
    add(
        f"- refinement from the truth, 1000 frames (with covariance): median "
        f"{r1k['median_s']:.3f} s, {r1k['iterations']} iterations"
    )
    add("")
    add(f"![reconstruction time against frames]({SCALING_PNG})")
    add("")
    add("| frames | wall time (s) | runs |")
    add("|---|---|---|")
    for r in sp["scaling"]:
        if r.get("skipped"):
            add(
                f"| {r['n_frames']} | not run (predicted {_f(r['predicted_s'], '.0f')} s, over the "
                f"{cfg.scaling_budget_s:.0f} s scaling budget) | 0 |"
            )
        else:
            add(f"| {r['n_frames']} | {r['median_s']:.3f} | {r['repeats']} |")
    add("")

    # counts
    c = sections["counts"]
    add("## Counts: required and run")
    add("")
    need = c["required_cpu_seconds"]
    avail = c["available_cpu_seconds"]
    add(
        "Everything is submitted at its required count in priority order (cheap accuracy parts; "
        "the headline cell; robustness and the first noise-free 6-frame scenes; the rest, "
        "interleaved) and a deadline stops starting expensive scenes when the budget is used, so "
        "the run stays within it; nothing is cut silently.  "
        + (
            f"All the required counts would need about {need:.0f} CPU-s "
            f"({need / cfg.workers / 60:.0f} min on {cfg.workers} cores) at the measured "
            "per-scene times; "
            if need
            else ""
        )
        + (f"{avail:.0f} CPU-s were available after the speed section." if avail else "")
    )
    add("")
    add("| experiment | required | run |")
    add("|---|---|---|")
    for r in c["accuracy_default"]:
        add(
            f"| default pipeline, {r['noise']:g} px, {r['n_frames']} frames | {r['required']} | "
            f"{r['run']} |"
        )
    ch = c["accuracy_cheap_parts"]
    add(
        "| CRLB, refinement from the truth, linearisation: every cell | "
        f"{ch['required']} | {ch['run_min']} (fewest of any cell) |"
    )
    for r in c["robustness"]:
        add(f"| robustness, {100 * r['fraction']:.0f} % outliers | {r['required']} | {r['run']} |")
    for r in c["stability"]:
        add(f"| noise-free, default, {r['n_frames']} frames | {r['required']} | {r['run']} |")
    for r in c["stability_linear"]:
        add(f"| noise-free, linearisation, {r['n_frames']} frames | {r['required']} | {r['run']} |")
    add("")
    add("Measured mean seconds per scene (one worker):")
    add("")
    add("| work | s / scene |")
    add("|---|---|")
    for k, v in c["per_scene_seconds"].items():
        add(f"| {k.replace('_', ' ')} | {v:.3f} |")
    add("")

    # honest notes
    add("## Honest notes")
    add("")
    for note in sections["honest_notes"]:
        add(f"- {note}")
    add("")
    return "\n".join(lines)


def _us(seconds: float) -> str:
    if seconds >= 1e-3:
        return f"{seconds * 1e3:.2f} ms"
    return f"{seconds * 1e6:.0f} µs"


def honest_notes(cfg: Config, sections: dict[str, Any]) -> list[str]:
    """Where targets are missed or the run fell short of what was asked, in words."""
    notes = []
    for t in sections["targets"]:
        if t["verdict"] != "PASS":
            notes.append(f"{t['verdict']}: {t['target']} — measured {t['measured'] or 'nothing'}.")
    c = sections["counts"]
    per = c["per_scene_seconds"]
    short = [r["run"] for r in c["accuracy_default"] if r["run"] < r["required"]]
    if short:
        times = ", ".join(
            f"{n} frames {per[f'default_{n}_frames']:.2f} s"
            for n in cfg.frame_counts
            if f"default_{n}_frames" in per
        )
        notes.append(
            f"The default pipeline ran on fewer than the required {cfg.accuracy_default_scenes} "
            f"scenes in {len(short)} of {len(c['accuracy_default'])} accuracy cells "
            f"({min(short)} to {max(short)} scenes; see 'Counts'): at the measured per-scene "
            f"time ({times}) not every cell fits the budget."
        )
    n_stab = sum(r["run"] for r in c["stability"])
    if n_stab < cfg.stability_scenes:
        times = ", ".join(
            f"{n} frames {per[f'noise_free_{n}_frames']:.2f} s"
            for n in cfg.stability_frames
            if f"noise_free_{n}_frames" in per
        )
        need = sum(
            r["required"] * per.get(f"noise_free_{r['n_frames']}_frames", math.nan)
            for r in c["stability"]
        )
        minutes = (
            f"; all of them would need about {need / cfg.workers / 60:.0f} min on "
            f"{cfg.workers} cores"
            if math.isfinite(need)
            else ""
        )
        notes.append(
            f"Only {n_stab} of the required {cfg.stability_scenes} noise-free scenes ran through "
            f"the default pipeline (per-scene time {times}){minutes}."
        )
    for r in c["robustness"]:
        if r["run"] < r["required"]:
            notes.append(
                f"Robustness with {100 * r['fraction']:.0f} % outliers ran on {r['run']} of the "
                f"required {r['required']} scenes."
            )
    if c["required_cpu_seconds"] and (short or n_stab < cfg.stability_scenes):
        notes.append(
            f"All the required counts would need about {c['required_cpu_seconds']:.0f} CPU-s "
            f"({c['required_cpu_seconds'] / cfg.workers / 60:.0f} min on {cfg.workers} cores) "
            "at the measured per-scene times, against the "
            f"{cfg.budget_s / 60:.0f}-minute budget."
        )
    skipped = [r for r in sections["speed"]["scaling"] if r.get("skipped")]
    if skipped:
        notes.append(
            "The scaling plot stops at "
            f"{max(r['n_frames'] for r in sections['speed']['scaling'] if not r.get('skipped'))}"
            f" frames: larger frame counts ({', '.join(str(r['n_frames']) for r in skipped)}) "
            f"were predicted to exceed the {cfg.scaling_budget_s:.0f} s scaling budget."
        )
    fd = sections["speed"]["refine_vs_fd"]
    for r in fd:
        if not r["generated_converged"]:
            notes.append(
                f"Refinement from the truth ({r['n_frames']} frames, problem {r['problem']}) hit "
                f"its iteration limit ({r['generated_iterations']}) without converging."
            )
        for k in r:
            if k.startswith("chi2_rel_diff_") and not _same_cost(r, k):
                method = k.rsplit("_", 1)[1]
                eq = r.get(f"speedup_equal_cost_{method}")
                notes.append(
                    f"At {r['n_frames']} frames (problem {r['problem']}) scipy {method} ended at "
                    f"a chi2 {100 * r[k]:+.2g} % from the generated-Jacobian refinement's (another "
                    "local minimum): to convergence the speedup compares unequal results ("
                    f"{r[f'speedup_{method}']:.0f} x); "
                    + (
                        f"timed to scipy's final cost it is {eq:.0f} x, which the target uses."
                        if eq is not None
                        else "scipy's cost is the lower one, so the target counts as missed."
                    )
                )
    rate = sections.get("truth_start_not_converged_rate")
    if rate:
        notes.append(
            f"Refinement started at the truth stopped at its iteration limit in {_pct(rate)} of "
            "the accuracy scenes."
        )
    notes.append(
        "Timings were taken on a shared 2-core machine; per-call and per-scene times vary "
        "between runs (the accuracy, robustness and stability numbers do not: fixed seeds)."
    )
    notes.extend(cfg.extra.get("notes", []))
    return notes


# ------------------------------------------------------------------------------ writing
def _clean(obj: Any) -> Any:
    """JSON-safe copy: non-finite floats become None, tuples lists, keys strings."""
    if isinstance(obj, dict):
        return {str(k): _clean(v) for k, v in obj.items() if not str(k).startswith("_")}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    if isinstance(obj, (np.floating, float)):
        v = float(obj)
        return v if math.isfinite(v) else None
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj


def write(
    out: Path,
    cfg: Config,
    sections: dict[str, Any],
    command: str,
    started: str,
    t_start: float | None = None,
) -> list[Path]:
    """Write the plots, ``REPORT.md`` and ``report.json`` into ``out``; return the paths."""
    out.mkdir(parents=True, exist_ok=True)
    hl = headline(cfg, sections)
    sections["headline"] = hl["headline"]
    sections["targets"] = hl["targets"]
    paths = _plots(out, cfg, sections)
    if t_start is not None:
        sections["wall_seconds"] = time.time() - t_start
    sections["honest_notes"] = honest_notes(cfg, sections)
    md = out / "REPORT.md"
    md.write_text(_markdown(cfg, sections, command, started))
    doc = {
        **hl["headline"],
        "targets": hl["targets"],
        "wall_seconds": sections["wall_seconds"],
        "command": command,
        "started": started,
        "machine": sections["machine"],
        "seeds": {
            "seed": cfg.seed,
            "scheme": "numpy SeedSequence(seed, spawn_key=(experiment, cell, index)) per scene",
            "experiments": dict(GROUPS),
        },
        "configuration": cfg.to_dict(),
        **{k: v for k, v in sections.items() if k not in ("machine", "headline", "targets")},
    }
    js = out / "report.json"
    js.write_text(json.dumps(_clean(doc), indent=1, allow_nan=False) + "\n")
    return [md, js, *paths]
