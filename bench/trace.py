"""The ``trace`` section of ``make bench``: images to observations to the 3-D curve.

Sequences: ``curverecon.trace.render.tumbling_scene`` (16 frames of 384 px, a curve of the
families bezier, helix, wave in turn, 25 degrees of rotation a frame) drawn by
``render_frame`` (a Gaussian line of sigma 1.2 px and 160 grey levels, noise sd 8, a background
gradient of 60 grey levels).  Per sequence:

- every frame traced (``curverecon.trace.frame.trace_image``); the polyline error is the
  distance of each traced point to the true projected curve; the key is the median over all
  points of all sequences (``trace_polyline_error_px_median``);
- the end identity (``curverecon.trace.ends.assign_ends``) is right when every traced frame's A
  is the same true end (``trace_end_identity_rate``: the share of sequences right in every
  frame);
- on the first sequences, the traced observations (as ``curverecon trace`` writes them, with
  ``"tangents_from_curve": true``) go through ``curverecon.reconstruct`` and ``curve3d`` is
  compared with the true curve by ``bench.curve_end_to_end.curve_error``
  (mean distance over the curve's length, best over the mirror image):
  ``images_curve_error_median`` (relative) and ``images_curve_within_1pct_rate``.

Sequences of seeds 2000.. (``RANDOM_SEQUENCES``) show each frame in its own random orientation
(``tumbling_scene(independent=True)``): the same end-to-end keys with the suffix
``_random_orientations``, the document flagged ``"ends_identified": false`` where continuity
cannot establish the ends (``curverecon.trace.ends.ends_identified``), as ``curverecon trace``
writes it.

Seeds 0.. are those the tracer's options were set on; the ``*_heldout`` keys repeat the
figures on seeds 1000.. (not used for tuning).  ``trace_seconds_per_frame_512``: the median
wall time of ``trace_image`` on a rendered 512 x 512 frame (one thread).
The sequences run on every core (``_map_sequences``: fork processes, the end-to-end ones first);
each draws from its own seed, so the figures do not depend on the scheduling.
``python -m bench.trace [--quick]`` prints the figures as JSON.
"""

from __future__ import annotations

import json
import sys
import time

import numpy as np

FAMILIES = ("bezier", "helix", "wave")
RANDOM_SEQUENCES = 6
"""Sequences (seeds 2000..) whose frames are in independent random orientations
(``tumbling_scene(independent=True)``): continuity cannot tell the ends apart, the document says
``"ends_identified": false`` as ``curverecon trace`` writes it, and the reconstruction decides
each frame's labelling; keys ``*_random_orientations``."""


def _sequence(seed: int, end_to_end: bool, independent: bool = False) -> dict:
    from bench.curve_end_to_end import curve_error
    from curverecon.curve.polyline import distance_to_polyline
    from curverecon.io import OBSERVATIONS_FORMAT, observations_from_dict
    from curverecon.pipeline import reconstruct
    from curverecon.trace.ends import assign_ends, ends_identified, frame_record
    from curverecon.trace.frame import trace_image
    from curverecon.trace.options import TraceOptions
    from curverecon.trace.render import render_frame, tumbling_scene
    from curverecon.trace.topology import TraceFailure

    rng = np.random.default_rng(seed)
    family = FAMILIES[seed % len(FAMILIES)]
    scene = tumbling_scene(rng, 16, family=family, independent=independent)
    options = TraceOptions()
    curves, truths, errors, skipped, first, index = [], [], [], 0, None, []
    for k, truth in enumerate(scene.observations.curves):
        img = render_frame(truth, rng) / 255.0
        try:
            tr = trace_image(img, options)
        except TraceFailure:
            skipped += 1
            continue
        first = k if first is None else first
        curves.append(tr.curve)
        index.append(k)
        truths.append(truth)
        errors.append(distance_to_polyline(tr.curve, truth)[0])
    out = {"seed": seed, "family": family, "skipped": skipped, "errors": np.concatenate(errors)}
    if len(curves) < 4:
        out.update(end_ok=False, curve_error=np.inf if end_to_end else None)
        return out
    assignment = assign_ends(
        curves, options.ambiguity_ratio, index, fit_length=options.tangent_fit_length
    )
    oriented = [c[::-1] if f else c for c, f in zip(curves, assignment.flip, strict=True)]
    a_is_a = [
        np.hypot(*(c[0] - t[0])) < np.hypot(*(c[0] - t[-1]))
        for c, t in zip(oriented, truths, strict=True)
    ]
    out["end_ok"] = bool(all(a_is_a) or not any(a_is_a))
    out["curve_error"] = None
    if end_to_end:
        frames = [frame_record(c, options.tangent_fit_length) for c in oriented]
        # as ``curverecon trace`` writes them: the tangents are fits to the polylines
        doc = {"format": OBSERVATIONS_FORMAT, "frames": frames, "tangents_from_curve": True}
        if not ends_identified(assignment):  # as ``curverecon trace`` decides it
            doc["ends_identified"] = False
        out["ends_identified"] = "ends_identified" not in doc
        obs = observations_from_dict(doc)
        try:
            rec = reconstruct(obs)
            # the true curve in the first traced frame's camera, its A (the traced A) at z = 0
            t = scene.truth
            local = (scene.curve_3d - t.A3[0]) @ t.rotations[0]
            true_curve = local @ t.rotations[first].T + t.A3[first]
            if not a_is_a[0]:
                true_curve = true_curve - [0.0, 0.0, true_curve[-1, 2]]
            out["curve_error"] = curve_error(np.asarray(rec.curve3d), true_curve)
        except Exception:  # a failed reconstruction counts as a miss
            out["curve_error"] = np.inf
    return out


def _one(job: tuple) -> dict:
    return _sequence(*job)


def _map_sequences(jobs: list[tuple]) -> list[dict]:
    """``_sequence`` of every (seed, end_to_end[, independent]) job, in order, on every core
    (fork processes; the end-to-end jobs, the long ones, first).  Each sequence draws from its
    own seed: the results do not depend on the scheduling."""
    import multiprocessing as mp
    import os

    workers = min(len(jobs), os.cpu_count() or 1)
    if workers <= 1:
        return [_one(j) for j in jobs]
    order = sorted(range(len(jobs)), key=lambda i: not jobs[i][1])
    with mp.get_context("fork").Pool(workers, maxtasksperchild=1) as pool:
        results = pool.map(_one, [jobs[i] for i in order], chunksize=1)
    out: list[dict] = [{}] * len(jobs)
    for i, r in zip(order, results, strict=True):
        out[i] = r
    return out


def _speed_512(repeats: int) -> float:
    from curverecon.trace.frame import trace_image
    from curverecon.trace.render import RenderOptions, render_frame, tumbling_scene

    rng = np.random.default_rng(7)
    scene = tumbling_scene(rng, 1, size=512)
    img = render_frame(scene.observations.curves[0], rng, RenderOptions(size=512)) / 255.0
    trace_image(img)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        trace_image(img)
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def _summary(results: list[dict], suffix: str) -> dict:
    errs = np.concatenate([r["errors"] for r in results])
    curve = np.array([r["curve_error"] for r in results if r["curve_error"] is not None])
    out = {
        f"trace_polyline_error_px_median{suffix}": round(float(np.median(errs)), 4),
        f"trace_polyline_error_px_p90{suffix}": round(float(np.quantile(errs, 0.9)), 4),
        f"trace_end_identity_rate{suffix}": round(
            float(np.mean([r["end_ok"] for r in results])), 4
        ),
        f"trace_sequences{suffix}": len(results),
        f"trace_frames_skipped{suffix}": int(sum(r["skipped"] for r in results)),
    }
    if len(curve):
        out[f"images_curve_error_median{suffix}"] = round(float(np.median(curve)), 5)
        out[f"images_curve_within_1pct_rate{suffix}"] = round(float(np.mean(curve < 0.01)), 4)
        out[f"images_sequences{suffix}"] = int(len(curve))
    return out


def run(quick: bool = False) -> dict:
    import os

    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    n_trace, n_e2e = (6, 2) if quick else (21, 12)
    n_held, n_held_e2e = (3, 1) if quick else (9, 4)
    n_random = 1 if quick else RANDOM_SEQUENCES
    jobs = [(s, s < n_e2e) for s in range(n_trace)]
    jobs += [(1000 + s, s < n_held_e2e) for s in range(n_held)]
    jobs += [(2000 + s, True, True) for s in range(n_random)]
    results = _map_sequences(jobs)
    main, held = results[:n_trace], results[n_trace : n_trace + n_held]
    rand = results[n_trace + n_held :]
    out = _summary(main, "")
    out.update(_summary(held, "_heldout"))
    out.update(_summary(rand, "_random_orientations"))
    out["images_ends_identified_random_orientations"] = int(
        sum(bool(r.get("ends_identified")) for r in rand)
    )
    out["trace_seconds_per_frame_512"] = round(_speed_512(5 if quick else 20), 4)
    missed = [r["seed"] for r in main + held if not r["end_ok"]]  # continuity's own test
    out["trace_end_identity_missed_seeds"] = missed
    out["images_curve_error_by_seed"] = {
        str(r["seed"]): round(float(r["curve_error"]), 5)
        for r in main + held + rand
        if r["curve_error"] is not None
    }
    return out


if __name__ == "__main__":
    print(json.dumps(run("--quick" in sys.argv[1:]), indent=1))
