"""Reading recorded tf from ROS bags: ``pinframes.read_rosbag`` against rosbags' own reader and
deserialiser (issue 29's goal: at most 2x, and linear in the transforms).

Cases: bags of 10^5 and 10^6 transforms (10 frames moving in ``world``, one
``geometry_msgs/TransformStamped`` per ``tf2_msgs/TFMessage`` as a ``TransformBroadcaster``
sends them, 100 Hz per frame), written by rosbags as a ROS 2 MCAP bag and a ROS 1 bag; at
10^5 also with compressed chunks (MCAP zstd, ROS 1 bz2), which pinframes inflates itself,
a piece at a time within ``max_decompressed_bytes``.
pinframes reads the whole tree (messages, decoding, tf2's rules, the moving frames);
the reference is rosbags alone, ``AnyReader`` + ``deserialize`` of every message, keeping the
message objects (no tree). Per transform the two sizes should cost the same (linear). Both
thread settings, each in a child process (``_machine.py``).

Run: ``python benchmarks/bench_rosbag.py [--quick]`` (quick: 10^5 transforms only, 3 rounds
instead of 5; 10^6 transforms are timed in one round); the bags are written first into a
temporary folder (about 20 s per 10^6 transforms on a quiet machine).
"""

from __future__ import annotations

import json
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from rosbags.highlevel import AnyReader
from rosbags.rosbag1 import Writer as Ros1Writer
from rosbags.rosbag2 import CompressionFormat, CompressionMode, StoragePlugin
from rosbags.rosbag2 import Writer as Ros2Writer
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

import pinframes
from _machine import describe_machine, print_table, row, run_in_settings

FRAMES = 10
SIZES = (100_000, 1_000_000)
TF = "tf2_msgs/msg/TFMessage"
REFERENCE = "rosbags read+deserialise"
PINFRAMES = "pinframes.read_rosbag"


def write_bags(folder: Path, transforms: int, compressed: bool = False) -> dict[str, Path]:
    """An MCAP (ROS 2) and a ROS 1 bag of ``transforms`` transforms, their chunks compressed
    (zstd, bz2) or not; their paths by storage."""
    rng = np.random.default_rng(transforms)
    translations = rng.normal(size=(transforms, 3))
    quaternions = rng.normal(size=(transforms, 4))
    quaternions /= np.linalg.norm(quaternions, axis=1, keepdims=True)
    stamps = 1_700_000_000 * 10**9 + (np.arange(transforms) // FRAMES) * 10_000_000
    bags = {}
    for storage in ("mcap", "ros1"):
        if storage == "ros1":
            store = get_typestore(Stores.ROS1_NOETIC)
            store.register(get_types_from_msg("geometry_msgs/TransformStamped[] transforms", TF))
            path = folder / f"tf_{transforms}{'_bz2' if compressed else ''}.bag"
            writer = Ros1Writer(path)
            if compressed:
                writer.set_compression(Ros1Writer.CompressionFormat.BZ2)
            serialise = store.serialize_ros1
        else:
            store = get_typestore(Stores.ROS2_HUMBLE)
            path = folder / f"tf_{transforms}{'_zstd' if compressed else ''}_mcap"
            writer = Ros2Writer(path, version=9, storage_plugin=StoragePlugin.MCAP)
            if compressed:
                writer.set_compression(CompressionMode.STORAGE, CompressionFormat.ZSTD)
            serialise = store.serialize_cdr
        types = store.types
        header_fields = types["std_msgs/msg/Header"].__dataclass_fields__
        with writer:
            connection = writer.add_connection("/tf", TF, typestore=store)
            for index in range(transforms):
                stamp = int(stamps[index])
                header = {"stamp": types["builtin_interfaces/msg/Time"](
                    sec=stamp // 10**9, nanosec=stamp % 10**9), "frame_id": "world"}
                if "seq" in header_fields:
                    header["seq"] = index
                message = types[TF](transforms=[types["geometry_msgs/msg/TransformStamped"](
                    header=types["std_msgs/msg/Header"](**header),
                    child_frame_id=f"frame_{index % FRAMES}",
                    transform=types["geometry_msgs/msg/Transform"](
                        translation=types["geometry_msgs/msg/Vector3"](*translations[index]),
                        rotation=types["geometry_msgs/msg/Quaternion"](*quaternions[index])))])
                writer.write(connection, stamp, serialise(message, TF))
        bags[f"{storage}, {'zstd' if storage == 'mcap' else 'bz2'} chunks" if compressed
             else storage] = path
    return bags


def rosbags_alone(path: Path) -> list[object]:
    """Every message of the bag deserialised by rosbags, with the types the bag carries."""
    with AnyReader([path], default_typestore=get_typestore(Stores.LATEST)) as reader:
        return [reader.deserialize(raw, connection.msgtype)
                for connection, _, raw in reader.messages(reader.connections)]


def largest_difference(tree: pinframes.FrameTree, messages: list) -> float:
    """The largest difference between frame_0's keyframes in ``tree`` and its transforms as
    rosbags deserialised them (sorted by stamp): metres, and 1 - |q . q'| for rotations."""
    rows = sorted((t.header.stamp.sec * 10**9 + t.header.stamp.nanosec,
                   (t.transform.translation.x, t.transform.translation.y,
                    t.transform.translation.z),
                   (t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z,
                    t.transform.rotation.w))
                  for message in messages for t in message.transforms
                  if t.child_frame_id == "frame_0")
    pose = tree.local_pose("frame_0")
    translations = np.array([row[1] for row in rows])
    quaternions = np.array([row[2] for row in rows])
    dots = np.abs(np.einsum("ij,ij->i", pose.quaternion, quaternions))
    return float(max(np.abs(pose.translation - translations).max(), (1 - dots).max()))


def timed_rounds(case: str, path: str, rounds: int) -> list[dict]:
    """Both reads of ``path`` timed in ``rounds`` alternating rounds (no warm-up: the bag was
    just written, its pages are cached; a 10^6 read takes minutes on a shared machine);
    ratios are medians of per-round ratios. The last round's results give the difference."""
    seconds: dict[str, list[float]] = {REFERENCE: [], PINFRAMES: []}
    for _ in range(rounds):
        start = time.perf_counter()
        messages = rosbags_alone(Path(path))
        seconds[REFERENCE].append(time.perf_counter() - start)
        start = time.perf_counter()
        tree = pinframes.read_rosbag(path)
        seconds[PINFRAMES].append(time.perf_counter() - start)
    error = largest_difference(tree, messages)
    ratios = [ours / theirs for ours, theirs in zip(seconds[PINFRAMES], seconds[REFERENCE],
                                                      strict=True)]
    return [row(case, REFERENCE, statistics.median(seconds[REFERENCE]), ratio=1.0),
            row(case, PINFRAMES, statistics.median(seconds[PINFRAMES]), error,
                ratio=statistics.median(ratios))]


def child(bag_table: dict[str, dict[str, str]], quick: bool) -> None:
    rows = []
    for transforms, bags in bag_table.items():
        for storage, path in bags.items():
            rounds = 1 if int(transforms) > 100_000 else 3 if quick else 5
            measured = timed_rounds(f"{storage}, {int(transforms):,} transforms", path, rounds)
            for entry in measured:
                entry["note"] = f"{entry['seconds'] / int(transforms) * 1e6:.2f} us/transform"
            rows += measured
    print(json.dumps(rows))


def main() -> None:
    if "--child" in sys.argv:
        table = json.loads(sys.argv[sys.argv.index("--bags") + 1])
        child(table, "--quick" in sys.argv)
        return
    quick = "--quick" in sys.argv
    print(describe_machine())
    with tempfile.TemporaryDirectory() as scratch:
        table = {}
        for transforms in SIZES[:1] if quick else SIZES:
            bags = write_bags(Path(scratch), transforms)
            if transforms == SIZES[0]:
                bags |= write_bags(Path(scratch), transforms, compressed=True)
            table[str(transforms)] = {storage: str(path) for storage, path in bags.items()}
        arguments = ["--bags", json.dumps(table)] + (["--quick"] if quick else [])
        print_table(run_in_settings(__file__, arguments), reference=REFERENCE)


if __name__ == "__main__":
    main()
