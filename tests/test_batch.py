"""``curverecon batch``: mixed inputs, failures recorded, bad arguments, resume, a killed worker.

One local Dask cluster of two worker processes serves the module (the command reaches it through
``--scheduler``); the sequences are tiny (12 frames of points and tangents, or 6 rendered frames
of 128 pixels) so that the module stays well under a minute and a half.
"""

from __future__ import annotations

import json
import math
import os
import signal
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("dask.distributed")
pd = pytest.importorskip("pandas")

import curverecon  # noqa: E402
from curverecon.batch import run  # noqa: E402
from curverecon.batch.runner import local_cluster  # noqa: E402
from curverecon.batch.task import COLUMNS  # noqa: E402
from curverecon.cli import main  # noqa: E402
from curverecon.io import load_observations, observations_to_dict, write_json  # noqa: E402
from curverecon.simulate import make_scene  # noqa: E402

CONTRACT_COLUMNS = [
    "input", "status", "error", "c", "alpha_deg", "beta_deg", "phi_deg", "c_std",
    "alpha_deg_std", "beta_deg_std", "phi_deg_std", "chi2", "frames", "outlier_frames", "seconds",
]  # fmt: skip


def _scene_file(path: Path, seed: int, frames: int = 12) -> Path:
    scene = make_scene(np.random.default_rng(seed), frames, point_sigma=0.5, tangent_sigma_deg=0.5)
    write_json(path, observations_to_dict(scene.observations))
    return path


@pytest.fixture(scope="module")
def client():
    from dask.distributed import Client

    cluster = local_cluster(2)
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()


@pytest.fixture(scope="module")
def data(tmp_path_factory) -> Path:
    """Observation files, a folder of them, a rendered image sequence and the same as a GIF."""
    import imageio.v3 as iio

    from curverecon.trace.render import RenderOptions, render_scene, tumbling_scene, write_images

    root = tmp_path_factory.mktemp("batch_data")
    _scene_file(root / "alpha.json", 2)
    (root / "more").mkdir()
    _scene_file(root / "more" / "beta.json", 5)
    _scene_file(root / "more" / "gamma.json", 6)
    rng = np.random.default_rng(3)
    scene = tumbling_scene(rng, 6, family="bezier", size=128, step_deg=25.0)
    images = render_scene(scene, rng, RenderOptions(size=128))
    write_images(images, root / "seq")
    frames = [iio.imread(p) for p in sorted((root / "seq").glob("*.png"))]
    iio.imwrite(root / "clip.gif", frames, plugin="pillow", duration=100, loop=0)
    return root


def _valid_json_outputs(out: Path) -> list[dict]:
    docs = []
    for p in sorted(out.glob("*.json")):
        docs.append(json.loads(p.read_text()))
    assert not list(out.glob(".*.tmp")), "a temporary file was left behind"
    return docs


def test_mixed_inputs_give_outputs_and_the_contract_summary(data, tmp_path, client):
    out = tmp_path / "out"
    inputs = [data / "alpha.json", data / "more", data / "seq", data / "clip.gif"]
    summary = run(inputs, out, client=client)
    assert list(summary.columns) == CONTRACT_COLUMNS == list(COLUMNS)
    assert list(summary["status"]) == ["ok"] * 5, summary["error"].tolist()
    names = ["alpha", "beta", "gamma", "seq", "clip"]
    for name in names:
        doc = json.loads((out / f"{name}.reconstruction.json").read_text())
        assert doc["format"] == "curverecon.reconstruction/1"
    for name in ("seq", "clip"):
        obs = json.loads((out / f"{name}.observations.json").read_text())
        assert obs["format"] == "curverecon.observations/1" and len(obs["frames"]) >= 4
    assert not (out / "alpha.observations.json").exists()
    # the same defaults as `curverecon reconstruct`
    rec = curverecon.reconstruct(load_observations(data / "alpha.json"))
    row = summary.iloc[0]
    assert row["input"] == str(data / "alpha.json")
    assert math.isclose(row["c"], rec.shape[0], rel_tol=1e-9)
    assert math.isclose(row["alpha_deg"], math.degrees(rec.shape[1]), rel_tol=1e-9)
    assert row["frames"] == 12 and row["c_std"] > 0 and row["seconds"] >= 0
    # the GIF holds the image folder's frames: the same traced sequence, the same shape
    seq, clip = summary.iloc[3], summary.iloc[4]
    assert math.isclose(seq["c"], clip["c"], rel_tol=1e-6)
    on_disk = pd.read_csv(out / "summary.csv", keep_default_na=False, na_values=[""])
    assert on_disk["input"].tolist() == summary["input"].tolist()
    assert np.allclose(on_disk["c"], summary["c"])
    parquet = pd.read_parquet(out / "summary.parquet")
    assert list(parquet.columns) == CONTRACT_COLUMNS and len(parquet) == 5
    _valid_json_outputs(out)


def test_failures_are_recorded_and_the_rest_goes_on(data, tmp_path, client, capsys):
    bad = tmp_path / "bad"
    bad.mkdir()
    (bad / "broken.json").write_text('{"format": "curverecon.observations/1", "frames": [')
    (bad / "nan.json").write_text(
        '{"format": "curverecon.observations/1", "frames": [{"A": [NaN, 1], "B": [2, 3], '
        '"tangent_A": [1, 0], "tangent_B": [0, 1]}]}'
    )
    _scene_file(bad / "short.json", 4, frames=3)
    (bad / "noise.mp4").write_bytes(b"\x00not a video at all" * 40)
    (bad / "nothing").mkdir()
    (bad / "nothing" / "notes.txt").write_text("no frames here")
    out = tmp_path / "out"
    status = main(
        ["batch", str(data / "alpha.json"), str(bad), "-o", str(out),
         "--scheduler", client.scheduler.address]
    )  # fmt: skip
    assert status == 3
    err = capsys.readouterr().err
    assert "Traceback" not in err
    assert len(err.strip().splitlines()) == 1 and "5 failed" in err  # not a TTY: one line
    summary = pd.read_csv(out / "summary.csv", keep_default_na=False)
    by_name = {Path(i).name: r for i, r in zip(summary["input"], summary.itertuples(), strict=True)}
    assert by_name["alpha.json"].status == "ok"
    expected = {
        "broken.json": "malformed JSON",
        "nan.json": "non-finite",
        "short.json": "frame",
        "noise.mp4": "cannot read",
        "nothing": "no image files",
    }
    for name, words in expected.items():
        row = by_name[name]
        assert row.status == "error", name
        assert words in row.error and "\n" not in row.error, (name, row.error)
    assert (out / "alpha.reconstruction.json").exists()
    assert not (out / "broken.reconstruction.json").exists()
    _valid_json_outputs(out)


@pytest.mark.parametrize(
    "case",
    ["no inputs", "missing", "unwritable", "same name", "single image"],
)
def test_bad_arguments_exit_2_before_anything_starts(data, tmp_path, case, capsys):
    out = tmp_path / "out"
    args = {
        "no inputs": [],
        "missing": [str(data / "alpha.json"), str(tmp_path / "absent.json")],
        "unwritable": [str(data / "alpha.json")],
        "same name": [str(data / "alpha.json"), str(tmp_path / "alpha.json")],
        "single image": [str(sorted((data / "seq").glob("*.png"))[0])],
    }[case]
    if case == "same name":
        _scene_file(tmp_path / "alpha.json", 9)
    if case == "unwritable":
        (tmp_path / "a_file").write_text("")
        out = tmp_path / "a_file" / "out"  # a folder cannot be made inside a file
    status = main(["batch", *args, "-o", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert status == 2
    assert len(err) == 1 and err[0].startswith("curverecon: error: "), err
    assert not out.exists()


def test_progress_bar_counts_inputs_done_failed_and_running(data, tmp_path, client, capsys):
    broken = tmp_path / "broken.json"
    broken.write_text("{")
    summary = run([data / "alpha.json", broken], tmp_path / "out", client=client, progress=True)
    assert summary["status"].tolist() == ["ok", "error"]
    err = capsys.readouterr().err
    assert "2/2" in err and "failed=1" in err and "running=0" in err


def test_without_the_extra_the_command_says_what_to_install(data, tmp_path, monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "dask.distributed", None)
    status = main(["batch", str(data / "alpha.json"), "-o", str(tmp_path / "out")])
    err = capsys.readouterr().err.strip()
    assert status == 2
    assert 'pip install "curverecon[batch]"' in err and len(err.splitlines()) == 1


def test_help_imports_neither_dask_nor_pandas():
    import subprocess

    code = (
        "import sys\n"
        "from curverecon.cli import build_parser\n"
        "build_parser().format_help()\n"
        "print(sorted(m for m in ('dask', 'distributed', 'pandas') if m in sys.modules))\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "[]"


def test_second_run_redoes_only_missing_or_older_outputs(data, tmp_path, client):
    src = tmp_path / "src"
    src.mkdir()
    for seed in (11, 12, 13):
        _scene_file(src / f"s{seed}.json", seed)
    out = tmp_path / "out"
    first = run([src], out, client=client)
    assert (first["status"] == "ok").all() and first.attrs["skipped"] == 0
    outputs = {p.name: p.stat().st_mtime_ns for p in out.glob("*.reconstruction.json")}
    # an interrupted run's leftovers: a temporary file, and a broken output newer than its input
    (out / ".s12.reconstruction.json.1.2.tmp").write_text('{"format": "curv')
    (out / "s12.reconstruction.json").write_text('{"format": "curverecon.reconstruction/1", ')
    # an input changed after its output was written
    later = time.time() + 5
    os.utime(src / "s13.json", (later, later))
    second = run([src], out, client=client)
    assert second.attrs["skipped"] == 1
    assert (second["status"] == "ok").all()
    again = {p.name: p.stat().st_mtime_ns for p in out.glob("*.reconstruction.json")}
    assert again["s11.reconstruction.json"] == outputs["s11.reconstruction.json"]
    assert again["s13.reconstruction.json"] != outputs["s13.reconstruction.json"]
    pd.testing.assert_frame_equal(
        first.drop(columns="seconds"), second.drop(columns="seconds"), check_exact=False
    )
    assert second["seconds"].iloc[0] == first["seconds"].iloc[0]  # the row of the first run
    _valid_json_outputs(out)
    forced = run([src], out, client=client, force=True)
    assert forced.attrs["skipped"] == 0
    final = {p.name: p.stat().st_mtime_ns for p in out.glob("*.reconstruction.json")}
    assert all(final[k] > again[k] for k in final)


def test_a_killed_worker_loses_nothing(tmp_path, client):
    """SIGKILL one of the two workers while it runs a task: Dask runs the task on another
    worker; the summary is complete and every output is valid JSON."""
    src = tmp_path / "src"
    src.mkdir()
    for seed in range(20, 30):
        _scene_file(src / f"k{seed}.json", seed)
    out = tmp_path / "out"
    pids = client.run(os.getpid)
    victim = sorted(pids)[0]
    result: dict = {}

    def batch() -> None:
        result["summary"] = run([src], out, client=client)

    thread = threading.Thread(target=batch)
    thread.start()
    deadline = time.monotonic() + 60
    killed = False
    while time.monotonic() < deadline and thread.is_alive():
        if client.processing().get(victim):
            os.kill(pids[victim], signal.SIGKILL)
            killed = True
            break
        time.sleep(0.02)
    thread.join(timeout=120)
    assert killed and not thread.is_alive()
    summary = result["summary"]
    assert len(summary) == 10 and (summary["status"] == "ok").all(), summary["error"].tolist()
    docs = _valid_json_outputs(out)
    assert sum(d.get("format") == "curverecon.reconstruction/1" for d in docs) == 10
    assert victim not in client.scheduler_info()["workers"]  # that worker is gone
