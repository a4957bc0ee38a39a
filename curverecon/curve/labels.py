"""Which end is A in a frame, judged by its polyline (``"ends_identified": false`` with curves).

The end points and tangents of a frame decide its labelling only weakly where the two
labellings' predictions differ little (a quarter of the frames at 1 degree of tangent noise fit
both within chi2 4), and traced tangents misfit by 5-30 degrees.  A polyline runs from A to B
along the whole curve: the 3-D curve of a reconstruction, placed in the frame in either
labelling (A on the polyline's first point and B on its last, or the other way round) fits one
direction at the noise level and the other, for a curve whose two ends differ, by pixels.

Placing it (:func:`polyline_misfits`): under orthographic projection the image chord A'B' and the
curve's chord length fix the chord's direction in space up to the sign of its depth; what is
left is the turn of the curve about its chord, swept over ``TURNS`` angles for both signs (every
placement at once, no local fit: a local pose fit from the end points' pose, 20 evaluations a
frame, took 0.18 s per 16 frames and was the labelling stage's largest cost after the pipeline
runs).  The misfit is the RMS of the polyline's samples' distances to the projected curve and of
the projected curve's samples' distances to the polyline, at the best placement
(``curve.labels_kernel``).
"""

from __future__ import annotations

import math

import numpy as np

from curverecon.curve.labels_kernel import placement_mean_squares
from curverecon.curve.polyline import resample
from curverecon.model.observations import Observations
from curverecon.model.pose import rotations, translations
from curverecon.model.reconstruction import Reconstruction

CURVE_SAMPLES = 150
"""Points of the 3-D curve projected in the fit, and of the polyline its samples are measured
to (equal arc length; distances are to the nearest sample: a chord of 100-300 px leaves
0.2-0.6 px of spacing error at 60 samples, the noise level of a traced polyline)."""

POLYLINE_SAMPLES = 24
"""Points of the polyline (equal arc length) whose distance to the projected curve is fitted."""

TURNS = 48
"""Angles of the curve's turn about its chord swept per sign of the chord's depth (7.5 degrees
apart), the best refined by ``FINE`` turns within one step either side."""

FINE = 9
"""Turns of the refinement (1.9 degrees apart)."""


def _turns(
    chord: np.ndarray,
    image_chord: np.ndarray,
    angles: np.ndarray,
    signs: tuple = (1.0, -1.0),
) -> np.ndarray:
    """(len(signs) len(angles), 3, 3) rotations taking the 3-D ``chord`` to a vector
    projecting onto ``image_chord`` (its depth of each sign in ``signs``; zero where the image
    chord is the longer), each turned about that vector by each of ``angles`` (radians)."""
    cx, cy, cz = (float(x) for x in chord)
    length = math.sqrt(cx * cx + cy * cy + cz * cz)
    wx, wy = float(image_chord[0]), float(image_chord[1])
    depth = math.sqrt(max(length * length - wx * wx - wy * wy, 0.0))
    scale = 1.0 / max(length, 1e-12)
    v = (cx * scale, cy * scale, cz * scale)
    s, c = np.sin(angles)[:, None, None], np.cos(angles)[:, None, None]
    rots = []
    for sign in signs:
        u = np.array([wx, wy, sign * depth])
        u = u / max(math.sqrt(float(u @ u)), 1e-12)
        r0 = _align(v, (float(u[0]), float(u[1]), float(u[2])))
        k = _skew(u)
        turn = np.eye(3) + s * k + (1.0 - c) * (k @ k)  # Rodrigues about u
        rots.append(turn @ r0)
    return np.concatenate(rots)


def _skew(a) -> np.ndarray:  # type: ignore[no-untyped-def]
    """The matrix of the cross product with the 3-vector ``a`` (a x .)."""
    return np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])


def _align(v: tuple, u: tuple) -> np.ndarray:
    """The smallest rotation taking unit vector ``v`` to unit vector ``u`` (3-tuples)."""
    axis = (v[1] * u[2] - v[2] * u[1], v[2] * u[0] - v[0] * u[2], v[0] * u[1] - v[1] * u[0])
    s = math.sqrt(axis[0] ** 2 + axis[1] ** 2 + axis[2] ** 2)
    c = v[0] * u[0] + v[1] * u[1] + v[2] * u[2]
    if s < 1e-12:
        if c > 0:
            return np.eye(3)
        vv = np.array(v)
        p = np.eye(3)[int(np.argmin(np.abs(vv)))]  # half a turn about an axis normal to v
        n = np.cross(vv, p)
        n /= np.linalg.norm(n)
        return 2.0 * np.outer(n, n) - np.eye(3)
    k = _skew(axis)
    return np.eye(3) + k + k @ k * ((1.0 - c) / (s * s))


def placed_rms(body: np.ndarray, polyline: np.ndarray) -> float:
    """RMS (px) of the curve ``body`` (A first; any rigid placement) at its best placement on
    ``polyline`` with its A on the polyline's first point and its B on the last (module
    docstring): ``TURNS`` turns for either sign of the chord's depth (every third sample), then
    ``FINE`` turns within one step either side of the best for each sign (every sample: noise
    can favour the wrong sign's coarse best)."""
    rel = body - body[0]
    poly, _ = resample(polyline, POLYLINE_SAMPLES)
    dense, _ = resample(polyline, CURVE_SAMPLES)
    image_chord = polyline[-1] - polyline[0]
    step = 2.0 * np.pi / TURNS

    origin = np.ascontiguousarray(polyline[0], dtype=float)

    def mean_squares(rots: np.ndarray, stride: int) -> np.ndarray:
        # polyline samples to each placed curve, and the curve's samples to the polyline
        return placement_mean_squares(
            np.ascontiguousarray(rots),
            np.ascontiguousarray(rel[::stride]),
            origin,
            np.ascontiguousarray(poly[::stride]),
            dense,
            max(6 // stride, 1),
        )

    coarse = np.arange(TURNS) * step
    ms = mean_squares(_turns(rel[-1], image_chord, coarse), 3)  # every third sample
    rots = []
    for k, sign in enumerate((1.0, -1.0)):  # either sign: noise can favour the wrong one
        fine = coarse[int(np.argmin(ms[k * TURNS : (k + 1) * TURNS]))]
        fine = fine + np.linspace(-step, step, FINE)
        rots.append(_turns(rel[-1], image_chord, fine, (sign,)))
    return float(np.sqrt(np.min(mean_squares(np.concatenate(rots), 1))))


def polyline_misfits(
    rec: Reconstruction, obs: Observations, frames: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Per frame the RMS (px, :func:`placed_rms`) of ``rec.curve3d`` placed on the frame's
    polyline as labelled in ``obs`` and reversed (labels exchanged): (N,), (N,), NaN outside
    the mask ``frames``."""
    rot0 = rotations(rec.poses[:1])[0]
    t0 = translations(rec.poses[:1])[0]
    curve = np.asarray(rec.curve3d, float)
    arc = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(curve, axis=0), axis=1))]
    t = np.linspace(0.0, arc[-1], CURVE_SAMPLES)
    curve = np.column_stack([np.interp(t, arc, curve[:, k]) for k in range(3)])
    body = (curve - t0) @ rot0  # frame 0's camera coordinates to the curve frame
    same = np.full(obs.n_frames, np.nan)
    other = np.full(obs.n_frames, np.nan)
    for i in np.flatnonzero(frames):
        polyline = np.asarray(obs.curves[i], float)
        same[i] = placed_rms(body, polyline)
        other[i] = placed_rms(body, polyline[::-1])
    return same, other
