"""Every SymPy symbol shared by the section-3 derivation.

The names of the symbols that become arguments of generated functions are fixed by
``docs/CONVENTIONS.md``: ``c, tan_alpha, tan_beta, phi, cos_phi, tan_phi, cp, dp, ep, delta,
sin_tau`` and ``alpha, beta`` for the angles.

Conventions (see ``docs/CONVENTIONS.md``):

* curve frame: A = (0, 0, 0), B = (c, 0, 0); tangent at B meets the plane x = 0 at
  S = (0, c tan(alpha), 0); tangent at A meets the plane x = c at
  T = (c, c tan(beta) cos(phi), c tan(beta) sin(phi));
* pose (paper's frame, theta = 0, no translation): R = R_y(tau) R_x(delta), orthographic
  projection keeps (x, y);
* observables c' = |A'B'| = c cos(tau), d' (signed y of D' on l1: x = 0), e' (signed y of E' on
  l2: x = c').  sin_tau is *signed* (B_z = -c sin(tau)).

Lengths are in the input's units (pixels); angles are in radians.
"""

from __future__ import annotations

import sympy as sp

# --- global (shape) unknowns -------------------------------------------------------------
c = sp.Symbol("c", positive=True)  # |AB| in space
alpha = sp.Symbol("alpha", real=True)  # angle between AB and the tangent at B
beta = sp.Symbol("beta", real=True)  # angle between AB and the tangent at A
phi = sp.Symbol("phi", real=True)  # signed angle from AS to BT about +x
tan_alpha = sp.Symbol("tan_alpha", real=True)
tan_beta = sp.Symbol("tan_beta", real=True)
cos_phi = sp.Symbol("cos_phi", real=True)
tan_phi = sp.Symbol("tan_phi", real=True)

# --- per-frame (local) unknowns ------------------------------------------------------------
delta = sp.Symbol("delta", real=True)  # rotation about AB
tau = sp.Symbol("tau", real=True)  # rotation about l1, in (-pi/2, pi/2)
sin_tau = sp.Symbol("sin_tau", real=True)  # signed sin(tau)

# --- per-frame observables -------------------------------------------------------------------
cp = sp.Symbol("cp", positive=True)  # c'  = |A'B'|
dp = sp.Symbol("dp", real=True)  # d'  = signed y of D' (on l1)
ep = sp.Symbol("ep", real=True)  # e'  = signed y of E' (on l2)

# --- the paper's named lengths of section 3 (signed, see derivations.construction) ----------
AS = sp.Symbol("AS", real=True)
AS_p = sp.Symbol("AS'", real=True)  # A S'
SS_p = sp.Symbol("SS'", real=True)  # S S'
AB = sp.Symbol("AB", positive=True)
AB_p = sp.Symbol("AB'", real=True)  # A B'
S_pS_pp = sp.Symbol("S'S''", real=True)  # S' S''
AD_p = sp.Symbol("AD'", real=True)  # A D'
D_pS_p = sp.Symbol("D'S'", real=True)  # D' S'

# --- auxiliary frame terms of the paper ----------------------------------------------------
p1, q1, p2, q2 = sp.symbols("p1 q1 p2 q2", real=True)
omega1, omega2 = sp.symbols("omega1 omega2", real=True)
u1, u2 = sp.symbols("u1 u2", real=True)  # d'c'/sqrt(p1^2+q1^2), e'c'/sqrt(p2^2+q2^2)
s1, s2, y = sp.symbols("s1 s2 y", real=True)  # (12'): tan^2 arccos u1, tan^2 arccos u2, y

SHAPE = (c, tan_alpha, tan_beta, phi)
OBSERVABLES = (cp, dp, ep)
LEAN_UNKNOWNS = (c, tan_alpha, tan_beta, cos_phi)
SQUARED_UNKNOWNS = (c, tan_alpha, tan_beta, tan_phi)

# LaTeX names for the report (sympy.latex(..., symbol_names=LATEX_NAMES))
LATEX_NAMES: dict[sp.Symbol, str] = {
    tan_alpha: r"\tan\alpha",
    tan_beta: r"\tan\beta",
    cos_phi: r"\cos\phi",
    tan_phi: r"\tan\phi",
    sin_tau: r"\sin\tau",
    cp: "c'",
    dp: "d'",
    ep: "e'",
    AS_p: "AS'",
    SS_p: "SS'",
    AB_p: "AB'",
    S_pS_pp: "S'S''",
    AD_p: "AD'",
    D_pS_p: "D'S'",
    p1: "p_1",
    q1: "q_1",
    p2: "p_2",
    q2: "q_2",
    omega1: r"\omega_1",
    omega2: r"\omega_2",
    u1: "u_1",
    u2: "u_2",
    s1: "s_1",
    s2: "s_2",
}
