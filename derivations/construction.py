"""The 3-D construction of section 3 of the paper, symbolically.

Steps (paper, section 3, items 1-4; conventions of ``docs/CONVENTIONS.md``):

1. A, B and the tangent at B lie in the frame plane: A = (0, 0, 0), B = (c, 0, 0), the tangent at
   B meets the plane p1 (x = 0, containing l1 = the y axis) at S = (0, c tan(alpha), 0).  The
   tangent at A meets the plane x = c at T = (c, c tan(beta) cos(phi), c tan(beta) sin(phi)).
2. The curve is rotated by delta about AB (the x axis): R_x(delta).  S' is the orthogonal
   projection of S onto l1 inside p1.
3. The curve (with S, not S') is rotated by tau about l1 (the y axis): R_y(tau).  S'' is the
   orthogonal projection of the new S onto the frame plane (orthographic projection keeps x, y).
   D' is where the projected tangent at B (the line B'S'') crosses l1; E' is where the projected
   tangent at A (the line A'T'') crosses l2 (x = c').
4. A shift perpendicular to the frame plane changes nothing and is omitted.

All lengths are *signed* coordinates: AS, AS' are y coordinates along l1, SS' the z coordinate
of S after step 2, AB' and S'S'' x coordinates, AD' = d', D'S' = (y of S') - d'.  Lengths are in
input units, angles in radians.
"""

from __future__ import annotations

from functools import cache

import numpy as np
import sympy as sp

from derivations import symbols as s


def rot_x(angle: sp.Expr) -> sp.Matrix:
    """Right-handed rotation about +x by ``angle`` (radians)."""
    co, si = sp.cos(angle), sp.sin(angle)
    return sp.Matrix([[1, 0, 0], [0, co, -si], [0, si, co]])


def rot_y(angle: sp.Expr) -> sp.Matrix:
    """Right-handed rotation about +y by ``angle`` (radians): [[c, 0, s], [0, 1, 0], [-s, 0, c]]."""
    co, si = sp.cos(angle), sp.sin(angle)
    return sp.Matrix([[co, 0, si], [0, 1, 0], [-si, 0, co]])


def _line_at_x(p: sp.Matrix, q: sp.Matrix, x0: sp.Expr) -> sp.Expr:
    """y coordinate where the image line through p and q (2-D, x and y used) crosses x = x0."""
    t = (x0 - p[0]) / (q[0] - p[0])
    return sp.cancel(p[1] + t * (q[1] - p[1]))


@cache
def build() -> dict[str, sp.Expr | sp.Matrix]:
    """Points and signed lengths of the construction, in (c, tan_alpha, tan_beta, phi, delta, tau).

    Keys: ``A, B, S, T`` (canonical frame), ``S_delta`` (S after step 2), ``S_prime``,
    ``S_rot, T_rot, B_rot`` (after step 3), ``S_pp`` (S'', image), ``cp, dp, ep`` (observables).
    """
    c, ta, tb, phi, delta, tau = s.c, s.tan_alpha, s.tan_beta, s.phi, s.delta, s.tau
    A = sp.Matrix([0, 0, 0])
    B = sp.Matrix([c, 0, 0])
    S = sp.Matrix([0, c * ta, 0])
    T = sp.Matrix([c, c * tb * sp.cos(phi), c * tb * sp.sin(phi)])
    Rd = rot_x(delta)
    R = rot_y(tau) * Rd  # R = R_y(tau) R_x(delta): CONVENTIONS.md with theta = 0
    S_delta = Rd * S
    S_prime = sp.Matrix([0, S_delta[1], 0])  # orthogonal projection of S onto l1 inside p1
    S_rot = R * S
    T_rot = (R * T).applyfunc(lambda e: sp.expand(sp.expand_trig(e)))
    B_rot = R * B
    S_pp = sp.Matrix([S_rot[0], S_rot[1], 0])  # orthographic projection keeps x, y
    B_p = sp.Matrix([B_rot[0], B_rot[1], 0])
    cp = B_rot[0]  # B'_y = 0: B' lies on +x for |tau| < pi/2
    dp = _line_at_x(B_p, S_pp, sp.Integer(0))  # D' = B'S'' crossed with l1 (x = 0)
    ep = _line_at_x(A, T_rot, cp)  # E' = A'T'' crossed with l2 (x = c')
    return {
        "A": A,
        "B": B,
        "S": S,
        "T": T,
        "S_delta": S_delta,
        "S_prime": S_prime,
        "S_rot": S_rot,
        "T_rot": T_rot,
        "B_rot": B_rot,
        "S_pp": S_pp,
        "cp": cp,
        "dp": dp,
        "ep": ep,
    }


@cache
def substitutions() -> dict[sp.Symbol, sp.Expr]:
    """Values of every symbol of the paper's section 3 from the construction.

    Maps the named lengths (AS, AS', SS', AB, AB', S'S'', AD', D'S'), the observables
    (cp, dp, ep) and sin_tau to expressions in (c, tan_alpha, tan_beta, phi, delta, tau).
    """
    k = build()
    return {
        s.AS: k["S"][1],
        s.AS_p: k["S_prime"][1],
        s.SS_p: k["S_delta"][2],
        s.AB: s.c,
        s.AB_p: k["B_rot"][0],
        s.S_pS_pp: k["S_pp"][0] - k["S_prime"][0],
        s.AD_p: k["dp"],
        s.D_pS_p: k["S_prime"][1] - k["dp"],
        s.cp: k["cp"],
        s.dp: k["dp"],
        s.ep: k["ep"],
        s.sin_tau: sp.sin(s.tau),
    }


def random_configurations(n: int, seed: int = 20240601) -> np.ndarray:
    """``n`` seeded random configurations (c, alpha, beta, phi, delta, tau), radians.

    c in [50, 200]; alpha, beta in [5, 85] degrees; phi, delta in (-180, 180) degrees;
    |tau| in [5, 80] degrees with alternating sign (both signs of sin(tau) are covered).
    """
    rng = np.random.default_rng(seed)
    deg = np.pi / 180
    c = rng.uniform(50, 200, n)
    alpha = rng.uniform(5, 85, n) * deg
    beta = rng.uniform(5, 85, n) * deg
    phi = rng.uniform(-180, 180, n) * deg
    delta = rng.uniform(-180, 180, n) * deg
    tau = rng.uniform(5, 80, n) * deg * np.where(np.arange(n) % 2 == 0, 1.0, -1.0)
    return np.column_stack([c, alpha, beta, phi, delta, tau])
