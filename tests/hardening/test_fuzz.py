"""A bounded fuzz run of the readers, and the inputs that once made one fail (see fuzz.py)."""

from __future__ import annotations

import pytest

from conftest import SHARED_DATA
from hardening import fuzz

# thousands of mutated files: in the slow set (CI runs it)
pytestmark = pytest.mark.slow

FUZZ_SEED = 20261123
INPUTS_PER_READER = 120
FEWER_INPUTS = {"read_asdf": 80}
"""Readers slower per input (asdf opens a file in about 40 ms) get fewer in the suite."""
READERS = fuzz.readers(SHARED_DATA)


@pytest.mark.parametrize("name", sorted(READERS))
def test_mutated_samples_give_pinframes_errors_only(name, tmp_path):
    count = FEWER_INPUTS.get(name, INPUTS_PER_READER)
    tried, failures = fuzz.fuzz({name: READERS[name]}, tmp_path, FUZZ_SEED, count=count)
    assert tried[name] == count
    assert not failures, "\n".join(
        f"{f.sample} input {f.index}: {f.error}" for f in failures[:10])


@pytest.mark.parametrize("record", fuzz.regression_inputs(), ids=lambda path: path.stem)
def test_inputs_that_once_failed_give_pinframes_errors_only(record, tmp_path):
    try:
        error = fuzz.replay(READERS, record, tmp_path)
    except fuzz.SampleMissing as missing:
        pytest.skip(f"remade from the shared sample {missing}, absent here")
    assert error is None


def test_the_regression_folder_holds_inputs():
    assert fuzz.regression_inputs(), f"no kept inputs in {fuzz.REGRESSIONS}"
