"""The demo's page in a real browser: Debian's headless Chromium opens it from disk.

It must run without console errors and without network requests, show the robot in
different places at two times (pixel statistics around the flange, no stored image), and
switch frame names off and on. Needs ``/usr/bin/chromium`` (``.ci/run`` installs it); without
it the tests are skipped, except in CI, where they fail.
"""

from __future__ import annotations

import io
import os
import time
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from pinframes.cli import main
from pinframes.cli.demo import VIEW_FILE

from headless_chromium import Chromium, available

if not available() and os.environ.get("CI"):
    pytest.fail("CI needs Debian's chromium for the browser tests", pytrace=False)
# headless Chromium takes seconds a test: in the slow set (CI runs it)
pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not available(), reason="chromium is not installed")]

WIDTH, HEIGHT = 1000, 700
FLANGE_ON_SCREEN = """(() => {
  const v = new MeshCat.THREE.Vector3();
  pinframes.viewer.scene_tree.find(["pinframes", "frames", "frame:robot%2Fflange"])
    .object.getWorldPosition(v);
  v.project(pinframes.viewer.camera);
  return [(v.x + 1) / 2 * innerWidth, (1 - v.y) / 2 * innerHeight];
})()"""


@pytest.fixture(scope="module")
def demo_page(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("demo")
    assert main(["demo", "--out", str(out)]) == 0
    return out / VIEW_FILE


@pytest.fixture(scope="module")
def browser(demo_page):
    with Chromium(WIDTH, HEIGHT) as chromium:
        chromium.open(demo_page)
        deadline = time.monotonic() + 60
        while not chromium.evaluate("Boolean(window.pinframes && window.pinframes.ready)"):
            assert time.monotonic() < deadline, "the page never got ready"
            time.sleep(0.1)
        yield chromium


def pixels(png: bytes) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=np.int16)


def test_page_loads_from_disk_without_errors_or_network(browser, demo_page):
    assert browser.evaluate("pinframes.duration") == pytest.approx(20.0)
    urls = browser.requested_urls()
    assert demo_page.resolve().as_uri() in urls
    assert all(url.startswith(("file:", "data:")) for url in urls), urls
    assert browser.errors() == []


def test_the_robot_moves_between_two_times(browser):
    browser.evaluate("pinframes.seek(0)")
    start, flange_start = pixels(browser.screenshot()), browser.evaluate(FLANGE_ON_SCREEN)
    assert "t = 0.000 s" in browser.evaluate("document.getElementById('pinframes-time')"
                                             ".textContent")
    browser.evaluate("pinframes.seek(20)")
    end, flange_end = pixels(browser.screenshot()), browser.evaluate(FLANGE_ON_SCREEN)
    assert "t = 20.000 s" in browser.evaluate("document.getElementById('pinframes-time')"
                                              ".textContent")
    for image in (start, end):  # not blank: many colours, real contrast
        assert image.shape == (HEIGHT, WIDTH, 3)
        assert image.std() > 20
        assert len(np.unique(image.reshape(-1, 3), axis=0)) > 200
    moved = np.hypot(*np.subtract(flange_end, flange_start))
    assert moved > 10, "the flange should move on the screen during the demo"
    difference = np.abs(end - start).sum(axis=2)
    for x, y in (flange_start, flange_end):
        around = difference[int(y) - 25:int(y) + 25, int(x) - 25:int(x) + 25]
        assert (around > 30).mean() > 0.05  # the robot left or entered this patch
    assert np.all(difference[:80, :200] == 0)  # the sky in the top left corner stays
    assert browser.errors() == []


def test_frame_names_switch_off_and_on(browser):
    browser.evaluate("pinframes.seek(0)")
    browser.screenshot()
    shown = browser.evaluate("pinframes.labelCount()")
    assert shown >= 5  # world, robot_base, positioner_base, workpiece, weld_seam, ...
    browser.evaluate("document.getElementById('pinframes-frame-names').click()")
    browser.screenshot()
    assert browser.evaluate("pinframes.labelCount()") == 0
    browser.evaluate("document.getElementById('pinframes-frame-names').click()")
    browser.screenshot()
    assert browser.evaluate("pinframes.labelCount()") == shown


def test_play_advances_the_time(browser):
    browser.evaluate("pinframes.seek(0)")
    browser.evaluate("document.getElementById('pinframes-play').click()")
    time.sleep(0.6)
    browser.screenshot()
    playing = float(browser.evaluate("document.getElementById('pinframes-slider').value"))
    browser.evaluate("document.getElementById('pinframes-play').click()")  # pause
    assert playing > 0.1
    assert browser.errors() == []
