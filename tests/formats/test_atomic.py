import os
import stat
import sys

import pytest

from pinframes.errors import WriteError
from pinframes.formats.atomic import atomic_write


def test_new_files_get_the_umask_mode_and_replaced_files_keep_theirs(tmp_path):
    old_umask = os.umask(0o022)
    try:
        path = tmp_path / "new.txt"
        with atomic_write(path, "w") as handle:
            handle.write("x")
        assert stat.S_IMODE(path.stat().st_mode) == 0o644
        path.chmod(0o600)
        with atomic_write(path, "w") as handle:
            handle.write("y")
        assert stat.S_IMODE(path.stat().st_mode) == 0o600 and path.read_text() == "y"
    finally:
        os.umask(old_umask)


def test_a_failed_write_keeps_the_old_file_and_leaves_no_temporary_file(tmp_path):
    path = tmp_path / "keep.txt"
    path.write_text("old")
    with pytest.raises(RuntimeError), atomic_write(path, "w") as handle:
        handle.write("half")
        raise RuntimeError("boom")
    assert path.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["keep.txt"]


def test_no_folders_are_created(tmp_path):
    with pytest.raises(WriteError) as info, atomic_write(tmp_path / "a" / "b.txt"):
        pass
    assert info.value.file.endswith("b.txt") and isinstance(info.value, OSError)
    assert not (tmp_path / "a").exists()


def process_umask() -> int:
    """The umask as the kernel reports it, read without changing it (Linux 4.7+)."""
    for line in open("/proc/self/status", encoding="ascii"):
        if line.startswith("Umask:"):
            return int(line.split()[1], 8)
    pytest.skip("this kernel does not report the umask in /proc/self/status")


def test_writing_never_changes_the_process_umask(tmp_path):
    """Another thread creating a file while a write runs must get the umask it set: the
    umask is observed at every call the writer makes, for a new file and a replaced one."""
    old_umask = os.umask(0o027)
    seen: set[int] = set()

    def watch(frame, event, arg):
        if event in ("c_call", "c_return"):
            seen.add(process_umask())

    try:
        for name in ("new.txt", "new.txt"):  # created, then replaced
            sys.setprofile(watch)
            try:
                with atomic_write(tmp_path / name, "w") as handle:
                    handle.write("x")
            finally:
                sys.setprofile(None)
        assert seen == {0o027}
        assert stat.S_IMODE((tmp_path / "new.txt").stat().st_mode) == 0o640
    finally:
        os.umask(old_umask)
