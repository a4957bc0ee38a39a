"""Property-based fuzzing of the configuration keys (``motion``, per-frame ``t`` and
``points``, optional tangents and polylines) through ``curverecon reconstruct``.

Documents of every row of the Section 2 table (``simulate_configuration``) are mutated, first in
their new keys (a motion of any name or type, times out of order or not numbers, further points
renamed, dropped or added, A or B among them), then by the generic mutations of
tests/test_fuzz.py.  The property, for every input: exit status 0 with a strict-JSON output, or
exit status 2 with exactly one line on stderr; never a traceback.
"""

from __future__ import annotations

import copy
import json
import math
import tempfile
from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st
from test_fuzz import BUDGET, ODD_VALUES, _check, _run, mutated_text

from curverecon.simulate import simulate_configuration

BASES = [
    simulate_configuration("fixed-axis", "AB", frames=5, seed=0, noise_px=0.5)[0],
    simulate_configuration("free", "ABC", frames=4, seed=1, noise_px=0.5, tangent_noise_deg=1)[0],
    simulate_configuration("uniform-rotation", "ABC", frames=5, seed=2, with_curve=True)[0],
    simulate_configuration("force-field", "AB", frames=10, seed=3, noise_px=1.0)[0],
]
for _doc in BASES:  # short polylines: the examples stay small
    for _frame in _doc["frames"]:
        if "curve" in _frame:
            _frame["curve"] = _frame["curve"][::15] + [_frame["curve"][-1]]

MOTION_VALUES = st.sampled_from(
    ["free", "uniform-rotation", "fixed-axis", "force-field", "rotation-free", "auto", "Free"]
)
NAMES = st.sampled_from(["A", "B", "C", "D", "", " ", "c", "é", "0"])
NUMBERS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(-(2**70), 2**70),
    ODD_VALUES,
)


@st.composite
def configuration_doc(draw) -> dict:
    """A configuration document with 0-3 mutations of its new keys."""
    doc = copy.deepcopy(draw(st.sampled_from(BASES)))
    frames = doc["frames"]
    for _ in range(draw(st.integers(0, 3))):
        i = draw(st.integers(0, len(frames) - 1))
        op = draw(st.sampled_from(["motion", "t", "t-drop", "point", "point-drop", "swap", "top"]))
        if op == "motion":
            doc["motion"] = draw(st.one_of(MOTION_VALUES, ODD_VALUES))
        elif op == "t":
            frames[i]["t"] = draw(NUMBERS)
        elif op == "t-drop":
            frames[i].pop("t", None)
        elif op == "point":
            pts = frames[i].setdefault("points", {})
            if isinstance(pts, dict):
                pts[draw(NAMES)] = [draw(NUMBERS), draw(NUMBERS)]
        elif op == "point-drop":
            pts = frames[i].get("points")
            if isinstance(pts, dict) and pts:
                pts.pop(sorted(pts)[0])
        elif op == "swap" and len(frames) > 1:
            j = draw(st.integers(0, len(frames) - 1))
            frames[i], frames[j] = frames[j], frames[i]
        elif op == "top":
            key = draw(st.sampled_from(["projection", "ends_identified", "tangents_from_curve"]))
            doc[key] = draw(st.one_of(st.sampled_from(["perspective", "stereo"]), ODD_VALUES))
    return doc


def _reconstruct(text: str, *flags: str) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        src, out = Path(tmp) / "in.json", Path(tmp) / "out.json"
        src.write_bytes(text.encode("utf-8", "surrogatepass"))
        status, stderr = _run(["reconstruct", str(src), "-o", str(out), "--quiet", *flags])
        _check(status, stderr, out)


@settings(max_examples=max(5, BUDGET // 2))
@given(configuration_doc())
def test_configuration_keys_answer_or_refuse_in_one_line(doc):
    _reconstruct(json.dumps(doc))


@settings(max_examples=max(5, BUDGET // 4))
@given(st.sampled_from(BASES).flatmap(mutated_text))
def test_mutated_configurations_answer_or_refuse_in_one_line(text):
    _reconstruct(text)


@settings(max_examples=max(5, BUDGET // 4))
@given(
    st.sampled_from(BASES),
    st.sampled_from(["free", "uniform-rotation", "fixed-axis", "force-field", "auto", "x", ""]),
)
def test_motion_flag_answers_or_refuses_in_one_line(doc, motion):
    _reconstruct(json.dumps(doc), "--motion", motion)


FLAG_VALUES = st.sampled_from(["-1", "0", "1", "3", "2.5", "nan", "inf", "x", "", "ABC", "AB"])


@settings(max_examples=BUDGET)
@given(
    st.sampled_from(["free", "uniform-rotation", "fixed-axis", "force-field"]),
    st.lists(
        st.tuples(
            st.sampled_from(
                ["--frames", "--noise-px", "--points", "--seed", "--curve-noise", "--tangents"]
            ),
            FLAG_VALUES,
        ),
        max_size=4,
    ),
)
def test_simulate_motion_flags_answer_or_refuse_in_one_line(motion, flags):
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "s.json"
        argv = ["simulate", "-o", str(out), "--motion", motion, "--frames", "4"]
        for flag, value in flags:
            argv += [flag] if flag == "--tangents" else [flag, value]
        status, stderr = _run(argv)
        _check(status, stderr, out)
        if status == 0:
            frames = json.loads(out.read_text())["frames"]
            assert all(math.isfinite(f["t"]) for f in frames)
