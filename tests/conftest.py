"""Shared fixtures. Geometry helpers that do not use pinframes' code are in geometry.py."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

SHARED_DATA = Path(os.environ.get("PINFRAMES_TEST_DATA")
                   or Path(__file__).resolve().parents[1].parent / "shared" / "data")
"""Real files other projects wrote (``weldx-files/``, ``duckietown-maps/``): the folder
``PINFRAMES_TEST_DATA`` names, else the one CI lays beside the checkout. Tests that read them
skip without them."""


@pytest.fixture
def rng() -> np.random.Generator:
    return np.random.default_rng(20261122)
