"""The hot-path kernels against independent computations: Pinocchio's SE3, Quaternion,
exp3/log3 and closed forms written here, on random inputs and the hard cases (near-identical
quaternions, antipodal keyframes, half turns)."""

import math

import numpy as np
import pinocchio as pin
import pytest

from pinframes.values._trigonometry import cos_sin
from pinframes.values.interpolation import Keyframes
from pinframes.values.joint import Joint
from pinframes.values.rotations import matrix_from_quaternion
from pinframes.values.se3 import IDENTITY, compose, inverse


def random_quaternions(rng, count):
    q = rng.normal(size=(count, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def pin_rotation(q):
    return pin.Quaternion(q[3], q[0], q[1], q[2]).toRotationMatrix()


def test_matrix_from_quaternion_of_a_batch_with_leading_axes(rng):
    q = random_quaternions(rng, 60).reshape(3, 20, 4)
    matrices = matrix_from_quaternion(q)
    assert matrices.shape == (3, 20, 3, 3)
    for index in np.ndindex(3, 20):
        np.testing.assert_allclose(matrices[index], pin_rotation(q[index]), atol=1e-15)


@pytest.mark.parametrize("left_batched", [False, True])
@pytest.mark.parametrize("right_batched", [False, True])
@pytest.mark.parametrize("count", [20, 300])  # below and above the small-batch threshold
def test_compose_and_inverse_match_pinocchio_se3(rng, left_batched, right_batched, count):
    def random_transform(batched):
        """Samples last: rotations (3, 3, N) and translations (3, N), or one static pose."""
        rotations = np.array([pin_rotation(q) for q in random_quaternions(rng, count)])
        translations = rng.normal(size=(count, 3))
        if not batched:
            return rotations[0], translations[0]
        return np.moveaxis(rotations, 0, -1), translations.T

    first, second = random_transform(left_batched), random_transform(right_batched)
    rotation, translation = compose(first, second)
    inverse_rotation, inverse_translation = inverse(first)
    if left_batched or right_batched:  # back to one pose per row, to index by sample
        rotation, translation = np.moveaxis(rotation, -1, 0), translation.T
    if left_batched:
        inverse_rotation = np.moveaxis(inverse_rotation, -1, 0)
        inverse_translation = inverse_translation.T
    for n in range(count):
        a = pin.SE3(*(part[..., n] if left_batched else part for part in first))
        b = pin.SE3(*(part[..., n] if right_batched else part for part in second))
        product = a * b
        batched = left_batched or right_batched
        np.testing.assert_allclose(rotation[n] if batched else rotation, product.rotation,
                                   atol=1e-14)
        np.testing.assert_allclose(translation[n] if batched else translation,
                                   product.translation, atol=1e-13)
        np.testing.assert_allclose(inverse_rotation[n] if left_batched else inverse_rotation,
                                   a.inverse().rotation, atol=1e-15)
        np.testing.assert_allclose(
            inverse_translation[n] if left_batched else inverse_translation,
            a.inverse().translation, atol=1e-14)
        if not batched:
            break
    assert compose(IDENTITY, first) is first and compose(first, IDENTITY) is first


def slerp_by_log(rotation_0, rotation_1, fraction):
    """Independent SLERP: R0 exp(f log(R0^T R1)) (the short way, via Pinocchio)."""
    relative = pin.log3(rotation_0.T @ rotation_1)
    return rotation_0 @ pin.exp3(fraction * relative)


def keyframes_of(quaternions, translations):
    times = np.arange(len(quaternions), dtype=np.int64) * 1_000_000_000
    return Keyframes(times, matrix_from_quaternion(np.asarray(quaternions)),
                     np.asarray(translations, dtype=float))


def test_slerp_and_linear_translation_match_exp_log_on_random_keyframes(rng):
    quaternions = random_quaternions(rng, 30)
    translations = rng.normal(size=(30, 3))
    keyframes = keyframes_of(quaternions, translations)
    times = np.sort(rng.integers(-2_000_000_000, 31_000_000_000, size=500))
    sampled_rotations, sampled_translations = keyframes.sample(times)
    for t, translation, rotation in zip(times, sampled_translations, sampled_rotations,
                                        strict=True):
        seconds = min(max(t / 1e9, 0.0), 29.0)
        index = min(int(seconds), 28)
        fraction = seconds - index
        expected_rotation = slerp_by_log(pin_rotation(quaternions[index]),
                                         pin_rotation(quaternions[index + 1]), fraction)
        expected_translation = ((1 - fraction) * translations[index]
                                + fraction * translations[index + 1])
        np.testing.assert_allclose(rotation, expected_rotation, atol=1e-12)
        np.testing.assert_allclose(translation, expected_translation, atol=1e-12)


def test_slerp_between_nearly_identical_quaternions_is_smooth_and_orthonormal(rng):
    base = random_quaternions(rng, 1)[0]
    for gap in (0.0, 1e-16, 1e-13, 1e-10, 1e-7):
        other = base + gap * rng.normal(size=4)
        other /= np.linalg.norm(other)
        keyframes = keyframes_of([base, other], np.zeros((2, 3)))
        times = np.linspace(0, 1_000_000_000, 11).astype(np.int64)
        rotations, _ = keyframes.sample(times)
        for fraction, rotation in zip(np.linspace(0, 1, 11), rotations, strict=True):
            expected = slerp_by_log(pin_rotation(base), pin_rotation(other), fraction)
            np.testing.assert_allclose(rotation, expected, atol=1e-12)
            np.testing.assert_allclose(rotation.T @ rotation, np.eye(3), atol=1e-12)


def test_antipodal_keyframes_are_the_same_rotation_and_stay_put(rng):
    q = random_quaternions(rng, 1)[0]
    keyframes = keyframes_of([q, -q, q], np.zeros((3, 3)))
    rotations, _ = keyframes.sample(np.linspace(0, 2e9, 41).astype(np.int64))
    for rotation in rotations:
        np.testing.assert_allclose(rotation, pin_rotation(q), atol=1e-14)


@pytest.mark.parametrize("axis", [(0.0, 0.0, 1.0), (1.0, 2.0, -2.0)])
def test_slerp_through_a_half_turn_turns_about_the_keyframes_axis(rng, axis):
    """180 degrees between keyframes (q1 = q0 * (axis, 0)): both ways round are equally
    short, so the path must turn about +axis or -axis, the same way at every time; the
    expected rotations are Rodrigues' formula written here by hand."""
    unit = np.asarray(axis) / np.linalg.norm(axis)
    q0 = random_quaternions(rng, 1)[0]
    r0 = pin_rotation(q0)
    q1_pin = pin.Quaternion(q0[3], q0[0], q0[1], q0[2]) * pin.Quaternion(0.0, *unit)
    q1 = np.array([q1_pin.x, q1_pin.y, q1_pin.z, q1_pin.w])
    keyframes = keyframes_of([q0, q1], np.zeros((2, 3)))
    fractions = np.linspace(0, 1, 9)
    rotations, _ = keyframes.sample((fractions * 1e9).astype(np.int64))

    def turned(sign):
        k = sign * np.array([[0, -unit[2], unit[1]], [unit[2], 0, -unit[0]],
                             [-unit[1], unit[0], 0]])
        angles = np.pi * fractions
        return np.array([r0 @ (np.eye(3) + np.sin(a) * k + (1 - np.cos(a)) * k @ k)
                         for a in angles])

    errors = [np.max(np.abs(rotations - turned(sign))) for sign in (1.0, -1.0)]
    assert min(errors) < 1e-12, errors


@pytest.mark.parametrize("kind", ["revolute", "continuous", "prismatic"])
@pytest.mark.parametrize("axis", [(0.0, 0.0, 1.0), (0.0, -1.0, 0.0), (1.0, 0.0, 0.0),
                                  (0.3, -0.5, 0.8), (0.0, -1.0, -4.37114e-08)])
@pytest.mark.parametrize("frame_batched", [False, True])
def test_joint_motion_matches_pinocchio(rng, kind, axis, frame_batched):
    """``Joint.moved(frame, q)`` = ``frame * motion(q)``, the motion built by Pinocchio
    (``exp3`` of the angle about the axis, or a slide along it)."""
    values = np.concatenate([rng.uniform(-7, 7, size=50), [0.0, np.pi, -np.pi]])
    frames = [pin.SE3(pin_rotation(q), rng.normal(size=3))
              for q in random_quaternions(rng, values.size if frame_batched else 1)]
    if frame_batched:  # samples last
        frame = (np.stack([f.rotation for f in frames], axis=-1),
                 np.stack([f.translation for f in frames], axis=-1))
    else:
        frame = (frames[0].rotation, frames[0].translation)
    rotations, translations = Joint("j", kind, axis).moved(frame, values)
    # samples last, one side static: back to one pose per row
    rotations = np.broadcast_to(rotations[..., None] if rotations.ndim == 2 else rotations,
                                (3, 3, values.size))
    translations = np.broadcast_to(
        translations[:, None] if translations.ndim == 1 else translations, (3, values.size))
    rotations, translations = np.moveaxis(rotations, -1, 0), translations.T
    unit = np.asarray(axis) / np.linalg.norm(axis)
    for n, (value, rotation, translation) in enumerate(
            zip(values, rotations, translations, strict=True)):
        if kind == "prismatic":
            motion = pin.SE3(np.eye(3), value * unit)
        else:
            motion = pin.SE3(pin.exp3(value * unit), np.zeros(3))
        expected = frames[n if frame_batched else 0] * motion
        np.testing.assert_allclose(rotation, expected.rotation, atol=1e-14)
        np.testing.assert_allclose(translation, expected.translation, atol=1e-13)


@pytest.mark.parametrize("kind", ["revolute", "prismatic"])
def test_joint_motion_of_one_value_on_a_static_frame_stays_static(rng, kind):
    frame = (pin_rotation(random_quaternions(rng, 1)[0]), rng.normal(size=3))
    rotation, translation = Joint("j", kind, (0.0, 0.0, -1.0)).moved(frame, 0.7)
    motion = (pin.SE3(pin.exp3(np.array([0.0, 0.0, -0.7])), np.zeros(3)) if kind == "revolute"
              else pin.SE3(np.eye(3), np.array([0.0, 0.0, -0.7])))
    expected = pin.SE3(*frame) * motion
    assert rotation.shape == (3, 3) and translation.shape == (3,)
    np.testing.assert_allclose(rotation, expected.rotation, atol=1e-15)
    np.testing.assert_allclose(translation, expected.translation, atol=1e-15)


@pytest.mark.parametrize("static_side", ["left", "right"])
@pytest.mark.parametrize("count", [20, 300])
def test_products_with_axis_aligned_static_factors_match_dense_ones(rng, static_side, count):
    """Static factors with exact zeros, +-1 and the 2e-16 residue of cos(pi/2) (as read
    from a URDF's right angles): the terms dropped lie within rounding of the dense
    products, computed here with einsum."""
    batched = np.moveaxis(np.array([pin_rotation(q) for q in random_quaternions(rng, count)]),
                          0, -1)
    residue = 2.220446049250313e-16
    for static in ([[1.0, 0.0, 0.0], [0.0, residue, 1.0], [0.0, -1.0, residue]],
                   [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
                   [[0.7071067811865476, 0.7071067811865476, 0.0],
                    [-0.7071067811865476, 0.7071067811865476, 0.0], [0.0, 0.0, 1.0]],
                   [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]):
        static = np.array(static)
        vector = static[1] * 0.3
        if static_side == "right":
            product = compose((batched, np.zeros((3, count))), (static, vector))
            expected = (np.einsum("ijn,jk->ikn", batched, static),
                        np.einsum("ijn,j->in", batched, vector))
        else:
            product = compose((static, vector), (batched, np.zeros((3, count))))
            expected = (np.einsum("ij,jkn->ikn", static, batched),
                        np.broadcast_to(vector[:, None], (3, count)))
        np.testing.assert_allclose(product[0], expected[0], rtol=0, atol=1e-15)
        np.testing.assert_allclose(product[1], expected[1], rtol=0, atol=1e-15)


def test_cosine_and_sine_from_the_half_angle_tangent_match_the_math_module(rng):
    angles = np.concatenate([rng.uniform(-7, 7, 2000), rng.uniform(-1e6, 1e6, 2000),
                             [0.0, np.pi, -np.pi, np.pi / 2, -np.pi / 2, 2 * np.pi, 1e-300]])
    cosine, sine = cos_sin(angles)
    expected_cosine = np.array([math.cos(a) for a in angles])
    expected_sine = np.array([math.sin(a) for a in angles])
    np.testing.assert_allclose(cosine, expected_cosine, rtol=0, atol=4.5e-16)
    np.testing.assert_allclose(sine, expected_sine, rtol=0, atol=4.5e-16)
    assert cos_sin(0.25) == pytest.approx((math.cos(0.25), math.sin(0.25)), abs=2e-16)
