"""A generated campaign of the bundled welding cell, for the batch tests."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

pytest.importorskip("distributed")
pytest.importorskip("pyarrow")

CELL = Path(__file__).resolve().parents[2] / "models" / "welding_cell"


@pytest.fixture(scope="session")
def make_campaign():
    """``models/welding_cell/make_campaign.py``'s ``make_campaign(out, runs, samples, seed)``."""
    spec = importlib.util.spec_from_file_location("make_campaign", CELL / "make_campaign.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.make_campaign
