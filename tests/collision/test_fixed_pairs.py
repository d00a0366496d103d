"""Pairs of links whose distance cannot change (fixed to each other) are left out of a
clearance over patterns, and counted; the rest equals Pinocchio + coal called directly."""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np
import pinocchio as pin

import pinframes
from ik_paths import example_robot
from pinframes.cli.clearance import clearance_summary
from pinframes.errors import JointWithoutSamplesWarning
from pinframes.formats.tables import clearance_text


def _ur5() -> tuple[pinframes.FrameTree, pin.Model, str]:
    urdf = example_robot("ur5_robot.urdf")
    tree = pinframes.FrameTree("world")
    tree.attach_urdf(urdf, "world", prefix="ur5/")
    return tree, pin.buildModelFromUrdf(str(urdf)), str(urdf)


def _pinocchio_clearance(model: pin.Model, urdf: str, q: np.ndarray) -> float:
    """The smallest distance of every pair of collision objects on different joints (links
    that can move against each other), by Pinocchio and coal called directly."""
    share = str(Path(urdf).parents[4])  # .../share holds the package example-robot-data
    geometry = pin.buildGeomFromUrdf(model, urdf, pin.GeometryType.COLLISION,
                                     package_dirs=[share])
    for first in range(len(geometry.geometryObjects)):
        for second in range(first + 1, len(geometry.geometryObjects)):
            if (geometry.geometryObjects[first].parentJoint
                    != geometry.geometryObjects[second].parentJoint):
                geometry.addCollisionPair(pin.CollisionPair(first, second))
    data, geometry_data = model.createData(), geometry.createData()
    pin.updateGeometryPlacements(model, data, geometry, geometry_data, q)
    pin.computeDistances(geometry, geometry_data)
    return min(result.min_distance for result in geometry_data.distanceResults)


def test_links_bolted_together_are_left_out_and_counted():
    tree, _, _ = _ur5()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", JointWithoutSamplesWarning)
        result = tree.clearance("ur5/*", "ur5/*")
    # wrist_3_link and ee_link are joined by a fixed joint: their overlap never changes
    assert ("ur5/wrist_3_link", "ur5/ee_link") in result.fixed_together
    assert all(pair not in result.fixed_together
               for pair in [("ur5/upper_arm_link", "ur5/forearm_link"),
                            ("ur5/forearm_link", "ur5/upper_arm_link")])
    assert result.distance[0] >= 0.0


def test_two_frames_named_outright_are_still_checked():
    tree, _, _ = _ur5()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", JointWithoutSamplesWarning)
        result = tree.clearance("ur5/wrist_3_link", "ur5/ee_link")
    assert result.fixed_together == ()
    assert result.distance[0] < 0.0  # the two shapes overlap where they are bolted together


def test_the_rest_equals_pinocchio_and_coal_on_random_configurations():
    tree, model, urdf = _ur5()
    names = [f"ur5/{name}" for name in model.names[1:]]
    rng = np.random.default_rng(7)
    q = rng.uniform(-np.pi, np.pi, size=(6, model.nq))
    tree.set_joint_trajectory(np.arange(6.0), q, names)
    result = tree.clearance("ur5/*", "ur5/*", times=np.arange(6.0))
    expected = [_pinocchio_clearance(model, urdf, row) for row in q]
    np.testing.assert_allclose(result.distance, expected, atol=1e-6)


def test_the_command_line_summary_counts_the_pairs_left_out():
    tree, _, _ = _ur5()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", JointWithoutSamplesWarning)
        result = tree.clearance("ur5/*", "ur5/*")
    assert f"{len(result.fixed_together)} pairs fixed to each other left out" in (
        clearance_summary(result))
    assert len(result.fixed_together) >= 1


def test_a_written_json_table_lists_the_fixed_pairs():
    tree, _, _ = _ur5()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", JointWithoutSamplesWarning)
        result = tree.clearance("ur5/*", "ur5/*")
    document = json.loads(clearance_text(result, "json"))
    assert [tuple(pair) for pair in document["fixed_together"]] == list(result.fixed_together)
