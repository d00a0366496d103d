"""The closest pair marked on the 3-D page, checked in Debian's headless Chromium.

A ball of radius 0.1 m flies at 0.5 m above the floor, along x from 0 to 2 m in 4 s, over a
0.4 m cube centred at x = 1 m (its top at z = 0.2 m). Worked out by hand: above the cube the
closest points are straight below the ball, 0.2 m apart; before it, the ball's nearest point
faces the cube's top edge at (0.8, 0, 0.2). The page is drawn in the cube's frame (x - 1 m):
its dots and segment must sit there (float32), and the text beside the time must name the
distance and the pair.
"""

from __future__ import annotations

import time

import numpy as np
import pytest

from pinframes import FrameTree, Pose
from pinframes.view import write_view

from headless_chromium import Chromium, available

# headless Chromium takes seconds a test: in the slow set (CI runs it)
pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not available(), reason="chromium is not installed")]

MARK = """(() => {
  const root = pinframes.viewer.scene_tree.find(["pinframes"]).object;
  const at = (name, x) => {
    const node = pinframes.viewer.scene_tree.find(["pinframes", "clearance", name]).object;
    node.updateMatrixWorld(true);
    const v = new MeshCat.THREE.Vector3(x, 0, 0).applyMatrix4(node.matrixWorld);
    return root.worldToLocal(v).toArray();
  };
  return [at("a", 0), at("b", 0), at("segment", 0), at("segment", 1),
          document.getElementById("pinframes-clearance").textContent];
})()"""


def link(name: str, geometry: str) -> str:
    return (f'<robot name="{name}"><link name="{name}"><collision><geometry>{geometry}'
            f'</geometry></collision></link></robot>')


def expected_points(x: float) -> tuple[np.ndarray, np.ndarray]:
    """Closest points on the ball (centre (x, 0, 0.5), r 0.1) and on the cube."""
    centre = np.array([x, 0.0, 0.5])
    on_cube = np.array([np.clip(x, 0.8, 1.2), 0.0, 0.2])
    towards = (on_cube - centre) / np.linalg.norm(on_cube - centre)
    return centre + 0.1 * towards, on_cube


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    tree = FrameTree()
    tree.add("flight", "world", Pose(translation=[[0, 0, 0.5], [2, 0, 0.5]], times=[0, 4]))
    tree.attach_urdf(link("ball", '<sphere radius="0.1"/>'), "flight")
    tree.add("floor", "world", Pose([1.0, 0.0, 0.0]))
    tree.attach_urdf(link("cube", '<box size="0.4 0.4 0.4"/>'), "floor")
    path = tmp_path_factory.mktemp("clearance") / "page.html"
    write_view(tree, path, times=np.linspace(0.0, 4.0, 9), relative_to="floor",
               clearance=("ball", "cube"))
    with Chromium(800, 600) as chromium:
        chromium.open(path)
        deadline = time.monotonic() + 60
        while not chromium.evaluate("Boolean(window.pinframes && window.pinframes.ready)"):
            assert time.monotonic() < deadline, "the page never got ready"
            time.sleep(0.1)
        yield chromium


@pytest.mark.parametrize("seconds", [0.0, 1.5, 2.0, 3.0])
def test_the_marks_sit_on_the_closest_points_and_the_text_names_the_pair(page, seconds):
    page.evaluate(f"pinframes.seek({seconds})")
    a, b, start, end, text = page.evaluate(MARK)
    expected_a, expected_b = expected_points(0.5 * seconds)
    in_floor = np.array([1.0, 0.0, 0.0])  # the drawing frame's origin in the world
    for actual, expected in ((a, expected_a), (b, expected_b), (start, expected_a),
                             (end, expected_b)):
        np.testing.assert_allclose(actual, expected - in_floor, atol=1e-5)
    distance = np.linalg.norm(expected_b - expected_a)
    assert text == f"closest: {1000 * distance:.1f} mm, ball \u2013 cube"
    assert page.errors() == []
