"""The Python examples of README.md run as written, from the repository root."""

import re
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def test_readme_python_examples_run(monkeypatch):
    monkeypatch.chdir(ROOT)
    blocks = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), re.S)
    assert blocks
    namespace: dict = {}
    for block in blocks:
        exec(compile(block, "README.md", "exec"), namespace)
    # The seam start turns with the table about the positioner's z axis: on a circle of 0.2 m.
    seam = namespace["pose_seam_in_world"].translation
    np.testing.assert_allclose(np.hypot(seam[:, 0] - 1.5, seam[:, 1]), 0.2, atol=1e-12)
