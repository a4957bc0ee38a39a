"""The command line: every bad input exits 2 with one line on stderr; the library raises."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from curverecon.cli import COMMANDS, main
from curverecon.errors import CurveReconError
from curverecon.io import observations_from_dict, observations_to_dict
from curverecon.pipeline import reconstruct
from curverecon.simulate import make_scene


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "curverecon", *args], capture_output=True, text=True, timeout=120
    )


def _doc(n=6, seed=0):
    return observations_to_dict(make_scene(np.random.default_rng(seed), n, 0.5, 0.5).observations)


def _few_frames():
    d = _doc()
    d["frames"] = d["frames"][:3]
    return json.dumps(d)


def _nan():
    d = _doc()
    d["frames"][0]["A"][0] = float("nan")  # json.dumps writes NaN
    return json.dumps(d)


def _inf():
    d = _doc()
    d["frames"][1]["tangent_B"] = [1e308 * 10, 1.0]  # json.dumps writes Infinity
    return json.dumps(d)


def _coincide():
    d = _doc()
    d["frames"][2]["B"] = list(d["frames"][2]["A"])
    return json.dumps(d)


def _perpendicular():
    d = _doc()
    f = d["frames"][3]
    ch = np.subtract(f["B"], f["A"])
    f["tangent_B"] = [-ch[1], ch[0]]  # parallel to l1: d' infinite
    return json.dumps(d)


def _degenerate():
    """Frames related by in-plane rotations, translations and scales of one frame."""
    d = _doc()
    f0 = d["frames"][0]
    frames = []
    for k in range(6):
        ang, sc, sh = 0.4 * k, 1.0 + 0.1 * k, np.array([10.0 * k, -3.0 * k])
        rot = np.array([[np.cos(ang), -np.sin(ang)], [np.sin(ang), np.cos(ang)]])
        frames.append(
            {
                "A": (sc * rot @ f0["A"] + sh).tolist(),
                "B": (sc * rot @ f0["B"] + sh).tolist(),
                "tangent_A": (rot @ f0["tangent_A"]).tolist(),
                "tangent_B": (rot @ f0["tangent_B"]).tolist(),
            }
        )
    d["frames"] = frames
    return json.dumps(d)


def _wrong_tag():
    d = _doc()
    d["format"] = "curverecon.observations/2"
    return json.dumps(d)


def _missing_key():
    d = _doc()
    del d["frames"][4]["tangent_A"]
    return json.dumps(d)


BAD = {
    "fewer than 4 frames": (_few_frames, "at least 4"),
    "NaN": (_nan, "finite"),
    "inf": (_inf, "finite"),
    "A equals B": (_coincide, "coincide"),
    "tangent perpendicular to A'B'": (_perpendicular, "perpendicular"),
    "degenerate motion": (_degenerate, "degenerate motion"),
    "malformed JSON": (lambda: '{"format": "curverecon.observations/1", "frames": [', "malformed"),
    "wrong format tag": (_wrong_tag, "wrong format tag"),
    "missing key": (_missing_key, 'missing key "tangent_A"'),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_input_exits_2_with_one_line(tmp_path, case):
    make, needle = BAD[case]
    inp = tmp_path / "in.json"
    inp.write_text(make())
    proc = run("reconstruct", str(inp), "-o", str(tmp_path / "out.json"))
    assert proc.returncode == 2, proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("curverecon: error: ") and needle in lines[0]
    assert not (tmp_path / "out.json").exists()


@pytest.mark.parametrize("case", sorted(set(BAD) - {"malformed JSON"}))
def test_bad_input_raises_in_the_library(case):
    make, needle = BAD[case]
    with pytest.raises(CurveReconError) as err:
        reconstruct(observations_from_dict(json.loads(make())))
    assert needle in str(err.value) and "\n" not in str(err.value)
    assert isinstance(err.value, ValueError)


def test_usage_errors_are_one_line(tmp_path):
    proc = run("reconstruct", str(tmp_path / "x.json"))  # no -o
    assert proc.returncode == 2 and len(proc.stderr.strip().splitlines()) == 1
    proc = run("reconstruct", str(tmp_path / "missing.json"), "-o", str(tmp_path / "o.json"))
    assert proc.returncode == 2 and "cannot read" in proc.stderr
    inp = tmp_path / "in.json"
    inp.write_text(json.dumps(_doc()))
    for option, value in (("--estimator", "bayes"), ("--curve-bundle", "maybe")):
        proc = run("reconstruct", str(inp), "-o", str(tmp_path / "o.json"), option, value)
        assert proc.returncode == 2 and len(proc.stderr.strip().splitlines()) == 1
        assert value in proc.stderr


def test_linear_with_too_few_frames(tmp_path):
    inp = tmp_path / "in.json"
    inp.write_text(json.dumps(_doc(10)))
    proc = run("reconstruct", str(inp), "-o", str(tmp_path / "o.json"), "--method", "linear")
    assert proc.returncode == 2 and "at least 38 frames" in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1


def test_simulate_then_reconstruct(tmp_path):
    scene, truth, out = tmp_path / "s.json", tmp_path / "t.json", tmp_path / "r.json"
    proc = run(
        "simulate",
        "-o",
        str(scene),
        "--truth",
        str(truth),
        "--frames",
        "12",
        "--point-noise",
        "0.5",
        "--tangent-noise",
        "0.5",
        "--seed",
        "7",
    )
    assert proc.returncode == 0, proc.stderr
    proc = run("reconstruct", str(scene), "-o", str(out))
    assert proc.returncode == 0, proc.stderr
    rec, tru = json.loads(out.read_text()), json.loads(truth.read_text())
    assert rec["format"] == "curverecon.reconstruction/1"
    for key in ("c", "alpha_deg", "beta_deg", "phi_deg", "frames", "outlier_frames"):
        assert key in rec
    assert len(rec["frames"]) == 12
    for frame in rec["frames"]:
        for key in ("delta_deg", "tau_deg", "A3", "B3", "tangent_A3", "tangent_B3", "inlier"):
            assert key in frame
        assert frame["A3"][2] == 0.0
    assert abs(rec["c"] / tru["c"] - 1) < 0.05
    for key in ("alpha_deg", "beta_deg", "phi_deg"):
        assert abs(rec[key] - tru[key]) < 5.0


def test_every_command_has_its_help(capsys):
    with pytest.raises(SystemExit) as done:
        main(["--help"])
    assert done.value.code == 0
    listing = capsys.readouterr().out
    for name, command in COMMANDS.items():
        assert name in listing and command.help in listing
        with pytest.raises(SystemExit) as done:
            main([name, "--help"])
        assert done.value.code == 0
        assert f"usage: curverecon {name}" in capsys.readouterr().out


def test_the_former_family_option_is_hidden(capsys):
    with pytest.raises(SystemExit):
        main(["simulate", "--help"])
    text = capsys.readouterr().out
    assert "--family" in text and "--curve-family" not in text
    assert "clothoid" in text and "loop" in text


def test_a_missing_command_names_every_command(capsys):
    assert main([]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and all(name in err[0] for name in COMMANDS)
