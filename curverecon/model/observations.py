"""Per-frame observations: image positions of A', B' and image directions of the tangents there.

Conventions (docs/CONVENTIONS.md): image coordinates x, y in input units (pixels); a tangent is a
line, so a direction vector may have any length and either sign.  In the paper's per-frame frame
(A' at the origin, B' on +x) the observables are

- ``c' = |A'B'|``, ``theta`` = the image direction of A'B' (radians),
- the tangent angles relative to the chord, ``rel_a``, ``rel_b`` in (-pi/2, pi/2],
- ``d' = -c' tan(rel_b)`` (where the projected tangent at B meets l1, the y axis through A'),
- ``e' = c' tan(rel_a)`` (where the projected tangent at A meets l2, the line x = c').
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from curverecon.errors import CurveReconError

MIN_FRAMES = 4
"""Each frame gives one equation beyond its own pose; four unknowns of the shape need four."""

PERPENDICULAR_TOL = 1e-9
"""|cos| of the angle between a tangent and A'B' below which d' or e' is taken as infinite."""

DEGENERATE_TOL = 1e-9
"""Spread (radians) of the relative tangent angles below which the motion is in-plane only."""


def wrap_line_angle(x: np.ndarray | float) -> np.ndarray:
    """Wrap angles of lines (period pi) to (-pi/2, pi/2]."""
    y = np.mod(np.asarray(x, dtype=float) + np.pi / 2, np.pi) - np.pi / 2
    return np.where(y <= -np.pi / 2, y + np.pi, y)


def wrap_angle(x: np.ndarray | float) -> np.ndarray:
    """Wrap angles (period 2 pi) to (-pi, pi]."""
    y = np.mod(np.asarray(x, dtype=float) + np.pi, 2 * np.pi) - np.pi
    return np.where(y <= -np.pi, y + 2 * np.pi, y)


def _as_xy(name: str, value: object) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise CurveReconError(f"{name} must be an array of numbers") from exc
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise CurveReconError(f"{name} must have shape (N, 2), got {arr.shape}")
    return arr


@dataclass
class Observations:
    """Observed frames.

    Attributes:
        a, b: (N, 2) image positions of A' and B' (input units).
        tangent_a, tangent_b: (N, 2) image directions of the projected tangents at A and B.
        curves: optional list of N polylines (K_i, 2), each ordered from A' to B'.
        ends_given: False when some frame's A', B' or tangents were taken from its polyline
            (the input did not give them): then they are not measurements of their own.
        warnings: what the loader changed or noticed (e.g. a long polyline averaged down);
            the reconstruction repeats them.
        tangents_from_curve: the input's tangents were estimated from its polylines (the
            document's ``"tangents_from_curve": true``, written by ``curverecon trace``): the
            reconstruction also tries the polylines alone and keeps what fits them better
            (``curverecon.pipeline.reconstruct``).
        ends_identified: A is the same physical end in every frame (default).  False (the
            document's ``"ends_identified": false``): the labels may name different ends in
            different frames, and the reconstruction decides each frame's labelling
            (``curverecon.robust.labels``).

    Construction validates every frame (finite numbers, A' != B', tangents not zero and not
    perpendicular to A'B') and raises :class:`CurveReconError` with a one-line message.
    """

    a: np.ndarray
    b: np.ndarray
    tangent_a: np.ndarray
    tangent_b: np.ndarray
    curves: list[np.ndarray] | None = field(default=None)
    ends_given: bool = True
    warnings: list[str] = field(default_factory=list)
    tangents_from_curve: bool = False
    ends_identified: bool = True

    def __post_init__(self) -> None:
        if not isinstance(self.ends_identified, bool | np.bool_):
            raise CurveReconError(
                f"ends_identified must be true or false, got {self.ends_identified!r}"
            )
        self.ends_identified = bool(self.ends_identified)
        self.a = _as_xy("A", self.a)
        self.b = _as_xy("B", self.b)
        self.tangent_a = _as_xy("tangent_A", self.tangent_a)
        self.tangent_b = _as_xy("tangent_B", self.tangent_b)
        n = self.a.shape[0]
        for name, arr in (
            ("B", self.b),
            ("tangent_A", self.tangent_a),
            ("tangent_B", self.tangent_b),
        ):
            if arr.shape[0] != n:
                raise CurveReconError(f"{name} has {arr.shape[0]} frames, A has {n}")
        if n == 0:
            raise CurveReconError("no frames")
        for name, arr in (
            ("A", self.a),
            ("B", self.b),
            ("tangent_A", self.tangent_a),
            ("tangent_B", self.tangent_b),
        ):
            bad = ~np.all(np.isfinite(arr), axis=1)
            if bad.any():
                raise CurveReconError(
                    f"frame {int(np.argmax(bad))}: {name} is not finite (NaN or inf)"
                )
        chord = self.b - self.a
        length = np.hypot(chord[:, 0], chord[:, 1])
        scale = np.maximum(np.max(np.abs(np.concatenate([self.a, self.b]))), 1.0)
        bad = length <= 1e-12 * scale
        if bad.any():
            raise CurveReconError(f"frame {int(np.argmax(bad))}: A' and B' coincide")
        for name, t in (("tangent_A", self.tangent_a), ("tangent_B", self.tangent_b)):
            norm = np.hypot(t[:, 0], t[:, 1])
            bad = norm == 0.0
            if bad.any():
                raise CurveReconError(f"frame {int(np.argmax(bad))}: {name} is the zero vector")
            cosang = np.abs(np.sum(t * chord, axis=1)) / (norm * length)
            bad = cosang < PERPENDICULAR_TOL
            if bad.any():
                which = "d'" if name == "tangent_B" else "e'"
                raise CurveReconError(
                    f"frame {int(np.argmax(bad))}: {name} is perpendicular to A'B' "
                    f"(parallel to the line it must cross, so {which} is infinite)"
                )
        if self.curves is not None:
            curves = []
            if len(self.curves) != n:
                raise CurveReconError(f"{len(self.curves)} curves for {n} frames")
            for i, c in enumerate(self.curves):
                arr = _as_xy(f"frame {i}: curve", c)
                if arr.shape[0] < 2 or not np.all(np.isfinite(arr)):
                    raise CurveReconError(f"frame {i}: curve needs at least 2 finite points")
                curves.append(arr)
            self.curves = curves

    # ----------------------------------------------------------------- derived observables
    @property
    def n_frames(self) -> int:
        return int(self.a.shape[0])

    @property
    def chord(self) -> np.ndarray:
        """(N, 2) image vector A'B'."""
        return self.b - self.a

    @property
    def cp(self) -> np.ndarray:
        """(N,) c' = |A'B'| (input units)."""
        ch = self.chord
        return np.hypot(ch[:, 0], ch[:, 1])

    @property
    def theta(self) -> np.ndarray:
        """(N,) image direction of A'B' (radians)."""
        ch = self.chord
        return np.arctan2(ch[:, 1], ch[:, 0])

    @property
    def psi_a(self) -> np.ndarray:
        """(N,) image angle of the tangent at A (radians, atan2 of the given direction)."""
        return np.arctan2(self.tangent_a[:, 1], self.tangent_a[:, 0])

    @property
    def psi_b(self) -> np.ndarray:
        """(N,) image angle of the tangent at B (radians, atan2 of the given direction)."""
        return np.arctan2(self.tangent_b[:, 1], self.tangent_b[:, 0])

    @property
    def rel_a(self) -> np.ndarray:
        """(N,) angle of the tangent line at A relative to A'B', in (-pi/2, pi/2]."""
        return wrap_line_angle(self.psi_a - self.theta)

    @property
    def rel_b(self) -> np.ndarray:
        """(N,) angle of the tangent line at B relative to A'B', in (-pi/2, pi/2]."""
        return wrap_line_angle(self.psi_b - self.theta)

    @property
    def dp(self) -> np.ndarray:
        """(N,) d' = -c' u_y / u_x with u the tangent at B rotated by -theta."""
        return -self.cp * np.tan(self.rel_b)

    @property
    def ep(self) -> np.ndarray:
        """(N,) e' = c' u_y / u_x with u the tangent at A rotated by -theta."""
        return self.cp * np.tan(self.rel_a)

    def measurements(self) -> np.ndarray:
        """(N, 6) ax, ay, bx, by, psi_a, psi_b in the order of measurement_model.PREDICTIONS."""
        return np.column_stack([self.a, self.b, self.psi_a, self.psi_b])

    def subset(self, index: np.ndarray) -> Observations:
        """The frames selected by an index or boolean mask."""
        idx = np.arange(self.n_frames)[index]
        curves = None if self.curves is None else [self.curves[i] for i in idx]
        return Observations(
            self.a[idx],
            self.b[idx],
            self.tangent_a[idx],
            self.tangent_b[idx],
            curves,
            self.ends_given,
            list(self.warnings),
            self.tangents_from_curve,
            self.ends_identified,
        )

    # ----------------------------------------------------------------- checks
    def require_reconstructable(self, min_frames: int = MIN_FRAMES) -> None:
        """Raise CurveReconError if there are too few frames or the motion is degenerate.

        Degenerate motion: every frame is related to every other by an in-plane similarity
        (rotation, translation, scale in the image), i.e. the tangent angles relative to A'B'
        do not change; then there is no rotation out of the image plane and the frames say
        nothing about depth.
        """
        n = self.n_frames
        if n < min_frames:
            raise CurveReconError(
                f"{n} frame(s) given; at least {min_frames} are needed "
                "(each frame adds one equation beyond its own pose, the shape has four unknowns)"
            )
        spread_a = np.ptp(wrap_line_angle(self.rel_a - self.rel_a[0]))
        spread_b = np.ptp(wrap_line_angle(self.rel_b - self.rel_b[0]))
        if max(spread_a, spread_b) <= DEGENERATE_TOL:
            raise CurveReconError(
                "degenerate motion: all frames are related by an in-plane similarity "
                "(no rotation out of the image plane), so the shape cannot be determined"
            )
