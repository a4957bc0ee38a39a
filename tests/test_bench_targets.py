"""``bench.targets``: the named targets read from a merged report, and REPORT.md's table
rewritten (not duplicated) on every section merge."""

from __future__ import annotations

import json

from bench import targets
from bench.__main__ import merge_section


def _cell(noise: float, frames: int, default: float, truth: float) -> dict:
    return {
        "noise": noise,
        "n_frames": frames,
        "default": {"success_rate": default},
        "truth_start": {"success_rate": truth},
    }


def _verdicts(doc: dict) -> dict[str, tuple[str, str]]:
    return {t: (m, v) for _, t, m, v, _ in targets.rows(doc)}


def test_missing_keys_are_not_measured_never_pass():
    got = targets.rows({})
    assert got and all(v == "MISS" and m == "not measured" for _, _, m, v, _ in got)


def test_bounds_are_inclusive_and_a_failed_fuzz_run_misses():
    doc = {
        "minimal_solve_seconds_median": 0.02,
        "success_rate_30pct_outliers": 0.899,
        "fuzz_tests_passed": False,
        "fuzz_tracebacks": 0,
        "bundle_curve_within_half_percent_rate_by_family": {"helix": 1.0, "random": 0.97},
    }
    v = _verdicts(doc)
    assert v["minimal_solve_seconds_median <= 0.02"][1] == "PASS"
    assert v["success_rate_30pct_outliers >= 0.90"][1] == "MISS"
    assert v["fuzz_tests_passed is True"][1] == "MISS"
    assert v["fuzz_tracebacks == 0"][1] == "PASS"
    family = next(k for k in v if k.startswith("curve3d within 0.5 %"))
    assert v[family] == ("lowest random 0.97 (2 families)", "MISS")


def test_accuracy_cells_criterion_counts_only_cells_of_six_frames_or_more():
    doc = {
        "accuracy": [
            _cell(1.0, 4, 0.10, 0.90),  # below 6 frames: not a cell of the criterion
            _cell(1.0, 6, 0.80, 0.82),  # 2 points: met (bound inclusive)
            _cell(2.0, 10, 0.70, 0.75),  # 5 points: missed
            _cell(2.0, 20, 0.99, 0.98),  # default better: met
        ]
    }
    key = next(k for k in _verdicts(doc) if k.startswith("default success within"))
    measured, verdict = _verdicts(doc)[key]
    assert verdict == "MISS"
    assert measured.startswith("2 of 3 cells") and "2 px / 10 frames (5.0 points)" in measured


def test_chi2_choice_note_holds_the_default_to_the_lower_chi2_basin():
    c6 = _cell(1.0, 6, 0.60, 0.85)
    c6["default"]["chi2_choice_success_rate"] = 0.61  # 1 point: met
    c10 = _cell(2.0, 10, 0.70, 0.75)
    c10["default"]["chi2_choice_success_rate"] = 0.73  # 3 points: missed
    doc = {"accuracy": [c6, c10, _cell(1.0, 4, 0.1, 0.9)]}
    note = targets.chi2_choice_note(doc)
    assert "in 1 of 2 cells" in note and "2 px / 10 frames (3.0 points)" in note
    assert note in targets.markdown(doc)
    # the target's own criterion is unchanged by it: both cells miss against the truth start
    key = next(k for k in _verdicts(doc) if k.startswith("default success within"))
    assert _verdicts(doc)[key][0].startswith("0 of 2 cells")
    assert targets.chi2_choice_note({"accuracy": [_cell(1.0, 6, 0.6, 0.8)]}) is None


def test_truth_start_note_sets_the_oracle_beside_the_curve_targets():
    doc = {
        "bundle_curve_within_half_percent_rate_by_family": {"helix": 1.0, "fourier": 0.5},
        "bundle_curve_within_half_percent_rate_by_family_truth_start": {
            "helix": 1.0,
            "fourier": 0.625,
        },
        "bundle_curve_scenes_per_family": 8,
        "polylines_only_angles_within_1deg_rate_truth_start": 0.25,
    }
    note = targets.truth_start_note(doc)
    assert "(8 scenes each): helix 1, fourier 0.625" in note
    assert "angles within 1 deg from the truth start: 0.25" in note
    assert note in targets.markdown(doc)
    # the target itself is still judged on the default's answer
    family = next(k for k in _verdicts(doc) if k.startswith("curve3d within 0.5 %"))
    assert _verdicts(doc)[family] == ("lowest fourier 0.5 (2 families)", "MISS")
    assert targets.truth_start_note({}) is None


def test_merge_section_rewrites_one_targets_table_and_fences_long_values(tmp_path):
    (tmp_path / "report.json").write_text(json.dumps({"minimal_solve_seconds_median": 0.5}))
    (tmp_path / "REPORT.md").write_text("# report\n\nbody\n")
    merge_section(tmp_path, "fuzz", {"fuzz_tests_passed": False, "fuzz_failure": "a\n| b |\nc"})
    merge_section(tmp_path, "fuzz", {"fuzz_tests_passed": True, "fuzz_failure": None})
    md = (tmp_path / "REPORT.md").read_text()
    heading = f"## {targets.TITLE}"
    assert md.count(heading) == 1 and md.count("## Section: fuzz") == 1
    assert "| fuzz: property tests (regression check) | fuzz_tests_passed is True | True |" in md
    assert "| four-frame solve time (regression check) | minimal_solve_seconds_median <= 0.02" in md
    merge_section(tmp_path, "fuzz", {"fuzz_failure": "line one\nline two"})
    md = (tmp_path / "REPORT.md").read_text()
    assert "| `fuzz_failure` | (below) |" in md and "```\nline one\nline two\n```" in md
    assert md.index(heading) < md.index("## Section: fuzz")


def test_regression_checks_are_marked_and_counted_apart_from_the_open_targets():
    # one open target met (the 20-frame time ratio), one regression check met (the fuzz
    # tracebacks): each count holds exactly its own rows
    doc = {"bundle_time_ratio_20_frames": 1.5, "fuzz_tracebacks": 0}
    text = targets.markdown(doc)
    got = targets.rows(doc)
    n_open = sum(not r[4] for r in got)
    n_kept = len(got) - n_open
    assert 0 < n_open < len(got)
    assert f"open targets: 1 of {n_open} met" in text
    assert f"regression checks: 1 of {n_kept}" in text
    assert "| fuzz: no traceback (regression check) | fuzz_tracebacks == 0 | 0 | **PASS** |" in text
    assert (
        "| polylines time ratio, 20 frames | bundle_time_ratio_20_frames <= 2 | 1.5 | **PASS** |"
        in text
    )


def test_every_target_has_its_own_name():
    names = [r[0] for r in targets.rows({})]
    assert len(set(names)) == len(names)
