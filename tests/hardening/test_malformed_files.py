"""Every malformed file of the corpus raises its pinframes error, naming file, frame, field."""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest

from hardening.file_cases import FILE_CASES, FOLDER, MISSING, Case
from hardening.readers import READERS
from pinframes.errors import PinframesError

BUILT_INS = (ValueError, KeyError, TypeError, OSError)


def write_input(folder: Path, name: str, content: str | bytes) -> Path:
    path = folder / name
    if content == FOLDER:
        path.mkdir()
    elif isinstance(content, bytes):
        path.write_bytes(content)
    elif content != MISSING:
        path.write_text(content, encoding="utf-8")
    return path


@pytest.mark.parametrize("case", FILE_CASES, ids=lambda case: f"{case.reader}-{case.id}")
def test_malformed_file_raises_a_located_pinframes_error(case: Case, tmp_path):
    for name, content in case.extra.items():
        write_input(tmp_path, name, content)
    reader = READERS[case.reader]
    path = write_input(tmp_path, reader.file_name, case.content)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # unknown fields warn; the error is what counts here
        with pytest.raises(PinframesError) as info:
            reader.read(path)
    error = info.value
    assert type(error) is case.error, f"{type(error).__name__}: {error}"
    assert isinstance(error, BUILT_INS)
    expected_file = path if case.file == "" else tmp_path / case.file
    assert error.file is not None and Path(error.file) == expected_file, str(error)
    # the frame, or the joint for errors about a robot joint (a URDF joint, a trajectory column)
    subject = error.frame if error.frame is not None else error.joint
    assert (subject, error.field) == (case.frame, case.field), str(error)
    assert case.message in error.message, str(error)
    assert str(error).startswith(error.file)


def test_the_corpus_covers_every_reader_with_unique_names():
    assert {case.reader for case in FILE_CASES} == set(READERS)
    ids = [(case.reader, case.id) for case in FILE_CASES]
    assert len(ids) == len(set(ids))
