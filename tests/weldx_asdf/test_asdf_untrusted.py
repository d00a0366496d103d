"""ASDF files from elsewhere: arrays stored outside the file are refused without opening
anything, and what a file's arrays decode to is bounded in total."""

from __future__ import annotations

import io
import os
import socket
import threading
from pathlib import Path

import asdf
import numpy as np
import pytest

from pinframes import Limits, read_asdf
from pinframes.errors import FileFormatError
from weldx_asdf.asdf_texts import asdf_text, legacy_hierarchy, time_grid, write_asdf_text

SECONDS_ALLOWED = 20.0


class Listener:
    """A TCP server on 127.0.0.1 that counts the connections it is offered."""

    def __init__(self) -> None:
        self.server = socket.create_server(("127.0.0.1", 0))
        self.server.settimeout(0.2)
        self.port = self.server.getsockname()[1]
        self.connections = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._accept, daemon=True)
        self._thread.start()

    def _accept(self) -> None:
        while not self._stop.is_set():
            try:
                connection, _ = self.server.accept()
            except TimeoutError:
                continue
            self.connections += 1
            connection.close()

    def close(self) -> None:
        self._stop.set()
        self._thread.join()
        self.server.close()


@pytest.fixture
def listener():
    server = Listener()
    yield server
    server.close()


def external_coordinates(source: str) -> str:
    """A legacy hierarchy whose frame ``torch`` has its coordinates in ``source``."""
    coordinates = ("!legacy!core/variable-1.0.0 {name: coordinates, dimensions: [c], dtype: "
                   f"<f8, data: !core/ndarray-1.0.0 {{source: '{source}', datatype: float64, "
                   "byteorder: little, shape: [3]}}")
    transformation = ("!legacy!core/transformations/local_coordinate_system-1.0.0 "
                      f"{{coordinates: {coordinates}}}")
    return legacy_hierarchy("cell", "world", [("torch", "world", transformation)])


def read_in_time(path: Path) -> BaseException | None:
    """What ``read_asdf(path)`` raised (None if it returned), failing the test if it does
    not end within SECONDS_ALLOWED (it would be waiting on a FIFO it opened)."""
    outcome: list[BaseException | None] = []

    def read() -> None:
        try:
            read_asdf(path)
            outcome.append(None)
        except BaseException as exc:  # handed to the test
            outcome.append(exc)

    thread = threading.Thread(target=read, daemon=True)
    thread.start()
    thread.join(SECONDS_ALLOWED)
    assert outcome, "the reader opened the FIFO and waited on it"
    return outcome[0]


@pytest.mark.parametrize("scheme", ["http", "ftp"])
def test_an_array_at_an_address_is_refused_without_connecting(tmp_path, listener, scheme):
    source = f"{scheme}://127.0.0.1:{listener.port}/arrays.asdf"
    path = write_asdf_text(tmp_path / "cell.asdf", external_coordinates(source))
    with pytest.raises(FileFormatError) as error:
        read_asdf(path)
    assert listener.connections == 0
    assert error.value.file == str(path) and error.value.frame == "torch"
    assert error.value.field == "coordinate_systems[0].transformation.coordinates.data"
    assert source in str(error.value) and "outside the file" in str(error.value)


@pytest.mark.parametrize("absolute", [True, False], ids=["absolute path", "relative path"])
def test_an_array_in_another_file_is_refused_without_opening_it(tmp_path, absolute):
    """The other file is a FIFO that nobody writes to: opening it would wait for ever."""
    os.mkfifo(tmp_path / "arrays.asdf")
    source = str(tmp_path / "arrays.asdf") if absolute else "arrays.asdf"
    path = write_asdf_text(tmp_path / "cell.asdf", external_coordinates(source))
    try:
        error = read_in_time(path)
    finally:
        release_reader(tmp_path / "arrays.asdf")
    assert isinstance(error, FileFormatError), error
    assert error.frame == "torch" and source in str(error)


def release_reader(fifo: Path) -> None:
    """End the wait of a process that opened ``fifo`` for reading (a writer that opens and
    closes it gives the reader end-of-file); nothing to do when none did."""
    try:
        os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
    except OSError:  # ENXIO: no process has it open for reading
        pass


def test_an_external_array_that_pinframes_would_not_decode_is_refused_too(tmp_path, listener):
    """asdf decodes every array of the hierarchy when it validates it, read or not."""
    body = legacy_hierarchy("cell", "world", [], extra=(
        f"notes: !core/ndarray-1.0.0 {{source: 'http://127.0.0.1:{listener.port}/x.asdf', "
        "datatype: float64, byteorder: little, shape: [3]}"))
    path = write_asdf_text(tmp_path / "cell.asdf", body)
    with pytest.raises(FileFormatError, match="outside the file") as error:
        read_asdf(path)
    assert error.value.field == "notes" and listener.connections == 0


ROWS, FRAMES = 10_000, 60
ARRAY_BYTES = ROWS * 3 * 8  # 240 kB each, all read from one compressed block


def shared_block_file(folder: Path) -> Path:
    """FRAMES frames whose coordinates, (ROWS, 3) zeros, all come from one zlib block of a
    few hundred bytes (the block written by asdf itself)."""
    buffer = io.BytesIO()
    asdf.AsdfFile({"a": np.zeros((ROWS, 3))}).write_to(buffer, all_array_compression="zlib")
    raw = buffer.getvalue()
    block = raw[raw.index(b"\xd3BLK"):].split(b"#ASDF BLOCK INDEX")[0]
    coordinates = ("!legacy!core/variable-1.0.0 {name: coordinates, dimensions: [time, c], "
                   "dtype: <f8, data: !core/ndarray-1.0.0 {source: 0, datatype: float64, "
                   f"byteorder: little, shape: [{ROWS}, 3]}}}}")
    grid = time_grid("P0DT0H0M0S", f"P0DT0H0M{ROWS - 1}S", "1S", legacy=True)
    transformation = ("!legacy!core/transformations/local_coordinate_system-1.0.0 "
                      f"{{time: {grid}, coordinates: {coordinates}}}")
    body = legacy_hierarchy("cell", "world", [(f"f{index:02d}", "world", transformation)
                                              for index in range(FRAMES)])
    path = folder / "shared.asdf"
    path.write_bytes(asdf_text(body).encode() + block)
    return path


def test_arrays_sharing_one_compressed_block_are_bounded_in_total(tmp_path):
    path = shared_block_file(tmp_path)
    assert path.stat().st_size < 40_000  # decodes to 60 x 240 kB
    limit = 5_000_000  # each array is far below it, all of them far above
    with pytest.raises(FileFormatError, match="max_decompressed_bytes=5,000,000") as error:
        read_asdf(path, limits=Limits(max_decompressed_bytes=limit))
    over = limit // ARRAY_BYTES  # the block (ARRAY_BYTES) and this many arrays fit
    assert error.value.frame == f"f{over - 1:02d}"
    assert error.value.file == str(path)
    tree = read_asdf(path)  # within the default limit: the file itself is fine
    assert len(tree.frames) == FRAMES + 1
    np.testing.assert_array_equal(tree.pose("f59", "world", times=[0.0, 5.0]).translation,
                                  np.zeros((2, 3)))
