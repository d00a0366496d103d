"""Size and build time of the 3-D page (``pinframes.view``) against the number of samples.

The bundled welding cell (its moving frames: robot links, positioner, workpiece, tools;
17 pieces of geometry) on grids of 101 to 20,000 times (the most a page takes) over its
20 s. The reference column is what the animation data alone must take: 4-byte floats for a
time, 3 positions and 4 quaternion values per moving frame and sample (each of the two
tracks of a frame stores the times), base64-encoded. Run from the repository root:
``python benchmarks/bench_view.py``.
"""

from __future__ import annotations

import base64
import time

import numpy as np

from _machine import describe_machine
from pinframes import read_scene
from pinframes.cli.demo import bundled_scene
from pinframes.view import load_geometry, view_html


def main() -> None:
    print(describe_machine())
    tree = read_scene(bundled_scene())
    geometry = load_geometry(tree)
    moving = sum(tree.sample_times(frame, tree.root) is not None for frame in tree.frames)
    static_page = len(view_html(tree, times=[0.0], geometry=geometry).encode())
    print(f"{moving} moving frames")
    print(f"page at one time (viewer bundle, geometry, frames): {static_page / 1e6:.2f} MB")
    print(f"{'samples':>8} {'page MB':>8} {'growth B/sample':>16} {'data only MB':>13} "
          f"{'build s':>8}")
    for samples in (101, 501, 2001, 10001, 20000):
        times = np.linspace(0.0, 20.0, samples)
        start = time.perf_counter()
        page = view_html(tree, times=times, geometry=geometry).encode()
        seconds = time.perf_counter() - start
        data_only = len(base64.b64encode(bytes(4 * samples * moving * (2 + 3 + 4))))
        print(f"{samples:>8} {len(page) / 1e6:>8.2f} "
              f"{(len(page) - static_page) / samples:>16.0f} {data_only / 1e6:>13.2f} "
              f"{seconds:>8.2f}")


if __name__ == "__main__":
    main()
