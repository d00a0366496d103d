"""Any frame name a tree accepts gives a working page, in Debian's headless Chromium: names
that are JavaScript property names or HTML, ``a/b`` beside ``a\u2215b``, and a frame too far
away to draw among them (left out with a warning, the rest drawn)."""

from __future__ import annotations

import io
import os
import time

import numpy as np
import pytest
from PIL import Image

from pinframes import FrameTree, Pose
from pinframes.view import GeometryWarning, write_view

from headless_chromium import Chromium, available

if not available() and os.environ.get("CI"):
    pytest.fail("CI needs Debian's chromium for the browser tests", pytrace=False)
# headless Chromium takes seconds a test: in the slow set (CI runs it)
pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not available(), reason="chromium is not installed")]

NAMES = {"constructor": (0.2, 0.0, 0.0), "__proto__": (0.0, 0.2, 0.0),
         "toString": (0.0, 0.0, 0.2), "hasOwnProperty": (0.2, 0.2, 0.0),
         "<!--<script>": (0.2, 0.0, 0.2), "</script><b>": (0.0, 0.2, 0.2),
         "a/b": (0.4, 0.0, 0.0), "a\u2215b": (0.0, 0.4, 0.0), "a%2Fb": (0.0, 0.0, 0.4)}
WORLD_POSITION = """(() => {
  const node = pinframes.viewer.scene_tree.find(["pinframes", "frames", %s]);
  const v = new MeshCat.THREE.Vector3();
  node.object.getWorldPosition(v);
  return [v.x, -v.z, v.y];  // meshcat's scene is y up: back to z up
})()"""


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    tree = FrameTree("world")
    for name, position in NAMES.items():
        tree.add(name, "world", Pose(list(position)))
    tree.add("far", "world", Pose([1e200, 0.0, 0.0]))
    path = tmp_path_factory.mktemp("names") / "names.html"
    with pytest.warns(GeometryWarning, match="'far' is not drawn"):
        write_view(tree, path)
    return path


@pytest.fixture(scope="module")
def browser(page):
    with Chromium(800, 600) as chromium:
        chromium.open(page)
        deadline = time.monotonic() + 60
        while not chromium.evaluate("Boolean(window.pinframes && window.pinframes.ready)"):
            assert time.monotonic() < deadline, f"the page never got ready: {chromium.errors()}"
            time.sleep(0.1)
        yield chromium


def test_every_name_gets_a_label_and_the_page_draws(browser):
    browser.evaluate("pinframes.seek(0)")
    image = np.asarray(Image.open(io.BytesIO(browser.screenshot())).convert("RGB"), np.int16)
    assert image.std() > 5 and len(np.unique(image.reshape(-1, 3), axis=0)) > 20
    assert browser.evaluate("pinframes.labelCount()") == len(NAMES) + 1  # and "world"
    texts = browser.evaluate("Array.from(document.querySelectorAll('.pinframes-label'))"
                             ".map((e) => e.textContent)")
    assert sorted(texts) == sorted(["world", *NAMES])
    assert browser.errors() == []


@pytest.mark.parametrize(("name", "segment"), [
    ("a/b", "frame:a%2Fb"), ("a\u2215b", "frame:a\u2215b"), ("a%2Fb", "frame:a%252Fb"),
    ("constructor", "frame:constructor"), ("<!--<script>", "frame:<!--<script>")])
def test_each_name_has_a_node_of_its_own_where_its_frame_is(browser, name, segment):
    quoted = '"' + segment.replace('"', '\\"') + '"'
    position = browser.evaluate(WORLD_POSITION % quoted)
    np.testing.assert_allclose(position, NAMES[name], atol=1e-6)
