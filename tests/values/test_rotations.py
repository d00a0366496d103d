import numpy as np
import pinocchio as pin

from pinframes.values.rotations import (
    matrix_from_axis_angle,
    matrix_from_quaternion,
    matrix_from_rpy,
    quaternion_from_matrix,
    rotation_matrix_defects,
    rpy_from_matrix,
)


def random_quaternions(rng, count):
    q = rng.normal(size=(count, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def test_matrix_from_quaternion_matches_pinocchio(rng):
    for q in random_quaternions(rng, 50):
        expected = pin.Quaternion(q[3], q[0], q[1], q[2]).toRotationMatrix()
        np.testing.assert_allclose(matrix_from_quaternion(q), expected, atol=1e-14)


def test_quaternion_round_trip_including_near_180_degrees(rng):
    quaternions = random_quaternions(rng, 200)
    quaternions[:4] = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0.7071068, 0, 0.7071068, 0]]
    quaternions /= np.linalg.norm(quaternions, axis=1, keepdims=True)
    back = quaternion_from_matrix(matrix_from_quaternion(quaternions))
    same_sign = np.where(quaternions[:, 3:4] < 0, -quaternions, quaternions)
    # q and -q are the same rotation: compare up to sign, w >= 0 on output.
    assert np.all(back[:, 3] >= 0)
    close = np.minimum(np.abs(back - same_sign).max(axis=1), np.abs(back + same_sign).max(axis=1))
    assert close.max() < 1e-12


def test_rpy_matches_pinocchio_and_round_trips(rng):
    for rpy in rng.uniform(-3, 3, size=(50, 3)) * [1, 0.5, 1]:
        np.testing.assert_allclose(matrix_from_rpy(rpy), pin.rpy.rpyToMatrix(*rpy), atol=1e-14)
        np.testing.assert_allclose(rpy_from_matrix(matrix_from_rpy(rpy)), rpy, atol=1e-12)


def test_rpy_at_gimbal_lock_still_gives_the_same_matrix():
    matrix = matrix_from_rpy([0.3, np.pi / 2, 0.2])
    np.testing.assert_allclose(matrix_from_rpy(rpy_from_matrix(matrix)), matrix, atol=1e-12)


def test_axis_angle_matches_pinocchio_exp(rng):
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    angles = np.array([-2.0, 0.0, 0.4, 3.1])
    matrices = matrix_from_axis_angle(axis, angles)
    for angle, matrix in zip(angles, matrices, strict=True):
        np.testing.assert_allclose(matrix, pin.exp3(axis * angle), atol=1e-14)


def test_defects_detect_scaling_and_reflection():
    assert max(rotation_matrix_defects(np.eye(3))) < 1e-15
    assert rotation_matrix_defects(np.eye(3) * 1.01)[0] > 0.01
    assert rotation_matrix_defects(np.diag([1.0, 1.0, -1.0]))[1] > 1.9
