"""Property-based fuzzing of every loader and entry point of the command.

Strategies start from valid documents (a simulated scene, the bundled flat-curve examples) and
mutate them: drop a key, retype a value, put NaN / infinity / huge numbers in, truncate the
text, nest, duplicate.  The property, for every input: exit status 0 with a strict-JSON output
file (no NaN, no infinity anywhere), or exit status 2 with exactly one line on stderr; never a
traceback.  The command runs in-process (``cli.main``); a few cases also run as a real process.

Budgets: the "ci" hypothesis profile (derandomised, ``make test``) or "fuzz" (``make fuzz``),
see tests/conftest.py.
"""

from __future__ import annotations

import contextlib
import copy
import io
import json
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from curverecon.cli import main
from curverecon.io import observations_to_dict
from curverecon.simulate import make_scene

ROOT = Path(__file__).resolve().parents[1]
BUDGET = settings.default.max_examples

OBSERVATIONS = observations_to_dict(
    make_scene(np.random.default_rng(0), 5, point_sigma=0.5, tangent_sigma_deg=0.5).observations
)
WITH_CURVES = observations_to_dict(
    make_scene(np.random.default_rng(1), 4, with_curve=True).observations
)
FLAT = [json.loads((ROOT / "examples" / f).read_text()) for f in ("flat_orthographic.json",)]

ODD_VALUES = st.sampled_from(
    [None, True, "x", "", [], {}, [1], [1, 2, 3], {"a": 1}, 0, -1, 1e308, -1e308, 1e-320, 2**70]
)
NON_FINITE = st.sampled_from([math.nan, math.inf, -math.inf])


def _paths(doc, prefix=()):
    """Every (container path, key) in a JSON document."""
    out = []
    if isinstance(doc, dict):
        for k, v in doc.items():
            out.append((prefix, k))
            out += _paths(v, (*prefix, k))
    elif isinstance(doc, list):
        for i, v in enumerate(doc):
            out.append((prefix, i))
            out += _paths(v, (*prefix, i))
    return out


def _container(doc, path):
    for p in path:
        doc = doc[p]
    return doc


@st.composite
def mutated_text(draw, base) -> str:
    """A valid document with 0-3 mutations, as text (sometimes truncated or nested)."""
    doc = copy.deepcopy(base)
    for _ in range(draw(st.integers(0, 3))):
        paths = _paths(doc)
        if not paths:
            break
        path, key = draw(st.sampled_from(paths))
        box = _container(doc, path)
        op = draw(st.sampled_from(["drop", "retype", "nonfinite", "scale", "duplicate", "nest"]))
        if op == "drop":
            del box[key]
        elif op == "retype":
            # a copy: sampled_from hands out the same list / dict object every time, and a later
            # mutation inside it would change the strategy itself (or make the document cyclic)
            box[key] = copy.deepcopy(draw(ODD_VALUES))
        elif op == "nonfinite":
            box[key] = draw(NON_FINITE)
        elif op == "scale":
            if isinstance(box[key], int | float) and not isinstance(box[key], bool):
                box[key] = box[key] * draw(st.sampled_from([0.0, -1.0, 1e-12, 1e12, 1e300]))
        elif op == "duplicate" and isinstance(box, list):
            box.append(copy.deepcopy(box[key]))
        elif op == "nest":
            box[key] = [box[key]]
    text = json.dumps(doc)  # writes NaN / Infinity literals: the reader must refuse them
    form = draw(st.sampled_from(["plain", "plain", "plain", "truncate", "deep", "binary"]))
    if form == "truncate":
        text = text[: draw(st.integers(0, max(0, len(text) - 1)))]
    elif form == "deep":
        depth = draw(st.sampled_from([10, 1000, 100_000]))
        text = "[" * depth + text + "]" * depth
    elif form == "binary":
        text = text[:20] + "\x00\xff\ufffe" + text[20:]
    return text


CASE_LOG = os.environ.get("CURVERECON_FUZZ_LOG")
"""If set, a file to which every case appends one line, "ok" or "traceback" (``bench/fuzz.py``)."""


def _run(argv: list[str]) -> tuple[int, str]:
    err = io.StringIO()
    outcome = "traceback"
    try:
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            status = main(argv)
        outcome = "ok"
    finally:
        if CASE_LOG:
            with open(CASE_LOG, "a") as fh:
                fh.write(outcome + "\n")
    return status, err.getvalue()


def _strict(path: Path):
    def refuse(name):
        raise AssertionError(f"non-finite {name} in {path}")

    return json.loads(path.read_text(), parse_constant=refuse)


def _check(status: int, stderr: str, out: Path) -> None:
    lines = [line for line in stderr.splitlines() if line.strip()]
    if status == 0:
        _strict(out)
        assert all(line.startswith("curverecon: warning: ") for line in lines)
    else:
        assert status == 2, stderr
        errors = [line for line in lines if line.startswith("curverecon: error: ")]
        assert len(errors) == 1 and lines[-1] == errors[0], stderr
        assert "Traceback" not in stderr


def _reconstruct(text: str, *flags: str) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        src, out = Path(tmp) / "in.json", Path(tmp) / "out.json"
        src.write_bytes(text.encode("utf-8", "surrogatepass"))
        status, stderr = _run(["reconstruct", str(src), "-o", str(out), *flags])
        _check(status, stderr, out)


@settings(max_examples=max(5, BUDGET // 2))
@given(mutated_text(OBSERVATIONS))
def test_reconstruct_answers_or_refuses_in_one_line(text):
    _reconstruct(text)


@settings(max_examples=max(3, BUDGET // 8))
@given(mutated_text(WITH_CURVES))
def test_reconstruct_with_polylines_answers_or_refuses_in_one_line(text):
    _reconstruct(text, "--curve-bundle", "off")


@settings(max_examples=BUDGET)
@given(mutated_text(FLAT[0]))
def test_match_flat_answers_or_refuses_in_one_line(text):
    with tempfile.TemporaryDirectory() as tmp:
        src, out = Path(tmp) / "in.json", Path(tmp) / "out.json"
        src.write_bytes(text.encode("utf-8", "surrogatepass"))
        status, stderr = _run(["match-flat", str(src), "-o", str(out)])
        _check(status, stderr, out)


FLAG_VALUES = st.sampled_from(
    ["-1", "0", "1", "4", "2.5", "nan", "inf", "-inf", "1e400", "x", "", "99999999999999999999"]
)


@settings(max_examples=BUDGET)
@given(
    st.lists(
        st.tuples(
            st.sampled_from(
                [
                    "--frames",
                    "--point-noise",
                    "--tangent-noise",
                    "--seed",
                    "--outlier-fraction",
                    "--chord",
                    "--with-curve",
                    "--bogus",
                ]
            ),
            FLAG_VALUES,
            FLAG_VALUES,
        ),
        max_size=4,
    )
)
def test_simulate_flags_answer_or_refuse_in_one_line(flags):
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "s.json"
        argv = ["simulate", "-o", str(out)]
        for flag, v1, v2 in flags:
            argv += {"--with-curve": [flag], "--chord": [flag, v1, v2]}.get(flag, [flag, v1])
        status, stderr = _run(argv)
        _check(status, stderr, out)


@settings(max_examples=max(5, BUDGET // 4))
@given(
    st.lists(
        st.tuples(
            st.sampled_from(
                [
                    "--method",
                    "--estimator",
                    "--point-sigma",
                    "--tangent-sigma",
                    "--curve-bundle",
                    "-o",
                ]
            ),
            st.one_of(FLAG_VALUES, st.sampled_from(["auto", "linear", "ml", "marginal", "on"])),
        ),
        max_size=3,
    )
)
def test_reconstruct_flags_answer_or_refuse_in_one_line(flags):
    with tempfile.TemporaryDirectory() as tmp:
        src, out = Path(tmp) / "in.json", Path(tmp) / "out.json"
        src.write_text(json.dumps(OBSERVATIONS))
        argv = ["reconstruct", str(src), "-o", str(out)]
        for flag, value in flags:
            argv += [flag, value if flag != "-o" else str(Path(tmp) / (value or "x"))]
        status, stderr = _run(argv)
        if status == 0 and not out.exists():  # "-o" given twice: the last one was written
            return
        _check(status, stderr, out)


@pytest.mark.parametrize(
    "argv, content",
    [
        (["reconstruct", "{in}", "-o", "{out}"], "[" * 100_000 + "]" * 100_000),
        (["match-flat", "{in}", "-o", "{out}"], "[" * 100_000 + "]" * 100_000),
        (["reconstruct", "{in}", "-o", "{out}"], "\x00\x01\x02binary"),
        (["simulate", "-o", "{out}", "--seed", "-1"], None),
        (["simulate", "-o", "{out}", "--frames", "100000000000"], None),
    ],
)
def test_real_process_exits_2_with_one_line(tmp_path, argv, content):
    """The cases that once ended in a traceback, run as a user runs them."""
    src = tmp_path / "in.json"
    if content is not None:
        src.write_text(content)
    argv = [a.format(**{"in": src, "out": tmp_path / "out.json"}) for a in argv]
    proc = subprocess.run(
        [sys.executable, "-m", "curverecon", *argv], capture_output=True, text=True, timeout=120
    )
    assert proc.returncode == 2, proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1, proc.stderr
    assert proc.stderr.startswith("curverecon: error: ")
