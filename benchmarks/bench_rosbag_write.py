"""Writing trees as ROS bags: ``pinframes.write(tree, "run.mcap" | "run.bag")`` against
rosbags serialising the same messages itself (issue 38's goal: at most 2x).

Case: 10^5 transforms, 10 frames moving in ``world`` with 10^4 keyframes each (100 Hz), so
10^4 ``tf2_msgs/TFMessage`` of 10 transforms, one per time, as a ``TransformBroadcaster``
publishing every frame at once sends them; as MCAP (CDR) and as a ROS 1 bag.

- pinframes: the whole write: the poses at every keyframe (``FrameTree.poses``), the
  messages, rosbags' serialisation and its writer, into a file renamed into place;
- reference (no pinframes code): rosbags alone building the same message objects from the
  same numpy arrays and serialising them (``serialize_cdr`` / ``serialize_ros1``), kept in
  memory: what any tool that writes tf through rosbags pays at least;
- for scale, rosbags building, serialising *and* writing them with its own ``Writer``.

Both thread settings, each in a child process (``_machine.py``). The largest difference is
that of the written bag's transforms (decoded by rosbags) to the keyframes, in metres.

Run: ``python benchmarks/bench_rosbag_write.py [--quick]`` (quick: 3 rounds instead of 7).
"""

from __future__ import annotations

import json
import shutil
import sys
import tempfile
from pathlib import Path
from typing import Any

import numpy as np
from rosbags.highlevel import AnyReader
from rosbags.rosbag1 import Writer as Ros1Writer
from rosbags.rosbag2 import StoragePlugin
from rosbags.rosbag2 import Writer as Ros2Writer
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

import pinframes
from _machine import describe_machine, interleaved, print_table, run_in_settings

FRAMES = 10
TIMES = 10_000
TF = "tf2_msgs/msg/TFMessage"
START_NS = 1_709_280_000 * 10**9  # 2024-03-01T08:00:00 UTC
STEP_NS = 10_000_000
REFERENCE = "rosbags serialise"
ALONE_WRITING = "rosbags serialise+write"
PINFRAMES = "pinframes.write"


def motion() -> tuple[np.ndarray, np.ndarray]:
    """Translations (F, T, 3) metres and unit quaternions (F, T, 4), w >= 0."""
    rng = np.random.default_rng(38)
    translations = rng.normal(size=(FRAMES, TIMES, 3))
    quaternions = rng.normal(size=(FRAMES, TIMES, 4))
    quaternions /= np.linalg.norm(quaternions, axis=2, keepdims=True)
    quaternions[quaternions[..., 3] < 0] *= -1
    return translations, quaternions


def tree_of(translations: np.ndarray, quaternions: np.ndarray) -> pinframes.FrameTree:
    tree = pinframes.FrameTree("world", reference_time=np.datetime64(START_NS, "ns"))
    times = (np.arange(TIMES) * STEP_NS).astype("timedelta64[ns]")
    for frame in range(FRAMES):
        tree.add(f"frame_{frame}", "world",
                 pinframes.Pose(translations[frame], quaternions[frame], times=times))
    return tree


def store_of(ros_version: int) -> Any:
    if ros_version == 2:
        return get_typestore(Stores.LATEST)
    store = get_typestore(Stores.ROS1_NOETIC)
    store.register(get_types_from_msg("geometry_msgs/TransformStamped[] transforms", TF))
    return store


def rosbags_messages(store: Any, translations: np.ndarray, quaternions: np.ndarray
                     ) -> list[bytes]:
    """rosbags alone: the TFMessages built from the arrays and serialised."""
    types = store.types
    header, time = types["std_msgs/msg/Header"], types["builtin_interfaces/msg/Time"]
    stamped, transform = (types["geometry_msgs/msg/TransformStamped"],
                          types["geometry_msgs/msg/Transform"])
    vector, rotation = types["geometry_msgs/msg/Vector3"], types["geometry_msgs/msg/Quaternion"]
    message = types[TF]
    ros1 = "seq" in header.__dataclass_fields__
    serialise = store.serialize_ros1 if ros1 else store.serialize_cdr
    moved = translations.transpose(1, 0, 2).tolist()
    turned = quaternions.transpose(1, 0, 2).tolist()
    out = []
    for index in range(TIMES):
        stamp_ns = START_NS + index * STEP_NS
        stamp = time(sec=stamp_ns // 10**9, nanosec=stamp_ns % 10**9)
        head = header(seq=0, stamp=stamp, frame_id="world") if ros1 else header(
            stamp=stamp, frame_id="world")
        out.append(serialise(message(transforms=[
            stamped(header=head, child_frame_id=f"frame_{frame}",
                    transform=transform(translation=vector(*moved[index][frame]),
                                        rotation=rotation(*turned[index][frame])))
            for frame in range(FRAMES)]), TF))
    return out


def rosbags_writing(path: Path, ros_version: int, translations: np.ndarray,
                    quaternions: np.ndarray) -> None:
    """rosbags alone, serialising and writing the messages with its own writer."""
    store = store_of(ros_version)
    data = rosbags_messages(store, translations, quaternions)
    if path.is_dir():
        shutil.rmtree(path)
    elif path.exists():
        path.unlink()
    writer = (Ros1Writer(path) if ros_version == 1
              else Ros2Writer(path, version=8, storage_plugin=StoragePlugin.MCAP))
    with writer:
        connection = writer.add_connection("/tf", TF, typestore=store)
        for index, raw in enumerate(data):
            writer.write(connection, START_NS + index * STEP_NS, raw)


def largest_difference(path: Path, translations: np.ndarray) -> float:
    """The largest difference between frame_0's written translations and its keyframes."""
    store = store_of(1 if path.suffix == ".bag" else 2)
    with AnyReader([path], default_typestore=store) as reader:
        rows = [(t.transform.translation.x, t.transform.translation.y,
                 t.transform.translation.z)
                for connection, _, raw in reader.messages()
                for t in reader.deserialize(raw, connection.msgtype).transforms
                if t.child_frame_id == "frame_0"]
    return float(np.abs(np.array(rows) - translations[0]).max())


def child(quick: bool) -> None:
    translations, quaternions = motion()
    tree = tree_of(translations, quaternions)
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        for kind, ros_version in (("MCAP", 2), ("ROS 1", 1)):
            suffix = ".mcap" if ros_version == 2 else ".bag"
            ours, theirs = Path(scratch) / f"ours{suffix}", Path(scratch) / f"theirs{suffix}"
            store = store_of(ros_version)
            measured = interleaved(f"{kind}, {FRAMES * TIMES:,} transforms", {
                REFERENCE: lambda store=store: rosbags_messages(store, translations,
                                                                quaternions),
                ALONE_WRITING: lambda theirs=theirs, version=ros_version: rosbags_writing(
                    theirs, version, translations, quaternions),
                PINFRAMES: lambda ours=ours: pinframes.write(tree, ours),
            }, 3 if quick else 7, reference=REFERENCE)
            error = largest_difference(ours, translations)
            for entry in measured:
                entry["note"] = f"{entry['seconds'] / (FRAMES * TIMES) * 1e6:.2f} us/transform"
                if entry["method"] == PINFRAMES:
                    entry["error"] = error
            rows += measured
    print(json.dumps(rows))


def main() -> None:
    if "--child" in sys.argv:
        child("--quick" in sys.argv)
        return
    quick = "--quick" in sys.argv
    print(describe_machine())
    print_table(run_in_settings(__file__, ["--quick"] if quick else []), reference=REFERENCE)


if __name__ == "__main__":
    main()
