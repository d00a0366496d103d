"""An ``<origin>`` inside ``<geometry>`` (after the shape, as a published welding end-effector
has it) is ignored as urdfdom and Pinocchio ignore it, with one warning; the link keeps its
shape and the clearance equals Pinocchio + coal on the same file."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

import pinframes
from pinframes.errors import GeometryWarning
from pinframes.values.geometry import GEOMETRY_METADATA_KEY

URDF = """<?xml version="1.0"?>
<robot name="torch_on_a_post">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <joint name="lift" type="prismatic">
    <parent link="base"/><child link="torch"/><origin xyz="0 0 0.5"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <link name="torch">
    <collision>
      <origin xyz="0 0 0.05"/>
      <geometry><cylinder radius="0.02" length="0.1"/><origin xyz="0 0 1.0" rpy="0 1 0"/></geometry>
    </collision>
  </link>
</robot>
"""


def test_the_stray_origin_is_ignored_with_one_warning_naming_the_link(tmp_path):
    path = tmp_path / "torch.urdf"
    path.write_text(URDF)
    with pytest.warns(GeometryWarning, match=r"torch\.collision\[0\]") as caught:
        tree = pinframes.read_urdf(path)
    assert len([w for w in caught if issubclass(w.category, GeometryWarning)]) == 1
    assert str(path) in str(caught[0].message)
    shape = tree.frame_metadata("torch")[GEOMETRY_METADATA_KEY].collision[0]
    assert shape.kind == "cylinder" and shape.xyz == (0.0, 0.0, 0.05)


def test_the_clearance_equals_pinocchio_and_coal_on_the_same_file(tmp_path):
    path = tmp_path / "torch.urdf"
    path.write_text(URDF)
    with pytest.warns(GeometryWarning):
        tree = pinframes.read_urdf(path)
    lifts = np.array([-0.4, -0.2, 0.0])
    tree.set_joint_trajectory([0.0, 1.0, 2.0], lifts[:, None], ["lift"])
    result = tree.clearance("base", "torch", times=[0.0, 1.0, 2.0])

    model = pin.buildModelFromUrdf(str(path))
    geometry = pin.buildGeomFromUrdf(model, str(path), pin.GeometryType.COLLISION)
    geometry.addAllCollisionPairs()
    data, geometry_data = model.createData(), geometry.createData()
    expected = []
    for lift in lifts:
        pin.computeDistances(model, data, geometry, geometry_data, np.array([lift]))
        expected.append(geometry_data.distanceResults[0].min_distance)
    np.testing.assert_allclose(result.distance, expected, atol=1e-9)
