"""Write the bundled weld as a ROS 2 recording: ``cell_run.mcap`` (needs the ``ros`` extra).

Run from the repository root::

    PYTHONPATH=src python models/welding_cell/make_bag.py

The cell of ``scene.yaml`` as ROS would record it, frame names without the scene's ``robot/``
prefix: ``/tf_static`` holds the static frames (``robot_base`` and ``positioner_base`` in
``world``, the robot's ``base_link`` on ``robot_base``, ``workpiece``, ``weld_seam``, and
``torch_tcp`` on the robot's ``flange``), ``/tf`` the turning ``positioner`` at its keyframes,
``/robot_description`` the welding robot's URDF, ``/joint_states`` the joint motion of
``robot_motion.csv`` at 10 Hz, and ``/weld_current`` (amperes, ``std_msgs/Float64``) a topic
that pinframes leaves alone. The run starts at 2024-03-01T08:00:00 UTC. The same script
writes the same bytes.
"""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

import numpy as np
from rosbags.rosbag2 import StoragePlugin, Writer
from rosbags.typesys import Stores, get_typestore

from pinframes import read_joint_trajectory, read_scene

HERE = Path(__file__).resolve().parent
START_NS = int(np.datetime64("2024-03-01T08:00:00", "ns").astype(np.int64))
STATIC = {"robot_base": "world", "positioner_base": "world", "workpiece": "positioner",
          "weld_seam": "workpiece", "torch_tcp": "flange"}
JOINT_STATE_STEP = 10  # every 10th row of robot_motion.csv (100 Hz): 10 Hz


def make_bag(out: Path) -> Path:
    """Write the recording to ``out`` (an MCAP file); return it."""
    scene = read_scene(HERE / "scene.yaml")
    store = get_typestore(Stores.ROS2_HUMBLE)
    types = store.types
    messages: list[tuple[str, str, int, object]] = []

    def transform(parent: str, child: str, stamp_ns: int, translation, quaternion) -> object:
        header = types["std_msgs/msg/Header"](
            stamp=types["builtin_interfaces/msg/Time"](sec=stamp_ns // 10**9,
                                                      nanosec=stamp_ns % 10**9),
            frame_id=parent)
        return types["geometry_msgs/msg/TransformStamped"](
            header=header, child_frame_id=child, transform=types["geometry_msgs/msg/Transform"](
                translation=types["geometry_msgs/msg/Vector3"](*map(float, translation)),
                rotation=types["geometry_msgs/msg/Quaternion"](*map(float, quaternion))))

    static = [transform(STATIC[name], name, START_NS, pose.translation, pose.quaternion)
              for name in STATIC
              for pose in [scene.local_pose("robot/flange" if name == "flange" else name)]]
    static.append(transform("robot_base", "base_link", START_NS, (0, 0, 0), (0, 0, 0, 1)))
    messages.append(("/tf_static", "tf2_msgs/msg/TFMessage", START_NS,
                     types["tf2_msgs/msg/TFMessage"](transforms=static)))
    positioner = scene.local_pose("positioner")
    for offset_ns, translation, quaternion in zip(
            positioner.times.astype(np.int64).tolist(), positioner.translation,
            positioner.quaternion, strict=True):
        stamp = START_NS + offset_ns
        messages.append(("/tf", "tf2_msgs/msg/TFMessage", stamp, types["tf2_msgs/msg/TFMessage"](
            transforms=[transform("positioner_base", "positioner", stamp, translation,
                                  quaternion)])))
    urdf = (HERE.parent / "welding_robot" / "welding_robot.urdf").read_text()
    messages.append(("/robot_description", "std_msgs/msg/String", START_NS,
                     types["std_msgs/msg/String"](data=urdf)))
    seconds, positions, joint_names = read_joint_trajectory(HERE / "robot_motion.csv")
    times = np.round(np.asarray(seconds, float) * 1e9).astype(np.int64)[::JOINT_STATE_STEP]
    for row, offset_ns in zip(positions[::JOINT_STATE_STEP], times.tolist(), strict=True):
        stamp = START_NS + offset_ns
        header = types["std_msgs/msg/Header"](
            stamp=types["builtin_interfaces/msg/Time"](sec=stamp // 10**9,
                                                      nanosec=stamp % 10**9), frame_id="")
        messages.append(("/joint_states", "sensor_msgs/msg/JointState", stamp,
                         types["sensor_msgs/msg/JointState"](
                             header=header, name=list(joint_names),
                             position=np.asarray(row, float), velocity=np.zeros(0),
                             effort=np.zeros(0))))
        current = 180.0 + 5.0 * np.sin(offset_ns / 1e9)
        messages.append(("/weld_current", "std_msgs/msg/Float64", stamp + 1,
                         types["std_msgs/msg/Float64"](data=float(current))))
    messages.sort(key=lambda message: message[2])
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch) / "bag"
        with Writer(folder, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
            connections = {}
            for topic, kind, received_ns, message in messages:
                if topic not in connections:
                    connections[topic] = writer.add_connection(topic, kind, typestore=store)
                writer.write(connections[topic], received_ns, store.serialize_cdr(message, kind))
        (written,) = folder.glob("*.mcap")
        shutil.copyfile(written, out)
    return out


if __name__ == "__main__":
    print(make_bag(HERE / "cell_run.mcap"))
