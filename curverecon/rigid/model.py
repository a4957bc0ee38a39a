"""The parametrisation of the orthographic Section 2 rows: body, motion model, per-frame parameters.

A rigid body is seen in frames f = 0 .. N-1 (times t_f) under orthographic projection.

* Body: every traceable point as a 3-vector relative to a reference point, in frame 0's camera
  coordinates.  The reference is A (A's body vector is 0; B, C, ... are free) for every row but
  the force field, whose reference is the mass centre G (every traceable point is free: G is an
  unobserved body point).  With tangents, the unit tangent directions at A and B as polar angles
  (polar from the viewing axis, azimuth in the image; frame 0).
* Motion: ``uniform-rotation``: R_f = Rot(n, w (t_f - t_0)), globals axis n(kappa, lam) and rate
  w (radians per unit of t); ``fixed-axis``: R_f = Rot(n, theta_f), globals n, locals theta_f
  (theta_0 = 0); ``free``: R_f any rotation (local, R_0 = I); ``force-field``: R_f any rotation
  and the mass centre's image on the parabola g0 + g1 t + g2 t^2 / 2 (globals g0, g1, g2).
* Per frame: the image of the reference point s_f (free, two locals) except for the force field
  (its parabola); rotations of the free and force-field rows as three locals (left increments).

Orthographic depth is unobservable: every body vector is relative to the reference point, so a
shift in depth never enters.  The mirror (z -> -z, with R_f -> S R_f S, S = diag(1, 1, -1)) maps
solutions to solutions; :func:`normalise` picks the mirror image in which B lies at or behind A in
frame 0 (B's body z minus A's >= 0) and the axis sign with a non-negative rate (uniform
rotation) or a non-negative sum of angles (fixed axis).

Measurements per frame: every traceable point's image (input units), then with tangents the image
angles of the tangents at A and B (radians, lines: residuals wrapped to (-pi/2, pi/2]).
Lengths in input units, angles in radians, t in the input's units.

Under a pinhole camera or a stereo pair (``Layout.projection`` "perspective" or "stereo"; the
measurement model of ``generated/rigid_pinhole.py``) the same parameters gain depth: the
reference point's image s_f becomes its 3-D position T_f in frame f's camera coordinates (three
locals; the force field's mass centre moves on a 3-D parabola, g0, g1, g2 three-vectors), a body
point is at X_f = T_f + R_f q, and ``rotation-free`` has R_f = I.  Perspective's one free scale
is fixed by A's depth in frame 0 (T_0z = 1, a fixed local) or, for the force field, by the
parabola's g0_z = 1 (a fixed global; the answer is rescaled to A's depth); stereo is metric.
No mirror: a pinhole tells near from far.  Lengths in the answer's units, images in pixels.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from curverecon.generated import rigid_model as gm

MOTIONS = ("uniform-rotation", "fixed-axis", "free", "force-field", "rotation-free")
AXIS_MOTIONS = ("uniform-rotation", "fixed-axis")


@dataclass(frozen=True)
class Layout:
    """Which parameters a row has: the motion model, the traceable points (A first), tangents."""

    motion: str
    points: tuple[str, ...]
    tangents: bool
    projection: str = "orthographic"

    @property
    def pinhole(self) -> bool:
        """A perspective or stereo row (depth in the parameters)."""
        return self.projection != "orthographic"

    @property
    def views(self) -> int:
        """Cameras seeing every frame (2 for stereo)."""
        return 2 if self.projection == "stereo" else 1

    @property
    def position_size(self) -> int:
        """Coordinates of the reference point's per-frame position (3 with depth, else 2)."""
        return 3 if self.pinhole else 2

    @property
    def rotation_local(self) -> int:
        """Index of the first rotation local (free rotations) in a frame's locals."""
        return 0 if self.centred else self.position_size

    @property
    def angle_local(self) -> int:
        """Index of the fixed axis's angle in a frame's locals."""
        return self.n_local - 1

    @property
    def centred(self) -> bool:
        """The reference point is the mass centre (force field), not A."""
        return self.motion == "force-field"

    @property
    def n_body(self) -> int:
        """Number of free body vectors."""
        return len(self.points) if self.centred else len(self.points) - 1

    @property
    def n_motion(self) -> int:
        ff = 3 * self.position_size
        return {"uniform-rotation": 3, "fixed-axis": 2, "free": 0, "force-field": ff}.get(
            self.motion, 0
        )

    @property
    def n_global(self) -> int:
        return 3 * self.n_body + (4 if self.tangents else 0) + self.n_motion

    @property
    def free_rotations(self) -> bool:
        return self.motion in ("free", "force-field")

    @property
    def n_local(self) -> int:
        return (
            (0 if self.centred else self.position_size)
            + (3 if self.free_rotations else 0)
            + (1 if self.motion == "fixed-axis" else 0)
        )

    @property
    def n_measurements(self) -> int:
        """Measurements per frame: two per point, one per tangent, in every view."""
        return self.views * (2 * len(self.points) + (2 if self.tangents else 0))

    def global_names(self) -> list[str]:
        names = [f"{p}_{k}" for p in self.body_points() for k in "xyz"]
        if self.tangents:
            names += ["tA_polar", "tA_azimuth", "tB_polar", "tB_azimuth"]
        names += {
            "uniform-rotation": ["axis_kappa", "axis_lam", "rate"],
            "fixed-axis": ["axis_kappa", "axis_lam"],
            "free": [],
            "force-field": [f"g{i}_{k}" for i in range(3) for k in "xyz"[: self.position_size]],
            "rotation-free": [],
        }[self.motion]
        return names

    def body_points(self) -> tuple[str, ...]:
        """The points with a free body vector (all of them for the force field, else all but A)."""
        return self.points if self.centred else self.points[1:]


@dataclass
class RigidState:
    """One estimate of a row's parameters (see the module docstring).

    Attributes:
        body: (n_body, 3) body vectors (input units).
        directions: (2, 2) polar, azimuth of the tangents at A and B (radians), or None.
        axis: (2,) kappa, lam of the rotation axis (radians), or None.
        rate: rotation rate w (radians per unit of t), or None.
        angles: (N,) fixed-axis angles theta_f (radians, theta_0 = 0), or None.
        rotations: (N, 3, 3) free rotations (R_0 = I), or None.
        shifts: (N, 2) image of the reference point A (input units), or None (force field).
        parabola: (3, 2) g0, g1, g2 of the mass centre's image ((3, 3): its 3-D position under
            a pinhole), or None.
        translations: (N, 3) the reference point A in every frame's camera coordinates (pinhole
            rows but the force field), or None.
    """

    body: np.ndarray
    directions: np.ndarray | None = None
    axis: np.ndarray | None = None
    rate: float | None = None
    angles: np.ndarray | None = None
    rotations: np.ndarray | None = None
    shifts: np.ndarray | None = None
    parabola: np.ndarray | None = None
    translations: np.ndarray | None = None

    def copy(self) -> RigidState:
        def c(v):
            return None if v is None else np.array(v, float)

        return RigidState(
            c(self.body),
            c(self.directions),
            c(self.axis),
            None if self.rate is None else float(self.rate),
            c(self.angles),
            c(self.rotations),
            c(self.shifts),
            c(self.parabola),
            c(self.translations),
        )


def rodrigues(w: np.ndarray) -> np.ndarray:
    """(..., 3, 3) exp([w]_x) of rotation vectors w (..., 3) (radians)."""
    w = np.asarray(w, float)
    theta = np.linalg.norm(w, axis=-1)[..., None, None]
    k = np.zeros((*w.shape[:-1], 3, 3))
    k[..., 0, 1], k[..., 0, 2], k[..., 1, 2] = -w[..., 2], w[..., 1], -w[..., 0]
    k[..., 1, 0], k[..., 2, 0], k[..., 2, 1] = w[..., 2], -w[..., 1], w[..., 0]
    small = theta < 1e-8
    safe = np.where(small, 1.0, theta)
    a = np.where(small, 1.0, np.sin(safe) / safe)
    b = np.where(small, 0.5, (1.0 - np.cos(safe)) / safe**2)
    return np.eye(3) + a * k + b * (k @ k)


def axis_vector(axis: np.ndarray) -> np.ndarray:
    """Unit axis n(kappa, lam) in frame 0's camera coordinates."""
    return np.asarray(gm.unit_direction(axis[0], axis[1]), float).reshape(3)


def axis_angles(n: np.ndarray) -> np.ndarray:
    """(kappa, lam) of a unit axis n (inverse of :func:`axis_vector`)."""
    n = np.asarray(n, float) / np.linalg.norm(n)
    return np.array([np.arccos(np.clip(n[2], -1.0, 1.0)), np.arctan2(n[1], n[0])])


def frame_angles(layout: Layout, state: RigidState, times: np.ndarray) -> np.ndarray | None:
    """(N,) rotation angle of every frame about the axis (radians), or None (free rotations)."""
    if layout.motion == "uniform-rotation":
        return float(state.rate) * (np.asarray(times, float) - float(times[0]))
    if layout.motion == "fixed-axis":
        return np.asarray(state.angles, float)
    return None


def frame_rotations(
    layout: Layout, state: RigidState, times: np.ndarray
) -> tuple[np.ndarray, np.ndarray | None]:
    """((N, 3, 3) rotations R_f, (N, 3, 3) increments of (kappa, lam, angle) or None)."""
    if layout.motion == "rotation-free":
        return np.broadcast_to(np.eye(3), (len(times), 3, 3)).copy(), None
    angles = frame_angles(layout, state, times)
    if angles is None:
        return np.asarray(state.rotations, float), None
    rot, inc = gm.axis_rotation(state.axis[0], state.axis[1], angles)
    return np.asarray(rot, float), np.asarray(inc, float)


def frame_shifts(layout: Layout, state: RigidState, times: np.ndarray) -> np.ndarray:
    """(N, 2) image of the reference point: the free shifts, or the force field's parabola."""
    if not layout.centred:
        return np.asarray(state.shifts, float)
    t = np.asarray(times, float)
    g = np.asarray(state.parabola, float)
    return g[0] + t[:, None] * g[1] + 0.5 * (t * t)[:, None] * g[2]


def frame_positions(layout: Layout, state: RigidState, times: np.ndarray) -> np.ndarray:
    """(N, 3) the reference point in every frame's camera coordinates (pinhole rows): the free
    translations, or the force field's 3-D parabola."""
    if not layout.centred:
        return np.asarray(state.translations, float)
    t = np.asarray(times, float)
    g = np.asarray(state.parabola, float)
    return g[0] + t[:, None] * g[1] + 0.5 * (t * t)[:, None] * g[2]


def body_vectors(layout: Layout, state: RigidState) -> np.ndarray:
    """(P, 3) every traceable point's body vector (A's is 0 unless the reference is G)."""
    body = np.asarray(state.body, float).reshape(layout.n_body, 3)
    if layout.centred:
        return body
    return np.vstack([np.zeros(3), body])


def points3(layout: Layout, state: RigidState, times: np.ndarray) -> np.ndarray:
    """(N, P, 3) every traceable point in every frame's camera coordinates, A at z = 0
    (pinhole rows: true depth, X = T + R q)."""
    rot, _ = frame_rotations(layout, state, times)
    if layout.pinhole:
        pos = frame_positions(layout, state, times)
        return np.einsum("fij,pj->fpi", rot, body_vectors(layout, state)) + pos[:, None, :]
    shift = frame_shifts(layout, state, times)
    q = body_vectors(layout, state)
    x = np.einsum("fij,pj->fpi", rot, q)
    x[:, :, :2] += shift[:, None, :]
    x[:, :, 2] -= x[:, :1, 2]
    return x


def tangent_vectors(state: RigidState) -> np.ndarray | None:
    """(2, 3) unit tangent directions at A and B in frame 0's coordinates, or None."""
    if state.directions is None:
        return None
    d = np.asarray(state.directions, float)
    return np.asarray(gm.unit_direction(d[:, 0], d[:, 1]), float)


def with_frames(state: RigidState, keep: np.ndarray) -> RigidState:
    """The state restricted to the frames ``keep`` (boolean or index; frame 0 must stay first)."""

    def pick(v):
        return None if v is None else np.asarray(v)[keep]

    return replace(
        state.copy(),
        angles=pick(state.angles),
        rotations=pick(state.rotations),
        shifts=pick(state.shifts),
        translations=pick(state.translations),
    )


def normalise(
    layout: Layout, state: RigidState, times: np.ndarray, mirror: bool | None = None
) -> RigidState:
    """The mirror image with B at or behind A in frame 0 (see the module docstring), the axis
    sign with a non-negative rate / angle sum, angles wrapped to (-pi, pi].  ``mirror``: True or
    False takes the mirror image or not, whatever B's depth (to compare with another estimate)."""
    s = state.copy()
    q = body_vectors(layout, s)
    if layout.pinhole:
        mirror = False  # a pinhole tells near from far
    if q[1, 2] - q[0, 2] < 0 if mirror is None else mirror:  # the mirror z -> -z
        s.body = s.body * np.array([1.0, 1.0, -1.0])
        if s.directions is not None:
            s.directions[:, 0] = np.pi - s.directions[:, 0]
        if s.rotations is not None:
            flip = np.diag([1.0, 1.0, -1.0])
            s.rotations = flip @ s.rotations @ flip
        if s.axis is not None:  # S Rot(n, a) S = Rot(-S n, a)
            n = axis_vector(s.axis) * np.array([-1.0, -1.0, 1.0])
            s.axis = axis_angles(n)
    if s.axis is not None:
        sign = s.rate if layout.motion == "uniform-rotation" else float(np.sum(s.angles))
        if sign < 0:  # Rot(n, a) = Rot(-n, -a)
            s.axis = axis_angles(-axis_vector(s.axis))
            if s.rate is not None:
                s.rate = -s.rate
            if s.angles is not None:
                s.angles = -s.angles
        if s.angles is not None:
            s.angles = np.angle(np.exp(1j * s.angles))
    return s
