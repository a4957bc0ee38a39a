"""docs/CONVENTIONS.md against the simulator's independent 3-D geometry.

The simulator builds a Bezier curve, rotates it with random rotations and projects it; here the
canonical frame (A at the origin, B on +x, t_B in the xy plane) is recovered from the 3-D truth,
the camera rotation is decomposed as R_z(theta) R_y(tau) R_x(delta), and the conventions' formulas
for d', e', (10), (11), B_z = -c sin(tau) and the generated measurement model are checked.
"""

from __future__ import annotations

import numpy as np
import pytest
from curverecon.generated import frame_equations, measurement_model
from scipy.spatial.transform import Rotation

from curverecon.model.observations import wrap_line_angle
from curverecon.simulate import make_scene


def canonical_parameters(truth) -> tuple[np.ndarray, np.ndarray]:
    """(shape with signed phi, poses (N, 5)) of a simulator truth, by the CONVENTIONS' frame."""
    x = truth.B3 - truth.A3
    c = float(np.linalg.norm(x[0]))
    x = x / np.linalg.norm(x, axis=1)[:, None]
    flip_b = np.where(np.sum(truth.tangent_B3 * x, 1) > 0, -1.0, 1.0)[:, None]
    tb = truth.tangent_B3 * flip_b  # t_B = (-cos alpha, sin alpha, 0): points back towards A
    y = tb - np.sum(tb * x, 1)[:, None] * x
    y /= np.linalg.norm(y, axis=1)[:, None]
    z = np.cross(x, y)
    rot = np.stack([x, y, z], -1)  # canonical -> camera
    flip_a = np.where(np.sum(truth.tangent_A3 * x, 1) < 0, -1.0, 1.0)[:, None]
    ta_c = np.einsum("nji,nj->ni", rot, truth.tangent_A3 * flip_a)
    phi = float(np.arctan2(ta_c[0, 2], ta_c[0, 1]))
    eul = Rotation.from_matrix(rot).as_euler("ZYX")  # R = R_z(e0) R_y(e1) R_x(e2)
    poses = np.column_stack([eul[:, 2], eul[:, 1], eul[:, 0], truth.A3[:, 0], truth.A3[:, 1]])
    return np.array([c, truth.alpha, truth.beta, phi]), poses


@pytest.fixture(scope="module", params=[0, 1, 2])
def scene(request):
    return make_scene(np.random.default_rng(100 + request.param), 12)


def test_canonical_frame_reproduces_the_tangents(scene):
    shape, poses = canonical_parameters(scene.truth)
    c, alpha, beta, phi = shape
    rot = measurement_model.rotation_matrix(*poses[:, :3].T)
    t_b = rot @ np.array([-np.cos(alpha), np.sin(alpha), 0.0])
    t_a = rot @ np.array([np.cos(beta), np.sin(beta) * np.cos(phi), np.sin(beta) * np.sin(phi)])
    # same lines as the simulator's tangents
    assert np.allclose(np.abs(np.sum(t_b * scene.truth.tangent_B3, 1)), 1.0, atol=1e-12)
    assert np.allclose(np.abs(np.sum(t_a * scene.truth.tangent_A3, 1)), 1.0, atol=1e-12)
    assert np.allclose(rot @ np.array([c, 0.0, 0.0]), scene.truth.B3 - scene.truth.A3, atol=1e-9)


def test_depth_of_b_is_minus_c_sin_tau(scene):
    shape, poses = canonical_parameters(scene.truth)
    bz = scene.truth.B3[:, 2] - scene.truth.A3[:, 2]
    assert np.allclose(bz, -shape[0] * np.sin(poses[:, 1]), atol=1e-9)
    assert np.all(np.abs(poses[:, 1]) < np.pi / 2)


def test_d_e_and_equations_10_11(scene):
    obs = scene.observations
    shape, poses = canonical_parameters(scene.truth)
    c, alpha, beta, phi = shape
    cp, dp, ep = obs.cp, obs.dp, obs.ep
    delta, tau = poses[:, 0], poses[:, 1]
    # d', e' by their geometric definition: intersect the projected tangent lines with l1 / l2
    theta = obs.theta
    rot_m = np.stack([np.cos(-theta), -np.sin(-theta), np.sin(-theta), np.cos(-theta)], -1)
    rot_m = rot_m.reshape(-1, 2, 2)
    ub = np.einsum("nij,nj->ni", rot_m, obs.tangent_b)
    ua = np.einsum("nij,nj->ni", rot_m, obs.tangent_a)
    d_geo = 0.0 + (0.0 - cp) * ub[:, 1] / ub[:, 0]  # line through B' = (c', 0), at x = 0
    e_geo = cp * ua[:, 1] / ua[:, 0]  # line through A' = (0, 0), at x = c'
    assert np.allclose(dp, d_geo, rtol=1e-9, atol=1e-9)
    assert np.allclose(ep, e_geo, rtol=1e-9, atol=1e-9)
    # (10), (11) with the CONVENTIONS' signs, by hand and from the generated module
    p1, q1 = dp * c * np.tan(alpha) * np.sin(tau), cp * c * np.tan(alpha)
    p2, q2 = ep * c * np.tan(beta) * np.sin(tau), cp * c * np.tan(beta)
    scale = np.abs(dp * cp) + np.abs(q1) + np.abs(p1)
    assert np.allclose((q1 * np.cos(delta) + p1 * np.sin(delta) - dp * cp) / scale, 0, atol=1e-9)
    scale = np.abs(ep * cp) + np.abs(q2) + np.abs(p2)
    lhs = q2 * np.cos(delta + phi) - p2 * np.sin(delta + phi)
    assert np.allclose((lhs - ep * cp) / scale, 0, atol=1e-9)
    r10 = frame_equations.residual_10(c, np.tan(alpha), cp, dp, delta, np.sin(tau))
    r11 = frame_equations.residual_11(c, np.tan(beta), phi, cp, ep, delta, np.sin(tau))
    assert np.max(np.abs(r10) / (np.abs(dp * cp) + cp * c)) < 1e-9
    assert np.max(np.abs(r11) / (np.abs(ep * cp) + cp * c)) < 1e-9


def test_paper_sign_of_delta_is_not_the_convention(scene):
    """The paper prints (10) with the opposite sign of delta: that must fail here."""
    obs = scene.observations
    shape, poses = canonical_parameters(scene.truth)
    c, alpha = shape[0], shape[1]
    delta, tau = poses[:, 0], poses[:, 1]
    p1, q1 = obs.dp * c * np.tan(alpha) * np.sin(tau), obs.cp * c * np.tan(alpha)
    wrong = q1 * np.cos(-delta) + p1 * np.sin(-delta) - obs.dp * obs.cp
    assert np.max(np.abs(wrong) / (np.abs(obs.dp * obs.cp) + np.abs(q1))) > 1e-3


def test_measurement_model_matches_projection(scene):
    shape, poses = canonical_parameters(scene.truth)
    pred = measurement_model.predict(*shape, *poses.T)
    obs = scene.observations
    assert np.allclose(pred[:, 0:2], obs.a, atol=1e-9)
    assert np.allclose(pred[:, 2:4], obs.b, atol=1e-9)
    assert np.allclose(wrap_line_angle(pred[:, 4] - obs.psi_a), 0, atol=1e-9)
    assert np.allclose(wrap_line_angle(pred[:, 5] - obs.psi_b), 0, atol=1e-9)
    a3, b3, ta3, tb3 = measurement_model.points_3d(*shape, *poses.T)
    assert np.allclose(b3 - a3, scene.truth.B3 - scene.truth.A3, atol=1e-9)
    assert np.allclose(np.abs(np.sum(ta3 * scene.truth.tangent_A3, 1)), 1, atol=1e-12)


def test_contract_angles_from_canonical_shape(scene):
    """alpha, beta, phi of the simulator (CONTRACT definitions) equal the canonical ones."""
    shape, _ = canonical_parameters(scene.truth)
    assert np.isclose(abs(shape[3]), scene.truth.phi, atol=1e-9)
    assert 0 <= scene.truth.alpha <= np.pi / 2 and 0 <= scene.truth.beta <= np.pi / 2
