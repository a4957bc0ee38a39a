"""c's Cramer-Rao bound of the perspective force field with A and B: ``python -m
bench.persp_force_field_bound``.

An independent 3-D construction (not ``curverecon.simulate``'s): a body with A, B and the mass
centre G at 0.14 c from the chord, turning smoothly (rotation vector w1 tau + w2 tau^2 / 2 over
the sequence, total turn ``sweep``), G on a 3-D parabola about (0, 0, 1) (the scale: G's depth at
t = 0; lateral reach 0.12, depth reach 0.08 of the distance, as ``simulate``'s scenes), seen by a
pinhole whose focal length puts the chord at ``CHORD_PX``.  The Jacobian of every frame's A', B'
pixels in the unknowns (A - G and B - G in frame 0's orientation, the parabola less g0_z, every
later frame's rotation as a left increment) is written out by hand; c's bound at 1 px follows
from it.  ``bench_scene_bound`` takes ``simulate_camera_configuration``'s own scenes (their
truth; the earlier turns of 180-300 degrees or the default, ``simulate.FORCE_FIELD_TURN_DEG``)
instead.  Prints the median relative bound against the turn and the frame count, against
the body's size over its distance, the orthographic twin's, and the bench's scenes' against
distance and frames.  Registered nowhere (a study behind docs/accuracy.md's force-field bullet).
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

CHORD_PX = 160.0


def skew(v: np.ndarray) -> np.ndarray:
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def scene(
    rng: np.random.Generator, frames: int, sweep_deg: float, c: float = 0.2, offset: float = 0.14
):
    """(a, b, parabola (3, 3) rows g0, g1, g2, rotations (F, 3, 3), times, focal px)."""
    u = rng.uniform(-0.3, 0.3)
    a = np.array([(-0.5 - u) * c, -offset * c, 0.0])
    b = np.array([(0.5 - u) * c, -offset * c, 0.0])
    r0 = Rotation.random(random_state=rng).as_matrix()
    t = np.arange(frames, dtype=float)
    tau = t / (frames - 1)
    w1 = rng.normal(size=3)
    w1 *= np.radians(sweep_deg) / np.linalg.norm(w1)
    w2 = rng.normal(size=3)
    w2 *= rng.uniform(0, 0.5) * np.radians(sweep_deg) / np.linalg.norm(w2)
    rots = Rotation.from_rotvec(np.outer(tau, w1) + np.outer(tau**2 / 2, w2)).as_matrix()
    reach = np.array([0.12, 0.12, 0.08])
    acc = rng.uniform(2, 4, 3) * rng.choice([-1, 1], 3) * reach
    vel = rng.uniform(-1, 1, 3) * reach - acc / 2
    g = np.array([[0.0, 0.0, 1.0], vel / (frames - 1), acc / (frames - 1) ** 2])
    return r0 @ a, r0 @ b, g, rots, t, CHORD_PX / c


def jacobian(a, b, g, rots, t, focal, perspective: bool = True) -> np.ndarray:
    """d(pixels of A, B in every frame) / d(a, b, parabola, rotations) (module docstring); the
    orthographic twin (pixels = focal (x, y)) drops the parabola's depth."""
    n = len(t)
    keep = [0, 1, 3, 4, 5, 6, 7, 8] if perspective else [0, 1, 3, 4, 6, 7]
    ng = 6 + len(keep)
    jac = np.zeros((4 * n, ng + 3 * (n - 1)))
    for f in range(n):
        gf = g[0] + g[1] * t[f] + g[2] * t[f] ** 2 / 2
        dg = np.hstack([np.eye(3), np.eye(3) * t[f], np.eye(3) * t[f] ** 2 / 2])[:, keep]
        for k, q in enumerate((a, b)):
            x = gf + rots[f] @ q
            if perspective:
                proj = np.array([[1, 0, -x[0] / x[2]], [0, 1, -x[1] / x[2]]]) * focal / x[2]
            else:
                proj = np.eye(3)[:2] * focal
            rows = slice(4 * f + 2 * k, 4 * f + 2 * k + 2)
            jac[rows, 3 * k : 3 * k + 3] = proj @ rots[f]
            jac[rows, 6:ng] = proj @ dg
            if f > 0:
                jac[rows, ng + 3 * (f - 1) : ng + 3 * f] = -proj @ skew(rots[f] @ q)
    return jac


def chord_bound(jac: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    """c's Cramer-Rao bound relative to c at 1 px (columns scaled before the SVD)."""
    d = (a - b) / np.linalg.norm(a - b)
    grad = np.zeros(jac.shape[1])
    grad[0:3], grad[3:6] = d, -d
    s = np.linalg.norm(jac, axis=0)
    _, sv, vt = np.linalg.svd(jac / s, full_matrices=False)
    coef = vt @ (grad / s) / sv
    return float(np.sqrt(coef @ coef) / np.linalg.norm(a - b))


def median_bound(sweep_deg: float, frames: int, perspective: bool = True, scenes: int = 20,
                 seed: int = 5, c: float = 0.2, offset: float = 0.14) -> float:  # fmt: skip
    """Median over ``scenes`` constructions of c's relative bound at 1 px."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(scenes):
        a, b, g, rots, t, focal = scene(rng, frames, sweep_deg, c, offset)
        out.append(chord_bound(jacobian(a, b, g, rots, t, focal, perspective), a, b))
    return float(np.median(out))


def bench_scene_bound(seed: int, frames: int, distance: float, turn_deg=None) -> float:
    """c's relative bound at 1 px on ``simulate_camera_configuration``'s force-field scene
    (default camera at ``distance``; ``turn_deg`` its range of turns, default the
    simulation's), from its truth."""
    from curverecon.simulate import simulate_camera_configuration

    _, truth = simulate_camera_configuration(
        "perspective", "force-field", "AB", frames, seed, distance=distance, turn_deg=turn_deg
    )
    mp = truth["motion_parameters"]
    g = np.array([mp["position"], mp["velocity"], mp["acceleration"]])
    t = np.array(truth["times"])
    rots = np.array([fr["rotation"] for fr in truth["frames"]])
    g_t = g[0] + np.outer(t, g[1]) + np.outer(t**2 / 2, g[2])
    a = rots[0].T @ (np.array(truth["frames"][0]["A3"]) - g_t[0])
    b = rots[0].T @ (np.array(truth["frames"][0]["B3"]) - g_t[0])
    focal = 800.0  # the default camera keeps its image size: focal and distance scale alike
    return chord_bound(jacobian(a, b, g, rots, t, focal), a, b)


def tangent_bound(seed: int, frames: int = 30, tangent_deg: float = 0.5) -> float:
    """c's relative bound at 1 px and ``tangent_deg`` on ``simulate_camera_configuration``'s
    force-field scene with tangents: the runtime's Fisher information at the truth."""
    from bench.configurations_persp import truth_state
    from curverecon.io import observations_from_dict
    from curverecon.options import ReconstructOptions
    from curverecon.rigid import rigid_data
    from curverecon.rigid.answer import chord_std
    from curverecon.rigid.model import Layout
    from curverecon.rigid.refinement import information_inverse
    from curverecon.simulate import simulate_camera_configuration

    doc, truth = simulate_camera_configuration(
        "perspective", "force-field", "AB", frames, seed, tangent_noise_deg=tangent_deg
    )
    layout = Layout("force-field", ("A", "B"), True, "perspective")
    opts = ReconstructOptions(point_sigma=1.0, tangent_sigma_deg=tangent_deg)
    data = rigid_data(observations_from_dict(doc), opts)
    state = truth_state(layout, data, truth, "AB")
    cov, _ = information_inverse(layout, state, data)
    return chord_std(layout, state, cov) / float(np.linalg.norm(state.body[1] - state.body[0]))


def main() -> None:
    frames = (12, 20, 30, 60, 120)
    print("median relative bound of c, 1 px, chord 160 px, 20 scenes; rows: turn (degrees)")
    print("turn   " + "  ".join(f"F={f:<5d}" for f in frames))
    for sweep in (240.0, 360.0, 540.0, 720.0, 1080.0):
        row = [median_bound(sweep, f) for f in frames]
        print(f"{sweep:5.0f}  " + "  ".join(f"{v:7.3g}" for v in row), flush=True)
    for c in (0.02, 0.05, 0.1, 0.2, 0.4):
        print(f"720 degrees, 30 frames, chord / distance {c}: {median_bound(720.0, 30, c=c):.3g}")
    for offset in (0.0, 0.05, 0.14, 0.3, 0.6, 1.0):
        got = median_bound(720.0, 30, offset=offset)
        print(f"720 degrees, 30 frames, mass centre {offset} c from the chord: {got:.3g}")
    tangents = [tangent_bound(s) for s in range(3)]
    print("tangents (0.5 degrees), simulate's scenes, 30 frames, seeds 0-2:", *tangents)
    for sweep in (240.0, 720.0):
        ortho = median_bound(sweep, 30, perspective=False)
        print(f"orthographic twin, {sweep:.0f} degrees, 30 frames: {ortho:.3g}")
    print("simulate_camera_configuration's scenes (seeds 0-9): median [min, max]")
    for turn in ((180.0, 300.0), None):
        label = "turns 180-300 degrees" if turn else "the default turns, 720-1080 degrees"
        for distance in (1000.0, 500.0, 250.0) if turn else (1000.0,):
            for n in (12, 20, 30, 60) if turn else (16, 20, 30):
                got = [bench_scene_bound(s, n, distance, turn) for s in range(10)]
                print(f"{label}, distance {distance:.0f}, {n} frames: {np.median(got):.3g} "
                      f"[{min(got):.3g}, {max(got):.3g}]", flush=True)  # fmt: skip


if __name__ == "__main__":
    main()
