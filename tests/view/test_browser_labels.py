"""Frame names on the demo's page do not print over each other: the torch tip, its target
and the seam point share one origin, and their names stack. Headless Chromium opens the page
from disk (skipped without ``/usr/bin/chromium``, except in CI)."""

from __future__ import annotations

import itertools
import os
import time

import pytest

from pinframes.cli import main
from pinframes.cli.demo import VIEW_FILE

from headless_chromium import Chromium, available

if not available() and os.environ.get("CI"):
    pytest.fail("CI needs Debian's chromium for the browser tests", pytrace=False)
# headless Chromium takes seconds a test: in the slow set (CI runs it)
pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not available(), reason="chromium is not installed")]

VISIBLE_LABELS = """[...document.querySelectorAll('.pinframes-label')]
  .filter((e) => e.style.display === 'block')
  .map((e) => { const r = e.getBoundingClientRect();
                return [e.textContent, r.left, r.top, r.right, r.bottom]; })"""


def test_frame_names_do_not_overlap(tmp_path):
    assert main(["demo", "--out", str(tmp_path)]) == 0
    with Chromium(1000, 700) as browser:
        browser.open(tmp_path / VIEW_FILE)
        deadline = time.monotonic() + 60
        while not browser.evaluate("Boolean(window.pinframes && window.pinframes.ready)"):
            assert time.monotonic() < deadline, "the page never got ready"
            time.sleep(0.1)
        for seconds in (0.0, 10.0):
            browser.evaluate(f"pinframes.seek({seconds})")
            browser.screenshot()  # a frame drawn: the labels placed
            labels = browser.evaluate(VISIBLE_LABELS)
            names = {label[0] for label in labels}
            assert {"torch_tcp", "torch_target", "seam_point"} <= names
            for (a, *box_a), (b, *box_b) in itertools.combinations(labels, 2):
                overlap = (min(box_a[2], box_b[2]) - max(box_a[0], box_b[0]),
                           min(box_a[3], box_b[3]) - max(box_a[1], box_b[1]))
                assert min(overlap) <= 0.5, f"{a!r} and {b!r} overlap at {seconds} s"
