"""``--motion auto`` on perspective documents: ``python -m bench.persp_auto``.

For every perspective row (``ROWS``: the motion simulated and its traceable points) ``SCENES``
scenes of ``curverecon.simulate.simulate_camera_configuration`` (its default camera and
distance, 1 px, 20 frames, 30 for the force field), each seeded by (bench seed, row, scene),
are reconstructed with the document's motion set to "auto" (``rigid.select``: every motion the
points determine under a pinhole, chosen by nested likelihood-ratio tests and BIC).  Keys per
row ``persp_auto_<row>_...``: ``chosen_rate`` the fraction of scenes whose chosen motion is the
simulated one, ``choices`` how often each motion was chosen, ``seconds_median`` the median wall
time of one auto reconstruction (every candidate fitted).  Not registered in
``bench.__main__``: ``run(seed, scenes, workers, rows)`` returns the keys, the command prints
them as JSON (``--rows`` a part, ``--detail`` every scene's scores and tests).
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402

import numpy as np  # noqa: E402

from bench.common import Task, chunks, run_tasks  # noqa: E402

ROWS = {
    "rotation_free": ("rotation-free", "AB"),
    "uniform_rotation": ("uniform-rotation", "AB"),
    "fixed_axis_3pt": ("fixed-axis", "ABC"),
    "free_4pt": ("free", "ABCD"),
    "force_field": ("force-field", "AB"),
}
SCENES = 20
"""Scenes per row (the least count for a rate the product asks for)."""
CHUNK = 5
DEFAULT_SEED = 0


def scene_seed(seed: int, row: int, index: int) -> int:
    return int(np.random.SeedSequence([seed, 39, row, index]).generate_state(1)[0])


def auto_scenes(seed: int, row: int, indices: range) -> list[dict]:
    """Per scene: the chosen motion (None with the error's message) and the wall time."""
    from curverecon.io import observations_from_dict
    from curverecon.options import ReconstructOptions
    from curverecon.rigid import reconstruct_rigid
    from curverecon.simulate import simulate_camera_configuration

    motion, names = list(ROWS.values())[row]
    frames = 30 if motion == "force-field" else 20
    out = []
    for i in indices:
        doc, _ = simulate_camera_configuration(
            "perspective", motion, names, frames, scene_seed(seed, row, i), noise_px=1.0
        )
        doc["motion"] = "auto"
        start = time.perf_counter()
        rec = {"index": i, "chosen": None}
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                got = reconstruct_rigid(observations_from_dict(doc), ReconstructOptions())
            rec["chosen"] = got.motion_scores["chosen"]
            rec["bic"] = {m: v["bic"] for m, v in got.motion_scores["scores"].items()}
            rec["p"] = {f"{t['simple']}<{t['complex']}": t["p"] for t in got.motion_scores["tests"]}
        except Exception as exc:  # noqa: BLE001 (a failure is counted, not raised)
            rec["message"] = str(exc)
        rec["seconds"] = time.perf_counter() - start
        out.append(rec)
    return out


def run(
    seed: int = DEFAULT_SEED,
    scenes: int = SCENES,
    workers: int = 1,
    rows: tuple[str, ...] = tuple(ROWS),
    detail: bool = False,
) -> dict:
    """The keys (module docstring) of ``rows`` (a subset of ``ROWS``); with ``detail`` also
    ``persp_auto_<row>_per_scene``: each scene's choice, every candidate's BIC and every nested
    test's p."""
    tasks = [
        Task(auto_scenes, (seed, row, idx), len(idx), f"{row}|{idx.start}")
        for row, key in enumerate(ROWS)
        if key in rows
        for idx in chunks(scenes, CHUNK)
    ]
    groups = run_tasks(tasks, workers, "persp auto", progress=False)
    out: dict = {}
    for row, (key, (motion, _)) in enumerate(ROWS.items()):
        recs = [r for label, g in groups.items() if label.split("|")[0] == str(row) for r in g]
        if not recs:
            continue
        chosen = [r["chosen"] for r in recs]
        pre = f"persp_auto_{key}_"
        out[pre + "chosen_rate"] = float(np.mean([c == motion for c in chosen]))
        out[pre + "choices"] = {str(c): chosen.count(c) for c in sorted(set(map(str, chosen)))}
        out[pre + "seconds_median"] = float(np.median([r["seconds"] for r in recs]))
        out[pre + "scenes"] = len(recs)
        if detail:
            out[pre + "per_scene"] = sorted(recs, key=lambda r: r["index"])
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seed", type=int, default=DEFAULT_SEED)
    parser.add_argument("--scenes", type=int, default=SCENES)
    parser.add_argument("--workers", type=int, default=1)
    parser.add_argument("--rows", nargs="+", choices=list(ROWS), default=list(ROWS))
    parser.add_argument("--detail", action="store_true", help="every scene's scores and tests")
    args = parser.parse_args()
    out = run(args.seed, args.scenes, args.workers, tuple(args.rows), args.detail)
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
