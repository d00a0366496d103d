"""Roll, pitch and yaw read from a rotation give the rotation back to rounding at every
pitch, the gimbal lock and its neighbourhood included (matrices built by scipy).

Before, yaw and roll were both read from entries of size cos(pitch): at pitch -90 degrees +
1e-7 rad the three angles gave back the matrix 5e-11 off, at + 1e-11 rad 4e-7 off, and a
tree written with rpy (URDF, scene, frames.yaml) came back that far off. The property tests
meet such a pitch only when Hypothesis happens to draw it, which depends on the modules
loaded before them (it draws the constants it finds in them), hence on the test order."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import pinframes
from pinframes.values.rotations import matrix_from_rpy, rpy_from_matrix

OFFSETS = [1e-3, 1e-5, 3e-6, 1e-7, 1e-9, 1e-11, 0.0]


@pytest.mark.parametrize("offset", OFFSETS)
@pytest.mark.parametrize("side", [-1.0, 1.0])
def test_angles_give_the_matrix_back_near_the_lock(offset, side):
    rng = np.random.default_rng(int(offset * 1e12) + int(side) + 1)
    roll, yaw = rng.uniform(-3.0, 3.0, size=2)
    matrix = Rotation.from_euler("ZYX", [yaw, side * (np.pi / 2 - offset), roll]).as_matrix()
    angles = rpy_from_matrix(matrix)
    assert abs(angles[1] - side * (np.pi / 2 - offset)) < 1e-8
    np.testing.assert_allclose(matrix_from_rpy(angles), matrix, rtol=0.0, atol=1e-15)


def test_a_frame_near_pitch_minus_ninety_degrees_survives_a_urdf(tmp_path):
    matrix = Rotation.from_euler("ZYX", [0.7, -(np.pi / 2 - 1e-7), -1.3]).as_matrix()
    tree = pinframes.FrameTree("world")
    tree.add("tool", "world", pinframes.Pose([0.1, 0.2, 0.3], matrix))
    pinframes.write_urdf(tree, tmp_path / "tool.urdf")
    back = pinframes.read_urdf(tmp_path / "tool.urdf")
    np.testing.assert_allclose(back.pose("tool", "world").rotation, matrix, rtol=0.0, atol=1e-15)
