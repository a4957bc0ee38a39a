"""``bench.bundle``'s oracle (the curve bundle started at the true curve and poses): on noise-free
frames it stays on the true curve, so where it misses a target on noisy frames, the noise did."""

from __future__ import annotations

import numpy as np
import pytest

from bench.bundle import main, truth_start_bundle, worst_angle_deg
from bench.curve_end_to_end import curve_error
from curverecon.curve.bundle import shape_and_poses
from curverecon.simulate import make_scene


def test_truth_start_stays_on_a_noise_free_curve():
    sc = make_scene(np.random.default_rng(5), 8, 0.0, 0.0, with_curve=True, curve_family="bezier")
    with_ends = truth_start_bundle(sc, True, 0.5)
    assert curve_error(with_ends.curve_points(200), sc.curve_3d) < 1e-4
    only = shape_and_poses(truth_start_bundle(sc, False, 0.5))[0]
    assert worst_angle_deg(only, sc.truth.shape) < 0.2
    assert abs(only[0] - sc.truth.c) / sc.truth.c < 1e-4


def test_worst_angle_folds_phi_and_sees_each_angle():
    truth = np.array([100.0, 0.5, 0.6, 2.0])
    assert worst_angle_deg(np.array([99.0, 0.5, 0.6, -2.0]), truth) < 1e-12  # mirror image
    off = truth + [0.0, 0.0, np.radians(3.0), 0.0]
    assert abs(worst_angle_deg(off, truth) - 3.0) < 1e-9


@pytest.mark.parametrize(
    "argv",
    [
        ["--truth-start", "3000"],
        ["--truth-start", "a", "2"],
        ["--truth-start", "3000", "0"],
        ["--seeds"],
    ],
)
def test_bad_arguments_exit_2_with_one_line(argv, capsys):
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1].startswith("python -m bench.bundle: error:")


def test_the_bundle_section_reports_every_key_the_targets_and_readme_read():
    """The keys of ``bench.bundle.run``'s report, read from its source (running it takes minutes):
    the curve bundle targets' named keys, and the paired comparison the README reads (a rename of
    a helper once turned it into ``bundle_pairedworst_angle_deg`` unseen)."""
    import ast
    import inspect

    from bench import bundle

    tree = ast.parse(inspect.getsource(bundle.run))
    keys = {
        k.value
        for node in ast.walk(tree)
        if isinstance(node, ast.Dict)
        for k in node.keys
        if isinstance(k, ast.Constant) and isinstance(k.value, str)
    }
    need = {
        "bundle_noise_free_max_error",
        "bundle_curve_error_median_by_family",
        "bundle_never_worse_rate",
        "polylines_only_angles_within_1deg_rate",
        "std_coverage_3sigma",
        "bundle_time_ratio_20_frames",
        "bundle_time_ratio_1000_frames",
        "bundle_paired_worst_angle_deg",
        "curve3d_normal_std_coverage_3sigma",
    }
    assert need <= keys, need - keys


def test_a_scene_refused_without_polylines_still_counts_for_the_coverages():
    """Helix 9114 (1 px, 12 frames): without polylines section 4 cannot place the curve on the
    end-point answer's poses (refused); with them the bundle answers.  The never-worse case keeps
    the answer with polylines (its shape and ``curve3d`` scored on its own std) and marks the
    scene as having no pair, instead of dropping it from the coverages."""
    from bench.bundle import case

    out = case(("never_worse", "helix", 9114))
    assert "error" not in out, out.get("error")
    assert "section 4" in out["off_refused"]
    assert "e_with" not in out and "e_without" not in out  # no pair to compare
    assert len(out["z_with"]) == 4 and np.all(np.isfinite(out["z_with"]))
    assert len(out["curve_zn"]) > 10 and np.all(np.isfinite(out["curve_zn"]))
