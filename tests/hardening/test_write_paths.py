"""Where writers write: only regular files are replaced, every legal name works, a path that
is no text path is an argument error, and killed writers leave no temporary files behind."""

from __future__ import annotations

import os
import signal
import stat
import subprocess
import sys
from functools import partial
from pathlib import Path

import pytest

import pinframes
from pinframes import FrameTree, Pose
from pinframes.errors import ArgumentTypeError, WriteError

WRITERS = {
    ".urdf": pinframes.write_urdf,
    ".yaml": pinframes.write_scene,
    "frames.yaml": pinframes.write_frames_yaml,
    ".asdf": partial(pinframes.write_asdf, schema="0.1.0"),
}


def small_tree() -> FrameTree:
    tree = FrameTree("world")
    tree.add("table", "world", Pose([1.0, 0.0, 0.8]))
    return tree


def named(folder: Path, suffix: str, length: int) -> Path:
    """A path in ``folder`` whose file name is ``length`` bytes and ends in ``suffix``."""
    stem = "frames" if suffix == "frames.yaml" else ""
    ending = ".yaml" if suffix == "frames.yaml" else suffix
    return folder / (stem + "n" * (length - len(stem) - len(ending)) + ending)


@pytest.mark.parametrize("suffix", list(WRITERS))
def test_a_fifo_is_refused_and_stays_a_fifo(suffix, tmp_path):
    path = named(tmp_path, suffix, 20)
    os.mkfifo(path)
    with pytest.raises(WriteError, match="not a regular file") as info:
        WRITERS[suffix](small_tree(), path)
    assert info.value.file == str(path)
    assert stat.S_ISFIFO(os.stat(path).st_mode)
    assert sorted(p.name for p in tmp_path.iterdir()) == [path.name]


def test_a_character_device_is_refused_and_kept(tmp_path):
    # a copy of /dev/null's device node in a scratch folder: were the refusal broken, only
    # this node would be replaced, never the system's /dev/null
    device = tmp_path / "null.yaml"
    try:
        os.mknod(device, stat.S_IFCHR | 0o666, os.makedev(1, 3))
    except PermissionError:
        pytest.skip("creating a device node needs root")
    for path in (device, tmp_path / "link.yaml"):
        if path.name == "link.yaml":
            path.symlink_to(device)
        with pytest.raises(WriteError, match="not a regular file"):
            pinframes.write_scene(small_tree(), path)
        assert stat.S_ISCHR(os.stat(device).st_mode)


@pytest.mark.parametrize("suffix", list(WRITERS))
def test_legal_names_up_to_255_bytes_are_written(suffix, tmp_path):
    for length in (242, 250, 255):
        path = named(tmp_path, suffix, length)
        WRITERS[suffix](small_tree(), path)
        assert path.is_file() and path.stat().st_size > 0
    assert len([p for p in tmp_path.iterdir() if p.name.endswith(".tmp")]) == 0


@pytest.mark.parametrize("suffix", list(WRITERS))
def test_a_name_over_255_bytes_is_a_write_error(suffix, tmp_path):
    path = named(tmp_path, suffix, 256)
    with pytest.raises(WriteError, match="too long") as info:
        WRITERS[suffix](small_tree(), path)
    assert info.value.file == str(path)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("suffix", list(WRITERS))
@pytest.mark.parametrize("path", [5, None, b"tree.yaml", b"a\0b", object(), "a\0b.yaml"],
                         ids=["int", "None", "bytes", "bytes-NUL", "object", "str-NUL"])
def test_a_path_that_is_no_text_path_is_an_argument_error(suffix, path):
    with pytest.raises(ArgumentTypeError) as info:
        WRITERS[suffix](small_tree(), path)
    assert info.value.field == "path"


@pytest.mark.parametrize("suffix", list(WRITERS))
def test_str_and_path_like_are_accepted(suffix, tmp_path):
    class Custom:  # any os.PathLike
        def __fspath__(self) -> str:
            return str(named(tmp_path, suffix, 30))

    for path in (str(named(tmp_path, suffix, 20)), named(tmp_path, suffix, 25), Custom()):
        WRITERS[suffix](small_tree(), path)
        assert Path(os.fspath(path)).is_file()


def test_temporary_files_of_killed_writers_are_removed_by_the_next_write(tmp_path):
    # a writer killed (SIGKILL) while its temporary file is open, as a crash would leave it
    child = subprocess.Popen([sys.executable, "-c", (
        "import sys, time\n"
        "from pinframes.formats.atomic import atomic_write\n"
        "with atomic_write(sys.argv[1]) as handle:\n"
        "    handle.write(b'half')\n"
        "    print('open', flush=True)\n"
        "    time.sleep(60)\n"), str(tmp_path / "frames.yaml")],
        stdout=subprocess.PIPE, text=True, env={**os.environ, "PYTHONPATH": os.pathsep.join(
            sys.path)})
    assert child.stdout.readline().strip() == "open"
    left = [p.name for p in tmp_path.iterdir()]
    assert len(left) == 1 and left[0].endswith(".tmp"), left
    child.send_signal(signal.SIGKILL)
    child.wait()
    # a temporary file of a writer still running (this process) must be kept
    ours = tmp_path / f".pinframes-{os.getpid()}-busy.tmp"
    ours.write_bytes(b"in progress")
    pinframes.write_frames_yaml(small_tree(), tmp_path / "frames.yaml")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(["frames.yaml", ours.name])
    assert pinframes.read_frames_yaml(tmp_path / "frames.yaml").frames == ["world", "table"]
