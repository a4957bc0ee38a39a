"""The issues' targets, checked against the merged ``report.json`` (every section's keys).

``REPORT.md``'s first table holds the targets of the core bench; the issues that came later
(12: the minimal solver and the robust pipeline, 13: the curve bundle, 16: fuzzing and scale)
name report keys and bounds of their own.  ``rows(doc)`` checks every one of them that the
report holds, so that a miss (or a fuzz test that failed, as on 2026-11-27 06:23 UTC, when only
the raw pytest tail said so) shows in one table at the top of the added sections.  A key the
report does not hold yet reads "not measured", never PASS.

Issues that have ended stay in the table (``ENDED``: a regression of theirs still shows) and
are marked so; the count at the top is of the open issues' targets, with the ended ones' apart.

``python -m bench.issue_targets [bench/report.json]`` prints the table.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

ENDED: dict[str, str] = {"12": "ended, blocked", "16": "ended, resolved"}
"""Issues that have ended, with how (``issues all``): their targets are kept as regression
checks, not counted with the open issues'."""

GAP_POINTS = 2.0
"""Issue 12: default success within 2 percentage points of refinement-from-truth success."""

MIN_CELL_FRAMES = 6
"""Issue 12: the accuracy cells that the 2-point criterion covers (>= 6 frames)."""


def _get(doc: dict[str, Any], path: str) -> Any:
    v: Any = doc
    for part in path.split("."):
        if not isinstance(v, dict) or part not in v:
            return None
        v = v[part]
    return v


def _cell_gaps(
    doc: dict[str, Any], reference: Callable[[dict[str, Any]], float | None] | None = None
) -> tuple[int, int, list[str]] | None:
    """(cells meeting the 2-point criterion, cells, the cells that miss) over the grid's cells
    with >= ``MIN_CELL_FRAMES`` frames and noise >= 0.25 px.  ``reference(cell)``: the success
    rate the default is held to (refinement from the truth unless given)."""
    if reference is None:

        def reference(a: dict[str, Any]) -> float | None:
            return a["truth_start"]["success_rate"]

    cells = [
        a
        for a in doc.get("accuracy") or []
        if a.get("n_frames", 0) >= MIN_CELL_FRAMES
        and a.get("default")
        and a.get("truth_start")
        and reference(a) is not None
    ]
    if not cells:
        return None
    missed = []
    for a in cells:
        gap = 100.0 * (reference(a) - a["default"]["success_rate"])
        if gap > GAP_POINTS:
            missed.append(f"{a['noise']:g} px / {a['n_frames']} frames ({gap:.1f} points)")
    return len(cells) - len(missed), len(cells), missed


def _target(
    issue: str, text: str, path: str, ok: Callable[[Any], bool], show: Callable[[Any], str] = str
) -> Callable[[dict[str, Any]], tuple[str, str, str, str]]:
    def check(doc: dict[str, Any]) -> tuple[str, str, str, str]:
        v = _get(doc, path)
        if v is None:
            return issue, text, "not measured", "MISS"
        return issue, text, show(v), "PASS" if ok(v) else "MISS"

    return check


def _cells(doc: dict[str, Any]) -> tuple[str, str, str, str]:
    text = f"default success within {GAP_POINTS:g} points of refinement from the truth, every cell"
    text += f" with >= {MIN_CELL_FRAMES} frames"
    got = _cell_gaps(doc)
    if got is None:
        return "12", text, "not measured", "MISS"
    good, n, missed = got
    shown = f"{good} of {n} cells" + (f"; misses: {', '.join(missed)}" if missed else "")
    return "12", text, shown, "PASS" if good == n else "MISS"


def chi2_choice_note(doc: dict[str, Any]) -> str | None:
    """Issue 12's cell criterion held to the chi2 choice instead (``bench.accuracy``: every
    scene scored on the lower-chi2 basin of the default's and the truth's): a diagnostic that
    separates fits the default missed from the truth's pose branches, not the issue's target."""
    got = _cell_gaps(doc, lambda a: a["default"].get("chi2_choice_success_rate"))
    if got is None:
        return None
    good, n, missed = got
    return (
        f"Diagnostic, not an issue target: the default within {GAP_POINTS:g} points of the chi2 "
        f"choice (each scene scored on the lower-chi2 basin of the default's and the truth "
        f"start's) in {good} of {n} cells with >= {MIN_CELL_FRAMES} frames"
        + (f"; misses: {', '.join(missed)}." if missed else ".")
    )


def truth_start_note(doc: dict[str, Any]) -> str | None:
    """Issue 13's curve and polylines-only targets beside the same measure for the curve bundle
    started at the true curve and poses (``bench.bundle``'s ``..._truth_start`` keys, an oracle):
    where the oracle misses the target too, the data do not determine the answer that well.
    A diagnostic, not the issue's target."""
    curve = _get(doc, "bundle_curve_within_half_percent_rate_by_family_truth_start")
    poly = _get(doc, "polylines_only_angles_within_1deg_rate_truth_start")
    parts = []
    if isinstance(curve, dict) and curve:
        rates = ", ".join(f"{f} {v:g}" for f, v in curve.items())
        scenes = _get(doc, "bundle_curve_scenes_per_family")
        each = f" ({scenes} scenes each)" if scenes else ""
        parts.append(f"curve3d within 0.5 % from the truth start{each}: {rates}")
    if isinstance(poly, (int, float)):
        parts.append(f"polylines only, angles within 1 deg from the truth start: {poly:g}")
    if not parts:
        return None
    return (
        "Diagnostic, not an issue target: the curve bundle started at the true curve and poses "
        "(an oracle, the fit the data allow near the truth): " + "; ".join(parts) + "."
    )


def _min_family(v: dict[str, float]) -> str:
    worst = min(v, key=v.get)
    return f"lowest {worst} {v[worst]:g} ({len(v)} families)"


CHECKS: list[Callable[[dict[str, Any]], tuple[str, str, str, str]]] = [
    _target(
        "12",
        "minimal_truth_listed_rate >= 0.999",
        "minimal_truth_listed_rate",
        lambda v: v >= 0.999,
    ),
    _target(
        "12",
        "minimal_solve_seconds_median <= 0.02",
        "minimal_solve_seconds_median",
        lambda v: v <= 0.02,
    ),
    _target(
        "12",
        "noise_free_truth_not_listed_rate (4, 5, 6 frames) <= 0.001",
        "noise_free_truth_not_listed_rate",
        lambda v: v <= 0.001,
    ),
    _target(
        "12", "noise_free_failure_rate <= 0.01", "noise_free_failure_rate", lambda v: v <= 0.01
    ),
    _target(
        "12",
        "success_rate_10pct_outliers >= 0.98",
        "success_rate_10pct_outliers",
        lambda v: v >= 0.98,
    ),
    _target(
        "12",
        "success_rate_30pct_outliers >= 0.90",
        "success_rate_30pct_outliers",
        lambda v: v >= 0.90,
    ),
    _cells,
    _target(
        "12",
        "reconstruct_seconds_20_frames <= 0.2",
        "reconstruct_seconds_20_frames",
        lambda v: v <= 0.2,
        lambda v: f"{v:.3f}",
    ),
    _target(
        "12",
        "reconstruct_seconds_10000_frames <= 3",
        "reconstruct_seconds_10000_frames",
        lambda v: v <= 3.0,
    ),
    _target(
        "13",
        "noise-free bundle: c to 1e-9 relative",
        "bundle_noise_free_max_error.c_rel",
        lambda v: v <= 1e-9,
        lambda v: f"{v:.2g}",
    ),
    _target(
        "13",
        "noise-free bundle: angles to 1e-7 deg",
        "bundle_noise_free_max_error.angle_deg",
        lambda v: v <= 1e-7,
        lambda v: f"{v:.2g}",
    ),
    _target(
        "13",
        "noise-free bundle: curve3d within 1e-6 of the length",
        "bundle_noise_free_max_error.curve3d_rel",
        lambda v: v <= 1e-6,
        lambda v: f"{v:.2g}",
    ),
    _target(
        "13",
        "curve3d within 0.5 % at 0.5 px, 12 frames, >= 98 % of every family",
        "bundle_curve_within_half_percent_rate_by_family",
        lambda v: min(v.values()) >= 0.98,
        _min_family,
    ),
    _target(
        "13", "bundle_never_worse_rate >= 0.99", "bundle_never_worse_rate", lambda v: v >= 0.99
    ),
    _target(
        "13",
        "polylines_only_angles_within_1deg_rate >= 0.95",
        "polylines_only_angles_within_1deg_rate",
        lambda v: v >= 0.95,
    ),
    _target("13", "std_coverage_3sigma >= 0.99", "std_coverage_3sigma", lambda v: v >= 0.99),
    _target(
        "13",
        "curve3d points within 3 std across the curve >= 0.99",
        "curve3d_normal_std_coverage_3sigma",
        lambda v: v >= 0.99,
    ),
    _target(
        "13",
        "bundle_time_ratio_20_frames <= 2",
        "bundle_time_ratio_20_frames",
        lambda v: v <= 2.0,
    ),
    _target(
        "13",
        "bundle_time_ratio_1000_frames <= 2",
        "bundle_time_ratio_1000_frames",
        lambda v: v <= 2.0,
    ),
    _target("16", "fuzz: no traceback", "fuzz_tracebacks", lambda v: v == 0),
    _target("16", "fuzz: every property test passes", "fuzz_tests_passed", lambda v: v is True),
]


def rows(doc: dict[str, Any]) -> list[tuple[str, str, str, str]]:
    """(issue, target, measured, PASS / MISS) for every target, ended issues' included."""
    return [check(doc) for check in CHECKS]


def markdown(doc: dict[str, Any]) -> str:
    """The table, with a count of the misses."""
    got = rows(doc)
    open_rows = [r for r in got if r[0] not in ENDED]
    ended_rows = [r for r in got if r[0] in ENDED]

    def met(rs: list[tuple[str, str, str, str]]) -> int:
        return sum(r[3] == "PASS" for r in rs)

    count = f"open issues: {met(open_rows)} of {len(open_rows)} met"
    if ended_rows:
        count += (
            f"; ended issues (kept as regression checks): {met(ended_rows)} of {len(ended_rows)}"
        )
    lines = [
        "## Issue targets",
        "",
        f"{count} (`bench/issue_targets.py`; from every section merged into report.json, each "
        "as of its own run).",
        "",
        "| issue | target | measured | verdict |",
        "|---|---|---|---|",
        *(
            f"| {i}{f' ({ENDED[i]})' if i in ENDED else ''} | {t} | {m} | **{v}** |"
            for i, t, m, v in got
        ),
    ]
    for note in (chi2_choice_note(doc), truth_start_note(doc)):
        if note:
            lines += ["", note]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    path = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).with_name("report.json"))
    print(markdown(json.loads(path.read_text())))
