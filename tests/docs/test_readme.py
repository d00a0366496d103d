"""The Python examples of README.md run as written, from the repository root."""

import re
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_readme_python_examples_run(monkeypatch):
    monkeypatch.chdir(ROOT)
    blocks = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), re.S)
    assert blocks
    namespace: dict = {}
    for block in blocks:
        exec(compile(block, "README.md", "exec"), namespace)
    # The seam start turns with the table about the positioner's z axis: on a circle of 0.2 m.
    seam = namespace["pose_seam_in_world"].translation
    np.testing.assert_allclose(np.hypot(seam[:, 0] - 1.5, seam[:, 1]), 0.2, atol=1e-12)
    # what the load_geometry example says it prints: 17 pieces, the torch's mesh file
    torch = namespace["torch"]
    assert (len(namespace["pieces"]), torch.source, torch.faces.shape) == (
        17, "meshes/torch.stl", (352, 3))
    # the shapes example: the probe's ball 0.3 m above the table top (the cylinder is
    # hypot(0.3, 0.2) - 0.03 m aside), less its radius
    assert namespace["jig"].clearance("table", "probe").distance[0] == \
        pytest.approx(0.3 - 0.02, abs=1e-12)


def test_readme_kinematics_example_prints_hand_derived_numbers(monkeypatch):
    """The numbers printed in the section on measured data, velocities and Jacobians."""
    monkeypatch.chdir(ROOT)
    blocks = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), re.S)
    namespace: dict = {}
    for block in blocks:  # up to this section's block (later ones reuse the name tree)
        exec(compile(block, "README.md", "exec"), namespace)
        if "jacobian_tcp" in namespace:
            break
    # the table turns 90 degrees in 10 s about z at (1.5, 0, 0.8)
    angles = np.array([0.0, np.pi / 4, np.pi / 2])
    for index, radius in enumerate([0.2, 0.25]):
        expected = np.stack([1.5 + radius * np.cos(angles), radius * np.sin(angles),
                             np.full(3, 0.85)], axis=1)
        np.testing.assert_allclose(namespace["profile_in_world"][:, index], expected,
                                   atol=1e-15)
    np.testing.assert_allclose(namespace["track_in_world"], [[1.7, 0, 0.8], [1.5, 0.2, 0.8]],
                               atol=1e-15)
    rate = np.pi / 20
    np.testing.assert_allclose(namespace["velocity_seam"].angular, [[0, 0, rate]], atol=1e-15)
    np.testing.assert_allclose(np.linalg.norm(namespace["velocity_seam"].linear), 0.2 * rate,
                               atol=1e-15)
    # joint_1 turns about the z axis of robot_base, 0.2 m up: its column is z x (p - axis)
    jacobian = namespace["jacobian_tcp"]
    tcp = namespace["tree"].pose("torch_tcp", "robot_base", times=[5.0]).translation[0]
    np.testing.assert_allclose(jacobian.matrix[0, :, 0], [-tcp[1], tcp[0], 0, 0, 0, 1],
                               atol=1e-14)
    velocity = namespace["velocity_tcp"]
    np.testing.assert_allclose(velocity.angular, [[0, 0, 0.05]], atol=1e-15)
    np.testing.assert_allclose(velocity.linear, [[-0.05 * tcp[1], 0.05 * tcp[0], 0]],
                               atol=1e-15)
