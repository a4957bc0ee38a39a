"""The bench's named targets, checked against the merged ``report.json`` (every section's keys).

``REPORT.md``'s first table holds the targets of the core bench; the added sections (the
four-frame minimal solver and the robust pipeline, the curve bundle, fuzzing and scale) name
report keys and bounds of their own.  ``rows(doc)`` checks every one of them that the report
holds, so that a miss (or a fuzz test that failed, which otherwise only the raw pytest tail
would say) shows in one table at the top of the added sections.  A key the report does not
hold yet reads "not measured", never PASS.

Each target is named by what it measures.  Targets of work that is finished stay in the table
as regression checks (``regression=True``: a regression of theirs still shows) and are counted
apart from the open targets.

``python -m bench.targets [bench/report.json]`` prints the table.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

GAP_POINTS = 2.0
"""Default success within 2 percentage points of refinement-from-truth success."""

MIN_CELL_FRAMES = 6
"""The accuracy cells that the 2-point criterion covers (>= 6 frames)."""

TITLE = "Targets of the added sections"
"""REPORT.md's heading of the table, which ``merge_section`` rewrites on every merge."""

Row = tuple[str, str, str, str, bool]
"""(target name, criterion, measured, PASS / MISS, regression check)."""


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
    name: str,
    text: str,
    path: str,
    ok: Callable[[Any], bool],
    show: Callable[[Any], str] = str,
    regression: bool = True,
) -> Callable[[dict[str, Any]], Row]:
    def check(doc: dict[str, Any]) -> Row:
        v = _get(doc, path)
        if v is None:
            return name, text, "not measured", "MISS", regression
        return name, text, show(v), "PASS" if ok(v) else "MISS", regression

    return check


def _cells(doc: dict[str, Any]) -> Row:
    name = "few-frame success against the truth start"
    text = f"default success within {GAP_POINTS:g} points of refinement from the truth, every cell"
    text += f" with >= {MIN_CELL_FRAMES} frames"
    got = _cell_gaps(doc)
    if got is None:
        return name, text, "not measured", "MISS", True
    good, n, missed = got
    shown = f"{good} of {n} cells" + (f"; misses: {', '.join(missed)}" if missed else "")
    return name, text, shown, "PASS" if good == n else "MISS", True


def chi2_choice_note(doc: dict[str, Any]) -> str | None:
    """The few-frame cell criterion held to the chi2 choice instead (``bench.accuracy``: every
    scene scored on the lower-chi2 basin of the default's and the truth's): a diagnostic that
    separates fits the default missed from the truth's pose branches, not a target."""
    got = _cell_gaps(doc, lambda a: a["default"].get("chi2_choice_success_rate"))
    if got is None:
        return None
    good, n, missed = got
    return (
        f"Diagnostic, not a target: the default within {GAP_POINTS:g} points of the chi2 "
        f"choice (each scene scored on the lower-chi2 basin of the default's and the truth "
        f"start's) in {good} of {n} cells with >= {MIN_CELL_FRAMES} frames"
        + (f"; misses: {', '.join(missed)}." if missed else ".")
    )


def truth_start_note(doc: dict[str, Any]) -> str | None:
    """The curve and polylines-only targets beside the same measure for the curve bundle
    started at the true curve and poses (``bench.bundle``'s ``..._truth_start`` keys, an oracle):
    where the oracle misses the target too, the data do not determine the answer that well.
    A diagnostic, not a target."""
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
        "Diagnostic, not a target: the curve bundle started at the true curve and poses "
        "(an oracle, the fit the data allow near the truth): " + "; ".join(parts) + "."
    )


def _min_family(v: dict[str, float]) -> str:
    worst = min(v, key=v.get)
    return f"lowest {worst} {v[worst]:g} ({len(v)} families)"


CHECKS: list[Callable[[dict[str, Any]], Row]] = [
    _target(
        "four-frame solver: truth listed",
        "minimal_truth_listed_rate >= 0.999",
        "minimal_truth_listed_rate",
        lambda v: v >= 0.999,
    ),
    _target(
        "four-frame solve time",
        "minimal_solve_seconds_median <= 0.02",
        "minimal_solve_seconds_median",
        lambda v: v <= 0.02,
    ),
    _target(
        "noise-free few frames: truth listed",
        "noise_free_truth_not_listed_rate (4, 5, 6 frames) <= 0.001",
        "noise_free_truth_not_listed_rate",
        lambda v: v <= 0.001,
    ),
    _target(
        "noise-free success",
        "noise_free_failure_rate <= 0.01",
        "noise_free_failure_rate",
        lambda v: v <= 0.01,
    ),
    _target(
        "outliers: 10 % of the frames",
        "success_rate_10pct_outliers >= 0.98",
        "success_rate_10pct_outliers",
        lambda v: v >= 0.98,
    ),
    _target(
        "outliers: 30 % of the frames",
        "success_rate_30pct_outliers >= 0.90",
        "success_rate_30pct_outliers",
        lambda v: v >= 0.90,
    ),
    _cells,
    _target(
        "reconstruction time, 20 frames",
        "reconstruct_seconds_20_frames <= 0.2",
        "reconstruct_seconds_20_frames",
        lambda v: v <= 0.2,
        lambda v: f"{v:.3f}",
    ),
    _target(
        "reconstruction time, 10,000 frames",
        "reconstruct_seconds_10000_frames <= 3",
        "reconstruct_seconds_10000_frames",
        lambda v: v <= 3.0,
    ),
    _target(
        "curve bundle noise-free: c",
        "noise-free bundle: c to 1e-9 relative",
        "bundle_noise_free_max_error.c_rel",
        lambda v: v <= 1e-9,
        lambda v: f"{v:.2g}",
        regression=False,
    ),
    _target(
        "curve bundle noise-free: angles",
        "noise-free bundle: angles to 1e-7 deg",
        "bundle_noise_free_max_error.angle_deg",
        lambda v: v <= 1e-7,
        lambda v: f"{v:.2g}",
        regression=False,
    ),
    _target(
        "curve bundle noise-free: curve3d",
        "noise-free bundle: curve3d within 1e-6 of the length",
        "bundle_noise_free_max_error.curve3d_rel",
        lambda v: v <= 1e-6,
        lambda v: f"{v:.2g}",
        regression=False,
    ),
    _target(
        "curve3d error by family",
        "curve3d within 0.5 % at 0.5 px, 12 frames, >= 98 % of every family",
        "bundle_curve_within_half_percent_rate_by_family",
        lambda v: min(v.values()) >= 0.98,
        _min_family,
        regression=False,
    ),
    _target(
        "polylines never worse",
        "bundle_never_worse_rate >= 0.99",
        "bundle_never_worse_rate",
        lambda v: v >= 0.99,
        regression=False,
    ),
    _target(
        "polylines-only angles",
        "polylines_only_angles_within_1deg_rate >= 0.95",
        "polylines_only_angles_within_1deg_rate",
        lambda v: v >= 0.95,
        regression=False,
    ),
    _target(
        "curve bundle shape std coverage",
        "std_coverage_3sigma >= 0.99",
        "std_coverage_3sigma",
        lambda v: v >= 0.99,
        regression=False,
    ),
    _target(
        "curve3d std coverage",
        "curve3d points within 3 std across the curve >= 0.99",
        "curve3d_normal_std_coverage_3sigma",
        lambda v: v >= 0.99,
        regression=False,
    ),
    _target(
        "polylines time ratio, 20 frames",
        "bundle_time_ratio_20_frames <= 2",
        "bundle_time_ratio_20_frames",
        lambda v: v <= 2.0,
        regression=False,
    ),
    _target(
        "polylines time ratio, 1,000 frames",
        "bundle_time_ratio_1000_frames <= 2",
        "bundle_time_ratio_1000_frames",
        lambda v: v <= 2.0,
        regression=False,
    ),
    _target("fuzz: no traceback", "fuzz_tracebacks == 0", "fuzz_tracebacks", lambda v: v == 0),
    _target(
        "fuzz: property tests",
        "fuzz_tests_passed is True",
        "fuzz_tests_passed",
        lambda v: v is True,
    ),
]


def rows(doc: dict[str, Any]) -> list[Row]:
    """(name, criterion, measured, PASS / MISS, regression check) for every target."""
    return [check(doc) for check in CHECKS]


def markdown(doc: dict[str, Any]) -> str:
    """The table, with a count of the misses."""
    got = rows(doc)
    open_rows = [r for r in got if not r[4]]
    kept_rows = [r for r in got if r[4]]

    def met(rs: list[Row]) -> int:
        return sum(r[3] == "PASS" for r in rs)

    count = f"open targets: {met(open_rows)} of {len(open_rows)} met"
    if kept_rows:
        count += f"; regression checks: {met(kept_rows)} of {len(kept_rows)}"
    lines = [
        f"## {TITLE}",
        "",
        f"{count} (`bench/targets.py`; from every section merged into report.json, each "
        "as of its own run).",
        "",
        "| target | criterion | measured | verdict |",
        "|---|---|---|---|",
        *(
            f"| {n}{' (regression check)' if kept else ''} | {t} | {m} | **{v}** |"
            for n, t, m, v, kept in got
        ),
    ]
    for note in (chi2_choice_note(doc), truth_start_note(doc)):
        if note:
            lines += ["", note]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    path = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).with_name("report.json"))
    print(markdown(json.loads(path.read_text())))
