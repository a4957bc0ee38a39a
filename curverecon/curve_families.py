"""Families of smooth 3-D test curves for the simulator (an INDEPENDENT 3-D construction).

Each family draws one random curve ``x(s)``, s in [0, 1], from A = x(0) = 0 to B = x(1), and
returns it as a :class:`Curve3D`: a function giving points and one giving derivatives (both
analytic or from an ODE solved to 1e-12 relative), so the simulator's end tangents and the
polyline points it projects are the same curve to float precision.  Nothing here uses the
project's solvers, splines or the (delta, tau) parametrisation.

Families (``FAMILIES``):

- ``bezier``: a random cubic Bezier curve (the simulator's original scenes; drawn by
  ``simulate.random_curve`` so the default scenes keep their seeds).
- ``helix``: a circular helix (constant curvature and torsion), 0.4 to 1.3 turns.
- ``clothoid``: curvature growing linearly with arc length (an Euler spiral) with a constant
  torsion, so the curve leaves its plane.
- ``fourier``: a chord plus four sine harmonics with random 3-D amplitudes decaying as 1/k
  (wiggly curves).
- ``sharp-ends``: gentle curvature with a sharp bend within 3-8 % of the length at each end
  (40 to 70 degrees of turning there).
- ``random``: curvature and torsion random smooth functions of arc length (three cosine
  harmonics each).

Every family is redrawn until alpha and beta (the CONTRACT's angles) lie in [10, 80] degrees,
as the Bezier scenes do.  Lengths: unit chord-free scale here; the simulator scales the curve
to its chord range.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

FAMILIES = ("bezier", "helix", "clothoid", "fourier", "sharp-ends", "random")

#: alpha and beta of every drawn curve lie in this range (degrees), as in the Bezier scenes.
ANGLE_RANGE_DEG = (10.0, 80.0)


@dataclass
class Curve3D:
    """A smooth 3-D curve on s in [0, 1] with x(0) = 0.

    points(s) -> (len(s), 3); derivative(s) -> (len(s), 3) (dx/ds, not normalised).
    """

    points: Callable[[np.ndarray], np.ndarray]
    derivative: Callable[[np.ndarray], np.ndarray]

    def scaled(self, factor: float) -> Curve3D:
        """The same curve scaled about A by ``factor``."""
        p, d = self.points, self.derivative
        return Curve3D(lambda s: factor * p(s), lambda s: factor * d(s))

    def ends(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(A, B, tangent at A into the curve, tangent at B into the curve), unnormalised."""
        e = np.array([0.0, 1.0])
        p, d = self.points(e), self.derivative(e)
        return p[0], p[1], d[0], -d[1]


def _bezier_curve(ctrl: np.ndarray) -> Curve3D:
    c = np.asarray(ctrl, float)

    def pts(s):
        s = np.asarray(s, float)[:, None]
        return (
            (1 - s) ** 3 * c[0]
            + 3 * (1 - s) ** 2 * s * c[1]
            + 3 * (1 - s) * s**2 * c[2]
            + s**3 * c[3]
        ) - c[0]

    def der(s):
        s = np.asarray(s, float)[:, None]
        return 3 * ((1 - s) ** 2 * (c[1] - c[0]) + 2 * (1 - s) * s * (c[2] - c[1])) + 3 * (
            s**2 * (c[3] - c[2])
        )

    return Curve3D(pts, der)


def _frenet_curve(kappa: Callable[[float], float], torsion: Callable[[float], float]) -> Curve3D:
    """The unit-speed curve with curvature kappa(s) and torsion torsion(s), s in [0, 1], from
    the origin along +x with normal +y (Frenet-Serret equations, DOP853 at 1e-12)."""

    def rhs(s, y):
        t, n, b = y[3:6], y[6:9], y[9:12]
        k, w = kappa(s), torsion(s)
        return np.concatenate([t, k * n, -k * t + w * b, -w * n])

    y0 = np.concatenate([np.zeros(3), [1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0]])
    sol = solve_ivp(rhs, (0.0, 1.0), y0, method="DOP853", rtol=1e-12, atol=1e-13, dense_output=True)
    if not sol.success:  # pragma: no cover - smooth right-hand sides
        raise RuntimeError(sol.message)
    dense = sol.sol

    def pts(s):
        return dense(np.clip(np.asarray(s, float), 0.0, 1.0)).T[:, 0:3]

    def der(s):
        v = dense(np.clip(np.asarray(s, float), 0.0, 1.0)).T[:, 3:6]
        return v / np.linalg.norm(v, axis=1, keepdims=True)

    return Curve3D(pts, der)


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def _helix(rng: np.random.Generator) -> Curve3D:
    turns = rng.uniform(0.4, 1.3)
    # unit length: total turning 2 pi turns spread over curvature and torsion
    total = 2 * np.pi * turns
    pitch_angle = rng.uniform(0.15, 0.8)  # angle of the tangent to the helix's normal plane
    k = total * np.cos(pitch_angle)
    w = total * np.sin(pitch_angle) * rng.choice([-1.0, 1.0])
    return _frenet_curve(lambda s: k, lambda s: w)


def _clothoid(rng: np.random.Generator) -> Curve3D:
    k0 = rng.uniform(0.0, 2.0)
    k1 = rng.uniform(3.0, 9.0)
    w = rng.uniform(-2.0, 2.0)
    if rng.random() < 0.5:  # curvature growing towards B or towards A
        return _frenet_curve(lambda s: k0 + k1 * s, lambda s: w)
    return _frenet_curve(lambda s: k0 + k1 * (1.0 - s), lambda s: w)


def _sharp_ends(rng: np.random.Generator) -> Curve3D:
    base = rng.uniform(0.3, 2.0)
    width = rng.uniform(0.03, 0.08) / 3.0  # 95 % of the bend within 3 widths
    turn_a, turn_b = np.radians(rng.uniform(40.0, 70.0, size=2))
    w = rng.uniform(-2.0, 2.0)

    def kappa(s: float) -> float:
        return (
            base + turn_a / width * np.exp(-s / width) + turn_b / width * np.exp(-(1.0 - s) / width)
        )

    return _frenet_curve(kappa, lambda s: w)


def _random_frenet(rng: np.random.Generator) -> Curve3D:
    ka = rng.normal(size=3) * [3.0, 2.0, 1.0]
    wa = rng.normal(size=3) * [2.0, 1.5, 1.0]
    k0, w0 = rng.uniform(1.0, 4.0), rng.uniform(-2.0, 2.0)
    ph = rng.uniform(0, 2 * np.pi, size=6)

    def kappa(s: float) -> float:
        v = k0 + sum(ka[j] * np.cos((j + 1) * np.pi * s + ph[j]) for j in range(3))
        return float(np.log1p(np.exp(v)))  # positive, smooth

    def torsion(s: float) -> float:
        return float(w0 + sum(wa[j] * np.cos((j + 1) * np.pi * s + ph[3 + j]) for j in range(3)))

    return _frenet_curve(kappa, torsion)


def _fourier(rng: np.random.Generator) -> Curve3D:
    chord = _unit(rng.normal(size=3))
    amp = np.array([_unit(rng.normal(size=3)) * rng.uniform(0.05, 0.25) / k for k in range(1, 5)])
    freq = np.pi * np.arange(1, 5)

    def pts(s):
        s = np.asarray(s, float)
        return np.outer(s, chord) + np.sin(np.outer(s, freq)) @ amp

    def der(s):
        s = np.asarray(s, float)
        return np.outer(np.ones_like(s), chord) + (np.cos(np.outer(s, freq)) * freq) @ amp

    return Curve3D(pts, der)


def _angles_ok(curve: Curve3D) -> bool:
    a, b, ta, tb = curve.ends()
    e = _unit(b - a)
    lo, hi = np.radians(ANGLE_RANGE_DEG)
    alpha = np.arccos(min(1.0, abs(tb @ e) / np.linalg.norm(tb)))
    beta = np.arccos(min(1.0, abs(ta @ e) / np.linalg.norm(ta)))
    return bool(lo <= alpha <= hi and lo <= beta <= hi)


_DRAW = {
    "helix": _helix,
    "clothoid": _clothoid,
    "fourier": _fourier,
    "sharp-ends": _sharp_ends,
    "random": _random_frenet,
}


def draw_curve(rng: np.random.Generator, family: str, chord: tuple[float, float]) -> Curve3D:
    """A random curve of ``family`` (not ``bezier``, see ``simulate.random_curve``) with
    alpha, beta in ``ANGLE_RANGE_DEG``, scaled so that its chord |AB| is uniform in ``chord``."""
    if family not in _DRAW:
        from curverecon.errors import CurveReconError

        raise CurveReconError(
            f"unknown curve family {family!r} (expected one of {', '.join(FAMILIES)})"
        )
    for _ in range(1000):
        curve = _DRAW[family](rng)
        if _angles_ok(curve):
            a, b, _, _ = curve.ends()
            return curve.scaled(rng.uniform(*chord) / float(np.linalg.norm(b - a)))
    raise RuntimeError(f"no {family} curve with alpha, beta in range")  # pragma: no cover


def bezier_curve(ctrl: np.ndarray) -> Curve3D:
    """The cubic Bezier curve with control points ``ctrl`` (4, 3), moved so that A = 0."""
    return _bezier_curve(ctrl)


__all__ = ["ANGLE_RANGE_DEG", "FAMILIES", "Curve3D", "bezier_curve", "draw_curve"]
