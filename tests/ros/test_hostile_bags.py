"""Small hostile bags that ask for gigabytes are refused within ``max_decompressed_bytes``,
and broken ones are errors naming the bag.

Each hostile bag is written by rosbags' own writers, a compressed part padded with zero
bytes its header does not count (``write_bag(..., padding=)``). It is read in a child
process that reports the rise of its peak resident memory during the read, with the size of
any file it writes capped (``RLIMIT_FSIZE``): a reader that inflated a part whole would
rise by the padding, or die writing it.
"""

from __future__ import annotations

import bz2
import json
import os
import resource
import sqlite3
import subprocess
import sys
from pathlib import Path

import lz4.frame
import numpy as np
import pytest

import pinframes
from pinframes.errors import FileFormatError

from ros.bag_writing import (
    STRING,
    Message,
    Transform,
    ros_version_of,
    string,
    tf_messages,
    write_bag,
    zstd,
)

SECOND = 1_000_000_000
START = 1_700_000_000 * SECOND
PADDING = 48 * 2**20  # bytes a compressed part inflates to beyond its content
LIMIT = 1_000_000  # max_decompressed_bytes of the hostile reads
RISE = 16 * 2**20  # bytes the peak memory may rise by while a hostile bag is refused
FILE_CAP = 8 * 2**20  # bytes any file the child writes may reach

CHILD = """
import json, resource, sys
import pinframes
import rosbags.rosbag1, rosbags.rosbag2, rosbags.typesys
from pinframes.errors import PinframesError
limits = pinframes.Limits(max_decompressed_bytes=int(sys.argv[2]))
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
try:
    pinframes.read_rosbag(sys.argv[1], limits=limits)
    outcome = "READ"
except PinframesError as exc:
    outcome = f"{type(exc).__name__} {exc}"
except BaseException as exc:
    outcome = f"NOT-A-PINFRAMES-ERROR {exc!r}"[:500]
rise = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before  # kB on Linux
print(json.dumps({"outcome": outcome, "rise_bytes": rise * 1024}))
"""


def _capped_files() -> None:
    resource.setrlimit(resource.RLIMIT_FSIZE, (FILE_CAP, FILE_CAP))


def read_in_child(bag: Path, limit: int) -> tuple[str, int]:
    """What reading ``bag`` under ``max_decompressed_bytes=limit`` raised in a child, and
    how far its peak resident memory rose during the read (bytes)."""
    tests = Path(__file__).resolve().parents[1]
    environment = {**os.environ, "OPENBLAS_NUM_THREADS": "1",
                   "PYTHONPATH": os.pathsep.join([str(tests), *sys.path])}
    done = subprocess.run([sys.executable, "-c", CHILD, str(bag), str(limit)],
                          env=environment, preexec_fn=_capped_files, capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, f"the child died ({done.returncode}): {done.stderr[-2000:]}"
    report = json.loads(done.stdout.strip().splitlines()[-1])
    return report["outcome"], report["rise_bytes"]


def _tool_bag(tmp_path: Path, storage: str, compression: str | None, padding: int) -> Path:
    version = ros_version_of(storage)
    return write_bag(tmp_path / "hostile", storage, tf_messages(version, [
        Transform("world", "tool", START + k * SECOND, (k, 0, 0)) for k in range(3)]),
        compression, padding)


def _size(bag: Path) -> int:
    return sum(f.stat().st_size for f in ([bag] if bag.is_file() else bag.iterdir()))


@pytest.mark.parametrize(("storage", "compression"), [
    ("ros1", "bz2"), ("ros1", "lz4"), ("mcap", "storage"), ("mcap", "message"),
    ("sqlite3", "message"), ("sqlite3", "file"), ("mcap", "file")])
def test_compressed_parts_are_inflated_within_the_limit(tmp_path, storage, compression):
    bag = _tool_bag(tmp_path, storage, compression, PADDING)
    assert _size(bag) < 300_000  # lz4 compresses at most about 255 to 1
    outcome, rise = read_in_child(bag, LIMIT)
    assert outcome.startswith("FileFormatError "), outcome
    assert "max_decompressed_bytes=1,000,000" in outcome and str(bag) in outcome, outcome
    assert rise < RISE, f"the peak memory rose by {rise:,} bytes"


@pytest.mark.parametrize(("storage", "compression"), [
    ("ros1", "bz2"), ("ros1", "lz4"), ("mcap", "storage"), ("sqlite3", "message"),
    ("sqlite3", "file")])
def test_a_bag_inflating_within_the_limit_is_read(tmp_path, storage, compression):
    bag = _tool_bag(tmp_path, storage, compression, 0)
    tree = pinframes.read_rosbag(bag, limits=pinframes.Limits(max_decompressed_bytes=LIMIT))
    assert tree.local_pose("tool").translation[:, 0].tolist() == [0, 1, 2]


def test_the_budget_counts_every_byte_inflated(tmp_path):
    from pinframes.formats.limits import using_limits
    from pinframes.formats.rosbag._inflation import InflationBudget

    def budget(limit: int) -> InflationBudget:
        with using_limits(pinframes.Limits(max_decompressed_bytes=limit)):
            return InflationBudget(tmp_path)

    # several bz2 streams and zstd frames in a row inflate as the libraries inflate them;
    # lz4 data is one frame, as lz4.frame.decompress reads it
    for codec, compress, decompress in (("bz2", bz2.compress, bz2.decompress),
                                        ("zstd", zstd.compress, zstd.decompress),
                                        ("lz4", lz4.frame.compress, lz4.frame.decompress)):
        data = compress(b"a" * 5000) + compress(np.arange(900).tobytes())
        size = len(decompress(data))
        assert budget(size).inflate(data, codec) == decompress(data)
        short = budget(size - 1)
        with using_limits(pinframes.Limits(max_decompressed_bytes=size - 1)), pytest.raises(
                FileFormatError, match=f"max_decompressed_bytes={size - 1:,}") as caught:
            short.inflate(data, codec)
        assert caught.value.file == str(tmp_path) and short.produced == size
        with pytest.raises(EOFError):  # a stream cut short
            budget(10**6).inflate(data[:10], codec)


def test_a_generated_column_is_refused_before_a_row_is_read(tmp_path):
    bag = _tool_bag(tmp_path, "sqlite3", None, 0)
    database = next(bag.glob("*.db3"))
    with sqlite3.connect(database) as connection:
        connection.executescript(f"""
            ALTER TABLE messages RENAME TO stored;
            CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL,
                timestamp INTEGER NOT NULL,
                data BLOB GENERATED ALWAYS AS (zeroblob({PADDING})) VIRTUAL);
            INSERT INTO messages(id, topic_id, timestamp)
                SELECT id, topic_id, timestamp FROM stored;
            DROP TABLE stored;""")
    assert _size(bag) < 64_000
    for path in (bag, database):  # the bag folder and its .db3 file on its own
        outcome, rise = read_in_child(path, 1000)
        assert outcome.startswith("FileFormatError "), outcome
        assert str(path) in outcome and "messages.data" in outcome, outcome
        assert rise < RISE, f"the peak memory rose by {rise:,} bytes"


def test_a_corrupt_time_field_of_a_ros1_message_is_an_error_naming_the_bag(tmp_path):
    bag = _tool_bag(tmp_path, "ros1", None, 0)
    data = bytearray(bag.read_bytes())
    # a message record's header field "time=" (4 bytes of length 13, the name, 8 bytes)
    field = data.index(b"\x0d\x00\x00\x00time=")
    data[field + 9:field + 17] = b"\xff" * 8
    bag.write_bytes(data)
    with pytest.raises(FileFormatError, match="disagrees with the bag's index") as caught:
        pinframes.read_rosbag(bag)
    assert caught.value.file == str(bag)


def test_a_description_is_never_opened_as_a_file(tmp_path):
    (tmp_path / "local.urdf").write_text('<robot name="local"><link name="secret"/></robot>')
    for text in (str(tmp_path / "local.urdf"), "", "  ", "just words", "<notrobot/>"):
        bag = write_bag(tmp_path / "described", "mcap", [
            Message("/robot_description", STRING, START, string(2, text))])
        with pytest.raises(FileFormatError, match="not a URDF") as caught:
            pinframes.read_rosbag(bag)
        assert caught.value.file == str(bag) and caught.value.field == "/robot_description"
        for part in bag.iterdir():
            part.unlink()
        bag.rmdir()
