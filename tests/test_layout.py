"""The layout's promises: one library call returns what the command writes, options
reach the stage that uses them, and no module imports another's private names."""

from __future__ import annotations

import ast
import json
from pathlib import Path

import numpy as np

import curverecon
from curverecon.cli import main
from curverecon.io import load_observations
from curverecon.options import OutlierOptions, ReconstructOptions
from curverecon.simulate import make_scene

ROOT = Path(__file__).resolve().parents[1]


def test_library_call_returns_what_the_command_writes(tmp_path, capsys):
    """examples/wire.json carries polylines: the curve stages (branch choice by the curve,
    section 4, the curve bundle) run inside ``curverecon.reconstruct`` as in the command."""
    path = ROOT / "examples" / "wire.json"
    out = tmp_path / "out.json"
    assert main(["reconstruct", str(path), "-o", str(out)]) == 0
    written = json.loads(out.read_text())
    rec = curverecon.reconstruct(load_observations(path))
    from_library = json.loads(json.dumps(rec.to_json_dict()))
    assert from_library == written
    assert written["estimator"] == "curve-bundle" and len(written["curve3d"]) > 10
    stderr = capsys.readouterr().err.strip().splitlines()
    assert stderr == [f"curverecon: warning: {w}" for w in rec.warnings]


def test_outlier_options_reach_the_outlier_stage():
    """A false-alarm rate of 1e-300 per frame (and no cap on the chi2 at which a frame left
    out of LO-RANSAC's consensus set is taken back, ``take_back_chi2``) flags nothing; the
    default flags the gross outlier frames of the same scene."""
    scene = make_scene(
        np.random.default_rng(3), 20, point_sigma=1.0, tangent_sigma_deg=1.0, outlier_fraction=0.2
    )
    default = curverecon.reconstruct(scene.observations)
    never = curverecon.reconstruct(
        scene.observations,
        options=ReconstructOptions(
            outliers=OutlierOptions(false_alarm=1e-300, take_back_chi2=float("inf"))
        ),
    )
    assert default.outlier_frames()
    assert never.outlier_frames() == []


def _private_imports(path: Path) -> list[str]:
    tree = ast.parse(path.read_text())
    bad = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("curverecon"):
            bad += [f"{node.module}.{a.name}" for a in node.names if a.name.startswith("_")]
    return [b for b in bad if not b.endswith(".__version__")]


def test_no_runtime_module_imports_another_modules_private_names():
    found = {
        str(p.relative_to(ROOT)): _private_imports(p)
        for p in (ROOT / "curverecon").rglob("*.py")
        if _private_imports(p)
    }
    assert found == {}


def test_stage_folders_are_in_the_order_the_data_passes():
    """The docs' map names every stage folder and every module in it."""
    text = (ROOT / "docs" / "architecture.md").read_text()
    for folder in ("trace", "model", "solvers", "robust", "refine", "curve"):
        for module in (ROOT / "curverecon" / folder).glob("*.py"):
            if module.name != "__init__.py":
                assert f"{folder}/{module.name}" in text, module
    order = [
        text.index(f"`{f}/`") for f in ("trace", "model", "solvers", "robust", "refine", "curve")
    ]
    assert order == sorted(order)


def test_progress_bar_only_when_asked(capsys):
    """The library draws the stage bar on stderr only with ``progress=True`` (the command asks
    when stderr is a terminal and not ``--quiet``); the answer is the same either way."""
    scene = make_scene(np.random.default_rng(4), 6, point_sigma=0.5, tangent_sigma_deg=0.5)
    quiet = curverecon.reconstruct(scene.observations)
    assert capsys.readouterr().err == ""
    shown = curverecon.reconstruct(scene.observations, options=ReconstructOptions(progress=True))
    err = capsys.readouterr().err
    assert "reconstruct:" in err and "hypotheses" in err and "final estimate" in err
    assert np.array_equal(quiet.shape, shown.shape)
